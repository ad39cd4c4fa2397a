//! Legacy VTK (`.vtk`) unstructured grids, ASCII and BINARY, read and written here.
//!
//! Own code rather than the `vtkio` crate (used for `.vtu`): vtkio 0.6's legacy parser (nom 3)
//! reserves memory from the counts a header declares (`POINTS 4000000000 double` aborts the
//! process), and its errors carry no line; this reader caps every reservation by the bytes left,
//! makes it fallibly (memory that cannot be had is [`ReadErrorKind::TooLarge`]) and names lines.
//! Cells are streamed into the simplex list as read: version 4's lists and version 5's
//! connectivity (its offsets are read first, as numbers); cell types are checked, not kept.
//!
//! Reading (`# vtk DataFile Version` 2.0 to 5.1):
//! ```text
//! # vtk DataFile Version 4.2
//! any title
//! ASCII | BINARY
//! DATASET UNSTRUCTURED_GRID
//! POINTS n float|double          3n numbers (z is kept, so coordinates have dimension 3)
//! CELLS m size                   m lists "k id ... id" (up to version 4)
//! CELLS m+1 c                    version 5: OFFSETS <type> (m+1 ints), CONNECTIVITY <type> (c ints)
//! CELL_TYPES m                   m ints
//! ```
//! * `METADATA` blocks (up to a blank line) are skipped; a `FIELD` before `CELL_TYPES` (data on
//!   the whole dataset, which attributes cannot hold) is refused. After `CELL_TYPES`,
//!   `POINT_DATA`/`CELL_DATA` arrays are attributes (`read_data`). A NaN is read from `nan`,
//!   `-nan` or `NaN` (any case) as a NaN; ASCII text holds neither a NaN's sign nor its payload,
//!   so an ASCII file gives the one quiet NaN where the writer had any NaN (every other number
//!   reads back bit for bit), while BINARY keeps every bit.
//! * Cell types 1 (vertex), 3 (line), 5 (triangle) and 10 (tetrahedron) are simplices; any other
//!   type (quad, polygon, hexahedron, wedge, quadratic cells...) is refused naming the cell's
//!   index and line, and so is a cell whose id count does not match its type.
//! * BINARY data is big-endian (`float`, `double`, `int`, `vtktypeint32`, `vtktypeint64`, ...),
//!   each block starting after the newline of its keyword line; errors inside a binary block name
//!   that keyword's line.
//! * Ids are 0-based; negative ids are [`ReadErrorKind::NegativeId`]. Only `DATASET
//!   UNSTRUCTURED_GRID` is read.
//!
//! Writing: version 4.2 layout, `POINTS n double` (3 per vertex, fewer padded with zeros, zeros
//! without coordinates), `CELLS`, `CELL_TYPES`, every simplex in listing order (vertices,
//! edges, triangles, tetrahedra), then the optional point and cell fields as `int` scalars
//! ([`write_with_fields`]). ASCII numbers are the shortest decimals that read back bit for bit.

use super::bytes::Input;
use super::write::{check_fits, push_f64, push_ids, vertex_count};
use super::{
    Coords, IntError, RawInput, ReadErrorKind, echo, no_room, parse_integer, syntax,
    try_with_capacity,
};
use super::{Float, parse_real};
use crate::complex::attributes::MAX_COMPONENTS;
use crate::complex::{Attribute, Location, Values, table};
use crate::io::{Res, SimplexCodes};

/// VTK's cell types of the four simplices.
const CELL_TYPES: SimplexCodes = SimplexCodes([1, 3, 5, 10]);

/// VTK's cell type of a simplex with `len` vertices.
fn cell_type(len: usize) -> u8 {
    CELL_TYPES.of_len(len) as u8
}

/// The number of vertices of a simplex cell type, or the type's name for refusals.
fn simplex_len(t: i64) -> Result<usize, &'static str> {
    CELL_TYPES.len_of(t).ok_or(match t {
        2 => "poly-vertex",
        4 => "poly-line",
        6 => "triangle strip",
        7 => "polygon",
        8 => "pixel",
        9 => "quad",
        11 => "voxel",
        12 => "hexahedron",
        13 => "wedge",
        14 => "pyramid",
        21..=37 => "quadratic or higher-order cell",
        _ => "unknown type",
    })
}

/// A VTK data type name's byte size and whether it is a float.
fn data_type(ty: &str, line: u32) -> Res<(usize, bool)> {
    Ok(match ty.to_ascii_lowercase().as_str() {
        "float" => (4, true),
        "double" => (8, true),
        "char" | "unsigned_char" | "bit" => (1, false),
        "short" | "unsigned_short" => (2, false),
        "int" | "unsigned_int" | "vtktypeint32" | "vtktypeuint32" => (4, false),
        "long" | "unsigned_long" | "vtktypeint64" | "vtktypeuint64" | "vtkidtype" => (8, false),
        _ => return Err((line, syntax(format!("unknown VTK data type '{ty}'")))),
    })
}

impl<'a> Input<'a> {
    /// `n` numbers of `ty` (a VTK data type name), collected.
    fn numbers(&mut self, n: usize, ty: &str, line: u32, what: &str) -> Res<Vec<f64>> {
        let (size, _) = data_type(ty, line)?;
        let mut out =
            try_with_capacity(n.min(self.left() / size.min(2) + 1), "an array of numbers")
                .map_err(|k| (line, k))?;
        self.each_number(n, ty, line, what, |_, x| {
            table::try_push(&mut out, x).map_err(|b| (line, no_room("an array of numbers")(b)))
        })?;
        Ok(out)
    }

