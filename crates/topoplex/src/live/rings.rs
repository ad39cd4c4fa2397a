//! Every vertex's one-ring, written out: an opt-in index of the live complex, so that passes
//! repeated over every vertex's neighbours (smoothing rounds, valences, edge counts) read a
//! compressed row per vertex rather than deduplicating the vertices of its star each time.
//!
//! # What it encodes
//! For vertex slot v, `neighbours[offsets[v] .. offsets[v + 1]]` is R_{0,0}(v): every vertex
//! sharing an edge with v (any live top through v holds both), each once, in the order v's star
//! first names them (the order of `MeshView::for_each_neighbour` in C++); a removed or isolated
//! vertex has an empty row. `held[i]` is the number of live tops, of any dimension ≥ 1, holding
//! the edge {v, `neighbours[i]`}; `top_dims` has bit p set when a live top of dimension p exists,
//! so on a complex whose tops are all triangles (`top_dims == 1 << 2`) `held` is the number of
//! triangles at the edge: 1 on the boundary, 2 inside, more at a non-manifold edge.
//!
//! # Storage and cost
//! Nothing until asked ([`LiveComplex::rings`]); then `4 (slots + 1)` bytes of offsets and 8
//! bytes per entry (each edge twice: 8·2e bytes, about 52 bytes a vertex of a closed triangle
//! mesh), reported by `Navigate::handle_bytes`. Built in one pass over the stars, O(Σ_v d·k_v),
//! one thread, with two 4-byte marks per vertex slot as scratch. It belongs to one state like
//! the dense numbering (module `dense`): every topological edit drops it, setting coordinates
//! keeps it, and a query builds it behind a `OnceLock` from `&self`. A ring is then O(1) to
//! find and reading it is linear in its length.

use super::{LiveComplex, unpack};
use crate::complex::MAX_DIMENSION;
use crate::relation::StructureKind;
use crate::structures::BuildError;
use crate::structures::common::{try_reserve, try_vec, try_with_capacity};

/// The built rings of one state (see the module doc).
#[derive(Debug, Default, Clone)]
pub(super) struct RingIndex {
    offsets: Vec<u32>,
    neighbours: Vec<u32>,
    held: Vec<u32>,
    top_dims: u16,
}

impl RingIndex {
    pub(super) fn bytes(&self) -> u64 {
        4 * (self.offsets.capacity() + self.neighbours.capacity() + self.held.capacity()) as u64
    }
}

/// The rings lent ([`LiveComplex::rings`]; the module doc says what each array holds).
#[derive(Debug, Clone, Copy)]
pub struct Rings<'a> {
    /// `vertex_slots + 1` offsets into `neighbours` and `held`.
    pub offsets: &'a [u32],
    /// Every vertex's neighbours, row after row.
    pub neighbours: &'a [u32],
    /// Per entry, the live tops (dimension ≥ 1) holding the edge from the row's vertex to it.
    pub held: &'a [u32],
    /// Bit p set when the complex has a live top of dimension p (p ≥ 1).
    pub top_dims: u16,
    /// Heap bytes of the index.
    pub bytes: u64,
}

impl<'a> Rings<'a> {
    /// R_{0,0}(v) for vertex slot v (empty for a removed or isolated vertex, and for a slot
    /// beyond the complex's). O(1).
    pub fn ring(&self, v: u32) -> &'a [u32] {
        self.range(v).map_or(&[], |r| &self.neighbours[r])
    }

    /// For each entry of `ring(v)`, the live tops holding that edge. O(1).
    pub fn edge_tops(&self, v: u32) -> &'a [u32] {
        self.range(v).map_or(&[], |r| &self.held[r])
    }

    fn range(&self, v: u32) -> Option<std::ops::Range<usize>> {
        let v = v as usize;
        let end = *self.offsets.get(v + 1)?;
        Some(self.offsets[v] as usize..end as usize)
    }
}

