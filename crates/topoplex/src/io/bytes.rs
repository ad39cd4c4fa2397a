//! A byte cursor for readers of formats that mix text and binary blocks (VTK, Gmsh): tokens
//! with their 1-based lines, whole lines, and raw bytes.

use super::{parse_integer, syntax};
use crate::io::Res;

/// A byte cursor that tracks lines.
pub(crate) struct Input<'a> {
    pub(crate) b: &'a [u8],
    pub(crate) pos: usize,
    pub(crate) line: u32,
    pub(crate) binary: bool,
}

impl<'a> Input<'a> {
    /// A cursor at the start of `b`, line 1, in text mode.
    pub(crate) fn new(b: &'a [u8]) -> Self {
        Input {
            b,
            pos: 0,
            line: 1,
            binary: false,
        }
    }

    pub(crate) fn skip_space(&mut self) {
        while let Some(&c) = self.b.get(self.pos) {
            if c == b'\n' {
                self.line = self.line.saturating_add(1);
            } else if !c.is_ascii_whitespace() {
                break;
            }
            self.pos += 1;
        }
    }

    /// The next whitespace-separated token and its line.
    pub(crate) fn token(&mut self) -> Option<(&'a str, u32)> {
        self.skip_space();
        let start = self.pos;
        while self
            .b
            .get(self.pos)
            .is_some_and(|c| !c.is_ascii_whitespace())
        {
            self.pos += 1;
        }
        (self.pos > start).then(|| {
            // Non-UTF-8 bytes make a token no keyword or number matches.
            let t = std::str::from_utf8(&self.b[start..self.pos]).unwrap_or("\u{fffd}");
            (t, self.line)
        })
    }

    pub(crate) fn expect_token(&mut self, what: &str) -> Res<(&'a str, u32)> {
        self.token().ok_or_else(|| {
            (
                self.line.max(1),
                syntax(format!("file ends early; expected {what}")),
            )
        })
    }

    /// The rest of the current line (without the newline), consuming it.
    pub(crate) fn rest_of_line(&mut self) -> &'a [u8] {
        let start = self.pos;
        while self.b.get(self.pos).is_some_and(|&c| c != b'\n') {
            self.pos += 1;
        }
        let s = &self.b[start..self.pos];
        if self.pos < self.b.len() {
            self.pos += 1;
            self.line = self.line.saturating_add(1);
        }
        s
    }

    /// Bytes not yet consumed.
    pub(crate) fn left(&self) -> usize {
        self.b.len() - self.pos
    }

    /// The next `n` bytes, consumed; `None` (nothing consumed) if fewer are left.
    pub(crate) fn take(&mut self, n: usize) -> Option<&'a [u8]> {
        let s = self.b.get(self.pos..self.pos.checked_add(n)?)?;
        self.pos += n;
        Some(s)
    }

    /// A count after a keyword.
    pub(crate) fn count(&mut self, keyword: &str) -> Res<usize> {
        let (tok, l) = self.expect_token(&format!("the count after {keyword}"))?;
        match parse_integer(tok) {
            Ok(v) if v >= 0 => usize::try_from(v)
                .map_err(|_| (l, syntax(format!("{keyword} count {tok} is too large")))),
            _ => Err((
                l,
                syntax(format!(
                    "{keyword} count '{tok}' is not a non-negative integer"
                )),
            )),
        }
    }
}
