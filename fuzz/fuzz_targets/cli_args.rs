//! The CLI's argument surface (issue 16): arbitrary argument lists, from a vocabulary of
//! commands, flags and values plus fuzzed bytes, run in-process on tiny fixture files. Whatever
//! the arguments, the CLI returns (no panic, no abort) with exit 0, or exit 1 and a message that
//! makes one bounded line. It runs in a scratch directory of its own; fuzzed path bytes have
//! their `/` replaced, so every file it writes stays inside that directory.
#![no_main]

use std::ffi::OsString;
use std::os::unix::ffi::OsStringExt;
use std::sync::Once;

use libfuzzer_sys::fuzz_target;

// The binary's source, so the fuzzer calls its `cli` function (clap parsing included).
#[allow(dead_code)]
#[path = "../../src/main.rs"]
mod cli_main;

const VOCABULARY: &[&str] = &[
    "report",
    "relation",
    "save",
    "verify",
    "decompose",
    "convert",
    "simplify",
    "help",
    "--help",
    "-V",
    "--structure",
    "--relation",
    "--simplex",
    "--out",
    "--force",
    "--format",
    "--census",
    "--ratio",
    "--preserve-topology",
    "--json",
    "--csv",
    "--svg",
    "--max-simplices",
    "--threads",
    "ig",
    "sig",
    "ia",
    "iqm",
    "nmia",
    "ts",
    "pe",
    "le",
    "de",
    "0,0",
    "0,1",
    "1,2",
    "2,1",
    "2,2",
    "0",
    "1",
    "2",
    "0 1",
    "0,1,2",
    "unlimited",
    "0.5",
    "-1",
    "1e309",
    "",
    "a.off",
    "a.obj",
    "a.simplices",
    "a.mesh",
    "a.ply",
    "a.stl",
    "a.vtk",
    "a.msh",
    "a.tpx",
    "missing.off",
    "out.off",
    "out.obj",
    "out.ply",
    "out.vtu",
    "out.tpx",
    "outdir",
    "=",
    // Issue 27: thread counts at and past the cap, the full check, saved files by magic, and
    // output paths that are a directory, a nested path or the input itself.
    "4",
    "1024",
    "1025",
    "100000",
    "18446744073709551616",
    "--verify",
    "iastar",
    "IA",
    "a.bin",
    "out.bin",
    ".",
    "outdir/out.off",
    "a.tpx.partial",
];

/// The fixtures: three triangles (OFF, converted to each other format) and a tetrahedron with a
/// dangling triangle and a wire edge (`.simplices`, saved with its SIG as `a.tpx` and with its
/// NMIA as `a.bin`, a saved file known by its magic number).
fn setup() {
    let dir = std::env::temp_dir().join(format!("topoplex-fuzz-cli-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::env::set_current_dir(&dir).unwrap();
    std::fs::write(
        "a.off",
        "OFF\n5 3 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n1 1 1\n3 0 1 2\n3 1 2 4\n3 0 1 3\n",
    )
    .unwrap();
    std::fs::write("a.simplices", "s 0 1 2 3\ns 1 2 4\ns 4 5\n").unwrap();
    for (to, extra) in [
        ("a.obj", None),
        ("a.mesh", None),
        ("a.ply", None),
        ("a.stl", None),
        ("a.vtk", None),
        ("a.msh", None),
        ("a.tpx", Some("sig")),
        ("a.bin", Some("nmia")),
    ] {
        let args: Vec<OsString> = match extra {
            None => ["topoplex", "convert", "a.off", to]
                .map(OsString::from)
                .to_vec(),
            Some(s) => [
                "topoplex",
                "save",
                "a.simplices",
                "--structure",
                s,
                "--out",
                to,
            ]
            .map(OsString::from)
            .to_vec(),
        };
        cli_main::cli(args).unwrap();
    }
}

/// Arguments from bytes: a byte below the vocabulary's length picks a word; 255 starts a
/// literal of the next `len` bytes (`/` replaced); other bytes are skipped. At most 10.
fn arguments(data: &[u8]) -> Vec<OsString> {
    let mut args = vec![OsString::from("topoplex")];
    let mut rest = data;
    while let Some((&b, tail)) = rest.split_first() {
        rest = tail;
        if usize::from(b) < VOCABULARY.len() {
            args.push(VOCABULARY[usize::from(b)].into());
        } else if b == 255 {
            let Some((&len, tail)) = rest.split_first() else {
                break;
            };
            let len = usize::from(len % 64).min(tail.len());
            let bytes = tail[..len]
                .iter()
                .map(|&c| if c == b'/' { b'_' } else { c })
                .collect();
            args.push(OsString::from_vec(bytes));
            rest = &tail[len..];
        }
        if args.len() > 10 {
            break;
        }
    }
    args
}

fuzz_target!(|data: &[u8]| {
    static SETUP: Once = Once::new();
    SETUP.call_once(setup);
    if let Err(msg) = cli_main::cli(arguments(data)) {
        let line = topoplex::error::one_line(&msg);
        assert!(!line.contains('\n') && !line.is_empty(), "{line}");
        assert!(
            line.len() <= topoplex::error::MESSAGE_MAX_BYTES + 32,
            "{line}"
        );
    }
});
