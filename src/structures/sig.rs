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
//! - `tables[p]`: the p-simplices as ascending vertex ids, in ascending lexicographic order. The
//!   paper's global numbering is `first[p] + row`: simplices ordered by dimension, `first` being
//!   the lookup table of index ranges (d + 2 entries; the paper counts d + 1).
//! - `boundary[p]` (p ≥ 1): fixed-size, p + 1 row numbers into `tables[p − 1]` per p-simplex;
//!   entry i is the facet opposite the simplex's i-th vertex.
//! - `head[p]`, `flag[p]`, `pool[p]` (p < d): the partial co-boundaries. `pool[p]` holds the
//!   variable-sized arrays, one per p-simplex, each the global ids of C*_{p,g}(σ) for g = d down
//!   to p + 1 (decreasing g as in the paper, ascending ids within one g) followed by the stop
//!   code `u32::MAX`; the paper's count of Σκ entries + Σ n_p stop codes maps one to one.
//!   `head[p][i]` is the paper's "integer pointer": the start of σ's array in `pool[p]` — or,
//!   when σ's bit in `flag[p]` is set (the manifold shortcut), the global id of the single
//!   d-simplex that is σ's whole partial co-boundary, with no array in the pool.
//!
//! Ids are u32; flags are packed 64 to a word; all arrays are flat per dimension (no
//! per-simplex allocation). The vertex tables are what the relation API needs to find a simplex
//! by its vertex ids (binary search, as the IG does); the paper does not count them, the real
//! bytes do.
//!
//! # Storage
//! `storage()` counts the arrays as built: integers = boundary entries + one head per p-simplex
//! (p < d) + pool length; bits = one flag per p-simplex (p < d); bytes = every array's heap
//! capacity, vertex tables included. The paper's closed formula (§4.2) is
//! `Σ_{p<d} Σ_{g>p} κ^g_p + 2 Σ_{p<d} n_p + Σ_{0<p≤d} (p+1) n_p` integers and `Σ_{p<d} n_p` bits;
//! it gives every simplex an array. A simplex using the shortcut stores neither its one entry nor
//! its stop code, so the count here is that formula minus 2 per shortcut simplex. On a closed
//! manifold every p-simplex with p < d − 1 takes the shortcut and every (d−1)-simplex has two
//! d-simplices, which gives §7's `Σ_{0<p≤d} (p+1) n_p + Σ_{0≤p<d} n_p + 3 n_{d−1}` exactly.
//!
//! ## Where the layout differs from the paper, and why
//! - The paper's per-simplex "visited" bit is not stored (Σ n_p bits fewer): queries take
//!   `&self` and may run from many threads, so the marks live in per-query hash sets. That costs
//!   per query a few words per simplex actually visited (hash-set entries, ~8–16 bytes each with
//!   load factor) instead of one bit per simplex of the complex, plus clearing nothing afterwards
//!   (the paper must reset every bit it set).
//! - The paper applies the flag only to p < d − 1 and keeps arrays for every (d−1)-simplex; here
//!   a (d−1)-simplex with a single d-simplex (a boundary facet) also takes the shortcut, since
//!   the flag bit is counted for it anyway (Σ_{p<d} n_p bits). Closed manifolds count the same.
//! - Boundary entries are row numbers within their dimension, not global ids: the dimension is
//!   implied, and it saves an addition per step. Partial co-boundary entries are global ids,
//!   because one array mixes dimensions and the id must tell which.
//! - The vertex tables (p + 1 ids per p-simplex) are extra, as in our IG.
//!
//! # Builds
//! - [`Sig::from_ig`]: §5, Algorithm 1 with RetrieveTopSimplexes (walk C_{p,p+1} up from σ) and
//!   VisitCluster (walk B_{r,r−1} then C_{r−1,r} among the top simplices found). VisitCluster
//!   additionally marks each (r−1)-face it has expanded: without that, k top triangles on one
//!   edge would cost k² (each rescans the edge's k co-faces).
//! - [`Sig::build`]: straight from the complex, never making an IG (no co-boundary lists).
//!   Per dimension p, the top simplices above each p-simplex come from enumerating every top
//!   simplex's p-faces (counting sort into CSR, released after that dimension); clusters are a
//!   union–find over those top simplices, keyed by the shared (g−1)-faces that contain σ.
//!   After the closure and the boundaries (each facet found by binary search, as in the IG),
//!   time O(Σ_{τ top} Σ_{p<r} C(r+1, p+1) · r), r = dim τ; extra memory one dimension's
//!   top-incidence CSR (4 bytes per (face, top simplex) pair) plus per-simplex scratch.
//!
//! # Cost of each relation (after locating σ: O(p log n_p) by binary search)
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
//! The "σ ∈ Boundary(G, p, θ)" tests of Algorithms 5–6 are answered from the vertex tables (a
//! merge of two sorted id lists): the same answer as walking B, cheaper by a constant factor.

