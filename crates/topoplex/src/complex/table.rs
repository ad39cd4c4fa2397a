//! Flat, sorted tables of p-simplices: the one representation of "a set of simplices" shared by
//! the complex model, the oracle and the incidence-based structures.

use crate::mapped::Arr;

pub(crate) use crate::alloc::abort_for;
pub use crate::alloc::{try_extend, try_grow, try_push, try_reserve_exact};
pub use crate::parallel::headroom;

/// The p-simplices of some set, each as `arity = p + 1` ascending vertex ids, concatenated, in
/// ascending lexicographic order, without duplicates. Simplex `i` of the table is its `i`-th
/// entry, so the table itself is the dense numbering of those simplices.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct SimplexTable {
    arity: usize,
    ids: Arr<u32>,
}

impl SimplexTable {
    /// An empty table of vertices, usable in statics.
    pub const EMPTY: SimplexTable = SimplexTable {
        arity: 1,
        ids: Arr::new(),
    };

    /// Wraps rows the caller knows are ascending and distinct (checked in debug builds).
    pub fn from_sorted_unique(arity: usize, ids: Vec<u32>) -> Self {
        let t = SimplexTable {
            arity,
            ids: ids.into(),
        };
        debug_assert!((1..t.len()).all(|i| t.get(i - 1) < t.get(i)));
        t
    }

    /// A table of rows of `arity` ids with no row.
    pub fn empty(arity: usize) -> Self {
        SimplexTable {
            arity,
            ids: Arr::new(),
        }
    }

    /// Sorts and deduplicates `ids` (rows of `arity` already-ascending vertex ids) into a table;
    /// returns it with the number of duplicate rows removed. O(n log n) comparisons.
    pub fn from_rows(arity: usize, ids: Vec<u32>) -> (Self, usize) {
        assert!(arity > 0 && ids.len().is_multiple_of(arity));
        let rows = ids.len() / arity;
        let ids = sort_dedup_rows(arity, ids);
        let table = SimplexTable {
            arity,
            ids: ids.into(),
        };
        let dups = rows - table.len();
        (table, dups)
    }

    /// [`Self::from_rows`] sorted by [`try_sort_dedup_rows`].
    fn from_rows_fallibly(arity: usize, ids: Vec<u32>) -> Result<(Self, usize), usize> {
        assert!(arity > 0 && ids.len().is_multiple_of(arity));
        let rows = ids.len() / arity;
        let ids = try_sort_dedup_rows(arity, ids)?;
        let table = SimplexTable {
            arity,
            ids: ids.into(),
        };
        let dups = rows - table.len();
        Ok((table, dups))
    }

    /// [`Self::from_rows`] whose memory is checked first: `Err(bytes)` when the sort's peak
    /// (two 8-byte keys per row, with any number of threads, and the rows out) cannot be
    /// reserved, instead of an abort.
    pub fn try_from_rows(arity: usize, ids: Vec<u32>) -> Result<(Self, usize), usize> {
        if arity > 0 && ids.len().is_multiple_of(arity) && rows_ascending(arity, &ids) {
            // Already a table (a Rips or alpha maker's listing): no sort, no memory.
            return Ok((SimplexTable::from_sorted_unique(arity, ids), 0));
        }
        let rows = ids.len() / arity.max(1);
        crate::parallel::headroom_for(
            rows,
            rows.saturating_mul(16)
                .saturating_add(ids.len().saturating_mul(4)),
        )?;
        // The probe cannot see what other threads take after it: the packed sort's arrays are
        // reserved fallibly too.
        Self::from_rows_fallibly(arity, ids)
    }

    /// A copy whose memory is reserved fallibly: `Err(bytes)` when it cannot be had.
    pub fn try_clone(&self) -> Result<Self, usize> {
        Ok(SimplexTable {
            arity: self.arity,
            ids: self.ids.try_clone()?,
        })
    }

    /// [`Self::vertices`] reserved fallibly: `Err(bytes)` when it cannot be had.
    pub fn try_vertices(n: u32) -> Result<Self, usize> {
        let mut ids = Vec::new();
        ids.try_reserve_exact(n as usize)
            .map_err(|_| n as usize * 4)?;
        ids.extend(0..n);
        Ok(SimplexTable {
            arity: 1,
            ids: ids.into(),
        })
    }

