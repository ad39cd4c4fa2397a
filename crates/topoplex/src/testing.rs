//! Checks shared by the test suite and the fuzz targets; not part of the API (hidden from the
//! docs, no stability promise).

/// Whether a live-complex handle that named `old` (ascending ids) before an edit may name `now`
/// after it without naming another simplex: `edit` is `(a, b, true)` for a contraction of b into
/// a, whose handles follow a face to its image (b replaced by a), and `(a, b, false)` for the
/// split undoing it, which takes them back (`now`'s image is `old`). Any other edit (`None`)
/// leaves a handle naming `old` or refused, so this is then false.
pub fn follows_edit(old: &[u32], now: &[u32], edit: Option<(u32, u32, bool)>) -> bool {
    let Some((a, b, contracted)) = edit else {
        return false;
    };
    let image = |r: &[u32]| -> Vec<u32> {
        let mut v: Vec<u32> = r.iter().map(|&x| if x == b { a } else { x }).collect();
        v.sort_unstable();
        v
    };
    if contracted {
        image(old) == now
    } else {
        image(now) == old
    }
}

/// How many file sections the readers have read on several threads in this process (tests of
/// the parallel readers check that the parallel path ran).
pub fn sections_read_in_parallel() -> usize {
    crate::io::chunked::sections_read()
}
