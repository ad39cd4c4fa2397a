//! `TpxStructure` (one of the family behind the relation API) and `TpxRelationTable`.

use super::{
    Failure, TpxStatus, build_into, free_box, get_into, guard, guard_value, in_slice, on, out_ptr,
    write_buffer,
};

use topoplex::complex::MAX_DIMENSION;
use topoplex::family::build;
use topoplex::relation::BuildError;
use topoplex::relation::{QueryError, StructureKind, Topology, normalize_simplex_into, sort_rows};

use super::complex::TpxComplex;

/// A built topological data structure (opaque). Create with `tpx_structure_build`, release with
/// `tpx_structure_free`. Immutable: every query takes a `const` pointer and may run from many
/// threads at once.
pub struct TpxStructure {
    pub(crate) topo: Box<dyn Topology>,
    /// Owner stamp carried by every `TpxSimplex` this structure makes.
    pub(crate) stamp: u32,
    /// Stamps this structure carried before (a live complex takes a new one at each
    /// compaction): their handles are refused as STALE_GENERATION, not FOREIGN_HANDLE.
    pub(crate) retired: Vec<u32>,
    /// The fast path of the one-handle queries, chosen by the structure's type.
    pub(crate) direct: super::direct::Direct,
}

impl TpxStructure {
    /// A structure with a fresh stamp.
    pub(crate) fn new(topo: Box<dyn Topology>) -> TpxStructure {
        TpxStructure {
            direct: super::direct::Direct::of(&*topo),
            topo,
            stamp: super::handles::new_stamp(),
            retired: Vec::new(),
        }
    }
}

/// Storage of a structure: what the papers count and what the process really holds.
#[repr(C)]
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct TpxStorage {
    /// Integers (references) the papers count for the topological relations.
    pub integers: u64,
    /// Bits the papers count (flags).
    pub bits: u64,
    /// Heap bytes of every array the structure owns.
    pub bytes: u64,
}

/// R_{p,q} of every p-simplex, in CSR form (opaque). Row i belongs to the i-th p-simplex in
/// `tpx_structure_simplices` order. Release with `tpx_relation_table_free`.
pub struct TpxRelationTable {
    offsets: Vec<usize>,
    ids: Vec<u32>,
}

pub(crate) fn kind_from_u32(kind: u32) -> Result<StructureKind, Failure> {
    StructureKind::from_abi(kind).ok_or_else(|| {
        Failure::new(
            TpxStatus::UnknownKind,
            format!("unknown structure kind {kind} (expected 0..=9, TPX_KIND_*)"),
        )
    })
}

pub(crate) fn build_failure(e: BuildError) -> Failure {
    let status = match &e {
        BuildError::NotImplemented { .. } => TpxStatus::NotImplemented,
        BuildError::Unsupported { .. } => TpxStatus::UnsupportedComplex,
        BuildError::TooLarge { .. } => TpxStatus::TooLarge,
    };
    Failure::new(status, e.to_string())
}

pub(crate) fn query_failure(e: QueryError) -> Failure {
    let status = match &e {
        QueryError::NotInComplex { .. } => TpxStatus::NotInComplex,
        QueryError::DimensionOutOfRange { .. } => TpxStatus::DimensionOutOfRange,
        QueryError::EmptySimplex
        | QueryError::TooManyVertices { .. }
        | QueryError::RepeatedVertex { .. }
        | QueryError::VertexOutOfRange { .. } => TpxStatus::InvalidSimplex,
        QueryError::InvalidHandle { .. } => TpxStatus::InvalidHandle,
        QueryError::StaleHandle { .. } => TpxStatus::StaleHandle,
        QueryError::WrongHandleKind { .. } => TpxStatus::WrongHandleKind,
        QueryError::StaleGeneration { .. } => TpxStatus::StaleGeneration,
        QueryError::TooLarge { .. } => TpxStatus::TooLarge,
    };
    Failure::new(status, e.to_string())
}

