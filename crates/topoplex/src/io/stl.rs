//! STL (`.stl`, ASCII and binary), read here; binary written with the `stl_io` crate and
//! ASCII written here (`stl_io` writes binary only).
//!
//! STL lists triangles, each with its own three corner points, and shares no vertices.
//!
//! Reading: corners with **exactly equal coordinates** (the same 32-bit floats, bit for bit) are
//! welded into one vertex; vertices are numbered in order of first appearance. Nothing closer
//! than equal is welded, so nearly equal corners stay distinct vertices. Coordinates are 32-bit
//! floats, widened to `f64` exactly. Normals are checked as numbers and ignored. A facet whose
//! corners weld together is a simplex that repeats a vertex (refused by the complex model,
//! naming the facet by its line in ASCII, its position in binary). An empty solid is refused
//! (no vertices).
//! * A file is binary when its size is 84 + 50 × the triangle count at byte 80, whatever its
//!   header says; else ASCII when it starts with `solid`; else binary whose size disagrees with
//!   its count, refused with both (a truncated file says so).
//! * ASCII: `solid name`, then facets (`facet normal x y z`, `outer loop`, three `vertex x y z`,
//!   `endloop`, `endfacet`), then `endsolid name`; keywords in any case; **every solid** of a
//!   file is read (several solids in one file are common), their corners welded together.
//!   With several solids, each triangle gets the label `stl:solid` (`i32`, on the listed
//!   simplices): the index of its solid's name (the rest of the `solid` line, trimmed) in order
//!   of first appearance, named by a label name. A file of one solid has no label: its name
//!   names the file, like a comment, and is not kept.
//!   A number that a 32-bit float can hold only as infinity or 0 (`1e39`, `1e-50`) is refused
//!   (the check shared by all readers, `io::parse_real`), as is anything out of order,
//!   naming the line and what was expected.
//!
//! Storage while reading: the coordinates, the listing and a hash map from corner bits to
//! vertex ids (about 20 bytes a vertex), all reserved fallibly; the file's bytes are read in
//! place. Time: linear in the file.
//!
//! Writing: refused unless the complex is a set of triangles covering every vertex (no edge,
//! tetrahedron or isolated vertex), with at most 3 coordinates per vertex that are exactly
//! 32-bit floats and pairwise distinct (else they would read back welded). Normals are the
//! normalised cross product of the winding (zero for a degenerate triangle). ASCII coordinates
//! are the shortest decimals that read back to the same 32-bit float. ASCII writes one solid
//! `topoplex`, or with `stl:solid` one solid per run of triangles of one label, named by the
//! label's name (and an empty second solid when there is one run, so that the file reads back
//! labelled); a label without a name, or a name with control characters or outer blanks, is
//! refused. Binary STL holds no attribute.

use std::collections::HashMap;

use stl_io::{Normal, Triangle, Vertex};

use super::bytes::Input;
use super::write::{check_coord_dim, show, vertex_count};
use super::{
    Coords, Float, RawInput, ReadErrorKind, echo, no_room, parse_real, syntax, try_with_capacity,
};
use crate::complex::table;
use crate::complex::{Attribute, LabelName, Location};
use crate::io::Res;

/// Corners welded as they come: each distinct corner (by its bits) gets the next id.
struct Welder {
    ids: HashMap<[u32; 3], u32>,
    coords: Vec<f64>,
    raw: RawInput,
}

impl Welder {
    /// Room for `triangles` facets (a bound the file's size gives).
    fn new(triangles: usize) -> Result<Welder, ReadErrorKind> {
        let mut ids = HashMap::new();
        // About one vertex for every two triangles in a closed mesh; more grow as needed.
        ids.try_reserve(triangles / 2 + 1)
            .map_err(|_| no_room("the corner index")(triangles / 2 * 20))?;
        let coords = try_with_capacity((triangles / 2 + 1) * 3, "the vertex coordinates")?;
        let mut raw = RawInput::new();
        raw.try_reserve(triangles, triangles * 3)?;
        Ok(Welder { ids, coords, raw })
    }

