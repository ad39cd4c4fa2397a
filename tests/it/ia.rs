//! Extended IA against exact answers on drawn fixtures, the oracle on random pseudo-manifolds
//! of dimensions 0–6 (pinched vertices and several components included), correct refusals on
//! random arbitrary complexes, and the IG on the real data when present.

use crate::common;
use common::{Rng, rel};

use std::collections::{BTreeMap, BTreeSet};

use proptest::prelude::*;
use topoplex::complex::is_subset;
use topoplex::oracle::{Oracle, check_structure, compare_structures};
use topoplex::structures::ia::{IndexedAdjacency, NONE};
use topoplex::structures::ig::IncidenceGraph;
use topoplex::{Complex, Topology, fixtures};

fn ia(c: &Complex) -> IndexedAdjacency {
    common::validated(IndexedAdjacency::build(c))
}

fn refusal(c: &Complex) -> String {
    common::refusal_of(IndexedAdjacency::build(c))
}

/// Components of the star of every vertex by brute force: d-simplices at v joined when they
/// share d vertices, v among them. Returns Σ_v components.
fn star_components_brute(tops: &[Vec<u32>], n: u32) -> u64 {
    let mut total = 0u64;
    for v in 0..n {
        let at: Vec<&Vec<u32>> = tops.iter().filter(|t| t.contains(&v)).collect();
        let mut comp: Vec<usize> = (0..at.len()).collect();
        for i in 0..at.len() {
            for j in i + 1..at.len() {
                let shared = at[i].iter().filter(|x| at[j].contains(x)).count();
                if shared + 1 == at[i].len() {
                    let (a, b) = (common::root(&mut comp, i), common::root(&mut comp, j));
                    comp[a] = b;
                }
            }
        }
        total += (0..at.len())
            .filter(|&i| common::root(&mut comp, i) == i)
            .count() as u64;
    }
    total
}

/// The storage the module doc promises, counted from the complex alone.
fn expected_integers(c: &Complex) -> (u64, u64) {
    let d = c.dimension();
    let tops: Vec<Vec<u32>> = c.tops(d).iter().map(<[u32]>::to_vec).collect();
    let plain = (2 * (d + 1) * tops.len()) as u64;
    (
        plain,
        plain + star_components_brute(&tops, c.vertex_count()),
    )
}

fn check_storage(s: &IndexedAdjacency, c: &Complex) {
    let (plain, ext) = expected_integers(c);
    assert_eq!(s.plain_ia_integers(), plain);
    assert_eq!((s.storage().integers, s.storage().bits), (ext, 0));
}

#[test]
fn bowtie_pinched_vertex() {
    //   0       3
    //   | \   / |
    //   |  2    |      two triangles sharing only vertex 2: a pinched vertex, accepted;
    //   | /   \ |      vertex 2 keeps one reference per star component
    //   1       4
    let c = fixtures::bowtie();
    let s = ia(&c);
    assert_eq!(s.star_components(2), &[0, 1]);
    assert_eq!(s.star_components(0), &[0]);
    assert_eq!(s.neighbours(0), &[NONE, NONE, NONE]);
    assert_eq!(rel(&s, &[2], 2), vec![vec![0, 1, 2], vec![2, 3, 4]]);
    assert_eq!(rel(&s, &[2], 0), vec![vec![0], vec![1], vec![3], vec![4]]);
    assert_eq!(
        rel(&s, &[1, 2], 1),
        vec![vec![0, 1], vec![0, 2], vec![2, 3], vec![2, 4]]
    );
    // 2·3·2 for the plain IA, plus 1 + 1 + 2 + 1 + 1 vertex references.
    assert_eq!(s.plain_ia_integers(), 12);
    assert_eq!(s.storage().integers, 18);
    check_structure(&s, &c).unwrap();
}

