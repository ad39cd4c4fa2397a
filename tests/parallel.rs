//! Builds with several threads give the same structures, byte for byte, as serial builds: each
//! structure is built with 1 and with 2 or 3 threads and saved (`.tpx`), and the files compared:
//! on grids large enough for every parallel step to split its work, and on random non-manifold
//! complexes and `../shared/data` with the split threshold lowered so that small inputs are cut
//! into many ranges too.

mod common;

use proptest::test_runner::{Config, TestRunner};
use topoplex::build;
use topoplex::fixtures::tetrahedral_grid;
use topoplex::{Complex, StructureKind};

/// The boundary surface of the grid plus a few wire edges: a 2-complex for the triangle-based
/// structures.
fn surface_with_wires(k: u32) -> Complex {
    let side = k + 1;
    let id = |i: u32, j: u32| i * side + j;
    let mut s: Vec<Vec<u32>> = Vec::new();
    for i in 0..k {
        for j in 0..k {
            s.push(vec![id(i, j), id(i + 1, j), id(i + 1, j + 1)]);
            s.push(vec![id(i, j), id(i, j + 1), id(i + 1, j + 1)]);
        }
    }
    let n = side * side;
    for w in 0..10 {
        s.push(vec![w, n + w]);
    }
    let refs: Vec<&[u32]> = s.iter().map(Vec::as_slice).collect();
    Complex::from_simplices(n + 10, &refs).unwrap()
}

/// `copies` k×k×k tetrahedral grids sharing their corner vertex 0 (so its star has `copies`
/// components: the IA keeps one reference each) and the edge from that corner along the first
/// axis (a pinched edge: its star is not connected through its triangles).
fn bouquet_of_grids(k: u32, copies: u32) -> Complex {
    let n = k + 1;
    let per = n * n * n;
    let grid = tetrahedral_grid(k);
    let mut tets: Vec<Vec<u32>> = Vec::new();
    for c in 0..copies {
        // Vertices 0 and `n * n` (the corner's neighbour along the first axis) are copy 0's
        // in every copy.
        let map = |v: u32| match v {
            0 => 0,
            v if v == n * n => n * n,
            v => c * per + v,
        };
        for t in grid.tops(3).iter() {
            let mut t: Vec<u32> = t.iter().map(|&v| map(v)).collect();
            t.sort_unstable();
            tets.push(t);
        }
    }
    let refs: Vec<&[u32]> = tets.iter().map(Vec::as_slice).collect();
    Complex::from_simplices(copies * per, &refs).unwrap()
}

/// `copies` k×k triangulated squares (as in [`surface_with_wires`]) sharing the edge {0, 1}
/// (a non-manifold edge of `copies` triangles) and the far corner ★ (a pinched vertex where
/// `copies` fans meet), plus a wire at ★ and at each copy's corner (k, 0): the corner
/// components of the triangle-based structures then span several fans at a vertex.
///
/// ```text
///   one copy, k = 2 (0, 1 and ★ are the same vertices in every copy)
///
///   0 ─────── 1 ─────── ·
///   │    ╲    │    ╲    │
///   · ─────── · ─────── ·
///   │    ╲    │    ╲    │
///   · ─────── · ─────── ★ ── wire
///   │
///   wire
/// ```
fn bouquet_of_squares(k: u32, copies: u32) -> Complex {
    let side = k + 1;
    let per = side * side;
    let far = per - 1;
    let map = |c: u32, v: u32| {
        if v == 0 || v == 1 || v == far {
            v
        } else {
            c * per + v
        }
    };
    let mut s: Vec<Vec<u32>> = Vec::new();
    for c in 0..copies {
        for i in 0..k {
            for j in 0..k {
                let id = |a: u32, b: u32| map(c, a * side + b);
                s.push(vec![id(i, j), id(i + 1, j), id(i + 1, j + 1)]);
                s.push(vec![id(i, j), id(i, j + 1), id(i + 1, j + 1)]);
            }
        }
    }
    let n = copies * per;
    s.push(vec![far, n]);
    for c in 0..copies {
        s.push(vec![map(c, k * side), n + 1 + c]);
    }
    let refs: Vec<&[u32]> = s.iter().map(Vec::as_slice).collect();
    Complex::from_simplices(n + 1 + copies, &refs).unwrap()
}

fn saved(kind: StructureKind, c: &Complex, threads: usize, name: &str) -> Option<Vec<u8>> {
    topoplex::parallel::set_threads(threads);
    let s = build(kind, c).ok()?;
    let path = std::env::temp_dir().join(format!(
        "topoplex-parallel-{}-{name}-{kind}-{threads}.tpx",
        std::process::id()
    ));
    topoplex::store::save(&path, c, Some(s.as_ref())).unwrap();
    let mut bytes = std::fs::read(&path).unwrap();
    std::fs::remove_file(&path).unwrap();
    // The live complex saves no stars (opening rebuilds them): compare its arrays as built.
    let live = s
        .as_any()
        .and_then(|a| a.downcast_ref::<topoplex::live::LiveComplex>());
    if let Some(live) = live {
        bytes.extend(format!("{live:?}").bytes());
    }
    Some(bytes)
}

/// Every structure that builds for `c` (the live complex too) saves to the same bytes with 1
/// and `threads` threads; returns how many built.
fn same_bytes(c: &Complex, threads: usize, name: &str) -> usize {
    let mut built = 0;
    for kind in StructureKind::ALL
        .into_iter()
        .chain([StructureKind::IaStar])
    {
        let one = saved(kind, c, 1, name);
        let many = saved(kind, c, threads, name);
        assert_eq!(one.is_some(), many.is_some(), "{name}: {kind}");
        if let (Some(one), Some(many)) = (one, many) {
            assert!(
                one == many,
                "{name}: {kind}: {threads}-thread build differs from 1-thread"
            );
            built += 1;
        }
    }
    built
}

#[test]
fn several_threads_build_the_same_bytes_as_one() {
    // One test in this binary: the thread count and split threshold are process-wide.
    for (name, c) in [
        ("grid", tetrahedral_grid(24)),
        ("surface", surface_with_wires(200)),
    ] {
        let built = same_bytes(&c, 2, name);
        assert!(built >= 3, "{name}: only {built} structures built");
    }

    // Small inputs cut into ranges of a few items: every range boundary lands somewhere.
    topoplex::parallel::set_split_threshold(2);
    let pinched = bouquet_of_grids(3, 5);
    let squares = bouquet_of_squares(4, 4);
    for threads in [2, 3] {
        assert!(same_bytes(&pinched, threads, "bouquet") >= 3);
        assert!(same_bytes(&squares, threads, "squares") >= 4);
    }
    let mut runner = TestRunner::new(Config {
        cases: 48,
        failure_persistence: None,
        ..Config::default()
    });
    let built = std::cell::Cell::new(0);
    runner
        .run(&common::random_input(5, 14, 24), |(n, list)| {
            let c = common::complex_of(n, &list);
            built.set(built.get() + same_bytes(&c, 3, "random"));
            Ok(())
        })
        .unwrap();
    assert!(
        built.get() >= 48,
        "random: only {} structures built",
        built.get()
    );

    topoplex::parallel::set_split_threshold(64);
    for f in common::shared_files() {
        if std::fs::metadata(&f).map_or(true, |m| m.len() > 300_000) {
            continue;
        }
        let Ok(c) = Complex::from_path(&f) else {
            continue;
        };
        same_bytes(&c, 2, &f.file_name().unwrap().to_string_lossy());
    }
}
