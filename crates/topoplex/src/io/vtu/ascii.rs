//! Our streaming reader of `.vtu` files whose data arrays are all `format="ascii"`: quick-xml
//! events over the file's bytes, numbers parsed straight from each array's text into the output
//! arrays (no copy of the text, no typed intermediate arrays), so that reading peaks near the
//! file plus its output rather than at vtkio's 5.9× (docs/benchmarks.md, "Reading").
//!
//! A file this reader does not take (no `VTKFile` of type `UnstructuredGrid`, a binary or
//! appended array, an `AppendedData` section, or an XML error before any array was read) is
//! handed back ([`Taken::No`]) to the vtkio path, so those files read and fail as before.
//! Errors found after an array started carry the line; the cell types and messages are the
//! vtkio path's.

use quick_xml::Reader;
use quick_xml::events::{BytesStart, Event};

use super::super::{Coords, RawInput, ReadErrorKind, capped_len, echo, no_room, syntax};
use super::super::{Float, parse_real};
use super::super::{check_integer, parse_count, parse_f64, parse_id};
use super::data::{self, Data};
use crate::complex::{Location, table};
use crate::io::Res;

/// What [`parse`] did with a file.
pub(super) enum Taken {
    /// Read by this module.
    Yes(RawInput),
    /// Not this module's (binary arrays, another data set...): the vtkio path reads it.
    No,
}

/// Why reading stopped.
enum Stop {
    /// Hand the file to vtkio.
    Vtkio,
    /// A refusal: line (0: unknown) and what is wrong.
    Err(u32, ReadErrorKind),
}

impl From<(u32, ReadErrorKind)> for Stop {
    fn from((line, kind): (u32, ReadErrorKind)) -> Stop {
        Stop::Err(line, kind)
    }
}

/// The number type of the points' data array.
#[derive(Clone, Copy)]
enum Real {
    F32,
    F64,
    Int,
}

/// Which array a `DataArray`'s text fills.
#[derive(Clone, Copy)]
enum Target {
    Points(Real),
    Connectivity,
    Offsets,
    Types,
    /// Point or cell data: the array's index in [`Data`], and whether it is point data.
    Data(usize, Location),
    /// An array we do not read: its text is skipped.
    Skip,
}

/// The piece being read: its declared counts and where its arrays start.
#[derive(Default)]
struct Piece {
    index: usize,
    /// The line of its `<Piece>` tag.
    line: u32,
    points: usize,
    cells: usize,
    /// Points of the pieces before (this piece's ids are shifted by it).
    point_base: u32,
    /// `raw.ids.len()` and simplex count when the piece started.
    id_base: usize,
    cell_base: usize,
    /// Numbers read into each array, and whether it was seen.
    coords: Option<usize>,
    connectivity: Option<usize>,
    offsets: Option<usize>,
    /// Simplex length (1..=4) of each cell, from its type.
    lens: Option<Vec<u8>>,
}

struct State<'a> {
    bytes: &'a [u8],
    /// Newlines counted up to `counted`: `line` is the line at byte `counted`.
    counted: usize,
    line: u32,
    /// An array's numbers were read: errors from now on are ours, not vtkio's.
    started: bool,
    grid: bool,
    section: &'static str,
    open: Vec<Vec<u8>>,
    piece: Option<Piece>,
    pieces: usize,
    target: Option<Target>,
    raw: RawInput,
    data: Vec<f64>,
    /// The point and cell data arrays.
    arrays: Data,
}

/// Reads `bytes` when every data array is ASCII (see the module doc).
pub(super) fn parse(bytes: &[u8]) -> Res<Taken> {
    let mut s = State {
        bytes,
        counted: 0,
        line: 1,
        started: false,
        grid: false,
        section: "",
        open: Vec::new(),
        piece: None,
        pieces: 0,
        target: None,
        raw: RawInput::new(),
        data: Vec::new(),
        arrays: Data::default(),
    };
    match s.run() {
        Ok(()) => s.finish().map(Taken::Yes),
        Err(Stop::Vtkio) => Ok(Taken::No),
        Err(Stop::Err(line, kind)) => Err((line, kind)),
    }
}

