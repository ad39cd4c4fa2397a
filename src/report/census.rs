//! The census of a complex (the survey's Table 1(a) and Table 3 columns): see the definitions in
//! the [module documentation](super).

use serde::Serialize;

use topoplex::complex::Complex;
use topoplex::structures::iqm::Iqm;

/// What the survey's tables count for one dataset. Definitions: [`super`].
#[derive(Debug, Clone, PartialEq, Eq, Serialize)]
pub struct Census {
    /// Dimension d of the complex.
    pub dimension: usize,
    /// n_0.
    pub vertices: usize,
    /// n_p for p = 0..=d.
    pub simplices: Vec<usize>,
    /// Top p-simplices for p = 0..=d (index 0: isolated vertices).
    pub top_simplices: Vec<usize>,
    /// Top 1-simplices.
    pub wire_edges: usize,
    /// Top 2-simplices of a complex of dimension ≥ 3 (0 when d ≤ 2).
    pub dangling_faces: usize,
    /// Σ over non-manifold edges of the number of connected components of their link.
    pub c_e: u64,
    /// Σ over vertices of the number of connected components of their link.
    pub c_v: u64,
    /// C_v − n_0 (negative when isolated vertices outnumber the extra components).
    pub c_v_minus_n0: i64,
    /// Components of the IQM decomposition, or why it could not be built.
    pub iqm_components: Result<usize, String>,
    /// Non-manifold p-simplices for p = 0..=d.
    pub non_manifold: Vec<usize>,
    /// Simplices whose link has dimension ≥ 3 and passed the necessary conditions only (counted
    /// as manifold without an exact sphere/ball test).
    pub approximated_links: usize,
    /// Simplices whose link test ran out of its work budget ([`LINK_WORK_PER_ID`]): counted
    /// neither manifold nor non-manifold, and (for vertices and edges) their link components not
    /// added to C_v and C_e.
    pub unclassified_links: usize,
    /// The first [`UNCLASSIFIED_SHOWN`] of them (vertex ids, ascending; in vertex order).
    pub unclassified_examples: Vec<Vec<u32>>,
}

/// Work units one link test may spend per vertex id in the link's maximal simplices (plus
/// [`LINK_WORK_BASE`]): the census is linear in Σ_σ |lk σ| ≤ Σ_τ (dim τ + 1) 2^{dim τ + 1} over
/// the top simplices τ, whatever the dimension. The test of a link of dimension ≤ 2 (every
/// simplex of a complex of dimension ≤ 3) spends at most ~10 units per id (a surface of m
/// triangles: 3m + 1 to look at it, 9m for its edges, ≤ 9m for its vertex links, 8m for χ), so
/// it always finishes; a 3-dimensional one ~40–70 (four surface tests per tetrahedron), so
/// most finish. The recursive test of a higher-dimensional link can take factorial time (the
/// boundary of a cross-polytope branches 2(k+1) ways per level), and is cut off instead.
pub const LINK_WORK_PER_ID: u64 = 64;

/// Work units every link test may spend besides [`LINK_WORK_PER_ID`].
pub const LINK_WORK_BASE: u64 = 256;

/// How many unclassified simplices the census lists.
pub const UNCLASSIFIED_SHOWN: usize = 8;

impl Census {
    /// Counts everything for `complex`: O(Σ_τ 2^{dim τ+1}) faces of top simplices grouped per
    /// vertex, plus one link test per simplex (small: the link of σ has the size of its star).
    pub fn of(complex: &Complex) -> Census {
        Census::try_of(complex).unwrap_or_else(|bytes| {
            std::alloc::handle_alloc_error(
                std::alloc::Layout::array::<u8>(bytes).unwrap_or(std::alloc::Layout::new::<u8>()),
            )
        })
    }

    /// [`Census::of`] whose closure is computed fallibly ([`Complex::try_closure`]):
    /// `Err(bytes)` names the reservation that could not be had, so that `report` refuses in
    /// one line rather than aborting.
    pub fn try_of(complex: &Complex) -> Result<Census, usize> {
        let d = complex.dimension();
        let top_simplices = complex.top_counts();
        let simplices: Vec<usize> = complex.try_closure()?.iter().map(|t| t.len()).collect();
        let n = complex.vertex_count() as usize;
        let links = LinkCounts::of(complex, None);
        Ok(Census {
            dimension: d,
            vertices: n,
            wire_edges: top_simplices.get(1).copied().unwrap_or(0),
            dangling_faces: if d >= 3 { top_simplices[2] } else { 0 },
            top_simplices,
            simplices,
            c_e: links.c_e,
            c_v: links.c_v,
            c_v_minus_n0: links.c_v as i64 - n as i64,
            iqm_components: Iqm::build(complex)
                .map(|i| i.component_count())
                .map_err(|e| e.to_string()),
            non_manifold: links.non_manifold,
            approximated_links: links.approximated,
            unclassified_links: links.unclassified,
            unclassified_examples: links.unclassified_examples,
        })
    }
}

