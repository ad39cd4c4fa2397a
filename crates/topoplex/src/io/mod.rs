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
//! The writers ([`mod@write`]) are their inverse.

use std::path::Path;

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
pub(crate) mod chunked;
pub mod medit;
pub mod msh;
pub mod obj;
pub mod off;
pub(crate) mod plain;
pub mod ply;
mod scan;
pub(crate) use scan::Float;
pub mod simplices;
pub mod stl;
pub mod triangulate;
pub mod vtk;
pub mod vtu;
pub mod write;

use crate::complex::table;
use crate::complex::{Budget, Complex, ComplexError};
pub use crate::complex::{Coords, RawInput};
use crate::error::echo;
pub(crate) use crate::error::no_room;
pub use crate::error::{ReadError, ReadErrorKind};

// Reading into a complex is io's (the model below knows no files), as pmp's and
// geometry-central's readers fill a mesh they include.
impl Complex {
    /// Reads and normalises a file (format by extension), under the default [`Budget`].
    pub fn from_path(path: &Path) -> Result<Complex, ComplexError> {
        Complex::from_path_with(path, Budget::default())
    }

    /// Reads and normalises a file (format by extension) under `budget`.
    pub fn from_path_with(path: &Path, budget: Budget) -> Result<Complex, ComplexError> {
        Complex::from_path_options(path, budget, ReadOptions::default())
    }

    /// Reads (with `options`) and normalises a file (format by extension) under `budget`.
    pub fn from_path_options(
        path: &Path,
        budget: Budget,
        options: ReadOptions,
    ) -> Result<Complex, ComplexError> {
        let raw = read_path_with(path, options)?;
        Complex::from_input(raw, Some(path), budget)
    }
}

/// How to read a file beyond its format.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct ReadOptions {
    /// Fan every convex planar polygon into triangles (CLI `--triangulate`): faces of more than
    /// 3 vertices in OFF, OBJ and PLY, polygon (7) and quad (9) cells in legacy VTK, Gmsh
    /// quadrangles; a polygon
    /// that is not convex and planar is refused with the reason ([`triangulate`]). Without it
    /// polygons are refused ([`ReadErrorKind::Polygon`]). Other formats read as without it.
    pub triangulate: bool,
}

/// [`read_path`] with `options`.
pub fn read_path_with(path: &Path, options: ReadOptions) -> Result<RawInput, ReadError> {
    if !options.triangulate {
        return read_path(path);
    }
    let err = error_at(path);
    let ext = extension(path);
    let raw = match ext.as_str() {
        "off" | "obj" => {
            let bytes = read_file(path).map_err(|k| err(0, k))?;
            let text = utf8_text(&bytes).map_err(|(line, k)| err(line, k))?;
            match ext.as_str() {
                "off" => off::parse_keeping(text, true),
                _ => obj::parse_keeping(text, true),
            }
        }
        "ply" | "vtk" | "msh" => {
            let bytes = read_file(path).map_err(|k| err(0, k))?;
            match ext.as_str() {
                "ply" => ply::parse_keeping(&bytes, true),
                "vtk" => vtk::parse_keeping(&bytes, true),
                _ => msh::parse_keeping(&bytes, true),
            }
        }
        _ => return read_path(path),
    };
    raw.and_then(triangulate::fan_polygons)
        .map_err(|(line, kind)| err(line, kind))
}

/// Reads a file, choosing the reader by extension.
///
/// Only regular files are read (see [`read_file`]); the text must be UTF-8 (a leading
/// byte-order mark is skipped). Peak memory: the file's bytes plus the reader's output; a
/// `.simplices` file of 32 MiB or more is read in blocks of about 8 MiB (twice: counted, then
/// parsed into arrays of their exact size), so its peak is the output and one block.
pub fn read_path(path: &Path) -> Result<RawInput, ReadError> {
    let err = error_at(path);
    let ext = extension(path);
    let parse: fn(&str) -> Result<RawInput, (u32, ReadErrorKind)> = match ext.as_str() {
        "off" => off::parse,
        "obj" => obj::parse,
        "mesh" => medit::parse,
        "simplices" => simplices::parse,
        _ => return read_binary_capable(path, &ext),
    };
    #[cfg(unix)]
    if ext == "simplices"
        && std::fs::metadata(path).is_ok_and(|m| m.is_file() && m.len() >= simplices::BLOCKS_FROM)
        && let Some(raw) = simplices::read_in_blocks(path)
    {
        return Ok(raw);
    }
    let bytes = read_file(path).map_err(|k| err(0, k))?;
    let text = utf8_text(&bytes).map_err(|(line, k)| err(line, k))?;
    parse(text).map_err(|(line, kind)| err(line, kind))
}

