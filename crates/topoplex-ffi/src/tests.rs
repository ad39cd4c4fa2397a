//! The ABI called from Rust as C would call it. No file IO, no FFI to C and small inputs, so
//! that `cargo +nightly miri test --lib ffi` can check the unsafe code (Stacked Borrows, leaks).

use std::ffi::CStr;
use std::ptr::{null, null_mut};

use super::*;

fn last_error() -> String {
    // SAFETY: tpx_last_error_message never returns NULL and the string is NUL-terminated.
    unsafe { CStr::from_ptr(tpx_last_error_message()) }
        .to_str()
        .unwrap()
        .to_string()
}

/// Builds a complex from a list of simplices through the ABI.
fn complex(n: u32, simplices: &[&[u32]]) -> *mut TpxComplex {
    let mut ids = Vec::new();
    let mut offsets = vec![0usize];
    for s in simplices {
        ids.extend_from_slice(s);
        offsets.push(ids.len());
    }
    let mut out = null_mut();
    let st = unsafe {
        tpx_complex_from_arrays(
            n,
            ids.as_ptr(),
            offsets.as_ptr(),
            simplices.len(),
            null(),
            0,
            &mut out,
        )
    };
    assert_eq!(st, TpxStatus::Ok, "{}", last_error());
    assert!(!out.is_null());
    out
}

/// A tetrahedron 0123, a dangling triangle 2 3 4 on its edge 2-3, and a wire edge 4-5.
///
/// ```text
///          3 ------ 4 ------ 5
///         /|\      /
///        / | \    /
///       0--|--2--/
///        \ | /
///         \|/
///          1
/// ```
fn tet_triangle_wire() -> *mut TpxComplex {
    complex(6, &[&[0, 1, 2, 3], &[2, 3, 4], &[4, 5]])
}

fn ig(c: *const TpxComplex) -> *mut TpxStructure {
    let mut s = null_mut();
    let st = unsafe { tpx_structure_build(c, TPX_KIND_IG, &mut s) };
    assert_eq!(st, TpxStatus::Ok, "{}", last_error());
    s
}

/// Calls tpx_relation with a buffer of `cap` entries; returns the status, the filled prefix and
/// `*out_len` (or the sentinel if untouched).
fn relation(s: *const TpxStructure, sigma: &[u32], q: u32, cap: usize) -> (TpxStatus, Vec<u32>) {
    let mut buf = vec![u32::MAX; cap];
    let mut len = 7777usize;
    let st = unsafe {
        tpx_relation(
            s,
            sigma.as_ptr(),
            sigma.len(),
            q,
            buf.as_mut_ptr(),
            cap,
            &mut len,
        )
    };
    if st == TpxStatus::Ok {
        buf.truncate(len);
    }
    (st, buf)
}

#[test]
fn status_numbers_are_the_agreed_abi() {
    use TpxStatus::*;
    let all = [
        Ok,
        NullArgument,
        InvalidArgument,
        IoError,
        ParseError,
        InvalidComplex,
        UnknownKind,
        NotImplemented,
        UnsupportedComplex,
        NotInComplex,
        InvalidSimplex,
        DimensionOutOfRange,
        BufferTooSmall,
        TooLarge,
        Panic,
    ];
    for (i, s) in all.into_iter().enumerate() {
        assert_eq!(s as u32, i as u32, "{s:?}");
    }
    // Saved files: 40..=44.
    let saved = [
        SavedFileCorrupt,
        SavedFileTruncated,
        SavedFileWrongVersion,
        SavedFileForeign,
        SavedFileWrongEndianness,
    ];
    for (i, s) in saved.into_iter().enumerate() {
        assert_eq!(s as u32, 40 + i as u32, "{s:?}");
    }
    let kinds = topoplex::relation::StructureKind::ALL;
    assert_eq!([TPX_KIND_IG, TPX_KIND_DE], [0, kinds.len() as u32 - 1]);
}

#[test]
fn version_is_the_crate_version() {
    let v = unsafe { CStr::from_ptr(tpx_version()) };
    assert_eq!(v.to_str().unwrap(), env!("CARGO_PKG_VERSION"));
}

#[test]
fn lifecycle_of_the_tetrahedron_with_triangle_and_wire() {
    let c = tet_triangle_wire();
    let (mut d, mut n, mut tops) = (99u32, 99u32, [99usize; 5]);
    unsafe {
        assert_eq!(tpx_complex_dimension(c, &mut d), TpxStatus::Ok);
        assert_eq!(tpx_complex_vertex_count(c, &mut n), TpxStatus::Ok);
        for (p, t) in tops.iter_mut().enumerate() {
            assert_eq!(tpx_complex_top_count(c, p as u32, t), TpxStatus::Ok);
        }
    }
    assert_eq!((d, n, tops), (3, 6, [0, 1, 1, 1, 0]));
    assert_eq!(last_error(), "");

    let s = ig(c);
    // The structure owns its data: the complex can go first.
    unsafe { tpx_complex_free(c) };
    let (mut kind, mut sd) = (99u32, 99u32);
    let mut counts = [99usize; 5];
    let mut top_counts = [99usize; 5];
    let mut storage = TpxStorage::default();
    unsafe {
        assert_eq!(tpx_structure_kind(s, &mut kind), TpxStatus::Ok);
        assert_eq!(tpx_structure_dimension(s, &mut sd), TpxStatus::Ok);
        for p in 0..5 {
            assert_eq!(
                tpx_structure_count(s, p as u32, &mut counts[p]),
                TpxStatus::Ok
            );
            assert_eq!(
                tpx_structure_top_count(s, p as u32, &mut top_counts[p]),
                TpxStatus::Ok
            );
        }
        assert_eq!(tpx_structure_storage(s, &mut storage), TpxStatus::Ok);
    }
    assert_eq!((kind, sd), (TPX_KIND_IG, 3));
    // 6 vertices; 6 tet edges + 2-4, 3-4, 4-5; 4 tet faces + 2 3 4; the tetrahedron.
    assert_eq!(counts, [6, 9, 5, 1, 0]);
    assert_eq!(top_counts, [0, 1, 1, 1, 0]);
    assert!(storage.bytes > 0 && storage.integers > 0);

    // Triangles on edge 2-3, given in the other order.
    let (st, rows) = relation(s, &[3, 2], 2, 16);
    assert_eq!(st, TpxStatus::Ok);
    assert_eq!(rows, [0, 2, 3, 1, 2, 3, 2, 3, 4]);
    // Edges at vertex 4.
    assert_eq!(relation(s, &[4], 1, 6).1, [2, 4, 3, 4, 4, 5]);
    // Boundary vertices of the dangling triangle.
    assert_eq!(relation(s, &[4, 3, 2], 0, 3).1, [2, 3, 4]);
    // Vertex 5 is on no triangle: an empty answer, with a NULL buffer.
    let mut len = 7usize;
    let st = unsafe { tpx_relation(s, [5u32].as_ptr(), 1, 2, null_mut(), 0, &mut len) };
    assert_eq!((st, len), (TpxStatus::Ok, 0));

    unsafe { tpx_structure_free(s) };
}

#[test]
fn simplices_in_lexicographic_order_and_buffer_too_small() {
    let c = tet_triangle_wire();
    let s = ig(c);
    let mut buf = [u32::MAX; 32];
    let mut len = 0usize;
    let st = unsafe { tpx_structure_simplices(s, 2, buf.as_mut_ptr(), buf.len(), &mut len) };
    assert_eq!(st, TpxStatus::Ok);
    assert_eq!(&buf[..len], [0, 1, 2, 0, 1, 3, 0, 2, 3, 1, 2, 3, 2, 3, 4]);

    // Size query with a NULL buffer, then too small: only *out_len is written.
    let mut len = 0usize;
    let st = unsafe { tpx_structure_simplices(s, 1, null_mut(), 0, &mut len) };
    assert_eq!((st, len), (TpxStatus::BufferTooSmall, 18));
    let mut small = [u32::MAX; 4];
    let mut len = 0usize;
    let st = unsafe { tpx_structure_simplices(s, 1, small.as_mut_ptr(), 4, &mut len) };
    assert_eq!((st, len), (TpxStatus::BufferTooSmall, 18));
    assert_eq!(small, [u32::MAX; 4]);
    assert!(last_error().contains("18"), "{}", last_error());

    let (st, untouched) = relation(s, &[2, 3], 2, 8);
    assert_eq!(st, TpxStatus::BufferTooSmall);
    assert_eq!(untouched, [u32::MAX; 8]);
    let mut len = 0usize;
    let st = unsafe { tpx_relation(s, [2u32, 3].as_ptr(), 2, 2, null_mut(), 0, &mut len) };
    assert_eq!((st, len), (TpxStatus::BufferTooSmall, 9));

    // A non-NULL need with a NULL buffer claiming room is a NULL argument.
    let st = unsafe { tpx_relation(s, [2u32, 3].as_ptr(), 2, 2, null_mut(), 9, &mut len) };
    assert_eq!(st, TpxStatus::NullArgument);

    unsafe {
        tpx_structure_free(s);
        tpx_complex_free(c);
    }
}

#[test]
fn relation_table_of_edges_at_each_vertex() {
    let c = tet_triangle_wire();
    let s = ig(c);
    let mut t = null_mut();
    assert_eq!(
        unsafe { tpx_relation_table(s, 0, 1, &mut t) },
        TpxStatus::Ok
    );
    let (mut no, mut ni) = (0usize, 0usize);
    let (offsets, ids) = unsafe {
        let o = tpx_relation_table_offsets(t, &mut no);
        let i = tpx_relation_table_ids(t, &mut ni);
        (
            std::slice::from_raw_parts(o, no).to_vec(),
            std::slice::from_raw_parts(i, ni).to_vec(),
        )
    };
    assert_eq!(offsets, [0, 6, 12, 20, 28, 34, 36]);
    #[rustfmt::skip]
    assert_eq!(ids, [
        0, 1, 0, 2, 0, 3,        // vertex 0
        0, 1, 1, 2, 1, 3,        // vertex 1
        0, 2, 1, 2, 2, 3, 2, 4,  // vertex 2
        0, 3, 1, 3, 2, 3, 3, 4,  // vertex 3
        2, 4, 3, 4, 4, 5,        // vertex 4
        4, 5,                    // vertex 5
    ]);
    unsafe {
        assert!(tpx_relation_table_offsets(null(), &mut no).is_null());
        assert!(tpx_relation_table_ids(t, null_mut()).is_null());
        tpx_relation_table_free(t);
        let mut t = null_mut();
        assert_eq!(
            tpx_relation_table(s, 4, 0, &mut t),
            TpxStatus::DimensionOutOfRange
        );
        assert_eq!(
            tpx_relation_table(s, 0, 4, &mut t),
            TpxStatus::DimensionOutOfRange
        );
        assert!(t.is_null());
        tpx_structure_free(s);
        tpx_complex_free(c);
    }
}

/// Calls tpx_complex_top_simplices with a buffer of `cap` entries; returns the status, the
/// filled prefix (or the untouched buffer) and `*out_len` (7777 if untouched).
fn top_simplices(c: *const TpxComplex, p: u32, cap: usize) -> (TpxStatus, Vec<u32>, usize) {
    let mut buf = vec![u32::MAX; cap];
    let mut len = 7777usize;
    let st = unsafe { tpx_complex_top_simplices(c, p, buf.as_mut_ptr(), cap, &mut len) };
    if st == TpxStatus::Ok {
        buf.truncate(len);
    }
    (st, buf, len)
}