impl State<'_> {
    /// The line of byte `pos` (positions only move forward).
    fn line_at(&mut self, pos: usize) -> u32 {
        let pos = pos.min(self.bytes.len());
        if pos > self.counted {
            let n = memchr::memchr_iter(b'\n', &self.bytes[self.counted..pos]).count();
            self.line = self
                .line
                .saturating_add(u32::try_from(n).unwrap_or(u32::MAX));
            self.counted = pos;
        }
        self.line
    }

    /// A structural problem: vtkio's (with today's message) until an array was read, ours after.
    fn structural(&mut self, pos: usize, msg: String) -> Stop {
        if self.started {
            Stop::Err(self.line_at(pos), syntax(msg))
        } else {
            Stop::Vtkio
        }
    }

    /// Step 1: the events, each dispatched.
    fn run(&mut self) -> Result<(), Stop> {
        let mut xml = Reader::from_reader(self.bytes);
        loop {
            let pos = xml.buffer_position() as usize;
            let event = match xml.read_event() {
                Ok(e) => e,
                Err(e) => {
                    let at = xml.error_position() as usize;
                    return Err(
                        self.structural(at, format!("VTU: XML error: {}", echo(e.to_string())))
                    );
                }
            };
            match event {
                Event::Start(e) => {
                    self.open.push(e.local_name().as_ref().to_vec());
                    self.open_element(&e, pos)?;
                }
                Event::Empty(e) => {
                    self.open_element(&e, pos)?;
                    self.close_element(e.local_name().as_ref(), pos)?;
                }
                Event::End(e) => {
                    self.open.pop();
                    self.close_element(e.local_name().as_ref(), pos)?;
                }
                Event::Text(t) => self.text(&t[..], pos)?,
                Event::CData(t) => self.text(&t[..], pos + "<![CDATA[".len())?,
                Event::Eof => break,
                _ => {}
            }
        }
        if let Some(name) = self.open.last() {
            let msg = format!("file ends inside <{}>", echo(name));
            return Err(self.structural(self.bytes.len(), msg));
        }
        if !self.grid {
            return Err(Stop::Vtkio);
        }
        Ok(())
    }

    /// Step 2: an opening tag.
    fn open_element(&mut self, e: &BytesStart, pos: usize) -> Result<(), Stop> {
        let attr = |name: &str| -> Option<Vec<u8>> {
            e.try_get_attribute(name)
                .ok()
                .flatten()
                .map(|a| a.value.into_owned())
        };
        match e.local_name().as_ref() {
            b"VTKFile" => {
                if attr("type").as_deref() != Some(b"UnstructuredGrid") {
                    return Err(Stop::Vtkio);
                }
                self.grid = true;
            }
            b"AppendedData" => return Err(Stop::Vtkio),
            b"Piece" => self.start_piece(attr("NumberOfPoints"), attr("NumberOfCells"), pos)?,
            b"Points" => self.section = "Points",
            b"Cells" => self.section = "Cells",
            b"PointData" => self.section = "PointData",
            b"CellData" => self.section = "CellData",
            b"FieldData" => self.section = "FieldData",
            b"DataArray" => {
                if self.section == "FieldData" {
                    let name = attr("Name").unwrap_or_default();
                    let msg = data::field_data(&String::from_utf8_lossy(&name));
                    return Err(Stop::Err(self.line_at(pos), syntax(msg)));
                }
                // A data array's declaration is checked here whatever its format: vtkio would
                // read a String array as Float64.
                let declared = self.data_array(e, pos)?;
                if attr("format").as_deref() != Some(b"ascii") {
                    return Err(Stop::Vtkio);
                }
                let target = match declared {
                    Some(t) => t,
                    None => self.target_of(attr("type"), attr("Name")),
                };
                self.target = Some(target);
            }
            _ => {}
        }
        Ok(())
    }

    /// A piece's counts, and room for its arrays (capped by what the file could hold).
    fn start_piece(
        &mut self,
        np: Option<Vec<u8>>,
        nc: Option<Vec<u8>>,
        pos: usize,
    ) -> Result<(), Stop> {
        let index = self.pieces;
        self.pieces += 1;
        let line = self.line_at(pos);
        let count = |v: Option<Vec<u8>>, what: &str| -> Result<usize, Stop> {
            let v = v.ok_or(Stop::Vtkio)?;
            let v = String::from_utf8_lossy(&v).into_owned();
            parse_count(&v, what)
                .map(|n| n as usize)
                .map_err(|k| Stop::Err(line, k))
        };
        let points = count(np, "NumberOfPoints")?;
        let cells = count(nc, "NumberOfCells")?;
        let left = self.bytes.len() - pos.min(self.bytes.len());
        let room = |b| Stop::Err(line, no_room("the vertex coordinates")(b));
        table::try_reserve_exact(&mut self.data, capped_len(points.saturating_mul(3), left))
            .map_err(room)?;
        self.raw
            .try_reserve(capped_len(cells, left), 0)
            .map_err(|k| Stop::Err(line, k))?;
        let point_base = u32::try_from(self.data.len() / 3)
            .map_err(|_| Stop::Err(line, syntax("more than 2^32 points")))?;
        self.piece = Some(Piece {
            index,
            line,
            points,
            cells,
            point_base,
            id_base: self.raw.ids.len(),
            cell_base: self.raw.simplex_count(),
            ..Piece::default()
        });
        Ok(())
    }

    /// A point or cell data array's declaration, checked, and its place in [`Data`] (`None`
    /// outside `PointData` and `CellData`).
    fn data_array(&mut self, e: &BytesStart, pos: usize) -> Result<Option<Target>, Stop> {
        let location = match self.section {
            "PointData" => Location::Vertices,
            "CellData" => Location::Listed,
            _ => return Ok(None),
        };
        let Some(piece) = self.piece.as_ref() else {
            return Ok(None);
        };
        let index = piece.index;
        self.started = true;
        let line = self.line_at(pos);
        let (name, kind, components) =
            data::declaration(e, location).map_err(|m| Stop::Err(line, syntax(m)))?;
        let i = self
            .arrays
            .open(index, location, name, kind, components)
            .map_err(|m| Stop::Err(line, syntax(m)))?;
        Ok(Some(Target::Data(i, location)))
    }

    /// Which array a `DataArray` of this `type` and `Name` fills.
    fn target_of(&self, ty: Option<Vec<u8>>, name: Option<Vec<u8>>) -> Target {
        match (self.section, self.piece.is_some()) {
            ("Points", true) => Target::Points(match ty.as_deref() {
                Some(b"Float32") => Real::F32,
                Some(b"Float64") => Real::F64,
                _ => Real::Int,
            }),
            ("Cells", true) => match name.as_deref() {
                Some(b"connectivity") => Target::Connectivity,
                Some(b"offsets") => Target::Offsets,
                Some(b"types") => Target::Types,
                _ => Target::Skip,
            },
            _ => Target::Skip,
        }
    }

    /// Step 3: an array's text, its numbers parsed into the output.
    fn text(&mut self, text: &[u8], pos: usize) -> Result<(), Stop> {
        let Some(target) = self.target.filter(|t| !matches!(t, Target::Skip)) else {
            return Ok(());
        };
        if self.piece.is_none() {
            return Ok(());
        }
        self.started = true;
        let mut line = self.line_at(pos);
        let Some(piece) = self.piece.as_mut() else {
            return Ok(());
        };
        let mut fill = Fill {
            target,
            piece,
            raw: &mut self.raw,
            data: &mut self.data,
            arrays: &mut self.arrays,
        };
        fill.reserve(text.len()).map_err(|k| Stop::Err(line, k))?;
        let mut i = 0;
        while i < text.len() {
            let c = text[i];
            if c.is_ascii_whitespace() {
                line = line.saturating_add(u32::from(c == b'\n'));
                i += 1;
                continue;
            }
            let start = i;
            while i < text.len() && !text[i].is_ascii_whitespace() {
                i += 1;
            }
            let tok = std::str::from_utf8(&text[start..i]).map_err(|_| {
                Stop::Err(
                    line,
                    syntax(format!("non-numeric token '{}'", echo(&text[start..i]))),
                )
            })?;
            fill.number(tok, line).map_err(|k| Stop::Err(line, k))?;
        }
        self.counted = (pos + text.len()).min(self.bytes.len()).max(self.counted);
        self.line = line;
        Ok(())
    }

    /// Step 4: a closing tag; a data array's and a piece's counts are checked.
    fn close_element(&mut self, name: &[u8], pos: usize) -> Result<(), Stop> {
        match name {
            b"DataArray" => {
                if let (Some(t), Some(piece)) = (self.target.take(), self.piece.as_mut()) {
                    let msg = match t {
                        Target::Data(i, location) => {
                            let n = match location {
                                Location::Vertices => piece.points,
                                Location::Listed => piece.cells,
                            };
                            self.arrays.close(i, piece.index, n).err()
                        }
                        t => piece.close_array(t),
                    };
                    if let Some(msg) = msg {
                        return Err(Stop::Err(self.line_at(pos), syntax(msg)));
                    }
                }
            }
            b"Points" | b"Cells" | b"PointData" | b"CellData" | b"FieldData" => self.section = "",
            b"Piece" => {
                if let Some(piece) = self.piece.take() {
                    // A missing array is reported at the piece's tag, as the vtkio path does.
                    self.arrays
                        .end_piece(piece.index)
                        .map_err(|m| Stop::Err(piece.line, syntax(m)))?;
                    let line = self.line_at(pos);
                    piece
                        .check_cells(&mut self.raw)
                        .map_err(|m| Stop::Err(line, syntax(m)))?;
                }
            }
            _ => {}
        }
        Ok(())
    }

    /// Step 5: the coordinates placed in the output.
    fn finish(self) -> Res<RawInput> {
        let mut raw = self.raw;
        self.arrays.into_attributes(&mut raw.attributes);
        let n = self.data.len() / 3;
        raw.vertex_count =
            Some(u32::try_from(n).map_err(|_| (0, syntax("more than 2^32 points")))?);
        raw.coords = Some(Coords {
            dim: 3,
            data: self.data,
        });
        Ok(raw)
    }
}

