//! Writers: every fixture, every file of `../shared/data` and random non-manifold complexes,
//! read → written in every format that can hold them → read back, give the same top simplices in
//! the same order with the same winding and bit-identical coordinates. A format that refuses
//! must have a reason the complex really has.

use crate::common;

use std::path::Path;

use proptest::prelude::*;
use topoplex::Complex;
use topoplex::io::Coords;
use topoplex::io::write::{Format, WriteErrorKind, listing, write_complex};

use common::Scratch;

/// Most vertices per simplex the format lists, and most coordinates per vertex.
fn capacity(f: Format) -> (usize, usize) {
    match f {
        Format::Off => (3, usize::MAX),
        Format::Obj | Format::Ply | Format::PlyBinary => (3, 3),
        Format::Medit | Format::Vtk | Format::VtkBinary | Format::Vtu => (4, 3),
        Format::Msh | Format::MshBinary | Format::Msh2 | Format::Msh2Binary => (4, 3),
        Format::Simplices => (16, usize::MAX),
        Format::Stl | Format::StlBinary => (3, 3),
    }
}

fn is_stl(f: Format) -> bool {
    matches!(f, Format::Stl | Format::StlBinary)
}

/// What STL holds beyond its capacity: triangles only, covering every vertex, with distinct
/// coordinates that are exactly 32-bit floats.
fn stl_holds(c: &Complex) -> bool {
    let only_triangles = (0..=c.dimension()).all(|p| p == 2 || c.tops(p).is_empty());
    let coords = c
        .coords()
        .map_or(vec![0.0; c.vertex_count() as usize * 3], |x| {
            (0..c.vertex_count() as usize)
                .flat_map(|v| {
                    (0..3).map(move |k| {
                        if k < x.dim {
                            x.data[v * x.dim + k]
                        } else {
                            0.0
                        }
                    })
                })
                .collect()
        });
    let exact = coords
        .iter()
        .all(|&x| f64::from(x as f32).to_bits() == x.to_bits());
    let mut points: Vec<[u64; 3]> = coords
        .chunks(3)
        .map(|p| [p[0].to_bits(), p[1].to_bits(), p[2].to_bits()])
        .collect();
    points.sort();
    points.dedup();
    only_triangles && exact && points.len() == c.vertex_count() as usize
}

/// Whether the format keeps the listing order across dimensions (else per dimension), and
/// whether it lists 0-simplices.
fn keeps_mixed_order(f: Format) -> bool {
    !matches!(f, Format::Medit | Format::Ply | Format::PlyBinary)
}

fn lists_points(f: Format) -> bool {
    !matches!(f, Format::Medit | Format::Ply | Format::PlyBinary)
}

/// STL numbers vertices by first appearance: the complex `c` renumbered so.
fn renumbered_by_first_appearance(c: &Complex) -> Complex {
    let mut new_id = vec![u32::MAX; c.vertex_count() as usize];
    let mut next = 0;
    let raw = listing(c);
    for &v in &raw.ids {
        if new_id[v as usize] == u32::MAX {
            new_id[v as usize] = next;
            next += 1;
        }
    }
    let ids: Vec<u32> = raw.ids.iter().map(|&v| new_id[v as usize]).collect();
    let coords = c.coords().map(|x| {
        let mut data = vec![0.0; x.data.len()];
        for (v, &w) in new_id.iter().enumerate() {
            let w = w as usize;
            data[w * x.dim..(w + 1) * x.dim].copy_from_slice(&x.data[v * x.dim..(v + 1) * x.dim]);
        }
        Coords { dim: x.dim, data }
    });
    Complex::from_arrays(c.vertex_count(), &ids, &raw.offsets, coords).unwrap()
}

fn rows(c: &Complex) -> Vec<Vec<u32>> {
    let raw = listing(c);
    (0..raw.simplex_count())
        .map(|i| raw.simplex(i).to_vec())
        .collect()
}

/// The listing as the format keeps it: grouped by dimension unless it keeps the mixed order,
/// without 0-simplices unless it lists them.
fn as_kept(rows: Vec<Vec<u32>>, f: Format) -> Vec<Vec<u32>> {
    let mut rows: Vec<Vec<u32>> = rows
        .into_iter()
        .filter(|s| lists_points(f) || s.len() > 1)
        .collect();
    if !keeps_mixed_order(f) {
        rows.sort_by_key(Vec::len); // stable: listing order within a dimension
    }
    rows
}

