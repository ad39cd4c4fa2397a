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

use std::fmt;
use std::path::{Path, PathBuf};

use crate::error::ReadError;

mod blocks;
mod input;
pub mod table;
pub(crate) use blocks::Want;
pub use input::{Coords, RawInput};
pub use table::{SimplexTable, is_subset, push_facets, sort_dedup_rows, write_facets};

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
}

/// The input simplices as given, and (computed on first use) which top simplex each became.
///
/// Cost: one copy of the input ids (held for the complex's life), plus an offset (8 bytes) per
/// listed simplex unless all have the same number of vertices (a mesh of one kind of cell:
/// then the offsets are a formula); the listing ↔ top maps cost 12 bytes per listed simplex
/// more, built on first use in O(Σ (p+1) log n_p) by binary search in the top tables.
#[derive(Debug, Clone, Default)]
struct Listing {
    ids: Vec<u32>,
    offsets: Offsets,
    maps: std::sync::OnceLock<ListingMaps>,
}

/// Where each listed simplex's ids start in [`Listing::ids`].
#[derive(Debug, Clone)]
enum Offsets {
    /// `count` simplices of `arity` ids each: simplex `i` starts at `i * arity`.
    Uniform { arity: usize, count: usize },
    /// Simplex `i` is `ids[o[i]..o[i + 1]]` (`o` starts with 0).
    Varied(Vec<usize>),
}

impl Default for Offsets {
    fn default() -> Self {
        Offsets::Uniform { arity: 0, count: 0 }
    }
}

impl Offsets {
    /// The offsets of a reader or caller (`o[0] == 0`, ascending), dropped for the formula when
    /// every simplex has the same length.
    fn from_vec(o: Vec<usize>) -> Offsets {
        let count = o.len().saturating_sub(1);
        let arity = o.get(1).copied().unwrap_or(0);
        let uniform = o.first().is_none_or(|&a| a == 0)
            && arity > 0
            && crate::parallel::map_ranges(o.len(), |r| {
                o[r.clone()].iter().zip(r).all(|(&x, i)| x == i * arity)
            })
            .into_iter()
            .all(|ok| ok);
        if uniform || count == 0 {
            Offsets::Uniform { arity, count }
        } else {
            Offsets::Varied(o)
        }
    }

    /// Number of simplices.
    fn count(&self) -> usize {
        match self {
            Offsets::Uniform { count, .. } => *count,
            Offsets::Varied(o) => o.len().saturating_sub(1),
        }
    }

    /// Where simplex `i` starts (`i == count()`: the ids' end).
    #[inline]
    fn at(&self, i: usize) -> usize {
        match self {
            Offsets::Uniform { arity, .. } => i * arity,
            Offsets::Varied(o) => o[i],
        }
    }
}

#[derive(Debug, Clone, Default)]
struct ListingMaps {
    /// Per listed simplex: its top simplex as (dimension, index), or `NONE_TOP` when absorbed
    /// as a face of another listed simplex.
    top: Vec<(u8, u32)>,
    /// Per dimension p, per top p-simplex: its first listing, `u32::MAX` for an isolated vertex
    /// that no simplex lists.
    first: Vec<Vec<u32>>,
}

const NONE_TOP: (u8, u32) = (u8::MAX, u32::MAX);

/// A top simplex at a vertex: (dimension, row, position of the vertex in the row).
type TopAt = (u8, u32, u8);

impl Complex {
    /// Normalises reader output that the complex may keep under `budget` (`file` names the
    /// source in errors): the simplex list becomes the listing and the coordinates the
    /// complex's, moved rather than copied, which keeps the peak memory of reading and building
    /// down (docs/bad-input.md, "Bounded resources"); the offsets are dropped when every
    /// simplex has the same length, and the line numbers once normalised.
    pub fn from_input(
        mut raw: RawInput,
        file: Option<&Path>,
        budget: Budget,
    ) -> Result<Complex, ComplexError> {
        let coords = raw.coords.take();
        let mut c = Complex::normalise_raw(&raw, file, coords, budget, false)?;
        c.listing.ids = raw.ids;
        c.listing.offsets = Offsets::from_vec(raw.offsets);
        Ok(c)
    }

    /// Normalises reader output under the default [`Budget`]; `file` names the source in errors.
    pub fn from_raw(raw: &RawInput, file: Option<&Path>) -> Result<Complex, ComplexError> {
        Complex::from_raw_with(raw, file, Budget::default())
    }

    /// Normalises reader output under `budget`; `file` names the source in errors. The input
    /// size is the listed ids plus the vertices the file declares.
    pub fn from_raw_with(
        raw: &RawInput,
        file: Option<&Path>,
        budget: Budget,
    ) -> Result<Complex, ComplexError> {
        Complex::normalise_raw(raw, file, raw.coords.clone(), budget, true)
    }

    /// [`Complex::from_raw_with`] with the coordinates given apart; the listing is left empty
    /// unless `copy_listing`.
    fn normalise_raw(
        raw: &RawInput,
        file: Option<&Path>,
        coords: Option<Coords>,
        budget: Budget,
        copy_listing: bool,
    ) -> Result<Complex, ComplexError> {
        let origin = |i: usize| Origin {
            file: file.map(Path::to_path_buf),
            line: raw.lines.get(i).copied().unwrap_or(0),
            index: i,
        };
        let n = match raw.vertex_count {
            Some(n) => n,
            None => {
                // The vertices are 0..=max id: a single large id would otherwise make a tiny
                // file demand gigabytes of isolated vertices.
                let Some((i, &max)) = (0..raw.simplex_count())
                    .flat_map(|i| raw.simplex(i).iter().map(move |v| (i, v)))
                    .max_by_key(|&(_, v)| *v)
                else {
                    return Err(ComplexError::NoVertices {
                        file: file.map(Path::to_path_buf),
                    });
                };
                if max >= MAX_IMPLIED_VERTICES {
                    return Err(ComplexError::ImpliedVertexCount {
                        origin: origin(i),
                        simplex: raw.simplex(i).to_vec(),
                        vertex: max,
                        max: MAX_IMPLIED_VERTICES,
                    });
                }
                max + 1
            }
        };
        let input_size = raw.ids.len() as u64 + raw.vertex_count.map_or(0, u64::from);
        Complex::build(
            n,
            coords,
            raw.simplex_count(),
            |i| raw.simplex(i),
            origin,
            file,
            (budget, input_size),
            if copy_listing {
                ListingSource::Arrays(&raw.ids, &raw.offsets)
            } else {
                ListingSource::None
            },
        )
    }

    /// Builds from arrays under the default [`Budget`]: simplex `i` is
    /// `ids[offsets[i]..offsets[i+1]]`.
    pub fn from_arrays(
        n_vertices: u32,
        ids: &[u32],
        offsets: &[usize],
        coords: Option<Coords>,
    ) -> Result<Complex, ComplexError> {
        Complex::from_arrays_with(n_vertices, ids, offsets, coords, Budget::default())
    }

    /// Builds from arrays under `budget`. The input size is the ids plus, when coordinates are
    /// given, the vertices (a bare vertex count, without coordinates, is not input: a caller
    /// asking for 2^32 isolated vertices must raise the budget).
    pub fn from_arrays_with(
        n_vertices: u32,
        ids: &[u32],
        offsets: &[usize],
        coords: Option<Coords>,
        budget: Budget,
    ) -> Result<Complex, ComplexError> {
        let input_size = ids.len() as u64
            + if coords.is_some() {
                u64::from(n_vertices)
            } else {
                0
            };
        let count = offsets.len().saturating_sub(1);
        let origin = |i| Origin {
            file: None,
            line: 0,
            index: i,
        };
        Complex::build(
            n_vertices,
            coords,
            count,
            |i| &ids[offsets[i]..offsets[i + 1]],
            origin,
            None,
            (budget, input_size),
            ListingSource::Arrays(ids, offsets),
        )
    }

    /// Builds from a list of simplices (tests, fixtures).
    pub fn from_simplices(n_vertices: u32, simplices: &[&[u32]]) -> Result<Complex, ComplexError> {
        let origin = |i| Origin {
            file: None,
            line: 0,
            index: i,
        };
        Complex::build(
            n_vertices,
            None,
            simplices.len(),
            |i| simplices[i],
            origin,
            None,
            (Budget::UNLIMITED, 0),
            ListingSource::Each,
        )
    }

