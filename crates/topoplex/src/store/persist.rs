//! The complex's sections, and dispatch of a structure's sections by kind.

use std::path::PathBuf;

use super::{Reader, StoreError, Writer, coords_of};
use crate::complex::Complex;
use crate::complex::Coords;

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
