//! Saved files through the CLI (issue 27 item 3): a crafted section table or altered arrays are
//! refused with one line naming the file (never exit 101), `--verify` checks an input fully,
//! `verify` catches a structure that no longer matches its complex, and the magic number, not
//! the extension, makes a saved file. Also the papercuts of item 6 met on the same path:
//! `--structure` in any case, a closed pipe on stdout, help texts naming every format; and the
//! C ABI's `TPX_OPEN_VERIFY`.

use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};

use topoplex::store::reseal;

/// A scratch directory of the test's own, deleted when dropped.
struct Scratch(PathBuf);

impl std::ops::Deref for Scratch {
    type Target = Path;
    fn deref(&self) -> &Path {
        &self.0
    }
}

impl Drop for Scratch {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

fn dir(name: &str) -> Scratch {
    let d = std::env::temp_dir().join(format!("tpx-cli-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    Scratch(d)
}

fn topoplex(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_topoplex"))
        .args(args)
        .output()
        .unwrap()
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).trim_end().to_string()
}

/// Exit 1 with one line on stderr (the CLI's error contract), returned.
fn refused(o: &Output) -> String {
    let err = stderr(o);
    assert_eq!(o.status.code(), Some(1), "{err}");
    assert_eq!(err.lines().count(), 1, "{err}");
    err
}

/// A bowtie (two triangles sharing vertex 2) saved with `structure` by the CLI.
fn saved_bowtie(d: &Path, structure: &str, out: &str) -> PathBuf {
    let input = d.join("bowtie.simplices");
    std::fs::write(&input, "s 0 1 2\ns 2 3 4\n").unwrap();
    let out = d.join(out);
    let o = topoplex(&[
        "save",
        input.to_str().unwrap(),
        "--structure",
        structure,
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    out
}

fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}

/// (table entry place, offset, count) of every section.
fn sections(b: &[u8]) -> Vec<(usize, usize, usize)> {
    let u64_at = |o: usize| u64::from_ne_bytes(b[o..o + 8].try_into().unwrap()) as usize;
    let n = u32::from_ne_bytes(b[24..28].try_into().unwrap()) as usize;
    let table = u64_at(40);
    (0..n)
        .map(|i| {
            (
                table + 32 * i,
                u64_at(table + 32 * i),
                u64_at(table + 32 * i + 8),
            )
        })
        .collect()
}

fn relation(file: &Path, extra: &[&str]) -> Output {
    let mut args = vec![
        "relation",
        s(file),
        "--structure",
        "ig",
        "--relation",
        "0,2",
    ];
    args.extend_from_slice(extra);
    topoplex(&args)
}

#[test]
fn a_section_counted_zero_is_refused_naming_the_file_never_a_panic() {
    let d = dir("zero");
    let good = saved_bowtie(&d, "ig", "bowtie.tpx");
    let bytes = std::fs::read(&good).unwrap();
    let want = relation(&good, &[]);
    assert!(want.status.success());
    let all = sections(&bytes);
    for (i, &(at, _, count)) in all.iter().enumerate() {
        if count == 0 {
            continue;
        }
        let mut bad = bytes.clone();
        bad[at + 8..at + 16].copy_from_slice(&0u64.to_ne_bytes());
        assert!(reseal(&mut bad));
        let path = d.join(format!("zero-{i}.tpx"));
        std::fs::write(&path, &bad).unwrap();
        let o = relation(&path, &[]);
        if o.status.success() {
            // Only a section the answer does not depend on (the source path) may be emptied.
            assert_eq!(o.stdout, want.stdout, "section {i} counted 0");
        } else {
            let err = refused(&o);
            assert!(err.contains(&format!("zero-{i}.tpx")), "{err}");
        }
    }
}

#[test]
fn flipped_array_bytes_are_refused_by_the_verify_flag_and_by_verify() {
    let d = dir("flip");
    let good = saved_bowtie(&d, "ig", "bowtie.tpx");
    let bytes = std::fs::read(&good).unwrap();
    // The last section with elements (an empty one may sit where the table starts).
    let (_, offset, _) = *sections(&bytes).iter().rfind(|e| e.2 > 0).unwrap();
    let mut bad = bytes.clone();
    bad[offset] ^= 0x01;
    let path = d.join("flipped.tpx");
    std::fs::write(&path, &bad).unwrap();
    // Without the flag the file is opened in shape only: an answer or a refusal, never a crash.
    let plain = relation(&path, &[]);
    assert!(
        matches!(plain.status.code(), Some(0 | 1)),
        "{}",
        stderr(&plain)
    );
    let err = refused(&relation(&path, &["--verify"]));
    assert!(
        err.contains("flipped.tpx") && err.contains("checksum mismatch"),
        "{err}"
    );
    let err = refused(&topoplex(&["verify", s(&path)]));
    assert!(err.contains("checksum mismatch"), "{err}");
    let out = d.join("out.off");
    for cmd in [
        vec!["report", s(&path), "--verify"],
        vec!["convert", s(&path), s(&out), "--verify"],
    ] {
        let err = refused(&topoplex(&cmd));
        assert!(err.contains("checksum mismatch"), "{cmd:?}: {err}");
    }
    // The untouched file passes the same checks.
    assert!(relation(&good, &["--verify"]).status.success());
}

#[test]
fn verify_refuses_a_structure_that_no_longer_matches_its_resealed_complex() {
    let d = dir("agree");
    let good = saved_bowtie(&d, "ig", "bowtie.tpx");
    let mut bytes = std::fs::read(&good).unwrap();
    // Section 4 is the complex's listing (ids): triangle 2 3 4 becomes 1 3 4, still a valid
    // complex, but the saved IG is the bowtie's.
    let (_, ids, count) = sections(&bytes)[4];
    assert_eq!(count, 6);
    let third = ids + 3 * 4;
    assert_eq!(bytes[third..third + 4], 2u32.to_ne_bytes());
    bytes[third..third + 4].copy_from_slice(&1u32.to_ne_bytes());
    assert!(reseal(&mut bytes));
    let path = d.join("mismatch.tpx");
    std::fs::write(&path, &bytes).unwrap();
    let err = refused(&topoplex(&["verify", s(&path)]));
    assert!(
        err.contains("mismatch.tpx") && err.contains("does not match the saved complex"),
        "{err}"
    );
    assert!(topoplex(&["verify", s(&good)]).status.success());
}

#[test]
fn a_saved_file_opens_by_its_magic_whatever_its_extension() {
    let d = dir("magic");
    let bin = saved_bowtie(&d, "ia", "bowtie.bin");
    let tpx = saved_bowtie(&d, "ia", "bowtie.tpx");
    let a = relation(&bin, &[]);
    assert!(a.status.success(), "{}", stderr(&a));
    assert_eq!(a.stdout, relation(&tpx, &[]).stdout);
    let v = topoplex(&["verify", s(&bin)]);
    assert!(v.status.success(), "{}", stderr(&v));
    // A file of another format with a .bin name is still refused by extension.
    let other = d.join("mesh.bin");
    std::fs::write(&other, "0 1 2\n").unwrap();
    let err = refused(&relation(&other, &[]));
    assert!(err.contains("unknown file extension"), "{err}");
}

#[test]
fn structure_names_are_case_insensitive() {
    let d = dir("case");
    let input = d.join("bowtie.simplices");
    std::fs::write(&input, "s 0 1 2\ns 2 3 4\n").unwrap();
    let lower = topoplex(&[
        "relation",
        s(&input),
        "--structure",
        "ia",
        "--relation",
        "0,2",
    ]);
    let upper = topoplex(&[
        "relation",
        s(&input),
        "--structure",
        "IA",
        "--relation",
        "0,2",
    ]);
    assert!(upper.status.success(), "{}", stderr(&upper));
    assert_eq!(lower.stdout, upper.stdout);
    let star = topoplex(&[
        "relation",
        s(&input),
        "--structure",
        "IAStar",
        "--relation",
        "0,2",
    ]);
    assert!(star.status.success(), "{}", stderr(&star));
}

#[test]
fn a_closed_pipe_on_stdout_ends_quietly_with_exit_0() {
    let d = dir("pipe");
    let input = d.join("strip.simplices");
    // Enough lines that the output outlasts the pipe's buffer.
    let text: String = (0..20000).map(|i| format!("s {i} {}\n", i + 1)).collect();
    std::fs::write(&input, text).unwrap();
    let mut child = Command::new(env!("CARGO_BIN_EXE_topoplex"))
        .args([
            "relation",
            s(&input),
            "--structure",
            "ig",
            "--relation",
            "0,1",
        ])
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    // Read one line (as `head -1` does), then close the pipe.
    let mut out = child.stdout.take().unwrap();
    let mut first = [0u8; 16];
    std::io::Read::read_exact(&mut out, &mut first).unwrap();
    drop(out);
    let o = child.wait_with_output().unwrap();
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    assert_eq!(stderr(&o), "");
}

#[test]
fn the_c_abi_verifies_on_request_and_opens_a_flipped_file_in_shape_only_without() {
    use std::ffi::CString;
    use std::ptr::null_mut;
    use topoplex_ffi::*;
    let d = dir("abi");
    let good = saved_bowtie(&d, "ig", "bowtie.tpx");
    let mut bytes = std::fs::read(&good).unwrap();
    // The last section with elements (an empty one may sit where the table starts).
    let (_, offset, _) = *sections(&bytes).iter().rfind(|e| e.2 > 0).unwrap();
    bytes[offset] ^= 0x01;
    let path = d.join("flipped.tpx");
    std::fs::write(&path, &bytes).unwrap();
    let (cgood, cbad) = (
        CString::new(s(&good)).unwrap(),
        CString::new(s(&path)).unwrap(),
    );
    unsafe {
        let mut c = null_mut();
        // The complex's sections are intact: opened without the flag, refused with it.
        assert_eq!(
            tpx_complex_open_flags(cbad.as_ptr(), 0, &mut c),
            TpxStatus::Ok
        );
        tpx_complex_free(c);
        let mut c = null_mut();
        let st = tpx_complex_open_flags(cbad.as_ptr(), TPX_OPEN_VERIFY, &mut c);
        assert_eq!(st, TpxStatus::SavedFileCorrupt);
        assert!(c.is_null());
        let mut st_out = null_mut();
        let st = tpx_structure_open(cbad.as_ptr(), TPX_KIND_IG, TPX_OPEN_VERIFY, &mut st_out);
        assert_eq!(st, TpxStatus::SavedFileCorrupt);
        assert!(st_out.is_null());
        let st = tpx_complex_open_flags(cgood.as_ptr(), TPX_OPEN_VERIFY, &mut c);
        assert_eq!(st, TpxStatus::Ok);
        tpx_complex_free(c);
        let st = tpx_complex_open_flags(cgood.as_ptr(), 8, &mut c);
        assert_eq!(st, TpxStatus::InvalidArgument);
    }
}

#[test]
fn help_texts_name_every_format_of_the_format_table() {
    use topoplex::io::write::Format;
    for cmd in [
        "report",
        "relation",
        "save",
        "decompose",
        "convert",
        "simplify",
    ] {
        let o = topoplex(&[cmd, "--help"]);
        assert!(o.status.success(), "{cmd}: {}", stderr(&o));
        let help = String::from_utf8_lossy(&o.stdout);
        for f in Format::ALL {
            let ext = format!(".{}", f.extension());
            assert!(help.contains(&ext), "{cmd} --help omits {ext}:\n{help}");
        }
        assert!(
            help.contains("saved file"),
            "{cmd} --help omits saved files"
        );
    }
    let convert = topoplex(&["convert", "--help"]);
    let help = String::from_utf8_lossy(&convert.stdout);
    for f in Format::ALL {
        assert!(
            help.contains(f.name()),
            "convert --help omits --format {}",
            f.name()
        );
    }
}
