//! Real Gmsh: `tests/interop/gmsh_mesh.py` meshes two glued cubes with physical groups through
//! Gmsh's own Python API (the PyPI wheel `gmsh` or Debian's `python3-gmsh`) and writes MSH 4.1
//! (ASCII and binary) and 2.2; each file read here must carry Gmsh's `$PhysicalNames` and, per
//! physical group and per elementary entity, the element counts Gmsh's API reports
//! (`getPhysicalGroups`, `getEntitiesForPhysicalGroup`, `getElements`). Skipped, saying why,
//! when `python3` cannot import `gmsh` (scripts/test.sh installs it into its venv).

use crate::common;

use std::collections::BTreeMap;
use std::process::Command;

use topoplex::complex::Location;
use topoplex::io::read_path;

use common::Scratch;

fn gmsh_present() -> bool {
    let out = Command::new("python3").args(["-c", "import gmsh"]).output();
    match out {
        Ok(o) if o.status.success() => true,
        Ok(o) => {
            eprintln!(
                "python3 cannot import gmsh ({}): skipping the real-Gmsh test",
                String::from_utf8_lossy(&o.stderr)
                    .lines()
                    .last()
                    .unwrap_or("")
            );
            false
        }
        Err(e) => {
            eprintln!("no python3 ({e}): skipping the real-Gmsh test");
            false
        }
    }
}

/// (simplex dimension, tag) → elements.
type Counts = BTreeMap<(usize, i64), usize>;

#[test]
fn a_geometry_meshed_by_real_gmsh_reads_with_its_physical_names_and_counts_per_tag() {
    if !gmsh_present() {
        return;
    }
    let dir = Scratch::new("gmsh-real");
    let script = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/interop/gmsh_mesh.py");
    let o = Command::new("python3")
        .arg(script)
        .arg(&dir.0)
        .output()
        .unwrap();
    assert!(
        o.status.success(),
        "gmsh_mesh.py: {}",
        String::from_utf8_lossy(&o.stderr)
    );
    let said: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    // What Gmsh says: names, and elements per physical group and per elementary entity.
    let (mut names, mut physical, mut elementary) = (Vec::new(), Counts::new(), Counts::new());
    for g in said["groups"].as_array().unwrap() {
        let dim = g["dim"].as_u64().unwrap() as usize;
        let tag = g["tag"].as_i64().unwrap();
        names.push((dim, tag, g["name"].as_str().unwrap().to_string()));
        for e in g["entities"].as_array().unwrap() {
            let (entity, count) = (e[0].as_i64().unwrap(), e[1].as_u64().unwrap() as usize);
            *physical.entry((dim, tag)).or_default() += count;
            *elementary.entry((dim, entity)).or_default() += count;
        }
    }
    assert_eq!(names.len(), 5, "{said}");
    assert!(physical.values().all(|&n| n > 0), "{said}");
    let mut listings = Vec::new();
    for file in ["t41.msh", "t41b.msh", "t22.msh"] {
        let raw = read_path(&dir.0.join(file)).unwrap_or_else(|e| panic!("{file}: {e}"));
        // Our reading: the same names, and per (dimension, tag) the same counts.
        let mut ours: Vec<(usize, i64, String)> = raw
            .attributes
            .label_names()
            .iter()
            .filter(|n| n.attribute == "gmsh:physical")
            .map(|n| (usize::from(n.dimension.unwrap()), n.label, n.name.clone()))
            .collect();
        ours.sort();
        names.sort();
        assert_eq!(ours, names, "{file}: $PhysicalNames");
        let count = |attribute: &str| {
            let a = raw.attributes.get(attribute, Location::Listed).unwrap();
            assert_eq!(a.components, 1, "{file}: {attribute}");
            let mut c = Counts::new();
            for i in 0..raw.simplex_count() {
                *c.entry((raw.simplex(i).len() - 1, a.label(i).unwrap()))
                    .or_default() += 1;
            }
            c
        };
        assert_eq!(
            count("gmsh:physical"),
            physical,
            "{file}: elements per physical group"
        );
        assert_eq!(
            count("gmsh:geometrical"),
            elementary,
            "{file}: elements per elementary entity"
        );
        listings.push(raw);
    }
    // The three files are one mesh (Gmsh's ASCII coordinates have 16 digits, its binary all).
    let xyz = |r: &topoplex::io::RawInput| r.coords.as_ref().unwrap().data.clone();
    for r in &listings[1..] {
        assert_eq!(r.ids, listings[0].ids);
        let (a, b) = (xyz(r), xyz(&listings[0]));
        assert_eq!(a.len(), b.len());
        assert!(a.iter().zip(&b).all(|(x, y)| (x - y).abs() <= 1e-14));
        assert!(r.attributes.bits_eq(&listings[0].attributes));
    }
}
