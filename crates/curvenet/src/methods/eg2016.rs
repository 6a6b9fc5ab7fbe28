//! The energy of the authors' Eurographics 2016 short paper (\[EG\] §2, "Optimization"): the
//! bi-Laplacian penalised by the mean-curvature guide, with soft constraints,
//!
//! `E(V) = Σ_v A_v ‖Δ²v‖² + ω₁ Σ_v A_v ‖Δv + 2H n*‖² + ω₀ Σ_s ‖v_s − v*_s‖²`,
//!
//! area-weighted as in docs/design.md §1 (the \[EG\] sums are unweighted). In matrix form the first term
//! is `Vᵀ (Ls M⁻¹ Ls M⁻¹ Ls M⁻¹ Ls) V` (a three-ring stencil). `H` and `n*` are the guide of
//! [`super::normal_control`] (eq. 1 on `V*`, `N*`). Units: the first term scales as length⁻⁴
//! relative to the second, so `ω₁ = w1 / s⁴` with `s` the mean patch size makes `w1`
//! dimensionless: the guide dominates at scales above `s / w1^¼`. `ω₀` is `w0` scaled like
//! `--soft` (relative to the guide term).

use super::normal_control::{propagate, Propagation};
use super::{check_finite, factor_on, known_rows, scatter, MethodResult, SurfacingMethod};
use crate::error::{Error, Result};
use crate::geom::mesh::Mesh;
use crate::operators::{blended_mean_curvature, Operators};
use crate::solve::sparse::{product, Csc};
use crate::solve::timing::{seconds_since, timed, Instant};
use crate::solve::{Eliminated, LeastSquares, SolveTimings};
use faer::Mat;

/// The user's setting of the short paper's energy (option `w1`, docs/design.md §6).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ShortPaperOptions {
    /// `w1`: weight of the curvature guide, dimensionless (`ω₁ = w1 / s⁴`, `s` the mean patch
    /// size). Default [`ShortPaperOptions::DEFAULT_W1`].
    pub w1: f64,
}

impl ShortPaperOptions {
    /// Default `w1`: the guide dominates above `s / w1^¼ ≈ s / 32`.
    pub const DEFAULT_W1: f64 = 1e6;
}

impl Default for ShortPaperOptions {
    fn default() -> Self {
        ShortPaperOptions { w1: Self::DEFAULT_W1 }
    }
}

/// The weights of the \[EG\] energy, scaled for the mesh (see the module documentation).
#[derive(Clone, Copy, Debug)]
pub struct ShortPaperParams {
    /// `ω₁ = w1 / s⁴`.
    pub omega1: f64,
    /// `ω₀` per curve vertex (already scaled like `soft`), `None` for hard constraints.
    pub omega0: Option<f64>,
}

/// The \[EG\] energy as a [`SurfacingMethod`]: keeps the propagation's factorisation and that
/// of its own system between solves.
pub struct ShortPaper {
    /// The weights of every solve.
    params: ShortPaperParams,
    propagation: Option<Eliminated>,
    /// The system's matrix (kept for the residual check) and factorisation.
    system: Option<(Csc, Eliminated)>,
}

impl ShortPaper {
    /// The method with `params`, nothing factorised yet.
    pub fn new(params: ShortPaperParams) -> Self {
        ShortPaper { params, propagation: None, system: None }
    }
}

impl SurfacingMethod for ShortPaper {
    fn name(&self) -> &'static str {
        super::Method::ShortPaper.name()
    }

    fn solve(&mut self, mesh: &Mesh, ops: &Operators, t: &mut SolveTimings) -> Result<MethodResult> {
        let (n, nc) = (mesh.num_vertices(), mesh.num_curve);
        let params = self.params;
        let first = if params.omega0.is_some() { 0 } else { nc };
        let kept = self.system.take().filter(|s| s.1.dim() == n - first);
        let propagation = self.propagation.take().filter(|s| s.dim() == n - nc);
        let Propagation { v_star, n_star, system } = propagate(mesh, ops, t, propagation)?;
        // The first solve frees the propagation's factor before factorising its own (peak
        // memory as one factor); later solves keep both.
        self.propagation = if kept.is_some() { system } else { None };
        if n == first {
            return Ok(MethodResult { positions: v_star, propagated_normals: Some(n_star), guide_curvature: None });
        }
        let clock = Instant::now();
        let h = blended_mean_curvature(&mesh.faces, &v_star, &n_star, &ops.mass, &mesh.on_boundary);
        let inv_m: Vec<f64> = ops.mass.iter().map(|a| 1.0 / a).collect();
        // Bending: T = Ls M⁻¹ Ls (all vertices).
        let tt = product(&ops.ls, &inv_m, &ops.ls, 0);
        // Guide: rows of open-border vertices left out, as in normal-control.
        let w: Vec<f64> = (0..n).map(|k| if mesh.on_boundary[k] { 0.0 } else { inv_m[k] }).collect();
        let (q, system) = match kept {
            Some(s) => {
                t.operators += seconds_since(clock);
                s
            }
            None => {
                let q = matrix(ops, &tt, &inv_m, &w, nc, first, &params);
                t.operators += seconds_since(clock);
                let system = timed(&mut t.factor, || factor_on(mesh, &q, first, "short-paper system (Δ⁴ + ω₁ guide)"))?;
                (q, system)
            }
        };
        let clock = Instant::now();
        let rhs = right_hand_side(mesh, ops, &tt, &inv_m, &w, &h, &n_star, first, &params);
        t.operators += seconds_since(clock);
        let clock = Instant::now();
        let sol = system.solve(rhs.clone());
        let residual = relative_residual(&q, &sol, &rhs);
        self.system = Some((q, system));
        // The Δ⁴ stencil's condition number grows like (size / spacing)⁸: check the solve.
        if !(residual <= 1e-6) {
            return Err(Error::numerical(format!(
                "the short-paper system is too ill-conditioned at this resolution (relative residual {residual:.1e}); \
                 raise `w1` or `spacing`"
            )));
        }
        let mut positions = mesh.positions.clone();
        scatter(&sol, 0, first, &mut positions);
        t.solve += seconds_since(clock);
        check_finite(&positions, "short-paper energy")?;
        Ok(MethodResult { positions, propagated_normals: Some(n_star), guide_curvature: Some(h) })
    }

    fn is_factored(&self) -> bool {
        self.propagation.is_some() || self.system.is_some()
    }

    fn release(&mut self) {
        self.propagation = None;
        self.system = None;
    }
}

