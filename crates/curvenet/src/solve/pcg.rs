//! Preconditioned conjugate gradients for the symmetric positive definite systems of the
//! energies (issue 31: the fine level without a factorisation of its own).
//!
//! [`pcg`] solves `A X = B` for a few right-hand sides at once (the three coordinates, or the
//! three components of the normals): each column runs its own conjugate-gradient recurrence
//! (its own step lengths), the products with `A` and the preconditioner are applied to all
//! columns together. `A` is any [`LinearOperator`] — [`Energy`] applies `Ls M⁻¹ Ls + μ M` on the
//! unknown rows from `Ls` and the areas without assembling it. The preconditioners:
//! [`Jacobi`] (`diag(A)⁻¹`) and [`TwoLevel`], a two-level cycle: a smoother on the fine system,
//! then a coarse-grid correction through a prolongation `P` with a factorised coarse system
//! (the coarse level the default already solves), then the smoother again — symmetric, so it
//! keeps CG's recurrence valid.
//!
//! Measured iteration counts against mesh size: docs/performance.md ("Conjugate gradients on
//! the fine level"), `cargo bench -p curvenet --bench pcg`.

use super::sparse::Csc;
use super::system::Eliminated;
use faer::{Mat, MatMut, MatRef};

/// A symmetric positive definite operator `y = A x` on `dim × k` blocks.
pub trait LinearOperator: Sync {
    /// Number of unknowns.
    fn dim(&self) -> usize;
    /// `y = A x`.
    fn apply(&self, x: MatRef<'_, f64>, y: MatMut<'_, f64>);
}

/// A symmetric positive definite approximation of `A⁻¹`: `z = M⁻¹ r`.
pub trait Preconditioner: Sync {
    /// `z = M⁻¹ r`.
    fn apply(&self, r: MatRef<'_, f64>, z: MatMut<'_, f64>);
}

impl LinearOperator for Csc {
    fn dim(&self) -> usize {
        self.nrows
    }

    /// A full symmetric matrix (both triangles stored).
    fn apply(&self, x: MatRef<'_, f64>, y: MatMut<'_, f64>) {
        self.sym_mul_dense(x, y);
    }
}

/// `Q = (Ls W Ls)_uu + diag(p)_uu` on the unknown rows `first..`, applied as two products with
/// `Ls` (the matrix of the 3D iterations, `W = M⁻¹`, `p = μ M`; [`crate::methods::iterated`]).
pub struct Energy<'a> {
    /// `Ls`, `n × n`, both triangles stored.
    pub ls: &'a Csc,
    /// `W`, `n`.
    pub w: &'a [f64],
    /// The diagonal added on the unknown rows, `n` (the rows `..first` are not read).
    pub diagonal: &'a [f64],
    /// The first unknown row.
    pub first: usize,
}

impl Energy<'_> {
    /// The diagonal of `Q` on the unknown rows: `Σ_k Ls_kj² W_k + p_j`.
    pub fn diag(&self) -> Vec<f64> {
        (self.first..self.ls.ncols)
            .map(|j| {
                let (rows, vals) = self.ls.col(j);
                rows.iter().zip(vals).map(|(&k, &v)| v * v * self.w[k as usize]).sum::<f64>() + self.diagonal[j]
            })
            .collect()
    }
}

impl LinearOperator for Energy<'_> {
    fn dim(&self) -> usize {
        self.ls.ncols - self.first
    }

    fn apply(&self, x: MatRef<'_, f64>, mut y: MatMut<'_, f64>) {
        let (n, k, first) = (self.ls.ncols, x.ncols(), self.first);
        let mut full = Mat::<f64>::zeros(n, k);
        for c in 0..k {
            for i in first..n {
                full[(i, c)] = x[(i - first, c)];
            }
        }
        let mut t = Mat::<f64>::zeros(n, k);
        self.ls.sym_mul_dense(full.as_ref(), t.as_mut());
        for c in 0..k {
            for i in 0..n {
                t[(i, c)] *= self.w[i];
            }
        }
        self.ls.sym_mul_dense(t.as_ref(), full.as_mut());
        for c in 0..k {
            for i in first..n {
                y[(i - first, c)] = full[(i, c)] + self.diagonal[i] * x[(i - first, c)];
            }
        }
    }
}

/// No preconditioner (plain conjugate gradients).
pub struct Identity;

