//! The closure by vertex blocks, with the boundary links when asked: the faces whose smallest
//! vertex is v (v's *block*) are made level by level inside the block, in the ranks of v's
//! neighbours above it, so every key fits one word whatever the ids' width.
//!
//! # Steps, per vertex v (ranges of vertices on [`crate::parallel::threads`] threads)
//! 1. N(v): the vertices above v in the top simplices at v, sorted; a face of v's block is v
//!    and a subset of N(v), written as the ranks of that subset packed `lb = bits(|N(v)| − 1)`
//!    per rank (the block fails, and the caller takes another path, when the longest subset
//!    needs more than 64 bits).
//! 2. A block of at most 12 neighbours above v, or up to [`MASK_MAX`] with many faces (nearly
//!    all blocks of a Rips or alpha complex: rips-building has 2–22) by masks: its faces are
//!    bits of a set of 2^|N(v)| subsets, visited from the largest mask down, which meets every
//!    face after its cofaces and each level in lexicographic order; a face sets its facets'
//!    bits and its links read their rows: nothing sorted or hashed ([`by_masks`]).
//!    Other blocks level by level downwards: the block's q-faces are its top simplices of
//!    dimension q and the facets that keep v of its (q+1)-faces; the candidates carry the slot
//!    they came from, so deduplicating a level also gives every slot but slot 0 its facet (the
//!    facet that drops vertex i ≥ 1 of a face lies in the same block). Small levels sort the
//!    candidates; levels of [`HASH_FROM`] candidates or more put them in a hash set and sort
//!    only the distinct faces (a Rips level has several candidates per face).
//! 3. Blocks are appended in vertex order to their range's buffers, reserved for every face
//!    the range's tops can give (only the pages written are touched). With one range (one
//!    thread) its buffers become the tables, nothing copied; several are copied into one array
//!    on the threads, facet indices shifted by the rows of the ranges before.
//! 4. Slot 0 (the facet without v) lies in the block of the face's second vertex: a search
//!    among that block's rows, packed as words past their first id, starting after the facet
//!    of the row before when both rows share their first two vertices (doubling steps).
//!
//! Work: by masks, 2^|N(v)|/64 words plus q steps per q-face of the block; by levels, Σ over
//! the blocks' faces of (q+1) candidates, hashed or sorted in cache-sized blocks; then one
//! search per simplex; memory: the closure's tables and links, and each block's
//! scratch.

use super::closure::TopAt;
use super::table::id_bits;
use super::{Complex, SimplexTable};

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
    /// [`by_masks`]: a bit per subset of N(v) (bit `m − 1 − rank` for each rank in it) that is
    /// a face of the block not yet visited; each visited face's row in its level; the faces in
    /// visiting order, each as its mask and its level above [`MASK_MAX`] bits.
    present: Vec<u64>,
    mrow: Vec<u32>,
    order: Vec<u32>,
}

/// Blocks of at most this many neighbours above v may take [`by_masks`] (tables of 2^20 words
/// and 2^20 bits per thread, had zeroed and touched only where faces are).
const MASK_MAX: usize = 20;

/// Whether v's block, with `m` neighbours above v and `generated` faces counted with their
/// repeats (Σ 2^a over its tops), takes [`by_masks`]: its bit set is small (2^12 bits), or
/// its 2^m / 64 words few next to the faces (a vertex of a graph with 20 edges above it has
/// 40, too few for 2^14 words).
fn takes_masks(m: usize, generated: usize) -> bool {
    #[cfg(test)]
    if MASKS_TEST.load(std::sync::atomic::Ordering::Relaxed) == 0 {
        return false;
    }
    m <= 12 || (m <= MASK_MAX && 1usize << m <= generated.saturating_mul(256))
}

/// 0: blocks never take [`by_masks`], else [`takes_masks`]' rule.
#[cfg(test)]
static MASKS_TEST: std::sync::atomic::AtomicUsize = std::sync::atomic::AtomicUsize::new(1);

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
/// block level instead of one per row; [`Part::reserved`] holds room for them all).
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