/// Reads a whole regular file with one read into a buffer of its size.
///
/// Anything else is refused before it is read, with a message saying what it is: a directory,
/// a named pipe (which would block until a writer comes), a device such as `/dev/zero` or
/// `/dev/urandom` (which never ends), a socket. The type is checked on the path before opening
/// and again on the opened file (the path may change in between); the open is non-blocking so
/// that a pipe swapped in meanwhile cannot hang it. A buffer that cannot be allocated is
/// [`ReadErrorKind::TooLarge`].
pub fn read_file(path: &Path) -> Result<Vec<u8>, ReadErrorKind> {
    use std::io::Read;
    let io = |e: std::io::Error| ReadErrorKind::Io(e.to_string());
    let (mut file, meta) = open_regular(path).map_err(io)?;
    let too_large =
        || ReadErrorKind::TooLarge(format!("{} bytes do not fit in memory", meta.len()));
    let len = usize::try_from(meta.len()).map_err(|_| too_large())?;
    let mut bytes = Vec::new();
    // One byte more than the size, so that read_to_end sees the end without growing the buffer.
    bytes
        .try_reserve_exact(len.saturating_add(1))
        .map_err(|_| too_large())?;
    #[cfg(unix)]
    if read_in_parallel(&file, len, &mut bytes) {
        return Ok(bytes);
    }
    file.read_to_end(&mut bytes).map_err(io)?;
    Ok(bytes)
}

/// Reads the `len` bytes of a large file into `bytes` (empty, capacity reserved) as ranges
/// read on [`crate::parallel::threads`] threads at their offsets (the kernel's copy and the
/// buffer's page faults are most of reading a file in the page cache). False, with `bytes`
/// emptied, when it runs serially or anything differs from a plain read (a read error, a file
/// that shrank or grew meanwhile): the caller then reads it in one go.
#[cfg(unix)]
fn read_in_parallel(file: &std::fs::File, len: usize, bytes: &mut Vec<u8>) -> bool {
    use rayon::prelude::*;
    use std::os::unix::fs::FileExt;
    // From 1 MiB (at the default split threshold).
    if !crate::parallel::splits(len / 16) {
        return false;
    }
    let piece = len.div_ceil(4 * crate::parallel::threads()).max(4096);
    chunked::extend_filled(bytes, len, 0);
    let read = crate::parallel::install(|| {
        bytes
            .par_chunks_mut(piece)
            .enumerate()
            .all(|(k, part)| file.read_exact_at(part, (k * piece) as u64).is_ok())
    });
    // Nothing after the size read (the file did not grow).
    if read && matches!(file.read_at(&mut [0u8; 1], len as u64), Ok(0)) {
        return true;
    }
    bytes.clear();
    false
}

/// Refuses anything but a regular file, naming what it is.
/// Refuses an output path that exists and is not a regular file — a device such as `/dev/full`
/// or `/dev/null`, a named pipe (which would block), a socket, a directory — before anything is
/// created beside it or written to it: the writers and `save` never replace or feed what they do
/// not own. A symbolic link is followed (a link to a regular file is written through); a path
/// that does not exist yet is fine.
pub fn check_output(path: &Path) -> std::io::Result<()> {
    match std::fs::metadata(path) {
        Ok(meta) => only_regular(&meta, "outputs are only written to regular files"),
        Err(_) => Ok(()),
    }
}

