//! The tops across each facet: an opt-in index of the live complex, so that face-to-face
//! navigation (FF on a surface, TT on a tetrahedral mesh, the same in any dimension) is a read
//! rather than two star scans.
//!
//! # What it encodes
//! For a live top t of dimension p ≥ 1 in slot s and each i ≤ p, entry `rows[p][s·(p+1) + i]`
//! names what lies across the facet of t opposite its i-th stored vertex (t without `tops[p][s·(p+1)
//! + i]`), among the live tops of the same dimension p: [`ACROSS_NONE`] when no other does (a
//! boundary facet, or one that only tops of other dimensions share), the packed top id
//! (`p << 28 | slot`, as the stars hold them) when exactly one does (a manifold facet), and
//! [`ACROSS_MANY`] when two or more do (a non-manifold facet: the caller scans a star for them).
//! A tombstoned slot's entries are [`ACROSS_NONE`].
//!
//! # Storage and cost
//! Nothing until asked ([`LiveComplex::adjacency`]); then 4 bytes per vertex of every top slot
//! (`4 Σ_p (p+1)·slots_p`: 12 bytes a triangle, 16 a tetrahedron), reported by
//! `Navigate::handle_bytes`. Built on several threads when large. Up to tetrahedra, facet by
//! facet: each facet is met once, at its smallest vertex, among the tops of that vertex's star,
//! and the facets a vertex owns are matched by sorting, O(Σ_v k_v·d log(k_v·d)). Above, top by
//! top: for each facet a scan of the smallest star of its vertices for the tops holding the
//! others, O(Σ_t d²·k), reading whether a top holds a vertex from that vertex's star when it is
//! short. Like the dense numbering
//! (module `dense`) it belongs to one state: every topological edit drops it, setting
//! coordinates keeps it, and a query builds it behind a `OnceLock` from `&self` — unless the
//! caller keeps it ([`LiveComplex::keep_adjacency`]): then each edit repairs the entries of the
//! tops in the stars of the vertices it touched (every entry that can change is there), O(Σ_t
//! d²·k) over those tops, and `compact()` builds it again for the new slots.

use std::sync::OnceLock;

use super::{LiveComplex, NONE, SLOT_MASK, pack, unpack};
use crate::complex::MAX_DIMENSION;
use crate::relation::StructureKind;
use crate::structures::BuildError;

/// Across a facet: no other top of the same dimension.
pub const ACROSS_NONE: u32 = NONE;
/// Across a facet: two or more other tops of the same dimension (a non-manifold facet).
pub const ACROSS_MANY: u32 = u32::MAX - 1;

/// The built index of one state (see the module doc).
#[derive(Debug, Default, Clone)]
pub(super) struct Across {
    rows: Vec<Vec<u32>>,
}

impl Across {
    pub(super) fn bytes(&self) -> u64 {
        self.rows.iter().map(|r| 4 * r.capacity() as u64).sum()
    }
}

/// What [`LiveComplex::across_before`] saw: the touched vertices and the tops in their stars.
pub(super) struct Touched {
    vertices: Vec<u32>,
    tops: Vec<u32>,
}

/// The index lent: `rows[p]` holds `p + 1` entries per slot of dimension p's top table (see the
/// module doc for what an entry says), `rows[0]` is empty.
#[derive(Debug, Clone, Copy)]
pub struct Adjacency<'a> {
    /// Per dimension, the entries of every slot.
    pub rows: [&'a [u32]; MAX_DIMENSION + 1],
    /// Heap bytes of the index.
    pub bytes: u64,
}

impl Adjacency<'_> {
    /// What lies across the facet of top `t` (dimension p, slot s) opposite its i-th vertex: an
    /// entry as the module doc says. O(1).
    pub fn across(&self, p: usize, slot: u32, i: usize) -> u32 {
        self.rows[p][slot as usize * (p + 1) + i]
    }
}

