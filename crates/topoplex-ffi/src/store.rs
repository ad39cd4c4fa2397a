//! Saved files (`.tpx`, see `topoplex::store`) and the build thread count.

use std::ffi::c_char;
use std::path::Path;

use super::complex::{TpxComplex, complex_failure};
use super::live::TpxLive;
use super::structure::{TpxStructure, build_failure, kind_from_u32};
use super::{Failure, TpxStatus, guard, on, open_into, path_arg};
use topoplex::store::{Saved, StoreError, save};

/// `tpx_structure_open`, `tpx_live_open` and `tpx_complex_open_flags` flag: check the whole
/// file before returning (every section's checksum, the saved complex, the structure's
/// invariants and its agreement with the complex; reads the whole file and builds).
pub const TPX_OPEN_VERIFY: u32 = 1;

/// `tpx_live_from_file` flag: fan each convex planar polygon of a mesh file into triangles and
/// refuse the other polygons with the reason, as `TPX_READ_TRIANGULATE` does for
/// `tpx_complex_from_file_flags`.
pub const TPX_OPEN_TRIANGULATE: u32 = 2;

pub(crate) fn store_failure(e: StoreError) -> Failure {
    let status = match &e {
        StoreError::Io { .. } => TpxStatus::IoError,
        StoreError::Foreign { .. } => TpxStatus::SavedFileForeign,
        StoreError::Truncated { .. } => TpxStatus::SavedFileTruncated,
        StoreError::WrongVersion { .. } => TpxStatus::SavedFileWrongVersion,
        StoreError::WrongEndianness { .. } => TpxStatus::SavedFileWrongEndianness,
        StoreError::Corrupt { .. } => TpxStatus::SavedFileCorrupt,
        StoreError::Complex { source, .. } => return complex_failure(source.clone()),
        StoreError::Build { source, .. } => return build_failure(source.clone()),
    };
    Failure::new(status, e.to_string())
}

/// The saved file at `path`, opened with `flags` (`TPX_OPEN_VERIFY` or 0) checked first and
/// verified when asked.
/// Whether `flags` ask for a full check (`TPX_OPEN_VERIFY`); any other bit is INVALID_ARGUMENT.
fn verify_flag(flags: u32) -> Result<bool, Failure> {
    if flags & !TPX_OPEN_VERIFY != 0 {
        return Err(Failure::new(
            TpxStatus::InvalidArgument,
            format!("unknown flags {flags:#x} (only TPX_OPEN_VERIFY = 1)"),
        ));
    }
    Ok(flags & TPX_OPEN_VERIFY != 0)
}

fn open_saved(path: &Path, flags: u32) -> Result<Saved, Failure> {
    verify_flag(flags)?;
    let saved = Saved::open(path).map_err(store_failure)?;
    if flags & TPX_OPEN_VERIFY != 0 {
        saved.verify().map_err(store_failure)?;
    }
    Ok(saved)
}

/// Saves the complex `c` and, unless `s` is NULL, the structure `s` built from it, to `path`
/// (a `.tpx` file: written beside it under a temporary name, then renamed).
///
/// Errors: NULL_ARGUMENT (`c` or `path`), INVALID_ARGUMENT (path not UTF-8), IO_ERROR. Cost:
/// one pass over the complex's listing and the structure's arrays.
///
/// # Safety
/// Non-NULL pointers must be valid (live handles; a NUL-terminated path). `s` must have been
/// built from `c` (or opened from a file saved with it): the file pairs them.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tpx_save(
    c: *const TpxComplex,
    s: *const TpxStructure,
    path: *const c_char,
) -> TpxStatus {
    on(c, "c", |c| {
        let path = path_arg(path, "path")?;
        // SAFETY: a non-NULL `s` is a live handle (documented contract).
        let s = unsafe { s.as_ref() };
        save(path, &c.complex, s.map(|s| s.topo.as_ref())).map_err(store_failure)
    })
}

