//! The fast path of the one-handle queries (`tpx_related`, `tpx_related_handles`): a walk over
//! every vertex or face makes one C call per element, so the fixed cost of a call is what such
//! a walk pays on top of its answers (issue 13: ~35 ns per call before this path, against
//! ~6 ids of answer).
//!
//! A call takes this path when its arguments are the usual ones — structure, handle and
//! `out_len` not NULL, a dense handle of this structure, a known order — and its answer fits
//! the caller's buffer. It then writes the answer straight into that buffer: what a structure
//! stores as one row (the IG's boundaries and co-boundaries, its edges at a vertex for R_{0,0};
//! the IA's adjacency row for R_{d,d}; the three radial cycles of TS, PE, LE and DE for R_{2,2})
//! is copied from the structure's arrays, other relations are walked into this thread's answer
//! buffer (one thread-local access) and copied. Everything else — a NULL pointer, a foreign,
//! stale or out-of-range handle, an answer longer than the buffer, a walk that fails, the live
//! complex — returns `None` and the caller runs the full path, which finds and reports the
//! problem with its message. So the fast path never writes an output unless it succeeds, and
//! every status and message is the full path's.
//!
//! Which direct writer a structure has is decided once, when its C handle is made
//! ([`Direct::of`]), not per call.

use std::any::Any;

use super::TpxStatus;
use super::handles::{TPX_ORDER_LEXICOGRAPHIC, TPX_ORDER_NATURAL, TpxSimplex};
use super::structure::TpxStructure;
use topoplex::complex::MAX_DIMENSION;
use topoplex::family::FastPath;
use topoplex::relation::Topology;
use topoplex::relation::handle::{Navigate, Order, SimplexHandle};
use topoplex::structures::de::DirectedEdge;
use topoplex::structures::ia::{IndexedAdjacency, NONE};
use topoplex::structures::ig::IncidenceGraph;
use topoplex::structures::le::LoopEdgeUse;
use topoplex::structures::nav::NavBase;
use topoplex::structures::pe::PartialEntities;
use topoplex::structures::radial::TriTopo;
use topoplex::structures::ts::TriangleSegment;

/// The direct writer of a structure's C handle, chosen once: its kind's row of the registry
/// ([`topoplex::family::fast_path`]), kept only when the concrete type is the one that row names
/// (what makes the casts of [`direct`] sound); `None` for no fast path (the live complex, whose
/// handles carry generations and forms, and sparse numberings).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Direct(Option<FastPath>);

impl Direct {
    /// The writer for `topo`.
    pub(crate) fn of(topo: &dyn Topology) -> Direct {
        let any: &dyn Any = topo;
        let dense = topo.as_navigate().is_some_and(|n| n.dense());
        let path = topoplex::family::fast_path(topo.kind());
        let is_its_type = match path {
            FastPath::Ig => any.is::<IncidenceGraph>(),
            FastPath::Ia => any.is::<IndexedAdjacency>(),
            FastPath::Ts => any.is::<TriangleSegment>(),
            FastPath::Pe => any.is::<PartialEntities>(),
            FastPath::Le => any.is::<LoopEdgeUse>(),
            FastPath::De => any.is::<DirectedEdge>(),
            FastPath::Walk => dense,
        };
        Direct(is_its_type.then_some(path))
    }
}

/// Where the answer goes: the caller's buffer, as dense indices or as handles.
pub(crate) trait Sink {
    /// Room in the buffer.
    fn room(&self) -> usize;
    /// Writes answer `k` (`k < room()`), the q-simplex of dense index `id`.
    fn put(&mut self, k: usize, id: u32);
    /// Sorts the first `len` answers ascending (lexicographic order).
    fn sort(&mut self, len: usize);
}

impl Sink for &mut [u32] {
    #[inline]
    fn room(&self) -> usize {
        self.len()
    }
    #[inline]
    fn put(&mut self, k: usize, id: u32) {
        self[k] = id;
    }
    fn sort(&mut self, len: usize) {
        self[..len].sort_unstable();
    }
}

/// Handles of dimension `q` of the structure stamped `owner`.
pub(crate) struct Handles<'a> {
    pub(crate) out: &'a mut [TpxSimplex],
    pub(crate) q: u32,
    pub(crate) owner: u32,
}

impl Sink for Handles<'_> {
    #[inline]
    fn room(&self) -> usize {
        self.out.len()
    }
    #[inline]
    fn put(&mut self, k: usize, id: u32) {
        self.out[k] = TpxSimplex {
            index: id,
            meta: self.q,
            owner: self.owner,
        };
    }
    fn sort(&mut self, len: usize) {
        // One dimension, one owner: ascending handles are ascending indices.
        self.out[..len].sort_unstable_by_key(|h| h.index);
    }
}

