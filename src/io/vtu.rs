//! VTK XML unstructured grids (`.vtu`), read and written with the `vtkio` crate (XML parsing,
//! base64 and zlib-compressed data arrays); this module maps its cells to simplices.
//!
//! Reading: every piece's points (3 coordinates, any numeric type, widened to `f64`) and cells.
//! Pieces are concatenated, each piece's ids shifted by the points before it. Cell types 1
//! (vertex), 3 (line), 5 (triangle) and 10 (tetrahedron) are simplices; any other (quad,
//! polygon, hexahedron, wedge, higher order...) is refused naming the cell's index, and so is a
//! cell whose id count does not match its type. vtkio reports XML errors without a line.
//! Pieces stored in other files (parallel formats) are not read. vtkio panics on some malformed
//! binary arrays; the panic is caught and reported as an error (one line: the panic hook stays
//! silent for it, [`crate::error::caught_quietly`]). vtkio's own arrays are allocated
//! infallibly: their peak is probed before parsing, ours are reserved fallibly; memory that
//! cannot be had is [`ReadErrorKind::TooLarge`].
//!
//! Writing: one piece, `Float64` points (3 per vertex, fewer padded with zeros, zeros without
//! coordinates), `connectivity`, `offsets` and `types` in listing order, as vtkio encodes them
//! (base64 binary, so coordinates are exact). Holds vertices, edges, triangles, tetrahedra.

use vtkio::model::{
    Attributes, ByteOrder, CellType, Cells, DataSet, IOBuffer, Piece, UnstructuredGridPiece,
    Version, VertexNumbers, Vtk,
};

use super::write::{check_coord_dim, check_max_len, vertex_count};
use super::{Coords, RawInput, ReadErrorKind, echo, no_room, syntax};
use crate::complex::table::{self, headroom};
use crate::error::caught_quietly;

/// vtkio's parse peak per byte of file, probed before it starts: 5.9 measured on ASCII data
/// arrays of short lines (it holds the file, each array's text as a string and the typed
/// arrays grown by doubling), 2.9 on base64 binary ones (scripts/read-peak.sh,
/// docs/benchmarks.md "Reading").
const VTKIO_PEAK_PER_BYTE: usize = 6;

type Res<T> = Result<T, (u32, ReadErrorKind)>;

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

/// One piece's points and cells appended to `raw` (its ids shifted by `base`).
fn add_piece(
    p: UnstructuredGridPiece,
    piece: usize,
    raw: &mut RawInput,
    data: &mut Vec<f64>,
) -> Res<()> {
    let base = data.len() / 3;
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
                "piece {piece}, cell #{i} of type {t:?} has {} ids, expected {len}",
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
    Ok(())
}

/// Parses a `.vtu` file.
pub fn parse(bytes: &[u8]) -> Res<RawInput> {
    // vtkio's arrays are allocated infallibly: its peak is probed first (address space, see
    // `headroom`), so that a file too large for memory is refused rather than an abort.
    headroom(bytes.len().saturating_mul(VTKIO_PEAK_PER_BYTE))
        .map_err(|b| (0, no_room("reading VTU")(b)))?;
    // vtkio 0.7.0-rc2 slices out of range on some malformed binary arrays (found by fuzzing):
    // its panic is caught here and reported as a parse error, without the panic hook's report.
    let parsed = caught_quietly(|| Vtk::parse_xml(bytes))
        .map_err(|_| err("VTU: malformed data array (vtkio failed on it: a caught panic)"))?;
    let vtk = parsed.map_err(|e| err(format!("VTU: {}", echo(e.to_string()))))?;
    let DataSet::UnstructuredGrid { pieces, .. } = vtk.data else {
        return Err(err(
            "not an UnstructuredGrid (only unstructured grids are read)",
        ));
    };
    let mut raw = RawInput::new();
    let mut data = Vec::new();
    for (i, piece) in pieces.into_iter().enumerate() {
        match piece {
            Piece::Inline(p) => add_piece(*p, i, &mut raw, &mut data)?,
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
    Ok(raw)
}

/// Writes `raw` as a `.vtu` file.
pub(crate) fn write(raw: &RawInput, out: &mut Vec<u8>) -> Result<(), String> {
    check_max_len(
        raw,
        4,
        "vertices, edges, triangles and tetrahedra (use .simplices)",
    )?;
    check_coord_dim(raw, 3)?;
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
        data: Attributes::new(),
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
