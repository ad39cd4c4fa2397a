//! The complex's sections, and dispatch of a structure's sections by kind.

use std::path::PathBuf;

use super::{ComplexSpans, Reader, Span, StoreError, Writer, coords_of};
use crate::complex::Complex;
use crate::complex::Coords;
use crate::complex::{Attribute, Attributes, LabelName, Location, Values};

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
    save_attributes(c.attributes(), w);
}

/// The attributes (version 2; nothing for a complex without any, so such a file is laid out as
/// version 1 wrote it): a count, then per attribute its name, location (0 vertices, 1 listed),
/// type (0 i32, 1 i64, 2 f32, 3 f64), components and values (a typed section), then a count
/// of label names and per name its attribute, dimension (`u64::MAX`: none), label (the `i64`'s
/// bits) and name.
fn save_attributes(at: &Attributes, w: &mut Writer) {
    if at.is_empty() {
        return;
    }
    let list: Vec<&Attribute> = at.iter().collect();
    w.scalar(list.len() as u64);
    for a in list {
        w.u8s(a.name.as_bytes());
        w.scalar(match a.location {
            Location::Vertices => 0,
            Location::Listed => 1,
        });
        // The type's code, the components, then the values as a typed section.
        fn typed<T: bytemuck::Pod>(w: &mut Writer, code: u64, components: usize, v: &[T]) {
            w.scalar(code);
            w.scalar(components as u64);
            w.section(v);
        }
        match &a.values {
            Values::I32(v) => typed(w, 0, a.components, v),
            Values::I64(v) => typed(w, 1, a.components, v),
            Values::F32(v) => typed(w, 2, a.components, v),
            Values::F64(v) => typed(w, 3, a.components, v),
        }
    }
    w.scalar(at.label_names().len() as u64);
    for n in at.label_names() {
        w.u8s(n.attribute.as_bytes());
        w.scalar(n.dimension.map_or(u64::MAX, u64::from));
        w.scalar(n.label as u64);
        w.u8s(n.name.as_bytes());
    }
}

/// The attributes [`save_attributes`] wrote, when sections are left before `end` (a file of
/// version 1, or of a complex without attributes, has none); checked against the complex.
pub(super) fn load_attributes(
    r: &mut Reader,
    c: &mut Complex,
    end: usize,
    spans: &mut ComplexSpans,
) -> Result<(), StoreError> {
    if r.next >= end {
        return Ok(());
    }
    let text = |r: &mut Reader, what: &str| -> Result<String, StoreError> {
        let bytes = r.u8s()?;
        String::from_utf8(r.copy(&bytes)?).map_err(|_| r.corrupt(format!("{what} is not UTF-8")))
    };
    let count = r.bounded(1 << 16, "attribute count")?;
    let mut list = Vec::new();
    for _ in 0..count {
        let name = text(r, "an attribute's name")?;
        let location = match r.bounded(1, "attribute location")? {
            0 => Location::Vertices,
            _ => Location::Listed,
        };
        let ty = r.bounded(3, "attribute type")?;
        let components = r.bounded(
            crate::complex::attributes::MAX_COMPONENTS as u64,
            "attribute components",
        )? as usize;
        let values = match ty {
            0 => {
                let a = r.arr::<i32>()?;
                spans.attributes.push((name.clone(), Span::of(&a)));
                Values::I32(r.copy(&a)?)
            }
            1 => {
                let a = r.arr::<i64>()?;
                spans.attributes.push((name.clone(), Span::of(&a)));
                Values::I64(r.copy(&a)?)
            }
            2 => {
                let a = r.arr::<f32>()?;
                spans.attributes.push((name.clone(), Span::of(&a)));
                Values::F32(r.copy(&a)?)
            }
            _ => {
                let a = r.arr::<f64>()?;
                spans.attributes.push((name.clone(), Span::of(&a)));
                Values::F64(r.copy(&a)?)
            }
        };
        list.push(Attribute {
            name,
            location,
            components,
            values,
        });
    }
    let names = r.bounded(1 << 24, "label name count")?;
    let mut label_names = Vec::new();
    for _ in 0..names {
        let attribute = text(r, "a label name's attribute")?;
        let dimension = match r.scalar()? {
            u64::MAX => None,
            d => Some(u8::try_from(d).map_err(|_| r.corrupt(format!("label dimension {d}")))?),
        };
        let label = r.scalar()? as i64;
        let name = text(r, "a label name")?;
        label_names.push(LabelName {
            attribute,
            dimension,
            label,
            name,
        });
    }
    c.set_attributes(Attributes::from_parts(list, label_names))
        .map_err(|e| r.corrupt(format!("attributes: {e}")))
}