/// The arguments of a fast call, read from the C pointers; `None` when any is unusual (the
/// full path reports it).
pub(crate) fn arguments<'a>(
    s: *const TpxStructure,
    h: *const TpxSimplex,
    order: u32,
    out_len: *mut usize,
) -> Option<(&'a TpxStructure, SimplexHandle, Order, &'a mut usize)> {
    // SAFETY: non-NULL pointers passed to the ABI are valid (documented contract).
    let (s, h, out_len) = unsafe { (s.as_ref()?, h.as_ref()?, out_len.as_mut()?) };
    let order = match order {
        TPX_ORDER_NATURAL => Order::Natural,
        TPX_ORDER_LEXICOGRAPHIC => Order::Lexicographic,
        _ => return None,
    };
    // A dense handle of this structure: form and local bits 0 (meta is the dimension).
    if h.owner != s.stamp || h.meta as usize > MAX_DIMENSION || s.direct.0.is_none() {
        return None;
    }
    Some((
        s,
        SimplexHandle::dense(h.meta as usize, h.index),
        order,
        out_len,
    ))
}

/// `buf[0 .. buf_len]` as a slice (empty for NULL with length 0); `None` for NULL with a
/// length or a length beyond the address space.
pub(crate) fn out_slice<'a, T>(buf: *mut T, buf_len: usize) -> Option<&'a mut [T]> {
    if buf_len == 0 {
        return Some(&mut []);
    }
    if buf.is_null() || buf_len > isize::MAX as usize / std::mem::size_of::<T>() {
        return None;
    }
    // SAFETY: the caller's buffer holds `buf_len` writable items (documented contract).
    Some(unsafe { std::slice::from_raw_parts_mut(buf, buf_len) })
}

/// R_{p,q}(h) written to `out`: `Some(len)` on success, `None` to take the full path (nothing
/// the caller can see was written then: a partial answer only ever lands in `out` when it is
/// then completed).
pub(crate) fn answer(
    s: &TpxStructure,
    h: SimplexHandle,
    q: u32,
    order: Order,
    out: &mut impl Sink,
) -> Option<usize> {
    let len = direct(s, h, q as usize, out).or_else(|| walked(s, h, q, out))?;
    if order == Order::Lexicographic {
        out.sort(len);
    }
    Some(len)
}

/// The answer from the structure's concrete type: a stored row copied, or the structure's own
/// loop (`NavBase::fast_into`) into this thread's buffer, with no call through the vtable.
/// `None` when this (structure, p, q) has neither, the handle is out of range or the answer
/// does not fit.
fn direct(s: &TpxStructure, h: SimplexHandle, q: usize, out: &mut impl Sink) -> Option<usize> {
    let (p, i) = (h.dim(), h.index());
    // SAFETY (each `concrete`): `s.direct` was set by `Direct::of(&*s.topo)`, which keeps a row
    // only after checking the concrete type of the structure `s.topo` holds (never replaced).
    match s.direct.0 {
        Some(FastPath::Ig) => ig(unsafe { concrete::<IncidenceGraph>(s) }, p, i, q, out),
        Some(FastPath::Ia) => {
            let ia = unsafe { concrete::<IndexedAdjacency>(s) };
            ia_adjacency(ia, p, i, q, out).or_else(|| looped(ia, p, i, q, out))
        }
        Some(FastPath::Ts) => radial(unsafe { concrete::<TriangleSegment>(s) }, p, i, q, out),
        Some(FastPath::Pe) => radial(unsafe { concrete::<PartialEntities>(s) }, p, i, q, out),
        Some(FastPath::Le) => radial(unsafe { concrete::<LoopEdgeUse>(s) }, p, i, q, out),
        Some(FastPath::De) => radial(unsafe { concrete::<DirectedEdge>(s) }, p, i, q, out),
        Some(FastPath::Walk) | None => None,
    }
}

/// The IA's R_{d,d}: its adjacency row without the NONE entries.
fn ia_adjacency(
    ia: &IndexedAdjacency,
    p: usize,
    i: u32,
    q: usize,
    out: &mut impl Sink,
) -> Option<usize> {
    let d = ia.dimension();
    if d == 0 || p != d || q != d || i as usize >= ia.count(d) {
        return None;
    }
    let row = ia.neighbours(i);
    let len = row.iter().filter(|&&t| t != NONE).count();
    copy_exact(len, row.iter().copied().filter(|&t| t != NONE), out)
}

/// A radial structure's R_{2,2} from its cycles, its other loops (VV, VF) through
/// [`looped`].
fn radial<T: TriTopo + NavBase>(
    t: &T,
    p: usize,
    i: u32,
    q: usize,
    out: &mut impl Sink,
) -> Option<usize> {
    let ff = p == 2 && q == 2 && t.dimension() >= 2 && i < t.n_tris();
    ff.then(|| radial_ff(t, i, out))
        .flatten()
        .or_else(|| looped(t, p, i, q, out))
}

