//! Interoperability with an independent reader and writer, Python's meshio
//! (tests/interop/meshio_check.py): files Topoplex writes are read by meshio with the same points
//! and cells, and files meshio writes are read by Topoplex as the same complex. Skipped (with a
//! note on stderr) when `python3 -c "import meshio"` fails; scripts/test.sh installs meshio.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::Command;

use topoplex::Complex;
use topoplex::io::Coords;
use topoplex::io::write::{Format, listing, write_complex};

fn meshio_present() -> bool {
    let ok = Command::new("python3")
        .args(["-c", "import meshio"])
        .output()
        .is_ok_and(|o| o.status.success());
    if !ok {
        eprintln!("python3 with meshio is absent: skipping the interop checks");
    }
    ok
}

/// Runs the helper; its JSON output as (points, cells by meshio type in file order).
fn meshio(
    mode: &str,
    path: &Path,
    format: &str,
) -> (Vec<[f64; 3]>, BTreeMap<String, Vec<Vec<u32>>>) {
    let script = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/interop/meshio_check.py");
    let o = Command::new("python3")
        .args([script, mode, path.to_str().unwrap(), format])
        .output()
        .unwrap();
    assert!(
        o.status.success(),
        "meshio {mode} {format} {}: {}",
        path.display(),
        String::from_utf8_lossy(&o.stderr)
    );
    let json: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let points = json["points"]
        .as_array()
        .unwrap()
        .iter()
        .map(|p| {
            let xs: Vec<f64> = p
                .as_array()
                .unwrap()
                .iter()
                .map(|x| x.as_str().unwrap().parse().unwrap())
                .collect();
            [xs[0], xs[1], xs[2]]
        })
        .collect();
    let mut cells: BTreeMap<String, Vec<Vec<u32>>> = BTreeMap::new();
    for block in json["cells"].as_array().unwrap() {
        let rows = block[1].as_array().unwrap().iter().map(|r| {
            r.as_array()
                .unwrap()
                .iter()
                .map(|v| v.as_u64().unwrap() as u32)
                .collect::<Vec<u32>>()
        });
        cells
            .entry(block[0].as_str().unwrap().to_string())
            .or_default()
            .extend(rows);
    }
    (points, cells)
}

fn meshio_type(len: usize) -> &'static str {
    ["vertex", "line", "triangle", "tetra"][len - 1]
}

/// The complex's listing by meshio cell type, in listing order.
fn cells_by_type(c: &Complex) -> BTreeMap<String, Vec<Vec<u32>>> {
    let raw = listing(c);
    let mut cells: BTreeMap<String, Vec<Vec<u32>>> = BTreeMap::new();
    for i in 0..raw.simplex_count() {
        let s = raw.simplex(i);
        cells
            .entry(meshio_type(s.len()).into())
            .or_default()
            .push(s.to_vec());
    }
    cells
}

fn points_of(c: &Complex) -> Vec<[f64; 3]> {
    let x = c.coords().unwrap();
    (0..c.vertex_count() as usize)
        .map(|v| {
            [0, 1, 2].map(|k| {
                if k < x.dim {
                    x.data[v * x.dim + k]
                } else {
                    0.0
                }
            })
        })
        .collect()
}

fn bits(points: &[[f64; 3]]) -> Vec<[u64; 3]> {
    points.iter().map(|p| p.map(f64::to_bits)).collect()
}

/// Triangles as corner coordinates (STL renumbers: compared by geometry).
fn corner_sets(points: &[[f64; 3]], cells: &[Vec<u32>]) -> Vec<Vec<[u64; 3]>> {
    cells
        .iter()
        .map(|t| {
            t.iter()
                .map(|&v| points[v as usize].map(f64::to_bits))
                .collect()
        })
        .collect()
}

struct Scratch(PathBuf);

impl Drop for Scratch {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

fn scratch(tag: &str) -> Scratch {
    let dir = std::env::temp_dir().join(format!("topoplex-interop-{}-{tag}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    Scratch(dir)
}

/// (our format, meshio's name, whether the format holds only triangles).
const FORMATS: &[(Format, &str, bool)] = &[
    (Format::Off, "off", true),
    (Format::Obj, "obj", true),
    (Format::Ply, "ply", true),
    (Format::PlyBinary, "ply-binary", true),
    (Format::Stl, "stl", true),
    (Format::StlBinary, "stl-binary", true),
    (Format::Medit, "medit", false),
    (Format::Vtk, "vtk", false),
    (Format::VtkBinary, "vtk-binary", false),
    // meshio's ASCII .vtu rounds coordinates to 11 digits: its binary (zlib) output is used.
    (Format::Vtu, "vtu-binary", false),
    (Format::Msh, "gmsh", false),
    (Format::MshBinary, "gmsh-binary", false),
    (Format::Msh2, "gmsh22", false),
    (Format::Msh2Binary, "gmsh22-binary", false),
];

/// What Topoplex writes: triangles wound as given (with exact 32-bit float coordinates, for
/// STL), or a tetrahedron, a dangling triangle and a wire edge.
fn our_complex(triangles_only: bool) -> Complex {
    //   3 ------ 2          triangles 2 1 0, 0 2 3, 1 4 2 (as wound)
    //   |      / | \        or tetrahedron 4 2 1 0, triangle 0 3 2, wire edge 3 4
    //   |    /   |  4
    //   0 ------ 1
    let data = vec![
        0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 1.0, 1.0, 0.5, 0.0, 1.0, 0.25, 2.0, 0.125, -1.0,
    ];
    let (ids, offsets): (&[u32], &[usize]) = if triangles_only {
        (&[2, 1, 0, 0, 2, 3, 1, 4, 2], &[0, 3, 6, 9])
    } else {
        (&[4, 2, 1, 0, 0, 3, 2, 3, 4], &[0, 4, 7, 9])
    };
    Complex::from_arrays(5, ids, offsets, Some(Coords { dim: 3, data })).unwrap()
}

#[test]
fn meshio_reads_what_topoplex_writes() {
    if !meshio_present() {
        return;
    }
    let dir = scratch("ours");
    for &(format, name, triangles_only) in FORMATS {
        let c = our_complex(triangles_only);
        let path = dir.0.join(format!("ours-{name}.{}", format.extension()));
        write_complex(&c, &path, Some(format)).unwrap();
        let (points, cells) = meshio("read", &path, name);
        let want = cells_by_type(&c);
        if matches!(format, Format::Stl | Format::StlBinary) {
            assert_eq!(
                corner_sets(&points, &cells["triangle"]),
                corner_sets(&points_of(&c), &want["triangle"]),
                "{name}"
            );
            continue;
        }
        assert_eq!(bits(&points), bits(&points_of(&c)), "{name}: points");
        assert_eq!(cells, want, "{name}: cells");
    }
}

#[test]
fn topoplex_reads_what_meshio_writes() {
    if !meshio_present() {
        return;
    }
    let dir = scratch("theirs");
    for &(format, name, _) in FORMATS {
        let path = dir.0.join(format!("theirs-{name}.{}", format.extension()));
        let (points, cells) = meshio("write", &path, name);
        let c = Complex::from_path(&path).unwrap_or_else(|e| panic!("{name}: {e}"));
        let got = cells_by_type(&c);
        if matches!(format, Format::Stl | Format::StlBinary) {
            assert_eq!(
                corner_sets(&points_of(&c), &got["triangle"]),
                corner_sets(&points, &cells["triangle"]),
                "{name}"
            );
            continue;
        }
        assert_eq!(bits(&points_of(&c)), bits(&points), "{name}: points");
        assert_eq!(got, cells, "{name}: cells");
    }
}
