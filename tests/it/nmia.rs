//! NMIA against exact answers on drawn fixtures (one per definition: non-manifold edge,
//! edge-based cluster, restricted-star component, radial order), the oracle and a brute-force
//! storage count on random mixed 3-complexes, and the IG on the real data when present.

use crate::common;
use common::rel;

use proptest::prelude::*;
use topoplex::complex::is_subset;
use topoplex::io::Coords;
use topoplex::oracle::{Oracle, check_structure, compare_structures};
use topoplex::structures::ia::IndexedAdjacency;
use topoplex::structures::ig::IncidenceGraph;
use topoplex::structures::nmia::NonManifoldIa;
use topoplex::{Complex, Topology, fixtures};

fn nmia(c: &Complex) -> NonManifoldIa {
    common::validated(NonManifoldIa::build(c))
}

/// Connected components of the link of `s`, by union-find over the link vertices.
fn link_components(tops: &[Vec<u32>], s: &[u32]) -> usize {
    let link: Vec<Vec<u32>> = tops
        .iter()
        .filter(|t| is_subset(s, t))
        .map(|t| {
            t.iter()
                .copied()
                .filter(|v| !s.contains(v))
                .collect::<Vec<u32>>()
        })
        .filter(|l| !l.is_empty())
        .collect();
    let mut verts: Vec<u32> = link.iter().flatten().copied().collect();
    verts.sort_unstable();
    verts.dedup();
    let mut parent: Vec<usize> = (0..verts.len()).collect();
    for l in &link {
        let a = verts.binary_search(&l[0]).unwrap();
        for w in &l[1..] {
            let b = verts.binary_search(w).unwrap();
            let (ra, rb) = (common::root(&mut parent, a), common::root(&mut parent, b));
            parent[ra] = rb;
        }
    }
    (0..verts.len())
        .filter(|&i| common::root(&mut parent, i) == i)
        .count()
}

/// (C_e, C_v, formula) counted from the complex by brute force on links.
fn brute_storage(c: &Complex) -> (u64, u64, u64) {
    let o = Oracle::new(c);
    let tops: Vec<Vec<u32>> = o.tops.iter().flatten().cloned().collect();
    let n_t = |p: usize| o.tops.get(p).map_or(0, Vec::len) as u64;
    let mut ce = 0u64;
    if o.dimension() >= 1 {
        for e in &o.levels[1] {
            let k = link_components(&tops, e);
            if k >= 2 {
                ce += k as u64;
            }
        }
    }
    let cv: u64 = (0..c.vertex_count())
        .map(|v| link_components(&tops, &[v]) as u64)
        .sum();
    (ce, cv, 8 * n_t(3) + 3 * n_t(2) + 2 * n_t(1) + ce + cv)
}

fn check_storage(s: &NonManifoldIa, c: &Complex) {
    let (ce, cv, total) = brute_storage(c);
    assert_eq!(s.edge_cluster_count() as u64, ce, "C_e");
    assert_eq!(s.vertex_cluster_count() as u64, cv, "C_v");
    assert_eq!((s.storage().integers, s.storage().bits), (total, 0));
}

fn refusal(c: &Complex) -> String {
    common::refusal_of(NonManifoldIa::build(c))
}

#[test]
fn two_dangling_faces_make_a_non_manifold_edge() {
    //        2
    //       / \
    //      0---1      triangles 0 1 2 and 0 1 3 share edge 0-1: a 2-manifold there, but
    //       \ /       lk(0-1) = {2, 3} has two components, so 0-1 is non-manifold with two
    //        3        clusters, linked to each other
    let c = common::complex_of(4, &[vec![0, 1, 2], vec![0, 1, 3]]);
    let s = nmia(&c);
    assert_eq!(s.edge_cluster_count(), 2);
    assert_eq!(s.succeeding(0, 0, 1), Some(1));
    assert_eq!(s.succeeding(1, 0, 1), Some(0));
    assert_eq!(s.succeeding(0, 0, 2), None);
    assert_eq!(s.vertex_clusters(0), &[0]);
    assert_eq!(rel(&s, &[0, 1], 2), vec![vec![0, 1, 2], vec![0, 1, 3]]);
    assert_eq!(rel(&s, &[0, 1, 2], 2), vec![vec![0, 1, 3]]);
    // 3·2 + C_e 2 + C_v 4.
    assert_eq!(s.storage().integers, 12);
    check_storage(&s, &c);
    check_structure(&s, &c).unwrap();
}

