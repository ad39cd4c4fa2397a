//! `TpxLive` (the updatable complex, [`topoplex::live::LiveComplex`]) and `TpxUndo` (what a
//! contraction returns so that `tpx_live_split` can undo it).
//!
//! Unlike `TpxStructure`, a `TpxLive` is edited in place: edits take a non-const pointer and
//! need exclusive access (no other call on the same handle at the same time); queries take a
//! const pointer and may run concurrently with each other. Every refused edit leaves the complex
//! unchanged and says why (statuses 20..=25, plus INVALID_SIMPLEX, NOT_IN_COMPLEX,
//! INVALID_ARGUMENT for coordinates of the wrong length).

use super::complex::TpxComplex;
use super::structure::{TpxStructure, sort_rows_in_place};
use super::write_buffer;
use super::{
    Failure, TpxStatus, build_into, free_box, get_into, guard, handle, in_slice, on, out_ptr,
    set_boxed,
};
use topoplex::live::{ContractMode, LiveComplex, Refusal, UndoRecord, VertexId};
use topoplex::relation::{QueryError, Topology};

/// `tpx_live_contract` mode: only an edge satisfying the link condition (topology preserved).
pub const TPX_CONTRACT_PRESERVE_TOPOLOGY: u32 = 0;
/// `tpx_live_contract` mode: any two live vertices (vertex unification).
pub const TPX_CONTRACT_FREE: u32 = 1;
/// `tpx_live_contract` mode: the link condition on the complex coned over its boundary
/// (`tpx_live_link_condition_with_boundary`): also keeps 2- and 3-manifolds with boundary
/// manifolds.
pub const TPX_CONTRACT_PRESERVE_MANIFOLD: u32 = 2;

/// An updatable simplicial complex (opaque): any dimension, non-manifold, mixed-dimensional.
/// Create with `tpx_live_from_complex`, release with `tpx_live_free`.
pub struct TpxLive {
    /// The live complex as a structure, so that the handle functions (`tpx_locate`,
    /// `tpx_related_handles`, ...) take it through `tpx_live_structure`.
    view: TpxStructure,
}

impl TpxLive {
    pub(crate) fn new(live: LiveComplex) -> TpxLive {
        TpxLive {
            view: TpxStructure::new(Box::new(live)),
        }
    }

    pub(crate) fn live(&self) -> &LiveComplex {
        self.view
            .topo
            .as_any()
            .and_then(|a| a.downcast_ref())
            .expect("a TpxLive holds a LiveComplex")
    }

    pub(crate) fn live_mut(&mut self) -> &mut LiveComplex {
        self.view
            .topo
            .as_any_mut()
            .and_then(|a| a.downcast_mut())
            .expect("a TpxLive holds a LiveComplex")
    }
}

/// The undo record of one contraction (opaque), for `tpx_live_split`. Release with
/// `tpx_undo_free`; it does not borrow the live complex.
pub struct TpxUndo {
    undo: UndoRecord,
}

pub(crate) fn refusal(e: Refusal) -> Failure {
    let status = match &e {
        Refusal::InvalidSimplex { .. } => TpxStatus::InvalidSimplex,
        Refusal::UnknownVertex { .. } => TpxStatus::DeadVertex,
        Refusal::NotAnEdge { .. } => TpxStatus::NotAnEdge,
        Refusal::LinkCondition { .. } => TpxStatus::LinkConditionFails,
        Refusal::AlreadyPresent { .. } => TpxStatus::SimplexAlreadyPresent,
        Refusal::NotTop { .. } => TpxStatus::NotATopSimplex,
        Refusal::NotInComplex { .. } => TpxStatus::NotInComplex,
        Refusal::StaleHandle(_) => TpxStatus::StaleUndo,
        Refusal::CoordinateDimension { .. } => TpxStatus::InvalidArgument,
        Refusal::NonFiniteCoordinate { .. } => TpxStatus::InvalidArgument,
    };
    Failure::new(status, e.to_string())
}

fn live_mut<'a>(p: *mut TpxLive) -> Result<&'a mut LiveComplex, Failure> {
    Ok(out_ptr(p, "live")?.live_mut())
}

/// Builds a live complex from `c`: the same vertex ids, every top simplex with its input
/// winding, the coordinates copied. `*out` receives a new handle owned by the caller (free with
/// `tpx_live_free`); it does not borrow `c`. Errors: NULL_ARGUMENT; TOO_LARGE when the
/// memory for its arrays cannot be had. Cost: O(size of the top simplices).
///
/// # Safety
/// Non-NULL pointers must be valid.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tpx_live_from_complex(
    c: *const TpxComplex,
    out: *mut *mut TpxLive,
) -> TpxStatus {
    build_into(c, "c", out, |c| {
        let live =
            LiveComplex::try_from_complex(&c.complex).map_err(super::structure::build_failure)?;
        Ok(TpxLive::new(live))
    })
}

