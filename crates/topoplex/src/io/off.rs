//! Reader for Geomview OFF files (`.off`), ASCII only.
//!
//! Accepted layout, as Geomview specifies it:
//!
//! ```text
//! [ST][C][N][4][n]OFF        header keyword
//! [Ndim]                     only for nOFF: the embedding dimension
//! NVertices NFaces [NEdges]  NEdges is ignored; it may be left out when NFaces ends its line
//! vertices                   coordinates, then normal (N), colour (C), texture (ST)
//! faces                      k i1 .. ik [colour]
//! ```
//!
//! * The reader is token-based: items may share a line or spread over several lines (the header
//!   may be followed by the counts on the same line). The exceptions: a face colour, which
//!   Geomview defines as the rest of the line holding the face's last vertex id: it must be 0,
//!   1, 3 or 4 numbers (integers or floats), kept as the attribute `off:color` on the listed
//!   simplices (`f64`, as many components; every face has one of one width, or none has);
//!   the edge count, which is optional at the end of the counts' line; and vertex lines, which
//!   must each hold whole vertices, the last vertex ending its line (so that colours or normals
//!   without their header prefix are refused on the line that shows them, not lines later).
//!   A file whose first vertex is on the counts' line does not use lines (a one-line OFF):
//!   its lines are not checked, and faces starting on the last vertex's line have no colour.
//! * Vertex coordinates: 3 per vertex; 4 for `4OFF`; `Ndim` for `nOFF`; `Ndim + 1` for `4nOFF`
//!   (the homogeneous component is kept as read). Normals (`N`) have 3 numbers, or as many as
//!   the vertex coordinates for `nOFF`; colours (`C`) 4 numbers; texture coordinates (`ST`) 2.
//!   Beyond the coordinates they are attributes on the vertices (`f64`): `off:normal`,
//!   `off:color`, `off:texture` (normals of more than 9 numbers are refused). Files with them
//!   (or with face colours) are read by the serial reader.
//! * Numbers are parsed as `f64`; `nan`, `inf` and `infinity` are accepted, since topology does
//!   not use coordinates, but a finite number that would become infinite or 0 is an error.
//! * A face with k = 1, 2, 3 ids is a vertex, an edge, a triangle. k > 3 is
//!   [`ReadErrorKind::Polygon`], k = 0 an error. Ids are 0-based and must fit in 32 bits; a
//!   negative id is [`ReadErrorKind::NegativeId`]. Each face is recorded at the line of its k.
//! * `#` starts a comment anywhere; blank lines, tabs, a missing final newline and LF, CRLF or
//!   lone-CR line ends are fine.
//! * Errors: missing or unknown header, `OFF BINARY`, non-numeric or overflowing numbers, files
//!   ending before the declared vertices or faces, and any non-comment content after the last
//!   face. When the file ends early the error names the file's last line.
//!
//! Ids beyond the vertex count and repeated ids are left to the complex model.

use super::chunked;
use super::scan::{self, Scanner};
use super::{
    Coords, RawInput, ReadErrorKind, capped_len, echo, integer_token, no_room, parse_count,
    parse_f64, syntax, try_with_capacity,
};
use crate::complex::attributes::MAX_COMPONENTS;
use crate::complex::{Attribute, Location, Values, table};
use crate::io::Res;

/// The prefixes of an OFF header keyword.
#[derive(Debug, Default, Clone, Copy)]
pub(super) struct Header {
    texture: bool,
    colour: bool,
    normals: bool,
    four: bool,
    ndim: bool,
}

