//! The edits of a [`LiveComplex`]: insertion and removal of top simplices, edge contraction and
//! its undo (vertex split), compaction. Each checks everything first and refuses with the
//! structure unchanged, then mutates.

use super::{
    DEAD, Image, Key, LiveComplex, NONE, Refusal, TopId, VertexId, pack, show, subset, unpack,
};
use crate::complex::MAX_DIMENSION;

/// How [`LiveComplex::contract`] decides whether it may unify two vertices.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ContractMode {
    /// Only an edge {a, b} satisfying the link condition Lk(a) ∩ Lk(b) = Lk(ab) in every
    /// dimension (Dey, Edelsbrunner, Guha, Nekhayev 1999): the result is homotopy equivalent to
    /// the input (and homeomorphic on closed manifolds).
    PreserveTopology,
    /// Any two live vertices, edge or not (Popović and Hoppe's vertex unification, 1997).
    Free,
    /// [`ContractMode::PreserveTopology`] plus the boundary: the link condition on the complex
    /// coned over its boundary ([`LiveComplex::link_condition_with_boundary`]), which on 2- and
    /// 3-manifolds with boundary also keeps the result a manifold with the same boundary
    /// topology.
    PreserveManifold,
}

/// What [`LiveComplex::split`] needs to undo a contraction exactly (same ids, same slots, same
/// winding, same coordinates).
#[derive(Debug, Clone, PartialEq)]
pub struct UndoRecord {
    /// The surviving vertex.
    pub a: VertexId,
    /// The vertex removed by the contraction (revived by the split).
    pub b: VertexId,
    epoch: u32,
    /// a's then b's coordinates before the contraction.
    coords: Vec<f64>,
    /// Top simplices the contraction retired (winding as stored).
    removed: TopList,
    /// Top simplices the contraction created (a moved top is in both lists, same slot).
    inserted: TopList,
    /// What the contraction changed in the data (`data` module); none without data.
    data: Option<super::data::DataUndo>,
}

/// Top simplices as packed ids and their vertices, in two flat arrays (a contraction's undo
/// record allocates three arrays, not one per simplex).
#[derive(Debug, Clone, Default, PartialEq)]
struct TopList {
    raw: Vec<u32>,
    ids: Vec<u32>,
}

impl TopList {
    fn push(&mut self, raw: u32, s: &[u32]) {
        self.raw.push(raw);
        self.ids.extend_from_slice(s);
    }

    fn reserve(&mut self, tops: usize, ids: usize) {
        self.raw.reserve(tops);
        self.ids.reserve(ids);
    }

    fn iter(&self) -> impl Iterator<Item = (u32, &[u32])> + '_ {
        let mut at = 0;
        self.raw.iter().map(move |&raw| {
            let w = unpack(raw).0 + 1;
            at += w;
            (raw, &self.ids[at - w..at])
        })
    }
}

impl UndoRecord {
    /// The (dimension, slot) of each top simplex the contraction retired (their data stays in
    /// the tombstoned slots: [`LiveComplex::slot_label`]).
    pub fn removed_slots(&self) -> impl Iterator<Item = (usize, u32)> + '_ {
        self.removed.raw.iter().map(|&raw| {
            let (p, slot) = unpack(raw);
            (p, slot as u32)
        })
    }

    /// The (dimension, slot) of each top simplex the contraction created or moved.
    pub fn inserted_slots(&self) -> impl Iterator<Item = (usize, u32)> + '_ {
        self.inserted.raw.iter().map(|&raw| {
            let (p, slot) = unpack(raw);
            (p, slot as u32)
        })
    }

    /// Top simplices the contraction removed (those of St(b), and those of St(a) that became
    /// faces of an image), with their vertices before the contraction. A top of St(b) whose
    /// image stays a top is listed here with b and in [`UndoRecord::inserted_tops`] with a:
    /// it was rewritten in its own slot.
    pub fn removed_tops(&self) -> impl Iterator<Item = &[u32]> + '_ {
        self.removed.iter().map(|(_, s)| s)
    }

    /// Top simplices the contraction created (images of St(b) with b replaced by a). A moved
    /// top keeps its slot, so its [`TopId`] from before the contraction stays valid and names
    /// the image; only a degenerate image (of a top through both a and b) that stays a top gets
    /// a new slot.
    pub fn inserted_tops(&self) -> impl Iterator<Item = TopId> + '_ {
        self.inserted.raw.iter().map(|&raw| TopId {
            raw,
            epoch: self.epoch,
        })
    }
}

