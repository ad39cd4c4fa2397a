//! OBJ's vertex data as attributes: vertex colours (`v x y z r g b [a]`), texture vertices
//! (`vt u [v [w]]`) and normals (`vn i j k`), tied to the vertices by the elements' `i/t/n`
//! references.
//!
//! * Colours: `obj:color` on the vertices (`f64`, 3 or 4 components: 6 or 7 numbers on a `v`
//!   line). Every `v` line has a colour or none has; one width throughout.
//! * `vt` and `vn`: `obj:vt` (`f64`, as many components as the widest `vt`, a missing `v` or
//!   `w` being 0 as the format says) and `obj:vn` (`f64`, 3). Where each vertex is given one
//!   value — every reference to it names the same numbers, the smooth-shaded export
//!   `f 1/1/1 2/2/2 3/3/3` — the attribute is on the vertices (NaN on a vertex no element
//!   gives one). Where a vertex gets different values in different elements (flat shading, a
//!   texture seam), the attribute is on the listed simplices, one value per corner in the
//!   simplex's own vertex order: 3 × the width components, NaN at a corner without one (an
//!   edge's third, a point's all). With `--triangulate`, such per-corner values on a polygon
//!   are refused (fanning would misplace them), naming the polygon's line. When no element
//!   refers to them, `vt`/`vn` statements are one per vertex in order if there are as many as
//!   `v` statements (meshio's convention), and otherwise refused: the data would belong to
//!   nothing. A reference to a statement that does not exist is an error naming its line.
//!
//! Cost: 16 bytes per `t` or `n` of an `i/t/n` reference while reading (none on plain `f i j k` lines), 24 per
//! `vt`/`vn` statement, then the attribute's own values.

use super::super::{RawInput, ReadErrorKind, parse_f64, syntax};
use crate::complex::{Attribute, Location, Values, table};

/// The vertex colour attribute.
pub(crate) const COLOR: &str = "obj:color";
/// The texture vertex attribute (meshio's name).
pub(crate) const TEXTURE: &str = "obj:vt";
/// The normal attribute (meshio's name).
pub(crate) const NORMAL: &str = "obj:vn";

/// Marks "no reference" in a per-vertex table.
const NONE: usize = usize::MAX;

/// One element vertex's reference to a `vt` or `vn` statement.
struct Corner {
    /// The listed simplex.
    listed: u32,
    /// The vertex id (0-based).
    vertex: u32,
    /// The statement (0-based; a positive index is checked when the file has been read, one
    /// beyond 32 bits kept as `u32::MAX`, which no file reaches).
    index: u32,
    /// Which of the simplex's vertices (a polygon's beyond 255 saturate: polygons are never
    /// kept per corner).
    corner: u8,
}

/// The `vt` or the `vn` statements and the references to them.
#[derive(Default)]
pub(super) struct Side {
    /// 3 numbers per statement (missing ones 0).
    values: Vec<f64>,
    /// The largest count of numbers on a statement.
    width: usize,
    /// Line of the first statement.
    first_line: u32,
    corners: Vec<Corner>,
}

impl Side {
    /// Statements read so far.
    fn count(&self) -> usize {
        self.values.len() / 3
    }

    /// Reads the numbers of a `vt` (`normal` false: 1 to 3 numbers) or `vn` (3) statement.
    pub(super) fn statement(
        &mut self,
        s: &mut super::Scanner<'_>,
        normal: bool,
        line: u32,
    ) -> Result<(), ReadErrorKind> {
        let mut row = [0.0; 3];
        let mut n = 0;
        while let Some((tok, _)) = s.token_in_line() {
            let x = parse_f64(
                tok,
                if normal {
                    "a normal"
                } else {
                    "a texture coordinate"
                },
            )?;
            if let Some(slot) = row.get_mut(n) {
                *slot = x;
            }
            n += 1;
        }
        let (kw, ok) = if normal {
            ("vn i j k", n == 3)
        } else {
            ("vt u [v [w]]", (1..=3).contains(&n))
        };
        if !ok {
            return Err(syntax(format!("{n} numbers where `{kw}` has them")));
        }
        if self.values.is_empty() {
            self.first_line = line;
        }
        self.width = self.width.max(n);
        table::try_extend(&mut self.values, &row).map_err(super::no_room("the `vt`/`vn` values"))
    }

    /// Records that corner `corner` of listed simplex `listed` (vertex `vertex`) refers to
    /// statement `index` (as written: positive, or negative counting back).
    pub(super) fn refer(
        &mut self,
        listed: usize,
        corner: usize,
        vertex: u32,
        index: i64,
        kind: &str,
    ) -> Result<(), ReadErrorKind> {
        let index = if index > 0 {
            u32::try_from(index - 1).unwrap_or(u32::MAX)
        } else {
            u32::try_from(self.count() as i64 + index).map_err(|_| {
                syntax(format!(
                    "relative {kind} index {index} reaches before the first `{kind}` ({} read so \
                     far)",
                    self.count()
                ))
            })?
        };
        table::try_push(
            &mut self.corners,
            Corner {
                listed: u32::try_from(listed)
                    .map_err(|_| syntax("more than 2^32 elements before a `vt`/`vn` reference"))?,
                vertex,
                index,
                corner: u8::try_from(corner).unwrap_or(u8::MAX),
            },
        )
        .map_err(super::no_room("the `vt`/`vn` references"))
    }

