//! The input rules of the complex model: closure, top simplices, absorption, errors.

use topoplex::complex::{ComplexError, MAX_DIMENSION};
use topoplex::io::RawInput;
use topoplex::{Complex, fixtures};

#[test]
fn duplicates_and_faces_are_absorbed_and_counted() {
    // Triangle 0 1 2 listed twice (once reordered), its edge 1 2 and vertex 0 listed too,
    // and a wire edge 2 3 whose vertex 3 is also listed.
    let c = Complex::from_simplices(5, &[&[0, 1, 2], &[2, 1, 0], &[1, 2], &[0], &[2, 3], &[3]])
        .unwrap();
    let s = c.stats();
    assert_eq!(
        (s.input_simplices, s.absorbed_duplicates, s.absorbed_faces),
        (6, 1, 3)
    );
    // Vertex 4 is used by nothing: an isolated vertex, a top 0-simplex.
    assert_eq!(c.top_counts(), vec![1, 1, 1]);
    assert_eq!(c.tops(0).as_flat(), &[4]);
    assert_eq!(c.tops(1).as_flat(), &[2, 3]);
    assert_eq!(c.dimension(), 2);
}

#[test]
fn closure_lists_every_face_in_lexicographic_order() {
    let c = fixtures::tetrahedron_with_dangling_triangle_and_wire();
    let cl = c.closure();
    let counts: Vec<usize> = cl.iter().map(|t| t.len()).collect();
    // 6 vertices; 6 tetra edges + 24, 34, 45; 4 tetra faces + 234; 1 tetrahedron.
    assert_eq!(counts, vec![6, 9, 5, 1]);
    assert_eq!(
        cl[2].as_flat(),
        &[0, 1, 2, 0, 1, 3, 0, 2, 3, 1, 2, 3, 2, 3, 4]
    );
}

#[test]
fn numeric_not_textual_order() {
    let c = Complex::from_simplices(12, &[&[0, 10, 11], &[0, 9, 10]]).unwrap();
    assert_eq!(c.tops(2).as_flat(), &[0, 9, 10, 0, 10, 11]);
}

#[test]
fn repeated_vertex_names_file_line_and_simplex() {
    let mut raw = RawInput::new();
    raw.vertex_count = Some(4);
    raw.push(&[0, 1, 2], 3);
    raw.push(&[1, 3, 1], 4);
    let e = Complex::from_raw(&raw, Some(std::path::Path::new("in.simplices"))).unwrap_err();
    assert!(matches!(e, ComplexError::RepeatedVertex { .. }));
    assert_eq!(
        e.to_string(),
        "in.simplices:4: simplex [1 3 1] repeats vertex 1"
    );
}

#[test]
fn out_of_range_vertex_names_file_line_and_simplex() {
    let mut raw = RawInput::new();
    raw.vertex_count = Some(3);
    raw.push(&[0, 1, 3], 7);
    let e = Complex::from_raw(&raw, Some(std::path::Path::new("m.off"))).unwrap_err();
    assert_eq!(
        e.to_string(),
        "m.off:7: simplex [0 1 3] uses vertex 3, but the complex has 3 vertices (ids 0..3)"
    );
}

#[test]
fn dimension_above_the_maximum_is_refused() {
    let ids: Vec<u32> = (0..=MAX_DIMENSION as u32 + 1).collect();
    let e = Complex::from_simplices(ids.len() as u32, &[&ids]).unwrap_err();
    assert!(
        e.to_string()
            .contains("dimension 16, above the supported maximum 15"),
        "{e}"
    );
    let ok: Vec<u32> = (0..=MAX_DIMENSION as u32).collect();
    assert_eq!(Complex::from_simplices(16, &[&ok]).unwrap().dimension(), 15);
}

#[test]
fn array_input_errors_name_the_position() {
    let e = Complex::from_arrays(3, &[0, 1, 1, 2, 2], &[0, 2, 5], None).unwrap_err();
    assert_eq!(
        e.to_string(),
        "input simplex #1: simplex [1 2 2] repeats vertex 2"
    );
    assert!(matches!(
        Complex::from_simplices(0, &[]),
        Err(ComplexError::NoVertices { .. })
    ));
}

