//! The large benchmark's driver (`scripts/bench.sh --large`): writes generated datasets and
//! times each phase of reading, building, saving and opening them.
//!
//! - `scale grid K OUT.mesh`: a K×K×K Freudenthal tetrahedral grid (~26K³ simplices) as MEDIT;
//! - `scale loop L OUT.off`: an icosahedron Loop-subdivided L times (20·4^L triangles) as OFF;
//! - `scale rips N DIM OUT.simplices`: the Rips complex of N random points in the unit square
//!   at the radius giving ~12 neighbours, up to dimension DIM, as `.simplices`;
//! - `scale phases FILE KIND THREADS TPX`: parse, normalise and build (THREADS threads), save
//!   to TPX, open, vertex-star walks on the opened structure; one `phase seconds peak_rss_mib
//!   cpu_seconds main_thread_cpu_seconds` line each.
//! - `scale soup FILE THREADS KIND,..`: what the side-by-side `build` op times (a complex from
//!   the listing's arrays, then the structure), best of 5, with the complex's share and the
//!   least CPU time of the 5 on the calling thread (the whole build's with one thread);
//!   `iastar` (the live complex) is accepted besides the nine kinds, here and in `structures`;
//! - `scale structures FILE THREADS [KIND,..]`: builds each structure (every kind, or the
//!   listed ones) with 1 and with THREADS threads, one `kind seconds_1 seconds_N same` line
//!   each, `same` saying whether both builds save to the same bytes.
//!
//! Generated data is never committed; the numbers go to docs/benchmarks.md.

use std::io::{BufWriter, Write};
use std::path::Path;
use std::time::Instant;

use topoplex::StructureKind;
use topoplex::fixtures::freudenthal_grid;
use topoplex::store::Saved;

fn peak_mib() -> f64 {
    let status = std::fs::read_to_string("/proc/self/status").unwrap_or_default();
    status
        .lines()
        .find_map(|l| l.strip_prefix("VmHWM:"))
        .and_then(|v| v.trim().trim_end_matches("kB").trim().parse::<f64>().ok())
        .map_or(0.0, |kb| kb / 1024.0)
}

/// This thread's CPU time in seconds (the first field of /proc/thread-self/schedstat, in ns;
/// 0 where that file is missing): with one thread, a build's time without the waits that other
/// processes on a loaded machine add to its wall time.
fn thread_cpu() -> f64 {
    std::fs::read_to_string("/proc/thread-self/schedstat")
        .ok()
        .and_then(|s| s.split_whitespace().next()?.parse::<f64>().ok())
        .map_or(0.0, |ns| ns * 1e-9)
}

fn grid(k: u32, out: &Path) -> std::io::Result<()> {
    let n = k + 1;
    let mut w = BufWriter::with_capacity(1 << 20, std::fs::File::create(out)?);
    writeln!(
        w,
        "MeshVersionFormatted 1\nDimension 3\nVertices\n{}",
        n * n * n
    )?;
    for x in 0..n {
        for y in 0..n {
            for z in 0..n {
                writeln!(w, "{x} {y} {z} 0")?;
            }
        }
    }
    writeln!(w, "Tetrahedra\n{}", 6 * (k as u64).pow(3))?;
    for [a, b, c, d] in freudenthal_grid(k, |[x, y, z]| (x * n + y) * n + z + 1) {
        writeln!(w, "{a} {b} {c} {d} 0")?;
    }
    writeln!(w, "End")?;
    w.flush()
}

