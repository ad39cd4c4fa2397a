//! Reader for Wavefront OBJ files (`.obj`), geometry statements only.
//!
//! * `v x y z` declares a vertex; a homogeneous `w` (4 numbers) may follow and is ignored (a
//!   weight only free-form geometry uses, which is refused), or a vertex colour `r g b` (6
//!   numbers) or `r g b a` (7), kept as the `obj:color` vertex field (module `data`). Fewer than 3
//!   numbers, or 5, or more than 7, are errors. Coordinates have dimension 3. Numbers are parsed as `f64`; `nan`, `inf` and
//!   `infinity` are accepted, since topology does not use coordinates, but a finite number that
//!   would become infinite or 0 (`1e309`, `1e-400`) is an error.
//! * `f` with vertices written `i`, `i/t`, `i//n` or `i/t/n` is a triangle; more than 3
//!   vertices is [`ReadErrorKind::Polygon`], fewer is an error (use `l` or `p`).
//! * `l i j k ...` (also `i/t`) gives one edge per consecutive pair; it needs at least 2 vertices.
//! * `p i j ...` gives one 0-simplex per index; it needs at least 1.
//! * Indices are 1-based; 0 is an error. Positive indices may refer to vertices defined later in
//!   the file, so they are recorded (0-based) without a range check, which the complex model does.
//!   Negative indices are relative to the vertices read so far (-1 is the last one); reaching
//!   before the first vertex is an error. Texture and normal indices (`i/t/n`) tie the `vt` and
//!   `vn` statements to the vertices: the `obj:vt` and `obj:vn` fields, on the vertices when
//!   each vertex is given one value and per corner on the listed simplices otherwise
//!   (module `data`: nothing of them is dropped).
//! * Free-form elements `curv curv2 surf` are refused (an error naming the statement): they are
//!   geometry a simplicial complex cannot hold, and dropping them would read the file as less
//!   than it is.
//! * Grouping statements are labels on the listed simplices (`i32`, one per simplex, for the
//!   simplices after the statement): `o NAME` → `obj:object`, `g NAME...` → `obj:group`,
//!   `usemtl NAME` → `obj:material`, each label the index of the name in order of first
//!   appearance (a [`LabelName`] names it; the names of a `g` line joined by one space are one
//!   name — a simplex in several groups has that combined group —, `g` alone is `default`),
//!   -1 before the kind's first statement; `s N` / `s off` → `obj:smoothing`, the number (`off`
//!   0, which is also the value before any `s`). An attribute exists only when its statement
//!   occurs. A nameless `o` or `usemtl`, or an `s` that is not `off` or a number, is an error.
//! * Ignored statements: `vp mtllib cstype deg bmat step parm trim hole scrv
//!   sp end con mg bevel c_interp d_interp lod maplib usemap shadow_obj trace_obj ctech stech`
//!   (their arguments are not checked). Any other keyword is an error.
//! * `#` starts a comment; a line ending in `\` (blanks and a comment may follow it) continues
//!   on the next line, in time linear in the statement's length (the statement is reported at
//!   its first line). Lines end in LF, CRLF or a lone CR; tabs and a missing final newline are
//!   fine.
//! * A file with no statements at all is an error.
//!
//! `vertex_count` is the number of `v` statements.

use super::scan::{self, Scanner};
use super::{
    Coords, RawInput, ReadErrorKind, echo, integer_token, no_room, parse_f64, parse_integer, syntax,
};
use crate::complex::{Attribute, LabelName, Location, table};

pub(crate) mod data;

