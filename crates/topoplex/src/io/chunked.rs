//! Sections of one entry per line parsed on several threads, with the serial reader's result.
//!
//! A section whose entries each hold a fixed number of numbers (MEDIT vertices and elements,
//! OFF vertices and faces) is, in nearly every file, one entry per line. When a section is
//! large and the split threshold of [`crate::parallel::splits`] is reached, the reader first
//! finds the section's lines (one `memchr` pass over its line ends), cuts them into ranges of
//! whole lines, and parses each range on its own thread straight into the output array, at the
//! position its first line fixes (the output is reserved and zero-filled beforehand: nothing is
//! copied afterwards, nothing is held twice).
//!
//! The ranges read every number exactly as the serial reader does (the same [`Scanner`] fast
//! paths and general parsers), but within the line. Whenever a range meets anything else — an
//! error, a line that holds more or fewer numbers than an entry (the serial reader would carry
//! on across the line end), a blank or comment line, a file that ends before the section's last
//! line — the attempt is dropped (the output truncated back) and the serial reader reads the
//! section from its start. So a file gives the same result and the same first error, with the
//! same line and message, whatever the thread count; only a file with an error pays for two
//! reads of that section.

use std::sync::atomic::{AtomicUsize, Ordering};

use super::scan::Scanner;

pub(crate) use crate::parallel::{extend_filled, extend_with};

/// Sections read on several threads so far (see [`sections_read`]).
static SECTIONS: AtomicUsize = AtomicUsize::new(0);

/// How many sections the readers have read on several threads in this process: tests check
/// that the parallel path did run, not only the serial one.
pub fn sections_read() -> usize {
    SECTIONS.load(Ordering::Relaxed)
}

/// The lines of a section: `n` lines from a line start, cut into ranges of whole lines.
pub(crate) struct Body {
    /// Byte where each range starts, and one past the last line's end (after its line end).
    pub(crate) cuts: Vec<usize>,
    /// Lines per range (the last range may hold fewer).
    pub(crate) step: usize,
    /// Lines in all.
    pub(crate) lines: usize,
    /// Line number of the first line.
    pub(crate) first_line: u32,
    /// Where the serial scanner would stand after the section's last entry, once it moves to
    /// the next token: the byte after the last line's end (or the end of the text) and that
    /// line's number (see [`Scanner::place`]).
    pub(crate) end: (usize, u32),
}

/// The `n` lines starting at byte `start` (a line start, line `line`) cut into about
/// [`crate::parallel::threads`]` × 4` ranges; `None` when the text has fewer lines, or when
/// the line numbers would overflow. One pass over the line ends (`\n`, `\r\n` or a lone `\r`,
/// as [`Scanner`] counts them).
pub(crate) fn body(text: &str, start: usize, line: u32, n: usize) -> Option<Body> {
    if n == 0 || u32::try_from(n).ok()?.checked_add(line).is_none() {
        return None;
    }
    let b = text.as_bytes();
    let parts = (4 * crate::parallel::threads()).clamp(1, n);
    let step = n.div_ceil(parts);
    let mut cuts = Vec::with_capacity(parts + 1);
    cuts.push(start);
    let (mut ends, mut line_start) = (0usize, start);
    for k in memchr::memchr2_iter(b'\n', b'\r', &b[start..]) {
        let at = start + k;
        if b[at] == b'\r' && b.get(at + 1) == Some(&b'\n') {
            continue; // the `\n` next ends the line
        }
        ends += 1;
        line_start = at + 1;
        if ends % step == 0 || ends == n {
            cuts.push(line_start);
        }
        if ends == n {
            break;
        }
    }
    let end = if ends == n {
        (line_start, line + n as u32)
    } else if ends + 1 == n && line_start < b.len() {
        // The last line has no line end: the scanner stays on it at the end of the text.
        cuts.push(b.len());
        (b.len(), line + ends as u32)
    } else {
        return None;
    };
    Some(Body {
        cuts,
        step,
        lines: n,
        first_line: line,
        end,
    })
}

