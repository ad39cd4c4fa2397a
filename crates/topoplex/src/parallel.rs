//! Threads for the build steps, and the parallel primitives they use.
//!
//! Every parallel step is deterministic: it either sorts (the sorted output does not depend on
//! how the work was split), writes each result to a position fixed before the split, or keeps
//! a minimum (the union–find's roots, a top simplex's first listing), so a structure built
//! with any number of threads is the same, byte for byte, as the serial one.
//!
//! Primitives: sorts of packed keys (`sort_keys`); collects, fills and copies in index order,
//! written in place into arrays reserved fallibly (filling a large array, and the first touch
//! of its pages, is then no serial step of a build); a CSR inversion with one range of sources
//! per thread (`try_invert`: the IG's co-boundaries, the SIG's tops above each simplex, the
//! IA's slot-0 buckets and star references); and a lock-free union–find whose roots are each
//! class's smallest member (`SharedUnionFind`: the IA's star components, the 2D structures'
//! corner components).
//!
//! The thread count is [`set_threads`] (the CLI's `--threads`, the C ABI's `tpx_set_threads`),
//! else the `TOPOPLEX_THREADS` environment variable, else every core. The pool starts with the
//! first step large enough to split (2^16 items): reading and building a small
//! input stays on the calling thread, so it pays no thread stacks or per-thread malloc arenas.

use std::sync::atomic::{AtomicU32, AtomicUsize, Ordering};
use std::sync::{Arc, Mutex};

/// 0: not set, read the environment.
static THREADS: AtomicUsize = AtomicUsize::new(0);

/// Below this many items a step runs serially: splitting costs more than it saves.
pub(crate) const MIN_PARALLEL: usize = 1 << 16;

/// The split threshold build steps use: [`MIN_PARALLEL`] unless a test lowered it.
static SPLIT_AT: AtomicUsize = AtomicUsize::new(MIN_PARALLEL);

/// Lowers (or restores) the number of items below which build steps run serially, so tests of
/// determinism split small complexes as a large one would be split. Not for production use.
#[doc(hidden)]
pub fn set_split_threshold(n: usize) {
    SPLIT_AT.store(n.max(1), Ordering::Relaxed);
}

/// Whether a step over `n` items runs on several threads: [`threads`] is above 1, `n` reaches
/// the split threshold, and the pool is running (a pool that cannot start, e.g. under a memory
/// limit, leaves the step serial: the same bytes, see the module doc).
pub(crate) fn splits(n: usize) -> bool {
    threads() > 1 && n >= split_threshold() && pool(threads()).is_some()
}

/// The number of items from which a step splits ([`MIN_PARALLEL`] unless a test lowered it).
fn split_threshold() -> usize {
    SPLIT_AT.load(Ordering::Relaxed)
}

/// `0..n` cut into consecutive ranges for a parallel step: one range when the step runs
/// serially, else 4 per thread (so uneven ranges even out). Callers concatenate the results in
/// range order, which makes them independent of the thread count.
pub(crate) fn ranges(n: usize) -> Vec<std::ops::Range<usize>> {
    if !splits(n) {
        return std::iter::once(0..n).collect();
    }
    let parts = (4 * threads()).min(n).max(1);
    let step = n.div_ceil(parts);
    (0..n).step_by(step).map(|a| a..(a + step).min(n)).collect()
}

/// Consecutive ranges of the `off.len() - 1` items of a CSR layout (item `i` weighs
/// `off[i + 1] - off[i]`), cut so that each holds about the same weight: one range when the
/// total weight is below the split threshold, else 4 per thread.
pub(crate) fn ranges_by_weight(off: &[usize]) -> Vec<std::ops::Range<usize>> {
    let n = off.len().saturating_sub(1);
    let total = off.last().copied().unwrap_or(0);
    if !splits(total) || n == 0 {
        return std::iter::once(0..n).collect();
    }
    let parts = 4 * threads();
    let mut cuts: Vec<usize> = (1..parts)
        .map(|k| off.partition_point(|&o| o < k * total / parts).min(n))
        .collect();
    cuts.insert(0, 0);
    cuts.push(n);
    cuts.dedup();
    cuts.windows(2).map(|w| w[0]..w[1]).collect()
}

