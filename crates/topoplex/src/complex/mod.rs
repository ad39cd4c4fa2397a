//! The input model: a simplicial complex given by its top simplices.
//!
//! # Input rules (a contract other tools rely on)
//! - A complex is given by simplices of any dimension `0..=MAX_DIMENSION` over vertex ids `0..n`.
//!   The complex is the closure of the given simplices; its *top* simplices are those that are
//!   not a proper face of another.
//! - A simplex listed twice, or listed together with one of its cofaces, is *absorbed*: counted
//!   in [`InputStats`] and reported by `topoplex report`, never an error.
//! - A simplex with a repeated vertex, with a vertex id `>= n`, with no vertex, or with more than
//!   `MAX_DIMENSION + 1` vertices is an error naming the file, line and simplex.
//! - Every id in `0..n` is a vertex; one that no simplex uses is an isolated vertex (a top
//!   0-simplex). A complex with no vertex at all is refused.
//! - Where the input does not declare its vertices (a `.simplices` file without `v` lines), n is
//!   max id + 1, up to [`MAX_IMPLIED_VERTICES`]; a larger id is an error naming the simplex
//!   (declare the vertices instead), so a few bytes cannot demand gigabytes.
//! - Vertex ids are the 0-based position of the vertex in the file.
//! - The closure may not outgrow the input beyond a [`Budget`]: a few bytes of high-dimensional
//!   simplices (or a vertex count with nothing behind it) would otherwise expand into gigabytes.
//!   By default the closure may have `max(2^20, 64 × input size)` simplices, the input size
//!   being the number of listed vertex ids plus the number of declared vertices (vertices a file
//!   lists, or given with coordinates through the API). The check uses an upper bound on the
//!   closure (`n + Σ_top (2^{p+1} − p − 2)`, computed in time linear in the top simplices, before
//!   anything of closure size is allocated); when that bound is above the limit but within 16
//!   times it, the closure's faces are counted exactly (work: the bound; memory: the faces at
//!   one vertex), so heavily shared high-dimensional inputs are not refused for faces they do
//!   not have. Every structure built from an accepted complex is bounded too: each is linear in
//!   the closure. Above it, [`ComplexError::TooLarge`] names
//!   the bound and the limit; [`Budget::max_simplices`] (CLI `--max-simplices`, C ABI
//!   `tpx_complex_from_*_budget`) raises or lowers it. Memory that the input's size asks for is
//!   reserved fallibly: a failed reservation is [`ComplexError::OutOfMemory`], not an abort.
//!
//! # Numbering
//! Top p-simplices are numbered `0..` in ascending lexicographic order of their ascending vertex
//! ids ([`SimplexTable`]); the same order numbers all p-simplices in [`Complex::closure`].
//!
//! # Layout
//! One job a file, each adding its `impl Complex`:
//! - this file: the type, its errors, the [`Budget`] and the accessors;
//! - `normalise.rs`: the constructors ([`Complex::from_raw`], [`Complex::from_arrays`], ...):
//!   checks, sorting, the budget check, repeats and faces absorbed;
//! - `listing.rs`: the simplices as listed and the listing ↔ top maps
//!   ([`Complex::input_simplex`], [`Complex::input_top`], [`Complex::top_listing`]);
//! - `closure.rs`: [`Complex::closure`] (by vertex blocks in `blocks.rs`) and the closure's
//!   bound and exact count that the budget check uses;
//! - `table.rs`: [`SimplexTable`] and the fallible reservations; `input.rs`: what readers
//!   produce ([`RawInput`], [`Coords`]).

use std::fmt;
use std::path::{Path, PathBuf};

use crate::error::ReadError;

pub mod attributes;
mod blocks;
mod closure;
mod input;
mod listing;
mod normalise;
pub mod table;
pub use attributes::{
    Attribute, AttributeError, Attributes, LabelName, Location, ValueType, Values,
};
pub(crate) use blocks::Want;
pub(crate) use input::PlainTables;
pub use input::{Coords, RawInput};
use listing::Listing;
pub use table::{SimplexTable, is_subset, push_facet, push_facets, sort_dedup_rows, write_facets};

/// Highest simplex dimension accepted. The closure of one 15-simplex has 65,535 simplices, which
/// every incidence-based structure stores; beyond that the count doubles per dimension.
pub const MAX_DIMENSION: usize = 15;

/// Most vertices a file may imply without declaring them (a `.simplices` file without `v`
/// lines has vertices 0..=max id, mostly isolated if the ids are sparse).
pub const MAX_IMPLIED_VERTICES: u32 = 1 << 24;

