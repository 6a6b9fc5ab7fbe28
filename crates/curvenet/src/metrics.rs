//! Measuring a surface against an analytic ground truth ([CG] §4.3, Table 1): distances of the
//! free vertices to the true surface and angles between the mesh normals and the true normals.

use crate::geom::DVec3;

/// An analytic surface with exact closest-point distances.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Truth {
    Sphere {
        center: DVec3,
        radius: f64,
    },
    /// Torus around the z axis through the origin.
    Torus {
        major: f64,
        minor: f64,
    },
    /// Infinite cylinder around the z axis.
    Cylinder {
        radius: f64,
    },
    /// `z = (x² − y²)/2`.
    Saddle,
}

impl Truth {
    /// Unsigned distance from `p` to the surface.
    pub fn distance(&self, p: DVec3) -> f64 {
        (p - self.closest_point(p)).length()
    }

    /// The closest point of the surface to `p`.
    pub fn closest_point(&self, p: DVec3) -> DVec3 {
        match *self {
            Truth::Sphere { center, radius } => center + (p - center).normalize_or(DVec3::X) * radius,
            Truth::Torus { major, minor } => {
                let q = DVec3::new(p.x, p.y, 0.0).normalize_or(DVec3::X) * major;
                q + (p - q).normalize_or(DVec3::Z) * minor
            }
            Truth::Cylinder { radius } => {
                let r = DVec3::new(p.x, p.y, 0.0).normalize_or(DVec3::X) * radius;
                DVec3::new(r.x, r.y, p.z)
            }
            Truth::Saddle => {
                // Newton's method on the squared distance to (x, y, f(x, y)).
                let (mut x, mut y) = (p.x, p.y);
                for _ in 0..30 {
                    let f = 0.5 * (x * x - y * y);
                    let (fx, fy) = (x, -y);
                    let dz = f - p.z;
                    let (gx, gy) = (x - p.x + dz * fx, y - p.y + dz * fy);
                    let (hxx, hyy, hxy) = (1.0 + fx * fx + dz, 1.0 + fy * fy - dz, fx * fy);
                    let det = hxx * hyy - hxy * hxy;
                    if det.abs() < 1e-300 {
                        break;
                    }
                    let (sx, sy) = ((hyy * gx - hxy * gy) / det, (hxx * gy - hxy * gx) / det);
                    x -= sx;
                    y -= sy;
                    if sx.abs() + sy.abs() < 1e-15 {
                        break;
                    }
                }
                DVec3::new(x, y, 0.5 * (x * x - y * y))
            }
        }
    }

    /// Unit outward normal of the surface at its closest point to `p`.
    pub fn normal(&self, p: DVec3) -> DVec3 {
        let q = self.closest_point(p);
        match *self {
            Truth::Sphere { center, .. } => (q - center).normalize_or(DVec3::Z),
            Truth::Torus { major, .. } => {
                (q - DVec3::new(q.x, q.y, 0.0).normalize_or(DVec3::X) * major).normalize_or(DVec3::Z)
            }
            Truth::Cylinder { .. } => DVec3::new(q.x, q.y, 0.0).normalize_or(DVec3::X),
            Truth::Saddle => DVec3::new(-q.x, q.y, 1.0).normalize(),
        }
    }
}

/// Summary of a set of distances.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct DistanceStats {
    pub count: usize,
    pub min: f64,
    pub max: f64,
    pub mean: f64,
    pub rms: f64,
}

impl DistanceStats {
    pub fn of(values: impl IntoIterator<Item = f64>) -> Self {
        let (mut n, mut min, mut max, mut sum, mut sq) = (0usize, f64::INFINITY, 0.0f64, 0.0, 0.0);
        for v in values {
            n += 1;
            min = min.min(v);
            max = max.max(v);
            sum += v;
            sq += v * v;
        }
        if n == 0 {
            return Self::default();
        }
        DistanceStats { count: n, min, max, mean: sum / n as f64, rms: (sq / n as f64).sqrt() }
    }
}

/// Distances of the vertices `first..` (the free vertices when `first` is the number of curve
/// vertices, as in [CG] Table 1) to `truth`.
pub fn distance_to_truth(positions: &[DVec3], first: usize, truth: &Truth) -> DistanceStats {
    DistanceStats::of(positions[first.min(positions.len())..].iter().map(|p| truth.distance(*p)))
}

/// Angles in degrees between `normals` and the true normals, over vertices `first..`.
pub fn normal_angles_to_truth(positions: &[DVec3], normals: &[DVec3], first: usize, truth: &Truth) -> DistanceStats {
    DistanceStats::of(
        (first.min(positions.len())..positions.len())
            .map(|i| normals[i].dot(truth.normal(positions[i])).clamp(-1.0, 1.0).acos().to_degrees()),
    )
}

