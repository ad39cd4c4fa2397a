//! Every structure on the same complexes: build time per simplex and time per retrieved element
//! of each relation family (issue 9 part 2, the Rust API side).
//!
//! Complexes: triangle and tetrahedral grids of ~10^4, 10^5, 10^6 simplices, and the real data
//! in `../shared/data` when present (files that are absent or do not load are skipped). For
//! each structure that encodes the complex (the others are skipped with their reason on stderr):
//! - `build`: `topoplex::build` from the complex (closure included); throughput = simplices
//!   of the complex, so criterion reports time per simplex;
//! - `Rd,q` (q < d): boundary of top d-simplices;
//! - `R0,q` (q > 0): co-boundary of vertices (VF, star cells, star edges, ...);
//! - `R0,0`: vertices adjacent to a vertex (VV); `Rd,d`: top simplices adjacent to one (FF).
//!
//! Queries go through `Topology::query` (the structure's own path, as `tpx_relation_table`
//! calls it) on an evenly spaced sample of at most `MAX_QUERIES` simplices; throughput = rows
//! retrieved by one pass over the sample, so criterion reports time per element.
//!
//! Benchmark ids are `<complex>/<kind>/<op>`, e.g. `tri-1M/ia/R0,2`. Criterion's filter selects a
//! subset (`cargo bench --bench structures -- tet-1M/ts/`); a filter without regex
//! metacharacters also skips building what it excludes. `benches/structures_table.py` turns
//! criterion's output into tables (docs/benchmarks.md merges its grid sizes into one table).

mod common;

use std::hint::black_box;
use std::path::Path;
use std::time::Duration;

use criterion::{BenchmarkId, Criterion, SamplingMode, Throughput};
use topoplex::Complex;
use topoplex::relation::{StructureKind, Topology};

/// Queries per relation family: enough to cover every kind of vertex/simplex of a grid while
/// keeping one pass near a millisecond.
const MAX_QUERIES: usize = 2048;

/// Real complexes, by path under ../shared/data.
const REAL: [&str; 4] = [
    "surfaces/bunny00.off",
    "tetrahedral/slug.mesh",
    "mixed/alpha_kitten.simplices",
    "highdim/rips_hippo1.simplices",
];

