//! Measuring a surface against an analytic ground truth (\[CG\] §4.3, Table 1): distances of the
//! free vertices to the true surface and angles between the mesh normals and the true normals.

pub mod check;

use crate::geom::DVec3;

/// An analytic surface with exact closest-point distances.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Truth {
    /// Sphere of `radius` around `center`.
    Sphere {
        /// Centre.
        center: DVec3,
        /// Radius.
        radius: f64,
    },
    /// Torus around the z axis through the origin.
    Torus {
        /// Distance from the axis to the tube's centre line (`R`).
        major: f64,
        /// Radius of the tube (`r`).
        minor: f64,
    },
    /// Infinite cylinder around the z axis.
    Cylinder {
        /// Radius.
        radius: f64,
    },
    /// `z = (x² − y²)/2`.
    Saddle,
    /// Axis-aligned ellipsoid `x²/a² + y²/b² + z²/c² = 1`.
    Ellipsoid {
        /// Semi-axes `(a, b, c)`.
        axes: DVec3,
    },
    /// The lens: the boundary of the intersection of two balls of `radius` centred at
    /// `z = ±offset` (`offset < radius`): two spherical caps meeting at a crease circle in the
    /// plane z = 0 (the `lens` example: radius 1, offset ½, a 60° crease).
    Lens {
        /// The balls' radius.
        radius: f64,
        /// Distance of the balls' centres from the plane z = 0.
        offset: f64,
    },
    /// The closed cylinder around the z axis: side `radius`, lids at `z = ±half_height` (the
    /// `can` example: 1, 1).
    Can {
        /// Radius.
        radius: f64,
        /// Half the height.
        half_height: f64,
    },
    /// The plane `n · x = offset` (unit `n`).
    Plane {
        /// Unit normal `n`.
        normal: DVec3,
        /// Offset along `n`.
        offset: f64,
    },
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
            Truth::Ellipsoid { axes } => closest_on_ellipsoid(axes, p),
            Truth::Plane { normal, offset } => p - normal * (normal.dot(p) - offset),
            Truth::Lens { radius, offset } => {
                // A cap's radial projection where it lands on the cap, else the crease circle.
                let rim = (radius * radius - offset * offset).sqrt();
                let mut best = DVec3::new(p.x, p.y, 0.0).normalize_or(DVec3::X) * rim;
                for up in [1.0, -1.0] {
                    let c = DVec3::Z * (-up * offset);
                    let q = c + (p - c).normalize_or(DVec3::Z * up) * radius;
                    if q.z * up >= 0.0 && q.distance(p) < best.distance(p) {
                        best = q;
                    }
                }
                best
            }
            Truth::Can { radius, half_height } => {
                let r = DVec3::new(p.x, p.y, 0.0);
                let side = r.normalize_or(DVec3::X) * radius + DVec3::Z * p.z.clamp(-half_height, half_height);
                let lid = (if r.length() > radius { r.normalize() * radius } else { r })
                    + DVec3::Z * (half_height * if p.z >= 0.0 { 1.0 } else { -1.0 });
                if side.distance(p) <= lid.distance(p) {
                    side
                } else {
                    lid
                }
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
            Truth::Ellipsoid { axes } => (q / (axes * axes)).normalize_or(DVec3::Z),
            Truth::Plane { normal, .. } => normal,
            Truth::Lens { radius, offset } => {
                // On the crease circle: the mean of the caps' normals (radial).
                let up = q.z.signum();
                if q.z.abs() < 1e-12 * radius {
                    DVec3::new(q.x, q.y, 0.0).normalize_or(DVec3::X)
                } else {
                    (q + DVec3::Z * (up * offset)).normalize_or(DVec3::Z * up)
                }
            }
            Truth::Can { radius, half_height } => {
                let r = DVec3::new(q.x, q.y, 0.0);
                let on_lid = (q.z.abs() - half_height).abs() < 1e-12 * half_height;
                let on_side = (r.length() - radius).abs() < 1e-12 * radius;
                match (on_lid, on_side) {
                    (true, false) => DVec3::Z * q.z.signum(),
                    (false, _) => r.normalize_or(DVec3::X),
                    (true, true) => (r.normalize_or(DVec3::X) + DVec3::Z * q.z.signum()).normalize(),
                }
            }
        }
    }

    /// Signed mean curvature at the closest point to `p` (`+1/r` on a sphere with outward
    /// normals, the library's convention `L V = −2 H N`): `None` where the surface has none (a
    /// crease or rim of `lens` and `can`). Ellipsoid: `H = (a² + b² + c² − |q|²) /
    /// (2 a² b² c² (x²/a⁴ + y²/b⁴ + z²/c⁴)^{3/2})`; saddle `z = (x² − y²)/2` with upward
    /// normals: `H = (x² − y²) / (2 (1 + x² + y²)^{3/2})`; torus: `½ (1/r + cos θ / ρ)`, `ρ`
    /// the distance from the axis.
    pub fn mean_curvature(&self, p: DVec3) -> Option<f64> {
        let q = self.closest_point(p);
        Some(match *self {
            Truth::Sphere { radius, .. } => 1.0 / radius,
            Truth::Torus { major, minor } => {
                let rho = (q.x * q.x + q.y * q.y).sqrt();
                0.5 * (1.0 / minor + (rho - major) / minor / rho)
            }
            Truth::Cylinder { radius } => 0.5 / radius,
            Truth::Saddle => {
                let w2 = 1.0 + q.x * q.x + q.y * q.y;
                (q.x * q.x - q.y * q.y) / (2.0 * w2 * w2.sqrt())
            }
            Truth::Ellipsoid { axes } => {
                let a2 = axes * axes;
                let g = (q * q / (a2 * a2)).element_sum();
                (a2.element_sum() - q.length_squared()) / (2.0 * a2.x * a2.y * a2.z * g * g.sqrt())
            }
            Truth::Plane { .. } => 0.0,
            Truth::Lens { radius, .. } => {
                if q.z.abs() < 1e-9 * radius {
                    return None;
                }
                1.0 / radius
            }
            Truth::Can { radius, half_height } => {
                let r = (q.x * q.x + q.y * q.y).sqrt();
                let on_lid = (q.z.abs() - half_height).abs() < 1e-9 * half_height;
                let on_side = (r - radius).abs() < 1e-9 * radius;
                match (on_lid, on_side) {
                    (true, true) => return None,
                    (true, false) => 0.0,
                    (false, _) => 0.5 / radius,
                }
            }
        })
    }

    /// Parses a truth specification: `sphere` (unit), `sphere:r`, `sphere:cx,cy,cz,r`,
    /// `torus:R,r` (axis z), `cylinder:r` (axis z), `ellipsoid:a,b,c`, `plane` (z = 0),
    /// `plane:nx,ny,nz,d` (n·x = d), `saddle` (z = (x² − y²)/2), `lens` / `lens:r,h` (two
    /// caps of radius r centred at z = ±h), `can` / `can:r,h` (closed cylinder, z ∈ [−h, h]). `None` when `spec` is not of
    /// this form (it may then name a reference mesh file).
    pub fn parse(spec: &str) -> Option<std::result::Result<Truth, String>> {
        let (name, args) = match spec.split_once(':') {
            Some((n, a)) => (n, Some(a)),
            None => (spec, None),
        };
        let known = ["sphere", "torus", "cylinder", "ellipsoid", "plane", "saddle", "lens", "can"];
        if !known.contains(&name) {
            return None;
        }
        let nums: std::result::Result<Vec<f64>, String> = match args {
            None => Ok(Vec::new()),
            Some(a) => a
                .split(',')
                .map(|x| {
                    x.trim()
                        .parse::<f64>()
                        .ok()
                        .filter(|v| v.is_finite())
                        .ok_or_else(|| format!("\"{x}\" is not a number"))
                })
                .collect(),
        };
        let nums = match nums {
            Ok(v) => v,
            Err(e) => return Some(Err(format!("truth \"{spec}\": {e}"))),
        };
        let bad = |want: &str| Some(Err(format!("truth \"{spec}\": expected {name}{want}")));
        let positive = |v: &[f64]| v.iter().all(|&x| x > 0.0);
        Some(Ok(match (name, nums.as_slice()) {
            ("sphere", []) => Truth::Sphere { center: DVec3::ZERO, radius: 1.0 },
            ("sphere", [r]) if *r > 0.0 => Truth::Sphere { center: DVec3::ZERO, radius: *r },
            ("sphere", [x, y, z, r]) if *r > 0.0 => Truth::Sphere { center: DVec3::new(*x, *y, *z), radius: *r },
            ("sphere", _) => return bad(":cx,cy,cz,r (or :r) with r > 0"),
            ("torus", [big, small]) if positive(&[*big, *small]) => Truth::Torus { major: *big, minor: *small },
            ("torus", _) => return bad(":R,r with R, r > 0"),
            ("cylinder", [r]) if *r > 0.0 => Truth::Cylinder { radius: *r },
            ("cylinder", _) => return bad(":r with r > 0"),
            ("ellipsoid", [a, b, c]) if positive(&[*a, *b, *c]) => Truth::Ellipsoid { axes: DVec3::new(*a, *b, *c) },
            ("ellipsoid", _) => return bad(":a,b,c with a, b, c > 0"),
            ("plane", []) => Truth::Plane { normal: DVec3::Z, offset: 0.0 },
            ("plane", [x, y, z, d]) if DVec3::new(*x, *y, *z).length() > 0.0 => {
                let n = DVec3::new(*x, *y, *z);
                Truth::Plane { normal: n.normalize(), offset: d / n.length() }
            }
            ("plane", _) => return bad(" or plane:nx,ny,nz,d with a non-zero normal"),
            ("saddle", []) => Truth::Saddle,
            ("lens", []) => Truth::Lens { radius: 1.0, offset: 0.5 },
            ("lens", [r, h]) if *r > *h && *h >= 0.0 => Truth::Lens { radius: *r, offset: *h },
            ("lens", _) => return bad(":r,h with r > h ≥ 0"),
            ("can", []) => Truth::Can { radius: 1.0, half_height: 1.0 },
            ("can", [r, h]) if positive(&[*r, *h]) => Truth::Can { radius: *r, half_height: *h },
            ("can", _) => return bad(":r,h with r, h > 0"),
            _ => return bad(" without parameters"),
        }))
    }
}

