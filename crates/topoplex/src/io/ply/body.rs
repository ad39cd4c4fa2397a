//! The body of a PLY file, read as it streams without the crate: the crate builds a map per
//! element (55× an ASCII file of short lines, 34× a binary one), this keeps only coordinates and
//! simplices. ASCII bodies: accepts and refuses what the crate does: one element per line, tokens
//! separated by spaces or tabs matching `[-+]?[0-9]+(.[0-9]+)?([eE][-+]?[0-9]+)?`, each parsed
//! as its property's type (so `-1` is no `uchar`), extra tokens ignored. Binary bodies: each
//! property's value in its type's width and the file's byte order, list lengths non-negative
//! integers; running out of bytes is the crate's end-of-file error.

use ply_rs_bw::ply::{ElementDef, Header, PropertyType, ScalarType};

use super::super::{
    Coords, Float, RawInput, ReadErrorKind, echo, no_room, parse_real, syntax, try_with_capacity,
};
use super::id;
use crate::complex::table;
use crate::complex::{Attribute, Location, ValueType, Values};
use crate::io::Res;

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

/// Whether `t` spells a NaN or an infinity (`nan`, `inf`, `infinity`, any case, signed).
fn is_non_finite(t: &[u8]) -> bool {
    let t = t
        .strip_prefix(b"-")
        .or_else(|| t.strip_prefix(b"+"))
        .unwrap_or(t);
    ["nan", "inf", "infinity"]
        .iter()
        .any(|w| t.eq_ignore_ascii_case(w.as_bytes()))
}

/// The PLY name of a scalar type, for messages.
fn type_name(ty: &ScalarType) -> &'static str {
    match ty {
        ScalarType::Char => "char",
        ScalarType::UChar => "uchar",
        ScalarType::Short => "short",
        ScalarType::UShort => "ushort",
        ScalarType::Int => "int",
        ScalarType::UInt => "uint",
        ScalarType::Float => "float",
        ScalarType::Double => "double",
    }
}

/// `t` parsed as the scalar type `ty`, as a float (every PLY scalar fits one exactly); `what`
/// names the value for the message. Floats go through the readers' shared check
/// ([`super::super::parse_real`]): a value the declared type would turn into infinity or 0
/// is refused; `nan` and `inf` spelled so are accepted (as in every reader).
fn scalar(t: &str, ty: &ScalarType, what: &dyn Fn() -> String) -> Result<f64, String> {
    let int = |ok: Option<f64>| {
        ok.ok_or_else(|| format!("'{}' is not a {} ({})", echo(t), type_name(ty), what()))
    };
    let real = |f: Float| {
        parse_real(t, &what(), f).map_err(|e| match e {
            ReadErrorKind::Syntax(m) => m,
            e => e.to_string(),
        })
    };
    match ty {
        ScalarType::Char => int(t.parse::<i8>().ok().map(f64::from)),
        ScalarType::UChar => int(t.parse::<u8>().ok().map(f64::from)),
        ScalarType::Short => int(t.parse::<i16>().ok().map(f64::from)),
        ScalarType::UShort => int(t.parse::<u16>().ok().map(f64::from)),
        ScalarType::Int => int(t.parse::<i32>().ok().map(f64::from)),
        ScalarType::UInt => int(t.parse::<u32>().ok().map(f64::from)),
        ScalarType::Float => real(Float::F32),
        ScalarType::Double => real(Float::F64),
    }
}

/// What is kept of an element's properties: the index of each wanted one, if present.
struct Wanted<'h> {
    def: &'h ElementDef,
    keys: Vec<Option<usize>>,
    /// Keys from this one on are extra properties kept as attributes: a `float` among them is
    /// parsed as an `f32` directly (exact, no double rounding through `f64`).
    extra_from: usize,
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
        Wanted {
            def,
            keys,
            extra_from: names.len(),
        }
    }

    /// Adds the scalar properties `extras` (indices into the element's properties) as kept
    /// extra properties, after the named ones.
    fn with_extras(mut self, extras: &[usize]) -> Self {
        self.extra_from = self.keys.len();
        self.keys.extend(extras.iter().map(|&p| Some(p)));
        self
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

/// Where element records come from: text lines, or packed values in a byte order.
enum Records<'a> {
    Text(Lines<'a>),
    Binary { rest: &'a [u8], big_endian: bool },
}

/// The next `n` bytes of `rest`, or `None` when fewer are left.
fn take<'a>(rest: &mut &'a [u8], n: usize) -> Option<&'a [u8]> {
    if rest.len() < n {
        return None;
    }
    let (a, b) = rest.split_at(n);
    *rest = b;
    Some(a)
}

