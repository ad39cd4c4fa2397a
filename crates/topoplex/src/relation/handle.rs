//! Handles: typed ids for vertices, top simplices and any simplex, and the navigation trait
//! [`Navigate`] that answers relations from handles to handles.
//!
//! Locate once, then navigate: [`Navigate::locate`] turns vertex ids into a [`SimplexHandle`]
//! (validating them, as [`Topology::relation`] does); every other operation takes and returns
//! handles, writes into caller-owned buffers or calls a visitor, and keeps no state in the
//! structure (one structure answers from many threads at once).
//!
//! # Ids
//! - [`VertexId`]: a vertex, `0..n` (the complex's vertex ids).
//! - [`TopId`]: a top simplex (a simplex that is no proper face of another), numbered densely
//!   over the whole complex: dimension ascending, then ascending lexicographic order of the
//!   sorted vertex ids within a dimension. The numbering depends only on the complex, so every
//!   structure built from one complex gives a top simplex the same `TopId`.
//! - [`SimplexHandle`]: any simplex. In the nine structures of this crate it is *dense*: `(p,
//!   index)` where `index` is the simplex's rank among the p-simplices in ascending lexicographic
//!   order (`0..count(p)`; a vertex's index is its id). So the caller's per-dimension arrays can
//!   be indexed by `handle.index()` (as pmp and geometry-central do with their handles), two
//!   handles of one structure name the same simplex exactly when they are equal, and sorting
//!   handles by index is lexicographic order.
//!
//! A structure that stores a dimension explicitly (the IG and SIG every dimension, the IA its
//! d-simplices, the 2D structures their triangles) answers from its own arrays. Simplices it
//! stores only implicitly (the IA's edges of a tetrahedral mesh, for instance) get their dense
//! index from a lexicographic table of that dimension built once, on the first request that
//! needs it (O(n_p log n_p) time, (p + 1)·n_p integers, then O(p log n_p) per handle lookup);
//! a caller that never asks for that dimension never pays for it. [`HandleForm::TopFace`] (a
//! top simplex plus a bit mask of its vertices) is for structures whose handles must outlive
//! edits (the live complex); none of the nine uses it. Such a structure still has dense indices
//! ([`Navigate::index_of`], [`Navigate::handle`]), numbered as above by tables built on demand,
//! valid until its next edit (`crate::live`, module `dense`).
//!
//! `u32::MAX` means "none" for every id ([`VertexId::NONE`], [`TopId::NONE`],
//! [`SimplexHandle::NONE`]).
//!
//! # Invalidation
//! The nine structures are immutable: a handle stays valid as long as the structure lives. A
//! handle used with another structure, or out of range, is refused with
//! [`QueryError::InvalidHandle`] when its index or dimension is out of range; one in range names
//! whatever simplex has that index there (the C ABI adds an owner stamp to catch that case, see
//! `tpx_locate`). Editable structures report handles of removed simplices as
//! [`QueryError::StaleHandle`] and handles from before a compaction as
//! [`QueryError::StaleGeneration`] (see [`SimplexHandle::generation`]).

use std::fmt;
use std::ops::Deref;

use crate::complex::MAX_DIMENSION;
use crate::relation::{QueryError, Topology};
use crate::scratch::Scratch;
use crate::union_find::UnionFind;

/// A vertex id, `0..n`. `VertexId::NONE` (`u32::MAX`) is no vertex.
#[repr(transparent)]
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, Default)]
pub struct VertexId(pub u32);

/// A top simplex id: dense over the complex's top simplices, dimension ascending, then
/// lexicographic within a dimension. `TopId::NONE` (`u32::MAX`) is no top simplex.
#[repr(transparent)]
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, Default)]
pub struct TopId(pub u32);

macro_rules! id_methods {
    ($t:ident) => {
        impl $t {
            /// No element (`u32::MAX`).
            pub const NONE: $t = $t(u32::MAX);

            /// The id as an array index.
            #[inline]
            pub fn index(self) -> usize {
                self.0 as usize
            }

            /// Whether this is [`Self::NONE`].
            #[inline]
            pub fn is_none(self) -> bool {
                self.0 == u32::MAX
            }
        }

        impl From<u32> for $t {
            fn from(i: u32) -> Self {
                $t(i)
            }
        }

        impl fmt::Display for $t {
            fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                write!(f, "{}", self.0)
            }
        }
    };
}
id_methods!(VertexId);
id_methods!(TopId);

/// How a [`SimplexHandle`] addresses its simplex.
#[repr(u8)]
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum HandleForm {
    /// `index` is the simplex's rank among the p-simplices, lexicographic (what the nine
    /// structures use).
    Dense = 0,
    /// `index` is a [`TopId`] and `local` a bit mask of that top simplex's vertices (bit i: its
    /// i-th smallest vertex), `p + 1` bits set. Reserved for structures that do not number
    /// implicit simplices.
    TopFace = 1,
}

