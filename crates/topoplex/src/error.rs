//! The one rule for text that leaves the library as a message (the CLI's stderr line,
//! `tpx_last_error_message`, every reader's error): a single line, bounded, with nothing
//! invisible.
//!
//! Messages echo input (file paths, tokens, CLI arguments). A hostile input could otherwise make
//! a 100 MB message, a message spread over several lines, or one whose meaning hides in control
//! characters, a byte-order mark or a no-break space ("non-numeric token '01'" that is really
//! `'0<VT>1'`). [`escape`] is the only escaper: [`echo`] applies it to a piece of input quoted in
//! a message (200 bytes), [`one_line`] to the whole message as it leaves (400 bytes).
//!
//! Escapes: `\0 \t \n \r`; `\xNN` for the other ASCII control bytes and for bytes that are not
//! UTF-8; `\u{N}` for every other control, whitespace-like or invisible character (no-break and
//! zero-width spaces, byte-order mark, bidirectional controls, line and paragraph separators,
//! variation selectors, private use). The backslash itself is not escaped, so escaping is
//! idempotent: a message built from echoed pieces passes [`one_line`] unchanged.

use std::fmt::Write as _;
use std::path::PathBuf;

/// Most bytes of escaped input [`echo`] shows before cutting it.
pub const ECHO_MAX_BYTES: usize = 200;

/// Most bytes of a message [`one_line`] keeps before cutting it (each error echoes at most
/// [`ECHO_MAX_BYTES`] of input; the rest is the file name and the explanation).
pub const MESSAGE_MAX_BYTES: usize = 400;

/// `text` escaped (see the module doc) and cut to at most `max_bytes` bytes, followed by
/// `… (N more bytes)` when cut, N counting the input bytes left out. The cut falls on a
/// character boundary, never inside an escape. Bytes that are not UTF-8 are shown as `\xNN`.
pub fn escape(text: impl AsRef<[u8]>, max_bytes: usize) -> String {
    let text = text.as_ref();
    let mut out = String::with_capacity(text.len().min(max_bytes) + 24);
    let mut consumed = 0;
    for chunk in text.utf8_chunks() {
        for c in chunk.valid().chars() {
            let before = out.len();
            push_escaped(&mut out, c);
            if out.len() > max_bytes {
                out.truncate(before);
                return cut(out, text.len() - consumed);
            }
            consumed += c.len_utf8();
        }
        for &b in chunk.invalid() {
            if out.len() + 4 > max_bytes {
                return cut(out, text.len() - consumed);
            }
            let _ = write!(out, "\\x{b:02x}");
            consumed += 1;
        }
    }
    out
}

/// A piece of input (token, keyword, argument, path) as a message quotes it: [`escape`]d and cut
/// to [`ECHO_MAX_BYTES`].
pub fn echo(input: impl AsRef<[u8]>) -> String {
    escape(input, ECHO_MAX_BYTES)
}

/// A path as a message names it: its bytes (not a lossy conversion) [`echo`]ed.
pub fn echo_path(path: &std::path::Path) -> String {
    echo(path.as_os_str().as_encoded_bytes())
}

/// A whole message as it leaves the library (stderr line, last error): [`escape`]d and cut to
/// [`MESSAGE_MAX_BYTES`]. Pieces already [`echo`]ed pass unchanged.
pub fn one_line(message: &str) -> String {
    escape(message, MESSAGE_MAX_BYTES)
}

fn cut(mut out: String, left: usize) -> String {
    let _ = write!(out, "… ({left} more bytes)");
    out
}

fn push_escaped(out: &mut String, c: char) {
    match c {
        '\0' => out.push_str("\\0"),
        '\t' => out.push_str("\\t"),
        '\n' => out.push_str("\\n"),
        '\r' => out.push_str("\\r"),
        ' ' => out.push(' '),
        c if c.is_ascii_control() => {
            let _ = write!(out, "\\x{:02x}", c as u32);
        }
        c if c.is_control() || c.is_whitespace() || invisible(c) => {
            let _ = write!(out, "\\u{{{:x}}}", c as u32);
        }
        c => out.push(c),
    }
}

/// Characters that print as nothing (or as something else): format characters, fillers,
/// variation selectors, tags, private use and noncharacters.
fn invisible(c: char) -> bool {
    matches!(c as u32,
        0xad | 0x34f | 0x61c | 0x115f | 0x1160 | 0x17b4 | 0x17b5 | 0x180b..=0x180f
        | 0x200b..=0x200f | 0x202a..=0x202e | 0x2060..=0x206f | 0x3164 | 0xfe00..=0xfe0f
        | 0xfeff | 0xffa0 | 0xfff0..=0xfffb | 0xe000..=0xf8ff | 0xe0000..=0xe0fff
        | 0xf0000..=0x10ffff)
}

/// Runs `f`, turning a panic into `Err` like [`std::panic::catch_unwind`], but without the
/// panic hook's report for panics on this thread while `f` runs: a caught panic that the caller
/// reports as an error (a crate's panic on malformed input) would otherwise add lines of
/// "thread panicked at" to the one-line message on stderr.
///
/// The first call wraps the process's panic hook once in one that stays silent on a thread
/// inside `caught_quietly` and passes every other panic to the hook it wrapped, so other
/// threads' panics are reported as before. (A hook set later replaces the wrapper; then caught
/// panics are reported again, nothing worse.)
pub fn caught_quietly<R>(f: impl FnOnce() -> R + std::panic::UnwindSafe) -> std::thread::Result<R> {
    use std::cell::Cell;
    thread_local!(static QUIET: Cell<bool> = const { Cell::new(false) });
    static WRAPPED: std::sync::Once = std::sync::Once::new();
    WRAPPED.call_once(|| {
        let previous = std::panic::take_hook();
        std::panic::set_hook(Box::new(move |info| {
            if !QUIET.with(Cell::get) {
                previous(info);
            }
        }));
    });
    let was = QUIET.with(|q| q.replace(true));
    let result = std::panic::catch_unwind(f);
    QUIET.with(|q| q.set(was));
    result
}

