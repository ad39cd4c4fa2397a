//! Triangle-Segment (TS) — De Floriani, Magillo, Puppo, Sobrero 2004, as described in §5.1 of
//! the 2005 survey. Complexes of dimension ≤ 2 only.
//!
//! # What it encodes
//! The vertices and the top simplices (triangles, wire edges; isolated vertices are just
//! vertices). Edges are not encoded.
//! - Per triangle t: R_{2,0}(t) (its vertices), and R*_{2,2}(t): for each edge of t, the
//!   triangles immediately preceding and succeeding t in radial order around that edge (see
//!   [`super::radial`] for the order). On an edge of two triangles both are the other triangle
//!   and one reference is stored; on a boundary edge (one triangle) the entry is `u32::MAX`.
//! - Per vertex v: R*_{0,2}(v), one triangle per connected component of the triangle part of
//!   lk(v), and R*_{0,0}(v), the other ends of the wire edges at v (each wire edge at v is a
//!   connected component of lk(v) on its own, so wire edges are implicit in these lists).
//!
//! # Layout
//! `tris` (3 ids per triangle, ascending, lexicographic order) is R_{2,0}; `next[3t + i]` is the
//! succeeding triangle around the edge of slot i of t (v_i v_{i+1 mod 3}); the preceding one is
//! `next` too unless the edge is in ≥ 3 triangles, in which case bit `3t + i` of `nonmanifold` is
//! set and `prev[rank]` holds it (rank = set bits before it, from `nonmanifold_rank` per word).
//! R*_{0,2} and R*_{0,0} are CSR lists over the vertices.
//!
//! # Storage
//! As §5.1 counts it: `6 n2 + C_e + C_v` integers, where C_e = Σ over edges in ≥ 3 triangles of
//! their triangle count (the second reference those triangles need), and C_v = Σ_v the number of
//! connected components of lk(v) (triangle components plus wire edges). A manifold surface costs
//! exactly `6 n2 + n0`. No bits are counted. Real bytes add the CSR offsets, the bitset with its
//! rank words, and the edge locator (2 n2 integers: see `radial::EdgeLocator`).
//!
//! # Cost of each relation (after locating σ: triangles O(log n2) by binary search in `tris`;
//! edges O(log n2) through the locator, or O(log deg) in the wire list)
//! - R_{0,2}(v): walk each star component from its stored triangle, crossing each edge at v
//!   once through its radial cycle: O(triangles at v).
//! - R_{0,1}(v), R_{0,0}(v): the same walk plus the wire list: O(triangles and wire edges at v);
//!   this exceeds the answer only when edges at v are in several triangles.
//! - R_{1,0}: O(1). R_{1,1}(e): the two vertex walks: O(star of both ends). R_{1,2}(e): the
//!   radial cycle: O(k) for k triangles.
//! - R_{2,0}, R_{2,1}: O(1). R_{2,2}(t): the three radial cycles: O(answer + 3).
//!
//! Queries keep no state in the structure: the walks' marks are per-query hash sets.

use super::BuildError;
use super::nav::NavIndex;
use super::radial::{self, EdgeAt, EdgeLocator, NONE, TriTopo, row3, slot_ends};
use crate::complex::{Complex, SimplexTable};
use crate::mapped::Arr;
use crate::relation::{Storage, StructureKind, Topology, per_dimension};

const KIND: StructureKind = StructureKind::Ts;

/// The Triangle-Segment structure (see the module documentation for what it stores and costs).
#[derive(Debug, Clone)]
pub struct TriangleSegment {
    n: u32,
    dim: usize,
    n_edges: usize,
    isolated: usize,
    n_wires: usize,
    tris: SimplexTable,
    next: Arr<u32>,
    nonmanifold: Arr<u64>,
    nonmanifold_rank: Arr<u32>,
    prev: Arr<u32>,
    comp_off: Arr<u32>,
    comp_tri: Arr<u32>,
    wire_off: Arr<u32>,
    wire_nbr: Arr<u32>,
    locator: EdgeLocator,
    /// Handle bookkeeping: windings, top simplices below d, lazy tables ([`super::nav`]).
    pub(crate) nav: NavIndex,
}

