//! OBJ writer: `v x y z` per vertex (fewer coordinates padded with zeros, zeros without
//! coordinates), then `p i`, `l i j` or `f i j k` (1-based) per simplex in listing order. Holds
//! vertices, edges and triangles, and at most 3 coordinates per vertex. The grouping labels
//! (`obj:object`, `obj:group`, `obj:material`, `obj:smoothing`, see [`crate::io::obj`]) are
//! written as `o`, `g`, `usemtl` and `s` statements before the first simplex of each run of
//! one label, so that reading back gives the same labels and names. Vertex colours
//! (`obj:color`) follow the coordinates on each `v` line; `obj:vt` and `obj:vn` (see
//! [`crate::io::obj::data`]) are written as `vt`/`vn` statements — one per vertex for a vertex
//! field, one per valued corner for a per-corner one — referred to by the elements' `i/t/n`,
//! so that they read back as they were. A value the references could not tie back to its
//! vertex or corner (a vertex field's value on a vertex no triangle, or for `obj:vt` no edge,
//! lists; a corner value on a point, or a normal on an edge) is refused.

use super::{RawInput, check_fits, push_ids, push_point, vertex_count};
use crate::complex::{Location, Values};
use crate::error::echo;
use crate::io::obj::LABELS;
use crate::io::obj::data::{COLOR, NORMAL, TEXTURE};

/// How one of `obj:vt`, `obj:vn` is written: its values and width (per vertex or per corner).
#[derive(Clone, Copy)]
enum Side<'a> {
    None,
    Vertices(&'a [f64], usize),
    Corners(&'a [f64], usize),
}

/// The row `i` of `w` numbers of `v`, unless it is all NaN (no value).
fn valued(v: &[f64], i: usize, w: usize) -> Option<&[f64]> {
    let row = &v[i * w..(i + 1) * w];
    (!row.iter().all(|x| x.is_nan())).then_some(row)
}

/// The `obj:vt` (`k` 0) or `obj:vn` (1) data of `raw`, checked to read back as it is.
fn side<'a>(raw: &'a RawInput, k: usize) -> Result<Side<'a>, String> {
    let name = [TEXTURE, NORMAL][k];
    // The simplices whose corners take a reference: triangles and, for `vt`, edges.
    let takes = |len: usize| len == 3 || (k == 0 && len == 2);
    let get = |location| match raw.attributes.get(name, location) {
        Some(a) => match &a.values {
            Values::F64(v) => Some((a, v.as_slice())),
            _ => None,
        },
        None => None,
    };
    match (get(Location::Vertices), get(Location::Listed)) {
        (Some(_), Some(_)) => Err(format!(
            "attribute {name} is on both the vertices and the listed simplices; OBJ holds one"
        )),
        (Some((a, v)), None) => {
            let mut listed = vec![false; vertex_count(raw)];
            let mut any = false;
            for i in 0..raw.simplex_count() {
                let s = raw.simplex(i);
                if takes(s.len()) {
                    any = true;
                    s.iter().for_each(|&x| listed[x as usize] = true);
                }
            }
            // With no element to refer to them, one statement per vertex reads back in order.
            if let Some(x) = (0..listed.len())
                .find(|&x| any && !listed[x] && valued(v, x, a.components).is_some())
            {
                return Err(format!(
                    "attribute {}: vertex {x} has a value but no {} lists it, so no reference                      would tie it back",
                    a.describe(),
                    if k == 0 {
                        "triangle or edge"
                    } else {
                        "triangle"
                    }
                ));
            }
            Ok(Side::Vertices(v, a.components))
        }
        (None, Some((a, v))) => {
            let w = a.components / 3;
            for i in 0..raw.simplex_count() {
                let len = raw.simplex(i).len();
                for c in 0..3 {
                    if (!takes(len) || c >= len) && valued(v, i * 3 + c, w).is_some() {
                        return Err(format!(
                            "attribute {}: simplex #{i} {} has a value at corner {c}, which an                              OBJ element of {len} vertices cannot refer to",
                            a.describe(),
                            super::show(raw.simplex(i))
                        ));
                    }
                }
            }
            Ok(Side::Corners(v, w))
        }
        (None, None) => Ok(Side::None),
    }
}

