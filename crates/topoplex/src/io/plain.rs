//! Plain OFF files streamed straight into the arrays a mesh keeps ([`PlainTables`]): the read
//! that lets an application's mesh hold no copy of the file and no listing beside its tables
//! (`crate::store::open_live`).
//!
//! Only the plainest OFF is taken: the header `OFF`, the counts ending their line, one vertex
//! of 3 numbers a line, one face `k i1 .. ik` a line with k = 2 or 3 and nothing after it (no
//! colour), distinct ids below the vertex count, comments and blank lines anywhere, nothing
//! after the last face. Numbers go through the OFF reader's own scanner and parsers
//! ([`super::scan`]), so every value is the one it gives. On anything else — another header, an
//! entry over two lines or two on one, a colour, a 1-vertex face or a polygon, a number or id
//! it would refuse, a file that ends early or is not UTF-8 — the answer is `None`, with no
//! message: the caller reads the file the general way ([`super::read_path`]), which takes all
//! that OFF allows and names what is wrong. So the tables are the general reader's listing, or
//! nothing.
//!
//! Memory: the file passes through a buffer of 1 MiB (longer lines grow it, up to 64 MiB, then
//! the general read takes over); what stays is the coordinates (24 bytes a vertex), the tops
//! (4 bytes an id) and a use count (4 bytes a vertex), reserved from the declared counts when the
//! file's size could hold them. Cost: one serial pass over the bytes.

use std::io::Read;
use std::path::Path;

use super::off;
use super::scan::{self, Scanner};
use crate::alloc;
use crate::complex::{Coords, MAX_DIMENSION, PlainTables};

/// Bytes read at a time.
const PIECE: usize = 1 << 20;
/// The longest line the buffer grows for.
const LONGEST_LINE: usize = 64 << 20;
/// Text within which a plain OFF's header and counts must stand (comments before them
/// included); the buffer grows past it only for tests' tiny pieces.
const HEADER_TEXT: usize = 64 << 10;
/// The fewest bytes a vertex or face line takes (`0 0 0` and `2 0 1` with their line end): a
/// declared count beyond what the file could hold is not reserved (the general reader says the
/// file ends early).
const SHORTEST_ENTRY: usize = 6;

/// A plain OFF file's tables (see the module doc), or `None` for the general read (also for
/// a path whose extension is not `.off`, any case, as [`super::read_path`] chooses).
pub(crate) fn read_off(path: &Path) -> Option<PlainTables> {
    (super::extension(path) == "off").then(|| read_off_in_pieces(path, PIECE))?
}

/// Why the stream stops: the file is not plain (or memory is short); the general read decides.
struct NotPlain;

type Step<T> = Result<T, NotPlain>;

/// [`read_off`] through a buffer of `piece` bytes (small in tests, so that entries and line
/// ends fall across pieces).
fn read_off_in_pieces(path: &Path, piece: usize) -> Option<PlainTables> {
    let (mut file, meta) = super::open_regular(path).ok()?;
    let len = usize::try_from(meta.len()).ok()?;
    let mut off = Stream::new(len);
    let mut buf: Vec<u8> = Vec::new();
    alloc::try_grow(&mut buf, piece.min(len.saturating_add(1)).max(1)).ok()?;
    buf.resize(buf.capacity(), 0);
    let mut have = 0;
    loop {
        let n = file.read(&mut buf[have..]).ok()?;
        have += n;
        if n == 0 {
            // The end of the file: whatever is left is the last line.
            off.feed(std::str::from_utf8(&buf[..have]).ok()?, true)
                .ok()?;
            return off.finish();
        }
        if have < buf.len() {
            continue;
        }
        // Whole lines to the stream; the header waits until its counts' line is in.
        let fed = match buf[..have].iter().rposition(|&c| c == b'\n' || c == b'\r') {
            Some(end) => off
                .feed(std::str::from_utf8(&buf[..=end]).ok()?, false)
                .ok()?
                .then_some(end + 1),
            None => None,
        };
        match fed {
            Some(used) => {
                buf.copy_within(used..have, 0);
                have -= used;
            }
            None if buf.len() >= LONGEST_LINE => return None,
            None => {
                let more = buf.len();
                alloc::try_grow(&mut buf, more).ok()?;
                buf.resize(buf.capacity(), 0);
            }
        }
    }
}

/// Where the stream stands.
#[derive(PartialEq)]
enum Stage {
    Header,
    Vertices,
    Faces,
    Done,
}

/// The tables filled so far.
struct Stream {
    stage: Stage,
    file_len: usize,
    nv: u32,
    nf: u32,
    coords: Vec<f64>,
    tops: Vec<Vec<u32>>,
    uses: Vec<u32>,
    faces: u32,
}

impl Stream {
    fn new(file_len: usize) -> Stream {
        Stream {
            stage: Stage::Header,
            file_len,
            nv: 0,
            nf: 0,
            coords: Vec::new(),
            tops: Vec::new(),
            uses: Vec::new(),
            faces: 0,
        }
    }