/// A handle to one simplex of one structure: 12 bytes, `Copy`, ordered by (dimension, index).
///
/// `generation` is 0 for the nine (immutable) structures; an editable structure stamps its
/// handles with its compaction count, so a handle from before a compaction is refused
/// ([`QueryError::StaleGeneration`]) instead of naming whatever simplex got its slot. It costs 4
/// bytes per handle (8 → 12), no work on the nine structures' query paths.
///
/// Build handles with [`Navigate::locate`], [`Navigate::handle`], [`Navigate::vertex`] or
/// [`Navigate::top`], or take them from navigation answers. See the module doc for what the
/// index means and when two handles name the same simplex.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct SimplexHandle {
    index: u32,
    dim: u8,
    form: HandleForm,
    local: u16,
    generation: u32,
}

impl PartialOrd for SimplexHandle {
    fn partial_cmp(&self, other: &Self) -> Option<std::cmp::Ordering> {
        Some(self.cmp(other))
    }
}

impl Ord for SimplexHandle {
    fn cmp(&self, other: &Self) -> std::cmp::Ordering {
        (self.dim, self.form, self.index, self.local, self.generation).cmp(&(
            other.dim,
            other.form,
            other.index,
            other.local,
            other.generation,
        ))
    }
}

impl SimplexHandle {
    /// No simplex: index `u32::MAX`.
    pub const NONE: SimplexHandle = SimplexHandle {
        index: u32::MAX,
        dim: 0,
        form: HandleForm::Dense,
        local: 0,
        generation: 0,
    };

    /// The dense handle of the p-simplex of rank `index` (not checked against a structure; see
    /// [`Navigate::handle`] for the checked form).
    #[inline]
    pub const fn dense(p: usize, index: u32) -> SimplexHandle {
        SimplexHandle {
            index,
            dim: p as u8,
            form: HandleForm::Dense,
            local: 0,
            generation: 0,
        }
    }

    /// The face of top simplex `top` made of the vertices selected by `mask` (bit i: the top
    /// simplex's i-th smallest vertex); p = popcount − 1. Not checked.
    #[inline]
    pub const fn top_face(top: TopId, mask: u16) -> SimplexHandle {
        SimplexHandle {
            index: top.0,
            dim: (mask.count_ones() as u8).saturating_sub(1),
            form: HandleForm::TopFace,
            local: mask,
            generation: 0,
        }
    }

    /// The same handle stamped with `generation` (an editable structure's compaction count;
    /// see the type's doc).
    #[inline]
    pub const fn with_generation(self, generation: u32) -> SimplexHandle {
        SimplexHandle { generation, ..self }
    }

    /// The compaction count of the structure when it issued this handle (0 for the nine
    /// immutable structures).
    #[inline]
    pub fn generation(self) -> u32 {
        self.generation
    }

    /// Dimension p of the simplex.
    #[inline]
    pub fn dim(self) -> usize {
        self.dim as usize
    }

    /// Dense index among the p-simplices (for [`HandleForm::Dense`]); the [`TopId`] for
    /// [`HandleForm::TopFace`].
    #[inline]
    pub fn index(self) -> u32 {
        self.index
    }

    /// How the handle addresses its simplex.
    #[inline]
    pub fn form(self) -> HandleForm {
        self.form
    }

    /// The vertex mask of a [`HandleForm::TopFace`] handle (0 for dense handles).
    #[inline]
    pub fn local(self) -> u16 {
        self.local
    }

    /// Whether this is [`Self::NONE`].
    #[inline]
    pub fn is_none(self) -> bool {
        self.index == u32::MAX
    }

    /// The vertex id, when this is a dense handle of a vertex.
    #[inline]
    pub fn as_vertex(self) -> Option<VertexId> {
        (self.dim == 0 && self.form == HandleForm::Dense).then_some(VertexId(self.index))
    }

    /// The handle as the C ABI's two words `(index, dim | form << 8 | local << 16)`; the
    /// generation is not among them (the C ABI's owner stamp stands for it).
    #[inline]
    pub fn to_words(self) -> (u32, u32) {
        (
            self.index,
            self.dim as u32 | (self.form as u32) << 8 | (self.local as u32) << 16,
        )
    }

