//! Simplified Incidence Graph (SIG) — De Floriani, Greenfieldboyce & Hui 2004.
//!
//! # What it encodes (§4.1)
//! Every simplex of the complex; for each p-simplex σ with p > 0 its boundary B_{p,p−1}(σ); and
//! for each p-simplex σ with p < d the partial co-boundaries C*_{p,g}(σ), p < g ≤ d: one
//! g-simplex for each g-cluster in the restricted star st(σ) = star(σ) − {σ}.
//!
//! ## Clusters: the definition used
//! The paper calls a g-cluster "a (g−1)-connected component whose top simplices all have
//! dimension g", two simplices being (g−1)-adjacent when they share a (g−1)-face, and the
//! component being taken inside st(σ), so the shared face must itself be in st(σ) (§4.1, Figure
//! 2(b): two triangles on edge e share only e, which is not in st(e), so they are two clusters).
//! Read literally on the whole of st(σ) this leaves simplices in no cluster at all (a dangling
//! triangle glued along an edge to a tetrahedron's face is in a 1-connected component whose top
//! simplices have dimensions 2 and 3). Algorithm 1 (BuildSIGFromIG with VisitCluster) and
//! Algorithm 6 (RetrieveCluster) settle it: they only ever walk top g-simplices, stepping from
//! one to another through a shared (g−1)-face. So this module uses:
//!
//! > The g-clusters of st(σ) are the classes of the top g-simplices of the complex that contain
//! > σ properly, under the transitive closure of "share a (g−1)-face that properly contains σ".
//!
//! For g = p + 1 the shared face would be σ itself, so each top (p+1)-simplex is its own cluster
//! (the paper's remark on C*_{p,p+1}). For g ≥ p + 2 two distinct top g-simplices containing σ
//! that share a (g−1)-face φ always have σ ⊂ φ (φ is their intersection), so the check is free.
//! Every top simplex of st(σ) is in exactly one cluster, which is what makes Coboundary complete.
//! The "arbitrarily selected" representative is fixed here as the cluster's lexicographically
//! smallest simplex, so both builds give equal structures. [`crate::oracle::Oracle::clusters`]
//! computes the same definition by brute force.
//!
//! # Layout (§4.2)
//! The p-simplices are numbered in ascending lexicographic order of their vertex ids (row
//! numbers per dimension; vertex v is row v). The paper's global numbering is `first[p] + row`:
//! simplices ordered by dimension, `first` being the lookup table of index ranges (d + 2
//! entries; the paper counts d + 1).
//! - `boundary[p]` (p ≥ 1): fixed-size, p + 1 rows of dimension p − 1 per p-simplex; entry i is
//!   the facet opposite the simplex's i-th vertex. This is the only place vertex ids live: see
//!   "Finding a simplex by its vertex ids" below.
//! - `cob[p]` (p < d): the partial co-boundaries. σ's array is the global ids of C*_{p,g}(σ) for
//!   g = d down to p + 1 (decreasing g as in the paper, ascending ids within one g). The arrays
//!   are concatenated in row order with neither the paper's heads nor its stop codes: each
//!   p-simplex has a 2-bit length code — 0, 1 or 2 entries, stored in `short`, or "long" (3 or
//!   more), stored in `long` with a u32 start per long array (CSR). The codes sit in blocks of
//!   64 simplices (two 64-bit planes) with the number of short entries and long arrays before
//!   the block, so σ's array is found in O(1) by two popcounts. When every p-simplex has the
//!   same code — on a manifold every vertex and edge of a tetrahedral mesh has one cluster —
//!   there are no blocks and array i starts at i × code.
//!
//! Ids are u32; all arrays are flat per dimension (no per-simplex allocation).
//!
//! ## Finding a simplex by its vertex ids
//! The relation API names simplices by vertex ids, which the paper does not store. They are read
//! from the boundary instead of a vertex table: the facet opposite the last vertex (entry p) is
//! the prefix (v_0..v_{p−1}), and the last vertex v_p is reached down the facets opposite vertex
//! 0 ((v_1..v_p), (v_2..v_p), ..., the vertex v_p): p reads. Lexicographic order of the
//! p-simplices is the order of (prefix row, last vertex), so σ is found one prefix at a time,
//! k = 1..p, by a search on that pair over the k-simplices, the prefix read in one access and the
//! last vertex computed only where the prefix matches. The search first tries a window of 64
//! rows around where the prefix would sit if prefixes were spread evenly (they nearly are in
//! meshes), else bisects the whole dimension. At k = d it searches only C*_{d−1,d} of the
//! prefix, which lists every d-simplex on that facet (each is a cluster of its own) in row
//! order. Reading a whole p-simplex's vertex ids (to output it) costs p(p+1)/2 boundary reads
//! instead of one copy.
//!
//! # Storage
//! `storage()`: integers and bits are what the paper's layout (§4.2) holds for this complex —
//! `Σ_{p<d} Σ_{g>p} κ^g_p + 2 Σ_{p<d} n_p + Σ_{0<p≤d} (p+1) n_p` integers (boundary entries, one
//! head per p-simplex, each array with its stop code) and `Σ_{p<d} n_p` flag bits, minus 2
//! integers per simplex taking the manifold shortcut (its one d-simplex is the head; no entry,
//! no stop code). On a closed manifold every p-simplex with p < d − 1 takes the shortcut and
//! every (d−1)-simplex has two d-simplices, which gives §7's
//! `Σ_{0<p≤d} (p+1) n_p + Σ_{0≤p<d} n_p + 3 n_{d−1}` exactly. Bytes are what is really held
//! (every array's heap capacity; [`Sig::heap_parts`] splits them):
//! `4 (Σ_{0<p≤d} (p+1) n_p + Σκ + L + 2 + d) + Σ_{p<d, not uniform} 24 ⌈n_p / 64⌉ + 8 (d + 1)`
//! (the last term: top counts), L being the number of long arrays (3+ clusters) plus one per
//! dimension. That is the paper's integers minus one head and one stop code per array,
//! plus the long offsets and 3 bits per simplex of a non-uniform dimension; no vertex table.
//! On tetrahedral meshes (docs/benchmarks.md) this is ~16 bytes per simplex, of which 11 are the
//! boundary (4 bytes per entry, (p+1) n_p entries) and ~4.7 the one entry per cluster.
//!
//! ## Where the layout differs from the paper, and why
//! - The paper's per-simplex "visited" bit is not stored (Σ n_p bits fewer): queries take
//!   `&self` and may run from many threads, so the marks live in per-query hash sets. That costs
//!   per query a few words per simplex actually visited (hash-set entries, ~8–16 bytes each with
//!   load factor) instead of one bit per simplex of the complex, plus clearing nothing afterwards
//!   (the paper must reset every bit it set).
//! - Heads, flags and stop codes are replaced by the length codes: the paper spends a head on
//!   every simplex and a stop code on every array; here an array of one or two entries (the
//!   shortcut, an interior facet's two d-simplices) costs its entries only, and the paper's
//!   shortcut is simply a length-1 array holding a d-simplex. The paper applies the flag only to
//!   p < d − 1; here a (d−1)-simplex with a single d-simplex (a boundary facet) counts as a
//!   shortcut too, since the flag bit is counted for it anyway. Closed manifolds count the same.
//! - Boundary entries are row numbers within their dimension, not global ids: the dimension is
//!   implied, and it saves an addition per step. Partial co-boundary entries are global ids,
//!   because one array mixes dimensions and the id must tell which.
//! - No vertex tables (our IG keeps (p + 1) ids per p-simplex for lookup): vertex ids are read
//!   through the boundary, as above.
//!
//! # Builds
//! - [`Sig::from_ig`]: §5, Algorithm 1 with RetrieveTopSimplexes (walk C_{p,p+1} up from σ) and
//!   VisitCluster (walk B_{r,r−1} then C_{r−1,r} among the top simplices found). VisitCluster
//!   additionally marks each (r−1)-face it has expanded: without that, k top triangles on one
//!   edge would cost k² (each rescans the edge's k co-faces).
//! - [`Sig::build`]: straight from the complex, never making an IG (no co-boundary lists).
//!   Per dimension p, the top simplices above each p-simplex come from enumerating every top
//!   simplex's p-faces (counting sort into CSR, released after that dimension; one range of top
//!   simplices per thread, `parallel::try_invert`); clusters are a union–find over
//!   those top simplices, keyed by the shared (g−1)-faces that contain σ, by ranges of
//!   p-simplices on several threads. Either way the same bytes with any thread count.
//!   After the closure and the boundaries (each facet found by binary search, as in the IG),
//!   time O(Σ_{τ top} Σ_{p<r} C(r+1, p+1) · r), r = dim τ; extra memory one dimension's
//!   top-incidence CSR (4 bytes per (face, top simplex) pair) plus per-simplex scratch.
//!
//! Both builds use the closure's vertex tables (the IG's, or `Complex::closure`) while building
//! and keep none of them, so the peak memory of a build is higher than what the SIG holds.
//!
//! # Cost of each relation
//! Locating σ from its vertex ids: O(Σ_{k≤p, k<d} (log n_k + k log m_k)) (+ O(d log c) at d),
//! m_k the number of k-simplices sharing σ's (k−1)-prefix, c the number of d-simplices on its
//! facet (searches, as above); a vertex table would cost O(p log n_p) comparisons of p + 1 ids. Every simplex output, and every top simplex a
//! co-boundary walk expands, has its vertex ids read in p(p+1)/2 boundary reads (r(r+1)/2 for
//! an r-simplex); p ≤ d, so each bound below only grows by a factor of the dimension.
//! Faces are reached through B_{r,r−1} along one canonical path each (drop vertices from the
//! highest position down), so no face is reached twice and Boundary needs no marks.
//! - R_{p,q}, q < p (Algorithm 4): O(C(p+1, q+1) · (p − q)).
//! - R_{p,g}, g > p (Algorithms 5–6): for each entry of C*_{p,r}(σ), r ≥ g, RetrieveCluster
//!   walks the top r-simplices of that cluster, expanding each (r−1)-face that contains σ once
//!   (its C*_{r−1,r} array); then the g-faces containing σ of each top simplex found.
//!   O(Σ_{g≤r≤d} λ_r(σ) · c(p, g, r)), λ_r(σ) being the number of top r-simplices containing σ
//!   and c a constant of the dimensions only — linear in the top simplices at σ, as §6 proves.
//!   (Algorithm 6 re-expands a shared face for every simplex on it, which is quadratic for a fan
//!   of k simplices on one face; the per-query "expanded" set removes that.)
//! - R_{p,p}, p > 0 (Algorithm 7): Coboundary(p) at each facet of σ, minus σ; two p-simplices
//!   share at most one facet, so results of different facets never repeat.
//! - R_{0,0}: the other end of every edge in Coboundary(1) of the vertex.
//!
//! The "σ ∈ Boundary(G, p, θ)" tests of Algorithms 5–6 are answered from vertex ids (the
//! r-simplex's ids read through the boundary, merged with σ's sorted ids): the same answer as
//! walking B, cheaper by a constant factor.