/// Writes the `vt` (`k` 0) or `vn` statements of `side`.
fn write_side(raw: &RawInput, side: Side<'_>, k: usize, out: &mut super::Out) {
    let kw: &[u8] = [b"vt".as_slice(), b"vn"][k];
    let line = |out: &mut super::Out, row: &[f64]| {
        out.extend_from_slice(kw);
        for &x in row {
            out.push(b' ');
            super::push_f64(out, x);
        }
        out.push(b'\n');
        out.spill();
    };
    match side {
        Side::None => {}
        Side::Vertices(v, w) => {
            (0..v.len() / w.max(1)).for_each(|x| line(out, &v[x * w..(x + 1) * w]))
        }
        Side::Corners(v, w) => {
            for i in 0..raw.simplex_count() {
                for c in 0..raw.simplex(i).len().min(3) {
                    if let Some(row) = valued(v, i * 3 + c, w) {
                        line(out, row);
                    }
                }
            }
        }
    }
}

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
    check_fits(
        raw,
        3,
        "points, edges and triangles (use .mesh, .msh, .vtk or .simplices)",
    )?;
    let groups = groupings(raw)?;
    let sides = [side(raw, 0)?, side(raw, 1)?];
    write_vertices(raw, out);
    write_side(raw, sides[0], 0, out);
    write_side(raw, sides[1], 1, out);
    // The next `vt`/`vn` statement a per-corner value refers to (1-based).
    let mut next = [1u64; 2];
    let mut current: Vec<i32> = groups
        .iter()
        // Smoothing is written at the first simplex, so that the attribute comes back.
        .map(|g| if g.0 == 3 { i32::MIN } else { -1 })
        .collect();
    for i in 0..raw.simplex_count() {
        write_group_changes(raw, &groups, &mut current, i, out);
        write_element(raw, i, &sides, &mut next, out);
        out.spill();
    }
    write_unused_names(raw, &groups, out);
    Ok(())
}

/// A `v` statement per vertex id, with its `obj:color` numbers when the complex has them.
fn write_vertices(raw: &RawInput, out: &mut super::Out) {
    let color = match raw.attributes.get(COLOR, Location::Vertices) {
        Some(a) => match &a.values {
            Values::F64(v) => Some((v.as_slice(), a.components)),
            _ => None,
        },
        None => None,
    };
    let coords = raw.coords.as_ref();
    for v in 0..vertex_count(raw) {
        out.extend_from_slice(b"v ");
        push_point(out, coords, v, 3);
        if let Some((c, w)) = color {
            for &x in &c[v * w..(v + 1) * w] {
                out.push(b' ');
                super::push_f64(out, x);
            }
        }
        out.push(b'\n');
        out.spill();
    }
}

/// Before listed simplex i: a `g`/`o`/`usemtl`/`s` statement for each grouping whose label
/// changes there (`current` holds each grouping's label in force).
fn write_group_changes(
    raw: &RawInput,
    groups: &[Grouping<'_>],
    current: &mut [i32],
    i: usize,
    out: &mut super::Out,
) {
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
}

/// Listed simplex i as a `p`, `l` or `f` statement, each corner with its `vt`/`vn` references
/// (`next` numbers the per-corner statements written so far).
fn write_element(
    raw: &RawInput,
    i: usize,
    sides: &[Side<'_>; 2],
    next: &mut [u64; 2],
    out: &mut super::Out,
) {
    let s = raw.simplex(i);
    out.push(match s.len() {
        1 => b'p',
        2 => b'l',
        _ => b'f',
    });
    out.push(b' ');
    if s.len() == 1 || sides.iter().all(|s| matches!(s, Side::None)) {
        push_ids(out, s, 1);
    } else {
        for (c, &x) in s.iter().enumerate() {
            if c > 0 {
                out.push(b' ');
            }
            push_ids(out, &[x], 1);
            // The references of this corner: `/t`, `//n`, `/t/n` or none.
            let mut refs = [None; 2];
            for (k, side) in sides.iter().enumerate() {
                if k == 1 && s.len() != 3 {
                    continue;
                }
                refs[k] = match *side {
                    Side::None => None,
                    Side::Vertices(..) => Some(u64::from(x) + 1),
                    Side::Corners(v, w) => valued(v, i * 3 + c, w).map(|_| {
                        next[k] += 1;
                        next[k] - 1
                    }),
                };
            }
            match refs {
                [None, None] => {}
                [Some(t), None] => out.extend_from_slice(format!("/{t}").as_bytes()),
                [None, Some(n)] => out.extend_from_slice(format!("//{n}").as_bytes()),
                [Some(t), Some(n)] => out.extend_from_slice(format!("/{t}/{n}").as_bytes()),
            }
        }
    }
    out.push(b'\n');
}

/// After the elements: the label names no simplex used (and smoothing on an empty listing), so
/// that they come back.
fn write_unused_names(raw: &RawInput, groups: &[Grouping<'_>], out: &mut super::Out) {
    for (k, attr, labels) in groups {
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
}