    /// Validates, sorts and absorbs. `(budget, input_size)`: the closure's upper bound is
    /// checked against `budget.limit(input_size)` before anything of closure size is allocated.
    /// The listing is copied from `listing_source` (left empty for the caller to fill when
    /// [`ListingSource::None`]).
    #[allow(clippy::too_many_arguments)]
    fn build<'a>(
        n: u32,
        coords: Option<Coords>,
        count: usize,
        simplex: impl Fn(usize) -> &'a [u32] + Sync,
        origin: impl Fn(usize) -> Origin,
        file: Option<&Path>,
        (budget, input_size): (Budget, u64),
        listing_source: ListingSource<'a>,
    ) -> Result<Complex, ComplexError> {
        let oom = |what: &'static str, bytes: usize| ComplexError::OutOfMemory {
            file: file.map(Path::to_path_buf),
            what,
            bytes: bytes as u64,
        };
        if n == 0 {
            return Err(ComplexError::NoVertices {
                file: file.map(Path::to_path_buf),
            });
        }
        if let Some(c) = &coords
            && c.data.len() != c.dim * n as usize
        {
            return Err(ComplexError::Coordinates(format!(
                "{} numbers given for {n} vertices of dimension {}",
                c.data.len(),
                c.dim
            )));
        }
        // Validate and bucket by dimension; rows are sorted so duplicates become equal rows.
        // Exact sizes up front: growing by doubling would hold up to twice the ids (peak memory).
        let mut totals = [0usize; MAX_DIMENSION + 1];
        for i in 0..count {
            let len = simplex(i).len();
            if (1..=MAX_DIMENSION + 1).contains(&len) {
                totals[len - 1] += len;
            }
        }
        let highest = totals.iter().rposition(|&t| t > 0).map_or(0, |p| p + 1);
        let mut by_dim: Vec<Rows> = totals[..highest]
            .iter()
            .enumerate()
            .map(|(p, &t)| Rows::new(p + 1, t))
            .collect();
        let invalid = |i: usize, why: Invalid| -> ComplexError {
            let origin = origin(i);
            let simplex = simplex(i).to_vec();
            match why {
                Invalid::Empty => ComplexError::EmptySimplex { origin },
                Invalid::TooHigh => ComplexError::DimensionTooHigh {
                    origin,
                    dim: simplex.len() - 1,
                    simplex,
                    max: MAX_DIMENSION,
                },
                Invalid::OutOfRange(vertex) => ComplexError::VertexOutOfRange {
                    origin,
                    simplex,
                    vertex,
                    n,
                },
                Invalid::Repeated(vertex) => ComplexError::RepeatedVertex {
                    origin,
                    simplex,
                    vertex,
                },
            }
        };
        let push = |by_dim: &mut Vec<Rows>, row: &[u32]| {
            by_dim[row.len() - 1]
                .push(row)
                .map_err(|bytes| oom("the input simplices", bytes))
        };
        if crate::parallel::splits(count) {
            sorted_rows_in_parallel(count, n, &simplex, &mut by_dim).map_err(
                |stop| match stop {
                    Stop::Refused(i, why) => invalid(i, why),
                    Stop::NoRoom(bytes) => oom("the input simplices", bytes),
                },
            )?;
        } else {
            let mut sorted = [0u32; MAX_DIMENSION + 1];
            for i in 0..count {
                let row = sorted_row(simplex(i), n, &mut sorted).map_err(|why| invalid(i, why))?;
                push(&mut by_dim, row)?;
            }
        }
        let mut stats = InputStats {
            input_simplices: count,
            ..Default::default()
        };
        let mut tables: Vec<SimplexTable> = Vec::with_capacity(by_dim.len());
        for (p, rows) in by_dim.into_iter().enumerate() {
            let (t, dups) = SimplexTable::try_from_rows(p + 1, rows.ids)
                .map_err(|bytes| oom("sorting the input simplices", bytes))?;
            stats.absorbed_duplicates += dups + rows.absorbed;
            tables.push(t);
        }
        let bound = closure_bound(n, &tables);
        let limit = budget.limit(input_size);
        // The bound ignores shared faces; when it is not far above the limit, count exactly.
        if bound > limit
            && (bound > limit.saturating_mul(EXACT_COUNT_FACTOR)
                || closure_count(n, &tables, limit).is_none())
        {
            return Err(ComplexError::TooLarge {
                file: file.map(Path::to_path_buf),
                bound,
                limit,
                input_size,
            });
        }
        let tops =
            absorb_faces(n, tables, &mut stats).map_err(|bytes| oom("the vertex tables", bytes))?;
        let listing = copy_listing(listing_source, count, &simplex, &totals)
            .map_err(|bytes| oom("the input listing", bytes))?;
        Ok(Complex {
            n_vertices: n,
            coords: coords.unwrap_or(Coords {
                dim: 0,
                data: Vec::new(),
            }),
            tops,
            stats,
            source: file.map(Path::to_path_buf),
            listing,
        })
    }

    /// The listing: its ids, its simplex count and where simplex `i` starts in the ids
    /// (`0..=count`): simplex `i` as given is `ids[at(i)..at(i + 1)]` (saved files keep them so
    /// that the complex is rebuilt exactly).
    pub(crate) fn listing_arrays(&self) -> (&[u32], usize, impl Fn(usize) -> usize + '_) {
        let o = &self.listing.offsets;
        (&self.listing.ids, o.count(), move |i| o.at(i))
    }

    /// Names the file the complex came from (a reopened saved complex names its first source).
    pub(crate) fn set_source(&mut self, source: Option<PathBuf>) {
        self.source = source;
    }

    /// Number of simplices as listed in the input (absorbed ones included).
    pub fn input_count(&self) -> usize {
        self.listing.offsets.count()
    }

    /// Listed simplex `i` exactly as given: its vertex order is the input's winding.
    pub fn input_simplex(&self, i: usize) -> &[u32] {
        let o = &self.listing.offsets;
        &self.listing.ids[o.at(i)..o.at(i + 1)]
    }

    /// Builds the listing ↔ top maps now if their memory (8 bytes a listing, 4 a top simplex)
    /// can be had: `Err(bytes)` otherwise, where the first use would abort.
    pub(crate) fn try_listing_maps(&self) -> Result<(), usize> {
        if self.listing.maps.get().is_none() {
            let tops: usize = self.tops.iter().map(SimplexTable::len).sum();
            let starts = (self.n_vertices as usize + 1) * 4 * self.tops.len();
            table::headroom(self.input_count() * 8 + tops * 4 + starts)?;
            // Another thread may have built them meanwhile: then ours is dropped.
            let _ = self.listing.maps.set(self.build_listing_maps()?);
        }
        Ok(())
    }

    fn listing_maps(&self) -> &ListingMaps {
        self.listing.maps.get_or_init(|| {
            self.build_listing_maps()
                .unwrap_or_else(|bytes| table::abort_for(bytes))
        })
    }

    /// The listing ↔ top maps, every array reserved fallibly (`Err(bytes)`). Each listing is
    /// searched among the top simplices that start with its smallest vertex (a few rows, not
    /// log n_p cache misses), listings on several threads. (Tables small next to the vertex
    /// count are searched whole.) Each top's first listing is the smallest listing that found
    /// it, kept by an atomic minimum on several threads: the same maps for any thread count.
    fn build_listing_maps(&self) -> Result<ListingMaps, usize> {
        let mut starts: Vec<Vec<u32>> = Vec::new();
        table::try_reserve_exact(&mut starts, self.tops.len())?;
        for t in &self.tops {
            // Starts cost O(n): worth it for tables of at least n/4 rows (a Rips complex's few
            // lower-dimensional tops over a million vertices are searched whole).
            starts.push(if t.len() < 64 || t.len() < self.n_vertices as usize / 4 {
                Vec::new()
            } else {
                self.first_vertex_starts(t)?
            });
        }
        // Listings in runs of at least `RUN` on several threads; inside a run each dimension's
        // last answer is tried first (then the row after it): a listing written in
        // lexicographic order, as Rips and alpha makers write it, then costs one compare, not
        // a search. The hint only saves work: the answer is the same without it.
        const RUN: usize = 4096;
        let find = |last: &mut [usize; MAX_DIMENSION + 1], i: usize| {
            let mut sorted = [0u32; MAX_DIMENSION + 1];
            let given = self.input_simplex(i);
            let sorted = &mut sorted[..given.len()];
            sorted.copy_from_slice(given);
            sorted.sort_unstable();
            let p = sorted.len() - 1;
            let (Some(t), Some(start)) = (self.tops.get(p), starts.get(p)) else {
                return NONE_TOP;
            };
            let near = [last[p].wrapping_add(1), last[p]];
            let found = match near
                .into_iter()
                .find(|&j| j < t.len() && t.get(j) == &*sorted)
            {
                Some(j) => Some(j),
                None => find_top(t, start, sorted),
            };
            found.map_or(NONE_TOP, |j| {
                last[p] = j;
                (p as u8, j as u32)
            })
        };
        let top = crate::parallel::try_map_collect_with(
            self.input_count(),
            RUN,
            || [usize::MAX; MAX_DIMENSION + 1],
            find,
        )?;
        drop(starts);
        let mut first: Vec<Vec<std::sync::atomic::AtomicU32>> = Vec::new();
        table::try_reserve_exact(&mut first, self.tops.len())?;
        for t in &self.tops {
            first.push(crate::parallel::try_atomics(t.len(), |_| u32::MAX)?);
        }
        if crate::parallel::splits(top.len()) {
            crate::parallel::map_ranges(top.len(), |range| {
                for i in range {
                    let (p, j) = top[i];
                    if p != u8::MAX {
                        first[p as usize][j as usize]
                            .fetch_min(i as u32, std::sync::atomic::Ordering::Relaxed);
                    }
                }
            });
        } else {
            // One thread: plain words, no atomic instruction per listing.
            for (i, &(p, j)) in top.iter().enumerate() {
                if p != u8::MAX {
                    let f = first[p as usize][j as usize].get_mut();
                    *f = (*f).min(i as u32);
                }
            }
        }
        let first = first.into_iter().map(crate::parallel::into_plain).collect();
        Ok(ListingMaps { top, first })
    }

    /// `start[v]`: the first row of `table` (sorted) whose first vertex is ≥ v, for v in
    /// `0..=n`; vertices in chunks on several threads, each chunk finding its first row by a
    /// binary search and walking on from there.
    fn first_vertex_starts(&self, table: &SimplexTable) -> Result<Vec<u32>, usize> {
        const CHUNK: usize = 4096;
        let mut start = crate::parallel::try_filled(self.n_vertices as usize + 1, 0u32)?;
        crate::parallel::fill_rows(&mut start, CHUNK, |c, part| {
            let v0 = c * CHUNK;
            let (mut row, mut hi) = (0, table.len());
            while row < hi {
                let mid = (row + hi) / 2;
                if (table.get(mid)[0] as usize) < v0 {
                    row = mid + 1;
                } else {
                    hi = mid;
                }
            }
            for (v, slot) in (v0..).zip(part.iter_mut()) {
                while row < table.len() && (table.get(row)[0] as usize) < v {
                    row += 1;
                }
                *slot = row as u32;
            }
        });
        Ok(start)
    }

    /// The top simplex that listed simplex `i` is, as (dimension, index in [`Complex::tops`]);
    /// `None` when it was absorbed as a face of another listed simplex. A repeated listing maps
    /// to the same top simplex as its first listing. First call: O(Σ (p+1) log n_p).
    pub fn input_top(&self, i: usize) -> Option<(usize, u32)> {
        let (p, j) = self.listing_maps().top[i];
        (p != u8::MAX).then_some((p as usize, j))
    }

    /// The first listing of top p-simplex `i`; `None` for an isolated vertex no simplex lists.
    pub fn top_listing(&self, p: usize, i: u32) -> Option<usize> {
        let f = self.listing_maps().first[p][i as usize];
        (f != u32::MAX).then_some(f as usize)
    }

    /// Top p-simplex `i` with its vertices in the order of its first listing (its input
    /// winding); ascending for an isolated vertex no simplex lists.
    pub fn top_oriented(&self, p: usize, i: u32) -> &[u32] {
        match self.top_listing(p, i) {
            Some(l) => self.input_simplex(l),
            None => self.tops(p).get(i as usize),
        }
    }

    /// The top simplices in input order, each once (at its first listing), vertices in input
    /// order, as (listing index, dimension, top index, vertices). Absorbed listings and repeats
    /// are skipped; isolated vertices that no simplex lists are not yielded (every id in
    /// `0..vertex_count` is a vertex).
    pub fn tops_as_given(&self) -> impl Iterator<Item = (usize, usize, u32, &[u32])> + '_ {
        let maps = self.listing_maps();
        (0..self.input_count()).filter_map(move |i| {
            let (p, j) = maps.top[i];
            (p != u8::MAX && maps.first[p as usize][j as usize] as usize == i)
                .then(|| (i, p as usize, j, self.input_simplex(i)))
        })
    }

    /// The top simplices of dimension ≥ 1 as (dimension, vertices in input order), in input
    /// order: those of [`Complex::tops_as_given`], without their indices. When every listed
    /// simplex of two or more vertices is a distinct top simplex (as many as there are top
    /// simplices of dimension ≥ 1: nothing absorbed or repeated), they are the listing itself,
    /// and the listing ↔ top maps (12 bytes a listing) are not built. O(listing).
    pub(crate) fn tops_listed(&self) -> impl Iterator<Item = (usize, &[u32])> + '_ {
        let direct = !self.tops_listed_needs_maps();
        let listing = (0..if direct { self.input_count() } else { 0 })
            .map(|i| self.input_simplex(i))
            .filter(|s| s.len() > 1)
            .map(|s| (s.len() - 1, s));
        let mapped = (!direct)
            .then(|| {
                self.tops_as_given()
                    .filter(|t| t.1 > 0)
                    .map(|(_, p, _, s)| (p, s))
            })
            .into_iter()
            .flatten();
        listing.chain(mapped)
    }

    /// Whether [`Complex::tops_listed`] needs the listing ↔ top maps.
    pub(crate) fn tops_listed_needs_maps(&self) -> bool {
        let tops: usize = self.tops.iter().skip(1).map(SimplexTable::len).sum();
        let listed = (0..self.input_count())
            .filter(|&i| self.listing.offsets.at(i + 1) - self.listing.offsets.at(i) > 1)
            .count();
        tops != listed
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

    /// What normalisation absorbed (duplicates, faces of other listed simplices).
    pub fn stats(&self) -> InputStats {
        self.stats
    }

    /// The file the complex was read from, if any.
    pub fn source(&self) -> Option<&Path> {
        self.source.as_deref()
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

    /// All simplices of the complex by dimension `0..=d`, each table in ascending lexicographic
    /// order (so the p-simplices are numbered by their position). Faces are made per block of
    /// their smallest vertex v, level by level, as ranks among the vertices above v packed in
    /// one word (`blocks.rs`); blocks come out in vertex order, so their concatenation is the
    /// sorted table. Ranges of vertices run on [`crate::parallel::threads`] threads. At most
    /// O(Σ_top 2^{p+1}) time (the closure bound the budget checks), the closure's size in
    /// memory. Where a block's ranks do not fit a word, every subset of each top at its
    /// smallest vertex in global ids, or (ids too wide for d of them) level by level.
    pub fn closure(&self) -> Vec<SimplexTable> {
        self.try_closure().unwrap_or_else(|bytes| {
            std::alloc::handle_alloc_error(
                std::alloc::Layout::array::<u8>(bytes).unwrap_or(std::alloc::Layout::new::<u8>()),
            )
        })
    }

    /// [`Self::closure`] with its memory reserved fallibly: `Err(bytes)` names the reservation
    /// that could not be had (structure builds turn it into `TooLarge`, not an abort).
    pub fn try_closure(&self) -> Result<Vec<SimplexTable>, usize> {
        let d = self.dimension();
        if d > 0
            && let Some(c) = self.closure_by_blocks(Want::Tables)?
        {
            return Ok(c.tables);
        }
        self.closure_by_words()
    }

    /// The closure from every subset of each top simplex at its smallest vertex, as global ids
    /// packed in words (level by level when d of them do not fit one): the path for blocks
    /// whose ranks do not fit a word.
    fn closure_by_words(&self) -> Result<Vec<SimplexTable>, usize> {
        let d = self.dimension();
        let bits = table::id_bits(self.n_vertices.saturating_sub(1));
        if d == 0 || d as u32 * bits > 64 {
            return self.closure_by_levels();
        }
        // The buckets grow by doubling pushes on worker threads (up to 3× their size while one
        // moves): probe for that over their bound first (every face of every top, repeats and
        // all, as ids), so that a refusal is an error, not an abort.
        let bound: usize = (1..=d)
            .map(|p| {
                self.tops[p]
                    .len()
                    .saturating_mul((p + 1) << p)
                    .saturating_mul(4)
            })
            .fold(0, usize::saturating_add);
        table::headroom(bound.saturating_mul(3))?;
        let (off, at) = self.tops_at_vertices()?;
        let parts = crate::parallel::ranges_by_weight(&off);
        let buckets = crate::parallel::map_chunks(parts.len(), |c| {
            let mut out: Vec<Vec<u32>> = vec![Vec::new(); d + 1];
            let mut keys: Vec<Vec<u64>> = vec![Vec::new(); d + 1];
            for v in parts[c].clone() {
                let tops = at[off[v]..off[v + 1]]
                    .iter()
                    .map(|&(p, j, pos)| &self.tops[p as usize].get(j as usize)[pos as usize + 1..]);
                faces_above(v as u32, tops, bits, &mut keys, &mut out);
            }
            out
        });
        let mut levels = vec![SimplexTable::try_vertices(self.n_vertices)?];
        for q in 1..=d {
            let len: usize = buckets.iter().map(|b| b[q].len()).sum();
            let mut ids = Vec::new();
            ids.try_reserve_exact(len).map_err(|_| len * 4)?;
            for b in &buckets {
                ids.extend_from_slice(&b[q]);
            }
            levels.push(SimplexTable::from_sorted_unique(q + 1, ids));
        }
        Ok(levels)
    }

    /// For each vertex v, the top simplices of dimension ≥ 1 in which v is not the last vertex,
    /// as (dimension, row, position of v): CSR offsets over the vertices, entries.
    fn tops_at_vertices(&self) -> Result<(Vec<usize>, Vec<TopAt>), usize> {
        let n = self.n_vertices as usize;
        let mut off = Vec::new();
        off.try_reserve_exact(n + 1).map_err(|_| (n + 1) * 8)?;
        off.resize(n + 1, 0usize);
        for t in self.tops.iter().skip(1) {
            for s in t.iter() {
                for &v in &s[..s.len() - 1] {
                    off[v as usize + 1] += 1;
                }
            }
        }
        for v in 0..n {
            off[v + 1] += off[v];
        }
        let mut fill = Vec::new();
        fill.try_reserve_exact(n + 1).map_err(|_| (n + 1) * 8)?;
        fill.extend_from_slice(&off);
        let mut at: Vec<TopAt> = Vec::new();
        at.try_reserve_exact(off[n]).map_err(|_| off[n] * 8)?;
        at.resize(off[n], (0u8, 0u32, 0u8));
        for (p, t) in self.tops.iter().enumerate().skip(1) {
            for (j, s) in t.iter().enumerate() {
                for (pos, &v) in s[..s.len() - 1].iter().enumerate() {
                    at[fill[v as usize]] = (p as u8, j as u32, pos as u8);
                    fill[v as usize] += 1;
                }
            }
        }
        Ok((off, at))
    }

    /// The closure level by level from the facets of the level above: O(Σ_p (p+1) n_p log n_p)
    /// time, the closure's size in memory. The same tables as [`Complex::closure`], for ids too
    /// wide to pack.
    fn closure_by_levels(&self) -> Result<Vec<SimplexTable>, usize> {
        let d = self.dimension();
        let mut levels: Vec<SimplexTable> = vec![SimplexTable::default(); d + 1];
        levels[d] = self.tops[d].try_clone()?;
        for p in (0..d).rev() {
            if p == 0 {
                levels[0] = SimplexTable::try_vertices(self.n_vertices)?;
                break;
            }
            let above = &levels[p + 1];
            // The facets of each (p+1)-simplex at a fixed place: written on several threads.
            let w = (p + 2) * (p + 1);
            let len = above.len() * w + self.tops[p].as_flat().len();
            let mut rows = Vec::new();
            rows.try_reserve_exact(len).map_err(|_| len * 4)?;
            rows.resize(len, 0u32);
            let (facets, listed) = rows.split_at_mut(above.len() * w);
            crate::parallel::fill_rows(facets, w, |i, out| write_facets(above.get(i), out));
            listed.copy_from_slice(self.tops[p].as_flat());
            levels[p] = SimplexTable::try_from_rows(p + 1, rows)?.0;
        }
        if d == 0 {
            levels[0] = SimplexTable::try_vertices(self.n_vertices)?;
        }
        Ok(levels)
    }
}

/// Appends to `out[q]` (rows of q + 1 ids) the q-simplices whose smallest vertex is `v`, in
/// ascending order: every nonempty subset of each of `tops` (the vertices above v in a top
/// simplex at v, ascending), packed `bits` per id, sorted and deduplicated per dimension.
fn faces_above<'a>(
    v: u32,
    tops: impl Iterator<Item = &'a [u32]>,
    bits: u32,
    keys: &mut [Vec<u64>],
    out: &mut [Vec<u32>],
) {
    for k in keys.iter_mut() {
        k.clear();
    }
    for above in tops {
        for mask in 1u32..1 << above.len() {
            let mut key = 0u64;
            for (i, &x) in above.iter().enumerate() {
                if mask >> i & 1 != 0 {
                    key = key << bits | u64::from(x);
                }
            }
            keys[mask.count_ones() as usize].push(key);
        }
    }
    let id_mask = (1u64 << bits) - 1;
    for (q, k) in keys.iter_mut().enumerate().skip(1) {
        k.sort_unstable();
        k.dedup();
        for &key in k.iter() {
            out[q].push(v);
            for i in (0..q).rev() {
                out[q].push((key >> (bits * i as u32) & id_mask) as u32);
            }
        }
    }
}