/// Opens a regular file for reading, refusing anything else before it is read, with a message
/// saying what it is: a directory, a named pipe (which would block until a writer comes), a
/// device such as `/dev/zero` (which never ends), a socket. The type is checked on the path
/// before opening and again on the opened file (the path may change in between); the open is
/// non-blocking so that a pipe swapped in meanwhile cannot hang it. Used by every reader and by
/// [`crate::store::Saved::open`].
pub fn open_regular(path: &Path) -> std::io::Result<(std::fs::File, std::fs::Metadata)> {
    check_regular(&std::fs::metadata(path)?)?;
    let mut options = std::fs::OpenOptions::new();
    options.read(true);
    #[cfg(unix)]
    {
        use std::os::unix::fs::OpenOptionsExt;
        options.custom_flags(libc::O_NONBLOCK);
    }
    let file = options.open(path)?;
    let meta = file.metadata()?;
    check_regular(&meta)?;
    Ok((file, meta))
}

fn check_regular(meta: &std::fs::Metadata) -> std::io::Result<()> {
    only_regular(meta, "only regular files are read")
}

/// `Ok` for a regular file, else an error saying what it is, with `why` in brackets.
fn only_regular(meta: &std::fs::Metadata, why: &str) -> std::io::Result<()> {
    let t = meta.file_type();
    if t.is_file() {
        return Ok(());
    }
    let what = if t.is_dir() {
        "a directory"
    } else {
        special_file_kind(&t)
    };
    Err(std::io::Error::new(
        std::io::ErrorKind::InvalidInput,
        format!("it is {what}, not a regular file ({why})"),
    ))
}

#[cfg(unix)]
fn special_file_kind(t: &std::fs::FileType) -> &'static str {
    use std::os::unix::fs::FileTypeExt;
    if t.is_fifo() {
        "a named pipe"
    } else if t.is_char_device() {
        "a character device (such as /dev/zero)"
    } else if t.is_block_device() {
        "a block device"
    } else if t.is_socket() {
        "a socket"
    } else {
        "a special file"
    }
}

#[cfg(not(unix))]
fn special_file_kind(_: &std::fs::FileType) -> &'static str {
    "a special file"
}

/// The file's bytes as text: UTF-8, a leading byte-order mark skipped. The error names the line
/// of the first invalid byte and shows the bytes, escaped.
fn utf8_text(bytes: &[u8]) -> Result<&str, (u32, ReadErrorKind)> {
    let text = std::str::from_utf8(bytes).map_err(|e| {
        let at = e.valid_up_to();
        let before = &bytes[..at];
        let line = before.iter().filter(|&&b| b == b'\n').count()
            + before
                .windows(2)
                .filter(|w| w[0] == b'\r' && w[1] != b'\n')
                .count()
            + usize::from(before.last() == Some(&b'\r'));
        let bad = &bytes[at..bytes.len().min(at + e.error_len().unwrap_or(1))];
        (
            u32::try_from(line + 1).unwrap_or(u32::MAX),
            syntax(format!(
                "file is not valid UTF-8 text (bad bytes '{}')",
                echo(bad)
            )),
        )
    })?;
    Ok(text.strip_prefix('\u{feff}').unwrap_or(text))
}

/// The path's extension in lower case ("" without one): what chooses the reader.
pub(crate) fn extension(path: &Path) -> String {
    path.extension()
        .and_then(|e| e.to_str())
        .map(|e| e.to_ascii_lowercase())
        .unwrap_or_default()
}

/// A reader's (line, what) as the [`ReadError`] of `path`.
fn error_at(path: &Path) -> impl Fn(u32, ReadErrorKind) -> ReadError + '_ {
    move |line, kind| ReadError {
        path: path.to_path_buf(),
        line,
        kind,
    }
}

/// A reader of bytes: the simplices, or the line (0: unknown) and what is wrong.
type ByteParser = fn(&[u8]) -> Result<RawInput, (u32, ReadErrorKind)>;

/// The readers of formats with a binary variant, which parse bytes rather than text.
fn read_binary_capable(path: &Path, ext: &str) -> Result<RawInput, ReadError> {
    let err = error_at(path);
    let parse: ByteParser = match ext {
        "ply" => ply::parse,
        "stl" => stl::parse,
        "vtk" => vtk::parse,
        "vtu" => vtu::parse,
        "msh" => msh::parse,
        _ => return Err(err(0, ReadErrorKind::UnknownExtension)),
    };
    let bytes = read_file(path).map_err(|k| err(0, k))?;
    parse(&bytes).map_err(|(line, kind)| err(line, kind))
}

// ---------------------------------------------------------------------------------------------
// Helpers shared by the readers.