#[test]
fn octahedron_adjacency() {
    //        4            vertices 0..5 = +x -x +y -y +z -z;
    //      / | \          the eight faces pick one of each pair
    //   2 - 0/1 - 3
    //      \ | /
    //        5
    let mut tops = Vec::new();
    for m in 0..8u32 {
        tops.push(vec![m & 1, 2 + (m >> 1 & 1), 4 + (m >> 2 & 1)]);
    }
    let c = common::complex_of(6, &tops);
    let s = ia(&c);
    // Face [0 2 4] (id 0): across the facet opposite 0 is [1 2 4], opposite 2 is [0 3 4],
    // opposite 4 is [0 2 5].
    let names: Vec<Vec<u32>> = s
        .neighbours(0)
        .iter()
        .map(|&t| s.top_simplices().get(t as usize).to_vec())
        .collect();
    assert_eq!(names, vec![vec![1, 2, 4], vec![0, 3, 4], vec![0, 2, 5]]);
    assert_eq!(rel(&s, &[0], 2).len(), 4);
    assert_eq!(rel(&s, &[0, 2], 2), vec![vec![0, 2, 4], vec![0, 2, 5]]);
    assert_eq!(rel(&s, &[0, 2], 1).len(), 6);
    assert_eq!(s.count(1), 12);
    // Closed, manifold: 2·3·8 + one reference per vertex.
    assert_eq!(s.storage().integers, 48 + 6);
    check_structure(&s, &c).unwrap();
}

#[test]
fn isolated_vertices_only_is_dimension_zero() {
    //   0   1   2      three isolated vertices: a 0-pseudo-manifold
    let c = Complex::from_simplices(3, &[]).unwrap();
    let s = ia(&c);
    assert_eq!(s.dimension(), 0);
    assert_eq!(rel(&s, &[1], 0), Vec::<Vec<u32>>::new());
    assert_eq!(s.storage().integers, 2 * 3 + 3);
    check_structure(&s, &c).unwrap();
}

#[test]
fn graphs_of_degree_two_are_one_dimensional() {
    //   0 --- 1 --- 2        3 --- 4
    //                         \   /     a path and a cycle: accepted
    //                           5
    let c = common::complex_of(
        6,
        &[vec![0, 1], vec![1, 2], vec![3, 4], vec![4, 5], vec![3, 5]],
    );
    let s = ia(&c);
    assert_eq!(rel(&s, &[1, 2], 1), vec![vec![0, 1]]);
    assert_eq!(rel(&s, &[4], 0), vec![vec![3], vec![5]]);
    check_storage(&s, &c);
    check_structure(&s, &c).unwrap();
    //   0 --- 1 --- 2
    //         |             vertex 1 in three edges: refused, naming it
    //         3
    let c = common::complex_of(4, &[vec![0, 1], vec![1, 2], vec![1, 3]]);
    let r = refusal(&c);
    assert!(
        r.contains("0-simplex [1] is a face of more than two 1-simplices"),
        "{r}"
    );
}

#[test]
fn refusals_name_the_first_offending_simplex() {
    // builtin example: isolated vertex 9 comes first (dimension 0), before wire edges.
    let r = refusal(&fixtures::builtin_example());
    assert!(r.starts_with("[9] is an isolated vertex"), "{r}");
    //          3 ------ 4 ------ 5     wire edge 4-5 is the lowest top simplex below 3
    let r = refusal(&fixtures::tetrahedron_with_dangling_triangle_and_wire());
    assert!(r.starts_with("[4 5] is a top 1-simplex"), "{r}");
    //   3 -- 0 -- 4   edge 0-1 in three triangles
    let r = refusal(&fixtures::three_triangles_on_an_edge());
    assert!(
        r.contains(
            "1-simplex [0 1] is a face of more than two 2-simplices ([0 1 2], [0 1 3], [0 1 4]"
        ),
        "{r}"
    );
    let r = refusal(&fixtures::pinched_pie());
    assert!(r.contains("[0 1] is a face of more than two"), "{r}");
    // Through the shared dispatch too.
    assert!(topoplex::build(topoplex::StructureKind::Ia, &fixtures::bowtie()).is_ok());
}

