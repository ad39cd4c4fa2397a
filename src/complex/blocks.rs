//! The closure by vertex blocks, with the boundary links when asked: the faces whose smallest
//! vertex is v (v's *block*) are made level by level inside the block, in the ranks of v's
//! neighbours above it, so every key fits one word whatever the ids' width.
//!
//! # Steps, per vertex v (ranges of vertices on [`crate::parallel::threads`] threads)
//! 1. N(v): the vertices above v in the top simplices at v, sorted; a face of v's block is v
//!    and a subset of N(v), written as the ranks of that subset packed `lb = bits(|N(v)| − 1)`
//!    per rank (the block fails, and the caller takes another path, when the longest subset
//!    needs more than 64 bits).
//! 2. Level by level downwards: the block's q-faces are its top simplices of dimension q and
//!    the facets that keep v of its (q+1)-faces; the candidates carry the slot they came from,
//!    so deduplicating a level also gives every slot but slot 0 its facet (the facet that drops
//!    vertex i ≥ 1 of a face lies in the same block). Small levels sort the candidates; levels
//!    of [`HASH_FROM`] candidates or more put them in a hash set and sort only the distinct
//!    faces (a Rips level has several candidates per face).
//! 3. Blocks are appended in vertex order to their range's buffers, the first range's buffers
//!    becoming the tables (nothing copied with one thread); local facet indices are shifted by
//!    the rows of the blocks before.
//! 4. Slot 0 (the facet without v) lies in the block of the face's second vertex: a search
//!    among that block's rows, packed as words past their first id, starting after the facet
//!    of the row before when both rows share their first two vertices (doubling steps).
//!
//! Work: Σ over the blocks' faces of (q+1) candidates, hashed or sorted in cache-sized blocks,
//! plus one search per simplex; memory: the closure's tables and links, and each block's
//! scratch.

use super::table::{headroom, id_bits};
use super::{Complex, SimplexTable, TopAt};

/// What [`Complex::closure_by_blocks`] makes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Want {
    /// The number of simplices of each dimension only.
    Counts,
    /// The tables.
    Tables,
    /// The tables and every simplex's boundary links.
    Links,
}

/// The closure made by [`Complex::closure_by_blocks`].
#[derive(Debug, Default)]
pub(crate) struct BlockClosure {
    /// Simplices per dimension `0..=d`.
    pub counts: Vec<usize>,
    /// The tables by dimension (empty for [`Want::Counts`]).
    pub tables: Vec<SimplexTable>,
    /// `boundary[p]` (p ≥ 1): per p-simplex, the rows in `tables[p − 1]` of its facets, entry i
    /// opposite its vertex i — as `structures::common::facet_links` (empty unless
    /// [`Want::Links`]).
    pub boundary: Vec<Vec<u32>>,
}

/// Slot 0 of a link row before step 4 fills it.
const UNSET: u32 = u32::MAX;

/// A candidate face of a block: its key (ranks) above the slot it came from.
trait Word: Copy + Ord + Send {
    fn pack(key: u64, origin: u32, ob: u32) -> Self;
    fn key(self, ob: u32) -> u64;
    fn origin(self, ob: u32) -> u32;
    fn buffer(s: &mut Scratch) -> &mut Vec<Self>;
}

impl Word for u64 {
    fn pack(key: u64, origin: u32, ob: u32) -> Self {
        key.checked_shl(ob).unwrap_or(0) | u64::from(origin)
    }
    fn key(self, ob: u32) -> u64 {
        self.checked_shr(ob).unwrap_or(0)
    }
    fn origin(self, ob: u32) -> u32 {
        (self & ((1u64 << ob) - 1)) as u32
    }
    fn buffer(s: &mut Scratch) -> &mut Vec<Self> {
        &mut s.cand64
    }
}

