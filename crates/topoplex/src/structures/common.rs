//! Helpers several structures share: per-query scratch sets and stacks for walks ([`IdSet`],
//! [`IdStack`], [`RowSet`]), IA's and NMIA's walk over top simplices and the check of their
//! star references ([`walk_tops`], [`check_star_refs`]), face enumeration
//! ([`faces_containing`], [`faces_of_tops`]), the union–find, per-thread pooled scratch buffers
//! ([`Scratch`]), the boundary links of a closure ([`facet_links`]), [`show`] for messages, and
//! the fallible allocations of input-sized arrays ([`try_vec`], [`try_with_capacity`],
//! [`try_iota`], [`try_reserve`]).

use rustc_hash::FxHashSet;

use super::BuildError;
use crate::complex::table::{self, partition_point};
use crate::complex::{Complex, SimplexTable, sort_dedup_rows};
pub(crate) use crate::error::show;
use crate::relation::StructureKind;
pub(crate) use crate::scratch::{Pooled, Scratch};
pub(crate) use crate::union_find::UnionFind;

/// The error for an array of `n` elements of `T` (named by `what`) that cannot be had: a build
/// under a raised budget must report `TooLarge`, never abort the host on allocation failure.
fn no_room<T>(kind: StructureKind, n: usize, what: &str) -> BuildError {
    too_large(
        kind,
        n.saturating_mul(size_of::<T>()),
        &format!("{n} {what}"),
    )
}

/// `vec![value; n]`, or `TooLarge` when the memory cannot be had (filled on several threads
/// when long: [`crate::parallel::try_filled`]).
pub(crate) fn try_vec<T: Clone + Send + Sync>(
    kind: StructureKind,
    value: T,
    n: usize,
    what: &str,
) -> Result<Vec<T>, BuildError> {
    crate::parallel::try_filled(n, value).map_err(|_| no_room::<T>(kind, n, what))
}

/// `Vec::with_capacity(n)`, or `TooLarge` when the memory cannot be had.
pub(crate) fn try_with_capacity<T>(
    kind: StructureKind,
    n: usize,
    what: &str,
) -> Result<Vec<T>, BuildError> {
    let mut v = Vec::new();
    try_reserve(kind, &mut v, n, what)?;
    Ok(v)
}

/// One vertex's star references checked as IA and NMIA keep them (`what` names them in the
/// errors): each a top simplex holding `v` (`holds(r)`), no walk from one (`walk(r, each)`,
/// `each` called for every top it reaches) reaching another. Returns the tops the walks reached.
pub(crate) fn check_star_refs(
    v: u32,
    refs: &[u32],
    what: &str,
    holds: impl Fn(u32) -> bool,
    mut walk: impl FnMut(u32, &mut dyn FnMut(u32)),
) -> Result<usize, String> {
    let mut reached = 0;
    for &r in refs {
        if !holds(r) {
            return Err(format!("{what} {r} of vertex {v} does not contain it"));
        }
        let mut clash = false;
        walk(r, &mut |t| {
            reached += 1;
            clash |= t != r && refs.contains(&t);
        });
        if clash {
            return Err(format!("two {what}s of vertex {v} are in one component"));
        }
    }
    Ok(reached)
}

/// `v.reserve_exact(extra)`, or `TooLarge` when the memory cannot be had.
pub(crate) fn try_reserve<T>(
    kind: StructureKind,
    v: &mut Vec<T>,
    extra: usize,
    what: &str,
) -> Result<(), BuildError> {
    table::try_reserve_exact(v, extra).map_err(|_| no_room::<T>(kind, extra, what))
}

/// `items.to_vec()`, or `TooLarge` when the memory cannot be had (copied on several threads
/// when long: [`crate::parallel::try_copied`]).
pub(crate) fn try_copy<T: Copy + Send + Sync>(
    kind: StructureKind,
    items: &[T],
    what: &str,
) -> Result<Vec<T>, BuildError> {
    crate::parallel::try_copied(items).map_err(|_| no_room::<T>(kind, items.len(), what))
}

