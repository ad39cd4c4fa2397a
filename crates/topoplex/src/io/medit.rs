//! Reader for ASCII MEDIT mesh files (`.mesh`).
//!
//! The file must start with `MeshVersionFormatted n` (n = 1 to 4) and `Dimension d` (d = 2 or
//! 3); a value may be on the keyword's line or a later one, as the reader is token-based (with
//! the line of every token kept for errors). Then sections, each a keyword, a count and the
//! entries:
//!
//! | section | entry |
//! |---|---|
//! | `Vertices` | d coordinates and a reference (kept: `medit:ref`) |
//! | `Edges`, `Triangles`, `Tetrahedra` | 2, 3, 4 vertex ids (1-based) and a reference (kept: `medit:ref`) |
//! | `Corners`, `Ridges`, `RequiredVertices`, `RequiredEdges`, `RequiredTriangles` | 1 integer (skipped) |
//! | `Normals`, `Tangents` | d numbers (skipped) |
//! | `NormalAtVertices`, `TangentAtVertices` | 2 integers (skipped) |
//! | `NormalAtTriangleVertices` | 3 integers (skipped) |
//! | `Identifier`, `Geometry` | no count: one string, the rest of the keyword's line or else the next line (skipped) |
//! | `Quadrilaterals` | an error ([`ReadErrorKind::Polygon`]`(4)`) unless empty |
//! | `Hexahedra` | an error ("hexahedra are not simplices") unless empty |
//!
//! `End` is optional; nothing but comments may follow it. Keywords are matched in any case.
//! Any other keyword is an error naming it. `#` starts a comment.
//!
//! * Each element is recorded at the line of its first vertex id. Ids must be >= 1 and fit in 32
//!   bits after conversion to 0-based; a negative id is [`ReadErrorKind::NegativeId`] (with the
//!   value as written). Ids beyond the vertex count are left to the complex model.
//! * Coordinates are parsed as `f64`; `nan`, `inf` and `infinity` are accepted, since topology
//!   does not use coordinates, but a finite number that would become infinite or 0 (`1e309`,
//!   `1e-400`) is an error. Lines end in LF, CRLF or a lone CR.
//! * References must be integers that fit in 32 bits; they are kept as the `i32` attribute
//!   `medit:ref` on the vertices and on the listed simplices (meshio's name), each unless all of
//!   its references are 0 (MEDIT's "no reference", which the writer writes where an element has
//!   none, so nothing is lost).
//! * Only one `Vertices` section is allowed; element sections may repeat (they add up). Without a
//!   `Vertices` section the vertex count is 0.
//! * A section ending before its count is reached is an error naming the file's last line.

use super::chunked;
use super::scan::{self, Scanner};
use super::{
    Coords, RawInput, ReadErrorKind, capped, check_integer, echo, no_room, parse_count, parse_f64,
    parse_integer, syntax, try_with_capacity,
};
use crate::complex::table;
use crate::complex::{Attribute, Location};
use crate::io::Res;

/// The attribute name of MEDIT references (meshio's).
pub const REF: &str = "medit:ref";

/// What one number of a section entry is.
#[derive(Clone, Copy, PartialEq)]
enum Item {
    /// 1-based vertex id, kept.
    Id,
    /// Coordinate, kept.
    Coord,
    /// Reference number: a 32-bit integer, kept apart.
    Ref,
    /// Other integer, ignored.
    Int,
    /// Other real number, ignored.
    Real,
}

struct Reader<'a> {
    t: Scanner<'a>,
    text: &'a str,
}

impl<'a> Reader<'a> {
    /// The token after `keyword`, or an error naming what was expected.
    fn value(&mut self, keyword: &str, expected: &str) -> Res<(&'a str, u32)> {
        let eof = |t: &Scanner| t.eof_line();
        self.t.token().ok_or_else(|| {
            (
                eof(&self.t),
                syntax(format!("file ends after '{keyword}'; expected {expected}")),
            )
        })
    }

    /// Reads a section's count.
    fn count(&mut self, keyword: &str) -> Res<u32> {
        let what = format!("{} count", nouns(keyword).0);
        let (tok, l) = self.value(keyword, &format!("the {what}"))?;
        parse_count(tok, &what).map_err(|k| (l, k))
    }