impl Word for u128 {
    fn pack(key: u64, origin: u32, ob: u32) -> Self {
        u128::from(key) << ob | u128::from(origin)
    }
    fn key(self, ob: u32) -> u64 {
        (self >> ob) as u64
    }
    fn origin(self, ob: u32) -> u32 {
        (self & ((1u128 << ob) - 1)) as u32
    }
    fn buffer(s: &mut Scratch) -> &mut Vec<Self> {
        &mut s.cand128
    }
}

/// One thread's buffers, reused from block to block.
#[derive(Default)]
struct Scratch {
    /// Per vertex id: its rank in the block's N(v), `u32::MAX` outside it.
    rank: Vec<u32>,
    nbr: Vec<u32>,
    /// Per level: the block's top simplices of that dimension, as keys.
    seeds: Vec<Vec<u64>>,
    /// Per level: the block's faces, as sorted keys.
    keys: Vec<Vec<u64>>,
    /// Per level q ≥ 2: q + 1 slots per face, slot i ≥ 1 the block-local row of its facet.
    links: Vec<Vec<u32>>,
    cand64: Vec<u64>,
    cand128: Vec<u128>,
    /// [`level_hashed`]'s open-addressed set: keys ([`EMPTY`] free) and their insertion ids.
    slot_keys: Vec<u64>,
    slot_ids: Vec<u32>,
    /// [`level_hashed`]'s distinct keys with their insertion ids, then each id's sorted row.
    distinct: Vec<(u64, u32)>,
    row_of: Vec<u32>,
}

/// A free slot of [`level_hashed`]'s set: no key is all ones (a key's ranks are distinct, so
/// a key of one rank has at most 32 bits and a longer key two different ranks).
const EMPTY: u64 = u64::MAX;

/// Levels with at least this many candidates deduplicate by hashing (fewer to sort).
const HASH_FROM: usize = 96;

/// [`HASH_FROM`], which tests move to run every level through one path or the other (both give
/// the same keys and links, so other tests running meanwhile are not disturbed).
/// The first position at or after `lo` in sorted `keys` whose key is not below `key`, found by
/// doubling steps from `lo` and then a binary search in the last step.
fn gallop(keys: &[u64], lo: usize, key: u64) -> usize {
    let (mut lo, mut step) = (lo, 1);
    while lo + step <= keys.len() && keys[lo + step - 1] < key {
        lo += step;
        step *= 2;
    }
    let hi = (lo + step).min(keys.len());
    lo + keys[lo..hi].partition_point(|&x| x < key)
}

#[cfg(test)]
static HASH_FROM_TEST: std::sync::atomic::AtomicUsize =
    std::sync::atomic::AtomicUsize::new(HASH_FROM);

fn hash_from() -> usize {
    #[cfg(test)]
    return HASH_FROM_TEST.load(std::sync::atomic::Ordering::Relaxed);
    #[cfg(not(test))]
    HASH_FROM
}

/// `len` more ids at the end of `v`, zeroed, for the caller to write (one capacity check per
/// block level instead of one per row). Growth doubles: large buffers are reallocated by
/// remapping their pages, not copying them, and the first part's buffers become the tables.
fn grow(v: &mut Vec<u32>, len: usize) -> &mut [u32] {
    let at = v.len();
    v.resize(at + len, 0);
    &mut v[at..]
}

/// One range of vertices' blocks, concatenated.
#[derive(Default)]
struct Part {
    counts: Vec<usize>,
    rows: Vec<Vec<u32>>,
    /// Per level q ≥ 1, q + 1 per row: slot 0 [`UNSET`] (q ≥ 2), others rows of the level
    /// below counted from this part's first.
    links: Vec<Vec<u32>>,
}

/// A block's shape: its ranks' width and its longest subset.
#[derive(Clone, Copy)]
struct Shape {
    lb: u32,
    dv: usize,
}

