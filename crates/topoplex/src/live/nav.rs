//! [`Navigate`] for the live complex: the same handle navigation as the nine structures, over
//! handles that survive edits.
//!
//! # Handles
//! - A vertex is its dense handle `(0, slot)`, as in the nine structures: valid while the vertex
//!   is live.
//! - Any other simplex σ is a [`HandleForm::TopFace`] handle: a top simplex T holding σ (its
//!   packed slot: dimension in the top 4 bits, slot below) and a mask of T's vertex positions
//!   (bit i: T's i-th vertex as stored, i.e. in its winding). A slot changes only when a
//!   contraction of b into a moves T in place (b replaced by a at its position; the split undoing
//!   it puts b back), so the handle names σ for as long as T lives, and across a contraction it
//!   follows T to σ's image (b replaced by a) — as a half-edge mesh's handles follow a collapse.
//! - When T is removed (`remove_top`, absorbed by an inserted simplex, or retired by a
//!   contraction) the handle keeps naming σ while σ exists: a removed slot keeps its vertices
//!   until [`LiveComplex::compact`] (a tombstone bit on the first), the mask picks σ out of them
//!   and σ is located again in the star of its vertex with the smallest star — the slow path,
//!   O(d·k_v) on every use of such a handle instead of O(1) (re-locate once to get a fast
//!   handle back). A top retired by a contraction of b into a keeps a in b's place, so a handle
//!   through it names σ's image like one through a moved top. The handle is refused with
//!   [`QueryError::StaleHandle`] only when its simplex is gone: a vertex of it removed (or
//!   contracted away while T was already removed), σ no longer a face of any top, or σ holding
//!   both ends of a contracted edge (its image is a lower simplex). An edit that brings σ back
//!   (the split undoing the contraction, inserting σ again) makes the handle name σ again; a
//!   handle never names a simplex other than σ or its image.
//! - Handles the live complex gives out are *canonical*: T is the live top holding σ with the
//!   smallest packed slot. So two handles taken without an edit in between name the same simplex
//!   exactly when they are equal; after edits, compare by [`Navigate::vertices_of`] (a later
//!   answer may name σ through another top). A top simplex's handle is its own full mask.
//! - Every handle carries the complex's generation (its compaction count,
//!   [`SimplexHandle::generation`]); after [`LiveComplex::compact`] an older handle is refused
//!   with [`QueryError::StaleGeneration`]. [`TopId`]s of the handle API are packed slots (not
//!   dense: they number live tops by dimension and slot, an isolated vertex v as `(0, v)`), valid
//!   until `compact`.
//!
//! # Cost (k_v = |St*(v)|, v the vertex of σ with the smallest star; d ≤ 15 is a constant)
//! - `locate`, `check`, `vertices_of`, `top`, `top_id`, `top_as_given`: O(1), except `locate`
//!   O(d·k_v) (a scan of St*(v) for the smallest slot holding σ). A handle through a removed
//!   top adds O(d·k_v) to every call taking it (it is located again, see above).
//! - `visit` R_{p,q}: the faces as in the relation API (module doc of [`crate::live`]), sorted and
//!   deduplicated in a per-thread scratch buffer, then each answer named canonically: for q > p
//!   for free (every top holding an answer holds σ, so the scan of St*(v) sees them all), for
//!   q ≤ p one scan of the answer's smallest star, O(d·k), except an adjacent simplex that is
//!   itself a top (R_{d,d} on a pure complex), named by the top it was found in. Answers come in ascending
//!   lexicographic order of their vertices, which is the natural order here: both [`Order`]s
//!   cost the same. No allocation once the scratch buffer has grown to the answer.
//! - `star`, `link`, `degree`, `is_boundary`, `is_manifold`, `fans_around`, `around_edge`: the
//!   trait's definitions over `visit` (costs in [`crate::relation::handle`]); `top_total` O(n) (isolated
//!   vertices are counted).

use std::cell::RefCell;

