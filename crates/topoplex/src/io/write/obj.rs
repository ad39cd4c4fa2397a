//! OBJ writer: `v x y z` per vertex (fewer coordinates padded with zeros, zeros without
//! coordinates), then `p i`, `l i j` or `f i j k` (1-based) per simplex in listing order. Holds
//! vertices, edges and triangles, and at most 3 coordinates per vertex. The grouping labels
//! (`obj:object`, `obj:group`, `obj:material`, `obj:smoothing`, see [`crate::io::obj`]) are
//! written as `o`, `g`, `usemtl` and `s` statements before the first simplex of each run of
//! one label, so that reading back gives the same labels and names.

use super::{RawInput, check_coord_dim, check_max_len, push_ids, push_point, vertex_count};
use crate::complex::{Location, Values};
use crate::error::echo;
use crate::io::obj::LABELS;

/// A grouping label to write: which of [`LABELS`], its attribute's name, its labels.
type Grouping<'a> = (usize, &'a str, &'a [i32]);

/// The grouping labels of `raw` to write, as (statement, attribute name, labels), checked:
/// a name for every label but a leading -1 (no statement yet), a name that reads back as
/// itself, smoothing groups not negative.
fn groupings(raw: &RawInput) -> Result<Vec<Grouping<'_>>, String> {
    let mut out = Vec::new();
    for (k, (_, attr)) in LABELS.iter().enumerate() {
        let Some(a) = raw.attributes.get(attr, Location::Listed) else {
            continue;
        };
        let Values::I32(v) = &a.values else {
            return Err(format!("attribute {} is not i32 labels", a.describe()));
        };
        let mut started = false;
        for (i, &label) in v.iter().enumerate() {
            let bad = |why: String| {
                Err(format!(
                    "attribute {}: simplex #{i} has label {label}, {why}",
                    a.describe()
                ))
            };
            if k == 3 {
                if label < 0 {
                    return bad("and a smoothing group is not negative".into());
                }
                continue;
            }
            if label == -1 && !started {
                continue;
            }
            started = true;
            let Some(name) = raw.attributes.label_name(attr, 0, i64::from(label)) else {
                return bad("which has no name to write".into());
            };
            let words = name.split_whitespace().collect::<Vec<_>>().join(" ");
            if words != name
                || name.is_empty()
                || name.contains('#')
                || name.ends_with('\\')
                || name.chars().any(char::is_control)
            {
                return bad(format!(
                    "named '{}', which an OBJ statement would not read back as itself",
                    echo(name)
                ));
            }
        }
        if k < 3
            && !started
            && !raw
                .attributes
                .label_names()
                .iter()
                .any(|n| n.attribute == *attr)
        {
            return Err(format!(
                "attribute {} labels no simplex and names no label, which OBJ cannot write (a \
                 statement names the simplices after it)",
                a.describe()
            ));
        }
        out.push((k, *attr, v.as_slice()));
    }
    Ok(out)
}

pub(super) fn write(raw: &RawInput, out: &mut super::Out) -> Result<(), String> {
    check_max_len(
        raw,
        3,
        "points, edges and triangles (use .mesh, .msh, .vtk or .simplices)",
    )?;
    check_coord_dim(raw, 3)?;
    let groups = groupings(raw)?;
    let mut current: Vec<i32> = groups
        .iter()
        // Smoothing is written at the first simplex, so that the attribute comes back.
        .map(|g| if g.0 == 3 { i32::MIN } else { -1 })
        .collect();
    let coords = raw.coords.as_ref();
    for v in 0..vertex_count(raw) {
        out.extend_from_slice(b"v ");
        push_point(out, coords, v, 3);
        out.push(b'\n');
        out.spill();
    }
    for i in 0..raw.simplex_count() {
        for (g, (k, attr, labels)) in groups.iter().enumerate() {
            let label = labels[i];
            if label == current[g] {
                continue;
            }
            current[g] = label;
            out.extend_from_slice(LABELS[*k].0.as_bytes());
            out.push(b' ');
            match (*k, label) {
                (3, 0) => out.extend_from_slice(b"off"),
                (3, n) => out.extend_from_slice(n.to_string().as_bytes()),
                _ => {
                    let name = raw.attributes.label_name(attr, 0, i64::from(label));
                    out.extend_from_slice(name.unwrap_or_default().as_bytes());
                }
            }
            out.push(b'\n');
        }
        let s = raw.simplex(i);
        out.push(match s.len() {
            1 => b'p',
            2 => b'l',
            _ => b'f',
        });
        out.push(b' ');
        push_ids(out, s, 1);
        out.push(b'\n');
        out.spill();
    }
    // Names no simplex used (and smoothing on an empty listing) last, so that they come back.
    for (k, attr, labels) in &groups {
        if *k == 3 {
            if labels.is_empty() {
                out.extend_from_slice(b"s off\n");
            }
            continue;
        }
        let mut names: Vec<_> = raw
            .attributes
            .label_names()
            .iter()
            .filter(|n| n.attribute == *attr && !labels.iter().any(|&l| i64::from(l) == n.label))
            .collect();
        names.sort_by_key(|n| n.label);
        for n in names {
            out.extend_from_slice(LABELS[*k].0.as_bytes());
            out.push(b' ');
            out.extend_from_slice(n.name.as_bytes());
            out.push(b'\n');
        }
    }
    Ok(())
}
