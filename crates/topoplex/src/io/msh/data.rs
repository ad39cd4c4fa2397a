//! Gmsh post-processing data: `$NodeData` and `$ElementData` sections, read as real fields and
//! written back.
//!
//! A section is a view at one time step: string tags (the first, in double quotes, is the
//! name), real tags (the first is the time value), integer tags (time step, number of
//! components, number of entities, optionally a partition), then per entity its tag and its
//! `components` reals (in binary files the tags are ASCII lines, the entities a 4-byte int and
//! little-endian doubles each). Each section becomes an `f64` attribute of that many
//! components (1 to 9): node data on the vertices (node tags mapped through `$Nodes`), element
//! data on the listed simplices (element tags mapped through `$Elements`, which must come
//! first). A name with one time step keeps its name; a name with several time steps becomes
//! one attribute per step, `NAME@STEP` (`STEP` the time-step integer tag). Time values, the
//! other string tags and partitions are not kept.
//!
//! Refused, naming the section and its line: a section that does not cover every node or
//! element (nothing here can hold "no value"), an entity listed twice or unknown, 0 or more
//! than 9 components, fewer than 3 integer tags, no name, the same name and step twice.
//!
//! Writing: every `f64` attribute other than `gmsh:physical`/`gmsh:geometrical`, after the
//! elements, in its location's section, time value 0; `NAME@STEP` attributes of a name with
//! several steps (and no attribute called `NAME` alone) are written as the steps of `NAME`,
//! so that they read back under the same names. Storage: one `f64` vector per section, filled
//! in place; a bitmap of the entities seen while a section is read.

use rustc_hash::FxHashMap;

use super::super::{ReadErrorKind, echo, no_room, parse_f64, syntax};
use super::{GEOMETRICAL, PHYSICAL, Reader, Res, Writer};
use crate::complex::attributes::MAX_COMPONENTS;
use crate::complex::{Attribute, Location, Values, table};

/// One section read: its name, time step, location, components and values.
pub(super) struct Section {
    name: String,
    step: i64,
    location: Location,
    components: usize,
    values: Vec<f64>,
}

/// The element tags read so far: `None` while element `i` had tag `i + 1` (Gmsh's usual
/// numbering, nothing stored), else every tag in listing order.
#[derive(Default)]
pub(super) struct ElementTags {
    tags: Option<Vec<u64>>,
    count: usize,
    /// Tag → listing index, built on the first `$ElementData` when the tags are not 1..=m.
    map: Option<FxHashMap<u64, u32>>,
}

impl ElementTags {
    /// The next element's tag.
    pub(super) fn push(&mut self, tag: i64, line: u32) -> Res<()> {
        let tag = u64::try_from(tag).unwrap_or(u64::MAX);
        let room = |b| (line, no_room("the element tags")(b));
        match &mut self.tags {
            None if tag == self.count as u64 + 1 => {}
            None => {
                let mut v = Vec::new();
                table::try_reserve_exact(&mut v, self.count + 1).map_err(room)?;
                v.extend(1..=self.count as u64);
                v.push(tag);
                self.tags = Some(v);
            }
            Some(v) => table::try_push(v, tag).map_err(room)?,
        }
        self.count += 1;
        Ok(())
    }

    /// The listing index of element `tag` (`Err(true)`: listed twice; `Err(false)`: unknown).
    fn index(&mut self, tag: i64) -> Result<usize, bool> {
        let tag = u64::try_from(tag).map_err(|_| false)?;
        let Some(tags) = &self.tags else {
            return (1..=self.count as u64)
                .contains(&tag)
                .then(|| tag as usize - 1)
                .ok_or(false);
        };
        let map = self.map.get_or_insert_with(|| {
            let mut m = FxHashMap::default();
            for (i, &t) in tags.iter().enumerate() {
                // u32::MAX marks a tag listed twice.
                m.entry(t).and_modify(|x| *x = u32::MAX).or_insert(i as u32);
            }
            m
        });
        match map.get(&tag) {
            Some(&u32::MAX) => Err(true),
            Some(&i) => Ok(i as usize),
            None => Err(false),
        }
    }
}

