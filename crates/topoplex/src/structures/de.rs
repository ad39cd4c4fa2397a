//! Directed Edge (DE) — Campagna, Kobbelt, Seidel 1998, extended to non-manifold triangle
//! complexes as described in §5.2.3 of the 2005 survey. Complexes of dimension ≤ 2 only.
//!
//! # What it encodes
//! Vertices and directed edges; triangles and unoriented edges are implicit. Triangle i
//! (triangles in lexicographic order, oriented v0 → v1 → v2 for ascending vertices) is bounded by
//! directed edges 3i (v0 → v1), 3i + 1 (v1 → v2), 3i + 2 (v2 → v0). Per directed edge: its start
//! and end vertex, the radially adjacent directed edge (the next one on the same edge in radial
//! order, see [`super::radial`]; cyclic, so a directed edge alone on its edge is its own
//! neighbour), and the previous and next directed edge on its triangle. Per vertex: one directed
//! edge starting at it per connected component of its link.
//!
//! Wire edges are directed edges too: wire edge k (lexicographic order) is the pair 3n2 + 2k
//! (lower end → upper end) and 3n2 + 2k + 1 (back), each the other's radial neighbour, previous
//! and next — a loop of two, as the PE bounds a wire edge. A wire edge at v is a component of
//! lk(v) on its own, so v lists the wire's directed edge that starts at v.
//!
//! # Storage
//! With D = 3 n2 + 2 n_w directed edges: `5 D + C_v` integers, where C_v = Σ_v the number of
//! connected components of lk(v) (triangle components plus wire edges); a manifold surface costs
//! `15 n2 + n0` (2823 for the survey's duck, as in its Table 3). No bits. Real bytes add the CSR
//! offsets over the vertices and the edge locator (2 n2 integers, see
//! `radial::EdgeLocator`).
//!
//! # Cost of each relation (after locating σ: a triangle by binary search over the ids, its
//! vertices being the start vertices of its directed edges, O(log n2); an edge through the locator
//! or, for a wire edge, by binary search over the wire pairs, O(log n))
//! - R_{0,q}(v): walk each link component from its stored directed edge, crossing each edge at v
//!   once through its radial cycle: O(triangles and wire edges at v).
//! - R_{1,0}: O(1). R_{1,1}(e): the walks at both ends. R_{1,2}(e): the radial cycle, O(k).
//! - R_{2,0}, R_{2,1}: O(1). R_{2,2}(t): the three radial cycles, O(answer + 3).

use super::BuildError;
use super::common::{try_copy, try_with_capacity};
use super::nav::NavIndex;
use super::radial::{self, EdgeAt, EdgeLocator, TriTopo, row3};
use crate::complex::Complex;
use crate::mapped::Arr;
use crate::relation::{Storage, StructureKind, Topology, per_dimension};

const KIND: StructureKind = StructureKind::De;

/// The Directed-Edge structure (see the module documentation for what it stores and costs).
#[derive(Debug, Clone)]
pub struct DirectedEdge {
    n: u32,
    dim: usize,
    isolated: usize,
    n_tris: u32,
    n_wires: u32,
    n_edges: usize,
    de_start: Arr<u32>,
    de_end: Arr<u32>,
    de_radial: Arr<u32>,
    de_prev: Arr<u32>,
    de_next: Arr<u32>,
    comp_off: Arr<u32>,
    comp_de: Arr<u32>,
    locator: EdgeLocator,
    /// Handle bookkeeping: windings, top simplices below d, lazy tables ([`super::nav`]).
    pub(crate) nav: NavIndex,
}

