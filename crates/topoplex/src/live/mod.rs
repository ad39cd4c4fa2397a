//! The live complex: an updatable structure for arbitrary simplicial complexes (any dimension up
//! to 15, non-manifold, mixed-dimensional) with insertion and removal of top simplices, edge
//! contraction (link-checked or free), vertex split as its exact undo, and coordinates.
//!
//! # Why not the IA* as published
//! IA* (Canino, De Floriani, Weiss 2011) stores the top simplices per dimension with their
//! vertices, adjacencies across (p−1)-faces where manifold, per-face lists where not, and one
//! incident top simplex per vertex *cluster*. Every edit would have to repair all three: a
//! contraction changes the adjacency of every top simplex in St(a) ∪ St(b), and may merge or
//! split the clusters of every vertex in the link of {a, b}, which needs a walk of those vertices'
//! stars to find new cluster representatives. This structure keeps the IA*'s top-simplex tables
//! (vertex lists, in input winding) and replaces adjacencies + cluster representatives by the
//! complete list of incident top simplices per vertex (the VT relation restricted to tops, as in
//! the leaves of a Stellar tree). On a pure d-complex that costs the same number of integers as
//! the plain IA — (d+1)·n_d vertex references plus (d+1)·n_d star entries against the IA's
//! (d+1)·n_d vertices and (d+1)·n_d adjacencies — and every edit touches only St(a) ∪ St(b).
//! Adjacency across a facet is found by scanning the star of one of its vertices.
//!
//! # What it encodes
//! - Per dimension p ≥ 1, a table of top p-simplices, p + 1 vertex ids per slot in the order the
//!   input gave them (its winding; a contraction replaces b by a in place, so winding survives).
//!   A removed slot is a tombstone (bit 31 set on its first id, so vertex ids stay below 2^31)
//!   that keeps its vertices — a top retired by a contraction of b into a with a in b's place —
//!   until [`LiveComplex::compact`], for the handles named through it (`nav`).
//! - Per vertex: alive or not, its coordinates, and its star St*(v): every live top simplex of
//!   dimension ≥ 1 containing v, as packed [`TopId`] raw values (dimension in the top 4 bits).
//!   A live vertex with an empty star is an isolated vertex (a top 0-simplex).
//!
//! Every other simplex is implicit, as a vertex subset of a top simplex.
//!
//! # Storage
//! Σ_{p≥1} 2(p+1)·t_p integers (t_p live-or-tombstoned top p-simplices: their vertices, and one
//! star entry per vertex of each) and n_0 alive bits. The stars are one arena (`stars` module):
//! each vertex's St*(v) is a block named by three `u32`s (start, length, capacity), so bytes add
//! 12 per vertex, and the arena's spare room: after a build every block is at exactly its
//! degree with 1/8 of the arena spare at its end (none after `compact()`); after edits, the
//! blocks' unused capacity and free blocks (the arena grows only while less than 1/8 of it is
//! free). Coordinates are not counted (the nine structures hold none). On a tetrahedral mesh:
//! 32 bytes per tetrahedron (+ 2 spare) + ~13 per vertex; on a triangle mesh 24 bytes per
//! triangle (+ 1.5 spare) + ~13 per vertex.
//!
//! Two indices are built only on request, reported by `Navigate::handle_bytes`, and belong to
//! one state of the topology (setting coordinates keeps them): the tops across each facet
//! ([`LiveComplex::adjacency`], module `across`: 4 bytes per vertex of every top, kept across
//! edits on request) and every vertex's one-ring with the tops at each edge
//! ([`LiveComplex::rings`], module `rings`: 4 bytes per vertex slot and 8 per ring entry,
//! dropped by each edit).
//!
//! # Cost of each relation
//! k_v = |St*(v)|; σ a p-simplex, v its vertex with the smallest star; d ≤ 15 so subsets of a
//! simplex count as constant factors.
//! - Locating σ (`contains`): scan St*(v) for a top simplex holding σ, O(d·k_v); p = 0 O(1).
//! - R_{p,q}, q < p: the (q+1)-subsets of σ — optimal.
//! - R_{p,q}, q > p: the q-faces through σ of every top in St*(v) holding σ, sorted and deduped:
//!   O(k_v·d + m log m), m the faces produced — optimal up to the log and the scan of St*(v).
//! - R_{0,0}: the other vertices of St*(v), deduped — O(d·k_v + m log m).
//! - R_{p,p}, p > 0: every p-simplex sharing a facet with σ contains σ's first or second vertex:
//!   scan both stars, O(d²·(k_v + k_w) + m log m).
//! - `count(p)`, `simplices(p)`: enumerate the p-faces of every live top, sort, dedup:
//!   O(Σ_t C(|t|, p+1) log) — not cached, since edits would invalidate it; `count(p)` is O(1)
//!   while the dense index of dimension p is built (module `dense`, dropped by each edit).
//!
//! # Cost of each operation
//! - [`LiveComplex::insert_top`] σ: validate, refuse if present (O(d·k_v)), retire the top
//!   simplices that σ absorbs (scan St*(u) for u ∈ σ: O(d²·Σ_{u∈σ} k_u)), append a slot.
//! - [`LiveComplex::remove_top`] σ: locate O(d·k_v), tombstone, remove from the d+1 stars
//!   O(Σ_{u∈σ} k_u). Its faces that no other top simplex holds go with it, except its vertices,
//!   which stay (isolated if nothing else holds them); removing an isolated vertex (a top
//!   0-simplex) removes the vertex.
//! - [`LiveComplex::link_condition`] {a, b}: O(d·(k_a + k_b) + |F_a|·|F_b|·|F_ab|) word
//!   operations (see [`link`]).
//! - [`LiveComplex::contract`] {a, b} → a: the link test, then each top of St(b) whose image
//!   stays a top is rewritten in its own slot (b replaced by a: O(d) and one entry appended to
//!   St*(a), amortised: St*(a) moves at most once per contraction, O(k_a + k_b) words, see
//!   `stars`; its id and its entries in the other stars stay), and the others are retired
//!   (O(d·k_max) each, a scan of each vertex's star). When the link condition holds no image
//!   can be a face of another simplex or absorb one, except the images of tops through both a
//!   and b (proof at `image_star_of_b`), so only those O(k_ab) are tested, each against the
//!   smallest star of its vertices: O(d·k_b + d·k_max·k_ab) in all. In
//!   [`ContractMode::Free`] every image is tested: O(d²·k_b·(k_b + k_min)) worst case. Slots
//!   are only taken by degenerate images that stay tops, so a run of contractions does not
//!   grow the tables.
//! - [`LiveComplex::split`]: the same order as the contraction it undoes.
//! - [`LiveComplex::compact`]: O(size), renumbers vertices and slots densely and returns the maps.
//!
//! # Data
//! The complex's attributes (labels and fields, [`crate::complex::attributes`]) travel with it:
//! a row per vertex slot and per top slot, and a record per other listed simplex with data, kept
//! through insert, remove, contraction, split and `compact()` ([`data`] says how and at what
//! cost); [`LiveComplex::to_complex`] writes them back.
//!
//! # Handles and invalidation
//! [`VertexId`]s and [`TopId`]s stay valid across every edit until [`LiveComplex::compact`]
//! (tombstones keep the slots; a top moved by a contraction keeps its id and names its image);
//! a [`TopId`] or [`UndoRecord`] from before a compaction is refused
//! ([`Refusal::StaleHandle`]). Vertex ids are plain slots: after `compact`, use the returned map.
//!
//! The live complex answers the whole handle API ([`crate::relation::handle::Navigate`]: locate,
//! boundary / co-boundary / adjacency per dimension, star, link, degree, `is_boundary`,
//! `is_manifold`, fans around a vertex counter-clockwise by the winding, radial groups around an
//! edge). A vertex's handle is its slot; any other simplex is named through a top simplex
//! holding it (a top simplex and a vertex mask). Every handle carries the complex's generation
//! (its compaction count, [`crate::relation::handle::Navigate::generation`]): one from before `compact` is
//! refused with [`QueryError::StaleGeneration`]; otherwise a handle names its simplex while that
//! simplex exists, even when the top simplex naming it is removed (a removed slot keeps its
//! vertices until `compact`, and the face is located again: O(d·k_v) per use), and is refused
//! with [`QueryError::StaleHandle`] once the simplex is gone; across a contraction it names the
//! simplex's image (b replaced by a). The generation costs 4 bytes per handle and one comparison
//! per check. Costs per operation: the `nav` module (O(1) checks and reads, `locate` O(d·k_v),
//! relations as above plus O(d·k) to name each answer of dimension ≤ p, answers lexicographic,
//! no allocation once warm).
//!
//! # Lent arrays, reading and writing
//! [`LiveComplex::arrays`] lends the tables, the star arena and its block table, the live
//! flags and the coordinates as they are stored ([`LiveArrays`]; C `tpx_live_arrays`), for
//! callers that navigate them inline (the C++ `topoplex::MeshView`): O(1), valid until the next
//! edit of the topology. [`LiveComplex::from_plain_listing`] builds the live complex straight
//! from a reader's listing when it is plain (the usual mesh file: no complex, no sort), and
//! [`LiveComplex::write`] writes it from [`LiveComplex::to_listing`] without building a complex.
//!
//! # Dense indices
//! The index half of the handle API (`handle(p, i)`, `index_of`, `related_ids`,
//! `related_batch`, `degree_batch`, `relation_view`) numbers the simplices above vertices by
//! lexicographic rank, as the nine structures do, from tables built on first use and dropped by
//! every edit (module `dense`: storage and costs; setting coordinates keeps them). A vertex's
//! index is its slot. Indices above vertices, lent views and dense handles made from indices
//! are valid until the next edit; the handles above are what lasts across edits.

