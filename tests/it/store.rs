//! Saved files (`.tpx`): every structure saved and opened back (memory-mapped) answers every
//! relation exactly like the structure freshly built; the complex comes back identical; damaged,
//! foreign, truncated and wrong-version files are refused with an error naming what is wrong.

use crate::common;

use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};

use proptest::prelude::*;
use topoplex::live::{ContractMode, LiveComplex, VertexId};
use topoplex::oracle::compare_structures;
use topoplex::store::{Saved, StoreError, save};
use topoplex::{BuildError, build};
use topoplex::{Complex, StructureKind, Topology, fixtures};

/// A fresh path per call: tests run in parallel threads.
fn temp_path(name: &str) -> PathBuf {
    static NEXT: AtomicUsize = AtomicUsize::new(0);
    let dir = std::env::temp_dir().join(format!("topoplex-store-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir.join(format!("{}-{name}", NEXT.fetch_add(1, Ordering::Relaxed)))
}

/// Saves `c` with each structure that encodes it, reopens the file and compares every relation
/// of every simplex, the complex's listing and statistics, and runs `verify`.
fn round_trip(c: &Complex, what: &str) {
    let path = temp_path(&format!("{}.tpx", what.replace(['/', ' '], "_")));
    for kind in StructureKind::ALL {
        let built = match build(kind, c) {
            Ok(s) => s,
            Err(BuildError::Unsupported { .. }) => continue,
            Err(e) => panic!("{what}: {kind}: {e}"),
        };
        save(&path, c, Some(built.as_ref())).unwrap_or_else(|e| panic!("{what}: {kind}: {e}"));
        let saved = Saved::open(&path).unwrap_or_else(|e| panic!("{what}: {kind}: {e}"));
        assert_eq!(saved.kind(), Some(kind));
        saved
            .verify()
            .unwrap_or_else(|e| panic!("{what}: {kind}: {e}"));
        let opened = saved.structure().unwrap().expect("a structure was saved");
        assert_eq!(opened.kind(), kind);
        opened
            .validate()
            .unwrap_or_else(|e| panic!("{what}: {kind}: reopened: {e}"));
        compare_structures(built.as_ref(), opened.as_ref())
            .unwrap_or_else(|e| panic!("{what}: {kind}: reopened: {e}"));
        assert_eq!(built.storage().integers, opened.storage().integers);
        same_complex(c, &saved.complex().unwrap(), what);
    }
    std::fs::remove_file(&path).unwrap();
}

fn same_complex(a: &Complex, b: &Complex, what: &str) {
    assert_eq!(a.vertex_count(), b.vertex_count(), "{what}");
    assert_eq!(a.top_counts(), b.top_counts(), "{what}");
    assert_eq!(a.stats(), b.stats(), "{what}");
    assert_eq!(a.coords(), b.coords(), "{what}");
    assert_eq!(a.source(), b.source(), "{what}");
    for p in 0..=a.dimension() {
        assert_eq!(a.tops(p), b.tops(p), "{what}: tops({p})");
    }
    assert_eq!(a.input_count(), b.input_count(), "{what}");
    for i in 0..a.input_count() {
        assert_eq!(
            a.input_simplex(i),
            b.input_simplex(i),
            "{what}: listing {i}"
        );
    }
}

#[test]
fn every_structure_of_every_fixture_reopens_with_the_same_relations() {
    for (name, c) in fixtures::all() {
        round_trip(&c, name);
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 40, ..ProptestConfig::default() })]
    #[test]
    fn random_complexes_reopen_with_the_same_relations(c in common::random_complex(5, 9, 8)) {
        round_trip(&c, "random");
    }

    #[test]
    fn random_surfaces_reopen_with_the_same_relations(c in common::random_complex(2, 12, 14)) {
        round_trip(&c, "random-2");
    }
}

