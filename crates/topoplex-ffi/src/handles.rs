//! Handles through the C ABI: `TpxSimplex` and the `tpx_*` functions that locate once and then
//! navigate from handles (see `topoplex::relation::handle` for what a handle is and what it costs).
//!
//! Every function checks its handles before use: a handle from another structure is
//! FOREIGN_HANDLE (its `owner` stamp differs), an index or dimension out of range INVALID_HANDLE,
//! a handle of the wrong dimension for the call WRONG_HANDLE_KIND — never undefined behaviour.
//! Answers of one dimension are written as dense indices (`uint32_t`): the q-simplex of index i
//! is the handle `{i, q, owner}` (`tpx_handle` builds it checked). Every structure, the live
//! complex included, answers both forms: the live complex's handles above vertices are not
//! their index (a top simplex and a vertex mask, lasting across edits), so it numbers those
//! simplices on demand — lexicographic ranks, as the nine do, built on first use and
//! renumbered by each edit (`topoplex::live`, module `dense`): its indices above vertices, and
//! the handles `{i, q, owner}` made from them, are valid until the next edit. The
//! handle-writing twins (`tpx_related_handles`, `tpx_related_handles_batch`,
//! `tpx_cyclic_handles`) give handles that last across edits instead. NOT_DENSE is no longer
//! returned by any function (its number stays reserved).
//!
//! No allocation on the query path: every function here, on success, allocates nothing once
//! this thread's buffers have grown to the answers asked (answer buffers and walk scratch are
//! kept per thread, never in the structure; lazily built dimension tables are built by the first
//! call that needs them). `tests/alloc_free.rs` checks it with a counting allocator for every
//! function and the nine structures. An error allocates its message.

use std::cell::RefCell;
use std::sync::atomic::{AtomicU32, Ordering as AtomicOrdering};

use super::direct::{self, guard_fast};
use super::structure::{TpxStructure, query_failure};
use super::{
    Failure, TpxStatus, check_room, guard, handle, in_slice, on, out_ptr, with_answer, with_kept,
    write_buffer,
};
use topoplex::complex::MAX_DIMENSION;
use topoplex::relation::handle::{Fans, Navigate, Order, SimplexHandle, TopId};
use topoplex::scratch::Scratch;

/// A handle to one simplex of one structure (12 bytes, plain data; copy freely).
///
/// `index` is the simplex's dense index among the simplices of its dimension (lexicographic
/// rank; a vertex's index is its id; the caller's per-dimension arrays can be indexed by it).
/// `meta` holds the dimension in its low 8 bits (`meta & 0xff`); the other bits are 0 for the
/// nine built structures. The live complex (`tpx_live_structure`) names a simplex above its
/// vertices by a top simplex (`index`: dimension in the top 4 bits, slot below) and a mask of its
/// vertices (`meta` bits 16..32, form 1 in bits 8..16), so that the handle lasts across edits;
/// its dense index is then `tpx_simplex_index` (valid until the next edit), and a handle
/// `{i, p, owner}` built from an index (form 0) is accepted too, naming the p-simplex of index
/// i at the time of use. `owner` is the stamp of the structure
/// that made it. A handle of a built structure stays valid as long as its structure lives; one of
/// a live complex names its simplex (or, across a contraction, its image) while that simplex
/// exists — also when the top simplex naming it was removed, at the cost of locating it again on
/// each use — and is refused once the simplex is gone (STALE_HANDLE) or the complex is compacted
/// (STALE_GENERATION). Copying it is free, nothing needs releasing.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct TpxSimplex {
    /// Dense index among the simplices of its dimension.
    pub index: u32,
    /// Dimension in bits 0..8; form and local bits above (0 here).
    pub meta: u32,
    /// Stamp of the owning structure (`tpx_structure_stamp`).
    pub owner: u32,
}

/// Answer order of the navigation functions: the structure's natural order.
pub const TPX_ORDER_NATURAL: u32 = 0;
/// Answer order of the navigation functions: ascending lexicographic (ascending index).
pub const TPX_ORDER_LEXICOGRAPHIC: u32 = 1;
/// Flag bit of a group written by `tpx_fans_around` / `tpx_around_edge`: the group closes.
pub const TPX_GROUP_CLOSED: u32 = 1;
/// Flag bit of a group: consistently oriented and counter-clockwise by the input winding.
pub const TPX_GROUP_ORIENTED: u32 = 2;

static NEXT_STAMP: AtomicU32 = AtomicU32::new(1);

/// A fresh owner stamp (never 0, so a zeroed `TpxSimplex` is foreign to every structure).
pub(crate) fn new_stamp() -> u32 {
    loop {
        let s = NEXT_STAMP.fetch_add(1, AtomicOrdering::Relaxed);
        if s != 0 {
            return s;
        }
    }
}

fn nav(s: &TpxStructure) -> Result<&dyn Navigate, Failure> {
    s.topo.as_navigate().ok_or_else(|| {
        Failure::new(
            TpxStatus::NotImplemented,
            "this structure has no handle navigation",
        )
    })
}

fn wrap(s: &TpxStructure, h: SimplexHandle) -> TpxSimplex {
    let (index, meta) = h.to_words();
    TpxSimplex {
        index,
        meta,
        owner: s.stamp,
    }
}

