//! Shared test support: random non-manifold complexes for property tests, and the real data in
//! `../shared/data` when present.
#![allow(dead_code)]

pub mod nav;

/// R_{p,q}(sigma) of `s` as rows of q + 1 ids, in ascending lexicographic order.
pub fn rel(s: &dyn topoplex::Topology, sigma: &[u32], q: usize) -> Vec<Vec<u32>> {
    let mut out = Vec::new();
    s.relation(sigma, q, &mut out).unwrap();
    topoplex::relation::sort_rows(&mut out, q + 1);
    out.chunks(q + 1).map(<[u32]>::to_vec).collect()
}

/// A complex built through the C ABI (`tpx_complex_from_arrays`) over `n` vertices from
/// `simplices`, with `coords` (3 per vertex) when given; the caller frees it. Panics on a
/// refusal, with the library's message.
pub fn c_complex(
    n: u32,
    simplices: &[&[u32]],
    coords: Option<&[f64]>,
) -> *mut topoplex_ffi::TpxComplex {
    use topoplex_ffi::*;
    let ids: Vec<u32> = simplices.concat();
    let mut offsets = vec![0usize];
    offsets.extend(simplices.iter().scan(0, |end, s| {
        *end += s.len();
        Some(*end)
    }));
    let (xyz, dim) = coords.map_or((std::ptr::null(), 0), |c| (c.as_ptr(), 3));
    let mut out = std::ptr::null_mut();
    // SAFETY: arrays of the stated lengths.
    let st = unsafe {
        let (ids, offsets) = (ids.as_ptr(), offsets.as_ptr());
        tpx_complex_from_arrays(n, ids, offsets, simplices.len(), xyz, dim, &mut out)
    };
    // SAFETY: the message is never NULL and NUL-terminated.
    let message = unsafe { std::ffi::CStr::from_ptr(tpx_last_error_message()) };
    assert_eq!(st, TpxStatus::Ok, "{}", message.to_string_lossy());
    out
}

/// A simplex as refusals name it: `[a b c]`.
pub fn show(ids: &[u32]) -> String {
    let v: Vec<String> = ids.iter().map(|i| i.to_string()).collect();
    format!("[{}]", v.join(" "))
}

/// The reason of a build refused as unsupported; panics on a success or another error.
pub fn refusal_of<T>(built: Result<T, topoplex::BuildError>) -> String {
    match built {
        Err(topoplex::BuildError::Unsupported { reason, .. }) => reason,
        other => panic!("expected a refusal, got {:?}", other.map(|_| ())),
    }
}

/// A structure built and validated, panicking with the error of either.
pub fn validated<S: topoplex::Topology, E: std::fmt::Debug>(built: Result<S, E>) -> S {
    let s = built.unwrap();
    s.validate().unwrap();
    s
}

/// A structure that refuses some complexes, checked on `c`: refused naming `expected` (the
/// offending simplex the brute force found), or, when there is none, accepted, valid, storing
/// what `check_storage` counts and matching the oracle.
pub fn refused_or_matches<S: topoplex::Topology>(
    c: &Complex,
    expected: Option<Vec<u32>>,
    build: fn(&Complex) -> Result<S, topoplex::BuildError>,
    check_storage: fn(&S, &Complex),
) -> Result<(), TestCaseError> {
    match expected {
        Some(bad) => {
            let r = refusal_of(build(c));
            prop_assert!(
                r.contains(&show(&bad)),
                "reason {} should name {:?}",
                r,
                bad
            );
        }
        None => {
            let s = validated(build(c));
            check_storage(&s, c);
            prop_assert_eq!(topoplex::oracle::check_structure(&s, c), Ok(()));
        }
    }
    Ok(())
}

/// Builds every kind; returns the ones that encode `c`, validated. A kind that is not
/// implemented yet or refuses the complex is skipped; any other failure panics.
pub fn buildable(c: &Complex, what: &str) -> Vec<Box<dyn topoplex::Topology>> {
    let mut out = Vec::new();
    for kind in topoplex::StructureKind::ALL {
        match topoplex::build(kind, c) {
            Ok(s) => {
                s.validate()
                    .unwrap_or_else(|e| panic!("{what}: {kind}: validate: {e}"));
                assert_eq!(s.kind(), kind);
                out.push(s);
            }
            Err(topoplex::BuildError::NotImplemented { .. })
            | Err(topoplex::BuildError::Unsupported { .. }) => {}
            Err(e) => panic!("{what}: {kind}: {e}"),
        }
    }
    out
}

