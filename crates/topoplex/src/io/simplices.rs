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
//! * `s a b c : L` gives the simplex an integer label `L` (`i64`), the attribute
//!   `simplices:label` on the listed simplices: blanks around the `:`, the label ends the line.
//!   Every `s` line has a label or none has (nothing holds "no label").
//! * `v` and `s` lines may be interleaved in any order.
//! * With `v` lines the vertex count is their number and the coordinates have dimension k (none
//!   when k = 0). Without `v` lines the vertex count is `None`: the vertices are `0..=max id`.
//! * `#` starts a comment; blank lines, tabs and a missing final newline are fine; lines end in
//!   LF, CRLF or a lone CR. Any other keyword is an error, and so is a file with no `v` or `s`
//!   line at all.

use super::chunked;
use super::scan::{self, Scanner};
use super::{Coords, RawInput, ReadErrorKind, echo, no_room, parse_f64, syntax};
use crate::complex::{Attribute, Location, Values, table};

/// The attribute of the labels after `:` on `s` lines.
pub(crate) const LABEL: &str = "simplices:label";

/// The labels of the `s` lines read so far: every line has one, or none has.
#[derive(Default)]
struct Labels {
    /// `None` before the first `s` line or when it has no label.
    values: Option<Vec<i64>>,
    /// The line of the first `s` line.
    first: Option<u32>,
}

impl Labels {
    fn keep(&mut self, label: Option<i64>, line: u32) -> Result<(), ReadErrorKind> {
        let first = *self.first.get_or_insert(line);
        match (&mut self.values, label) {
            (Some(v), Some(l)) => {
                table::try_push(v, l).map_err(no_room("the simplex labels"))?;
            }
            (None, None) => {}
            (None, Some(l)) if first == line => self.values = Some(vec![l]),
            (v, _) => {
                let (this, that) = if v.is_some() {
                    ("has no label", "has one")
                } else {
                    ("has a label", "has none")
                };
                return Err(syntax(format!(
                    "s line {this}, but the first s line (line {first}) {that}: every s line \
                     has a label or none has"
                )));
            }
        }
        Ok(())
    }
}

/// The label after an `s` line's `:`: one integer that fits 64 bits, ending the line.
fn read_label(s: &mut Scanner<'_>) -> Result<i64, ReadErrorKind> {
    let Some((tok, _)) = s.token_in_line() else {
        return Err(syntax("s line ends after ':'; expected a label"));
    };
    let label = match super::parse_integer(tok) {
        Ok(v) => i64::try_from(v).ok(),
        Err(_) => None,
    }
    .ok_or_else(|| {
        syntax(format!(
            "label '{}' after ':' is not an integer that fits 64 bits",
            echo(tok)
        ))
    })?;
    if let Some((tok, _)) = s.token_in_line() {
        return Err(syntax(format!(
            "'{}' after the label of an s line (the label ends it)",
            echo(tok)
        )));
    }
    Ok(label)
}

/// Reads a `.simplices` file's text. A large file is read on several threads (ranges of whole
/// lines counted, then parsed into arrays reserved at their size), with the same result and the
/// same first error as the serial read.
pub fn parse(text: &str) -> Result<RawInput, (u32, ReadErrorKind)> {
    if crate::parallel::splits(text.len() / 8)
        && let Some(raw) = parse_in_parallel(text)
    {
        return Ok(raw);
    }
    parse_serially(text)
}

/// What one range of lines holds (the first pass of [`parse_in_parallel`]).
#[derive(Default, Clone, Copy)]
struct Counts {
    lines: usize,
    simplices: usize,
    ids: usize,
    vertices: usize,
    /// Coordinates of the range's first `v` line (every `v` line of the range has as many).
    dim: Option<usize>,
}

/// Reads the file on several threads in two passes over ranges of whole lines: the first
/// counts each range's lines, simplices, ids and vertices (tokens only, no numbers); the second
/// parses each range straight into its place in arrays reserved at their exact size. `None`
/// when anything is not plain — an error of any kind, a `v` line whose coordinate count differs
/// from the first's, memory that cannot be had — for the serial reader to read the file (and
/// report the first error, with its line and message).
fn parse_in_parallel(text: &str) -> Option<RawInput> {
    let ranges = counted_ranges(text)?;
    let mut sized = Sized::of(ranges.iter().map(|(_, c)| c))?;
    let mut fill = sized.filling();
    fill.ranges(text, ranges.iter().map(|(r, c)| (*r, c)))?;
    chunked::note_section();
    Some(sized.into_raw())
}

