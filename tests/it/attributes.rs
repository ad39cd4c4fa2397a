//! Attributes (labels and fields) through the readers, the writers, the complex and the CLI:
//! random listings with random data written in every format that holds them and read back bit
//! for bit; the labelled meshes of `../shared/data/labelled` read alike by the three writers
//! Gmsh used (MSH 4.1 and 2.2, MEDIT, legacy VTK) and kept through our own round trips; every
//! "cannot hold" refused with the attribute's name and nothing written.

use crate::common;

use std::path::Path;
use std::process::Command;

use proptest::prelude::*;
use topoplex::Complex;
use topoplex::complex::{Attribute, Attributes, LabelName, Location, Values};
use topoplex::io::write::{Format, listing, write_complex, write_raw};
use topoplex::io::{Coords, RawInput, read_path};

use common::Scratch;

fn simplices(r: &RawInput) -> Vec<Vec<u32>> {
    (0..r.simplex_count())
        .map(|i| r.simplex(i).to_vec())
        .collect()
}

/// The simplices of `rows` of at most three vertices (what OFF, OBJ and PLY list), in order,
/// with its vertex count and coordinates.
fn up_to_triangles(rows: &RawInput) -> RawInput {
    let mut raw = RawInput::new();
    raw.vertex_count = rows.vertex_count;
    raw.coords = rows.coords.clone();
    for s in simplices(rows).iter().filter(|s| s.len() <= 3) {
        raw.push(s, 0);
    }
    raw
}

/// A listing of `n` vertices with coordinates: random simplices of 1 to 4 vertices (0-simplices
/// only when `points`), grouped by size ascending when `grouped` (MEDIT's sections), faces of
/// other listed simplices and repeats included.
fn random_listing(seed: u64, n: u32, count: usize, points: bool, grouped: bool) -> RawInput {
    let mut rng = common::Rng((seed) | 1);
    let mut rows: Vec<Vec<u32>> = Vec::new();
    for _ in 0..count {
        let lo = if points { 1 } else { 2 };
        let k = lo + rng.below(5 - lo);
        let mut s: Vec<u32> = Vec::new();
        while s.len() < k {
            let v = rng.below(n as usize) as u32;
            if !s.contains(&v) {
                s.push(v);
            }
        }
        rows.push(s);
        if rng.below(4) == 0 {
            let last = rows.last().unwrap().clone();
            if last.len() > 2 {
                rows.push(last[..last.len() - 1].to_vec()); // a listed face
            } else {
                rows.push(last); // a repeat
            }
        }
    }
    if grouped {
        rows.sort_by_key(Vec::len);
    }
    let mut raw = RawInput::new();
    raw.vertex_count = Some(n);
    raw.coords = Some(Coords {
        dim: 3,
        data: (0..n as usize * 3).map(|i| i as f64 * 0.25).collect(),
    });
    for r in &rows {
        raw.push(r, 0);
    }
    raw
}

/// Nonzero labels (0 is MEDIT's and Gmsh's "none", which the readers do not keep).
fn labels(rng: &mut common::Rng, len: usize) -> Vec<i32> {
    (0..len).map(|_| 1 + rng.below(7) as i32).collect()
}

/// Writes `raw` as `format`, reads it back, and checks listing, coordinates and attributes.
fn round_trip(raw: &RawInput, format: Format, dir: &Path) -> Result<(), String> {
    let path = dir.join(format!("r.{}", format.extension()));
    write_raw(raw, &path, Some(format)).map_err(|e| e.to_string())?;
    let back = read_path(&path).map_err(|e| e.to_string())?;
    if simplices(&back) != simplices(raw) {
        return Err(format!("{}: the listing changed", format.name()));
    }
    if !back.attributes.bits_eq(&raw.attributes) {
        return Err(format!(
            "{}: attributes changed:\n{:?}\nread back as\n{:?}",
            format.name(),
            raw.attributes,
            back.attributes
        ));
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(24))]

    /// MEDIT references on vertices and on listed edges, triangles and tetrahedra (faces and
    /// repeats included) come back bit for bit.
    #[test]
    fn medit_references_on_vertices_and_listed_simplices_round_trip(seed in any::<u64>(), n in 4u32..30, count in 1usize..40) {
        let mut raw = random_listing(seed, n, count, false, true);
        let mut rng = common::Rng((seed ^ 1) | 1);
        let m = raw.simplex_count();
        raw.attributes.insert(Attribute::labels("medit:ref", Location::Vertices, labels(&mut rng, n as usize)));
        raw.attributes.insert(Attribute::labels("medit:ref", Location::Listed, labels(&mut rng, m)));
        let dir = Scratch::new("medit");
        prop_assert_eq!(round_trip(&raw, Format::Medit, &dir.0), Ok(()));
    }

    /// Gmsh physical and elementary tags, with physical group names, come back bit for bit in
    /// MSH 4.1 and 2.2, ASCII and binary (physical tags constant per entity, as 4.1 keeps them).
    #[test]
    fn gmsh_physical_and_elementary_tags_round_trip(seed in any::<u64>(), n in 4u32..30, count in 1usize..40) {
        let mut raw = random_listing(seed, n, count, true, false);
        let mut rng = common::Rng((seed ^ 2) | 1);
        let m = raw.simplex_count();
        let geometrical: Vec<i32> = labels(&mut rng, m).iter().map(|g| g + 1).collect();
        let physical: Vec<i32> = (0..m)
            .map(|i| (raw.simplex(i).len() as i32) * 10 + geometrical[i] % 3)
            .collect();
        raw.attributes.insert(Attribute::labels("gmsh:geometrical", Location::Listed, geometrical));
        raw.attributes.insert(Attribute::labels("gmsh:physical", Location::Listed, physical.clone()));
        raw.attributes.add_label_name(LabelName {
            attribute: "gmsh:physical".into(),
            dimension: Some(raw.simplex(0).len() as u8 - 1),
            label: i64::from(physical[0]),
            name: "first group".into(),
        });
        let dir = Scratch::new("msh");
        for f in [Format::Msh, Format::MshBinary, Format::Msh2, Format::Msh2Binary] {
            prop_assert_eq!(round_trip(&raw, f, &dir.0), Ok(()));
        }
    }

    /// Gmsh `$NodeData`/`$ElementData`: `f64` fields of 1 to 9 components on the vertices and
    /// the listed elements, several time steps of one name (`NAME@STEP`) among them, beside
    /// physical tags, come back bit for bit in MSH 4.1 and 2.2, ASCII and binary (NaN,
    /// infinities and subnormals included).
    #[test]
    fn gmsh_node_and_element_data_with_time_steps_round_trip(seed in any::<u64>(), n in 4u32..30, count in 1usize..40) {
        let mut raw = random_listing(seed, n, count, true, false);
        let mut rng = common::Rng((seed ^ 4) | 1);
        let m = raw.simplex_count();
        let specials = [f64::NAN, f64::NEG_INFINITY, -0.0, 5e-324, 1e300, -1.5];
        let real = |rng: &mut common::Rng, i: usize| {
            if rng.below(5) == 0 { specials[i % specials.len()] } else { rng.next() as f64 / 7.0 - 1e9 }
        };
        for location in [Location::Vertices, Location::Listed] {
            let count = if location == Location::Vertices { n as usize } else { m };
            let steps = rng.below(4);
            let mut names: Vec<String> = (0..steps).map(|s| format!("u@{}", s * 3)).collect();
            if steps == 1 {
                names[0] = "u".into();
            }
            names.push("velocity field".into());
            for name in names {
                let c = 1 + rng.below(9);
                let values = (0..count * c).map(|i| real(&mut rng, i)).collect();
                raw.attributes.insert(Attribute { name, location, components: c, values: Values::F64(values) });
            }
        }
        raw.attributes.insert(Attribute::labels("gmsh:physical", Location::Listed, labels(&mut rng, m)));
        raw.attributes.check(n as usize, m).unwrap();
        let dir = Scratch::new("msh-data");
        for f in [Format::Msh2, Format::Msh2Binary] {
            prop_assert_eq!(round_trip(&raw, f, &dir.0), Ok(()));
        }
        // MSH 4.1 keeps physical tags per entity: without them, every field comes back.
        raw.attributes.remove("gmsh:physical");
        for f in [Format::Msh, Format::MshBinary] {
            prop_assert_eq!(round_trip(&raw, f, &dir.0), Ok(()));
        }
    }

    /// Point and cell data of every type and 1 to 9 components come back bit for bit through
    /// legacy VTK, ASCII and binary, and VTU (NaN, infinities and subnormals included).
    #[test]
    fn vtk_and_vtu_point_and_cell_data_of_every_type_round_trip(seed in any::<u64>(), n in 4u32..30, count in 1usize..40) {
        let mut raw = random_listing(seed, n, count, true, false);
        let mut rng = common::Rng((seed ^ 3) | 1);
        let m = raw.simplex_count();
        let specials = [f64::NAN, f64::INFINITY, -0.0, 5e-324, 1e300, -1.5];
        for (k, location) in [Location::Vertices, Location::Listed].into_iter().enumerate() {
            let count = if location == Location::Vertices { n as usize } else { m };
            let c = 1 + rng.below(9);
            let reals: Vec<f64> = (0..count * c)
                .map(|i| if rng.below(5) == 0 { specials[i % specials.len()] } else { rng.next() as f64 / 7.0 })
                .collect();
            raw.attributes.insert(Attribute { name: format!("f64_{k}"), location, components: c, values: Values::F64(reals.clone()) });
            raw.attributes.insert(Attribute { name: format!("f32_{k}"), location, components: 1 + rng.below(9), values: Values::F32(vec![]) });
            let a = raw.attributes.get(&format!("f32_{k}"), location).unwrap().components;
            raw.attributes.insert(Attribute { name: format!("f32_{k}"), location, components: a, values: Values::F32((0..count * a).map(|i| reals[i % reals.len()] as f32).collect()) });
            raw.attributes.insert(Attribute { name: format!("i64_{k}"), location, components: 2, values: Values::I64((0..count * 2).map(|_| rng.next() as i64).collect()) });
            raw.attributes.insert(Attribute { name: format!("i32_{k}"), location, components: 1, values: Values::I32((0..count).map(|_| rng.next() as i32).collect()) });
        }
        raw.attributes.check(n as usize, m).unwrap();
        let dir = Scratch::new("vtk");
        for f in [Format::Vtk, Format::VtkBinary, Format::Vtu] {
            prop_assert_eq!(round_trip(&raw, f, &dir.0), Ok(()));
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(24))]

    /// Vertex and listed properties of every type PLY holds (`int`, `uint`, `float`,
    /// `double`) on a random listing of edges and triangles (listed faces and repeats included,
    /// in any order) come back bit for bit in ASCII and binary PLY: the writer lays out
    /// triangles then edges, each value beside its simplex, so the data read back is the
    /// original's permuted the same way as the listing.
    #[test]
    fn ply_vertex_and_face_properties_of_every_type_round_trip(seed in any::<u64>(), n in 4u32..30, count in 1usize..40) {
        let rows = random_listing(seed, n, count, false, false);
        // PLY lists triangles and edges: keep those.
        let mut raw = up_to_triangles(&rows);
        let mut rng = common::Rng((seed ^ 5) | 1);
        let m = raw.simplex_count();
        for (k, location) in [Location::Vertices, Location::Listed].into_iter().enumerate() {
            let len = if location == Location::Vertices { n as usize } else { m };
            let mut add = |name: &str, values: Values| {
                raw.attributes.insert(Attribute { name: format!("{name}_{k}"), location, components: 1, values });
            };
            add("int", Values::I32((0..len).map(|_| rng.next() as i32).collect()));
            add("uint", Values::I64((0..len).map(|_| i64::from(rng.next() as u32)).collect()));
            add("float", Values::F32((0..len).map(|_| f32::from_bits(rng.next() as u32 & 0x7f7f_ffff) * if rng.below(2) == 0 { -1.0 } else { 1.0 }).collect()));
            add("double", Values::F64((0..len).map(|_| f64::from_bits(rng.next() & 0x7fef_ffff_ffff_ffff)).collect()));
        }
        raw.attributes.check(n as usize, m).unwrap();
        // What the file lists: triangles, then edges, each in listing order.
        let order: Vec<usize> = (0..m).filter(|&i| raw.simplex(i).len() == 3)
            .chain((0..m).filter(|&i| raw.simplex(i).len() == 2)).collect();
        let mut want = RawInput::new();
        for &i in &order {
            want.push(raw.simplex(i), 0);
        }
        want.attributes = raw.attributes.pick(0..n as usize, order.iter().copied());
        let dir = Scratch::new("ply");
        for f in [Format::Ply, Format::PlyBinary] {
            let path = dir.0.join("r.ply");
            write_raw(&raw, &path, Some(f)).unwrap();
            let back = read_path(&path).unwrap();
            prop_assert_eq!(simplices(&back), simplices(&want));
            prop_assert!(back.attributes.bits_eq(&want.attributes), "{}: {:?}\nread back as\n{:?}", f.name(), want.attributes, back.attributes);
        }
    }
}