impl Complex {
    /// The closure by vertex blocks (module documentation); `Ok(None)` when some block's keys
    /// do not fit a word (more than 64 bits of ranks: e.g. two 15-simplices at a vertex with
    /// 17 neighbours above it), for the caller to take another path. `Err(bytes)` when memory
    /// cannot be had. The same tables as [`Complex::closure`] for any thread count.
    pub(crate) fn closure_by_blocks(&self, want: Want) -> Result<Option<BlockClosure>, usize> {
        let d = self.dimension();
        let n = self.n_vertices as usize;
        if want != Want::Counts {
            // Blocks grow by doubling pushes on worker threads: probe for their bound (every
            // face of every top, repeats and all) so that a refusal is an error, not an abort.
            let ids: usize = (1..=d)
                .map(|p| self.tops[p].len().saturating_mul((p + 1) << p))
                .fold(0, usize::saturating_add);
            let per = if want == Want::Links { 24 } else { 12 };
            headroom(ids.saturating_mul(per))?;
        }
        let (off, at) = self.tops_at_vertices()?;
        let parts = crate::parallel::ranges_by_weight(&off);
        let done = crate::parallel::map_chunks(parts.len(), |c| {
            let mut s = Scratch::default();
            // One rank per vertex id (a chunk at a time per thread: threads × 4n bytes).
            s.rank.try_reserve_exact(n).map_err(|_| n * 4)?;
            s.rank.resize(n, u32::MAX);
            let mut part = Part {
                counts: vec![0; d + 1],
                rows: vec![Vec::new(); d + 1],
                links: vec![Vec::new(); d + 1],
            };
            s.seeds = vec![Vec::new(); d + 1];
            s.keys = vec![Vec::new(); d + 1];
            s.links = vec![Vec::new(); d + 1];
            for v in parts[c].clone() {
                if !self.block(v as u32, &at[off[v]..off[v + 1]], want, &mut s, &mut part) {
                    return Ok(None);
                }
            }
            Ok(Some(part))
        });
        let done = done
            .into_iter()
            .collect::<Result<Vec<Option<Part>>, usize>>()?;
        let Some(mut parts) = done.into_iter().collect::<Option<Vec<Part>>>() else {
            return Ok(None);
        };
        let mut out = BlockClosure {
            counts: vec![n; d + 1],
            ..Default::default()
        };
        for q in 1..=d {
            out.counts[q] = parts.iter().map(|p| p.counts[q]).sum();
        }
        if want == Want::Counts {
            return Ok(Some(out));
        }
        out.tables = concat_rows(&mut parts, n as u32, d)?;
        if want == Want::Links {
            out.boundary = concat_links(&mut parts, d)?;
            for q in 2..=d {
                facets_without_first(&out.tables, q, &mut out.boundary[q])?;
            }
        }
        Ok(Some(out))
    }

    /// Step 1–2 for vertex v's block, appended to `part`; false when its keys do not fit.
    fn block(&self, v: u32, tops: &[TopAt], want: Want, s: &mut Scratch, part: &mut Part) -> bool {
        let above =
            |&(p, j, pos): &TopAt| &self.tops[p as usize].get(j as usize)[pos as usize + 1..];
        // N(v) once each (marked in `rank`), sorted, then each id's rank.
        s.nbr.clear();
        let mut dv = 0;
        for t in tops {
            let a = above(t);
            for &x in a {
                if s.rank[x as usize] == u32::MAX {
                    s.rank[x as usize] = 0;
                    s.nbr.push(x);
                }
            }
            dv = dv.max(a.len());
        }
        if dv == 0 {
            return true;
        }
        s.nbr.sort_unstable();
        for (i, &x) in s.nbr.iter().enumerate() {
            s.rank[x as usize] = i as u32;
        }
        let lb = id_bits(s.nbr.len() as u32 - 1);
        let fits = dv as u32 * lb <= 64;
        if fits {
            for q in 1..=dv {
                s.seeds[q].clear();
            }
            for t in tops {
                let a = above(t);
                let key = a
                    .iter()
                    .fold(0u64, |k, &x| k << lb | u64::from(s.rank[x as usize]));
                s.seeds[a.len()].push(key);
            }
        }
        for &x in &s.nbr {
            s.rank[x as usize] = u32::MAX;
        }
        if !fits {
            return false;
        }
        let shape = Shape { lb, dv };
        for q in (1..=dv).rev() {
            let from_above = if q < dv { s.keys[q + 1].len() } else { 0 };
            let Ok(sentinel) = u32::try_from(from_above * (q + 2)) else {
                return false;
            };
            let ob = if want == Want::Links {
                id_bits(sentinel)
            } else {
                0
            };
            let candidates = s.seeds[q].len() + from_above;
            if candidates >= hash_from() {
                level_hashed(q, shape, want, s);
            } else if q as u32 * lb + ob <= 64 {
                level::<u64>(q, shape, ob, sentinel, want, s);
            } else {
                level::<u128>(q, shape, ob, sentinel, want, s);
            }
        }
        emit(v, shape, want, s, part);
        true
    }
}