#[test]
fn top_simplices_and_coordinates_give_back_the_complex() {
    // Two triangles given unsorted, one a duplicate, plus an isolated vertex 4 and a face of
    // the first triangle (absorbed).
    //
    //   2 ---- 3       4 (isolated)
    //   | \    |
    //   |  \   |
    //   0 ---- 1
    let ids = [2u32, 1, 0, 1, 3, 2, 0, 2, 1, 0, 1];
    let offsets = [0usize, 3, 6, 9, 11];
    #[rustfmt::skip]
    let coords = [
        0.0, 0.0, 0.5,
        1.0, 0.0, 0.5,
        0.0, 1.0, 0.5,
        1.0, 1.0, 0.5,
        9.0, 9.0, 9.0,
    ];
    let mut c = null_mut();
    let st = unsafe {
        tpx_complex_from_arrays(
            5,
            ids.as_ptr(),
            offsets.as_ptr(),
            4,
            coords.as_ptr(),
            3,
            &mut c,
        )
    };
    assert_eq!(st, TpxStatus::Ok, "{}", last_error());

    assert_eq!(
        top_simplices(c, 2, 6),
        (TpxStatus::Ok, vec![0, 1, 2, 1, 2, 3], 6)
    );
    assert_eq!(top_simplices(c, 1, 0), (TpxStatus::Ok, vec![], 0));
    assert_eq!(top_simplices(c, 0, 1), (TpxStatus::Ok, vec![4], 1));
    // Too small: nothing copied, the needed length reported; a NULL buffer asks for the size.
    assert_eq!(
        top_simplices(c, 2, 5),
        (TpxStatus::BufferTooSmall, vec![u32::MAX; 5], 6)
    );
    let mut len = 0usize;
    let st = unsafe { tpx_complex_top_simplices(c, 2, null_mut(), 0, &mut len) };
    assert_eq!((st, len), (TpxStatus::BufferTooSmall, 6));
    assert_eq!(
        top_simplices(c, 3, 16),
        (TpxStatus::DimensionOutOfRange, vec![u32::MAX; 16], 7777)
    );
    assert!(last_error().contains("p = 3"), "{}", last_error());

    let mut dim = 99usize;
    assert_eq!(unsafe { tpx_complex_coord_dim(c, &mut dim) }, TpxStatus::Ok);
    assert_eq!(dim, 3);
    let mut buf = [f64::NAN; 15];
    let mut len = 0usize;
    let st = unsafe { tpx_complex_coords(c, buf.as_mut_ptr(), 15, &mut len) };
    assert_eq!((st, len), (TpxStatus::Ok, 15));
    assert_eq!(buf, coords);
    let mut small = [f64::NAN; 14];
    let mut len = 0usize;
    let st = unsafe { tpx_complex_coords(c, small.as_mut_ptr(), 14, &mut len) };
    assert_eq!((st, len), (TpxStatus::BufferTooSmall, 15));
    assert!(small.iter().all(|x| x.is_nan()));
    assert!(last_error().contains("14 double"), "{}", last_error());
    unsafe { tpx_complex_free(c) };

    // Without coordinates: dimension 0 and an empty answer, even into a NULL buffer.
    let c = tet_triangle_wire();
    let (mut dim, mut len) = (99usize, 99usize);
    unsafe {
        assert_eq!(tpx_complex_coord_dim(c, &mut dim), TpxStatus::Ok);
        assert_eq!(
            tpx_complex_coords(c, null_mut(), 0, &mut len),
            TpxStatus::Ok
        );
    }
    assert_eq!((dim, len), (0, 0));
    assert_eq!(top_simplices(c, 3, 4), (TpxStatus::Ok, vec![0, 1, 2, 3], 4));
    assert_eq!(top_simplices(c, 1, 2), (TpxStatus::Ok, vec![4, 5], 2));
    unsafe { tpx_complex_free(c) };
}

#[test]
fn null_arguments_are_refused_and_outputs_untouched() {
    let c = tet_triangle_wire();
    let s = ig(c);
    let mut u = 42u32;
    let mut z = 42usize;
    unsafe {
        assert_eq!(
            tpx_complex_dimension(null(), &mut u),
            TpxStatus::NullArgument
        );
        assert_eq!(u, 42);
        assert!(last_error().contains("`c`"), "{}", last_error());
        assert_eq!(
            tpx_complex_dimension(c, null_mut()),
            TpxStatus::NullArgument
        );
        assert_eq!(
            tpx_complex_vertex_count(null(), &mut u),
            TpxStatus::NullArgument
        );
        assert_eq!(
            tpx_complex_top_count(c, 0, null_mut()),
            TpxStatus::NullArgument
        );
        assert_eq!(
            tpx_complex_coord_dim(null(), &mut z),
            TpxStatus::NullArgument
        );
        assert_eq!(
            tpx_complex_coords(c, null_mut(), 0, null_mut()),
            TpxStatus::NullArgument
        );
        assert_eq!(
            tpx_complex_top_simplices(null(), 0, null_mut(), 0, &mut z),
            TpxStatus::NullArgument
        );
        assert_eq!(
            tpx_complex_top_simplices(c, 3, null_mut(), 4, &mut z),
            TpxStatus::NullArgument
        );
        assert_eq!(
            tpx_structure_build(null(), 0, &mut null_mut()),
            TpxStatus::NullArgument
        );
        assert_eq!(
            tpx_structure_build(c, 0, null_mut()),
            TpxStatus::NullArgument
        );
        assert_eq!(tpx_structure_kind(null(), &mut u), TpxStatus::NullArgument);
        assert_eq!(
            tpx_structure_dimension(s, null_mut()),
            TpxStatus::NullArgument
        );
        assert_eq!(
            tpx_structure_count(null(), 0, &mut z),
            TpxStatus::NullArgument
        );
        assert_eq!(
            tpx_structure_top_count(s, 0, null_mut()),
            TpxStatus::NullArgument
        );
        assert_eq!(
            tpx_structure_storage(s, null_mut()),
            TpxStatus::NullArgument
        );
        assert_eq!(
            tpx_structure_simplices(s, 0, null_mut(), 0, null_mut()),
            TpxStatus::NullArgument
        );
        assert_eq!(
            tpx_relation(s, null(), 1, 0, null_mut(), 0, &mut z),
            TpxStatus::NullArgument
        );
        assert_eq!(
            tpx_relation(null(), [0u32].as_ptr(), 1, 0, null_mut(), 0, &mut z),
            TpxStatus::NullArgument
        );
        assert_eq!(
            tpx_relation_table(s, 0, 0, null_mut()),
            TpxStatus::NullArgument
        );
        assert_eq!(
            tpx_complex_from_file(null(), &mut null_mut()),
            TpxStatus::NullArgument
        );
        assert_eq!(
            tpx_complex_from_arrays(1, null(), null(), 0, null(), 0, null_mut()),
            TpxStatus::NullArgument
        );
        assert_eq!(
            tpx_complex_from_arrays(
                3,
                null(),
                [0usize, 2].as_ptr(),
                1,
                null(),
                0,
                &mut null_mut()
            ),
            TpxStatus::NullArgument
        );
        assert_eq!((u, z), (42, 42));
        tpx_complex_free(null_mut());
        tpx_structure_free(null_mut());
        tpx_relation_table_free(null_mut());
        tpx_structure_free(s);
        tpx_complex_free(c);
    }
}

#[test]
fn complex_errors_map_to_statuses_with_evidence() {
    let mut out = null_mut();
    unsafe {
        // Decreasing offsets.
        let st = tpx_complex_from_arrays(
            3,
            [0u32, 1, 2].as_ptr(),
            [0usize, 2, 1].as_ptr(),
            2,
            null(),
            0,
            &mut out,
        );
        assert_eq!(st, TpxStatus::InvalidArgument);
        // Repeated vertex in simplex #1.
        let st = tpx_complex_from_arrays(
            3,
            [0u32, 1, 2, 2].as_ptr(),
            [0usize, 2, 4].as_ptr(),
            2,
            null(),
            0,
            &mut out,
        );
        assert_eq!(st, TpxStatus::InvalidComplex);
        assert!(last_error().contains("#1"), "{}", last_error());
        assert!(last_error().contains("[2 2]"), "{}", last_error());
        // Vertex 3 of 3.
        let st = tpx_complex_from_arrays(
            3,
            [0u32, 3].as_ptr(),
            [0usize, 2].as_ptr(),
            1,
            null(),
            0,
            &mut out,
        );
        assert_eq!(st, TpxStatus::InvalidComplex);
        // No vertices.
        let st = tpx_complex_from_arrays(0, null(), null(), 0, null(), 0, &mut out);
        assert_eq!(st, TpxStatus::InvalidComplex);
        // Coordinates with dimension 0.
        let st = tpx_complex_from_arrays(1, null(), null(), 0, [0.0].as_ptr(), 0, &mut out);
        assert_eq!(st, TpxStatus::InvalidArgument);
        assert!(out.is_null());
        // Unknown extension: refused after the file is probed for the .tpx magic (a file
        // access Miri's isolation does not allow).
        #[cfg(not(miri))]
        {
            let st = tpx_complex_from_file(c"mesh.txt".as_ptr(), &mut out);
            assert_eq!(st, TpxStatus::ParseError);
            assert!(last_error().contains("mesh.txt"), "{}", last_error());
        }
        let st = tpx_complex_from_file(c"bad\xff.off".as_ptr(), &mut out);
        assert_eq!(st, TpxStatus::InvalidArgument);
        assert!(out.is_null());

        // Isolated vertices only, with coordinates.
        let st = tpx_complex_from_arrays(2, null(), null(), 0, [0.0, 1.0].as_ptr(), 1, &mut out);
        assert_eq!(st, TpxStatus::Ok, "{}", last_error());
        let mut d = 9u32;
        assert_eq!(tpx_complex_dimension(out, &mut d), TpxStatus::Ok);
        assert_eq!(d, 0);
        tpx_complex_free(out);
    }
}

