//! `TpxComplex`: a normalised complex (its top simplices), input to every structure.

use std::ffi::c_char;

use super::{
    Failure, TpxStatus, free_box, get_into, guard, handle, in_slice, on, open_into, out_ptr,
    set_boxed, try_copy, write_buffer,
};
use topoplex::complex::{Budget, Complex, ComplexError};
use topoplex::io::{Coords, ReadErrorKind};

/// A normalised simplicial complex (opaque). Create with `tpx_complex_from_arrays` or
/// `tpx_complex_from_file`, release with `tpx_complex_free`. Immutable once built.
pub struct TpxComplex {
    pub(crate) complex: Complex,
}

pub(crate) fn complex_failure(e: ComplexError) -> Failure {
    let status = match &e {
        ComplexError::Read(r) => match r.kind {
            ReadErrorKind::Io(_) => TpxStatus::IoError,
            ReadErrorKind::TooLarge(_) => TpxStatus::TooLarge,
            _ => TpxStatus::ParseError,
        },
        ComplexError::TooLarge { .. } | ComplexError::OutOfMemory { .. } => TpxStatus::TooLarge,
        _ => TpxStatus::InvalidComplex,
    };
    Failure::new(status, e.to_string())
}

/// The status of an input that could not be opened (a mesh file or a `.tpx`).
pub(crate) fn open_failure(e: topoplex::store::OpenError) -> Failure {
    match e {
        topoplex::store::OpenError::Read(e) => complex_failure(e),
        topoplex::store::OpenError::Saved(e) => super::store::store_failure(e),
        topoplex::store::OpenError::Build(e) => super::structure::build_failure(e),
    }
}

/// Builds a complex from simplices given as arrays: simplex `i` is
/// `ids[offsets[i] .. offsets[i+1]]` (vertex ids in any order), so `offsets` has
/// `n_simplices + 1` non-decreasing entries. The complex is the closure of these simplices over
/// the vertices `0 .. n_vertices` (unused ids are isolated vertices; duplicates and faces of
/// other listed simplices are absorbed). `ids` and `offsets` may be NULL when `n_simplices == 0`.
///
/// `coords` may be NULL (no coordinates; `coord_dim` ignored); otherwise it holds
/// `n_vertices * coord_dim` doubles, vertex-major, and is copied.
///
/// On success `*out` receives a new complex owned by the caller (free with `tpx_complex_free`).
/// Errors: NULL_ARGUMENT, INVALID_ARGUMENT (offsets decreasing, `coord_dim == 0` with coords),
/// INVALID_COMPLEX (message names the offending simplex by its input position), TOO_LARGE
/// (sizes that overflow, a closure above the default budget — see
/// `tpx_complex_from_arrays_budget` — or memory that cannot be allocated: never an abort).
/// Cost: O(n log n in the total input size n) for sorting and absorbing faces; memory of the top simplices.
///
/// # Safety
/// Non-NULL pointers must point to arrays of the stated lengths.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tpx_complex_from_arrays(
    n_vertices: u32,
    ids: *const u32,
    offsets: *const usize,
    n_simplices: usize,
    coords: *const f64,
    coord_dim: usize,
    out: *mut *mut TpxComplex,
) -> TpxStatus {
    // SAFETY: the same contract, passed on.
    unsafe {
        tpx_complex_from_arrays_budget(
            n_vertices,
            ids,
            offsets,
            n_simplices,
            coords,
            coord_dim,
            0,
            out,
        )
    }
}

/// The budget `max_simplices` stands for: 0 the default rule, anything else a fixed limit
/// (`UINT64_MAX`: unlimited).
fn budget(max_simplices: u64) -> Budget {
    Budget {
        max_simplices: (max_simplices != 0).then_some(max_simplices),
    }
}

