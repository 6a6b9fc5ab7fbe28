//! Normal-controlled surfacing (\[CG\] §3.4): propagate positions and normals from the curves,
//! estimate the signed mean curvature from both (eq. 1), and find the surface whose Laplacian
//! best matches the mean-curvature vectors (eq. 2–3), with hard or soft (\[CG\] §4.5) curve
//! constraints.
//!
//! 1. Propagation: `L² V* = 0`, `L² N* = 0` on the free vertices, curve vertices fixed; in
//!    symmetric form `(Ls M⁻¹ Ls)_ff X_f = −(Ls M⁻¹ Ls)_fc X_c`, one factorisation for the six
//!    columns; `N*` normalised.
//! 2. Guide: `H(v) = h(v) · n*(v)` with `h` from eq. 1 on `(V*, N*)` (signed, docs/design.md §1),
//!    divided by the barycentric area of the Laplacian's metric ([`GuideArea::Barycentric`],
//!    default: the area the sum covers), by the Laplacian's own Voronoi area `M`
//!    ([`GuideArea::Mass`]) or by the area of `v*` on `V*` as the paper states it
//!    ([`GuideArea::Surface`]).
//! 3. Fit: `min Σ_v w_v ‖(Ls V)_v − b_v‖²`, `b_v = −2 A_v H_v n*_v` (that is `L V = −2 H N*`),
//!    with `w_v = 1/A_v` (area-weighted, docs/design.md §1) or `1/A_v²` (\[CG\] eq. 2 as written). Rows
//!    of open-boundary vertices are left out (their one-sided Laplacian is not a curvature).
//!    With the area weighting and no open boundary the matrix is the propagation's, and its
//!    factorisation is reused.
//! 4. Guide updates (`guide_updates` times, an extension of the paper): eq. 1 is evaluated
//!    again on the fitted surface `V` (same normals `N*`) and the fit repeated with the same
//!    factorisation. `V*` is a biharmonic interpolant whose tangential distribution differs
//!    from the fit's (at open borders markedly: the cylinder of \[CG\] Fig. 1 bulges to radius
//!    1.09 with `V*`, and is exact to 2e-5 after one update); the fitted surface's is the
//!    one the fit's Laplacian sees.
//! 5. Soft constraints (\[CG\] §4.5): `+ ω_s Σ_{s ∈ curve} ‖v_s − v*_s‖²`, all vertices unknown.

use super::{
    check_finite, factor_like, factor_on, known_rows, scatter, Energy, GuideArea, MethodResult, SurfacingMethod,
};
use crate::error::{Error, Result};
use crate::geom::mesh::Mesh;
use crate::geom::{fmt_point, DVec3};
use crate::operators::{blended_mean_curvature, mixed_areas, Operators};
use crate::solve::sparse::product_lower_keeping_pattern;
use crate::solve::timing::{seconds_since, timed, Instant};
use crate::solve::{Eliminated, LeastSquares, SolveTimings};
use faer::Mat;

/// The user's settings of normal-control (options `energy`, `guide_area`, `guide_updates`;
/// docs/design.md §6).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NormalControlOptions {
    /// `energy`: weighting of the energy's terms. Default [`Energy::Area`].
    pub energy: Energy,
    /// `guide_area`: the area dividing eq. 1. Default [`GuideArea::Barycentric`].
    pub guide_area: GuideArea,
    /// `guide_updates`: how many times the guide is re-estimated on the fitted surface and the
    /// fit repeated with the same factorisation (0: the paper). Default
    /// [`NormalControlOptions::DEFAULT_GUIDE_UPDATES`].
    pub guide_updates: usize,
}

impl NormalControlOptions {
    /// Default `guide_updates`: one update removes the tangential bias of `V*` (module docs, 4).
    pub const DEFAULT_GUIDE_UPDATES: usize = 1;
}

impl Default for NormalControlOptions {
    fn default() -> Self {
        NormalControlOptions {
            energy: Energy::Area,
            guide_area: GuideArea::Barycentric,
            guide_updates: Self::DEFAULT_GUIDE_UPDATES,
        }
    }
}