impl TriangleSegment {
    /// Radial cycles by sorting the triangle edges (O(n2 log n2)), star components by
    /// union-find over corners.
    pub fn build(complex: &Complex) -> Result<TriangleSegment, BuildError> {
        let parts = radial::parts(KIND, complex)?;
        let tris = parts.tris;
        let n2 = tris.len() as u32;
        let rad = radial::radial(KIND, &tris, complex.coords())?;
        let m = 3 * n2 as usize;
        let mut next = vec![NONE; m];
        let mut nonmanifold = vec![0u64; m.div_ceil(64)];
        let mut prev = Vec::new();
        let mut size = vec![0u32; rad.edges.len()];
        for &e in &rad.slot_edge {
            size[e as usize] += 1;
        }
        for s in 0..m {
            let k = size[rad.slot_edge[s] as usize];
            if k >= 2 {
                next[s] = rad.next[s] / 3;
            }
            if k >= 3 {
                nonmanifold[s / 64] |= 1 << (s % 64);
                prev.push(rad.prev[s] / 3);
            }
        }
        let nonmanifold_rank = ranks(&nonmanifold);
        radial::components_headroom(KIND, parts.n, tris.len(), parts.wires.len())?;
        let (comp_off, corners) =
            radial::vertex_components(parts.n, n2, |t| row3(&tris, t), |s| rad.next[s as usize]);
        let comp_tri: Vec<u32> = corners.into_iter().map(|c| c / 3).collect();
        let (wire_off, wire_nbr) = radial::wire_lists(parts.n, &parts.wires);
        let locator = EdgeLocator::build(KIND, &tris)?;
        Ok(TriangleSegment {
            nav: NavIndex::new(KIND, complex)?,
            n: parts.n,
            dim: parts.dim,
            n_edges: rad.edges.len() + parts.wires.len(),
            isolated: parts.isolated,
            n_wires: parts.wires.len(),
            tris,
            next: next.into(),
            nonmanifold: nonmanifold.into(),
            nonmanifold_rank: nonmanifold_rank.into(),
            prev: prev.into(),
            comp_off: comp_off.into(),
            comp_tri: comp_tri.into(),
            wire_off: wire_off.into(),
            wire_nbr: wire_nbr.into(),
            locator,
        })
    }

    /// The triangles preceding and succeeding triangle `t` around its edge `v_i v_{i+1 mod 3}`
    /// (`u32::MAX` on a boundary edge): R*_{2,2} as stored. O(1).
    pub fn around(&self, t: u32, i: u32) -> (u32, u32) {
        let s = (3 * t + i) as usize;
        let next = self.next[s];
        if self.nonmanifold[s / 64] >> (s % 64) & 1 == 1 {
            let below = self.nonmanifold[s / 64] & ((1u64 << (s % 64)) - 1);
            let rank = self.nonmanifold_rank[s / 64] + below.count_ones();
            (self.prev[rank as usize], next)
        } else {
            (next, next)
        }
    }

    /// R*_{0,2}(v): one triangle per connected component of lk(v) with triangles.
    pub fn vertex_triangles(&self, v: u32) -> &[u32] {
        &self.comp_tri[self.comp_off[v as usize] as usize..self.comp_off[v as usize + 1] as usize]
    }

    /// R*_{0,0}(v): the other ends of the wire edges at v, ascending.
    pub fn wire_neighbours_of(&self, v: u32) -> &[u32] {
        &self.wire_nbr[self.wire_off[v as usize] as usize..self.wire_off[v as usize + 1] as usize]
    }

    /// C_e as §5.1 counts it: triangle references beyond one per triangle edge.
    pub fn nonmanifold_slots(&self) -> usize {
        self.prev.len()
    }
}

/// Set bits before each 64-bit word.
fn ranks(bits: &[u64]) -> Vec<u32> {
    let mut acc = 0u32;
    bits.iter()
        .map(|w| {
            let r = acc;
            acc += w.count_ones();
            r
        })
        .collect()
}

impl TriTopo for TriangleSegment {
    #[inline]
    fn n_tris(&self) -> u32 {
        self.tris.len() as u32
    }

    #[inline]
    fn tri(&self, t: u32) -> [u32; 3] {
        row3(&self.tris, t)
    }

    #[inline]
    fn radial_next(&self, s: u32) -> u32 {
        let t2 = self.next[s as usize];
        if t2 == NONE {
            return s;
        }
        let (a, b) = slot_ends(self.tri(s / 3), s);
        let tv = self.tri(t2);
        (0..3)
            .map(|i| 3 * t2 + i)
            .find(|&r| {
                let (x, y) = slot_ends(tv, r);
                (x == a && y == b) || (x == b && y == a)
            })
            .expect("the next triangle around an edge contains the edge")
    }

    fn star_corners(&self, v: u32, out: &mut Vec<u32>) {
        let reps = self
            .vertex_triangles(v)
            .iter()
            .map(|&t| radial::corner(t, self.tri(t), v));
        radial::walk_star(self, v, reps, out);
    }

    fn wire_neighbours(&self, v: u32, out: &mut Vec<u32>) {
        out.extend_from_slice(self.wire_neighbours_of(v));
    }

    fn find_tri(&self, t: &[u32]) -> Option<u32> {
        self.tris.find(t)
    }

