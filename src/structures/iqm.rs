//! Initial Quasi-Manifold (IQM) data structure — De Floriani, Mesmoudi, Morando and Puppo 2003,
//! as described in §3.1 and §3.4 of the 2005 survey. The decomposition is the *standard
//! decomposition* of that paper and of Morando's thesis ("Decomposition and Modeling in the
//! Non-Manifold Domain", 2003): top simplices pasted along manifold adjacencies, vertices split
//! where their star is not manifold-connected. The definitions below are this module's precise
//! reading of it, and the tests check the result against them by brute force.
//!
//! # Definitions
//! - A top h-simplex is a simplex of the complex that is not a proper face of another.
//! - A *joint* is an (h−1)-simplex τ (h ≥ 1) contained in exactly two top simplices σ, σ′ of
//!   the complex, both of dimension h: σ and σ′ are *manifold-adjacent* through τ. (Points
//!   inside τ then have a manifold neighbourhood; if a third top simplex of any dimension
//!   contains τ, they do not.)
//! - Two top simplices in the star of a vertex v are *manifold-connected around v* when a chain
//!   of manifold adjacencies joins them through joints that all contain v.
//! - A regular h-complex is an *initial quasi-manifold* when, for every vertex, every two top
//!   simplices of its star are (h−1)-manifold-connected within that star.
//!
//! # The standard decomposition
//! Explode the complex into its top simplices, each with its own copy of each of its vertices
//! (a *slot*: top σ, vertex v ∈ σ). Identify the slots (σ, v) and (σ′, v) whenever σ and σ′ are
//! manifold-adjacent through a joint τ ∋ v; close transitively. An equivalence class of slots is
//! a *vertex copy*; the top simplices over vertex copies form the decomposed complex, and its
//! connected components (top simplices sharing a vertex copy, equivalently joined by a chain of
//! joints) are the *IQM components*. So vertex v is split into one copy per class of top
//! simplices of its star that are manifold-connected around v, and nothing else is cut:
//! - every component is regular (joints join simplices of one dimension) and an initial
//!   quasi-manifold: the star of a vertex copy is, by construction, one manifold-connected
//!   class, and a joint keeps exactly two cofaces after the split;
//! - the decomposition depends only on the complex (joints and stars are defined from it), not
//!   on the order of the input nor on the vertex numbering;
//! - mapping each copy back to its vertex glues the components back into the complex.
//!
//! A vertex with two or more copies is a *split vertex*. Its copies may lie in different
//! components (the pinched pie: two fans at a vertex) or in one component (a pseudo-manifold
//! pinched at a vertex, the survey's Fig. 1b).
//!
//! Decision where the papers are silent for mixed dimensions: a face shared by two top
//! h-simplices that is also in a top simplex of another dimension is not a joint (the domain is
//! not manifold there), so the two are not pasted along it.
//!
//! Algorithm, O(S log S) for S = Σ_σ (dim σ + 1) slots (a sort of the facets; linear apart from
//! it), plus the joint test below:
//! 1. For each h ≥ 1, list the facets of the top h-simplices and sort them; a facet listed by
//!    exactly two top h-simplices is a joint candidate.
//! 2. A candidate τ is a joint unless it is a face of a top simplex of higher dimension: scanned
//!    among the higher-dimensional top simplices at the vertex of τ having fewest of them
//!    (nothing to scan on a pure mesh).
//! 3. Union-find on slots (the vertices of τ in both simplices) and on top simplices.
//! 4. Number components (dimension descending, then by their first top simplex in
//!    lexicographic order), their top simplices in that order, and copies per component in
//!    order of first appearance; build adjacencies by sorting the facets over copy ids.
//!
//! `count(p)` needs n_p, which the decomposition does not hold: the build also counts the
//! closure once (O(Σ_p (p+1) n_p log n_p), the same as the IG's build) and keeps only the
//! counts.
//!
//! # Layout (flat arrays, ids `u32`, `NONE = u32::MAX`)
//! - `tops[k]`: the top k-simplices as k + 1 copy ids (entry j is the copy of the simplex's
//!   j-th smallest vertex), grouped by component: component i owns rows
//!   `comp_top_start[i]..` up to the next component of the same dimension. This is each
//!   component's extended IA: R_{k,0} over copies, local id = copy − `comp_copy_start[i]`.
//! - `adj[k]` (k ≥ 1): k + 1 entries per top k-simplex; entry j is the top k-simplex of the same
//!   component sharing the facet opposite entry j (R_{k,k}), `NONE` when there is none. A facet
//!   over copies that three or more top simplices of one component share would also get
//!   `NONE` (counted by [`Iqm::crowded_facets`]; never observed). Star walks never need such
//!   a facet: every joint keeps exactly two cofaces, and joints alone connect a copy's star.
//! - `copy_top[c]`: one top simplex in the star of copy c (the extension R*_{0,k}).
//! - `copy_vertex[c]`, `copy_comp[c]`: the vertex copy c stands for, and its component.
//! - Hypergraph: `split_vertices[a]` with `hyper_offsets`/`hyper_copies` (CSR) listing the
//!   copies of hyperarc a; `vertex_ref[v]` is the only copy of a vertex that is not split, or
//!   `SPLIT | a` for split vertex v on hyperarc a (the hyperarc of a copy c is that of
//!   `copy_vertex[c]`).
//!
//! # Storage (as the survey counts it; bits: none)
//! - each component: 1 reference to its extended IA;
//! - each top k-simplex: k + 1 vertex references and, for k ≥ 1, k + 1 adjacency references;
//! - each vertex copy: 1 reference to a top simplex of its star (the IA extension);
//! - each hyperarc: its split vertex and one reference per copy;
//! - each copy of a split vertex: its component and its hyperarc (2 references).
//!
//! Not counted (in the real bytes): `copy_vertex`, `copy_comp` and `vertex_ref` for vertices
//! that are not split (there, copy and vertex coincide in the paper's model), the component
//! offsets, and the per-dimension simplex counts.
//!
//! # Cost of each relation
//! The API addresses a simplex σ by vertex ids and this structure stores no simplex index, so
//! every query first *locates* σ: it walks the star of a vertex v = σ\[0\] (every copy of v, and
//! in each component the top simplices around the copy by adjacencies through facets containing
//! it) and keeps the top simplices containing σ: O(n_v · d), n_v = number of top simplices in
//! the star of v. After that, with the survey's Table 2:
//! - R_{p,q}, q < p (boundary): the q-faces of σ, O(C(p+1, q+1) · q): optimal.
//! - R_{0,q}, q > 0: the q-faces through v of the top simplices of the star: optimal (linear in
//!   the star walked).
//! - R_{p,q}, 0 < p < q (co-boundary of a non-vertex simplex): **sub-optimal**, O(n_v): the star
//!   of σ is not manifold-connected inside a component (it may span several components), so it
//!   is found by filtering the whole star of v. R_{d−1,d} is optimal in the paper once σ is given
//!   as a facet of a top simplex (one adjacency); addressed by vertex ids it is O(n_v) too.
//! - R_{p,p}, p > 0 (adjacency): **sub-optimal**, O(n_{v0} + n_{v1}) for two vertices v0, v1
//!   of σ (every facet of σ contains one of them): R_{1,1} and R_{2,2} as in Table 2, and every
//!   R_{p,p} with p below the dimension of some top simplex. For a top k-simplex, R_{k,k} within
//!   its component is the k + 1 adjacency entries, but other components may share its facets.
//! - R_{0,0}: the other vertices of the top simplices in the star of v: optimal.
//! - Output rows are deduplicated by one sort, O(m log m) for m faces produced.
//!
//! Queries keep no state in the structure: "visited" marks are a per-query hash set.

