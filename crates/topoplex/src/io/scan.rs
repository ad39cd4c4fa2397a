//! Byte-level scanning shared by the readers: tokens with their line, and numbers parsed
//! straight from the bytes.
//!
//! One pass over the text, no allocation per line or token: a table classifies each byte,
//! comments are skipped with `memchr`, floats are parsed by `fast-float2` and integers by a
//! digit loop. Lines end in `\n`, `\r\n` or a lone `\r` (old Mac files), so line numbers are
//! right for all three. Spaces, tabs and form feeds separate tokens; `#` starts a comment that
//! runs to the end of its line. Any other byte (a vertical tab, a NUL, a no-break space) is part
//! of a token, so it shows up, escaped by [`crate::error::echo`], in the error about that token.

use super::{IntError, ReadErrorKind, echo, syntax};

const TOKEN: u8 = 0;
const BLANK: u8 = 1;
const NEWLINE: u8 = 2;
const COMMENT: u8 = 3;
const BACKSLASH: u8 = 4;

/// What each byte is to the scanner.
static CLASS: [u8; 256] = {
    let mut t = [TOKEN; 256];
    t[b' ' as usize] = BLANK;
    t[b'\t' as usize] = BLANK;
    t[0x0c] = BLANK;
    t[b'\n' as usize] = NEWLINE;
    t[b'\r' as usize] = NEWLINE;
    t[b'#' as usize] = COMMENT;
    t[b'\\' as usize] = BACKSLASH;
    t
};

/// A cursor over a text that yields whitespace-separated tokens with their 1-based line.
///
/// Two ways to walk: [`Scanner::token`] crosses line ends (token-based formats: OFF, MEDIT);
/// [`Scanner::token_in_line`] stops at the end of the line, and [`Scanner::next_line`] moves on
/// (line-based formats: OBJ, `.simplices`). With continuation on (OBJ), a `\` followed by
/// nothing but blanks or a comment joins the next line to the current one.
#[derive(Clone)]
pub(crate) struct Scanner<'a> {
    text: &'a str,
    pos: usize,
    line: u32,
    continuation: bool,
    dangling: bool,
}

impl<'a> Scanner<'a> {
    pub(crate) fn new(text: &'a str) -> Self {
        Scanner {
            text,
            pos: 0,
            line: 1,
            continuation: false,
            dangling: false,
        }
    }

    /// A scanner over `text` standing at byte `pos` (a line start), on line `line`.
    pub(crate) fn at_line(text: &'a str, pos: usize, line: u32) -> Self {
        Scanner {
            pos,
            line,
            ..Scanner::new(text)
        }
    }

    /// The byte the cursor stands at.
    pub(crate) fn pos(&self) -> usize {
        self.pos
    }

    /// Moves the cursor to byte `pos` (a line start, or the end of the text) on line `line`:
    /// where the scanner would stand after reading up to there itself.
    pub(crate) fn place(&mut self, pos: usize, line: u32) {
        self.pos = pos;
        self.line = line;
    }

    /// A scanner for which a trailing `\` continues the line (OBJ).
    pub(crate) fn with_continuation(text: &'a str) -> Self {
        Scanner {
            continuation: true,
            ..Scanner::new(text)
        }
    }

    /// The 1-based line the cursor is on.
    pub(crate) fn line(&self) -> u32 {
        self.line
    }

    /// The whole text's length in bytes (for capacity caps).
    pub(crate) fn len(&self) -> usize {
        self.text.len()
    }

    /// Whether a `\` continued the last line past the end of the file.
    pub(crate) fn dangling_continuation(&self) -> bool {
        self.dangling
    }

    /// The line to blame when the file ends early: its last line (a final line end does not
    /// start another), at least 1.
    pub(crate) fn eof_line(&self) -> u32 {
        let b = self.text.as_bytes();
        let ends_in_newline = matches!(b.last(), Some(b'\n' | b'\r'));
        if self.pos >= b.len() && ends_in_newline {
            (self.line - 1).max(1)
        } else {
            self.line.max(1)
        }
    }

