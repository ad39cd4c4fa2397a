//! Reader for Geomview OFF files (`.off`), ASCII only.
//!
//! Accepted layout, as Geomview specifies it:
//!
//! ```text
//! [ST][C][N][4][n]OFF        header keyword
//! [Ndim]                     only for nOFF: the embedding dimension
//! NVertices NFaces NEdges    NEdges must be present (a non-negative integer) but is ignored
//! vertices                   coordinates, then normal (N), colour (C), texture (ST)
//! faces                      k i1 .. ik [colour]
//! ```
//!
//! * The reader is token-based: items may share a line or spread over several lines (the header
//!   may be followed by the counts on the same line). The one exception is a face colour, which
//!   Geomview defines as the rest of the line holding the face's last vertex id: it must be 0,
//!   1, 3 or 4 numbers (integers or floats), which are checked to be numbers and then ignored.
//! * Vertex coordinates: 3 per vertex; 4 for `4OFF`; `Ndim` for `nOFF`; `Ndim + 1` for `4nOFF`
//!   (the homogeneous component is kept as read). Normals (`N`) have 3 numbers, or as many as
//!   the vertex coordinates for `nOFF`; colours (`C`) 4 numbers; texture coordinates (`ST`) 2.
//!   Only the coordinates are kept.
//! * Numbers are parsed as `f64`; `nan`, `inf` and `infinity` are accepted, since topology does
//!   not use coordinates.
//! * A face with k = 1, 2, 3 ids is a vertex, an edge, a triangle. k > 3 is
//!   [`ReadErrorKind::Polygon`], k = 0 an error. Ids are 0-based and must fit in 32 bits; a
//!   negative id is [`ReadErrorKind::NegativeId`]. Each face is recorded at the line of its k.
//! * `#` starts a comment anywhere; blank lines, tabs, CRLF and a missing final newline are fine.
//! * Errors: missing or unknown header, `OFF BINARY`, non-numeric or overflowing numbers, files
//!   ending before the declared vertices or faces, and any non-comment content after the last
//!   face. When the file ends early the error names the file's last line.
//!
//! Ids beyond the vertex count and repeated ids are left to the complex model.

use super::{
    Coords, IntError, RawInput, ReadErrorKind, Tokens, capped, parse_count, parse_f64, parse_id,
    parse_integer, syntax,
};

/// The prefixes of an OFF header keyword.
#[derive(Debug, Default, Clone, Copy)]
struct Header {
    texture: bool,
    colour: bool,
    normals: bool,
    four: bool,
    ndim: bool,
}

impl Header {
    fn parse(tok: &str) -> Option<Header> {
        let mut s = tok;
        let mut flag = |prefix: &str| match s.strip_prefix(prefix) {
            Some(rest) => {
                s = rest;
                true
            }
            None => false,
        };
        let h = Header {
            texture: flag("ST"),
            colour: flag("C"),
            normals: flag("N"),
            four: flag("4"),
            ndim: flag("n"),
        };
        (s == "OFF").then_some(h)
    }
}

