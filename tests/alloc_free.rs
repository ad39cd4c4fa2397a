//! Every handle operation through the C ABI allocates nothing on the query path: a counting
//! global allocator (per thread, armed only around each call) checks a second pass of every
//! operation over every simplex of every one of the nine structures, and of the live complex's
//! navigation on handles through a removed top simplex. The first pass warms what
//! may be kept between queries (this thread's answer buffers, the tables a structure builds on
//! first use). Failed calls are not counted: an error's message is the one allocation allowed.

mod common;

use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;
use std::ptr::{null, null_mut};

use topoplex_ffi::*;

struct Counting;

thread_local! {
    static ARMED: Cell<bool> = const { Cell::new(false) };
    static COUNT: Cell<u64> = const { Cell::new(0) };
}

fn note() {
    // `try_with`: the allocator may run while this thread's locals are being torn down.
    if ARMED.try_with(Cell::get).unwrap_or(false) {
        let _ = COUNT.try_with(|c| c.set(c.get() + 1));
    }
}

// SAFETY: forwards to the system allocator; counting touches only const thread-locals.
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        note();
        // SAFETY: the caller's contract, forwarded.
        unsafe { System.alloc(layout) }
    }
    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        note();
        // SAFETY: the caller's contract, forwarded.
        unsafe { System.alloc_zeroed(layout) }
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        note();
        // SAFETY: the caller's contract, forwarded.
        unsafe { System.realloc(ptr, layout, new_size) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        // SAFETY: the caller's contract, forwarded.
        unsafe { System.dealloc(ptr, layout) }
    }
}

#[global_allocator]
static ALLOC: Counting = Counting;

/// Calls made in the measured pass, and the allocating ones by name.
#[derive(Default)]
struct Tally {
    measure: bool,
    calls: usize,
    allocating: Vec<String>,
}

impl Tally {
    /// Runs `f` with the counter armed; in the measured pass, records a successful call that
    /// allocated.
    fn call(&mut self, what: impl FnOnce() -> String, f: impl FnOnce() -> TpxStatus) {
        COUNT.with(|c| c.set(0));
        ARMED.with(|a| a.set(true));
        let st = f();
        ARMED.with(|a| a.set(false));
        let n = COUNT.with(Cell::get);
        if self.measure && st == TpxStatus::Ok {
            self.calls += 1;
            if n > 0 {
                self.allocating
                    .push(format!("{} ({n} allocations)", what()));
            }
        }
    }
}

/// A complex through the C ABI, without coordinates.
fn complex(n: u32, simplices: &[&[u32]]) -> *mut TpxComplex {
    common::c_complex(n, simplices, None)
}

