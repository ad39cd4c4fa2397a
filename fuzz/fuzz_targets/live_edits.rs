#![no_main]
//! Differential: random edit sequences (insert, remove, contract in both modes, split, move a
//! vertex) on a complex built from arbitrary bytes, through the C ABI (`TpxLive`) and the Rust
//! API side by side. Both must agree on every outcome, stay valid, and (compacted) answer every
//! relation like the brute-force oracle on their own `to_complex()`. After every edit, handle
//! navigation through the C ABI (`tpx_live_structure` + the handle functions, one handle at a
//! time and `tpx_related_handles_batch`) answers like the Rust `Navigate`; every handle taken
//! since the start names the simplex it last named or that simplex's image under the edit, or is
//! STALE_HANDLE because that simplex is gone; after the final compaction every older handle is
//! STALE_GENERATION.
use libfuzzer_sys::fuzz_target;
use topoplex::live::{ContractMode, LiveComplex, VertexId};
use topoplex::oracle::check_structure;
use topoplex::testing::follows_edit;
use topoplex::{Complex, Navigate, Order, Topology};
use topoplex_ffi::*;

/// The vertices of a C handle of the live complex, with the status.
fn c_vertices(s: *const TpxStructure, h: &TpxSimplex) -> (TpxStatus, Vec<u32>) {
    let mut buf = [0u32; 16];
    let mut len = 0usize;
    let st = unsafe { tpx_simplex_vertices(s, h, buf.as_mut_ptr(), 16, &mut len) };
    (st, buf[..len].to_vec())
}

/// C handles of up to 24 simplices (vertices, top simplices, then edges, which are named through
/// a top that may be removed before them), with their vertices.
fn c_handles(s: *const TpxStructure, rust: &LiveComplex) -> Vec<(TpxSimplex, Vec<u32>)> {
    let rows = rust
        .vertices()
        .map(|v| vec![v.0])
        .take(8)
        .chain(rust.tops().map(|(_, t)| t.to_vec()).take(8))
        .chain(rust.edges().into_iter().map(|e| e.to_vec()).take(8));
    rows.map(|row| {
        let mut h = TpxSimplex::default();
        assert_eq!(
            unsafe { tpx_locate(s, row.as_ptr(), row.len(), &mut h) },
            TpxStatus::Ok
        );
        let mut sorted = row;
        sorted.sort_unstable();
        (h, sorted)
    })
    .collect()
}

/// The length of the answer `call(buf, buf.len(), &mut len)` wrote into `buf`; None when `buf`
/// is too small for it (the fuzzer's buffers are fixed), any other status a failure.
fn filled(
    buf: &mut [TpxSimplex],
    call: impl FnOnce(*mut TpxSimplex, usize, *mut usize) -> TpxStatus,
) -> Option<usize> {
    let mut len = 0usize;
    match call(buf.as_mut_ptr(), buf.len(), &mut len) {
        TpxStatus::BufferTooSmall => None,
        st => {
            assert_eq!(st, TpxStatus::Ok);
            Some(len)
        }
    }
}

/// Navigation through the C ABI equals the Rust API's, as vertex rows.
fn c_navigation_matches(s: *const TpxStructure, rust: &LiveComplex) {
    let mut buf = vec![TpxSimplex::default(); 1 << 12];
    let mut rbuf = Vec::new();
    let rows =
        |hs: &[TpxSimplex]| -> Vec<Vec<u32>> { hs.iter().map(|h| c_vertices(s, h).1).collect() };
    for (h, row) in c_handles(s, rust) {
        let rh = rust.locate(&row).unwrap();
        for q in 0..=rust.dimension() {
            let Some(len) = filled(&mut buf, |out, cap, len| unsafe {
                tpx_related_handles(s, &h, q as u32, TPX_ORDER_NATURAL, out, cap, len)
            }) else {
                continue;
            };
            rust.related(rh, q, Order::Natural, &mut rbuf).unwrap();
            let want: Vec<Vec<u32>> = rbuf
                .iter()
                .map(|&x| rust.vertices_of(x).unwrap().to_vec())
                .collect();
            assert_eq!(rows(&buf[..len]), want);
        }
        let mut len = 0usize;
        if unsafe {
            tpx_star(
                s,
                &h,
                1,
                TPX_ORDER_NATURAL,
                buf.as_mut_ptr(),
                buf.len(),
                &mut len,
            )
        } == TpxStatus::Ok
        {
            rust.link(rh, Order::Natural, &mut rbuf).unwrap();
            assert_eq!(len, rbuf.len());
        }
        let mut r = 0u32;
        assert_eq!(unsafe { tpx_simplex_test(s, &h, 1, &mut r) }, TpxStatus::Ok);
        assert_eq!(r == 1, rust.is_manifold(rh).unwrap());
    }
    c_batches_match(s, rust);
}

/// `tpx_related_handles_batch` over every handle of `c_handles` (dimensions mixed) equals the
/// Rust API's `related_handles_batch`, as vertex rows, CSR ends included.
fn c_batches_match(s: *const TpxStructure, rust: &LiveComplex) {
    let (hs, rows): (Vec<TpxSimplex>, Vec<Vec<u32>>) = c_handles(s, rust).into_iter().unzip();
    let rh: Vec<_> = rows.iter().map(|r| rust.locate(r).unwrap()).collect();
    let mut buf = vec![TpxSimplex::default(); 1 << 12];
    let mut offsets = vec![0u32; hs.len() + 1];
    let (mut want, mut ends) = (Vec::new(), Vec::new());
    for q in 0..=rust.dimension() {
        let Some(len) = filled(&mut buf, |out, cap, len| unsafe {
            tpx_related_handles_batch(
                s,
                hs.as_ptr(),
                hs.len(),
                q as u32,
                TPX_ORDER_LEXICOGRAPHIC,
                offsets.as_mut_ptr(),
                out,
                cap,
                len,
            )
        }) else {
            continue;
        };
        want.clear();
        ends.clear();
        rust.related_handles_batch(&rh, q, Order::Lexicographic, &mut want, &mut ends)
            .unwrap();
        let got_ends: Vec<usize> = offsets[1..].iter().map(|&o| o as usize).collect();
        assert_eq!(got_ends, ends);
        let got: Vec<Vec<u32>> = buf[..len].iter().map(|h| c_vertices(s, h).1).collect();
        let want: Vec<Vec<u32>> = want
            .iter()
            .map(|&x| rust.vertices_of(x).unwrap().to_vec())
            .collect();
        assert_eq!(got, want);
    }
}