/// The text's ranges of whole lines ([`chunked::line_ranges`]), each with its counts (on several
/// threads); `None` when a range is not plain.
fn counted_ranges(text: &str) -> Option<Vec<((usize, usize), Counts)>> {
    let cuts = chunked::line_ranges(text);
    let ranges: Vec<(usize, usize)> = cuts.windows(2).map(|w| (w[0], w[1])).collect();
    let counts = crate::parallel::map_chunks(ranges.len(), |r| count_range(text, ranges[r]));
    let counts: Vec<Counts> = counts.into_iter().collect::<Option<_>>()?;
    Some(ranges.into_iter().zip(counts).collect())
}

/// The arrays a file's range counts size: the listing and the coordinates, reserved at their
/// exact size and zero-filled for the ranges to be parsed into in place.
struct Sized {
    raw: RawInput,
    data: Vec<f64>,
    /// Coordinates per `v` line (`None`: no `v` line).
    dim: Option<usize>,
    vertices: usize,
}

impl Sized {
    /// `None` when the ranges disagree on the coordinate count, hold nothing, more than 2^32
    /// vertices, or memory cannot be had.
    fn of<'c>(counts: impl IntoIterator<Item = &'c Counts> + Clone) -> Option<Sized> {
        let all = || counts.clone().into_iter();
        let dim = all().find_map(|c| c.dim);
        if all().any(|c| c.dim.is_some() && c.dim != dim) {
            return None;
        }
        let (simplices, ids, vertices) = all().fold((0usize, 0usize, 0usize), |t, c| {
            (t.0 + c.simplices, t.1 + c.ids, t.2 + c.vertices)
        });
        if simplices + vertices == 0 || u32::try_from(vertices).is_err() {
            return None;
        }
        let coords = vertices.checked_mul(dim.unwrap_or(0))?;
        let mut raw = RawInput::new();
        raw.try_reserve(simplices, ids).ok()?;
        let mut data = Vec::new();
        table::try_reserve_exact(&mut data, coords).ok()?;
        chunked::extend_filled(&mut raw.ids, ids, 0);
        chunked::extend_filled(&mut raw.offsets, simplices, 0);
        chunked::extend_filled(&mut raw.lines, simplices, 0);
        chunked::extend_filled(&mut data, coords, 0.0);
        Some(Sized {
            raw,
            data,
            dim,
            vertices,
        })
    }

    /// The arrays' shares, handed out range by range from the start.
    fn filling(&mut self) -> Filling<'_> {
        Filling {
            ids: &mut self.raw.ids[..],
            offsets: &mut self.raw.offsets[1..],
            lines: &mut self.raw.lines[..],
            data: &mut self.data[..],
            per_vertex: self.dim.unwrap_or(0),
            line: 1,
            id_base: 0,
        }
    }

    /// The filled listing, with its vertex count and coordinates when `v` lines gave them.
    fn into_raw(self) -> RawInput {
        let mut raw = self.raw;
        if let Some(dim) = self.dim {
            raw.vertex_count = Some(self.vertices as u32);
            raw.coords = (dim > 0).then_some(Coords {
                dim,
                data: self.data,
            });
        }
        raw
    }
}

/// What is left of the arrays, and where the next range's numbering starts.
struct Filling<'a> {
    ids: &'a mut [u32],
    offsets: &'a mut [usize],
    lines: &'a mut [u32],
    data: &'a mut [f64],
    per_vertex: usize,
    line: u32,
    id_base: usize,
}

