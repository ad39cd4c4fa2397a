//! Garland–Heckbert error quadrics in any coordinate dimension, for simplices of any dimension.
//!
//! In R^n the squared distance from a point x to the affine hull of a k-simplex with vertices
//! p_0..p_k is `(x − p_0)ᵀ (I − U Uᵀ) (x − p_0)`, U an orthonormal basis of the simplex's
//! edge directions p_i − p_0 (Garland and Zhou's generalisation, 2005). Expanded, that is the
//! quadric `Q(x) = xᵀ A x + 2 bᵀ x + c` with `A = I − U Uᵀ`, `b = −A p_0`, `c = p_0ᵀ A p_0`:
//! for a triangle in R^3 it is Garland and Heckbert's plane quadric, for an edge in R^3 the
//! squared distance to its line, for a vertex the squared distance to the point. A simplex
//! spanning all of R^n (a tetrahedron in R^3) has `A = 0`: its quadric is zero and only the
//! quadrics of its boundary facets hold the shape (see [`super`]).
//!
//! Quadrics add: a vertex's quadric is the sum of its simplices' quadrics, each weighted by a
//! function of the simplex's k-volume that the caller chooses (OpenMesh's ModQuadric and
//! Garland and Heckbert weight by area). Storage: `(n + 1)(n + 2) / 2` numbers per quadric (10 in R^3): the
//! upper triangle of A row by row, then b, then c.

/// The layout of quadrics in R^n: packs and unpacks the `(n + 1)(n + 2) / 2` numbers.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct QuadricSpace {
    n: usize,
}

/// Relative size under which a pivot or an edge direction counts as zero.
const EPS: f64 = 1e-12;

impl QuadricSpace {
    /// The space of quadrics over R^`n` (`n` numbers per point).
    pub fn new(n: usize) -> QuadricSpace {
        QuadricSpace { n }
    }

    /// Coordinate dimension n.
    pub fn dim(&self) -> usize {
        self.n
    }

    /// Numbers per quadric: `(n + 1)(n + 2) / 2`.
    pub fn len(&self) -> usize {
        (self.n + 1) * (self.n + 2) / 2
    }

    /// Always false: even R^0 has the constant term.
    pub fn is_empty(&self) -> bool {
        false
    }

    /// Index of A[i][j] (i ≤ j) in the packed upper triangle.
    fn a(&self, i: usize, j: usize) -> usize {
        debug_assert!(i <= j && j < self.n);
        i * self.n - i * (i.saturating_sub(1)) / 2 + (j - i)
    }

    fn b(&self, i: usize) -> usize {
        self.n * (self.n + 1) / 2 + i
    }

    fn c(&self) -> usize {
        self.len() - 1
    }