    /// Reads `count` entries laid out as `items`, calling `entry` with the kept numbers (ids or
    /// coordinates) and the line of the entry's first number.
    fn entries(
        &mut self,
        keyword: &str,
        count: u32,
        items: &[Item],
        mut entry: impl FnMut(&[u32], &[f64], i32, u32) -> Result<(), ReadErrorKind>,
    ) -> Res<()> {
        let (name, names) = nouns(keyword);
        let mut ids = Vec::with_capacity(items.len());
        let mut xs = Vec::with_capacity(items.len());
        for e in 0..count {
            ids.clear();
            xs.clear();
            let mut first_line = 0;
            let mut reference = 0;
            for (j, &item) in items.iter().enumerate() {
                let l = match self.fast_item(item, &mut ids, &mut xs, &mut reference) {
                    Some(r) => r?,
                    None => {
                        let Some((tok, l)) = self.t.token() else {
                            let msg = if j == 0 {
                                format!(
                                    "{name} count {count} declared but file ends after {e} {names}"
                                )
                            } else {
                                format!(
                                    "file ends inside {name} {}: expected {} numbers ({}), found \
                                     {j}",
                                    e + 1,
                                    items.len(),
                                    layout(items)
                                )
                            };
                            return Err((self.t.eof_line(), syntax(msg)));
                        };
                        let r = match item {
                            Item::Id => scan::id(tok, true).map(|id| ids.push(id)),
                            Item::Coord => {
                                parse_f64(tok, "a vertex coordinate").map(|x| xs.push(x))
                            }
                            Item::Ref => reference_value(tok).map(|r| reference = r),
                            Item::Int => {
                                check_integer(tok, "").map_err(|_| int_entry_error(tok, keyword))
                            }
                            Item::Real => parse_f64(tok, &format!("a {keyword} entry")).map(|_| ()),
                        };
                        r.map_err(|k| (l, k))?;
                        l
                    }
                };
                if j == 0 {
                    first_line = l;
                }
            }
            entry(&ids, &xs, reference, first_line).map_err(|k| (first_line, k))?;
        }
        Ok(())
    }

    /// Fast path for one number of an entry (see [`Scanner::digits`]): `None` leaves the token
    /// to the general path. Returns the number's line.
    #[inline]
    fn fast_item(
        &mut self,
        item: Item,
        ids: &mut Vec<u32>,
        xs: &mut Vec<f64>,
        reference: &mut i32,
    ) -> Option<Res<u32>> {
        match item {
            Item::Id => self.t.digits(true).map(|(v, l)| {
                let id = scan::id_value(v, true).map_err(|k| (l, k))?;
                ids.push(id);
                Ok(l)
            }),
            Item::Coord => self.t.real(true).map(|(x, l)| {
                xs.push(x);
                Ok(l)
            }),
            Item::Ref => self.t.digits(true).map(|(v, l)| {
                *reference = i32::try_from(v).map_err(|_| (l, reference_range(v)))?;
                Ok(l)
            }),
            Item::Int => self.t.digits(true).map(|(_, l)| Ok(l)),
            Item::Real => self.t.real(true).map(|(_, l)| Ok(l)),
        }
    }

