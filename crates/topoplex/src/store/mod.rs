//! The saved format `.tpx`: a complex and, optionally, one structure built on it, opened back
//! zero-copy by memory mapping.
//!
//! # Layout (version 2)
//! All integers are in the byte order named by the header (the writer's; every platform we ship
//! is little-endian) and vertex/simplex ids are 32 bits wide.
//!
//! | bytes | what |
//! |---|---|
//! | 0..8 | magic `\x89TPX\r\n\x1a\n` (the high byte and the line endings expose text-mode transfers) |
//! | 8..12 | byte-order mark `0x01020304` as written by the writer |
//! | 12..16 | format version (2; files of version 1 are read too) |
//! | 16..20 | id width in bits (32) |
//! | 20..24 | content: 0 = complex only, 1 + `TPX_KIND_*` = complex and that structure |
//! | 24..28 | number of sections |
//! | 28..32 | index of the structure's first section (= the number of sections without one) |
//! | 32..40 | file length in bytes |
//! | 40..48 | offset of the section table |
//! | 48..56 | XXH3-64 of bytes 0..48 followed by the section table |
//! | 56..64 | zero |
//!
//! Each section holds one array: 64-byte aligned, described in the table by 32 bytes (offset,
//! element count, element size in bytes (1..=64), zero, XXH3-64 of its bytes); padding is zero. The complex comes first (its
//! vertex count, coordinates, the simplices as listed and, since version 2, its attributes —
//! labels and fields, copied on open like the listing; a complex without any is laid out as in
//! version 1), then the structure's arrays in the order its `save` wrote them. A saved live
//! complex gets its data back from the complex saved beside it.
//!
//! # Checksums and validation: what opening costs
//! A saved file is known by its magic number, whatever its name ([`is_saved_path`]). Opening
//! reads and checks the header and the section table (their checksum, then every section's
//! offset, length and alignment against the file's length), so no array view can point outside
//! the file whatever its bytes. Loading the structure checks its shape (each `Persist` impl's
//! `check`: array lengths against counts and dimension, per-dimension tables), so no count it
//! reports is made up. The structure's arrays are then views into the mapped file: opening
//! touches a few pages, whatever the file's size. Section checksums and the values inside the
//! arrays are *not* read on open, since that would read the whole file; [`Saved::verify`]
//! (and [`Saved::open_checked`], `--verify`, `TPX_OPEN_VERIFY`) checks them all, rebuilds the
//! complex, runs the structure's `validate()` and compares it with a structure built afresh
//! from the complex. Until then a file whose header is intact but whose arrays were altered
//! gives wrong answers or a query may panic on an inconsistent index, never an out-of-bounds
//! read (every access is bounds-checked; the CLI reports such a panic as a corrupt file, the C
//! ABI as `TPX_STATUS_PANIC`). The complex is rebuilt from its listing when asked for
//! ([`Saved::complex`]), which validates it fully.
//!
//! # The live complex
//! The live complex (content code 10, kind `iastar`) is saved compacted (no tombstones; ids as
//! [`crate::live::LiveComplex::compact`] gives them, the numbering of the complex saved beside
//! it) and opened back *editable*: its tables are copied out of the file and its stars rebuilt,
//! O(size), then every invariant is checked before it is returned (module doc of `live/store.rs`).

use std::fs::File;
use std::io;
use std::path::{Path, PathBuf};
use std::sync::Arc;

use crate::complex::{Complex, ComplexError, table};
use crate::io::Coords;
use crate::live::LiveComplex;
use crate::relation::{StructureKind, Topology};

mod persist;
pub use crate::codec::{Field, MAGIC, Persist, StoreError, VERSION, Writer};
pub(crate) use crate::codec::{HEADER_LEN, Reader, Sections, check_head};
pub use crate::mapped::{Arr, Backing};

/// One array of an opened file: `count` elements from byte `offset` of its bytes (aligned to
/// the element, inside the file: checked on open).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Span {
    /// Byte offset of the first element.
    pub offset: usize,
    /// Number of elements.
    pub count: usize,
}

impl Span {
    fn of<T: bytemuck::Pod>(a: &Arr<T>) -> Span {
        match a {
            Arr::Mapped { start, len, .. } => Span {
                offset: *start,
                count: *len,
            },
            // A reader's arrays are all views of the opened bytes.
            Arr::Owned(_) => unreachable!("a saved section is a view"),
        }
    }
}

