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
            Truth::Sphere { center, radius } => {
                center + (p - center).normalize_or(DVec3::X) * radius
            }
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
            Truth::Torus { major, .. } => (q - DVec3::new(q.x, q.y, 0.0).normalize_or(DVec3::X)
                * major)
                .normalize_or(DVec3::Z),
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
        DistanceStats {
            count: n,
            min,
            max,
            mean: sum / n as f64,
            rms: (sq / n as f64).sqrt(),
        }
    }
}

/// Distances of the vertices `first..` (the free vertices when `first` is the number of curve
/// vertices, as in [CG] Table 1) to `truth`.
pub fn distance_to_truth(positions: &[DVec3], first: usize, truth: &Truth) -> DistanceStats {
    DistanceStats::of(
        positions[first.min(positions.len())..]
            .iter()
            .map(|p| truth.distance(*p)),
    )
}

/// Angles in degrees between `normals` and the true normals, over vertices `first..`.
pub fn normal_angles_to_truth(
    positions: &[DVec3],
    normals: &[DVec3],
    first: usize,
    truth: &Truth,
) -> DistanceStats {
    DistanceStats::of((first.min(positions.len())..positions.len()).map(|i| {
        normals[i]
            .dot(truth.normal(positions[i]))
            .clamp(-1.0, 1.0)
            .acos()
            .to_degrees()
    }))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn closest_points_are_on_the_surfaces() {
        let p = DVec3::new(0.3, -1.7, 0.9);
        let s = Truth::Sphere {
            center: DVec3::new(0.1, 0.0, 0.0),
            radius: 2.0,
        };
        assert!(
            (s.distance(p) - ((p - DVec3::new(0.1, 0.0, 0.0)).length() - 2.0).abs()).abs() < 1e-15
        );
        let t = Truth::Torus {
            major: 4.0,
            minor: 2.0,
        };
        assert!((t.distance(DVec3::new(6.5, 0.0, 0.0)) - 0.5).abs() < 1e-15);
        assert!((t.distance(DVec3::new(0.0, 4.0, 1.0)) - 1.0).abs() < 1e-15);
        let sad = Truth::Saddle;
        let q = sad.closest_point(p);
        assert!((q.z - 0.5 * (q.x * q.x - q.y * q.y)).abs() < 1e-12);
        // The offset is along the normal.
        let d = p - q;
        assert!(d.normalize().cross(sad.normal(p)).length() < 1e-9);
    }
}