/// The sorted input rows of one dimension, deduplicated as they come while that pays: a file
/// of many short lines lists the same few simplices over and over (an 8-byte `s 1 2 3` line can
/// only name vertices 0–9), and holding every copy until the final sort would cost 12 bytes a
/// line plus the sort's keys (issue 16 class 5: reading must peak under 5× the file). Each
/// block of [`Rows::BLOCK`] rows is sorted and deduplicated with what is held; once a block
/// removes less than half of the rows, the rest is reserved exactly and kept as is (unique
/// inputs pay one sort of one block).
/// Where [`Complex::build`] copies the listing from.
enum ListingSource<'a> {
    /// Nowhere: the caller moves its own arrays in.
    None,
    /// Simplex by simplex, through the accessor.
    Each,
    /// Arrays in which simplex `i` is `ids[offsets[i]..offsets[i + 1]]`: the simplices are one
    /// run of `ids`, copied whole on several threads.
    Arrays(&'a [u32], &'a [usize]),
}

/// The listing of simplices `0..count` (all checked: 1 to `MAX_DIMENSION + 1` ids each, so
/// `totals`, the ids per length, has one non-zero entry exactly when every simplex has the same
/// length, and the offsets are then a formula). Memory reserved fallibly (`Err(bytes)`).
fn copy_listing<'a>(
    source: ListingSource<'a>,
    count: usize,
    simplex: &impl Fn(usize) -> &'a [u32],
    totals: &[usize],
) -> Result<Listing, usize> {
    let mut listing = Listing::default();
    let id_count: usize = totals.iter().sum();
    let varied = totals.iter().filter(|&&t| t > 0).count() > 1;
    let mut offsets = Vec::new();
    match source {
        ListingSource::None => return Ok(listing),
        ListingSource::Arrays(ids, o) if count > 0 => {
            // Every simplex was sliced out of `ids` by the caller already, so `o[..=count]` is
            // ascending and within `ids`.
            let (base, run) = (o[0], &ids[o[0]..o[count]]);
            listing.ids = crate::parallel::try_map_collect(run.len(), |k| run[k])
                .map_err(|_| id_count * 4)?;
            if varied {
                offsets = crate::parallel::try_map_collect(count + 1, |i| o[i] - base)
                    .map_err(|_| (count + 1) * 8)?;
            }
        }
        _ => {
            if varied {
                table::try_reserve_exact(&mut offsets, count + 1).map_err(|_| (count + 1) * 8)?;
                offsets.push(0);
            }
            table::try_reserve_exact(&mut listing.ids, id_count).map_err(|_| id_count * 4)?;
            for i in 0..count {
                listing.ids.extend_from_slice(simplex(i));
                if varied {
                    offsets.push(listing.ids.len());
                }
            }
        }
    }
    listing.offsets = if varied {
        Offsets::Varied(offsets)
    } else {
        Offsets::Uniform {
            arity: id_count / count.max(1),
            count,
        }
    };
    Ok(listing)
}