    /// Hands `n` numbers of `ty` to `f` one by one (with their index), so that a reader keeps
    /// only what it needs of them: ASCII tokens, or big-endian binary starting after the
    /// newline that ends the keyword line `line`.
    fn each_number(
        &mut self,
        n: usize,
        ty: &str,
        line: u32,
        what: &str,
        mut f: impl FnMut(usize, f64) -> Res<()>,
    ) -> Res<()> {
        let (size, float) = data_type(ty, line)?;
        if self.binary {
            return self.binary_numbers(n, ty, size, float, line, what, f);
        }
        for i in 0..n {
            let Some((tok, l)) = self.token() else {
                return Err((
                    self.line.max(1),
                    syntax(format!("file ends after {i} of the {n} {what}")),
                ));
            };
            let x = if float {
                // The shared check: a value the declared type holds only as inf or 0 is refused.
                let f = if size == 4 { Float::F32 } else { Float::F64 };
                let what = format!("one of the {what}, declared {ty}");
                Some(parse_real(tok, &what, f).map_err(|k| (l, k))?)
            } else {
                match parse_integer(tok) {
                    Ok(v) => Some(v as f64),
                    Err(IntError::OutOfRange) => Some(f64::INFINITY),
                    Err(_) => None,
                }
            };
            f(
                i,
                x.ok_or_else(|| (l, syntax(format!("'{tok}' is not a {ty} among the {what}"))))?,
            )?;
        }
        Ok(())
    }

    /// Hands `n` ASCII tokens to `f` with their lines; the file ending first is an error.
    fn each_token(
        &mut self,
        n: usize,
        what: &str,
        mut f: impl FnMut(&'a str, u32) -> Res<()>,
    ) -> Res<()> {
        for i in 0..n {
            let (tok, l) = self.token().ok_or_else(|| {
                (
                    self.line.max(1),
                    syntax(format!("file ends after {i} of the {n} {what}")),
                )
            })?;
            f(tok, l)?;
        }
        Ok(())
    }

    /// The `n × size` bytes of a binary block, which starts after the newline that ends the
    /// keyword line `line`; consumed.
    fn binary_block(
        &mut self,
        n: usize,
        size: usize,
        ty: &str,
        line: u32,
        what: &str,
    ) -> Res<&'a [u8]> {
        self.rest_of_line();
        let bytes = n
            .checked_mul(size)
            .filter(|&b| b <= self.left())
            .ok_or_else(|| {
                (
                    line,
                    syntax(format!(
                        "{n} binary {ty} {what} declared but only {} bytes are left",
                        self.left()
                    )),
                )
            })?;
        let block = &self.b[self.pos..self.pos + bytes];
        self.pos += bytes;
        Ok(block)
    }

    #[allow(clippy::too_many_arguments)]
    fn binary_numbers(
        &mut self,
        n: usize,
        ty: &str,
        size: usize,
        float: bool,
        line: u32,
        what: &str,
        mut f: impl FnMut(usize, f64) -> Res<()>,
    ) -> Res<()> {
        let block = self.binary_block(n, size, ty, line, what)?;
        let signed = !ty.starts_with("unsigned") && !ty.contains("uint");
        for (i, c) in block.chunks_exact(size).enumerate() {
            let x = match (size, float) {
                (4, true) => f64::from(f32::from_be_bytes(c.try_into().unwrap())),
                (8, true) => f64::from_be_bytes(c.try_into().unwrap()),
                _ => be_integer(c, signed) as f64,
            };
            f(i, x)?;
        }
        Ok(())
    }
}

/// A big-endian integer of 1, 2, 4 or 8 bytes, exactly.
fn be_integer(c: &[u8], signed: bool) -> i128 {
    let mut b = [0u8; 8];
    b[8 - c.len()..].copy_from_slice(c);
    let unsigned = u64::from_be_bytes(b);
    let bits = 8 * c.len() as u32;
    if signed && unsigned >> (bits - 1) & 1 == 1 {
        i128::from(unsigned) - (1i128 << bits)
    } else {
        i128::from(unsigned)
    }
}

/// An id read as a number, as a vertex id.
fn vertex_id(x: f64, line: u32) -> Res<u32> {
    if x < 0.0 {
        return Err((line, ReadErrorKind::NegativeId(x as i64)));
    }
    if x.fract() != 0.0 || x > f64::from(u32::MAX) {
        return Err((
            line,
            syntax(format!("vertex id {x} does not fit in 32 bits")),
        ));
    }
    Ok(x as u32)
}

/// The cells, pushed into a fresh [`RawInput`] (each on the `CELLS` line), from the version 4
/// `CELLS m size` layout or version 5's.
fn read_cells(inp: &mut Input, version5: bool, line: u32) -> Res<RawInput> {
    let a = inp.count("CELLS")?;
    let b = inp.count("CELLS")?;
    let mut raw = RawInput::new();
    // Exact reservations (fallible) from the declared counts, capped by what the bytes left can
    // hold (each entry takes at least 2 bytes in ASCII, 1 in binary).
    let cap = inp.left() / if inp.binary { 1 } else { 2 } + 1;
    if version5 {
        read_cells5(inp, a, b, line, &mut raw)?;
    } else {
        raw.try_reserve(a.min(cap), b.saturating_sub(a).min(cap))
            .map_err(|k| (line, k))?;
        read_cells4(inp, a, b, line, &mut raw)?;
    }
    Ok(raw)
}