/// Statements that carry nothing a simplicial complex keeps (parameter-space vertices of
/// free-form geometry, material libraries, display attributes, and the free-form attribute and body statements,
/// which mean nothing without a `curv`, `curv2` or `surf` element). Their arguments are not
/// checked.
const IGNORED: &[&str] = &[
    "vp",
    "mtllib",
    "cstype",
    "deg",
    "bmat",
    "step",
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

/// Free-form elements: geometry that is not simplices. Refused rather than dropped, so that a
/// file is never read as less than it holds.
const FREE_FORM: &[&str] = &["curv", "curv2", "surf"];

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
#[inline]
fn vertex_index(tok: &str, form: Form, seen: u32) -> Result<u32, ReadErrorKind> {
    // The common case: a plain positive index.
    let b = tok.as_bytes();
    if !b.is_empty()
        && b.len() <= 9
        && b.iter().all(u8::is_ascii_digit)
        && let Ok(i) = scan::id(tok, true)
    {
        return Ok(i);
    }
    vertex_index_slow(tok, form, seen)
}

fn vertex_index_slow(tok: &str, form: Form, seen: u32) -> Result<u32, ReadErrorKind> {
    let mut parts = tok.split('/');
    let i = parts.next().unwrap_or_default();
    let (t, n, extra) = (parts.next(), parts.next(), parts.next().is_some());
    let nonzero_int = |s: &str| parse_integer(s).is_ok_and(|v| v != 0);
    let well_formed = !extra
        && match (form, t, n) {
            (_, None, _) => true,
            (Form::Face | Form::Line, Some(t), None) => nonzero_int(t),
            (Form::Face, Some(t), Some(n)) => (t.is_empty() || nonzero_int(t)) && nonzero_int(n),
            _ => false,
        };
    if !well_formed || i.is_empty() {
        let forms = match form {
            Form::Face => "i, i/t, i//n or i/t/n",
            Form::Line => "i or i/t",
            Form::Point => "i",
        };
        return Err(syntax(format!(
            "malformed vertex reference '{}' (expected {forms} with non-zero integer indices)",
            echo(tok)
        )));
    }
    let before_first = || {
        syntax(format!(
            "relative vertex index {} reaches before the first vertex ({seen} vertices read so \
             far)",
            echo(i)
        ))
    };
    let v = match integer_token(i, "a", "vertex index")? {
        Some(v) => v,
        None if i.starts_with('-') => return Err(before_first()),
        None => {
            return Err(syntax(format!(
                "vertex index {} does not fit in 32 bits",
                echo(i)
            )));
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
            .map_err(|_| syntax(format!("vertex index {} does not fit in 32 bits", echo(i))))
    } else {
        u32::try_from(i128::from(seen) + v).map_err(|_| before_first())
    }
}

/// What the statements read so far built.
struct State {
    raw: RawInput,
    /// x y z of each `v` statement.
    data: Vec<f64>,
    /// `v` statements so far.
    seen: u32,
    /// Scratch for the ids of one `l` statement.
    ids: Vec<u32>,
    /// Each `o`, `g`, `usemtl` and `s` statement: (listed simplices before it, which of
    /// [`LABELS`], label).
    changes: Vec<(usize, usize, i32)>,
    /// The names of each of the first three of [`LABELS`], in order of first appearance.
    names: [Vec<String>; 3],
    /// `vt` statements and the references to them.
    texture: data::Side,
    /// `vn` statements and the references to them.
    normal: data::Side,
    /// Vertex colours.
    colors: data::Colors,
    /// Scratch for the texture and normal indices of one element's vertices.
    refs: Vec<(Option<i64>, Option<i64>)>,
}

/// The label attributes of OBJ's grouping statements, in the order the writer writes them:
/// `o` objects, `g` groups, `usemtl` materials (each label the index of the name in order of
/// first appearance, named by a [`LabelName`]), `s` smoothing groups (the group number, `off`
/// 0).
pub(crate) const LABELS: [(&str, &str); 4] = [
    ("o", "obj:object"),
    ("g", "obj:group"),
    ("usemtl", "obj:material"),
    ("s", "obj:smoothing"),
];

/// A grouping statement's label: its names joined by a space (`g` alone: `default`), as the
/// index of that name, or the smoothing group's number (`off`: 0).
fn grouping(s: &mut Scanner<'_>, k: usize, st: &mut State) -> Result<(), ReadErrorKind> {
    let mut words: Vec<&str> = Vec::new();
    while let Some((tok, _)) = s.token_in_line() {
        words.push(tok);
    }
    let label = if k == 3 {
        match words.as_slice() {
            ["off"] => 0,
            [n] => match parse_integer(n) {
                Ok(v) if (0..=i128::from(i32::MAX)).contains(&v) => v as i32,
                _ => {
                    return Err(syntax(format!(
                        "smoothing group '{}' is not 'off' or a number 0 to {}",
                        echo(n),
                        i32::MAX
                    )));
                }
            },
            _ => {
                return Err(syntax(format!(
                    "an `s` statement takes one smoothing group ('off' or a number), not {}",
                    words.len()
                )));
            }
        }
    } else {
        let name = if words.is_empty() {
            if k == 1 {
                "default".to_string()
            } else {
                return Err(syntax(format!("`{}` statement with no name", LABELS[k].0)));
            }
        } else {
            words.join(" ")
        };
        let names = &mut st.names[k];
        match names.iter().position(|n| *n == name) {
            Some(i) => i as i32,
            None => {
                names.push(name);
                i32::try_from(names.len() - 1).map_err(|_| syntax("too many names"))?
            }
        }
    };
    st.changes.push((st.raw.simplex_count(), k, label));
    Ok(())
}

/// The labels the grouping statements give the listed simplices: one attribute per statement
/// kind that occurs, -1 before a kind's first statement (0 for `s`), with the names.
fn grouping_attributes(st: &mut State) {
    let m = st.raw.simplex_count();
    for (k, (_, attr)) in LABELS.iter().enumerate() {
        if !st.changes.iter().any(|c| c.1 == k) {
            continue;
        }
        let mut values = Vec::with_capacity(m);
        let mut current = if k == 3 { 0 } else { -1 };
        let mut changes = st.changes.iter().filter(|c| c.1 == k).peekable();
        for i in 0..m {
            while let Some(&&(at, _, label)) = changes.peek() {
                if at > i {
                    break;
                }
                current = label;
                changes.next();
            }
            values.push(current);
        }
        st.raw
            .attributes
            .insert(Attribute::labels(attr, Location::Listed, values));
        if k < 3 {
            for (label, name) in std::mem::take(&mut st.names[k]).into_iter().enumerate() {
                st.raw.attributes.add_label_name(LabelName {
                    attribute: (*attr).to_string(),
                    dimension: None,
                    label: label as i64,
                    name,
                });
            }
        }
    }
}

/// Reads an OBJ file's text.
pub fn parse(text: &str) -> Result<RawInput, (u32, ReadErrorKind)> {
    parse_keeping(text, false)
}

/// [`parse`], keeping faces of more than 3 vertices as polygons when `polygons` (for
/// [`super::ReadOptions::triangulate`]).
pub(crate) fn parse_keeping(text: &str, polygons: bool) -> Result<RawInput, (u32, ReadErrorKind)> {
    let mut s = Scanner::with_continuation(text);
    let mut raw = RawInput::new();
    raw.polygons.keep = polygons;
    let mut st = State {
        raw,
        data: Vec::new(),
        seen: 0,
        ids: Vec::new(),
        changes: Vec::new(),
        names: Default::default(),
        texture: data::Side::default(),
        normal: data::Side::default(),
        colors: data::Colors::default(),
        refs: Vec::new(),
    };
    let mut statements = 0usize;
    loop {
        // A statement is reported at its first line, continuations included.
        let line = s.line();
        let mut result = Ok(());
        if let Some((keyword, _)) = s.token_in_line() {
            statements += 1;
            result = statement(&mut s, keyword, &mut st);
            if result.is_err() {
                // A dangling continuation is the first thing wrong with the statement.
                s.skip_rest_of_line();
            }
        }
        if s.dangling_continuation() {
            return Err((
                line,
                syntax("line continuation '\\' at the end of the file"),
            ));
        }
        result.map_err(|k| (line, k))?;
        if !s.next_line() {
            break;
        }
    }
    if statements == 0 {
        return Err((s.eof_line(), syntax("file is empty (no OBJ statements)")));
    }
    grouping_attributes(&mut st);
    let mut raw = st.raw;
    let n = st.seen as usize;
    st.colors.finish(&mut raw);
    st.texture.finish(data::TEXTURE, "vt", &mut raw, n)?;
    st.normal.finish(data::NORMAL, "vn", &mut raw, n)?;
    raw.vertex_count = Some(st.seen);
    raw.coords = Some(Coords {
        dim: 3,
        data: st.data,
    });
    Ok(raw)
}

/// Reads the rest of one statement (after its keyword, which was on `line`).
fn statement(s: &mut Scanner<'_>, keyword: &str, st: &mut State) -> Result<(), ReadErrorKind> {
    let line = s.line();
    match keyword {
        "v" => vertex(s, st),
        "f" => face(s, st, line),
        "l" => line_element(s, st, line),
        "p" => points(s, st, line),
        "vt" => st.texture.statement(s, false, line),
        "vn" => st.normal.statement(s, true, line),
        k if let Some(g) = LABELS.iter().position(|l| l.0 == k) => grouping(s, g, st),
        k if FREE_FORM.contains(&k) => Err(syntax(format!(
            "free-form element '{k}' (a curve or surface) is not supported: only v, f, l and p \
             statements make simplices"
        ))),
        k if IGNORED.contains(&k) => {
            s.skip_rest_of_line();
            Ok(())
        }
        k => Err(syntax(format!("unknown OBJ statement '{}'", echo(k)))),
    }
}

/// An `f` statement after its keyword: a triangle (its `vt`/`vn` references recorded), or a
/// polygon kept for --triangulate (else refused).
fn face(s: &mut Scanner<'_>, st: &mut State, line: u32) -> Result<(), ReadErrorKind> {
    if let Some(ids) = plain_triangle(s) {
        return st.raw.try_push(&ids, line);
    }
    let mut refs = [""; 3];
    let mut k = 0;
    // A polygon kept for --triangulate: every id, as read.
    let keep = st.raw.polygons.keep;
    st.ids.clear();
    st.refs.clear();
    while let Some((tok, _)) = s.token_in_line() {
        if let Some(slot) = refs.get_mut(k) {
            *slot = tok;
        }
        if keep {
            let id = vertex_index(tok, Form::Face, st.seen)?;
            table::try_push(&mut st.ids, id).map_err(no_room("a polygon's ids"))?;
            table::try_push(&mut st.refs, corner_refs(tok)).map_err(no_room("a polygon's ids"))?;
        }
        k += 1;
    }
    match k {
        0 => return Err(syntax("face with no vertices")),
        1 => return Err(syntax("face with 1 vertex; use a `p` line for a point")),
        2 => return Err(syntax("face with 2 vertices; use an `l` line for an edge")),
        3 => {}
        k => {
            let listed = st.raw.simplex_count();
            st.raw
                .try_push_polygon(&st.ids, line, ReadErrorKind::Polygon(k))?;
            let refs = std::mem::take(&mut st.refs);
            let ids = std::mem::take(&mut st.ids);
            let done = record_refs(st, listed, &ids, &refs);
            (st.refs, st.ids) = (refs, ids);
            return done;
        }
    }
    let mut ids = [0u32; 3];
    for (id, tok) in ids.iter_mut().zip(refs) {
        *id = vertex_index(tok, Form::Face, st.seen)?;
    }
    let listed = st.raw.simplex_count();
    st.raw.try_push(&ids, line)?;
    if refs.iter().any(|t| t.contains('/')) {
        record_refs(st, listed, &ids, &refs.map(corner_refs))?;
    }
    Ok(())
}

/// An `l` statement after its keyword: each consecutive pair of its vertices an edge.
fn line_element(s: &mut Scanner<'_>, st: &mut State, line: u32) -> Result<(), ReadErrorKind> {
    st.ids.clear();
    st.refs.clear();
    while let Some((tok, _)) = s.token_in_line() {
        let id = vertex_index(tok, Form::Line, st.seen)?;
        table::try_push(&mut st.ids, id).map_err(no_room("a line element's ids"))?;
        table::try_push(&mut st.refs, corner_refs(tok)).map_err(no_room("a line element's ids"))?;
    }
    if st.ids.len() < 2 {
        return Err(syntax(format!(
            "line element with {} vertices; an `l` line needs at least 2",
            st.ids.len()
        )));
    }
    let (ids, refs) = (std::mem::take(&mut st.ids), std::mem::take(&mut st.refs));
    let mut done = Ok(());
    for (pair, r) in ids.windows(2).zip(refs.windows(2)) {
        let listed = st.raw.simplex_count();
        done = st.raw.try_push(pair, line);
        if done.is_ok() && r.iter().any(|r| r.0.is_some()) {
            done = record_refs(st, listed, pair, r);
        }
        if done.is_err() {
            break;
        }
    }
    (st.ids, st.refs) = (ids, refs);
    done
}

/// A `p` statement after its keyword: each vertex a point.
fn points(s: &mut Scanner<'_>, st: &mut State, line: u32) -> Result<(), ReadErrorKind> {
    let before = st.raw.simplex_count();
    while let Some((tok, _)) = s.token_in_line() {
        let id = vertex_index(tok, Form::Point, st.seen)?;
        st.raw.try_push(&[id], line)?;
    }
    if st.raw.simplex_count() == before {
        return Err(syntax("point element with no vertices"));
    }
    Ok(())
}

/// The texture and normal indices of an element vertex `i`, `i/t`, `i//n` or `i/t/n` that
/// [`vertex_index`] accepted.
fn corner_refs(tok: &str) -> (Option<i64>, Option<i64>) {
    let mut parts = tok.split('/').skip(1);
    let index = |p: Option<&str>| {
        p.filter(|p| !p.is_empty())
            .and_then(|p| parse_integer(p).ok())
            // Beyond 64 bits: out of range, which `data::Side` reports.
            .map(|v| i64::try_from(v).unwrap_or(if v > 0 { i64::MAX } else { i64::MIN }))
    };
    let t = index(parts.next());
    (t, index(parts.next()))
}

/// Records the texture and normal references of the corners of listed simplex `listed`.
fn record_refs(
    st: &mut State,
    listed: usize,
    ids: &[u32],
    refs: &[(Option<i64>, Option<i64>)],
) -> Result<(), ReadErrorKind> {
    for (corner, (&v, &(t, n))) in ids.iter().zip(refs).enumerate() {
        if let Some(t) = t {
            st.texture.refer(listed, corner, v, t, "vt")?;
        }
        if let Some(n) = n {
            st.normal.refer(listed, corner, v, n, "vn")?;
        }
    }
    Ok(())
}

/// Fast path: `f i j k` with three plain positive indices and nothing else, read as scanned.
/// `None` (the scanner unmoved) for anything else, which the general path reads.
#[inline]
fn plain_triangle(s: &mut Scanner<'_>) -> Option<[u32; 3]> {
    let saved = s.clone();
    let mut ids = [0u32; 3];
    let mut plain = true;
    for id in &mut ids {
        match s.digits(false) {
            Some((v @ 1.., _)) if v <= 1 << 32 => *id = (v - 1) as u32,
            _ => {
                plain = false;
                break;
            }
        }
    }
    if plain && s.token_in_line().is_none() {
        return Some(ids);
    }
    *s = saved;
    None
}

/// `v x y z [w | r g b [a]]`: keeps x y z and the colour.
fn vertex(s: &mut Scanner<'_>, st: &mut State) -> Result<(), ReadErrorKind> {
    let line = s.line();
    let mut xyz = [0.0; 3];
    let mut tail = [0.0; 4];
    let mut n = 0;
    loop {
        let x = match s.real(false) {
            Some((x, _)) => x,
            None => match s.token_in_line() {
                Some((tok, _)) => parse_f64(tok, "a vertex coordinate")?,
                None => break,
            },
        };
        if let Some(slot) = xyz.get_mut(n) {
            *slot = x;
        } else if let Some(slot) = tail.get_mut(n - 3) {
            *slot = x;
        }
        n += 1;
    }
    match n {
        0..=2 => {
            return Err(syntax(format!("expected 3 vertex coordinates, found {n}")));
        }
        3 | 4 | 6 | 7 => {
            st.colors.push(n, &tail, line)?;
            table::try_extend(&mut st.data, &xyz).map_err(no_room("the vertex coordinates"))?
        }
        _ => {
            return Err(syntax(format!(
                "v statement with {n} numbers; expected x y z, optionally followed by w (4 \
                 numbers) or by a colour (6 or 7 numbers)"
            )));
        }
    }
    st.seen = st
        .seen
        .checked_add(1)
        .ok_or_else(|| syntax("more than 4294967295 vertices"))?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    reader_test_helpers!();

    #[test]
    fn triangles_in_all_forms() {
        let text = "# cube corner\nmtllib a.mtl\no thing\nv 0 0 0\nv 1 0 0\nv 0 1 0 1.0\n\
                    v 0 0 1\nvt 0 0\nvn 0 0 1\ng group\ns off\nusemtl red\n\
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
    fn grouping_statements_are_labels_with_names() {
        let r = ok(
            "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\no thing\ng a  b\nusemtl red\ns 4\n\
                    l 1 2 3\ng\nf 1 2 3\ng a b\ns off\nusemtl blue\np 1\n",
        );
        let at = &r.attributes;
        let labels = |n| match &at.get(n, Location::Listed).unwrap().values {
            crate::complex::Values::I32(v) => v.clone(),
            v => panic!("{v:?}"),
        };
        assert_eq!(labels("obj:object"), [-1, 0, 0, 0, 0]);
        assert_eq!(labels("obj:group"), [-1, 0, 0, 1, 0]);
        assert_eq!(labels("obj:material"), [-1, 0, 0, 0, 1]);
        assert_eq!(labels("obj:smoothing"), [0, 4, 4, 4, 0]);
        assert_eq!(at.label_name("obj:group", 2, 0), Some("a b"));
        assert_eq!(at.label_name("obj:group", 2, 1), Some("default"));
        assert_eq!(at.label_name("obj:material", 1, 1), Some("blue"));
        assert_eq!(at.label_name("obj:object", 1, 0), Some("thing"));
        // No grouping statement: no attribute.
        assert!(ok("v 0 0 0\np 1\n").attributes.is_empty());
        err(
            "v 0 0 0\ns x\n",
            2,
            "smoothing group 'x' is not 'off' or a number 0 to 2147483647",
        );
        err("v 0 0 0\nusemtl\n", 2, "`usemtl` statement with no name");
    }

    fn field(r: &RawInput, name: &str, location: Location) -> (usize, Vec<u64>) {
        let a = r
            .attributes
            .get(name, location)
            .unwrap_or_else(|| panic!("no {name}"));
        match &a.values {
            crate::complex::Values::F64(v) => {
                (a.components, v.iter().map(|x| x.to_bits()).collect())
            }
            v => panic!("{v:?}"),
        }
    }

    fn bits(xs: &[f64]) -> Vec<u64> {
        xs.iter().map(|x| x.to_bits()).collect()
    }

    #[test]
    fn vertex_colours_are_a_vertex_field_on_every_v_line_or_none() {
        let r = ok("v 0 0 0 1 0 0\nv 1 0 0 0 1 0\nv 0 1 0 0 0 0.5\nf 1 2 3\n");
        assert_eq!(
            field(&r, data::COLOR, Location::Vertices),
            (3, bits(&[1., 0., 0., 0., 1., 0., 0., 0., 0.5]))
        );
        let r = ok("v 0 0 0 1 0 0 1\nv 1 0 0 0 1 0 0.5\n");
        assert_eq!(field(&r, data::COLOR, Location::Vertices).0, 4);
        // A homogeneous weight is no colour.
        assert!(ok("v 0 0 0 1\nv 1 0 0\n").attributes.is_empty());
        err(
            "v 0 0 0 1 0 0\nv 1 0 0\n",
            2,
            "`v` statement with no colour, where the first (line 1) has a colour of 3 numbers",
        );
        err(
            "v 0 0 0\n\nv 1 0 0 1 1 1 1\n",
            3,
            "`v` statement with a colour of 4 numbers, where the first (line 1) has no colour",
        );
    }

    #[test]
    fn texture_and_normal_references_one_per_vertex_make_vertex_fields() {
        // vt statements in another order than the vertices, one vertex (4) in no element.
        let r = ok(
            "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 5 5 5\nvt 0.5 0.25\nvt 1 0\nvt 0 1\n\
                    vn 0 0 1\nf 1/2/1 2/1/1 3/3/1\nl 2/1 1/-2\n",
        );
        let nan = f64::NAN;
        assert_eq!(
            field(&r, data::TEXTURE, Location::Vertices),
            (2, bits(&[1., 0., 0.5, 0.25, 0., 1., nan, nan]))
        );
        assert_eq!(
            field(&r, data::NORMAL, Location::Vertices),
            (
                3,
                bits(&[0., 0., 1., 0., 0., 1., 0., 0., 1., nan, nan, nan])
            )
        );
        // A `vt` of 3 numbers widens the field; the others' `w` is 0.
        let r = ok("v 0 0 0\nv 1 0 0\nvt 1\nvt 2 3 4\nl 1/1 2/2\n");
        assert_eq!(
            field(&r, data::TEXTURE, Location::Vertices),
            (3, bits(&[1., 0., 0., 2., 3., 4.]))
        );
    }

    #[test]
    fn values_that_differ_at_one_vertex_are_kept_per_corner() {
        // Flat shading: vertex 1 gets two normals.
        let r = ok("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nvn 0 0 -1\nvn 1 1 1\n\
                    f 1//1 3//1 2//1\nf 1//2 2//2 4//2\nl 1 2\np 3\n");
        let nan = [f64::NAN; 3];
        let (a, b) = ([0., 0., -1.], [1., 1., 1.]);
        let want: Vec<f64> = [a, a, a, b, b, b, nan, nan, nan, nan, nan, nan].concat();
        assert_eq!(field(&r, data::NORMAL, Location::Listed), (9, bits(&want)));
        assert!(r.attributes.get(data::NORMAL, Location::Vertices).is_none());
    }

    #[test]
    fn unreferenced_or_missing_texture_and_normal_statements_are_errors_or_one_per_vertex() {
        // As many as the vertices, no reference: one per vertex (meshio's reading).
        let r = ok("v 0 0 0\nv 1 0 0\nvn 0 0 1\nvn 0 1 0\nl 1 2\n");
        assert_eq!(field(&r, data::NORMAL, Location::Vertices).0, 3);
        err(
            "v 0 0 0\nv 1 0 0\n\nvt 0 0\nl 1 2\n",
            4,
            "1 `vt` statements that no element refers to (`i/t/n`) and that are not one per \
             vertex (2 `v`)",
        );
        err(
            "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1 2/1 3/1\nf 1/1 2/2 3/1\n",
            6,
            "vt index 2 refers to no `vt` statement (1 in the file)",
        );
        err(
            "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//-2 2//1 3//1\n",
            5,
            "relative vn index -2 reaches before the first `vn` (1 read so far)",
        );
        err(
            "v 0 0 0\nvn 0 0\n",
            2,
            "2 numbers where `vn i j k` has them",
        );
        err(
            "v 0 0 0\nvt 0 0 0 0\n",
            2,
            "4 numbers where `vt u [v [w]]` has them",
        );
        err(
            "v 0 0 0\nv 1 0 0\nvt 0\nl 1/1 2/99999999999999999999999\n",
            4,
            "vt index 4294967296 refers to no `vt` statement (1 in the file)",
        );
        err(
            "v 0 0 0\nvt x\n",
            2,
            "non-numeric token 'x' where a texture coordinate",
        );
    }

    #[test]
    fn per_corner_values_on_a_polygon_to_fan_are_refused() {
        let text = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvn 0 0 1\nvn 0 0 -1\n\
                    f 1//1 2//1 3//1 4//1\nf 1//2 4//2 3//2\n";
        match parse_keeping(text, true) {
            Err((7, k)) => assert!(k.to_string().contains("not carried through --triangulate")),
            other => panic!("{other:?}"),
        }
        // One normal per vertex: fanned polygons keep it as a vertex field.
        let r = parse_keeping(
            "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvn 0 0 1\n\
                              f 1//1 2//1 3//1 4//1\n",
            true,
        )
        .unwrap();
        assert_eq!(field(&r, data::NORMAL, Location::Vertices).0, 3);
    }

    #[test]
    fn negative_indices_are_relative() {
        let r = ok(
            "vt 0 0\nvn 0 0 1\nvn 0 1 0\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf -3 -2 -1\nv 0 0 1\n\
                    f -1/-1 -2//-2 1\n",
        );
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
        let r = ok("v 0 0 0\nv 1 0 0\nv 0 1 0\nl 1 2 3 1\nl 1/1 -1/2\np 1 2\np -1\nvt 0\nvt 1\n");
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
        let r = ok("v nan inf 0\nvp whatever\ncstype bspline\nend\n");
        assert!(r.coords.clone().unwrap().data[0].is_nan());
    }

    #[test]
    fn vertices_only() {
        let r = ok("v 0 0 0\n");
        assert_eq!(r.vertex_count, Some(1));
        assert_eq!(r.simplex_count(), 0);
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

    #[test]
    fn free_form_elements_are_refused() {
        for kw in ["curv", "curv2", "surf"] {
            err(
                &format!("v 0 0 0\ncstype bspline\n{kw} 0 1 1 2\nend\n"),
                3,
                &format!("free-form element '{kw}' (a curve or surface) is not supported"),
            );
        }
    }

    #[test]
    fn continuation_over_a_million_lines() {
        // Was quadratic (each continuation copied the statement so far).
        let text = format!(
            "v 0 0 0\nv 1 0 0\nl 1{}\nl 2 1\n",
            " 2 1 \\\n".repeat(1_000_000)
        );
        let r = ok(&text);
        assert_eq!(r.simplex_count(), 2_000_001);
        assert_eq!(r.lines[0], 3);
        assert_eq!(r.lines[2_000_000], 1_000_004);
    }

    #[test]
    fn continuation_with_comment_and_cr_only_lines() {
        let r = ok("v 0 0 0\rv 1 0 0\rv 0 1 0\rf 1 2 \\ # more\r3\r\rf 1 \\\r\n2 3");
        assert_eq!(r.lines, [4, 7]);
        err(
            "v 0 0 0\rv 0 0\r",
            2,
            "expected 3 vertex coordinates, found 2",
        );
    }

    #[test]
    fn coordinates_that_do_not_fit_a_double() {
        err("v 0 0 0\nv 1e309 0 0\n", 2, "'1e309' is too large");
        err("v 0 0 0\nv 0 1e-400 0\n", 2, "'1e-400' is too small");
        // Ignored colour numbers are checked too: no number changes silently.
        err("v 0 0 0 1 1 1E999\n", 1, "'1E999' is too large");
    }

    #[test]
    fn echoed_tokens_are_escaped() {
        err(
            "v 0 0 0\n\u{feff}f 1 1 1\n",
            2,
            "unknown OBJ statement '\\u{feff}f'",
        );
        err("v 0 0 0\nf 1 1 \u{b}1\n", 2, "non-numeric token '\\x0b1'");
        err("v 0 0 0\nf 1 1 1\u{b}\n", 2, "'1\\x0b'");
    }
}
