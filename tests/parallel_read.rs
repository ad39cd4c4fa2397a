//! Reading on several threads gives what reading on one gives: the same arrays for a good file,
//! the same first error (line and message) for a bad one. Each text is parsed with 1 thread and
//! with 2 and 3 threads with the split threshold lowered to 2, so that sections of a few lines
//! are cut into ranges of a line or two and every error lands next to a range's edge somewhere.
//! Random files (good ones, and good ones with one line broken in one of many ways), the
//! files of `../shared/data` when present.

mod common;
use common::Rng;

use topoplex::io::{RawInput, ReadErrorKind, medit, off, simplices};
use topoplex::parallel::{set_split_threshold, set_threads};
use topoplex::testing::sections_read_in_parallel;

/// The thread count and split threshold are global: one test at a time sets them.
static GLOBALS: std::sync::Mutex<()> = std::sync::Mutex::new(());

type Parse = fn(&str) -> Result<RawInput, (u32, ReadErrorKind)>;

/// Parses `text` with 1, 2 and 3 threads (threshold 2 when several) and asserts the same
/// outcome; returns it.
fn same_on_every_thread_count(parse: Parse, text: &str) -> Result<RawInput, (u32, ReadErrorKind)> {
    set_split_threshold(usize::MAX);
    set_threads(1);
    let serial = parse(text);
    set_split_threshold(2);
    for t in [2, 3] {
        set_threads(t);
        let got = parse(text);
        assert_eq!(got, serial, "{t} threads differ from 1 on:\n{text}");
    }
    set_threads(1);
    serial
}

/// A MEDIT file of `nv` vertices and `nt` tetrahedra (random ids), one entry a line.
fn medit_text(rng: &mut Rng, nv: usize, nt: usize) -> Vec<String> {
    let mut lines = vec![
        "MeshVersionFormatted 2".to_string(),
        "Dimension 3".into(),
        "Vertices".into(),
        nv.to_string(),
    ];
    for i in 0..nv {
        lines.push(format!(
            "{} {}.5 -{}e-3 {}",
            i,
            rng.below(100),
            rng.below(9),
            i % 3
        ));
    }
    lines.push("Tetrahedra".into());
    lines.push(format!("{nt} # tets"));
    for _ in 0..nt {
        let v: Vec<String> = (0..4).map(|_| (1 + rng.below(nv)).to_string()).collect();
        lines.push(format!("{} 0", v.join(" ")));
    }
    lines.push("End".into());
    lines
}

/// An OFF file of `nv` vertices and `nf` triangles (random ids), one entry a line.
fn off_text(rng: &mut Rng, nv: usize, nf: usize) -> Vec<String> {
    let mut lines = vec!["OFF".to_string(), format!("{nv} {nf} 0")];
    for i in 0..nv {
        lines.push(format!("{i} {}.25 {}", rng.below(50), rng.below(7)));
    }
    for _ in 0..nf {
        let v: Vec<String> = (0..3).map(|_| rng.below(nv).to_string()).collect();
        lines.push(format!("3 {}", v.join(" ")));
    }
    lines
}

/// A `.simplices` file: `v` lines (some files have none) and `s` lines of 1 to 4 ids,
/// interleaved, with blank and comment lines now and then.
fn simplices_text(rng: &mut Rng, nv: usize, ns: usize) -> Vec<String> {
    let with_v = rng.below(4) != 0;
    let dim = rng.below(3);
    let mut lines = Vec::new();
    let (mut v, mut s) = (0, 0);
    while v < nv * usize::from(with_v) || s < ns {
        if with_v && v < nv && (s == ns || rng.below(3) == 0) {
            let xs: Vec<String> = (0..dim).map(|_| format!("{}.5", rng.below(9))).collect();
            lines.push(format!("v {}", xs.join(" ")).trim_end().to_string());
            v += 1;
        } else {
            let ids: Vec<String> = (0..1 + rng.below(4))
                .map(|_| rng.below(nv).to_string())
                .collect();
            lines.push(format!("s {}", ids.join(" ")));
            s += 1;
        }
        match rng.below(20) {
            0 => lines.push(String::new()),
            1 => lines.push("# comment".into()),
            _ => {}
        }
    }
    lines
}

/// One way to break or bend a line: what the serial reader must decide, and the parallel one
/// must agree with.
fn bend(rng: &mut Rng, line: &str) -> String {
    let words: Vec<&str> = line.split(' ').collect();
    match rng.below(14) {
        0 => String::new(),                                         // blank line
        1 => "# a comment".into(),                                  // comment line
        2 => format!("{line} 7"),                                   // one number too many
        3 => words[..words.len() - 1].join(" "),                    // one too few
        4 => format!("{line}\n{line}"),                             // an extra entry
        5 => words.join("\n"),                                      // an entry across lines
        6 => line.replacen(words[0], "x", 1),                       // not a number
        7 => line.replacen(words[0], "0", 1),                       // id 0 (MEDIT) / fine (OFF)
        8 => line.replacen(words[0], "-3", 1),                      // negative
        9 => line.replacen(words[0], "1e999", 1),                   // overflow
        10 => format!("{line}   # trailing comment"),               // fine
        11 => format!("\t{}", words.join("\t")),                    // tabs: fine
        12 => line.replacen(words[0], "99999999999", 1),            // too large an id
        _ => format!("{} 1.5", words[..words.len() - 1].join(" ")), // a float reference
    }
}

