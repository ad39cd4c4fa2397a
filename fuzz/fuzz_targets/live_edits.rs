#![no_main]
//! Differential: random edit sequences (insert, remove, contract in both modes, split, move a
//! vertex) on a complex built from arbitrary bytes, through the C ABI (`TpxLive`) and the Rust
//! API side by side. Both must agree on every outcome, stay valid, and (compacted) answer every
//! relation like the brute-force oracle on their own `to_complex()`.
use libfuzzer_sys::fuzz_target;
use topoplex::ffi::*;
use topoplex::live::{ContractMode, LiveComplex, VertexId};
use topoplex::oracle::check_structure;
use topoplex::{Complex, Topology};

fuzz_target!(|data: &[u8]| {
    let split = data.first().map_or(0, |&b| b as usize).min(data.len());
    let (n, list) = topoplex_fuzz_support::decode(&data[..split]);
    let refs: Vec<&[u32]> = list.iter().map(Vec::as_slice).collect();
    let Ok(c) = Complex::from_simplices(n, &refs) else {
        return;
    };
    let mut rust = LiveComplex::from_complex(&c);
    let ids: Vec<u32> = list.iter().flatten().copied().collect();
    let mut offsets = vec![0usize];
    offsets.extend(list.iter().scan(0, |o, s| {
        *o += s.len();
        Some(*o)
    }));
    let mut tc: *mut TpxComplex = std::ptr::null_mut();
    let mut live: *mut TpxLive = std::ptr::null_mut();
    unsafe {
        let st = tpx_complex_from_arrays(n, ids.as_ptr(), offsets.as_ptr(), list.len(), std::ptr::null(), 0, &mut tc);
        assert_eq!(st, TpxStatus::Ok);
        assert_eq!(tpx_live_from_complex(tc, &mut live), TpxStatus::Ok);
        tpx_complex_free(tc);
    }
    let mut undos: Vec<(*mut TpxUndo, topoplex::live::UndoRecord)> = Vec::new();
    for op in data[split..].chunks(4) {
        let &[kind, x, y, z] = op else { break };
        let n = rust.vertex_slots().max(1);
        let (a, b) = (x as u32 % (n + 1), y as u32 % (n + 1));
        let sigma: Vec<u32> = [a, b, z as u32 % (n + 1)][..1 + (kind as usize >> 4) % 3].to_vec();
        let (st, ok) = match kind % 5 {
            0 => unsafe {
                (tpx_live_insert_top(live, sigma.as_ptr(), sigma.len()), rust.insert_top(&sigma).is_ok())
            },
            1 => unsafe {
                (tpx_live_remove_top(live, sigma.as_ptr(), sigma.len()), rust.remove_top(&sigma).is_ok())
            },
            2 | 3 => {
                let (mode, m) = if kind % 5 == 2 {
                    (TPX_CONTRACT_PRESERVE_TOPOLOGY, ContractMode::PreserveTopology)
                } else {
                    (TPX_CONTRACT_FREE, ContractMode::Free)
                };
                let mut u: *mut TpxUndo = std::ptr::null_mut();
                let st = unsafe { tpx_live_contract(live, a, b, mode, std::ptr::null(), 0, &mut u) };
                let r = rust.contract(VertexId(a), VertexId(b), m, None);
                let ok = r.is_ok();
                if let Ok(rec) = r {
                    undos.push((u, rec));
                }
                (st, ok)
            }
            _ => match undos.pop() {
                Some((u, rec)) => {
                    let st = unsafe { tpx_live_split(live, u) };
                    unsafe { tpx_undo_free(u) };
                    (st, rust.split(&rec).is_ok())
                }
                None => continue,
            },
        };
        assert_eq!(st == TpxStatus::Ok, ok, "C ABI and Rust disagree on {op:?}: {st:?}");
        assert_eq!(unsafe { tpx_live_validate(live) }, TpxStatus::Ok);
        rust.validate().unwrap();
        let mut dense = rust.clone();
        dense.compact();
        check_structure(&dense, &rust.to_complex()).unwrap();
    }
    for (u, _) in undos {
        unsafe { tpx_undo_free(u) };
    }
    unsafe { tpx_live_free(live) };
});
