//! Writers: files out of a listing (a [`RawInput`]: vertex count, coordinates, simplices in
//! order), no topology. The inverse of the readers.
//!
//! [`write_complex`] writes a [`Complex`] as it was given: its top simplices in input order, each
//! with its input vertex order (winding) ([`Complex::tops_as_given`]); isolated vertices and wire
//! edges are kept; coordinates are written in the shortest decimal that reads back to the same
//! `f64` (ryu), so a file read back gives bit-identical coordinates (NaN payloads aside).
//!
//! What each format holds (anything else is refused with [`WriteErrorKind::CannotHold`] naming
//! the first offending simplex, never dropped):
//!
//! | format | simplices | coordinates |
//! |---|---|---|
//! | OFF | dimension 0..=2, in listing order | 3 numbers per vertex (`OFF`), any other count `nOFF` |
//! | OBJ | 0..=2 (`p`, `l`, `f`), in listing order | at most 3 |
//! | MEDIT | 1..=3, grouped by dimension (sections) | 2 (`Dimension 2`) or 3 |
//! | `.simplices` | any | any |
//! | PLY ([`super::ply`]) | 1..=2, triangles then edges (listed data follows its simplex) | at most 3 (`double`); finite in ASCII |
//! | STL ([`super::stl`]) | 2 only, covering every vertex | at most 3, distinct, exactly `f32` |
//! | VTK ([`super::vtk`]), VTU ([`super::vtu`]) | 0..=3, in listing order | at most 3 |
//! | Gmsh MSH ([`super::msh`]) | 0..=3, in listing order | at most 3 |
//!
//! Formats that need coordinates get zeros when the complex has none, and fewer than 3 numbers
//! per vertex are padded with zeros (MEDIT keeps 2). Listed 0-simplices are isolated vertices,
//! which every format keeps as vertices; formats without a point element (MEDIT) list them no
//! further. Formats with one section per cell type keep the listing order within a dimension.
//! The components of a decomposition are written by [`crate::decompose`], above the structures.

use std::path::{Path, PathBuf};

use super::{Coords, RawInput};
use crate::complex::{Attribute, Complex, Location, Values};

mod medit;
mod obj;
mod off;
mod simplices;

/// An output format. Files written in any of them are read back by [`super::read_path`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Format {
    /// Geomview OFF (`.off`), ASCII.
    Off,
    /// Wavefront OBJ (`.obj`).
    Obj,
    /// MEDIT ASCII (`.mesh`).
    Medit,
    /// Topoplex's `.simplices`.
    Simplices,
    /// PLY, ASCII (`.ply`).
    Ply,
    /// PLY, binary little-endian (`.ply`).
    PlyBinary,
    /// STL, ASCII (`.stl`).
    Stl,
    /// STL, binary (`.stl`).
    StlBinary,
    /// Legacy VTK unstructured grid, ASCII (`.vtk`).
    Vtk,
    /// Legacy VTK unstructured grid, BINARY (`.vtk`).
    VtkBinary,
    /// VTK XML unstructured grid (`.vtu`).
    Vtu,
    /// Gmsh MSH 4.1, ASCII (`.msh`).
    Msh,
    /// Gmsh MSH 4.1, binary.
    MshBinary,
    /// Gmsh MSH 2.2, ASCII.
    Msh2,
    /// Gmsh MSH 2.2, binary.
    Msh2Binary,
}

impl Format {
    /// Every format, in the order of their C ABI numbers (`TPX_FORMAT_*`).
    pub const ALL: [Format; 15] = [
        Format::Off,
        Format::Obj,
        Format::Medit,
        Format::Simplices,
        Format::Ply,
        Format::PlyBinary,
        Format::Stl,
        Format::StlBinary,
        Format::Vtk,
        Format::VtkBinary,
        Format::Msh,
        Format::MshBinary,
        Format::Msh2,
        Format::Msh2Binary,
        Format::Vtu,
    ];

