//! Partial Entities (PE) — Lee and Lee 2001, in the simplified form for simplicial complexes of
//! §5.2.1 of the 2005 survey (no loops, shells or regions). Complexes of dimension ≤ 2 only.
//!
//! # What it encodes
//! Faces (triangles), edges, vertices and partial-edges. A partial-edge is the appearance of an
//! edge on the boundary of one face; a face is bounded by three partial-edges, and an edge in m
//! triangles has m of them. Per face: one partial-edge on its boundary. Per edge: one
//! partial-edge of it. Per partial-edge: its edge, its face, the previous and next partial-edge
//! around its edge (radial order, see [`super::radial`]; cyclic, so an edge of one triangle has
//! its partial-edge as its own neighbours), the previous and next partial-edge on the face
//! boundary, and its start vertex. Per vertex: the list of partial-edges starting at it.
//!
//! Wire edges as in the survey: a wire edge has a loop of two partial-edges, one starting at
//! each end; their face is `u32::MAX` and each is the other's previous and next both on the
//! loop and around the edge.
//!
//! # Layout
//! Face t (triangles in lexicographic order, oriented v0 → v1 → v2) is bounded by partial-edges
//! 3t, 3t + 1, 3t + 2 (from v0, v1, v2); wire edge k (lexicographic order) has partial-edges
//! 3n2 + 2k (from its lower end) and 3n2 + 2k + 1. Edges are numbered in lexicographic order.
//! Each partial-edge field is an array over the partial-edges; the vertex lists are CSR.
//!
//! # Storage
//! With P = 3 n2 + 2 n_w partial-edges: `n2 + n1 + 7 P + P + n0` integers — one per face, one
//! per edge, the seven fields of each partial-edge, every partial-edge once in a vertex list and
//! one list head per vertex (as the IG counts one per co-boundary array). No bits. The survey's
//! Table 3 PE column (6918 for its duck, n0 = 93, n2 = 182) equals 12 P + n1 + n0 and cannot be
//! derived from the fields it lists; this module counts the fields. Real bytes add the CSR
//! offsets' extra entry.
//!
//! # Cost of each relation (after locating σ: a face or an edge by binary search over the ids,
//! whose vertices come from their partial-edges in O(1): O(log n))
//! - R_{0,2}(v), R_{0,1}(v), R_{0,0}(v): the vertex list, each partial-edge giving its face, and
//!   its edge and the previous one on the face: O(partial-edges at v).
//! - R_{1,0}: O(1). R_{1,1}(e): the lists of both ends. R_{1,2}(e): the radial cycle, O(k).
//! - R_{2,0}, R_{2,1}: the face loop, O(1). R_{2,2}(t): the three radial cycles, O(answer + 3).

use super::BuildError;
use super::common::{try_copy, try_vec, try_with_capacity};
use super::nav::NavIndex;
use super::radial::{self, EdgeAt, NONE, TriTopo, row3};
use crate::complex::Complex;
use crate::mapped::Arr;
use crate::relation::{Storage, StructureKind, Topology, per_dimension};

const KIND: StructureKind = StructureKind::Pe;

/// The Partial Entity structure (see the module documentation for what it stores and costs).
#[derive(Debug, Clone)]
pub struct PartialEntities {
    n: u32,
    dim: usize,
    isolated: usize,
    n_tris: u32,
    n_wires: usize,
    face_pe: Arr<u32>,
    edge_pe: Arr<u32>,
    pe_edge: Arr<u32>,
    pe_face: Arr<u32>,
    pe_rprev: Arr<u32>,
    pe_rnext: Arr<u32>,
    pe_fprev: Arr<u32>,
    pe_fnext: Arr<u32>,
    pe_start: Arr<u32>,
    vertex_off: Arr<u32>,
    vertex_pe: Arr<u32>,
    /// Handle bookkeeping: windings, top simplices below d, lazy tables ([`super::nav`]).
    pub(crate) nav: NavIndex,
}