/// `f` over each of [`ranges`]`(n)`, results in range order.
pub(crate) fn map_ranges<T: Send>(
    n: usize,
    f: impl Fn(std::ops::Range<usize>) -> T + Sync + Send,
) -> Vec<T> {
    let r = ranges(n);
    map_chunks(r.len(), |i| f(r[i].clone()))
}

/// `f(i, row)` for every row `i` of `width` items of `out` (each row written by one call; the
/// last row may be shorter), on several threads when `out` holds enough items (rows of many
/// items split as readily as many rows of one), in runs of rows like [`ranges`].
pub(crate) fn fill_rows<T: Send>(
    out: &mut [T],
    width: usize,
    f: impl Fn(usize, &mut [T]) + Sync + Send,
) {
    use rayon::prelude::*;
    let width = width.max(1);
    if !splits(out.len()) {
        out.chunks_mut(width)
            .enumerate()
            .for_each(|(i, row)| f(i, row));
        return;
    }
    let step = out.len().div_ceil(width).div_ceil(4 * threads());
    install(|| {
        out.par_chunks_mut(step * width)
            .enumerate()
            .for_each(|(c, part)| {
                for (k, row) in part.chunks_mut(width).enumerate() {
                    f(c * step + k, row);
                }
            })
    });
}

/// The most threads a build may use: a bound on what any front end can ask for, so that a
/// mistyped count cannot start thousands of threads (each with its stack).
pub const MAX_THREADS: usize = 256;

/// Sets the number of threads later builds use, held to `1..=MAX_THREADS` (front ends refuse
/// counts outside it with [`check_threads`] rather than have them moved).
pub fn set_threads(n: usize) {
    THREADS.store(n.clamp(1, MAX_THREADS), Ordering::Relaxed);
}

/// `Ok(n)` when `n` is a thread count a front end may set, else why not (one line).
pub fn check_threads(n: usize) -> Result<usize, String> {
    if (1..=MAX_THREADS).contains(&n) {
        Ok(n)
    } else {
        Err(format!("thread count {n} is outside 1..={MAX_THREADS}"))
    }
}

/// The `TOPOPLEX_THREADS` environment variable: `Ok(None)` when it is not set, `Ok(Some(n))`
/// for a count in `1..=MAX_THREADS`, else an error naming the variable and its (escaped) value.
/// [`threads`] falls back to every core when the value is not a count; front ends call this
/// first so that a bad value is reported rather than ignored.
pub fn threads_from_env() -> Result<Option<usize>, String> {
    let Some(v) = std::env::var_os("TOPOPLEX_THREADS") else {
        return Ok(None);
    };
    let text = v.to_string_lossy();
    let bad = || {
        format!(
            "TOPOPLEX_THREADS={}: not a thread count in 1..={MAX_THREADS}",
            crate::error::echo(text.as_bytes())
        )
    };
    let n = text.trim().parse::<usize>().map_err(|_| bad())?;
    check_threads(n).map(Some).map_err(|_| bad())
}

/// The number of threads builds use: [`set_threads`], else `TOPOPLEX_THREADS`, else the
/// number of cores.
pub fn threads() -> usize {
    // Read once: `available_parallelism` reads cgroup files on every call, and small sorts on
    // query paths ask for the thread count.
    static DEFAULT: std::sync::OnceLock<usize> = std::sync::OnceLock::new();
    match THREADS.load(Ordering::Relaxed) {
        0 => *DEFAULT.get_or_init(|| {
            threads_from_env()
                .ok()
                .flatten()
                .unwrap_or_else(|| std::thread::available_parallelism().map_or(1, |n| n.get()))
                .min(MAX_THREADS)
        }),
        n => n,
    }
}

/// The pool for `n` threads, built on first use and kept (one per count asked for); `None`
/// when its threads cannot be started (no memory for their stacks, a thread limit), tried
/// again on the next call. Callers then run serially, never on rayon's global pool.
fn pool(n: usize) -> Option<Arc<rayon::ThreadPool>> {
    static POOLS: Mutex<Vec<(usize, Arc<rayon::ThreadPool>)>> = Mutex::new(Vec::new());
    let mut pools = POOLS.lock().unwrap_or_else(|e| e.into_inner());
    if let Some((_, p)) = pools.iter().find(|(k, _)| *k == n) {
        return Some(Arc::clone(p));
    }
    // Rayon stops the threads it did start when a later one fails.
    let p = Arc::new(
        rayon::ThreadPoolBuilder::new()
            .num_threads(n)
            .thread_name(|i| format!("topoplex-{i}"))
            .build()
            .ok()?,
    );
    pools.push((n, Arc::clone(&p)));
    Some(p)
}