    /// Reads a section's `count` entries on several threads when it is large and laid out one
    /// entry per line (see [`chunked`]): the `per` kept numbers of each entry (ids or
    /// coordinates) appended to `out` and each entry's reference to `refs`, whose capacities
    /// must be reserved, and the scanner moved past the section. `None` (nothing appended, the
    /// scanner unmoved) otherwise: the serial [`Reader::entries`] then reads the section,
    /// errors included.
    fn parallel_entries<T: Kept>(
        &mut self,
        count: u32,
        items: &[Item],
        out: &mut Vec<T>,
        per: usize,
        refs: &mut Vec<i32>,
    ) -> Option<chunked::Body> {
        let n = count as usize;
        if !crate::parallel::splits(n)
            || out.capacity() - out.len() < n.checked_mul(per)?
            || refs.capacity() - refs.len() < n
        {
            return None;
        }
        // The entries start on the next line: nothing but a comment may follow the count.
        let mut sc = self.t.clone();
        if sc.token_in_line().is_some() || !sc.next_line() {
            return None;
        }
        let body = chunked::body(self.text, sc.pos(), sc.line(), n)?;
        let (base, ref_base) = (out.len(), refs.len());
        chunked::extend_filled(out, n * per, T::default());
        chunked::extend_filled(refs, n, 0);
        let (slots, ref_slots) = (&mut out[base..], &mut refs[ref_base..]);
        let read = chunked::fill_with_side(
            self.text,
            &body,
            slots,
            per,
            ref_slots,
            |sc, slot, mut r| {
                let mut kept = 0;
                for &item in items {
                    match item_in_line(sc, item)? {
                        Num::Skip => {}
                        Num::Ref(v) => *r.as_deref_mut()? = v,
                        num => {
                            *slot.get_mut(kept)? = T::from_num(num)?;
                            kept += 1;
                        }
                    }
                }
                Some(()).filter(|_| kept == per)
            },
        );
        if !read {
            out.truncate(base);
            refs.truncate(ref_base);
            return None;
        }
        self.t.place(body.end.0, body.end.1);
        Some(body)
    }
}

/// One number of an entry as [`Reader::entries`] reads it: `None` when the line ends first
/// or the number is not what the item needs (the serial reader then reads it and reports it).
#[inline]
fn item_in_line(sc: &mut Scanner<'_>, item: Item) -> Option<Num> {
    match item {
        Item::Id => match sc.digits(false) {
            Some((v, _)) => scan::id_value(v, true).ok().map(Num::Id),
            None => scan::id(sc.token_in_line()?.0, true).ok().map(Num::Id),
        },
        Item::Coord | Item::Real => {
            let x = match sc.real(false) {
                Some((x, _)) => x,
                None => parse_f64(sc.token_in_line()?.0, "").ok()?,
            };
            Some(if item == Item::Coord {
                Num::X(x)
            } else {
                Num::Skip
            })
        }
        Item::Ref => match sc.digits(false) {
            Some((v, _)) => i32::try_from(v).ok().map(Num::Ref),
            None => reference_value(sc.token_in_line()?.0).ok().map(Num::Ref),
        },
        Item::Int => match sc.digits(false) {
            Some(_) => Some(Num::Skip),
            None => check_integer(sc.token_in_line()?.0, "")
                .ok()
                .map(|()| Num::Skip),
        },
    }
}

/// A number of an entry read on a thread: a vertex id, a coordinate, a reference, or one that
/// is skipped.
#[derive(Clone, Copy)]
enum Num {
    Id(u32),
    X(f64),
    Ref(i32),
    Skip,
}

/// A reference number: an integer that fits in 32 bits (libMeshb's and meshio's `int`).
fn reference_value(tok: &str) -> Result<i32, ReadErrorKind> {
    check_integer(tok, "reference number")?;
    match parse_integer(tok) {
        Ok(v) => i32::try_from(v).map_err(|_| {
            syntax(format!(
                "reference number '{}' does not fit in 32 bits (attribute 'medit:ref' holds i32)",
                echo(tok)
            ))
        }),
        Err(_) => Err(syntax(format!(
            "reference number '{}' does not fit in 32 bits (attribute 'medit:ref' holds i32)",
            echo(tok)
        ))),
    }
}

/// The error for a reference of the fast path above `i32::MAX`.
fn reference_range(v: u64) -> ReadErrorKind {
    reference_value(&v.to_string()).unwrap_err()
}

/// What an entry keeps: vertex ids (`u32`) or coordinates (`f64`).
trait Kept: Copy + Default + Send + Sync {
    fn from_num(n: Num) -> Option<Self>;
}

impl Kept for u32 {
    fn from_num(n: Num) -> Option<u32> {
        match n {
            Num::Id(v) => Some(v),
            _ => None,
        }
    }
}

impl Kept for f64 {
    fn from_num(n: Num) -> Option<f64> {
        match n {
            Num::X(x) => Some(x),
            _ => None,
        }
    }
}

