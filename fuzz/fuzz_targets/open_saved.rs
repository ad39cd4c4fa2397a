#![no_main]
//! Saved files (`.tpx`) from arbitrary bytes: opening, verifying and loading never panic or
//! read out of bounds, whatever the header, section table or arrays say; a file that passes
//! `verify` answers every relation of its first vertices without panicking. Seeds in
//! corpus/open_saved are valid files (every structure of small complexes).
use libfuzzer_sys::fuzz_target;
use std::path::Path;
use topoplex::store::Saved;

fuzz_target!(|data: &[u8]| {
    let Ok(saved) = Saved::from_bytes(Path::new("fuzz.tpx"), data) else {
        return;
    };
    let _ = saved.complex();
    let verified = saved.verify().is_ok();
    let Ok(Some(s)) = saved.structure() else {
        return;
    };
    if verified {
        let mut out = Vec::new();
        for v in 0..s.vertex_count().min(16) {
            for q in 0..=s.dimension() {
                let _ = s.relation(&[v], q, &mut out);
            }
        }
    }
});
