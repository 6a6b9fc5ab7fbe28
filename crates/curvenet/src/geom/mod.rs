//! Small geometric helpers shared by the pipeline stages: vector aliases, bounding boxes,
//! orthonormal frames and segment–segment closest points.

pub mod distance;
pub mod intersect;
pub mod mesh;
pub mod polyline;

pub use glam::{DVec2, DVec3};

/// Axis-aligned bounding box of a point set.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Aabb {
    /// Smallest coordinates.
    pub min: DVec3,
    /// Largest coordinates.
    pub max: DVec3,
}

impl Aabb {
    /// The empty box (min = +inf, max = −inf); `extend` grows it.
    pub fn empty() -> Self {
        Aabb { min: DVec3::splat(f64::INFINITY), max: DVec3::splat(f64::NEG_INFINITY) }
    }

    /// Bounding box of `points`; empty when `points` is.
    pub fn of(points: impl IntoIterator<Item = DVec3>) -> Self {
        let mut b = Self::empty();
        for p in points {
            b.extend(p);
        }
        b
    }

    /// Grows the box to contain `p`.
    pub fn extend(&mut self, p: DVec3) {
        self.min = self.min.min(p);
        self.max = self.max.max(p);
    }

    /// Length of the diagonal (0 for a single point, NaN-free: 0 for the empty box).
    pub fn diagonal(&self) -> f64 {
        if self.min.x > self.max.x {
            return 0.0;
        }
        (self.max - self.min).length()
    }

    /// The centre of the box.
    pub fn center(&self) -> DVec3 {
        0.5 * (self.min + self.max)
    }
}

/// Two unit vectors `(e1, e2)` with `e1 × e2 = n` for a unit `n` (a right-handed frame of the
/// plane orthogonal to `n`).
pub fn plane_frame(n: DVec3) -> (DVec3, DVec3) {
    // Pick the coordinate axis least aligned with n to avoid cancellation.
    let a = if n.x.abs() <= n.y.abs() && n.x.abs() <= n.z.abs() {
        DVec3::X
    } else if n.y.abs() <= n.z.abs() {
        DVec3::Y
    } else {
        DVec3::Z
    };
    let e1 = (a - n * a.dot(n)).normalize();
    let e2 = n.cross(e1);
    (e1, e2)
}

/// A cell of a uniform grid: the integer coordinates of `p / h`, floored.
pub type GridCell = (i64, i64, i64);

/// The cell of side `h` that holds `p`.
pub fn grid_cell(p: DVec3, h: f64) -> GridCell {
    ((p.x / h).floor() as i64, (p.y / h).floor() as i64, (p.z / h).floor() as i64)
}

/// The cells of side `h` that the segment `ab` inflated by `pad` meets, each once (sorted):
/// the boxes of its pieces of length ≤ `h`, so that a long segment fills a line of cells, not
/// the slab of its bounding box (a 2-sample CAD edge across a whole network). The spatial
/// index of node finding, of the sampler's boundary and near-miss grids.
pub fn segment_cells(a: DVec3, b: DVec3, pad: f64, h: f64, out: &mut Vec<GridCell>) {
    out.clear();
    let pieces = ((a.distance(b) / h).ceil() as usize).clamp(1, 1 << 24);
    for i in 0..pieces {
        let (p, q) = (a.lerp(b, i as f64 / pieces as f64), a.lerp(b, (i + 1) as f64 / pieces as f64));
        let (lo, hi) = (grid_cell(p.min(q) - DVec3::splat(pad), h), grid_cell(p.max(q) + DVec3::splat(pad), h));
        for x in lo.0..=hi.0 {
            for y in lo.1..=hi.1 {
                for z in lo.2..=hi.2 {
                    out.push((x, y, z));
                }
            }
        }
    }
    out.sort_unstable();
    out.dedup();
}