use crate::store::Arr;
use rustc_hash::FxHashSet;

use super::common::{IdSet, IdStack, UnionFind, faces_containing};
use super::common::{
    try_closure, try_copy, try_iota, try_order, try_push, try_vec, try_with_capacity,
};
use super::nav::{NavBase, NavIndex};
use super::{BuildError, to_u32};
use crate::complex::table::id_bits;
use crate::complex::{Complex, SimplexTable, is_subset, sort_dedup_rows};
use crate::relation::{QueryError, Storage, StructureKind, Topology};

const KIND: StructureKind = StructureKind::Iqm;
const NONE: u32 = u32::MAX;
/// Flag on `vertex_ref`: the rest is a hyperarc index, not a copy id.
const SPLIT: u32 = 1 << 31;

/// The IQM decomposition of a complex with its extended-IA components and hypergraph.
#[derive(Debug, Clone)]
pub struct Iqm {
    n: u32,
    counts: Vec<usize>,
    tops: Vec<Arr<u32>>,
    adj: Vec<Arr<u32>>,
    comp_dim: Arr<u8>,
    comp_top_start: Arr<u32>,
    comp_copy_start: Arr<u32>,
    copy_vertex: Arr<u32>,
    copy_comp: Arr<u32>,
    copy_top: Arr<u32>,
    vertex_ref: Arr<u32>,
    split_vertices: Arr<u32>,
    hyper_offsets: Arr<u32>,
    hyper_copies: Arr<u32>,
    /// Facets over copies shared by three or more top simplices of one component (left without
    /// adjacency). Kept to report, not to use.
    crowded_facets: usize,
    /// Handle bookkeeping: windings, top simplices below d, lazy tables ([`super::nav`]).
    pub(crate) nav: NavIndex,
}

/// One IQM component, self-contained: its top simplices over local vertex ids `0..m`, and the
/// original vertex id of each local id.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ComponentPiece {
    /// Dimension of the component (of its top simplices).
    pub dimension: usize,
    /// `dimension + 1` local ids per top simplex; row j's entries follow the ascending order of
    /// the original ids they stand for.
    pub tops: Vec<u32>,
    /// `original[local]`: the original vertex id of each local vertex (a vertex copy).
    pub original: Vec<u32>,
    /// Global id of local vertex 0 (copies are numbered component after component).
    pub first_copy: u32,
}