    /// The attribute `name` these statements and references make (see the module doc), put
    /// into `raw`; `vertices` is the number of `v` statements.
    pub(super) fn finish(
        self,
        name: &str,
        kind: &str,
        raw: &mut RawInput,
        vertices: usize,
    ) -> Result<(), (u32, ReadErrorKind)> {
        let n = self.count();
        let w = self.width;
        let row = |i: usize| &self.values[i * 3..i * 3 + w];
        if self.corners.is_empty() {
            if n == 0 {
                return Ok(());
            }
            if n != vertices {
                return Err((
                    self.first_line,
                    syntax(format!(
                        "{n} `{kind}` statements that no element refers to (`i/t/n`) and that are \
                         not one per vertex ({vertices} `v`): the data would belong to nothing"
                    )),
                ));
            }
            let values = (0..n).flat_map(|i| row(i).iter().copied()).collect();
            raw.attributes
                .insert(field(name, Location::Vertices, w, values));
            return Ok(());
        }
        if let Some(c) = self.corners.iter().find(|c| c.index as usize >= n) {
            return Err((
                raw.lines[c.listed as usize],
                syntax(format!(
                    "{kind} index {} refers to no `{kind}` statement ({n} in the file)",
                    u64::from(c.index) + 1
                )),
            ));
        }
        // One statement per vertex, unless two references to a vertex differ in value.
        let mut at = vec![NONE; vertices];
        let mut per_vertex = true;
        for c in &self.corners {
            let Some(slot) = at.get_mut(c.vertex as usize) else {
                continue; // an id out of range, which the complex refuses
            };
            let i = c.index as usize;
            if *slot == NONE {
                *slot = i;
            } else if !row(*slot)
                .iter()
                .zip(row(i))
                .all(|(a, b)| a.to_bits() == b.to_bits())
            {
                per_vertex = false;
                break;
            }
        }
        if per_vertex {
            let all = &self.values;
            let values = at
                .iter()
                .flat_map(|&i| {
                    (0..w).map(move |k| if i == NONE { f64::NAN } else { all[i * 3 + k] })
                })
                .collect();
            raw.attributes
                .insert(field(name, Location::Vertices, w, values));
            return Ok(());
        }
        if let Some(c) = self
            .corners
            .iter()
            .find(|c| raw.polygons.at.binary_search(&(c.listed as usize)).is_ok())
        {
            return Err((
                raw.lines[c.listed as usize],
                syntax(format!(
                    "a polygon with `{kind}` references, in a file whose `{kind}` values differ \
                     between the corners of one vertex: the per-corner values ({name} on the \
                     listed simplices) are not carried through --triangulate"
                )),
            ));
        }
        let mut values = vec![f64::NAN; raw.simplex_count() * 3 * w];
        for c in &self.corners {
            let start = (c.listed as usize * 3 + usize::from(c.corner)) * w;
            values[start..start + w].copy_from_slice(row(c.index as usize));
        }
        raw.attributes
            .insert(field(name, Location::Listed, 3 * w, values));
        Ok(())
    }
}

fn field(name: &str, location: Location, components: usize, values: Vec<f64>) -> Attribute {
    Attribute {
        name: name.to_string(),
        location,
        components,
        values: Values::F64(values),
    }
}

/// The vertex colours read so far: the width the first `v` line set (0: none), its line.
#[derive(Default)]
pub(super) struct Colors {
    width: Option<(usize, u32)>,
    values: Vec<f64>,
}

impl Colors {
    /// Records the colour of a `v` statement on `line` (`numbers`: the statement's count of
    /// numbers, `tail` those after x y z).
    pub(super) fn push(
        &mut self,
        numbers: usize,
        tail: &[f64],
        line: u32,
    ) -> Result<(), ReadErrorKind> {
        let w = match numbers {
            6 | 7 => numbers - 3,
            _ => 0,
        };
        let (first, first_line) = *self.width.get_or_insert((w, line));
        if w != first {
            let has = |w| match w {
                0 => "no colour".to_string(),
                w => format!("a colour of {w} numbers"),
            };
            return Err(syntax(format!(
                "`v` statement with {}, where the first (line {first_line}) has {}: vertex \
                 colours ({COLOR}) are on every `v` line or none",
                has(w),
                has(first)
            )));
        }
        table::try_extend(&mut self.values, &tail[..w])
            .map_err(super::no_room("the vertex colours"))
    }

    /// The `obj:color` attribute, when the `v` lines have colours.
    pub(super) fn finish(self, raw: &mut RawInput) {
        if let Some((w @ 3.., _)) = self.width {
            raw.attributes
                .insert(field(COLOR, Location::Vertices, w, self.values));
        }
    }
}

/// Whether the OBJ writer holds `a`: `obj:color` (`f64`, 3 or 4 components) on the vertices,
/// `obj:vt` (`f64`, 1 to 3 components on the vertices, 3, 6 or 9 on the listed simplices) and
/// `obj:vn` (`f64`, 3 on the vertices, 9 on the listed simplices).
pub(crate) fn holds(a: &Attribute) -> bool {
    let c = a.components;
    matches!(a.values, Values::F64(_))
        && match (a.name.as_str(), a.location) {
            (COLOR, Location::Vertices) => c == 3 || c == 4,
            (TEXTURE, Location::Vertices) => (1..=3).contains(&c),
            (TEXTURE, Location::Listed) => c == 3 || c == 6 || c == 9,
            (NORMAL, Location::Vertices) => c == 3,
            (NORMAL, Location::Listed) => c == 9,
            _ => false,
        }
}