impl Header {
    /// No prefix: the keyword is `OFF` itself (3 coordinates, nothing else per vertex).
    pub(super) fn is_plain(&self) -> bool {
        !(self.texture || self.colour || self.normals || self.four || self.ndim)
    }

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

/// Reads an OFF file's text.
pub fn parse(text: &str) -> Result<RawInput, (u32, ReadErrorKind)> {
    parse_keeping(text, false)
}

/// [`parse`], keeping faces of more than 3 vertices as polygons when `polygons` (for
/// [`super::ReadOptions::triangulate`]).
pub(crate) fn parse_keeping(text: &str, polygons: bool) -> Result<RawInput, (u32, ReadErrorKind)> {
    let mut t = Scanner::new(text);
    let h = header(&mut t)?;
    let dim = dimension(&mut t, h)?;
    let (nv, nf) = counts(&mut t)?;
    let counts_line = t.line();
    let layout = Layout::new(h, dim);
    let (data, extra, widest, last_line) = match vertices_in_parallel(&mut t, text, nv, &layout) {
        Some(data) => (data, Vec::new(), layout.per_vertex, 0),
        None => vertices(&mut t, nv, &layout, counts_line)?,
    };
    let mut raw = RawInput::new();
    raw.polygons.keep = polygons;
    raw.vertex_count = Some(nv);
    raw.coords = Some(Coords { dim, data });
    vertex_attributes(&mut raw, &layout, extra).map_err(|k| (counts_line, k))?;
    let mut colours = FaceColours::default();
    let cap = capped_len(nf as usize, t.len());
    raw.try_reserve(cap, cap.saturating_mul(3).min(t.len()))
        .map_err(|k| (counts_line, k))?;
    if !faces_in_parallel(&mut t, text, nf, &mut raw) {
        faces(&mut t, nf, &mut raw, last_line, &mut colours, |(l, k)| {
            first_face_hint(l, k, widest, &layout)
        })?;
    }
    if colours.width > 0 {
        raw.attributes.insert(Attribute {
            name: COLOR.to_string(),
            location: Location::Listed,
            components: colours.width,
            values: Values::F64(colours.values),
        });
    }
    if let Some((tok, l)) = t.token() {
        return Err((
            l,
            syntax(format!(
                "unexpected content '{}' after the end of the data ({nv} vertices and {nf} \
                 faces declared)",
                echo(tok)
            )),
        ));
    }
    Ok(raw)
}

/// The next token, or an "ends early" error with the given message.
fn next_or<'a>(t: &mut Scanner<'a>, msg: impl FnOnce() -> String) -> Res<(&'a str, u32)> {
    match t.token() {
        Some(tok) => Ok(tok),
        None => Err((t.eof_line(), syntax(msg()))),
    }
}

/// The header keyword; `OFF BINARY` is refused.
pub(super) fn header(t: &mut Scanner<'_>) -> Res<Header> {
    let Some((head, head_line)) = t.token() else {
        return Err((
            t.eof_line(),
            syntax("file is empty; expected an OFF header such as 'OFF'"),
        ));
    };
    let h = Header::parse(head).ok_or_else(|| {
        (
            head_line,
            syntax(format!(
                "expected an OFF header ([ST][C][N][4][n]OFF), found '{}'",
                echo(head)
            )),
        )
    })?;
    if let Some(("BINARY", l)) = t.peek() {
        return Err((l, syntax("binary OFF is not supported")));
    }
    Ok(h)
}

/// The number of coordinates per vertex: read after `nOFF`, else 3 (4 for `4OFF`).
fn dimension(t: &mut Scanner<'_>, h: Header) -> Res<usize> {
    if !h.ndim {
        return Ok(if h.four { 4 } else { 3 });
    }
    let (tok, l) = next_or(t, || {
        "file ends after the nOFF header; expected the dimension".into()
    })?;
    let n = parse_count(tok, "nOFF dimension").map_err(|k| (l, k))? as usize;
    if n == 0 {
        return Err((l, syntax("nOFF dimension must be at least 1, found 0")));
    }
    Ok(n + usize::from(h.four))
}

/// `NVertices NFaces [NEdges]`. The edge count is ignored, and may be left out when the face
/// count ends its line (many writers omit it); otherwise it must be a non-negative integer.
pub(super) fn counts(t: &mut Scanner<'_>) -> Res<(u32, u32)> {
    let (tok, l) = next_or(t, || {
        "file ends after the header; expected the vertex count".into()
    })?;
    let nv = parse_count(tok, "vertex count").map_err(|k| (l, k))?;
    let (tok, l) = next_or(t, || {
        "file ends after the vertex count; expected the face count".into()
    })?;
    let nf = parse_count(tok, "face count").map_err(|k| (l, k))?;
    let Some((tok, l)) = t.token_in_line() else {
        return Ok((nv, nf));
    };
    let e = || echo(tok);
    match integer_token(tok, "the", "edge count").map_err(|k| (l, k))? {
        Some(v) if v >= 0 => Ok((nv, nf)),
        None if !tok.starts_with('-') => Ok((nv, nf)),
        _ => Err((l, syntax(format!("edge count {} is negative", e())))),
    }
}

/// What each number of a vertex is.
struct Layout {
    dim: usize,
    normal: usize,
    colour: usize,
    per_vertex: usize,
    /// The numbers for messages, e.g. "3 coordinates, 4 colour".
    text: String,
}