/// One binary value of type `ty`, as a float (every PLY scalar fits one exactly).
fn binary_scalar(rest: &mut &[u8], ty: &ScalarType, big: bool) -> Option<f64> {
    macro_rules! num {
        ($t:ty) => {{
            let a = take(rest, size_of::<$t>())?.try_into().ok()?;
            let v = if big {
                <$t>::from_be_bytes(a)
            } else {
                <$t>::from_le_bytes(a)
            };
            f64::from(v)
        }};
    }
    Some(match ty {
        ScalarType::Char => num!(i8),
        ScalarType::UChar => num!(u8),
        ScalarType::Short => num!(i16),
        ScalarType::UShort => num!(u16),
        ScalarType::Int => num!(i32),
        ScalarType::UInt => num!(u32),
        ScalarType::Float => num!(f32),
        ScalarType::Double => num!(f64),
    })
}

/// One binary element's values, as [`read_line`] gives them; `Ok(false)` when the bytes ran
/// out.
fn read_binary(
    rest: &mut &[u8],
    big: bool,
    def: &ElementDef,
    wanted: &Wanted,
    vals: &mut [f64],
    list: &mut Vec<f64>,
) -> Res<bool> {
    for (p, (name, prop)) in def.properties.iter().enumerate() {
        let slot = wanted.keys.iter().position(|&k| k == Some(p));
        match &prop.data_type {
            PropertyType::Scalar(ty) => {
                let Some(x) = binary_scalar(rest, ty, big) else {
                    return Ok(false);
                };
                if let Some(s) = slot {
                    vals[s] = x;
                }
            }
            PropertyType::List(count_ty, ty) => {
                let Some(count) = binary_scalar(rest, count_ty, big) else {
                    return Ok(false);
                };
                if count < 0.0 || count.fract() != 0.0 {
                    return Err((
                        0,
                        syntax(format!(
                            "PLY: list length {count} of property '{}' is no count",
                            echo(name)
                        )),
                    ));
                }
                // Each entry is read before it is kept: the bytes left bound the list.
                for _ in 0..count as u64 {
                    let Some(x) = binary_scalar(rest, ty, big) else {
                        return Ok(false);
                    };
                    if slot.is_some() {
                        table::try_push(list, x)
                            .map_err(|b| (0, no_room("a list property's entries")(b)))?;
                    }
                }
            }
        }
    }
    Ok(true)
}

