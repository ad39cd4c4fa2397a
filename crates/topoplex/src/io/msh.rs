//! Gmsh MSH (`.msh`) versions 2.2 and 4.1, ASCII and binary, read and written here.
//!
//! Own code rather than the `mshio` crate: mshio reads version 4.1 only, writes nothing and
//! reports errors without a line; one reader for both versions, sharing the byte cursor of the
//! VTK reader, is smaller than mshio plus a version 2 reader and a writer.
//!
//! Reading:
//! * `$MeshFormat` gives the version (2.x or 4.1), ASCII (0) or binary (1), and the data size
//!   (8). Binary files must be little-endian (the `1` after the header reads as 1).
//! * `$Nodes` numbers the vertices in file order; node tags (any positive integers, sparse or
//!   unordered) are mapped to those positions. Coordinates have dimension 3. In version 4,
//!   parametric coordinates are skipped.
//! * `$Elements`: types 15 (point), 1 (line), 2 (triangle), 4 (tetrahedron) are simplices;
//!   any other type (quadrangle 3, hexahedron 5, prism 6, pyramid 7, higher-order elements) is
//!   refused naming the element's tag and line. A node tag not in `$Nodes` is an error naming
//!   the element.
//! * Tags become the `i32` attributes `gmsh:physical` and `gmsh:geometrical` on the listed
//!   simplices (meshio's names): in version 2.2 an element's first two tags (further ones,
//!   partitions, are skipped); in 4.1 the elementary tag is the block's entity and the physical
//!   tags the entity's in `$Entities` (an entity in several physical groups gives
//!   `gmsh:physical` that many components, 0 where an element has fewer). `$PhysicalNames`
//!   become label names of `gmsh:physical` per dimension. An array equal to what the writer
//!   writes without it (physical 0, elementary 1 everywhere) is not kept: nothing is lost.
//! * `$NodeData` and `$ElementData` are read as `f64` fields (`msh/data.rs`: every time step
//!   kept, `NAME@STEP` when a name has several; partial data refused); `$ElementNodeData` is
//!   refused.
//! * Other sections are skipped to their `$End` line. Counts allocate at most what the bytes
//!   left could hold.
//! * Errors in a binary block name the line of its section keyword.
//!
//! Writing: nodes tagged 1..=n in vertex order (3 coordinates, fewer padded with zeros, zeros
//! without coordinates), elements tagged 1..=m in listing order, `$PhysicalNames` when
//! `gmsh:physical` has label names. Version 2.2 gives each element its `gmsh:physical` (else 0)
//! and `gmsh:geometrical` (else 1) tags; version 4.1 puts all nodes in one block and the
//! elements in one block per run of equal type and entity, so the listing order is kept across
//! dimensions. The entity is the `gmsh:geometrical` tag, else (with `gmsh:physical`) one entity
//! per physical tag and dimension, else 1; with `gmsh:physical` an `$Entities` section gives each
//! entity its physical tag — elements of one entity with different physical tags cannot be held
//! (write 2.2). Holds points, edges, triangles and tetrahedra, and at most 3 coordinates;
//! `f64` attributes are written as `$NodeData`/`$ElementData` after the elements (`msh/data.rs`).

use rustc_hash::FxHashMap;

use super::bytes::Input;
use super::write::{check_fits, push_f64, vertex_count};
use super::{Coords, RawInput, ReadErrorKind, echo, no_room, parse_integer, syntax};
use super::{Float, parse_real};
use crate::complex::{Attribute, LabelName, Location, Values, table};
use crate::io::{Res, SimplexCodes};

mod data;
pub(crate) use data::holds as holds_data;

/// Gmsh's element types of the four simplices.
const ELEMENT_TYPES: SimplexCodes = SimplexCodes([15, 1, 2, 4]);

/// Gmsh's element type of a simplex with `len` vertices.
fn element_type(len: usize) -> i32 {
    ELEMENT_TYPES.of_len(len) as i32
}

/// The vertex count of a simplex element type, or the type's name for refusals.
fn simplex_len(t: i64) -> Result<usize, String> {
    ELEMENT_TYPES.len_of(t).ok_or_else(|| match t {
        3 => "quadrangle".into(),
        5 => "hexahedron".into(),
        6 => "prism".into(),
        7 => "pyramid".into(),
        _ => format!("type {t}"),
    })
}

/// The message for a `$...` section keyword met where `what` was expected: the section ended
/// before the entries it declared (or an entry was cut short), not a bad number.
fn section_ended(tok: &str, what: &str) -> Option<ReadErrorKind> {
    tok.starts_with('$').then(|| {
        syntax(format!(
            "the section ends ('{}') where {what} was expected: fewer entries than declared, or \
             an entry with fewer values than its type has",
            echo(tok)
        ))
    })
}

/// The attribute name of Gmsh physical tags (meshio's).
pub const PHYSICAL: &str = "gmsh:physical";
/// The attribute name of Gmsh elementary (geometrical entity) tags (meshio's).
pub const GEOMETRICAL: &str = "gmsh:geometrical";