/// The unit eigenvector of the smallest eigenvalue of the symmetric 3×3 matrix `m` (cyclic
/// Jacobi rotations; Golub and Van Loan, *Matrix Computations*, §8.5): the normal of the plane
/// that best fits directions or points whose scatter matrix `m` is.
pub fn smallest_eigenvector(m: [[f64; 3]; 3]) -> DVec3 {
    let mut a = m;
    let mut v = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    for _ in 0..32 {
        let off = a[0][1] * a[0][1] + a[0][2] * a[0][2] + a[1][2] * a[1][2];
        if off <= 1e-30 * (a[0][0] * a[0][0] + a[1][1] * a[1][1] + a[2][2] * a[2][2]).max(1e-300) {
            break;
        }
        for (p, q) in [(0, 1), (0, 2), (1, 2)] {
            if a[p][q] == 0.0 {
                continue;
            }
            let theta = (a[q][q] - a[p][p]) / (2.0 * a[p][q]);
            let t = theta.signum() / (theta.abs() + (theta * theta + 1.0).sqrt());
            let t = if theta == 0.0 { 1.0 } else { t };
            let (c, s) = (1.0 / (t * t + 1.0).sqrt(), t / (t * t + 1.0).sqrt());
            for k in 0..3 {
                let (akp, akq) = (a[k][p], a[k][q]);
                a[k][p] = c * akp - s * akq;
                a[k][q] = s * akp + c * akq;
            }
            for k in 0..3 {
                let (apk, aqk) = (a[p][k], a[q][k]);
                a[p][k] = c * apk - s * aqk;
                a[q][k] = s * apk + c * aqk;
            }
            for row in v.iter_mut() {
                let (vp, vq) = (row[p], row[q]);
                row[p] = c * vp - s * vq;
                row[q] = s * vp + c * vq;
            }
        }
    }
    let k = (0..3).min_by(|&i, &j| a[i][i].total_cmp(&a[j][j])).unwrap_or(0);
    DVec3::new(v[0][k], v[1][k], v[2][k]).normalize_or_zero()
}

/// The scatter matrix `Σ (x − c)(x − c)ᵀ` of `xs` about `c`.
pub fn scatter(xs: impl IntoIterator<Item = DVec3>, c: DVec3) -> [[f64; 3]; 3] {
    let mut m = [[0.0; 3]; 3];
    for x in xs {
        let d = (x - c).to_array();
        for i in 0..3 {
            for j in 0..3 {
                m[i][j] += d[i] * d[j];
            }
        }
    }
    m
}

/// Closest points of the segments `p0p1` and `q0q1`: returns `(s, t)` in `[0,1]²` such that
/// `p0 + s (p1 − p0)` and `q0 + t (q1 − q0)` are closest (Ericson, *Real-Time Collision
/// Detection*, §5.1.9). Degenerate (zero-length) segments are handled as points.
pub fn closest_params_segment_segment(p0: DVec3, p1: DVec3, q0: DVec3, q1: DVec3) -> (f64, f64) {
    let d1 = p1 - p0;
    let d2 = q1 - q0;
    let r = p0 - q0;
    let a = d1.length_squared();
    let e = d2.length_squared();
    let f = d2.dot(r);
    let eps = 1e-300;
    if a <= eps && e <= eps {
        return (0.0, 0.0);
    }
    if a <= eps {
        return (0.0, (f / e).clamp(0.0, 1.0));
    }
    let c = d1.dot(r);
    if e <= eps {
        return ((-c / a).clamp(0.0, 1.0), 0.0);
    }
    let b = d1.dot(d2);
    let denom = a * e - b * b;
    let mut s = if denom > 1e-14 * a * e { ((b * f - c * e) / denom).clamp(0.0, 1.0) } else { 0.0 };
    let mut t = (b * s + f) / e;
    if t < 0.0 {
        t = 0.0;
        s = (-c / a).clamp(0.0, 1.0);
    } else if t > 1.0 {
        t = 1.0;
        s = ((b - c) / a).clamp(0.0, 1.0);
    }
    (s, t)
}

/// Signed area of a closed planar polygon (positive when counter-clockwise).
pub fn polygon_signed_area(poly: &[DVec2]) -> f64 {
    let n = poly.len();
    let mut a = 0.0;
    for i in 0..n {
        let p = poly[i];
        let q = poly[(i + 1) % n];
        a += p.perp_dot(q);
    }
    0.5 * a
}

/// Vector area `½ Σ pᵢ × pᵢ₊₁` of a closed 3D polygon: its direction is the normal of the best
/// fitting plane (oriented by the traversal, right-hand rule), its length the projected area.
pub fn polygon_vector_area(poly: &[DVec3]) -> DVec3 {
    let n = poly.len();
    if n == 0 {
        return DVec3::ZERO;
    }
    let o = poly[0];
    let mut a = DVec3::ZERO;
    for i in 1..n.saturating_sub(1) {
        a += (poly[i] - o).cross(poly[i + 1] - o);
    }
    0.5 * a
}

/// Formats a point for messages: `(x, y, z)` with 6 decimals, or in scientific notation with
/// 7 significant digits when the point's largest coordinate is below 1e-3 or from 1e7 (tiny
/// and huge networks keep readable positions).
pub fn fmt_point(p: DVec3) -> String {
    let m = p.abs().max_element();
    if m == 0.0 || (1e-3..1e7).contains(&m) || !m.is_finite() {
        format!("({:.6}, {:.6}, {:.6})", p.x, p.y, p.z)
    } else {
        format!("({:.6e}, {:.6e}, {:.6e})", p.x, p.y, p.z)
    }
}

#[cfg(test)]
#[path = "tests/geom.rs"]
mod tests;