#[test]
fn two_tetrahedra_and_a_pinched_pair() {
    //      3                  6       tetrahedra 0123 and 1234 share face 123;
    //     /|\                /|\      tetrahedra 4567 and 4 8 9 10 share only vertex 4
    //    0-+-2---4 ...      4-+-7
    //     \|/ \ /            \|/
    //      1   (1234)         5
    let c = common::complex_of(
        11,
        &[
            vec![0, 1, 2, 3],
            vec![1, 2, 3, 4],
            vec![4, 5, 6, 7],
            vec![4, 8, 9, 10],
        ],
    );
    let s = ia(&c);
    assert_eq!(s.star_components(4), &[1, 2, 3]);
    assert_eq!(s.neighbours(0), &[1, NONE, NONE, NONE]);
    assert_eq!(rel(&s, &[4], 3).len(), 3);
    assert_eq!(
        rel(&s, &[1, 2], 3),
        vec![vec![0, 1, 2, 3], vec![1, 2, 3, 4]]
    );
    assert_eq!(rel(&s, &[1, 2, 3], 2).len(), 6);
    check_storage(&s, &c);
    check_structure(&s, &c).unwrap();
}

/// A random d-pseudo-manifold: 1–3 components, each a subset of the boundary of the
/// (d+1)-cross-polytope refined by stellar subdivisions, vertices of different components
/// identified at random (pinched vertices, for d ≥ 2), ids shuffled.
fn random_pseudo_manifold(d: usize, seed: u64) -> (u32, Vec<Vec<u32>>) {
    let mut rng = Rng(seed | 1);
    let mut all: Vec<Vec<u32>> = Vec::new();
    let mut n = 0u32;
    let comps = 1 + rng.below(3);
    let budget = match d {
        5.. => 3,
        4 => 6,
        _ => 12,
    };
    let mut firsts = Vec::new();
    for _ in 0..comps {
        let base = n;
        n += 2 * (d as u32 + 1);
        let mut tops: Vec<Vec<u32>> = (0..1u32 << (d + 1))
            .map(|m| {
                (0..=d as u32)
                    .map(|i| base + 2 * i + (m >> i & 1))
                    .collect()
            })
            .collect();
        // Keep a random subset, at least one.
        let keep = 1 + rng.below(budget.min(tops.len()));
        while tops.len() > keep {
            let i = rng.below(tops.len());
            tops.swap_remove(i);
        }
        for _ in 0..rng.below(3) {
            let i = rng.below(tops.len());
            let t = tops.swap_remove(i);
            for j in 0..=d {
                let mut s = t.clone();
                s[j] = n;
                s.sort_unstable();
                tops.push(s);
            }
            n += 1;
        }
        firsts.push(tops.clone());
        all.extend(tops);
    }
    // Identify vertices across components (never within one: that could fold two facets).
    let mut map: Vec<u32> = (0..n).collect();
    if d >= 2 {
        for c in 1..firsts.len() {
            if rng.below(2) == 0 {
                let a = firsts[c - 1][0][rng.below(d + 1)];
                let b = firsts[c][0][rng.below(d + 1)];
                map[b as usize] = map[a as usize];
            }
        }
    }
    // Compact and shuffle the ids.
    let used: BTreeSet<u32> = all.iter().flatten().map(|&v| map[v as usize]).collect();
    let mut ids: Vec<u32> = (0..used.len() as u32).collect();
    for i in (1..ids.len()).rev() {
        ids.swap(i, rng.below(i + 1));
    }
    let rename: BTreeMap<u32, u32> = used.iter().copied().zip(ids).collect();
    let tops = all
        .iter()
        .map(|t| t.iter().map(|&v| rename[&map[v as usize]]).collect())
        .collect();
    (rename.len() as u32, tops)
}

