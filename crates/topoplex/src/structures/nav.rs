//! [`Navigate`] written once for the nine structures, over dense handles (see
//! [`crate::relation::handle`]): what each structure adds is [`NavBase`] — where its [`NavIndex`] lives,
//! which dimensions it stores as a lexicographic table, and optional fast walks.
//!
//! # What the index holds, and its cost
//! - the winding of every top simplex: the permutation from its ascending vertices to its first
//!   listing in the input, 4 bits per vertex in one `u64` per top simplex (8 bytes each);
//! - the top simplices below the complex's dimension d (wire edges, dangling faces, isolated
//!   vertices), as a lexicographic table per dimension, to tell top simplices from others and
//!   to number them; top d-simplices are the d-simplices, so need no table;
//! - lazily, per dimension p the structure does not store, the lexicographic table of the
//!   p-simplices (built from [`Topology::simplices`] on the first request that needs it:
//!   O(n_p log n_p) time, (p + 1)·n_p integers) with, per vertex, its first row among the rows
//!   that start with it (n_0 + 1 integers: a row is then searched among the rows sharing its
//!   first vertex, not in the whole table);
//! - lazily, per relation R_{p,q} a caller asks to be lent ([`Navigate::relation_view`]) and the
//!   structure does not store as a CSR, its index: `n_p + 1` offsets and every answer, 4 bytes
//!   each, built by one walk over every p-simplex on the first request.
//!
//! # Cost of each operation (on top of the structure's own relation cost)
//! - `locate`: validation, then binary search in the p-table: O(p log n_p) in a stored table,
//!   O(p log r) in a lazy one (r rows share the simplex's first vertex); vertices O(1).
//! - `vertices_of`: O(p) (a table row). `top`, `top_id`: O(1) for d-simplices, O(p log t_p)
//!   below d (t_p top p-simplices).
//! - `visit`: a structure's fast walk when it has one (answers are handles directly); otherwise
//!   the structure's vertex-id relation into a per-thread scratch buffer, then each answer row
//!   located in its table, O(q log n_q) per answer (O(q log r) in a lazy table, as `locate`).
//!   No allocation once the scratch is warm.
//! - `related_ids`, `related_batch`: where the structure has a loop for (p, q)
//!   ([`NavBase::fast_into`]: TS, PE, LE, DE for VV, VF, FF; the IG for R_{p,p±1} and R_{0,0};
//!   the IA for R_{d,d} and R_{0,d}) the answers are appended with no call per answer and the
//!   handle checked once; otherwise one `visit` per simplex.
//! - `degree_batch`: O(1) per simplex for counts the structure stores
//!   ([`NavBase::stored_degree`]: the IG), else the walk counted in a scratch buffer.
//! - `relation_view`: O(1) once built (the IG's co-boundaries are lent as stored, never built).

use std::sync::OnceLock;

use super::BuildError;
use super::common::{Scratch, try_table, try_with_capacity};
use crate::codec::Field;
use crate::complex::{Complex, MAX_DIMENSION, SimplexTable};
use crate::mapped::Arr;
use crate::relation::handle::{
    HandleForm, Navigate, Order, RelationView, SimplexHandle, TopId, Vertices, append_in_order,
    batch_by_ids,
};
use crate::relation::{QueryError, StructureKind, Topology, normalize_simplex_into};

// Saved with its structure (`.tpx`): the windings are mapped back, the lazy tables rebuilt on use.
impl crate::codec::Field for NavIndex {
    fn put(&self, w: &mut crate::codec::Writer) {
        self.top_first.put(w);
        self.windings.put(w);
        self.low_tops.put(w);
    }
    fn get(r: &mut crate::codec::Reader) -> Result<Self, crate::codec::StoreError> {
        let nav = NavIndex {
            top_first: Field::get(r)?,
            windings: Field::get(r)?,
            low_tops: Field::get(r)?,
            lazy: Default::default(),
            views: Default::default(),
        };
        // The shape every handle lookup indexes by, checked before anything trusts it.
        let t = &nav.top_first;
        let consistent =
            t.len() >= 2
                && t.windows(2).all(|w| w[0] <= w[1])
                && t[0] == 0
                && nav.windings.len() == t[t.len() - 1] as usize
                && nav.low_tops.len() == t.len() - 2
                && nav.low_tops.iter().enumerate().all(|(p, tab)| {
                    tab.arity() == p + 1 && tab.len() == (t[p + 1] - t[p]) as usize
                });
        if !consistent {
            return Err(r.corrupt("handle index: top counts, windings and low tops disagree"));
        }
        Ok(nav)
    }
}