use std::fmt;

use crate::complex::{Complex, MAX_DIMENSION, RawInput};
use crate::relation::{QueryError, Storage, StructureKind, Topology};
use crate::structures::BuildError;
use crate::structures::common::{too_large, try_copy, try_vec};
use crate::structures::ia::faces_containing as faces;

mod across;
mod build;
pub mod data;
mod dense;
mod edit;
pub mod link;
mod nav;
mod rings;
mod stars;
mod store;

use stars::Stars;

pub use across::{ACROSS_MANY, ACROSS_NONE, Adjacency};
pub use data::{VertexMerge, VertexPolicy};
pub use edit::{CompactMaps, ContractMode, UndoRecord};
pub use rings::Rings;

/// "No vertex" marker.
const NONE: u32 = u32::MAX;
/// Tombstone bit, set on a removed top's first id: the slot keeps its vertices until
/// [`LiveComplex::compact`], so a handle through it can still find its face (`nav`). Vertex ids
/// stay below it.
const DEAD: u32 = 1 << 31;
/// Bits of a packed top id that hold the slot; the dimension is in the 4 bits above.
const SLOT_BITS: u32 = 28;
const SLOT_MASK: u32 = (1 << SLOT_BITS) - 1;

/// A vertex of a [`LiveComplex`]: the crate's vertex handle; its slot, stable until
/// [`LiveComplex::compact`].
pub use crate::relation::handle::VertexId;

/// A top simplex of a [`LiveComplex`]: its dimension and slot, and the compaction epoch it was
/// issued in (so a handle from before [`LiveComplex::compact`] is refused, not misread).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct TopId {
    raw: u32,
    epoch: u32,
}

impl TopId {
    /// Dimension of the top simplex (≥ 1; isolated vertices are addressed by [`VertexId`]).
    pub fn dim(self) -> usize {
        (self.raw >> SLOT_BITS) as usize
    }

    /// Slot in its dimension's table.
    pub fn slot(self) -> u32 {
        self.raw & SLOT_MASK
    }
}

fn pack(p: usize, slot: u32) -> u32 {
    ((p as u32) << SLOT_BITS) | slot
}

fn unpack(raw: u32) -> (usize, usize) {
    ((raw >> SLOT_BITS) as usize, (raw & SLOT_MASK) as usize)
}

fn show(ids: &[u32]) -> String {
    let v: Vec<String> = ids.iter().map(|i| i.to_string()).collect();
    format!("[{}]", v.join(" "))
}