/// Level q of a block (step 2): its faces into `s.keys[q]`, and with [`Want::Links`] the
/// block-local facet of slots 1.. of every (q+1)-face into `s.links[q + 1]`.
fn level<W: Word>(q: usize, shape: Shape, ob: u32, sentinel: u32, want: Want, s: &mut Scratch) {
    let Shape { lb, dv } = shape;
    // Without links the words are bare keys.
    let tag = |o: u32| if ob == 0 { 0 } else { o };
    let mut cand = std::mem::take(W::buffer(s));
    cand.clear();
    cand.extend(s.seeds[q].iter().map(|&k| W::pack(k, tag(sentinel), ob)));
    if q < dv {
        // Keys of level q + 1 hold `len` ranks; dropping rank e keeps those above and below it.
        let len = q + 1;
        for (i, &k) in s.keys[q + 1].iter().enumerate() {
            for e in 0..len {
                let low = lb * (len - 1 - e) as u32;
                let hi = k.checked_shr(lb * (len - e) as u32).unwrap_or(0);
                let facet = hi << low | (k & ((1u64 << low) - 1));
                cand.push(W::pack(facet, tag((i * (len + 1) + e + 1) as u32), ob));
            }
        }
    }
    cand.sort_unstable();
    let links = want == Want::Links && q < dv;
    if links {
        let w = q + 2;
        s.links[q + 1].clear();
        s.links[q + 1].resize(s.keys[q + 1].len() * w, 0);
    }
    let keys = &mut s.keys[q];
    keys.clear();
    for &c in &cand {
        let key = c.key(ob);
        if keys.last() != Some(&key) {
            keys.push(key);
        }
        if links {
            let o = c.origin(ob);
            if o != sentinel {
                s.links[q + 1][o as usize] = (keys.len() - 1) as u32;
            }
        }
    }
    *W::buffer(s) = cand;
}