/// One element line's values: the wanted properties as floats (lists: their entries appended
/// to `list`), each token checked against its property's type. Entry `index` of element
/// `name` names the line's values in messages; a line with more values than the element's
/// properties declare is refused (nothing is dropped silently).
#[allow(clippy::too_many_arguments)]
fn read_line(
    l: &[u8],
    line: u32,
    name: &str,
    index: usize,
    def: &ElementDef,
    wanted: &Wanted,
    vals: &mut [f64],
    list: &mut Vec<f64>,
) -> Res<()> {
    let bad = |msg: String| (line, syntax(format!("PLY: {msg}")));
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
    let mut seen = 0usize;
    // The next token, checked to be a number as the PLY grammar has it (`nan` and `inf` too
    // where the type is a float), as text.
    let mut next = |ty: &ScalarType, prop: &str| -> Res<&str> {
        let what = || format!("property '{}' of {} #{index}", echo(prop), echo(name));
        let t = toks.next().ok_or_else(|| {
            bad(format!(
                "{} #{index} ends after {seen} values; expected a {} for {}",
                echo(name),
                type_name(ty),
                what()
            ))
        })?;
        seen += 1;
        let float = matches!(ty, ScalarType::Float | ScalarType::Double);
        if !(is_number(t) || float && is_non_finite(t)) {
            return Err(bad(format!(
                "'{}' is not a number ({}, declared {})",
                echo(t),
                what(),
                type_name(ty)
            )));
        }
        // The grammar admits ASCII only.
        Ok(std::str::from_utf8(t).unwrap_or(""))
    };
    for (p, (prop, def_p)) in def.properties.iter().enumerate() {
        let slot = wanted.keys.iter().position(|&k| k == Some(p));
        let what = || format!("property '{}' of {} #{index}", echo(prop), echo(name));
        match &def_p.data_type {
            PropertyType::Scalar(ty) => {
                let t = next(ty, prop)?;
                let x = scalar(t, ty, &what).map_err(bad)?;
                if let Some(s) = slot {
                    vals[s] = match ty {
                        // Checked by `scalar`; read again as an `f32` for an exact attribute.
                        ScalarType::Float if s >= wanted.extra_from => {
                            t.parse::<f32>().map_or(x, f64::from)
                        }
                        _ => x,
                    };
                }
            }
            PropertyType::List(count_ty, ty) => {
                let t = next(count_ty, prop)?;
                let count =
                    scalar(t, count_ty, &|| format!("list length of {}", what())).map_err(bad)?;
                if count < 0.0 || count.fract() != 0.0 {
                    return Err(bad(format!(
                        "list length '{t}' is not a count ({})",
                        what()
                    )));
                }
                for _ in 0..count as u64 {
                    let t = next(ty, prop)?;
                    let x = scalar(t, ty, &what).map_err(bad)?;
                    if slot.is_some() {
                        table::try_push(list, x)
                            .map_err(|b| (line, no_room("a list property's entries")(b)))?;
                    }
                }
            }
        }
    }
    if let Some(t) = toks.next() {
        let more = 1 + toks.count();
        return Err(bad(format!(
            "{} #{index} has {more} more value(s) than its properties declare ('{}' follows \
             the last of its {seen} values)",
            echo(name),
            echo(t)
        )));
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

/// The vertex coordinates, faces and edges of a body starting at line `first_line`: ASCII when
/// `binary` is `None`, else binary, big-endian when `Some(true)`.
pub(super) fn parse_body(
    header: &Header,
    header_text: &[u8],
    body: &[u8],
    first_line: usize,
    binary: Option<bool>,
    polygons: bool,
) -> Res<RawInput> {
    let mut records = match binary {
        None => Records::Text(Lines {
            rest: body,
            line: first_line,
        }),
        Some(big_endian) => Records::Binary {
            rest: body,
            big_endian,
        },
    };
    let mut kept = Kept::new(body.len(), binary.is_some());
    kept.declared = declarations(header_text);
    kept.raw.polygons.keep = polygons;
    for (name, def) in &header.elements {
        let wanted = kept.prepare(name, def)?;
        kept.read_elements(&mut records, name, def, &wanted)?;
    }
    kept.into_raw()
}

/// What a body keeps of its elements, filled element by element.
struct Kept {
    /// The faces (then the edges) as simplices.
    raw: RawInput,
    coords: Coords,
    /// Edges as pairs of ids, listed after the faces.
    edges: Vec<u32>,
    vertex_count: usize,
    /// The wanted scalar properties of the element being read.
    vals: Vec<f64>,
    /// The extra properties (attributes) read so far, and for the element being read the
    /// column of each of its extra properties (in key order after the named ones).
    columns: Vec<Column>,
    current: Vec<usize>,
    /// The slot in `vals` of the first extra property.
    extra_base: usize,
    /// Each property declaration of the header: element, property, line.
    declared: Vec<(String, String, u32)>,
    /// Each element that lists simplices: its name, part, entry count and extra properties.
    listers: Vec<(String, Part, usize, Vec<String>)>,
    /// The wanted list property's entries of the element being read.
    list: Vec<f64>,
    /// Elements any reservation may be made for: bounded by the bytes left.
    cap: usize,
    binary: bool,
}

impl Kept {
    fn new(body_len: usize, binary: bool) -> Kept {
        Kept {
            raw: RawInput::new(),
            coords: Coords {
                dim: 3,
                data: Vec::new(),
            },
            edges: Vec::new(),
            vertex_count: 0,
            vals: vec![0.0f64; 3],
            columns: Vec::new(),
            current: Vec::new(),
            extra_base: 0,
            declared: Vec::new(),
            listers: Vec::new(),
            list: Vec::new(),
            // Every element line takes at least 2 bytes (a binary element at least 1), so the
            // bytes left bound every reservation.
            cap: if binary {
                body_len + 1
            } else {
                body_len / 2 + 1
            },
            binary,
        }
    }

    /// The properties kept of element `name`, checked, and the room for its `def.count`
    /// entries reserved.
    fn prepare<'h>(&mut self, name: &str, def: &'h ElementDef) -> Res<Wanted<'h>> {
        let (w, part) = match name {
            "vertex" => (self.prepare_vertices(def)?, Part::Vertices),
            "face" | "tetra" | "tristrips" => (self.prepare_faces(name, def)?, Part::Faces),
            "edge" => (self.prepare_edges(def)?, Part::Edges),
            _ => return self.prepare_other(name, def),
        };
        self.prepare_extras(name, def, w, part)
    }

    /// The element's properties beyond coordinates and vertex ids, kept as attributes: each
    /// scalar one gets its column (created, or continued from an element of the same part and
    /// value type); a list one is refused.
    fn prepare_extras<'h>(
        &mut self,
        name: &str,
        def: &'h ElementDef,
        w: Wanted<'h>,
        part: Part,
    ) -> Res<Wanted<'h>> {
        let mut extras = Vec::new();
        self.current.clear();
        let mut names = Vec::new();
        for (p, (prop, pdef)) in def.properties.iter().enumerate() {
            if w.keys.contains(&Some(p)) {
                continue;
            }
            let ty = match &pdef.data_type {
                PropertyType::Scalar(ty) => value_type(ty),
                PropertyType::List(..) => {
                    return Err((
                        line_of(&self.declared, name, prop),
                        syntax(format!(
                            "PLY: property '{}' of element '{}' is a list; Topoplex keeps a list \
                         only as the vertex ids, and refuses it rather than dropping it",
                            echo(prop),
                            echo(name)
                        )),
                    ));
                }
            };
            let col = match self
                .columns
                .iter()
                .position(|c| c.part == part && c.name == *prop)
            {
                Some(k) if self.columns[k].values.value_type() != ty => {
                    return Err((
                        line_of(&self.declared, name, prop),
                        syntax(format!(
                            "PLY: property '{}' of element '{}' is {}, but an element before it \
                         lists simplices with it as {}; an attribute has one type",
                            echo(prop),
                            echo(name),
                            ty.name(),
                            self.columns[k].values.value_type().name()
                        )),
                    ));
                }
                Some(k) => k,
                None => {
                    self.columns.push(Column {
                        name: prop.clone(),
                        element: name.to_string(),
                        part,
                        values: empty_values(ty),
                    });
                    self.columns.len() - 1
                }
            };
            extras.push(p);
            self.current.push(col);
            names.push(prop.clone());
        }
        if part != Part::Vertices {
            self.listers
                .push((name.to_string(), part, def.count, names));
        }
        let w = w.with_extras(&extras);
        self.vals.resize(w.keys.len().max(3), 0.0);
        self.extra_base = w.extra_from;
        Ok(w)
    }

    /// An element Topoplex does not read: refused when it lists vertex ids, else ignored.
    fn prepare_other<'h>(&mut self, name: &str, def: &'h ElementDef) -> Res<Wanted<'h>> {
        self.current.clear();
        // An element that lists vertex ids but is none of the above would be dropped.
        let ids = ["vertex_indices", "vertex_index", "vertex1", "vertex2"];
        if def.count > 0
            && let Some((p, _)) = def
                .properties
                .iter()
                .find(|(k, _)| ids.contains(&k.as_str()))
        {
            return Err(at0(syntax(format!(
                "PLY: element '{}' has a '{}' property (vertex ids) but is not an element \
                 Topoplex reads (vertex, face, edge, tetra, tristrips); refusing it rather \
                 than dropping its {} entries",
                echo(name),
                echo(p),
                def.count
            ))));
        }
        Ok(Wanted::new(def, &[]))
    }

    /// `x`, `y` and (for 3 coordinates) `z`, which must be scalars.
    fn prepare_vertices<'h>(&mut self, def: &'h ElementDef) -> Res<Wanted<'h>> {
        let w = Wanted::new(def, &[&["x"], &["y"], &["z"]]);
        self.coords.dim = if w.keys[2].is_some() || def.count == 0 {
            3
        } else {
            2
        };
        self.vertex_count = def.count;
        if def.count > 0 {
            for (k, key) in ["x", "y", "z"][..self.coords.dim].iter().enumerate() {
                need_scalar(&w, k, "vertex #0", key)?;
            }
        }
        self.coords.data = try_with_capacity(
            def.count.min(self.cap) * self.coords.dim,
            "the vertex coordinates",
        )
        .map_err(at0)?;
        Ok(w)
    }

    /// `vertex_indices` (or `vertex_index`) of a `face`, `tetra` or `tristrips` element, which
    /// must be a list of integers.
    fn prepare_faces<'h>(&mut self, name: &str, def: &'h ElementDef) -> Res<Wanted<'h>> {
        let w = Wanted::new(def, &[&["vertex_indices", "vertex_index"]]);
        match w.keys[0].map(|p| &def.properties[p].data_type) {
            _ if def.count == 0 => {}
            None => return Err(at0(syntax(format!("{name} #0 has no vertex_indices list")))),
            Some(PropertyType::List(_, ScalarType::Float | ScalarType::Double))
            | Some(PropertyType::Scalar(_)) => {
                return Err(at0(syntax(format!(
                    "{name} #0: vertex_indices is not a list of integers"
                ))));
            }
            Some(PropertyType::List(..)) => {}
        }
        self.raw
            .try_reserve(def.count.min(self.cap), 0)
            .map_err(at0)?;
        Ok(w)
    }

    /// `vertex1` and `vertex2`, which must be scalars.
    fn prepare_edges<'h>(&mut self, def: &'h ElementDef) -> Res<Wanted<'h>> {
        let w = Wanted::new(def, &[&["vertex1"], &["vertex2"]]);
        if def.count > 0 {
            need_scalar(&w, 0, "edge #0", "vertex1")?;
            need_scalar(&w, 1, "edge #0", "vertex2")?;
        }
        self.edges = try_with_capacity(def.count.min(self.cap) * 2, "the edges").map_err(at0)?;
        Ok(w)
    }

    /// The `def.count` entries of element `name` from `records`, each kept as [`Kept::keep`]
    /// says.
    fn read_elements(
        &mut self,
        records: &mut Records,
        name: &str,
        def: &ElementDef,
        wanted: &Wanted,
    ) -> Res<()> {
        for i in 0..def.count {
            self.list.clear();
            let read = match records {
                Records::Text(lines) => match lines.next_line() {
                    Some((l, n)) => {
                        read_line(l, n, name, i, def, wanted, &mut self.vals, &mut self.list)
                            .map(|()| 0)
                    }
                    None => Ok(u32::try_from(lines.line).unwrap_or(u32::MAX)),
                },
                Records::Binary { rest, big_endian } => read_binary(
                    rest,
                    *big_endian,
                    def,
                    wanted,
                    &mut self.vals,
                    &mut self.list,
                )
                .map(|full| if full { 0 } else { u32::MAX }),
            };
            // `Ok(0)`: read; else the line to blame for the end of the data.
            match read? {
                0 => {}
                line => return Err(self.ended(line, name, def.count, i)),
            }
            self.keep(name, i)?;
        }
        Ok(())
    }

    /// The error for data that end at entry `i` of the `count` of element `name` (`line`: the
    /// text line to blame).
    #[cold]
    fn ended(&self, line: u32, name: &str, count: usize, i: usize) -> (u32, ReadErrorKind) {
        let line = if self.binary { 0 } else { line };
        (
            line,
            syntax(format!(
                "PLY: Unexpected end of file while reading element '{}' (expected {count}, got {i}).",
                echo(name),
            )),
        )
    }

    /// Entry `i` of element `name`, just read into `vals` and `list`, kept.
    #[inline]
    fn keep(&mut self, name: &str, i: usize) -> Res<()> {
        let before = self.raw.simplex_count();
        self.keep_simplices(name, i)?;
        if self.current.is_empty() {
            return Ok(());
        }
        // One row per vertex or edge, per simplex for faces (a strip's triangles share its).
        let rows = match name {
            "vertex" | "edge" => 1,
            _ => self.raw.simplex_count() - before,
        };
        let base = self.extra_base;
        for (j, &c) in self.current.iter().enumerate() {
            let x = self.vals[base + j];
            let col = &mut self.columns[c];
            for _ in 0..rows {
                push_value(&mut col.values, x).map_err(|b| at0(no_room("a property")(b)))?;
            }
        }
        Ok(())
    }

    /// Entry `i` of element `name`, its coordinates or simplices kept.
    #[inline]
    fn keep_simplices(&mut self, name: &str, i: usize) -> Res<()> {
        match name {
            "vertex" => table::try_extend(&mut self.coords.data, &self.vals[..self.coords.dim])
                .map_err(|b| at0(no_room("the vertex coordinates")(b)))?,
            "face" => push_face(&mut self.raw, &self.list, i)?,
            "tetra" => push_tetra(&mut self.raw, &self.list, i)?,
            "tristrips" => push_strips(&mut self.raw, &self.list, i)?,
            "edge" => {
                for x in [self.vals[0], self.vals[1]] {
                    let v = id_of(x, "")
                        .map_err(|_| at0(id_of(x, &format!("edge #{i}")).unwrap_err()))?;
                    table::try_push(&mut self.edges, v)
                        .map_err(|b| at0(no_room("the edges")(b)))?;
                }
            }
            _ => {}
        }
        Ok(())
    }

    /// The faces, then the edges, with the vertex count and coordinates.
    fn into_raw(self) -> Res<RawInput> {
        let Kept {
            mut raw,
            coords,
            edges,
            vertex_count,
            columns,
            listers,
            declared,
            ..
        } = self;
        let faces = raw.simplex_count();
        raw.vertex_count =
            Some(u32::try_from(vertex_count).map_err(|_| at0(syntax("more than 2^32 vertices")))?);
        raw.coords = Some(coords);
        // Faces come before edges in the listing, whatever the elements' order.
        raw.try_reserve(edges.len() / 2, edges.len()).map_err(at0)?;
        for e in edges.chunks_exact(2) {
            raw.push(e, 0);
        }
        attributes(
            &mut raw,
            columns,
            &listers,
            &declared,
            faces + edges.len() / 2,
        )?;
        Ok(raw)
    }
}

