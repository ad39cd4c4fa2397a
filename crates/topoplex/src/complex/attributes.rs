//! Named data carried with the mesh: integer labels and real fields on the vertices and on the
//! listed simplices, and names for label values (Gmsh `$PhysicalNames`).
//!
//! # Model
//! An [`Attribute`] is a name, a [`Location`], a number of components (1 to
//! [`MAX_COMPONENTS`]) and one flat array of [`Values`] of one type (`i32`, `i64`, `f32`,
//! `f64`), `components` numbers per element, element after element:
//! - [`Location::Vertices`]: one element per vertex id `0..n`;
//! - [`Location::Listed`]: one element per simplex *as listed* (input order, the order of
//!   [`super::Complex::input_simplex`]), whatever became of it: a top simplex, a face the
//!   closure absorbed (a boundary triangle listed with a reference beside its tetrahedra keeps
//!   its reference) or a repeat.
//!
//! Names are those meshio uses (`medit:ref`, `gmsh:physical`, `gmsh:geometrical`, point and
//! cell data names as the file gives them); within one location a name is used once.
//! [`LabelName`]s give a label value of an integer attribute a name, optionally per dimension
//! (a Gmsh physical group is a (dimension, tag) pair).
//!
//! A simplex reaches its data through its vertices: [`super::Complex::listed_index`] gives the
//! first listing of a simplex (a top simplex's first listing, or the first listing of a face
//! that was listed on its own), and [`Attribute::element`] its numbers; a simplex that was
//! never listed has none.
//!
//! # Storage and costs
//! The values' bytes (`components × elements × size of the type`) plus the name, nothing per
//! element beyond them: readers fill the arrays in input order as they read, and the complex
//! moves them in. [`super::Complex::listed_index`] costs a binary search in the top table for a
//! top simplex (the listing ↔ top maps, built on first use, see `listing.rs`) and, for a listed
//! face, a binary search in an index of the absorbed listings (8 bytes + the ids of each
//! absorbed listing, built on first use in O(a log a)).

use crate::error::echo;

/// Largest number of components of one attribute (a 3×3 tensor).
pub const MAX_COMPONENTS: usize = 9;

/// What an attribute's elements are.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, serde::Serialize)]
pub enum Location {
    /// One element per vertex id `0..n`.
    Vertices,
    /// One element per simplex as listed, in input order.
    Listed,
}

impl Location {
    /// `vertices` or `listed simplices`, for messages and `report`.
    pub fn describe(self) -> &'static str {
        match self {
            Location::Vertices => "vertices",
            Location::Listed => "listed simplices",
        }
    }
}

/// The type of an attribute's numbers.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, serde::Serialize)]
pub enum ValueType {
    /// 32-bit integer labels.
    I32,
    /// 64-bit integer labels.
    I64,
    /// 32-bit reals.
    F32,
    /// 64-bit reals.
    F64,
}

impl ValueType {
    /// `i32`, `i64`, `f32` or `f64`.
    pub fn name(self) -> &'static str {
        match self {
            ValueType::I32 => "i32",
            ValueType::I64 => "i64",
            ValueType::F32 => "f32",
            ValueType::F64 => "f64",
        }
    }

    /// Whether the values are integer labels.
    pub fn is_integer(self) -> bool {
        matches!(self, ValueType::I32 | ValueType::I64)
    }
}

/// An attribute's numbers, `components` per element, element after element.
#[derive(Debug, Clone, PartialEq)]
pub enum Values {
    /// 32-bit integer labels.
    I32(Vec<i32>),
    /// 64-bit integer labels.
    I64(Vec<i64>),
    /// 32-bit reals.
    F32(Vec<f32>),
    /// 64-bit reals.
    F64(Vec<f64>),
}

impl Values {
    /// The type of the numbers.
    pub fn value_type(&self) -> ValueType {
        match self {
            Values::I32(_) => ValueType::I32,
            Values::I64(_) => ValueType::I64,
            Values::F32(_) => ValueType::F32,
            Values::F64(_) => ValueType::F64,
        }
    }

