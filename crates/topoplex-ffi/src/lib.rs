//! The C ABI of Topoplex (`include/topoplex.h` is generated from this crate by cbindgen; see
//! `tests/header.rs`): libtopoplex.so and libtopoplex.a over the core crate `topoplex`. With the
//! core's `sys` module, the only code with `unsafe`.
//!
//! # Conventions (every function)
//! - Fallible functions return a [`TpxStatus`]; `TPX_STATUS_OK` is 0. Numbers are fixed forever:
//!   a retired status keeps its number and no new status reuses it.
//! - Every pointer argument is checked for NULL (`TPX_STATUS_NULL_ARGUMENT`).
//! - Out-parameters are written only on success, except `*out_len` on
//!   `TPX_STATUS_BUFFER_TOO_SMALL`, which then holds the needed number of elements (`uint32_t`,
//!   or `double` for coordinates).
//! - No Rust panic crosses the boundary: each body runs under `catch_unwind` and a panic becomes
//!   `TPX_STATUS_PANIC` (so the crate must keep `panic = "unwind"`, checked below).
//! - After each status-returning call, [`tpx_last_error_message`] describes its failure (or is
//!   empty after success), naming the file, line and simplex where the Rust error does.
//! - Allocation failure does not abort the host where the input sets the size: making a complex
//!   reserves its input-sized arrays fallibly and refuses a closure above its budget (both
//!   `TPX_STATUS_TOO_LARGE`); every later allocation (structures, answers) is linear in that
//!   closure. Under a raised budget a structure larger than the memory available still aborts
//!   in Rust's allocator: keep the default budget when running under a tight memory limit.
//! - Handles are opaque; functions that only read take `const` pointers, and a `const
//!   TpxStructure *` may be queried from many threads at once.
//! - Every handle returned through `out` is owned by the caller and released by the matching
//!   `tpx_*_free`, which accepts NULL.

#![warn(missing_docs)]

use std::cell::{Cell, RefCell};
use std::ffi::{CString, c_char};
use std::panic::{AssertUnwindSafe, catch_unwind};
use std::sync::atomic::{AtomicUsize, Ordering};

mod attributes;
mod complex;
mod decomposition;
mod direct;
mod handles;
mod live;
mod simplify;
mod store;
mod structure;
#[cfg(test)]
mod tests;
mod write;

pub use attributes::*;
pub use complex::*;
pub use decomposition::*;
pub use handles::*;
pub use live::*;
pub use simplify::*;
pub use store::*;
pub use structure::*;
pub use write::*;

// The panic boundary below relies on unwinding; with `panic = "abort"` a bug would kill the host.
#[cfg(panic = "abort")]
compile_error!("topoplex's C ABI requires panic = \"unwind\"");