/// Old → new ids after [`LiveComplex::compact`]; `u32::MAX` marks a removed vertex or slot.
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct CompactMaps {
    /// `vertices[old]` = new vertex id.
    pub vertices: Vec<u32>,
    /// `tops[p][old slot]` = new slot of the top p-simplex (`tops[0]` is empty).
    pub tops: Vec<Vec<u32>>,
}

impl LiveComplex {
    /// Checks a simplex given by the caller: 1..=16 distinct live vertices; returns it sorted.
    fn check_simplex(&self, sigma: &[u32]) -> Result<Key, Refusal> {
        let bad = |why| Refusal::InvalidSimplex {
            simplex: sigma.to_vec(),
            why,
        };
        if sigma.is_empty() {
            return Err(bad("no vertex"));
        }
        if sigma.len() > MAX_DIMENSION + 1 {
            return Err(bad("more than 16 vertices"));
        }
        for &v in sigma {
            self.check_vertex(v)?;
        }
        let k = Key::new(sigma);
        if k.as_slice().windows(2).any(|w| w[0] == w[1]) {
            return Err(bad("repeated vertex"));
        }
        Ok(k)
    }

    /// Inserts σ (vertices in the winding to keep) as a top simplex, with its faces. Top
    /// simplices that σ contains stop being top (they become its faces). Refused: invalid
    /// simplex, a vertex not live, σ already in the complex (as a top simplex or a face), or a
    /// single vertex (vertices are added by [`LiveComplex::add_vertex`]). Cost: module doc.
    pub fn insert_top(&mut self, sigma: &[u32]) -> Result<TopId, Refusal> {
        self.renumbered();
        self.check_simplex(sigma)?;
        if self.holds(sigma) {
            return Err(Refusal::AlreadyPresent {
                simplex: sigma.to_vec(),
            });
        }
        let kept = self.across_before(|| sigma.iter().copied());
        let mut absorbed: Vec<u32> = Vec::new();
        for &v in sigma {
            for &raw in &self.star[v as usize] {
                if !absorbed.contains(&raw) && subset(self.top_raw(raw), sigma) {
                    absorbed.push(raw);
                }
            }
        }
        for raw in absorbed {
            let (p, slot) = unpack(raw);
            self.detach(p, slot as u32);
        }
        let slot = self.push_top(sigma);
        self.across_after(kept);
        Ok(self.handle(pack(sigma.len() - 1, slot)))
    }