    /// How many numbers in all.
    pub fn len(&self) -> usize {
        match self {
            Values::I32(v) => v.len(),
            Values::I64(v) => v.len(),
            Values::F32(v) => v.len(),
            Values::F64(v) => v.len(),
        }
    }

    /// Whether there is no number.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Bytes the numbers take.
    pub fn bytes(&self) -> usize {
        let size = match self {
            Values::I32(_) | Values::F32(_) => 4,
            Values::I64(_) | Values::F64(_) => 8,
        };
        self.len() * size
    }

    /// Number `i` as an `i64` when the values are integers.
    pub fn integer(&self, i: usize) -> Option<i64> {
        match self {
            Values::I32(v) => v.get(i).map(|&x| i64::from(x)),
            Values::I64(v) => v.get(i).copied(),
            _ => None,
        }
    }

    /// Number `i` as an `f64` (exact for every type but `i64` beyond 2^53).
    pub fn real(&self, i: usize) -> Option<f64> {
        match self {
            Values::I32(v) => v.get(i).map(|&x| f64::from(x)),
            Values::I64(v) => v.get(i).map(|&x| x as f64),
            Values::F32(v) => v.get(i).map(|&x| f64::from(x)),
            Values::F64(v) => v.get(i).copied(),
        }
    }

    /// Whether numbers `i` and `j` are the same bits (NaNs with the same payload are equal).
    pub fn same(&self, i: usize, j: usize) -> bool {
        match self {
            Values::I32(v) => v[i] == v[j],
            Values::I64(v) => v[i] == v[j],
            Values::F32(v) => v[i].to_bits() == v[j].to_bits(),
            Values::F64(v) => v[i].to_bits() == v[j].to_bits(),
        }
    }

    /// The numbers at `picks` (each an element index), `components` per element, in order.
    pub fn pick(&self, picks: impl Iterator<Item = usize> + Clone, components: usize) -> Values {
        fn take<T: Copy>(v: &[T], picks: impl Iterator<Item = usize>, c: usize) -> Vec<T> {
            picks
                .flat_map(|i| v[i * c..(i + 1) * c].iter().copied())
                .collect()
        }
        match self {
            Values::I32(v) => Values::I32(take(v, picks, components)),
            Values::I64(v) => Values::I64(take(v, picks, components)),
            Values::F32(v) => Values::F32(take(v, picks, components)),
            Values::F64(v) => Values::F64(take(v, picks, components)),
        }
    }

    /// Whether every number is the same bits as in `other` (NaNs included).
    pub fn bits_eq(&self, other: &Values) -> bool {
        match (self, other) {
            (Values::I32(a), Values::I32(b)) => a == b,
            (Values::I64(a), Values::I64(b)) => a == b,
            (Values::F32(a), Values::F32(b)) => {
                a.len() == b.len() && a.iter().zip(b).all(|(x, y)| x.to_bits() == y.to_bits())
            }
            (Values::F64(a), Values::F64(b)) => {
                a.len() == b.len() && a.iter().zip(b).all(|(x, y)| x.to_bits() == y.to_bits())
            }
            _ => false,
        }
    }
}

/// A number type of [`Values`]: what a new element gets (0 for labels, NaN for reals) and the
/// mean of two (the first for labels).
trait Number: Copy {
    const UNSET: Self;
    fn mean(a: Self, b: Self) -> Self;
}

impl Number for i32 {
    const UNSET: i32 = 0;
    fn mean(a: i32, _: i32) -> i32 {
        a
    }
}

impl Number for i64 {
    const UNSET: i64 = 0;
    fn mean(a: i64, _: i64) -> i64 {
        a
    }
}

impl Number for f32 {
    const UNSET: f32 = f32::NAN;
    fn mean(a: f32, b: f32) -> f32 {
        (a + b) / 2.0
    }
}

