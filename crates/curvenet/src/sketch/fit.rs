//! Reverse engineering a mesh into Cauchy constraints (\[A11\] §6).
//!
//! The input mesh is its own initial domain (cotangent weights and areas of the mesh, \[A11\] §6:
//! "we re-use the existing mesh structure"). Feature vertices come from a dihedral-angle threshold
//! (\[A11\] §6, after \[GSMCO09\]; CAD-like meshes) and become Cauchy constraints; every other vertex
//! is free. The ghost vertices get the "naive guess" of \[A11\] §6, per side: the orientation is the
//! normal of the faces on the neighbour's side of `u` (so a sharp edge gets one orientation per
//! side, i.e. its sharpness), and the ghost is centred on the input (`g₁ = v + 2e`, `e` the edge
//! `u − v` in that tangent plane; `g₂ = 3g₁ − 3u + v`). Optionally the ghosts are then fitted by
//! linear least squares, point to point, in the complete setup (\[A11\] §6.2: every ghost
//! coordinate a variable), with the ghost basis of [`crate::methods::andrews2011::reduce`] and a small Tikhonov pull
//! towards the naive guess.
//!
//! Not implemented: ridge/valley feature curves for organic meshes, the point-to-plane metric,
//! the reduced setup and the greedy reduction of curves (see `docs/cauchy.md`).

use crate::error::{Error, Result};
use crate::geom::mesh::Mesh;
use crate::geom::DVec3;
use crate::methods::andrews2011::reduce::GhostBasis;
use crate::methods::andrews2011::system::{MicroWeight, Role, Stencil, System};
use crate::operators::{cotan_operators, Metric};
use crate::solve::timing::Instant;
use serde::{Deserialize, Serialize};
use std::collections::HashMap;

/// Options of [`fit`].
#[derive(Clone, Debug, PartialEq)]
pub struct FitOptions {
    /// Laplacian order (1–3).
    pub order: usize,
    /// Dihedral angle (degrees) above which an edge is a feature.
    pub angle: f64,
    /// Fit the ghosts by least squares (point to point, complete setup).
    pub optimize: bool,
    /// For smooth meshes: when `Some(f)`, the feature vertices are instead the fraction `f` of
    /// vertices whose signed mean curvature lies farthest from the median — the crests (ridges)
    /// and troughs (valleys) of the surface, a cheap stand-in for \[OBS04\]'s ridge/valley lines.
    pub curvature_fraction: Option<f64>,
    /// Greedy reduction of the feature curves (\[A11\] §6.1): when `Some(t)`, start from the
    /// border curves and the largest feature curve and add, one at a time, the curve nearest to
    /// the worst vertex until the largest point-to-point error is below `t` times the mesh's
    /// largest extent divided by 5 (\[A11\]: 0.1 for a mesh scaled into a 5×5×5 box). A "curve"
    /// is a connected component of feature vertices.
    pub reduce: Option<f64>,
}

impl Default for FitOptions {
    fn default() -> Self {
        FitOptions { order: 2, angle: 30.0, optimize: false, curvature_fraction: None, reduce: None }
    }
}

/// A fitted model: the domain mesh, its Cauchy vertices and ghost vertices. Re-surfaced by
/// [`resurface`]. Serialised as the JSON written by `curvenet fit`.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
pub struct CauchyModel {
    /// Laplacian order `k` of the system (1–3).
    pub order: usize,
    /// Domain vertex positions (the input mesh; Cauchy vertices keep theirs).
    pub positions: Vec<[f64; 3]>,
    /// Domain triangles.
    pub faces: Vec<[u32; 3]>,
    /// Cauchy constraint vertices.
    pub constraints: Vec<u32>,
    /// Ghost vertices: `[vertex, source, number]` and position.
    pub ghosts: Vec<([u32; 3], [f64; 3])>,
}

/// What [`fit`] measured.
#[derive(Clone, Debug, Default, Serialize)]
pub struct FitReport {
    /// Vertices of the input mesh.
    pub vertices: usize,
    /// Vertices on feature curves (the Cauchy constraints).
    pub feature_vertices: usize,
    /// Ghost vertices of the model.
    pub ghosts: usize,
    /// Largest and RMS distance between each re-surfaced vertex and its input position, and the
    /// same relative to the bounding-box diagonal.
    pub max_distance: f64,
    /// RMS distance (see `max_distance`).
    pub rms_distance: f64,
    /// Bounding-box diagonal of the input mesh.
    pub diagonal: f64,
    /// Wall-clock time of the fit, seconds.
    pub seconds: f64,
    /// Feature curves (connected components) found, and kept by the greedy reduction.
    pub curves: usize,
    /// Feature curves kept by the greedy reduction (both 0 without `reduce`).
    pub curves_kept: usize,
}

