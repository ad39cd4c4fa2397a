//! The stars of the live complex in one flat arena: every vertex's St*(v) is a block of one
//! `u32` array, named by its start, length and capacity (12 bytes per vertex), instead of a
//! `Vec` per vertex (a 24-byte header plus a heap block with the allocator's own header, and
//! freed blocks that the allocator keeps for itself).
//!
//! # Layout and costs
//! - `words`: the blocks, back to back. A complex built from a list of tops gets each vertex's
//!   block at exactly its degree (the arena is Σ_v deg(v) words), and the allocation 1/8 of
//!   spare room at its end (address space: its pages are touched only when used). A run of
//!   contractions frees more than it appends, so that room is used up only when 1/8 of the
//!   arena is free and the arena is compacted in place rather than reallocated: a
//!   reallocation would hold the old and the new arena at once (and, in glibc's heap, leave
//!   the old one's pages resident).
//! - A block that must grow moves: in place when it ends the arena, else into a free block of
//!   its size class or onto the end of the arena. Size classes are 1..8, then four per doubling
//!   (10, 12, 14, 16, 20, 24, …), so a star growing one entry at a time moves O(log k) times
//!   and copies O(k) words in all: a push is amortised O(1).
//! - A freed block (a moved block's old room, a contracted vertex's star) goes on the free list
//!   of the largest class it holds (its rest is lost until the next compaction).
//! - When the arena's allocation is full and at least 1/8 of it is free, the blocks are slid
//!   down in address order (in place, O(arena + vertices), a bitmap of block starts as the only
//!   scratch); otherwise the allocation grows by 1/8. So the arena grows only while less than
//!   1/8 of it is free: its length stays below 8/7 of the largest Σ_v cap(v) it has held,
//!   plus one growth step, and every push stays amortised O(1).
//! - Removal from a star is a swap with its last entry (order is not kept); a star never
//!   shrinks its block, except [`Stars::release`], which frees it.
//!
//! Bytes: 4 per arena word of its allocation (Σ_v cap(v), free room, and 1/8 spare after a
//! build) + 12 per vertex.

use std::ops::{Index, IndexMut};

use crate::relation::StructureKind;
use crate::structures::BuildError;
use crate::structures::common::{too_large, try_with_capacity};

/// "No block" in a free list.
const END: u32 = u32::MAX;
/// Size classes: 8 small ones and four per doubling from 8 to 2^32.
const CLASSES: usize = 8 + 4 * 29;

/// One vertex's block in the arena. `repr(C)` and plain words, so the block table can be lent
/// as three `u32`s per vertex ([`Stars::lend`]).
#[derive(Debug, Clone, Copy, Default, bytemuck::Pod, bytemuck::Zeroable)]
#[repr(C)]
struct Block {
    start: u32,
    len: u32,
    cap: u32,
}

/// The stars of every vertex slot, in one arena; see the module doc.
#[derive(Debug, Clone)]
pub(crate) struct Stars {
    words: Vec<u32>,
    blocks: Vec<Block>,
    /// Per size class, the start of its first free block (the next one's start is the block's
    /// first word), or `END`.
    free: Vec<u32>,
    /// Σ cap over the vertices' blocks (the rest of `words` is free or lost).
    owned: usize,
}

/// Words of size class `c`.
fn class_size(c: usize) -> usize {
    if c < 8 {
        return c + 1;
    }
    let (doubling, quarter) = ((c - 8) / 4, (c - 8) % 4);
    (8usize << doubling) + (quarter + 1) * (2usize << doubling)
}

/// The smallest class holding `n ≥ 1` words.
fn class_at_least(n: usize) -> usize {
    if n <= 8 {
        return n - 1;
    }
    // n in (8·2^d, 16·2^d]: quarters of 2·2^d words.
    let d = (usize::BITS - 1 - ((n - 1) / 8).leading_zeros()) as usize;
    let step = 2usize << d;
    8 + 4 * d + (n - 1 - (8usize << d)) / step
}