/// What PLY cannot hold is refused naming the attribute, and nothing is written: several
/// components, a name that is no PLY property name or is a coordinate's, an `i64` beyond
/// `uint`, listed data beside a listed vertex, a non-finite real in ASCII (binary keeps it).
#[test]
fn ply_refuses_data_it_cannot_hold() {
    let mut base = RawInput::new();
    base.vertex_count = Some(3);
    base.push(&[0, 1, 2], 0);
    let dir = Scratch::new("ply-refuse");
    let path = dir.0.join("x.ply");
    let vertices = |name: &str, components: usize, values: Values| {
        let mut raw = base.clone();
        raw.attributes.insert(Attribute {
            name: name.into(),
            location: Location::Vertices,
            components,
            values,
        });
        raw
    };
    let mut point = base.clone();
    point.push(&[1], 0);
    point
        .attributes
        .insert(Attribute::labels("region", Location::Listed, vec![1, 2]));
    let cases = [
        (
            vertices("normal", 3, Values::F32(vec![0.0; 9])),
            Format::PlyBinary,
            "'normal'",
        ),
        (
            vertices("two words", 1, Values::I32(vec![0; 3])),
            Format::Ply,
            "'two words'",
        ),
        (
            vertices("x", 1, Values::I32(vec![0; 3])),
            Format::Ply,
            "'x'",
        ),
        (
            vertices("big", 1, Values::I64(vec![0, 1, 1 << 32])),
            Format::PlyBinary,
            "'big'",
        ),
        (point, Format::PlyBinary, "simplex #1 [1] is a vertex"),
        (
            vertices("q", 1, Values::F64(vec![0.0, f64::NAN, 1.0])),
            Format::Ply,
            "non-finite value at element 1",
        ),
    ];
    for (raw, f, says) in cases {
        let e = write_raw(&raw, &path, Some(f)).unwrap_err().to_string();
        assert!(e.contains(says), "{e}");
        assert!(!path.exists(), "{e}: a file was written");
    }
    // Binary PLY keeps the NaN, bit for bit.
    let raw = vertices("q", 1, Values::F64(vec![0.0, f64::NAN, 1.0]));
    write_raw(&raw, &path, Some(Format::PlyBinary)).unwrap();
    assert!(
        read_path(&path)
            .unwrap()
            .attributes
            .bits_eq(&raw.attributes)
    );
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(24))]

    /// OFF vertex normals, colours and texture coordinates, and face colours of 1, 3 or 4
    /// numbers (NaN, infinities and subnormals included) on random listings of points, edges
    /// and triangles come back bit for bit.
    #[test]
    fn off_vertex_and_face_colours_round_trip(seed in any::<u64>(), n in 4u32..30, count in 1usize..40) {
        let rows = random_listing(seed, n, count, true, false);
        let mut raw = up_to_triangles(&rows);
        let m = raw.simplex_count();
        let mut rng = common::Rng((seed ^ 11) | 1);
        let specials = [f64::NAN, f64::INFINITY, -0.0, 5e-324, 255.0, 0.5];
        let mut reals = |len: usize| -> Values {
            Values::F64((0..len).map(|i| if rng.below(4) == 0 { specials[i % specials.len()] } else { rng.next() as f64 / 3.0 }).collect())
        };
        for (name, c) in [("off:normal", 3), ("off:color", 4), ("off:texture", 2)] {
            if seed % 3 != 0 || name == "off:color" {
                let values = reals(n as usize * c);
                raw.attributes.insert(Attribute { name: name.into(), location: Location::Vertices, components: c, values });
            }
        }
        if m > 0 {
            let c = [1, 3, 4][(seed % 3) as usize];
            let values = reals(m * c);
            raw.attributes.insert(Attribute { name: "off:color".into(), location: Location::Listed, components: c, values });
        }
        raw.attributes.check(n as usize, m).unwrap();
        let dir = Scratch::new("off");
        prop_assert_eq!(round_trip(&raw, Format::Off, &dir.0), Ok(()));
    }
}