fuzz_target!(|data: &[u8]| {
    let split = data.first().map_or(0, |&b| b as usize).min(data.len());
    let (n, list) = topoplex_fuzz_support::decode(&data[..split]);
    let refs: Vec<&[u32]> = list.iter().map(Vec::as_slice).collect();
    let Ok(c) = Complex::from_simplices(n, &refs) else {
        return;
    };
    let mut rust = LiveComplex::from_complex(&c);
    let (st, tc) = topoplex_fuzz_support::c_complex(n, &list);
    assert_eq!(st, TpxStatus::Ok);
    let mut live: *mut TpxLive = std::ptr::null_mut();
    unsafe {
        assert_eq!(tpx_live_from_complex(tc, &mut live), TpxStatus::Ok);
        tpx_complex_free(tc);
    }
    let mut view: *const TpxStructure = std::ptr::null();
    assert_eq!(
        unsafe { tpx_live_structure(live, &mut view) },
        TpxStatus::Ok
    );
    let mut before = c_handles(view, &rust);
    let mut undos: Vec<(*mut TpxUndo, topoplex::live::UndoRecord)> = Vec::new();
    for op in data[split..].chunks(4) {
        let &[kind, x, y, z] = op else { break };
        let n = rust.vertex_slots().max(1);
        let (a, b) = (x as u32 % (n + 1), y as u32 % (n + 1));
        let sigma: Vec<u32> = [a, b, z as u32 % (n + 1)][..1 + (kind as usize >> 4) % 3].to_vec();
        // (a, b, contracted) of an edit that moves tops in place, for the handle check below.
        let mut edit = None;
        let (st, ok) = match kind % 5 {
            0 => unsafe {
                (
                    tpx_live_insert_top(live, sigma.as_ptr(), sigma.len()),
                    rust.insert_top(&sigma).is_ok(),
                )
            },
            1 => unsafe {
                (
                    tpx_live_remove_top(live, sigma.as_ptr(), sigma.len()),
                    rust.remove_top(&sigma).is_ok(),
                )
            },
            2 | 3 => {
                let (mode, m) = if kind % 5 == 2 {
                    (
                        TPX_CONTRACT_PRESERVE_TOPOLOGY,
                        ContractMode::PreserveTopology,
                    )
                } else {
                    (TPX_CONTRACT_FREE, ContractMode::Free)
                };
                let mut u: *mut TpxUndo = std::ptr::null_mut();
                let st =
                    unsafe { tpx_live_contract(live, a, b, mode, std::ptr::null(), 0, &mut u) };
                let r = rust.contract(VertexId(a), VertexId(b), m, None);
                let ok = r.is_ok();
                if let Ok(rec) = r {
                    undos.push((u, rec));
                    edit = Some((a, b, true));
                }
                (st, ok)
            }
            _ => match undos.pop() {
                Some((u, rec)) => {
                    let st = unsafe { tpx_live_split(live, u) };
                    unsafe { tpx_undo_free(u) };
                    edit = Some((rec.a.0, rec.b.0, false));
                    (st, rust.split(&rec).is_ok())
                }
                None => continue,
            },
        };
        assert_eq!(
            st == TpxStatus::Ok,
            ok,
            "C ABI and Rust disagree on {op:?}: {st:?}"
        );
        assert_eq!(unsafe { tpx_live_validate(live) }, TpxStatus::Ok);
        rust.validate().unwrap();
        let mut dense = rust.clone();
        dense.compact();
        check_structure(&dense, &rust.to_complex()).unwrap();
        // Every handle taken so far names the simplex it last named or its image under this
        // edit (a contraction of b into a, or the split back), or is refused because that
        // simplex is gone.
        for (h, row) in before.iter_mut() {
            let (st, got) = c_vertices(view, h);
            match st {
                TpxStatus::Ok => {
                    assert!(
                        got == *row || follows_edit(row, &got, edit),
                        "{row:?} -> {got:?}"
                    );
                    *row = got;
                }
                TpxStatus::StaleHandle => assert!(!rust.contains(row), "{row:?} refused"),
                _ => panic!("{st:?}: {row:?}"),
            }
        }
        c_navigation_matches(view, &rust);
        for (h, row) in c_handles(view, &rust) {
            if before.len() < 96 && !before.iter().any(|(k, _)| *k == h) {
                before.push((h, row));
            }
        }
    }
    assert_eq!(
        unsafe { tpx_live_compact(live, std::ptr::null_mut(), 0, std::ptr::null_mut()) },
        TpxStatus::Ok
    );
    rust.compact();
    for (h, _) in &before {
        assert_eq!(c_vertices(view, h).0, TpxStatus::StaleGeneration);
    }
    c_navigation_matches(view, &rust);
    for (u, _) in undos {
        unsafe { tpx_undo_free(u) };
    }
    unsafe { tpx_live_free(live) };
});