/// Closest point on the ellipsoid with semi-axes `e` to `p`: the root `t` of
/// `Σ (eᵢ yᵢ / (eᵢ² + t))² = 1` by bisection, `xᵢ = eᵢ² yᵢ / (eᵢ² + t)` (the Lagrange condition).
/// Exact for points outside or near the surface; a point deep inside on a symmetry plane of
/// the smallest axis falls back to radial projection.
fn closest_on_ellipsoid(e: DVec3, p: DVec3) -> DVec3 {
    let e2 = e * e;
    let f = |t: f64| (0..3).map(|i| (e[i] * p[i] / (e2[i] + t)).powi(2)).sum::<f64>() - 1.0;
    let lo_bound = (0..3).filter(|&i| p[i] != 0.0).map(|i| -e2[i]).fold(f64::NEG_INFINITY, f64::max);
    if lo_bound == f64::NEG_INFINITY {
        // The centre: the closest points are the ends of the smallest axis.
        let k = if e.x <= e.y && e.x <= e.z {
            0
        } else if e.y <= e.z {
            1
        } else {
            2
        };
        let mut q = DVec3::ZERO;
        q[k] = e[k];
        return q;
    }
    let radial = |p: DVec3| p / ((p / e).length());
    let mut lo = lo_bound + 1e-300f64.max(1e-15 * e2.max_element());
    if f(lo) < 0.0 {
        return radial(p);
    }
    let mut hi = e.max_element() * p.length() + 1.0;
    while f(hi) > 0.0 {
        hi *= 2.0;
    }
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if f(mid) > 0.0 {
            lo = mid;
        } else {
            hi = mid;
        }
        if hi - lo <= 1e-15 * hi.abs().max(1e-300) {
            break;
        }
    }
    let t = 0.5 * (lo + hi);
    DVec3::new(e2.x * p.x / (e2.x + t), e2.y * p.y / (e2.y + t), e2.z * p.z / (e2.z + t))
}

