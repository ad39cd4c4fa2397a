//! Indexed data structure with Adjacencies (IA) [Nie97, PBCF93] and its extension with vertex
//! stars, as described in §3 of the 2005 survey — for d-dimensional pseudo-manifolds, d ≥ 0.
//!
//! # Domain
//! Regular complexes (every top simplex has the complex's dimension d; an isolated vertex or any
//! lower-dimensional top simplex disqualifies) in which every (d−1)-simplex is a face of at most
//! two d-simplices. Connectedness is not required, and vertex stars may be pinched (several
//! (d−1)-connected components). Anything else is refused with [`BuildError::Unsupported`] naming
//! the first offending simplex: first the lowest-dimensional top simplex below d (ascending
//! lexicographic within a dimension), then the lexicographically first (d−1)-simplex in three or
//! more d-simplices. d = 0 (isolated vertices only) and d = 1 (graphs whose vertices have at most
//! two edges) are accepted; at d = 0 the only shared "facet" is the empty simplex, which is not a
//! simplex of the complex, so every R_{0,0} slot is empty.
//!
//! # What it encodes
//! Only the vertices and the d-simplices; every other simplex is implicit, as a vertex subset of
//! a d-simplex.
//! - Plain IA: per d-simplex, R_{d,0} (its d + 1 vertices, ascending) and R_{d,d}: entry `i` is
//!   the d-simplex across the facet opposite the `i`-th vertex, `u32::MAX` when that facet is on
//!   the boundary.
//! - Extended IA (what [`IndexedAdjacency`] is): per vertex, one d-simplex for each
//!   (d−1)-connected component of its star (two d-simplices at v are in one component when a
//!   chain of d-simplices at v joins them, consecutive ones sharing a (d−1)-face that contains
//!   v). On initial quasi-manifolds this is the survey's R*_{0,d}, one reference per vertex; on
//!   pinched pseudo-manifolds it keeps every vertex star complete. Stored in CSR form, the
//!   references of one vertex in ascending d-simplex order.
//!
//! # Storage
//! Plain IA: `2(d+1)·n_d` integers ([`IndexedAdjacency::plain_ia_integers`]). Extended IA adds
//! one integer per component of a vertex star, `C_v = Σ_v c_v` (`= n_0` on initial
//! quasi-manifolds): `2(d+1)·n_d + C_v` integers, no bits. The CSR offsets (n + 1 integers) and
//! the per-dimension simplex counts cached at build are in the real bytes, not the paper count.
//!
//! # Cost of each relation
//! n_v is the number of d-simplices in the star of vertex v; σ is a p-simplex, v = σ's lowest
//! vertex (w its second); "dedup" is a per-query hash set.
//! - Locating σ: p = d by binary search in the sorted R_{d,0} table, O(d log n_d); p = 0 is
//!   free; 0 < p < d walks the star of v until a d-simplex containing σ, O(d·n_v).
//! - R_{p,q}, q < p: the (q+1)-subsets of σ, O(C(p+1, q+1)·(q+1)) — optimal (survey §3).
//! - R_{d,d}: read directly, O(d) — optimal.
//! - R_{0,d}: walk the star of v from its component references through R_{d,d} across facets
//!   containing v: O(d·n_v) — optimal (survey §3: the extension exists for this).
//! - R_{0,q}, 0 < q < d: the same walk, then the q-faces through v of each d-simplex, dedup:
//!   O(C(d, q)·n_v), linear in the output up to a factor depending on d only — optimal. As
//!   dense indices (handles, `related_ids`): the faces whose smallest vertex is v are the lazy
//!   table's rows starting with v (a range, no search); the others from one walk, edges
//!   deduplicated by their other vertex, (d−1)-faces given by the d-simplex of smaller id on
//!   their two sides (no dedup), each found among the lazy table's rows sharing its first vertex
//!   (see `super::nav`); the star of a vertex (every dimension) from one walk.
//! - R_{0,0}: the walk, the other vertices of each d-simplex, dedup: O(d·n_v) — optimal.
//! - R_{p,q}, 0 < p < q: walk the whole star of v and keep the d-simplices containing σ (the star
//!   of σ need not be (d−1)-connected through faces containing σ — a pinched edge — so walking
//!   only those could miss some), then their q-faces through σ, dedup: O(d·n_v + C(d−p, q−p)·s),
//!   s = d-simplices containing σ — not optimal (depends on n_v, not on the star of σ), as the
//!   survey states for the IA family.
//! - R_{p,p}, 0 < p < d: every facet of σ contains v or w, so walk the stars of v and w; each
//!   d-simplex sharing a facet f of σ gives f ∪ {x} for its vertices x ∉ σ, dedup:
//!   O(d·(n_v + n_w) + output) — not optimal.
//! - `count(p)`: cached at build (see below); `simplices(p)` enumerates the p-faces of every
//!   d-simplex and deduplicates, O(n_d·C(d+1, p+1)·log).
//!
//! Queries keep no state in the structure: every walk has its own hash set.
//!
//! # Build
//! Steps split between [`crate::parallel::threads`] threads, each writing to positions fixed
//! before the split, so any thread count gives the same bytes:
//! - R_{d,d}: each facet slot is matched in the bucket of its facet's smallest vertex v: the
//!   slots of the run of d-simplices that start with v (the table is sorted) and the slot-0
//!   facets whose d-simplex's second vertex is v (one counting sort of the d-simplices, 4 bytes
//!   each, by ranges of d-simplices on several threads); buckets sorted and matched by chunks
//!   of vertices on several threads, each chunk storing its pairs straight into R_{d,d} (a
//!   slot is in one pair: the stores never meet).
//!   O(n_d·d·(1 + log b)) for buckets of b slots.
//! - Star components: with one thread, one walk per component through R_{d,d} (1 byte a slot);
//!   with several, a shared union–find over the slots by ranges of d-simplices (4 bytes a
//!   slot), whose roots (smallest slots) are the walks' starts; then inverted by vertex on
//!   several threads. O(d²·n_d).
//! - The arrays are filled (R_{d,d}'s "none", the union–find's singletons) and the d-simplices
//!   copied on several threads too, and the handle index's listing maps and windings
//!   are found by runs of listings.
//! - `count(p)`: n_{d−1} from R_{d,d}; 0 < p < d − 1 counted at their smallest vertex from a
//!   walk of its star, by chunks of vertices on several threads. O(Σ_v n_v·C(d, p)·log).

