//! Quadric-error edge-contraction simplification of any simplicial complex: triangle and
//! tetrahedral meshes, mixed-dimensional and non-manifold complexes, any dimension (Garland and
//! Heckbert 1997, generalised to k-simplices in R^n by Garland and Zhou 2005), on the
//! [`LiveComplex`].
//!
//! # Steps ([`simplify`])
//! 1. `init_quadrics`: every vertex gets the sum of the quadrics of the top simplices around
//!    it — the squared distance to each top k-simplex's affine hull in the coordinate space
//!    R^n, weighted by `vol_k(σ)^(2/k)` (area for a triangle, length² for an edge, so simplices
//!    of different dimensions weigh in the same unit) — plus, for every *boundary facet* of a
//!    top simplex (a facet no other top simplex holds), the quadric of the facet's hull with
//!    its owner's weight. The latter keeps open borders of surfaces and, for simplices that
//!    span R^n (tetrahedra in R^3, whose own quadric is zero), the boundary surface.
//! 2. `fill_queue`: every edge {a, b} with its cost `min_x (Q_a + Q_b)(x)`; the minimiser
//!    solves `A x = −b`, and where A is singular or the solution lies more than 4 edge lengths
//!    from the edge's midpoint, the best point of the segment [a, b] is taken instead.
//! 3. `contract_loop`: pop the cheapest edge; entries carry the sum of their two vertices'
//!    versions and are skipped when it changed (lazy invalidation, no decrease-key); contract
//!    it (into the vertex with the larger star, which then moves to the minimiser), add the
//!    quadrics, bump the survivor's version and push its edges with their new costs. With
//!    `preserve_topology` the contraction is link-checked in every dimension, on the complex
//!    coned over its boundary ([`ContractMode::PreserveManifold`]: manifolds with boundary
//!    stay manifolds), and a refused edge
//!    is parked; when the queue runs dry before the target, the parked edges whose endpoints'
//!    neighbourhoods changed since (a contraction touched the survivor and its ring) are queued
//!    again, and the loop ends when none did.
//!    It stops once the live top simplices are at most `ceil(ratio × input top simplices)`.
//! 4. [`LiveComplex::to_complex`], for any writer or any of the nine structures.
//!
//! # Data and regions
//! The live complex carries the input's attributes through every contraction (the
//! [`crate::live::data`] module): each surviving top keeps its labels, a top that drops a
//! dimension keeps its preimage's, listed faces are renamed with the edge, and the output
//! complex has them all. With [`Options::keep_regions`] (an integer label of the listed
//! simplices, such as `gmsh:physical` or `medit:ref`), a contraction of b into a must leave the
//! regions apart (`Regions::allow`, tried in both directions): b lies in the closure of at most
//! two labels (an interface or an interior vertex, never a corner where three or more meet —
//! labels of the listed faces through b count, by dimension), the tops and listed faces through
//! the edge carry exactly b's labels (so an interface vertex moves only along its interface),
//! and no label loses its last tops with the edge. When a has more labels than b, a stays where
//! it is. Refusals are counted in [`Stats::refused_regions`]; each check costs O(k_a + k_b)
//! plus the listed faces at the two vertices.
//!
//! # Cost
//! Step 1 O(Σ_σ d² (n² + d·k_v)), step 2 O(E (n³ + log E)), step 3 per contraction the
//! [`LiveComplex::contract`] cost plus O(deg(a) (n³ + log E)) for the new costs. Memory beyond
//! the live complex: `(n + 1)(n + 2) / 2` doubles and two integers per vertex (three with
//! `preserve_topology`), and a queue of 16-byte entries allocated once at 1.25 × the edges (one
//! entry per live edge plus stale ones: when it is full, the stale entries are dropped).
//! Contractions rewrite the moved top simplices in their slots, so the live complex does not
//! grow.

pub mod quadric;

use std::cmp::Reverse;
use std::collections::BinaryHeap;

use std::path::Path;

use crate::complex::{Complex, push_facet};
use crate::io::write::{Format, WriteError, WriteErrorKind};
use crate::io::{Coords, RawInput};
use crate::live::{ContractMode, LiveComplex, Refusal, VertexId};
use crate::relation::StructureKind;
use crate::structures::BuildError;
use crate::structures::common::{try_vec, try_with_capacity};
use quadric::{QuadricSpace, sum_into};

/// Most top simplices of one dimension the live complex's handles can number (2^28) halved:
/// a contraction keeps moved tops in their slots, but a degenerate image that stays a top (a
/// top through both ends whose image is no face of another) takes a new slot.
pub const MAX_TOPS_PER_DIMENSION: usize = 1 << 27;