impl Number for f64 {
    const UNSET: f64 = f64::NAN;
    fn mean(a: f64, b: f64) -> f64 {
        (a + b) / 2.0
    }
}

/// `$body` with `$v` bound to the values' vector, whatever their type.
macro_rules! each_type {
    ($values:expr, $v:ident => $body:expr) => {
        match $values {
            Values::I32($v) => $body,
            Values::I64($v) => $body,
            Values::F32($v) => $body,
            Values::F64($v) => $body,
        }
    };
}

/// Row operations (a row: the `c` numbers of one element), used by the live complex to keep
/// data beside its slots.
impl Values {
    /// No number, of the same type.
    pub fn empty_like(&self) -> Values {
        each_type!(self, _v => self.pick(std::iter::empty(), 1))
    }

    /// Appends a row: a copy of row `from`, or unset numbers (0 for labels, NaN for reals).
    pub fn push_row(&mut self, c: usize, from: Option<usize>) {
        fn go<T: Number>(v: &mut Vec<T>, c: usize, from: Option<usize>) {
            match from {
                Some(i) => v.extend_from_within(i * c..(i + 1) * c),
                None => v.extend(std::iter::repeat_n(T::UNSET, c)),
            }
        }
        each_type!(self, v => go(v, c, from))
    }

    /// Row `i` as its own one-row values.
    pub fn row(&self, i: usize, c: usize) -> Values {
        self.pick(std::iter::once(i), c)
    }

    /// Sets row `i` from a one-row `row` of the same type (another type is ignored).
    pub fn set_row(&mut self, i: usize, c: usize, row: &Values) {
        match (self, row) {
            (Values::I32(v), Values::I32(r)) => v[i * c..(i + 1) * c].copy_from_slice(r),
            (Values::I64(v), Values::I64(r)) => v[i * c..(i + 1) * c].copy_from_slice(r),
            (Values::F32(v), Values::F32(r)) => v[i * c..(i + 1) * c].copy_from_slice(r),
            (Values::F64(v), Values::F64(r)) => v[i * c..(i + 1) * c].copy_from_slice(r),
            _ => {}
        }
    }

    /// Row `a` becomes the mean of rows `a` and `b` (reals), or stays (labels).
    pub fn merge_rows(&mut self, a: usize, b: usize, c: usize) {
        fn go<T: Number>(v: &mut [T], a: usize, b: usize, c: usize) {
            for k in 0..c {
                v[a * c + k] = T::mean(v[a * c + k], v[b * c + k]);
            }
        }
        each_type!(self, v => go(v, a, b, c))
    }

    /// Sets row `i` from `f64`s (rounded to the type; integers truncated).
    pub fn set_row_f64(&mut self, i: usize, row: &[f64]) {
        let c = row.len();
        match self {
            Values::I32(v) => {
                for (x, &y) in v[i * c..(i + 1) * c].iter_mut().zip(row) {
                    *x = y as i32;
                }
            }
            Values::I64(v) => {
                for (x, &y) in v[i * c..(i + 1) * c].iter_mut().zip(row) {
                    *x = y as i64;
                }
            }
            Values::F32(v) => {
                for (x, &y) in v[i * c..(i + 1) * c].iter_mut().zip(row) {
                    *x = y as f32;
                }
            }
            Values::F64(v) => v[i * c..(i + 1) * c].copy_from_slice(row),
        }
    }

    /// Appends every row of `other` (same type; another type is ignored).
    pub fn append(&mut self, other: &Values) {
        match (self, other) {
            (Values::I32(v), Values::I32(r)) => v.extend_from_slice(r),
            (Values::I64(v), Values::I64(r)) => v.extend_from_slice(r),
            (Values::F32(v), Values::F32(r)) => v.extend_from_slice(r),
            (Values::F64(v), Values::F64(r)) => v.extend_from_slice(r),
            _ => {}
        }
    }
}