/// Version, binary, and the reading state.
struct Reader<'a> {
    inp: Input<'a>,
    v4: bool,
    /// Node tag → vertex id.
    tags: FxHashMap<u64, u32>,
    coords: Vec<f64>,
    raw: RawInput,
    /// Per element, its physical tags (`physical_width` each, 0 where it has fewer).
    physical: Vec<i32>,
    /// Per element, its elementary tag.
    geometrical: Vec<i32>,
    /// Physical tags per element: 1, or the most any entity of `$Entities` has.
    physical_width: usize,
    /// Version 4 `$Entities`: (dimension, tag) → physical tags.
    entities: FxHashMap<(i64, i64), Vec<i32>>,
    /// The element tags, for `$ElementData`.
    elements: data::ElementTags,
    /// The `$NodeData` and `$ElementData` sections read.
    data: Vec<data::Section>,
}

impl<'a> Reader<'a> {
    /// An integer: an ASCII token, or `size` little-endian bytes (4: int, 8: size_t).
    fn int(&mut self, size: usize, what: &str, line: u32) -> Res<(i64, u32)> {
        if self.inp.binary {
            let b = self.inp.take(size).ok_or_else(|| {
                (
                    line,
                    syntax(format!("file ends inside binary data; expected {what}")),
                )
            })?;
            let v = if size == 4 {
                i64::from(i32::from_le_bytes(b.try_into().unwrap()))
            } else {
                u64::from_le_bytes(b.try_into().unwrap()).min(i64::MAX as u64) as i64
            };
            return Ok((v, line));
        }
        let (tok, l) = self.inp.expect_token(what)?;
        match parse_integer(tok) {
            Ok(v) => Ok((v.clamp(i64::MIN.into(), i64::MAX.into()) as i64, l)),
            Err(_) => Err((
                l,
                section_ended(tok, what).unwrap_or_else(|| {
                    syntax(format!(
                        "'{}' where {what} (an integer) was expected",
                        echo(tok)
                    ))
                }),
            )),
        }
    }

    /// A count: size_t in version 4; an ASCII line in version 2, binary or not.
    fn count(&mut self, what: &str, line: u32) -> Res<usize> {
        let binary = self.inp.binary;
        self.inp.binary &= self.v4;
        let r = self.int(8, what, line);
        self.inp.binary = binary;
        let (v, l) = r?;
        usize::try_from(v).map_err(|_| (l, syntax(format!("{what} {v} is negative"))))
    }

    fn real(&mut self, line: u32) -> Res<f64> {
        if self.inp.binary {
            let b = self
                .inp
                .take(8)
                .ok_or_else(|| (line, syntax("file ends inside binary node coordinates")))?;
            return Ok(f64::from_le_bytes(b.try_into().unwrap()));
        }
        let (tok, l) = self.inp.expect_token("a node coordinate")?;
        // The shared check: a value a double holds only as inf or 0 is refused.
        parse_real(tok, "a node coordinate", Float::F64)
            .map_err(|k| (l, section_ended(tok, "a node coordinate").unwrap_or(k)))
    }

    /// After a binary block: the newline before the `$End` keyword.
    fn end(&mut self, keyword: &str) -> Res<()> {
        let (tok, l) = self.inp.expect_token(keyword)?;
        if tok != keyword {
            return Err((
                l,
                syntax(format!(
                    "expected {keyword} after the declared entries, found '{}' (an entry with \
                     more values than its type has, or more entries than declared)",
                    echo(tok)
                )),
            ));
        }
        Ok(())
    }

    /// A count header line of a section in binary version 2 is ASCII; the binary data starts
    /// after its newline.
    fn enter_binary_block(&mut self) {
        if self.inp.binary {
            self.inp.rest_of_line();
        }
    }

    fn node(&mut self, tag: i64, line: u32) -> Res<()> {
        let id =
            u32::try_from(self.tags.len()).map_err(|_| (line, syntax("more than 2^32 nodes")))?;
        let tag = u64::try_from(tag)
            .map_err(|_| (line, syntax(format!("node tag {tag} is negative"))))?;
        self.tags.try_reserve(1).map_err(|_| {
            (
                line,
                no_room("the node tags")(self.tags.len().saturating_mul(24)),
            )
        })?;
        if self.tags.insert(tag, id).is_some() {
            return Err((line, syntax(format!("node tag {tag} appears twice"))));
        }
        Ok(())
    }

    fn nodes(&mut self, line: u32) -> Res<()> {
        if !self.v4 {
            let n = self.count("the node count", line)?;
            self.reserve(n, 4 + 24, line)?;
            self.enter_binary_block();
            for _ in 0..n {
                let (tag, l) = self.int(4, "a node tag", line)?;
                self.node(tag, l)?;
                for _ in 0..3 {
                    let x = self.real(line)?;
                    table::try_push(&mut self.coords, x)
                        .map_err(|b| (line, no_room("the vertex coordinates")(b)))?;
                }
            }
            return self.end("$EndNodes");
        }
        self.enter_binary_block();
        let blocks = self.count("the node block count", line)?;
        let n = self.count("the node count", line)?;
        self.count("the minimum node tag", line)?;
        self.count("the maximum node tag", line)?;
        self.reserve(n, 8 + 24, line)?;
        for _ in 0..blocks {
            let (dim, _) = self.int(4, "an entity dimension", line)?;
            self.int(4, "an entity tag", line)?;
            let (parametric, l) = self.int(4, "the parametric flag", line)?;
            let k = self.count("the block's node count", line)?;
            for _ in 0..k {
                let (tag, l) = self.int(8, "a node tag", line)?;
                self.node(tag, l)?;
            }
            let extra = if parametric == 1 {
                usize::try_from(dim).map_err(|_| (l, syntax("negative entity dimension")))?
            } else {
                0
            };
            for _ in 0..k {
                for _ in 0..3 {
                    let x = self.real(line)?;
                    table::try_push(&mut self.coords, x)
                        .map_err(|b| (line, no_room("the vertex coordinates")(b)))?;
                }
                for _ in 0..extra {
                    self.real(line)?;
                }
            }
        }
        self.end("$EndNodes")
    }

