//! MEDIT writer: `MeshVersionFormatted 2`, `Dimension 2` (2 coordinates per vertex) or `3`
//! (fewer padded with zeros, zeros without coordinates), `Vertices`, then `Edges`,
//! `Triangles`, `Tetrahedra` (1-based ids), each in listing order, and `End`. References are
//! the `medit:ref` attribute of the vertices and of the listed simplices, 0 without one.
//! Listed 0-simplices are left to the vertex count (MEDIT has no point element): one with a
//! nonzero reference cannot be held.

use super::{RawInput, check_fits, push_ids, push_point, vertex_count};
use crate::complex::Location;
use crate::io::medit::REF;

pub(super) fn write(raw: &RawInput, out: &mut super::Out) -> Result<(), String> {
    check_fits(
        raw,
        4,
        "edges, triangles and tetrahedra (use .msh, .vtk or .simplices)",
    )?;
    let coords = raw.coords.as_ref();
    let width = if coords.is_some_and(|c| c.dim == 2) {
        2
    } else {
        3
    };
    let reference = |location| {
        let a = raw.attributes.get(REF, location);
        move |i: usize| a.and_then(|a| a.label(i)).unwrap_or(0)
    };
    let (vertex_ref, listed_ref) = (reference(Location::Vertices), reference(Location::Listed));
    if let Some(i) =
        (0..raw.simplex_count()).find(|&i| raw.simplex(i).len() == 1 && listed_ref(i) != 0)
    {
        return Err(format!(
            "listed vertex {} (simplex {i} of the listing) has reference {} in '{REF}', but MEDIT \
             has no point element (use .vtk, .vtu or .msh)",
            raw.simplex(i)[0],
            listed_ref(i)
        ));
    }
    let n = vertex_count(raw);
    out.extend_from_slice(
        format!("MeshVersionFormatted 2\nDimension {width}\nVertices\n{n}\n").as_bytes(),
    );
    for v in 0..n {
        push_point(out, coords, v, width);
        out.extend_from_slice(format!(" {}\n", vertex_ref(v)).as_bytes());
        out.spill();
    }
    for (len, keyword) in [(2, "Edges"), (3, "Triangles"), (4, "Tetrahedra")] {
        let rows = (0..raw.simplex_count()).filter(|&i| raw.simplex(i).len() == len);
        let count = rows.clone().count();
        if count == 0 {
            continue;
        }
        out.extend_from_slice(format!("{keyword}\n{count}\n").as_bytes());
        for i in rows {
            push_ids(out, raw.simplex(i), 1);
            out.extend_from_slice(format!(" {}\n", listed_ref(i)).as_bytes());
            out.spill();
        }
    }
    out.extend_from_slice(b"End\n");
    Ok(())
}