/// `p` as a dimension of the structure's complex, or DIMENSION_OUT_OF_RANGE naming `what`.
fn dimension_arg(topo: &dyn Topology, p: u32, what: &str) -> Result<usize, Failure> {
    let d = topo.dimension();
    if p as usize > d {
        return Err(Failure::new(
            TpxStatus::DimensionOutOfRange,
            format!("{what} = {p} is above the complex's dimension {d}"),
        ));
    }
    Ok(p as usize)
}

/// Builds a structure of `kind` (`TPX_KIND_*`) for the complex `c`.
///
/// `TPX_KIND_IASTAR` builds the live complex's structure (the same as `tpx_live_from_complex`
/// makes, behind `tpx_live_structure`), answering every function that takes a structure; a
/// `TpxStructure` is never edited, so to edit, build a `TpxLive` instead.
///
/// On success `*out` receives a new structure owned by the caller (free with
/// `tpx_structure_free`); it does not borrow `c`, which may be freed first.
/// Errors: NULL_ARGUMENT, UNKNOWN_KIND, NOT_IMPLEMENTED, UNSUPPORTED_COMPLEX (message names the
/// first simplex the structure cannot encode), TOO_LARGE. Cost: the structure's build cost
/// (see its module documentation; near-linear in the size of the closure for most kinds).
///
/// # Safety
/// Non-NULL pointers must be valid (a live complex; a writable handle pointer).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tpx_structure_build(
    c: *const TpxComplex,
    kind: u32,
    out: *mut *mut TpxStructure,
) -> TpxStatus {
    build_into(c, "c", out, |c| {
        let kind = kind_from_u32(kind)?;
        let topo = build(kind, &c.complex).map_err(build_failure)?;
        Ok(TpxStructure::new(topo))
    })
}

/// The kind (`TPX_KIND_*`) named `name` into `*out`: the names the `topoplex` CLI's
/// `--structure` takes (`ig`, `sig`, `ia`, `iqm`, `nmia`, `ts`, `pe`, `le`, `de`, `iastar`),
/// ASCII case ignored — the library's one name map, so that a client need not write its own.
/// Errors: NULL_ARGUMENT, INVALID_ARGUMENT (not UTF-8), UNKNOWN_KIND (no kind has this name;
/// the message echoes it, capped and escaped); `*out` is written only on success. O(length of
/// `name`); no allocation on success.
///
/// # Safety
/// Non-NULL pointers must be valid; `name` must be NUL-terminated.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tpx_kind_from_name(
    name: *const std::ffi::c_char,
    out: *mut u32,
) -> TpxStatus {
    guard(|| {
        let out = out_ptr(out, "out")?;
        if name.is_null() {
            return Err(super::Failure::null("name"));
        }
        // SAFETY: a non-NULL `name` is NUL-terminated (documented contract).
        let bytes = unsafe { std::ffi::CStr::from_ptr(name) }.to_bytes();
        let text = std::str::from_utf8(bytes).map_err(|e| {
            Failure::new(
                TpxStatus::InvalidArgument,
                format!("structure name is not valid UTF-8: {e}"),
            )
        })?;
        let kind = StructureKind::from_name(text).ok_or_else(|| {
            let names: Vec<&str> = StructureKind::NAMED.iter().map(|k| k.name()).collect();
            Failure::new(
                TpxStatus::UnknownKind,
                format!(
                    "unknown structure name `{}` (expected one of {})",
                    topoplex::error::echo(bytes),
                    names.join(", ")
                ),
            )
        })?;
        *out = kind.abi();
        Ok(())
    })
}

/// The name of kind `kind` (`TPX_KIND_*`) into `*out`: the static NUL-terminated string the
/// CLI's `--structure` takes (`"ig"` .. `"iastar"`; never freed, valid for the process), the
/// inverse of `tpx_kind_from_name`. Errors: NULL_ARGUMENT, UNKNOWN_KIND; `*out` written only on
/// success. O(1), no allocation.
///
/// # Safety
/// Non-NULL pointers must be valid.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tpx_kind_name(kind: u32, out: *mut *const std::ffi::c_char) -> TpxStatus {
    const NAMES: [&std::ffi::CStr; 10] = [
        c"ig", c"sig", c"ia", c"iqm", c"nmia", c"ts", c"pe", c"le", c"de", c"iastar",
    ];
    guard(|| {
        let out = out_ptr(out, "out")?;
        let k = kind_from_u32(kind)?;
        let name = NAMES[k.abi() as usize];
        debug_assert_eq!(name.to_str(), Ok(k.name()));
        *out = name.as_ptr();
        Ok(())
    })
}