/// Each `property` line of a header (`header`: its bytes, from `ply` on): the element it is
/// in, its name, its line (1-based).
fn declarations(header: &[u8]) -> Vec<(String, String, u32)> {
    let mut out = Vec::new();
    let mut element = String::new();
    for (i, l) in header.split(|&c| c == b'\n').enumerate() {
        let l = String::from_utf8_lossy(l);
        let words: Vec<&str> = l.split_whitespace().collect();
        match words.as_slice() {
            ["element", name, ..] => element = (*name).to_string(),
            ["property", .., name] => out.push((
                element.clone(),
                (*name).to_string(),
                u32::try_from(i + 1).unwrap_or(u32::MAX),
            )),
            _ => {}
        }
    }
    out
}

/// The header line declaring property `prop` of element `element` (0 when not found).
fn line_of(declared: &[(String, String, u32)], element: &str, prop: &str) -> u32 {
    declared
        .iter()
        .find(|(e, p, _)| e == element && p == prop)
        .map_or(0, |d| d.2)
}

/// Which part of the listing an element's entries make (vertices are not listed).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Part {
    Vertices,
    /// `face`, `tetra`, `tristrips`: listed first.
    Faces,
    /// `edge`: listed after the faces.
    Edges,
}

/// The values of one extra property over one part, in reading order.
struct Column {
    name: String,
    /// The first element that has it, for messages.
    element: String,
    part: Part,
    values: Values,
}

