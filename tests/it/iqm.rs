//! IQM: the standard decomposition checked from its definition (brute force, independent of the
//! implementation), exact decompositions of the survey's figures, every relation against the
//! oracle, the component writers, and the real data against the IG when present.

use crate::common::{self, rel};

use std::collections::{BTreeMap, BTreeSet, HashMap};

use proptest::prelude::*;
use topoplex::complex::is_subset;
use topoplex::oracle::{check_structure, compare_structures};
use topoplex::structures::ig::IncidenceGraph;
use topoplex::structures::iqm::{Decomposition, Iqm};
use topoplex::{Complex, Topology, fixtures};

fn iqm(c: &Complex) -> Iqm {
    common::validated(Iqm::build(c))
}

/// All top simplices of a complex, any dimension, ascending ids.
fn tops_of(c: &Complex) -> Vec<Vec<u32>> {
    (0..=c.dimension())
        .flat_map(|k| c.tops(k).iter().map(<[u32]>::to_vec).collect::<Vec<_>>())
        .collect()
}

/// A top simplex of a component in original ids.
fn original_row(piece: &topoplex::structures::iqm::ComponentPiece, row: &[u32]) -> Vec<u32> {
    row.iter().map(|&l| piece.original[l as usize]).collect()
}

/// Canonical form: components as sets of top simplices (original ids), and for each vertex the
/// partition of its star into copies (each copy: the set of top simplices holding it).
type Canon = (
    BTreeSet<BTreeSet<Vec<u32>>>,
    BTreeMap<u32, BTreeSet<BTreeSet<Vec<u32>>>>,
);

fn canon(dec: &Decomposition, relabel: impl Fn(u32) -> u32) -> Canon {
    let mut comps = BTreeSet::new();
    let mut copies: BTreeMap<u32, BTreeSet<BTreeSet<Vec<u32>>>> = BTreeMap::new();
    for piece in &dec.components {
        let k = piece.dimension;
        let mut set = BTreeSet::new();
        let mut star: Vec<BTreeSet<Vec<u32>>> = vec![BTreeSet::new(); piece.original.len()];
        for row in piece.tops.chunks_exact(k + 1) {
            let mut t: Vec<u32> = row
                .iter()
                .map(|&l| relabel(piece.original[l as usize]))
                .collect();
            t.sort_unstable();
            for &l in row {
                star[l as usize].insert(t.clone());
            }
            set.insert(t);
        }
        for (l, s) in star.into_iter().enumerate() {
            copies
                .entry(relabel(piece.original[l]))
                .or_default()
                .insert(s);
        }
        comps.insert(set);
    }
    (comps, copies)
}

/// The standard decomposition straight from its definition, by brute force: joints are facets
/// shared by exactly two top simplices of one dimension and in no other top simplex; the copies
/// of v are the classes of its star under manifold adjacency through joints containing v.
fn brute_force_copies(c: &Complex) -> BTreeMap<u32, BTreeSet<BTreeSet<Vec<u32>>>> {
    let tops = tops_of(c);
    let joint = |a: &[u32], b: &[u32]| -> bool {
        if a.len() != b.len() || a.len() < 2 || a == b {
            return false;
        }
        let tau: Vec<u32> = a.iter().copied().filter(|v| b.contains(v)).collect();
        tau.len() == a.len() - 1 && tops.iter().filter(|t| is_subset(&tau, t)).count() == 2
    };
    let mut out = BTreeMap::new();
    for v in 0..c.vertex_count() {
        let star: Vec<&Vec<u32>> = tops.iter().filter(|t| t.contains(&v)).collect();
        let mut class: Vec<usize> = (0..star.len()).collect();
        // Relax to a fixpoint: tiny inputs only.
        let mut changed = true;
        while changed {
            changed = false;
            for i in 0..star.len() {
                for j in 0..star.len() {
                    if class[i] != class[j] && joint(star[i], star[j]) {
                        let (lo, hi) = (class[i].min(class[j]), class[i].max(class[j]));
                        for x in class.iter_mut() {
                            if *x == hi {
                                *x = lo;
                            }
                        }
                        changed = true;
                    }
                }
            }
        }
        let mut parts: BTreeMap<usize, BTreeSet<Vec<u32>>> = BTreeMap::new();
        for (i, t) in star.iter().enumerate() {
            parts.entry(class[i]).or_default().insert((*t).clone());
        }
        out.insert(v, parts.into_values().collect());
    }
    out
}