/// A generated complex: name, generator, side length.
type Grid = (&'static str, fn(u32) -> Complex, u32);

/// Criterion's name filter when it is a plain substring (no regex metacharacters); used only to
/// skip building structures no selected benchmark needs.
fn literal_filter() -> Option<String> {
    let mut args = std::env::args().skip(1);
    while let Some(a) = args.next() {
        if a.starts_with("--") {
            // Options that take a value.
            if matches!(
                a.as_str(),
                "--save-baseline"
                    | "--baseline"
                    | "--baseline-lenient"
                    | "--load-baseline"
                    | "--profile-time"
                    | "--sample-size"
                    | "--warm-up-time"
                    | "--measurement-time"
                    | "--nresamples"
                    | "--noise-threshold"
                    | "--confidence-level"
                    | "--significance-level"
                    | "--plotting-backend"
                    | "--output-format"
                    | "--color"
                    | "--format"
            ) {
                args.next();
            }
            continue;
        }
        if a.starts_with('-') {
            continue;
        }
        return (!a.chars().any(|c| "\\^$.|?*+()[]{}".contains(c))).then_some(a);
    }
    None
}

/// The relation families for dimension d: (op name, p, q).
fn families(d: usize) -> Vec<(String, usize, usize)> {
    let mut ops = Vec::new();
    for q in 0..d {
        ops.push((format!("R{d},{q}"), d, q));
    }
    for q in 1..=d {
        ops.push((format!("R0,{q}"), 0, q));
    }
    ops.push(("R0,0".to_string(), 0, 0));
    if d > 0 {
        ops.push((format!("R{d},{d}"), d, d));
    }
    ops
}

/// At most `MAX_QUERIES` p-simplices spread evenly over the structure's table.
fn sample(topo: &dyn Topology, p: usize) -> Vec<u32> {
    let mut all = Vec::new();
    topo.simplices(p, &mut all);
    let n = all.len() / (p + 1);
    let step = n.div_ceil(MAX_QUERIES).max(1);
    all.chunks_exact(p + 1)
        .step_by(step)
        .flatten()
        .copied()
        .collect()
}

/// One pass of R_{p,q} over `queries` (rows of p + 1 ids); returns the rows retrieved.
fn pass(topo: &dyn Topology, queries: &[u32], p: usize, q: usize, out: &mut Vec<u32>) -> usize {
    let mut rows = 0;
    for sigma in queries.chunks_exact(p + 1) {
        out.clear();
        topo.query(sigma, q, out).expect("sampled simplex");
        rows += out.len() / (q + 1);
    }
    rows
}

/// Whether a literal filter can select some benchmark of a complex of dimension d.
fn selects_any(filter: Option<&str>, name: &str, d: usize) -> bool {
    filter.is_none_or(|f| {
        StructureKind::ALL.iter().any(|kind| {
            std::iter::once("build".to_string())
                .chain(families(d).into_iter().map(|(op, _, _)| op))
                .any(|op| format!("{name}/{kind}/{op}").contains(f))
        })
    })
}

fn bench_complex(c: &mut Criterion, name: &str, complex: &Complex, filter: Option<&str>) {
    let d = complex.dimension();
    let ops = families(d);
    let mut g = c.benchmark_group(name);
    for kind in StructureKind::ALL {
        let wanted = |op: &str| filter.is_none_or(|f| format!("{name}/{kind}/{op}").contains(f));
        if !wanted("build") && !ops.iter().any(|(op, _, _)| wanted(op)) {
            continue;
        }
        let topo = match topoplex::build(kind, complex) {
            Ok(t) => t,
            Err(e) => {
                eprintln!("{name}/{kind}: skipped: {e}");
                continue;
            }
        };
        let simplices: usize = (0..=d).map(|p| topo.count(p)).sum();
        if wanted("build") {
            // Builds of 10^6 simplices take most of a second: ten single-build samples.
            g.sampling_mode(SamplingMode::Flat)
                .sample_size(10)
                .warm_up_time(Duration::from_millis(1))
                .measurement_time(Duration::from_millis(500))
                .throughput(Throughput::Elements(simplices as u64));
            g.bench_function(BenchmarkId::new(kind.name(), "build"), |b| {
                b.iter(|| topoplex::build(kind, black_box(complex)).unwrap())
            });
        }
        g.sampling_mode(SamplingMode::Auto)
            .sample_size(10)
            .warm_up_time(Duration::from_millis(50))
            .measurement_time(Duration::from_millis(200));
        let mut out = Vec::new();
        let mut samples: Vec<Option<Vec<u32>>> = vec![None; d + 1];
        for (op, p, q) in &ops {
            if !wanted(op) {
                continue;
            }
            let (p, q) = (*p, *q);
            let queries = samples[p].get_or_insert_with(|| sample(topo.as_ref(), p));
            let rows = pass(topo.as_ref(), queries, p, q, &mut out);
            if rows == 0 {
                continue;
            }
            g.throughput(Throughput::Elements(rows as u64));
            g.bench_function(BenchmarkId::new(kind.name(), op), |b| {
                b.iter(|| pass(topo.as_ref(), black_box(queries), p, q, &mut out))
            });
        }
    }
    g.finish();
}

fn main() {
    // Plots and the default 100,000 bootstrap resamples cost seconds per benchmark; the tables
    // need only the mean.
    let mut c = Criterion::default()
        .without_plots()
        .nresamples(10_000)
        .configure_from_args();
    let filter = literal_filter();
    let filter = filter.as_deref();
    let grids: [Grid; 6] = [
        ("tri-10k", common::triangle_grid, 41),
        ("tri-100k", common::triangle_grid, 129),
        ("tri-1M", common::triangle_grid, 408),
        ("tet-10k", common::tetrahedral_grid, 7),
        ("tet-100k", common::tetrahedral_grid, 15),
        ("tet-1M", common::tetrahedral_grid, 34),
    ];
    for (name, make, k) in grids {
        let d = if name.starts_with("tri") { 2 } else { 3 };
        if selects_any(filter, name, d) {
            bench_complex(&mut c, name, &make(k), filter);
        }
    }
    let data = Path::new(env!("CARGO_MANIFEST_DIR")).join("../shared/data");
    for file in REAL {
        let path = data.join(file);
        let name = Path::new(file).file_stem().unwrap().to_string_lossy();
        match Complex::from_path(&path) {
            Ok(complex) if selects_any(filter, &name, complex.dimension()) => {
                bench_complex(&mut c, &name, &complex, filter)
            }
            Ok(_) => {}
            Err(e) => eprintln!("{file}: skipped: {e}"),
        }
    }
    c.final_summary();
}