/// Releases a live complex. NULL is a no-op.
///
/// # Safety
/// `l` must be NULL or a live handle from this library, not used afterwards.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tpx_live_free(l: *mut TpxLive) {
    // SAFETY: the same contract, passed on.
    unsafe { free_box(l) }
}

/// Releases an undo record. NULL is a no-op.
///
/// # Safety
/// `u` must be NULL or a handle from `tpx_live_contract`, not used afterwards.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tpx_undo_free(u: *mut TpxUndo) {
    // SAFETY: the same contract, passed on.
    unsafe { free_box(u) }
}

/// Number of vertex slots into `*out`: vertex ids are `0 .. slots`, some of them removed
/// (contracted away or deleted) until `tpx_live_compact`. O(1).
///
/// # Safety
/// Non-NULL pointers must be valid.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tpx_live_vertex_slots(l: *const TpxLive, out: *mut u32) -> TpxStatus {
    get_into(l, "l", out, |l| l.live().vertex_slots())
}

/// Number of live vertices into `*out`. O(1).
///
/// # Safety
/// Non-NULL pointers must be valid.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tpx_live_vertex_count(l: *const TpxLive, out: *mut u32) -> TpxStatus {
    get_into(l, "l", out, |l| l.live().live_vertex_count())
}

/// Whether vertex `v` is live (1) or removed / out of range (0), into `*out`. O(1).
///
/// # Safety
/// Non-NULL pointers must be valid.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tpx_live_is_vertex(l: *const TpxLive, v: u32, out: *mut u32) -> TpxStatus {
    get_into(l, "l", out, |l| l.live().is_live(VertexId(v)) as u32)
}

/// Dimension of the complex (highest live top simplex) into `*out`. O(d).
///
/// # Safety
/// Non-NULL pointers must be valid.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tpx_live_dimension(l: *const TpxLive, out: *mut u32) -> TpxStatus {
    get_into(l, "l", out, |l| l.live().dimension() as u32)
}

/// Number of live top p-simplices into `*out` (p = 0: isolated vertices). O(1) for p ≥ 1,
/// O(vertices) for p = 0.
///
/// # Safety
/// Non-NULL pointers must be valid.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tpx_live_top_count(
    l: *const TpxLive,
    p: u32,
    out: *mut usize,
) -> TpxStatus {
    get_into(l, "l", out, |l| l.live().top_count(p as usize))
}

/// The live top p-simplices (p ≥ 1) as rows of p+1 vertex ids in their stored order (input
/// winding, b replaced by a in place after contractions), in slot order, into `buf`;
/// `*out_len` receives the number of uint32_t. Errors: NULL_ARGUMENT, BUFFER_TOO_SMALL (nothing
/// copied, `*out_len` = needed length). Cost: O(slots of dimension p).
///
/// # Safety
/// Non-NULL pointers must be valid; `buf` must have room for `buf_len` uint32_t.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tpx_live_top_simplices(
    l: *const TpxLive,
    p: u32,
    buf: *mut u32,
    buf_len: usize,
    out_len: *mut usize,
) -> TpxStatus {
    on(l, "l", |l| {
        let out_len = out_ptr(out_len, "out_len")?;
        let rows: Vec<u32> = l
            .live()
            .tops()
            .filter(|(t, _)| t.dim() == p as usize)
            .flat_map(|(_, s)| s.iter().copied())
            .collect();
        write_buffer(&rows, buf, buf_len, out_len)
    })
}

/// R_{p,q}(σ) for σ given by vertex ids in any order (p = simplex_len − 1), as rows of q+1
/// ascending ids in ascending lexicographic order, into `buf`; `*out_len` receives the number
/// of uint32_t. Errors: NULL_ARGUMENT, INVALID_SIMPLEX, NOT_IN_COMPLEX (also for a removed
/// vertex), DIMENSION_OUT_OF_RANGE, BUFFER_TOO_SMALL. Cost: module doc of `live` (linear in the
/// stars of σ's vertices).
///
/// # Safety
/// Non-NULL pointers must be valid; `simplex` has `simplex_len` ids, `buf` room for `buf_len`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tpx_live_relation(
    l: *const TpxLive,
    simplex: *const u32,
    simplex_len: usize,
    q: u32,
    buf: *mut u32,
    buf_len: usize,
    out_len: *mut usize,
) -> TpxStatus {
    on(l, "l", |l| {
        let out_len = out_ptr(out_len, "out_len")?;
        let sigma = in_slice(simplex, simplex_len, "simplex")?;
        let mut rows = Vec::new();
        l.live()
            .relation(sigma, q as usize, &mut rows)
            .map_err(|e| {
                let status = match &e {
                    QueryError::NotInComplex { .. } => TpxStatus::NotInComplex,
                    QueryError::DimensionOutOfRange { .. } => TpxStatus::DimensionOutOfRange,
                    _ => TpxStatus::InvalidSimplex,
                };
                Failure::new(status, e.to_string())
            })?;
        sort_rows_in_place(&mut rows, q as usize + 1);
        write_buffer(&rows, buf, buf_len, out_len)
    })
}

