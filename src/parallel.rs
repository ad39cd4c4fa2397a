//! Threads for the build steps, and the parallel primitives they use.
//!
//! Every parallel step is deterministic: it either sorts (the sorted output does not depend on
//! how the work was split) or writes each result to a position fixed before the split, so a
//! structure built with any number of threads is the same, byte for byte, as the serial one.
//!
//! The thread count is [`set_threads`] (the CLI's `--threads`, the C ABI's `tpx_set_threads`),
//! else the `TOPOPLEX_THREADS` environment variable, else every core.

use std::sync::atomic::{AtomicUsize, Ordering};
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
    threads() > 1 && n >= SPLIT_AT.load(Ordering::Relaxed) && pool(threads()).is_some()
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

/// `f(i, row)` for every row `i` of `width` items of `out` (each row written by one call),
/// split like [`ranges`].
pub(crate) fn fill_rows<T: Send>(
    out: &mut [T],
    width: usize,
    f: impl Fn(usize, &mut [T]) + Sync + Send,
) {
    use rayon::prelude::*;
    let rows = out.len() / width.max(1);
    if width == 0 || !splits(rows) {
        out.chunks_mut(width.max(1))
            .enumerate()
            .for_each(|(i, row)| f(i, row));
        return;
    }
    let step = rows.div_ceil(4 * threads());
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

/// Sets the number of threads later builds use (at least 1).
pub fn set_threads(n: usize) {
    THREADS.store(n.max(1), Ordering::Relaxed);
}

/// The number of threads builds use: [`set_threads`], else `TOPOPLEX_THREADS`, else the
/// number of cores.
pub fn threads() -> usize {
    // Read once: `available_parallelism` reads cgroup files on every call, and small sorts on
    // query paths ask for the thread count.
    static DEFAULT: std::sync::OnceLock<usize> = std::sync::OnceLock::new();
    match THREADS.load(Ordering::Relaxed) {
        0 => *DEFAULT.get_or_init(|| {
            std::env::var("TOPOPLEX_THREADS")
                .ok()
                .and_then(|v| v.trim().parse::<usize>().ok())
                .filter(|&n| n > 0)
                .unwrap_or_else(|| std::thread::available_parallelism().map_or(1, |n| n.get()))
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
/// [`crate::complex::table::headroom`]).
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
    crate::complex::table::try_reserve_exact(&mut tmp, keys.len())?;
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
    use rayon::prelude::*;
    let mut out = Vec::new();
    crate::complex::table::try_reserve_exact(&mut out, n)?;
    if splits(n) {
        install(|| out.par_extend((0..n).into_par_iter().map(f)));
    } else {
        out.extend((0..n).map(f));
    }
    Ok(out)
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
}
