//! OBJ writer: `v x y z` per vertex (fewer coordinates padded with zeros, zeros without
//! coordinates), then `p i`, `l i j` or `f i j k` (1-based) per simplex in listing order. Holds
//! vertices, edges and triangles, and at most 3 coordinates per vertex.

use super::{RawInput, check_coord_dim, check_max_len, push_ids, push_point, vertex_count};

pub(super) fn write(raw: &RawInput, out: &mut Vec<u8>) -> Result<(), String> {
    check_max_len(
        raw,
        3,
        "points, edges and triangles (use .mesh, .msh, .vtk or .simplices)",
    )?;
    check_coord_dim(raw, 3)?;
    let coords = raw.coords.as_ref();
    for v in 0..vertex_count(raw) {
        out.extend_from_slice(b"v ");
        push_point(out, coords, v, 3);
        out.push(b'\n');
    }
    for i in 0..raw.simplex_count() {
        let s = raw.simplex(i);
        out.push(match s.len() {
            1 => b'p',
            2 => b'l',
            _ => b'f',
        });
        out.push(b' ');
        push_ids(out, s, 1);
        out.push(b'\n');
    }
    Ok(())
}