/// The arrays one data array's numbers go to.
struct Fill<'s> {
    target: Target,
    piece: &'s mut Piece,
    raw: &'s mut RawInput,
    data: &'s mut Vec<f64>,
    arrays: &'s mut Data,
}

impl Fill<'_> {
    /// Room for the numbers a text of `len` bytes can hold (at most one per two bytes).
    fn reserve(&mut self, len: usize) -> Result<(), ReadErrorKind> {
        let n = len / 2 + 1;
        match self.target {
            Target::Connectivity => table::try_reserve_exact(&mut self.raw.ids, n)
                .map_err(no_room("the simplices' vertex ids")),
            Target::Types => {
                let lens = self.piece.lens.get_or_insert_with(Vec::new);
                let n = n.min(self.piece.cells.saturating_sub(lens.len()));
                table::try_reserve_exact(lens, n).map_err(no_room("the cell types"))
            }
            Target::Data(i, location) => {
                let elements = match location {
                    Location::Vertices => self.piece.points,
                    Location::Listed => self.piece.cells,
                };
                self.arrays.reserve(i, n.min(elements.saturating_mul(9)))
            }
            // Declared counts reserved these at the piece.
            _ => Ok(()),
        }
    }

    fn number(&mut self, tok: &str, line: u32) -> Result<(), ReadErrorKind> {
        let p = &mut *self.piece;
        match self.target {
            Target::Points(real) => {
                let v = match real {
                    Real::F64 => parse_f64(tok, "a point coordinate")?,
                    // The shared check: a value a 32-bit float holds only as inf or 0 is
                    // refused.
                    Real::F32 => parse_real(tok, "a point coordinate", Float::F32)?,
                    Real::Int => {
                        check_integer(tok, "point coordinate")?;
                        parse_f64(tok, "a point coordinate")?
                    }
                };
                *p.coords.get_or_insert(0) += 1;
                table::try_push(self.data, v).map_err(no_room("the vertex coordinates"))
            }
            Target::Connectivity => {
                let v = parse_id(tok, false)?;
                let v = v
                    .checked_add(p.point_base)
                    .ok_or_else(|| syntax(format!("piece {}: id {v} too large", p.index)))?;
                *p.connectivity.get_or_insert(0) += 1;
                table::try_push(&mut self.raw.ids, v).map_err(no_room("the simplices' vertex ids"))
            }
            Target::Offsets => {
                let off = parse_count(tok, "cell offset")? as usize;
                *p.offsets.get_or_insert(0) += 1;
                table::try_push(&mut self.raw.offsets, p.id_base + off)
                    .map_err(no_room("the simplex offsets"))?;
                table::try_push(&mut self.raw.lines, line)
                    .map_err(no_room("the simplices' line numbers"))
            }
            Target::Types => {
                let lens = p.lens.get_or_insert_with(Vec::new);
                let t = parse_count(tok, "cell type")?;
                let len = simplex_len(t).map_err(|name| {
                    syntax(format!(
                        "piece {}, cell #{} is a {name}, which is not a simplex",
                        p.index,
                        lens.len()
                    ))
                })?;
                table::try_push(lens, len).map_err(no_room("the cell types"))
            }
            Target::Data(i, _) => self.arrays.push_token(i, tok),
            Target::Skip => Ok(()),
        }
    }
}