/// The structure's handle for `h`, its owner stamp and form checked (FOREIGN_HANDLE,
/// STALE_GENERATION, INVALID_HANDLE), not yet its range.
fn unwrap_owned(
    s: &TpxStructure,
    n: &dyn Navigate,
    h: &TpxSimplex,
) -> Result<SimplexHandle, Failure> {
    if h.owner != s.stamp && s.retired.contains(&h.owner) {
        return Err(Failure::new(
            TpxStatus::StaleGeneration,
            format!(
                "handle {{index {}, meta {:#x}}} was made before a compaction of this live complex: map or locate it again",
                h.index, h.meta
            ),
        ));
    }
    if h.owner != s.stamp {
        return Err(Failure::new(
            TpxStatus::ForeignHandle,
            format!(
                "handle {{index {}, meta {:#x}}} belongs to structure {}, not to this one ({})",
                h.index, h.meta, h.owner, s.stamp
            ),
        ));
    }
    let sh = SimplexHandle::from_words(h.index, h.meta).ok_or_else(|| {
        Failure::new(
            TpxStatus::InvalidHandle,
            format!("handle meta {:#x}: unknown form or dimension", h.meta),
        )
    })?;
    Ok(sh.with_generation(n.generation()))
}

/// [`unwrap_owned`] and the range check: for functions that hand the handle to several
/// [`Navigate`] calls. A function making one call skips this second check, since every
/// `Navigate` method checks its handle itself.
fn unwrap(s: &TpxStructure, n: &dyn Navigate, h: &TpxSimplex) -> Result<SimplexHandle, Failure> {
    let sh = unwrap_owned(s, n, h)?;
    n.check(sh).map_err(query_failure)?;
    Ok(sh)
}

fn order_arg(order: u32) -> Result<Order, Failure> {
    match order {
        TPX_ORDER_NATURAL => Ok(Order::Natural),
        TPX_ORDER_LEXICOGRAPHIC => Ok(Order::Lexicographic),
        _ => Err(Failure::new(
            TpxStatus::InvalidArgument,
            format!("order {order} is not TPX_ORDER_NATURAL (0) or TPX_ORDER_LEXICOGRAPHIC (1)"),
        )),
    }
}

thread_local! {
    static HANDLES: RefCell<Vec<SimplexHandle>> = const { RefCell::new(Vec::new()) };
    static FANS: RefCell<Fans> = RefCell::new(Fans::default());
}

/// The owner stamp of structure `s` into `*out`: every handle it makes carries it. O(1).
///
/// # Safety
/// Non-NULL pointers must be valid.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tpx_structure_stamp(s: *const TpxStructure, out: *mut u32) -> TpxStatus {
    super::get_into(s, "s", out, |s| s.stamp)
}

/// Locates the simplex with vertex ids `simplex[0 .. simplex_len]` (any order) and writes its
/// handle to `*out`. Errors: NULL_ARGUMENT, INVALID_SIMPLEX, NOT_IN_COMPLEX. Cost: O(p log n_p)
/// (a binary search; for dimensions a structure stores only implicitly, the first call builds
/// that dimension's table once, see the Rust `handle` module). No allocation otherwise.
///
/// # Safety
/// Non-NULL pointers must be valid; `simplex` must hold `simplex_len` ids.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tpx_locate(
    s: *const TpxStructure,
    simplex: *const u32,
    simplex_len: usize,
    out: *mut TpxSimplex,
) -> TpxStatus {
    on(s, "s", |s| {
        let out = out_ptr(out, "out")?;
        let sigma = in_slice(simplex, simplex_len, "simplex")?;
        let h = nav(s)?.locate(sigma).map_err(query_failure)?;
        *out = wrap(s, h);
        Ok(())
    })
}

/// The handle of the p-simplex of dense index `index` into `*out` (for a vertex: p = 0, index =
/// its id). Errors: INVALID_HANDLE (p > d or index >= n_p). O(1); on the live complex, for
/// p > 0, the handle lasting across edits of the simplex of that rank now (its table built on
/// first use), O(p + d·k_v).
///
/// # Safety
/// Non-NULL pointers must be valid.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tpx_handle(
    s: *const TpxStructure,
    p: u32,
    index: u32,
    out: *mut TpxSimplex,
) -> TpxStatus {
    on(s, "s", |s| {
        let out = out_ptr(out, "out")?;
        let h = nav(s)?
            .handle(p.min(255) as usize, index)
            .map_err(query_failure)?;
        *out = wrap(s, h);
        Ok(())
    })
}

/// The dense index of `*h` into `*out`: its rank among the simplices of its dimension in
/// ascending lexicographic order (a vertex: its id) — the index `tpx_handle` takes back, that
/// `tpx_related` writes and the relation views are indexed by, and that the caller's
/// per-dimension arrays can use. For the nine structures it is `h->index`; the live complex's
/// handles above vertices are not their index (they last across edits), and this gives the
/// index of its numbering of the moment, valid until its next edit. Errors: NULL_ARGUMENT,
/// FOREIGN_HANDLE, STALE_GENERATION, INVALID_HANDLE, STALE_HANDLE; `*out` written only on
/// success. O(1) (the live complex: O(p log n_p), the dimension's table built on first use).
///
/// # Safety
/// Non-NULL pointers must be valid.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tpx_simplex_index(
    s: *const TpxStructure,
    h: *const TpxSimplex,
    out: *mut u32,
) -> TpxStatus {
    on(s, "s", |s| {
        let h = handle(h, "h")?;
        let out = out_ptr(out, "out")?;
        let n = nav(s)?;
        *out = n.index_of(unwrap_owned(s, n, h)?).map_err(query_failure)?;
        Ok(())
    })
}