    /// Adds `weight(vol)` × the squared distance to the affine hull of `points` (k + 1 points
    /// of n numbers each, flat) into `q`, `vol` being the simplex's k-volume (1 for a point);
    /// returns `vol`. `scratch` is reused so that no call allocates once it has grown.
    pub fn add_simplex(
        &self,
        q: &mut [f64],
        points: &[f64],
        scratch: &mut Vec<f64>,
        weight: impl FnOnce(f64) -> f64,
    ) -> f64 {
        let n = self.n;
        let k = points.len() / n - 1;
        let p0 = &points[..n];
        // Orthonormal basis of the edge directions (modified Gram–Schmidt); the product of the
        // residual lengths is k! × the k-volume.
        scratch.clear();
        let mut volume = 1.0;
        let mut rank = 0;
        for i in 1..=k {
            let start = rank * n;
            scratch.extend((0..n).map(|t| points[i * n + t] - p0[t]));
            let scale = norm(&scratch[start..start + n]);
            for r in 0..rank {
                let (basis, e) = scratch.split_at_mut(start);
                let u = &basis[r * n..r * n + n];
                let d = dot(u, e);
                for t in 0..n {
                    e[t] -= d * u[t];
                }
            }
            let len = norm(&scratch[start..start + n]);
            if len <= EPS * scale.max(f64::MIN_POSITIVE) {
                // A degenerate simplex: no volume, so no weight, but its hull is still spanned.
                volume = 0.0;
                scratch.truncate(start);
                continue;
            }
            volume *= len / i as f64;
            for x in &mut scratch[start..start + n] {
                *x /= len;
            }
            rank += 1;
        }
        let weight = weight(volume);
        if weight == 0.0 {
            return volume;
        }
        // A = I − U Uᵀ, b = −A p0, c = p0ᵀ A p0, all times the weight.
        let basis = &scratch[..rank * n];
        let entry = |i: usize, j: usize| {
            let mut v = if i == j { 1.0 } else { 0.0 };
            for u in basis.chunks_exact(n) {
                v -= u[i] * u[j];
            }
            v
        };
        let mut c = 0.0;
        for i in 0..n {
            let mut ap = 0.0;
            for j in 0..n {
                let aij = entry(i.min(j), i.max(j));
                if j >= i {
                    q[self.a(i, j)] += weight * aij;
                }
                ap += aij * p0[j];
            }
            q[self.b(i)] -= weight * ap;
            c += p0[i] * ap;
        }
        q[self.c()] += weight * c;
        volume
    }

    /// `Q(x) = xᵀ A x + 2 bᵀ x + c` (clamped at 0 against rounding).
    pub fn eval(&self, q: &[f64], x: &[f64]) -> f64 {
        let n = self.n;
        let mut s = q[self.c()];
        for i in 0..n {
            let mut row = q[self.a(i, i)] * x[i];
            for j in i + 1..n {
                row += 2.0 * q[self.a(i, j)] * x[j];
            }
            s += x[i] * row + 2.0 * q[self.b(i)] * x[i];
        }
        s.max(0.0)
    }

    /// The point minimising `q` (solves `A x = −b`), or `None` when A is singular: Gaussian
    /// elimination with partial pivoting in `scratch` (n × (n + 1) numbers), a pivot below
    /// 1e-12 × the largest diagonal entry counting as zero.
    pub fn minimiser(&self, q: &[f64], x: &mut [f64], scratch: &mut Vec<f64>) -> bool {
        let n = self.n;
        let w = n + 1;
        scratch.clear();
        let mut diag: f64 = 0.0;
        for i in 0..n {
            for j in 0..n {
                scratch.push(q[self.a(i.min(j), i.max(j))]);
            }
            scratch.push(-q[self.b(i)]);
            diag = diag.max(q[self.a(i, i)].abs());
        }
        if diag == 0.0 {
            return false;
        }
        let m = scratch.as_mut_slice();
        for col in 0..n {
            let piv = (col..n)
                .max_by(|&r, &s| m[r * w + col].abs().total_cmp(&m[s * w + col].abs()))
                .unwrap_or(col);
            if m[piv * w + col].abs() <= EPS * diag {
                return false;
            }
            if piv != col {
                for t in 0..w {
                    m.swap(piv * w + t, col * w + t);
                }
            }
            for r in col + 1..n {
                let f = m[r * w + col] / m[col * w + col];
                if f != 0.0 {
                    for t in col..w {
                        m[r * w + t] -= f * m[col * w + t];
                    }
                }
            }
        }
        for i in (0..n).rev() {
            let mut s = m[i * w + n];
            for j in i + 1..n {
                s -= m[i * w + j] * x[j];
            }
            x[i] = s / m[i * w + i];
        }
        x.iter().all(|v| v.is_finite())
    }