/// The coordinates of live vertex `v` (`tpx_live_coord_dim` doubles) into `buf`; `*out_len`
/// receives their number. Errors: NULL_ARGUMENT, DEAD_VERTEX, BUFFER_TOO_SMALL. O(1).
///
/// # Safety
/// Non-NULL pointers must be valid; `buf` must have room for `buf_len` doubles.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tpx_live_coords(
    l: *const TpxLive,
    v: u32,
    buf: *mut f64,
    buf_len: usize,
    out_len: *mut usize,
) -> TpxStatus {
    on(l, "l", |l| {
        let out_len = out_ptr(out_len, "out_len")?;
        let xyz = l.live().coords(VertexId(v)).map_err(refusal)?;
        write_buffer(xyz, buf, buf_len, out_len)
    })
}

/// Coordinates per vertex into `*out` (0 when the complex has none). O(1).
///
/// # Safety
/// Non-NULL pointers must be valid.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tpx_live_coord_dim(l: *const TpxLive, out: *mut usize) -> TpxStatus {
    get_into(l, "l", out, |l| l.live().coord_dim())
}

/// Sets the coordinates of live vertex `v` from `xyz[0 .. len]` (`len` must be the coordinate
/// dimension). Not an edit of the topology: handles, dense indices and lent views stay valid;
/// a later `tpx_live_split` puts back the coordinates its contraction's a and b had. Errors:
/// NULL_ARGUMENT, DEAD_VERTEX, INVALID_ARGUMENT (wrong length, a NaN or infinite number);
/// on error nothing changes. O(1).
///
/// # Safety
/// Non-NULL pointers must be valid; `xyz` has `len` doubles.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tpx_live_set_coords(
    l: *mut TpxLive,
    v: u32,
    xyz: *const f64,
    len: usize,
) -> TpxStatus {
    guard(|| {
        let live = live_mut(l)?;
        let xyz = in_slice(xyz, len, "xyz")?;
        live.set_coords(VertexId(v), xyz).map_err(refusal)
    })
}

/// Sets the coordinates of every vertex slot at once from `data[0 .. len]`, slot after slot
/// (`len` = `tpx_live_vertex_slots` × `tpx_live_coord_dim`; the numbers of removed vertices are
/// stored and never read). Not an edit of the topology: handles, dense indices and lent views
/// stay valid. Errors: NULL_ARGUMENT (`data` may be NULL only when `len` is 0),
/// INVALID_ARGUMENT (wrong length, or a NaN or infinite number: the message names its vertex
/// and coordinate); on error nothing changes. Needs exclusive access. Cost: O(len), no
/// allocation (the array is overwritten in place, so a pointer from `tpx_live_all_coords`
/// stays valid and reads the new numbers).
///
/// # Safety
/// Non-NULL pointers must be valid; `data` has `len` doubles.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tpx_live_set_all_coords(
    l: *mut TpxLive,
    data: *const f64,
    len: usize,
) -> TpxStatus {
    guard(|| {
        let live = live_mut(l)?;
        let data = in_slice(data, len, "data")?;
        live.set_all_coords(data).map_err(refusal)
    })
}

/// Lends the coordinates of every vertex slot, slot after slot (`tpx_live_coord_dim` doubles
/// each; a removed vertex's are meaningless): `*out` points into the live complex's own array,
/// `*out_len` = slots × coord_dim. Valid until the next edit that adds or drops vertex slots
/// (`tpx_live_add_vertex`, `tpx_live_compact`) or `tpx_live_free`; setting coordinates writes
/// through it in place. Errors: NULL_ARGUMENT; outputs written only on success. O(1).
///
/// # Safety
/// Non-NULL pointers must be valid.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tpx_live_all_coords(
    l: *const TpxLive,
    out: *mut *const f64,
    out_len: *mut usize,
) -> TpxStatus {
    on(l, "l", |l| {
        let out = out_ptr(out, "out")?;
        let out_len = out_ptr(out_len, "out_len")?;
        let all = l.live().all_coords();
        *out = all.as_ptr();
        *out_len = all.len();
        Ok(())
    })
}

