//! Loop Edge-use (LE) — McMains 2000, the Radial Edge specialised to regular simplicial
//! 2-complexes, as described in §5.2.2 of the 2005 survey.
//!
//! # Domain
//! Regular 2-complexes whose vertices each have a star of one connected component (non-manifold
//! singularities only at edges, where any number of triangles may meet). Building refuses, naming
//! the offending simplex with the smallest vertex: a tetrahedron (dimension > 2), an isolated
//! vertex, a wire edge, or a vertex whose star splits into several components (a bowtie vertex).
//!
//! # What it encodes
//! Faces, edges, vertices and edge-uses (an edge-use is an edge on the boundary of one face, with
//! the face's single orientation v0 → v1 → v2 for ascending vertices). Per face: one edge-use.
//! Per edge: one edge-use. Per edge-use: its face, its edge, the next edge-use around the edge in
//! radial order (see [`super::radial`]; cyclic), the next edge-use on the face boundary, its start
//! vertex, and the next edge-use starting at the same vertex (cyclic; the survey asks for
//! counter-clockwise order around the vertex, which is undefined at a vertex on non-manifold
//! edges: this ring is in ascending edge-use id, i.e. triangle, order). Per vertex: one edge-use
//! starting at it.
//!
//! # Layout
//! Face t (lexicographic order) has edge-uses 3t, 3t + 1, 3t + 2 (starting at v0, v1, v2); edges
//! are numbered in lexicographic order. One array per edge-use field.
//!
//! # Storage
//! `n2 + n1 + 6 · 3 n2 + n0` integers: one per face, per edge and per vertex, and the six fields
//! the survey lists per edge-use. No bits. The survey's Table 3 LE column counts five per
//! edge-use (16 n2 + n1 + n0: 3278 for its duck); its text lists six, which is what this module
//! stores and counts.
//!
//! # Cost of each relation (after locating σ: a face or an edge by binary search over the ids,
//! whose vertices come from their edge-uses in O(1): O(log n))
//! - R_{0,q}(v): the vertex ring (one edge-use per triangle at v), each edge-use giving its face,
//!   its edge and the edge of the edge-use before it on the face (two steps of "next"):
//!   O(triangles at v).
//! - R_{1,0}: O(1). R_{1,1}(e): the rings of both ends. R_{1,2}(e): the radial cycle, O(k).
//! - R_{2,0}, R_{2,1}: the face loop, O(1). R_{2,2}(t): the three radial cycles, O(answer + 3).

use super::BuildError;
use super::common::try_copy;
use super::nav::NavIndex;
use super::pe::by_start;
use super::radial::{self, EdgeAt, NONE, TriTopo, row3, show};
use crate::complex::Complex;
use crate::mapped::Arr;
use crate::relation::{Storage, StructureKind, Topology, per_dimension};

const KIND: StructureKind = StructureKind::Le;

/// The Loop-Edge-use structure (see the module documentation for what it stores and costs).
#[derive(Debug, Clone)]
pub struct LoopEdgeUse {
    n: u32,
    n_tris: u32,
    face_eu: Arr<u32>,
    edge_eu: Arr<u32>,
    eu_face: Arr<u32>,
    eu_edge: Arr<u32>,
    eu_rnext: Arr<u32>,
    eu_fnext: Arr<u32>,
    eu_start: Arr<u32>,
    eu_vnext: Arr<u32>,
    vertex_eu: Arr<u32>,
    /// Handle bookkeeping: windings, top simplices below d, lazy tables ([`super::nav`]).
    pub(crate) nav: NavIndex,
}