#[test]
fn real_data_reopens_with_the_same_relations() {
    // Files up to 300 kB: every relation of every structure is compared, and the larger files
    // are already checked against the IG by tests/it/structures.rs (the suite's time budget).
    common::for_each_shared_complex(300_000, |path, c| {
        round_trip(&c, &path.display().to_string())
    });
}

/// A tetrahedron glued to a triangle at an edge, saved with its IA.
fn saved_bytes() -> Vec<u8> {
    //   3
    //   |\      tetrahedron 0 1 2 3, triangle 1 2 4 hanging on edge 1-2
    //   0-1-4
    //    \|/
    //     2
    let c = Complex::from_simplices(5, &[&[0, 1, 2, 3], &[1, 2, 4]]).unwrap();
    let s = build(StructureKind::Nmia, &c).unwrap();
    let path = temp_path("small.tpx");
    save(&path, &c, Some(s.as_ref())).unwrap();
    let bytes = std::fs::read(&path).unwrap();
    std::fs::remove_file(&path).unwrap();
    bytes
}

fn open_bytes(bytes: &[u8]) -> Result<Saved, StoreError> {
    Saved::from_bytes(Path::new("x.tpx"), bytes)
}

#[test]
fn a_complex_only_file_builds_any_structure() {
    let c = fixtures::builtin_example();
    let path = temp_path("complex-only.tpx");
    save(&path, &c, None).unwrap();
    let saved = Saved::open(&path).unwrap();
    assert_eq!(saved.kind(), None);
    assert!(saved.structure().unwrap().is_none());
    saved.verify().unwrap();
    let ig = saved.structure_of(StructureKind::Ig).unwrap();
    let fresh = build(StructureKind::Ig, &c).unwrap();
    compare_structures(fresh.as_ref(), ig.as_ref()).unwrap();
    std::fs::remove_file(&path).unwrap();
}

#[test]
fn foreign_truncated_wrong_version_and_swapped_files_are_refused() {
    let good = saved_bytes();
    assert!(open_bytes(&good).is_ok());
    let msg = |r: Result<Saved, StoreError>| r.err().expect("refused").to_string();
    assert!(msg(open_bytes(b"OFF\n3 1 0\n")).contains("not a topoplex saved file"));
    assert!(msg(open_bytes(&good[..40])).contains("truncated"));
    assert!(msg(open_bytes(&good[..good.len() - 1])).contains("truncated"));
    let mut v3 = good.clone();
    v3[12..16].copy_from_slice(&3u32.to_ne_bytes());
    assert!(msg(open_bytes(&v3)).contains("format version 3"));
    let mut swapped = good.clone();
    swapped[8..12].copy_from_slice(&0x0102_0304u32.swap_bytes().to_ne_bytes());
    assert!(msg(open_bytes(&swapped)).contains("byte order"));
    let mut longer = good.clone();
    longer.push(0);
    assert!(msg(open_bytes(&longer)).contains("corrupt"));
}

#[test]
fn a_flipped_header_bit_fails_on_open_and_a_flipped_data_bit_fails_verify() {
    let good = saved_bytes();
    // Every byte of the header and section table is covered by the checksum checked on open.
    let table = u64::from_ne_bytes(good[40..48].try_into().unwrap()) as usize;
    for i in (8..64).chain(table..good.len()) {
        let mut bad = good.clone();
        bad[i] ^= 0x10;
        assert!(open_bytes(&bad).is_err(), "flipped byte {i} accepted");
    }
    // A flipped bit inside an array opens (nothing is read) but fails `verify`.
    for i in (64..table).step_by(7) {
        let mut bad = good.clone();
        bad[i] ^= 0x01;
        if let Ok(saved) = open_bytes(&bad) {
            let unchanged = bad == good;
            assert!(
                unchanged || saved.verify().is_err(),
                "flipped byte {i} verified"
            );
        }
    }
}

