//! The structures, one module each, all behind [`crate::relation::Topology`].
//!
//! Every build is linear (up to a log factor) in the closure of its complex, and the closure is
//! bounded when the complex is made ([`crate::complex::Budget`]: by default `max(2^20, 64 ×
//! input size)` simplices), so no input of a few bytes can make a build take gigabytes. A
//! complex made under a raised or unlimited budget builds with the memory its closure needs,
//! and when that memory cannot be had the build is [`BuildError::TooLarge`], never an abort:
//! input-sized arrays are reserved fallibly (`common::try_*`) and steps that allocate inside
//! sorts and walks first check their peak ([`crate::complex::table::headroom`]).

use crate::complex::Complex;
use crate::relation::{StructureKind, Topology};

pub(crate) mod common;
pub(crate) mod cyclic;
pub mod de;
pub mod ia;
pub mod ig;
pub mod iqm;
pub mod le;
pub(crate) mod nav;
pub mod nmia;
pub mod pe;
pub mod radial;
pub mod sig;
pub mod ts;

/// Why a structure could not be built for a complex.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum BuildError {
    /// Kept for the C ABI's TPX_STATUS_NOT_IMPLEMENTED (numbers are never reused); every kind
    /// is implemented today.
    #[error("structure `{kind}` is not implemented yet")]
    NotImplemented {
        /// The structure asked for.
        kind: StructureKind,
    },
    /// The structure's domain excludes this complex; `reason` names the first offending simplex.
    #[error("structure `{kind}` cannot encode this complex: {reason}")]
    Unsupported {
        /// The structure asked for.
        kind: StructureKind,
        /// Why, naming the first offending simplex.
        reason: String,
    },
    /// The structure's arrays would exceed their index range or the memory available.
    #[error("structure `{kind}`: the complex is too large: {what}")]
    TooLarge {
        /// The structure asked for.
        kind: StructureKind,
        /// What overflowed.
        what: String,
    },
}

/// Builds a structure of `kind` for `complex`.
pub fn build(kind: StructureKind, complex: &Complex) -> Result<Box<dyn Topology>, BuildError> {
    match kind {
        StructureKind::Ig => Ok(Box::new(ig::IncidenceGraph::build(complex)?)),
        StructureKind::Sig => Ok(Box::new(sig::Sig::build(complex)?)),
        StructureKind::Ia => Ok(Box::new(ia::IndexedAdjacency::build(complex)?)),
        StructureKind::Iqm => Ok(Box::new(iqm::Iqm::build(complex)?)),
        StructureKind::Nmia => Ok(Box::new(nmia::NonManifoldIa::build(complex)?)),
        StructureKind::Ts => Ok(Box::new(ts::TriangleSegment::build(complex)?)),
        StructureKind::Pe => Ok(Box::new(pe::PartialEntities::build(complex)?)),
        StructureKind::Le => Ok(Box::new(le::LoopEdgeUse::build(complex)?)),
        StructureKind::De => Ok(Box::new(de::DirectedEdge::build(complex)?)),
        StructureKind::IaStar => Ok(Box::new(crate::live::LiveComplex::try_from_complex(
            complex,
        )?)),
    }
}

/// Converts a count to `u32` indexes, or says what overflowed.
pub(crate) fn to_u32(kind: StructureKind, n: usize, what: &str) -> Result<u32, BuildError> {
    u32::try_from(n).map_err(|_| BuildError::TooLarge {
        kind,
        what: format!("{n} {what} exceed 32-bit indexes"),
    })
}
