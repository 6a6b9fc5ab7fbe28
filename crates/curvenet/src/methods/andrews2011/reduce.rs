//! The ghost vertex basis of \[A11\] §6.2: every free vertex as an affine function of the ghost
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

/// `K` and `W` of \[A11\] eq. 4 for one system and fixed constraint positions.
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
            return Err(Error::usage(format!(
                "the ghost basis would hold {nf} × {ng} entries (limit {MAX_BASIS_ENTRIES}); use a coarser mesh"
            )));
        }
        // The dense basis (8 bytes per entry) and a block being solved: refused before it is
        // allocated when the memory is not there (an allocation failure would abort).
        let need = 8.0 * nf as f64 * (ng as f64 + 256.0) + 100e6;
        if let Some(have) = crate::solve::memory::available_memory(None).filter(|&have| need > have) {
            return Err(Error::memory(format!(
                "the ghost basis ({nf} free vertices × {ng} ghosts) would take about {:.2} GB, more than the memory \
                 available ({:.2} GB); use a coarser mesh, fewer feature curves, or leave the optimisation out",
                need / 1e9,
                have / 1e9
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

    /// Free vertex positions `K + W G` for ghost positions `ghosts` (\[A11\] eq. 4), `#free × 3`.
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

/// Timings of [`bench()`]: a fresh factor-and-solve against re-solves through the ghost basis.
#[derive(Clone, Debug, Default, serde::Serialize)]
pub struct ResolveBench {
    /// Free vertices of the system.
    pub unknowns: usize,
    /// Ghost vertices.
    pub ghosts: usize,
    /// Best of `reps` fresh LU factorisations and solves.
    pub factor_and_solve: f64,
    /// Building the basis (one solve per ghost, three for `K`).
    pub basis: f64,
    /// `K + W G` for all ghosts moved (best of `reps`).
    pub full_update: f64,
    /// `x += W[:, J] ΔG` for the ghosts of the `moved` constraint vertices (best of `reps`).
    pub partial_update: f64,
    /// Ghosts moved in the partial update.
    pub partial_ghosts: usize,
    /// Largest difference between the basis and a direct solve for the moved ghosts.
    pub max_difference: f64,
}

/// Times a fresh factor-and-solve of `system` against the ghost basis re-solves (\[A11\] §6.2):
/// every ghost moved by a pseudo-random offset of `scale`, and the ghosts of the first
/// `moved_vertices` Cauchy vertices only.
pub fn bench(
    system: &System,
    positions: &[DVec3],
    ghosts: &[DVec3],
    scale: f64,
    moved_vertices: usize,
    reps: usize,
) -> Result<ResolveBench> {
    use crate::solve::timing::Instant;
    // Fresh factor-and-solve, timed `reps` times (at least once); the last factorisation is
    // kept for the basis.
    let fresh = |best: &mut f64| -> Result<_> {
        let t = Instant::now();
        let fac = system.factor()?;
        let mut b = system.rhs(positions, ghosts);
        fac.solve_in_place(&mut b);
        *best = best.min(t.elapsed().as_secs_f64());
        Ok(fac)
    };
    let mut best = f64::INFINITY;
    let mut f = fresh(&mut best)?;
    for _ in 1..reps {
        f = fresh(&mut best)?;
    }
    let t = Instant::now();
    let basis = GhostBasis::new(system, &f, positions)?;
    let basis_time = t.elapsed().as_secs_f64();
    let mut rng = crate::network::Rng::new(7);
    let moved: Vec<DVec3> = ghosts.iter().map(|g| *g + scale * rng.gaussian3()).collect();
    let mut full = f64::INFINITY;
    let mut x = Mat::<f64>::zeros(0, 0);
    for _ in 0..reps {
        let t = Instant::now();
        x = basis.evaluate(&moved);
        full = full.min(t.elapsed().as_secs_f64());
    }
    let mut direct = system.rhs(positions, &moved);
    f.solve_in_place(&mut direct);
    let mut diff: f64 = 0.0;
    for r in 0..x.nrows() {
        for c in 0..3 {
            diff = diff.max((x[(r, c)] - direct[(r, c)]).abs());
        }
    }
    // Partial: the ghosts of the first few Cauchy vertices.
    let mut vertices: Vec<u32> = system.ghosts.iter().map(|g| g.vertex).collect();
    vertices.dedup();
    vertices.truncate(moved_vertices);
    let ids: Vec<u32> =
        (0..system.ghosts.len() as u32).filter(|&j| vertices.contains(&system.ghosts[j as usize].vertex)).collect();
    let delta: Vec<DVec3> = ids.iter().map(|&j| moved[j as usize] - ghosts[j as usize]).collect();
    let base = basis.evaluate(ghosts);
    let mut partial = f64::INFINITY;
    for _ in 0..reps {
        let mut y = base.clone();
        let t = Instant::now();
        basis.update(&mut y, &ids, &delta);
        partial = partial.min(t.elapsed().as_secs_f64());
    }
    Ok(ResolveBench {
        unknowns: system.num_free(),
        ghosts: system.ghosts.len(),
        factor_and_solve: best,
        basis: basis_time,
        full_update: full,
        partial_update: partial,
        partial_ghosts: ids.len(),
        max_difference: diff,
    })
}
