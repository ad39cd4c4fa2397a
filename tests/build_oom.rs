//! Issue 16, class 10 for structure builds and readers: under a raised budget a complex may be
//! as large as the caller allows, and a build whose arrays do not fit must say `TooLarge`, never
//! abort the process ("memory allocation failed"). Each structure is built in a child process
//! (this test binary run again) on a 180,000-triangle grid under `RLIMIT_AS` set 1 to 64 MB
//! above what the process already uses, so the build stops at its first, a later, or no array.
//! Each reader (every format, `.tpx` opened as a complex and as a live complex) reads a
//! 45,000-triangle grid (1 to 4 MB) the same way under margins of 0.5 to 32 MB. Linux only.

use std::process::Command;

use topoplex::StructureKind;

const CHILD: &str = "TOPOPLEX_BUILD_OOM_KIND";

/// The system allocator, which in the child names the failed allocation's caller on stderr
/// (lifting the limit first, so the backtrace can be printed) before passing the failure on.
struct Tell;

static LIMIT: std::sync::atomic::AtomicU64 = std::sync::atomic::AtomicU64::new(u64::MAX);

static TELLING: std::sync::atomic::AtomicBool = std::sync::atomic::AtomicBool::new(false);

// SAFETY: every call is forwarded to `System`; only the failure path adds a side effect.
unsafe impl std::alloc::GlobalAlloc for Tell {
    unsafe fn alloc(&self, layout: std::alloc::Layout) -> *mut u8 {
        // SAFETY: forwarded as is.
        let p = unsafe { std::alloc::System.alloc(layout) };
        if p.is_null() && !TELLING.swap(true, std::sync::atomic::Ordering::SeqCst) {
            let limit = LIMIT.load(std::sync::atomic::Ordering::SeqCst);
            set_address_space_limit(libc::RLIM_INFINITY);
            let bt = std::backtrace::Backtrace::force_capture().to_string();
            let ours: Vec<&str> = bt.lines().filter(|l| l.contains("topoplex::")).collect();
            eprintln!("failed {} bytes at {}", layout.size(), ours.join(" <- "));
            set_address_space_limit(limit);
            TELLING.store(false, std::sync::atomic::Ordering::SeqCst);
        }
        p
    }

    unsafe fn dealloc(&self, ptr: *mut u8, layout: std::alloc::Layout) {
        // SAFETY: forwarded as is.
        unsafe { std::alloc::System.dealloc(ptr, layout) }
    }
}

#[global_allocator]
static ALLOC: Tell = Tell;

/// The nine structures and the live complex (IA*, whose build is `LiveComplex::try_from_complex`).
const KINDS: [StructureKind; 10] = StructureKind::NAMED;

/// A k×k grid of squares, two triangles each, as a complex.
fn grid(k: u32) -> topoplex::Complex {
    let mut ids = Vec::with_capacity(6 * (k * k) as usize);
    for y in 0..k {
        for x in 0..k {
            let a = y * (k + 1) + x;
            ids.extend_from_slice(&[a, a + 1, a + k + 2, a, a + k + 2, a + k + 1]);
        }
    }
    let offsets: Vec<usize> = (0..=ids.len() / 3).map(|i| 3 * i).collect();
    topoplex::Complex::from_arrays((k + 1) * (k + 1), &ids, &offsets, None).unwrap()
}

fn vm_size_bytes() -> u64 {
    let s = std::fs::read_to_string("/proc/self/status").unwrap();
    let line = s.lines().find(|l| l.starts_with("VmSize:")).unwrap();
    line.split_whitespace()
        .nth(1)
        .unwrap()
        .parse::<u64>()
        .unwrap()
        * 1024
}

/// Margins above the current address space at which each build is tried, in MB: the smallest
/// stops the first input-sized array, the largest lets the whole build through, and those
/// between stop it at later steps.
const MARGINS_MB: [u64; 11] = [1, 2, 3, 5, 8, 13, 18, 24, 32, 44, 64];

/// The readers' margins, in KB: finer, for files of 1 to 4 MB whose reading peaks at a few
/// times their size.
const READ_MARGINS_KB: [u64; 11] = [
    512, 1024, 1536, 2048, 2560, 3072, 4096, 5120, 6144, 8192, 32768,
];

fn set_address_space_limit(bytes: u64) {
    LIMIT.store(bytes, std::sync::atomic::Ordering::SeqCst);
    let lim = libc::rlimit {
        rlim_cur: bytes,
        rlim_max: libc::RLIM_INFINITY,
    };
    // SAFETY: setrlimit only reads the struct.
    assert_eq!(unsafe { libc::setrlimit(libc::RLIMIT_AS, &lim) }, 0);
}