impl Layout {
    fn new(h: Header, dim: usize) -> Layout {
        let normal = match (h.normals, h.ndim) {
            (false, _) => 0,
            (true, true) => dim,
            (true, false) => 3,
        };
        let colour = if h.colour { 4 } else { 0 };
        let texture = if h.texture { 2 } else { 0 };
        let mut text = format!("{dim} coordinates");
        for (n, what) in [(normal, "normal"), (colour, "colour"), (texture, "texture")] {
            if n > 0 {
                text.push_str(&format!(", {n} {what}"));
            }
        }
        Layout {
            dim,
            normal,
            colour,
            per_vertex: dim + normal + colour + texture,
            text,
        }
    }

    /// What number `j` of a vertex is, for messages.
    fn what(&self, j: usize) -> &'static str {
        if j < self.dim {
            "a vertex coordinate"
        } else if j < self.dim + self.normal {
            "a vertex normal component"
        } else if j < self.dim + self.normal + self.colour {
            "a vertex colour component"
        } else {
            "a vertex texture coordinate"
        }
    }
}

/// Reads `nv` vertices, keeping their coordinates. Vertices may share a line, but each line
/// holds whole vertices: extra numbers on a line (colours or normals without their header
/// prefix) are an error on that line rather than a shift that surfaces lines later.
/// Also returns the most vertex numbers one line held, and the line of the last vertex number.
///
/// The exception: a file whose vertices start on the counts' line (`counts_line`; a one-line
/// OFF such as `OFF 3 1 0 0 0 0 1 0 0 0 1 0 3 0 1 2`) does not use lines to separate its
/// items, so its lines are not checked, and the faces may follow the last vertex on its line.
fn vertices(
    t: &mut Scanner<'_>,
    nv: u32,
    layout: &Layout,
    counts_line: u32,
) -> Res<(Vec<f64>, Vec<f64>, usize, u32)> {
    let (dim, per_vertex) = (layout.dim, layout.per_vertex);
    let cap = capped_len((nv as usize).saturating_mul(dim), t.len());
    let mut data = try_with_capacity(cap, "the vertex coordinates").map_err(|k| (t.line(), k))?;
    let cap = capped_len((nv as usize).saturating_mul(per_vertex - dim), t.len());
    let mut extra =
        try_with_capacity(cap, "the vertex normals and colours").map_err(|k| (t.line(), k))?;
    // (line, numbers read on it) for the line holding the vertex numbers read last.
    let mut on_line = (0u32, 0usize);
    let mut widest = 0;
    let mut compact = false;
    for i in 0..nv {
        for j in 0..per_vertex {
            let (x, l) = match t.real(true) {
                Some(number) => number,
                None => {
                    let Some((tok, l)) = t.token() else {
                        return Err((t.eof_line(), syntax(ends_inside_vertex(nv, i, j, layout))));
                    };
                    (parse_f64(tok, layout.what(j)).map_err(|k| (l, k))?, l)
                }
            };
            if i == 0 && j == 0 && l == counts_line {
                compact = true;
            }
            if l != on_line.0 {
                if !compact {
                    check_whole_vertices(on_line, layout)?;
                }
                on_line = (l, 0);
            }
            on_line.1 += 1;
            widest = widest.max(on_line.1);
            if j < dim {
                table::try_push(&mut data, x)
                    .map_err(|b| (l, no_room("the vertex coordinates")(b)))?;
            } else {
                table::try_push(&mut extra, x)
                    .map_err(|b| (l, no_room("the vertex normals and colours")(b)))?;
            }
        }
    }
    // The last vertex line must end with its last vertex.
    if nv > 0 && !compact {
        let mut extra = 0;
        while t.token_in_line().is_some() {
            extra += 1;
        }
        if extra > 0 {
            // Even a whole number of extra vertices: they would be read as faces.
            return Err((
                on_line.0,
                syntax(format!(
                    "line holds {} numbers after the last vertex ({} numbers each: {}); \
                     vertex colours need the C header prefix (COFF), normals N, texture \
                     coordinates ST",
                    extra, layout.per_vertex, layout.text
                )),
            ));
        }
        check_whole_vertices(on_line, layout)?;
    }
    Ok((data, extra, widest.max(on_line.1), on_line.0))
}

/// The body of a section of `n` entries that starts on the line after the scanner's (nothing
/// but a comment may follow it there), when it is large enough to split and present.
fn section_body(t: &Scanner<'_>, text: &str, n: u32) -> Option<chunked::Body> {
    if !crate::parallel::splits(n as usize) {
        return None;
    }
    let mut sc = t.clone();
    if sc.token_in_line().is_some() || !sc.next_line() {
        return None;
    }
    chunked::body(text, sc.pos(), sc.line(), n as usize)
}