impl Filling<'_> {
    /// Parses the next ranges of `text` (in file order, with their counts) into their shares,
    /// on several threads. `None` when one is not plain.
    fn ranges<'c>(
        &mut self,
        text: &str,
        ranges: impl Iterator<Item = ((usize, usize), &'c Counts)>,
    ) -> Option<()> {
        fn take<'a, T>(left: &mut &'a mut [T], n: usize) -> &'a mut [T] {
            let (part, rest) = std::mem::take(left).split_at_mut(n);
            *left = rest;
            part
        }
        let mut parts = Vec::new();
        for (range, c) in ranges {
            let i = take(&mut self.ids, c.ids);
            let o = take(&mut self.offsets, c.simplices);
            let l = take(&mut self.lines, c.simplices);
            let d = take(&mut self.data, c.vertices * self.per_vertex);
            parts.push((range, self.line, self.id_base, i, o, l, d));
            self.line = self.line.checked_add(u32::try_from(c.lines).ok()?)?;
            self.id_base += c.ids;
        }
        let filled = crate::parallel::install(|| {
            use rayon::prelude::*;
            parts
                .into_par_iter()
                .all(|(range, line, id_base, i, o, l, d)| {
                    fill_range(text, range, line, id_base, i, o, l, d).is_some()
                })
        });
        filled.then_some(())
    }
}

/// Files from this size are read in blocks ([`read_in_blocks`]).
pub(crate) const BLOCKS_FROM: u64 = 32 << 20;

/// The size of a block of [`read_in_blocks`] (extended to the end of its last line).
const BLOCK: usize = 8 << 20;

/// One block of the file: where it starts and how long it is (whole lines), with its ranges of
/// lines and their counts.
struct Block {
    at: u64,
    len: usize,
    ranges: Vec<((usize, usize), Counts)>,
}

/// Reads a large `.simplices` file as [`parse_in_parallel`] reads its text, without ever
/// holding the whole text: a first pass reads the file in blocks of about 8 MiB of whole lines
/// and counts each block's ranges of lines; the arrays are reserved at their exact size; a
/// second pass reads the blocks again and parses each range into its place. The peak is the
/// reader's output and one block, not the output and the file (the file's bytes were a fifth
/// of the peak for lines of 4 bytes). `None` whenever anything is not plain — a line that the
/// parallel reader does not read, a block that is not UTF-8 or holds no line end, a file that
/// changed between the passes, memory that cannot be had — for the caller to read the file
/// whole (and report the first error with its line). Cost: the file read twice.
#[cfg(unix)]
pub(crate) fn read_in_blocks(path: &std::path::Path) -> Option<RawInput> {
    read_in_blocks_of(path, BLOCK)
}

/// [`read_in_blocks`] with blocks of about `block` bytes.
#[cfg(unix)]
fn read_in_blocks_of(path: &std::path::Path, block: usize) -> Option<RawInput> {
    use std::os::unix::fs::FileExt;
    let (file, meta) = super::open_regular(path).ok()?;
    let size = meta.len();
    let mut buf: Vec<u8> = Vec::new();
    table::try_reserve_exact(&mut buf, block).ok()?;
    // The block at `at`: up to BLOCK bytes, cut after its last line end (the file's end ends
    // the last); `None` when a block holds no line end or is not UTF-8.
    let read = |at: u64, len: Option<usize>, buf: &mut Vec<u8>| -> Option<usize> {
        let want = len.unwrap_or_else(|| block.min((size - at) as usize));
        buf.clear();
        buf.resize(want, 0);
        file.read_exact_at(buf, at).ok()?;
        let end = if len.is_some() || at + want as u64 == size {
            want
        } else {
            memchr::memrchr(b'\n', buf)? + 1
        };
        buf.truncate(end);
        std::str::from_utf8(buf).ok()?;
        Some(end)
    };
    // The first pass: blocks and their counts.
    let mut blocks = Vec::new();
    let mut at = 0u64;
    while at < size {
        let len = read(at, None, &mut buf)?;
        let mut start = 0;
        if at == 0 && buf.starts_with("\u{feff}".as_bytes()) {
            start = 3;
        }
        let text = std::str::from_utf8(&buf[start..]).ok()?;
        let ranges = counted_ranges(text)?.into_iter();
        blocks.push(Block {
            at,
            len,
            ranges: ranges
                .map(|((a, z), c)| ((a + start, z + start), c))
                .collect(),
        });
        at += len as u64;
    }
    let mut sized = Sized::of(blocks.iter().flat_map(|b| b.ranges.iter().map(|(_, c)| c)))?;
    // The second pass: each block read again, its ranges parsed into their shares.
    let mut fill = sized.filling();
    for block in &blocks {
        read(block.at, Some(block.len), &mut buf)?;
        let text = std::str::from_utf8(&buf).ok()?;
        fill.ranges(text, block.ranges.iter().map(|(r, c)| (*r, c)))?;
    }
    // Nothing changed between the passes (a file that grew or shrank).
    if file.metadata().ok()?.len() != size {
        return None;
    }
    chunked::note_section();
    Some(sized.into_raw())
}

