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

/// What each sampled simplex is asked: a relation `R_{p,q}`, or only whether it is there.
#[derive(Clone, Copy)]
enum Ask {
    /// Baseline: finding the sampled simplices by their vertex ids (searches by prefix), which
    /// every relation query pays once; throughput counts one element per query.
    Locate,
    /// `R_{p,q}` of each; throughput counts its output simplices.
    Relation(usize),
}

fn run(
    c: &mut criterion::BenchmarkGroup<'_, criterion::measurement::WallTime>,
    name: &str,
    size: u64,
    s: &Sig,
    queries: &[Vec<u32>],
    ask: Ask,
) {
    let elements = match ask {
        Ask::Locate => queries.len() as u64,
        Ask::Relation(q) => output_size(s, queries, q),
    };
    c.throughput(Throughput::Elements(elements));
    let mut out = Vec::new();
    c.bench_with_input(BenchmarkId::new(name, size), queries, |b, queries| {
        b.iter(|| {
            let mut total = 0;
            for sigma in queries {
                total += match ask {
                    Ask::Locate => usize::from(s.contains(sigma)),
                    Ask::Relation(q) => {
                        s.relation(sigma, q, &mut out).unwrap();
                        out.len()
                    }
                };
            }
            total
        })
    });
}

/// One grid's benchmarks: locating sampled edges, then each relation `R_{p,q}` of `pq` from
/// sampled p-simplices, named `"{shape} R{p},{q}"`; the complex's size is its simplex count.
fn grid(
    g: &mut criterion::BenchmarkGroup<'_, criterion::measurement::WallTime>,
    shape: &str,
    s: &Sig,
    pq: &[(usize, usize)],
) {
    let d = s.dimension();
    let n: u64 = (0..=d).map(|p| s.count(p) as u64).sum();
    let samples: Vec<Vec<Vec<u32>>> = (0..=d).map(|p| sample(s, p)).collect();
    run(
        g,
        &format!("{shape} locate edge"),
        n,
        s,
        &samples[1],
        Ask::Locate,
    );
    for &(p, q) in pq {
        run(
            g,
            &format!("{shape} R{p},{q}"),
            n,
            s,
            &samples[p],
            Ask::Relation(q),
        );
    }
}

fn grids(cr: &mut Criterion) {
    let mut g = cr.benchmark_group("sig_grid");
    let tri = [(0, 2), (0, 0), (1, 2), (2, 2), (2, 0)];
    let tet = [(0, 3), (0, 1), (1, 3), (1, 2), (2, 2), (3, 3), (3, 1)];
    // Side lengths for ~10^4, 10^5, 10^6 simplices.
    let grids = [
        (
            "tri",
            triangle_grid as fn(u32) -> Complex,
            [41, 129, 408],
            &tri[..],
        ),
        ("tet", tetrahedral_grid, [7, 15, 34], &tet[..]),
    ];
    for (shape, build, sides, pq) in grids {
        for k in sides {
            grid(&mut g, shape, &Sig::build(&build(k)).unwrap(), pq);
        }
    }
    g.finish();
}

fn fans(cr: &mut Criterion) {
    let mut g = cr.benchmark_group("sig_fan");
    for k in [10u32, 100, 1_000, 10_000, 100_000] {
        let k64 = k as u64;
        let (hub, book) = (
            Sig::build(&vertex_fan(k)).unwrap(),
            Sig::build(&edge_fan(k)).unwrap(),
        );
        let asks: [(&str, &Sig, &[u32], usize); 6] = [
            ("vertex fan R0,2(hub)", &hub, &[0], 2),
            ("vertex fan R0,1(hub)", &hub, &[0], 1),
            ("vertex fan R0,0(hub)", &hub, &[0], 0),
            ("edge fan R1,2(spine)", &book, &[0, 1], 2),
            ("edge fan R0,2(end)", &book, &[0], 2),
            ("edge fan R2,2(page)", &book, &[0, 1, 2], 2),
        ];
        for (name, s, sigma, q) in asks {
            run(&mut g, name, k64, s, &[sigma.to_vec()], Ask::Relation(q));
        }
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