    /// Removes the top simplex σ (vertices in any order). Its faces that no other top simplex
    /// holds go with it; its vertices stay (as isolated vertices if nothing else holds them).
    /// For a single isolated vertex, removes the vertex. Refused: invalid simplex, a vertex not
    /// live, σ not in the complex, σ a proper face of another simplex. Cost: module doc.
    pub fn remove_top(&mut self, sigma: &[u32]) -> Result<(), Refusal> {
        self.renumbered();
        let k = self.check_simplex(sigma)?;
        if let Some(raw) = self.find_top(k.as_slice()) {
            let kept = self.across_before(|| k.as_slice().to_vec());
            let (p, slot) = unpack(raw);
            let s = self.detach(p, slot as u32);
            self.across_after(kept);
            self.retire_vanished_records(&s);
            return Ok(());
        }
        if let Some(raw) = self.top_containing(sigma) {
            return Err(Refusal::NotTop {
                simplex: sigma.to_vec(),
                coface: self.top_raw(raw).to_vec(),
            });
        }
        if sigma.len() == 1 {
            // A live vertex with an empty star: an isolated vertex.
            self.alive[sigma[0] as usize] = false;
            self.live_vertices -= 1;
            if self.live_vertices == 0 {
                // A complex keeps at least one vertex.
                self.alive[sigma[0] as usize] = true;
                self.live_vertices = 1;
                return Err(Refusal::InvalidSimplex {
                    simplex: sigma.to_vec(),
                    why: "the last vertex of the complex cannot be removed",
                });
            }
            self.retire_vanished_records(sigma);
            return Ok(());
        }
        Err(Refusal::NotInComplex {
            simplex: sigma.to_vec(),
        })
    }

    /// Removes the top simplex `t` (see [`LiveComplex::remove_top`]). Refused: a handle from
    /// before `compact()` or of a removed top simplex.
    pub fn remove_top_id(&mut self, t: TopId) -> Result<(), Refusal> {
        self.renumbered();
        self.check_top(t)?;
        let kept = self.across_before(|| self.top_raw(t.raw).to_vec());
        let (p, slot) = unpack(t.raw);
        let s = self.detach(p, slot as u32);
        self.across_after(kept);
        self.retire_vanished_records(&s);
        Ok(())
    }

    /// The vertices of the tops through any of `vs`, with `vs` (what an edit at them touches).
    fn star_vertices(&self, vs: &[u32]) -> Vec<u32> {
        let mut out = vs.to_vec();
        for &v in vs {
            for &raw in &self.star[v as usize] {
                out.extend_from_slice(self.top_raw(raw));
            }
        }
        out
    }

    /// After a removal of `s`: the listed faces' records through its vertices whose simplex went
    /// with it are retired (their data goes with the simplex). O(records at s's vertices).
    fn retire_vanished_records(&mut self, s: &[u32]) {
        if self.data.is_empty() {
            return;
        }
        let gone: Vec<u32> = self
            .data
            .records_at(s)
            .filter(|&(_, ids)| !self.holds_simplex(ids))
            .map(|(r, _)| r)
            .collect();
        self.data.retire(&gone);
    }

    /// Whether contracting {a, b} is allowed in `mode`, without changing anything: both live and
    /// distinct, and in [`ContractMode::PreserveTopology`] an edge satisfying the link condition.
    pub fn can_contract(
        &self,
        a: VertexId,
        b: VertexId,
        mode: ContractMode,
    ) -> Result<(), Refusal> {
        self.check_vertex(a.0)?;
        self.check_vertex(b.0)?;
        if a == b {
            return Err(Refusal::InvalidSimplex {
                simplex: vec![a.0, b.0],
                why: "repeated vertex",
            });
        }
        match mode {
            ContractMode::PreserveTopology => self.link_condition(a, b)?,
            ContractMode::PreserveManifold => self.link_condition_with_boundary(a, b)?,
            ContractMode::Free => {}
        }
        Ok(())
    }

