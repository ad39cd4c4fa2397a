//! Builds with several threads give the same structures, byte for byte, as serial builds: each
//! structure is built with 1 and with 2 threads and saved (`.tpx`), and the files compared.
//! The grids are large enough for every parallel step to split its work.

use topoplex::structures::build;
use topoplex::{Complex, StructureKind};

/// A k×k×k grid of cubes, each cut into the six tetrahedra around its main diagonal.
fn tetrahedral_grid(k: u32) -> Complex {
    let n = k + 1;
    let id = |p: [u32; 3]| (p[0] * n + p[1]) * n + p[2];
    let mut tets: Vec<Vec<u32>> = Vec::new();
    for x in 0..k {
        for y in 0..k {
            for z in 0..k {
                for perm in [
                    [0, 1, 2],
                    [0, 2, 1],
                    [1, 0, 2],
                    [1, 2, 0],
                    [2, 0, 1],
                    [2, 1, 0],
                ] {
                    let mut p = [x, y, z];
                    let mut t = vec![id(p)];
                    for a in perm {
                        p[a] += 1;
                        t.push(id(p));
                    }
                    tets.push(t);
                }
            }
        }
    }
    let refs: Vec<&[u32]> = tets.iter().map(Vec::as_slice).collect();
    Complex::from_simplices(n * n * n, &refs).unwrap()
}

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

fn saved(kind: StructureKind, c: &Complex, threads: usize, name: &str) -> Option<Vec<u8>> {
    topoplex::parallel::set_threads(threads);
    let s = build(kind, c).ok()?;
    let path = std::env::temp_dir().join(format!(
        "topoplex-parallel-{}-{name}-{kind}-{threads}.tpx",
        std::process::id()
    ));
    topoplex::store::save(&path, c, Some(s.as_ref())).unwrap();
    let bytes = std::fs::read(&path).unwrap();
    std::fs::remove_file(&path).unwrap();
    Some(bytes)
}

#[test]
fn two_threads_build_the_same_bytes_as_one() {
    // One test in this binary: the thread count is process-wide.
    for (name, c) in [
        ("grid", tetrahedral_grid(24)),
        ("surface", surface_with_wires(200)),
    ] {
        let mut built = 0;
        for kind in StructureKind::ALL {
            let one = saved(kind, &c, 1, name);
            let two = saved(kind, &c, 2, name);
            assert_eq!(one.is_some(), two.is_some(), "{name}: {kind}");
            if let (Some(one), Some(two)) = (one, two) {
                assert!(
                    one == two,
                    "{name}: {kind}: 2-thread build differs from 1-thread"
                );
                built += 1;
            }
        }
        assert!(built >= 3, "{name}: only {built} structures built");
    }
}