    /// The name used by the CLI's `--format` and in messages (`off`, `obj`, `mesh`,
    /// `simplices`, `ply`, `ply-binary`, `stl`, `stl-binary`, `vtk`, `vtk-binary`, `msh` (4.1),
    /// `msh-binary`, `msh2`, `msh2-binary`, `vtu`).
    pub fn name(self) -> &'static str {
        match self {
            Format::Off => "off",
            Format::Obj => "obj",
            Format::Medit => "mesh",
            Format::Simplices => "simplices",
            Format::Ply => "ply",
            Format::PlyBinary => "ply-binary",
            Format::Stl => "stl",
            Format::StlBinary => "stl-binary",
            Format::Vtk => "vtk",
            Format::VtkBinary => "vtk-binary",
            Format::Vtu => "vtu",
            Format::Msh => "msh",
            Format::MshBinary => "msh-binary",
            Format::Msh2 => "msh2",
            Format::Msh2Binary => "msh2-binary",
        }
    }

    /// The format called `name` (see [`Format::name`]), any case.
    pub fn from_name(name: &str) -> Option<Format> {
        let name = name.to_ascii_lowercase();
        Format::ALL.into_iter().find(|f| f.name() == name)
    }

    /// The file extension written for this format, without the dot.
    pub fn extension(self) -> &'static str {
        match self {
            Format::PlyBinary => "ply",
            Format::StlBinary => "stl",
            Format::VtkBinary => "vtk",
            Format::MshBinary | Format::Msh2 | Format::Msh2Binary => "msh",
            f => f.name(),
        }
    }

    /// The format a path's extension asks for (any case), `None` for an unknown extension. An
    /// extension shared by an ASCII and a binary variant means the ASCII one.
    pub fn from_path(path: &Path) -> Option<Format> {
        let ext = path.extension()?.to_str()?.to_ascii_lowercase();
        Format::ALL.into_iter().find(|f| f.extension() == ext)
    }

    /// Whether this format holds attribute `a` (in its own convention, see the table of
    /// [`self`](crate::io::write)): MEDIT `medit:ref` (integers within 32 bits), Gmsh
    /// `gmsh:physical` and `gmsh:geometrical` on the listed simplices (the same) and any other
    /// `f64` field as `$NodeData`/`$ElementData` (a name without `\"` or control characters;
    /// `f32` and integer fields are not widened: write VTK or VTU), legacy VTK any
    /// point or cell data whose name has no blank, VTU any point or cell data whose name has no
    /// control character (an XML attribute value; tabs and newlines would read back as blanks),
    /// PLY any 1-component attribute as a property of its type (see `ply::holds`), OBJ its
    /// grouping labels (`obj:object`, `obj:group`, `obj:material`, `obj:smoothing`, `i32` on
    /// the listed simplices; names checked when written) and vertex data (`obj:color`, `obj:vt`,
    /// `obj:vn`, see `obj::data::holds`), OFF `off:normal`, `off:color`,
    /// `off:texture` (`f64`) on the vertices and `off:color` (`f64`, 1, 3 or 4 components) on
    /// the listed simplices, `.simplices` `simplices:label` (`i64` on the listed simplices), ASCII STL `stl:solid` (`i32` on the listed triangles, named).
    pub fn holds(self, a: &Attribute) -> bool {
        let int32 = a.components == 1
            && match &a.values {
                Values::I32(_) => true,
                Values::I64(v) => v.iter().all(|&x| i32::try_from(x).is_ok()),
                _ => false,
            };
        match self {
            Format::Medit => a.name == super::medit::REF && int32,
            Format::Msh | Format::MshBinary | Format::Msh2 | Format::Msh2Binary => {
                (a.location == Location::Listed
                    && (a.name == super::msh::PHYSICAL || a.name == super::msh::GEOMETRICAL)
                    && int32)
                    || super::msh::holds_data(a)
            }
            Format::Vtk | Format::VtkBinary => !a
                .name
                .bytes()
                .any(|b| b.is_ascii_whitespace() || b.is_ascii_control()),
            Format::Vtu => !a.name.is_empty() && !a.name.chars().any(char::is_control),
            Format::Ply | Format::PlyBinary => super::ply::holds(a),
            Format::Off => off::holds(a),
            Format::Simplices => {
                a.name == super::simplices::LABEL
                    && a.location == Location::Listed
                    && a.components == 1
                    && matches!(a.values, Values::I64(_))
            }
            Format::Stl => {
                a.name == super::stl::SOLID
                    && a.location == Location::Listed
                    && a.components == 1
                    && matches!(a.values, Values::I32(_))
            }
            Format::Obj => {
                a.location == Location::Listed
                    && a.components == 1
                    && matches!(a.values, Values::I32(_))
                    && super::obj::LABELS.iter().any(|l| l.1 == a.name)
                    || super::obj::data::holds(a)
            }
            _ => false,
        }
    }

    /// The first attribute of `raw` this format does not hold, as the reason for
    /// [`WriteErrorKind::CannotHold`]: the attribute, the formats that hold it, and how to drop
    /// it.
    /// Whether this format holds the names of the labels of attribute `attribute` (Gmsh's
    /// `$PhysicalNames` for `gmsh:physical`; OBJ's `o`, `g`, `usemtl` names for `obj:object`,
    /// `obj:group`, `obj:material`; ASCII STL's solid names for `stl:solid`).
    pub fn holds_label_names(self, attribute: &str) -> bool {
        match self {
            Format::Msh | Format::MshBinary | Format::Msh2 | Format::Msh2Binary => {
                attribute == super::msh::PHYSICAL
            }
            // The names are the statements' and the solids' own.
            Format::Obj => super::obj::LABELS[..3].iter().any(|l| l.1 == attribute),
            Format::Stl => attribute == super::stl::SOLID,
            _ => false,
        }
    }

    /// Whether this format holds every attribute and label name of `raw`.
    pub fn holds_data(self, raw: &RawInput) -> bool {
        self.check_attributes(raw).is_ok()
    }

    fn check_attributes(self, raw: &RawInput) -> Result<(), String> {
        if let Some(n) = raw
            .attributes
            .label_names()
            .iter()
            .find(|n| !self.holds_label_names(&n.attribute))
        {
            let mut can: Vec<String> = Format::ALL
                .into_iter()
                .filter(|f| f.holds_label_names(&n.attribute))
                .map(|f| format!(".{}", f.extension()))
                .collect();
            can.dedup();
            let count = raw.attributes.label_names().len();
            return Err(format!(
                "the names of the labels of '{}' ({count}, such as {} = '{}'): {}drop them \
                 explicitly (CLI: --drop-data label-names keeps the labels)",
                crate::error::echo(&n.attribute),
                n.label,
                crate::error::echo(&n.name),
                if can.is_empty() {
                    String::new()
                } else {
                    format!("write {}, or ", can.join(", "))
                }
            ));
        }
        let Some(a) = raw.attributes.iter().find(|a| !self.holds(a)) else {
            return Ok(());
        };
        let mut can: Vec<&str> = Format::ALL
            .into_iter()
            .filter(|f| f.holds(a))
            .map(|f| f.extension())
            .collect();
        can.dedup();
        let can = if can.is_empty() {
            "no format here holds it".to_string()
        } else {
            format!(
                "write {}",
                can.iter()
                    .map(|e| format!(".{e}"))
                    .collect::<Vec<_>>()
                    .join(", ")
            )
        };
        Err(format!(
            "attribute {}: {can}, or drop it explicitly (CLI: --drop-data '{}' or all)",
            a.describe(),
            crate::error::echo(&a.name)
        ))
    }

    /// Serialises `raw` in this format, attributes included. Errors:
    /// [`WriteErrorKind::CannotHold`] (a simplex, the coordinates or an attribute the format
    /// cannot hold; nothing is written).
    pub fn write(self, raw: &RawInput) -> Result<Vec<u8>, WriteErrorKind> {
        let mut out = Out::memory();
        self.write_into(raw, &mut out)?;
        Ok(out.buf)
    }

    /// [`Format::write`] into `out`, which the text writers (OFF, OBJ, MEDIT, `.simplices`)
    /// hand to its file piece by piece as they go; the others build the whole file first.
    fn write_into(self, raw: &RawInput, out: &mut Out) -> Result<(), WriteErrorKind> {
        let refuse = |reason| WriteErrorKind::CannotHold {
            format: self.name(),
            reason,
        };
        self.check_attributes(raw).map_err(refuse)?;
        match self {
            Format::Off => off::write(raw, out),
            Format::Obj => obj::write(raw, out),
            Format::Medit => medit::write(raw, out),
            Format::Simplices => {
                simplices::write(raw, out);
                Ok(())
            }
            Format::Ply => super::ply::write(raw, false, out),
            Format::PlyBinary => super::ply::write(raw, true, out),
            Format::Stl => super::stl::write_ascii(raw, out),
            Format::StlBinary => super::stl::write_binary(raw, out),
            Format::Vtk => super::vtk::write(raw, false, out),
            Format::VtkBinary => super::vtk::write(raw, true, out),
            Format::Vtu => super::vtu::write(raw, out),
            Format::Msh => super::msh::write(raw, true, false, out),
            Format::MshBinary => super::msh::write(raw, true, true, out),
            Format::Msh2 => super::msh::write(raw, false, false, out),
            Format::Msh2Binary => super::msh::write(raw, false, true, out),
        }
        .map_err(refuse)?;
        Ok(())
    }
}