/// The handle bookkeeping one structure owns (see the module doc).
#[derive(Debug, Clone, Default)]
#[doc(hidden)]
pub struct NavIndex {
    /// `TopId` of the first top p-simplex, per p, plus the total.
    top_first: Vec<u32>,
    /// Winding of each top simplex: nibble i is the rank, among its ascending vertices, of the
    /// i-th vertex of its first listing.
    windings: Arr<u64>,
    /// Top p-simplices for p < d, lexicographic.
    low_tops: Vec<SimplexTable>,
    /// Lexicographic p-tables of the dimensions the structure does not store.
    lazy: [OnceLock<LazyTable>; MAX_DIMENSION + 1],
    /// Relation indexes built for [`Navigate::relation_view`], slot `p (d + 1) + q`.
    views: OnceLock<Box<[OnceLock<Csr>]>>,
}

/// A lazily built lexicographic p-table and, per vertex v, the first row starting with v
/// (`first[v] .. first[v + 1]` are the rows whose smallest vertex is v).
#[derive(Debug, Clone, Default)]
#[doc(hidden)]
pub struct LazyTable {
    table: SimplexTable,
    first: Vec<u32>,
}

impl LazyTable {
    /// The table of `rows` (ascending, distinct rows of p + 1 ids below `n`) and its per-vertex
    /// starts: O(rows + n).
    fn new(p: usize, n: u32, rows: Vec<u32>) -> LazyTable {
        let table = SimplexTable::from_sorted_unique(p + 1, rows);
        // Rows are ascending: the last one has the largest first vertex.
        let n = table
            .len()
            .checked_sub(1)
            .map_or(n, |r| n.max(table.get(r)[0] + 1));
        let mut first = vec![0u32; n as usize + 1];
        for row in table.iter() {
            first[row[0] as usize + 1] += 1;
        }
        for v in 0..n as usize {
            first[v + 1] += first[v];
        }
        LazyTable { table, first }
    }

    /// Row index of `s` (ascending ids), searched among the rows sharing its first vertex.
    pub(crate) fn find(&self, s: &[u32]) -> Option<u32> {
        if s.len() != self.table.arity() {
            return None;
        }
        let rows = self.starting_with(s[0]);
        let (mut lo, mut hi) = (rows.start as usize, rows.end as usize);
        while lo < hi {
            let mid = (lo + hi) / 2;
            match self.table.get(mid)[1..].cmp(&s[1..]) {
                std::cmp::Ordering::Less => lo = mid + 1,
                std::cmp::Ordering::Greater => hi = mid,
                std::cmp::Ordering::Equal => return Some(mid as u32),
            }
        }
        None
    }

    /// Row `r`'s ids.
    #[inline]
    pub(crate) fn row(&self, r: u32) -> &[u32] {
        self.table.get(r as usize)
    }

    /// The rows whose smallest vertex is `v` (empty past the last such vertex): O(1).
    pub(crate) fn starting_with(&self, v: u32) -> std::ops::Range<u32> {
        let v = v as usize;
        if v + 1 >= self.first.len() {
            return 0..0;
        }
        self.first[v]..self.first[v + 1]
    }

    fn heap_bytes(&self) -> usize {
        self.table.heap_bytes() + 4 * self.first.capacity()
    }
}

/// `NavBase` for a structure with a `nav: NavIndex` field and no fast path of its own: the
/// generic walks answer every relation.
macro_rules! plain_nav_base {
    ($t:ty) => {
        impl $crate::structures::nav::NavBase for $t {
            fn nav(&self) -> &$crate::structures::nav::NavIndex {
                &self.nav
            }
        }
    };
}
pub(crate) use plain_nav_base;

/// One relation index of [`Navigate::relation_view`]: offsets (n + 1) and answers.
#[derive(Debug, Clone, Default)]
pub(crate) struct Csr {
    pub(crate) offsets: Vec<u32>,
    pub(crate) ids: Vec<u32>,
}