/// Parses OFF text; errors carry the 1-based line.
pub fn parse(text: &str) -> Result<RawInput, (u32, ReadErrorKind)> {
    let mut t = Tokens::new(text);

    let Some((head, head_line)) = t.next() else {
        return Err((
            t.eof_line(),
            syntax("file is empty; expected an OFF header such as 'OFF'"),
        ));
    };
    let h = Header::parse(head).ok_or_else(|| {
        (
            head_line,
            syntax(format!(
                "expected an OFF header ([ST][C][N][4][n]OFF), found '{head}'"
            )),
        )
    })?;
    if let Some(("BINARY", l)) = t.peek() {
        return Err((l, syntax("binary OFF is not supported")));
    }

    // Next token or an "ends early" error describing what was expected.
    macro_rules! next_or {
        ($($msg:tt)*) => {
            match t.next() {
                Some(tok) => tok,
                None => return Err((t.eof_line(), syntax(format!($($msg)*)))),
            }
        };
    }

    let dim = if h.ndim {
        let (tok, l) = next_or!("file ends after the nOFF header; expected the dimension");
        let n = parse_count(tok, "nOFF dimension").map_err(|k| (l, k))? as usize;
        if n == 0 {
            return Err((l, syntax("nOFF dimension must be at least 1, found 0")));
        }
        n + usize::from(h.four)
    } else if h.four {
        4
    } else {
        3
    };

    let (tok, l) = next_or!("file ends after the header; expected the vertex count");
    let nv = parse_count(tok, "vertex count").map_err(|k| (l, k))?;
    let (tok, l) = next_or!("file ends after the vertex count; expected the face count");
    let nf = parse_count(tok, "face count").map_err(|k| (l, k))?;
    let (tok, l) = next_or!("file ends after the face count; expected the edge count");
    match parse_integer(tok) {
        Ok(v) if v >= 0 => {}
        Err(IntError::OutOfRange) if !tok.starts_with('-') => {}
        Ok(_) | Err(IntError::OutOfRange) => {
            return Err((l, syntax(format!("edge count {tok} is negative"))));
        }
        Err(IntError::NotInteger) => {
            return Err((l, syntax(format!("edge count '{tok}' is not an integer"))));
        }
        Err(IntError::NotNumber) => {
            return Err((
                l,
                syntax(format!(
                    "non-numeric token '{tok}' where the edge count was expected"
                )),
            ));
        }
    }

    // Per-vertex layout: what each of the numbers is.
    let normal_dim = match (h.normals, h.ndim) {
        (false, _) => 0,
        (true, true) => dim,
        (true, false) => 3,
    };
    let colour_dim = if h.colour { 4 } else { 0 };
    let texture_dim = if h.texture { 2 } else { 0 };
    let per_vertex = dim + normal_dim + colour_dim + texture_dim;
    let mut layout = format!("{dim} coordinates");
    for (n, what) in [
        (normal_dim, "normal"),
        (colour_dim, "colour"),
        (texture_dim, "texture"),
    ] {
        if n > 0 {
            layout.push_str(&format!(", {n} {what}"));
        }
    }

    let mut data = Vec::with_capacity(capped((nv as usize).saturating_mul(dim), text));
    for i in 0..nv {
        for j in 0..per_vertex {
            let Some((tok, l)) = t.next() else {
                let msg = if j == 0 {
                    format!("vertex count {nv} declared but file ends after {i} vertices")
                } else if j < dim {
                    format!(
                        "file ends inside vertex {}: expected {dim} vertex coordinates, found {j}",
                        i + 1
                    )
                } else {
                    format!(
                        "file ends inside vertex {}: expected {per_vertex} numbers ({layout}), \
                         found {j}",
                        i + 1
                    )
                };
                return Err((t.eof_line(), syntax(msg)));
            };
            let what = if j < dim {
                "a vertex coordinate"
            } else if j < dim + normal_dim {
                "a vertex normal component"
            } else if j < dim + normal_dim + colour_dim {
                "a vertex colour component"
            } else {
                "a vertex texture coordinate"
            };
            let x = parse_f64(tok, what).map_err(|k| (l, k))?;
            if j < dim {
                data.push(x);
            }
        }
    }

    let mut raw = RawInput::new();
    raw.vertex_count = Some(nv);
    raw.coords = Some(Coords { dim, data });
    raw.ids
        .reserve(capped((nf as usize).saturating_mul(3), text));
    raw.offsets.reserve(capped(nf as usize, text));
    raw.lines.reserve(capped(nf as usize, text));

    let mut ids = [0u32; 3];
    for f in 0..nf {
        let (tok, face_line) = next_or!("face count {nf} declared but file ends after {f} faces");
        let k = match parse_integer(tok) {
            Ok(k) => k,
            Err(IntError::NotNumber) => {
                return Err((
                    face_line,
                    syntax(format!(
                        "non-numeric token '{tok}' where a face vertex count was expected"
                    )),
                ));
            }
            Err(IntError::NotInteger) => {
                return Err((
                    face_line,
                    syntax(format!("face vertex count '{tok}' is not an integer")),
                ));
            }
            Err(IntError::OutOfRange) => {
                return Err((
                    face_line,
                    syntax(format!("face vertex count {tok} is out of range")),
                ));
            }
        };
        if k < 0 {
            return Err((
                face_line,
                syntax(format!("face vertex count {k} is negative")),
            ));
        }
        if k == 0 {
            return Err((face_line, syntax("face with 0 vertices")));
        }
        if k > 3 {
            return Err((
                face_line,
                match usize::try_from(k) {
                    Ok(k) => ReadErrorKind::Polygon(k),
                    Err(_) => syntax(format!("face vertex count {k} is out of range")),
                },
            ));
        }
        let k = k as usize;
        let mut last_line = face_line;
        for (j, id) in ids.iter_mut().take(k).enumerate() {
            let (tok, l) = next_or!(
                "file ends inside face {}: expected {k} vertex ids, found {j}",
                f + 1
            );
            *id = parse_id(tok, false).map_err(|e| (l, e))?;
            last_line = l;
        }
        let colour = t.rest_of_line(last_line);
        for &(tok, l) in &colour {
            parse_f64(tok, "a face colour component").map_err(|e| (l, e))?;
        }
        if !matches!(colour.len(), 0 | 1 | 3 | 4) {
            return Err((
                last_line,
                syntax(format!(
                    "face {} has {} numbers after its {k} vertex ids; a face colour has 0, 1, 3 \
                     or 4 numbers",
                    f + 1,
                    colour.len()
                )),
            ));
        }
        raw.push(&ids[..k], face_line);
    }

    if let Some((tok, l)) = t.next() {
        return Err((
            l,
            syntax(format!(
                "unexpected content '{tok}' after the end of the data ({nv} vertices and {nf} \
                 faces declared)"
            )),
        ));
    }
    Ok(raw)
}

