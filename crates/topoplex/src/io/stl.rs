//! STL (`.stl`, ASCII and binary), read with the `stl_io` crate, binary written with it and
//! ASCII written here (`stl_io` writes binary only).
//!
//! STL lists triangles, each with its own three corner points, and shares no vertices.
//!
//! Reading: corners with **exactly equal coordinates** (the same 32-bit floats, bit for bit) are
//! welded into one vertex; vertices are numbered in order of first appearance. Nothing closer
//! than equal is welded, so nearly equal corners stay distinct vertices. Coordinates are 32-bit
//! floats, widened to `f64` exactly. Normals are ignored. A facet whose corners weld together is
//! a simplex that repeats a vertex (refused by the complex model, naming the facet by its
//! position). `stl_io` reports errors without a line; an empty solid is refused (no vertices).
//! A file is binary when its size is 84 + 50 × the triangle count at byte 80, whatever its
//! header says, and ASCII otherwise.
//!
//! Writing: refused unless the complex is a set of triangles covering every vertex (no edge,
//! tetrahedron or isolated vertex), with at most 3 coordinates per vertex that are exactly
//! 32-bit floats and pairwise distinct (else they would read back welded). Normals are the
//! normalised cross product of the winding (zero for a degenerate triangle). ASCII coordinates
//! are the shortest decimals that read back to the same 32-bit float.

use std::borrow::Cow;
use std::io::Cursor;

use stl_io::{Normal, Triangle, Vertex};

use super::write::{check_coord_dim, show, vertex_count};
use super::{Coords, RawInput, ReadErrorKind, no_room, syntax, try_with_capacity};
use crate::complex::table::headroom;

/// The bytes as `stl_io` tells them apart: it takes any file starting with `solid ` for ASCII
/// and anything else for binary. A binary file whose 80-byte header starts with `solid` (many
/// exporters write one) gets a blank header; an ASCII `solid` with no name gets a space.
fn for_stl_io(bytes: &[u8]) -> Result<Cow<'_, [u8]>, ReadErrorKind> {
    let binary_size = bytes
        .get(80..84)
        .map(|c| 84 + 50 * u64::from(u32::from_le_bytes(c.try_into().unwrap())));
    if binary_size == Some(bytes.len() as u64) {
        if bytes.starts_with(b"solid") {
            let mut b = try_with_capacity(bytes.len(), "a copy of the file")?;
            b.extend_from_slice(bytes);
            b[..80].fill(0);
            return Ok(Cow::Owned(b));
        }
    } else if bytes.starts_with(b"solid") && matches!(bytes.get(5), Some(b'\n' | b'\r')) {
        let mut b = try_with_capacity(bytes.len() + 1, "a copy of the file")?;
        b.extend_from_slice(b"solid ");
        b.extend_from_slice(&bytes[5..]);
        return Ok(Cow::Owned(b));
    }
    Ok(Cow::Borrowed(bytes))
}

/// Parses an STL file, welding exactly equal corners.
pub fn parse(bytes: &[u8]) -> Result<RawInput, (u32, ReadErrorKind)> {
    if bytes.len() < 84 && !bytes.starts_with(b"solid") {
        return Err((
            0,
            syntax(format!(
                "{} bytes: too short for binary STL (84-byte header) and no ASCII 'solid'",
                bytes.len()
            )),
        ));
    }
    let bytes = for_stl_io(bytes).map_err(|k| (0, k))?;
    // The crate's arrays are allocated infallibly: their peak is probed first (3 times the
    // file; reading and normalising a 980,000-triangle grid peaks at 2.7 × binary, 1.9 × ASCII
    // STL), so that a file too large for memory is refused rather than an abort.
    headroom(bytes.len().saturating_mul(3)).map_err(|b| (0, no_room("reading STL")(b)))?;
    let mesh =
        stl_io::read_stl(&mut Cursor::new(bytes)).map_err(|e| (0, syntax(format!("STL: {e}"))))?;
    let mut raw = RawInput::new();
    let n =
        u32::try_from(mesh.vertices.len()).map_err(|_| (0, syntax("more than 2^32 vertices")))?;
    raw.vertex_count = Some(n);
    let mut data =
        try_with_capacity(mesh.vertices.len() * 3, "the vertex coordinates").map_err(|k| (0, k))?;
    data.extend(mesh.vertices.iter().flat_map(|v| v.0.map(f64::from)));
    raw.coords = Some(Coords { dim: 3, data });
    raw.try_reserve(mesh.faces.len(), mesh.faces.len() * 3)
        .map_err(|k| (0, k))?;
    for f in &mesh.faces {
        // Ids are below n, which fits in u32.
        raw.push(&f.vertices.map(|v| v as u32), 0);
    }
    Ok(raw)
}

