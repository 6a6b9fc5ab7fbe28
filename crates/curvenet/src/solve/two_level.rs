//! The fine level's systems solved without a factorisation of their own (issue 31): conjugate
//! gradients preconditioned by a two-level cycle whose coarse-grid solve is the coarse level's
//! own factorisation, kept from its last 3D iteration (`pipeline::levels`), and whose
//! prolongation is the transfer's location of each fine vertex in the coarse mesh
//! (`tessellate::transfer`).
//!
//! The default runs its 3D iterations on a coarse level at twice the spacing and then one
//! iteration on the fine level (docs/design.md §2.2): four inner steps, each a solve of the
//! normals' system and one of the fit's, `Q = Ls W Ls + μ M` on the free vertices with
//! `W = M⁻¹` or the fit's row weights. With a direct solver that iteration is one fine
//! factorisation — most of a large run's time and memory. Here each solve is [`pcg_until`]
//! with [`TwoLevel`] (damped Jacobi, `ω = 1 / (1.05 λ_max(D⁻¹Q))`, [`SMOOTHING`] steps before and
//! after the coarse correction), started from the last solution (the prior normals, the
//! current positions), stopped when an iteration moves no unknown by more than the caller's
//! step (the 3D iterations stop on vertex moves too) or at a relative residual of
//! [`RESIDUAL`]; after [`MAX_ITERATIONS`] without converging the caller factorises instead.
//! Iteration counts against mesh size: docs/performance.md ("Conjugate gradients on the fine
//! level").

use super::pcg::{jacobi_spectral_radius, pcg_until, CgReport, Energy, LinearOperator, TwoLevel, Until};
use super::sparse::Csc;
use super::system::Eliminated;
use faer::Mat;
use glam::DVec3;

/// A fine vertex located on the coarse mesh: the vertex, the coarse triangle (its corners)
/// and the barycentric coordinates there (non-negative, summing to 1), as the transfer
/// between the default's levels finds them (`tessellate::transfer`).
pub type Location = (u32, [u32; 3], [f64; 3]);

/// Smoothing steps before and after the coarse correction. In a default run's fine level at
/// 1M vertices (sphere), V(1,1) took 3, 8, 2, 4, 1, 2, 1, 2 iterations for its eight solves
/// (7.6 s), V(2,2) fewer at two more products each (10.3 s), the additive cycle (no
/// smoothing) 5, 12, 1, 3, 1, 3, 1, 3 (7.9 s) but stopped farther from the direct solution
/// (7e-7 against 1e-8 of the diagonal).
pub const SMOOTHING: usize = 1;

/// The relative residual that stops a solve whatever its steps.
pub const RESIDUAL: f64 = 1e-10;

/// Iterations after which a solve counts as not converged (the caller falls back to a
/// factorisation).
pub const MAX_ITERATIONS: usize = 60;

/// Power-method steps for `λ_max(D⁻¹Q)` (one column each; the damping takes a 5 % margin).
const POWER_STEPS: usize = 12;

/// The coarse level a fine level's systems are preconditioned with: the prolongation from the
/// coarse free vertices to the fine ones and the coarse systems' factorisations (the normals'
/// and, with open borders or the uniform weighting, the fit's).
pub struct Coarse {
    /// `P`, fine free vertices × coarse free vertices: each fine vertex's barycentric
    /// coordinates in its coarse triangle, the corners on curves left out (zero there).
    pub p: Csc,
    /// `Pᵀ`.
    pub pt: Csc,
    /// The coarse normals' system (`Ls M⁻¹ Ls + μ M` on the coarse free vertices).
    pub normals: Eliminated,
    /// The coarse fit's system when it is not the normals'.
    pub fit: Option<Eliminated>,
    /// The coarse level's propagated normals at the fine free vertices (interpolated by `P`
    /// with the curve corners, normalised; zero where a vertex was not located): the start of
    /// the fine level's first normals' solve, closer than the fine surface's own normals.
    pub normals_start: Option<Mat<f64>>,
}

impl std::fmt::Debug for Coarse {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "Coarse({} × {} prolongation)", self.p.nrows, self.p.ncols)
    }
}