/// Why an edit was refused. The structure is unchanged after every refusal.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum Refusal {
    /// The simplex is empty, has more than 16 vertices, or repeats a vertex.
    #[error("invalid simplex {}: {why}", show(.simplex))]
    InvalidSimplex {
        /// The simplex as given.
        simplex: Vec<u32>,
        /// What is wrong with it.
        why: &'static str,
    },
    /// A vertex id is out of range or names a removed (contracted or deleted) vertex.
    #[error("vertex {vertex} is not a live vertex (slots 0..{slots})")]
    UnknownVertex {
        /// The vertex as given.
        vertex: u32,
        /// Number of vertex slots.
        slots: u32,
    },
    /// Topology-preserving contraction of a pair that is not an edge.
    #[error("{{{a}, {b}}} is not an edge of the complex")]
    NotAnEdge {
        /// First vertex.
        a: u32,
        /// Second vertex.
        b: u32,
    },
    /// The link condition Lk(a) ∩ Lk(b) = Lk(ab) fails; `simplex` is a lowest-dimensional
    /// simplex of Lk(a) ∩ Lk(b) that is not in Lk(ab), of dimension `dim`.
    #[error("link condition fails for edge {{{a}, {b}}} in dimension {dim}: {} is in Lk({a}) ∩ Lk({b}) but not in Lk({a}{b})", show(.simplex))]
    LinkCondition {
        /// First vertex.
        a: u32,
        /// Second vertex.
        b: u32,
        /// Dimension of the offending link simplex.
        dim: usize,
        /// The offending link simplex (ascending).
        simplex: Vec<u32>,
    },
    /// Insertion of a simplex that is already in the complex (as a top simplex or a face).
    #[error("simplex {} is already in the complex", show(.simplex))]
    AlreadyPresent {
        /// The simplex as given.
        simplex: Vec<u32>,
    },
    /// Removal of a simplex that is a proper face of another simplex.
    #[error("simplex {} is not a top simplex (it is a face of {})", show(.simplex), show(.coface))]
    NotTop {
        /// The simplex as given.
        simplex: Vec<u32>,
        /// A top simplex having it as a proper face.
        coface: Vec<u32>,
    },
    /// Removal of a simplex that is not in the complex.
    #[error("simplex {} is not in the complex", show(.simplex))]
    NotInComplex {
        /// The simplex as given.
        simplex: Vec<u32>,
    },
    /// A handle or undo record from before a `compact()`, of a removed top simplex, or an undo
    /// record whose contraction's result has since been edited.
    #[error("stale handle: {0}")]
    StaleHandle(String),
    /// Coordinates of the wrong length.
    #[error("{given} coordinates given, the complex has {dim} per vertex")]
    CoordinateDimension {
        /// Numbers given.
        given: usize,
        /// Coordinates per vertex.
        dim: usize,
    },
    /// A coordinate given is NaN or infinite (nothing was changed).
    #[error("coordinate {coordinate} of vertex {vertex} is {value}, not a finite number")]
    NonFiniteCoordinate {
        /// The vertex it was for.
        vertex: u32,
        /// Its position among the vertex's coordinates.
        coordinate: usize,
        /// The number as given (`NaN`, `inf`, `-inf`).
        value: String,
    },
}

/// An updatable simplicial complex; see the module documentation.
#[derive(Debug, Clone)]
pub struct LiveComplex {
    /// `tops[p]`: p + 1 ids per slot (input winding); a tombstone's first id has `DEAD` set.
    /// `tops[0]` is unused (isolated vertices are live vertices with an empty star).
    tops: Vec<Vec<u32>>,
    /// Live top p-simplices per dimension (p ≥ 1).
    live_tops: [usize; MAX_DIMENSION + 1],
    alive: Vec<bool>,
    live_vertices: u32,
    /// St*(v): packed ids of the live top simplices of dimension ≥ 1 containing v, one block
    /// per vertex in one arena (`stars` module).
    star: Stars,
    coord_dim: usize,
    coords: Vec<f64>,
    /// Bumped by `compact()`; handles and undo records carry it.
    epoch: u32,
    /// Contraction scratch: the images of St(b), kept between edits to avoid allocating.
    images: Vec<Image>,
    /// The attributes carried beside the slots (`data` module); empty without data.
    data: data::LiveData,
    /// Dense indices above vertices and lent views, built on first use, dropped by each edit
    /// (`dense` module).
    dense: dense::DenseIndex,
    /// The facet adjacency when the caller keeps it across edits (`across` module), else None.
    kept_across: Option<across::Across>,
}

/// The arrays of a [`LiveComplex`] as stored ([`LiveComplex::arrays`]): what every navigation
/// reads, for callers that walk them inline. Layout (the module doc's storage):
/// - a top p-simplex is named by its packed id `p << 28 | slot`, the raw value of a
///   [`crate::relation::handle::TopId`] and of `tpx_live_top_vertices`' argument;
/// - St*(v), the live tops of dimension ≥ 1 through vertex slot v, is
///   `star_words[start .. start + len]` with `start = star_blocks[3v]`,
///   `len = star_blocks[3v + 1]` (`star_blocks[3v + 2]` is the block's capacity), in no
///   particular order (an edit may reorder it);
/// - a vertex slot is live when `alive[v]`; an isolated vertex is a live vertex with an empty
///   star; its coordinates are `coords[v·coord_dim ..][.. coord_dim]`.
#[derive(Debug, Clone, Copy)]
pub struct LiveArrays<'a> {
    /// `tops[p]`, p ≥ 1: p + 1 vertex ids per slot in stored order (the input winding). A
    /// removed slot (a tombstone, never in a star) has bit 31 set on its first id. `tops[0]` is
    /// empty.
    pub tops: [&'a [u32]; MAX_DIMENSION + 1],
    /// The star arena (packed top ids), addressed through `star_blocks`.
    pub star_words: &'a [u32],
    /// Start, length and capacity of each vertex slot's star block: 3 words per slot.
    pub star_blocks: &'a [u32],
    /// Per vertex slot: live or not.
    pub alive: &'a [bool],
    /// `coord_dim` numbers per vertex slot.
    pub coords: &'a [f64],
    /// Coordinates per vertex (0 when the complex has none).
    pub coord_dim: usize,
    /// The compaction count (the handles' generation).
    pub generation: u32,
}

/// A top simplex's image under a contraction: at most 16 ids inline, in stored order.
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct Image {
    len: u8,
    /// From a top through both a and b (b dropped, one dimension lower).
    degenerate: bool,
    /// Still a top simplex after the contraction (decided before anything changes).
    kept: bool,
    /// The top of St(b) it is the image of (packed id).
    from: u32,
    ids: [u32; MAX_DIMENSION + 1],
}

