#![no_main]
//! Call sequences through the C ABI, as a C caller might make them: complexes from arbitrary
//! arrays (invalid ones included), every kind, queries with arbitrary (often invalid) simplices,
//! dimensions and buffer sizes, relation tables, decompositions, frees in any order. Nothing may
//! panic (TPX_STATUS_PANIC fails the run), and every successful answer must equal the Rust API's.
use libfuzzer_sys::fuzz_target;
use std::ptr::{null, null_mut};
use topoplex::ffi::*;
use topoplex::relation::sort_rows;

struct Bytes<'a>(&'a [u8]);

impl Bytes<'_> {
    fn next(&mut self) -> u8 {
        let Some((&b, rest)) = self.0.split_first() else {
            return 0;
        };
        self.0 = rest;
        b
    }
}

fuzz_target!(|data: &[u8]| {
    let mut b = Bytes(data);
    let (n, list) = topoplex_fuzz_support::decode(&data[..data.len().min(64)]);
    b.0 = &data[data.len().min(64)..];
    let mut ids = Vec::new();
    let mut offsets = vec![0usize];
    for s in &list {
        ids.extend_from_slice(s);
        offsets.push(ids.len());
    }
    let mut complex = null_mut();
    let st = unsafe {
        tpx_complex_from_arrays(
            n,
            ids.as_ptr(),
            offsets.as_ptr(),
            list.len(),
            null(),
            0,
            &mut complex,
        )
    };
    assert_ne!(st, TpxStatus::Panic);
    if st != TpxStatus::Ok {
        assert!(complex.is_null());
        return;
    }
    let refs: Vec<&[u32]> = list.iter().map(Vec::as_slice).collect();
    let rust = topoplex::Complex::from_simplices(n, &refs).expect("the ABI accepted it");
    let kind = u32::from(b.next() % 11); // 9 and 10 are unknown kinds
    let mut s = null_mut();
    let st = unsafe { tpx_structure_build(complex, kind, &mut s) };
    assert_ne!(st, TpxStatus::Panic);
    if b.next() % 2 == 0 {
        // Free the complex early: structures do not borrow it.
        unsafe { tpx_complex_free(complex) };
        complex = null_mut();
    }
    if st == TpxStatus::Ok {
        let kind = topoplex::StructureKind::ALL[kind as usize];
        let topo = topoplex::build(kind, &rust).expect("the ABI built it");
        for _ in 0..16 {
            let len = usize::from(b.next() % 5);
            let sigma: Vec<u32> = (0..len).map(|_| u32::from(b.next() % 14)).collect();
            let q = u32::from(b.next() % 5);
            let cap = usize::from(b.next());
            let mut buf = vec![0u32; cap];
            let mut out_len = 0usize;
            let st = unsafe {
                tpx_relation(
                    s,
                    sigma.as_ptr(),
                    sigma.len(),
                    q,
                    buf.as_mut_ptr(),
                    cap,
                    &mut out_len,
                )
            };
            assert_ne!(st, TpxStatus::Panic);
            let mut want = Vec::new();
            let expected = topo.relation(&sigma, q as usize, &mut want);
            match st {
                TpxStatus::Ok => {
                    sort_rows(&mut want, q as usize + 1);
                    assert_eq!(&buf[..out_len], &want[..]);
                }
                TpxStatus::BufferTooSmall => {
                    assert!(expected.is_ok());
                    assert_eq!(out_len, want.len());
                    assert!(cap < want.len());
                }
                _ => assert!(expected.is_err(), "{st:?} but the Rust API answered"),
            }
            if b.next() % 4 == 0 {
                let (p, q) = (u32::from(b.next() % 5), u32::from(b.next() % 5));
                let mut t = null_mut();
                let st = unsafe { tpx_relation_table(s, p, q, &mut t) };
                assert_ne!(st, TpxStatus::Panic);
                unsafe { tpx_relation_table_free(t) };
            }
        }
    }
    if !complex.is_null() && b.next() % 3 == 0 {
        let mut d = null_mut();
        assert_eq!(
            unsafe { tpx_decomposition_build(complex, &mut d) },
            TpxStatus::Ok
        );
        let mut count = 0usize;
        unsafe { tpx_decomposition_component_count(d, &mut count) };
        unsafe { tpx_decomposition_free(d) };
    }
    unsafe {
        tpx_structure_free(s);
        tpx_complex_free(complex);
    }
});
