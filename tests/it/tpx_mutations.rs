//! Saved files (`.tpx`) altered behind their checksums (the edit resealed, so that it reaches
//! the checks past the checksums): every section's count and offset changed and every word of
//! every section rewritten, for every structure of small complexes. Each altered file is refused
//! on open or load, or answers every relation exactly as the unaltered file does, or is refused
//! by `verify`, and nothing panics.

use std::panic::{AssertUnwindSafe, catch_unwind};
use std::path::Path;

use topoplex::error::caught_quietly;
use topoplex::store::{Saved, reseal, save};
use topoplex::{Complex, StructureKind, Topology, build, fixtures};

/// The complexes drawn: a tetrahedron with a dangling triangle and wire (every 3D structure)
/// and three triangles on an edge (the 2D ones too).
fn complexes() -> Vec<(&'static str, Complex)> {
    vec![
        (
            "tetrahedron+triangle+wire",
            fixtures::tetrahedron_with_dangling_triangle_and_wire(),
        ),
        (
            "three triangles on an edge",
            fixtures::three_triangles_on_an_edge(),
        ),
    ]
}

fn saved(c: &Complex, s: Option<&dyn Topology>, name: &str) -> Vec<u8> {
    let dir = std::env::temp_dir().join(format!("tpx-mutations-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join(format!("{name}.tpx"));
    save(&path, c, s).unwrap();
    let bytes = std::fs::read(&path).unwrap();
    std::fs::remove_file(&path).unwrap();
    let _ = std::fs::remove_dir(&dir);
    bytes
}

fn u64_at(b: &[u8], o: usize) -> u64 {
    u64::from_ne_bytes(b[o..o + 8].try_into().unwrap())
}

/// (offset, count, size) of every section, and the place of each table entry.
fn sections(b: &[u8]) -> Vec<(usize, u64, u64, u32)> {
    let n = u32::from_ne_bytes(b[24..28].try_into().unwrap()) as usize;
    let table = u64_at(b, 40) as usize;
    (0..n)
        .map(|i| {
            let at = table + 32 * i;
            let size = u32::from_ne_bytes(b[at + 16..at + 20].try_into().unwrap());
            (at, u64_at(b, at), u64_at(b, at + 8), size)
        })
        .collect()
}

/// Every alteration of `good`: (what, bytes), resealed.
fn alterations(good: &[u8]) -> Vec<(String, Vec<u8>)> {
    let mut out = Vec::new();
    for (i, &(at, offset, count, size)) in sections(good).iter().enumerate() {
        let counts = [0, count.saturating_sub(1), count + 1, u64::MAX / 2];
        for c in counts.into_iter().filter(|&c| c != count) {
            let mut b = good.to_vec();
            b[at + 8..at + 16].copy_from_slice(&c.to_ne_bytes());
            reseal(&mut b);
            out.push((format!("section {i}: count {count} -> {c}"), b));
        }
        for o in [offset + 64, 0] {
            let mut b = good.to_vec();
            b[at..at + 8].copy_from_slice(&o.to_ne_bytes());
            reseal(&mut b);
            out.push((format!("section {i}: offset {offset} -> {o}"), b));
        }
        if size != 4 && size != 8 {
            continue;
        }
        // The first few elements and the last: counts, offsets and ids at both ends.
        let values: [u64; 5] = [0, 1, 5, u32::MAX as u64, u64::MAX];
        let last = count.saturating_sub(1) as usize;
        for j in (0..count.min(4) as usize).chain((count > 4).then_some(last)) {
            let place = offset as usize + j * size as usize;
            for &v in &values {
                let mut b = good.to_vec();
                match size {
                    4 => b[place..place + 4].copy_from_slice(&(v as u32).to_ne_bytes()),
                    _ => b[place..place + 8].copy_from_slice(&v.to_ne_bytes()),
                }
                if b[..] == good[..] {
                    continue;
                }
                reseal(&mut b);
                out.push((format!("section {i}: element {j} -> {v:#x}"), b));
            }
        }
    }
    out
}

/// What happens to one altered file; `Err` for a panic on open, load or verify, or for wrong
/// answers that `verify` passes. A query that panics (caught, as the CLI and the C ABI catch
/// it) counts as a wrong answer: `verify` must refuse that file.
fn outcome(bytes: &[u8], c: &Complex, want: &[String]) -> Result<&'static str, String> {
    let name = Path::new("altered.tpx");
    let run = catch_unwind(AssertUnwindSafe(|| {
        let Ok(saved) = Saved::from_bytes(name, bytes) else {
            return Ok("refused on open");
        };
        let s = match saved.structure() {
            Ok(Some(s)) => s,
            Ok(None) => return Ok("complex only"),
            Err(_) => return Ok("refused on load"),
        };
        let got = caught_quietly(AssertUnwindSafe(|| {
            topoplex::testing::answers(s.as_ref(), c)
        }));
        if got.as_deref().is_ok_and(|got| got == want) {
            return Ok("same answers");
        }
        match saved.verify() {
            Err(_) => Ok("refused by verify"),
            Ok(()) => match got {
                Ok(got) => {
                    let diff = got.iter().zip(want).find(|(g, w)| g != w);
                    Err(format!("different answers, verified: {diff:?}"))
                }
                Err(_) => Err("a query panicked, verified".into()),
            },
        }
    }));
    run.unwrap_or_else(|p| {
        let msg = p
            .downcast_ref::<String>()
            .cloned()
            .or_else(|| p.downcast_ref::<&str>().map(|s| s.to_string()))
            .unwrap_or_default();
        Err(format!("panic on open, load or verify: {msg}"))
    })
}

#[test]
fn altered_saved_files_are_refused_or_answer_alike_never_a_panic() {
    let mut bad = Vec::new();
    let mut tried = 0;
    for (what, c) in complexes() {
        for kind in StructureKind::NAMED {
            let Ok(s) = build(kind, &c) else { continue };
            let good = saved(&c, Some(s.as_ref()), &format!("{kind}"));
            let want = topoplex::testing::answers(s.as_ref(), &c);
            for (change, bytes) in alterations(&good) {
                tried += 1;
                if let Err(e) = outcome(&bytes, &c, &want) {
                    bad.push(format!("{what}, {kind}, {change}: {e}"));
                }
            }
        }
    }
    assert!(tried > 1000, "only {tried} alterations");
    assert!(
        bad.is_empty(),
        "{} of {tried} alterations:\n{}",
        bad.len(),
        bad.join("\n")
    );
}
