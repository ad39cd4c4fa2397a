//! Incidence Graph (IG) — Edelsbrunner 1987, as described in §3.2 of the 2005 survey.
//!
//! # What it encodes
//! Every simplex of the complex, and for each p-simplex σ its immediate boundary B_{p,p−1}(σ)
//! (0 < p ≤ d) and immediate co-boundary C_{p,p+1}(σ) (0 ≤ p < d).
//!
//! # Layout
//! - `tables[p]`: the p-simplices as ascending vertex ids in ascending lexicographic order; a
//!   p-simplex's id is its row. Vertex `v` is 0-simplex `v`.
//! - `boundary[p]` (p ≥ 1): p + 1 ids into `tables[p − 1]` per p-simplex; entry `i` is the facet
//!   opposite the simplex's `i`-th vertex.
//! - `cob_offsets[p]`, `cob[p]` (p < d): C_{p,p+1} in CSR form, each list ascending.
//!
//! # Storage
//! As the SIG paper (§7.1) counts the IG: `2 Σ_{0<p≤d} (p+1) n_p + Σ_{0≤p<d} n_p` integers
//! (each boundary link stored twice, plus one index per co-boundary array) and no bits. The
//! vertex tables, which the paper does not count, are in the real bytes: the relation API
//! addresses simplices by vertex ids, and binary search in them is how a simplex is found.
//!
//! # Cost of each relation (after locating σ: O(p log n_p) by binary search)
//! - R_{p,q}, q < p: the (q+1)-subsets of σ's vertex ids, which the tables already hold (the
//!   papers' recursive walk down the boundary links visits C(p+1, l+1) simplices per level l
//!   and needs deduplication for the same answer): O(C(p+1, q+1)·(q+1)) — optimal.
//! - R_{p,q}, q > p: co-boundary level by level: O(Σ_{p<l≤q} (l+1−p) s_l), where s_l is the
//!   number of l-simplices in the star of σ — linear in the part of the star walked.
//! - R_{p,p}, p > 0: for each facet, its co-boundary minus σ: O(Σ_f |C_{p−1,p}(f)|); two
//!   distinct p-simplices share at most one facet, so nothing needs deduplication.
//! - R_{0,0}: the other end of each edge in C_{0,1}(v): O(deg v).
//!
//! Queries keep no state in the structure: the "visited" marks are a per-query set.

use super::common::{IdSet, Scratch, faces_containing, try_closure_links};
use super::nav::{Fast, NavBase, NavIndex, Visit, with_scratch};
use super::{BuildError, to_u32};
use crate::complex::{Complex, SimplexTable};
use crate::mapped::Arr;
use crate::relation::handle::SimplexHandle;
use crate::relation::{QueryError, Storage, StructureKind, Topology};

const KIND: StructureKind = StructureKind::Ig;

/// The Incidence Graph (see the module documentation for what it stores and costs).
#[derive(Debug, Clone)]
pub struct IncidenceGraph {
    tables: Vec<SimplexTable>,
    boundary: Vec<Arr<u32>>,
    cob_offsets: Vec<Arr<u32>>,
    cob: Vec<Arr<u32>>,
    top_counts: Vec<usize>,
    /// Handle bookkeeping: windings, top simplices below d, lazy tables ([`super::nav`]).
    pub(crate) nav: NavIndex,
}