/// `tpx_complex_from_arrays` with an explicit closure budget: the complex's closure may have at
/// most `max_simplices` simplices (by its upper bound n + Σ over top p-simplices of
/// 2^{p+1} − p − 2, or by an exact count when that bound is within 16 times the limit); 0 keeps the default, max(2^20, 64 × (ids + vertices given with
/// coordinates)); `UINT64_MAX` removes the limit. Above it: TOO_LARGE, nothing allocated of
/// closure size. Same arguments, ownership, errors and cost otherwise.
///
/// # Safety
/// Non-NULL pointers must point to arrays of the stated lengths.
#[unsafe(no_mangle)]
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn tpx_complex_from_arrays_budget(
    n_vertices: u32,
    ids: *const u32,
    offsets: *const usize,
    n_simplices: usize,
    coords: *const f64,
    coord_dim: usize,
    max_simplices: u64,
    out: *mut *mut TpxComplex,
) -> TpxStatus {
    guard(|| {
        let out = out_ptr(out, "out")?;
        let offsets: &[usize] = if n_simplices == 0 && offsets.is_null() {
            &[0]
        } else {
            let n = n_simplices.checked_add(1).ok_or_else(|| {
                Failure::new(TpxStatus::TooLarge, "n_simplices + 1 overflows size_t")
            })?;
            in_slice(offsets, n, "offsets")?
        };
        if let Some(i) = (1..offsets.len()).find(|&i| offsets[i] < offsets[i - 1]) {
            return Err(Failure::new(
                TpxStatus::InvalidArgument,
                format!(
                    "offsets decrease at simplex #{}: offsets[{}] = {} < offsets[{}] = {}",
                    i - 1,
                    i,
                    offsets[i],
                    i - 1,
                    offsets[i - 1]
                ),
            ));
        }
        let ids = in_slice(ids, offsets[offsets.len() - 1], "ids")?;
        let coords = if coords.is_null() {
            None
        } else {
            if coord_dim == 0 {
                return Err(Failure::new(
                    TpxStatus::InvalidArgument,
                    "coordinates given with coord_dim == 0",
                ));
            }
            let len = (n_vertices as usize)
                .checked_mul(coord_dim)
                .ok_or_else(|| {
                    Failure::new(
                        TpxStatus::TooLarge,
                        "n_vertices * coord_dim overflows size_t",
                    )
                })?;
            Some(Coords {
                dim: coord_dim,
                data: try_copy(in_slice(coords, len, "coords")?, "coords")?,
            })
        };
        let complex =
            Complex::from_arrays_with(n_vertices, ids, offsets, coords, budget(max_simplices))
                .map_err(complex_failure)?;
        set_boxed(out, TpxComplex { complex });
        Ok(())
    })
}

/// Reads a complex from a file, the format chosen by extension: `.off`, `.obj`, `.mesh`,
/// `.simplices`, `.ply`, `.stl`, `.vtk`, `.vtu`, `.msh`, or a saved `.tpx` (its complex, rebuilt
/// from the saved listing; the saved file's statuses `SAVED_FILE_*`) — the same door as the CLI
/// (`path` is a NUL-terminated UTF-8 path).
///
/// On success `*out` receives a new complex owned by the caller (free with `tpx_complex_free`).
/// Errors: NULL_ARGUMENT, INVALID_ARGUMENT (path not UTF-8), IO_ERROR (cannot read),
/// PARSE_ERROR (syntax or unknown extension; message `file:line: what`), INVALID_COMPLEX
/// (message `file:line: simplex [..] ...`), TOO_LARGE (closure above the default budget, see
/// `tpx_complex_from_file_budget`; memory that cannot be allocated). Cost: linear in the file
/// plus normalisation.
///
/// # Safety
/// `path`, if non-NULL, must be a NUL-terminated string.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tpx_complex_from_file(
    path: *const c_char,
    out: *mut *mut TpxComplex,
) -> TpxStatus {
    // SAFETY: the same contract, passed on.
    unsafe { tpx_complex_from_file_budget(path, 0, out) }
}

