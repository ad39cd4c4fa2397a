//! OFF writer: `OFF` (3 coordinates per vertex, fewer padded with zeros, zeros without
//! coordinates) or `nOFF` with the dimension (more than 3); then one face per simplex, `k ids`,
//! in listing order. Holds vertices, edges and triangles. The attributes `off:normal`,
//! `off:color`, `off:texture` on the vertices (`f64`; as many normal components as coordinates
//! are written, 4 colour components, 2 texture coordinates) make the `N`, `C`, `ST` prefixes and
//! follow each vertex's coordinates; `off:color` on the listed simplices (`f64`, 1, 3 or 4
//! components) follows each face's ids.

use super::{RawInput, check_max_len, push_f64, push_ids, push_point, vertex_count};
use crate::complex::{Attribute, Location, Values};
use crate::io::off::{COLOR, NORMAL, TEXTURE};

/// Whether OFF holds `a` (see the module doc; widths that depend on the coordinates are
/// checked when writing).
pub(crate) fn holds(a: &Attribute) -> bool {
    matches!(a.values, Values::F64(_))
        && match a.location {
            Location::Vertices => [NORMAL, COLOR, TEXTURE].contains(&a.name.as_str()),
            Location::Listed => a.name == COLOR && matches!(a.components, 1 | 3 | 4),
        }
}

/// Appends element `i` of `a` (f64 values), each number after a blank.
fn push_element(out: &mut Vec<u8>, a: Option<&Attribute>, i: usize) {
    let Some(a) = a else { return };
    let Values::F64(v) = &a.values else { return };
    for &x in &v[i * a.components..(i + 1) * a.components] {
        out.push(b' ');
        push_f64(out, x);
    }
}

pub(super) fn write(raw: &RawInput, out: &mut super::Out) -> Result<(), String> {
    check_max_len(
        raw,
        3,
        "vertices, edges and triangles (use .mesh, .msh, .vtk or .simplices)",
    )?;
    let coords = raw.coords.as_ref();
    let width = coords.map_or(3, |c| c.dim.max(3));
    let at = |name| raw.attributes.get(name, Location::Vertices);
    let (normal, colour, texture) = (at(NORMAL), at(COLOR), at(TEXTURE));
    for (a, want) in [(normal, width), (colour, 4), (texture, 2)] {
        if let Some(a) = a
            && a.components != want
        {
            return Err(format!(
                "attribute {} has {} components; OFF writes {want} for it here",
                a.describe(),
                a.components
            ));
        }
    }
    let face_colour = raw.attributes.get(COLOR, Location::Listed);
    if let Some(a) = face_colour
        && raw.simplex_count() == 0
    {
        return Err(format!(
            "attribute {} is on no face; OFF keeps a face colour only beside a face",
            a.describe()
        ));
    }
    let mut prefix = String::new();
    for (a, letters) in [(texture, "ST"), (colour, "C"), (normal, "N")] {
        if a.is_some() {
            prefix.push_str(letters);
        }
    }
    let vertex = |out: &mut Vec<u8>, v: usize| {
        push_point(out, coords, v, width);
        for a in [normal, colour, texture] {
            push_element(out, a, v);
        }
    };
    let faces = (0..raw.simplex_count()).map(|i| raw.simplex(i));
    let colour = |out: &mut Vec<u8>, i: usize| push_element(out, face_colour, i);
    let m = raw.simplex_count();
    write_lines(
        out,
        &prefix,
        width,
        vertex_count(raw),
        vertex,
        m,
        faces,
        |v| v,
        colour,
    );
    Ok(())
}

/// The lines of an OFF file: the header keyword (`prefix` before it) for `width` numbers a
/// vertex, the counts, `n` vertex lines (`vertex(out, v)` writes vertex v's numbers) and the `m`
/// faces `k ids` with each id through `id` and `extra(out, i)` after face i's ids. Handed to the
/// file line by line ([`super::Out::spill`]). Shared by [`write`] and the live complex's writer,
/// which writes from its own arrays with no listing.
#[allow(clippy::too_many_arguments)]
pub(crate) fn write_lines<'s>(
    out: &mut super::Out,
    prefix: &str,
    width: usize,
    n: usize,
    mut vertex: impl FnMut(&mut Vec<u8>, usize),
    m: usize,
    faces: impl Iterator<Item = &'s [u32]>,
    id: impl Fn(u32) -> u32,
    mut extra: impl FnMut(&mut Vec<u8>, usize),
) {
    out.extend_from_slice(prefix.as_bytes());
    if width == 3 {
        out.extend_from_slice(b"OFF\n");
    } else {
        out.extend_from_slice(format!("nOFF\n{width}\n").as_bytes());
    }
    out.extend_from_slice(format!("{n} {m} 0\n").as_bytes());
    for v in 0..n {
        vertex(out, v);
        out.push(b'\n');
        out.spill();
    }
    let mut ids = [0u32; 3];
    for (i, s) in faces.enumerate() {
        for (x, &v) in ids.iter_mut().zip(s) {
            *x = id(v);
        }
        push_ids(out, &[s.len() as u32], 0);
        out.push(b' ');
        push_ids(out, &ids[..s.len()], 0);
        extra(out, i);
        out.push(b'\n');
        out.spill();
    }
}
