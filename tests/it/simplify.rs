//! `topoplex::simplify`: quadric-error edge contraction. With `preserve_topology` the Betti
//! numbers (Z/2) and 2-/3-manifoldness must hold; small drawn fixtures with exact answers, real
//! data from ../shared/data when present, the refusals, and the CLI.

use crate::common;

use std::collections::HashMap;
use std::process::Command;

use topoplex::complex::push_facet;
use topoplex::io::Coords;
use topoplex::live::LiveComplex;
use topoplex::simplify::{Options, SimplifyError, simplify, simplify_live};
use topoplex::{Complex, StructureKind, Topology};

fn with_coords(n: u32, simplices: &[&[u32]], xyz: &[f64], dim: usize) -> Complex {
    let mut ids = Vec::new();
    let mut offsets = vec![0];
    for s in simplices {
        ids.extend_from_slice(s);
        offsets.push(ids.len());
    }
    Complex::from_arrays(
        n,
        &ids,
        &offsets,
        Some(Coords {
            dim,
            data: xyz.to_vec(),
        }),
    )
    .unwrap()
}

fn opts(ratio: f64, preserve_topology: bool) -> Options {
    Options::new(ratio, preserve_topology)
}

/// Simplifies on a live complex, validates it, and returns the result as a complex (checked by
/// building the IG from it and validating that too).
fn run(c: &Complex, ratio: f64, preserve: bool) -> (Complex, topoplex::simplify::Stats) {
    let mut live = LiveComplex::from_complex(c);
    let stats = simplify_live(&mut live, &opts(ratio, preserve), &mut |_, _| {}).unwrap();
    live.validate().unwrap();
    let out = live.to_complex();
    topoplex::build(StructureKind::Ig, &out)
        .unwrap()
        .validate()
        .unwrap();
    let total: usize = out.top_counts().iter().sum();
    assert_eq!(total, stats.output_tops);
    (out, stats)
}

// ---------------------------------------------------------------------------------------------
// Betti numbers over Z/2 and manifoldness, by brute force on the closure.

/// Ranks of the boundary maps by column reduction over GF(2) (sparse columns, pivot table).
fn boundary_rank(levels: &[topoplex::complex::SimplexTable], p: usize) -> usize {
    let lower = &levels[p - 1];
    let mut pivot_of: HashMap<u32, Vec<u32>> = HashMap::new();
    let mut rank = 0;
    let mut face = Vec::new();
    for s in levels[p].iter() {
        let mut col: Vec<u32> = (0..s.len())
            .map(|skip| {
                face.clear();
                push_facet(s, skip, &mut face);
                lower.find(&face).expect("face in closure")
            })
            .collect();
        col.sort_unstable();
        while let Some(&low) = col.last() {
            match pivot_of.get(&low) {
                Some(other) => col = xor(&col, other),
                None => break,
            }
        }
        if let Some(&low) = col.last() {
            pivot_of.insert(low, col);
            rank += 1;
        }
    }
    rank
}

fn xor(a: &[u32], b: &[u32]) -> Vec<u32> {
    let (mut i, mut j, mut out) = (0, 0, Vec::with_capacity(a.len() + b.len()));
    while i < a.len() || j < b.len() {
        if j == b.len() || (i < a.len() && a[i] < b[j]) {
            out.push(a[i]);
            i += 1;
        } else if i == a.len() || b[j] < a[i] {
            out.push(b[j]);
            j += 1;
        } else {
            i += 1;
            j += 1;
        }
    }
    out
}

fn betti(c: &Complex) -> Vec<usize> {
    let levels = c.closure();
    let d = levels.len() - 1;
    let ranks: Vec<usize> = (0..=d + 1)
        .map(|p| {
            if p == 0 || p > d {
                0
            } else {
                boundary_rank(&levels, p)
            }
        })
        .collect();
    let mut b: Vec<usize> = (0..=d)
        .map(|p| levels[p].len() - ranks[p] - ranks[p + 1])
        .collect();
    // Contractions may lower the dimension; compare the nonzero part.
    while b.len() > 1 && b.last() == Some(&0) {
        b.pop();
    }
    b
}