impl Preconditioner for Identity {
    fn apply(&self, r: MatRef<'_, f64>, mut z: MatMut<'_, f64>) {
        z.copy_from(r);
    }
}

/// `z = diag(A)⁻¹ r`.
pub struct Jacobi {
    /// `1 / A_ii`.
    pub inv_diag: Vec<f64>,
}

impl Jacobi {
    /// From the diagonal of `A`.
    pub fn new(diag: &[f64]) -> Self {
        Jacobi { inv_diag: diag.iter().map(|d| 1.0 / d).collect() }
    }
}

impl Preconditioner for Jacobi {
    fn apply(&self, r: MatRef<'_, f64>, mut z: MatMut<'_, f64>) {
        for c in 0..r.ncols() {
            for i in 0..r.nrows() {
                z[(i, c)] = self.inv_diag[i] * r[(i, c)];
            }
        }
    }
}

/// The two-level cycle: `smoothing` damped-Jacobi steps `z += ω D⁻¹ (r − A z)`, the coarse
/// correction `z += P A_c⁻¹ Pᵀ (r − A z)`, `smoothing` steps again. With `smoothing` 0 it is
/// the additive `z = ω D⁻¹ r + P A_c⁻¹ Pᵀ r`.
pub struct TwoLevel<'a> {
    /// The fine operator.
    pub a: &'a dyn LinearOperator,
    /// `1 / A_ii`.
    pub inv_diag: Vec<f64>,
    /// The damping `ω`.
    pub omega: f64,
    /// Smoothing steps before and after the coarse correction.
    pub smoothing: usize,
    /// `P`, fine unknowns × coarse unknowns.
    pub p: &'a Csc,
    /// `Pᵀ`.
    pub pt: &'a Csc,
    /// The factorised coarse system on the coarse unknowns.
    pub coarse: &'a Eliminated,
}

/// An estimate of the largest eigenvalue of `D⁻¹ A` (`inv_diag` = `1 / A_ii`): `iterations`
/// steps of the power method from a fixed start, the last Rayleigh quotient. The damped
/// Jacobi smoother `z += ω D⁻¹ (r − A z)` converges for `ω < 2 / λ_max`; [`TwoLevel`] takes
/// `ω = 1 / λ_max` (a fixed `ω = 0.5` diverged on the torus's system, whose `λ_max` is above 4).
pub fn jacobi_spectral_radius(a: &dyn LinearOperator, inv_diag: &[f64], iterations: usize) -> f64 {
    let n = a.dim();
    let mut x = Mat::from_fn(n, 1, |i, _| 1.0 + ((i * 7919) % 101) as f64 / 101.0);
    let mut y = Mat::<f64>::zeros(n, 1);
    let mut lambda = 0.0;
    for _ in 0..iterations.max(1) {
        let norm = (0..n).map(|i| x[(i, 0)] * x[(i, 0)]).sum::<f64>().sqrt();
        if !(norm > 0.0) {
            break;
        }
        for i in 0..n {
            x[(i, 0)] /= norm;
        }
        a.apply(x.as_ref(), y.as_mut());
        for i in 0..n {
            y[(i, 0)] *= inv_diag[i];
        }
        lambda = (0..n).map(|i| x[(i, 0)] * y[(i, 0)]).sum::<f64>();
        std::mem::swap(&mut x, &mut y);
    }
    lambda
}

impl TwoLevel<'_> {
    /// `z += ω D⁻¹ (r − A z)`.
    fn smooth(&self, r: MatRef<'_, f64>, z: &mut Mat<f64>, az: &mut Mat<f64>) {
        self.a.apply(z.as_ref(), az.as_mut());
        for c in 0..r.ncols() {
            for i in 0..r.nrows() {
                z[(i, c)] += self.omega * self.inv_diag[i] * (r[(i, c)] - az[(i, c)]);
            }
        }
    }
}

