//! PLY (`.ply`, ASCII and binary, either byte order). The `ply-rs-bw` crate reads the header
//! and writes; bodies are read by our own streaming reader (the crate's map per element costs
//! 55× an ASCII file of short lines, 34× a binary one; ours keeps only coordinates and
//! simplices, under 5×). This module maps elements to simplices.
//!
//! Reading:
//! * `vertex` elements give the vertices; their `x`, `y` and optional `z` properties (any
//!   numeric type) the coordinates (dimension 3, or 2 without `z`).
//! * `face` elements with a `vertex_indices` (or `vertex_index`) list of 1, 2 or 3 ids are a
//!   vertex, an edge, a triangle; more is [`ReadErrorKind::Polygon`], none an error. Ids are
//!   0-based; a negative id is [`ReadErrorKind::NegativeId`].
//! * `tetra` elements with a `vertex_indices` list of exactly 4 ids are tetrahedra.
//! * `tristrips` elements are read as their triangles: the `vertex_indices` list holds strips
//!   separated by -1, every 3 consecutive ids of a strip make a triangle, a triangle that
//!   repeats an id (a degenerate join between strips) is skipped, a strip of fewer than 3 ids
//!   is refused.
//! * `edge` elements with `vertex1` and `vertex2` are edges.
//! * Other elements are ignored, unless they have a vertex-id property (`vertex_indices`,
//!   `vertex_index`, `vertex1`, `vertex2`): those are refused rather than dropped. Faces,
//!   tetras and strips come before edges in the listing.
//! * Every other scalar property of `vertex`, `face`, `tetra`, `tristrips` and `edge` elements
//!   (normals, colours, `quality`, user properties) is an attribute
//!   ([`crate::complex::attributes`]) of one component named as the property: on the vertices
//!   for `vertex`, else on the listed simplices (the triangles of a strip share the strip's
//!   values). Types are kept exactly: `char`, `uchar`, `short`, `ushort`, `int` as `i32`,
//!   `uint` as `i64`, `float` as `f32`, `double` as `f64`. A listed property must be on every
//!   element that lists simplices (one value per listed simplex, never padded) with one type;
//!   a list property other than the vertex ids is refused naming it, never dropped.
//! * Every value is checked against its declared type: a line with more values than the
//!   element's properties is refused, as is a `float` (`double`) that the type could hold only
//!   as infinity or 0 (`1e39`, `1e-50` for `float`; the check shared by all readers,
//!   `io::parse_real`); `nan` and `inf` are read.
//! * Errors carry the line where the parser knows it (ASCII); otherwise the message names the
//!   element and its index. Declared counts allocate at most what the parser caps them to.
//!
//! Writing: `vertex` with `double x y z` (fewer coordinates padded with zeros, zeros without
//! coordinates), `face` with `list uchar int vertex_indices` for the triangles, `edge` with `int
//! vertex1 vertex2` for the edges, each in listing order. Holds vertices, edges and triangles,
//! and at most 3 coordinates; listed 0-simplices are left to the vertex count. ASCII PLY
//! refuses non-finite coordinates (PLY readers do not parse `inf` or `nan`); binary keeps them.
//! Attributes of one component become properties after those (`holds`, which [`super::write::Format::holds`] asks): vertex ones on
//! `vertex`, listed ones on both `face` and `edge`, each value beside its simplex (so the
//! triangles-then-edges order read back carries the data with it); `i32` as `int`, `i64` as
//! `uint` (held only when every value fits), `f32` as `float`, `f64` as `double`. Refused:
//! listed data beside listed 0-simplices (not written), and non-finite reals in ASCII.

use ply_rs_bw::parser::Parser;
use ply_rs_bw::ply::{
    Addable, DefaultElement, ElementDef, Encoding, Ply, Property, PropertyDef, PropertyType,
    ScalarType,
};
use ply_rs_bw::writer::Writer;

use super::write::{check_fits, vertex_count};
use super::{RawInput, ReadErrorKind, echo, syntax};
use crate::complex::{Attribute, Location, Values};

mod body;

