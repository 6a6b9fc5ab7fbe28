//! The factor-once object of every method: a linear system on the unknown rows of `X` with the
//! known rows eliminated, in the spirit of libigl's `min_quad_with_fixed` and of faer's split
//! of symbolic and numeric factorisation.
//!
//! Every surfacing energy is a quadratic form in the vertex positions (or normals) `X`, `n × k`,
//! whose rows `..first` are known (the curve vertices under hard constraints; none under soft
//! ones) and whose rows `first..` are unknown. Writing `Q` for its matrix and `X̃` for `X` with
//! the unknown rows zeroed, the minimiser solves
//!
//! `Q_uu X_u = B_u − (Q X̃)_u`,
//!
//! so `Q_uu` is factorised once ([`Eliminated::factor`]) — its symbolic analysis kept for a
//! matrix with the same pattern and new values ([`Eliminated::refactor`]) — and every new set of
//! known values or targets costs a right-hand side and triangular solves
//! ([`Eliminated::solve`]).
//!
//! The energies of normal-control (\[CG\] eq. 1–3), the polyharmonic baselines and the short
//! paper are weighted least squares in the cotangent Laplacian, `Σ_v w_v ‖(Ls X)_v − T_v‖²`
//! ([`LeastSquares`]): `Q = Ls W Ls` and `B − Q X̃ = Ls W (T − Ls X̃)`, computed as two sparse
//! products without forming the coupling block `Q_uk`.

use super::cholesky::Cholesky;
use super::sparse::{product_lower, Csc};
use super::Factorization;
use crate::error::Result;
use faer::Mat;

/// The weighted least-squares energy `E(X) = Σ_v w_v ‖(A X)_v − T_v‖²` for a symmetric `A`
/// (the cotangent matrix `Ls`), in the unknown rows `first..` of `X` with the rows `..first`
/// known. Weights `w_v = 0` leave row `v` out (open-boundary rows).
#[derive(Clone, Copy, Debug)]
pub struct LeastSquares<'a> {
    /// `A`, `n × n`, symmetric.
    pub a: &'a Csc,
    /// `w`, `n`.
    pub w: &'a [f64],
    /// The first unknown row.
    pub first: usize,
}

impl LeastSquares<'_> {
    /// The lower triangle of `(Aᵀ W A)_uu`, the matrix of the normal equations on the unknowns.
    pub fn matrix(&self) -> Csc {
        product_lower(self.a, self.w, self.a, self.first)
    }

    /// The right-hand side `(Aᵀ W (T − A X̃))_u`, `(n − first) × k`, for the known rows `known`
    /// (`n × k`, zero on the unknown rows; see [`Eliminated`]) and the target `T` (`n × k`,
    /// `None`: zero).
    pub fn rhs(&self, target: Option<&Mat<f64>>, known: &Mat<f64>) -> Mat<f64> {
        let (a, w, first) = (self.a, self.w, self.first);
        let n = a.nrows;
        let k = known.ncols();
        let mut y = Mat::<f64>::zeros(n, k);
        // X̃ is zero but on the known rows: the column-wise product skips the zeros.
        a.mul_dense(known.as_ref(), y.as_mut());
        for c in 0..k {
            for i in 0..n {
                let b = target.map_or(0.0, |t| t[(i, c)]);
                y[(i, c)] = w[i] * (b - y[(i, c)]);
            }
        }
        let mut z = Mat::<f64>::zeros(n, k);
        a.sym_mul_dense(y.as_ref(), z.as_mut());
        let mut out = Mat::<f64>::zeros(n - first, k);
        for c in 0..k {
            for i in first..n {
                out[(i - first, c)] = z[(i, c)];
            }
        }
        out
    }
}

/// A factorised system on the unknown rows `first..n` of `X` (rows `..first` known and
/// eliminated): factor once, solve for many right-hand sides (see the module documentation).
pub struct Eliminated<F: Factorization = Cholesky> {
    first: usize,
    factor: F,
}

impl Eliminated<Cholesky> {
    /// Factorises `q_uu` (the lower triangle of the matrix on the unknowns `first..`, as
    /// [`LeastSquares::matrix`] gives it). `parts[i]`, when given, is the part (patch) of unknown
    /// `i`: the ordering dissects along the parts ([`Cholesky::factor_in_parts`]). `what` names
    /// the system in errors.
    ///
    /// Errors with [`crate::Error::Numerical`] when the matrix is not numerically positive
    /// definite (a patch without a constrained vertex, degenerate triangles).
    pub fn factor(q_uu: &Csc, first: usize, parts: Option<&[u32]>, what: &str) -> Result<Self> {
        let factor = Cholesky::factor_in_parts(q_uu, what, parts).map_err(|e| {
            // A failed pivot names its unknown: the vertex is `first` rows further.
            match e.at().vertex {
                Some(j) => e.vertex(first + j),
                None => e,
            }
        })?;
        Ok(Eliminated { first, factor })
    }

    /// The factorisation of `q_uu`, a matrix with the same unknowns and (usually) the same
    /// pattern as this one's: only the numeric factorisation when the pattern is the same,
    /// reusing the symbolic analysis (ordering, elimination tree, supernodes).
    pub fn refactor(&self, q_uu: &Csc, what: &str) -> Result<Self> {
        let first = self.first;
        let factor = self.factor.refactor(q_uu, what).map_err(|e| match e.at().vertex {
            Some(j) => e.vertex(first + j),
            None => e,
        })?;
        Ok(Eliminated { first, factor })
    }

    /// Whether `q_uu`, on unknowns `first..`, has this factorisation's unknowns and sparsity
    /// pattern (so that [`Eliminated::refactor`] reuses its symbolic analysis).
    pub fn same_pattern(&self, q_uu: &Csc, first: usize) -> bool {
        first == self.first && self.factor.same_pattern(q_uu)
    }
}

impl<F: Factorization> Eliminated<F> {
    /// The first unknown row.
    pub fn first(&self) -> usize {
        self.first
    }

    /// Number of unknowns.
    pub fn dim(&self) -> usize {
        self.factor.dim()
    }

    /// The factorisation.
    pub fn factorization(&self) -> &F {
        &self.factor
    }

    /// Solves for the unknowns: `rhs` (`dim × k`, e.g. [`LeastSquares::rhs`]) in, `X_u` out.
    pub fn solve(&self, mut rhs: Mat<f64>) -> Mat<f64> {
        self.factor.solve_in_place(rhs.as_mut());
        rhs
    }
}