/// Minimises the \[EG\] energy once on `mesh` with the operators `ops`.
pub fn short_paper(
    mesh: &Mesh,
    ops: &Operators,
    params: &ShortPaperParams,
    t: &mut SolveTimings,
) -> Result<MethodResult> {
    ShortPaper::new(*params).solve(mesh, ops, t)
}

/// The lower triangle of the system on the unknowns `first..`: `Q_b + ω₁ (Ls W Ls)` with
/// `Q_b = T M⁻¹ T` (`tt` = `T`), plus `ω₁ ω₀` on the soft curve rows.
fn matrix(ops: &Operators, tt: &Csc, inv_m: &[f64], w: &[f64], nc: usize, first: usize, p: &ShortPaperParams) -> Csc {
    let n = inv_m.len();
    let qb = product(tt, inv_m, tt, first);
    let mut q = qb.add_scaled(&product(&ops.ls, w, &ops.ls, first), p.omega1);
    if let Some(o) = p.omega0 {
        let diag: Vec<f64> = (0..n).map(|k| if k < nc { p.omega1 * o } else { 0.0 }).collect();
        q.add_diagonal(&diag);
    }
    q
}

/// The right-hand side `−(T M⁻¹ T X̃)_u + ω₁ (Ls W (b − Ls X̃))_u (+ ω₁ ω₀ v*_c)` with
/// `b = −2 M H n*`.
#[allow(clippy::too_many_arguments)]
fn right_hand_side(
    mesh: &Mesh,
    ops: &Operators,
    tt: &Csc,
    inv_m: &[f64],
    w: &[f64],
    h: &[f64],
    n_star: &[crate::geom::DVec3],
    first: usize,
    p: &ShortPaperParams,
) -> Mat<f64> {
    let (n, nc) = (mesh.num_vertices(), mesh.num_curve);
    let known = known_rows(n, first, &[&mesh.positions]);
    let mut y = Mat::<f64>::zeros(n, 3);
    tt.mul_dense(known.as_ref(), y.as_mut());
    let mut rhs = LeastSquares { a: tt, w: inv_m, first }.rhs(Some(&y), &Mat::<f64>::zeros(n, 3));
    let mut b = Mat::<f64>::zeros(n, 3);
    for k in 0..n {
        for c in 0..3 {
            b[(k, c)] = -2.0 * ops.mass[k] * h[k] * n_star[k][c];
        }
    }
    let guide = LeastSquares { a: &ops.ls, w, first }.rhs(Some(&b), &known);
    for i in 0..n - first {
        for c in 0..3 {
            rhs[(i, c)] = -rhs[(i, c)] + p.omega1 * guide[(i, c)];
        }
    }
    if let Some(o) = p.omega0 {
        for (k, q) in mesh.positions[..nc].iter().enumerate() {
            for c in 0..3 {
                rhs[(k, c)] += p.omega1 * o * q[c];
            }
        }
    }
    rhs
}

/// `‖Q x − b‖ / ‖b‖` (Frobenius) for the full symmetric `q` (both triangles stored).
fn relative_residual(q: &Csc, x: &Mat<f64>, b: &Mat<f64>) -> f64 {
    let mut r = Mat::<f64>::zeros(x.nrows(), x.ncols());
    q.mul_dense(x.as_ref(), r.as_mut());
    let (mut num, mut den) = (0.0f64, 0.0f64);
    for i in 0..x.nrows() {
        for c in 0..x.ncols() {
            num += (r[(i, c)] - b[(i, c)]).powi(2);
            den += b[(i, c)].powi(2);
        }
    }
    num.sqrt() / den.sqrt().max(f64::MIN_POSITIVE)
}