/// Starts the pool of [`threads`] threads now if there are several and it is not running, so
/// that a memory probe made next counts what the threads took (see
/// [`headroom`]).
pub(crate) fn start_pool() {
    if threads() > 1 {
        let _ = pool(threads());
    }
}

/// Runs `f` in the pool of [`threads`] threads (directly when that is 1 or the pool cannot
/// start), so rayon calls inside use that many threads. Callers reach it only after
/// [`splits`] (or [`map_chunks`]' own check) found the pool running, which it then stays.
pub(crate) fn install<R: Send>(f: impl FnOnce() -> R + Send) -> R {
    match threads() {
        1 => f(),
        n => match pool(n) {
            Some(p) => p.install(f),
            None => f(),
        },
    }
}

/// Sorts `keys` (set bits below `bits`) in ascending order with `sort_run(run, scratch, bits)`,
/// which sorts `run` using `scratch` (as long) and leaves the result in `run`: with one thread or
/// few keys, once over all keys; else each of [`threads`] chunks on its own thread, then the
/// sorted runs are merged, every merge split between threads at a co-ranked position. One
/// scratch buffer as long as `keys` serves the runs and then the merges, so the sort's peak is
/// the same with any number of threads; `Err(bytes)` when it cannot be reserved.
pub(crate) fn sort_keys(
    keys: &mut Vec<u64>,
    bits: u32,
    sort_run: fn(&mut [u64], &mut [u64], u32),
) -> Result<(), usize> {
    let mut tmp = Vec::new();
    crate::alloc::try_reserve_exact(&mut tmp, keys.len())?;
    tmp.resize(keys.len(), 0u64);
    if !splits(keys.len()) {
        sort_run(keys, &mut tmp, bits);
        return Ok(());
    }
    let t = threads();
    install(|| {
        let runs = t.next_power_of_two();
        let chunk = keys.len().div_ceil(runs);
        rayon::scope(|s| {
            for (part, scratch) in keys.chunks_mut(chunk).zip(tmp.chunks_mut(chunk)) {
                s.spawn(move |_| sort_run(part, scratch, bits));
            }
        });
        // Merge runs pairwise, doubling their width each round.
        let mut width = chunk;
        while width < keys.len() {
            merge_round(keys, &mut tmp, width);
            std::mem::swap(keys, &mut tmp);
            width *= 2;
        }
    });
    Ok(())
}

/// Merges each pair of adjacent sorted runs of `width` from `src` into `dst`.
fn merge_round(src: &[u64], dst: &mut [u64], width: usize) {
    rayon::scope(|s| {
        for (pair, out) in src.chunks(2 * width).zip(dst.chunks_mut(2 * width)) {
            s.spawn(move |_| {
                let (a, b) = pair.split_at(width.min(pair.len()));
                par_merge(a, b, out);
            });
        }
    });
}

/// Merges sorted `a` and `b` into `out`, splitting large merges in two halves that rayon may
/// run on two threads: the first half of `out` takes the smallest elements (co-ranking).
fn par_merge(a: &[u64], b: &[u64], out: &mut [u64]) {
    if out.len() < MIN_PARALLEL {
        merge(a, b, out);
        return;
    }
    let half = out.len() / 2;
    // i elements from a and half - i from b form the smallest half.
    let (mut lo, mut hi) = (half.saturating_sub(b.len()), half.min(a.len()));
    while lo < hi {
        let i = (lo + hi) / 2;
        if a[i] < b[half - i - 1] {
            lo = i + 1;
        } else {
            hi = i;
        }
    }
    let (a1, a2) = a.split_at(lo);
    let (b1, b2) = b.split_at(half - lo);
    let (o1, o2) = out.split_at_mut(half);
    rayon::join(|| par_merge(a1, b1, o1), || par_merge(a2, b2, o2));
}

fn merge(a: &[u64], b: &[u64], out: &mut [u64]) {
    let (mut i, mut j) = (0, 0);
    for o in out.iter_mut() {
        if j == b.len() || (i < a.len() && a[i] <= b[j]) {
            *o = a[i];
            i += 1;
        } else {
            *o = b[j];
            j += 1;
        }
    }
}

