//! The link condition Lk(a) ∩ Lk(b) = Lk(ab) for an edge {a, b} (Dey, Edelsbrunner, Guha,
//! Nekhayev 1999), checked in every dimension at once.
//!
//! Lk(ab) ⊆ Lk(a) ∩ Lk(b) always holds, so only the other inclusion is checked. With
//! F_a = {t \ {a} : t ∈ St*(a), b ∉ t}, F_b likewise, and F_ab = {t \ {a, b} : t ∈ St*(a), b ∈ t},
//! Lk(a) ∩ Lk(b) is the closure of {x ∩ y : x ∈ F_a, y ∈ F_b} (faces of a top through both a and
//! b are in Lk(ab) anyway), and Lk(ab) the closure of F_ab. So the condition holds iff every
//! non-empty x ∩ y is inside some z ∈ F_ab. The vertices that can occur in x ∩ y are the common
//! ones C = V(F_a) ∩ V(F_b); with |C| ≤ 64 each set becomes one word and each test two word
//! operations: O(d·(k_a + k_b) log + |F_a|·|F_b|·|F_ab|) with duplicate and non-maximal words
//! dropped first. Past 64 common vertices, sorted id lists do the same work.
//!
//! On failure the reported simplex is a lowest-dimensional one of Lk(a) ∩ Lk(b) outside Lk(ab).

use std::cell::RefCell;

use super::{LiveComplex, Refusal, VertexId, subset};

impl LiveComplex {
    /// Whether {a, b} is an edge satisfying the link condition. `Err(NotAnEdge)` for a non-edge,
    /// `Err(LinkCondition { dim, simplex })` naming a lowest-dimensional simplex of
    /// Lk(a) ∩ Lk(b) not in Lk(ab). Read-only; allocates nothing after a thread's first calls
    /// (per-thread scratch). Cost: module doc of [`crate::live::link`].
    pub fn link_condition(&self, a: VertexId, b: VertexId) -> Result<(), Refusal> {
        self.check_vertex(a.0)?;
        self.check_vertex(b.0)?;
        let (a, b) = (a.0, b.0);
        if a == b
            || !self.star[a as usize]
                .iter()
                .any(|&r| self.top_raw(r).contains(&b))
        {
            return Err(Refusal::NotAnEdge { a, b });
        }
        let found = SCRATCH.with(|s| match s.try_borrow_mut() {
            Ok(mut s) => self.first_violation(a, b, &mut s),
            Err(_) => self.first_violation(a, b, &mut Scratch::default()),
        });
        match found {
            None => Ok(()),
            Some(simplex) => Err(Refusal::LinkCondition {
                a,
                b,
                dim: simplex.len() - 1,
                simplex,
            }),
        }
    }

    /// The common vertices C, then the word or list test (module doc).
    fn first_violation(&self, a: u32, b: u32, s: &mut Scratch) -> Option<Vec<u32>> {
        let fa = || self.star[a as usize].iter().map(|&r| self.top_raw(r));
        let fb = || self.star[b as usize].iter().map(|&r| self.top_raw(r));
        common_vertices(fa(), fb(), a, b, s);
        if s.common.is_empty() {
            return None;
        }
        if s.common.len() > 64 {
            let fa: Vec<&[u32]> = fa().filter(|t| !t.contains(&b)).collect();
            let fab: Vec<&[u32]> = self.star[a as usize]
                .iter()
                .map(|&r| self.top_raw(r))
                .filter(|t| t.contains(&b))
                .collect();
            let fb: Vec<&[u32]> = fb().filter(|t| !t.contains(&a)).collect();
            return lists::first_violation(&s.common, &fa, &fb, &fab);
        }
        let Scratch {
            common, ma, mb, mz, ..
        } = s;
        ma.clear();
        mb.clear();
        mz.clear();
        for t in fa() {
            let m = words::mask(common, t);
            if t.contains(&b) {
                mz.push(m);
            } else {
                ma.push(m);
            }
        }
        for t in fb().filter(|t| !t.contains(&a)) {
            mb.push(words::mask(common, t));
        }
        maximal(ma);
        maximal(mb);
        words::first_violation(common, ma, mb, mz)
    }
}

/// Per-thread buffers of the link test, so that a check allocates nothing once warm.
#[derive(Default)]
struct Scratch {
    va: Vec<u32>,
    vb: Vec<u32>,
    common: Vec<u32>,
    ma: Vec<u64>,
    mb: Vec<u64>,
    mz: Vec<u64>,
}

thread_local! {
    static SCRATCH: RefCell<Scratch> = RefCell::new(Scratch::default());
}

