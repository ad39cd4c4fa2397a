//! `TpxDecomposition`: the IQM standard decomposition as plain arrays, for handing each
//! initial-quasi-manifold component to a manifold-only library.

use super::complex::TpxComplex;
use super::structure::build_failure;
use super::{Failure, TpxStatus, build_into, free_box, get_into, on, out_ptr};
use topoplex::structures::iqm::{Decomposition, Iqm};

/// The standard decomposition of a complex into initial quasi-manifold components (opaque).
/// Create with `tpx_decomposition_build`, release with `tpx_decomposition_free`. Immutable;
/// every array it hands out lives as long as the handle.
pub struct TpxDecomposition {
    dec: Decomposition,
}

/// Cuts the complex `c` into its IQM components (see `src/structures/iqm.rs` for the
/// definitions): each component is regular and an initial quasi-manifold, and vertices are
/// split into one copy per manifold-connected part of their star.
///
/// On success `*out` receives a new handle owned by the caller (free with
/// `tpx_decomposition_free`); it does not borrow `c`. Errors: NULL_ARGUMENT, TOO_LARGE.
/// Cost: O(S log S) for S = Σ (dim σ + 1) over top simplices σ, plus one count of the closure.
///
/// # Safety
/// Non-NULL pointers must be valid (a live complex; a writable handle pointer).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tpx_decomposition_build(
    c: *const TpxComplex,
    out: *mut *mut TpxDecomposition,
) -> TpxStatus {
    build_into(c, "c", out, |c| {
        let iqm = Iqm::build(&c.complex).map_err(build_failure)?;
        let dec = iqm.decomposition();
        Ok(TpxDecomposition { dec })
    })
}

/// Releases a decomposition. NULL is a no-op.
///
/// # Safety
/// `d` must be NULL or a live handle from this library, not used afterwards.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tpx_decomposition_free(d: *mut TpxDecomposition) {
    // SAFETY: the same contract, passed on.
    unsafe { free_box(d) }
}

/// Number of components into `*out`. Components are numbered by dimension, descending, then by
/// their first top simplex in lexicographic order. O(1).
///
/// # Safety
/// Non-NULL pointers must be valid.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tpx_decomposition_component_count(
    d: *const TpxDecomposition,
    out: *mut usize,
) -> TpxStatus {
    get_into(d, "d", out, |d| d.dec.components.len())
}

/// Component `index`: its dimension k, its top k-simplices as rows of k+1 *local* vertex ids
/// (`*tops_len` = number of uint32_t; each row in the vertex order of the top simplex's first
/// listing in the input, so its winding is kept), and `original_ids[local]`, the original vertex id of each
/// local vertex (`*original_len` = number of local vertices; two local vertices of one component
/// may share an original id where a vertex was split inside the component). Arrays belong to
/// the handle. Errors: NULL_ARGUMENT, DIMENSION_OUT_OF_RANGE when `index` is not below the
/// component count. O(1).
///
/// # Safety
/// Non-NULL pointers must be valid.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tpx_decomposition_component(
    d: *const TpxDecomposition,
    index: usize,
    dimension: *mut u32,
    tops: *mut *const u32,
    tops_len: *mut usize,
    original_ids: *mut *const u32,
    original_len: *mut usize,
) -> TpxStatus {
    on(d, "d", |d| {
        let (dimension, tops, tops_len) = (
            out_ptr(dimension, "dimension")?,
            out_ptr(tops, "tops")?,
            out_ptr(tops_len, "tops_len")?,
        );
        let (original_ids, original_len) = (
            out_ptr(original_ids, "original_ids")?,
            out_ptr(original_len, "original_len")?,
        );
        let piece = d.dec.components.get(index).ok_or_else(|| {
            Failure::new(
                TpxStatus::DimensionOutOfRange,
                format!(
                    "component {index} does not exist ({} components)",
                    d.dec.components.len()
                ),
            )
        })?;
        *dimension = piece.dimension as u32;
        *tops = piece.tops.as_ptr();
        *tops_len = piece.tops.len();
        *original_ids = piece.original.as_ptr();
        *original_len = piece.original.len();
        Ok(())
    })
}

/// The hypergraph of split vertices (vertices with two or more copies), ascending:
/// `vertices[a]` has copies `copies[offsets[a] .. offsets[a+1]]` (global copy ids; `offsets`
/// has `*vertices_len + 1` entries). A global copy id c is local id
/// `c − first global copy of its component`, and [`tpx_decomposition_copies`] maps it to its
/// vertex and component. Arrays belong to the handle. O(1).
///
/// # Safety
/// Non-NULL pointers must be valid.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tpx_decomposition_split_vertices(
    d: *const TpxDecomposition,
    vertices: *mut *const u32,
    vertices_len: *mut usize,
    offsets: *mut *const u32,
    copies: *mut *const u32,
    copies_len: *mut usize,
) -> TpxStatus {
    on(d, "d", |d| {
        let outs = (
            out_ptr(vertices, "vertices")?,
            out_ptr(vertices_len, "vertices_len")?,
            out_ptr(offsets, "offsets")?,
            out_ptr(copies, "copies")?,
            out_ptr(copies_len, "copies_len")?,
        );
        *outs.0 = d.dec.split_vertices.as_ptr();
        *outs.1 = d.dec.split_vertices.len();
        *outs.2 = d.dec.split_offsets.as_ptr();
        *outs.3 = d.dec.split_copies.as_ptr();
        *outs.4 = d.dec.split_copies.len();
        Ok(())
    })
}

/// Every vertex copy (global ids, numbered component after component): `copy_vertex[c]` is the
/// original vertex and `copy_component[c]` the component of copy c; `*len` = number of copies.
/// Arrays belong to the handle. O(1).
///
/// # Safety
/// Non-NULL pointers must be valid.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tpx_decomposition_copies(
    d: *const TpxDecomposition,
    copy_vertex: *mut *const u32,
    copy_component: *mut *const u32,
    len: *mut usize,
) -> TpxStatus {
    on(d, "d", |d| {
        let (cv, cc, len) = (
            out_ptr(copy_vertex, "copy_vertex")?,
            out_ptr(copy_component, "copy_component")?,
            out_ptr(len, "len")?,
        );
        *cv = d.dec.copy_vertex.as_ptr();
        *cc = d.dec.copy_component.as_ptr();
        *len = d.dec.copy_vertex.len();
        Ok(())
    })
}