/// The decomposition as plain arrays (for export and writers).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Decomposition {
    /// Number of vertices of the original complex.
    pub vertex_count: u32,
    /// Components, one per IQM component.
    pub components: Vec<ComponentPiece>,
    /// For each global copy id: the original vertex and the component.
    pub copy_vertex: Vec<u32>,
    /// Original vertex of each global copy id.
    pub copy_component: Vec<u32>,
    /// The split vertices (two or more copies), ascending; the copies of `split_vertices[a]` are
    /// `split_copies[split_offsets[a]..split_offsets[a + 1]]`, ascending global copy ids.
    pub split_vertices: Vec<u32>,
    /// Component of each global copy id.
    pub split_offsets: Vec<u32>,
    /// Start of each split vertex's copies in `split_copies` (one more entry than split vertices).
    pub split_copies: Vec<u32>,
}

/// Rows of `arity - 1` ids: the facets of every row of `rows` (facet j omits entry j), each
/// sorted ascending.
fn facet_rows(rows: &[u32], arity: usize, sort_each: bool) -> Result<Vec<u32>, BuildError> {
    let mut out = try_with_capacity(KIND, rows.len() * (arity - 1), "facet rows")?;
    for r in rows.chunks_exact(arity) {
        for skip in 0..arity {
            let start = out.len();
            out.extend(
                r.iter()
                    .enumerate()
                    .filter(|&(j, _)| j != skip)
                    .map(|(_, &v)| v),
            );
            if sort_each {
                out[start..].sort_unstable();
            }
        }
    }
    Ok(out)
}

/// Row indices of `rows` (fixed `width`, `width >= 1`) in lexicographic order of the rows.
fn sorted_order(rows: &[u32], width: usize) -> Result<Vec<u32>, BuildError> {
    let n = rows.len() / width;
    let row = |i: u32| &rows[i as usize * width..(i as usize + 1) * width];
    let bits = id_bits(rows.iter().copied().max().unwrap_or(0));
    let order = try_order(KIND, n, width as u32 * bits, |i| {
        row(i).iter().fold(0u64, |acc, &v| (acc << bits) | v as u64)
    })?;
    Ok(match order {
        Some(order) => order,
        None => {
            let mut order = try_iota(KIND, n, "rows")?;
            order.sort_unstable_by(|&a, &b| row(a).cmp(row(b)).then(a.cmp(&b)));
            order
        }
    })
}

/// Calls `f` with each run of equal rows (as indices in `order`).
fn for_each_group(rows: &[u32], width: usize, order: &[u32], mut f: impl FnMut(&[u32])) {
    let row = |i: u32| &rows[i as usize * width..(i as usize + 1) * width];
    let mut start = 0;
    while start < order.len() {
        let mut end = start + 1;
        while end < order.len() && row(order[end]) == row(order[start]) {
            end += 1;
        }
        f(&order[start..end]);
        start = end;
    }
}

/// Appends the q-faces of `top` (ascending) that contain `sigma` (ascending subset of `top`).
/// No allocation: queries call this once per top simplex of a star.
fn push_cofaces(top: &[u32], sigma: &[u32], q: usize, out: &mut Vec<u32>) {
    faces_containing(top, sigma, q, |f| out.extend_from_slice(f));
}

/// Appends every (q+1)-subset of `s` (ascending).
fn push_subsets(s: &[u32], q: usize, out: &mut Vec<u32>) {
    faces_containing(s, &[], q, |f| out.extend_from_slice(f));
}