impl Reader<'_> {
    /// A `$NodeData` (`nodes`) or `$ElementData` section, read whole and checked.
    pub(super) fn data_section(&mut self, nodes: bool, line: u32, elements_read: bool) -> Res<()> {
        let kw = if nodes { "$NodeData" } else { "$ElementData" };
        if !nodes && !elements_read {
            return Err((
                line,
                syntax("$ElementData before $Elements (its element tags name nothing yet)"),
            ));
        }
        let binary = std::mem::replace(&mut self.inp.binary, false);
        let r = self.data_header(kw, line);
        self.inp.binary = binary;
        let (name, step, components, count) = r?;
        let what = format!("{kw} '{}' (time step {step})", echo(&name));
        let (location, want, entities) = if nodes {
            (Location::Vertices, self.tags.len(), "nodes")
        } else {
            (Location::Listed, self.elements.count, "elements")
        };
        if count != want {
            return Err((
                line,
                syntax(format!(
                    "{what} has values for {count} {entities}, but the mesh has {want}: partial \
                     data cannot be held (every {} needs a value)",
                    &entities[..entities.len() - 1]
                )),
            ));
        }
        if binary {
            self.inp.rest_of_line();
        }
        let entity = &entities[..entities.len() - 1];
        let values = self.data_values(nodes, want, components, &what, entity, line)?;
        self.end(&format!("$End{}", &kw[1..]))?;
        if self
            .data
            .iter()
            .any(|s| s.name == name && s.step == step && s.location == location)
        {
            return Err((
                line,
                syntax(format!(
                    "a second {what} (one section per name and time step)"
                )),
            ));
        }
        table::try_push(
            &mut self.data,
            Section {
                name,
                step,
                location,
                components,
                values,
            },
        )
        .map_err(|b| (line, no_room("an attribute's values")(b)))
    }

    /// The `want` entries of a data section (one per node or element, in any order), each a
    /// tag and `components` values, into a table by vertex id or listing index; a tag the mesh
    /// does not list or a second entry of one tag refused naming it.
    fn data_values(
        &mut self,
        nodes: bool,
        want: usize,
        components: usize,
        what: &str,
        entity: &str,
        line: u32,
    ) -> Res<Vec<f64>> {
        let total = want
            .checked_mul(components)
            .ok_or((line, syntax("data too large")))?;
        let room = |b| (line, no_room("an attribute's values")(b));
        // `total` is bounded by the mesh already read.
        let mut values: Vec<f64> = Vec::new();
        table::try_reserve_exact(&mut values, total).map_err(room)?;
        values.resize(total, f64::NAN);
        let mut seen = vec![false; want];
        let tag_what = format!("a {entity} tag of {what}");
        for _ in 0..want {
            let (tag, l) = self.int(4, &tag_what, line)?;
            let i = if nodes {
                u64::try_from(tag)
                    .ok()
                    .and_then(|t| self.tags.get(&t).copied())
                    .map(|i| i as usize)
                    .ok_or(false)
            } else {
                self.elements.index(tag)
            }
            .map_err(|twice| {
                let why = if twice {
                    "listed twice in $Elements"
                } else if nodes {
                    "which $Nodes does not list"
                } else {
                    "which $Elements does not list"
                };
                (l, syntax(format!("{what}: {entity} {tag}, {why}")))
            })?;
            if std::mem::replace(&mut seen[i], true) {
                return Err((
                    l,
                    syntax(format!(
                        "{what}: {entity} {tag} has two values (so another has none: partial \
                         data cannot be held)"
                    )),
                ));
            }
            for x in &mut values[i * components..(i + 1) * components] {
                *x = self.value(l, what)?;
            }
        }
        Ok(values)
    }

    /// The tags of a data section (ASCII in every file): name, time step, components, count.
    fn data_header(&mut self, kw: &str, line: u32) -> Res<(String, i64, usize, usize)> {
        let n = self.count("the string tag count", line)?;
        let mut name = None;
        for _ in 0..n {
            self.inp.skip_space();
            let l = self.inp.line;
            let tag = self.quoted(l, || {
                format!("{kw}: expected a string tag in double quotes")
            })?;
            name.get_or_insert(tag);
        }
        let name = name.filter(|n| !n.is_empty()).ok_or_else(|| {
            (
                line,
                syntax(format!("{kw} has no name (its first string tag)")),
            )
        })?;
        let n = self.count("the real tag count", line)?;
        for _ in 0..n {
            let (tok, l) = self.inp.expect_token("a real tag")?;
            parse_f64(tok, "a real tag").map_err(|k| (l, k))?;
        }
        let n = self.count("the integer tag count", line)?;
        let mut ints = Vec::new();
        for _ in 0..n {
            let (v, l) = self.int(4, "an integer tag", line)?;
            if ints.len() < 3 {
                ints.push((v, l));
            }
        }
        let what = format!("{kw} '{}'", echo(&name));
        let [(step, _), (components, cl), (count, nl)] = ints[..] else {
            return Err((
                line,
                syntax(format!(
                    "{what} has {n} integer tags; 3 are needed (time step, components, count)"
                )),
            ));
        };
        let components = usize::try_from(components)
            .ok()
            .filter(|c| (1..=MAX_COMPONENTS).contains(c))
            .ok_or_else(|| {
                (
                    cl,
                    syntax(format!(
                        "{what} has {components} components; 1 to {MAX_COMPONENTS} are held"
                    )),
                )
            })?;
        let count = usize::try_from(count).map_err(|_| {
            (
                nl,
                syntax(format!("{what}: value count {count} is negative")),
            )
        })?;
        Ok((name, step, components, count))
    }

    /// One data value: an ASCII real or a little-endian double.
    fn value(&mut self, line: u32, what: &str) -> Res<f64> {
        if self.inp.binary {
            let b = self.inp.take(8).ok_or_else(|| {
                (
                    line,
                    syntax(format!("file ends inside the binary values of {what}")),
                )
            })?;
            return Ok(f64::from_le_bytes(b.try_into().unwrap_or([0; 8])));
        }
        let (tok, l) = self.inp.expect_token("a data value")?;
        // The section is named only when a value is refused (nothing formatted per value).
        parse_f64(tok, "a data value").map_err(|e| match e {
            ReadErrorKind::Syntax(m) => (l, syntax(format!("{m} in {what}"))),
            e => (l, e),
        })
    }
}

