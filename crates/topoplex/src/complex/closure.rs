//! The closure: every simplex of the complex by dimension, each table in ascending
//! lexicographic order ([`Complex::closure`]), made by vertex blocks (`blocks.rs`), else from
//! every subset of each top simplex packed in words, else level by level; and the closure's
//! size for the [`Budget`](super::Budget) check of normalisation: an upper bound
//! ([`closure_bound`]) and an exact count ([`closure_count`]).
//!
//! Costs: the closure at most O(Σ_top 2^{p+1}) time (the bound the budget checks) and its own
//! size in memory, reserved fallibly by [`Complex::try_closure`]; the bound O(listed
//! simplices); the exact count the bound's work, and the faces at one vertex plus an entry per
//! listed id in memory.

use super::blocks::Want;
use super::table;
use super::{Complex, SimplexTable, write_facets};

/// A top simplex at a vertex: (dimension, row, position of the vertex in the row).
pub(super) type TopAt = (u8, u32, u8);

impl Complex {
    /// All simplices of the complex by dimension `0..=d`, each table in ascending lexicographic
    /// order (so the p-simplices are numbered by their position). Faces are made per block of
    /// their smallest vertex v, level by level, as ranks among the vertices above v packed in
    /// one word (`blocks.rs`); blocks come out in vertex order, so their concatenation is the
    /// sorted table. Ranges of vertices run on [`crate::parallel::threads`] threads. At most
    /// O(Σ_top 2^{p+1}) time (the closure bound the budget checks), the closure's size in
    /// memory. Where a block's ranks do not fit a word, every subset of each top at its
    /// smallest vertex in global ids, or (ids too wide for d of them) level by level.
    pub fn closure(&self) -> Vec<SimplexTable> {
        self.try_closure().unwrap_or_else(|bytes| {
            std::alloc::handle_alloc_error(
                std::alloc::Layout::array::<u8>(bytes).unwrap_or(std::alloc::Layout::new::<u8>()),
            )
        })
    }

    /// [`Self::closure`] with its memory reserved fallibly: `Err(bytes)` names the reservation
    /// that could not be had (structure builds turn it into `TooLarge`, not an abort).
    pub fn try_closure(&self) -> Result<Vec<SimplexTable>, usize> {
        let d = self.dimension();
        if d > 0
            && let Some(c) = self.closure_by_blocks(Want::Tables)?
        {
            return Ok(c.tables);
        }
        self.closure_by_words()
    }

    /// The closure from every subset of each top simplex at its smallest vertex, as global ids
    /// packed in words (level by level when d of them do not fit one): the path for blocks
    /// whose ranks do not fit a word.
    fn closure_by_words(&self) -> Result<Vec<SimplexTable>, usize> {
        let d = self.dimension();
        let bits = table::id_bits(self.n_vertices.saturating_sub(1));
        if d == 0 || d as u32 * bits > 64 {
            return self.closure_by_levels();
        }
        // The buckets grow by doubling pushes on worker threads (up to 3× their size while one
        // moves): probe for that over their bound first (every face of every top, repeats and
        // all, as ids), so that a refusal is an error, not an abort.
        let bound: usize = (1..=d)
            .map(|p| {
                self.tops[p]
                    .len()
                    .saturating_mul((p + 1) << p)
                    .saturating_mul(4)
            })
            .fold(0, usize::saturating_add);
        crate::parallel::headroom_for(bound / 4, bound.saturating_mul(3))?;
        let (off, at) = self.tops_at_vertices()?;
        let parts = crate::parallel::ranges_by_weight(&off);
        let buckets = crate::parallel::map_chunks(parts.len(), |c| {
            let mut out: Vec<Vec<u32>> = vec![Vec::new(); d + 1];
            let mut keys: Vec<Vec<u64>> = vec![Vec::new(); d + 1];
            for v in parts[c].clone() {
                let tops = at[off[v]..off[v + 1]]
                    .iter()
                    .map(|&(p, j, pos)| &self.tops[p as usize].get(j as usize)[pos as usize + 1..]);
                faces_above(v as u32, tops, bits, &mut keys, &mut out);
            }
            out
        });
        let mut levels = vec![SimplexTable::try_vertices(self.n_vertices)?];
        for q in 1..=d {
            let len: usize = buckets.iter().map(|b| b[q].len()).sum();
            let mut ids = Vec::new();
            ids.try_reserve_exact(len).map_err(|_| len * 4)?;
            for b in &buckets {
                ids.extend_from_slice(&b[q]);
            }
            levels.push(SimplexTable::from_sorted_unique(q + 1, ids));
        }
        Ok(levels)
    }