/// What to simplify to.
#[derive(Debug, Clone, PartialEq)]
pub struct Options {
    /// Fraction of the input's top simplices to keep, in (0, 1].
    pub ratio: f64,
    /// Contract only edges satisfying the link condition in every dimension: the Betti numbers
    /// are kept, and a 2- or 3-manifold stays one.
    pub preserve_topology: bool,
    /// Keep the regions of this integer label attribute of the listed simplices apart (module
    /// doc, "Data and regions"): no contraction erases a region or merges two across their
    /// interface.
    pub keep_regions: Option<String>,
}

impl Options {
    /// Down to `ratio`, link-checked when `preserve_topology`, without regions.
    pub fn new(ratio: f64, preserve_topology: bool) -> Options {
        Options {
            ratio,
            preserve_topology,
            keep_regions: None,
        }
    }
}

/// Why a complex was not simplified.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SimplifyError {
    /// The ratio is not in (0, 1].
    #[error("ratio {0} is outside (0, 1]")]
    Ratio(f64),
    /// The complex has no vertex coordinates: quadrics need geometry.
    #[error("{}the complex has no vertex coordinates; simplification measures distances", source_prefix(.file))]
    NoCoordinates {
        /// The input file, when known.
        file: Option<std::path::PathBuf>,
    },
    /// `keep_regions` names no integer label attribute of the listed simplices.
    #[error("{}--keep-regions {name}: {why}", source_prefix(.file))]
    Regions {
        /// The input file, when known.
        file: Option<std::path::PathBuf>,
        /// The attribute asked for.
        name: String,
        /// What the input has instead.
        why: String,
    },
    /// A coordinate is NaN or infinite.
    #[error("{}vertex {vertex} has a non-finite coordinate", source_prefix(.file))]
    NonFinite {
        /// The input file, when known.
        file: Option<std::path::PathBuf>,
        /// The first vertex with a non-finite coordinate.
        vertex: u32,
    },
    /// An array sized from the input cannot be allocated while building the live complex
    /// (reported, never an abort).
    #[error("{}cannot hold the input: {source}", source_prefix(.file))]
    Memory {
        /// The input file, when known.
        file: Option<std::path::PathBuf>,
        /// What could not be allocated.
        source: crate::structures::BuildError,
    },
    /// More top simplices of one dimension than the live complex can number.
    #[error("{}{count} top {dim}-simplices, above the {max} simplification can hold", source_prefix(.file))]
    TooLarge {
        /// The input file, when known.
        file: Option<std::path::PathBuf>,
        /// The dimension.
        dim: usize,
        /// Top simplices of that dimension.
        count: usize,
        /// [`MAX_TOPS_PER_DIMENSION`].
        max: usize,
    },
}

fn source_prefix(file: &Option<std::path::PathBuf>) -> String {
    file.as_ref()
        .map(|p| format!("{}: ", crate::error::echo_path(p)))
        .unwrap_or_default()
}

/// What a simplification did.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, serde::Serialize)]
pub struct Stats {
    /// Top simplices of the input (all dimensions, isolated vertices included).
    pub input_tops: usize,
    /// The target: `ceil(ratio × input_tops)`.
    pub target_tops: usize,
    /// Top simplices of the result.
    pub output_tops: usize,
    /// Contractions made.
    pub contractions: usize,
    /// Contractions refused by the link condition (with `preserve_topology`).
    pub refused: usize,
    /// Times the queue ran dry and the refused edges whose neighbourhood had changed since were
    /// queued again.
    pub refills: usize,
    /// Contractions refused to keep the regions apart (with `keep_regions`).
    pub refused_regions: usize,
}

/// The simplified complex and what it took.
#[derive(Debug, Clone)]
pub struct Simplified {
    /// The result, vertices renumbered densely (see [`LiveComplex::to_complex`]).
    pub complex: Complex,
    /// Counts.
    pub stats: Stats,
}

/// Simplifies `complex` to about `options.ratio` × its top simplices; `progress(done, total)`
/// is called now and then with top simplices removed so far and to remove in all.
pub fn simplify(
    complex: &Complex,
    options: &Options,
    progress: &mut dyn FnMut(usize, usize),
) -> Result<Simplified, SimplifyError> {
    check(complex, options)?;
    let mut live = live_of(complex)?;
    let stats = simplify_live(&mut live, options, progress)?;
    Ok(Simplified {
        complex: live.to_complex(),
        stats,
    })
}