/// Every component is a connected, regular initial quasi-manifold: for every local vertex, the
/// top simplices of its star are connected through facets containing it that have exactly two
/// cofaces in the component.
fn assert_initial_quasi_manifolds(dec: &Decomposition) -> Result<(), String> {
    for (i, piece) in dec.components.iter().enumerate() {
        let k = piece.dimension;
        let rows: Vec<Vec<u32>> = piece
            .tops
            .chunks_exact(k + 1)
            .map(|r| {
                let mut r = r.to_vec();
                r.sort_unstable();
                r
            })
            .collect();
        let m = piece.original.len();
        if rows.iter().any(|r| r.iter().any(|&l| l as usize >= m)) {
            return Err(format!("component {i}: local id out of range"));
        }
        let mut cofaces: HashMap<Vec<u32>, usize> = HashMap::new();
        for r in &rows {
            if r.windows(2).any(|w| w[0] == w[1]) {
                return Err(format!("component {i}: a top simplex repeats a vertex"));
            }
            for skip in 0..r.len() {
                let mut f = r.clone();
                f.remove(skip);
                *cofaces.entry(f).or_default() += 1;
            }
        }
        // Union-find over rows, per vertex star and for the whole component.
        fn find(p: &mut [usize], mut x: usize) -> usize {
            while p[x] != x {
                x = p[x];
            }
            x
        }
        let mut whole: Vec<usize> = (0..rows.len()).collect();
        for x in 0..m as u32 {
            let star: Vec<usize> = (0..rows.len()).filter(|&r| rows[r].contains(&x)).collect();
            if star.is_empty() {
                return Err(format!(
                    "component {i}: local vertex {x} is in no top simplex"
                ));
            }
            let mut p: Vec<usize> = (0..star.len()).collect();
            for a in 0..star.len() {
                for b in a + 1..star.len() {
                    let (ra, rb) = (&rows[star[a]], &rows[star[b]]);
                    let shared: Vec<u32> = ra.iter().copied().filter(|v| rb.contains(v)).collect();
                    if shared.len() == k && cofaces.get(&shared) == Some(&2) {
                        let (fa, fb) = (find(&mut p, a), find(&mut p, b));
                        p[fa] = fb;
                    }
                }
                let (fa, f0) = (find(&mut whole, star[a]), find(&mut whole, star[0]));
                whole[fa] = f0;
            }
            let roots: BTreeSet<usize> = (0..star.len()).map(|a| find(&mut p, a)).collect();
            if roots.len() != 1 {
                return Err(format!(
                    "component {i}: the star of local vertex {x} (vertex {}) is in {} manifold-connected parts",
                    piece.original[x as usize],
                    roots.len()
                ));
            }
        }
        let roots: BTreeSet<usize> = (0..rows.len()).map(|r| find(&mut whole, r)).collect();
        if roots.len() != 1 {
            return Err(format!("component {i} is not connected"));
        }
    }
    Ok(())
}

/// Gluing the components back (each local id to its original id) gives the complex's top
/// simplices exactly once each, and the copy arrays agree with the components.
fn assert_glues_back(dec: &Decomposition, c: &Complex) -> Result<(), String> {
    let mut glued = Vec::new();
    for piece in &dec.components {
        for row in piece.tops.chunks_exact(piece.dimension + 1) {
            let mut t = original_row(piece, row);
            t.sort_unstable();
            if t.windows(2).any(|w| w[0] >= w[1]) {
                return Err(format!(
                    "top simplex {t:?}: not ascending or repeats a vertex"
                ));
            }
            glued.push(t);
        }
        for (l, &v) in piece.original.iter().enumerate() {
            let g = piece.first_copy as usize + l;
            if dec.copy_vertex[g] != v {
                return Err(format!(
                    "copy {g}: copy_vertex disagrees with its component"
                ));
            }
        }
    }
    glued.sort();
    let mut want = tops_of(c);
    want.sort();
    if glued != want {
        return Err(format!("glued {glued:?}, complex has {want:?}"));
    }
    for (a, &v) in dec.split_vertices.iter().enumerate() {
        let copies =
            &dec.split_copies[dec.split_offsets[a] as usize..dec.split_offsets[a + 1] as usize];
        if copies.len() < 2 || copies.iter().any(|&g| dec.copy_vertex[g as usize] != v) {
            return Err(format!("hyperarc of split vertex {v} is wrong: {copies:?}"));
        }
    }
    Ok(())
}