/// `tpx_complex_from_file` with an explicit closure budget `max_simplices` (0: the default,
/// max(2^20, 64 × (listed ids + declared vertices)); `UINT64_MAX`: unlimited; see
/// `tpx_complex_from_arrays_budget`). Same ownership, errors and cost otherwise.
///
/// # Safety
/// `path`, if non-NULL, must be a NUL-terminated string.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tpx_complex_from_file_budget(
    path: *const c_char,
    max_simplices: u64,
    out: *mut *mut TpxComplex,
) -> TpxStatus {
    open_into(path, out, |path| {
        let complex =
            topoplex::store::open_complex(path, budget(max_simplices)).map_err(open_failure)?;
        Ok(TpxComplex { complex })
    })
}

/// `tpx_complex_from_file_flags`' flag: fan every convex planar polygon of a mesh file into
/// triangles (the CLI's `--triangulate`).
pub const TPX_READ_TRIANGULATE: u32 = 1;

/// `tpx_complex_from_file_budget` with read `flags`, 0 or `TPX_READ_TRIANGULATE`: faces of more
/// than 3 vertices in OFF, OBJ and PLY, polygon and quad cells in legacy VTK and Gmsh quadrangles
/// are fanned into
/// triangles from their first vertex, each keeping the polygon's winding, line and listed
/// attributes; a polygon that is not planar (beyond 1e-6 × its size), not convex, degenerate,
/// repeats a vertex or has no coordinates is PARSE_ERROR naming file, line, polygon and why.
/// Other formats and saved (`.tpx`) files read as without the flag.
///
/// On success `*out` receives a new complex owned by the caller (free with `tpx_complex_free`).
/// Errors: as `tpx_complex_from_file_budget`, plus INVALID_ARGUMENT for an unknown flag
/// (nothing read). Cost: as it, plus O(k) for each polygon of k vertices and a copy of the
/// listing when there are polygons.
///
/// # Safety
/// `path`, if non-NULL, must be a NUL-terminated string; `out` must be valid for writes.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tpx_complex_from_file_flags(
    path: *const c_char,
    max_simplices: u64,
    flags: u32,
    out: *mut *mut TpxComplex,
) -> TpxStatus {
    open_into(path, out, |path| {
        if flags & !TPX_READ_TRIANGULATE != 0 {
            return Err(Failure::new(
                TpxStatus::InvalidArgument,
                format!("unknown flags {flags:#x} (only TPX_READ_TRIANGULATE = 1)"),
            ));
        }
        let budget = budget(max_simplices);
        let complex = if flags & TPX_READ_TRIANGULATE != 0 && !topoplex::store::is_saved_path(path)
        {
            let options = topoplex::io::ReadOptions { triangulate: true };
            Complex::from_path_options(path, budget, options).map_err(complex_failure)?
        } else {
            topoplex::store::open_complex(path, budget).map_err(open_failure)?
        };
        Ok(TpxComplex { complex })
    })
}

/// Releases a complex. NULL is a no-op. Structures built from it stay valid (they own their
/// data).
///
/// # Safety
/// `complex` must be NULL or a live handle from this library, not used afterwards.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tpx_complex_free(complex: *mut TpxComplex) {
    // SAFETY: the same contract, passed on.
    unsafe { free_box(complex) }
}

/// What normalising the input absorbed (`TpxComplex`'s input statistics).
#[repr(C)]
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct TpxInputStats {
    /// Simplices as given, absorbed ones included.
    pub input_simplices: usize,
    /// Extra listings of a simplex listed more than once.
    pub absorbed_duplicates: usize,
    /// Listed simplices that are a proper face of another listed simplex.
    pub absorbed_faces: usize,
}