/// Releases a structure. NULL is a no-op.
///
/// # Safety
/// `s` must be NULL or a live handle from this library, not used afterwards (and not being
/// queried by another thread).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tpx_structure_free(s: *mut TpxStructure) {
    // SAFETY: the same contract, passed on.
    unsafe { free_box(s) }
}

/// The structure's kind (`TPX_KIND_*`) into `*out`. O(1).
///
/// # Safety
/// Non-NULL pointers must be valid.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tpx_structure_kind(s: *const TpxStructure, out: *mut u32) -> TpxStatus {
    on(s, "s", |s| {
        let out = out_ptr(out, "out")?;
        let kind = s.topo.kind();
        *out = kind.abi();
        Ok(())
    })
}

/// Dimension d of the encoded complex into `*out`. O(1).
///
/// # Safety
/// Non-NULL pointers must be valid.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tpx_structure_dimension(
    s: *const TpxStructure,
    out: *mut u32,
) -> TpxStatus {
    get_into(s, "s", out, |s| s.topo.dimension() as u32)
}

/// Number n_p of p-simplices into `*out`; 0 for p > d. Cost: the structure's (O(1) for
/// incidence-based kinds).
///
/// # Safety
/// Non-NULL pointers must be valid.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tpx_structure_count(
    s: *const TpxStructure,
    p: u32,
    out: *mut usize,
) -> TpxStatus {
    get_into(s, "s", out, |s| s.topo.count(p as usize))
}

/// Number of top p-simplices into `*out`; 0 for p > d.
///
/// # Safety
/// Non-NULL pointers must be valid.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tpx_structure_top_count(
    s: *const TpxStructure,
    p: u32,
    out: *mut usize,
) -> TpxStatus {
    get_into(s, "s", out, |s| s.topo.top_count(p as usize))
}

/// Storage of the structure into `*out`.
///
/// # Safety
/// Non-NULL pointers must be valid.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tpx_structure_storage(
    s: *const TpxStructure,
    out: *mut TpxStorage,
) -> TpxStatus {
    on(s, "s", |s| {
        let out = out_ptr(out, "out")?;
        let st = s.topo.storage();
        *out = TpxStorage {
            integers: st.integers,
            bits: st.bits,
            bytes: st.bytes,
        };
        Ok(())
    })
}

/// Every p-simplex, as rows of p+1 ascending vertex ids in ascending lexicographic order,
/// copied into `buf` (the caller's, `buf_len` uint32_t); `*out_len` receives the number of
/// uint32_t written, `(p+1) * n_p`.
///
/// Errors: NULL_ARGUMENT (`buf` may be NULL only when `buf_len == 0`), DIMENSION_OUT_OF_RANGE
/// (p > d), BUFFER_TOO_SMALL (nothing copied; `*out_len` = needed length). Cost: the
/// structure's enumeration, O((p+1) n_p) or O((p+1) n_p log n_p), each call.
///
/// # Safety
/// Non-NULL pointers must be valid; `buf` must have room for `buf_len` uint32_t.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tpx_structure_simplices(
    s: *const TpxStructure,
    p: u32,
    buf: *mut u32,
    buf_len: usize,
    out_len: *mut usize,
) -> TpxStatus {
    on(s, "s", |s| {
        let out_len = out_ptr(out_len, "out_len")?;
        let p = dimension_arg(s.topo.as_ref(), p, "p")?;
        let mut rows = Vec::new();
        s.topo.simplices(p, &mut rows);
        write_buffer(&rows, buf, buf_len, out_len)
    })
}