/// Opens the structure of `kind` (`TPX_KIND_*`) saved in `path` by memory mapping it: the
/// structure's arrays are read from the file as queries touch them. If the file holds another
/// kind or only a complex, the structure is built from the saved complex instead. With
/// `flags & TPX_OPEN_VERIFY`, every checksum and the structure's invariants are checked first.
///
/// On success `*out` receives a new structure owned by the caller (free with
/// `tpx_structure_free`; the mapping lives until then). Errors: NULL_ARGUMENT,
/// INVALID_ARGUMENT (path not UTF-8, unknown flag), UNKNOWN_KIND, IO_ERROR,
/// SAVED_FILE_CORRUPT, SAVED_FILE_TRUNCATED, SAVED_FILE_WRONG_VERSION, SAVED_FILE_FOREIGN,
/// SAVED_FILE_WRONG_ENDIANNESS, and the build errors of `tpx_structure_build` when building.
/// Cost: O(sections) without VERIFY; O(file size) with it.
///
/// # Safety
/// `path`, if non-NULL, must be NUL-terminated; `out` must be valid for writes.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tpx_structure_open(
    path: *const c_char,
    kind: u32,
    flags: u32,
    out: *mut *mut TpxStructure,
) -> TpxStatus {
    open_into(path, out, |path| {
        let kind = kind_from_u32(kind)?;
        let saved = open_saved(path, flags)?;
        let topo = saved.structure_of(kind).map_err(store_failure)?;
        Ok(TpxStructure::new(topo))
    })
}

/// Opens the complex saved in `path`, rebuilt from its saved listing (validated like any
/// input). On success `*out` receives a new complex owned by the caller (free with
/// `tpx_complex_free`). Errors: as `tpx_structure_open`, plus INVALID_COMPLEX. Cost: a
/// normalisation of the saved listing.
///
/// # Safety
/// `path`, if non-NULL, must be NUL-terminated; `out` must be valid for writes.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tpx_complex_open(
    path: *const c_char,
    out: *mut *mut TpxComplex,
) -> TpxStatus {
    // SAFETY: the same contract, passed on.
    unsafe { tpx_complex_open_flags(path, 0, out) }
}

/// `tpx_complex_open` with `flags`: with `TPX_OPEN_VERIFY`, the whole file is checked first
/// (every checksum, the saved complex, the saved structure's invariants and its agreement with
/// the complex, as `topoplex verify` does). On success `*out` receives a new complex owned by
/// the caller (free with `tpx_complex_free`). Errors: as `tpx_complex_open`, plus
/// INVALID_ARGUMENT for an unknown flag. Cost: a normalisation of the saved listing; with
/// VERIFY, O(file size) plus a build of the saved structure's kind.
///
/// # Safety
/// `path`, if non-NULL, must be NUL-terminated; `out` must be valid for writes.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tpx_complex_open_flags(
    path: *const c_char,
    flags: u32,
    out: *mut *mut TpxComplex,
) -> TpxStatus {
    open_into(path, out, |path| {
        let saved = open_saved(path, flags)?;
        let complex = saved.complex().map_err(store_failure)?;
        Ok(TpxComplex { complex })
    })
}

/// Saves the live complex `l` with its complex to `path` (`.tpx`). Saving compacts a copy on the
/// fly: removed vertices and slots are not written, ids are renumbered as `tpx_live_compact`
/// would (`l` itself is unchanged). Errors: NULL_ARGUMENT, INVALID_ARGUMENT (path not UTF-8),
/// IO_ERROR. Cost: O(size).
///
/// # Safety
/// Non-NULL pointers must be valid (a live handle; a NUL-terminated path).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tpx_live_save(l: *const TpxLive, path: *const c_char) -> TpxStatus {
    on(l, "l", |l| {
        let path = path_arg(path, "path")?;
        l.live().save(path).map_err(store_failure)
    })
}