/// Allocations below this size are not input-sized at the grid used here (the smallest input
/// array, a vertex offset table, is 362 KB); one of them failing means the limit was met
/// between arrays, which no reservation can prevent. Those aborts are told apart and allowed.
const SMALL: usize = 256 << 10;

/// The start of each test: in a child process (`CHILD` set), the child's run, which never
/// returns; in the parent, whether address-space limits can be tried here (Linux, not Miri).
fn limits_can_be_tried() -> bool {
    if let Ok(spec) = std::env::var(CHILD) {
        child(&spec);
    }
    cfg!(target_os = "linux") && !cfg!(miri)
}

/// The child: builds `kind` (`name@threads`) under each margin from the `start`-th, printing
/// `MB:too-large` or `MB:built` per try on stdout (an abort cuts the list short); other errors
/// fail. With 2 threads the pool is started inside the limit: at the smallest margins its
/// threads cannot start and the build runs serially.
fn child(spec: &str) -> ! {
    let (kind, start) = spec.rsplit_once(':').unwrap();
    let (kind, threads) = kind.split_once('@').unwrap_or((kind, "1"));
    topoplex::parallel::set_threads(threads.parse().unwrap());
    // Arrays above 64 KB are mapped and unmapped on free (glibc would otherwise raise the
    // threshold and keep freed memory), so the address space used is what is live.
    // SAFETY: mallopt only sets allocator parameters, before any large allocation.
    unsafe {
        libc::mallopt(libc::M_MMAP_THRESHOLD, 64 << 10);
        libc::mallopt(libc::M_TRIM_THRESHOLD, 64 << 10);
    }
    if let Some(path) = kind.strip_prefix("read=") {
        read_child(std::path::Path::new(path), start.parse().unwrap());
    }
    if let Some(path) = kind.strip_prefix("read-ffi=") {
        read_ffi_child(path, start.parse().unwrap());
    }
    let kind = KINDS.into_iter().find(|k| k.name() == kind).unwrap();
    let complex = grid(300);
    for mb in &MARGINS_MB[start.parse::<usize>().unwrap()..] {
        set_address_space_limit(vm_size_bytes() + (mb << 20));
        let outcome = topoplex::build(kind, &complex).map(drop);
        set_address_space_limit(libc::RLIM_INFINITY);
        match outcome {
            Err(topoplex::BuildError::TooLarge { .. }) => println!("{mb}:too-large"),
            Ok(()) => println!("{mb}:built"),
            Err(e) => panic!("{e}"),
        }
    }
    std::process::exit(0)
}

/// The outcome of each margin for `kind` (`abort` for an allowed small-allocation abort), or
/// why it is wrong.
fn tries(me: &std::path::Path, test: &str, kind: &str) -> Result<Vec<String>, String> {
    let mut outcomes = Vec::new();
    while outcomes.len() < MARGINS_MB.len() {
        let out = Command::new(me)
            .args(["--exact", test, "--test-threads=1", "--nocapture"])
            .env(CHILD, format!("{kind}:{}", outcomes.len()))
            // One malloc arena: a thread's own arena reserves 64 MB of address space up front,
            // which would hide the limit.
            .env("MALLOC_ARENA_MAX", "1")
            .output()
            .unwrap();
        let stdout = String::from_utf8_lossy(&out.stdout);
        for line in stdout.lines() {
            if let Some((_, outcome)) = line.rsplit_once(':') {
                outcomes.push(outcome.to_string());
            }
        }
        if out.status.success() {
            break;
        }
        // The allocator's last word: `failed N bytes at <callers>`.
        let err = String::from_utf8_lossy(&out.stderr);
        let last = err.lines().rfind(|l| l.contains("failed ")).unwrap_or("");
        let bytes: usize = last
            .split("failed ")
            .nth(1)
            .and_then(|r| r.split(' ').next())
            .and_then(|n| n.parse().ok())
            .unwrap_or(usize::MAX);
        if bytes >= SMALL {
            return Err(format!(
                "{kind}: aborted at margin #{} after {outcomes:?}: {last}",
                outcomes.len()
            ));
        }
        outcomes.push("abort".to_string());
    }
    Ok(outcomes)
}