/// Lends top simplex `top` (a top id of `tpx_live_structure`'s numbering, as `tpx_top` and
/// `tpx_top_id` use: dimension in the top 4 bits, slot below) with its vertices in stored
/// order — the input winding, b replaced by a in place after contractions — without a copy:
/// `*out` points into the live complex's top table, `*out_len` = p + 1 ids, valid until the
/// next edit (insert, remove, contract, split, add vertex, compact) or `tpx_live_free`. For a
/// whole-mesh pass in winding order (writing faces, per-face normals) with no call per vertex
/// and no buffer. Errors: NULL_ARGUMENT, INVALID_HANDLE (no live top in that slot, or an
/// isolated vertex, which has no stored row: it is its own id); outputs written only on
/// success. O(1).
///
/// # Safety
/// Non-NULL pointers must be valid.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tpx_live_top_vertices(
    l: *const TpxLive,
    top: u32,
    out: *mut *const u32,
    out_len: *mut usize,
) -> TpxStatus {
    on(l, "l", |l| {
        let out = out_ptr(out, "out")?;
        let out_len = out_ptr(out_len, "out_len")?;
        let row = l
            .live()
            .top_as_given_slice(topoplex::relation::handle::TopId(top))
            .map_err(super::structure::query_failure)?;
        *out = row.as_ptr();
        *out_len = row.len();
        Ok(())
    })
}

/// The live complex's own arrays, lent (see `tpx_live_arrays`). Every pointer points into the
/// live complex and is valid until its next edit of the topology (insert, remove, contract,
/// split, add vertex, compact) or `tpx_live_free`; setting coordinates writes in place and
/// keeps every pointer valid. An empty array may be a dangling non-NULL pointer with length 0.
///
/// Layout (the C++ `topoplex::MeshView` walks it inline):
/// - a top p-simplex (p ≥ 1) is named by its packed id `p << 28 | slot` (`tpx_live_top_vertices`'
///   argument); `tops[p]` holds p + 1 vertex ids per slot in stored order (the input winding),
///   `top_lens[p]` ids in all; a removed slot (tombstone) has bit 31 set on its first id and is
///   in no star. `tops[0]` is empty.
/// - vertex slot v's star, the packed ids of the live tops of dimension ≥ 1 through v, in no
///   particular order (an edit may reorder it), is
///   `star_words[star_blocks[3v] .. star_blocks[3v] + star_blocks[3v + 1]]`
///   (`star_blocks[3v + 2]` is the block's capacity).
/// - `alive[v]` (v < `vertex_slots`): the slot holds a vertex; a live vertex with an empty star
///   is an isolated vertex. Its coordinates are `coords[v * coord_dim ..][.. coord_dim]`.
#[repr(C)]
#[derive(Debug, Clone, Copy)]
pub struct TpxLiveArrays {
    /// Per dimension 0..=15: the top table (see above).
    pub tops: [*const u32; 16],
    /// Per dimension: ids in `tops[p]` (slots × (p + 1)).
    pub top_lens: [usize; 16],
    /// The star arena.
    pub star_words: *const u32,
    /// Words in `star_words`.
    pub star_words_len: usize,
    /// 3 words per vertex slot: start, length, capacity of its star.
    pub star_blocks: *const u32,
    /// Per vertex slot: 1 when it holds a live vertex.
    pub alive: *const bool,
    /// Vertex slots (live or not).
    pub vertex_slots: u32,
    /// The compaction count (the handles' generation).
    pub generation: u32,
    /// `vertex_slots * coord_dim` numbers.
    pub coords: *const f64,
    /// Numbers per vertex (0 when the complex has no coordinates).
    pub coord_dim: usize,
}

/// Lends the live complex's arrays into `*out` (a caller-owned struct filled in; nothing is
/// allocated or copied): the top tables, the vertex stars, the live flags and the coordinates,
/// valid until the next edit (see `TpxLiveArrays`). With them a caller walks the complex with
/// no call per query: a vertex's tops, a top's vertices in winding, the tops through a simplex
/// (filter the smallest star of its vertices), the one-ring (the other vertices of a star).
/// Errors: NULL_ARGUMENT; `*out` written only on success. O(1).
///
/// # Safety
/// Non-NULL pointers must be valid.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tpx_live_arrays(l: *const TpxLive, out: *mut TpxLiveArrays) -> TpxStatus {
    on(l, "l", |l| {
        let out = out_ptr(out, "out")?;
        let a = l.live().arrays();
        *out = TpxLiveArrays {
            tops: std::array::from_fn(|p| a.tops[p].as_ptr()),
            top_lens: std::array::from_fn(|p| a.tops[p].len()),
            star_words: a.star_words.as_ptr(),
            star_words_len: a.star_words.len(),
            star_blocks: a.star_blocks.as_ptr(),
            alive: a.alive.as_ptr(),
            vertex_slots: a.alive.len() as u32,
            generation: a.generation,
            coords: a.coords.as_ptr(),
            coord_dim: a.coord_dim,
        };
        Ok(())
    })
}

/// `TpxLiveAdjacency` entry: no other top of the same dimension across this facet.
pub const TPX_ACROSS_NONE: u32 = u32::MAX;
/// `TpxLiveAdjacency` entry: two or more tops of the same dimension across this facet (a
/// non-manifold facet): scan a star of the facet for them.
pub const TPX_ACROSS_MANY: u32 = u32::MAX - 1;