/// The vertex's coordinates as 32-bit floats, or why they are not exactly that.
fn corner(raw: &RawInput, v: u32) -> Result<[f32; 3], String> {
    let mut p = [0f32; 3];
    if let Some(c) = &raw.coords {
        for (k, x) in p.iter_mut().enumerate().take(c.dim) {
            let want = c.data[v as usize * c.dim + k];
            *x = want as f32;
            if f64::from(*x).to_bits() != want.to_bits() {
                return Err(format!(
                    "vertex {v} coordinate {want:e} is not exactly a 32-bit float (STL stores \
                     32-bit floats; use .ply, .vtk or .msh to keep it)"
                ));
            }
        }
    }
    Ok(p)
}

/// Checks that STL can hold `raw` and returns the corners of each vertex.
fn corners(raw: &RawInput) -> Result<Vec<[f32; 3]>, String> {
    check_coord_dim(raw, 3)?;
    if let Some(i) = (0..raw.simplex_count()).find(|&i| raw.simplex(i).len() != 3) {
        let s = raw.simplex(i);
        return Err(format!(
            "simplex #{i} {} has dimension {}; STL holds triangles only",
            show(s),
            s.len() - 1
        ));
    }
    let n = vertex_count(raw);
    let mut used = vec![false; n];
    for &v in &raw.ids {
        used[v as usize] = true;
    }
    if let Some(v) = used.iter().position(|&u| !u) {
        return Err(format!(
            "vertex {v} is in no triangle; STL lists triangles only"
        ));
    }
    let points = (0..n as u32)
        .map(|v| corner(raw, v))
        .collect::<Result<Vec<_>, _>>()?;
    let mut seen = std::collections::HashMap::with_capacity(n);
    for (v, p) in points.iter().enumerate() {
        if let Some(w) = seen.insert(p.map(f32::to_bits), v) {
            return Err(format!(
                "vertices {w} and {v} have the same coordinates; STL would weld them into one"
            ));
        }
    }
    Ok(points)
}

fn normal(t: [[f32; 3]; 3]) -> [f32; 3] {
    let d = |a: [f32; 3], b: [f32; 3]| [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
    let (u, w) = (d(t[0], t[1]), d(t[0], t[2]));
    let n = [
        u[1] * w[2] - u[2] * w[1],
        u[2] * w[0] - u[0] * w[2],
        u[0] * w[1] - u[1] * w[0],
    ];
    let len = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
    if len > 0.0 && len.is_finite() {
        n.map(|x| x / len)
    } else {
        [0.0; 3]
    }
}

fn triangles(raw: &RawInput) -> Result<Vec<[[f32; 3]; 3]>, String> {
    let points = corners(raw)?;
    Ok((0..raw.simplex_count())
        .map(|i| {
            let s = raw.simplex(i);
            [s[0], s[1], s[2]].map(|v| points[v as usize])
        })
        .collect())
}

/// Writes `raw` as binary STL (through `stl_io`).
pub(crate) fn write_binary(raw: &RawInput, out: &mut Vec<u8>) -> Result<(), String> {
    let tris: Vec<Triangle> = triangles(raw)?
        .into_iter()
        .map(|t| Triangle {
            normal: Normal::new(normal(t)),
            vertices: t.map(Vertex::new),
        })
        .collect();
    stl_io::write_stl(out, tris.iter()).map_err(|e| format!("STL writer: {e}"))
}

fn push_f32(out: &mut Vec<u8>, x: f32) {
    let mut buf = ryu::Buffer::new();
    let s = buf.format(x);
    out.extend_from_slice(s.strip_suffix(".0").unwrap_or(s).as_bytes());
}

fn push_xyz(out: &mut Vec<u8>, p: [f32; 3]) {
    for x in p {
        out.push(b' ');
        push_f32(out, x);
    }
    out.push(b'\n');
}

/// Writes `raw` as ASCII STL.
pub(crate) fn write_ascii(raw: &RawInput, out: &mut Vec<u8>) -> Result<(), String> {
    out.extend_from_slice(b"solid topoplex\n");
    for t in triangles(raw)? {
        out.extend_from_slice(b"facet normal");
        push_xyz(out, normal(t));
        out.extend_from_slice(b"outer loop\n");
        for p in t {
            out.extend_from_slice(b"vertex");
            push_xyz(out, p);
        }
        out.extend_from_slice(b"endloop\nendfacet\n");
    }
    out.extend_from_slice(b"endsolid topoplex\n");
    Ok(())
}