/// The kind named in [`SimplifyError::Memory`]: the arrays are the live complex's and its run's.
const K: StructureKind = StructureKind::IaStar;

/// [`SimplifyError::Memory`] for an array of the run (quadrics, stamps, the queue) that could
/// not be allocated: each is reserved fallibly at its exact size before the contractions start.
fn memory(source: BuildError) -> SimplifyError {
    SimplifyError::Memory { file: None, source }
}

/// The live complex of `complex`, or [`SimplifyError::Memory`]: built fallibly, as the
/// structures are.
fn live_of(complex: &Complex) -> Result<LiveComplex, SimplifyError> {
    LiveComplex::try_from_complex(complex).map_err(|source| SimplifyError::Memory {
        file: complex.source().map(Path::to_path_buf),
        source,
    })
}

/// [`simplify`] taking the complex by value: it is dropped as soon as the live complex is
/// built, and its freed pages handed back to the system (see
/// `sys::release_freed_memory`), so the peak memory holds one copy of the input, not two.
pub fn simplify_owned(
    complex: Complex,
    options: &Options,
    progress: &mut dyn FnMut(usize, usize),
) -> Result<Simplified, SimplifyError> {
    check(&complex, options)?;
    let mut live = live_of(&complex)?;
    drop(complex);
    // Before the quadrics and the queue: the input's pages go back to the system.
    crate::sys::release_freed_memory();
    let stats = simplify_live(&mut live, options, progress)?;
    Ok(Simplified {
        complex: live.to_complex(),
        stats,
    })
}

/// The same on a live complex, in place (its coordinates must be finite; see [`simplify`]).
pub fn simplify_live(
    live: &mut LiveComplex,
    options: &Options,
    progress: &mut dyn FnMut(usize, usize),
) -> Result<Stats, SimplifyError> {
    if !(options.ratio > 0.0 && options.ratio <= 1.0) {
        return Err(SimplifyError::Ratio(options.ratio));
    }
    if live.coord_dim() == 0 {
        return Err(SimplifyError::NoCoordinates { file: None });
    }
    let input_tops = top_count(live);
    let regions = match &options.keep_regions {
        Some(name) => Some(Regions::of(live, name)?),
        None => None,
    };
    let mut state = State::try_new(live, options).map_err(memory)?;
    state.regions = regions;
    state.stats.input_tops = input_tops;
    state.stats.target_tops = ((options.ratio * input_tops as f64).ceil() as usize).max(1);
    init_quadrics(&mut state);
    fill_queue(&mut state).map_err(memory)?;
    contract_loop(&mut state, progress);
    state.stats.output_tops = state.tops;
    Ok(state.stats)
}

/// Checks before any work that the result can be written to `path`: its extension names a
/// format ([`crate::io::write::Format::from_path`]), that format holds a complex of `complex`'s
/// dimension and coordinates (a simplification never raises either; probed by writing one
/// simplex of that dimension to memory), and the file can be opened for writing (it is created
/// empty if missing: remove it if the work then fails).
pub fn check_output(path: &Path, complex: &Complex) -> Result<(), WriteError> {
    let err = |kind| WriteError {
        path: path.to_path_buf(),
        kind,
    };
    let format = Format::from_path(path).ok_or_else(|| err(WriteErrorKind::UnknownExtension))?;
    let d = complex.dimension() as u32;
    let mut probe = RawInput::new();
    probe.vertex_count = Some(d + 1);
    // Distinct points (formats such as STL refuse coincident vertices).
    probe.coords = complex.coords().map(|c| {
        let mut data = vec![0.0; c.dim * (d as usize + 1)];
        for i in 1..=d as usize {
            data[i * c.dim + (i - 1) % c.dim] = 1.0 + ((i - 1) / c.dim) as f64;
        }
        Coords { dim: c.dim, data }
    });
    probe.push(&(0..=d).collect::<Vec<u32>>(), 0);
    format.write(&probe).map_err(err)?;
    std::fs::OpenOptions::new()
        .append(true)
        .create(true)
        .open(path)
        .map(drop)
        .map_err(|e| err(WriteErrorKind::Io(e.to_string())))
}

