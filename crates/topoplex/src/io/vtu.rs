//! VTK XML unstructured grids (`.vtu`). Files whose data arrays are all ASCII are read by our
//! streaming reader (`vtu/ascii.rs`: quick-xml events, numbers parsed straight into the output,
//! errors with lines); the others (base64, zlib-compressed or appended arrays) are read and
//! written with the `vtkio` crate, and this module maps its cells to simplices.
//!
//! Reading: every piece's points (3 coordinates, any numeric type, widened to `f64`) and cells.
//! Pieces are concatenated, each piece's ids shifted by the points before it. Cell types 1
//! (vertex), 3 (line), 5 (triangle) and 10 (tetrahedron) are simplices; any other (quad,
//! polygon, hexahedron, wedge, higher order...) is refused naming the cell's index, and so is a
//! cell whose id count does not match its type. Our ASCII reader names the line of an error
//! (and checks the declared `NumberOfPoints`/`NumberOfCells` against the arrays); vtkio
//! reports XML errors without a line.
//! Point and cell data (`<PointData>`, `<CellData>` arrays of any numeric type, 1 to 9
//! components) are kept as attributes named by the array's `Name`, point data on the vertices,
//! cell data on the listed simplices, each type exactly (`vtu/data.rs`); a `String` or other
//! non-numeric array is refused naming the array and its line (checked before vtkio reads the
//! file, since it would take one for `Float64`). Pieces concatenate their data; every piece
//! must carry the same arrays. `<FieldData>` arrays (data on the whole mesh, which attributes
//! cannot hold) are refused naming the array and its line, never skipped; so is appended data
//! not encoded in base64 (`encoding="raw"`: vtkio 0.7.0-rc2 declares no feature that decodes
//! it), naming the line of `<AppendedData>`.
//! Pieces stored in other files (parallel formats) are not read. vtkio panics on some malformed
//! binary arrays; the panic is caught and reported as an error (one line: the panic hook stays
//! silent for it, [`crate::error::caught_quietly`]). vtkio's own arrays are allocated
//! infallibly: their peak is probed before parsing, ours (and all of the ASCII reader's) are
//! reserved fallibly; memory that cannot be had is [`ReadErrorKind::TooLarge`].
//!
//! Writing: one piece, `Float64` points (3 per vertex, fewer padded with zeros, zeros without
//! coordinates), `connectivity`, `offsets` and `types` in listing order, as vtkio encodes them
//! (base64 binary, so coordinates are exact). Holds vertices, edges, triangles, tetrahedra.
//! Every attribute is written as a data array of the piece in its own type (`Int32`, `Int64`,
//! `Float32`, `Float64`) and components: vertex attributes as point data, listed ones as cell
//! data (cells are written in listing order), so they read back bit for bit.

use vtkio::model::{
    Attributes, ByteOrder, CellType, Cells, DataSet, ElementType, IOBuffer, Piece,
    UnstructuredGridPiece, Version, VertexNumbers, Vtk,
};

mod ascii;
mod data;

use super::write::{check_fits, vertex_count};
use super::{Coords, RawInput, ReadErrorKind, echo, no_room, syntax};
use crate::complex::table::{self, headroom};
use crate::complex::{Location, Values};
use crate::error::caught_quietly;
use crate::io::Res;

/// vtkio's parse peak per byte of file, probed before it starts: 5.9 measured on ASCII data
/// arrays of short lines (it holds the file, each array's text as a string and the typed
/// arrays grown by doubling; those files are now read by our ASCII reader, but a file mixing
/// ASCII and binary arrays still comes here), 2.9 on base64 binary ones (scripts/read-peak.sh,
/// docs/benchmarks.md "Reading").
const VTKIO_PEAK_PER_BYTE: usize = 6;

fn err(msg: impl Into<String>) -> (u32, ReadErrorKind) {
    (0, syntax(msg))
}

fn simplex_len(t: CellType) -> Result<usize, String> {
    Ok(match t {
        CellType::Vertex => 1,
        CellType::Line => 2,
        CellType::Triangle => 3,
        CellType::Tetra => 4,
        other => return Err(format!("{other:?}")),
    })
}