/// Every handle operation on every simplex of `s`, through the C ABI.
fn every_operation(s: *const TpxStructure, kind: u32, t: &mut Tally) {
    let mut d = 0u32;
    // SAFETY: live structure, valid out pointers (here and below).
    unsafe { tpx_structure_dimension(s, &mut d) };
    let mut ids = vec![0u32; 4096];
    let mut handles = vec![TpxSimplex::default(); 4096];
    let mut offsets = vec![0u32; 4096];
    let mut flags = vec![0u32; 4096];
    let (mut len, mut len2) = (0usize, 0usize);
    let mut word = 0u32;
    for p in 0..=d {
        let mut count = 0usize;
        unsafe { tpx_structure_count(s, p, &mut count) };
        let all: Vec<u32> = (0..count as u32).collect();
        let mut every = Vec::with_capacity(count);
        for i in 0..count as u32 {
            let name = |op: &str| format!("kind {kind}: {op} of {p}-simplex {i}");
            let mut h = TpxSimplex::default();
            t.call(
                || name("tpx_handle"),
                || unsafe { tpx_handle(s, p, i, &mut h) },
            );
            every.push(h);
            let mut verts = [0u32; 16];
            t.call(
                || name("tpx_simplex_vertices"),
                || unsafe { tpx_simplex_vertices(s, &h, verts.as_mut_ptr(), 16, &mut len) },
            );
            let mut again = TpxSimplex::default();
            t.call(
                || name("tpx_locate"),
                || unsafe { tpx_locate(s, verts.as_ptr(), p as usize + 1, &mut again) },
            );
            assert_eq!(again, h);
            t.call(
                || name("tpx_top_id"),
                || unsafe { tpx_top_id(s, &h, &mut word) },
            );
            for q in 0..=d {
                for order in [TPX_ORDER_NATURAL, TPX_ORDER_LEXICOGRAPHIC] {
                    t.call(
                        || name(&format!("tpx_related q={q} order={order}")),
                        || unsafe {
                            tpx_related(s, &h, q, order, ids.as_mut_ptr(), ids.len(), &mut len)
                        },
                    );
                }
                t.call(
                    || name(&format!("tpx_degree q={q}")),
                    || unsafe { tpx_degree(s, &h, q, &mut len) },
                );
            }
            for link in [0, 1] {
                for order in [TPX_ORDER_NATURAL, TPX_ORDER_LEXICOGRAPHIC] {
                    t.call(
                        || name(&format!("tpx_star link={link} order={order}")),
                        || unsafe {
                            tpx_star(
                                s,
                                &h,
                                link,
                                order,
                                handles.as_mut_ptr(),
                                handles.len(),
                                &mut len,
                            )
                        },
                    );
                }
            }
            for what in [0, 1] {
                t.call(
                    || name(&format!("tpx_simplex_test {what}")),
                    || unsafe { tpx_simplex_test(s, &h, what, &mut word) },
                );
            }
            let qs: &[u32] = match p {
                0 => &[0],
                1 => &[2, 3],
                _ => &[],
            };
            for &q in qs {
                t.call(
                    || name(&format!("tpx_cyclic q={q}")),
                    || unsafe {
                        tpx_cyclic(
                            s,
                            &h,
                            q,
                            ids.as_mut_ptr(),
                            ids.len(),
                            offsets.as_mut_ptr(),
                            flags.as_mut_ptr(),
                            flags.len() - 1,
                            &mut len,
                            &mut len2,
                        )
                    },
                );
            }
        }
        for q in 0..=d {
            t.call(
                || format!("kind {kind}: tpx_related_batch p={p} q={q}"),
                || unsafe {
                    tpx_related_batch(
                        s,
                        p,
                        all.as_ptr(),
                        all.len(),
                        q,
                        TPX_ORDER_NATURAL,
                        offsets.as_mut_ptr(),
                        ids.as_mut_ptr(),
                        ids.len(),
                        &mut len,
                    )
                },
            );
            t.call(
                || format!("kind {kind}: tpx_degree_batch p={p} q={q}"),
                || unsafe { tpx_degree_batch(s, p, all.as_ptr(), all.len(), q, ids.as_mut_ptr()) },
            );
            // The first call builds the index (the warm-up pass); later calls only lend it.
            let mut view = std::mem::MaybeUninit::<TpxRelationView>::zeroed();
            t.call(
                || format!("kind {kind}: tpx_relation_view p={p} q={q}"),
                || unsafe { tpx_relation_view(s, p, q, view.as_mut_ptr()) },
            );
            t.call(
                || format!("kind {kind}: tpx_related_handles_batch p={p} q={q}"),
                || unsafe {
                    tpx_related_handles_batch(
                        s,
                        every.as_ptr(),
                        every.len(),
                        q,
                        TPX_ORDER_LEXICOGRAPHIC,
                        offsets.as_mut_ptr(),
                        handles.as_mut_ptr(),
                        handles.len(),
                        &mut len,
                    )
                },
            );
        }
    }
    let mut tops = 0u32;
    unsafe { tpx_top_total(s, &mut tops) };
    for top in 0..tops {
        let mut h = TpxSimplex::default();
        let mut verts = [0u32; 16];
        t.call(
            || format!("kind {kind}: tpx_top {top}"),
            || unsafe { tpx_top(s, top, &mut h) },
        );
        t.call(
            || format!("kind {kind}: tpx_top_as_given {top}"),
            || unsafe { tpx_top_as_given(s, top, verts.as_mut_ptr(), 16, &mut len) },
        );
    }
}