    /// The inverse of [`Self::to_words`]; `None` when the form byte is unknown or the dimension
    /// is above [`MAX_DIMENSION`].
    pub fn from_words(index: u32, meta: u32) -> Option<SimplexHandle> {
        let dim = (meta & 0xff) as u8;
        let form = match (meta >> 8) & 0xff {
            0 => HandleForm::Dense,
            1 => HandleForm::TopFace,
            _ => return None,
        };
        if dim as usize > MAX_DIMENSION {
            return None;
        }
        Some(SimplexHandle {
            index,
            dim,
            form,
            local: (meta >> 16) as u16,
            generation: 0,
        })
    }
}

impl fmt::Display for SimplexHandle {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.form {
            HandleForm::Dense => write!(f, "{}-simplex #{}", self.dim, self.index),
            HandleForm::TopFace => write!(
                f,
                "{}-face {:#06x} of top simplex #{}",
                self.dim, self.local, self.index
            ),
        }
    }
}

/// The vertex ids of one simplex, by value (no allocation): up to 16 ids.
#[derive(Clone, Copy, PartialEq, Eq, Hash)]
pub struct Vertices {
    len: u8,
    ids: [u32; MAX_DIMENSION + 1],
}

impl Vertices {
    /// Copies `ids` (at most 16).
    pub fn from_slice(ids: &[u32]) -> Vertices {
        let mut v = Vertices {
            len: ids.len() as u8,
            ids: [0; MAX_DIMENSION + 1],
        };
        v.ids[..ids.len()].copy_from_slice(ids);
        v
    }
}

impl Deref for Vertices {
    type Target = [u32];
    fn deref(&self) -> &[u32] {
        &self.ids[..self.len as usize]
    }
}

impl fmt::Debug for Vertices {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_list().entries(self.iter()).finish()
    }
}

/// Order of a navigation answer.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Order {
    /// The structure's own order (what its walk produces; cheapest).
    #[default]
    Natural,
    /// Ascending lexicographic order of the sorted vertex ids (for dense handles: ascending
    /// index). Costs a sort of the answer.
    Lexicographic,
}

/// Cyclically ordered groups of simplices, written by [`Navigate::fans_around`] and
/// [`Navigate::around_edge`]. Group k is `items[offsets[k]..offsets[k + 1]]`. Reuse one value
/// across calls to avoid allocation.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct Fans {
    /// The simplices of every group, group after group, each group in cyclic order.
    pub items: Vec<SimplexHandle>,
    /// Start of each group in `items`, plus one final entry `items.len()`.
    pub offsets: Vec<u32>,
    /// Whether each group closes (its last simplex is adjacent to its first).
    pub closed: Vec<bool>,
    /// Whether each group is consistently oriented by the input winding and listed
    /// counter-clockwise by it (always false around an edge and where no winding applies).
    pub oriented: Vec<bool>,
}

impl Fans {
    /// Empties every array, keeping the allocations.
    pub fn clear(&mut self) {
        self.items.clear();
        self.offsets.clear();
        self.closed.clear();
        self.oriented.clear();
    }

    /// Makes this a copy of `other`, reusing the allocations.
    pub fn copy_from(&mut self, other: &Fans) {
        self.clear();
        self.items.extend_from_slice(&other.items);
        self.offsets.extend_from_slice(&other.offsets);
        self.closed.extend_from_slice(&other.closed);
        self.oriented.extend_from_slice(&other.oriented);
    }

    /// Number of groups.
    pub fn len(&self) -> usize {
        self.closed.len()
    }

    /// Whether there is no group.
    pub fn is_empty(&self) -> bool {
        self.closed.is_empty()
    }

    /// The simplices of group `k`, in order.
    pub fn group(&self, k: usize) -> &[SimplexHandle] {
        &self.items[self.offsets[k] as usize..self.offsets[k + 1] as usize]
    }
}

/// R_{p,q} of every p-simplex of a structure as one CSR the structure lends
/// ([`Navigate::relation_view`]): the answer of the p-simplex of dense index i is
/// `ids[offsets[i]..offsets[i + 1]]`, dense q-indices in natural order (the same answers, in the
/// same order, as [`Navigate::related`]). Valid as long as the structure lives; reading one
/// answer is two loads and no call, which is what lets a C++ range iterate it inline.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct RelationView<'a> {
    offsets: &'a [u32],
    ids: &'a [u32],
    built: bool,
}