/// Reads an element section of `count` entries of `items` into `raw` on several threads (see
/// [`Reader::parallel_entries`]); false, with nothing read, for the serial reader to read it.
fn elements_in_parallel(
    r: &mut Reader<'_>,
    count: u32,
    items: &[Item],
    raw: &mut RawInput,
    refs: &mut Vec<i32>,
) -> bool {
    let (n, k) = (count as usize, items.len() - 1);
    let room = |len: usize, cap: usize| cap - len >= n;
    if !room(raw.offsets.len(), raw.offsets.capacity())
        || !room(raw.lines.len(), raw.lines.capacity())
    {
        return false;
    }
    let base = raw.ids.len();
    let Some(body) = r.parallel_entries(count, items, &mut raw.ids, k, refs) else {
        return false;
    };
    // One entry a line: offsets and lines follow from the position.
    let first = body.first_line;
    chunked::extend_with(&mut raw.offsets, n, |i| base + (i + 1) * k)
        && chunked::extend_with(&mut raw.lines, n, |i| first + i as u32)
}

/// The error for a token of an integer section (`Corners`, ...) that is not an integer.
fn int_entry_error(tok: &str, keyword: &str) -> ReadErrorKind {
    check_integer(tok, &format!("{keyword} entry")).unwrap_err()
}

/// Singular and plural nouns for a section's entries, for messages: "triangle", "triangles"
/// for the simplex and polyhedron sections, "Corners entry", "Corners entries" for the others.
fn nouns(keyword: &str) -> (String, String) {
    let (one, many) = match keyword.to_ascii_lowercase().as_str() {
        "vertices" => ("vertex", "vertices"),
        "edges" => ("edge", "edges"),
        "triangles" => ("triangle", "triangles"),
        "tetrahedra" => ("tetrahedron", "tetrahedra"),
        "quadrilaterals" => ("quadrilateral", "quadrilaterals"),
        "hexahedra" => ("hexahedron", "hexahedra"),
        _ => return (format!("{keyword} entry"), format!("{keyword} entries")),
    };
    (one.into(), many.into())
}

fn layout(items: &[Item]) -> String {
    let count = |i: Item| items.iter().filter(|&&x| x == i).count();
    let mut parts = Vec::new();
    for (item, what) in [
        (Item::Id, "vertex ids"),
        (Item::Coord, "coordinates"),
        (Item::Ref, "reference"),
        (Item::Int, "integers"),
        (Item::Real, "numbers"),
    ] {
        let n = count(item);
        if n > 0 {
            parts.push(format!("{n} {what}"));
        }
    }
    parts.join(", ")
}

/// Parses MEDIT (`.mesh`) text; errors carry the 1-based line.
pub fn parse(text: &str) -> Result<RawInput, (u32, ReadErrorKind)> {
    let mut r = Reader {
        t: Scanner::new(text),
        text,
    };
    r.version()?;
    let dim = r.dimension()?;
    let mut mesh = Mesh {
        dim,
        raw: RawInput::new(),
        refs: Vec::new(),
        vertices: None,
    };
    while let Some((kw, l)) = r.t.token() {
        if !r.section(kw, l, &mut mesh)? {
            break;
        }
    }
    Ok(mesh.into_raw())
}

/// What the sections have read so far.
struct Mesh {
    /// The `Dimension` of the header: coordinates per vertex.
    dim: usize,
    /// The element sections' simplices.
    raw: RawInput,
    /// The element sections' references, one per simplex of `raw`.
    refs: Vec<i32>,
    /// The `Vertices` section, once read: its count, coordinates and references.
    vertices: Option<(u32, Vec<f64>, Vec<i32>)>,
}

impl Mesh {
    /// The simplices with the vertex count, coordinates (none without a `Vertices` section)
    /// and references: `medit:ref` on the vertices and on the listed simplices, each kept
    /// unless all its references are 0 (MEDIT's "no reference", which the writer writes where
    /// there is none: nothing is lost).
    fn into_raw(self) -> RawInput {
        let Mesh {
            dim,
            mut raw,
            refs,
            vertices,
        } = self;
        let (n, data, vertex_refs) = vertices.unwrap_or_default();
        raw.vertex_count = Some(n);
        raw.coords = Some(Coords { dim, data });
        for (location, refs) in [(Location::Vertices, vertex_refs), (Location::Listed, refs)] {
            if refs.iter().any(|&r| r != 0) {
                raw.attributes
                    .insert(Attribute::labels(REF, location, refs));
            }
        }
        raw
    }
}