#[test]
fn tetrahedron_with_dangling_triangle_and_wire_clusters() {
    //          3 ------ 4 ------ 5     edge 2-3: clusters {tet 0123} and {face 234};
    //         /|\      /               vertex 4: components {face 234} and {wire 45}
    //       0--|--2---/
    //          1
    let c = fixtures::tetrahedron_with_dangling_triangle_and_wire();
    let s = nmia(&c);
    // ids: tet 0, face 1, wire 2.
    assert_eq!(s.succeeding(0, 2, 3), Some(1));
    assert_eq!(s.succeeding(1, 2, 3), Some(0));
    assert_eq!(s.vertex_clusters(4), &[1, 2]);
    assert_eq!(s.vertex_clusters(2), &[0]);
    assert_eq!(
        rel(&s, &[2, 3], 2),
        vec![vec![0, 2, 3], vec![1, 2, 3], vec![2, 3, 4]]
    );
    assert_eq!(rel(&s, &[4], 1), vec![vec![2, 4], vec![3, 4], vec![4, 5]]);
    // 8 + 3 + 2 + C_e 2 + C_v (1 + 1 + 1 + 1 + 2 + 1).
    assert_eq!(s.storage().integers, 22);
    check_storage(&s, &c);
    check_structure(&s, &c).unwrap();
}

#[test]
fn builtin_example_counts() {
    //            4 ----- 5      tet 0123, face 016 on edge 0-1, wires 34 and 45,
    //            |              face 278 pinched at 2, isolated vertex 9
    //            3
    //    6----0--|--2----7
    let c = fixtures::builtin_example();
    let s = nmia(&c);
    // C_e: edge 0-1 has two clusters. C_v: 2, 3 and 4 have two components, 9 none, others one.
    assert_eq!(s.edge_cluster_count(), 2);
    assert_eq!(s.vertex_cluster_count(), 12);
    assert!(s.vertex_clusters(9).is_empty());
    assert_eq!(s.storage().integers, 8 + 6 + 4 + 2 + 12);
    assert_eq!(rel(&s, &[2], 2).len(), 4);
    assert_eq!(
        (0..=3).map(|p| s.top_count(p)).collect::<Vec<_>>(),
        vec![1, 2, 2, 1]
    );
    check_storage(&s, &c);
    check_structure(&s, &c).unwrap();
}

#[test]
fn pinched_pie_is_one_star_component() {
    //        2       4
    //       / \     / \      two closed fans around 0 sharing edge 0-1: four clusters at
    //      3---1---5   |     0-1 (one per triangle), but the restricted star of 0 is one
    //       \  |  /    |     component (its link is a connected figure-eight)
    //        `-0-'----'
    let c = fixtures::pinched_pie();
    let s = nmia(&c);
    // C_e: 4 at 0-1, and 2 at each of 0-2, 0-3, 0-4, 0-5 (two dangling faces each).
    assert_eq!(s.edge_cluster_count(), 4 + 4 * 2);
    // No coordinates: the ring at 0-1 follows ascending ids 012 → 013 → 014 → 015 → 012.
    assert_eq!(s.succeeding(0, 0, 1), Some(1));
    assert_eq!(s.succeeding(3, 0, 1), Some(0));
    assert_eq!(s.vertex_clusters(0).len(), 1);
    assert_eq!(s.vertex_cluster_count(), 6);
    check_storage(&s, &c);
    check_structure(&s, &c).unwrap();
}

#[test]
fn tetrahedra_pinched_at_an_edge_and_at_a_vertex() {
    //     2   4               tets 0123 and 0145 share only edge 0-1: two clusters there;
    //     |\ /|               tet 0 6 7 8 shares only vertex 0: a second component at 0
    //   3-0---1-5
    let c = common::complex_of(9, &[vec![0, 1, 2, 3], vec![0, 1, 4, 5], vec![0, 6, 7, 8]]);
    let s = nmia(&c);
    assert_eq!(s.edge_cluster_count(), 2);
    assert_eq!(s.vertex_clusters(0), &[0, 2]);
    assert_eq!(s.vertex_clusters(1), &[0]);
    assert_eq!(
        rel(&s, &[0, 1], 3),
        vec![vec![0, 1, 2, 3], vec![0, 1, 4, 5]]
    );
    assert_eq!(rel(&s, &[0, 1, 2, 3], 3), Vec::<Vec<u32>>::new());
    check_storage(&s, &c);
    check_structure(&s, &c).unwrap();
}