/// Whether `c` is a pure d-manifold, possibly with boundary, d = 2 or 3: every (d−1)-simplex in
/// one or two d-simplices, and every vertex link a connected (d−1)-manifold that is a sphere
/// or a disk (a cycle or a path for d = 2; χ = 2 or 1 with a 2-manifold link for d = 3).
fn is_manifold(c: &Complex) -> bool {
    let d = c.dimension();
    if c.top_counts()[..d].iter().any(|&k| k > 0) {
        return false;
    }
    let tops: Vec<Vec<u32>> = c.tops(d).iter().map(<[u32]>::to_vec).collect();
    let mut link: HashMap<u32, Vec<Vec<u32>>> = HashMap::new();
    for t in &tops {
        for &v in t {
            link.entry(v)
                .or_default()
                .push(t.iter().copied().filter(|&u| u != v).collect());
        }
    }
    let n = c.vertex_count();
    if (0..n).any(|v| !link.contains_key(&v)) {
        return false;
    }
    link.values().all(|l| {
        let lc = common::complex_of(n, l);
        let lb = betti(&lc);
        let isolated = (n as usize)
            - l.iter()
                .flatten()
                .collect::<std::collections::HashSet<_>>()
                .len();
        let connected = lb[0] - isolated == 1;
        match d {
            2 => {
                let mut deg: HashMap<u32, usize> = HashMap::new();
                for e in l {
                    for &u in e {
                        *deg.entry(u).or_default() += 1;
                    }
                }
                connected && deg.values().all(|&k| k <= 2)
            }
            3 => {
                let mut per_edge: HashMap<(u32, u32), usize> = HashMap::new();
                for t in l {
                    let mut s = t.clone();
                    s.sort_unstable();
                    for (a, b) in [(s[0], s[1]), (s[0], s[2]), (s[1], s[2])] {
                        *per_edge.entry((a, b)).or_default() += 1;
                    }
                }
                let edges_ok = per_edge.values().all(|&k| k <= 2);
                let at = |i: usize| lb.get(i).copied().unwrap_or(0) as i64;
                let chi = at(0) - isolated as i64 - at(1) + at(2);
                connected && edges_ok && is_manifold_2(l) && (chi == 2 || chi == 1)
            }
            _ => false,
        }
    }) && {
        let mut facets: HashMap<Vec<u32>, usize> = HashMap::new();
        for t in &tops {
            for skip in 0..t.len() {
                let mut f = Vec::new();
                push_facet(t, skip, &mut f);
                f.sort_unstable();
                *facets.entry(f).or_default() += 1;
            }
        }
        facets.values().all(|&k| k <= 2)
    }
}

/// Every vertex of a triangle list (a 3-manifold's vertex link) has a path or cycle as link.
fn is_manifold_2(tris: &[Vec<u32>]) -> bool {
    let mut link: HashMap<u32, Vec<(u32, u32)>> = HashMap::new();
    for t in tris {
        for i in 0..3 {
            link.entry(t[i])
                .or_default()
                .push((t[(i + 1) % 3], t[(i + 2) % 3]));
        }
    }
    link.values().all(|edges| {
        let mut deg: HashMap<u32, usize> = HashMap::new();
        let mut parent: HashMap<u32, u32> = HashMap::new();
        fn find(p: &mut HashMap<u32, u32>, x: u32) -> u32 {
            let y = *p.entry(x).or_insert(x);
            if y == x {
                x
            } else {
                let r = find(p, y);
                p.insert(x, r);
                r
            }
        }
        for &(a, b) in edges {
            *deg.entry(a).or_default() += 1;
            *deg.entry(b).or_default() += 1;
            let (ra, rb) = (find(&mut parent, a), find(&mut parent, b));
            parent.insert(ra, rb);
        }
        let roots: std::collections::HashSet<u32> = deg
            .keys()
            .copied()
            .collect::<Vec<_>>()
            .into_iter()
            .map(|v| find(&mut parent, v))
            .collect();
        roots.len() == 1 && deg.values().all(|&k| k <= 2)
    })
}

// ---------------------------------------------------------------------------------------------
// Drawn fixtures.

/// The octahedron: a closed sphere, 6 vertices, 8 triangles.
///
/// ```text
///        4 (top)
///      / | \
///   0 -- 1 -- 2 -- 3 -- 0   (equator)
///      \ | /
///        5 (bottom)
/// ```
fn octahedron() -> Complex {
    let xyz = [
        1., 0., 0., 0., 1., 0., -1., 0., 0., 0., -1., 0., 0., 0., 1., 0., 0., -1.,
    ];
    let mut tris: Vec<Vec<u32>> = Vec::new();
    for i in 0..4u32 {
        tris.push(vec![i, (i + 1) % 4, 4]);
        tris.push(vec![(i + 1) % 4, i, 5]);
    }
    let refs: Vec<&[u32]> = tris.iter().map(Vec::as_slice).collect();
    with_coords(6, &refs, &xyz, 3)
}

