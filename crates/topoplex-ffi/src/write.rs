//! Writing a `TpxComplex` or a `TpxLive` to a file (`tpx_complex_write`, `tpx_live_write`).

use std::ffi::c_char;
use std::path::Path;

use super::complex::TpxComplex;
use super::live::TpxLive;
use super::{Failure, TpxStatus, on, path_arg};
use topoplex::io::write::{Format, WriteError, WriteErrorKind, write_complex};

/// The format named by the output file's extension (`tpx_complex_write`).
pub const TPX_FORMAT_FROM_EXTENSION: u32 = 0;
/// Geomview OFF (`.off`): vertices, edges, triangles.
pub const TPX_FORMAT_OFF: u32 = 1;
/// Wavefront OBJ (`.obj`): points, edges, triangles; at most 3 coordinates.
pub const TPX_FORMAT_OBJ: u32 = 2;
/// MEDIT ASCII (`.mesh`): edges, triangles, tetrahedra; 2 or 3 coordinates.
pub const TPX_FORMAT_MEDIT: u32 = 3;
/// Topoplex `.simplices`: any complex.
pub const TPX_FORMAT_SIMPLICES: u32 = 4;
/// PLY ASCII (`.ply`): edges and triangles; at most 3 coordinates.
pub const TPX_FORMAT_PLY: u32 = 5;
/// PLY binary little-endian.
pub const TPX_FORMAT_PLY_BINARY: u32 = 6;
/// STL ASCII (`.stl`): triangles covering every vertex, distinct 32-bit float coordinates.
pub const TPX_FORMAT_STL: u32 = 7;
/// STL binary.
pub const TPX_FORMAT_STL_BINARY: u32 = 8;
/// Legacy VTK unstructured grid, ASCII (`.vtk`): vertices, edges, triangles, tetrahedra.
pub const TPX_FORMAT_VTK: u32 = 9;
/// Legacy VTK unstructured grid, BINARY.
pub const TPX_FORMAT_VTK_BINARY: u32 = 10;
/// Gmsh MSH 4.1 ASCII (`.msh`): points, edges, triangles, tetrahedra.
pub const TPX_FORMAT_MSH: u32 = 11;
/// Gmsh MSH 4.1 binary.
pub const TPX_FORMAT_MSH_BINARY: u32 = 12;
/// Gmsh MSH 2.2 ASCII.
pub const TPX_FORMAT_MSH2: u32 = 13;
/// Gmsh MSH 2.2 binary.
pub const TPX_FORMAT_MSH2_BINARY: u32 = 14;
/// VTK XML unstructured grid (`.vtu`): vertices, edges, triangles, tetrahedra.
pub const TPX_FORMAT_VTU: u32 = 15;

/// The `Format` of a `TPX_FORMAT_*` number (`None` for `TPX_FORMAT_FROM_EXTENSION`).
pub(crate) fn format_from_u32(format: u32) -> Result<Option<Format>, Failure> {
    if format == TPX_FORMAT_FROM_EXTENSION {
        return Ok(None);
    }
    Format::ALL
        .get(format as usize - 1)
        .copied()
        .map(Some)
        .ok_or_else(|| {
            Failure::new(
                TpxStatus::UnknownFormat,
                format!(
                    "unknown format {format} (expected 0..={}, TPX_FORMAT_*)",
                    Format::ALL.len()
                ),
            )
        })
}

/// Writes the complex `c` to the file `path` (NUL-terminated UTF-8) in `format`
/// (`TPX_FORMAT_*`; `TPX_FORMAT_FROM_EXTENSION` picks it from the path's extension): its top
/// simplices in input order with their input vertex order (winding), isolated vertices and wire
/// edges kept, coordinates in the shortest decimal that reads back bit for bit. Reading the file
/// back with `tpx_complex_from_file` gives the same complex.
///
/// Errors: NULL_ARGUMENT, INVALID_ARGUMENT (path not UTF-8), UNKNOWN_FORMAT (format number or
/// extension unknown), FORMAT_CANNOT_HOLD (the format cannot hold the complex, e.g. OFF with a
/// tetrahedron; the message names the first offending simplex; nothing is written), IO_ERROR
/// (cannot write). Cost: linear in the complex; the file is built in memory, then written.
///
/// # Safety
/// `c` must be NULL or a live complex; `path` NULL or a NUL-terminated string.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tpx_complex_write(
    c: *const TpxComplex,
    path: *const c_char,
    format: u32,
) -> TpxStatus {
    write_into(c, "c", path, format, |c, p, f| {
        write_complex(&c.complex, p, f)
    })
}

/// The one body of `tpx_complex_write` and `tpx_live_write`: the handle `h` (named `what`),
/// `path` and `format` checked in that order, then `write` writes the file.
fn write_into<H>(
    h: *const H,
    what: &str,
    path: *const c_char,
    format: u32,
    write: impl FnOnce(&H, &Path, Option<Format>) -> Result<(), WriteError>,
) -> TpxStatus {
    on(h, what, |h| {
        let path = path_arg(path, "path")?;
        let format = format_from_u32(format)?;
        write(h, path, format).map_err(write_failure)
    })
}

fn write_failure(e: WriteError) -> Failure {
    let status = match e.kind {
        WriteErrorKind::Io(_) => TpxStatus::IoError,
        WriteErrorKind::UnknownExtension => TpxStatus::UnknownFormat,
        WriteErrorKind::CannotHold { .. } => TpxStatus::FormatCannotHold,
    };
    Failure::new(status, e.to_string())
}

/// Writes the live complex `l` to the file `path` as `tpx_complex_write` writes
/// `tpx_live_to_complex`'s complex (the same bytes: live vertices renumbered densely in
/// ascending id order, tops in dimension-then-slot order with their winding, then each other
/// listed simplex that carries data, coordinates and attributes), without building that
/// complex: the memory above the live complex is its listing (4 bytes per id, 12 per simplex)
/// and the file's bytes. Errors as `tpx_complex_write`. Cost: linear in the live complex.
///
/// # Safety
/// `l` must be NULL or a live complex; `path` NULL or a NUL-terminated string.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tpx_live_write(
    l: *const TpxLive,
    path: *const c_char,
    format: u32,
) -> TpxStatus {
    write_into(l, "l", path, format, |l, p, f| l.live().write(p, f))
}