/// Refuses what [`simplify`] cannot do, before any work: a ratio outside (0, 1], no or
/// non-finite coordinates, too many top simplices.
pub fn check(complex: &Complex, options: &Options) -> Result<(), SimplifyError> {
    if !(options.ratio > 0.0 && options.ratio <= 1.0) {
        return Err(SimplifyError::Ratio(options.ratio));
    }
    let file = complex.source().map(std::path::Path::to_path_buf);
    let Some(coords) = complex.coords() else {
        return Err(SimplifyError::NoCoordinates { file });
    };
    if let Some(i) = coords.data.iter().position(|x| !x.is_finite()) {
        return Err(SimplifyError::NonFinite {
            file,
            vertex: (i / coords.dim) as u32,
        });
    }
    for (dim, &count) in complex.top_counts().iter().enumerate() {
        if count > MAX_TOPS_PER_DIMENSION {
            return Err(SimplifyError::TooLarge {
                file,
                dim,
                count,
                max: MAX_TOPS_PER_DIMENSION,
            });
        }
    }
    Ok(())
}

/// Live top simplices: those of dimension ≥ 1 and the isolated vertices.
fn top_count(live: &LiveComplex) -> usize {
    live.tops().count() + live.vertices().filter(|&v| is_isolated(live, v)).count()
}

fn is_isolated(live: &LiveComplex, v: VertexId) -> bool {
    live.vertex_star(v)
        .map(|mut s| s.next().is_none())
        .unwrap_or(false)
}

/// A queue entry: cost bits (a non-negative f32's bits order as the float does), the two
/// vertices, and the sum of their versions when the cost was computed.
type Entry = Reverse<(u32, u32, u32, u32)>;

/// The simplification's working state around the live complex.
struct State<'a> {
    live: &'a mut LiveComplex,
    mode: ContractMode,
    space: QuadricSpace,
    /// `space.len()` numbers per vertex slot.
    quadrics: Vec<f64>,
    version: Vec<u32>,
    /// One entry per live edge, plus stale ones up to [`QUEUE_SLACK`] (its capacity).
    queue: BinaryHeap<Entry>,
    /// Per vertex: bumped whenever a contraction changes its neighbourhood (it is the survivor
    /// or in the survivor's ring), which may change the link condition of its edges. Empty
    /// when contractions are free (nothing is parked).
    touch: Vec<u32>,
    /// Entries refused by the link condition, with the sum of their vertices' touches then:
    /// retried once that changes ([`unpark`]).
    parked: Vec<(Entry, u32)>,
    /// Live top simplices now.
    tops: usize,
    stats: Stats,
    scratch: Scratch,
    /// With `keep_regions`: the label attribute and the live tops per label.
    regions: Option<Regions>,
}

/// `keep_regions`'s state: which label attribute, and how many live tops carry each label.
struct Regions {
    attr: usize,
    counts: rustc_hash::FxHashMap<i64, usize>,
}

impl Regions {
    fn of(live: &LiveComplex, name: &str) -> Result<Regions, SimplifyError> {
        let attr = live
            .label_attribute(name)
            .ok_or_else(|| SimplifyError::Regions {
                file: None,
                name: name.to_string(),
                why: "no integer label attribute of that name on the listed simplices".into(),
            })?;
        let mut counts = rustc_hash::FxHashMap::default();
        for (t, _) in live.tops() {
            *counts
                .entry(live.slot_label(attr, t.dim(), t.slot()))
                .or_insert(0) += 1;
        }
        Ok(Regions { attr, counts })
    }

    /// The (dimension, label) pairs of the live tops and listed faces through `v` (through both
    /// `v` and `with` when given), sorted, each once, into `out`.
    /// Read from the live complex's own arrays (no handle checks): this runs for every
    /// candidate edge that passes the link test. A vertex meets few distinct pairs, so each is
    /// added once by a scan rather than sorted out of a list of every top.
    fn labels(&self, live: &LiveComplex, v: u32, with: Option<u32>, out: &mut Vec<(usize, i64)>) {
        out.clear();
        let through = |s: &[u32]| with.is_none_or(|w| s.contains(&w));
        let mut add = |pair: (usize, i64)| {
            if !out.contains(&pair) {
                out.push(pair);
            }
        };
        let a = live.arrays();
        let at = 3 * v as usize;
        // A slot past the table (never a candidate's) reads as an empty star.
        let block = a.star_blocks.get(at..at + 3).unwrap_or(&[0, 0, 0]);
        let (start, len) = (block[0] as usize, block[1] as usize);
        for &raw in &a.star_words[start..start + len] {
            let (p, slot) = ((raw >> 28) as usize, raw & 0x0fff_ffff);
            let w = p + 1;
            if through(&a.tops[p][slot as usize * w..(slot as usize + 1) * w]) {
                add((p, live.slot_label(self.attr, p, slot)));
            }
        }
        for (s, label) in live.record_labels_at(self.attr, v) {
            if through(s) {
                add((s.len() - 1, label));
            }
        }
        out.sort_unstable();
    }