/// Parameters of one normal-control solve: the user's settings and the soft-constraint weight
/// derived from `soft` (see [`crate::Options::soft`]).
#[derive(Clone, Copy, Debug, Default)]
pub struct NormalControlParams {
    /// The user's settings.
    pub options: NormalControlOptions,
    /// Soft-constraint weight `ω_s` per curve vertex, already scaled (see
    /// [`crate::Options::soft`]); `None` for hard constraints.
    pub soft_weight: Option<f64>,
}

/// The propagated positions and normals (\[CG\] §3.4, "Initial vertices and propagated
/// normals") and the factorisation that computed them.
pub(crate) struct Propagation {
    /// `V*`: the biharmonic interpolant of the curve vertices, `#V`.
    pub v_star: Vec<DVec3>,
    /// `N*`: the biharmonic interpolant of the curve normals, normalised, `#V`.
    pub n_star: Vec<DVec3>,
    /// The factorisation of `(Ls M⁻¹ Ls)_ff` (none without free vertices).
    pub system: Option<Eliminated>,
}

/// The normal-control method as a [`SurfacingMethod`]: keeps the factorisations of its
/// systems between solves. The matrices depend on neither the curve positions nor the normals,
/// so a solve with new curve values costs only right-hand sides and triangular solves
/// ([`crate::Surfacer`]).
#[derive(Default)]
pub struct NormalControl {
    /// The parameters of every solve.
    params: NormalControlParams,
    /// `(Ls M⁻¹ Ls)_ff` of the propagation.
    propagation: Option<Eliminated>,
    /// The fit's matrix when it differs from the propagation's (open borders, uniform
    /// weighting, soft constraints).
    fit: Option<Eliminated>,
}

impl NormalControl {
    /// The method with `params`, nothing factorised yet.
    pub fn new(params: NormalControlParams) -> Self {
        NormalControl { params, propagation: None, fit: None }
    }

    /// Takes the factorisation of the propagation system `(Ls M⁻¹ Ls)_ff` of the last solve
    /// (`None` before one), e.g. for [`super::iterated::Iterated::reusing`]: the iterations'
    /// matrix has its pattern.
    pub(crate) fn take_propagation(&mut self) -> Option<Eliminated> {
        self.propagation.take()
    }
}

impl SurfacingMethod for NormalControl {
    fn name(&self) -> &'static str {
        super::Method::NormalControl.name()
    }

    fn solve(&mut self, mesh: &Mesh, ops: &Operators, t: &mut SolveTimings) -> Result<MethodResult> {
        // Factorisations of another mesh (another number of unknowns) are not reused.
        let free = mesh.num_vertices() - mesh.num_curve;
        if self.propagation.as_ref().is_some_and(|s| s.dim() != free) {
            self.propagation = None;
        }
        let fit_dim = if self.params.soft_weight.is_some() { mesh.num_vertices() } else { free };
        if self.fit.as_ref().is_some_and(|s| s.dim() != fit_dim) {
            self.fit = None;
        }
        let params = self.params;
        normal_control_cached(mesh, ops, &params, t, self)
    }

    fn is_factored(&self) -> bool {
        self.propagation.is_some() || self.fit.is_some()
    }

    fn release(&mut self) {
        self.propagation = None;
        self.fit = None;
    }
}