#[test]
fn without_declared_vertices_the_count_is_max_id_plus_one() {
    let mut raw = RawInput::new();
    raw.push(&[2, 5], 1);
    let c = Complex::from_raw(&raw, None).unwrap();
    assert_eq!(c.vertex_count(), 6);
    // 0, 1, 3, 4 are isolated.
    assert_eq!(c.tops(0).as_flat(), &[0, 1, 3, 4]);
}

/// Regression (found by the `read_simplices` fuzz target): `s 0 1000000000 3 8 9` in a file
/// without `v` lines implied a billion isolated vertices and exhausted memory.
#[test]
fn a_huge_id_without_declared_vertices_is_refused_not_allocated() {
    let mut raw = RawInput::new();
    raw.push(&[0, 1], 1);
    raw.push(&[0, 1_000_000_000, 3, 8, 9], 2);
    let e = Complex::from_raw(&raw, Some(std::path::Path::new("s.simplices"))).unwrap_err();
    assert!(matches!(
        e,
        ComplexError::ImpliedVertexCount {
            vertex: 1_000_000_000,
            ..
        }
    ));
    assert!(e.to_string().starts_with("s.simplices:2: simplex [0 1000000000 3 8 9] uses vertex 1000000000, which would make 1000000001 vertices"), "{e}");
    // Just below the limit the vertices are 0..=max id: 2^24 vertices from 2 ids, above the
    // default closure budget (issue 16: `s 16777215` made `report` use 1.2 GB), accepted when
    // the caller raises the budget.
    let mut raw = RawInput::new();
    raw.push(&[0, topoplex::complex::MAX_IMPLIED_VERTICES - 1], 1);
    let e = Complex::from_raw(&raw, None).unwrap_err();
    assert!(
        matches!(
            e,
            ComplexError::TooLarge {
                bound: 16_777_217,
                limit: 1_048_576,
                input_size: 2,
                ..
            }
        ),
        "{e:?}"
    );
    let big = topoplex::Budget {
        max_simplices: Some(1 << 25),
    };
    assert_eq!(
        Complex::from_raw_with(&raw, None, big)
            .unwrap()
            .vertex_count(),
        topoplex::complex::MAX_IMPLIED_VERTICES
    );
}