/// Where the saved complex's arrays lie in the opened bytes ([`Saved::complex_spans`]): each
/// the array the complex holds, element for element.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct ComplexSpans {
    /// The coordinates (`f64`, vertex-major, `coords().dim` per vertex); `None` without any.
    pub coords: Option<Span>,
    /// The listing's vertex ids (`u32`), as `Complex::input_simplex` gives them in turn.
    pub listed_ids: Span,
    /// The listing's offsets (`u64`, one more than the listed simplices, from 0).
    pub listed_offsets: Span,
    /// Each attribute's values by name (the element type is the attribute's), saved order.
    pub attributes: Vec<(String, Span)>,
}

/// An opened `.tpx` file: checked header and section table over mapped bytes.
pub struct Saved {
    sections: Sections,
    kind: Option<StructureKind>,
    structure_first: usize,
}

/// Saves `complex` and, when given, a structure built on it, to `path` (written to a temporary
/// file beside it, then renamed, so a failed save leaves no half file under the name). Cost:
/// one pass over the structure's arrays.
pub fn save(
    path: &Path,
    complex: &Complex,
    structure: Option<&dyn Topology>,
) -> Result<(), StoreError> {
    let io_err = |e: io::Error| StoreError::Io {
        path: path.to_path_buf(),
        message: e.to_string(),
    };
    let mut tmp = path.as_os_str().to_owned();
    tmp.push(".partial");
    let tmp = PathBuf::from(tmp);
    // The rename would replace a device or pipe under `path` by a regular file.
    crate::io::check_output(path).map_err(io_err)?;
    crate::io::check_output(&tmp).map_err(io_err)?;
    let file = File::create(&tmp).map_err(io_err)?;
    let mut w = Writer::create(file);
    w.u8s(&MAGIC);
    persist::save_complex(complex, &mut w);
    let first = w.entries.len() as u32;
    let kind = match structure {
        Some(s) => {
            crate::family::save(s, &mut w);
            s.kind() as u32 + 1
        }
        None => 0,
    };
    let done = w
        .finish(kind, first)
        .and_then(|()| std::fs::rename(&tmp, path));
    if let Err(e) = done {
        let _ = std::fs::remove_file(&tmp);
        return Err(io_err(e));
    }
    Ok(())
}