use super::{DEAD, Key, LiveComplex, NONE, pack, subset, unpack};
use crate::complex::MAX_DIMENSION;
use crate::relation::handle::{
    HandleForm, Navigate, Order, RelationView, SimplexHandle, TopId, VertexId, Vertices,
};
use crate::relation::{QueryError, Topology, normalize_simplex};
use crate::structures::common::{Scratch, faces_containing};

/// One answer row: the simplex (ascending) and the top naming it (packed slot; `NONE` while
/// not yet named), with the mask of that top's vertices.
#[derive(Clone, Copy)]
struct Row {
    key: Key,
    raw: u32,
    mask: u16,
}

thread_local! {
    static ROWS: RefCell<Vec<Row>> = const { RefCell::new(Vec::new()) };
}

/// Runs `f` with this thread's row buffer, cleared (a nested call — a visitor navigating
/// again — gets a fresh one).
fn with_rows<R>(f: impl FnOnce(&mut Vec<Row>) -> R) -> R {
    let mut f = Some(f);
    let kept = ROWS.try_with(|cell| {
        let mut rows = cell.try_borrow_mut().ok()?;
        rows.clear();
        Some((f.take().expect("called once"))(&mut rows))
    });
    match kept {
        Ok(Some(r)) => r,
        _ => (f.take().expect("not called yet"))(&mut Vec::new()),
    }
}

fn invalid(h: SimplexHandle, reason: &'static str) -> QueryError {
    QueryError::InvalidHandle { handle: h, reason }
}

/// Mask of the positions of `face`'s vertices within `top` (a superset, in its stored order).
fn mask_of(top: &[u32], face: &[u32]) -> u16 {
    top.iter()
        .enumerate()
        .filter(|(_, v)| face.contains(v))
        .fold(0u16, |m, (i, _)| m | 1 << i)
}

impl LiveComplex {
    fn vertex_handle(&self, v: u32) -> SimplexHandle {
        SimplexHandle::dense(0, v).with_generation(self.epoch)
    }

    fn face_handle(&self, raw: u32, mask: u16) -> SimplexHandle {
        SimplexHandle::top_face(TopId(raw), mask).with_generation(self.epoch)
    }

    /// The canonical handle of σ (ascending, live vertices, |σ| ≥ 2): the live top holding it
    /// with the smallest packed slot, if any. O(d·k_v).
    fn canonical(&self, sigma: &[u32]) -> Option<SimplexHandle> {
        let v = self.smallest_star(sigma);
        let raw = self.star[v as usize]
            .iter()
            .copied()
            .filter(|&raw| subset(sigma, self.top_raw(raw)))
            .min()?;
        Some(self.face_handle(raw, mask_of(self.top_raw(raw), sigma)))
    }

    /// The handle of live top simplex `t` (its full mask).
    pub fn top_handle(&self, t: super::TopId) -> Result<SimplexHandle, super::Refusal> {
        self.check_top(t)?;
        Ok(self.face_handle(t.raw, ((1u32 << (t.dim() + 1)) - 1) as u16))
    }

    /// Top simplex `t` (a top id of the handle API, as [`Navigate::top`] takes) with its
    /// vertices in their stored order — the input winding, b replaced by a in place after a
    /// contraction — lent from the top table: no copy, no allocation; the borrow ends at the
    /// next edit. [`Navigate::top_as_given`] gives the same ids by value. `InvalidHandle` for a
    /// removed slot, and for an isolated vertex (a top 0-simplex: its id is the top id's slot,
    /// and no row of a table holds it). O(1).
    pub fn top_as_given_slice(&self, t: TopId) -> Result<&[u32], QueryError> {
        let h = self.top(t)?;
        if h.form() == HandleForm::Dense {
            return Err(invalid(
                h,
                "an isolated vertex (top 0-simplex) has no stored row: it is its own id",
            ));
        }
        Ok(self.top_raw(t.0))
    }