    /// The point of segment [p, r] minimising `q` (a quadratic in the segment parameter t,
    /// clamped to [0, 1]) into `x`.
    pub fn segment_minimiser(&self, q: &[f64], p: &[f64], r: &[f64], x: &mut [f64]) {
        // Q(p + t d) = Q(p) + 2 t (A p + b)·d + t² dᵀ A d.
        let n = self.n;
        let mut slope = 0.0;
        let mut curv = 0.0;
        for i in 0..n {
            let di = r[i] - p[i];
            let (mut ap, mut ad) = (q[self.b(i)], 0.0);
            for j in 0..n {
                let aij = q[self.a(i.min(j), i.max(j))];
                ap += aij * p[j];
                ad += aij * (r[j] - p[j]);
            }
            slope += ap * di;
            curv += ad * di;
        }
        let t = if curv > 0.0 {
            (-slope / curv).clamp(0.0, 1.0)
        } else if slope + curv < 0.0 {
            1.0 // Q(r) − Q(p) = 2 slope + curv < slope + curv when slope < 0
        } else {
            0.0
        };
        for i in 0..n {
            x[i] = p[i] + t * (r[i] - p[i]);
        }
    }
}

/// `out[i] = a[i] + b[i]`.
pub fn sum_into(a: &[f64], b: &[f64], out: &mut [f64]) {
    for ((o, x), y) in out.iter_mut().zip(a).zip(b) {
        *o = x + y;
    }
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

fn norm(a: &[f64]) -> f64 {
    dot(a, a).sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn quadric(n: usize, simplices: &[&[f64]]) -> (QuadricSpace, Vec<f64>, f64) {
        let s = QuadricSpace::new(n);
        let mut q = vec![0.0; s.len()];
        let mut scratch = Vec::new();
        let mut vol = 0.0;
        for pts in simplices {
            vol += s.add_simplex(&mut q, pts, &mut scratch, |v| v);
        }
        (s, q, vol)
    }

    fn close(a: f64, b: f64) -> bool {
        (a - b).abs() <= 1e-9 * (1.0 + a.abs().max(b.abs()))
    }

    #[test]
    fn triangle_in_the_plane_z0_measures_area_times_height_squared() {
        //   y
        //   2 .
        //     |  .
        //     0----1  x     (0,0,0) (2,0,0) (0,2,0): area 2
        let (s, q, vol) = quadric(3, &[&[0., 0., 0., 2., 0., 0., 0., 2., 0.]]);
        assert!(close(vol, 2.0));
        assert!(close(s.eval(&q, &[5.0, -7.0, 3.0]), 2.0 * 9.0));
        assert!(close(s.eval(&q, &[1.0, 1.0, 0.0]), 0.0));
        // The plane's quadric alone is singular (any point of the plane is optimal).
        let mut x = [0.0; 3];
        assert!(!s.minimiser(&q, &mut x, &mut Vec::new()));
    }

    #[test]
    fn three_coordinate_planes_meet_at_their_corner() {
        // Right triangles of area 1/2 in z=1, y=2 and x=3: the minimiser is (3, 2, 1).
        let (s, q, _) = quadric(
            3,
            &[
                &[0., 0., 1., 1., 0., 1., 0., 1., 1.],
                &[0., 2., 0., 1., 2., 0., 0., 2., 1.],
                &[3., 0., 0., 3., 1., 0., 3., 0., 1.],
            ],
        );
        let mut x = [0.0; 3];
        assert!(s.minimiser(&q, &mut x, &mut Vec::new()));
        for (a, b) in x.iter().zip([3.0, 2.0, 1.0]) {
            assert!(close(*a, b), "{x:?}");
        }
        assert!(close(s.eval(&q, &x), 0.0));
        // At the origin: 0.5 × (1² + 2² + 3²).
        assert!(close(s.eval(&q, &[0.0; 3]), 7.0));
    }

    #[test]
    fn edge_in_r3_measures_distance_to_its_line() {
        // Edge (0,0,0)-(0,0,3) on the z axis, length 3.
        let (s, q, vol) = quadric(3, &[&[0., 0., 0., 0., 0., 3.]]);
        assert!(close(vol, 3.0));
        assert!(close(s.eval(&q, &[3.0, 4.0, 100.0]), 3.0 * 25.0));
    }

    #[test]
    fn vertex_measures_squared_distance_with_weight_one() {
        let (s, q, _) = quadric(2, &[&[1.0, 2.0]]);
        assert!(close(s.eval(&q, &[4.0, 6.0]), 25.0));
        let mut x = [0.0; 2];
        assert!(s.minimiser(&q, &mut x, &mut Vec::new()));
        assert!(close(x[0], 1.0) && close(x[1], 2.0));
    }

    #[test]
    fn tetrahedron_in_r3_spans_the_space_and_has_zero_quadric() {
        let (_, q, vol) = quadric(3, &[&[0., 0., 0., 1., 0., 0., 0., 1., 0., 0., 0., 1.]]);
        assert!(close(vol, 1.0 / 6.0));
        assert!(q.iter().all(|&v| v.abs() < 1e-15), "{q:?}");
    }

    #[test]
    fn tetrahedron_in_r4_measures_distance_to_its_hyperplane() {
        // The unit corner tetrahedron in the hyperplane w = 0 of R^4, volume 1/6.
        let (s, q, vol) = quadric(
            4,
            &[&[
                0., 0., 0., 0., 1., 0., 0., 0., 0., 1., 0., 0., 0., 0., 1., 0.,
            ]],
        );
        assert!(close(vol, 1.0 / 6.0));
        assert!(close(s.eval(&q, &[9.0, -9.0, 9.0, 2.0]), 4.0 / 6.0));
    }

    #[test]
    fn slanted_triangle_and_degenerate_triangle() {
        // The triangle (1,0,0) (0,1,0) (0,0,1): plane x+y+z=1, area √3/2.
        let (s, q, vol) = quadric(3, &[&[1., 0., 0., 0., 1., 0., 0., 0., 1.]]);
        assert!(close(vol, 3f64.sqrt() / 2.0));
        // Distance² from the origin is 1/3.
        assert!(close(s.eval(&q, &[0.0; 3]), 3f64.sqrt() / 2.0 / 3.0));
        // Three collinear points: zero area, so no contribution.
        let (_, q, vol) = quadric(3, &[&[0., 0., 0., 1., 1., 1., 2., 2., 2.]]);
        assert_eq!(vol, 0.0);
        assert!(q.iter().all(|&v| v == 0.0));
    }

    #[test]
    fn segment_minimiser_clamps_to_the_segment() {
        // Quadric of the point (1, 0) in R^2; segment (0,0)-(4,0): optimum t = 1/4.
        let (s, q, _) = quadric(2, &[&[1.0, 0.0]]);
        let mut x = [0.0; 2];
        s.segment_minimiser(&q, &[0.0, 0.0], &[4.0, 0.0], &mut x);
        assert!(close(x[0], 1.0) && close(x[1], 0.0));
        // Segment (2,0)-(5,0): clamped at its start.
        s.segment_minimiser(&q, &[2.0, 0.0], &[5.0, 0.0], &mut x);
        assert!(close(x[0], 2.0));
        // Flat quadric (a line): the end with the lower value, here both equal → start.
        let (s, q, _) = quadric(2, &[&[0.0, 0.0, 1.0, 0.0]]);
        s.segment_minimiser(&q, &[0.0, 1.0], &[0.0, 3.0], &mut x);
        assert!(close(x[1], 1.0));
    }

    #[test]
    fn packing_indexes_every_entry_once() {
        for n in 0..7 {
            let s = QuadricSpace::new(n);
            let mut seen = vec![false; s.len()];
            for i in 0..n {
                for j in i..n {
                    assert!(!seen[s.a(i, j)]);
                    seen[s.a(i, j)] = true;
                }
                seen[s.b(i)] = true;
            }
            seen[s.c()] = true;
            assert!(seen.iter().all(|&b| b), "n = {n}");
        }
    }
}