/// Result of a fallible `tpx_*` call. Values are part of the ABI and never reused.
#[repr(u32)]
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TpxStatus {
    /// Success.
    Ok = 0,
    /// A required pointer argument was NULL.
    NullArgument = 1,
    /// An argument is malformed: offsets not monotone, coordinate dimension 0, path not UTF-8.
    InvalidArgument = 2,
    /// The file cannot be read (missing, permissions).
    IoError = 3,
    /// The file is not valid in its format, or its extension is unknown (message: `file:line: what`).
    ParseError = 4,
    /// The simplices do not form a complex: repeated vertex, id out of range, dimension above
    /// 15, empty simplex, no vertices.
    InvalidComplex = 5,
    /// The kind number is not one of `TPX_KIND_*`.
    UnknownKind = 6,
    /// The kind exists but is not implemented yet.
    NotImplemented = 7,
    /// The structure cannot encode this complex (the message names the first offending simplex).
    UnsupportedComplex = 8,
    /// The query simplex is not a simplex of the complex.
    NotInComplex = 9,
    /// The query simplex is empty, repeats a vertex, has an out-of-range vertex or more than 16
    /// vertices.
    InvalidSimplex = 10,
    /// A dimension argument (p or q) is above the complex's dimension.
    DimensionOutOfRange = 11,
    /// The caller's buffer is too short; `*out_len` holds the needed number of elements
    /// (`uint32_t`, or `double` for coordinates).
    BufferTooSmall = 12,
    /// A size does not fit the index types.
    TooLarge = 13,
    /// An internal bug was caught at the boundary; the message has the panic text.
    Panic = 14,
    /// A handle names no simplex of this structure: index or dimension out of range, `NONE`,
    /// unknown form bits.
    InvalidHandle = 15,
    /// A handle of a simplex that an edit removed (editable structures only).
    StaleHandle = 16,
    /// A handle of the wrong kind for the call (an edge where a vertex is needed).
    WrongHandleKind = 17,
    /// A handle made by another structure (its owner stamp does not match).
    ForeignHandle = 18,
    // 19 is reserved: no status ever had it (the gap after the handle statuses 15–18), and
    // none will.
    /// Live complex: a topology-preserving contraction of two vertices that are not an edge.
    NotAnEdge = 20,
    /// Live complex: the link condition Lk(a) ∩ Lk(b) = Lk(ab) fails; the message names the
    /// dimension and a lowest-dimensional offending link simplex.
    LinkConditionFails = 21,
    /// Live complex: inserting a simplex that is already in the complex (top or face).
    SimplexAlreadyPresent = 22,
    /// Live complex: removing a simplex that is a proper face of another (message: a coface).
    NotATopSimplex = 23,
    /// Live complex: a vertex id out of range or of a removed (contracted, deleted) vertex.
    DeadVertex = 24,
    /// Live complex: an undo record from before `tpx_live_compact`, applied already, or whose
    /// contraction's result later edits changed (the message says which).
    StaleUndo = 25,
    // 26 is reserved: no status ever had it (the gap after the live-complex statuses 20–25),
    // and none will.
    /// `tpx_simplify*`: the ratio is not in (0, 1] (NaN included).
    InvalidRatio = 27,
    /// `tpx_simplify_file`: the file system refused to write the output file.
    WriteError = 28,
    /// `tpx_simplify*`: the complex cannot be simplified: no vertex coordinates, a non-finite
    /// coordinate, or more top simplices of one dimension than the live complex numbers.
    CannotSimplify = 29,
    /// The output format number is not one of `TPX_FORMAT_*`, or the output file's extension
    /// names no format.
    UnknownFormat = 30,
    /// The output format cannot hold the complex (a tetrahedron in OFF, an edge in STL); the
    /// message names the first offending simplex. Nothing was written.
    FormatCannotHold = 31,
    // 32–39 are reserved: no status ever had them (the gap after the simplification and
    // writer statuses 27–31), and none will.
    /// A saved file (`.tpx`) is corrupt: a checksum, offset or length is wrong (the message
    /// names the file and the first inconsistency).
    SavedFileCorrupt = 40,
    /// A saved file is shorter than its header says.
    SavedFileTruncated = 41,
    /// A saved file was written by another format version.
    SavedFileWrongVersion = 42,
    /// The file is not a saved file (wrong magic number).
    SavedFileForeign = 43,
    /// A saved file was written on a host of the other byte order.
    SavedFileWrongEndianness = 44,
    // 45–51 are reserved: no status ever had them (the gap after the saved-file statuses
    // 40–44), and none will.
    /// A handle from before `tpx_live_compact` (live complex): the compaction renumbered every
    /// id, so it names nothing any more; map the ids or locate again.
    StaleGeneration = 52,
    /// No longer returned: the live complex, which once numbered only its vertices densely, now
    /// numbers every dimension (until its next edit). Kept so that the number is never reused.
    NotDense = 53,
    /// No attribute of that name (at that location); the message names it.
    NoSuchAttribute = 54,
}

