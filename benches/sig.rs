//! SIG query cost per output element, as the complex grows (triangulated and tetrahedral grids
//! of ~10^4, 10^5, 10^6 simplices) and as the star of the query simplex grows (fans of 10 to
//! 10^5 triangles around one vertex and around one edge). Throughput is in output simplices, so
//! a flat time per element across sizes is what §6's linear bound predicts.
//!
//! `cargo bench --bench sig` (see docs/benchmarks.md for the settings used).

use std::time::Duration;

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use topoplex::structures::sig::Sig;
use topoplex::{Complex, Topology};

mod common;
use common::{complex, tetrahedral_grid, triangle_grid};

/// k triangles 0-i-(i+1) around vertex 0 (an open fan).
fn vertex_fan(k: u32) -> Complex {
    let tris: Vec<Vec<u32>> = (1..=k).map(|i| vec![0, i, i + 1]).collect();
    complex(k + 2, &tris)
}

/// k triangles 0-1-i on edge 0-1 (a book).
fn edge_fan(k: u32) -> Complex {
    let tris: Vec<Vec<u32>> = (2..k + 2).map(|i| vec![0, 1, i]).collect();
    complex(k + 2, &tris)
}

/// Up to 512 p-simplices spread evenly over the table.
fn sample(s: &Sig, p: usize) -> Vec<Vec<u32>> {
    let mut all = Vec::new();
    s.simplices(p, &mut all);
    let n = all.len() / (p + 1);
    let step = (n / 512).max(1);
    all.chunks(p + 1)
        .step_by(step)
        .take(512)
        .map(<[u32]>::to_vec)
        .collect()
}

/// Output simplices of one pass of `queries`.
fn output_size(s: &Sig, queries: &[Vec<u32>], q: usize) -> u64 {
    let mut out = Vec::new();
    queries
        .iter()
        .map(|sigma| {
            s.relation(sigma, q, &mut out).unwrap();
            (out.len() / (q + 1)) as u64
        })
        .sum()
}

fn run(
    c: &mut criterion::BenchmarkGroup<'_, criterion::measurement::WallTime>,
    name: &str,
    size: u64,
    s: &Sig,
    queries: &[Vec<u32>],
    q: usize,
) {
    c.throughput(Throughput::Elements(output_size(s, queries, q)));
    let mut out = Vec::new();
    c.bench_with_input(BenchmarkId::new(name, size), queries, |b, queries| {
        b.iter(|| {
            let mut total = 0;
            for sigma in queries {
                s.relation(sigma, q, &mut out).unwrap();
                total += out.len();
            }
            total
        })
    });
}

/// Baseline: finding the sampled simplices by their vertex ids (searches by prefix), which every
/// query above pays once; throughput counts one element per query.
fn locate(
    c: &mut criterion::BenchmarkGroup<'_, criterion::measurement::WallTime>,
    name: &str,
    size: u64,
    s: &Sig,
    queries: &[Vec<u32>],
) {
    c.throughput(Throughput::Elements(queries.len() as u64));
    c.bench_with_input(BenchmarkId::new(name, size), queries, |b, queries| {
        b.iter(|| queries.iter().filter(|q| s.contains(q)).count())
    });
}

fn grids(cr: &mut Criterion) {
    let mut g = cr.benchmark_group("sig_grid");
    // Side lengths for ~10^4, 10^5, 10^6 simplices.
    for k in [41u32, 129, 408] {
        let s = Sig::build(&triangle_grid(k)).unwrap();
        let n: u64 = (0..=2).map(|p| s.count(p) as u64).sum();
        let (v, e, t) = (sample(&s, 0), sample(&s, 1), sample(&s, 2));
        locate(&mut g, "tri locate edge", n, &s, &e);
        run(&mut g, "tri R0,2", n, &s, &v, 2);
        run(&mut g, "tri R0,0", n, &s, &v, 0);
        run(&mut g, "tri R1,2", n, &s, &e, 2);
        run(&mut g, "tri R2,2", n, &s, &t, 2);
        run(&mut g, "tri R2,0", n, &s, &t, 0);
    }
    for k in [7u32, 15, 34] {
        let s = Sig::build(&tetrahedral_grid(k)).unwrap();
        let n: u64 = (0..=3).map(|p| s.count(p) as u64).sum();
        let (v, e, f, t) = (sample(&s, 0), sample(&s, 1), sample(&s, 2), sample(&s, 3));
        locate(&mut g, "tet locate edge", n, &s, &e);
        run(&mut g, "tet R0,3", n, &s, &v, 3);
        run(&mut g, "tet R0,1", n, &s, &v, 1);
        run(&mut g, "tet R1,3", n, &s, &e, 3);
        run(&mut g, "tet R1,2", n, &s, &e, 2);
        run(&mut g, "tet R2,2", n, &s, &f, 2);
        run(&mut g, "tet R3,3", n, &s, &t, 3);
        run(&mut g, "tet R3,1", n, &s, &t, 1);
    }
    g.finish();
}

fn fans(cr: &mut Criterion) {
    let mut g = cr.benchmark_group("sig_fan");
    for k in [10u32, 100, 1_000, 10_000, 100_000] {
        let k64 = k as u64;
        let s = Sig::build(&vertex_fan(k)).unwrap();
        run(&mut g, "vertex fan R0,2(hub)", k64, &s, &[vec![0]], 2);
        run(&mut g, "vertex fan R0,1(hub)", k64, &s, &[vec![0]], 1);
        run(&mut g, "vertex fan R0,0(hub)", k64, &s, &[vec![0]], 0);
        let s = Sig::build(&edge_fan(k)).unwrap();
        run(&mut g, "edge fan R1,2(spine)", k64, &s, &[vec![0, 1]], 2);
        run(&mut g, "edge fan R0,2(end)", k64, &s, &[vec![0]], 2);
        run(&mut g, "edge fan R2,2(page)", k64, &s, &[vec![0, 1, 2]], 2);
    }
    g.finish();
}

fn config() -> Criterion {
    Criterion::default()
        .sample_size(10)
        .warm_up_time(Duration::from_millis(200))
        .measurement_time(Duration::from_millis(600))
}

criterion_group! {
    name = benches;
    config = config();
    targets = grids, fans
}
criterion_main!(benches);
