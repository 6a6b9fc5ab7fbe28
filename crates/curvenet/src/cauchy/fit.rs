//! Reverse engineering a mesh into Cauchy constraints ([A11] §6).
//!
//! The input mesh is its own initial domain (cotangent weights and areas of the mesh, [A11] §6:
//! "we re-use the existing mesh structure"). Feature vertices come from a dihedral-angle threshold
//! ([A11] §6, after [GSMCO09]; CAD-like meshes) and become Cauchy constraints; every other vertex
//! is free. The ghost vertices get the "naive guess" of [A11] §6, per side: the orientation is the
//! normal of the faces on the neighbour's side of `u` (so a sharp edge gets one orientation per
//! side, i.e. its sharpness), and the ghost is centred on the input (`g₁ = v + 2e`, `e` the edge
//! `u − v` in that tangent plane; `g₂ = 3g₁ − 3u + v`). Optionally the ghosts are then fitted by
//! linear least squares, point to point, in the complete setup ([A11] §6.2: every ghost
//! coordinate a variable), with the ghost basis of [`super::reduce`] and a small Tikhonov pull
//! towards the naive guess.
//!
//! Not implemented: ridge/valley feature curves for organic meshes, the point-to-plane metric,
//! the reduced setup and the greedy reduction of curves (see `docs/cauchy.md`).

use super::reduce::GhostBasis;
use super::system::{MicroWeight, Role, Stencil, System};
use crate::error::{Error, Result};
use crate::geom::DVec3;
use crate::mesh::Mesh;
use crate::operators::{cotan_operators, Metric};
use serde::{Deserialize, Serialize};
use std::collections::HashMap;
use std::time::Instant;

/// Options of [`fit`].
#[derive(Clone, Debug, PartialEq)]
pub struct FitOptions {
    /// Laplacian order (1–3).
    pub order: usize,
    /// Dihedral angle (degrees) above which an edge is a feature.
    pub angle: f64,
    /// Fit the ghosts by least squares (point to point, complete setup).
    pub optimize: bool,
}

impl Default for FitOptions {
    fn default() -> Self {
        FitOptions { order: 2, angle: 30.0, optimize: false }
    }
}

/// A fitted model: the domain mesh, its Cauchy vertices and ghost vertices. Re-surfaced by
/// [`resurface`]. Serialised as the JSON written by `curvenet fit`.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
pub struct CauchyModel {
    pub order: usize,
    /// Domain vertex positions (the input mesh; Cauchy vertices keep theirs).
    pub positions: Vec<[f64; 3]>,
    pub faces: Vec<[u32; 3]>,
    /// Cauchy constraint vertices.
    pub constraints: Vec<u32>,
    /// Ghost vertices: `[vertex, source, number]` and position.
    pub ghosts: Vec<([u32; 3], [f64; 3])>,
}

/// What [`fit`] measured.
#[derive(Clone, Debug, Default, Serialize)]
pub struct FitReport {
    pub vertices: usize,
    pub feature_vertices: usize,
    pub ghosts: usize,
    /// Largest and RMS distance between each re-surfaced vertex and its input position, and the
    /// same relative to the bounding-box diagonal.
    pub max_distance: f64,
    pub rms_distance: f64,
    pub diagonal: f64,
    pub seconds: f64,
}

fn face_normal(p: &[DVec3], f: [u32; 3]) -> DVec3 {
    (p[f[1] as usize] - p[f[0] as usize]).cross(p[f[2] as usize] - p[f[0] as usize])
}

