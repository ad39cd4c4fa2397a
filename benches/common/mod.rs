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
pub fn tetrahedral_grid(k: u32) -> Complex {
    let n = k + 1;
    let id = |x: u32, y: u32, z: u32| (x * n + y) * n + z;
    let mut tets = Vec::with_capacity(6 * (k * k * k) as usize);
    let axes: [[u32; 3]; 3] = [[1, 0, 0], [0, 1, 0], [0, 0, 1]];
    for x in 0..k {
        for y in 0..k {
            for z in 0..k {
                for perm in [
                    [0, 1, 2],
                    [0, 2, 1],
                    [1, 0, 2],
                    [1, 2, 0],
                    [2, 0, 1],
                    [2, 1, 0],
                ] {
                    let mut p = [x, y, z];
                    let mut t = vec![id(p[0], p[1], p[2])];
                    for a in perm {
                        for c in 0..3 {
                            p[c] += axes[a][c];
                        }
                        t.push(id(p[0], p[1], p[2]));
                    }
                    tets.push(t);
                }
            }
        }
    }
    complex(n * n * n, &tets)
}

pub fn complex(n: u32, simplices: &[Vec<u32>]) -> Complex {
    let refs: Vec<&[u32]> = simplices.iter().map(Vec::as_slice).collect();
    Complex::from_simplices(n, &refs).unwrap()
}
