#![no_main]
//! Call sequences through the C ABI, as a C caller might make them: complexes from arbitrary
//! arrays (invalid ones included), every kind, queries with arbitrary (often invalid) simplices,
//! dimensions and buffer sizes, relation tables, decompositions, frees in any order. Nothing may
//! panic (TPX_STATUS_PANIC fails the run), and every successful answer must equal the Rust API's.
use libfuzzer_sys::fuzz_target;
use std::ptr::null_mut;
use topoplex::relation::sort_rows;
use topoplex_ffi::*;

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
    let (st, mut complex) = topoplex_fuzz_support::c_complex(n, &list);
    assert_ne!(st, TpxStatus::Panic);
    if st != TpxStatus::Ok {
        assert!(complex.is_null());
        return;
    }
    let refs: Vec<&[u32]> = list.iter().map(Vec::as_slice).collect();
    let rust = topoplex::Complex::from_simplices(n, &refs).expect("the ABI accepted it");
    let kind = u32::from(b.next() % 11); // 9 is the live complex, 10 an unknown kind
    let mut s = null_mut();
    let st = unsafe { tpx_structure_build(complex, kind, &mut s) };
    assert_ne!(st, TpxStatus::Panic);
    if b.next() % 2 == 0 {
        // Free the complex early: structures do not borrow it.
        unsafe { tpx_complex_free(complex) };
        complex = null_mut();
    }
    if st == TpxStatus::Ok {
        let kind = topoplex::StructureKind::from_abi(kind).expect("the ABI built it");
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
        handle_calls(s, topo.as_ref(), &mut b);
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

/// Handle calls with arbitrary (often bad) handles: located ones, ones built from arbitrary
/// words, ones with another owner. Successful answers must equal the Rust API's; no panic.
fn handle_calls(s: *const TpxStructure, topo: &dyn topoplex::Topology, b: &mut Bytes) {
    let nav = topo.as_navigate().expect("every structure navigates");
    let mut stamp = 0u32;
    assert_eq!(unsafe { tpx_structure_stamp(s, &mut stamp) }, TpxStatus::Ok);
    let mut asked = Vec::new();
    for _ in 0..8 {
        let mut h = TpxSimplex::default();
        let st = match b.next() % 3 {
            0 => {
                let len = usize::from(b.next() % 5);
                let sigma: Vec<u32> = (0..len).map(|_| u32::from(b.next() % 14)).collect();
                unsafe { tpx_locate(s, sigma.as_ptr(), sigma.len(), &mut h) }
            }
            1 => unsafe {
                tpx_handle(s, u32::from(b.next() % 5), u32::from(b.next() % 40), &mut h)
            },
            _ => {
                h = TpxSimplex {
                    index: u32::from(b.next()) * 3,
                    meta: u32::from(b.next() % 20) | u32::from(b.next() % 3) << 8,
                    owner: if b.next().is_multiple_of(2) {
                        stamp
                    } else {
                        u32::from(b.next())
                    },
                };
                TpxStatus::Ok
            }
        };
        assert_ne!(st, TpxStatus::Panic);
        asked.push(h);
        let q = u32::from(b.next() % 5);
        let order = u32::from(b.next() % 3);
        let cap = usize::from(b.next() % 64);
        let mut buf = vec![0u32; cap];
        let mut len = 0usize;
        let st = unsafe { tpx_related(s, &h, q, order, buf.as_mut_ptr(), cap, &mut len) };
        assert_ne!(st, TpxStatus::Panic);
        if st == TpxStatus::Ok && order == TPX_ORDER_LEXICOGRAPHIC {
            let sh = nav
                .handle((h.meta & 0xff) as usize, h.index)
                .expect("accepted");
            let mut want = Vec::new();
            nav.related(sh, q as usize, topoplex::Order::Lexicographic, &mut want)
                .expect("the ABI answered");
            let want: Vec<u32> = want.iter().map(|x| x.index()).collect();
            assert_eq!(&buf[..len], &want[..]);
        }
        let mut deg = 0usize;
        let st = unsafe { tpx_degree(s, &h, q, &mut deg) };
        assert_ne!(st, TpxStatus::Panic);
        // The counts-only batch and the lent view answer as the per-handle calls do.
        let p = h.meta & 0xff;
        let mut degs = [0u32; 1];
        let bst = unsafe { tpx_degree_batch(s, p, &h.index, 1, q, degs.as_mut_ptr()) };
        assert_ne!(bst, TpxStatus::Panic);
        if st == TpxStatus::Ok && h.owner == stamp && h.meta >> 8 == 0 {
            assert_eq!((bst, degs[0] as usize), (TpxStatus::Ok, deg));
        }
        let mut view = std::mem::MaybeUninit::<TpxRelationView>::zeroed();
        let vst = unsafe { tpx_relation_view(s, p, q, view.as_mut_ptr()) };
        assert_ne!(vst, TpxStatus::Panic);
        if vst == TpxStatus::Ok && st == TpxStatus::Ok && h.owner == stamp && h.meta >> 8 == 0 {
            let v = unsafe { view.assume_init() };
            let i = h.index as usize;
            let (a, z) = unsafe { (*v.offsets.add(i), *v.offsets.add(i + 1)) };
            assert_eq!((z - a) as usize, deg);
        }
        let mut flag = 0u32;
        let what = u32::from(b.next() % 3);
        assert_ne!(
            unsafe { tpx_simplex_test(s, &h, what, &mut flag) },
            TpxStatus::Panic
        );
        let mut stars = vec![TpxSimplex::default(); cap];
        let st = unsafe {
            tpx_star(
                s,
                &h,
                u32::from(b.next() % 2),
                order,
                stars.as_mut_ptr(),
                cap,
                &mut len,
            )
        };
        assert_ne!(st, TpxStatus::Panic);
        let (mut offsets, mut flags) = (vec![0u32; 9], vec![0u32; 8]);
        let (mut ni, mut ng) = (0usize, 0usize);
        let st = unsafe {
            tpx_cyclic(
                s,
                &h,
                q,
                buf.as_mut_ptr(),
                cap,
                offsets.as_mut_ptr(),
                flags.as_mut_ptr(),
                8,
                &mut ni,
                &mut ng,
            )
        };
        assert_ne!(st, TpxStatus::Panic);
        let mut top = u32::MAX;
        assert_ne!(unsafe { tpx_top_id(s, &h, &mut top) }, TpxStatus::Panic);
        let st = unsafe { tpx_top_as_given(s, top, buf.as_mut_ptr(), cap, &mut len) };
        assert_ne!(st, TpxStatus::Panic);
    }
    batch_call(s, nav, &asked[..usize::from(b.next() % 9)], b);
}

/// `tpx_related_handles_batch` over the handles tried (often bad): no panic, and a success
/// equals the Rust API's answers, handle by handle.
fn batch_call(
    s: *const TpxStructure,
    nav: &dyn topoplex::Navigate,
    asked: &[TpxSimplex],
    b: &mut Bytes,
) {
    let q = u32::from(b.next() % 5);
    let order = u32::from(b.next() % 3);
    let cap = usize::from(b.next() % 96);
    let mut buf = vec![TpxSimplex::default(); cap];
    let mut offsets = vec![u32::MAX; asked.len() + 1];
    let offsets_ptr = if b.next().is_multiple_of(16) {
        null_mut()
    } else {
        offsets.as_mut_ptr()
    };
    let mut len = 0usize;
    let st = unsafe {
        tpx_related_handles_batch(
            s,
            asked.as_ptr(),
            asked.len(),
            q,
            order,
            offsets_ptr,
            buf.as_mut_ptr(),
            cap,
            &mut len,
        )
    };
    assert_ne!(st, TpxStatus::Panic);
    if st != TpxStatus::Ok {
        assert!(
            offsets.iter().all(|&o| o == u32::MAX),
            "offsets written on {st:?}"
        );
        return;
    }
    let order = [topoplex::Order::Natural, topoplex::Order::Lexicographic][order as usize];
    let mut want = Vec::new();
    assert_eq!(offsets[asked.len()] as usize, len);
    for (k, h) in asked.iter().enumerate() {
        let sh = nav
            .handle((h.meta & 0xff) as usize, h.index)
            .expect("accepted");
        nav.related(sh, q as usize, order, &mut want)
            .expect("the ABI answered");
        let got: Vec<u32> = buf[offsets[k] as usize..offsets[k + 1] as usize]
            .iter()
            .map(|x| x.index)
            .collect();
        let want: Vec<u32> = want.iter().map(|x| x.index()).collect();
        assert_eq!(got, want);
    }
}