/// Feature vertices: the ends of edges whose dihedral angle exceeds `angle` degrees, and of
/// boundary edges.
pub fn feature_vertices(positions: &[DVec3], faces: &[[u32; 3]], angle: f64) -> Vec<bool> {
    let mut edges: HashMap<(u32, u32), Vec<usize>> = HashMap::new();
    for (fi, f) in faces.iter().enumerate() {
        for k in 0..3 {
            let (a, b) = (f[k], f[(k + 1) % 3]);
            edges.entry((a.min(b), a.max(b))).or_default().push(fi);
        }
    }
    let cos = angle.to_radians().cos();
    let mut out = vec![false; positions.len()];
    for (&(a, b), fs) in &edges {
        let sharp = match fs.as_slice() {
            [f, g] => {
                let (n, m) = (
                    face_normal(positions, faces[*f]).normalize_or_zero(),
                    face_normal(positions, faces[*g]).normalize_or_zero(),
                );
                n.dot(m) < cos
            }
            _ => true,
        };
        if sharp {
            out[a as usize] = true;
            out[b as usize] = true;
        }
    }
    out
}

fn stencil_of(positions: &[DVec3], faces: &[[u32; 3]]) -> Result<Stencil> {
    let mut mesh = Mesh::default();
    mesh.positions = positions.to_vec();
    mesh.faces = faces.to_vec();
    let ops = cotan_operators(&mesh, Metric::Surface, positions);
    if let Some(i) = ops.mass.iter().position(|a| !(*a > 0.0)) {
        return Err(Error::Input(format!("vertex {i} has zero area: degenerate or unreferenced")));
    }
    Ok(Stencil::from_operators(&ops, positions.to_vec()))
}

/// Reverse engineers `positions`/`faces` (see the module docs). Returns the model, the
/// re-surfaced positions and the report.
pub fn fit(positions: &[DVec3], faces: &[[u32; 3]], o: &FitOptions) -> Result<(CauchyModel, Vec<DVec3>, FitReport)> {
    let start = Instant::now();
    if !(1..=3).contains(&o.order) {
        return Err(Error::Usage(format!("order {} is not 1, 2 or 3", o.order)));
    }
    let n = positions.len();
    let feature = feature_vertices(positions, faces, o.angle);
    let nfeat = feature.iter().filter(|&&f| f).count();
    if nfeat == 0 {
        return Err(Error::Input(format!(
            "no edge has a dihedral angle above {}°: lower the angle (the reverse engineering needs feature curves)",
            o.angle
        )));
    }
    let roles: Vec<Role> = feature.iter().map(|&f| if f { Role::Cauchy } else { Role::Free }).collect();
    let stencil = stencil_of(positions, faces)?;
    let system = System::build(&stencil, &roles, o.order, MicroWeight::Consistent)?;
    // Per-side orientation: the normal of the faces around edge (u, v).
    let mut side: HashMap<(u32, u32), DVec3> = HashMap::new();
    for f in faces {
        let nf = face_normal(positions, *f);
        for k in 0..3 {
            for j in 1..3 {
                let (u, v) = (f[k], f[(k + j) % 3]);
                if feature[u as usize] && !feature[v as usize] {
                    *side.entry((u, v)).or_insert(DVec3::ZERO) += nf;
                }
            }
        }
    }
    let naive: Vec<DVec3> = system
        .ghosts
        .iter()
        .map(|g| {
            let (u, v) = (positions[g.vertex as usize], positions[g.source as usize]);
            let e = u - v;
            let nrm = side.get(&(g.vertex, g.source)).copied().unwrap_or(DVec3::ZERO).normalize_or_zero();
            let t = e - e.dot(nrm) * nrm;
            let t = if t.length() > 1e-12 * e.length() { t.normalize() * e.length() } else { e };
            let g1 = v + 2.0 * t;
            if g.number == 1 {
                g1
            } else {
                3.0 * g1 - 3.0 * u + v
            }
        })
        .collect();
    let f = system.factor()?;
    let ghosts = if o.optimize && !system.ghosts.is_empty() {
        let basis = GhostBasis::new(&system, &f, positions)?;
        least_squares(&system, &basis, positions, &naive)?
    } else {
        naive
    };
    let mut b = system.rhs(positions, &ghosts);
    f.solve_in_place(&mut b);
    let out = system.scatter(&b, positions);
    super::system::check_finite(&out)?;
    let d: Vec<f64> = out.iter().zip(positions).map(|(a, b)| a.distance(*b)).collect();
    let diagonal = crate::geom::Aabb::of(positions.iter().copied()).diagonal();
    let report = FitReport {
        vertices: n,
        feature_vertices: nfeat,
        ghosts: system.ghosts.len(),
        max_distance: d.iter().copied().fold(0.0, f64::max),
        rms_distance: (d.iter().map(|x| x * x).sum::<f64>() / n as f64).sqrt(),
        diagonal,
        seconds: start.elapsed().as_secs_f64(),
    };
    let model = CauchyModel {
        order: o.order,
        positions: positions.iter().map(|p| p.to_array()).collect(),
        faces: faces.to_vec(),
        constraints: (0..n as u32).filter(|&i| feature[i as usize]).collect(),
        ghosts: system
            .ghosts
            .iter()
            .zip(&ghosts)
            .map(|(g, p)| ([g.vertex, g.source, g.number], p.to_array()))
            .collect(),
    };
    Ok((model, out, report))
}