    /// The handle's simplex, ascending, after checking it.
    fn handle_vertices(&self, h: SimplexHandle) -> Result<Vertices, QueryError> {
        let h = self.live_form(h)?;
        if h.form() == HandleForm::Dense {
            return Ok(Vertices::from_slice(&[h.index()]));
        }
        let mut ids = [0u32; MAX_DIMENSION + 1];
        let mut k = 0;
        for (i, &v) in self.top_raw(h.index()).iter().enumerate() {
            if h.local() >> i & 1 == 1 {
                ids[k] = v;
                k += 1;
            }
        }
        ids[..k].sort_unstable();
        Ok(Vertices::from_slice(&ids[..k]))
    }

    /// `h` checked, named through a live top: `h` itself when its top lives (O(1)); when its top
    /// was removed (by `remove_top`, absorbed by an insertion, or retired by a contraction),
    /// the canonical handle of the simplex the removed slot's kept vertices name under the mask,
    /// if that simplex still exists — O(d) to read it and O(d·k_v) to locate it. Else
    /// `StaleHandle`: a vertex of it was removed, or the simplex itself is gone.
    fn live_form(&self, h: SimplexHandle) -> Result<SimplexHandle, QueryError> {
        self.check_form(h)?;
        if h.form() == HandleForm::Dense && h.dim() > 0 {
            // An index of the numbering of the moment (`dense` module): named canonically.
            let row = self.table(h.dim()).get(h.index() as usize);
            return Ok(self
                .canonical(row)
                .expect("a row of the table is a simplex"));
        }
        if h.form() == HandleForm::Dense || self.top_raw(h.index())[0] < DEAD {
            return Ok(h);
        }
        let stale = || QueryError::StaleHandle { handle: h };
        let mut ids = [0u32; MAX_DIMENSION + 1];
        let mut k = 0;
        for (i, &v) in self.top_raw(h.index()).iter().enumerate() {
            if h.local() >> i & 1 == 1 {
                ids[k] = v & !DEAD;
                k += 1;
            }
        }
        let sigma = &mut ids[..k];
        sigma.sort_unstable();
        // A repeated id: a face through both ends of a contracted edge, collapsed.
        if sigma.windows(2).any(|w| w[0] == w[1]) || sigma.iter().any(|&v| !self.alive[v as usize])
        {
            return Err(stale());
        }
        self.canonical(sigma).ok_or_else(stale)
    }

    /// After a contraction of b into a retired the top `raw` of St(b): its kept vertices get a
    /// in b's place, so that a handle through it names its face's image, as one through a top
    /// moved in place does (a face through both a and b collapses: refused). O(d).
    pub(super) fn bury_image(&mut self, raw: u32, a: u32, b: u32) {
        let (p, slot) = unpack(raw);
        for x in &mut self.tops[p][slot * (p + 1)..(slot + 1) * (p + 1)] {
            if *x & !DEAD == b {
                *x = a | (*x & DEAD);
            }
        }
    }

    /// Every check of `h` that needs no lookup: generation, form, ranges, mask.
    fn check_form(&self, h: SimplexHandle) -> Result<(), QueryError> {
        if h.generation() != self.epoch {
            return Err(QueryError::StaleGeneration {
                handle: h,
                generation: h.generation(),
                current: self.epoch,
            });
        }
        if h.is_none() {
            return Err(invalid(h, "the NONE handle"));
        }
        if h.form() == HandleForm::Dense {
            if h.dim() != 0 {
                if h.dim() > Topology::dimension(self)
                    || h.index() as usize >= self.index_count(h.dim())
                {
                    return Err(invalid(h, "index beyond the simplices of its dimension"));
                }
                return Ok(());
            }
            if h.index() >= self.vertex_slots() {
                return Err(invalid(h, "vertex beyond the vertex slots"));
            }
            if !self.alive[h.index() as usize] {
                return Err(QueryError::StaleHandle { handle: h });
            }
            return Ok(());
        }
        let (p, slot) = unpack(h.index());
        if p == 0 || (slot + 1) * (p + 1) > self.tops[p].len() {
            return Err(invalid(h, "no top simplex slot of this number"));
        }
        let mask = h.local() as u32;
        if h.dim() == 0 || mask >> (p + 1) != 0 || mask.count_ones() as usize != h.dim() + 1 {
            return Err(invalid(h, "vertex mask does not fit its top simplex"));
        }
        Ok(())
    }