/// Version 5: `OFFSETS <type>` (`a` ints) then `CONNECTIVITY <type>` (`b` ints); cell `i` is
/// the connectivity entries `offsets[i]..offsets[i + 1]`. The connectivity is streamed into
/// `raw` (only the cells before the first bad offset pair are kept); errors come in the order
/// the whole block gives them: a malformed number first, then the first cell whose offsets or
/// ids are wrong.
fn read_cells5(inp: &mut Input, a: usize, b: usize, line: u32, raw: &mut RawInput) -> Res<()> {
    let (kw, l) = inp.expect_token("OFFSETS")?;
    if !kw.eq_ignore_ascii_case("OFFSETS") {
        return Err((
            l,
            syntax(format!("expected OFFSETS after CELLS, found '{kw}'")),
        ));
    }
    let (ty, _) = inp.expect_token("the OFFSETS data type")?;
    let offsets = inp.numbers(a, ty, l, "offsets")?;
    // The cells before the first whose offsets are out of order or range: consecutive ranges.
    let bad_offsets = offsets
        .windows(2)
        .position(|w| !(0.0 <= w[0] && w[0] <= w[1] && w[1] <= b as f64));
    // Cells cover the connectivity exactly (as VTK's own reader requires): entries before the
    // first offset or after the last would be dropped silently.
    if bad_offsets.is_none()
        && let (Some(&first), Some(&last)) = (offsets.first(), offsets.last())
        && (first != 0.0 || last != b as f64)
    {
        return Err((
            l,
            syntax(format!(
                "OFFSETS run from {first} to {last}, but they must run from 0 to the {b} \
                 CONNECTIVITY entries (entries outside the cells would be dropped)"
            )),
        ));
    }
    let good = &offsets[..bad_offsets.map_or(offsets.len(), |i| i + 1)];
    let (start, end) = match good {
        [first, .., last] => (*first as usize, *last as usize),
        _ => (0, 0),
    };
    let (kw, l2) = inp.expect_token("CONNECTIVITY")?;
    if !kw.eq_ignore_ascii_case("CONNECTIVITY") {
        return Err((l2, syntax(format!("expected CONNECTIVITY, found '{kw}'"))));
    }
    let (ty, _) = inp.expect_token("the CONNECTIVITY data type")?;
    let cells = good.len().saturating_sub(1);
    raw.try_reserve(cells, end - start).map_err(|k| (l, k))?;
    let mut bad_id = None;
    inp.each_number(b, ty, l2, "connectivity entries", |i, x| {
        if (start..end).contains(&i) && bad_id.is_none() {
            match vertex_id(x, l2) {
                Ok(v) => raw.ids.push(v),
                Err(e) => bad_id = Some(e),
            }
        }
        Ok(())
    })?;
    // A bad id lies in a cell before the first bad offset pair, so it is reported first.
    if let Some(e) = bad_id {
        return Err(e);
    }
    if let Some(i) = bad_offsets {
        let (s, e) = (offsets[i], offsets[i + 1]);
        return Err((
            l,
            syntax(format!("cell #{i}: offsets {s}..{e} out of order or range")),
        ));
    }
    for &o in good.iter().skip(1) {
        raw.offsets.push(o as usize - start);
        raw.lines.push(line);
    }
    Ok(())
}

/// Version 4: `CELLS a b`, then `b` ints making `a` lists "k id ... id". Streams the entries
/// straight into `raw`; a structural error is kept until every entry has been read, so that a
/// malformed or missing entry later in the block is reported first, as when the whole block
/// was read before being split into cells.
fn read_cells4(inp: &mut Input, a: usize, b: usize, line: u32, raw: &mut RawInput) -> Res<()> {
    let ends_inside = |i: usize| {
        (
            line,
            syntax(format!("CELLS size {b} ends inside cell #{i}")),
        )
    };
    let mut pending: Option<(u32, ReadErrorKind)> = None;
    // The cell being read: its index, the ids it still expects, its first bad id.
    let mut cell = 0usize;
    let mut left = 0usize;
    let mut in_cell = false;
    let mut bad_id: Option<(u32, ReadErrorKind)> = None;
    let mut used = 0usize;
    inp.each_number(b, "int", line, "CELLS entries", |_, x| {
        if pending.is_some() {
            return Ok(());
        }
        if in_cell {
            match vertex_id(x, line) {
                Ok(v) => table::try_push(&mut raw.ids, v)
                    .map_err(|b| (line, no_room("the simplices' vertex ids")(b)))?,
                Err(e) => {
                    bad_id.get_or_insert(e);
                }
            }
            left -= 1;
        } else if cell < a {
            // A huge or non-finite length saturates.
            left = x.max(0.0) as usize;
            in_cell = true;
        } else {
            return Ok(());
        }
        used += 1;
        if in_cell && left == 0 {
            if let Some(e) = bad_id.take() {
                pending = Some(e);
            }
            table::try_push(&mut raw.offsets, raw.ids.len())
                .map_err(|b| (line, no_room("the simplex offsets")(b)))?;
            table::try_push(&mut raw.lines, line)
                .map_err(|b| (line, no_room("the simplices' line numbers")(b)))?;
            in_cell = false;
            cell += 1;
        }
        Ok(())
    })?;
    if let Some(e) = pending {
        return Err(e);
    }
    if in_cell || cell < a {
        return Err(ends_inside(cell));
    }
    if used != b {
        return Err((
            line,
            syntax(format!("CELLS size {b} but the {a} cells use {used}")),
        ));
    }
    Ok(())
}

/// The first cell of `raw` whose VTK type `t` (cell `i`) is no simplex or does not match its
/// id count, as the error to report.
/// With `polygons` (for [`super::ReadOptions::triangulate`]), a polygon (type 7, 3 ids or
/// more) or quad (type 9, 4 ids) is kept: `Ok(true)`.
fn check_type(
    raw: &RawInput,
    i: usize,
    t: f64,
    (types_line, cells_line): (u32, u32),
    polygons: bool,
) -> Res<bool> {
    let have = raw.simplex(i).len();
    if polygons && ((t == 7.0 && have >= 3) || (t == 9.0 && have == 4)) {
        return Ok(true);
    }
    let len = simplex_len(t as i64).map_err(|name| {
        (
            types_line,
            syntax(format!(
                "cell #{i} has VTK type {t} ({name}), which is not a simplex"
            )),
        )
    })?;
    if have != len {
        return Err((
            cells_line,
            syntax(format!(
                "cell #{i} of VTK type {t} has {have} ids, expected {len}"
            )),
        ));
    }
    Ok(false)
}

/// Parses a legacy VTK unstructured grid.
pub fn parse(bytes: &[u8]) -> Res<RawInput> {
    parse_keeping(bytes, false)
}

