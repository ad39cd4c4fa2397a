//! Topoplex: compact topological data structures for arbitrary simplicial complexes —
//! non-manifold, mixed-dimensional, any dimension — behind one relation API ([`Topology`],
//! [`Navigate`]). The C ABI is the crate `topoplex-ffi`, the command-line tool `topoplex-cli`.
//!
//! # The family, and how to choose
//! A [`Complex`] is read from a file ([`Complex::from_path`], or any input path with
//! [`store::open_complex`]) or made from arrays ([`Complex::from_arrays`]); [`build`] then makes
//! one of the structures of De Floriani, Hui and colleagues' survey ([`StructureKind`]):
//!
//! | kind | type | domain | strength |
//! |---|---|---|---|
//! | `ig` | [`structures::ig::IncidenceGraph`] | any | every relation from stored rows |
//! | `sig` | [`structures::sig::Sig`] | any | the IG's answers in less space |
//! | `ia` | [`structures::ia::IndexedAdjacency`] | pseudo-manifolds | the most compact; adjacency stored |
//! | `iqm` | [`structures::iqm::Iqm`] | any | decomposition into quasi-manifold parts |
//! | `nmia` | [`structures::nmia::NonManifoldIa`] | any | the IA extended to non-manifold stars |
//! | `ts`, `pe`, `le`, `de` | [`structures::ts`], [`structures::pe`], [`structures::le`], [`structures::de`] | dimension ≤ 2 | radial order around edges |
//! | `iastar` | [`live::LiveComplex`] | any | editable: insert, remove, contract, split, `compact()` |
//!
//! Each structure's module doc states what it encodes, its storage and the cost of each
//! relation. Queries take `&self` and may run from many threads at once; [`Navigate::locate`]
//! finds a simplex once, then walks go handle to handle ([`SimplexHandle`], [`VertexId`],
//! [`TopId`]). [`store`] saves a complex and a structure as `.tpx` and maps them back zero-copy;
//! [`simplify`] decimates through the live complex; [`decompose`] writes the IQM's parts.
//!
//! ```
//! use topoplex::{Complex, StructureKind, build};
//! // Two triangles sharing an edge, and a dangling edge: a mixed-dimensional complex.
//! let c = Complex::from_arrays(5, &[0, 1, 2, 1, 2, 3, 3, 4], &[0, 3, 6, 8], None).unwrap();
//! let ig = build(StructureKind::Ig, &c).unwrap();
//! // R_{1,2}: the triangles around the edge [1 2], as rows of ascending ids.
//! let mut out = Vec::new();
//! ig.query(&[1, 2], 2, &mut out).unwrap();
//! assert_eq!(out, [0, 1, 2, 1, 2, 3]);
//! ig.validate().unwrap();
//! ```
//!
//! # Floors
//! Each module imports only from the floors below it (ARCHITECTURE.md; `tests/layers.rs`
//! fails on a climb): tools ([`error`], [`alloc`], [`sys`], [`parallel`], [`mapped`]), the
//! model ([`complex`]), [`io`], the relation API ([`relation`]), the section codec
//! ([`codec`]), [`structures`], the live mesh ([`live`]), the kind registry ([`family`]),
//! [`store`], and the algorithms ([`decompose`], [`simplify`]). Every message that leaves the
//! library is bounded and escaped by [`error::escape`].

#![deny(unsafe_code)]
#![warn(missing_docs)]

// Tools.
pub mod alloc;
pub mod error;
pub mod mapped;
pub mod parallel;
#[doc(hidden)]
pub mod scratch;
pub mod sys;
pub(crate) mod union_find;
// The model and io.
pub mod complex;
pub mod io;
// The relation API.
pub mod relation;
pub use relation::handle;
// The structures, the live mesh and the registry of kinds.
pub mod codec;
pub mod family;
pub mod live;
pub mod structures;
// The saved file and the algorithms.
pub mod decompose;
pub mod simplify;
pub mod store;
// Test support: the brute-force oracle, fixtures and test hooks (not part of the API).
#[doc(hidden)]
pub mod fixtures;
#[doc(hidden)]
pub mod oracle;
#[doc(hidden)]
pub mod testing;

pub use complex::{Budget, Complex, ComplexError};
pub use family::build;
pub use handle::{Fans, Navigate, Order, RelationView, SimplexHandle, TopId, VertexId, Vertices};
pub use relation::BuildError;
pub use relation::{QueryError, Storage, StructureKind, Topology};
