//! Readers: one module per file format, parsing only.
//!
//! A reader turns bytes into a [`RawInput`]: a vertex count, optional coordinates and a list of
//! simplices with the line each came from. It checks syntax (numbers, counts, headers, polygons
//! that are not simplices, negative ids) but no topology: repeated vertices, ids out of range,
//! duplicates and faces of other simplices are the complex model's business
//! ([`crate::complex::Complex::from_raw`]), which reports them with the same file and line.
//!
//! The format is chosen by file extension: `.off`, `.obj`, `.mesh`, `.simplices`, `.ply`, `.stl`,
//! `.vtk`, `.vtu`, `.msh`.
//! The writers ([`write`]) are their inverse.

use std::path::{Path, PathBuf};

/// The helpers every reader's unit tests share, bound to the calling module's `parse`: `ok`
/// (parse or panic), `err` (an error on the given line whose message contains a needle) and
/// `simplices` (the parsed simplices as vectors).
#[cfg(test)]
macro_rules! reader_test_helpers {
    () => {
        fn ok(text: &str) -> RawInput {
            parse(text).unwrap_or_else(|e| panic!("unexpected error {e:?}"))
        }

        fn err(text: &str, line: u32, needle: &str) {
            match parse(text) {
                Ok(r) => panic!("expected an error, got {r:?}"),
                Err((l, k)) => {
                    let msg = k.to_string();
                    assert_eq!(l, line, "wrong line for error '{msg}'");
                    assert!(msg.contains(needle), "message '{msg}' lacks '{needle}'");
                }
            }
        }

        fn simplices(r: &RawInput) -> Vec<Vec<u32>> {
            (0..r.simplex_count())
                .map(|i| r.simplex(i).to_vec())
                .collect()
        }
    };
}

mod bytes;
pub mod medit;
pub mod msh;
pub mod obj;
pub mod off;
pub mod ply;
pub mod simplices;
pub mod stl;
pub mod vtk;
pub mod vtu;
pub mod write;

/// Vertex coordinates, `dim` numbers per vertex, vertex-major.
#[derive(Debug, Clone, PartialEq)]
pub struct Coords {
    pub dim: usize,
    pub data: Vec<f64>,
}

/// What a reader produced: unvalidated simplices over 0-based vertex ids.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct RawInput {
    /// Number of vertices the file declares. `None` only for a `.simplices` file without `v`
    /// lines, where the vertices are `0..=max id`.
    pub vertex_count: Option<u32>,
    /// Coordinates of the declared vertices, when the format carries them.
    pub coords: Option<Coords>,
    /// Simplex vertex ids, concatenated; simplex `i` is `ids[offsets[i]..offsets[i + 1]]`
    /// (so `offsets` has one more entry than there are simplices and starts with 0).
    pub ids: Vec<u32>,
    pub offsets: Vec<usize>,
    /// 1-based line of each simplex in the file (0 when not from a file).
    pub lines: Vec<u32>,
}

impl RawInput {
    pub fn new() -> Self {
        RawInput {
            offsets: vec![0],
            ..Default::default()
        }
    }

    /// Appends one simplex read on `line`.
    pub fn push(&mut self, ids: &[u32], line: u32) {
        self.ids.extend_from_slice(ids);
        self.offsets.push(self.ids.len());
        self.lines.push(line);
    }

    pub fn simplex_count(&self) -> usize {
        self.offsets.len() - 1
    }

    pub fn simplex(&self, i: usize) -> &[u32] {
        &self.ids[self.offsets[i]..self.offsets[i + 1]]
    }
}

/// What was wrong, without the location ([`ReadError`] adds file and line).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ReadErrorKind {
    #[error("cannot read file: {0}")]
    Io(String),
    #[error(
        "unknown file extension (expected .off, .obj, .mesh, .simplices, .ply, .stl, .vtk or .msh)"
    )]
    UnknownExtension,
    #[error("{0}")]
    Syntax(String),
    #[error("polygon with {0} vertices is not a simplex")]
    Polygon(usize),
    #[error("negative vertex id {0}")]
    NegativeId(i64),
}

/// A reader error naming the file and the 1-based line (line 0: the file as a whole).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{}:{line}: {kind}", path.display())]
pub struct ReadError {
    pub path: PathBuf,
    pub line: u32,
    pub kind: ReadErrorKind,
}