impl Part {
    /// An empty part whose buffers hold, without growing, every face its tops can give: a top
    /// with `a` vertices above v gives v's block at most C(a, q) q-faces. The bound is loose
    /// (a Rips face comes from several tops) but only the pages written are ever touched, and
    /// no block pays for a reallocation or its copy.
    fn reserved(d: usize, tops: &[TopAt], want: Want) -> Result<Part, usize> {
        let mut part = Part {
            counts: vec![0; d + 1],
            rows: vec![Vec::new(); d + 1],
            links: vec![Vec::new(); d + 1],
        };
        if want == Want::Counts {
            return Ok(part);
        }
        // Tops by their number of vertices above v, then C(a, q) faces from each.
        let mut by_above = [0usize; super::MAX_DIMENSION + 1];
        for &(p, _, pos) in tops {
            by_above[usize::from(p - pos)] += 1;
        }
        let mut faces = [0usize; super::MAX_DIMENSION + 1];
        for (a, &k) in by_above.iter().enumerate() {
            for (q, f) in faces.iter_mut().enumerate().take(a + 1).skip(1) {
                *f = f.saturating_add(k.saturating_mul(BINOMIAL[a][q]));
            }
        }
        for (q, &f) in faces.iter().enumerate().take(d + 1).skip(1) {
            let ids = f.saturating_mul(q + 1);
            let bytes = ids.saturating_mul(4);
            part.rows[q].try_reserve_exact(ids).map_err(|_| bytes)?;
            if want == Want::Links {
                part.links[q].try_reserve_exact(ids).map_err(|_| bytes)?;
            }
        }
        Ok(part)
    }
}