/// The structure's own loop for R_{p,q} (`NavBase::fast_into`, where it has one) into this
/// thread's answer buffer, copied when it fits.
fn looped<T: NavBase>(t: &T, p: usize, i: u32, q: usize, out: &mut impl Sink) -> Option<usize> {
    let d = t.dimension();
    if p > d || q > d || i as usize >= t.count(p) || !t.has_fast(p, q) {
        return None;
    }
    with_buffer(|v| {
        t.fast_into(p, i, q, v);
        copy_exact(v.len(), v.iter().copied(), out)
    })
}

/// Runs `f` on this thread's cleared answer buffer; `None` when it is in use (a reentrant
/// call) or gone (thread teardown): the full path copes with both.
#[inline]
fn with_buffer(f: impl FnOnce(&mut Vec<u32>) -> Option<usize>) -> Option<usize> {
    super::ANSWER
        .try_with(|cell| {
            let mut v = cell.try_borrow_mut().ok()?;
            v.clear();
            let r = f(&mut v);
            super::trim_kept(&mut v);
            r
        })
        .ok()
        .flatten()
}

/// The structure behind `s.topo` as its concrete type `T`, without the dynamic type check of
/// `downcast_ref` (a call through the vtable on every query).
///
/// # Safety
/// `s.topo` must hold a `T` (what `s.direct` records).
#[inline]
unsafe fn concrete<T: Topology>(s: &TpxStructure) -> &T {
    debug_assert!((&*s.topo as &dyn Any).is::<T>());
    // SAFETY: the caller guarantees the concrete type; the data pointer of a `dyn Topology`
    // points to that value.
    unsafe { &*(&*s.topo as *const dyn Topology as *const T) }
}

/// The IG's stored rows: R_{p,p−1}, R_{p,p+1}, and R_{0,0} as the other end of each edge at v.
fn ig(g: &IncidenceGraph, p: usize, i: u32, q: usize, out: &mut impl Sink) -> Option<usize> {
    let d = g.dimension();
    if p > d || q > d || i as usize >= g.count(p) {
        return None;
    }
    if q + 1 == p {
        let row = g.boundary_ids(p, i);
        copy_exact(row.len(), row.iter().copied(), out)
    } else if q == p + 1 {
        let row = g.coboundary_ids(p, i);
        copy_exact(row.len(), row.iter().copied(), out)
    } else if p == 0 && q == 0 && d >= 1 {
        let edges = g.coboundary_ids(0, i);
        copy_exact(
            edges.len(),
            edges.iter().map(|&e| {
                let ends = g.boundary_ids(1, e);
                if ends[0] == i { ends[1] } else { ends[0] }
            }),
            out,
        )
    } else {
        None
    }
}

/// R_{2,2} of triangle `i` (a triangle of `t`): the triangles around its three edges, in
/// radial order (the order of the structure's own walk); `None` past 48 of them.
fn radial_ff<T: TriTopo>(t: &T, i: u32, out: &mut impl Sink) -> Option<usize> {
    // Counted first, so that a buffer too short is left as it was.
    let mut tmp = [0u32; 48];
    let mut k = 0;
    for s in 3 * i..3 * i + 3 {
        let mut r = t.radial_next(s);
        while r != s {
            *tmp.get_mut(k)? = r / 3;
            k += 1;
            r = t.radial_next(r);
        }
    }
    copy_exact(k, tmp[..k].iter().copied(), out)
}

/// A row of `len` ids into `out` when it fits (nothing written otherwise).
#[inline]
fn copy_exact(len: usize, row: impl Iterator<Item = u32>, out: &mut impl Sink) -> Option<usize> {
    if len > out.room() {
        return None;
    }
    for (k, id) in row.enumerate() {
        out.put(k, id);
    }
    Some(len)
}

/// Any other relation of the nine: the structure's own walk into this thread's answer buffer,
/// then copied when it fits.
fn walked(s: &TpxStructure, h: SimplexHandle, q: u32, out: &mut impl Sink) -> Option<usize> {
    let n: &dyn Navigate = s.topo.as_navigate()?;
    with_buffer(|v| {
        n.related_ids(h, q as usize, Order::Natural, v).ok()?;
        copy_exact(v.len(), v.iter().copied(), out)
    })
}

/// The boundary of a fast call: `Some(TPX_STATUS_OK)` when `body` answered (the last error
/// cleared), `Some(TPX_STATUS_PANIC)` when it panicked (recorded as the full guard does),
/// `None` when the full path must run.
pub(crate) fn guard_fast(body: impl FnOnce() -> bool) -> Option<TpxStatus> {
    match std::panic::catch_unwind(std::panic::AssertUnwindSafe(body)) {
        Ok(true) => {
            super::clear_last_error();
            Some(TpxStatus::Ok)
        }
        Ok(false) => None,
        Err(payload) => Some(super::guard(|| {
            std::panic::resume_unwind(payload);
        })),
    }
}