/// Why a listed simplex is refused (the error is made with its origin by the caller).
#[derive(Debug, Clone, Copy)]
enum Invalid {
    Empty,
    TooHigh,
    OutOfRange(u32),
    Repeated(u32),
}

/// Simplex `s` checked (1 to `MAX_DIMENSION + 1` vertices, ids below `n`, none repeated) and
/// sorted into `buf`: the sorted row.
#[inline]
fn sorted_row<'b>(
    s: &'b [u32],
    n: u32,
    buf: &'b mut [u32; MAX_DIMENSION + 1],
) -> Result<&'b [u32], Invalid> {
    if s.is_empty() {
        return Err(Invalid::Empty);
    }
    if s.len() > MAX_DIMENSION + 1 {
        return Err(Invalid::TooHigh);
    }
    if s.is_sorted_by(|a, b| a < b) {
        // Ascending as given (Rips and alpha makers write rows so): no repeat, and the first
        // id out of range, if any, is at the end.
        return match s[s.len() - 1] {
            last if last < n => Ok(s),
            _ => Err(Invalid::OutOfRange(
                *s.iter().find(|&&v| v >= n).unwrap_or(&n),
            )),
        };
    }
    if let Some(&v) = s.iter().find(|&&v| v >= n) {
        return Err(Invalid::OutOfRange(v));
    }
    let row = &mut buf[..s.len()];
    row.copy_from_slice(s);
    row.sort_unstable();
    if let Some(w) = row.windows(2).find(|w| w[0] == w[1]) {
        return Err(Invalid::Repeated(w[0]));
    }
    Ok(row)
}