/// Coordinates read back equal the written ones bit for bit, padded with zeros where the format
/// needs more numbers (zeros only, when the complex had none).
fn same_coords(a: Option<&Coords>, b: Option<&Coords>, n: usize) -> Result<(), String> {
    let Some(b) = b else {
        return match a {
            None => Ok(()),
            Some(_) => Err("coordinates lost".into()),
        };
    };
    let adim = a.map_or(0, |c| c.dim);
    if b.dim < adim {
        return Err(format!(
            "coordinate dimension {} read back as {}",
            adim, b.dim
        ));
    }
    for v in 0..n {
        for i in 0..b.dim {
            let want = a.filter(|_| i < adim).map_or(0.0, |a| a.data[v * adim + i]);
            let got = b.data[v * b.dim + i];
            let same = want.to_bits() == got.to_bits() || (want.is_nan() && got.is_nan());
            if !same {
                return Err(format!(
                    "vertex {v} coordinate {i}: wrote {want:e}, read {got:e}"
                ));
            }
        }
    }
    Ok(())
}

/// Writes `c` as `f` into `dir` and reads it back; checks the refusal's reason when refused.
fn round_trip(c: &Complex, f: Format, dir: &Path, name: &str) -> Result<(), String> {
    let path = dir.join(format!("{name}.{}", f.extension()));
    let (max_len, max_coords) = capacity(f);
    let fits = (0..=c.dimension()).all(|p| p < max_len || c.tops(p).is_empty())
        && c.coords().is_none_or(|x| x.dim <= max_coords)
        && (!is_stl(f) || stl_holds(c))
        && (f != Format::Ply
            || c.coords()
                .is_none_or(|x| x.data.iter().all(|v| v.is_finite())));
    match write_complex(c, &path, Some(f)) {
        Err(e) => {
            let WriteErrorKind::CannotHold { .. } = e.kind else {
                return Err(format!("{f:?}: {e}"));
            };
            if fits {
                return Err(format!("{f:?} refused a complex it can hold: {e}"));
            }
            if path.exists() {
                return Err(format!("{f:?} refused but left {}", path.display()));
            }
            return Ok(());
        }
        Ok(()) if !fits => return Err(format!("{f:?} accepted a complex it cannot hold")),
        Ok(()) => {}
    }
    let back = Complex::from_path(&path).map_err(|e| format!("{f:?}: read back: {e}"))?;
    let renumbered;
    let c = if is_stl(f) {
        renumbered = renumbered_by_first_appearance(c);
        &renumbered
    } else {
        c
    };
    if back.vertex_count() != c.vertex_count() {
        return Err(format!(
            "{f:?}: {} vertices read back as {}",
            c.vertex_count(),
            back.vertex_count()
        ));
    }
    for p in 0..=c.dimension().max(back.dimension()) {
        if c.tops(p) != back.tops(p) {
            return Err(format!("{f:?}: top {p}-simplices differ"));
        }
    }
    if as_kept(rows(c), f) != as_kept(rows(&back), f) {
        return Err(format!("{f:?}: listing order or winding differs"));
    }
    same_coords(c.coords(), back.coords(), c.vertex_count() as usize)
        .map_err(|e| format!("{f:?}: {e}"))
}

fn round_trip_all(c: &Complex, name: &str) {
    let dir = Scratch::new(name);
    for f in Format::ALL {
        round_trip(c, f, &dir.0, name).unwrap_or_else(|e| panic!("{name}: {e}"));
    }
}

#[test]
fn fixtures_round_trip_through_every_format() {
    for (name, c) in topoplex::fixtures::all() {
        round_trip_all(&c, name);
    }
}

#[test]
fn shared_data_round_trips_through_every_format() {
    for (file, mut c) in common::shared_complexes() {
        // The shape through every format; the labelled meshes' data round trips through the
        // formats that hold it in tests/it/attributes.rs.
        c.take_attributes();
        let name = file.file_stem().unwrap().to_string_lossy().into_owned();
        round_trip_all(&c, &name);
    }
}

#[test]
fn awkward_coordinates_read_back_bit_for_bit() {
    //   0 ---- 1     one triangle and a wire edge, with coordinates that need 17 digits,
    //    \   /       subnormals, huge exponents, negative zero and non-finite values
    //      2 ---- 3
    let xs = [
        0.1,
        -0.0,
        1e300,
        f64::MIN_POSITIVE / 3.0,
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::NAN,
        std::f64::consts::PI,
        -1.0 / 3.0,
        f64::MAX,
        5e-324,
        123456789.0,
    ];
    let c = Complex::from_arrays(
        4,
        &[2, 1, 0, 3, 2],
        &[0, 3, 5],
        Some(Coords {
            dim: 3,
            data: xs.to_vec(),
        }),
    )
    .unwrap();
    round_trip_all(&c, "awkward");
}

