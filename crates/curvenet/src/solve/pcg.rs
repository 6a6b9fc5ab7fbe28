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
use rayon::prelude::*;
use std::sync::Mutex;

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
/// Both products run over rows in parallel, all columns of a row at once (one pass over `Ls`
/// per product), in scratch buffers kept between applications: allocating them afresh cost a
/// fifth of a solve in page faults (100k vertices).
pub struct Energy<'a> {
    /// `Ls`, `n × n`, both triangles stored.
    pub ls: &'a Csc,
    /// `W`, `n`.
    pub w: &'a [f64],
    /// The diagonal added on the unknown rows, `n` (the rows `..first` are not read).
    pub diagonal: &'a [f64],
    /// The first unknown row.
    pub first: usize,
    /// Row-major scratch: the unknowns, `W Ls x`, the result.
    scratch: Mutex<[Vec<f64>; 3]>,
}

impl<'a> Energy<'a> {
    /// `Q` from its parts (see the fields).
    pub fn new(ls: &'a Csc, w: &'a [f64], diagonal: &'a [f64], first: usize) -> Self {
        Energy { ls, w, diagonal, first, scratch: Mutex::new(Default::default()) }
    }

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

/// Rows per parallel task in [`Energy`]'s products.
const ROWS_PER_TASK: usize = 4096;

impl LinearOperator for Energy<'_> {
    fn dim(&self) -> usize {
        self.ls.ncols - self.first
    }