#[cfg(test)]
/// A property as a float, when it is a number.
fn number(p: &Property) -> Option<f64> {
    Some(match *p {
        Property::Char(x) => x.into(),
        Property::UChar(x) => x.into(),
        Property::Short(x) => x.into(),
        Property::UShort(x) => x.into(),
        Property::Int(x) => x.into(),
        Property::UInt(x) => x.into(),
        Property::Float(x) => x.into(),
        Property::Double(x) => x,
        _ => return None,
    })
}

/// A vertex id property (scalar or list entry), checked to be a non-negative integer.
fn id(x: i64, what: &str) -> Result<u32, ReadErrorKind> {
    if x < 0 {
        return Err(ReadErrorKind::NegativeId(x));
    }
    u32::try_from(x).map_err(|_| syntax(format!("{what}: vertex id {x} does not fit in 32 bits")))
}

#[cfg(test)]
/// A list property of vertex ids.
fn id_list(p: &Property, what: &str) -> Result<Vec<u32>, ReadErrorKind> {
    let ids: Vec<i64> = match p {
        Property::ListChar(v) => v.iter().map(|&x| x.into()).collect(),
        Property::ListUChar(v) => v.iter().map(|&x| x.into()).collect(),
        Property::ListShort(v) => v.iter().map(|&x| x.into()).collect(),
        Property::ListUShort(v) => v.iter().map(|&x| x.into()).collect(),
        Property::ListInt(v) => v.iter().map(|&x| x.into()).collect(),
        Property::ListUInt(v) => v.iter().map(|&x| x.into()).collect(),
        _ => {
            return Err(syntax(format!(
                "{what}: vertex_indices is not a list of integers"
            )));
        }
    };
    ids.into_iter().map(|x| id(x, what)).collect()
}

#[cfg(test)]
fn scalar_id(e: &DefaultElement, key: &str, what: &str) -> Result<u32, ReadErrorKind> {
    let p = e
        .get(key)
        .ok_or_else(|| syntax(format!("{what} has no `{key}` property")))?;
    match number(p) {
        Some(x) if x.fract() == 0.0 && x.abs() < 1e18 => id(x as i64, what),
        _ => Err(syntax(format!("{what}: `{key}` is not an integer"))),
    }
}

/// The crate's error as `(line, kind)`: its message's first line, without its "Line N: " (the
/// line is reported), capped and escaped.
fn crate_error(e: &ply_rs_bw::parser::ParseError) -> (u32, ReadErrorKind) {
    let line = e.line().map_or(0, |l| u32::try_from(l).unwrap_or(u32::MAX));
    let msg = e.to_string();
    let first = msg.lines().next().unwrap_or("");
    let first = match first.split_once(": ") {
        Some((l, rest)) if l.starts_with("Line ") => rest,
        _ => first,
    };
    (line, syntax(format!("PLY: {}", echo(first))))
}

/// Parses a PLY file. Errors are `(line, kind)` with line 0 when only an element index is known.
/// The header is read by the crate, the body (ASCII or binary) by our own reader (streaming,
/// nothing kept per element but what the complex needs).
pub fn parse(bytes: &[u8]) -> Result<RawInput, (u32, ReadErrorKind)> {
    parse_keeping(bytes, false)
}

/// [`parse`], keeping faces of more than 3 vertices as polygons when `polygons` (for
/// [`super::ReadOptions::triangulate`]).
pub(crate) fn parse_keeping(
    bytes: &[u8],
    polygons: bool,
) -> Result<RawInput, (u32, ReadErrorKind)> {
    let mut reader = ply_rs_bw::parser::Reader::new(bytes);
    let header = Parser::<DefaultElement>::new()
        .read_header(&mut reader)
        .map_err(|e| crate_error(&e))?;
    let body = *reader.get_ref();
    let header_len = bytes.len() - body.len();
    let first_line = bytes[..header_len].iter().filter(|&&c| c == b'\n').count() + 1;
    let binary = match header.encoding {
        Encoding::Ascii => None,
        Encoding::BinaryBigEndian => Some(true),
        Encoding::BinaryLittleEndian => Some(false),
    };
    body::parse_body(
        &header,
        &bytes[..header_len],
        body,
        first_line,
        binary,
        polygons,
    )
}