impl IncidenceGraph {
    /// Builds from the closure of the complex: boundaries by radix sorting the facet slots and
    /// merging them with the sorted table below, co-boundaries by a counting sort of the
    /// boundaries (`parallel::try_invert`: one range of simplices per thread, the same
    /// lists with any thread count; 4 bytes a simplex per thread while it runs). O(Σ_p (p+1) n_p · p) time when p facet ids fit in 64 bits (else a binary
    /// search per facet, O(Σ_p (p+1) n_p · p log n_p)).
    pub fn build(complex: &Complex) -> Result<IncidenceGraph, BuildError> {
        let (tables, boundary) = try_closure_links(KIND, complex)?;
        for (p, t) in tables.iter().enumerate() {
            to_u32(KIND, t.len(), "simplices of one dimension")?;
            to_u32(KIND, t.len() * (p + 1), "boundary links of one dimension")?;
        }
        let d = tables.len() - 1;
        let mut cob_offsets = vec![Vec::new(); d];
        let mut cob = vec![Vec::new(); d];
        for p in 0..d {
            let (off, list) = invert(tables[p].len(), &boundary[p + 1], p + 2)?;
            cob_offsets[p] = off;
            cob[p] = list;
        }
        let top_counts = (0..=d)
            .map(|p| {
                if p == d {
                    tables[d].len()
                } else {
                    (0..tables[p].len())
                        .filter(|&i| cob_offsets[p][i] == cob_offsets[p][i + 1])
                        .count()
                }
            })
            .collect();
        let nav = NavIndex::new(KIND, complex)?;
        Ok(IncidenceGraph {
            nav,
            tables,
            boundary: boundary.into_iter().map(Arr::from).collect(),
            cob_offsets: cob_offsets.into_iter().map(Arr::from).collect(),
            cob: cob.into_iter().map(Arr::from).collect(),
            top_counts,
        })
    }

    /// Id of a p-simplex (ascending ids) in `tables[p]`.
    pub fn find(&self, sigma: &[u32]) -> Option<u32> {
        self.tables.get(sigma.len().checked_sub(1)?)?.find(sigma)
    }

    /// The p-simplices in id order.
    pub fn table(&self, p: usize) -> &SimplexTable {
        &self.tables[p]
    }

    /// B_{p,p−1} of p-simplex `id`: facet ids, entry i opposite vertex i.
    #[inline]
    pub fn boundary_ids(&self, p: usize, id: u32) -> &[u32] {
        let w = p + 1;
        &self.boundary[p][id as usize * w..(id as usize + 1) * w]
    }

    /// C_{p,p+1} of p-simplex `id`: ids of (p+1)-simplices, ascending (empty for p = d).
    #[inline]
    pub fn coboundary_ids(&self, p: usize, id: u32) -> &[u32] {
        match (self.cob_offsets.get(p), self.cob.get(p)) {
            (Some(off), Some(list)) => {
                &list[off[id as usize] as usize..off[id as usize + 1] as usize]
            }
            _ => &[],
        }
    }

    fn emit(&self, q: usize, ids: impl IntoIterator<Item = u32>, out: &mut Vec<u32>) {
        for i in ids {
            out.extend_from_slice(self.tables[q].get(i as usize));
        }
    }
}

/// Inverts fixed-width `links` (each row of `width` ids into a table of `n` simplices) into CSR
/// form: for each target, the rows pointing at it, ascending. On several threads for large
/// tables (`parallel::try_invert`); `TooLarge` when the arrays cannot be had.
fn invert(n: usize, links: &[u32], width: usize) -> Result<(Vec<u32>, Vec<u32>), BuildError> {
    struct Rows<'a>(&'a [u32], usize);
    impl crate::parallel::Incidences for Rows<'_> {
        fn visit(&self, range: std::ops::Range<usize>, f: &mut impl FnMut(u32, u32)) {
            let w = self.1;
            let rows = self.0[range.start * w..range.end * w].chunks_exact(w);
            for (x, row) in (range.start as u32..).zip(rows) {
                for &t in row {
                    f(x, t);
                }
            }
        }
    }
    crate::parallel::try_invert(n, links.len() / width, &Rows(links, width))
        .map_err(|bytes| super::common::too_large(KIND, bytes, "the co-boundaries"))
}

impl NavBase for IncidenceGraph {
    fn nav(&self) -> &NavIndex {
        &self.nav
    }

    fn stored_table(&self, p: usize) -> Option<&SimplexTable> {
        self.tables.get(p)
    }

    // The stored relations with no call per answer: R_{p,p±1} and R_{0,0}, the same answers in
    // the same order as `fast_visit`.
    fn has_fast(&self, p: usize, q: usize) -> bool {
        q + 1 == p || q == p + 1 || (p == 0 && q == 0)
    }

    fn fast_into(&self, p: usize, i: u32, q: usize, ids: &mut Vec<u32>) {
        if q + 1 == p {
            ids.extend_from_slice(self.boundary_ids(p, i));
        } else if q == p + 1 {
            ids.extend_from_slice(self.coboundary_ids(p, i));
        } else {
            for &e in self.coboundary_ids(0, i) {
                let ends = self.boundary_ids(1, e);
                ids.push(if ends[0] == i { ends[1] } else { ends[0] });
            }
        }
    }