    /// The vertices `0..n` as a table of 0-simplices.
    pub fn vertices(n: u32) -> Self {
        SimplexTable {
            arity: 1,
            ids: (0..n).collect(),
        }
    }

    /// Wraps an array of rows read from a saved file; their order is the saver's invariant,
    /// checked by the owning structure's `validate()`. `ids.len()` must be a multiple of `arity`.
    pub fn from_arr(arity: usize, ids: Arr<u32>) -> Self {
        assert!(arity > 0 && ids.len().is_multiple_of(arity));
        SimplexTable { arity, ids }
    }

    /// Number of ids per row (p + 1 for p-simplices).
    pub fn arity(&self) -> usize {
        self.arity
    }

    /// Number of rows.
    pub fn len(&self) -> usize {
        self.ids.len().checked_div(self.arity).unwrap_or(0)
    }

    /// Whether the table has no row.
    pub fn is_empty(&self) -> bool {
        self.ids.is_empty()
    }

    /// Row `i` (panics when `i >= len()`).
    pub fn get(&self, i: usize) -> &[u32] {
        &self.ids[i * self.arity..(i + 1) * self.arity]
    }

    /// All rows concatenated.
    pub fn as_flat(&self) -> &[u32] {
        &self.ids
    }

    /// The rows in order.
    pub fn iter(&self) -> impl ExactSizeIterator<Item = &[u32]> + '_ {
        self.ids.chunks_exact(self.arity.max(1))
    }

    /// Index of `simplex` (ascending ids) in the table: O(arity · log len).
    pub fn find(&self, simplex: &[u32]) -> Option<u32> {
        if simplex.len() != self.arity {
            return None;
        }
        let (mut lo, mut hi) = (0usize, self.len());
        while lo < hi {
            let mid = (lo + hi) / 2;
            match self.get(mid).cmp(simplex) {
                std::cmp::Ordering::Less => lo = mid + 1,
                std::cmp::Ordering::Greater => hi = mid,
                std::cmp::Ordering::Equal => return Some(mid as u32),
            }
        }
        None
    }

    /// Heap bytes held by the table.
    pub fn heap_bytes(&self) -> usize {
        self.ids.capacity() * 4
    }
}

/// Sorts rows of `arity` u32s lexicographically and drops repeated rows. Rows whose ids fit in
/// 64 bits together are radix sorted as one packed key (linear time); other rows of up to four
/// ids are packed into one u128 key, which sorts several times faster than comparing slices.
pub fn sort_dedup_rows(arity: usize, ids: Vec<u32>) -> Vec<u32> {
    try_sort_dedup_rows(arity, ids).unwrap_or_else(|bytes| abort_for(bytes))
}

/// [`sort_dedup_rows`] whose packed keys, sort scratch and rows out (the radix path, the one
/// split between threads) are reserved fallibly: `Err(bytes)` when they cannot be had. The
/// other paths, serial, allocate as [`sort_dedup_rows`] does (callers probe them).
pub fn try_sort_dedup_rows(arity: usize, ids: Vec<u32>) -> Result<Vec<u32>, usize> {
    if arity > 0 && rows_ascending(arity, &ids) {
        return Ok(ids);
    }
    // Rows whose ids fit side by side in 64 bits sort by a linear-time radix sort, so building
    // the closure costs the same per simplex at 10^4 and 10^6 simplices.
    let widest = ids.iter().copied().max().unwrap_or(0);
    let bits = id_bits(widest);
    if arity >= 2 && arity as u32 * bits <= 64 {
        let mut keys: Vec<u64> = crate::parallel::try_map_collect(ids.len() / arity, |r| {
            let row = &ids[r * arity..(r + 1) * arity];
            row.iter().fold(0u64, |acc, &v| (acc << bits) | v as u64)
        })?;
        // The keys hold the rows now: free them before the sort's buffer (peak memory).
        drop(ids);
        try_radix_sort(&mut keys, arity as u32 * bits)?;
        keys.dedup();
        return unpack_keys(&keys, arity, bits);
    }
    // Buckets by first vertex cost 16 bytes per id up to the largest: only when the ids are not
    // far sparser than the rows (a few rows with a huge id — a hostile saved file's — would
    // otherwise allocate gigabytes).
    let rows = ids.len() / arity.max(1);
    if arity >= 3
        && (arity as u32 - 1) * bits <= 128
        && widest as usize <= rows.saturating_mul(4).max(1 << 16)
    {
        return sort_dedup_by_first(arity, ids, bits);
    }
    Ok(sort_dedup_serial(arity, ids))
}