/// The vertex ids of `*h`, ascending, into `buf` (p + 1 of them; `*out_len` = p + 1).
/// Errors: NULL_ARGUMENT, FOREIGN_HANDLE, INVALID_HANDLE, BUFFER_TOO_SMALL. O(p).
///
/// # Safety
/// Non-NULL pointers must be valid; `buf` must have room for `buf_len` ids.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tpx_simplex_vertices(
    s: *const TpxStructure,
    h: *const TpxSimplex,
    buf: *mut u32,
    buf_len: usize,
    out_len: *mut usize,
) -> TpxStatus {
    on(s, "s", |s| {
        let h = handle(h, "h")?;
        let out_len = out_ptr(out_len, "out_len")?;
        let n = nav(s)?;
        let v = n.vertices_of(unwrap(s, n, h)?).map_err(query_failure)?;
        write_buffer(&v, buf, buf_len, out_len)
    })
}

/// Number of top simplices over all dimensions into `*out` (top ids are `0 .. *out`, except on
/// the live complex, whose top ids are packed slots: see `tpx_live_structure`). O(1) (O(n) on
/// the live complex).
///
/// # Safety
/// Non-NULL pointers must be valid.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tpx_top_total(s: *const TpxStructure, out: *mut u32) -> TpxStatus {
    on(s, "s", |s| {
        let out = out_ptr(out, "out")?;
        *out = nav(s)?.top_total();
        Ok(())
    })
}

/// The handle of top simplex `top` (top ids: dimension ascending, lexicographic within; the same
/// for every structure built from one complex) into `*out`. Errors: INVALID_HANDLE (out of
/// range). O(1) for top d-simplices, O(p log n) below.
///
/// # Safety
/// Non-NULL pointers must be valid.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tpx_top(
    s: *const TpxStructure,
    top: u32,
    out: *mut TpxSimplex,
) -> TpxStatus {
    on(s, "s", |s| {
        let out = out_ptr(out, "out")?;
        let h = nav(s)?.top(TopId(top)).map_err(query_failure)?;
        *out = wrap(s, h);
        Ok(())
    })
}

/// The top id of `*h` into `*out`, or `UINT32_MAX` when it is not a top simplex. Errors:
/// FOREIGN_HANDLE, INVALID_HANDLE. O(1) for d-simplices, O(p log n) below.
///
/// # Safety
/// Non-NULL pointers must be valid.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tpx_top_id(
    s: *const TpxStructure,
    h: *const TpxSimplex,
    out: *mut u32,
) -> TpxStatus {
    on(s, "s", |s| {
        let h = handle(h, "h")?;
        let out = out_ptr(out, "out")?;
        let n = nav(s)?;
        let t = n.top_id(unwrap(s, n, h)?).map_err(query_failure)?;
        *out = t.map_or(u32::MAX, |t| t.0);
        Ok(())
    })
}

/// Top simplex `top` as given in the input (its first listing's vertex order, hence its
/// winding) into `buf`; `*out_len` = its vertex count. `tpx_simplex_vertices` of `tpx_top`
/// gives the normalised (ascending) form. Errors: INVALID_HANDLE, BUFFER_TOO_SMALL. O(p).
///
/// # Safety
/// Non-NULL pointers must be valid; `buf` must have room for `buf_len` ids.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tpx_top_as_given(
    s: *const TpxStructure,
    top: u32,
    buf: *mut u32,
    buf_len: usize,
    out_len: *mut usize,
) -> TpxStatus {
    on(s, "s", |s| {
        let out_len = out_ptr(out_len, "out_len")?;
        let v = nav(s)?.top_as_given(TopId(top)).map_err(query_failure)?;
        write_buffer(&v, buf, buf_len, out_len)
    })
}

/// R_{p,q}(*h) (p = the handle's dimension) as dense indices of q-simplices into `buf`, in
/// `order` (`TPX_ORDER_*`); `*out_len` = the number written. Errors: FOREIGN_HANDLE,
/// INVALID_HANDLE, DIMENSION_OUT_OF_RANGE (q > d), INVALID_ARGUMENT (order), BUFFER_TOO_SMALL
/// (nothing written; `*out_len` = needed). On the live complex, indices above vertices are its
/// numbering until the next edit (module doc). Cost: the structure's walk (module docs), plus a sort
/// for lexicographic order; rows a structure stores (the IG's boundaries and co-boundaries, the
/// IA's adjacency, the radial cycles' FF) are copied straight into `buf` (see `ffi::direct`).
/// No allocation once this thread's buffers have grown to the answer.
///
/// # Safety
/// Non-NULL pointers must be valid; `buf` must have room for `buf_len` ids.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tpx_related(
    s: *const TpxStructure,
    h: *const TpxSimplex,
    q: u32,
    order: u32,
    buf: *mut u32,
    buf_len: usize,
    out_len: *mut usize,
) -> TpxStatus {
    related_into(s, h, q, order, buf, buf_len, out_len)
}

/// What an answer is written as: dense indices (`u32`: `tpx_related`, `tpx_related_batch`,
/// `tpx_cyclic`) or handles (`TpxSimplex`: their `_handles` twins). Each pair of twins is one
/// generic body over it ([`related_into`], [`batch_into`], [`cyclic_into`]); an impl is the table
/// of what differs.
trait Written: Copy + 'static {
    /// What the full path collects in [`Written::KEPT`].
    type Kept: 'static;
    /// This thread's kept buffer of the full path.
    const KEPT: &'static std::thread::LocalKey<RefCell<Vec<Self::Kept>>>;
    /// The items' name in messages.
    const NAME: &'static str;
    /// Whether these are dense indices (which the live complex's handles above vertices are
    /// not: they are converted through `Navigate::index_of`).
    const DENSE: bool;
    /// R_{p,q}(h) by the full path (the structure's walk).
    const WALK: Walk<Self::Kept>;
    /// A batch's answers into the caller's buffer, or BUFFER_TOO_SMALL.
    const WRITE: Write<Self::Kept, Self>;
    /// The caller's buffer as the fast path's [`direct::Sink`] (answers of dimension `q` of the
    /// structure stamped `owner`).
    fn sink(out: &mut [Self], q: u32, owner: u32) -> impl direct::Sink + '_;
    /// A kept answer as written.
    fn item(s: &TpxStructure, x: &Self::Kept) -> Self;
    /// The simplex of handle `h` as written.
    fn of_handle(s: &TpxStructure, h: SimplexHandle) -> Self;
}