impl Piece {
    /// A closed data array's count checked against the piece's declared counts.
    fn close_array(&mut self, t: Target) -> Option<String> {
        let (n, want, what) = match t {
            Target::Points(_) => {
                let n = *self.coords.get_or_insert(0);
                (n, self.points.saturating_mul(3), "point coordinates")
            }
            Target::Connectivity => {
                self.connectivity.get_or_insert(0);
                return None;
            }
            Target::Offsets => {
                let n = *self.offsets.get_or_insert(0);
                (n, self.cells, "cell offsets")
            }
            Target::Types => {
                let n = self.lens.get_or_insert_with(Vec::new).len();
                (n, self.cells, "cell types")
            }
            Target::Data(..) | Target::Skip => return None,
        };
        (n != want).then(|| {
            format!(
                "piece {}: {n} {what}, expected {want} (NumberOfPoints=\"{}\", NumberOfCells=\"{}\")",
                self.index, self.points, self.cells
            )
        })
    }

    /// The piece's cells: each cell's id range within the connectivity, of its type's length.
    fn check_cells(self, raw: &mut RawInput) -> Result<(), String> {
        let i = self.index;
        if self.coords.is_none() && self.points > 0 {
            return Err(format!("piece {i}: no point coordinates"));
        }
        let lens = self.lens.unwrap_or_default();
        if self.cells > 0 && (self.connectivity.is_none() || self.offsets.is_none()) {
            return Err(format!(
                "piece {i}: cells need connectivity, offsets and types arrays"
            ));
        }
        if lens.len() != self.cells {
            return Err(format!(
                "piece {i}: {} cell types for {} cells",
                lens.len(),
                self.cells
            ));
        }
        let ends = &raw.offsets[self.cell_base + 1..];
        let mut start = self.id_base;
        for (c, (&end, &len)) in ends.iter().zip(&lens).enumerate() {
            if end < start || end > raw.ids.len() {
                return Err(format!(
                    "piece {i}, cell #{c}: offsets out of order or range"
                ));
            }
            if end - start != usize::from(len) {
                return Err(format!(
                    "piece {i}, cell #{c} of type {} has {} ids, expected {len}",
                    cell_name(len),
                    end - start
                ));
            }
            start = end;
        }
        if start != raw.ids.len() {
            return Err(format!(
                "piece {i}: {} connectivity ids, the offsets end at {}",
                raw.ids.len() - self.id_base,
                start - self.id_base
            ));
        }
        Ok(())
    }
}

