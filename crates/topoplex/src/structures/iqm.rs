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
//!   Rows are kept ascending (the queries test subsets by merging); the input winding of each
//!   top simplex lives in the handle index, and [`Iqm::decomposition`] writes every component's
//!   rows in it, so a component written to a file keeps the input's orientation.
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

use crate::mapped::Arr;

use super::common::{IdSet, IdStack, Scratch, UnionFind, faces_containing, too_large};
use super::common::{
    try_closure_counts, try_copy, try_iota, try_order, try_push, try_vec, try_with_capacity,
};
use super::nav::NavIndex;
use super::{BuildError, to_u32};
use crate::complex::table::id_bits;
use crate::complex::{Complex, SimplexTable, is_subset, push_facet, sort_dedup_rows};
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
    /// `dimension + 1` local ids per top simplex, each row in the vertex order of the top
    /// simplex's first listing in the input (its winding); rows in lexicographic order of their
    /// original ids.
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
            push_facet(r, skip, &mut out);
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

/// The top simplices of the complex, exploded: top k-simplex i is global top
/// `top_base[k] + i`, and its j-th vertex (ascending) is slot `slot_base[k] + i·(k+1) + j`.
struct Exploded<'a> {
    tables: Vec<&'a SimplexTable>,
    slot_base: Vec<usize>,
    top_base: Vec<usize>,
}

impl<'a> Exploded<'a> {
    fn new(complex: &'a Complex) -> Exploded<'a> {
        let d = complex.dimension();
        let tables: Vec<&SimplexTable> = (0..=d).map(|k| complex.tops(k)).collect();
        let mut slot_base = vec![0usize; d + 2];
        let mut top_base = vec![0usize; d + 2];
        for k in 0..=d {
            slot_base[k + 1] = slot_base[k] + tables[k].len() * (k + 1);
            top_base[k + 1] = top_base[k] + tables[k].len();
        }
        Exploded {
            tables,
            slot_base,
            top_base,
        }
    }

    fn dimension(&self) -> usize {
        self.tables.len() - 1
    }

    fn slots(&self) -> usize {
        self.slot_base[self.dimension() + 1]
    }

    fn top_total(&self) -> usize {
        self.top_base[self.dimension() + 1]
    }

    /// Dimension of global top `g`.
    fn dim_of(&self, g: u32) -> usize {
        (0..=self.dimension())
            .rfind(|&k| self.top_base[k] <= g as usize)
            .unwrap()
    }
}

/// Step 2 of the algorithm: for each vertex, the top simplices of dimension ≥ 2 at it,
/// dimension descending (CSR), to tell whether a facet of a top h-simplex lies in a top simplex
/// of higher dimension.
struct HigherTops {
    offsets: Vec<u32>,
    tops: Vec<u32>,
}

impl HigherTops {
    fn new(x: &Exploded, n: u32) -> Result<HigherTops, BuildError> {
        let mut offsets = try_vec(KIND, 0u32, n as usize + 1, "vertex star offsets")?;
        for t in x.tables.iter().skip(2) {
            for &v in t.as_flat() {
                offsets[v as usize + 1] += 1;
            }
        }
        for v in 0..n as usize {
            offsets[v + 1] += offsets[v];
        }
        let mut fill = try_copy(KIND, &offsets, "vertex star offsets")?;
        let mut tops = try_vec(KIND, 0u32, offsets[n as usize] as usize, "vertex stars")?;
        for k in (2..=x.dimension()).rev() {
            for (i, s) in x.tables[k].iter().enumerate() {
                for &v in s {
                    tops[fill[v as usize] as usize] = (x.top_base[k] + i) as u32;
                    fill[v as usize] += 1;
                }
            }
        }
        Ok(HigherTops { offsets, tops })
    }