    /// For each vertex v, the top simplices of dimension ≥ 1 in which v is not the last vertex,
    /// as (dimension, row, position of v): CSR offsets over the vertices, entries.
    pub(super) fn tops_at_vertices(&self) -> Result<(Vec<usize>, Vec<TopAt>), usize> {
        let n = self.n_vertices as usize;
        let mut off = Vec::new();
        off.try_reserve_exact(n + 1).map_err(|_| (n + 1) * 8)?;
        off.resize(n + 1, 0usize);
        for t in self.tops.iter().skip(1) {
            for s in t.iter() {
                for &v in &s[..s.len() - 1] {
                    off[v as usize + 1] += 1;
                }
            }
        }
        for v in 0..n {
            off[v + 1] += off[v];
        }
        let mut fill = Vec::new();
        fill.try_reserve_exact(n + 1).map_err(|_| (n + 1) * 8)?;
        fill.extend_from_slice(&off);
        let mut at: Vec<TopAt> = Vec::new();
        at.try_reserve_exact(off[n]).map_err(|_| off[n] * 8)?;
        at.resize(off[n], (0u8, 0u32, 0u8));
        for (p, t) in self.tops.iter().enumerate().skip(1) {
            for (j, s) in t.iter().enumerate() {
                for (pos, &v) in s[..s.len() - 1].iter().enumerate() {
                    at[fill[v as usize]] = (p as u8, j as u32, pos as u8);
                    fill[v as usize] += 1;
                }
            }
        }
        Ok((off, at))
    }

    /// The closure level by level from the facets of the level above: O(Σ_p (p+1) n_p log n_p)
    /// time, the closure's size in memory. The same tables as [`Complex::closure`], for ids too
    /// wide to pack.
    pub(super) fn closure_by_levels(&self) -> Result<Vec<SimplexTable>, usize> {
        let d = self.dimension();
        let mut levels: Vec<SimplexTable> = vec![SimplexTable::default(); d + 1];
        levels[d] = self.tops[d].try_clone()?;
        for p in (0..d).rev() {
            if p == 0 {
                levels[0] = SimplexTable::try_vertices(self.n_vertices)?;
                break;
            }
            let above = &levels[p + 1];
            // The facets of each (p+1)-simplex at a fixed place: written on several threads.
            let w = (p + 2) * (p + 1);
            let len = above.len() * w + self.tops[p].as_flat().len();
            let mut rows = Vec::new();
            rows.try_reserve_exact(len).map_err(|_| len * 4)?;
            rows.resize(len, 0u32);
            let (facets, listed) = rows.split_at_mut(above.len() * w);
            crate::parallel::fill_rows(facets, w, |i, out| write_facets(above.get(i), out));
            listed.copy_from_slice(self.tops[p].as_flat());
            levels[p] = SimplexTable::try_from_rows(p + 1, rows)?.0;
        }
        if d == 0 {
            levels[0] = SimplexTable::try_vertices(self.n_vertices)?;
        }
        Ok(levels)
    }
}

/// Appends to `out[q]` (rows of q + 1 ids) the q-simplices whose smallest vertex is `v`, in
/// ascending order: every nonempty subset of each of `tops` (the vertices above v in a top
/// simplex at v, ascending), packed `bits` per id, sorted and deduplicated per dimension.
fn faces_above<'a>(
    v: u32,
    tops: impl Iterator<Item = &'a [u32]>,
    bits: u32,
    keys: &mut [Vec<u64>],
    out: &mut [Vec<u32>],
) {
    for k in keys.iter_mut() {
        k.clear();
    }
    for above in tops {
        for mask in 1u32..1 << above.len() {
            let mut key = 0u64;
            for (i, &x) in above.iter().enumerate() {
                if mask >> i & 1 != 0 {
                    key = key << bits | u64::from(x);
                }
            }
            keys[mask.count_ones() as usize].push(key);
        }
    }
    let id_mask = (1u64 << bits) - 1;
    for (q, k) in keys.iter_mut().enumerate().skip(1) {
        k.sort_unstable();
        k.dedup();
        for &key in k.iter() {
            out[q].push(v);
            for i in (0..q).rev() {
                out[q].push((key >> (bits * i as u32) & id_mask) as u32);
            }
        }
    }
}

