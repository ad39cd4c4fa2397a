//! OFF writer: `OFF` (3 coordinates per vertex, fewer padded with zeros, zeros without
//! coordinates) or `nOFF` with the dimension (more than 3); then one face per simplex, `k ids`,
//! in listing order. Holds vertices, edges and triangles.

use super::{RawInput, check_max_len, push_ids, push_point, vertex_count};

pub(super) fn write(raw: &RawInput, out: &mut Vec<u8>) -> Result<(), String> {
    check_max_len(
        raw,
        3,
        "vertices, edges and triangles (use .mesh, .msh, .vtk or .simplices)",
    )?;
    let coords = raw.coords.as_ref();
    let width = coords.map_or(3, |c| c.dim.max(3));
    if width == 3 {
        out.extend_from_slice(b"OFF\n");
    } else {
        out.extend_from_slice(format!("nOFF\n{width}\n").as_bytes());
    }
    let n = vertex_count(raw);
    out.extend_from_slice(format!("{n} {} 0\n", raw.simplex_count()).as_bytes());
    for v in 0..n {
        push_point(out, coords, v, width);
        out.push(b'\n');
    }
    for i in 0..raw.simplex_count() {
        let s = raw.simplex(i);
        out.extend_from_slice(s.len().to_string().as_bytes());
        out.push(b' ');
        push_ids(out, s, 0);
        out.push(b'\n');
    }
    Ok(())
}