impl LiveComplex {
    /// The tops across each facet of every top (module doc), built on the first call after an
    /// edit and kept until the next one. [`BuildError::TooLarge`] when its memory cannot be had
    /// (or a 15-dimensional table so full that a top id would read as [`ACROSS_MANY`]).
    /// Cost: the first call O(Σ_t d²·k) on [`crate::parallel::threads`] threads (module doc),
    /// the others O(1).
    pub fn adjacency(&self) -> Result<Adjacency<'_>, BuildError> {
        let across = match &self.kept_across {
            Some(kept) => kept,
            None => {
                let lock: &OnceLock<Across> = self.dense.across();
                if lock.get().is_none() {
                    let built = self.build_across()?;
                    let _ = lock.set(built);
                }
                lock.get().expect("set above")
            }
        };
        let mut rows: [&[u32]; MAX_DIMENSION + 1] = [&[]; MAX_DIMENSION + 1];
        for (p, r) in across.rows.iter().enumerate() {
            rows[p] = r;
        }
        Ok(Adjacency {
            rows,
            bytes: across.bytes(),
        })
    }

    /// Keeps the facet adjacency across edits (`true`: built now if it is not, then repaired by
    /// every insert, removal, contraction and split around what it changed, and rebuilt by
    /// `compact()`), or goes back to building it on request and dropping it at each edit
    /// (`false`). Kept, [`LiveComplex::adjacency`] is O(1) after any edit; each edit costs
    /// O(Σ_t d²·k) more over the tops t in the stars of the vertices it touches (the vertices of
    /// the tops it adds, removes or rewrites: for a contraction of ab, those of St(a) ∪ St(b)).
    /// [`BuildError::TooLarge`] (nothing kept) when the index's memory cannot be had.
    pub fn keep_adjacency(&mut self, keep: bool) -> Result<(), BuildError> {
        if !keep {
            self.kept_across = None;
        } else if self.kept_across.is_none() {
            self.kept_across = Some(self.build_across()?);
        }
        Ok(())
    }

    /// Whether the facet adjacency is kept across edits ([`LiveComplex::keep_adjacency`]).
    pub fn keeps_adjacency(&self) -> bool {
        self.kept_across.is_some()
    }

    /// Before an edit that adds, removes or rewrites tops whose vertices are among `touched`:
    /// when the adjacency is kept, those vertices and the tops now in their stars (each entry
    /// that can change belongs to a top sharing a facet with a changed top, so to such a star).
    /// `touched` is called only then (a complex that does not keep the index pays nothing).
    pub(super) fn across_before<I: IntoIterator<Item = u32>>(
        &self,
        touched: impl FnOnce() -> I,
    ) -> Option<Touched> {
        self.kept_across.as_ref()?;
        let mut vertices: Vec<u32> = touched().into_iter().collect();
        vertices.sort_unstable();
        vertices.dedup();
        let tops = self.tops_at(&vertices);
        Some(Touched { vertices, tops })
    }

    /// After the edit [`LiveComplex::across_before`] saw: the entries of the tops at the touched
    /// vertices before and after are cleared, and those of the live ones filled again; the rows
    /// grow with the top tables. Nothing when the adjacency is not kept. If a row cannot grow,
    /// the kept adjacency is dropped (`keeps_adjacency()` then says false).
    pub(super) fn across_after(&mut self, touched: Option<Touched>) {
        let (Some(t), Some(mut across)) = (touched, self.kept_across.take()) else {
            return;
        };
        for p in 1..=MAX_DIMENSION {
            let row = &mut across.rows[p];
            let need = self.tops[p].len();
            if row.len() < need {
                if row.try_reserve(need - row.len()).is_err() {
                    return;
                }
                row.resize(need, NONE);
            }
        }
        let after = self.tops_at(&t.vertices);
        for &raw in t.tops.iter().chain(&after) {
            let (p, slot) = unpack(raw);
            across.rows[p][slot * (p + 1)..(slot + 1) * (p + 1)].fill(NONE);
        }
        for &raw in &after {
            let (p, slot) = unpack(raw);
            self.fill_across(
                p,
                slot,
                &mut across.rows[p][slot * (p + 1)..(slot + 1) * (p + 1)],
            );
        }
        self.kept_across = Some(across);
    }

    /// After `compact()` renumbered every slot: a kept adjacency built again for the new slots
    /// (dropped if its memory cannot be had).
    pub(super) fn across_compacted(&mut self) {
        if self.kept_across.is_some() {
            self.kept_across = self.build_across().ok();
        }
    }

    /// The live tops in the stars of `vertices` (live or not), each once, ascending.
    fn tops_at(&self, vertices: &[u32]) -> Vec<u32> {
        let mut tops: Vec<u32> = vertices
            .iter()
            .filter(|&&v| (v as usize) < self.alive.len())
            .flat_map(|&v| self.star[v as usize].iter().copied())
            .collect();
        tops.sort_unstable();
        tops.dedup();
        tops
    }

    /// Every dimension's entries, each top's filled in turn ([`LiveComplex::fill_across`]).
    fn build_across(&self) -> Result<Across, BuildError> {
        use rayon::prelude::*;
        const K: StructureKind = StructureKind::IaStar;
        let mut rows = Vec::with_capacity(MAX_DIMENSION + 1);
        rows.push(Vec::new());
        for p in 1..=MAX_DIMENSION {
            let table = &self.tops[p];
            if p == MAX_DIMENSION && table.len() / (p + 1) >= SLOT_MASK as usize - 1 {
                return Err(BuildError::TooLarge {
                    kind: K,
                    what: "a 15-dimensional top table of 2^28 - 1 slots or more".into(),
                });
            }
            let mut row =
                crate::structures::common::try_vec(K, NONE, table.len(), "facet adjacency")?;
            if p <= 3 {
                row = self.across_by_owners(p, row);
            } else {
                let fill = |(slot, out): (usize, &mut [u32])| self.fill_across(p, slot, out);
                if crate::parallel::splits(table.len() / (p + 1)) {
                    crate::parallel::install(|| {
                        row.par_chunks_mut(p + 1).enumerate().for_each(fill)
                    });
                } else {
                    row.chunks_mut(p + 1).enumerate().for_each(fill);
                }
            }
            rows.push(row);
        }
        Ok(Across { rows })
    }

    /// Dimension p's entries (p ≤ 3; `row` all `NONE`) facet by facet rather than top by top:
    /// each facet is met at its smallest vertex a, whose star holds every top through it; the
    /// facets a owns are sorted by their other vertices and matched in runs (one top: none
    /// across; two: each other; more: many). Each entry is written once, by its facet's owner,
    /// so vertex ranges run on several threads; the row goes through atomics, converted in place.
    /// O(Σ_v k_v·d log(k_v·d)) with no read of a top beyond the stars' own.
    fn across_by_owners(&self, p: usize, row: Vec<u32>) -> Vec<u32> {
        use rayon::prelude::*;
        use std::sync::atomic::{AtomicU32, Ordering::Relaxed};
        let cells: Vec<AtomicU32> = row.into_iter().map(AtomicU32::new).collect();
        let owned_by = |range: std::ops::Range<usize>| {
            // (the facet's other vertices, packed; the top; its entry)
            let mut facets: Vec<(u64, u32, usize)> = Vec::new();
            for a in range {
                if !self.alive[a] {
                    continue;
                }
                facets.clear();
                let a = a as u32;
                for &u in self.star[a as usize].iter() {
                    let (q, slot) = unpack(u);
                    if q != p {
                        continue;
                    }
                    let t = self.top_raw(u);
                    let at = t
                        .iter()
                        .position(|&w| w == a)
                        .expect("a top of a's star holds a");
                    if p == 2 {
                        // A triangle (a, x, y) in winding order from a: a owns edge ax (opposite
                        // y) when x > a, and edge ay (opposite x) when y > a.
                        const NEXT: [usize; 3] = [1, 2, 0];
                        let (i, j) = (NEXT[at], NEXT[NEXT[at]]);
                        if t[i] > a {
                            facets.push((u64::from(t[i]), u, slot * 3 + j));
                        }
                        if t[j] > a {
                            facets.push((u64::from(t[j]), u, slot * 3 + i));
                        }
                        continue;
                    }
                    // The facets through a (opposite each other vertex i) that a owns: its
                    // other vertices all above a.
                    'facet: for i in (0..=p).filter(|&i| i != at) {
                        let mut rest = [u32::MAX; 2];
                        let mut k = 0;
                        for (m, &w) in t.iter().enumerate() {
                            if m == i || m == at {
                                continue;
                            }
                            if w < a {
                                continue 'facet;
                            }
                            rest[k] = w;
                            k += 1;
                        }
                        if rest[0] > rest[1] {
                            rest.swap(0, 1);
                        }
                        let key = (u64::from(rest[0]) << 32) | u64::from(rest[1]);
                        facets.push((key, u, slot * (p + 1) + i));
                    }
                }
                match_facets(&mut facets, |entry, across| {
                    cells[entry].store(across, Relaxed)
                });
            }
        };
        let ranges = crate::parallel::ranges(self.alive.len());
        if ranges.len() > 1 {
            crate::parallel::install(|| ranges.into_par_iter().for_each(owned_by));
        } else {
            ranges.into_iter().for_each(owned_by);
        }
        cells.into_iter().map(AtomicU32::into_inner).collect()
    }

    /// The entries of top slot `slot` of dimension p into `out` (`p + 1`, all `NONE` on entry):
    /// for each facet, the tops of dimension p through its vertex of smallest star that hold
    /// its other vertices. Whether a top u holds a vertex w is read from w's star when that is
    /// short (the star's cache lines are already near; a surface's usual case), else from u's
    /// vertices.
    fn fill_across(&self, p: usize, slot: usize, out: &mut [u32]) {
        const SHORT: usize = 16;
        let t = &self.tops[p][slot * (p + 1)..(slot + 1) * (p + 1)];
        if t[0] >= super::DEAD {
            return;
        }
        let me = pack(p, slot as u32);
        // Each vertex's star read from the block table once.
        let mut stars: [&[u32]; MAX_DIMENSION + 1] = [&[]; MAX_DIMENSION + 1];
        for (j, &w) in t.iter().enumerate() {
            stars[j] = &self.star[w as usize];
        }
        let holds = |u: u32, j: usize| {
            if stars[j].len() <= SHORT {
                stars[j].contains(&u)
            } else {
                self.top_raw(u).contains(&t[j])
            }
        };
        for (i, entry) in out.iter_mut().enumerate() {
            let x = (0..=p)
                .filter(|&j| j != i)
                .min_by_key(|&j| stars[j].len())
                .expect("a facet has a vertex");
            for &u in stars[x] {
                if u != me && unpack(u).0 == p && (0..=p).all(|j| j == i || j == x || holds(u, j)) {
                    *entry = if *entry == NONE { u } else { ACROSS_MANY };
                }
            }
        }
    }
}