/// Reads a file, choosing the reader by extension.
pub fn read_path(path: &Path) -> Result<RawInput, ReadError> {
    let err = |line, kind| ReadError {
        path: path.to_path_buf(),
        line,
        kind,
    };
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .map(|e| e.to_ascii_lowercase())
        .unwrap_or_default();
    let parse: fn(&str) -> Result<RawInput, (u32, ReadErrorKind)> = match ext.as_str() {
        "off" => off::parse,
        "obj" => obj::parse,
        "mesh" => medit::parse,
        "simplices" => simplices::parse,
        _ => return read_binary_capable(path, &ext),
    };
    let bytes = std::fs::read(path).map_err(|e| err(0, ReadErrorKind::Io(e.to_string())))?;
    let text = std::str::from_utf8(&bytes).map_err(|e| {
        let line = bytes[..e.valid_up_to()]
            .iter()
            .filter(|&&b| b == b'\n')
            .count() as u32
            + 1;
        err(
            line,
            ReadErrorKind::Syntax("file is not valid UTF-8 text".into()),
        )
    })?;
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    parse(text).map_err(|(line, kind)| err(line, kind))
}

/// A reader of bytes: the simplices, or the line (0: unknown) and what is wrong.
type ByteParser = fn(&[u8]) -> Result<RawInput, (u32, ReadErrorKind)>;

/// The readers of formats with a binary variant, which parse bytes rather than text.
fn read_binary_capable(path: &Path, ext: &str) -> Result<RawInput, ReadError> {
    let err = |line, kind| ReadError {
        path: path.to_path_buf(),
        line,
        kind,
    };
    let parse: ByteParser = match ext {
        "ply" => ply::parse,
        "stl" => stl::parse,
        "vtk" => vtk::parse,
        "vtu" => vtu::parse,
        "msh" => msh::parse,
        _ => return Err(err(0, ReadErrorKind::UnknownExtension)),
    };
    let bytes = std::fs::read(path).map_err(|e| err(0, ReadErrorKind::Io(e.to_string())))?;
    parse(&bytes).map_err(|(line, kind)| err(line, kind))
}

// ---------------------------------------------------------------------------------------------
// Helpers shared by the readers.

/// Shorthand for a syntax error.
pub(crate) fn syntax(msg: impl Into<String>) -> ReadErrorKind {
    ReadErrorKind::Syntax(msg.into())
}

/// Caps a capacity taken from a count declared in the file by what the text could hold (every
/// number needs at least one character and one separator), so that a huge declared count in a
/// small file does not allocate.
pub(crate) fn capped(n: usize, text: &str) -> usize {
    n.min(text.len() / 2 + 1)
}

/// Whitespace-separated tokens, each with its 1-based line. `#` starts a comment that runs to
/// the end of its line. Lines end in `\n` or `\r\n`; spaces, tabs and stray `\r` separate tokens.
pub(crate) struct Tokens<'a> {
    lines: std::str::Lines<'a>,
    words: std::str::SplitAsciiWhitespace<'a>,
    line: u32,
    peeked: Option<Option<(&'a str, u32)>>,
}

impl<'a> Tokens<'a> {
    pub(crate) fn new(text: &'a str) -> Self {
        Tokens {
            lines: text.lines(),
            words: "".split_ascii_whitespace(),
            line: 0,
            peeked: None,
        }
    }

    fn advance(&mut self) -> Option<(&'a str, u32)> {
        loop {
            if let Some(w) = self.words.next() {
                return Some((w, self.line));
            }
            let l = self.lines.next()?;
            self.line = self.line.saturating_add(1);
            self.words = strip_comment(l).split_ascii_whitespace();
        }
    }

    pub(crate) fn peek(&mut self) -> Option<(&'a str, u32)> {
        if self.peeked.is_none() {
            self.peeked = Some(self.advance());
        }
        self.peeked.unwrap()
    }

    /// Consumes and returns the tokens left on `line`.
    pub(crate) fn rest_of_line(&mut self, line: u32) -> Vec<(&'a str, u32)> {
        let mut out = Vec::new();
        while let Some(tok) = self.peek().filter(|&(_, l)| l == line) {
            out.push(tok);
            self.next();
        }
        out
    }