/// The non-manifold simplices of dimension `0..=max_p`, each as ascending vertex ids, by
/// dimension (each list in ascending lexicographic order). Same cost as [`Census::of`]'s link
/// tests.
pub fn non_manifold_simplices(complex: &Complex, max_p: usize) -> Vec<Vec<Vec<u32>>> {
    let mut lists = LinkCounts::of(complex, Some(max_p)).listed;
    for l in &mut lists {
        l.sort_unstable();
    }
    lists
}

struct LinkCounts {
    c_e: u64,
    c_v: u64,
    non_manifold: Vec<usize>,
    approximated: usize,
    unclassified: usize,
    unclassified_examples: Vec<Vec<u32>>,
    /// The non-manifold simplices of dimension up to the limit asked for, by dimension.
    listed: Vec<Vec<Vec<u32>>>,
}

impl LinkCounts {
    /// Every simplex σ is visited once, at its lowest vertex v: the top simplices containing σ
    /// are those of the star of v whose part above v contains σ \ {v}, so each top τ ∋ v lists
    /// every subset of its vertices above v and equal subsets are grouped.
    fn of(complex: &Complex, list_up_to: Option<usize>) -> LinkCounts {
        let stars = Stars::of(complex);
        let mut out = LinkCounts::new(complex.dimension(), list_up_to);
        // Per-vertex scratch: subsets as (start in `keys`, length, top), grouped by sorting.
        let mut keys: Vec<u32> = Vec::new();
        let mut entries: Vec<(u32, u8, u32)> = Vec::new();
        let mut link = Rows::default();
        for v in 0..complex.vertex_count() as usize {
            // An isolated vertex: empty link, a 0-manifold with no component.
            if stars.at(v).is_empty() {
                continue;
            }
            stars.subsets_above(v, &mut keys, &mut entries);
            let key = |e: &(u32, u8, u32)| &keys[e.0 as usize..e.0 as usize + e.1 as usize];
            let mut i = 0;
            while i < entries.len() {
                let rho = key(&entries[i]);
                let mut j = i + 1;
                while j < entries.len() && key(&entries[j]) == rho {
                    j += 1;
                }
                // lk(σ) for σ = {v} ∪ ρ: the top simplices containing σ, minus σ.
                link.clear();
                for e in &entries[i..j] {
                    let t = stars.tops[e.2 as usize];
                    link.push(
                        t.iter()
                            .copied()
                            .filter(|&x| x as usize != v && rho.binary_search(&x).is_err()),
                    );
                }
                out.count(v, rho, &link);
                i = j;
            }
        }
        out
    }

    /// Nothing counted yet, for a complex of dimension `d`.
    fn new(d: usize, list_up_to: Option<usize>) -> LinkCounts {
        LinkCounts {
            c_e: 0,
            c_v: 0,
            non_manifold: vec![0; d + 1],
            approximated: 0,
            unclassified: 0,
            unclassified_examples: Vec::new(),
            listed: vec![Vec::new(); list_up_to.map_or(0, |m| m.min(d) + 1)],
        }
    }

    /// Counts σ = {v} ∪ `rho` by the test of its link `link`.
    fn count(&mut self, v: usize, rho: &[u32], link: &Rows) {
        let p = rho.len();
        let mut work = Work::for_link(link);
        let Some(a) = analyse(link, &mut work) else {
            self.unclassified += 1;
            if self.unclassified_examples.len() < UNCLASSIFIED_SHOWN {
                let mut sigma = vec![v as u32];
                sigma.extend_from_slice(rho);
                self.unclassified_examples.push(sigma);
            }
            return;
        };
        if a.shape == Shape::Neither {
            self.non_manifold[p] += 1;
            if let Some(list) = self.listed.get_mut(p) {
                list.push(
                    std::iter::once(v as u32)
                        .chain(rho.iter().copied())
                        .collect(),
                );
            }
        }
        if a.approximate && a.shape != Shape::Neither {
            self.approximated += 1;
        }
        if p == 0 {
            self.c_v += a.components as u64;
        } else if p == 1 && a.shape == Shape::Neither {
            self.c_e += a.components as u64;
        }
    }
}

/// The star of each vertex: the top simplices of dimension ≥ 1 at it (CSR over `tops`).
struct Stars<'c> {
    tops: Vec<&'c [u32]>,
    off: Vec<u32>,
    star: Vec<u32>,
}

