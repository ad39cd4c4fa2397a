//! `.simplices` writer: one `v` line per vertex with its coordinates (bare `v` without them, so
//! the vertex count is explicit), then one `s` line per simplex in listing order. Holds any
//! complex. The `simplices:label` attribute (`i64` on the listed simplices) follows each
//! simplex's ids as ` : L`.

use super::{RawInput, push_ids, push_point, vertex_count};
use crate::complex::{Location, Values};
use crate::io::simplices::LABEL;

pub(super) fn write(raw: &RawInput, out: &mut super::Out) {
    let coords = raw.coords.as_ref();
    let width = coords.map_or(0, |c| c.dim);
    for v in 0..vertex_count(raw) {
        out.push(b'v');
        if width > 0 {
            out.push(b' ');
            push_point(out, coords, v, width);
        }
        out.push(b'\n');
        out.spill();
    }
    let labels = match raw
        .attributes
        .get(LABEL, Location::Listed)
        .map(|a| &a.values)
    {
        Some(Values::I64(v)) => Some(v),
        _ => None,
    };
    for i in 0..raw.simplex_count() {
        out.push(b's');
        out.push(b' ');
        push_ids(out, raw.simplex(i), 0);
        if let Some(v) = labels {
            out.extend_from_slice(format!(" : {}", v[i]).as_bytes());
        }
        out.push(b'\n');
        out.spill();
    }
}