impl<'a> Reader<'a> {
    /// `MeshVersionFormatted` and its value (1 to 4), which must open the file.
    fn version(&mut self) -> Res<()> {
        let (tok, l) = self.header_value(
            "MeshVersionFormatted",
            ("file is empty", "at the start of the file"),
            "the version number",
        )?;
        if !matches!(parse_integer(tok), Ok(1..=4)) {
            let tok = echo(tok);
            return Err((
                l,
                syntax(format!(
                    "unsupported MeshVersionFormatted '{tok}' (expected 1, 2, 3 or 4)"
                )),
            ));
        }
        Ok(())
    }

    /// `Dimension` and its value (2 or 3), which must follow the version.
    fn dimension(&mut self) -> Res<usize> {
        let (tok, l) = self.header_value(
            "Dimension",
            ("file ends after the version", "after MeshVersionFormatted"),
            "the dimension",
        )?;
        match parse_integer(tok) {
            Ok(d @ 2..=3) => Ok(d as usize),
            _ => {
                let tok = echo(tok);
                Err((
                    l,
                    syntax(format!("Dimension must be 2 or 3, found '{tok}'")),
                ))
            }
        }
    }

    /// The value (`what`) of header keyword `keyword`, which must be the next token (in any
    /// case). `(at_end, place)`: what the file is when it ends before the keyword, and where
    /// the keyword must stand, for the errors.
    fn header_value(
        &mut self,
        keyword: &str,
        (at_end, place): (&str, &str),
        what: &str,
    ) -> Res<(&'a str, u32)> {
        let Some((kw, l)) = self.t.token() else {
            return Err((
                self.t.eof_line(),
                syntax(format!("{at_end}; expected '{keyword}'")),
            ));
        };
        if !kw.eq_ignore_ascii_case(keyword) {
            let kw = echo(kw);
            return Err((
                l,
                syntax(format!("expected '{keyword}' {place}, found '{kw}'")),
            ));
        }
        self.value(kw, what)
    }

    /// The section that keyword `kw` (at line `l`) opens, read into `mesh`; false at `End`.
    fn section(&mut self, kw: &'a str, l: u32, mesh: &mut Mesh) -> Res<bool> {
        let dim = mesh.dim;
        match kw.to_ascii_lowercase().as_str() {
            "end" => {
                if let Some((tok, l)) = self.t.token() {
                    return Err((
                        l,
                        syntax(format!("unexpected content '{}' after End", echo(tok))),
                    ));
                }
                return Ok(false);
            }
            "vertices" => self.vertices(kw, l, mesh)?,
            "edges" => self.elements(kw, l, 2, mesh)?,
            "triangles" => self.elements(kw, l, 3, mesh)?,
            "tetrahedra" => self.elements(kw, l, 4, mesh)?,
            "corners" | "ridges" | "requiredvertices" | "requirededges" | "requiredtriangles" => {
                self.skipped(kw, &[Item::Int])?;
            }
            "normals" | "tangents" => self.skipped(kw, &vec![Item::Real; dim])?,
            "normalatvertices" | "tangentatvertices" => self.skipped(kw, &[Item::Int; 2])?,
            "normalattrianglevertices" => self.skipped(kw, &[Item::Int; 3])?,
            "identifier" | "geometry" => {
                // The string is the rest of this line, or else the whole next line.
                if self.t.token_in_line().is_none() {
                    self.value(kw, "a string")?;
                }
                self.t.skip_rest_of_line();
            }
            "quadrilaterals" => self.reject(kw, ReadErrorKind::Polygon(4))?,
            "hexahedra" => self.reject(kw, syntax("hexahedra are not simplices"))?,
            lower => return Err((l, not_a_section(kw, lower))),
        }
        Ok(true)
    }