impl Iqm {
    /// Computes the standard decomposition and encodes it (see the module doc for the
    /// algorithm). O(S log S) for S slots, plus the joint test.
    pub fn build(complex: &Complex) -> Result<Iqm, BuildError> {
        let n = complex.vertex_count();
        let d = complex.dimension();
        let tables: Vec<&SimplexTable> = (0..=d).map(|k| complex.tops(k)).collect();
        let mut slot_base = vec![0usize; d + 2];
        let mut top_base = vec![0usize; d + 2];
        for k in 0..=d {
            slot_base[k + 1] = slot_base[k] + tables[k].len() * (k + 1);
            top_base[k + 1] = top_base[k] + tables[k].len();
        }
        // Copies get the `SPLIT` bit free; slots bound the copies.
        to_u32(KIND, slot_base[d + 1] * 2, "vertex slots (twice)")?;
        let dim_of = |g: u32| (0..=d).rfind(|&k| top_base[k] <= g as usize).unwrap();

        // vstar: top simplices of dimension >= 2 at each vertex, dimension descending, for the
        // test "is this facet of an h-simplex inside a higher-dimensional top simplex".
        let mut vstar_off = try_vec(KIND, 0u32, n as usize + 1, "vertex star offsets")?;
        for t in tables.iter().skip(2) {
            for &v in t.as_flat() {
                vstar_off[v as usize + 1] += 1;
            }
        }
        for v in 0..n as usize {
            vstar_off[v + 1] += vstar_off[v];
        }
        let mut fill = try_copy(KIND, &vstar_off, "vertex star offsets")?;
        let mut vstar = try_vec(KIND, 0u32, vstar_off[n as usize] as usize, "vertex stars")?;
        for k in (2..=d).rev() {
            for (i, s) in tables[k].iter().enumerate() {
                for &v in s {
                    vstar[fill[v as usize] as usize] = (top_base[k] + i) as u32;
                    fill[v as usize] += 1;
                }
            }
        }
        let in_higher_top = |tau: &[u32], k: usize| -> bool {
            let hub = *tau
                .iter()
                .min_by_key(|&&v| vstar_off[v as usize + 1] - vstar_off[v as usize])
                .unwrap();
            let list =
                &vstar[vstar_off[hub as usize] as usize..vstar_off[hub as usize + 1] as usize];
            for &g in list {
                let kg = dim_of(g);
                if kg <= k {
                    break;
                }
                if is_subset(tau, tables[kg].get(g as usize - top_base[kg])) {
                    return true;
                }
            }
            false
        };

        let mut slots = UnionFind::try_new(KIND, slot_base[d + 1], "vertex slots")?;
        let mut tops_uf = UnionFind::try_new(KIND, top_base[d + 1], "top simplices")?;
        for k in 1..=d {
            let w = k + 1;
            let facets = facet_rows(tables[k].as_flat(), w, false)?;
            let order = sorted_order(&facets, k)?;
            for_each_group(&facets, k, &order, |group| {
                if group.len() != 2 {
                    return;
                }
                let (r1, r2) = (group[0] as usize, group[1] as usize);
                if in_higher_top(&facets[r1 * k..(r1 + 1) * k], k) {
                    return;
                }
                let (i1, j1, i2, j2) = (r1 / w, r1 % w, r2 / w, r2 % w);
                tops_uf.union((top_base[k] + i1) as u32, (top_base[k] + i2) as u32);
                // Both rows are ascending, so the shared vertices come in the same order.
                let a = (0..w).filter(|&j| j != j1);
                let b = (0..w).filter(|&j| j != j2);
                for (ja, jb) in a.zip(b) {
                    slots.union(
                        (slot_base[k] + i1 * w + ja) as u32,
                        (slot_base[k] + i2 * w + jb) as u32,
                    );
                }
            });
        }

        // Components: dimension descending, then by first top simplex.
        let mut comp_of_root = try_vec(KIND, NONE, top_base[d + 1], "component roots")?;
        let mut comp_dim: Vec<u8> = Vec::new();
        let mut top_comp: Vec<Vec<u32>> = vec![Vec::new(); d + 1];
        for k in (0..=d).rev() {
            for i in 0..tables[k].len() {
                let r = tops_uf.find((top_base[k] + i) as u32) as usize;
                if comp_of_root[r] == NONE {
                    comp_of_root[r] = comp_dim.len() as u32;
                    comp_dim.push(k as u8);
                }
                try_push(KIND, &mut top_comp[k], comp_of_root[r], "top components")?;
            }
        }
        let m = comp_dim.len();
        to_u32(KIND, m, "components")?;

        let mut tops: Vec<Vec<u32>> = vec![Vec::new(); d + 1];
        let mut comp_top_start = vec![0u32; m];
        let mut comp_copy_start = vec![0u32; m + 1];
        let mut copy_of_root = try_vec(KIND, NONE, slot_base[d + 1], "vertex copies")?;
        let mut copy_vertex: Vec<u32> = Vec::new();
        let mut copy_comp: Vec<u32> = Vec::new();
        let mut copy_top: Vec<u32> = Vec::new();
        let mut last_comp = NONE;
        for k in (0..=d).rev() {
            let w = k + 1;
            let mut order = try_iota(KIND, tables[k].len(), "top simplices")?;
            order.sort_by_key(|&i| top_comp[k][i as usize]);
            let mut rows = try_with_capacity(KIND, tables[k].len() * w, "component rows")?;
            for (new_i, &i) in order.iter().enumerate() {
                let comp = top_comp[k][i as usize];
                if comp != last_comp {
                    comp_top_start[comp as usize] = new_i as u32;
                    comp_copy_start[comp as usize] = copy_vertex.len() as u32;
                    last_comp = comp;
                }
                let s = tables[k].get(i as usize);
                for (j, &v) in s.iter().enumerate() {
                    let r = slots.find((slot_base[k] + i as usize * w + j) as u32) as usize;
                    if copy_of_root[r] == NONE {
                        copy_of_root[r] = copy_vertex.len() as u32;
                        try_push(KIND, &mut copy_vertex, v, "vertex copies")?;
                        try_push(KIND, &mut copy_comp, comp, "vertex copies")?;
                        try_push(KIND, &mut copy_top, new_i as u32, "vertex copies")?;
                    }
                    rows.push(copy_of_root[r]);
                }
            }
            tops[k] = rows;
        }
        comp_copy_start[m] = copy_vertex.len() as u32;

        // Adjacency inside components, from facets over copy ids.
        let mut adj: Vec<Vec<u32>> = vec![Vec::new(); d + 1];
        let mut crowded_facets = 0;
        for k in 1..=d {
            let w = k + 1;
            let facets = facet_rows(&tops[k], w, true)?;
            let order = sorted_order(&facets, k)?;
            let mut a = try_vec(KIND, NONE, tops[k].len(), "adjacencies")?;
            for_each_group(&facets, k, &order, |group| match group.len() {
                1 => {}
                2 => {
                    let (r1, r2) = (group[0] as usize, group[1] as usize);
                    a[r1] = (r2 / w) as u32;
                    a[r2] = (r1 / w) as u32;
                }
                _ => crowded_facets += 1,
            });
            adj[k] = a;
        }

        // Hypergraph.
        let mut per_vertex = try_vec(KIND, 0u32, n as usize, "vertex copy counts")?;
        for &v in &copy_vertex {
            per_vertex[v as usize] += 1;
        }
        let mut vertex_ref = try_vec(KIND, NONE, n as usize, "vertex references")?;
        let mut split_vertices = Vec::new();
        let mut hyper_offsets = vec![0u32];
        for v in 0..n {
            if per_vertex[v as usize] >= 2 {
                vertex_ref[v as usize] = SPLIT | split_vertices.len() as u32;
                split_vertices.push(v);
                hyper_offsets.push(hyper_offsets.last().unwrap() + per_vertex[v as usize]);
            }
        }
        let mut hfill: Vec<u32> = hyper_offsets[..split_vertices.len()].to_vec();
        let hyper_len = *hyper_offsets.last().unwrap() as usize;
        let mut hyper_copies = try_vec(KIND, 0u32, hyper_len, "split vertex copies")?;
        for (c, &v) in copy_vertex.iter().enumerate() {
            let v = v as usize;
            let r = vertex_ref[v];
            if r == NONE {
                vertex_ref[v] = c as u32;
            } else if r & SPLIT != 0 {
                let a = (r & !SPLIT) as usize;
                hyper_copies[hfill[a] as usize] = c as u32;
                hfill[a] += 1;
            }
        }
        let counts = try_closure(KIND, complex)?
            .iter()
            .map(SimplexTable::len)
            .collect();
        Ok(Iqm {
            nav: NavIndex::new(KIND, complex)?,
            n,
            counts,
            tops: tops.into_iter().map(Arr::from).collect(),
            adj: adj.into_iter().map(Arr::from).collect(),
            comp_dim: comp_dim.into(),
            comp_top_start: comp_top_start.into(),
            comp_copy_start: comp_copy_start.into(),
            copy_vertex: copy_vertex.into(),
            copy_comp: copy_comp.into(),
            copy_top: copy_top.into(),
            vertex_ref: vertex_ref.into(),
            split_vertices: split_vertices.into(),
            hyper_offsets: hyper_offsets.into(),
            hyper_copies: hyper_copies.into(),
            crowded_facets,
        })
    }