/// Why [`sorted_rows_in_parallel`] stopped: simplex `i` is refused, or memory ran out.
enum Stop {
    Refused(usize, Invalid),
    NoRoom(usize),
}

/// [`sorted_row`] of simplices `0..count` pushed into `by_dim` (by length) on several threads,
/// with the serial loop's result: the same rows, the first refused simplex in input order.
/// While a dimension's rows may still be deduplicated by blocks ([`Rows::push`]), windows of
/// simplices are checked and sorted in ranges on [`crate::parallel::threads`] threads into
/// buffers of the window's size (reserved fallibly), then pushed in order; from where no
/// dimension deduplicates any more (at once for most inputs, after one block for large
/// ones), the rest is written in place ([`rows_in_place`]).
fn sorted_rows_in_parallel<'a>(
    count: usize,
    n: u32,
    simplex: &(impl Fn(usize) -> &'a [u32] + Sync),
    by_dim: &mut [Rows],
) -> Result<(), Stop> {
    const WINDOW: usize = 1 << 18;
    let mut w = 0;
    while w < count {
        if by_dim.iter().all(|r| r.next_dedup == usize::MAX) {
            return rows_in_place(w..count, n, simplex, by_dim);
        }
        let window = w..(w + WINDOW).min(count);
        let parts = crate::parallel::map_ranges(window.len(), |r| {
            let r = (w + r.start)..(w + r.end);
            let ids: usize = r
                .clone()
                .map(|i| simplex(i).len().min(MAX_DIMENSION + 1))
                .sum();
            let mut rows: Vec<u32> = Vec::new();
            table::try_reserve_exact(&mut rows, ids)?;
            let mut buf = [0u32; MAX_DIMENSION + 1];
            for i in r.clone() {
                match sorted_row(simplex(i), n, &mut buf) {
                    Ok(row) => rows.extend_from_slice(row),
                    Err(why) => return Ok((rows, r, Some((i, why)))),
                }
            }
            Ok((rows, r, None))
        });
        for part in parts {
            let (rows, r, refused) = part.map_err(Stop::NoRoom)?;
            let mut at = 0;
            for i in r.start..refused.map_or(r.end, |(i, _)| i) {
                let len = simplex(i).len();
                by_dim[len - 1]
                    .push(&rows[at..at + len])
                    .map_err(Stop::NoRoom)?;
                at += len;
            }
            if let Some((i, why)) = refused {
                return Err(Stop::Refused(i, why));
            }
        }
        w = window.end;
    }
    Ok(())
}

/// The rows of simplices `range` written in place on several threads, once no dimension
/// deduplicates: each dimension's array is reserved at its exact final size (as
/// [`Rows::push`] would) and filled with zeros, every range of simplices counts its rows per
/// dimension, and then sorts its simplices into its own slice of each array.
fn rows_in_place<'a>(
    range: std::ops::Range<usize>,
    n: u32,
    simplex: &(impl Fn(usize) -> &'a [u32] + Sync),
    by_dim: &mut [Rows],
) -> Result<(), Stop> {
    use rayon::prelude::*;
    let ranges: Vec<_> = crate::parallel::ranges(range.len())
        .into_iter()
        .map(|r| (range.start + r.start)..(range.start + r.end))
        .collect();
    let dims = by_dim.len();
    let counts = crate::parallel::map_chunks(ranges.len(), |k| {
        let mut c = [0usize; MAX_DIMENSION + 1];
        for i in ranges[k].clone() {
            let len = simplex(i).len();
            if (1..=dims).contains(&len) {
                c[len - 1] += len;
            }
        }
        c
    });
    let mut tails = Vec::with_capacity(dims);
    for rows in by_dim.iter_mut() {
        let base = rows.ids.len();
        table::try_reserve_exact(&mut rows.ids, rows.left).map_err(Stop::NoRoom)?;
        crate::parallel::extend_filled(&mut rows.ids, rows.left, 0);
        rows.left = 0;
        tails.push(&mut rows.ids[base..]);
    }
    let mut parts = Vec::with_capacity(ranges.len());
    for (c, r) in counts.iter().zip(&ranges) {
        let mine: Vec<&mut [u32]> = tails
            .iter_mut()
            .zip(c)
            .map(|(t, &len)| {
                let (a, b) = std::mem::take(t).split_at_mut(len);
                *t = b;
                a
            })
            .collect();
        parts.push((mine, r.clone()));
    }
    let refused: Vec<Option<(usize, Invalid)>> = crate::parallel::install(|| {
        parts
            .into_par_iter()
            .map(|(mut slices, r)| {
                let mut at = [0usize; MAX_DIMENSION + 1];
                let mut buf = [0u32; MAX_DIMENSION + 1];
                for i in r {
                    match sorted_row(simplex(i), n, &mut buf) {
                        Ok(row) => {
                            let p = row.len() - 1;
                            slices[p][at[p]..at[p] + row.len()].copy_from_slice(row);
                            at[p] += row.len();
                        }
                        Err(why) => return Some((i, why)),
                    }
                }
                None
            })
            .collect()
    });
    match refused.into_iter().flatten().next() {
        Some((i, why)) => Err(Stop::Refused(i, why)),
        None => Ok(()),
    }
}

struct Rows {
    arity: usize,
    ids: Vec<u32>,
    /// Ids still to come for this dimension.
    left: usize,
    /// Row count at which the next block is deduplicated; `usize::MAX` once that stopped.
    next_dedup: usize,
    /// Rows removed as duplicates so far.
    absorbed: usize,
}

impl Rows {
    /// Rows a block holds before it is deduplicated.
    const BLOCK: usize = 1 << 18;

