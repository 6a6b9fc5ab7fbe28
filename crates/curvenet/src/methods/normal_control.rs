//! Normal-controlled surfacing ([CG] §3.4): propagate positions and normals from the curves,
//! estimate the signed mean curvature from both (eq. 1), and find the surface whose Laplacian
//! best matches the mean-curvature vectors (eq. 2–3), with hard or soft ([CG] §4.5) curve
//! constraints.
//!
//! 1. Propagation: `L² V* = 0`, `L² N* = 0` on the free vertices, curve vertices fixed; in
//!    symmetric form `(Ls M⁻¹ Ls)_ff X_f = −(Ls M⁻¹ Ls)_fc X_c`, one factorisation for the six
//!    columns; `N*` normalised.
//! 2. Guide: `H(v) = h(v) · n*(v)` with `h` from eq. 1 on `(V*, N*)` (signed, docs/design.md §1),
//!    divided by the Laplacian's own Voronoi area `M` ([`GuideArea::Mass`], default) or by the
//!    area of `v*` on `V*` as the paper states it ([`GuideArea::Surface`]).
//! 3. Fit: `min Σ_v w_v ‖(Ls V)_v − b_v‖²`, `b_v = −2 A_v H_v n*_v` (that is `L V = −2 H N*`),
//!    with `w_v = 1/A_v` (area-weighted, docs/design.md §1) or `1/A_v²` ([CG] eq. 2 as written). Rows
//!    of open-boundary vertices are left out (their one-sided Laplacian is not a curvature).
//!    With the area weighting and no open boundary the matrix is the propagation's, and its
//!    factorisation is reused.
//! 4. Guide updates (`guide_updates` times, an extension of the paper): eq. 1 is evaluated
//!    again on the fitted surface `V` (same normals `N*`) and the fit repeated with the same
//!    factorisation. `V*` is a biharmonic interpolant whose tangential distribution differs
//!    from the fit's (at open borders markedly: the cylinder of [CG] Fig. 1 bulges to radius
//!    1.09 with `V*`, and is exact to 2e-5 after one update); the fitted surface's is the
//!    one the fit's Laplacian sees.
//! 5. Soft constraints ([CG] §4.5): `+ ω_s Σ_{s ∈ curve} ‖v_s − v*_s‖²`, all vertices unknown.

use super::{
    check_finite, factor_on, known_rows, scatter, weighted_rhs, GuideArea, MethodResult, SolveTimings, Weighting,
};
use crate::solve::timing::Instant;
use crate::error::{Error, Result};
use crate::geom::{fmt_point, DVec3};
use crate::geom::mesh::Mesh;
use crate::operators::{blended_mean_curvature, mixed_areas, Operators};
use crate::solve::Cholesky;
use crate::solve::sparse::product_lower;
use faer::Mat;

/// Parameters of one normal-control solve.
#[derive(Clone, Copy, Debug, Default)]
pub struct NormalControlParams {
    pub weighting: Weighting,
    /// The area dividing eq. 1.
    pub guide_area: GuideArea,
    /// How many times the guide is re-estimated on the fitted surface (0: the paper).
    pub guide_updates: usize,
    /// Soft-constraint weight `ω_s` per curve vertex, already scaled (see
    /// [`crate::Options::soft`]); `None` for hard constraints.
    pub soft_weight: Option<f64>,
}

/// The propagated positions and normals ([CG] §3.4, "Initial vertices and propagated
/// normals") and the factorisation that computed them.
pub(crate) struct Propagation {
    /// `V*`: the biharmonic interpolant of the curve vertices, `#V`.
    pub v_star: Vec<DVec3>,
    /// `N*`: the biharmonic interpolant of the curve normals, normalised, `#V`.
    pub n_star: Vec<DVec3>,
    /// The factorisation of `(Ls M⁻¹ Ls)_ff` (none without free vertices).
    pub chol: Option<Cholesky>,
}

/// The factorisations of the normal-control systems, kept between solves on the same mesh,
/// operators and parameters: the matrices depend on neither the curve positions nor the
/// normals, so a solve with new curve normals costs only right-hand sides and triangular
/// solves ([`crate::pipeline::surfacer::Surfacer`]).
#[derive(Default)]
pub struct Factors {
    /// `(Ls M⁻¹ Ls)_ff` of the propagation.
    pub(crate) propagation: Option<Cholesky>,
    /// The fit's matrix when it differs from the propagation's (open borders, uniform
    /// weighting, soft constraints).
    pub(crate) fit: Option<Cholesky>,
}