    /// Skips blanks and a comment on the current line (following continuations); true when a
    /// token starts at the cursor, false at the end of the line or of the file.
    fn skip_blanks(&mut self) -> bool {
        let b = self.text.as_bytes();
        while let Some(&c) = b.get(self.pos) {
            match CLASS[c as usize] {
                TOKEN => return true,
                BLANK => self.pos += 1,
                NEWLINE => return false,
                COMMENT => {
                    self.pos = self.line_end(self.pos);
                    return false;
                }
                _ if self.continues_at(self.pos) => self.continue_line(),
                _ => return true,
            }
        }
        false
    }

    /// The offset of the line end (or the end of the text) at or after `from`.
    fn line_end(&self, from: usize) -> usize {
        let b = self.text.as_bytes();
        memchr::memchr2(b'\n', b'\r', &b[from..]).map_or(b.len(), |k| from + k)
    }

    /// Whether the `\` at `at` continues the line: continuation is on and only blanks or a
    /// comment follow it on its line.
    fn continues_at(&self, at: usize) -> bool {
        if !self.continuation {
            return false;
        }
        let rest = &self.text.as_bytes()[at + 1..];
        let after = rest
            .iter()
            .position(|&c| CLASS[c as usize] != BLANK)
            .map(|k| rest[k]);
        matches!(after, None | Some(b'\n' | b'\r' | b'#'))
    }

    /// Moves past a continuing `\` and its line end to the next line.
    fn continue_line(&mut self) {
        self.pos = self.line_end(self.pos);
        if !self.next_line() || self.pos >= self.text.len() {
            self.dangling = true;
        }
    }

    /// The next token on the current line, or `None` at its end (the cursor stays there).
    #[inline]
    pub(crate) fn token_in_line(&mut self) -> Option<(&'a str, u32)> {
        if !self.skip_blanks() {
            return None;
        }
        let b = self.text.as_bytes();
        let start = self.pos;
        let mut i = start;
        loop {
            while i < b.len() && CLASS[b[i] as usize] == TOKEN {
                i += 1;
            }
            // A `\` inside a token is part of it, unless it continues the line.
            if i < b.len() && b[i] == b'\\' && !self.continues_at(i) {
                i += 1;
                continue;
            }
            break;
        }
        self.pos = i;
        Some((&self.text[start..i], self.line))
    }

    /// Skips what is left of the current line (continuations included).
    pub(crate) fn skip_rest_of_line(&mut self) {
        while self.token_in_line().is_some() {}
    }

    /// Moves past the line end at the cursor to the start of the next line; false at the end of
    /// the file. The cursor must be at a line end (after [`Scanner::token_in_line`] returned
    /// `None`).
    pub(crate) fn next_line(&mut self) -> bool {
        let b = self.text.as_bytes();
        match b.get(self.pos) {
            None => return false,
            Some(b'\r') if b.get(self.pos + 1) == Some(&b'\n') => self.pos += 2,
            Some(_) => self.pos += 1,
        }
        self.line = self.line.saturating_add(1);
        true
    }

    /// The next token, on this line or a later one.
    #[inline]
    pub(crate) fn token(&mut self) -> Option<(&'a str, u32)> {
        self.seek(true);
        self.token_in_line()
    }

    /// Moves to the start of the next token, across line ends when `cross` (else only within the
    /// line); false when there is none.
    #[inline]
    fn seek(&mut self, cross: bool) -> bool {
        // The common cases first: the token is here, or after one space or one `\n`.
        let b = self.text.as_bytes();
        let class = |i: usize| b.get(i).map(|&c| CLASS[c as usize]);
        match class(self.pos) {
            Some(TOKEN) => return true,
            Some(BLANK) if class(self.pos + 1) == Some(TOKEN) => {
                self.pos += 1;
                return true;
            }
            Some(NEWLINE)
                if cross && b[self.pos] == b'\n' && class(self.pos + 1) == Some(TOKEN) =>
            {
                self.pos += 1;
                self.line = self.line.saturating_add(1);
                return true;
            }
            _ => {}
        }
        loop {
            if self.skip_blanks() {
                return true;
            }
            if !cross || !self.next_line() {
                return false;
            }
        }
    }

    /// Whether the byte at `i` ends a token for the fast paths (a `\` never does: the general
    /// path decides whether it continues the line).
    #[inline]
    fn ends_token(&self, i: usize) -> bool {
        self.text
            .as_bytes()
            .get(i)
            .is_none_or(|&c| matches!(CLASS[c as usize], BLANK | NEWLINE | COMMENT))
    }