use crate::mapped::Arr;
use rustc_hash::{FxHashMap, FxHashSet};

use super::common::{too_large, try_closure_links};
use super::ig::IncidenceGraph;
use super::nav::{Fast, NavBase, NavIndex, Visit};
use super::{BuildError, to_u32};
use crate::complex::table::partition_point;
use crate::complex::{Complex, SimplexTable};
use crate::relation::handle::SimplexHandle;
use crate::relation::{QueryError, Storage, StructureKind, Topology};

const KIND: StructureKind = StructureKind::Sig;

/// Global ids are below this (see [`lookup_table`]): one value kept free, as the paper's stop
/// code needed it, so that ids fit in u32 with room for a sentinel.
const MAX_IDS: u32 = u32::MAX;

/// Length code of a partial co-boundary array: 0, 1 or 2 = that many entries in `short`;
/// `LONG` = three or more, in `long`.
const LONG: u8 = 3;

/// Simplices per [`Block`].
const BLOCK: usize = 64;

/// The Simplified Incidence Graph (see the module documentation for what it stores and costs).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Sig {
    /// Global id of the first p-simplex; `first[d + 1]` = total. The paper's lookup table.
    first: Vec<u32>,
    /// B_{p,p−1}: p + 1 rows of dimension p − 1 per p-simplex, entry i opposite vertex i.
    boundary: Vec<Arr<u32>>,
    /// The partial co-boundaries of the p-simplices, p < d.
    cob: Vec<Cob>,
    top_counts: Vec<usize>,
    /// Handle bookkeeping: windings, top simplices below d, lazy tables ([`super::nav`]).
    pub(crate) nav: NavIndex,
}

/// The partial co-boundary arrays of one dimension, concatenated without heads or stop codes:
/// a 2-bit length code per simplex says where its array is.
#[derive(Debug, Clone, PartialEq, Eq)]
pub(crate) struct Cob {
    /// The code every simplex of the dimension has, when they all have the same (then `blocks`
    /// is empty and array i starts at i × code in `short`, or is long array i).
    uniform: Option<u8>,
    blocks: Arr<Block>,
    /// The arrays of 1 or 2 entries, in simplex order.
    short: Arr<u32>,
    /// Start of each long array in `long`, plus the end: one entry per long simplex + 1.
    long_start: Arr<u32>,
    long: Arr<u32>,
}

/// Codes of 64 consecutive simplices as two bit planes, and the short entries and long arrays
/// of the simplices before the block: array i is found by two popcounts.
/// `repr(C)` and `Pod` (no padding: two u64 then two u32) so a saved file's blocks are viewed
/// in place.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, bytemuck::Pod, bytemuck::Zeroable)]
#[repr(C)]
pub(crate) struct Block {
    lo: u64,
    hi: u64,
    short_before: u32,
    long_before: u32,
}