impl Image {
    fn push(&mut self, v: u32) {
        self.ids[self.len as usize] = v;
        self.len += 1;
    }

    fn as_slice(&self) -> &[u32] {
        &self.ids[..self.len as usize]
    }
}

/// `small ⊆ big` for unsorted vertex lists of at most 16 ids.
#[inline]
fn subset(small: &[u32], big: &[u32]) -> bool {
    small.len() <= big.len() && small.iter().all(|v| big.contains(v))
}

/// A sorted copy of at most 16 ids, inline.
#[derive(Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub(crate) struct Key {
    len: u8,
    ids: [u32; MAX_DIMENSION + 1],
}

impl Key {
    pub(crate) fn new(vs: &[u32]) -> Key {
        let mut ids = [0u32; MAX_DIMENSION + 1];
        ids[..vs.len()].copy_from_slice(vs);
        ids[..vs.len()].sort_unstable();
        Key {
            len: vs.len() as u8,
            ids,
        }
    }

    /// A copy of `vs`, already ascending (not checked): no sort.
    #[inline]
    pub(crate) fn sorted(vs: &[u32]) -> Key {
        let mut ids = [0u32; MAX_DIMENSION + 1];
        ids[..vs.len()].copy_from_slice(vs);
        Key {
            len: vs.len() as u8,
            ids,
        }
    }

    pub(crate) fn as_slice(&self) -> &[u32] {
        &self.ids[..self.len as usize]
    }
}

impl fmt::Debug for Key {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{:?}", self.as_slice())
    }
}

impl LiveComplex {
    /// Builds from a complex: every vertex of `complex` is live with the same id, every top
    /// simplex gets a slot in input order with its input winding (`Complex::tops_as_given`;
    /// read from the listing itself when it holds nothing but distinct top simplices).
    /// O(size of the top simplices). Aborts, like `Vec`, when the memory cannot be had: a host
    /// that must survive that uses [`LiveComplex::try_from_complex`].
    pub fn from_complex(complex: &Complex) -> LiveComplex {
        Self::try_from_complex(complex).unwrap_or_else(|e| panic!("{e}"))
    }

    /// [`LiveComplex::from_complex`], or [`BuildError::TooLarge`] (kind `IaStar`) when an array
    /// sized from the input cannot be allocated: every array is reserved exactly, fallibly, before
    /// it is filled, so no allocation failure aborts the process.
    ///
    /// When the listing is the complex's top simplices (the usual case for maximal simplices)
    /// the tables and stars come from it directly, the stars on several threads (`build`
    /// module; the same arrays with any thread count); otherwise every top is pushed in turn.
    pub fn try_from_complex(complex: &Complex) -> Result<LiveComplex, BuildError> {
        let n = Self::check_vertex_count(complex)?;
        if complex.tops_listed_needs_maps() {
            return Self::try_from_complex_by_pushes(complex);
        }
        let parts = build::from_listing(complex, n)?;
        let (coord_dim, coords) = Self::coords_of(complex)?;
        let mut live = parts.into_live(n, coord_dim, coords)?;
        live.data = data::LiveData::of(complex, &live);
        Ok(live)
    }

    /// A reader's listing straight into a live complex, when it is plain (a declared vertex
    /// count, no attributes, every simplex 2 to 16 distinct ids below the count, none listed
    /// twice or a face of another — the usual mesh file): the same live complex as
    /// [`LiveComplex::try_from_complex`] of its normalised complex, without the complex (no
    /// sort, no closure bound, the complex's memory never taken). `None` for any other listing:
    /// normalise it ([`Complex::from_input`]) and build from the complex, which also names what
    /// is wrong with a bad one. `crate::store::open_live` does both.
    pub fn from_plain_listing(raw: &RawInput) -> Option<Result<LiveComplex, BuildError>> {
        build::from_plain_listing(raw)
    }

    /// A streamed plain file's tables as a live complex, the tables moved in (no copy): `None`
    /// when a top repeats another or is a face of another, for the general read.
    pub(crate) fn from_plain_tables(
        tables: crate::complex::PlainTables,
    ) -> Option<Result<LiveComplex, BuildError>> {
        build::from_plain_tables(tables)
    }

    fn check_vertex_count(complex: &Complex) -> Result<usize, BuildError> {
        let n = complex.vertex_count() as usize;
        if n > DEAD as usize {
            return Err(BuildError::TooLarge {
                kind: StructureKind::IaStar,
                what: format!("{n} vertices (at most 2^31)"),
            });
        }
        Ok(n)
    }

    fn coords_of(complex: &Complex) -> Result<(usize, Vec<f64>), BuildError> {
        Ok(match complex.coords() {
            Some(c) => (
                c.dim,
                try_copy(StructureKind::IaStar, &c.data, "coordinates")?,
            ),
            None => (0, Vec::new()),
        })
    }

    /// [`LiveComplex::try_from_complex`] by pushing every top simplex, in listing order, into
    /// its table and its vertices' stars: any complex, on one thread.
    fn try_from_complex_by_pushes(complex: &Complex) -> Result<LiveComplex, BuildError> {
        const K: StructureKind = StructureKind::IaStar;
        let n = Self::check_vertex_count(complex)?;
        let (coord_dim, coords) = Self::coords_of(complex)?;
        if complex.tops_listed_needs_maps() {
            complex
                .try_listing_maps()
                .map_err(|bytes| too_large(K, bytes, "the input listing's maps"))?;
        }
        let mut degree = try_vec(K, 0u32, n, "vertex degrees")?;
        let mut per_dim = [0usize; MAX_DIMENSION + 1];
        for (p, s) in complex.tops_listed() {
            per_dim[p] += 1;
            for &v in s {
                degree[v as usize] += 1;
            }
        }
        let tops = build::empty_tables(&per_dim)?;
        let star = Stars::with_degrees(K, &degree)?;
        drop(degree);
        let mut live = build::Parts {
            tops,
            live_tops: [0; MAX_DIMENSION + 1],
            star,
        }
        .into_live(n, coord_dim, coords)?;
        for (_, s) in complex.tops_listed() {
            live.push_top(s);
        }
        live.data = data::LiveData::of(complex, &live);
        Ok(live)
    }

    /// Appends a slot for `s` (not checked) and enters it in its vertices' stars.
    fn push_top(&mut self, s: &[u32]) -> u32 {
        self.push_top_from(s, None)
    }

