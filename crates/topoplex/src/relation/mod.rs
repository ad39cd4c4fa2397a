//! The relation API every structure implements.
//!
//! For a p-simplex σ of a d-complex, R_{p,q}(σ) is
//! - `q < p` (boundary): the q-faces of σ;
//! - `q > p` (co-boundary): the q-simplices in the star of σ, i.e. those having σ as a face;
//! - `q == p > 0` (adjacency): the p-simplices other than σ sharing a (p−1)-face with σ;
//! - `q == p == 0`: the vertices sharing an edge with σ.
//!
//! A simplex is addressed by its vertex ids. Answers are written to a caller-owned `Vec<u32>`
//! as rows of `q + 1` ascending vertex ids, each simplex once, in the structure's own order (see
//! [`sort_rows`] for lexicographic order). Queries take `&self`; structures keep no traversal
//! state, so one structure answers from many threads at once (each query has its own scratch).

use std::fmt;

use crate::complex::{MAX_DIMENSION, sort_dedup_rows};
pub(crate) mod cyclic;
pub mod handle;

use handle::{Navigate, SimplexHandle};

/// Storage of a built structure: what the papers count, and what the process really holds.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, serde::Serialize)]
pub struct Storage {
    /// Integers (references) the papers count for the topological relations.
    pub integers: u64,
    /// Bits the papers count (flags).
    pub bits: u64,
    /// Heap bytes of every array the structure owns, vertex lists and indexes included.
    pub bytes: u64,
}

/// The nine structures of the family. The discriminants are the C ABI's `TPX_KIND_*` numbers:
/// fixed, never reused nor renumbered (see [`StructureKind::abi`]).
#[repr(u32)]
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum StructureKind {
    /// Incidence Graph.
    Ig = 0,
    /// Simplified Incidence Graph.
    Sig = 1,
    /// Indexed data structure with Adjacencies (extended with vertex stars).
    Ia = 2,
    /// Initial Quasi-Manifold structure.
    Iqm = 3,
    /// Non-Manifold Indexed data structure with Adjacencies.
    Nmia = 4,
    /// Triangle-Segment structure.
    Ts = 5,
    /// Partial Entities structure.
    Pe = 6,
    /// Loop Edge-use structure.
    Le = 7,
    /// Directed Edge structure.
    De = 8,
    /// The live complex ([`crate::live::LiveComplex`]): updatable, IA*-like; not in
    /// [`StructureKind::ALL`] (the nine frozen structures), C ABI kind 9.
    IaStar = 9,
}

impl StructureKind {
    /// Every kind, in ABI order.
    pub const ALL: [StructureKind; 9] = [
        StructureKind::Ig,
        StructureKind::Sig,
        StructureKind::Ia,
        StructureKind::Iqm,
        StructureKind::Nmia,
        StructureKind::Ts,
        StructureKind::Pe,
        StructureKind::Le,
        StructureKind::De,
    ];

    /// The C ABI number (`TPX_KIND_*`).
    pub fn abi(self) -> u32 {
        self as u32
    }

    /// The kind of C ABI number `n`, if any: the nine of [`StructureKind::ALL`] and the live
    /// complex (9), which builds, saves and opens as any kind does.
    pub fn from_abi(n: u32) -> Option<StructureKind> {
        StructureKind::NAMED.into_iter().find(|k| k.abi() == n)
    }

    /// The CLI name (`ig`, `sig`, ...).
    pub fn name(self) -> &'static str {
        match self {
            StructureKind::Ig => "ig",
            StructureKind::Sig => "sig",
            StructureKind::Ia => "ia",
            StructureKind::Iqm => "iqm",
            StructureKind::Nmia => "nmia",
            StructureKind::Ts => "ts",
            StructureKind::Pe => "pe",
            StructureKind::Le => "le",
            StructureKind::De => "de",
            StructureKind::IaStar => "iastar",
        }
    }

    /// Every kind with a CLI name: the nine of [`StructureKind::ALL`], then the live complex.
    pub const NAMED: [StructureKind; 10] = {
        let mut named = [StructureKind::IaStar; 10];
        let mut i = 0;
        while i < StructureKind::ALL.len() {
            named[i] = StructureKind::ALL[i];
            i += 1;
        }
        named
    };

    /// The kind whose CLI name is `name`, ASCII case ignored (`pe`, `PE`, `IaStar`: any of
    /// [`StructureKind::NAMED`], the live complex included): the one map from names to kinds,
    /// behind the CLI's `--structure`, `tpx_kind_from_name` and the C++ `Kind::from_name`.
    /// O(1) (ten comparisons).
    pub fn from_name(name: &str) -> Option<StructureKind> {
        StructureKind::NAMED
            .into_iter()
            .find(|k| k.name().eq_ignore_ascii_case(name))
    }
}