/// The median of `values` (the upper one of an even count; NaN for none): benchmarks report
/// medians of repeated runs.
pub fn median(mut values: Vec<f64>) -> f64 {
    if values.is_empty() {
        return f64::NAN;
    }
    values.sort_by(f64::total_cmp);
    values[values.len() / 2]
}

/// Summary of a set of distances.
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize)]
pub struct DistanceStats {
    /// Number of values.
    pub count: usize,
    /// Smallest value.
    pub min: f64,
    /// Largest value.
    pub max: f64,
    /// Mean.
    pub mean: f64,
    /// Root mean square.
    pub rms: f64,
}

impl DistanceStats {
    /// The summary of `values` (all zero for none).
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
/// vertices, as in \[CG\] Table 1) to `truth`.
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

pub use crate::geom::distance::{closest_point_on_segment, closest_point_on_triangle, MeshDistance};

/// A ground truth: an analytic surface or a reference mesh.
#[derive(Clone, Copy, Debug)]
pub enum Reference<'a> {
    /// An analytic surface.
    Analytic(Truth),
    /// A triangle mesh.
    Mesh {
        /// Vertex positions.
        positions: &'a [DVec3],
        /// Triangles.
        faces: &'a [[u32; 3]],
    },
}

/// What [`evaluate`] measured (\[CG\] §4.3, Fig. 5). Angles in degrees.
#[derive(Clone, Debug, Default, serde::Serialize)]
pub struct Evaluation {
    /// Vertices evaluated (the free ones) and excluded (on the curves).
    pub vertices: usize,
    /// Vertices left out (on the curves).
    pub excluded: usize,
    /// Distances of the evaluated vertices to the truth.
    pub distance: DistanceStats,
    /// Distances of the reference mesh's vertices to the mesh (reference meshes only).
    pub reverse: Option<DistanceStats>,
    /// Symmetric Hausdorff distance, vertex-sampled (reference meshes only).
    pub hausdorff: Option<f64>,
    /// Angle between the mesh's vertex normals and the truth's normals.
    pub normal_angle: DistanceStats,
    /// Angle between the propagated normals `N*` and the mesh's normals, when known.
    pub propagated_deviation: Option<DistanceStats>,
    /// The discrete mean curvature against the truth's (analytic truths only).
    pub mean_curvature: Option<CurvatureError>,
}