/// A copy of `table`, or `TooLarge` when the memory cannot be had.
pub(crate) fn try_table(
    kind: StructureKind,
    table: &SimplexTable,
) -> Result<SimplexTable, BuildError> {
    // Copied on several threads (the copy of a large table, and its first touch of the new
    // pages, would otherwise be a serial step of every build).
    let ids = crate::parallel::try_copied(table.as_flat())
        .map_err(|bytes| too_large(kind, bytes, "a copy of a simplex table"))?;
    Ok(SimplexTable::from_arr(table.arity(), ids.into()))
}

/// The complex's closure ([`Complex::try_closure`]), or `TooLarge`.
pub(crate) fn try_closure(
    kind: StructureKind,
    complex: &Complex,
) -> Result<Vec<SimplexTable>, BuildError> {
    complex
        .try_closure()
        .map_err(|bytes| too_large(kind, bytes, "the closure"))
}

/// The closure's tables and every simplex's boundary links ([`facet_links`] per dimension):
/// made together by vertex blocks, or, where a block's keys do not fit a word, the closure and
/// then the links.
pub(crate) fn try_closure_links(
    kind: StructureKind,
    complex: &Complex,
) -> Result<(Vec<SimplexTable>, Vec<Vec<u32>>), BuildError> {
    let no_room = |bytes| too_large(kind, bytes, "the closure and its boundary links");
    if complex.dimension() > 0
        && let Some(c) = complex
            .closure_by_blocks(crate::complex::Want::Links)
            .map_err(no_room)?
    {
        return Ok((c.tables, c.boundary));
    }
    let tables = try_closure(kind, complex)?;
    let mut boundary = vec![Vec::new(); tables.len()];
    for (p, b) in boundary.iter_mut().enumerate().skip(1) {
        *b = facet_links(&tables, p);
    }
    Ok((tables, boundary))
}

/// The number of simplices of each dimension of the closure, without its tables where the
/// vertex blocks allow (memory: one block at a time per thread).
pub(crate) fn try_closure_counts(
    kind: StructureKind,
    complex: &Complex,
) -> Result<Vec<usize>, BuildError> {
    let no_room = |bytes| too_large(kind, bytes, "the closure's counts");
    if complex.dimension() > 0
        && let Some(c) = complex
            .closure_by_blocks(crate::complex::Want::Counts)
            .map_err(no_room)?
    {
        return Ok(c.counts);
    }
    Ok(try_closure(kind, complex)?
        .iter()
        .map(SimplexTable::len)
        .collect())
}

/// `Unsupported` for a complex outside `kind`'s domain, and why.
pub(crate) fn unsupported(kind: StructureKind, reason: String) -> BuildError {
    BuildError::Unsupported { kind, reason }
}

/// `TooLarge` for `bytes` that could not be had for `what`.
pub(crate) fn too_large(kind: StructureKind, bytes: usize, what: &str) -> BuildError {
    BuildError::TooLarge {
        kind,
        what: format!("cannot allocate {bytes} bytes for {what}"),
    }
}

/// [`table::order_by_key`] after checking that its peak (packed keys, the radix sort's scratch and
/// the order: 20 bytes an element) can be had, else `TooLarge`.
pub(crate) fn try_order(
    kind: StructureKind,
    n: usize,
    key_bits: u32,
    key: impl Fn(u32) -> u64 + Sync + Send,
) -> Result<Option<Vec<u32>>, BuildError> {
    crate::parallel::headroom_for(n, n.saturating_mul(20))
        .map_err(|bytes| too_large(kind, bytes, "a sort"))?;
    // Reserved fallibly too: the probe cannot see what other threads take after it.
    table::try_order_by_key(n, key_bits, key).map_err(|bytes| too_large(kind, bytes, "a sort"))
}