    /// Reserves for `n` items of at least `bytes` bytes each (2 in ASCII), capped by the input.
    fn reserve(&mut self, n: usize, bytes: usize, line: u32) -> Res<()> {
        let per = if self.inp.binary { bytes } else { 2 };
        let n = n.min(self.inp.left() / per + 1);
        self.tags
            .try_reserve(n)
            .map_err(|_| (line, no_room("the node tags")(n.saturating_mul(24))))?;
        table::try_reserve_exact(&mut self.coords, n * 3)
            .map_err(|b| (line, no_room("the vertex coordinates")(b)))
    }

    /// One element: its node tags mapped to vertex ids, and its tags (`physical`, at most
    /// [`Reader::physical_width`], and `geometrical`).
    fn element(
        &mut self,
        (tag, t, line): (i64, i64, u32),
        nodes: &[i64],
        physical: &[i32],
        geometrical: i32,
    ) -> Res<()> {
        let mut ids = [0u32; 4];
        for (id, &node) in ids.iter_mut().zip(nodes) {
            *id = u64::try_from(node)
                .ok()
                .and_then(|n| self.tags.get(&n).copied())
                .ok_or_else(|| {
                    (
                        line,
                        syntax(format!(
                            "element {tag} (type {t}) uses node {node}, which $Nodes does not list"
                        )),
                    )
                })?;
        }
        if t == 3 {
            self.raw
                .try_push_polygon(&ids, line, ReadErrorKind::Polygon(4))
                .map_err(|k| (line, k))?;
        } else {
            self.raw
                .try_push(&ids[..nodes.len()], line)
                .map_err(|k| (line, k))?;
        }
        self.elements.push(tag, line)?;
        let room = |b| (line, no_room("the element tags")(b));
        for k in 0..self.physical_width {
            table::try_push(&mut self.physical, physical.get(k).copied().unwrap_or(0))
                .map_err(room)?;
        }
        table::try_push(&mut self.geometrical, geometrical).map_err(room)
    }

    /// A tag that must fit Gmsh's `int`.
    fn tag32(v: i64, what: &str, line: u32) -> Res<i32> {
        i32::try_from(v).map_err(|_| {
            (
                line,
                syntax(format!("{what} {v} does not fit in 32 bits (Gmsh's int)")),
            )
        })
    }

    /// The rest of line `l`, trimmed, as a string in double quotes: what the quotes hold, or a
    /// refusal saying what was `expected` and what was found.
    fn quoted(&mut self, l: u32, expected: impl FnOnce() -> String) -> Res<String> {
        let text = String::from_utf8_lossy(self.inp.rest_of_line());
        let text = text.trim();
        match text.strip_prefix('"').and_then(|t| t.strip_suffix('"')) {
            Some(inside) => Ok(inside.to_string()),
            None => Err((l, syntax(format!("{}, found '{}'", expected(), echo(text))))),
        }
    }

    /// `$PhysicalNames`: a count, then lines `dimension tag "name"`.
    fn physical_names(&mut self, line: u32) -> Res<()> {
        let binary = std::mem::replace(&mut self.inp.binary, false);
        let n = self.count("the physical name count", line)?;
        for _ in 0..n {
            let (dim, l) = self.int(4, "a physical group's dimension", line)?;
            let (tag, _) = self.int(4, "a physical tag", l)?;
            let dimension = u8::try_from(dim).ok().filter(|&d| d <= 3).ok_or_else(|| {
                (
                    l,
                    syntax(format!("physical group dimension {dim} is not 0 to 3")),
                )
            })?;
            let name = self.quoted(l, || {
                format!("physical group ({dim}, {tag}): expected its name in double quotes")
            })?;
            self.raw.attributes.add_label_name(LabelName {
                attribute: PHYSICAL.into(),
                dimension: Some(dimension),
                label: tag,
                name,
            });
        }
        self.inp.binary = binary;
        self.end("$EndPhysicalNames")
    }

    /// Version 4 `$Entities`: points, curves, surfaces, volumes, each with its physical tags
    /// (bounding boxes and bounding entities skipped).
    fn entities(&mut self, line: u32) -> Res<()> {
        if !self.v4 {
            return self.skip("$Entities", line);
        }
        self.enter_binary_block();
        let mut counts = [0usize; 4];
        for (d, c) in counts.iter_mut().enumerate() {
            *c = self.count(
                [
                    "the point count",
                    "the curve count",
                    "the surface count",
                    "the volume count",
                ][d],
                line,
            )?;
        }
        for (dim, &count) in counts.iter().enumerate() {
            for _ in 0..count {
                let (tag, l) = self.int(4, "an entity tag", line)?;
                for _ in 0..if dim == 0 { 3 } else { 6 } {
                    self.real(l)?;
                }
                let np = self.count("the entity's physical tag count", l)?;
                let mut physical = Vec::new();
                for _ in 0..np.min(self.inp.left()) {
                    let (p, l) = self.int(4, "a physical tag", l)?;
                    physical.push(Self::tag32(p, "physical tag", l)?);
                }
                if dim > 0 {
                    let nb = self.count("the entity's bounding entity count", l)?;
                    for _ in 0..nb.min(self.inp.left()) {
                        self.int(4, "a bounding entity tag", l)?;
                    }
                }
                self.physical_width = self.physical_width.max(physical.len());
                self.entities.insert((dim as i64, tag), physical);
            }
        }
        self.end("$EndEntities")
    }