/// Smallest closure the default [`Budget`] always allows, in simplices (16 disjoint 15-simplices;
/// every structure stays well under a gigabyte at this size).
pub const BUDGET_FLOOR: u64 = 1 << 20;

/// Closure simplices the default [`Budget`] allows per unit of input size (a listed vertex id or
/// a declared vertex). Triangle and tetrahedral meshes need about 1.3 and 2.9 (by the upper
/// bound); a top p-simplex alone needs `(2^{p+1} − p − 2)/(p + 1)`: 56 at p = 8, 101 at p = 9,
/// 4,095 at p = 15 — so inputs made mostly of simplices of dimension ≥ 9 need the floor or an
/// explicit budget.
pub const BUDGET_RATIO: u64 = 64;

/// How large a complex an input may expand into (see the module documentation).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Budget {
    /// Most simplices the closure may have (see the module documentation for how it is
    /// checked); `None` for the default rule
    /// `max(BUDGET_FLOOR, BUDGET_RATIO × input size)`.
    pub max_simplices: Option<u64>,
}

impl Budget {
    /// No limit (the caller takes responsibility for the memory).
    pub const UNLIMITED: Budget = Budget {
        max_simplices: Some(u64::MAX),
    };

    /// The limit for an input of `input_size` listed ids and declared vertices.
    pub fn limit(&self, input_size: u64) -> u64 {
        self.max_simplices
            .unwrap_or_else(|| BUDGET_FLOOR.max(BUDGET_RATIO.saturating_mul(input_size)))
    }
}

/// Where a simplex came from: a file line, or its position in an array given through the API.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Origin {
    /// The file the simplex was read from (`None` for arrays).
    pub file: Option<PathBuf>,
    /// 1-based line in `file` (0 when not from a file).
    pub line: u32,
    /// 0-based position among the input simplices.
    pub index: usize,
}

impl fmt::Display for Origin {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match &self.file {
            Some(p) => write!(f, "{}:{}", crate::error::echo_path(p), self.line),
            None => write!(f, "input simplex #{}", self.index),
        }
    }
}

fn show(ids: &[u32]) -> String {
    // A simplex has at most 16 vertices; a longer list comes from the input and is cut, so that
    // a million-id line does not make a megabyte message (docs/bad-input.md).
    const SHOWN: usize = MAX_DIMENSION + 2;
    let v: Vec<String> = ids.iter().take(SHOWN).map(|i| i.to_string()).collect();
    if ids.len() > SHOWN {
        format!("[{} … ({} ids)]", v.join(" "), ids.len())
    } else {
        format!("[{}]", v.join(" "))
    }
}