/// Matches the facets one vertex owns, `(facet key, top, entry)`, by key: a facet in one top
/// sets nothing, in two sets each entry to the other top, in more sets each to [`ACROSS_MANY`].
/// A vertex owns a handful on a mesh: those are matched by scanning (no sort, no moves); a
/// large star's are sorted first. O(m²) for m ≤ 24, else O(m log m).
fn match_facets(facets: &mut [(u64, u32, usize)], mut set: impl FnMut(usize, u32)) {
    const SCAN: usize = 24;
    if facets.len() > SCAN {
        facets.sort_unstable();
        for run in facets.chunk_by(|x, y| x.0 == y.0) {
            match run {
                [_] => {}
                [x, y] => {
                    set(x.2, y.1);
                    set(y.2, x.1);
                }
                _ => run.iter().for_each(|x| set(x.2, ACROSS_MANY)),
            }
        }
        return;
    }
    let mut matched = 0u32; // bit j: facets[j] belongs to a run already handled
    for i in 0..facets.len() {
        if matched >> i & 1 == 1 {
            continue;
        }
        let key = facets[i].0;
        let mut partner = None;
        let mut many = false;
        for (j, f) in facets.iter().enumerate().skip(i + 1) {
            if f.0 == key {
                matched |= 1 << j;
                many = partner.is_some();
                partner = partner.or(Some(j));
            }
        }
        match partner {
            None => {}
            Some(j) if !many => {
                set(facets[i].2, facets[j].1);
                set(facets[j].2, facets[i].1);
            }
            Some(_) => facets[i..]
                .iter()
                .filter(|f| f.0 == key)
                .for_each(|f| set(f.2, ACROSS_MANY)),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::{ACROSS_MANY, ACROSS_NONE};
    use crate::complex::{Complex, xorshift_below};
    use crate::live::{ContractMode, LiveComplex, VertexId};

    /// The entries a brute force gives: every other live top of the same dimension holding the
    /// facet, counted over all tops.
    /// Returns how many non-manifold facets it met.
    fn check(live: &LiveComplex) -> usize {
        let mut many = 0;
        let adj = live.adjacency().unwrap();
        let tops: Vec<_> = live.tops().map(|(t, s)| (t, s.to_vec())).collect();
        for (t, s) in &tops {
            let p = t.dim();
            for i in 0..=p {
                let facet: Vec<u32> = (0..=p).filter(|&j| j != i).map(|j| s[j]).collect();
                let others: Vec<u32> = tops
                    .iter()
                    .filter(|(u, vu)| {
                        u != t && u.dim() == p && facet.iter().all(|w| vu.contains(w))
                    })
                    .map(|(u, _)| super::pack(p, u.slot()))
                    .collect();
                let want = match others.len() {
                    0 => ACROSS_NONE,
                    1 => others[0],
                    _ => ACROSS_MANY,
                };
                assert_eq!(adj.across(p, t.slot(), i), want, "top {s:?} facet {i}");
                many += usize::from(want == ACROSS_MANY);
            }
        }
        many
    }

    /// A live complex of `from + 1`.. random simplices of 2 to `sizes + 1` distinct vertices
    /// among `least` to `least + 7`: few vertices, so facets are shared by none, one or several
    /// tops.
    fn random_live(
        below: &mut impl FnMut(u64) -> u64,
        least: u32,
        from: u64,
        sizes: u64,
    ) -> LiveComplex {
        let n = least + below(8) as u32;
        let mut rows: Vec<Vec<u32>> = Vec::new();
        for _ in 0..from + below(14) {
            let len = 2 + below(sizes) as usize;
            let mut s: Vec<u32> = Vec::new();
            while s.len() < len.min(n as usize) {
                let v = below(u64::from(n)) as u32;
                if !s.contains(&v) {
                    s.push(v);
                }
            }
            rows.push(s);
        }
        let refs: Vec<&[u32]> = rows.iter().map(Vec::as_slice).collect();
        LiveComplex::from_complex(&Complex::from_simplices(n, &refs).unwrap())
    }

    /// Random non-manifold complexes to dimension 4 over a few vertices (so facets are shared by
    /// none, one or several tops, of the same dimension or not): the index equals the brute
    /// force when built, and after each of a run of random contractions, removals and inserts
    /// (each edit drops it; the next call builds it for the new state).
    #[test]
    fn the_tops_across_each_facet_equal_brute_force_across_edits() {
        let mut below = xorshift_below(0xacc0_55ed);
        let mut many = 0;
        for _ in 0..200 {
            let mut live = random_live(&mut below, 4, 1, 4);
            many += check(&live);
            for _ in 0..6 {
                let vs: Vec<VertexId> = live.vertices().collect();
                let (a, b) = (
                    vs[below(vs.len() as u64) as usize],
                    vs[below(vs.len() as u64) as usize],
                );
                match below(3) {
                    0 if a != b => {
                        let _ = live.contract(a, b, ContractMode::Free, None);
                    }
                    1 => {
                        let top: Option<Vec<u32>> = live.tops().next().map(|(_, s)| s.to_vec());
                        if let Some(s) = top {
                            live.remove_top(&s).unwrap();
                        }
                    }
                    _ => {
                        let c = vs[below(vs.len() as u64) as usize];
                        let _ = live.insert_top(&[a.0, b.0, c.0]);
                    }
                }
                live.check_invariants().unwrap();
                many += check(&live);
            }
        }
        assert!(many > 50, "only {many} non-manifold facets met");
    }

    /// Kept across edits: after each random insertion, removal (by simplex and by id),
    /// contraction (free or link-checked), split of the last contraction and compaction, the
    /// repaired index (never rebuilt: it stays kept) equals the brute force.
    #[test]
    fn the_kept_adjacency_equals_brute_force_after_every_edit() {
        let mut below = xorshift_below(0x4ee9_ada0);
        let (mut many, mut edits) = (0, 0);
        for _ in 0..150 {
            let mut live = random_live(&mut below, 5, 2, 3);
            live.keep_adjacency(true).unwrap();
            let mut undo = Vec::new();
            for _ in 0..10 {
                let vs: Vec<VertexId> = live.vertices().collect();
                let pick = |k: u64| vs[k as usize];
                let (a, b) = (pick(below(vs.len() as u64)), pick(below(vs.len() as u64)));
                let changed = match below(6) {
                    0 | 1 if a != b => {
                        let mode = if below(2) == 0 {
                            ContractMode::Free
                        } else {
                            ContractMode::PreserveTopology
                        };
                        live.contract(a, b, mode, None)
                            .map(|u| undo.push(u))
                            .is_ok()
                    }
                    2 => {
                        let first = live.tops().next().map(|(t, s)| (t, s.to_vec()));
                        match first {
                            Some((t, _)) if below(2) == 0 => live.remove_top_id(t).is_ok(),
                            Some((_, s)) => live.remove_top(&s).is_ok(),
                            None => false,
                        }
                    }
                    3 => undo.pop().is_some_and(|u| live.split(&u).is_ok()),
                    4 if below(4) == 0 => {
                        live.compact();
                        undo.clear();
                        true
                    }
                    _ => {
                        let c = pick(below(vs.len() as u64));
                        live.insert_top(&[a.0, b.0, c.0]).is_ok()
                    }
                };
                edits += usize::from(changed);
                live.check_invariants().unwrap();
                assert!(live.keeps_adjacency());
                many += check(&live);
            }
        }
        assert!(
            edits > 800 && many > 50,
            "{edits} edits, {many} non-manifold facets"
        );
    }

    /// A hub: vertex 0 in a closed fan of 40 triangles, three more triangles on its edge {0, 1}
    /// (a book of five pages) and two tetrahedra through it: more facets than the scan matches,
    /// so they are sorted; the index equals the brute force.
    #[test]
    fn a_hub_of_forty_triangles_and_a_book_equals_brute_force() {
        let mut rows: Vec<Vec<u32>> = (1..=40).map(|i| vec![0, i, i % 40 + 1]).collect();
        rows.extend((41..44).map(|w| vec![0, 1, w]));
        rows.push(vec![0, 5, 20, 44]);
        rows.push(vec![0, 5, 20, 45]);
        let refs: Vec<&[u32]> = rows.iter().map(Vec::as_slice).collect();
        let live = LiveComplex::from_complex(&Complex::from_simplices(46, &refs).unwrap());
        assert!(live.star[0].len() > 40);
        assert!(
            check(&live) >= 5,
            "the book's five pages are across a non-manifold edge"
        );
    }
}
