//! The biharmonic and triharmonic baselines ([CG] §4.3, Table 1; [EG] Fig. 2): `Δ²V = 0` or
//! `Δ³V = 0` on the free vertices with the curve vertices fixed.
//!
//! Written in symmetric form (multiplying the rows by `M`): `(Ls M⁻¹ Ls)_ff V_f = −(Ls M⁻¹
//! Ls)_fc V_c` and, for `Δ³`, the matrix `−Ls M⁻¹ Ls M⁻¹ Ls` — the same systems as libigl's
//! `harmonic(V, F, b, bc, k)` for the cotangent Laplacian.

use super::{check_finite, factor_on, known_rows, scatter, weighted_rhs, MethodResult, SolveTimings};
use crate::solve::timing::Instant;
use crate::error::Result;
use crate::geom::mesh::Mesh;
use crate::operators::Operators;
use crate::solve::sparse::{product_lower, Csc};
use faer::Mat;

/// Solves `Δᵏ V = 0` (`order` 2 or 3) for the free vertices of `mesh`.
pub fn polyharmonic(mesh: &Mesh, ops: &Operators, order: usize, t: &mut SolveTimings) -> Result<MethodResult> {
    let (n, nc) = (mesh.num_vertices(), mesh.num_curve);
    let mut positions = mesh.positions.clone();
    if n == nc {
        return Ok(MethodResult { positions, ..Default::default() });
    }
    let clock = Instant::now();
    let known = known_rows(n, nc, &[&mesh.positions]);
    let (q, rhs) = system(ops, order, &known, nc);
    t.operators += clock.elapsed().as_secs_f64();
    let clock = Instant::now();
    let chol = factor_on(mesh, &q, nc, if order == 2 { "biharmonic system" } else { "triharmonic system" })?;
    t.factor += clock.elapsed().as_secs_f64();
    let clock = Instant::now();
    let mut sol = rhs;
    chol.solve_in_place(sol.as_mut());
    scatter(&sol, 0, nc, &mut positions);
    t.solve += clock.elapsed().as_secs_f64();
    check_finite(&positions, "polyharmonic solve")?;
    Ok(MethodResult { positions, ..Default::default() })
}

/// The system of `Δᵏ X = 0` (`order` 2 or 3) on the unknown rows `first..` with the rows
/// `..first` of `known` fixed: the lower triangle of the matrix on the unknowns and the
/// right-hand side `−(Q X̃)_f` (one column per column of `known`).
pub(crate) fn system(ops: &Operators, order: usize, known: &Mat<f64>, first: usize) -> (Csc, Mat<f64>) {
    let n = ops.ls.nrows;
    let inv_m: Vec<f64> = ops.mass.iter().map(|a| 1.0 / a).collect();
    if order == 2 {
        (product_lower(&ops.ls, &inv_m, &ops.ls, first), weighted_rhs(&ops.ls, &inv_m, None, known, first))
    } else {
        // T = Ls M⁻¹ Ls; Q₃ = −Ls M⁻¹ T; rhs = −(Q₃ X̃)_f = (Ls M⁻¹ T X̃)_f.
        let tt = crate::solve::sparse::product(&ops.ls, &inv_m, &ops.ls, 0);
        let neg: Vec<f64> = inv_m.iter().map(|x| -x).collect();
        let q3 = product_lower(&ops.ls, &neg, &tt, first);
        let mut y = Mat::<f64>::zeros(n, known.ncols());
        tt.sym_mul_dense(known.as_ref(), y.as_mut());
        let rhs = weighted_rhs(&ops.ls, &inv_m, Some(&y), &Mat::<f64>::zeros(n, known.ncols()), first);
        (q3, rhs)
    }
}