/// The attribute type a PLY scalar type is kept as: every integer type up to `int` as `i32`,
/// `uint` as `i64`, `float` as `f32`, `double` as `f64` (exact).
fn value_type(ty: &ScalarType) -> ValueType {
    match ty {
        ScalarType::Char
        | ScalarType::UChar
        | ScalarType::Short
        | ScalarType::UShort
        | ScalarType::Int => ValueType::I32,
        ScalarType::UInt => ValueType::I64,
        ScalarType::Float => ValueType::F32,
        ScalarType::Double => ValueType::F64,
    }
}

fn empty_values(ty: ValueType) -> Values {
    match ty {
        ValueType::I32 => Values::I32(Vec::new()),
        ValueType::I64 => Values::I64(Vec::new()),
        ValueType::F32 => Values::F32(Vec::new()),
        ValueType::F64 => Values::F64(Vec::new()),
    }
}

/// Appends `x` (a value of the column's PLY type, so exact in it) to `v`.
fn push_value(v: &mut Values, x: f64) -> Result<(), usize> {
    match v {
        Values::I32(v) => table::try_push(v, x as i32),
        Values::I64(v) => table::try_push(v, x as i64),
        Values::F32(v) => table::try_push(v, x as f32),
        Values::F64(v) => table::try_push(v, x),
    }
}