impl<'a> RelationView<'a> {
    /// A view over `offsets` (n + 1 entries, non-decreasing, first 0, last `ids.len()`) and
    /// `ids`; `built` when it is an index built for the view rather than stored arrays.
    pub(crate) fn new(offsets: &'a [u32], ids: &'a [u32], built: bool) -> RelationView<'a> {
        debug_assert!(offsets.first() == Some(&0) && offsets.last() == Some(&(ids.len() as u32)));
        RelationView {
            offsets,
            ids,
            built,
        }
    }

    /// Number of p-simplices (answers).
    pub fn len(&self) -> usize {
        self.offsets.len() - 1
    }

    /// Whether there is no p-simplex.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The answer of the p-simplex of dense index `i` (panics when `i >= len()`). O(1).
    pub fn get(&self, i: usize) -> &'a [u32] {
        &self.ids[self.offsets[i] as usize..self.offsets[i + 1] as usize]
    }

    /// The n + 1 offsets.
    pub fn offsets(&self) -> &'a [u32] {
        self.offsets
    }

    /// Every answer, one after the other.
    pub fn ids(&self) -> &'a [u32] {
        self.ids
    }

    /// Whether this is an index built for the view (memory: [`RelationView::bytes`], counted
    /// in [`Navigate::handle_bytes`]) rather than the structure's own arrays (no extra memory).
    pub fn is_built(&self) -> bool {
        self.built
    }

    /// Bytes of the two arrays, `4 (n + 1) + 4 · total`.
    pub fn bytes(&self) -> u64 {
        4 * (self.offsets.len() + self.ids.len()) as u64
    }
}

/// Navigation from handles to handles: locate once, then answer without re-locating.
///
/// Object-safe, and implemented by every structure of this crate; `Box<dyn Topology>` reaches it
/// through [`Topology::as_navigate`]. The required methods are the locating and reading
/// primitives and [`Navigate::visit`]; everything else has a default written on top of them,
/// which a structure may override with a faster walk (answers must stay the same).
///
/// Every answer holds each simplex once. Answers are handles of the same structure; for the
/// nine structures they are dense, so equal handles name equal simplices.
pub trait Navigate: Topology {
    // ---- locating and reading ----

    /// The handle of the simplex with vertex ids `sigma` (any order). Validates as
    /// [`Topology::relation`] does: `EmptySimplex`, `TooManyVertices`, `RepeatedVertex`,
    /// `VertexOutOfRange`, `NotInComplex`. Cost: the structure's locate cost (module doc).
    fn locate(&self, sigma: &[u32]) -> Result<SimplexHandle, QueryError>;

    /// The dense handle of the p-simplex of rank `index`, checked: `InvalidHandle` when p is
    /// above the dimension or `index >= count(p)`. O(1).
    fn handle(&self, p: usize, index: u32) -> Result<SimplexHandle, QueryError> {
        let h = SimplexHandle::dense(p.min(MAX_DIMENSION), index);
        if p > MAX_DIMENSION {
            return Err(QueryError::InvalidHandle {
                handle: h,
                reason: "dimension above the complex's",
            });
        }
        self.check(h).map(|_| h)
    }

    /// Checks that `h` names a simplex of this structure: `InvalidHandle` (out of range, bad
    /// form, `NONE`), `StaleHandle` (removed by an edit), `WrongHandleKind`. O(1).
    fn check(&self, h: SimplexHandle) -> Result<(), QueryError>;

    /// The handle of vertex `v` (`InvalidHandle` when `v >= n`). O(1).
    fn vertex(&self, v: VertexId) -> Result<SimplexHandle, QueryError> {
        self.handle(0, v.0)
    }

    /// The vertex ids of `h`, ascending. O(p) for dimensions the structure stores, O(p + log
    /// n_p) otherwise (see the module doc).
    fn vertices_of(&self, h: SimplexHandle) -> Result<Vertices, QueryError>;

    /// Number of top simplices, all dimensions (`TopId`s are `0..top_total()` for the nine
    /// structures; the live complex numbers its top simplices by packed slot instead, see
    /// [`crate::live`]).
    fn top_total(&self) -> u32 {
        (0..=self.dimension())
            .map(|p| self.top_count(p) as u32)
            .sum()
    }

    /// The handle of top simplex `t` (`InvalidHandle` when out of range).
    fn top(&self, t: TopId) -> Result<SimplexHandle, QueryError>;

    /// The [`TopId`] of `h` when it names a top simplex, else `None`.
    fn top_id(&self, h: SimplexHandle) -> Result<Option<TopId>, QueryError>;

    /// Top simplex `t` as given in the input: its vertex order, hence its winding (the first
    /// listing when the input repeated it). Use [`Navigate::vertices_of`] for the normalised
    /// (ascending) form.
    fn top_as_given(&self, t: TopId) -> Result<Vertices, QueryError>;

    /// The structure's generation (compaction count) that its handles must carry; 0 for the
    /// nine immutable structures (see [`SimplexHandle::generation`]).
    fn generation(&self) -> u32 {
        0
    }

    /// Whether every handle this structure gives out is dense (true for the nine; the live
    /// complex names simplices of dimension ≥ 1 by a top simplex and a vertex mask). Every
    /// structure has dense indices all the same ([`Navigate::index_of`], [`Navigate::handle`]);
    /// this says whether a handle *is* its index.
    fn dense(&self) -> bool {
        true
    }