use super::nav::{Fast, NavBase, NavIndex, Visit};
use crate::mapped::Arr;
use rustc_hash::FxHashSet;
use std::sync::atomic::Ordering;

use super::common::{
    PairParts, Scratch, check_star_refs, too_large, try_push, try_table, try_vec, walk_tops,
};
use super::{BuildError, to_u32};
use crate::complex::table::{id_bits, order_by_key, partition_point};
use crate::complex::{Complex, MAX_DIMENSION, SimplexTable, is_subset};
use crate::relation::handle::{Order, SimplexHandle};
use crate::relation::{QueryError, Storage, StructureKind, Topology};

const KIND: StructureKind = StructureKind::Ia;
/// "No simplex" in adjacency slots.
pub const NONE: u32 = u32::MAX;

// The shared walking helpers moved to `super::common`; re-exported here for code written
// against their old home.
pub(crate) use super::common::{IdSet, RowSet, faces_containing, faces_of_tops, show};

/// The Indexed data structure with Adjacencies (see the module documentation for what it stores and costs).
#[derive(Debug, Clone)]
pub struct IndexedAdjacency {
    d: usize,
    n: u32,
    /// R_{d,0}: the d-simplices, ascending lexicographic (a d-simplex's id is its row).
    tops: SimplexTable,
    /// R_{d,d}: d + 1 entries per d-simplex, entry `i` across the facet opposite vertex `i`.
    adj: Arr<u32>,
    /// Per vertex, one d-simplex per component of its star (CSR).
    vstar_off: Arr<u32>,
    vstar: Arr<u32>,
    /// n_p for p = 0..=d.
    counts: Vec<usize>,
    /// Handle bookkeeping: windings, top simplices below d, lazy tables ([`super::nav`]).
    pub(crate) nav: NavIndex,
}

/// R_{d,d} for sorted d-simplices: `Err((facet, first three d-simplices))` if a facet has more
/// than two d-simplices (the lexicographically first such facet).
#[allow(clippy::type_complexity)]
fn adjacency(tops: &SimplexTable, d: usize) -> Result<Vec<u32>, (Vec<u32>, Vec<u32>)> {
    let w = d + 1;
    let mut adj = vec![NONE; tops.len() * w];
    if d == 0 {
        return Ok(adj);
    }
    let facet = |k: u32| {
        let (t, i) = (k as usize / w, k as usize % w);
        tops.get(t)
            .iter()
            .enumerate()
            .filter(move |&(j, _)| j != i)
            .map(|(_, &v)| v)
    };
    let max = tops.as_flat().iter().copied().max().unwrap_or(0);
    let bits = id_bits(max);
    let order = order_by_key(tops.len() * w, d as u32 * bits, |k| {
        facet(k).fold(0u64, |acc, v| (acc << bits) | v as u64)
    })
    .unwrap_or_else(|| {
        let mut order: Vec<u32> = (0..(tops.len() * w) as u32).collect();
        order.sort_unstable_by(|&a, &b| facet(a).cmp(facet(b)).then(a.cmp(&b)));
        order
    });
    let mut i = 0;
    while i < order.len() {
        let mut j = i + 1;
        while j < order.len() && facet(order[j]).eq(facet(order[i])) {
            j += 1;
        }
        match j - i {
            1 => {}
            2 => {
                let (a, b) = (order[i], order[i + 1]);
                adj[a as usize] = b / w as u32;
                adj[b as usize] = a / w as u32;
            }
            _ => {
                let three = order[i..i + 3]
                    .iter()
                    .flat_map(|&k| tops.get(k as usize / w).iter().copied())
                    .collect();
                return Err((facet(order[i]).collect(), three));
            }
        }
        i = j;
    }
    Ok(adj)
}

