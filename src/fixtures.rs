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
    ]
}
