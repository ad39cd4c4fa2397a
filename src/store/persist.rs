//! The complex's sections, and dispatch of a structure's sections by kind.

use std::any::Any;
use std::path::PathBuf;

use super::{Persist, Reader, StoreError, Writer, coords_of};
use crate::complex::Complex;
use crate::io::Coords;
use crate::relation::{StructureKind, Topology};
use crate::structures::{de, ia, ig, iqm, le, nmia, pe, sig, ts};

/// Vertex count, coordinates, the listing as given (ids and offsets) and the source path: all
/// the complex model needs to rebuild the same complex.
pub(super) fn save_complex(c: &Complex, w: &mut Writer) {
    w.scalar(c.vertex_count() as u64);
    let (dim, data) = coords_of(c);
    w.scalar(dim);
    w.section(data);
    let (ids, count, offset) = c.listing_arrays();
    w.u32s(ids);
    w.usizes_from(count + 1, (0..=count).map(offset));
    let source = c.source().map(|p| p.to_string_lossy().into_owned());
    w.u8s(source.unwrap_or_default().as_bytes());
}

pub(super) fn load_complex(r: &mut Reader) -> Result<Complex, StoreError> {
    let n = r.u32("vertex count")?;
    let dim = r.bounded(64, "coordinate dimension")? as usize;
    let data = r.arr::<f64>()?;
    if data.len() as u64 != dim as u64 * n as u64 {
        return Err(r.corrupt(format!(
            "{} coordinates for {n} vertices of dimension {dim}",
            data.len()
        )));
    }
    let ids = r.u32s()?;
    let offsets = r.usizes()?;
    // from_arrays slices by these offsets: they must run from 0 to the ids' end, ascending.
    let monotone = offsets.windows(2).all(|w| w[0] <= w[1]);
    if offsets.first() != Some(&0) || offsets.last() != Some(&ids.len()) || !monotone {
        return Err(r.corrupt("listing offsets are not ascending from 0 to the ids' length"));
    }
    let source = r.u8s()?;
    let source =
        (!source.is_empty()).then(|| PathBuf::from(String::from_utf8_lossy(&source).into_owned()));
    let coords = match dim {
        0 => None,
        _ => Some(Coords {
            dim,
            data: r.copy(&data)?,
        }),
    };
    let mut c =
        Complex::from_arrays(n, &ids, &offsets, coords).map_err(|source| StoreError::Complex {
            path: r.saved.path.clone(),
            source,
        })?;
    c.set_source(source);
    Ok(c)
}

/// Appends the structure's sections (its concrete type found by downcasting).
pub(super) fn save_structure(s: &dyn Topology, w: &mut Writer) {
    let any: &dyn Any = s;
    fn go<T: Persist + 'static>(any: &dyn Any, w: &mut Writer) -> bool {
        any.downcast_ref::<T>().map(|t| t.save(w)).is_some()
    }
    let saved = go::<ig::IncidenceGraph>(any, w)
        || go::<sig::Sig>(any, w)
        || go::<ia::IndexedAdjacency>(any, w)
        || go::<iqm::Iqm>(any, w)
        || go::<nmia::NonManifoldIa>(any, w)
        || go::<ts::TriangleSegment>(any, w)
        || go::<pe::PartialEntities>(any, w)
        || go::<le::LoopEdgeUse>(any, w)
        || go::<de::DirectedEdge>(any, w)
        || go::<crate::live::LiveComplex>(any, w);
    assert!(saved, "every structure kind implements Persist");
}

pub(super) fn load_structure(
    kind: StructureKind,
    r: &mut Reader,
) -> Result<Box<dyn Topology>, StoreError> {
    fn go<T: Persist + Topology>(r: &mut Reader) -> Result<Box<dyn Topology>, StoreError> {
        Ok(Box::new(T::load(r)?))
    }
    match kind {
        StructureKind::Ig => go::<ig::IncidenceGraph>(r),
        StructureKind::Sig => go::<sig::Sig>(r),
        StructureKind::Ia => go::<ia::IndexedAdjacency>(r),
        StructureKind::Iqm => go::<iqm::Iqm>(r),
        StructureKind::Nmia => go::<nmia::NonManifoldIa>(r),
        StructureKind::Ts => go::<ts::TriangleSegment>(r),
        StructureKind::Pe => go::<pe::PartialEntities>(r),
        StructureKind::Le => go::<le::LoopEdgeUse>(r),
        StructureKind::De => go::<de::DirectedEdge>(r),
        StructureKind::IaStar => go::<crate::live::LiveComplex>(r),
    }
}
