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
//! | PLY ([`super::ply`]) | 1..=2, triangles then edges | at most 3 (`double`); finite in ASCII |
//! | STL ([`super::stl`]) | 2 only, covering every vertex | at most 3, distinct, exactly `f32` |
//! | VTK ([`super::vtk`]), VTU ([`super::vtu`]) | 0..=3, in listing order | at most 3 |
//! | Gmsh MSH ([`super::msh`]) | 0..=3, in listing order | at most 3 |
//!
//! Formats that need coordinates get zeros when the complex has none, and fewer than 3 numbers
//! per vertex are padded with zeros (MEDIT keeps 2). Listed 0-simplices are isolated vertices,
//! which every format keeps as vertices; formats without a point element (MEDIT) list them no
//! further. Formats with one section per cell type keep the listing order within a dimension.
//!
//! [`write_components`] writes each component of an IQM decomposition
//! ([`crate::structures::iqm::Decomposition`]) as its own file, over its local vertex ids (the
//! vertex copies, so a split vertex appears once per copy, with the coordinates of the vertex it
//! copies), plus `gluing.json` mapping each component's local ids back to the original ids.
//! By default the format follows the component's dimension: 2 → OFF (`component_<i>.off`),
//! 3 → MEDIT (`component_<i>.mesh`), when the coordinates have at most 3 numbers per vertex;
//! anything else → `.simplices`. [`write_components_as`] uses one given format for all.
//!
//! `gluing.json`:
//! ```json
//! { "vertex_count": 10, "coordinate_dimension": 3,
//!   "components": [ { "file": "component_0.mesh", "dimension": 3, "top_count": 1,
//!                     "original_ids": [0, 1, 2, 3] } ],
//!   "split_vertices": [ { "vertex": 0, "copies": [ { "component": 0, "local_id": 0 } ] } ] }
//! ```
//! `original_ids[j]` is the original vertex of local vertex j of that component.

use std::path::{Path, PathBuf};

use super::{Coords, RawInput};
use crate::complex::Complex;
use crate::structures::iqm::{ComponentPiece, Decomposition};

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

    /// Serialises `raw` in this format. Errors: [`WriteErrorKind::CannotHold`].
    pub fn write(self, raw: &RawInput) -> Result<Vec<u8>, WriteErrorKind> {
        let refuse = |reason| WriteErrorKind::CannotHold {
            format: self.name(),
            reason,
        };
        let mut out = Vec::new();
        match self {
            Format::Off => off::write(raw, &mut out),
            Format::Obj => obj::write(raw, &mut out),
            Format::Medit => medit::write(raw, &mut out),
            Format::Simplices => {
                simplices::write(raw, &mut out);
                Ok(())
            }
            Format::Ply => super::ply::write(raw, false, &mut out),
            Format::PlyBinary => super::ply::write(raw, true, &mut out),
            Format::Stl => super::stl::write_ascii(raw, &mut out),
            Format::StlBinary => super::stl::write_binary(raw, &mut out),
            Format::Vtk => super::vtk::write(raw, false, &mut out),
            Format::VtkBinary => super::vtk::write(raw, true, &mut out),
            Format::Vtu => super::vtu::write(raw, &mut out),
            Format::Msh => super::msh::write(raw, true, false, &mut out),
            Format::MshBinary => super::msh::write(raw, true, true, &mut out),
            Format::Msh2 => super::msh::write(raw, false, false, &mut out),
            Format::Msh2Binary => super::msh::write(raw, false, true, &mut out),
        }
        .map_err(refuse)?;
        Ok(out)
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
        "unknown output extension (expected .off, .obj, .mesh, .simplices, .ply, .stl or .vtk)"
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
    fn io(path: &Path, e: std::io::Error) -> WriteError {
        WriteError {
            path: path.to_path_buf(),
            kind: WriteErrorKind::Io(e.to_string()),
        }
    }
}