/// Every component's top simplex, read through its local ids as given, is the complex's top
/// simplex in its input winding (the vertex order of its first listing).
fn assert_winding_kept(dec: &Decomposition, c: &Complex) -> Result<(), String> {
    for piece in &dec.components {
        let k = piece.dimension;
        for row in piece.tops.chunks_exact(k + 1) {
            let given = original_row(piece, row);
            let mut sorted = given.clone();
            sorted.sort_unstable();
            let Some(i) = c.tops(k).find(&sorted) else {
                return Err(format!("{given:?} is no top simplex of the complex"));
            };
            let want = c.top_oriented(k, i);
            if given != want {
                return Err(format!("component row {given:?}, input winding {want:?}"));
            }
        }
    }
    Ok(())
}

fn check_decomposition(c: &Complex) -> Result<(), String> {
    let s = iqm(c);
    let dec = s.decomposition();
    assert_initial_quasi_manifolds(&dec)?;
    assert_glues_back(&dec, c)?;
    assert_winding_kept(&dec, c)?;
    let (_, copies) = canon(&dec, |v| v);
    let want = brute_force_copies(c);
    if copies != want {
        return Err(format!("copies {copies:?}, definition gives {want:?}"));
    }
    if s.component_count() != dec.components.len() {
        return Err("component_count disagrees".into());
    }
    Ok(())
}

fn set(rows: &[&[u32]]) -> BTreeSet<Vec<u32>> {
    rows.iter().map(|r| r.to_vec()).collect()
}

/// Copies of each vertex as sets of top simplices; vertices with one copy omitted.
fn split_of(dec: &Decomposition) -> BTreeMap<u32, BTreeSet<BTreeSet<Vec<u32>>>> {
    canon(dec, |v| v)
        .1
        .into_iter()
        .filter(|(_, p)| p.len() > 1)
        .collect()
}

#[test]
fn pinched_pie_splits_into_two_disks() {
    //        2       4
    //       / \     / \
    //      3---1---5   |     two closed fans at 0 sharing edge 0-1 (in four triangles)
    //       \  |  /    |
    //        `-0-'----'
    let s = iqm(&fixtures::pinched_pie());
    let dec = s.decomposition();
    let (comps, _) = canon(&dec, |v| v);
    let a = set(&[&[0, 1, 2], &[0, 2, 3], &[0, 1, 3]]);
    let b = set(&[&[0, 1, 4], &[0, 4, 5], &[0, 1, 5]]);
    assert_eq!(comps, [a.clone(), b.clone()].into_iter().collect());
    // Each fan is cut open along 0-1: vertex 1 gets one copy per triangle, 0 one per fan.
    let split = split_of(&dec);
    assert_eq!(split.keys().copied().collect::<Vec<_>>(), vec![0, 1]);
    assert_eq!(split[&0], [a, b].into_iter().collect());
    assert_eq!(split[&1].len(), 4);
    assert!(split[&1].iter().all(|c| c.len() == 1));
    assert_eq!(dec.split_vertices, vec![0, 1]);
    // 2 components + 6·6 triangle refs + 10 copies + hyperarcs (2 vertices + 6 copies) + 2·6.
    assert_eq!(
        (s.storage().integers, s.storage().bits),
        (2 + 36 + 10 + 8 + 12, 0)
    );
    // Relations across the cut edge see both fans.
    assert_eq!(
        rel(&s, &[0, 1], 2),
        vec![vec![0, 1, 2], vec![0, 1, 3], vec![0, 1, 4], vec![0, 1, 5]]
    );
    assert_eq!(
        rel(&s, &[0, 1, 2], 2),
        vec![vec![0, 1, 3], vec![0, 1, 4], vec![0, 1, 5], vec![0, 2, 3]]
    );
    assert_eq!(
        rel(&s, &[1], 0),
        vec![vec![0], vec![2], vec![3], vec![4], vec![5]]
    );
}