impl Preconditioner for TwoLevel<'_> {
    fn apply(&self, r: MatRef<'_, f64>, mut out: MatMut<'_, f64>) {
        let (n, k) = (r.nrows(), r.ncols());
        let mut z = Mat::<f64>::zeros(n, k);
        let mut az = Mat::<f64>::zeros(n, k);
        for _ in 0..self.smoothing {
            self.smooth(r, &mut z, &mut az);
        }
        // Coarse correction of the residual r − A z.
        let mut res = Mat::<f64>::zeros(n, k);
        res.copy_from(r);
        if self.smoothing > 0 {
            self.a.apply(z.as_ref(), az.as_mut());
            for c in 0..k {
                for i in 0..n {
                    res[(i, c)] -= az[(i, c)];
                }
            }
        }
        let mut rc = Mat::<f64>::zeros(self.pt.nrows, k);
        self.pt.mul_dense(res.as_ref(), rc.as_mut());
        let ec = self.coarse.solve(rc);
        let mut e = Mat::<f64>::zeros(n, k);
        self.p.mul_dense(ec.as_ref(), e.as_mut());
        for c in 0..k {
            for i in 0..n {
                z[(i, c)] += e[(i, c)];
                if self.smoothing == 0 {
                    z[(i, c)] += self.omega * self.inv_diag[i] * r[(i, c)];
                }
            }
        }
        if self.smoothing > 0 {
            for _ in 0..self.smoothing {
                self.smooth(r, &mut z, &mut az);
            }
        }
        out.copy_from(&z);
    }
}

/// What [`pcg`] did.
#[derive(Clone, Debug, Default)]
pub struct CgReport {
    /// Iterations run.
    pub iterations: usize,
    /// The largest relative residual `‖b − A x‖ / ‖b‖` over the columns, after each iteration.
    pub residuals: Vec<f64>,
    /// Whether every column reached the tolerance.
    pub converged: bool,
}

/// Solves `A X = B` by preconditioned conjugate gradients from the start `x` (overwritten by
/// the solution), each column until `‖b − A x‖ ≤ tol ‖b‖`, at most `max_iterations`.
pub fn pcg(
    a: &dyn LinearOperator,
    m: &dyn Preconditioner,
    b: MatRef<'_, f64>,
    mut x: MatMut<'_, f64>,
    tol: f64,
    max_iterations: usize,
) -> CgReport {
    let (n, k) = (b.nrows(), b.ncols());
    let norm = |v: MatRef<'_, f64>, c: usize| (0..n).map(|i| v[(i, c)] * v[(i, c)]).sum::<f64>().sqrt();
    let dot = |u: &Mat<f64>, v: &Mat<f64>, c: usize| (0..n).map(|i| u[(i, c)] * v[(i, c)]).sum::<f64>();
    let b_norm: Vec<f64> = (0..k).map(|c| norm(b, c).max(f64::MIN_POSITIVE)).collect();
    let mut r = Mat::<f64>::zeros(n, k);
    a.apply(x.as_ref(), r.as_mut());
    for c in 0..k {
        for i in 0..n {
            r[(i, c)] = b[(i, c)] - r[(i, c)];
        }
    }
    let relative = |r: &Mat<f64>| (0..k).map(|c| norm(r.as_ref(), c) / b_norm[c]).fold(0.0, f64::max);
    let mut report = CgReport { converged: relative(&r) <= tol, ..Default::default() };
    if report.converged {
        return report;
    }
    let mut z = Mat::<f64>::zeros(n, k);
    m.apply(r.as_ref(), z.as_mut());
    let mut p = z.clone();
    let mut rz: Vec<f64> = (0..k).map(|c| dot(&r, &z, c)).collect();
    let mut q = Mat::<f64>::zeros(n, k);
    while report.iterations < max_iterations {
        a.apply(p.as_ref(), q.as_mut());
        for c in 0..k {
            let pq = dot(&p, &q, c);
            let alpha = if pq > 0.0 { rz[c] / pq } else { 0.0 };
            for i in 0..n {
                x[(i, c)] += alpha * p[(i, c)];
                r[(i, c)] -= alpha * q[(i, c)];
            }
        }
        report.iterations += 1;
        let res = relative(&r);
        report.residuals.push(res);
        if res <= tol {
            report.converged = true;
            break;
        }
        m.apply(r.as_ref(), z.as_mut());
        for c in 0..k {
            let next = dot(&r, &z, c);
            let beta = if rz[c] > 0.0 { next / rz[c] } else { 0.0 };
            rz[c] = next;
            for i in 0..n {
                p[(i, c)] = z[(i, c)] + beta * p[(i, c)];
            }
        }
    }
    report
}

#[cfg(test)]
#[path = "tests/pcg.rs"]
mod tests;