/// One named array of data on the vertices or on the listed simplices.
#[derive(Debug, Clone, PartialEq)]
pub struct Attribute {
    /// The name (meshio's: `medit:ref`, `gmsh:physical`, `gmsh:geometrical`, or as the file
    /// gives it).
    pub name: String,
    /// What the elements are.
    pub location: Location,
    /// Numbers per element, 1 to [`MAX_COMPONENTS`].
    pub components: usize,
    /// `components` numbers per element, element after element.
    pub values: Values,
}

impl Attribute {
    /// An attribute of one integer label per element.
    pub fn labels(name: &str, location: Location, values: Vec<i32>) -> Attribute {
        Attribute {
            name: name.to_string(),
            location,
            components: 1,
            values: Values::I32(values),
        }
    }

    /// Number of elements.
    pub fn element_count(&self) -> usize {
        self.values.len() / self.components.max(1)
    }

    /// The numbers of element `i` as `f64`s (see [`Values::real`]); `None` out of range.
    pub fn element(&self, i: usize) -> Option<Vec<f64>> {
        (i < self.element_count()).then(|| {
            (i * self.components..(i + 1) * self.components)
                .filter_map(|k| self.values.real(k))
                .collect()
        })
    }

    /// The label of element `i` (its first component) when the values are integers.
    pub fn label(&self, i: usize) -> Option<i64> {
        (i < self.element_count())
            .then(|| self.values.integer(i * self.components))
            .flatten()
    }

    /// The distinct labels with their element counts, ascending (first components; empty for
    /// reals).
    pub fn label_counts(&self) -> Vec<(i64, usize)> {
        let mut labels: Vec<i64> = (0..self.element_count())
            .filter_map(|i| self.label(i))
            .collect();
        labels.sort_unstable();
        let mut out: Vec<(i64, usize)> = Vec::new();
        for l in labels {
            match out.last_mut() {
                Some((last, n)) if *last == l => *n += 1,
                _ => out.push((l, 1)),
            }
        }
        out
    }

    /// `'name' (on listed simplices, i32 × 1)`, for messages.
    pub fn describe(&self) -> String {
        format!(
            "'{}' (on {}, {} × {})",
            echo(&self.name),
            self.location.describe(),
            self.values.value_type().name(),
            self.components
        )
    }
}

/// A name given to one value of an integer attribute (a Gmsh physical group's name).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct LabelName {
    /// The attribute whose values it names (`gmsh:physical`).
    pub attribute: String,
    /// The dimension of the simplices it names, when the name is per dimension (Gmsh's are).
    pub dimension: Option<u8>,
    /// The label value.
    pub label: i64,
    /// The name.
    pub name: String,
}

/// The attributes of a listing or complex, and the names of label values.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Attributes {
    list: Vec<Attribute>,
    names: Vec<LabelName>,
}

/// Why attributes do not fit their listing (see [`Attributes::check`]).
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("attribute {attribute}: {reason}")]
pub struct AttributeError {
    /// The attribute, as [`Attribute::describe`] gives it.
    pub attribute: String,
    /// What is wrong.
    pub reason: String,
}

impl Attributes {
    /// No attribute.
    pub fn new() -> Attributes {
        Attributes::default()
    }

    /// Whether there is no attribute and no label name.
    pub fn is_empty(&self) -> bool {
        self.list.is_empty() && self.names.is_empty()
    }