#[test]
fn octahedron_preserving_topology_stops_at_the_tetrahedron_boundary() {
    let c = octahedron();
    assert_eq!(betti(&c), vec![1, 0, 1]);
    let (out, stats) = run(&c, 0.01, true);
    // The smallest triangulated sphere: 4 triangles on 4 vertices. No edge of it satisfies the
    // link condition, so the loop ends there above the target of 1.
    assert_eq!(out.top_counts(), vec![0, 0, 4]);
    assert_eq!(out.vertex_count(), 4);
    assert_eq!(stats.contractions, 2);
    assert!(stats.refused > 0);
    assert_eq!(betti(&out), vec![1, 0, 1]);
    assert!(is_manifold(&out));
}

#[test]
fn octahedron_without_the_link_condition_goes_below_a_sphere() {
    let (out, stats) = run(&octahedron(), 0.01, false);
    assert_eq!(stats.target_tops, 1);
    assert!(stats.output_tops <= 1, "{stats:?}");
    assert!(out.top_counts().iter().sum::<usize>() <= 1);
}

/// A flat 4 × 4 grid of squares in z = 0, each cut into two triangles (32 triangles, 25
/// vertices): every quadric vanishes on the plane, so every contraction costs 0 and every
/// vertex stays in the plane; the boundary facets keep the square's outline.
///
/// ```text
///  20-21-22-23-24
///   | /| /| /| /|
///  15-16-17-18-19     ... rows of 5 vertices, (x, y) = (i % 5, i / 5)
///   | /| /| /| /|
///   0--1--2--3--4
/// ```
fn flat_grid() -> Complex {
    let mut xyz = Vec::new();
    for i in 0..25 {
        xyz.extend_from_slice(&[(i % 5) as f64, (i / 5) as f64, 0.0]);
    }
    let mut tris = Vec::new();
    for y in 0..4u32 {
        for x in 0..4u32 {
            let v = y * 5 + x;
            tris.push(vec![v, v + 1, v + 6]);
            tris.push(vec![v, v + 6, v + 5]);
        }
    }
    let refs: Vec<&[u32]> = tris.iter().map(Vec::as_slice).collect();
    with_coords(25, &refs, &xyz, 3)
}

#[test]
fn flat_grid_stays_flat_and_keeps_its_corners_and_disk_topology() {
    let c = flat_grid();
    let (out, stats) = run(&c, 0.25, true);
    assert!(stats.output_tops <= 8, "{stats:?}");
    let k = out.coords().unwrap();
    for v in 0..out.vertex_count() as usize {
        let p = &k.data[3 * v..3 * v + 3];
        assert!(p[2].abs() < 1e-9, "vertex {v} left the plane: {p:?}");
        assert!((-1e-9..=4.0 + 1e-9).contains(&p[0]) && (-1e-9..=4.0 + 1e-9).contains(&p[1]));
    }
    // The four corners cost the most to move (two boundary lines meet there): still present.
    for corner in [[0.0, 0.0], [4.0, 0.0], [0.0, 4.0], [4.0, 4.0]] {
        assert!(
            (0..out.vertex_count() as usize).any(|v| (k.data[3 * v] - corner[0]).abs() < 1e-9
                && (k.data[3 * v + 1] - corner[1]).abs() < 1e-9),
            "corner {corner:?} moved"
        );
    }
    assert_eq!(betti(&out), vec![1]);
    assert!(is_manifold(&out));
}

/// A square of four wire edges: a 1-cycle. Preserving topology, it can shrink to a triangle
/// cycle (3 edges, the smallest) and no further.
///
/// ```text
///  3 --- 2
///  |     |
///  0 --- 1
/// ```
#[test]
fn wire_square_preserving_topology_keeps_its_cycle() {
    let c = with_coords(
        4,
        &[&[0, 1], &[1, 2], &[2, 3], &[3, 0]],
        &[0., 0., 1., 0., 1., 1., 0., 1.],
        2,
    );
    assert_eq!(betti(&c), vec![1, 1]);
    let (out, _) = run(&c, 0.25, true);
    assert_eq!(out.top_counts(), vec![0, 3]);
    assert_eq!(betti(&out), vec![1, 1]);
    // Free contraction may collapse the cycle.
    let (free, _) = run(&c, 0.25, false);
    assert!(free.top_counts().iter().sum::<usize>() <= 1);
}

/// Two tetrahedron surfaces pinched at vertex 0 (a non-manifold vertex), plus a wire edge
/// dangling from vertex 7: β = (1, 0, 2).
///
/// ```text
///    2   5
///   /|\ /|\
///  1-+-0-+-4    7 -- 8
///   \|/ \|/     (the wire)
///    3   6
/// ```
#[test]
fn pinched_spheres_with_a_wire_keep_their_betti_numbers() {
    let xyz = [
        0., 0., 0., -1., 0., 0., -0.5, 1., 0., -0.5, 0., 1., 1., 0., 0., 0.5, 1., 0., 0.5, 0., 1.,
        0., -1., 0., 0., -2., 0.,
    ];
    let c = with_coords(
        9,
        &[
            &[0, 1, 2],
            &[0, 2, 3],
            &[0, 3, 1],
            &[1, 3, 2],
            &[0, 4, 5],
            &[0, 5, 6],
            &[0, 6, 4],
            &[4, 6, 5],
            &[0, 7],
            &[7, 8],
        ],
        &xyz,
        3,
    );
    let b = betti(&c);
    assert_eq!(b, vec![1, 0, 2]);
    let (out, _) = run(&c, 0.1, true);
    assert_eq!(betti(&out), b);
}