/// Bytes a text writer gathers before it hands them to the file.
const SPILL: usize = 1 << 20;

/// A writer's output: bytes gathered in memory and, when writing a file, handed to it in pieces
/// of about [`SPILL`] bytes as the writer goes ([`Out::spill`]), so that writing a large mesh
/// costs a piece of memory rather than the whole file. Derefs to the buffer, so a writer
/// pushes bytes as into any `Vec<u8>`. The first I/O error is kept and reported at the end.
pub(crate) struct Out {
    buf: Vec<u8>,
    file: Option<std::fs::File>,
    error: Option<std::io::Error>,
}

impl Out {
    fn memory() -> Out {
        Out {
            buf: Vec::new(),
            file: None,
            error: None,
        }
    }

    /// Hands the gathered bytes to the file once they pass [`SPILL`] (nothing in memory).
    pub(crate) fn spill(&mut self) {
        if self.buf.len() < SPILL {
            return;
        }
        if let Some(file) = &mut self.file {
            if self.error.is_none()
                && let Err(e) = std::io::Write::write_all(file, &self.buf)
            {
                self.error = Some(e);
            }
            self.buf.clear();
        }
    }

    /// Writes what is left; the first I/O error, if any.
    fn finish(mut self) -> std::io::Result<()> {
        if let Some(e) = self.error.take() {
            return Err(e);
        }
        if let Some(file) = &mut self.file {
            std::io::Write::write_all(file, &self.buf)?;
        }
        Ok(())
    }
}

