//! Times `Complex::from_arrays` alone (the normalisation every `soup` build starts with):
//! `from_arrays FILE THREADS [RUNS]` prints the best and median of RUNS (default 15) runs in
//! seconds, and the complex's top counts. For profiling (`perf record`) and side-by-side runs
//! against another build of this example.

use std::path::Path;
use std::time::Instant;

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let [file, threads, rest @ ..] = args.as_slice() else {
        eprintln!("usage: from_arrays FILE THREADS [RUNS]");
        std::process::exit(1);
    };
    let runs: usize = rest.first().map_or(15, |r| r.parse().expect("RUNS"));
    let raw = topoplex::io::read_path(Path::new(file)).expect("read");
    let n = raw
        .vertex_count
        .unwrap_or_else(|| raw.ids.iter().max().map_or(0, |m| m + 1));
    topoplex::parallel::set_threads(threads.parse().expect("THREADS"));
    let mut times = Vec::with_capacity(runs);
    let mut counts = Vec::new();
    for _ in 0..runs {
        let t = Instant::now();
        let c = topoplex::Complex::from_arrays(n, &raw.ids, &raw.offsets, None).expect("complex");
        times.push(t.elapsed().as_secs_f64());
        counts = c.top_counts();
        drop(c);
    }
    times.sort_by(f64::total_cmp);
    println!(
        "best {:.5} median {:.5} tops {:?}",
        times[0],
        times[times.len() / 2],
        counts
    );
}