fn face_normal(p: &[DVec3], f: [u32; 3]) -> DVec3 {
    (p[f[1] as usize] - p[f[0] as usize]).cross(p[f[2] as usize] - p[f[0] as usize])
}

/// Feature vertices: the ends of edges whose dihedral angle exceeds `angle` degrees, and of
/// boundary edges ([`crate::operators::sharp_edges`], the detection `curvenet sample` finds its
/// creases with).
pub fn feature_vertices(positions: &[DVec3], faces: &[[u32; 3]], angle: f64) -> Vec<bool> {
    let (sharp, boundary) = crate::operators::sharp_edges(positions, faces, angle.to_radians());
    let mut out = vec![false; positions.len()];
    for (a, b) in sharp.into_iter().chain(boundary) {
        out[a as usize] = true;
        out[b as usize] = true;
    }
    out
}

/// The fraction `f` of vertices whose signed mean curvature is farthest from the median, plus
/// the vertices of open borders.
pub fn curvature_features(positions: &[DVec3], faces: &[[u32; 3]], f: f64) -> Vec<bool> {
    let n = positions.len();
    let (_, h) = crate::operators::normals_and_mean_curvature(faces, positions, &vec![false; n]);
    let mut sorted: Vec<f64> = h.iter().copied().filter(|x| x.is_finite()).collect();
    sorted.sort_by(f64::total_cmp);
    let median = sorted.get(sorted.len() / 2).copied().unwrap_or(0.0);
    let mut dev: Vec<f64> = h.iter().map(|x| (x - median).abs()).collect();
    let mut order: Vec<usize> = (0..n).collect();
    order.sort_by(|&a, &b| dev[b].total_cmp(&dev[a]));
    let keep = ((f * n as f64).round() as usize).clamp(1, n);
    let mut out = vec![false; n];
    for &i in &order[..keep] {
        out[i] = true;
    }
    dev.clear();
    // Open borders stay constrained.
    let border = feature_vertices(positions, faces, 180.0);
    for i in 0..n {
        out[i] |= border[i];
    }
    out
}

fn stencil_of(positions: &[DVec3], faces: &[[u32; 3]]) -> Result<Stencil> {
    let mesh = Mesh { positions: positions.to_vec(), faces: faces.to_vec(), ..Mesh::default() };
    let ops = cotan_operators(&mesh, Metric::Surface, positions);
    if let Some(i) = ops.mass.iter().position(|a| a.is_nan() || *a <= 0.0) {
        return Err(Error::input(format!("vertex {i} has zero area: degenerate or unreferenced")));
    }
    Ok(Stencil::from_operators(&ops, positions.to_vec()))
}

