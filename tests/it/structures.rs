//! Every structure that can encode a complex answers exactly like the oracle (fixtures, random
//! complexes) and like the IG (real data), and answers the same from 8 threads at once.
//! Structures that cannot encode a complex must say so with `Unsupported`, never a wrong answer.

use crate::common;

use std::sync::Arc;

use proptest::prelude::*;
use topoplex::oracle::{check_structure, compare_structures};
use topoplex::{Complex, StructureKind, Topology, fixtures};

#[test]
fn every_structure_matches_the_oracle_on_every_fixture() {
    for (name, c) in fixtures::all() {
        for s in common::buildable(&c, name) {
            check_structure(s.as_ref(), &c).unwrap_or_else(|e| panic!("{name}: {e}"));
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 200, ..ProptestConfig::default() })]
    #[test]
    fn every_structure_matches_the_oracle_on_random_complexes(c in common::random_complex(6, 9, 8)) {
        for s in common::buildable(&c, "random") {
            prop_assert_eq!(check_structure(s.as_ref(), &c), Ok(()));
        }
    }

    #[test]
    fn every_structure_matches_the_oracle_on_random_surfaces(c in common::random_complex(2, 12, 14)) {
        for s in common::buildable(&c, "random 2-complex") {
            prop_assert_eq!(check_structure(s.as_ref(), &c), Ok(()));
        }
    }
}

/// Every relation of every simplex, serially, as (p, q, sigma) → sorted answer.
fn all_answers(s: &dyn Topology, stride: usize, offset: usize) -> Vec<Vec<u32>> {
    let d = s.dimension();
    let mut answers = Vec::new();
    let (mut sigmas, mut out) = (Vec::new(), Vec::new());
    let mut k = 0usize;
    for p in 0..=d {
        sigmas.clear();
        s.simplices(p, &mut sigmas);
        for sigma in sigmas.chunks_exact(p + 1) {
            for q in 0..=d {
                if k % stride == offset {
                    s.relation(sigma, q, &mut out).unwrap();
                    topoplex::relation::sort_rows(&mut out, q + 1);
                    answers.push(out.clone());
                }
                k += 1;
            }
        }
    }
    answers
}

#[test]
fn eight_threads_query_one_structure_and_agree_with_serial_answers() {
    let mut complexes: Vec<(String, Complex)> = fixtures::all()
        .into_iter()
        .map(|(n, c)| (n.to_string(), c))
        .collect();
    for (path, c) in common::shared_complexes() {
        if c.closure().iter().map(|t| t.len()).sum::<usize>() < 60_000 {
            complexes.push((path.display().to_string(), c));
        }
    }
    for (name, c) in complexes {
        for s in common::buildable(&c, &name) {
            let s: Arc<dyn Topology> = Arc::from(s);
            let serial = all_answers(s.as_ref(), 1, 0);
            // Thread t answers every 8th query starting at t, all at the same time.
            let handles: Vec<_> = (0..8)
                .map(|t| {
                    let s = Arc::clone(&s);
                    std::thread::spawn(move || all_answers(s.as_ref(), 8, t))
                })
                .collect();
            let parts: Vec<Vec<Vec<u32>>> =
                handles.into_iter().map(|h| h.join().unwrap()).collect();
            for (i, want) in serial.iter().enumerate() {
                assert_eq!(
                    &parts[i % 8][i / 8],
                    want,
                    "{name}: {}: query #{i}",
                    s.kind()
                );
            }
        }
    }
}

#[test]
fn real_data_every_structure_agrees_with_the_ig() {
    common::for_each_shared_complex(u64::MAX, |path, c| {
        let what = path.display().to_string();
        let all = common::buildable(&c, &what);
        let ig = all
            .iter()
            .find(|s| s.kind() == StructureKind::Ig)
            .expect("the IG encodes everything");
        for s in all.iter().filter(|s| s.kind() != StructureKind::Ig) {
            compare_structures(ig.as_ref(), s.as_ref()).unwrap_or_else(|e| panic!("{what}: {e}"));
        }
    });
}

/// Worst cases for stars: a vertex in 10^5 triangles, an edge in 10^4 triangles, one
/// 15-simplex. Every structure that accepts them builds and answers with the exact counts (a
/// quadratic step would not finish within the test run).
#[test]
fn worst_case_stars_build_and_answer() {
    let fan: Vec<Vec<u32>> = (1..=100_000u32).map(|i| vec![0, i, i + 1]).collect();
    let book: Vec<Vec<u32>> = (2..10_002u32).map(|i| vec![0, 1, i]).collect();
    let top: Vec<u32> = (0..16).collect();
    let cases: Vec<(&str, Complex, Vec<u32>, usize, usize)> = vec![
        (
            "vertex in 10^5 triangles",
            common::complex_of(100_002, &fan),
            vec![0],
            2,
            100_000,
        ),
        (
            "edge in 10^4 triangles",
            common::complex_of(10_002, &book),
            vec![0, 1],
            2,
            10_000,
        ),
        (
            "one 15-simplex",
            common::complex_of(16, &[top]),
            vec![3, 9],
            8,
            3432,
        ),
    ];
    let mut out = Vec::new();
    for (what, c, sigma, q, expected) in cases {
        for s in common::buildable(&c, what) {
            s.relation(&sigma, q, &mut out).unwrap();
            assert_eq!(out.len() / (q + 1), expected, "{what}: {}", s.kind());
        }
    }
}
