//! Incidence Graph against exact answers on drawn fixtures and the real data when present (the
//! oracle on random non-manifold complexes: `structures`, for every structure).

use crate::common::{self, rel};

use topoplex::oracle::check_structure;
use topoplex::structures::ig::IncidenceGraph;
use topoplex::{Topology, fixtures};

fn ig(c: &topoplex::Complex) -> IncidenceGraph {
    common::validated(IncidenceGraph::build(c))
}

#[test]
fn three_triangles_on_an_edge_exact() {
    //        2
    //   3 -- 0 -- 4     edge 0-1 into the page, in three triangles
    //        1
    let g = ig(&fixtures::three_triangles_on_an_edge());
    assert_eq!(
        rel(&g, &[0, 1], 2),
        vec![vec![0, 1, 2], vec![0, 1, 3], vec![0, 1, 4]]
    );
    assert_eq!(rel(&g, &[0, 1, 2], 2), vec![vec![0, 1, 3], vec![0, 1, 4]]);
    assert_eq!(rel(&g, &[1], 0), vec![vec![0], vec![2], vec![3], vec![4]]);
    assert_eq!(
        rel(&g, &[0, 2], 1),
        vec![vec![0, 1], vec![0, 3], vec![0, 4], vec![1, 2]]
    );
    assert_eq!(rel(&g, &[0, 1, 2], 0), vec![vec![0], vec![1], vec![2]]);
    let s = g.storage();
    // n = (5, 7, 3): 2·(2·7 + 3·3) + (5 + 7) integers.
    assert_eq!((s.integers, s.bits), (2 * (2 * 7 + 3 * 3) + 12, 0));
}

#[test]
fn tetrahedron_with_dangling_triangle_and_wire_exact() {
    //          3 ------ 4 ------ 5
    //         /|\      /
    //       0--|--2---/          tetra 0123, triangle 234, wire edge 45
    //          1
    let g = ig(&fixtures::tetrahedron_with_dangling_triangle_and_wire());
    assert_eq!(rel(&g, &[2, 3], 3), vec![vec![0, 1, 2, 3]]);
    assert_eq!(
        rel(&g, &[2, 3], 2),
        vec![vec![0, 2, 3], vec![1, 2, 3], vec![2, 3, 4]]
    );
    assert_eq!(rel(&g, &[4], 1), vec![vec![2, 4], vec![3, 4], vec![4, 5]]);
    assert_eq!(rel(&g, &[4], 3), Vec::<Vec<u32>>::new());
    assert_eq!(rel(&g, &[2, 3, 4], 2), vec![vec![0, 2, 3], vec![1, 2, 3]]);
    assert_eq!(rel(&g, &[0, 1, 2, 3], 3), Vec::<Vec<u32>>::new());
    assert_eq!(rel(&g, &[5], 0), vec![vec![4]]);
    assert_eq!(
        (0..=3).map(|p| g.top_count(p)).collect::<Vec<_>>(),
        vec![0, 1, 1, 1]
    );
}

#[test]
fn bowtie_exact() {
    //   0       3
    //   | \   / |
    //   |  2    |      two triangles sharing only vertex 2
    //   | /   \ |
    //   1       4
    let g = ig(&fixtures::bowtie());
    assert_eq!(rel(&g, &[2], 2), vec![vec![0, 1, 2], vec![2, 3, 4]]);
    assert_eq!(rel(&g, &[0, 1, 2], 2), Vec::<Vec<u32>>::new());
    assert_eq!(rel(&g, &[2], 0), vec![vec![0], vec![1], vec![3], vec![4]]);
}

#[test]
fn queries_are_refused_with_the_simplex_named() {
    let g = ig(&fixtures::bowtie());
    let mut out = Vec::new();
    common::check_bowtie_refusal(&g, &mut out);
    assert!(
        g.relation(&[2, 2], 0, &mut out)
            .unwrap_err()
            .to_string()
            .contains("repeats vertex 2")
    );
    assert!(
        g.relation(&[7], 0, &mut out)
            .unwrap_err()
            .to_string()
            .contains("uses vertex 7")
    );
    assert!(
        g.relation(&[0], 3, &mut out)
            .unwrap_err()
            .to_string()
            .contains("above the complex's dimension 2")
    );
    assert!(g.relation(&[], 0, &mut out).is_err());
    // Vertex order in the query does not matter.
    assert_eq!(rel(&g, &[2, 1, 0], 0), vec![vec![0], vec![1], vec![2]]);
}

#[test]
fn every_fixture_matches_the_oracle() {
    for (name, c) in fixtures::all() {
        check_structure(&ig(&c), &c).unwrap_or_else(|e| panic!("{name}: {e}"));
    }
}

#[test]
fn fifteen_simplex_closure() {
    let (c, top) = common::fifteen_simplex();
    common::check_fifteen_simplex(&ig(&c), &top, &mut Vec::new());
}

#[test]
fn real_data_builds_and_validates() {
    for (path, c) in common::shared_complexes() {
        let g = ig(&c);
        // Spot-check a few simplices against the oracle: a full oracle pass is quadratic.
        let o = topoplex::oracle::Oracle::new(&c);
        let mut out = Vec::new();
        for p in 0..=o.dimension() {
            for sigma in o.levels[p].iter().step_by((o.levels[p].len() / 5).max(1)) {
                for q in 0..=o.dimension() {
                    g.relation(sigma, q, &mut out).unwrap();
                    topoplex::relation::sort_rows(&mut out, q + 1);
                    let want: Vec<u32> = o.relation(sigma, q).concat();
                    assert_eq!(out, want, "{}: R_{{{p},{q}}}({sigma:?})", path.display());
                }
            }
        }
    }
}
