//! The section codec of `.tpx` files: the header and section-table layout (described in
//! [`crate::store`]'s module doc), [`Writer`] and [`Reader`] (one array a section), [`Persist`]
//! and [`Field`] (a structure's sections as the list of its fields), and [`StoreError`]. It stands
//! below the structures, which save themselves through it, and above the model and the relation
//! API whose types it writes; [`crate::store`] (the file as a whole) stands above the structures.

use std::fs::File;
use std::io::{self, BufWriter, Seek, SeekFrom, Write};
use std::marker::PhantomData;
use std::path::{Path, PathBuf};
use std::sync::Arc;

use crate::complex::{ComplexError, SimplexTable};
use crate::mapped::{Arr, Backing};
use crate::relation::{BuildError, StructureKind};

mod field;
pub use field::Field;
pub(crate) use field::dimension_at_most;

/// First bytes of every `.tpx` file.
pub const MAGIC: [u8; 8] = *b"\x89TPX\r\n\x1a\n";
/// The format version this build writes; it reads every version from 1 up to it (version 2
/// added the complex's attributes after its source; a version-1 file has none).
pub const VERSION: u32 = 2;
/// Written as a native `u32`; read back swapped on a host of the other byte order.
const BYTE_ORDER_MARK: u32 = 0x0102_0304;
pub(crate) const HEADER_LEN: usize = 64;
const ENTRY_LEN: usize = 32;
pub(crate) const ALIGN: u64 = 64;
/// More sections than any structure writes: bounds the table a hostile header can demand.
const MAX_SECTIONS: u64 = 1 << 16;

/// Why a `.tpx` file could not be written, opened or verified. Each names the file.
#[derive(Debug, thiserror::Error)]
pub enum StoreError {
    /// The file cannot be read or written.
    #[error("{}: {message}", crate::error::echo_path(.path))]
    Io {
        /// The file.
        path: PathBuf,
        /// The system's message.
        message: String,
    },
    /// The file is not a `.tpx` file (its first bytes are not the magic number).
    #[error("{}: not a topoplex saved file (.tpx): wrong magic number", crate::error::echo_path(.path))]
    Foreign {
        /// The file.
        path: PathBuf,
    },
    /// The file is shorter than its header says.
    #[error("{}: truncated saved file: {what}", crate::error::echo_path(.path))]
    Truncated {
        /// The file.
        path: PathBuf,
        /// What is missing.
        what: String,
    },
    /// The file was written by another format version.
    #[error("{}: saved file format version {found}, this build reads versions 1 to {supported}", crate::error::echo_path(.path))]
    WrongVersion {
        /// The file.
        path: PathBuf,
        /// The file's version.
        found: u32,
        /// The version this build reads.
        supported: u32,
    },
    /// The file was written on a host of the other byte order.
    #[error("{}: saved file written in the other byte order (big- vs little-endian); save it again on this machine", crate::error::echo_path(.path))]
    WrongEndianness {
        /// The file.
        path: PathBuf,
    },
    /// A checksum, offset, length or value is wrong.
    #[error("{}: corrupt saved file: {what}", crate::error::echo_path(.path))]
    Corrupt {
        /// The file.
        path: PathBuf,
        /// The first inconsistency found.
        what: String,
    },
    /// The saved complex is not a valid complex.
    #[error("{}: saved complex: {source}", crate::error::echo_path(.path))]
    Complex {
        /// The file.
        path: PathBuf,
        /// What the complex model refused.
        source: ComplexError,
    },
    /// The requested structure could not be built from the saved complex.
    #[error("{}: {source}", crate::error::echo_path(.path))]
    Build {
        /// The file.
        path: PathBuf,
        /// Why the build failed.
        source: BuildError,
    },
}

/// What a section's elements are (their size in bytes).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Entry {
    pub(crate) offset: u64,
    pub(crate) count: u64,
    pub(crate) size: u32,
    pub(crate) checksum: u64,
}

