//! [`write_components`] writes each component of an IQM decomposition
//! ([`Decomposition`]) as its own file, over its local vertex ids (the
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

use crate::complex::{Coords, RawInput};
use crate::io::write::{Format, WriteError};
use crate::structures::iqm::{ComponentPiece, Decomposition};

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
    // Every target checked before the first write: a device or pipe among them writes nothing.
    let gluing = dir.join("gluing.json");
    for path in files
        .iter()
        .map(|(name, _)| dir.join(name))
        .chain([gluing.clone()])
    {
        crate::io::check_output(&path).map_err(|e| WriteError::io(&path, e))?;
    }
    let mut paths = Vec::with_capacity(files.len() + 1);
    let mut names = Vec::with_capacity(files.len());
    for (name, bytes) in files {
        let path = dir.join(&name);
        std::fs::write(&path, bytes).map_err(|e| WriteError::io(&path, e))?;
        names.push(name);
        paths.push(path);
    }
    let path = gluing;
    let json = gluing_json(dec, coords, &names);
    let text = serde_json::to_string_pretty(&json).expect("JSON of numbers and strings");
    std::fs::write(&path, text + "\n").map_err(|e| WriteError::io(&path, e))?;
    paths.push(path);
    Ok(paths)
}
