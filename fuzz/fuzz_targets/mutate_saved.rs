#![no_main]
//! Valid saved files (`.tpx`), altered (issue 27): byte edits anywhere, section counts and
//! offsets rewritten, with or without the checksums rewritten after (so that edits reach the
//! checks behind them). Every altered file is refused on open or load, or answers every
//! relation exactly as the unaltered file does, or is refused by `verify`; open, load and
//! verify never panic, and a query that panics (caught, as the CLI and the C ABI catch it) is
//! allowed only on a file that `verify` refuses.
use std::panic::AssertUnwindSafe;
use std::path::Path;
use std::sync::OnceLock;

use libfuzzer_sys::fuzz_target;
use topoplex::error::caught_quietly;
use topoplex::store::{Saved, reseal};
use topoplex_fuzz_support::{SavedSeed, saved_seeds};

fuzz_target!(|data: &[u8]| {
    static SEEDS: OnceLock<Vec<SavedSeed>> = OnceLock::new();
    let seeds = SEEDS.get_or_init(saved_seeds);
    let Some((&pick, mut ops)) = data.split_first() else {
        return;
    };
    let (complex, good, want) = &seeds[usize::from(pick) % seeds.len()];
    let mut bytes = good.clone();
    // Edits of 6 bytes: a 4-byte place (modulo the length), a mode and a value. Mode bit 0: set
    // the byte; bit 1: write the value as a little u64 at the place; bit 2: reseal after.
    let mut resealing = false;
    while ops.len() >= 6 {
        let place = u32::from_le_bytes(ops[..4].try_into().unwrap()) as usize % bytes.len();
        let (mode, value) = (ops[4], ops[5]);
        if mode & 2 != 0 && place + 8 <= bytes.len() {
            let wide = u64::from(value).wrapping_mul(0x0101_0101_0101_0101) >> (mode >> 3);
            bytes[place..place + 8].copy_from_slice(&wide.to_ne_bytes());
        } else {
            bytes[place] = if mode & 1 != 0 {
                value
            } else {
                bytes[place] ^ value
            };
        }
        resealing |= mode & 4 != 0;
        ops = &ops[6..];
    }
    if resealing {
        reseal(&mut bytes);
    }
    let Ok(saved) = Saved::from_bytes(Path::new("fuzz.tpx"), &bytes) else {
        return;
    };
    let _ = saved.complex();
    let s = match saved.structure() {
        Ok(Some(s)) => s,
        _ => return,
    };
    let got = caught_quietly(AssertUnwindSafe(|| {
        topoplex::testing::answers(s.as_ref(), complex)
    }));
    if got.as_ref().is_ok_and(|got| got == want) {
        return;
    }
    assert!(
        saved.verify().is_err(),
        "an altered file answers differently (or a query panicked) and passes verify"
    );
});