#[test]
fn pseudo_manifold_strip_is_one_component_with_vertex_0_split() {
    //    0 ---- 3 ---- 5 ---- 6        every edge in at most two triangles, yet the star
    //   / \    / \    / \    /         of 0 is two fans meeting only at 0
    //  1 ---- 2 ---- 4 ---- 0
    let c = fixtures::strip_pinched_at_a_vertex();
    let s = iqm(&c);
    let dec = s.decomposition();
    assert_eq!(s.component_count(), 1);
    assert_eq!(dec.components[0].dimension, 2);
    assert_eq!(dec.components[0].original.len(), 8);
    let split = split_of(&dec);
    assert_eq!(split.len(), 1);
    assert_eq!(
        split[&0],
        [
            set(&[&[0, 1, 2], &[0, 2, 3]]),
            set(&[&[0, 4, 5], &[0, 5, 6]])
        ]
        .into_iter()
        .collect()
    );
    // Both copies of 0 are in the one component.
    assert_eq!(dec.split_copies.len(), 2);
    assert!(
        dec.split_copies
            .iter()
            .all(|&g| dec.copy_component[g as usize] == 0)
    );
}

#[test]
fn vertex_with_four_iqm_components_but_two_clusters() {
    // tetrahedra 0123, 0124, 0125 on triangle 012; 0134 joins 0123 and 0124; tetrahedron
    // 0678 and triangle 0 9 10 touch at 0 only
    let s = iqm(&fixtures::four_iqm_components_two_clusters());
    let dec = s.decomposition();
    let (comps, _) = canon(&dec, |v| v);
    let want: BTreeSet<BTreeSet<Vec<u32>>> = [
        set(&[&[0, 1, 2, 3], &[0, 1, 2, 4], &[0, 1, 3, 4]]),
        set(&[&[0, 1, 2, 5]]),
        set(&[&[0, 6, 7, 8]]),
        set(&[&[0, 9, 10]]),
    ]
    .into_iter()
    .collect();
    assert_eq!(comps, want);
    let counts: BTreeMap<u32, usize> = split_of(&dec).iter().map(|(&v, p)| (v, p.len())).collect();
    // 2 is cut three ways: 0123 and 0124 share only the non-manifold triangle 012 around it.
    assert_eq!(counts, [(0, 4), (1, 2), (2, 3)].into_iter().collect());
    assert_eq!(
        (0..dec.components.len())
            .map(|i| s.component_dimension(i))
            .collect::<Vec<_>>(),
        vec![3, 3, 3, 2]
    );
}

#[test]
fn builtin_example_components() {
    // tetrahedron 0123, triangle 016 on edge 01, wire 3-4-5, triangle 278, isolated 9
    let s = iqm(&fixtures::builtin_example());
    let dec = s.decomposition();
    let pieces: Vec<(usize, Vec<Vec<u32>>)> = dec
        .components
        .iter()
        .map(|p| {
            let rows = p
                .tops
                .chunks_exact(p.dimension + 1)
                .map(|r| original_row(p, r))
                .collect();
            (p.dimension, rows)
        })
        .collect();
    assert_eq!(
        pieces,
        vec![
            (3, vec![vec![0, 1, 2, 3]]),
            (2, vec![vec![0, 1, 6]]),
            (2, vec![vec![2, 7, 8]]),
            (1, vec![vec![3, 4], vec![4, 5]]),
            (0, vec![vec![9]]),
        ]
    );
    assert_eq!(dec.split_vertices, vec![0, 1, 2, 3]);
    // The wire is pasted at 4: one copy shared by both edges.
    assert_eq!(dec.components[3].original, vec![3, 4, 5]);
}

#[test]
fn bowtie_listed_clockwise_keeps_its_winding_in_each_component() {
    //   0       3
    //   | \   / |      triangle 2-1-0 listed clockwise, 2-3-4 counter-clockwise: the
    //   |  2    |      two components (split at 2) give them back exactly as listed
    //   | /   \ |
    //   1       4
    let c = Complex::from_simplices(5, &[&[2, 1, 0], &[2, 3, 4]]).unwrap();
    let dec = iqm(&c).decomposition();
    let rows: Vec<Vec<u32>> = dec
        .components
        .iter()
        .flat_map(|p| {
            p.tops
                .chunks_exact(p.dimension + 1)
                .map(|r| original_row(p, r))
                .collect::<Vec<_>>()
        })
        .collect();
    assert_eq!(rows, vec![vec![2, 1, 0], vec![2, 3, 4]]);
    // Local ids still number copies in order of first appearance in the ascending rows.
    assert_eq!(dec.components[0].tops, vec![2, 1, 0]);
    assert_eq!(dec.components[0].original, vec![0, 1, 2]);
}