#[cfg(test)]
/// The whole file read by the crate (one map per element), mapped to simplices: the reference
/// the tests hold the streaming body reader to.
fn via_crate(bytes: &[u8]) -> Result<RawInput, (u32, ReadErrorKind)> {
    let ply = Parser::<DefaultElement>::new()
        .read_ply(&mut &bytes[..])
        .map_err(|e| crate_error(&e))?;
    let at0 = |k| (0, k);
    let mut raw = RawInput::new();
    let vertices: &[DefaultElement] = ply.payload.get("vertex").map_or(&[], Vec::as_slice);
    raw.vertex_count =
        Some(u32::try_from(vertices.len()).map_err(|_| at0(syntax("more than 2^32 vertices")))?);
    let dim = match vertices.first() {
        Some(v) if v.contains_key("z") => 3,
        Some(_) => 2,
        None => 3,
    };
    let mut data = Vec::with_capacity(vertices.len() * dim);
    for (i, v) in vertices.iter().enumerate() {
        for key in &["x", "y", "z"][..dim] {
            let x = v.get(*key).and_then(number).ok_or_else(|| {
                at0(syntax(format!(
                    "vertex #{i} has no numeric `{key}` property"
                )))
            })?;
            data.push(x);
        }
    }
    raw.coords = Some(super::Coords { dim, data });
    for (i, f) in ply.payload.get("face").into_iter().flatten().enumerate() {
        let what = format!("face #{i}");
        let list = f
            .get("vertex_indices")
            .or_else(|| f.get("vertex_index"))
            .ok_or_else(|| at0(syntax(format!("{what} has no vertex_indices list"))))?;
        let ids = id_list(list, &what).map_err(at0)?;
        match ids.len() {
            0 => return Err(at0(syntax(format!("{what} has no vertex")))),
            1..=3 => raw.push(&ids, 0),
            k => {
                return Err(at0(syntax(format!(
                    "{what}: {}",
                    ReadErrorKind::Polygon(k)
                ))));
            }
        }
    }
    for (i, e) in ply.payload.get("edge").into_iter().flatten().enumerate() {
        let what = format!("edge #{i}");
        let a = scalar_id(e, "vertex1", &what).map_err(at0)?;
        let b = scalar_id(e, "vertex2", &what).map_err(at0)?;
        raw.push(&[a, b], 0);
    }
    Ok(raw)
}

fn element(name: &str, count: usize, props: &[(String, PropertyType)]) -> ElementDef {
    let mut e = ElementDef::new(name.to_string());
    e.count = count;
    for (p, t) in props {
        e.properties.add(PropertyDef::new(p.to_string(), t.clone()));
    }
    e
}

/// Property names PLY keeps for coordinates and vertex ids, which no attribute may take.
const RESERVED: [&str; 7] = [
    "x",
    "y",
    "z",
    "vertex_indices",
    "vertex_index",
    "vertex1",
    "vertex2",
];

/// Whether PLY holds attribute `a` ([`super::write::Format::holds`]): one component, a name
/// that is a PLY property name (printable ASCII without blanks, not a coordinate or vertex-id
/// property), and a type PLY has: `i32` (`int`), `f32` (`float`), `f64` (`double`), `i64`
/// whose values all fit `uint` (what a `uint` property reads as).
pub(crate) fn holds(a: &Attribute) -> bool {
    a.components == 1
        && !a.name.is_empty()
        && a.name.bytes().all(|b| b.is_ascii_graphic())
        && !RESERVED.contains(&a.name.as_str())
        && match &a.values {
            Values::I64(v) => v.iter().all(|&x| u32::try_from(x).is_ok()),
            _ => true,
        }
}

/// The PLY type an attribute is written as (see [`holds`]).
fn scalar_type(v: &Values) -> PropertyType {
    PropertyType::Scalar(match v {
        Values::I32(_) => ScalarType::Int,
        Values::I64(_) => ScalarType::UInt,
        Values::F32(_) => ScalarType::Float,
        Values::F64(_) => ScalarType::Double,
    })
}

/// Element `i` of 1-component values as a PLY property (an `i64` fits `uint`: [`holds`]).
fn property(v: &Values, i: usize) -> Property {
    match v {
        Values::I32(v) => Property::Int(v[i]),
        Values::I64(v) => Property::UInt(u32::try_from(v[i]).unwrap_or(u32::MAX)),
        Values::F32(v) => Property::Float(v[i]),
        Values::F64(v) => Property::Double(v[i]),
    }
}