/// `f(i)` for every `i` in `0..n`, collected in index order: split in [`threads`] ranges when
/// `n` is large, so the result does not depend on the thread count.
pub(crate) fn map_collect<T: Send>(n: usize, f: impl Fn(usize) -> T + Sync + Send) -> Vec<T> {
    use rayon::prelude::*;
    if !splits(n) {
        return (0..n).map(f).collect();
    }
    install(|| (0..n).into_par_iter().map(f).collect())
}

/// [`map_collect`] into an array reserved fallibly before any `f` runs: `Err(bytes)` when it
/// cannot be had. Rayon's collect writes in place into the reserved array, so the threads add
/// no array of their own.
pub(crate) fn try_map_collect<T: Send>(
    n: usize,
    f: impl Fn(usize) -> T + Sync + Send,
) -> Result<Vec<T>, usize> {
    let mut out = Vec::new();
    crate::alloc::try_reserve_exact(&mut out, n)?;
    extend_reserved(&mut out, n, f);
    Ok(out)
}

/// Appends `f(i)` for `i` in `0..n` to `v`, whose spare capacity (at least `n`, reserved
/// fallibly by the caller) it writes in place: on several threads when `n` is large, so the
/// first touch of the new pages is split too. Results in index order.
pub(crate) fn extend_reserved<T: Send>(
    v: &mut Vec<T>,
    n: usize,
    f: impl Fn(usize) -> T + Sync + Send,
) {
    use rayon::prelude::*;
    debug_assert!(v.capacity() - v.len() >= n, "capacity not reserved");
    if splits(n) {
        install(|| v.par_extend((0..n).into_par_iter().map(f)));
    } else {
        v.extend((0..n).map(f));
    }
}

/// [`try_map_collect`] with a scratch state per run of at least `run` consecutive indices
/// (`init()` at each run's start): `f(state, i)` may use it as a hint (the last answer, to try
/// first) but its result must not depend on it, so that the array is the same for any split.
pub(crate) fn try_map_collect_with<S, T: Send>(
    n: usize,
    run: usize,
    init: impl Fn() -> S + Sync + Send,
    f: impl Fn(&mut S, usize) -> T + Sync + Send,
) -> Result<Vec<T>, usize> {
    use rayon::prelude::*;
    let mut out = Vec::new();
    crate::alloc::try_reserve_exact(&mut out, n)?;
    if splits(n) {
        let items = (0..n).into_par_iter().with_min_len(run.max(1));
        install(|| out.par_extend(items.map_init(init, f)));
    } else {
        let mut state = init();
        out.extend((0..n).map(|i| f(&mut state, i)));
    }
    Ok(out)
}

/// `n` copies of `value` in an array reserved fallibly (`Err(bytes)`), written on several
/// threads when `n` is large.
pub(crate) fn try_filled<T: Clone + Send + Sync>(n: usize, value: T) -> Result<Vec<T>, usize> {
    try_map_collect(n, |_| value.clone())
}

/// A copy of `items` in an array reserved fallibly (`Err(bytes)`), copied on several threads
/// when it is long.
pub(crate) fn try_copied<T: Copy + Send + Sync>(items: &[T]) -> Result<Vec<T>, usize> {
    let mut out = Vec::new();
    crate::alloc::try_reserve_exact(&mut out, items.len())?;
    if splits(items.len()) {
        extend_reserved(&mut out, items.len(), |i| items[i]);
    } else {
        out.extend_from_slice(items);
    }
    Ok(out)
}

/// `f(item)` for each of `items` (pieces of work the caller cut, e.g. one per range of
/// [`ranges`]), results in order: on [`threads`] threads when there are several pieces, on the
/// calling thread when there is one (so a small input never wakes the pool).
pub(crate) fn map_items<I: Send, T: Send>(
    items: Vec<I>,
    f: impl Fn(I) -> T + Sync + Send,
) -> Vec<T> {
    use rayon::prelude::*;
    if items.len() < 2 {
        return items.into_iter().map(f).collect();
    }
    install(|| items.into_par_iter().map(f).collect())
}

/// `f(c)` for each of `chunks` chunks of work the caller sized, in chunk order: on
/// [`threads`] threads whenever there are several chunks.
pub(crate) fn map_chunks<T: Send>(chunks: usize, f: impl Fn(usize) -> T + Sync + Send) -> Vec<T> {
    use rayon::prelude::*;
    if threads() == 1 || chunks < 2 || pool(threads()).is_none() {
        return (0..chunks).map(f).collect();
    }
    install(|| (0..chunks).into_par_iter().map(f).collect())
}