#[test]
fn three_triangles_on_an_edge_are_three_components() {
    let s = iqm(&fixtures::three_triangles_on_an_edge());
    assert_eq!(s.component_count(), 3);
    assert_eq!(s.copies_of(0).len(), 3);
    assert_eq!(s.copies_of(1).len(), 3);
    assert_eq!(s.copies_of(2).len(), 1);
    assert_eq!(rel(&s, &[0, 1, 2], 2), vec![vec![0, 1, 3], vec![0, 1, 4]]);
}

#[test]
fn triangles_on_an_edge_of_a_tetrahedron_are_not_pasted() {
    //        4
    //        |          triangles 014 and 015 share edge 0-1, which is also an edge of
    //   5 -- 0 -- 2     tetrahedron 0123: the domain is not manifold along 0-1
    //        | /
    //        1 -- 3
    let c = Complex::from_simplices(6, &[&[0, 1, 2, 3], &[0, 1, 4], &[0, 1, 5]]).unwrap();
    let s = iqm(&c);
    assert_eq!(s.component_count(), 3);
    assert_eq!(s.copies_of(0).len(), 3);
    assert_eq!(s.copies_of(1).len(), 3);
    // Without the tetrahedron the two triangles form one disk.
    let s = iqm(&Complex::from_simplices(4, &[&[0, 1, 2], &[0, 1, 3]]).unwrap());
    assert_eq!(s.component_count(), 1);
    assert!(s.split_vertices().is_empty());
}

#[test]
fn manifold_surface_is_one_component_without_split() {
    // octahedron: closed surface
    let c = Complex::from_simplices(
        6,
        &[
            &[0, 1, 2],
            &[0, 2, 3],
            &[0, 3, 4],
            &[0, 1, 4],
            &[1, 2, 5],
            &[2, 3, 5],
            &[3, 4, 5],
            &[1, 4, 5],
        ],
    )
    .unwrap();
    let s = iqm(&c);
    assert_eq!(s.component_count(), 1);
    assert!(s.split_vertices().is_empty());
    // 1 component + 8·6 + 6 vertex references.
    assert_eq!(s.storage().integers, 1 + 48 + 6);
}

#[test]
fn every_fixture_matches_the_oracle_and_the_definition() {
    for (name, c) in fixtures::all() {
        check_structure(&iqm(&c), &c).unwrap_or_else(|e| panic!("{name}: {e}"));
        check_decomposition(&c).unwrap_or_else(|e| panic!("{name}: {e}"));
    }
}

#[test]
fn queries_are_refused_with_the_simplex_named() {
    let s = iqm(&fixtures::bowtie());
    let mut out = Vec::new();
    common::check_bowtie_refusal(&s, &mut out);
    assert!(s.relation(&[0], 3, &mut out).is_err());
    assert_eq!(rel(&s, &[2, 1, 0], 0), vec![vec![0], vec![1], vec![2]]);
}