    /// The id of corner `p`, a new one when it was not seen before.
    fn corner(&mut self, p: [f32; 3]) -> Result<u32, ReadErrorKind> {
        let key = p.map(f32::to_bits);
        if let Some(&v) = self.ids.get(&key) {
            return Ok(v);
        }
        let v = u32::try_from(self.ids.len()).map_err(|_| syntax("more than 2^32 vertices"))?;
        self.ids
            .try_reserve(1)
            .map_err(|_| no_room("the corner index")(self.ids.len() * 20))?;
        self.ids.insert(key, v);
        table::try_extend(&mut self.coords, &p.map(f64::from))
            .map_err(no_room("the vertex coordinates"))?;
        Ok(v)
    }

    fn facet(&mut self, corners: [[f32; 3]; 3], line: u32) -> Result<(), ReadErrorKind> {
        let mut ids = [0u32; 3];
        for (v, p) in ids.iter_mut().zip(corners) {
            *v = self.corner(p)?;
        }
        self.raw.try_push(&ids, line)
    }

    fn into_raw(self) -> RawInput {
        let mut raw = self.raw;
        // Ids are below 2^32 (checked as they were made).
        raw.vertex_count = Some(self.ids.len() as u32);
        raw.coords = Some(Coords {
            dim: 3,
            data: self.coords,
        });
        raw
    }
}

/// Parses an STL file, welding exactly equal corners.
pub fn parse(bytes: &[u8]) -> Result<RawInput, (u32, ReadErrorKind)> {
    let declared = bytes
        .get(80..84)
        .map(|c| u32::from_le_bytes(c.try_into().unwrap()));
    let binary_size = declared.map(|n| 84 + 50 * u64::from(n));
    if binary_size == Some(bytes.len() as u64) {
        return binary(bytes).map_err(|k| (0, k));
    }
    let text = bytes.starts_with(b"solid") || bytes.starts_with(b"SOLID");
    // A binary file may start with `solid` too (many exporters write it in the header): one
    // with a NUL byte that is not ASCII gets the binary message below.
    if text {
        match ascii(bytes) {
            Err(_) if declared.is_some() && memchr::memchr(0, bytes).is_some() => {}
            r => return r,
        }
    }
    match (declared, binary_size) {
        (Some(n), Some(size)) => {
            let whole = (bytes.len() - 84) / 50;
            let what = if (bytes.len() as u64) < size {
                "truncated binary STL"
            } else {
                "binary STL with bytes after its last triangle"
            };
            Err((
                0,
                syntax(format!(
                    "{what}: the header declares {n} triangles (84 + 50 × {n} = {size} bytes) \
                     but the file has {} bytes ({whole} whole triangle(s)){}",
                    bytes.len(),
                    if text {
                        "; not ASCII either (it holds NUL bytes)"
                    } else {
                        "; not ASCII either (no 'solid' at the start)"
                    }
                )),
            ))
        }
        _ => Err((
            0,
            syntax(format!(
                "{} bytes: too short for binary STL (84-byte header) and no ASCII 'solid'",
                bytes.len()
            )),
        )),
    }
}

/// A binary STL of the right size: 80 bytes of header, the count, 50 bytes a triangle (normal,
/// three corners, attribute bytes), little-endian 32-bit floats.
fn binary(bytes: &[u8]) -> Result<RawInput, ReadErrorKind> {
    let body = &bytes[84..];
    let mut w = Welder::new(body.len() / 50)?;
    let f = |b: &[u8], k: usize| f32::from_le_bytes(b[4 * k..4 * k + 4].try_into().unwrap());
    for t in body.chunks_exact(50) {
        let corner = |c: usize| [f(t, 3 * c + 3), f(t, 3 * c + 4), f(t, 3 * c + 5)];
        w.facet([corner(0), corner(1), corner(2)], 0)?;
    }
    Ok(w.into_raw())
}