impl std::ops::Deref for Out {
    type Target = Vec<u8>;
    fn deref(&self) -> &Vec<u8> {
        &self.buf
    }
}

impl std::ops::DerefMut for Out {
    fn deref_mut(&mut self) -> &mut Vec<u8> {
        &mut self.buf
    }
}

/// Why a file was not written, without the path ([`WriteError`] adds it).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum WriteErrorKind {
    /// The file system refused (the text of the `std::io::Error`).
    #[error("cannot write file: {0}")]
    Io(String),
    /// The extension names no format.
    #[error(
        "unknown output extension (expected .off, .obj, .mesh, .simplices, .ply, .stl, .vtk, \
         .vtu or .msh)"
    )]
    UnknownExtension,
    /// The format cannot hold the complex; `reason` names the first offending simplex or what
    /// of the coordinates does not fit.
    #[error("the {format} format cannot hold this complex: {reason}")]
    CannotHold {
        /// [`Format::name`] of the format.
        format: &'static str,
        /// What does not fit.
        reason: String,
    },
}

/// A file that could not be written.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{}: {kind}", crate::error::echo_path(path))]
pub struct WriteError {
    /// The file (or directory) being written.
    pub path: PathBuf,
    /// What went wrong.
    pub kind: WriteErrorKind,
}

