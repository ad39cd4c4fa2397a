//! The one registry of the ten kinds: for each [`StructureKind`], how it is built from a complex,
//! saved into and loaded from a `.tpx` file, and which direct answer path the C ABI takes for it.
//! Adding a kind is one row of `registry!`'s invocation (and its `TPX_KIND_*` number in
//! [`StructureKind`]); nothing else matches on kinds to find a type.

use std::any::Any;

use crate::codec::{Persist, Reader, StoreError, Writer};
use crate::complex::Complex;
use crate::live::LiveComplex;
use crate::relation::{BuildError, StructureKind, Topology};
use crate::structures::{de, ia, ig, iqm, le, nmia, pe, sig, ts};

/// How the C ABI answers a relation of a structure of this kind without going through the
/// generic walk: the stored rows it reads directly, if any.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FastPath {
    /// No direct rows: the structure's own `Navigate` walk (or none for sparse numberings).
    Walk,
    /// The IG: boundaries, co-boundaries and R_{0,0} from its stored rows.
    Ig,
    /// The IA: R_{d,d} from its adjacency rows.
    Ia,
    /// TS: R_{2,2} from the radial cycles.
    Ts,
    /// PE: R_{2,2} from the radial cycles.
    Pe,
    /// LE: R_{2,2} from the radial cycles.
    Le,
    /// DE: R_{2,2} from the radial cycles.
    De,
}

/// A kind's row of the registry.
struct Member {
    build: fn(&Complex) -> Result<Box<dyn Topology>, BuildError>,
    load: fn(&mut Reader) -> Result<Box<dyn Topology>, StoreError>,
    save: fn(&dyn Topology, &mut Writer) -> bool,
    fast: FastPath,
}

fn load_as<T: Persist + Topology>(r: &mut Reader) -> Result<Box<dyn Topology>, StoreError> {
    Ok(Box::new(T::load(r)?))
}

fn save_as<T: Persist + 'static>(s: &dyn Topology, w: &mut Writer) -> bool {
    let any: &dyn Any = s;
    any.downcast_ref::<T>().map(|t| t.save(w)).is_some()
}

/// Writes the table, indexed by the kind's ABI number, from one row per kind.
macro_rules! registry {
    ($($kind:ident => $ty:ty, $build:path, $fast:ident;)*) => {
        const MEMBERS: [Member; StructureKind::NAMED.len()] = [$(Member {
            build: |c| Ok(Box::new($build(c)?)),
            load: load_as::<$ty>,
            save: save_as::<$ty>,
            fast: FastPath::$fast,
        },)*];
        /// The kinds in the table's order (checked against the ABI numbers by a unit test).
        #[cfg(test)]
        const ORDER: [StructureKind; StructureKind::NAMED.len()] = [$(StructureKind::$kind,)*];
    };
}

registry! {
    Ig => ig::IncidenceGraph, ig::IncidenceGraph::build, Ig;
    Sig => sig::Sig, sig::Sig::build, Walk;
    Ia => ia::IndexedAdjacency, ia::IndexedAdjacency::build, Ia;
    Iqm => iqm::Iqm, iqm::Iqm::build, Walk;
    Nmia => nmia::NonManifoldIa, nmia::NonManifoldIa::build, Walk;
    Ts => ts::TriangleSegment, ts::TriangleSegment::build, Ts;
    Pe => pe::PartialEntities, pe::PartialEntities::build, Pe;
    Le => le::LoopEdgeUse, le::LoopEdgeUse::build, Le;
    De => de::DirectedEdge, de::DirectedEdge::build, De;
    IaStar => LiveComplex, LiveComplex::try_from_complex, Walk;
}

fn member(kind: StructureKind) -> &'static Member {
    &MEMBERS[kind.abi() as usize]
}

/// Builds a structure of `kind` for `complex`.
pub fn build(kind: StructureKind, complex: &Complex) -> Result<Box<dyn Topology>, BuildError> {
    (member(kind).build)(complex)
}

/// Reads a structure of `kind` from the sections `r` is at.
pub(crate) fn load(kind: StructureKind, r: &mut Reader) -> Result<Box<dyn Topology>, StoreError> {
    (member(kind).load)(r)
}

/// Appends the structure's sections.
pub(crate) fn save(s: &dyn Topology, w: &mut Writer) {
    let saved = (member(s.kind()).save)(s, w);
    assert!(saved, "a structure's kind() names its own type");
}

/// The C ABI's direct answer path for `kind`.
pub fn fast_path(kind: StructureKind) -> FastPath {
    member(kind).fast
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_table_is_in_abi_order_and_names_every_kind() {
        for (i, k) in ORDER.iter().enumerate() {
            assert_eq!(k.abi() as usize, i);
        }
        assert_eq!(ORDER, StructureKind::NAMED);
    }
}