/// [`level`] for a level with many candidates: each candidate is put in a hash set (its slot's
/// link takes the key's insertion id), then only the distinct keys are sorted and the links
/// renamed from insertion ids to rows. The same keys and links as [`level`].
fn level_hashed(q: usize, shape: Shape, want: Want, s: &mut Scratch) {
    let Shape { lb, dv } = shape;
    let from_above = if q < dv { s.keys[q + 1].len() } else { 0 };
    let links = want == Want::Links && q < dv;
    let m = s.seeds[q].len() + from_above * (q + 1);
    let bits = (2 * m).next_power_of_two().trailing_zeros();
    let mask = (1usize << bits) - 1;
    s.slot_keys.clear();
    s.slot_keys.resize(1 << bits, EMPTY);
    s.slot_ids.resize(1 << bits, 0);
    s.distinct.clear();
    // The key's insertion id, inserting it when new.
    let insert = |key: u64, s_keys: &mut Vec<u64>, ids: &mut Vec<u32>, d: &mut Vec<(u64, u32)>| {
        let mut h = (key.wrapping_mul(0x9e37_79b9_7f4a_7c15) >> (64 - bits)) as usize;
        loop {
            if s_keys[h] == key {
                return ids[h];
            }
            if s_keys[h] == EMPTY {
                let id = d.len() as u32;
                s_keys[h] = key;
                ids[h] = id;
                d.push((key, id));
                return id;
            }
            h = (h + 1) & mask;
        }
    };
    for i in 0..s.seeds[q].len() {
        let k = s.seeds[q][i];
        insert(k, &mut s.slot_keys, &mut s.slot_ids, &mut s.distinct);
    }
    if links {
        s.links[q + 1].clear();
        s.links[q + 1].resize(from_above * (q + 2), 0);
    }
    if q < dv {
        let len = q + 1;
        for i in 0..from_above {
            let k = s.keys[q + 1][i];
            for e in 0..len {
                let low = lb * (len - 1 - e) as u32;
                let hi = k.checked_shr(lb * (len - e) as u32).unwrap_or(0);
                let facet = hi << low | (k & ((1u64 << low) - 1));
                let id = insert(facet, &mut s.slot_keys, &mut s.slot_ids, &mut s.distinct);
                if links {
                    s.links[q + 1][i * (len + 1) + e + 1] = id;
                }
            }
        }
    }
    s.distinct.sort_unstable();
    let keys = &mut s.keys[q];
    keys.clear();
    keys.extend(s.distinct.iter().map(|&(k, _)| k));
    if links {
        s.row_of.clear();
        s.row_of.resize(s.distinct.len(), 0);
        for (row, &(_, id)) in s.distinct.iter().enumerate() {
            s.row_of[id as usize] = row as u32;
        }
        for link in s.links[q + 1].chunks_exact_mut(q + 2) {
            for l in &mut link[1..] {
                *l = s.row_of[*l as usize];
            }
        }
    }
}

/// Appends a block's faces (and links) to its part (step 3's block-local half).
fn emit(v: u32, shape: Shape, want: Want, s: &Scratch, part: &mut Part) {
    let Shape { lb, dv } = shape;
    for q in 1..=dv {
        part.counts[q] += s.keys[q].len();
    }
    if want == Want::Counts {
        return;
    }
    // The part's rows of each level before this block: where its local facet rows start.
    let mut base = [0u32; super::MAX_DIMENSION + 1];
    for (q, b) in base.iter_mut().enumerate().take(dv + 1).skip(1) {
        *b = (part.rows[q].len() / (q + 1)) as u32;
    }
    let mask = (1u64 << lb) - 1;
    for q in 1..=dv {
        let keys = &s.keys[q];
        let rows = grow(&mut part.rows[q], keys.len() * (q + 1));
        for (row, &k) in rows.chunks_exact_mut(q + 1).zip(keys) {
            row[0] = v;
            for e in 0..q {
                row[e + 1] = s.nbr[(k >> (lb * (q - 1 - e) as u32) & mask) as usize];
            }
        }
        if want != Want::Links {
            continue;
        }
        let links = grow(&mut part.links[q], keys.len() * (q + 1));
        if q == 1 {
            for (row, &k) in links.chunks_exact_mut(2).zip(keys) {
                row.copy_from_slice(&[s.nbr[k as usize], v]);
            }
            continue;
        }
        for (row, local) in links
            .chunks_exact_mut(q + 1)
            .zip(s.links[q].chunks_exact(q + 1))
        {
            row[0] = UNSET;
            for e in 1..=q {
                row[e] = local[e].wrapping_add(base[q - 1]);
            }
        }
    }
}

