//! Reads one file `REPS` times in this process (`Complex::from_path`, any format) and prints, tab
//! separated: the file, its size, the median wall time of one read in seconds, the bytes its
//! attributes hold (`Attributes::bytes`) and the process's peak resident memory above what it
//! was before the first read (Linux: /proc/self/status VmHWM). The measure behind
//! `scripts/bench_attributes.sh` (issue 26: reading with data against the same mesh without).
//!
//! Usage: `cargo run --release --example read_attributes -- FILE [REPS]`

#[path = "support/peak.rs"]
mod peak;
use peak::peak_bytes;

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let Some(file) = args.first() else {
        eprintln!("usage: read_attributes FILE [REPS]");
        std::process::exit(1);
    };
    let reps: usize = args
        .get(1)
        .and_then(|r| r.parse().ok())
        .unwrap_or(20)
        .max(1);
    let path = std::path::Path::new(file);
    let size = std::fs::metadata(path).map(|m| m.len()).unwrap_or(0);
    let base = peak_bytes();
    let mut times = Vec::with_capacity(reps);
    let mut bytes = 0;
    for _ in 0..reps {
        let start = std::time::Instant::now();
        let c = match topoplex::Complex::from_path(path) {
            Ok(c) => c,
            Err(e) => {
                eprintln!("{e}");
                std::process::exit(1);
            }
        };
        times.push(start.elapsed().as_secs_f64());
        bytes = c.attributes().bytes();
        drop(c);
    }
    times.sort_by(f64::total_cmp);
    let peak = peak_bytes().saturating_sub(base);
    println!(
        "{}\t{size}\t{:.6}\t{bytes}\t{peak}",
        path.display(),
        times[reps / 2]
    );
}