    /// The `Vertices` section (at line `l`): its count and `dim` coordinates a vertex.
    fn vertices(&mut self, kw: &str, l: u32, mesh: &mut Mesh) -> Res<()> {
        if mesh.vertices.is_some() {
            return Err((l, syntax("second Vertices section")));
        }
        let dim = mesh.dim;
        let items: Vec<Item> = std::iter::repeat_n(Item::Coord, dim)
            .chain([Item::Ref])
            .collect();
        let n = self.count(kw)?;
        let cap = capped((n as usize).saturating_mul(dim), self.text);
        let mut data = try_with_capacity(cap, "the vertex coordinates").map_err(|k| (l, k))?;
        let mut refs = try_with_capacity(capped(n as usize, self.text), "the vertex references")
            .map_err(|k| (l, k))?;
        if self
            .parallel_entries(n, &items, &mut data, dim, &mut refs)
            .is_none()
        {
            self.entries(kw, n, &items, |_, xs, r, _| {
                table::try_extend(&mut data, xs).map_err(no_room("the vertex coordinates"))?;
                table::try_push(&mut refs, r).map_err(no_room("the vertex references"))
            })?;
        }
        mesh.vertices = Some((n, data, refs));
        Ok(())
    }

    /// An element section (at line `l`) of simplices of `k` vertices, appended to `mesh`'s
    /// simplices and references.
    fn elements(&mut self, kw: &str, l: u32, k: usize, mesh: &mut Mesh) -> Res<()> {
        let n = self.count(kw)?;
        let cap = capped(n as usize, self.text);
        let (raw, refs) = (&mut mesh.raw, &mut mesh.refs);
        raw.try_reserve(cap, cap.saturating_mul(k).min(self.text.len()))
            .map_err(|e| (l, e))?;
        table::try_reserve_exact(refs, cap)
            .map_err(|bytes| (l, no_room("the element references")(bytes)))?;
        let items: Vec<Item> = std::iter::repeat_n(Item::Id, k)
            .chain([Item::Ref])
            .collect();
        if !elements_in_parallel(self, n, &items, raw, refs) {
            self.entries(kw, n, &items, |ids, _, r, line| {
                raw.try_push(ids, line)?;
                table::try_push(refs, r).map_err(no_room("the element references"))
            })?;
        }
        Ok(())
    }

    /// A section of elements that are not simplices: an error at its first entry, if any.
    fn reject(&mut self, keyword: &str, kind: ReadErrorKind) -> Res<()> {
        let count = self.count(keyword)?;
        if count == 0 {
            return Ok(());
        }
        let (name, names) = nouns(keyword);
        match self.t.token() {
            Some((_, l)) => Err((l, kind)),
            None => Err((
                self.t.eof_line(),
                syntax(format!(
                    "{name} count {count} declared but file ends after 0 {names}"
                )),
            )),
        }
    }

    /// A section whose entries (laid out as `items`) are checked and dropped.
    fn skipped(&mut self, kw: &str, items: &[Item]) -> Res<()> {
        let n = self.count(kw)?;
        self.entries(kw, n, items, |_, _, _, _| Ok(()))
    }
}

/// The error for keyword `kw` (`lower` in lower case) where no section it names may stand.
fn not_a_section(kw: &str, lower: &str) -> ReadErrorKind {
    if lower == "meshversionformatted" || lower == "dimension" {
        return syntax(format!("'{kw}' may appear only once, at the start"));
    }
    let kw_shown = echo(kw);
    if parse_f64(kw, "").is_ok() {
        return syntax(format!(
            "unexpected number '{kw_shown}' where a section keyword was expected (does the \
             previous section hold more entries than its count?)"
        ));
    }
    syntax(format!("unknown MEDIT section keyword '{kw_shown}'"))
}

#[cfg(test)]
mod tests {
    use super::*;

    reader_test_helpers!();

    const HEAD: &str = "MeshVersionFormatted 2\nDimension 3\n";

    #[test]
    fn all_simplex_sections() {
        let text = "MeshVersionFormatted 1\n\nDimension\n3\n\
                    Vertices\n4\n0 0 0 1\n1 0 0 1\n0 1 0 2\n0 0 1 -1\n\
                    Edges\n1\n1 2 7\n\
                    Triangles\n2\n1 2 3 0\n2 3 4 0\n\
                    Tetrahedra\n1\n1 2 3 4 5\n\
                    End\n";
        let r = ok(text);
        assert_eq!(r.vertex_count, Some(4));
        let c = r.coords.as_ref().unwrap();
        assert_eq!(c.dim, 3);
        assert_eq!(c.data[9..], [0., 0., 1.]);
        assert_eq!(
            simplices(&r),
            [vec![0, 1], vec![0, 1, 2], vec![1, 2, 3], vec![0, 1, 2, 3]]
        );
        assert_eq!(r.lines, [13, 16, 17, 20]);
    }

