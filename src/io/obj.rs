//! Reader for Wavefront OBJ files (`.obj`), geometry statements only.
//!
//! * `v x y z` declares a vertex; a homogeneous `w` (4 numbers) or a vertex colour `r g b`
//!   (6 numbers, or 7) may follow and is ignored. Fewer than 3 numbers, or 5, or more than 7,
//!   are errors. Coordinates have dimension 3. Numbers are parsed as `f64`; `nan`, `inf` and
//!   `infinity` are accepted, since topology does not use coordinates.
//! * `f` with vertices written `i`, `i/t`, `i//n` or `i/t/n` is a triangle; more than 3
//!   vertices is [`ReadErrorKind::Polygon`], fewer is an error (use `l` or `p`).
//! * `l i j k ...` (also `i/t`) gives one edge per consecutive pair; it needs at least 2 vertices.
//! * `p i j ...` gives one 0-simplex per index; it needs at least 1.
//! * Indices are 1-based; 0 is an error. Positive indices may refer to vertices defined later in
//!   the file, so they are recorded (0-based) without a range check, which the complex model does.
//!   Negative indices are relative to the vertices read so far (-1 is the last one); reaching
//!   before the first vertex is an error. Texture and normal indices are checked to be non-zero
//!   integers and ignored.
//! * Ignored statements: `vt vn vp o g s usemtl mtllib cstype deg bmat step curv curv2 surf parm
//!   trim hole scrv sp end con mg bevel c_interp d_interp lod maplib usemap shadow_obj trace_obj
//!   ctech stech` (their arguments are not checked). Any other keyword is an error.
//! * `#` starts a comment; a line ending in `\` continues on the next line (the statement is
//!   reported at its first line). CRLF, tabs and a missing final newline are fine.
//! * A file with no statements at all is an error.
//!
//! `vertex_count` is the number of `v` statements.

use super::{
    Coords, IntError, RawInput, ReadErrorKind, parse_f64, parse_integer, strip_comment, syntax,
};
use std::borrow::Cow;

const IGNORED: &[&str] = &[
    "vt",
    "vn",
    "vp",
    "o",
    "g",
    "s",
    "usemtl",
    "mtllib",
    "cstype",
    "deg",
    "bmat",
    "step",
    "curv",
    "curv2",
    "surf",
    "parm",
    "trim",
    "hole",
    "scrv",
    "sp",
    "end",
    "con",
    "mg",
    "bevel",
    "c_interp",
    "d_interp",
    "lod",
    "maplib",
    "usemap",
    "shadow_obj",
    "trace_obj",
    "ctech",
    "stech",
];

/// Which `/` forms an element allows for its vertices.
#[derive(Clone, Copy, PartialEq)]
enum Form {
    /// `f`: `i`, `i/t`, `i//n`, `i/t/n`.
    Face,
    /// `l`: `i`, `i/t`.
    Line,
    /// `p`: `i`.
    Point,
}

/// Resolves one element vertex to a 0-based id; `seen` is the number of `v` statements so far.
fn vertex_index(tok: &str, form: Form, seen: u32) -> Result<u32, ReadErrorKind> {
    let parts: Vec<&str> = tok.split('/').collect();
    let nonzero_int = |s: &str| parse_integer(s).is_ok_and(|v| v != 0);
    let well_formed = match (form, parts.as_slice()) {
        (_, [_]) => true,
        (Form::Face | Form::Line, [_, t]) => nonzero_int(t),
        (Form::Face, [_, t, n]) => (t.is_empty() || nonzero_int(t)) && nonzero_int(n),
        _ => false,
    };
    if !well_formed || parts[0].is_empty() {
        let forms = match form {
            Form::Face => "i, i/t, i//n or i/t/n",
            Form::Line => "i or i/t",
            Form::Point => "i",
        };
        return Err(syntax(format!(
            "malformed vertex reference '{tok}' (expected {forms} with non-zero integer indices)"
        )));
    }
    let i = parts[0];
    let v = match parse_integer(i) {
        Ok(v) => v,
        Err(IntError::NotNumber) => {
            return Err(syntax(format!(
                "non-numeric token '{i}' where a vertex index was expected"
            )));
        }
        Err(IntError::NotInteger) => {
            return Err(syntax(format!("vertex index '{i}' is not an integer")));
        }
        Err(IntError::OutOfRange) if i.starts_with('-') => {
            return Err(syntax(format!(
                "relative vertex index {i} reaches before the first vertex ({seen} vertices read \
                 so far)"
            )));
        }
        Err(IntError::OutOfRange) => {
            return Err(syntax(format!("vertex index {i} does not fit in 32 bits")));
        }
    };
    if v == 0 {
        return Err(syntax(
            "vertex index 0 is invalid (OBJ indices start at 1; negative ones count back from the \
             last vertex)",
        ));
    }
    if v > 0 {
        u32::try_from(v - 1)
            .map_err(|_| syntax(format!("vertex index {i} does not fit in 32 bits")))
    } else {
        let id = i128::from(seen) + v;
        u32::try_from(id).map_err(|_| {
            syntax(format!(
                "relative vertex index {i} reaches before the first vertex ({seen} vertices read \
                 so far)"
            ))
        })
    }
}