/// The vertex and the listed attributes of `raw` (each held: checked by the caller), refused
/// when they would not come back: listed data beside listed 0-simplices (which PLY leaves to
/// the vertex count), non-finite reals in ASCII.
fn data(raw: &RawInput, binary: bool) -> Result<(Vec<&Attribute>, Vec<&Attribute>), String> {
    let mut at = (Vec::new(), Vec::new());
    for a in raw.attributes.iter() {
        if !binary
            && let Some(i) =
                (0..a.values.len()).find(|&i| a.values.real(i).is_some_and(|x| !x.is_finite()))
        {
            return Err(format!(
                "attribute {} has a non-finite value at element {i}, which PLY readers do not \
                 accept in ASCII (use ply-binary)",
                a.describe()
            ));
        }
        match a.location {
            Location::Vertices => at.0.push(a),
            Location::Listed => {
                if let Some(i) = (0..raw.simplex_count()).find(|&i| raw.simplex(i).len() == 1) {
                    return Err(format!(
                        "attribute {} is on the listed simplices, and simplex #{i} {} is a \
                         vertex, which PLY does not list (its value would be lost)",
                        a.describe(),
                        super::write::show(raw.simplex(i))
                    ));
                }
                at.1.push(a);
            }
        }
    }
    Ok(at)
}

/// Writes `raw` as PLY, ASCII or binary little-endian, with its attributes as properties:
/// vertex ones on `vertex`, listed ones on `face` and `edge` (each value with its simplex).
pub(crate) fn write(raw: &RawInput, binary: bool, out: &mut Vec<u8>) -> Result<(), String> {
    check_fits(
        raw,
        3,
        "vertices, edges and triangles (use .msh, .vtk or .simplices)",
    )?;
    if !binary
        && let Some(c) = &raw.coords
        && let Some(i) = c.data.iter().position(|x| !x.is_finite())
    {
        return Err(format!(
            "vertex {} has a non-finite coordinate, which PLY readers do not accept in ASCII \
             (use ply-binary)",
            i / c.dim
        ));
    }
    let mut elements = Elements::of(raw)?;
    let (vertex_data, listed_data) = data(raw, binary)?;
    elements.add_data(raw, &vertex_data, &listed_data);
    let mut ply = elements.into_ply(binary, &vertex_data, &listed_data);
    Writer::new()
        .write_ply(out, &mut ply)
        .map_err(|e| format!("PLY writer: {e}"))?;
    Ok(())
}

/// The listed simplices of `len` vertices, by listing index.
fn rows_of(raw: &RawInput, len: usize) -> impl Iterator<Item = usize> + '_ {
    (0..raw.simplex_count()).filter(move |&i| raw.simplex(i).len() == len)
}

/// The three PLY elements a complex writes: a vertex per vertex id (x, y, z; 0 where there are
/// fewer coordinates), a face per listed triangle, an edge per listed edge.
struct Elements {
    vertices: Vec<DefaultElement>,
    faces: Vec<DefaultElement>,
    edges: Vec<DefaultElement>,
}

impl Elements {
    fn of(raw: &RawInput) -> Result<Elements, String> {
        let id =
            |v: u32| i32::try_from(v).map_err(|_| format!("vertex id {v} does not fit PLY's int"));
        let coords = raw.coords.as_ref();
        let n = vertex_count(raw);
        let mut vertices = Vec::with_capacity(n);
        for v in 0..n {
            let mut e = DefaultElement::new();
            for (k, key) in ["x", "y", "z"].into_iter().enumerate() {
                let x = coords
                    .filter(|c| k < c.dim)
                    .map_or(0.0, |c| c.data[v * c.dim + k]);
                e.insert(key.to_string(), Property::Double(x));
            }
            vertices.push(e);
        }
        let mut faces = Vec::new();
        for i in rows_of(raw, 3) {
            let mut e = DefaultElement::new();
            let ids = raw
                .simplex(i)
                .iter()
                .map(|&v| id(v))
                .collect::<Result<_, _>>()?;
            e.insert("vertex_indices".to_string(), Property::ListInt(ids));
            faces.push(e);
        }
        let mut edges = Vec::new();
        for i in rows_of(raw, 2) {
            let mut e = DefaultElement::new();
            e.insert("vertex1".to_string(), Property::Int(id(raw.simplex(i)[0])?));
            e.insert("vertex2".to_string(), Property::Int(id(raw.simplex(i)[1])?));
            edges.push(e);
        }
        Ok(Elements {
            vertices,
            faces,
            edges,
        })
    }