    /// R_{p,0}(σ): σ's vertices, or for a vertex the other vertices of its star, sorted and
    /// deduplicated as plain ids (no row keys: the VV walk's cost is the sort of O(d·k_v) ids).
    fn visit_vertices(&self, sigma: &[u32], visit: &mut dyn FnMut(SimplexHandle)) {
        let mut ids = Scratch::<Vec<u32>>::take();
        if sigma.len() == 1 {
            for &raw in &self.star[sigma[0] as usize] {
                ids.extend(self.top_raw(raw).iter().filter(|&&u| u != sigma[0]));
            }
            ids.sort_unstable();
            ids.dedup();
        } else {
            ids.extend_from_slice(sigma);
        }
        for &u in ids.iter() {
            visit(self.vertex_handle(u));
        }
    }

    /// Every answer row of R_{p,q}(σ), q ≥ 1 (vertices: `visit_vertices`), into `rows`, named or
    /// not (`raw == NONE`), duplicates allowed.
    fn answer_rows(&self, sigma: &[u32], q: usize, rows: &mut Vec<Row>) {
        let p = sigma.len() - 1;
        let unnamed = |f: &[u32]| Row {
            key: Key::new(f),
            raw: NONE,
            mask: 0,
        };
        if q < p {
            faces_containing(sigma, &[], q, |f| rows.push(unnamed(f)));
        } else if q > p {
            // Every top holding an answer holds σ, hence is in St*(v): name answers here.
            let v = self.smallest_star(sigma);
            for &raw in &self.star[v as usize] {
                let t = self.top_raw(raw);
                if t.len() > q && subset(sigma, t) {
                    let top = Key::new(t);
                    faces_containing(top.as_slice(), sigma, q, |f| {
                        rows.push(Row {
                            key: Key::sorted(f), // faces come ascending
                            raw,
                            mask: mask_of(t, f),
                        })
                    });
                }
            }
        } else {
            self.adjacent_rows(sigma, rows, unnamed);
        }
    }

    /// R_{p,p}, p > 0: every p-simplex sharing a facet with σ holds σ[0] or σ[1], so it lies in
    /// a top of St*(σ[0]), or of St*(σ[1]) without σ[0]. Each top t is tested once: it holds a
    /// facet of σ when it misses at most one vertex of σ (O(d²) per top).
    fn adjacent_rows(&self, sigma: &[u32], rows: &mut Vec<Row>, unnamed: impl Fn(&[u32]) -> Row) {
        let p = sigma.len() - 1;
        for (h, &hub) in sigma[..2].iter().enumerate() {
            for &raw in &self.star[hub as usize] {
                let t = self.top_raw(raw);
                if h == 1 && t.contains(&sigma[0]) {
                    continue; // seen in St*(σ[0])
                }
                let mut missing = None;
                let mut misses = 0;
                for (i, v) in sigma.iter().enumerate() {
                    if !t.contains(v) {
                        misses += 1;
                        missing = Some(i);
                    }
                }
                match (misses, missing) {
                    (0, _) => (0..=p)
                        .for_each(|skip| self.rows_across(sigma, skip, t, raw, rows, &unnamed)),
                    (1, Some(skip)) => self.rows_across(sigma, skip, t, raw, rows, &unnamed),
                    _ => {}
                }
            }
        }
    }

