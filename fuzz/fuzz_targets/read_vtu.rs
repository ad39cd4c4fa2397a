#![no_main]
//! The vtu reader on arbitrary bytes: it must return a value or an error, never panic, hang or
//! over-allocate (declared counts reserve nothing beyond the input); whatever it accepts must
//! normalise or be refused cleanly, and small results must build structures that validate.
use libfuzzer_sys::fuzz_target;

/// libFuzzer aborts on every panic, caught or not; `vtu::parse` catches the vtkio crate's known
/// panics on malformed arrays, so only panics elsewhere abort.
fn abort_unless_vtkio() {
    static ONCE: std::sync::Once = std::sync::Once::new();
    ONCE.call_once(|| {
        std::panic::set_hook(Box::new(|info| {
            if info.location().is_some_and(|l| l.file().contains("vtkio")) {
                return;
            }
            eprintln!("{info}");
            std::process::abort();
        }));
    });
}

fuzz_target!(|data: &[u8]| {
    abort_unless_vtkio();
    if let Ok(raw) = topoplex::io::vtu::parse(data) {
        topoplex_fuzz_support::check_raw(&raw);
    }
});