/// `[a b c]`, for messages naming a simplex.
pub(crate) fn show(ids: &[u32]) -> String {
    let v: Vec<String> = ids.iter().map(|i| i.to_string()).collect();
    format!("[{}]", v.join(" "))
}

/// What was wrong, without the location ([`ReadError`] adds file and line).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ReadErrorKind {
    /// The file could not be opened or read.
    #[error("cannot read file: {0}")]
    Io(String),
    /// The file does not fit in memory (`TPX_STATUS_TOO_LARGE` through the C ABI).
    #[error("file too large: {0}")]
    TooLarge(String),
    /// The extension names no supported format.
    #[error(
        "unknown file extension (expected .off, .obj, .mesh, .simplices, .ply, .stl, .vtk, .vtu or .msh)"
    )]
    UnknownExtension,
    /// The text does not follow the format.
    #[error("{0}")]
    Syntax(String),
    /// A polygon of more than 3 vertices (only simplices are accepted unless the reader is
    /// asked to triangulate).
    #[error("polygon with {0} vertices is not a simplex (--triangulate fans convex planar ones)")]
    Polygon(usize),
    /// A negative vertex id.
    #[error("negative vertex id {0}")]
    NegativeId(i64),
    /// A polygon that `--triangulate` (`crate::io::ReadOptions::triangulate`) cannot fan into
    /// triangles: which one and why.
    #[error("cannot triangulate {0}")]
    Triangulation(String),
}

/// A reader error naming the file and the 1-based line (line 0: the file as a whole, shown as
/// `file: what`, with no line).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{}{}: {kind}", echo_path(path), line_part(*line))]
pub struct ReadError {
    /// The file.
    pub path: PathBuf,
    /// 1-based line (0: the file as a whole).
    pub line: u32,
    /// What was wrong.
    pub kind: ReadErrorKind,
}

/// `:LINE` for a line of the file, nothing for the file as a whole (line 0).
fn line_part(line: u32) -> String {
    if line == 0 {
        String::new()
    } else {
        format!(":{line}")
    }
}

/// The [`ReadErrorKind::TooLarge`] of an allocation of `what` (a reader's output array) that
/// failed asking for the given bytes: `map_err(no_room("..."))` on the `Err(bytes)` of
/// [`crate::alloc::try_push`] and its family.
pub(crate) fn no_room(what: &'static str) -> impl Fn(usize) -> ReadErrorKind {
    move |bytes| {
        ReadErrorKind::TooLarge(format!(
            "cannot allocate {bytes} bytes for {what} (out of memory)"
        ))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::path::Path;

    #[test]
    fn plain_text_is_unchanged() {
        assert_eq!(
            echo("abc 1.5e3 café 漢字 it's a\\b"),
            "abc 1.5e3 café 漢字 it's a\\b"
        );
    }

    #[test]
    fn control_and_invisible_characters_are_escaped() {
        assert_eq!(echo("0\u{b}1"), "0\\x0b1");
        assert_eq!(echo("a\0b\tc\r\n"), "a\\0b\\tc\\r\\n");
        assert_eq!(echo("1\u{a0}2"), "1\\u{a0}2");
        assert_eq!(echo("\u{feff}OFF"), "\\u{feff}OFF");
        assert_eq!(
            echo("a\u{202e}b\u{200b}\u{2028}"),
            "a\\u{202e}b\\u{200b}\\u{2028}"
        );
        assert_eq!(echo("\u{7f}\u{85}\u{3000}"), "\\x7f\\u{85}\\u{3000}");
    }

    #[test]
    fn invalid_bytes_are_escaped() {
        assert_eq!(echo(b"ply\xff\xfe\x00\x01"), "ply\\xff\\xfe\\0\\x01");
        assert_eq!(echo(b"caf\xe9"), "caf\\xe9");
    }

    #[test]
    fn long_input_is_cut_on_a_character_boundary_with_the_rest_counted() {
        let long = "9".repeat(100_000_000);
        assert_eq!(
            echo(&long),
            format!("{}… (99999800 more bytes)", "9".repeat(ECHO_MAX_BYTES))
        );
        // Escapes count towards the cap.
        let e = echo(vec![0xffu8; 1000]);
        assert_eq!(e, format!("{}… (950 more bytes)", "\\xff".repeat(50)));
        let e = echo("é".repeat(300));
        assert_eq!(e, format!("{}… (400 more bytes)", "é".repeat(100)));
        // An escape is never cut in half.
        assert_eq!(escape("abc\n\n\n", 5), "abc\\n… (2 more bytes)");
        assert_eq!(escape("short", 5), "short");
    }

    #[test]
    fn a_message_of_echoed_pieces_passes_one_line_unchanged() {
        let nasty = b"\xef\xbb\xbf0\x0b1\xff\n\xe2\x80\xae".repeat(40);
        let msg = format!(
            "f.off:3: token '{}' in {}",
            echo(&nasty),
            echo_path(Path::new("a\tb"))
        );
        assert_eq!(one_line(&msg), msg);
        let e = echo(&nasty);
        assert_eq!(escape(&e, usize::MAX), e);
    }

    #[cfg(unix)]
    #[test]
    fn paths_are_echoed_from_their_bytes() {
        use std::os::unix::ffi::OsStrExt;
        let p = Path::new(std::ffi::OsStr::from_bytes(b"/tmp/a\nb's\xff.off"));
        assert_eq!(echo_path(p), "/tmp/a\\nb's\\xff.off");
    }
}