    /// Whether `gone` may move onto `keep` without touching a region interface, and if so
    /// whether the survivor must stay where `keep` is (it is on more interfaces than `gone`).
    /// `gone` must lie on at most two regions' closure (an interface, not a corner where three
    /// or more meet), the edge must carry exactly `gone`'s labels (so an interface vertex moves
    /// only along its interface), and no label may lose its last tops with the edge.
    fn allow(
        &self,
        live: &LiveComplex,
        keep: u32,
        gone: u32,
        scratch: &mut [Vec<(usize, i64)>; 2],
    ) -> Option<bool> {
        let [at_gone, on_edge] = scratch;
        self.labels(live, gone, None, at_gone);
        if at_gone.len() > 2 {
            return None;
        }
        self.labels(live, gone, Some(keep), on_edge);
        if on_edge != at_gone {
            return None;
        }
        // Tops through the edge, per label: they go with it (a conservative bound).
        let star = live.vertex_star(VertexId(gone)).ok()?;
        let mut through: Vec<i64> = star
            .filter(|&t| live.top_vertices(t).is_ok_and(|s| s.contains(&keep)))
            .map(|t| live.slot_label(self.attr, t.dim(), t.slot()))
            .collect();
        through.sort_unstable();
        for run in through.chunk_by(|x, y| x == y) {
            if self.counts.get(&run[0]).copied().unwrap_or(0) <= run.len() {
                return None;
            }
        }
        self.labels(live, keep, None, on_edge);
        Some(on_edge != at_gone)
    }

    /// After a contraction: the retired tops' labels out, the created ones' in.
    fn update(&mut self, live: &LiveComplex, undo: &crate::live::UndoRecord) {
        for (p, slot) in undo.removed_slots() {
            if let Some(c) = self.counts.get_mut(&live.slot_label(self.attr, p, slot)) {
                *c -= 1;
            }
        }
        for (p, slot) in undo.inserted_slots() {
            *self
                .counts
                .entry(live.slot_label(self.attr, p, slot))
                .or_insert(0) += 1;
        }
    }
}

/// Buffers reused by every cost evaluation and quadric construction.
#[derive(Default)]
struct Scratch {
    q: Vec<f64>,
    x: Vec<f64>,
    solve: Vec<f64>,
    points: Vec<f64>,
    basis: Vec<f64>,
    mark: Vec<u32>,
    mark_stamp: u32,
    ring: Vec<u32>,
    /// Region labels of a vertex and of an edge (`keep_regions`).
    labels: [Vec<(usize, i64)>; 2],
}

