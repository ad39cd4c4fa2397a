//! The live complex's sections in a saved file (`.tpx`; opening and saving a whole file is
//! `crate::store`'s, which stands above).
//!
//! Saving compacts on the fly: tombstones are not persisted, so the file holds the live complex
//! renumbered as [`LiveComplex::compact`] would (vertices and slots dense, in ascending old
//! order — the numbering of [`LiveComplex::to_complex`], which is the complex saved beside it).
//! Sections: the vertex count, the coordinates, the isolated vertices, and per dimension the
//! top-simplex table (p + 1 ids per slot, in stored winding). Stars are not saved: opening rebuilds them from the tables.
//!
//! Opening copies the mapped tables into owned, editable arrays and rebuilds the stars: O(size),
//! unlike the nine structures, whose arrays are mapped. A hostile file is refused before
//! anything trusts it: a vertex count above the vertex references the file holds (so nothing is
//! allocated for vertices the file does not name), ids beyond the vertex count, a table whose length is no multiple of its
//! arity, too many slots, then every invariant (`validate()`: repeated vertices, a top simplex
//! that is a face of another). Handles and undo records do not survive a save (the opened
//! complex starts at generation 0).

use super::{DEAD, LiveComplex, MAX_DIMENSION, SLOT_MASK, Stars};
use crate::codec::{Persist, Reader, StoreError, Writer};
use crate::mapped::Arr;

impl Persist for LiveComplex {
    fn save(&self, w: &mut Writer) {
        let (map, n) = self.vertex_map();
        w.scalar(n as u64);
        w.scalar(self.coord_dim as u64);
        let k = self.coord_dim;
        let coords: Vec<f64> = (0..self.alive.len())
            .filter(|&v| self.alive[v])
            .flat_map(|v| self.coords[v * k..(v + 1) * k].iter().copied())
            .collect();
        w.section(&coords);
        // Isolated vertices listed, so that every vertex is named in the file: a hostile vertex
        // count is refused before anything is allocated per vertex.
        let isolated: Vec<u32> = (0..self.alive.len())
            .filter(|&v| self.alive[v] && self.star[v].is_empty())
            .map(|v| map[v])
            .collect();
        w.u32s(&isolated);
        for p in 1..=MAX_DIMENSION {
            let rows: Vec<u32> = self.tops[p]
                .chunks_exact(p + 1)
                .filter(|s| s[0] < DEAD)
                .flatten()
                .map(|&v| map[v as usize])
                .collect();
            w.u32s(&rows);
        }
    }

    fn load(r: &mut Reader) -> Result<Self, StoreError> {
        let n = r.u32("vertex count")?;
        if n == 0 || n > DEAD {
            return Err(r.corrupt(format!("live complex with {n} vertex slots")));
        }
        let coord_dim = r.bounded(64, "coordinate dimension")? as usize;
        let coords: Arr<f64> = r.arr()?;
        r.expect_len("live coordinates", coords.len(), n as usize * coord_dim)?;
        let isolated = r.u32s()?;
        let mut tables = Vec::with_capacity(MAX_DIMENSION);
        for p in 1..=MAX_DIMENSION {
            let t = r.u32s()?;
            if t.len() % (p + 1) != 0 || t.len() / (p + 1) > SLOT_MASK as usize {
                return Err(r.corrupt(format!(
                    "top {p}-simplex table of {} ids is no whole number of slots",
                    t.len()
                )));
            }
            if let Some(&v) = t.iter().find(|&&v| v >= n) {
                return Err(r.corrupt(format!("top {p}-simplex table names vertex {v} of {n}")));
            }
            tables.push(t);
        }
        let named = isolated.len() + tables.iter().map(|t| t.len()).sum::<usize>();
        if n as usize > named {
            return Err(r.corrupt(format!(
                "{n} vertices, but the file names only {named} vertex references"
            )));
        }
        // The tables and stars built below are allocated infallibly: their size (per vertex a
        // degree, a flag and a star's header; per id a slot in a table and one in a star) is
        // probed first, so that a file too large for memory is refused rather than an abort.
        let ids: usize = tables.iter().map(|t| t.len()).sum();
        let bytes = (n as usize)
            .saturating_mul(4 + 1 + size_of::<Vec<u32>>())
            .saturating_add(ids.saturating_mul(8));
        crate::parallel::headroom_for(ids, bytes)
            .map_err(|bytes| r.out_of_memory("the live complex's tables", bytes))?;
        let coords = r.copy(&coords)?;
        let live = LiveComplex::from_tables(n, coord_dim, coords, &tables);
        live.check_invariants()
            .map_err(|e| r.corrupt(format!("live complex: {e}")))?;
        // Every vertex is in a top simplex or listed isolated, exactly once.
        let lonely = live.star.iter().filter(|s| s.is_empty()).count();
        let listed = isolated.windows(2).all(|w| w[0] < w[1])
            && isolated
                .iter()
                .all(|&v| v < n && live.star[v as usize].is_empty());
        if !listed || lonely != isolated.len() {
            return Err(r.corrupt("live complex: isolated vertices listed wrongly"));
        }
        Ok(live)
    }
}

impl LiveComplex {
    /// Every vertex live, the top simplices of `tables[p - 1]` in its slots (ids < n checked by
    /// the caller; everything else by `validate()` after).
    fn from_tables(n: u32, coord_dim: usize, coords: Vec<f64>, tables: &[Arr<u32>]) -> LiveComplex {
        let mut degree = vec![0u32; n as usize];
        for t in tables {
            for &v in t.iter() {
                degree[v as usize] += 1;
            }
        }
        // Sizes probed by the caller (`headroom`), so a failure here is a panic, not an abort.
        let mut live = super::build::Parts {
            tops: (0..=MAX_DIMENSION)
                .map(|p| match p {
                    0 => Vec::new(),
                    _ => Vec::with_capacity(tables[p - 1].len()),
                })
                .collect(),
            live_tops: [0; MAX_DIMENSION + 1],
            // The degrees come from the file's tables, which are in memory already.
            star: Stars::with_degrees(crate::relation::StructureKind::IaStar, &degree)
                .unwrap_or_else(|e| panic!("{e}")),
        }
        .into_live(n as usize, coord_dim, coords)
        .unwrap_or_else(|e| panic!("{e}"));
        for (i, t) in tables.iter().enumerate() {
            for s in t.chunks_exact(i + 2) {
                live.push_top(s);
            }
        }
        live
    }
}