    /// [`LiveComplex::push_top`] whose data row is a copy of top `from`'s (packed id), or
    /// unset.
    fn push_top_from(&mut self, s: &[u32], from: Option<u32>) -> u32 {
        let p = s.len() - 1;
        let slot = (self.tops[p].len() / (p + 1)) as u32;
        assert!(slot <= SLOT_MASK, "more than 2^28 top {p}-simplices");
        self.tops[p].extend_from_slice(s);
        self.attach(p, slot);
        self.data.push_top(p, from.map(unpack));
        slot
    }

    /// Enters the top at (p, slot) in its vertices' stars and counts it live.
    fn attach(&mut self, p: usize, slot: u32) {
        let raw = pack(p, slot);
        let w = p + 1;
        for i in 0..w {
            let v = self.tops[p][slot as usize * w + i];
            self.star.push(v, raw);
        }
        self.live_tops[p] += 1;
    }

    /// Removes the top at (p, slot) from its vertices' stars and tombstones the slot; returns
    /// its vertices.
    fn detach(&mut self, p: usize, slot: u32) -> Vec<u32> {
        let raw = pack(p, slot);
        let w = p + 1;
        let s = self.tops[p][slot as usize * w..(slot as usize + 1) * w].to_vec();
        for &v in &s {
            self.unstar(v, raw);
        }
        self.tops[p][slot as usize * w] |= DEAD;
        self.live_tops[p] -= 1;
        s
    }

    /// Like [`LiveComplex::detach`], leaving the star of `skip` alone (the caller has taken it).
    fn detach_except(&mut self, p: usize, slot: u32, skip: u32) {
        let raw = pack(p, slot);
        let w = p + 1;
        for i in 0..w {
            let v = self.tops[p][slot as usize * w + i];
            if v != skip {
                self.unstar(v, raw);
            }
        }
        self.tops[p][slot as usize * w] |= DEAD;
        self.live_tops[p] -= 1;
    }

    /// Removes the entry `raw` from St*(v). O(k_v).
    fn unstar(&mut self, v: u32, raw: u32) {
        let i = self.star[v as usize]
            .iter()
            .position(|&x| x == raw)
            .expect("star entry");
        self.star.swap_remove(v, i);
    }

    /// Vertices of the top with packed id `raw`, in stored (winding) order.
    #[inline]
    fn top_raw(&self, raw: u32) -> &[u32] {
        let (p, slot) = unpack(raw);
        &self.tops[p][slot * (p + 1)..(slot + 1) * (p + 1)]
    }

    fn handle(&self, raw: u32) -> TopId {
        TopId {
            raw,
            epoch: self.epoch,
        }
    }

    /// Number of vertex slots (live or removed); vertex ids are `0..vertex_slots()`.
    pub fn vertex_slots(&self) -> u32 {
        self.alive.len() as u32
    }

    /// Number of live vertices.
    pub fn live_vertex_count(&self) -> u32 {
        self.live_vertices
    }

    /// Whether `v` is a live vertex.
    pub fn is_live(&self, v: VertexId) -> bool {
        self.alive.get(v.index()).copied().unwrap_or(false)
    }