/// [`Written::WALK`]: R_{p,q}(h) in `order` into the kept buffer.
type Walk<K> = fn(
    &dyn Navigate,
    SimplexHandle,
    usize,
    Order,
    &mut Vec<K>,
) -> Result<(), topoplex::relation::QueryError>;

/// [`Written::WRITE`]: `v` into `buf[0 .. buf_len]`, `*out_len` its length.
type Write<K, U> = fn(&TpxStructure, &[K], *mut U, usize, &mut usize) -> Result<(), Failure>;

impl Written for u32 {
    type Kept = u32;
    const KEPT: &'static std::thread::LocalKey<RefCell<Vec<u32>>> = &super::ANSWER;
    const NAME: &'static str = "ids";
    const DENSE: bool = true;
    const WALK: Walk<u32> = |n, h, q, order, v| n.related_ids(h, q, order, v);
    const WRITE: Write<u32, u32> =
        |_, v, buf, buf_len, out_len| write_buffer(v, buf, buf_len, out_len);

    fn sink(out: &mut [u32], _: u32, _: u32) -> impl direct::Sink + '_ {
        out
    }

    fn item(_: &TpxStructure, &x: &u32) -> u32 {
        x
    }

    fn of_handle(_: &TpxStructure, h: SimplexHandle) -> u32 {
        h.index()
    }
}

impl Written for TpxSimplex {
    type Kept = SimplexHandle;
    const KEPT: &'static std::thread::LocalKey<RefCell<Vec<SimplexHandle>>> = &HANDLES;
    const NAME: &'static str = "handles";
    const DENSE: bool = false;
    const WALK: Walk<SimplexHandle> = |n, h, q, order, v| n.related(h, q, order, v);
    const WRITE: Write<SimplexHandle, TpxSimplex> = write_items;

    fn sink(out: &mut [TpxSimplex], q: u32, owner: u32) -> impl direct::Sink + '_ {
        direct::Handles { out, q, owner }
    }

    fn item(s: &TpxStructure, &x: &SimplexHandle) -> TpxSimplex {
        wrap(s, x)
    }

    fn of_handle(s: &TpxStructure, h: SimplexHandle) -> TpxSimplex {
        wrap(s, h)
    }
}

/// The one body of `tpx_related` and `tpx_related_handles`: the fast path ([`direct`]) when the
/// arguments are the usual ones and the answer fits, else the full path ([`answer_into`]),
/// which finds and reports every error.
#[inline]
fn related_into<U: Written>(
    s: *const TpxStructure,
    h: *const TpxSimplex,
    q: u32,
    order: u32,
    buf: *mut U,
    buf_len: usize,
    out_len: *mut usize,
) -> TpxStatus {
    let fast = guard_fast(|| {
        let Some((st, sh, ord, len)) = direct::arguments(s, h, order, out_len) else {
            return false;
        };
        let Some(out) = direct::out_slice(buf, buf_len) else {
            return false;
        };
        direct::answer(st, sh, q, ord, &mut U::sink(out, q, st.stamp))
            .map(|n| *len = n)
            .is_some()
    });
    if let Some(status) = fast {
        return status;
    }
    let order = order_arg(order);
    answer_into(s, h, buf, buf_len, out_len, |n, sh, v| {
        (U::WALK)(n, sh, q as usize, order?, v).map_err(query_failure)
    })
}

/// The one body of the functions that answer one handle into the caller's buffer: `s`, `h`
/// and `out_len` NULL-checked, the handle's owner stamp and form checked (its range is checked
/// once, by the `Navigate` call inside `answer`), the answer built in this thread's kept
/// buffer ([`Written::KEPT`]; no allocation once it has grown), then written to `buf` as
/// [`Written::item`] (only on success; BUFFER_TOO_SMALL with the needed length otherwise).
fn answer_into<U: Written>(
    s: *const TpxStructure,
    h: *const TpxSimplex,
    buf: *mut U,
    buf_len: usize,
    out_len: *mut usize,
    answer: impl FnOnce(&dyn Navigate, SimplexHandle, &mut Vec<U::Kept>) -> Result<(), Failure>,
) -> TpxStatus {
    on(s, "s", |s| {
        let h = handle(h, "h")?;
        let out_len = out_ptr(out_len, "out_len")?;
        let n = nav(s)?;
        let sh = unwrap_owned(s, n, h)?;
        with_kept(U::KEPT, |v| {
            v.clear();
            let r = answer(n, sh, v).and_then(|()| write_items(s, v, buf, buf_len, out_len));
            super::trim_kept(v);
            r
        })
    })
}