/// The root of `i` in the union-find forest `parent` (`parent[r] == r` at a root), the path
/// compressed on the way: a brute force's connected components.
pub fn root(parent: &mut [usize], i: usize) -> usize {
    if parent[i] == i {
        i
    } else {
        let r = root(parent, parent[i]);
        parent[i] = r;
        r
    }
}

/// The one 15-simplex over vertices 0..16, and its vertices.
pub fn fifteen_simplex() -> (Complex, Vec<u32>) {
    let top: Vec<u32> = (0..16).collect();
    (Complex::from_simplices(16, &[&top]).unwrap(), top)
}

/// What every structure answers on [`fifteen_simplex`]: C(16, 8) 7-faces, the 15-simplex as a
/// vertex's star, eight 14-faces around a 7-face; `out` holds the last answer.
pub fn check_fifteen_simplex(s: &dyn topoplex::Topology, top: &[u32], out: &mut Vec<u32>) {
    assert_eq!(s.count(7), 12870);
    s.relation(&[3], 15, out).unwrap();
    assert_eq!(out.as_slice(), top);
    s.relation(&[0, 1, 2, 3, 4, 5, 6, 7], 14, out).unwrap();
    assert_eq!(out.len() / 15, 8);
}

/// The refusal of a query on a simplex that is not in [`topoplex::fixtures::bowtie`] (the
/// edge 0-3), which names it and leaves `out` empty.
pub fn check_bowtie_refusal(s: &dyn topoplex::Topology, out: &mut Vec<u32>) {
    out.push(99);
    let e = s.relation(&[0, 3], 2, out).unwrap_err();
    assert_eq!(e.to_string(), "simplex [0 3] is not in the complex");
    assert!(out.is_empty());
}

/// The `topoplex` binary run with `args`, its output collected.
pub fn run(args: &[&str]) -> std::process::Output {
    std::process::Command::new(env!("CARGO_BIN_EXE_topoplex"))
        .args(args)
        .output()
        .expect("binary runs")
}

/// A small xorshift generator (no dependency, reproducible): one seed draws a whole fixture.
pub struct Rng(pub u64);

impl Rng {
    /// The next 64 random bits.
    pub fn next(&mut self) -> u64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        self.0
    }

    /// A number below `n` (`n` > 0).
    pub fn below(&mut self, n: usize) -> usize {
        (self.next() % n as u64) as usize
    }
}

use std::path::PathBuf;

use proptest::prelude::*;
use topoplex::Complex;

/// A vertex count and a list of simplices (vertex ids in shuffled order, duplicates and faces
/// of other simplices included) over few vertices, so that simplices collide into non-manifold
/// vertices and edges, wire edges and isolated vertices; dimension up to `max_dim`.
pub fn random_input(
    max_dim: usize,
    max_vertices: u32,
    max_simplices: usize,
) -> impl Strategy<Value = (u32, Vec<Vec<u32>>)> {
    (1..=max_vertices).prop_flat_map(move |n| {
        let all: Vec<u32> = (0..n).collect();
        let simplex =
            proptest::sample::subsequence(all, 1..=(max_dim + 1).min(n as usize)).prop_shuffle();
        let list = proptest::collection::vec(simplex, 0..=max_simplices);
        // Repeat a few simplices to exercise absorption of duplicates.
        (
            Just(n),
            list,
            proptest::collection::vec(any::<prop::sample::Index>(), 0..3),
        )
            .prop_map(|(n, mut list, dups)| {
                if !list.is_empty() {
                    for i in dups {
                        let s = list[i.index(list.len())].clone();
                        list.push(s);
                    }
                }
                (n, list)
            })
    })
}

pub fn complex_of(n: u32, simplices: &[Vec<u32>]) -> Complex {
    let refs: Vec<&[u32]> = simplices.iter().map(Vec::as_slice).collect();
    Complex::from_simplices(n, &refs).expect("generated input is valid")
}

/// The complex of a [`random_input`] (its strategy, shrinking as it does).
pub fn random_complex(
    max_dim: usize,
    max_vertices: u32,
    max_simplices: usize,
) -> impl Strategy<Value = Complex> {
    random_input(max_dim, max_vertices, max_simplices).prop_map(|(n, list)| complex_of(n, &list))
}

/// `../shared/data` relative to the crate (or `$TOPOPLEX_SHARED_DATA` when set, for a checkout
/// elsewhere), if present.
pub fn shared_data() -> Option<PathBuf> {
    let dir = match std::env::var_os("TOPOPLEX_SHARED_DATA") {
        Some(d) => PathBuf::from(d),
        None => PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../shared/data"),
    };
    dir.is_dir().then_some(dir)
}