fn join(lines: &[String], eol: &str, final_eol: bool) -> String {
    let mut t = lines.join(eol);
    if final_eol {
        t.push_str(eol);
    }
    t
}

#[test]
fn medit_off_and_simplices_read_the_same_on_every_thread_count() {
    let _one_at_a_time = GLOBALS.lock().unwrap_or_else(|e| e.into_inner());
    let before = sections_read_in_parallel();
    let mut rng = Rng(0x9e37_79b9_7f4a_7c15);
    let mut errors = 0;
    for case in 0..600 {
        let eol = ["\n", "\r\n", "\r"][case / 3 % 3];
        let final_eol = case % 5 != 0;
        let (nv, n) = (1 + rng.below(30), rng.below(40));
        let (parse, mut lines, first_entry): (Parse, _, _) = match case % 3 {
            0 => (medit::parse as Parse, medit_text(&mut rng, nv, n), 4),
            1 => (off::parse as Parse, off_text(&mut rng, nv, n), 2),
            _ => (
                simplices::parse as Parse,
                simplices_text(&mut rng, nv, n),
                0,
            ),
        };
        // Break 0 to 2 entry lines (the header is left alone).
        for _ in 0..case / 9 % 3 {
            let body = lines.len() - first_entry;
            let at = first_entry + rng.below(body.max(1));
            if at < lines.len() {
                lines[at] = bend(&mut rng, &lines[at]);
            }
        }
        // Sometimes cut the file short.
        if case % 7 == 3 {
            let keep = lines.len() - rng.below(4).min(lines.len());
            lines.truncate(keep);
        }
        let text = join(&lines, eol, final_eol);
        if same_on_every_thread_count(parse, &text).is_err() {
            errors += 1;
        }
    }
    assert!(
        errors > 40 && errors < 360,
        "{errors} of 400 files had errors"
    );
    assert!(
        sections_read_in_parallel() > before + 200,
        "the parallel path ran on {} sections only",
        sections_read_in_parallel() - before
    );
}

#[test]
fn shared_data_reads_the_same_on_every_thread_count() {
    let _one_at_a_time = GLOBALS.lock().unwrap_or_else(|e| e.into_inner());
    for path in common::shared_files() {
        let parse: Parse = match path.extension().and_then(|e| e.to_str()) {
            Some("mesh") => medit::parse,
            Some("off") => off::parse,
            Some("simplices") => simplices::parse,
            _ => continue,
        };
        let text = std::fs::read_to_string(&path).unwrap();
        // The whole read (the file read in pieces on several threads, then parsed) too.
        set_threads(1);
        let serial = topoplex::io::read_path(&path);
        set_split_threshold(2);
        set_threads(2);
        assert_eq!(topoplex::io::read_path(&path), serial, "{}", path.display());
        let before = sections_read_in_parallel();
        let got = same_on_every_thread_count(parse, &text);
        assert!(got.is_ok(), "{}: {got:?}", path.display());
        eprintln!(
            "{}: {} sections read in parallel",
            path.display(),
            sections_read_in_parallel() - before
        );
    }
}

/// What a complex is made of, for comparing two builds.
fn summary(c: &topoplex::Complex) -> (Vec<Vec<u32>>, Vec<Vec<u32>>, String) {
    let tops = (0..=c.dimension())
        .map(|p| c.tops(p).iter().flatten().copied().collect())
        .collect();
    let listing = (0..c.input_count())
        .map(|i| c.input_simplex(i).to_vec())
        .collect();
    (tops, listing, format!("{:?}", c.stats()))
}

/// `cases` inputs that `draw` makes (from the generator seeded `seed`, and the case number),
/// each read as from `path` serially without splitting, then with 2 and 3 threads split at
/// every 2 rows: the same complex or the same first error each time. Returns how many inputs
/// were refused.
fn the_same_on_every_thread_count(
    seed: u64,
    cases: usize,
    path: Option<&std::path::Path>,
    mut draw: impl FnMut(&mut Rng, usize) -> RawInput,
) -> usize {
    let _one_at_a_time = GLOBALS.lock().unwrap_or_else(|e| e.into_inner());
    let mut rng = Rng(seed);
    let mut refused = 0;
    for case in 0..cases {
        let raw = draw(&mut rng, case);
        let build = || topoplex::Complex::from_raw(&raw, path).map(|c| summary(&c));
        set_split_threshold(usize::MAX);
        set_threads(1);
        let serial = build();
        set_split_threshold(2);
        for t in [2, 3] {
            set_threads(t);
            assert_eq!(build(), serial, "{t} threads, case {case}");
        }
        set_threads(1);
        refused += usize::from(serial.is_err());
    }
    refused
}

