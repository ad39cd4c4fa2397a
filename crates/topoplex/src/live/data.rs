//! The live complex's data: the attributes of the complex it was built from, kept beside its
//! slots through every edit ([`crate::complex::attributes`] is the model).
//!
//! - **Vertex attributes**: a row per vertex slot. A new vertex gets unset numbers (0 for
//!   labels, NaN for reals). A contraction {a, b} → a leaves a's row as the
//!   [`VertexPolicy`] says (a's own, or the mean of a's and b's for reals), or as the caller's
//!   [`VertexMerge`] callback makes it, and b's row in b's slot; the split restores a's row
//!   exactly.
//! - **Top attributes** (the listed attributes of the complex's top simplices): a row per top
//!   slot of each dimension. A top rewritten in place by a contraction keeps its slot, hence its
//!   row; a top that a contraction makes one dimension lower (an image through both a and b that
//!   stays a top) gets the row of the top it is the image of; retired tops keep theirs in their
//!   tombstoned slot, so a split restores them exactly. An inserted top gets unset numbers
//!   ([`LiveComplex::set_top_values`] sets them).
//! - **Listed faces** (every other listed simplex with data: a boundary triangle listed beside
//!   its tetrahedra, a listed vertex, a repeat): a record of its vertices as listed and its row.
//!   A contraction renames b to a in the records through b (found by a per-vertex index: O(the
//!   records at b)); a record that would then repeat a vertex (the face collapsed with the edge)
//!   is retired, and the split restores every record it changed. A record whose simplex is no
//!   longer in the complex (its cofaces removed) is not written by
//!   [`LiveComplex::to_complex`] and is dropped by [`LiveComplex::compact`].
//!
//! `compact()` remaps every row with the slots. Storage: the rows' bytes, plus for the records
//! their ids, 1 byte each for liveness and the per-vertex index (24 bytes per vertex in a record
//! plus 4 per entry); nothing at all without data. Costs per edit: O(attributes) per inserted or
//! moved top, O(records at b) per contraction.

use rustc_hash::FxHashMap;

use super::{DEAD, LiveComplex, MAX_DIMENSION, NONE};
use crate::complex::{Attribute, Attributes, Complex, LabelName, Location, Values};

/// What a contraction {a, b} → a does to a's vertex attributes.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub enum VertexPolicy {
    /// a keeps its own values (b's stay in b's slot for a split).
    #[default]
    Survivor,
    /// Reals become the mean of a's and b's; labels stay a's.
    Average,
}

/// A caller's rule for a's vertex data at a contraction {a, b} → a
/// ([`LiveComplex::set_vertex_merge`]): called once per vertex attribute with its name, a and
/// b, a's row (to change in place) and b's row, as `f64`s (labels exact up to 2^53; what it
/// leaves in a's row is rounded to the attribute's type, integers truncated). Called before the
/// contraction changes the complex; it must not panic (a panic unwinds out of the edit, with
/// a's row half merged).
pub type VertexMerge = dyn Fn(&str, u32, u32, &mut [f64], &[f64]) + Send + Sync;

/// The caller's merge, shared by clones of the live complex.
#[derive(Clone)]
struct Merge(std::sync::Arc<VertexMerge>);

impl std::fmt::Debug for Merge {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("VertexMerge(callback)")
    }
}

/// One listed attribute on the top slots: a row per slot, per dimension.
#[derive(Debug, Clone)]
struct TopAttribute {
    name: String,
    components: usize,
    /// `rows[p]`: a row per top p-slot (`rows[0]` unused, empty).
    rows: Vec<Values>,
}

/// The listed simplices with data that are not top simplices.
#[derive(Debug, Clone, Default)]
struct Records {
    /// Each record's vertices, as listed (b renamed to a by contractions).
    ids: Vec<Vec<u32>>,
    /// Retired by a contraction that collapsed it.
    retired: Vec<bool>,
    /// Each listed attribute's row per record (the same names as the top attributes).
    table: Vec<Attribute>,
    /// Vertex → the records holding it.
    at: FxHashMap<u32, Vec<u32>>,
}

/// The live complex's data (see the module doc).
#[derive(Debug, Clone, Default)]
pub struct LiveData {
    vertex: Vec<Attribute>,
    top: Vec<TopAttribute>,
    records: Records,
    names: Vec<LabelName>,
    policy: VertexPolicy,
    /// The caller's merge, which takes the place of `policy` when set.
    merge: Option<Merge>,
}

