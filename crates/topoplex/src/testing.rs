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

/// Every answer a structure gives about the simplices of `c`, as text: counts, listings, and
/// every relation of every simplex (rows sorted, as the CLI prints them, since a structure's own
/// order may vary; errors as text). The saved-file mutation test and fuzz target compare an
/// altered file's answers with these.
pub fn answers(s: &dyn crate::relation::Topology, c: &crate::complex::Complex) -> Vec<String> {
    let mut out = Vec::new();
    let mut buf = Vec::new();
    let d = s.dimension();
    out.push(format!("d {d} n {}", s.vertex_count()));
    for p in 0..=d.min(4) {
        out.push(format!("count {p} {} {}", s.count(p), s.top_count(p)));
        buf.clear();
        s.simplices(p, &mut buf);
        out.push(format!("simplices {p} {buf:?}"));
    }
    let closure = c.closure();
    for sigma in closure.iter().flat_map(|t| t.iter()) {
        out.push(format!("contains {sigma:?} {}", s.contains(sigma)));
        for q in 0..=d.min(4) {
            let r = s.relation(sigma, q, &mut buf).map(|()| {
                crate::relation::sort_rows(&mut buf, q + 1);
                buf.clone()
            });
            out.push(format!("R {sigma:?} {q} {r:?}"));
        }
    }
    out
}
