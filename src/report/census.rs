//! The census of a complex (the survey's Table 1(a) and Table 3 columns): see the definitions in
//! the [module documentation](super).

use serde::Serialize;

use crate::complex::Complex;
use crate::structures::iqm::Iqm;

/// What the survey's tables count for one dataset. Definitions: [`super`].
#[derive(Debug, Clone, PartialEq, Eq, Serialize)]
pub struct Census {
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
}

impl Census {
    /// Counts everything for `complex`: O(Σ_τ 2^{dim τ+1}) faces of top simplices grouped per
    /// vertex, plus one link test per simplex (small: the link of σ has the size of its star).
    pub fn of(complex: &Complex) -> Census {
        let d = complex.dimension();
        let top_simplices = complex.top_counts();
        let simplices: Vec<usize> = complex.closure().iter().map(|t| t.len()).collect();
        let n = complex.vertex_count() as usize;
        let links = LinkCounts::of(complex, None);
        Census {
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
        }
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
    /// The non-manifold simplices of dimension up to the limit asked for, by dimension.
    listed: Vec<Vec<Vec<u32>>>,
}

impl LinkCounts {
    /// Every simplex σ is visited once, at its lowest vertex v: the top simplices containing σ
    /// are those of the star of v whose part above v contains σ \ {v}, so each top τ ∋ v lists
    /// every subset of its vertices above v and equal subsets are grouped.
    fn of(complex: &Complex, list_up_to: Option<usize>) -> LinkCounts {
        let d = complex.dimension();
        let n = complex.vertex_count() as usize;
        // Star of each vertex (CSR over the top simplices of dimension ≥ 1).
        let mut tops: Vec<&[u32]> = Vec::new();
        for p in 1..=d {
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

        let mut out = LinkCounts {
            c_e: 0,
            c_v: 0,
            non_manifold: vec![0; d + 1],
            approximated: 0,
            listed: vec![Vec::new(); list_up_to.map_or(0, |m| m.min(d) + 1)],
        };
        // Per-vertex scratch: subsets as (start in `keys`, length, top), grouped by sorting.
        let mut keys: Vec<u32> = Vec::new();
        let mut entries: Vec<(u32, u8, u32)> = Vec::new();
        let mut link = Rows::default();
        for v in 0..n {
            let st = &star[off[v] as usize..off[v + 1] as usize];
            // An isolated vertex: empty link, a 0-manifold with no component.
            if st.is_empty() {
                continue;
            }
            keys.clear();
            entries.clear();
            for &g in st {
                let t = tops[g as usize];
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
                    let t = tops[e.2 as usize];
                    link.push(
                        t.iter()
                            .copied()
                            .filter(|&x| x as usize != v && rho.binary_search(&x).is_err()),
                    );
                }
                let p = rho.len();
                let a = analyse(&link);
                if a.shape == Shape::Neither {
                    out.non_manifold[p] += 1;
                    if let Some(list) = out.listed.get_mut(p) {
                        list.push(
                            std::iter::once(v as u32)
                                .chain(rho.iter().copied())
                                .collect(),
                        );
                    }
                }
                if a.approximate && a.shape != Shape::Neither {
                    out.approximated += 1;
                }
                if p == 0 {
                    out.c_v += a.components as u64;
                } else if p == 1 && a.shape == Shape::Neither {
                    out.c_e += a.components as u64;
                }
                i = j;
            }
        }
        out
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
/// complex whose maximal simplices are `rows` (see the module documentation for exactness).
pub(crate) fn analyse(rows: &Rows) -> Analysis {
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
        shape(rows, &verts, &mut approximate)
    };
    Analysis {
        components,
        shape,
        approximate,
    }
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

/// Sphere/ball test of a connected complex with vertices `verts`.
fn shape(rows: &Rows, verts: &[u32], approximate: &mut bool) -> Shape {
    if verts.is_empty() {
        return Shape::Sphere;
    }
    let arity = rows.row(0).len();
    if rows.iter().any(|r| r.len() != arity) {
        return Shape::Neither;
    }
    let k = arity - 1;
    if k == 0 {
        // Connected: one point (two points are handled with the components).
        return Shape::Ball;
    }
    if k == 1 {
        // A connected graph with degrees ≤ 2 is a path or a cycle.
        let mut degree = vec![0u32; verts.len()];
        for r in rows.iter() {
            for x in r {
                degree[verts.binary_search(x).unwrap()] += 1;
            }
        }
        if degree.iter().any(|&g| g > 2) {
            return Shape::Neither;
        }
        return match degree.iter().filter(|&&g| g == 1).count() {
            0 => Shape::Sphere,
            2 => Shape::Ball,
            _ => Shape::Neither,
        };
    }
    // k ≥ 2: a pseudo-manifold (each facet in one or two k-simplices) ...
    let mut facets: Vec<u32> = Vec::with_capacity(rows.len() * arity * k);
    for r in rows.iter() {
        for skip in 0..arity {
            facets.extend(
                r.iter()
                    .enumerate()
                    .filter(|&(i, _)| i != skip)
                    .map(|(_, &x)| x),
            );
        }
    }
    let facets = counted_rows(k, &facets);
    if facets.iter().any(|&(_, c)| c > 2) {
        return Shape::Neither;
    }
    // ... whose vertex links are (k−1)-spheres or balls (a combinatorial manifold) ...
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
        let a = analyse(&sub);
        *approximate |= a.approximate;
        if a.shape == Shape::Neither {
            return Shape::Neither;
        }
    }
    // ... told apart by its boundary and Euler characteristic.
    let chi = euler_characteristic(rows, arity);
    let closed = facets.iter().all(|&(_, c)| c == 2);
    if k == 2 {
        // A connected compact surface: closed with χ = 2 is the sphere; with boundary, χ = 1
        // leaves only the disk (the projective plane, the other χ = 1 surface, is closed).
        return match (closed, chi) {
            (true, 2) => Shape::Sphere,
            (false, 1) => Shape::Ball,
            _ => Shape::Neither,
        };
    }
    // k ≥ 3: necessary conditions only (a homology sphere passes).
    *approximate = true;
    let sphere_chi = if k.is_multiple_of(2) { 2 } else { 0 };
    if closed {
        return if chi == sphere_chi {
            Shape::Sphere
        } else {
            Shape::Neither
        };
    }
    let mut boundary = Rows::default();
    for (f, _) in facets.iter().filter(|&&(_, c)| c == 1) {
        boundary.push(f.iter().copied());
    }
    let b = analyse(&boundary);
    if b.shape == Shape::Sphere && chi == 1 {
        Shape::Ball
    } else {
        Shape::Neither
    }
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
        let count = crate::complex::sort_dedup_rows(len, f).len() / len;
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
    use crate::fixtures;

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
    }