/// R_{d,d} like [`adjacency`], with the facet slots bucketed by their facet's smallest vertex
/// (a counting sort: 4 bytes per slot) and each bucket sorted on its own, so no key wider than
/// a word is ever needed and buckets are matched on [`crate::parallel::threads`] threads. The
/// result (and the facet named in an error: the lexicographically first with three or more
/// d-simplices) is the same whatever the thread count. O(n_d·d·(1 + log b)) for buckets of b.
/// The outer `Err` is `TooLarge`: an array that cannot be had.
#[allow(clippy::type_complexity)]
pub(crate) fn adjacency_by_vertex(
    kind: StructureKind,
    tops: &SimplexTable,
    d: usize,
    n: u32,
) -> Result<Result<Vec<u32>, (Vec<u32>, Vec<u32>)>, BuildError> {
    let w = d + 1;
    let slots = tops.len() * w;
    // Shared words: each slot is in one matched pair, so the chunks' stores never meet and the
    // array is the same whatever the thread count (no serial scatter of the pairs afterwards).
    let adj = crate::parallel::try_atomics(slots, |_| NONE)
        .map_err(|bytes| too_large(kind, bytes, "adjacencies"))?;
    if d == 0 {
        return Ok(Ok(crate::parallel::into_plain(adj)));
    }
    // Slot k = (top k / w, facet opposite vertex k % w); its facet's smallest vertex is the
    // top's first vertex unless that is the one left out (slot 0 of a top). The tops are
    // sorted, so the other slots at v are those of the run of tops starting with v: only the
    // slot-0 facets are bucketed, by the top's second vertex (a counting sort of the tops, on
    // several threads: each bucket lists its slots in top order for any thread count).
    let (start, order) = crate::parallel::try_invert(n as usize, tops.len(), &SecondVertex(tops))
        .map_err(|bytes| too_large(kind, bytes, "facet slots"))?;
    let facet = |k: u32| {
        let (t, i) = (k as usize / w, k as usize % w);
        let mut f = [0u32; 16];
        let row = tops.get(t);
        f[..i].copy_from_slice(&row[..i]);
        f[i..d].copy_from_slice(&row[i + 1..]);
        f
    };
    // Buckets in chunks of vertices; each chunk stores its matched pairs and yields its first
    // error.
    let chunks = (n as usize).div_ceil(1024).max(1);
    let pair = |a: u32, b: u32| {
        adj[a as usize].store(b / w as u32, Ordering::Relaxed);
        adj[b as usize].store(a / w as u32, Ordering::Relaxed);
    };
    let per_chunk = |c: usize| {
        let (v0, v1) = (c * 1024, ((c + 1) * 1024).min(n as usize));
        let mut bucket: Vec<([u32; 16], u32)> = Vec::new();
        // The first top whose first vertex is v0 or more.
        let mut t = partition_point(0..tops.len(), |mid| (tops.get(mid)[0] as usize) < v0);
        for v in v0..v1 {
            bucket.clear();
            while t < tops.len() && tops.get(t)[0] as usize == v {
                bucket.extend((t * w + 1..(t + 1) * w).map(|k| (facet(k as u32), k as u32)));
                t += 1;
            }
            let range = start[v] as usize..start[v + 1] as usize;
            bucket.extend(order[range].iter().map(|&k| (facet(k), k)));
            bucket.sort_unstable();
            let mut i = 0;
            while i < bucket.len() {
                let mut j = i + 1;
                while j < bucket.len() && bucket[j].0 == bucket[i].0 {
                    j += 1;
                }
                match j - i {
                    1 => {}
                    2 => pair(bucket[i].1, bucket[i + 1].1),
                    _ => {
                        return Some((
                            bucket[i].0,
                            [bucket[i].1, bucket[i + 1].1, bucket[i + 2].1],
                        ));
                    }
                }
                i = j;
            }
        }
        None
    };
    let results = crate::parallel::map_chunks(chunks, per_chunk);
    // The first error in vertex order, as one thread would find it.
    if let Some((f, three)) = results.into_iter().flatten().next() {
        let three = three
            .iter()
            .flat_map(|&k| tops.get(k as usize / w).iter().copied())
            .collect();
        return Ok(Err((f[..d].to_vec(), three)));
    }
    Ok(Ok(crate::parallel::into_plain(adj)))
}

/// The slot-0 facets of the d-simplices (slot `t·(d+1)`) by their d-simplex's second vertex, for
/// [`crate::parallel::try_invert`].
struct SecondVertex<'a>(&'a SimplexTable);

impl crate::parallel::Incidences for SecondVertex<'_> {
    fn visit(&self, range: std::ops::Range<usize>, f: &mut impl FnMut(u32, u32)) {
        let w = self.0.arity();
        for t in range {
            f((t * w) as u32, self.0.get(t)[1]);
        }
    }
}