/// A cube [0,2]³ cut into 8 unit cubes, each into 6 tetrahedra around its main diagonal
/// (48 tetrahedra, 27 vertices): a 3-ball. Preserving topology keeps a 3-manifold ball.
fn cube_of_tets() -> Complex {
    let id = |x: u32, y: u32, z: u32| x + 3 * y + 9 * z;
    let mut xyz = Vec::new();
    for v in 0..27u32 {
        xyz.extend_from_slice(&[(v % 3) as f64, ((v / 3) % 3) as f64, (v / 9) as f64]);
    }
    let mut tets = Vec::new();
    for z in 0..2 {
        for y in 0..2 {
            for x in 0..2 {
                let c = |dx: u32, dy: u32, dz: u32| id(x + dx, y + dy, z + dz);
                let (a, h) = (c(0, 0, 0), c(1, 1, 1));
                // The six monotone paths from a to h through the cube's corners.
                for (p, q) in [
                    (c(1, 0, 0), c(1, 1, 0)),
                    (c(1, 0, 0), c(1, 0, 1)),
                    (c(0, 1, 0), c(1, 1, 0)),
                    (c(0, 1, 0), c(0, 1, 1)),
                    (c(0, 0, 1), c(1, 0, 1)),
                    (c(0, 0, 1), c(0, 1, 1)),
                ] {
                    tets.push(vec![a, p, q, h]);
                }
            }
        }
    }
    let refs: Vec<&[u32]> = tets.iter().map(Vec::as_slice).collect();
    with_coords(27, &refs, &xyz, 3)
}

#[test]
fn cube_of_tetrahedra_stays_a_three_ball() {
    let c = cube_of_tets();
    assert!(is_manifold(&c));
    assert_eq!(betti(&c), vec![1]);
    let (out, stats) = run(&c, 0.2, true);
    assert!(stats.contractions > 0);
    assert!(is_manifold(&out), "{stats:?}");
    assert_eq!(betti(&out), vec![1]);
    // The boundary quadrics hold the cube's shape: every vertex stays in [0, 2]³.
    let k = out.coords().unwrap();
    assert!(
        k.data.iter().all(|&x| (-1e-9..=2.0 + 1e-9).contains(&x)),
        "{:?}",
        k.data
    );
}

/// The boundary of the 4-simplex (five tetrahedra, a 3-sphere) in R^4: the smallest
/// triangulated 3-sphere, so preserving topology contracts nothing.
#[test]
fn boundary_of_the_four_simplex_is_already_minimal() {
    let mut xyz = vec![0.0; 20];
    for i in 0..4 {
        xyz[4 * (i + 1) + i] = 1.0;
    }
    let tets: Vec<Vec<u32>> = (0..5u32)
        .map(|skip| (0..5).filter(|&v| v != skip).collect())
        .collect();
    let refs: Vec<&[u32]> = tets.iter().map(Vec::as_slice).collect();
    let c = with_coords(5, &refs, &xyz, 4);
    assert_eq!(betti(&c), vec![1, 0, 0, 1]);
    let (out, stats) = run(&c, 0.2, true);
    assert_eq!(stats.contractions, 0);
    assert_eq!(out.top_counts(), vec![0, 0, 0, 5]);
}

#[test]
fn ratio_one_changes_nothing() {
    let c = flat_grid();
    let (out, stats) = run(&c, 1.0, false);
    assert_eq!(stats.contractions, 0);
    assert_eq!(out.top_counts(), c.top_counts());
}

#[test]
fn refusals_name_the_problem() {
    let c = flat_grid();
    for bad in [0.0, -0.5, 1.5, f64::NAN] {
        let e = simplify(&c, &opts(bad, false), &mut |_, _| {}).unwrap_err();
        assert!(matches!(e, SimplifyError::Ratio(_)), "{e}");
        assert!(e.to_string().contains("outside (0, 1]"), "{e}");
    }
    let bare = Complex::from_simplices(3, &[&[0, 1, 2]]).unwrap();
    let e = simplify(&bare, &opts(0.5, false), &mut |_, _| {}).unwrap_err();
    assert!(matches!(e, SimplifyError::NoCoordinates { .. }), "{e}");
    let nan = with_coords(3, &[&[0, 1, 2]], &[0., 0., 1., f64::NAN, 0., 1.], 2);
    let e = simplify(&nan, &opts(0.5, false), &mut |_, _| {}).unwrap_err();
    assert_eq!(e.to_string(), "vertex 1 has a non-finite coordinate");
}