/// Random runs of labels for `len` listed simplices, numbered in order of first appearance
/// (OBJ's numbering), -1 for a leading run when `lead`; the labels used.
fn runs(rng: &mut common::Rng, len: usize, lead: bool) -> (Vec<i32>, i32) {
    let mut out = Vec::with_capacity(len);
    let mut used = 0i32;
    let mut current = if lead { -1 } else { 0 };
    used += i32::from(!lead);
    for i in 0..len {
        // Without a leading run, label 0 comes first.
        if (lead || i > 0) && rng.below(3) == 0 {
            let pick = rng.below(used as usize + 1) as i32;
            current = pick;
            if pick == used {
                used += 1;
            }
        }
        out.push(current);
    }
    (out, used)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(24))]

    /// OBJ objects, groups (names of several words included), materials and smoothing groups
    /// on random listings of points, edges and triangles come back bit for bit, names included.
    #[test]
    fn obj_groups_objects_materials_and_smoothing_round_trip(seed in any::<u64>(), n in 4u32..30, count in 1usize..40) {
        let rows = random_listing(seed, n, count, true, false);
        let mut raw = up_to_triangles(&rows);
        let m = raw.simplex_count();
        let mut rng = common::Rng((seed ^ 7) | 1);
        for (k, attr) in ["obj:object", "obj:group", "obj:material"].into_iter().enumerate() {
            let lead = rng.below(2) == 0;
            let (labels, used) = runs(&mut rng, m, lead);
            if used == 0 {
                continue;
            }
            raw.attributes.insert(Attribute::labels(attr, Location::Listed, labels));
            for label in 0..used {
                raw.attributes.add_label_name(LabelName {
                    attribute: attr.into(),
                    dimension: None,
                    label: i64::from(label),
                    name: if k == 1 && label % 2 == 1 { format!("part {label} of {k}") } else { format!("{attr}-{label}") },
                });
            }
        }
        let smooth: Vec<i32> = runs(&mut rng, m, false).0.into_iter().map(|x| x * 3).collect();
        raw.attributes.insert(Attribute::labels("obj:smoothing", Location::Listed, smooth));
        raw.attributes.check(n as usize, m).unwrap();
        let dir = Scratch::new("obj");
        prop_assert_eq!(round_trip(&raw, Format::Obj, &dir.0), Ok(()));
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(24))]

    /// ASCII STL solids: triangles (a chain covering every vertex, then random ones, repeats
    /// included) labelled by runs of named solids, one run or many, come back bit for bit.
    #[test]
    fn stl_solid_names_round_trip(seed in any::<u64>(), n in 4u32..30, count in 0usize..30) {
        let base = random_listing(seed, n, 1, false, false);
        let mut raw = RawInput::new();
        raw.vertex_count = base.vertex_count;
        raw.coords = base.coords;
        let mut rng = common::Rng((seed ^ 13) | 1);
        for v in 0..n - 2 {
            raw.push(&[v, v + 1, v + 2], 0);
        }
        for _ in 0..count {
            let a = rng.below(n as usize - 2) as u32;
            raw.push(&[a, a + 1 + rng.below((n - a - 2) as usize) as u32, n - 1], 0);
        }
        let m = raw.simplex_count();
        let (labels, used) = runs(&mut rng, m, false);
        raw.attributes.insert(Attribute::labels("stl:solid", Location::Listed, labels));
        for label in 0..used {
            raw.attributes.add_label_name(LabelName {
                attribute: "stl:solid".into(),
                dimension: None,
                label: i64::from(label),
                name: format!("part {label}"),
            });
        }
        raw.attributes.check(n as usize, m).unwrap();
        let dir = Scratch::new("stl");
        prop_assert_eq!(round_trip(&raw, Format::Stl, &dir.0), Ok(()));
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(24))]

    /// `.simplices` labels (`s ... : L`, any `i64`) on random listings of every dimension come
    /// back bit for bit.
    #[test]
    fn simplices_labels_round_trip(seed in any::<u64>(), n in 4u32..30, count in 1usize..40) {
        let mut raw = random_listing(seed, n, count, true, false);
        let mut rng = common::Rng((seed ^ 17) | 1);
        let m = raw.simplex_count();
        let values = (0..m).map(|i| if i % 5 == 4 { i64::MIN } else { rng.next() as i64 }).collect();
        raw.attributes.insert(Attribute { name: "simplices:label".into(), location: Location::Listed, components: 1, values: Values::I64(values) });
        let dir = Scratch::new("simplices");
        prop_assert_eq!(round_trip(&raw, Format::Simplices, &dir.0), Ok(()));
    }
}

/// STL solids that cannot be written are refused naming the attribute: in binary STL, a label
/// without a name, a name with a newline.
#[test]
fn stl_refuses_solid_labels_it_cannot_write() {
    let mut raw = RawInput::new();
    raw.vertex_count = Some(3);
    raw.coords = Some(Coords {
        dim: 3,
        data: vec![0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0],
    });
    raw.push(&[0, 1, 2], 0);
    raw.attributes
        .insert(Attribute::labels("stl:solid", Location::Listed, vec![0]));
    let dir = Scratch::new("stl-refuse");
    let path = dir.0.join("s.stl");
    let e = write_raw(&raw, &path, Some(Format::Stl))
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("'stl:solid'") && e.contains("label 0, which has no name"),
        "{e}"
    );
    raw.attributes.add_label_name(LabelName {
        attribute: "stl:solid".into(),
        dimension: None,
        label: 0,
        name: "two\nlines".into(),
    });
    let e = write_raw(&raw, &path, Some(Format::Stl))
        .unwrap_err()
        .to_string();
    assert!(e.contains("would not read back as itself"), "{e}");
    let e = write_raw(&raw, &path, Some(Format::StlBinary))
        .unwrap_err()
        .to_string();
    assert!(e.contains("'stl:solid'") && e.contains(" .stl,"), "{e}");
    assert!(!path.exists());
}

/// OBJ labels numbered otherwise than by first appearance read back renumbered, each simplex
/// keeping its name; labels OBJ cannot write are refused naming the attribute and simplex.
#[test]
fn obj_labels_keep_their_names_and_unwritable_ones_are_refused() {
    let mut raw = RawInput::new();
    raw.vertex_count = Some(3);
    for s in [[0u32, 1, 2], [0, 1, 2], [0, 1, 2]] {
        raw.push(&s, 0);
    }
    let named = |labels: Vec<i32>, names: &[(i64, &str)]| {
        let mut r = raw.clone();
        r.attributes
            .insert(Attribute::labels("obj:group", Location::Listed, labels));
        for &(label, name) in names {
            r.attributes.add_label_name(LabelName {
                attribute: "obj:group".into(),
                dimension: None,
                label,
                name: name.into(),
            });
        }
        r
    };
    let dir = Scratch::new("obj-names");
    let path = dir.0.join("g.obj");
    let r = named(vec![7, 3, 7], &[(3, "three"), (7, "seven")]);
    write_raw(&r, &path, Some(Format::Obj)).unwrap();
    let back = read_path(&path).unwrap();
    let names = |r: &RawInput| -> Vec<String> {
        let a = r.attributes.get("obj:group", Location::Listed).unwrap();
        (0..3)
            .map(|i| {
                r.attributes
                    .label_name("obj:group", 2, a.label(i).unwrap())
                    .unwrap()
                    .to_string()
            })
            .collect()
    };
    assert_eq!(names(&back), ["seven", "three", "seven"]);
    assert_eq!(names(&back), names(&r));
    for (r, says) in [
        (
            named(vec![0, 1, 0], &[(0, "a")]),
            "simplex #1 has label 1, which has no name",
        ),
        (
            named(vec![0, -1, 0], &[(0, "a")]),
            "simplex #1 has label -1",
        ),
        (named(vec![0, 0, 0], &[(0, "a # b")]), "named 'a # b'"),
        (named(vec![0, 0, 0], &[(0, " a")]), "named ' a'"),
    ] {
        let e = write_raw(&r, &path, Some(Format::Obj))
            .unwrap_err()
            .to_string();
        assert!(e.contains("'obj:group'") && e.contains(says), "{e}");
    }
    let mut r = raw.clone();
    r.attributes.insert(Attribute::labels(
        "obj:smoothing",
        Location::Listed,
        vec![1, -2, 1],
    ));
    let e = write_raw(&r, &path, Some(Format::Obj))
        .unwrap_err()
        .to_string();
    assert!(e.contains("simplex #1 has label -2"), "{e}");
}

/// A random real for OBJ data: a few decimals, negative or not.
fn real(rng: &mut common::Rng) -> f64 {
    (rng.below(2001) as f64 - 1000.0) / 64.0
}

