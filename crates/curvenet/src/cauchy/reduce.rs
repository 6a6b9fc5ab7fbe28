//! The ghost vertex basis of [A11] §6.2: every free vertex as an affine function of the ghost
//! vertices, `vᵢ = kᵢ + Σ_j w_ij g_j` (eq. 4), from the split right-hand side
//! `bᵢ = lᵢ + Σ_j m_ij g_j` (eq. 5): `A W = M` (one solve per ghost vertex) and `A K = L` (three
//! solves). Moving ghost vertices then updates the surface by a dense product, without
//! re-factorising or solving — the interactive edit and the least-squares fit of [`super`] use it.
//!
//! Memory is `#free × #ghosts` doubles: meant for the moderate meshes of editing and fitting.

use super::system::{Factored, System};
use crate::error::{Error, Result};
use crate::geom::DVec3;
use faer::Mat;

/// `K` and `W` of [A11] eq. 4 for one system and fixed constraint positions.
pub struct GhostBasis {
    /// `K`, `#free × 3`.
    pub k: Mat<f64>,
    /// `W`, `#free × #ghosts`.
    pub w: Mat<f64>,
}

/// Largest `#free × #ghosts` the basis may allocate (8 GB of doubles).
pub const MAX_BASIS_ENTRIES: usize = 1 << 30;

impl GhostBasis {
    /// Solves `A K = L` and `A W = M` with the factorisation `f` of `system`'s matrix.
    pub fn new(system: &System, f: &Factored, positions: &[DVec3]) -> Result<Self> {
        let (nf, ng) = (system.num_free(), system.ghosts.len());
        if nf.saturating_mul(ng) > MAX_BASIS_ENTRIES {
            return Err(Error::Usage(format!(
                "the ghost basis would hold {nf} × {ng} entries (limit {MAX_BASIS_ENTRIES}); use a coarser mesh"
            )));
        }
        let zero = vec![DVec3::ZERO; ng];
        let mut k = system.rhs(positions, &zero);
        f.solve_in_place(&mut k);
        let mut w = Mat::<f64>::zeros(nf, ng);
        for (r, terms) in system.ghost_terms.iter().enumerate() {
            for &(g, c) in terms {
                w[(r, g as usize)] += c;
            }
        }
        // Solve in column blocks (the LU's triangular solves are multi-RHS).
        const BLOCK: usize = 256;
        let mut start = 0;
        while start < ng {
            let end = (start + BLOCK).min(ng);
            let mut block = w.subcols(start, end - start).to_owned();
            f.solve_in_place(&mut block);
            w.subcols_mut(start, end - start).copy_from(&block);
            start = end;
        }
        Ok(GhostBasis { k, w })
    }

    /// Free vertex positions `K + W G` for ghost positions `ghosts` ([A11] eq. 4), `#free × 3`.
    pub fn evaluate(&self, ghosts: &[DVec3]) -> Mat<f64> {
        let ng = ghosts.len();
        let g = Mat::<f64>::from_fn(ng, 3, |i, c| ghosts[i][c]);
        &self.k + &self.w * &g
    }

    /// Updates free positions `x` (`#free × 3`) for ghosts `moved` displaced by `delta`:
    /// `x += W[:, moved] Δ` — cost proportional to the number of moved ghosts.
    pub fn update(&self, x: &mut Mat<f64>, moved: &[u32], delta: &[DVec3]) {
        for (&j, d) in moved.iter().zip(delta) {
            let col = self.w.col(j as usize);
            for i in 0..x.nrows() {
                let wij = col[i];
                x[(i, 0)] += wij * d.x;
                x[(i, 1)] += wij * d.y;
                x[(i, 2)] += wij * d.z;
            }
        }
    }
}