/// R_{p,q} for many p-simplices at once, in CSR form: for the dense p-indices
/// `indices[0 .. count]`, `offsets[0 .. count + 1]` receives the start of each answer in `buf`
/// (`offsets[count]` = total) and `buf` the dense q-indices, each answer in `order`.
/// Errors: INVALID_HANDLE (p > d or an index out of range), DIMENSION_OUT_OF_RANGE,
/// BUFFER_TOO_SMALL (nothing written; `*out_len` = needed length of `buf`), as `tpx_related`
/// (the live complex: indices valid until its next edit, module doc).
/// `offsets` must hold `count + 1` entries. Cost: one walk per index (TS, PE, LE, DE answer
/// VV, VF and FF in one loop with no call per answer); allocation-free once this thread's buffer
/// has grown to the total.
///
/// # Safety
/// Non-NULL pointers must be valid; `indices` holds `count` ids, `offsets` room for `count + 1`,
/// `buf` room for `buf_len`.
#[unsafe(no_mangle)]
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn tpx_related_batch(
    s: *const TpxStructure,
    p: u32,
    indices: *const u32,
    count: usize,
    q: u32,
    order: u32,
    offsets: *mut u32,
    buf: *mut u32,
    buf_len: usize,
    out_len: *mut usize,
) -> TpxStatus {
    let inputs = (indices, count, "indices");
    let out = (offsets, buf, buf_len, out_len);
    batch_into(s, inputs, order, out, |_, n, indices, order, ids, ends| {
        let p = (p as usize).min(MAX_DIMENSION + 1);
        let too_large = |_| Failure::new(TpxStatus::TooLarge, "offsets do not fit in memory");
        ends.try_reserve(count).map_err(too_large)?;
        n.related_batch(p, indices, q as usize, order, ids, ends)
            .map_err(query_failure)
    })
}

/// The one body of `tpx_related_batch` and `tpx_related_handles_batch`: the arguments checked
/// (the `count` inputs, named `what` in messages), then `answer` fills this thread's kept
/// buffer with every answer and `ends` with where each ends. The answers (fewer than 2^32) and
/// the offsets are written only on success.
fn batch_into<U: Written, I>(
    s: *const TpxStructure,
    (inputs, count, what): (*const I, usize, &str),
    order: u32,
    (offsets, buf, buf_len, out_len): (*mut u32, *mut U, usize, *mut usize),
    answer: impl FnOnce(
        &TpxStructure,
        &dyn Navigate,
        &[I],
        Order,
        &mut Vec<U::Kept>,
        &mut Vec<usize>,
    ) -> Result<(), Failure>,
) -> TpxStatus {
    on(s, "s", |s| {
        let out_len = out_ptr(out_len, "out_len")?;
        let inputs = in_slice(inputs, count, what)?;
        if offsets.is_null() {
            return Err(Failure::null("offsets"));
        }
        let order = order_arg(order)?;
        let n = nav(s)?;
        // Offsets are written only on success: kept aside, then copied.
        let mut ends = Scratch::<Vec<usize>>::take();
        with_kept(U::KEPT, |v| {
            v.clear();
            let r = answer(s, n, inputs, order, v, &mut ends).and_then(|()| {
                if u32::try_from(v.len()).is_err() {
                    let message = format!("answers exceed 2^32 {}", U::NAME);
                    return Err(Failure::new(TpxStatus::TooLarge, message));
                }
                (U::WRITE)(s, v, buf, buf_len, out_len)?;
                // SAFETY: `offsets` has room for `count + 1` entries (documented contract), and
                // `ends` holds `count` ends below 2^32 (checked above).
                unsafe {
                    *offsets = 0;
                    for (k, &e) in ends.iter().enumerate() {
                        *offsets.add(k + 1) = e as u32;
                    }
                }
                Ok(())
            });
            super::trim_kept(v);
            r
        })
    })
}

/// |R_{p,q}(*h)| into `*out`, without writing the answer. Same errors and cost as `tpx_related`;
/// no allocation.
///
/// # Safety
/// Non-NULL pointers must be valid.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tpx_degree(
    s: *const TpxStructure,
    h: *const TpxSimplex,
    q: u32,
    out: *mut usize,
) -> TpxStatus {
    on(s, "s", |s| {
        let h = handle(h, "h")?;
        let out = out_ptr(out, "out")?;
        let n = nav(s)?;
        *out = n
            .degree(unwrap_owned(s, n, h)?, q as usize)
            .map_err(query_failure)?;
        Ok(())
    })
}

/// |R_{p,q}| of the p-simplices of dense indices `indices[0 .. count]` into `degrees[0 ..
/// count]`, without writing any answer (a valence histogram, boundary and non-manifold edge
/// lists read degrees only). Errors: NULL_ARGUMENT, INVALID_HANDLE (p > d or an index out of
/// range; on the live complex a removed vertex), DIMENSION_OUT_OF_RANGE (q > d); nothing is
/// written on error. Cost: for relations the IG stores (R_{p,p±1}, and R_{0,0} = the edges at
/// a vertex) O(1) per index from its offsets; otherwise the walk of each answer, counted in a
/// scratch buffer (no answer copied out). No allocation once this thread's scratch is warm.
///
/// # Safety
/// Non-NULL pointers must be valid; `indices` holds `count` ids and `degrees` room for `count`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tpx_degree_batch(
    s: *const TpxStructure,
    p: u32,
    indices: *const u32,
    count: usize,
    q: u32,
    degrees: *mut u32,
) -> TpxStatus {
    on(s, "s", |s| {
        let indices = in_slice(indices, count, "indices")?;
        if degrees.is_null() && count > 0 {
            return Err(Failure::null("degrees"));
        }
        let n = nav(s)?;
        let p = (p as usize).min(MAX_DIMENSION + 1);
        // Counted aside first: an error leaves `degrees` untouched.
        with_answer(|k| {
            k.try_reserve(count)
                .map_err(|_| Failure::new(TpxStatus::TooLarge, "degrees do not fit in memory"))?;
            k.resize(count, 0);
            n.degree_batch(p, indices, q as usize, k)
                .map_err(query_failure)?;
            write_slice(k, degrees);
            Ok(())
        })
    })
}

/// Copies `data` to `out`, which has room for `data.len()` items (checked by the caller).
fn write_slice<T: Copy>(data: &[T], out: *mut T) {
    if !data.is_empty() {
        // SAFETY: the caller checked `out` non-NULL with room for `data.len()` items; `data`
        // belongs to this library, so the two cannot overlap.
        unsafe { std::ptr::copy_nonoverlapping(data.as_ptr(), out, data.len()) };
    }
}

