//! `topoplex report`: the survey's comparison tables for one or more complexes — a census of each
//! dataset (Table 1(a), Table 3), each structure's storage (Table 1(b)) and measured build and
//! query times — as Markdown, JSON, CSV ([`render`]) and SVG bar charts ([`svg`]).
//!
//! # Census: definitions
//! For a simplex σ, lk(σ) = {τ : τ ∪ σ ∈ K, τ ∩ σ = ∅}, whose maximal simplices are τ \ σ for
//! the top simplices τ ⊇ σ. *Connected* means connected through shared vertices: two maximal
//! simplices of lk(σ) are in one component when a chain of maximal simplices, consecutive ones
//! sharing a vertex, joins them. For a vertex v that is exactly the survey's "connected component
//! of the restricted star": top simplices at v joined by a chain sharing edges that contain v
//! (the NMIA's R_{0,clusters} and the TS's R*_{0,2} with R*_{0,0}: a wire edge at v is a
//! component by itself). For an edge e, the components of lk(e) are its *edge-based clusters*:
//! tetrahedra around e joined by triangles containing e; every dangling face or other top
//! simplex meeting the rest of the star only in e is a cluster by itself.
//! - **Wire edges**: top 1-simplices. **Dangling faces**: top 2-simplices of a complex of
//!   dimension ≥ 3 (0 for d ≤ 2, where the triangles are counted as top 2-simplices).
//! - **Non-manifold simplex**: σ whose link is neither a combinatorial sphere nor a ball, of any
//!   dimension (the empty link of a top simplex or of an isolated vertex is the (−1)-sphere;
//!   a point is the 0-ball, two points the 0-sphere). So a manifold point may be of any local
//!   dimension: an edge of exactly two triangles is manifold whether or not tetrahedra exist
//!   elsewhere, while an edge of three triangles, a vertex where a wire edge meets a triangle
//!   and the centre of the pinched pie (whose link is a figure eight) are not. The test is
//!   exact for links of dimension ≤ 2 (every simplex of a complex of dimension ≤ 3): a
//!   connected pure link, every facet in ≤ 2 maximal simplices, vertex links spheres or balls
//!   (recursively), then closed with χ = 2 (sphere) or bounded with χ = 1 (ball). For links of
//!   dimension ≥ 3 (vertices and edges of complexes of dimension ≥ 4, 5) those conditions are
//!   necessary only — closed with χ = 1 + (−1)^k, or bounded with a sphere boundary and χ = 1
//!   — so the count there is a lower bound; how many simplices passed that way is reported as
//!   `approximated_links`. Every link test has a work budget linear in the link's size
//!   ([`census::LINK_WORK_PER_ID`]), so the census is linear in the complex for every dimension
//!   up to 15: single simplices, boundaries of simplices and cones are recognised exactly at
//!   once, and a link whose recursive test would exceed the budget (high-dimensional links that
//!   are none of these) is counted in `unclassified_links` and its simplex listed (first few) in
//!   `unclassified_examples` — neither manifold nor non-manifold, nor added to C_v or C_e.
//! - **C_v** = Σ over vertices of the number of components of lk(v) (0 for an isolated vertex),
//!   reported as C_v − n_0 (0 on a manifold without isolated vertices, negative with isolated
//!   vertices). The NMIA's and the TS's C_v are exactly this.
//! - **C_e** = Σ over *non-manifold* edges of the number of components of lk(e). On a complex
//!   of dimension ≤ 2 this is the TS's C_e (edges in ≥ 3 triangles, each triangle a cluster). On
//!   a 3-complex it is the NMIA's C_e except at an edge whose star is exactly two dangling faces:
//!   manifold here (its link is the 0-sphere), while the NMIA stores a cluster reference for
//!   each (it has no other adjacency for dangling faces) and counts 2. The survey's Table 1
//!   seems to do the same: its spider has 1989 dangling faces and C_e = 44, while its NMIA
//!   storage, 17.22k, is about 5.98k integers above 8·503 + 3·1989 + 44 + 1250 — roughly two
//!   per edge between two dangling faces of a web of 1989 triangles.
//! - **IQM components**: components of the IQM's standard decomposition
//!   ([`topoplex::structures::iqm`]).
//!
//! # Timings
//! Each structure is built once (timed); when that took under [`timing::MIN_TIME`] it is built
//! again until the repeats take that long, and the mean of the repeats is reported. Queries
//! call [`topoplex::relation::Topology::query`] directly (the simplex is already sorted and valid,
//! so no validation is timed) on a deterministic sample: at most [`timing::SAMPLE`] vertices and
//! as many top simplices of dimension ≥ 1, spread evenly over the vertex ids and over the top
//! simplices in dimension-then-lexicographic order. The relation families
//! ([`timing::Family`]) are
//! - **boundary** (top-simplex-based): R_{p,q}, every q < p, of each sampled top p-simplex;
//! - **co-boundary** (vertex-based): R_{0,q}, every 0 < q ≤ d, of each sampled vertex;
//! - **adjacency, vertex-based**: R_{0,0} of each sampled vertex;
//! - **adjacency, top-simplex-based**: R_{p,p} of each sampled top p-simplex.
//!
//! A family runs one warm-up pass over its queries, then repeats passes until they take
//! [`timing::MIN_TIME`] (at most [`timing::MAX_PASSES`]); the figure is the time of a pass over
//! the rows it retrieves (ns per element), also given per query.