    /// Whether `tau`, a facet of a top k-simplex, is a face of a top simplex of dimension
    /// above k: scans the higher tops at the vertex of `tau` having fewest.
    fn contain(&self, x: &Exploded, tau: &[u32], k: usize) -> bool {
        let at = |v: u32| self.offsets[v as usize] as usize..self.offsets[v as usize + 1] as usize;
        let hub = *tau.iter().min_by_key(|&&v| at(v).len()).unwrap();
        for &g in &self.tops[at(hub)] {
            let kg = x.dim_of(g);
            if kg <= k {
                break;
            }
            if is_subset(tau, x.tables[kg].get(g as usize - x.top_base[kg])) {
                return true;
            }
        }
        false
    }
}

/// Steps 1–3: pastes top simplices along joints. Returns the union-finds over slots and over
/// global tops.
fn paste_joints(x: &Exploded, higher: &HigherTops) -> Result<(UnionFind, UnionFind), BuildError> {
    let mut slots =
        UnionFind::try_new(x.slots()).map_err(|b| too_large(KIND, b, "vertex slots"))?;
    let mut tops_uf =
        UnionFind::try_new(x.top_total()).map_err(|b| too_large(KIND, b, "top simplices"))?;
    for k in 1..=x.dimension() {
        let w = k + 1;
        let facets = facet_rows(x.tables[k].as_flat(), w, false)?;
        let order = sorted_order(&facets, k)?;
        for_each_group(&facets, k, &order, |group| {
            if group.len() != 2 {
                return;
            }
            let (r1, r2) = (group[0] as usize, group[1] as usize);
            if higher.contain(x, &facets[r1 * k..(r1 + 1) * k], k) {
                return;
            }
            let (i1, j1, i2, j2) = (r1 / w, r1 % w, r2 / w, r2 % w);
            tops_uf.union((x.top_base[k] + i1) as u32, (x.top_base[k] + i2) as u32);
            // Both rows are ascending, so the shared vertices come in the same order.
            let a = (0..w).filter(|&j| j != j1);
            let b = (0..w).filter(|&j| j != j2);
            for (ja, jb) in a.zip(b) {
                slots.union(
                    (x.slot_base[k] + i1 * w + ja) as u32,
                    (x.slot_base[k] + i2 * w + jb) as u32,
                );
            }
        });
    }
    Ok((slots, tops_uf))
}

/// Step 4a: numbers the components, dimension descending, then by first top simplex. Returns
/// each component's dimension and, per dimension, the component of each top simplex.
fn number_components(
    x: &Exploded,
    tops_uf: &mut UnionFind,
) -> Result<(Vec<u8>, Vec<Vec<u32>>), BuildError> {
    let d = x.dimension();
    let mut comp_of_root = try_vec(KIND, NONE, x.top_total(), "component roots")?;
    let mut comp_dim: Vec<u8> = Vec::new();
    let mut top_comp: Vec<Vec<u32>> = vec![Vec::new(); d + 1];
    for k in (0..=d).rev() {
        for i in 0..x.tables[k].len() {
            let r = tops_uf.find((x.top_base[k] + i) as u32) as usize;
            if comp_of_root[r] == NONE {
                comp_of_root[r] = comp_dim.len() as u32;
                comp_dim.push(k as u8);
            }
            try_push(KIND, &mut top_comp[k], comp_of_root[r], "top components")?;
        }
    }
    Ok((comp_dim, top_comp))
}

/// Step 4b's output: top simplices over copy ids, grouped by component, and the copies.
#[derive(Default)]
struct Copies {
    tops: Vec<Vec<u32>>,
    comp_top_start: Vec<u32>,
    comp_copy_start: Vec<u32>,
    copy_vertex: Vec<u32>,
    copy_comp: Vec<u32>,
    copy_top: Vec<u32>,
}

/// Step 4b: rows of each dimension grouped by component (lexicographic within one), each slot
/// class numbered as a copy in order of first appearance.
fn number_copies(
    x: &Exploded,
    slots: &mut UnionFind,
    top_comp: &[Vec<u32>],
    m: usize,
) -> Result<Copies, BuildError> {
    let d = x.dimension();
    let mut out = Copies {
        tops: vec![Vec::new(); d + 1],
        comp_top_start: vec![0u32; m],
        comp_copy_start: vec![0u32; m + 1],
        ..Copies::default()
    };
    let mut copy_of_root = try_vec(KIND, NONE, x.slots(), "vertex copies")?;
    let mut last_comp = NONE;
    for k in (0..=d).rev() {
        let w = k + 1;
        let mut order = try_iota(KIND, x.tables[k].len(), "top simplices")?;
        order.sort_by_key(|&i| top_comp[k][i as usize]);
        let mut rows = try_with_capacity(KIND, x.tables[k].len() * w, "component rows")?;
        for (new_i, &i) in order.iter().enumerate() {
            let comp = top_comp[k][i as usize];
            if comp != last_comp {
                out.comp_top_start[comp as usize] = new_i as u32;
                out.comp_copy_start[comp as usize] = out.copy_vertex.len() as u32;
                last_comp = comp;
            }
            for (j, &v) in x.tables[k].get(i as usize).iter().enumerate() {
                let r = slots.find((x.slot_base[k] + i as usize * w + j) as u32) as usize;
                if copy_of_root[r] == NONE {
                    copy_of_root[r] = out.copy_vertex.len() as u32;
                    try_push(KIND, &mut out.copy_vertex, v, "vertex copies")?;
                    try_push(KIND, &mut out.copy_comp, comp, "vertex copies")?;
                    try_push(KIND, &mut out.copy_top, new_i as u32, "vertex copies")?;
                }
                rows.push(copy_of_root[r]);
            }
        }
        out.tops[k] = rows;
    }
    out.comp_copy_start[m] = out.copy_vertex.len() as u32;
    Ok(out)
}

/// Step 4c: adjacency inside components, from the facets over copy ids. Returns the adjacency
/// per dimension and the number of crowded facets.
fn component_adjacency(tops: &[Vec<u32>]) -> Result<(Vec<Vec<u32>>, usize), BuildError> {
    let mut adj: Vec<Vec<u32>> = vec![Vec::new(); tops.len()];
    let mut crowded_facets = 0;
    for k in 1..tops.len() {
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
    Ok((adj, crowded_facets))
}

/// The hypergraph: `vertex_ref`, split vertices and the CSR of their copies.
struct Hypergraph {
    vertex_ref: Vec<u32>,
    split_vertices: Vec<u32>,
    offsets: Vec<u32>,
    copies: Vec<u32>,
}

/// Step 4d: the hypergraph of split vertices from the copies' vertices.
fn hypergraph(n: u32, copy_vertex: &[u32]) -> Result<Hypergraph, BuildError> {
    let mut per_vertex = try_vec(KIND, 0u32, n as usize, "vertex copy counts")?;
    for &v in copy_vertex {
        per_vertex[v as usize] += 1;
    }
    let mut vertex_ref = try_vec(KIND, NONE, n as usize, "vertex references")?;
    let mut split_vertices = Vec::new();
    let mut offsets = vec![0u32];
    for v in 0..n {
        if per_vertex[v as usize] >= 2 {
            vertex_ref[v as usize] = SPLIT | split_vertices.len() as u32;
            split_vertices.push(v);
            offsets.push(offsets.last().unwrap() + per_vertex[v as usize]);
        }
    }
    let mut fill: Vec<u32> = offsets[..split_vertices.len()].to_vec();
    let copies_len = *offsets.last().unwrap() as usize;
    let mut copies = try_vec(KIND, 0u32, copies_len, "split vertex copies")?;
    for (c, &v) in copy_vertex.iter().enumerate() {
        let v = v as usize;
        let r = vertex_ref[v];
        if r == NONE {
            vertex_ref[v] = c as u32;
        } else if r & SPLIT != 0 {
            let a = (r & !SPLIT) as usize;
            copies[fill[a] as usize] = c as u32;
            fill[a] += 1;
        }
    }
    Ok(Hypergraph {
        vertex_ref,
        split_vertices,
        offsets,
        copies,
    })
}

impl Iqm {
    /// Computes the standard decomposition and encodes it (see the module doc for the
    /// algorithm). O(S log S) for S slots, plus the joint test.
    pub fn build(complex: &Complex) -> Result<Iqm, BuildError> {
        let n = complex.vertex_count();
        let x = Exploded::new(complex);
        // Copies get the `SPLIT` bit free; slots bound the copies.
        to_u32(KIND, x.slots() * 2, "vertex slots (twice)")?;
        let higher = HigherTops::new(&x, n)?;
        let (mut slots, mut tops_uf) = paste_joints(&x, &higher)?;
        let (comp_dim, top_comp) = number_components(&x, &mut tops_uf)?;
        let m = comp_dim.len();
        to_u32(KIND, m, "components")?;
        let copies = number_copies(&x, &mut slots, &top_comp, m)?;
        let (adj, crowded_facets) = component_adjacency(&copies.tops)?;
        let hyper = hypergraph(n, &copies.copy_vertex)?;
        let counts = try_closure_counts(KIND, complex)?;
        Ok(Iqm {
            nav: NavIndex::new(KIND, complex)?,
            n,
            counts,
            tops: copies.tops.into_iter().map(Arr::from).collect(),
            adj: adj.into_iter().map(Arr::from).collect(),
            comp_dim: comp_dim.into(),
            comp_top_start: copies.comp_top_start.into(),
            comp_copy_start: copies.comp_copy_start.into(),
            copy_vertex: copies.copy_vertex.into(),
            copy_comp: copies.copy_comp.into(),
            copy_top: copies.copy_top.into(),
            vertex_ref: hyper.vertex_ref.into(),
            split_vertices: hyper.split_vertices.into(),
            hyper_offsets: hyper.offsets.into(),
            hyper_copies: hyper.copies.into(),
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
                let mut tops = Vec::with_capacity(self.comp_rows(i).len() * (k + 1));
                for t in self.comp_rows(i) {
                    self.push_row_as_given(k, t as u32, &mut tops);
                }
                for c in &mut tops {
                    *c -= first;
                }
                ComponentPiece {
                    dimension: k,
                    tops,
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

    /// Appends the copies of top k-simplex `t` in the vertex order of its first listing (its
    /// winding): the stored row follows ascending original ids, the handle index keeps the
    /// permutation to the input. O(k log n_k) (locating the row's top id).
    fn push_row_as_given(&self, k: usize, t: u32, out: &mut Vec<u32>) {
        use crate::relation::handle::Navigate;
        let row = self.row(k, t);
        let mut orig = [0u32; crate::complex::MAX_DIMENSION + 1];
        for (o, &c) in orig.iter_mut().zip(row) {
            *o = self.copy_vertex[c as usize];
        }
        let orig = &orig[..row.len()];
        let given = self
            .locate(orig)
            .and_then(|h| self.top_id(h))
            .ok()
            .flatten()
            .and_then(|id| self.top_as_given(id).ok());
        match given {
            Some(given) => out.extend(
                given
                    .iter()
                    .map(|v| row[orig.binary_search(v).expect("same vertex set")]),
            ),
            // Unreachable for a validated structure: every row is a top simplex of the complex.
            None => out.extend_from_slice(row),
        }
    }

    /// Visits the top simplices in the star of vertex `v`, every copy in turn, walking each
    /// copy's star by adjacencies through facets that contain the copy. Calls `f(k, t)`, which
    /// returns `false` to stop the walk.
    fn walk_star(&self, v: u32, mut f: impl FnMut(usize, u32) -> bool) {
        let mut seen: IdSet = IdSet::default();
        let mut stack = IdStack::default();
        for &c in self.copies_of(v) {
            if !self.walk_copy_star(c, &mut seen, &mut stack, &mut f) {
                return;
            }
        }
    }

    /// Visits the top simplices in the star of copy `c` from `copy_top[c]`, by adjacencies
    /// through facets containing `c`; `false` when `f` stopped the walk.
    fn walk_copy_star(
        &self,
        c: u32,
        seen: &mut IdSet,
        stack: &mut IdStack,
        f: &mut impl FnMut(usize, u32) -> bool,
    ) -> bool {
        let k = self.comp_dim[self.copy_comp[c as usize] as usize] as usize;
        seen.clear();
        let t0 = self.copy_top[c as usize];
        seen.insert(t0);
        stack.push(t0);
        while let Some(t) = stack.pop() {
            if !f(k, t) {
                while stack.pop().is_some() {}
                return false;
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
        true
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
        let mut buf = [0u32; crate::complex::MAX_DIMENSION + 1];
        self.walk_star(v, |k, t| {
            let buf = &mut buf[..k + 1];
            for (b, &c) in buf.iter_mut().zip(self.row(k, t)) {
                *b = self.copy_vertex[c as usize];
            }
            if keep(buf) {
                found.extend_from_slice(buf);
                lens.push(k + 1);
                return !first_only;
            }
            true
        });
    }
}

/// Appends the distinct rows of `rows` (width `w`) to `out`, in lexicographic order. Sorts
/// row indices in this thread's scratch: no allocation once it is warm.
fn sort_dedup_rows_into(w: usize, rows: &[u32], out: &mut Vec<u32>) {
    let row = |i: u32| &rows[i as usize * w..(i as usize + 1) * w];
    let mut order = Scratch::<Vec<u32>>::take();
    order.extend(0..(rows.len() / w) as u32);
    order.sort_unstable_by(|&a, &b| row(a).cmp(row(b)));
    let mut last: Option<&[u32]> = None;
    for &i in order.iter() {
        if last != Some(row(i)) {
            out.extend_from_slice(row(i));
            last = Some(row(i));
        }
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

super::nav::plain_nav_base!(Iqm);

impl Topology for Iqm {
    crate::relation::topology_preamble! {
        self, KIND;
        dimension: self.counts.len() - 1;
        vertex_count: self.n;
        count(p): self.counts.get(p).copied().unwrap_or(0);
        top_count(p): self.tops.get(p).map_or(0, |t| t.len() / (p + 1));
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
        let (mut found, mut lens) = (Scratch::<Vec<u32>>::take(), Scratch::<Vec<usize>>::take());
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
        // This thread's pooled buffers: no allocation once they are warm.
        let (mut found, mut lens) = (Scratch::<Vec<u32>>::take(), Scratch::<Vec<usize>>::take());
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
        let mut rows = Scratch::<Vec<u32>>::take();
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
            let mut facet = Scratch::<Vec<u32>>::take();
            let mut produced = Scratch::<Vec<u32>>::take();
            for t in rows_of(&found, &lens) {
                for skip in 0..=p {
                    facet.clear();
                    push_facet(sigma, skip, &mut facet);
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
        sort_dedup_rows_into(q + 1, &rows, out);
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
        let c_total = self.copy_vertex.len();
        if self.copy_comp.len() != c_total || self.copy_top.len() != c_total {
            return Err("copy arrays differ in length".into());
        }
        // Occurrences of each copy among top simplices, to compare with its star walk.
        let mut occurrences = vec![0u32; c_total];
        for i in 0..self.component_count() {
            self.check_component(i, &mut occurrences)?;
        }
        self.check_copy_references()?;
        self.check_hypergraph(&occurrences)?;
        if self.counts.first().copied() != Some(self.n as usize) {
            return Err("vertex count disagrees with n_0".into());
        }
        Ok(())
    }
}

/// The steps of [`Iqm::validate`].
impl Iqm {
    /// Component `i`: ascending rows over its own copies, symmetric facet adjacencies inside
    /// it. Counts each copy's occurrences.
    fn check_component(&self, i: usize, occurrences: &mut [u32]) -> Result<(), String> {
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
                self.check_adjacency(i, k, t, &orig)?;
            }
        }
        Ok(())
    }

    /// The adjacency entries of top k-simplex `t` of component `i` (original ids `orig`).
    fn check_adjacency(&self, i: usize, k: usize, t: usize, orig: &[u32]) -> Result<(), String> {
        let row = self.row(k, t as u32);
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
            let back =
                self.adj[k][u as usize * (k + 1)..(u as usize + 1) * (k + 1)].contains(&(t as u32));
            if !shared || !back || u as usize == t {
                return Err(format!(
                    "{orig:?}: adjacency {j} is not a symmetric facet neighbour"
                ));
            }
        }
        Ok(())
    }

    /// Each copy's star reference is a top simplex of its component holding it.
    fn check_copy_references(&self) -> Result<(), String> {
        for c in 0..self.copy_vertex.len() {
            let comp = self.copy_comp[c] as usize;
            let k = self.comp_dim[comp] as usize;
            let t0 = self.copy_top[c];
            if !self.comp_rows(comp).contains(&(t0 as usize))
                || !self.row(k, t0).contains(&(c as u32))
            {
                return Err(format!("copy {c}: its star reference does not contain it"));
            }
        }
        Ok(())
    }

    /// Every vertex has its copies listed by the hypergraph (split exactly when two or more),
    /// and each copy's star walk reaches every top simplex holding it.
    fn check_hypergraph(&self, occurrences: &[u32]) -> Result<(), String> {
        let mut per_vertex = vec![0u32; self.n as usize];
        for &v in self.copy_vertex.iter() {
            if v >= self.n {
                return Err(format!("copy of vertex {v} out of range"));
            }
            per_vertex[v as usize] += 1;
        }
        let (mut seen, mut stack) = (IdSet::default(), IdStack::default());
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
                let mut walked = 0;
                self.walk_copy_star(c, &mut seen, &mut stack, &mut |_, _| {
                    walked += 1;
                    true
                });
                if walked != occurrences[c as usize] {
                    return Err(format!(
                        "copy {c} of vertex {v}: {} top simplices hold it, its star walk reaches {walked}",
                        occurrences[c as usize]
                    ));
                }
            }
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
