//! Readers: one module per file format, parsing only.
//!
//! A reader turns bytes into a [`RawInput`]: a vertex count, optional coordinates and a list of
//! simplices with the line each came from. It checks syntax (numbers, counts, headers, polygons
//! that are not simplices, negative ids) but no topology: repeated vertices, ids out of range,
//! duplicates and faces of other simplices are the complex model's business
//! ([`crate::complex::Complex::from_raw`]), which reports them with the same file and line.
//!
//! The format is chosen by file extension: `.off`, `.obj`, `.mesh`, `.simplices`.

use std::path::{Path, PathBuf};

pub mod medit;
pub mod obj;
pub mod off;
pub mod simplices;
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
    #[error("unknown file extension (expected .off, .obj, .mesh or .simplices)")]
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
        _ => return Err(err(0, ReadErrorKind::UnknownExtension)),
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
