//! Reads and normalises one file (`Complex::from_path`, any format) and prints its size, the
//! process's peak resident memory and their ratio: the measure behind the class 5 bound of
//! docs/bad-input.md ("reading peaks under 5× the file"). Linux (reads /proc/self/status).
//! `scripts/read-peak.sh` generates short-line files in every text format and runs it on each.
//!
//! Usage: `cargo run --release --example read_peak -- FILE...`

#[path = "support/peak.rs"]
mod peak;
use peak::peak_bytes;

fn main() {
    let files: Vec<String> = std::env::args().skip(1).collect();
    if files.len() != 1 {
        eprintln!("usage: read_peak FILE (one file per process: the peak is per process)");
        std::process::exit(1);
    }
    let path = std::path::Path::new(&files[0]);
    let size = std::fs::metadata(path).map(|m| m.len()).unwrap_or(0);
    let base = peak_bytes();
    let budget = topoplex::Budget {
        max_simplices: Some(u64::MAX),
    };
    let c = match topoplex::Complex::from_path_with(path, budget) {
        Ok(c) => c,
        Err(e) => {
            eprintln!("{e}");
            std::process::exit(1);
        }
    };
    let peak = peak_bytes();
    println!(
        "{}\t{size}\t{}\t{peak}\t{:.2}\t{}",
        path.display(),
        c.input_count(),
        peak.saturating_sub(base) as f64 / size.max(1) as f64,
        c.stats().absorbed_duplicates
    );
}