/// Whether the rows of `arity` ids in `ids` are in strictly ascending lexicographic order,
/// i.e. already sorted and without repeats (sorting would leave them as they are): one pass,
/// ranges of rows on several threads, each range stopping at its first descent.
pub(crate) fn rows_ascending(arity: usize, ids: &[u32]) -> bool {
    let rows = ids.len() / arity;
    if rows < 2 {
        return true;
    }
    // Ranges of row pairs: range r compares rows r.start..=r.end, so the ranges overlap by one
    // row and every adjacent pair is compared.
    crate::parallel::map_ranges(rows - 1, |r| {
        ids[r.start * arity..(r.end + 1) * arity]
            .chunks_exact(arity)
            .is_sorted_by(|a, b| a < b)
    })
    .into_iter()
    .all(|ok| ok)
}

/// [`sort_dedup_rows`] for rows too wide to pack in 64 bits (or single ids).
fn sort_dedup_serial(arity: usize, ids: Vec<u32>) -> Vec<u32> {
    fn packed<K: Ord + Copy>(
        arity: usize,
        ids: &[u32],
        pack: impl Fn(&[u32]) -> K,
        unpack: impl Fn(K, &mut Vec<u32>),
    ) -> Vec<u32> {
        let mut keys: Vec<K> = ids.chunks_exact(arity).map(pack).collect();
        keys.sort_unstable();
        keys.dedup();
        let mut out = Vec::with_capacity(keys.len() * arity);
        for k in keys {
            unpack(k, &mut out);
        }
        out
    }
    match arity {
        1 => {
            let mut ids = ids;
            ids.sort_unstable();
            ids.dedup();
            ids
        }
        2 => packed(
            2,
            &ids,
            |r| ((r[0] as u64) << 32) | r[1] as u64,
            |k, out| out.extend_from_slice(&[(k >> 32) as u32, k as u32]),
        ),
        3 | 4 => packed(
            arity,
            &ids,
            |r| r.iter().fold(0u128, |acc, &v| (acc << 32) | v as u128),
            |k, out| {
                for i in (0..arity).rev() {
                    out.push((k >> (32 * i)) as u32);
                }
            },
        ),
        _ => {
            let rows = ids.len() / arity;
            let mut order: Vec<u32> = (0..rows as u32).collect();
            let row = |i: u32| &ids[i as usize * arity..(i as usize + 1) * arity];
            order.sort_unstable_by(|&a, &b| row(a).cmp(row(b)));
            order.dedup_by(|a, b| row(*a) == row(*b));
            let mut out = Vec::with_capacity(order.len() * arity);
            for i in order {
                out.extend_from_slice(row(i));
            }
            out
        }
    }
}