/// C(a, q) for a, q ≤ 15.
const BINOMIAL: [[usize; 16]; 16] = {
    let mut c = [[0usize; 16]; 16];
    let mut a = 0;
    while a < 16 {
        c[a][0] = 1;
        let mut q = 1;
        while q <= a {
            c[a][q] = c[a - 1][q - 1] + c[a - 1][q];
            q += 1;
        }
        a += 1;
    }
    c
};

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
            crate::parallel::headroom_for(ids, ids.saturating_mul(per))?;
        }
        let (off, at) = self.tops_at_vertices()?;
        let parts = crate::parallel::ranges_by_weight(&off);
        let done = crate::parallel::map_chunks(parts.len(), |c| {
            let mut s = Scratch::default();
            // One rank per vertex id (a chunk at a time per thread: threads × 4n bytes).
            s.rank.try_reserve_exact(n).map_err(|_| n * 4)?;
            s.rank.resize(n, u32::MAX);
            let range = parts[c].clone();
            let mut part = Part::reserved(d, &at[off[range.start]..off[range.end]], want)?;
            s.seeds = vec![Vec::new(); d + 1];
            s.keys = vec![Vec::new(); d + 1];
            s.links = vec![Vec::new(); d + 1];
            for v in range {
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
        let (mut dv, mut generated) = (0, 0usize);
        for t in tops {
            let a = above(t);
            for &x in a {
                if s.rank[x as usize] == u32::MAX {
                    s.rank[x as usize] = 0;
                    s.nbr.push(x);
                }
            }
            dv = dv.max(a.len());
            generated += 1 << a.len();
        }
        if dv == 0 {
            return true;
        }
        s.nbr.sort_unstable();
        for (i, &x) in s.nbr.iter().enumerate() {
            s.rank[x as usize] = i as u32;
        }
        let m = s.nbr.len();
        if takes_masks(m, generated) {
            if s.mrow.len() < 1 << m {
                // Zeroed by the allocator: pages touched only where faces are.
                s.mrow = vec![0; 1 << m];
                s.present = vec![0; (1usize << m).div_ceil(64)];
            }
            for t in tops {
                let r: usize = above(t)
                    .iter()
                    .fold(0, |r, &x| r | 1 << (m - 1 - s.rank[x as usize] as usize));
                s.present[r >> 6] |= 1 << (r & 63);
            }
            for &x in &s.nbr {
                s.rank[x as usize] = u32::MAX;
            }
            by_masks(v, Shape { lb: m as u32, dv }, want, s, part);
            return true;
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

/// Step 2 for a block of few neighbours above v (`shape.lb` is their number m here): its faces
/// are subsets of N(v), each a mask with bit `m − 1 − rank` per rank, the tops' masks set in
/// the bit set `s.present`. Masks in descending order meet every face after all its cofaces
/// (supersets are larger), so one pass, taking the highest set bit each time, gives each face
/// its row and sets its facets' bits; and among masks of one level, descending is the
/// lexicographic order of the rank sequences (the first rank that differs is the highest bit
/// that differs). A second pass over the faces in that order writes the rows and the facet
/// links of slots 1... No candidate is sorted or hashed: O(2^m / 64 + Σ faces · q), and the
/// bit set is empty again at the end.
fn by_masks(v: u32, shape: Shape, want: Want, s: &mut Scratch, part: &mut Part) {
    let Shape { lb, dv } = shape;
    let m = lb as usize;
    let mut count = [0u32; super::MAX_DIMENSION + 2];
    s.order.clear();
    for w in (0..(1usize << m).div_ceil(64)).rev() {
        while s.present[w] != 0 {
            let hb = 63 - s.present[w].leading_zeros() as usize;
            s.present[w] ^= 1 << hb;
            let r = w << 6 | hb;
            if r == 0 {
                break; // v alone, the last bit
            }
            let q = r.count_ones() as usize;
            s.mrow[r] = count[q];
            count[q] += 1;
            s.order.push((r | q << MASK_MAX) as u32);
            let mut x = r;
            while x != 0 {
                let b = x & x.wrapping_neg();
                s.present[(r ^ b) >> 6] |= 1 << ((r ^ b) & 63);
                x ^= b;
            }
        }
    }
    for (total, &c) in part.counts.iter_mut().zip(&count).take(dv + 1) {
        *total += c as usize;
    }
    if want == Want::Counts {
        return;
    }
    // Where this block's rows of each level start, as ids and as rows.
    let (mut at, mut base) = ([0usize; 17], [0u32; 17]);
    for q in 1..=dv {
        at[q] = part.rows[q].len();
        base[q] = (at[q] / (q + 1)) as u32;
        grow(&mut part.rows[q], count[q] as usize * (q + 1));
        if want == Want::Links {
            grow(&mut part.links[q], count[q] as usize * (q + 1));
        }
    }
    for &o in &s.order {
        let (r, q) = (o as usize & ((1 << MASK_MAX) - 1), o as usize >> MASK_MAX);
        let w = q + 1;
        let out = &mut part.rows[q][at[q]..at[q] + w];
        out[0] = v;
        // Ranks ascending: bits from the highest.
        let mut x = r;
        for o in &mut out[1..] {
            let hb = usize::BITS - 1 - x.leading_zeros();
            *o = s.nbr[m - 1 - hb as usize];
            x ^= 1 << hb;
        }
        if want == Want::Links {
            let link = &mut part.links[q][at[q]..at[q] + w];
            if q == 1 {
                link.copy_from_slice(&[out[1], v]);
            } else {
                // Slot e drops the e-th rank: the e-th highest bit.
                link[0] = UNSET;
                let mut x = r;
                for l in &mut link[1..] {
                    let b = 1usize << (usize::BITS - 1 - x.leading_zeros());
                    *l = s.mrow[r ^ b] + base[q - 1];
                    x ^= b;
                }
            }
        }
        at[q] += w;
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

/// Step 3: each level's rows, parts in order (so in vertex order: sorted tables). With one
/// part (one thread) its buffers become the tables, nothing copied.
fn concat_rows(parts: &mut [Part], n: u32, d: usize) -> Result<Vec<SimplexTable>, usize> {
    let mut tables = vec![SimplexTable::try_vertices(n)?];
    let none = vec![0; parts.len()];
    for q in 1..=d {
        let bufs = parts.iter_mut().map(|p| std::mem::take(&mut p.rows[q]));
        let ids = append_parts(bufs.collect(), &none)?;
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
        let bufs = parts.iter_mut().map(|p| std::mem::take(&mut p.links[q]));
        boundary.push(append_parts(bufs.collect(), &shifts)?);
    }
    Ok(boundary)
}

/// The parts' buffers one after the other, part k's ids shifted by `shifts[k]` ([`UNSET`]
/// kept); the result holds no spare capacity. One part is returned as it is; several are
/// copied into one array on the threads, each part to its place.
fn append_parts(mut bufs: Vec<Vec<u32>>, shifts: &[u32]) -> Result<Vec<u32>, usize> {
    use rayon::prelude::*;
    if bufs.len() < 2 {
        let mut all = bufs.pop().unwrap_or_default();
        all.shrink_to_fit();
        return Ok(all);
    }
    let total: usize = bufs.iter().map(Vec::len).sum();
    // Probed, then had zeroed from the allocator: fresh pages, faulted in by the thread that
    // copies into them rather than cleared by this one.
    crate::parallel::headroom_for(total, total.saturating_mul(4))?;
    let mut all = vec![0u32; total];
    let mut pieces = Vec::with_capacity(bufs.len());
    let mut rest = all.as_mut_slice();
    for b in &bufs {
        let (piece, after) = rest.split_at_mut(b.len());
        pieces.push(piece);
        rest = after;
    }
    crate::parallel::install(|| {
        pieces
            .into_par_iter()
            .zip(bufs)
            .zip(shifts)
            .for_each(|((out, b), &s)| {
                if s == 0 {
                    out.copy_from_slice(&b);
                } else {
                    for (o, &i) in out.iter_mut().zip(&b) {
                        *o = if i == UNSET { i } else { i.wrapping_add(s) };
                    }
                }
            })
    });
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
        crate::parallel::headroom_for(below.len(), below.len() * 8)?;
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
                None => super::table::partition_point(lo..hi, |mid| below.get(mid) < f),
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

    /// Random non-manifold complexes over few vertices (faces shared), dimension ≤ 7, some with
    /// blocks of more than 20 neighbours above a vertex next to smaller ones, and some
    /// over ids up to 2^20 (global ids too wide for d of them to share a word; ranks are not).
    fn random_complexes() -> impl Iterator<Item = Complex> {
        let mut rnd = crate::complex::xorshift_below(0x9e37_79b9_7f4a_7c15);
        (0..300).map(move |i| {
            // Some over up to 48 vertices with more simplices: blocks by levels (more than 20
            // neighbours above v, or more than 12 and few faces) next to blocks by masks.
            let (n, spread, count) = match i % 5 {
                0 => (1 << 20, 1 << 16, 24),
                1 => (24 + rnd(24) as u32, 1, 96),
                _ => (1 + rnd(16) as u32, 1, 24),
            };
            let small = n / spread;
            crate::complex::random_complex(&mut rnd, n, count, 8, (small as u64, spread))
        })
    }

    #[test]
    fn blocks_give_the_closure_and_the_facet_links_of_every_simplex() {
        use std::sync::atomic::Ordering::Relaxed;
        // Every level sorted, then every level hashed, then the threshold the build uses, each
        // with no block by masks; then the build's way ([`takes_masks`]).
        MASKS_TEST.store(0, Relaxed);
        for (from, complexes) in [(usize::MAX, 100), (0, 100), (HASH_FROM, 300)] {
            HASH_FROM_TEST.store(from, Relaxed);
            blocks_match_levels(complexes);
        }
        MASKS_TEST.store(1, Relaxed);
        blocks_match_levels(300);
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
            let tables = c.closure_by_blocks(Want::Tables).unwrap().unwrap().tables;
            assert_eq!(tables, levels, "tables without links");
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