    #[test]
    fn dimension_2_tokens_across_lines_comments_crlf_tabs_no_end() {
        let text = "# a square\r\nMeshVersionFormatted\t2\r\nDimension 2\r\n\
                    Vertices 3 # count on the keyword line\r\n0 0 0\t1 0 0\r\n0 1\r\n0\r\n\
                    Triangles\r\n1\r\n1 2 3 1";
        let r = ok(text);
        assert_eq!(r.coords.as_ref().unwrap().dim, 2);
        assert_eq!(r.coords.clone().unwrap().data, [0., 0., 1., 0., 0., 1.]);
        assert_eq!(simplices(&r), [[0, 1, 2]]);
        assert_eq!(r.lines, [10]);
    }

    #[test]
    fn skipped_sections() {
        let text = format!(
            "{HEAD}Identifier\n\"my mesh # 1\"\nGeometry \"a.mesh\"\n\
             Vertices\n3\n0 0 0 0\n1 0 0 0\n0 1 0 0\n\
             Corners\n1\n1\nRidges\n1\n1\nRequiredVertices\n2\n1 2\n\
             RequiredEdges\n0\nRequiredTriangles\n1\n1\n\
             Normals\n1\n0 0 1\nTangents\n1\n1 0 nan\n\
             NormalAtVertices\n1\n1 1\nTangentAtVertices\n1\n1 1\n\
             NormalAtTriangleVertices\n1\n1 1 1\n\
             Quadrilaterals\n0\nHexahedra\n0\n\
             triangles\n1\n1 2 3 0\nEND\n# trailing comment\n"
        );
        let r = ok(&text);
        assert_eq!(simplices(&r), [[0, 1, 2]]);
        assert_eq!(r.vertex_count, Some(3));
    }

    #[test]
    fn no_vertices_section() {
        let r = ok(HEAD);
        assert_eq!(r.vertex_count, Some(0));
        assert_eq!(r.simplex_count(), 0);
    }

    #[test]
    fn header_errors() {
        err(
            "Dimension 3\n",
            1,
            "expected 'MeshVersionFormatted' at the start of the file, found 'Dimension'",
        );
        err("MeshVersionFormatted\n", 1, "expected the version number");
        err(
            "MeshVersionFormatted 7\nDimension 3\n",
            1,
            "unsupported MeshVersionFormatted '7'",
        );
        err(
            "MeshVersionFormatted 1\nVertices 0\n",
            2,
            "expected 'Dimension' after MeshVersionFormatted",
        );
        err(
            "MeshVersionFormatted 1\nDimension 4\n",
            2,
            "Dimension must be 2 or 3, found '4'",
        );
        err(&format!("{HEAD}Dimension 3\n"), 3, "may appear only once");
    }

    #[test]
    fn truncated_sections() {
        err(&format!("{HEAD}Vertices\n"), 3, "expected the vertex count");
        err(
            &format!("{HEAD}Vertices\n2\n0 0 0 1\n"),
            5,
            "vertex count 2 declared but file ends after 1 vertices",
        );
        err(
            &format!("{HEAD}Vertices\n1\n0 0 0\n"),
            5,
            "file ends inside vertex 1: expected 4 numbers (3 coordinates, 1 reference), found 3",
        );
        err(
            &format!("{HEAD}Triangles\n10\n1 2 3 0\n"),
            5,
            "triangle count 10 declared but file ends after 1 triangles",
        );
        err(
            &format!("{HEAD}Tetrahedra\n1\n1 2 3"),
            5,
            "file ends inside tetrahedron 1: expected 5 numbers (4 vertex ids, 1 reference), found 3",
        );
        err(&format!("{HEAD}Identifier\n"), 3, "expected a string");
        err(
            &format!("{HEAD}RequiredVertices\n3\n1 2\n"),
            5,
            "RequiredVertices entry count 3 declared but file ends after 2 RequiredVertices entries",
        );
        err(
            &format!("{HEAD}Quadrilaterals 3\n"),
            3,
            "quadrilateral count 3 declared but file ends after 0 quadrilaterals",
        );
        err(
            &format!("{HEAD}Triangles\n4000000000\n"),
            4,
            "triangle count 4000000000 declared but file ends after 0 triangles",
        );
    }