/// `n` atomic words set by `init(i)`, reserved fallibly (`Err(bytes)`), set on several threads
/// when `n` is large.
pub(crate) fn try_atomics(
    n: usize,
    init: impl Fn(usize) -> u32 + Sync + Send,
) -> Result<Vec<AtomicU32>, usize> {
    try_map_collect(n, |i| AtomicU32::new(init(i)))
}

/// The plain words of `v`, in place (same size and alignment: no new allocation).
pub(crate) fn into_plain(v: Vec<AtomicU32>) -> Vec<u32> {
    v.into_iter().map(AtomicU32::into_inner).collect()
}

/// Union–find over `0..n` that several threads may merge into at once (lock-free: a root is
/// linked below a smaller root by compare-and-swap, paths are halved by compare-and-swap). A
/// parent is never larger than its child, so each class's root is its smallest member whatever
/// the order of the unions or the number of threads: labels are deterministic. 4 bytes per item.
pub(crate) struct SharedUnionFind(Vec<AtomicU32>);

impl SharedUnionFind {
    /// `n` singletons (`n` ≤ 2^32), or `Err(bytes)` when the memory cannot be had.
    pub(crate) fn try_new(n: usize) -> Result<Self, usize> {
        Ok(SharedUnionFind(try_atomics(n, |i| i as u32)?))
    }

    /// The root of `x`'s class (the smallest member once every union is done).
    pub(crate) fn find(&self, mut x: u32) -> u32 {
        loop {
            let up = self.0[x as usize].load(Ordering::Relaxed);
            if up == x {
                return x;
            }
            let upper = self.0[up as usize].load(Ordering::Relaxed);
            if upper != up {
                // Path halving; losing the race only leaves a longer path.
                let _ = self.0[x as usize].compare_exchange_weak(
                    up,
                    upper,
                    Ordering::Relaxed,
                    Ordering::Relaxed,
                );
            }
            x = upper;
        }
    }

    /// Merges the classes of `a` and `b`.
    pub(crate) fn union(&self, a: u32, b: u32) {
        let (mut a, mut b) = (a, b);
        loop {
            a = self.find(a);
            b = self.find(b);
            if a == b {
                return;
            }
            let (lo, hi) = (a.min(b), a.max(b));
            // Succeeds only while `hi` is still a root; else retry from the new roots.
            if self.0[hi as usize]
                .compare_exchange(hi, lo, Ordering::Relaxed, Ordering::Relaxed)
                .is_ok()
            {
                return;
            }
        }
    }

    /// Each item's root (its class's smallest member), once every union is done; roots are
    /// found on several threads for many items. No new array: the parent words become the roots.
    pub(crate) fn into_roots(self) -> Vec<u32> {
        map_ranges(self.0.len(), |range| {
            for x in range {
                let root = self.find(x as u32);
                self.0[x].store(root, Ordering::Relaxed);
            }
        });
        into_plain(self.0)
    }

    /// Whether `x` is its class's root (its smallest member, once every union is done).
    pub(crate) fn is_root(&self, x: u32) -> bool {
        self.0[x as usize].load(Ordering::Relaxed) == x
    }
}

/// A relation from sources `0..n` to targets, for [`try_invert`].
pub(crate) trait Incidences: Sync {
    /// Calls `f(value, t)` for each target `t` of each source in `range`, sources in order;
    /// `value` is what the inversion lists for that source.
    fn visit(&self, range: std::ops::Range<usize>, f: &mut impl FnMut(u32, u32));
}