#[test]
fn writers_emit_each_component_and_the_gluing() {
    let c = fixtures::builtin_example();
    let coords = topoplex::io::Coords {
        dim: 3,
        data: (0..30).map(f64::from).collect(),
    };
    let dec = iqm(&c).decomposition();
    let dir = std::env::temp_dir().join(format!("topoplex-iqm-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let paths = topoplex::decompose::write_components(&dec, Some(&coords), &dir).unwrap();
    let names: Vec<String> = paths
        .iter()
        .map(|p| p.file_name().unwrap().to_string_lossy().into_owned())
        .collect();
    assert_eq!(
        names,
        vec![
            "component_0.mesh",
            "component_1.off",
            "component_2.off",
            "component_3.simplices",
            "component_4.simplices",
            "gluing.json"
        ]
    );
    // Triangle 2 7 8 over local ids 0 1 2, with the coordinates of 2, 7, 8.
    let off = std::fs::read_to_string(&paths[2]).unwrap();
    assert_eq!(off, "OFF\n3 1 0\n6 7 8\n21 22 23\n24 25 26\n3 0 1 2\n");
    let mesh = std::fs::read_to_string(&paths[0]).unwrap();
    assert!(mesh.contains("Tetrahedra\n1\n1 2 3 4 0\n"), "{mesh}");
    let wire = std::fs::read_to_string(&paths[3]).unwrap();
    assert!(
        wire.ends_with("v 9 10 11\nv 12 13 14\nv 15 16 17\ns 0 1\ns 1 2\n"),
        "{wire}"
    );
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&paths[5]).unwrap()).unwrap();
    assert_eq!(
        json["components"][3]["original_ids"],
        serde_json::json!([3, 4, 5])
    );
    assert_eq!(json["split_vertices"][3]["vertex"], 3);
    assert_eq!(
        json["split_vertices"][3]["copies"],
        serde_json::json!([{"component": 0, "local_id": 3}, {"component": 3, "local_id": 0}])
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 200, ..ProptestConfig::default() })]
    #[test]
    fn random_decompositions_follow_the_definition(c in common::random_complex(6, 8, 10)) {
        prop_assert_eq!(check_decomposition(&c), Ok(()));
    }

    /// Low dimensions and more simplices: mixed-dimensional joints and wire edges.
    #[test]
    fn random_low_dimensional_decompositions_follow_the_definition(
        (n, list) in common::random_input(3, 7, 14),
    ) {
        let c = common::complex_of(n, &list);
        prop_assert_eq!(check_decomposition(&c), Ok(()));
        prop_assert_eq!(check_structure(&iqm(&c), &c), Ok(()));
    }

    /// Same decomposition after renumbering the vertices and reordering the simplices.
    #[test]
    fn decomposition_ignores_input_order(
        (n, list) in common::random_input(4, 8, 10),
        seed in any::<u64>(),
    ) {
        let c = common::complex_of(n, &list);
        // A permutation of the vertex ids and of the simplex order from the seed.
        let mut perm: Vec<u32> = (0..n).collect();
        let mut x = seed | 1;
        let mut next = move || { x ^= x << 13; x ^= x >> 7; x ^= x << 17; x };
        for i in (1..perm.len()).rev() {
            perm.swap(i, (next() % (i as u64 + 1)) as usize);
        }
        let mut shuffled: Vec<Vec<u32>> =
            list.iter().map(|s| s.iter().map(|&v| perm[v as usize]).collect()).collect();
        for i in (1..shuffled.len()).rev() {
            shuffled.swap(i, (next() % (i as u64 + 1)) as usize);
        }
        let c2 = common::complex_of(n, &shuffled);
        let mut inverse = vec![0u32; n as usize];
        for (v, &p) in perm.iter().enumerate() {
            inverse[p as usize] = v as u32;
        }
        let a = canon(&iqm(&c).decomposition(), |v| v);
        let b = canon(&iqm(&c2).decomposition(), |v| inverse[v as usize]);
        prop_assert_eq!(a, b);
    }
}

/// Compares every relation of about `per_dim` simplices of each dimension with the IG.
fn compare_sampled(a: &Iqm, g: &IncidenceGraph, per_dim: usize) -> Result<(), String> {
    let d = g.dimension();
    let (mut all, mut ra, mut rb) = (Vec::new(), Vec::new(), Vec::new());
    for p in 0..=d {
        all.clear();
        g.simplices(p, &mut all);
        let n = all.len() / (p + 1);
        for sigma in all.chunks_exact(p + 1).step_by((n / per_dim).max(1)) {
            for q in 0..=d {
                a.relation(sigma, q, &mut ra).map_err(|e| e.to_string())?;
                g.relation(sigma, q, &mut rb).map_err(|e| e.to_string())?;
                topoplex::relation::sort_rows(&mut ra, q + 1);
                topoplex::relation::sort_rows(&mut rb, q + 1);
                if ra != rb {
                    return Err(format!("R_{{{p},{q}}}({sigma:?}): IQM {ra:?}, IG {rb:?}"));
                }
            }
        }
    }
    Ok(())
}

#[test]
fn real_data_matches_the_incidence_graph() {
    for (path, c) in common::shared_complexes() {
        let what = path.display().to_string();
        let slots: usize = (0..=c.dimension()).map(|k| c.tops(k).len() * (k + 1)).sum();
        // Building (and the IG) on the largest files takes seconds in debug builds.
        if slots > 60_000 {
            continue;
        }
        let s = iqm(&c);
        let dec = s.decomposition();
        assert_glues_back(&dec, &c).unwrap_or_else(|e| panic!("{what}: {e}"));
        let g = IncidenceGraph::build(&c).unwrap();
        if slots <= 2_000 {
            assert_initial_quasi_manifolds(&dec).unwrap_or_else(|e| panic!("{what}: {e}"));
            compare_structures(&s, &g).unwrap_or_else(|e| panic!("{what}: {e}"));
        } else {
            compare_sampled(&s, &g, 300).unwrap_or_else(|e| panic!("{what}: {e}"));
        }
    }
}