fn loop_surface(levels: u32, out: &Path) -> std::io::Result<()> {
    let t = (1.0 + 5f64.sqrt()) / 2.0;
    let mut pts: Vec<[f64; 3]> = vec![
        [-1., t, 0.],
        [1., t, 0.],
        [-1., -t, 0.],
        [1., -t, 0.],
        [0., -1., t],
        [0., 1., t],
        [0., -1., -t],
        [0., 1., -t],
        [t, 0., -1.],
        [t, 0., 1.],
        [-t, 0., -1.],
        [-t, 0., 1.],
    ];
    let mut tris: Vec<[u32; 3]> = vec![
        [0, 11, 5],
        [0, 5, 1],
        [0, 1, 7],
        [0, 7, 10],
        [0, 10, 11],
        [1, 5, 9],
        [5, 11, 4],
        [11, 10, 2],
        [10, 7, 6],
        [7, 1, 8],
        [3, 9, 4],
        [3, 4, 2],
        [3, 2, 6],
        [3, 6, 8],
        [3, 8, 9],
        [4, 9, 5],
        [2, 4, 11],
        [6, 2, 10],
        [8, 6, 7],
        [9, 8, 1],
    ];
    for _ in 0..levels {
        // Midpoint subdivision (the connectivity of Loop's scheme; positions are not smoothed,
        // which does not change the topology the benchmark measures).
        let mut mid = std::collections::HashMap::new();
        let mut next = Vec::with_capacity(tris.len() * 4);
        let mut m = |a: u32, b: u32, pts: &mut Vec<[f64; 3]>| {
            *mid.entry((a.min(b), a.max(b))).or_insert_with(|| {
                let (p, q) = (pts[a as usize], pts[b as usize]);
                pts.push([(p[0] + q[0]) / 2., (p[1] + q[1]) / 2., (p[2] + q[2]) / 2.]);
                pts.len() as u32 - 1
            })
        };
        for [a, b, c] in tris {
            let (ab, bc, ca) = (m(a, b, &mut pts), m(b, c, &mut pts), m(c, a, &mut pts));
            next.extend_from_slice(&[[a, ab, ca], [b, bc, ab], [c, ca, bc], [ab, bc, ca]]);
        }
        tris = next;
    }
    let mut w = BufWriter::with_capacity(1 << 20, std::fs::File::create(out)?);
    writeln!(w, "OFF\n{} {} 0", pts.len(), tris.len())?;
    for p in &pts {
        writeln!(w, "{} {} {}", p[0], p[1], p[2])?;
    }
    for [a, b, c] in &tris {
        writeln!(w, "3 {a} {b} {c}")?;
    }
    w.flush()
}

fn rips(n: u32, dim: usize, out: &Path) -> std::io::Result<()> {
    let mut x = 0x2545_f491_4f6c_dd1du64;
    let mut rnd = || {
        x ^= x << 13;
        x ^= x >> 7;
        x ^= x << 17;
        (x >> 11) as f64 / (1u64 << 53) as f64
    };
    let pts: Vec<[f64; 2]> = (0..n).map(|_| [rnd(), rnd()]).collect();
    let r = (12.0 / (std::f64::consts::PI * n as f64)).sqrt();
    let cells = (1.0 / r).floor().max(1.0) as usize;
    let cell = |p: [f64; 2]| {
        let c = |v: f64| ((v * cells as f64) as usize).min(cells - 1);
        (c(p[0]), c(p[1]))
    };
    let mut grid = vec![Vec::new(); cells * cells];
    for (i, &p) in pts.iter().enumerate() {
        let (a, b) = cell(p);
        grid[a * cells + b].push(i as u32);
    }
    let close = |i: u32, j: u32| {
        let (p, q) = (pts[i as usize], pts[j as usize]);
        (p[0] - q[0]).powi(2) + (p[1] - q[1]).powi(2) <= r * r
    };
    let mut nbrs: Vec<Vec<u32>> = vec![Vec::new(); n as usize];
    for (i, &p) in pts.iter().enumerate() {
        let (a, b) = cell(p);
        for da in a.saturating_sub(1)..=(a + 1).min(cells - 1) {
            for db in b.saturating_sub(1)..=(b + 1).min(cells - 1) {
                for &j in &grid[da * cells + db] {
                    if j > i as u32 && close(i as u32, j) {
                        nbrs[i].push(j);
                    }
                }
            }
        }
        nbrs[i].sort_unstable();
    }
    // Maximal cliques are not needed: listing every simplex up to `dim` (faces are absorbed).
    let mut w = BufWriter::with_capacity(1 << 20, std::fs::File::create(out)?);
    let mut stack = Vec::new();
    for v in 0..n {
        writeln!(w, "s {v}")?;
        stack.clear();
        stack.push((vec![v], nbrs[v as usize].clone()));
        while let Some((s, cand)) = stack.pop() {
            for (k, &c) in cand.iter().enumerate() {
                let mut t = s.clone();
                t.push(c);
                if t.len() == dim + 1 {
                    let line: Vec<String> = t.iter().map(u32::to_string).collect();
                    writeln!(w, "s {}", line.join(" "))?;
                } else {
                    let rest: Vec<u32> = cand[k + 1..]
                        .iter()
                        .copied()
                        .filter(|&u| close(c, u))
                        .collect();
                    if rest.is_empty() {
                        let line: Vec<String> = t.iter().map(u32::to_string).collect();
                        writeln!(w, "s {}", line.join(" "))?;
                    } else {
                        stack.push((t, rest));
                    }
                }
            }
        }
    }
    w.flush()
}

