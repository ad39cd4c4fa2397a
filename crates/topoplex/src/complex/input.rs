//! What a reader hands the model: the raw simplex list and coordinates, unvalidated
//! ([`RawInput`]), and the coordinates the complex keeps ([`Coords`]). Readers ([`crate::io`])
//! stand above this and produce it; [`super::Complex::from_input`] normalises it.

use super::Attributes;
use crate::alloc;
use crate::error::{ReadErrorKind, no_room};

/// Vertex coordinates, `dim` numbers per vertex, vertex-major.
#[derive(Debug, Clone, PartialEq)]
pub struct Coords {
    /// Numbers per vertex.
    pub dim: usize,
    /// `dim` numbers per vertex, vertex after vertex.
    pub data: Vec<f64>,
}

/// What a reader produced: unvalidated simplices over 0-based vertex ids.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct RawInput {
    /// Number of vertices the file declares. `None` only for a `.simplices` file without `v`
    /// lines, where the vertices are `0..=max id`.
    pub vertex_count: Option<u32>,
    /// Coordinates of the declared vertices, when the format carries them.
    pub coords: Option<Coords>,
    /// Simplex vertex ids, concatenated; simplex `i` is `ids[offsets[i]..offsets[i + 1]]`
    /// (so `offsets` has one more entry than there are simplices and starts with 0).
    pub ids: Vec<u32>,
    /// Simplex boundaries in `ids` (see `ids`).
    pub offsets: Vec<usize>,
    /// 1-based line of each simplex in the file (0 when not from a file).
    pub lines: Vec<u32>,
    /// Named data on the vertices and on the simplices in the order pushed
    /// ([`super::attributes`]).
    pub attributes: Attributes,
    /// Polygons kept for triangulation (`crate::io::ReadOptions::triangulate`): empty unless
    /// a reader was asked to keep them.
    pub(crate) polygons: Polygons,
}

/// A reader's polygons (faces or cells of more than three vertices, listed as they are, to be
/// fanned into triangles before normalising): whether the reader keeps them rather than
/// refusing them, and the listing indices of those kept, in increasing order.
#[derive(Debug, Clone, Default, PartialEq)]
pub(crate) struct Polygons {
    /// Keep polygons (set by the caller of the reader) instead of refusing them.
    pub(crate) keep: bool,
    /// Listing indices of the polygons kept.
    pub(crate) at: Vec<usize>,
}

impl RawInput {
    /// An empty input (offsets start at 0).
    pub fn new() -> Self {
        RawInput {
            offsets: vec![0],
            ..Default::default()
        }
    }

    /// Appends one simplex read on `line` (growth infallible: for inputs built in memory; the
    /// readers use [`RawInput::try_push`]).
    pub fn push(&mut self, ids: &[u32], line: u32) {
        self.ids.extend_from_slice(ids);
        self.offsets.push(self.ids.len());
        self.lines.push(line);
    }

    /// [`RawInput::push`] whose growth is reserved fallibly: [`ReadErrorKind::TooLarge`] when
    /// the memory cannot be had (a reader's output never aborts the process).
    #[inline]
    pub fn try_push(&mut self, ids: &[u32], line: u32) -> Result<(), ReadErrorKind> {
        alloc::try_extend(&mut self.ids, ids).map_err(no_room("the simplices' vertex ids"))?;
        alloc::try_push(&mut self.offsets, self.ids.len())
            .map_err(no_room("the simplex offsets"))?;
        alloc::try_push(&mut self.lines, line).map_err(no_room("the simplices' line numbers"))
    }

    /// Reserves room for `simplices` more simplices of `ids` ids in all, fallibly
    /// ([`ReadErrorKind::TooLarge`]). Readers size it from declared counts capped by what the
    /// file could hold, so that the arrays are allocated once, at their size.
    pub fn try_reserve(&mut self, simplices: usize, ids: usize) -> Result<(), ReadErrorKind> {
        alloc::try_reserve_exact(&mut self.offsets, simplices)
            .map_err(no_room("the simplex offsets"))?;
        alloc::try_reserve_exact(&mut self.lines, simplices)
            .map_err(no_room("the simplices' line numbers"))?;
        alloc::try_reserve_exact(&mut self.ids, ids).map_err(no_room("the simplices' vertex ids"))
    }

    /// Keeps (when asked to, see [`Polygons`]) the polygon `ids` read on `line` (more than three
    /// vertices), listed as it is and recorded as a polygon; else `Err(refusal)`.
    pub(crate) fn try_push_polygon(
        &mut self,
        ids: &[u32],
        line: u32,
        refusal: ReadErrorKind,
    ) -> Result<(), ReadErrorKind> {
        if !self.polygons.keep {
            return Err(refusal);
        }
        let at = self.simplex_count();
        alloc::try_push(&mut self.polygons.at, at).map_err(no_room("the polygons' indices"))?;
        self.try_push(ids, line)
    }

    /// Number of simplices read.
    pub fn simplex_count(&self) -> usize {
        self.offsets.len() - 1
    }

    /// Simplex `i` as read (panics when out of range).
    pub fn simplex(&self, i: usize) -> &[u32] {
        &self.ids[self.offsets[i]..self.offsets[i + 1]]
    }
}

/// A plain mesh file as a streaming reader hands it over, already in the arrays a mesh keeps:
/// every listed simplex a top of its dimension, in listing order, with no listing kept beside
/// them (`crate::io::plain`). The reader has checked that each simplex has 2 to
/// `MAX_DIMENSION + 1` distinct ids below `vertex_count`; whether one repeats another or is a
/// face of another is left to the builder (then the file is read again the general way).
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct PlainTables {
    /// Vertices the file declares (at least 1).
    pub(crate) vertex_count: u32,
    /// Their coordinates, `vertex_count × dim` numbers.
    pub(crate) coords: Coords,
    /// `tops[p]`: the listed p-simplices' ids, `p + 1` each, as written (winding kept);
    /// `tops[0]` is empty.
    pub(crate) tops: Vec<Vec<u32>>,
    /// `uses[v]`: how many listed simplices hold vertex `v`.
    pub(crate) uses: Vec<u32>,
}