    /// The p-simplices of top t (packed id `raw`) across σ's facet without σ[skip]: that facet
    /// plus one vertex of t outside σ. One that is t itself (a top) is named by t: no other top
    /// holds it.
    fn rows_across(
        &self,
        sigma: &[u32],
        skip: usize,
        t: &[u32],
        raw: u32,
        rows: &mut Vec<Row>,
        unnamed: &impl Fn(&[u32]) -> Row,
    ) {
        let p = sigma.len() - 1;
        let mut face = [0u32; MAX_DIMENSION + 1];
        let mut k = 0;
        for (i, &v) in sigma.iter().enumerate() {
            if i != skip {
                face[k] = v;
                k += 1;
            }
        }
        for &x in t.iter().filter(|x| !sigma.contains(x)) {
            face[p] = x;
            rows.push(if t.len() == p + 1 {
                Row {
                    key: Key::new(t),
                    raw,
                    mask: ((1u32 << (p + 1)) - 1) as u16,
                }
            } else {
                unnamed(&face[..=p])
            });
        }
    }
}

impl Navigate for LiveComplex {
    fn locate(&self, sigma: &[u32]) -> Result<SimplexHandle, QueryError> {
        let n = self.vertex_slots();
        let k = sigma.len();
        if k == 0 || k > MAX_DIMENSION + 1 || sigma.iter().any(|&v| v >= n) {
            return Err(normalize_simplex(sigma, n).expect_err("an invalid simplex"));
        }
        let s = Key::new(sigma);
        let s = s.as_slice();
        if s.windows(2).any(|w| w[0] == w[1]) {
            return Err(normalize_simplex(sigma, n).expect_err("a repeated vertex"));
        }
        let not_in = || QueryError::NotInComplex {
            simplex: s.to_vec(),
        };
        if s.iter().any(|&v| !self.alive[v as usize]) {
            return Err(not_in());
        }
        if k == 1 {
            return Ok(self.vertex_handle(s[0]));
        }
        self.canonical(s).ok_or_else(not_in)
    }

    /// A vertex: its slot. Above vertices: the p-simplex of rank `index` in the numbering of
    /// the moment (`dense` module; its table built on first use), named canonically by a top
    /// simplex, so that the handle lasts across edits even though the index does not.
    fn handle(&self, p: usize, index: u32) -> Result<SimplexHandle, QueryError> {
        let h = SimplexHandle::dense(p.min(MAX_DIMENSION), index).with_generation(self.epoch);
        if p > MAX_DIMENSION {
            return Err(invalid(h, "dimension above the complex's"));
        }
        self.live_form(h)
    }

    /// A vertex: its slot; above: the rank of its vertices in the numbering of the moment
    /// (`dense` module), O(p log n_p) once the table is built.
    fn index_of(&self, h: SimplexHandle) -> Result<u32, QueryError> {
        let h = self.live_form(h)?;
        if h.form() == HandleForm::Dense {
            return Ok(h.index());
        }
        Ok(self.rank_of(&self.handle_vertices(h)?))
    }

    /// The walk of `visit`, each answer's index found by [`Navigate::index_of`] (its vertices
    /// read from its handle, then a binary search): both orders cost the same, answers come
    /// lexicographic, which is also ascending index order.
    fn related_ids(
        &self,
        h: SimplexHandle,
        q: usize,
        _order: Order,
        ids: &mut Vec<u32>,
    ) -> Result<(), QueryError> {
        if q == 0 {
            return self.visit(h, 0, &mut |x| ids.push(x.index()));
        }
        if q <= Topology::dimension(self) {
            self.table(q); // built before the walk, not inside its visitor
        }
        let mut failed = None;
        self.visit(h, q, &mut |x| match self.dense_of(x) {
            Ok(i) => ids.push(i),
            Err(e) => failed = Some(e),
        })?;
        failed.map_or(Ok(()), Err)
    }

