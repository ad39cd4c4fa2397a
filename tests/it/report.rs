//! `topoplex report`: the census against the TS and NMIA storage formulas on random complexes,
//! and the command's output formats (Markdown, JSON, CSV, SVG) on drawn fixtures, several files
//! at once, and a missing file. No timing is checked.

use crate::common::{self, run};

use std::path::PathBuf;
use std::process::Output;

use proptest::prelude::*;
use topoplex::{Complex, StructureKind, fixtures};
use topoplex_cli::report::Census;
use topoplex_cli::report::render::CSV_COLUMNS;

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

fn temp_dir() -> PathBuf {
    let dir = std::env::temp_dir().join(format!("topoplex-report-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Writes `c` as a .simplices file (its top simplices, vertex count declared).
fn write_simplices(name: &str, c: &Complex) -> PathBuf {
    let mut text = String::new();
    for _ in 0..c.vertex_count() {
        text.push_str("v\n");
    }
    for p in 0..=c.dimension() {
        for s in c.tops(p).iter() {
            let ids: Vec<String> = s.iter().map(|v| v.to_string()).collect();
            text.push_str(&format!("s {}\n", ids.join(" ")));
        }
    }
    let path = temp_dir().join(name);
    std::fs::write(&path, text).unwrap();
    path
}

/// Edges in exactly two top triangles and in no other top simplex: manifold for the census
/// (their link is two points) but two clusters each for the NMIA, whose dangling faces have no
/// other adjacency.
fn edges_between_two_dangling_faces(c: &Complex) -> u64 {
    let mut edges: Vec<[u32; 2]> = Vec::new();
    for t in c.tops(2).iter() {
        edges.extend([[t[0], t[1]], [t[0], t[2]], [t[1], t[2]]]);
    }
    edges.sort();
    let in_higher = |e: &[u32; 2]| {
        (3..=c.dimension()).any(|p| {
            c.tops(p)
                .iter()
                .any(|s| s.contains(&e[0]) && s.contains(&e[1]))
        })
    };
    edges
        .chunk_by(|a, b| a == b)
        .filter(|g| g.len() == 2 && !in_higher(&g[0]))
        .count() as u64
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 300, ..ProptestConfig::default() })]

    /// The TS stores 6 n_2 + C_e + C_v integers (§5.1), with C_e and C_v as the census counts
    /// them.
    #[test]
    fn census_matches_the_ts_storage_formula(c in common::random_complex(2, 9, 10)) {
        let census = Census::of(&c);
        if let Ok(ts) = topoplex::build(StructureKind::Ts, &c) {
            let n2 = census.simplices.get(2).copied().unwrap_or(0) as u64;
            prop_assert_eq!(ts.storage().integers, 6 * n2 + census.c_e + census.c_v);
        }
    }

    /// The NMIA stores 8 n_3 + 3 n_2^t + 2 n_1^t + C_e + C_v (§4.1); its C_e also counts the two
    /// clusters of an edge between exactly two dangling faces.
    #[test]
    fn census_matches_the_nmia_storage_formula(c in common::random_complex(3, 9, 10)) {
        let census = Census::of(&c);
        if let Ok(nmia) = topoplex::build(StructureKind::Nmia, &c) {
            let top = |p: usize| census.top_simplices.get(p).copied().unwrap_or(0) as u64;
            let want = 8 * top(3) + 3 * top(2) + 2 * top(1) + census.c_e + census.c_v
                + 2 * edges_between_two_dangling_faces(&c);
            prop_assert_eq!(nmia.storage().integers, want);
        }
    }
}

#[test]
fn census_counts_the_iqm_components_the_iqm_reports() {
    for (name, c) in fixtures::all() {
        let iqm = topoplex::build(StructureKind::Iqm, &c).unwrap();
        let comps = iqm
            .summary()
            .into_iter()
            .find(|(k, _)| *k == "components")
            .unwrap()
            .1 as usize;
        assert_eq!(Census::of(&c).iqm_components, Ok(comps), "{name}");
    }
}