/// Opens `path` as an editable live complex: the saved live complex when the file holds one
/// (`topoplex save INPUT --structure iastar`, `tpx_live_save`), else one built from the saved
/// complex. Its arrays are copied out of the file (editable), so opening costs O(size), unlike
/// `tpx_structure_open`. `flags` as `tpx_structure_open` (`TPX_OPEN_VERIFY`). On success `*out`
/// receives a new live complex owned by the caller (free with `tpx_live_free`). Errors: as
/// `tpx_structure_open`.
///
/// # Safety
/// `path`, if non-NULL, must be NUL-terminated; `out` must be valid for writes.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tpx_live_open(
    path: *const c_char,
    flags: u32,
    out: *mut *mut TpxLive,
) -> TpxStatus {
    open_into(path, out, |path| {
        let saved = open_saved(path, flags)?;
        let live = topoplex::live::LiveComplex::open_saved(&saved).map_err(store_failure)?;
        Ok(TpxLive::new(live))
    })
}

/// Reads any input file into a new editable live complex — the application's mesh — the format
/// chosen as `tpx_complex_from_file` chooses it (`.off` ... `.msh`, or a saved `.tpx`, opened as
/// `tpx_live_open` opens it; `flags`: `TPX_OPEN_VERIFY` for a saved file, `TPX_OPEN_TRIANGULATE`
/// to fan convex planar polygons, or 0). A plain OFF file (the header `OFF`, one vertex or face
/// a line, edges and triangles of distinct ids) is streamed into the live complex's arrays: the
/// peak is the live complex and a 1 MiB buffer. Another mesh file
/// whose listing is plain (a declared vertex count, no data arrays, every simplex 2 to 16
/// distinct vertices, none listed twice or a face of another: the usual mesh) is read straight
/// into the live complex, with no `TpxComplex` built: the process's peak is the file's bytes
/// plus the reader's listing, then the listing plus the live complex. Any other file is
/// normalised as `tpx_complex_from_file` does (default budget) and built from that complex.
/// Either way the same live complex as `tpx_live_from_complex(tpx_complex_from_file(path))`:
/// the same vertex ids, each top simplex in its slot in input order with its winding.
///
/// On success `*out` receives a new live complex owned by the caller (free with
/// `tpx_live_free`). Errors: as `tpx_complex_from_file` and `tpx_live_open`; INVALID_ARGUMENT
/// for unknown flags (only TPX_OPEN_VERIFY and TPX_OPEN_TRIANGULATE here). Cost: linear in the
/// file plus the build.
///
/// # Safety
/// `path`, if non-NULL, must be NUL-terminated; `out` must be valid for writes.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tpx_live_from_file(
    path: *const c_char,
    flags: u32,
    out: *mut *mut TpxLive,
) -> TpxStatus {
    open_into(path, out, |path| {
        let verify = verify_flag(flags & !TPX_OPEN_TRIANGULATE)?;
        let options = topoplex::io::ReadOptions {
            triangulate: flags & TPX_OPEN_TRIANGULATE != 0,
        };
        let live = topoplex::store::open_live_with(path, verify, options)
            .map_err(super::complex::open_failure)?;
        Ok(TpxLive::new(live))
    })
}

/// Sets the number of threads later builds use, 1 to 256 (`0` or more than 256 is
/// INVALID_ARGUMENT, the count unchanged). Without a call, the
/// `TOPOPLEX_THREADS` environment variable, else every core. Builds give the same structure
/// whatever the count. O(1).
#[unsafe(no_mangle)]
pub extern "C" fn tpx_set_threads(threads: u32) -> TpxStatus {
    guard(|| {
        topoplex::parallel::check_threads(threads as usize)
            .map_err(|e| Failure::new(TpxStatus::InvalidArgument, e))?;
        topoplex::parallel::set_threads(threads as usize);
        Ok(())
    })
}
