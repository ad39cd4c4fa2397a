//! Quadric-error edge-contraction simplification of any simplicial complex.

pub mod quadric;