/// Writes the sections of a `.tpx` file in order. Each call appends one array; the first write
/// error is kept and returned by `Writer::finish`, so `save` implementations stay linear.
pub struct Writer {
    out: BufWriter<File>,
    pos: u64,
    pub(crate) entries: Vec<Entry>,
    error: Option<io::Error>,
}

impl Writer {
    pub(crate) fn create(file: File) -> Writer {
        let mut w = Writer {
            // Small: sections larger than the buffer go to the file directly, so it only
            // gathers headers, scalars and padding (and a fixed allocation stays small).
            out: BufWriter::with_capacity(64 << 10, file),
            pos: 0,
            entries: Vec::new(),
            error: None,
        };
        // The header is written last, once the table's place and checksum are known.
        w.write_raw(&[0u8; HEADER_LEN]);
        w
    }

    fn write_raw(&mut self, bytes: &[u8]) {
        if self.error.is_none()
            && let Err(e) = self.out.write_all(bytes)
        {
            self.error = Some(e);
        }
        self.pos += bytes.len() as u64;
    }

    fn pad_to(&mut self, align: u64) {
        let pad = self.pos.next_multiple_of(align) - self.pos;
        self.write_raw(&[0u8; ALIGN as usize][..pad as usize]);
    }

    /// Appends an array of any plain element type.
    pub fn section<T: bytemuck::Pod>(&mut self, items: &[T]) {
        self.pad_to(ALIGN);
        let bytes: &[u8] = bytemuck::cast_slice(items);
        self.entries.push(Entry {
            offset: self.pos,
            count: items.len() as u64,
            size: size_of::<T>() as u32,
            checksum: xxhash_rust::xxh3::xxh3_64(bytes),
        });
        self.write_raw(bytes);
    }

    /// Appends an array of bytes.
    pub fn u8s(&mut self, items: &[u8]) {
        self.section(items);
    }

    /// Appends an array of 32-bit integers.
    pub fn u32s(&mut self, items: &[u32]) {
        self.section(items);
    }

    /// Appends an array of 64-bit integers.
    pub fn u64s(&mut self, items: &[u64]) {
        self.section(items);
    }

    /// Appends an array of `usize`, widened to 64 bits (on 64-bit targets written as is: no
    /// input-sized copy, which could not be had fallibly here).
    pub fn usizes(&mut self, items: &[usize]) {
        #[cfg(target_pointer_width = "64")]
        self.section::<u64>(bytemuck::cast_slice(items));
        #[cfg(not(target_pointer_width = "64"))]
        {
            let wide: Vec<u64> = items.iter().map(|&x| x as u64).collect();
            self.section(&wide);
        }
    }

    /// Appends `count` numbers produced by `items`, widened to 64 bits: the bytes of
    /// [`Writer::usizes`] of the same numbers, without an array holding them (e.g. offsets
    /// that are a formula).
    pub fn usizes_from(&mut self, count: usize, items: impl Iterator<Item = usize>) {
        self.pad_to(ALIGN);
        let offset = self.pos;
        let mut hash = xxhash_rust::xxh3::Xxh3::new();
        let mut buf = [0u64; 1024];
        let mut written = 0usize;
        let mut items = items.take(count);
        loop {
            let mut n = 0;
            for (slot, x) in buf.iter_mut().zip(&mut items) {
                *slot = x as u64;
                n += 1;
            }
            if n == 0 {
                break;
            }
            let bytes: &[u8] = bytemuck::cast_slice(&buf[..n]);
            hash.update(bytes);
            self.write_raw(bytes);
            written += n;
        }
        assert_eq!(written, count, "usizes_from: the iterator ended early");
        self.entries.push(Entry {
            offset,
            count: count as u64,
            size: 8,
            checksum: hash.digest(),
        });
    }

    /// Appends one number (a one-element 64-bit section).
    pub fn scalar(&mut self, x: u64) {
        self.section(&[x]);
    }