impl fmt::Display for StructureKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

fn show(ids: &[u32]) -> String {
    let v: Vec<String> = ids.iter().map(|i| i.to_string()).collect();
    format!("[{}]", v.join(" "))
}

/// Why a query has no answer. Each variant names the simplex as given.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum QueryError {
    /// The query simplex has no vertex.
    #[error("simplex with no vertex")]
    EmptySimplex,
    /// The query simplex has more than `MAX_DIMENSION + 1` vertices.
    #[error("simplex {} has {} vertices, above the supported maximum dimension {max}", show(.simplex), .simplex.len())]
    TooManyVertices {
        /// The simplex as given.
        simplex: Vec<u32>,
        /// The supported maximum dimension.
        max: usize,
    },
    /// The query simplex lists a vertex twice.
    #[error("simplex {} repeats vertex {vertex}", show(.simplex))]
    RepeatedVertex {
        /// The simplex as given.
        simplex: Vec<u32>,
        /// The repeated id.
        vertex: u32,
    },
    /// The query simplex uses a vertex id `>= n`.
    #[error("simplex {} uses vertex {vertex}, but the complex has {n} vertices", show(.simplex))]
    VertexOutOfRange {
        /// The simplex as given.
        simplex: Vec<u32>,
        /// The out-of-range id.
        vertex: u32,
        /// The number of vertices.
        n: u32,
    },
    /// The simplex is not in the complex.
    #[error("simplex {} is not in the complex", show(.simplex))]
    NotInComplex {
        /// The simplex as given.
        simplex: Vec<u32>,
    },
    /// p or q is above the complex's dimension.
    #[error("relation R_{{{p},{q}}}: dimension {q} is above the complex's dimension {dim}")]
    DimensionOutOfRange {
        /// Dimension of the query simplex.
        p: usize,
        /// Dimension asked for.
        q: usize,
        /// Dimension of the complex.
        dim: usize,
    },
    /// A handle that names no simplex of this structure (out of range, `NONE`, bad form).
    #[error("invalid handle {handle}: {reason}")]
    InvalidHandle {
        /// The handle as given.
        handle: SimplexHandle,
        /// What is wrong with it.
        reason: &'static str,
    },
    /// A handle of a simplex that an edit removed.
    #[error("stale handle {handle}: the simplex was removed")]
    StaleHandle {
        /// The handle as given.
        handle: SimplexHandle,
    },
    /// A handle issued before the structure's last compaction (its generation is older): its
    /// ids were renumbered, so it names nothing any more (editable structures only).
    #[error(
        "stale handle {handle}: issued at generation {generation}, before a compaction (the structure is at generation {current}); map or locate it again"
    )]
    StaleGeneration {
        /// The handle as given.
        handle: SimplexHandle,
        /// The handle's generation.
        generation: u32,
        /// The structure's generation (its compaction count).
        current: u32,
    },
    /// A handle of the wrong kind for the operation (an edge where a vertex is needed).
    #[error("handle {handle} is not {expected}")]
    WrongHandleKind {
        /// The handle as given.
        handle: SimplexHandle,
        /// What the operation needs ("a vertex", "an edge").
        expected: &'static str,
    },
    /// An index a query builds (a relation view) does not fit in memory or in 32-bit offsets.
    #[error("{what}: {bytes} bytes do not fit in memory (or its offsets in 32 bits)")]
    TooLarge {
        /// What was being built.
        what: &'static str,
        /// Bytes it needed.
        bytes: u64,
    },
}

/// The relation API. Implementors provide [`Topology::query`] for a validated simplex; callers
/// use [`Topology::relation`], which validates first.
/// `Any` lets the saved format ([`crate::store`]) find a structure's concrete type.
pub trait Topology: Send + Sync + std::any::Any {
    /// Which structure this is.
    fn kind(&self) -> StructureKind;

    /// Dimension d of the complex.
    fn dimension(&self) -> usize;

    /// Number of vertices n (vertex ids are `0..n`).
    fn vertex_count(&self) -> u32;

    /// Number of p-simplices n_p (0 for `p > d`).
    fn count(&self, p: usize) -> usize;

    /// Number of top p-simplices (not a proper face of another).
    fn top_count(&self, p: usize) -> usize;

    /// Appends every p-simplex, as rows of `p + 1` ascending ids in ascending lexicographic order.
    fn simplices(&self, p: usize, out: &mut Vec<u32>);

    /// R_{p,q}(σ) for `sigma` with ascending, distinct, in-range ids and `q <= d`, appended to
    /// `out` (rows of `q + 1` ascending ids, each simplex once). `NotInComplex` if σ is not a
    /// simplex of the complex.
    fn query(&self, sigma: &[u32], q: usize, out: &mut Vec<u32>) -> Result<(), QueryError>;

