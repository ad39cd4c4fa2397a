//! The live complex (issue 14): link-checked edge contractions per second on manifold triangle
//! and tetrahedral grids, the link condition alone, storage against the IA's bytes, and handle
//! navigation against the static IA and IG.
//!
//! - `<grid>/live/link`: `link_condition` on a sample of edges of the fresh mesh; throughput =
//!   edges checked.
//! - `<grid>/live/contract`: one pass over a sample of edges of a fresh copy (cloned outside the
//!   timing), calling `contract(a, b, PreserveTopology, None)` on each pair still live; each
//!   call checks the link condition and contracts when it holds. Throughput = calls.
//! - Storage (printed to stderr, `storage <grid>: live B bytes, ia B bytes, ratio r`).
//! - `<grid>/nav/<query>/<kind>`: handle navigation on the live complex next to the static IA and
//!   IG built from the same mesh, through the same `&dyn Navigate` calls: one pass over every
//!   vertex (`VV` = R_{0,0}, `VT` = R_{0,d}, `star` = the star of the vertex) or every top
//!   simplex (`TT` = R_{d,d}, adjacency across facets), each answer visited (`visit`, no
//!   allocation). Handles are taken before the timing (the live complex's top handles are its
//!   own full-mask handles, its answers canonical). Throughput = handles asked.
//!
//! Times are the benchmark thread's on-CPU time (`/proc/thread-self/schedstat`, wall time where
//! that file is missing): on a shared, loaded machine wall time mostly measures the queue.

mod common;

use std::hint::black_box;
use std::time::{Duration, Instant};

use criterion::{Criterion, Throughput};
use topoplex::live::{ContractMode, LiveComplex, VertexId};
use topoplex::relation::{StructureKind, Topology};
use topoplex::{Complex, Navigate, Order, SimplexHandle};

const SAMPLE: usize = 20_000;

fn edge_sample(live: &LiveComplex) -> Vec<[u32; 2]> {
    let edges = live.edges();
    let step = (edges.len() / SAMPLE).max(1);
    edges.into_iter().step_by(step).take(SAMPLE).collect()
}

/// On-CPU time of this thread so far.
fn cpu_now() -> Option<Duration> {
    let s = std::fs::read_to_string("/proc/thread-self/schedstat").ok()?;
    let ns: u64 = s.split_whitespace().next()?.parse().ok()?;
    Some(Duration::from_nanos(ns))
}

/// Times `f` by on-CPU time (wall time as a fallback).
fn cpu_timed(f: impl FnOnce()) -> Duration {
    let (c0, w0) = (cpu_now(), Instant::now());
    f();
    match (c0, cpu_now()) {
        (Some(a), Some(b)) => b - a,
        _ => w0.elapsed(),
    }
}

fn bench_grid(c: &mut Criterion, name: &str, complex: &Complex) {
    let live = LiveComplex::from_complex(complex);
    let ia = topoplex::build(StructureKind::Ia, complex).expect("grids are manifolds");
    let (lb, ib) = (live.storage().bytes, ia.storage().bytes);
    eprintln!(
        "storage {name}: live {lb} bytes, ia {ib} bytes, ratio {:.2}",
        lb as f64 / ib as f64
    );
    let edges = edge_sample(&live);
    let mut g = c.benchmark_group(format!("{name}/live"));
    g.throughput(Throughput::Elements(edges.len() as u64));
    g.bench_function("link", |bch| {
        bch.iter_custom(|iters| {
            (0..iters)
                .map(|_| {
                    cpu_timed(|| {
                        let mut ok = 0usize;
                        for &[a, b] in &edges {
                            ok += live.link_condition(VertexId(a), VertexId(b)).is_ok() as usize;
                        }
                        black_box(ok);
                    })
                })
                .sum()
        })
    });
    let mut done = 0usize;
    g.bench_function("contract", |bch| {
        bch.iter_custom(|iters| {
            let mut total = Duration::ZERO;
            for _ in 0..iters {
                let mut copy = live.clone();
                total += cpu_timed(|| {
                    done = 0;
                    for &[a, b] in &edges {
                        let r = copy.contract(
                            VertexId(a),
                            VertexId(b),
                            ContractMode::PreserveTopology,
                            None,
                        );
                        done += r.is_ok() as usize;
                    }
                });
                black_box(&copy);
            }
            total
        })
    });
    g.finish();
    eprintln!(
        "contract {name}: {done} of {} calls contracted",
        edges.len()
    );
}

