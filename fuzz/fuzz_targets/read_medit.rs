#![no_main]
//! The medit reader on arbitrary text: it must return a value or an error, never panic, hang or
//! over-allocate; whatever it accepts must normalise or be refused cleanly, and small results
//! must build an IG that validates.
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    if let Ok(text) = std::str::from_utf8(data)
        && let Ok(raw) = topoplex::io::medit::parse(text)
    {
        topoplex_fuzz_support::check_raw(&raw);
    }
});
