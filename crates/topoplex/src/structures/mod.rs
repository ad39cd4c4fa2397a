//! The structures, one module each, all behind [`crate::relation::Topology`].
//!
//! Every build is linear (up to a log factor) in the closure of its complex, and the closure is
//! bounded when the complex is made ([`crate::complex::Budget`]: by default `max(2^20, 64 ×
//! input size)` simplices), so no input of a few bytes can make a build take gigabytes. A
//! complex made under a raised or unlimited budget builds with the memory its closure needs,
//! and when that memory cannot be had the build is [`BuildError::TooLarge`], never an abort:
//! input-sized arrays are reserved fallibly (`common::try_*`) and steps that allocate inside
//! sorts and walks first check their peak ([`crate::complex::table::headroom`]).

use crate::relation::StructureKind;

pub(crate) mod common;
pub mod de;
pub mod ia;
pub mod ig;
pub mod iqm;
pub mod le;
#[doc(hidden)]
pub mod nav;
pub mod nmia;
pub mod pe;
pub mod radial;
pub mod sig;
pub mod ts;

pub use crate::relation::BuildError;

/// Converts a count to `u32` indexes, or says what overflowed.
pub(crate) fn to_u32(kind: StructureKind, n: usize, what: &str) -> Result<u32, BuildError> {
    u32::try_from(n).map_err(|_| BuildError::TooLarge {
        kind,
        what: format!("{n} {what} exceed 32-bit indexes"),
    })
}