    /// The line to blame when the file ends early: its last line (at least 1). Meaningful once
    /// [`Iterator::next`] has returned `None`.
    pub(crate) fn eof_line(&self) -> u32 {
        self.line.max(1)
    }
}

impl<'a> Iterator for Tokens<'a> {
    type Item = (&'a str, u32);

    fn next(&mut self) -> Option<(&'a str, u32)> {
        match self.peeked.take() {
            Some(p) => p,
            None => self.advance(),
        }
    }
}

/// The part of a line before any `#`.
pub(crate) fn strip_comment(line: &str) -> &str {
    line.find('#').map_or(line, |i| &line[..i])
}

/// Why a token is not an integer.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum IntError {
    /// Not a number at all.
    NotNumber,
    /// A number, but not an integer (`1.5`, `1e3`, `nan`).
    NotInteger,
    /// An integer too large even for `i128`.
    OutOfRange,
}

/// Parses a decimal integer with an optional sign.
pub(crate) fn parse_integer(tok: &str) -> Result<i128, IntError> {
    let digits = tok.strip_prefix(['+', '-']).unwrap_or(tok);
    if !digits.is_empty() && digits.bytes().all(|b| b.is_ascii_digit()) {
        tok.parse::<i128>().map_err(|_| IntError::OutOfRange)
    } else if tok.parse::<f64>().is_ok() {
        Err(IntError::NotInteger)
    } else {
        Err(IntError::NotNumber)
    }
}

/// Parses a vertex id: 0-based, or 1-based when `one_based` (then converted to 0-based).
/// Negative values are [`ReadErrorKind::NegativeId`] with the value as written.
pub(crate) fn parse_id(tok: &str, one_based: bool) -> Result<u32, ReadErrorKind> {
    let v = match parse_integer(tok) {
        Ok(v) => v,
        Err(IntError::NotNumber) => {
            return Err(syntax(format!(
                "non-numeric token '{tok}' where a vertex id was expected"
            )));
        }
        Err(IntError::NotInteger) => {
            return Err(syntax(format!("vertex id '{tok}' is not an integer")));
        }
        Err(IntError::OutOfRange) if tok.starts_with('-') => {
            return Err(syntax(format!("negative vertex id {tok}")));
        }
        Err(IntError::OutOfRange) => {
            return Err(syntax(format!("vertex id {tok} does not fit in 32 bits")));
        }
    };
    if v < 0 {
        return Err(match i64::try_from(v) {
            Ok(v) => ReadErrorKind::NegativeId(v),
            Err(_) => syntax(format!("negative vertex id {tok}")),
        });
    }
    let v = if one_based {
        if v == 0 {
            return Err(syntax(
                "vertex id 0 is invalid: ids in this format start at 1",
            ));
        }
        v - 1
    } else {
        v
    };
    u32::try_from(v).map_err(|_| syntax(format!("vertex id {tok} does not fit in 32 bits")))
}

/// Parses a count declared in the file (`what` names it, e.g. "vertex count"): a non-negative
/// integer that fits in 32 bits.
pub(crate) fn parse_count(tok: &str, what: &str) -> Result<u32, ReadErrorKind> {
    match parse_integer(tok) {
        Ok(v) if v < 0 => Err(syntax(format!("{what} {tok} is negative"))),
        Ok(v) => {
            u32::try_from(v).map_err(|_| syntax(format!("{what} {tok} does not fit in 32 bits")))
        }
        Err(IntError::OutOfRange) if tok.starts_with('-') => {
            Err(syntax(format!("{what} {tok} is negative")))
        }
        Err(IntError::OutOfRange) => Err(syntax(format!("{what} {tok} does not fit in 32 bits"))),
        Err(IntError::NotInteger) => Err(syntax(format!("{what} '{tok}' is not an integer"))),
        Err(IntError::NotNumber) => Err(syntax(format!(
            "non-numeric token '{tok}' where the {what} was expected"
        ))),
    }
}

/// Parses a floating-point number (`what` names it, e.g. "a vertex coordinate"). `nan`, `inf`
/// and `infinity` (any case, optionally signed) are accepted.
pub(crate) fn parse_f64(tok: &str, what: &str) -> Result<f64, ReadErrorKind> {
    tok.parse::<f64>().map_err(|_| {
        syntax(format!(
            "non-numeric token '{tok}' where {what} was expected"
        ))
    })
}