impl Csr {
    /// The rows `row(i, buf)` writes into a cleared scratch buffer for i in 0..n, appended in
    /// turn (the arrays grown fallibly, then trimmed): a relation view's index.
    pub(crate) fn build(
        n: usize,
        mut row: impl FnMut(u32, &mut Vec<u32>) -> Result<(), QueryError>,
    ) -> Result<Csr, QueryError> {
        let too_large = |bytes: u64| QueryError::TooLarge {
            what: "relation view",
            bytes,
        };
        let mut offsets: Vec<u32> = Vec::new();
        offsets
            .try_reserve_exact(n + 1)
            .map_err(|_| too_large(4 * (n as u64 + 1)))?;
        offsets.push(0);
        let mut ids: Vec<u32> = Vec::new();
        let mut buf = Scratch::<Vec<u32>>::take();
        for i in 0..n as u32 {
            buf.clear();
            row(i, &mut buf)?;
            ids.try_reserve(buf.len())
                .map_err(|_| too_large(4 * (ids.len() + buf.len()) as u64))?;
            ids.extend_from_slice(&buf);
            offsets.push(u32::try_from(ids.len()).map_err(|_| too_large(4 * ids.len() as u64))?);
        }
        // Shrinking in place: the amortised growth's slack is not kept for the structure's life.
        ids.shrink_to_fit();
        Ok(Csr { offsets, ids })
    }
}

impl NavIndex {
    /// The index of `complex`: windings of its top simplices and its tops below dimension d.
    /// O(Σ top sizes · log) time.
    pub(crate) fn new(kind: StructureKind, complex: &Complex) -> Result<NavIndex, BuildError> {
        let d = complex.dimension();
        complex
            .try_listing_maps()
            .map_err(|bytes| super::common::too_large(kind, bytes, "the listing maps"))?;
        let mut top_first = Vec::with_capacity(d + 2);
        let tops: usize = (0..=d).map(|p| complex.tops(p).len()).sum();
        let mut windings = try_with_capacity(kind, tops, "top windings")?;
        let mut total = 0u32;
        for p in 0..=d {
            top_first.push(total);
            let tops = complex.tops(p);
            // On several threads: each winding depends on its own top simplex only. Written in
            // place: the array was reserved fallibly, a collected temporary would not be.
            crate::parallel::extend_reserved(&mut windings, tops.len(), |i| {
                winding(tops.get(i), complex.top_oriented(p, i as u32))
            });
            total += tops.len() as u32;
        }
        top_first.push(total);
        let low_tops = (0..d)
            .map(|p| try_table(kind, complex.tops(p)))
            .collect::<Result<_, _>>()?;
        Ok(NavIndex {
            top_first,
            windings: windings.into(),
            low_tops,
            lazy: Default::default(),
            views: Default::default(),
        })
    }

    /// The same index with no lazily built table (for a structure derived from another).
    pub(crate) fn without_caches(&self) -> NavIndex {
        NavIndex {
            top_first: self.top_first.clone(),
            windings: self.windings.clone(),
            low_tops: self.low_tops.clone(),
            lazy: Default::default(),
            views: Default::default(),
        }
    }

    /// Heap bytes held, lazily built tables included.
    pub(crate) fn heap_bytes(&self) -> usize {
        self.top_first.capacity() * 4
            + self.windings.capacity() * 8
            + self
                .low_tops
                .iter()
                .map(SimplexTable::heap_bytes)
                .sum::<usize>()
            + self
                .lazy
                .iter()
                .filter_map(OnceLock::get)
                .map(LazyTable::heap_bytes)
                .sum::<usize>()
            + self.views.get().map_or(0, |v| {
                v.len() * std::mem::size_of::<OnceLock<Csr>>()
                    + v.iter()
                        .filter_map(OnceLock::get)
                        .map(|c| 4 * (c.offsets.capacity() + c.ids.capacity()))
                        .sum::<usize>()
            })
    }
}

/// Equal when the complexes' windings and top simplices are; lazily built tables are caches.
impl PartialEq for NavIndex {
    fn eq(&self, other: &NavIndex) -> bool {
        (&self.top_first, &self.windings, &self.low_tops)
            == (&other.top_first, &other.windings, &other.low_tops)
    }
}

impl Eq for NavIndex {}

/// Nibble-packed ranks of `given`'s vertices within `sorted`.
fn winding(sorted: &[u32], given: &[u32]) -> u64 {
    if sorted == given {
        // Listed in ascending order (the common case for generated complexes): no search.
        return (0..given.len() as u64).fold(0, |w, i| w | i << (4 * i));
    }
    given.iter().enumerate().fold(0u64, |w, (i, v)| {
        let rank = sorted.binary_search(v).expect("same vertex set") as u64;
        w | rank << (4 * i)
    })
}