impl Cob {
    /// The array of simplex `i`: O(1).
    fn get(&self, i: usize) -> &[u32] {
        let (code, short_at, long_at) = match self.uniform {
            Some(c) => (c, i * (c as usize % 3), i),
            None => {
                let b = &self.blocks[i / BLOCK];
                let k = i % BLOCK;
                let below = (1u64 << k) - 1;
                let (lo, hi) = (b.lo & below, b.hi & below);
                let code = ((b.lo >> k & 1) | (b.hi >> k & 1) << 1) as u8;
                let short = (lo & !hi).count_ones() + 2 * (hi & !lo).count_ones();
                let long = (lo & hi).count_ones();
                (
                    code,
                    (b.short_before + short) as usize,
                    (b.long_before + long) as usize,
                )
            }
        };
        if code == LONG {
            &self.long[self.long_start[long_at] as usize..self.long_start[long_at + 1] as usize]
        } else {
            &self.short[short_at..short_at + code as usize]
        }
    }

    fn heap_parts(&self) -> [usize; 4] {
        [
            self.blocks.capacity() * std::mem::size_of::<Block>(),
            self.short.capacity() * 4,
            self.long_start.capacity() * 4,
            self.long.capacity() * 4,
        ]
    }
}

/// Appends partial co-boundary arrays for the p-simplices in order.
struct CobWriter {
    codes: Vec<u8>,
    short: Vec<u32>,
    long_start: Vec<u32>,
    long: Vec<u32>,
    tops: usize,
}

impl CobWriter {
    fn new(n: usize) -> Self {
        CobWriter {
            codes: Vec::with_capacity(n),
            short: Vec::new(),
            long_start: vec![0],
            long: Vec::new(),
            tops: 0,
        }
    }

    /// `reps`: one global id per cluster, any order; reordered to decreasing dimension, then
    /// ascending id.
    fn push(&mut self, reps: &mut [u32], first: &[u32]) {
        if reps.is_empty() {
            self.tops += 1;
        }
        reps.sort_unstable_by_key(|&e| (std::cmp::Reverse(dim_of(first, e)), e));
        if reps.len() < LONG as usize {
            self.codes.push(reps.len() as u8);
            self.short.extend_from_slice(reps);
        } else {
            self.codes.push(LONG);
            self.long.extend_from_slice(reps);
            self.long_start.push(self.long.len() as u32);
        }
    }

    /// Appends the arrays `part` wrote for the simplices that follow this writer's.
    fn append(&mut self, part: CobWriter) {
        let base = self.long.len() as u32;
        self.codes.extend_from_slice(&part.codes);
        self.short.extend_from_slice(&part.short);
        self.long.extend_from_slice(&part.long);
        self.long_start
            .extend(part.long_start[1..].iter().map(|&x| x + base));
        self.tops += part.tops;
    }

    fn finish(self) -> Result<(Cob, usize), BuildError> {
        for (len, what) in [
            (
                self.short.len(),
                "short partial co-boundary entries of one dimension",
            ),
            (
                self.long.len(),
                "long partial co-boundary entries of one dimension",
            ),
        ] {
            to_u32(KIND, len, what)?;
        }
        let uniform = match self.codes.first() {
            Some(&c) if self.codes.iter().all(|&x| x == c) => Some(c),
            None => Some(0),
            _ => None,
        };
        let mut blocks = Vec::new();
        if uniform.is_none() {
            let (mut short, mut long) = (0u32, 0u32);
            blocks.reserve_exact(self.codes.len().div_ceil(BLOCK));
            for chunk in self.codes.chunks(BLOCK) {
                let mut b = Block {
                    short_before: short,
                    long_before: long,
                    ..Block::default()
                };
                for (k, &c) in chunk.iter().enumerate() {
                    b.lo |= u64::from(c & 1) << k;
                    b.hi |= u64::from(c >> 1) << k;
                    if c == LONG {
                        long += 1;
                    } else {
                        short += u32::from(c);
                    }
                }
                blocks.push(b);
            }
        }
        let shrink = |mut v: Vec<u32>| {
            v.shrink_to_fit();
            v
        };
        Ok((
            Cob {
                uniform,
                blocks: blocks.into(),
                short: shrink(self.short).into(),
                long_start: shrink(self.long_start).into(),
                long: shrink(self.long).into(),
            },
            self.tops,
        ))
    }
}

fn dim_of(first: &[u32], gid: u32) -> usize {
    first.partition_point(|&f| f <= gid) - 1
}

/// Positions of `tau`'s vertices that are not in `sigma` (both ascending, σ ⊆ τ), as a bit mask.
fn outside(tau: &[u32], sigma: &[u32]) -> u32 {
    let mut mask = 0u32;
    let mut j = 0;
    for (i, &v) in tau.iter().enumerate() {
        if j < sigma.len() && sigma[j] == v {
            j += 1;
        } else {
            mask |= 1 << i;
        }
    }
    mask
}

/// The faces of r-simplex `id` obtained by dropping `drops` of the positions in `allowed`,
/// through `boundary`, each reached once: positions are dropped from the highest down, so a
/// position not yet dropped keeps its index in every face on the way.
fn walk_faces<B: std::ops::Deref<Target = [u32]>>(
    boundary: &[B],
    r: usize,
    id: u32,
    below: usize,
    drops: usize,
    allowed: u32,
    f: &mut impl FnMut(u32),
) {
    if drops == 0 {
        f(id);
        return;
    }
    for i in (0..below).rev() {
        if allowed >> i & 1 == 0 {
            continue;
        }
        // Not enough droppable positions left below i: no face down this branch.
        if ((allowed & ((1u32 << i) - 1)).count_ones() as usize) < drops - 1 {
            break;
        }
        let facet = boundary[r][id as usize * (r + 1) + i];
        walk_faces(boundary, r - 1, facet, i, drops - 1, allowed, f);
    }
}

fn lookup_table(counts: impl Iterator<Item = usize>) -> Result<Vec<u32>, BuildError> {
    let mut first = vec![0u32];
    let mut total = 0usize;
    for n in counts {
        total += n;
        // u32::MAX stays free, as in the paper's layout where it is the stop code.
        if total >= MAX_IDS as usize {
            return Err(BuildError::TooLarge {
                kind: KIND,
                what: format!("{total} simplices exceed 32-bit global ids"),
            });
        }
        first.push(total as u32);
    }
    first.shrink_to_fit();
    Ok(first)
}

/// Union–find root with path halving.
fn root(parent: &mut [u32], mut i: u32) -> u32 {
    while parent[i as usize] != i {
        parent[i as usize] = parent[parent[i as usize] as usize];
        i = parent[i as usize];
    }
    i
}

/// Row of each top r-simplex in the closure's r-simplices: both tables are sorted, so one
/// merge walk per dimension.
fn top_rows(complex: &Complex, tables: &[SimplexTable]) -> Vec<Vec<u32>> {
    let mut top_rows: Vec<Vec<u32>> = vec![Vec::new(); tables.len()];
    for (r, rows) in top_rows.iter_mut().enumerate() {
        let all = &tables[r];
        let mut i = 0usize;
        for t in complex.tops(r).iter() {
            while all.get(i) < t {
                i += 1;
            }
            rows.push(i as u32);
        }
    }
    top_rows
}

/// What the steps of [`Sig::build`] share: the closure, the lookup table and the boundaries.
struct BuildSteps<'a> {
    tables: &'a [SimplexTable],
    first: &'a [u32],
    boundary: &'a [Vec<u32>],
}