/// Issue 16 class 4: the closure budget's default rule and its bound, on drawn inputs.
#[test]
fn closure_budget_counts_every_face_of_every_listed_simplex() {
    // One 15-simplex: 16 vertices + 65,519 faces of dimension >= 1 = 65,535, under the floor.
    let s: Vec<u32> = (0..16).collect();
    let ids = s.clone();
    let offsets = [0, 16];
    let c = Complex::from_arrays(16, &ids, &offsets, None).unwrap();
    assert_eq!(c.dimension(), 15);
    // 17 disjoint 15-simplices: 17 · 65,535 = 1,114,095 > 2^20, and > 64 · 272 ids.
    let ids: Vec<u32> = (0..17 * 16).collect();
    let offsets: Vec<usize> = (0..=17).map(|i| i * 16).collect();
    let e = Complex::from_arrays(17 * 16, &ids, &offsets, None).unwrap_err();
    assert!(
        matches!(
            e,
            ComplexError::TooLarge {
                bound: 1_114_095,
                limit: 1_048_576,
                input_size: 272,
                ..
            }
        ),
        "{e:?}"
    );
    // A triangle fan of 2^20 triangles is far under 64 per id: the ratio, not the floor, rules.
    let n = 1u32 << 20;
    let mut ids = Vec::new();
    for i in 1..n - 1 {
        ids.extend_from_slice(&[0, i, i + 1]);
    }
    let offsets: Vec<usize> = (0..=ids.len() / 3).map(|i| i * 3).collect();
    let c = Complex::from_arrays(n, &ids, &offsets, None).unwrap();
    assert_eq!(c.tops(2).len(), n as usize - 2);
    // Shared faces: v = 0 joined to the 2^11 facets of the boundary of the 11-dimensional
    // cross-polytope (vertices 2i+1, 2i+2 opposite). The bound, 23 + 2^11 · (2^12 − 13) =
    // 8,361,983, is above the default limit (2^20 + 2^19 for 24,576 ids), but the closure has
    // 2 · 3^11 − 1 = 354,293 simplices (the faces of the sphere, 3^11 − 1, each with and
    // without 0, and 0 itself): counted exactly, accepted.
    let k = 10u32;
    let mut ids = Vec::new();
    for choice in 0u32..(1 << (k + 1)) {
        ids.push(0);
        ids.extend((0..=k).map(|i| 2 * i + 1 + ((choice >> i) & 1)));
    }
    let offsets: Vec<usize> = (0..=1usize << (k + 1))
        .map(|i| i * (k as usize + 2))
        .collect();
    let c = Complex::from_arrays(2 * k + 3, &ids, &offsets, None).unwrap();
    assert_eq!(c.tops(11).len(), 2048);
    let closure: usize = c.closure().iter().map(|t| t.len()).sum();
    assert_eq!(closure, 2 * 3usize.pow(11) - 1);
    // The exact count is tried only while the bound is within 16 times the limit: under a
    // limit of 500,000 (16× = 8,000,000 < the bound) it is refused, under 600,000 counted.
    let limit = |m| topoplex::Budget {
        max_simplices: Some(m),
    };
    let e = Complex::from_arrays_with(2 * k + 3, &ids, &offsets, None, limit(500_000));
    assert!(matches!(e, Err(ComplexError::TooLarge { .. })), "{e:?}");
    assert!(Complex::from_arrays_with(2 * k + 3, &ids, &offsets, None, limit(600_000)).is_ok());
    // The count itself refuses: one 15-simplex (65,535 simplices, bound exact) under 65,534.
    let e = Complex::from_arrays_with(16, &s, &[0, 16], None, limit(65_534));
    assert!(
        matches!(e, Err(ComplexError::TooLarge { bound: 65_535, .. })),
        "{e:?}"
    );
    assert!(Complex::from_arrays_with(16, &s, &[0, 16], None, limit(65_535)).is_ok());
    // An explicit limit replaces the rule both ways.
    let tight = topoplex::Budget {
        max_simplices: Some(100),
    };
    let e = Complex::from_arrays_with(16, &s, &[0, 16], None, tight).unwrap_err();
    assert!(e.to_string().contains("up to 65535 simplices"), "{e}");
    assert!(e.to_string().contains("--max-simplices"), "{e}");
}

#[test]
fn input_order_and_winding_are_kept() {
    //   3           Listed: triangle 2 1 0 (clockwise as drawn), its edge 1 2 (absorbed),
    //   |\          triangle 0 1 2 again (a repeat, absorbed), wire edge 3 1, vertex 4 alone.
    //   | \         Tops in input order: [2 1 0], [3 1], [4]; top tables stay ascending.
    //   1--2
    //   |  /
    //   0 /
    let c = Complex::from_simplices(5, &[&[2, 1, 0], &[1, 2], &[0, 1, 2], &[3, 1], &[4]]).unwrap();
    assert_eq!(c.input_count(), 5);
    assert_eq!(c.input_simplex(0), &[2, 1, 0]);
    assert_eq!(c.input_top(0), Some((2, 0)));
    assert_eq!(c.input_top(1), None);
    assert_eq!(c.input_top(2), Some((2, 0)));
    assert_eq!(c.input_top(3), Some((1, 0)));
    assert_eq!(c.top_listing(2, 0), Some(0));
    assert_eq!(c.top_oriented(2, 0), &[2, 1, 0]);
    assert_eq!(c.top_oriented(1, 0), &[3, 1]);
    assert_eq!(c.tops(1).get(0), &[1, 3]);
    let given: Vec<(usize, Vec<u32>)> = c
        .tops_as_given()
        .map(|(i, _, _, s)| (i, s.to_vec()))
        .collect();
    assert_eq!(
        given,
        vec![(0, vec![2, 1, 0]), (3, vec![3, 1]), (4, vec![4])]
    );

    // An isolated vertex nobody lists keeps its ascending row and has no listing.
    let c = Complex::from_simplices(3, &[&[1, 0]]).unwrap();
    assert_eq!(c.top_listing(0, 0), None);
    assert_eq!(c.top_oriented(0, 0), &[2]);
    assert_eq!(c.tops_as_given().count(), 1);
}

