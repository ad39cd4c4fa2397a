//! The body of a `format ascii` PLY file, read line by line without the crate: the crate builds
//! a map per element (55× the file for short lines), this keeps only coordinates and simplices.
//! Accepts and refuses what the crate does: one element per line, tokens separated by spaces or
//! tabs matching `[-+]?[0-9]+(.[0-9]+)?([eE][-+]?[0-9]+)?`, each parsed as its property's type
//! (so `-1` is no `uchar`), extra tokens ignored.

use ply_rs_bw::ply::{ElementDef, Header, PropertyType, ScalarType};

use super::super::{Coords, RawInput, ReadErrorKind, echo, syntax};
use super::id;

type Res<T> = Result<T, (u32, ReadErrorKind)>;

/// Whether `t` is a number as the crate's data-line grammar has it.
fn is_number(t: &[u8]) -> bool {
    let mut i = usize::from(matches!(t.first(), Some(b'-' | b'+')));
    let digits = |i: &mut usize| {
        let s = *i;
        while t.get(*i).is_some_and(u8::is_ascii_digit) {
            *i += 1;
        }
        *i > s
    };
    if !digits(&mut i) {
        return false;
    }
    if t.get(i) == Some(&b'.') {
        i += 1;
        if !digits(&mut i) {
            return false;
        }
    }
    if matches!(t.get(i), Some(b'e' | b'E')) {
        i += 1;
        if matches!(t.get(i), Some(b'-' | b'+')) {
            i += 1;
        }
        if !digits(&mut i) {
            return false;
        }
    }
    i == t.len()
}

/// `t` parsed as the scalar type `ty`, as a float (every PLY scalar fits one exactly).
fn scalar(t: &str, ty: &ScalarType) -> Option<f64> {
    Some(match ty {
        ScalarType::Char => t.parse::<i8>().ok()?.into(),
        ScalarType::UChar => t.parse::<u8>().ok()?.into(),
        ScalarType::Short => t.parse::<i16>().ok()?.into(),
        ScalarType::UShort => t.parse::<u16>().ok()?.into(),
        ScalarType::Int => t.parse::<i32>().ok()?.into(),
        ScalarType::UInt => t.parse::<u32>().ok()?.into(),
        ScalarType::Float => t.parse::<f32>().ok()?.into(),
        ScalarType::Double => t.parse::<f64>().ok()?,
    })
}

/// What is kept of an element's properties: the index of each wanted one, if present.
struct Wanted<'h> {
    def: &'h ElementDef,
    keys: Vec<Option<usize>>,
}

impl<'h> Wanted<'h> {
    fn new(def: &'h ElementDef, names: &[&[&str]]) -> Self {
        let keys = names
            .iter()
            .map(|alts| {
                def.properties
                    .iter()
                    .position(|(k, _)| alts.contains(&k.as_str()))
            })
            .collect();
        Wanted { def, keys }
    }
}

/// The body's lines, each with its 1-based line number.
struct Lines<'a> {
    rest: &'a [u8],
    line: usize,
}

impl<'a> Lines<'a> {
    fn next_line(&mut self) -> Option<(&'a [u8], u32)> {
        if self.rest.is_empty() {
            return None;
        }
        // The crate reads up to '\n'; a lone '\r' or "\r\n" ends the data too.
        let end = self
            .rest
            .iter()
            .position(|&c| c == b'\n')
            .map_or(self.rest.len(), |p| p + 1);
        let (l, rest) = self.rest.split_at(end);
        self.rest = rest;
        let n = u32::try_from(self.line).unwrap_or(u32::MAX);
        self.line += 1;
        Some((l, n))
    }
}

/// One element line's values: the wanted properties as floats (lists: their entries appended
/// to `list`), checked against the property types.
fn read_line(
    l: &[u8],
    line: u32,
    def: &ElementDef,
    wanted: &Wanted,
    vals: &mut [f64],
    list: &mut Vec<f64>,
) -> Res<()> {
    let bad = |msg: String| (line, syntax(format!("PLY: {}", echo(&msg))));
    let mut body = l;
    while let Some((&c, r)) = body.split_last() {
        if c == b'\n' || c == b'\r' {
            body = r;
        } else {
            break;
        }
    }
    let mut toks = body
        .split(|&c| c == b' ' || c == b'\t')
        .filter(|t| !t.is_empty());
    // The crate checks the whole line's grammar first.
    if body
        .split(|&c| c == b' ' || c == b'\t')
        .any(|t| !t.is_empty() && !is_number(t))
    {
        return Err(bad(format!(
            "Couldn't read element line '{}'",
            String::from_utf8_lossy(body)
        )));
    }
    let mut next = |ty: &dyn std::fmt::Debug| {
        toks.next()
            .map(|t| std::str::from_utf8(t).unwrap_or(""))
            .ok_or_else(|| {
                bad(format!(
                    "expected element of type '{ty:?}', but found nothing"
                ))
            })
    };
    for (p, (name, prop)) in def.properties.iter().enumerate() {
        let slot = wanted.keys.iter().position(|&k| k == Some(p));
        match &prop.data_type {
            PropertyType::Scalar(ty) => {
                let t = next(ty)?;
                let x = scalar(t, ty)
                    .ok_or_else(|| bad(format!("'{t}' is no {ty:?} (property '{name}')")))?;
                if let Some(s) = slot {
                    vals[s] = x;
                }
            }
            PropertyType::List(count_ty, ty) => {
                let t = next(count_ty)?;
                let count: usize = t
                    .parse()
                    .map_err(|_| bad(format!("'{t}' is no list length (property '{name}')")))?;
                for _ in 0..count {
                    let t = next(ty)?;
                    let x = scalar(t, ty)
                        .ok_or_else(|| bad(format!("'{t}' is no {ty:?} (property '{name}')")))?;
                    if slot.is_some() {
                        list.push(x);
                    }
                }
            }
        }
    }
    Ok(())
}