/// The visitor [`NavBase::fast_visit`] calls with each answer.
pub(crate) type Visit<'a> = &'a mut dyn FnMut(SimplexHandle);

/// What [`NavBase::fast_visit`] returns: `None` when the structure has no walk of its own.
pub(crate) type Fast = Option<Result<(), QueryError>>;

/// What a structure provides to get [`Navigate`].
#[doc(hidden)]
pub trait NavBase: Topology {
    /// The structure's handle bookkeeping.
    fn nav(&self) -> &NavIndex;

    /// The structure's own lexicographic table of p-simplices (p ≥ 1), if it stores one.
    fn stored_table(&self, _p: usize) -> Option<&SimplexTable> {
        None
    }

    /// R_{p,q}(h) straight from the structure's arrays, when it has a walk for this (p, q); `h`
    /// is checked and has vertices `sigma`. `None`: fall back to the vertex-id relation.
    fn fast_visit(&self, _h: SimplexHandle, _sigma: &[u32], _q: usize, _visit: Visit<'_>) -> Fast {
        None
    }

    /// The star of vertex `v` (checked) into `out`: dimensions ascending, each in `order`,
    /// the same answers and order as one [`NavBase::fast_visit`] per dimension, from one walk.
    /// `false` (nothing written) when the structure has no such walk.
    fn fast_star(&self, _v: u32, _order: Order, _out: &mut Vec<SimplexHandle>) -> bool {
        false
    }

    /// Whether [`NavBase::fast_into`] answers R_{p,q} (p, q ≤ d).
    fn has_fast(&self, _p: usize, _q: usize) -> bool {
        false
    }

    /// Appends R_{p,q} of the dense p-simplex `i` to `ids` as dense q-indices, in natural order
    /// (the order [`NavBase::fast_visit`] gives), from the structure's arrays with no call per
    /// answer. Called only when [`NavBase::has_fast`] says so, with `i < count(p)` checked.
    fn fast_into(&self, _p: usize, _i: u32, _q: usize, _ids: &mut Vec<u32>) {}

    /// |R_{p,q}| of dense p-simplex `i` (`i < count(p)` checked) in O(1) from stored arrays,
    /// when the structure stores the relation with its counts (the IG's co-boundary offsets).
    fn stored_degree(&self, _p: usize, _i: u32, _q: usize) -> Option<usize> {
        None
    }

    /// R_{p,q} of every p-simplex as a CSR the structure stores (the IG's co-boundaries), lent
    /// at no cost; `None`: [`Navigate::relation_view`] builds an index.
    fn stored_view(&self, _p: usize, _q: usize) -> Option<RelationView<'_>> {
        None
    }

    /// The lexicographic table of the p-simplices (p ≥ 1): stored, or built on first use.
    fn table(&self, p: usize) -> &SimplexTable {
        if let Some(t) = self.stored_table(p) {
            return t;
        }
        &self.lazy_table(p).table
    }

    /// The lazy p-table (p ≥ 1, not stored), built on first use.
    #[doc(hidden)]
    fn lazy_table(&self, p: usize) -> &LazyTable {
        self.nav().lazy[p].get_or_init(|| {
            let mut rows = Vec::new();
            self.simplices(p, &mut rows);
            LazyTable::new(p, self.vertex_count(), rows)
        })
    }
}

/// Runs `f` with a scratch buffer from this thread's pool, empty (reentrant: a visitor that
/// navigates again gets another buffer).
pub(crate) fn with_scratch<R>(f: impl FnOnce(&mut Vec<u32>) -> R) -> R {
    let mut rows = Scratch::<Vec<u32>>::take();
    f(&mut rows)
}

/// Dense handle of the simplex with ascending ids `s`, if it is in `t`'s structure.
fn find<T: NavBase + ?Sized>(t: &T, s: &[u32]) -> Option<SimplexHandle> {
    let p = s.len() - 1;
    if p == 0 {
        return (s[0] < t.vertex_count()).then(|| SimplexHandle::dense(0, s[0]));
    }
    if p > t.dimension() {
        return None;
    }
    match t.stored_table(p) {
        Some(table) => table.find(s),
        None => t.lazy_table(p).find(s),
    }
    .map(|i| SimplexHandle::dense(p, i))
}

