//! Reader for simplex lists (`.simplices`), Topoplex's own line-based format.
//!
//! ```text
//! # a triangle with a dangling edge
//! v 0 0
//! v 1 0
//! v 0 1
//! v 2 2
//! s 0 1 2
//! s 2 3
//! ```
//!
//! * `v x1 .. xk` declares the next vertex with k >= 0 coordinates; every `v` line must have the
//!   same k. Coordinates are parsed as `f64`; `nan`, `inf` and `infinity` are accepted, since
//!   topology does not use coordinates, but a finite number that would become infinite or 0
//!   (`1e309`, `1e-400`) is an error.
//! * `s a b c ...` declares a simplex by at least one 0-based vertex id (ids must fit in 32 bits;
//!   a negative id is [`ReadErrorKind::NegativeId`]). Each simplex is recorded at its line.
//! * `v` and `s` lines may be interleaved in any order.
//! * With `v` lines the vertex count is their number and the coordinates have dimension k (none
//!   when k = 0). Without `v` lines the vertex count is `None`: the vertices are `0..=max id`.
//! * `#` starts a comment; blank lines, tabs and a missing final newline are fine; lines end in
//!   LF, CRLF or a lone CR. Any other keyword is an error, and so is a file with no `v` or `s`
//!   line at all.

use super::scan::{self, Scanner};
use super::{Coords, RawInput, ReadErrorKind, echo, no_room, parse_f64, syntax};
use crate::complex::table;