    /// Reads `text`, whole lines (the file's last piece, `at_end`, may lack its line end).
    /// False when the header is not whole in it yet and the text is short (the caller gives
    /// more text).
    fn feed(&mut self, text: &str, at_end: bool) -> Step<bool> {
        let mut t = Scanner::new(text);
        if self.stage == Stage::Header {
            match self.header(&mut t) {
                // Only a short text may hold a header not yet whole: a piece's worth of text
                // without one is not a plain OFF (and is not read to the end to find out).
                Err(NotPlain) if !at_end && text.len() < HEADER_TEXT => return Ok(false),
                header => header?,
            }
        }
        loop {
            let more = match self.stage {
                Stage::Header => unreachable!("the header is read first"),
                Stage::Vertices => self.vertex(&mut t)?,
                Stage::Faces => self.face(&mut t)?,
                Stage::Done => match t.token() {
                    Some(_) => return Err(NotPlain),
                    None => false,
                },
            };
            if !more {
                return Ok(true);
            }
        }
    }

    /// The header `OFF` and the counts, alone on their line; the arrays reserved for them.
    /// Whatever is wrong, [`NotPlain`]: a header not yet whole in the text the caller has read
    /// so far looks the same, so the caller gives more text until the file ends.
    fn header(&mut self, t: &mut Scanner<'_>) -> Step<()> {
        let h = off::header(t).map_err(|_| NotPlain)?;
        let (nv, nf) = off::counts(t).map_err(|_| NotPlain)?;
        let fits = |n: u32| (n as usize) <= self.file_len / SHORTEST_ENTRY;
        if !h.is_plain() || t.token_in_line().is_some() || nv == 0 || !fits(nv) || !fits(nf) {
            return Err(NotPlain);
        }
        let room = |_| NotPlain;
        alloc::try_reserve_exact(&mut self.coords, 3 * nv as usize).map_err(room)?;
        alloc::try_reserve_exact(&mut self.uses, nv as usize).map_err(room)?;
        self.uses.resize(nv as usize, 0);
        alloc::try_reserve_exact(&mut self.tops, MAX_DIMENSION + 1).map_err(room)?;
        self.tops.resize_with(MAX_DIMENSION + 1, Vec::new);
        // Triangles, as meshes have them; edges grow their own table.
        alloc::try_reserve_exact(&mut self.tops[2], 3 * nf as usize).map_err(room)?;
        (self.nv, self.nf) = (nv, nf);
        self.stage = Stage::Vertices;
        Ok(())
    }

    /// The next vertex line; false when the piece has no more entries.
    fn vertex(&mut self, t: &mut Scanner<'_>) -> Step<bool> {
        let Some(x) = real(t, true)? else {
            return Ok(false);
        };
        let y = real(t, false)?.ok_or(NotPlain)?;
        let z = real(t, false)?.ok_or(NotPlain)?;
        if t.token_in_line().is_some() {
            return Err(NotPlain);
        }
        self.coords.extend_from_slice(&[x, y, z]);
        if self.coords.len() == 3 * self.nv as usize {
            self.stage = if self.nf == 0 {
                Stage::Done
            } else {
                Stage::Faces
            };
        }
        Ok(true)
    }

    /// The next face line; false when the piece has no more entries.
    fn face(&mut self, t: &mut Scanner<'_>) -> Step<bool> {
        let k = match t.digits(true) {
            Some((k @ 2..=3, _)) => k as usize,
            Some(_) => return Err(NotPlain),
            None if t.token().is_some() => return Err(NotPlain),
            None => return Ok(false),
        };
        let mut ids = [0u32; 3];
        for j in 0..k {
            let v = id(t)?;
            if v >= self.nv || ids[..j].contains(&v) {
                return Err(NotPlain);
            }
            ids[j] = v;
        }
        if t.token_in_line().is_some() {
            return Err(NotPlain);
        }
        alloc::try_extend(&mut self.tops[k - 1], &ids[..k]).map_err(|_| NotPlain)?;
        for &v in &ids[..k] {
            self.uses[v as usize] += 1;
        }
        self.faces += 1;
        if self.faces == self.nf {
            self.stage = Stage::Done;
        }
        Ok(true)
    }

    /// The tables, when the file held every declared entry.
    fn finish(mut self) -> Option<PlainTables> {
        if self.stage != Stage::Done {
            return None;
        }
        self.tops[2].shrink_to_fit();
        Some(PlainTables {
            vertex_count: self.nv,
            coords: Coords {
                dim: 3,
                data: self.coords,
            },
            tops: self.tops,
            uses: self.uses,
        })
    }
}

/// The next number (across line ends when `cross`, else on this line) as the OFF reader reads
/// it; `None` when there is no more token there.
fn real(t: &mut Scanner<'_>, cross: bool) -> Step<Option<f64>> {
    if let Some((x, _)) = t.real(cross) {
        return Ok(Some(x));
    }
    let tok = if cross { t.token() } else { t.token_in_line() };
    match tok {
        None => Ok(None),
        Some((tok, _)) => scan::real(tok.as_bytes()).map(Some).map_err(|_| NotPlain),
    }
}

/// The next vertex id on this line, as the OFF reader reads it.
fn id(t: &mut Scanner<'_>) -> Step<u32> {
    if let Some((v, _)) = t.digits(false) {
        return scan::id_value(v, false).map_err(|_| NotPlain);
    }
    let (tok, _) = t.token_in_line().ok_or(NotPlain)?;
    scan::id(tok, false).map_err(|_| NotPlain)
}

#[cfg(test)]
mod tests;
