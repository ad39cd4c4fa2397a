//! The live complex (issue 14): link-checked edge contractions per second on manifold triangle
//! and tetrahedral grids, the link condition alone, and storage against the IA's bytes.
//!
//! - `<grid>/live/link`: `link_condition` on a sample of edges of the fresh mesh; throughput =
//!   edges checked.
//! - `<grid>/live/contract`: one pass over a sample of edges of a fresh copy (cloned outside the
//!   timing), calling `contract(a, b, PreserveTopology, None)` on each pair still live; each
//!   call checks the link condition and contracts when it holds. Throughput = calls.
//! - Storage (printed to stderr, `storage <grid>: live B bytes, ia B bytes, ratio r`).
//!
//! Times are the benchmark thread's on-CPU time (`/proc/thread-self/schedstat`, wall time where
//! that file is missing): on a shared, loaded machine wall time mostly measures the queue.

mod common;

use std::hint::black_box;
use std::time::{Duration, Instant};

use criterion::{Criterion, Throughput};
use topoplex::live::{ContractMode, LiveComplex, VertexId};
use topoplex::relation::{StructureKind, Topology};
use topoplex::{Complex, structures};

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
    let ia = structures::build(StructureKind::Ia, complex).expect("grids are manifolds");
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

fn benches(c: &mut Criterion) {
    bench_grid(c, "tri-180k", &common::triangle_grid(300));
    bench_grid(c, "tet-160k", &common::tetrahedral_grid(30));
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