use rustc_hash::{FxHashMap, FxHashSet};

use super::ig::IncidenceGraph;
use super::{BuildError, to_u32};
use crate::complex::{Complex, SimplexTable};
use crate::relation::{QueryError, Storage, StructureKind, Topology};

const KIND: StructureKind = StructureKind::Sig;

/// End of a partial co-boundary array in `pool`.
const STOP: u32 = u32::MAX;

#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Sig {
    tables: Vec<SimplexTable>,
    /// Global id of the first p-simplex; `first[d + 1]` = total. The paper's lookup table.
    first: Vec<u32>,
    boundary: Vec<Vec<u32>>,
    head: Vec<Vec<u32>>,
    flag: Vec<Vec<u64>>,
    pool: Vec<Vec<u32>>,
    top_counts: Vec<usize>,
}

/// One dimension's heads, flags, pool, and its number of top simplices.
type CobArrays = (Vec<u32>, Vec<u64>, Vec<u32>, usize);

/// Appends partial co-boundary arrays for the p-simplices in order.
struct CobWriter {
    head: Vec<u32>,
    flag: Vec<u64>,
    pool: Vec<u32>,
    first_d: u32,
    tops: usize,
}

impl CobWriter {
    fn new(n: usize, first_d: u32) -> Self {
        CobWriter {
            head: Vec::with_capacity(n),
            flag: vec![0; n.div_ceil(64)],
            pool: Vec::new(),
            first_d,
            tops: 0,
        }
    }

    /// `reps`: one global id per cluster, any order; reordered to decreasing dimension, then
    /// ascending id.
    fn push(&mut self, reps: &mut [u32], first: &[u32]) {
        let i = self.head.len();
        if reps.is_empty() {
            self.tops += 1;
        }
        if reps.len() == 1 && reps[0] >= self.first_d {
            self.head.push(reps[0]);
            self.flag[i / 64] |= 1 << (i % 64);
            return;
        }
        reps.sort_unstable_by_key(|&e| (std::cmp::Reverse(dim_of(first, e)), e));
        self.head.push(self.pool.len() as u32);
        self.pool.extend_from_slice(reps);
        self.pool.push(STOP);
    }