impl WriteError {
    pub(crate) fn io(path: &Path, e: std::io::Error) -> WriteError {
        WriteError {
            path: path.to_path_buf(),
            kind: WriteErrorKind::Io(e.to_string()),
        }
    }
}

/// The complex as a listing: every vertex, its coordinates, its attributes, and the top
/// simplices in input order with their input winding ([`Complex::tops_as_given`]) — or, when
/// the complex carries attributes on its listed simplices, every listed simplex as given
/// (absorbed faces and repeats included, each with its data: a boundary triangle's reference
/// is written with it). Reading back what a writer made of it gives the same listing (within a
/// dimension, for formats with one section per cell type).
pub fn listing(c: &Complex) -> RawInput {
    let mut raw = RawInput::new();
    raw.vertex_count = Some(c.vertex_count());
    raw.coords = c.coords().cloned();
    raw.attributes = c.attributes().clone();
    if c.attributes()
        .iter()
        .any(|a| a.location == Location::Listed)
    {
        for i in 0..c.input_count() {
            raw.push(c.input_simplex(i), 0);
        }
    } else {
        for (_, _, _, s) in c.tops_as_given() {
            raw.push(s, 0);
        }
    }
    raw
}

/// Writes `c` to `path` in `format` (by default the one its extension names). Nothing is
/// written when the format cannot hold the complex.
pub fn write_complex(c: &Complex, path: &Path, format: Option<Format>) -> Result<(), WriteError> {
    write_raw(&listing(c), path, format)
}

/// Writes a listing to `path` in `format` (by default the one its extension names).
pub fn write_raw(raw: &RawInput, path: &Path, format: Option<Format>) -> Result<(), WriteError> {
    let format = format
        .or_else(|| Format::from_path(path))
        .ok_or_else(|| WriteError {
            path: path.to_path_buf(),
            kind: WriteErrorKind::UnknownExtension,
        })?;
    write_file(path, |out| format.write_into(raw, out))
}

/// Writes to `path` what `write` puts into its [`Out`], which hands it to the file piece by
/// piece; nothing is left under `path` when `write` refuses or an I/O error occurs.
pub(crate) fn write_file(
    path: &Path,
    write: impl FnOnce(&mut Out) -> Result<(), WriteErrorKind>,
) -> Result<(), WriteError> {
    let err = |kind| WriteError {
        path: path.to_path_buf(),
        kind,
    };
    // Written beside `path` under a temporary name, then renamed: a refusal or an I/O error
    // midway leaves no half file under the name. The rename would replace a device or a pipe
    // under either name by a regular file, so both must be regular or absent.
    let mut tmp = path.as_os_str().to_owned();
    tmp.push(".partial");
    let tmp = std::path::PathBuf::from(tmp);
    for p in [path, &tmp] {
        super::check_output(p).map_err(|e| WriteError::io(path, e))?;
    }
    let file = std::fs::File::create(&tmp).map_err(|e| WriteError::io(path, e))?;
    let mut out = Out {
        buf: Vec::new(),
        file: Some(file),
        error: None,
    };
    let done = match write(&mut out) {
        Ok(()) => out
            .finish()
            .and_then(|()| std::fs::rename(&tmp, path))
            .map_err(|e| WriteError::io(path, e)),
        Err(kind) => Err(err(kind)),
    };
    if done.is_err() {
        let _ = std::fs::remove_file(&tmp);
    }
    done
}

// ---------------------------------------------------------------------------------------------
// Helpers shared by the writers.

/// Appends `x` in the shortest decimal that parses back to the same `f64` (`1` rather than
/// `1.0`); non-finite values as `NaN`, `inf`, `-inf`, which every reader here accepts.
pub(crate) fn push_f64(out: &mut Vec<u8>, x: f64) {
    let mut buf = ryu::Buffer::new();
    let s = buf.format(x);
    out.extend_from_slice(s.strip_suffix(".0").unwrap_or(s).as_bytes());
}