/// [`parse`], keeping polygon (7) and quad (9) cells as polygons when `polygons` (for
/// [`super::ReadOptions::triangulate`]).
pub(crate) fn parse_keeping(bytes: &[u8], polygons: bool) -> Res<RawInput> {
    let mut inp = Input::new(bytes);
    let first = inp.rest_of_line();
    let first = String::from_utf8_lossy(first);
    let version = first
        .trim()
        .strip_prefix("# vtk DataFile Version")
        .map(str::trim)
        .ok_or_else(|| {
            (
                1,
                syntax("expected '# vtk DataFile Version x.y' on the first line"),
            )
        })?;
    // Versions 1.0 to 5.1 (5.1 brought OFFSETS and CONNECTIVITY); any other is refused
    // rather than read by guesswork.
    let (major, minor) = version
        .split_once('.')
        .and_then(|(a, b)| Some((a.parse::<u32>().ok()?, b.parse::<u32>().ok()?)))
        .filter(|&(a, b)| (1..=4).contains(&a) || (a == 5 && b <= 1))
        .ok_or_else(|| {
            (
                1,
                syntax(format!(
                    "unsupported legacy VTK version '{}' (versions 1.0 to 5.1 are read)",
                    echo(version)
                )),
            )
        })?;
    let version5 = (major, minor) >= (5, 0);
    inp.rest_of_line(); // title
    let (mode, l) = inp.expect_token("ASCII or BINARY")?;
    inp.binary = match mode.to_ascii_uppercase().as_str() {
        "ASCII" => false,
        "BINARY" => true,
        _ => {
            return Err((
                l,
                syntax(format!("expected ASCII or BINARY, found '{mode}'")),
            ));
        }
    };
    let (kw, l) = inp.expect_token("DATASET")?;
    let (ds, _) = inp.expect_token("the dataset type")?;
    if !kw.eq_ignore_ascii_case("DATASET") || !ds.eq_ignore_ascii_case("UNSTRUCTURED_GRID") {
        return Err((
            l,
            syntax(format!(
                "expected 'DATASET UNSTRUCTURED_GRID', found '{kw} {ds}' (only unstructured grids are read)"
            )),
        ));
    }
    read_sections(&mut inp, version5, polygons)
}

/// The sections after the header, up to `CELL_TYPES`, checked against each other. Cell types
/// are checked as they are read, not kept.
fn read_sections(inp: &mut Input, version5: bool, polygons: bool) -> Res<RawInput> {
    let mut points: Option<Vec<f64>> = None;
    let mut cells: Option<(RawInput, u32)> = None;
    let (m, types_line, bad_type) = loop {
        let (kw, l) = inp.expect_token("POINTS, CELLS or CELL_TYPES")?;
        match kw.to_ascii_uppercase().as_str() {
            "POINTS" => {
                let n = inp.count("POINTS")?;
                let (ty, _) = inp.expect_token("the POINTS data type")?;
                let n3 = n
                    .checked_mul(3)
                    .ok_or((l, syntax("POINTS count too large")))?;
                points.take(); // a repeated section replaces the first: free it first
                points = Some(inp.numbers(n3, ty, l, "point coordinates")?);
            }
            "METADATA" => {
                // Skipped up to the blank line that ends it.
                inp.rest_of_line();
                while inp.left() > 0 && !inp.rest_of_line().trim_ascii().is_empty() {}
            }
            "CELLS" => {
                cells.take();
                cells = Some((read_cells(inp, version5, l)?, l));
            }
            "CELL_TYPES" => {
                let m = inp.count("CELL_TYPES")?;
                let mut bad = None;
                inp.each_number(m, "int", l, "cell types", |i, t| {
                    if bad.is_none()
                        && let Some((raw, cells_line)) = &mut cells
                        && i < raw.simplex_count()
                    {
                        match check_type(raw, i, t, (l, *cells_line), polygons) {
                            Ok(true) => table::try_push(&mut raw.polygons.at, i)
                                .map_err(|b| (l, no_room("the polygons' indices")(b)))?,
                            Ok(false) => {}
                            Err(e) => bad = Some(e),
                        }
                    }
                    Ok(())
                })?;
                break (m, l, bad);
            }
            "FIELD" => {
                return Err((l, syntax("FIELD data before CELL_TYPES is not supported")));
            }
            _ => {
                return Err((
                    l,
                    syntax(format!(
                        "unexpected '{kw}' (expected POINTS, CELLS or CELL_TYPES)"
                    )),
                ));
            }
        }
    };
    let points = points.ok_or((types_line, syntax("no POINTS section")))?;
    let (mut raw, _) = cells.ok_or((types_line, syntax("CELL_TYPES without CELLS")))?;
    if m != raw.simplex_count() {
        return Err((
            types_line,
            syntax(format!("{m} cell types for {} cells", raw.simplex_count())),
        ));
    }
    if let Some(e) = bad_type {
        return Err(e);
    }
    raw.vertex_count =
        Some(u32::try_from(points.len() / 3).map_err(|_| (0, syntax("more than 2^32 points")))?);
    raw.coords = Some(Coords {
        dim: 3,
        data: points,
    });
    read_data(inp, &mut raw)?;
    Ok(raw)
}

