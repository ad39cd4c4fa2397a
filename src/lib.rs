//! Topoplex: compact topological data structures for arbitrary simplicial complexes —
//! non-manifold, mixed-dimensional, any dimension — behind one relation API
//! ([`relation::Topology`]) and a C ABI.
//!
//! - [`io`] reads files into raw simplex lists; [`complex`] normalises them into a [`Complex`].
//! - [`structures`] builds any of the family (IG, SIG, IA, IQM, NMIA, TS, PE, LE, DE).
//! - [`live`] is the updatable complex: insertion, removal, edge contraction, vertex split.
//! - [`oracle`] answers every relation by brute force, for tests.
//! - [`report`] is `topoplex report`: census, storage and timings of every structure.
//! - [`error::escape`] is the one escaper: every message that leaves the library is bounded
//!   and escaped by it ([`error::echo`] for quoted input, [`error::one_line`] for the message).
//! - [`store`] saves the complex and a structure as `.tpx` and maps them back zero-copy.
//! - [`ffi`] is the C ABI (`include/topoplex.h`), the only module allowed `unsafe` code.

#![deny(unsafe_code)]
#![warn(missing_docs)]

pub mod alloc;
pub mod complex;
pub mod decompose;
pub mod error;
pub mod family;
#[allow(unsafe_code)]
pub mod ffi;
pub mod fixtures;
pub use relation::handle;
pub mod codec;
pub mod io;
pub mod live;
pub mod mapped;
pub mod oracle;
pub mod parallel;
pub mod relation;
pub mod report;
pub(crate) mod scratch;
pub mod simplify;
pub mod store;
pub mod structures;
pub mod sys;
#[doc(hidden)]
pub mod testing;
pub(crate) mod union_find;

pub use complex::{Budget, Complex, ComplexError};
pub use family::build;
pub use handle::{Fans, Navigate, Order, RelationView, SimplexHandle, TopId, VertexId, Vertices};
pub use relation::BuildError;
pub use relation::{QueryError, Storage, StructureKind, Topology};