/// The columns as attributes of `raw`: vertex ones as they are, and for each property of the
/// listing elements its face part then its edge part, one value per listed simplex; a property
/// some listing element (with entries) lacks is refused, naming it and the element.
fn attributes(
    raw: &mut RawInput,
    columns: Vec<Column>,
    listers: &[(String, Part, usize, Vec<String>)],
    declared: &[(String, String, u32)],
    listed_count: usize,
) -> Res<()> {
    let mut listed: Vec<Column> = Vec::new();
    for c in columns {
        if c.part == Part::Vertices {
            raw.attributes.insert(Attribute {
                name: c.name,
                location: Location::Vertices,
                components: 1,
                values: c.values,
            });
        } else {
            listed.push(c);
        }
    }
    // Face parts first (the listing's order), each followed by its edge part.
    listed.sort_by_key(|c| c.part == Part::Edges);
    let mut done: Vec<String> = Vec::new();
    for k in 0..listed.len() {
        let name = listed[k].name.clone();
        if done.contains(&name) {
            continue;
        }
        if let Some((lister, ..)) = listers
            .iter()
            .find(|(_, _, count, props)| *count > 0 && !props.contains(&name))
        {
            let line = line_of(declared, &listed[k].element, &name);
            return Err((
                line,
                syntax(format!(
                    "PLY: property '{}' of element '{}' is not on element '{}', which lists \
                 simplices too; an attribute has a value for every listed simplex, so it is \
                 refused rather than padded",
                    echo(&name),
                    echo(&listed[k].element),
                    echo(lister)
                )),
            ));
        }
        let mut values = listed[k].values.empty_like();
        for c in listed.iter().filter(|c| c.name == name) {
            if let Some(other) = listed
                .iter()
                .find(|o| o.name == name && o.values.value_type() != c.values.value_type())
            {
                let line = line_of(declared, &other.element, &name);
                return Err((
                    line,
                    syntax(format!(
                        "PLY: property '{}' is {} on element '{}' and {} on element '{}'; an \
                     attribute has one type",
                        echo(&name),
                        c.values.value_type().name(),
                        echo(&c.element),
                        other.values.value_type().name(),
                        echo(&other.element)
                    )),
                ));
            }
            values.append(&c.values);
        }
        debug_assert_eq!(values.len(), listed_count);
        raw.attributes.insert(Attribute {
            name: name.clone(),
            location: Location::Listed,
            components: 1,
            values,
        });
        done.push(name);
    }
    Ok(())
}