    // Counts the IG stores: p + 1 facets, the co-boundary's offsets, and for R_{0,0} the edges
    // at v (each edge at v has a distinct other end).
    fn stored_degree(&self, p: usize, i: u32, q: usize) -> Option<usize> {
        if q + 1 == p {
            Some(p + 1)
        } else if q == p + 1 || (p == 0 && q == 0) {
            Some(self.coboundary_ids(p, i).len())
        } else {
            None
        }
    }

    // C_{p,p+1} is stored in CSR form, ascending within a list: lent as it is.
    fn stored_view(&self, p: usize, q: usize) -> Option<crate::relation::handle::RelationView<'_>> {
        (q == p + 1).then(|| {
            crate::relation::handle::RelationView::new(&self.cob_offsets[p], &self.cob[p], false)
        })
    }

    /// The stored links as handles (row `i` of `tables[p]` is dense p-simplex `i`): R_{p,p−1},
    /// R_{p,p+1} O(answer); R_{0,0} the other end of each edge at v. Others: the generic path.
    fn fast_visit(&self, h: SimplexHandle, _sigma: &[u32], q: usize, visit: Visit<'_>) -> Fast {
        let (p, id) = (h.dim(), h.index());
        let ids = if q + 1 == p {
            self.boundary_ids(p, id)
        } else if q == p + 1 {
            self.coboundary_ids(p, id)
        } else if p == 0 && q == 0 {
            for &e in self.coboundary_ids(0, id) {
                let ends = self.boundary_ids(1, e);
                let other = if ends[0] == id { ends[1] } else { ends[0] };
                visit(SimplexHandle::dense(0, other));
            }
            return Some(Ok(()));
        } else if q != p {
            // Several steps up or down: one step at a time, each level sorted and deduplicated
            // (so the natural order here is ascending), in this thread's scratch buffers.
            with_scratch(|level| {
                let up = q > p;
                let step = |r: usize, x: u32| {
                    if up {
                        self.coboundary_ids(r, x)
                    } else {
                        self.boundary_ids(r, x)
                    }
                };
                level.push(id);
                let mut next = Scratch::<Vec<u32>>::take();
                let mut r = p;
                while r != q {
                    next.clear();
                    for &x in level.iter() {
                        next.extend_from_slice(step(r, x));
                    }
                    next.sort_unstable();
                    next.dedup();
                    std::mem::swap(level, &mut *next);
                    r = if up { r + 1 } else { r - 1 };
                }
                level
                    .iter()
                    .for_each(|&x| visit(SimplexHandle::dense(q, x)));
            });
            return Some(Ok(()));
        } else {
            return None;
        };
        ids.iter().for_each(|&x| visit(SimplexHandle::dense(q, x)));
        Some(Ok(()))
    }
}

impl Topology for IncidenceGraph {
    crate::relation::topology_preamble! {
        self, KIND;
        dimension: self.tables.len() - 1;
        vertex_count: self.tables[0].len() as u32;
        count(p): self.tables.get(p).map_or(0, SimplexTable::len);
        top_count(p): self.top_counts.get(p).copied().unwrap_or(0);
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
        if q == p {
            if p == 0 {
                for &e in self.coboundary_ids(0, id) {
                    let edge = self.tables[1].get(e as usize);
                    out.push(if edge[0] == id { edge[1] } else { edge[0] });
                }
            } else {
                for &f in self.boundary_ids(p, id) {
                    let others = self
                        .coboundary_ids(p - 1, f)
                        .iter()
                        .copied()
                        .filter(|&t| t != id);
                    self.emit(p, others, out);
                }
            }
            return Ok(());
        }
        if q < p {
            // The q-faces are the (q+1)-subsets of σ's vertex ids, which the tables store: no
            // link needs following once σ is found.
            faces_containing(sigma, &[], q, |f| out.extend_from_slice(f));
            return Ok(());
        }
        if q == p + 1 {
            self.emit(q, self.coboundary_ids(p, id).iter().copied(), out);
            return Ok(());
        }
        // Walk up one level at a time, deduplicating with per-query marks.
        let mut level = self.coboundary_ids(p, id).to_vec();
        let mut next = Vec::new();
        let mut seen = IdSet::default();
        for l in p + 1..q {
            next.clear();
            seen.clear();
            for &s in &level {
                let step = self.coboundary_ids(l, s);
                next.extend(step.iter().copied().filter(|&t| seen.insert(t)));
            }
            std::mem::swap(&mut level, &mut next);
        }
        self.emit(q, level, out);
        Ok(())
    }