/// `v.push(x)` whose growth (doubling) is reserved fallibly ([`table::try_push`]), for arrays
/// whose final length the input decides but no count gives in advance.
pub(crate) fn try_push<T>(
    kind: StructureKind,
    v: &mut Vec<T>,
    x: T,
    what: &str,
) -> Result<(), BuildError> {
    table::try_push(v, x).map_err(|bytes| too_large(kind, bytes, what))
}

/// `(0..n as u32).collect()`, or `TooLarge` when the memory cannot be had.
pub(crate) fn try_iota(kind: StructureKind, n: usize, what: &str) -> Result<Vec<u32>, BuildError> {
    let mut v = try_with_capacity(kind, n, what)?;
    v.extend(0..n as u32);
    Ok(v)
}

/// Calls `f` with every (q+1)-vertex face of `top` (ascending) that contains `sigma` (ascending,
/// a subset of `top`), in no particular order. O(C(|top|−|σ|, q+1−|σ|)·(q+1)).
pub(crate) fn faces_containing(top: &[u32], sigma: &[u32], q: usize, mut f: impl FnMut(&[u32])) {
    if q + 1 < sigma.len() || q + 1 > top.len() {
        return;
    }
    let mut rest = [0u32; 16];
    let mut r = 0;
    for &v in top {
        if sigma.binary_search(&v).is_err() {
            rest[r] = v;
            r += 1;
        }
    }
    let k = q + 1 - sigma.len();
    if k > r {
        return;
    }
    let mut idx = [0usize; 16];
    for (i, x) in idx.iter_mut().enumerate().take(k) {
        *x = i;
    }
    let mut row = [0u32; 16];
    loop {
        // Merge σ with the chosen vertices into an ascending row.
        let (mut a, mut b, mut o) = (0, 0, 0);
        while a < sigma.len() || b < k {
            if b == k || (a < sigma.len() && sigma[a] < rest[idx[b]]) {
                row[o] = sigma[a];
                a += 1;
            } else {
                row[o] = rest[idx[b]];
                b += 1;
            }
            o += 1;
        }
        f(&row[..o]);
        // Next k-combination of 0..r in lexicographic order.
        let Some(i) = (0..k).rev().find(|&i| idx[i] < r - k + i) else {
            return;
        };
        idx[i] += 1;
        for j in i + 1..k {
            idx[j] = idx[j - 1] + 1;
        }
    }
}

/// Entries kept inline by the per-query scratch types below: a vertex star of a triangle or
/// tetrahedral mesh fits, so a typical query allocates nothing and scans a few cache lines
/// instead of hashing.
const INLINE: usize = 64;

/// Up to [`INLINE`] ids held inline, then `S` on the heap: the storage of [`IdSet`] and
/// [`IdStack`].
pub(crate) struct InlineIds<S> {
    /// Ids held inline (for a set, `len > INLINE` once they moved to `spill`).
    len: usize,
    inline: [u32; INLINE],
    spill: S,
}

impl<S: Default> Default for InlineIds<S> {
    fn default() -> Self {
        InlineIds {
            len: 0,
            inline: [0; INLINE],
            spill: S::default(),
        }
    }
}

/// Per-query set of ids (the papers' "visited" marks): an inline array scanned linearly while it
/// holds at most [`INLINE`] ids, a hash set beyond (so large stars stay linear).
pub(crate) type IdSet = InlineIds<FxHashSet<u32>>;

/// Per-query stack of ids: inline up to [`INLINE`] entries, then on the heap.
pub(crate) type IdStack = InlineIds<Vec<u32>>;

impl IdSet {
    /// Adds `x`; false if it was there already.
    #[inline]
    pub(crate) fn insert(&mut self, x: u32) -> bool {
        if self.len <= INLINE {
            if self.inline[..self.len].contains(&x) {
                return false;
            }
            if self.len < INLINE {
                self.inline[self.len] = x;
                self.len += 1;
                return true;
            }
            self.spill.extend(self.inline);
            self.len = INLINE + 1;
        }
        self.spill.insert(x)
    }