    fn finish(mut self) -> Result<CobArrays, BuildError> {
        to_u32(
            KIND,
            self.pool.len(),
            "partial co-boundary entries of one dimension",
        )?;
        self.pool.shrink_to_fit();
        Ok((self.head, self.flag, self.pool, self.tops))
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
fn walk_faces(
    boundary: &[Vec<u32>],
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

/// Boundaries of every simplex by binary search of each facet in the table below.
fn boundaries(tables: &[SimplexTable]) -> Result<Vec<Vec<u32>>, BuildError> {
    let d = tables.len() - 1;
    let mut boundary = vec![Vec::new(); d + 1];
    let mut facet = Vec::with_capacity(d + 1);
    for p in 1..=d {
        let below = &tables[p - 1];
        let mut b = Vec::with_capacity(tables[p].len() * (p + 1));
        for s in tables[p].iter() {
            for skip in 0..=p {
                facet.clear();
                facet.extend(
                    s.iter()
                        .enumerate()
                        .filter(|&(j, _)| j != skip)
                        .map(|(_, &v)| v),
                );
                b.push(below.find(&facet).expect("closure contains every facet"));
            }
        }
        boundary[p] = b;
    }
    Ok(boundary)
}

fn lookup_table(tables: &[SimplexTable]) -> Result<Vec<u32>, BuildError> {
    let mut first = vec![0u32];
    let mut total = 0usize;
    for t in tables {
        total += t.len();
        // u32::MAX is the stop code, so it cannot be an id.
        if total >= STOP as usize {
            return Err(BuildError::TooLarge {
                kind: KIND,
                what: format!("{total} simplices exceed 32-bit global ids"),
            });
        }
        first.push(total as u32);
    }
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

impl Sig {
    /// §5, Algorithm 1: boundaries copied from the IG; for each simplex, its top simplices by
    /// RetrieveTopSimplexes, grouped into clusters by VisitCluster.
    pub fn from_ig(ig: &IncidenceGraph) -> Result<Sig, BuildError> {
        let d = ig.dimension();
        let tables: Vec<SimplexTable> = (0..=d).map(|p| ig.table(p).clone()).collect();
        let first = lookup_table(&tables)?;
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
        let (mut head, mut flag, mut pool) = (Vec::new(), Vec::new(), Vec::new());
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
            let mut w = CobWriter::new(tables[p].len(), first[d]);
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
            let (h, f, pl, t) = w.finish()?;
            head.push(h);
            flag.push(f);
            pool.push(pl);
            top_counts[p] = t;
        }
        Ok(Sig {
            tables,
            first,
            boundary,
            head,
            flag,
            pool,
            top_counts,
        })
    }

    /// Builds straight from the complex (never an IG): closure, boundaries, then per dimension p
    /// the top simplices above each p-simplex and their clusters by union–find.
    pub fn build(complex: &Complex) -> Result<Sig, BuildError> {
        let tables = complex.closure();
        let d = tables.len() - 1;
        let first = lookup_table(&tables)?;
        let boundary = boundaries(&tables)?;
        // Top rows per dimension: both tables are sorted, so one merge walk each.
        let mut top_rows: Vec<Vec<u32>> = vec![Vec::new(); d + 1];
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
        let (mut head, mut flag, mut pool) = (Vec::new(), Vec::new(), Vec::new());
        let mut top_counts = vec![0; d + 1];
        top_counts[d] = tables[d].len();
        let mut parent: Vec<u32> = Vec::new();
        let mut by_face: FxHashMap<u32, u32> = FxHashMap::default();
        let mut reps = Vec::new();
        for p in 0..d {
            let n = tables[p].len();
            // CSR: the top simplices (global ids, ascending) above each p-simplex.
            let mut off = vec![0u32; n + 1];
            for (r, rows) in top_rows.iter().enumerate().skip(p + 1) {
                for &t in rows {
                    walk_faces(&boundary, r, t, r + 1, r - p, u32::MAX, &mut |f| {
                        off[f as usize + 1] += 1
                    });
                }
            }
            for i in 0..n {
                off[i + 1] += off[i];
            }
            let mut fill = off.clone();
            let mut above = vec![0u32; off[n] as usize];
            for (r, rows) in top_rows.iter().enumerate().skip(p + 1) {
                for &t in rows {
                    walk_faces(&boundary, r, t, r + 1, r - p, u32::MAX, &mut |f| {
                        above[fill[f as usize] as usize] = first[r] + t;
                        fill[f as usize] += 1;
                    });
                }
            }
            drop(fill);
            let mut w = CobWriter::new(n, first[d]);
            for s in 0..n {
                let sigma = tables[p].get(s);
                let list = &above[off[s] as usize..off[s + 1] as usize];
                reps.clear();
                // Group by dimension (ascending ids are grouped by dimension already).
                let mut a = 0;
                while a < list.len() {
                    let r = dim_of(&first, list[a]);
                    let b = a + list[a..].partition_point(|&g| g < first[r + 1]);
                    let group = &list[a..b];
                    if r == p + 1 {
                        reps.extend_from_slice(group);
                    } else {
                        parent.clear();
                        parent.extend(0..group.len() as u32);
                        by_face.clear();
                        for (k, &g) in group.iter().enumerate() {
                            let t = g - first[r];
                            let mask = outside(tables[r].get(t as usize), sigma);
                            for i in 0..=r {
                                if mask >> i & 1 == 0 {
                                    continue;
                                }
                                let face = boundary[r][t as usize * (r + 1) + i];
                                match by_face.get(&face) {
                                    None => {
                                        by_face.insert(face, k as u32);
                                    }
                                    Some(&other) => {
                                        let (x, y) =
                                            (root(&mut parent, other), root(&mut parent, k as u32));
                                        // The smaller index stays root: the root is the cluster's
                                        // smallest simplex.
                                        let (lo, hi) = (x.min(y), x.max(y));
                                        parent[hi as usize] = lo;
                                    }
                                }
                            }
                        }
                        for k in 0..group.len() as u32 {
                            if root(&mut parent, k) == k {
                                reps.push(group[k as usize]);
                            }
                        }
                    }
                    a = b;
                }
                w.push(&mut reps, &first);
            }
            let (h, f, pl, t) = w.finish()?;
            head.push(h);
            flag.push(f);
            pool.push(pl);
            top_counts[p] = t;
        }
        Ok(Sig {
            tables,
            first,
            boundary,
            head,
            flag,
            pool,
            top_counts,
        })
    }

    /// Row of p-simplex `sigma` (ascending ids) in its dimension.
    pub fn find(&self, sigma: &[u32]) -> Option<u32> {
        self.tables.get(sigma.len().checked_sub(1)?)?.find(sigma)
    }

    fn is_flagged(&self, p: usize, i: u32) -> bool {
        self.flag[p][i as usize / 64] >> (i % 64) & 1 == 1
    }

    /// All partial co-boundaries of p-simplex row `i` (p < d), global ids, decreasing dimension.
    fn cstar(&self, p: usize, i: u32) -> &[u32] {
        let h = &self.head[p][i as usize];
        if self.is_flagged(p, i) {
            return std::slice::from_ref(h);
        }
        let rest = &self.pool[p][*h as usize..];
        &rest[..rest.iter().position(|&x| x == STOP).unwrap_or(rest.len())]
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
                    out.extend_from_slice(self.tables[g].get((e - self.first[g]) as usize));
                }
            }
        }
        Some(out)
    }