/// The sections read, as attributes: `NAME`, or `NAME@STEP` when a name has several steps.
pub(super) fn attributes(sections: Vec<Section>, into: &mut crate::complex::Attributes) {
    let steps = |s: &Section, all: &[(String, i64, Location)]| {
        all.iter()
            .filter(|(n, _, l)| *n == s.name && *l == s.location)
            .count()
    };
    let keys: Vec<(String, i64, Location)> = sections
        .iter()
        .map(|s| (s.name.clone(), s.step, s.location))
        .collect();
    for s in sections {
        let name = if steps(&s, &keys) > 1 {
            format!("{}@{}", s.name, s.step)
        } else {
            s.name.clone()
        };
        into.insert(Attribute {
            name,
            location: s.location,
            components: s.components,
            values: Values::F64(s.values),
        });
    }
}

/// Whether MSH holds attribute `a` as a data section: `f64`, a name that can be a Gmsh string
/// tag (not empty, no double quote or control character), not one of the tag names.
pub(crate) fn holds(a: &Attribute) -> bool {
    matches!(a.values, Values::F64(_))
        && a.name != PHYSICAL
        && a.name != GEOMETRICAL
        && !a.name.is_empty()
        && !a.name.chars().any(|c| c == '"' || c.is_control())
}

/// The name and time step an attribute is written under (see the module doc).
fn name_and_step<'a>(a: &'a Attribute, all: &[&Attribute]) -> (&'a str, i64) {
    fn split(name: &str) -> Option<(&str, i64)> {
        let (base, step) = name.rsplit_once('@')?;
        let n: i64 = step.parse().ok()?;
        (n.to_string() == step && !base.is_empty()).then_some((base, n))
    }
    if let Some((base, step)) = split(&a.name) {
        let here = || all.iter().filter(|b| b.location == a.location);
        let siblings = here()
            .filter(|b| split(&b.name).is_some_and(|(x, _)| x == base))
            .count();
        let plain = here().any(|b| b.name == base);
        if siblings > 1 && !plain {
            return (base, step);
        }
    }
    (&a.name, 0)
}