/// The simplex length of a VTK cell type, or the type's name (vtkio's) when it is no simplex.
fn simplex_len(t: u32) -> Result<u8, String> {
    Ok(match t {
        1 => 1,
        3 => 2,
        5 => 3,
        10 => 4,
        _ => {
            return Err(vtkio_cell_name(t));
        }
    })
}

/// The vtkio name of a simplex cell type by its length.
fn cell_name(len: u8) -> &'static str {
    match len {
        1 => "Vertex",
        2 => "Line",
        3 => "Triangle",
        _ => "Tetra",
    }
}

/// A VTK cell type's name as vtkio's `CellType` spells it (so that both paths refuse alike).
fn vtkio_cell_name(t: u32) -> String {
    const LINEAR: [&str; 14] = [
        "Vertex",
        "PolyVertex",
        "Line",
        "PolyLine",
        "Triangle",
        "TriangleStrip",
        "Polygon",
        "Pixel",
        "Quad",
        "Tetra",
        "Voxel",
        "Hexahedron",
        "Wedge",
        "Pyramid",
    ];
    const QUADRATIC: [&str; 15] = [
        "QuadraticEdge",
        "QuadraticTriangle",
        "QuadraticQuad",
        "QuadraticTetra",
        "QuadraticHexahedron",
        "QuadraticWedge",
        "QuadraticPyramid",
        "BiquadraticQuad",
        "TriquadraticHexahedron",
        "QuadraticLinearQuad",
        "QuadraticLinearWedge",
        "BiquadraticQuadraticWedge",
        "BiquadraticQuadraticHexahedron",
        "BiquadraticTriangle",
        "CubicLine",
    ];
    let t = t as usize;
    match t {
        1..=14 => LINEAR[t - 1].to_string(),
        21..=35 => QUADRATIC[t - 21].to_string(),
        41 => "ConvexPointSet".to_string(),
        42 => "Polyhedron".to_string(),
        _ => format!("cell of VTK type {t}"),
    }
}