    /// Contracts b into a: every top simplex through b gets a in b's place (one through both
    /// loses b), images that became a face of another simplex or a duplicate are dropped, top
    /// simplices of St(a) that became a face of an image are retired, b is removed, and a moves
    /// to `new_position` when given. Returns the record [`LiveComplex::split`] needs to undo it.
    /// Refused (unchanged): a or b not live, a == b, coordinates of the wrong length, and in
    /// [`ContractMode::PreserveTopology`] a non-edge or a failing link condition (with the
    /// dimension). Cost: module doc.
    pub fn contract(
        &mut self,
        a: VertexId,
        b: VertexId,
        mode: ContractMode,
        new_position: Option<&[f64]>,
    ) -> Result<UndoRecord, Refusal> {
        self.renumbered();
        self.can_contract(a, b, mode)?;
        if let Some(xyz) = new_position {
            self.check_coords_of(a.0, xyz)?;
        }
        let kept = self.across_before(|| self.star_vertices(&[a.0, b.0]));
        let k = self.coord_dim;
        let mut undo = UndoRecord {
            a,
            b,
            epoch: self.epoch,
            coords: [a, b]
                .iter()
                .flat_map(|v| &self.coords[v.index() * k..(v.index() + 1) * k])
                .copied()
                .collect(),
            removed: TopList::default(),
            inserted: TopList::default(),
            data: (!self.data.is_empty()).then(|| self.data.contract(a.0, b.0)),
        };
        let linked = mode != ContractMode::Free;
        self.image_star_of_b(a.0, b.0, linked);
        self.move_star_of_b(a.0, b.0, linked, &mut undo);
        self.alive[b.index()] = false;
        self.live_vertices -= 1;
        if let Some(xyz) = new_position {
            self.coords[a.index() * k..(a.index() + 1) * k].copy_from_slice(xyz);
        }
        self.across_after(kept);
        Ok(undo)
    }

    /// Step 1 of a contraction, before anything changes: the image of every top of St(b) (b
    /// replaced by a in place, or dropped where a is already there) into `self.images`, each
    /// marked kept when it is still a top simplex afterwards.
    ///
    /// Two images never coincide: t1 − b + a = t2 − b would make t2 = t1 − a a face of t1, and
    /// t1 − b = t2 − b gives t1 = t2. An image is not kept when it lies in a larger image or in
    /// a top of St(a) outside St(b) (every image holds a, so such a top is in the star of each
    /// of its vertices: the smallest is scanned). When the link condition holds (`linked`), only
    /// the degenerate images need the test: an image t − b + a of a top t ∌ a inside a top
    /// T ∈ St(a) would put τ = t − b in Lk(a) ∩ Lk(b), hence in Lk(ab), making t ∪ {a} a
    /// simplex and t no top; and an image t − b + a inside another image t' − b (+ a) would
    /// likewise make t ∪ {a} a simplex.
    fn image_star_of_b(&mut self, a: u32, b: u32, linked: bool) {
        let mut images = std::mem::take(&mut self.images);
        images.clear();
        for &raw in &self.star[b as usize] {
            let t = self.top_raw(raw);
            let has_a = t.contains(&a);
            let mut img = Image {
                degenerate: has_a,
                from: raw,
                ..Image::default()
            };
            for &v in t {
                if v != b {
                    img.push(v);
                } else if !has_a {
                    img.push(a);
                }
            }
            img.kept = img.len > 1;
            images.push(img);
        }
        for i in 0..images.len() {
            let img = images[i];
            if !img.kept || (linked && !img.degenerate) {
                continue;
            }
            let under_image = images
                .iter()
                .any(|j| j.len > img.len && j.len > 1 && subset(img.as_slice(), j.as_slice()));
            let hub = self.smallest_star(img.as_slice());
            let under_top = self.star[hub as usize].iter().any(|&raw| {
                let t = self.top_raw(raw);
                !t.contains(&b) && subset(img.as_slice(), t)
            });
            images[i].kept = !under_image && !under_top;
        }
        self.images = images;
    }