    /// Whether [`Navigate::visit`] gives each answer in lexicographic order already (the live
    /// complex's walks do), so that the defaults asked for [`Order::Lexicographic`] sort
    /// nothing. False for the nine.
    fn visits_lexicographic(&self) -> bool {
        false
    }

    /// The dense index of `h`: its rank among the simplices of its dimension in ascending
    /// lexicographic order (a vertex: its id), the index [`Navigate::handle`] takes back and
    /// `related_ids`, `related_batch`, `degree_batch` and [`Navigate::relation_view`] use.
    /// Checked as [`Navigate::check`]. O(1) for dense handles; the live complex finds it in
    /// its numbering of the moment (O(p log n_p), see `live::dense`). A vertex's index is its
    /// id, also in the live complex, whose ids are slots: after a vertex is removed, and until
    /// `compact()`, vertex indices run to the slot count with gaps (a removed slot's index is
    /// refused), so walk the live vertices' ids rather than `0..count(0)`.
    fn index_of(&self, h: SimplexHandle) -> Result<u32, QueryError> {
        self.check(h)?;
        Ok(h.index())
    }

    /// Heap bytes of the handle bookkeeping (windings, tables built on first use), which
    /// [`Topology::storage`] does not count. 0 by default.
    fn handle_bytes(&self) -> u64 {
        0
    }

    // ---- navigation ----

    /// Calls `visit` with every simplex of R_{p,q}(h), p = `h.dim()`, in the structure's
    /// natural order, each once. `DimensionOutOfRange` when q is above the complex's dimension.
    /// No allocation once the structure's scratch is warm (the cost is the structure's
    /// relation cost plus, for implicit dimensions, O(log n_q) per answer).
    fn visit(
        &self,
        h: SimplexHandle,
        q: usize,
        visit: &mut dyn FnMut(SimplexHandle),
    ) -> Result<(), QueryError>;

    /// R_{p,q}(h) written into `out` (cleared first; no allocation when its capacity
    /// suffices), in `order`.
    fn related(
        &self,
        h: SimplexHandle,
        q: usize,
        order: Order,
        out: &mut Vec<SimplexHandle>,
    ) -> Result<(), QueryError> {
        out.clear();
        let order = to_sort(self, order);
        append_in_order(out, order, |out| self.visit(h, q, &mut |x| out.push(x)))
    }

    /// R_{p,q} of many p-simplices at once, as one CSR: for each dense index of `indices`, its
    /// answer's dense q-indices are appended to `ids` (in `order`) and the end of that answer in
    /// `ids` to `ends`. `InvalidHandle` for an index out of range (or p above the dimension),
    /// `DimensionOutOfRange` as [`Navigate::visit`]; on error `ids` and `ends` hold a prefix.
    /// Default: one [`Navigate::related_ids`] per index; a structure may answer in a loop with
    /// no call per answer (TS, PE, LE, DE for VV, VF and FF; the IG for R_{0,0} and R_{p,p±1}).
    /// No allocation beyond `ids` and `ends`.
    fn related_batch(
        &self,
        p: usize,
        indices: &[u32],
        q: usize,
        order: Order,
        ids: &mut Vec<u32>,
        ends: &mut Vec<usize>,
    ) -> Result<(), QueryError> {
        batch_by_ids(self, p, indices, q, order, ids, ends)
    }

    /// R_{p,q} of many handles at once, of any dimensions (mixed), as one CSR of handles: for
    /// each handle of `hs`, its answer (as [`Navigate::related`] gives it, in `order`) is
    /// appended to `out` and the end of that answer in `out` to `ends`. Works for every
    /// structure; on the live complex the answers last across edits, unlike the dense indices
    /// of [`Navigate::related_batch`]. Errors as [`Navigate::related`] for the first handle
    /// that fails; then `out` and `ends` hold a prefix. Cost: one [`Navigate::visit`] per handle;
    /// no allocation beyond `out` and `ends`.
    fn related_handles_batch(
        &self,
        hs: &[SimplexHandle],
        q: usize,
        order: Order,
        out: &mut Vec<SimplexHandle>,
        ends: &mut Vec<usize>,
    ) -> Result<(), QueryError> {
        let order = to_sort(self, order);
        for &h in hs {
            append_in_order(out, order, |out| self.visit(h, q, &mut |x| out.push(x)))?;
            ends.push(out.len());
        }
        Ok(())
    }