/// The cube [0,1]³ cut into six tetrahedra around its diagonal 0-7 (vertex i at the corner
/// whose x, y, z are bits 0, 1, 2 of i).
fn kuhn_cube() -> Vec<Vec<u32>> {
    fixtures::freudenthal_grid(1, |[x, y, z]| x | y << 1 | z << 2)
        .map(|mut t| {
            t.sort_unstable();
            t.to_vec()
        })
        .collect()
}

#[test]
fn manifold_tetrahedral_mesh_costs_8n3_plus_n0() {
    //      6-------7
    //     /|      /|     six tetrahedra around the diagonal 0-7: a closed fan there,
    //    4-------5 |     every edge manifold, every vertex star one component
    //    | 2-----|-3
    //    |/      |/
    //    0-------1
    let c = common::complex_of(8, &kuhn_cube());
    let s = nmia(&c);
    assert_eq!(s.edge_cluster_count(), 0);
    assert_eq!(s.storage().integers, 8 * 6 + 8);
    assert_eq!(rel(&s, &[0, 7], 3).len(), 6);
    assert_eq!(rel(&s, &[0, 7], 2).len(), 6);
    check_storage(&s, &c);
    check_structure(&s, &c).unwrap();
}

fn with_coords(n: u32, tops: &[Vec<u32>], xyz: &[[f64; 3]]) -> Complex {
    let ids: Vec<u32> = tops.concat();
    let mut offsets = vec![0];
    for t in tops {
        offsets.push(offsets.last().unwrap() + t.len());
    }
    let data = xyz.iter().flatten().copied().collect();
    Complex::from_arrays(n, &ids, &offsets, Some(Coords { dim: 3, data })).unwrap()
}

fn around_z(deg: f64) -> [f64; 3] {
    let r = deg.to_radians();
    [r.cos(), r.sin(), 0.5]
}

#[test]
fn radial_order_of_dangling_faces_follows_angles() {
    //   top view, edge 0-1 along +z through the centre:
    //
    //              4 (90°)
    //              |
    //   3 (200°) - 0/1 - 2 (0°)          counter-clockwise: 2, 4, 3, 5
    //               \
    //                5 (300°)
    let tops = vec![vec![0, 1, 2], vec![0, 1, 3], vec![0, 1, 4], vec![0, 1, 5]];
    let xyz = [
        [0.0, 0.0, 0.0],
        [0.0, 0.0, 1.0],
        around_z(0.0),
        around_z(200.0),
        around_z(90.0),
        around_z(300.0),
    ];
    let c = with_coords(6, &tops, &xyz);
    let s = nmia(&c);
    // Face ids are their rows: [0 1 2] = 0, [0 1 3] = 1, [0 1 4] = 2, [0 1 5] = 3.
    let next: Vec<Option<u32>> = (0..4).map(|f| s.succeeding(f, 0, 1)).collect();
    assert_eq!(next, vec![Some(2), Some(3), Some(1), Some(0)]);
    check_structure(&s, &c).unwrap();
    // Without coordinates: ascending ids.
    let c = common::complex_of(6, &tops);
    let s = nmia(&c);
    let next: Vec<Option<u32>> = (0..4).map(|f| s.succeeding(f, 0, 1)).collect();
    assert_eq!(next, vec![Some(1), Some(2), Some(3), Some(0)]);
}

#[test]
fn radial_order_of_a_fan_and_a_face() {
    //   top view, edge 0-1 along +z:
    //
    //        2 (120°)   3 (60°)
    //             \  A  /            fan of tets A = 0 1 2 3 and B = 0 1 3 4 sweeps
    //              \   /   B         counter-clockwise from 4 (0°) to 2 (120°): entry B,
    //     5 ------ 0/1 ------ 4      exit A; then the dangling face F = 0 1 5 (240°):
    //   (240°)                       A → F → B around 0-1
    let tops = vec![vec![0, 1, 2, 3], vec![0, 1, 3, 4], vec![0, 1, 5]];
    let xyz = [
        [0.0, 0.0, 0.0],
        [0.0, 0.0, 1.0],
        around_z(120.0),
        around_z(60.0),
        around_z(0.0),
        around_z(240.0),
    ];
    let c = with_coords(6, &tops, &xyz);
    let s = nmia(&c);
    let (a, b, f) = (0, 1, 2);
    assert_eq!(s.succeeding(a, 0, 1), Some(f));
    assert_eq!(s.succeeding(f, 0, 1), Some(b));
    assert_eq!(s.succeeding(b, 0, 1), None);
    check_storage(&s, &c);
    check_structure(&s, &c).unwrap();
    // Without coordinates the fan runs from its lower end vertex (2, in A) to 4 (in B).
    let c = common::complex_of(6, &tops);
    let s = nmia(&c);
    assert_eq!(s.succeeding(b, 0, 1), Some(f));
    assert_eq!(s.succeeding(f, 0, 1), Some(a));
    assert_eq!(s.succeeding(a, 0, 1), None);
}