/// A reader's result: an error carries the line it names.
pub(crate) type Res<T> = Result<T, (u32, ReadErrorKind)>;

/// A format's type codes of the four simplices (vertex, edge, triangle, tetrahedron), one
/// table that both the writer (size to code) and the reader (code to size) use.
pub(crate) struct SimplexCodes(pub(crate) [i64; 4]);

impl SimplexCodes {
    /// The code of a simplex of `len` vertices: the tetrahedron's for any size outside 1..=3.
    pub(crate) fn of_len(&self, len: usize) -> i64 {
        match len {
            1..=3 => self.0[len - 1],
            _ => self.0[3],
        }
    }

    /// The vertex count of the simplex whose code is `code`, if it is one of the four.
    pub(crate) fn len_of(&self, code: i64) -> Option<usize> {
        self.0.iter().position(|&c| c == code).map(|i| i + 1)
    }
}

/// Shorthand for a syntax error.
pub(crate) fn syntax(msg: impl Into<String>) -> ReadErrorKind {
    ReadErrorKind::Syntax(msg.into())
}

/// A `Vec` of `n` elements' capacity reserved fallibly ([`ReadErrorKind::TooLarge`] naming
/// `what`); `n` comes from a declared count capped by what the file could hold ([`capped`]).
pub(crate) fn try_with_capacity<T>(n: usize, what: &'static str) -> Result<Vec<T>, ReadErrorKind> {
    let mut v = Vec::new();
    table::try_reserve_exact(&mut v, n).map_err(no_room(what))?;
    Ok(v)
}

/// Caps a capacity taken from a count declared in the file by what the text could hold (every
/// number needs at least one character and one separator), so that a huge declared count in a
/// small file does not allocate.
pub(crate) fn capped(n: usize, text: &str) -> usize {
    capped_len(n, text.len())
}

/// [`capped`] for a text of `len` bytes.
pub(crate) fn capped_len(n: usize, len: usize) -> usize {
    n.min(len / 2 + 1)
}

/// Whitespace-separated tokens, each with its 1-based line: [`scan::Scanner`] behind the
/// interface of a peekable iterator. `#` starts a comment that runs to the end of its line; lines
/// end in `\n`, `\r\n` or a lone `\r`; spaces, tabs and form feeds separate tokens.
#[allow(dead_code)] // the interface other readers share; ours use Scanner
pub(crate) struct Tokens<'a> {
    scanner: scan::Scanner<'a>,
}

#[allow(dead_code)]
impl<'a> Tokens<'a> {
    pub(crate) fn new(text: &'a str) -> Self {
        Tokens {
            scanner: scan::Scanner::new(text),
        }
    }

    pub(crate) fn peek(&mut self) -> Option<(&'a str, u32)> {
        self.scanner.peek()
    }

    /// Consumes and returns the tokens left on `line` (the line of the last token returned).
    pub(crate) fn rest_of_line(&mut self, line: u32) -> Vec<(&'a str, u32)> {
        let mut out = Vec::new();
        if self.scanner.line() == line {
            while let Some(tok) = self.scanner.token_in_line() {
                out.push(tok);
            }
        }
        out
    }
}