    /// Number of IQM components.
    pub fn component_count(&self) -> usize {
        self.comp_dim.len()
    }

    /// Number of vertex copies (every vertex has at least one).
    pub fn copy_count(&self) -> usize {
        self.copy_vertex.len()
    }

    /// The split vertices (two or more copies), ascending.
    pub fn split_vertices(&self) -> &[u32] {
        &self.split_vertices
    }

    /// The copies of vertex `v` (global copy ids, ascending).
    pub fn copies_of(&self, v: u32) -> &[u32] {
        let r = self.vertex_ref[v as usize];
        if r & SPLIT != 0 {
            let a = (r & !SPLIT) as usize;
            &self.hyper_copies[self.hyper_offsets[a] as usize..self.hyper_offsets[a + 1] as usize]
        } else {
            std::slice::from_ref(&self.vertex_ref[v as usize])
        }
    }

    /// Facets over copies that three or more top simplices of one component share (such facets
    /// get no adjacency entry; the standard decomposition is not known to produce any).
    pub fn crowded_facets(&self) -> usize {
        self.crowded_facets
    }

    /// Dimension of component `i`.
    pub fn component_dimension(&self, i: usize) -> usize {
        self.comp_dim[i] as usize
    }

    /// Rows of component `i` in its dimension's tables.
    fn comp_rows(&self, i: usize) -> std::ops::Range<usize> {
        let k = self.comp_dim[i];
        let start = self.comp_top_start[i] as usize;
        let end = if i + 1 < self.comp_dim.len() && self.comp_dim[i + 1] == k {
            self.comp_top_start[i + 1] as usize
        } else {
            self.tops[k as usize].len() / (k as usize + 1)
        };
        start..end
    }