/// The complex as a listing: every vertex, its coordinates, and the top simplices in input
/// order with their input winding ([`Complex::tops_as_given`]). Reading back what a writer made
/// of it gives the same listing (within a dimension, for formats with one section per cell type).
pub fn listing(c: &Complex) -> RawInput {
    let mut raw = RawInput::new();
    raw.vertex_count = Some(c.vertex_count());
    raw.coords = c.coords().cloned();
    for (_, _, _, s) in c.tops_as_given() {
        raw.push(s, 0);
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
    let err = |kind| WriteError {
        path: path.to_path_buf(),
        kind,
    };
    let format = format
        .or_else(|| Format::from_path(path))
        .ok_or_else(|| err(WriteErrorKind::UnknownExtension))?;
    let bytes = format.write(raw).map_err(err)?;
    std::fs::write(path, bytes).map_err(|e| WriteError::io(path, e))
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
    for i in 0..width {
        if i > 0 {
            out.push(b' ');
        }
        let x = coords
            .filter(|c| i < c.dim)
            .map_or(0.0, |c| c.data[v * c.dim + i]);
        push_f64(out, x);
    }
}

/// Appends the ids of `s` plus `base`, space-separated.
pub(crate) fn push_ids(out: &mut Vec<u8>, s: &[u32], base: u64) {
    for (i, &v) in s.iter().enumerate() {
        if i > 0 {
            out.push(b' ');
        }
        out.extend_from_slice((u64::from(v) + base).to_string().as_bytes());
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

fn default_format(dimension: usize, coords: Option<&Coords>) -> Format {
    let fits = coords.is_none_or(|c| c.dim <= 3);
    match dimension {
        2 if fits => Format::Off,
        3 if fits => Format::Medit,
        _ => Format::Simplices,
    }
}

/// One component as a listing over its local vertex ids, with its vertices' coordinates.
fn component_listing(piece: &ComponentPiece, coords: Option<&Coords>) -> RawInput {
    let mut raw = RawInput::new();
    raw.vertex_count = Some(piece.original.len() as u32);
    raw.coords = coords.map(|c| Coords {
        dim: c.dim,
        data: piece
            .original
            .iter()
            .flat_map(|&v| &c.data[v as usize * c.dim..(v as usize + 1) * c.dim])
            .copied()
            .collect(),
    });
    for row in piece.tops.chunks_exact(piece.dimension + 1) {
        raw.push(row, 0);
    }
    raw
}

/// The `gluing.json` document for `dec` with the component file names given.
pub fn gluing_json(
    dec: &Decomposition,
    coords: Option<&Coords>,
    files: &[String],
) -> serde_json::Value {
    let components: Vec<serde_json::Value> = dec
        .components
        .iter()
        .zip(files)
        .map(|(c, f)| {
            serde_json::json!({
                "file": f,
                "dimension": c.dimension,
                "top_count": c.tops.len() / (c.dimension + 1),
                "original_ids": c.original,
            })
        })
        .collect();
    let split: Vec<serde_json::Value> = dec
        .split_vertices
        .iter()
        .enumerate()
        .map(|(a, &v)| {
            let copies =
                &dec.split_copies[dec.split_offsets[a] as usize..dec.split_offsets[a + 1] as usize];
            let copies: Vec<serde_json::Value> = copies
                .iter()
                .map(|&c| {
                    let comp = dec.copy_component[c as usize] as usize;
                    serde_json::json!({
                        "component": comp,
                        "local_id": c - dec.components[comp].first_copy,
                    })
                })
                .collect();
            serde_json::json!({ "vertex": v, "copies": copies })
        })
        .collect();
    serde_json::json!({
        "vertex_count": dec.vertex_count,
        "coordinate_dimension": coords.map(|c| c.dim),
        "components": components,
        "split_vertices": split,
    })
}

/// Whether `name` is one of the files [`write_components`] or [`write_components_as`] write:
/// `component_<i>.<ext>` for the extension of any [`Format`], or `gluing.json`.
pub fn is_decomposition_file(name: &str) -> bool {
    if name == "gluing.json" {
        return true;
    }
    let Some((stem, ext)) = name.rsplit_once('.') else {
        return false;
    };
    let Some(i) = stem.strip_prefix("component_") else {
        return false;
    };
    Format::ALL.iter().any(|f| f.extension() == ext)
        && !i.is_empty()
        && i.bytes().all(|b| b.is_ascii_digit())
}

/// Writes every component of `dec` into `dir` (created if missing) and `gluing.json`; returns
/// the paths written, components first. `coords` are the original complex's coordinates. Each
/// component's format follows its dimension (see the module documentation).
pub fn write_components(
    dec: &Decomposition,
    coords: Option<&Coords>,
    dir: &Path,
) -> Result<Vec<PathBuf>, WriteError> {
    write_components_with(dec, coords, dir, |piece| {
        default_format(piece.dimension, coords)
    })
}

/// [`write_components`] with every component in `format`. Every component is checked before
/// any file is written: if the format cannot hold one, nothing is written.
pub fn write_components_as(
    dec: &Decomposition,
    coords: Option<&Coords>,
    dir: &Path,
    format: Format,
) -> Result<Vec<PathBuf>, WriteError> {
    write_components_with(dec, coords, dir, |_| format)
}

fn write_components_with(
    dec: &Decomposition,
    coords: Option<&Coords>,
    dir: &Path,
    format_of: impl Fn(&ComponentPiece) -> Format,
) -> Result<Vec<PathBuf>, WriteError> {
    // Serialise first, so that a refusal leaves no partial output.
    let mut files = Vec::with_capacity(dec.components.len());
    for (i, piece) in dec.components.iter().enumerate() {
        let format = format_of(piece);
        let name = format!("component_{i}.{}", format.extension());
        let bytes = format
            .write(&component_listing(piece, coords))
            .map_err(|kind| WriteError {
                path: dir.join(&name),
                kind,
            })?;
        files.push((name, bytes));
    }
    std::fs::create_dir_all(dir).map_err(|e| WriteError::io(dir, e))?;
    let mut paths = Vec::with_capacity(files.len() + 1);
    let mut names = Vec::with_capacity(files.len());
    for (name, bytes) in files {
        let path = dir.join(&name);
        std::fs::write(&path, bytes).map_err(|e| WriteError::io(&path, e))?;
        names.push(name);
        paths.push(path);
    }
    let path = dir.join("gluing.json");
    let json = gluing_json(dec, coords, &names);
    let text = serde_json::to_string_pretty(&json).expect("JSON of numbers and strings");
    std::fs::write(&path, text + "\n").map_err(|e| WriteError::io(&path, e))?;
    paths.push(path);
    Ok(paths)
}