/// Closest point to `p` on the triangle `abc` (Ericson, *Real-Time Collision Detection*,
/// §5.1.5).
pub fn closest_point_on_triangle(p: DVec3, a: DVec3, b: DVec3, c: DVec3) -> DVec3 {
    let (ab, ac, ap) = (b - a, c - a, p - a);
    let (d1, d2) = (ab.dot(ap), ac.dot(ap));
    if d1 <= 0.0 && d2 <= 0.0 {
        return a;
    }
    let bp = p - b;
    let (d3, d4) = (ab.dot(bp), ac.dot(bp));
    if d3 >= 0.0 && d4 <= d3 {
        return b;
    }
    let vc = d1 * d4 - d3 * d2;
    if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
        return a + ab * (d1 / (d1 - d3));
    }
    let cp = p - c;
    let (d5, d6) = (ab.dot(cp), ac.dot(cp));
    if d6 >= 0.0 && d5 <= d6 {
        return c;
    }
    let vb = d5 * d2 - d1 * d6;
    if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
        return a + ac * (d2 / (d2 - d6));
    }
    let va = d3 * d6 - d5 * d4;
    if va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0 {
        return b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
    }
    let denom = 1.0 / (va + vb + vc);
    a + ab * (vb * denom) + ac * (vc * denom)
}

/// Exact point-to-mesh distance queries, accelerated by a uniform grid of triangle boxes.
pub struct MeshDistance<'a> {
    positions: &'a [DVec3],
    faces: &'a [[u32; 3]],
    origin: DVec3,
    cell: f64,
    dims: [usize; 3],
    cells: Vec<Vec<u32>>,
}

impl<'a> MeshDistance<'a> {
    /// Builds the grid (about one triangle per cell on average).
    pub fn new(positions: &'a [DVec3], faces: &'a [[u32; 3]]) -> Self {
        let bb = crate::geom::Aabb::of(faces.iter().flatten().map(|&i| positions[i as usize]));
        let ext = (bb.max - bb.min).max(DVec3::splat(1e-300));
        let volume_cells = (faces.len().max(1) as f64).max(1.0);
        let cell = (ext.x * ext.y * ext.z / volume_cells).cbrt().max(ext.max_element() / 256.0).max(1e-300);
        let dims = [0, 1, 2].map(|k| ((ext[k] / cell).ceil() as usize).clamp(1, 512));
        let mut cells = vec![Vec::new(); dims[0] * dims[1] * dims[2]];
        let me = MeshDistance { positions, faces, origin: bb.min, cell, dims, cells: Vec::new() };
        for (fi, f) in faces.iter().enumerate() {
            let tb = crate::geom::Aabb::of(f.iter().map(|&i| positions[i as usize]));
            let (lo, hi) = (me.cell_of(tb.min), me.cell_of(tb.max));
            for x in lo[0]..=hi[0] {
                for y in lo[1]..=hi[1] {
                    for z in lo[2]..=hi[2] {
                        cells[(z * dims[1] + y) * dims[0] + x].push(fi as u32);
                    }
                }
            }
        }
        MeshDistance { cells, ..me }
    }

    fn cell_of(&self, p: DVec3) -> [usize; 3] {
        let q = (p - self.origin) / self.cell;
        [0, 1, 2].map(|k| (q[k].floor().max(0.0) as usize).min(self.dims[k] - 1))
    }

    /// Distance from `p` to the mesh and the closest point.
    pub fn closest(&self, p: DVec3) -> (f64, DVec3) {
        let c = self.cell_of(p);
        let mut best = (f64::INFINITY, p);
        let max_ring = *self.dims.iter().max().unwrap_or(&1);
        for ring in 0..=max_ring {
            // Every point in rings beyond `ring` is at least this far away.
            let outside = (p - self.origin) / self.cell;
            let inside_grid = (0..3).all(|k| outside[k] >= 0.0 && outside[k] <= self.dims[k] as f64);
            if inside_grid && ring > 0 && best.0 <= (ring as f64 - 1.0) * self.cell {
                break;
            }
            let lo = [0, 1, 2].map(|k| c[k].saturating_sub(ring));
            let hi = [0, 1, 2].map(|k| (c[k] + ring).min(self.dims[k] - 1));
            for x in lo[0]..=hi[0] {
                for y in lo[1]..=hi[1] {
                    for z in lo[2]..=hi[2] {
                        let on_shell = [x, y, z].iter().zip(c.iter()).any(|(&v, &cc)| v.abs_diff(cc) == ring);
                        if !on_shell {
                            continue;
                        }
                        for &fi in &self.cells[(z * self.dims[1] + y) * self.dims[0] + x] {
                            let f = self.faces[fi as usize];
                            let q = closest_point_on_triangle(
                                p,
                                self.positions[f[0] as usize],
                                self.positions[f[1] as usize],
                                self.positions[f[2] as usize],
                            );
                            let d = p.distance(q);
                            if d < best.0 {
                                best = (d, q);
                            }
                        }
                    }
                }
            }
        }
        best
    }
}

#[cfg(test)]
#[path = "tests/metrics.rs"]
mod tests;