    fn row(&self, k: usize, t: u32) -> &[u32] {
        &self.tops[k][t as usize * (k + 1)..(t as usize + 1) * (k + 1)]
    }

    /// The decomposition as plain arrays: components over local ids, copies, split vertices.
    pub fn decomposition(&self) -> Decomposition {
        let components = (0..self.component_count())
            .map(|i| {
                let k = self.comp_dim[i] as usize;
                let first = self.comp_copy_start[i];
                let copies = first..self.comp_copy_start[i + 1];
                let rows = self.comp_rows(i);
                let flat = &self.tops[k][rows.start * (k + 1)..rows.end * (k + 1)];
                ComponentPiece {
                    dimension: k,
                    tops: flat.iter().map(|&c| c - first).collect(),
                    original: self.copy_vertex[copies.start as usize..copies.end as usize].to_vec(),
                    first_copy: first,
                }
            })
            .collect();
        Decomposition {
            vertex_count: self.n,
            components,
            copy_vertex: self.copy_vertex.to_vec(),
            copy_component: self.copy_comp.to_vec(),
            split_vertices: self.split_vertices.to_vec(),
            split_offsets: self.hyper_offsets.to_vec(),
            split_copies: self.hyper_copies.to_vec(),
        }
    }

    /// Visits the top simplices in the star of vertex `v`, every copy in turn, walking each
    /// copy's star by adjacencies through facets that contain the copy. Calls `f(k, t)`, which
    /// returns `false` to stop the walk.
    fn walk_star(&self, v: u32, mut f: impl FnMut(usize, u32) -> bool) {
        let mut seen: IdSet = IdSet::default();
        let mut stack = IdStack::default();
        for &c in self.copies_of(v) {
            let k = self.comp_dim[self.copy_comp[c as usize] as usize] as usize;
            seen.clear();
            let t0 = self.copy_top[c as usize];
            seen.insert(t0);
            stack.push(t0);
            while let Some(t) = stack.pop() {
                if !f(k, t) {
                    return;
                }
                if k == 0 {
                    continue;
                }
                let row = self.row(k, t);
                let pos = row
                    .iter()
                    .position(|&x| x == c)
                    .expect("star walk stays at c");
                let a = &self.adj[k][t as usize * (k + 1)..(t as usize + 1) * (k + 1)];
                for (j, &u) in a.iter().enumerate() {
                    if j != pos && u != NONE && seen.insert(u) {
                        stack.push(u);
                    }
                }
            }
        }
    }

    /// Original ids of top k-simplex `t` (ascending by construction).
    fn originals(&self, k: usize, t: u32, buf: &mut Vec<u32>) {
        buf.clear();
        buf.extend(self.row(k, t).iter().map(|&c| self.copy_vertex[c as usize]));
    }

    /// Appends to `found` the top simplices (original ids) of the star of `v` for which `keep`
    /// holds, and their vertex counts to `lens`; with `first_only`, stops at the first one.
    fn star_tops(
        &self,
        v: u32,
        keep: impl Fn(&[u32]) -> bool,
        first_only: bool,
        found: &mut Vec<u32>,
        lens: &mut Vec<usize>,
    ) {
        let mut buf = Vec::with_capacity(self.counts.len());
        self.walk_star(v, |k, t| {
            self.originals(k, t, &mut buf);
            if keep(&buf) {
                found.extend_from_slice(&buf);
                lens.push(k + 1);
                return !first_only;
            }
            true
        });
    }
}

/// Rows of varying length, flat.
fn rows_of<'a>(flat: &'a [u32], lens: &'a [usize]) -> impl Iterator<Item = &'a [u32]> + 'a {
    let mut at = 0;
    lens.iter().map(move |&l| {
        at += l;
        &flat[at - l..at]
    })
}

impl NavBase for Iqm {
    fn nav(&self) -> &NavIndex {
        &self.nav
    }
}

impl Topology for Iqm {
    fn as_navigate(&self) -> Option<&dyn crate::handle::Navigate> {
        Some(self)
    }

    fn kind(&self) -> StructureKind {
        KIND
    }

    fn dimension(&self) -> usize {
        self.counts.len() - 1
    }

    fn vertex_count(&self) -> u32 {
        self.n
    }

    fn count(&self, p: usize) -> usize {
        self.counts.get(p).copied().unwrap_or(0)
    }

    fn top_count(&self, p: usize) -> usize {
        self.tops.get(p).map_or(0, |t| t.len() / (p + 1))
    }

    fn simplices(&self, p: usize, out: &mut Vec<u32>) {
        if p == 0 {
            out.extend(0..self.n);
            return;
        }
        let mut rows = Vec::new();
        let mut buf = Vec::new();
        for k in p..self.tops.len() {
            for t in 0..(self.tops[k].len() / (k + 1)) as u32 {
                self.originals(k, t, &mut buf);
                push_subsets(&buf, p, &mut rows);
            }
        }
        out.extend(sort_dedup_rows(p + 1, rows));
    }