    /// Each attribute as a property of every vertex, or of every face and edge (by listing
    /// index).
    fn add_data(&mut self, raw: &RawInput, vertex_data: &[&Attribute], listed_data: &[&Attribute]) {
        for a in vertex_data {
            for (v, e) in self.vertices.iter_mut().enumerate() {
                e.insert(a.name.clone(), property(&a.values, v));
            }
        }
        for a in listed_data {
            for (i, e) in rows_of(raw, 3).zip(self.faces.iter_mut()) {
                e.insert(a.name.clone(), property(&a.values, i));
            }
            for (i, e) in rows_of(raw, 2).zip(self.edges.iter_mut()) {
                e.insert(a.name.clone(), property(&a.values, i));
            }
        }
    }

    /// The header declaring each element with its properties, and the payload.
    fn into_ply(
        self,
        binary: bool,
        vertex_data: &[&Attribute],
        listed_data: &[&Attribute],
    ) -> Ply<DefaultElement> {
        let mut ply = Ply::<DefaultElement>::new();
        ply.header.encoding = if binary {
            Encoding::BinaryLittleEndian
        } else {
            Encoding::Ascii
        };
        ply.header.comments.push("written by topoplex".to_string());
        let double = PropertyType::Scalar(ScalarType::Double);
        let int = PropertyType::Scalar(ScalarType::Int);
        let declared = |base: Vec<(&'static str, PropertyType)>, data: &[&Attribute]| {
            let mut props: Vec<(String, PropertyType)> =
                base.into_iter().map(|(k, t)| (k.to_string(), t)).collect();
            props.extend(
                data.iter()
                    .map(|a| (a.name.clone(), scalar_type(&a.values))),
            );
            props
        };
        let xyz = vec![("x", double.clone()), ("y", double.clone()), ("z", double)];
        let n = self.vertices.len();
        ply.header
            .elements
            .add(element("vertex", n, &declared(xyz, vertex_data)));
        ply.payload.insert("vertex".to_string(), self.vertices);
        // Listed data on no face or edge: an empty `face` element still declares it.
        if !self.faces.is_empty() || (self.edges.is_empty() && !listed_data.is_empty()) {
            let list = PropertyType::List(ScalarType::UChar, ScalarType::Int);
            let props = declared(vec![("vertex_indices", list)], listed_data);
            ply.header
                .elements
                .add(element("face", self.faces.len(), &props));
            ply.payload.insert("face".to_string(), self.faces);
        }
        if !self.edges.is_empty() {
            let ends = vec![("vertex1", int.clone()), ("vertex2", int)];
            let props = declared(ends, listed_data);
            ply.header
                .elements
                .add(element("edge", self.edges.len(), &props));
            ply.payload.insert("edge".to_string(), self.edges);
        }
        ply
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// ASCII bodies read by the streaming reader and by the crate: the same simplices and
    /// coordinates, or both refused. (Where the reader is stricter than the crate — extra
    /// values on a line, floats the declared type cannot hold — or reads more — `nan`,
    /// `tetra`, `tristrips` — the cases are in the tests below.)
    const HEAD: &str =
        "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n";

    /// Each case is [`HEAD`] followed by it.
    const CASES: [&str; 15] = [
        "element face 2\nproperty list uchar int vertex_indices\nend_header\n0 0\n1 0\n0 1\n3 0 1 2\n2 1 2\n",
        "element edge 1\nproperty int vertex1\nproperty uint vertex2\nelement face 1\nproperty list uchar uint vertex_index\nend_header\n0 0\n1 0\n0 1\n0 1\n1 2\n",
        "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0\n1 0\n0 1\n4 0 1 2 0\n",
        "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0\n1 0\n0 1\n3 0 -1 2\n",
        "element face 1\nproperty list uchar uchar vertex_indices\nend_header\n0 0\n1 0\n0 1\n3 0 256 2\n",
        "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0\n1 0\n0 1\n3 0 1\n",
        "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0\n1 0\n0 1\n",
        "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0\n1 x\n0 1\n3 0 1 2\n",
        "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0\n1 .5\n0 1\n3 0 1 2\n",
        "element face 1\nproperty list uchar int vertex_indices\nend_header\n0\t0\r\n1.5e3 -0\n0 +1\n3 0 1 2\n",
        "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0\n1 0\n0 1\n0\n",
        "element other 1\nproperty float w\nend_header\n0 0\n1 0\n0 1\n5\n",
        "element edge 1\nproperty float vertex1\nproperty float vertex2\nend_header\n0 0\n1 0\n0 1\n0 1.5\n",
        "end_header\n0 0\n1 0\n0 1\n\n",
        "end_header\n0 0\n1 0\n",
    ];

    #[test]
    fn ascii_body_reads_as_the_crate_does() {
        let mut both_ok = 0;
        for case in CASES {
            let text = format!("{HEAD}{case}");
            let ours = parse(text.as_bytes());
            let theirs = via_crate(text.as_bytes());
            match (&ours, &theirs) {
                (Ok(a), Ok(b)) => {
                    assert_eq!(a, b, "{text}");
                    both_ok += 1;
                }
                (Err(_), Err(_)) => {}
                _ => panic!("{text}\nours {ours:?}\ncrate {theirs:?}"),
            }
        }
        assert!(both_ok >= 4, "only {both_ok} cases read");
    }

    fn err(text: &str) -> String {
        let (line, kind) = parse(text.as_bytes()).unwrap_err();
        format!("{line}: {kind}")
    }

    const FACE: &str = "element face 1\nproperty list uchar int vertex_indices\nend_header\n";

    #[test]
    fn an_extra_value_on_a_face_or_vertex_line_is_refused_naming_the_element() {
        let e = err(&format!("{HEAD}{FACE}0 0\n1 0\n0 1\n3 0 1 2 9\n"));
        assert_eq!(
            e,
            "12: PLY: face #0 has 1 more value(s) than its properties declare ('9' follows the \
             last of its 4 values)"
        );
        let e = err(&format!("{HEAD}{FACE}0 0\n1 0 7 8\n0 1\n3 0 1 2\n"));
        assert!(
            e.starts_with("10: PLY: vertex #1 has 2 more value(s)"),
            "{e}"
        );
    }

    #[test]
    fn floats_the_declared_type_cannot_hold_are_refused_and_nan_is_read() {
        for (tok, what) in [
            ("1e39", "too large for a 32-bit float"),
            ("1e309", "too large for a 32-bit float"),
            ("1e-50", "too small for a 32-bit float"),
            ("1e-400", "too small for a 32-bit float"),
        ] {
            let e = err(&format!("{HEAD}{FACE}0 0\n1 {tok}\n0 1\n3 0 1 2\n"));
            assert!(
                e.starts_with(&format!("10: PLY: number '{tok}' is {what}"))
                    && e.contains("property 'y' of vertex #1"),
                "{e}"
            );
        }
        // Declared double: 1e39 is exact enough, 1e309 is not.
        let head = HEAD.replace("float", "double");
        let raw = parse(format!("{head}{FACE}0 0\n1 1e39\n0 1\n3 0 1 2\n").as_bytes()).unwrap();
        assert_eq!(raw.coords.unwrap().data[3], 1e39);
        let e = err(&format!("{head}{FACE}0 0\n1 1e309\n0 1\n3 0 1 2\n"));
        assert!(e.contains("too large for a 64-bit float"), "{e}");
        // nan and inf spelled so are read, as every reader does; not for an integer type.
        let raw =
            parse(format!("{HEAD}{FACE}nan 0\n-inf 0\n0 Infinity\n3 0 1 2\n").as_bytes()).unwrap();
        let d = raw.coords.unwrap().data;
        assert!(d[0].is_nan() && d[2] == f64::NEG_INFINITY && d[5] == f64::INFINITY);
        let e = err(&format!("{HEAD}{FACE}0 0\n1 0\n0 1\n3 0 nan 2\n"));
        assert_eq!(
            e,
            "12: PLY: 'nan' is not a number (property 'vertex_indices' of face #0, declared int)"
        );
    }

    #[test]
    fn tetra_elements_are_tetrahedra() {
        let text = "ply\nformat ascii 1.0\nelement vertex 5\nproperty float x\nproperty float y\n\
             property float z\nelement tetra 2\nproperty list uchar int vertex_indices\n\
             end_header\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n1 1 1\n4 0 1 2 3\n4 1 2 3 4\n";
        let raw = parse(text.as_bytes()).unwrap();
        assert_eq!(raw.ids, [0, 1, 2, 3, 1, 2, 3, 4]);
        let e = err(&text.replace("4 1 2 3 4\n", "3 1 2 3\n"));
        assert_eq!(e, "0: tetra #1 has 3 vertex ids; a tetra element lists 4");
    }

    #[test]
    fn tristrips_are_read_as_their_triangles() {
        let head = "ply\nformat ascii 1.0\nelement vertex 6\nproperty float x\n\
                    property float y\nelement tristrips 1\nproperty list int int vertex_indices\n\
                    end_header\n0 0\n1 0\n0 1\n1 1\n2 0\n2 1\n";
        // Two strips: 0 1 2 3 (triangles 012, 123) and 4 5 1 (triangle 451).
        let raw = parse(format!("{head}8 0 1 2 3 -1 4 5 1\n").as_bytes()).unwrap();
        assert_eq!(raw.ids, [0, 1, 2, 1, 2, 3, 4, 5, 1]);
        // A strip stitched by repeated ids: the degenerate joins make no triangle.
        let raw = parse(format!("{head}8 0 1 2 2 4 4 5 1\n").as_bytes()).unwrap();
        assert_eq!(raw.ids, [0, 1, 2, 4, 5, 1]);
        let e = err(&format!("{head}5 0 1 2 -1 4\n"));
        assert_eq!(
            e,
            "0: tristrips #0: strip #1 has 1 vertex ids; a strip needs at least 3"
        );
    }

    #[test]
    fn an_unknown_element_listing_vertex_ids_is_refused_not_dropped() {
        let e = err(&format!(
            "{HEAD}element polyline 1\nproperty list uchar int vertex_indices\nend_header\n\
             0 0\n1 0\n0 1\n3 0 1 2\n"
        ));
        assert!(
            e.starts_with("0: PLY: element 'polyline' has a 'vertex_indices' property"),
            "{e}"
        );
        // Elements without vertex ids (materials, cameras) are still ignored.
        assert!(parse(format!("{HEAD}{}", CASES[11]).as_bytes()).is_ok());
    }

    /// The cases the crate reads, written by the crate in both byte orders: the streaming
    /// binary reader gives the same simplices and coordinates; cut short, both refuse.
    #[test]
    fn binary_body_reads_as_the_crate_does() {
        let mut read = 0;
        for case in CASES {
            let text = format!("{HEAD}{case}");
            let Ok(mut ply) = Parser::<DefaultElement>::new().read_ply(&mut text.as_bytes()) else {
                continue;
            };
            for encoding in [Encoding::BinaryLittleEndian, Encoding::BinaryBigEndian] {
                ply.header.encoding = encoding;
                let mut bytes = Vec::new();
                Writer::new().write_ply(&mut bytes, &mut ply).unwrap();
                let (ours, theirs) = (parse(&bytes), via_crate(&bytes));
                match (&ours, &theirs) {
                    (Ok(a), Ok(b)) => assert_eq!(a, b, "{text} as {encoding:?}"),
                    (Err(_), Err(_)) => {}
                    _ => panic!("{text} as {encoding:?}\nours {ours:?}\ncrate {theirs:?}"),
                }
                read += usize::from(ours.is_ok());
                let body = bytes.len()
                    - (bytes
                        .windows(11)
                        .position(|w| w == b"end_header\n")
                        .unwrap()
                        + 11);
                for cut in 1..=body.min(3) {
                    let short = &bytes[..bytes.len() - cut];
                    assert!(
                        parse(short).is_err() && via_crate(short).is_err(),
                        "{text} cut {cut}"
                    );
                }
            }
        }
        assert!(read >= 8, "only {read} binary cases read");
    }

    /// Extra vertex, face and edge properties of every scalar type: read as attributes of the
    /// mapped type (values exact), listed ones in listing order (faces, then edges, whatever
    /// the elements' order), and written back in both encodings to the same attributes.
    #[test]
    fn extra_properties_are_attributes_and_come_back_in_both_encodings() {
        let text = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n\
             property uchar red\nproperty float quality\nproperty uint id\n\
             element edge 1\nproperty int vertex1\nproperty int vertex2\nproperty short region\n\
             element face 2\nproperty list uchar int vertex_indices\nproperty short region\n\
             property double w\nend_header\n\
             0 0 255 0.1 4294967295\n1 0 0 -1e-3 0\n0 1 7 3.4028235e38 12\n0 1 -5\n\
             3 0 1 2 9 0.25\n2 1 2 -32768 1e300\n";
        let e = err(&text.replace("property double w\n", ""));
        assert!(e.contains("has 1 more value"), "{e}");
        // The edge lacks `w`: refused, naming both and the line declaring it.
        let e = err(text);
        assert_eq!(
            e,
            "16: PLY: property 'w' of element 'face' is not on element 'edge', which lists \
             simplices too; an attribute has a value for every listed simplex, so it is refused \
             rather than padded"
        );
        let text = text
            .replace(
                "property short region\nelement face",
                "property short region\nproperty double w\nelement face",
            )
            .replace("0 1 -5\n", "0 1 -5 -0\n");
        let raw = parse(text.as_bytes()).unwrap();
        assert_eq!(raw.ids, [0, 1, 2, 1, 2, 0, 1]);
        let at = &raw.attributes;
        let v = |n| &at.get(n, Location::Vertices).unwrap().values;
        let l = |n| &at.get(n, Location::Listed).unwrap().values;
        assert_eq!(v("red"), &Values::I32(vec![255, 0, 7]));
        assert_eq!(v("quality"), &Values::F32(vec![0.1, -1e-3, f32::MAX]));
        assert_eq!(v("id"), &Values::I64(vec![4294967295, 0, 12]));
        assert_eq!(l("region"), &Values::I32(vec![9, -32768, -5]));
        assert!(l("w").bits_eq(&Values::F64(vec![0.25, 1e300, -0.0])));
        assert_eq!(at.iter().count(), 5);
        for binary in [false, true] {
            let mut out = Vec::new();
            write(&raw, binary, &mut out).unwrap();
            let back = parse(&out).unwrap();
            assert_eq!(back.ids, raw.ids);
            assert!(back.attributes.bits_eq(at), "{:?}", back.attributes);
        }
    }

    #[test]
    fn a_list_property_other_than_the_vertex_ids_is_refused_naming_it() {
        let e = err(&format!(
            "{HEAD}element face 1\nproperty list uchar int vertex_indices\n\
             property list uchar float texcoord\nend_header\n0 0\n1 0\n0 1\n3 0 1 2 2 0 0\n"
        ));
        assert!(
            e.starts_with("8: PLY: property 'texcoord' of element 'face' is a list"),
            "{e}"
        );
        let e = err(&HEAD.replace(
            "property float y\n",
            "property float y\nproperty list uchar int n\nend_header\n0 0 0\n1 0 0\n0 1 0\n",
        ));
        assert!(
            e.contains("property 'n' of element 'vertex' is a list"),
            "{e}"
        );
    }

    #[test]
    fn a_strip_s_triangles_share_its_values() {
        let text = "ply\nformat ascii 1.0\nelement vertex 5\nproperty float x\nproperty float y\n\
             element tristrips 1\nproperty list int int vertex_indices\nproperty int part\n\
             element face 1\nproperty list uchar int vertex_indices\nproperty int part\n\
             end_header\n0 0\n1 0\n0 1\n1 1\n2 2\n4 0 1 2 3 6\n3 2 3 4 8\n";
        let raw = parse(text.as_bytes()).unwrap();
        assert_eq!(
            raw.attributes.get("part", Location::Listed).unwrap().values,
            Values::I32(vec![6, 6, 8])
        );
    }
}