    #[test]
    fn bad_numbers() {
        err(
            &format!("{HEAD}Vertices\n1\n0 abc 0 1\n"),
            5,
            "non-numeric token 'abc' where a vertex coordinate was expected",
        );
        err(
            &format!("{HEAD}Vertices\n1\n0 0 0 1.5\n"),
            5,
            "reference number '1.5' is not an integer",
        );
        err(
            &format!("{HEAD}Edges\n1\n1 x 0\n"),
            5,
            "non-numeric token 'x' where a vertex id was expected",
        );
        err(
            &format!("{HEAD}Edges\n1\n1 0 0\n"),
            5,
            "vertex id 0 is invalid",
        );
        err(
            &format!("{HEAD}Edges\n1\n1 4294967297 0\n"),
            5,
            "vertex id 4294967297 does not fit in 32 bits",
        );
        err(
            &format!("{HEAD}Edges\n-1\n"),
            4,
            "edge count -1 is negative",
        );
        err(
            &format!("{HEAD}Vertices\n99999999999\n"),
            4,
            "vertex count 99999999999 does not fit in 32 bits",
        );
        err(
            &format!("{HEAD}Corners\n1\n1.5\n"),
            5,
            "Corners entry '1.5' is not an integer",
        );
        assert_eq!(
            parse(&format!("{HEAD}Edges\n1\n1\n-2 0\n")),
            Err((6, ReadErrorKind::NegativeId(-2)))
        );
        let r = ok(&format!("{HEAD}Edges\n1\n1 4294967296 0\n"));
        assert_eq!(r.simplex(0), [0, u32::MAX]);
    }

    #[test]
    fn non_simplex_sections() {
        assert_eq!(
            parse(&format!("{HEAD}Quadrilaterals\n1\n1 2 3 4 0\n")),
            Err((5, ReadErrorKind::Polygon(4)))
        );
        err(
            &format!("{HEAD}Hexahedra\n1\n\n1 2 3 4 5 6 7 8 0\n"),
            6,
            "hexahedra are not simplices",
        );
    }

    #[test]
    fn unknown_section_and_extra_content() {
        err(
            &format!("{HEAD}Vertices 0\nPrisms\n1\n"),
            4,
            "unknown MEDIT section keyword 'Prisms'",
        );
        err(
            &format!("{HEAD}Edges\n1\n1 2 0 0\n"),
            5,
            "unexpected number '0' where a section keyword was expected",
        );
        err(
            &format!("{HEAD}End\n\nVertices 0\n"),
            5,
            "unexpected content 'Vertices' after End",
        );
        err(
            &format!("{HEAD}Vertices 0\nVertices 0\n"),
            4,
            "second Vertices section",
        );
    }

    #[test]
    fn cr_only_line_ends() {
        let r =
            ok("MeshVersionFormatted 2\rDimension 2\rVertices\r2\r0 0 0\r1 0 0\rEdges 1\r1 2 0\r");
        assert_eq!(r.lines, [8]);
    }

    #[test]
    fn coordinates_that_do_not_fit_a_double() {
        err(
            &format!("{HEAD}Vertices\n1\n0 1e309 0 1\n"),
            5,
            "'1e309' is too large for a 64-bit float (a vertex coordinate",
        );
        err(
            &format!("{HEAD}Vertices\n1\n0 0 1e-400 1\n"),
            5,
            "'1e-400' is too small",
        );
    }

    #[test]
    fn echoed_tokens_are_escaped() {
        err(
            &format!("{HEAD}Tri\u{b}angles\n"),
            3,
            "unknown MEDIT section keyword 'Tri\\x0bangles'",
        );
        err(
            &format!("{HEAD}Corners 1\n1\u{0}\n"),
            4,
            "non-numeric token '1\\0' where a Corners entry was expected",
        );
    }
}