/// The tops across each facet, lent (see `tpx_live_adjacency`). For the live top of dimension p
/// in slot s (packed id `p << 28 | s`) and i ≤ p, `across[p][s * (p + 1) + i]` says what lies
/// across its facet opposite its i-th stored vertex (`TpxLiveArrays::tops[p][s * (p + 1) + i]`),
/// among the live tops of dimension p: `TPX_ACROSS_NONE` (a boundary facet, or one only tops of
/// other dimensions share), the packed id of the one other top, or `TPX_ACROSS_MANY`. Entries of
/// a tombstoned slot are `TPX_ACROSS_NONE`. Valid as `TpxLiveArrays` is: until the next edit of
/// the topology (setting coordinates keeps it).
#[repr(C)]
#[derive(Debug, Clone, Copy)]
pub struct TpxLiveAdjacency {
    /// Per dimension 0..=15: `p + 1` entries per slot of the top table (`tops[0]`: empty).
    pub across: [*const u32; 16],
    /// Per dimension: entries in `across[p]` (the same as `TpxLiveArrays::top_lens[p]`).
    pub across_lens: [usize; 16],
    /// Heap bytes of the index (4 per vertex of every top slot).
    pub bytes: u64,
}

/// Lends the tops across each facet of every top into `*out` (a caller-owned struct filled in):
/// an index built on the first call after an edit, kept with the live complex until its next
/// edit of the topology (or repaired by each edit after `tpx_live_keep_adjacency`), so that FF (faces across a triangle's edges), TT (tetrahedra across a
/// tetrahedron's triangles) and the same in any dimension are one read each (see
/// `TpxLiveAdjacency`; C++ `topoplex::MeshView` uses it when given). Errors: NULL_ARGUMENT,
/// TOO_LARGE (its memory cannot be had); `*out` written only on success. Cost: the first call
/// after an edit O(Σ_t d²·k) over every top t (k the smallest star of a facet's vertices) on
/// the library's threads, 4 bytes per vertex of every top slot; later calls O(1).
/// Not to be called while another thread edits the live complex.
///
/// # Safety
/// Non-NULL pointers must be valid.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tpx_live_adjacency(
    l: *const TpxLive,
    out: *mut TpxLiveAdjacency,
) -> TpxStatus {
    on(l, "l", |l| {
        let out = out_ptr(out, "out")?;
        let a = l
            .live()
            .adjacency()
            .map_err(crate::structure::build_failure)?;
        *out = TpxLiveAdjacency {
            across: std::array::from_fn(|p| a.rows[p].as_ptr()),
            across_lens: std::array::from_fn(|p| a.rows[p].len()),
            bytes: a.bytes,
        };
        Ok(())
    })
}

/// Keeps the facet adjacency across edits (`keep` ≠ 0: built now if it is not, then repaired
/// by every insert, removal, contraction and split, rebuilt by `tpx_live_compact`), or goes back
/// to building it on request and dropping it at each edit (`keep` = 0). Kept,
/// `tpx_live_adjacency` is O(1) after any edit (its pointers still change with the edit: take
/// it again); each edit costs more, O(Σ_t d²·k) over the tops t in the stars of the vertices it
/// touches (for a contraction of ab, the vertices of St(a) ∪ St(b)). 4 bytes per vertex of every
/// top slot. Errors: NULL_ARGUMENT, TOO_LARGE (nothing kept). Cost: the first call the index's
/// build, as `tpx_live_adjacency`.
///
/// # Safety
/// Non-NULL pointers must be valid.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tpx_live_keep_adjacency(l: *mut TpxLive, keep: u32) -> TpxStatus {
    guard(|| {
        let live = live_mut(l)?;
        live.keep_adjacency(keep != 0)
            .map_err(crate::structure::build_failure)
    })
}

/// Every vertex's one-ring, lent (see `tpx_live_rings`): for vertex slot v,
/// `neighbours[offsets[v] .. offsets[v + 1]]` are the vertices sharing an edge with v, each once,
/// in the order v's star first names them (C++ `MeshView::for_each_neighbour`'s order; an empty
/// row for a removed or isolated vertex), and `held[i]` the number of live tops (dimension ≥ 1)
/// holding the edge from v to `neighbours[i]`. Valid as `TpxLiveArrays` is: until the next edit
/// of the topology (setting coordinates keeps it).
#[repr(C)]
#[derive(Debug, Clone, Copy)]
pub struct TpxLiveRings {
    /// `vertex_slots + 1` offsets into `neighbours` and `held`.
    pub offsets: *const u32,
    /// The rows, one after another (`entries` ids).
    pub neighbours: *const u32,
    /// Per entry of `neighbours`, the live tops holding that edge (`entries` counts).
    pub held: *const u32,
    /// Vertex slots covered (`TpxLiveArrays::vertex_slots`).
    pub vertex_slots: u32,
    /// Bit p set when the complex has a live top of dimension p (p ≥ 1): with only bit 2 set
    /// (every top a triangle), `held` counts an edge's triangles (1 on the boundary, more than 2
    /// at a non-manifold edge).
    pub top_dims: u32,
    /// Entries in `neighbours` and in `held` (twice the edges).
    pub entries: usize,
    /// Heap bytes of the index (4 per vertex slot + 8 per entry).
    pub bytes: u64,
}

