//! `.simplices` writer: one `v` line per vertex with its coordinates (bare `v` without them, so
//! the vertex count is explicit), then one `s` line per simplex in listing order. Holds any
//! complex.

use super::{RawInput, push_ids, push_point, vertex_count};

pub(super) fn write(raw: &RawInput, out: &mut Vec<u8>) {
    let coords = raw.coords.as_ref();
    let width = coords.map_or(0, |c| c.dim);
    for v in 0..vertex_count(raw) {
        out.push(b'v');
        if width > 0 {
            out.push(b' ');
            push_point(out, coords, v, width);
        }
        out.push(b'\n');
    }
    for i in 0..raw.simplex_count() {
        out.push(b's');
        out.push(b' ');
        push_ids(out, raw.simplex(i), 0);
        out.push(b'\n');
    }
}
