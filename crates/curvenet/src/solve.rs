//! Factor once, solve many: a sparse Cholesky factorisation (faer's supernodal `LLᵀ` with AMD
//! ordering) of the SPD system on the unknown vertices, reused for every right-hand side
//! (DESIGN §1, last convention). Hard constraints are eliminated before the factorisation.

use crate::error::{Error, Result};
use crate::sparse::Csc;
use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::cholesky::llt::factor::LltRegularization;
use faer::sparse::linalg::cholesky::{
    factorize_symbolic_cholesky, CholeskySymbolicParams, LltRef, SymbolicCholesky, SymmetricOrdering,
};
use faer::{Conj, MatMut, Par, Side};

/// A Cholesky factorisation `Q = L Lᵀ` of a sparse symmetric positive definite matrix.
pub struct Cholesky {
    symbolic: SymbolicCholesky<u32>,
    values: Vec<f64>,
}

impl Cholesky {
    /// Factorises `q` (symmetric; both triangles stored, the lower one is read). `what` names
    /// the system in error messages.
    ///
    /// Errors with [`Error::Numerical`] when `q` is not numerically positive definite (a patch
    /// with no constrained vertex, degenerate triangles) or too large to index.
    pub fn factor(q: &Csc, what: &str) -> Result<Self> {
        let a = q.to_faer().ok_or_else(|| {
            Error::Numerical(format!("{what}: the system has too many non-zeros to index with 32 bits"))
        })?;
        let symbolic = factorize_symbolic_cholesky(
            a.symbolic(),
            Side::Lower,
            SymmetricOrdering::Amd,
            CholeskySymbolicParams::default(),
        )
        .map_err(|e| Error::Numerical(format!("{what}: symbolic factorisation failed ({e:?})")))?;
        let mut values = vec![0.0; symbolic.len_val()];
        let par = Par::Seq;
        let mut mem = MemBuffer::try_new(symbolic.factorize_numeric_llt_scratch::<f64>(par, Default::default()))
            .map_err(|_| Error::Numerical(format!("{what}: out of memory for the factorisation")))?;
        symbolic
            .factorize_numeric_llt(
                &mut values,
                a.as_ref(),
                Side::Lower,
                LltRegularization::default(),
                par,
                MemStack::new(&mut mem),
                Default::default(),
            )
            .map_err(|e| {
                Error::Numerical(format!(
                    "{what}: the system is not positive definite ({e:?}); a patch may have no constrained vertex, \
                     or degenerate triangles"
                ))
            })?;
        if values.iter().any(|v| !v.is_finite()) {
            return Err(Error::Numerical(format!("{what}: the factorisation produced non-finite values")));
        }
        Ok(Cholesky { symbolic, values })
    }

    /// Number of unknowns.
    pub fn dim(&self) -> usize {
        self.symbolic.nrows()
    }

    /// Solves `Q X = B` in place for all columns of `rhs` at once.
    pub fn solve_in_place(&self, rhs: MatMut<'_, f64>) {
        let llt = LltRef::new(&self.symbolic, &self.values);
        let par = Par::Seq;
        let mut mem = MemBuffer::new(llt.solve_in_place_scratch::<f64>(rhs.ncols(), par));
        llt.solve_in_place_with_conj(Conj::No, rhs, par, MemStack::new(&mut mem));
    }
}

#[cfg(test)]
#[path = "tests/solve.rs"]
mod tests;