    /// Whether p-simplex σ stores its partial co-boundary through the manifold shortcut.
    pub fn uses_shortcut(&self, sigma: &[u32]) -> bool {
        let p = sigma.len() - 1;
        p < self.dimension() && self.find(sigma).is_some_and(|i| self.is_flagged(p, i))
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
            let mask = outside(self.tables[r].get(m as usize), sigma);
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
            let Scratch { cluster, found, .. } = sc;
            for &m in cluster.iter() {
                let mask = outside(self.tables[r].get(m as usize), sigma);
                walk_faces(&self.boundary, r, m, r + 1, r - g, mask, &mut |f| {
                    if found.insert(f) {
                        emit(f)
                    }
                });
            }
        }
    }

    fn emit_row(&self, q: usize, i: u32, out: &mut Vec<u32>) {
        out.extend_from_slice(self.tables[q].get(i as usize));
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
}

impl Topology for Sig {
    fn kind(&self) -> StructureKind {
        KIND
    }

    fn dimension(&self) -> usize {
        self.tables.len() - 1
    }

    fn vertex_count(&self) -> u32 {
        self.tables[0].len() as u32
    }

    fn count(&self, p: usize) -> usize {
        self.tables.get(p).map_or(0, SimplexTable::len)
    }

    fn top_count(&self, p: usize) -> usize {
        self.top_counts.get(p).copied().unwrap_or(0)
    }

