//! Dense indices for the live complex, so that it answers the index-based half of the handle API
//! ([`Navigate::handle`] for every p, [`Navigate::index_of`], `related_ids`, `related_batch`,
//! `degree_batch`, [`Navigate::relation_view`]) like the nine structures, without storing
//! anything for them until asked.
//!
//! # Numbering
//! - A vertex's index is its slot (its id): stable across edits until
//!   [`LiveComplex::compact`]. Vertex indices run over `0..vertex_slots()`; removed vertices are
//!   holes (a handle of one is refused, its row of a vertex view is empty), so
//!   `vertex_slots() == count(0)` exactly when no vertex was removed since the last compaction.
//! - A p-simplex, p ≥ 1, has the index of its rank among the p-simplices in ascending
//!   lexicographic order of their vertex ids — what the nine structures use. An edit (insert,
//!   remove, contract, split, add a vertex, compact) renumbers them: indices above vertices,
//!   dense handles built from them (`SimplexHandle::dense(p, i)`, which the C++ ranges make from
//!   an index) and lent views are valid until the next edit; an edit drops every table and view
//!   (so the Rust borrow checker, and the C documentation, end their use there). Handles the
//!   live complex gives out (top simplex + mask, module doc of `nav`) do survive edits: keep
//!   those, not indices, across an edit. Setting coordinates is not an edit of the topology and
//!   keeps everything.
//!
//! # Storage and cost
//! Nothing until a dimension's index is asked. Then, per dimension p ≥ 1, the lexicographic
//! table of its p-simplices, built once per edit from [`Topology::simplices`] (O(Σ_t C(|t|, p+1)
//! log) time, (p + 1)·n_p integers), after which `handle(p, i)` is O(p + d·k_v) (a row read, then
//! the simplex named canonically) and `index_of` O(p log n_p) (a binary search); and per relation
//! R_{p,q} lent as a view, its CSR (`4 (rows + 1) + 4 Σ|R_{p,q}|` bytes, one walk over every
//! p-simplex). Both are reported by [`Navigate::handle_bytes`]. Tables and views are filled from
//! `&self` behind `OnceLock`s, so queries stay `&self` and thread-safe; two threads asking at
//! once may both build, and the first result is kept.

use std::sync::OnceLock;

use super::LiveComplex;
use crate::complex::{MAX_DIMENSION, SimplexTable};
use crate::relation::Topology;
use crate::relation::handle::{Order, RelationView, SimplexHandle};
use crate::relation::{QueryError, handle::Navigate};
use crate::structures::nav::Csr;

/// The lazily built numbering of one state of the live complex (see the module doc); emptied by
/// every edit.
#[derive(Debug, Default)]
pub(super) struct DenseIndex {
    /// Lexicographic table of the p-simplices, p ≥ 1 (slot 0 unused).
    tables: [OnceLock<SimplexTable>; MAX_DIMENSION + 1],
    /// Views built for [`Navigate::relation_view`], slot `p (d + 1) + q` for the dimension d
    /// the complex had when the first was asked (no edit since, so d has not changed).
    views: OnceLock<Box<[OnceLock<Csr>]>>,
    /// The tops across each facet (module `across`), when asked.
    across: OnceLock<super::across::Across>,
    /// Every vertex's one-ring (module `rings`), when asked.
    rings: OnceLock<super::rings::RingIndex>,
}

/// A clone starts with no tables: they are caches, rebuilt on use.
impl Clone for DenseIndex {
    fn clone(&self) -> DenseIndex {
        DenseIndex::default()
    }
}

impl DenseIndex {
    /// The facet adjacency's place (module `across`).
    pub(super) fn across(&self) -> &OnceLock<super::across::Across> {
        &self.across
    }

    /// The one-rings' place (module `rings`).
    pub(super) fn rings(&self) -> &OnceLock<super::rings::RingIndex> {
        &self.rings
    }

    /// Heap bytes of the tables, views, facet adjacency and rings built so far.
    pub(super) fn bytes(&self) -> u64 {
        self.bytes_of_numbering()
            + self.across.get().map_or(0, |a| a.bytes())
            + self.rings.get().map_or(0, |r| r.bytes())
    }

    fn bytes_of_numbering(&self) -> u64 {
        let tables: usize = self
            .tables
            .iter()
            .filter_map(OnceLock::get)
            .map(SimplexTable::heap_bytes)
            .sum();
        let views: usize = self.views.get().map_or(0, |v| {
            v.len() * std::mem::size_of::<OnceLock<Csr>>()
                + v.iter()
                    .filter_map(OnceLock::get)
                    .map(|c| 4 * (c.offsets.capacity() + c.ids.capacity()))
                    .sum::<usize>()
        });
        (tables + views) as u64
    }
}

impl LiveComplex {
    /// Drops the numbering above vertices and every lent view: called by each edit.
    pub(super) fn renumbered(&mut self) {
        self.dense = DenseIndex::default();
    }

    /// The lexicographic table of the p-simplices (1 ≤ p ≤ MAX_DIMENSION), built on first use.
    pub(super) fn table(&self, p: usize) -> &SimplexTable {
        self.dense.tables[p].get_or_init(|| {
            let mut rows = Vec::new();
            self.simplices(p, &mut rows);
            SimplexTable::from_sorted_unique(p + 1, rows)
        })
    }

    /// n_p (p ≥ 1) when this state's table of p-simplices is built, without building it.
    pub(super) fn counted(&self, p: usize) -> Option<usize> {
        self.dense.tables.get(p)?.get().map(SimplexTable::len)
    }

    /// Number of dense indices of dimension p: vertex slots for p = 0, n_p above.
    pub(super) fn index_count(&self, p: usize) -> usize {
        if p == 0 {
            self.vertex_slots() as usize
        } else {
            self.table(p).len()
        }
    }

    /// The view of R_{p,q} (both ≤ the dimension, checked by the caller), built on first use.
    pub(super) fn dense_view(&self, p: usize, q: usize) -> Result<RelationView<'_>, QueryError> {
        let d = Topology::dimension(self);
        let slots = self
            .dense
            .views
            .get_or_init(|| (0..(d + 1) * (d + 1)).map(|_| OnceLock::new()).collect());
        let slot = &slots[p * (d + 1) + q];
        if slot.get().is_none() {
            let _ = slot.set(self.build_view(p, q)?);
        }
        let c = slot.get().expect("set above");
        Ok(RelationView::new(&c.offsets, &c.ids, true))
    }

    /// One walk over every index of dimension p (a removed vertex: an empty row), each answer
    /// as dense q-indices in natural (lexicographic) order; arrays grown fallibly.
    fn build_view(&self, p: usize, q: usize) -> Result<Csr, QueryError> {
        Csr::build(self.index_count(p), |i, buf| {
            if p > 0 || self.alive[i as usize] {
                let h = Navigate::handle(self, p, i)?;
                self.related_ids(h, q, Order::Natural, buf)?;
            }
            Ok(())
        })
    }

    /// The dense index of the simplex with ascending ids `s` (a simplex of the complex).
    pub(super) fn rank_of(&self, s: &[u32]) -> u32 {
        if s.len() == 1 {
            return s[0];
        }
        self.table(s.len() - 1)
            .find(s)
            .expect("a simplex of the complex is in its dimension's table")
    }

    /// The dense handle of R-answer `x` (a handle this complex just gave out).
    pub(super) fn dense_of(&self, x: SimplexHandle) -> Result<u32, QueryError> {
        Ok(self.rank_of(&self.vertices_of(x)?))
    }
}