    fn storage(&self) -> Storage {
        let links: usize = self.boundary.iter().map(|b| b.len()).sum::<usize>()
            + self.cob.iter().map(|c| c.len()).sum::<usize>();
        let arrays: usize = self.tables[..self.tables.len() - 1]
            .iter()
            .map(SimplexTable::len)
            .sum();
        let bytes = self
            .tables
            .iter()
            .map(SimplexTable::heap_bytes)
            .sum::<usize>()
            + [&self.boundary, &self.cob_offsets, &self.cob]
                .iter()
                .flat_map(|v| v.iter())
                .map(|a| a.capacity() * 4)
                .sum::<usize>();
        Storage {
            integers: (links + arrays) as u64,
            bits: 0,
            bytes: bytes as u64,
        }
    }

    fn validate(&self) -> Result<(), String> {
        let d = self.dimension();
        if self.tables[0]
            .iter()
            .enumerate()
            .any(|(i, v)| v[0] as usize != i)
        {
            return Err("vertex table is not 0..n".into());
        }
        for p in 0..=d {
            let t = &self.tables[p];
            if t.arity() != p + 1 {
                return Err(format!("table {p} has arity {}", t.arity()));
            }
            for i in 1..t.len() {
                if t.get(i - 1) >= t.get(i) {
                    return Err(format!("table {p} not strictly ascending at row {i}"));
                }
            }
            for (i, s) in t.iter().enumerate() {
                if s.windows(2).any(|w| w[0] >= w[1]) {
                    return Err(format!("{p}-simplex {i} {s:?} not ascending"));
                }
                if p > 0 {
                    for (k, &f) in self.boundary_ids(p, i as u32).iter().enumerate() {
                        let facet: Vec<u32> = s
                            .iter()
                            .enumerate()
                            .filter(|&(j, _)| j != k)
                            .map(|(_, &v)| v)
                            .collect();
                        if self.tables[p - 1].get(f as usize) != facet.as_slice() {
                            return Err(format!(
                                "boundary entry {k} of {p}-simplex {s:?} is not the facet {facet:?}"
                            ));
                        }
                        if !self.coboundary_ids(p - 1, f).contains(&(i as u32)) {
                            return Err(format!(
                                "{s:?} missing from the co-boundary of its facet {facet:?}"
                            ));
                        }
                    }
                }
                if p < d {
                    for &c in self.coboundary_ids(p, i as u32) {
                        if !self.boundary_ids(p + 1, c).contains(&(i as u32)) {
                            return Err(format!(
                                "co-boundary of {s:?} lists {:?}, which does not have it as a facet",
                                self.tables[p + 1].get(c as usize)
                            ));
                        }
                    }
                }
            }
            if p < d && self.cob[p].len() != self.boundary[p + 1].len() {
                return Err(format!(
                    "C_{{{p},{}}} has {} links, B_{{{},{p}}} has {}",
                    p + 1,
                    self.cob[p].len(),
                    p + 1,
                    self.boundary[p + 1].len()
                ));
            }
        }
        if self.tables[d].is_empty() {
            return Err(format!("no {d}-simplex in a {d}-complex"));
        }
        Ok(())
    }
}

crate::persist_fields!(IncidenceGraph { tables, boundary, cob_offsets, cob, top_counts, nav } check |s| {
    let levels = s.tables.len();
    if levels == 0 || s.boundary.len() != levels || s.cob_offsets.len() + 1 != levels || s.cob.len() + 1 != levels || s.top_counts.len() != levels {
        return Err("per-dimension tables of different lengths".into());
    }
    for (p, t) in s.tables.iter().enumerate() {
        if t.arity() != p + 1 || (p > 0 && s.boundary[p].len() != t.len() * (p + 1)) {
            return Err(format!("{p}-simplex table or boundary rows of the wrong shape"));
        }
    }
    Ok(())
});