/// Checks that a token is an integer (`what` names it, e.g. "reference number"); its value is
/// not used.
pub(crate) fn check_integer(tok: &str, what: &str) -> Result<(), ReadErrorKind> {
    match parse_integer(tok) {
        Ok(_) | Err(IntError::OutOfRange) => Ok(()),
        Err(IntError::NotInteger) => Err(syntax(format!("{what} '{tok}' is not an integer"))),
        Err(IntError::NotNumber) => Err(syntax(format!(
            "non-numeric token '{tok}' where a {what} was expected"
        ))),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A file under the temp dir, removed on drop.
    struct TempFile(PathBuf);

    impl TempFile {
        fn new(name: &str, bytes: &[u8]) -> TempFile {
            let path = std::env::temp_dir()
                .join(format!("topoplex-io-test-{}-{name}", std::process::id()));
            std::fs::write(&path, bytes).unwrap();
            TempFile(path)
        }
    }

    impl Drop for TempFile {
        fn drop(&mut self) {
            let _ = std::fs::remove_file(&self.0);
        }
    }

    #[test]
    fn dispatch_by_extension() {
        let cases: [(&str, &[u8]); 5] = [
            ("a.off", b"OFF\n2 1 0\n0 0 0\n1 0 0\n2 0 1\n"),
            ("a.OBJ", b"v 0 0 0\nv 1 0 0\nl 1 2\n"),
            (
                "a.mesh",
                b"MeshVersionFormatted 1\nDimension 3\nEdges 1\n1 2 0\n",
            ),
            ("a.simplices", b"s 0 1\n"),
            ("bom.simplices", "\u{feff}s 0 1\n".as_bytes()),
        ];
        for (name, bytes) in cases {
            let f = TempFile::new(name, bytes);
            let r = read_path(&f.0).unwrap_or_else(|e| panic!("{name}: {e}"));
            assert_eq!(r.simplex(0), [0, 1], "{name}");
        }
    }

    #[test]
    fn errors_name_file_and_line() {
        let f = TempFile::new("bad.off", b"OFF\n1 1 0\n0 0 0\n4 0 0 0 0\n");
        let e = read_path(&f.0).unwrap_err();
        assert_eq!((e.line, &e.kind), (4, &ReadErrorKind::Polygon(4)));
        assert!(
            e.to_string()
                .ends_with("bad.off:4: polygon with 4 vertices is not a simplex")
        );
    }

    #[test]
    fn unknown_extension_and_missing_file() {
        let e = read_path(Path::new("x.ply")).unwrap_err();
        assert_eq!((e.line, e.kind), (0, ReadErrorKind::UnknownExtension));
        let e = read_path(Path::new("no-such-dir-topoplex/x.off")).unwrap_err();
        assert!(matches!(e.kind, ReadErrorKind::Io(_)));
    }

    #[test]
    fn invalid_utf8() {
        let f = TempFile::new("latin1.simplices", b"s 0 1\n# caf\xe9\ns 1 2\n");
        let e = read_path(&f.0).unwrap_err();
        assert_eq!(e.line, 2);
        assert_eq!(
            e.kind,
            ReadErrorKind::Syntax("file is not valid UTF-8 text".into())
        );
    }

    #[test]
    fn tokens_track_lines() {
        let mut t = Tokens::new("a b # c\r\n\n\td\te\nf");
        assert_eq!(t.peek(), Some(("a", 1)));
        assert_eq!(t.rest_of_line(1), [("a", 1), ("b", 1)]);
        assert_eq!(t.collect::<Vec<_>>(), [("d", 3), ("e", 3), ("f", 4)]);
    }

    #[test]
    fn number_helpers() {
        assert_eq!(parse_integer("+7"), Ok(7));
        assert_eq!(parse_integer("1e3"), Err(IntError::NotInteger));
        assert_eq!(parse_integer("-"), Err(IntError::NotNumber));
        assert_eq!(parse_integer(&"9".repeat(50)), Err(IntError::OutOfRange));
        assert!(parse_id(&format!("-{}", "9".repeat(50)), false).is_err());
        assert_eq!(parse_id("5", true), Ok(4));
        assert_eq!(capped(usize::MAX, "abcd"), 3);
    }
}