/// `tpx_complex_from_file_flags` with `TPX_READ_TRIANGULATE`: a convex quad becomes two
/// triangles (refused without the flag), a bent one is PARSE_ERROR naming the reason, and an
/// unknown flag is INVALID_ARGUMENT with nothing returned.
#[cfg(not(miri))]
#[test]
fn triangulate_flag_fans_a_quad_and_refuses_a_bent_one() {
    use std::ffi::CString;
    let dir = std::env::temp_dir().join(format!("tpx-ffi-tri-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let write = |name: &str, z: &str| {
        let p = dir.join(name);
        std::fs::write(
            &p,
            format!("OFF\n4 1 0\n0 0 0\n1 0 0\n1 1 {z}\n0 1 0\n4 0 1 2 3\n"),
        )
        .unwrap();
        CString::new(p.to_str().unwrap()).unwrap()
    };
    let (flat, bent) = (write("flat.off", "0"), write("bent.off", "0.5"));
    let mut out = null_mut();
    unsafe {
        assert_eq!(
            tpx_complex_from_file_flags(flat.as_ptr(), 0, 0, &mut out),
            TpxStatus::ParseError
        );
        assert!(last_error().contains("not a simplex"), "{}", last_error());
        let st = tpx_complex_from_file_flags(flat.as_ptr(), 0, TPX_READ_TRIANGULATE, &mut out);
        assert_eq!(st, TpxStatus::Ok, "{}", last_error());
        let mut n = 0usize;
        assert_eq!(tpx_complex_top_count(out, 2, &mut n), TpxStatus::Ok);
        assert_eq!(n, 2);
        tpx_complex_free(out);
        out = null_mut();
        let st = tpx_complex_from_file_flags(bent.as_ptr(), 0, TPX_READ_TRIANGULATE, &mut out);
        assert_eq!(st, TpxStatus::ParseError);
        assert!(last_error().contains("not planar"), "{}", last_error());
        assert!(out.is_null());
        let st = tpx_complex_from_file_flags(flat.as_ptr(), 0, 2, &mut out);
        assert_eq!(st, TpxStatus::InvalidArgument);
        assert!(out.is_null());
    }
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn kinds_and_query_errors_map_to_statuses() {
    let c = tet_triangle_wire();
    let mut s = null_mut();
    unsafe {
        assert_eq!(tpx_structure_build(c, 10, &mut s), TpxStatus::UnknownKind);
        assert!(last_error().contains("0..=9"), "{}", last_error());
        assert_eq!(
            tpx_structure_build(c, u32::MAX, &mut s),
            TpxStatus::UnknownKind
        );
        assert!(s.is_null());
        for kind in 0..=TPX_KIND_IASTAR {
            let st = tpx_structure_build(c, kind, &mut s);
            // Kinds land one by one; each either builds or says so.
            match st {
                TpxStatus::Ok => tpx_structure_free(std::mem::replace(&mut s, null_mut())),
                TpxStatus::NotImplemented | TpxStatus::UnsupportedComplex => {
                    assert!(!last_error().is_empty());
                    assert!(s.is_null());
                }
                other => panic!("kind {kind}: {other:?} {}", last_error()),
            }
        }
    }
    let s = ig(c);
    assert_eq!(relation(s, &[0, 4], 0, 8).0, TpxStatus::NotInComplex);
    assert!(last_error().contains("[0 4]"), "{}", last_error());
    assert_eq!(relation(s, &[], 0, 8).0, TpxStatus::InvalidSimplex);
    assert_eq!(relation(s, &[1, 1], 0, 8).0, TpxStatus::InvalidSimplex);
    assert_eq!(relation(s, &[6], 0, 8).0, TpxStatus::InvalidSimplex);
    assert_eq!(relation(s, &[0], 4, 8).0, TpxStatus::DimensionOutOfRange);
    let mut len = 0usize;
    let st = unsafe { tpx_structure_simplices(s, 4, null_mut(), 0, &mut len) };
    assert_eq!((st, len), (TpxStatus::DimensionOutOfRange, 0));
    // A success clears the message.
    assert_eq!(relation(s, &[0], 1, 8).0, TpxStatus::Ok);
    assert_eq!(last_error(), "");
    unsafe {
        tpx_structure_free(s);
        tpx_complex_free(c);
    }
}

/// tpx_relation validates and sorts on its own (no allocation per call): its answers and error
/// messages must be those of the Rust API, `Topology::relation` then `sort_rows`, for every
/// simplex and every q, with answers of all sizes following each other on one thread (the
/// per-thread answer buffer is reused). A 4-simplex makes rows of 5 ids (the general sort).
#[test]
fn relation_matches_the_rust_api_for_every_simplex_and_q() {
    // A 4-simplex 0..4 sharing vertex 4 with a triangle 4 5 6, and a wire edge 6-7.
    let c = complex(8, &[&[4, 3, 2, 1, 0], &[6, 5, 4], &[7, 6]]);
    for kind in [TPX_KIND_IG, TPX_KIND_SIG] {
        let mut s = null_mut();
        assert_eq!(
            unsafe { tpx_structure_build(c, kind, &mut s) },
            TpxStatus::Ok,
            "{}",
            last_error()
        );
        let topo = unsafe { &*s }.topo.as_ref();
        let d = topo.dimension();
        for p in 0..=d {
            let mut all = Vec::new();
            topo.simplices(p, &mut all);
            for sigma in all.chunks_exact(p + 1) {
                // Given in descending order, to exercise the sort of the query simplex.
                let given: Vec<u32> = sigma.iter().rev().copied().collect();
                for q in 0..=d {
                    let mut want = Vec::new();
                    topo.relation(sigma, q, &mut want).unwrap();
                    topoplex::relation::sort_rows(&mut want, q + 1);
                    let (st, got) = relation(s, &given, q as u32, 512);
                    assert_eq!(st, TpxStatus::Ok, "{}", last_error());
                    assert_eq!(got, want, "kind {kind} R{p},{q} of {sigma:?}");
                }
            }
        }
        // Invalid queries: the same message as the Rust API's error.
        for bad in [&[][..], &[3, 1, 3], &[2, 8], &[0, 5]] {
            let want = topo
                .relation(bad, 1, &mut Vec::new())
                .unwrap_err()
                .to_string();
            let (st, _) = relation(s, bad, 1, 8);
            assert_ne!(st, TpxStatus::Ok);
            assert_eq!(last_error(), want);
        }
        let too_many: Vec<u32> = (0..17).collect();
        let want = topo
            .relation(&too_many, 0, &mut Vec::new())
            .unwrap_err()
            .to_string();
        assert_eq!(relation(s, &too_many, 0, 8).0, TpxStatus::InvalidSimplex);
        assert_eq!(last_error(), want);
        unsafe { tpx_structure_free(s) };
    }
    unsafe { tpx_complex_free(c) };
}

#[test]
fn answers_are_sorted_in_place_for_every_arity() {
    for arity in 1..=6usize {
        // Rows r = 0..5 of `arity` ids (r, r+1, ...), listed 3 1 4 0 2.
        let row = |r: u32| (r..r + arity as u32).collect::<Vec<u32>>();
        let mut rows: Vec<u32> = [3, 1, 4, 0, 2].into_iter().flat_map(row).collect();
        super::structure::sort_rows_in_place(&mut rows, arity);
        let want: Vec<u32> = (0..5).flat_map(row).collect();
        assert_eq!(rows, want, "arity {arity}");
        // Rows that differ only in a later id (high ids: no carry between packed ids), and
        // more rows than are sorted on the stack.
        for n in [7u32, 200] {
            let row = |r: u32| {
                let mut v = vec![u32::MAX - 1; arity];
                v[arity - 1] = u32::MAX - 1 - (r % 3);
                v[0] = r / 3;
                v
            };
            let mut rows: Vec<u32> = (0..n).rev().flat_map(row).collect();
            let mut want: Vec<Vec<u32>> = (0..n).map(row).collect();
            want.sort();
            super::structure::sort_rows_in_place(&mut rows, arity);
            assert_eq!(rows, want.concat(), "arity {arity}, {n} rows");
        }
    }
}

#[test]
fn a_panic_becomes_a_status_not_an_unwind() {
    let st = guard(|| panic!("boom at [1 2]"));
    assert_eq!(st, TpxStatus::Panic);
    assert!(last_error().contains("boom at [1 2]"), "{}", last_error());
    assert_eq!(guard_value(5, || panic!("x")), 5);
}

#[test]
fn queries_from_two_threads_share_one_structure() {
    // A const handle shared across threads, as the header promises C callers may do.
    #[derive(Clone, Copy)]
    struct Shared(*const TpxStructure);
    unsafe impl Send for Shared {}
    let c = tet_triangle_wire();
    let s = ig(c);
    let shared = Shared(s);
    let answers: Vec<Vec<u32>> = std::thread::scope(|scope| {
        let hs: Vec<_> = (0..2u32)
            .map(|v| {
                scope.spawn(move || {
                    let shared = shared;
                    relation(shared.0, &[v + 2], 0, 8).1
                })
            })
            .collect();
        hs.into_iter().map(|h| h.join().unwrap()).collect()
    });
    assert_eq!(answers, [vec![0, 1, 3, 4], vec![0, 1, 2, 4]]);
    unsafe {
        tpx_structure_free(s);
        tpx_complex_free(c);
    }
}

#[test]
fn decomposition_of_the_bowtie_splits_its_pinch_vertex() {
    //   0       3
    //   | \   / |
    //   |  2    |     two triangles sharing only vertex 2: two components, vertex 2 split
    //   | /   \ |
    //   1       4
    let c = complex(5, &[&[0, 1, 2], &[2, 3, 4]]);
    let mut d = null_mut();
    assert_eq!(unsafe { tpx_decomposition_build(c, &mut d) }, TpxStatus::Ok);
    let mut count = 0usize;
    assert_eq!(
        unsafe { tpx_decomposition_component_count(d, &mut count) },
        TpxStatus::Ok
    );
    assert_eq!(count, 2);
    let mut originals = Vec::new();
    for i in 0..count {
        let (mut dim, mut tops, mut tops_len, mut orig, mut orig_len) =
            (0u32, null(), 0usize, null(), 0usize);
        let st = unsafe {
            tpx_decomposition_component(
                d,
                i,
                &mut dim,
                &mut tops,
                &mut tops_len,
                &mut orig,
                &mut orig_len,
            )
        };
        assert_eq!(st, TpxStatus::Ok, "{}", last_error());
        assert_eq!((dim, tops_len, orig_len), (2, 3, 3));
        let tops = unsafe { std::slice::from_raw_parts(tops, tops_len) };
        let orig = unsafe { std::slice::from_raw_parts(orig, orig_len) };
        let mut tri: Vec<u32> = tops.iter().map(|&l| orig[l as usize]).collect();
        tri.sort();
        originals.push(tri);
    }
    originals.sort();
    assert_eq!(originals, [vec![0, 1, 2], vec![2, 3, 4]]);
    let (mut sv, mut sv_len, mut off, mut copies, mut copies_len) =
        (null(), 0usize, null(), null(), 0usize);
    assert_eq!(
        unsafe {
            tpx_decomposition_split_vertices(
                d,
                &mut sv,
                &mut sv_len,
                &mut off,
                &mut copies,
                &mut copies_len,
            )
        },
        TpxStatus::Ok
    );
    assert_eq!(unsafe { std::slice::from_raw_parts(sv, sv_len) }, [2]);
    assert_eq!(copies_len, 2);
    let (mut cv, mut cc, mut n) = (null(), null(), 0usize);
    assert_eq!(
        unsafe { tpx_decomposition_copies(d, &mut cv, &mut cc, &mut n) },
        TpxStatus::Ok
    );
    assert_eq!(n, 6);
    let copies = unsafe { std::slice::from_raw_parts(copies, copies_len) };
    let cv = unsafe { std::slice::from_raw_parts(cv, n) };
    let cc = unsafe { std::slice::from_raw_parts(cc, n) };
    assert!(copies.iter().all(|&k| cv[k as usize] == 2));
    assert_ne!(cc[copies[0] as usize], cc[copies[1] as usize]);
    let (mut dim, mut p, mut l) = (0u32, null(), 0usize);
    let st =
        unsafe { tpx_decomposition_component(d, 2, &mut dim, &mut p, &mut l, &mut null(), &mut 0) };
    assert_eq!(st, TpxStatus::DimensionOutOfRange);
    assert_eq!(
        unsafe { tpx_decomposition_component_count(null(), &mut count) },
        TpxStatus::NullArgument
    );
    unsafe {
        tpx_decomposition_free(d);
        tpx_decomposition_free(null_mut());
        tpx_complex_free(c);
    }
}

/// Issue 16, class 11: a NULL buffer with a non-zero length is NULL_ARGUMENT even when the
/// answer is empty (the edge 4-5 has no triangle), as the header promises; `*out_len` untouched.
#[test]
fn a_null_buffer_with_a_length_is_refused_even_for_an_empty_answer() {
    let c = tet_triangle_wire();
    let s = ig(c);
    let mut len = 42usize;
    unsafe {
        let st = tpx_relation(s, [4u32, 5].as_ptr(), 2, 2, null_mut(), 8, &mut len);
        assert_eq!((st, len), (TpxStatus::NullArgument, 42));
        assert!(last_error().contains("`buf`"), "{}", last_error());
        // Length 0 with NULL still asks for the size.
        let st = tpx_relation(s, [4u32, 5].as_ptr(), 2, 2, null_mut(), 0, &mut len);
        assert_eq!((st, len), (TpxStatus::Ok, 0));
        // The same rule on every buffer-filling export: an empty answer and a NULL buffer.
        let st = tpx_complex_coords(c, null_mut(), 3, &mut len);
        assert_eq!(st, TpxStatus::NullArgument);
        let st = tpx_complex_top_simplices(c, 0, null_mut(), 3, &mut len);
        assert_eq!(st, TpxStatus::NullArgument);
        let st = tpx_structure_simplices(s, 0, null_mut(), 100, &mut len);
        assert_eq!(st, TpxStatus::NullArgument);
        // Handle answers too (their writer checked the room first: an empty answer passed).
        let mut h = TpxSimplex::default();
        let st = tpx_locate(s, [4u32, 5].as_ptr(), 2, &mut h);
        assert_eq!(st, TpxStatus::Ok);
        let st = tpx_related_handles(s, &h, 2, TPX_ORDER_NATURAL, null_mut(), 8, &mut len);
        assert_eq!(st, TpxStatus::NullArgument);
        let mut offsets = [7u32; 2];
        let st = tpx_related_handles_batch(
            s,
            &h,
            1,
            2,
            TPX_ORDER_NATURAL,
            offsets.as_mut_ptr(),
            null_mut(),
            8,
            &mut len,
        );
        assert_eq!((st, offsets), (TpxStatus::NullArgument, [7, 7]));
        assert!(last_error().contains("`buf`"), "{}", last_error());
        assert_eq!(len, 0);
        tpx_structure_free(s);
        tpx_complex_free(c);
    }
}

/// Issue 16, classes 4 and 10: a vertex count with nothing behind it, or a closure above the
/// budget, is TOO_LARGE before anything of that size is allocated (never an abort); the
/// budget can be raised; `*out` is untouched.
#[test]
fn closure_bombs_are_too_large_and_the_budget_can_be_raised() {
    let mut out = null_mut();
    unsafe {
        let st = tpx_complex_from_arrays(u32::MAX, null(), null(), 0, null(), 0, &mut out);
        assert_eq!(st, TpxStatus::TooLarge, "{}", last_error());
        assert!(last_error().contains("4294967295"), "{}", last_error());
        assert!(out.is_null());
        // One 4-simplex: 5 + 26 simplices by the bound; a budget of 30 refuses it, 31 takes it.
        let ids = [0u32, 1, 2, 3, 4];
        let offsets = [0usize, 5];
        let build = |max: u64, out: &mut *mut TpxComplex| {
            tpx_complex_from_arrays_budget(
                5,
                ids.as_ptr(),
                offsets.as_ptr(),
                1,
                null(),
                0,
                max,
                out,
            )
        };
        assert_eq!(build(30, &mut out), TpxStatus::TooLarge);
        assert!(
            last_error().contains("up to 31 simplices"),
            "{}",
            last_error()
        );
        assert!(out.is_null());
        assert_eq!(build(31, &mut out), TpxStatus::Ok, "{}", last_error());
        tpx_complex_free(std::mem::replace(&mut out, null_mut()));
        assert_eq!(build(u64::MAX, &mut out), TpxStatus::Ok);
        tpx_complex_free(out);
    }
}

/// Issue 16, class 12: what normalisation absorbed is visible through the C ABI.
#[test]
fn input_stats_count_absorbed_duplicates_and_faces() {
    // 0 1 2 twice (once reversed), its edge 1 2, and the wire 3 4.
    let c = complex(5, &[&[0, 1, 2], &[2, 1, 0], &[1, 2], &[3, 4]]);
    let mut st = TpxInputStats {
        input_simplices: 9,
        absorbed_duplicates: 9,
        absorbed_faces: 9,
    };
    unsafe {
        assert_eq!(tpx_complex_input_stats(c, &mut st), TpxStatus::Ok);
        assert_eq!(
            st,
            TpxInputStats {
                input_simplices: 4,
                absorbed_duplicates: 1,
                absorbed_faces: 1,
            }
        );
        assert_eq!(
            tpx_complex_input_stats(null(), &mut st),
            TpxStatus::NullArgument
        );
        assert_eq!(
            tpx_complex_input_stats(c, null_mut()),
            TpxStatus::NullArgument
        );
        tpx_complex_free(c);
    }
}

/// Issue 16, class 6 (C ABI side): the last error message is one bounded line, control
/// characters escaped, whatever the failure's text.
#[test]
fn last_error_message_is_one_bounded_escaped_line() {
    let long = format!("{}\n\u{b}{}", "x".repeat(5_000), "y".repeat(10));
    let st = guard(|| Err(Failure::new(TpxStatus::ParseError, long)));
    assert_eq!(st, TpxStatus::ParseError);
    let msg = last_error();
    assert!(
        msg.len() < topoplex::error::MESSAGE_MAX_BYTES + 40,
        "{}",
        msg.len()
    );
    assert!(msg.ends_with("more bytes)"), "{msg}");
    assert!(!msg.contains('\n') && !msg.contains('\u{b}'));
    let st = guard(|| Err(Failure::new(TpxStatus::ParseError, "a\nb\u{b}c\0")));
    assert_eq!(st, TpxStatus::ParseError);
    assert_eq!(last_error(), "a\\nb\\x0bc\\0");
}

/// Handles through the C ABI on the tetrahedron with a dangling triangle and a wire: locate,
/// vertices, related (both orders), batch CSR, degree, tops as given, and every bad handle a
/// clear status with outputs untouched.
#[test]
fn handles_locate_navigate_and_refuse_bad_handles() {
    let c = tet_triangle_wire();
    let s = ig(c);
    let mut other = null_mut();
    assert_eq!(
        unsafe { tpx_structure_build(c, TPX_KIND_NMIA, &mut other) },
        TpxStatus::Ok
    );
    unsafe {
        let mut e = TpxSimplex::default();
        assert_eq!(tpx_locate(s, [3, 2].as_ptr(), 2, &mut e), TpxStatus::Ok);
        assert_eq!(e.meta & 0xff, 1);
        let mut v = [0u32; 4];
        let mut len = 0usize;
        assert_eq!(
            tpx_simplex_vertices(s, &e, v.as_mut_ptr(), 4, &mut len),
            TpxStatus::Ok
        );
        assert_eq!(&v[..len], &[2, 3]);
        // Triangles at edge 2-3: 0 2 3, 1 2 3, 2 3 4, as dense indices of triangles.
        let mut buf = [0u32; 8];
        let st = tpx_related(
            s,
            &e,
            2,
            TPX_ORDER_LEXICOGRAPHIC,
            buf.as_mut_ptr(),
            8,
            &mut len,
        );
        assert_eq!(st, TpxStatus::Ok);
        let mut rows = Vec::new();
        for &i in &buf[..len] {
            let mut t = TpxSimplex::default();
            assert_eq!(tpx_handle(s, 2, i, &mut t), TpxStatus::Ok);
            let mut w = [0u32; 3];
            let mut wl = 0;
            assert_eq!(
                tpx_simplex_vertices(s, &t, w.as_mut_ptr(), 3, &mut wl),
                TpxStatus::Ok
            );
            rows.push(w.to_vec());
        }
        assert_eq!(rows, [vec![0, 2, 3], vec![1, 2, 3], vec![2, 3, 4]]);
        let mut deg = 0usize;
        assert_eq!(tpx_degree(s, &e, 2, &mut deg), TpxStatus::Ok);
        assert_eq!(deg, 3);
        // Too small: status, needed length, buffer untouched.
        let mut small = [u32::MAX; 2];
        let st = tpx_related(s, &e, 2, TPX_ORDER_NATURAL, small.as_mut_ptr(), 2, &mut len);
        assert_eq!(
            (st, len, small),
            (TpxStatus::BufferTooSmall, 3, [u32::MAX; 2])
        );
        // Batch: R_{0,0} of vertices 4 and 5 in CSR form.
        let mut offsets = [9u32; 3];
        let mut ids = [0u32; 16];
        let st = tpx_related_batch(
            s,
            0,
            [4, 5].as_ptr(),
            2,
            0,
            TPX_ORDER_LEXICOGRAPHIC,
            offsets.as_mut_ptr(),
            ids.as_mut_ptr(),
            16,
            &mut len,
        );
        assert_eq!(st, TpxStatus::Ok);
        assert_eq!((offsets, &ids[..len]), ([0, 3, 4], &[2, 3, 5, 4][..]));
        // Tops: 4-5 (wire), 2 3 4 (dangling), 0 1 2 3; as given and numbered the same.
        let mut total = 0;
        assert_eq!(tpx_top_total(s, &mut total), TpxStatus::Ok);
        assert_eq!(total, 3);
        let mut t = TpxSimplex::default();
        assert_eq!(tpx_top(s, 2, &mut t), TpxStatus::Ok);
        let mut id = 0;
        assert_eq!(tpx_top_id(s, &t, &mut id), TpxStatus::Ok);
        assert_eq!(id, 2);
        assert_eq!(tpx_top_id(s, &e, &mut id), TpxStatus::Ok);
        assert_eq!(id, u32::MAX);
        // Bad handles: foreign, out of range, NONE, unknown form, wrong kind; outputs untouched.
        let mut foreign = TpxSimplex::default();
        assert_eq!(
            tpx_locate(other, [3, 2].as_ptr(), 2, &mut foreign),
            TpxStatus::Ok
        );
        deg = 77;
        assert_eq!(
            tpx_degree(s, &foreign, 2, &mut deg),
            TpxStatus::ForeignHandle
        );
        let past = TpxSimplex {
            index: 10,
            meta: 1,
            owner: e.owner,
        };
        assert_eq!(tpx_degree(s, &past, 2, &mut deg), TpxStatus::InvalidHandle);
        let none = TpxSimplex {
            index: u32::MAX,
            meta: 0,
            owner: e.owner,
        };
        assert_eq!(tpx_degree(s, &none, 0, &mut deg), TpxStatus::InvalidHandle);
        let form = TpxSimplex {
            index: 0,
            meta: 7 << 8,
            owner: e.owner,
        };
        assert_eq!(tpx_degree(s, &form, 0, &mut deg), TpxStatus::InvalidHandle);
        assert_eq!(deg, 77);
        let (mut ni, mut ng) = (0usize, 0usize);
        let st = tpx_cyclic(
            s,
            &e,
            0,
            buf.as_mut_ptr(),
            8,
            offsets.as_mut_ptr(),
            small.as_mut_ptr(),
            2,
            &mut ni,
            &mut ng,
        );
        assert_eq!(st, TpxStatus::WrongHandleKind);
        assert_eq!(
            tpx_degree(s, &e, 9, &mut deg),
            TpxStatus::DimensionOutOfRange
        );
        assert_eq!(tpx_degree(s, null(), 0, &mut deg), TpxStatus::NullArgument);
        tpx_structure_free(other);
        tpx_structure_free(s);
        tpx_complex_free(c);
    }
}

/// Every kind's ABI number is its TPX_KIND_* constant, in both directions (not only the ends).
#[test]
fn kind_numbers_are_the_tpx_kind_constants() {
    use topoplex::relation::StructureKind as K;
    let pairs = [
        (K::Ig, TPX_KIND_IG),
        (K::Sig, TPX_KIND_SIG),
        (K::Ia, TPX_KIND_IA),
        (K::Iqm, TPX_KIND_IQM),
        (K::Nmia, TPX_KIND_NMIA),
        (K::Ts, TPX_KIND_TS),
        (K::Pe, TPX_KIND_PE),
        (K::Le, TPX_KIND_LE),
        (K::De, TPX_KIND_DE),
        (K::IaStar, TPX_KIND_IASTAR),
    ];
    for (k, n) in pairs {
        assert_eq!((k.abi(), K::from_abi(n)), (n, Some(k)));
    }
    assert_eq!(K::from_abi(10), None);
}

/// The input listing through the C ABI: a repeated triangle and an absorbed edge are counted,
/// each listing comes back as given with the top id it became.
///
/// ```text
///   listed: (2 1 0), (0 1) absorbed face, (1 2 0) repeat of the first, (3 2)
///   tops:   id 0 = 2-3 (edge), id 1 = 0 1 2 (triangle)
/// ```
#[test]
fn input_listing_and_stats_come_back_as_given() {
    let c = complex(4, &[&[2, 1, 0], &[0, 1], &[1, 2, 0], &[3, 2]]);
    unsafe {
        let mut st = TpxInputStats::default();
        assert_eq!(tpx_complex_input_stats(c, &mut st), TpxStatus::Ok);
        assert_eq!(
            (
                st.input_simplices,
                st.absorbed_duplicates,
                st.absorbed_faces
            ),
            (4, 1, 1)
        );
        let mut got = Vec::new();
        for i in 0..4 {
            let (mut buf, mut len, mut top) = ([0u32; 4], 0usize, 0u32);
            let s = tpx_complex_input_simplex(c, i, buf.as_mut_ptr(), 4, &mut len, &mut top);
            assert_eq!(s, TpxStatus::Ok);
            got.push((buf[..len].to_vec(), top));
        }
        assert_eq!(
            got,
            [
                (vec![2, 1, 0], 1),
                (vec![0, 1], u32::MAX),
                (vec![1, 2, 0], 1),
                (vec![3, 2], 0)
            ]
        );
        let (mut buf, mut len, mut top) = ([0u32; 4], 0usize, 7u32);
        let s = tpx_complex_input_simplex(c, 4, buf.as_mut_ptr(), 4, &mut len, &mut top);
        assert_eq!((s, top), (TpxStatus::InvalidArgument, 7));
        tpx_complex_free(c);
    }
}

/// Relation views of the tetrahedron-with-triangle-and-wire (drawing at `tet_triangle_wire`):
/// the IG lends its stored co-boundary R_{1,2} as it is (built = 0) and builds R_{0,0} once
/// (built = 1, kept: the same arrays on the second call); every answer equals `tpx_related`;
/// `tpx_degree_batch` gives the counts alone. Errors leave the outputs untouched.
#[test]
fn relation_views_and_degree_batches_match_tpx_related() {
    let c = tet_triangle_wire();
    let s = ig(c);
    unsafe {
        let related = |p: u32, i: u32, q: u32| {
            let mut h = TpxSimplex::default();
            assert_eq!(tpx_handle(s, p, i, &mut h), TpxStatus::Ok);
            let (mut buf, mut len) = ([0u32; 16], 0usize);
            let st = tpx_related(s, &h, q, TPX_ORDER_NATURAL, buf.as_mut_ptr(), 16, &mut len);
            assert_eq!(st, TpxStatus::Ok);
            buf[..len].to_vec()
        };
        let view = |p: u32, q: u32| {
            let mut v = std::mem::MaybeUninit::<TpxRelationView>::zeroed();
            assert_eq!(tpx_relation_view(s, p, q, v.as_mut_ptr()), TpxStatus::Ok);
            v.assume_init()
        };
        let answer = |v: &TpxRelationView, i: usize| {
            let (a, b) = (*v.offsets.add(i) as usize, *v.offsets.add(i + 1) as usize);
            std::slice::from_raw_parts(v.ids.add(a), b - a).to_vec()
        };
        // Edges: 01 02 03 12 13 23 24 34 45; edge 23 (index 5) is in triangles 023, 123, 234.
        let ef = view(1, 2);
        assert_eq!((ef.count, ef.built), (9, 0));
        for i in 0..9 {
            assert_eq!(answer(&ef, i), related(1, i as u32, 2), "edge {i}");
        }
        assert_eq!(answer(&ef, 5).len(), 3);
        assert_eq!(answer(&ef, 8), Vec::<u32>::new());
        let vv = view(0, 0);
        assert_eq!((vv.count, vv.built), (6, 1));
        let mut total = 0;
        for i in 0..6 {
            assert_eq!(answer(&vv, i), related(0, i as u32, 0), "vertex {i}");
            total += answer(&vv, i).len() as u64;
        }
        assert_eq!(vv.bytes, 4 * (7 + total));
        let again = view(0, 0);
        assert_eq!((again.offsets, again.ids), (vv.offsets, vv.ids));
        // Degrees of the vertices (R_{0,0}) and of the edges (R_{1,2}), counts only.
        let mut deg = [9u32; 9];
        let all: Vec<u32> = (0..9).collect();
        assert_eq!(
            tpx_degree_batch(s, 0, all.as_ptr(), 6, 0, deg.as_mut_ptr()),
            TpxStatus::Ok
        );
        assert_eq!(deg[..6], [3, 3, 4, 4, 3, 1]);
        assert_eq!(
            tpx_degree_batch(s, 1, all.as_ptr(), 9, 2, deg.as_mut_ptr()),
            TpxStatus::Ok
        );
        assert_eq!(deg, [2, 2, 2, 2, 2, 3, 1, 1, 0]);
        // Errors: index out of range, q above d, NULL, the live complex; nothing written.
        let mut untouched = [7u32; 2];
        let st = tpx_degree_batch(s, 0, [0, 6].as_ptr(), 2, 0, untouched.as_mut_ptr());
        assert_eq!((st, untouched), (TpxStatus::InvalidHandle, [7, 7]));
        let st = tpx_degree_batch(s, 0, [0].as_ptr(), 1, 4, untouched.as_mut_ptr());
        assert_eq!((st, untouched), (TpxStatus::DimensionOutOfRange, [7, 7]));
        let st = tpx_degree_batch(s, 0, [0].as_ptr(), 1, 0, null_mut());
        assert_eq!(st, TpxStatus::NullArgument);
        let mut v = TpxRelationView {
            offsets: null(),
            ids: null(),
            count: 77,
            built: 0,
            bytes: 0,
        };
        assert_eq!(
            tpx_relation_view(s, 4, 0, &mut v),
            TpxStatus::DimensionOutOfRange
        );
        assert_eq!(v.count, 77);
        assert_eq!(
            tpx_relation_view(s, 0, 0, null_mut()),
            TpxStatus::NullArgument
        );
        let mut live = null_mut();
        assert_eq!(tpx_live_from_complex(c, &mut live), TpxStatus::Ok);
        let mut ls = null();
        assert_eq!(tpx_live_structure(live, &mut ls), TpxStatus::Ok);
        // The live complex numbers as the IG does (lexicographic ranks; its vertices are
        // its slots, none removed here): its views and degrees are the IG's.
        for (p, q) in [(0, 0), (1, 2), (2, 1), (2, 2), (0, 3)] {
            let mut lv = std::mem::MaybeUninit::<TpxRelationView>::zeroed();
            assert_eq!(tpx_relation_view(ls, p, q, lv.as_mut_ptr()), TpxStatus::Ok);
            let lv = lv.assume_init();
            let iv = view(p, q);
            assert_eq!((lv.count, lv.built), (iv.count, 1), "R_{{{p},{q}}}");
            // Natural orders differ (the live complex's is lexicographic): the same sets.
            for i in 0..iv.count {
                let mut want = answer(&iv, i);
                want.sort_unstable();
                assert_eq!(answer(&lv, i), want, "R_{{{p},{q}}} of {i}");
            }
            let idx: Vec<u32> = (0..iv.count as u32).collect();
            let mut ld = vec![0u32; idx.len()];
            let st = tpx_degree_batch(ls, p, idx.as_ptr(), idx.len(), q, ld.as_mut_ptr());
            assert_eq!(st, TpxStatus::Ok);
            let want: Vec<u32> = (0..iv.count).map(|i| answer(&iv, i).len() as u32).collect();
            assert_eq!(ld, want, "degrees R_{{{p},{q}}}");
        }
        tpx_live_free(live);
        tpx_structure_free(s);
        tpx_complex_free(c);
    }
}

/// Four threads ask for the same relation view of one structure at once: each gets the same
/// kept arrays (the first index built is the one lent; a concurrent second build is dropped).
#[test]
fn threads_asking_for_one_view_share_one_index() {
    #[derive(Clone, Copy)]
    struct Shared(*const TpxStructure);
    unsafe impl Send for Shared {}
    let c = tet_triangle_wire();
    let mut s = null_mut();
    assert_eq!(
        unsafe { tpx_structure_build(c, TPX_KIND_NMIA, &mut s) },
        TpxStatus::Ok
    );
    let shared = Shared(s);
    let views: Vec<(usize, usize, usize)> = std::thread::scope(|scope| {
        let hs: Vec<_> = (0..4)
            .map(|_| {
                scope.spawn(move || {
                    let shared = shared;
                    let mut v = std::mem::MaybeUninit::<TpxRelationView>::zeroed();
                    let st = unsafe { tpx_relation_view(shared.0, 1, 2, v.as_mut_ptr()) };
                    assert_eq!(st, TpxStatus::Ok);
                    let v = unsafe { v.assume_init() };
                    (v.offsets as usize, v.ids as usize, v.count)
                })
            })
            .collect();
        hs.into_iter().map(|h| h.join().unwrap()).collect()
    });
    assert!(views.iter().all(|&v| v == views[0]), "{views:?}");
    assert_eq!(views[0].2, 9);
    unsafe {
        tpx_structure_free(s);
        tpx_complex_free(c);
    }
}

/// A disk of four triangles around vertex 4 and a fifth on edge 1-2:
///
/// ```text
///   0 ------ 1
///   | \    / | \
///   |   4    |  5
///   | /    \ | /
///   3 ------ 2
/// ```
/// For every kind that takes it: `tpx_related` and `tpx_related_handles` (their fast path:
/// stored rows, the structures' loops, the generic walk) give what the Rust API's
/// `related_ids` gives, for every simplex, every q and both orders; a buffer one short is
/// BUFFER_TOO_SMALL with the needed length and the buffer untouched; a success after a failure
/// clears the last error; a handle with local bits set (not dense) still gets the full path's
/// answer or error.
#[test]
fn tpx_related_fast_path_matches_the_rust_api_on_every_kind() {
    use topoplex::relation::handle::{Order, SimplexHandle};
    let c = complex(
        6,
        &[&[0, 1, 4], &[1, 2, 4], &[2, 3, 4], &[0, 3, 4], &[1, 2, 5]],
    );
    let mut built = 0;
    // Under Miri (scripts/test.sh) one kind per fast-path writer — the IG's rows, the IA's
    // adjacency, the radial cycles (PE), the generic walk (NMIA) — and the first simplex of each
    // dimension only (the batch: the first three): the whole sweep takes tens of minutes there,
    // and two simplices instead of one took 90 s of the suite's time for the same code paths.
    let kinds: Vec<u32> = if cfg!(miri) {
        vec![TPX_KIND_IG, TPX_KIND_IA, TPX_KIND_PE, TPX_KIND_NMIA]
    } else {
        (0..=TPX_KIND_DE).collect()
    };
    for &kind in &kinds {
        let mut s = null_mut();
        if unsafe { tpx_structure_build(c, kind, &mut s) } != TpxStatus::Ok {
            continue;
        }
        built += 1;
        let n = unsafe { (*s).topo.as_navigate().unwrap() };
        let mut stamp = 0;
        assert_eq!(unsafe { tpx_structure_stamp(s, &mut stamp) }, TpxStatus::Ok);
        for p in 0..=2u32 {
            let count = unsafe { (*s).topo.count(p as usize) } as u32;
            let walked = if cfg!(miri) { count.min(1) } else { count };
            for i in 0..walked {
                let h = TpxSimplex {
                    index: i,
                    meta: p,
                    owner: stamp,
                };
                for q in 0..=2u32 {
                    for (order, o) in [
                        (TPX_ORDER_NATURAL, Order::Natural),
                        (TPX_ORDER_LEXICOGRAPHIC, Order::Lexicographic),
                    ] {
                        let mut want = Vec::new();
                        n.related_ids(
                            SimplexHandle::dense(p as usize, i),
                            q as usize,
                            o,
                            &mut want,
                        )
                        .unwrap();
                        let (mut buf, mut len) = ([u32::MAX; 16], 0usize);
                        let st =
                            unsafe { tpx_related(s, &h, q, order, buf.as_mut_ptr(), 16, &mut len) };
                        assert_eq!(st, TpxStatus::Ok, "kind {kind} R_{p},{q} of {i}");
                        assert_eq!(&buf[..len], &want[..], "kind {kind} R_{p},{q} of {i}");
                        assert_eq!(last_error(), "");
                        let mut hb = [TpxSimplex::default(); 16];
                        let st = unsafe {
                            tpx_related_handles(s, &h, q, order, hb.as_mut_ptr(), 16, &mut len)
                        };
                        assert_eq!(st, TpxStatus::Ok);
                        let got: Vec<u32> = hb[..len].iter().map(|x| x.index).collect();
                        assert_eq!(got, want, "kind {kind} handles R_{p},{q} of {i}");
                        assert!(hb[..len].iter().all(|x| x.meta == q && x.owner == stamp));
                        if !want.is_empty() {
                            let mut short = [u32::MAX; 16];
                            let mut need = 0usize;
                            let st = unsafe {
                                tpx_related(
                                    s,
                                    &h,
                                    q,
                                    order,
                                    short.as_mut_ptr(),
                                    want.len() - 1,
                                    &mut need,
                                )
                            };
                            assert_eq!((st, need), (TpxStatus::BufferTooSmall, want.len()));
                            assert!(
                                short.iter().all(|&x| x == u32::MAX),
                                "kind {kind}: buffer written"
                            );
                        }
                    }
                }
            }
            // The batch over every p-simplex (the stored rows' fast path included) equals the
            // Rust API's; one id short, nothing is written.
            let all: Vec<u32> = (0..if cfg!(miri) { count.min(3) } else { count }).collect();
            for q in 0..=2u32 {
                for (order, o) in [
                    (TPX_ORDER_NATURAL, Order::Natural),
                    (TPX_ORDER_LEXICOGRAPHIC, Order::Lexicographic),
                ] {
                    let (mut want, mut ends) = (Vec::new(), Vec::new());
                    n.related_batch(p as usize, &all, q as usize, o, &mut want, &mut ends)
                        .unwrap();
                    // The batch into buffers of `cap` ids, pre-filled with u32::MAX.
                    let batch = |cap: usize| {
                        let mut off = vec![u32::MAX; all.len() + 1];
                        let mut ids = vec![u32::MAX; cap];
                        let mut len = 0usize;
                        let st = unsafe {
                            tpx_related_batch(
                                s,
                                p,
                                all.as_ptr(),
                                all.len(),
                                q,
                                order,
                                off.as_mut_ptr(),
                                ids.as_mut_ptr(),
                                cap,
                                &mut len,
                            )
                        };
                        (st, len, off, ids)
                    };
                    let (st, len, off, ids) = batch(want.len() + 1);
                    assert_eq!(
                        (st, len),
                        (TpxStatus::Ok, want.len()),
                        "kind {kind} batch R_{p},{q}"
                    );
                    assert_eq!(&ids[..len], &want[..], "kind {kind} batch R_{p},{q}");
                    let ends32: Vec<u32> = std::iter::once(0)
                        .chain(ends.iter().map(|&e| e as u32))
                        .collect();
                    assert_eq!(off, ends32, "kind {kind} batch offsets R_{p},{q}");
                    if !want.is_empty() {
                        let (st, len, off, ids) = batch(want.len() - 1);
                        assert_eq!((st, len), (TpxStatus::BufferTooSmall, want.len()));
                        assert!(
                            off.iter().chain(&ids).all(|&x| x == u32::MAX),
                            "kind {kind}: written"
                        );
                    }
                }
            }
            // Past the last simplex: the full path's INVALID_HANDLE, then a success clears it.
            let bad = TpxSimplex {
                index: count,
                meta: p,
                owner: stamp,
            };
            let (mut buf, mut len) = ([0u32; 16], 0usize);
            let st = unsafe {
                tpx_related(
                    s,
                    &bad,
                    0,
                    TPX_ORDER_NATURAL,
                    buf.as_mut_ptr(),
                    16,
                    &mut len,
                )
            };
            assert_eq!(st, TpxStatus::InvalidHandle);
            assert!(!last_error().is_empty());
            let good = TpxSimplex {
                index: 0,
                meta: p,
                owner: stamp,
            };
            let st = unsafe {
                tpx_related(
                    s,
                    &good,
                    0,
                    TPX_ORDER_NATURAL,
                    buf.as_mut_ptr(),
                    16,
                    &mut len,
                )
            };
            assert_eq!((st, last_error()), (TpxStatus::Ok, String::new()));
            // Local bits on a dense handle: not the fast path's; the answer is the same.
            let odd = TpxSimplex {
                index: 0,
                meta: p | 1 << 16,
                owner: stamp,
            };
            let mut len2 = 0;
            let mut buf2 = [0u32; 16];
            let st = unsafe {
                tpx_related(
                    s,
                    &odd,
                    0,
                    TPX_ORDER_NATURAL,
                    buf2.as_mut_ptr(),
                    16,
                    &mut len2,
                )
            };
            assert_eq!((st, &buf2[..len2]), (TpxStatus::Ok, &buf[..len]));
        }
        unsafe { tpx_structure_free(s) };
    }
    assert!(
        built >= kinds.len().min(6),
        "only {built} kinds took the disk"
    );
    unsafe { tpx_complex_free(c) };
}

/// `tpx_kind_from_name` knows every CLI name in any ASCII case, and refuses unknown names
/// (echoed in the message), NULL, and non-UTF-8 bytes, leaving `*out` untouched.
#[test]
fn kind_names_map_to_their_tpx_kind_numbers_in_any_case() {
    use std::ffi::CString;
    for k in topoplex::relation::StructureKind::NAMED {
        for name in [k.name().to_string(), k.name().to_ascii_uppercase()] {
            let c = CString::new(name.clone()).unwrap();
            let mut out = u32::MAX;
            assert_eq!(
                unsafe { tpx_kind_from_name(c.as_ptr(), &mut out) },
                TpxStatus::Ok,
                "{name}"
            );
            assert_eq!(out, k.abi(), "{name}");
        }
    }
    let mut out = 77u32;
    let bad = CString::new("tetgen\n").unwrap();
    assert_eq!(
        unsafe { tpx_kind_from_name(bad.as_ptr(), &mut out) },
        TpxStatus::UnknownKind
    );
    assert!(last_error().contains("`tetgen\\n`"), "{}", last_error());
    let not_utf8 = [0xffu8, 0];
    assert_eq!(
        unsafe { tpx_kind_from_name(not_utf8.as_ptr().cast(), &mut out) },
        TpxStatus::InvalidArgument
    );
    assert_eq!(
        unsafe { tpx_kind_from_name(null(), &mut out) },
        TpxStatus::NullArgument
    );
    assert_eq!(
        unsafe { tpx_kind_from_name(bad.as_ptr(), null_mut()) },
        TpxStatus::NullArgument
    );
    assert_eq!(out, 77);
    // And back: each kind's name is the one from_name takes.
    for k in topoplex::relation::StructureKind::NAMED {
        let mut name = null();
        assert_eq!(unsafe { tpx_kind_name(k.abi(), &mut name) }, TpxStatus::Ok);
        assert_eq!(
            unsafe { std::ffi::CStr::from_ptr(name) }.to_str(),
            Ok(k.name())
        );
    }
    let mut name = null();
    assert_eq!(
        unsafe { tpx_kind_name(10, &mut name) },
        TpxStatus::UnknownKind
    );
    assert!(name.is_null());
}

// Attributes (`attributes.rs`).

/// Two triangles 012 and 213 sharing edge 1-2, which is also listed on its own (an absorbed
/// face, listing 2), and a repeat of 012 (listing 3):
///
/// ```text
///     0 --- 1
///      \  / | \
///       2 --+-- 3      (012, 213; edge 12 listed; 012 listed twice)
/// ```
fn two_triangles_with_listed_edge() -> *mut TpxComplex {
    complex(4, &[&[0, 1, 2], &[2, 1, 3], &[1, 2], &[2, 0, 1]])
}

fn set_attr<T>(
    c: *mut TpxComplex,
    name: &CStr,
    location: u32,
    ty: u32,
    k: usize,
    v: &[T],
) -> TpxStatus {
    unsafe {
        tpx_complex_set_attribute(
            c,
            name.as_ptr(),
            location,
            ty,
            k,
            v.as_ptr().cast(),
            v.len(),
        )
    }
}

fn attribute_count(c: *const TpxComplex) -> usize {
    let mut n = usize::MAX;
    assert_eq!(
        unsafe { tpx_complex_attribute_count(c, &mut n) },
        TpxStatus::Ok
    );
    n
}

fn info(c: *const TpxComplex, i: usize) -> TpxAttributeInfo {
    let mut out = TpxAttributeInfo {
        name: null(),
        name_len: 0,
        location: u32::MAX,
        value_type: u32::MAX,
        components: 0,
        elements: 0,
    };
    assert_eq!(
        unsafe { tpx_complex_attribute_info(c, i, &mut out) },
        TpxStatus::Ok,
        "{}",
        last_error()
    );
    out
}

fn info_name(i: &TpxAttributeInfo) -> String {
    let bytes = unsafe { std::slice::from_raw_parts(i.name.cast::<u8>(), i.name_len) };
    String::from_utf8(bytes.to_vec()).unwrap()
}

/// The numbers of attribute `i`, lent, copied out as `T`.
fn lent<T: Copy>(c: *const TpxComplex, i: usize) -> Vec<T> {
    let mut p = null();
    let mut n = 0;
    assert_eq!(
        unsafe { tpx_complex_attribute_data(c, i, &mut p, &mut n) },
        TpxStatus::Ok
    );
    unsafe { std::slice::from_raw_parts(p.cast::<T>(), n) }.to_vec()
}

#[test]
fn attributes_set_from_arrays_are_enumerated_found_and_lent_bit_for_bit() {
    let c = two_triangles_with_listed_edge();
    assert_eq!(TpxStatus::NoSuchAttribute as u32, 54);
    assert_eq!(attribute_count(c), 0);
    // Three components per vertex, with a NaN payload and a negative zero to check bits.
    let velocity: Vec<f64> = vec![
        1.5,
        -0.0,
        f64::from_bits(0x7ff8_0000_dead_beef),
        2.0,
        3.0,
        4.0,
        -1e300,
        5e-324,
        0.1,
        7.0,
        8.0,
        9.0,
    ];
    let refs: Vec<i32> = vec![7, -8, 9, i32::MIN];
    assert_eq!(
        set_attr(
            c,
            c"velocity",
            TPX_LOCATION_VERTICES,
            TPX_VALUE_F64,
            3,
            &velocity
        ),
        TpxStatus::Ok,
        "{}",
        last_error()
    );
    assert_eq!(
        set_attr(
            c,
            c"medit:ref",
            TPX_LOCATION_LISTED,
            TPX_VALUE_I32,
            1,
            &refs
        ),
        TpxStatus::Ok,
        "{}",
        last_error()
    );
    assert_eq!(attribute_count(c), 2);
    let (a, b) = (info(c, 0), info(c, 1));
    assert_eq!(info_name(&a), "velocity");
    assert_eq!(
        (a.location, a.value_type, a.components, a.elements),
        (TPX_LOCATION_VERTICES, TPX_VALUE_F64, 3, 4)
    );
    assert_eq!(info_name(&b), "medit:ref");
    assert_eq!(
        (b.location, b.value_type, b.components, b.elements),
        (TPX_LOCATION_LISTED, TPX_VALUE_I32, 1, 4)
    );
    let got: Vec<f64> = lent(c, 0);
    assert_eq!(
        got.iter().map(|x| x.to_bits()).collect::<Vec<_>>(),
        velocity.iter().map(|x| x.to_bits()).collect::<Vec<_>>()
    );
    assert_eq!(lent::<i32>(c, 1), refs);
    let mut at = usize::MAX;
    assert_eq!(
        unsafe {
            tpx_complex_attribute_find(c, c"medit:ref".as_ptr(), TPX_LOCATION_LISTED, &mut at)
        },
        TpxStatus::Ok
    );
    assert_eq!(at, 1);
    // The same name at the other location is another attribute: absent here.
    at = 77;
    assert_eq!(
        unsafe {
            tpx_complex_attribute_find(c, c"medit:ref".as_ptr(), TPX_LOCATION_VERTICES, &mut at)
        },
        TpxStatus::NoSuchAttribute
    );
    assert!(last_error().contains("medit:ref"), "{}", last_error());
    assert_eq!(at, 77, "output written on failure");
    // Replacing keeps the position and changes the type.
    let wide: Vec<i64> = vec![1 << 40, 2, 3, -4];
    assert_eq!(
        set_attr(
            c,
            c"medit:ref",
            TPX_LOCATION_LISTED,
            TPX_VALUE_I64,
            1,
            &wide
        ),
        TpxStatus::Ok
    );
    assert_eq!(attribute_count(c), 2);
    assert_eq!(info(c, 1).value_type, TPX_VALUE_I64);
    assert_eq!(lent::<i64>(c, 1), wide);
    // Removing takes both locations; a second time there is nothing to remove.
    assert_eq!(
        unsafe { tpx_complex_remove_attribute(c, c"velocity".as_ptr()) },
        TpxStatus::Ok
    );
    assert_eq!(attribute_count(c), 1);
    assert_eq!(info_name(&info(c, 0)), "medit:ref");
    assert_eq!(
        unsafe { tpx_complex_remove_attribute(c, c"velocity".as_ptr()) },
        TpxStatus::NoSuchAttribute
    );
    unsafe { tpx_complex_free(c) };
}

#[test]
fn attribute_refusals_name_the_attribute_and_change_nothing() {
    let c = two_triangles_with_listed_edge();
    let refs: Vec<i32> = vec![1, 2, 3, 4];
    assert_eq!(
        set_attr(c, c"ref", TPX_LOCATION_LISTED, TPX_VALUE_I32, 1, &refs),
        TpxStatus::Ok
    );
    let cases: Vec<(TpxStatus, &CStr, u32, u32, usize, usize, &str)> = vec![
        // (status, name, location, type, components, count, message part)
        (
            TpxStatus::InvalidArgument,
            c"ref",
            TPX_LOCATION_LISTED,
            TPX_VALUE_I32,
            1,
            3,
            "3 numbers",
        ),
        (
            TpxStatus::InvalidArgument,
            c"temp",
            TPX_LOCATION_VERTICES,
            TPX_VALUE_F32,
            1,
            5,
            "'temp'",
        ),
        (
            TpxStatus::InvalidArgument,
            c"t",
            TPX_LOCATION_VERTICES,
            TPX_VALUE_F32,
            0,
            0,
            "0 components",
        ),
        (
            TpxStatus::InvalidArgument,
            c"t",
            TPX_LOCATION_VERTICES,
            TPX_VALUE_F32,
            10,
            40,
            "10 components",
        ),
        (
            TpxStatus::InvalidArgument,
            c"",
            TPX_LOCATION_VERTICES,
            TPX_VALUE_F32,
            1,
            4,
            "name is empty",
        ),
        (
            TpxStatus::InvalidArgument,
            c"t",
            2,
            TPX_VALUE_F32,
            1,
            4,
            "location 2",
        ),
        (
            TpxStatus::InvalidArgument,
            c"t",
            TPX_LOCATION_VERTICES,
            4,
            1,
            4,
            "value type 4",
        ),
    ];
    let data = [0u64; 64];
    for (want, name, loc, ty, k, count, says) in cases {
        let st = unsafe {
            tpx_complex_set_attribute(c, name.as_ptr(), loc, ty, k, data.as_ptr().cast(), count)
        };
        assert_eq!(st, want, "{name:?} {loc} {ty} {k} {count}");
        assert!(last_error().contains(says), "{}", last_error());
        assert_eq!(attribute_count(c), 1);
        assert_eq!(lent::<i32>(c, 0), refs);
    }
    let st = unsafe {
        tpx_complex_set_attribute(
            c,
            c"t".as_ptr(),
            TPX_LOCATION_VERTICES,
            TPX_VALUE_F64,
            1,
            null(),
            4,
        )
    };
    assert_eq!(st, TpxStatus::NullArgument);
    let st = unsafe {
        tpx_complex_set_attribute(
            c,
            null(),
            TPX_LOCATION_VERTICES,
            TPX_VALUE_F64,
            1,
            data.as_ptr().cast(),
            4,
        )
    };
    assert_eq!(st, TpxStatus::NullArgument);
    // A named label keeps its attribute integer: replacing it by reals is refused, and the
    // labels stay as they were.
    let mut attrs = unsafe { (*c).complex.take_attributes() };
    attrs.add_label_name(topoplex::complex::LabelName {
        attribute: "ref".into(),
        dimension: Some(2),
        label: 3,
        name: "wall".into(),
    });
    unsafe { (*c).complex.set_attributes(attrs) }.unwrap();
    let reals = [0.5f64; 4];
    assert_eq!(
        set_attr(c, c"ref", TPX_LOCATION_LISTED, TPX_VALUE_F64, 1, &reals),
        TpxStatus::InvalidArgument
    );
    assert!(last_error().contains("wall"), "{}", last_error());
    assert_eq!(info(c, 0).value_type, TPX_VALUE_I32);
    assert_eq!(lent::<i32>(c, 0), refs);
    let (mut p, mut n) = (null(), 99);
    assert_eq!(
        unsafe { tpx_complex_label_name(c, c"ref".as_ptr(), 2, 3, &mut p, &mut n) },
        TpxStatus::Ok
    );
    assert_eq!(
        unsafe { std::slice::from_raw_parts(p.cast::<u8>(), n) },
        b"wall"
    );
    // Another dimension, another label: no name.
    for (d, l) in [(1, 3), (2, 4)] {
        assert_eq!(
            unsafe { tpx_complex_label_name(c, c"ref".as_ptr(), d, l, &mut p, &mut n) },
            TpxStatus::Ok
        );
        assert!(p.is_null() && n == 0);
    }
    // Removing the attribute removes its label names too.
    assert_eq!(
        unsafe { tpx_complex_remove_attribute(c, c"ref".as_ptr()) },
        TpxStatus::Ok
    );
    assert!(unsafe { (*c).complex.attributes() }.is_empty());
    unsafe { tpx_complex_free(c) };
}

#[test]
fn listed_index_is_the_first_listing_of_every_simplex_of_the_closure() {
    let c = two_triangles_with_listed_edge();
    let cx = unsafe { &(*c).complex };
    // Every simplex over 4 vertices (subsets), against a scan of the listing.
    for mask in 1u32..16 {
        let s: Vec<u32> = (0..4).filter(|v| mask >> v & 1 == 1).collect();
        let oracle = (0..cx.input_count()).find(|&i| {
            let mut l = cx.input_simplex(i).to_vec();
            l.sort_unstable();
            l == s
        });
        // Given in descending order: the order does not matter.
        let rev: Vec<u32> = s.iter().rev().copied().collect();
        let mut got = 12345;
        assert_eq!(
            unsafe { tpx_complex_listed_index(c, rev.as_ptr(), rev.len(), &mut got) },
            TpxStatus::Ok
        );
        assert_eq!(got, oracle.unwrap_or(TPX_NOT_LISTED), "{s:?}");
    }
    for bad in [&[][..], &[1, 1], &[0, 4]] {
        let mut got = 12345;
        assert_eq!(
            unsafe { tpx_complex_listed_index(c, bad.as_ptr(), bad.len(), &mut got) },
            TpxStatus::InvalidSimplex,
            "{bad:?}"
        );
        assert_eq!(got, 12345);
    }
    unsafe { tpx_complex_free(c) };
}

/// The live top id of the top simplex `sigma`.
fn live_top_id(l: *const TpxLive, sigma: &[u32]) -> u32 {
    let mut s = null();
    assert_eq!(unsafe { tpx_live_structure(l, &mut s) }, TpxStatus::Ok);
    let mut h = TpxSimplex {
        index: 0,
        meta: 0,
        owner: 0,
    };
    assert_eq!(
        unsafe { tpx_locate(s, sigma.as_ptr(), sigma.len(), &mut h) },
        TpxStatus::Ok,
        "{}",
        last_error()
    );
    let mut t = 0;
    assert_eq!(unsafe { tpx_top_id(s, &h, &mut t) }, TpxStatus::Ok);
    t
}

fn live_row(l: *const TpxLive, name: &CStr, top: Option<u32>, v: u32) -> (TpxStatus, Vec<f64>) {
    let mut buf = [f64::NAN; 4];
    let mut n = 0;
    let st = match top {
        Some(t) => unsafe { tpx_live_top_values(l, name.as_ptr(), t, buf.as_mut_ptr(), 4, &mut n) },
        None => unsafe { tpx_live_vertex_values(l, name.as_ptr(), v, buf.as_mut_ptr(), 4, &mut n) },
    };
    (st, buf[..n].to_vec())
}

#[test]
fn live_top_and_vertex_values_by_handle_survive_into_the_complex() {
    let c = two_triangles_with_listed_edge();
    let refs: Vec<i32> = vec![10, 20, 30, 40];
    let temp: Vec<f32> = vec![1.0, 2.0, 6.0, 8.0];
    assert_eq!(
        set_attr(c, c"ref", TPX_LOCATION_LISTED, TPX_VALUE_I32, 1, &refs),
        TpxStatus::Ok
    );
    assert_eq!(
        set_attr(c, c"temp", TPX_LOCATION_VERTICES, TPX_VALUE_F32, 1, &temp),
        TpxStatus::Ok
    );
    let mut l = null_mut();
    assert_eq!(unsafe { tpx_live_from_complex(c, &mut l) }, TpxStatus::Ok);
    let t012 = live_top_id(l, &[0, 1, 2]);
    let t123 = live_top_id(l, &[1, 2, 3]);
    // A top's values are those of its first listing.
    assert_eq!(
        live_row(l, c"ref", Some(t012), 0),
        (TpxStatus::Ok, vec![10.0])
    );
    assert_eq!(
        live_row(l, c"ref", Some(t123), 0),
        (TpxStatus::Ok, vec![20.0])
    );
    for v in 0..4 {
        assert_eq!(
            live_row(l, c"temp", None, v),
            (TpxStatus::Ok, vec![f64::from(temp[v as usize])])
        );
    }
    assert_eq!(
        unsafe { tpx_live_set_top_values(l, c"ref".as_ptr(), t123, [42.0].as_ptr(), 1) },
        TpxStatus::Ok,
        "{}",
        last_error()
    );
    assert_eq!(
        live_row(l, c"ref", Some(t123), 0),
        (TpxStatus::Ok, vec![42.0])
    );
    // Refusals change nothing.
    assert_eq!(
        unsafe { tpx_live_set_top_values(l, c"ref".as_ptr(), t123, [1.0, 2.0].as_ptr(), 2) },
        TpxStatus::InvalidArgument
    );
    for label in [1.5, f64::NAN, f64::INFINITY, 2147483648.0] {
        let st = unsafe { tpx_live_set_top_values(l, c"ref".as_ptr(), t123, [label].as_ptr(), 1) };
        assert_eq!(st, TpxStatus::InvalidArgument, "{label}");
        assert!(last_error().contains("i32 labels"), "{}", last_error());
    }
    assert_eq!(
        unsafe { tpx_live_set_top_values(l, c"ref".as_ptr(), t123, [-2147483648.0].as_ptr(), 1) },
        TpxStatus::Ok
    );
    assert_eq!(
        live_row(l, c"ref", Some(t123), 0),
        (TpxStatus::Ok, vec![-2147483648.0])
    );
    assert_eq!(
        unsafe { tpx_live_set_top_values(l, c"ref".as_ptr(), t123, [42.0].as_ptr(), 1) },
        TpxStatus::Ok
    );
    assert_eq!(
        unsafe { tpx_live_set_top_values(l, c"nope".as_ptr(), t123, [1.0].as_ptr(), 1) },
        TpxStatus::NoSuchAttribute
    );
    assert!(last_error().contains("nope"));
    assert_eq!(
        live_row(l, c"temp", Some(t123), 0).0,
        TpxStatus::NoSuchAttribute
    );
    assert_eq!(live_row(l, c"ref", None, 0).0, TpxStatus::NoSuchAttribute);
    assert_eq!(live_row(l, c"temp", None, 9).0, TpxStatus::DeadVertex);
    assert_eq!(
        live_row(l, c"ref", Some(t123 + 5), 0).0,
        TpxStatus::InvalidHandle
    );
    assert_eq!(
        live_row(l, c"ref", Some(t123), 0),
        (TpxStatus::Ok, vec![42.0])
    );
    let mut n = 0;
    assert_eq!(
        unsafe { tpx_live_top_values(l, c"ref".as_ptr(), t123, null_mut(), 0, &mut n) },
        TpxStatus::BufferTooSmall
    );
    assert_eq!(n, 1);
    // Averaging contraction of edge 1-2: vertex 1 gets the mean of 1 and 2.
    assert_eq!(
        unsafe { tpx_live_set_vertex_policy(l, 7) },
        TpxStatus::InvalidArgument
    );
    assert_eq!(
        unsafe { tpx_live_set_vertex_policy(l, TPX_VERTEX_AVERAGE) },
        TpxStatus::Ok
    );
    let mut undo = null_mut();
    let st = unsafe {
        tpx_live_contract(
            l,
            1,
            2,
            TPX_CONTRACT_PRESERVE_TOPOLOGY,
            null(),
            0,
            &mut undo,
        )
    };
    assert_eq!(st, TpxStatus::Ok, "{}", last_error());
    let mean = (f64::from(temp[1]) + f64::from(temp[2])) / 2.0;
    assert_eq!(live_row(l, c"temp", None, 1), (TpxStatus::Ok, vec![mean]));
    unsafe { tpx_undo_free(undo) };
    unsafe { tpx_live_free(l) };
    // Without the contraction, a set value reaches the complex made from the live one.
    let mut l = null_mut();
    assert_eq!(unsafe { tpx_live_from_complex(c, &mut l) }, TpxStatus::Ok);
    let t123 = live_top_id(l, &[1, 2, 3]);
    assert_eq!(
        unsafe { tpx_live_set_top_values(l, c"ref".as_ptr(), t123, [-5.0].as_ptr(), 1) },
        TpxStatus::Ok
    );
    let mut back = null_mut();
    assert_eq!(unsafe { tpx_live_to_complex(l, &mut back) }, TpxStatus::Ok);
    let mut i = usize::MAX;
    assert_eq!(
        unsafe { tpx_complex_listed_index(back, [3, 2, 1].as_ptr(), 3, &mut i) },
        TpxStatus::Ok
    );
    let mut at = 0;
    assert_eq!(
        unsafe { tpx_complex_attribute_find(back, c"ref".as_ptr(), TPX_LOCATION_LISTED, &mut at) },
        TpxStatus::Ok
    );
    assert_eq!(lent::<i32>(back, at)[i], -5);
    unsafe { tpx_complex_free(back) };
    unsafe { tpx_live_free(l) };
    unsafe { tpx_complex_free(c) };
}

/// Three triangles on the edge 0-1 and a fourth, 0 2 5, across the edge 0-2 of the first: the
/// lent facet adjacency names the one triangle across a manifold edge, says MANY across the
/// non-manifold edge and NONE on the boundary; NULL arguments are refused with the output
/// untouched; after a contraction the next call describes the new state.
#[test]
fn the_facet_adjacency_is_lent_and_follows_edits() {
    let c = complex(6, &[&[0, 1, 2], &[0, 1, 3], &[0, 1, 4], &[0, 2, 5]]);
    let mut l = null_mut();
    assert_eq!(unsafe { tpx_live_from_complex(c, &mut l) }, TpxStatus::Ok);
    let mut adj = TpxLiveAdjacency {
        across: [null(); 16],
        across_lens: [7; 16],
        bytes: 7,
    };
    assert_eq!(
        unsafe { tpx_live_adjacency(null(), &mut adj) },
        TpxStatus::NullArgument
    );
    assert_eq!(
        unsafe { tpx_live_adjacency(l, null_mut()) },
        TpxStatus::NullArgument
    );
    assert_eq!(
        (adj.across_lens[2], adj.bytes),
        (7, 7),
        "output written on a refusal"
    );
    assert_eq!(unsafe { tpx_live_adjacency(l, &mut adj) }, TpxStatus::Ok);
    assert_eq!(adj.across_lens[2], 12);
    assert_eq!(adj.bytes, 4 * 12);
    let row = |adj: &TpxLiveAdjacency, slot: usize| -> Vec<u32> {
        let all = unsafe { std::slice::from_raw_parts(adj.across[2], adj.across_lens[2]) };
        all[3 * slot..3 * slot + 3].to_vec()
    };
    let t012 = live_top_id(l, &[0, 1, 2]);
    let t025 = live_top_id(l, &[0, 2, 5]);
    assert_eq!(t012 >> 28, 2);
    // 0 1 2: across from 0 (edge 1 2) none, from 1 (edge 0 2) the triangle 0 2 5, from 2
    // (edge 0 1) the two other triangles on it.
    assert_eq!(
        row(&adj, (t012 & 0x0fff_ffff) as usize),
        [TPX_ACROSS_NONE, t025, TPX_ACROSS_MANY]
    );
    // Contracting 5 into 2 removes the triangle 0 2 5: the edge 0 2 is a boundary again.
    let st = unsafe { tpx_live_contract(l, 2, 5, TPX_CONTRACT_FREE, null(), 0, null_mut()) };
    assert_eq!(st, TpxStatus::Ok);
    assert_eq!(unsafe { tpx_live_adjacency(l, &mut adj) }, TpxStatus::Ok);
    let t012 = live_top_id(l, &[0, 1, 2]);
    assert_eq!(row(&adj, (t012 & 0x0fff_ffff) as usize)[1], TPX_ACROSS_NONE);
    // Kept across edits: inserting 0 2 6 puts a triangle across 0 1 2's edge 0 2 again, read
    // from the repaired index; NULL refused; keep = 0 returns to building on request.
    assert_eq!(
        unsafe { tpx_live_keep_adjacency(null_mut(), 1) },
        TpxStatus::NullArgument
    );
    assert_eq!(unsafe { tpx_live_keep_adjacency(l, 1) }, TpxStatus::Ok);
    let mut v = 0;
    assert_eq!(
        unsafe { tpx_live_add_vertex(l, [0.0f64; 0].as_ptr(), 0, &mut v) },
        TpxStatus::Ok
    );
    assert_eq!(
        unsafe { tpx_live_insert_top(l, [0, 2, v].as_ptr(), 3) },
        TpxStatus::Ok
    );
    assert!(unsafe { &*l }.live().keeps_adjacency());
    assert_eq!(unsafe { tpx_live_adjacency(l, &mut adj) }, TpxStatus::Ok);
    let t02v = live_top_id(l, &[0, 2, v]);
    assert_eq!(row(&adj, (t012 & 0x0fff_ffff) as usize)[1], t02v);
    assert_eq!(unsafe { tpx_live_keep_adjacency(l, 0) }, TpxStatus::Ok);
    assert!(!unsafe { &*l }.live().keeps_adjacency());
    unsafe {
        tpx_live_free(l);
        tpx_complex_free(c);
    }
}

/// The same book of three triangles on the edge 0-1 with 0 2 5 beside it: the lent rings name
/// each vertex's neighbours with the tops at each edge (three at the non-manifold edge 0-1);
/// NULL arguments are refused with the output untouched; after a contraction the next call
/// describes the new state.
#[test]
fn the_rings_are_lent_and_follow_edits() {
    let c = complex(6, &[&[0, 1, 2], &[0, 1, 3], &[0, 1, 4], &[0, 2, 5]]);
    let mut l = null_mut();
    assert_eq!(unsafe { tpx_live_from_complex(c, &mut l) }, TpxStatus::Ok);
    let mut r = TpxLiveRings {
        offsets: null(),
        neighbours: null(),
        held: null(),
        vertex_slots: 7,
        top_dims: 7,
        entries: 7,
        bytes: 7,
    };
    assert_eq!(
        unsafe { tpx_live_rings(null(), &mut r) },
        TpxStatus::NullArgument
    );
    assert_eq!(
        unsafe { tpx_live_rings(l, null_mut()) },
        TpxStatus::NullArgument
    );
    assert_eq!(
        (r.vertex_slots, r.entries, r.bytes),
        (7, 7, 7),
        "output written on a refusal"
    );
    // Vertex v's (neighbour, tops at the edge) pairs, sorted.
    let ring = |r: &TpxLiveRings, v: usize| -> Vec<(u32, u32)> {
        let off = unsafe { std::slice::from_raw_parts(r.offsets, r.vertex_slots as usize + 1) };
        let (b, e) = (off[v] as usize, off[v + 1] as usize);
        let ids = unsafe { std::slice::from_raw_parts(r.neighbours, r.entries) };
        let held = unsafe { std::slice::from_raw_parts(r.held, r.entries) };
        let mut out: Vec<(u32, u32)> = ids[b..e]
            .iter()
            .copied()
            .zip(held[b..e].iter().copied())
            .collect();
        out.sort_unstable();
        out
    };
    assert_eq!(unsafe { tpx_live_rings(l, &mut r) }, TpxStatus::Ok);
    assert_eq!((r.vertex_slots, r.top_dims, r.entries), (6, 1 << 2, 18));
    assert_eq!(r.bytes, 4 * 7 + 8 * 18);
    assert_eq!(ring(&r, 0), [(1, 3), (2, 2), (3, 1), (4, 1), (5, 1)]);
    assert_eq!(ring(&r, 1), [(0, 3), (2, 1), (3, 1), (4, 1)]);
    assert_eq!(ring(&r, 5), [(0, 1), (2, 1)]);
    // Contracting 5 into 2: 5's row is empty, 0-2 is held by one triangle again.
    let st = unsafe { tpx_live_contract(l, 2, 5, TPX_CONTRACT_FREE, null(), 0, null_mut()) };
    assert_eq!(st, TpxStatus::Ok);
    assert_eq!(unsafe { tpx_live_rings(l, &mut r) }, TpxStatus::Ok);
    assert_eq!(ring(&r, 5), []);
    assert_eq!(ring(&r, 0), [(1, 3), (2, 1), (3, 1), (4, 1)]);
    unsafe {
        tpx_live_free(l);
        tpx_complex_free(c);
    }
}