    fn simplices(&self, p: usize, out: &mut Vec<u32>) {
        if let Some(t) = self.tables.get(p) {
            out.extend_from_slice(t.as_flat());
        }
    }

    fn contains(&self, sigma: &[u32]) -> bool {
        self.find(sigma).is_some()
    }

    fn query(&self, sigma: &[u32], q: usize, out: &mut Vec<u32>) -> Result<(), QueryError> {
        let p = sigma.len() - 1;
        let id = self.find(sigma).ok_or_else(|| QueryError::NotInComplex {
            simplex: sigma.to_vec(),
        })?;
        if q < p {
            // Algorithm 4, each face along its one canonical path.
            walk_faces(&self.boundary, p, id, p + 1, p - q, u32::MAX, &mut |f| {
                self.emit_row(q, f, out)
            });
            return Ok(());
        }
        let mut sc = Scratch::default();
        if q > p {
            self.coboundary(p, id, sigma, q, &mut sc, &mut |f| self.emit_row(q, f, out));
        } else if p == 0 {
            // Algorithm 7 on a vertex: the other end of each edge.
            if self.dimension() > 0 {
                let v = sigma[0];
                self.coboundary(0, id, sigma, 1, &mut sc, &mut |e| {
                    let edge = self.tables[1].get(e as usize);
                    out.push(if edge[0] == v { edge[1] } else { edge[0] });
                });
            }
        } else {
            // Algorithm 7: Coboundary(p) at each facet, minus σ.
            let mut facet = Vec::with_capacity(p);
            for k in 0..=p {
                facet.clear();
                facet.extend(
                    sigma
                        .iter()
                        .enumerate()
                        .filter(|&(j, _)| j != k)
                        .map(|(_, &v)| v),
                );
                let f = self.boundary[p][id as usize * (p + 1) + k];
                self.coboundary(p - 1, f, &facet, p, &mut sc, &mut |t| {
                    if t != id {
                        self.emit_row(p, t, out)
                    }
                });
            }
        }
        Ok(())
    }

    fn storage(&self) -> Storage {
        let d = self.dimension();
        let boundary: usize = self.boundary.iter().map(Vec::len).sum();
        let heads: usize = self.head.iter().map(Vec::len).sum();
        let pool: usize = self.pool.iter().map(Vec::len).sum();
        let flags: usize = (0..d).map(|p| self.tables[p].len()).sum();
        let words = |v: &Vec<Vec<u32>>| v.iter().map(|a| a.capacity() * 4).sum::<usize>();
        let bytes = self
            .tables
            .iter()
            .map(SimplexTable::heap_bytes)
            .sum::<usize>()
            + self.first.capacity() * 4
            + words(&self.boundary)
            + words(&self.head)
            + words(&self.pool)
            + self.flag.iter().map(|f| f.capacity() * 8).sum::<usize>();
        Storage {
            integers: (boundary + heads + pool) as u64,
            bits: flags as u64,
            bytes: bytes as u64,
        }
    }