    fn apply(&self, x: MatRef<'_, f64>, mut y: MatMut<'_, f64>) {
        let (n, k, first) = (self.ls.ncols, x.ncols(), self.first);
        let mut guard = self.scratch.lock().unwrap_or_else(|e| e.into_inner());
        let [xr, t, out] = &mut *guard;
        xr.resize((n - first) * k, 0.0);
        t.resize(n * k, 0.0);
        out.resize((n - first) * k, 0.0);
        for c in 0..k {
            match x.col(c).try_as_col_major() {
                Some(col) => col.as_slice().iter().enumerate().for_each(|(i, v)| xr[i * k + c] = *v),
                None => (0..n - first).for_each(|i| xr[i * k + c] = x[(i, c)]),
            }
        }
        let (ls, w, diagonal) = (self.ls, self.w, self.diagonal);
        // t = W Ls x̂ (x̂: x on the unknown rows, zero on the known ones).
        t.par_chunks_mut(k).with_min_len(ROWS_PER_TASK).enumerate().for_each(|(i, ti)| {
            ti.fill(0.0);
            let (rows, vals) = ls.col(i);
            for (&j, &v) in rows.iter().zip(vals) {
                if let Some(j) = (j as usize).checked_sub(first) {
                    for (tc, xc) in ti.iter_mut().zip(&xr[j * k..(j + 1) * k]) {
                        *tc += v * xc;
                    }
                }
            }
            for tc in ti.iter_mut() {
                *tc *= w[i];
            }
        });
        // y = (Ls t)_u + p_u x.
        let t = &*t;
        out.par_chunks_mut(k).with_min_len(ROWS_PER_TASK).enumerate().for_each(|(r, oi)| {
            let i = r + first;
            for (oc, xc) in oi.iter_mut().zip(&xr[r * k..(r + 1) * k]) {
                *oc = diagonal[i] * xc;
            }
            let (rows, vals) = ls.col(i);
            for (&j, &v) in rows.iter().zip(vals) {
                let j = j as usize;
                for (oc, tc) in oi.iter_mut().zip(&t[j * k..(j + 1) * k]) {
                    *oc += v * tc;
                }
            }
        });
        for c in 0..k {
            match y.as_mut().col_mut(c).try_as_col_major_mut() {
                Some(col) => col.as_slice_mut().iter_mut().enumerate().for_each(|(i, v)| *v = out[i * k + c]),
                None => (0..n - first).for_each(|i| y[(i, c)] = out[i * k + c]),
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
    pub inv_diag: &'a [f64],
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
    /// `z += ω D⁻¹ (r − A z)` (`az`: scratch).
    fn smooth(&self, r: &Mat<f64>, z: &mut Mat<f64>, az: &mut Mat<f64>) {
        self.a.apply(z.as_ref(), az.as_mut());
        for c in 0..r.ncols() {
            let (rc, azc) = (r.col_as_slice(c), az.col_as_slice(c));
            let inv = self.inv_diag;
            par_rows(z.col_as_slice_mut(c), |i, zi| *zi += self.omega * inv[i] * (rc[i] - azc[i]));
        }
    }
}

impl Preconditioner for TwoLevel<'_> {
    fn apply(&self, r: MatRef<'_, f64>, mut out: MatMut<'_, f64>) {
        let (n, k) = (r.nrows(), r.ncols());
        let r = owned(r);
        let inv = self.inv_diag;
        // z = ω D⁻¹ r: the additive cycle's smoothing, or the first step from z = 0.
        let mut z = Mat::<f64>::zeros(n, k);
        for c in 0..k {
            let rc = r.col_as_slice(c);
            par_rows(z.col_as_slice_mut(c), |i, zi| *zi = self.omega * inv[i] * rc[i]);
        }
        let mut az = Mat::<f64>::zeros(n, k);
        for _ in 1..self.smoothing {
            self.smooth(&r, &mut z, &mut az);
        }
        // Coarse correction of the residual r − A z (of r itself in the additive cycle).
        let res = if self.smoothing > 0 {
            self.a.apply(z.as_ref(), az.as_mut());
            for c in 0..k {
                let rc = r.col_as_slice(c);
                par_rows(az.col_as_slice_mut(c), |i, a| *a = rc[i] - *a);
            }
            &az
        } else {
            &r
        };
        let mut rc = Mat::<f64>::zeros(self.pt.nrows, k);
        self.p.tr_mul_dense(res, &mut rc);
        let ec = self.coarse.solve(rc);
        let mut e = Mat::<f64>::zeros(n, k);
        self.pt.tr_mul_dense(&ec, &mut e);
        for c in 0..k {
            let ecol = e.col_as_slice(c);
            par_rows(z.col_as_slice_mut(c), |i, zi| *zi += ecol[i]);
        }
        for _ in 0..self.smoothing {
            self.smooth(&r, &mut z, &mut az);
        }
        out.copy_from(&z);
    }
}

/// Rows per parallel task in the vector updates.
const VECTOR_ROWS_PER_TASK: usize = 1 << 15;

/// `f(i, &mut v[i])` for every row, in parallel for long vectors (each row on its own:
/// deterministic).
fn par_rows(v: &mut [f64], f: impl Fn(usize, &mut f64) + Sync + Send) {
    v.par_iter_mut().with_min_len(VECTOR_ROWS_PER_TASK).enumerate().for_each(|(i, x)| f(i, x));
}

/// `Σ a_i b_i` in fixed chunks summed in order: parallel and the same in every run.
fn dot(a: &[f64], b: &[f64]) -> f64 {
    let parts: Vec<f64> = a
        .par_chunks(VECTOR_ROWS_PER_TASK)
        .zip(b.par_chunks(VECTOR_ROWS_PER_TASK))
        .map(|(x, y)| x.iter().zip(y).map(|(p, q)| p * q).sum::<f64>())
        .collect();
    parts.iter().sum()
}

/// An owned (column-major) copy.
fn owned(m: MatRef<'_, f64>) -> Mat<f64> {
    let mut o = Mat::<f64>::zeros(m.nrows(), m.ncols());
    o.copy_from(m);
    o
}

/// What [`pcg`] did.
#[derive(Clone, Debug, Default)]
pub struct CgReport {
    /// Iterations run.
    pub iterations: usize,
    /// The largest relative residual `‖b − A x‖ / ‖b‖` over the columns, after each iteration.
    pub residuals: Vec<f64>,
    /// Whether every column reached the residual tolerance, or an iteration's step fell
    /// below [`Until::step`].
    pub converged: bool,
}

/// Solves `A X = B` by preconditioned conjugate gradients from the start `x` (overwritten by
/// the solution), each column until `‖b − A x‖ ≤ tol ‖b‖`, at most `max_iterations`.
pub fn pcg(
    a: &dyn LinearOperator,
    m: &dyn Preconditioner,
    b: MatRef<'_, f64>,
    x: MatMut<'_, f64>,
    tol: f64,
    max_iterations: usize,
) -> CgReport {
    pcg_until(a, m, b, x, Until { residual: tol, step: 0.0, along: None, max_iterations })
}

/// When [`pcg_until`] stops.
#[derive(Clone, Copy, Debug)]
pub struct Until<'a> {
    /// Every column's relative residual `‖b − A x‖ / ‖b‖` at most this.
    pub residual: f64,
    /// Or the last iteration moved no entry of `x` by more than this (the update's size: the
    /// 3D iterations stop on vertex moves, not on residuals; docs/performance.md).
    pub step: f64,
    /// Measure the step of a row along this row (`Σ_c step_c d_c`, e.g. the vertex normals:
    /// the 3D iterations keep only the normal part of the fit's move) rather than its largest
    /// entry.
    pub along: Option<&'a Mat<f64>>,
    /// Or this many iterations, not converged.
    pub max_iterations: usize,
}

/// [`pcg`] with the stops of `until`.
pub fn pcg_until(
    a: &dyn LinearOperator,
    m: &dyn Preconditioner,
    b: MatRef<'_, f64>,
    mut x_out: MatMut<'_, f64>,
    until: Until<'_>,
) -> CgReport {
    let (n, k) = (b.nrows(), b.ncols());
    let b = owned(b);
    let mut x = owned(x_out.as_ref());
    let b_norm: Vec<f64> =
        (0..k).map(|c| dot(b.col_as_slice(c), b.col_as_slice(c)).sqrt().max(f64::MIN_POSITIVE)).collect();
    let mut r = Mat::<f64>::zeros(n, k);
    a.apply(x.as_ref(), r.as_mut());
    for c in 0..k {
        let bc = b.col_as_slice(c);
        par_rows(r.col_as_slice_mut(c), |i, ri| *ri = bc[i] - *ri);
    }
    let relative =
        |r: &Mat<f64>| (0..k).map(|c| dot(r.col_as_slice(c), r.col_as_slice(c)).sqrt() / b_norm[c]).fold(0.0, f64::max);
    let mut report = CgReport { converged: relative(&r) <= until.residual, ..Default::default() };
    if report.converged {
        return report;
    }
    let mut z = Mat::<f64>::zeros(n, k);
    m.apply(r.as_ref(), z.as_mut());
    let mut p = z.clone();
    let mut rz: Vec<f64> = (0..k).map(|c| dot(r.col_as_slice(c), z.col_as_slice(c))).collect();
    let mut q = Mat::<f64>::zeros(n, k);
    while report.iterations < until.max_iterations {
        a.apply(p.as_ref(), q.as_mut());
        let mut alphas = vec![0.0; k];
        for c in 0..k {
            let (pc, qc) = (p.col_as_slice(c), q.col_as_slice(c));
            let pq = dot(pc, qc);
            let alpha = if pq > 0.0 { rz[c] / pq } else { 0.0 };
            alphas[c] = alpha;
            par_rows(x.col_as_slice_mut(c), |i, xi| *xi += alpha * pc[i]);
            par_rows(r.col_as_slice_mut(c), |i, ri| *ri -= alpha * qc[i]);
        }
        let step = match until.along.filter(|d| d.nrows() == n && d.ncols() == k) {
            Some(d) => {
                (0..n).map(|i| (0..k).map(|c| alphas[c] * p[(i, c)] * d[(i, c)]).sum::<f64>().abs()).fold(0.0, f64::max)
            }
            None => (0..k)
                .map(|c| alphas[c].abs() * p.col_as_slice(c).iter().fold(0.0f64, |m, v| m.max(v.abs())))
                .fold(0.0, f64::max),
        };
        report.iterations += 1;
        let res = relative(&r);
        report.residuals.push(res);
        if res <= until.residual || (until.step > 0.0 && step <= until.step) {
            report.converged = true;
            break;
        }
        m.apply(r.as_ref(), z.as_mut());
        for c in 0..k {
            let next = dot(r.col_as_slice(c), z.col_as_slice(c));
            let beta = if rz[c] > 0.0 { next / rz[c] } else { 0.0 };
            rz[c] = next;
            let zc = z.col_as_slice(c);
            par_rows(p.col_as_slice_mut(c), |i, pi| *pi = zc[i] + beta * *pi);
        }
    }
    x_out.copy_from(&x);
    report
}

#[cfg(test)]
#[path = "tests/pcg.rs"]
mod tests;