/// Step 3: each level's rows, parts in order (so in vertex order: sorted tables). The first
/// part's buffer is extended in place: with one part (one thread) nothing is copied.
fn concat_rows(parts: &mut [Part], n: u32, d: usize) -> Result<Vec<SimplexTable>, usize> {
    let mut tables = vec![SimplexTable::try_vertices(n)?];
    for q in 1..=d {
        let ids = append_parts(
            parts.iter_mut().map(|p| std::mem::take(&mut p.rows[q])),
            |_| 0,
        )?;
        tables.push(SimplexTable::from_sorted_unique(q + 1, ids));
    }
    Ok(tables)
}

/// Step 3 for the links: part-relative facet rows shifted by the rows of the parts before.
fn concat_links(parts: &mut [Part], d: usize) -> Result<Vec<Vec<u32>>, usize> {
    let mut boundary = vec![Vec::new()];
    for q in 1..=d {
        // Rows of level q − 1 in the parts before each part (edges link to vertex ids).
        let shifts: Vec<u32> = parts
            .iter()
            .scan(0u32, |before, p| {
                let s = *before;
                if q > 1 {
                    *before = before.wrapping_add(p.counts[q - 1] as u32);
                }
                Some(s)
            })
            .collect();
        let links = append_parts(
            parts.iter_mut().map(|p| std::mem::take(&mut p.links[q])),
            |k| shifts[k],
        )?;
        boundary.push(links);
    }
    Ok(boundary)
}

/// The parts' buffers one after the other in the first one's, part k's ids shifted by
/// `shift(k)` ([`UNSET`] kept); the result holds no spare capacity.
fn append_parts(
    mut bufs: impl Iterator<Item = Vec<u32>>,
    shift: impl Fn(usize) -> u32,
) -> Result<Vec<u32>, usize> {
    let mut all = bufs.next().unwrap_or_default();
    for (k, b) in bufs.enumerate() {
        let s = shift(k + 1);
        all.try_reserve_exact(b.len())
            .map_err(|_| (all.len() + b.len()) * 4)?;
        if s == 0 {
            all.extend_from_slice(&b);
        } else {
            all.extend(
                b.iter()
                    .map(|&i| if i == UNSET { i } else { i.wrapping_add(s) }),
            );
        }
    }
    all.shrink_to_fit();
    Ok(all)
}