/// One piece's points and cells appended to `raw` (its ids shifted by `base`), its point and
/// cell data to `arrays` (`lines`: where the file declares them).
fn add_piece(
    p: UnstructuredGridPiece,
    piece: usize,
    raw: &mut RawInput,
    data: &mut Vec<f64>,
    (arrays, lines): (&mut data::Data, &data::Lines),
) -> Res<()> {
    let base = data.len() / 3;
    let points_before = data.len();
    let points: Vec<f64> = p
        .points
        .cast_into::<f64>()
        .ok_or_else(|| err(format!("piece {piece}: points are not numbers")))?;
    table::try_extend(data, &points).map_err(|b| (0, no_room("the vertex coordinates")(b)))?;
    drop(points);
    let (connectivity, offsets): (Vec<u64>, Vec<u64>) = match p.cells.cell_verts {
        VertexNumbers::XML {
            connectivity,
            offsets,
        } => (connectivity, offsets),
        VertexNumbers::Legacy { vertices, .. } => {
            // Not produced by the XML reader; converted for completeness.
            let mut conn = Vec::new();
            let mut offs = Vec::new();
            let mut k = 0;
            while k < vertices.len() {
                let n = vertices[k] as usize;
                let ids = vertices
                    .get(k + 1..k + 1 + n)
                    .ok_or_else(|| err("truncated cell list"))?;
                for &v in ids {
                    table::try_push(&mut conn, u64::from(v))
                        .map_err(|b| (0, no_room("the cells")(b)))?;
                }
                table::try_push(&mut offs, conn.len() as u64)
                    .map_err(|b| (0, no_room("the cells")(b)))?;
                k += 1 + n;
            }
            (conn, offs)
        }
    };
    if offsets.len() != p.cells.types.len() {
        return Err(err(format!(
            "piece {piece}: {} cell types for {} cells",
            p.cells.types.len(),
            offsets.len()
        )));
    }
    raw.try_reserve(offsets.len(), connectivity.len())
        .map_err(|k| (0, k))?;
    let mut start = 0u64;
    let mut ids = Vec::with_capacity(4);
    for (i, (&end, &t)) in offsets.iter().zip(&p.cells.types).enumerate() {
        let len = simplex_len(t).map_err(|name| {
            err(format!(
                "piece {piece}, cell #{i} is a {name}, which is not a simplex"
            ))
        })?;
        let cell = connectivity
            .get(start as usize..end as usize)
            .filter(|_| start <= end)
            .ok_or_else(|| {
                err(format!(
                    "piece {piece}, cell #{i}: offsets out of order or range"
                ))
            })?;
        if cell.len() != len {
            return Err(err(format!(
                "piece {piece}, cell #{i} (VTK type {}) has {} ids, expected {len}",
                t as u8,
                cell.len()
            )));
        }
        ids.clear();
        for &v in cell {
            let v = u32::try_from(v as usize + base)
                .map_err(|_| err(format!("piece {piece}, cell #{i}: id {v} too large")))?;
            ids.push(v);
        }
        raw.try_push(&ids, 0).map_err(|k| (0, k))?;
        start = end;
    }
    let point_count = (data.len() - points_before) / 3;
    let cell_count = offsets.len();
    for (location, list) in [
        (Location::Vertices, p.data.point),
        (Location::Listed, p.data.cell),
    ] {
        for a in list {
            let elements = match location {
                Location::Vertices => point_count,
                Location::Listed => cell_count,
            };
            piece_array(a, piece, location, elements, arrays, lines)?;
        }
    }
    arrays
        .end_piece(piece)
        .map_err(|m| (lines.piece(piece), syntax(m)))
}

/// One point or cell data array vtkio read, appended to `arrays`.
fn piece_array(
    a: vtkio::model::Attribute,
    piece: usize,
    location: Location,
    elements: usize,
    arrays: &mut data::Data,
    lines: &data::Lines,
) -> Res<()> {
    let (name, components, buf) = match a {
        vtkio::model::Attribute::DataArray(d) => (d.name, d.elem.num_comp(), d.data),
        vtkio::model::Attribute::Field { name, .. } => {
            return Err(err(format!(
                "{} field '{}' (legacy only) is not read",
                data::section(location),
                echo(&name)
            )));
        }
    };
    let line = lines.array(piece, location, &name);
    let at = |m: String| (line, syntax(m));
    let kind = data::Data::buffer_kind(&buf).ok_or_else(|| {
        at(format!(
            "{} array '{}' is a bit array, which is not held",
            data::section(location),
            echo(&name)
        ))
    })?;
    // The declaration was checked by `data::scan`; this repeats it on what vtkio made of it.
    let components =
        data::checked_components(location, &name, components.to_string().as_bytes()).map_err(at)?;
    let i = arrays
        .open(piece, location, name, kind, components)
        .map_err(at)?;
    arrays.extend(i, buf).map_err(at)?;
    arrays.close(i, piece, elements).map_err(at)
}

/// Parses a `.vtu` file: by our ASCII reader when its data arrays are all ASCII, else by vtkio.
pub fn parse(bytes: &[u8]) -> Res<RawInput> {
    match ascii::parse(bytes)? {
        ascii::Taken::Yes(raw) => Ok(raw),
        ascii::Taken::No => parse_vtkio(bytes),
    }
}

/// vtkio's error text without its Rust debug wrappers: `Custom("missing field `@version`")`
/// becomes the quoted text, `UnexpectedEof` "unexpected end of file".
fn plain_vtkio(msg: &str) -> String {
    let mut s = msg.replace("Deserialization error: ", "");
    while let Some(i) = s.find("Custom(\"") {
        let Some(j) = s[i + 8..].find("\")") else {
            break;
        };
        s = format!("{}{}{}", &s[..i], &s[i + 8..i + 8 + j], &s[i + 8 + j + 2..]);
    }
    s.replace("UnexpectedEof", "unexpected end of file")
}