impl Coarse {
    /// From the transfer's `locations` of the fine free vertices (fine: `fine_first..fine_n`,
    /// the first rows the curve vertices; coarse likewise) and the coarse systems, which must
    /// have the coarse free vertices as their unknowns (`None` otherwise), and the coarse
    /// level's propagated normals at all its vertices.
    pub fn new(
        locations: &[Location],
        (fine_first, fine_n): (usize, usize),
        (coarse_first, coarse_n): (usize, usize),
        (normals, fit): (Eliminated, Option<Eliminated>),
        coarse_normals: Option<&[DVec3]>,
    ) -> Option<Self> {
        let free = coarse_n.checked_sub(coarse_first)?;
        let fits = |e: &Eliminated| e.first() == coarse_first && e.dim() == free;
        if !fits(&normals) || !fit.as_ref().is_none_or(fits) {
            return None;
        }
        let mut t = Vec::with_capacity(3 * locations.len());
        let coarse_normals = coarse_normals.filter(|n| n.len() == coarse_n);
        let mut normals_start = coarse_normals.map(|_| Mat::<f64>::zeros(fine_n.saturating_sub(fine_first), 3));
        let fine_free = fine_n.checked_sub(fine_first)?;
        for &(v, corners, w) in locations {
            let row = (v as usize).checked_sub(fine_first).filter(|&r| r < fine_free)?;
            if let (Some(start), Some(nc)) = (normals_start.as_mut(), coarse_normals) {
                let mut n = DVec3::ZERO;
                for (&c, &x) in corners.iter().zip(&w) {
                    n += x * *nc.get(c as usize)?;
                }
                let n = n.normalize_or_zero();
                for c in 0..3 {
                    start[(row, c)] = n[c];
                }
            }
            for (&c, &x) in corners.iter().zip(&w) {
                let c = c as usize;
                if c >= coarse_first && c < coarse_n && x != 0.0 {
                    t.push((row as u32, (c - coarse_first) as u32, x));
                }
            }
        }
        let pt = Csc::from_triplets(free, fine_free, t.iter().map(|&(i, j, v)| (j, i, v)).collect());
        let p = Csc::from_triplets(fine_free, free, t);
        Some(Coarse { p, pt, normals, fit, normals_start })
    }
}

/// One fine system `Q` solved by two-level preconditioned conjugate gradients.
pub struct FineSystem<'a> {
    energy: Energy<'a>,
    inv_diag: Vec<f64>,
    omega: f64,
    coarse: &'a Eliminated,
    p: &'a Csc,
    pt: &'a Csc,
}

impl<'a> FineSystem<'a> {
    /// `Q` = `energy` with `coarse` (its coarse counterpart, factorised) and the prolongation
    /// `p` (`pt` = `pᵀ`). `None` when the sizes do not match or `Q`'s diagonal is not positive.
    pub fn new(energy: Energy<'a>, coarse: &'a Eliminated, p: &'a Csc, pt: &'a Csc) -> Option<Self> {
        if p.nrows != energy.dim() || p.ncols != coarse.dim() {
            return None;
        }
        let diag = energy.diag();
        if !diag.iter().all(|d| *d > 0.0 && d.is_finite()) {
            return None;
        }
        let inv_diag: Vec<f64> = diag.iter().map(|d| 1.0 / d).collect();
        let lambda = jacobi_spectral_radius(&energy, &inv_diag, POWER_STEPS);
        if !(lambda > 0.0 && lambda.is_finite()) {
            return None;
        }
        Some(FineSystem { energy, inv_diag, omega: 1.0 / (1.05 * lambda), coarse, p, pt })
    }

    /// Solves `Q X = rhs` from `start` (the unknown rows), stopping when an iteration moves no
    /// entry by more than `step` (no row along its row of `along`, when given). The solution
    /// and what conjugate gradients did (not converged: the caller falls back to a
    /// factorisation).
    pub fn solve(&self, rhs: &Mat<f64>, start: Mat<f64>, step: f64, along: Option<&Mat<f64>>) -> (Mat<f64>, CgReport) {
        let m = TwoLevel {
            a: &self.energy,
            inv_diag: &self.inv_diag,
            omega: self.omega,
            smoothing: SMOOTHING,
            p: self.p,
            pt: self.pt,
            coarse: self.coarse,
        };
        let mut x = start;
        let until = Until { residual: RESIDUAL, step, along, max_iterations: MAX_ITERATIONS };
        let report = pcg_until(&self.energy, &m, rhs.as_ref(), x.as_mut(), until);
        (x, report)
    }
}

#[cfg(test)]
#[path = "tests/two_level.rs"]
mod tests;