    /// Appends a simplex table: its arity, then its rows.
    pub fn table(&mut self, t: &SimplexTable) {
        self.scalar(t.arity() as u64);
        self.u32s(t.as_flat());
    }

    pub(crate) fn finish(mut self, kind: u32, structure_first: u32) -> io::Result<()> {
        self.pad_to(8);
        let table_offset = self.pos;
        let mut table = Vec::with_capacity(self.entries.len() * ENTRY_LEN);
        for e in &self.entries {
            table.extend_from_slice(&e.offset.to_ne_bytes());
            table.extend_from_slice(&e.count.to_ne_bytes());
            table.extend_from_slice(&e.size.to_ne_bytes());
            table.extend_from_slice(&0u32.to_ne_bytes());
            table.extend_from_slice(&e.checksum.to_ne_bytes());
        }
        self.write_raw(&table);
        let file_len = self.pos;
        let mut header = [0u8; HEADER_LEN];
        header[0..8].copy_from_slice(&MAGIC);
        header[8..12].copy_from_slice(&BYTE_ORDER_MARK.to_ne_bytes());
        header[12..16].copy_from_slice(&VERSION.to_ne_bytes());
        header[16..20].copy_from_slice(&32u32.to_ne_bytes());
        header[20..24].copy_from_slice(&kind.to_ne_bytes());
        header[24..28].copy_from_slice(&(self.entries.len() as u32).to_ne_bytes());
        header[28..32].copy_from_slice(&structure_first.to_ne_bytes());
        header[32..40].copy_from_slice(&file_len.to_ne_bytes());
        header[40..48].copy_from_slice(&table_offset.to_ne_bytes());
        let sum = head_checksum(&header[..48], &table);
        header[48..56].copy_from_slice(&sum.to_ne_bytes());
        if let Some(e) = self.error.take() {
            return Err(e);
        }
        let mut file = self.out.into_inner().map_err(|e| e.into_error())?;
        file.seek(SeekFrom::Start(0))?;
        file.write_all(&header)?;
        file.sync_all()
    }
}

pub(crate) fn head_checksum(header48: &[u8], table: &[u8]) -> u64 {
    let mut h = xxhash_rust::xxh3::Xxh3::new();
    h.update(header48);
    h.update(table);
    h.digest()
}

/// Reads the sections of an opened file in the order they were written, as views (arrays) or
/// numbers; every shape error names the file.
pub struct Reader<'a> {
    pub(crate) saved: &'a Sections,
    pub(crate) next: usize,
}

/// An opened file's bytes, its path (for errors) and its checked section table: what a
/// [`Reader`] reads from.
pub(crate) struct Sections {
    pub(crate) path: PathBuf,
    pub(crate) backing: Arc<Backing>,
    pub(crate) entries: Vec<Entry>,
}