/// Parses Wavefront OBJ text; errors carry the 1-based line.
pub fn parse(text: &str) -> Result<RawInput, (u32, ReadErrorKind)> {
    let mut raw = RawInput::new();
    let mut data = Vec::new();
    let mut seen: u32 = 0;
    let mut statements = 0usize;
    let mut ids: Vec<u32> = Vec::new();

    let mut lines = text.lines().zip(1u32..);
    let mut last_line = 0u32;
    while let Some((first, line)) = lines.next() {
        last_line = line;
        // Join continuation lines (a trailing `\`).
        let mut stmt = Cow::Borrowed(strip_comment(first));
        while let Some(head) = stmt.trim_end().strip_suffix('\\') {
            let head = head.to_owned();
            let Some((next, l)) = lines.next() else {
                return Err((
                    line,
                    syntax("line continuation '\\' at the end of the file"),
                ));
            };
            last_line = l;
            stmt = Cow::Owned(format!("{head} {}", strip_comment(next)));
        }

        let mut toks = stmt.split_ascii_whitespace();
        let Some(keyword) = toks.next() else { continue };
        statements += 1;
        let err = |k: ReadErrorKind| (line, k);
        match keyword {
            "v" => {
                let start = data.len();
                for tok in toks {
                    data.push(parse_f64(tok, "a vertex coordinate").map_err(err)?);
                }
                let n = data.len() - start;
                match n {
                    0..=2 => {
                        return Err(err(syntax(format!(
                            "expected 3 vertex coordinates, found {n}"
                        ))));
                    }
                    3 | 4 | 6 | 7 => data.truncate(start + 3),
                    _ => {
                        return Err(err(syntax(format!(
                            "v statement with {n} numbers; expected x y z, optionally followed by \
                             w (4 numbers) or by a colour (6 or 7 numbers)"
                        ))));
                    }
                }
                seen = seen
                    .checked_add(1)
                    .ok_or_else(|| err(syntax("more than 4294967295 vertices")))?;
            }
            "f" => {
                let toks: Vec<&str> = toks.collect();
                match toks.len() {
                    0 => return Err(err(syntax("face with no vertices"))),
                    1 => {
                        return Err(err(syntax(
                            "face with 1 vertex; use a `p` line for a point",
                        )));
                    }
                    2 => {
                        return Err(err(syntax(
                            "face with 2 vertices; use an `l` line for an edge",
                        )));
                    }
                    3 => {}
                    k => return Err(err(ReadErrorKind::Polygon(k))),
                }
                ids.clear();
                for tok in toks {
                    ids.push(vertex_index(tok, Form::Face, seen).map_err(err)?);
                }
                raw.push(&ids, line);
            }
            "l" => {
                ids.clear();
                for tok in toks {
                    ids.push(vertex_index(tok, Form::Line, seen).map_err(err)?);
                }
                if ids.len() < 2 {
                    return Err(err(syntax(format!(
                        "line element with {} vertices; an `l` line needs at least 2",
                        ids.len()
                    ))));
                }
                for pair in ids.windows(2) {
                    raw.push(pair, line);
                }
            }
            "p" => {
                let before = raw.simplex_count();
                for tok in toks {
                    let id = vertex_index(tok, Form::Point, seen).map_err(err)?;
                    raw.push(&[id], line);
                }
                if raw.simplex_count() == before {
                    return Err(err(syntax("point element with no vertices")));
                }
            }
            k if IGNORED.contains(&k) => {}
            k => return Err(err(syntax(format!("unknown OBJ statement '{k}'")))),
        }
    }

    if statements == 0 {
        return Err((
            last_line.max(1),
            syntax("file is empty (no OBJ statements)"),
        ));
    }
    raw.vertex_count = Some(seen);
    raw.coords = Some(Coords { dim: 3, data });
    Ok(raw)
}

#[cfg(test)]
mod tests {
    use super::*;

    reader_test_helpers!();

    #[test]
    fn triangles_in_all_forms() {
        let text = "# cube corner\nmtllib a.mtl\no thing\nv 0 0 0\nv 1 0 0\nv 0 1 0 1.0\n\
                    v 0 0 1 0.5 0.5 0.5\nvt 0 0\nvn 0 0 1\ng group\ns off\nusemtl red\n\
                    f 1 2 3\nf 1/1 2/1 4/1\nf 1//1 3//1 4//1\nf 2/1/1 3/1/1 4/1/1\n";
        let r = ok(text);
        assert_eq!(r.vertex_count, Some(4));
        let c = r.coords.as_ref().unwrap();
        assert_eq!(c.dim, 3);
        assert_eq!(c.data, [0., 0., 0., 1., 0., 0., 0., 1., 0., 0., 0., 1.]);
        assert_eq!(simplices(&r), [[0, 1, 2], [0, 1, 3], [0, 2, 3], [1, 2, 3]]);
        assert_eq!(r.lines, [13, 14, 15, 16]);
    }