impl<'c> Stars<'c> {
    fn of(complex: &'c Complex) -> Stars<'c> {
        let n = complex.vertex_count() as usize;
        let mut tops: Vec<&[u32]> = Vec::new();
        for p in 1..=complex.dimension() {
            tops.extend(complex.tops(p).iter());
        }
        let mut off = vec![0u32; n + 1];
        for t in &tops {
            for &v in *t {
                off[v as usize + 1] += 1;
            }
        }
        for v in 0..n {
            off[v + 1] += off[v];
        }
        let mut fill = off.clone();
        let mut star = vec![0u32; off[n] as usize];
        for (g, t) in tops.iter().enumerate() {
            for &v in *t {
                star[fill[v as usize] as usize] = g as u32;
                fill[v as usize] += 1;
            }
        }
        Stars { tops, off, star }
    }

    /// The tops at `v`, as indices in `tops`.
    fn at(&self, v: usize) -> &[u32] {
        &self.star[self.off[v] as usize..self.off[v + 1] as usize]
    }

    /// Every subset of the vertices above `v` of every top at `v`, as (start in `keys`, length,
    /// top) in `entries`, sorted by length, ids and top (equal subsets side by side).
    fn subsets_above(&self, v: usize, keys: &mut Vec<u32>, entries: &mut Vec<(u32, u8, u32)>) {
        keys.clear();
        entries.clear();
        for &g in self.at(v) {
            let t = self.tops[g as usize];
            let pos = t.iter().position(|&x| x as usize == v).unwrap();
            let above = &t[pos + 1..];
            for mask in 0u32..(1 << above.len()) {
                let start = keys.len() as u32;
                for (i, &x) in above.iter().enumerate() {
                    if mask & (1 << i) != 0 {
                        keys.push(x);
                    }
                }
                entries.push((start, mask.count_ones() as u8, g));
            }
        }
        let key = |e: &(u32, u8, u32)| &keys[e.0 as usize..e.0 as usize + e.1 as usize];
        entries.sort_unstable_by(|a, b| (a.1, key(a), a.2).cmp(&(b.1, key(b), b.2)));
    }
}

/// What one link test may still spend (one unit ≈ one vertex id touched).
pub(crate) struct Work {
    left: u64,
}

impl Work {
    /// The budget of the test of `link`: [`LINK_WORK_BASE`] + [`LINK_WORK_PER_ID`] per id.
    pub(crate) fn for_link(link: &Rows) -> Work {
        Work {
            left: LINK_WORK_BASE + LINK_WORK_PER_ID * link.ids.len() as u64,
        }
    }

    /// Spends `units`; `None` once the budget is gone.
    fn spend(&mut self, units: usize) -> Option<()> {
        self.left = self.left.checked_sub(units as u64)?;
        Some(())
    }
}

/// A small complex given by its maximal simplices (rows of ascending ids, any lengths).
#[derive(Debug, Default, Clone)]
pub(crate) struct Rows {
    ids: Vec<u32>,
    off: Vec<usize>,
}

impl Rows {
    fn clear(&mut self) {
        self.ids.clear();
        self.off.clear();
    }

    fn push(&mut self, row: impl IntoIterator<Item = u32>) {
        if self.off.is_empty() {
            self.off.push(0);
        }
        self.ids.extend(row);
        self.off.push(self.ids.len());
    }

    fn len(&self) -> usize {
        self.off.len().saturating_sub(1)
    }

    fn row(&self, i: usize) -> &[u32] {
        &self.ids[self.off[i]..self.off[i + 1]]
    }

    fn iter(&self) -> impl Iterator<Item = &[u32]> + '_ {
        (0..self.len()).map(|i| self.row(i))
    }