impl Reader<'_> {
    /// A `Corrupt` error naming the file.
    pub fn corrupt(&self, what: impl Into<String>) -> StoreError {
        StoreError::Corrupt {
            path: self.saved.path.clone(),
            what: what.into(),
        }
    }

    fn entry(&mut self, size: u32) -> Result<Entry, StoreError> {
        let i = self.next;
        let e = *self
            .saved
            .entries
            .get(i)
            .ok_or_else(|| self.corrupt(format!("section {i} is missing")))?;
        if e.size != size {
            return Err(self.corrupt(format!(
                "section {i} has {}-byte elements where {size}-byte ones were expected",
                e.size
            )));
        }
        self.next += 1;
        Ok(e)
    }

    /// The next section, an array of any plain element type of the saved element size.
    pub fn arr<T: bytemuck::Pod>(&mut self) -> Result<Arr<T>, StoreError> {
        let e = self.entry(size_of::<T>() as u32)?;
        // Offsets, lengths and alignment were checked against the file on open.
        Ok(Arr::Mapped {
            backing: Arc::clone(&self.saved.backing),
            start: e.offset as usize,
            len: e.count as usize,
            _t: PhantomData,
        })
    }

    /// The next section, an array of bytes.
    pub fn u8s(&mut self) -> Result<Arr<u8>, StoreError> {
        self.arr()
    }

    /// The next section, an array of 32-bit integers.
    pub fn u32s(&mut self) -> Result<Arr<u32>, StoreError> {
        self.arr()
    }

    /// The next section, an array of 64-bit integers.
    pub fn u64s(&mut self) -> Result<Arr<u64>, StoreError> {
        self.arr()
    }

    /// The next section, 64-bit integers as `usize` (copied, the copy reserved fallibly:
    /// [`Reader::out_of_memory`]; refused if one does not fit).
    pub fn usizes(&mut self) -> Result<Vec<usize>, StoreError> {
        let wide = self.u64s()?;
        self.usizes_of(&wide)
    }

    /// A section of 64-bit integers ([`Reader::u64s`]) copied as `usize`, as [`Reader::usizes`].
    pub fn usizes_of(&self, wide: &Arr<u64>) -> Result<Vec<usize>, StoreError> {
        let mut out = Vec::new();
        crate::alloc::try_reserve_exact(&mut out, wide.len())
            .map_err(|bytes| self.out_of_memory("a copy of a saved array", bytes))?;
        for &x in wide.iter() {
            out.push(usize::try_from(x).map_err(|_| self.corrupt(format!("{x} overflows usize")))?);
        }
        Ok(out)
    }

    /// A copy of a mapped array, reserved fallibly ([`Reader::out_of_memory`]).
    pub fn copy<T: bytemuck::Pod>(&self, a: &Arr<T>) -> Result<Vec<T>, StoreError> {
        let mut out = Vec::new();
        crate::alloc::try_extend(&mut out, a)
            .map_err(|bytes| self.out_of_memory("a copy of a saved array", bytes))?;
        Ok(out)
    }

    /// Memory that opening asks for (a copy of the file's arrays) that cannot be had: the
    /// complex model's `OutOfMemory` (`TPX_STATUS_TOO_LARGE` through the C ABI), not an abort.
    pub fn out_of_memory(&self, what: &'static str, bytes: usize) -> StoreError {
        StoreError::Complex {
            path: self.saved.path.clone(),
            source: ComplexError::OutOfMemory {
                file: None,
                what,
                bytes: bytes as u64,
            },
        }
    }

    /// The next section, one number.
    pub fn scalar(&mut self) -> Result<u64, StoreError> {
        let a = self.u64s()?;
        match *a {
            [x] => Ok(x),
            _ => Err(self.corrupt(format!(
                "section {} should hold one number, holds {}",
                self.next - 1,
                a.len()
            ))),
        }
    }

    /// The next number, which must be at most `max`.
    pub fn bounded(&mut self, max: u64, what: &str) -> Result<u64, StoreError> {
        let x = self.scalar()?;
        if x > max {
            return Err(self.corrupt(format!("{what} is {x}, above {max}")));
        }
        Ok(x)
    }

    /// The next number as a `u32`.
    pub fn u32(&mut self, what: &str) -> Result<u32, StoreError> {
        Ok(self.bounded(u32::MAX as u64, what)? as u32)
    }

    /// The next number as a `usize`.
    pub fn usize(&mut self, what: &str) -> Result<usize, StoreError> {
        Ok(self.bounded(usize::MAX as u64, what)? as usize)
    }

    /// A simplex table written by [`Writer::table`]: arity 1..=16, length a multiple of it.
    /// Row order is the structure's invariant, checked by `verify`.
    pub fn table(&mut self) -> Result<SimplexTable, StoreError> {
        let arity = self.bounded(crate::complex::MAX_DIMENSION as u64 + 1, "table arity")?;
        if arity == 0 {
            return Err(self.corrupt("table arity is 0"));
        }
        let ids = self.u32s()?;
        if ids.len() % arity as usize != 0 {
            return Err(self.corrupt(format!(
                "table of {} ids is not made of rows of {arity}",
                ids.len()
            )));
        }
        Ok(SimplexTable::from_arr(arity as usize, ids))
    }

    /// Checks that `len` is `want`, naming the array.
    pub fn expect_len(&self, what: &str, len: usize, want: usize) -> Result<(), StoreError> {
        if len != want {
            return Err(self.corrupt(format!("{what} has {len} entries, expected {want}")));
        }
        Ok(())
    }

    pub(crate) fn done(&self) -> Result<(), StoreError> {
        let left = self.saved.entries.len() - self.next;
        if left != 0 {
            return Err(self.corrupt(format!("{left} sections left unread")));
        }
        Ok(())
    }
}