pub mod census;
pub mod census_vtk;
pub mod render;
pub mod svg;
pub mod timing;

pub use census::Census;
pub use timing::{Family, FamilyTiming, Measured, Sample, StructureResult};
use topoplex::complex::{Complex, InputStats};
use topoplex::relation::StructureKind;

/// Everything `report` prints for one complex.
#[derive(Debug, Clone)]
pub struct Dataset {
    /// The file as given, or "built-in example".
    pub name: String,
    /// The file, `None` for the built-in example.
    pub file: Option<String>,
    /// What normalisation absorbed.
    pub input: InputStats,
    /// The census of the complex.
    pub census: Census,
    /// The simplices the timings query.
    pub sample: Sample,
    /// One entry per kind, in [`StructureKind::NAMED`] order (the live complex `iastar` last).
    pub structures: Vec<StructureResult>,
    /// The complex's attributes, in the order the file gives them.
    pub attributes: Vec<AttributeSummary>,
}

/// What `report` says of one attribute: where it is, its type, and for integer labels the
/// distinct values with their counts and names.
#[derive(Debug, Clone, serde::Serialize)]
pub struct AttributeSummary {
    /// The attribute's name (`medit:ref`, `gmsh:physical`, a VTK array's name...).
    pub name: String,
    /// `vertices` or `listed simplices`.
    pub on: &'static str,
    /// `i32`, `i64`, `f32` or `f64`.
    #[serde(rename = "type")]
    pub value_type: &'static str,
    /// Numbers per element.
    pub components: usize,
    /// Elements (vertices, or simplices as listed).
    pub elements: usize,
    /// Integer labels: each distinct value (first component), how many elements carry it, and
    /// its name when the file names it (for one dimension: the listed simplices' with the
    /// label); empty for reals.
    pub labels: Vec<LabelCount>,
}

/// One distinct label of an [`AttributeSummary`].
#[derive(Debug, Clone, serde::Serialize)]
pub struct LabelCount {
    /// The value.
    pub label: i64,
    /// Elements carrying it.
    pub count: usize,
    /// Its names (a Gmsh physical group's, per dimension), if any.
    pub names: Vec<String>,
}

impl AttributeSummary {
    /// The summary of each attribute of `complex`.
    pub fn of(complex: &Complex) -> Vec<AttributeSummary> {
        let at = complex.attributes();
        at.iter()
            .map(|a| AttributeSummary {
                name: a.name.clone(),
                on: a.location.describe(),
                value_type: a.values.value_type().name(),
                components: a.components,
                elements: a.element_count(),
                labels: a
                    .label_counts()
                    .into_iter()
                    .map(|(label, count)| LabelCount {
                        label,
                        count,
                        names: at
                            .label_names()
                            .iter()
                            .filter(|n| n.attribute == a.name && n.label == label)
                            .map(|n| n.name.clone())
                            .collect(),
                    })
                    .collect(),
            })
            .collect()
    }
}

impl Dataset {
    /// Counts, builds and times every structure on `complex`. `progress` hears what is being
    /// done (for a progress bar); it is called between steps, never inside a timed loop.
    /// `Err(bytes)` when the census's closure cannot be had (structures that cannot be built
    /// are reported in their [`StructureResult`] instead).
    pub fn measure(
        name: &str,
        file: Option<&str>,
        complex: &Complex,
        progress: &mut dyn FnMut(&str),
    ) -> Result<Dataset, usize> {
        progress("census");
        let census = Census::try_of(complex)?;
        let total: usize = census.simplices.iter().sum();
        let sample = Sample::of(complex, timing::SAMPLE);
        let structures = StructureKind::NAMED
            .into_iter()
            .map(|kind| timing::measure(kind, complex, &sample, total, progress))
            .collect();
        Ok(Dataset {
            name: name.to_string(),
            file: file.map(str::to_string),
            input: complex.stats(),
            census,
            sample,
            structures,
            attributes: AttributeSummary::of(complex),
        })
    }
}
