//! Writers: files out of plain arrays, no topology.
//!
//! [`write_components`] writes each component of an IQM decomposition
//! ([`crate::structures::iqm::Decomposition`]) as its own file, over its local vertex ids (the
//! vertex copies, so a split vertex appears once per copy, with the coordinates of the vertex it
//! copies), plus `gluing.json` mapping each component's local ids back to the original ids.
//!
//! Formats, by component dimension:
//! - 2 → OFF (`component_<i>.off`), 3 → MEDIT (`component_<i>.mesh`, 1-based ids, reference 0),
//!   when the coordinates have at most 3 numbers per vertex (fewer are padded with zeros; none
//!   given: all zeros, and `gluing.json` says `"coordinate_dimension": null`);
//! - any other dimension, or coordinates of more than 3 numbers: `.simplices` (`v` lines with
//!   the coordinates as given, then one `s` line per top simplex).
//!
//! `gluing.json`:
//! ```json
//! { "vertex_count": 10, "coordinate_dimension": 3,
//!   "components": [ { "file": "component_0.mesh", "dimension": 3, "top_count": 1,
//!                     "original_ids": [0, 1, 2, 3] } ],
//!   "split_vertices": [ { "vertex": 0, "copies": [ { "component": 0, "local_id": 0 } ] } ] }
//! ```
//! `original_ids[j]` is the original vertex of local vertex j of that component.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use super::Coords;
use crate::structures::iqm::{ComponentPiece, Decomposition};

/// A file that could not be written.
#[derive(Debug, thiserror::Error)]
#[error("{}: {source}", path.display())]
pub struct WriteError {
    /// The file that could not be written.
    pub path: PathBuf,
    /// The operating system's error.
    pub source: std::io::Error,
}

#[derive(Clone, Copy, PartialEq, Eq)]
enum Format {
    Off,
    Medit,
    Simplices,
}

fn format_for(dimension: usize, coords: Option<&Coords>) -> Format {
    let fits = coords.is_none_or(|c| c.dim <= 3);
    match dimension {
        2 if fits => Format::Off,
        3 if fits => Format::Medit,
        _ => Format::Simplices,
    }
}

/// The coordinates of original vertex `v`, padded to `width` numbers (zeros when absent).
fn point(coords: Option<&Coords>, v: u32, width: usize, out: &mut String) {
    for i in 0..width {
        let x = coords
            .filter(|c| i < c.dim)
            .map_or(0.0, |c| c.data[v as usize * c.dim + i]);
        if i > 0 {
            out.push(' ');
        }
        let _ = write!(out, "{x}");
    }
}

fn component_text(piece: &ComponentPiece, coords: Option<&Coords>, format: Format) -> String {
    let k = piece.dimension;
    let rows = piece.tops.chunks_exact(k + 1);
    let mut s = String::new();
    match format {
        Format::Off => {
            let _ = writeln!(s, "OFF\n{} {} 0", piece.original.len(), rows.len());
            for &v in &piece.original {
                point(coords, v, 3, &mut s);
                s.push('\n');
            }
            for r in rows {
                let _ = writeln!(s, "3 {} {} {}", r[0], r[1], r[2]);
            }
        }
        Format::Medit => {
            let _ = writeln!(
                s,
                "MeshVersionFormatted 1\nDimension 3\nVertices\n{}",
                piece.original.len()
            );
            for &v in &piece.original {
                point(coords, v, 3, &mut s);
                s.push_str(" 0\n");
            }
            let _ = writeln!(s, "Tetrahedra\n{}", rows.len());
            for r in rows {
                let _ = writeln!(s, "{} {} {} {} 0", r[0] + 1, r[1] + 1, r[2] + 1, r[3] + 1);
            }
            s.push_str("End\n");
        }
        Format::Simplices => {
            let _ = writeln!(
                s,
                "# IQM component: dimension {k}, {} top simplices",
                rows.len()
            );
            let width = coords.map_or(0, |c| c.dim);
            for &v in &piece.original {
                s.push('v');
                if width > 0 {
                    s.push(' ');
                    point(coords, v, width, &mut s);
                }
                s.push('\n');
            }
            for r in rows {
                s.push('s');
                for &x in r {
                    let _ = write!(s, " {x}");
                }
                s.push('\n');
            }
        }
    }
    s
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

/// Whether `name` is one of the files [`write_components`] writes: `component_<i>.off`,
/// `component_<i>.mesh`, `component_<i>.simplices` or `gluing.json`.
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
    matches!(ext, "off" | "mesh" | "simplices")
        && !i.is_empty()
        && i.bytes().all(|b| b.is_ascii_digit())
}

/// Writes every component of `dec` into `dir` (created if missing) and `gluing.json`; returns
/// the paths written, components first. `coords` are the original complex's coordinates.
pub fn write_components(
    dec: &Decomposition,
    coords: Option<&Coords>,
    dir: &Path,
) -> Result<Vec<PathBuf>, WriteError> {
    let fail = |path: &Path| {
        let path = path.to_path_buf();
        move |source| WriteError { path, source }
    };
    std::fs::create_dir_all(dir).map_err(fail(dir))?;
    let mut names = Vec::with_capacity(dec.components.len());
    let mut paths = Vec::with_capacity(dec.components.len() + 1);
    for (i, piece) in dec.components.iter().enumerate() {
        let format = format_for(piece.dimension, coords);
        let ext = match format {
            Format::Off => "off",
            Format::Medit => "mesh",
            Format::Simplices => "simplices",
        };
        let name = format!("component_{i}.{ext}");
        let path = dir.join(&name);
        std::fs::write(&path, component_text(piece, coords, format)).map_err(fail(&path))?;
        names.push(name);
        paths.push(path);
    }
    let path = dir.join("gluing.json");
    let json = gluing_json(dec, coords, &names);
    let text = serde_json::to_string_pretty(&json).expect("JSON of numbers and strings");
    std::fs::write(&path, text + "\n").map_err(fail(&path))?;
    paths.push(path);
    Ok(paths)
}