    /// Step 2 of a contraction: every top of St(b) whose image is kept and not degenerate is
    /// rewritten in its own slot (b replaced by a, so its id, its winding and its entries in the
    /// other vertices' stars stay; it joins St(a)); the others are retired. In
    /// [`ContractMode::Free`] the tops of St(a) that an image absorbs are retired too; then the
    /// kept degenerate images get new slots.
    fn move_star_of_b(&mut self, a: u32, b: u32, linked: bool, undo: &mut UndoRecord) {
        let images = std::mem::take(&mut self.images);
        let k = images.len();
        undo.removed
            .reserve(k, k * images.first().map_or(0, |i| i.len as usize + 1));
        undo.inserted
            .reserve(k, k * images.first().map_or(0, |i| i.len as usize));
        // The retired ones first, so that St*(a) moves at most once, to its final size.
        let moved = |img: &Image| img.kept && !img.degenerate;
        for img in &images {
            let (p, slot) = unpack(img.from);
            undo.removed.push(img.from, self.top_raw(img.from));
            if !moved(img) {
                self.detach_except(p, slot as u32, b);
                self.bury_image(img.from, a, b);
            }
        }
        self.star
            .reserve(a, images.iter().filter(|img| moved(img)).count());
        for img in images.iter().filter(|img| moved(img)) {
            let (p, slot) = unpack(img.from);
            let w = p + 1;
            let t = &mut self.tops[p][slot * w..(slot + 1) * w];
            let at = t
                .iter()
                .position(|&v| v == b)
                .expect("b in its star's tops");
            t[at] = a;
            self.star.push(a, img.from);
            undo.inserted.push(img.from, img.as_slice());
        }
        self.star.release(b);
        let mut i = 0;
        while !linked && i < self.star[a as usize].len() {
            let raw = self.star[a as usize][i];
            let t = self.top_raw(raw);
            if images
                .iter()
                .any(|img| img.kept && img.len as usize > t.len() && subset(t, img.as_slice()))
            {
                let (p, slot) = unpack(raw);
                undo.removed.push(raw, t);
                self.detach(p, slot as u32);
            } else {
                i += 1;
            }
        }
        for img in images.iter().filter(|img| img.kept && img.degenerate) {
            let slot = self.push_top_from(img.as_slice(), Some(img.from));
            undo.inserted
                .push(pack(img.len as usize - 1, slot), img.as_slice());
        }
        self.images = images;
    }

    /// Undoes the contraction that returned `undo` (vertex split): b is revived with its
    /// coordinates, the created top simplices are removed and the retired ones restored in
    /// their slots, a gets its coordinates back. Splits must come in reverse order of the
    /// contractions where they touch the same simplices. Refused (unchanged) when `undo` is from
    /// before a `compact()`, was applied already, or later edits changed what it would restore
    /// (a created top simplex removed or a restored one now a face of another simplex).
    pub fn split(&mut self, undo: &UndoRecord) -> Result<(), Refusal> {
        self.renumbered();
        self.check_undo(undo)?;
        // The restored tops hold b or were St(a)'s; the created ones are St(a)'s now.
        let kept = self.across_before(|| {
            let restored = undo.removed.iter().flat_map(|(_, s)| s.iter().copied());
            self.star_vertices(&[undo.a.0]).into_iter().chain(restored)
        });
        for &raw in &undo.inserted.raw {
            let (p, slot) = unpack(raw);
            self.detach(p, slot as u32);
        }
        let b = undo.b.index();
        self.alive[b] = true;
        self.live_vertices += 1;
        for (raw, s) in undo.removed.iter() {
            let (p, slot) = unpack(raw);
            let w = p + 1;
            self.tops[p][slot * w..(slot + 1) * w].copy_from_slice(s);
            self.attach(p, slot as u32);
        }
        let k = self.coord_dim;
        self.coords[undo.a.index() * k..(undo.a.index() + 1) * k]
            .copy_from_slice(&undo.coords[..k]);
        self.coords[b * k..(b + 1) * k].copy_from_slice(&undo.coords[k..]);
        if let Some(d) = &undo.data {
            self.data.split(undo.a.0, d);
        }
        self.across_after(kept);
        Ok(())
    }