    /// Whether `sigma` (ascending, distinct, in range) is a simplex of the complex.
    fn contains(&self, sigma: &[u32]) -> bool;

    /// The structure's storage (arrays and their bytes).
    fn storage(&self) -> Storage;

    /// Checks every invariant of the structure; the error names the first broken one.
    fn validate(&self) -> Result<(), String>;

    /// Structure-specific figures for `report` (for example the IQM's component count), as
    /// (name, value) pairs. None by default.
    fn summary(&self) -> Vec<(&'static str, u64)> {
        Vec::new()
    }

    /// This structure's handle navigation ([`Navigate`]), when it has one (every structure of
    /// this crate does).
    fn as_navigate(&self) -> Option<&dyn Navigate> {
        None
    }

    /// The structure as [`std::any::Any`], for the C ABI to reach an editable structure's own
    /// type behind a `Box<dyn Topology>`. None by default.
    fn as_any(&self) -> Option<&dyn std::any::Any> {
        None
    }

    /// Mutable form of [`Topology::as_any`]. None by default.
    fn as_any_mut(&mut self) -> Option<&mut dyn std::any::Any> {
        None
    }

    /// R_{p,q}(σ) for σ given by vertex ids in any order; p = |σ| − 1. Validates σ (no repeated
    /// or out-of-range vertex, in the complex) and q, then appends the answer to `out` (cleared
    /// first) in the structure's order. Cost: the structure's [`Topology::query`] cost.
    fn relation(&self, sigma: &[u32], q: usize, out: &mut Vec<u32>) -> Result<(), QueryError> {
        out.clear();
        let sorted = normalize_simplex(sigma, self.vertex_count())?;
        let d = self.dimension();
        if q > d {
            return Err(QueryError::DimensionOutOfRange {
                p: sorted.len() - 1,
                q,
                dim: d,
            });
        }
        self.query(&sorted, q, out)
    }
}

/// Writes, inside an `impl Topology for T` block, the [`Topology`] methods every structure spells
/// alike: `kind`, `dimension`, `vertex_count`, `count` and `top_count` from one expression each,
/// and `as_navigate` (every structure has handles). Optional clauses after them, in any order:
/// `answers: m;` makes `query` and `contains` the 2D family's `m::query` and `m::contains`;
/// `simplices: m(n);` makes `simplices` `m::simplices(self, n, p, out)`; `as_any;` makes `as_any`
/// and `as_any_mut` the structure itself (the live complex). The caller names `self` first, and
/// the index of `count` and `top_count`, so that its expressions may use them (macro hygiene):
///
/// ```text
/// impl Topology for T {
///     crate::relation::topology_preamble! {
///         self, KIND;
///         dimension: self.d;
///         vertex_count: self.n;
///         count(p): self.counts.get(p).copied().unwrap_or(0);
///         top_count(p): if p == self.d { self.tops.len() } else { 0 };
///         answers: radial;
///     }
///
///     fn storage(&self) -> Storage { .. }
///     ..
/// }
/// ```
macro_rules! topology_preamble {
    (
        $this:ident, $kind:expr;
        dimension: $dimension:expr;
        vertex_count: $vertex_count:expr;
        count($p:ident): $count:expr;
        top_count($tp:ident): $top_count:expr;
        $($more:tt)*
    ) => {
        #[inline]
        fn kind(&$this) -> $crate::StructureKind {
            $kind
        }

        #[inline]
        fn dimension(&$this) -> usize {
            $dimension
        }

        #[inline]
        fn vertex_count(&$this) -> u32 {
            $vertex_count
        }

        #[inline]
        fn count(&$this, $p: usize) -> usize {
            $count
        }

        #[inline]
        fn top_count(&$this, $tp: usize) -> usize {
            $top_count
        }

        #[inline]
        fn as_navigate(&$this) -> Option<&dyn $crate::Navigate> {
            Some($this)
        }

        $crate::relation::topology_preamble!(@more $this; $($more)*);
    };
    (@more $this:ident;) => {};
    (@more $this:ident; answers: $m:ident; $($more:tt)*) => {
        fn query(
            &$this,
            sigma: &[u32],
            q: usize,
            out: &mut Vec<u32>,
        ) -> Result<(), $crate::QueryError> {
            $m::query($this, sigma, q, out)
        }

        fn contains(&$this, sigma: &[u32]) -> bool {
            $m::contains($this, sigma)
        }

        $crate::relation::topology_preamble!(@more $this; $($more)*);
    };
    (@more $this:ident; simplices: $m:ident($n:expr); $($more:tt)*) => {
        fn simplices(&$this, p: usize, out: &mut Vec<u32>) {
            $m::simplices($this, $n, p, out)
        }

        $crate::relation::topology_preamble!(@more $this; $($more)*);
    };
    (@more $this:ident; as_any; $($more:tt)*) => {
        fn as_any(&$this) -> Option<&dyn std::any::Any> {
            Some($this)
        }

        fn as_any_mut(&mut $this) -> Option<&mut dyn std::any::Any> {
            Some($this)
        }

        $crate::relation::topology_preamble!(@more $this; $($more)*);
    };
}
pub(crate) use topology_preamble;