/// Upper bound on the closure's size: every vertex, and every face of dimension ≥ 1 of every
/// listed (deduplicated) simplex, as if no face were shared. O(number of listed simplices).
pub(super) fn closure_bound(n: u32, tables: &[SimplexTable]) -> u64 {
    let faces = tables.iter().enumerate().skip(1).map(|(p, t)| {
        let per = (1u64 << (p + 1)) - p as u64 - 2;
        (t.len() as u64).saturating_mul(per)
    });
    faces.fold(u64::from(n), u64::saturating_add)
}

/// How far above the budget's limit the closure bound may be for [`closure_count`] to be tried
/// (its work is the bound).
pub(super) const EXACT_COUNT_FACTOR: u64 = 16;

/// The closure's exact size (every vertex and every distinct face of dimension ≥ 1 of a listed
/// simplex), or `None` once it passes `limit`. Each face is counted at its lowest vertex v: the
/// listed simplices at v give every subset of their vertices above v, told apart by a 64-bit
/// hash of the ids (a collision could only undercount by one in ~2^64). Work: the
/// [`closure_bound`]; memory: the faces at one vertex, plus one entry per listed id.
pub(super) fn closure_count(n: u32, tables: &[SimplexTable], limit: u64) -> Option<u64> {
    use std::hash::{BuildHasher, Hash, Hasher};
    if u64::from(n) > limit {
        return None;
    }
    // at[v]: (dimension, row) of every listed simplex of dimension ≥ 1 whose vertex v is.
    // Reserved fallibly: under a raised limit n may be large (then the input is refused).
    let mut off: Vec<usize> = Vec::new();
    off.try_reserve_exact(n as usize + 1).ok()?;
    off.resize(n as usize + 1, 0);
    for t in tables.iter().skip(1) {
        for &v in t.as_flat() {
            off[v as usize + 1] += 1;
        }
    }
    for v in 0..n as usize {
        off[v + 1] += off[v];
    }
    let mut fill = off.clone();
    let mut at: Vec<(u8, u32)> = Vec::new();
    at.try_reserve_exact(off[n as usize]).ok()?;
    at.resize(off[n as usize], (0, 0));
    for (p, t) in tables.iter().enumerate().skip(1) {
        for (j, row) in t.iter().enumerate() {
            for &v in row {
                at[fill[v as usize]] = (p as u8, j as u32);
                fill[v as usize] += 1;
            }
        }
    }
    let hasher = rustc_hash::FxBuildHasher;
    let mut faces: rustc_hash::FxHashSet<u64> = Default::default();
    let mut count = u64::from(n);
    for v in 0..n as usize {
        faces.clear();
        for &(p, j) in &at[off[v]..off[v + 1]] {
            let row = tables[p as usize].get(j as usize);
            let above = &row[row.iter().position(|&x| x as usize == v)? + 1..];
            for mask in 1u32..(1 << above.len()) {
                let mut h = hasher.build_hasher();
                for (i, x) in above.iter().enumerate() {
                    if mask & (1 << i) != 0 {
                        x.hash(&mut h);
                    }
                }
                faces.insert(h.finish());
            }
        }
        count += faces.len() as u64;
        if count > limit {
            return None;
        }
    }
    Some(count)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Random non-manifold complexes over few vertices (so faces are shared), dimension ≤ 6.
    fn random_complexes() -> impl Iterator<Item = Complex> {
        let mut rnd = crate::complex::xorshift_below(0x2545_f491_4f6c_dd1d);
        (0..300).map(move |_| {
            let n = 1 + rnd(16) as u32;
            crate::complex::random_complex(&mut rnd, n, 20, 7, (n as u64, 1))
        })
    }

    #[test]
    fn closure_by_vertex_buckets_equals_closure_by_levels() {
        for c in random_complexes() {
            assert_eq!(Ok(c.closure()), c.closure_by_levels());
            assert_eq!(c.closure_by_words(), c.closure_by_levels());
        }
    }

    #[test]
    fn ids_too_wide_to_pack_take_the_level_path() {
        // 2^20 vertices: 20 bits per id, so a 4-simplex's faces need 80 bits.
        let top = [3, 70_000, 500_000, 1_000_000, 1_048_575];
        let c = Complex::from_simplices(1 << 20, &[&top, &[3, 9]]).unwrap();
        let levels = c.closure();
        assert_eq!(Ok(levels.clone()), c.closure_by_levels());
        assert_eq!(levels[1].len(), 10 + 1);
        assert_eq!(levels[4].get(0), &top);
    }
}