/// What normalisation absorbed (duplicates and faces of other listed simplices, which are not
/// errors) into `*out`. O(1).
///
/// # Safety
/// Non-NULL pointers must be valid (a live handle; a writable `TpxInputStats`).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tpx_complex_input_stats(
    c: *const TpxComplex,
    out: *mut TpxInputStats,
) -> TpxStatus {
    get_into(c, "c", out, |c| {
        let s = c.complex.stats();
        TpxInputStats {
            input_simplices: s.input_simplices,
            absorbed_duplicates: s.absorbed_duplicates,
            absorbed_faces: s.absorbed_faces,
        }
    })
}

/// Dimension d of the complex (highest dimension of a simplex) into `*out`. O(1).
///
/// # Safety
/// Non-NULL pointers must be valid (a live handle; a writable `uint32_t`).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tpx_complex_dimension(c: *const TpxComplex, out: *mut u32) -> TpxStatus {
    get_into(c, "c", out, |c| c.complex.dimension() as u32)
}

/// Number of vertices n into `*out` (vertex ids are `0 .. n`). O(1).
///
/// # Safety
/// Non-NULL pointers must be valid (a live handle; a writable `uint32_t`).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tpx_complex_vertex_count(
    c: *const TpxComplex,
    out: *mut u32,
) -> TpxStatus {
    get_into(c, "c", out, |c| c.complex.vertex_count())
}

/// Number of top p-simplices (not a face of another simplex) into `*out`; 0 for p > d. O(1).
///
/// # Safety
/// Non-NULL pointers must be valid (a live handle; a writable `size_t`).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tpx_complex_top_count(
    c: *const TpxComplex,
    p: u32,
    out: *mut usize,
) -> TpxStatus {
    get_into(c, "c", out, |c| c.complex.tops(p as usize).len())
}

/// Number of coordinates per vertex into `*out`: 0 when the complex has no coordinates (built
/// from arrays without them, or read from a `.simplices` file without `v` lines). O(1).
///
/// # Safety
/// Non-NULL pointers must be valid (a live handle; a writable `size_t`).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tpx_complex_coord_dim(c: *const TpxComplex, out: *mut usize) -> TpxStatus {
    get_into(c, "c", out, |c| c.complex.coords().map_or(0, |x| x.dim))
}

/// The vertex coordinates, vertex-major (`coord_dim` doubles per vertex, vertex ids `0 .. n`),
/// copied into `buf` (the caller's, `buf_len` doubles); `*out_len` receives the number of
/// doubles written, `n * coord_dim` (0 without coordinates).
///
/// Errors: NULL_ARGUMENT (`buf` may be NULL only when `buf_len == 0`), BUFFER_TOO_SMALL
/// (nothing copied; `*out_len` = needed number of doubles, so a call with `buf_len == 0` asks
/// for the size). Cost: one copy, O(n * coord_dim).
///
/// # Safety
/// Non-NULL pointers must be valid; `buf` must have room for `buf_len` doubles.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tpx_complex_coords(
    c: *const TpxComplex,
    buf: *mut f64,
    buf_len: usize,
    out_len: *mut usize,
) -> TpxStatus {
    on(c, "c", |c| {
        let out_len = out_ptr(out_len, "out_len")?;
        let data = c.complex.coords().map_or(&[][..], |x| &x.data[..]);
        write_buffer(data, buf, buf_len, out_len)
    })
}