impl Factors {
    /// Whether a factorisation is kept.
    pub fn is_empty(&self) -> bool {
        self.propagation.is_none() && self.fit.is_none()
    }
}

/// `L² V* = 0`, `L² N* = 0` on the free vertices with the curve vertices fixed, in symmetric
/// form `(Ls M⁻¹ Ls)_ff X_f = −(Ls M⁻¹ Ls)_fc X_c`: one factorisation (or `cached`, that of an
/// earlier call on the same mesh and operators), six columns.
pub(crate) fn propagate(
    mesh: &Mesh,
    ops: &Operators,
    t: &mut SolveTimings,
    cached: Option<Cholesky>,
) -> Result<Propagation> {
    let (n, nc) = (mesh.num_vertices(), mesh.num_curve);
    let mut v_star = mesh.positions.clone();
    let mut n_star: Vec<DVec3> = mesh.curve_normals.clone();
    n_star.resize(n, DVec3::ZERO);
    if n == nc {
        return Ok(Propagation { v_star, n_star, chol: None });
    }
    let inv_m: Vec<f64> = ops.mass.iter().map(|a| 1.0 / a).collect();
    let right_hand_sides = || {
        let known = known_rows(n, nc, &[&mesh.positions, &mesh.curve_normals]);
        weighted_rhs(&ops.ls, &inv_m, None, &known, nc)
    };
    let (chol, rhs) = match cached {
        Some(c) => {
            let clock = Instant::now();
            let rhs = right_hand_sides();
            t.operators += clock.elapsed().as_secs_f64();
            (c, rhs)
        }
        None => {
            let clock = Instant::now();
            let q = product_lower(&ops.ls, &inv_m, &ops.ls, nc);
            t.operators += clock.elapsed().as_secs_f64();
            // Below `PARALLEL_FROM` unknowns the numeric factorisation runs on one thread: the
            // right-hand sides are computed on the other core meanwhile. Above, the
            // factorisation uses every core and they follow it (less memory at its peak).
            // Stage times: the factorisation's own; the rest of the window to the operators.
            let factor = || {
                let clock = Instant::now();
                let chol = factor_on(mesh, &q, nc, "propagation system (L² V* = 0)");
                (chol, clock.elapsed().as_secs_f64())
            };
            let window = Instant::now();
            let ((chol, factor_time), rhs) = if q.ncols < crate::solve::PARALLEL_FROM {
                rayon::join(factor, right_hand_sides)
            } else {
                let c = factor();
                (c, right_hand_sides())
            };
            t.factor += factor_time;
            t.operators += (window.elapsed().as_secs_f64() - factor_time).max(0.0);
            (chol?, rhs)
        }
    };
    let clock = Instant::now();
    let mut sol = rhs;
    chol.solve_in_place(sol.as_mut());
    scatter(&sol, 0, nc, &mut v_star);
    scatter(&sol, 3, nc, &mut n_star);
    t.solve += clock.elapsed().as_secs_f64();
    for i in nc..n {
        let u = n_star[i].normalize_or_zero();
        if u == DVec3::ZERO || !u.is_finite() {
            return Err(Error::numerical(format!(
                "the propagated normal vanishes at vertex {i} near {}: the input normals around it cancel out \
                 (check that they all point outward)",
                fmt_point(v_star[i])
            )));
        }
        n_star[i] = u;
    }
    check_finite(&v_star, "propagation")?;
    Ok(Propagation { v_star, n_star, chol: Some(chol) })
}

/// Runs the method on `mesh` with the operators `ops` (planar or surface metric).
pub fn normal_control(
    mesh: &Mesh,
    ops: &Operators,
    params: &NormalControlParams,
    t: &mut SolveTimings,
) -> Result<MethodResult> {
    normal_control_cached(mesh, ops, params, t, &mut Factors::default())
}