/// Reverse engineers `positions`/`faces` (see the module docs). Returns the model, the
/// re-surfaced positions and the report.
pub fn fit(positions: &[DVec3], faces: &[[u32; 3]], o: &FitOptions) -> Result<(CauchyModel, Vec<DVec3>, FitReport)> {
    let start = Instant::now();
    if !(1..=3).contains(&o.order) {
        return Err(Error::usage(format!("order {} is not 1, 2 or 3", o.order)));
    }
    if !(o.angle.is_finite() && (0.0..=180.0).contains(&o.angle)) {
        return Err(Error::usage(format!("`angle` {} is not in [0, 180] degrees", o.angle)));
    }
    if let Some(t) = o.reduce.filter(|t| !(t.is_finite() && *t > 0.0)) {
        return Err(Error::usage(format!("`reduce` {t} is not a positive tolerance")));
    }
    let n = positions.len();
    let feature = match o.curvature_fraction {
        None => feature_vertices(positions, faces, o.angle),
        Some(f) => {
            if !(f > 0.0 && f < 1.0) {
                return Err(Error::usage(format!("curvature fraction {f} is not in (0, 1)")));
            }
            curvature_features(positions, faces, f)
        }
    };
    let mut feature = feature;
    let (curves, curves_kept) = match o.reduce {
        Some(t) => greedy_reduction(positions, faces, &mut feature, o.order, t)?,
        None => (0, 0),
    };
    let nfeat = feature.iter().filter(|&&f| f).count();
    if nfeat == 0 {
        return Err(Error::input(format!(
            "no edge has a dihedral angle above {}°: lower the angle (the reverse engineering needs feature curves)",
            o.angle
        )));
    }
    let roles: Vec<Role> = feature.iter().map(|&f| if f { Role::Cauchy } else { Role::Free }).collect();
    let stencil = stencil_of(positions, faces)?;
    let system = System::build(&stencil, &roles, o.order, MicroWeight::Consistent)?;
    let naive = naive_ghosts(&system, positions, faces, &feature);
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
    crate::methods::check_finite(&out, "Cauchy solve")?;
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
        curves,
        curves_kept,
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

/// The naive ghosts of the module docs for the Cauchy vertices `feature`.
fn naive_ghosts(system: &System, positions: &[DVec3], faces: &[[u32; 3]], feature: &[bool]) -> Vec<DVec3> {
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
    system
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
        .collect()
}

/// \[A11\] §6.1, greedy: keeps in `feature` only the curves the reduction selects. Returns the
/// numbers of curves found and kept.
fn greedy_reduction(
    positions: &[DVec3],
    faces: &[[u32; 3]],
    feature: &mut [bool],
    order: usize,
    threshold: f64,
) -> Result<(usize, usize)> {
    let n = positions.len();
    // Components of the feature vertices along mesh edges (union-find).
    let mut parent: Vec<u32> = (0..n as u32).collect();
    fn root(p: &mut [u32], mut i: u32) -> u32 {
        while p[i as usize] != i {
            p[i as usize] = p[p[i as usize] as usize];
            i = p[i as usize];
        }
        i
    }
    for f in faces {
        for k in 0..3 {
            let (a, b) = (f[k], f[(k + 1) % 3]);
            if feature[a as usize] && feature[b as usize] {
                let (ra, rb) = (root(&mut parent, a), root(&mut parent, b));
                parent[ra as usize] = rb;
            }
        }
    }
    let mut comp_of: HashMap<u32, usize> = HashMap::new();
    let mut comps: Vec<Vec<u32>> = Vec::new();
    for v in 0..n as u32 {
        if feature[v as usize] {
            let r = root(&mut parent, v);
            let c = *comp_of.entry(r).or_insert_with(|| {
                comps.push(Vec::new());
                comps.len() - 1
            });
            comps[c].push(v);
        }
    }
    if comps.is_empty() {
        return Ok((0, 0));
    }
    let border = feature_vertices(positions, faces, 180.0);
    let mut active: Vec<bool> = comps.iter().map(|c| c.iter().any(|&v| border[v as usize])).collect();
    let largest = (0..comps.len()).max_by_key(|&c| comps[c].len()).unwrap_or(0);
    active[largest] = true;
    let bb = crate::geom::Aabb::of(positions.iter().copied());
    let extent = (bb.max - bb.min).max_element();
    let tol = threshold * extent / 5.0;
    let stencil = stencil_of(positions, faces)?;
    loop {
        let current: Vec<bool> = {
            let mut f = vec![false; n];
            for (c, verts) in comps.iter().enumerate() {
                if active[c] {
                    for &v in verts {
                        f[v as usize] = true;
                    }
                }
            }
            f
        };
        let roles: Vec<Role> = current.iter().map(|&f| if f { Role::Cauchy } else { Role::Free }).collect();
        let system = System::build(&stencil, &roles, order, MicroWeight::Consistent)?;
        let ghosts = naive_ghosts(&system, positions, faces, &current);
        let out = system.solve(positions, &ghosts)?;
        let (worst, err) =
            (0..n).map(|i| (i, out[i].distance(positions[i]))).max_by(|a, b| a.1.total_cmp(&b.1)).unwrap_or((0, 0.0));
        let inactive: Vec<usize> = (0..comps.len()).filter(|&c| !active[c]).collect();
        if err < tol || inactive.is_empty() {
            feature.copy_from_slice(&current);
            return Ok((comps.len(), active.iter().filter(|&&a| a).count()));
        }
        // The inactive curve nearest to the worst vertex (`inactive` is not empty here).
        let p = positions[worst];
        let dist = |c: usize| comps[c].iter().map(|&v| positions[v as usize].distance(p)).fold(f64::INFINITY, f64::min);
        if let Some(next) = inactive.into_iter().min_by(|&a, &b| dist(a).total_cmp(&dist(b))) {
            active[next] = true;
        }
    }
}

/// Point-to-point least squares over all ghost coordinates (\[A11\] §6.2, complete setup):
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
        Error::numerical(format!("ghost least squares: normal equations not positive definite ({e:?})"))
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
            return Err(Error::input(format!("model face {f:?} names a vertex ≥ {n}")));
        }
    }
    if model.constraints.is_empty() {
        return Err(Error::input(
            "the model has no Cauchy constraints: nothing fixes its shape (it would re-surface to a point)",
        ));
    }
    if let Some(i) = positions.iter().position(|p| !p.is_finite()) {
        return Err(Error::input(format!("model vertex {i} has a non-finite coordinate")));
    }
    let mut roles = vec![Role::Free; n];
    for &c in &model.constraints {
        *roles.get_mut(c as usize).ok_or_else(|| Error::input(format!("model constraint {c} is not a vertex")))? =
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
                Error::input(format!("the model has no ghost {} for vertex {} from {}", g.number, g.vertex, g.source))
            })
        })
        .collect::<Result<_>>()?;
    system.solve(&positions, &ghosts)
}