/// An ASCII STL: every solid in the file.
fn ascii(bytes: &[u8]) -> Res<RawInput> {
    // Each facet takes at least 7 lines of at least 6 bytes.
    let mut w = Welder::new(bytes.len() / 42 + 1).map_err(|k| (0, k))?;
    let mut inp = Input::new(bytes);
    let mut solids = 0usize;
    // The distinct solid names in order, and where each solid starts with its label.
    let mut names: Vec<String> = Vec::new();
    let mut starts: Vec<(usize, i32)> = Vec::new();
    while let Some((tok, l)) = inp.token() {
        if !tok.eq_ignore_ascii_case("solid") {
            let what = if solids == 0 {
                "'solid'"
            } else {
                "'solid' (another solid) or the end of the file"
            };
            return Err((l, syntax(format!("expected {what}, found '{}'", echo(tok)))));
        }
        let name = String::from_utf8_lossy(inp.rest_of_line())
            .trim()
            .to_string();
        let label = match names.iter().position(|n| *n == name) {
            Some(i) => i,
            None => {
                names.push(name);
                names.len() - 1
            }
        };
        starts.push((w.raw.simplex_count(), label as i32));
        solids += 1;
        loop {
            let (tok, l) = inp.expect_token("'facet' or 'endsolid'")?;
            if tok.eq_ignore_ascii_case("endsolid") {
                // Its name, if any, ends the line.
                if inp.line == l {
                    inp.rest_of_line();
                }
                break;
            }
            let facet_line = l;
            if !tok.eq_ignore_ascii_case("facet") {
                return Err((
                    l,
                    syntax(format!(
                        "expected 'facet' or 'endsolid', found '{}'",
                        echo(tok)
                    )),
                ));
            }
            let corners = facet_corners(&mut inp)?;
            w.facet(corners, facet_line).map_err(|k| (facet_line, k))?;
        }
    }
    let mut raw = w.into_raw();
    if solids >= 2 {
        solid_labels(&mut raw, &starts, names)?;
    }
    Ok(raw)
}

/// A facet after its `facet` keyword, through `endfacet`: the normal (read, checked, not
/// kept) and the three corners of its loop.
fn facet_corners(inp: &mut Input) -> Res<[[f32; 3]; 3]> {
    keyword(inp, "normal")?;
    for _ in 0..3 {
        number(inp, "a normal component")?;
    }
    keyword(inp, "outer")?;
    keyword(inp, "loop")?;
    let mut corners = [[0f32; 3]; 3];
    for (k, c) in corners.iter_mut().enumerate() {
        let (tok, l) = inp.expect_token("'vertex'")?;
        if !tok.eq_ignore_ascii_case("vertex") {
            return Err((
                l,
                syntax(format!(
                    "expected 'vertex' (corner {} of 3 of a facet), found '{}'",
                    k + 1,
                    echo(tok)
                )),
            ));
        }
        for x in c.iter_mut() {
            *x = number(inp, "a vertex coordinate")?;
        }
    }
    let (tok, l) = inp.expect_token("'endloop'")?;
    if tok.eq_ignore_ascii_case("vertex") {
        return Err((
            l,
            syntax("a facet with more than 3 vertices (STL facets are triangles)"),
        ));
    }
    if !tok.eq_ignore_ascii_case("endloop") {
        return Err((
            l,
            syntax(format!("expected 'endloop', found '{}'", echo(tok))),
        ));
    }
    keyword(inp, "endfacet")?;
    Ok(corners)
}