/// Inverts a relation from `sources` items to `targets` items into CSR form (offsets,
/// entries): target `t`'s entries are the values of its sources ([`Incidences::visit`]), in
/// source order. On several threads when `sources` is large: the sources are cut into one
/// range per thread, each range counts its targets in an array of its own, and each target's
/// entries are laid out range after range, so every range scatters its sources, in order, to
/// positions fixed before the split: the same arrays with any thread count, no sort. Offsets
/// and entries fit 32 bits (callers check). `Err(bytes)` when an array cannot be had: 4 bytes a
/// target and 4 an entry, plus 4 a target per thread when split.
/// O(sources + threads·targets + entries).
pub(crate) fn try_invert(
    targets: usize,
    sources: usize,
    inc: &impl Incidences,
) -> Result<(Vec<u32>, Vec<u32>), usize> {
    use crate::alloc::try_reserve_exact;
    if !splits(sources) {
        return invert_serial(targets, sources, inc);
    }
    let parts = threads().min(sources);
    let step = sources.div_ceil(parts);
    let part = |r: usize| r * step..((r + 1) * step).min(sources);
    // Per range, its count of each target, then (in place) its first position in each target.
    let mut cursors = Vec::new();
    try_reserve_exact(&mut cursors, parts)?;
    for _ in 0..parts {
        let mut c = Vec::new();
        try_reserve_exact(&mut c, targets)?;
        c.resize(targets, 0u32);
        cursors.push(c);
    }
    install(|| {
        use rayon::prelude::*;
        cursors.par_iter_mut().enumerate().for_each(|(r, c)| {
            inc.visit(part(r), &mut |_, t| c[t as usize] += 1);
        })
    });
    let mut off = Vec::new();
    try_reserve_exact(&mut off, targets + 1)?;
    off.resize(targets + 1, 0u32);
    offsets_by_range(&mut off, &mut cursors);
    let list = try_atomics(off[targets] as usize, |_| 0)?;
    install(|| {
        use rayon::prelude::*;
        cursors.par_iter_mut().enumerate().for_each(|(r, c)| {
            inc.visit(part(r), &mut |x, t| {
                list[c[t as usize] as usize].store(x, Ordering::Relaxed);
                c[t as usize] += 1;
            });
        })
    });
    Ok((off, into_plain(list)))
}

/// [`try_invert`] on one thread: a counting sort, which keeps source order by itself.
fn invert_serial(
    targets: usize,
    sources: usize,
    inc: &impl Incidences,
) -> Result<(Vec<u32>, Vec<u32>), usize> {
    use crate::alloc::try_reserve_exact;
    let mut off = Vec::new();
    try_reserve_exact(&mut off, targets + 1)?;
    off.resize(targets + 1, 0u32);
    inc.visit(0..sources, &mut |_, t| off[t as usize + 1] += 1);
    for i in 0..targets {
        off[i + 1] += off[i];
    }
    let mut fill = Vec::new();
    try_reserve_exact(&mut fill, targets)?;
    fill.extend_from_slice(&off[..targets]);
    let mut list = Vec::new();
    try_reserve_exact(&mut list, off[targets] as usize)?;
    list.resize(off[targets] as usize, 0u32);
    inc.visit(0..sources, &mut |x, t| {
        list[fill[t as usize] as usize] = x;
        fill[t as usize] += 1;
    });
    Ok((off, list))
}

/// From each range's count of each target (`counts[r][t]`): the CSR offsets `off` (targets + 1)
/// and, in place of the counts, each range's first position in each target (the ranges' entries
/// one after another). Targets in blocks on several threads: each block's total first, then
/// the blocks' offsets.
fn offsets_by_range(off: &mut [u32], counts: &mut [Vec<u32>]) {
    use rayon::prelude::*;
    let targets = off.len() - 1;
    let block = targets.div_ceil(4 * threads()).max(1);
    let blocks = targets.div_ceil(block);
    let totals: Vec<u32> = map_chunks(blocks, |b| {
        (b * block..((b + 1) * block).min(targets))
            .map(|t| counts.iter().map(|c| c[t]).sum::<u32>())
            .sum()
    });
    let mut starts = Vec::with_capacity(blocks);
    let mut acc = 0u32;
    for t in totals {
        starts.push(acc);
        acc += t;
    }
    off[targets] = acc;
    // Each block's slice of `off` (its targets' starts) and of every range's counts.
    let mut pieces = Vec::with_capacity(blocks);
    let mut per_range: Vec<std::slice::ChunksMut<'_, u32>> =
        counts.iter_mut().map(|c| c.chunks_mut(block)).collect();
    for (o, start) in off[..targets].chunks_mut(block).zip(starts) {
        let cs: Vec<&mut [u32]> = per_range.iter_mut().map(|it| it.next().unwrap()).collect();
        pieces.push((start, o, cs));
    }
    install(|| {
        pieces.into_par_iter().for_each(|(mut acc, o, mut cs)| {
            for (k, slot) in o.iter_mut().enumerate() {
                *slot = acc;
                for c in cs.iter_mut() {
                    let n = c[k];
                    c[k] = acc;
                    acc += n;
                }
            }
        })
    });
}