    #[inline]
    pub(crate) fn contains(&self, x: &u32) -> bool {
        if self.len <= INLINE {
            self.inline[..self.len].contains(x)
        } else {
            self.spill.contains(x)
        }
    }

    pub(crate) fn clear(&mut self) {
        self.len = 0;
        self.spill.clear();
    }
}

impl IdStack {
    #[inline]
    pub(crate) fn push(&mut self, x: u32) {
        if self.len < INLINE {
            self.inline[self.len] = x;
            self.len += 1;
        } else {
            self.spill.push(x);
        }
    }

    #[inline]
    pub(crate) fn pop(&mut self) -> Option<u32> {
        if let Some(x) = self.spill.pop() {
            return Some(x);
        }
        if self.len == 0 {
            return None;
        }
        self.len -= 1;
        Some(self.inline[self.len])
    }
}

/// The frontier of a walk over top simplices ([`walk_tops`]): what is reached, once.
pub(crate) struct Frontier<'s> {
    seen: &'s mut IdSet,
    stack: IdStack,
}

impl Frontier<'_> {
    /// Queues top `u` unless the walk has seen it.
    #[inline]
    pub(crate) fn reach(&mut self, u: u32) {
        if self.seen.insert(u) {
            self.stack.push(u);
        }
    }
}

/// The depth-first walk of IA and NMIA over top simplices: from each of `starts`, every top
/// `expand(t, verts(t), frontier)` reaches, each once (`seen` must hold none of them);
/// `visit(t, verts(t))` for each, stopping (and returning false) when it returns false.
#[inline]
pub(crate) fn walk_tops<'a>(
    starts: &[u32],
    seen: &mut IdSet,
    verts: impl Fn(u32) -> &'a [u32],
    mut visit: impl FnMut(u32, &[u32]) -> bool,
    mut expand: impl FnMut(u32, &[u32], &mut Frontier),
) -> bool {
    let mut frontier = Frontier {
        seen,
        stack: IdStack::default(),
    };
    for &r in starts {
        frontier.reach(r);
        while let Some(t) = frontier.stack.pop() {
            let vs = verts(t);
            if !visit(t, vs) {
                return false;
            }
            expand(t, vs, &mut frontier);
        }
    }
    true
}

/// Per-query set of rows already emitted: rows of up to four ids as one u128 key, kept inline
/// and scanned while few (as [`IdSet`]), hashed beyond; longer rows hashed as vectors.
pub(crate) struct RowSet {
    len: usize,
    inline: [u128; RowSet::INLINE],
    small: FxHashSet<u128>,
    big: FxHashSet<Vec<u32>>,
}

impl Default for RowSet {
    fn default() -> Self {
        RowSet {
            len: 0,
            inline: [0; RowSet::INLINE],
            small: FxHashSet::default(),
            big: FxHashSet::default(),
        }
    }
}

impl RowSet {
    /// Fewer than [`IdSet`]'s: u128 compares cost more and row sets grow faster than stars.
    const INLINE: usize = 32;

    pub(crate) fn insert(&mut self, row: &[u32]) -> bool {
        if row.len() > 4 {
            return self.big.insert(row.to_vec());
        }
        let key = row.iter().fold(0u128, |acc, &v| (acc << 32) | v as u128);
        if self.len <= Self::INLINE {
            if self.inline[..self.len].contains(&key) {
                return false;
            }
            if self.len < Self::INLINE {
                self.inline[self.len] = key;
                self.len += 1;
                return true;
            }
            self.small.extend(self.inline);
            self.len = Self::INLINE + 1;
        }
        self.small.insert(key)
    }

    /// Appends `row` to `out` unless it was emitted before.
    pub(crate) fn emit(&mut self, row: &[u32], out: &mut Vec<u32>) {
        if self.insert(row) {
            out.extend_from_slice(row);
        }
    }
}

