//! The point and cell data of `.vtu` pieces (`<PointData>`, `<CellData>` data arrays), kept as
//! attributes ([`crate::complex::attributes`]) named by the array's `Name`: point data on
//! [`Location::Vertices`], cell data on [`Location::Listed`] (cells are listed in file order).
//!
//! Types are kept exactly: `Int8`, `UInt8`, `Int16`, `UInt16`, `Int32` as `i32`; `UInt32`,
//! `Int64`, `UInt64` as `i64` (a `UInt64` above 2^63 is an error); `Float32` as `f32`; `Float64`
//! as `f64`. `NumberOfComponents` 1 to [`MAX_COMPONENTS`]. Any other type (`String`, `Bit`...)
//! is refused naming the array and its line, never skipped (vtkio would read a `String` array
//! as `Float64`: [`scan`] checks every declaration before vtkio sees the file).
//!
//! Pieces concatenate: every piece must carry the same arrays (same name, type class and
//! components); an array one piece lacks is an error naming it. Storage: the values only,
//! appended in place as each piece is read (one vector per array, grown fallibly).

use quick_xml::Reader;
use quick_xml::events::{BytesStart, Event};
use vtkio::model::IOBuffer;

use super::super::{ReadErrorKind, echo, no_room, parse_f64, parse_integer, syntax};
use crate::complex::attributes::MAX_COMPONENTS;
use crate::complex::{Attribute, Attributes, Location, Values, table};

/// The number type of a point or cell data array, as VTK XML names it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Kind {
    I8,
    U8,
    I16,
    U16,
    I32,
    U32,
    I64,
    U64,
    F32,
    F64,
}

impl Kind {
    const ALL: [(Kind, &'static str); 10] = [
        (Kind::I8, "Int8"),
        (Kind::U8, "UInt8"),
        (Kind::I16, "Int16"),
        (Kind::U16, "UInt16"),
        (Kind::I32, "Int32"),
        (Kind::U32, "UInt32"),
        (Kind::I64, "Int64"),
        (Kind::U64, "UInt64"),
        (Kind::F32, "Float32"),
        (Kind::F64, "Float64"),
    ];

    fn of(ty: &[u8]) -> Option<Kind> {
        Kind::ALL
            .iter()
            .find(|(_, n)| n.as_bytes() == ty)
            .map(|&(k, _)| k)
    }

    fn name(self) -> &'static str {
        Kind::ALL
            .iter()
            .find(|(k, _)| *k == self)
            .map_or("", |x| x.1)
    }

    /// The kind of a buffer vtkio read.
    fn of_buffer(b: &IOBuffer) -> Option<Kind> {
        Some(match b {
            IOBuffer::I8(_) => Kind::I8,
            IOBuffer::U8(_) => Kind::U8,
            IOBuffer::I16(_) => Kind::I16,
            IOBuffer::U16(_) => Kind::U16,
            IOBuffer::I32(_) => Kind::I32,
            IOBuffer::U32(_) => Kind::U32,
            IOBuffer::I64(_) => Kind::I64,
            IOBuffer::U64(_) => Kind::U64,
            IOBuffer::F32(_) => Kind::F32,
            IOBuffer::F64(_) => Kind::F64,
            IOBuffer::Bit(_) => return None,
        })
    }

    /// The (empty) values it is kept in.
    fn values(self) -> Values {
        match self {
            Kind::I8 | Kind::U8 | Kind::I16 | Kind::U16 | Kind::I32 => Values::I32(Vec::new()),
            Kind::U32 | Kind::I64 | Kind::U64 => Values::I64(Vec::new()),
            Kind::F32 => Values::F32(Vec::new()),
            Kind::F64 => Values::F64(Vec::new()),
        }
    }