/// One navigation query: which handles it starts from, and what it walks.
#[derive(Clone, Copy)]
enum Query {
    Vv,
    Vt,
    Star,
    Tt,
}

impl Query {
    const ALL: [(Query, &'static str); 4] = [
        (Query::Vv, "VV"),
        (Query::Vt, "VT"),
        (Query::Tt, "TT"),
        (Query::Star, "star"),
    ];
}

/// The vertex handles and the top-simplex handles of `n`, taken once.
fn handles_of(
    n: &dyn Navigate,
    live: Option<&LiveComplex>,
) -> (Vec<SimplexHandle>, Vec<SimplexHandle>) {
    let d = n.dimension();
    let verts = (0..n.count(0) as u32)
        .map(|v| n.vertex(topoplex::VertexId(v)).unwrap())
        .collect();
    let tops = match live {
        Some(l) => l.tops().map(|(t, _)| l.top_handle(t).unwrap()).collect(),
        None => (0..n.count(d) as u32)
            .map(|i| n.handle(d, i).unwrap())
            .collect(),
    };
    (verts, tops)
}

/// One pass of `query` over its handles; returns a checksum of the answers.
fn walk(n: &dyn Navigate, query: Query, verts: &[SimplexHandle], tops: &[SimplexHandle]) -> usize {
    let d = n.dimension();
    let mut sum = 0usize;
    let mut star = Vec::new();
    let (hs, q) = match query {
        Query::Vv => (verts, 0),
        Query::Vt => (verts, d),
        Query::Tt => (tops, d),
        Query::Star => {
            for &h in verts {
                n.star(h, Order::Natural, &mut star).unwrap();
                sum += star.len();
            }
            return sum;
        }
    };
    for &h in hs {
        n.visit(h, q, &mut |x| sum += x.dim() + 1).unwrap();
    }
    sum
}

fn bench_navigation(c: &mut Criterion, name: &str, complex: &Complex) {
    let live = LiveComplex::from_complex(complex);
    let ia = topoplex::build(StructureKind::Ia, complex).expect("grids are manifolds");
    let ig = topoplex::build(StructureKind::Ig, complex).expect("IG builds every complex");
    let kinds: [(&str, &dyn Navigate, Option<&LiveComplex>); 3] = [
        ("live", &live, Some(&live)),
        ("ia", ia.as_navigate().unwrap(), None),
        ("ig", ig.as_navigate().unwrap(), None),
    ];
    let handles: Vec<_> = kinds.iter().map(|(_, n, l)| handles_of(*n, *l)).collect();
    for (query, qname) in Query::ALL {
        let mut g = c.benchmark_group(format!("{name}/nav/{qname}"));
        let sums: Vec<usize> = kinds
            .iter()
            .zip(&handles)
            .map(|((_, n, _), (v, t))| walk(*n, query, v, t))
            .collect();
        assert!(sums.windows(2).all(|w| w[0] == w[1]), "{qname}: {sums:?}");
        for ((kind, n, _), (v, t)) in kinds.iter().zip(&handles) {
            let count = if matches!(query, Query::Tt) {
                t.len()
            } else {
                v.len()
            };
            g.throughput(Throughput::Elements(count as u64));
            g.bench_function(*kind, |bch| {
                bch.iter_custom(|iters| {
                    (0..iters)
                        .map(|_| {
                            cpu_timed(|| {
                                black_box(walk(*n, query, v, t));
                            })
                        })
                        .sum()
                })
            });
        }
        g.finish();
    }
}

fn benches(c: &mut Criterion) {
    bench_grid(c, "tri-180k", &common::triangle_grid(300));
    bench_grid(c, "tet-160k", &common::tetrahedral_grid(30));
    bench_navigation(c, "tri-180k", &common::triangle_grid(300));
    bench_navigation(c, "tet-160k", &common::tetrahedral_grid(30));
}

fn main() {
    let mut c = Criterion::default()
        .configure_from_args()
        .sample_size(10)
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(2));
    benches(&mut c);
    c.final_summary();
}