#[test]
fn hostile_bytes_never_panic_on_open_verify_or_query() {
    // Every prefix and many one-byte edits of a valid file: open and verify return (never
    // panic), and a file that passes verify answers queries without panicking.
    let good = saved_bytes();
    let mut x = 0x2545_f491_4f6c_dd1du64;
    let mut cases: Vec<Vec<u8>> = (0..good.len())
        .step_by(13)
        .map(|n| good[..n].to_vec())
        .collect();
    for _ in 0..300 {
        x ^= x << 13;
        x ^= x >> 7;
        x ^= x << 17;
        let mut bad = good.clone();
        bad[(x % good.len() as u64) as usize] = (x >> 32) as u8;
        cases.push(bad);
    }
    for bytes in cases {
        let Ok(saved) = open_bytes(&bytes) else {
            continue;
        };
        if saved.verify().is_ok()
            && let Ok(Some(s)) = saved.structure()
        {
            query_everything(s.as_ref());
        }
    }
}

fn query_everything(s: &dyn Topology) {
    let mut out = Vec::new();
    let d = s.dimension().min(3);
    for v in 0..s.vertex_count().min(8) {
        for q in 0..=d {
            let _ = s.relation(&[v], q, &mut out);
        }
    }
}

#[test]
fn the_c_abi_saves_opens_and_names_bad_files_by_status() {
    use std::ffi::CString;
    use std::ptr::{null, null_mut};
    use topoplex_ffi::*;
    let c = fixtures::builtin_example();
    let path = temp_path("abi.tpx");
    let cpath = CString::new(path.to_str().unwrap()).unwrap();
    let fresh = build(StructureKind::Sig, &c).unwrap();
    save(&path, &c, Some(fresh.as_ref())).unwrap();
    unsafe {
        let mut s = null_mut();
        let st = tpx_structure_open(cpath.as_ptr(), TPX_KIND_SIG, TPX_OPEN_VERIFY, &mut s);
        assert_eq!(st, TpxStatus::Ok);
        let (mut buf, mut len) = ([0u32; 64], 0usize);
        let st = tpx_relation(s, [0u32].as_ptr(), 1, 1, buf.as_mut_ptr(), 64, &mut len);
        assert_eq!(st, TpxStatus::Ok);
        let mut want = Vec::new();
        fresh.relation(&[0], 1, &mut want).unwrap();
        topoplex::relation::sort_rows(&mut want, 2);
        let mut got = buf[..len].to_vec();
        topoplex::relation::sort_rows(&mut got, 2);
        assert_eq!(got, want);
        // Saved again through the ABI from the mapped structure, then opened as a complex.
        let mut cx = null_mut();
        assert_eq!(tpx_complex_open(cpath.as_ptr(), &mut cx), TpxStatus::Ok);
        let again = temp_path("abi-again.tpx");
        let cagain = CString::new(again.to_str().unwrap()).unwrap();
        assert_eq!(tpx_save(cx, s, cagain.as_ptr()), TpxStatus::Ok);
        assert_eq!(tpx_save(cx, null(), cagain.as_ptr()), TpxStatus::Ok);
        tpx_structure_free(s);
        tpx_complex_free(cx);
        // A foreign file, a truncated one, and an unknown flag.
        std::fs::write(&again, b"OFF\n").unwrap();
        let mut s = null_mut();
        let st = tpx_structure_open(cagain.as_ptr(), TPX_KIND_SIG, 0, &mut s);
        assert_eq!(st, TpxStatus::SavedFileForeign);
        let bytes = std::fs::read(&path).unwrap();
        std::fs::write(&again, &bytes[..bytes.len() / 2]).unwrap();
        let st = tpx_structure_open(cagain.as_ptr(), TPX_KIND_SIG, 0, &mut s);
        assert_eq!(st, TpxStatus::SavedFileTruncated);
        assert!(s.is_null());
        let st = tpx_structure_open(cpath.as_ptr(), TPX_KIND_SIG, 6, &mut s);
        assert_eq!(st, TpxStatus::InvalidArgument);
        assert_eq!(tpx_set_threads(0), TpxStatus::InvalidArgument);
        // Bounded: a mistyped count cannot start thousands of threads.
        assert_eq!(tpx_set_threads(257), TpxStatus::InvalidArgument);
        assert_eq!(tpx_set_threads(100_000), TpxStatus::InvalidArgument);
        std::fs::remove_file(&again).unwrap();
    }
    std::fs::remove_file(&path).unwrap();
}