#[cfg(test)]
mod tests {
    use super::*;

    reader_test_helpers!();

    const TETRA: &str =
        "OFF\n4 4 6\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 1 2\n3 0 1 3\n3 0 2 3\n3 1 2 3\n";

    #[test]
    fn plain() {
        let r = ok(TETRA);
        assert_eq!(r.vertex_count, Some(4));
        let c = r.coords.as_ref().unwrap();
        assert_eq!(c.dim, 3);
        assert_eq!(c.data.len(), 12);
        assert_eq!(c.data[9..], [0.0, 0.0, 1.0]);
        assert_eq!(simplices(&r), [[0, 1, 2], [0, 1, 3], [0, 2, 3], [1, 2, 3]]);
        assert_eq!(r.lines, [7, 8, 9, 10]);
    }

    #[test]
    fn vertices_edges_and_triangles() {
        let r = ok("OFF\n3 3 0\n0 0 0\n1 0 0\n0 1 0\n1 0\n2 0 1\n3 0 1 2\n");
        assert_eq!(simplices(&r), [vec![0], vec![0, 1], vec![0, 1, 2]]);
        assert_eq!(r.lines, [6, 7, 8]);
    }

    #[test]
    fn empty_complex() {
        let r = ok("OFF\n0 0 0\n");
        assert_eq!(r.vertex_count, Some(0));
        assert_eq!(r.simplex_count(), 0);
    }

    #[test]
    fn coff() {
        let r = ok("COFF\n3 1 0\n0 0 0 1 0 0 1\n1 0 0 0 1 0 1\n0 1 0 0 0 1 0.5\n3 0 1 2\n");
        assert_eq!(
            r.coords.clone().unwrap().data,
            [0., 0., 0., 1., 0., 0., 0., 1., 0.]
        );
        assert_eq!(simplices(&r), [[0, 1, 2]]);
    }

    #[test]
    fn noff() {
        let r = ok("NOFF\n3 1 0\n0 0 0 0 0 1\n1 0 0 0 0 1\n0 1 0 0 0 1\n3 0 1 2\n");
        assert_eq!(
            r.coords.clone().unwrap().data,
            [0., 0., 0., 1., 0., 0., 0., 1., 0.]
        );
    }

    #[test]
    fn four_off() {
        let r = ok("4OFF\n2 1 0\n0 0 0 1\n1 2 3 1\n2 0 1\n");
        let c = r.coords.clone().unwrap();
        assert_eq!(c.dim, 4);
        assert_eq!(c.data, [0., 0., 0., 1., 1., 2., 3., 1.]);
        assert_eq!(simplices(&r), [[0, 1]]);
    }

    #[test]
    fn n_off_dim_5() {
        let r = ok("nOFF\n5\n2 1 0\n1 2 3 4 5\n6 7 8 9 10\n2 1 0\n");
        let c = r.coords.clone().unwrap();
        assert_eq!(c.dim, 5);
        assert_eq!(c.data, [1., 2., 3., 4., 5., 6., 7., 8., 9., 10.]);
        assert_eq!(simplices(&r), [[1, 0]]);
    }