    /// The attributes, in the order they were added (the order a file gives them).
    pub fn iter(&self) -> std::slice::Iter<'_, Attribute> {
        self.list.iter()
    }

    /// The attribute called `name` at `location`.
    pub fn get(&self, name: &str, location: Location) -> Option<&Attribute> {
        self.list
            .iter()
            .find(|a| a.name == name && a.location == location)
    }

    /// The first attribute called `name`, on the listed simplices before the vertices.
    pub fn find(&self, name: &str) -> Option<&Attribute> {
        self.get(name, Location::Listed)
            .or_else(|| self.get(name, Location::Vertices))
    }

    /// Adds an attribute; one already called the same at the same location is replaced.
    pub fn insert(&mut self, a: Attribute) {
        match self
            .list
            .iter_mut()
            .find(|b| b.name == a.name && b.location == a.location)
        {
            Some(b) => *b = a,
            None => self.list.push(a),
        }
    }

    /// Builds attributes from a list and label names (not checked: see [`Attributes::check`]).
    pub fn from_parts(list: Vec<Attribute>, names: Vec<LabelName>) -> Attributes {
        Attributes { list, names }
    }

    /// The names of label values.
    pub fn label_names(&self) -> &[LabelName] {
        &self.names
    }

    /// Adds a name for a label value.
    pub fn add_label_name(&mut self, n: LabelName) {
        self.names.push(n);
    }

    /// The name of `label` of attribute `attribute` for simplices of `dimension`.
    pub fn label_name(&self, attribute: &str, dimension: usize, label: i64) -> Option<&str> {
        self.names
            .iter()
            .find(|n| {
                n.attribute == attribute
                    && n.label == label
                    && n.dimension.is_none_or(|d| usize::from(d) == dimension)
            })
            .map(|n| n.name.as_str())
    }

    /// Removes the attributes called `name` (both locations) and the names of their labels;
    /// whether any was there.
    pub fn remove(&mut self, name: &str) -> bool {
        let before = self.list.len() + self.names.len();
        self.list.retain(|a| a.name != name);
        self.names.retain(|n| n.attribute != name);
        before != self.list.len() + self.names.len()
    }

    /// Removes every label name (the labels stay); whether there was any.
    pub fn remove_label_names(&mut self) -> bool {
        let had = !self.names.is_empty();
        self.names.clear();
        had
    }

    /// Removes everything.
    pub fn clear(&mut self) {
        self.list.clear();
        self.names.clear();
    }

    /// Bytes of the values and names.
    pub fn bytes(&self) -> usize {
        self.list
            .iter()
            .map(|a| a.values.bytes() + a.name.len())
            .chain(
                self.names
                    .iter()
                    .map(|n| n.name.len() + n.attribute.len() + 16),
            )
            .sum()
    }

    /// Checks that each attribute has 1..=[`MAX_COMPONENTS`] components and one element per
    /// vertex (`vertices`) or per listed simplex (`listed`), that names are not empty and not
    /// used twice at one location, and that label names name an integer attribute.
    pub fn check(&self, vertices: usize, listed: usize) -> Result<(), AttributeError> {
        for (k, a) in self.list.iter().enumerate() {
            let err = |reason: String| AttributeError {
                attribute: a.describe(),
                reason,
            };
            if a.name.is_empty() {
                return Err(err("the name is empty".into()));
            }
            if !(1..=MAX_COMPONENTS).contains(&a.components) {
                return Err(err(format!(
                    "{} components, expected 1 to {MAX_COMPONENTS}",
                    a.components
                )));
            }
            let want = match a.location {
                Location::Vertices => vertices,
                Location::Listed => listed,
            };
            if a.values.len() != want.saturating_mul(a.components) {
                return Err(err(format!(
                    "{} numbers, but {} {} × {} components need {}",
                    a.values.len(),
                    want,
                    a.location.describe(),
                    a.components,
                    want.saturating_mul(a.components)
                )));
            }
            if self.list[..k]
                .iter()
                .any(|b| b.name == a.name && b.location == a.location)
            {
                return Err(err("the name is used twice".into()));
            }
        }
        for n in &self.names {
            if !self
                .list
                .iter()
                .any(|a| a.name == n.attribute && a.values.value_type().is_integer())
            {
                return Err(AttributeError {
                    attribute: format!("'{}'", echo(&n.attribute)),
                    reason: format!(
                        "label {} is named '{}', but there is no integer attribute of that name",
                        n.label,
                        echo(&n.name)
                    ),
                });
            }
        }
        Ok(())
    }

    /// The attributes kept for a new listing: vertex attributes at `vertices` (old vertex ids,
    /// in the new order) and listed ones at `listed` (old listing indices, in the new order).
    pub fn pick(
        &self,
        vertices: impl Iterator<Item = usize> + Clone,
        listed: impl Iterator<Item = usize> + Clone,
    ) -> Attributes {
        let list = self
            .list
            .iter()
            .map(|a| Attribute {
                name: a.name.clone(),
                location: a.location,
                components: a.components,
                values: match a.location {
                    Location::Vertices => a.values.pick(vertices.clone(), a.components),
                    Location::Listed => a.values.pick(listed.clone(), a.components),
                },
            })
            .collect();
        Attributes {
            list,
            names: self.names.clone(),
        }
    }

    /// Replaces the listed attributes' elements by those at `listed` (old listing indices, in
    /// the new order; an index may repeat), the vertex attributes left as they are. Cost: the
    /// new listed arrays.
    pub fn pick_listed(&mut self, listed: impl Iterator<Item = usize> + Clone) {
        for a in &mut self.list {
            if a.location == Location::Listed {
                a.values = a.values.pick(listed.clone(), a.components);
            }
        }
    }

    /// Whether both hold the same attributes (names, locations, components, types, and every
    /// number's bits) and label names, in any order.
    pub fn bits_eq(&self, other: &Attributes) -> bool {
        self.list.len() == other.list.len()
            && self.list.iter().all(|a| {
                other
                    .get(&a.name, a.location)
                    .is_some_and(|b| a.components == b.components && a.values.bits_eq(&b.values))
            })
            && self.names.len() == other.names.len()
            && self.names.iter().all(|n| other.names.contains(n))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn label_counts_of_a_reference_array() {
        let a = Attribute::labels("medit:ref", Location::Listed, vec![3, 1, 3, 2, 3]);
        assert_eq!(a.label_counts(), vec![(1, 1), (2, 1), (3, 3)]);
        assert_eq!(a.label(4), Some(3));
        assert_eq!(a.label(5), None);
    }

    #[test]
    fn check_names_the_attribute_whose_length_is_wrong() {
        let mut at = Attributes::new();
        at.insert(Attribute::labels(
            "medit:ref",
            Location::Vertices,
            vec![1, 2],
        ));
        assert!(at.check(2, 0).is_ok());
        let e = at.check(3, 0).unwrap_err();
        assert!(e.to_string().contains("'medit:ref'"), "{e}");
        assert!(e.to_string().contains("2 numbers"), "{e}");
    }

    #[test]
    fn a_label_name_without_its_attribute_is_refused() {
        let mut at = Attributes::new();
        at.add_label_name(LabelName {
            attribute: "gmsh:physical".into(),
            dimension: Some(3),
            label: 1,
            name: "volume".into(),
        });
        assert!(at.check(0, 0).is_err());
        at.insert(Attribute::labels("gmsh:physical", Location::Listed, vec![]));
        assert!(at.check(0, 0).is_ok());
        assert_eq!(at.label_name("gmsh:physical", 3, 1), Some("volume"));
        assert_eq!(at.label_name("gmsh:physical", 2, 1), None);
    }

    #[test]
    fn pick_keeps_components_together() {
        let a = Attribute {
            name: "v".into(),
            location: Location::Vertices,
            components: 2,
            values: Values::F64(vec![0.0, 0.5, 1.0, 1.5, 2.0, 2.5]),
        };
        let mut at = Attributes::new();
        at.insert(a);
        let p = at.pick([2, 0].into_iter(), std::iter::empty());
        assert_eq!(
            p.get("v", Location::Vertices).unwrap().values,
            Values::F64(vec![2.0, 2.5, 0.0, 0.5])
        );
    }
}