#[test]
fn complexes_are_checked_and_sorted_the_same_on_every_thread_count() {
    let path = Some(std::path::Path::new("r.simplices"));
    let refused = the_same_on_every_thread_count(0x2545_f491_4f6c_dd1d, 300, path, |rng, case| {
        let n = 2 + rng.below(12) as u32;
        let mut raw = RawInput::new();
        raw.vertex_count = Some(n);
        for i in 0..rng.below(60) {
            let len = 1 + rng.below(4);
            let mut s: Vec<u32> = (0..len).map(|_| rng.below(n as usize) as u32).collect();
            s.sort_unstable();
            s.dedup();
            if rng.below(3) == 0 {
                s.reverse(); // a winding that is not ascending
            }
            // Now and then a simplex the complex model refuses.
            match (case % 4, rng.below(40)) {
                (1, 0) => s.push(s[0]),
                (2, 0) => s.push(n + rng.below(3) as u32),
                (3, 0) => s = (0..17).collect(),
                (3, 1) => s.clear(),
                _ => {}
            }
            raw.push(&s, i as u32 + 1);
        }
        raw
    });
    assert!(refused > 30, "only {refused} of 300 inputs refused");
}

/// Inputs large enough (over 2 × 2^18 rows of one dimension) for the normaliser to deduplicate
/// by blocks: windows of simplices pushed in order, then (once blocks stop halving) rows written
/// in place. Many duplicates (blocks keep halving) or none; a refused simplex early, late, or
/// none.
#[test]
fn large_inputs_deduplicated_by_blocks_are_normalised_the_same_on_every_thread_count() {
    let _one_at_a_time = GLOBALS.lock().unwrap_or_else(|e| e.into_inner());
    let count = (1 << 19) + 12_345;
    for (dups, bad_at) in [
        (true, None),
        (false, None),
        (true, Some(300_000)),
        (false, Some(count - 7)),
        (false, Some(1 << 18)),
    ] {
        let mut rng = Rng(0x1234_5678_9abc_def1);
        let n: u32 = if dups { 40 } else { 1 << 20 };
        let mut raw = RawInput::new();
        raw.vertex_count = Some(n);
        for i in 0..count {
            let mut s = [0u32; 3];
            loop {
                for x in &mut s {
                    *x = rng.below(n as usize) as u32;
                }
                if s[0] != s[1] && s[1] != s[2] && s[0] != s[2] {
                    break;
                }
            }
            if bad_at == Some(i) {
                s[2] = s[0];
            }
            raw.push(&s, i as u32 + 1);
        }
        // A few edges and tetrahedra too.
        raw.push(&[0, 1], 0);
        raw.push(&[0, 1, 2, 3], 0);
        let build = || topoplex::Complex::from_raw(&raw, None).map(|c| summary(&c));
        set_split_threshold(usize::MAX);
        set_threads(1);
        let serial = build();
        assert_eq!(serial.is_err(), bad_at.is_some());
        set_split_threshold(2);
        set_threads(2);
        let parallel = build();
        set_threads(1);
        assert!(parallel == serial, "dups {dups}, refused at {bad_at:?}");
    }
}

/// Listings as Rips and alpha makers write them — rows ascending, each dimension in
/// lexicographic order, so neither rows nor tables are sorted — with repeats, faces of listed
/// simplices, and now and then one bad simplex: the same complex (or first error) on every
/// thread count, every range edge landing somewhere (threshold 2).
#[test]
fn ascending_listings_are_normalised_the_same_on_every_thread_count() {
    let refused = the_same_on_every_thread_count(0x0dd_ba11_5eed_1234, 200, None, |rng, case| {
        let n = 3 + rng.below(30) as u32;
        let mut listed: Vec<Vec<u32>> = (0..rng.below(80))
            .map(|_| {
                let mut s: Vec<u32> = (0..1 + rng.below(5))
                    .map(|_| rng.below(n as usize) as u32)
                    .collect();
                s.sort_unstable();
                s.dedup();
                s
            })
            .collect();
        for i in 0..listed.len() {
            match rng.below(6) {
                0 if listed[i].len() > 1 => listed.push(listed[i][1..].to_vec()),
                1 => listed.push(listed[i].clone()),
                _ => {}
            }
        }
        listed.sort_by(|a, b| (a.len(), a).cmp(&(b.len(), b)));
        if case % 3 == 1 && !listed.is_empty() {
            let at = rng.below(listed.len());
            listed[at] = match rng.below(3) {
                0 => vec![1, n + rng.below(4) as u32],
                1 => vec![2, 2],
                _ => Vec::new(),
            };
        }
        let mut raw = RawInput::new();
        raw.vertex_count = Some(n);
        for (i, s) in listed.iter().enumerate() {
            raw.push(s, i as u32 + 1);
        }
        raw
    });
    assert!(refused > 30, "only {refused} of 200 inputs refused");
}