/// The first pass over one range: its counts, `None` when a line is not plain.
fn count_range(text: &str, (a, z): (usize, usize)) -> Option<Counts> {
    let mut s = Scanner::at_line(&text[..z], a, 1);
    let mut c = Counts::default();
    loop {
        if let Some((keyword, _)) = s.token_in_line() {
            let mut n = 0;
            while s.token_in_line().is_some() {
                n += 1;
            }
            match keyword {
                "v" => {
                    if *c.dim.get_or_insert(n) != n {
                        return None;
                    }
                    c.vertices += 1;
                }
                "s" if n > 0 => {
                    c.simplices += 1;
                    c.ids += n;
                }
                _ => return None,
            }
        }
        if !s.next_line() {
            break;
        }
        c.lines += 1;
    }
    Some(c)
}

/// The second pass over one range, whose first line is `line` and first id lands at `id_base`
/// of the whole: its ids, offsets, lines and coordinates written into its shares. `None` when
/// a number is not what the serial reader accepts.
#[allow(clippy::too_many_arguments)]
fn fill_range(
    text: &str,
    (a, z): (usize, usize),
    line: u32,
    id_base: usize,
    ids: &mut [u32],
    offsets: &mut [usize],
    lines: &mut [u32],
    coords: &mut [f64],
) -> Option<()> {
    let mut s = Scanner::at_line(&text[..z], a, line);
    let (mut at, mut simplex, mut x) = (0, 0, 0);
    loop {
        if let Some((keyword, l)) = s.token_in_line() {
            if keyword == "v" {
                loop {
                    *coords.get_mut(x)? = match s.real(false) {
                        Some((v, _)) => v,
                        None => match s.token_in_line() {
                            Some((tok, _)) => parse_f64(tok, "").ok()?,
                            None => break,
                        },
                    };
                    x += 1;
                }
            } else {
                loop {
                    *ids.get_mut(at)? = match s.digits(false) {
                        Some((v, _)) => scan::id_value(v, false).ok()?,
                        None => match s.token_in_line() {
                            Some((tok, _)) => scan::id(tok, false).ok()?,
                            None => break,
                        },
                    };
                    at += 1;
                }
                *offsets.get_mut(simplex)? = id_base + at;
                *lines.get_mut(simplex)? = l;
                simplex += 1;
            }
        }
        if !s.next_line() {
            break;
        }
    }
    (at == ids.len() && simplex == offsets.len() && x == coords.len()).then_some(())
}