    /// The range of an integer kind.
    fn range(self) -> (i128, i128) {
        match self {
            Kind::I8 => (i8::MIN.into(), i8::MAX.into()),
            Kind::U8 => (0, u8::MAX.into()),
            Kind::I16 => (i16::MIN.into(), i16::MAX.into()),
            Kind::U16 => (0, u16::MAX.into()),
            Kind::I32 => (i32::MIN.into(), i32::MAX.into()),
            Kind::U32 => (0, u32::MAX.into()),
            Kind::I64 => (i64::MIN.into(), i64::MAX.into()),
            // Kept as i64: above 2^63 is refused.
            Kind::U64 => (0, i64::MAX.into()),
            Kind::F32 | Kind::F64 => (0, 0),
        }
    }
}

/// `point data` or `cell data`.
pub(super) fn section(location: Location) -> &'static str {
    match location {
        Location::Vertices => "point data",
        Location::Listed => "cell data",
    }
}

/// A data array's declaration checked: its `Name`, kind and components (the message names the
/// array and what is wrong).
pub(super) fn declared(
    location: Location,
    name: Option<&str>,
    ty: Option<&[u8]>,
    components: Option<&[u8]>,
) -> Result<(String, Kind, usize), String> {
    let s = section(location);
    let name = match name {
        Some(n) if !n.is_empty() => n.to_string(),
        _ => return Err(format!("a {s} array has no Name (an attribute needs one)")),
    };
    let e = echo(&name);
    let kind = match ty {
        None => return Err(format!("{s} array '{e}' has no type")),
        Some(t) => Kind::of(t).ok_or_else(|| {
            format!(
                "{s} array '{e}' has type '{}', which is not a number type (Int8 to UInt64, \
                 Float32 and Float64 are read)",
                echo(t)
            )
        })?,
    };
    let components = match components {
        None => 1,
        Some(c) => checked_components(location, &name, c)?,
    };
    Ok((name, kind, components))
}

/// A `NumberOfComponents` value checked: 1 to [`MAX_COMPONENTS`].
pub(super) fn checked_components(
    location: Location,
    name: &str,
    text: &[u8],
) -> Result<usize, String> {
    std::str::from_utf8(text)
        .ok()
        .and_then(|c| c.trim().parse::<usize>().ok())
        .filter(|c| (1..=MAX_COMPONENTS).contains(c))
        .ok_or_else(|| {
            format!(
                "{} array '{}' has NumberOfComponents=\"{}\"; 1 to {MAX_COMPONENTS} are held",
                section(location),
                echo(name),
                echo(text)
            )
        })
}

/// One array being filled: the attribute, the kind of the current piece's declaration, the
/// pieces it was seen in, and its length when the current piece's array started.
struct Array {
    attr: Attribute,
    kind: Kind,
    pieces: usize,
    start: usize,
}

/// The point and cell data of the pieces read so far, concatenated.
#[derive(Default)]
pub(super) struct Data {
    arrays: Vec<Array>,
}

impl Data {
    /// Array `name` at `location` starts in piece `piece`: its index. The first piece declares
    /// the arrays; the others must declare the same (same value type and components), once.
    pub(super) fn open(
        &mut self,
        piece: usize,
        location: Location,
        name: String,
        kind: Kind,
        components: usize,
    ) -> Result<usize, String> {
        let s = section(location);
        let found = self
            .arrays
            .iter()
            .position(|a| a.attr.location == location && a.attr.name == name);
        let i = match found {
            Some(i) => {
                let a = &mut self.arrays[i];
                if a.pieces > piece {
                    return Err(format!(
                        "piece {piece}: a second {s} array named '{}'",
                        echo(&name)
                    ));
                }
                if a.attr.components != components
                    || a.attr.values.value_type() != kind.values().value_type()
                {
                    return Err(format!(
                        "piece {piece}: {s} array '{}' is {} × {components}, but {} × {} in \
                         piece 0",
                        echo(&name),
                        kind.name(),
                        a.kind.name(),
                        a.attr.components
                    ));
                }
                i
            }
            None if piece > 0 => {
                return Err(format!(
                    "piece {piece} has {s} array '{}', which piece 0 lacks (every piece needs \
                     the same arrays)",
                    echo(&name)
                ));
            }
            None => {
                self.arrays.push(Array {
                    attr: Attribute {
                        name,
                        location,
                        components,
                        values: kind.values(),
                    },
                    kind,
                    pieces: 0,
                    start: 0,
                });
                self.arrays.len() - 1
            }
        };
        let a = &mut self.arrays[i];
        a.kind = kind;
        a.pieces = piece + 1;
        a.start = a.attr.values.len();
        Ok(i)
    }