/// How far a mesh's discrete mean curvature (cotangent, [`crate::operators::cotan_mean_curvature`])
/// is from the truth's, over the evaluated vertices off open borders where the truth has one:
/// what curvature maps and isophotes show and distances hide.
#[derive(Clone, Debug, Default, serde::Serialize)]
pub struct CurvatureError {
    /// The scale errors are relative to: the largest `|H|` of the truth over those vertices
    /// (the curvature itself on a sphere or cylinder).
    pub scale: f64,
    /// `|H_mesh − H_true|`, absolute.
    pub absolute: DistanceStats,
    /// `|H_mesh − H_true| / scale`: median, 99th percentile and maximum.
    pub relative_median: f64,
    /// 99th percentile of the relative error.
    pub relative_p99: f64,
    /// Largest relative error.
    pub relative_max: f64,
}

/// [`CurvatureError`] of the mesh over the vertices `free` against `truth`; `None` when no
/// vertex qualifies or the truth is flat (no scale).
pub fn curvature_error(
    positions: &[DVec3],
    faces: &[[u32; 3]],
    free: &[usize],
    truth: &Truth,
) -> Option<CurvatureError> {
    let border = crate::operators::border_vertices(faces, positions.len());
    let h = crate::operators::cotan_mean_curvature(faces, positions, &border);
    let pairs: Vec<(f64, f64)> = free
        .iter()
        .filter(|&&i| !border[i])
        .filter_map(|&i| truth.mean_curvature(positions[i]).map(|t| (h[i], t)))
        .collect();
    let scale = pairs.iter().map(|p| p.1.abs()).fold(0.0, f64::max);
    if pairs.is_empty() || !(scale > 0.0) {
        return None;
    }
    let mut rel: Vec<f64> = pairs.iter().map(|(m, t)| (m - t).abs() / scale).collect();
    rel.sort_by(f64::total_cmp);
    let at = |q: f64| rel[((q * (rel.len() - 1) as f64).round() as usize).min(rel.len() - 1)];
    Some(CurvatureError {
        scale,
        absolute: DistanceStats::of(pairs.iter().map(|(m, t)| (m - t).abs())),
        relative_median: at(0.5),
        relative_p99: at(0.99),
        relative_max: at(1.0),
    })
}