    fn contains(&self, sigma: &[u32]) -> bool {
        // Sized for a mesh vertex's star, so the walk rarely reallocates.
        let (mut found, mut lens) = (Vec::with_capacity(256), Vec::with_capacity(64));
        self.star_tops(
            sigma[0],
            |t| is_subset(sigma, t),
            true,
            &mut found,
            &mut lens,
        );
        !lens.is_empty()
    }

    fn query(&self, sigma: &[u32], q: usize, out: &mut Vec<u32>) -> Result<(), QueryError> {
        let p = sigma.len() - 1;
        // Sized for a mesh vertex's star, so the walk rarely reallocates.
        let (mut found, mut lens) = (Vec::with_capacity(256), Vec::with_capacity(64));
        // Locating σ is all a boundary query needs.
        let first_only = q < p;
        self.star_tops(
            sigma[0],
            |t| is_subset(sigma, t),
            first_only,
            &mut found,
            &mut lens,
        );
        if lens.is_empty() {
            return Err(QueryError::NotInComplex {
                simplex: sigma.to_vec(),
            });
        }
        let mut rows = Vec::with_capacity(256);
        if q < p {
            push_subsets(sigma, q, out);
            return Ok(());
        } else if q > p {
            for t in rows_of(&found, &lens) {
                push_cofaces(t, sigma, q, &mut rows);
            }
        } else if p == 0 {
            rows.extend(found.iter().copied().filter(|&u| u != sigma[0]));
        } else {
            // Every facet of σ contains σ[0] or σ[1].
            let shares_facet =
                |t: &[u32]| t.len() > p && sigma.iter().filter(|v| t.contains(v)).count() >= p;
            found.clear();
            lens.clear();
            self.star_tops(sigma[0], shares_facet, false, &mut found, &mut lens);
            self.star_tops(sigma[1], shares_facet, false, &mut found, &mut lens);
            let mut facet = Vec::with_capacity(p);
            let mut produced = Vec::new();
            for t in rows_of(&found, &lens) {
                for skip in 0..=p {
                    facet.clear();
                    facet.extend(
                        sigma
                            .iter()
                            .enumerate()
                            .filter(|&(j, _)| j != skip)
                            .map(|(_, &v)| v),
                    );
                    if is_subset(&facet, t) {
                        produced.clear();
                        push_cofaces(t, &facet, p, &mut produced);
                        // σ itself is among the cofaces of its facet.
                        for row in produced.chunks_exact(p + 1) {
                            if row != sigma {
                                rows.extend_from_slice(row);
                            }
                        }
                    }
                }
            }
        }
        out.extend(sort_dedup_rows(q + 1, rows));
        Ok(())
    }

    fn storage(&self) -> Storage {
        let mut integers = self.comp_dim.len() as u64 + self.copy_vertex.len() as u64;
        for (k, t) in self.tops.iter().enumerate() {
            let rows = (t.len() / (k + 1)) as u64;
            integers += rows * (k as u64 + 1) * if k >= 1 { 2 } else { 1 };
        }
        let split_copies = self.hyper_copies.len() as u64;
        integers += self.split_vertices.len() as u64 + split_copies + 2 * split_copies;
        let bytes = self
            .tops
            .iter()
            .chain(self.adj.iter())
            .map(|v| v.capacity() * 4)
            .sum::<usize>()
            + self.comp_dim.capacity()
            + [
                &self.comp_top_start,
                &self.comp_copy_start,
                &self.copy_vertex,
                &self.copy_comp,
                &self.copy_top,
                &self.vertex_ref,
                &self.split_vertices,
                &self.hyper_offsets,
                &self.hyper_copies,
            ]
            .iter()
            .map(|v| v.capacity() * 4)
            .sum::<usize>()
            + self.counts.capacity() * 8;
        Storage {
            integers,
            bits: 0,
            bytes: bytes as u64,
        }
    }

    fn summary(&self) -> Vec<(&'static str, u64)> {
        vec![
            ("components", self.component_count() as u64),
            ("split_vertices", self.split_vertices().len() as u64),
            ("vertex_copies", self.copy_count() as u64),
        ]
    }