    /// Fast path: the next token (across lines when `cross`) when it is 1 to 10 decimal digits,
    /// parsed as it is scanned, with its line. `None` for anything else, with the cursor at the
    /// token's start so that [`Scanner::token`] or [`Scanner::token_in_line`] returns it next
    /// for the general path (and its detailed errors).
    #[inline]
    pub(crate) fn digits(&mut self, cross: bool) -> Option<(u64, u32)> {
        if !self.seek(cross) {
            return None;
        }
        let b = self.text.as_bytes();
        let start = self.pos;
        let mut i = start;
        let mut v = 0u64;
        while let Some(d) = b.get(i).map(|c| c.wrapping_sub(b'0')).filter(|&d| d <= 9) {
            // Wraps only past 19 digits, which are refused below.
            v = v.wrapping_mul(10).wrapping_add(u64::from(d));
            i += 1;
        }
        if i == start || i - start > 10 || !self.ends_token(i) {
            return None;
        }
        self.pos = i;
        Some((v, self.line))
    }

    /// Fast path: the next token (across lines when `cross`) when it is a real number that
    /// [`real`] accepts, parsed straight from the text, with its line. `None` otherwise, with
    /// the cursor at the token's start (see [`Scanner::digits`]).
    #[inline]
    pub(crate) fn real(&mut self, cross: bool) -> Option<(f64, u32)> {
        if !self.seek(cross) {
            return None;
        }
        let b = &self.text.as_bytes()[self.pos..];
        let (x, n) = fast_float2::parse_partial::<f64, _>(b).ok()?;
        if !self.ends_token(self.pos + n) || !in_range(x, &b[..n]) {
            return None;
        }
        self.pos += n;
        Some((x, self.line))
    }

    /// The next token without consuming it.
    pub(crate) fn peek(&self) -> Option<(&'a str, u32)> {
        self.clone().token()
    }
}

// ---------------------------------------------------------------------------------------------
// Numbers.

/// Why a token is not a usable real number.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum RealError {
    /// Not a number at all.
    NotNumber,
    /// A finite number too large for `f64` (it would become infinite).
    Overflow,
    /// A non-zero number too small for `f64` (it would become 0).
    Underflow,
}

/// Parses a real number: decimal or scientific notation, or `nan`, `inf`, `infinity` (any
/// case, optionally signed). A finite number that `f64` can only hold as infinity or as 0 is an
/// error rather than a silent change; one that becomes subnormal keeps the nearest value.
#[inline]
pub(crate) fn real(tok: &[u8]) -> Result<f64, RealError> {
    let x: f64 = fast_float2::parse(tok).map_err(|_| RealError::NotNumber)?;
    checked_range(x, tok)
}

/// The floating-point type a format declares for its numbers (PLY `float`/`double`, VTK
/// `float`/`double`, STL's 32-bit floats): a number is refused when that type cannot hold it
/// as written, not only when `f64` cannot.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Float {
    F32,
    F64,
}

impl Float {
    /// The type's width in bits, for messages.
    pub(crate) fn bits(self) -> u32 {
        match self {
            Float::F32 => 32,
            Float::F64 => 64,
        }
    }
}

/// Parses a real number as [`real`] does, rounded to the declared type `ty` (one rounding,
/// from the decimal): a finite number that `ty` can only hold as infinity or as 0 (`1e39`,
/// `1e-50` as a 32-bit float) is an error; the value is returned widened to `f64` exactly.
#[inline]
pub(crate) fn real_as(tok: &[u8], ty: Float) -> Result<f64, RealError> {
    let x = match ty {
        Float::F64 => return real(tok),
        Float::F32 => {
            f64::from(fast_float2::parse::<f32, _>(tok).map_err(|_| RealError::NotNumber)?)
        }
    };
    checked_range(x, tok)
}

/// `x`, parsed from `tok`, when [`in_range`]; else why not: 0 from non-zero digits underflowed,
/// anything else overflowed.
#[inline]
fn checked_range(x: f64, tok: &[u8]) -> Result<f64, RealError> {
    if in_range(x, tok) {
        Ok(x)
    } else if x == 0.0 {
        Err(RealError::Underflow)
    } else {
        Err(RealError::Overflow)
    }
}

