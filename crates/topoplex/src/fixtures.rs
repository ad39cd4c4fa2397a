//! Small named complexes with drawings, shared by tests, the CLI's built-in example and fuzz
//! seeds. Each returns a normalised [`Complex`].

use crate::complex::Complex;

fn make(n: u32, simplices: &[&[u32]]) -> Complex {
    Complex::from_simplices(n, simplices).expect("fixture is a valid complex")
}

/// The CLI's built-in example: a tetrahedron with a dangling triangle on one of its edges, two
/// wire edges hanging from the top vertex, a second triangle pinched at a vertex, and an
/// isolated vertex.
///
/// ```text
///            4 ----- 5        wire edges 3-4 and 4-5
///            |
///            3                tetrahedron 0 1 2 3
///           /|\               dangling triangle 0 1 6 on edge 0-1 (non-manifold edge)
///          / | \              triangle 2 7 8 touching only at vertex 2 (non-manifold vertex)
///    6----0--|--2----7
///         \ \|/ /   \|
///          \-1-/     8        isolated vertex 9
/// ```
pub fn builtin_example() -> Complex {
    make(
        10,
        &[&[0, 1, 2, 3], &[0, 1, 6], &[3, 4], &[4, 5], &[2, 7, 8]],
    )
}

/// Two triangles sharing only vertex 2.
///
/// ```text
///   0       3
///   | \   / |
///   |  2    |
///   | /   \ |
///   1       4
/// ```
pub fn bowtie() -> Complex {
    make(5, &[&[0, 1, 2], &[2, 3, 4]])
}

/// Three triangles on edge 0-1 (a non-manifold edge), as in `fan3.obj`.
///
/// ```text
///        2
///        |
///   3 -- 0 -- 4       each of 2, 3, 4 is joined to 0 and 1;
///        |            edge 0-1 runs into the page
///        1
/// ```
pub fn three_triangles_on_an_edge() -> Complex {
    make(5, &[&[0, 1, 2], &[0, 1, 3], &[0, 1, 4]])
}

/// A tetrahedron 0123, a dangling triangle 2 3 4 on its edge 2-3, and a wire edge 4-5.
///
/// ```text
///          3 ------ 4 ------ 5
///         /|\      /
///        / | \    /
///       0--|--2--/
///        \ | /
///         \|/
///          1
/// ```
pub fn tetrahedron_with_dangling_triangle_and_wire() -> Complex {
    make(6, &[&[0, 1, 2, 3], &[2, 3, 4], &[4, 5]])
}

/// A pinched pie: two closed fans around vertex 0 whose rims are the cycles 1-2-3 and 1-4-5,
/// which share vertex 1. The link of 0 is one connected figure-eight, so 0 is not a
/// non-manifold vertex by the link definition, yet the domain is pinched at 0 (and edge 0-1 is
/// in four triangles).
///
/// ```text
///        2       4
///       / \     / \
///      3---1---5   |     rims 1-2-3-1 and 1-4-5-1, every rim edge joined to 0,
///       \  |  /    |     which sits above 1 (out of the page)
///        `-0-'----'
/// ```
pub fn pinched_pie() -> Complex {
    make(
        6,
        &[
            &[0, 1, 2],
            &[0, 2, 3],
            &[0, 1, 3],
            &[0, 1, 4],
            &[0, 4, 5],
            &[0, 1, 5],
        ],
    )
}

/// A pseudo-manifold that is not an initial quasi-manifold (the survey's Fig. 1b): a strip of
/// six triangles whose two ends both touch vertex 0. Every edge is in at most two triangles and
/// the triangles are edge-connected, but the star of 0 is two fans joined only away from 0.
///
/// ```text
///    0 ---- 3 ---- 5 ---- 6        top row
///   / \    / \    / \    /
///  /   \  /   \  /   \  /
/// 1 ---- 2 ---- 4 ---- 0           bottom row: vertex 0 again
/// ```
pub fn strip_pinched_at_a_vertex() -> Complex {
    make(
        7,
        &[
            &[0, 1, 2],
            &[0, 2, 3],
            &[2, 3, 4],
            &[3, 4, 5],
            &[0, 4, 5],
            &[0, 5, 6],
        ],
    )
}