/// What a structure writes to and reads back from a saved file.
pub trait Persist: Sized {
    /// Appends the structure's arrays and numbers.
    fn save(&self, w: &mut Writer);
    /// Reads them back in the same order. Checks the shapes it needs (array lengths against
    /// counts), not the invariants `validate()` checks.
    fn load(r: &mut Reader) -> Result<Self, StoreError>;
}

pub(crate) type Head = (Vec<Entry>, Option<StructureKind>, usize);

/// Checks the header and the section table of `bytes` (see the module doc).
pub(crate) fn check_head(path: &Path, bytes: &[u8]) -> Result<Head, StoreError> {
    let corrupt = |what: String| StoreError::Corrupt {
        path: path.to_path_buf(),
        what,
    };
    check_fixed_fields(path, bytes, &corrupt)?;
    let (u32_at, u64_at) = (|o| header_u32(bytes, o), |o| header_u64(bytes, o));
    let (kind_code, n_sections, first) = (u32_at(20), u32_at(24) as u64, u32_at(28) as usize);
    let (file_len, table_offset, sum) = (u64_at(32), u64_at(40), u64_at(48));
    let table = section_table(path, bytes, (file_len, table_offset, n_sections), &corrupt)?;
    if head_checksum(&bytes[..48], table) != sum {
        return Err(corrupt("header checksum mismatch".into()));
    }
    let kind = content_kind(kind_code, &corrupt)?;
    if first > n_sections as usize || (kind.is_none() && first != n_sections as usize) {
        return Err(corrupt(format!(
            "structure starts at section {first} of {n_sections}"
        )));
    }
    let entries = parse_table(table, table_offset, &corrupt)?;
    Ok((entries, kind, first))
}

/// Checks the header's fields that every file has alike: the magic, the length, the byte
/// order, the version, the reserved bytes and the id width.
fn check_fixed_fields(
    path: &Path,
    bytes: &[u8],
    corrupt: &dyn Fn(String) -> StoreError,
) -> Result<(), StoreError> {
    if bytes.len() < MAGIC.len() || bytes[..MAGIC.len()] != MAGIC {
        return Err(StoreError::Foreign {
            path: path.to_path_buf(),
        });
    }
    if bytes.len() < HEADER_LEN {
        return Err(StoreError::Truncated {
            path: path.to_path_buf(),
            what: format!(
                "{} bytes, shorter than the {HEADER_LEN}-byte header",
                bytes.len()
            ),
        });
    }
    let (u32_at, u64_at) = (|o| header_u32(bytes, o), |o| header_u64(bytes, o));
    match u32_at(8) {
        BYTE_ORDER_MARK => {}
        m if m == BYTE_ORDER_MARK.swap_bytes() => {
            return Err(StoreError::WrongEndianness {
                path: path.to_path_buf(),
            });
        }
        m => return Err(corrupt(format!("byte-order mark {m:#010x}"))),
    }
    if !(1..=VERSION).contains(&u32_at(12)) {
        return Err(StoreError::WrongVersion {
            path: path.to_path_buf(),
            found: u32_at(12),
            supported: VERSION,
        });
    }
    if u64_at(56) != 0 {
        return Err(corrupt(format!(
            "reserved header bytes hold {:#x}",
            u64_at(56)
        )));
    }
    if u32_at(16) != 32 {
        return Err(corrupt(format!(
            "id width {} bits, expected 32",
            u32_at(16)
        )));
    }
    Ok(())
}

