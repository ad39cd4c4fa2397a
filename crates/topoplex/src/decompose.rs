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
//!
//! # Data
//! [`write_components_of`] takes the complex and gives each component its data
//! ([`crate::complex::attributes`]): a vertex copy the row of the vertex it copies; a top the
//! row of its first listing; a listed face with data (absorbed by the closure) a row in every
//! component holding it (all its vertices in the component and it a face of one of the
//! component's tops), written after the tops. By default a component whose data its
//! dimension's format cannot hold goes to the first of Gmsh MSH, VTK, VTU and MEDIT that holds
//! it (or else its dimension's format, which refuses, naming what it cannot hold).
//! Cost: O(tops + listed faces × their faces' lookups), a hash set of one dimension's faces per
//! component that has listed faces.

use std::path::{Path, PathBuf};

use rustc_hash::FxHashSet;

use crate::complex::{Complex, Coords, Location, RawInput};
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

/// The data of one component of `complex`'s decomposition (module doc, "Data"): the vertex rows
/// of its copies, its tops' rows, then its listed faces' rows, with those faces appended to
/// `raw` (whose tops are already there).
fn component_data(piece: &ComponentPiece, complex: &Complex, raw: &mut RawInput) {
    let at = complex.attributes();
    if at.is_empty() {
        return;
    }
    let w = piece.dimension + 1;
    let original =
        |s: &[u32]| -> Vec<u32> { s.iter().map(|&v| piece.original[v as usize]).collect() };
    // A top no listing names (an isolated vertex the input only counted) gets unset numbers:
    // the row past the listing's end, appended to a copy of the listed attributes.
    let unlisted = complex.input_count();
    let mut listed: Vec<usize> = piece
        .tops
        .chunks_exact(w)
        .map(|row| complex.listed_index(&original(row)).unwrap_or(unlisted))
        .collect();
    if at.iter().any(|a| a.location == Location::Listed) {
        // Listed faces: every listing that is not a top's first listing, when the component
        // holds it.
        let local: rustc_hash::FxHashMap<u32, u32> = piece
            .original
            .iter()
            .enumerate()
            .map(|(l, &v)| (v, l as u32))
            .collect();
        let firsts: FxHashSet<usize> = listed.iter().copied().collect();
        let mut faces: Vec<FxHashSet<Vec<u32>>> = vec![FxHashSet::default(); w + 1];
        for i in 0..complex.input_count() {
            let s = complex.input_simplex(i);
            if firsts.contains(&i) || s.len() > w {
                continue;
            }
            let Some(mut ids) = s
                .iter()
                .map(|v| local.get(v).copied())
                .collect::<Option<Vec<u32>>>()
            else {
                continue;
            };
            let k = ids.len();
            if faces[k].is_empty() {
                faces[k] = piece
                    .tops
                    .chunks_exact(w)
                    .flat_map(|row| sorted_subsets(row, k))
                    .collect();
            }
            let given = ids.clone();
            ids.sort_unstable();
            if faces[k].contains(&ids) {
                raw.push(&given, 0);
                listed.push(i);
            }
        }
    }
    let extended;
    let at = if listed.contains(&unlisted) {
        extended = crate::complex::Attributes::from_parts(
            at.iter()
                .map(|a| {
                    let mut a = a.clone();
                    if a.location == Location::Listed {
                        a.values.push_row(a.components, None);
                    }
                    a
                })
                .collect(),
            at.label_names().to_vec(),
        );
        &extended
    } else {
        at
    };
    raw.attributes = at.pick(
        piece.original.iter().map(|&v| v as usize),
        listed.iter().copied(),
    );
}

/// The `k`-vertex subsets of `row` (at most 16 vertices), each ascending.
fn sorted_subsets(row: &[u32], k: usize) -> impl Iterator<Item = Vec<u32>> + '_ {
    (0u32..1 << row.len())
        .filter(move |m| m.count_ones() as usize == k)
        .map(move |m| {
            let mut s: Vec<u32> = (0..row.len())
                .filter(|i| m >> i & 1 == 1)
                .map(|i| row[i])
                .collect();
            s.sort_unstable();
            s
        })
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

/// [`write_components`] for `complex`'s decomposition `dec`, each component with its data
/// (module doc, "Data"), in `format` or by default by its dimension and data.
pub fn write_components_of(
    dec: &Decomposition,
    complex: &Complex,
    dir: &Path,
    format: Option<Format>,
) -> Result<Vec<PathBuf>, WriteError> {
    let coords = complex.coords();
    write_pieces(dec, coords, dir, |piece| {
        let mut raw = component_listing(piece, coords);
        component_data(piece, complex, &mut raw);
        let format = format.unwrap_or_else(|| {
            let by_dimension = default_format(piece.dimension, coords);
            let holds = |f: Format| f.holds_data(&raw);
            [
                by_dimension,
                Format::Vtk,
                Format::Vtu,
                Format::Medit,
                Format::Msh,
            ]
            .into_iter()
            .find(|&f| holds(f) && (f == by_dimension || piece.dimension <= 3))
            .unwrap_or(by_dimension)
        });
        (format, raw)
    })
}

fn write_components_with(
    dec: &Decomposition,
    coords: Option<&Coords>,
    dir: &Path,
    format_of: impl Fn(&ComponentPiece) -> Format,
) -> Result<Vec<PathBuf>, WriteError> {
    write_pieces(dec, coords, dir, |piece| {
        (format_of(piece), component_listing(piece, coords))
    })
}

/// Writes the components as `listing_of` lays each out, then `gluing.json`.
fn write_pieces(
    dec: &Decomposition,
    coords: Option<&Coords>,
    dir: &Path,
    listing_of: impl Fn(&ComponentPiece) -> (Format, RawInput),
) -> Result<Vec<PathBuf>, WriteError> {
    // Serialise first, so that a refusal leaves no partial output.
    let mut files = Vec::with_capacity(dec.components.len());
    for (i, piece) in dec.components.iter().enumerate() {
        let (format, raw) = listing_of(piece);
        let name = format!("component_{i}.{}", format.extension());
        let bytes = format.write(&raw).map_err(|kind| WriteError {
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