/// Why an input could not become a complex. Vertex ids in messages are 0-based positions.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ComplexError {
    /// The file could not be read or parsed.
    #[error(transparent)]
    Read(#[from] ReadError),
    /// A simplex lists one vertex twice.
    #[error("{origin}: simplex {} repeats vertex {vertex}", show(.simplex))]
    RepeatedVertex {
        /// Where the simplex was given.
        origin: Origin,
        /// The simplex as given.
        simplex: Vec<u32>,
        /// The repeated vertex id.
        vertex: u32,
    },
    /// A simplex uses a vertex id `>= n`.
    #[error("{origin}: simplex {} uses vertex {vertex}, but the complex has {n} vertices (ids 0..{n})", show(.simplex))]
    VertexOutOfRange {
        /// Where the simplex was given.
        origin: Origin,
        /// The simplex as given.
        simplex: Vec<u32>,
        /// The out-of-range id.
        vertex: u32,
        /// The number of vertices.
        n: u32,
    },
    /// A simplex has more than `MAX_DIMENSION + 1` vertices.
    #[error("{origin}: simplex {} has dimension {dim}, above the supported maximum {max}", show(.simplex))]
    DimensionTooHigh {
        /// Where the simplex was given.
        origin: Origin,
        /// The simplex as given.
        simplex: Vec<u32>,
        /// Its dimension.
        dim: usize,
        /// The supported maximum ([`MAX_DIMENSION`]).
        max: usize,
    },
    /// Without declared vertices, an id would imply more than [`MAX_IMPLIED_VERTICES`] vertices.
    #[error("{origin}: simplex {} uses vertex {vertex}, which would make {} vertices (without `v` lines the vertices are 0..=max id); above {max} vertices, declare them with `v` lines", show(.simplex), *.vertex as u64 + 1)]
    ImpliedVertexCount {
        /// Where the simplex was given.
        origin: Origin,
        /// The simplex as given.
        simplex: Vec<u32>,
        /// The largest id.
        vertex: u32,
        /// The limit ([`MAX_IMPLIED_VERTICES`]).
        max: u32,
    },
    /// A simplex with no vertex.
    #[error("{origin}: simplex with no vertex")]
    EmptySimplex {
        /// Where the simplex was given.
        origin: Origin,
    },
    /// The input has no vertex at all.
    #[error("{}complex has no vertices", .file.as_ref().map(|p| format!("{}: ", crate::error::echo_path(p))).unwrap_or_default())]
    NoVertices {
        /// The file, if the input came from one.
        file: Option<PathBuf>,
    },
    /// An attribute does not fit the vertices or the listing.
    #[error("{}{error}", .file.as_ref().map(|p| format!("{}: ", crate::error::echo_path(p))).unwrap_or_default())]
    Attribute {
        /// What does not fit.
        error: AttributeError,
        /// The file, if the input came from one.
        file: Option<PathBuf>,
    },
    /// The coordinate array does not match the vertex count.
    #[error("coordinates: {0}")]
    Coordinates(String),
    /// The closure could exceed the [`Budget`].
    #[error("{}the closure could have up to {bound} simplices from an input of size {input_size} (listed vertex ids + declared vertices), above the budget of {limit} (default: max(2^20, 64 × input size)); raise it with --max-simplices (C ABI: tpx_complex_from_*_budget)", .file.as_ref().map(|p| format!("{}: ", crate::error::echo_path(p))).unwrap_or_default())]
    TooLarge {
        /// The file, if the input came from one.
        file: Option<PathBuf>,
        /// Upper bound on the closure's simplices: n + Σ over top p-simplices of their faces
        /// of dimension ≥ 1.
        bound: u64,
        /// The budget's limit for this input.
        limit: u64,
        /// Listed vertex ids plus declared vertices.
        input_size: u64,
    },
    /// Memory that the input's size asks for could not be reserved.
    #[error("{}out of memory: cannot reserve {bytes} bytes for {what}", .file.as_ref().map(|p| format!("{}: ", crate::error::echo_path(p))).unwrap_or_default())]
    OutOfMemory {
        /// The file, if the input came from one.
        file: Option<PathBuf>,
        /// What the memory was for.
        what: &'static str,
        /// How much was asked for.
        bytes: u64,
    },
}

/// What normalisation absorbed.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, serde::Serialize)]
pub struct InputStats {
    /// Simplices as given (including absorbed ones).
    pub input_simplices: usize,
    /// Simplices listed more than once: each extra listing counts one.
    pub absorbed_duplicates: usize,
    /// Listed simplices that are a proper face of another listed simplex.
    pub absorbed_faces: usize,
}

/// A normalised complex: vertex count, optional coordinates, top simplices by dimension.
#[derive(Debug, Clone)]
pub struct Complex {
    n_vertices: u32,
    /// Always a fully initialised value (`dim` 0 when the input has no coordinates) rather than
    /// an `Option`: optimised code may read `dim` before testing an `Option`'s niche, which
    /// valgrind's memcheck then reports as a jump on uninitialised memory.
    coords: Coords,
    /// `tops[p]`: the top p-simplices, `p = 0..=dimension`.
    tops: Vec<SimplexTable>,
    stats: InputStats,
    source: Option<PathBuf>,
    /// The simplices as listed: order and vertex order (winding) exactly as given.
    listing: Listing,
    /// Named data on the vertices and the listed simplices ([`attributes`]).
    attributes: Attributes,
}

impl Complex {
    /// Names the file the complex came from (a reopened saved complex names its first source).
    pub(crate) fn set_source(&mut self, source: Option<PathBuf>) {
        self.source = source;
    }

    /// Number of vertices n (vertex ids are `0..n`).
    pub fn vertex_count(&self) -> u32 {
        self.n_vertices
    }

    /// Dimension d of the complex: the highest dimension of a top simplex.
    pub fn dimension(&self) -> usize {
        self.tops.len() - 1
    }

    /// Vertex coordinates, when the input has them.
    pub fn coords(&self) -> Option<&Coords> {
        (self.coords.dim > 0).then_some(&self.coords)
    }