#[test]
fn json_for_two_files_is_an_array_with_exact_censuses() {
    let a = write_simplices("bowtie.simplices", &fixtures::bowtie());
    let b = write_simplices(
        "tet-tri-wire.simplices",
        &fixtures::tetrahedron_with_dangling_triangle_and_wire(),
    );
    let o = run(&["report", a.to_str().unwrap(), b.to_str().unwrap(), "--json"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let arr = v.as_array().expect("two datasets: an array");
    assert_eq!(arr.len(), 2);
    assert_eq!(arr[0]["file"], a.to_str().unwrap());
    // Bowtie: v2's link is two edges (C_v − n_0 = 1, one non-manifold vertex).
    let c = &arr[0]["census"];
    assert_eq!(
        (&c["c_e"], &c["c_v_minus_n0"], &c["iqm_components"]),
        (
            &serde_json::json!(0),
            &serde_json::json!(1),
            &serde_json::json!(2)
        )
    );
    assert_eq!(c["non_manifold"], serde_json::json!([1, 0, 0]));
    // Tetrahedron 0123 + dangling triangle 234 + wire 45: edge 2-3 has two clusters.
    let c = &arr[1]["census"];
    assert_eq!(c["wire_edges"], 1);
    assert_eq!(c["dangling_faces"], 1);
    assert_eq!(c["c_e"], 2);
    assert_eq!(c["c_v_minus_n0"], 1);
    assert_eq!(c["non_manifold"], serde_json::json!([3, 1, 0, 0]));
    assert_eq!(arr[1]["top_simplices"], serde_json::json!([0, 1, 1, 1]));
    // Every structure either has storage and four timed families, or says why it cannot.
    for d in arr {
        for k in StructureKind::NAMED {
            let s = &d["structures"][k.name()];
            if s["unsupported"].is_string() {
                continue;
            }
            assert!(s["integers"].is_u64() && s["bytes"].is_u64(), "{k}: {s}");
            for f in topoplex_cli::report::Family::ALL {
                let t = &s["families"][f.name()];
                assert!(
                    t["queries"].is_u64() && t["elements"].is_u64(),
                    "{k} {f:?}: {t}"
                );
            }
        }
    }
    // The 2-complex's sample covers all its vertices and both triangles.
    assert_eq!(arr[0]["sample"]["vertices"], 5);
    assert_eq!(arr[0]["sample"]["tops"], 2);
}

#[test]
fn csv_has_one_row_per_dataset_and_structure() {
    let a = write_simplices("fan3.simplices", &fixtures::three_triangles_on_an_edge());
    let o = run(&["report", a.to_str().unwrap(), "--csv"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let text = String::from_utf8(o.stdout).unwrap();
    let lines: Vec<&str> = text.lines().collect();
    assert_eq!(lines[0], CSV_COLUMNS.join(","));
    assert_eq!(lines.len(), 1 + StructureKind::NAMED.len());
    let col = |name: &str| CSV_COLUMNS.iter().position(|c| *c == name).unwrap();
    for (line, kind) in lines[1..].iter().zip(StructureKind::NAMED) {
        // Unsupported reasons with commas are quoted: split on commas outside quotes.
        let mut fields = Vec::new();
        let mut cur = String::new();
        let mut quoted = false;
        for ch in line.chars() {
            match ch {
                '"' => quoted = !quoted,
                ',' if !quoted => fields.push(std::mem::take(&mut cur)),
                _ => cur.push(ch),
            }
        }
        fields.push(cur);
        assert_eq!(fields.len(), CSV_COLUMNS.len(), "{line}");
        assert_eq!(fields[col("structure")], kind.name());
        assert_eq!(fields[col("c_e")], "3");
        assert_eq!(fields[col("non_manifold")], "2 1 0");
        assert_eq!(fields[col("top_simplices")], "0 0 3");
        let unsupported = !fields[col("unsupported")].is_empty();
        assert_eq!(unsupported, fields[col("heap_bytes")].is_empty(), "{line}");
    }
}

/// Tags balance, every attribute value is quoted, and `&` only starts an entity.
fn assert_xml_ish(svg: &str) {
    assert!(svg.starts_with("<svg "), "{}", &svg[..40.min(svg.len())]);
    let mut stack: Vec<String> = Vec::new();
    let mut rest = svg;
    while let Some(i) = rest.find('<') {
        let text = &rest[..i];
        for (j, _) in text.match_indices('&') {
            let ent = &text[j..];
            assert!(
                ["&amp;", "&lt;", "&gt;", "&quot;"]
                    .iter()
                    .any(|e| ent.starts_with(e)),
                "bare & in {text}"
            );
        }
        let end = rest[i..].find('>').expect("tag closes") + i;
        let tag = &rest[i + 1..end];
        assert_eq!(tag.matches('"').count() % 2, 0, "{tag}");
        if let Some(name) = tag.strip_prefix('/') {
            assert_eq!(stack.pop().as_deref(), Some(name), "closing {name}");
        } else if !tag.ends_with('/') {
            stack.push(tag.split_whitespace().next().unwrap().to_string());
        }
        rest = &rest[end + 1..];
    }
    assert!(stack.is_empty(), "unclosed {stack:?}");
}

#[test]
fn svg_is_well_formed_and_names_every_structure_and_dataset() {
    let a = write_simplices("pie.simplices", &fixtures::pinched_pie());
    let b = write_simplices("strip.simplices", &fixtures::strip_pinched_at_a_vertex());
    let out = temp_dir().join("chart.svg");
    let o = run(&[
        "report",
        a.to_str().unwrap(),
        b.to_str().unwrap(),
        "--svg",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    // Markdown still goes to stdout.
    assert!(String::from_utf8(o.stdout).unwrap().contains("## Census"));
    let svg = std::fs::read_to_string(&out).unwrap();
    assert_xml_ish(&svg);
    for k in StructureKind::NAMED {
        assert!(
            svg.contains(&format!(">{}</text>", k.name())),
            "legend lacks {k}"
        );
    }
    for name in [
        "pie.simplices",
        "strip.simplices",
        "co-boundary",
        "bytes per simplex",
    ] {
        assert!(svg.contains(name), "{name}");
    }
    // Two time charts (one per dataset) after the storage chart.
    assert_eq!(svg.matches("ns per retrieved element").count(), 2);
}

#[test]
fn markdown_has_census_storage_and_a_section_per_dataset() {
    let o = run(&["report"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let text = String::from_utf8(o.stdout).unwrap();
    // The built-in example's census row, worked out in its drawing (src/fixtures.rs).
    assert!(
        text.contains("| built-in example | 3 | 10 | 2 | 2 | 1 2 2 1 | 2 | 2 | 5 | 4 1 0 0 |"),
        "{text}"
    );
    assert!(text.contains("## Storage: heap bytes per simplex"));
    assert!(
        text.contains("| ts | — |"),
        "ts cannot encode a 3-complex: {text}"
    );
    assert!(text.contains("unsupported: structure `ts` cannot encode this complex"));
}

#[test]
fn a_missing_file_is_named_and_nothing_is_printed() {
    let good = write_simplices("ok.simplices", &fixtures::bowtie());
    let o = run(&[
        "report",
        good.to_str().unwrap(),
        "/nonexistent/missing.off",
        "--json",
    ]);
    assert_eq!(o.status.code(), Some(1));
    let err = stderr(&o);
    assert!(err.contains("/nonexistent/missing.off"), "{err}");
    assert!(err.contains("cannot read file"), "{err}");
    assert_eq!(err.trim_end().lines().count(), 1, "{err}");
    assert!(o.stdout.is_empty());
}

#[test]
fn real_data_reports_load_and_count() {
    // A small real file of each kind, when ../shared/data is present.
    let Some(dir) = common::shared_data() else {
        eprintln!("../shared/data is absent: skipping");
        return;
    };
    for rel in ["nonmanifold/fan3.obj", "tetrahedral/octopus-low.mesh"] {
        let path = dir.join(rel);
        let Ok(c) = Complex::from_path(&path) else {
            eprintln!("{rel} does not load: skipping");
            continue;
        };
        let o = run(&["report", path.to_str().unwrap(), "--json"]);
        assert!(o.status.success(), "{rel}: {}", stderr(&o));
        let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
        assert_eq!(v["vertices"], c.vertex_count());
        assert!(v["census"]["iqm_components"].is_u64(), "{rel}");
    }
}