/// CPU seconds (user + system) of the process and of the calling thread so far, from
/// `/proc` (clock ticks of 1/100 s).
fn cpu_seconds() -> (f64, f64) {
    let ticks = |path: &str| {
        let stat = std::fs::read_to_string(path).unwrap_or_default();
        // Fields after the command name (which ends with the last ')'): utime is the 12th.
        let rest = stat.rsplit_once(')').map_or("", |(_, r)| r);
        let f: Vec<f64> = rest
            .split_whitespace()
            .skip(11)
            .take(2)
            .filter_map(|x| x.parse().ok())
            .collect();
        f.iter().sum::<f64>() / 100.0
    };
    (ticks("/proc/self/stat"), ticks("/proc/thread-self/stat"))
}

fn phases(file: &Path, kind: StructureKind, threads: usize, tpx: &Path) {
    // Columns: phase, wall seconds, peak MiB, then the phase's CPU seconds for the whole
    // process and for the main thread alone. The main thread waits while the pool works, so
    // its CPU is the phase's serial part: on a busy machine, where wall time mostly measures
    // waiting, `main + (cpu - main) / THREADS` estimates the phase's quiet wall time.
    let cpu_at = std::cell::Cell::new(cpu_seconds());
    let line = |what: &str, t: Instant| {
        let (c0, m0) = cpu_at.get();
        let (c, m) = cpu_seconds();
        cpu_at.set((c, m));
        println!(
            "{what} {:.3} {:.0} {:.2} {:.2}",
            t.elapsed().as_secs_f64(),
            peak_mib(),
            c - c0,
            m - m0
        );
    };
    // Reading and normalising run on THREADS threads too, as in `topoplex --threads`.
    topoplex::parallel::set_threads(threads);
    let t = Instant::now();
    let raw = topoplex::io::read_path(file).expect("read");
    line("parse", t);
    let t = Instant::now();
    // What `Complex::from_path` does after reading: the complex keeps the parsed arrays.
    let complex =
        topoplex::Complex::from_input(raw, Some(file), Default::default()).expect("complex");
    line("complex", t);
    let t = Instant::now();
    let s = topoplex::build(kind, &complex).expect("build");
    line("build", t);
    let simplices: usize = (0..=s.dimension()).map(|p| s.count(p)).sum();
    println!("simplices {simplices} {:.0}", peak_mib());
    println!("bytes_retained {} {:.0}", s.storage().bytes, peak_mib());
    let t = Instant::now();
    topoplex::store::save(tpx, &complex, Some(s.as_ref())).expect("save");
    line("save", t);
    drop(s);
    drop(complex);
    let t = Instant::now();
    let saved = Saved::open(tpx).expect("open");
    let opened = saved.structure().expect("structure").expect("saved");
    let mut out = Vec::new();
    opened
        .relation(&[0], opened.dimension(), &mut out)
        .expect("query");
    line("open+query", t);
    let t = Instant::now();
    let n = opened.vertex_count();
    let mut found = 0usize;
    let step = (n / 100_000).max(1);
    let mut walks = 0;
    for v in (0..n).step_by(step as usize) {
        opened
            .relation(&[v], opened.dimension(), &mut out)
            .expect("walk");
        found += out.len();
        walks += 1;
    }
    println!(
        "walks {:.3} {:.0} ({walks} vertex stars, {found} ids)",
        t.elapsed().as_secs_f64(),
        peak_mib()
    );
}