/// Whether `bytes` more can be allocated now: reserved and released at once (address space,
/// not pages), so a step whose peak is known but whose buffers are made infallibly (a sort's
/// keys and scratch) fails with `Err(bytes)` before it starts rather than aborting half way.
/// For a step that may split, the crate uses `headroom_for`, which starts the pool first.
pub fn headroom(bytes: usize) -> Result<(), usize> {
    let mut probe: Vec<u8> = Vec::new();
    probe.try_reserve_exact(bytes).map_err(|_| bytes)
}

/// [`headroom`] for a step over `items` items: when it will split (see [`splits`]), the pool
/// is started first (or found not to start), so that its threads' stacks are not taken after
/// the probe passed. A step too small to split never starts the pool: two threads' stacks and
/// malloc arenas would cost a small input more memory than they save time.
pub(crate) fn headroom_for(items: usize, bytes: usize) -> Result<(), usize> {
    if threads() > 1 && items >= split_threshold() {
        start_pool();
    }
    headroom(bytes)
}

/// Appends `n` copies of `x` to `v`, on several threads when `n` reaches the split threshold
/// (the pages are then touched in parallel);
/// the capacity must be reserved already (checked: false, nothing appended, when it is not).
pub(crate) fn extend_filled<T: Copy + Send + Sync>(v: &mut Vec<T>, n: usize, x: T) -> bool {
    if v.capacity() - v.len() < n {
        return false;
    }
    if splits(n) {
        use rayon::prelude::*;
        install(|| v.par_extend(rayon::iter::repeat_n(x, n)));
    } else {
        v.extend(std::iter::repeat_n(x, n));
    }
    true
}

