//! Echoing input back in error messages: capped and escaped.
//!
//! A message that quotes the file must stay one short, readable line whatever the file holds: a
//! 100 MB token, a NUL, a vertical tab, a no-break space, a stray byte-order mark or a binary
//! header. [`echo`] shows at most [`ECHO_CAP`] bytes of escaped text, then how long the input
//! was; every byte that would not print as itself (control characters, invisible or
//! whitespace-like Unicode characters, bytes that are not UTF-8) is shown as an escape:
//! `\0 \t \n \r`, `\xNN` for other control bytes and invalid bytes, `\u{NNNN}` for other
//! characters, and `\\`, `\'` for the backslash and the quote that messages put around it.

use std::fmt::Write as _;
use std::path::Path;

/// The most bytes of escaped text [`echo`] writes before cutting the input short.
pub const ECHO_CAP: usize = 200;

/// `input` as it may appear in a one-line message: escaped, and cut to at most [`ECHO_CAP`] bytes
/// of text followed by `… (N bytes)` when longer.
pub fn echo(input: impl AsRef<[u8]>) -> String {
    let input = input.as_ref();
    let mut out = String::new();
    let mut consumed = 0;
    for chunk in input.utf8_chunks() {
        for c in chunk.valid().chars() {
            let before = out.len();
            push_char(&mut out, c);
            if out.len() > ECHO_CAP {
                out.truncate(before);
                return cut(out, input.len());
            }
            consumed += c.len_utf8();
        }
        for &b in chunk.invalid() {
            if out.len() + 4 > ECHO_CAP {
                return cut(out, input.len());
            }
            write!(out, "\\x{b:02x}").unwrap();
            consumed += 1;
        }
    }
    debug_assert_eq!(consumed, input.len());
    out
}

/// A path for a message: escaped as [`echo`] does, but never cut (paths are bounded by the
/// system).
pub fn echo_path(path: &Path) -> String {
    let lossy = path.to_string_lossy();
    let mut out = String::with_capacity(lossy.len());
    for c in lossy.chars() {
        match c {
            // Paths quote nothing, so a quote or backslash stays as written.
            '\'' | '\\' => out.push(c),
            _ => push_char(&mut out, c),
        }
    }
    out
}

fn cut(mut out: String, total: usize) -> String {
    write!(out, "… ({total} bytes)").unwrap();
    out
}

fn push_char(out: &mut String, c: char) {
    match c {
        '\\' => out.push_str("\\\\"),
        '\'' => out.push_str("\\'"),
        '\0' => out.push_str("\\0"),
        '\t' => out.push_str("\\t"),
        '\n' => out.push_str("\\n"),
        '\r' => out.push_str("\\r"),
        c if c.is_ascii_control() => write!(out, "\\x{:02x}", c as u32).unwrap(),
        ' ' => out.push(' '),
        c if c.is_control() || c.is_whitespace() || invisible(c) => {
            write!(out, "\\u{{{:x}}}", c as u32).unwrap()
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn plain_text_is_unchanged() {
        assert_eq!(echo("abc 1.5e3 café"), "abc 1.5e3 café");
    }

    #[test]
    fn control_and_invisible_characters_are_escaped() {
        assert_eq!(echo("0\u{b}1"), "0\\x0b1");
        assert_eq!(echo("a\0b\tc\r\n"), "a\\0b\\tc\\r\\n");
        assert_eq!(echo("1\u{a0}2"), "1\\u{a0}2");
        assert_eq!(echo("\u{feff}OFF"), "\\u{feff}OFF");
        assert_eq!(echo("a\u{202e}b\u{200b}"), "a\\u{202e}b\\u{200b}");
        assert_eq!(echo("\u{7f}\u{85}"), "\\x7f\\u{85}");
        assert_eq!(echo("it's a\\b"), "it\\'s a\\\\b");
    }

    #[test]
    fn invalid_bytes_are_escaped() {
        assert_eq!(echo(b"ply\xff\xfe\x00\x01"), "ply\\xff\\xfe\\0\\x01");
        assert_eq!(echo(b"caf\xe9"), "caf\\xe9");
    }

    #[test]
    fn long_input_is_cut_with_its_length() {
        let long = "9".repeat(100_000_000);
        let e = echo(&long);
        assert_eq!(e, format!("{}… (100000000 bytes)", "9".repeat(ECHO_CAP)));
        // Escapes count towards the cap: never more than ECHO_CAP bytes before the cut.
        let e = echo(vec![0xffu8; 1000]);
        assert!(e.ends_with("… (1000 bytes)"));
        assert_eq!(e.len(), 200 + "… (1000 bytes)".len());
        let e = echo("é".repeat(300));
        assert!(e.starts_with(&"é".repeat(100)) && e.ends_with("… (600 bytes)"));
    }

    #[test]
    fn paths_are_escaped_not_cut() {
        let p = format!("/tmp/{}/a\nb's.off", "d".repeat(300));
        assert_eq!(
            echo_path(Path::new(&p)),
            format!("/tmp/{}/a\\nb's.off", "d".repeat(300))
        );
    }
}
