//! Method (4) of \[CG\] §4.2 (after Botsch and Kobbelt): `Δ²V = 0` on the free vertices with the
//! positions fixed on the curves and `ΔV = b₁` prescribed there, with `b₁ = −2 H n` from the
//! input normals (\[CG\]: "we directly cast the b₁ as equality constraints").
//!
//! **How `b₁` is derived.** `n` is the input normal of the curve vertex; `H` is the signed
//! mean curvature of the normal-control guide (eq. 1) at that vertex, evaluated on the
//! propagated surface `V*` with the propagated normals `N*` around it and divided by the
//! Laplacian's area (so that `b₁` is consistent with `L`). At open-border vertices, where the
//! one-sided Laplacian is not a curvature, `b₁` is the one-sided Laplacian of `V*`.
//!
//! **Solve.** Written in mixed form with `U = ΔV`: `ΔU = 0` on the free vertices with
//! `U = b₁` on the curves, then `ΔV = U` on the free vertices with `V` fixed on the curves —
//! two solves with the same matrix `−(Ls)_ff`, factored once. The direct form, with the rows
//! `(L V)_c = b₁` added as equality constraints on `V_f`, has rows that vanish (a curve vertex
//! whose ring holds no free vertex) and rows that contradict each other; in the mixed form
//! `b₁` is boundary data of `U`, so no constraint row can be dependent.

use super::normal_control::{propagate, Propagation};
use super::{check_finite, known_rows, scatter, MethodResult, SurfacingMethod};
use crate::error::Result;
use crate::geom::mesh::Mesh;
use crate::geom::DVec3;
use crate::operators::{blended_mean_curvature, Operators};
use crate::solve::timing::timed;
use crate::solve::{Eliminated, SolveTimings};
use faer::Mat;

/// Method (4) as a [`SurfacingMethod`]: keeps the propagation's factorisation and that of
/// `−(Ls)_ff` between solves.
#[derive(Default)]
pub struct Method4 {
    propagation: Option<Eliminated>,
    laplacian: Option<Eliminated>,
}

impl Method4 {
    /// The method, nothing factorised yet.
    pub fn new() -> Self {
        Method4::default()
    }
}

impl SurfacingMethod for Method4 {
    fn name(&self) -> &'static str {
        super::Method::Method4.name()
    }

    fn solve(&mut self, mesh: &Mesh, ops: &Operators, t: &mut SolveTimings) -> Result<MethodResult> {
        let (n, nc) = (mesh.num_vertices(), mesh.num_curve);
        let free = n - nc;
        let laplacian = self.laplacian.take().filter(|s| s.dim() == free);
        let propagation = self.propagation.take().filter(|s| s.dim() == free);
        let Propagation { v_star, n_star, system } = propagate(mesh, ops, t, propagation)?;
        // The first solve frees the propagation's factor before factorising its own (peak
        // memory as one factor); later solves keep both.
        self.propagation = if laplacian.is_some() { system } else { None };
        if n == nc {
            return Ok(MethodResult { positions: v_star, propagated_normals: Some(n_star), guide_curvature: None });
        }
        let (h, u_curve) = timed(&mut t.operators, || boundary_values(mesh, ops, &v_star, &n_star));
        let laplacian = match laplacian {
            Some(s) => s,
            None => {
                let k = timed(&mut t.operators, || ops.ls.restrict(nc, -1.0));
                timed(&mut t.factor, || {
                    Eliminated::factor(&k, nc, None, "method (4) system (−Ls on the free vertices)")
                })?
            }
        };
        let positions = timed(&mut t.solve, || mixed_solve(mesh, ops, &laplacian, &u_curve));
        self.laplacian = Some(laplacian);
        check_finite(&positions, "method (4)")?;
        Ok(MethodResult { positions, propagated_normals: Some(n_star), guide_curvature: Some(h) })
    }

    fn is_factored(&self) -> bool {
        self.propagation.is_some() || self.laplacian.is_some()
    }

    fn release(&mut self) {
        self.propagation = None;
        self.laplacian = None;
    }
}

/// Runs method (4) once on `mesh` with the operators `ops`.
pub fn method4(mesh: &Mesh, ops: &Operators, t: &mut SolveTimings) -> Result<MethodResult> {
    Method4::new().solve(mesh, ops, t)
}

/// The guide `H` (eq. 1 on `V*`, `N*`, areas `M`) and the prescribed `U = b₁` at the curve
/// vertices: `−2 H n` with the input normal `n`, the one-sided Laplacian of `V*` on open
/// borders (module docs).
fn boundary_values(mesh: &Mesh, ops: &Operators, v_star: &[DVec3], n_star: &[DVec3]) -> (Vec<f64>, Vec<DVec3>) {
    let (n, nc) = (mesh.num_vertices(), mesh.num_curve);
    let h = blended_mean_curvature(&mesh.faces, v_star, n_star, &ops.mass, &mesh.on_boundary);
    // One-sided Laplacian of V* (for open-border vertices).
    let mut lv = Mat::<f64>::zeros(n, 3);
    ops.ls.sym_mul_dense(known_rows(n, n, &[v_star]).as_ref(), lv.as_mut());
    let mut u_curve = vec![DVec3::ZERO; nc];
    for (c, u) in u_curve.iter_mut().enumerate() {
        *u = if mesh.on_boundary[c] {
            DVec3::new(lv[(c, 0)], lv[(c, 1)], lv[(c, 2)]) / ops.mass[c]
        } else {
            -2.0 * h[c] * mesh.curve_normals[c]
        };
    }
    (h, u_curve)
}

/// The two solves of the mixed form with the factorisation `laplacian` of `−(Ls)_ff`:
/// `−Ls_ff U_f = Ls_fc U_c`, then `−Ls_ff V_f = −M_f U_f + Ls_fc V_c`. Returns every position.
fn mixed_solve(mesh: &Mesh, ops: &Operators, laplacian: &Eliminated, u_curve: &[DVec3]) -> Vec<DVec3> {
    let (n, nc) = (mesh.num_vertices(), mesh.num_curve);
    // U: −Ls_ff U_f = Ls_fc U_c.
    let mut y = Mat::<f64>::zeros(n, 3);
    ops.ls.mul_dense(known_rows(n, nc, &[u_curve]).as_ref(), y.as_mut());
    let mut u = Mat::<f64>::zeros(n - nc, 3);
    for i in nc..n {
        for c in 0..3 {
            u[(i - nc, c)] = y[(i, c)];
        }
    }
    let u = laplacian.solve(u);
    // V: −Ls_ff V_f = −M_f U_f + Ls_fc V_c.
    ops.ls.mul_dense(known_rows(n, nc, &[&mesh.positions]).as_ref(), y.as_mut());
    let mut v = Mat::<f64>::zeros(n - nc, 3);
    for i in nc..n {
        for c in 0..3 {
            v[(i - nc, c)] = -ops.mass[i] * u[(i - nc, c)] + y[(i, c)];
        }
    }
    let v = laplacian.solve(v);
    let mut positions = mesh.positions.clone();
    scatter(&v, 0, nc, &mut positions);
    positions
}