/// OBJ's vertex data on a random listing of points, edges and triangles: colours (3 or 4
/// numbers), `obj:vt` and `obj:vn` as vertex fields (NaN on the vertices no element can refer
/// them from) or per corner (values differing at a vertex), written and read back bit for bit.
#[test]
fn obj_colours_textures_and_normals_round_trip_per_vertex_and_per_corner() {
    let dir = Scratch::new("obj-data");
    let mut per_corner = 0;
    for seed in 1..=60u64 {
        let mut rng = common::Rng((seed * 0x9e37_79b9) | 1);
        let n = 4 + rng.below(12) as u32;
        let mut raw = up_to_triangles(&random_listing(seed, n, 1 + rng.below(12), true, false));
        let m = raw.simplex_count();
        let nv = n as usize;
        let w = 3 + rng.below(2);
        let colours: Vec<f64> = (0..nv * w).map(|_| rng.below(256) as f64 / 255.0).collect();
        raw.attributes.insert(Attribute {
            name: "obj:color".into(),
            location: Location::Vertices,
            components: w,
            values: Values::F64(colours),
        });
        for (name, width, takes) in [
            ("obj:vt", 1 + rng.below(3), &[2usize, 3][..]),
            ("obj:vn", 3, &[3][..]),
        ] {
            let takes = |i: usize| takes.contains(&raw.simplex(i).len());
            if rng.below(2) == 0 {
                // A vertex field: a value wherever an element can refer to it.
                let referred: Vec<bool> = (0..nv)
                    .map(|v| (0..m).any(|i| takes(i) && raw.simplex(i).contains(&(v as u32))))
                    .collect();
                let values = (0..nv * width)
                    .map(|k| {
                        if referred[k / width] {
                            real(&mut rng)
                        } else {
                            f64::NAN
                        }
                    })
                    .collect();
                raw.attributes.insert(Attribute {
                    name: name.into(),
                    location: Location::Vertices,
                    components: width,
                    values: Values::F64(values),
                });
            } else {
                // Per corner, kept only where a vertex is at two valued corners (else it reads
                // back, rightly, as a vertex field).
                let mut values = vec![f64::NAN; m * 3 * width];
                let mut seen = std::collections::HashSet::new();
                let mut twice = false;
                for i in (0..m).filter(|&i| takes(i)) {
                    for (c, &v) in raw.simplex(i).iter().enumerate() {
                        twice |= !seen.insert(v);
                        for k in 0..width {
                            values[(i * 3 + c) * width + k] = real(&mut rng);
                        }
                    }
                }
                if twice {
                    per_corner += 1;
                    raw.attributes.insert(Attribute {
                        name: name.into(),
                        location: Location::Listed,
                        components: 3 * width,
                        values: Values::F64(values),
                    });
                }
            }
        }
        round_trip(&raw, Format::Obj, &dir.0).unwrap_or_else(|e| panic!("seed {seed}: {e}"));
    }
    assert!(per_corner > 10, "{per_corner}");
}

/// What OBJ cannot tie back is refused: a vertex value on a vertex no element refers to, a
/// normal at an edge's corner, a point's corner value.
#[test]
fn obj_refuses_vertex_data_no_reference_would_tie_back() {
    let mut raw = RawInput::new();
    raw.vertex_count = Some(4);
    raw.push(&[0, 1, 2], 0);
    raw.push(&[2, 3], 0);
    raw.push(&[3], 0);
    let dir = Scratch::new("obj-refused");
    let path = dir.0.join("r.obj");
    let refused = |a: Attribute, says: &str| {
        let mut r = raw.clone();
        r.attributes.insert(a);
        let e = write_raw(&r, &path, Some(Format::Obj))
            .unwrap_err()
            .to_string();
        assert!(e.contains(says), "{e}");
        assert!(!path.exists());
    };
    let f64s = |name: &str, location, components, values: Vec<f64>| Attribute {
        name: name.into(),
        location,
        components,
        values: Values::F64(values),
    };
    refused(
        f64s("obj:vn", Location::Vertices, 3, vec![1.0; 12]),
        "vertex 3 has a value but no triangle lists it",
    );
    let mut corners = vec![f64::NAN; 27];
    corners[9..12].copy_from_slice(&[0., 0., 1.]);
    refused(
        f64s("obj:vn", Location::Listed, 9, corners),
        "simplex #1 [2 3] has a value at corner 0",
    );
    let mut corners = vec![f64::NAN; 9];
    corners[6] = 0.5;
    refused(
        f64s("obj:vt", Location::Listed, 3, corners),
        "simplex #2 [3] has a value at corner 0",
    );
    // An edge refers to its texture coordinates: vertex 3 is tied back through [2 3].
    let mut r = raw.clone();
    r.attributes
        .insert(f64s("obj:vt", Location::Vertices, 1, vec![0., 1., 2., 3.]));
    round_trip(&r, Format::Obj, &dir.0).unwrap();
}

/// Blender's flat-shaded tetrahedron (`../shared/data/nonmanifold/tet.obj`, `f a//n`): each
/// face's normal at its three corners, per corner since every vertex gets three normals; written
/// and read back bit for bit; the OFF writer refuses it by name.
#[test]
fn obj_flat_normals_of_real_data_are_kept_per_corner() {
    let Some(path) = common::shared_data().map(|d| d.join("nonmanifold/tet.obj")) else {
        eprintln!("../shared/data is absent: skipping tet.obj");
        return;
    };
    let raw = read_path(&path).unwrap();
    let text = std::fs::read_to_string(&path).unwrap();
    let normals: Vec<Vec<f64>> = text
        .lines()
        .filter_map(|l| l.strip_prefix("vn "))
        .map(|l| l.split_whitespace().map(|x| x.parse().unwrap()).collect())
        .collect();
    let a = raw.attributes.get("obj:vn", Location::Listed).unwrap();
    assert_eq!(a.components, 9);
    // Face f refers to normal f at every corner (the file's own `f a//f` lines).
    assert_eq!(raw.simplex_count(), normals.len());
    for (f, normal) in normals.iter().enumerate() {
        let e = a.element(f).unwrap();
        for c in 0..3 {
            assert_eq!(e[c * 3..c * 3 + 3], normal[..], "face {f} corner {c}");
        }
    }
    let dir = Scratch::new("obj-tet");
    round_trip(&raw, Format::Obj, &dir.0).unwrap();
    // The grouping labels, which OFF does not hold either, aside: the normals are refused.
    let mut normals_only = raw.clone();
    normals_only.attributes.remove_label_names();
    for name in ["obj:object", "obj:group", "obj:material", "obj:smoothing"] {
        normals_only.attributes.remove(name);
    }
    let e = write_raw(&normals_only, &dir.0.join("t.off"), Some(Format::Off))
        .unwrap_err()
        .to_string();
    assert!(e.contains("'obj:vn'") && e.contains("write .obj"), "{e}");
}

/// NaNs in data: the text formats hold a NaN but neither its sign nor its payload (it reads
/// back as a NaN, every other number bit for bit); binary legacy VTK, VTU and binary MSH keep
/// every bit. Hand-written `nan`, `-nan`, `NaN` and infinities read as such.
#[test]
fn nan_values_read_back_as_nan_in_text_and_bit_for_bit_in_binary() {
    let mut raw = RawInput::new();
    raw.vertex_count = Some(3);
    raw.coords = Some(Coords {
        dim: 3,
        data: vec![0., 0., 0., 1., 0., 0., 0., 1., 0.],
    });
    raw.push(&[0, 1, 2], 0);
    let nans64 = [
        f64::NAN,
        -f64::NAN,
        f64::from_bits(0x7ff0_0000_0000_0001), // signalling, payload 1
    ];
    let nans32 = [f32::NAN, -f32::NAN, f32::from_bits(0x7fc0_1234)];
    raw.attributes.insert(Attribute {
        name: "w".into(),
        location: Location::Vertices,
        components: 1,
        values: Values::F64(nans64.to_vec()),
    });
    raw.attributes.insert(Attribute {
        name: "v".into(),
        location: Location::Vertices,
        components: 1,
        values: Values::F32(nans32.to_vec()),
    });
    raw.attributes.insert(Attribute {
        name: "c".into(),
        location: Location::Listed,
        components: 3,
        values: Values::F64(vec![f64::NAN, 1.5, -f64::NAN]),
    });
    let dir = Scratch::new("nan");
    for f in [Format::VtkBinary, Format::Vtu] {
        round_trip(&raw, f, &dir.0).unwrap();
    }
    let mut only64 = raw.clone();
    only64.attributes.remove("v");
    for f in [Format::MshBinary, Format::Msh2Binary] {
        round_trip(&only64, f, &dir.0).unwrap();
    }
    // Text: NaN stays NaN, the rest bit for bit.
    let nan_or_same = |a: &Values, b: &Values| {
        a.len() == b.len()
            && (0..a.len()).all(|i| {
                let (x, y) = (a.real(i).unwrap(), b.real(i).unwrap());
                if x.is_nan() {
                    y.is_nan()
                } else {
                    x.to_bits() == y.to_bits()
                }
            })
    };
    for (f, r) in [
        (Format::Vtk, &raw),
        (Format::Msh, &only64),
        (Format::Msh2, &only64),
    ] {
        let path = dir.0.join(format!("t.{}", f.extension()));
        write_raw(r, &path, Some(f)).unwrap();
        let back = read_path(&path).unwrap();
        for a in r.attributes.iter() {
            let b = back.attributes.get(&a.name, a.location).unwrap();
            assert_eq!(b.values.value_type(), a.values.value_type(), "{}", a.name);
            assert!(
                nan_or_same(&a.values, &b.values),
                "{}: {a:?} read back as {b:?}",
                f.name()
            );
        }
    }
    let path = dir.0.join("hand.vtk");
    std::fs::write(
        &path,
        "# vtk DataFile Version 4.2\nt\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 5 double\n\
         0 0 0 1 0 0 0 1 0 1 1 0 2 2 0\nCELLS 1 4\n3 0 1 2\nCELL_TYPES 1\n5\n\
         POINT_DATA 5\nSCALARS s double 1\nLOOKUP_TABLE default\nnan -nan NaN inf -inf\n",
    )
    .unwrap();
    let back = read_path(&path).unwrap();
    let s = &back.attributes.get("s", Location::Vertices).unwrap().values;
    assert!((0..3).all(|i| s.real(i).unwrap().is_nan()), "{s:?}");
    assert_eq!(s.real(3), Some(f64::INFINITY));
    assert_eq!(s.real(4), Some(f64::NEG_INFINITY));
}