/// Why an input path could not be opened ([`open_complex`], [`open_structure`]): the message is
/// the underlying error's, unchanged.
#[derive(Debug, thiserror::Error)]
pub enum OpenError {
    /// A mesh file could not be read or normalised.
    #[error(transparent)]
    Read(#[from] ComplexError),
    /// A saved file could not be opened, or its structure built.
    #[error(transparent)]
    Saved(#[from] StoreError),
    /// The structure could not be built from the file's complex.
    #[error(transparent)]
    Build(#[from] crate::relation::BuildError),
}

/// The one door for an input path, used by the CLI and the C ABI alike: a saved file
/// ([`is_saved_path`]: by its magic number, whatever its extension) gives its complex (rebuilt
/// from the saved listing), any other path is read by extension ([`Complex::from_path_with`],
/// normalised under `budget`).
pub fn open_complex(path: &Path, budget: crate::complex::Budget) -> Result<Complex, OpenError> {
    open_complex_with(path, budget, false)
}

/// [`open_complex`], and with `verify` a saved file is first checked fully ([`Saved::verify`]:
/// checksums, invariants, structure against complex; O(file size) and more). A mesh file is
/// always checked fully by reading it, so `verify` changes nothing for one.
pub fn open_complex_with(
    path: &Path,
    budget: crate::complex::Budget,
    verify: bool,
) -> Result<Complex, OpenError> {
    if is_saved_path(path) {
        return Ok(Saved::open_checked(path, verify)?.complex()?);
    }
    Ok(Complex::from_path_with(path, budget)?)
}

/// An editable live complex for an input path: a saved file's live complex (or one built from
/// its saved complex; with `verify`, the file checked fully first); a plain OFF file streamed
/// into the live complex's arrays (`io::plain`: no copy of the file, no listing, so the peak is
/// the live complex and a 1 MiB buffer); another mesh file read straight into the live complex
/// when its listing is plain ([`LiveComplex::from_plain_listing`]: no complex built, so the peak
/// is the file's bytes and the reader's listing, then the listing and the live complex); else
/// normalised under the default budget and built from the complex. Cost: O(file) plus the
/// build (a plain-looking OFF file that turns out not to be, e.g. a top listed twice, is read
/// twice).
pub fn open_live(path: &Path, verify: bool) -> Result<LiveComplex, OpenError> {
    open_live_with(path, verify, crate::io::ReadOptions::default())
}

/// [`open_live`] reading a mesh file with `options` (`triangulate`: convex planar polygons
/// fanned into triangles, others refused with the reason; a polygon never streams, so such a
/// file is read by its reader).
pub fn open_live_with(
    path: &Path,
    verify: bool,
    options: crate::io::ReadOptions,
) -> Result<LiveComplex, OpenError> {
    if is_saved_path(path) {
        let saved = Saved::open_checked(path, verify)?;
        return Ok(LiveComplex::open_saved(&saved)?);
    }
    if let Some(tables) = crate::io::plain::read_off(path)
        && let Some(live) = LiveComplex::from_plain_tables(tables)
    {
        return Ok(live?);
    }
    let raw = crate::io::read_path_with(path, options).map_err(ComplexError::from)?;
    if let Some(live) = LiveComplex::from_plain_listing(&raw) {
        return Ok(live?);
    }
    let complex = Complex::from_input(raw, Some(path), crate::complex::Budget::default())?;
    Ok(LiveComplex::try_from_complex(&complex)?)
}

/// A structure of `kind` for an input path: a saved file's structure is mapped when it is of
/// that kind (else built from the saved complex); any other path is read under `budget` and
/// built.
pub fn open_structure(
    path: &Path,
    kind: StructureKind,
    budget: crate::complex::Budget,
) -> Result<Box<dyn Topology>, OpenError> {
    open_structure_with(path, kind, budget, false)
}

/// [`open_structure`], and with `verify` a saved file is first checked fully
/// ([`open_complex_with`]).
pub fn open_structure_with(
    path: &Path,
    kind: StructureKind,
    budget: crate::complex::Budget,
    verify: bool,
) -> Result<Box<dyn Topology>, OpenError> {
    if is_saved_path(path) {
        return Ok(Saved::open_checked(path, verify)?.structure_of(kind)?);
    }
    let complex = Complex::from_path_with(path, budget)?;
    Ok(crate::family::build(kind, &complex)?)
}

/// Whether `path` names a saved file: its extension is `.tpx`, or it is a regular file whose
/// first bytes are the magic number [`MAGIC`] (so `save --out x.bin` opens back). Cost: one
/// `stat` and, without the extension, a read of 8 bytes; a FIFO or device is never opened here.
pub fn is_saved_path(path: &Path) -> bool {
    if path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("tpx"))
    {
        return true;
    }
    let Ok((mut file, _)) = crate::io::open_regular(path) else {
        return false;
    };
    let mut head = [0u8; MAGIC.len()];
    io::Read::read_exact(&mut file, &mut head).is_ok() && head == MAGIC
}

impl Saved {
    /// Opens a saved file by memory mapping it. Checks the header and section table (see the
    /// module doc); reads no array. Cost: O(sections), a few pages.
    pub fn open(path: &Path) -> Result<Saved, StoreError> {
        let io_err = |e: io::Error| StoreError::Io {
            path: path.to_path_buf(),
            message: e.to_string(),
        };
        // Only a regular file: a pipe would hang the open, a directory or device mislead it.
        let (file, _) = crate::io::open_regular(path).map_err(io_err)?;
        Saved::open_file(path, &file)
    }

    /// [`Saved::open`] of a file already opened (by [`crate::io::open_regular`]; `path` names
    /// it in errors), for a caller that maps the same file again to view its arrays in place
    /// ([`Saved::complex_spans`]): both maps are then of one file, whatever is renamed over
    /// `path` meanwhile. Cost: as [`Saved::open`].
    pub fn open_file(path: &Path, file: &File) -> Result<Saved, StoreError> {
        let io_err = |e: io::Error| StoreError::Io {
            path: path.to_path_buf(),
            message: e.to_string(),
        };
        // A mapping counts against an address-space limit: one that does not fit is memory
        // the file asks for (TooLarge), not an I/O error.
        let map = crate::sys::map_file(file).map_err(|e| match e.kind() {
            io::ErrorKind::OutOfMemory => StoreError::Complex {
                path: path.to_path_buf(),
                source: ComplexError::OutOfMemory {
                    file: None,
                    what: "mapping the file",
                    bytes: file.metadata().map_or(0, |m| m.len()),
                },
            },
            _ => io_err(e),
        })?;
        Saved::from_backing(path, Backing::Map(map))
    }

    /// [`Saved::open`], then with `verify` [`Saved::verify`] before returning.
    pub fn open_checked(path: &Path, verify: bool) -> Result<Saved, StoreError> {
        let saved = Saved::open(path)?;
        if verify {
            saved.verify()?;
        }
        Ok(saved)
    }

    /// Opens saved bytes held in memory (copied into aligned words); `name` stands for the file
    /// in errors. Same checks as [`Saved::open`].
    pub fn from_bytes(name: &Path, bytes: &[u8]) -> Result<Saved, StoreError> {
        let n = bytes.len().div_ceil(8);
        let mut words = Vec::new();
        table::try_reserve_exact(&mut words, n).map_err(|bytes| StoreError::Complex {
            path: name.to_path_buf(),
            source: ComplexError::OutOfMemory {
                file: None,
                what: "a copy of the saved bytes",
                bytes: bytes as u64,
            },
        })?;
        words.resize(n, 0u64);
        bytemuck::cast_slice_mut::<u64, u8>(&mut words)[..bytes.len()].copy_from_slice(bytes);
        Saved::from_backing(name, Backing::Heap(words, bytes.len()))
    }

    fn from_backing(path: &Path, backing: Backing) -> Result<Saved, StoreError> {
        let (entries, kind, structure_first) = check_head(path, backing.bytes())?;
        Ok(Saved {
            sections: Sections {
                path: path.to_path_buf(),
                backing: Arc::new(backing),
                entries,
            },
            kind,
            structure_first,
        })
    }

    /// The structure saved in the file, if any.
    pub fn kind(&self) -> Option<StructureKind> {
        self.kind
    }

    /// The file's length in bytes.
    pub fn len(&self) -> usize {
        self.sections.backing.bytes().len()
    }

    /// Whether the file is empty (never, once opened).
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    fn reader(&self, first: usize) -> Reader<'_> {
        Reader {
            saved: &self.sections,
            next: first,
        }
    }

    /// The saved complex, rebuilt from its saved listing (so validated like any input): the
    /// same complex, numbering and statistics as the one saved. Cost: a normalisation.
    pub fn complex(&self) -> Result<Complex, StoreError> {
        Ok(self.complex_spans()?.0)
    }

    /// [`Saved::complex`], and where the arrays it copied lie in the opened bytes (in the file,
    /// for [`Saved::open`]), checked against them on open: a caller that maps the file itself
    /// views them there instead of copying (the Python binding's read-only numpy arrays).
    pub fn complex_spans(&self) -> Result<(Complex, ComplexSpans), StoreError> {
        let mut r = self.reader(1);
        let mut spans = ComplexSpans::default();
        let mut c = persist::load_complex(&mut r, &mut spans)?;
        persist::load_attributes(&mut r, &mut c, self.structure_first, &mut spans)?;
        if r.next != self.structure_first {
            return Err(r.corrupt("the complex's sections do not end where the structure's begin"));
        }
        Ok((c, spans))
    }

    /// The saved structure, its arrays viewing the mapped file; `None` for a file holding only
    /// a complex. Cost: O(sections) plus the structure's small tables (copied).
    pub fn structure(&self) -> Result<Option<Box<dyn Topology>>, StoreError> {
        let Some(kind) = self.kind else {
            return Ok(None);
        };
        let mut r = self.reader(self.structure_first);
        let s = crate::family::load(kind, &mut r)?;
        r.done()?;
        self.same_vertex_count(s.vertex_count())?;
        Ok(Some(s))
    }

    /// The saved structure's vertex count against the saved complex's (section 1, one number):
    /// a cheap check that the two belong together.
    fn same_vertex_count(&self, n: u32) -> Result<(), StoreError> {
        let mut r = self.reader(1);
        let saved = r.scalar()?;
        if saved != u64::from(n) {
            return Err(self.corrupt(format!(
                "the saved structure has {n} vertices, the saved complex {saved}"
            )));
        }
        Ok(())
    }

    /// The file's path (as opened).
    pub(crate) fn path(&self) -> &Path {
        &self.sections.path
    }

    /// The saved structure as its concrete type `T` when the file holds one of `kind` (`T`'s
    /// kind), else `None`; owned, not boxed (no copy to take it out of a `dyn Topology`).
    pub(crate) fn structure_as<T: Persist>(
        &self,
        kind: StructureKind,
    ) -> Result<Option<T>, StoreError> {
        if self.kind != Some(kind) {
            return Ok(None);
        }
        let mut r = self.reader(self.structure_first);
        let s = T::load(&mut r)?;
        r.done()?;
        Ok(Some(s))
    }

    /// A structure of `kind`: the saved one when it is of that kind, else built from the saved
    /// complex.
    pub fn structure_of(&self, kind: StructureKind) -> Result<Box<dyn Topology>, StoreError> {
        if self.kind == Some(kind)
            && let Some(s) = self.structure()?
        {
            return Ok(s);
        }
        let complex = self.complex()?;
        crate::family::build(kind, &complex).map_err(|source| StoreError::Build {
            path: self.sections.path.clone(),
            source,
        })
    }

    /// Checks every section's checksum (reads the whole file), rebuilds the saved complex from
    /// its listing (validating it as any input), checks the saved structure's invariants
    /// (`validate()`), and that it agrees with the saved complex: a structure built afresh
    /// from it gives the same simplices and the same answer to every relation of every simplex.
    /// Cost: O(file size) plus a normalisation, a build and every relation of both structures.
    pub fn verify(&self) -> Result<(), StoreError> {
        let bytes = self.sections.backing.bytes();
        // Padding between sections must be zero, so that every byte of the file is checked.
        let mut covered = HEADER_LEN;
        for (i, e) in self.sections.entries.iter().enumerate() {
            let start = e.offset as usize;
            let end = start + (e.count * e.size as u64) as usize;
            if start >= covered && bytes[covered..start].iter().any(|&b| b != 0) {
                return Err(self.corrupt(format!("non-zero padding before section {i}")));
            }
            if xxhash_rust::xxh3::xxh3_64(&bytes[start..end]) != e.checksum {
                return Err(self.corrupt(format!("section {i}: checksum mismatch")));
            }
            covered = covered.max(end);
        }
        let table = u64::from_ne_bytes(bytes[40..48].try_into().unwrap()) as usize;
        if bytes[covered.min(table)..table].iter().any(|&b| b != 0) {
            return Err(self.corrupt("non-zero padding before the section table"));
        }
        // The complex is rebuilt from its listing, so validated like any input.
        let complex = self.complex()?;
        if let Some(s) = self.structure()? {
            // A hostile file whose checksums were recomputed may still break an invariant that
            // `validate` indexes through: its panic is an answer here, not a crash.
            let kind = s.kind();
            let checked =
                crate::error::caught_quietly(std::panic::AssertUnwindSafe(|| s.validate()));
            match checked {
                Ok(Ok(())) => {}
                Ok(Err(e)) => return Err(self.corrupt(format!("saved {kind}: {e}"))),
                Err(_) => {
                    return Err(self.corrupt(format!("saved {kind}: inconsistent arrays")));
                }
            }
            // A valid structure of another complex (both sections resealed): every relation of
            // a structure built afresh from the saved complex must be the saved one's.
            let fresh =
                crate::family::build(kind, &complex).map_err(|source| StoreError::Build {
                    path: self.sections.path.clone(),
                    source,
                })?;
            let agree = crate::error::caught_quietly(std::panic::AssertUnwindSafe(|| {
                crate::oracle::compare_structures(fresh.as_ref(), s.as_ref())
            }));
            match agree {
                Ok(Ok(())) => {}
                Ok(Err(e)) => {
                    return Err(self.corrupt(format!(
                        "saved {kind} does not match the saved complex: {e}"
                    )));
                }
                Err(_) => {
                    return Err(self.corrupt(format!(
                        "saved {kind} does not match the saved complex (inconsistent arrays)"
                    )));
                }
            }
        }
        Ok(())
    }

    fn corrupt(&self, what: impl Into<String>) -> StoreError {
        StoreError::Corrupt {
            path: self.sections.path.clone(),
            what: what.into(),
        }
    }
}

/// Rewrites the checksums of saved bytes after an edit (every section's whose place lies inside
/// the bytes, then the header's), so that an edit reaches the checks behind them: for tests and
/// fuzzing of what opening and `verify` catch beyond a checksum. Returns `false`, leaving the
/// bytes as they are, when they have no readable header or section table. Cost: O(bytes).
#[doc(hidden)]
pub fn reseal(bytes: &mut [u8]) -> bool {
    if bytes.len() < HEADER_LEN {
        return false;
    }
    let u64_at = |b: &[u8], o: usize| u64::from_ne_bytes(b[o..o + 8].try_into().unwrap());
    let n = u32::from_ne_bytes(bytes[24..28].try_into().unwrap()) as usize;
    let table = u64_at(bytes, 40);
    let Some(end) = usize::try_from(table)
        .ok()
        .and_then(|t| n.checked_mul(32).and_then(|l| l.checked_add(t)))
        .filter(|&end| end <= bytes.len() && table >= HEADER_LEN as u64)
    else {
        return false;
    };
    let table = table as usize;
    for i in 0..n {
        let at = table + 32 * i;
        let (offset, count) = (u64_at(bytes, at), u64_at(bytes, at + 8));
        let size = u32::from_ne_bytes(bytes[at + 16..at + 20].try_into().unwrap()) as u64;
        let span = count
            .checked_mul(size)
            .and_then(|l| l.checked_add(offset))
            .filter(|&e| e <= bytes.len() as u64);
        if let Some(e) = span {
            let sum = xxhash_rust::xxh3::xxh3_64(&bytes[offset as usize..e as usize]);
            bytes[at + 24..at + 32].copy_from_slice(&sum.to_ne_bytes());
        }
    }
    let sum = crate::codec::head_checksum(&bytes[..48], &bytes[table..end]);
    bytes[48..56].copy_from_slice(&sum.to_ne_bytes());
    true
}

/// Coordinates as saved: dimension, then the numbers.
fn coords_of(c: &Complex) -> (u64, &[f64]) {
    match c.coords() {
        Some(Coords { dim, data }) => (*dim as u64, data),
        None => (0, &[]),
    }
}

// Saving and opening a whole file belongs to the store, which stands above the live mesh.
impl LiveComplex {
    /// Saves the live complex and its complex ([`LiveComplex::to_complex`]) to `path` (`.tpx`;
    /// compacted on the fly, see the module doc). Cost: O(size).
    pub fn save(&self, path: &std::path::Path) -> Result<(), StoreError> {
        save(path, &self.to_complex(), Some(self))
    }