/// n_p for p = 0..=d without listing the faces: n_{d−1} from the adjacencies (a facet is on
/// one or two d-simplices), and for 0 < p < d − 1 the p-faces counted at their smallest vertex
/// v, from a walk of v's star (its components' seeds in `vstar`), split between threads by
/// vertex. Memory: one star at a time per thread. O(Σ_v |star(v)|·C(d, p)·log).
fn face_counts(
    tops: &SimplexTable,
    adj: &[u32],
    vstar_off: &[u32],
    vstar: &[u32],
    d: usize,
    n: u32,
) -> Vec<usize> {
    let w = d + 1;
    let mut counts = vec![0; d + 1];
    counts[0] = n as usize;
    counts[d] = tops.len();
    if d >= 2 {
        let open: usize = crate::parallel::map_ranges(adj.len(), |r| {
            adj[r].iter().filter(|&&a| a == NONE).count()
        })
        .into_iter()
        .sum();
        counts[d - 1] = open + (adj.len() - open) / 2;
    }
    if d < 3 {
        return counts;
    }
    let per_chunk = |c: usize| {
        let mut sums = vec![0usize; d];
        let (mut seen, mut stack, mut faces) = (FxHashSet::default(), Vec::new(), Vec::new());
        let mut upper = Vec::with_capacity(w);
        for v in (c * 1024) as u32..(((c + 1) * 1024) as u32).min(n) {
            seen.clear();
            let seeds = &vstar[vstar_off[v as usize] as usize..vstar_off[v as usize + 1] as usize];
            stack.extend_from_slice(seeds);
            seen.extend(seeds.iter().copied());
            let mut star = Vec::new();
            while let Some(x) = stack.pop() {
                star.push(x);
                let row = tops.get(x as usize);
                for (i, &u) in row.iter().enumerate() {
                    let y = adj[x as usize * w + i];
                    if u != v && y != NONE && seen.insert(y) {
                        stack.push(y);
                    }
                }
            }
            for (p, sum) in sums.iter_mut().enumerate().take(d - 1).skip(1) {
                faces.clear();
                for &x in &star {
                    upper.clear();
                    upper.extend(tops.get(x as usize).iter().copied().filter(|&u| u > v));
                    for mask in 0u32..1 << upper.len() {
                        if mask.count_ones() as usize == p {
                            let mut f = [0u32; 16];
                            let mut j = 0;
                            for (b, &u) in upper.iter().enumerate() {
                                if mask >> b & 1 == 1 {
                                    f[j] = u;
                                    j += 1;
                                }
                            }
                            faces.push(f);
                        }
                    }
                }
                faces.sort_unstable();
                faces.dedup();
                *sum += faces.len();
            }
        }
        sums
    };
    let chunks = (n as usize).div_ceil(1024);
    for sums in crate::parallel::map_chunks(chunks, per_chunk) {
        for p in 1..d - 1 {
            counts[p] += sums[p];
        }
    }
    counts
}

/// Per-vertex star components: (CSR offsets, one d-simplex per component), each vertex's list
/// ascending. A component's reference is its smallest d-simplex: the serial path walks each
/// component once through the adjacencies from its first slot in (d-simplex, vertex) order; on
/// several threads, a shared union–find over the slots (whose roots are the smallest slots)
/// gives the same components. The (vertex, d-simplex) pairs come in ascending d-simplex order,
/// so inverting them by vertex (in source order, see [`crate::parallel::try_invert`]) lists
/// each vertex's references ascending. O(d²·n_d).
fn vertex_components(
    tops: &SimplexTable,
    adj: &[u32],
    d: usize,
    n: u32,
) -> Result<(Vec<u32>, Vec<u32>), BuildError> {
    let parts = if crate::parallel::splits(tops.len() * (d + 1)) {
        component_roots(tops, adj, d)?
    } else {
        vec![component_walks(tops, adj, d)?]
    };
    let pairs = PairParts::new(parts);
    crate::parallel::try_invert(n as usize, pairs.len(), &pairs)
        .map_err(|bytes| too_large(KIND, bytes, "star components"))
}

/// The (vertex, smallest d-simplex) of each star component, in (d-simplex, vertex) order, by
/// one walk per component from its first unvisited slot. 1 byte per slot.
fn component_walks(
    tops: &SimplexTable,
    adj: &[u32],
    d: usize,
) -> Result<Vec<(u32, u32)>, BuildError> {
    let w = d + 1;
    let mut visited = try_vec(KIND, false, tops.len() * w, "visit marks")?;
    let mut pairs = Vec::new();
    let mut stack = Vec::new();
    for t in 0..tops.len() {
        for j in 0..w {
            if visited[t * w + j] {
                continue;
            }
            let v = tops.get(t)[j];
            try_push(KIND, &mut pairs, (v, t as u32), "star components")?;
            visited[t * w + j] = true;
            stack.push((t, j));
            while let Some((u, pos)) = stack.pop() {
                for i in (0..w).filter(|&i| i != pos) {
                    let x = adj[u * w + i];
                    if x == NONE {
                        continue;
                    }
                    let x = x as usize;
                    let px = tops.get(x).iter().position(|&y| y == v).unwrap();
                    if !visited[x * w + px] {
                        visited[x * w + px] = true;
                        stack.push((x, px));
                    }
                }
            }
        }
    }
    Ok(pairs)
}

/// [`component_walks`] on several threads: slot (t, j) (vertex j of d-simplex t) is joined to
/// the slot of the same vertex in each neighbour across a facet containing it, by ranges of
/// d-simplices; the roots, the smallest slot of each component, are the walks' starts: their
/// pairs listed by range of d-simplices, ranges in order. 4 bytes per slot.
fn component_roots(
    tops: &SimplexTable,
    adj: &[u32],
    d: usize,
) -> Result<Vec<Vec<(u32, u32)>>, BuildError> {
    let w = d + 1;
    let slots = tops.len() * w;
    let uf = crate::parallel::SharedUnionFind::try_new(slots)
        .map_err(|bytes| too_large(KIND, bytes, "star component labels"))?;
    crate::parallel::map_ranges(tops.len(), |range| {
        for t in range {
            let row = tops.get(t);
            for (i, &x) in adj[t * w..(t + 1) * w].iter().enumerate() {
                // Each shared facet once, from its smaller d-simplex.
                if x == NONE || (x as usize) < t {
                    continue;
                }
                let other = tops.get(x as usize);
                for (j, &v) in row.iter().enumerate().filter(|&(j, _)| j != i) {
                    let px = other.iter().position(|&y| y == v).unwrap();
                    uf.union((t * w + j) as u32, (x as usize * w + px) as u32);
                }
            }
        }
    });
    crate::parallel::map_ranges(tops.len(), |range| {
        let mut pairs = Vec::new();
        for t in range {
            for (j, &v) in tops.get(t).iter().enumerate() {
                if uf.is_root((t * w + j) as u32) {
                    try_push(KIND, &mut pairs, (v, t as u32), "star components")?;
                }
            }
        }
        Ok(pairs)
    })
    .into_iter()
    .collect()
}