    /// Room for up to `n` more numbers of array `i`.
    pub(super) fn reserve(&mut self, i: usize, n: usize) -> Result<(), ReadErrorKind> {
        let room = no_room("an attribute's values");
        match &mut self.arrays[i].attr.values {
            Values::I32(v) => table::try_reserve_exact(v, n).map_err(room),
            Values::I64(v) => table::try_reserve_exact(v, n).map_err(room),
            Values::F32(v) => table::try_reserve_exact(v, n).map_err(room),
            Values::F64(v) => table::try_reserve_exact(v, n).map_err(room),
        }
    }

    /// One number of array `i`, as written in an ASCII array.
    pub(super) fn push_token(&mut self, i: usize, tok: &str) -> Result<(), ReadErrorKind> {
        let a = &mut self.arrays[i];
        let (kind, location) = (a.kind, a.attr.location);
        let what = || {
            format!(
                "the values of {} array '{}'",
                section(location),
                echo(&a.attr.name)
            )
        };
        let room = no_room("an attribute's values");
        // The array is named only when a number is refused (nothing formatted per number).
        let real = |tok: &str| {
            parse_f64(tok, "a data value").map_err(|e| match e {
                ReadErrorKind::Syntax(m) => syntax(format!("{m} among {}", what())),
                e => e,
            })
        };
        match &mut a.attr.values {
            Values::F64(v) => {
                let x = real(tok)?;
                table::try_push(v, x).map_err(room)
            }
            Values::F32(v) => {
                let wide = real(tok)?;
                let x = tok.parse::<f32>().unwrap_or(wide as f32);
                if wide.is_finite() && !x.is_finite() {
                    return Err(syntax(format!(
                        "'{}' overflows Float32 among {}",
                        echo(tok),
                        what()
                    )));
                }
                table::try_push(v, x).map_err(room)
            }
            values => {
                let x = parse_integer(tok).map_err(|_| {
                    syntax(format!(
                        "'{}' is not of type {} among {}",
                        echo(tok),
                        kind.name(),
                        what()
                    ))
                })?;
                let (lo, hi) = kind.range();
                if x < lo || x > hi {
                    return Err(syntax(format!(
                        "'{}' does not fit {} among {}{}",
                        echo(tok),
                        kind.name(),
                        what(),
                        if kind == Kind::U64 {
                            " (a UInt64 above 2^63 cannot be held)"
                        } else {
                            ""
                        }
                    )));
                }
                match values {
                    Values::I32(v) => table::try_push(v, x as i32).map_err(room),
                    Values::I64(v) => table::try_push(v, x as i64).map_err(room),
                    _ => Ok(()),
                }
            }
        }
    }