/// What a contraction changed in the data, for the split.
#[derive(Debug, Clone, Default, PartialEq)]
pub(super) struct DataUndo {
    /// a's row of each vertex attribute before the contraction.
    a_rows: Vec<Values>,
    /// Records changed: (record, its ids before, whether it joined a's index).
    records: Vec<(u32, Vec<u32>, bool)>,
}

impl LiveData {
    /// Whether there is no data at all (every edit then skips it).
    pub(super) fn is_empty(&self) -> bool {
        self.vertex.is_empty() && self.top.is_empty() && self.records.ids.is_empty()
    }

    /// The data of `complex` for the live complex built from it: vertex attributes as they are,
    /// listed ones split between the top slots (in the order the build gives them:
    /// [`Complex::tops_listed`]) and records for every other listing.
    pub(super) fn of(complex: &Complex, live: &LiveComplex) -> LiveData {
        let at = complex.attributes();
        let mut data = LiveData {
            vertex: at
                .iter()
                .filter(|a| a.location == Location::Vertices)
                .cloned()
                .collect(),
            names: at.label_names().to_vec(),
            ..LiveData::default()
        };
        let listed: Vec<&Attribute> = at
            .iter()
            .filter(|a| a.location == Location::Listed)
            .collect();
        if listed.is_empty() {
            return data;
        }
        // The listing of each top slot, per dimension, in the order the build pushed them.
        let mut slot_listing: Vec<Vec<usize>> = vec![Vec::new(); MAX_DIMENSION + 1];
        let mut is_top = vec![false; complex.input_count()];
        if complex.tops_listed_needs_maps() {
            for (i, p, _, _) in complex.tops_as_given().filter(|t| t.1 > 0) {
                slot_listing[p].push(i);
                is_top[i] = true;
            }
        } else {
            for (i, top) in is_top.iter_mut().enumerate() {
                let p = complex.input_simplex(i).len() - 1;
                if p > 0 {
                    slot_listing[p].push(i);
                    *top = true;
                }
            }
        }
        debug_assert!(
            (1..=MAX_DIMENSION).all(|p| slot_listing[p].len() * (p + 1) == live.tops[p].len())
        );
        let others: Vec<usize> = (0..complex.input_count()).filter(|&i| !is_top[i]).collect();
        for a in &listed {
            data.top.push(TopAttribute {
                name: a.name.clone(),
                components: a.components,
                rows: slot_listing
                    .iter()
                    .map(|l| a.values.pick(l.iter().copied(), a.components))
                    .collect(),
            });
            data.records.table.push(Attribute {
                name: a.name.clone(),
                location: Location::Listed,
                components: a.components,
                values: a.values.pick(others.iter().copied(), a.components),
            });
        }
        for (r, &i) in others.iter().enumerate() {
            let ids = complex.input_simplex(i).to_vec();
            for &v in &ids {
                data.records.at.entry(v).or_default().push(r as u32);
            }
            data.records.ids.push(ids);
            data.records.retired.push(false);
        }
        data
    }

    /// A row of unset numbers for a new vertex.
    pub(super) fn push_vertex(&mut self) {
        for a in &mut self.vertex {
            a.values.push_row(a.components, None);
        }
    }

    /// A row for a new top p-slot: a copy of `from`'s (a (dimension, slot) of the same
    /// attribute), or unset numbers.
    pub(super) fn push_top(&mut self, p: usize, from: Option<(usize, usize)>) {
        for t in &mut self.top {
            let c = t.components;
            match from {
                Some((q, slot)) if q != p => {
                    let row = t.rows[q].row(slot, c);
                    t.rows[p].push_row(c, None);
                    let at = t.rows[p].len() / c - 1;
                    t.rows[p].set_row(at, c, &row);
                }
                Some((_, slot)) => t.rows[p].push_row(c, Some(slot)),
                None => t.rows[p].push_row(c, None),
            }
        }
    }