impl LoopEdgeUse {
    /// Checks the domain, then radial cycles by sorting the triangle edges: O(n2 log n2 + n0).
    pub fn build(complex: &Complex) -> Result<LoopEdgeUse, BuildError> {
        let parts = radial::parts(KIND, complex)?;
        let n2 = parts.tris.len() as u32;
        let tris = &parts.tris;
        let rad = radial::radial(KIND, tris, complex.coords())?;
        radial::components_headroom(KIND, parts.n, tris.len(), parts.wires.len())?;
        let (comp_off, comps) =
            radial::vertex_components(parts.n, n2, |t| row3(tris, t), |s| rad.next[s as usize]);
        let (wire_off, wire_nbr) = radial::wire_lists(parts.n, &parts.wires);
        let refuse = |reason: String| BuildError::Unsupported { kind: KIND, reason };
        for v in 0..parts.n as usize {
            let k = (comp_off[v + 1] - comp_off[v]) as usize;
            let wires = &wire_nbr[wire_off[v] as usize..wire_off[v + 1] as usize];
            if let Some(&w) = wires.first() {
                return Err(refuse(format!(
                    "wire edge {} (LE encodes regular 2-complexes only: every top simplex a \
                     triangle)",
                    show(&[v as u32, w])
                )));
            }
            if k == 0 {
                return Err(refuse(format!(
                    "isolated vertex [{v}] (LE encodes regular 2-complexes only: every vertex on \
                     a triangle)"
                )));
            }
            if k > 1 {
                let (c0, c1) = (comps[comp_off[v] as usize], comps[comp_off[v] as usize + 1]);
                return Err(refuse(format!(
                    "vertex [{v}]: its star has {k} connected components (triangles {} and {} \
                     share no edge at it); LE needs one component per vertex star",
                    show(tris.get(c0 as usize / 3)),
                    show(tris.get(c1 as usize / 3))
                )));
            }
        }
        let m = 3 * n2;
        let eu_start: Vec<u32> = (0..m)
            .map(|s| row3(tris, s / 3)[(s % 3) as usize])
            .collect();
        let (off, list) = by_start(parts.n, &eu_start);
        let mut eu_vnext = vec![NONE; m as usize];
        let mut vertex_eu = vec![NONE; parts.n as usize];
        for v in 0..parts.n as usize {
            let ring = &list[off[v] as usize..off[v + 1] as usize];
            vertex_eu[v] = ring[0];
            for (j, &s) in ring.iter().enumerate() {
                eu_vnext[s as usize] = ring[(j + 1) % ring.len()];
            }
        }
        Ok(LoopEdgeUse {
            nav: NavIndex::new(KIND, complex)?,
            n: parts.n,
            n_tris: n2,
            face_eu: (0..n2).map(|t| 3 * t).collect(),
            edge_eu: Arr::from(try_copy(KIND, &rad.edge_first, "radial links")?),
            eu_face: (0..m).map(|s| s / 3).collect(),
            eu_edge: Arr::from(try_copy(KIND, &rad.slot_edge, "radial links")?),
            eu_rnext: Arr::from(try_copy(KIND, &rad.next, "radial links")?),
            eu_fnext: (0..m).map(|s| s - s % 3 + (s + 1) % 3).collect(),
            eu_start: eu_start.into(),
            eu_vnext: eu_vnext.into(),
            vertex_eu: vertex_eu.into(),
        })
    }

    /// The next edge-use around the edge of `u` (radial order).
    pub fn radial_next_use(&self, u: u32) -> u32 {
        self.eu_rnext[u as usize]
    }

    /// The next edge-use starting at the start vertex of `u`.
    pub fn vertex_next_use(&self, u: u32) -> u32 {
        self.eu_vnext[u as usize]
    }

    fn start(&self, u: u32) -> u32 {
        self.eu_start[u as usize]
    }

    fn edge_ends(&self, e: u32) -> (u32, u32) {
        let u = self.edge_eu[e as usize];
        let (a, b) = (self.start(u), self.start(self.eu_fnext[u as usize]));
        (a.min(b), a.max(b))
    }
}

impl TriTopo for LoopEdgeUse {
    #[inline]
    fn n_tris(&self) -> u32 {
        self.n_tris
    }

    #[inline]
    fn tri(&self, t: u32) -> [u32; 3] {
        let u0 = self.face_eu[t as usize];
        let u1 = self.eu_fnext[u0 as usize];
        let u2 = self.eu_fnext[u1 as usize];
        [self.start(u0), self.start(u1), self.start(u2)]
    }

    #[inline]
    fn radial_next(&self, s: u32) -> u32 {
        self.eu_rnext[s as usize]
    }

    fn star_corners(&self, v: u32, out: &mut Vec<u32>) {
        let first = self.vertex_eu[v as usize];
        let mut u = first;
        // A ring holds each edge-use once: a longer one (a saved file's arrays altered) stops
        // with a panic the CLI and the C ABI report, not an answer growing without bound.
        let most = self.eu_vnext.len();
        let start = out.len();
        loop {
            out.push(u);
            assert!(
                out.len() - start <= most,
                "vertex ring does not close (inconsistent arrays)"
            );
            u = self.eu_vnext[u as usize];
            if u == first {
                break;
            }
        }
    }

    fn wire_neighbours(&self, _v: u32, _out: &mut Vec<u32>) {}

    fn find_edge(&self, a: u32, b: u32) -> Option<EdgeAt> {
        let n1 = self.edge_eu.len() as u32;
        let e = radial::partition(n1, |e| self.edge_ends(e) < (a, b));
        (e < n1 && self.edge_ends(e) == (a, b)).then(|| EdgeAt::Slot(self.edge_eu[e as usize]))
    }
}

radial::nav_base!(LoopEdgeUse);