impl PartialEntities {
    /// Radial cycles by sorting the triangle edges: O(n2 log n2 + n1 + n0).
    pub fn build(complex: &Complex) -> Result<PartialEntities, BuildError> {
        let parts = radial::parts(KIND, complex)?;
        let n2 = parts.tris.len() as u32;
        let rad = radial::radial(KIND, &parts.tris, complex.coords())?;
        let (tri_edge_id, wire_id) = radial::merge_edges(&rad.edges, &parts.wires);
        let n1 = rad.edges.len() + parts.wires.len();
        let p_count = 3 * n2 as usize + 2 * parts.wires.len();
        let mut pe = PartialEntities {
            nav: NavIndex::new(KIND, complex)?,
            n: parts.n,
            dim: parts.dim,
            isolated: parts.isolated,
            n_tris: n2,
            n_wires: parts.wires.len(),
            face_pe: (0..n2).map(|t| 3 * t).collect(),
            edge_pe: Arr::from(try_vec(KIND, NONE, n1, "edge references")?),
            pe_edge: Arr::from(try_with_capacity(KIND, p_count, "edge uses")?),
            pe_face: Arr::from(try_with_capacity(KIND, p_count, "edge uses")?),
            pe_rprev: Arr::from(try_copy(KIND, &rad.prev, "radial links")?),
            pe_rnext: Arr::from(try_copy(KIND, &rad.next, "radial links")?),
            pe_fprev: Arr::from(try_with_capacity(KIND, p_count, "edge uses")?),
            pe_fnext: Arr::from(try_with_capacity(KIND, p_count, "edge uses")?),
            pe_start: Arr::from(try_with_capacity(KIND, p_count, "edge uses")?),
            vertex_off: Arr::from(Vec::new()),
            vertex_pe: Arr::from(Vec::new()),
        };
        for (e, &first) in rad.edge_first.iter().enumerate() {
            pe.edge_pe[tri_edge_id[e] as usize] = first;
        }
        for s in 0..3 * n2 {
            let t = s / 3;
            pe.pe_edge
                .push(tri_edge_id[rad.slot_edge[s as usize] as usize]);
            pe.pe_face.push(t);
            pe.pe_fprev.push(3 * t + (s + 2) % 3);
            pe.pe_fnext.push(3 * t + (s + 1) % 3);
            pe.pe_start.push(row3(&parts.tris, t)[(s % 3) as usize]);
        }
        for (k, w) in parts.wires.iter().enumerate() {
            let p = 3 * n2 + 2 * k as u32;
            pe.edge_pe[wire_id[k] as usize] = p;
            for (this, other, start) in [(p, p + 1, w[0]), (p + 1, p, w[1])] {
                debug_assert_eq!(pe.pe_edge.len(), this as usize);
                pe.pe_edge.push(wire_id[k]);
                pe.pe_face.push(NONE);
                pe.pe_rprev.push(other);
                pe.pe_rnext.push(other);
                pe.pe_fprev.push(other);
                pe.pe_fnext.push(other);
                pe.pe_start.push(start);
            }
        }
        let (off, list) = by_start(parts.n, &pe.pe_start);
        pe.vertex_off = Arr::from(off);
        pe.vertex_pe = Arr::from(list);
        Ok(pe)
    }

    /// The partial-edges starting at `v`, ascending.
    pub fn vertex_partial_edges(&self, v: u32) -> &[u32] {
        &self.vertex_pe
            [self.vertex_off[v as usize] as usize..self.vertex_off[v as usize + 1] as usize]
    }

    /// Previous and next partial-edge around the edge of `p` (radial order).
    pub fn around_edge(&self, p: u32) -> (u32, u32) {
        (self.pe_rprev[p as usize], self.pe_rnext[p as usize])
    }

    /// The face of partial-edge `p` (`u32::MAX` for a wire edge's).
    pub fn face_of(&self, p: u32) -> u32 {
        self.pe_face[p as usize]
    }

    /// A partial-edge of edge `e` (edges in lexicographic order).
    pub fn edge_partial_edge(&self, e: u32) -> u32 {
        self.edge_pe[e as usize]
    }

    fn start(&self, p: u32) -> u32 {
        self.pe_start[p as usize]
    }