    /// The live vertices, ascending.
    pub fn vertices(&self) -> impl Iterator<Item = VertexId> + '_ {
        (0..self.vertex_slots())
            .filter(|&v| self.alive[v as usize])
            .map(VertexId)
    }

    pub(crate) fn check_vertex(&self, v: u32) -> Result<(), Refusal> {
        if self.alive.get(v as usize).copied().unwrap_or(false) {
            Ok(())
        } else {
            Err(Refusal::UnknownVertex {
                vertex: v,
                slots: self.vertex_slots(),
            })
        }
    }

    /// The complex's own arrays, lent for navigation without a call per query (the C ABI's
    /// `tpx_live_arrays`, the C++ `topoplex::MeshView`, which navigates them inline). Nothing
    /// is copied or built: O(1). The borrow ends at the next edit, which may move any array
    /// (setting coordinates writes in place, so C callers keep their pointers across it).
    pub fn arrays(&self) -> LiveArrays<'_> {
        let (star_words, star_blocks) = self.star.lend();
        LiveArrays {
            tops: std::array::from_fn(|p| self.tops.get(p).map_or(&[][..], |t| &t[..])),
            star_words,
            star_blocks,
            alive: &self.alive,
            coords: &self.coords,
            coord_dim: self.coord_dim,
            generation: self.epoch,
        }
    }

    /// Coordinates per vertex (0 when the complex has none).
    pub fn coord_dim(&self) -> usize {
        self.coord_dim
    }

    /// The coordinates of a live vertex (empty when the complex has none). O(1).
    pub fn coords(&self, v: VertexId) -> Result<&[f64], Refusal> {
        self.check_vertex(v.0)?;
        let k = self.coord_dim;
        Ok(&self.coords[v.index() * k..(v.index() + 1) * k])
    }

    /// Sets the coordinates of a live vertex; `xyz` must have [`LiveComplex::coord_dim`]
    /// finite numbers. Refused, changing nothing: [`Refusal::UnknownVertex`] (a removed or
    /// out-of-range vertex), [`Refusal::CoordinateDimension`], [`Refusal::NonFiniteCoordinate`].
    /// Not an edit of the topology: handles, dense indices and lent views stay valid. A
    /// [`LiveComplex::split`] puts back the coordinates a and b had before the contraction it
    /// undoes (also over a later setting of a's). O(coord_dim).
    pub fn set_coords(&mut self, v: VertexId, xyz: &[f64]) -> Result<(), Refusal> {
        self.check_vertex(v.0)?;
        self.check_coords_of(v.0, xyz)?;
        let k = self.coord_dim;
        self.coords[v.index() * k..(v.index() + 1) * k].copy_from_slice(xyz);
        Ok(())
    }

    /// Every vertex slot's coordinates, slot after slot ([`LiveComplex::coord_dim`] numbers
    /// each; a removed vertex's are its last ones, meaningless): the array itself, lent, so a
    /// pass over all vertices reads it without a call per vertex. O(1).
    pub fn all_coords(&self) -> &[f64] {
        &self.coords
    }

    /// Sets every vertex slot's coordinates at once from `data`, slot after slot:
    /// `vertex_slots() × coord_dim()` finite numbers (those of removed vertices are stored and
    /// never read). Refused, changing nothing: [`Refusal::CoordinateDimension`] (`given` the
    /// length, `dim` the length needed), [`Refusal::NonFiniteCoordinate`] (the first one). Not
    /// an edit of the topology (as [`LiveComplex::set_coords`]). O(vertex slots), no
    /// allocation: the array is overwritten in place.
    pub fn set_all_coords(&mut self, data: &[f64]) -> Result<(), Refusal> {
        if data.len() != self.coords.len() {
            return Err(Refusal::CoordinateDimension {
                given: data.len(),
                dim: self.coords.len(),
            });
        }
        // Finite unless the exponent bits are all ones: tested a block at a time without a
        // branch per number (a pass of smoothing sets every coordinate), the culprit found only
        // when a block holds one.
        const EXPONENT: u64 = 0x7ff0_0000_0000_0000;
        let finite = |c: &[f64]| {
            !c.iter()
                .fold(false, |bad, x| bad | (x.to_bits() & EXPONENT == EXPONENT))
        };
        if !data.chunks(256).all(finite)
            && let Some(i) = data.iter().position(|x| !x.is_finite())
        {
            let k = self.coord_dim.max(1);
            return Err(Refusal::NonFiniteCoordinate {
                vertex: (i / k) as u32,
                coordinate: i % k,
                value: data[i].to_string(),
            });
        }
        self.coords.copy_from_slice(data);
        Ok(())
    }

    /// `xyz` as the coordinates of vertex `v` (live or about to be): the right length, finite.
    fn check_coords_of(&self, v: u32, xyz: &[f64]) -> Result<(), Refusal> {
        if xyz.len() != self.coord_dim {
            return Err(Refusal::CoordinateDimension {
                given: xyz.len(),
                dim: self.coord_dim,
            });
        }
        if let Some(i) = xyz.iter().position(|x| !x.is_finite()) {
            return Err(Refusal::NonFiniteCoordinate {
                vertex: v,
                coordinate: i,
                value: xyz[i].to_string(),
            });
        }
        Ok(())
    }

    /// Adds an isolated vertex with coordinates `xyz` ([`LiveComplex::coord_dim`] finite
    /// numbers). Amortised O(1).
    pub fn add_vertex(&mut self, xyz: &[f64]) -> Result<VertexId, Refusal> {
        self.check_coords_of(self.vertex_slots(), xyz)?;
        self.renumbered();
        let v = self.vertex_slots();
        if v >= DEAD {
            return Err(Refusal::StaleHandle("vertex slots exhausted".into()));
        }
        self.alive.push(true);
        self.star.add_vertex();
        self.coords.extend_from_slice(xyz);
        self.data.push_vertex();
        self.live_vertices += 1;
        Ok(VertexId(v))
    }

    /// The live top simplices of dimension ≥ 1 (isolated vertices: [`LiveComplex::vertices`]
    /// with an empty [`LiveComplex::vertex_star`]), by dimension then slot, with their vertices
    /// in stored (winding) order. O(1) per item plus tombstones skipped.
    pub fn tops(&self) -> impl Iterator<Item = (TopId, &[u32])> + '_ {
        (1..=MAX_DIMENSION).flat_map(move |p| {
            self.tops[p]
                .chunks_exact(p + 1)
                .enumerate()
                .filter(|(_, s)| s[0] < DEAD)
                .map(move |(slot, s)| (self.handle(pack(p, slot as u32)), s))
        })
    }

    /// The vertices of a live top simplex, in stored (winding) order. O(1).
    pub fn top_vertices(&self, t: TopId) -> Result<&[u32], Refusal> {
        self.check_top(t)?;
        Ok(self.top_raw(t.raw))
    }

    /// The live top whose packed id is `packed` (dimension << 28 | slot: the numbering of the
    /// handle API, [`crate::relation::handle::TopId`], and of the C ABI's live tops), as a
    /// handle of the current compaction epoch. Errors: [`Refusal::StaleHandle`] when no live
    /// top of dimension ≥ 1 has that slot. O(1).
    pub fn top_of_packed(&self, packed: u32) -> Result<TopId, Refusal> {
        let t = TopId {
            raw: packed,
            epoch: self.epoch,
        };
        if t.dim() >= self.tops.len() {
            return Err(Refusal::StaleHandle(format!(
                "top id {packed:#x} names dimension {}",
                t.dim()
            )));
        }
        self.check_top(t)?;
        Ok(t)
    }

    fn check_top(&self, t: TopId) -> Result<(), Refusal> {
        if t.epoch != self.epoch {
            return Err(Refusal::StaleHandle(format!(
                "top simplex handle from before compaction {}",
                t.epoch + 1
            )));
        }
        let (p, slot) = unpack(t.raw);
        let w = p + 1;
        if p == 0 || (slot + 1) * w > self.tops[p].len() || self.tops[p][slot * w] >= DEAD {
            return Err(Refusal::StaleHandle(format!(
                "top {p}-simplex slot {slot} is not live"
            )));
        }
        Ok(())
    }

    /// St*(v): the live top simplices of dimension ≥ 1 containing `v`, in no particular order.
    /// O(1) per item.
    pub fn vertex_star(&self, v: VertexId) -> Result<impl Iterator<Item = TopId> + '_, Refusal> {
        self.check_vertex(v.0)?;
        Ok(self.star[v.index()].iter().map(|&raw| self.handle(raw)))
    }

    /// The edges of the complex, each once as (lower id, higher id), ascending.
    /// O(Σ_t |t|² + m log m).
    pub fn edges(&self) -> Vec<[u32; 2]> {
        let mut out = Vec::new();
        self.simplices(1, &mut out);
        out.chunks_exact(2).map(|e| [e[0], e[1]]).collect()
    }

    /// The complex as a [`Complex`], live vertices renumbered densely in ascending id order (the
    /// numbering [`LiveComplex::compact`] gives), top simplices in dimension-then-slot order with
    /// their winding, coordinates kept. Freeze it into any of the nine structures with
    /// [`crate::build`]. O(size).
    pub fn to_complex(&self) -> Complex {
        let raw = self.to_listing();
        let n = raw.vertex_count.unwrap_or(0);
        let mut c = Complex::from_arrays(n, &raw.ids, &raw.offsets, raw.coords)
            .expect("a live complex is a valid complex (has a vertex, ids in range)");
        if !self.data.is_empty() {
            c.set_attributes(raw.attributes)
                .expect("the live data has a row per live vertex, top and record");
        }
        c
    }

    /// The complex as a listing, what a writer takes: the numbering of
    /// [`LiveComplex::to_complex`], every live top in dimension-then-slot order with its
    /// winding, then each other listed simplex that carries data and still exists, the
    /// coordinates and the attributes. O(size), no complex built (no sorting, no closure).
    pub fn to_listing(&self) -> RawInput {
        let (map, n) = self.vertex_map();
        let mut raw = RawInput::new();
        raw.vertex_count = Some(n);
        let mut live_slots: Vec<Vec<usize>> = vec![Vec::new(); MAX_DIMENSION + 1];
        let tops: usize = self.live_tops.iter().sum();
        let ids: usize = (1..=MAX_DIMENSION)
            .map(|p| (p + 1) * self.live_tops[p])
            .sum();
        raw.ids.reserve_exact(ids);
        raw.offsets.reserve_exact(tops + 1);
        // No line numbers: nothing was read from a file, and writers do not read them.
        let push = |raw: &mut RawInput, s: &[u32]| {
            raw.ids.extend(s.iter().map(|&v| map[v as usize]));
            raw.offsets.push(raw.ids.len());
        };
        for (t, s) in self.tops() {
            push(&mut raw, s);
            if !self.data.is_empty() {
                live_slots[t.dim()].push(t.slot() as usize);
            }
        }
        let mut records = Vec::new();
        for (r, s) in self.data.live_records(|s| self.holds_simplex(s)) {
            push(&mut raw, s);
            records.push(r);
        }
        raw.coords = (self.coord_dim > 0).then(|| {
            let k = self.coord_dim;
            let mut data = Vec::with_capacity(n as usize * k);
            for v in (0..self.vertex_slots() as usize).filter(|&v| self.alive[v]) {
                data.extend_from_slice(&self.coords[v * k..(v + 1) * k]);
            }
            crate::complex::Coords { dim: k, data }
        });
        if !self.data.is_empty() {
            raw.attributes = self.data.attributes(&self.alive, &live_slots, &records);
        }
        raw
    }

    /// Writes the complex to `path` in `format` (by default the one its extension names), as
    /// writing [`LiveComplex::to_complex`] would, but from [`LiveComplex::to_listing`]: no
    /// complex is built, so the memory above the live complex is the listing (4 bytes per id,
    /// 12 per simplex) and the file's bytes. Nothing is written when the format cannot hold it.
    ///
    /// An OFF file of edges and triangles (at most 3 coordinates, no attributes) is written
    /// straight from the tables, with no listing: the memory above the live complex is a 1 MiB
    /// piece of the file (and 4 bytes a vertex slot once vertices were removed).
    pub fn write(
        &self,
        path: &std::path::Path,
        format: Option<crate::io::write::Format>,
    ) -> Result<(), crate::io::write::WriteError> {
        use crate::io::write::{Format, write_plain_off, write_raw};
        let format = format.or_else(|| Format::from_path(path));
        let plain = format == Some(Format::Off)
            && self.data.is_empty()
            && self.coord_dim <= 3
            && self.live_tops[3..].iter().all(|&k| k == 0);
        if !plain {
            return write_raw(&self.to_listing(), path, format);
        }
        // Dense vertex ids as `to_listing` numbers them: the slots, unless some were removed.
        let gaps = self.live_vertices != self.vertex_slots();
        let map = if gaps {
            self.vertex_map().0
        } else {
            Vec::new()
        };
        let k = self.coord_dim;
        let mut slot = 0;
        let coords = |_| {
            while !self.alive[slot] {
                slot += 1;
            }
            slot += 1;
            &self.coords[(slot - 1) * k..slot * k]
        };
        let m: usize = self.live_tops.iter().sum();
        let faces = self.tops().map(|(_, s)| s);
        let id = |v: u32| if gaps { map[v as usize] } else { v };
        write_plain_off(path, self.live_vertices as usize, coords, m, faces, id)
    }

    /// Old vertex slot → dense id (`NONE` for removed ones), and the live count.
    fn vertex_map(&self) -> (Vec<u32>, u32) {
        let mut next = 0;
        let map = self
            .alive
            .iter()
            .map(|&a| {
                if a {
                    next += 1;
                    next - 1
                } else {
                    NONE
                }
            })
            .collect();
        (map, next)
    }

    /// The live top with the same vertex set as `sorted` (ascending), if any.
    fn find_top(&self, sorted: &[u32]) -> Option<u32> {
        if sorted.len() < 2 {
            return None;
        }
        let v = self.smallest_star(sorted);
        self.star[v as usize]
            .iter()
            .copied()
            .find(|&raw| unpack(raw).0 + 1 == sorted.len() && subset(sorted, self.top_raw(raw)))
    }

    /// A live top containing `sigma` (any order, live vertices, |σ| ≥ 1), if any.
    fn top_containing(&self, sigma: &[u32]) -> Option<u32> {
        let v = self.smallest_star(sigma);
        self.star[v as usize]
            .iter()
            .copied()
            .find(|&raw| subset(sigma, self.top_raw(raw)))
    }

    fn smallest_star(&self, sigma: &[u32]) -> u32 {
        *sigma
            .iter()
            .min_by_key(|&&v| self.star[v as usize].len())
            .unwrap()
    }

    /// Whether `sigma` (any order) is a simplex of the complex.
    fn holds(&self, sigma: &[u32]) -> bool {
        if sigma.iter().any(|&v| !self.alive[v as usize]) {
            return false;
        }
        sigma.len() == 1 || self.top_containing(sigma).is_some()
    }
}