#[test]
fn isolated_vertices_without_coordinates_and_mixed_order_survive() {
    //   4 (isolated, unlisted)   5 (listed point)
    //   0 --- 1 --- 2            edge, triangle, edge listed in that order,
    //          \   /             triangle wound 2 1 3
    //            3
    let c = Complex::from_simplices(6, &[&[1, 0], &[2, 1, 3], &[5], &[3, 2, 1], &[2, 0]]).unwrap();
    assert_eq!(rows(&c), [vec![1, 0], vec![2, 1, 3], vec![5], vec![2, 0]]);
    round_trip_all(&c, "mixed");
}

#[test]
fn refusals_name_the_simplex() {
    //   a tetrahedron 0 1 2 3 with 4-dimensional coordinates
    let c = Complex::from_arrays(
        4,
        &[0, 1, 2, 3],
        &[0, 4],
        Some(Coords {
            dim: 4,
            data: vec![0.0; 16],
        }),
    )
    .unwrap();
    let msg = |f: Format| match f.write(&listing(&c)) {
        Err(e) => e.to_string(),
        Ok(_) => panic!("{f:?} accepted"),
    };
    assert_eq!(
        msg(Format::Off),
        "the off format cannot hold this complex: simplex #0 [0 1 2 3] has dimension 3; it \
         holds vertices, edges and triangles (use .mesh, .msh, .vtk or .simplices)"
    );
    assert_eq!(
        msg(Format::Medit),
        "the mesh format cannot hold this complex: the coordinates have 4 numbers per vertex; \
         it holds at most 3"
    );
    assert!(Format::Simplices.write(&listing(&c)).is_ok());
}

#[test]
fn exact_text_of_each_format() {
    //   0 --- 1      triangle 1 0 2 (as wound in the input), wire edge 2 3
    //    \   /
    //      2 --- 3
    let c = Complex::from_arrays(
        4,
        &[1, 0, 2, 2, 3],
        &[0, 3, 5],
        Some(Coords {
            dim: 2,
            data: vec![0.0, 1.0, 1.0, 1.0, 0.5, 0.0, 1.5, -0.25],
        }),
    )
    .unwrap();
    let text = |f: Format| String::from_utf8(f.write(&listing(&c)).unwrap()).unwrap();
    assert_eq!(
        text(Format::Off),
        "OFF\n4 2 0\n0 1 0\n1 1 0\n0.5 0 0\n1.5 -0.25 0\n3 1 0 2\n2 2 3\n"
    );
    assert_eq!(
        text(Format::Obj),
        "v 0 1 0\nv 1 1 0\nv 0.5 0 0\nv 1.5 -0.25 0\nf 2 1 3\nl 3 4\n"
    );
    assert_eq!(
        text(Format::Medit),
        "MeshVersionFormatted 2\nDimension 2\nVertices\n4\n0 1 0\n1 1 0\n0.5 0 0\n1.5 -0.25 0\n\
         Edges\n1\n3 4 0\nTriangles\n1\n2 1 3 0\nEnd\n"
    );
    assert_eq!(
        text(Format::Simplices),
        "v 0 1\nv 1 1\nv 0.5 0\nv 1.5 -0.25\ns 1 0 2\ns 2 3\n"
    );
}

#[test]
fn stl_welds_equal_corners_and_numbers_vertices_by_first_appearance() {
    //   3 ------ 2      two triangles 3 0 2 and 0 1 2 sharing edge 0-2, listed so that the
    //   |      / |      first appearances are 3, 0, 2, 1: read back as 0, 1, 2, 3
    //   |    /   |
    //   0 ------ 1
    let xyz = vec![0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 1.0, 1.0, 0.5, 0.0, 1.0, 0.25];
    let c = Complex::from_arrays(
        4,
        &[3, 0, 2, 0, 1, 2],
        &[0, 3, 6],
        Some(Coords { dim: 3, data: xyz }),
    )
    .unwrap();
    round_trip_all(&c, "stl-square");
    let dir = Scratch::new("stl-square-b");
    for f in [Format::Stl, Format::StlBinary] {
        let path = dir.0.join("s.stl");
        write_complex(&c, &path, Some(f)).unwrap();
        let back = Complex::from_path(&path).unwrap();
        assert_eq!(back.vertex_count(), 4, "{f:?}: corners welded");
        assert_eq!(rows(&back), [vec![0, 1, 2], vec![1, 3, 2]], "{f:?}");
        assert_eq!(back.coords().unwrap().data[..3], [0.0, 1.0, 0.25]);
    }
    // 0.1 is not a 32-bit float: refused rather than rounded.
    let c = Complex::from_arrays(
        3,
        &[0, 1, 2],
        &[0, 3],
        Some(Coords {
            dim: 2,
            data: vec![0.1, 0.0, 1.0, 0.0, 0.0, 1.0],
        }),
    )
    .unwrap();
    let e = Format::Stl.write(&listing(&c)).unwrap_err().to_string();
    assert!(
        e.contains("vertex 0 coordinate 1e-1 is not exactly a 32-bit float"),
        "{e}"
    );
}