impl IndexedAdjacency {
    /// Checks the domain, then builds R_{d,d} by sorting the facets of the d-simplices and the
    /// vertex references by one walk per star component. O(n_d·d·log n_d) time.
    pub fn build(complex: &Complex) -> Result<IndexedAdjacency, BuildError> {
        let d = complex.dimension();
        let n = complex.vertex_count();
        for p in 0..d {
            if let Some(s) = complex.tops(p).iter().next() {
                let what = if p == 0 {
                    "an isolated vertex".to_string()
                } else {
                    format!("a top {p}-simplex (a face of no {}-simplex)", p + 1)
                };
                return Err(super::common::unsupported(
                    KIND,
                    format!(
                        "{} is {what}, but IA encodes only regular complexes, whose top simplices \
                     all have the complex's dimension {d}",
                        show(s)
                    ),
                ));
            }
        }
        let tops = try_table(KIND, complex.tops(d))?;
        to_u32(KIND, tops.len() * (d + 1), "adjacency entries")?;
        let adj = adjacency_by_vertex(KIND, &tops, d, n)?.map_err(|(facet, three)| {
            let three: Vec<String> = three.chunks(d + 1).map(show).collect();
            super::common::unsupported(
                KIND,
                format!(
                    "{}-simplex {} is a face of more than two {d}-simplices ({}, ...), so the \
                 complex is not a pseudo-manifold",
                    d - 1,
                    show(&facet),
                    three.join(", ")
                ),
            )
        })?;
        let (vstar_off, vstar) = vertex_components(&tops, &adj, d, n)?;
        let counts = face_counts(&tops, &adj, &vstar_off, &vstar, d, n);
        let nav = NavIndex::new(KIND, complex)?;
        Ok(IndexedAdjacency {
            nav,
            d,
            n,
            tops,
            adj: adj.into(),
            vstar_off: vstar_off.into(),
            vstar: vstar.into(),
            counts,
        })
    }

    /// Integers of the plain IA (R_{d,0} and R_{d,d} only): `2(d+1)·n_d`.
    pub fn plain_ia_integers(&self) -> u64 {
        (2 * (self.d + 1) * self.tops.len()) as u64
    }

    /// The d-simplices (R_{d,0}), ascending lexicographic; a d-simplex's id is its row.
    pub fn top_simplices(&self) -> &SimplexTable {
        &self.tops
    }

    /// R_{d,d} of d-simplex `t`: entry `i` across the facet opposite vertex `i`, or [`NONE`].
    #[inline]
    pub fn neighbours(&self, t: u32) -> &[u32] {
        let w = self.d + 1;
        &self.adj[t as usize * w..(t as usize + 1) * w]
    }

    /// One d-simplex per (d−1)-connected component of the star of `v`, ascending.
    pub fn star_components(&self, v: u32) -> &[u32] {
        &self.vstar[self.vstar_off[v as usize] as usize..self.vstar_off[v as usize + 1] as usize]
    }

    /// Visits every d-simplex in the star of `v` once, walking from the component references
    /// through the facets containing `v`; stops early when `visit` returns false (and then
    /// returns false). `seen` must hold no simplex of the star of `v`.
    fn walk_star(&self, v: u32, seen: &mut IdSet, visit: impl FnMut(u32, &[u32]) -> bool) -> bool {
        self.walk_from(v, self.star_components(v), seen, visit)
    }

    /// [`Self::walk_star`] from the given d-simplices at `v` only.
    fn walk_from(
        &self,
        v: u32,
        starts: &[u32],
        seen: &mut IdSet,
        visit: impl FnMut(u32, &[u32]) -> bool,
    ) -> bool {
        let w = self.d + 1;
        let verts = |t: u32| self.tops.get(t as usize);
        walk_tops(starts, seen, verts, visit, |t, vs, frontier| {
            for (i, &x) in vs.iter().enumerate() {
                let u = self.adj[t as usize * w + i];
                if x != v && u != NONE {
                    frontier.reach(u);
                }
            }
        })
    }

    /// R_{0,q} of vertex `v`, 0 < q < d, as dense q-indices (rows of the lazy q-table), each
    /// once and ascending, from one walk of the star of `v` ([`Self::cofaces_in`]).
    fn vertex_cofaces(&self, v: u32, q: usize, found: impl FnMut(u32)) {
        self.with_star(v, |star, lower| self.cofaces_in(v, star, lower, q, found));
    }

    /// `then` of the d-simplices of the star of `v` (walk order) and of their vertices below
    /// `v` ([`Self::lower_neighbours`]), both in this thread's scratch vectors.
    fn with_star<R>(&self, v: u32, then: impl FnOnce(&[u32], &[u32]) -> R) -> R {
        let mut star = Scratch::<Vec<u32>>::take();
        star.clear();
        self.walk_star(v, &mut IdSet::default(), |t, _| {
            star.push(t);
            true
        });
        let mut lower = Scratch::<Vec<u32>>::take();
        self.lower_neighbours(v, &star, &mut lower);
        then(&star, &lower)
    }