/// Incidence Graph.
pub const TPX_KIND_IG: u32 = 0;
/// Simplified Incidence Graph.
pub const TPX_KIND_SIG: u32 = 1;
/// Indexed data structure with Adjacencies.
pub const TPX_KIND_IA: u32 = 2;
/// Initial Quasi-Manifold structure.
pub const TPX_KIND_IQM: u32 = 3;
/// Non-Manifold Indexed data structure with Adjacencies.
pub const TPX_KIND_NMIA: u32 = 4;
/// Triangle-Segment structure.
pub const TPX_KIND_TS: u32 = 5;
/// Partial Entities (Partial Edge) structure.
pub const TPX_KIND_PE: u32 = 6;
/// Loop Edge-use structure.
pub const TPX_KIND_LE: u32 = 7;
/// Directed Edge structure.
pub const TPX_KIND_DE: u32 = 8;
/// The live complex (IA*-like). Works wherever a kind is taken: `tpx_structure_build` and
/// `tpx_structure_open` give it as an immutable `TpxStructure`; the editable one is a `TpxLive`
/// (`tpx_live_from_complex`, `tpx_live_open`), navigated through `tpx_live_structure`.
pub const TPX_KIND_IASTAR: u32 = 9;

/// A failure on its way to C: the status and the message for `tpx_last_error_message`.
pub(crate) struct Failure {
    status: TpxStatus,
    message: String,
}

impl Failure {
    pub(crate) fn new(status: TpxStatus, message: impl Into<String>) -> Self {
        Failure {
            status,
            message: message.into(),
        }
    }

    pub(crate) fn null(what: &str) -> Self {
        Failure::new(TpxStatus::NullArgument, format!("`{what}` is NULL"))
    }
}

thread_local! {
    /// `None` after a success: clearing must not allocate (`CString::default()` would).
    static LAST_ERROR: RefCell<Option<CString>> = const { RefCell::new(None) };
    /// Whether [`LAST_ERROR`] holds a message (counted in [`THREADS_WITH_ERROR`]).
    static ERROR_SET: Cell<bool> = const { Cell::new(false) };
}

/// How many threads have a message in [`LAST_ERROR`]. A success clears this thread's message
/// only when some thread has one: while none has, the call reads one shared word and makes no
/// thread-local access (in a shared library each is a call to `__tls_get_addr`) — what a walk
/// of one call per element pays on every call. Relaxed suffices: a thread only needs to see
/// its own increments.
static THREADS_WITH_ERROR: AtomicUsize = AtomicUsize::new(0);

fn set_last_error(message: &str) {
    // One bounded line with control characters escaped (NUL included, which CString refuses):
    // a 100 MB token in a file must not become a 100 MB message.
    let line = topoplex::error::one_line(message);
    let c = CString::new(line).unwrap_or_default();
    // `try_with`: during thread teardown the slot may be gone; the message is then dropped
    // rather than panicking outside the panic boundary.
    let _ = LAST_ERROR.try_with(|e| *e.borrow_mut() = Some(c));
    if !ERROR_SET.replace(true) {
        THREADS_WITH_ERROR.fetch_add(1, Ordering::Relaxed);
    }
}

#[inline]
fn clear_last_error() {
    if THREADS_WITH_ERROR.load(Ordering::Relaxed) != 0 && ERROR_SET.get() {
        let _ = LAST_ERROR.try_with(|e| e.borrow_mut().take());
        ERROR_SET.set(false);
        THREADS_WITH_ERROR.fetch_sub(1, Ordering::Relaxed);
    }
}

fn panic_text(payload: &(dyn std::any::Any + Send)) -> String {
    if let Some(s) = payload.downcast_ref::<&str>() {
        (*s).to_string()
    } else if let Some(s) = payload.downcast_ref::<String>() {
        s.clone()
    } else {
        "non-string panic payload".to_string()
    }
}