/// Issue 16 class 5: a long listing of few distinct simplices (a file of short lines) is
/// deduplicated block by block as it is read; the result and the counts are those of one final
/// sort. Three cases: repeats only, repeats after a run of distinct triangles (blocks keep
/// halving), distinct triangles after repeats (deduplication stops, the rest is kept).
#[test]
fn long_listings_of_repeats_dedup_in_blocks_with_the_same_result() {
    // Triangles of a fan around vertex 0: [0 i i+1].
    let fan = |i: u32| [0, i, i + 1];
    let cases: [(&str, Vec<[u32; 3]>); 3] = [
        ("repeats", (0..1_500_000).map(|k| fan(1 + k % 7)).collect()),
        (
            "distinct then repeats",
            (0..200_000)
                .map(|k| fan(1 + k))
                .chain((0..1_300_000).map(|k| fan(1 + k % 7)))
                .collect(),
        ),
        (
            "repeats then distinct",
            (0..600_000)
                .map(|k| fan(1 + k % 7))
                .chain((0..900_000).map(|k| fan(1 + k)))
                .collect(),
        ),
    ];
    for (name, tris) in cases {
        let ids: Vec<u32> = tris.iter().flatten().copied().collect();
        let offsets: Vec<usize> = (0..=tris.len()).map(|i| 3 * i).collect();
        let n = ids.iter().max().unwrap() + 1;
        let c = Complex::from_arrays(n, &ids, &offsets, None).unwrap();
        let mut unique = tris.clone();
        unique.sort_unstable();
        unique.dedup();
        let flat: Vec<u32> = unique.iter().flatten().copied().collect();
        assert_eq!(c.tops(2).as_flat(), &flat[..], "{name}");
        let s = c.stats();
        assert_eq!(
            (s.input_simplices, s.absorbed_duplicates, s.absorbed_faces),
            (tris.len(), tris.len() - unique.len(), 0),
            "{name}"
        );
        // The listing keeps every simplex as given.
        assert_eq!(c.input_count(), tris.len(), "{name}");
        assert_eq!(
            c.input_simplex(tris.len() - 1),
            &tris[tris.len() - 1],
            "{name}"
        );
    }
}

/// Setting a complex's coordinates: the whole array replaced in place (same dimension) or with
/// a new dimension (a complex without coordinates gains them); wrong lengths, dimension 0 and
/// non-finite numbers are refused naming the problem, and change nothing; the topology and the
/// listing are untouched.
#[test]
fn set_coords_replaces_the_array_and_refuses_bad_input_unchanged() {
    let mut c = Complex::from_simplices(4, &[&[2, 1, 0], &[2, 3]]).unwrap();
    assert!(c.coords().is_none());
    let before_tops = c.top_counts();
    let xyz: Vec<f64> = (0..12).map(|k| k as f64 * 0.5).collect();
    c.set_coords(3, &xyz).unwrap();
    assert_eq!(
        (c.coords().unwrap().dim, &c.coords().unwrap().data),
        (3, &xyz)
    );
    let moved: Vec<f64> = xyz.iter().map(|x| x + 1.0).collect();
    c.set_coords(3, &moved).unwrap();
    assert_eq!(c.coords().unwrap().data, moved);
    let flat: Vec<f64> = (0..8).map(f64::from).collect();
    c.set_coords(2, &flat).unwrap();
    assert_eq!(
        (c.coords().unwrap().dim, &c.coords().unwrap().data),
        (2, &flat)
    );
    let refused = |c: &mut Complex, dim: usize, data: &[f64]| match c.set_coords(dim, data) {
        Err(ComplexError::Coordinates(m)) => m,
        other => panic!("expected a refusal, got {other:?}"),
    };
    assert!(refused(&mut c, 2, &flat[..7]).contains("7 numbers given for 4 vertices"));
    assert!(refused(&mut c, 0, &[]).contains("dimension at least 1"));
    let mut bad = flat.clone();
    bad[5] = f64::NAN;
    assert_eq!(
        refused(&mut c, 2, &bad),
        "coordinate 1 of vertex 2 is NaN, not a finite number"
    );
    assert_eq!(
        (c.coords().unwrap().dim, &c.coords().unwrap().data),
        (2, &flat)
    );
    assert_eq!(c.top_counts(), before_tops);
    assert_eq!(c.top_oriented(2, 0), &[2, 1, 0]);
}
