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
use std::sync::Arc;

/// The fill-reducing ordering of a factorisation.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Ordering {
    /// Approximate minimum degree (faer's).
    Amd,
    /// Nested dissection by level structures ([`crate::ordering::nested_dissection`]).
    NestedDissection,
    /// Nested dissection from [`Ordering::NESTED_DISSECTION_FROM`] unknowns, else AMD.
    #[default]
    Auto,
}

impl Ordering {
    /// Size from which [`Ordering::Auto`] uses nested dissection (measured: see
    /// `docs/performance.md`).
    pub const NESTED_DISSECTION_FROM: usize = 300_000;
}

/// Unknowns from which the numeric factorisation uses all cores.
const PARALLEL_FROM: usize = 250_000;

/// A Cholesky factorisation `Q = L Lᵀ` of a sparse symmetric positive definite matrix.
///
/// The symbolic analysis (fill-reducing ordering, elimination tree, supernodes) depends only
/// on the sparsity pattern; [`Cholesky::refactor`] reuses it for another matrix with the same
/// pattern (the iterated method's systems, whose weights change but not their structure).
pub struct Cholesky {
    symbolic: Arc<SymbolicCholesky<u32>>,
    /// Fingerprint of the factored matrix's pattern (to check pattern reuse).
    pattern: u64,
    values: Vec<f64>,
}

impl Cholesky {
    /// Factorises `q` (symmetric; both triangles stored, the lower one is read). `what` names
    /// the system in error messages.
    ///
    /// Errors with [`Error::Numerical`] when `q` is not numerically positive definite (a patch
    /// with no constrained vertex, degenerate triangles) or too large to index.
    pub fn factor(q: &Csc, what: &str) -> Result<Self> {
        Self::factor_ordered(q, what, Ordering::Auto)
    }

    /// [`Cholesky::factor`] with a chosen fill-reducing ordering.
    pub fn factor_ordered(q: &Csc, what: &str, ordering: Ordering) -> Result<Self> {
        let use_nd = match ordering {
            Ordering::Amd => false,
            Ordering::NestedDissection => true,
            Ordering::Auto => q.ncols >= Ordering::NESTED_DISSECTION_FROM,
        };
        let (fwd, inv);
        let ord = if use_nd {
            fwd = crate::ordering::nested_dissection(q);
            let mut i = vec![0u32; fwd.len()];
            for (k, &v) in fwd.iter().enumerate() {
                i[v as usize] = k as u32;
            }
            inv = i;
            SymmetricOrdering::Custom(faer::perm::PermRef::new_checked(&fwd, &inv, q.ncols))
        } else {
            SymmetricOrdering::Amd
        };
        let symbolic = with_faer(q, what, |a| {
            factorize_symbolic_cholesky(a.symbolic(), Side::Lower, ord, CholeskySymbolicParams::default())
        })?
        .map_err(|e| Error::Numerical(format!("{what}: symbolic factorisation failed ({e:?})")))?;
        let symbolic = Arc::new(symbolic);
        let values = with_faer(q, what, |a| numeric(&symbolic, a, what))??;
        Ok(Cholesky { symbolic, pattern: fingerprint(q), values })
    }

    /// Factorises `q`, reusing this factorisation's symbolic analysis when `q` has the same
    /// sparsity pattern (only the numeric factorisation is computed), else from scratch.
    pub fn refactor(&self, q: &Csc, what: &str) -> Result<Self> {
        if fingerprint(q) != self.pattern {
            return Cholesky::factor(q, what);
        }
        let values = with_faer(q, what, |a| numeric(&self.symbolic, a, what))??;
        Ok(Cholesky { symbolic: Arc::clone(&self.symbolic), pattern: self.pattern, values })
    }

    /// Number of non-zeros of the factor `L`.
    pub fn factor_nnz(&self) -> usize {
        self.symbolic.len_val()
    }

    /// Number of unknowns.
    pub fn dim(&self) -> usize {
        self.symbolic.nrows()
    }

    /// Solves `Q X = B` in place for all columns of `rhs` at once.
    pub fn solve_in_place(&self, rhs: MatMut<'_, f64>) {
        // Triangular solves are bound by memory bandwidth; two threads on half the columns
        // each are ~15% faster than one on all (measured at 100k unknowns).
        if rhs.ncols() >= 2 && rhs.nrows() >= 5000 {
            let k = rhs.ncols() / 2;
            let (a, b) = rhs.split_at_col_mut(k);
            rayon::join(|| self.solve_seq(a), || self.solve_seq(b));
            return;
        }
        self.solve_seq(rhs);
    }

    fn solve_seq(&self, rhs: MatMut<'_, f64>) {
        let llt = LltRef::new(&self.symbolic, &self.values);
        let par = Par::Seq;
        let mut mem = MemBuffer::new(llt.solve_in_place_scratch::<f64>(rhs.ncols(), par));
        llt.solve_in_place_with_conj(Conj::No, rhs, par, MemStack::new(&mut mem));
    }
}

/// A 64-bit FNV-1a hash of the pattern of `q` (dimensions, column pointers, row indices): the
/// same pattern gives the same fingerprint; different patterns collide with probability ~2⁻⁶⁴.
fn fingerprint(q: &Csc) -> u64 {
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    let mut eat = |x: u64| {
        h ^= x;
        h = h.wrapping_mul(0x0000_0100_0000_01b3);
    };
    eat(q.nrows as u64);
    eat(q.ncols as u64);
    q.col_ptr.iter().for_each(|&p| eat(p as u64));
    q.row_idx.iter().for_each(|&r| eat(r as u64));
    h
}

/// A borrowed faer view of `q` (only the column pointers are converted to `u32`).
fn with_faer<R>(q: &Csc, what: &str, f: impl FnOnce(faer::sparse::SparseColMatRef<'_, u32, f64>) -> R) -> Result<R> {
    let col_ptr: Vec<u32> =
        q.col_ptr.iter().map(|&p| u32::try_from(p).ok()).collect::<Option<_>>().ok_or_else(|| {
            Error::Numerical(format!("{what}: the system has too many non-zeros to index with 32 bits"))
        })?;
    let sym = faer::sparse::SymbolicSparseColMatRef::new_checked(q.nrows, q.ncols, &col_ptr, None, &q.row_idx);
    Ok(f(faer::sparse::SparseColMatRef::new(sym, &q.values)))
}

/// The numeric `LLᵀ` factorisation of `a` on the symbolic structure `symbolic`.
fn numeric(
    symbolic: &SymbolicCholesky<u32>,
    a: faer::sparse::SparseColMatRef<'_, u32, f64>,
    what: &str,
) -> Result<Vec<f64>> {
    let mut values = vec![0.0; symbolic.len_val()];
    // Two threads pay off for large factors only (measured: slower at 100k unknowns, 18% faster
    // at 400k, 13% at 1M).
    let par = if a.ncols() >= PARALLEL_FROM { Par::rayon(0) } else { Par::Seq };
    let mut mem = MemBuffer::try_new(symbolic.factorize_numeric_llt_scratch::<f64>(par, Default::default()))
        .map_err(|_| Error::Numerical(format!("{what}: out of memory for the factorisation")))?;
    symbolic
        .factorize_numeric_llt(
            &mut values,
            a,
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
    Ok(values)
}

#[cfg(test)]
#[path = "tests/solve.rs"]
mod tests;