#[test]
fn refusals_name_the_offending_simplex() {
    let c = common::complex_of(6, &[vec![0, 1, 2, 3, 4], vec![4, 5]]);
    let r = refusal(&c);
    assert!(
        r.starts_with("top 4-simplex [0 1 2 3 4] has dimension 4"),
        "{r}"
    );
    //   three tetrahedra on triangle 0 1 2 (apexes 3, 4, 5): not embeddable in E^3
    let c = common::complex_of(6, &[vec![0, 1, 2, 3], vec![0, 1, 2, 4], vec![0, 1, 2, 5]]);
    let r = refusal(&c);
    assert!(
        r.contains("triangle [0 1 2] is a face of more than two tetrahedra"),
        "{r}"
    );
    // Lower dimensions are accepted: a 2-complex is all dangling faces. The only fixture
    // refused is one with a triangle in three tetrahedra (the survey's Fig. 5 star).
    for (name, c) in fixtures::all() {
        if expected_refusal(&c).is_some() {
            assert!(NonManifoldIa::build(&c).is_err(), "{name}");
            continue;
        }
        let s = nmia(&c);
        check_structure(&s, &c).unwrap_or_else(|e| panic!("{name}: {e}"));
        check_storage(&s, &c);
    }
    let c = Complex::from_simplices(2, &[]).unwrap();
    check_structure(&nmia(&c), &c).unwrap();
}

/// The lexicographically first triangle in three or more tetrahedra, by brute force.
fn expected_refusal(c: &Complex) -> Option<Vec<u32>> {
    let o = Oracle::new(c);
    if o.dimension() < 3 {
        return None;
    }
    o.levels[2]
        .iter()
        .find(|f| o.levels[3].iter().filter(|t| is_subset(f, t)).count() > 2)
        .cloned()
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 300, ..ProptestConfig::default() })]
    #[test]
    fn random_mixed_complexes_match_the_oracle(c in common::random_complex(3, 9, 9)) {
        common::refused_or_matches(&c, expected_refusal(&c), NonManifoldIa::build, check_storage)?;
    }
}

#[test]
fn octahedron_costs_what_the_extended_ia_costs() {
    //        4
    //      / | \        a closed surface: every edge is in two dangling faces, so it is
    //   2 - 0/1 - 3     non-manifold with two clusters (2 integers); 3n_2 + 2n_1 + n_0
    //      \ | /        equals the 2D extended IA's 6n_2 + n_0 since 2n_1 = 3n_2
    //        5
    let tops: Vec<Vec<u32>> = (0..8u32)
        .map(|m| vec![m & 1, 2 + (m >> 1 & 1), 4 + (m >> 2 & 1)])
        .collect();
    let c = common::complex_of(6, &tops);
    let s = nmia(&c);
    assert_eq!(s.edge_cluster_count(), 2 * 12);
    assert_eq!(s.storage().integers, 6 * 8 + 6);
    check_storage(&s, &c);
    check_structure(&s, &c).unwrap();
}

#[test]
fn real_data_matches_the_incidence_graph() {
    for (path, c) in common::shared_complexes() {
        if c.dimension() > 3 {
            assert!(NonManifoldIa::build(&c).is_err());
            continue;
        }
        // Build, validation and comparison walk every star in debug builds: keep to the
        // files of moderate size (the big ones are for benchmarks).
        let tops: usize = (0..=3).map(|p| c.tops(p).len()).sum();
        if tops > 11_000 {
            continue;
        }
        let s = nmia(&c);
        // Where the extended IA applies too, both count the same integers (see the module
        // docs: a manifold surface's edges each cost two cluster links, 2n_1 = 3n_2).
        if let Ok(ia) = IndexedAdjacency::build(&c) {
            if c.dimension() >= 2 && s.edge_cluster_count() == 2 * s.count(1) {
                assert_eq!(s.storage().integers, ia.storage().integers);
            }
            if c.dimension() == 3 && s.edge_cluster_count() == 0 {
                assert_eq!(s.storage().integers, ia.storage().integers);
            }
        }
        if tops <= 4_000 {
            let g = IncidenceGraph::build(&c).unwrap();
            compare_structures(&s, &g).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        }
    }
}