impl LoopEdgeUse {
    /// The arrays with one entry per edge-use.
    fn per_use(&self) -> [&Arr<u32>; 6] {
        [
            &self.eu_face,
            &self.eu_edge,
            &self.eu_rnext,
            &self.eu_fnext,
            &self.eu_start,
            &self.eu_vnext,
        ]
    }
}

impl Topology for LoopEdgeUse {
    crate::relation::topology_preamble! {
        self, KIND;
        dimension: 2;
        vertex_count: self.n;
        count(p): per_dimension(p, 2, [self.n as usize, self.edge_eu.len(), self.n_tris as usize]);
        top_count(p): if p == 2 { self.n_tris as usize } else { 0 };
        answers: radial;
    }

    fn simplices(&self, p: usize, out: &mut Vec<u32>) {
        if p == 1 {
            for e in 0..self.edge_eu.len() as u32 {
                let (a, b) = self.edge_ends(e);
                out.extend_from_slice(&[a, b]);
            }
        } else {
            radial::simplices(self, self.n, p, out);
        }
    }

    fn storage(&self) -> Storage {
        let integers = self.n_tris as u64 * 19 + self.edge_eu.len() as u64 + self.n as u64;
        let others = [&self.face_eu, &self.edge_eu, &self.vertex_eu];
        radial::storage_of(integers, self.per_use().into_iter().chain(others))
    }

    fn validate(&self) -> Result<(), String> {
        let m = 3 * self.n_tris as usize;
        if self.per_use().iter().any(|a| a.len() != m) || self.vertex_eu.len() != self.n as usize {
            return Err("edge-use arrays have the wrong shape".into());
        }
        if self.n_tris == 0 {
            return Err("an LE holds at least one triangle".into());
        }
        for u in 0..m as u32 {
            let i = u as usize;
            let (f, fnext, vnext, rnext) = (
                self.eu_face[i],
                self.eu_fnext[i],
                self.eu_vnext[i],
                self.eu_rnext[i],
            );
            if [fnext, vnext, rnext].iter().any(|&x| x as usize >= m) {
                return Err(format!("edge-use {u} refers outside the array"));
            }
            if f != u / 3 || fnext != 3 * f + (u + 1) % 3 {
                return Err(format!(
                    "edge-use {u} is not slot {} of face {}",
                    u % 3,
                    u / 3
                ));
            }
            if self.start(vnext) != self.start(u) {
                return Err(format!("edge-use {u}: vertex ring reaches another vertex"));
            }
            let e = self.eu_edge[i];
            if e as usize >= self.edge_eu.len() || self.eu_edge[rnext as usize] != e {
                return Err(format!("edge-use {u}: radial neighbour on another edge"));
            }
            let (a, b) = (self.start(u), self.start(fnext));
            if (a.min(b), a.max(b)) != self.edge_ends(e) {
                return Err(format!("edge-use {u}: ends [{a} {b}] are not its edge"));
            }
        }
        for (e, &u) in self.edge_eu.iter().enumerate() {
            if self.eu_edge[u as usize] != e as u32 {
                return Err(format!("edge {e} refers to an edge-use of another edge"));
            }
            if e > 0 && self.edge_ends(e as u32 - 1) >= self.edge_ends(e as u32) {
                return Err(format!("edges not in lexicographic order at {e}"));
            }
        }
        // Each vertex ring is one cycle holding every edge-use starting at the vertex.
        let mut on_ring = 0usize;
        for v in 0..self.n {
            let u = self.vertex_eu[v as usize];
            if u as usize >= m || self.start(u) != v {
                return Err(format!(
                    "vertex {v} refers to an edge-use starting elsewhere"
                ));
            }
            let mut x = u;
            loop {
                on_ring += 1;
                x = self.eu_vnext[x as usize];
                if x == u || on_ring > m {
                    break;
                }
            }
        }
        if on_ring != m {
            return Err("vertex rings do not partition the edge-uses".into());
        }
        radial::validate_common(self, self.n)?;
        radial::validate_components(self, self.n, |v| vec![self.vertex_eu[v as usize]])
    }
}

crate::persist_fields!(LoopEdgeUse {
    n,
    n_tris,
    face_eu,
    edge_eu,
    eu_face,
    eu_edge,
    eu_rnext,
    eu_fnext,
    eu_start,
    eu_vnext,
    vertex_eu, nav
} check |s| {
    if s.face_eu.len() != s.n_tris as usize || s.vertex_eu.len() != s.n as usize || s.eu_face.len() != 3 * s.n_tris as usize {
        return Err("arrays of the wrong length for the triangles and vertices".into());
    }
    Ok(())
});