/// Lends every vertex's one-ring with the number of tops at each of its edges into `*out` (a
/// caller-owned struct filled in): an index built on the first call after an edit and kept
/// with the live complex until its next edit of the topology (setting coordinates keeps it), so
/// that passes repeated over every vertex's neighbours (smoothing rounds, valences, boundary and
/// non-manifold edge counts) read one row per vertex rather than deduplicating its star's
/// vertices each time (see `TpxLiveRings`; C++ `topoplex::MeshView` uses it when given). Errors:
/// NULL_ARGUMENT, TOO_LARGE (its memory cannot be had, or 2^32 entries or more); `*out` written
/// only on success. Cost: the first call after an edit O(Σ_v d·k_v) on one thread, 4 bytes per
/// vertex slot and 8 per entry (about 52 bytes a vertex of a closed triangle mesh); later calls
/// O(1). Not to be called while another thread edits the live complex.
///
/// # Safety
/// Non-NULL pointers must be valid.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tpx_live_rings(l: *const TpxLive, out: *mut TpxLiveRings) -> TpxStatus {
    on(l, "l", |l| {
        let out = out_ptr(out, "out")?;
        let r = l.live().rings().map_err(crate::structure::build_failure)?;
        *out = TpxLiveRings {
            offsets: r.offsets.as_ptr(),
            neighbours: r.neighbours.as_ptr(),
            held: r.held.as_ptr(),
            vertex_slots: (r.offsets.len() - 1) as u32,
            top_dims: u32::from(r.top_dims),
            entries: r.neighbours.len(),
            bytes: r.bytes,
        };
        Ok(())
    })
}

/// Adds an isolated vertex at `xyz[0 .. len]`; its id into `*out`. Errors: NULL_ARGUMENT,
/// INVALID_ARGUMENT (wrong length, a NaN or infinite number). Amortised O(1).
///
/// # Safety
/// Non-NULL pointers must be valid; `xyz` has `len` doubles.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tpx_live_add_vertex(
    l: *mut TpxLive,
    xyz: *const f64,
    len: usize,
    out: *mut u32,
) -> TpxStatus {
    guard(|| {
        let live = live_mut(l)?;
        let xyz = in_slice(xyz, len, "xyz")?;
        let out = out_ptr(out, "out")?;
        *out = live.add_vertex(xyz).map_err(refusal)?.0;
        Ok(())
    })
}

/// Inserts the simplex `ids[0 .. len]` (its vertex order is kept as its winding) as a top
/// simplex; top simplices it contains become its faces. Errors: NULL_ARGUMENT, INVALID_SIMPLEX
/// (empty, repeated vertex, more than 16), DEAD_VERTEX, SIMPLEX_ALREADY_PRESENT (also for a
/// single vertex: add vertices with `tpx_live_add_vertex`). Cost: O(d² Σ_{v∈σ} |St(v)|).
///
/// # Safety
/// Non-NULL pointers must be valid; `ids` has `len` ids.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tpx_live_insert_top(
    l: *mut TpxLive,
    ids: *const u32,
    len: usize,
) -> TpxStatus {
    guard(|| {
        let live = live_mut(l)?;
        let ids = in_slice(ids, len, "ids")?;
        live.insert_top(ids).map(|_| ()).map_err(refusal)
    })
}

/// Removes the top simplex `ids[0 .. len]` (any order). Its faces that no other top simplex
/// holds go too, except its vertices, which stay (isolated if nothing else holds them); a
/// single isolated vertex is removed itself. Errors: NULL_ARGUMENT, INVALID_SIMPLEX,
/// DEAD_VERTEX, NOT_IN_COMPLEX, NOT_A_TOP_SIMPLEX. Cost: O(Σ_{v∈σ} |St(v)|).
///
/// # Safety
/// Non-NULL pointers must be valid; `ids` has `len` ids.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tpx_live_remove_top(
    l: *mut TpxLive,
    ids: *const u32,
    len: usize,
) -> TpxStatus {
    guard(|| {
        let live = live_mut(l)?;
        let ids = in_slice(ids, len, "ids")?;
        live.remove_top(ids).map_err(refusal)
    })
}