/// R_{p,q}(sigma) for sigma = `simplex[0 .. simplex_len]` (vertex ids in any order, p = simplex_len-1):
/// rows of q+1 ascending vertex ids, in ascending lexicographic order, copied into `buf`;
/// `*out_len` receives the number of uint32_t written (a multiple of q+1, possibly 0).
///
/// R_{p,q} is the q-faces of sigma for q < p, the q-simplices having sigma as a face for q > p, the
/// other p-simplices sharing a (p-1)-face for q == p > 0, and the vertices sharing an edge for
/// q == p == 0.
///
/// Errors: NULL_ARGUMENT (`buf` may be NULL when `buf_len == 0`), INVALID_SIMPLEX (empty,
/// repeated or out-of-range ids, more than 16 ids), DIMENSION_OUT_OF_RANGE (q > d),
/// NOT_IN_COMPLEX, BUFFER_TOO_SMALL (nothing copied; `*out_len` = needed length, so a call with
/// `buf_len == 0` asks for the size). Cost: the structure's query cost plus O(k log k) to sort
/// the k answers (O(k) when the structure already gives them in order); the answer is
/// recomputed on each call. Apart from the structure's own query, a call allocates nothing
/// once a thread has answered a query as large: the answer is assembled in a per-thread buffer
/// that is kept between calls.
///
/// # Safety
/// Non-NULL pointers must be valid; `simplex` must hold `simplex_len` ids and `buf` must have
/// room for `buf_len` uint32_t.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tpx_relation(
    s: *const TpxStructure,
    simplex: *const u32,
    simplex_len: usize,
    q: u32,
    buf: *mut u32,
    buf_len: usize,
    out_len: *mut usize,
) -> TpxStatus {
    on(s, "s", |s| {
        let out_len = out_ptr(out_len, "out_len")?;
        let sigma = in_slice(simplex, simplex_len, "simplex")?;
        let topo = s.topo.as_ref();
        let mut sorted = [0u32; MAX_DIMENSION + 1];
        let sorted = normalize_simplex_into(sigma, topo.vertex_count(), &mut sorted)
            .map_err(query_failure)?;
        let q = q as usize;
        if q > topo.dimension() {
            return Err(query_failure(QueryError::DimensionOutOfRange {
                p: sorted.len() - 1,
                q,
                dim: topo.dimension(),
            }));
        }
        super::with_answer(|rows| {
            topo.query(sorted, q, rows).map_err(query_failure)?;
            sort_rows_in_place(rows, q + 1);
            write_buffer(rows, buf, buf_len, out_len)
        })
    })
}

/// Sorts distinct rows of `arity` ids into ascending lexicographic order in place: a linear
/// check first (many structures answer in order already), then for rows of 2 to 4 ids a sort of
/// packed integer keys (one comparison per pair instead of a lexicographic loop: this sort was
/// a quarter of a vertex-star query), on the stack for the usual small answers.
pub(crate) fn sort_rows_in_place(rows: &mut Vec<u32>, arity: usize) {
    /// Rows per answer sorted through keys on the stack; longer answers sort the rows directly.
    const STACK_ROWS: usize = 64;
    fn sort_fixed<const N: usize>(rows: &mut [u32]) {
        let (chunks, rest) = rows.as_chunks_mut::<N>();
        debug_assert!(rest.is_empty());
        if chunks.is_sorted() {
            return;
        }
        if N == 1 || chunks.len() > STACK_ROWS {
            chunks.sort_unstable();
            return;
        }
        // Big-endian packing: the integer order of the keys is the lexicographic order.
        let mut keys = [0u128; STACK_ROWS];
        let keys = &mut keys[..chunks.len()];
        for (k, row) in keys.iter_mut().zip(chunks.iter()) {
            *k = row.iter().fold(0u128, |acc, &v| (acc << 32) | v as u128);
        }
        if keys.len() <= 16 {
            // A plain insertion sort: the typical answer (a triangle's 3 neighbours, a vertex's
            // 6 to 20 cofaces) is too short for the general sort's set-up to pay off.
            for i in 1..keys.len() {
                let k = keys[i];
                let mut j = i;
                while j > 0 && keys[j - 1] > k {
                    keys[j] = keys[j - 1];
                    j -= 1;
                }
                keys[j] = k;
            }
        } else {
            keys.sort_unstable();
        }
        for (k, row) in keys.iter().zip(chunks.iter_mut()) {
            for (i, v) in row.iter_mut().enumerate() {
                *v = (k >> (32 * (N - 1 - i))) as u32;
            }
        }
    }
    match arity {
        1 => sort_fixed::<1>(rows),
        2 => sort_fixed::<2>(rows),
        3 => sort_fixed::<3>(rows),
        4 => sort_fixed::<4>(rows),
        _ => {
            if !rows.chunks_exact(arity).is_sorted() {
                sort_rows(rows, arity);
            }
        }
    }
}