#[test]
fn every_build_under_an_address_space_limit_says_too_large() {
    if !limits_can_be_tried() {
        return;
    }
    let me = std::env::current_exe().unwrap();
    let mut bad = Vec::new();
    // Every structure serially and with 2 threads (the parallel steps' buffers, the sort's
    // merge buffer, the pool's threads).
    let specs = KINDS
        .map(StructureKind::name)
        .into_iter()
        .flat_map(|k| [format!("{k}@1"), format!("{k}@2")]);
    for kind in specs {
        let kind = kind.as_str();
        match tries(
            &me,
            "every_build_under_an_address_space_limit_says_too_large",
            kind,
        ) {
            // The smallest margin refused, the largest built: both outcomes exercised.
            Ok(t) if t[0] == "too-large" && t[t.len() - 1] == "built" => {
                eprintln!("{kind}: {t:?}")
            }
            Ok(t) => bad.push(format!("{kind}: {t:?}")),
            Err(e) => bad.push(e),
        }
    }
    assert!(bad.is_empty(), "{}", bad.join("\n"));
}

/// The reader child: opens `path` (any format by extension; `.tpx` as a saved complex and, when
/// the name says `live`, as an editable live complex) under each of [`READ_MARGINS_KB`] from
/// the `start`-th, printing `KB:too-large` or `KB:built` per try like [`child`].
fn read_child(path: &std::path::Path, start: usize) -> ! {
    use topoplex::io::ReadErrorKind;
    use topoplex::store::StoreError;
    let live = path.to_string_lossy().contains("live");
    for kb in &READ_MARGINS_KB[start..] {
        set_address_space_limit(vm_size_bytes() + (kb << 10));
        let outcome: Result<(), String> = if topoplex::store::is_saved_path(path) {
            let opened = if live {
                topoplex::live::LiveComplex::open(path).map(drop)
            } else {
                topoplex::store::Saved::open(path).and_then(|s| s.complex().map(drop))
            };
            match opened {
                Ok(()) => Ok(()),
                Err(StoreError::Complex {
                    source: topoplex::ComplexError::OutOfMemory { .. },
                    ..
                })
                | Err(StoreError::Build {
                    source: topoplex::BuildError::TooLarge { .. },
                    ..
                }) => Err("too-large".into()),
                Err(e) => Err(e.to_string()),
            }
        } else {
            match topoplex::io::read_path(path) {
                Ok(_) => Ok(()),
                Err(e) if matches!(e.kind, ReadErrorKind::TooLarge(_)) => Err("too-large".into()),
                Err(e) => Err(e.to_string()),
            }
        };
        set_address_space_limit(libc::RLIM_INFINITY);
        match outcome {
            Ok(()) => println!("{kb}:built"),
            Err(e) if e == "too-large" => println!("{kb}:too-large"),
            Err(e) => panic!("{e}"),
        }
    }
    std::process::exit(0)
}

/// [`read_child`] through the C ABI: `tpx_complex_from_file` must return
/// `TPX_STATUS_TOO_LARGE` (reading or normalising) or OK, never abort the host.
fn read_ffi_child(path: &str, start: usize) -> ! {
    use topoplex_ffi::{TpxComplex, TpxStatus, tpx_complex_free, tpx_complex_from_file};
    let c_path = std::ffi::CString::new(path).unwrap();
    for kb in &READ_MARGINS_KB[start..] {
        let mut out: *mut TpxComplex = std::ptr::null_mut();
        set_address_space_limit(vm_size_bytes() + (kb << 10));
        // SAFETY: a NUL-terminated path and a valid out pointer, as the header asks.
        let st = unsafe { tpx_complex_from_file(c_path.as_ptr(), &mut out) };
        set_address_space_limit(libc::RLIM_INFINITY);
        match st {
            TpxStatus::Ok => {
                // SAFETY: a complex the call returned, freed once.
                unsafe { tpx_complex_free(out) };
                println!("{kb}:built");
            }
            TpxStatus::TooLarge => println!("{kb}:too-large"),
            other => panic!("status {other:?}"),
        }
    }
    std::process::exit(0)
}