    /// The vertices below `v` of the d-simplices `star` of `v`, ascending, each once: the
    /// smallest vertices of the faces through v that do not start with v.
    fn lower_neighbours(&self, v: u32, star: &[u32], lower: &mut Vec<u32>) {
        lower.clear();
        for &t in star {
            for &x in self.tops.get(t as usize) {
                // A mesh vertex has a few lower neighbours: a scan beats sorting the repeats.
                if x < v && !lower.contains(&x) {
                    lower.push(x);
                }
            }
        }
        lower.sort_unstable();
    }

    /// R_{0,q} of `v` from the d-simplices `star` of `v` and its `lower` neighbours
    /// ([`Self::lower_neighbours`]), each face once, in ascending row order. A q-face through v
    /// is a row of the lazy table starting with its smallest vertex: with v (that range comes
    /// last, every row of it through v: each face of the IA's complex lies in a d-simplex), or
    /// with some x in `lower`, and then it is one of x's rows whose second vertex is at most v
    /// (rows are ascending). Edges [x, v] are searched among x's rows. For q ≥ 2, when x has
    /// few rows ([`Self::SCAN_ROWS`]: a mesh vertex has a dozen) they are scanned in order for
    /// v up to second vertex v; else (a hub x) the faces through x and v of the d-simplices in
    /// the star are searched one by one. No face is searched twice, no set is kept for the
    /// scans, and the cost is O(C(d, q)·n_v·log) at worst.
    fn cofaces_in(
        &self,
        v: u32,
        star: &[u32],
        lower: &[u32],
        q: usize,
        mut found: impl FnMut(u32),
    ) {
        let table = self.lazy_table(q);
        let search = |row: &[u32]| table.find(row).expect("a face of a d-simplex is a simplex");
        for &x in lower {
            if q == 1 {
                found(search(&[x, v]));
                continue;
            }
            let rows = table.starting_with(x);
            if rows.len() <= Self::SCAN_ROWS as usize {
                // In order, up to the first row whose second vertex is above v.
                for r in rows {
                    let row = table.row(r);
                    if row[1] > v {
                        break;
                    }
                    if row[1..].contains(&v) {
                        found(r);
                    }
                }
                continue;
            }
            let mut ids = Scratch::<Vec<u32>>::take();
            ids.clear();
            let mut set = RowSet::default();
            for &t in star {
                let verts = self.tops.get(t as usize);
                if verts.contains(&x) {
                    faces_containing(verts, &[x, v], q, |f| {
                        if f[0] == x && set.insert(f) {
                            ids.push(search(f));
                        }
                    });
                }
            }
            ids.sort_unstable();
            ids.iter().for_each(|&r| found(r));
        }
        table.starting_with(v).for_each(&mut found);
    }

    /// Rows of a lower neighbour scanned for a vertex's cofaces before searching them instead.
    const SCAN_ROWS: u32 = 64;

    /// Whether some d-simplex contains σ (ascending, p > 0), by walking the star of σ's first
    /// vertex.
    fn in_some_top(&self, sigma: &[u32]) -> bool {
        let mut seen = IdSet::default();
        !self.walk_star(sigma[0], &mut seen, |_, t| !is_subset(sigma, t))
    }
}

impl NavBase for IndexedAdjacency {
    fn nav(&self) -> &NavIndex {
        &self.nav
    }

    fn stored_table(&self, p: usize) -> Option<&SimplexTable> {
        (p == self.d).then_some(&self.tops)
    }

    // The same walks with no call per answer (R_{d,d}, R_{0,d}; d ≥ 1), same order as
    // `fast_visit`.
    fn has_fast(&self, p: usize, q: usize) -> bool {
        self.d > 0 && ((q == self.d && p == self.d) || (p == 0 && q >= 1))
    }

    // One walk of the star of v, then its q-faces through v for q = 1 .. d − 1 from the
    // d-simplices met (the same answers and order as one walk per dimension).
    fn fast_star(&self, v: u32, order: Order, out: &mut Vec<SimplexHandle>) -> bool {
        let d = self.d;
        if d == 0 {
            return false;
        }
        self.with_star(v, |star, lower| {
            // The q-faces come ascending (`cofaces_in`): lexicographic in either order.
            for q in 1..d {
                self.cofaces_in(v, star, lower, q, |x| out.push(SimplexHandle::dense(q, x)));
            }
            let start = out.len();
            out.extend(star.iter().map(|&t| SimplexHandle::dense(d, t)));
            if order == Order::Lexicographic {
                out[start..].sort_unstable();
            }
        });
        true
    }

    fn fast_into(&self, p: usize, i: u32, q: usize, ids: &mut Vec<u32>) {
        if p == self.d {
            ids.extend(self.neighbours(i).iter().filter(|&&u| u != NONE));
        } else if q < self.d {
            self.vertex_cofaces(i, q, |x| ids.push(x));
        } else {
            let mut seen = IdSet::default();
            self.walk_star(i, &mut seen, |t, _| {
                ids.push(t);
                true
            });
        }
    }