    /// Opens a `.tpx` file as an editable live complex: the saved live complex when the file
    /// holds one, else one built from the saved complex. Cost: O(size) (copied, not mapped).
    pub fn open(path: &std::path::Path) -> Result<LiveComplex, StoreError> {
        LiveComplex::open_saved(&Saved::open(path)?)
    }

    /// [`LiveComplex::open`] of an opened file.
    pub fn open_saved(saved: &Saved) -> Result<LiveComplex, StoreError> {
        let kind = crate::relation::StructureKind::IaStar;
        if let Some(mut live) = saved.structure_as::<LiveComplex>(kind)? {
            let complex = saved.complex()?;
            live.attach_data(&complex);
            return Ok(live);
        }
        LiveComplex::try_from_complex(&saved.complex()?).map_err(|source| StoreError::Build {
            path: saved.path().to_path_buf(),
            source,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::open_live_with;
    use crate::io::ReadOptions;

    /// A square as one quadrilateral in OFF: the mesh refuses it as read, and with triangulate
    /// holds the two triangles of its fan from the first vertex, winding kept.
    #[test]
    fn a_quad_in_an_off_file_is_refused_or_fanned_into_the_mesh() {
        let path =
            std::env::temp_dir().join(format!("topoplex-store-quad-{}.off", std::process::id()));
        std::fs::write(&path, "OFF\n4 1 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n").unwrap();
        assert!(open_live_with(&path, false, ReadOptions::default()).is_err());
        let live = open_live_with(&path, false, ReadOptions { triangulate: true }).unwrap();
        let tops: Vec<Vec<u32>> = live.tops().map(|(_, s)| s.to_vec()).collect();
        assert_eq!(tops, [vec![0, 1, 2], vec![0, 2, 3]]);
        let _ = std::fs::remove_file(&path);
    }
}