    /// The numbers vtkio read for array `i`, appended in their own type.
    pub(super) fn extend(&mut self, i: usize, buf: IOBuffer) -> Result<(), String> {
        fn widen<T: Copy, U>(
            v: &mut Vec<U>,
            xs: &[T],
            f: impl Fn(T) -> Option<U>,
        ) -> Result<(), String> {
            table::try_reserve_exact(v, xs.len())
                .map_err(|b| no_room("an attribute's values")(b).to_string())?;
            for &x in xs {
                v.push(f(x).ok_or("a UInt64 above 2^63 cannot be held")?);
            }
            Ok(())
        }
        let a = &mut self.arrays[i];
        let what = format!(
            "{} array '{}'",
            section(a.attr.location),
            echo(&a.attr.name)
        );
        let r = match (&mut a.attr.values, &buf) {
            (Values::I32(v), IOBuffer::I8(x)) => widen(v, x, |x| Some(i32::from(x))),
            (Values::I32(v), IOBuffer::U8(x)) => widen(v, x, |x| Some(i32::from(x))),
            (Values::I32(v), IOBuffer::I16(x)) => widen(v, x, |x| Some(i32::from(x))),
            (Values::I32(v), IOBuffer::U16(x)) => widen(v, x, |x| Some(i32::from(x))),
            (Values::I32(v), IOBuffer::I32(x)) => widen(v, x, Some),
            (Values::I64(v), IOBuffer::U32(x)) => widen(v, x, |x| Some(i64::from(x))),
            (Values::I64(v), IOBuffer::I64(x)) => widen(v, x, Some),
            (Values::I64(v), IOBuffer::U64(x)) => widen(v, x, |x| i64::try_from(x).ok()),
            (Values::F32(v), IOBuffer::F32(x)) => widen(v, x, Some),
            (Values::F64(v), IOBuffer::F64(x)) => widen(v, x, Some),
            _ => Err("its type differs between pieces".to_string()),
        };
        r.map_err(|m| format!("{what}: {m}"))
    }

    /// Array `i` closed in piece `piece`, whose elements (points or cells) number `elements`:
    /// its count checked.
    pub(super) fn close(&self, i: usize, piece: usize, elements: usize) -> Result<(), String> {
        let a = &self.arrays[i];
        let n = a.attr.values.len() - a.start;
        let want = elements.saturating_mul(a.attr.components);
        (n == want).then_some(()).ok_or_else(|| {
            format!(
                "piece {piece}: {} array '{}' has {n} numbers, expected {elements} × {} = {want}",
                section(a.attr.location),
                echo(&a.attr.name),
                a.attr.components
            )
        })
    }

    /// Piece `piece` ended: every array of the pieces before must have been in it.
    pub(super) fn end_piece(&self, piece: usize) -> Result<(), String> {
        match self.arrays.iter().find(|a| a.pieces != piece + 1) {
            None => Ok(()),
            Some(a) => Err(format!(
                "piece {piece} lacks {} array '{}', which piece 0 has (every piece needs the \
                 same arrays)",
                section(a.attr.location),
                echo(&a.attr.name)
            )),
        }
    }

    /// The arrays as attributes, in file order.
    pub(super) fn into_attributes(self, into: &mut Attributes) {
        for a in self.arrays {
            into.insert(a.attr);
        }
    }

    /// The kind of a buffer vtkio read (`None`: a bit array, not held).
    pub(super) fn buffer_kind(b: &IOBuffer) -> Option<Kind> {
        Kind::of_buffer(b)
    }
}

/// Where the data arrays of a file stand: each array's `(piece, location, name)` with the line
/// of its `DataArray` tag, and each piece's line (for the vtkio path's messages).
#[derive(Default)]
pub(super) struct Lines {
    arrays: Vec<(usize, Location, String, u32)>,
    pieces: Vec<u32>,
}

impl Lines {
    /// The line of an array (0: unknown).
    pub(super) fn array(&self, piece: usize, location: Location, name: &str) -> u32 {
        self.arrays
            .iter()
            .find(|a| a.0 == piece && a.1 == location && a.2 == name)
            .map_or(0, |a| a.3)
    }

    /// The line of a piece's tag (0: unknown).
    pub(super) fn piece(&self, piece: usize) -> u32 {
        self.pieces.get(piece).copied().unwrap_or(0)
    }
}