/// The vertices read on several threads when they are many and one a line (see
/// [`chunked`]); `None` (the scanner unmoved, nothing reserved) for [`vertices`] to read them.
fn vertices_in_parallel(
    t: &mut Scanner<'_>,
    text: &str,
    nv: u32,
    layout: &Layout,
) -> Option<Vec<f64>> {
    // Normals, colours and texture coordinates are kept by the serial reader.
    if layout.per_vertex != layout.dim {
        return None;
    }
    let body = section_body(t, text, nv)?;
    let (dim, per_vertex) = (layout.dim, layout.per_vertex);
    let len = (nv as usize).checked_mul(dim)?;
    // The serial reader's reservation, so that the attempt fails (and the serial reader
    // reports it) exactly where the serial reader would.
    let mut data = try_with_capacity(capped_len(len, t.len()), "the vertex coordinates").ok()?;
    chunked::extend_filled(&mut data, len, 0.0).then_some(())?;
    let read = chunked::fill(text, &body, &mut data, dim, |sc, xs| {
        let mut kept = xs.iter_mut();
        for _ in 0..per_vertex {
            let x = match sc.real(false) {
                Some((x, _)) => x,
                None => parse_f64(sc.token_in_line()?.0, "").ok()?,
            };
            // The first `dim` numbers are the coordinates; the rest are checked and dropped.
            if let Some(slot) = kept.next() {
                *slot = x;
            }
        }
        Some(())
    });
    read.then(|| {
        t.place(body.end.0, body.end.1);
        data
    })
}

/// The faces read into `raw` on several threads when they are many, one a line, and all of
/// the first face's size (see [`chunked`]); false (nothing read, the scanner unmoved) for
/// [`faces`] to read them.
fn faces_in_parallel(t: &mut Scanner<'_>, text: &str, nf: u32, raw: &mut RawInput) -> bool {
    let Some(body) = section_body(t, text, nf) else {
        return false;
    };
    let mut first = Scanner::at_line(text, body.cuts[0], body.first_line);
    let k = match first.digits(false) {
        Some((k @ 1..=3, _)) => k as usize,
        _ => return false,
    };
    let n = nf as usize;
    let room = |len: usize, cap: usize| cap - len >= n;
    if !room(raw.offsets.len(), raw.offsets.capacity())
        || !room(raw.lines.len(), raw.lines.capacity())
        || raw.ids.capacity() - raw.ids.len() < n * k
    {
        return false;
    }
    let base = raw.ids.len();
    chunked::extend_filled(&mut raw.ids, n * k, 0);
    let read = chunked::fill(text, &body, &mut raw.ids[base..], k, |sc, ids| {
        if sc.digits(false)?.0 != k as u64 {
            return None;
        }
        for id in ids.iter_mut() {
            *id = match sc.digits(false) {
                Some((v, _)) => scan::id_value(v, false).ok()?,
                None => scan::id(sc.token_in_line()?.0, false).ok()?,
            };
        }
        // The colour: the rest of the line, 0, 1, 3 or 4 numbers.
        let mut colour = 0;
        while let Some((tok, _)) = sc.token_in_line() {
            parse_f64(tok, "").ok()?;
            colour += 1;
        }
        // A colour is kept by the serial reader.
        (colour == 0).then_some(())
    });
    if !read {
        raw.ids.truncate(base);
        return false;
    }
    t.place(body.end.0, body.end.1);
    let line = body.first_line;
    chunked::extend_with(&mut raw.offsets, n, |i| base + (i + 1) * k)
        && chunked::extend_with(&mut raw.lines, n, |i| line + i as u32)
}

/// An error in the first face when vertex lines held several vertices each: most likely the
/// vertices have more numbers than the header says (colours without `C`), so the faces were
/// read from vertex lines. Says so after the error.
fn first_face_hint(
    line: u32,
    kind: ReadErrorKind,
    widest: usize,
    layout: &Layout,
) -> (u32, ReadErrorKind) {
    let first_face_failed = matches!(&kind, ReadErrorKind::Syntax(_) | ReadErrorKind::Polygon(_));
    if widest <= layout.per_vertex || !first_face_failed {
        return (line, kind);
    }
    (
        line,
        syntax(format!(
            "{kind} (vertex lines hold up to {widest} numbers where a vertex of this header has \
             {} ({}); vertex colours need the C header prefix (COFF), normals N)",
            layout.per_vertex, layout.text
        )),
    )
}

fn ends_inside_vertex(nv: u32, i: u32, j: usize, layout: &Layout) -> String {
    if j == 0 {
        format!("vertex count {nv} declared but file ends after {i} vertices")
    } else if j < layout.dim {
        format!(
            "file ends inside vertex {}: expected {} vertex coordinates, found {j}",
            i + 1,
            layout.dim
        )
    } else {
        format!(
            "file ends inside vertex {}: expected {} numbers ({}), found {j}",
            i + 1,
            layout.per_vertex,
            layout.text
        )
    }
}