/// The star of vertex 0 with four IQM components but two 3-clusters and one 2-cluster (the
/// survey's Fig. 5): tetrahedra 0123, 0124, 0125 on triangle 012 (a non-manifold triangle),
/// with 0134 joining 0123 and 0124 through triangles 013 and 014; a tetrahedron 0678 touching
/// at 0 only; a triangle 0 9 10 touching at 0 only.
///
/// ```text
///              5                  3-cluster {0123, 0124, 0134, 0125}: IQM components
///              |                  {0123, 0124, 0134} and {0125}
///      3 ----- 1 ----- 4
///       \    / \    /             3-cluster {0678}
///        \  /   \  /   6-7-8     2-cluster {0 9 10}
///          0 ----- 2     \|/
///          | \           0        (0 drawn twice)
///          9--10
/// ```
pub fn four_iqm_components_two_clusters() -> Complex {
    make(
        11,
        &[
            &[0, 1, 2, 3],
            &[0, 1, 2, 4],
            &[0, 1, 3, 4],
            &[0, 1, 2, 5],
            &[0, 6, 7, 8],
            &[0, 9, 10],
        ],
    )
}

/// The Freudenthal (Kuhn) triangulation of the k×k×k grid of unit cubes: every cube cut into
/// the six tetrahedra around its main diagonal, 6k³ tetrahedra over the (k+1)³ grid points
/// (~26k³ simplices with their faces). The generator behind [`tetrahedral_grid`] and the
/// tetrahedral grids that tests, benches and the `scale` example write out.
///
/// Each tetrahedron comes as its four corners numbered by `vertex` (given a corner's grid
/// coordinates `[x, y, z]`, each in `0..=k`), walking from the cube's lowest corner to its
/// highest one axis step at a time. Cubes come by x, then y, then z (z varying fastest), six
/// tetrahedra each, for the axis orders 012, 021, 102, 120, 201, 210. Lazy: a grid too large to
/// hold can be written out as it is generated.
///
/// ```
/// use topoplex::fixtures::freudenthal_grid;
/// // One cube, corner (x, y, z) numbered x + 2y + 4z: six tetrahedra around the diagonal 0-7.
/// let tets: Vec<[u32; 4]> = freudenthal_grid(1, |[x, y, z]| x | y << 1 | z << 2).collect();
/// assert_eq!(tets[0], [0, 1, 3, 7]);
/// assert_eq!(tets[5], [0, 4, 6, 7]);
/// assert_eq!(freudenthal_grid(3, |_| 0).count(), 6 * 27);
/// ```
pub fn freudenthal_grid(
    k: u32,
    vertex: impl Fn([u32; 3]) -> u32,
) -> impl Iterator<Item = [u32; 4]> {
    const AXIS_ORDERS: [[usize; 3]; 6] = [
        [0, 1, 2],
        [0, 2, 1],
        [1, 0, 2],
        [1, 2, 0],
        [2, 0, 1],
        [2, 1, 0],
    ];
    let cubes = (0..k).flat_map(move |x| (0..k).flat_map(move |y| (0..k).map(move |z| [x, y, z])));
    cubes
        .flat_map(|lowest| {
            AXIS_ORDERS.map(|axes| {
                let mut p = lowest;
                let mut corners = [p; 4];
                for (corner, axis) in corners[1..].iter_mut().zip(axes) {
                    p[axis] += 1;
                    *corner = p;
                }
                corners
            })
        })
        .map(move |corners| corners.map(&vertex))
}

/// The k×k×k grid of [`freudenthal_grid`] as a complex: (k+1)³ vertices, (x, y, z) numbered
/// (x·(k+1) + y)·(k+1) + z, and the 6k³ tetrahedra listed in the generator's order.
pub fn tetrahedral_grid(k: u32) -> Complex {
    let n = k + 1;
    let tets: Vec<[u32; 4]> = freudenthal_grid(k, |[x, y, z]| (x * n + y) * n + z).collect();
    let refs: Vec<&[u32]> = tets.iter().map(|t| &t[..]).collect();
    make(n * n * n, &refs)
}

/// Every fixture by name (tests iterate over them).
pub fn all() -> Vec<(&'static str, Complex)> {
    vec![
        ("builtin_example", builtin_example()),
        ("bowtie", bowtie()),
        ("three_triangles_on_an_edge", three_triangles_on_an_edge()),
        (
            "tetrahedron_with_dangling_triangle_and_wire",
            tetrahedron_with_dangling_triangle_and_wire(),
        ),
        ("pinched_pie", pinched_pie()),
        ("strip_pinched_at_a_vertex", strip_pinched_at_a_vertex()),
        (
            "four_iqm_components_two_clusters",
            four_iqm_components_two_clusters(),
        ),
    ]
}