/// The serial reader.
fn parse_serially(text: &str) -> Result<RawInput, (u32, ReadErrorKind)> {
    let mut s = Scanner::new(text);
    let mut raw = RawInput::new();
    let mut data = Vec::new();
    // (number of coordinates, line) of the first `v` line.
    let mut first_v: Option<(usize, u32)> = None;
    let mut vertices: u32 = 0;
    let mut ids = Vec::new();
    let mut labels = Labels::default();
    let mut label = None;
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
                                Some((":", _)) => {
                                    label = Some(read_label(&mut s).map_err(err)?);
                                    break;
                                }
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
                    labels.keep(label.take(), line).map_err(err)?;
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

    if let Some(values) = labels.values {
        raw.attributes.insert(Attribute {
            name: LABEL.to_string(),
            location: Location::Listed,
            components: 1,
            values: Values::I64(values),
        });
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

    /// A file read in blocks of `block` bytes reads as its whole text parses (ids, offsets,
    /// lines, vertex count, coordinates), or is left to the whole read (`None`).
    fn blocks_read_as_the_text(name: &str, text: &str, block: usize) -> Option<RawInput> {
        let path = std::env::temp_dir().join(format!("tpx-blocks-{}-{name}", std::process::id()));
        std::fs::write(&path, text).unwrap();
        let got = read_in_blocks_of(&path, block);
        std::fs::remove_file(&path).ok();
        if let Some(got) = &got {
            let want = parse(text.strip_prefix('\u{feff}').unwrap_or(text)).unwrap();
            assert_eq!(got, &want, "{name}");
        }
        got
    }

    #[test]
    fn files_read_in_blocks_read_as_their_text() {
        // Lines of every length and ending, comments, blank lines, vertices between simplices.
        let mut text = String::from("\u{feff}# head\r\nv 0 0\nv 1 0\rv 0 1\r\n\n");
        for i in 0..4000u32 {
            match i % 5 {
                0 => text.push_str(&format!("s {} {}\r\n", i % 3, i % 3 + 1)),
                1 => text.push_str(&format!("s {}\n", i % 3)),
                2 => text.push_str("v 2 2\n# a comment\n"),
                3 => text.push_str(&format!("s 0 1 2 {}\r", 3 + i % 7)),
                _ => text.push_str("\t s 1 2\t\n\n"),
            }
        }
        text.push_str("s 0 1");
        for block in [64, 1000, 4096, 1 << 20] {
            let got = blocks_read_as_the_text("mixed.simplices", &text, block);
            assert!(got.is_some(), "block {block}");
        }
        // Without vertices, and a file of one block.
        let plain = "s 1 2 3\n".repeat(3000);
        assert!(blocks_read_as_the_text("plain.simplices", &plain, 4096).is_some());
        assert!(blocks_read_as_the_text("plain1.simplices", &plain, 1 << 20).is_some());
        // Labels, errors and v lines of other widths are left to the whole read.
        let labelled = "s 0 1 : 3\n".repeat(1000);
        assert!(blocks_read_as_the_text("labels.simplices", &labelled, 512).is_none());
        let bad = format!("{plain}s 0 x\n{plain}");
        assert!(blocks_read_as_the_text("bad.simplices", &bad, 4096).is_none());
        let widths = format!("v 0 0\n{plain}v 0 0 0\n");
        assert!(blocks_read_as_the_text("widths.simplices", &widths, 4096).is_none());
        // A line longer than a block.
        let long = format!("s {}\n", "1 ".repeat(5000));
        assert!(blocks_read_as_the_text("long.simplices", &long.repeat(3), 4096).is_none());
    }

    #[test]
    fn labels_after_a_colon_are_an_i64_attribute() {
        let r = ok("v\nv\nv\ns 0 1 2 : 7\ns 1 2\t:\t-9223372036854775808 # min\n");
        assert_eq!(simplices(&r), [vec![0, 1, 2], vec![1, 2]]);
        let a = r.attributes.get(LABEL, Location::Listed).unwrap();
        assert_eq!(a.values, Values::I64(vec![7, i64::MIN]));
        assert!(ok("s 0 1\n").attributes.is_empty());
        err(
            "s 0 1 : 7\ns 1 2\n",
            2,
            "s line has no label, but the first s line (line 1) has one",
        );
        err(
            "s 0 1\ns 1 2 : 7\n",
            2,
            "s line has a label, but the first s line (line 1) has none",
        );
        err("s 0 1 :\n", 1, "s line ends after ':'");
        err(
            "s 0 1 : 1.5\n",
            1,
            "label '1.5' after ':' is not an integer",
        );
        err(
            "s 0 1 : 9223372036854775808\n",
            1,
            "not an integer that fits 64 bits",
        );
        err("s 0 1 : 7 8\n", 1, "'8' after the label of an s line");
        // Written back, read back the same (ids and labels).
        let mut out = Vec::new();
        super::super::write::Format::Simplices
            .write(&r)
            .map(|b| out = b)
            .unwrap();
        let back = ok(std::str::from_utf8(&out).unwrap());
        assert!(back.attributes.bits_eq(&r.attributes));
        assert_eq!(back.ids, r.ids);
    }

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