/// The p-faces of the top simplices of dimension above p, sources in global id order, for
/// [`BuildSteps::tops_above`].
struct TopFaces<'a> {
    steps: &'a BuildSteps<'a>,
    p: usize,
    top_rows: &'a [Vec<u32>],
    at: &'a [usize],
}

impl crate::parallel::Incidences for TopFaces<'_> {
    fn visit(&self, range: std::ops::Range<usize>, f: &mut impl FnMut(u32, u32)) {
        let (p, s) = (self.p, self.steps);
        let mut k = self.at.partition_point(|&a| a <= range.start) - 1;
        for i in range {
            while i >= self.at[k + 1] {
                k += 1;
            }
            let r = p + 1 + k;
            let t = self.top_rows[r][i - self.at[k]];
            let g = s.first[r] + t;
            walk_faces(s.boundary, r, t, r + 1, r - p, u32::MAX, &mut |face| {
                f(g, face)
            });
        }
    }
}

impl BuildSteps<'_> {
    /// CSR of the top simplices (global ids, ascending) above each p-simplex: offsets, entries;
    /// an inversion of the tops' p-faces (`parallel::try_invert`, on several threads
    /// for many tops). `TooLarge` when the arrays cannot be had.
    fn tops_above(
        &self,
        p: usize,
        top_rows: &[Vec<u32>],
    ) -> Result<(Vec<u32>, Vec<u32>), BuildError> {
        // Tops of dimension p + 1.. in global id order; `at[k]` is where dimension p + 1 + k's
        // start.
        let mut at = vec![0usize];
        for rows in &top_rows[p + 1..] {
            at.push(at.last().unwrap() + rows.len());
        }
        let faces = TopFaces {
            steps: self,
            p,
            top_rows,
            at: &at,
        };
        crate::parallel::try_invert(self.tables[p].len(), *at.last().unwrap(), &faces)
            .map_err(|bytes| too_large(KIND, bytes, "the tops above each simplex"))
    }

    /// The partial co-boundaries of the p-simplices in `range`: per simplex, the (p+1)-simplices
    /// above it, and for each higher dimension one representative (the smallest) per cluster of
    /// its top simplices joined through faces outside σ.
    fn clusters(
        &self,
        p: usize,
        range: std::ops::Range<usize>,
        off: &[u32],
        above: &[u32],
    ) -> CobWriter {
        let first = self.first;
        let mut w = CobWriter::new(range.len());
        let mut parent: Vec<u32> = Vec::new();
        let mut by_face: FxHashMap<u32, u32> = FxHashMap::default();
        let mut reps = Vec::new();
        for s in range {
            let sigma = self.tables[p].get(s);
            let list = &above[off[s] as usize..off[s + 1] as usize];
            reps.clear();
            // Group by dimension (ascending ids are grouped by dimension already).
            let mut a = 0;
            while a < list.len() {
                let r = dim_of(first, list[a]);
                let b = a + list[a..].partition_point(|&g| g < first[r + 1]);
                let group = &list[a..b];
                if r == p + 1 {
                    reps.extend_from_slice(group);
                } else {
                    self.cluster_roots(r, sigma, group, (&mut parent, &mut by_face));
                    reps.extend(
                        (0..group.len() as u32).filter_map(|k| {
                            (root(&mut parent, k) == k).then_some(group[k as usize])
                        }),
                    );
                }
                a = b;
            }
            w.push(&mut reps, first);
        }
        w
    }

    /// Union–find over `group` (top r-simplices above σ, global ids ascending): two are joined
    /// when they share a facet outside σ; the smaller index stays root, so each cluster's root
    /// is its smallest simplex.
    fn cluster_roots(
        &self,
        r: usize,
        sigma: &[u32],
        group: &[u32],
        (parent, by_face): (&mut Vec<u32>, &mut FxHashMap<u32, u32>),
    ) {
        parent.clear();
        parent.extend(0..group.len() as u32);
        by_face.clear();
        for (k, &g) in group.iter().enumerate() {
            let t = g - self.first[r];
            let mask = outside(self.tables[r].get(t as usize), sigma);
            for i in 0..=r {
                if mask >> i & 1 == 0 {
                    continue;
                }
                let face = self.boundary[r][t as usize * (r + 1) + i];
                match by_face.get(&face) {
                    None => {
                        by_face.insert(face, k as u32);
                    }
                    Some(&other) => {
                        let (x, y) = (root(parent, other), root(parent, k as u32));
                        let (lo, hi) = (x.min(y), x.max(y));
                        parent[hi as usize] = lo;
                    }
                }
            }
        }
    }
}

impl Sig {
    /// §5, Algorithm 1: boundaries copied from the IG; for each simplex, its top simplices by
    /// RetrieveTopSimplexes, grouped into clusters by VisitCluster.
    pub fn from_ig(ig: &IncidenceGraph) -> Result<Sig, BuildError> {
        let d = ig.dimension();
        let tables: Vec<&SimplexTable> = (0..=d).map(|p| ig.table(p)).collect();
        let first = lookup_table(tables.iter().map(|t| t.len()))?;
        let mut boundary = vec![Vec::new(); d + 1];
        for (p, b) in boundary.iter_mut().enumerate().skip(1) {
            *b = (0..tables[p].len() as u32)
                .flat_map(|i| ig.boundary_ids(p, i).iter().copied())
                .collect();
        }
        let gid = |p: usize, i: u32| first[p] + i;
        let local = |g: u32| {
            let p = dim_of(&first, g);
            (p, g - first[p])
        };
        let mut cob = Vec::with_capacity(d);
        let mut top_counts = vec![0; d + 1];
        top_counts[d] = tables[d].len();
        let mut seen = FxHashSet::default();
        let mut tops: Vec<u32> = Vec::new();
        let mut in_s = FxHashSet::default();
        let mut visited = FxHashSet::default();
        let mut expanded = FxHashSet::default();
        let mut stack = Vec::new();
        let mut reps = Vec::new();
        for p in 0..d {
            let mut w = CobWriter::new(tables[p].len());
            for s in 0..tables[p].len() as u32 {
                // RetrieveTopSimplexes(I, σ).
                seen.clear();
                tops.clear();
                stack.clear();
                stack.push(gid(p, s));
                seen.insert(gid(p, s));
                while let Some(g) = stack.pop() {
                    let (l, i) = local(g);
                    let cob = ig.coboundary_ids(l, i);
                    if cob.is_empty() {
                        tops.push(g);
                    }
                    for &c in cob {
                        if seen.insert(gid(l + 1, c)) {
                            stack.push(gid(l + 1, c));
                        }
                    }
                }
                // Ascending order: the first unvisited simplex of a cluster is its smallest.
                tops.sort_unstable();
                in_s.clear();
                in_s.extend(tops.iter().copied());
                visited.clear();
                expanded.clear();
                reps.clear();
                for &t in &tops {
                    if t == gid(p, s) || visited.contains(&t) {
                        continue;
                    }
                    let (r, _) = local(t);
                    reps.push(t);
                    visited.insert(t);
                    if r == p + 1 {
                        continue;
                    }
                    // VisitCluster(S, σ').
                    stack.clear();
                    stack.push(t);
                    while let Some(m) = stack.pop() {
                        let (_, mi) = local(m);
                        for &f in ig.boundary_ids(r, mi) {
                            if !expanded.insert(gid(r - 1, f)) {
                                continue;
                            }
                            for &c in ig.coboundary_ids(r - 1, f) {
                                let c = gid(r, c);
                                if in_s.contains(&c) && visited.insert(c) {
                                    stack.push(c);
                                }
                            }
                        }
                    }
                }
                w.push(&mut reps, &first);
            }
            let (c, t) = w.finish()?;
            cob.push(c);
            top_counts[p] = t;
        }
        Ok(Sig {
            nav: ig.nav.without_caches(),
            first,
            boundary: boundary.into_iter().map(Arr::from).collect(),
            cob,
            top_counts,
        })
    }