    fn simplex_len(&self, tag: i64, t: i64, line: u32) -> Res<usize> {
        // A quadrangle (nodes in order around it) kept for --triangulate.
        if t == 3 && self.raw.polygons.keep {
            return Ok(4);
        }
        simplex_len(t).map_err(|name| {
            (
                line,
                syntax(if name.starts_with("type ") {
                    format!(
                        "element {tag} has {name}, not a first-order simplex type (15 point, 1 \
                         line, 2 triangle, 4 tetrahedron)"
                    )
                } else {
                    format!("element {tag} is a {name}, which is not a simplex")
                }),
            )
        })
    }

    fn elements(&mut self, line: u32) -> Res<()> {
        if self.v4 {
            return self.elements_v4(line);
        }
        let m = self.count("the element count", line)?;
        self.enter_binary_block();
        let mut nodes = Vec::with_capacity(4);
        let mut read = 0;
        while read < m {
            // Binary version 2: blocks of one type; ASCII: one element per line.
            let (t, ntags, count) = if self.inp.binary {
                let (t, _) = self.int(4, "an element type", line)?;
                let (k, _) = self.int(4, "the block's element count", line)?;
                let (ntags, _) = self.int(4, "the tag count", line)?;
                let k = usize::try_from(k).map_err(|_| (line, syntax("negative element count")))?;
                (t, ntags, k.min(m - read))
            } else {
                (0, 0, 1)
            };
            for _ in 0..count {
                let (tag, l) = self.int(4, "an element tag", line)?;
                let (t, ntags) = if self.inp.binary {
                    (t, ntags)
                } else {
                    (
                        self.int(4, "an element type", l)?.0,
                        self.int(4, "the tag count", l)?.0,
                    )
                };
                let len = self.simplex_len(tag, t, l)?;
                // Tags: physical, elementary, then partition data (skipped).
                let mut tags = [0i32; 2];
                for k in 0..ntags.max(0) {
                    let (v, l) = self.int(4, "an element tag", l)?;
                    if let Some(slot) = tags.get_mut(k as usize) {
                        let what = ["physical tag", "elementary tag"][k as usize];
                        *slot = Self::tag32(v, what, l)?;
                    }
                }
                nodes.clear();
                for _ in 0..len {
                    nodes.push(self.int(4, "a node tag", l)?.0);
                }
                self.element((tag, t, l), &nodes, &tags[..1], tags[1])?;
            }
            read += count.max(1);
        }
        self.end("$EndElements")
    }

    fn elements_v4(&mut self, line: u32) -> Res<()> {
        self.enter_binary_block();
        let blocks = self.count("the element block count", line)?;
        let declared = self.count("the element count", line)?;
        for what in ["the minimum element tag", "the maximum element tag"] {
            self.count(what, line)?;
        }
        let mut nodes = Vec::with_capacity(4);
        let mut total = 0usize;
        for _ in 0..blocks {
            let (dim, _) = self.int(4, "an entity dimension", line)?;
            let (entity, l) = self.int(4, "an entity tag", line)?;
            let geometrical = Self::tag32(entity, "entity tag", l)?;
            let physical = self
                .entities
                .get(&(dim, entity))
                .cloned()
                .unwrap_or_default();
            let (t, l) = self.int(4, "an element type", line)?;
            let k = self.count("the block's element count", line)?;
            total = total.saturating_add(k);
            for _ in 0..k {
                let (tag, l) = self.int(8, "an element tag", l)?;
                let len = self.simplex_len(tag, t, l)?;
                nodes.clear();
                for _ in 0..len {
                    nodes.push(self.int(8, "a node tag", l)?.0);
                }
                self.element((tag, t, l), &nodes, &physical, geometrical)?;
            }
        }
        if total != declared {
            return Err((
                line,
                syntax(format!(
                    "$Elements declares {declared} elements but its {blocks} blocks hold {total}"
                )),
            ));
        }
        self.end("$EndElements")
    }

    /// Skips a section to its `$End...` keyword.
    fn skip(&mut self, keyword: &str, line: u32) -> Res<()> {
        let end = format!("$End{}", &keyword[1..]);
        let rest = &self.inp.b[self.inp.pos..];
        let at = rest
            .windows(end.len())
            .position(|w| w == end.as_bytes())
            .ok_or_else(|| (line, syntax(format!("{keyword} has no {end}"))))?;
        // Lines are not counted across a skipped section that may hold binary data; count the
        // newlines anyway so that later ASCII errors stay close.
        let skipped = &rest[..at + end.len()];
        let newlines = skipped.iter().filter(|&&b| b == b'\n').count();
        self.inp.line = self.inp.line.saturating_add(newlines as u32);
        self.inp.pos += skipped.len();
        Ok(())
    }
}

/// Parses a Gmsh MSH file, version 2.2 or 4.1, ASCII or binary.
pub fn parse(bytes: &[u8]) -> Res<RawInput> {
    parse_keeping(bytes, false)
}