/// Refuses a line holding vertex numbers that are not a whole number of vertices.
fn check_whole_vertices((line, n): (u32, usize), layout: &Layout) -> Res<()> {
    if line == 0 || n % layout.per_vertex == 0 {
        return Ok(());
    }
    Err((
        line,
        syntax(format!(
            "line holds {n} vertex numbers, not a whole number of vertices of {} numbers each \
             ({}); vertex colours need the C header prefix (COFF), normals N, texture \
             coordinates ST",
            layout.per_vertex, layout.text
        )),
    ))
}

/// Reads `nf` faces into `raw`, each recorded at the line of its vertex count; `hint` amends an
/// error in the first face. A face starting on `vertex_line` (the line of the last vertex
/// number: a one-line file) has no colour: the rest of that line holds the next faces.
fn faces(
    t: &mut Scanner<'_>,
    nf: u32,
    raw: &mut RawInput,
    vertex_line: u32,
    colours: &mut FaceColours,
    hint: impl Fn((u32, ReadErrorKind)) -> (u32, ReadErrorKind),
) -> Res<()> {
    for f in 0..nf {
        face(t, f, nf, raw, vertex_line, colours).map_err(|e| if f == 0 { hint(e) } else { e })?;
    }
    Ok(())
}

/// Reads face `f` (0-based) of `nf`; its colour unless it starts on `vertex_line`.
#[inline]
fn face(
    t: &mut Scanner<'_>,
    f: u32,
    nf: u32,
    raw: &mut RawInput,
    vertex_line: u32,
    colours: &mut FaceColours,
) -> Res<()> {
    let keep = |e| match e {
        ReadErrorKind::Polygon(k) if raw.polygons.keep => Ok(k),
        e => Err(e),
    };
    let (k, face_line) = match t.digits(true) {
        Some((k, l)) => (
            face_size_of(i128::from(k))
                .or_else(keep)
                .map_err(|e| (l, e))?,
            l,
        ),
        None => {
            let (tok, l) = next_or(t, || {
                format!("face count {nf} declared but file ends after {f} faces")
            })?;
            (face_size(tok).or_else(keep).map_err(|e| (l, e))?, l)
        }
    };
    // A polygon kept for --triangulate grows as its ids are read (its count is not trusted).
    let mut small = [0u32; 3];
    let mut polygon = Vec::new();
    for j in 0..k {
        let id = match t.digits(true) {
            Some((v, l)) => scan::id_value(v, false).map_err(|e| (l, e))?,
            None => {
                let (tok, l) = next_or(t, || {
                    format!(
                        "file ends inside face {}: expected {k} vertex ids, found {j}",
                        f + 1
                    )
                })?;
                scan::id(tok, false).map_err(|e| (l, e))?
            }
        };
        match small.get_mut(j) {
            Some(slot) if k <= 3 => *slot = id,
            _ => table::try_push(&mut polygon, id)
                .map_err(|b| (face_line, no_room("a polygon's ids")(b)))?,
        }
    }
    let line = t.line();
    let n = if face_line != vertex_line {
        face_colour(t, f, k, &mut colours.scratch)?
    } else {
        0
    };
    colours.keep(f, n, line)?;
    if k > 3 {
        return raw
            .try_push_polygon(&polygon, face_line, ReadErrorKind::Polygon(k))
            .map_err(|e| (face_line, e));
    }
    raw.try_push(&small[..k], face_line)
        .map_err(|e| (face_line, e))
}

/// A face's vertex count: 1, 2 or 3.
fn face_size(tok: &str) -> Result<usize, ReadErrorKind> {
    match integer_token(tok, "a", "face vertex count")? {
        Some(k) => face_size_of(k),
        None => Err(syntax(format!(
            "face vertex count {} is out of range",
            echo(tok)
        ))),
    }
}

/// A face's vertex count from its value.
fn face_size_of(k: i128) -> Result<usize, ReadErrorKind> {
    match k {
        ..0 => Err(syntax(format!("face vertex count {k} is negative"))),
        0 => Err(syntax("face with 0 vertices")),
        1..=3 => Ok(k as usize),
        _ => Err(match usize::try_from(k) {
            Ok(k) => ReadErrorKind::Polygon(k),
            Err(_) => syntax(format!("face vertex count {k} is out of range")),
        }),
    }
}

