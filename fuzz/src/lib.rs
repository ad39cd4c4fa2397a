//! Checks shared by the fuzz targets.

use topoplex::io::RawInput;
use topoplex::oracle::check_structure;
use topoplex::{BuildError, build};
use topoplex::{Complex, StructureKind};
use topoplex_ffi::{TpxComplex, TpxStatus, tpx_complex_from_arrays};

/// Whatever a reader accepted either normalises or is refused with an error; a small complex
/// then builds every structure, and each answers like the oracle.
pub fn check_raw(raw: &RawInput) {
    // Large (or implied: 0..=max id) vertex counts are valid but make the oracle slow.
    let implied = raw.ids.iter().max().map_or(0, |&m| m as u64 + 1);
    if raw.simplex_count() > 300 || u64::from(raw.vertex_count.unwrap_or(0)).max(implied) > 2000 {
        if raw.vertex_count.is_none()
            && implied > u64::from(topoplex::complex::MAX_IMPLIED_VERTICES)
        {
            // A huge implied count must be refused, not allocated.
            assert!(Complex::from_raw(raw, None).is_err());
        }
        return;
    }
    if let Ok(c) = Complex::from_raw(raw, None) {
        check_complex(&c);
    }
}

/// Every structure that accepts `c` validates and matches the oracle (when the closure is small
/// enough for the oracle's scans).
pub fn check_complex(c: &Complex) {
    let size: usize = c.closure().iter().map(|t| t.len()).sum();
    if size > 3000 {
        return;
    }
    for kind in StructureKind::ALL {
        match build(kind, c) {
            Ok(s) => {
                if let Err(e) = s.validate() {
                    panic!("{kind}: validate: {e}");
                }
                if let Err(e) = check_structure(s.as_ref(), c) {
                    panic!("{e}");
                }
            }
            Err(BuildError::NotImplemented { .. } | BuildError::Unsupported { .. }) => {}
            Err(e) => panic!("{kind}: unexpected build error {e}"),
        }
    }
}

/// The complex of `list` over `n` vertices made through the C ABI as a C caller makes it
/// (`tpx_complex_from_arrays`, no coordinates): the status, and the handle (NULL unless OK),
/// which the caller frees.
pub fn c_complex(n: u32, list: &[Vec<u32>]) -> (TpxStatus, *mut TpxComplex) {
    let ids: Vec<u32> = list.concat();
    let mut offsets = vec![0usize];
    offsets.extend(list.iter().scan(0, |end, s| {
        *end += s.len();
        Some(*end)
    }));
    let mut out = std::ptr::null_mut();
    // SAFETY: `ids` and `offsets` hold what `list.len()` and the offsets say.
    let st = unsafe {
        let (ids, offsets) = (ids.as_ptr(), offsets.as_ptr());
        tpx_complex_from_arrays(n, ids, offsets, list.len(), std::ptr::null(), 0, &mut out)
    };
    (st, out)
}

/// Decodes bytes into a vertex count and a list of simplices: byte 0 picks n in 1..=12, then
/// each simplex is a length byte (1..=7 ids) followed by that many id bytes (mod n + 2, so ids
/// out of range and repeated ids occur too).
pub fn decode(data: &[u8]) -> (u32, Vec<Vec<u32>>) {
    let Some((&first, mut rest)) = data.split_first() else {
        return (1, Vec::new());
    };
    let n = u32::from(first % 12) + 1;
    let mut list = Vec::new();
    while let Some((&len, tail)) = rest.split_first() {
        let len = usize::from(len % 7) + 1;
        let take = len.min(tail.len());
        list.push(
            tail[..take]
                .iter()
                .map(|&b| u32::from(b) % (n + 2))
                .collect(),
        );
        rest = &tail[take..];
    }
    (n, list)
}

/// One seed of the `.tpx` mutation target: the complex, its saved file's bytes and the
/// unaltered file's answers.
pub type SavedSeed = (Complex, Vec<u8>, Vec<String>);

/// The valid saved files the `.tpx` mutation target alters: every structure that accepts a
/// tetrahedron with a dangling triangle and a wire, or three triangles on an edge, saved with
/// its complex, with the complex and the unaltered file's answers.
pub fn saved_seeds() -> Vec<SavedSeed> {
    let dir = std::env::temp_dir().join(format!("topoplex-fuzz-saved-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let mut seeds = Vec::new();
    for c in [
        topoplex::fixtures::tetrahedron_with_dangling_triangle_and_wire(),
        topoplex::fixtures::three_triangles_on_an_edge(),
    ] {
        for kind in StructureKind::NAMED {
            let Ok(s) = build(kind, &c) else { continue };
            let path = dir.join(format!("{kind}.tpx"));
            topoplex::store::save(&path, &c, Some(s.as_ref())).unwrap();
            let bytes = std::fs::read(&path).unwrap();
            std::fs::remove_file(&path).unwrap();
            let want = topoplex::testing::answers(s.as_ref(), &c);
            seeds.push((c.clone(), bytes, want));
        }
    }
    let _ = std::fs::remove_dir(&dir);
    seeds
}
