//! Topoplex: topological data structures for arbitrary simplicial complexes.
pub mod io;