pub(super) fn load_complex(
    r: &mut Reader,
    spans: &mut ComplexSpans,
) -> Result<Complex, StoreError> {
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
    spans.listed_ids = Span::of(&ids);
    let wide = r.u64s()?;
    spans.listed_offsets = Span::of(&wide);
    let offsets = r.usizes_of(&wide)?;
    // from_arrays slices by these offsets: they must run from 0 to the ids' end, ascending.
    let monotone = offsets.windows(2).all(|w| w[0] <= w[1]);
    if offsets.first() != Some(&0) || offsets.last() != Some(&ids.len()) || !monotone {
        return Err(r.corrupt("listing offsets are not ascending from 0 to the ids' length"));
    }
    let source = r.u8s()?;
    let source =
        (!source.is_empty()).then(|| PathBuf::from(String::from_utf8_lossy(&source).into_owned()));
    spans.coords = (dim > 0).then(|| Span::of(&data));
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

#[cfg(test)]
mod tests {
    use crate::codec::head_checksum;
    use crate::complex::{Attribute, Attributes, Complex, Coords, Location, Values};

    /// The spans of `Saved::complex_spans` name, in the file's own bytes, the very arrays the
    /// opened complex holds: coordinates, the listing's ids and offsets, and each attribute.
    #[test]
    fn complex_spans_point_at_the_complex_arrays_in_the_file() {
        let listing: &[&[u32]] = &[&[2, 0, 1], &[1, 2, 3], &[3, 4], &[1, 2]];
        let mut ids = Vec::new();
        let mut offsets = vec![0usize];
        for s in listing {
            ids.extend_from_slice(s);
            offsets.push(ids.len());
        }
        let coords: Vec<f64> = (0..15).map(|i| f64::from(i) * 0.5 - 3.0).collect();
        let mut c = Complex::from_arrays(
            5,
            &ids,
            &offsets,
            Some(Coords {
                dim: 3,
                data: coords.clone(),
            }),
        )
        .unwrap();
        let mut attrs = Attributes::default();
        let heat: Vec<f32> = (0..10).map(|i| i as f32 * 1.5).collect();
        let label: Vec<i64> = vec![7, -1, 9, 11];
        attrs.insert(Attribute {
            name: "heat".into(),
            location: Location::Vertices,
            components: 2,
            values: Values::F32(heat.clone()),
        });
        attrs.insert(Attribute {
            name: "label".into(),
            location: Location::Listed,
            components: 1,
            values: Values::I64(label.clone()),
        });
        c.set_attributes(attrs).unwrap();
        let dir = std::env::temp_dir().join(format!("topoplex-spans-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("spans.tpx");
        super::super::save(&path, &c, None).unwrap();
        let bytes = std::fs::read(&path).unwrap();
        let (file, _) = crate::io::open_regular(&path).unwrap();
        let saved = super::super::Saved::open_file(&path, &file).unwrap();
        let (back, spans) = saved.complex_spans().unwrap();
        fn at<T: bytemuck::Pod>(bytes: &[u8], s: super::Span) -> Vec<T> {
            let b = &bytes[s.offset..s.offset + s.count * size_of::<T>()];
            b.chunks_exact(size_of::<T>())
                .map(bytemuck::pod_read_unaligned)
                .collect()
        }
        assert_eq!(at::<f64>(&bytes, spans.coords.unwrap()), coords);
        assert_eq!(back.coords().unwrap().data, coords);
        assert_eq!(at::<u32>(&bytes, spans.listed_ids), ids);
        let wide: Vec<u64> = offsets.iter().map(|&o| o as u64).collect();
        assert_eq!(at::<u64>(&bytes, spans.listed_offsets), wide);
        assert_eq!(back.input_count(), listing.len());
        for (i, s) in listing.iter().enumerate() {
            assert_eq!(back.input_simplex(i), *s);
        }
        let names: Vec<&str> = spans.attributes.iter().map(|(n, _)| n.as_str()).collect();
        assert_eq!(names, ["heat", "label"]);
        assert_eq!(at::<f32>(&bytes, spans.attributes[0].1), heat);
        assert_eq!(at::<i64>(&bytes, spans.attributes[1].1), label);
        // A complex without coordinates or attributes has no span for them.
        let bare = crate::fixtures::builtin_example();
        super::super::save(&path, &bare, None).unwrap();
        let (_, spans) = super::super::Saved::open(&path)
            .unwrap()
            .complex_spans()
            .unwrap();
        assert_eq!(spans.coords, None);
        assert!(spans.attributes.is_empty());
        std::fs::remove_dir_all(&dir).ok();
    }

    /// A file of version 1 (the same layout as a version-2 file of a complex without
    /// attributes, the version field 1) still opens, and gives the same complex.
    #[test]
    fn a_version_1_file_still_opens() {
        let c = crate::fixtures::builtin_example();
        let dir = std::env::temp_dir().join(format!("topoplex-v1-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("v1.tpx");
        super::super::save(&path, &c, None).unwrap();
        let mut bytes = std::fs::read(&path).unwrap();
        assert_eq!(u32::from_ne_bytes(bytes[12..16].try_into().unwrap()), 2);
        bytes[12..16].copy_from_slice(&1u32.to_ne_bytes());
        let n = u32::from_ne_bytes(bytes[24..28].try_into().unwrap()) as usize;
        let table = u64::from_ne_bytes(bytes[40..48].try_into().unwrap()) as usize;
        let sum = head_checksum(&bytes[..48], &bytes[table..table + 32 * n]);
        bytes[48..56].copy_from_slice(&sum.to_ne_bytes());
        std::fs::write(&path, &bytes).unwrap();
        let back = super::super::Saved::open(&path).unwrap().complex().unwrap();
        assert_eq!(back.top_counts(), c.top_counts());
        assert!(back.attributes().is_empty());
        std::fs::remove_dir_all(&dir).ok();
    }
}
