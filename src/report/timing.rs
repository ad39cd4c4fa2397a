//! Build and query timings per structure (see the [module documentation](super) for the
//! families and the sampling).

use std::hint::black_box;
use std::time::{Duration, Instant};

use serde::Serialize;

use topoplex::complex::Complex;
use topoplex::relation::{Storage, StructureKind, Topology};

/// Most vertices and most top simplices queried per family.
pub const SAMPLE: usize = 1000;
/// Each measurement repeats until it has taken this long (or [`MAX_PASSES`]).
pub const MIN_TIME: Duration = Duration::from_millis(20);
/// Most vertices (and most top simplices) a family queries.
pub const MAX_PASSES: u32 = 10_000;

/// A relation family: which simplices are asked which relations.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Family {
    /// R_{p,q}, q < p, of sampled top p-simplices (p ≥ 1), every such q.
    Boundary,
    /// R_{0,q}, 0 < q ≤ d, of sampled vertices, every such q.
    Coboundary,
    /// R_{0,0} of sampled vertices.
    AdjacencyVertex,
    /// R_{p,p} of sampled top p-simplices (p ≥ 1).
    AdjacencyTop,
}

impl Family {
    /// Every family, in report order.
    pub const ALL: [Family; 4] = [
        Family::Boundary,
        Family::Coboundary,
        Family::AdjacencyVertex,
        Family::AdjacencyTop,
    ];

    /// Machine name (JSON keys, CSV columns).
    pub fn name(self) -> &'static str {
        match self {
            Family::Boundary => "boundary",
            Family::Coboundary => "coboundary",
            Family::AdjacencyVertex => "adjacency_vertex",
            Family::AdjacencyTop => "adjacency_top",
        }
    }

    /// Human label (tables, charts).
    pub fn label(self) -> &'static str {
        match self {
            Family::Boundary => "boundary R(p,q<p) of tops",
            Family::Coboundary => "co-boundary R(0,q>0) of vertices",
            Family::AdjacencyVertex => "adjacency R(0,0) of vertices",
            Family::AdjacencyTop => "adjacency R(p,p) of tops",
        }
    }
}

/// The simplices queried: evenly spread, deterministic.
#[derive(Debug, Clone, PartialEq, Eq, Serialize)]
pub struct Sample {
    /// Vertices queried / vertices of the complex.
    pub vertices: usize,
    /// Vertices of the complex.
    pub vertices_total: usize,
    /// Top simplices of dimension ≥ 1 queried / their number.
    pub tops: usize,
    /// Top simplices of dimension ≥ 1.
    pub tops_total: usize,
    #[serde(skip)]
    vertex_ids: Vec<u32>,
    /// Sampled tops as (dimension, row).
    #[serde(skip)]
    top_rows: Vec<(usize, Vec<u32>)>,
}

impl Sample {
    /// At most `limit` vertices and `limit` top simplices, spread evenly.
    pub fn of(complex: &Complex, limit: usize) -> Sample {
        let n = complex.vertex_count() as usize;
        let vertex_ids: Vec<u32> = spread(n, limit).map(|i| i as u32).collect();
        let d = complex.dimension();
        let tops_total: usize = (1..=d).map(|p| complex.tops(p).len()).sum();
        let mut top_rows = Vec::new();
        let mut picks = spread(tops_total, limit).peekable();
        let mut base = 0;
        for p in 1..=d {
            let t = complex.tops(p);
            while let Some(&i) = picks.peek() {
                if i >= base + t.len() {
                    break;
                }
                top_rows.push((p, t.get(i - base).to_vec()));
                picks.next();
            }
            base += t.len();
        }
        Sample {
            vertices: vertex_ids.len(),
            vertices_total: n,
            tops: top_rows.len(),
            tops_total,
            vertex_ids,
            top_rows,
        }
    }

    /// The (simplex, q) queries of a family.
    fn queries(&self, family: Family, d: usize) -> Vec<(Vec<u32>, usize)> {
        let mut out = Vec::new();
        match family {
            Family::Boundary => {
                for (p, row) in &self.top_rows {
                    out.extend((0..*p).map(|q| (row.clone(), q)));
                }
            }
            Family::Coboundary => {
                for &v in &self.vertex_ids {
                    out.extend((1..=d).map(|q| (vec![v], q)));
                }
            }
            Family::AdjacencyVertex => out.extend(self.vertex_ids.iter().map(|&v| (vec![v], 0))),
            Family::AdjacencyTop => out.extend(self.top_rows.iter().map(|(p, r)| (r.clone(), *p))),
        }
        out
    }
}

/// `count` indexes spread evenly over `0..n` (all of them when `n <= count`).
fn spread(n: usize, count: usize) -> impl Iterator<Item = usize> {
    let k = n.min(count);
    (0..k).map(move |i| i * n / k)
}

