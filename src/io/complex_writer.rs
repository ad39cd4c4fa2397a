//! A minimal writer of a whole [`Complex`] by file extension, for `topoplex simplify` until the
//! format writers of issue 15 land: `.off`, `.obj` (dimension ≤ 2), `.mesh` (dimension ≤ 3,
//! coordinates of 2 or 3 numbers) and `.simplices` (anything). Top simplices are written in
//! [`Complex::tops_as_given`] order with their winding; every vertex is declared, so isolated
//! vertices survive. Numbers are written in Rust's shortest round-trip form.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use crate::complex::Complex;

/// Why a complex was not written.
#[derive(Debug, thiserror::Error)]
pub enum ComplexWriteError {
    /// The extension is none of `.off`, `.obj`, `.mesh`, `.simplices`.
    #[error("{}: unknown output extension (expected .off, .obj, .mesh or .simplices)", .0.display())]
    UnknownExtension(PathBuf),
    /// The format cannot hold the complex (its dimension or its coordinates).
    #[error("{}: {why}", .path.display())]
    Unsupported {
        /// The output path.
        path: PathBuf,
        /// What the format lacks.
        why: String,
    },
    /// The file could not be written.
    #[error("{}: cannot write: {source}", .path.display())]
    Io {
        /// The output path.
        path: PathBuf,
        /// The system's error.
        source: std::io::Error,
    },
}

/// The formats by extension.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Format {
    Off,
    Obj,
    Medit,
    Simplices,
}

fn format_of(path: &Path) -> Result<Format, ComplexWriteError> {
    match path.extension().and_then(|e| e.to_str()) {
        Some("off") => Ok(Format::Off),
        Some("obj") => Ok(Format::Obj),
        Some("mesh") => Ok(Format::Medit),
        Some("simplices") => Ok(Format::Simplices),
        _ => Err(ComplexWriteError::UnknownExtension(path.to_path_buf())),
    }
}

/// Checks, before any work, that `path` has a known extension and that the format can hold a
/// complex of dimension `dim` with `coord_dim` numbers per vertex.
pub fn check_output(path: &Path, dim: usize, coord_dim: usize) -> Result<(), ComplexWriteError> {
    let unsupported = |why: &str| ComplexWriteError::Unsupported {
        path: path.to_path_buf(),
        why: why.to_string(),
    };
    match format_of(path)? {
        Format::Off | Format::Obj if dim > 2 => Err(unsupported(
            "this format holds complexes of dimension at most 2 (use .mesh or .simplices)",
        )),
        Format::Medit if dim > 3 => Err(unsupported(
            "MEDIT holds complexes of dimension at most 3 (use .simplices)",
        )),
        Format::Medit if !(2..=3).contains(&coord_dim) => Err(unsupported(
            "MEDIT needs 2 or 3 coordinates per vertex (use .simplices)",
        )),
        _ => Ok(()),
    }
}

/// Writes `c` to `path` in the format its extension names.
pub fn write_complex(c: &Complex, path: &Path) -> Result<(), ComplexWriteError> {
    check_output(path, c.dimension(), c.coords().map_or(0, |k| k.dim))?;
    let text = match format_of(path)? {
        Format::Off => off(c),
        Format::Obj => obj(c),
        Format::Medit => medit(c),
        Format::Simplices => simplices(c),
    };
    std::fs::write(path, text).map_err(|source| ComplexWriteError::Io {
        path: path.to_path_buf(),
        source,
    })
}

fn point(c: &Complex, v: u32, out: &mut String) {
    if let Some(k) = c.coords() {
        for (i, x) in k.data[v as usize * k.dim..(v as usize + 1) * k.dim]
            .iter()
            .enumerate()
        {
            if i > 0 {
                out.push(' ');
            }
            let _ = write!(out, "{x}");
        }
    }
}

fn ids(s: &[u32], base: u32, out: &mut String) {
    for (i, v) in s.iter().enumerate() {
        if i > 0 {
            out.push(' ');
        }
        let _ = write!(out, "{}", v + base);
    }
}

/// The listed top simplices of dimension ≥ 1 (isolated vertices are declared as vertices).
fn tops(c: &Complex) -> impl Iterator<Item = &[u32]> {
    c.tops_as_given()
        .map(|(_, _, _, s)| s)
        .filter(|s| s.len() > 1)
}

fn off(c: &Complex) -> String {
    let mut s = String::new();
    let k = c.coords().map_or(3, |k| k.dim);
    if k == 3 {
        s.push_str("OFF\n");
    } else {
        let _ = writeln!(s, "nOFF\n{k}");
    }
    let _ = writeln!(s, "{} {} 0", c.vertex_count(), tops(c).count());
    for v in 0..c.vertex_count() {
        if c.coords().is_some() {
            point(c, v, &mut s);
        } else {
            s.push_str(&vec!["0"; k].join(" "));
        }
        s.push('\n');
    }
    for t in tops(c) {
        let _ = write!(s, "{} ", t.len());
        ids(t, 0, &mut s);
        s.push('\n');
    }
    s
}

fn obj(c: &Complex) -> String {
    let mut s = String::new();
    for v in 0..c.vertex_count() {
        s.push('v');
        if c.coords().is_some() {
            s.push(' ');
            point(c, v, &mut s);
        } else {
            s.push_str(" 0 0 0");
        }
        s.push('\n');
    }
    for t in tops(c) {
        s.push_str(if t.len() == 3 { "f " } else { "l " });
        ids(t, 1, &mut s);
        s.push('\n');
    }
    s
}

fn medit(c: &Complex) -> String {
    let k = c.coords().map_or(3, |k| k.dim);
    let mut s = format!("MeshVersionFormatted 2\nDimension {k}\n");
    let _ = writeln!(s, "Vertices\n{}", c.vertex_count());
    for v in 0..c.vertex_count() {
        point(c, v, &mut s);
        s.push_str(" 0\n");
    }
    for (p, name) in [(1, "Edges"), (2, "Triangles"), (3, "Tetrahedra")] {
        let n = tops(c).filter(|t| t.len() == p + 1).count();
        if n == 0 {
            continue;
        }
        let _ = writeln!(s, "{name}\n{n}");
        for t in tops(c).filter(|t| t.len() == p + 1) {
            ids(t, 1, &mut s);
            s.push_str(" 0\n");
        }
    }
    s.push_str("End\n");
    s
}

fn simplices(c: &Complex) -> String {
    let mut s = String::new();
    for v in 0..c.vertex_count() {
        s.push('v');
        if c.coords().is_some() {
            s.push(' ');
            point(c, v, &mut s);
        }
        s.push('\n');
    }
    for t in tops(c) {
        s.push_str("s ");
        ids(t, 0, &mut s);
        s.push('\n');
    }
    s
}