/// Checks the optional colour after face `f`'s `k` ids: the rest of the line, 0, 1, 3 or 4
/// numbers.
fn face_colour(t: &mut Scanner<'_>, f: u32, k: usize, into: &mut [f64; 4]) -> Res<usize> {
    let line = t.line();
    let mut n = 0;
    while let Some((tok, l)) = t.token_in_line() {
        let x = parse_f64(tok, "a face colour component").map_err(|e| (l, e))?;
        if let Some(slot) = into.get_mut(n) {
            *slot = x;
        }
        n += 1;
    }
    if !matches!(n, 0 | 1 | 3 | 4) {
        return Err((
            line,
            syntax(format!(
                "face {} has {n} numbers after its {k} vertex ids; a face colour has 0, 1, 3 \
                 or 4 numbers",
                f + 1
            )),
        ));
    }
    Ok(n)
}

/// The attribute name of OFF colours, on the vertices (`C`) and on the faces.
pub(crate) const COLOR: &str = "off:color";
/// The attribute name of OFF vertex normals (`N`).
pub(crate) const NORMAL: &str = "off:normal";
/// The attribute name of OFF texture coordinates (`ST`).
pub(crate) const TEXTURE: &str = "off:texture";

/// The face colours read so far: every face has one of the same width, or none has.
#[derive(Default)]
struct FaceColours {
    /// The colour width of the first face (0: none).
    width: usize,
    values: Vec<f64>,
    /// The colour of the face being read.
    scratch: [f64; 4],
}

impl FaceColours {
    /// Keeps face `f`'s colour of `n` numbers (in `scratch`), read on `line`.
    fn keep(&mut self, f: u32, n: usize, line: u32) -> Res<()> {
        if f == 0 {
            self.width = n;
        } else if n != self.width {
            return Err((
                line,
                syntax(format!(
                    "face {} has a colour of {n} numbers where face 1 has {}; a colour is kept \
                     for every face or none (an attribute has one width)",
                    f + 1,
                    self.width
                )),
            ));
        }
        table::try_extend(&mut self.values, &self.scratch[..n])
            .map_err(|b| (line, no_room("the face colours")(b)))
    }
}