impl DirectedEdge {
    /// Radial cycles by sorting the triangle edges (O(n2 log n2)), link components by
    /// union-find over corners.
    pub fn build(complex: &Complex) -> Result<DirectedEdge, BuildError> {
        let parts = radial::parts(KIND, complex)?;
        let tris = &parts.tris;
        let n2 = tris.len() as u32;
        let nw = parts.wires.len() as u32;
        let rad = radial::radial(KIND, tris, complex.coords())?;
        let d = (3 * n2 + 2 * nw) as usize;
        let mut de = DirectedEdge {
            nav: NavIndex::new(KIND, complex)?,
            n: parts.n,
            dim: parts.dim,
            isolated: parts.isolated,
            n_tris: n2,
            n_wires: nw,
            n_edges: rad.edges.len() + nw as usize,
            de_start: Arr::from(try_with_capacity(KIND, d, "edge uses")?),
            de_end: Arr::from(try_with_capacity(KIND, d, "edge uses")?),
            de_radial: Arr::from(try_copy(KIND, &rad.next, "radial links")?),
            de_prev: Arr::from(try_with_capacity(KIND, d, "edge uses")?),
            de_next: Arr::from(try_with_capacity(KIND, d, "edge uses")?),
            comp_off: Arr::from(Vec::new()),
            comp_de: Arr::from(Vec::new()),
            locator: EdgeLocator::build(KIND, tris)?,
        };
        de.de_radial.reserve_exact(2 * nw as usize);
        for s in 0..3 * n2 {
            let (a, b) = radial::slot_ends(row3(tris, s / 3), s);
            de.de_start.push(a);
            de.de_end.push(b);
            de.de_prev.push(s - s % 3 + (s + 2) % 3);
            de.de_next.push(s - s % 3 + (s + 1) % 3);
        }
        for (k, w) in parts.wires.iter().enumerate() {
            let x = 3 * n2 + 2 * k as u32;
            for (this, other, a, b) in [(x, x + 1, w[0], w[1]), (x + 1, x, w[1], w[0])] {
                debug_assert_eq!(de.de_start.len(), this as usize);
                de.de_start.push(a);
                de.de_end.push(b);
                de.de_radial.push(other);
                de.de_prev.push(other);
                de.de_next.push(other);
            }
        }
        radial::components_headroom(KIND, parts.n, tris.len(), parts.wires.len())?;
        let (off, corners) =
            radial::vertex_components(parts.n, n2, |t| row3(tris, t), |s| rad.next[s as usize]);
        // Append each vertex's wire directed edges after its triangle components.
        let (woff, wnbr) = radial::wire_lists(parts.n, &parts.wires);
        let mut comp_off = vec![0u32; parts.n as usize + 1];
        let mut comp_de = Vec::with_capacity(corners.len() + wnbr.len());
        for v in 0..parts.n as usize {
            comp_de.extend_from_slice(&corners[off[v] as usize..off[v + 1] as usize]);
            for &w in &wnbr[woff[v] as usize..woff[v + 1] as usize] {
                let v = v as u32;
                let k = parts
                    .wires
                    .find(&[v.min(w), v.max(w)])
                    .expect("wire edge listed");
                comp_de.push(3 * n2 + 2 * k + u32::from(w < v));
            }
            comp_off[v + 1] = comp_de.len() as u32;
        }
        de.comp_off = comp_off.into();
        de.comp_de = comp_de.into();
        Ok(de)
    }

    /// One directed edge starting at `v` per connected component of lk(v).
    pub fn vertex_directed_edges(&self, v: u32) -> &[u32] {
        &self.comp_de[self.comp_off[v as usize] as usize..self.comp_off[v as usize + 1] as usize]
    }

    /// Start and end vertex of directed edge `x`.
    pub fn ends(&self, x: u32) -> (u32, u32) {
        (self.de_start[x as usize], self.de_end[x as usize])
    }

    /// The radially adjacent directed edge of `x`.
    pub fn adjacent(&self, x: u32) -> u32 {
        self.de_radial[x as usize]
    }

    fn wire_ends(&self, k: u32) -> (u32, u32) {
        self.ends(3 * self.n_tris + 2 * k)
    }
}

impl TriTopo for DirectedEdge {
    #[inline]
    fn n_tris(&self) -> u32 {
        self.n_tris
    }

    #[inline]
    fn tri(&self, t: u32) -> [u32; 3] {
        let i = 3 * t as usize;
        [self.de_start[i], self.de_start[i + 1], self.de_start[i + 2]]
    }

    #[inline]
    fn radial_next(&self, s: u32) -> u32 {
        self.de_radial[s as usize]
    }

    fn star_corners(&self, v: u32, out: &mut Vec<u32>) {
        let m = 3 * self.n_tris;
        let reps = self
            .vertex_directed_edges(v)
            .iter()
            .copied()
            .filter(|&x| x < m);
        radial::walk_star(self, v, reps, out);
    }

    fn wire_neighbours(&self, v: u32, out: &mut Vec<u32>) {
        let m = 3 * self.n_tris;
        for &x in self.vertex_directed_edges(v) {
            if x >= m {
                out.push(self.de_end[x as usize]);
            }
        }
    }