impl LiveComplex {
    /// Every vertex's one-ring with the tops at each edge (module doc), built on the first call
    /// after an edit and kept until the next one (setting coordinates keeps it).
    /// [`BuildError::TooLarge`] when its memory cannot be had or the rings hold 2^32 entries or
    /// more. Cost: the first call O(Σ_v d·k_v), the others O(1).
    ///
    /// ```
    /// use topoplex::Complex;
    /// use topoplex::live::LiveComplex;
    /// // Three triangles on the edge 0-1 (a non-manifold edge) and one more on 0-2.
    /// let tops: [&[u32]; 4] = [&[0, 1, 2], &[0, 1, 3], &[0, 1, 4], &[0, 2, 5]];
    /// let live = LiveComplex::from_complex(&Complex::from_simplices(6, &tops).unwrap());
    /// let rings = live.rings().unwrap();
    /// // Vertex 0's neighbours, each with the number of triangles at that edge.
    /// let mut at_0: Vec<(u32, u32)> = rings.ring(0).iter().copied()
    ///     .zip(rings.edge_tops(0).iter().copied())
    ///     .collect();
    /// at_0.sort_unstable();
    /// assert_eq!(at_0, [(1, 3), (2, 2), (3, 1), (4, 1), (5, 1)]);
    /// assert_eq!(rings.top_dims, 1 << 2); // triangles only: the counts are triangle counts
    /// ```
    pub fn rings(&self) -> Result<Rings<'_>, BuildError> {
        let lock = self.dense.rings();
        if lock.get().is_none() {
            let built = self.build_rings()?;
            let _ = lock.set(built);
        }
        let r = lock.get().expect("set above");
        Ok(Rings {
            offsets: &r.offsets,
            neighbours: &r.neighbours,
            held: &r.held,
            top_dims: r.top_dims,
            bytes: r.bytes(),
        })
    }

    /// The pass of the module doc: per vertex, a mark says which candidates its row holds
    /// already and a count per candidate gathers the tops at that edge.
    fn build_rings(&self) -> Result<RingIndex, BuildError> {
        const K: StructureKind = StructureKind::IaStar;
        let slots = self.alive.len();
        let too_large = || BuildError::TooLarge {
            kind: K,
            what: "vertex rings of 2^32 entries or more".into(),
        };
        // Step 1: room. Each top of dimension q names q others of each of its vertices, so
        // Σ_t q(q + 1) bounds the entries; a closed surface fills half of it.
        let bound: u64 = (1..=MAX_DIMENSION)
            .map(|q| (self.live_tops[q] * q * (q + 1)) as u64)
            .sum();
        let first_guess = usize::try_from(bound.div_ceil(2)).map_err(|_| too_large())?;
        let mut offsets = try_vec(K, 0u32, slots + 1, "vertex ring offsets")?;
        let mut neighbours: Vec<u32> = try_with_capacity(K, first_guess, "vertex rings")?;
        let mut held: Vec<u32> = try_with_capacity(K, first_guess, "vertex ring edge counts")?;
        let mut mark = try_vec(K, 0u32, slots, "vertex ring marks")?;
        let mut count = try_vec(K, 0u32, slots, "vertex ring counts")?;
        // Doubling when short, as a push would, but fallibly (the guess above is a half).
        let grow = |v: &mut Vec<u32>, room: usize, what: &str| {
            if v.capacity() - v.len() < room {
                try_reserve(K, v, room.max(v.len()), what)?;
            }
            Ok::<(), BuildError>(())
        };
        // Step 2: one row per vertex, in slot order. Each candidate is written at the row's
        // end and kept only when new (its mark is not this vertex's), its count restarted or
        // advanced by a mask: no branch per candidate, whose outcome would follow the mesh's
        // numbering rather than a pattern (one row's room plus one, for the write past the last
        // kept entry).
        for v in 0..slots {
            offsets[v] = u32::try_from(neighbours.len()).map_err(|_| too_large())?;
            if !self.alive[v] {
                continue;
            }
            let stamp = v as u32 + 1;
            mark[v] = stamp;
            let star = &self.star[v];
            let room: usize = star.iter().map(|&t| unpack(t).0).sum::<usize>() + 1;
            let start = neighbours.len();
            grow(&mut neighbours, room, "vertex rings")?;
            neighbours.resize(start + room, 0);
            let out = &mut neighbours[start..];
            let mut n = 0;
            for &t in star {
                for &w in self.top_raw(t) {
                    let w = w as usize;
                    let fresh = mark[w] != stamp;
                    out[n] = w as u32;
                    mark[w] = stamp;
                    let keep = u32::from(fresh).wrapping_sub(1);
                    count[w] = (count[w] & keep).wrapping_add(1);
                    n += usize::from(fresh);
                }
            }
            neighbours.truncate(start + n);
            let ring = &neighbours[start..];
            grow(&mut held, ring.len(), "vertex ring edge counts")?;
            held.extend(ring.iter().map(|&w| count[w as usize]));
        }
        offsets[slots] = u32::try_from(neighbours.len()).map_err(|_| too_large())?;
        // Step 3: give back the room the guess left over.
        neighbours.shrink_to_fit();
        held.shrink_to_fit();
        let top_dims = (1..=MAX_DIMENSION)
            .filter(|&q| self.live_tops[q] > 0)
            .fold(0u16, |m, q| m | 1 << q);
        Ok(RingIndex {
            offsets,
            neighbours,
            held,
            top_dims,
        })
    }
}
