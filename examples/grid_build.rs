//! The Rust side of scripts/bench_py.py's build benchmark: makes the triangles of a K×K grid of
//! squares (2K² triangles, the same rows in the same order as the script's numpy array) in
//! memory, then times `Complex::from_uniform` (`from_arrays` without offsets: one array of
//! rows of 3, as a numpy (n, 3) array lies) and, with a KIND, the structure's build on it, and
//! reports the peak resident memory of those calls: VmHWM read after resetting it
//! (`/proc/self/clear_refs`) once the input is made, so the input's making is not counted
//! but the input itself is. Linux only for the memory (0 elsewhere). A measuring tool, not a
//! test.
//!
//! Usage: `cargo run --release --example grid_build -- K [KIND]`
//! Prints one line of names and values: `triangles T rss_before_bytes B complex_s S [KIND_s S2]
//! peak_bytes P`.

use std::time::Instant;

fn status_bytes(key: &str) -> u64 {
    let s = std::fs::read_to_string("/proc/self/status").unwrap_or_default();
    s.lines()
        .find(|l| l.starts_with(key))
        .and_then(|l| l.split_whitespace().nth(1))
        .and_then(|n| n.parse::<u64>().ok())
        .map_or(0, |kib| kib * 1024)
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let Some(k) = args.first().and_then(|k| k.parse::<u32>().ok()) else {
        eprintln!("usage: grid_build K [KIND]");
        std::process::exit(1);
    };
    let kind = args.get(1).map(|n| {
        topoplex::StructureKind::from_name(n).unwrap_or_else(|| {
            eprintln!("unknown structure {n}");
            std::process::exit(1);
        })
    });
    // Row-major squares; square (i, j) with a = j (K+1) + i gives [a, a+1, a+K+2] and
    // [a, a+K+2, a+K+1].
    let w = k + 1;
    let mut ids = Vec::with_capacity(6 * (k as usize) * (k as usize));
    for j in 0..k {
        for i in 0..k {
            let a = j * w + i;
            ids.extend_from_slice(&[a, a + 1, a + w + 1, a, a + w + 1, a + w]);
        }
    }
    // The peak from here on: the input is resident, its making forgotten.
    let _ = std::fs::write("/proc/self/clear_refs", "5");
    let before = status_bytes("VmRSS:");
    let t = Instant::now();
    let c = topoplex::Complex::from_uniform(w * w, 3, &ids, None).expect("complex");
    let complex_s = t.elapsed().as_secs_f64();
    let mut line = format!(
        "triangles {} rss_before_bytes {before} complex_s {complex_s:.4}",
        ids.len() / 3
    );
    if let Some(kind) = kind {
        let t = Instant::now();
        let s = topoplex::build(kind, &c).expect("structure");
        line += &format!(" {}_s {:.4}", kind.name(), t.elapsed().as_secs_f64());
        drop(s);
    }
    line += &format!(" peak_bytes {}", status_bytes("VmHWM:"));
    println!("{line}");
}