/// The same data as an ASCII `.vtu` written by hand (our streaming reader) and as the base64
/// `.vtu` our writer makes of it (the vtkio path) reads alike, bit for bit; a name no VTU holds
/// (a control character) is refused by the writer.
#[test]
fn vtu_ascii_and_base64_paths_read_the_same_data() {
    let array = |ty: &str, name: &str, comps: usize, body: &str| {
        format!(
            "<DataArray type=\"{ty}\" Name=\"{name}\" NumberOfComponents=\"{comps}\" \
             format=\"ascii\">{body}</DataArray>\n"
        )
    };
    let text = format!(
        "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"1.0\">\n\
         <UnstructuredGrid>\n<Piece NumberOfPoints=\"4\" NumberOfCells=\"2\">\n<PointData>\n{}{}\
         </PointData>\n<Points>\n{}</Points>\n<Cells>\n{}{}{}</Cells>\n<CellData>\n{}{}\
         </CellData>\n</Piece>\n</UnstructuredGrid>\n</VTKFile>\n",
        array("Float64", "temperature &lt;K&gt;", 1, "1e-310 -0 NaN -inf"),
        array("Int8", "flag", 3, "-128 0 127 1 2 3 4 5 6 7 8 9"),
        array("Float64", "", 3, "0 0 0 1 0 0 0 1 0 1 1 1"),
        array("Int64", "connectivity", 1, "0 1 2 1 3"),
        array("Int64", "offsets", 1, "3 5"),
        array("UInt8", "types", 1, "5 3"),
        array("UInt32", "region", 1, "4294967295 0"),
        array("Float32", "stress", 9, &"0.1 3.4028235e38 1e-45 ".repeat(6)),
    );
    let dir = Scratch::new("vtu-paths");
    let hand = dir.0.join("hand.vtu");
    std::fs::write(&hand, &text).unwrap();
    let ours = read_path(&hand).unwrap();
    assert_eq!(ours.attributes.iter().count(), 4);
    let t = ours
        .attributes
        .get("temperature <K>", Location::Vertices)
        .unwrap();
    let Values::F64(v) = &t.values else {
        panic!("{t:?}")
    };
    assert_eq!(v[0].to_bits(), 1e-310f64.to_bits());
    assert_eq!(v[1].to_bits(), (-0.0f64).to_bits());
    assert!(v[2].is_nan() && v[3] == f64::NEG_INFINITY);
    assert_eq!(
        ours.attributes
            .get("region", Location::Listed)
            .unwrap()
            .values,
        Values::I64(vec![4294967295, 0])
    );
    // Any name without control characters is held, XML's special characters included.
    let mut ours = ours;
    ours.attributes.insert(Attribute::labels(
        "q\"u'o<t>&e ü",
        Location::Listed,
        vec![-1, 1],
    ));
    let written = dir.0.join("base64.vtu");
    write_raw(&ours, &written, None).unwrap();
    let bytes = std::fs::read(&written).unwrap();
    let body = String::from_utf8_lossy(&bytes);
    assert!(!body.contains("format=\"ascii\"") && body.contains("format=\"binary\""));
    let theirs = read_path(&written).unwrap();
    assert_eq!(simplices(&theirs), simplices(&ours));
    assert!(theirs.attributes.bits_eq(&ours.attributes));
    let mut bad = ours.clone();
    bad.attributes
        .insert(Attribute::labels("tab\there", Location::Listed, vec![1, 2]));
    let e = write_raw(&bad, &dir.0.join("bad.vtu"), None)
        .unwrap_err()
        .to_string();
    assert!(e.contains("'tab\\there'") || e.contains("tab"), "{e}");
    assert!(!dir.0.join("bad.vtu").exists());
}

/// Every format that does not hold an attribute refuses it, naming it and a format that does,
/// and writes nothing; dropped explicitly, the rest is written.
#[test]
fn formats_that_cannot_hold_an_attribute_refuse_it_and_write_nothing() {
    let mut raw = random_listing(7, 6, 5, false, true);
    raw.attributes.insert(Attribute::labels(
        "medit:ref",
        Location::Vertices,
        vec![1; 6],
    ));
    let dir = Scratch::new("refuse");
    for f in Format::ALL {
        let path = dir.0.join(format!("x.{}", f.extension()));
        let r = write_raw(&raw, &path, Some(f));
        if f.holds(raw.attributes.iter().next().unwrap()) {
            continue;
        }
        let e = r.expect_err(f.name()).to_string();
        assert!(
            e.contains("'medit:ref'") && e.contains(".mesh"),
            "{}: {e}",
            f.name()
        );
        assert!(!path.exists(), "{}: a file was written", f.name());
    }
}

/// A boundary triangle listed with a reference beside its tetrahedron keeps it: reachable by
/// its vertices (in any order), written back with the tetrahedron; a face never listed has no
/// listing.
#[test]
fn a_listed_boundary_triangle_keeps_its_reference_beside_its_tetrahedron() {
    let text = "MeshVersionFormatted 2\nDimension 3\nVertices\n4\n0 0 0 0\n1 0 0 0\n0 1 0 0\n\
                0 0 1 0\nTriangles\n1\n1 2 3 7\nTetrahedra\n1\n1 2 3 4 9\nEnd\n";
    let dir = Scratch::new("face");
    let path = dir.0.join("t.mesh");
    std::fs::write(&path, text).unwrap();
    let c = Complex::from_path(&path).unwrap();
    assert_eq!(c.top_counts(), vec![0, 0, 0, 1]);
    let refs = c.attributes().get("medit:ref", Location::Listed).unwrap();
    let face = c.listed_index(&[2, 0, 1]).unwrap();
    assert_eq!(refs.label(face), Some(7));
    let tet = c.listed_index(&[3, 2, 1, 0]).unwrap();
    assert_eq!(refs.label(tet), Some(9));
    assert_eq!(c.listed_index(&[0, 1, 3]), None);
    assert!(
        c.attributes()
            .get("medit:ref", Location::Vertices)
            .is_none()
    );
    let out = dir.0.join("back.mesh");
    write_complex(&c, &out, None).unwrap();
    let back = read_path(&out).unwrap();
    assert_eq!(simplices(&back), vec![vec![0, 1, 2], vec![0, 1, 2, 3]]);
    assert!(back.attributes.bits_eq(&listing(&c).attributes));
}

/// Malformed data is an error naming the file's line and the array.
#[test]
fn malformed_data_sections_name_the_line_and_the_array() {
    let head = "# vtk DataFile Version 4.2\nt\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 3 double\n\
                0 0 0 1 0 0 0 1 0\nCELLS 1 4\n3 0 1 2\nCELL_TYPES 1\n5\n";
    let cases: [(&str, &str, u32); 5] = [
        (
            "CELL_DATA 2\nSCALARS region int 1\nLOOKUP_TABLE default\n1 2\n",
            "CELL_DATA 2 for 1 cells",
            11,
        ),
        (
            "CELL_DATA 1\nSCALARS region int 1\nLOOKUP_TABLE default\n1.5\n",
            "'1.5' is not of type int among the values of SCALARS 'region'",
            14,
        ),
        (
            "POINT_DATA 3\nSCALARS t float 1\nLOOKUP_TABLE default\n1 1e39 2\n",
            "number '1e39' is too large for a 32-bit float (among the values of SCALARS 't', \
             declared float; it would become infinite)",
            14,
        ),
        (
            "POINT_DATA 3\nSCALARS t float 1\nLOOKUP_TABLE default\n1 1e-50 2\n",
            "number '1e-50' is too small for a 32-bit float (among the values of SCALARS 't', \
             declared float; it would become 0)",
            14,
        ),
        (
            "CELL_DATA 1\nLOOKUP_TABLE lut 1\n0 0 0 1\n",
            "unsupported data section 'LOOKUP_TABLE'",
            12,
        ),
    ];
    let dir = Scratch::new("malformed");
    for (body, want, line) in cases {
        let path = dir.0.join("m.vtk");
        std::fs::write(&path, format!("{head}{body}")).unwrap();
        let e = read_path(&path).unwrap_err().to_string();
        assert!(e.contains(want), "{e}");
        assert!(e.contains(&format!(":{line}:")), "{e}");
    }
    let medit = "MeshVersionFormatted 2\nDimension 3\nVertices\n1\n0 0 0 4294967296\nEnd\n";
    let path = dir.0.join("m.mesh");
    std::fs::write(&path, medit).unwrap();
    let e = read_path(&path).unwrap_err().to_string();
    assert!(
        e.contains("does not fit in 32 bits") && e.contains(":5:"),
        "{e}"
    );
    let msh = "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$PhysicalNames\n1\n2 1 unquoted\n$EndPhysicalNames\n";
    let path = dir.0.join("m.msh");
    std::fs::write(&path, msh).unwrap();
    let e = read_path(&path).unwrap_err().to_string();
    assert!(
        e.contains("physical group (2, 1)") && e.contains(":6:"),
        "{e}"
    );
}