/// [`normal_control`] with the factorisations of `factors` (from an earlier call with the
/// same mesh, `ops` and `params`; the curve positions and normals may differ), computing and
/// storing those it lacks.
pub fn normal_control_cached(
    mesh: &Mesh,
    ops: &Operators,
    params: &NormalControlParams,
    t: &mut SolveTimings,
    factors: &mut Factors,
) -> Result<MethodResult> {
    let (n, nc) = (mesh.num_vertices(), mesh.num_curve);
    let Propagation { v_star, n_star, chol: prop } = propagate(mesh, ops, t, factors.propagation.take())?;
    let inv_m: Vec<f64> = ops.mass.iter().map(|a| 1.0 / a).collect();
    if n == nc {
        // No free vertex: the mesh is the curves' (patches without interior points).
        let area = mixed_areas(&mesh.faces, &v_star);
        let h = blended_mean_curvature(&mesh.faces, &v_star, &n_star, &area, &mesh.on_boundary);
        return Ok(MethodResult { positions: v_star, propagated_normals: Some(n_star), guide_curvature: Some(h) });
    }

    // 3. The fit's system: weights per row, one factorisation.
    let clock = Instant::now();
    let w: Vec<f64> = (0..n)
        .map(|k| match (mesh.on_boundary[k], params.weighting) {
            (true, _) => 0.0,
            (false, Weighting::Area) => inv_m[k],
            (false, Weighting::Uniform) => inv_m[k] * inv_m[k],
        })
        .collect();
    // Hard constraints eliminate the curve vertices; soft ones keep every vertex unknown.
    let first = if params.soft_weight.is_some() { 0 } else { nc };
    let known = known_rows(n, first, &[&mesh.positions]);
    let reuse =
        params.soft_weight.is_none() && params.weighting == Weighting::Area && !mesh.on_boundary.iter().any(|&b| b);
    if !(reuse && prop.is_some()) && factors.fit.is_none() {
        let mut q = product_lower(&ops.ls, &w, &ops.ls, first);
        if let Some(omega) = params.soft_weight {
            let mut diag = vec![0.0; n];
            diag[..nc].iter_mut().for_each(|d| *d = omega);
            q.add_diagonal(&diag);
        }
        t.operators += clock.elapsed().as_secs_f64();
        let clock = Instant::now();
        let own = factor_on(
            mesh,
            &q,
            first,
            if params.soft_weight.is_some() { "soft-constrained system" } else { "fit system (L V = −2 H N*)" },
        )?;
        t.factor += clock.elapsed().as_secs_f64();
        factors.fit = Some(own);
    }
    let chol = match (reuse, prop.as_ref()) {
        (true, Some(p)) => p,
        _ => factors.fit.as_ref().ok_or_else(|| Error::numerical("the fit system was not factorised"))?,
    };

    // 2–4. Guide from V*, fit, then guide from the fitted surface and fit again.
    let mut guide_positions = v_star;
    let mut positions = mesh.positions.clone();
    let mut h = Vec::new();
    for _ in 0..=params.guide_updates {
        let clock = Instant::now();
        let surface_area;
        let area = match params.guide_area {
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
            )));
        }
        let mut b = Mat::<f64>::zeros(n, 3);
        for k in 0..n {
            let s = -2.0 * ops.mass[k] * h[k];
            b[(k, 0)] = s * n_star[k].x;
            b[(k, 1)] = s * n_star[k].y;
            b[(k, 2)] = s * n_star[k].z;
        }
        let mut rhs = weighted_rhs(&ops.ls, &w, Some(&b), &known, first);
        if let Some(omega) = params.soft_weight {
            for (k, p) in mesh.positions[..nc].iter().enumerate() {
                rhs[(k, 0)] += omega * p.x;
                rhs[(k, 1)] += omega * p.y;
                rhs[(k, 2)] += omega * p.z;
            }
        }
        t.operators += clock.elapsed().as_secs_f64();
        let clock = Instant::now();
        chol.solve_in_place(rhs.as_mut());
        scatter(&rhs, 0, first, &mut positions);
        t.solve += clock.elapsed().as_secs_f64();
        check_finite(&positions, "fit")?;
        guide_positions = positions.clone();
    }
    factors.propagation = prop;
    Ok(MethodResult { positions, propagated_normals: Some(n_star), guide_curvature: Some(h) })
}
