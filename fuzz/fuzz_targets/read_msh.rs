#![no_main]
//! The msh reader on arbitrary bytes: it must return a value or an error, never panic, hang or
//! over-allocate (declared counts reserve nothing beyond the input); whatever it accepts must
//! normalise or be refused cleanly, and small results must build structures that validate.
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    if let Ok(raw) = topoplex::io::msh::parse(data) {
        topoplex_fuzz_support::check_raw(&raw);
    }
});