    /// Before a contraction {a, b} → a: a's rows kept for the split, then a's rows merged by
    /// the policy, and every record through b renamed (or retired when it holds a too).
    pub(super) fn contract(&mut self, a: u32, b: u32) -> DataUndo {
        let (ai, bi) = (a as usize, b as usize);
        let mut undo = DataUndo {
            a_rows: self
                .vertex
                .iter()
                .map(|x| x.values.row(ai, x.components))
                .collect(),
            records: Vec::new(),
        };
        if let Some(Merge(f)) = &self.merge {
            for x in &mut self.vertex {
                let c = x.components;
                let real = |i: usize| x.values.real(i).unwrap_or(f64::NAN);
                let mut row_a: Vec<f64> = (ai * c..(ai + 1) * c).map(real).collect();
                let row_b: Vec<f64> = (bi * c..(bi + 1) * c).map(real).collect();
                f(&x.name, a, b, &mut row_a, &row_b);
                x.values.set_row_f64(ai, &row_a);
            }
        } else if self.policy == VertexPolicy::Average {
            for x in &mut self.vertex {
                x.values.merge_rows(ai, bi, x.components);
            }
        }
        let through_b = self.records.at.get(&b).cloned().unwrap_or_default();
        for r in through_b {
            let ids = &mut self.records.ids[r as usize];
            if self.records.retired[r as usize] {
                continue;
            }
            let before = ids.clone();
            let joins = !ids.contains(&a);
            if joins {
                for v in ids.iter_mut().filter(|v| **v == b) {
                    *v = a;
                }
                self.records.at.entry(a).or_default().push(r);
            } else {
                self.records.retired[r as usize] = true;
            }
            undo.records.push((r, before, joins));
        }
        undo
    }

    /// Undoes [`LiveData::contract`].
    pub(super) fn split(&mut self, a: u32, undo: &DataUndo) {
        for (x, row) in self.vertex.iter_mut().zip(&undo.a_rows) {
            x.values.set_row(a as usize, x.components, row);
        }
        for (r, before, joined) in undo.records.iter().rev() {
            self.records.ids[*r as usize].clone_from(before);
            self.records.retired[*r as usize] = false;
            if *joined
                && let Some(list) = self.records.at.get_mut(&a)
                && let Some(k) = list.iter().rposition(|x| x == r)
            {
                list.remove(k);
            }
        }
    }

    /// After `compact()`: vertex rows of the live vertices (`vmap[v] != NONE`), top rows of the
    /// live slots (`tops[p][slot] != NONE`), records remapped, those retired or through a removed
    /// vertex dropped (`exists[r]`: whether record r's simplex is still in the complex).
    pub(super) fn compact(&mut self, vmap: &[u32], tops: &[Vec<u32>], exists: &[bool]) {
        let alive = (0..vmap.len()).filter(|&v| vmap[v] != NONE);
        for x in &mut self.vertex {
            x.values = x.values.pick(alive.clone(), x.components);
        }
        for t in &mut self.top {
            for (p, rows) in t.rows.iter_mut().enumerate().skip(1) {
                let live = (0..tops[p].len()).filter(|&s| tops[p][s] != NONE);
                *rows = rows.pick(live, t.components);
            }
        }
        let keep: Vec<usize> = (0..self.records.ids.len())
            .filter(|&r| {
                !self.records.retired[r]
                    && self.records.ids[r]
                        .iter()
                        .all(|&v| vmap[v as usize] != NONE)
                    && exists[r]
            })
            .collect();
        for x in &mut self.records.table {
            x.values = x.values.pick(keep.iter().copied(), x.components);
        }
        let ids: Vec<Vec<u32>> = keep
            .iter()
            .map(|&r| {
                self.records.ids[r]
                    .iter()
                    .map(|&v| vmap[v as usize])
                    .collect()
            })
            .collect();
        self.records.at.clear();
        for (r, s) in ids.iter().enumerate() {
            for &v in s {
                self.records.at.entry(v).or_default().push(r as u32);
            }
        }
        self.records.retired = vec![false; ids.len()];
        self.records.ids = ids;
    }