/// The labelled meshes: the same Gmsh mesh written by Gmsh as MSH 4.1 and 2.2 reads with the
/// same tags and names; Gmsh's MEDIT references equal its elementary tags and its VTK
/// `CellEntityIds` its physical tags, element for element; every one survives our own writers.
#[test]
fn labelled_meshes_read_alike_in_every_format_gmsh_wrote_and_survive_our_writers() {
    let Some(data) = common::shared_data().map(|d| d.join("labelled")) else {
        eprintln!("../shared/data is absent: skipping the labelled meshes");
        return;
    };
    if !data.is_dir() {
        eprintln!("../shared/data/labelled is absent: skipping");
        return;
    }
    let read = |name: &str| read_path(&data.join(name)).unwrap();
    let (v4, v2) = (read("gmsh_t15.msh"), read("gmsh_t15_v22.msh"));
    assert_eq!(simplices(&v4), simplices(&v2));
    assert!(v4.attributes.bits_eq(&v2.attributes));
    assert_eq!(v4.attributes.label_names().len(), 5);
    let listed = |r: &RawInput, name: &str| {
        r.attributes
            .get(name, Location::Listed)
            .unwrap()
            .values
            .clone()
    };
    let (msh, mesh) = (read("gmsh_t16.msh"), read("gmsh_t16.mesh"));
    assert_eq!(msh.simplex_count(), mesh.simplex_count());
    let by_dim = |r: &RawInput, name: &str| {
        let v = listed(r, name);
        let mut rows: Vec<(usize, i64)> = (0..r.simplex_count())
            .map(|i| (r.simplex(i).len(), v.integer(i).unwrap()))
            .collect();
        rows.sort_by_key(|x| x.0);
        rows
    };
    assert_eq!(by_dim(&msh, "gmsh:geometrical"), by_dim(&mesh, "medit:ref"));
    let (t2, t2vtk) = (read("gmsh_t2.msh"), read("gmsh_t2.vtk"));
    assert_eq!(simplices(&t2), simplices(&t2vtk));
    assert!(listed(&t2, "gmsh:physical").bits_eq(&listed(&t2vtk, "CellEntityIds")));
    let dir = Scratch::new("labelled");
    for (file, formats) in [
        (
            "gmsh_t2.msh",
            &[
                Format::Msh,
                Format::MshBinary,
                Format::Msh2,
                Format::Msh2Binary,
            ][..],
        ),
        ("gmsh_t15.msh", &[Format::Msh, Format::Msh2Binary][..]),
        ("gmsh_t16.msh", &[Format::Msh, Format::Msh2][..]),
        ("gmsh_t5.msh", &[Format::MshBinary][..]),
        ("gmsh_t16.mesh", &[Format::Medit][..]),
        ("gmsh_t2.vtk", &[Format::Vtk, Format::VtkBinary][..]),
    ] {
        let c = Complex::from_path(&data.join(file)).unwrap();
        let raw = listing(&c);
        for &f in formats {
            round_trip(&raw, f, &dir.0).unwrap_or_else(|e| panic!("{file}: {e}"));
        }
    }
}

/// The CLI keeps the data it can and refuses the rest: `convert` to a format without it exits 1
/// naming the attribute, `--drop-data` drops it by name or all, naming an absent one is an
/// error, `save` and `simplify` carry it, and a verb that does not (`convert --census`)
/// refuses instead of dropping it.
#[test]
fn cli_convert_keeps_refuses_or_drops_data_on_request() {
    let dir = Scratch::new("cli");
    let input = dir.0.join("in.mesh");
    std::fs::write(
        &input,
        "MeshVersionFormatted 2\nDimension 3\nVertices\n3\n0 0 0 1\n1 0 0 2\n0 1 0 3\n\
         Triangles\n1\n1 2 3 5\nEnd\n",
    )
    .unwrap();
    let run = |args: &[&str]| {
        let o = Command::new(env!("CARGO_BIN_EXE_topoplex"))
            .args(args)
            .output()
            .unwrap();
        (
            o.status.code(),
            String::from_utf8_lossy(&o.stderr).to_string(),
        )
    };
    let p = |name: &str| dir.0.join(name).to_str().unwrap().to_string();
    let inp = input.to_str().unwrap();
    let (code, err) = run(&["convert", inp, &p("a.off")]);
    assert_eq!(code, Some(1));
    assert!(
        err.contains("'medit:ref'") && err.contains("--drop-data"),
        "{err}"
    );
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(!dir.0.join("a.off").exists());
    assert_eq!(run(&["convert", inp, &p("a.vtk")]).0, Some(0));
    let back = read_path(&dir.0.join("a.vtk")).unwrap();
    assert_eq!(listed_labels(&back.attributes, "medit:ref"), vec![5]);
    assert_eq!(
        run(&["convert", inp, &p("b.off"), "--drop-data", "medit:ref"]).0,
        Some(0)
    );
    assert_eq!(
        run(&["convert", inp, &p("c.off"), "--drop-data", "all"]).0,
        Some(0)
    );
    let (code, err) = run(&["convert", inp, &p("d.off"), "--drop-data", "nothing"]);
    assert_eq!(code, Some(1));
    assert!(
        err.contains("no such attribute") && err.contains("'medit:ref'"),
        "{err}"
    );
    // save keeps the data; --census, which writes its own fields, refuses it.
    assert_eq!(run(&["save", inp, "--out", &p("s.tpx")]).0, Some(0));
    assert_eq!(run(&["convert", &p("s.tpx"), &p("t.mesh")]).0, Some(0));
    let back = read_path(&dir.0.join("t.mesh")).unwrap();
    assert_eq!(listed_labels(&back.attributes, "medit:ref"), vec![5]);
    let (code, err) = run(&["convert", inp, &p("c.vtk"), "--census"]);
    assert_eq!(code, Some(1));
    assert!(err.contains("does not carry attributes yet"), "{err}");
    // simplify carries the data: the one triangle keeps reference 5.
    assert_eq!(
        run(&["simplify", inp, "--out", &p("s.mesh"), "--ratio", "1"]).0,
        Some(0)
    );
    let back = read_path(&dir.0.join("s.mesh")).unwrap();
    assert_eq!(listed_labels(&back.attributes, "medit:ref"), vec![5]);
}

fn listed_labels(at: &Attributes, name: &str) -> Vec<i64> {
    let a = at.get(name, Location::Listed).unwrap();
    (0..a.element_count())
        .map(|i| a.label(i).unwrap())
        .collect()
}

/// The expected labels of a live complex: each top's label by its vertex set, and the listed
/// faces' labels as a multiset of (vertex set, label) — moved by each edit as the data module
/// says, by brute force over whole sets.
#[derive(Debug, Clone, PartialEq)]
struct Labels {
    tops: std::collections::BTreeMap<Vec<u32>, i64>,
    faces: Vec<(Vec<u32>, i64)>,
    /// The vertex field: vertex → value.
    field: std::collections::BTreeMap<u32, f64>,
}

fn key(s: &[u32]) -> Vec<u32> {
    let mut v = s.to_vec();
    v.sort_unstable();
    v.dedup();
    v
}