/// Checks the link condition for edge {a, b} without changing anything: OK, NOT_AN_EDGE, or
/// LINK_CONDITION_FAILS (message: the dimension and an offending link simplex); DEAD_VERTEX.
/// Cost: O(d (|St(a)| + |St(b)|)) on meshes.
///
/// # Safety
/// Non-NULL pointers must be valid.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tpx_live_link_condition(l: *const TpxLive, a: u32, b: u32) -> TpxStatus {
    link_test(l, a, b, LiveComplex::link_condition)
}

/// The link condition on the complex coned over its boundary by a dummy vertex ω (Dey,
/// Edelsbrunner, Guha, Nekhayev 1999): a boundary facet is a simplex that is a facet of exactly
/// one simplex. OK, NOT_AN_EDGE or LINK_CONDITION_FAILS (message: dimension and simplex, ω
/// written as 4294967294); DEAD_VERTEX. Cost: O(d² (|St(a)|² + |St(b)|²)).
///
/// # Safety
/// Non-NULL pointers must be valid.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tpx_live_link_condition_with_boundary(
    l: *const TpxLive,
    a: u32,
    b: u32,
) -> TpxStatus {
    link_test(l, a, b, LiveComplex::link_condition_with_boundary)
}

/// The one body of `tpx_live_link_condition` and `tpx_live_link_condition_with_boundary`.
fn link_test(
    l: *const TpxLive,
    a: u32,
    b: u32,
    test: impl FnOnce(&LiveComplex, VertexId, VertexId) -> Result<(), Refusal>,
) -> TpxStatus {
    guard(|| test(handle(l, "l")?.live(), VertexId(a), VertexId(b)).map_err(refusal))
}

/// Contracts b into a (`mode`: `TPX_CONTRACT_PRESERVE_TOPOLOGY`, `TPX_CONTRACT_FREE` or
/// `TPX_CONTRACT_PRESERVE_MANIFOLD`), moving
/// a to `position[0 .. position_len]` when `position` is not NULL. When `out_undo` is not NULL
/// it receives a new undo record (owned by the caller, free with `tpx_undo_free`) for
/// `tpx_live_split`. Errors: NULL_ARGUMENT, INVALID_ARGUMENT (unknown mode, wrong coordinate
/// count), INVALID_SIMPLEX (a == b), DEAD_VERTEX, and in topology-preserving mode NOT_AN_EDGE
/// or LINK_CONDITION_FAILS. Refused contractions change nothing. Cost: O(d (|St(a)| + |St(b)|))
/// per top simplex of St(b) on meshes.
///
/// # Safety
/// Non-NULL pointers must be valid; `position` has `position_len` doubles.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tpx_live_contract(
    l: *mut TpxLive,
    a: u32,
    b: u32,
    mode: u32,
    position: *const f64,
    position_len: usize,
    out_undo: *mut *mut TpxUndo,
) -> TpxStatus {
    guard(|| {
        let live = live_mut(l)?;
        let mode = match mode {
            TPX_CONTRACT_PRESERVE_TOPOLOGY => ContractMode::PreserveTopology,
            TPX_CONTRACT_FREE => ContractMode::Free,
            TPX_CONTRACT_PRESERVE_MANIFOLD => ContractMode::PreserveManifold,
            m => {
                return Err(Failure::new(
                    TpxStatus::InvalidArgument,
                    format!("unknown contraction mode {m} (TPX_CONTRACT_*)"),
                ));
            }
        };
        let position = if position.is_null() {
            None
        } else {
            Some(in_slice(position, position_len, "position")?)
        };
        let undo = live
            .contract(VertexId(a), VertexId(b), mode, position)
            .map_err(refusal)?;
        // SAFETY: a non-NULL `out_undo` is valid for writes (documented contract).
        if let Some(out_undo) = unsafe { out_undo.as_mut() } {
            set_boxed(out_undo, TpxUndo { undo });
        }
        Ok(())
    })
}

/// Undoes the contraction that produced `u` (vertex split): same ids, slots, winding and
/// coordinates as before it. `u` stays owned by the caller. Errors: NULL_ARGUMENT, STALE_UNDO
/// (from before `tpx_live_compact`, applied already, or later edits changed what it restores).
/// Cost: that of the contraction.
///
/// # Safety
/// Non-NULL pointers must be valid.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tpx_live_split(l: *mut TpxLive, u: *const TpxUndo) -> TpxStatus {
    on(u, "u", |u| {
        let live = live_mut(l)?;
        live.split(&u.undo).map_err(refusal)
    })
}