/// An error at no particular line (line 0).
fn at0(k: ReadErrorKind) -> (u32, ReadErrorKind) {
    (0, k)
}

/// Face `i` with ids `list` as a simplex of `raw`.
fn push_face(raw: &mut RawInput, list: &[f64], i: usize) -> Res<()> {
    let what = || format!("face #{i}");
    let mut ids = [0u32; 3];
    // A polygon kept for --triangulate: every id.
    let mut polygon = Vec::new();
    let keep = raw.polygons.keep && list.len() > 3;
    for (k, &x) in list.iter().enumerate() {
        let v = id_of(x, "").map_err(|_| at0(id_of(x, &what()).unwrap_err()))?;
        if k < 3 {
            ids[k] = v;
        }
        if keep {
            table::try_push(&mut polygon, v).map_err(|b| at0(no_room("a polygon's ids")(b)))?;
        }
    }
    match list.len() {
        0 => Err(at0(syntax(format!("face #{i} has no vertex")))),
        1..=3 => raw.try_push(&ids[..list.len()], 0).map_err(at0),
        k => raw
            .try_push_polygon(&polygon, 0, ReadErrorKind::Polygon(k))
            .map_err(|e| at0(syntax(format!("face #{i}: {e}")))),
    }
}

/// Tetra `i` with ids `list` as a tetrahedron of `raw`: exactly 4 ids.
fn push_tetra(raw: &mut RawInput, list: &[f64], i: usize) -> Res<()> {
    let what = || format!("tetra #{i}");
    if list.len() != 4 {
        return Err(at0(syntax(format!(
            "tetra #{i} has {} vertex ids; a tetra element lists 4",
            list.len()
        ))));
    }
    let mut ids = [0u32; 4];
    for (v, &x) in ids.iter_mut().zip(list) {
        *v = id_of(x, "").map_err(|_| at0(id_of(x, &what()).unwrap_err()))?;
    }
    raw.try_push(&ids, 0).map_err(at0)
}

