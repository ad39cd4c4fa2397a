//! The root package's integration tests, one module per former `tests/NAME.rs`, in one binary:
//! one link of the core instead of one per file (the test suite's compile time). Run one file's
//! tests with `cargo test --test it NAME::` (e.g. `cargo test --test it bad_input::`).
//!
//! Tests that need a process of their own stay separate binaries in `tests/`: `alloc_free.rs` and
//! `build_oom.rs` install a `#[global_allocator]` (and `build_oom.rs` sets `RLIMIT_AS` and runs
//! itself again), `memory.rs` reads the process's peak RSS, and `parallel.rs` and
//! `parallel_read.rs` set the process-wide thread count and split threshold (each under a lock
//! of its own, which the other modules here would not take).
//!
//! Proptest keeps the regressions of `tests/it/NAME.rs` in `tests/proptest-regressions/NAME.txt`
//! (the directory beside the one holding `main.rs`).

#[path = "../common/mod.rs"]
mod common;

mod attributes;
mod bad_input;
mod cli;
mod complex;
mod formats;
mod gmsh_real;
mod handles;
mod hardening;
mod ia;
mod ig;
mod interop;
mod iqm;
mod live;
mod nmia;
mod readme;
mod report;
mod sig;
mod simplify;
mod store;
mod structures;
mod tpx_cli;
mod tpx_mutations;
mod tri;