/// Every readable complex file under `../shared/data` (files that are documented error cases,
/// like quad meshes, are returned too: callers decide).
pub fn shared_files() -> Vec<PathBuf> {
    let Some(dir) = shared_data() else {
        eprintln!("../shared/data is absent: skipping real-data checks");
        return Vec::new();
    };
    let mut files = Vec::new();
    for sub in std::fs::read_dir(&dir).unwrap().flatten() {
        if sub.path().is_dir() {
            for f in std::fs::read_dir(sub.path()).unwrap().flatten() {
                files.push(f.path());
            }
        }
    }
    files.sort();
    files
}

/// Every file of [`shared_files`] that reads as a complex, with its complex, read one at a time
/// as the iterator advances (the documented error cases, like quad meshes, are skipped).
pub fn shared_complexes() -> impl Iterator<Item = (PathBuf, Complex)> {
    shared_files()
        .into_iter()
        .filter_map(|p| Complex::from_path(&p).ok().map(|c| (p, c)))
}

/// Calls `f(path, complex)` for every complex of [`shared_complexes`] in a file of at most
/// `max_bytes` (`u64::MAX`: every file), the files shared out to as many threads as the machine
/// has cores (at most 4), each file read in the thread that checks it. For the real-data sweeps
/// that walk every relation of every structure: on two cores the test harness's other thread had
/// long finished while one such sweep still ran alone. A panic in `f` fails the test (the scope
/// re-raises it once every thread is done).
pub fn for_each_shared_complex(max_bytes: u64, f: impl Fn(&std::path::Path, Complex) + Sync) {
    let files = shared_files();
    let next = std::sync::atomic::AtomicUsize::new(0);
    let threads = std::thread::available_parallelism().map_or(1, |n| n.get().min(4));
    std::thread::scope(|scope| {
        for _ in 0..threads {
            scope.spawn(|| {
                loop {
                    let i = next.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
                    let Some(path) = files.get(i) else { break };
                    if std::fs::metadata(path).map_or(true, |m| m.len() > max_bytes) {
                        continue;
                    }
                    if let Ok(c) = Complex::from_path(path) {
                        f(path, c);
                    }
                }
            });
        }
    });
}

/// A scratch directory under the temp dir (named by the process, `tag` and the thread, so
/// parallel tests do not meet), removed on drop.
pub struct Scratch(pub PathBuf);

impl Scratch {
    pub fn new(tag: &str) -> Scratch {
        let dir = std::env::temp_dir().join(format!(
            "topoplex-test-{}-{tag}-{:?}",
            std::process::id(),
            std::thread::current().id()
        ));
        std::fs::create_dir_all(&dir).unwrap();
        Scratch(dir)
    }
}

impl Drop for Scratch {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

/// Checks that the generated `table` stands between `<!-- {section}:begin -->` and
/// `<!-- {section}:end -->` in docs/bad-input.md, or writes it there when
/// `TOPOPLEX_WRITE_BAD_INPUT_DOC` is set. `test` names the test target that regenerates it.
pub fn check_bad_input_doc(section: &str, table: &str, test: &str) {
    // One table at a time: the tables of tests/it/bad_input.rs and tests/it/hardening.rs live in
    // one file and one process, and a regeneration reads, edits and writes the whole file.
    static DOC: std::sync::Mutex<()> = std::sync::Mutex::new(());
    let _one = DOC
        .lock()
        .unwrap_or_else(std::sync::PoisonError::into_inner);
    let doc_path = format!("{}/docs/bad-input.md", env!("CARGO_MANIFEST_DIR"));
    let doc = std::fs::read_to_string(&doc_path).unwrap_or_default();
    let (begin, end) = (
        format!("<!-- {section}:begin -->\n"),
        format!("<!-- {section}:end -->"),
    );
    let (Some(a), Some(b)) = (doc.find(&begin), doc.find(&end)) else {
        panic!("docs/bad-input.md lacks the {section} table markers")
    };
    if std::env::var_os("TOPOPLEX_WRITE_BAD_INPUT_DOC").is_some() {
        let new = format!("{}{begin}{table}{}", &doc[..a], &doc[b..]);
        std::fs::write(&doc_path, new).unwrap();
        return;
    }
    assert_eq!(
        &doc[a + begin.len()..b],
        table,
        "docs/bad-input.md is stale: TOPOPLEX_WRITE_BAD_INPUT_DOC=1 cargo test --test {test}"
    );
}