/// The declarations of every point and cell data array before `AppendedData`, checked as
/// [`declared`] does (the error carries the line of the `DataArray` tag). An XML error ends
/// the scan quietly: vtkio reports it.
pub(super) fn scan(bytes: &[u8]) -> Result<Lines, (u32, ReadErrorKind)> {
    let mut xml = Reader::from_reader(bytes);
    let mut lines = Lines::default();
    let (mut counted, mut line) = (0usize, 1u32);
    let mut at: Option<Location> = None;
    let mut field = false;
    let mut line_at = |pos: usize| {
        let pos = pos.min(bytes.len());
        if pos > counted {
            let n = memchr::memchr_iter(b'\n', &bytes[counted..pos]).count();
            line = line.saturating_add(u32::try_from(n).unwrap_or(u32::MAX));
            counted = pos;
        }
        line
    };
    loop {
        let pos = xml.buffer_position() as usize;
        let (e, empty) = match xml.read_event() {
            Ok(Event::Start(e)) => (e, false),
            Ok(Event::Empty(e)) => (e, true),
            Ok(Event::End(e)) => {
                if matches!(e.local_name().as_ref(), b"PointData" | b"CellData") {
                    at = None;
                }
                field &= e.local_name().as_ref() != b"FieldData";
                continue;
            }
            Ok(Event::Eof) | Err(_) => break,
            Ok(_) => continue,
        };
        match e.local_name().as_ref() {
            b"AppendedData" => {
                let encoding = e.try_get_attribute("encoding").ok().flatten();
                if encoding.is_some_and(|a| a.value.as_ref() != b"base64") {
                    return Err((
                        line_at(pos),
                        syntax(
                            "<AppendedData> not base64-encoded (encoding=\"raw\"): not read \
                             (the VTU decoder here takes base64 only); write it with base64 \
                             appended data (VTK: SetEncodeAppendedData(1)), inline binary or ASCII",
                        ),
                    ));
                }
                break;
            }
            b"FieldData" if !empty => field = true,
            b"Piece" => lines.pieces.push(line_at(pos)),
            b"PointData" if !empty => at = Some(Location::Vertices),
            b"CellData" if !empty => at = Some(Location::Listed),
            b"DataArray" => {
                if field {
                    let name = e.try_get_attribute("Name").ok().flatten();
                    let name = name.map(|a| String::from_utf8_lossy(&a.value).into_owned());
                    return Err((line_at(pos), syntax(field_data(&name.unwrap_or_default()))));
                }
                if let Some(location) = at {
                    let l = line_at(pos);
                    let (name, _, _) = declaration(&e, location).map_err(|m| (l, syntax(m)))?;
                    let piece = lines.pieces.len().saturating_sub(1);
                    lines.arrays.push((piece, location, name, l));
                }
            }
            _ => {}
        }
    }
    Ok(lines)
}

/// The refusal of a `<FieldData>` array `name`: data on the whole mesh, which the model has no
/// place for (attributes are on the vertices and the listed simplices), refused rather than
/// dropped.
pub(super) fn field_data(name: &str) -> String {
    format!(
        "<FieldData> array '{}': data on the whole mesh, which Topoplex's attributes (on the \
         vertices and the listed simplices) cannot hold; refused rather than dropped (remove it, \
         or move it to PointData or CellData)",
        crate::error::echo(name)
    )
}

/// [`declared`] on a `DataArray` tag's attributes (its `Name` unescaped).
pub(super) fn declaration(
    e: &BytesStart,
    location: Location,
) -> Result<(String, Kind, usize), String> {
    let raw = |name: &str| {
        e.try_get_attribute(name)
            .ok()
            .flatten()
            .map(|a| a.value.into_owned())
    };
    let name = e.try_get_attribute("Name").ok().flatten().map(|a| {
        a.unescape_value()
            .map(|v| v.into_owned())
            .unwrap_or_else(|_| String::from_utf8_lossy(&a.value).into_owned())
    });
    declared(
        location,
        name.as_deref(),
        raw("type").as_deref(),
        raw("NumberOfComponents").as_deref(),
    )
}