/// Whether `x`, parsed from `tok`, is what `tok` says: not infinite unless spelled so, not 0
/// unless its digits are.
#[inline]
fn in_range(x: f64, tok: &[u8]) -> bool {
    if x.is_infinite() {
        return tok.iter().any(|b| b.eq_ignore_ascii_case(&b'i'));
    }
    if x == 0.0 {
        let mantissa = tok.split(|b| b.eq_ignore_ascii_case(&b'e')).next();
        return !mantissa.is_some_and(|m| m.iter().any(|b| (b'1'..=b'9').contains(b)));
    }
    true
}

/// Parses a decimal integer with an optional sign.
#[inline]
pub(crate) fn integer(tok: &[u8]) -> Result<i128, IntError> {
    let (negative, digits) = match tok.first() {
        Some(b'-') => (true, &tok[1..]),
        Some(b'+') => (false, &tok[1..]),
        _ => (false, tok),
    };
    if digits.is_empty() || !digits.iter().all(u8::is_ascii_digit) {
        return Err(if fast_float2::parse::<f64, _>(tok).is_ok() {
            IntError::NotInteger
        } else {
            IntError::NotNumber
        });
    }
    let v = if digits.len() <= 18 {
        i128::from(digits_value(digits))
    } else {
        // Rare: long tokens (leading zeros, out-of-range values) take the checked path.
        let mut v: i128 = 0;
        for &d in digits {
            v = v
                .checked_mul(10)
                .and_then(|v| v.checked_add(i128::from(d - b'0')))
                .ok_or(IntError::OutOfRange)?;
        }
        v
    };
    Ok(if negative { -v } else { v })
}

/// The value of at most 18 decimal digits (cannot overflow).
#[inline]
fn digits_value(digits: &[u8]) -> u64 {
    digits
        .iter()
        .fold(0u64, |v, &d| v * 10 + u64::from(d - b'0'))
}

/// Parses a vertex id: 0-based, or 1-based when `one_based` (then converted to 0-based). The
/// common case (plain digits that fit) takes a short path; everything else gets the detailed
/// errors of [`super::parse_id`].
#[inline]
pub(crate) fn id(tok: &str, one_based: bool) -> Result<u32, ReadErrorKind> {
    let b = tok.as_bytes();
    if !b.is_empty() && b.len() <= 10 && b.iter().all(u8::is_ascii_digit) {
        let v = digits_value(b);
        let v = if one_based { v.wrapping_sub(1) } else { v };
        if let Ok(v) = u32::try_from(v) {
            return Ok(v);
        }
    }
    super::parse_id(tok, one_based)
}

/// A vertex id from the value of its digits (see [`Scanner::digits`]): 0-based, or 1-based when
/// `one_based`.
#[inline]
pub(crate) fn id_value(v: u64, one_based: bool) -> Result<u32, ReadErrorKind> {
    let id = if one_based { v.wrapping_sub(1) } else { v };
    u32::try_from(id).or_else(|_| super::parse_id(&v.to_string(), one_based))
}

/// Parses a real number where `what` was expected (e.g. "a vertex coordinate").
#[inline]
pub(crate) fn real_or_err(tok: &str, what: &str) -> Result<f64, ReadErrorKind> {
    real(tok.as_bytes()).map_err(|e| real_error(e, tok, what))
}

/// Parses a real number of the declared type `ty` where `what` was expected.
#[inline]
pub(crate) fn real_or_err_as(tok: &str, what: &str, ty: Float) -> Result<f64, ReadErrorKind> {
    real_as(tok.as_bytes(), ty).map_err(|e| real_error_as(e, tok, what, ty))
}

/// The message for a token that [`real`] refused.
pub(crate) fn real_error(e: RealError, tok: &str, what: &str) -> ReadErrorKind {
    real_error_as(e, tok, what, Float::F64)
}