    /// The live records through any vertex of `s`, as (record, vertices), each once.
    pub(super) fn records_at<'a>(
        &'a self,
        s: &[u32],
    ) -> impl Iterator<Item = (u32, &'a [u32])> + 'a {
        let mut rs: Vec<u32> = s
            .iter()
            .filter_map(|v| self.records.at.get(v))
            .flatten()
            .copied()
            .filter(|&r| !self.records.retired[r as usize])
            .collect();
        rs.sort_unstable();
        rs.dedup();
        rs.into_iter()
            .map(|r| (r, self.records.ids[r as usize].as_slice()))
    }

    /// Retires records (their simplex is gone).
    pub(super) fn retire(&mut self, rs: &[u32]) {
        for &r in rs {
            self.records.retired[r as usize] = true;
        }
    }

    /// Each record's vertices (retired ones included).
    pub(super) fn record_ids(&self) -> &[Vec<u32>] {
        &self.records.ids
    }

    /// The live records whose simplex exists, as (record, vertices).
    pub(super) fn live_records<'a>(
        &'a self,
        exists: impl Fn(&[u32]) -> bool + 'a,
    ) -> impl Iterator<Item = (usize, &'a [u32])> + 'a {
        (0..self.records.ids.len())
            .filter(move |&r| !self.records.retired[r] && exists(&self.records.ids[r]))
            .map(|r| (r, self.records.ids[r].as_slice()))
    }

    /// The attributes of [`LiveComplex::to_complex`]'s listing: vertex rows of `alive`
    /// vertices, then per listed attribute the rows of the live top slots (dimension then slot
    /// order) followed by the rows of `records`.
    pub(super) fn attributes(
        &self,
        alive: &[bool],
        live_slots: &[Vec<usize>],
        records: &[usize],
    ) -> Attributes {
        let mut list: Vec<Attribute> = self
            .vertex
            .iter()
            .map(|x| Attribute {
                values: x
                    .values
                    .pick((0..alive.len()).filter(|&v| alive[v]), x.components),
                ..x.clone()
            })
            .collect();
        for (t, table) in self.top.iter().zip(&self.records.table) {
            let mut values = table.values.empty_like();
            for (p, slots) in live_slots.iter().enumerate().skip(1) {
                values.append(&t.rows[p].pick(slots.iter().copied(), t.components));
            }
            values.append(&table.values.pick(records.iter().copied(), t.components));
            list.push(Attribute {
                name: t.name.clone(),
                location: Location::Listed,
                components: t.components,
                values,
            });
        }
        Attributes::from_parts(list, self.names.clone())
    }

    /// The row of listed attribute `name` for top p-slot `slot`.
    pub(super) fn top_row(&self, name: &str, p: usize, slot: usize) -> Option<Values> {
        let t = self.top.iter().find(|t| t.name == name)?;
        Some(t.rows[p].row(slot, t.components))
    }

    /// Sets the row of listed attribute `name` for top p-slot `slot` from `f64`s; false when
    /// there is no such attribute or the row has the wrong length.
    pub(super) fn set_top_row(&mut self, name: &str, p: usize, slot: usize, row: &[f64]) -> bool {
        match self.top.iter_mut().find(|t| t.name == name) {
            Some(t) if t.components == row.len() => {
                t.rows[p].set_row_f64(slot, row);
                true
            }
            _ => false,
        }
    }

    /// The row of vertex attribute `name` for vertex slot `v`.
    pub(super) fn vertex_row(&self, name: &str, v: usize) -> Option<Values> {
        let x = self.vertex.iter().find(|x| x.name == name)?;
        Some(x.values.row(v, x.components))
    }

    /// Sets the row of vertex attribute `name` for vertex slot `v` from `f64`s; false when there
    /// is no such attribute or the row has the wrong length.
    pub(super) fn set_vertex_row(&mut self, name: &str, v: usize, row: &[f64]) -> bool {
        match self.vertex.iter_mut().find(|x| x.name == name) {
            Some(x) if x.components == row.len() => {
                x.values.set_row_f64(v, row);
                true
            }
            _ => false,
        }
    }

    /// The policy for vertex attributes at a contraction (the caller's merge unset).
    pub(super) fn set_policy(&mut self, policy: VertexPolicy) {
        self.policy = policy;
        self.merge = None;
    }

    /// Checks the rows against the slots: one row per vertex slot and per top slot, one id list
    /// per record, every record's live vertices indexed.
    pub(super) fn check(&self, vertex_slots: usize, tops: &[Vec<u32>]) -> Result<(), String> {
        for x in &self.vertex {
            if x.values.len() != vertex_slots * x.components {
                return Err(format!(
                    "vertex attribute '{}': rows ≠ vertex slots",
                    x.name
                ));
            }
        }
        for t in &self.top {
            for (p, table) in tops.iter().enumerate().skip(1) {
                if t.rows[p].len() / t.components != table.len() / (p + 1) {
                    return Err(format!("top attribute '{}': rows ≠ {p}-slots", t.name));
                }
            }
        }
        for (r, ids) in self.records.ids.iter().enumerate() {
            if self.records.retired[r] {
                continue;
            }
            for &v in ids {
                if !self
                    .records
                    .at
                    .get(&v)
                    .is_some_and(|l| l.contains(&(r as u32)))
                {
                    return Err(format!("record {r} is not indexed at vertex {v}"));
                }
            }
        }
        Ok(())
    }
}

impl LiveComplex {
    /// The data this complex carries (see the `data` module).
    pub fn data_is_empty(&self) -> bool {
        self.data.is_empty()
    }