/// Two solids or more: each facet labelled with its solid's name (the distinct names in order,
/// as label names), the solids starting at the listing indices of `starts`.
fn solid_labels(raw: &mut RawInput, starts: &[(usize, i32)], names: Vec<String>) -> Res<()> {
    let m = raw.simplex_count();
    let mut labels = try_with_capacity(m, "the solid labels").map_err(|k| (0, k))?;
    for (k, &(start, label)) in starts.iter().enumerate() {
        let end = starts.get(k + 1).map_or(m, |s| s.0);
        labels.extend(std::iter::repeat_n(label, end - start));
    }
    raw.attributes
        .insert(Attribute::labels(SOLID, Location::Listed, labels));
    for (label, name) in names.into_iter().enumerate() {
        raw.attributes.add_label_name(LabelName {
            attribute: SOLID.to_string(),
            dimension: None,
            label: label as i64,
            name,
        });
    }
    Ok(())
}

/// The label of each triangle's solid in an ASCII file of several solids (the index of the
/// solid's name in order of first appearance, named by a [`LabelName`]).
pub(crate) const SOLID: &str = "stl:solid";

/// The next token, which must be `word` (any case).
fn keyword(inp: &mut Input, word: &str) -> Res<()> {
    let (tok, l) = inp.expect_token(&format!("'{word}'"))?;
    if tok.eq_ignore_ascii_case(word) {
        Ok(())
    } else {
        Err((
            l,
            syntax(format!("expected '{word}', found '{}'", echo(tok))),
        ))
    }
}

/// The next token as a 32-bit float (`what` names it).
fn number(inp: &mut Input, what: &str) -> Res<f32> {
    let (tok, l) = inp.expect_token(what)?;
    // Exact: the value was rounded to a 32-bit float once.
    parse_real(tok, what, Float::F32)
        .map(|x| x as f32)
        .map_err(|k| (l, k))
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
                     32-bit floats; use .ply, .vtk or .msh to keep it, or `convert --round-f32` to round)"
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

/// The solid names of each triangle from the `stl:solid` labels, checked: every label named,
/// each name a line that reads back as itself.
fn solid_names(raw: &RawInput) -> Result<Option<Vec<&str>>, String> {
    let Some(a) = raw.attributes.get(SOLID, Location::Listed) else {
        return Ok(None);
    };
    let mut out = Vec::with_capacity(raw.simplex_count());
    for i in 0..raw.simplex_count() {
        let label = a.label(i).unwrap_or(i64::MIN);
        let Some(name) = raw.attributes.label_name(SOLID, 2, label) else {
            return Err(format!(
                "attribute {}: triangle #{i} has label {label}, which has no name to write",
                a.describe()
            ));
        };
        if name.trim() != name || name.chars().any(char::is_control) {
            return Err(format!(
                "attribute {}: solid name '{}' would not read back as itself",
                a.describe(),
                echo(name)
            ));
        }
        out.push(name);
    }
    Ok(Some(out))
}