/// R_{p,q} of every p-simplex at once, as a new table owned by the caller (free with
/// `tpx_relation_table_free`). Row i belongs to the i-th p-simplex in `tpx_structure_simplices`
/// order and lists rows of q+1 ascending ids in ascending lexicographic order (as
/// `tpx_relation`).
///
/// Errors: NULL_ARGUMENT, DIMENSION_OUT_OF_RANGE (p > d or q > d). Cost: n_p queries plus the
/// sorting of each answer; memory O(n_p + total answer size).
///
/// # Safety
/// Non-NULL pointers must be valid.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tpx_relation_table(
    s: *const TpxStructure,
    p: u32,
    q: u32,
    out: *mut *mut TpxRelationTable,
) -> TpxStatus {
    build_into(s, "s", out, |s| {
        let topo = s.topo.as_ref();
        let p = dimension_arg(topo, p, "p")?;
        let q = dimension_arg(topo, q, "q")?;
        let mut simplices = Vec::new();
        topo.simplices(p, &mut simplices);
        let mut offsets = Vec::with_capacity(simplices.len() / (p + 1) + 1);
        offsets.push(0);
        let mut ids = Vec::new();
        let mut rows = Vec::new();
        for sigma in simplices.chunks_exact(p + 1) {
            rows.clear();
            // `simplices` lists valid, ascending simplices of the complex, as `query` expects.
            topo.query(sigma, q, &mut rows).map_err(query_failure)?;
            sort_rows_in_place(&mut rows, q + 1);
            ids.extend_from_slice(&rows);
            offsets.push(ids.len());
        }
        Ok(TpxRelationTable { offsets, ids })
    })
}

/// The row offsets of a relation table: `*len` receives n_p + 1; row i is
/// `ids[offsets[i] .. offsets[i+1]]` of `tpx_relation_table_ids`. The array belongs to the
/// table and lives as long as it. Returns NULL (and leaves `*len` alone) if `t` or `len` is
/// NULL. O(1).
///
/// # Safety
/// Non-NULL pointers must be valid.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tpx_relation_table_offsets(
    t: *const TpxRelationTable,
    len: *mut usize,
) -> *const usize {
    table_array(t, len, |t| &t.offsets)
}

/// The concatenated rows of a relation table (rows of q+1 ids): `*len` receives the number of
/// uint32_t. The array belongs to the table and lives as long as it; when `*len` is 0 the
/// pointer is non-NULL but must not be read. Returns NULL (and leaves `*len` alone) if `t` or
/// `len` is NULL. O(1).
///
/// # Safety
/// Non-NULL pointers must be valid.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tpx_relation_table_ids(
    t: *const TpxRelationTable,
    len: *mut usize,
) -> *const u32 {
    table_array(t, len, |t| &t.ids)
}

/// The one body of `tpx_relation_table_offsets` and `tpx_relation_table_ids`: the array `get`
/// picks, its length into `*len`; NULL (and `*len` left alone) if `t` or `len` is NULL.
fn table_array<T>(
    t: *const TpxRelationTable,
    len: *mut usize,
    get: impl FnOnce(&TpxRelationTable) -> &[T],
) -> *const T {
    guard_value(std::ptr::null(), || {
        // SAFETY: non-NULL pointers are valid (documented contract).
        match unsafe { (t.as_ref(), len.as_mut()) } {
            (Some(t), Some(len)) => {
                let a = get(t);
                *len = a.len();
                a.as_ptr()
            }
            _ => std::ptr::null(),
        }
    })
}

/// Releases a relation table. NULL is a no-op.
///
/// # Safety
/// `t` must be NULL or a live handle from this library, not used afterwards.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tpx_relation_table_free(t: *mut TpxRelationTable) {
    // SAFETY: the same contract, passed on.
    unsafe { free_box(t) }
}
