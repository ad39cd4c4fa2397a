//! The `topoplex` binary as a user runs it: output formats, exit codes, one-line errors, and
//! `relation --structure X` equal to `--structure ig` line by line.

use crate::common::{self, run};

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use topoplex::StructureKind;

fn stdout(o: &Output) -> String {
    String::from_utf8(o.stdout.clone()).unwrap()
}

fn stderr(o: &Output) -> String {
    String::from_utf8(o.stderr.clone()).unwrap()
}

/// Runs `args`, which must succeed; its output.
fn succeeded(args: &[&str]) -> Output {
    let o = run(args);
    assert!(o.status.success(), "{args:?}: {}", stderr(&o));
    o
}

/// Runs `args`, which must fail with exit 1 and a message containing `what`.
fn refused(args: &[&str], what: &str) {
    let o = run(args);
    assert_eq!(o.status.code(), Some(1), "{args:?}");
    assert!(stderr(&o).contains(what), "{args:?}: {}", stderr(&o));
}

fn temp_file(name: &str, text: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("topoplex-cli-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let p = dir.join(name);
    std::fs::write(&p, text).unwrap();
    p
}

#[test]
fn report_on_the_builtin_example() {
    let o = succeeded(&["report"]);
    let text = stdout(&o);
    assert!(text.contains("dimension: 3"), "{text}");
    assert!(
        text.contains("simplices per dimension (n_0..n_d): 10 13 6 1"),
        "{text}"
    );
    assert!(
        text.contains("top simplices per dimension: 1 2 2 1"),
        "{text}"
    );
    let o = run(&["report", "--json"]);
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(v["dimension"], 3);
    assert_eq!(v["simplices"], serde_json::json!([10, 13, 6, 1]));
    assert_eq!(v["top_simplices"], serde_json::json!([1, 2, 2, 1]));
    let ig = &v["structures"]["ig"];
    // 2·(2·13 + 3·6 + 4·1) + (10 + 13 + 6) integers, as the SIG paper counts the IG.
    assert_eq!(ig["integers"], 2 * (2 * 13 + 3 * 6 + 4) + 29);
    assert!(ig["bytes"].as_u64().unwrap() > 0 && ig["build_ms"].is_number());
    for k in StructureKind::ALL {
        let s = &v["structures"][k.name()];
        assert!(
            s["integers"].is_u64() || s["unsupported"].is_string(),
            "{k}: {s}"
        );
    }
}

#[test]
fn report_counts_absorbed_input() {
    let f = temp_file("absorb.simplices", "s 0 1 2\ns 2 1 0\ns 1 2\ns 3\n");
    let v: serde_json::Value =
        serde_json::from_slice(&run(&["report", f.to_str().unwrap(), "--json"]).stdout).unwrap();
    assert_eq!(
        (
            v["absorbed_duplicates"].as_u64(),
            v["absorbed_faces"].as_u64()
        ),
        (Some(1), Some(1))
    );
    assert_eq!(v["top_simplices"], serde_json::json!([1, 0, 1]));
}

#[test]
fn relation_dump_format_is_exact() {
    // Two triangles on edge 0 10, plus vertex ids that sort differently as text and as numbers.
    let f = temp_file("two.simplices", "s 0 10 11\ns 0 9 10\n");
    let o = succeeded(&[
        "relation",
        f.to_str().unwrap(),
        "--structure",
        "ig",
        "--relation",
        "1,2",
    ]);
    let expected = "0 9;0 9 10\n0 10;0 9 10;0 10 11\n0 11;0 10 11\n9 10;0 9 10\n10 11;0 10 11\n";
    // Vertices 1..8 are isolated and have no edges, so only edges appear.
    assert_eq!(stdout(&o), expected);
    assert_dump_one(&f, "ig", (1, 0), "10 0", "0 10;0;10\n");
    assert_dump_one(&f, "ig", (0, 0), "3", "3\n");
}

#[test]
fn errors_exit_nonzero_with_one_line() {
    let good = temp_file("g.simplices", "s 0 1 2\n");
    let bad = temp_file("bad.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 1\n");
    let quad = temp_file(
        "quad.obj",
        "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n",
    );
    let txt = good.with_extension("txt");
    let cases: Vec<(Vec<String>, &str)> = vec![
        (
            relation_args(&bad, "ig", (0, 1), None),
            "bad.off:6: simplex [0 1 1] repeats vertex 1",
        ),
        (
            relation_args(&quad, "ig", (0, 1), None),
            "quad.obj:5: polygon with 4 vertices is not a simplex",
        ),
        (
            relation_args(&good, "xyz", (0, 1), None),
            "unknown structure `xyz`",
        ),
        (
            relation_args(&good, "ig", (0, 3), None),
            "the complex has dimension 2",
        ),
        (
            relation_args(&good, "ig", (1, 2), Some("0 5")),
            "uses vertex 5",
        ),
        (
            relation_args(&good, "ig", (1, 2), Some("0")),
            "P = 1 needs 2",
        ),
        (
            vec!["report".into(), "/nonexistent/x.off".into()],
            "cannot read file",
        ),
        (
            vec!["report".into(), txt.to_str().unwrap().into()],
            "unknown file extension",
        ),
    ];
    for (args, needle) in cases {
        let o = run(&args.iter().map(String::as_str).collect::<Vec<_>>());
        let err = stderr(&o);
        assert_eq!(o.status.code(), Some(1), "{args:?}: {err}");
        assert!(err.contains(needle), "{args:?}: {err}");
        assert_eq!(err.trim_end().lines().count(), 1, "{args:?}: {err}");
        assert!(!err.contains("panicked"), "{err}");
    }
}

/// `relation FILE --structure KIND --relation P,Q [--simplex SIMPLEX]`.
fn relation(file: &Path, kind: &str, pq: (usize, usize), simplex: Option<&str>) -> Output {
    let args = relation_args(file, kind, pq, simplex);
    run(&args.iter().map(String::as_str).collect::<Vec<_>>())
}

/// The arguments of [`relation`].
fn relation_args(
    file: &Path,
    kind: &str,
    (p, q): (usize, usize),
    simplex: Option<&str>,
) -> Vec<String> {
    let pq = format!("{p},{q}");
    let mut args = vec![
        "relation",
        file.to_str().unwrap(),
        "--structure",
        kind,
        "--relation",
        &pq,
    ];
    args.extend(simplex.into_iter().flat_map(|s| ["--simplex", s]));
    args.into_iter().map(String::from).collect()
}

fn dump(file: &Path, kind: &str, p: usize, q: usize) -> Output {
    relation(file, kind, (p, q), None)
}

/// Asserts the dump of one simplex's relation: `expected` on stdout.
fn assert_dump_one(file: &Path, kind: &str, pq: (usize, usize), simplex: &str, expected: &str) {
    let o = relation(file, kind, pq, Some(simplex));
    assert_eq!(stdout(&o), expected);
}

#[test]
fn iastar_dumps_what_the_ig_dumps_on_a_mixed_complex() {
    //        4
    //       / \
    //      3---5---6      7     the tetrahedron 0 1 2 3 below its apex 3, the triangle 3 4 5
    //     /|\                   hanging from the apex, the wire edge 5 6, vertex 7 alone
    //    0-+-2
    //     \|/
    //      1
    let f = temp_file("mixed.simplices", "s 0 1 2 3\ns 3 4 5\ns 5 6\ns 7\n");
    for p in 0..=3 {
        for q in 0..=3 {
            let want = dump(&f, "ig", p, q);
            let got = dump(&f, "iastar", p, q);
            assert!(
                got.status.success(),
                "iastar R_{{{p},{q}}}: {}",
                stderr(&got)
            );
            assert_eq!(
                stdout(&got),
                stdout(&want),
                "iastar R_{{{p},{q}}} differs from ig"
            );
        }
    }
    // Exact answers for one row each way: the apex's triangles, the wire's vertices.
    assert_dump_one(&f, "iastar", (0, 2), "3", "3;0 1 3;0 2 3;1 2 3;3 4 5\n");
    assert_dump_one(&f, "iastar", (1, 0), "6 5", "5 6;5;6\n");
}

#[test]
fn every_structure_dumps_what_the_ig_dumps_on_real_data() {
    common::for_each_shared_complex(u64::MAX, |path, c| {
        // The dump of every P,Q through every structure is a lot of process output: keep to the
        // files of moderate size (the library-level comparison covers the rest).
        if c.closure().iter().map(|t| t.len()).sum::<usize>() > 40_000 {
            return;
        }
        let d = c.dimension();
        // The IG's dumps once per file, each compared with every other structure's.
        let want: Vec<Vec<u8>> = (0..=d)
            .flat_map(|p| (0..=d).map(move |q| (p, q)))
            .map(|(p, q)| {
                let ig = dump(path, "ig", p, q);
                assert!(
                    ig.status.success(),
                    "{}: ig: {}",
                    path.display(),
                    stderr(&ig)
                );
                ig.stdout
            })
            .collect();
        let kinds = StructureKind::ALL.into_iter().skip(1);
        for kind in kinds.chain([StructureKind::IaStar]) {
            if topoplex::build(kind, &c).is_err() {
                continue;
            }
            for p in 0..=d {
                for q in 0..=d {
                    let want = &want[p * (d + 1) + q];
                    let got = dump(path, kind.name(), p, q);
                    assert!(
                        got.status.success(),
                        "{}: {kind}: {}",
                        path.display(),
                        stderr(&got)
                    );
                    assert!(
                        got.stdout == *want,
                        "{}: {kind} R_{{{p},{q}}} differs from ig",
                        path.display()
                    );
                }
            }
        }
    });
}

/// `topoplex decompose` of a bowtie with a wire (written as `file`) into the folder `out` beside
/// it, with `options`; the command must succeed. Returns the folder and the output.
///
/// ```text
///   0       3
///   | \   / |      bowtie: two triangles pinched at vertex 2, plus a wire edge 4-5
///   |  2    |
///   | /   \ |
///   1       4 --- 5
/// ```
fn decompose_bowtie(file: &str, out: &str, options: &[&str]) -> (PathBuf, Output) {
    let f = temp_file(
        file,
        "v 0 0 0\nv 0 1 0\nv 1 0.5 0\nv 2 1 0\nv 2 0 0\nv 3 0 0\ns 0 1 2\ns 2 3 4\ns 4 5\n",
    );
    let out = f.with_file_name(out);
    let mut args = vec![
        "decompose",
        f.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ];
    args.extend_from_slice(options);
    let o = succeeded(&args);
    (out, o)
}

#[test]
fn decompose_writes_components_and_gluing() {
    let (out, o) = decompose_bowtie("bowtie.simplices", "bowtie-parts", &[]);
    assert!(
        stdout(&o).starts_with("3 components, 2 split vertices"),
        "{}",
        stdout(&o)
    );
    let gluing: serde_json::Value =
        serde_json::from_slice(&std::fs::read(out.join("gluing.json")).unwrap()).unwrap();
    let comps = gluing["components"].as_array().unwrap();
    assert_eq!(comps.len(), 3);
    // Every component file loads back, and its original ids cover its part of the complex.
    let mut tops = Vec::new();
    for c in comps {
        let file = out.join(c["file"].as_str().unwrap());
        let part = topoplex::Complex::from_path(&file).unwrap();
        let orig: Vec<u32> = c["original_ids"]
            .as_array()
            .unwrap()
            .iter()
            .map(|v| v.as_u64().unwrap() as u32)
            .collect();
        let d = part.dimension();
        for t in part.tops(d).iter() {
            let mut g: Vec<u32> = t.iter().map(|&l| orig[l as usize]).collect();
            g.sort();
            tops.push(g);
        }
    }
    tops.sort();
    assert_eq!(tops, vec![vec![0, 1, 2], vec![2, 3, 4], vec![4, 5]]);
}

#[test]
fn convert_keeps_order_winding_and_coordinates() {
    //   0 --- 1      triangle wound 1 0 2, then a wire edge 2 3, vertex 4 isolated
    //    \   /
    //      2 --- 3   4
    let f = temp_file(
        "convert.simplices",
        "v 0 0.1 0\nv 1 0 0\nv 0.3 1 0\nv 2 1 1e-300\nv 5 5 5\ns 1 0 2\ns 2 3\n",
    );
    let out = f.with_file_name("converted.off");
    succeeded(&["convert", f.to_str().unwrap(), out.to_str().unwrap()]);
    assert_eq!(
        std::fs::read_to_string(&out).unwrap(),
        "OFF\n5 2 0\n0 0.1 0\n1 0 0\n0.3 1 0\n2 1 1e-300\n5 5 5\n3 1 0 2\n2 2 3\n"
    );
    // Back to .simplices: the same text as the input.
    let back = f.with_file_name("back.txt");
    succeeded(&[
        "convert",
        out.to_str().unwrap(),
        back.to_str().unwrap(),
        "--format",
        "simplices",
    ]);
    assert_eq!(
        std::fs::read_to_string(&back).unwrap(),
        std::fs::read_to_string(&f).unwrap()
    );
}

#[test]
fn convert_refuses_what_the_format_cannot_hold() {
    let f = temp_file("tet.simplices", "s 0 1 2 3\n");
    let out = f.with_file_name("tet-refused.off");
    refused(
        &["convert", f.to_str().unwrap(), out.to_str().unwrap()],
        "the off format cannot hold this complex: simplex #0 [0 1 2 3]",
    );
    assert!(!out.exists());
    refused(
        &["convert", f.to_str().unwrap(), "x.unknown"],
        "unknown output extension",
    );
    refused(
        &["convert", f.to_str().unwrap(), "x.off", "--format", "dxf"],
        "unknown format `dxf`",
    );
}

/// `convert --round-f32`: STL refuses 0.1 (not a 32-bit float) without it; with it every
/// coordinate becomes the nearest 32-bit float, which reads back exactly; a coordinate beyond
/// the 32-bit range is refused, naming the vertex, and nothing is written.
#[test]
fn convert_round_f32_rounds_for_stl_and_refuses_what_does_not_fit() {
    let off = temp_file(
        "round.off",
        "OFF\n3 1 0\n0.1 0 0\n1 0.3 0\n0 1 0.7\n3 0 1 2\n",
    );
    let stl = off.with_extension("stl");
    refused(
        &["convert", off.to_str().unwrap(), stl.to_str().unwrap()],
        "not exactly a 32-bit float",
    );
    succeeded(&[
        "convert",
        off.to_str().unwrap(),
        stl.to_str().unwrap(),
        "--round-f32",
    ]);
    let back = topoplex::Complex::from_path(&stl).unwrap();
    let want: Vec<f64> = [0.1, 0.0, 0.0, 1.0, 0.3, 0.0, 0.0, 1.0, 0.7]
        .iter()
        .map(|&x| f64::from(x as f32))
        .collect();
    assert_eq!(back.coords().unwrap().data, want);
    let far = temp_file("far.off", "OFF\n3 1 0\n0 0 0\n1 1e300 0\n0 1 0\n3 0 1 2\n");
    let far_stl = far.with_extension("stl");
    let o = run(&[
        "convert",
        far.to_str().unwrap(),
        far_stl.to_str().unwrap(),
        "--round-f32",
    ]);
    assert_eq!(o.status.code(), Some(1));
    let e = stderr(&o);
    assert!(
        e.contains("vertex 1 coordinate 1 = 1e300") && e.lines().count() == 1,
        "{e}"
    );
    assert!(!far_stl.exists());
}

/// `--triangulate` on every command that reads a mesh: a hexagon and a quad glued along an edge
/// (OBJ, each face in its own `usemtl` group) are refused without it; with it `convert` writes
/// the fans from each polygon's first vertex in order (winding kept, each triangle in its
/// polygon's group), and `report`, `relation`, `save`, `simplify` and `decompose` take the
/// same 6 triangles; a bent quad is refused on one line naming file, line and reason.
#[test]
fn triangulate_fans_polygons_on_every_command_and_refuses_a_bent_quad() {
    let obj = temp_file(
        "polygons.obj",
        "v 0 0 0\nv 2 0 0\nv 3 1 0\nv 2 2 0\nv 0 2 0\nv -1 1 0\nv 3 3 0\nv 4 2 0\n\
         usemtl hex\nf 1 2 3 4 5 6\nusemtl quad\nf 4 3 8 7\n",
    );
    let inp = obj.to_str().unwrap();
    let dir = obj.with_extension("d");
    std::fs::create_dir_all(&dir).unwrap();
    let p = |name: &str| dir.join(name).to_str().unwrap().to_string();
    refused(
        &["convert", inp, &p("plain.off")],
        "polygon with 6 vertices is not a simplex",
    );
    succeeded(&["convert", inp, &p("fan.obj"), "--triangulate"]);
    let text = std::fs::read_to_string(p("fan.obj")).unwrap();
    let faces: Vec<&str> = text
        .lines()
        .filter(|l| l.starts_with("f ") || l.starts_with("usemtl"))
        .collect();
    assert_eq!(
        faces,
        [
            "usemtl hex",
            "f 1 2 3",
            "f 1 3 4",
            "f 1 4 5",
            "f 1 5 6",
            "usemtl quad",
            "f 4 3 8",
            "f 4 8 7"
        ]
    );
    // The flag goes before or after the command.
    for args in [
        vec!["--triangulate", "report", inp, "--csv"],
        vec![
            "relation",
            inp,
            "--structure",
            "ig",
            "--relation",
            "2,0",
            "--triangulate",
        ],
        vec!["save", inp, "--out", &p("s.tpx"), "--triangulate"],
        vec![
            "simplify",
            inp,
            "--out",
            &p("s.obj"),
            "--ratio",
            "0.5",
            "--triangulate",
        ],
        vec![
            "decompose",
            inp,
            "--out",
            &p("parts"),
            "--format",
            "obj",
            "--triangulate",
        ],
    ] {
        succeeded(&args);
        let mut without = args.clone();
        without.retain(|a| *a != "--triangulate");
        refused(&without, "polygon with 6 vertices is not a simplex");
    }
    let o = run(&[
        "relation",
        inp,
        "--structure",
        "ig",
        "--relation",
        "2,0",
        "--triangulate",
    ]);
    assert_eq!(stdout(&o).lines().count(), 6, "{}", stdout(&o));
    let saved = topoplex::store::open_complex(Path::new(&p("s.tpx")), Default::default()).unwrap();
    assert_eq!(saved.top_counts(), [0, 0, 6]);
    let bent = temp_file(
        "bent.obj",
        "v 0 0 0\nv 1 0 0\nv 1 1 0.2\nv 0 1 0\nf 1 2 3 4\n",
    );
    let o = run(&["report", bent.to_str().unwrap(), "--triangulate"]);
    assert_eq!(o.status.code(), Some(1));
    let e = stderr(&o);
    assert!(
        e.contains("bent.obj:5: cannot triangulate polygon #0")
            && e.contains("not planar")
            && e.lines().count() == 1,
        "{e}"
    );
}

#[test]
fn decompose_writes_components_in_a_chosen_format() {
    let (out, _) = decompose_bowtie("bowtie-fmt.simplices", "bowtie-obj", &["--format", "obj"]);
    let mut names: Vec<String> = std::fs::read_dir(&out)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    assert_eq!(
        names,
        [
            "component_0.obj",
            "component_1.obj",
            "component_2.obj",
            "gluing.json"
        ]
    );
}

#[test]
fn convert_census_marks_singularities_for_paraview() {
    //   0       3
    //   | \   / |      bowtie pinched at vertex 2
    //   |  2    |
    //   | /   \ |
    //   1       4
    let f = temp_file("bowtie-census.simplices", "s 0 1 2\ns 2 3 4\n");
    let out = f.with_file_name("bowtie-census.vtk");
    succeeded(&[
        "convert",
        f.to_str().unwrap(),
        out.to_str().unwrap(),
        "--census",
    ]);
    let text = std::fs::read_to_string(&out).unwrap();
    assert!(
        text.contains("SCALARS non_manifold_vertex int 1\nLOOKUP_TABLE default\n0 0 1 0 0\n"),
        "{text}"
    );
    refused(
        &["convert", f.to_str().unwrap(), "x.off", "--census"],
        "--census writes legacy VTK",
    );
}

/// Outputs that exist and are not regular files — a named pipe, a link to `/dev/null` — are
/// refused with exit 1, before anything is written beside them, and left as they were (`save`
/// used to write OUT.partial and rename it over whatever OUT was).
#[test]
fn outputs_that_are_not_regular_files_are_refused_and_left_alone() {
    use std::os::unix::fs::FileTypeExt;
    let input = temp_file(
        "cli-special-out.off",
        "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n",
    );
    let dir = std::env::temp_dir().join(format!("topoplex-special-out-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let pipe = dir.join("pipe.tpx");
    let made = Command::new("mkfifo").arg(&pipe).status();
    assert!(made.is_ok_and(|s| s.success()), "mkfifo failed");
    let null_link = dir.join("null.off");
    std::os::unix::fs::symlink("/dev/null", &null_link).unwrap();
    let input = input.to_str().unwrap();
    for args in [
        vec![
            "save",
            input,
            "--structure",
            "ig",
            "--out",
            pipe.to_str().unwrap(),
        ],
        vec!["save", input, "--out", null_link.to_str().unwrap()],
        vec!["convert", input, null_link.to_str().unwrap()],
    ] {
        let o = run(&args);
        assert_eq!(o.status.code(), Some(1), "{args:?}: {}", stderr(&o));
        let e = stderr(&o);
        assert!(
            e.contains("not a regular file") && e.lines().count() == 1,
            "{args:?}: {e}"
        );
    }
    assert!(std::fs::metadata(&pipe).unwrap().file_type().is_fifo());
    let link = std::fs::symlink_metadata(&null_link).unwrap();
    assert!(link.file_type().is_symlink());
    assert!(
        std::fs::metadata("/dev/null")
            .unwrap()
            .file_type()
            .is_char_device()
    );
    let left: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().file_name())
        .collect();
    assert_eq!(
        left.len(),
        2,
        "something was written beside the outputs: {left:?}"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

/// `--threads` and `TOPOPLEX_THREADS` are bounded (1..=256) and a bad value is an error (exit 1,
/// one line naming the flag or variable), never ignored.
#[test]
fn thread_counts_outside_the_bound_are_refused() {
    let input = temp_file(
        "cli-threads.off",
        "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n",
    );
    let input = input.to_str().unwrap();
    let args = ["relation", input, "--structure", "ig", "--relation", "0,2"];
    for (threads, env, needle) in [
        (
            Some("100000"),
            None,
            "--threads: thread count 100000 is outside 1..=256",
        ),
        (
            Some("0"),
            None,
            "--threads: thread count 0 is outside 1..=256",
        ),
        (
            None,
            Some("abc"),
            "TOPOPLEX_THREADS=abc: not a thread count in 1..=256",
        ),
        (
            None,
            Some("20000"),
            "TOPOPLEX_THREADS=20000: not a thread count",
        ),
    ] {
        let mut cmd = Command::new(env!("CARGO_BIN_EXE_topoplex"));
        cmd.args(args);
        if let Some(t) = threads {
            cmd.args(["--threads", t]);
        }
        match env {
            Some(v) => cmd.env("TOPOPLEX_THREADS", v),
            None => cmd.env_remove("TOPOPLEX_THREADS"),
        };
        let o = cmd.output().unwrap();
        let e = stderr(&o);
        assert_eq!(o.status.code(), Some(1), "{threads:?} {env:?}: {e}");
        assert!(e.contains(needle) && e.lines().count() == 1, "{e}");
    }
    succeeded(&[&args[..], &["--threads", "256"]].concat());
}

/// A `.tpx` name on a named pipe or a directory is refused at once by every command that opens
/// it (`verify` included), saying what it is; the pipe used to hang them all.
#[test]
fn a_saved_file_name_on_a_pipe_or_directory_is_refused_not_waited_on() {
    let dir = std::env::temp_dir().join(format!("topoplex-special-in-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(dir.join("dir.tpx")).unwrap();
    let pipe = dir.join("pipe.tpx");
    let made = Command::new("mkfifo").arg(&pipe).status();
    assert!(made.is_ok_and(|s| s.success()), "mkfifo failed");
    for (name, what) in [("pipe.tpx", "a named pipe"), ("dir.tpx", "a directory")] {
        let file = dir.join(name);
        let file = file.to_str().unwrap();
        for args in [
            vec!["verify", file],
            vec!["report", file],
            vec!["relation", file, "--structure", "ig", "--relation", "0,1"],
        ] {
            let mut child = Command::new(env!("CARGO_BIN_EXE_topoplex"))
                .args(&args)
                .stdout(std::process::Stdio::null())
                .stderr(std::process::Stdio::piped())
                .spawn()
                .unwrap();
            let deadline = std::time::Instant::now() + std::time::Duration::from_secs(20);
            let status = loop {
                if let Some(s) = child.try_wait().unwrap() {
                    break s;
                }
                if std::time::Instant::now() > deadline {
                    let _ = child.kill();
                    panic!("{args:?} still running after 20 s");
                }
                std::thread::sleep(std::time::Duration::from_millis(20));
            };
            let mut e = String::new();
            std::io::Read::read_to_string(&mut child.stderr.take().unwrap(), &mut e).unwrap();
            assert_eq!(status.code(), Some(1), "{args:?}: {e}");
            assert!(e.contains(what) && e.lines().count() == 1, "{args:?}: {e}");
        }
    }
    std::fs::remove_dir_all(&dir).unwrap();
}
