//! Interoperability with an independent reader and writer, Python's meshio
//! (tests/interop/meshio_check.py): files Topoplex writes are read by meshio with the same points
//! and cells, and files meshio writes are read by Topoplex as the same complex. Skipped (with a
//! note on stderr) when `python3 -c "import meshio"` fails; scripts/test.sh installs meshio.

use std::collections::BTreeMap;
use std::path::PathBuf;
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

/// Cells by meshio type name, each type's cells in file order.
type Cells = BTreeMap<String, Vec<Vec<u32>>>;

/// Runs the helper once for all `jobs` (mode, file, meshio format); per job, its JSON output
/// as (points, cells).
fn meshio(jobs: &[(&str, PathBuf, &str)]) -> Vec<(Vec<[f64; 3]>, Cells)> {
    meshio_lines(jobs).iter().map(|l| parse_answer(l)).collect()
}

/// Runs the helper once for all `jobs`; per job, its output line.
fn meshio_lines(jobs: &[(&str, PathBuf, &str)]) -> Vec<String> {
    use std::io::Write;
    let script = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/interop/meshio_check.py");
    let mut child = Command::new("python3")
        .arg(script)
        .stdin(std::process::Stdio::piped())
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    let mut input = String::new();
    for (mode, path, format) in jobs {
        input.push_str(&format!("{mode} {} {format}\n", path.display()));
    }
    child
        .stdin
        .take()
        .unwrap()
        .write_all(input.as_bytes())
        .unwrap();
    let o = child.wait_with_output().unwrap();
    assert!(
        o.status.success(),
        "meshio: {}",
        String::from_utf8_lossy(&o.stderr)
    );
    let text = String::from_utf8(o.stdout).unwrap();
    let answers: Vec<String> = text.lines().map(str::to_string).collect();
    assert_eq!(answers.len(), jobs.len());
    answers
}

/// Point or cell data as meshio gives it: name → values (exact, as strings of reprs parsed).
type Data = BTreeMap<String, Vec<u64>>;

/// A `readdata`/`writedata` answer: (point data, cell data), each value's f64 bits.
fn parse_data(line: &str) -> (Data, Data) {
    let json: serde_json::Value = serde_json::from_str(line).unwrap();
    let get = |key: &str| -> Data {
        json[key]
            .as_object()
            .unwrap()
            .iter()
            .map(|(k, v)| {
                let xs = v.as_array().unwrap().iter().map(|x| {
                    let x: f64 = x.as_str().unwrap().parse().unwrap();
                    // Every NaN alike: Python prints them all as 'nan'.
                    if x.is_nan() {
                        f64::NAN.to_bits()
                    } else {
                        x.to_bits()
                    }
                });
                (k.clone(), xs.collect())
            })
            .collect()
    };
    (get("point_data"), get("cell_data"))
}

/// Our attributes in meshio's terms: the vertex ones as point data, the listed ones as cell
/// data (numbers as f64 bits, NaNs alike), the gmsh:* tag arrays left out.
fn our_data(c: &Complex) -> (Data, Data) {
    let (mut point, mut cell) = (Data::new(), Data::new());
    for a in c
        .attributes()
        .iter()
        .filter(|a| !a.name.starts_with("gmsh:"))
    {
        let xs = (0..a.values.len())
            .map(|i| {
                let x = a.values.real(i).unwrap();
                if x.is_nan() {
                    f64::NAN.to_bits()
                } else {
                    x.to_bits()
                }
            })
            .collect();
        match a.location {
            topoplex::complex::Location::Vertices => point.insert(a.name.clone(), xs),
            topoplex::complex::Location::Listed => cell.insert(a.name.clone(), xs),
        };
    }
    (point, cell)
}

/// Point and cell data: what meshio writes (VTU binary, MSH 2.2 and 4.1 binary) Topoplex reads
/// with the same values, and what Topoplex writes of it meshio reads with the same values.
#[test]
fn point_and_cell_data_read_alike_by_meshio_and_topoplex_both_ways() {
    if !meshio_present() {
        return;
    }
    let dir = scratch("data");
    let formats = [
        (Format::Vtu, "vtu-binary"),
        (Format::Msh2Binary, "gmsh22-binary"),
        (Format::MshBinary, "gmsh-binary"),
        (Format::Msh, "gmsh-binary"),
    ];
    let theirs: Vec<_> = formats
        .iter()
        .enumerate()
        .map(|(i, &(f, name))| {
            (
                "writedata",
                dir.0.join(format!("theirs-{i}.{}", f.extension())),
                name,
            )
        })
        .collect();
    let written = meshio_lines(&theirs);
    let mut ours = Vec::new();
    for ((&(format, name), (_, path, _)), line) in formats.iter().zip(&theirs).zip(&written) {
        let c = Complex::from_path(path).unwrap_or_else(|e| panic!("{name}: {e}"));
        let want = parse_data(line);
        assert!(!want.0.is_empty() && !want.1.is_empty(), "{name}");
        assert_eq!(our_data(&c), want, "{name}: what we read of meshio's file");
        let out = dir
            .0
            .join(format!("ours-{}.{}", format.name(), format.extension()));
        write_complex(&c, &out, Some(format)).unwrap();
        ours.push(("readdata", out, name));
    }
    for ((&(format, _), line), want) in formats.iter().zip(meshio_lines(&ours)).zip(&written) {
        assert_eq!(
            parse_data(&line),
            parse_data(want),
            "{}: what meshio reads of ours",
            format.name()
        );
    }
}

fn parse_answer(line: &str) -> (Vec<[f64; 3]>, Cells) {
    let json: serde_json::Value = serde_json::from_str(line).unwrap();
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
    let mut cells = Cells::new();
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
fn cells_by_type(c: &Complex) -> Cells {
    let raw = listing(c);
    let mut cells = Cells::new();
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
    let mut jobs = Vec::new();
    for &(format, name, triangles_only) in FORMATS {
        let path = dir.0.join(format!("ours-{name}.{}", format.extension()));
        write_complex(&our_complex(triangles_only), &path, Some(format)).unwrap();
        jobs.push(("read", path, name));
    }
    let answers = meshio(&jobs);
    for (&(format, name, triangles_only), (points, cells)) in FORMATS.iter().zip(answers) {
        let c = our_complex(triangles_only);
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
    let jobs: Vec<_> = FORMATS
        .iter()
        .map(|&(format, name, _)| {
            let path = dir.0.join(format!("theirs-{name}.{}", format.extension()));
            ("write", path, name)
        })
        .collect();
    let answers = meshio(&jobs);
    for ((&(format, name, _), (points, cells)), (_, path, _)) in
        FORMATS.iter().zip(answers).zip(&jobs)
    {
        let c = Complex::from_path(path).unwrap_or_else(|e| panic!("{name}: {e}"));
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