/// The panic boundary of every status-returning function: runs `body`, records its failure (or
/// clears the last error), and turns a panic into [`TpxStatus::Panic`].
pub(crate) fn guard(body: impl FnOnce() -> Result<(), Failure>) -> TpxStatus {
    match catch_unwind(AssertUnwindSafe(body)) {
        Ok(Ok(())) => {
            clear_last_error();
            TpxStatus::Ok
        }
        Ok(Err(f)) => {
            set_last_error(&f.message);
            f.status
        }
        Err(payload) => {
            set_last_error(&format!(
                "internal error (panic): {}",
                panic_text(payload.as_ref())
            ));
            TpxStatus::Panic
        }
    }
}

/// Runs `body` for a function that cannot report a status (getters returning pointers, `free`):
/// a panic yields `fallback`.
pub(crate) fn guard_value<T>(fallback: T, body: impl FnOnce() -> T) -> T {
    catch_unwind(AssertUnwindSafe(body)).unwrap_or(fallback)
}

/// The prelude of every function on a handle, written once: the panic boundary ([`guard`]) and
/// the NULL check of the handle `h` (named `what` in the message), then `body` on it.
pub(crate) fn on<H>(
    h: *const H,
    what: &str,
    body: impl FnOnce(&H) -> Result<(), Failure>,
) -> TpxStatus {
    guard(|| body(handle(h, what)?))
}

/// `Some(&mut *p)` for a non-NULL out-pointer. The caller guarantees that a non-NULL `p` is
/// valid for writes.
pub(crate) fn out_ptr<'a, T>(p: *mut T, what: &str) -> Result<&'a mut T, Failure> {
    // SAFETY: non-NULL pointers passed to the ABI are valid for writes (documented contract).
    unsafe { p.as_mut() }.ok_or_else(|| Failure::null(what))
}

/// The whole body of a getter that reads one value of a handle into `*out`: both pointers
/// NULL-checked (`what` names the handle argument), `*out` written only on success.
pub(crate) fn get_into<H, T>(
    h: *const H,
    what: &str,
    out: *mut T,
    get: impl FnOnce(&H) -> T,
) -> TpxStatus {
    on(h, what, |h| {
        *out_ptr(out, "out")? = get(h);
        Ok(())
    })
}

thread_local! {
    /// The answer of the current `tpx_relation` / `tpx_related` / `tpx_related_batch` /
    /// `tpx_degree_batch` call on this thread, kept between calls so that a walk over every
    /// simplex does not allocate an answer per call.
    pub(crate) static ANSWER: RefCell<Vec<u32>> = const { RefCell::new(Vec::new()) };
}

/// Runs `f` with this thread's kept buffer from `key` (a fresh one during thread teardown or
/// while it is in use).
pub(crate) fn with_kept<T: Default, R>(
    key: &'static std::thread::LocalKey<RefCell<T>>,
    f: impl FnOnce(&mut T) -> R,
) -> R {
    let mut f = Some(f);
    let kept = key.try_with(|cell| {
        let mut v = cell.try_borrow_mut().ok()?;
        Some((f.take().expect("called once"))(&mut v))
    });
    match kept {
        Ok(Some(r)) => r,
        _ => (f.take().expect("not called yet"))(&mut T::default()),
    }
}

/// Releases a kept buffer above 1 Mi items, so that one huge answer does not pin its memory for
/// the thread's lifetime.
pub(crate) fn trim_kept<T>(v: &mut Vec<T>) {
    const KEEP: usize = 1 << 20;
    if v.capacity() > KEEP {
        *v = Vec::new();
    }
}

/// Runs `f` on this thread's cleared answer buffer ([`ANSWER`]), trimmed afterwards.
pub(crate) fn with_answer<R>(f: impl FnOnce(&mut Vec<u32>) -> R) -> R {
    with_kept(&ANSWER, |v| {
        v.clear();
        let r = f(v);
        trim_kept(v);
        r
    })
}

/// The opaque handle types whose C owner holds a `Box` (rustls-ffi's `Castable<Ownership =
/// OwnershipBox>`): each is made by [`set_boxed`] and released by [`free_box`] in its
/// `tpx_*_free`, and no other type can be.
pub(crate) trait Boxed {}