/// What `live` says: every live top's label, every listed face's (through `to_complex`), every
/// live vertex's field value.
fn labels_of(live: &topoplex::live::LiveComplex) -> Labels {
    use topoplex::live::VertexId;
    let tops = live
        .tops()
        .map(|(t, s)| {
            let v = live.top_values("region", t).unwrap().unwrap();
            assert_eq!(v.len(), 1);
            (key(s), v.integer(0).unwrap())
        })
        .collect();
    let c = live.to_complex();
    let a = c.attributes().get("region", Location::Listed).unwrap();
    let live_tops: std::collections::BTreeSet<Vec<u32>> =
        live.tops().map(|(_, s)| key(s)).collect();
    // to_complex renumbers vertices densely: map back by the live vertex order.
    let ids: Vec<u32> = live.vertices().map(|v| v.0).collect();
    let mut faces: Vec<(Vec<u32>, i64)> = (live_tops.len()..c.input_count())
        .map(|i| {
            let s: Vec<u32> = c
                .input_simplex(i)
                .iter()
                .map(|&v| ids[v as usize])
                .collect();
            (key(&s), a.label(i).unwrap())
        })
        .collect();
    faces.sort();
    let field = live
        .vertices()
        .map(|v| {
            let x = live
                .vertex_values("weight", VertexId(v.0))
                .unwrap()
                .unwrap();
            (v.0, x.real(0).unwrap())
        })
        .collect();
    Labels { tops, faces, field }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    /// Random complexes to dimension 6 with random labels on every listed simplex and a random
    /// vertex field, through random contractions (link-checked and free), splits, insertions,
    /// removals and compactions: after each edit every surviving top keeps its label (an image
    /// its preimage's), listed faces are renamed or retired with the edge, the survivor keeps
    /// its field value, a split restores everything exactly, compact remaps, and
    /// `to_complex` writes the same labels.
    #[test]
    fn labels_and_fields_survive_random_edits_of_the_live_complex(
        (n, simplices) in common::random_input(6, 9, 14),
        seed in any::<u64>(),
        steps in proptest::collection::vec((0u8..6, any::<u32>(), any::<u32>()), 1..12),
    ) {
        use topoplex::Topology;
        use topoplex::live::{ContractMode, LiveComplex, VertexId};
        let mut rng = common::Rng(seed | 1);
        let mut c = common::complex_of(n, &simplices);
        let m = c.input_count();
        let mut at = Attributes::new();
        at.insert(Attribute::labels("region", Location::Listed, labels(&mut rng, m)));
        at.insert(Attribute {
            name: "weight".into(),
            location: Location::Vertices,
            components: 1,
            values: Values::F64((0..n).map(|v| f64::from(v) + 0.5).collect()),
        });
        c.set_attributes(at).unwrap();
        let mut live = LiveComplex::try_from_complex(&c).unwrap();
        let average = seed % 2 == 0;
        if average {
            live.set_vertex_policy(topoplex::live::VertexPolicy::Average);
        }
        live.validate().unwrap();
        // The listed labels at the start: tops by their first listing, faces the others.
        let mut want = labels_of(&live);
        let region = c.attributes().get("region", Location::Listed).unwrap();
        for (s, l) in &want.tops {
            prop_assert_eq!(Some(region.label(c.listed_index(s).unwrap()).unwrap()), Some(*l));
        }
        let mut undo_stack = Vec::new();
        for (op, x, y) in steps {
            let verts: Vec<u32> = live.vertices().map(|v| v.0).collect();
            let (a, b) = (verts[x as usize % verts.len()], verts[y as usize % verts.len()]);
            match op {
                0 | 1 => {
                    let mode = if op == 0 { ContractMode::PreserveTopology } else { ContractMode::Free };
                    let before = want.clone();
                    let Ok(undo) = live.contract(VertexId(a), VertexId(b), mode, None) else { continue };
                    let image = |s: &[u32]| key(&s.iter().map(|&v| if v == b { a } else { v }).collect::<Vec<_>>());
                    let now: std::collections::BTreeSet<Vec<u32>> = live.tops().map(|(_, s)| key(s)).collect();
                    // Tops without b stay as they are (a free contraction may retire an image
                    // of St(b) into one of them); each image of St(b) that is a top takes its
                    // preimage's label; two images never coincide.
                    let mut tops = std::collections::BTreeMap::new();
                    for (s, l) in before.tops.iter().filter(|(s, _)| !s.contains(&b)) {
                        if now.contains(s) {
                            tops.insert(s.clone(), *l);
                        }
                    }
                    let mut images = std::collections::BTreeSet::new();
                    for (s, l) in before.tops.iter().filter(|(s, _)| s.contains(&b)) {
                        let img = image(s);
                        prop_assert!(images.insert(img.clone()), "two images {:?}", img);
                        if now.contains(&img) && !tops.contains_key(&img) {
                            tops.insert(img, *l);
                        }
                    }
                    for s in &now {
                        prop_assert!(tops.contains_key(s), "top {:?} has no preimage", s);
                    }
                    want.tops = tops;
                    let fb = want.field.remove(&b).unwrap();
                    if average {
                        let fa = want.field.get_mut(&a).unwrap();
                        *fa = (*fa + fb) / 2.0;
                    }
                    let mut faces: Vec<(Vec<u32>, i64)> = before.faces.iter()
                        .filter(|(s, _)| !(s.contains(&a) && s.contains(&b)))
                        .map(|(s, l)| (image(s), *l))
                        .collect();
                    // Records through the collapsed edge go; the others exist when their image does.
                    let model_has = |s: &Vec<u32>| s.len() == 1 || now.iter().any(|t| s.iter().all(|v| t.contains(v)));
                    faces.retain(|(s, _)| model_has(s));
                    faces.sort();
                    want.faces = faces;
                    undo_stack.push((undo, before));
                }
                2 => {
                    if let Some((undo, before)) = undo_stack.pop() {
                        live.split(&undo).unwrap();
                        want = before;
                    }
                }
                3 => {
                    let s = key(&[a, b]);
                    if s.len() == 2 && live.insert_top(&s).is_ok() {
                        // Inserted: label unset (0); the tops it absorbed go.
                        undo_stack.clear();
                        want = labels_of(&live);
                        prop_assert_eq!(want.tops.get(&s).copied(), Some(0));
                    }
                }
                4 => {
                    let tops: Vec<Vec<u32>> = live.tops().map(|(_, s)| s.to_vec()).collect();
                    if !tops.is_empty() {
                        let t = &tops[x as usize % tops.len()];
                        live.remove_top(t).unwrap();
                        undo_stack.clear();
                        want.tops.remove(&key(t));
                        let now: Vec<Vec<u32>> = live.tops().map(|(_, s)| key(s)).collect();
                        let alive: std::collections::BTreeSet<u32> = live.vertices().map(|v| v.0).collect();
                        want.faces.retain(|(s, _)| if s.len() == 1 { alive.contains(&s[0]) } else { now.iter().any(|t| s.iter().all(|v| t.contains(v))) });
                    }
                }
                _ => {
                    let maps = live.compact();
                    undo_stack.clear();
                    let map = |v: u32| maps.vertices[v as usize];
                    want.tops = want.tops.iter().map(|(s, l)| (key(&s.iter().map(|&v| map(v)).collect::<Vec<_>>()), *l)).collect();
                    want.faces = want.faces.iter().map(|(s, l)| (key(&s.iter().map(|&v| map(v)).collect::<Vec<_>>()), *l)).collect();
                    want.faces.sort();
                    want.field = want.field.iter().map(|(&v, &x)| (map(v), x)).collect();
                }
            }
            live.validate().unwrap();
            prop_assert_eq!(labels_of(&live), want.clone());
            // What the live complex writes (no complex built) is what its complex would write.
            let raw = live.to_listing();
            let via = topoplex::io::write::listing(&live.to_complex());
            prop_assert_eq!((&raw.ids, &raw.offsets, raw.vertex_count), (&via.ids, &via.offsets, via.vertex_count));
            prop_assert_eq!(raw.coords.as_ref().map(|c| &c.data), via.coords.as_ref().map(|c| &c.data));
            prop_assert!(raw.attributes.bits_eq(&via.attributes));
        }
    }
}

/// `decompose` keeps the data: the bowtie (two triangles pinched at a vertex, two components)
/// with a label per triangle, a listed edge with its own label and a vertex field — each
/// component's tops carry their triangle's label, the listed edge goes to the component holding
/// it, and every vertex copy carries its vertex's value.
#[test]
fn decompose_gives_each_component_its_tops_faces_and_vertex_copies_data() {
    use topoplex::structures::iqm::Iqm;
    //   0       3
    //   | \   / |      triangles [0 1 2] (label 10) and [2 3 4] (label 20), pinched at 2;
    //   |  2    |      the edge [3 4] listed too (label 7)
    //   | /   \ |
    //   1       4
    let mut c = common::complex_of(5, &[vec![0, 1, 2], vec![2, 3, 4], vec![3, 4]]);
    let mut at = Attributes::new();
    at.insert(Attribute::labels(
        "region",
        Location::Listed,
        vec![10, 20, 7],
    ));
    at.insert(Attribute {
        name: "weight".into(),
        location: Location::Vertices,
        components: 1,
        values: Values::F64(vec![0.5, 1.5, 2.5, 3.5, 4.5]),
    });
    c.set_attributes(at).unwrap();
    let dec = Iqm::build(&c).unwrap().decomposition();
    assert_eq!(dec.components.len(), 2);
    let dir = Scratch::new("decompose");
    let paths = topoplex::decompose::write_components_of(&dec, &c, &dir.0, None).unwrap();
    let mut seen = Vec::new();
    for (piece, path) in dec.components.iter().zip(&paths) {
        let back = read_path(path).unwrap();
        let region = back.attributes.get("region", Location::Listed).unwrap();
        let weight = back.attributes.get("weight", Location::Vertices).unwrap();
        for (local, &v) in piece.original.iter().enumerate() {
            assert_eq!(weight.values.real(local), Some(f64::from(v) + 0.5));
        }
        for i in 0..back.simplex_count() {
            let original: Vec<u32> = back
                .simplex(i)
                .iter()
                .map(|&l| piece.original[l as usize])
                .collect();
            seen.push((key(&original), region.label(i).unwrap()));
        }
    }
    seen.sort();
    assert_eq!(
        seen,
        vec![(vec![0, 1, 2], 10), (vec![2, 3, 4], 20), (vec![3, 4], 7)]
    );
    // A vertex no simplex lists (only counted) is a component of its own, with unset labels.
    let mut c = common::complex_of(4, &[vec![0, 1, 2]]);
    let mut at = Attributes::new();
    at.insert(Attribute::labels("region", Location::Listed, vec![10]));
    c.set_attributes(at).unwrap();
    let dec = Iqm::build(&c).unwrap().decomposition();
    let dir = Scratch::new("decompose-isolated");
    let vtk = Some(topoplex::io::write::Format::Vtk);
    let paths = topoplex::decompose::write_components_of(&dec, &c, &dir.0, vtk).unwrap();
    assert_eq!(paths.len(), dec.components.len() + 1);
}