/// [`parse`], keeping quadrangles (type 3) as polygons when `polygons` (for
/// [`super::ReadOptions::triangulate`]).
pub(crate) fn parse_keeping(bytes: &[u8], polygons: bool) -> Res<RawInput> {
    let mut inp = Input::new(bytes);
    let v4 = mesh_format(&mut inp)?;
    let mut r = Reader {
        inp,
        v4,
        tags: FxHashMap::default(),
        coords: Vec::new(),
        raw: RawInput::new(),
        physical: Vec::new(),
        geometrical: Vec::new(),
        physical_width: 1,
        entities: FxHashMap::default(),
        elements: data::ElementTags::default(),
        data: Vec::new(),
    };
    r.raw.polygons.keep = polygons;
    r.end("$EndMeshFormat")?;
    r.sections()?;
    r.finish()
}

/// The `$MeshFormat` header up to its end keyword: the version (true for 4.1, false for 2.x),
/// the file type (ASCII or binary, with the endianness check) and the data size.
fn mesh_format(inp: &mut Input) -> Res<bool> {
    let (kw, l) = inp.expect_token("$MeshFormat")?;
    if kw != "$MeshFormat" {
        return Err((l, syntax(format!("expected $MeshFormat, found '{kw}'"))));
    }
    let (version, l) = inp.expect_token("the version")?;
    let v4 = match version {
        "4.1" => true,
        v if v.starts_with("2.") => false,
        v => {
            return Err((
                l,
                syntax(format!(
                    "unsupported MSH version '{v}' (2.x and 4.1 are read)"
                )),
            ));
        }
    };
    let (ft, l) = inp.expect_token("the file type")?;
    let (ds, _) = inp.expect_token("the data size")?;
    inp.binary = match ft {
        "0" => false,
        "1" => true,
        _ => {
            return Err((
                l,
                syntax(format!("file type '{ft}' is neither 0 (ASCII) nor 1")),
            ));
        }
    };
    if ds != "8" {
        return Err((l, syntax(format!("data size '{ds}' is not 8"))));
    }
    if inp.binary {
        inp.rest_of_line();
        if inp.take(4) != Some(&1i32.to_le_bytes()[..]) {
            return Err((
                l + 1,
                syntax("binary MSH is not little-endian (or is truncated)"),
            ));
        }
    }
    Ok(v4)
}

impl Reader<'_> {
    /// Every section after the header, in file order: nodes and elements once each (nodes
    /// first), names, entities and data sections; per-element-node data refused; unknown
    /// sections skipped to their end keyword.
    fn sections(&mut self) -> Res<()> {
        let r = self;
        let (mut seen_nodes, mut seen_elements) = (false, false);
        while let Some((kw, l)) = r.inp.token() {
            match kw {
                "$Nodes" if seen_nodes => return Err((l, syntax("a second $Nodes section"))),
                "$Nodes" => {
                    r.nodes(l)?;
                    seen_nodes = true;
                }
                "$Elements" if !seen_nodes => {
                    return Err((l, syntax("$Elements before $Nodes")));
                }
                "$Elements" => {
                    r.elements(l)?;
                    seen_elements = true;
                }
                "$PhysicalNames" => r.physical_names(l)?,
                "$Entities" => r.entities(l)?,
                "$NodeData" if !seen_nodes => {
                    return Err((l, syntax("$NodeData before $Nodes")));
                }
                "$NodeData" => r.data_section(true, l, seen_elements)?,
                "$ElementData" => r.data_section(false, l, seen_elements)?,
                "$ElementNodeData" => {
                    return Err((
                        l,
                        syntax(format!(
                            "{kw}: Gmsh per-element-node data is not read (no attribute holds \
                             it), and reading the mesh without it would drop it; remove the \
                             section to read the mesh alone"
                        )),
                    ));
                }
                k if k.starts_with('$') && !k.starts_with("$End") && k.len() > 1 => {
                    let k = k.to_string();
                    r.skip(&k, l)?;
                }
                k => return Err((l, syntax(format!("unexpected '{k}' between sections")))),
            }
        }
        Ok(())
    }

    /// The input once every section is read: the nodes' count and coordinates, the physical
    /// and elementary tags as attributes (kept unless equal to what the writer writes without
    /// them, physical 0 and elementary 1, so that nothing is lost either way) and the data
    /// sections'.
    fn finish(self) -> Res<RawInput> {
        let r = self;
        let n = u32::try_from(r.tags.len()).map_err(|_| (0, syntax("more than 2^32 nodes")))?;
        let mut raw = r.raw;
        raw.vertex_count = Some(n);
        raw.coords = Some(Coords {
            dim: 3,
            data: r.coords,
        });
        let (physical, geometrical) = (r.physical, r.geometrical);
        if physical.iter().any(|&p| p != 0) || !raw.attributes.label_names().is_empty() {
            raw.attributes.insert(Attribute {
                name: PHYSICAL.into(),
                location: Location::Listed,
                components: r.physical_width,
                values: Values::I32(physical),
            });
        }
        if geometrical.iter().any(|&g| g != 1) {
            raw.attributes.insert(Attribute::labels(
                GEOMETRICAL,
                Location::Listed,
                geometrical,
            ));
        }
        data::attributes(r.data, &mut raw.attributes);
        Ok(raw)
    }
}