    fn edge_ends(&self, e: u32) -> (u32, u32) {
        let p = self.edge_pe[e as usize];
        let (a, b) = (self.start(p), self.start(self.pe_fnext[p as usize]));
        (a.min(b), a.max(b))
    }
}

/// Items `0..` grouped by their start vertex: CSR offsets and the items, ascending per vertex.
pub(crate) fn by_start(n: u32, start: &[u32]) -> (Vec<u32>, Vec<u32>) {
    let mut off = vec![0u32; n as usize + 1];
    for &v in start {
        off[v as usize + 1] += 1;
    }
    for i in 0..n as usize {
        off[i + 1] += off[i];
    }
    let mut fill = off.clone();
    let mut list = vec![0u32; start.len()];
    for (p, &v) in start.iter().enumerate() {
        list[fill[v as usize] as usize] = p as u32;
        fill[v as usize] += 1;
    }
    (off, list)
}

impl TriTopo for PartialEntities {
    #[inline]
    fn n_tris(&self) -> u32 {
        self.n_tris
    }

    #[inline]
    fn tri(&self, t: u32) -> [u32; 3] {
        let p0 = self.face_pe[t as usize];
        let p1 = self.pe_fnext[p0 as usize];
        let p2 = self.pe_fnext[p1 as usize];
        [self.start(p0), self.start(p1), self.start(p2)]
    }

    #[inline]
    fn radial_next(&self, s: u32) -> u32 {
        self.pe_rnext[s as usize]
    }

    fn star_corners(&self, v: u32, out: &mut Vec<u32>) {
        out.extend(
            self.vertex_partial_edges(v)
                .iter()
                .copied()
                .filter(|&p| self.pe_face[p as usize] != NONE),
        );
    }

    fn wire_neighbours(&self, v: u32, out: &mut Vec<u32>) {
        for &p in self.vertex_partial_edges(v) {
            if self.pe_face[p as usize] == NONE {
                out.push(self.start(self.pe_fnext[p as usize]));
            }
        }
    }

    fn find_edge(&self, a: u32, b: u32) -> Option<EdgeAt> {
        let n1 = self.edge_pe.len() as u32;
        let e = radial::partition(n1, |e| self.edge_ends(e) < (a, b));
        if e == n1 || self.edge_ends(e) != (a, b) {
            return None;
        }
        let p = self.edge_pe[e as usize];
        Some(if self.pe_face[p as usize] == NONE {
            EdgeAt::Wire
        } else {
            EdgeAt::Slot(p)
        })
    }
}

radial::nav_base!(PartialEntities);

impl PartialEntities {
    /// The arrays with one entry per partial edge, `pe_edge` aside.
    fn per_use(&self) -> [&Arr<u32>; 6] {
        [
            &self.pe_face,
            &self.pe_rprev,
            &self.pe_rnext,
            &self.pe_fprev,
            &self.pe_fnext,
            &self.pe_start,
        ]
    }
}

impl Topology for PartialEntities {
    crate::relation::topology_preamble! {
        self, KIND;
        dimension: self.dim;
        vertex_count: self.n;
        count(p):
            per_dimension(p, self.dim, [self.n as usize, self.edge_pe.len(), self.n_tris as usize]);
        top_count(p): per_dimension(p, 2, [self.isolated, self.n_wires, self.n_tris as usize]);
        answers: radial;
    }

    fn simplices(&self, p: usize, out: &mut Vec<u32>) {
        if p == 1 {
            for e in 0..self.edge_pe.len() as u32 {
                let (a, b) = self.edge_ends(e);
                out.extend_from_slice(&[a, b]);
            }
        } else {
            radial::simplices(self, self.n, p, out);
        }
    }

    fn storage(&self) -> Storage {
        let p = self.pe_edge.len() as u64;
        let integers = self.n_tris as u64 + self.edge_pe.len() as u64 + 8 * p + self.n as u64;
        let others = [
            &self.face_pe,
            &self.edge_pe,
            &self.pe_edge,
            &self.vertex_off,
            &self.vertex_pe,
        ];
        radial::storage_of(integers, self.per_use().into_iter().chain(others))
    }