    /// R_{p,q}(h) appended to `ids` as dense q-indices (for dense handles), in `order`; `h` is
    /// checked once. Default: [`Navigate::visit`]; the nine structures answer from their arrays
    /// with no call per answer where they have a loop for (p, q) (see `related_batch`). No
    /// allocation beyond `ids`.
    fn related_ids(
        &self,
        h: SimplexHandle,
        q: usize,
        order: Order,
        ids: &mut Vec<u32>,
    ) -> Result<(), QueryError> {
        append_in_order(ids, order, |ids| {
            self.visit(h, q, &mut |x| ids.push(x.index()))
        })
    }

    /// |R_{p,q}| of the dense p-indices `indices` into `out` (`out.len() == indices.len()`),
    /// without writing any answer: for the stored relations of the IG (co-boundaries,
    /// boundaries, R_{0,0} = edges at v) O(1) per index from its offsets; otherwise each
    /// answer walked and counted in a scratch buffer (the walk's cost). Errors as
    /// [`Navigate::related_batch`]; on error `out` holds a prefix. No allocation once this
    /// thread's scratch is warm.
    fn degree_batch(
        &self,
        p: usize,
        indices: &[u32],
        q: usize,
        out: &mut [u32],
    ) -> Result<(), QueryError> {
        for (&i, o) in indices.iter().zip(out.iter_mut()) {
            *o = self.degree(self.handle(p, i)?, q)? as u32;
        }
        Ok(())
    }