/// Best of `reps` builds (the first also warms the pool), and the saved bytes of the last.
fn timed_build(c: &topoplex::Complex, kind: StructureKind, threads: usize) -> (f64, Vec<u8>) {
    topoplex::parallel::set_threads(threads);
    let mut best = f64::INFINITY;
    let mut bytes = Vec::new();
    for _ in 0..2 {
        let t = Instant::now();
        let Ok(s) = topoplex::build(kind, c) else {
            return (f64::NAN, Vec::new());
        };
        best = best.min(t.elapsed().as_secs_f64());
        let path = std::env::temp_dir().join(format!("scale-{}.tpx", std::process::id()));
        topoplex::store::save(&path, c, Some(s.as_ref())).expect("save");
        bytes = std::fs::read(&path).expect("read back");
        std::fs::remove_file(&path).ok();
    }
    (best, bytes)
}

fn structures(file: &Path, threads: usize, kinds: &[StructureKind]) {
    let t = Instant::now();
    let c = topoplex::Complex::from_path(file).expect("complex");
    println!("read+complex {:.3}", t.elapsed().as_secs_f64());
    for &kind in kinds {
        let (t1, b1) = timed_build(&c, kind, 1);
        let (tn, bn) = timed_build(&c, kind, threads);
        println!("{kind} {t1:.3} {tn:.3} {}", b1 == bn);
    }
}

fn soup(file: &Path, threads: usize, kinds: &[StructureKind]) {
    let raw = topoplex::io::read_path(file).expect("read");
    let n = raw
        .vertex_count
        .unwrap_or_else(|| raw.ids.iter().max().map_or(0, |m| m + 1));
    topoplex::parallel::set_threads(threads);
    for &kind in kinds {
        let (mut best, mut complex_best, mut cpu_best) =
            (f64::INFINITY, f64::INFINITY, f64::INFINITY);
        let mut simplices = 0;
        for _ in 0..5 {
            let cpu = thread_cpu();
            let t = Instant::now();
            let c =
                topoplex::Complex::from_arrays(n, &raw.ids, &raw.offsets, None).expect("complex");
            let tc = t.elapsed().as_secs_f64();
            let s = topoplex::build(kind, &c).expect("build");
            let all = t.elapsed().as_secs_f64();
            cpu_best = cpu_best.min(thread_cpu() - cpu);
            if simplices == 0 {
                // Once: the live complex counts by enumerating its faces.
                simplices = (0..=s.dimension()).map(|p| s.count(p)).sum::<usize>();
            }
            if all < best {
                (best, complex_best) = (all, tc);
            }
        }
        println!(
            "{kind} {best:.6} s (complex {complex_best:.6} s) {simplices} simplices {:.1} ns/simplex, this thread's CPU {cpu_best:.6} s",
            best * 1e9 / simplices as f64
        );
    }
}

/// A kind by its CLI name (`iastar` included).
fn kind_named(name: &str) -> StructureKind {
    StructureKind::from_name(name).expect("structure name")
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let a: Vec<&str> = args.iter().map(String::as_str).collect();
    let done = match a.as_slice() {
        ["grid", k, out] => grid(k.parse().unwrap(), Path::new(out)),
        ["loop", l, out] => loop_surface(l.parse().unwrap(), Path::new(out)),
        ["rips", n, d, out] => rips(n.parse().unwrap(), d.parse().unwrap(), Path::new(out)),
        ["phases", file, kind, threads, tpx] => {
            // As the `topoplex` CLI does: a fixed mmap threshold, so that glibc's per-thread
            // arenas do not keep freed arrays resident (the peaks are then the CLI's). Only
            // here: it costs the timing loops below fresh pages for every large array.
            topoplex::sys::fix_malloc_thresholds_for_executable();
            let kind = kind_named(kind);
            phases(
                Path::new(file),
                kind,
                threads.parse().unwrap(),
                Path::new(tpx),
            );
            Ok(())
        }
        ["soup", file, threads, list] => {
            let kinds: Vec<StructureKind> = list.split(',').map(kind_named).collect();
            soup(Path::new(file), threads.parse().unwrap(), &kinds);
            Ok(())
        }
        ["structures", file, threads, rest @ ..] => {
            let kinds: Vec<StructureKind> = match rest {
                [] => StructureKind::ALL.to_vec(),
                [list] => list.split(',').map(kind_named).collect(),
                _ => panic!("usage: scale structures FILE THREADS [KIND,..]"),
            };
            structures(Path::new(file), threads.parse().unwrap(), &kinds);
            Ok(())
        }
        _ => {
            eprintln!("usage: see the module doc of examples/scale.rs");
            std::process::exit(2);
        }
    };
    done.expect("writing the dataset");
}