    // p indexes several per-dimension arrays at once.
    #[allow(clippy::needless_range_loop)]
    fn validate(&self) -> Result<(), String> {
        let d = self.dimension();
        if self.tables[d].is_empty() {
            return Err(format!("no {d}-simplex in a {d}-complex"));
        }
        if self.tables[0]
            .iter()
            .enumerate()
            .any(|(i, v)| v[0] as usize != i)
        {
            return Err("vertex table is not 0..n".into());
        }
        if self.first.len() != d + 2 || self.first[0] != 0 {
            return Err("lookup table has the wrong length".into());
        }
        for p in 0..=d {
            let t = &self.tables[p];
            if t.arity() != p + 1 {
                return Err(format!("table {p} has arity {}", t.arity()));
            }
            if self.first[p + 1] - self.first[p] != t.len() as u32 {
                return Err(format!("lookup table range of dimension {p} is not n_{p}"));
            }
            for i in 1..t.len() {
                if t.get(i - 1) >= t.get(i) {
                    return Err(format!("table {p} not strictly ascending at row {i}"));
                }
            }
            if p > 0 {
                if self.boundary[p].len() != t.len() * (p + 1) {
                    return Err(format!("B_{{{p},{}}} has the wrong size", p - 1));
                }
                for (i, s) in t.iter().enumerate() {
                    for (k, &f) in self.boundary[p][i * (p + 1)..(i + 1) * (p + 1)]
                        .iter()
                        .enumerate()
                    {
                        let facet: Vec<u32> = s
                            .iter()
                            .enumerate()
                            .filter(|&(j, _)| j != k)
                            .map(|(_, &v)| v)
                            .collect();
                        if (f as usize) >= self.tables[p - 1].len()
                            || self.tables[p - 1].get(f as usize) != facet.as_slice()
                        {
                            return Err(format!(
                                "boundary entry {k} of {p}-simplex {s:?} is not the facet {facet:?}"
                            ));
                        }
                    }
                }
            }
        }
        // Every top simplex above each simplex, counted through the faces of the top simplices.
        let mut above: Vec<Vec<u32>> = (0..d).map(|p| vec![0; self.tables[p].len()]).collect();
        let mut is_top: Vec<Vec<bool>> = (0..=d).map(|p| vec![false; self.count(p)]).collect();
        is_top[d].iter_mut().for_each(|t| *t = true);
        for p in 0..d {
            let mut expect_pool = 0usize;
            if self.head[p].len() != self.tables[p].len() {
                return Err(format!("dimension {p}: one head per simplex expected"));
            }
            for i in 0..self.tables[p].len() as u32 {
                let s = self.tables[p].get(i as usize);
                if self.is_flagged(p, i) {
                    let e = self.head[p][i as usize];
                    if e < self.first[d] || e >= self.first[d + 1] {
                        return Err(format!("shortcut of {s:?} is not a {d}-simplex"));
                    }
                } else {
                    if self.head[p][i as usize] as usize != expect_pool {
                        return Err(format!("array of {s:?} is not where the previous one ends"));
                    }
                    let list = self.cstar(p, i);
                    expect_pool += list.len() + 1;
                    if expect_pool > self.pool[p].len() {
                        return Err(format!("array of {s:?} runs past the pool"));
                    }
                    if list.len() == 1 && self.dim_of(list[0]) == d {
                        return Err(format!("{s:?} should use the manifold shortcut"));
                    }
                    if list.windows(2).any(|w| {
                        let (a, b) = (self.dim_of(w[0]), self.dim_of(w[1]));
                        a < b || (a == b && w[0] >= w[1])
                    }) {
                        return Err(format!("array of {s:?} is not in decreasing dimension"));
                    }
                    if list.is_empty() {
                        is_top[p][i as usize] = true;
                    }
                }
                for &e in self.cstar(p, i) {
                    let r = self.dim_of(e);
                    if r <= p || r > d {
                        return Err(format!("C* of {s:?} lists a {r}-simplex"));
                    }
                    let t = self.tables[r].get((e - self.first[r]) as usize);
                    if !crate::complex::is_subset(s, t) {
                        return Err(format!("C* of {s:?} lists {t:?}, not in its star"));
                    }
                }
            }
            if expect_pool != self.pool[p].len() {
                return Err(format!("dimension {p}: pool has unused entries"));
            }
        }
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
        // The clusters listed at σ partition its top simplices, each led by its smallest.
        let mut sc = Scratch::default();
        for p in 0..d {
            for i in 0..self.tables[p].len() as u32 {
                let s = self.tables[p].get(i as usize);
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
                    self.retrieve_cluster(p, s, r, e - self.first[r], &mut sc);
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