/// `.tpx` keeps every attribute bit for bit (random listings with every type, 1–9 components,
/// label names), with and without a saved structure, and a saved live complex opens back with
/// its data.
#[test]
fn saved_files_keep_attributes_and_the_live_complex_its_data() {
    use topoplex::live::LiveComplex;
    use topoplex::store::{Saved, save};
    let dir = Scratch::new("tpx");
    for seed in 1..6u64 {
        let mut raw = random_listing(seed, 12, 20, true, false);
        let mut rng = common::Rng(seed | 1);
        let m = raw.simplex_count();
        raw.attributes.insert(Attribute::labels(
            "region",
            Location::Listed,
            labels(&mut rng, m),
        ));
        raw.attributes.insert(Attribute {
            name: "v".into(),
            location: Location::Vertices,
            components: 3,
            values: Values::F32((0..36).map(|i| i as f32 / 3.0).collect()),
        });
        raw.attributes.insert(Attribute {
            name: "w".into(),
            location: Location::Listed,
            components: 9,
            values: Values::I64((0..m as i64 * 9).map(|i| i * 1_000_000_007).collect()),
        });
        raw.attributes.add_label_name(LabelName {
            attribute: "region".into(),
            dimension: None,
            label: 3,
            name: "three".into(),
        });
        let c = Complex::from_raw(&raw, None).unwrap();
        let ig = topoplex::build(topoplex::StructureKind::Ig, &c).unwrap();
        for structure in [None, Some(ig.as_ref())] {
            let path = dir.0.join("a.tpx");
            save(&path, &c, structure).unwrap();
            let back = Saved::open(&path).unwrap().complex().unwrap();
            assert!(back.attributes().bits_eq(c.attributes()), "seed {seed}");
        }
        let live = LiveComplex::try_from_complex(&c).unwrap();
        let path = dir.0.join("l.tpx");
        live.save(&path).unwrap();
        let opened = LiveComplex::open(&path).unwrap();
        assert!(
            opened
                .to_complex()
                .attributes()
                .bits_eq(live.to_complex().attributes()),
            "seed {seed}: the live complex's data"
        );
    }
}

/// A caller's merge at contractions, against a brute force: on random complexes with a 2-vector
/// field and a label on the vertices, each contraction {a, b} → a calls the merge once per
/// vertex attribute with (name, a, b) and a's and b's rows as they were, leaves a's row as the
/// merge made it (rounded to the type) and b's as it was; a split restores a's row bit for bit.
/// `set_vertex_values` sets one vertex's row and refuses a wrong width or a dead vertex.
#[test]
fn a_callers_vertex_merge_at_contractions_matches_a_brute_force_and_splits_restore() {
    use std::sync::{Arc, Mutex};
    use topoplex::Topology;
    use topoplex::live::{ContractMode, LiveComplex, VertexId};
    let mut contracted = 0;
    for seed in 1..=40u64 {
        let mut rng = common::Rng((seed * 0x2545_f491) | 1);
        let n = 5 + rng.below(6) as u32;
        let count = 3 + rng.below(6);
        let mut c = common::complex_of(n, &some_simplices(&mut rng, n, count, 4));
        let mut at = Attributes::new();
        at.insert(Attribute {
            name: "velocity".into(),
            location: Location::Vertices,
            components: 2,
            values: Values::F64((0..2 * n).map(|i| f64::from(i) * 0.75 - 3.0).collect()),
        });
        at.insert(Attribute {
            name: "material".into(),
            location: Location::Vertices,
            components: 1,
            values: Values::I32((0..n as i32).map(|v| 10 + v % 3).collect()),
        });
        c.set_attributes(at).unwrap();
        let mut live = LiveComplex::try_from_complex(&c).unwrap();
        let calls: Arc<Mutex<Vec<(String, u32, u32)>>> = Arc::default();
        let log = Arc::clone(&calls);
        // Reals: a weighted sum; labels: the larger.
        live.set_vertex_merge(move |name, a, b, row_a, row_b| {
            log.lock().unwrap().push((name.to_string(), a, b));
            for (x, &y) in row_a.iter_mut().zip(row_b) {
                *x = if name == "material" {
                    x.max(y)
                } else {
                    0.25 * *x + 0.75 * y
                };
            }
        });
        let row = |live: &LiveComplex, name: &str, v: u32| {
            let r = live.vertex_values(name, VertexId(v)).unwrap().unwrap();
            (0..r.len())
                .map(|i| r.real(i).unwrap())
                .collect::<Vec<f64>>()
        };
        for _ in 0..6 {
            let verts: Vec<u32> = live.vertices().map(|v| v.0).collect();
            if verts.len() < 2 {
                break;
            }
            let a = verts[rng.below(verts.len())];
            let b = verts[rng.below(verts.len())];
            let before: Vec<(Vec<f64>, Vec<f64>)> = ["velocity", "material"]
                .iter()
                .map(|name| (row(&live, name, a), row(&live, name, b)))
                .collect();
            calls.lock().unwrap().clear();
            let Ok(undo) = live.contract(VertexId(a), VertexId(b), ContractMode::Free, None) else {
                continue;
            };
            contracted += 1;
            assert_eq!(
                *calls.lock().unwrap(),
                [
                    ("velocity".to_string(), a, b),
                    ("material".to_string(), a, b)
                ]
            );
            let (va, vb) = &before[0];
            let want: Vec<f64> = va
                .iter()
                .zip(vb)
                .map(|(x, y)| 0.25 * x + 0.75 * y)
                .collect();
            assert_eq!(row(&live, "velocity", a), want, "seed {seed}");
            assert_eq!(
                row(&live, "material", a),
                [before[1].0[0].max(before[1].1[0])]
            );
            if rng.below(2) == 0 {
                live.split(&undo).unwrap();
                assert_eq!(row(&live, "velocity", a), before[0].0);
                assert_eq!(row(&live, "material", a), before[1].0);
                assert_eq!(row(&live, "velocity", b), before[0].1);
            }
            live.validate().unwrap();
        }
        // One vertex's row, set and read back; wrong widths and dead vertices refused.
        let v = live.vertices().next().unwrap();
        assert_eq!(
            live.set_vertex_values("velocity", v, &[1.5, -2.0]),
            Ok(true)
        );
        assert_eq!(row(&live, "velocity", v.0), [1.5, -2.0]);
        assert_eq!(live.set_vertex_values("velocity", v, &[1.5]), Ok(false));
        assert_eq!(live.set_vertex_values("absent", v, &[1.5]), Ok(false));
        assert!(
            live.set_vertex_values("velocity", VertexId(n + 7), &[0., 0.])
                .is_err()
        );
    }
    assert!(contracted > 40, "{contracted}");
}

/// `LiveComplex::top_of_packed` (packed id → top handle, O(1)) against every live top the complex
/// lists, through removals and compaction: each packed id gives back its top; the packed id of
/// a removed top, of dimension 0 or past the tables is refused.
#[test]
fn packed_top_ids_convert_to_every_live_top_and_refuse_dead_ones() {
    use topoplex::live::LiveComplex;
    let pack = |t: topoplex::live::TopId| ((t.dim() as u32) << 28) | t.slot();
    for seed in 1..=30u64 {
        let mut rng = common::Rng(seed | 1);
        let n = 6 + rng.below(7) as u32;
        let count = 2 + rng.below(9);
        let c = common::complex_of(n, &some_simplices(&mut rng, n, count, 5));
        let mut live = LiveComplex::try_from_complex(&c).unwrap();
        for round in 0..3 {
            let tops: Vec<(topoplex::live::TopId, Vec<u32>)> =
                live.tops().map(|(t, s)| (t, s.to_vec())).collect();
            for (t, s) in &tops {
                let got = live.top_of_packed(pack(*t)).unwrap();
                assert_eq!(got, *t);
                assert_eq!(live.top_vertices(got).unwrap(), &s[..]);
            }
            assert!(live.top_of_packed(3).is_err(), "a 0-simplex");
            assert!(live.top_of_packed(u32::MAX).is_err());
            if tops.is_empty() {
                break;
            }
            let (t, s) = &tops[rng.below(tops.len())];
            live.remove_top(s).unwrap();
            assert!(
                live.top_of_packed(pack(*t)).is_err(),
                "removed top {s:?} still converts"
            );
            if round == 1 {
                live.compact();
            }
        }
    }
}

/// `count` random simplices of 2 to `max_len` distinct vertices below `n` (`n` ≥ `max_len`).
fn some_simplices(rng: &mut common::Rng, n: u32, count: usize, max_len: usize) -> Vec<Vec<u32>> {
    (0..count)
        .map(|_| {
            let k = 2 + rng.below(max_len - 1);
            let mut s: Vec<u32> = Vec::new();
            while s.len() < k {
                let v = rng.below(n as usize) as u32;
                if !s.contains(&v) {
                    s.push(v);
                }
            }
            s
        })
        .collect()
}