    /// Replaces the vertex coordinates by `data`: `dim` numbers per vertex, vertex after vertex
    /// (`vertex_count() × dim` finite numbers, `dim ≥ 1`; a complex without coordinates gains
    /// them), so that an application moves vertices without rebuilding the complex. Refused with
    /// [`ComplexError::Coordinates`] naming the problem (wrong length, `dim` 0, the first
    /// non-finite number with its vertex), nothing changed. Structures built before keep what
    /// they were built with (TS, PE, LE, DE order edges by angle at build). O(n·dim); no
    /// allocation when `dim` is the current one (the array is overwritten in place), else one
    /// reserved fallibly (`ComplexError::OutOfMemory`).
    pub fn set_coords(&mut self, dim: usize, data: &[f64]) -> Result<(), ComplexError> {
        let n = self.n_vertices as usize;
        if dim == 0 || Some(data.len()) != n.checked_mul(dim) {
            return Err(ComplexError::Coordinates(format!(
                "{} numbers given for {n} vertices of dimension {dim}: expected {n} × {dim} (dimension at least 1)",
                data.len()
            )));
        }
        if let Some(i) = data.iter().position(|x| !x.is_finite()) {
            return Err(ComplexError::Coordinates(format!(
                "coordinate {} of vertex {} is {}, not a finite number",
                i % dim,
                i / dim,
                data[i]
            )));
        }
        if dim == self.coords.dim {
            self.coords.data.copy_from_slice(data);
            return Ok(());
        }
        let mut fresh = Vec::new();
        fresh
            .try_reserve_exact(data.len())
            .map_err(|_| ComplexError::OutOfMemory {
                file: self.source.clone(),
                what: "coordinates",
                bytes: 8 * data.len() as u64,
            })?;
        fresh.extend_from_slice(data);
        self.coords = Coords { dim, data: fresh };
        Ok(())
    }

    /// What normalisation absorbed (duplicates, faces of other listed simplices).
    pub fn stats(&self) -> InputStats {
        self.stats
    }

    /// The file the complex was read from, if any.
    pub fn source(&self) -> Option<&Path> {
        self.source.as_deref()
    }

    /// The named data on the vertices and the listed simplices ([`attributes`]).
    pub fn attributes(&self) -> &Attributes {
        &self.attributes
    }

    /// The named data, to add, replace or drop attributes: they must still fit
    /// ([`Attributes::check`] against [`Complex::vertex_count`] and [`Complex::input_count`]),
    /// which [`Complex::set_attributes`] checks.
    pub fn take_attributes(&mut self) -> Attributes {
        std::mem::take(&mut self.attributes)
    }

    /// Replaces the named data, checked against the vertices and the listing.
    pub fn set_attributes(&mut self, attributes: Attributes) -> Result<(), ComplexError> {
        attributes
            .check(self.n_vertices as usize, self.input_count())
            .map_err(|error| ComplexError::Attribute {
                error,
                file: self.source.clone(),
            })?;
        self.attributes = attributes;
        Ok(())
    }

    /// Top p-simplices (empty table for `p > dimension`).
    pub fn tops(&self, p: usize) -> &SimplexTable {
        static EMPTY: SimplexTable = SimplexTable::EMPTY;
        self.tops.get(p).unwrap_or(&EMPTY)
    }

    /// Number of top simplices per dimension `0..=d`.
    pub fn top_counts(&self) -> Vec<usize> {
        self.tops.iter().map(SimplexTable::len).collect()
    }
}

/// A xorshift generator for the unit tests' random listings: each call a number below `m`.
#[cfg(test)]
pub(crate) fn xorshift_below(seed: u64) -> impl FnMut(u64) -> u64 {
    let mut x = seed;
    move |m: u64| {
        x ^= x << 13;
        x ^= x >> 7;
        x ^= x << 17;
        x % m
    }
}

/// A random complex over `n` vertices for the unit tests: `rnd(count)` simplices, each of 1 to
/// `max_len` draws `rnd(choices) * spread` (ascending, repeats dropped).
#[cfg(test)]
pub(crate) fn random_complex(
    rnd: &mut impl FnMut(u64) -> u64,
    n: u32,
    count: u64,
    max_len: u64,
    (choices, spread): (u64, u32),
) -> Complex {
    let simplices: Vec<Vec<u32>> = (0..rnd(count))
        .map(|_| {
            let mut s: Vec<u32> = (0..1 + rnd(max_len))
                .map(|_| rnd(choices) as u32 * spread)
                .collect();
            s.sort_unstable();
            s.dedup();
            s
        })
        .collect();
    let refs: Vec<&[u32]> = simplices.iter().map(Vec::as_slice).collect();
    Complex::from_simplices(n, &refs).unwrap()
}