impl<'a> State<'a> {
    /// The run's vertex-sized arrays, allocated fallibly (an error, not an abort, when they
    /// cannot be had).
    fn try_new(live: &'a mut LiveComplex, options: &Options) -> Result<State<'a>, BuildError> {
        let n = live.coord_dim();
        let space = QuadricSpace::new(n);
        let slots = live.vertex_slots() as usize;
        let tops = top_count(live);
        let quadrics = try_vec(K, 0.0, slots.saturating_mul(space.len()), "quadrics")?;
        let version = try_vec(K, 0, slots, "vertex versions")?;
        // Only link-checked runs park refused edges.
        let stamps = if options.preserve_topology { slots } else { 0 };
        let touch = try_vec(K, 0, stamps, "touch stamps")?;
        let mark = try_vec(K, 0, slots, "ring marks")?;
        Ok(State {
            mode: if options.preserve_topology {
                ContractMode::PreserveManifold
            } else {
                ContractMode::Free
            },
            space,
            quadrics,
            version,
            queue: BinaryHeap::new(),
            touch,
            parked: Vec::new(),
            tops,
            stats: Stats::default(),
            regions: None,
            scratch: Scratch {
                q: vec![0.0; space.len()],
                x: vec![0.0; n],
                mark,
                ..Default::default()
            },
            live,
        })
    }

    fn quadric(&self, v: u32) -> &[f64] {
        let m = self.space.len();
        &self.quadrics[v as usize * m..(v as usize + 1) * m]
    }

    fn point(&self, v: u32) -> &[f64] {
        self.live.coords(VertexId(v)).unwrap_or(&[])
    }

    /// The cost of contracting {a, b} and, in `scratch.x`, where the survivor goes.
    fn cost(&mut self, a: u32, b: u32) -> f64 {
        let m = self.space.len();
        let mut q = std::mem::take(&mut self.scratch.q);
        let mut x = std::mem::take(&mut self.scratch.x);
        let mut solve = std::mem::take(&mut self.scratch.solve);
        sum_into(self.quadric(a), self.quadric(b), &mut q[..m]);
        let (pa, pb) = (self.point(a), self.point(b));
        let ok = self.space.minimiser(&q, &mut x, &mut solve) && near_segment(&x, pa, pb);
        if !ok {
            self.space.segment_minimiser(&q, pa, pb, &mut x);
        }
        let c = self.space.eval(&q, &x);
        self.scratch = Scratch {
            q,
            x,
            solve,
            ..std::mem::take(&mut self.scratch)
        };
        c
    }

    /// Queues {a, b} with its cost, first dropping the stale entries if the queue is full (so
    /// its allocation never grows by doubling).
    fn push(&mut self, a: u32, b: u32) {
        let e = self.entry(a, b);
        if self.queue.len() == self.queue.capacity() {
            drop_stale(self);
        }
        self.queue.push(e);
    }

    fn entry(&mut self, a: u32, b: u32) -> Entry {
        let c = self.cost(a, b) as f32;
        let bits = if c.is_finite() {
            c.max(0.0).to_bits()
        } else {
            f32::MAX.to_bits()
        };
        let stamp = self.version[a as usize].wrapping_add(self.version[b as usize]);
        Reverse((bits, a, b, stamp))
    }

    fn touched(&self, a: u32, b: u32) -> u32 {
        self.touch[a as usize].wrapping_add(self.touch[b as usize])
    }

    fn is_current(&self, a: u32, b: u32, stamp: u32) -> bool {
        self.live.is_live(VertexId(a))
            && self.live.is_live(VertexId(b))
            && self.version[a as usize].wrapping_add(self.version[b as usize]) == stamp
    }

    /// The other vertices of the top simplices around `v`, each once, into `scratch.ring`.
    fn ring(&mut self, v: u32) {
        let s = &mut self.scratch;
        s.mark_stamp = s.mark_stamp.wrapping_add(1);
        if s.mark_stamp == 0 {
            s.mark.fill(0);
            s.mark_stamp = 1;
        }
        s.ring.clear();
        let Ok(star) = self.live.vertex_star(VertexId(v)) else {
            return;
        };
        for t in star {
            for &u in self.live.top_vertices(t).unwrap_or(&[]) {
                if u != v && s.mark[u as usize] != s.mark_stamp {
                    s.mark[u as usize] = s.mark_stamp;
                    s.ring.push(u);
                }
            }
        }
    }
}

/// Whether the minimiser x lies within 4 edge lengths of the edge's midpoint (else a nearly
/// singular system threw it far off, and the segment's best point is used).
fn near_segment(x: &[f64], a: &[f64], b: &[f64]) -> bool {
    let mut len2 = 0.0;
    let mut off2 = 0.0;
    for i in 0..x.len() {
        len2 += (a[i] - b[i]).powi(2);
        off2 += (x[i] - 0.5 * (a[i] + b[i])).powi(2);
    }
    off2 <= 16.0 * len2
}

/// Step 1: the quadric of every vertex (module doc).
fn init_quadrics(state: &mut State) {
    let n = state.space.dim();
    let m = state.space.len();
    let tops: Vec<_> = state.live.tops().map(|(t, _)| t).collect();
    let mut facet = Vec::with_capacity(16);
    for t in tops {
        let verts: Vec<u32> = state.live.top_vertices(t).unwrap_or(&[]).to_vec();
        let k = verts.len() - 1;
        gather(state, &verts, None);
        // The owner's weight: vol_k^(2/k), a squared length for every k.
        let mut basis = std::mem::take(&mut state.scratch.basis);
        let mut q = std::mem::take(&mut state.scratch.q);
        q.fill(0.0);
        let mut weight = 0.0;
        state
            .space
            .add_simplex(&mut q, &state.scratch.points, &mut basis, |vol| {
                weight = vol.powf(2.0 / k as f64);
                if k < n { weight } else { 0.0 }
            });
        for &v in &verts {
            add_into(
                &mut state.quadrics[v as usize * m..(v as usize + 1) * m],
                &q,
            );
        }
        // Boundary facets: hull quadric with the owner's weight, to each facet vertex.
        for skip in 0..verts.len() {
            facet.clear();
            push_facet(&verts, skip, &mut facet);
            if weight == 0.0 || !is_boundary_facet(state.live, &facet) {
                continue;
            }
            gather(state, &facet, None);
            q.fill(0.0);
            state
                .space
                .add_simplex(&mut q, &state.scratch.points, &mut basis, |_| weight);
            for &v in &facet {
                add_into(
                    &mut state.quadrics[v as usize * m..(v as usize + 1) * m],
                    &q,
                );
            }
        }
        state.scratch.basis = basis;
        state.scratch.q = q;
    }
}

/// The coordinates of `verts` into `scratch.points`, flat.
fn gather(state: &mut State, verts: &[u32], _: Option<()>) {
    let mut pts = std::mem::take(&mut state.scratch.points);
    pts.clear();
    for &v in verts {
        pts.extend_from_slice(state.point(v));
    }
    state.scratch.points = pts;
}

fn add_into(acc: &mut [f64], q: &[f64]) {
    for (a, x) in acc.iter_mut().zip(q) {
        *a += x;
    }
}

/// Whether exactly one live top simplex holds `facet` (the one it was taken from).
fn is_boundary_facet(live: &LiveComplex, facet: &[u32]) -> bool {
    let Some(&v) = facet.iter().min_by_key(|&&v| {
        live.vertex_star(VertexId(v))
            .map(|s| s.count())
            .unwrap_or(0)
    }) else {
        return false;
    };
    let Ok(star) = live.vertex_star(VertexId(v)) else {
        return false;
    };
    star.filter(|&t| {
        live.top_vertices(t)
            .is_ok_and(|s| facet.iter().all(|u| s.contains(u)))
    })
    .nth(1)
    .is_none()
}

/// Step 2: every live edge with its cost, found as the ring of each vertex (no edge list is
/// materialised). The edges are counted first so that the queue is allocated once, at
/// [`QUEUE_SLACK`] × the edges: it never grows by doubling. Allocated fallibly.
fn fill_queue(state: &mut State) -> Result<(), BuildError> {
    let mut edges = 0;
    for_each_ring(state, |_, _, ring| edges += ring.len());
    let mut entries = try_with_capacity(K, with_slack(edges), "the edge queue")?;
    for_each_ring(state, |state, v, ring| {
        for &u in ring {
            entries.push(state.entry(v, u));
        }
    });
    state.queue = BinaryHeap::from(entries);
    Ok(())
}

/// Calls `f(state, v, ring)` for every live vertex v with its ring vertices above v.
fn for_each_ring(state: &mut State, mut f: impl FnMut(&mut State, u32, &[u32])) {
    for v in 0..state.live.vertex_slots() {
        if !state.live.is_live(VertexId(v)) {
            continue;
        }
        state.ring(v);
        let mut ring = std::mem::take(&mut state.scratch.ring);
        ring.retain(|&u| u > v);
        f(state, v, &ring);
        state.scratch.ring = ring;
    }
}

/// The queue holds its live entries and up to a quarter more (stale ones, dropped when it is
/// full): a lazy queue without the doubling of a growing vector.
const QUEUE_SLACK: (usize, usize) = (5, 4);

fn with_slack(n: usize) -> usize {
    (n * QUEUE_SLACK.0 / QUEUE_SLACK.1).max(1024)
}

/// Step 3: contract the cheapest edges until the target (module doc).
fn contract_loop(state: &mut State, progress: &mut dyn FnMut(usize, usize)) {
    let target = state.stats.target_tops;
    let total = state.tops.saturating_sub(target);
    let mut last_report = 0;
    while state.tops > target {
        let Some(entry) = state.queue.pop() else {
            // Dry: retry the refused edges whose neighbourhood changed since, if any.
            if !unpark(state) {
                break;
            }
            state.stats.refills += 1;
            continue;
        };
        let Reverse((_, a, b, stamp)) = entry;
        if !state.is_current(a, b, stamp) {
            continue;
        }
        if contract_edge(state, entry) {
            let done = total - state.tops.saturating_sub(target);
            if done - last_report >= 1024 {
                last_report = done;
                progress(done, total);
            }
        }
    }
    progress(total - state.tops.saturating_sub(target), total);
}

/// A candidate {a, b} refused by the link test: counted and parked until its neighbourhood
/// changes. Returns false (nothing contracted).
fn park(state: &mut State, entry: Entry, a: u32, b: u32) -> bool {
    state.stats.refused += 1;
    let touched = state.touched(a, b);
    state.parked.push((entry, touched));
    false
}

/// Contracts {a, b} into the vertex with the larger star, at the minimiser; false if refused
/// (then the entry is parked).
fn contract_edge(state: &mut State, entry: Entry) -> bool {
    let Reverse((_, a, b, _)) = entry;
    let star = |v: u32| {
        state
            .live
            .vertex_star(VertexId(v))
            .map(|s| s.count())
            .unwrap_or(0)
    };
    let (mut keep, mut gone) = if star(a) >= star(b) { (a, b) } else { (b, a) };
    let mut stay = false;
    if state.regions.is_some() {
        // The link test first (it is symmetric in the edge's ends and refuses most candidates,
        // while the regions' labels cost a walk of both stars): the regions are asked only
        // about edges that may contract.
        match state
            .live
            .can_contract(VertexId(keep), VertexId(gone), state.mode)
        {
            Ok(()) => {}
            Err(Refusal::LinkCondition { .. } | Refusal::NotAnEdge { .. }) => {
                return park(state, entry, a, b);
            }
            Err(e) => panic!("checking live edge {{{keep}, {gone}}}: {e}"),
        }
    }
    if let Some(regions) = &state.regions {
        let mut labels = std::mem::take(&mut state.scratch.labels);
        let way = match regions.allow(state.live, keep, gone, &mut labels) {
            Some(s) => Some((keep, gone, s)),
            None => regions
                .allow(state.live, gone, keep, &mut labels)
                .map(|s| (gone, keep, s)),
        };
        state.scratch.labels = labels;
        match way {
            Some((k, g, s)) => (keep, gone, stay) = (k, g, s),
            None => {
                state.stats.refused_regions += 1;
                return false;
            }
        }
    }
    state.cost(keep, gone);
    if stay {
        // The survivor is on more interfaces than the vertex it absorbs: it stays put.
        let at = state.point(keep).to_vec();
        state.scratch.x.clear();
        state.scratch.x.extend_from_slice(&at);
    }
    let x = std::mem::take(&mut state.scratch.x);
    let result = state
        .live
        .contract(VertexId(keep), VertexId(gone), state.mode, Some(&x));
    state.scratch.x = x;
    let undo = match result {
        Ok(undo) => undo,
        Err(Refusal::LinkCondition { .. } | Refusal::NotAnEdge { .. }) => {
            return park(state, entry, a, b);
        }
        Err(e) => panic!("contracting live edge {{{keep}, {gone}}}: {e}"),
    };
    if let Some(regions) = &mut state.regions {
        regions.update(state.live, &undo);
    }
    let removed = undo.removed_tops().count();
    let inserted = undo.inserted_tops().count();
    state.tops =
        state.tops + inserted + usize::from(is_isolated(state.live, VertexId(keep))) - removed;
    state.stats.contractions += 1;
    let m = state.space.len();
    let (k, g) = (keep as usize * m, gone as usize * m);
    for i in 0..m {
        state.quadrics[k + i] += state.quadrics[g + i];
    }
    state.version[keep as usize] = state.version[keep as usize].wrapping_add(1);
    state.version[gone as usize] = state.version[gone as usize].wrapping_add(1);
    state.ring(keep);
    let ring = std::mem::take(&mut state.scratch.ring);
    let parks = !state.touch.is_empty();
    if parks {
        state.touch[keep as usize] = state.touch[keep as usize].wrapping_add(1);
    }
    for &u in &ring {
        if parks {
            state.touch[u as usize] = state.touch[u as usize].wrapping_add(1);
        }
        state.push(keep, u);
    }
    state.scratch.ring = ring;
    true
}

/// Moves the parked entries whose vertices' neighbourhoods changed back into the queue and
/// drops the stale ones; false when none moved (no refused edge can have become legal).
fn unpark(state: &mut State) -> bool {
    let parked = std::mem::take(&mut state.parked);
    let mut moved = false;
    for (entry, touched) in parked {
        let Reverse((_, a, b, stamp)) = entry;
        if !state.is_current(a, b, stamp) {
            continue;
        }
        if state.touched(a, b) != touched {
            if state.queue.len() == state.queue.capacity() {
                drop_stale(state);
            }
            state.queue.push(entry);
            moved = true;
        } else {
            state.parked.push((entry, touched));
        }
    }
    moved
}

/// Rebuilds the queue without its stale entries, in the same allocation unless the live ones
/// alone leave less than the slack free.
fn drop_stale(state: &mut State) {
    let queue = std::mem::take(&mut state.queue);
    let mut entries = queue.into_vec();
    entries.retain(|&Reverse((_, a, b, stamp))| state.is_current(a, b, stamp));
    let want = with_slack(entries.len());
    if entries.capacity() < want {
        entries.reserve_exact(want - entries.len());
    }
    state.queue = BinaryHeap::from(entries);
}