/// The live complex after `edits` (kind, a, b: insert {a, b, a+b}, remove a top, contract
/// freely), refusals ignored: tombstones and all.
fn edited_live(c: &Complex, edits: &[(u8, u32, u32)]) -> LiveComplex {
    let mut live = LiveComplex::from_complex(c);
    for &(kind, a, b) in edits {
        let n = live.vertex_slots();
        let (a, b) = (a % n, b % n);
        let _ = match kind {
            0 => live.insert_top(&[a, b, (a + b) % n]).map(|_| ()),
            1 => {
                let top: Option<Vec<u32>> = live.tops().next().map(|(_, s)| s.to_vec());
                top.map_or(Ok(()), |s| live.remove_top(&s))
            }
            _ => live
                .contract(VertexId(a), VertexId(b), ContractMode::Free, None)
                .map(|_| ()),
        };
    }
    live.validate().unwrap();
    live
}

/// Saved and opened back: valid, the same relations, windings, coordinates and complex as a
/// compacted copy (saving compacts), and still editable like it.
fn live_round_trip(live: &LiveComplex) {
    let path = temp_path("live.tpx");
    live.save(&path).unwrap();
    let saved = Saved::open(&path).unwrap();
    assert_eq!(saved.kind(), Some(StructureKind::IaStar));
    saved.verify().unwrap();
    let mut opened = LiveComplex::open(&path).unwrap();
    opened.validate().unwrap();
    let mut dense = live.clone();
    dense.compact();
    compare_structures(&dense, &opened).unwrap();
    let tops = |l: &LiveComplex| -> Vec<(usize, u32, Vec<u32>)> {
        l.tops()
            .map(|(t, s)| (t.dim(), t.slot(), s.to_vec()))
            .collect()
    };
    assert_eq!(tops(&dense), tops(&opened));
    for v in dense.vertices() {
        assert_eq!(dense.coords(v).unwrap(), opened.coords(v).unwrap());
    }
    same_complex(&live.to_complex(), &saved.complex().unwrap(), "live");
    if let Some([a, b]) = dense.edges().first().copied() {
        let x = dense.contract(VertexId(a), VertexId(b), ContractMode::Free, None);
        let y = opened.contract(VertexId(a), VertexId(b), ContractMode::Free, None);
        assert_eq!(x.is_ok(), y.is_ok());
        compare_structures(&dense, &opened).unwrap();
    }
    std::fs::remove_file(&path).unwrap();
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 40, ..ProptestConfig::default() })]
    #[test]
    fn edited_live_complexes_reopen_editable_with_the_same_relations(
        (n, list) in common::random_input(5, 9, 8),
        edits in proptest::collection::vec((0u8..3, 0u32..9, 0u32..9), 0..8),
    ) {
        live_round_trip(&edited_live(&common::complex_of(n, &list), &edits));
    }
}

#[test]
fn every_fixture_reopens_as_a_live_complex() {
    for (name, c) in fixtures::all() {
        live_round_trip(&LiveComplex::from_complex(&c));
        live_round_trip(&edited_live(&c, &[(2, 0, 1), (1, 0, 0), (0, 1, 2)]));
        let _ = name;
    }
}

fn saved_live_bytes() -> Vec<u8> {
    let c = Complex::from_simplices(6, &[&[0, 1, 2, 3], &[1, 2, 4], &[4, 5]]).unwrap();
    let live = edited_live(&c, &[(2, 3, 0)]);
    let path = temp_path("small-live.tpx");
    live.save(&path).unwrap();
    let bytes = std::fs::read(&path).unwrap();
    std::fs::remove_file(&path).unwrap();
    bytes
}