    /// Direct walks (d-simplex `t` is dense d-simplex `t`): R_{d,0}, R_{d,d} O(d); R_{0,d},
    /// R_{0,0} the star walk, O(d·n_v). Others: the generic path.
    fn fast_visit(&self, h: SimplexHandle, sigma: &[u32], q: usize, visit: Visit<'_>) -> Fast {
        let d = self.d;
        if d == 0 {
            return None;
        }
        match (h.dim(), q) {
            (p, 0) if p == d => sigma
                .iter()
                .for_each(|&x| visit(SimplexHandle::dense(0, x))),
            (p, q) if p == d && q == d => {
                for &u in self.neighbours(h.index()).iter().filter(|&&u| u != NONE) {
                    visit(SimplexHandle::dense(d, u));
                }
            }
            (0, q) if q == d => {
                let mut seen = IdSet::default();
                self.walk_star(sigma[0], &mut seen, |t, _| {
                    visit(SimplexHandle::dense(d, t));
                    true
                });
            }
            (0, 0) => {
                let (v, mut seen, mut others) = (sigma[0], IdSet::default(), IdSet::default());
                self.walk_star(v, &mut seen, |_, t| {
                    for &x in t.iter().filter(|&&x| x != v) {
                        if others.insert(x) {
                            visit(SimplexHandle::dense(0, x));
                        }
                    }
                    true
                });
            }
            (0, q) => self.vertex_cofaces(sigma[0], q, |x| visit(SimplexHandle::dense(q, x))),
            _ => return None,
        }
        Some(Ok(()))
    }
}

/// The cases of [`IndexedAdjacency`]'s `query`; each returns whether σ is in the complex.
impl IndexedAdjacency {
    /// σ a d-simplex: its facet neighbours (q = d) or its q-faces. `None` when σ is not one.
    fn query_top(&self, sigma: &[u32], q: usize, out: &mut Vec<u32>) -> Option<()> {
        let t = self.tops.find(sigma)?;
        if q == self.d {
            for &u in self.neighbours(t) {
                if u != NONE {
                    out.extend_from_slice(self.tops.get(u as usize));
                }
            }
        } else {
            faces_containing(sigma, &[], q, |f| out.extend_from_slice(f));
        }
        Some(())
    }

    /// R_{0,0} (q = 0) or R_{0,1} of vertex v: an edge at v is named by its other end, so one
    /// id set serves both.
    fn query_vertex_edges(&self, v: u32, q: usize, out: &mut Vec<u32>) {
        let (mut seen, mut others) = (IdSet::default(), IdSet::default());
        self.walk_star(v, &mut seen, |_, t| {
            for &x in t.iter().filter(|&&x| x != v) {
                if others.insert(x) {
                    match q {
                        0 => out.push(x),
                        _ => out.extend_from_slice(&[x.min(v), x.max(v)]),
                    }
                }
            }
            true
        });
    }

    /// R_{p,q}, p < q: the q-faces containing σ of the top simplices around σ\[0\].
    fn query_coboundary(&self, sigma: &[u32], q: usize, out: &mut Vec<u32>) -> bool {
        let (mut set, mut seen) = (RowSet::default(), IdSet::default());
        let mut found = false;
        self.walk_star(sigma[0], &mut seen, |_, t| {
            if is_subset(sigma, t) {
                found = true;
                if q == self.d {
                    out.extend_from_slice(t);
                } else {
                    faces_containing(t, sigma, q, |f| set.emit(f, out));
                }
            }
            true
        });
        found
    }

    /// R_{p,p}, 0 < p < d: every facet of σ contains σ\[0\] or σ\[1\], so the stars of those
    /// two vertices hold every p-simplex sharing a facet with σ.
    fn query_adjacency(&self, sigma: &[u32], out: &mut Vec<u32>) -> bool {
        let p = sigma.len() - 1;
        let mut set = RowSet::default();
        let mut found = false;
        let mut facet = [0u32; MAX_DIMENSION + 1];
        let mut row = [0u32; MAX_DIMENSION + 1];
        let mut visit = |_: u32, t: &[u32]| {
            let shared = sigma.iter().filter(|v| t.binary_search(v).is_ok()).count();
            if shared == p + 1 {
                found = true;
            }
            if shared < p {
                return true;
            }
            for skip in 0..=p {
                if shared == p && t.binary_search(&sigma[skip]).is_ok() {
                    continue;
                }
                let mut k = 0;
                for (j, &v) in sigma.iter().enumerate() {
                    if j != skip {
                        facet[k] = v;
                        k += 1;
                    }
                }
                for &x in t.iter().filter(|x| sigma.binary_search(x).is_err()) {
                    // The facet with x inserted in order, on the stack.
                    let at = facet[..p].partition_point(|&y| y < x);
                    row[..at].copy_from_slice(&facet[..at]);
                    row[at] = x;
                    row[at + 1..=p].copy_from_slice(&facet[at..p]);
                    set.emit(&row[..=p], out);
                }
            }
            true
        };
        // Separate walks: a shared `seen` would stop the second walk at simplices the first
        // one met, before it reaches the rest of the star of σ[1]. Rows are deduplicated.
        self.walk_star(sigma[0], &mut IdSet::default(), &mut visit);
        self.walk_star(sigma[1], &mut IdSet::default(), &mut visit);
        found
    }
}

impl Topology for IndexedAdjacency {
    crate::relation::topology_preamble! {
        self, KIND;
        dimension: self.d;
        vertex_count: self.n;
        count(p): self.counts.get(p).copied().unwrap_or(0);
        top_count(p): if p == self.d { self.tops.len() } else { 0 };
    }