    /// Built on first use, valid until the next edit (`dense` module).
    fn relation_view(&self, p: usize, q: usize) -> Result<Option<RelationView<'_>>, QueryError> {
        let d = Topology::dimension(self);
        if p > d || q > d {
            return Err(QueryError::DimensionOutOfRange { p, q, dim: d });
        }
        self.dense_view(p, q).map(Some)
    }

    /// O(1) through a live top; through a removed one, O(d·k_v) (it is located again: module doc).
    fn check(&self, h: SimplexHandle) -> Result<(), QueryError> {
        self.live_form(h).map(|_| ())
    }

    fn vertex(&self, v: VertexId) -> Result<SimplexHandle, QueryError> {
        Navigate::handle(self, 0, v.0)
    }

    fn vertices_of(&self, h: SimplexHandle) -> Result<Vertices, QueryError> {
        self.handle_vertices(h)
    }

    fn top_total(&self) -> u32 {
        (0..=MAX_DIMENSION).map(|p| self.top_count(p) as u32).sum()
    }

    fn top(&self, t: TopId) -> Result<SimplexHandle, QueryError> {
        let bad = |why| invalid(SimplexHandle::top_face(t, 0), why);
        if t.is_none() {
            return Err(bad("the NONE top id"));
        }
        let (p, slot) = unpack(t.0);
        if p == 0 {
            let v = slot as u32;
            if !self.is_live(VertexId(v)) || !self.star[slot].is_empty() {
                return Err(bad("not an isolated vertex"));
            }
            return Ok(self.vertex_handle(v));
        }
        if (slot + 1) * (p + 1) > self.tops[p].len() || self.tops[p][slot * (p + 1)] >= DEAD {
            return Err(bad("no live top simplex in this slot"));
        }
        Ok(self.face_handle(t.0, ((1u32 << (p + 1)) - 1) as u16))
    }

    fn top_id(&self, h: SimplexHandle) -> Result<Option<TopId>, QueryError> {
        let h = self.live_form(h)?;
        if h.form() == HandleForm::Dense {
            let isolated = self.star[h.index() as usize].is_empty();
            return Ok(isolated.then(|| TopId(pack(0, h.index()))));
        }
        let p = unpack(h.index()).0;
        Ok((h.dim() == p).then_some(TopId(h.index())))
    }

    fn top_as_given(&self, t: TopId) -> Result<Vertices, QueryError> {
        let h = self.top(t)?;
        if h.form() == HandleForm::Dense {
            return Ok(Vertices::from_slice(&[h.index()]));
        }
        Ok(Vertices::from_slice(self.top_raw(t.0)))
    }

    /// The dense numbering's tables and views built since the last edit (`dense` module).
    fn handle_bytes(&self) -> u64 {
        self.dense.bytes()
    }

    fn generation(&self) -> u32 {
        self.epoch
    }

    fn dense(&self) -> bool {
        false
    }

    /// Its walks answer in lexicographic order, and τ ↦ τ ∖ σ keeps that order within a
    /// dimension, so its stars and links come in order too: both orders cost the same.
    fn visits_lexicographic(&self) -> bool {
        true
    }

    fn visit(
        &self,
        h: SimplexHandle,
        q: usize,
        visit: &mut dyn FnMut(SimplexHandle),
    ) -> Result<(), QueryError> {
        let sigma = self.handle_vertices(h)?;
        let d = Topology::dimension(self);
        if q > d {
            return Err(QueryError::DimensionOutOfRange {
                p: h.dim(),
                q,
                dim: d,
            });
        }
        if q == 0 {
            self.visit_vertices(&sigma, visit);
            return Ok(());
        }
        with_rows(|rows| {
            self.answer_rows(&sigma, q, rows);
            // Lexicographic, and for q > p the smallest naming slot first. Every key has q + 1
            // ids: compare those, not the whole inline arrays.
            rows.sort_unstable_by(|a, b| {
                let w = q + 1;
                a.key.ids[..w].cmp(&b.key.ids[..w]).then(a.raw.cmp(&b.raw))
            });
            let mut last: Option<Key> = None;
            for r in rows.iter() {
                if last == Some(r.key) {
                    continue;
                }
                last = Some(r.key);
                let s = r.key.as_slice();
                visit(if r.raw != NONE {
                    self.face_handle(r.raw, r.mask)
                } else {
                    self.canonical(s).expect("an answer is a simplex")
                });
            }
        });
        Ok(())
    }
}