impl Topology for LiveComplex {
    // `vertex_count` is the vertex slots (removed vertices included: they are not simplices;
    // `count(0)` is the number of live ones).
    crate::relation::topology_preamble! {
        self, StructureKind::IaStar;
        dimension: (1..=MAX_DIMENSION)
            .rev()
            .find(|&p| self.live_tops[p] > 0)
            .unwrap_or(0);
        vertex_count: self.vertex_slots();
        count(p): if p == 0 {
            self.live_vertices as usize
        } else if let Some(n) = self.counted(p) {
            n // O(1) while the dense table of this state is built
        } else {
            let mut out = Vec::new();
            self.simplices(p, &mut out);
            out.len() / (p + 1)
        };
        top_count(p): if p == 0 {
            self.vertices()
                .filter(|v| self.star[v.index()].is_empty())
                .count()
        } else {
            self.live_tops.get(p).copied().unwrap_or(0)
        };
        as_any;
    }

    fn simplices(&self, p: usize, out: &mut Vec<u32>) {
        if p == 0 {
            out.extend(self.vertices().map(|v| v.0));
            return;
        }
        let mut rows = Vec::new();
        for (_, s) in self.tops() {
            if s.len() > p {
                let k = Key::new(s);
                faces(k.as_slice(), &[], p, |f| rows.extend_from_slice(f));
            }
        }
        out.extend(crate::complex::sort_dedup_rows(p + 1, rows));
    }