/// Reads a `.simplices` file's text.
pub fn parse(text: &str) -> Result<RawInput, (u32, ReadErrorKind)> {
    let mut s = Scanner::new(text);
    let mut raw = RawInput::new();
    let mut data = Vec::new();
    // (number of coordinates, line) of the first `v` line.
    let mut first_v: Option<(usize, u32)> = None;
    let mut vertices: u32 = 0;
    let mut ids = Vec::new();
    loop {
        if let Some((keyword, line)) = s.token_in_line() {
            let err = |k: ReadErrorKind| (line, k);
            match keyword {
                "v" => {
                    let start = data.len();
                    loop {
                        let x = match s.real(false) {
                            Some((x, _)) => x,
                            None => match s.token_in_line() {
                                Some((tok, _)) => {
                                    parse_f64(tok, "a vertex coordinate").map_err(err)?
                                }
                                None => break,
                            },
                        };
                        table::try_push(&mut data, x)
                            .map_err(|b| err(no_room("the vertex coordinates")(b)))?;
                    }
                    let k = data.len() - start;
                    match first_v {
                        None => first_v = Some((k, line)),
                        Some((k0, l0)) if k != k0 => {
                            return Err(err(syntax(format!(
                                "v line has {k} coordinates but the first v line (line {l0}) has \
                                 {k0}"
                            ))));
                        }
                        Some(_) => {}
                    }
                    vertices = vertices
                        .checked_add(1)
                        .ok_or_else(|| err(syntax("more than 4294967295 vertices")))?;
                }
                "s" => {
                    ids.clear();
                    loop {
                        let id = match s.digits(false) {
                            Some((v, _)) => scan::id_value(v, false),
                            None => match s.token_in_line() {
                                Some((tok, _)) => scan::id(tok, false),
                                None => break,
                            },
                        };
                        table::try_push(&mut ids, id.map_err(err)?)
                            .map_err(|b| err(no_room("an s line's ids")(b)))?;
                    }
                    if ids.is_empty() {
                        return Err(err(syntax("s line with no vertex ids")));
                    }
                    raw.try_push(&ids, line).map_err(err)?;
                }
                k => {
                    return Err(err(syntax(format!(
                        "unknown keyword '{}' (expected 'v' or 's')",
                        echo(k)
                    ))));
                }
            }
        }
        if !s.next_line() {
            break;
        }
    }

    match first_v {
        None if raw.simplex_count() == 0 => {
            Err((s.eof_line(), syntax("file is empty (no `v` or `s` lines)")))
        }
        None => Ok(raw),
        Some((dim, _)) => {
            raw.vertex_count = Some(vertices);
            raw.coords = (dim > 0).then_some(Coords { dim, data });
            Ok(raw)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    reader_test_helpers!();

    #[test]
    fn with_v_lines() {
        let r = ok("# comment\nv 0 0\nv 1 0\n\ns 0 1 # edge\nv 0 1\ns 0 1 2\ns 2\n");
        assert_eq!(r.vertex_count, Some(3));
        let c = r.coords.as_ref().unwrap();
        assert_eq!(c.dim, 2);
        assert_eq!(c.data, [0., 0., 1., 0., 0., 1.]);
        assert_eq!(simplices(&r), [vec![0, 1], vec![0, 1, 2], vec![2]]);
        assert_eq!(r.lines, [5, 7, 8]);
    }

    #[test]
    fn v_lines_without_coordinates() {
        let r = ok("v\nv\ns 0 1\n");
        assert_eq!(r.vertex_count, Some(2));
        assert_eq!(r.coords, None);
    }

    #[test]
    fn without_v_lines() {
        let r = ok("s 0 1 2 3 4\ns 7\n");
        assert_eq!(r.vertex_count, None);
        assert_eq!(r.coords, None);
        assert_eq!(simplices(&r), [vec![0, 1, 2, 3, 4], vec![7]]);
    }

    #[test]
    fn crlf_tabs_no_final_newline_nan_and_unchecked_topology() {
        let r = ok("v\t1 nan\r\nv inf 2\r\ns\t1 1\t9");
        assert_eq!(simplices(&r), [[1, 1, 9]]);
        assert_eq!(r.lines, [3]);
        assert!(r.coords.clone().unwrap().data[1].is_nan());
    }

    #[test]
    fn empty_file() {
        err("", 1, "file is empty");
        err("# nothing\n\n\n", 3, "file is empty");
    }

    #[test]
    fn errors() {
        err(
            "v 0 0\nv 1 0 0\n",
            2,
            "v line has 3 coordinates but the first v line (line 1) has 2",
        );
        err("s 0 1\n\nq 1\n", 3, "unknown keyword 'q'");
        err("s 0 1\nS 1\n", 2, "unknown keyword 'S'");
        err("s 0 1\ns\n", 2, "s line with no vertex ids");
        err(
            "s 0 abc\n",
            1,
            "non-numeric token 'abc' where a vertex id was expected",
        );
        err("s 0 1.0\n", 1, "vertex id '1.0' is not an integer");
        err(
            "s 4294967296\n",
            1,
            "vertex id 4294967296 does not fit in 32 bits",
        );
        err(
            "v x\n",
            1,
            "non-numeric token 'x' where a vertex coordinate was expected",
        );
        assert_eq!(
            parse("v\ns 0\ns 1 -4\n"),
            Err((3, ReadErrorKind::NegativeId(-4)))
        );
        assert_eq!(ok("s 4294967295\n").simplex(0), [u32::MAX]);
    }

    #[test]
    fn cr_only_line_ends() {
        let r = ok("v 0\rv 1\r\rs 0 1\rs 1");
        assert_eq!(r.lines, [4, 5]);
        err("s 0 1\rs 1 x\r", 2, "non-numeric token 'x'");
    }

    #[test]
    fn coordinates_that_do_not_fit_a_double() {
        err(
            "v 0\nv 1e309\n",
            2,
            "number '1e309' is too large for a 64-bit float",
        );
        err(
            "v 0\nv 1e-400\n",
            2,
            "number '1e-400' is too small for a 64-bit float",
        );
    }

    #[test]
    fn echoed_tokens_are_escaped_and_capped() {
        err("s 0 1\u{a0}2\n", 1, "non-numeric token '1\\u{a0}2'");
        let text = format!("s 0 {}\n", "7".repeat(100_000_000));
        let Err((1, k)) = parse(&text) else {
            panic!("expected an error on line 1")
        };
        let msg = k.to_string();
        assert!(msg.len() < 300, "{} bytes", msg.len());
        assert!(
            msg.ends_with("… (99999800 more bytes) does not fit in 32 bits"),
            "{msg}"
        );
    }
}