/// Parses a `.vtu` file with vtkio.
fn parse_vtkio(bytes: &[u8]) -> Res<RawInput> {
    // vtkio's arrays are allocated infallibly: its peak is probed first (address space, see
    // `headroom`), so that a file too large for memory is refused rather than an abort.
    headroom(bytes.len().saturating_mul(VTKIO_PEAK_PER_BYTE))
        .map_err(|b| (0, no_room("reading VTU")(b)))?;
    // vtkio reads any array type it does not know as Float64: the declarations are checked
    // first.
    let lines = data::scan(bytes)?;
    // vtkio 0.7.0-rc2 slices out of range on some malformed binary arrays (found by fuzzing):
    // its panic is caught here and reported as a parse error, without the panic hook's report.
    let parsed = caught_quietly(|| Vtk::parse_xml(bytes))
        .map_err(|_| err("VTU: malformed data array (vtkio failed on it: a caught panic)"))?;
    let vtk = parsed.map_err(|e| err(format!("VTU: {}", echo(plain_vtkio(&e.to_string())))))?;
    let DataSet::UnstructuredGrid { pieces, .. } = vtk.data else {
        return Err(err(
            "not an UnstructuredGrid (only unstructured grids are read)",
        ));
    };
    let mut raw = RawInput::new();
    let mut data = Vec::new();
    let mut arrays = data::Data::default();
    for (i, piece) in pieces.into_iter().enumerate() {
        match piece {
            Piece::Inline(p) => add_piece(*p, i, &mut raw, &mut data, (&mut arrays, &lines))?,
            _ => {
                return Err(err(format!(
                    "piece {i} is stored in another file (not read)"
                )));
            }
        }
    }
    if data.len() % 3 != 0 {
        return Err(err("the point coordinates are not a multiple of 3"));
    }
    raw.vertex_count =
        Some(u32::try_from(data.len() / 3).map_err(|_| err("more than 2^32 points"))?);
    raw.coords = Some(Coords { dim: 3, data });
    arrays.into_attributes(&mut raw.attributes);
    Ok(raw)
}

/// Writes `raw` as a `.vtu` file.
pub(crate) fn write(raw: &RawInput, out: &mut Vec<u8>) -> Result<(), String> {
    check_fits(
        raw,
        4,
        "vertices, edges, triangles and tetrahedra (use .simplices)",
    )?;
    let n = vertex_count(raw);
    let coords = raw.coords.as_ref();
    let points: Vec<f64> = (0..n)
        .flat_map(|v| {
            (0..3).map(move |k| {
                coords
                    .filter(|c| k < c.dim)
                    .map_or(0.0, |c| c.data[v * c.dim + k])
            })
        })
        .collect();
    let types = (0..raw.simplex_count())
        .map(|i| match raw.simplex(i).len() {
            1 => CellType::Vertex,
            2 => CellType::Line,
            3 => CellType::Triangle,
            _ => CellType::Tetra,
        })
        .collect();
    let piece = UnstructuredGridPiece {
        points: IOBuffer::F64(points),
        cells: Cells {
            cell_verts: VertexNumbers::XML {
                connectivity: raw.ids.iter().map(|&v| u64::from(v)).collect(),
                offsets: raw.offsets[1..].iter().map(|&o| o as u64).collect(),
            },
            types,
        },
        data: piece_data(raw),
    };
    let vtk = Vtk {
        version: Version::new_xml(1, 0),
        title: String::new(),
        byte_order: ByteOrder::LittleEndian,
        file_path: None,
        data: DataSet::inline(piece),
    };
    vtk.write_xml(out).map_err(|e| format!("VTU writer: {e}"))
}