impl<'a> Iterator for Tokens<'a> {
    type Item = (&'a str, u32);

    fn next(&mut self) -> Option<(&'a str, u32)> {
        self.scanner.token()
    }
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
    scan::integer(tok.as_bytes())
}

/// A token's integer value, or the error every reader gives for a token that is not an
/// integer, `what` named with its article `the` ("a", "the"): "non-numeric token 'x' where a
/// vertex id was expected", "vertex id '1.5' is not an integer". `Ok(None)`: an integer too
/// large even for `i128`, which each caller words by its sign.
#[inline]
pub(crate) fn integer_token(
    tok: &str,
    the: &str,
    what: &str,
) -> Result<Option<i128>, ReadErrorKind> {
    match parse_integer(tok) {
        Ok(v) => Ok(Some(v)),
        Err(IntError::OutOfRange) => Ok(None),
        Err(IntError::NotInteger) => {
            Err(syntax(format!("{what} '{}' is not an integer", echo(tok))))
        }
        Err(IntError::NotNumber) => Err(syntax(format!(
            "non-numeric token '{}' where {the} {what} was expected",
            echo(tok)
        ))),
    }
}

/// Parses a vertex id: 0-based, or 1-based when `one_based` (then converted to 0-based).
/// Negative values are [`ReadErrorKind::NegativeId`] with the value as written.
pub(crate) fn parse_id(tok: &str, one_based: bool) -> Result<u32, ReadErrorKind> {
    let e = || echo(tok);
    let v = match integer_token(tok, "a", "vertex id")? {
        Some(v) => v,
        None if tok.starts_with('-') => {
            return Err(syntax(format!("negative vertex id {}", e())));
        }
        None => return Err(syntax(format!("vertex id {} does not fit in 32 bits", e()))),
    };
    if v < 0 {
        return Err(match i64::try_from(v) {
            Ok(v) => ReadErrorKind::NegativeId(v),
            Err(_) => syntax(format!("negative vertex id {}", e())),
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
    u32::try_from(v).map_err(|_| syntax(format!("vertex id {} does not fit in 32 bits", e())))
}

/// Parses a count declared in the file (`what` names it, e.g. "vertex count"): a non-negative
/// integer that fits in 32 bits.
pub(crate) fn parse_count(tok: &str, what: &str) -> Result<u32, ReadErrorKind> {
    let too_large = || syntax(format!("{what} {} does not fit in 32 bits", echo(tok)));
    match integer_token(tok, "the", what)? {
        Some(v) if v >= 0 => u32::try_from(v).map_err(|_| too_large()),
        None if !tok.starts_with('-') => Err(too_large()),
        _ => Err(syntax(format!("{what} {} is negative", echo(tok)))),
    }
}

/// Parses a floating-point number (`what` names it, e.g. "a vertex coordinate"). `nan`, `inf`
/// and `infinity` (any case, optionally signed) are accepted; a finite number that would become
/// infinite or 0 in an `f64` (`1e309`, `1e-400`) is an error.
pub(crate) fn parse_f64(tok: &str, what: &str) -> Result<f64, ReadErrorKind> {
    scan::real_or_err(tok, what)
}

/// Parses a floating-point number of the format's declared type `ty` (`what` names it): as
/// [`parse_f64`], and refused when `ty` could hold it only as infinity or 0 (`1e39`, `1e-50`
/// for a 32-bit float). The one check every reader uses for declared float types.
pub(crate) fn parse_real(tok: &str, what: &str, ty: Float) -> Result<f64, ReadErrorKind> {
    scan::real_or_err_as(tok, what, ty)
}

/// Checks that a token is an integer (`what` names it, e.g. "reference number"); its value is
/// not used.
pub(crate) fn check_integer(tok: &str, what: &str) -> Result<(), ReadErrorKind> {
    integer_token(tok, "a", what).map(|_| ())
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::path::PathBuf;

    /// The text readers refuse a file without a statement on its last line, blank and
    /// comment lines counted.
    #[test]
    fn text_readers_refuse_an_empty_file_on_its_last_line() {
        type Parse = fn(&str) -> Result<RawInput, (u32, ReadErrorKind)>;
        let readers: [(&str, Parse); 4] = [
            ("medit", medit::parse),
            ("off", off::parse),
            ("obj", obj::parse),
            ("simplices", simplices::parse),
        ];
        for (name, parse) in readers {
            for (text, line) in [("", 1), ("# c\n\n", 2), ("# nothing\n\n\n", 3)] {
                match parse(text) {
                    Ok(r) => panic!("{name}: {text:?} read as {r:?}"),
                    Err((l, k)) => {
                        assert_eq!(l, line, "{name}: {text:?}: {k}");
                        assert!(k.to_string().contains("file is empty"), "{name}: {k}");
                    }
                }
            }
        }
    }

    /// A file under the temp dir, removed on drop.
    pub(super) struct TempFile(pub(super) PathBuf);

    impl TempFile {
        pub(super) fn new(name: &str, bytes: &[u8]) -> TempFile {
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
                .contains("bad.off:4: polygon with 4 vertices is not a simplex (--triangulate")
        );
    }

    #[test]
    fn unknown_extension_and_missing_file() {
        let e = read_path(Path::new("x.dxf")).unwrap_err();
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
            ReadErrorKind::Syntax("file is not valid UTF-8 text (bad bytes '\\xe9')".into())
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