/// Distinct coordinates that are exact 32-bit floats, so that every format, STL included, can
/// hold the complex's geometry.
fn with_coordinates(c: &Complex) -> Complex {
    let raw = listing(c);
    let data = (0..c.vertex_count())
        .flat_map(|v| [f64::from(v) * 0.5, -f64::from(v), 0.25])
        .collect();
    Complex::from_arrays(
        c.vertex_count(),
        &raw.ids,
        &raw.offsets,
        Some(Coords { dim: 3, data }),
    )
    .unwrap()
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 64, ..ProptestConfig::default() })]
    #[test]
    fn random_complexes_round_trip(c in common::random_complex(4, 8, 8)) {
        let dir = Scratch::new("random");
        for f in Format::ALL {
            prop_assert_eq!(round_trip(&c, f, &dir.0, "random"), Ok(()));
            prop_assert_eq!(round_trip(&with_coordinates(&c), f, &dir.0, "random-xyz"), Ok(()));
        }
    }

    #[test]
    fn random_triangle_sets_round_trip_through_stl((n, list) in common::random_input(2, 8, 8)) {
        // Triangles only, every vertex in one: what STL holds.
        let tris: Vec<Vec<u32>> = list.into_iter().filter(|s| s.len() == 3).collect();
        let used: std::collections::BTreeSet<u32> = tris.iter().flatten().copied().collect();
        prop_assume!(!tris.is_empty() && used.len() == n as usize);
        let c = with_coordinates(&common::complex_of(n, &tris));
        prop_assert!(stl_holds(&c));
        let dir = Scratch::new("random-stl");
        for f in [Format::Stl, Format::StlBinary] {
            prop_assert_eq!(round_trip(&c, f, &dir.0, "random"), Ok(()));
        }
    }
}

#[test]
fn c_abi_writes_by_extension_or_format_constant() {
    use std::ffi::{CStr, CString};
    use topoplex_ffi::*;
    let last = || {
        // SAFETY: never NULL, NUL-terminated.
        unsafe { CStr::from_ptr(tpx_last_error_message()) }
            .to_string_lossy()
            .into_owned()
    };
    //   a tetrahedron 3 2 1 0 (as wound) and a wire edge 4 0
    let ids = [3u32, 2, 1, 0, 4, 0];
    let offsets = [0usize, 4, 6];
    let xyz: Vec<f64> = (0..15).map(|i| f64::from(i) / 7.0).collect();
    let mut c = std::ptr::null_mut();
    // SAFETY: arrays of the stated lengths.
    let st = unsafe {
        tpx_complex_from_arrays(
            5,
            ids.as_ptr(),
            offsets.as_ptr(),
            2,
            xyz.as_ptr(),
            3,
            &mut c,
        )
    };
    assert_eq!(st, TpxStatus::Ok);
    let dir = Scratch::new("abi");
    let path = |name: &str| CString::new(dir.0.join(name).to_str().unwrap()).unwrap();
    let write =
        |name: &str, format: u32| unsafe { tpx_complex_write(c, path(name).as_ptr(), format) };
    assert_eq!(
        write("a.mesh", TPX_FORMAT_FROM_EXTENSION),
        TpxStatus::Ok,
        "{}",
        last()
    );
    let back = Complex::from_path(&dir.0.join("a.mesh")).unwrap();
    // MEDIT has one section per cell type: edges before tetrahedra.
    assert_eq!(rows(&back), [vec![4, 0], vec![3, 2, 1, 0]]);
    assert_eq!(back.coords().unwrap().data, xyz);
    assert_eq!(
        write("a.off", TPX_FORMAT_FROM_EXTENSION),
        TpxStatus::FormatCannotHold
    );
    assert!(
        last().contains("simplex #0 [3 2 1 0] has dimension 3"),
        "{}",
        last()
    );
    assert!(!dir.0.join("a.off").exists());
    assert_eq!(
        write("a.txt", TPX_FORMAT_FROM_EXTENSION),
        TpxStatus::UnknownFormat
    );
    assert_eq!(write("a.txt", 999), TpxStatus::UnknownFormat);
    assert_eq!(write("a.txt", TPX_FORMAT_SIMPLICES), TpxStatus::Ok);
    assert_eq!(
        write("no-such-dir/a.off", TPX_FORMAT_SIMPLICES),
        TpxStatus::IoError
    );
    // SAFETY: NULL arguments are checked.
    let st = unsafe { tpx_complex_write(std::ptr::null(), path("x.off").as_ptr(), 0) };
    assert_eq!(st, TpxStatus::NullArgument);
    let st = unsafe { tpx_complex_write(c, std::ptr::null(), 0) };
    assert_eq!(st, TpxStatus::NullArgument);
    unsafe { tpx_complex_free(c) };
}