/// Measures a mesh against a ground truth over its vertices not flagged in `exclude` (the
/// curve vertices, as in \[CG\] Table 1). `normals`: the mesh's vertex normals (computed from
/// the faces when `None`); `propagated`: the propagated normals `N*`, if known.
pub fn evaluate(
    positions: &[DVec3],
    faces: &[[u32; 3]],
    normals: Option<&[DVec3]>,
    exclude: &[bool],
    reference: Reference<'_>,
    propagated: Option<&[DVec3]>,
) -> Evaluation {
    let computed;
    let normals = match normals {
        Some(n) => n,
        None => {
            computed = crate::operators::vertex_normals(faces, positions);
            &computed
        }
    };
    let free: Vec<usize> = (0..positions.len()).filter(|&i| !exclude.get(i).copied().unwrap_or(false)).collect();
    let angle = |a: DVec3, b: DVec3| a.dot(b).clamp(-1.0, 1.0).acos().to_degrees();
    let mut e = Evaluation { vertices: free.len(), excluded: positions.len() - free.len(), ..Default::default() };
    match reference {
        Reference::Analytic(truth) => {
            e.distance = DistanceStats::of(free.iter().map(|&i| truth.distance(positions[i])));
            e.normal_angle = DistanceStats::of(free.iter().map(|&i| angle(normals[i], truth.normal(positions[i]))));
            e.mean_curvature = curvature_error(positions, faces, &free, &truth);
        }
        Reference::Mesh { positions: rp, faces: rf } => {
            let to_ref = MeshDistance::new(rp, rf);
            let face_normal = |f: usize| {
                let [a, b, c] = rf[f].map(|i| rp[i as usize]);
                (b - a).cross(c - a).normalize_or_zero()
            };
            let hits: Vec<(f64, DVec3, usize)> = free.iter().map(|&i| to_ref.closest_face(positions[i])).collect();
            e.distance = DistanceStats::of(hits.iter().map(|h| h.0));
            e.normal_angle = DistanceStats::of(
                free.iter()
                    .zip(&hits)
                    .filter(|(_, h)| h.2 != usize::MAX)
                    .map(|(&i, h)| angle(normals[i], face_normal(h.2))),
            );
            let to_mesh = MeshDistance::new(positions, faces);
            let reverse = DistanceStats::of(rp.iter().map(|p| to_mesh.closest(*p).0));
            e.hausdorff = Some(reverse.max.max(e.distance.max));
            e.reverse = Some(reverse);
        }
    }
    e.propagated_deviation =
        propagated.map(|pn| DistanceStats::of(free.iter().map(|&i| angle(pn[i].normalize_or_zero(), normals[i]))));
    e
}

/// Flags the vertices lying within `tolerance` of the network's curves (its polylines).
pub fn near_curves(positions: &[DVec3], network: &crate::network::Network, tolerance: f64) -> Vec<bool> {
    let mut pts = Vec::new();
    let mut segs = Vec::new();
    for c in &network.curves {
        let base = pts.len() as u32;
        pts.extend_from_slice(&c.points);
        let n = c.points.len() as u32;
        let m = if c.closed { n } else { n.saturating_sub(1) };
        for k in 0..m {
            let (a, b) = (base + k, base + (k + 1) % n);
            segs.push([a, b, b]);
        }
    }
    let bvh = MeshDistance::new(&pts, &segs);
    positions.iter().map(|p| bvh.closest(*p).0 <= tolerance).collect()
}

/// The analytic surface the example `name` samples, where there is one.
pub fn example_truth(name: &str) -> Option<Truth> {
    Some(match name {
        "sphere" | "globe" | "cube" => Truth::Sphere { center: DVec3::ZERO, radius: 1.0 },
        "torus" => Truth::Torus { major: 4.0, minor: 2.0 },
        "cylinder" => Truth::Cylinder { radius: 1.0 },
        "saddle" => Truth::Saddle,
        "lens" => Truth::Lens { radius: 1.0, offset: 0.5 },
        "can" => Truth::Can { radius: 1.0, half_height: 1.0 },
        _ => return None,
    })
}

#[cfg(test)]
#[path = "tests/metrics.rs"]
mod tests;
