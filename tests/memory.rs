//! Bounded resources: reading and normalising a large file peaks within a small multiple of
//! the file size (documented in docs/bad-input.md). Linux only (reads /proc/self/status).

use std::io::Write;

fn status_kib(field: &str) -> Option<u64> {
    let s = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = s.lines().find(|l| l.starts_with(field))?;
    line.split_whitespace().nth(1)?.parse().ok()
}

#[test]
fn reading_a_large_off_peaks_within_five_times_the_file() {
    // Resetting the peak counter needs Linux >= 4.0; skip elsewhere.
    if std::fs::write("/proc/self/clear_refs", "5").is_err() || status_kib("VmHWM:").is_none() {
        eprintln!("no /proc peak-RSS reset here: skipping");
        return;
    }
    let k = 400u32; // a k×k grid of squares, two triangles each: 320,000 triangles
    let path = std::env::temp_dir().join(format!("topoplex-mem-{}.off", std::process::id()));
    {
        let mut w = std::io::BufWriter::new(std::fs::File::create(&path).unwrap());
        let n = (k + 1) * (k + 1);
        writeln!(w, "OFF\n{n} {} 0", 2 * k * k).unwrap();
        for y in 0..=k {
            for x in 0..=k {
                writeln!(w, "{x} {y} 0").unwrap();
            }
        }
        for y in 0..k {
            for x in 0..k {
                let a = y * (k + 1) + x;
                writeln!(
                    w,
                    "3 {a} {} {}\n3 {} {} {}",
                    a + 1,
                    a + k + 2,
                    a,
                    a + k + 2,
                    a + k + 1
                )
                .unwrap();
            }
        }
    }
    let file_bytes = std::fs::metadata(&path).unwrap().len();
    std::fs::write("/proc/self/clear_refs", "5").unwrap();
    let before = status_kib("VmRSS:").unwrap() * 1024;
    let c = topoplex::Complex::from_path(&path).unwrap();
    let peak = status_kib("VmHWM:").unwrap() * 1024;
    std::fs::remove_file(&path).ok();
    assert_eq!(c.top_counts(), vec![0, 0, 2 * k as usize * k as usize]);
    let used = peak.saturating_sub(before);
    eprintln!(
        "file {file_bytes} B, peak while reading {used} B ({:.2}x)",
        used as f64 / file_bytes as f64
    );
    assert!(
        used <= 5 * file_bytes,
        "reading peaked at {used} B for a {file_bytes} B file"
    );
}