/// The largest class that fits in `n ≥ 1` words.
fn class_at_most(n: usize) -> usize {
    let c = class_at_least(n);
    if class_size(c) > n { c - 1 } else { c }
}

impl Stars {
    /// Empty stars for `degrees.len()` vertices, each block reserved at exactly its degree
    /// (fill them with [`Stars::push`]). Fallible: [`BuildError::TooLarge`] when the arena or
    /// the block table cannot be allocated or the arena would pass 2^32 words.
    pub(crate) fn with_degrees(kind: StructureKind, degrees: &[u32]) -> Result<Stars, BuildError> {
        let total: usize = degrees.iter().map(|&k| k as usize).sum();
        if total > u32::MAX as usize {
            return Err(too_large(kind, total * 4, "star entries (at most 2^32)"));
        }
        let mut blocks = try_with_capacity(kind, degrees.len(), "vertex stars")?;
        let mut start = 0u32;
        for &k in degrees {
            blocks.push(Block {
                start,
                len: 0,
                cap: k,
            });
            start += k;
        }
        let mut words = try_with_capacity(kind, total + total / 8, "star entries")?;
        words.resize(total, 0);
        Ok(Stars {
            words,
            blocks,
            free: vec![END; CLASSES],
            owned: total,
        })
    }

    /// The stars of a CSR layout: vertex v's star is `entries[off[v] .. off[v + 1]]`, its block
    /// at exactly its length, and 1/8 of spare room after the arena, as [`Stars::with_degrees`]
    /// followed by a push of every entry in order leaves them. Fallible as `with_degrees`.
    pub(crate) fn from_csr(
        kind: StructureKind,
        off: &[u32],
        mut entries: Vec<u32>,
    ) -> Result<Stars, BuildError> {
        let total = entries.len();
        let n = off.len() - 1;
        let mut blocks = try_with_capacity(kind, n, "vertex stars")?;
        blocks.extend(off.windows(2).map(|w| Block {
            start: w[0],
            len: w[1] - w[0],
            cap: w[1] - w[0],
        }));
        if entries.capacity() != total + total / 8 {
            // The arena's spare room; the inversion sized `entries` exactly. Grown in place
            // (a large block is remapped, not copied), and shrunk if it was larger.
            entries.shrink_to_fit();
            entries
                .try_reserve_exact(total / 8)
                .map_err(|_| too_large(kind, 4 * (total + total / 8), "star entries"))?;
        }
        Ok(Stars {
            words: entries,
            blocks,
            free: vec![END; CLASSES],
            owned: total,
        })
    }

    /// Number of vertex slots.
    pub(crate) fn len(&self) -> usize {
        self.blocks.len()
    }

    /// Adds a vertex slot with an empty star. Amortised O(1).
    pub(crate) fn add_vertex(&mut self) {
        self.blocks.push(Block::default());
    }