    fn find_edge(&self, a: u32, b: u32) -> Option<EdgeAt> {
        if let Some(s) = self.locator.find(self.n_tris, |t| self.tri(t), a, b) {
            return Some(EdgeAt::Slot(s));
        }
        let k = radial::partition(self.n_wires, |k| self.wire_ends(k) < (a, b));
        (k < self.n_wires && self.wire_ends(k) == (a, b)).then_some(EdgeAt::Wire)
    }
}

radial::nav_base!(DirectedEdge);

impl Topology for DirectedEdge {
    crate::relation::topology_preamble! {
        self, KIND;
        dimension: self.dim;
        vertex_count: self.n;
        count(p): per_dimension(p, self.dim, [self.n as usize, self.n_edges, self.n_tris as usize]);
        top_count(p):
            per_dimension(p, 2, [self.isolated, self.n_wires as usize, self.n_tris as usize]);
        answers: radial;
        simplices: radial(self.n);
    }

    fn storage(&self) -> Storage {
        let integers = 5 * self.de_start.len() as u64 + self.comp_de.len() as u64;
        let words = [
            &self.de_start,
            &self.de_end,
            &self.de_radial,
            &self.de_prev,
            &self.de_next,
            &self.comp_off,
            &self.comp_de,
        ]
        .iter()
        .map(|a| a.capacity())
        .sum::<usize>();
        Storage {
            integers,
            bits: 0,
            bytes: (words * 4 + self.locator.heap_bytes()) as u64,
        }
    }

    fn validate(&self) -> Result<(), String> {
        let m = 3 * self.n_tris;
        let d = (m + 2 * self.n_wires) as usize;
        if [
            &self.de_start,
            &self.de_end,
            &self.de_radial,
            &self.de_prev,
            &self.de_next,
        ]
        .iter()
        .any(|a| a.len() != d)
        {
            return Err("directed-edge arrays have the wrong length".into());
        }
        for x in 0..d as u32 {
            let i = x as usize;
            let (next, prev, rad) = (self.de_next[i], self.de_prev[i], self.de_radial[i]);
            if [next, prev, rad].iter().any(|&y| y as usize >= d) {
                return Err(format!("directed edge {x} refers outside the array"));
            }
            if self.de_prev[next as usize] != x {
                return Err(format!(
                    "directed edge {x}: next and previous are not inverse"
                ));
            }
            if self.de_end[i] != self.de_start[next as usize] || self.de_start[i] >= self.n {
                return Err(format!(
                    "directed edge {x} does not end where its next starts"
                ));
            }
            let (a, b) = self.ends(x);
            let (c, e) = self.ends(rad);
            if (a.min(b), a.max(b)) != (c.min(e), c.max(e)) || a == b {
                return Err(format!(
                    "directed edge {x}: radial neighbour on another edge"
                ));
            }
            if x < m {
                if next != x - x % 3 + (x + 1) % 3 || rad >= m {
                    return Err(format!("directed edge {x} leaves triangle {}", x / 3));
                }
            } else if next != rad || self.de_next[next as usize] != x || (x - m) % 2 == 1 && a < b {
                return Err(format!("wire directed edge {x} is not in a loop of two"));
            }
        }
        for k in 1..self.n_wires {
            if self.wire_ends(k - 1) >= self.wire_ends(k) {
                return Err(format!("wire edges not in lexicographic order at {k}"));
            }
        }
        radial::validate_common(self, self.n)?;
        radial::validate_components(self, self.n, |v| {
            self.vertex_directed_edges(v)
                .iter()
                .copied()
                .filter(|&x| x < m)
                .collect()
        })?;
        let mut wires_listed = 0;
        for v in 0..self.n {
            for &x in self.vertex_directed_edges(v) {
                if x >= m {
                    wires_listed += 1;
                    if self.de_start[x as usize] != v {
                        return Err(format!(
                            "vertex {v} lists wire directed edge {x} of another"
                        ));
                    }
                }
            }
        }
        if wires_listed != 2 * self.n_wires as usize {
            return Err("not every wire directed edge is listed at its start".into());
        }
        self.locator.validate(self.n_tris, |t| self.tri(t))
    }
}

crate::persist_fields!(DirectedEdge {
    n,
    dim,
    isolated,
    n_tris,
    n_wires,
    n_edges,
    de_start,
    de_end,
    de_radial,
    de_prev,
    de_next,
    comp_off,
    comp_de,
    locator, nav
} check |s| {
    crate::codec::dimension_at_most(s.dim, 2)?;
    if s.de_start.len() != s.de_end.len() || s.de_next.len() != s.de_start.len() {
        return Err("directed-edge arrays of different lengths".into());
    }
    Ok(())
});