impl Writer<'_> {
    /// The data sections of `raw`'s `f64` attributes (vertex ids and listing indices + 1 are
    /// the node and element tags the writer gives).
    pub(super) fn data_sections(&mut self, raw: &crate::complex::RawInput) {
        let all: Vec<&Attribute> = raw.attributes.iter().filter(|a| holds(a)).collect();
        for a in &all {
            let Values::F64(v) = &a.values else { continue };
            let kw = match a.location {
                Location::Vertices => "NodeData",
                Location::Listed => "ElementData",
            };
            let (name, step) = name_and_step(a, &all);
            let count = a.element_count();
            self.out.extend_from_slice(
                format!(
                    "${kw}\n1\n\"{name}\"\n1\n0\n3\n{step}\n{}\n{count}\n",
                    a.components
                )
                .as_bytes(),
            );
            for i in 0..count {
                // The entity's tag is an int in binary files (Gmsh's and meshio's).
                if self.binary {
                    self.out.extend_from_slice(&(i as i32 + 1).to_le_bytes());
                } else {
                    self.out.extend_from_slice(format!("{} ", i + 1).as_bytes());
                }
                self.reals(&v[i * a.components..(i + 1) * a.components]);
            }
            self.close_block();
            self.out.extend_from_slice(format!("$End{kw}\n").as_bytes());
        }
    }
}

#[cfg(test)]
mod tests {
    use super::super::parse;
    use super::*;

    /// Nodes tagged 10, 30, 20 (vertices 0, 1, 2); a triangle tagged 7 and a point tagged 5.
    const MESH: &str = "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n3\n10 0 0 0\n30 1 0 0\n\
                        20 0 1 0\n$EndNodes\n$Elements\n2\n7 2 2 0 1 10 20 30\n5 15 2 0 1 30\n\
                        $EndElements\n";

    fn section(kw: &str, name: &str, step: i64, comps: usize, rows: &[&str]) -> String {
        format!(
            "${kw}\n1\n\"{name}\"\n1\n0.5\n3\n{step}\n{comps}\n{}\n{}\n$End{kw}\n",
            rows.len(),
            rows.join("\n")
        )
    }

    fn error(text: &str) -> (u32, String) {
        let e = parse(text.as_bytes()).unwrap_err();
        (e.0, e.1.to_string())
    }