    /// Every vertex's star, by vertex slot.
    pub(crate) fn iter(&self) -> impl Iterator<Item = &[u32]> + '_ {
        (0..self.blocks.len()).map(move |v| &self[v])
    }

    /// The arena and the block table as plain words (start, length, capacity per vertex slot),
    /// for inline navigation ([`super::LiveArrays`]). O(1), nothing copied.
    pub(crate) fn lend(&self) -> (&[u32], &[u32]) {
        (&self.words, bytemuck::cast_slice(&self.blocks))
    }

    /// Total entries over all stars. O(vertices).
    pub(crate) fn entries(&self) -> usize {
        self.blocks.iter().map(|b| b.len as usize).sum()
    }

    /// Bytes held: the arena's allocation, the block table's, the free-list heads.
    pub(crate) fn bytes(&self) -> usize {
        4 * self.words.capacity() + 12 * self.blocks.capacity() + 4 * self.free.capacity()
    }

    /// Appends `x` to St*(v). Amortised O(1) (module doc).
    pub(crate) fn push(&mut self, v: u32, x: u32) {
        let b = self.blocks[v as usize];
        if b.len == b.cap {
            self.reserve(v, 1);
        }
        let b = &mut self.blocks[v as usize];
        self.words[(b.start + b.len) as usize] = x;
        b.len += 1;
    }

    /// Makes room in St*(v) for `more` entries beyond its length, moving its block at most once.
    pub(crate) fn reserve(&mut self, v: u32, more: usize) {
        let b = self.blocks[v as usize];
        let need = b.len as usize + more;
        if need <= b.cap as usize {
            return;
        }
        assert!(
            need <= u32::MAX as usize,
            "a star of more than 2^32 entries"
        );
        if b.cap > 0 && (b.start + b.cap) as usize == self.words.len() {
            self.extend_tail(v, need);
            return;
        }
        let c = class_at_least(need);
        let (to, cap) = match self.pop_free(c) {
            Some((start, k)) => (start, class_size(k)),
            None => {
                let cap = class_size(c);
                self.make_room(cap);
                let start = self.words.len();
                assert!(
                    start + cap <= u32::MAX as usize,
                    "more than 2^32 star entries"
                );
                self.words.resize(start + cap, 0);
                (start as u32, cap)
            }
        };
        // Read again: a compaction in `make_room` moves blocks.
        let b = self.blocks[v as usize];
        self.words
            .copy_within(b.start as usize..(b.start + b.len) as usize, to as usize);
        self.free_block(b.start, b.cap);
        self.owned += cap;
        self.blocks[v as usize] = Block {
            start: to,
            len: b.len,
            cap: cap as u32,
        };
    }

    /// Grows the block of `v`, which ends the arena, in place to the class holding `need`.
    fn extend_tail(&mut self, v: u32, need: usize) {
        let more = class_size(class_at_least(need)) - self.blocks[v as usize].cap as usize;
        if self.words.len() + more > self.words.capacity() {
            // No compaction here: the block would move; grow the allocation by 1/8 at least.
            self.words.reserve_exact(more.max(self.words.len() / 8));
        }
        assert!(
            self.words.len() + more <= u32::MAX as usize,
            "more than 2^32 star entries"
        );
        self.words.resize(self.words.len() + more, 0);
        self.blocks[v as usize].cap += more as u32;
        self.owned += more;
    }

    /// Before appending `more` words: compacts when the allocation is full and 1/8 of it is
    /// free, else lets it grow by 1/8 at least.
    fn make_room(&mut self, more: usize) {
        if self.words.len() + more <= self.words.capacity() {
            return;
        }
        if 8 * (self.words.len() - self.owned) >= self.words.len() {
            self.compact_arena();
        }
        if self.words.len() + more > self.words.capacity() {
            self.words.reserve_exact(more.max(self.words.len() / 8));
        }
    }

    /// A free block of class `c` or up to two classes above, if any: its start and class.
    fn pop_free(&mut self, c: usize) -> Option<(u32, usize)> {
        (c..(c + 3).min(CLASSES)).find_map(|k| {
            let start = self.free[k];
            (start != END).then(|| {
                self.free[k] = self.words[start as usize];
                (start, k)
            })
        })
    }

    /// Puts the block [start, start + cap) on a free list (nothing for an empty one).
    fn free_block(&mut self, start: u32, cap: u32) {
        self.owned -= cap as usize;
        if cap == 0 {
            return;
        }
        let c = class_at_most(cap as usize);
        self.words[start as usize] = self.free[c];
        self.free[c] = start;
    }

    /// Removes entry `i` of St*(v) by moving its last entry there. O(1).
    pub(crate) fn swap_remove(&mut self, v: u32, i: usize) {
        let b = &mut self.blocks[v as usize];
        assert!(i < b.len as usize, "star entry {i} of {}", b.len);
        b.len -= 1;
        let s = b.start as usize;
        self.words[s + i] = self.words[s + b.len as usize];
    }

    /// Empties St*(v) and frees its block. O(1).
    pub(crate) fn release(&mut self, v: u32) {
        let b = std::mem::take(&mut self.blocks[v as usize]);
        self.free_block(b.start, b.cap);
    }

    /// Slides every block down to the start of the arena in address order, dropping the free
    /// lists. In place: a block's first word is parked in its `start` while the word holds the
    /// vertex, found again through a bitmap of block starts. O(arena / 64 + vertices + moved).
    fn compact_arena(&mut self) {
        let mut starts = vec![0u64; self.words.len() / 64 + 1];
        for (v, b) in self.blocks.iter_mut().enumerate() {
            if b.cap > 0 {
                let s = b.start as usize;
                starts[s / 64] |= 1 << (s % 64);
                b.start = std::mem::replace(&mut self.words[s], v as u32);
            } else {
                // An empty block's start must stay inside the shrunk arena: St*(v) is the
                // slice words[start .. start], which panics past the end.
                b.start = 0;
            }
        }
        let mut to = 0usize;
        for (w, &bits) in starts.iter().enumerate() {
            let mut bits = bits;
            while bits != 0 {
                let at = w * 64 + bits.trailing_zeros() as usize;
                bits &= bits - 1;
                let b = &mut self.blocks[self.words[at] as usize];
                let cap = b.cap as usize;
                self.words.copy_within(at + 1..at + cap, to + 1);
                self.words[to] = b.start;
                b.start = to as u32;
                to += cap;
            }
        }
        self.words.truncate(to);
        self.free.fill(END);
    }

    /// Keeps the vertex slots whose `keep` is true, in order, and packs the arena with each
    /// block at its length (no spare room, allocation shrunk). O(arena + vertices).
    pub(crate) fn retain_packed(&mut self, keep: &[bool]) {
        let mut next = 0;
        for (v, &kept) in keep.iter().enumerate().take(self.blocks.len()) {
            if kept {
                self.blocks[next] = self.blocks[v];
                next += 1;
            } else {
                let b = std::mem::take(&mut self.blocks[v]);
                self.owned -= b.cap as usize;
            }
        }
        self.blocks.truncate(next);
        for b in &mut self.blocks {
            self.owned -= (b.cap - b.len) as usize;
            b.cap = b.len;
            if b.cap == 0 {
                b.start = 0;
            }
        }
        self.compact_arena();
        self.words.shrink_to_fit();
        self.blocks.shrink_to_fit();
    }

    /// The arena's invariants: blocks and free blocks inside it and disjoint, lengths within
    /// capacities, the owned count right. O(arena + vertices).
    pub(crate) fn check(&self) -> Result<(), String> {
        let mut used = vec![false; self.words.len()];
        let mut claim = |start: usize, cap: usize, what: &dyn Fn() -> String| {
            if start + cap > used.len() {
                return Err(format!("{} runs past the star arena", what()));
            }
            for u in &mut used[start..start + cap] {
                if std::mem::replace(u, true) {
                    return Err(format!("{} overlaps another star block", what()));
                }
            }
            Ok(())
        };
        let mut owned = 0;
        for (v, b) in self.blocks.iter().enumerate() {
            if b.len > b.cap {
                return Err(format!("star of {v} holds {} entries in {}", b.len, b.cap));
            }
            owned += b.cap as usize;
            claim(b.start as usize, b.cap as usize, &|| format!("star of {v}"))?;
        }
        if owned != self.owned {
            return Err(format!(
                "star blocks own {owned} words, counted {}",
                self.owned
            ));
        }
        for (c, &head) in self.free.iter().enumerate() {
            let mut at = head;
            while at != END {
                claim(at as usize, class_size(c), &|| {
                    format!("free star block at {at}")
                })?;
                at = self.words[at as usize];
            }
        }
        Ok(())
    }
}