    fn simplices(&self, p: usize, out: &mut Vec<u32>) {
        if p > self.d {
        } else if p == self.d {
            out.extend_from_slice(self.tops.as_flat());
        } else if p == 0 {
            out.extend(0..self.n);
        } else {
            let mut rows = Vec::new();
            faces_of_tops(self.tops.iter(), p, &mut rows);
            out.extend_from_slice(&rows);
        }
    }

    fn contains(&self, sigma: &[u32]) -> bool {
        let p = sigma.len() - 1;
        if p == 0 {
            sigma[0] < self.n
        } else if p == self.d {
            self.tops.find(sigma).is_some()
        } else {
            p < self.d && self.in_some_top(sigma)
        }
    }

    fn query(&self, sigma: &[u32], q: usize, out: &mut Vec<u32>) -> Result<(), QueryError> {
        let p = sigma.len() - 1;
        let missing = || QueryError::NotInComplex {
            simplex: sigma.to_vec(),
        };
        if p == self.d {
            return self.query_top(sigma, q, out).ok_or_else(missing);
        }
        let found = if p > self.d {
            false
        } else if q < p {
            let found = self.in_some_top(sigma);
            if found {
                faces_containing(sigma, &[], q, |f| out.extend_from_slice(f));
            }
            found
        } else if p == 0 && q <= 1 {
            self.query_vertex_edges(sigma[0], q, out);
            true
        } else if q > p {
            self.query_coboundary(sigma, q, out)
        } else {
            let start = out.len();
            let found = self.query_adjacency(sigma, out);
            if !found {
                out.truncate(start);
            }
            found
        };
        if found { Ok(()) } else { Err(missing()) }
    }

    fn storage(&self) -> Storage {
        let bytes = self.tops.heap_bytes()
            + 4 * (self.adj.capacity() + self.vstar_off.capacity() + self.vstar.capacity())
            + 8 * self.counts.capacity();
        Storage {
            integers: self.plain_ia_integers() + self.vstar.len() as u64,
            bits: 0,
            bytes: bytes as u64,
        }
    }

    fn validate(&self) -> Result<(), String> {
        let (d, w) = (self.d, self.d + 1);
        if self.tops.arity() != w || self.tops.is_empty() {
            return Err(format!("R_{{{d},0}} table is empty or not of arity {w}"));
        }
        for (t, s) in self.tops.iter().enumerate() {
            if s.windows(2).any(|p| p[0] >= p[1]) || s[d] >= self.n {
                return Err(format!(
                    "{d}-simplex {t} {s:?} not ascending or out of range"
                ));
            }
            if t > 0 && self.tops.get(t - 1) >= s {
                return Err(format!("R_{{{d},0}} not strictly ascending at {t}"));
            }
            for (i, &u) in self.neighbours(t as u32).iter().enumerate() {
                if u == NONE {
                    continue;
                }
                let other = self.tops.get(u as usize);
                let shared = s.iter().filter(|v| other.contains(v)).count();
                if u as usize == t || shared != d || other.contains(&s[i]) {
                    return Err(format!(
                        "R_{{{d},{d}}} entry {i} of {s:?} is {other:?}, not across the facet opposite {}",
                        s[i]
                    ));
                }
                let back = other.iter().position(|v| !s.contains(v)).unwrap();
                if self.neighbours(u)[back] != t as u32 {
                    return Err(format!(
                        "R_{{{d},{d}}} not symmetric between {s:?} and {other:?}"
                    ));
                }
            }
        }
        match adjacency(&self.tops, d) {
            Ok(a) if a == self.adj => {}
            _ => return Err(format!("R_{{{d},{d}}} misses a shared facet")),
        }
        if self.vstar_off.len() != self.n as usize + 1 {
            return Err("vertex reference offsets have the wrong length".into());
        }
        // Walking from every reference must reach every (d-simplex, vertex) incidence exactly
        // once, and no reference may lie in another reference's component.
        let mut reached = 0usize;
        for v in 0..self.n {
            let refs = self.star_components(v);
            if refs.is_empty() {
                return Err(format!("vertex {v} has no star reference"));
            }
            let holds =
                |r: u32| (r as usize) < self.tops.len() && self.tops.get(r as usize).contains(&v);
            reached += check_star_refs(v, refs, "star reference", holds, |r, each| {
                self.walk_from(v, &[r], &mut IdSet::default(), |t, _| {
                    each(t);
                    true
                });
            })?;
        }
        if reached != self.tops.len() * w {
            return Err(format!(
                "vertex star references reach {reached} of {} incidences",
                self.tops.len() * w
            ));
        }
        Ok(())
    }
}

crate::persist_fields!(IndexedAdjacency { d, n, tops, adj, vstar_off, vstar, counts, nav } check |s| {
    let d = s.d;
    if d > crate::complex::MAX_DIMENSION {
        return Err(format!("dimension {d} above {}", crate::complex::MAX_DIMENSION));
    }
    if s.tops.arity() != d + 1 || s.adj.len() != (d + 1) * s.tops.len() || s.counts.len() != d + 1 {
        return Err(format!("top table, adjacency or counts do not fit dimension {d}"));
    }
    if s.vstar_off.len() != s.n as usize + 1 || s.vstar_off.last() != Some(&(s.vstar.len() as u32)) {
        return Err("vertex star offsets do not fit the vertices".into());
    }
    Ok(())
});