/// Step 4: slot 0 of every q-simplex (q ≥ 2), the facet without its first vertex, searched
/// among the (q−1)-simplices that start with the simplex's second vertex.
fn facets_without_first(tables: &[SimplexTable], q: usize, links: &mut [u32]) -> Result<(), usize> {
    let below = &tables[q - 1];
    let n = tables[0].len();
    let mut start = Vec::new();
    start.try_reserve_exact(n + 1).map_err(|_| (n + 1) * 4)?;
    start.resize(n + 1, 0u32);
    for s in below.iter() {
        start[s[0] as usize + 1] += 1;
    }
    for v in 0..n {
        start[v + 1] += start[v];
    }
    let bits = id_bits(n.saturating_sub(1) as u32);
    let pack = |r: &[u32]| r.iter().fold(0u64, |k, &v| k << bits | u64::from(v));
    // The rows past their first id, as words when q − 1 ids fit (a compare of words).
    let rest = if (q - 1) as u32 * bits <= 64 {
        headroom(below.len() * 8)?;
        Some(crate::parallel::map_collect(below.len(), |i| {
            pack(&below.get(i)[1..])
        }))
    } else {
        None
    };
    // Runs of rows on several threads. Rows that share their first two vertices with the row
    // before have facets after its facet (same first vertex, larger rest): the search gallops
    // from there, a step or two in a Rips block instead of a search over the whole start.
    const RUN: usize = 1024;
    let w = q + 1;
    crate::parallel::fill_rows(links, w * RUN, |c, run| {
        let mut prev: Option<(&[u32], usize)> = None;
        for (k, row) in run.chunks_exact_mut(w).enumerate() {
            let sigma = tables[q].get(c * RUN + k);
            let f = &sigma[1..];
            let (mut lo, hi) = (
                start[f[0] as usize] as usize,
                start[f[0] as usize + 1] as usize,
            );
            if let Some((p, at)) = prev
                && p[..2] == sigma[..2]
            {
                lo = at + 1;
            }
            let at = match &rest {
                Some(keys) => gallop(&keys[..hi], lo, pack(&f[1..])),
                None => {
                    let (mut lo, mut hi) = (lo, hi);
                    while lo < hi {
                        let mid = (lo + hi) / 2;
                        if below.get(mid) < f {
                            lo = mid + 1;
                        } else {
                            hi = mid;
                        }
                    }
                    lo
                }
            };
            debug_assert_eq!(below.get(at), f, "the closure holds every facet");
            row[0] = at as u32;
            prev = Some((sigma, at));
        }
    });
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Random non-manifold complexes over few vertices (faces shared), dimension ≤ 7, and some
    /// over ids up to 2^20 (global ids too wide for d of them to share a word; ranks are not).
    fn random_complexes() -> impl Iterator<Item = Complex> {
        let mut rnd = crate::complex::xorshift_below(0x9e37_79b9_7f4a_7c15);
        (0..300).map(move |i| {
            let (n, spread) = if i % 5 == 0 {
                (1 << 20, 1 << 16)
            } else {
                (1 + rnd(16) as u32, 1)
            };
            let small = n / spread;
            let simplices: Vec<Vec<u32>> = (0..rnd(24))
                .map(|_| {
                    let mut s: Vec<u32> = (0..1 + rnd(8))
                        .map(|_| rnd(small as u64) as u32 * spread)
                        .collect();
                    s.sort_unstable();
                    s.dedup();
                    s
                })
                .collect();
            let refs: Vec<&[u32]> = simplices.iter().map(Vec::as_slice).collect();
            Complex::from_simplices(n, &refs).unwrap()
        })
    }

    #[test]
    fn blocks_give_the_closure_and_the_facet_links_of_every_simplex() {
        use std::sync::atomic::Ordering::Relaxed;
        // Every level sorted, then every level hashed, then the threshold the build uses.
        for (from, complexes) in [(usize::MAX, 100), (0, 100), (HASH_FROM, 300)] {
            HASH_FROM_TEST.store(from, Relaxed);
            blocks_match_levels(complexes);
        }
    }

    fn blocks_match_levels(complexes: usize) {
        for c in random_complexes().take(complexes) {
            let levels = c.closure_by_levels().unwrap();
            if c.dimension() == 0 {
                continue;
            }
            let got = c
                .closure_by_blocks(Want::Links)
                .unwrap()
                .expect("ranks fit");
            assert_eq!(got.tables, levels);
            for p in 1..levels.len() {
                let want = crate::structures::common::facet_links(&levels, p);
                assert_eq!(got.boundary[p], want, "dimension {p}");
            }
            let counts = c.closure_by_blocks(Want::Counts).unwrap().unwrap().counts;
            let lens: Vec<usize> = levels.iter().map(SimplexTable::len).collect();
            assert_eq!(counts, lens);
        }
    }

    #[test]
    fn a_block_whose_ranks_do_not_fit_a_word_is_refused_and_the_closure_made_otherwise() {
        //   vertex 0 in two 15-simplices whose other 30 vertices differ: 30 ranks of 5 bits,
        //   15 of them in a key = 75 bits.
        let a: Vec<u32> = (0..16).collect();
        let b: Vec<u32> = std::iter::once(0).chain(16..31).collect();
        let c = Complex::from_simplices(31, &[&a, &b]).unwrap();
        assert!(c.closure_by_blocks(Want::Tables).unwrap().is_none());
        let tables = c.try_closure().unwrap();
        assert_eq!(tables, c.closure_by_levels().unwrap());
        assert_eq!(tables[15].len(), 2);
        assert_eq!(tables[1].len(), 240);
    }
}