    /// R_{p,q} of every p-simplex as one CSR lent by the structure ([`RelationView`]), for a
    /// caller that iterates answers itself (the C++ ranges read it inline, with no call per
    /// query). Where the structure stores the relation as a CSR (the IG's co-boundaries
    /// R_{p,p+1}) the view is its own arrays, at no cost. Otherwise the first call builds an
    /// index of R_{p,q} — one walk over every p-simplex (the cost of `related_batch` over all
    /// of them), its arrays grown fallibly (`TooLarge`) — kept until the structure is dropped
    /// (`4 (n_p + 1) + 4 · Σ|R_{p,q}|` bytes, in [`Navigate::handle_bytes`]); later calls are
    /// O(1). `DimensionOutOfRange` for p or q above the dimension. `Ok(None)` for a structure
    /// that lends no view (none of this crate's: the live complex lends one valid until its
    /// next edit, see `live::dense`).
    fn relation_view(&self, _p: usize, _q: usize) -> Result<Option<RelationView<'_>>, QueryError> {
        Ok(None)
    }

    /// The q-faces of h, q < p (`DimensionOutOfRange` otherwise); see [`Navigate::related`].
    fn boundary(
        &self,
        h: SimplexHandle,
        q: usize,
        order: Order,
        out: &mut Vec<SimplexHandle>,
    ) -> Result<(), QueryError> {
        if q >= h.dim() {
            return Err(out_of_range(h.dim(), q, h.dim().saturating_sub(1)));
        }
        self.related(h, q, order, out)
    }

    /// The q-simplices having h as a face, q > p (`DimensionOutOfRange` otherwise).
    fn coboundary(
        &self,
        h: SimplexHandle,
        q: usize,
        order: Order,
        out: &mut Vec<SimplexHandle>,
    ) -> Result<(), QueryError> {
        if q <= h.dim() || q > self.dimension() {
            return Err(out_of_range(h.dim(), q, self.dimension()));
        }
        self.related(h, q, order, out)
    }

    /// The p-simplices adjacent to h (sharing a (p−1)-face; for a vertex, sharing an edge).
    fn adjacent(
        &self,
        h: SimplexHandle,
        order: Order,
        out: &mut Vec<SimplexHandle>,
    ) -> Result<(), QueryError> {
        self.related(h, h.dim(), order, out)
    }

    /// The star of h without h: every simplex having h as a proper face, dimension ascending,
    /// each dimension in `order`.
    fn star(
        &self,
        h: SimplexHandle,
        order: Order,
        out: &mut Vec<SimplexHandle>,
    ) -> Result<(), QueryError> {
        out.clear();
        self.check(h)?;
        if h.dim() == 0 && self.vertex_star(h.index(), order, out) {
            return Ok(());
        }
        let order = to_sort(self, order);
        for q in h.dim() + 1..=self.dimension() {
            append_in_order(out, order, |out| self.visit(h, q, &mut |x| out.push(x)))?;
        }
        Ok(())
    }

    /// [`Navigate::star`] of vertex `v` (checked) from one walk of the structure's own, when it
    /// has one: the same answers and order as one walk per dimension. `false` (nothing
    /// written) sends `star` to the walk per dimension, the default.
    fn vertex_star(&self, _v: u32, _order: Order, _out: &mut Vec<SimplexHandle>) -> bool {
        false
    }

    /// The link of h: for every τ in the star of h, the face τ ∖ h; dimension ascending, each
    /// dimension in `order`. Cost: the star, plus locating each link simplex. No allocation
    /// beyond `out` once this thread's scratch buffers are warm.
    fn link(
        &self,
        h: SimplexHandle,
        order: Order,
        out: &mut Vec<SimplexHandle>,
    ) -> Result<(), QueryError> {
        let sigma = self.vertices_of(h)?;
        let mut star = Scratch::<Vec<SimplexHandle>>::take();
        self.star(h, Order::Natural, &mut star)?;
        out.clear();
        let mut rest = [0u32; MAX_DIMENSION + 1];
        for &tau in star.iter() {
            let t = self.vertices_of(tau)?;
            let k = minus(&t, &sigma, &mut rest);
            out.push(self.locate(&rest[..k])?);
        }
        // Simplices of the star map to distinct link simplices (τ ↦ τ ∖ σ is injective on
        // the star), already grouped by dimension.
        if to_sort(self, order) == Order::Lexicographic {
            out.sort_unstable();
        }
        Ok(())
    }

    /// |R_{p,q}(h)|: the number of q-simplices related to h. Same cost as [`Navigate::visit`],
    /// no allocation.
    fn degree(&self, h: SimplexHandle, q: usize) -> Result<usize, QueryError> {
        let mut k = 0;
        self.visit(h, q, &mut |_| k += 1)?;
        Ok(k)
    }

    /// Whether h lies on the boundary: h, or a simplex of its star, is a non-top simplex with
    /// exactly one coface one dimension up (a surface's boundary edges, their vertices and
    /// triangles; a dangling end of a wire). Cost: the star of h and one degree per simplex.
    fn is_boundary(&self, h: SimplexHandle) -> Result<bool, QueryError> {
        let mut star = Scratch::<Vec<SimplexHandle>>::take();
        self.star(h, Order::Natural, &mut star)?;
        for &tau in std::iter::once(&h).chain(star.iter()) {
            let p = tau.dim();
            if p < self.dimension() && self.top_id(tau)?.is_none() && self.degree(tau, p + 1)? == 1
            {
                return Ok(true);
            }
        }
        Ok(false)
    }

    /// Whether h is a manifold simplex: its star is pure (every top simplex containing h has
    /// one dimension k + p + 1) and its link is a connected k-pseudo-manifold — for k = 0 one or
    /// two points; for k ≥ 1 every (k−1)-face of the link in one or two of its k-simplices, and
    /// the k-simplices joined through them. On surfaces and tetrahedral meshes this is exact for
    /// edges and for vertices of surfaces (link a path or a cycle); a vertex of a 3-complex is
    /// called manifold when its link is a connected pseudo-surface. A top simplex is manifold.
    /// Cost: the star of h, plus a sort of the link's facets.
    fn is_manifold(&self, h: SimplexHandle) -> Result<bool, QueryError> {
        let sigma = self.vertices_of(h)?;
        let mut star = Scratch::<Vec<SimplexHandle>>::take();
        self.star(h, Order::Natural, &mut star)?;
        // The link of the top simplices of the star, rows of one arity, flat.
        let mut rows = Scratch::<Vec<u32>>::take();
        let mut arity = None;
        let mut rest = [0u32; MAX_DIMENSION + 1];
        for &tau in star.iter() {
            if self.top_id(tau)?.is_some() {
                let k = minus(&self.vertices_of(tau)?, &sigma, &mut rest);
                if *arity.get_or_insert(k) != k {
                    return Ok(false);
                }
                rows.extend_from_slice(&rest[..k]);
            }
        }
        Ok(arity.is_none_or(|a| link_is_pseudo_manifold(&rows, a)))
    }

    // ---- cyclic order ----

    /// The triangles around vertex `v` of a complex of dimension ≤ 2, grouped into manifold
    /// fans (triangles joined through edges at v that bound exactly two triangles), each in
    /// cyclic order, counter-clockwise by the input winding where the fan is consistently
    /// oriented (`oriented[k]`), else from its lowest triangle. An open fan starts at a
    /// triangle on a fan end. Fans are listed by their first triangle. `InvalidHandle` when `v`
    /// is not a vertex; `DimensionOutOfRange` for complexes of dimension above 2. Cost: the
    /// star of v and the triangle degree of each edge at v.
    fn fans_around(&self, v: SimplexHandle, out: &mut Fans) -> Result<(), QueryError> {
        super::cyclic::fans_around(self, v, out)
    }

    /// The q-simplices around edge `e` in radial order, q = 2 (triangles) or 3 (tetrahedra).
    /// Around an edge of a 2-complex: one group, the triangles in the structure's radial order
    /// (TS, PE, LE, DE: by angle about the edge when coordinates are given; otherwise ascending).
    /// Around an edge of a 3-complex: one group per cluster of q-simplices joined through
    /// (q−1)-faces containing e that bound exactly two of them, each in order. For q = 2 the
    /// groups are the sweeps through those clusters of tetrahedra (every triangle between two
    /// consecutive tetrahedra, and the end triangles of an open cluster; a triangle where
    /// clusters meet is in each of their sweeps), then every remaining triangle as a group of
    /// its own. `WrongHandleKind` when e is not an edge.
    fn around_edge(&self, e: SimplexHandle, q: usize, out: &mut Fans) -> Result<(), QueryError> {
        super::cyclic::around_edge(self, e, q, out)
    }
}