/// A k×k grid in every format the readers take (each writer's output; legacy VTK also as
/// version 5, OFFSETS / CONNECTIVITY, written here) and saved as `.tpx` (complex, live
/// complex), in `dir`. Returns (name, path).
fn grid_files(dir: &std::path::Path, k: u32) -> Vec<(String, std::path::PathBuf)> {
    use topoplex::io::write::{Format, write_complex};
    let mut complex = grid(k);
    let n = complex.vertex_count();
    let coords = (0..n).flat_map(|v| [f64::from(v % (k + 1)), f64::from(v / (k + 1)), 0.0]);
    let ids: Vec<u32> = (0..complex.input_count())
        .flat_map(|i| complex.input_simplex(i).to_vec())
        .collect();
    let offsets: Vec<usize> = (0..=ids.len() / 3).map(|i| 3 * i).collect();
    let data: Vec<f64> = coords.collect();
    complex = topoplex::Complex::from_arrays(
        n,
        &ids,
        &offsets,
        Some(topoplex::io::Coords { dim: 3, data }),
    )
    .unwrap();
    let mut files = Vec::new();
    for format in Format::ALL {
        let ext = match format.name().split('-').next().unwrap() {
            "msh2" => "msh",
            e => e,
        };
        let path = dir.join(format!("grid-{}.{ext}", format.name()));
        write_complex(&complex, &path, Some(format)).unwrap();
        files.push((format.name().to_string(), path));
    }
    let path = dir.join("grid-v5.vtk");
    let mut text = format!(
        "# vtk DataFile Version 5.1\ngrid\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS {n} double\n"
    );
    for v in 0..n {
        text += &format!("{} {} 0\n", v % (k + 1), v / (k + 1));
    }
    let m = ids.len() / 3;
    text += &format!("CELLS {} {}\nOFFSETS vtktypeint64\n", m + 1, ids.len());
    for o in &offsets {
        text += &format!("{o}\n");
    }
    text += "CONNECTIVITY vtktypeint64\n";
    for t in ids.chunks(3) {
        text += &format!("{} {} {}\n", t[0], t[1], t[2]);
    }
    text += &format!("CELL_TYPES {m}\n");
    text += &"5\n".repeat(m);
    std::fs::write(&path, text).unwrap();
    files.push(("vtk5".into(), path));
    // VTU with ASCII data arrays: read by our streaming reader, not vtkio.
    let path = dir.join("grid-ascii.vtu");
    let mut text = format!(
        "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\">\n\
         <UnstructuredGrid>\n<Piece NumberOfPoints=\"{n}\" NumberOfCells=\"{m}\">\n<Points>\n\
         <DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n"
    );
    for v in 0..n {
        text += &format!("{} {} 0\n", v % (k + 1), v / (k + 1));
    }
    text += "</DataArray>\n</Points>\n<Cells>\n\
             <DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n";
    for t in ids.chunks(3) {
        text += &format!("{} {} {}\n", t[0], t[1], t[2]);
    }
    text += "</DataArray>\n<DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n";
    for o in &offsets[1..] {
        text += &format!("{o}\n");
    }
    text += "</DataArray>\n<DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">\n";
    text += &"5\n".repeat(m);
    text += "</DataArray>\n</Cells>\n</Piece>\n</UnstructuredGrid>\n</VTKFile>\n";
    std::fs::write(&path, text).unwrap();
    files.push(("vtu-ascii".into(), path));
    let path = dir.join("grid.tpx");
    topoplex::store::save(&path, &complex, None).unwrap();
    files.push(("tpx".into(), path));
    let path = dir.join("grid-live.tpx");
    topoplex::live::LiveComplex::try_from_complex(&complex)
        .unwrap()
        .save(&path)
        .unwrap();
    files.push(("tpx-live".into(), path));
    files
}

/// The readers' row: a file of a few MB in each format read under the same margins. The
/// smallest margin refuses (`TooLarge`: the file's buffer or a first output array), the largest
/// reads, and no try aborts on an allocation above [`SMALL`] (a reader's output arrays, the
/// crates' arrays behind vtkio probed first, `.tpx` copies and mapping).
#[test]
fn every_reader_under_an_address_space_limit_says_too_large() {
    if !limits_can_be_tried() {
        return;
    }
    let dir = std::env::temp_dir().join(format!("topoplex-read-oom-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let me = std::env::current_exe().unwrap();
    let mut bad = Vec::new();
    let mut files = grid_files(&dir, 150);
    // The C ABI's file reader on one text and one binary format.
    for name in ["off", "ply-binary"] {
        let (_, path) = files.iter().find(|(n, _)| n == name).unwrap().clone();
        files.push((format!("{name} via tpx_complex_from_file"), path));
    }
    for (name, path) in files {
        let size = std::fs::metadata(&path).unwrap().len();
        let mode = if name.contains("tpx_complex_from_file") {
            "read-ffi"
        } else {
            "read"
        };
        let spec = format!("{mode}={}", path.display());
        match tries(
            &me,
            "every_reader_under_an_address_space_limit_says_too_large",
            &spec,
        ) {
            Ok(t) if t[0] == "too-large" && t[t.len() - 1] == "built" => {
                eprintln!("{name} ({size} bytes): {t:?}")
            }
            Ok(t) => bad.push(format!("{name}: {t:?}")),
            Err(e) => bad.push(format!("{name}: {e}")),
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
    assert!(bad.is_empty(), "{}", bad.join("\n"));
}
