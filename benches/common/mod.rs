//! Generated complexes shared by the benches (`structures`, `sig`): triangle and tetrahedral
//! grids.

use topoplex::Complex;

/// A k×k grid of squares, each cut into two triangles: (k+1)² vertices, ~6k² simplices.
pub fn triangle_grid(k: u32) -> Complex {
    let id = |i: u32, j: u32| i * (k + 1) + j;
    let mut tris = Vec::with_capacity(2 * (k * k) as usize);
    for i in 0..k {
        for j in 0..k {
            tris.push(vec![id(i, j), id(i + 1, j), id(i + 1, j + 1)]);
            tris.push(vec![id(i, j), id(i, j + 1), id(i + 1, j + 1)]);
        }
    }
    complex((k + 1) * (k + 1), &tris)
}

/// A k×k×k grid of cubes, each cut into the six tetrahedra around its main diagonal
/// (Freudenthal): ~26k³ simplices.
pub use topoplex::fixtures::tetrahedral_grid;

pub fn complex(n: u32, simplices: &[Vec<u32>]) -> Complex {
    let refs: Vec<&[u32]> = simplices.iter().map(Vec::as_slice).collect();
    Complex::from_simplices(n, &refs).unwrap()
}
