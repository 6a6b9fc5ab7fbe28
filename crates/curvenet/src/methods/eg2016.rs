//! The energy of the authors' Eurographics 2016 short paper ([EG] §2, "Optimization"): the
//! bi-Laplacian penalised by the mean-curvature guide, with soft constraints,
//!
//! `E(V) = Σ_v A_v ‖Δ²v‖² + ω₁ Σ_v A_v ‖Δv + 2H n*‖² + ω₀ Σ_s ‖v_s − v*_s‖²`,
//!
//! area-weighted as in docs/design.md §1 (the [EG] sums are unweighted). In matrix form the first term
//! is `Vᵀ (Ls M⁻¹ Ls M⁻¹ Ls M⁻¹ Ls) V` (a three-ring stencil). `H` and `n*` are the guide of
//! [`super::normal_control`] (eq. 1 on `V*`, `N*`). Units: the first term scales as length⁻⁴
//! relative to the second, so `ω₁ = w1 / s⁴` with `s` the mean patch size makes `w1`
//! dimensionless: the guide dominates at scales above `s / w1^¼`. `ω₀` is `w0` scaled like
//! `--soft` (relative to the guide term).

use super::normal_control::{propagate, Propagation};
use super::{check_finite, factor_on, known_rows, scatter, weighted_rhs, MethodResult, SolveTimings};
use crate::solve::timing::Instant;
use crate::error::Result;
use crate::geom::mesh::Mesh;
use crate::operators::{blended_mean_curvature, Operators};
use crate::solve::sparse::product;
use faer::Mat;

/// Parameters of the [EG] energy.
#[derive(Clone, Copy, Debug)]
pub struct ShortPaperParams {
    /// `ω₁` (already scaled: `w1 / s⁴`).
    pub omega1: f64,
    /// `ω₀` per curve vertex (already scaled), `None` for hard constraints.
    pub omega0: Option<f64>,
}

/// Minimises the [EG] energy on `mesh` with the operators `ops`.
pub fn short_paper(
    mesh: &Mesh,
    ops: &Operators,
    params: &ShortPaperParams,
    t: &mut SolveTimings,
) -> Result<MethodResult> {
    let (n, nc) = (mesh.num_vertices(), mesh.num_curve);
    let Propagation { v_star, n_star, .. } = propagate(mesh, ops, t, None)?;
    let first = if params.omega0.is_some() { 0 } else { nc };
    if n == first {
        return Ok(MethodResult { positions: v_star, propagated_normals: Some(n_star), guide_curvature: None });
    }
    let clock = Instant::now();
    let h = blended_mean_curvature(&mesh.faces, &v_star, &n_star, &ops.mass, &mesh.on_boundary);
    let inv_m: Vec<f64> = ops.mass.iter().map(|a| 1.0 / a).collect();
    // Bending: T = Ls M⁻¹ Ls (all vertices), Q_b = T M⁻¹ T restricted.
    let tt = product(&ops.ls, &inv_m, &ops.ls, 0);
    let qb = product(&tt, &inv_m, &tt, first);
    // Guide: rows of open-border vertices left out, as in normal-control.
    let w: Vec<f64> = (0..n).map(|k| if mesh.on_boundary[k] { 0.0 } else { inv_m[k] }).collect();
    let mut q = qb.add_scaled(&product(&ops.ls, &w, &ops.ls, first), params.omega1);
    if let Some(o) = params.omega0 {
        let diag: Vec<f64> = (0..n).map(|k| if k < nc { params.omega1 * o } else { 0.0 }).collect();
        q.add_diagonal(&diag);
    }
    // Right-hand side: −(T M⁻¹ T X̃)_u + ω₁ (Ls W (b − Ls X̃))_u (+ ω₀ v*_c).
    let known = known_rows(n, first, &[&mesh.positions]);
    let mut y = Mat::<f64>::zeros(n, 3);
    tt.mul_dense(known.as_ref(), y.as_mut());
    let mut rhs = weighted_rhs(&tt, &inv_m, Some(&y), &Mat::<f64>::zeros(n, 3), first);
    let mut b = Mat::<f64>::zeros(n, 3);
    for k in 0..n {
        for c in 0..3 {
            b[(k, c)] = -2.0 * ops.mass[k] * h[k] * n_star[k][c];
        }
    }
    let guide = weighted_rhs(&ops.ls, &w, Some(&b), &known, first);
    for i in 0..n - first {
        for c in 0..3 {
            rhs[(i, c)] = -rhs[(i, c)] + params.omega1 * guide[(i, c)];
        }
    }
    if let Some(o) = params.omega0 {
        for (k, p) in mesh.positions[..nc].iter().enumerate() {
            for c in 0..3 {
                rhs[(k, c)] += params.omega1 * o * p[c];
            }
        }
    }
    t.operators += clock.elapsed().as_secs_f64();
    let clock = Instant::now();
    let chol = factor_on(mesh, &q, first, "short-paper system (Δ⁴ + ω₁ guide)")?;
    t.factor += clock.elapsed().as_secs_f64();
    let clock = Instant::now();
    let b0 = rhs.clone();
    chol.solve_in_place(rhs.as_mut());
    // The Δ⁴ stencil's condition number grows like (size / spacing)⁸: check the solve.
    let mut r = Mat::<f64>::zeros(n - first, 3);
    q.mul_dense(rhs.as_ref(), r.as_mut());
    let (mut num, mut den) = (0.0f64, 0.0f64);
    for i in 0..n - first {
        for c in 0..3 {
            num += (r[(i, c)] - b0[(i, c)]).powi(2);
            den += b0[(i, c)].powi(2);
        }
    }
    if !(num.sqrt() <= 1e-6 * den.sqrt().max(f64::MIN_POSITIVE)) {
        return Err(crate::error::Error::numerical(format!(
            "the short-paper system is too ill-conditioned at this resolution (relative residual {:.1e}); \
             raise `w1` or `spacing`",
            num.sqrt() / den.sqrt()
        )));
    }
    let mut positions = mesh.positions.clone();
    scatter(&rhs, 0, first, &mut positions);
    t.solve += clock.elapsed().as_secs_f64();
    check_finite(&positions, "short-paper energy")?;
    Ok(MethodResult { positions, propagated_normals: Some(n_star), guide_curvature: Some(h) })
}