    fn validate(&self) -> Result<(), String> {
        let pc = self.pe_edge.len();
        let n2 = self.n_tris;
        if pc != 3 * n2 as usize + 2 * self.n_wires || self.per_use().iter().any(|a| a.len() != pc)
        {
            return Err("partial-edge arrays have different lengths".into());
        }
        for p in 0..pc as u32 {
            let i = p as usize;
            let (fnext, fprev, rnext, rprev) = (
                self.pe_fnext[i],
                self.pe_fprev[i],
                self.pe_rnext[i],
                self.pe_rprev[i],
            );
            if [fnext, fprev, rnext, rprev]
                .iter()
                .any(|&x| x as usize >= pc)
            {
                return Err(format!("partial-edge {p} refers outside the array"));
            }
            if self.pe_fprev[fnext as usize] != p || self.pe_rprev[rnext as usize] != p {
                return Err(format!("partial-edge {p}: next/previous are not inverse"));
            }
            if self.pe_edge[rnext as usize] != self.pe_edge[i] {
                return Err(format!(
                    "partial-edge {p}: radial neighbour on another edge"
                ));
            }
            let face = self.pe_face[i];
            if face != self.pe_face[fnext as usize] {
                return Err(format!("partial-edge {p}: loop neighbour on another face"));
            }
            let e = self.pe_edge[i];
            if e as usize >= self.edge_pe.len() {
                return Err(format!("partial-edge {p}: edge {e} out of range"));
            }
            // The partial-edge runs from its start to the start of the next one on its loop.
            let (a, b) = (self.start(p), self.start(fnext));
            if (a.min(b), a.max(b)) != self.edge_ends(e) || a >= self.n {
                return Err(format!("partial-edge {p}: ends [{a} {b}] are not its edge"));
            }
            if face == NONE {
                if (p as usize) < 3 * n2 as usize
                    || fnext != rnext
                    || self.pe_fnext[fnext as usize] != p
                {
                    return Err(format!("wire partial-edge {p} is not in a loop of two"));
                }
            } else if face != p / 3 || fnext != 3 * face + (p + 1) % 3 {
                return Err(format!(
                    "partial-edge {p} is not slot {} of face {face}",
                    p % 3
                ));
            }
        }
        for (t, &p) in self.face_pe.iter().enumerate() {
            if self.pe_face.get(p as usize) != Some(&(t as u32)) {
                return Err(format!(
                    "face {t} refers to partial-edge {p} of another face"
                ));
            }
        }
        for e in 0..self.edge_pe.len() as u32 {
            if self.pe_edge.get(self.edge_pe[e as usize] as usize) != Some(&e) {
                return Err(format!("edge {e} refers to a partial-edge of another edge"));
            }
            if e > 0 && self.edge_ends(e - 1) >= self.edge_ends(e) {
                return Err(format!("edges not in lexicographic order at {e}"));
            }
        }
        if (self.vertex_off.len(), self.vertex_pe.len()) != (self.n as usize + 1, pc) {
            return Err("vertex lists have the wrong shape".into());
        }
        for v in 0..self.n {
            if let Some(&p) = self
                .vertex_partial_edges(v)
                .iter()
                .find(|&&p| self.start(p) != v)
            {
                return Err(format!(
                    "vertex {v} lists partial-edge {p}, which starts elsewhere"
                ));
            }
        }
        radial::validate_common(self, self.n)
    }
}

crate::persist_fields!(PartialEntities {
    n,
    dim,
    isolated,
    n_tris,
    n_wires,
    face_pe,
    edge_pe,
    pe_edge,
    pe_face,
    pe_rprev,
    pe_rnext,
    pe_fprev,
    pe_fnext,
    pe_start,
    vertex_off,
    vertex_pe, nav
} check |s| {
    crate::codec::dimension_at_most(s.dim, 2)?;
    if s.face_pe.len() != s.n_tris as usize || s.vertex_off.len() != s.n as usize + 1 {
        return Err("arrays of the wrong length for the triangles and vertices".into());
    }
    Ok(())
});