/// Appends `f(i)` for `i` in `0..n` to `v`, on several threads when `n` reaches the split
/// threshold; the capacity must be reserved already (checked: false, nothing appended, when it
/// is not).
pub(crate) fn extend_with<T: Send>(
    v: &mut Vec<T>,
    n: usize,
    f: impl Fn(usize) -> T + Sync + Send,
) -> bool {
    if v.capacity() - v.len() < n {
        return false;
    }
    if splits(n) {
        use rayon::prelude::*;
        install(|| v.par_extend((0..n).into_par_iter().map(f)));
    } else {
        v.extend((0..n).map(f));
    }
    true
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn merging_sorted_runs_matches_a_serial_sort() {
        let mut x = 0x9e37_79b9_7f4a_7c15u64;
        for n in [0, 1, 5, MIN_PARALLEL - 1, 3 * MIN_PARALLEL + 17] {
            let keys: Vec<u64> = (0..n)
                .map(|_| {
                    x ^= x << 13;
                    x ^= x >> 7;
                    x ^= x << 17;
                    x % 1000 // many equal keys
                })
                .collect();
            let mut want = keys.clone();
            want.sort_unstable();
            for t in [2, 3, 4] {
                let mut got = keys.clone();
                pool(t).expect("a pool").install(|| {
                    let runs = t.next_power_of_two();
                    let chunk = got.len().div_ceil(runs).max(1);
                    for part in got.chunks_mut(chunk) {
                        part.sort_unstable();
                    }
                    let mut tmp = vec![0u64; got.len()];
                    let mut width = chunk;
                    while width < got.len() {
                        merge_round(&got, &mut tmp, width);
                        std::mem::swap(&mut got, &mut tmp);
                        width *= 2;
                    }
                });
                assert_eq!(got, want, "n = {n}, {t} threads");
            }
        }
    }

    fn xorshift(x: &mut u64) -> u64 {
        *x ^= *x << 13;
        *x ^= *x >> 7;
        *x ^= *x << 17;
        *x
    }

    #[test]
    fn shared_union_find_roots_are_each_class_smallest_member_on_any_thread_count() {
        let mut x = 0x2545_f491_4f6c_dd1du64;
        let n = 50_000u32;
        let edges: Vec<(u32, u32)> = (0..40_000)
            .map(|_| {
                let a = (xorshift(&mut x) % n as u64) as u32;
                // Mostly near neighbours (long chains), some far jumps.
                let b = if a.is_multiple_of(7) {
                    (xorshift(&mut x) % n as u64) as u32
                } else {
                    (a + 1 + (xorshift(&mut x) % 3) as u32).min(n - 1)
                };
                (a, b)
            })
            .collect();
        // Serial labels: the smallest member of each class.
        let mut parent: Vec<u32> = (0..n).collect();
        fn root(p: &mut [u32], mut x: u32) -> u32 {
            while p[x as usize] != x {
                x = p[x as usize];
            }
            x
        }
        for &(a, b) in &edges {
            let (ra, rb) = (root(&mut parent, a), root(&mut parent, b));
            parent[ra.max(rb) as usize] = ra.min(rb);
        }
        let want: Vec<u32> = (0..n).map(|i| root(&mut parent, i)).collect();
        for t in [1, 2, 3, 4] {
            let uf = SharedUnionFind::try_new(n as usize).unwrap();
            pool(t).expect("a pool").install(|| {
                rayon::scope(|s| {
                    for part in edges.chunks(edges.len().div_ceil(t)) {
                        let uf = &uf;
                        s.spawn(move |_| part.iter().for_each(|&(a, b)| uf.union(a, b)));
                    }
                })
            });
            let got: Vec<u32> = (0..n).map(|i| uf.find(i)).collect();
            assert_eq!(got, want, "{t} threads");
            let roots = (0..n).filter(|&i| uf.is_root(i)).count();
            assert_eq!(roots, (0..n).filter(|&i| want[i as usize] == i).count());
        }
    }

    #[test]
    fn parallel_inversion_lists_each_target_sources_in_order_like_the_counting_sort() {
        let mut x = 0x9e37_79b9_7f4a_7c15u64;
        // Three distinct targets per source among 5000: many sources per target.
        let sources = 3 * MIN_PARALLEL;
        let links: Vec<[u32; 3]> = (0..sources)
            .map(|_| {
                let a = (xorshift(&mut x) % 4998) as u32;
                [a, a + 1, a + 2]
            })
            .collect();
        struct Links(Vec<[u32; 3]>);
        impl Incidences for Links {
            fn visit(&self, range: std::ops::Range<usize>, f: &mut impl FnMut(u32, u32)) {
                for i in range {
                    self.0[i].iter().for_each(|&t| f(2 * i as u32 + 1, t));
                }
            }
        }
        let links = Links(links);
        let want = invert_serial(5000, sources, &links).unwrap();
        let before = threads();
        assert_eq!(want.0[5000] as usize, 3 * sources);
        for t in [2, 3] {
            set_threads(t);
            assert!(splits(sources), "the test must take the parallel path");
            assert!(
                try_invert(5000, sources, &links).unwrap() == want,
                "{t} threads"
            );
        }
        set_threads(1);
        assert!(try_invert(5000, sources, &links).unwrap() == want);
        set_threads(before);
    }

    /// The fills and collects, split at a threshold of 2 into pieces whose edges fall inside
    /// rows and runs (3 rows of 7 and a short one; runs of 5 over 23 items), give the serial
    /// arrays on 1 to 3 threads.
    #[test]
    fn fills_and_collects_split_anywhere_give_the_serial_arrays() {
        let (before, split) = (threads(), SPLIT_AT.load(Ordering::Relaxed));
        set_split_threshold(2);
        let items: Vec<u64> = (0..23u64).map(|i| i * i % 17).collect();
        for t in [1, 2, 3] {
            set_threads(t);
            let mut rows = vec![0usize; 3 * 7 + 2];
            fill_rows(&mut rows, 7, |i, row| {
                for (k, x) in row.iter_mut().enumerate() {
                    *x = 100 * i + k;
                }
            });
            let want: Vec<usize> = (0..23).map(|j| 100 * (j / 7) + j % 7).collect();
            assert_eq!(rows, want, "{t} threads");
            assert_eq!(try_copied(&items).unwrap(), items, "{t} threads");
            assert_eq!(try_filled(23, 9u8).unwrap(), vec![9u8; 23], "{t} threads");
            // Each run's state starts afresh: an answer written from the state would show it.
            let hinted = try_map_collect_with(
                items.len(),
                5,
                || 0usize,
                |seen, i| {
                    *seen += 1;
                    items[i] + 1
                },
            )
            .unwrap();
            let want: Vec<u64> = items.iter().map(|x| x + 1).collect();
            assert_eq!(hinted, want, "{t} threads");
            let words = into_plain(try_atomics(23, |i| 3 * i as u32).unwrap());
            assert_eq!(words, (0..23).map(|i| 3 * i).collect::<Vec<u32>>());
        }
        set_threads(before);
        set_split_threshold(split);
    }
}