/// R_{p,q} of every p-simplex as one CSR lent by a structure (`tpx_relation_view`), for
/// iterating answers in the caller's own loop with no call per query (the C++
/// `Structure::view` ranges do): the answer of the p-simplex of dense index i is
/// `ids[offsets[i] .. offsets[i + 1]]`, in natural order. The arrays belong to the structure
/// and live as long as it does (the live complex: until its next edit).
#[repr(C)]
#[derive(Debug, Clone, Copy)]
pub struct TpxRelationView {
    /// `count + 1` offsets into `ids` (first 0, last the total).
    pub offsets: *const u32,
    /// Every answer, p-simplex after p-simplex, as dense q-indices.
    pub ids: *const u32,
    /// Number of p-simplices (n_p).
    pub count: usize,
    /// 1 when the arrays are an index built for the view, 0 when they are the structure's own.
    pub built: u32,
    /// Bytes of the two arrays (`4 (count + 1) + 4 * total`): extra memory when `built`.
    pub bytes: u64,
}

/// Lends R_{p,q} of every p-simplex as one CSR into `*out` (`TpxRelationView`). The arrays are
/// owned by the structure and stay valid, unchanged, until `tpx_structure_free`; read them from
/// any number of threads. Where the structure stores the relation in CSR form (the IG's
/// co-boundaries R_{p,p+1}) they are its own arrays: O(1), no memory. Otherwise the first call
/// builds an index — one walk over every p-simplex (the cost of `tpx_related_batch` over every
/// p-simplex), `4 (n_p + 1) + 4 Σ|R_{p,q}|` bytes kept with the
/// structure (`built` = 1, `bytes`) — and later calls are O(1). Each answer is in natural order,
/// the same as `tpx_related` (TPX_ORDER_NATURAL). Errors: NULL_ARGUMENT,
/// DIMENSION_OUT_OF_RANGE (p or q > d), TOO_LARGE (the index does not fit in memory or its
/// offsets in 32 bits); `*out` is written only on success.
///
/// The live complex lends views too, built the same way, but they (and its indices above
/// vertices) are valid only until its next edit — insert, remove, contract, split, add vertex,
/// compact; setting coordinates keeps them — which drops them (after an edit, ask again: one
/// walk). Its vertex rows are its vertex slots (`count` = `tpx_live_vertex_slots`), a removed
/// vertex's row empty.
///
/// # Safety
/// Non-NULL pointers must be valid.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tpx_relation_view(
    s: *const TpxStructure,
    p: u32,
    q: u32,
    out: *mut TpxRelationView,
) -> TpxStatus {
    on(s, "s", |s| {
        let out = out_ptr(out, "out")?;
        let n = nav(s)?;
        let v = n
            .relation_view(p as usize, q as usize)
            .map_err(query_failure)?
            .ok_or_else(|| {
                Failure::new(TpxStatus::NotDense, "this structure lends no relation view")
            })?;
        *out = TpxRelationView {
            offsets: v.offsets().as_ptr(),
            ids: v.ids().as_ptr(),
            count: v.len(),
            built: u32::from(v.is_built()),
            bytes: v.bytes(),
        };
        Ok(())
    })
}

/// The star (every simplex having `*h` as a proper face, dimension ascending) or, with `link`
/// non-zero, the link (τ ∖ h for each such τ) of `*h`, as handles into `buf`, each dimension in
/// `order`. Errors as `tpx_related`. Cost: the star's walks (the link also locates each face).
/// No allocation once this thread's buffers are warm.
///
/// # Safety
/// Non-NULL pointers must be valid; `buf` must have room for `buf_len` handles.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tpx_star(
    s: *const TpxStructure,
    h: *const TpxSimplex,
    link: u32,
    order: u32,
    buf: *mut TpxSimplex,
    buf_len: usize,
    out_len: *mut usize,
) -> TpxStatus {
    let order = order_arg(order);
    answer_into(s, h, buf, buf_len, out_len, |n, sh, hs| {
        let order = order?;
        if link != 0 {
            n.link(sh, order, hs)
        } else {
            n.star(sh, order, hs)
        }
        .map_err(query_failure)
    })
}

/// Whether `*h` is on the boundary (`what` = 0) or a manifold simplex (`what` = 1), as 0 or 1
/// into `*out` (definitions: `Navigate::is_boundary`, `Navigate::is_manifold`). Errors as
/// `tpx_related`, INVALID_ARGUMENT for another `what`. Cost: the star of h (for the manifold
/// test, plus a sort of the link's facets). No allocation once this thread's buffers are warm.
///
/// # Safety
/// Non-NULL pointers must be valid.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tpx_simplex_test(
    s: *const TpxStructure,
    h: *const TpxSimplex,
    what: u32,
    out: *mut u32,
) -> TpxStatus {
    on(s, "s", |s| {
        let h = handle(h, "h")?;
        let out = out_ptr(out, "out")?;
        let n = nav(s)?;
        let sh = unwrap(s, n, h)?;
        let r = match what {
            0 => n.is_boundary(sh),
            1 => n.is_manifold(sh),
            _ => {
                return Err(Failure::new(
                    TpxStatus::InvalidArgument,
                    format!("test {what} is not 0 (boundary) or 1 (manifold)"),
                ));
            }
        };
        *out = u32::from(r.map_err(query_failure)?);
        Ok(())
    })
}