    #[test]
    fn negative_indices_are_relative() {
        let r = ok("v 0 0 0\nv 1 0 0\nv 0 1 0\nf -3 -2 -1\nv 0 0 1\nf -1/-1 -2//-2 1\n");
        assert_eq!(simplices(&r), [[0, 1, 2], [3, 2, 0]]);
    }

    #[test]
    fn forward_references_are_recorded() {
        let r = ok("f 1 2 3\nv 0 0 0\nv 1 0 0\nv 0 1 0\n");
        assert_eq!(simplices(&r), [[0, 1, 2]]);
        assert_eq!(r.vertex_count, Some(3));
    }

    #[test]
    fn lines_and_points() {
        let r = ok("v 0 0 0\nv 1 0 0\nv 0 1 0\nl 1 2 3 1\nl 1/1 -1/2\np 1 2\np -1\n");
        assert_eq!(
            simplices(&r),
            [
                vec![0, 1],
                vec![1, 2],
                vec![2, 0],
                vec![0, 2],
                vec![0],
                vec![1],
                vec![2]
            ]
        );
        assert_eq!(r.lines, [4, 4, 4, 5, 6, 6, 7]);
    }

    #[test]
    fn continuation_crlf_tabs_no_final_newline() {
        let r = ok("v 0 0 0\r\nv\t1 0 0\r\nv 0 1 \\\r\n 0\r\nf 1 \\\n 2 \\\n\t3");
        assert_eq!(r.vertex_count, Some(3));
        assert_eq!(simplices(&r), [[0, 1, 2]]);
        assert_eq!(r.lines, [5]);
    }

    #[test]
    fn nan_coordinates_and_unchecked_ignored_statements() {
        let r = ok("v nan inf 0\nvt whatever\ncurv 0 1 1 2\nend\n");
        assert!(r.coords.clone().unwrap().data[0].is_nan());
    }

    #[test]
    fn vertices_only() {
        let r = ok("v 0 0 0\n");
        assert_eq!(r.vertex_count, Some(1));
        assert_eq!(r.simplex_count(), 0);
    }

    #[test]
    fn empty_file() {
        err("", 1, "file is empty");
        err("# nothing\n\n", 2, "file is empty");
    }

    #[test]
    fn vertex_errors() {
        err(
            "v 0 0 0\nv 1 2\n",
            2,
            "expected 3 vertex coordinates, found 2",
        );
        err(
            "v 0 abc 0\n",
            1,
            "non-numeric token 'abc' where a vertex coordinate was expected",
        );
        err("v 0 0 0 1 1\n", 1, "v statement with 5 numbers");
    }

    #[test]
    fn face_errors() {
        let vs = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\n";
        assert_eq!(
            parse(&format!("{vs}f 1 2 3 4\n")),
            Err((5, ReadErrorKind::Polygon(4)))
        );
        err(
            &format!("{vs}f 1 2\n"),
            5,
            "face with 2 vertices; use an `l` line for an edge",
        );
        err(&format!("{vs}f\n"), 5, "face with no vertices");
        err(&format!("{vs}f 1 0 2\n"), 5, "vertex index 0 is invalid");
        err(
            &format!("{vs}f 1 2 abc\n"),
            5,
            "non-numeric token 'abc' where a vertex index",
        );
        err(
            &format!("{vs}f 1 2 2.5\n"),
            5,
            "vertex index '2.5' is not an integer",
        );
        err(
            &format!("{vs}f 1 2 4294967297\n"),
            5,
            "vertex index 4294967297 does not fit in 32 bits",
        );
        err(
            &format!("{vs}f 1 2 -5\n"),
            5,
            "relative vertex index -5 reaches before the first vertex (4 vertices",
        );
        err(
            &format!("{vs}f 1 2 1/x\n"),
            5,
            "malformed vertex reference '1/x'",
        );
        err(
            &format!("{vs}f 1 2 1/1/\n"),
            5,
            "malformed vertex reference '1/1/'",
        );
        err(
            &format!("{vs}f 1 2 /1\n"),
            5,
            "malformed vertex reference '/1'",
        );
        let r = ok(&format!("{vs}f 1 2 4294967296\n"));
        assert_eq!(r.simplex(0), [0, 1, u32::MAX]);
    }

    #[test]
    fn line_and_point_errors() {
        err(
            "v 0 0 0\nl 1\n",
            2,
            "line element with 1 vertices; an `l` line needs at least 2",
        );
        err(
            "v 0 0 0\nv 0 0 0\nl 1 2//1\n",
            3,
            "malformed vertex reference '2//1'",
        );
        err("v 0 0 0\np\n", 2, "point element with no vertices");
        err("v 0 0 0\np 1/1\n", 2, "malformed vertex reference '1/1'");
        err(
            "v 0 0 0\n\n\np -2\n",
            4,
            "relative vertex index -2 reaches before the first vertex",
        );
    }

    #[test]
    fn unknown_statement_and_dangling_continuation() {
        err("v 0 0 0\n\nfoo 1 2\n", 3, "unknown OBJ statement 'foo'");
        err("v 0 0 0\nF 1 1 1\n", 2, "unknown OBJ statement 'F'");
        err("v 0 0 0\nf 1 1 \\", 2, "line continuation");
    }
}