/// Writes `raw` as MSH 2.2 or 4.1, ASCII or binary (little-endian).
pub(crate) fn write(
    raw: &RawInput,
    v4: bool,
    binary: bool,
    out: &mut Vec<u8>,
) -> Result<(), String> {
    check_fits(
        raw,
        4,
        "points, edges, triangles and tetrahedra (use .simplices)",
    )?;
    let n = vertex_count(raw);
    let m = raw.simplex_count();
    if !v4 && (n > i32::MAX as usize || m > i32::MAX as usize) {
        return Err("more than 2^31 nodes or elements (use version 4.1)".into());
    }
    let tags = Tags::of(raw, v4)?;
    let mut w = Writer { out, binary };
    w.format(v4);
    w.physical_names(raw);
    if v4 {
        w.entities(&tags);
    }
    w.nodes(raw, n, v4, tags.node_entity);
    w.elements(raw, v4, &tags);
    w.data_sections(raw);
    Ok(())
}

/// The tags the writer gives each element: physical (`gmsh:physical`, else 0) and elementary
/// (`gmsh:geometrical`; else in version 4 one entity per physical tag and dimension, numbered
/// from 1 in order of appearance; else 1), and, in version 4, the `$Entities` they make.
struct Tags {
    physical: Vec<i32>,
    elementary: Vec<i32>,
    /// (dimension, entity tag, physical tag) in order of first use; empty when the file has no
    /// physical tag (then no `$Entities` section is written).
    entities: Vec<(usize, i32, i32)>,
    /// The entity of the node block: the first highest-dimensional element's.
    node_entity: (i32, i32),
}

impl Tags {
    fn of(raw: &RawInput, v4: bool) -> Result<Tags, String> {
        let m = raw.simplex_count();
        let labels = |name| {
            raw.attributes.get(name, Location::Listed).map(|a| {
                (0..m)
                    .map(|i| a.label(i).unwrap_or(0) as i32)
                    .collect::<Vec<i32>>()
            })
        };
        let given = labels(GEOMETRICAL);
        let physical = labels(PHYSICAL).unwrap_or_else(|| vec![0; m]);
        let has_physical = raw.attributes.get(PHYSICAL, Location::Listed).is_some();
        let elementary = match given {
            Some(g) => g,
            None if v4 && has_physical => {
                let mut numbers: FxHashMap<(usize, i32), i32> = FxHashMap::default();
                let mut next = [1i32; 4];
                (0..m)
                    .map(|i| {
                        let d = raw.simplex(i).len() - 1;
                        *numbers.entry((d, physical[i])).or_insert_with(|| {
                            next[d] += 1;
                            next[d] - 1
                        })
                    })
                    .collect()
            }
            None => vec![1; m],
        };
        let mut entities: Vec<(usize, i32, i32)> = Vec::new();
        if v4 && has_physical {
            let mut seen: FxHashMap<(usize, i32), (i32, usize)> = FxHashMap::default();
            for i in 0..m {
                let d = raw.simplex(i).len() - 1;
                match seen.get(&(d, elementary[i])) {
                    Some(&(p, first)) if p != physical[i] => {
                        return Err(format!(
                            "simplices {first} and {i} of the listing are in entity ({d}, {}) \
                             with different '{PHYSICAL}' labels {p} and {}: MSH 4.1 keeps \
                             physical groups per entity (write msh2, or give the entities apart \
                             in '{GEOMETRICAL}')",
                            elementary[i], physical[i]
                        ));
                    }
                    Some(_) => {}
                    None => {
                        seen.insert((d, elementary[i]), (physical[i], i));
                        entities.push((d, elementary[i], physical[i]));
                    }
                }
            }
        }
        let top = (0..m).max_by_key(|&i| (raw.simplex(i).len(), std::cmp::Reverse(i)));
        let node_entity = match top {
            Some(i) if !entities.is_empty() => ((raw.simplex(i).len() - 1) as i32, elementary[i]),
            _ => (3, 1),
        };
        Ok(Tags {
            physical,
            elementary,
            entities,
            node_entity,
        })
    }
}

/// The runs of consecutive simplices of `raw` of equal length and elementary tag, as
/// `(start, end)`.
fn equal_length_runs(raw: &RawInput, elementary: &[i32]) -> Vec<(usize, usize)> {
    let mut runs: Vec<(usize, usize)> = Vec::new();
    for i in 0..raw.simplex_count() {
        match runs.last_mut() {
            Some((start, end))
                if raw.simplex(*start).len() == raw.simplex(i).len()
                    && elementary[*start] == elementary[i] =>
            {
                *end = i + 1
            }
            _ => runs.push((i, i + 1)),
        }
    }
    runs
}