/// The attributes of `raw` as the piece's point data (on the vertices) and cell data (on the
/// listed simplices), each in its own type and components, in order.
fn piece_data(raw: &RawInput) -> Attributes {
    let mut out = Attributes::new();
    for a in raw.attributes.iter() {
        let data = match &a.values {
            Values::I32(v) => IOBuffer::I32(v.clone()),
            Values::I64(v) => IOBuffer::I64(v.clone()),
            Values::F32(v) => IOBuffer::F32(v.clone()),
            Values::F64(v) => IOBuffer::F64(v.clone()),
        };
        let array = vtkio::model::Attribute::DataArray(vtkio::model::DataArray {
            name: a.name.clone(),
            elem: ElementType::Generic(a.components as u32),
            data,
        });
        match a.location {
            Location::Vertices => out.point.push(array),
            Location::Listed => out.cell.push(array),
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `raw` without its lines (the vtkio path has none).
    fn unlined(mut raw: RawInput) -> RawInput {
        raw.lines.iter_mut().for_each(|l| *l = 0);
        raw
    }

    /// Our reader's result on an ASCII file, checked equal to the vtkio path's.
    fn both(text: &str) -> RawInput {
        let ours = match ascii::parse(text.as_bytes()) {
            Ok(ascii::Taken::Yes(raw)) => raw,
            Ok(ascii::Taken::No) => panic!("handed to vtkio:\n{text}"),
            Err(e) => panic!("{e:?}\n{text}"),
        };
        let theirs = parse_vtkio(text.as_bytes()).unwrap_or_else(|e| panic!("{e:?}\n{text}"));
        assert_eq!(unlined(ours.clone()), theirs, "{text}");
        ours
    }

    /// Our reader's refusal: its line and message.
    fn refused(text: &str) -> (u32, String) {
        match ascii::parse(text.as_bytes()) {
            Err((line, ReadErrorKind::Syntax(m))) => (line, m),
            Err(e) => panic!("{e:?}"),
            Ok(ascii::Taken::Yes(_)) => panic!("read:\n{text}"),
            Ok(ascii::Taken::No) => panic!("handed to vtkio:\n{text}"),
        }
    }

    fn head(points: usize, cells: usize) -> String {
        format!(
            "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\">\n\
             <UnstructuredGrid>\n<Piece NumberOfPoints=\"{points}\" NumberOfCells=\"{cells}\">\n"
        )
    }

    fn array(kind: &str, name: &str, body: &str) -> String {
        format!(
            "<DataArray type=\"{kind}\" Name=\"{name}\" format=\"ascii\">\n{body}</DataArray>\n"
        )
    }

    const TAIL: &str = "</Piece>\n</UnstructuredGrid>\n</VTKFile>\n";

    /// A triangle and an edge over four points:
    /// ```text
    ///   2        3
    ///   | \      |
    ///   0--1     1
    /// ```
    fn triangle_and_edge(conn: &str, offsets: &str, types: &str) -> String {
        head(4, 2)
            + "<Points>\n"
            + "<DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n"
            + "0 0 0\n1 0 0\n0 1 0\n1 1 0\n</DataArray>\n"
            + "</Points>\n<Cells>\n"
            + &array("Int32", "connectivity", conn)
            + &array("Int32", "offsets", offsets)
            + &array("UInt8", "types", types)
            + "</Cells>\n"
            + TAIL
    }

    #[test]
    fn triangle_and_edge_read_alike_with_lines() {
        let raw = both(&triangle_and_edge("0 1 2\n1 3\n", "3\n5\n", "5\n3\n"));
        assert_eq!(raw.simplex(0), [0, 1, 2]);
        assert_eq!(raw.simplex(1), [1, 3]);
        assert_eq!(raw.vertex_count, Some(4));
        // Each cell's line is its offset's line.
        assert_eq!(raw.lines, [19, 20]);
    }

    #[test]
    fn fixtures_binary_go_to_vtkio() {
        let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/../../fuzz/corpus/read_vtu");
        let mut ascii_seen = 0;
        for e in std::fs::read_dir(dir).unwrap() {
            let bytes = std::fs::read(e.unwrap().path()).unwrap();
            let theirs = parse_vtkio(&bytes).unwrap();
            match ascii::parse(&bytes).unwrap() {
                ascii::Taken::Yes(ours) => {
                    ascii_seen += 1;
                    assert_eq!(unlined(ours), theirs);
                }
                ascii::Taken::No => {
                    assert!(String::from_utf8_lossy(&bytes).contains("format=\"binary\""));
                }
            }
            assert_eq!(unlined(parse(&bytes).unwrap()), theirs);
        }
        assert!(ascii_seen >= 1, "an ASCII seed in {dir}");
    }

    /// Random ASCII grids: several pieces, the four simplex types, Float32/Float64/Int32
    /// points, numbers in several spellings, point and cell data of every type and 1 to 9
    /// components (the same arrays in every piece), varied whitespace.
    fn random_grid(seed: u64) -> String {
        let mut state = seed.wrapping_mul(0x9e37_79b9_7f4a_7c15) | 1;
        let mut rnd = move |n: u64| {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            state % n
        };
        let mut out =
            "<?xml version=\"1.0\"?>\n<!-- generated -->\n<VTKFile type=\"UnstructuredGrid\" \
                       version=\"1.0\" byte_order=\"LittleEndian\">\n<UnstructuredGrid>\n"
                .to_string();
        const TYPES: [(&str, i64, i64); 10] = [
            ("Int8", -128, 127),
            ("UInt8", 0, 255),
            ("Int16", -32768, 32767),
            ("UInt16", 0, 65535),
            ("Int32", i32::MIN as i64, i32::MAX as i64),
            ("UInt32", 0, u32::MAX as i64),
            ("Int64", i64::MIN, i64::MAX),
            ("UInt64", 0, i64::MAX),
            ("Float32", 0, 0),
            ("Float64", 0, 0),
        ];
        // (cell data?, type, components) per array, the same in every piece.
        let specs: Vec<(bool, usize, usize)> = (0..rnd(5))
            .map(|_| (rnd(2) == 0, rnd(10) as usize, 1 + rnd(9) as usize))
            .collect();
        fn number(t: usize, rnd: &mut dyn FnMut(u64) -> u64) -> String {
            let (name, lo, hi) = TYPES[t];
            match name {
                "Float32" => format!(
                    "{}e{}",
                    rnd(1 << 24) as i64 - (1 << 23),
                    rnd(60) as i64 - 30
                ),
                "Float64" => format!("-{}.{}e{}", rnd(1000), rnd(1 << 50), rnd(600) as i64 - 300),
                _ => match rnd(3) {
                    0 => lo.to_string(),
                    1 => hi.to_string(),
                    _ => (i128::from(lo)
                        + i128::from(rnd(1 << 62)) % (i128::from(hi) - i128::from(lo) + 1))
                        .to_string(),
                },
            }
        }
        let data = |cells: bool, count: usize, rnd: &mut dyn FnMut(u64) -> u64| {
            let mut out = String::new();
            for (k, &(_, t, comps)) in specs.iter().enumerate().filter(|x| x.1.0 == cells) {
                let body: String = (0..count * comps).map(|_| number(t, rnd) + " ").collect();
                out += &format!(
                    "<DataArray type=\"{}\" Name=\"a{k} &amp; b\" NumberOfComponents=\"{comps}\" \
                     format=\"ascii\">{body}</DataArray>\n",
                    TYPES[t].0
                );
            }
            out
        };
        for _ in 0..1 + rnd(3) {
            let np = 1 + rnd(12) as usize;
            let nc = rnd(15) as usize;
            let sep = |r: u64| [" ", "\n", "  ", "\t", "\r\n"][r as usize];
            let (kind, coord): (&str, fn(u64) -> String) = match rnd(3) {
                0 => ("Float32", |r| format!("{}.{}e-{}", r % 97, r % 1013, r % 5)),
                1 => ("Float64", |r| format!("-{}.{}", r % 1000, r % 9_999_991)),
                _ => ("Int32", |r| format!("{}", r as i64 % 50 - 25)),
            };
            let coords: String = (0..3 * np)
                .map(|_| coord(rnd(1 << 40)) + sep(rnd(5)))
                .collect();
            let (mut conn, mut offs, mut types, mut end) =
                (String::new(), String::new(), String::new(), 0);
            for _ in 0..nc {
                let (t, len) = [(1, 1), (3, 2), (5, 3), (10, 4)][rnd(4) as usize];
                for _ in 0..len {
                    conn += &format!("{}{}", rnd(np as u64), sep(rnd(5)));
                }
                end += len;
                offs += &format!("{end}{}", sep(rnd(5)));
                types += &format!("{t}{}", sep(rnd(5)));
            }
            out += &format!("<Piece NumberOfPoints=\"{np}\" NumberOfCells=\"{nc}\">\n");
            out += "<PointData Scalars=\"s\">\n";
            out += &array("Float32", "s", &"1.5 ".repeat(np));
            out += &data(false, np, &mut rnd);
            out += "</PointData>\n<Points>\n";
            out += &format!(
                "<DataArray type=\"{kind}\" NumberOfComponents=\"3\" format=\"ascii\">{coords}</DataArray>\n"
            );
            out += "</Points>\n<Cells>\n";
            // Arrays in either order.
            let mut cells = [
                array("Int64", "connectivity", &conn),
                array("Int64", "offsets", &offs),
                array("UInt8", "types", &types),
            ];
            if rnd(2) == 0 {
                cells.reverse();
            }
            out += &cells.concat();
            out += "</Cells>\n<CellData>\n";
            out += &data(true, nc, &mut rnd);
            out += "</CellData>\n</Piece>\n";
        }
        out + "</UnstructuredGrid>\n</VTKFile>\n"
    }

    #[test]
    fn random_ascii_grids_read_as_vtkio_reads_them() {
        let mut with_data = 0;
        for seed in 0..200 {
            let raw = both(&random_grid(seed));
            // The point data "s" and the random arrays are kept.
            assert!(raw.attributes.get("s", Location::Vertices).is_some());
            with_data += usize::from(raw.attributes.iter().count() > 1);
        }
        assert!(with_data > 100, "{with_data} grids with random arrays");
    }

    #[test]
    fn binary_or_other_data_sets_go_to_vtkio() {
        let bin = triangle_and_edge("0 1 2\n1 3\n", "3\n5\n", "5\n3\n").replacen(
            "format=\"ascii\"",
            "format=\"binary\"",
            1,
        );
        assert!(matches!(ascii::parse(bin.as_bytes()), Ok(ascii::Taken::No)));
        let poly = "<VTKFile type=\"PolyData\"></VTKFile>\n";
        assert!(matches!(
            ascii::parse(poly.as_bytes()),
            Ok(ascii::Taken::No)
        ));
        assert!(matches!(ascii::parse(b""), Ok(ascii::Taken::No)));
        // vtkio's messages for those stay, without their Rust debug wrappers.
        assert!(
            parse(b"")
                .unwrap_err()
                .1
                .to_string()
                .contains("XML error: unexpected end of file")
        );
    }

    #[test]
    fn refusals_name_line_and_cell() {
        let ok = triangle_and_edge("0 1 2\n1 3\n", "3\n5\n", "5\n3\n");
        // Truncated inside the connectivity.
        let cut = &ok[..ok.find("1 3\n").unwrap()];
        let (line, m) = refused(cut);
        assert_eq!((line, m.as_str()), (16, "file ends inside <DataArray>"));
        // A bad number, on its line.
        let (line, m) = refused(&triangle_and_edge("0 1 2\n1 x\n", "3\n5\n", "5\n3\n"));
        assert_eq!(line, 16);
        assert!(m.contains("'x'"), "{m}");
        // A hexahedron's type, named as vtkio names it.
        let (line, m) = refused(&triangle_and_edge("0 1 2\n1 3\n", "3\n5\n", "5\n12\n"));
        assert_eq!(
            (line, m.as_str()),
            (
                24,
                "piece 0, cell #1 is a Hexahedron, which is not a simplex"
            )
        );
        // Wrong counts: offsets, types, ids per cell, connectivity left over, coordinates.
        let (_, m) = refused(&triangle_and_edge("0 1 2\n1 3\n", "3\n", "5\n3\n"));
        assert!(m.starts_with("piece 0: 1 cell offsets, expected 2"), "{m}");
        let (_, m) = refused(&triangle_and_edge("0 1 2\n1 3\n", "3\n5\n", "5\n"));
        assert!(m.starts_with("piece 0: 1 cell types, expected 2"), "{m}");
        let (_, m) = refused(&triangle_and_edge("0 1 2\n1 3\n", "2\n5\n", "5\n3\n"));
        assert_eq!(m, "piece 0, cell #0 of type Triangle has 2 ids, expected 3");
        let (_, m) = refused(&triangle_and_edge("0 1 2\n1 3 0\n", "3\n5\n", "5\n3\n"));
        assert_eq!(m, "piece 0: 6 connectivity ids, the offsets end at 5");
        let (_, m) = refused(&triangle_and_edge("0 1 2\n1 3\n", "3\n9\n", "5\n3\n"));
        assert_eq!(m, "piece 0, cell #1: offsets out of order or range");
        let (line, m) = refused(&ok.replacen("1 1 0\n", "1 1\n", 1));
        assert_eq!(line, 11);
        assert!(
            m.starts_with("piece 0: 11 point coordinates, expected 12"),
            "{m}"
        );
        // A negative id, as the other readers report it.
        let neg = triangle_and_edge("0 1 2\n1 -3\n", "3\n5\n", "5\n3\n");
        assert!(matches!(
            ascii::parse(neg.as_bytes()),
            Err((16, ReadErrorKind::NegativeId(-3)))
        ));
    }

    /// The triangle and edge with `point` data and `cell` data sections' arrays.
    fn with_data(point: &str, cell: &str) -> String {
        triangle_and_edge("0 1 2\n1 3\n", "3\n5\n", "5\n3\n").replacen(
            "</Piece>",
            &format!("<PointData>\n{point}</PointData>\n<CellData>\n{cell}</CellData>\n</Piece>"),
            1,
        )
    }

    fn data_array(kind: &str, name: &str, comps: usize, body: &str) -> String {
        format!(
            "<DataArray type=\"{kind}\" Name=\"{name}\" NumberOfComponents=\"{comps}\" \
             format=\"ascii\">\n{body}</DataArray>\n"
        )
    }

    /// Both paths' refusal of an ASCII file: the same line and message.
    fn refused_alike(text: &str) -> (u32, String) {
        let ours = refused(text);
        let theirs = match parse_vtkio(text.as_bytes()) {
            Err((line, ReadErrorKind::Syntax(m))) => (line, m),
            other => panic!("vtkio path: {other:?}"),
        };
        assert_eq!(ours, theirs, "{text}");
        ours
    }

    #[test]
    fn point_and_cell_data_of_each_type_are_kept_exactly() {
        let text = with_data(
            &(data_array("UInt8", "u8", 1, "0 255 7 9\n")
                + &data_array("UInt64", "big", 1, "9223372036854775807 0 1 2\n")
                + &data_array("Float32", "v", 2, "0.1 -0 1e-45 inf 3 4 nan 6\n")),
            &(data_array("Int16", "region", 1, "-32768 32767\n")
                + &data_array("Float64", "t", 9, &"0.1 ".repeat(18))),
        );
        let ours = match ascii::parse(text.as_bytes()) {
            Ok(ascii::Taken::Yes(raw)) => raw,
            _ => panic!("not read"),
        };
        let theirs = parse_vtkio(text.as_bytes()).unwrap();
        assert!(ours.attributes.bits_eq(&theirs.attributes));
        let at = &ours.attributes;
        let get = |n: &str, l| at.get(n, l).unwrap();
        assert_eq!(
            get("u8", Location::Vertices).values,
            Values::I32(vec![0, 255, 7, 9])
        );
        assert_eq!(
            get("big", Location::Vertices).values,
            Values::I64(vec![i64::MAX, 0, 1, 2])
        );
        let Values::F32(v) = &get("v", Location::Vertices).values else {
            panic!("not f32")
        };
        assert_eq!(v[0], 0.1f32);
        assert_eq!(v[1].to_bits(), (-0.0f32).to_bits());
        assert_eq!(v[2].to_bits(), 1);
        assert!(v[3].is_infinite() && v[6].is_nan());
        assert_eq!(get("v", Location::Vertices).components, 2);
        assert_eq!(
            get("region", Location::Listed).values,
            Values::I32(vec![-32768, 32767])
        );
        assert_eq!(
            get("t", Location::Listed).values,
            Values::F64(vec![0.1; 18])
        );
    }

    #[test]
    fn data_that_cannot_be_held_is_refused_naming_the_array_and_line() {
        // (the paths that must refuse it, point data, cell data, line, what the refusal says)
        type Refuse = fn(&str) -> (u32, String);
        let cases: [(Refuse, String, String, u32, &str); 5] = [
            // A String array, in either path (vtkio would read it as Float64).
            (
                refused_alike,
                data_array("String", "names", 1, "a b c d\n"),
                String::new(),
                28,
                "point data array 'names' has type 'String'",
            ),
            (
                refused_alike,
                String::new(),
                data_array("Float64", "w", 10, "0\n"),
                30,
                "cell data array 'w' has NumberOfComponents=\"10\"; 1 to 9",
            ),
            // Our path: values of the wrong type or out of range, wrong counts, on their lines.
            (
                refused,
                data_array("UInt64", "big", 1, "0\n1\n9223372036854775808 3\n"),
                String::new(),
                31,
                "above 2^63",
            ),
            (
                refused,
                data_array("Int8", "s", 1, "1 2 128 4\n"),
                String::new(),
                29,
                "'128' does not fit Int8 among the values of point data array 's'",
            ),
            (
                refused,
                String::new(),
                data_array("Int32", "r", 1, "1 2.5\n"),
                31,
                "'2.5' is not of type Int32",
            ),
        ];
        for (refuse, points, cells, want_line, want) in cases {
            let (line, m) = refuse(&with_data(&points, &cells));
            assert_eq!(line, want_line, "{m}");
            assert!(m.contains(want), "{m}");
        }
        let (_, m) = refused(&with_data("", &data_array("Int32", "r", 2, "1 2 3\n")));
        assert_eq!(
            m,
            "piece 0: cell data array 'r' has 3 numbers, expected 2 × 2 = 4"
        );
        let (_, m) = refused(&with_data(
            "",
            &(data_array("Int32", "r", 1, "1 2\n") + &data_array("Int32", "r", 1, "1 2\n")),
        ));
        assert_eq!(m, "piece 0: a second cell data array named 'r'");
    }

    /// Two pieces: their data concatenates; a piece lacking an array, or with one the first
    /// lacks, is refused naming it.
    #[test]
    fn pieces_concatenate_their_data_and_must_carry_the_same_arrays() {
        // `first` with the piece of `second` appended after its own.
        let appended = |first: &str, second: &str| {
            let piece = &second
                [second.find("<Piece").unwrap()..second.find("</UnstructuredGrid>").unwrap()];
            first.replacen(
                "</UnstructuredGrid>",
                &format!("{piece}</UnstructuredGrid>"),
                1,
            )
        };
        let one = with_data(&data_array("Int32", "p", 1, "1 2 3 4\n"), "");
        let raw = both(&appended(&one, &one));
        assert_eq!(
            raw.attributes.get("p", Location::Vertices).unwrap().values,
            Values::I32(vec![1, 2, 3, 4, 1, 2, 3, 4])
        );
        let other = with_data(&data_array("Int32", "q", 1, "1 2 3 4\n"), "");
        let (_, m) = refused_alike(&appended(&one, &other));
        assert!(
            m.contains("piece 1 has point data array 'q', which piece 0 lacks"),
            "{m}"
        );
        let bare = triangle_and_edge("0 1 2\n1 3\n", "3\n5\n", "5\n3\n");
        let lacking = appended(&one, &bare);
        let (_, m) = refused_alike(&lacking);
        assert!(
            m.contains("piece 1 lacks point data array 'p', which piece 0 has"),
            "{m}"
        );
    }

    /// Our writer's output (base64, read by vtkio) gives back every attribute bit for bit,
    /// and a UInt64 above 2^63 written by vtkio is refused naming the array.
    #[test]
    fn written_data_reads_back_through_vtkio_and_huge_uint64_is_refused() {
        let text = with_data(
            &data_array("Float32", "v", 2, "0.1 -0 1e-45 inf 3 4 nan 6\n"),
            &data_array("Int64", "r", 1, "-9223372036854775808 5\n"),
        );
        let raw = both_but_nan(&text);
        let mut out = Vec::new();
        write(&raw, &mut out).unwrap();
        assert!(String::from_utf8_lossy(&out).contains("format=\"binary\""));
        let back = parse(&out).unwrap();
        assert!(back.attributes.bits_eq(&raw.attributes));
        let mut vtk = Vtk::parse_xml(&out[..]).unwrap();
        let DataSet::UnstructuredGrid { pieces, .. } = &mut vtk.data else {
            panic!()
        };
        let Piece::Inline(p) = &mut pieces[0] else {
            panic!()
        };
        p.data.cell = vec![vtkio::model::Attribute::DataArray(
            vtkio::model::DataArray {
                name: "huge".into(),
                elem: ElementType::Generic(1),
                data: IOBuffer::U64(vec![1, 1 << 63]),
            },
        )];
        let mut huge = Vec::new();
        vtk.write_xml(&mut huge).unwrap();
        let (line, m) = match parse(&huge) {
            Err((line, ReadErrorKind::Syntax(m))) => (line, m),
            other => panic!("{other:?}"),
        };
        assert!(line > 0);
        assert!(
            m.contains("cell data array 'huge': a UInt64 above 2^63 cannot be held"),
            "{m}"
        );
    }

    /// Our reader's result on an ASCII file (NaNs allowed: attributes compared bit for bit).
    fn both_but_nan(text: &str) -> RawInput {
        let Ok(ascii::Taken::Yes(ours)) = ascii::parse(text.as_bytes()) else {
            panic!("not read")
        };
        let theirs = parse_vtkio(text.as_bytes()).unwrap();
        assert!(ours.attributes.bits_eq(&theirs.attributes));
        ours
    }

    /// Standard base64 with padding (for hand-made appended data).
    fn base64(bytes: &[u8]) -> String {
        const A: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
        let mut out = String::new();
        for c in bytes.chunks(3) {
            let n = (u32::from(c[0]) << 16)
                | (u32::from(*c.get(1).unwrap_or(&0)) << 8)
                | u32::from(*c.get(2).unwrap_or(&0));
            for k in 0..4 {
                out.push(if k <= c.len() {
                    A[(n >> (18 - 6 * k) & 63) as usize] as char
                } else {
                    '='
                });
            }
        }
        out
    }

    /// Appended base64 data goes through vtkio: point and cell data come back in their own
    /// types. (Raw appended data is not read: vtkio is built without its `binary` feature.)
    #[test]
    fn appended_data_is_read_in_its_own_types() {
        let mut blob = String::new();
        let mut offsets = Vec::new();
        let mut block = |bytes: Vec<u8>| {
            offsets.push(blob.len());
            let mut b = (bytes.len() as u32).to_le_bytes().to_vec();
            b.extend_from_slice(&bytes);
            blob += &base64(&b);
        };
        let le = |xs: &[f64]| xs.iter().flat_map(|x| x.to_le_bytes()).collect::<Vec<u8>>();
        block(le(&[1.5, f64::NAN, -2.0]));
        block(le(&[0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0]));
        block([0i32, 1, 2].iter().flat_map(|x| x.to_le_bytes()).collect());
        block(3i32.to_le_bytes().to_vec());
        block(vec![5u8]);
        block(vec![(-3i8) as u8]);
        let arr = |ty: &str, name: &str, comps: usize, k: usize| {
            format!(
                "<DataArray type=\"{ty}\" Name=\"{name}\" NumberOfComponents=\"{comps}\" \
                 format=\"appended\" offset=\"{}\"/>\n",
                offsets[k]
            )
        };
        let mut file = format!(
            "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" \
             byte_order=\"LittleEndian\" header_type=\"UInt32\">\n<UnstructuredGrid>\n\
             <Piece NumberOfPoints=\"3\" NumberOfCells=\"1\">\n<PointData>\n{}</PointData>\n\
             <Points>\n{}</Points>\n<Cells>\n{}{}{}</Cells>\n<CellData>\n{}</CellData>\n</Piece>\n\
             </UnstructuredGrid>\n<AppendedData encoding=\"base64\">\n_",
            arr("Float64", "t", 1, 0),
            arr("Float64", "Points", 3, 1),
            arr("Int32", "connectivity", 1, 2),
            arr("Int32", "offsets", 1, 3),
            arr("UInt8", "types", 1, 4),
            arr("Int8", "region", 1, 5),
        )
        .into_bytes();
        file.extend_from_slice(blob.as_bytes());
        file.extend_from_slice(b"\n</AppendedData>\n</VTKFile>\n");
        assert!(matches!(ascii::parse(&file), Ok(ascii::Taken::No)));
        let raw = parse(&file).unwrap();
        assert_eq!(raw.simplex(0), [0, 1, 2]);
        let t = raw.attributes.get("t", Location::Vertices).unwrap();
        assert!(t.values.bits_eq(&Values::F64(vec![1.5, f64::NAN, -2.0])));
        assert_eq!(
            raw.attributes
                .get("region", Location::Listed)
                .unwrap()
                .values,
            Values::I32(vec![-3])
        );
    }
}