/// The native-endian `u32` at byte `o` of the header.
fn header_u32(bytes: &[u8], o: usize) -> u32 {
    u32::from_ne_bytes(bytes[o..o + 4].try_into().unwrap())
}

/// The native-endian `u64` at byte `o` of the header.
fn header_u64(bytes: &[u8], o: usize) -> u64 {
    u64::from_ne_bytes(bytes[o..o + 8].try_into().unwrap())
}

/// The section table's bytes, checked against the file length the header states and its
/// section count: `(file_len, table_offset, n_sections)`.
fn section_table<'b>(
    path: &Path,
    bytes: &'b [u8],
    (file_len, table_offset, n_sections): (u64, u64, u64),
    corrupt: &dyn Fn(String) -> StoreError,
) -> Result<&'b [u8], StoreError> {
    if file_len > bytes.len() as u64 {
        return Err(StoreError::Truncated {
            path: path.to_path_buf(),
            what: format!("{} bytes of the {file_len} the header states", bytes.len()),
        });
    }
    if file_len < bytes.len() as u64 {
        return Err(corrupt(format!(
            "{} bytes where the header states {file_len}",
            bytes.len()
        )));
    }
    if n_sections > MAX_SECTIONS {
        return Err(corrupt(format!("{n_sections} sections")));
    }
    let table_end = table_offset
        .checked_add(n_sections * ENTRY_LEN as u64)
        .filter(|&end| table_offset >= HEADER_LEN as u64 && end == file_len)
        .ok_or_else(|| {
            corrupt(format!(
                "section table at {table_offset} for {n_sections} sections in {file_len} bytes"
            ))
        })?;
    Ok(&bytes[table_offset as usize..table_end as usize])
}

/// The structure kind that content code `code` names (`None` for a complex alone).
fn content_kind(
    code: u32,
    corrupt: &dyn Fn(String) -> StoreError,
) -> Result<Option<StructureKind>, StoreError> {
    Ok(match code {
        0 => None,
        // Content code = kind + 1; the live complex (kind 9) is not in ALL.
        k => Some(
            StructureKind::ALL
                .into_iter()
                .chain([StructureKind::IaStar])
                .find(|s| s.abi() + 1 == k)
                .ok_or_else(|| corrupt(format!("unknown content code {k}")))?,
        ),
    })
}

fn parse_table(
    table: &[u8],
    table_offset: u64,
    corrupt: &dyn Fn(String) -> StoreError,
) -> Result<Vec<Entry>, StoreError> {
    let mut entries = Vec::with_capacity(table.len() / ENTRY_LEN);
    for (i, raw) in table.chunks_exact(ENTRY_LEN).enumerate() {
        let u64_at = |o: usize| u64::from_ne_bytes(raw[o..o + 8].try_into().unwrap());
        let e = Entry {
            offset: u64_at(0),
            count: u64_at(8),
            size: u32::from_ne_bytes(raw[16..20].try_into().unwrap()),
            checksum: u64_at(24),
        };
        if !(1..=64).contains(&e.size) {
            return Err(corrupt(format!("section {i}: element size {}", e.size)));
        }
        let end = e
            .count
            .checked_mul(e.size as u64)
            .and_then(|n| n.checked_add(e.offset));
        let fits = end.is_some_and(|end| end <= table_offset);
        if !fits || e.offset < HEADER_LEN as u64 || !e.offset.is_multiple_of(ALIGN) {
            return Err(corrupt(format!(
                "section {i}: {} elements of {} bytes at offset {} do not fit before the table at {table_offset}",
                e.count, e.size, e.offset
            )));
        }
        entries.push(e);
    }
    // Section 0 repeats the magic number: a cheap check that offsets mean what they say.
    match entries.first() {
        Some(e) if e.size == 1 && e.count == MAGIC.len() as u64 => Ok(entries),
        _ => Err(corrupt("section 0 is not the magic number".into())),
    }
}