/// `L² V* = 0`, `L² N* = 0` on the free vertices with the curve vertices fixed, in symmetric
/// form `(Ls M⁻¹ Ls)_ff X_f = −(Ls M⁻¹ Ls)_fc X_c`: one factorisation (or `cached`, that of an
/// earlier call on the same mesh and operators), six columns.
pub(crate) fn propagate(
    mesh: &Mesh,
    ops: &Operators,
    t: &mut SolveTimings,
    cached: Option<Eliminated>,
) -> Result<Propagation> {
    let (n, nc) = (mesh.num_vertices(), mesh.num_curve);
    let mut v_star = mesh.positions.clone();
    let mut n_star: Vec<DVec3> = mesh.curve_normals.clone();
    n_star.resize(n, DVec3::ZERO);
    if n == nc {
        return Ok(Propagation { v_star, n_star, system: None });
    }
    let inv_m: Vec<f64> = ops.mass.iter().map(|a| 1.0 / a).collect();
    let energy = LeastSquares { a: &ops.ls, w: &inv_m, first: nc };
    let right_hand_sides = || {
        let known = known_rows(n, nc, &[&mesh.positions, &mesh.curve_normals]);
        energy.rhs(seam_propagation_targets(mesh).as_ref(), &known)
    };
    let (system, rhs) = match cached {
        Some(c) => (c, timed(&mut t.operators, right_hand_sides)),
        None => {
            let q = timed(&mut t.operators, || energy.matrix());
            // Below `PARALLEL_FROM` unknowns the numeric factorisation runs on one thread: the
            // right-hand sides are computed on the other core meanwhile. Above, the
            // factorisation uses every core and they follow it (less memory at its peak).
            // Stage times: the factorisation's own; the rest of the window to the operators.
            let factor = || {
                let clock = Instant::now();
                let system = factor_on(mesh, &q, nc, "propagation system (L² V* = 0)");
                (system, seconds_since(clock))
            };
            let window = Instant::now();
            let ((system, factor_time), rhs) = if q.ncols < crate::solve::PARALLEL_FROM {
                rayon::join(factor, right_hand_sides)
            } else {
                let c = factor();
                (c, right_hand_sides())
            };
            t.factor += factor_time;
            t.operators += (seconds_since(window) - factor_time).max(0.0);
            (system?, rhs)
        }
    };
    timed(&mut t.solve, || {
        let sol = system.solve(rhs);
        scatter(&sol, 0, nc, &mut v_star);
        scatter(&sol, 3, nc, &mut n_star);
    });
    for i in nc..n {
        let u = n_star[i].normalize_or_zero();
        if u == DVec3::ZERO || !u.is_finite() {
            return Err(Error::numerical(format!(
                "the propagated normal vanishes at vertex {i} near {}: the input normals around it cancel out \
                 (check that they all point outward)",
                fmt_point(v_star[i])
            ))
            .vertex(i)
            .point(v_star[i]));
        }
        n_star[i] = u;
    }
    check_finite(&v_star, "propagation")?;
    Ok(Propagation { v_star, n_star, system: Some(system) })
}

/// Runs the method once on `mesh` with the operators `ops` (planar or surface metric),
/// without keeping its factorisations.
pub fn normal_control(
    mesh: &Mesh,
    ops: &Operators,
    params: &NormalControlParams,
    t: &mut SolveTimings,
) -> Result<MethodResult> {
    NormalControl::new(*params).solve(mesh, ops, t)
}

/// The fit's row weights `w_v` (\[CG\] eq. 2; module docs, 3): `1/A_v` (area-weighted) or
/// `1/A_v²` (as written), 0 on open-boundary rows (`left_out`, [`Mesh::fit_row_left_out`]).
pub(crate) fn fit_weights(left_out: &[bool], inv_m: &[f64], energy: Energy) -> Vec<f64> {
    (0..inv_m.len())
        .map(|k| match (left_out[k], energy) {
            (true, _) => 0.0,
            (false, Energy::Area) => inv_m[k],
            (false, Energy::Uniform) => inv_m[k] * inv_m[k],
        })
        .collect()
}