    fn new(arity: usize, total_ids: usize) -> Rows {
        let rows = total_ids / arity;
        let dedup = rows > 2 * Rows::BLOCK;
        Rows {
            arity,
            // Exact reservation unless blocks may shrink it (growth by doubling would hold up
            // to twice the ids).
            ids: Vec::new(),
            left: total_ids,
            next_dedup: if dedup { Rows::BLOCK } else { usize::MAX },
            absorbed: 0,
        }
    }

    /// Appends one sorted row; `Err(bytes)` when memory runs out.
    fn push(&mut self, row: &[u32]) -> Result<(), usize> {
        if self.ids.len() == self.ids.capacity() {
            let want = if self.next_dedup == usize::MAX {
                self.left
            } else {
                (self.next_dedup * self.arity - self.ids.len()).min(self.left)
            };
            self.ids
                .try_reserve_exact(want.max(row.len()))
                .map_err(|_| want * 4)?;
        }
        self.ids.extend_from_slice(row);
        self.left -= row.len();
        if self.next_dedup != usize::MAX && self.ids.len() == self.next_dedup * self.arity {
            self.dedup();
        }
        Ok(())
    }

    /// Sorts and deduplicates what is held; sets the next block's bound, or stops.
    fn dedup(&mut self) {
        let before = self.ids.len() / self.arity;
        let ids = std::mem::take(&mut self.ids);
        self.ids = sort_dedup_rows(self.arity, ids);
        let after = self.ids.len() / self.arity;
        self.absorbed += before - after;
        // Held rows sorted plus a fresh block: continue while blocks halve at least.
        self.next_dedup = if before - after >= Rows::BLOCK / 2 {
            after + Rows::BLOCK
        } else {
            usize::MAX
        };
    }
}

/// Upper bound on the closure's size: every vertex, and every face of dimension ≥ 1 of every
/// listed (deduplicated) simplex, as if no face were shared. O(number of listed simplices).
fn closure_bound(n: u32, tables: &[SimplexTable]) -> u64 {
    let faces = tables.iter().enumerate().skip(1).map(|(p, t)| {
        let per = (1u64 << (p + 1)) - p as u64 - 2;
        (t.len() as u64).saturating_mul(per)
    });
    faces.fold(u64::from(n), u64::saturating_add)
}

/// How far above the budget's limit the closure bound may be for [`closure_count`] to be tried
/// (its work is the bound).
const EXACT_COUNT_FACTOR: u64 = 16;

/// The closure's exact size (every vertex and every distinct face of dimension ≥ 1 of a listed
/// simplex), or `None` once it passes `limit`. Each face is counted at its lowest vertex v: the
/// listed simplices at v give every subset of their vertices above v, told apart by a 64-bit
/// hash of the ids (a collision could only undercount by one in ~2^64). Work: the
/// [`closure_bound`]; memory: the faces at one vertex, plus one entry per listed id.
fn closure_count(n: u32, tables: &[SimplexTable], limit: u64) -> Option<u64> {
    use std::hash::{BuildHasher, Hash, Hasher};
    if u64::from(n) > limit {
        return None;
    }
    // at[v]: (dimension, row) of every listed simplex of dimension ≥ 1 whose vertex v is.
    // Reserved fallibly: under a raised limit n may be large (then the input is refused).
    let mut off: Vec<usize> = Vec::new();
    off.try_reserve_exact(n as usize + 1).ok()?;
    off.resize(n as usize + 1, 0);
    for t in tables.iter().skip(1) {
        for &v in t.as_flat() {
            off[v as usize + 1] += 1;
        }
    }
    for v in 0..n as usize {
        off[v + 1] += off[v];
    }
    let mut fill = off.clone();
    let mut at: Vec<(u8, u32)> = Vec::new();
    at.try_reserve_exact(off[n as usize]).ok()?;
    at.resize(off[n as usize], (0, 0));
    for (p, t) in tables.iter().enumerate().skip(1) {
        for (j, row) in t.iter().enumerate() {
            for &v in row {
                at[fill[v as usize]] = (p as u8, j as u32);
                fill[v as usize] += 1;
            }
        }
    }
    let hasher = rustc_hash::FxBuildHasher;
    let mut faces: rustc_hash::FxHashSet<u64> = Default::default();
    let mut count = u64::from(n);
    for v in 0..n as usize {
        faces.clear();
        for &(p, j) in &at[off[v]..off[v + 1]] {
            let row = tables[p as usize].get(j as usize);
            let above = &row[row.iter().position(|&x| x as usize == v)? + 1..];
            for mask in 1u32..(1 << above.len()) {
                let mut h = hasher.build_hasher();
                for (i, x) in above.iter().enumerate() {
                    if mask & (1 << i) != 0 {
                        x.hash(&mut h);
                    }
                }
                faces.insert(h.finish());
            }
        }
        count += faces.len() as u64;
        if count > limit {
            return None;
        }
    }
    Some(count)
}

/// Row of `sorted` in top table `t`: among the rows that start with its first vertex when
/// `start` holds the first-vertex starts, else in the whole table.
fn find_top(t: &SimplexTable, start: &[u32], sorted: &[u32]) -> Option<usize> {
    if start.is_empty() {
        return t.find(sorted).map(|j| j as usize);
    }
    let v = sorted[0] as usize;
    let (lo, hi) = (start[v] as usize, start[v + 1] as usize);
    let (mut a, mut b) = (lo, hi);
    while a < b {
        let mid = (a + b) / 2;
        if t.get(mid) < sorted {
            a = mid + 1;
        } else {
            b = mid;
        }
    }
    (a < hi && t.get(a) == sorted).then_some(a)
}

/// Drops listed simplices that are faces of higher-dimensional listed ones, and adds the vertices
/// no simplex uses as top 0-simplices. A p-simplex is tested against the listed simplices of
/// higher dimension at its *hub*, its vertex with the fewest listed simplices of dimension ≥ 2:
/// O(Σ_σ min_{v∈σ} deg(v) · d) in all, near linear on meshes (the worst case is many
/// low-dimensional simplices all at one hub vertex). Only the hubs' simplices are gathered
/// (a Rips complex's few low-dimensional tops touch a small part of its stars). Testing against
/// every listed simplex, absorbed or not, gives the verdict of testing against the kept ones: a
/// face of an absorbed simplex is a face of the simplex that absorbed it. The per-vertex arrays
/// are reserved fallibly: `Err(bytes)` when they cannot be had.
fn absorb_faces(
    n: u32,
    mut tables: Vec<SimplexTable>,
    stats: &mut InputStats,
) -> Result<Vec<SimplexTable>, usize> {
    // No listed simplex at all: every vertex is isolated.
    let d = tables.len().max(1) - 1;
    let (degree, used) = degrees(n, &tables)?;
    let used = |v: u32| used[v as usize];
    let hub = |s: &[u32]| *s.iter().min_by_key(|&&v| degree[v as usize]).unwrap();
    let mut kept: Vec<SimplexTable> = vec![SimplexTable::default(); d + 1];
    // Only when some dimension 1..d has simplices to test: a pure mesh never pays for the stars.
    let test = tables
        .get(1..d)
        .is_some_and(|t| t.iter().any(|t| !t.is_empty()));
    if test {
        let stars = HubStars::new(n, &tables, &degree, hub)?;
        for p in (1..d).rev() {
            let t = &tables[p];
            let parts = crate::parallel::map_ranges(t.len(), |r| -> Result<_, usize> {
                let (mut rows, mut absorbed) = (Vec::new(), 0usize);
                for s in r.map(|i| t.get(i)) {
                    // A star lists its simplices by dimension: those above p are its tail.
                    let star = stars.at(hub(s));
                    let above = &star[star.partition_point(|&(q, _)| q as usize <= p)..];
                    let is_face = above
                        .iter()
                        .any(|&(q, j)| is_subset(s, tables[q as usize].get(j as usize)));
                    if is_face {
                        absorbed += 1;
                    } else {
                        table::try_extend(&mut rows, s)?;
                    }
                }
                Ok((rows, absorbed))
            });
            let mut rows = Vec::new();
            for part in parts {
                let (part, absorbed) = part?;
                stats.absorbed_faces += absorbed;
                if rows.is_empty() {
                    rows = part;
                } else {
                    table::try_extend(&mut rows, &part)?;
                }
            }
            // A subsequence of a sorted table is still sorted.
            kept[p] = SimplexTable::from_sorted_unique(p + 1, rows);
        }
    }
    for p in 1..=d {
        if p == d || !test {
            kept[p] = std::mem::take(&mut tables[p]);
        }
    }
    let listed_vertices = tables.first().map_or(0, SimplexTable::len);
    let listed_isolated = tables
        .first()
        .map_or(0, |t| t.iter().filter(|s| !used(s[0])).count());
    stats.absorbed_faces += listed_vertices - listed_isolated;
    let free = (0..n).filter(|&v| !used(v)).count();
    let mut isolated: Vec<u32> = Vec::new();
    isolated.try_reserve_exact(free).map_err(|_| free * 4)?;
    isolated.extend((0..n).filter(|&v| !used(v)));
    kept[0] = SimplexTable::from_sorted_unique(1, isolated);
    // A complex of only isolated vertices has d = 0.
    while kept.len() > 1 && kept.last().unwrap().is_empty() {
        kept.pop();
    }
    Ok(kept)
}