/// The point and cell data after `CELL_TYPES`: `POINT_DATA n` and `CELL_DATA m` sections of
/// `SCALARS` (with their `LOOKUP_TABLE` line), `VECTORS`, `NORMALS`, `TENSORS`,
/// `TEXTURE_COORDINATES`, `COLOR_SCALARS` and `FIELD` arrays, each kept as an attribute of its
/// name on the vertices or the listed simplices ([`crate::complex::attributes`]). `METADATA`
/// blocks are skipped; anything else (a `LOOKUP_TABLE` definition, another dataset section) is
/// an error naming it.
fn read_data(inp: &mut Input, raw: &mut RawInput) -> Res<()> {
    let n = raw.vertex_count.unwrap_or(0) as usize;
    let m = raw.simplex_count();
    let mut at: Option<(Location, usize)> = None;
    while let Some((kw, l)) = inp.token() {
        let upper = kw.to_ascii_uppercase();
        match upper.as_str() {
            "POINT_DATA" | "CELL_DATA" => {
                let count = inp.count(kw)?;
                let (location, want, what) = if upper == "POINT_DATA" {
                    (Location::Vertices, n, "points")
                } else {
                    (Location::Listed, m, "cells")
                };
                if count != want {
                    return Err((l, syntax(format!("{kw} {count} for {want} {what}"))));
                }
                at = Some((location, want));
            }
            "METADATA" => {
                inp.rest_of_line();
                while inp.left() > 0 && !inp.rest_of_line().trim_ascii().is_empty() {}
            }
            _ => {
                let Some((location, count)) = at else {
                    return Err((
                        l,
                        syntax(format!(
                            "unexpected '{}' after CELL_TYPES (expected POINT_DATA or CELL_DATA)",
                            echo(kw)
                        )),
                    ));
                };
                for a in data_arrays(inp, &upper, kw, l, location, count)? {
                    if raw.attributes.get(&a.name, location).is_some() {
                        return Err((
                            l,
                            syntax(format!(
                                "a second array named '{}' in the {} data",
                                echo(&a.name),
                                if location == Location::Vertices {
                                    "point"
                                } else {
                                    "cell"
                                }
                            )),
                        ));
                    }
                    raw.attributes.insert(a);
                }
            }
        }
    }
    Ok(())
}

/// One data section's arrays (`FIELD` holds several), `count` elements each.
fn data_arrays(
    inp: &mut Input,
    upper: &str,
    kw: &str,
    l: u32,
    location: Location,
    count: usize,
) -> Res<Vec<Attribute>> {
    let d = DataSection { l, location, count };
    let (name, _) = inp.expect_token(&format!("the name after {kw}"))?;
    let name = name.to_string();
    Ok(match upper {
        "SCALARS" => {
            let (ty, components) = d.scalars_header(inp, &name)?;
            vec![d.array(inp, &name, &ty, components, "SCALARS")?]
        }
        "VECTORS" | "NORMALS" | "TENSORS" => {
            let (ty, _) = inp.expect_token(&format!("the {kw} data type"))?;
            let ty = ty.to_string();
            let k = if upper == "TENSORS" { 9 } else { 3 };
            vec![d.array(inp, &name, &ty, k, kw)?]
        }
        "TEXTURE_COORDINATES" => {
            let k = inp.count("TEXTURE_COORDINATES")?;
            let (ty, _) = inp.expect_token("the TEXTURE_COORDINATES data type")?;
            let ty = ty.to_string();
            vec![d.array(inp, &name, &ty, k, kw)?]
        }
        "COLOR_SCALARS" => {
            let k = inp.count("COLOR_SCALARS")?;
            let ty = if inp.binary { "unsigned_char" } else { "float" };
            vec![d.array(inp, &name, ty, k, kw)?]
        }
        "FIELD" => d.field_arrays(inp)?,
        _ => {
            return Err((
                l,
                syntax(format!(
                    "unsupported data section '{}' (SCALARS, VECTORS, NORMALS, TENSORS, \
                     TEXTURE_COORDINATES, COLOR_SCALARS and FIELD are read)",
                    echo(kw)
                )),
            ));
        }
    })
}

/// One POINT_DATA or CELL_DATA array's context: its keyword's line, where its elements are and
/// how many.
struct DataSection {
    l: u32,
    location: Location,
    count: usize,
}

impl DataSection {
    /// An array of `components` numbers of VTK type `ty` per element, `name`d.
    fn array(
        &self,
        inp: &mut Input,
        name: &str,
        ty: &str,
        components: usize,
        what: &str,
    ) -> Res<Attribute> {
        let l = self.l;
        if !(1..=MAX_COMPONENTS).contains(&components) {
            return Err((
                l,
                syntax(format!(
                    "array '{}' has {components} components; 1 to {MAX_COMPONENTS} are held",
                    echo(name)
                )),
            ));
        }
        let total = self
            .count
            .checked_mul(components)
            .ok_or((l, syntax("array too large")))?;
        let values = inp.values(total, ty, l, &format!("values of {what} '{}'", echo(name)))?;
        Ok(Attribute {
            name: name.to_string(),
            location: self.location,
            components,
            values,
        })
    }

    /// A SCALARS array's header after its name: the data type, an optional component count
    /// (1 when absent) and the LOOKUP_TABLE line.
    fn scalars_header(&self, inp: &mut Input, name: &str) -> Res<(String, usize)> {
        let l = self.l;
        let (ty, _) = inp.expect_token("the SCALARS data type")?;
        let ty = ty.to_string();
        let rest = String::from_utf8_lossy(inp.rest_of_line())
            .trim()
            .to_string();
        let components = if rest.is_empty() {
            1
        } else {
            rest.parse::<usize>().map_err(|_| {
                (
                    l,
                    syntax(format!(
                        "SCALARS '{}': '{}' is not a component count",
                        echo(name),
                        echo(&rest)
                    )),
                )
            })?
        };
        let (lt, ll) = inp.expect_token("LOOKUP_TABLE")?;
        if !lt.eq_ignore_ascii_case("LOOKUP_TABLE") {
            return Err((
                ll,
                syntax(format!(
                    "expected LOOKUP_TABLE after SCALARS '{}', found '{}'",
                    echo(name),
                    echo(lt)
                )),
            ));
        }
        inp.expect_token("the lookup table's name")?;
        Ok((ty, components))
    }