/// One family's measurement on one structure.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct FamilyTiming {
    /// The family measured.
    pub family: Family,
    /// Queries per pass and the rows they retrieve.
    pub queries: usize,
    /// Rows retrieved per pass.
    pub elements: u64,
    /// Timed passes (after one warm-up pass).
    pub passes: u32,
    /// Mean time per retrieved row; `None` when the family retrieves nothing here.
    pub ns_per_element: Option<f64>,
    /// Mean time per query.
    pub ns_per_query: Option<f64>,
    /// A query failed (a bug: every queried simplex is in the complex).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub error: Option<String>,
}

/// One structure's figures.
#[derive(Debug, Clone, PartialEq)]
pub struct Measured {
    /// Storage of the structure.
    pub storage: Storage,
    /// Storage bytes / Σ_p n_p.
    pub bytes_per_simplex: f64,
    /// Mean build time (one build when it takes ≥ `MIN_TIME`, else repeated builds after one).
    pub build_ms: f64,
    /// Mean build time per simplex of the complex.
    pub build_ns_per_simplex: f64,
    /// Builds timed.
    pub builds: u32,
    /// The structure's own `summary()` figures (IQM: components, split vertices...).
    pub summary: Vec<(String, u64)>,
    /// The families' timings.
    pub families: Vec<FamilyTiming>,
}

/// What happened to one structure on one dataset.
#[derive(Debug, Clone, PartialEq)]
pub struct StructureResult {
    /// The structure.
    pub kind: StructureKind,
    /// `Err`: why the structure cannot encode the complex (or could not be built).
    pub outcome: Result<Measured, String>,
}

/// Builds `kind` for `complex` and times its build and the four families on `sample`.
/// `total` is Σ_p n_p.
pub fn measure(
    kind: StructureKind,
    complex: &Complex,
    sample: &Sample,
    total: usize,
    progress: &mut dyn FnMut(&str),
) -> StructureResult {
    progress(&format!("building {kind}"));
    let start = Instant::now();
    let built = topoplex::family::build(kind, complex);
    let first = start.elapsed();
    let topo = match built {
        Ok(t) => t,
        Err(e) => {
            return StructureResult {
                kind,
                outcome: Err(e.to_string()),
            };
        }
    };
    let (build_time, builds) = if first >= MIN_TIME {
        (first, 1)
    } else {
        // The first build warmed the allocator and caches; time the repeats.
        let start = Instant::now();
        let mut builds = 0;
        while builds == 0 || (start.elapsed() < MIN_TIME && builds < MAX_PASSES) {
            black_box(topoplex::family::build(kind, complex).ok());
            builds += 1;
        }
        (start.elapsed() / builds, builds)
    };
    let d = complex.dimension();
    let families = Family::ALL
        .into_iter()
        .map(|f| {
            progress(&format!("timing {kind} {}", f.name()));
            time_family(topo.as_ref(), f, &sample.queries(f, d))
        })
        .collect();
    let storage = topo.storage();
    StructureResult {
        kind,
        outcome: Ok(Measured {
            storage,
            bytes_per_simplex: storage.bytes as f64 / total.max(1) as f64,
            build_ms: build_time.as_secs_f64() * 1e3,
            build_ns_per_simplex: build_time.as_secs_f64() * 1e9 / total.max(1) as f64,
            builds,
            summary: topo
                .summary()
                .into_iter()
                .map(|(k, v)| (k.to_string(), v))
                .collect(),
            families,
        }),
    }
}

fn time_family(topo: &dyn Topology, family: Family, queries: &[(Vec<u32>, usize)]) -> FamilyTiming {
    let mut out = Vec::new();
    let pass = |out: &mut Vec<u32>| -> Result<u64, String> {
        let mut elements = 0u64;
        for (sigma, q) in queries {
            out.clear();
            topo.query(black_box(sigma), *q, out)
                .map_err(|e| format!("R_{{{},{q}}}: {e}", sigma.len() - 1))?;
            elements += (out.len() / (q + 1)) as u64;
        }
        Ok(elements)
    };
    let mut result = FamilyTiming {
        family,
        queries: queries.len(),
        elements: 0,
        passes: 0,
        ns_per_element: None,
        ns_per_query: None,
        error: None,
    };
    match pass(&mut out) {
        Ok(e) => result.elements = e,
        Err(e) => {
            result.error = Some(e);
            return result;
        }
    }
    if queries.is_empty() {
        return result;
    }
    let start = Instant::now();
    let mut passes = 0u32;
    while passes == 0 || (start.elapsed() < MIN_TIME && passes < MAX_PASSES) {
        // Errors were ruled out by the warm-up pass; the answer is the same each time.
        black_box(pass(&mut out).ok());
        passes += 1;
    }
    let ns = start.elapsed().as_secs_f64() * 1e9 / passes as f64;
    result.passes = passes;
    result.ns_per_query = Some(ns / queries.len() as f64);
    if result.elements > 0 {
        result.ns_per_element = Some(ns / result.elements as f64);
    }
    result
}