/// Per vertex, the number of listed simplices of dimension ≥ 2 at it (saturating: it only
/// picks hubs), and whether a listed simplex of dimension ≥ 1 uses it — which a kept one then
/// does too (a listed simplex is kept or a face of a kept one). Reserved fallibly.
fn degrees(n: u32, tables: &[SimplexTable]) -> Result<(Vec<u32>, Vec<bool>), usize> {
    let n = n as usize;
    let mut degree: Vec<u32> = Vec::new();
    table::try_reserve_exact(&mut degree, n)?;
    degree.resize(n, 0);
    let mut edge: Vec<bool> = Vec::new();
    table::try_reserve_exact(&mut edge, n)?;
    edge.resize(n, false);
    for (p, t) in tables.iter().enumerate().skip(1) {
        for &v in t.as_flat() {
            if p == 1 {
                edge[v as usize] = true;
            } else {
                degree[v as usize] = degree[v as usize].saturating_add(1);
            }
        }
    }
    for (e, &k) in edge.iter_mut().zip(&degree) {
        *e |= k > 0;
    }
    Ok((degree, edge))
}

/// A listed simplex as (dimension, row in its table).
type Listed = (u8, u32);

/// The listed simplices of dimension ≥ 2 at each hub of a simplex to test (CSR over the hubs,
/// in hub order of first appearance).
struct HubStars {
    /// Per vertex: its hub number, `u32::MAX` when it is no hub.
    slot: Vec<u32>,
    off: Vec<usize>,
    at: Vec<Listed>,
}

impl HubStars {
    /// The stars of the hubs (by `hub`) of the simplices of dimensions 1..d−1 that may be faces
    /// (hubs with a listed simplex of dimension ≥ 2). Reserved fallibly.
    fn new(
        n: u32,
        tables: &[SimplexTable],
        degree: &[u32],
        hub: impl Fn(&[u32]) -> u32,
    ) -> Result<HubStars, usize> {
        let d = tables.len() - 1;
        let mut slot: Vec<u32> = Vec::new();
        table::try_reserve_exact(&mut slot, n as usize)?;
        slot.resize(n as usize, u32::MAX);
        let mut off = vec![0usize];
        for t in &tables[1..d] {
            for s in t.iter() {
                let h = hub(s) as usize;
                if slot[h] == u32::MAX && degree[h] > 0 {
                    if degree[h] == u32::MAX {
                        // Only a saturated count: more listed simplices than memory holds.
                        return Err(usize::MAX);
                    }
                    let end = off[off.len() - 1] + degree[h] as usize;
                    slot[h] = (off.len() - 1) as u32;
                    table::try_push(&mut off, end)?;
                }
            }
        }
        let mut fill: Vec<usize> = Vec::new();
        table::try_reserve_exact(&mut fill, off.len())?;
        fill.extend_from_slice(&off);
        let mut at: Vec<Listed> = Vec::new();
        let len = off[off.len() - 1];
        table::try_reserve_exact(&mut at, len)?;
        at.resize(len, (0, 0));
        for (p, t) in tables.iter().enumerate().skip(2) {
            for (j, s) in t.iter().enumerate() {
                for &v in s {
                    let h = slot[v as usize];
                    if h != u32::MAX {
                        at[fill[h as usize]] = (p as u8, j as u32);
                        fill[h as usize] += 1;
                    }
                }
            }
        }
        Ok(HubStars { slot, off, at })
    }