    /// A FIELD's arrays (after its name): each with its name, components, tuples (one per
    /// element) and data type.
    fn field_arrays(&self, inp: &mut Input) -> Res<Vec<Attribute>> {
        let arrays = inp.count("FIELD")?;
        let mut out = Vec::new();
        for _ in 0..arrays {
            let (array, al) = inp.expect_token("a FIELD array's name")?;
            let array = array.to_string();
            let k = inp.count("the array's component count")?;
            let tuples = inp.count("the array's tuple count")?;
            let (ty, _) = inp.expect_token("the array's data type")?;
            let ty = ty.to_string();
            if tuples != self.count {
                return Err((
                    al,
                    syntax(format!(
                        "FIELD array '{}' has {tuples} tuples for {} elements",
                        echo(&array),
                        self.count
                    )),
                ));
            }
            out.push(self.array(inp, &array, &ty, k, "FIELD array")?);
        }
        Ok(out)
    }
}

impl Input<'_> {
    /// `n` numbers of VTK type `ty` kept exactly: integer types up to 32 bits (and `bit`) as
    /// `i32`, wider ones as `i64`, `float` as `f32` (a finite number that overflows it is an
    /// error), `double` as `f64`.
    fn values(&mut self, n: usize, ty: &str, line: u32, what: &str) -> Res<Values> {
        let lower = ty.to_ascii_lowercase();
        let (size, float) = data_type(ty, line)?;
        let cap = n.min(self.left() / size.min(2) + 1);
        let room = |b| (line, no_room("an attribute's values")(b));
        let bad = |tok: &str, l: u32| {
            (
                l,
                syntax(format!(
                    "'{}' is not of type {ty} among the {what}",
                    echo(tok)
                )),
            )
        };
        if float {
            let mut xs: Vec<f64> =
                try_with_capacity(cap, "an attribute's values").map_err(|k| (line, k))?;
            if self.binary {
                self.binary_numbers(n, ty, size, true, line, what, |_, x| {
                    table::try_push(&mut xs, x).map_err(room)
                })?;
            } else {
                self.each_token(n, what, |tok, l| {
                    // The readers' shared check: a value the declared type holds only as
                    // inf or 0 is refused (one rounding, to the declared type).
                    let f = if size == 4 { Float::F32 } else { Float::F64 };
                    let x = match super::scan::real_as(tok.as_bytes(), f) {
                        Ok(x) => x,
                        Err(super::scan::RealError::NotNumber) => return Err(bad(tok, l)),
                        Err(e) => {
                            let what = format!("among the {what}, declared {ty}");
                            return Err((l, super::scan::real_error_as(e, tok, &what, f)));
                        }
                    };
                    table::try_push(&mut xs, x).map_err(room)
                })?;
            }
            return Ok(if size == 4 {
                Values::F32(xs.into_iter().map(|x| x as f32).collect())
            } else {
                Values::F64(xs)
            });
        }
        let wide = size == 8 || lower == "unsigned_int" || lower == "vtktypeuint32";
        let mut xs: Vec<i64> =
            try_with_capacity(cap, "an attribute's values").map_err(|k| (line, k))?;
        if self.binary {
            let block = self.binary_block(n, size, ty, line, what)?;
            let signed = !lower.starts_with("unsigned") && !lower.contains("uint");
            for c in block.chunks_exact(size) {
                let x = i64::try_from(be_integer(c, signed))
                    .map_err(|_| (line, syntax(format!("a {ty} above 2^63 among the {what}"))))?;
                table::try_push(&mut xs, x).map_err(room)?;
            }
        } else {
            self.each_token(n, what, |tok, l| {
                let x = parse_integer(tok)
                    .ok()
                    .and_then(|v| i64::try_from(v).ok())
                    .ok_or_else(|| bad(tok, l))?;
                if !wide && i32::try_from(x).is_err() {
                    return Err((
                        l,
                        syntax(format!(
                            "'{}' does not fit {ty} among the {what}",
                            echo(tok)
                        )),
                    ));
                }
                table::try_push(&mut xs, x).map_err(room)
            })?;
        }
        Ok(if wide {
            Values::I64(xs)
        } else {
            Values::I32(xs.into_iter().map(|x| x as i32).collect())
        })
    }
}

/// A named integer field: one value per point or per cell.
pub struct Field<'a> {
    /// The field's name (no whitespace).
    pub name: &'a str,
    /// One value per point (point data) or per listed simplex (cell data).
    pub values: &'a [i32],
}

fn push_number(out: &mut Vec<u8>, binary: bool, x: f64) {
    if binary {
        out.extend_from_slice(&x.to_be_bytes());
    } else {
        push_f64(out, x);
    }
}

fn push_ints(out: &mut Vec<u8>, binary: bool, xs: impl Iterator<Item = i64>) {
    for (i, x) in xs.enumerate() {
        if binary {
            out.extend_from_slice(&(x as i32).to_be_bytes());
        } else {
            if i > 0 {
                out.push(b' ');
            }
            out.extend_from_slice(x.to_string().as_bytes());
        }
    }
    out.push(b'\n');
}

/// Writes `raw` as a legacy VTK unstructured grid, ASCII or BINARY.
pub(crate) fn write(raw: &RawInput, binary: bool, out: &mut Vec<u8>) -> Result<(), String> {
    write_with_fields(raw, binary, &[], &[], out)
}

/// Writes `raw` as a legacy VTK unstructured grid with integer point and cell fields (ParaView
/// colours by them); `Err` names what does not fit.
pub fn write_with_fields(
    raw: &RawInput,
    binary: bool,
    point_fields: &[Field],
    cell_fields: &[Field],
    out: &mut Vec<u8>,
) -> Result<(), String> {
    check_fits(
        raw,
        4,
        "vertices, edges, triangles and tetrahedra (use .simplices)",
    )?;
    if let Some(&v) = raw.ids.iter().find(|&&v| v > i32::MAX as u32) {
        return Err(format!("vertex id {v} does not fit VTK's int"));
    }
    let n = vertex_count(raw);
    let m = raw.simplex_count();
    let mode = if binary { "BINARY" } else { "ASCII" };
    out.extend_from_slice(
        format!(
            "# vtk DataFile Version 4.2\nwritten by topoplex\n{mode}\nDATASET UNSTRUCTURED_GRID\n\
             POINTS {n} double\n"
        )
        .as_bytes(),
    );
    push_points(out, raw, n, binary);
    push_cells(out, raw, binary);
    for (keyword, count, fields, location) in [
        ("POINT_DATA", n, point_fields, Location::Vertices),
        ("CELL_DATA", m, cell_fields, Location::Listed),
    ] {
        let attrs: Vec<&Attribute> = raw
            .attributes
            .iter()
            .filter(|a| a.location == location)
            .collect();
        if !attrs.is_empty() || !fields.is_empty() {
            out.extend_from_slice(format!("{keyword} {count}\n").as_bytes());
        }
        for a in attrs {
            push_attribute(out, binary, a);
        }
        push_fields(out, binary, keyword, count, fields)?;
    }
    Ok(())
}