impl Writer<'_> {
    /// The `$MeshFormat` section (with the binary byte-order int).
    fn format(&mut self, v4: bool) {
        let version = if v4 { "4.1" } else { "2.2" };
        self.out.extend_from_slice(
            format!("$MeshFormat\n{version} {} 8\n", u8::from(self.binary)).as_bytes(),
        );
        if self.binary {
            self.out.extend_from_slice(&1i32.to_le_bytes());
            self.out.push(b'\n');
        }
        self.out.extend_from_slice(b"$EndMeshFormat\n");
    }

    /// `$PhysicalNames` (always ASCII), when `raw` names physical tags: a name without a
    /// dimension is written for each dimension whose elements carry its tag.
    fn physical_names(&mut self, raw: &RawInput) {
        let at = &raw.attributes;
        let physical = at.get(PHYSICAL, Location::Listed);
        let mut rows: Vec<(u8, i64, &str)> = Vec::new();
        for n in at.label_names().iter().filter(|n| n.attribute == PHYSICAL) {
            match n.dimension {
                Some(d) => rows.push((d, n.label, &n.name)),
                None => {
                    for d in 0..=3u8 {
                        let used = physical.is_some_and(|a| {
                            (0..raw.simplex_count()).any(|i| {
                                raw.simplex(i).len() == usize::from(d) + 1
                                    && a.label(i) == Some(n.label)
                            })
                        });
                        if used {
                            rows.push((d, n.label, &n.name));
                        }
                    }
                }
            }
        }
        if rows.is_empty() {
            return;
        }
        self.out
            .extend_from_slice(format!("$PhysicalNames\n{}\n", rows.len()).as_bytes());
        for (d, label, name) in rows {
            self.out
                .extend_from_slice(format!("{d} {label} \"{name}\"\n").as_bytes());
        }
        self.out.extend_from_slice(b"$EndPhysicalNames\n");
    }

    /// Version 4 `$Entities` with each entity's physical tag (bounding boxes zero, no bounding
    /// entities: Gmsh reads such discrete entities).
    fn entities(&mut self, tags: &Tags) {
        if tags.entities.is_empty() {
            return;
        }
        let mut counts = [0u64; 4];
        for &(d, _, _) in &tags.entities {
            counts[d] += 1;
        }
        self.out.extend_from_slice(b"$Entities\n");
        self.sizes(&counts);
        for dim in 0..4 {
            for &(_, tag, p) in tags.entities.iter().filter(|e| e.0 == dim) {
                self.ints(&[tag]);
                self.reals_open(&vec![0.0; if dim == 0 { 3 } else { 6 }]);
                let physical: &[i32] = if p == 0 {
                    &[]
                } else {
                    std::slice::from_ref(&p)
                };
                self.sizes_open(&[physical.len() as u64]);
                self.ints(physical);
                if dim > 0 {
                    self.sizes_open(&[0]);
                }
                self.line();
            }
        }
        self.close_block();
        self.out.extend_from_slice(b"$EndEntities\n");
    }

    /// The `$Nodes` section: the `n` vertices, tagged 1..=n, with 3 coordinates each (0 where
    /// `raw` has fewer), in one block of entity `entity` in version 4.
    fn nodes(&mut self, raw: &RawInput, n: usize, v4: bool, entity: (i32, i32)) {
        self.out.extend_from_slice(b"$Nodes\n");
        if v4 {
            self.sizes(&[1, n as u64, 1, n as u64]);
            self.ints(&[entity.0, entity.1, 0]);
            self.sizes(&[n as u64]);
            for v in 0..n {
                self.sizes(&[v as u64 + 1]);
            }
        } else {
            self.out.extend_from_slice(format!("{n}\n").as_bytes());
        }
        let coords = raw.coords.as_ref();
        for v in 0..n {
            if !v4 {
                self.ints_open(&[v as i64 + 1]);
            }
            let p: Vec<f64> = (0..3)
                .map(|k| {
                    coords
                        .filter(|c| k < c.dim)
                        .map_or(0.0, |c| c.data[v * c.dim + k])
                })
                .collect();
            self.reals(&p);
        }
        self.close_block();
        self.out.extend_from_slice(b"$EndNodes\n");
    }

    /// The `$Elements` section: the simplices of `raw`, tagged 1..=m, a block per run of equal
    /// length and elementary tag (version 4, binary version 2).
    fn elements(&mut self, raw: &RawInput, v4: bool, tags: &Tags) {
        let m = raw.simplex_count();
        let binary = self.binary;
        self.out.extend_from_slice(b"$Elements\n");
        let runs = equal_length_runs(raw, &tags.elementary);
        if v4 {
            self.sizes(&[runs.len() as u64, m as u64, 1, m as u64]);
        } else {
            self.out.extend_from_slice(format!("{m}\n").as_bytes());
        }
        for &(start, end) in &runs {
            let len = raw.simplex(start).len();
            let t = element_type(len);
            if v4 {
                self.ints(&[len as i32 - 1, tags.elementary[start], t]);
                self.sizes(&[(end - start) as u64]);
            } else if binary {
                self.ints(&[t, (end - start) as i32, 2]);
            }
            for i in start..end {
                let ids = raw.simplex(i).iter().map(|&v| u64::from(v) + 1);
                if v4 {
                    let row: Vec<u64> = std::iter::once(i as u64 + 1).chain(ids).collect();
                    self.sizes(&row);
                } else {
                    // Tags: physical, elementary; the type is in the block header in binary.
                    let (p, e) = (i64::from(tags.physical[i]), i64::from(tags.elementary[i]));
                    let head: &[i64] = if binary {
                        &[p, e]
                    } else {
                        &[i64::from(t), 2, p, e]
                    };
                    let row: Vec<i64> = std::iter::once(i as i64 + 1)
                        .chain(head.iter().copied())
                        .chain(ids.map(|x| x as i64))
                        .collect();
                    self.ints_open(&row);
                    self.line();
                }
            }
        }
        self.close_block();
        self.out.extend_from_slice(b"$EndElements\n");
    }
}

/// Numbers in ASCII (space-separated, one record per line) or little-endian binary.
struct Writer<'a> {
    out: &'a mut Vec<u8>,
    binary: bool,
}