/// The top p-simplices (those that are not a face of another simplex) as rows of p+1 ascending
/// vertex ids in ascending lexicographic order, copied into `buf` (the caller's, `buf_len`
/// uint32_t); `*out_len` receives the number of uint32_t written, `(p+1) *`
/// `tpx_complex_top_count(c, p)`. Together with `tpx_complex_vertex_count` this is the whole
/// complex: its closure is every simplex.
///
/// Errors: NULL_ARGUMENT (`buf` may be NULL only when `buf_len == 0`), DIMENSION_OUT_OF_RANGE
/// (p > d), BUFFER_TOO_SMALL (nothing copied; `*out_len` = needed length). Cost: one copy,
/// O((p+1) * number of top p-simplices).
///
/// # Safety
/// Non-NULL pointers must be valid; `buf` must have room for `buf_len` uint32_t.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tpx_complex_top_simplices(
    c: *const TpxComplex,
    p: u32,
    buf: *mut u32,
    buf_len: usize,
    out_len: *mut usize,
) -> TpxStatus {
    on(c, "c", |c| {
        let out_len = out_ptr(out_len, "out_len")?;
        let d = c.complex.dimension();
        if p as usize > d {
            return Err(Failure::new(
                TpxStatus::DimensionOutOfRange,
                format!("p = {p} is above the complex's dimension {d}"),
            ));
        }
        write_buffer(c.complex.tops(p as usize).as_flat(), buf, buf_len, out_len)
    })
}

/// Replaces the vertex coordinates of `c` by `data[0 .. len]`: `dim` doubles per vertex, vertex
/// after vertex (`len` = vertex count × `dim`, `dim` ≥ 1; a complex without coordinates gains
/// them), so that an application moves its vertices without building a new complex. Structures
/// built from `c` before keep what they were built with. Errors: NULL_ARGUMENT (`data` may be
/// NULL only when `len` is 0), INVALID_ARGUMENT (wrong length, `dim` 0, a NaN or infinite
/// number: the message names its vertex), TOO_LARGE (a new dimension's array cannot be
/// allocated); on error nothing changes. Not to be called while another thread reads `c`.
/// Cost: O(len); no allocation when `dim` is the current one.
///
/// # Safety
/// Non-NULL pointers must be valid; `data` holds `len` doubles.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tpx_complex_set_coords(
    c: *mut TpxComplex,
    dim: usize,
    data: *const f64,
    len: usize,
) -> TpxStatus {
    guard(|| {
        let c = out_ptr(c, "c")?;
        let data = in_slice(data, len, "data")?;
        c.complex.set_coords(dim, data).map_err(|e| {
            let f = complex_failure(e.clone());
            match e {
                ComplexError::Coordinates(_) => Failure::new(TpxStatus::InvalidArgument, f.message),
                _ => f,
            }
        })
    })
}

/// Top p-simplex `i` of `c` (the i-th of `tpx_complex_top_simplices(c, p)`) with its vertices in
/// its input winding (the order of its first listing), lent: `*out` points into the complex's
/// own listing, `*out_len` = p + 1 ids, valid until `tpx_complex_free` (setting coordinates
/// does not move it). An isolated vertex no simplex lists lends itself. Errors: NULL_ARGUMENT,
/// DIMENSION_OUT_OF_RANGE (p > d), INVALID_ARGUMENT (`i` ≥ the number of top p-simplices); the
/// outputs are written only on success. O(1) (the first call builds the listing maps,
/// O(Σ (p+1) log n_p)); no copy.
///
/// # Safety
/// Non-NULL pointers must be valid.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tpx_complex_top_oriented(
    c: *const TpxComplex,
    p: u32,
    i: u32,
    out: *mut *const u32,
    out_len: *mut usize,
) -> TpxStatus {
    guard(|| {
        let c = &handle(c, "c")?.complex;
        let out = out_ptr(out, "out")?;
        let out_len = out_ptr(out_len, "out_len")?;
        let d = c.dimension();
        if p as usize > d {
            return Err(Failure::new(
                TpxStatus::DimensionOutOfRange,
                format!("p = {p} is above the complex's dimension {d}"),
            ));
        }
        let n = c.tops(p as usize).len();
        if i as usize >= n {
            return Err(Failure::new(
                TpxStatus::InvalidArgument,
                format!("top {p}-simplex {i}: the complex has {n}"),
            ));
        }
        let row = c.top_oriented(p as usize, i);
        *out = row.as_ptr();
        *out_len = row.len();
        Ok(())
    })
}