    #[test]
    fn builtin_example() {
        // Components of lk(v): 2 at v2 (tet, triangle 2 7 8), v3 (tet, wire 3-4), v4 (two
        // wires), none at the isolated v9: C_v = 12. Non-manifold: v0, v1 (link: a triangle
        // with a hair), v2, v3; edge 0-1 (link: edge 2-3 and point 6, 2 clusters). v4 sits
        // inside the path 3-4-5 (link: two points), a manifold point.
        check(
            "builtin",
            &fixtures::builtin_example(),
            (2, 2, vec![1, 2, 2, 1], 2, 2, 5, vec![4, 1, 0, 0]),
        );
    }

    #[test]
    fn bowtie() {
        // v2's link is two disjoint edges.
        check(
            "bowtie",
            &fixtures::bowtie(),
            (0, 0, vec![0, 0, 2], 0, 1, 2, vec![1, 0, 0]),
        );
    }

    #[test]
    fn three_triangles_on_an_edge() {
        // lk(0-1) = three points: 3 clusters. lk(0), lk(1): a star with a degree-3 centre.
        check(
            "fan3",
            &fixtures::three_triangles_on_an_edge(),
            (0, 0, vec![0, 0, 3], 3, 0, 3, vec![2, 1, 0]),
        );
    }