/// Rows too wide for one word, sorted and deduplicated: a counting sort by their first id, then
/// each bucket (the rows at one vertex: few, in cache) by the other ids packed in a u128.
/// Buckets in ranges on several threads, concatenated in order. O(rows · arity + ids' range).
/// Every input-sized array is reserved fallibly (`Err(bytes)`).
fn sort_dedup_by_first(arity: usize, ids: Vec<u32>, bits: u32) -> Result<Vec<u32>, usize> {
    let rows = ids.len() / arity;
    let n = ids
        .chunks_exact(arity)
        .map(|r| r[0])
        .max()
        .map_or(0, |m| m as usize + 1);
    let mut start: Vec<usize> = Vec::new();
    try_reserve_exact(&mut start, n + 1)?;
    start.resize(n + 1, 0);
    for r in ids.chunks_exact(arity) {
        start[r[0] as usize + 1] += 1;
    }
    for v in 0..n {
        start[v + 1] += start[v];
    }
    let mut order: Vec<u32> = Vec::new();
    try_reserve_exact(&mut order, rows)?;
    order.resize(rows, 0);
    {
        let mut fill: Vec<usize> = Vec::new();
        try_reserve_exact(&mut fill, n + 1)?;
        fill.extend_from_slice(&start);
        for (i, r) in ids.chunks_exact(arity).enumerate() {
            order[fill[r[0] as usize]] = i as u32;
            fill[r[0] as usize] += 1;
        }
    }
    let mask = (1u128 << bits) - 1;
    let parts = crate::parallel::ranges_by_weight(&start);
    let done = crate::parallel::map_chunks(parts.len(), |c| -> Result<Vec<u32>, usize> {
        let range = parts[c].clone();
        let mut out = Vec::new();
        try_reserve_exact(&mut out, (start[range.end] - start[range.start]) * arity)?;
        let mut keys: Vec<u128> = Vec::new();
        for v in range {
            keys.clear();
            try_grow(&mut keys, start[v + 1] - start[v])?;
            keys.extend(order[start[v]..start[v + 1]].iter().map(|&i| {
                let r = &ids[i as usize * arity + 1..(i as usize + 1) * arity];
                r.iter().fold(0u128, |k, &x| k << bits | u128::from(x))
            }));
            keys.sort_unstable();
            keys.dedup();
            for &k in &keys {
                out.push(v as u32);
                for e in (0..arity - 1).rev() {
                    out.push((k >> (bits * e as u32) & mask) as u32);
                }
            }
        }
        Ok(out)
    });
    // The input is in the buckets now: free it before they are joined (peak memory).
    drop((ids, order));
    if done.len() == 1 {
        return done.into_iter().next().unwrap_or(Ok(Vec::new()));
    }
    let mut joined = Vec::new();
    let mut total = 0usize;
    for part in &done {
        total += part.as_ref().map_or(0, Vec::len);
    }
    try_reserve_exact(&mut joined, total)?;
    for part in done {
        joined.extend_from_slice(&part?);
    }
    Ok(joined)
}

/// Rows of `arity` ids of `bits` bits each from their packed keys (split between threads; each
/// row's place is fixed by its key's index).
fn unpack_keys(keys: &[u64], arity: usize, bits: u32) -> Result<Vec<u32>, usize> {
    let mask = (1u64 << bits) - 1;
    let mut out = Vec::new();
    try_reserve_exact(&mut out, keys.len() * arity)?;
    out.resize(keys.len() * arity, 0u32);
    let unpack = |(row, &k): (&mut [u32], &u64)| {
        for (i, v) in row.iter_mut().enumerate() {
            *v = ((k >> (bits * (arity - 1 - i) as u32)) & mask) as u32;
        }
    };
    if crate::parallel::splits(keys.len()) {
        use rayon::prelude::*;
        crate::parallel::install(|| {
            out.par_chunks_mut(arity)
                .zip(keys.par_iter())
                .for_each(unpack);
        });
    } else {
        out.chunks_mut(arity).zip(keys.iter()).for_each(unpack);
    }
    Ok(out)
}

/// Bits needed to write `max` (at least 1).
pub fn id_bits(max: u32) -> u32 {
    (32 - max.leading_zeros()).max(1)
}

/// Sorts keys whose set bits all lie below `bits` (≤ 64): LSD radix sort by 11-bit digits,
/// O(n·bits/11), skipping digits on which every key agrees. Small inputs use `sort_unstable`.
/// With several threads ([`crate::parallel`]), chunks are sorted on their own threads and
/// merged: the same result, in the same memory (the keys and one scratch array as long).
pub fn radix_sort(keys: &mut Vec<u64>, bits: u32) {
    if let Err(bytes) = try_radix_sort(keys, bits) {
        abort_for(bytes)
    }
}

/// [`radix_sort`] whose scratch array is reserved fallibly: `Err(bytes)` when it cannot be had
/// (the keys are then untouched).
pub fn try_radix_sort(keys: &mut Vec<u64>, bits: u32) -> Result<(), usize> {
    if keys.len() < SMALL_SORT {
        keys.sort_unstable();
        return Ok(());
    }
    crate::parallel::sort_keys(keys, bits, radix_sort_run)
}

/// Below this many keys `sort_unstable` beats the radix sort's passes.
const SMALL_SORT: usize = 4096;

/// Sorts `keys` by LSD radix passes through `tmp` (as long), the result left in `keys`.
fn radix_sort_run(keys: &mut [u64], tmp: &mut [u64], bits: u32) {
    if keys.len() < SMALL_SORT {
        keys.sort_unstable();
        return;
    }
    radix_passes(keys, tmp, bits, |&k| k);
}