    /// What contractions do to vertex attributes (default: the survivor keeps its own); unsets
    /// a merge set by [`LiveComplex::set_vertex_merge`].
    pub fn set_vertex_policy(&mut self, policy: VertexPolicy) {
        self.data.set_policy(policy);
    }

    /// What contractions {a, b} → a do to a's vertex attributes, by the caller's rule (see
    /// [`VertexMerge`]): `merge(name, a, b, row_a, row_b)` per vertex attribute, before the
    /// contraction; the split restores a's row as it was. Replaces the [`VertexPolicy`] until
    /// [`LiveComplex::set_vertex_policy`] is called. Costs one call and 2 × components numbers
    /// copied per vertex attribute per contraction.
    pub fn set_vertex_merge(
        &mut self,
        merge: impl Fn(&str, u32, u32, &mut [f64], &[f64]) + Send + Sync + 'static,
    ) {
        self.data.merge = Some(Merge(std::sync::Arc::new(merge)));
    }

    /// Sets the row of vertex attribute `name` for live vertex `v` (numbers as `f64`, rounded
    /// to the attribute's type, integers truncated); false when there is no such attribute or
    /// `row` has the wrong number of components. O(attributes + components).
    pub fn set_vertex_values(
        &mut self,
        name: &str,
        v: super::VertexId,
        row: &[f64],
    ) -> Result<bool, super::Refusal> {
        self.check_vertex(v.0)?;
        Ok(self.data.set_vertex_row(name, v.index(), row))
    }

    /// The row of listed attribute `name` for live top `t` (its label: the first number).
    pub fn top_values(
        &self,
        name: &str,
        t: super::TopId,
    ) -> Result<Option<Values>, super::Refusal> {
        self.check_top(t)?;
        Ok(self.data.top_row(name, t.dim(), t.slot() as usize))
    }

    /// Sets the row of listed attribute `name` for live top `t` (numbers as `f64`, rounded to
    /// the attribute's type); false when there is no such attribute or `row` has the wrong
    /// number of components.
    pub fn set_top_values(
        &mut self,
        name: &str,
        t: super::TopId,
        row: &[f64],
    ) -> Result<bool, super::Refusal> {
        self.check_top(t)?;
        Ok(self.data.set_top_row(name, t.dim(), t.slot() as usize, row))
    }

    /// The row of vertex attribute `name` for live vertex `v`.
    pub fn vertex_values(
        &self,
        name: &str,
        v: super::VertexId,
    ) -> Result<Option<Values>, super::Refusal> {
        self.check_vertex(v.0)?;
        Ok(self.data.vertex_row(name, v.index()))
    }

    /// The index of listed attribute `name` when it holds integer labels (for
    /// [`LiveComplex::slot_label`] and [`LiveComplex::record_labels_at`]).
    pub fn label_attribute(&self, name: &str) -> Option<usize> {
        self.data
            .top
            .iter()
            .position(|t| t.name == name && t.rows[1].value_type().is_integer())
    }

    /// The label (first number) of label attribute `attr` on top p-slot `slot`, live or
    /// tombstoned. O(1).
    pub fn slot_label(&self, attr: usize, p: usize, slot: u32) -> i64 {
        let t = &self.data.top[attr];
        t.rows[p].integer(slot as usize * t.components).unwrap_or(0)
    }

    /// The live listed faces through vertex `v` with their label of label attribute `attr`, as
    /// (vertices, label). O(records at v).
    pub fn record_labels_at(
        &self,
        attr: usize,
        v: u32,
    ) -> impl Iterator<Item = (&[u32], i64)> + '_ {
        let r = &self.data.records;
        let c = r.table[attr].components;
        r.at.get(&v)
            .into_iter()
            .flatten()
            .filter(move |&&k| !r.retired[k as usize])
            .map(move |&k| {
                let label = r.table[attr].values.integer(k as usize * c).unwrap_or(0);
                (r.ids[k as usize].as_slice(), label)
            })
    }

    /// Takes its data from `complex`, the complex it was saved beside (the same slots, in
    /// [`LiveComplex::to_complex`]'s order: a compacted live complex saved with its own
    /// `to_complex()`).
    pub(crate) fn attach_data(&mut self, complex: &Complex) {
        self.data = LiveData::of(complex, self);
    }

    /// Whether the simplex `s` (vertex ids in any order, live vertices) is in the complex.
    pub(super) fn holds_simplex(&self, s: &[u32]) -> bool {
        s.iter()
            .all(|&v| (v as usize) < self.alive.len() && v < DEAD && self.alive[v as usize])
            && (s.len() == 1 || self.holds(s))
    }
}