impl Boxed for TpxComplex {}
impl Boxed for TpxStructure {}
impl Boxed for TpxRelationTable {}
impl Boxed for TpxLive {}
impl Boxed for TpxUndo {}
impl Boxed for TpxDecomposition {}

/// Puts `v` in `*out` as a new handle owned by the caller, to be released with its `tpx_*_free`
/// (rustls-ffi's `set_boxed_mut_ptr`). Called last, once nothing can fail, so that `*out` is
/// written only on success.
pub(crate) fn set_boxed<T: Boxed>(out: &mut *mut T, v: T) {
    *out = Box::into_raw(Box::new(v));
}

/// The whole body of a constructor from a handle: `input` (named `what`) and `out`
/// NULL-checked in that order, then `make` builds the new handle, put in `*out` on success only.
pub(crate) fn build_into<I, O: Boxed>(
    input: *const I,
    what: &str,
    out: *mut *mut O,
    make: impl FnOnce(&I) -> Result<O, Failure>,
) -> TpxStatus {
    on(input, what, |input| {
        let out = out_ptr(out, "out")?;
        set_boxed(out, make(input)?);
        Ok(())
    })
}

/// The whole body of a constructor from a file: `out` NULL-checked, then `path` read by
/// [`path_arg`], then `make` builds the new handle, put in `*out` on success only.
pub(crate) fn open_into<O: Boxed>(
    path: *const c_char,
    out: *mut *mut O,
    make: impl FnOnce(&std::path::Path) -> Result<O, Failure>,
) -> TpxStatus {
    guard(|| {
        let out = out_ptr(out, "out")?;
        let path = path_arg(path, "path")?;
        set_boxed(out, make(path)?);
        Ok(())
    })
}

/// A NUL-terminated UTF-8 path argument (named `what` in messages): NULL_ARGUMENT when NULL,
/// INVALID_ARGUMENT when not UTF-8.
pub(crate) fn path_arg<'a>(p: *const c_char, what: &str) -> Result<&'a std::path::Path, Failure> {
    if p.is_null() {
        return Err(Failure::null(what));
    }
    // SAFETY: a non-NULL path is NUL-terminated (documented contract of the callers).
    let s = unsafe { std::ffi::CStr::from_ptr(p) }
        .to_str()
        .map_err(|e| {
            Failure::new(
                TpxStatus::InvalidArgument,
                format!("{what} is not valid UTF-8: {e}"),
            )
        })?;
    Ok(std::path::Path::new(s))
}

/// The body of every `tpx_*_free`: releases a handle made by [`set_boxed`]. NULL is a no-op; a
/// panic while dropping does not cross the boundary.
///
/// # Safety
/// `p` must be NULL or a handle from [`set_boxed`], not used afterwards.
pub(crate) unsafe fn free_box<T: Boxed>(p: *mut T) {
    guard_value((), || {
        if !p.is_null() {
            // SAFETY: the handle came from Box::into_raw in `set_boxed` and is released once
            // (the caller's contract).
            drop(unsafe { Box::from_raw(p) });
        }
    })
}

/// Shared reference to a handle, or NULL_ARGUMENT.
pub(crate) fn handle<'a, T>(p: *const T, what: &str) -> Result<&'a T, Failure> {
    // SAFETY: non-NULL handles come from this library and are alive (documented contract).
    unsafe { p.as_ref() }.ok_or_else(|| Failure::null(what))
}

/// A copy of `data` whose allocation failure is `TooLarge`, not an abort of the host.
pub(crate) fn try_copy<T: Copy>(data: &[T], what: &str) -> Result<Vec<T>, Failure> {
    let mut v = Vec::new();
    v.try_reserve_exact(data.len()).map_err(|_| {
        Failure::new(
            TpxStatus::TooLarge,
            format!(
                "`{what}`: cannot allocate {} bytes",
                std::mem::size_of_val(data)
            ),
        )
    })?;
    v.extend_from_slice(data);
    Ok(v)
}