/// Stable LSD radix sort of `items` by `key(item)`, whose set bits all lie below `bits` (≤ 64).
fn radix_sort_by<T: Copy + Default>(items: &mut [T], bits: u32, key: impl Fn(&T) -> u64) {
    let mut tmp = vec![T::default(); items.len()];
    radix_passes(items, &mut tmp, bits, key);
}

/// Stable LSD radix passes of 11 bits over `items` by `key`, ping-ponging through `tmp` (as
/// long); a digit every item shares is skipped. The result is left in `items`.
fn radix_passes<T: Copy>(items: &mut [T], tmp: &mut [T], bits: u32, key: impl Fn(&T) -> u64) {
    const DIGIT: u32 = 11;
    const BUCKETS: usize = 1 << DIGIT;
    let mut count = vec![0usize; BUCKETS];
    let (mut src, mut dst) = (items, tmp);
    let mut in_tmp = false;
    let mut shift = 0;
    while shift < bits.min(64) {
        count.iter_mut().for_each(|c| *c = 0);
        for it in src.iter() {
            count[((key(it) >> shift) as usize) & (BUCKETS - 1)] += 1;
        }
        if count.contains(&src.len()) {
            shift += DIGIT;
            continue;
        }
        let mut sum = 0;
        for c in count.iter_mut() {
            let here = *c;
            *c = sum;
            sum += here;
        }
        for it in src.iter() {
            let b = ((key(it) >> shift) as usize) & (BUCKETS - 1);
            dst[count[b]] = *it;
            count[b] += 1;
        }
        std::mem::swap(&mut src, &mut dst);
        in_tmp = !in_tmp;
        shift += DIGIT;
    }
    if in_tmp {
        // `src` is the scratch now, `dst` the items.
        dst.copy_from_slice(src);
    }
}

/// The indices `0..n` sorted by `(key(i), i)`, when every key is below `2^key_bits` (≤ 64):
/// radix sort, linear; `None` for wider keys, for callers to fall back to a comparison sort.
pub fn order_by_key(
    n: usize,
    key_bits: u32,
    key: impl Fn(u32) -> u64 + Sync + Send,
) -> Option<Vec<u32>> {
    try_order_by_key(n, key_bits, key).unwrap_or_else(|bytes| abort_for(bytes))
}

/// [`order_by_key`] whose packed keys, sort scratch and order (the path split between threads,
/// taken when key and index fit one word) are reserved fallibly: `Err(bytes)` when they cannot
/// be had. Wider keys take serial paths that allocate as [`order_by_key`] does.
pub fn try_order_by_key(
    n: usize,
    key_bits: u32,
    key: impl Fn(u32) -> u64 + Sync + Send,
) -> Result<Option<Vec<u32>>, usize> {
    let Ok(last) = n.saturating_sub(1).try_into() else {
        return Ok(None);
    };
    let index_bits = id_bits(last);
    if key_bits > 64 {
        return Ok(None);
    }
    if key_bits + index_bits <= 64 {
        // Key and index packed in one word: half the memory traffic of pairs.
        let mut keys: Vec<u64> =
            crate::parallel::try_map_collect(n, |i| (key(i as u32) << index_bits) | i as u64)?;
        try_radix_sort(&mut keys, key_bits + index_bits)?;
        let mask = (1u64 << index_bits) - 1;
        return Ok(Some(crate::parallel::try_map_collect(n, |i| {
            (keys[i] & mask) as u32
        })?));
    }
    Ok(order_by_wide_key(n, key_bits, index_bits, key))
}

