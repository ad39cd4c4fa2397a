//! The non-manifold census as a legacy VTK file, to see the singularities in ParaView.
//!
//! Cells: the top simplices in input order and winding (as [`topoplex::io::write::listing`]),
//! then one cell per non-manifold edge and per non-manifold triangle. Fields:
//! - point `non_manifold_vertex`: 1 for a non-manifold vertex, else 0;
//! - cell `role`: 0 for a top simplex, 1 for a non-manifold edge, 2 for a non-manifold triangle;
//! - cell `iqm_component`: the IQM component of each top simplex (its index in
//!   [`topoplex::structures::iqm::Iqm::decomposition`]), -1 for the non-manifold cells (and for
//!   every cell when the IQM cannot be built).
//!
//! Holds complexes of dimension up to 3 with at most 3 coordinates per vertex (VTK's cells).
//! Cost: the census's link tests plus the IQM build.

use std::path::Path;

use rustc_hash::FxHashMap;

use super::census::non_manifold_simplices;
use topoplex::complex::Complex;
use topoplex::io::vtk::{Field, write_with_fields};
use topoplex::io::write::{WriteError, WriteErrorKind, listing};
use topoplex::structures::iqm::Iqm;

/// The IQM component of each top simplex, keyed by its ascending vertex ids.
fn components(complex: &Complex) -> FxHashMap<Vec<u32>, i32> {
    let mut of = FxHashMap::default();
    let Ok(iqm) = Iqm::build(complex) else {
        return of;
    };
    for (i, piece) in iqm.decomposition().components.iter().enumerate() {
        for row in piece.tops.chunks_exact(piece.dimension + 1) {
            let mut s: Vec<u32> = row.iter().map(|&l| piece.original[l as usize]).collect();
            s.sort_unstable();
            of.insert(s, i as i32);
        }
    }
    of
}

/// The census file's bytes (ASCII or BINARY legacy VTK).
pub fn census_vtk(complex: &Complex, binary: bool) -> Result<Vec<u8>, WriteErrorKind> {
    let mut raw = listing(complex);
    let comp = components(complex);
    let mut iqm_component = Vec::with_capacity(raw.simplex_count());
    let mut sorted = Vec::new();
    for i in 0..raw.simplex_count() {
        sorted.clear();
        sorted.extend_from_slice(raw.simplex(i));
        sorted.sort_unstable();
        iqm_component.push(comp.get(&sorted).copied().unwrap_or(-1));
    }
    let mut role = vec![0; raw.simplex_count()];
    let nm = non_manifold_simplices(complex, 2);
    let mut non_manifold_vertex = vec![0; complex.vertex_count() as usize];
    for (p, list) in nm.iter().enumerate() {
        for s in list {
            if p == 0 {
                non_manifold_vertex[s[0] as usize] = 1;
            } else {
                raw.push(s, 0);
                role.push(p as i32);
                iqm_component.push(-1);
            }
        }
    }
    let mut out = Vec::new();
    write_with_fields(
        &raw,
        binary,
        &[Field {
            name: "non_manifold_vertex",
            values: &non_manifold_vertex,
        }],
        &[
            Field {
                name: "role",
                values: &role,
            },
            Field {
                name: "iqm_component",
                values: &iqm_component,
            },
        ],
        &mut out,
    )
    .map_err(|reason| WriteErrorKind::CannotHold {
        format: "vtk",
        reason,
    })?;
    Ok(out)
}

/// Writes [`census_vtk`] (ASCII) to `path`.
pub fn write_census_vtk(complex: &Complex, path: &Path) -> Result<(), WriteError> {
    let err = |kind| WriteError {
        path: path.to_path_buf(),
        kind,
    };
    let bytes = census_vtk(complex, false).map_err(err)?;
    std::fs::write(path, bytes).map_err(|e| err(WriteErrorKind::Io(e.to_string())))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bowtie_marks_its_pinch_vertex_and_components() {
        //   0       3
        //   | \   / |      two triangles pinched at vertex 2: 2 is non-manifold, and the IQM
        //   |  2    |      cuts the bowtie into two components
        //   | /   \ |
        //   1       4
        let c = Complex::from_simplices(5, &[&[0, 1, 2], &[2, 3, 4]]).unwrap();
        let text = String::from_utf8(census_vtk(&c, false).unwrap()).unwrap();
        assert!(
            text.contains(
                "POINT_DATA 5\nSCALARS non_manifold_vertex int 1\nLOOKUP_TABLE default\n0 0 1 0 0\n"
            ),
            "{text}"
        );
        assert!(
            text.contains("SCALARS role int 1\nLOOKUP_TABLE default\n0 0\n"),
            "{text}"
        );
        assert!(
            text.contains("SCALARS iqm_component int 1\nLOOKUP_TABLE default\n0 1\n"),
            "{text}"
        );
    }

    #[test]
    fn listed_non_manifold_simplices_match_the_census_counts() {
        for (name, c) in topoplex::fixtures::all() {
            let census = super::super::census::Census::of(&c);
            let lists = non_manifold_simplices(&c, c.dimension());
            let counts: Vec<usize> = lists.iter().map(Vec::len).collect();
            assert_eq!(counts, census.non_manifold, "{name}");
        }
    }

    #[test]
    fn three_triangles_on_an_edge_add_a_marker_cell() {
        //        2
        //   3 -- 0 -- 4      triangles 0 1 2, 0 1 3, 0 1 4 on the non-manifold edge 0-1
        //        1
        let c = Complex::from_simplices(5, &[&[0, 1, 2], &[0, 1, 3], &[0, 1, 4]]).unwrap();
        let text = String::from_utf8(census_vtk(&c, false).unwrap()).unwrap();
        assert!(text.contains("CELLS 4 15\n"), "{text}");
        assert!(text.contains("2 0 1\n"), "{text}");
        assert!(
            text.contains("SCALARS role int 1\nLOOKUP_TABLE default\n0 0 0 1\n"),
            "{text}"
        );
        assert!(text.contains("LOOKUP_TABLE default\n0 1 2 -1\n"), "{text}");
        // It reads back as a complex: the marker edge is absorbed as a face.
        let raw = topoplex::io::vtk::parse(text.as_bytes()).unwrap();
        let back = Complex::from_raw(&raw, None).unwrap();
        assert_eq!(back.top_counts(), c.top_counts());
    }
}