    fn query(&self, sigma: &[u32], q: usize, out: &mut Vec<u32>) -> Result<(), QueryError> {
        if !self.holds(sigma) {
            return Err(QueryError::NotInComplex {
                simplex: sigma.to_vec(),
            });
        }
        let p = sigma.len() - 1;
        let mut rows = Vec::new();
        if q < p {
            faces(sigma, &[], q, |f| rows.extend_from_slice(f));
        } else if q > p {
            let v = self.smallest_star(sigma);
            for &raw in &self.star[v as usize] {
                let t = self.top_raw(raw);
                if t.len() > q && subset(sigma, t) {
                    faces(Key::new(t).as_slice(), sigma, q, |f| {
                        rows.extend_from_slice(f)
                    });
                }
            }
        } else if p == 0 {
            for &raw in &self.star[sigma[0] as usize] {
                rows.extend(self.top_raw(raw).iter().filter(|&&u| u != sigma[0]));
            }
        } else {
            self.adjacent(sigma, &mut rows);
        }
        out.extend(crate::complex::sort_dedup_rows(q + 1, rows));
        Ok(())
    }

    fn contains(&self, sigma: &[u32]) -> bool {
        self.holds(sigma)
    }

    fn storage(&self) -> Storage {
        let slots: usize = self.tops.iter().map(Vec::len).sum();
        let star_entries = self.star.entries();
        let bytes = 4 * self.tops.iter().map(Vec::capacity).sum::<usize>()
            + 24 * self.tops.capacity()
            + self.alive.capacity()
            + self.star.bytes();
        Storage {
            integers: (slots + star_entries) as u64,
            bits: self.alive.len() as u64,
            bytes: bytes as u64,
        }
    }

    fn validate(&self) -> Result<(), String> {
        self.check_invariants()
    }
}

impl LiveComplex {
    /// R_{p,p} for p > 0: every p-simplex sharing a facet with σ holds σ[0] or σ[1].
    fn adjacent(&self, sigma: &[u32], rows: &mut Vec<u32>) {
        let p = sigma.len() - 1;
        let mut face = [0u32; MAX_DIMENSION + 1];
        for &hub in &sigma[..2] {
            for &raw in &self.star[hub as usize] {
                let t = self.top_raw(raw);
                if t.len() < p + 1 {
                    continue;
                }
                for skip in 0..=p {
                    // The facet of σ without its `skip`-th vertex, if this top holds it.
                    let f: Vec<u32> = (0..=p).filter(|&i| i != skip).map(|i| sigma[i]).collect();
                    if !subset(&f, t) {
                        continue;
                    }
                    for &x in t {
                        if sigma.contains(&x) {
                            continue;
                        }
                        face[..p].copy_from_slice(&f);
                        face[p] = x;
                        face[..=p].sort_unstable();
                        rows.extend_from_slice(&face[..=p]);
                    }
                }
            }
        }
    }

    /// Every invariant: slots hold distinct live vertices; stars list exactly the live tops
    /// through each vertex, once; no top is a face of (or equal to) another; counts agree.
    fn check_invariants(&self) -> Result<(), String> {
        let n = self.vertex_slots() as usize;
        if self.star.len() != n || self.coords.len() != n * self.coord_dim {
            return Err("per-vertex arrays disagree on the vertex count".into());
        }
        self.data.check(n, &self.tops)?;
        let live = self.alive.iter().filter(|&&a| a).count();
        if live != self.live_vertices as usize || live == 0 {
            return Err(format!(
                "{live} live vertices, counted {}",
                self.live_vertices
            ));
        }
        let mut entries = 0usize;
        for p in 1..=MAX_DIMENSION {
            let mut count = 0;
            for (slot, s) in self.tops[p].chunks_exact(p + 1).enumerate() {
                if s[0] >= DEAD {
                    continue;
                }
                count += 1;
                entries += p + 1;
                self.check_top_slot(p, slot as u32, s)?;
            }
            if count != self.live_tops[p] {
                return Err(format!(
                    "{count} live top {p}-simplices, counted {}",
                    self.live_tops[p]
                ));
            }
        }
        for (v, st) in self.star.iter().enumerate() {
            if !self.alive[v] && !st.is_empty() {
                return Err(format!("removed vertex {v} has a non-empty star"));
            }
            for (i, &raw) in st.iter().enumerate() {
                if st[..i].contains(&raw) {
                    return Err(format!("star of {v} lists a top simplex twice"));
                }
            }
        }
        self.star.check()?;
        let listed = self.star.entries();
        if listed != entries {
            return Err(format!(
                "stars hold {listed} entries, the live tops have {entries} vertices"
            ));
        }
        Ok(())
    }

    fn check_top_slot(&self, p: usize, slot: u32, s: &[u32]) -> Result<(), String> {
        let raw = pack(p, slot);
        for (i, &v) in s.iter().enumerate() {
            if v as usize >= self.alive.len() || !self.alive[v as usize] {
                return Err(format!("top {p}-simplex {} uses dead vertex {v}", show(s)));
            }
            if s[..i].contains(&v) {
                return Err(format!("top {p}-simplex {} repeats {v}", show(s)));
            }
            if !self.star[v as usize].contains(&raw) {
                return Err(format!("star of {v} misses top {}", show(s)));
            }
        }
        for &other in &self.star[s[0] as usize] {
            if other != raw && subset(s, self.top_raw(other)) {
                return Err(format!(
                    "top {} is a face of top {}",
                    show(s),
                    show(self.top_raw(other))
                ));
            }
        }
        Ok(())
    }
}