    fn validate(&self) -> Result<(), String> {
        let m = self.component_count();
        let c_total = self.copy_vertex.len();
        if self.copy_comp.len() != c_total || self.copy_top.len() != c_total {
            return Err("copy arrays differ in length".into());
        }
        // Occurrences of each copy among top simplices, to compare with its star walk.
        let mut occurrences = vec![0u32; c_total];
        for i in 0..m {
            let k = self.comp_dim[i] as usize;
            let copies = self.comp_copy_start[i]..self.comp_copy_start[i + 1];
            if copies.is_empty() {
                return Err(format!("component {i} has no vertex"));
            }
            for t in self.comp_rows(i) {
                let row = self.row(k, t as u32);
                let orig: Vec<u32> = row.iter().map(|&c| self.copy_vertex[c as usize]).collect();
                if orig.windows(2).any(|w| w[0] >= w[1]) {
                    return Err(format!(
                        "top {k}-simplex {orig:?} of component {i}: vertices not ascending"
                    ));
                }
                for &c in row {
                    if !copies.contains(&c) {
                        return Err(format!(
                            "top {k}-simplex {orig:?} of component {i} uses copy {c} of another component"
                        ));
                    }
                    if self.copy_comp[c as usize] as usize != i {
                        return Err(format!("copy {c} does not name component {i}"));
                    }
                    occurrences[c as usize] += 1;
                }
                if k >= 1 {
                    let a = &self.adj[k][t * (k + 1)..(t + 1) * (k + 1)];
                    for (j, &u) in a.iter().enumerate() {
                        if u == NONE {
                            continue;
                        }
                        if !self.comp_rows(i).contains(&(u as usize)) {
                            return Err(format!("{orig:?}: adjacency {j} leaves component {i}"));
                        }
                        let other = self.row(k, u);
                        let shared = row
                            .iter()
                            .enumerate()
                            .filter(|&(jj, _)| jj != j)
                            .all(|(_, c)| other.contains(c));
                        let back = self.adj[k][u as usize * (k + 1)..(u as usize + 1) * (k + 1)]
                            .contains(&(t as u32));
                        if !shared || !back || u as usize == t {
                            return Err(format!(
                                "{orig:?}: adjacency {j} is not a symmetric facet neighbour"
                            ));
                        }
                    }
                }
            }
        }
        for c in 0..c_total {
            let comp = self.copy_comp[c] as usize;
            let k = self.comp_dim[comp] as usize;
            let t0 = self.copy_top[c];
            if !self.comp_rows(comp).contains(&(t0 as usize))
                || !self.row(k, t0).contains(&(c as u32))
            {
                return Err(format!("copy {c}: its star reference does not contain it"));
            }
        }
        let mut per_vertex = vec![0u32; self.n as usize];
        for &v in &self.copy_vertex {
            if v >= self.n {
                return Err(format!("copy of vertex {v} out of range"));
            }
            per_vertex[v as usize] += 1;
        }
        let mut walked = vec![0u32; c_total];
        for v in 0..self.n {
            if per_vertex[v as usize] == 0 {
                return Err(format!("vertex {v} has no copy"));
            }
            let copies = self.copies_of(v);
            if copies.len() != per_vertex[v as usize] as usize {
                return Err(format!(
                    "vertex {v}: hypergraph lists {} copies, components hold {}",
                    copies.len(),
                    per_vertex[v as usize]
                ));
            }
            if (copies.len() >= 2) != self.split_vertices.binary_search(&v).is_ok() {
                return Err(format!(
                    "vertex {v}: split status disagrees with its copies"
                ));
            }
            for &c in copies {
                if self.copy_vertex[c as usize] != v {
                    return Err(format!("vertex {v} lists copy {c} of another vertex"));
                }
            }
            for &c in copies {
                let k = self.comp_dim[self.copy_comp[c as usize] as usize] as usize;
                let mut count = 0;
                let mut seen = FxHashSet::default();
                seen.insert(self.copy_top[c as usize]);
                let mut stack = vec![self.copy_top[c as usize]];
                while let Some(t) = stack.pop() {
                    count += 1;
                    if k == 0 {
                        continue;
                    }
                    let row = self.row(k, t);
                    let pos = row.iter().position(|&x| x == c).unwrap();
                    let a = &self.adj[k][t as usize * (k + 1)..(t as usize + 1) * (k + 1)];
                    for (j, &u) in a.iter().enumerate() {
                        if j != pos && u != NONE && seen.insert(u) {
                            stack.push(u);
                        }
                    }
                }
                walked[c as usize] = count;
            }
        }
        if let Some(c) = (0..c_total).find(|&c| walked[c] != occurrences[c]) {
            return Err(format!(
                "copy {c} of vertex {}: {} top simplices hold it, its star walk reaches {}",
                self.copy_vertex[c], occurrences[c], walked[c]
            ));
        }
        if self.counts.first().copied() != Some(self.n as usize) {
            return Err("vertex count disagrees with n_0".into());
        }
        Ok(())
    }
}

crate::persist_fields!(Iqm {
    n,
    counts,
    tops,
    adj,
    comp_dim,
    comp_top_start,
    comp_copy_start,
    copy_vertex,
    copy_comp,
    copy_top,
    vertex_ref,
    split_vertices,
    hyper_offsets,
    hyper_copies,
    crowded_facets, nav
} check |s| {
    if s.counts.is_empty() || s.tops.len() != s.adj.len() || s.vertex_ref.len() != s.n as usize {
        return Err("per-dimension or per-vertex arrays of the wrong length".into());
    }
    Ok(())
});