    #[test]
    fn four_n_off_has_homogeneous_component() {
        let r = ok("4nOFF 2\n1 0 0\n1 2 1\n");
        let c = r.coords.clone().unwrap();
        assert_eq!(c.dim, 3);
        assert_eq!(c.data, [1., 2., 1.]);
    }

    #[test]
    fn n_off_normals_have_vertex_dimension() {
        // 2 coordinates, 2 normal components.
        let r = ok("NnOFF 2\n2 1 0\n0 0 0 1\n1 0 0 1\n2 0 1\n");
        assert_eq!(r.coords.clone().unwrap().data, [0., 0., 1., 0.]);
    }

    #[test]
    fn stcnoff() {
        // 3 coordinates, 3 normal, 4 colour, 2 texture numbers per vertex.
        let text = "STCNOFF\n3 1 0\n\
                    0 0 0  0 0 1  1 0 0 1  0 0\n\
                    1 0 0  0 0 1  0 1 0 1  1 0\n\
                    0 1 0  0 0 1  0 0 1 1  0 1\n\
                    3 0 1 2\n";
        let r = ok(text);
        assert_eq!(
            r.coords.clone().unwrap().data,
            [0., 0., 0., 1., 0., 0., 0., 1., 0.]
        );
        assert_eq!(r.lines, [6]);
    }

    #[test]
    fn colours_after_face_ids() {
        let text = "OFF\n3 4 0\n0 0 0\n1 0 0\n0 1 0\n\
                    3 0 1 2 7\n3 0 1 2 255 0 0\n3 0 1 2 1.0 0.5 0.25 1\n3 0 1 2\n";
        let r = ok(text);
        assert_eq!(r.simplex_count(), 4);
        assert_eq!(r.lines, [6, 7, 8, 9]);
    }

    #[test]
    fn comments_and_blank_lines() {
        let text = "# leading comment\n\nOFF # header\n# between\n4 1 6 # counts\n\n\
                    0 0 0\n1 0 0 # v1\n0 1 0\n#\n0 0 1\n\n# face next\n3 0 1 2 # face\n# end\n";
        let r = ok(text);
        assert_eq!(r.vertex_count, Some(4));
        assert_eq!(r.lines, [14]);
    }

    #[test]
    fn counts_on_header_line_and_items_sharing_lines() {
        let r = ok("OFF 3 2 0\n0 0 0 1 0 0 0 1 0\n3 0 1 2\n2\n0\n1\n");
        assert_eq!(simplices(&r), [vec![0, 1, 2], vec![0, 1]]);
        // A face split over lines is recorded at the line of its k.
        assert_eq!(r.lines, [3, 4]);
    }

    #[test]
    fn crlf_tabs_and_no_final_newline() {
        let r = ok("OFF\r\n3\t1\t0\r\n0\t0 0\r\n1 0 0\r\n0 1 0\r\n3\t0\t1\t2");
        assert_eq!(simplices(&r), [[0, 1, 2]]);
        assert_eq!(r.lines, [6]);
    }

    #[test]
    fn nan_and_inf_coordinates_are_accepted() {
        let r = ok("OFF\n1 1 0\nnan inf -inf\n1 0\n");
        let d = r.coords.clone().unwrap().data;
        assert!(d[0].is_nan() && d[1] == f64::INFINITY && d[2] == f64::NEG_INFINITY);
    }

    #[test]
    fn ids_are_not_range_checked_here() {
        let r = ok("OFF\n1 1 0\n0 0 0\n3 0 0 9\n");
        assert_eq!(simplices(&r), [[0, 0, 9]]);
    }

    #[test]
    fn huge_declared_count_does_not_allocate() {
        err(
            "OFF\n4000000000 1 0\n0 0 0\n",
            3,
            "vertex count 4000000000 declared but file ends after 1 vertices",
        );
        err(
            "OFF\n0 4000000000 0\n",
            2,
            "face count 4000000000 declared but file ends after 0 faces",
        );
    }

    #[test]
    fn empty_file() {
        err("", 1, "file is empty");
        err("# only a comment\n\n", 2, "file is empty");
    }

    #[test]
    fn wrong_header() {
        err("PLY\n3 1 0\n", 1, "expected an OFF header");
        err("# c\noff\n", 2, "found 'off'");
        err("3 1 0\n0 0 0\n", 1, "found '3'");
        err("CSTOFF\n0 0 0\n", 1, "found 'CSTOFF'");
    }