fn invalid(h: SimplexHandle, reason: &'static str) -> QueryError {
    QueryError::InvalidHandle { handle: h, reason }
}

/// `InvalidHandle` for the first of `indices` at or above `count(p)`.
fn check_indices<T: NavBase + ?Sized>(t: &T, p: usize, indices: &[u32]) -> Result<(), QueryError> {
    let count = t.count(p);
    match indices.iter().find(|&&i| i as usize >= count) {
        Some(&bad) => Err(invalid(
            SimplexHandle::dense(p, bad),
            "index beyond the simplices of its dimension",
        )),
        None => Ok(()),
    }
}

/// The index of R_{p,q} behind [`Navigate::relation_view`]: one walk over every p-simplex, each
/// answer walked into a scratch buffer and appended (the arrays grown fallibly, then trimmed).
fn build_view<T: NavBase>(t: &T, p: usize, q: usize) -> Result<Csr, QueryError> {
    Csr::build(t.count(p), |i, buf| {
        t.related_ids(SimplexHandle::dense(p, i), q, Order::Natural, buf)
    })
}

impl<T: NavBase> Navigate for T {
    fn locate(&self, sigma: &[u32]) -> Result<SimplexHandle, QueryError> {
        // Sorted on the stack: locating allocates nothing unless it fails.
        let mut buf = [0u32; MAX_DIMENSION + 1];
        let s = normalize_simplex_into(sigma, self.vertex_count(), &mut buf)?;
        find(self, s).ok_or_else(|| QueryError::NotInComplex {
            simplex: s.to_vec(),
        })
    }

    fn check(&self, h: SimplexHandle) -> Result<(), QueryError> {
        if h.form() != HandleForm::Dense {
            return Err(invalid(h, "not a dense handle of this structure"));
        }
        if h.is_none() {
            return Err(invalid(h, "the NONE handle"));
        }
        if h.dim() > self.dimension() {
            return Err(invalid(h, "dimension above the complex's"));
        }
        if h.index() as usize >= self.count(h.dim()) {
            return Err(invalid(h, "index beyond the simplices of its dimension"));
        }
        Ok(())
    }

    fn vertices_of(&self, h: SimplexHandle) -> Result<Vertices, QueryError> {
        self.check(h)?;
        Ok(match h.dim() {
            0 => Vertices::from_slice(&[h.index()]),
            p => Vertices::from_slice(self.table(p).get(h.index() as usize)),
        })
    }

    fn handle_bytes(&self) -> u64 {
        self.nav().heap_bytes() as u64
    }

    fn top_total(&self) -> u32 {
        *self.nav().top_first.last().unwrap_or(&0)
    }

    fn top(&self, t: TopId) -> Result<SimplexHandle, QueryError> {
        let nav = self.nav();
        if t.0 >= self.top_total() {
            return Err(invalid(
                SimplexHandle::top_face(t, 0),
                "top simplex id out of range",
            ));
        }
        let p = nav.top_first.partition_point(|&f| f <= t.0) - 1;
        let i = t.0 - nav.top_first[p];
        if p == self.dimension() {
            return Ok(SimplexHandle::dense(p, i));
        }
        let s = nav.low_tops[p].get(i as usize);
        Ok(find(self, s).expect("a top simplex is in the complex"))
    }

    fn top_id(&self, h: SimplexHandle) -> Result<Option<TopId>, QueryError> {
        self.check(h)?;
        let nav = self.nav();
        let p = h.dim();
        if p == self.dimension() {
            return Ok(Some(TopId(nav.top_first[p] + h.index())));
        }
        let v = self.vertices_of(h)?;
        Ok(nav.low_tops[p]
            .find(&v)
            .map(|i| TopId(nav.top_first[p] + i)))
    }

    fn top_as_given(&self, t: TopId) -> Result<Vertices, QueryError> {
        let sorted = self.vertices_of(self.top(t)?)?;
        let w = self.nav().windings[t.index()];
        let mut given = [0u32; MAX_DIMENSION + 1];
        for (i, g) in given.iter_mut().enumerate().take(sorted.len()) {
            *g = sorted[((w >> (4 * i)) & 0xf) as usize];
        }
        Ok(Vertices::from_slice(&given[..sorted.len()]))
    }