/// Cyclic order: with `q` = 0, the manifold fans of triangles around vertex `*h` (a complex of
/// dimension ≤ 2; counter-clockwise by the input winding where oriented); with `q` = 2 or 3,
/// the triangles / tetrahedra around edge `*h` in radial order. Group k is
/// `items[offsets[k] .. offsets[k+1]]` (dense indices of triangles, or of tetrahedra for q = 3),
/// `flags[k]` has `TPX_GROUP_CLOSED` and `TPX_GROUP_ORIENTED`; `*out_items` and `*out_groups`
/// receive the counts. `offsets` needs `groups + 1` entries. Errors: WRONG_HANDLE_KIND (not a
/// vertex / not an edge), DIMENSION_OUT_OF_RANGE, BUFFER_TOO_SMALL (nothing written; the needed counts in `*out_items`
/// and `*out_groups`). Cost: the star of the vertex or edge. No allocation once this thread's
/// buffers are warm.
///
/// # Safety
/// Non-NULL pointers must be valid; `items` has room for `items_len`, `offsets` for
/// `groups_len + 1` and `flags` for `groups_len` entries.
#[unsafe(no_mangle)]
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn tpx_cyclic(
    s: *const TpxStructure,
    h: *const TpxSimplex,
    q: u32,
    items: *mut u32,
    items_len: usize,
    offsets: *mut u32,
    flags: *mut u32,
    groups_len: usize,
    out_items: *mut usize,
    out_groups: *mut usize,
) -> TpxStatus {
    let items = (items, items_len);
    let groups = (offsets, flags, groups_len);
    cyclic_into(s, h, q, items, groups, (out_items, out_groups))
}

/// The output buffers of `tpx_cyclic` and `tpx_cyclic_handles` (items of type `T`).
struct CyclicOut<T> {
    items: *mut T,
    items_len: usize,
    offsets: *mut u32,
    flags: *mut u32,
    groups_len: usize,
    out_items: *mut usize,
    out_groups: *mut usize,
}

/// The one body of `tpx_cyclic` and `tpx_cyclic_handles`: `items` is (`items`, `items_len`),
/// `groups` (`offsets`, `flags`, `groups_len`), `counts` (`out_items`, `out_groups`).
fn cyclic_into<U: Written>(
    s: *const TpxStructure,
    h: *const TpxSimplex,
    q: u32,
    (items, items_len): (*mut U, usize),
    (offsets, flags, groups_len): (*mut u32, *mut u32, usize),
    (out_items, out_groups): (*mut usize, *mut usize),
) -> TpxStatus {
    let o = CyclicOut {
        items,
        items_len,
        offsets,
        flags,
        groups_len,
        out_items,
        out_groups,
    };
    on(s, "s", |s| cyclic_checked(s, h, q, o))
}

/// [`cyclic_into`] once `s` is checked.
fn cyclic_checked<U: Written>(
    s: &TpxStructure,
    h: *const TpxSimplex,
    q: u32,
    o: CyclicOut<U>,
) -> Result<(), Failure> {
    let h = handle(h, "h")?;
    let out_items = out_ptr(o.out_items, "out_items")?;
    let out_groups = out_ptr(o.out_groups, "out_groups")?;
    let (items, offsets, flags) = (o.items, o.offsets, o.flags);
    let n = nav(s)?;
    let sh = unwrap(s, n, h)?;
    with_kept(&FANS, |fans| {
        match q {
            0 => n.fans_around(sh, fans),
            _ => n.around_edge(sh, q as usize, fans),
        }
        .map_err(query_failure)?;
        let (ni, ng) = (fans.items.len(), fans.len());
        if ni > o.items_len || ng > o.groups_len {
            *out_items = ni;
            *out_groups = ng;
            return Err(Failure::new(
                TpxStatus::BufferTooSmall,
                format!("the answer needs {ni} items and {ng} groups"),
            ));
        }
        if (ni > 0 && items.is_null()) || offsets.is_null() || (ng > 0 && flags.is_null()) {
            return Err(Failure::null("items, offsets or flags"));
        }
        if U::DENSE && !n.dense() {
            // Handles that are not their index (the live complex): written as their index.
            for x in fans.items.iter_mut() {
                *x = SimplexHandle::dense(x.dim(), n.index_of(*x).map_err(query_failure)?);
            }
        }
        for (i, &x) in fans.items.iter().enumerate() {
            // SAFETY: room for items_len >= ni entries.
            unsafe { *items.add(i) = U::of_handle(s, x) };
        }
        for k in 0..=ng {
            // SAFETY: room for groups_len + 1 >= ng + 1 offsets.
            unsafe { *offsets.add(k) = fans.offsets.get(k).copied().unwrap_or(0) };
        }
        for k in 0..ng {
            let closed = if fans.closed[k] { TPX_GROUP_CLOSED } else { 0 };
            let f = closed
                | if fans.oriented[k] {
                    TPX_GROUP_ORIENTED
                } else {
                    0
                };
            // SAFETY: room for groups_len >= ng flags.
            unsafe { *flags.add(k) = f };
        }
        *out_items = ni;
        *out_groups = ng;
        Ok(())
    })
}

/// `tpx_cyclic` with the items written as handles (`TpxSimplex`), which on the live complex
/// last across edits (its indices do not). Same
/// arguments, errors and cost; `items` has room for `items_len` handles.
///
/// # Safety
/// Non-NULL pointers must be valid; `items` has room for `items_len`, `offsets` for
/// `groups_len + 1` and `flags` for `groups_len` entries.
#[unsafe(no_mangle)]
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn tpx_cyclic_handles(
    s: *const TpxStructure,
    h: *const TpxSimplex,
    q: u32,
    items: *mut TpxSimplex,
    items_len: usize,
    offsets: *mut u32,
    flags: *mut u32,
    groups_len: usize,
    out_items: *mut usize,
    out_groups: *mut usize,
) -> TpxStatus {
    let items = (items, items_len);
    let groups = (offsets, flags, groups_len);
    cyclic_into(s, h, q, items, groups, (out_items, out_groups))
}