#[test]
fn damaged_live_files_are_refused_or_valid_never_a_panic() {
    let good = saved_live_bytes();
    let open_live = |b: &[u8]| open_bytes(b).and_then(|s| LiveComplex::open_saved(&s));
    open_live(&good).unwrap().validate().unwrap();
    assert!(open_bytes(&good[..good.len() - 3]).is_err(), "truncated");
    // Every one-byte edit of the sections: verify refuses it; opened without verify, the live
    // complex is refused or passes every invariant (ids in range, no top a face of another).
    let table = u64::from_ne_bytes(good[40..48].try_into().unwrap()) as usize;
    for i in 64..table {
        for flip in [0x01u8, 0x80, 0xff] {
            let mut bad = good.clone();
            bad[i] ^= flip;
            let Ok(saved) = open_bytes(&bad) else {
                continue;
            };
            assert!(saved.verify().is_err(), "flipped byte {i} verified");
            if let Ok(live) = LiveComplex::open_saved(&saved) {
                live.validate().unwrap();
                query_everything(&live);
            }
        }
    }
}

#[test]
fn the_cli_and_the_c_abi_save_and_open_the_live_complex() {
    use topoplex_ffi::*;
    let input = temp_path("bowtie.off");
    std::fs::write(
        &input,
        "OFF\n5 2 0\n0 0 0\n1 0 0\n0 1 0\n2 0 0\n2 1 0\n3 0 1 2\n3 1 3 4\n",
    )
    .unwrap();
    let out = temp_path("bowtie-live.tpx");
    let st = std::process::Command::new(env!("CARGO_BIN_EXE_topoplex"))
        .args([
            "save",
            input.to_str().unwrap(),
            "--structure",
            "iastar",
            "--out",
        ])
        .arg(&out)
        .status()
        .unwrap();
    assert!(st.success());
    assert_eq!(
        Saved::open(&out).unwrap().kind(),
        Some(StructureKind::IaStar)
    );
    let cpath = std::ffi::CString::new(out.to_str().unwrap()).unwrap();
    let mut l = std::ptr::null_mut();
    // SAFETY: valid NUL-terminated paths and out pointers; handles freed once.
    unsafe {
        assert_eq!(
            tpx_live_open(cpath.as_ptr(), TPX_OPEN_VERIFY, &mut l),
            TpxStatus::Ok
        );
        let mut k = 0usize;
        assert_eq!(tpx_live_top_count(l, 2, &mut k), TpxStatus::Ok);
        assert_eq!(k, 2);
        let mut u = std::ptr::null_mut();
        assert_eq!(
            tpx_live_contract(
                l,
                0,
                2,
                TPX_CONTRACT_PRESERVE_TOPOLOGY,
                std::ptr::null(),
                0,
                &mut u
            ),
            TpxStatus::Ok
        );
        tpx_undo_free(u);
        let again = temp_path("bowtie-edited.tpx");
        let cagain = std::ffi::CString::new(again.to_str().unwrap()).unwrap();
        assert_eq!(tpx_live_save(l, cagain.as_ptr()), TpxStatus::Ok);
        tpx_live_free(l);
        let reopened = LiveComplex::open(&again).unwrap();
        assert_eq!(
            (reopened.live_vertex_count(), reopened.top_count(2)),
            (4, 1)
        );
        std::fs::write(&again, b"OFF\n").unwrap();
        let mut l2 = std::ptr::null_mut();
        assert_eq!(
            tpx_live_open(cagain.as_ptr(), 0, &mut l2),
            TpxStatus::SavedFileForeign
        );
        std::fs::remove_file(&again).unwrap();
    }
    std::fs::remove_file(&out).unwrap();
    std::fs::remove_file(&input).unwrap();
}