/// Runs every operation twice on each of the nine structures of the complex of `simplices`
/// that can hold it; the second pass must not allocate, and over 1000 calls must have been
/// measured. Returns the number of structures.
fn check_complex(n: u32, simplices: &[&[u32]]) -> usize {
    let c = complex(n, simplices);
    let mut built = 0;
    let mut t = Tally::default();
    for kind in TPX_KIND_IG..=TPX_KIND_DE {
        let mut s = null_mut();
        // SAFETY: live complex, valid out pointer.
        if unsafe { tpx_structure_build(c, kind, &mut s) } != TpxStatus::Ok {
            // SAFETY: never NULL, NUL-terminated.
            let why = unsafe { std::ffi::CStr::from_ptr(tpx_last_error_message()) };
            eprintln!("kind {kind} not built: {why:?}");
            continue;
        }
        built += 1;
        t.measure = false;
        every_operation(s, kind, &mut t);
        t.measure = true;
        every_operation(s, kind, &mut t);
        // SAFETY: built above, freed once.
        unsafe { tpx_structure_free(s) };
    }
    // One line per operation that allocated (by kind and operation, simplices merged).
    let mut ops: Vec<&str> = t
        .allocating
        .iter()
        .map(|a| a.split(" of ").next().unwrap_or(a))
        .collect();
    ops.dedup();
    assert!(
        t.allocating.is_empty(),
        "{} of {} calls allocated, in {:#?}",
        t.allocating.len(),
        t.calls,
        ops
    );
    // SAFETY: built above.
    unsafe { tpx_complex_free(c) };
    assert!(t.calls > 1000, "{} calls measured", t.calls);
    built
}

#[test]
fn surface_with_pinch_fan_and_wire_allocates_nothing_in_any_structure() {
    //   2       4         a pinched pie (two fans at 0 sharing edge 0-1), a third triangle
    //  / \     / \        on 0-1 (non-manifold edge), a bowtie triangle at 5, a wire 6-7
    // 3---1---5---|---7   and an isolated vertex 8; windings mixed
    //  \  |  /    |  /
    //   `-0-'----'  6
    let built = check_complex(
        9,
        &[
            &[0, 1, 2],
            &[2, 3, 0],
            &[3, 1, 0],
            &[1, 0, 4],
            &[0, 4, 5],
            &[5, 1, 0],
            &[5, 6, 7],
            &[6, 7],
            &[7, 6, 8],
        ],
    );
    // IA needs a pseudo-manifold, LE connected vertex stars: the next fixture has both.
    assert_eq!(built, 7, "every structure but IA and LE holds this complex");
}

#[test]
fn open_octahedron_allocates_nothing_in_any_structure() {
    //        4            the octahedron on 0..5 (4 on top, 5 below the square 0-1-2-3)
    //      / | \          without its face 0 1 5: a disk-like pseudo-manifold with a
    //    3 --+-- 1         boundary cycle 0-1-5, windings mixed
    //      \ | /
    //        5     (0 and 2 at the back and front of the square)
    let built = check_complex(
        6,
        &[
            &[0, 1, 4],
            &[2, 1, 4],
            &[2, 3, 4],
            &[3, 0, 4],
            &[2, 5, 1],
            &[3, 2, 5],
            &[0, 3, 5],
        ],
    );
    assert_eq!(built, 9, "every structure holds a pseudo-manifold surface");
}

#[test]
fn tetrahedra_with_dangling_triangle_and_wire_allocate_nothing() {
    //          3 ------ 4 ------ 5    tetrahedra 0123 and 1235 (sharing 123), a dangling
    //         /|\      /              triangle 3 4 2 on edge 2-3, a wire 4-5, and a third
    //        / | \    /               tetrahedron 0 2 3 6 around edge 2-3
    //       0--|--2--/
    //        \ | /
    //         \|/
    //          1
    let built = check_complex(
        7,
        &[
            &[0, 1, 2, 3],
            &[1, 2, 3, 5],
            &[3, 4, 2],
            &[4, 5],
            &[0, 2, 3, 6],
        ],
    );
    assert!(
        built >= 4,
        "IG, SIG, IA and IQM hold a 3-complex ({built} built)"
    );
}