/// [`normal_control`] with the factorisations of `kept` (from an earlier call with the
/// same mesh, `ops` and `params`; the curve positions and normals may differ), computing and
/// storing those it lacks.
fn normal_control_cached(
    mesh: &Mesh,
    ops: &Operators,
    params: &NormalControlParams,
    t: &mut SolveTimings,
    kept: &mut NormalControl,
) -> Result<MethodResult> {
    let (n, nc) = (mesh.num_vertices(), mesh.num_curve);
    let Propagation { v_star, n_star, system: prop } = propagate(mesh, ops, t, kept.propagation.take())?;
    let inv_m: Vec<f64> = ops.mass.iter().map(|a| 1.0 / a).collect();
    if n == nc {
        // No free vertex: the mesh is the curves' (patches without interior points).
        let area = mixed_areas(&mesh.faces, &v_star);
        let h = blended_mean_curvature(&mesh.faces, &v_star, &n_star, &area, &mesh.on_boundary);
        return Ok(MethodResult { positions: v_star, propagated_normals: Some(n_star), guide_curvature: Some(h) });
    }

    // 3. The fit's system: weights per row, one factorisation.
    let clock = Instant::now();
    let left_out = mesh.fit_row_left_out();
    let w = fit_weights(&left_out, &inv_m, params.options.energy);
    // Hard constraints eliminate the curve vertices; soft ones keep every vertex unknown.
    let first = if params.soft_weight.is_some() { 0 } else { nc };
    let known = known_rows(n, first, &[&mesh.positions]);
    let fit_energy = LeastSquares { a: &ops.ls, w: &w, first };
    let reuse = params.soft_weight.is_none() && params.options.energy == Energy::Area && !left_out.iter().any(|&b| b);
    if !(reuse && prop.is_some()) && kept.fit.is_none() {
        // On the propagation system's pattern: its symbolic analysis is shared.
        let mut q = product_lower_keeping_pattern(&ops.ls, &w, &ops.ls, first);
        if let Some(omega) = params.soft_weight {
            let mut diag = vec![0.0; n];
            diag[..nc].iter_mut().for_each(|d| *d = omega);
            q.add_diagonal(&diag);
        }
        t.operators += seconds_since(clock);
        let what =
            if params.soft_weight.is_some() { "soft-constrained system" } else { "fit system (L V = −2 H N*)" };
        kept.fit = Some(timed(&mut t.factor, || factor_like(mesh, &q, first, what, prop.as_ref()))?);
    }
    let system = match (reuse, prop.as_ref()) {
        (true, Some(p)) => p,
        _ => kept.fit.as_ref().ok_or_else(|| Error::internal("the fit system was not factorised"))?,
    };

    // 2–4. Guide from V*, fit, then guide from the fitted surface and fit again.
    let mut guide_positions = v_star;
    let mut positions = mesh.positions.clone();
    let mut h = Vec::new();
    for _ in 0..=params.options.guide_updates {
        let clock = Instant::now();
        let surface_area;
        let area = match params.options.guide_area {
            GuideArea::Barycentric => &ops.barycentric,
            GuideArea::Mass => &ops.mass,
            GuideArea::Surface => {
                surface_area = mixed_areas(&mesh.faces, &guide_positions);
                &surface_area
            }
        };
        h = blended_mean_curvature(&mesh.faces, &guide_positions, &n_star, area, &mesh.on_boundary);
        if let Some(i) = h.iter().position(|x| !x.is_finite()) {
            return Err(Error::numerical(format!(
                "the mean-curvature guide is not finite at vertex {i} (a degenerate triangle?)"
            ))
            .vertex(i));
        }
        let mut b = Mat::<f64>::zeros(n, 3);
        for k in 0..n {
            let s = -2.0 * ops.mass[k] * h[k];
            b[(k, 0)] = s * n_star[k].x;
            b[(k, 1)] = s * n_star[k].y;
            b[(k, 2)] = s * n_star[k].z;
        }
        seam_targets(mesh, &ops.mass, &n_star, &mut h, &mut b);
        let mut rhs = fit_energy.rhs(Some(&b), &known);
        if let Some(omega) = params.soft_weight {
            for (k, p) in mesh.positions[..nc].iter().enumerate() {
                rhs[(k, 0)] += omega * p.x;
                rhs[(k, 1)] += omega * p.y;
                rhs[(k, 2)] += omega * p.z;
            }
        }
        t.operators += seconds_since(clock);
        timed(&mut t.solve, || {
            let sol = system.solve(rhs);
            scatter(&sol, 0, first, &mut positions);
        });
        check_finite(&positions, "fit")?;
        guide_positions = positions.clone();
    }
    kept.propagation = prop;
    Ok(MethodResult { positions, propagated_normals: Some(n_star), guide_curvature: Some(h) })
}