/// Writes `raw` as ASCII STL: one solid `topoplex`, or with `stl:solid` labels one solid per
/// run of triangles of one label, named by it (an empty second solid when there is one run,
/// so that the file has several solids and reads back labelled).
pub(crate) fn write_ascii(raw: &RawInput, out: &mut Vec<u8>) -> Result<(), String> {
    let names = solid_names(raw)?;
    let tris = triangles(raw)?;
    let name = |i: usize| names.as_ref().map_or("topoplex", |n| n[i]);
    let mut open: Option<&str> = None;
    let mut solids = 0;
    for (i, t) in tris.into_iter().enumerate() {
        if open != Some(name(i)) {
            if let Some(n) = open {
                out.extend_from_slice(format!("endsolid {n}\n").as_bytes());
            }
            out.extend_from_slice(format!("solid {}\n", name(i)).as_bytes());
            open = Some(name(i));
            solids += 1;
        }
        out.extend_from_slice(b"facet normal");
        push_xyz(out, normal(t));
        out.extend_from_slice(b"outer loop\n");
        for p in t {
            out.extend_from_slice(b"vertex");
            push_xyz(out, p);
        }
        out.extend_from_slice(b"endloop\nendfacet\n");
    }
    let last = open.unwrap_or("topoplex");
    if open.is_none() {
        out.extend_from_slice(b"solid topoplex\n");
        solids += 1;
    }
    out.extend_from_slice(format!("endsolid {last}\n").as_bytes());
    if names.is_some() && solids < 2 {
        out.extend_from_slice(format!("solid {last}\nendsolid {last}\n").as_bytes());
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn facet(a: &str, b: &str, c: &str) -> String {
        format!(
            "facet normal 0 0 1\nouter loop\nvertex {a}\nvertex {b}\nvertex {c}\nendloop\nendfacet\n"
        )
    }

    fn err(bytes: &[u8]) -> String {
        let (line, kind) = parse(bytes).unwrap_err();
        format!("{line}: {kind}")
    }

    #[test]
    fn every_solid_of_an_ascii_file_is_read_and_welded() {
        let text = format!(
            "solid a\n{}endsolid a\nsolid b\n{}{}endsolid b\n",
            facet("0 0 0", "1 0 0", "0 1 0"),
            facet("1 0 0", "0 1 0", "1 1 0"),
            facet("5 5 5", "6 5 5", "5 6 5"),
        );
        let raw = parse(text.as_bytes()).unwrap();
        assert_eq!(raw.ids, [0, 1, 2, 1, 2, 3, 4, 5, 6]);
        assert_eq!(raw.vertex_count, Some(7));
        assert_eq!(&raw.coords.unwrap().data[9..12], &[1.0, 1.0, 0.0]);
        // Keywords in any case, a solid without a name, and no final newline.
        let upper = format!("SOLID\n{}ENDSOLID", facet("0 0 0", "1 0 0", "0 1 0"))
            .replace("vertex", "VERTEX");
        assert_eq!(parse(upper.as_bytes()).unwrap().ids, [0, 1, 2]);
    }

    #[test]
    fn several_solids_label_their_triangles_by_name() {
        let f = facet("0 0 0", "1 0 0", "0 1 0");
        let g = facet("0 0 0", "1 0 0", "0 0 1");
        let text = format!(
            "solid a\n{f}{g}endsolid a\nsolid  b c \r\n{g}endsolid\nsolid a\n{f}endsolid a\n"
        );
        let raw = parse(text.as_bytes()).unwrap();
        let at = &raw.attributes;
        let a = at.get(SOLID, Location::Listed).unwrap();
        assert_eq!(
            (0..4).map(|i| a.label(i).unwrap()).collect::<Vec<_>>(),
            [0, 0, 1, 0]
        );
        assert_eq!(at.label_name(SOLID, 2, 1), Some("b c"));
        // Written back as solids, read back the same.
        let mut out = Vec::new();
        write_ascii(&raw, &mut out).unwrap();
        let back = parse(&out).unwrap();
        assert!(
            back.attributes.bits_eq(at),
            "{}",
            String::from_utf8_lossy(&out)
        );
        assert_eq!(back.ids, raw.ids);
        // One solid: no label.
        let one = parse(format!("solid a\n{f}endsolid a\n").as_bytes()).unwrap();
        assert!(one.attributes.is_empty());
    }

    #[test]
    fn ascii_numbers_a_32_bit_float_cannot_hold_are_refused() {
        for (tok, what) in [
            ("1e-50", "too small for a 32-bit float"),
            ("1e39", "too large for a 32-bit float"),
            ("1e-400", "too small for a 32-bit float"),
        ] {
            let text = format!(
                "solid\n{}endsolid\n",
                facet("0 0 0", &format!("1 {tok} 0"), "0 1 0")
            );
            let e = err(text.as_bytes());
            assert_eq!(
                e,
                format!(
                    "5: number '{tok}' is {what} (a vertex coordinate; it would become {})",
                    if what.contains("small") {
                        "0"
                    } else {
                        "infinite"
                    }
                )
            );
        }
        // Normals are numbers too.
        let text = format!("solid\n{}endsolid\n", facet("0 0 0", "1 0 0", "0 1 0"))
            .replace("normal 0 0 1", "normal 0 0 1e39");
        assert!(
            err(text.as_bytes()).starts_with(
                "2: number '1e39' is too large for a 32-bit float (a normal component"
            )
        );
        // Subnormal 32-bit floats, nan and inf are read.
        let text = format!(
            "solid\n{}endsolid\n",
            facet("1e-40 0 0", "nan 0 0", "inf 0 0")
        );
        let d = parse(text.as_bytes()).unwrap().coords.unwrap().data;
        assert_eq!(d[0], f64::from(1e-40f32));
        assert!(d[3].is_nan() && d[6].is_infinite());
    }

    #[test]
    fn ascii_structure_errors_name_the_line_and_what_was_expected() {
        let one = facet("0 0 0", "1 0 0", "0 1 0");
        let cases = [
            (
                format!("solid\n{one}"),
                "9: file ends early; expected 'facet' or 'endsolid'",
            ),
            (
                format!("solid\n{one}endsolid\nxyz\n"),
                "10: expected 'solid' (another solid) or the end of the file, found 'xyz'",
            ),
            (
                format!("solid\n{}endsolid\n", one.replace("outer loop", "outer")),
                "4: expected 'loop', found 'vertex'",
            ),
            (
                format!(
                    "solid\n{}endsolid\n",
                    one.replace("endloop", "vertex 1 1 0\nendloop")
                ),
                "7: a facet with more than 3 vertices (STL facets are triangles)",
            ),
            (
                format!(
                    "solid\n{}endsolid\n",
                    one.replace("vertex 1 0 0", "vertex 1 0")
                ),
                "6: non-numeric token 'vertex' where a vertex coordinate was expected",
            ),
        ];
        for (text, want) in &cases {
            assert_eq!(err(text.as_bytes()), *want);
        }
    }

    fn binary_file(declared: u32, triangles: usize) -> Vec<u8> {
        let mut b = vec![0u8; 80];
        b.extend_from_slice(&declared.to_le_bytes());
        for t in 0..triangles {
            b.extend_from_slice(&[0u8; 12]);
            for p in [[0f32, 0., 0.], [1., 0., 0.], [0., 1. + t as f32, 0.]] {
                for x in p {
                    b.extend_from_slice(&x.to_le_bytes());
                }
            }
            b.extend_from_slice(&[0u8; 2]);
        }
        b
    }

    #[test]
    fn a_binary_file_whose_size_disagrees_with_its_count_says_so_with_the_counts() {
        assert_eq!(parse(&binary_file(2, 2)).unwrap().ids, [0, 1, 2, 0, 1, 3]);
        assert_eq!(
            err(&binary_file(3, 2)),
            "0: truncated binary STL: the header declares 3 triangles (84 + 50 × 3 = 234 bytes) \
             but the file has 184 bytes (2 whole triangle(s)); not ASCII either (no 'solid' at the \
             start)"
        );
        let mut cut = binary_file(2, 2);
        cut.truncate(150);
        assert!(err(&cut).contains("the file has 150 bytes (1 whole triangle(s))"));
        assert!(err(&binary_file(1, 2)).starts_with(
            "0: binary STL with bytes after its last triangle: the header declares 1 triangles"
        ));
        // A header starting with `solid`, truncated: still the binary message.
        let mut solid = binary_file(3, 2);
        solid[..6].copy_from_slice(b"solid ");
        assert!(
            err(&solid).ends_with("not ASCII either (it holds NUL bytes)"),
            "{}",
            err(&solid)
        );
        // ... and of the right size, read as binary.
        let mut solid = binary_file(2, 2);
        solid[..6].copy_from_slice(b"solid ");
        assert_eq!(parse(&solid).unwrap().ids, [0, 1, 2, 0, 1, 3]);
    }
}