/// Drops removed vertices and top slots, renumbering the live ones densely in ascending order.
/// When `vertex_map` is not NULL it receives, for each old vertex id, its new id (`UINT32_MAX`
/// for a removed vertex): `*out_len` = old `tpx_live_vertex_slots`; with a buffer too short
/// nothing is compacted (BUFFER_TOO_SMALL, `*out_len` = needed length). Undo records issued
/// before are refused afterwards (STALE_UNDO), and so are handles (`TpxSimplex`) made before
/// (STALE_GENERATION: the complex takes a new owner stamp and keeps the old ones, 4 bytes per
/// compaction). Cost: O(size).
///
/// # Safety
/// Non-NULL pointers must be valid; `vertex_map` has room for `map_len` uint32_t.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tpx_live_compact(
    l: *mut TpxLive,
    vertex_map: *mut u32,
    map_len: usize,
    out_len: *mut usize,
) -> TpxStatus {
    guard(|| {
        let l = out_ptr(l, "l")?;
        let slots = l.live().vertex_slots() as usize;
        if !vertex_map.is_null() && map_len < slots {
            let out_len = out_ptr(out_len, "out_len")?;
            *out_len = slots;
            return Err(Failure::new(
                TpxStatus::BufferTooSmall,
                format!("vertex_map holds {map_len} uint32_t, the map needs {slots}"),
            ));
        }
        let maps = l.live_mut().compact();
        // Handles carry the stamp: a new one makes every older handle STALE_GENERATION.
        let old = std::mem::replace(&mut l.view.stamp, super::handles::new_stamp());
        l.view.retired.push(old);
        if !vertex_map.is_null() {
            let out_len = out_ptr(out_len, "out_len")?;
            write_buffer(&maps.vertices, vertex_map, map_len, out_len)?;
        }
        Ok(())
    })
}

/// The live complex as a new `TpxComplex` (live vertices renumbered densely in ascending order,
/// as `tpx_live_compact` would; windings and coordinates kept), owned by the caller: freeze it
/// into any structure with `tpx_structure_build`. Errors: NULL_ARGUMENT. Cost: O(size).
///
/// # Safety
/// Non-NULL pointers must be valid.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tpx_live_to_complex(
    l: *const TpxLive,
    out: *mut *mut TpxComplex,
) -> TpxStatus {
    build_into(l, "l", out, |l| {
        let complex = l.live().to_complex();
        Ok(TpxComplex { complex })
    })
}

/// Checks every invariant of the live complex: OK, or PANIC with the broken invariant in the
/// message (a library bug). Cost: O(d² Σ_v |St(v)|²) — for tests.
///
/// # Safety
/// Non-NULL pointers must be valid.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tpx_live_validate(l: *const TpxLive) -> TpxStatus {
    on(l, "l", |l| {
        l.live()
            .validate()
            .map_err(|e| Failure::new(TpxStatus::Panic, format!("invalid live complex: {e}")))
    })
}

/// The live complex as a structure, into `*out`: borrowed (valid until `tpx_live_free`; never
/// pass it to `tpx_structure_free`), so that the handle functions navigate it exactly as a built
/// structure — `tpx_locate`, `tpx_simplex_vertices`, `tpx_related_handles`, `tpx_degree`,
/// `tpx_star`, `tpx_simplex_test`, `tpx_cyclic_handles`, `tpx_top`, `tpx_top_id`,
/// `tpx_top_as_given`, and the vertex-id functions (`tpx_relation`, `tpx_structure_count`, ...).
/// The index functions too: `tpx_handle(p, i)`, `tpx_related`, `tpx_related_batch`,
/// `tpx_degree_batch`, `tpx_cyclic`, `tpx_relation_view`.
///
/// Why a lent structure rather than a second family of functions: one set of navigation
/// functions (and one C++ class) serves every kind, so code written for a built structure runs
/// on the editable one unchanged; the view costs nothing (it is the live complex behind the
/// relation API) and is the same object across edits, so a `const TpxStructure *` taken once
/// stays usable. `tpx_structure_build(c, TPX_KIND_IASTAR, ..)` gives the same navigation on a
/// live complex nobody edits.
///
/// Across edits: handles (`TpxSimplex` from `tpx_locate`, `tpx_handle`, the `_handles`
/// functions) name their simplex while it exists — STALE_HANDLE once it is gone, and
/// STALE_GENERATION for any handle after `tpx_live_compact`. A vertex's index is its id, stable
/// until `tpx_live_compact`. Indices above vertices are lexicographic ranks of the moment: every
/// edit (not a coordinate change) renumbers them and drops lent views, so use them, and
/// handles `{i, q, owner}` made from them, only until the next edit. Top ids are not dense:
/// dimension in the top 4 bits, slot below (an isolated vertex v: `v`). Not to be used while
/// another thread edits the live complex. O(1).
///
/// # Safety
/// Non-NULL pointers must be valid.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tpx_live_structure(
    l: *const TpxLive,
    out: *mut *const TpxStructure,
) -> TpxStatus {
    on(l, "l", |l| {
        let out = out_ptr(out, "out")?;
        *out = &l.view;
        Ok(())
    })
}