    #[cfg(test)]
    pub(crate) fn from(rows: &[&[u32]]) -> Rows {
        let mut r = Rows::default();
        for row in rows {
            r.push(row.iter().copied());
        }
        r
    }
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Shape {
    /// A combinatorial sphere (the empty complex is the (−1)-sphere).
    Sphere,
    /// A combinatorial ball.
    Ball,
    Neither,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Analysis {
    pub components: usize,
    pub shape: Shape,
    /// A dimension-≥3 test answered Sphere/Ball from necessary conditions only.
    pub approximate: bool,
}

/// Connected components (vertices joined by shared simplices) and the sphere/ball test of the
/// complex whose maximal simplices are `rows` (see the module documentation for exactness);
/// `None` when `work` runs out first.
pub(crate) fn analyse(rows: &Rows, work: &mut Work) -> Option<Analysis> {
    work.spend(rows.ids.len() + 1)?;
    if let Some(shape) = simplex_or_its_boundary(rows) {
        return Some(Analysis {
            components: 1,
            shape,
            approximate: false,
        });
    }
    if let Some(base) = cone_base(rows) {
        // A cone c * X is a ball exactly when X is a sphere or a ball (lk(c) = X): one level
        // down per apex, instead of a recursion through every vertex.
        let b = analyse(&base, work)?;
        return Some(Analysis {
            components: 1,
            shape: match b.shape {
                Shape::Sphere | Shape::Ball => Shape::Ball,
                Shape::Neither => Shape::Neither,
            },
            approximate: b.approximate,
        });
    }
    let mut approximate = false;
    let (components, verts) = components(rows);
    let shape = if components > 1 {
        // Two points are the 0-sphere; any other disconnected complex is neither.
        if rows.len() == 2 && rows.iter().all(|r| r.len() == 1) {
            Shape::Sphere
        } else {
            Shape::Neither
        }
    } else {
        shape(rows, &verts, &mut approximate, work)?
    };
    Some(Analysis {
        components,
        shape,
        approximate,
    })
}

/// X for a complex of two or more maximal simplices that is a cone c * X: a vertex c in every
/// row (the smallest such), and the rows without it. Rows are ascending.
fn cone_base(rows: &Rows) -> Option<Rows> {
    if rows.len() < 2 {
        return None;
    }
    let apex = *rows
        .row(0)
        .iter()
        .find(|x| rows.iter().skip(1).all(|r| r.binary_search(x).is_ok()))?;
    let mut base = Rows::default();
    for r in rows.iter() {
        base.push(r.iter().copied().filter(|&x| x != apex));
    }
    Some(base)
}

/// Exact answers that need no recursion: one simplex is a ball; the k+2 facets of a
/// (k+1)-simplex (k ≥ 1) are a k-sphere. `None` for anything else (rows are distinct).
fn simplex_or_its_boundary(rows: &Rows) -> Option<Shape> {
    let first = rows.iter().next()?;
    if first.is_empty() {
        return None;
    }
    if rows.len() == 1 {
        return Some(Shape::Ball);
    }
    let arity = first.len();
    if arity < 2 || rows.len() != arity + 1 || rows.iter().any(|r| r.len() != arity) {
        return None;
    }
    let mut verts: Vec<u32> = rows.ids.clone();
    verts.sort_unstable();
    verts.dedup();
    (verts.len() == arity + 1).then_some(Shape::Sphere)
}

/// Number of connected components, and the sorted distinct vertices.
fn components(rows: &Rows) -> (usize, Vec<u32>) {
    let mut verts: Vec<u32> = rows.ids.clone();
    verts.sort_unstable();
    verts.dedup();
    let mut parent: Vec<u32> = (0..verts.len() as u32).collect();
    fn root(parent: &mut [u32], mut x: u32) -> u32 {
        while parent[x as usize] != x {
            parent[x as usize] = parent[parent[x as usize] as usize];
            x = parent[x as usize];
        }
        x
    }
    let mut count = verts.len();
    for row in rows.iter() {
        let Some((&first, rest)) = row.split_first() else {
            continue;
        };
        let a = verts.binary_search(&first).unwrap() as u32;
        for &x in rest {
            let b = verts.binary_search(&x).unwrap() as u32;
            let (ra, rb) = (root(&mut parent, a), root(&mut parent, b));
            if ra != rb {
                parent[ra as usize] = rb;
                count -= 1;
            }
        }
    }
    (count, verts)
}

/// Sphere/ball test of a connected complex with vertices `verts` (none: the empty sphere).
fn shape(rows: &Rows, verts: &[u32], approximate: &mut bool, work: &mut Work) -> Option<Shape> {
    if verts.is_empty() {
        return Some(Shape::Sphere);
    }
    let arity = rows.row(0).len();
    if rows.iter().any(|r| r.len() != arity) {
        return Some(Shape::Neither);
    }
    match arity - 1 {
        // Connected: one point (two points are handled with the components).
        0 => Some(Shape::Ball),
        1 => Some(graph_shape(rows, verts)),
        _ => pseudo_manifold_shape(rows, verts, approximate, work),
    }
}

/// A connected graph with degrees ≤ 2 is a path (ball) or a cycle (sphere).
fn graph_shape(rows: &Rows, verts: &[u32]) -> Shape {
    let mut degree = vec![0u32; verts.len()];
    for r in rows.iter() {
        for x in r {
            degree[verts.binary_search(x).unwrap()] += 1;
        }
    }
    if degree.iter().any(|&g| g > 2) {
        return Shape::Neither;
    }
    match degree.iter().filter(|&&g| g == 1).count() {
        0 => Shape::Sphere,
        2 => Shape::Ball,
        _ => Shape::Neither,
    }
}

/// Shape of a connected pure k-complex, k ≥ 2: a pseudo-manifold whose vertex links are
/// spheres or balls, told apart by its boundary and Euler characteristic.
fn pseudo_manifold_shape(
    rows: &Rows,
    verts: &[u32],
    approximate: &mut bool,
    work: &mut Work,
) -> Option<Shape> {
    let arity = rows.row(0).len();
    let k = arity - 1;
    // A pseudo-manifold: each facet in one or two k-simplices ...
    work.spend(rows.ids.len() * arity)?;
    let mut facets: Vec<u32> = Vec::with_capacity(rows.len() * arity * k);
    for r in rows.iter() {
        topoplex::complex::push_facets(r, &mut facets);
    }
    let facets = counted_rows(k, &facets);
    if facets.iter().any(|&(_, c)| c > 2) {
        return Some(Shape::Neither);
    }
    // ... whose vertex links are (k−1)-spheres or balls (a combinatorial manifold) ...
    if !vertex_links_are_manifold(rows, verts, approximate, work)? {
        return Some(Shape::Neither);
    }
    // ... told apart by its boundary and Euler characteristic.
    work.spend(rows.len() << arity)?;
    let chi = euler_characteristic(rows, arity);
    let closed = facets.iter().all(|&(_, c)| c == 2);
    if k == 2 {
        // A connected compact surface: closed with χ = 2 is the sphere; with boundary, χ = 1
        // leaves only the disk (the projective plane, the other χ = 1 surface, is closed).
        return Some(match (closed, chi) {
            (true, 2) => Shape::Sphere,
            (false, 1) => Shape::Ball,
            _ => Shape::Neither,
        });
    }
    // k ≥ 3: necessary conditions only (a homology sphere passes).
    *approximate = true;
    let sphere_chi = if k.is_multiple_of(2) { 2 } else { 0 };
    if closed {
        return Some(if chi == sphere_chi {
            Shape::Sphere
        } else {
            Shape::Neither
        });
    }
    let mut boundary = Rows::default();
    for (f, _) in facets.iter().filter(|&&(_, c)| c == 1) {
        boundary.push(f.iter().copied());
    }
    let b = analyse(&boundary, work)?;
    Some(if b.shape == Shape::Sphere && chi == 1 {
        Shape::Ball
    } else {
        Shape::Neither
    })
}

/// Whether the link of every vertex of `rows` is a sphere or a ball.
fn vertex_links_are_manifold(
    rows: &Rows,
    verts: &[u32],
    approximate: &mut bool,
    work: &mut Work,
) -> Option<bool> {
    // Rows at each vertex (CSR), so a hub vertex's large link is not scanned once per vertex.
    let mut at_off = vec![0usize; verts.len() + 1];
    for &x in &rows.ids {
        at_off[verts.binary_search(&x).unwrap() + 1] += 1;
    }
    for i in 0..verts.len() {
        at_off[i + 1] += at_off[i];
    }
    let mut fill = at_off.clone();
    let mut at = vec![0usize; rows.ids.len()];
    for (i, r) in rows.iter().enumerate() {
        for x in r {
            let w = verts.binary_search(x).unwrap();
            at[fill[w]] = i;
            fill[w] += 1;
        }
    }
    let mut sub = Rows::default();
    for (wi, &w) in verts.iter().enumerate() {
        sub.clear();
        for &i in &at[at_off[wi]..at_off[wi + 1]] {
            sub.push(rows.row(i).iter().copied().filter(|&x| x != w));
        }
        let a = analyse(&sub, work)?;
        *approximate |= a.approximate;
        if a.shape == Shape::Neither {
            return Some(false);
        }
    }
    Some(true)
}

/// Distinct rows of `arity` ids with how many times each occurs.
fn counted_rows(arity: usize, ids: &[u32]) -> Vec<(&[u32], u32)> {
    let mut rows: Vec<&[u32]> = ids.chunks_exact(arity).collect();
    rows.sort_unstable();
    let mut out: Vec<(&[u32], u32)> = Vec::new();
    for r in rows {
        match out.last_mut() {
            Some((last, c)) if *last == r => *c += 1,
            _ => out.push((r, 1)),
        }
    }
    out
}

/// Σ_i (−1)^i f_i over every non-empty face of the rows (all of `arity` vertices).
fn euler_characteristic(rows: &Rows, arity: usize) -> i64 {
    let mut chi = 0i64;
    let mut faces: Vec<Vec<u32>> = vec![Vec::new(); arity + 1];
    for r in rows.iter() {
        for mask in 1u32..(1 << arity) {
            let len = mask.count_ones() as usize;
            faces[len].extend(
                r.iter()
                    .enumerate()
                    .filter(|&(i, _)| mask & (1 << i) != 0)
                    .map(|(_, &x)| x),
            );
        }
    }
    for (len, f) in faces.into_iter().enumerate().skip(1) {
        let count = topoplex::complex::sort_dedup_rows(len, f).len() / len;
        chi += if len % 2 == 1 {
            count as i64
        } else {
            -(count as i64)
        };
    }
    chi
}

#[cfg(test)]
mod tests {
    use super::*;
    use topoplex::fixtures;

    /// (wire edges, dangling faces, top simplices, C_e, C_v − n_0, IQM components,
    /// non-manifold per dimension), worked out by hand from each fixture's drawing.
    type Expected = (usize, usize, Vec<usize>, u64, i64, usize, Vec<usize>);

    fn check(name: &str, c: &Complex, want: Expected) {
        let got = Census::of(c);
        let (we, df, tops, ce, cv, iqm, nm) = want;
        assert_eq!(
            (
                got.wire_edges,
                got.dangling_faces,
                got.top_simplices.clone(),
                got.c_e,
                got.c_v_minus_n0,
                got.iqm_components.clone(),
                got.non_manifold.clone(),
            ),
            (we, df, tops, ce, cv, Ok(iqm), nm),
            "{name}"
        );
        assert_eq!(got.approximated_links, 0, "{name}");
        assert_eq!(got.unclassified_links, 0, "{name}");
    }

    /// One test per fixture, named after it: its census checked against the `Expected` tuple
    /// worked out by hand (the comment above each row says how).
    macro_rules! census_cases {
        ($($fixture:ident: $name:literal, $want:expr;)*) => {
            $(
                #[test]
                fn $fixture() {
                    check($name, &fixtures::$fixture(), $want);
                }
            )*
        };
    }

    census_cases! {
        // Components of lk(v): 2 at v2 (tet, triangle 2 7 8), v3 (tet, wire 3-4), v4 (two
        // wires), none at the isolated v9: C_v = 12. Non-manifold: v0, v1 (link: a triangle
        // with a hair), v2, v3; edge 0-1 (link: edge 2-3 and point 6, 2 clusters). v4 sits
        // inside the path 3-4-5 (link: two points), a manifold point.
        builtin_example: "builtin", (2, 2, vec![1, 2, 2, 1], 2, 2, 5, vec![4, 1, 0, 0]);
        // v2's link is two disjoint edges.
        bowtie: "bowtie", (0, 0, vec![0, 0, 2], 0, 1, 2, vec![1, 0, 0]);
        // lk(0-1) = three points: 3 clusters. lk(0), lk(1): a star with a degree-3 centre.
        three_triangles_on_an_edge: "fan3", (0, 0, vec![0, 0, 3], 3, 0, 3, vec![2, 1, 0]);
        // lk(2-3): edge 0-1 and point 4. v2, v3: a triangle plus an edge; v4: an edge plus a
        // point (two components).
        tetrahedron_with_dangling_triangle_and_wire: "tet+triangle+wire",
            (1, 1, vec![0, 1, 1, 1], 2, 1, 3, vec![3, 1, 0, 0]);
        // lk(0) is one figure eight (connected: C_v counts 1) but not a circle; edge 0-1 is in
        // four triangles. The two fans are two IQM components.
        pinched_pie: "pinched pie", (0, 0, vec![0, 0, 6], 4, 0, 2, vec![2, 1, 0]);
        // lk(0): paths 1-2-3 and 4-5-6. Every edge is in one or two triangles. One IQM
        // component (0 is split inside it).
        strip_pinched_at_a_vertex: "strip", (0, 0, vec![0, 0, 6], 0, 1, 1, vec![1, 0, 0]);
        // lk(0): {123,124,134,125}, {678}, {9 10}: 3 components. Triangle 012 is in three
        // tetrahedra, so edges 01, 02, 12 have a degree-3 link vertex (one cluster each) and
        // v1, v2 have an edge in three link triangles; v3, v4 have two link triangles on an
        // edge (a disk).
        four_iqm_components_two_clusters: "fig5", (0, 1, vec![0, 0, 1, 5], 3, 2, 4, vec![3, 3, 1, 0]);
    }

    fn shape_of(rows: &[&[u32]]) -> (Shape, bool) {
        let mut work = Work { left: u64::MAX };
        let a = analyse(&Rows::from(rows), &mut work).unwrap();
        (a.shape, a.approximate)
    }

    /// [`shape_of`] over owned rows.
    fn shape_of_rows(rows: &[Vec<u32>]) -> (Shape, bool) {
        let refs: Vec<&[u32]> = rows.iter().map(Vec::as_slice).collect();
        shape_of(&refs)
    }

    /// Every edge of a closed surface is in exactly two triangles (so a wrong triangulation
    /// cannot pass for the surface it claims to be).
    fn assert_closed_surface(tris: &[[u32; 3]]) {
        let mut edges: Vec<[u32; 2]> = Vec::new();
        for t in tris {
            edges.extend([[t[0], t[1]], [t[0], t[2]], [t[1], t[2]]]);
        }
        edges.sort();
        for e in edges.chunk_by(|a, b| a == b) {
            assert_eq!(e.len(), 2, "edge {:?}", e[0]);
        }
    }

    fn sorted(tris: &[[u32; 3]]) -> Vec<Vec<u32>> {
        tris.iter()
            .map(|t| {
                let mut t = t.to_vec();
                t.sort();
                t
            })
            .collect()
    }

    #[test]
    fn spheres_balls_and_other_links() {
        use Shape::*;
        assert_eq!(shape_of(&[]), (Sphere, false));
        assert_eq!(shape_of(&[&[]]), (Sphere, false));
        assert_eq!(shape_of(&[&[4]]), (Ball, false));
        assert_eq!(shape_of(&[&[4], &[7]]), (Sphere, false));
        assert_eq!(shape_of(&[&[1], &[2], &[3]]), (Neither, false));
        // Path, cycle, a degree-3 vertex, an edge with a point.
        assert_eq!(shape_of(&[&[1, 2], &[2, 3]]), (Ball, false));
        assert_eq!(shape_of(&[&[1, 2], &[2, 3], &[1, 3]]), (Sphere, false));
        assert_eq!(shape_of(&[&[1, 2], &[1, 3], &[1, 4]]), (Neither, false));
        assert_eq!(shape_of(&[&[1, 2], &[5]]), (Neither, false));
        // Octahedron boundary (vertices ±x 0/1, ±y 2/3, ±z 4/5) is the 2-sphere; without one
        // triangle it is a disk.
        let mut octa: Vec<[u32; 3]> = Vec::new();
        for x in [0, 1] {
            for y in [2, 3] {
                for z in [4, 5] {
                    octa.push([x, y, z]);
                }
            }
        }
        assert_closed_surface(&octa);
        let rows = sorted(&octa);
        assert_eq!(shape_of_rows(&rows), (Sphere, false));
        assert_eq!(shape_of_rows(&rows[1..]), (Ball, false));
        // Two triangles glued along an edge: a disk. Two glued at a vertex only: not a
        // manifold (the vertex's link is two disjoint edges).
        assert_eq!(shape_of(&[&[0, 1, 2], &[1, 2, 3]]), (Ball, false));
        assert_eq!(shape_of(&[&[0, 1, 2], &[2, 3, 4]]), (Neither, false));
        // The 7-vertex torus (χ = 0) and the 6-vertex projective plane (closed, χ = 1).
        let torus: Vec<[u32; 3]> = (0..7)
            .flat_map(|i| [[i, (i + 1) % 7, (i + 3) % 7], [i, (i + 2) % 7, (i + 3) % 7]])
            .collect();
        assert_closed_surface(
            &sorted(&torus)
                .iter()
                .map(|t| [t[0], t[1], t[2]])
                .collect::<Vec<_>>(),
        );
        assert_eq!(shape_of_rows(&sorted(&torus)), (Neither, false));
        let rp2: Vec<[u32; 3]> = vec![
            [1, 2, 3],
            [1, 3, 4],
            [1, 4, 5],
            [1, 5, 6],
            [1, 2, 6],
            [2, 3, 5],
            [2, 4, 5],
            [2, 4, 6],
            [3, 4, 6],
            [3, 5, 6],
        ];
        assert_closed_surface(&rp2);
        assert_eq!(shape_of_rows(&sorted(&rp2)), (Neither, false));
        // Dimension 3: one tetrahedron is a ball, the boundary of the 4-simplex a sphere —
        // both exactly (a simplex and its boundary are recognised as such) ...
        assert_eq!(shape_of(&[&[0, 1, 2, 3]]), (Ball, false));
        let s3: Vec<Vec<u32>> = (0..5u32)
            .map(|skip| (0..5).filter(|&v| v != skip).collect())
            .collect();
        assert_eq!(shape_of_rows(&s3), (Sphere, false));
        // ... as are cones: two tetrahedra on a triangle are a ball, two on a vertex (a cone
        // over two disjoint triangles) are not a manifold ...
        assert_eq!(shape_of(&[&[0, 1, 2, 3], &[1, 2, 3, 4]]), (Ball, false));
        assert_eq!(shape_of(&[&[0, 1, 2, 3], &[3, 4, 5, 6]]), (Neither, false));
        // ... while the boundary of the 16-cell (vertices 2i and 2i+1 opposite) passes as a
        // 3-sphere by the necessary conditions only.
        assert_eq!(
            shape_of_rows(&cross_polytope_boundary(3, 0)),
            (Sphere, true)
        );
    }

    /// The 2^{k+1} facets of the boundary of the (k+1)-dimensional cross-polytope over
    /// vertices `first + 2i`, `first + 2i + 1` (opposite), i = 0..=k, each row ascending.
    fn cross_polytope_boundary(k: u32, first: u32) -> Vec<Vec<u32>> {
        (0u32..(1 << (k + 1)))
            .map(|choice| {
                (0..=k)
                    .map(|i| first + 2 * i + ((choice >> i) & 1))
                    .collect()
            })
            .collect()
    }

    #[test]
    fn cone_over_the_16_cell_boundary_has_one_approximated_link() {
        // v = 0 joined to the 16 tetrahedra of the 16-cell's boundary (vertices 1..=8): lk(v)
        // is that 3-sphere, tested by the necessary conditions only; every other link is a
        // cone or of dimension ≤ 2, tested exactly. Nothing is non-manifold.
        let tops: Vec<Vec<u32>> = cross_polytope_boundary(3, 1)
            .into_iter()
            .map(|f| [vec![0], f].concat())
            .collect();
        let refs: Vec<&[u32]> = tops.iter().map(Vec::as_slice).collect();
        let c = Complex::from_simplices(9, &refs).unwrap();
        let got = Census::of(&c);
        assert_eq!(got.non_manifold, vec![0; 5]);
        assert_eq!(got.approximated_links, 1);
        assert_eq!((got.c_e, got.c_v_minus_n0), (0, 0));
        assert_eq!(got.unclassified_links, 0);
    }

    /// One k-simplex for k = 11..=15: every link is a simplex (a ball), recognised at once, so
    /// the census visits each of the 2^{k+1} − 1 faces once (it took minutes at k = 10 when
    /// the link test recursed through every vertex order).
    #[test]
    fn one_high_dimensional_simplex_is_classified_exactly() {
        for k in 11..=15u32 {
            let s: Vec<u32> = (0..=k).collect();
            let c = Complex::from_simplices(k + 1, &[&s]).unwrap();
            let got = Census::of(&c);
            assert_eq!(
                got.simplices.iter().sum::<usize>(),
                (1 << (k + 1)) - 1,
                "k={k}"
            );
            assert_eq!(got.non_manifold, vec![0; k as usize + 1], "k={k}");
            assert_eq!(
                (got.unclassified_links, got.approximated_links),
                (0, 0),
                "k={k}"
            );
            assert_eq!(got.c_v_minus_n0, 0, "k={k}");
        }
    }

    /// Two 15-simplices on a 14-face 1..=15: the link of a face σ inside the shared face is two
    /// simplices on a common facet — a cone over a cone over ... two points, a ball, found one
    /// apex at a time (the plain recursion through every vertex order took minutes).
    #[test]
    fn two_glued_15_simplices_are_classified_exactly() {
        let a: Vec<u32> = (0..16).collect();
        let b: Vec<u32> = (1..17).collect();
        let c = Complex::from_simplices(17, &[&a, &b]).unwrap();
        let got = Census::of(&c);
        assert_eq!((got.unclassified_links, got.approximated_links), (0, 0));
        assert_eq!(got.non_manifold, vec![0; 16]);
        // 0 and 16 are manifold points of the 15-ball; so is every vertex: C_v = n_0.
        assert_eq!(got.c_v_minus_n0, 0);
    }

    /// A cone v * ∂X over the boundary of the (k+1)-dimensional cross-polytope (k = 6; v = 0,
    /// vertices 2i+1 and 2i+2 opposite, 2^{k+1} facets): the link of v is ∂X, neither a simplex, its
    /// boundary nor a cone, whose recursive test branches 2(k+1) ways per level. The census
    /// ends within its work budget and names v among the simplices it could not classify.
    #[test]
    fn cone_over_a_cross_polytope_ends_with_unclassified_links_named() {
        let k = 6u32;
        let v = 0;
        let tops: Vec<Vec<u32>> = cross_polytope_boundary(k, 1)
            .into_iter()
            .map(|f| [vec![v], f].concat())
            .collect();
        let refs: Vec<&[u32]> = tops.iter().map(Vec::as_slice).collect();
        let c = Complex::from_simplices(2 * k + 3, &refs).unwrap();
        let got = Census::of(&c);
        assert!(got.unclassified_links > 0);
        assert!(
            got.unclassified_examples.contains(&vec![v]),
            "{:?}",
            got.unclassified_examples
        );
        assert!(got.unclassified_examples.len() <= UNCLASSIFIED_SHOWN);
        // What was classified is right: a cone over a sphere is a ball, nothing non-manifold.
        assert_eq!(got.non_manifold, vec![0; k as usize + 2]);
    }
}