/// Appends `width` coordinates of vertex `v`, space-separated, padded with zeros (all zeros
/// without coordinates).
pub(crate) fn push_point(out: &mut Vec<u8>, coords: Option<&Coords>, v: usize, width: usize) {
    let xs = coords.map_or(&[][..], |c| &c.data[v * c.dim..(v + 1) * c.dim]);
    push_numbers(out, xs, width);
}

/// Appends `width` numbers, `xs` then zeros, space-separated.
fn push_numbers(out: &mut Vec<u8>, xs: &[f64], width: usize) {
    for i in 0..width {
        if i > 0 {
            out.push(b' ');
        }
        push_f64(out, xs.get(i).copied().unwrap_or(0.0));
    }
}

/// Writes an OFF file of `n` vertices, vertex v's coordinates `coords(v)` (at most 3, padded
/// with zeros; asked for in order), and `m` faces, edges and triangles, their ids through `id`,
/// straight from a mesh's arrays with no listing: the live complex's writer. The same bytes as
/// [`write_raw`] of the listing they would make (no attributes).
pub(crate) fn write_plain_off<'a, 's>(
    path: &Path,
    n: usize,
    mut coords: impl FnMut(usize) -> &'a [f64],
    m: usize,
    faces: impl Iterator<Item = &'s [u32]>,
    id: impl Fn(u32) -> u32,
) -> Result<(), WriteError> {
    write_file(path, |out| {
        let vertex = |out: &mut Vec<u8>, v| push_numbers(out, coords(v), 3);
        off::write_lines(out, "", 3, n, vertex, m, faces, id, |_, _| {});
        Ok(())
    })
}

/// Appends the ids of `s` plus `base`, space-separated.
pub(crate) fn push_ids(out: &mut Vec<u8>, s: &[u32], base: u64) {
    for (i, &v) in s.iter().enumerate() {
        if i > 0 {
            out.push(b' ');
        }
        out.extend_from_slice(itoa::Buffer::new().format(u64::from(v) + base).as_bytes());
    }
}

/// The vertex count to write: the declared one, else `max id + 1`.
pub(crate) fn vertex_count(raw: &RawInput) -> usize {
    match raw.vertex_count {
        Some(n) => n as usize,
        None => raw.ids.iter().max().map_or(0, |&m| m as usize + 1),
    }
}

/// The first simplex with more than `max_len` vertices, as a refusal naming it and what the
/// format holds.
pub(crate) fn check_max_len(raw: &RawInput, max_len: usize, holds: &str) -> Result<(), String> {
    match (0..raw.simplex_count()).find(|&i| raw.simplex(i).len() > max_len) {
        None => Ok(()),
        Some(i) => Err(format!(
            "simplex #{i} {} has dimension {}; it holds {holds}",
            show(raw.simplex(i)),
            raw.simplex(i).len() - 1
        )),
    }
}

/// What a format of points in space refuses: a simplex of more than `max_len` vertices (the
/// refusal naming what it `holds`) or coordinates of more than three numbers per vertex.
pub(crate) fn check_fits(raw: &RawInput, max_len: usize, holds: &str) -> Result<(), String> {
    check_max_len(raw, max_len, holds)?;
    check_coord_dim(raw, 3)
}

/// Refuses coordinates of more than `max` numbers per vertex.
pub(crate) fn check_coord_dim(raw: &RawInput, max: usize) -> Result<(), String> {
    match &raw.coords {
        Some(c) if c.dim > max => Err(format!(
            "the coordinates have {} numbers per vertex; it holds at most {max}",
            c.dim
        )),
        _ => Ok(()),
    }
}

/// `[a b c]`, capped at 16 ids (a simplex has at most 16).
pub(crate) fn show(s: &[u32]) -> String {
    let v: Vec<String> = s.iter().take(16).map(u32::to_string).collect();
    format!("[{}]", v.join(" "))
}

// ---------------------------------------------------------------------------------------------
// IQM components.