/// The fit's targets on the seam rows of a mesh cut along creases (docs/design.md §13,
/// [`Mesh::seam_rows`]): `b_v = −2 A_v H̄_v n_v − ½ Σ |e| ν_e`, with `H̄_v` the mean guide of
/// the copy's neighbours that are not on a border (eq. 1 needs a closed one-ring) and `n_v` its
/// side's normal. Overwrites rows `v` of `b` (n × 3) and `h`.
pub(crate) fn seam_targets(mesh: &Mesh, mass: &[f64], normals: &[DVec3], h: &mut [f64], b: &mut Mat<f64>) {
    if mesh.seam_rows.is_empty() {
        return;
    }
    let mut sum: std::collections::HashMap<u32, (f64, usize)> =
        mesh.seam_rows.iter().map(|&(v, _)| (v, (0.0, 0))).collect();
    for f in &mesh.faces {
        for k in 0..3 {
            if let Some(s) = sum.get_mut(&f[k]) {
                for j in [f[(k + 1) % 3], f[(k + 2) % 3]] {
                    if !mesh.on_boundary[j as usize] {
                        // (Each interior neighbour counts once per face it shares: a weighting.)
                        s.0 += h[j as usize];
                        s.1 += 1;
                    }
                }
            }
        }
    }
    for &(v, [c, _]) in &mesh.seam_rows {
        let k = v as usize;
        let (total, count) = sum[&v];
        h[k] = if count > 0 { total / count as f64 } else { 0.0 };
        let t = -2.0 * mass[k] * h[k] * normals[k] - c;
        for d in 0..3 {
            b[(k, d)] = t[d];
        }
    }
}

/// Targets for the seam rows of the normals' energy `‖L N‖²` in the 3D iterations (docs/design.md
/// §13): the one-sided `(Ls N)_v` of the current surface's normals `prior` (the copies' own
/// normals at the curve vertices). A copy's one-sided Laplacian holds the normal's derivative
/// across the seam; a zero target would force it to vanish (the natural boundary condition
/// of the biharmonic energy, which flattens a cap along its crease). `None` without seams.
pub(crate) fn seam_normal_targets(mesh: &Mesh, ls: &crate::solve::sparse::Csc, prior: &[DVec3]) -> Option<Mat<f64>> {
    if mesh.seam_rows.is_empty() {
        return None;
    }
    let nc = mesh.num_curve;
    let value = |j: usize| if j < nc { mesh.curve_normals[j] } else { prior[j] };
    let mut b = Mat::<f64>::zeros(mesh.num_vertices(), 3);
    for &(v, _) in &mesh.seam_rows {
        let (rows, vals) = ls.col(v as usize);
        let t: DVec3 = rows.iter().zip(vals).map(|(&j, &w)| w * value(j as usize)).sum();
        for d in 0..3 {
            b[(v as usize, d)] = t[d];
        }
    }
    Some(b)
}

/// Targets of the seam rows in the propagation `L² [V N] = 0` (docs/design.md §13): the
/// boundary terms of the one-sided Laplacians, `−½ Σ |e| ν_e` for the positions and
/// `−½ Σ |e| S ν_e` for the normals ([`Mesh::seam_rows`]); zero targets would make the
/// surface and its normals leave the seam flat. `None` without seams.
fn seam_propagation_targets(mesh: &Mesh) -> Option<Mat<f64>> {
    if mesh.seam_rows.is_empty() {
        return None;
    }
    let mut b = Mat::<f64>::zeros(mesh.num_vertices(), 6);
    for &(v, [c, u]) in &mesh.seam_rows {
        for d in 0..3 {
            b[(v as usize, d)] = -c[d];
            b[(v as usize, 3 + d)] = -u[d];
        }
    }
    Some(b)
}