    /// Every precondition of [`LiveComplex::split`], checked before anything changes.
    fn check_undo(&self, undo: &UndoRecord) -> Result<(), Refusal> {
        let stale = |why: String| Err(Refusal::StaleHandle(why));
        if undo.epoch != self.epoch {
            return stale("undo record from before a compaction".into());
        }
        let (a, b) = (undo.a.index(), undo.b.index());
        if b >= self.alive.len() || self.alive[b] || !self.alive.get(a).copied().unwrap_or(false) {
            return stale(format!(
                "vertex {b} is live or vertex {a} is not: split already applied or out of order",
            ));
        }
        for (raw, s) in undo.inserted.iter() {
            let (p, slot) = unpack(raw);
            if self.tops[p][slot * (p + 1)] >= DEAD || self.top_raw(raw) != s {
                return stale(format!("created top simplex {} was edited since", show(s)));
            }
        }
        let inserted = &undo.inserted.raw;
        for (raw, s) in undo.removed.iter() {
            let (p, slot) = unpack(raw);
            if self.tops[p][slot * (p + 1)] < DEAD && !inserted.contains(&raw) {
                return stale(format!("slot of {} is in use", show(s)));
            }
            if let Some(&v) = s
                .iter()
                .find(|&&v| v as usize != b && !self.alive[v as usize])
            {
                return stale(format!("vertex {v} of {} was removed since", show(s)));
            }
            self.check_restorable(s, undo.b.0, inserted)?;
        }
        Ok(())
    }

    /// A restored top simplex `s` must not be a face of, equal to, or a coface of a live top
    /// simplex that the split keeps.
    fn check_restorable(&self, s: &[u32], b: u32, inserted: &[u32]) -> Result<(), Refusal> {
        for &v in s.iter().filter(|&&v| v != b) {
            for &raw in &self.star[v as usize] {
                let t = self.top_raw(raw);
                if !inserted.contains(&raw) && (subset(s, t) || subset(t, s)) {
                    return Err(Refusal::StaleHandle(format!(
                        "restoring {} conflicts with top simplex {} added since",
                        show(s),
                        show(t)
                    )));
                }
            }
        }
        Ok(())
    }

    /// Drops tombstones: live vertices and top slots are renumbered densely in ascending old
    /// order (the numbering of [`LiveComplex::to_complex`]). Every [`TopId`] and [`UndoRecord`]
    /// issued before is refused afterwards; vertex ids must be mapped by the caller. O(size).
    pub fn compact(&mut self) -> CompactMaps {
        let records: Vec<bool> = self
            .data
            .record_ids()
            .iter()
            .map(|s| self.holds_simplex(s))
            .collect();
        self.renumbered();
        let (vmap, n) = self.vertex_map();
        let mut maps = CompactMaps {
            vertices: vmap,
            tops: vec![Vec::new(); MAX_DIMENSION + 1],
        };
        for p in 1..=MAX_DIMENSION {
            let w = p + 1;
            let old = std::mem::take(&mut self.tops[p]);
            let mut next = 0u32;
            let mut table = Vec::with_capacity(self.live_tops[p] * w);
            maps.tops[p] = old
                .chunks_exact(w)
                .map(|s| {
                    if s[0] >= DEAD {
                        return NONE;
                    }
                    table.extend(s.iter().map(|&v| maps.vertices[v as usize]));
                    next += 1;
                    next - 1
                })
                .collect();
            self.tops[p] = table;
        }
        let k = self.coord_dim;
        let mut coords = Vec::with_capacity(n as usize * k);
        for v in 0..self.alive.len() {
            if self.alive[v] {
                coords.extend_from_slice(&self.coords[v * k..(v + 1) * k]);
                for raw in self.star[v].iter_mut() {
                    let (p, slot) = unpack(*raw);
                    *raw = pack(p, maps.tops[p][slot]);
                }
            }
        }
        self.star.retain_packed(&self.alive);
        self.data.compact(&maps.vertices, &maps.tops, &records);
        self.coords = coords;
        self.alive = vec![true; n as usize];
        self.epoch = self.epoch.wrapping_add(1);
        self.across_compacted();
        maps
    }
}