// ---------------------------------------------------------------------------------------------
// Real data.

#[test]
fn real_data_preserving_topology_keeps_betti_numbers_and_manifoldness() {
    let Some(dir) = common::shared_data() else {
        eprintln!("../shared/data is absent: skipping");
        return;
    };
    for rel in [
        "nonmanifold/truck.obj",
        "nonmanifold/fan3.obj",
        "nonmanifold/hourglass_ico.obj",
        "mixed/alpha_kitten.simplices",
        "mixed/gmsh_baffles_wire.mesh",
        "highdim/rips_hippo1.simplices",
        "tetrahedral/octopus-low.mesh",
        "tetrahedral/decimated-knight.mesh",
        "surfaces/elephant.off",
    ] {
        let path = dir.join(rel);
        let Ok(c) = Complex::from_path(&path) else {
            eprintln!("{rel} does not load: skipping");
            continue;
        };
        let before = betti(&c);
        let manifold = matches!(c.dimension(), 2 | 3) && is_manifold(&c);
        let (out, stats) = run(&c, 0.2, true);
        assert!(stats.contractions > 0, "{rel}: {stats:?}");
        assert_eq!(betti(&out), before, "{rel}: {stats:?}");
        if manifold {
            assert!(
                is_manifold(&out),
                "{rel} is no longer a manifold: {stats:?}"
            );
        }
        eprintln!("{rel}: betti {before:?}, manifold {manifold}, {stats:?}");
    }
}

// ---------------------------------------------------------------------------------------------
// The CLI.

fn cli(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_topoplex"))
        .args(args)
        .output()
        .unwrap()
}

fn write_fixture(dir: &std::path::Path, name: &str, text: &str) -> String {
    let p = dir.join(name);
    std::fs::write(&p, text).unwrap();
    p.to_str().unwrap().to_string()
}

fn octahedron_off() -> String {
    let c = octahedron();
    let mut s = String::from("OFF\n6 8 0\n");
    for v in 0..6 {
        let p = &c.coords().unwrap().data[3 * v..3 * v + 3];
        s.push_str(&format!("{} {} {}\n", p[0], p[1], p[2]));
    }
    for (_, _, _, t) in c.tops_as_given() {
        s.push_str(&format!("3 {} {} {}\n", t[0], t[1], t[2]));
    }
    s
}

#[test]
fn cli_simplifies_into_each_format_and_the_result_loads() {
    let dir = tempdir("cli_ok");
    let input = write_fixture(&dir, "octa.off", &octahedron_off());
    for ext in ["off", "obj", "mesh", "simplices"] {
        let out = dir.join(format!("out.{ext}"));
        let o = cli(&[
            "simplify",
            &input,
            "--out",
            out.to_str().unwrap(),
            "--ratio",
            "0.5",
            "--preserve-topology",
        ]);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        let back = Complex::from_path(&out).unwrap();
        assert_eq!(back.top_counts(), vec![0, 0, 4], "{ext}");
        assert_eq!(betti(&back), vec![1, 0, 1]);
        assert_eq!(back.coords().unwrap().dim, 3);
    }
}

#[test]
fn cli_refusals_are_one_line_and_exit_1() {
    let dir = tempdir("cli_bad");
    let input = write_fixture(&dir, "octa.off", &octahedron_off());
    let bare = write_fixture(&dir, "bare.simplices", "s 0 1 2\ns 0 2 3\n");
    let out = dir.join("o.off");
    let out = out.to_str().unwrap();
    let cases: Vec<(Vec<&str>, &str)> = vec![
        (vec![&input, "--out", out, "--ratio", "0"], "outside (0, 1]"),
        (
            vec![&input, "--out", out, "--ratio", "1.5"],
            "outside (0, 1]",
        ),
        (
            vec![&input, "--out", "/nonexistent-dir/o.off", "--ratio", "0.5"],
            "cannot write",
        ),
        (
            vec![
                &input,
                "--out",
                out.trim_end_matches(".off"),
                "--ratio",
                "0.5",
            ],
            "unknown output extension",
        ),
        (
            vec![&bare, "--out", out, "--ratio", "0.5"],
            "no vertex coordinates",
        ),
    ];
    for (args, needle) in cases {
        let mut all = vec!["simplify"];
        all.extend(args);
        let o = cli(&all);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(1), "{all:?}: {err}");
        assert!(err.contains(needle), "{all:?}: {err}");
        assert_eq!(err.trim_end().lines().count(), 1, "{err}");
        assert!(!std::path::Path::new(out).exists(), "{all:?} left {out}");
    }
}