/// [`order_by_key`] when key and index do not fit one word together (serial).
fn order_by_wide_key(
    n: usize,
    key_bits: u32,
    index_bits: u32,
    key: impl Fn(u32) -> u64,
) -> Option<Vec<u32>> {
    let hi = key_bits + index_bits - 64;
    if hi <= 16 {
        // Key and index do not fit one word: a counting sort by the key's top `hi` bits (stable,
        // so indices stay ascending within a bucket), then each bucket, small enough to stay in
        // cache at 10^6 simplices, by its remaining key bits and the index packed in one word.
        let lo_bits = key_bits - hi;
        let lo_mask = (1u64 << lo_bits) - 1;
        let mut start = vec![0usize; (1 << hi) + 1];
        for i in 0..n as u32 {
            start[(key(i) >> lo_bits) as usize + 1] += 1;
        }
        for b in 1..start.len() {
            start[b] += start[b - 1];
        }
        let mut fill = start.clone();
        let mut words = vec![0u64; n];
        for i in 0..n as u32 {
            let k = key(i);
            let b = (k >> lo_bits) as usize;
            words[fill[b]] = ((k & lo_mask) << index_bits) | i as u64;
            fill[b] += 1;
        }
        let mut bucket = Vec::new();
        for b in start.windows(2) {
            bucket.clear();
            bucket.extend_from_slice(&words[b[0]..b[1]]);
            radix_sort(&mut bucket, 64);
            words[b[0]..b[1]].copy_from_slice(&bucket);
        }
        let mask = (1u64 << index_bits) - 1;
        return Some(words.into_iter().map(|w| (w & mask) as u32).collect());
    }
    // The sort is stable and the pairs start in index order, so equal keys stay by index.
    let mut pairs: Vec<(u64, u32)> = (0..n as u32).map(|i| (key(i), i)).collect();
    radix_sort_by(&mut pairs, key_bits, |&(k, _)| k);
    Some(pairs.into_iter().map(|(_, i)| i).collect())
}

/// Appends to `out` the facets of `simplex` (ascending ids): facet `i` omits vertex `i`, so the
/// facets come in descending lexicographic order.
pub fn push_facets(simplex: &[u32], out: &mut Vec<u32>) {
    for skip in 0..simplex.len() {
        push_facet(simplex, skip, out);
    }
}

/// Appends to `out` the facet of `simplex` that omits its vertex at position `skip`, the other
/// ids in their order.
///
/// ```
/// let mut out = vec![9];
/// topoplex::complex::push_facet(&[4, 1, 7], 1, &mut out);
/// assert_eq!(out, [9, 4, 7]);
/// ```
pub fn push_facet(simplex: &[u32], skip: usize, out: &mut Vec<u32>) {
    out.extend_from_slice(&simplex[..skip]);
    out.extend_from_slice(&simplex[skip + 1..]);
}

/// Writes the facets of `simplex` to `out` (|simplex| · (|simplex| − 1) ids) in the order of
/// [`push_facets`].
pub fn write_facets(simplex: &[u32], out: &mut [u32]) {
    let p = simplex.len() - 1;
    for (skip, f) in out.chunks_exact_mut(p).enumerate() {
        f[..skip].copy_from_slice(&simplex[..skip]);
        f[skip..].copy_from_slice(&simplex[skip + 1..]);
    }
}

/// The first index of `range` at which `below` turns false (`below` holds on a prefix of the
/// range and nowhere after it): a binary search, O(log len) calls.
#[inline]
pub(crate) fn partition_point(
    range: std::ops::Range<usize>,
    mut below: impl FnMut(usize) -> bool,
) -> usize {
    let (mut lo, mut hi) = (range.start, range.end);
    while lo < hi {
        let mid = lo + (hi - lo) / 2;
        if below(mid) {
            lo = mid + 1;
        } else {
            hi = mid;
        }
    }
    lo
}