/// `p[0..len]` as a slice; `p` may be NULL only when `len == 0`.
pub(crate) fn in_slice<'a, T>(p: *const T, len: usize, what: &str) -> Result<&'a [T], Failure> {
    if len == 0 {
        return Ok(&[]);
    }
    if p.is_null() {
        return Err(Failure::null(what));
    }
    if len > isize::MAX as usize / std::mem::size_of::<T>().max(1) {
        return Err(Failure::new(
            TpxStatus::TooLarge,
            format!("`{what}`: {len} elements exceed the address space"),
        ));
    }
    // SAFETY: the caller guarantees `p` points to `len` readable elements; size checked above.
    Ok(unsafe { std::slice::from_raw_parts(p, len) })
}

/// Copies `data` to the caller's buffer: the shared tail of every "fill a buffer" function.
/// `*out_len` receives `data.len()` on success and on BUFFER_TOO_SMALL.
pub(crate) fn write_buffer<T: Copy>(
    data: &[T],
    buf: *mut T,
    buf_len: usize,
    out_len: &mut usize,
) -> Result<(), Failure> {
    let unit = c_type_name(std::any::type_name::<T>());
    check_room(buf, buf_len, data.len(), unit, out_len)?;
    if !data.is_empty() {
        // SAFETY: `buf` is valid for `buf_len >= data.len()` writes (documented contract) and
        // cannot overlap `data`, which this library owns.
        unsafe { std::ptr::copy_nonoverlapping(data.as_ptr(), buf, data.len()) };
    }
    *out_len = data.len();
    Ok(())
}

/// The checks before an answer of `need` items (`unit` in messages) is written to the caller's
/// `buf` of `buf_len`: NULL_ARGUMENT for a NULL buffer with a non-zero length, whatever the
/// answer's size (the header promises it: an empty answer must not hide the caller's bug),
/// then BUFFER_TOO_SMALL with `*out_len` = `need`.
pub(crate) fn check_room<T>(
    buf: *mut T,
    buf_len: usize,
    need: usize,
    unit: &str,
    out_len: &mut usize,
) -> Result<(), Failure> {
    if buf.is_null() && buf_len > 0 {
        return Err(Failure::null("buf"));
    }
    if need > buf_len {
        *out_len = need;
        return Err(Failure::new(
            TpxStatus::BufferTooSmall,
            format!("buffer holds {buf_len} {unit}, the answer needs {need}"),
        ));
    }
    Ok(())
}

/// The C spelling of the element types the buffers carry, for messages.
fn c_type_name(rust: &str) -> &str {
    match rust {
        "u32" => "uint32_t",
        "f64" => "double",
        other => other,
    }
}

/// The library version, e.g. `"0.1.0"`: a static NUL-terminated string, never freed.
#[unsafe(no_mangle)]
pub extern "C" fn tpx_version() -> *const c_char {
    concat!(env!("CARGO_PKG_VERSION"), "\0").as_ptr().cast()
}

/// The message of the most recent status-returning `tpx_*` call on this thread: `""` if it
/// succeeded. The string belongs to the library and stays valid until the next `tpx_*` call on
/// this thread; copy it to keep it. Never NULL.
#[unsafe(no_mangle)]
pub extern "C" fn tpx_last_error_message() -> *const c_char {
    static EMPTY: &[u8] = b"\0";
    guard_value(EMPTY.as_ptr().cast(), || {
        // The CString's heap buffer does not move when the thread-local is read; it is replaced
        // (and the old pointer dies) only by the next status-returning call on this thread.
        LAST_ERROR
            .try_with(|e| {
                e.borrow()
                    .as_ref()
                    .map_or(EMPTY.as_ptr().cast(), |c| c.as_ptr())
            })
            .unwrap_or(EMPTY.as_ptr().cast())
    })
}