    #[test]
    fn binary_rejected() {
        err("OFF BINARY\n", 1, "binary OFF is not supported");
        err("COFF BINARY\n", 1, "binary OFF is not supported");
    }

    #[test]
    fn missing_counts() {
        err("OFF\n", 1, "expected the vertex count");
        err("OFF\n3 1\n", 2, "expected the edge count");
        err(
            "OFF\nx 1 0\n",
            2,
            "non-numeric token 'x' where the vertex count was expected",
        );
        err("OFF\n3 -1 0\n", 2, "face count -1 is negative");
        err("OFF\n3 1 0.5\n", 2, "edge count '0.5' is not an integer");
        err(
            "OFF\n4294967296 1 0\n",
            2,
            "vertex count 4294967296 does not fit in 32 bits",
        );
        err("nOFF\n0\n0 0 0\n", 2, "dimension must be at least 1");
    }

    #[test]
    fn truncated_vertices() {
        err(
            "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1\n",
            5,
            "expected 3 vertex coordinates, found 2",
        );
        err(
            "OFF\n3 1 0\n0 0 0\n1 0 0\n",
            4,
            "vertex count 3 declared but file ends after 2 vertices",
        );
        err(
            "COFF\n1 0 0\n0 0 0 1 1\n",
            3,
            "expected 7 numbers (3 coordinates, 4 colour), found 5",
        );
    }

    #[test]
    fn truncated_faces() {
        let text = "OFF\n3 10 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n3 0 1 2\n3 0 1 2\n3 0 1 2\n";
        err(
            text,
            9,
            "face count 10 declared but file ends after 4 faces",
        );
        err(
            "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1",
            6,
            "file ends inside face 1: expected 3 vertex ids, found 2",
        );
    }

    #[test]
    fn non_numeric() {
        err(
            "OFF\n1 1 0\n0 abc 0\n1 0\n",
            3,
            "non-numeric token 'abc' where a vertex coordinate was expected",
        );
        err(
            "OFF\n1 1 0\n0 0 0\n3 0 abc 0\n",
            4,
            "non-numeric token 'abc' where a vertex id was expected",
        );
        err(
            "OFF\n1 1 0\n0 0 0\nx 0\n",
            4,
            "non-numeric token 'x' where a face vertex count was expected",
        );
        err(
            "OFF\n1 1 0\n0 0 0\n1 0.5\n",
            4,
            "vertex id '0.5' is not an integer",
        );
        err(
            "COFF\n1 0 0\n0 0 0 1 1 red 1\n",
            3,
            "non-numeric token 'red' where a vertex colour",
        );
        err(
            "OFF\n1 1 0\n0 0 0\n1 0 red\n",
            4,
            "non-numeric token 'red' where a face colour",
        );
    }

    #[test]
    fn overflowing_and_negative_ids() {
        err(
            "OFF\n1 1 0\n0 0 0\n1 4294967296\n",
            4,
            "vertex id 4294967296 does not fit in 32 bits",
        );
        err("OFF\n1 1 0\n0 0 0\n\n2 0\n-1\n", 6, "negative vertex id -1");
        assert_eq!(
            parse("OFF\n1 1 0\n0 0 0\n2 0 -3\n"),
            Err((4, ReadErrorKind::NegativeId(-3)))
        );
        let r = ok("OFF\n1 1 0\n0 0 0\n1 4294967295\n");
        assert_eq!(simplices(&r), [[u32::MAX]]);
    }

    #[test]
    fn polygons_and_empty_faces() {
        assert_eq!(
            parse("OFF\n4 1 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n"),
            Err((7, ReadErrorKind::Polygon(4)))
        );
        err("OFF\n1 1 0\n0 0 0\n0\n", 4, "face with 0 vertices");
        err(
            "OFF\n1 1 0\n0 0 0\n-2 0 0\n",
            4,
            "face vertex count -2 is negative",
        );
    }

    #[test]
    fn bad_face_colour_count() {
        err(
            "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2 1 1\n",
            6,
            "has 2 numbers after its 3 vertex ids",
        );
        err(
            "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2 1 1 1 1 1\n",
            6,
            "has 5 numbers",
        );
    }

    #[test]
    fn extra_content_after_last_face() {
        err(
            "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n\n3 0 1 2\n",
            8,
            "unexpected content '3' after the end of the data",
        );
        err(
            "OFF\n1 0 0\n0 0 0\n# fine\nextra\n",
            5,
            "unexpected content 'extra'",
        );
    }
}