/// An attribute as `SCALARS` (1 to 4 components, the legacy format's limit) or else a
/// one-array `FIELD`, in its own type: `int`, `vtktypeint64`, `float`, `double`.
fn push_attribute(out: &mut Vec<u8>, binary: bool, a: &Attribute) {
    let ty = match a.values {
        Values::I32(_) => "int",
        Values::I64(_) => "vtktypeint64",
        Values::F32(_) => "float",
        Values::F64(_) => "double",
    };
    let (name, k) = (&a.name, a.components);
    let head = if k <= 4 {
        format!("SCALARS {name} {ty} {k}\nLOOKUP_TABLE default\n")
    } else {
        format!("FIELD FieldData 1\n{name} {k} {} {ty}\n", a.element_count())
    };
    out.extend_from_slice(head.as_bytes());
    let mut ascii = |i: usize, s: &dyn Fn(&mut Vec<u8>)| {
        if i > 0 {
            out.push(if i.is_multiple_of(k) { b'\n' } else { b' ' });
        }
        s(out);
    };
    match (&a.values, binary) {
        (Values::I32(v), true) => push_be(out, v, |x| x.to_be_bytes()),
        (Values::I64(v), true) => push_be(out, v, |x| x.to_be_bytes()),
        (Values::F32(v), true) => push_be(out, v, |x| x.to_be_bytes()),
        (Values::F64(v), true) => push_be(out, v, |x| x.to_be_bytes()),
        (Values::I32(v), false) => {
            for (i, x) in v.iter().enumerate() {
                ascii(i, &|o| o.extend_from_slice(x.to_string().as_bytes()));
            }
        }
        (Values::I64(v), false) => {
            for (i, x) in v.iter().enumerate() {
                ascii(i, &|o| o.extend_from_slice(x.to_string().as_bytes()));
            }
        }
        (Values::F32(v), false) => {
            for (i, &x) in v.iter().enumerate() {
                // The shortest decimal that reads back as the same f32.
                ascii(i, &|o| {
                    let mut b = ryu::Buffer::new();
                    let s = b.format(x);
                    o.extend_from_slice(s.strip_suffix(".0").unwrap_or(s).as_bytes());
                });
            }
        }
        (Values::F64(v), false) => {
            for (i, &x) in v.iter().enumerate() {
                ascii(i, &|o| push_f64(o, x));
            }
        }
    }
    out.push(b'\n');
}

/// Each of `v` as its big-endian bytes (`be`), as legacy VTK's binary wants.
fn push_be<T, const N: usize>(out: &mut Vec<u8>, v: &[T], be: impl Fn(&T) -> [u8; N]) {
    for x in v {
        out.extend_from_slice(&be(x));
    }
}

/// The coordinates of the `n` points, 3 a point (0 where `raw` has fewer).
fn push_points(out: &mut Vec<u8>, raw: &RawInput, n: usize, binary: bool) {
    let coords = raw.coords.as_ref();
    for v in 0..n {
        for k in 0..3 {
            if k > 0 && !binary {
                out.push(b' ');
            }
            let x = coords
                .filter(|c| k < c.dim)
                .map_or(0.0, |c| c.data[v * c.dim + k]);
            push_number(out, binary, x);
        }
        if !binary {
            out.push(b'\n');
        }
    }
    if binary {
        out.push(b'\n');
    }
}

/// The `CELLS` and `CELL_TYPES` sections: the simplices of `raw`.
fn push_cells(out: &mut Vec<u8>, raw: &RawInput, binary: bool) {
    let m = raw.simplex_count();
    let size = m + raw.ids.len();
    out.extend_from_slice(format!("CELLS {m} {size}\n").as_bytes());
    for i in 0..m {
        let s = raw.simplex(i);
        if binary {
            out.extend_from_slice(&(s.len() as i32).to_be_bytes());
            for &v in s {
                out.extend_from_slice(&(v as i32).to_be_bytes());
            }
        } else {
            out.extend_from_slice(format!("{} ", s.len()).as_bytes());
            push_ids(out, s, 0);
            out.push(b'\n');
        }
    }
    if binary {
        out.push(b'\n');
    }
    out.extend_from_slice(format!("CELL_TYPES {m}\n").as_bytes());
    push_ints(
        out,
        binary,
        (0..m).map(|i| i64::from(cell_type(raw.simplex(i).len()))),
    );
}