    /// Builds straight from the complex (never an IG): closure, boundaries, then per dimension p
    /// the top simplices above each p-simplex and their clusters by union–find. The boundaries
    /// and the clusters are computed on [`crate::parallel::threads`] threads, in ranges of
    /// simplices whose results are concatenated in order (the same bytes with any count).
    pub fn build(complex: &Complex) -> Result<Sig, BuildError> {
        let (tables, boundary) = try_closure_links(KIND, complex)?;
        let d = tables.len() - 1;
        let first = lookup_table(tables.iter().map(SimplexTable::len))?;
        let top_rows = top_rows(complex, &tables);
        let mut cob = Vec::with_capacity(d);
        let mut top_counts = vec![0; d + 1];
        top_counts[d] = tables[d].len();
        let steps = BuildSteps {
            tables: &tables,
            first: &first,
            boundary: &boundary,
        };
        for p in 0..d {
            let (off, above) = steps.tops_above(p, &top_rows)?;
            let parts = crate::parallel::map_ranges(tables[p].len(), |range| {
                steps.clusters(p, range, &off, &above)
            });
            let mut w = CobWriter::new(0);
            for part in parts {
                w.append(part);
            }
            let (c, t) = w.finish()?;
            cob.push(c);
            top_counts[p] = t;
        }
        Ok(Sig {
            nav: NavIndex::new(KIND, complex)?,
            first,
            boundary: boundary.into_iter().map(Arr::from).collect(),
            cob,
            top_counts,
        })
    }

    /// Row of p-simplex `sigma` (ascending ids) in its dimension: the vertex, then each prefix
    /// (v_0..v_k) in turn, by `find_extension` below dimension d and `find_top`
    /// at d. O(Σ_{k≤p, k<d} (log n_k + k log m_k)) (+ O(d log c) at d), m_k the number of
    /// k-simplices sharing σ's (k−1)-prefix and c the number of d-simplices on its facet.
    pub fn find(&self, sigma: &[u32]) -> Option<u32> {
        let p = sigma.len().checked_sub(1)?;
        let d = self.dimension();
        if p > d || sigma[0] as usize >= self.count(0) {
            return None;
        }
        let mut row = sigma[0];
        for (k, &v) in sigma.iter().enumerate().skip(1) {
            row = if k == d {
                self.find_top(row, v)?
            } else {
                self.find_extension(k, row, v)?
            };
        }
        Some(row)
    }

    /// The d-simplex made of (d−1)-simplex row `prefix` and a larger vertex `v`, among the
    /// d-simplices on `prefix`: each is a cluster of its own, so C*_{d−1,d}(prefix) lists them
    /// all, by ascending id. Those having `prefix` as prefix are one run of rows, those that do
    /// not sit before or after it by their own prefix row, so one bisection finds `v`: O(d log c)
    /// for c d-simplices on the facet (O(d) on a manifold: c ≤ 2).
    fn find_top(&self, prefix: u32, v: u32) -> Option<u32> {
        use std::cmp::Ordering::{Equal, Greater, Less};
        let d = self.dimension();
        let list = self.cstar(d - 1, prefix);
        let row = |e: u32| e - self.first[d];
        let found = list.binary_search_by(|&e| {
            let r = row(e);
            match self.boundary[d][r as usize * (d + 1) + d].cmp(&prefix) {
                Equal => self.last(d, r).cmp(&v),
                o @ (Less | Greater) => o,
            }
        });
        found.ok().map(|i| row(list[i]))
    }

    /// The k-simplex made of (k−1)-simplex row `prefix` and a larger vertex `v`. Rows are in
    /// lexicographic order, which is the order of (prefix row, last vertex): the prefix column
    /// of the stored boundary is ascending, and the rows sharing `prefix` are one run ordered by
    /// last vertex. The search looks first in a window of 64 rows around where `prefix` would
    /// sit if prefixes were spread evenly over the rows (as they nearly are in meshes), else
    /// bisects the whole dimension: O(log n_k) probes either way, and the last vertex (k reads)
    /// is computed only on rows of the run.
    fn find_extension(&self, k: usize, prefix: u32, v: u32) -> Option<u32> {
        use std::cmp::Ordering::{Equal, Less};
        let b = &self.boundary[k];
        let n = b.len() / (k + 1);
        if n == 0 {
            return None;
        }
        let cmp = |i: usize| {
            b[i * (k + 1) + k]
                .cmp(&prefix)
                .then_with(|| self.last(k, i as u32).cmp(&v))
        };
        let guess = (prefix as f64 + 0.5) / self.count(k - 1) as f64 * n as f64;
        let g = (guess as usize).min(n - 1);
        // Rows before `lo` are smaller than σ, rows from `hi` on are not. If the window of
        // 2 × WINDOW rows around the guess does not bracket σ, bisect the whole dimension: its
        // first probes are the same for every query, so they stay in cache.
        const WINDOW: usize = 32;
        let (a, z) = (g.saturating_sub(WINDOW), (g + WINDOW).min(n - 1));
        let (mut lo, mut hi) = (0, n);
        if (a == 0 || cmp(a) == Less) && (z == n - 1 || cmp(z) != Less) {
            (lo, hi) = (
                if a == 0 { 0 } else { a + 1 },
                if z == n - 1 { n } else { z + 1 },
            );
        }
        let lo = partition_point(lo..hi, |mid| cmp(mid) == Less);
        (lo < n && cmp(lo) == Equal).then_some(lo as u32)
    }

    /// The largest vertex of p-simplex row `i`: down the facets opposite vertex 0 (v_1..v_p,
    /// v_2..v_p, ..., v_p). O(p).
    fn last(&self, p: usize, i: u32) -> u32 {
        let mut r = i;
        for k in (1..=p).rev() {
            r = self.boundary[k][r as usize * (k + 1)];
        }
        r
    }

    /// Appends the vertex ids of p-simplex row `i`: the last vertex of each prefix, down the
    /// facets opposite the last vertex. O(p²) boundary reads.
    fn push_tuple(&self, p: usize, i: u32, out: &mut Vec<u32>) {
        let start = out.len();
        out.resize(start + p + 1, 0);
        let mut r = i;
        for k in (1..=p).rev() {
            out[start + k] = self.last(k, r);
            r = self.boundary[k][r as usize * (k + 1) + k];
        }
        out[start] = r;
    }