/// Vertices other than a and b in a top of St(a) and in a top of St(b), ascending, into
/// `s.common` (a superset of V(F_a) ∩ V(F_b), which changes no x ∩ y).
fn common_vertices<'a>(
    fa: impl Iterator<Item = &'a [u32]>,
    fb: impl Iterator<Item = &'a [u32]>,
    a: u32,
    b: u32,
    s: &mut Scratch,
) {
    let collect = |f: &mut dyn Iterator<Item = &'a [u32]>, v: &mut Vec<u32>| {
        v.clear();
        for t in f {
            v.extend(t.iter().copied().filter(|&x| x != a && x != b));
        }
        v.sort_unstable();
        v.dedup();
    };
    collect(&mut { fa }, &mut s.va);
    collect(&mut { fb }, &mut s.vb);
    s.common.clear();
    let (mut i, mut j) = (0, 0);
    while i < s.va.len() && j < s.vb.len() {
        match s.va[i].cmp(&s.vb[j]) {
            std::cmp::Ordering::Less => i += 1,
            std::cmp::Ordering::Greater => j += 1,
            std::cmp::Ordering::Equal => {
                s.common.push(s.va[i]);
                i += 1;
                j += 1;
            }
        }
    }
}

/// Keeps the maximal sets of a family of words (drops zero, duplicates and subsets), in place.
fn maximal(masks: &mut Vec<u64>) {
    masks.retain(|&m| m != 0);
    masks.sort_unstable_by(|x, y| y.count_ones().cmp(&x.count_ones()).then(x.cmp(y)));
    masks.dedup();
    let mut kept = 0;
    for i in 0..masks.len() {
        let m = masks[i];
        if !masks[..kept].iter().any(|&k| m & !k == 0) {
            masks[kept] = m;
            kept += 1;
        }
    }
    masks.truncate(kept);
}

/// The common vertices as bits of one word.
mod words {
    /// The bits of `t ∩ common`.
    pub(super) fn mask(common: &[u32], t: &[u32]) -> u64 {
        t.iter()
            .filter_map(|v| common.binary_search(v).ok())
            .fold(0u64, |m, i| m | 1 << i)
    }

    /// A lowest-dimensional x ∩ y (x ∈ ma, y ∈ mb) face not under any z ∈ mz, as vertex ids.
    pub(super) fn first_violation(
        common: &[u32],
        ma: &[u64],
        mb: &[u64],
        mz: &[u64],
    ) -> Option<Vec<u32>> {
        let covered = |w: u64| mz.iter().any(|&z| w & !z == 0);
        let mut best: Option<u64> = None;
        for &x in ma {
            for &y in mb {
                let w = x & y;
                if w == 0 || covered(w) {
                    continue;
                }
                let m = smallest_uncovered(w, &covered);
                if best.is_none_or(|b| m.count_ones() < b.count_ones()) {
                    best = Some(m);
                }
            }
        }
        best.map(|m| {
            (0..64)
                .filter(|i| m >> i & 1 == 1)
                .map(|i| common[i])
                .collect()
        })
    }

    /// A submask of `w` with the fewest bits that no z covers (w itself is uncovered).
    fn smallest_uncovered(w: u64, covered: &impl Fn(u64) -> bool) -> u64 {
        let mut best = w;
        let mut s = w;
        while s != 0 {
            if s.count_ones() < best.count_ones() && !covered(s) {
                best = s;
            }
            s = (s - 1) & w;
        }
        best
    }
}

/// Sorted id lists, for more than 64 common vertices.
mod lists {
    use super::subset;

    pub(super) fn first_violation(
        common: &[u32],
        fa: &[&[u32]],
        fb: &[&[u32]],
        fab: &[&[u32]],
    ) -> Option<Vec<u32>> {
        let restrict = |t: &[u32]| -> Vec<u32> {
            let mut v: Vec<u32> = t
                .iter()
                .copied()
                .filter(|v| common.binary_search(v).is_ok())
                .collect();
            v.sort_unstable();
            v
        };
        let xa: Vec<Vec<u32>> = fa.iter().map(|t| restrict(t)).collect();
        let xb: Vec<Vec<u32>> = fb.iter().map(|t| restrict(t)).collect();
        let covered = |w: &[u32]| fab.iter().any(|z| subset(w, z));
        let mut best: Option<Vec<u32>> = None;
        for x in &xa {
            for y in &xb {
                let w: Vec<u32> = x.iter().copied().filter(|v| y.contains(v)).collect();
                if w.is_empty() || covered(&w) {
                    continue;
                }
                // Subsets of w by increasing size (|w| ≤ 15).
                let mut m = (0..1u32 << w.len()).collect::<Vec<_>>();
                m.sort_by_key(|s| s.count_ones());
                let first = m
                    .into_iter()
                    .skip(1)
                    .map(|s| {
                        (0..w.len())
                            .filter(|i| s >> i & 1 == 1)
                            .map(|i| w[i])
                            .collect::<Vec<u32>>()
                    })
                    .find(|s| !covered(s))
                    .unwrap_or(w);
                if best.as_ref().is_none_or(|b| first.len() < b.len()) {
                    best = Some(first);
                }
            }
        }
        best
    }
}