/// A `POINT_DATA` or `CELL_DATA` section (`keyword`) of `fields`, `count` values each; nothing
/// without fields. `Err` names a field of another length.
fn push_fields(
    out: &mut Vec<u8>,
    binary: bool,
    keyword: &str,
    count: usize,
    fields: &[Field],
) -> Result<(), String> {
    for f in fields {
        if f.values.len() != count {
            return Err(format!(
                "field {} has {} values for {count} {}",
                f.name,
                f.values.len(),
                if keyword == "POINT_DATA" {
                    "points"
                } else {
                    "cells"
                }
            ));
        }
        out.extend_from_slice(
            format!("SCALARS {} int 1\nLOOKUP_TABLE default\n", f.name).as_bytes(),
        );
        push_ints(out, binary, f.values.iter().map(|&x| i64::from(x)));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn vtk(body: &str) -> String {
        format!("# vtk DataFile Version 4.2\nt\nASCII\nDATASET UNSTRUCTURED_GRID\n{body}")
    }

    fn message(body: &str) -> (u32, String) {
        let (line, kind) = parse(vtk(body).as_bytes()).unwrap_err();
        (line, kind.to_string())
    }

    /// Streamed cells report as the whole block did: a malformed entry after a bad id wins
    /// (read first), the block ending inside a cell wins over that cell's bad id, a bad id
    /// wins over a type error.
    #[test]
    fn streamed_cells_report_errors_in_the_order_the_whole_block_did() {
        // (the sections after the points, the line reported where it matters, what it says)
        let cases = [
            (
                "CELLS 2 6\n2 0 -1\n2 0 x\nCELL_TYPES 2\n3 3\n",
                Some(9),
                "'x' is not a int",
            ),
            (
                "CELLS 2 5\n2 0 1\n3 0 -1\nCELL_TYPES 2\n3 5\n",
                Some(7),
                "ends inside cell #1",
            ),
            ("CELLS 2 6\n2 0 -1\n2 0 1\nCELL_TYPES 2\n9 3\n", None, "-1"),
            (
                "CELLS 2 6\n2 0 1\n2 0 1\nCELL_TYPES 2\n3 9\n",
                Some(10),
                "cell #1 has VTK type 9 (quad)",
            ),
            (
                "CELLS 2 6\n2 0 1\n2 0 1\nCELL_TYPES 3\n3 9 3\n",
                None,
                "3 cell types for 2 cells",
            ),
        ];
        for (cells, line, want) in cases {
            let (l, m) = message(&format!("POINTS 3 double\n0 0 0 1 0 0 0 1 0\n{cells}"));
            if let Some(line) = line {
                assert_eq!(l, line, "{m}");
            }
            assert!(m.contains(want), "{m}");
        }
    }

    /// A repeated CELLS section replaces the first, as before.
    #[test]
    fn a_repeated_cells_section_replaces_the_first() {
        let raw = parse(
            vtk(
                "POINTS 3 double\n0 0 0 1 0 0 0 1 0\nCELLS 1 3\n2 0 1\nCELLS 1 4\n3 0 1 2\n\
                 CELL_TYPES 1\n5\n",
            )
            .as_bytes(),
        )
        .unwrap();
        assert_eq!(raw.simplex_count(), 1);
        assert_eq!(raw.simplex(0), &[0, 1, 2]);
        assert_eq!(raw.lines, vec![9]);
    }

    /// Version 5 (OFFSETS / CONNECTIVITY) with the connectivity streamed: cell `i` is
    /// `offsets[i]..offsets[i + 1]`, the offsets running from 0 to the connectivity's size
    /// (else entries would be dropped: refused); a bad id in a cell before
    /// the first bad offset pair is reported first, else the offsets, else a malformed number
    /// anywhere in the block before both.
    #[test]
    fn version_5_cells_stream_and_report_in_cell_order() {
        let v5 = |cells: &str| {
            format!(
                "# vtk DataFile Version 5.1\nt\nASCII\nDATASET UNSTRUCTURED_GRID\n\
                 POINTS 3 double\n0 0 0 1 0 0 0 1 0\n{cells}"
            )
        };
        //   2
        //   | \        cells: triangle 0 1 2, edge 1 2 (offsets 0..3..5 of 5 entries)
        //   0---1
        let raw = parse(
            v5(
                "CELLS 3 5\nOFFSETS vtktypeint64\n0 3 5\nCONNECTIVITY vtktypeint64\n0 1 2 1 2\n\
                CELL_TYPES 2\n5 3\n",
            )
            .as_bytes(),
        )
        .unwrap();
        assert_eq!(raw.simplex_count(), 2);
        assert_eq!(
            (raw.simplex(0), raw.simplex(1)),
            (&[0, 1, 2][..], &[1, 2][..])
        );
        assert_eq!(raw.lines, [7, 7]);
        let err = |cells: &str| {
            let (l, k) = parse(v5(cells).as_bytes()).unwrap_err();
            (l, k.to_string())
        };
        // Offsets not from 0, or not to the end: entries outside the cells are not dropped.
        for offsets in ["1 4 6", "0 3 5"] {
            let (l, m) = err(&format!(
                "CELLS 3 7\nOFFSETS vtktypeint64\n{offsets}\nCONNECTIVITY vtktypeint64\n\
                 9 0 1 2 1 2 9\nCELL_TYPES 2\n5 3\n"
            ));
            assert_eq!(l, 8);
            assert!(
                m.starts_with("OFFSETS run from ") && m.contains("the 7 CONNECTIVITY"),
                "{m}"
            );
        }
        // Cell 1's offsets are out of range (7 > 6 entries); cell 0 has a bad id: cell 0 first.
        let (l, m) = err(
            "CELLS 3 6\nOFFSETS int\n0 3 7\nCONNECTIVITY int\n0 -1 2 0 1 2\nCELL_TYPES 2\n5 5\n",
        );
        assert_eq!((l, m.as_str()), (10, "negative vertex id -1"));
        // The same bad id after the bad pair is not read: the offsets are reported.
        let (l, m) = err(
            "CELLS 3 6\nOFFSETS int\n0 3 2\nCONNECTIVITY int\n0 1 2 0 -1 2\nCELL_TYPES 2\n5 5\n",
        );
        assert_eq!(
            (l, m.as_str()),
            (8, "cell #1: offsets 3..2 out of order or range")
        );
        // A malformed number anywhere in the connectivity comes before both.
        let (l, m) = err(
            "CELLS 3 6\nOFFSETS int\n0 3 2\nCONNECTIVITY int\n0 -1 2\n0 x 2\nCELL_TYPES 2\n5 5\n",
        );
        assert_eq!(l, 12);
        assert!(m.contains("'x' is not a int"), "{m}");
    }
}