/// Parses the body's lines into `out`, `per` items per line: `entry(scanner, items)` reads
/// one line's entry (the scanner stands at the line's start and must be left at its end),
/// `None` when the line is not a plain entry. The ranges run on [`crate::parallel::threads`]
/// threads; false when any line failed (then `out` holds garbage the caller drops).
pub(crate) fn fill<T: Send>(
    text: &str,
    body: &Body,
    out: &mut [T],
    per: usize,
    entry: impl Fn(&mut Scanner<'_>, &mut [T]) -> Option<()> + Sync + Send,
) -> bool {
    fill_with_side::<T, ()>(text, body, out, per, &mut [], |sc, items, _| {
        entry(sc, items)
    })
}

/// [`fill`] with one more value per line kept apart in `side` (a MEDIT element's reference
/// beside its vertex ids): `side` is empty (nothing kept; `entry` gets `None`) or holds one
/// slot per line.
pub(crate) fn fill_with_side<T: Send, S: Send>(
    text: &str,
    body: &Body,
    out: &mut [T],
    per: usize,
    side: &mut [S],
    entry: impl Fn(&mut Scanner<'_>, &mut [T], Option<&mut S>) -> Option<()> + Sync + Send,
) -> bool {
    use rayon::prelude::*;
    let run = |r: usize, part: &mut [T], mut side: Option<&mut [S]>| -> bool {
        let (a, z) = (body.cuts[r], body.cuts[r + 1]);
        let first = body.first_line + (r * body.step) as u32;
        let mut sc = Scanner::at_line(&text[..z], a, first);
        for (k, items) in part.chunks_mut(per.max(1)).enumerate() {
            let slot = side.as_deref_mut().and_then(|s| s.get_mut(k));
            if entry(&mut sc, items, slot).is_none() || sc.token_in_line().is_some() {
                return false;
            }
            sc.next_line();
        }
        sc.pos() == z
    };
    if per == 0 || out.len() != per * body.lines || !(side.is_empty() || side.len() == body.lines) {
        debug_assert!(false, "the output does not match the lines");
        return false;
    }
    let read = crate::parallel::install(|| {
        let parts = out.par_chunks_mut(per * body.step).enumerate();
        if side.is_empty() {
            parts.all(|(r, part)| run(r, part, None))
        } else {
            parts
                .zip(side.par_chunks_mut(body.step))
                .all(|((r, part), side)| run(r, part, Some(side)))
        }
    });
    if read {
        note_section();
    }
    read
}

/// Counts one section read on several threads (see [`sections_read`]).
pub(crate) fn note_section() {
    SECTIONS.fetch_add(1, Ordering::Relaxed);
}

/// `text` cut into about [`crate::parallel::threads`]` × 4` ranges of whole lines (each cut
/// just after a line end): the byte where each range starts, and the text's end.
pub(crate) fn line_ranges(text: &str) -> Vec<usize> {
    let b = text.as_bytes();
    let parts = 4 * crate::parallel::threads();
    let mut cuts = vec![0];
    for k in 1..parts {
        let from = (b.len() / parts * k).max(*cuts.last().unwrap_or(&0));
        let Some(at) = memchr::memchr2(b'\n', b'\r', &b[from..]).map(|i| from + i) else {
            break;
        };
        let next = if b[at] == b'\r' && b.get(at + 1) == Some(&b'\n') {
            at + 2
        } else {
            at + 1
        };
        if next < b.len() && next > *cuts.last().unwrap_or(&0) {
            cuts.push(next);
        }
    }
    cuts.push(b.len());
    cuts
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bodies_of_lines_with_every_line_end() {
        let text = "head\na\r\nb\rc\nd";
        let b = body(text, 5, 2, 4).unwrap();
        assert_eq!(*b.cuts.first().unwrap(), 5);
        assert_eq!(*b.cuts.last().unwrap(), text.len());
        assert_eq!(b.end, (text.len(), 5));
        let b = body(text, 5, 2, 3).unwrap();
        assert_eq!(*b.cuts.last().unwrap(), 12);
        assert_eq!(b.end, (12, 5));
        assert!(body(text, 5, 2, 5).is_none());
        assert!(body("x\n", 2, 2, 1).is_none());
        let b = body("x\ny\n", 2, 2, 1).unwrap();
        assert_eq!(b.end, (4, 3));
    }
}