    fn find_edge(&self, a: u32, b: u32) -> Option<EdgeAt> {
        if let Some(s) = self.locator.find(self.n_tris(), |t| self.tri(t), a, b) {
            return Some(EdgeAt::Slot(s));
        }
        self.wire_neighbours_of(a)
            .binary_search(&b)
            .ok()
            .map(|_| EdgeAt::Wire)
    }
}

radial::nav_base!(TriangleSegment;
    fn stored_table(&self, p: usize) -> Option<&SimplexTable> {
        (p == 2).then_some(&self.tris)
    }
);

impl Topology for TriangleSegment {
    crate::relation::topology_preamble! {
        self, KIND;
        dimension: self.dim;
        vertex_count: self.n;
        count(p): per_dimension(p, self.dim, [self.n as usize, self.n_edges, self.tris.len()]);
        top_count(p): per_dimension(p, 2, [self.isolated, self.n_wires, self.tris.len()]);
        answers: radial;
        simplices: radial(self.n);
    }

    fn storage(&self) -> Storage {
        let n2 = self.tris.len() as u64;
        let integers =
            6 * n2 + (self.prev.len() + self.comp_tri.len() + self.wire_nbr.len()) as u64;
        let words = self.next.capacity()
            + self.prev.capacity()
            + self.nonmanifold_rank.capacity()
            + self.comp_off.capacity()
            + self.comp_tri.capacity()
            + self.wire_off.capacity()
            + self.wire_nbr.capacity();
        let bytes = self.tris.heap_bytes()
            + words * 4
            + self.nonmanifold.capacity() * 8
            + self.locator.heap_bytes();
        Storage {
            integers,
            bits: 0,
            bytes: bytes as u64,
        }
    }

    fn validate(&self) -> Result<(), String> {
        let n2 = self.n_tris();
        if self.tris.arity() != 3 || self.next.len() != 3 * n2 as usize {
            return Err("triangle arrays have the wrong shape".into());
        }
        radial::validate_common(self, self.n)?;
        // The stored preceding triangle must be the one whose successor is t.
        let mut nm = 0;
        for t in 0..n2 {
            for i in 0..3 {
                let s = 3 * t + i;
                let (p, nx) = self.around(t, i);
                let k = {
                    let mut k = 1;
                    let mut r = self.radial_next(s);
                    while r != s {
                        k += 1;
                        r = self.radial_next(r);
                    }
                    k
                };
                let flagged = self.nonmanifold[s as usize / 64] >> (s % 64) & 1 == 1;
                if flagged != (k >= 3) {
                    return Err(format!(
                        "slot {i} of triangle {t}: edge in {k} triangles but flag {flagged}"
                    ));
                }
                nm += usize::from(flagged);
                if (k == 1) != (nx == NONE) {
                    return Err(format!("slot {i} of triangle {t}: boundary mark wrong"));
                }
                if k >= 2 && !(0..3).any(|j| self.radial_next(3 * p + j) == s) {
                    return Err(format!(
                        "triangle {p} stored before {t} does not precede it"
                    ));
                }
            }
        }
        if nm != self.prev.len() || self.nonmanifold_rank != ranks(&self.nonmanifold) {
            return Err("non-manifold slot table inconsistent".into());
        }
        radial::validate_components(self, self.n, |v| {
            self.vertex_triangles(v)
                .iter()
                .map(|&t| radial::corner(t, self.tri(t), v))
                .collect()
        })?;
        for v in 0..self.n {
            let w = self.wire_neighbours_of(v);
            if w.windows(2).any(|x| x[0] >= x[1]) || w.iter().any(|&x| x >= self.n || x == v) {
                return Err(format!("wire list of vertex {v} is not ascending in range"));
            }
            for &x in w {
                if self.wire_neighbours_of(x).binary_search(&v).is_err() {
                    return Err(format!("wire edge [{v} {x}] stored at one end only"));
                }
                if self
                    .locator
                    .find(n2, |t| self.tri(t), v.min(x), v.max(x))
                    .is_some()
                {
                    return Err(format!("wire edge [{v} {x}] is also a triangle edge"));
                }
            }
        }
        if self.wire_nbr.len() != 2 * self.n_wires {
            return Err("wire lists disagree with the wire count".into());
        }
        self.locator.validate(n2, |t| self.tri(t))
    }
}

crate::persist_fields!(TriangleSegment {
    n,
    dim,
    n_edges,
    isolated,
    n_wires,
    tris,
    next,
    nonmanifold,
    nonmanifold_rank,
    prev,
    comp_off,
    comp_tri,
    wire_off,
    wire_nbr,
    locator, nav
} check |s| {
    crate::codec::dimension_at_most(s.dim, 2)?;
    if s.next.len() != 3 * s.tris.len() || s.wire_off.len() != s.n as usize + 1 {
        return Err("arrays of the wrong length for the triangles and vertices".into());
    }
    Ok(())
});