/// What the IA must say about a complex, by brute force: `Some(simplex named)` if refused.
fn expected_refusal(c: &Complex) -> Option<Vec<u32>> {
    let o = Oracle::new(c);
    let d = o.dimension();
    for p in 0..d {
        if let Some(s) = o.tops[p].first() {
            return Some(s.clone());
        }
    }
    if d == 0 {
        return None;
    }
    o.levels[d - 1]
        .iter()
        .find(|f| o.levels[d].iter().filter(|t| is_subset(f, t)).count() > 2)
        .cloned()
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 64, ..ProptestConfig::default() })]
    #[test]
    fn random_pseudo_manifolds_match_the_oracle(d in 1usize..=6, seed in any::<u64>()) {
        let (n, tops) = random_pseudo_manifold(d, seed);
        let c = common::complex_of(n, &tops);
        prop_assert_eq!(c.dimension(), d);
        prop_assert_eq!(expected_refusal(&c), None, "generator made a non-pseudo-manifold");
        let s = ia(&c);
        check_storage(&s, &c);
        prop_assert_eq!(check_structure(&s, &c), Ok(()));
    }

    #[test]
    fn random_complexes_are_refused_correctly_or_match(c in common::random_complex(6, 8, 7)) {
        common::refused_or_matches(&c, expected_refusal(&c), IndexedAdjacency::build, check_storage)?;
    }
}

#[test]
fn real_data_matches_the_incidence_graph() {
    for (path, c) in common::shared_complexes() {
        // Build, validation and comparison walk every star in debug builds: keep to the
        // files of moderate size (the big ones are for benchmarks).
        let tops = c.tops(c.dimension()).len();
        if tops > 11_000 {
            continue;
        }
        let Ok(s) = IndexedAdjacency::build(&c) else {
            continue;
        };
        s.validate().unwrap();
        let d = c.dimension();
        assert_eq!(s.plain_ia_integers(), (2 * (d + 1) * tops) as u64);
        assert!(s.storage().integers >= s.plain_ia_integers() + c.vertex_count() as u64);
        if tops <= 4_000 {
            let g = IncidenceGraph::build(&c).unwrap();
            compare_structures(&s, &g).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        }
    }
}

/// The tetrahedra around one edge [0, apex]: vertex 0 starts over a hundred triangles, so a ring
/// vertex (0 is its lower neighbour) finds its triangles through 0 by searching them one by one
/// rather than scanning 0's rows; the apex meets both ways. Every vertex's star (both orders)
/// and each R_{0,q} equal the oracle's, the edges and triangles in ascending dense order.
#[test]
fn stars_beside_a_hub_vertex_with_many_faces_match_the_oracle() {
    use topoplex::{Navigate, Order};
    let k = 80u32;
    let apex = k + 1;
    let tets: Vec<Vec<u32>> = (1..k).map(|i| vec![0, i, i + 1, apex]).collect();
    let refs: Vec<&[u32]> = tets.iter().map(Vec::as_slice).collect();
    let c = Complex::from_simplices(apex + 1, &refs).unwrap();
    let s = ia(&c);
    let n: &dyn Navigate = s.as_navigate().unwrap();
    let o = Oracle::new(&c);
    let mut buf = Vec::new();
    for v in 0..=apex {
        let h = n.handle(0, v).unwrap();
        let mut want: Vec<Vec<u32>> = (1..=3).flat_map(|q| o.relation(&[v], q)).collect();
        want.sort();
        for order in [Order::Natural, Order::Lexicographic] {
            n.star(h, order, &mut buf).unwrap();
            let mut got: Vec<Vec<u32>> = buf
                .iter()
                .map(|&x| n.vertices_of(x).unwrap().to_vec())
                .collect();
            got.sort();
            assert_eq!(got, want, "star of {v} ({order:?})");
        }
        for q in 1..=2 {
            n.related(h, q, Order::Natural, &mut buf).unwrap();
            let ids: Vec<u32> = buf.iter().map(|x| x.index()).collect();
            assert!(
                ids.is_sorted_by(|a, b| a < b),
                "R_{{0,{q}}} of {v}: {ids:?}"
            );
            assert_eq!(ids.len(), o.relation(&[v], q).len(), "R_{{0,{q}}} of {v}");
        }
    }
}
