//! Bounded resources: reading and normalising a large file peaks within a small multiple of
//! the file size (documented in docs/bad-input.md), for every text format. Linux only (reads
//! /proc/self/status). One test: the peak counter is per process, so the files are read one
//! after the other.

use std::io::Write;

fn status_kib(field: &str) -> Option<u64> {
    let s = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = s.lines().find(|l| l.starts_with(field))?;
    line.split_whitespace().nth(1)?.parse().ok()
}

/// A k×k grid of squares, two triangles each, written with `vertex` and `triangle` (0-based
/// ids) after `head`.
fn write_grid(
    path: &std::path::Path,
    k: u32,
    head: &str,
    vertex: impl Fn(u32, u32) -> String,
    triangle: impl Fn(u32, u32, u32) -> String,
) {
    let mut w = std::io::BufWriter::new(std::fs::File::create(path).unwrap());
    w.write_all(head.as_bytes()).unwrap();
    for y in 0..=k {
        for x in 0..=k {
            writeln!(w, "{}", vertex(x, y)).unwrap();
        }
    }
    for y in 0..k {
        for x in 0..k {
            let a = y * (k + 1) + x;
            writeln!(w, "{}", triangle(a, a + 1, a + k + 2)).unwrap();
            writeln!(w, "{}", triangle(a, a + k + 2, a + k + 1)).unwrap();
        }
    }
}

/// Peak bytes above the resident size before the call, while `Complex::from_path` reads and
/// normalises `path`.
fn peak_while_reading(path: &std::path::Path) -> (u64, topoplex::Complex) {
    std::fs::write("/proc/self/clear_refs", "5").unwrap();
    let before = status_kib("VmRSS:").unwrap() * 1024;
    let c = topoplex::Complex::from_path(path).unwrap();
    let peak = status_kib("VmHWM:").unwrap() * 1024;
    (peak.saturating_sub(before), c)
}

#[test]
fn reading_large_files_peaks_within_five_times_the_file() {
    // Resetting the peak counter needs Linux >= 4.0; skip elsewhere.
    if std::fs::write("/proc/self/clear_refs", "5").is_err() || status_kib("VmHWM:").is_none() {
        eprintln!("no /proc peak-RSS reset here: skipping");
        return;
    }
    let k = 400u32; // 320,000 triangles
    let n = (k + 1) * (k + 1);
    let t = 2 * k * k;
    let dir = std::env::temp_dir();
    let pid = std::process::id();
    let off_head = format!("OFF\n{n} {t} 0\n");
    let mesh_head = format!("MeshVersionFormatted 2\nDimension 3\nVertices\n{n}\n");
    type Writer = Box<dyn Fn(&std::path::Path)>;
    let files: Vec<(&str, Writer)> = vec![
        (
            "off",
            Box::new(move |p| {
                write_grid(
                    p,
                    k,
                    &off_head,
                    |x, y| format!("{x} {y} 0"),
                    |a, b, c| format!("3 {a} {b} {c}"),
                )
            }),
        ),
        (
            "obj",
            Box::new(move |p| {
                write_grid(
                    p,
                    k,
                    "",
                    |x, y| format!("v {x} {y} 0"),
                    |a, b, c| format!("f {} {} {}", a + 1, b + 1, c + 1),
                )
            }),
        ),
        (
            "simplices",
            Box::new(move |p| {
                write_grid(
                    p,
                    k,
                    "",
                    |x, y| format!("v {x} {y} 0"),
                    |a, b, c| format!("s {a} {b} {c}"),
                )
            }),
        ),
        (
            "mesh",
            Box::new(move |p| {
                let first = std::cell::Cell::new(true);
                write_grid(
                    p,
                    k,
                    &mesh_head,
                    |x, y| format!("{x} {y} 0 0"),
                    |a, b, c| {
                        // The section header goes before the first triangle.
                        let s = format!("{} {} {} 0", a + 1, b + 1, c + 1);
                        if first.replace(false) {
                            format!("Triangles\n{t}\n{s}")
                        } else {
                            s
                        }
                    },
                )
            }),
        ),
    ];
    // Each format in a fresh process (this test binary run again): memory an earlier read freed
    // but the allocator kept would otherwise hide part of the next read's peak.
    let Ok(only) = std::env::var(FORMAT_VAR) else {
        let mut failures = Vec::new();
        for (ext, _) in &files {
            let out = std::process::Command::new(std::env::current_exe().unwrap())
                .args([TEST, "--exact", "--nocapture", "--test-threads=1"])
                .env(FORMAT_VAR, ext)
                .output()
                .unwrap();
            let stderr = String::from_utf8_lossy(&out.stderr);
            let line = stderr
                .lines()
                .find(|l| l.starts_with(ext))
                .unwrap_or_default();
            eprintln!("{line}");
            if !out.status.success() {
                failures.push(format!("{ext}: {line}"));
            }
        }
        assert!(failures.is_empty(), "reading peaked above 5x: {failures:?}");
        return;
    };
    let (ext, write) = files.iter().find(|(e, _)| *e == only).unwrap();
    let path = dir.join(format!("topoplex-mem-{pid}.{ext}"));
    write(&path);
    let file_bytes = std::fs::metadata(&path).unwrap().len();
    let (used, c) = peak_while_reading(&path);
    std::fs::remove_file(&path).ok();
    assert_eq!(c.top_counts(), vec![0, 0, t as usize], "{ext}");
    let ratio = used as f64 / file_bytes as f64;
    eprintln!("{ext}: file {file_bytes} B, peak while reading {used} B ({ratio:.2}x)");
    assert!(
        used <= 5 * file_bytes,
        "{ext}: reading peaked at {used} B for a {file_bytes} B file"
    );
}

/// Set in the child processes: the one format to read.
const FORMAT_VAR: &str = "TOPOPLEX_MEMORY_TEST_FORMAT";
const TEST: &str = "reading_large_files_peaks_within_five_times_the_file";