/// The vertex numbers after the coordinates (`extra`, `per_vertex - dim` a vertex) as the
/// `off:normal`, `off:color` and `off:texture` attributes.
fn vertex_attributes(
    raw: &mut RawInput,
    layout: &Layout,
    extra: Vec<f64>,
) -> Result<(), ReadErrorKind> {
    let width = layout.per_vertex - layout.dim;
    if width == 0 {
        return Ok(());
    }
    let texture = width - layout.normal - layout.colour;
    let mut start = 0;
    for (name, c) in [
        (NORMAL, layout.normal),
        (COLOR, layout.colour),
        (TEXTURE, texture),
    ] {
        if c == 0 {
            continue;
        }
        if c > MAX_COMPONENTS {
            return Err(syntax(format!(
                "vertex normals of {c} numbers: an attribute has at most {MAX_COMPONENTS} \
                 components, so they are refused rather than dropped"
            )));
        }
        let values = extra
            .chunks_exact(width)
            .flat_map(|v| v[start..start + c].iter().copied())
            .collect();
        raw.attributes.insert(Attribute {
            name: name.to_string(),
            location: Location::Vertices,
            components: c,
            values: Values::F64(values),
        });
        start += c;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    reader_test_helpers!();

    const TETRA: &str =
        "OFF\n4 4 6\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 1 2\n3 0 1 3\n3 0 2 3\n3 1 2 3\n";

    #[test]
    fn vertex_normals_colours_texture_and_face_colours_are_attributes() {
        let r = ok(
            "STCNOFF\n3 2\n0 0 0 0 0 1 1 0 0 1 0.5 0.5\n1 0 0 0 0 1 0 1 0 1 1 0\n\
                    0 1 0 0 0 1 0 0 1 0.5 0 1\n3 0 1 2 255 0 0\n2 0 1 0 255 0\n",
        );
        let at = &r.attributes;
        let v = |name, location| at.get(name, location).unwrap();
        assert_eq!(
            v(NORMAL, Location::Vertices).values,
            Values::F64([0., 0., 1.].repeat(3))
        );
        assert_eq!(v(COLOR, Location::Vertices).components, 4);
        assert_eq!(
            v(COLOR, Location::Vertices).values,
            Values::F64(vec![1., 0., 0., 1., 0., 1., 0., 1., 0., 0., 1., 0.5])
        );
        assert_eq!(
            v(TEXTURE, Location::Vertices).values,
            Values::F64(vec![0.5, 0.5, 1., 0., 0., 1.])
        );
        let faces = v(COLOR, Location::Listed);
        assert_eq!(
            (faces.components, faces.element(1)),
            (3, Some(vec![0., 255., 0.]))
        );
        // No face colour: no attribute; a colour on some faces only is refused.
        assert!(ok(TETRA).attributes.is_empty());
        err(
            "OFF\n3 2\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2 1 0 0\n2 0 1\n",
            7,
            "face 2 has a colour of 0 numbers where face 1 has 3",
        );
    }

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
    fn one_line_off_is_read() {
        let r = ok("OFF 3 1 0 0 0 0 1 0 0 0 1 0 3 0 1 2");
        assert_eq!(r.vertex_count, Some(3));
        assert_eq!(r.coords.as_ref().unwrap().data[3..6], [1.0, 0.0, 0.0]);
        assert_eq!(simplices(&r), [[0, 1, 2]]);
        // Several faces on the line, and a final newline.
        let r = ok("OFF 4 2 0 0 0 0 1 0 0 0 1 0 0 0 1 3 0 1 2 3 1 2 3\n");
        assert_eq!(simplices(&r), [[0, 1, 2], [1, 2, 3]]);
        // Faces on lines of their own after one-line vertices keep their colours: every face
        // (the one on the vertex line has none) or none.
        let r = ok("OFF 3 2 0 0 0 0 1 0 0 0 1 0 3 0 1 2\n2 0 1\n");
        assert_eq!(r.ids, [0, 1, 2, 0, 1]);
        err(
            "OFF 3 2 0 0 0 0 1 0 0 0 1 0 3 0 1 2\n2 0 1 0.5 0.5 0.5\n",
            2,
            "face 2 has a colour of 3 numbers where face 1 has 0",
        );
        // A count that disagrees is still refused.
        assert!(parse("OFF 3 1 0 0 0 0 1 0 0 0 1 0 3 0 1 2 7").is_err());
        // Vertices on lines of their own keep the line checks (colours without C).
        let e = parse("OFF\n3 1 0\n0 0 0 1 1 1 1\n1 0 0 1 1 1 1\n0 1 0 1 1 1 1\n3 0 1 2\n")
            .unwrap_err();
        assert_eq!(e.0, 3);
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

    /// The header's prefixes decide how many numbers a vertex line has and which of them are
    /// coordinates: C (colour) and N (normal) columns are skipped, 4 adds one coordinate, n
    /// reads the dimension, 4n adds a homogeneous one; each case's coordinates and faces.
    #[test]
    fn header_prefixes_decide_which_numbers_are_coordinates() {
        // (case, text, coordinates per vertex, coordinates, faces)
        type Case = (
            &'static str,
            &'static str,
            usize,
            &'static [f64],
            &'static [&'static [u32]],
        );
        let cases: [Case; 6] = [
            (
                "COFF",
                "COFF\n3 1 0\n0 0 0 1 0 0 1\n1 0 0 0 1 0 1\n0 1 0 0 0 1 0.5\n3 0 1 2\n",
                3,
                &[0., 0., 0., 1., 0., 0., 0., 1., 0.],
                &[&[0, 1, 2]],
            ),
            (
                "NOFF",
                "NOFF\n3 1 0\n0 0 0 0 0 1\n1 0 0 0 0 1\n0 1 0 0 0 1\n3 0 1 2\n",
                3,
                &[0., 0., 0., 1., 0., 0., 0., 1., 0.],
                &[&[0, 1, 2]],
            ),
            (
                "4OFF",
                "4OFF\n2 1 0\n0 0 0 1\n1 2 3 1\n2 0 1\n",
                4,
                &[0., 0., 0., 1., 1., 2., 3., 1.],
                &[&[0, 1]],
            ),
            (
                "nOFF of dimension 5",
                "nOFF\n5\n2 1 0\n1 2 3 4 5\n6 7 8 9 10\n2 1 0\n",
                5,
                &[1., 2., 3., 4., 5., 6., 7., 8., 9., 10.],
                &[&[1, 0]],
            ),
            (
                "4nOFF: a homogeneous component",
                "4nOFF 2\n1 0 0\n1 2 1\n",
                3,
                &[1., 2., 1.],
                &[],
            ),
            (
                "NnOFF: normals of the vertex dimension (2 coordinates, 2 normal components)",
                "NnOFF 2\n2 1 0\n0 0 0 1\n1 0 0 1\n2 0 1\n",
                2,
                &[0., 0., 1., 0.],
                &[&[0, 1]],
            ),
        ];
        for (case, text, dim, data, faces) in cases {
            let r = parse(text).unwrap_or_else(|e| panic!("{case}: {e:?}"));
            let c = r.coords.as_ref().unwrap();
            assert_eq!((c.dim, &c.data[..]), (dim, data), "{case}");
            assert_eq!(simplices(&r), faces, "{case}");
        }
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
                    3 0 1 2 7 0 0 1\n3 0 1 2 255 0 0 9\n3 0 1 2 1.0 0.5 0.25 1\n3 0 1 2 0 0 0 0\n";
        let r = ok(text);
        assert_eq!(r.simplex_count(), 4);
        assert_eq!(r.lines, [6, 7, 8, 9]);
        let c = r.attributes.get(COLOR, Location::Listed).unwrap();
        assert_eq!(c.element(2), Some(vec![1.0, 0.5, 0.25, 1.0]));
        // Geomview allows faces of different colour widths (0, 1, 3, 4); one attribute cannot
        // hold them, so they are refused rather than padded or dropped.
        err(
            "OFF\n3 2 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2 7\n3 0 1 2 255 0 0\n",
            7,
            "face 2 has a colour of 3 numbers where face 1 has 1",
        );
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
        err("OFF\n3\n", 2, "expected the face count");
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

    #[test]
    fn header_without_edge_count() {
        // Many writers leave NEdges out: the face count ending its line is enough.
        let r = ok("OFF\n3 1\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
        assert_eq!(simplices(&r), [[0, 1, 2]]);
        assert_eq!(r.lines, [6]);
        let r = ok("OFF 3 1\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
        assert_eq!(r.lines, [5]);
    }

    #[test]
    fn vertex_colours_without_the_c_prefix() {
        // Line 3 holds 7 numbers where an OFF vertex has 3: refused there, not lines later.
        err(
            "OFF\n3 1 0\n0 0 0 1 0 0 1\n1 0 0 0 1 0 1\n0 1 0 0 0 1 1\n3 0 1 2\n",
            3,
            "line holds 7 vertex numbers, not a whole number of vertices of 3 numbers each",
        );
        // RGB colours (6 numbers a line) read as two vertices a line: the faces then start on
        // a vertex line, and the message says so.
        err(
            "OFF\n4 1 0\n0 0 0 1 0.5 0\n1 0 0 0 1 0\n0 1 0 0 0 1\n0 0 1 1 1 1\n3 0 1 2\n",
            5,
            "face with 0 vertices (vertex lines hold up to 6 numbers where a vertex of this \
             header has 3 (3 coordinates); vertex colours need the C header prefix (COFF)",
        );
        // Two vertices on one line are fine.
        let r = ok("OFF\n2 1 0\n0 0 0 0.5 0 0\n2 0 1\n");
        assert_eq!(r.coords.unwrap().data, [0., 0., 0., 0.5, 0., 0.]);
        // The last vertex line must end with the last vertex.
        err(
            "OFF\n1 1 0\n0 0 0 9\n1 0\n",
            3,
            "line holds 1 numbers after the last vertex",
        );
        err(
            "OFF\n2 1 0\n0 0 0\n1 0 0 3 0 1\n1 0\n",
            4,
            "line holds 3 numbers after the last vertex",
        );
    }

    #[test]
    fn cr_only_line_ends() {
        let r = ok("OFF\r3 1 0\r0 0 0\r1 0 0\r0 1 0\r3 0 1 2\r");
        assert_eq!(r.lines, [6]);
        err("OFF\r1 1 0\r0 0 0\r\r1 x\r", 5, "non-numeric token 'x'");
    }

    #[test]
    fn coordinates_that_do_not_fit_a_double() {
        err(
            "OFF\n1 0 0\n0 1e309 0\n",
            3,
            "number '1e309' is too large for a 64-bit float (a vertex coordinate; it would \
             become infinite)",
        );
        err(
            "OFF\n1 0 0\n\n0 0 -1e-400\n",
            4,
            "number '-1e-400' is too small for a 64-bit float (a vertex coordinate; it would \
             become 0)",
        );
    }

    #[test]
    fn echoed_tokens_are_escaped_and_capped() {
        err(
            "OFF\n1 1 0\n0 0\u{b}1 0\n1 0\n",
            3,
            "non-numeric token '0\\x0b1'",
        );
        err("\u{a0}OFF\n", 1, "found '\\u{a0}OFF'");
        err("OFF\n1 1 0\n0 0 0\n1 0\0\n", 4, "non-numeric token '0\\0'");
        let long = format!("OFF\n1 1 0\n0 {} 0\n1 0\n", "x".repeat(1_000_000));
        let Err((3, k)) = parse(&long) else {
            panic!("expected an error on line 3")
        };
        let msg = k.to_string();
        assert!(msg.len() < 400, "{} bytes", msg.len());
        assert!(msg.contains("… (999800 more bytes)"), "{msg}");
    }
}