/// Appends to `out` what `fill` pushes, that part sorted when `order` is lexicographic (left
/// as pushed when `fill` fails).
pub(crate) fn append_in_order<T: Ord, E>(
    out: &mut Vec<T>,
    order: Order,
    fill: impl FnOnce(&mut Vec<T>) -> Result<(), E>,
) -> Result<(), E> {
    let start = out.len();
    fill(out)?;
    if order == Order::Lexicographic {
        out[start..].sort_unstable();
    }
    Ok(())
}

/// The order [`Navigate::visit`]'s answers still have to be sorted into for `order`: none
/// ([`Order::Natural`]) where they come lexicographic already.
fn to_sort<N: Navigate + ?Sized>(n: &N, order: Order) -> Order {
    if n.visits_lexicographic() {
        Order::Natural
    } else {
        order
    }
}

/// [`Navigate::related_batch`] by one [`Navigate::related_ids`] per index.
pub(crate) fn batch_by_ids<N: Navigate + ?Sized>(
    n: &N,
    p: usize,
    indices: &[u32],
    q: usize,
    order: Order,
    ids: &mut Vec<u32>,
    ends: &mut Vec<usize>,
) -> Result<(), QueryError> {
    for &i in indices {
        n.related_ids(n.handle(p, i)?, q, order, ids)?;
        ends.push(ids.len());
    }
    Ok(())
}

fn out_of_range(p: usize, q: usize, dim: usize) -> QueryError {
    QueryError::DimensionOutOfRange { p, q, dim }
}

/// Writes the ids of `t` that are not in `sigma` (both ascending) to `out`; returns how many.
fn minus(t: &[u32], sigma: &[u32], out: &mut [u32; MAX_DIMENSION + 1]) -> usize {
    let mut k = 0;
    for &v in t.iter().filter(|v| !sigma.contains(v)) {
        out[k] = v;
        k += 1;
    }
    k
}

/// Whether the k-simplices `rows` (flat, `arity` ascending ids each, arity ≥ 1) form a connected
/// pseudo-manifold (see [`Navigate::is_manifold`]). Empty: true (the link of a top simplex).
/// Works in this thread's scratch buffers: no allocation once they are warm.
pub(crate) fn link_is_pseudo_manifold(rows: &[u32], arity: usize) -> bool {
    let m = rows.len() / arity;
    if m == 0 {
        return true;
    }
    if arity == 1 {
        return m <= 2;
    }
    // Facet f = (row f / arity without its entry f % arity), still ascending; sorted by content.
    let facet = |f: u32| {
        let (i, skip) = (f as usize / arity, f as usize % arity);
        rows[i * arity..(i + 1) * arity]
            .iter()
            .enumerate()
            .filter(move |&(j, _)| j != skip)
            .map(|(_, &v)| v)
    };
    let mut facets = Scratch::<Vec<u32>>::take();
    facets.extend(0..(m * arity) as u32);
    facets.sort_unstable_by(|&a, &b| facet(a).cmp(facet(b)).then(a.cmp(&b)));
    let mut parents = Scratch::<Vec<u32>>::take();
    let mut uf = UnionFind::reusing(std::mem::take(&mut *parents), m);
    let mut ok = true;
    for group in facets.chunk_by(|&a, &b| facet(a).eq(facet(b))) {
        match group {
            [_] => {}
            [a, b] => uf.union(a / arity as u32, b / arity as u32),
            _ => {
                ok = false;
                break;
            }
        }
    }
    let root = uf.find(0);
    ok = ok && (1..m as u32).all(|i| uf.find(i) == root);
    *parents = uf.into_inner();
    ok
}

crate::scratch::pooled_vec!(SimplexHandle);

impl crate::scratch::Pooled for Fans {
    fn pool() -> &'static std::thread::LocalKey<std::cell::RefCell<Vec<Self>>> {
        thread_local! {
            static POOL: std::cell::RefCell<Vec<Fans>> =
                const { std::cell::RefCell::new(Vec::new()) };
        }
        &POOL
    }
    fn reset(&mut self) {
        self.clear();
    }
    fn capacity(&self) -> usize {
        self.items.capacity()
    }
}