    #[test]
    fn node_and_element_data_follow_sparse_tags_and_time_steps_get_their_step() {
        let text = format!(
            "{MESH}{}{}{}",
            section("NodeData", "T", 0, 1, &["20 2", "10 1", "30 3"]),
            section("NodeData", "T", 4, 1, &["10 -1", "30 -3", "20 -2"]),
            section("ElementData", "v", 1, 3, &["5 0 0 1", "7 1 2 3"]),
        );
        let raw = parse(text.as_bytes()).unwrap();
        let at = &raw.attributes;
        let f = |name: &str, l| at.get(name, l).unwrap().values.clone();
        // Vertex 0 is node 10, vertex 1 node 30, vertex 2 node 20.
        assert_eq!(
            f("T@0", Location::Vertices),
            Values::F64(vec![1.0, 3.0, 2.0])
        );
        assert_eq!(
            f("T@4", Location::Vertices),
            Values::F64(vec![-1.0, -3.0, -2.0])
        );
        // Element 7 is listed first, element 5 second.
        assert_eq!(
            f("v", Location::Listed),
            Values::F64(vec![1.0, 2.0, 3.0, 0.0, 0.0, 1.0])
        );
        assert!(at.get("T", Location::Vertices).is_none());
    }

    #[test]
    fn malformed_data_sections_are_refused_naming_section_line_and_counts() {
        let bad = |s: String| error(&format!("{MESH}{s}"));
        let (line, m) = bad(section("NodeData", "T", 0, 1, &["10 1", "30 3"]));
        assert_eq!(line, 15);
        assert_eq!(
            m,
            "$NodeData 'T' (time step 0) has values for 2 nodes, but the mesh has 3: partial \
             data cannot be held (every node needs a value)"
        );
        let (line, m) = bad(section("NodeData", "T", 0, 1, &["10 1", "11 3", "20 2"]));
        assert_eq!(line, 25);
        assert_eq!(
            m,
            "$NodeData 'T' (time step 0): node 11, which $Nodes does not list"
        );
        let (_, m) = bad(section("ElementData", "v", 0, 1, &["7 1", "7 2"]));
        assert!(m.contains("element 7 has two values"), "{m}");
        let (line, m) = bad(section("ElementData", "v", 0, 12, &["7 1", "5 2"]));
        assert_eq!(line, 22);
        assert_eq!(m, "$ElementData 'v' has 12 components; 1 to 9 are held");
        let (_, m) = bad(section("NodeData", "T", 0, 1, &["10 1", "30 x", "20 2"]));
        assert!(m.contains("'x'") && m.contains("$NodeData 'T'"), "{m}");
        let twice = section("NodeData", "T", 2, 1, &["10 1", "30 3", "20 2"]);
        let (_, m) = bad(twice.clone() + &twice);
        assert!(m.starts_with("a second $NodeData 'T' (time step 2)"), "{m}");
        let before = MESH.replace(
            "$Elements",
            &(section("ElementData", "v", 0, 1, &["7 1", "5 2"]) + "$Elements"),
        );
        assert!(
            error(&before)
                .1
                .starts_with("$ElementData before $Elements")
        );
    }

    /// Names with `@` come back as they were: a lone `u@3`, `v@1`/`v@2` beside a plain `v`,
    /// `w@01` (not a canonical step), and a true series `x@0`/`x@5` (written as steps of `x`).
    #[test]
    fn step_suffixes_round_trip_whatever_their_siblings() {
        let mut raw = crate::complex::RawInput::new();
        raw.vertex_count = Some(2);
        raw.push(&[0, 1], 0);
        let names = ["u@3", "v", "v@1", "v@2", "w@01", "x@0", "x@5"];
        for (k, name) in names.iter().enumerate() {
            raw.attributes.insert(Attribute {
                name: name.to_string(),
                location: Location::Vertices,
                components: 1,
                values: Values::F64(vec![k as f64, -(k as f64)]),
            });
        }
        for v4 in [false, true] {
            let mut out = Vec::new();
            super::super::write(&raw, v4, false, &mut out).unwrap();
            let text = String::from_utf8(out).unwrap();
            assert!(text.contains("\"x\"\n1\n0\n3\n5\n"), "{text}");
            assert!(text.contains("\"v@1\"\n1\n0\n3\n0\n"), "{text}");
            let back = parse(text.as_bytes()).unwrap();
            assert!(
                back.attributes.bits_eq(&raw.attributes),
                "{:?}",
                back.attributes
            );
        }
    }
}