#[test]
fn mutated_seed_files_are_refused_or_read_never_panic() {
    // Random byte edits (xorshift, fixed seed) of the fuzz corpus seeds of the byte readers.
    type Parse = fn(&[u8]) -> Result<topoplex::io::RawInput, (u32, topoplex::io::ReadErrorKind)>;
    let readers: [(&str, Parse); 5] = [
        ("read_ply", topoplex::io::ply::parse),
        ("read_stl", topoplex::io::stl::parse),
        ("read_vtk", topoplex::io::vtk::parse),
        ("read_vtu", topoplex::io::vtu::parse),
        ("read_msh", topoplex::io::msh::parse),
    ];
    let mut state: u64 = 0x9e37_79b9_7f4a_7c15;
    let mut rnd = move || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        state
    };
    for (dir, parse) in readers {
        let corpus = concat!(env!("CARGO_MANIFEST_DIR"), "/fuzz/corpus");
        let seeds: Vec<Vec<u8>> = std::fs::read_dir(format!("{corpus}/{dir}"))
            .unwrap()
            .map(|e| std::fs::read(e.unwrap().path()).unwrap())
            .collect();
        for i in 0..1500 {
            let mut b = seeds[i % seeds.len()].clone();
            for _ in 0..1 + rnd() % 4 {
                if b.is_empty() {
                    break;
                }
                let p = rnd() as usize % b.len();
                match rnd() % 4 {
                    0 => b[p] = rnd() as u8,
                    1 => b.truncate(p),
                    2 => {
                        b.remove(p);
                    }
                    _ => b.insert(p, b"0123456789 -.\n$e"[(rnd() % 16) as usize]),
                }
            }
            if let Ok(raw) = parse(&b) {
                let _ = Complex::from_raw(&raw, None);
            }
        }
    }
}

/// Fuzz find: a legacy VTK cell whose length is a 40-digit number is a CELLS error, not an
/// overflow in the length arithmetic.
#[test]
fn vtk_cell_length_beyond_usize_is_an_error() {
    let text = "# vtk DataFile Version 4.2\nwritten by topoplex\nASCII\nDATASET UNSTRUCTURED_GRID\n\
                POINTS 5 double\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n2 2 2\nCELLS 2 8\n4 0 1 2 3\n\
                9999999999999999999999999999999999999999 0 1\nCELL_TYPES 2\n10\n3\n";
    let e = topoplex::io::vtk::parse(text.as_bytes()).unwrap_err();
    assert!(e.1.to_string().contains("ends inside cell #1"), "{}", e.1);
}

/// A 200×200 grid of 80,000 triangles with non-round coordinates: its OFF, OBJ, MEDIT and
/// `.simplices` files pass 1 MiB, so the text writers hand the file over in pieces; every
/// format still reads back the same complex (order, winding, coordinates bit for bit).
#[test]
fn a_grid_larger_than_a_write_piece_round_trips_through_every_format() {
    let k = 200u32;
    let mut ids = Vec::new();
    let mut offsets = vec![0usize];
    for j in 0..k {
        for i in 0..k {
            let a = j * (k + 1) + i;
            for t in [[a, a + 1, a + k + 2], [a, a + k + 2, a + k + 1]] {
                ids.extend_from_slice(&t);
                offsets.push(ids.len());
            }
        }
    }
    let n = (k + 1) * (k + 1);
    let data = (0..n)
        .flat_map(|v| {
            let (x, y) = (f64::from(v % (k + 1)), f64::from(v / (k + 1)));
            [x / 3.0, y / 7.0, (x * y).sin()]
        })
        .collect();
    let c = Complex::from_arrays(
        n,
        &ids,
        &offsets,
        Some(topoplex::io::Coords { dim: 3, data }),
    )
    .unwrap();
    round_trip_all(&c, "grid-200");
}
