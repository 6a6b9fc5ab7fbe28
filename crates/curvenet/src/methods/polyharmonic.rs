//! The biharmonic and triharmonic baselines (\[CG\] §4.3, Table 1; \[EG\] Fig. 2): `Δ²V = 0` or
//! `Δ³V = 0` on the free vertices with the curve vertices fixed.
//!
//! Written in symmetric form (multiplying the rows by `M`): `(Ls M⁻¹ Ls)_ff V_f = −(Ls M⁻¹
//! Ls)_fc V_c` and, for `Δ³`, the matrix `−Ls M⁻¹ Ls M⁻¹ Ls` — the same systems as libigl's
//! `harmonic(V, F, b, bc, k)` for the cotangent Laplacian.

use super::{check_finite, factor_on, known_rows, scatter, MethodResult, SurfacingMethod};
use crate::error::Result;
use crate::geom::mesh::Mesh;
use crate::operators::Operators;
use crate::solve::sparse::{product_lower, Csc};
use crate::solve::timing::timed;
use crate::solve::{Eliminated, LeastSquares, SolveTimings};
use faer::Mat;

/// `Δᵏ V = 0` (`order` 2 or 3) as a [`SurfacingMethod`]: the system's factorisation is kept
/// between solves.
pub struct Polyharmonic {
    /// 2 (biharmonic) or 3 (triharmonic).
    order: usize,
    system: Option<Eliminated>,
}

impl Polyharmonic {
    /// The method of `order` 2 or 3, nothing factorised yet.
    pub fn new(order: usize) -> Self {
        Polyharmonic { order, system: None }
    }
}

impl SurfacingMethod for Polyharmonic {
    fn name(&self) -> &'static str {
        if self.order == 2 {
            super::Method::Biharmonic.name()
        } else {
            super::Method::Triharmonic.name()
        }
    }

    fn solve(&mut self, mesh: &Mesh, ops: &Operators, t: &mut SolveTimings) -> Result<MethodResult> {
        let (n, nc) = (mesh.num_vertices(), mesh.num_curve);
        let mut positions = mesh.positions.clone();
        if n == nc {
            return Ok(MethodResult { positions, ..Default::default() });
        }
        let order = self.order;
        let (products, rhs) = timed(&mut t.operators, || {
            let p = Products::new(ops, order);
            let rhs = rhs(ops, &p, &known_rows(n, nc, &[&mesh.positions]), nc);
            (p, rhs)
        });
        let system = match self.system.take().filter(|s| s.dim() == n - nc) {
            Some(s) => s,
            None => {
                let q = timed(&mut t.operators, || matrix(ops, &products, nc));
                let what = if order == 2 { "biharmonic system" } else { "triharmonic system" };
                timed(&mut t.factor, || factor_on(mesh, &q, nc, what))?
            }
        };
        timed(&mut t.solve, || scatter(&system.solve(rhs), 0, nc, &mut positions));
        self.system = Some(system);
        check_finite(&positions, "polyharmonic solve")?;
        Ok(MethodResult { positions, ..Default::default() })
    }

    fn is_factored(&self) -> bool {
        self.system.is_some()
    }

    fn release(&mut self) {
        self.system = None;
    }
}

/// Solves `Δᵏ V = 0` (`order` 2 or 3) once for the free vertices of `mesh`.
pub fn polyharmonic(mesh: &Mesh, ops: &Operators, order: usize, t: &mut SolveTimings) -> Result<MethodResult> {
    Polyharmonic::new(order).solve(mesh, ops, t)
}

/// The products shared by the matrix and the right-hand side of `Δᵏ X = 0`: `M⁻¹` and, for
/// `order` 3, `T = Ls M⁻¹ Ls` (assembled once per solve).
pub(crate) struct Products {
    inv_m: Vec<f64>,
    tt: Option<Csc>,
}

impl Products {
    /// The products of `ops` for `order` 2 or 3.
    pub(crate) fn new(ops: &Operators, order: usize) -> Self {
        let inv_m: Vec<f64> = ops.mass.iter().map(|a| 1.0 / a).collect();
        let tt = (order != 2).then(|| crate::solve::sparse::product(&ops.ls, &inv_m, &ops.ls, 0));
        Products { inv_m, tt }
    }
}

/// The lower triangle of the matrix of `Δᵏ X = 0` on the unknown rows `first..`:
/// `(Ls M⁻¹ Ls)_uu` (order 2) or `(−Ls M⁻¹ Ls M⁻¹ Ls)_uu` (order 3, `p.tt` given).
pub(crate) fn matrix(ops: &Operators, p: &Products, first: usize) -> Csc {
    match &p.tt {
        None => product_lower(&ops.ls, &p.inv_m, &ops.ls, first),
        Some(tt) => {
            let neg: Vec<f64> = p.inv_m.iter().map(|x| -x).collect();
            product_lower(&ops.ls, &neg, tt, first)
        }
    }
}

/// The right-hand side `−(Q X̃)_u` of `Δᵏ X = 0` on the unknown rows `first..` with the rows
/// `..first` of `known` fixed (one column per column of `known`).
pub(crate) fn rhs(ops: &Operators, p: &Products, known: &Mat<f64>, first: usize) -> Mat<f64> {
    let n = ops.ls.nrows;
    let energy = LeastSquares { a: &ops.ls, w: &p.inv_m, first };
    match &p.tt {
        None => energy.rhs(None, known),
        Some(tt) => {
            // T = Ls M⁻¹ Ls; Q₃ = −Ls M⁻¹ T; rhs = −(Q₃ X̃)_f = (Ls M⁻¹ T X̃)_f.
            let mut y = Mat::<f64>::zeros(n, known.ncols());
            tt.sym_mul_dense(known.as_ref(), y.as_mut());
            energy.rhs(Some(&y), &Mat::<f64>::zeros(n, known.ncols()))
        }
    }
}