/// Whether ascending `small` is a subset of ascending `big`: O(|big|).
pub fn is_subset(small: &[u32], big: &[u32]) -> bool {
    let mut it = big.iter();
    small.iter().all(|s| it.any(|b| b == s))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn partition_point_finds_where_a_prefix_ends_in_every_window() {
        // Against the linear scan: every window lo..hi of 0..12 and every cut inside it.
        for hi in 0..12 {
            for lo in 0..=hi {
                for cut in lo..=hi {
                    let below = |i: usize| i < cut;
                    let linear = (lo..hi).find(|&i| !below(i)).unwrap_or(hi);
                    assert_eq!(
                        partition_point(lo..hi, below),
                        linear,
                        "{lo}..{hi} cut {cut}"
                    );
                }
            }
        }
    }

    #[test]
    fn rows_sort_as_vectors_of_numbers() {
        for arity in 1..=6 {
            // `0 9 10` before `0 10 11`: numeric, not textual, order.
            let mut rows = vec![
                vec![0u32, 10, 11, 12, 13, 14],
                vec![0, 9, 10, 11, 12, 13],
                vec![0, 10, 11, 12, 13, 14],
            ];
            for r in &mut rows {
                r.truncate(arity);
            }
            let flat: Vec<u32> = rows.concat();
            let (t, dups) = SimplexTable::from_rows(arity, flat);
            let mut expect = rows.clone();
            expect.sort();
            expect.dedup();
            assert_eq!(t.iter().map(|r| r.to_vec()).collect::<Vec<_>>(), expect);
            assert_eq!(dups, rows.len() - expect.len());
            for (i, r) in expect.iter().enumerate() {
                assert_eq!(t.find(r), Some(i as u32));
            }
            assert_eq!(t.find(&vec![7; arity]), None);
        }
    }

    #[test]
    fn radix_sort_matches_comparison_sort() {
        // Large enough for the radix path, with digits on which all keys agree (skipped).
        let mut x = 0x9e37_79b9_7f4a_7c15u64;
        let mut keys: Vec<u64> = (0..20_000)
            .map(|_| {
                x ^= x << 13;
                x ^= x >> 7;
                x ^= x << 17;
                (x & 0xff_00ff_ffff) | (1 << 40)
            })
            .collect();
        let mut want = keys.clone();
        want.sort_unstable();
        radix_sort(&mut keys, 41);
        assert_eq!(keys, want);
        // Three digit passes: the result ends in the scratch array and is copied back.
        let mut odd: Vec<u64> = want
            .iter()
            .map(|k| k.wrapping_mul(0x9e37) % (1 << 33))
            .collect();
        let mut want_odd = odd.clone();
        want_odd.sort_unstable();
        try_radix_sort(&mut odd, 33).unwrap();
        assert_eq!(odd, want_odd);
        // Order by key then index: equal keys keep index order.
        let order = order_by_key(10_000, 3, |i| (i % 7 % 3) as u64).unwrap();
        let mut want: Vec<u32> = (0..10_000).collect();
        want.sort_by_key(|&i| (i % 7 % 3, i));
        assert_eq!(order, want);
        assert!(order_by_key(10, 65, |i| i as u64).is_none());
        // Keys too wide to share a word with the index: bucketed by their top bits, then
        // sorted within buckets; still by (key, index).
        let key = |i: u32| (((i % 5) as u64) << 60) | ((i * 7919) % 1000) as u64;
        let order = order_by_key(10_000, 63, key).unwrap();
        let mut want: Vec<u32> = (0..10_000).collect();
        want.sort_by_key(|&i| (key(i), i));
        assert_eq!(order, want);
        // Wider still (more than 16 bits left over): sorted as (key, index) pairs.
        let key = |i: u32| ((i % 3) as u64) << 63 | (i % 11) as u64;
        let order = order_by_key(100_000, 64, key).unwrap();
        let mut want: Vec<u32> = (0..100_000).collect();
        want.sort_by_key(|&i| (key(i), i));
        assert_eq!(order, want);
    }

    #[test]
    fn rows_of_many_vertices_sort_by_radix() {
        // Ids up to 2^20 in rows of 3: 60-bit keys, radix path; compare with slice sorting.
        let mut x = 12345u32;
        let mut ids = Vec::new();
        for _ in 0..15_000 {
            let mut r = [0u32; 3];
            for v in &mut r {
                x = x.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
                *v = (x >> 12) % 64;
            }
            r.sort_unstable();
            if r[0] < r[1] && r[1] < r[2] {
                ids.extend_from_slice(&[r[0], r[1] << 14, r[2] << 14]);
            }
        }
        let mut want: Vec<Vec<u32>> = ids.chunks(3).map(<[u32]>::to_vec).collect();
        want.sort();
        want.dedup();
        let got = sort_dedup_rows(3, ids);
        assert_eq!(got, want.concat());
    }

    #[test]
    fn facets_and_subsets() {
        let mut f = Vec::new();
        push_facets(&[1, 4, 7], &mut f);
        assert_eq!(f, vec![4, 7, 1, 7, 1, 4]);
        assert!(is_subset(&[1, 7], &[1, 4, 7]));
        assert!(!is_subset(&[1, 5], &[1, 4, 7]));
        assert!(is_subset(&[], &[1]));
    }
}