/// Handle calls of the live complex's navigation, on handles located before the edit, some of
/// them named through the removed top (located again on each use), and in one batch.
fn live_operations(s: *const TpxStructure, hs: &[TpxSimplex], d: u32, t: &mut Tally) {
    let mut handles = vec![TpxSimplex::default(); 4096];
    let mut offsets = vec![0u32; hs.len() + 1];
    let mut verts = [0u32; 16];
    let mut ids = vec![0u32; 4096];
    let mut len = 0usize;
    for (k, h) in hs.iter().enumerate() {
        let name = |op: &str| format!("live: {op} of handle {k}");
        t.call(
            || name("tpx_simplex_vertices"),
            || unsafe { tpx_simplex_vertices(s, h, verts.as_mut_ptr(), 16, &mut len) },
        );
        for q in 0..=d {
            t.call(
                || name(&format!("tpx_related_handles q={q}")),
                || unsafe {
                    tpx_related_handles(
                        s,
                        h,
                        q,
                        TPX_ORDER_NATURAL,
                        handles.as_mut_ptr(),
                        handles.len(),
                        &mut len,
                    )
                },
            );
            t.call(
                || name(&format!("tpx_degree q={q}")),
                || unsafe { tpx_degree(s, h, q, &mut len) },
            );
            // Dense indices of the live complex (its tables built by the warming pass).
            t.call(
                || name(&format!("tpx_related q={q}")),
                || unsafe {
                    tpx_related(
                        s,
                        h,
                        q,
                        TPX_ORDER_NATURAL,
                        ids.as_mut_ptr(),
                        ids.len(),
                        &mut len,
                    )
                },
            );
        }
        let mut index = 0u32;
        t.call(
            || name("tpx_simplex_index"),
            || unsafe { tpx_simplex_index(s, h, &mut index) },
        );
        t.call(
            || name("tpx_star"),
            || unsafe {
                tpx_star(
                    s,
                    h,
                    0,
                    TPX_ORDER_NATURAL,
                    handles.as_mut_ptr(),
                    handles.len(),
                    &mut len,
                )
            },
        );
    }
    for q in 0..=d {
        t.call(
            || format!("live: tpx_related_handles_batch q={q}"),
            || unsafe {
                tpx_related_handles_batch(
                    s,
                    hs.as_ptr(),
                    hs.len(),
                    q,
                    TPX_ORDER_LEXICOGRAPHIC,
                    offsets.as_mut_ptr(),
                    handles.as_mut_ptr(),
                    handles.len(),
                    &mut len,
                )
            },
        );
    }
}