    /// The listed simplices of dimension ≥ 2 at `v`, by dimension (empty when `v` is no hub).
    fn at(&self, v: u32) -> &[Listed] {
        match self.slot[v as usize] {
            u32::MAX => &[],
            h => &self.at[self.off[h as usize]..self.off[h as usize + 1]],
        }
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

#[cfg(test)]
mod tests {
    use super::*;

    /// Random non-manifold complexes over few vertices (so faces are shared), dimension ≤ 6.
    fn random_complexes() -> impl Iterator<Item = Complex> {
        let mut x = 0x2545_f491_4f6c_dd1du64;
        let mut rnd = move |m: u64| {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            x % m
        };
        (0..300).map(move |_| {
            let n = 1 + rnd(16) as u32;
            let simplices: Vec<Vec<u32>> = (0..rnd(20))
                .map(|_| {
                    let mut s: Vec<u32> = (0..1 + rnd(7)).map(|_| rnd(n as u64) as u32).collect();
                    s.sort_unstable();
                    s.dedup();
                    s
                })
                .collect();
            let refs: Vec<&[u32]> = simplices.iter().map(Vec::as_slice).collect();
            Complex::from_simplices(n, &refs).unwrap()
        })
    }

    /// Normalises a listing by definition: rows sorted, repeats counted, a row that is a
    /// proper subset of another counted as a face, unused vertices isolated.
    fn normalised_by_brute_force(n: u32, listed: &[Vec<u32>]) -> (Vec<Vec<Vec<u32>>>, InputStats) {
        let mut rows: Vec<Vec<u32>> = listed
            .iter()
            .map(|s| {
                let mut s = s.clone();
                s.sort_unstable();
                s
            })
            .collect();
        rows.sort();
        rows.dedup();
        let mut stats = InputStats {
            input_simplices: listed.len(),
            absorbed_duplicates: listed.len() - rows.len(),
            absorbed_faces: 0,
        };
        let mut tops: Vec<Vec<Vec<u32>>> = vec![Vec::new(); MAX_DIMENSION + 1];
        for s in &rows {
            if rows.iter().any(|t| t.len() > s.len() && is_subset(s, t)) {
                stats.absorbed_faces += 1;
            } else {
                tops[s.len() - 1].push(s.clone());
            }
        }
        let used: std::collections::HashSet<u32> = rows.iter().flatten().copied().collect();
        tops[0].extend((0..n).filter(|v| !used.contains(v)).map(|v| vec![v]));
        tops[0].sort();
        while tops.len() > 1 && tops.last().unwrap().is_empty() {
            tops.pop();
        }
        (tops, stats)
    }

    fn tops_of(c: &Complex) -> Vec<Vec<Vec<u32>>> {
        (0..=c.dimension())
            .map(|p| c.tops(p).iter().map(<[u32]>::to_vec).collect())
            .collect()
    }

    fn from_listing(n: u32, listed: &[Vec<u32>]) -> Result<Complex, ComplexError> {
        let ids: Vec<u32> = listed.concat();
        let mut offsets = vec![0];
        for s in listed {
            offsets.push(offsets.last().unwrap() + s.len());
        }
        Complex::from_arrays_with(n, &ids, &offsets, None, Budget::UNLIMITED)
    }

    /// A listing written as Rips and alpha makers write it (rows ascending, in lexicographic
    /// order per dimension: no sort needed) and the same simplices shuffled and reversed (every
    /// row and table sorted) give the tops and counts of the definition — with repeats and
    /// faces of other listed simplices, some shared and mixed in. Large listings (so the
    /// ascending check and the rows split into ranges) and small.
    #[test]
    fn ascending_listings_and_shuffled_ones_normalise_as_by_definition() {
        let mut rnd = crate::complex::xorshift_below(0x51ed_270b_2763_f3a9);
        for case in 0..120 {
            let n = 2 + rnd(if case % 3 == 0 { 400 } else { 12 }) as u32;
            let count = rnd(if case % 10 == 0 { 3000 } else { 40 }) as usize;
            let mut listed: Vec<Vec<u32>> = (0..count)
                .map(|_| {
                    let mut s: Vec<u32> = (0..1 + rnd(6)).map(|_| rnd(n as u64) as u32).collect();
                    s.sort_unstable();
                    s.dedup();
                    s
                })
                .collect();
            // Faces of listed simplices and repeats.
            for i in 0..listed.len() {
                match rnd(5) {
                    0 if listed[i].len() > 1 => {
                        let mut f = listed[i].clone();
                        f.remove(rnd(f.len() as u64) as usize);
                        listed.push(f);
                    }
                    1 => listed.push(listed[i].clone()),
                    _ => {}
                }
            }
            let want = normalised_by_brute_force(n, &listed);
            // As a maker writes it: by dimension, each in order (repeats stay next to each other).
            let mut ascending = listed.clone();
            ascending.sort_by(|a, b| (a.len(), a).cmp(&(b.len(), b)));
            if case % 2 == 0 {
                // Dimensions interleaved; each dimension still in order.
                ascending.sort_by_key(|s| s.len() % 3);
            }
            let mut shuffled = listed.clone();
            for i in (1..shuffled.len()).rev() {
                shuffled.swap(i, rnd(i as u64 + 1) as usize);
                if rnd(2) == 0 {
                    shuffled[i].reverse();
                }
            }
            for given in [&ascending, &shuffled, &listed] {
                let c = from_listing(n, given).unwrap();
                assert_eq!((tops_of(&c), c.stats()), want, "case {case}");
                let back: Vec<Vec<u32>> = (0..c.input_count())
                    .map(|i| c.input_simplex(i).to_vec())
                    .collect();
                assert_eq!(&back, given);
            }
        }
    }

    /// One bad simplex at every position of an ascending listing (so the rows before it took
    /// the ascending path): the error names it as the per-row checks do, and of two bad ones
    /// the first.
    #[test]
    fn a_bad_simplex_anywhere_in_an_ascending_listing_is_the_error() {
        let n = 9u32;
        let good: Vec<Vec<u32>> = (0..7u32).map(|v| vec![v, v + 1, v + 2]).collect();
        let bad: [(Vec<u32>, &str); 6] = [
            (
                vec![1, 4, 9],
                "uses vertex 9, but the complex has 9 vertices",
            ),
            (
                vec![3, 10, 12],
                "uses vertex 10, but the complex has 9 vertices",
            ),
            (
                vec![12, 3, 10],
                "uses vertex 12, but the complex has 9 vertices",
            ),
            (vec![2, 5, 5], "repeats vertex 5"),
            (vec![], "simplex with no vertex"),
            (
                (0..17).collect(),
                "has dimension 16, above the supported maximum 15",
            ),
        ];
        for (b, why) in &bad {
            for at in 0..=good.len() {
                let mut listed = good.clone();
                listed.insert(at, b.clone());
                let e = from_listing(n, &listed).unwrap_err().to_string();
                assert!(
                    e.starts_with(&format!("input simplex #{at}:")) && e.contains(why),
                    "{b:?} at {at}: {e}"
                );
                // A later bad simplex does not hide it.
                listed.push(vec![0, 0]);
                assert_eq!(from_listing(n, &listed).unwrap_err().to_string(), e);
            }
        }
    }

    #[test]
    fn closure_by_vertex_buckets_equals_closure_by_levels() {
        for c in random_complexes() {
            assert_eq!(Ok(c.closure()), c.closure_by_levels());
            assert_eq!(c.closure_by_words(), c.closure_by_levels());
        }
    }

    #[test]
    fn ids_too_wide_to_pack_take_the_level_path() {
        // 2^20 vertices: 20 bits per id, so a 4-simplex's faces need 80 bits.
        let top = [3, 70_000, 500_000, 1_000_000, 1_048_575];
        let c = Complex::from_simplices(1 << 20, &[&top, &[3, 9]]).unwrap();
        let levels = c.closure();
        assert_eq!(Ok(levels.clone()), c.closure_by_levels());
        assert_eq!(levels[1].len(), 10 + 1);
        assert_eq!(levels[4].get(0), &top);
    }

    /// Listings of every kind past one run of the map search: sorted runs of tops, shuffled
    /// windings, repeats, absorbed faces, over few vertices (starts) and many (whole search).
    #[test]
    fn listing_maps_name_the_top_each_listing_became() {
        let mut rnd = crate::complex::xorshift_below(0x9e37_79b9_7f4a_7c15);
        for n in [40u32, 3000, 200_000] {
            let mut listed: Vec<Vec<u32>> = (0..9000)
                .map(|_| {
                    let mut s: Vec<u32> = (0..1 + rnd(5)).map(|_| rnd(n as u64) as u32).collect();
                    s.sort_unstable();
                    s.dedup();
                    s
                })
                .collect();
            listed.sort();
            for i in 0..listed.len() {
                match rnd(6) {
                    0 => listed[i].reverse(),
                    1 => listed.push(listed[i].clone()),
                    _ => {}
                }
            }
            let refs: Vec<&[u32]> = listed.iter().map(Vec::as_slice).collect();
            let c = Complex::from_simplices(n, &refs).unwrap();
            let mut first_seen = std::collections::HashMap::new();
            for (i, given) in listed.iter().enumerate() {
                let mut s = given.clone();
                s.sort_unstable();
                let want = c.tops(s.len() - 1).find(&s).map(|j| (s.len() - 1, j));
                assert_eq!(c.input_top(i), want, "listing {i}: {given:?}");
                let first = *first_seen.entry(s).or_insert(i);
                if let Some((p, j)) = want {
                    assert_eq!(c.top_listing(p, j), Some(first));
                }
            }
            // Built again on 2 and 3 threads, cut into small pieces (runs of listings, chunks
            // of vertex starts, ranges of the first-listing minimum): the same maps.
            let (threads, split) = (crate::parallel::threads(), crate::parallel::MIN_PARALLEL);
            crate::parallel::set_split_threshold(5);
            for t in [2, 3] {
                crate::parallel::set_threads(t);
                let maps = c.build_listing_maps().unwrap();
                assert_eq!(maps.top, c.listing_maps().top, "n = {n}, {t} threads");
                assert_eq!(maps.first, c.listing_maps().first, "n = {n}, {t} threads");
            }
            crate::parallel::set_threads(threads);
            crate::parallel::set_split_threshold(split);
        }
    }

    /// Vertex starts of sorted tables with gaps (vertices starting no row) at the chunks'
    /// edges, found on 1 to 3 threads, against a count of the rows by first vertex.
    #[test]
    fn first_vertex_starts_count_the_rows_before_each_vertex() {
        let mut rnd = crate::complex::xorshift_below(0x2545_f491_4f6c_dd1d);
        let n = 3 * 4096 + 5;
        let skip = |v: u64| (4090..4100).contains(&(v % 4096)) || v < 3 || v + 3 > n;
        let mut rows: Vec<Vec<u32>> = (0..20_000)
            .map(|_| {
                let a = rnd(n - 1);
                vec![a as u32, (a + 1 + rnd(n - 1 - a)) as u32]
            })
            .filter(|r| !skip(u64::from(r[0])))
            .collect();
        rows.sort();
        rows.dedup();
        let refs: Vec<&[u32]> = rows.iter().map(Vec::as_slice).collect();
        let c = Complex::from_simplices(n as u32, &refs).unwrap();
        let table = c.tops(1);
        let mut want = vec![0u32; n as usize + 1];
        for s in table.iter() {
            want[s[0] as usize + 1] += 1;
        }
        for v in 0..n as usize {
            want[v + 1] += want[v];
        }
        let (threads, split) = (crate::parallel::threads(), crate::parallel::MIN_PARALLEL);
        crate::parallel::set_split_threshold(2);
        for t in [1, 2, 3] {
            crate::parallel::set_threads(t);
            assert_eq!(c.first_vertex_starts(table).unwrap(), want, "{t} threads");
        }
        crate::parallel::set_threads(threads);
        crate::parallel::set_split_threshold(split);
    }
}