impl Writer<'_> {
    /// A record of size_t values (a whole line in ASCII).
    fn sizes(&mut self, xs: &[u64]) {
        for (i, x) in xs.iter().enumerate() {
            if self.binary {
                self.out.extend_from_slice(&x.to_le_bytes());
            } else {
                if i > 0 {
                    self.out.push(b' ');
                }
                self.out.extend_from_slice(x.to_string().as_bytes());
            }
        }
        self.line();
    }

    /// Numbers that more numbers follow on the same ASCII line: `le` gives a number's
    /// little-endian bytes, `text` writes it in ASCII.
    fn open<T: Copy, const N: usize>(
        &mut self,
        xs: &[T],
        le: fn(T) -> [u8; N],
        text: fn(&mut Vec<u8>, T),
    ) {
        for &x in xs {
            if self.binary {
                self.out.extend_from_slice(&le(x));
            } else {
                text(self.out, x);
                self.out.push(b' ');
            }
        }
    }

    /// A record of ints, then a size_t follows on the same line in ASCII.
    fn ints(&mut self, xs: &[i32]) {
        self.open(xs, i32::to_le_bytes, |o, x| {
            o.extend_from_slice(x.to_string().as_bytes())
        });
    }

    /// Ints (version 2) that more numbers follow on the same ASCII line.
    fn ints_open(&mut self, xs: &[i64]) {
        for (i, &x) in xs.iter().enumerate() {
            if self.binary {
                self.out.extend_from_slice(&(x as i32).to_le_bytes());
            } else {
                if i > 0 {
                    self.out.push(b' ');
                }
                self.out.extend_from_slice(x.to_string().as_bytes());
            }
        }
        if !self.binary {
            self.out.push(b' ');
        }
    }

    /// Size_t values that more numbers follow on the same ASCII line.
    fn sizes_open(&mut self, xs: &[u64]) {
        self.open(xs, u64::to_le_bytes, |o, x| {
            o.extend_from_slice(x.to_string().as_bytes())
        });
    }

    /// Reals that more numbers follow on the same ASCII line.
    fn reals_open(&mut self, xs: &[f64]) {
        self.open(xs, f64::to_le_bytes, push_f64);
    }

    /// Node coordinates: a whole line in ASCII.
    fn reals(&mut self, xs: &[f64]) {
        for (i, &x) in xs.iter().enumerate() {
            if self.binary {
                self.out.extend_from_slice(&x.to_le_bytes());
            } else {
                if i > 0 {
                    self.out.push(b' ');
                }
                push_f64(self.out, x);
            }
        }
        self.line();
    }

    fn line(&mut self) {
        if !self.binary {
            if self.out.last() == Some(&b' ') {
                self.out.pop();
            }
            self.out.push(b'\n');
        }
    }

    /// The newline that ends a binary block before its `$End` keyword.
    fn close_block(&mut self) {
        if self.binary {
            self.out.push(b'\n');
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn simplices(r: &RawInput) -> Vec<Vec<u32>> {
        (0..r.simplex_count())
            .map(|i| r.simplex(i).to_vec())
            .collect()
    }

    #[test]
    fn version_2_sparse_node_tags_map_to_file_order() {
        //   node tags 10, 30, 20 are vertices 0, 1, 2; triangle 10 20 30 is [0 2 1], and the
        //   point element on node 30 is [1]
        let text = "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$PhysicalNames\n1\n2 1 \"x\"\n\
                    $EndPhysicalNames\n$Nodes\n3\n10 0 0 0\n30 1 0 0\n20 0 1 0\n$EndNodes\n\
                    $Elements\n2\n1 2 2 0 1 10 20 30\n2 15 2 0 1 30\n$EndElements\n";
        let r = parse(text.as_bytes()).unwrap();
        assert_eq!(r.vertex_count, Some(3));
        assert_eq!(simplices(&r), [vec![0, 2, 1], vec![1]]);
        assert_eq!(r.lines, [16, 17]);
        assert_eq!(r.coords.unwrap().data[3..6], [1.0, 0.0, 0.0]);
    }

    #[test]
    fn version_4_skips_parametric_coordinates() {
        //   one block of 2 parametric nodes on a curve (1 parameter each), one line element
        let text = "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n1 2 5 6\n1 1 1 2\n5\n6\n\
                    0 0 0 0.25\n1 0 0 0.75\n$EndNodes\n$Elements\n1 1 1 1\n1 1 1 1\n1 6 5\n\
                    $EndElements\n";
        let r = parse(text.as_bytes()).unwrap();
        assert_eq!(simplices(&r), [vec![1, 0]]);
        assert_eq!(r.coords.unwrap().data, [0.0, 0.0, 0.0, 1.0, 0.0, 0.0]);
    }

    #[test]
    fn errors_name_the_element_and_its_line() {
        let nodes = "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n1\n1 0 0 0\n$EndNodes\n";
        let e =
            parse(format!("{nodes}$Elements\n1\n7 5 0 1 1 1 1 1 1 1 1\n$EndElements\n").as_bytes())
                .unwrap_err();
        assert_eq!(e.0, 10);
        assert_eq!(
            e.1.to_string(),
            "element 7 is a hexahedron, which is not a simplex"
        );
        let e = parse(b"$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Elements\n0\n$EndElements\n")
            .unwrap_err();
        assert_eq!(
            (e.0, e.1.to_string()),
            (4, "$Elements before $Nodes".to_string())
        );
    }
}