#[test]
fn live_handles_through_a_removed_top_allocate_nothing() {
    // The tetrahedra above; then the dangling triangle 3 4 2 is removed. Edge 2-3 was named
    // through it (the lowest packed top holding it): that handle is located again on each use
    // (2-3 lives on in the tetrahedra); those of 3-4 and of the triangle are refused.
    let c = complex(
        7,
        &[
            &[0, 1, 2, 3],
            &[1, 2, 3, 5],
            &[3, 4, 2],
            &[4, 5],
            &[0, 2, 3, 6],
        ],
    );
    let (mut l, mut s) = (null_mut(), null());
    // SAFETY: valid complex and out pointers; the view is borrowed from `l`.
    unsafe {
        assert_eq!(tpx_live_from_complex(c, &mut l), TpxStatus::Ok);
        assert_eq!(tpx_live_structure(l, &mut s), TpxStatus::Ok);
    }
    let rows: [&[u32]; 6] = [
        &[2],
        &[2, 3],
        &[3, 4],
        &[2, 3, 4],
        &[1, 2, 3],
        &[0, 2, 3, 6],
    ];
    let hs: Vec<TpxSimplex> = rows
        .iter()
        .map(|r| {
            let mut h = TpxSimplex::default();
            // SAFETY: as above.
            assert_eq!(
                unsafe { tpx_locate(s, r.as_ptr(), r.len(), &mut h) },
                TpxStatus::Ok
            );
            h
        })
        .collect();
    // SAFETY: as above.
    unsafe {
        assert_eq!(
            tpx_live_remove_top(l, [3u32, 4, 2].as_ptr(), 3),
            TpxStatus::Ok
        );
    }
    let hs: Vec<TpxSimplex> = hs
        .into_iter()
        .filter(|h| {
            let mut n = 0usize;
            // SAFETY: as above.
            unsafe { tpx_degree(s, h, 0, &mut n) == TpxStatus::Ok }
        })
        .collect();
    assert_eq!(
        hs.len(),
        4,
        "2, 2-3, 1 2 3 and 0 2 3 6 live on; 3-4 and 3 4 2 are gone"
    );
    let mut t = Tally::default();
    live_operations(s, &hs, 3, &mut t);
    t.measure = true;
    live_operations(s, &hs, 3, &mut t);
    // SAFETY: created above, freed once.
    unsafe {
        tpx_live_free(l);
        tpx_complex_free(c);
    }
    assert!(t.allocating.is_empty(), "allocating: {:?}", t.allocating);
    assert!(t.calls > 40, "{} calls measured", t.calls);
}

/// Both link checks of the live complex (`tpx_live_link_condition` and, the one behind
/// `simplify --preserve-topology` and `TPX_CONTRACT_PRESERVE_MANIFOLD`,
/// `tpx_live_link_condition_with_boundary`) on every edge of a 3×3 grid of squares cut in two
/// (a disk: interior edges, boundary edges, and interior edges joining two boundary vertices,
/// which the coned test refuses) allocate nothing once warm; the refusals are not measured
/// (their message allocates).
///
/// ```text
///   12-13-14-15
///   | /| /| /|
///   8--9-10-11
///   | /| /| /|
///   4--5--6--7
///   | /| /| /|
///   0--1--2--3
/// ```
#[test]
fn live_link_checks_allocate_nothing() {
    let mut tris: Vec<[u32; 3]> = Vec::new();
    for i in 0..3u32 {
        for j in 0..3u32 {
            let v = 4 * i + j;
            tris.push([v, v + 1, v + 5]);
            tris.push([v, v + 5, v + 4]);
        }
    }
    let rows: Vec<&[u32]> = tris.iter().map(|t| &t[..]).collect();
    let c = complex(16, &rows);
    let mut l = null_mut();
    // SAFETY: valid complex and out pointer.
    unsafe { assert_eq!(tpx_live_from_complex(c, &mut l), TpxStatus::Ok) };
    let mut edges: Vec<(u32, u32)> = tris
        .iter()
        .flat_map(|t| [(t[0], t[1]), (t[1], t[2]), (t[0], t[2])])
        .map(|(a, b)| (a.min(b), a.max(b)))
        .collect();
    edges.sort_unstable();
    edges.dedup();
    let mut t = Tally::default();
    let (mut passed, mut refused) = (0, 0);
    for measure in [false, true] {
        t.measure = measure;
        for &(a, b) in &edges {
            // SAFETY: `l` is alive (here and below).
            t.call(
                || format!("link condition {a}-{b}"),
                || unsafe { tpx_live_link_condition(l, a, b) },
            );
            t.call(
                || format!("coned link condition {a}-{b}"),
                || {
                    let st = unsafe { tpx_live_link_condition_with_boundary(l, a, b) };
                    if measure {
                        if st == TpxStatus::Ok {
                            passed += 1
                        } else {
                            refused += 1
                        }
                    }
                    st
                },
            );
        }
    }
    // SAFETY: created above, freed once.
    unsafe {
        tpx_live_free(l);
        tpx_complex_free(c);
    }
    assert!(t.allocating.is_empty(), "allocating: {:?}", t.allocating);
    assert!(
        passed > 10 && refused > 0,
        "{passed} passed, {refused} refused"
    );
}
