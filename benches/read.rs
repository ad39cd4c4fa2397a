//! Reading speed of the four text readers (issue 17 item 1): `io::read_path` on generated files
//! of ~20-40 MB, file already in the page cache. Throughput is in bytes, so criterion reports
//! MB/s of input.
//!
//! Files (written once to the temp dir, removed at the end):
//! - `tet-grid.mesh`: a 40×40×40 Freudenthal tetrahedral grid as MEDIT (384,000 tetrahedra);
//! - `tri-grid.off`, `tri-grid.obj`, `tri-grid.simplices`: a 700×700 triangle grid (980,000
//!   triangles) with coordinates written as `{:.6}` decimals.
//!
//! Benchmark ids are `read/<file>`; `cargo bench --bench read -- mesh` selects one.

use std::fmt::Write as _;
use std::hint::black_box;
use std::path::PathBuf;
use std::time::Duration;

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use topoplex::fixtures::freudenthal_grid;

/// The (k+1)² vertices of a k×k grid with non-round coordinates, as `x y z` lines after `prefix`.
fn grid_vertices(out: &mut String, k: u32, prefix: &str, suffix: &str) {
    for i in 0..=k {
        for j in 0..=k {
            let (x, y) = (i as f64 / 7.0, j as f64 / 3.0);
            writeln!(out, "{prefix}{x:.6} {y:.6} {:.6}{suffix}", (x * y).sin()).unwrap();
        }
    }
}

/// The two triangles of each square of a k×k grid, as 0-based vertex ids.
fn grid_triangles(k: u32) -> impl Iterator<Item = [u32; 3]> {
    let id = move |i: u32, j: u32| i * (k + 1) + j;
    (0..k).flat_map(move |i| {
        (0..k).flat_map(move |j| {
            [
                [id(i, j), id(i + 1, j), id(i + 1, j + 1)],
                [id(i, j), id(i, j + 1), id(i + 1, j + 1)],
            ]
        })
    })
}

fn off(k: u32) -> String {
    let mut s = format!("OFF\n{} {} 0\n", (k + 1) * (k + 1), 2 * k * k);
    grid_vertices(&mut s, k, "", "");
    for [a, b, c] in grid_triangles(k) {
        writeln!(s, "3 {a} {b} {c}").unwrap();
    }
    s
}

fn obj(k: u32) -> String {
    let mut s = String::from("# triangle grid\n");
    grid_vertices(&mut s, k, "v ", "");
    for [a, b, c] in grid_triangles(k) {
        writeln!(s, "f {} {} {}", a + 1, b + 1, c + 1).unwrap();
    }
    s
}

fn simplices(k: u32) -> String {
    let mut s = String::new();
    grid_vertices(&mut s, k, "v ", "");
    for [a, b, c] in grid_triangles(k) {
        writeln!(s, "s {a} {b} {c}").unwrap();
    }
    s
}

/// A k×k×k grid of cubes, six tetrahedra each (Freudenthal), as MEDIT.
fn medit(k: u32) -> String {
    let n = k + 1;
    let mut s = format!(
        "MeshVersionFormatted 2\nDimension 3\nVertices\n{}\n",
        n * n * n
    );
    for x in 0..n {
        for y in 0..n {
            for z in 0..n {
                writeln!(s, "{}.25 {}.5 {}.125 0", x, y, z).unwrap();
            }
        }
    }
    writeln!(s, "Tetrahedra\n{}", 6 * k * k * k).unwrap();
    for [a, b, c, d] in freudenthal_grid(k, |[x, y, z]| (x * n + y) * n + z + 1) {
        writeln!(s, "{a} {b} {c} {d} 1").unwrap();
    }
    s.push_str("End\n");
    s
}

fn bench(c: &mut Criterion) {
    let dir = std::env::temp_dir().join(format!("topoplex-read-bench-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let files: Vec<(&str, PathBuf)> = [
        ("tet-grid.mesh", medit(40)),
        ("tri-grid.off", off(700)),
        ("tri-grid.obj", obj(700)),
        ("tri-grid.simplices", simplices(700)),
    ]
    .into_iter()
    .map(|(name, text)| {
        let path = dir.join(name);
        std::fs::write(&path, text).unwrap();
        (name, path)
    })
    .collect();

    let mut g = c.benchmark_group("read");
    g.sample_size(10)
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(4));
    for (name, path) in &files {
        g.throughput(Throughput::Bytes(std::fs::metadata(path).unwrap().len()));
        g.bench_function(*name, |b| {
            b.iter(|| black_box(topoplex::io::read_path(path).unwrap()))
        });
    }
    g.finish();
    std::fs::remove_dir_all(&dir).ok();
}

criterion_group!(benches, bench);
criterion_main!(benches);