/// Checks that the wanted property `k` of `w` exists and is a scalar.
fn need_scalar(w: &Wanted, k: usize, what: &str, key: &str) -> Res<()> {
    match w.keys[k].map(|p| &w.def.properties[p].data_type) {
        Some(PropertyType::Scalar(_)) => Ok(()),
        _ => Err((0, syntax(format!("{what} has no numeric `{key}` property")))),
    }
}

/// A vertex id read as a float from an integer or float property.
fn id_of(x: f64, what: &str) -> Result<u32, ReadErrorKind> {
    if x.fract() != 0.0 || x.abs() >= 1e18 {
        return Err(syntax(format!("{what}: vertex id {x} is not an integer")));
    }
    id(x as i64, what)
}

/// The vertex coordinates, faces and edges of an ASCII body starting at line `first_line`.
pub(super) fn parse_body(header: &Header, body: &[u8], first_line: usize) -> Res<RawInput> {
    let at0 = |k| (0, k);
    let mut lines = Lines {
        rest: body,
        line: first_line,
    };
    let mut raw = RawInput::new();
    let mut coords = Coords {
        dim: 3,
        data: Vec::new(),
    };
    let mut edges: Vec<u32> = Vec::new();
    let mut vertex_count = 0usize;
    let mut vals = [0.0f64; 3];
    let mut list = Vec::new();
    // Every element line takes at least 2 bytes, so the bytes left bound every reservation.
    let cap = body.len() / 2 + 1;
    for (name, def) in &header.elements {
        let wanted = match name.as_str() {
            "vertex" => {
                let w = Wanted::new(def, &[&["x"], &["y"], &["z"]]);
                coords.dim = if w.keys[2].is_some() || def.count == 0 {
                    3
                } else {
                    2
                };
                vertex_count = def.count;
                if def.count > 0 {
                    for (k, key) in ["x", "y", "z"][..coords.dim].iter().enumerate() {
                        need_scalar(&w, k, "vertex #0", key)?;
                    }
                }
                coords.data = Vec::new();
                coords.data.reserve_exact(def.count.min(cap) * coords.dim);
                w
            }
            "face" => {
                let w = Wanted::new(def, &[&["vertex_indices", "vertex_index"]]);
                match w.keys[0].map(|p| &def.properties[p].data_type) {
                    _ if def.count == 0 => {}
                    None => return Err(at0(syntax("face #0 has no vertex_indices list"))),
                    Some(PropertyType::List(_, ScalarType::Float | ScalarType::Double))
                    | Some(PropertyType::Scalar(_)) => {
                        return Err(at0(syntax(
                            "face #0: vertex_indices is not a list of integers",
                        )));
                    }
                    Some(PropertyType::List(..)) => {}
                }
                raw.offsets.reserve_exact(def.count.min(cap));
                raw.lines.reserve_exact(def.count.min(cap));
                w
            }
            "edge" => {
                let w = Wanted::new(def, &[&["vertex1"], &["vertex2"]]);
                if def.count > 0 {
                    need_scalar(&w, 0, "edge #0", "vertex1")?;
                    need_scalar(&w, 1, "edge #0", "vertex2")?;
                }
                edges.reserve_exact(def.count.min(cap) * 2);
                w
            }
            _ => Wanted::new(def, &[]),
        };
        for i in 0..def.count {
            let Some((l, n)) = lines.next_line() else {
                return Err((
                    u32::try_from(lines.line).unwrap_or(u32::MAX),
                    syntax(format!(
                        "PLY: Unexpected end of file while reading element '{}' (expected {}, got {i}).",
                        echo(name),
                        def.count
                    )),
                ));
            };
            list.clear();
            read_line(l, n, def, &wanted, &mut vals, &mut list)?;
            match name.as_str() {
                "vertex" => coords.data.extend_from_slice(&vals[..coords.dim]),
                "face" => push_face(&mut raw, &list, i)?,
                "edge" => {
                    for x in [vals[0], vals[1]] {
                        let v = id_of(x, "")
                            .map_err(|_| at0(id_of(x, &format!("edge #{i}")).unwrap_err()))?;
                        edges.push(v);
                    }
                }
                _ => {}
            }
        }
    }
    raw.vertex_count =
        Some(u32::try_from(vertex_count).map_err(|_| at0(syntax("more than 2^32 vertices")))?);
    raw.coords = Some(coords);
    // Faces come before edges in the listing, whatever the elements' order.
    raw.offsets.reserve_exact(edges.len() / 2);
    raw.lines.reserve_exact(edges.len() / 2);
    for e in edges.chunks_exact(2) {
        raw.push(e, 0);
    }
    Ok(raw)
}

/// Face `i` with ids `list` as a simplex of `raw`.
fn push_face(raw: &mut RawInput, list: &[f64], i: usize) -> Res<()> {
    let at0 = |k| (0, k);
    let what = || format!("face #{i}");
    let mut ids = [0u32; 3];
    for (k, &x) in list.iter().enumerate() {
        let v = id_of(x, "").map_err(|_| at0(id_of(x, &what()).unwrap_err()))?;
        if k < 3 {
            ids[k] = v;
        }
    }
    match list.len() {
        0 => Err(at0(syntax(format!("face #{i} has no vertex")))),
        1..=3 => {
            raw.push(&ids[..list.len()], 0);
            Ok(())
        }
        k => Err(at0(syntax(format!(
            "face #{i}: {}",
            ReadErrorKind::Polygon(k)
        )))),
    }
}