    #[test]
    fn tetrahedron_with_dangling_triangle_and_wire() {
        // lk(2-3): edge 0-1 and point 4. v2, v3: a triangle plus an edge; v4: an edge plus a
        // point (two components).
        check(
            "tet+triangle+wire",
            &fixtures::tetrahedron_with_dangling_triangle_and_wire(),
            (1, 1, vec![0, 1, 1, 1], 2, 1, 3, vec![3, 1, 0, 0]),
        );
    }

    #[test]
    fn pinched_pie() {
        // lk(0) is one figure eight (connected: C_v counts 1) but not a circle; edge 0-1 is in
        // four triangles. The two fans are two IQM components.
        check(
            "pinched pie",
            &fixtures::pinched_pie(),
            (0, 0, vec![0, 0, 6], 4, 0, 2, vec![2, 1, 0]),
        );
    }

    #[test]
    fn strip_pinched_at_a_vertex() {
        // lk(0): paths 1-2-3 and 4-5-6. Every edge is in one or two triangles. One IQM
        // component (0 is split inside it).
        check(
            "strip",
            &fixtures::strip_pinched_at_a_vertex(),
            (0, 0, vec![0, 0, 6], 0, 1, 1, vec![1, 0, 0]),
        );
    }

    #[test]
    fn four_iqm_components_two_clusters() {
        // lk(0): {123,124,134,125}, {678}, {9 10}: 3 components. Triangle 012 is in three
        // tetrahedra, so edges 01, 02, 12 have a degree-3 link vertex (one cluster each) and
        // v1, v2 have an edge in three link triangles; v3, v4 have two link triangles on an
        // edge (a disk).
        check(
            "fig5",
            &fixtures::four_iqm_components_two_clusters(),
            (0, 1, vec![0, 0, 1, 5], 3, 2, 4, vec![3, 3, 1, 0]),
        );
    }

    fn shape_of(rows: &[&[u32]]) -> (Shape, bool) {
        let a = analyse(&Rows::from(rows));
        (a.shape, a.approximate)
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
        let refs: Vec<&[u32]> = rows.iter().map(Vec::as_slice).collect();
        assert_eq!(shape_of(&refs), (Sphere, false));
        assert_eq!(shape_of(&refs[1..]), (Ball, false));
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
        let rows = sorted(&torus);
        let refs: Vec<&[u32]> = rows.iter().map(Vec::as_slice).collect();
        assert_eq!(shape_of(&refs), (Neither, false));
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
        let rows = sorted(&rp2);
        let refs: Vec<&[u32]> = rows.iter().map(Vec::as_slice).collect();
        assert_eq!(shape_of(&refs), (Neither, false));
        // Dimension 3: one tetrahedron is a ball, the boundary of the 4-simplex a sphere —
        // both through the necessary conditions only.
        assert_eq!(shape_of(&[&[0, 1, 2, 3]]), (Ball, true));
        let s3: Vec<Vec<u32>> = (0..5u32)
            .map(|skip| (0..5).filter(|&v| v != skip).collect())
            .collect();
        let refs: Vec<&[u32]> = s3.iter().map(Vec::as_slice).collect();
        assert_eq!(shape_of(&refs), (Sphere, true));
    }

    #[test]
    fn a_vertex_of_a_4_simplex_has_an_approximated_link() {
        // The 4-simplex: every vertex's link is a tetrahedron (a 3-ball), tested approximately;
        // no simplex is non-manifold.
        let c = Complex::from_simplices(5, &[&[0, 1, 2, 3, 4]]).unwrap();
        let got = Census::of(&c);
        assert_eq!(got.non_manifold, vec![0; 5]);
        assert_eq!(got.approximated_links, 5);
        assert_eq!((got.c_e, got.c_v_minus_n0), (0, 0));
    }
}