/// `counts[p]` for `p <= d`, 0 above: a figure per dimension (`count`, `top_count`) of a
/// structure of dimension `d` that stores `counts` for dimensions 0, 1, ...
pub(crate) fn per_dimension<const N: usize>(p: usize, d: usize, counts: [usize; N]) -> usize {
    if p <= d {
        counts.get(p).copied().unwrap_or(0)
    } else {
        0
    }
}

/// [`normalize_simplex`] into the caller's `buf`: `sigma` sorted and checked the same way (the
/// same errors), without allocating unless it fails — for a query run once per simplex of a
/// whole mesh.
///
/// ```
/// use topoplex::complex::MAX_DIMENSION;
/// let mut buf = [0u32; MAX_DIMENSION + 1];
/// assert_eq!(topoplex::relation::normalize_simplex_into(&[7, 2, 5], 8, &mut buf).unwrap(), [2, 5, 7]);
/// assert!(topoplex::relation::normalize_simplex_into(&[2, 2], 8, &mut buf).is_err());
/// ```
pub fn normalize_simplex_into<'a>(
    sigma: &[u32],
    n: u32,
    buf: &'a mut [u32; MAX_DIMENSION + 1],
) -> Result<&'a [u32], QueryError> {
    let k = sigma.len();
    if k == 0 || k > buf.len() || sigma.iter().any(|&v| v >= n) {
        return Err(normalize_simplex(sigma, n).expect_err("an invalid simplex"));
    }
    let out = &mut buf[..k];
    out.copy_from_slice(sigma);
    out.sort_unstable();
    if out.windows(2).any(|w| w[0] == w[1]) {
        return Err(normalize_simplex(sigma, n).expect_err("a repeated vertex"));
    }
    Ok(out)
}

/// Sorts a copy of `sigma` and checks it: non-empty, within `MAX_DIMENSION`, no repeated vertex,
/// every id below `n`.
pub fn normalize_simplex(sigma: &[u32], n: u32) -> Result<Vec<u32>, QueryError> {
    if sigma.is_empty() {
        return Err(QueryError::EmptySimplex);
    }
    if sigma.len() > MAX_DIMENSION + 1 {
        return Err(QueryError::TooManyVertices {
            simplex: sigma.to_vec(),
            max: MAX_DIMENSION,
        });
    }
    if let Some(&v) = sigma.iter().find(|&&v| v >= n) {
        return Err(QueryError::VertexOutOfRange {
            simplex: sigma.to_vec(),
            vertex: v,
            n,
        });
    }
    let mut s = sigma.to_vec();
    s.sort_unstable();
    if let Some(w) = s.windows(2).find(|w| w[0] == w[1]) {
        return Err(QueryError::RepeatedVertex {
            simplex: sigma.to_vec(),
            vertex: w[0],
        });
    }
    Ok(s)
}

/// Sorts rows of `arity` ids into ascending lexicographic order (the `relation` dump order).
/// Rows must be distinct already; O(k log k).
pub fn sort_rows(rows: &mut Vec<u32>, arity: usize) {
    let sorted = sort_dedup_rows(arity, std::mem::take(rows));
    *rows = sorted;
}

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

#[cfg(test)]
mod tests {
    use super::StructureKind;

    #[test]
    fn named_kinds_are_the_nine_then_the_live_complex_each_found_by_its_name() {
        assert_eq!(StructureKind::NAMED[..9], StructureKind::ALL);
        assert_eq!(StructureKind::NAMED[9], StructureKind::IaStar);
        for k in StructureKind::NAMED {
            assert_eq!(StructureKind::from_name(k.name()), Some(k));
        }
        assert_eq!(StructureKind::from_name("IG"), Some(StructureKind::Ig));
        assert_eq!(
            StructureKind::from_name("IaStar"),
            Some(StructureKind::IaStar)
        );
        for bad in ["", "i", "igx", " ig", "ia*", "iastar\0"] {
            assert_eq!(StructureKind::from_name(bad), None, "{bad:?}");
        }
    }

    #[test]
    fn every_named_kind_is_found_by_its_abi_number_and_no_other_number_is() {
        for k in StructureKind::NAMED {
            assert_eq!(StructureKind::from_abi(k.abi()), Some(k));
        }
        assert_eq!(StructureKind::from_abi(10), None);
        assert_eq!(StructureKind::from_abi(u32::MAX), None);
    }
}