/// R_{p,q}(*h) as handles (`TpxSimplex`) into `buf`, in `order`; `*out_len` = the number
/// written. Works for every structure, the live complex included (`tpx_related` writes dense
/// indices, which the live complex has only for vertices). Errors as `tpx_related`. Cost: the
/// structure's walk (the live complex: answers come lexicographic, both orders cost the same).
/// Allocation-free once this thread's buffer has grown to the answer.
///
/// # Safety
/// Non-NULL pointers must be valid; `buf` must have room for `buf_len` handles.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tpx_related_handles(
    s: *const TpxStructure,
    h: *const TpxSimplex,
    q: u32,
    order: u32,
    buf: *mut TpxSimplex,
    buf_len: usize,
    out_len: *mut usize,
) -> TpxStatus {
    related_into(s, h, q, order, buf, buf_len, out_len)
}

/// R_{p,q} of many handles at once, of any dimensions (mixed), in CSR form as handles: for the
/// handles `hs[0 .. count]`, `offsets[0 .. count + 1]` receives the start of each answer in
/// `buf` (`offsets[count]` = total) and `buf` the answers (`TpxSimplex`), each in `order`.
/// Works for every structure, the live complex included (`tpx_related_batch` takes and writes
/// dense indices, which the live complex has only for vertices). Errors: those of
/// `tpx_related_handles` for the first handle that fails (the message gives its position),
/// INVALID_ARGUMENT (order), BUFFER_TOO_SMALL (nothing written; `*out_len` = needed length of
/// `buf`), TOO_LARGE (more than 2^32 answers); nothing is written on an error. Cost: one walk
/// per handle, as `tpx_related_handles`; allocation-free once this thread's buffers have grown
/// to `count` and the total.
///
/// # Safety
/// Non-NULL pointers must be valid; `hs` holds `count` handles, `offsets` room for `count + 1`
/// entries, `buf` room for `buf_len` handles.
#[unsafe(no_mangle)]
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn tpx_related_handles_batch(
    s: *const TpxStructure,
    hs: *const TpxSimplex,
    count: usize,
    q: u32,
    order: u32,
    offsets: *mut u32,
    buf: *mut TpxSimplex,
    buf_len: usize,
    out_len: *mut usize,
) -> TpxStatus {
    let inputs = (hs, count, "hs");
    let out = (offsets, buf, buf_len, out_len);
    batch_into(s, inputs, order, out, |s, n, hs, order, out, ends| {
        let too_large = |_| Failure::new(TpxStatus::TooLarge, "the batch does not fit in memory");
        let mut checked = Scratch::<Vec<SimplexHandle>>::take();
        checked.try_reserve(count).map_err(too_large)?;
        for (k, h) in hs.iter().enumerate() {
            checked.push(unwrap(s, n, h).map_err(|f| at_position(f, k))?);
        }
        ends.try_reserve(count).map_err(too_large)?;
        n.related_handles_batch(&checked, q as usize, order, out, ends)
            .map_err(|e| at_position(query_failure(e), ends.len()))
    })
}

/// `f` with the position of the batch entry it is about.
fn at_position(f: Failure, k: usize) -> Failure {
    Failure::new(f.status, format!("batch entry {k}: {}", f.message))
}

/// Writes the kept answer `v` as [`Written::item`]s into `buf` (NULL_ARGUMENT and
/// BUFFER_TOO_SMALL as `write_buffer`'s, counting "entries").
fn write_items<U: Written>(
    s: &TpxStructure,
    v: &[U::Kept],
    buf: *mut U,
    buf_len: usize,
    out_len: &mut usize,
) -> Result<(), Failure> {
    check_room(buf, buf_len, v.len(), "entries", out_len)?;
    for (i, x) in v.iter().enumerate() {
        // SAFETY: `buf` has room for `buf_len >= v.len()` items (documented contract).
        unsafe { *buf.add(i) = U::item(s, x) };
    }
    *out_len = v.len();
    Ok(())
}

/// Listed simplex `i` of the input (`0 .. input_simplices`) exactly as given (order and
/// winding) into `buf`, and into `*top` the top id it became (as `tpx_top` numbers them, the same
/// in every structure of `c`), or `UINT32_MAX` when it was absorbed as a face of another listed
/// simplex (a repeated listing maps to the same top as its first). Writing the tops back in
/// input order: `i` ascending, skipping absorbed and repeated ones. Errors: INVALID_ARGUMENT (`i`
/// out of range), BUFFER_TOO_SMALL. O(p) (the first call builds the listing map,
/// O(Σ (p+1) log n_p)).
///
/// # Safety
/// Non-NULL pointers must be valid; `buf` must have room for `buf_len` ids.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tpx_complex_input_simplex(
    c: *const super::TpxComplex,
    i: usize,
    buf: *mut u32,
    buf_len: usize,
    out_len: *mut usize,
    top: *mut u32,
) -> TpxStatus {
    guard(|| {
        let c = &handle(c, "c")?.complex;
        let out_len = out_ptr(out_len, "out_len")?;
        let top = out_ptr(top, "top")?;
        if i >= c.input_count() {
            return Err(Failure::new(
                TpxStatus::InvalidArgument,
                format!("listed simplex {i}: the input lists {}", c.input_count()),
            ));
        }
        let t = c.input_top(i).map_or(u32::MAX, |(p, j)| {
            (0..p).map(|q| c.tops(q).len() as u32).sum::<u32>() + j
        });
        write_buffer(c.input_simplex(i), buf, buf_len, out_len)?;
        *top = t;
        Ok(())
    })
}