    /// All partial co-boundaries of p-simplex row `i` (p < d), global ids, decreasing dimension.
    fn cstar(&self, p: usize, i: u32) -> &[u32] {
        self.cob[p].get(i as usize)
    }

    /// The paper's manifold shortcut: σ's whole partial co-boundary is one d-simplex.
    fn is_shortcut(&self, p: usize, i: u32) -> bool {
        let d = self.dimension();
        matches!(self.cstar(p, i), &[e] if e >= self.first[d])
    }

    fn dim_of(&self, g: u32) -> usize {
        dim_of(&self.first, g)
    }

    /// C*_{p,g}(σ) as rows of g + 1 vertex ids (the representative of each g-cluster), or `None`
    /// if σ is not a simplex. Empty for g ≤ p or g > d.
    pub fn partial_coboundary(&self, sigma: &[u32], g: usize) -> Option<Vec<u32>> {
        let id = self.find(sigma)?;
        let p = sigma.len() - 1;
        let mut out = Vec::new();
        if p < self.dimension() {
            for &e in self.cstar(p, id) {
                if self.dim_of(e) == g {
                    self.push_tuple(g, e - self.first[g], &mut out);
                }
            }
        }
        Some(out)
    }

    /// Whether p-simplex σ's partial co-boundary is the paper's manifold shortcut: a single
    /// d-simplex, which the paper stores in place of the head, with no array.
    pub fn uses_shortcut(&self, sigma: &[u32]) -> bool {
        let p = sigma.len() - 1;
        p < self.dimension() && self.find(sigma).is_some_and(|i| self.is_shortcut(p, i))
    }

    /// Heap bytes of each array kind, summed over dimensions (their total is
    /// `storage().bytes`): where the bytes go.
    pub fn heap_parts(&self) -> Vec<(&'static str, usize)> {
        let mut cob = [0usize; 4];
        for c in &self.cob {
            for (a, b) in cob.iter_mut().zip(c.heap_parts()) {
                *a += b;
            }
        }
        vec![
            (
                "lookup table, top counts",
                self.first.capacity() * 4 + self.top_counts.capacity() * 8,
            ),
            (
                "boundary",
                self.boundary.iter().map(|b| b.capacity() * 4).sum(),
            ),
            ("co-boundary length codes", cob[0]),
            ("co-boundary short arrays", cob[1]),
            ("co-boundary long offsets", cob[2]),
            ("co-boundary long arrays", cob[3]),
        ]
    }

    /// Algorithm 6, RetrieveCluster: the top r-simplices (rows) in the r-cluster of st(σ) holding
    /// row `start`, into `sc.cluster`.
    fn retrieve_cluster(&self, p: usize, sigma: &[u32], r: usize, start: u32, sc: &mut Scratch) {
        sc.cluster.clear();
        sc.stack.clear();
        sc.stack.push(start);
        sc.visited.insert(self.first[r] + start);
        while let Some(m) = sc.stack.pop() {
            sc.cluster.push(m);
            if r == p + 1 {
                continue;
            }
            sc.tuple.clear();
            self.push_tuple(r, m, &mut sc.tuple);
            let mask = outside(&sc.tuple, sigma);
            for i in 0..=r {
                if mask >> i & 1 == 0 {
                    continue;
                }
                let face = self.boundary[r][m as usize * (r + 1) + i];
                if !sc.expanded.insert(self.first[r - 1] + face) {
                    continue;
                }
                // C*_{r−1,r}(face): the top r-simplices on the face; the array is in decreasing
                // dimension, so they sit after any higher-dimensional entries.
                for &e in self.cstar(r - 1, face) {
                    if e >= self.first[r + 1] {
                        continue;
                    }
                    if e < self.first[r] {
                        break;
                    }
                    if sc.visited.insert(e) {
                        sc.stack.push(e - self.first[r]);
                    }
                }
            }
        }
    }

    /// Algorithm 5, Coboundary: the g-simplices (rows) of st(σ), each once, to `emit`.
    fn coboundary(
        &self,
        p: usize,
        id: u32,
        sigma: &[u32],
        g: usize,
        sc: &mut Scratch,
        emit: &mut impl FnMut(u32),
    ) {
        sc.visited.clear();
        sc.expanded.clear();
        sc.found.clear();
        for &e in self.cstar(p, id) {
            let r = self.dim_of(e);
            if r < g {
                break;
            }
            self.retrieve_cluster(p, sigma, r, e - self.first[r], sc);
            if r == g {
                // Top g-simplices: never a face of another, and clusters are disjoint.
                sc.cluster.iter().for_each(|&m| emit(m));
                continue;
            }
            let Scratch {
                cluster,
                found,
                tuple,
                ..
            } = sc;
            for &m in cluster.iter() {
                tuple.clear();
                self.push_tuple(r, m, tuple);
                let mask = outside(tuple, sigma);
                walk_faces(&self.boundary, r, m, r + 1, r - g, mask, &mut |f| {
                    if found.insert(f) {
                        emit(f)
                    }
                });
            }
        }
    }

    fn emit_row(&self, q: usize, i: u32, out: &mut Vec<u32>) {
        self.push_tuple(q, i, out);
    }
}

/// Per-query marks: the paper's visited bits, kept out of the structure.
#[derive(Default)]
struct Scratch {
    visited: FxHashSet<u32>,
    expanded: FxHashSet<u32>,
    found: FxHashSet<u32>,
    stack: Vec<u32>,
    cluster: Vec<u32>,
    /// Vertex ids of the simplex being expanded.
    tuple: Vec<u32>,
}

impl crate::structures::common::Pooled for Scratch {
    fn pool() -> &'static std::thread::LocalKey<std::cell::RefCell<Vec<Self>>> {
        thread_local! {
            static POOL: std::cell::RefCell<Vec<Scratch>> = const { std::cell::RefCell::new(Vec::new()) };
        }
        &POOL
    }
    fn reset(&mut self) {
        self.visited.clear();
        self.expanded.clear();
        self.found.clear();
        self.stack.clear();
        self.cluster.clear();
        self.tuple.clear();
    }
    fn capacity(&self) -> usize {
        self.visited.capacity() + self.found.capacity() + self.stack.capacity()
    }
}