impl Index<usize> for Stars {
    type Output = [u32];

    /// St*(v) as a slice. O(1).
    fn index(&self, v: usize) -> &[u32] {
        let b = self.blocks[v];
        &self.words[b.start as usize..(b.start + b.len) as usize]
    }
}

impl IndexMut<usize> for Stars {
    /// St*(v) as a mutable slice (entries rewritten in place). O(1).
    fn index_mut(&mut self, v: usize) -> &mut [u32] {
        let b = self.blocks[v];
        &mut self.words[b.start as usize..(b.start + b.len) as usize]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const K: StructureKind = StructureKind::IaStar;

    #[test]
    fn classes_cover_every_size_once() {
        for n in 1..5000usize {
            let c = class_at_least(n);
            assert!(
                class_size(c) >= n && (c == 0 || class_size(c - 1) < n),
                "n = {n}"
            );
            let m = class_at_most(n);
            assert!(class_size(m) <= n && class_size(m + 1) > n, "n = {n}");
        }
        assert_eq!(
            (0..14).map(class_size).collect::<Vec<_>>(),
            [1, 2, 3, 4, 5, 6, 7, 8, 10, 12, 14, 16, 20, 24]
        );
        assert!(class_size(CLASSES - 1) >= u32::MAX as usize);
    }

    /// Three vertices of degrees 2, 0, 3 (arena `[a a | c c c]`); vertex 0 grows past its room
    /// and moves to the end, vertex 2 is released and its room reused, then a compaction.
    #[test]
    fn blocks_grow_move_and_compact() {
        let mut s = Stars::with_degrees(K, &[2, 0, 3]).unwrap();
        for (v, x) in [(0, 10), (0, 11), (2, 20), (2, 21), (2, 22)] {
            s.push(v, x);
        }
        assert_eq!(s.words.len(), 5);
        s.push(0, 12);
        assert_eq!(&s[0], &[10, 11, 12]);
        assert_eq!(s.blocks[0].start, 5, "moved onto the end");
        s.check().unwrap();
        s.release(2);
        s.push(1, 30);
        s.push(1, 31);
        s.push(1, 32);
        assert_eq!(s.blocks[1].start, 2, "took vertex 2's freed room");
        s.swap_remove(0, 0);
        assert_eq!(&s[0], &[12, 11]);
        s.check().unwrap();
        s.compact_arena();
        s.check().unwrap();
        assert_eq!(s.words.len(), 3 + 3, "vertex 0's old room dropped");
        assert_eq!(
            (&s[0], &s[1], &s[2]),
            (&[12, 11][..], &[30, 31, 32][..], &[][..])
        );
        s.retain_packed(&[false, true, true]);
        s.check().unwrap();
        assert_eq!((s.len(), &s[0], s.words.len()), (2, &[30, 31, 32][..], 3));
    }

    /// An isolated vertex built last (degree 0: its block starts at the arena's end, 4) keeps a
    /// readable, empty star after a compaction shrinks the arena below that start.
    #[test]
    fn an_empty_star_after_the_arena_shrinks() {
        let mut s = Stars::with_degrees(K, &[4, 0]).unwrap();
        for x in 0..4 {
            s.push(0, x);
        }
        s.release(0);
        s.push(0, 7);
        s.compact_arena();
        s.check().unwrap();
        assert_eq!(s.words.len(), 1);
        assert_eq!((&s[0], &s[1]), (&[7][..], &[][..]));
    }

    /// One star growing one entry at a time to 10,000 entries beside a neighbour that keeps
    /// moving: entries kept, arena below twice what the blocks own.
    #[test]
    fn a_growing_hub_keeps_its_entries() {
        let mut s = Stars::with_degrees(K, &[1, 1]).unwrap();
        for x in 0..10_000u32 {
            s.push(0, x);
            if x % 7 == 0 {
                s.push(1, x);
            }
        }
        s.check().unwrap();
        assert!(s[0].iter().copied().eq(0..10_000));
        assert!(s[1].iter().copied().eq((0..10_000).filter(|x| x % 7 == 0)));
        assert!(
            s.words.len() < 2 * s.owned,
            "{} words for {}",
            s.words.len(),
            s.owned
        );
    }
}