/// Tristrips entry `i` as triangles of `raw`: its `vertex_indices` list holds strips separated
/// by -1, and every 3 consecutive ids of a strip are a triangle (orientation, which alternates
/// along a strip, is not kept: simplices are vertex sets). A triangle of a strip that repeats
/// a vertex is a degenerate join between strips (the way writers stitch strips without -1)
/// and is not a simplex, so it is skipped; a strip of 1 or 2 ids makes no triangle and is
/// refused.
fn push_strips(raw: &mut RawInput, list: &[f64], i: usize) -> Res<()> {
    let what = || format!("tristrips #{i}");
    let mut strip = [0u32; 2];
    let mut len = 0usize;
    let mut strip_index = 0usize;
    let short = |len: usize, k: usize| {
        at0(syntax(format!(
            "tristrips #{i}: strip #{k} has {len} vertex ids; a strip needs at least 3"
        )))
    };
    for &x in list {
        if x == -1.0 {
            if len < 3 {
                return Err(short(len, strip_index));
            }
            len = 0;
            strip_index += 1;
            continue;
        }
        let v = id_of(x, "").map_err(|_| at0(id_of(x, &what()).unwrap_err()))?;
        if len >= 2 {
            let t = [strip[0], strip[1], v];
            if t[0] != t[1] && t[1] != t[2] && t[0] != t[2] {
                raw.try_push(&t, 0).map_err(at0)?;
            }
            strip = [strip[1], v];
        } else {
            strip[len] = v;
        }
        len += 1;
    }
    if len < 3 && (len > 0 || strip_index == 0) {
        return Err(short(len, strip_index));
    }
    Ok(())
}