impl Sig {
    /// R_{p,q} of the p-simplex `id` with vertex ids `sigma`, as q-simplex ids (for q = 0 the
    /// vertex ids), each once, in the order of the paper's algorithms. Marks live in this
    /// thread's pooled [`Scratch`]: no allocation once it is warm.
    fn related_ids(&self, id: u32, sigma: &[u32], q: usize, emit: &mut impl FnMut(u32)) {
        let p = sigma.len() - 1;
        if q < p {
            // Algorithm 4, each face along its one canonical path.
            walk_faces(&self.boundary, p, id, p + 1, p - q, u32::MAX, emit);
            return;
        }
        let mut sc = crate::structures::common::Scratch::<Scratch>::take();
        if q > p {
            self.coboundary(p, id, sigma, q, &mut sc, emit);
        } else if p == 0 {
            // Algorithm 7 on a vertex: the other end of each edge.
            if self.dimension() > 0 {
                let v = sigma[0];
                self.coboundary(0, id, sigma, 1, &mut sc, &mut |e| {
                    // Entry 1 is the facet opposite vertex 1, i.e. vertex 0.
                    let edge = &self.boundary[1][e as usize * 2..e as usize * 2 + 2];
                    emit(if edge[1] == v { edge[0] } else { edge[1] });
                });
            }
        } else {
            // Algorithm 7: Coboundary(p) at each facet, minus σ.
            let mut facet = [0u32; crate::complex::MAX_DIMENSION + 1];
            for k in 0..=p {
                let mut j = 0;
                for (i, &v) in sigma.iter().enumerate() {
                    if i != k {
                        facet[j] = v;
                        j += 1;
                    }
                }
                let f = self.boundary[p][id as usize * (p + 1) + k];
                self.coboundary(p - 1, f, &facet[..p], p, &mut sc, &mut |t| {
                    if t != id {
                        emit(t)
                    }
                });
            }
        }
    }
}

impl NavBase for Sig {
    fn nav(&self) -> &NavIndex {
        &self.nav
    }

    // Ids of one dimension are lexicographic ranks: every answer is a dense handle as is.
    fn fast_visit(&self, h: SimplexHandle, sigma: &[u32], q: usize, visit: Visit<'_>) -> Fast {
        self.related_ids(h.index(), sigma, q, &mut |f| {
            visit(SimplexHandle::dense(q, f))
        });
        Some(Ok(()))
    }
}

impl Topology for Sig {
    crate::relation::topology_preamble! {
        self, KIND;
        dimension: self.first.len() - 2;
        vertex_count: self.first[1];
        count(p): match (self.first.get(p), self.first.get(p + 1)) {
            (Some(a), Some(b)) => (b - a) as usize,
            _ => 0,
        };
        top_count(p): self.top_counts.get(p).copied().unwrap_or(0);
    }

    fn simplices(&self, p: usize, out: &mut Vec<u32>) {
        let n = self.count(p);
        out.reserve(n * (p + 1));
        for i in 0..n as u32 {
            self.push_tuple(p, i, out);
        }
    }

    fn contains(&self, sigma: &[u32]) -> bool {
        self.find(sigma).is_some()
    }

    fn query(&self, sigma: &[u32], q: usize, out: &mut Vec<u32>) -> Result<(), QueryError> {
        let id = self.find(sigma).ok_or_else(|| QueryError::NotInComplex {
            simplex: sigma.to_vec(),
        })?;
        self.related_ids(id, sigma, q, &mut |f| self.emit_row(q, f, out));
        Ok(())
    }

    fn storage(&self) -> Storage {
        let d = self.dimension();
        let boundary: usize = self.boundary.iter().map(|b| b.len()).sum();
        // The paper's layout: a head per p-simplex (p < d) and, unless it takes the shortcut,
        // an array of its entries and a stop code.
        let mut cob = 0usize;
        for p in 0..d {
            for i in 0..self.count(p) as u32 {
                cob += 1;
                if !self.is_shortcut(p, i) {
                    cob += self.cstar(p, i).len() + 1;
                }
            }
        }
        let flags: usize = (0..d).map(|p| self.count(p)).sum();
        Storage {
            integers: (boundary + cob) as u64,
            bits: flags as u64,
            bytes: self.heap_parts().iter().map(|&(_, b)| b).sum::<usize>() as u64,
        }
    }

    fn validate(&self) -> Result<(), String> {
        let d = self.check_lookup()?;
        self.check_boundaries(d)?;
        for p in 0..d {
            self.check_codes(p)?;
        }
        let is_top = self.check_cstars(d)?;
        let above = self.count_tops_above(d, &is_top)?;
        self.check_clusters(d, &is_top, &above)
    }
}

/// The steps of [`Sig::validate`].
impl Sig {
    /// The lookup table and the per-dimension array counts; returns the dimension d.
    fn check_lookup(&self) -> Result<usize, String> {
        let d = match self.first.len().checked_sub(2) {
            Some(d) if self.first[0] == 0 => d,
            _ => return Err("lookup table has the wrong length".into()),
        };
        if self.first.windows(2).any(|w| w[0] > w[1]) {
            return Err("lookup table is not ascending".into());
        }
        if self.count(d) == 0 {
            return Err(format!("no {d}-simplex in a {d}-complex"));
        }
        if self.boundary.len() != d + 1 || self.cob.len() != d || self.top_counts.len() != d + 1 {
            return Err("one boundary per dimension, one co-boundary per dimension below d".into());
        }
        Ok(d)
    }

    /// Each boundary array: sized, in range, rows strictly ascending, entries the facets.
    fn check_boundaries(&self, d: usize) -> Result<(), String> {
        let mut s = Vec::new();
        let mut facet = Vec::new();
        let mut prev = Vec::new();
        for p in 1..=d {
            let b = &self.boundary[p];
            if b.len() != self.count(p) * (p + 1) {
                return Err(format!("B_{{{p},{}}} has the wrong size", p - 1));
            }
            if let Some(i) = b.iter().position(|&f| f as usize >= self.count(p - 1)) {
                return Err(format!("B_{{{p},{}}} entry {i} is out of range", p - 1));
            }
            // Rows below are checked, entries are in range: tuples can be read. Each row is its
            // prefix row plus a larger vertex, rows strictly ascending, entries the facets.
            prev.clear();
            for i in 0..self.count(p) as u32 {
                s.clear();
                self.push_tuple(p, i, &mut s);
                if s[p] <= s[p - 1] {
                    return Err(format!("{p}-simplex {i} reads as {s:?}, not ascending"));
                }
                if i > 0 && prev >= s {
                    return Err(format!("{p}-simplices not strictly ascending at {s:?}"));
                }
                for k in 0..=p {
                    facet.clear();
                    self.push_tuple(p - 1, b[i as usize * (p + 1) + k], &mut facet);
                    let want = s
                        .iter()
                        .enumerate()
                        .filter(|&(j, _)| j != k)
                        .map(|(_, &v)| v);
                    if !facet.iter().copied().eq(want) {
                        return Err(format!(
                            "boundary entry {k} of {p}-simplex {s:?} is {facet:?}"
                        ));
                    }
                }
                std::mem::swap(&mut prev, &mut s);
            }
        }
        Ok(())
    }