    fn related_batch(
        &self,
        p: usize,
        indices: &[u32],
        q: usize,
        order: Order,
        ids: &mut Vec<u32>,
        ends: &mut Vec<usize>,
    ) -> Result<(), QueryError> {
        // Out-of-range dimensions take the checked path, which reports them.
        let d = self.dimension();
        if p > d || q > d || !self.has_fast(p, q) {
            return batch_by_ids(self, p, indices, q, order, ids, ends);
        }
        check_indices(self, p, indices)?;
        for &i in indices {
            append_in_order(ids, order, |ids| {
                self.fast_into(p, i, q, ids);
                Ok::<_, QueryError>(())
            })?;
            ends.push(ids.len());
        }
        Ok(())
    }

    fn related_ids(
        &self,
        h: SimplexHandle,
        q: usize,
        order: Order,
        ids: &mut Vec<u32>,
    ) -> Result<(), QueryError> {
        let (p, d) = (h.dim(), self.dimension());
        if p > d || q > d || !self.has_fast(p, q) {
            return append_in_order(ids, order, |ids| {
                self.visit(h, q, &mut |x| ids.push(x.index()))
            });
        }
        self.check(h)?;
        append_in_order(ids, order, |ids| {
            self.fast_into(p, h.index(), q, ids);
            Ok(())
        })
    }

    fn degree_batch(
        &self,
        p: usize,
        indices: &[u32],
        q: usize,
        out: &mut [u32],
    ) -> Result<(), QueryError> {
        let d = self.dimension();
        if q > d {
            return Err(QueryError::DimensionOutOfRange { p, q, dim: d });
        }
        if p > d {
            let h =
                SimplexHandle::dense(p.min(MAX_DIMENSION), indices.first().copied().unwrap_or(0));
            return Err(invalid(h, "dimension above the complex's"));
        }
        check_indices(self, p, indices)?;
        if !self.has_fast(p, q) {
            for (&i, o) in indices.iter().zip(out.iter_mut()) {
                *o = match self.stored_degree(p, i, q) {
                    Some(k) => k as u32,
                    None => self.degree(SimplexHandle::dense(p, i), q)? as u32,
                };
            }
            return Ok(());
        }
        let mut buf = Scratch::<Vec<u32>>::take();
        for (&i, o) in indices.iter().zip(out.iter_mut()) {
            *o = match self.stored_degree(p, i, q) {
                Some(k) => k as u32,
                None => {
                    buf.clear();
                    self.fast_into(p, i, q, &mut buf);
                    buf.len() as u32
                }
            };
        }
        Ok(())
    }

    fn relation_view(&self, p: usize, q: usize) -> Result<Option<RelationView<'_>>, QueryError> {
        let d = self.dimension();
        if p > d || q > d {
            return Err(QueryError::DimensionOutOfRange { p, q, dim: d });
        }
        if let Some(v) = self.stored_view(p, q) {
            return Ok(Some(v));
        }
        let slots = self
            .nav()
            .views
            .get_or_init(|| (0..(d + 1) * (d + 1)).map(|_| OnceLock::new()).collect());
        let slot = &slots[p * (d + 1) + q];
        if slot.get().is_none() {
            // Two threads may both build it; the first to finish is kept, the other dropped.
            let _ = slot.set(build_view(self, p, q)?);
        }
        let c = slot.get().expect("set above");
        Ok(Some(RelationView::new(&c.offsets, &c.ids, true)))
    }

    fn vertex_star(&self, v: u32, order: Order, out: &mut Vec<SimplexHandle>) -> bool {
        self.fast_star(v, order, out)
    }

    fn visit(
        &self,
        h: SimplexHandle,
        q: usize,
        visit: &mut dyn FnMut(SimplexHandle),
    ) -> Result<(), QueryError> {
        self.check(h)?;
        // σ's ids borrowed from its table (no copy): this runs once per simplex of a walk.
        let vertex = [h.index()];
        let sigma: &[u32] = match h.dim() {
            0 => &vertex,
            p => self.table(p).get(h.index() as usize),
        };
        let d = self.dimension();
        if q > d {
            return Err(QueryError::DimensionOutOfRange {
                p: h.dim(),
                q,
                dim: d,
            });
        }
        if let Some(r) = self.fast_visit(h, sigma, q, visit) {
            return r;
        }
        with_scratch(|rows| {
            let answer = self.query(sigma, q, rows);
            if answer.is_ok() {
                for row in rows.chunks_exact(q + 1) {
                    visit(find(self, row).expect("an answer is a simplex of the complex"));
                }
            }
            answer
        })
    }
}