/// The p-simplices of the closure of `tops` (rows of equal arity), ascending lexicographic.
pub(crate) fn faces_of_tops<'a>(
    tops: impl Iterator<Item = &'a [u32]>,
    p: usize,
    rows: &mut Vec<u32>,
) {
    for t in tops {
        faces_containing(t, &[], p, |f| rows.extend_from_slice(f));
    }
    *rows = sort_dedup_rows(p + 1, std::mem::take(rows));
}

/// B_{p,p−1} of every p-simplex of a closure (`tables` by dimension, each sorted): slot
/// `k·(p+1) + i` holds the row in `tables[p − 1]` of the facet of simplex k opposite its vertex
/// i. Each facet is found by binary search among the rows that start with its first vertex (a
/// range the size of a vertex star, so the search stays in cache); p-simplices in ranges on
/// [`crate::parallel::threads`] threads, each row written by one range. O(n_p · p · log star).
pub(crate) fn facet_links(tables: &[crate::complex::SimplexTable], p: usize) -> Vec<u32> {
    let below = &tables[p - 1];
    // start[v]: the first row of `below` whose first vertex is ≥ v.
    let n = tables[0].len();
    let mut start = vec![0u32; n + 1];
    for s in below.iter() {
        start[s[0] as usize + 1] += 1;
    }
    for v in 0..n {
        start[v + 1] += start[v];
    }
    // Rows as one word each when p ids fit (a compare of words, not of slices).
    let bits = crate::complex::table::id_bits(n.saturating_sub(1) as u32);
    let pack = |r: &[u32]| r.iter().fold(0u64, |k, &v| k << bits | u64::from(v));
    let packed = (p as u32 * bits <= 64)
        .then(|| crate::parallel::map_collect(below.len(), |i| pack(below.get(i))));
    let mut b = vec![0u32; tables[p].len() * (p + 1)];
    crate::parallel::fill_rows(&mut b, p + 1, |i, row| {
        let s = tables[p].get(i);
        let mut facet = [0u32; 16];
        for (skip, slot) in row.iter_mut().enumerate() {
            facet[..skip].copy_from_slice(&s[..skip]);
            facet[skip..p].copy_from_slice(&s[skip + 1..]);
            let (lo, hi) = (
                start[facet[0] as usize] as usize,
                start[facet[0] as usize + 1] as usize,
            );
            let k = match &packed {
                Some(keys) => {
                    let key = pack(&facet[..p]);
                    lo + keys[lo..hi].partition_point(|&x| x < key)
                }
                None => partition_point(lo..hi, |mid| below.get(mid) < &facet[..p]),
            };
            debug_assert_eq!(below.get(k), &facet[..p], "closure contains every facet");
            *slot = k as u32;
        }
    });
    b
}

/// (vertex, top simplex) pairs in parts (as the ranges of top simplices that found them
/// returned them), read as the one list of the parts one after another, for
/// [`crate::parallel::try_invert`]: from vertex to top simplex (the vertex star references of
/// the IA and the NMIA).
pub(crate) struct PairParts {
    parts: Vec<Vec<(u32, u32)>>,
    /// `first[k]`: the index of part `k`'s first pair in the whole list (then the total).
    first: Vec<usize>,
}

impl PairParts {
    pub(crate) fn new(parts: Vec<Vec<(u32, u32)>>) -> PairParts {
        let mut first = Vec::with_capacity(parts.len() + 1);
        first.push(0);
        for p in &parts {
            first.push(first[first.len() - 1] + p.len());
        }
        PairParts { parts, first }
    }

    pub(crate) fn len(&self) -> usize {
        self.first[self.parts.len()]
    }
}

impl crate::parallel::Incidences for PairParts {
    fn visit(&self, range: std::ops::Range<usize>, f: &mut impl FnMut(u32, u32)) {
        // The last part starting at or before the range (empty parts are stepped over).
        let mut k = self.first.partition_point(|&s| s <= range.start).max(1) - 1;
        for i in range {
            while i >= self.first[k + 1] {
                k += 1;
            }
            let (v, t) = self.parts[k][i - self.first[k]];
            f(t, v);
        }
    }
}