    /// The co-boundary codes of dimension p: uniform or one block per `BLOCK` simplices with
    /// running counts, and short/long arrays of the sizes the codes say.
    fn check_codes(&self, p: usize) -> Result<(), String> {
        let c = &self.cob[p];
        let n = self.count(p);
        let (mut short, mut long) = (0usize, 0usize);
        let code_of = |i: usize| match c.uniform {
            Some(code) => code,
            None => {
                let b = &c.blocks[i / BLOCK];
                ((b.lo >> (i % BLOCK) & 1) | (b.hi >> (i % BLOCK) & 1) << 1) as u8
            }
        };
        match c.uniform {
            Some(code) if code > LONG || !c.blocks.is_empty() => {
                return Err(format!("dimension {p}: bad uniform code {code}"));
            }
            None if c.blocks.len() != n.div_ceil(BLOCK) => {
                return Err(format!(
                    "dimension {p}: one code block per {BLOCK} simplices"
                ));
            }
            _ => {}
        }
        for i in 0..n {
            if c.uniform.is_none() && i % BLOCK == 0 {
                let b = &c.blocks[i / BLOCK];
                if (b.short_before as usize, b.long_before as usize) != (short, long) {
                    return Err(format!("dimension {p}: block {} counts wrong", i / BLOCK));
                }
            }
            match code_of(i) {
                LONG => long += 1,
                code => short += code as usize,
            }
        }
        if let Some(b) = c.blocks.last()
            && !n.is_multiple_of(BLOCK)
            && (b.lo | b.hi) >> (n % BLOCK) != 0
        {
            return Err(format!("dimension {p}: codes past the last simplex"));
        }
        if short != c.short.len()
            || long + 1 != c.long_start.len()
            || c.long_start[0] != 0
            || c.long_start[long] as usize != c.long.len()
            || c.long_start
                .windows(2)
                .any(|w| w[1] < w[0] + u32::from(LONG))
        {
            return Err(format!(
                "dimension {p}: arrays do not match the codes (long arrays hold ≥ 3)"
            ));
        }
        Ok(())
    }

    /// Each C* array lists simplices of its star in decreasing dimension; returns which
    /// simplices are top (an empty C* below d, every d-simplex).
    // p indexes several per-dimension arrays at once.
    #[allow(clippy::needless_range_loop)]
    fn check_cstars(&self, d: usize) -> Result<Vec<Vec<bool>>, String> {
        let mut is_top: Vec<Vec<bool>> = (0..=d).map(|p| vec![false; self.count(p)]).collect();
        is_top[d].iter_mut().for_each(|t| *t = true);
        let (mut s, mut t) = (Vec::new(), Vec::new());
        for p in 0..d {
            for i in 0..self.count(p) as u32 {
                s.clear();
                self.push_tuple(p, i, &mut s);
                let list = self.cstar(p, i);
                if list.windows(2).any(|w| {
                    let (a, b) = (self.dim_of(w[0]), self.dim_of(w[1]));
                    a < b || (a == b && w[0] >= w[1])
                }) {
                    return Err(format!("array of {s:?} is not in decreasing dimension"));
                }
                if list.is_empty() {
                    is_top[p][i as usize] = true;
                }
                for &e in list {
                    let r = self.dim_of(e);
                    if r <= p || r > d {
                        return Err(format!("C* of {s:?} lists a {r}-simplex"));
                    }
                    t.clear();
                    self.push_tuple(r, e - self.first[r], &mut t);
                    if !crate::complex::is_subset(&s, &t) {
                        return Err(format!("C* of {s:?} lists {t:?}, not in its star"));
                    }
                }
            }
        }
        Ok(is_top)
    }

    /// Checks the top counts and returns, per simplex below d, the number of top simplices
    /// above it (counted through the faces of the top simplices).
    fn count_tops_above(&self, d: usize, is_top: &[Vec<bool>]) -> Result<Vec<Vec<u32>>, String> {
        let mut above: Vec<Vec<u32>> = (0..d).map(|p| vec![0; self.count(p)]).collect();
        for (r, tops) in is_top.iter().enumerate() {
            if tops.iter().filter(|&&t| t).count() != self.top_counts[r] {
                return Err(format!("top count of dimension {r} is wrong"));
            }
            for (t, _) in tops.iter().enumerate().filter(|(_, t)| **t) {
                for (p, counts) in above.iter_mut().enumerate().take(r) {
                    walk_faces(
                        &self.boundary,
                        r,
                        t as u32,
                        r + 1,
                        r - p,
                        u32::MAX,
                        &mut |f| counts[f as usize] += 1,
                    );
                }
            }
        }
        Ok(above)
    }

    /// The clusters listed at each simplex partition its top simplices, each led by its
    /// smallest.
    // p indexes several per-dimension arrays at once.
    #[allow(clippy::needless_range_loop)]
    fn check_clusters(
        &self,
        d: usize,
        is_top: &[Vec<bool>],
        above: &[Vec<u32>],
    ) -> Result<(), String> {
        let mut sc = Scratch::default();
        let mut s = Vec::new();
        for p in 0..d {
            for i in 0..self.count(p) as u32 {
                s.clear();
                self.push_tuple(p, i, &mut s);
                sc.visited.clear();
                sc.expanded.clear();
                let mut total = 0usize;
                for &e in self.cstar(p, i) {
                    let r = self.dim_of(e);
                    if sc.visited.contains(&e) {
                        return Err(format!("C* of {s:?} lists two simplices of one cluster"));
                    }
                    if !is_top[r][(e - self.first[r]) as usize] {
                        return Err(format!("C* of {s:?} lists a simplex that is not top"));
                    }
                    self.retrieve_cluster(p, &s, r, e - self.first[r], &mut sc);
                    if sc.cluster.iter().any(|&m| m + self.first[r] < e) {
                        return Err(format!(
                            "C* of {s:?}: a cluster is not led by its smallest simplex"
                        ));
                    }
                    total += sc.cluster.len();
                }
                if total != above[p][i as usize] as usize {
                    return Err(format!(
                        "clusters at {s:?} hold {total} top simplices, its star has {}",
                        above[p][i as usize]
                    ));
                }
            }
        }
        Ok(())
    }
}

crate::persist_fields!(Cob {
    uniform,
    blocks,
    short,
    long_start,
    long
});

impl crate::codec::Field for Vec<Cob> {
    fn put(&self, w: &mut crate::codec::Writer) {
        w.scalar(self.len() as u64);
        for c in self {
            crate::codec::Field::put(c, w);
        }
    }
    fn get(r: &mut crate::codec::Reader) -> Result<Self, crate::codec::StoreError> {
        let n = r.bounded(crate::complex::MAX_DIMENSION as u64 + 1, "dimensions")?;
        (0..n).map(|_| crate::codec::Field::get(r)).collect()
    }
}

crate::persist_fields!(Sig { first, boundary, cob, top_counts, nav } check |s| {
    let d = s.top_counts.len().checked_sub(1).ok_or("no dimension")?;
    if s.first.len() != d + 2 || s.boundary.len() != d + 1 || s.cob.len() != d {
        return Err(format!("tables of {} dimensions for dimension {d}", s.first.len()));
    }
    // The lookup table gives every count: it must ascend from 0 and agree with the boundary
    // rows (whose lengths the file bounds), so that no count read from it is made up.
    if s.first[0] != 0 || s.first.windows(2).any(|w| w[0] > w[1]) {
        return Err("the lookup table of first ids does not ascend from 0".into());
    }
    for p in 1..=d {
        let n = (s.first[p + 1] - s.first[p]) as usize;
        if s.boundary[p].len() != n * (p + 1) || s.top_counts[p] > n {
            return Err(format!("{p}-simplex boundary rows do not fit the lookup table"));
        }
    }
    Ok(())
});