fn tempdir(name: &str) -> std::path::PathBuf {
    let d = std::env::temp_dir().join(format!("topoplex-simplify-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

// ---------------------------------------------------------------------------------------------
// --keep-regions.

/// The label of each top simplex by its listing (`name`, listed attribute), tops in
/// [`Complex::tops_as_given`] order.
fn labelled_tops(c: &Complex, name: &str) -> Vec<(Vec<u32>, i64)> {
    use topoplex::complex::Location;
    let a = c.attributes().get(name, Location::Listed).unwrap();
    c.tops_as_given()
        .filter(|t| t.1 > 0)
        .map(|(i, _, _, s)| (s.to_vec(), a.label(i).unwrap()))
        .collect()
}

/// The pairs of labels whose top simplices share a facet (a region interface).
fn interfaces(tops: &[(Vec<u32>, i64)]) -> std::collections::BTreeSet<(i64, i64)> {
    let mut at: HashMap<Vec<u32>, Vec<i64>> = HashMap::new();
    for (s, l) in tops {
        for skip in 0..s.len() {
            let mut f = Vec::new();
            push_facet(s, skip, &mut f);
            f.sort_unstable();
            at.entry(f).or_default().push(*l);
        }
    }
    let mut out = std::collections::BTreeSet::new();
    for labels in at.values() {
        for &a in labels {
            for &b in labels {
                if a < b {
                    out.insert((a, b));
                }
            }
        }
    }
    out
}

/// Each region's Betti numbers (the closure of its top simplices, over its own vertices).
fn region_betti(tops: &[(Vec<u32>, i64)]) -> std::collections::BTreeMap<i64, Vec<usize>> {
    let mut by: std::collections::BTreeMap<i64, Vec<Vec<u32>>> = Default::default();
    for (s, l) in tops {
        by.entry(*l).or_default().push(s.clone());
    }
    by.into_iter()
        .map(|(l, mut ss)| {
            let mut ids: Vec<u32> = ss.concat();
            ids.sort_unstable();
            ids.dedup();
            for s in &mut ss {
                for v in s.iter_mut() {
                    *v = ids.binary_search(v).unwrap() as u32;
                }
            }
            (l, betti(&common::complex_of(ids.len() as u32, &ss)))
        })
        .collect()
}

/// The positions (as bits) of the vertices where three or more regions meet.
fn corners(c: &Complex, tops: &[(Vec<u32>, i64)]) -> std::collections::BTreeSet<Vec<u64>> {
    let mut at: HashMap<u32, std::collections::BTreeSet<i64>> = HashMap::new();
    for (s, l) in tops {
        for &v in s {
            at.entry(v).or_default().insert(*l);
        }
    }
    let xyz = c.coords().unwrap();
    at.into_iter()
        .filter(|(_, ls)| ls.len() >= 3)
        .map(|(v, _)| {
            xyz.data[v as usize * xyz.dim..(v as usize + 1) * xyz.dim]
                .iter()
                .map(|x| x.to_bits())
                .collect()
        })
        .collect()
}

/// A 6×6×6 tetrahedral grid cut into four regions (x and y halves: four regions meet along a
/// line), with coordinates.
fn four_regions() -> Complex {
    use topoplex::complex::{Attribute, Attributes, Location};
    let k = 6u32;
    let n = k + 1;
    let id = |[x, y, z]: [u32; 3]| (x * n + y) * n + z;
    let tets: Vec<[u32; 4]> = topoplex::fixtures::freudenthal_grid(k, id).collect();
    let coords: Vec<f64> = (0..n * n * n)
        .flat_map(|v| {
            [
                f64::from(v / (n * n)),
                f64::from(v / n % n),
                f64::from(v % n),
            ]
        })
        .collect();
    let mut c = Complex::from_arrays(
        n * n * n,
        &tets.concat(),
        &(0..=tets.len()).map(|i| i * 4).collect::<Vec<_>>(),
        Some(Coords {
            dim: 3,
            data: coords,
        }),
    )
    .unwrap();
    let labels: Vec<i32> = tets
        .iter()
        .map(|t| {
            let (x, y) = t
                .iter()
                .fold((0, 0), |(x, y), &v| (x + v / (n * n), y + v / n % n));
            1 + i32::from(x * 2 > 4 * k) + 2 * i32::from(y * 2 > 4 * k)
        })
        .collect();
    let mut at = Attributes::new();
    at.insert(Attribute::labels("region", Location::Listed, labels));
    c.set_attributes(at).unwrap();
    c
}

/// `keep_regions` on four regions of a grid and on the six-volume mesh of
/// ../shared/data/labelled (Gmsh's t16, MEDIT references): every interface present before is
/// present after, each region keeps its Betti numbers, no region is erased, and the count
/// reaches its target within 1 %.
#[test]
fn keep_regions_keeps_every_interface_and_each_regions_betti_numbers() {
    let mut cases = vec![("four regions".to_string(), four_regions(), "region")];
    if let Some(d) = common::shared_data() {
        let f = d.join("labelled/gmsh_t16.mesh");
        if f.exists() {
            cases.push((
                "gmsh_t16.mesh".into(),
                Complex::from_path(&f).unwrap(),
                "medit:ref",
            ));
        }
    }
    for (name, c, attr) in cases {
        let before = labelled_tops(&c, attr);
        let options = Options {
            keep_regions: Some(attr.to_string()),
            ..Options::new(0.5, true)
        };
        let out = simplify(&c, &options, &mut |_, _| {}).unwrap();
        let after = labelled_tops(&out.complex, attr);
        assert_eq!(
            interfaces(&after),
            interfaces(&before),
            "{name}: interfaces"
        );
        assert_eq!(
            corners(&out.complex, &after),
            corners(&c, &before),
            "{name}: corners"
        );
        assert_eq!(
            region_betti(&after),
            region_betti(&before),
            "{name}: region Betti numbers"
        );
        let st = out.stats;
        let off = st.output_tops.abs_diff(st.target_tops) as f64 / st.target_tops as f64;
        assert!(
            off <= 0.01,
            "{name}: {} tops for a target of {} ({st:?})",
            st.output_tops,
            st.target_tops
        );
        assert!(
            st.refused_regions > 0,
            "{name}: the regions constrained nothing ({st:?})"
        );
    }
}

/// Without `keep_regions` the line where the grid's four regions meet is simplified away (so
/// the test above can fail), and a name that is not a label attribute is refused.
#[test]
fn without_keep_regions_interfaces_move_and_unknown_names_are_refused() {
    let c = four_regions();
    let before = labelled_tops(&c, "region");
    let out = simplify(&c, &Options::new(0.3, true), &mut |_, _| {}).unwrap();
    let after = labelled_tops(&out.complex, "region");
    assert_eq!(corners(&c, &before).len(), 7);
    assert_ne!(corners(&out.complex, &after), corners(&c, &before));
    let options = Options {
        keep_regions: Some("nothing".into()),
        ..Options::new(0.5, true)
    };
    let e = simplify(&c, &options, &mut |_, _| {}).unwrap_err();
    assert!(matches!(e, SimplifyError::Regions { .. }), "{e}");
}

// ---------------------------------------------------------------------------------------------
// The C ABI.

mod ffi {
    use std::ffi::{CStr, CString};
    use std::ptr::{null, null_mut};

    use topoplex_ffi::*;

    fn last_error() -> String {
        // SAFETY: never NULL, NUL-terminated.
        unsafe { CStr::from_ptr(tpx_last_error_message()) }
            .to_string_lossy()
            .into_owned()
    }

    fn octahedron() -> *mut TpxComplex {
        let c = super::octahedron();
        let tops: Vec<&[u32]> = c.tops_as_given().map(|(_, _, _, t)| t).collect();
        crate::common::c_complex(6, &tops, Some(&c.coords().unwrap().data))
    }

    /// The number of triangles of `c`, through the C ABI.
    fn triangles(c: *const TpxComplex) -> usize {
        let mut n = 0usize;
        let st = unsafe { tpx_complex_top_count(c, 2, &mut n) };
        assert_eq!(st, TpxStatus::Ok);
        n
    }

    #[test]
    fn simplify_through_the_abi_and_its_refusals() {
        let c = octahedron();
        let mut out = null_mut();
        let st = unsafe { tpx_simplify(c, 0.01, true, &mut out) };
        assert_eq!(st, TpxStatus::Ok, "{}", last_error());
        assert_eq!(triangles(out), 4);
        unsafe { tpx_complex_free(out) };
        // Refusals leave *out untouched.
        let sentinel = std::ptr::dangling_mut::<TpxComplex>();
        for bad in [0.0, 1.01, f64::NAN, -1.0] {
            let mut out = sentinel;
            assert_eq!(
                unsafe { tpx_simplify(c, bad, false, &mut out) },
                TpxStatus::InvalidRatio
            );
            assert!(last_error().contains("outside (0, 1]"), "{}", last_error());
            assert_eq!(out, sentinel);
        }
        let mut out = sentinel;
        assert_eq!(
            unsafe { tpx_simplify(null(), 0.5, false, &mut out) },
            TpxStatus::NullArgument
        );
        assert_eq!(
            unsafe { tpx_simplify(c, 0.5, false, null_mut()) },
            TpxStatus::NullArgument
        );
        assert_eq!(out, sentinel);
        // In place: the same result, and refusals leave the complex as it was.
        let c2 = octahedron();
        assert_eq!(
            unsafe { tpx_simplify_in_place(c2, 1.5, true) },
            TpxStatus::InvalidRatio
        );
        assert_eq!(triangles(c2), 8);
        assert_eq!(
            unsafe { tpx_simplify_in_place(c2, 0.01, true) },
            TpxStatus::Ok
        );
        assert_eq!(triangles(c2), 4);
        assert_eq!(
            unsafe { tpx_simplify_in_place(null_mut(), 0.5, true) },
            TpxStatus::NullArgument
        );
        unsafe { tpx_complex_free(c2) };
        unsafe { tpx_complex_free(c) };
        // No coordinates.
        let (ids, offsets) = ([0u32, 1, 2], [0usize, 3]);
        let mut bare = null_mut();
        let st = unsafe {
            tpx_complex_from_arrays(3, ids.as_ptr(), offsets.as_ptr(), 1, null(), 0, &mut bare)
        };
        assert_eq!(st, TpxStatus::Ok);
        let mut out = sentinel;
        assert_eq!(
            unsafe { tpx_simplify(bare, 0.5, false, &mut out) },
            TpxStatus::CannotSimplify
        );
        assert!(
            last_error().contains("no vertex coordinates"),
            "{}",
            last_error()
        );
        assert_eq!(out, sentinel);
        unsafe { tpx_complex_free(bare) };
    }

    #[test]
    fn simplify_file_writes_or_refuses_before_the_work() {
        let dir = super::tempdir("ffi");
        let input = dir.join("octa.off");
        std::fs::write(&input, super::octahedron_off()).unwrap();
        let input = CString::new(input.to_str().unwrap()).unwrap();
        let good = dir.join("out.obj");
        let out = CString::new(good.to_str().unwrap()).unwrap();
        let st = unsafe { tpx_simplify_file(input.as_ptr(), out.as_ptr(), 0.5, true) };
        assert_eq!(st, TpxStatus::Ok, "{}", last_error());
        let back = topoplex::Complex::from_path(&good).unwrap();
        assert_eq!(back.top_counts(), vec![0, 0, 4]);
        for (path, status, needle) in [
            (
                "/nonexistent-dir/out.off",
                TpxStatus::WriteError,
                "cannot write",
            ),
            (
                "out.xyz",
                TpxStatus::UnknownFormat,
                "unknown output extension",
            ),
        ] {
            let p = CString::new(path).unwrap();
            let st = unsafe { tpx_simplify_file(input.as_ptr(), p.as_ptr(), 0.5, false) };
            assert_eq!(st, status, "{path}");
            assert!(last_error().contains(needle), "{}", last_error());
        }
        // A tetrahedron cannot go to OFF: refused before the work, nothing left behind.
        let tet = dir.join("tet.simplices");
        std::fs::write(&tet, "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\ns 0 1 2 3\n").unwrap();
        let tet = CString::new(tet.to_str().unwrap()).unwrap();
        let off = dir.join("tet.off");
        let off_c = CString::new(off.to_str().unwrap()).unwrap();
        let st = unsafe { tpx_simplify_file(tet.as_ptr(), off_c.as_ptr(), 0.5, false) };
        assert_eq!(st, TpxStatus::FormatCannotHold, "{}", last_error());
        assert!(!off.exists());
        let stl = dir.join("out.stl");
        let stl_c = CString::new(stl.to_str().unwrap()).unwrap();
        // STL takes triangles but only 32-bit floats: the moved vertices are refused after the
        // work, and the file it had created is removed.
        let st = unsafe { tpx_simplify_file(input.as_ptr(), stl_c.as_ptr(), 0.5, false) };
        assert_eq!(st, TpxStatus::FormatCannotHold, "{}", last_error());
        assert!(last_error().contains("32-bit float"), "{}", last_error());
        assert!(!stl.exists());
        let missing = CString::new("/nonexistent-dir/in.off").unwrap();
        let st = unsafe { tpx_simplify_file(missing.as_ptr(), out.as_ptr(), 0.5, false) };
        assert_eq!(st, TpxStatus::IoError);
        let st = unsafe { tpx_simplify_file(input.as_ptr(), out.as_ptr(), 2.0, false) };
        assert_eq!(st, TpxStatus::InvalidRatio);
        let st = unsafe { tpx_simplify_file(null(), out.as_ptr(), 0.5, false) };
        assert_eq!(st, TpxStatus::NullArgument);
    }
}