/// The message for a token that [`real_as`] refused for the type `ty`.
pub(crate) fn real_error_as(e: RealError, tok: &str, what: &str, ty: Float) -> ReadErrorKind {
    let tok = echo(tok);
    let bits = ty.bits();
    syntax(match e {
        RealError::NotNumber => format!("non-numeric token '{tok}' where {what} was expected"),
        RealError::Overflow => format!(
            "number '{tok}' is too large for a {bits}-bit float ({what}; it would become infinite)"
        ),
        RealError::Underflow => format!(
            "number '{tok}' is too small for a {bits}-bit float ({what}; it would become 0)"
        ),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tokens(mut s: Scanner<'_>) -> Vec<(&str, u32)> {
        std::iter::from_fn(|| s.token()).collect()
    }

    #[test]
    fn line_ends_lf_crlf_and_lone_cr() {
        let s = Scanner::new("a\nb\r\nc\rd\r\re");
        assert_eq!(
            tokens(s),
            [("a", 1), ("b", 2), ("c", 3), ("d", 4), ("e", 6)]
        );
    }

    #[test]
    fn comments_blanks_and_token_bytes() {
        let s = Scanner::new("a b#c d\n \t\x0cx\x0by\u{a0}z #\n#\r\nq");
        assert_eq!(
            tokens(s),
            [("a", 1), ("b", 1), ("x\x0by\u{a0}z", 2), ("q", 4)]
        );
    }

    #[test]
    fn lines_one_at_a_time() {
        let mut s = Scanner::new("v 1 2\n\ns 0\n");
        assert_eq!(s.token_in_line(), Some(("v", 1)));
        assert_eq!(s.token_in_line(), Some(("1", 1)));
        s.skip_rest_of_line();
        assert_eq!(s.token_in_line(), None);
        assert!(s.next_line());
        assert_eq!(s.token_in_line(), None);
        assert!(s.next_line());
        assert_eq!(s.token_in_line(), Some(("s", 3)));
        assert_eq!(s.peek(), Some(("0", 3)));
        assert_eq!(s.token_in_line(), Some(("0", 3)));
        assert_eq!(s.token_in_line(), None);
        assert!(s.next_line());
        assert!(!s.next_line());
        assert_eq!(s.eof_line(), 3);
    }

    #[test]
    fn continuation() {
        let mut s = Scanner::with_continuation("f 1\\\n 2 \\ # c\r\n3\\4 \\\n\nx");
        let mut got = Vec::new();
        while let Some(t) = s.token_in_line() {
            got.push(t);
        }
        assert_eq!(got, [("f", 1), ("1", 1), ("2", 2), ("3\\4", 3)]);
        assert!(!s.dangling_continuation());
        // Without continuation a backslash is an ordinary byte.
        let s = Scanner::new("f 1\\\n2");
        assert_eq!(tokens(s), [("f", 1), ("1\\", 1), ("2", 2)]);
        let mut s = Scanner::with_continuation("f 1 \\\n");
        while s.token_in_line().is_some() {}
        assert!(s.dangling_continuation());
    }

    #[test]
    fn continuation_over_a_million_lines_is_linear() {
        let text = format!("l{}\n", " 1 \\\n".repeat(1_000_000));
        let mut s = Scanner::with_continuation(&text);
        let mut n = 0;
        while s.token_in_line().is_some() {
            n += 1;
        }
        assert_eq!(n, 1_000_001);
    }

    #[test]
    fn eof_line() {
        let mut s = Scanner::new("");
        assert_eq!((s.token(), s.eof_line()), (None, 1));
        let mut s = Scanner::new("# c\n\n");
        assert_eq!((s.token(), s.eof_line()), (None, 2));
        let mut s = Scanner::new("a\rb");
        s.token();
        assert_eq!(
            (s.token(), s.token(), s.eof_line()),
            (Some(("b", 2)), None, 2)
        );
    }

    #[test]
    fn reals() {
        assert_eq!(real(b"1.5e3"), Ok(1500.0));
        assert_eq!(real(b"-.5"), Ok(-0.5));
        assert_eq!(real(b"0e999"), Ok(0.0));
        assert_eq!(real(b"-0.000"), Ok(-0.0));
        assert!(real(b"NaN").unwrap().is_nan());
        assert_eq!(real(b"-Infinity"), Ok(f64::NEG_INFINITY));
        assert_eq!(real(b"1e309"), Err(RealError::Overflow));
        assert_eq!(real(b"-1e400"), Err(RealError::Overflow));
        assert_eq!(real(b"1e-400"), Err(RealError::Underflow));
        assert_eq!(real(b"0.0001e-330"), Err(RealError::Underflow));
        assert_eq!(real(b"4e-320"), Ok(4e-320)); // subnormal: kept
        assert_eq!(real(b"1.7976931348623157e308"), Ok(f64::MAX));
        for bad in [&b""[..], b"x", b"1.2.3", b"1e", b"--1", b"1 ", b"infinit"] {
            assert_eq!(real(bad), Err(RealError::NotNumber), "{bad:?}");
        }
    }

    #[test]
    fn reals_of_a_declared_32_bit_type() {
        let f = Float::F32;
        assert_eq!(real_as(b"1.5", f), Ok(1.5));
        assert_eq!(real_as(b"0.1", f), Ok(f64::from(0.1f32)));
        assert_eq!(real_as(b"3.4028235e38", f), Ok(f64::from(f32::MAX)));
        assert_eq!(real_as(b"1e39", f), Err(RealError::Overflow));
        assert_eq!(real_as(b"-1e39", f), Err(RealError::Overflow));
        assert_eq!(real_as(b"1e309", f), Err(RealError::Overflow));
        assert_eq!(real_as(b"1e-50", f), Err(RealError::Underflow));
        assert_eq!(real_as(b"1e-400", f), Err(RealError::Underflow));
        assert_eq!(real_as(b"1e-40", f), Ok(f64::from(1e-40f32))); // subnormal: kept
        assert_eq!(real_as(b"0e99", f), Ok(0.0));
        assert!(real_as(b"nan", f).unwrap().is_nan());
        assert_eq!(real_as(b"-inf", f), Ok(f64::NEG_INFINITY));
        assert_eq!(real_as(b"x", f), Err(RealError::NotNumber));
        // The 64-bit type is `real`.
        assert_eq!(real_as(b"1e39", Float::F64), Ok(1e39));
        assert_eq!(real_as(b"1e-400", Float::F64), Err(RealError::Underflow));
        let msg = real_error_as(RealError::Underflow, "1e-50", "a vertex coordinate", f);
        assert!(
            msg.to_string().contains("too small for a 32-bit float"),
            "{msg}"
        );
    }

    #[test]
    fn integers_and_ids() {
        assert_eq!(integer(b"+7"), Ok(7));
        assert_eq!(integer(b"-12"), Ok(-12));
        assert_eq!(integer(&[b'0'; 40]), Ok(0));
        assert_eq!(integer(b"1e3"), Err(IntError::NotInteger));
        assert_eq!(integer(b"-"), Err(IntError::NotNumber));
        assert_eq!(
            integer("9".repeat(50).as_bytes()),
            Err(IntError::OutOfRange)
        );
        assert_eq!(id("4294967295", false), Ok(u32::MAX));
        assert_eq!(id("4294967296", true), Ok(u32::MAX));
        assert!(id("4294967296", false).is_err());
        assert!(id("0", true).is_err());
        assert_eq!(id("0001", true), Ok(0));
    }

    #[test]
    fn fast_paths_leave_other_tokens_to_the_general_path() {
        let mut s = Scanner::new("12 \n 4294967296 99999999999 1.5e3 1e309 7x 3#c\n-1");
        assert_eq!(s.digits(true), Some((12, 1)));
        assert_eq!(s.digits(false), None);
        assert_eq!(s.digits(true), Some((4294967296, 2)));
        assert_eq!(s.digits(true), None);
        assert_eq!(s.token(), Some(("99999999999", 2)));
        assert_eq!(s.digits(true), None);
        assert_eq!(s.real(true), Some((1500.0, 2)));
        assert_eq!(s.real(true), None);
        assert_eq!(s.token(), Some(("1e309", 2)));
        assert_eq!(s.real(true), None);
        assert_eq!(s.token(), Some(("7x", 2)));
        assert_eq!(s.real(false), Some((3.0, 2)));
        assert_eq!(s.digits(false), None);
        assert_eq!(s.real(true), Some((-1.0, 3)));
        assert_eq!(s.real(true), None);
        // A backslash that may continue the line is left to the general path.
        let mut s = Scanner::with_continuation("1\\\n2");
        assert_eq!(s.digits(false), None);
        assert_eq!(s.token_in_line(), Some(("1", 1)));
        assert_eq!(s.digits(false), Some((2, 2)));
    }
}