/// Point-to-point least squares over all ghost coordinates ([A11] §6.2, complete setup):
/// `min ‖K + W G − X‖² + λ ‖G − G₀‖²` with `λ` 10⁻⁶ of the mean diagonal of `WᵀW`.
fn least_squares(system: &System, basis: &GhostBasis, positions: &[DVec3], g0: &[DVec3]) -> Result<Vec<DVec3>> {
    use faer::linalg::solvers::Solve;
    let nf = system.num_free();
    let ng = system.ghosts.len();
    let target = faer::Mat::<f64>::from_fn(nf, 3, |r, c| positions[system.free[r] as usize][c] - basis.k[(r, c)]);
    let mut normal = basis.w.transpose() * &basis.w;
    let mean_diag = (0..ng).map(|i| normal[(i, i)]).sum::<f64>() / ng as f64;
    let lambda = 1e-6 * mean_diag.max(f64::MIN_POSITIVE);
    for i in 0..ng {
        normal[(i, i)] += lambda;
    }
    let g0m = faer::Mat::<f64>::from_fn(ng, 3, |i, c| g0[i][c]);
    let rhs = basis.w.transpose() * &target + &g0m * faer::Scale(lambda);
    let llt = normal.llt(faer::Side::Lower).map_err(|e| {
        Error::Numerical(format!("ghost least squares: normal equations not positive definite ({e:?})"))
    })?;
    let sol = llt.solve(&rhs);
    Ok((0..ng).map(|i| DVec3::new(sol[(i, 0)], sol[(i, 1)], sol[(i, 2)])).collect())
}

/// Solves a fitted model again (`curvenet resurface`).
pub fn resurface(model: &CauchyModel) -> Result<Vec<DVec3>> {
    let positions: Vec<DVec3> = model.positions.iter().map(|p| DVec3::from_array(*p)).collect();
    let n = positions.len();
    for f in &model.faces {
        if f.iter().any(|&v| v as usize >= n) {
            return Err(Error::Input(format!("model face {f:?} names a vertex ≥ {n}")));
        }
    }
    let mut roles = vec![Role::Free; n];
    for &c in &model.constraints {
        *roles.get_mut(c as usize).ok_or_else(|| Error::Input(format!("model constraint {c} is not a vertex")))? =
            Role::Cauchy;
    }
    let stencil = stencil_of(&positions, &model.faces)?;
    let system = System::build(&stencil, &roles, model.order, MicroWeight::Consistent)?;
    let stored: HashMap<[u32; 3], DVec3> = model.ghosts.iter().map(|(k, p)| (*k, DVec3::from_array(*p))).collect();
    let ghosts: Vec<DVec3> = system
        .ghosts
        .iter()
        .map(|g| {
            stored.get(&[g.vertex, g.source, g.number]).copied().ok_or_else(|| {
                Error::Input(format!("the model has no ghost {} for vertex {} from {}", g.number, g.vertex, g.source))
            })
        })
        .collect::<Result<_>>()?;
    system.solve(&positions, &ghosts)
}
