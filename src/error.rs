//! The one rule for text that leaves the library as a message (the CLI's stderr line,
//! `tpx_last_error_message`): a single line, bounded, with nothing invisible.
//!
//! Messages echo input (file paths, tokens, CLI arguments). A hostile input could otherwise make
//! a 100 MB message, a message spread over several lines, or one whose meaning hides in control
//! characters, a byte-order mark or a no-break space ("non-numeric token '01'" that is really
//! `'0<VT>1'`). [`one_line`] escapes those and caps the length.

use std::fmt::Write as _;

/// Most bytes of a message [`one_line`] keeps before cutting it (each error echoes at most
/// ~200 bytes of input; the rest is the file name and the explanation).
pub const MESSAGE_MAX_BYTES: usize = 400;

/// `text` as one line of at most `max_bytes` bytes (plus a short "… (N more bytes)" note when
/// cut): control characters (`\n`, `\t`, NUL, …), invisible and space-like format characters
/// (no-break and zero-width spaces, byte-order mark, bidirectional controls, line and paragraph
/// separators) are written as escapes (`\n`, `\t`, `\u{feff}`), so what is shown is what was
/// there. The cut falls on a character boundary, never inside an escape.
pub fn one_line(text: &str, max_bytes: usize) -> String {
    let mut out = String::with_capacity(text.len().min(max_bytes) + 32);
    for (i, c) in text.char_indices() {
        let before = out.len();
        match c {
            '\n' => out.push_str("\\n"),
            '\r' => out.push_str("\\r"),
            '\t' => out.push_str("\\t"),
            '\0' => out.push_str("\\0"),
            c if is_hidden(c) => {
                let _ = write!(out, "\\u{{{:x}}}", c as u32);
            }
            c => out.push(c),
        }
        if out.len() > max_bytes {
            out.truncate(before);
            let _ = write!(out, "… ({} more bytes)", text.len() - i);
            break;
        }
    }
    out
}

/// Control characters and characters that print as nothing or as a plain space.
fn is_hidden(c: char) -> bool {
    c.is_control()
        || matches!(
            c,
            '\u{00a0}' // no-break space
                | '\u{00ad}' // soft hyphen
                | '\u{034f}'
                | '\u{061c}'
                | '\u{115f}'
                | '\u{1160}'
                | '\u{1680}'
                | '\u{180e}'
                | '\u{2000}'..='\u{200f}' // spaces of every width, zero-width, LRM/RLM
                | '\u{2028}'..='\u{202f}' // separators, bidi embeddings, narrow no-break space
                | '\u{205f}'..='\u{206f}' // math space, word joiner, invisible operators
                | '\u{3000}'
                | '\u{3164}'
                | '\u{fe00}'..='\u{fe0f}' // variation selectors
                | '\u{feff}' // byte-order mark
                | '\u{ffa0}'
                | '\u{fff9}'..='\u{fffb}'
        )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn controls_and_invisible_characters_are_escaped() {
        assert_eq!(
            one_line("token '0\u{b}1' at\nline\t2\0", 100),
            "token '0\\u{b}1' at\\nline\\t2\\0"
        );
        assert_eq!(
            one_line("\u{feff}a\u{a0}b\u{200b}c\u{202e}", 100),
            "\\u{feff}a\\u{a0}b\\u{200b}c\\u{202e}"
        );
        // Printable text, accents and CJK included, is kept as is.
        assert_eq!(one_line("é 漢字 ok", 100), "é 漢字 ok");
    }

    #[test]
    fn long_text_is_cut_on_a_character_boundary_with_the_rest_counted() {
        let long = "é".repeat(1000); // 2000 bytes
        let got = one_line(&long, 11);
        assert_eq!(got, format!("{}… (1990 more bytes)", "é".repeat(5)));
        // An escape is never cut in half.
        let got = one_line("abc\n\n\n", 5);
        assert_eq!(got, "abc\\n… (2 more bytes)");
        assert_eq!(one_line("short", 5), "short");
    }
}
