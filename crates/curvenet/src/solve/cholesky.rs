//! Factor once, solve many: a sparse Cholesky factorisation (faer's supernodal `LLᵀ` with AMD
//! ordering) of the SPD system on the unknown vertices, reused for every right-hand side
//! (docs/design.md §1, last convention; §8). Hard constraints are eliminated before the factorisation.

use super::tree_solve;
use crate::error::{Error, Result};
use crate::solve::sparse::Csc;
use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::cholesky::llt::factor::LltRegularization;
use faer::sparse::linalg::cholesky::{
    factorize_symbolic_cholesky, CholeskySymbolicParams, LltRef, SymbolicCholesky, SymbolicCholeskyRaw,
    SymmetricOrdering,
};
use faer::sparse::linalg::SupernodalThreshold;
use faer::{Conj, MatMut, Par, Side};
use std::sync::Arc;

/// The fill-reducing ordering of a factorisation.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Ordering {
    /// Approximate minimum degree (faer's).
    Amd,
    /// Nested dissection by level structures ([`crate::solve::ordering::nested_dissection`]).
    NestedDissection,
    /// Nested dissection from [`Ordering::NESTED_DISSECTION_FROM`] unknowns, else AMD; with
    /// parts ([`Cholesky::factor_in_parts`]) nested dissection along them from
    /// [`Ordering::PARTS_FROM`] unknowns.
    #[default]
    Auto,
}

impl Ordering {
    /// Size from which [`Ordering::Auto`] uses nested dissection by levels (measured on the
    /// sphere and torus systems: faster than AMD at 200k unknowns, slower at 100k).
    pub const NESTED_DISSECTION_FROM: usize = 150_000;
    /// Size from which [`Ordering::Auto`] uses nested dissection along parts when they are
    /// given (measured: ordering and factorisation together as fast as AMD's at 18k unknowns,
    /// 15% faster at 48k, 35% at 200k; the factor has 14–32% fewer non-zeros).
    pub const PARTS_FROM: usize = 15_000;
}

/// Unknowns from which the triangular solves run on two subtrees in parallel ([`tree_solve`]).
const TREE_SOLVE_FROM: usize = 5000;

/// Unknowns from which the numeric factorisation uses all cores.
#[cfg_attr(not(feature = "parallel"), allow(dead_code))]
pub(crate) const PARALLEL_FROM: usize = 250_000;

/// The symbolic analysis and how its elimination tree splits between two threads.
struct Symbolic {
    chol: SymbolicCholesky<u32>,
    split: Option<tree_solve::TreeSplit>,
}

/// A Cholesky factorisation `Q = L Lᵀ` of a sparse symmetric positive definite matrix.
///
/// The symbolic analysis (fill-reducing ordering, elimination tree, supernodes) depends only
/// on the sparsity pattern; [`Cholesky::refactor`] reuses it for another matrix with the same
/// pattern (the iterated method's systems, whose weights change but not their structure).
pub struct Cholesky {
    symbolic: Arc<Symbolic>,
    /// Fingerprint of the factored matrix's pattern (to check pattern reuse).
    pattern: u64,
    values: Vec<f64>,
}

impl Cholesky {
    /// Factorises `q` (symmetric; both triangles stored, or the lower one only, which is the
    /// one read). `what` names the system in error messages.
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
        let order = use_nd.then(|| crate::solve::ordering::nested_dissection(q));
        Self::factor_with(q, what, order.as_deref())
    }

    /// [`Cholesky::factor`] for a system whose unknowns fall in parts coupled only along thin
    /// borders (`parts[i]`: the part of unknown `i`; for the surfacing systems, the patch of
    /// each free vertex, see `Mesh::free_vertex_patches`): nested dissection
    /// along the parts ([`crate::solve::ordering::nested_dissection_in_parts`]) from
    /// [`Ordering::PARTS_FROM`] unknowns. `None` or parts of the wrong length: as
    /// [`Cholesky::factor`].
    pub fn factor_in_parts(q: &Csc, what: &str, parts: Option<&[u32]>) -> Result<Self> {
        match parts {
            Some(p) if p.len() == q.ncols => {
                let order =
                    (q.ncols >= Ordering::PARTS_FROM).then(|| crate::solve::ordering::nested_dissection_in_parts(q, p));
                let order = order.or_else(|| {
                    (q.ncols >= Ordering::NESTED_DISSECTION_FROM).then(|| crate::solve::ordering::nested_dissection(q))
                });
                // A failed pivot names the patch of its unknown.
                Self::factor_named(q, what, order.as_deref(), &|j| format!("free vertex {j} of patch {}", p[j]))
                    .map_err(|e| match e.at().vertex.and_then(|j| p.get(j)) {
                        Some(&patch) => e.patch(patch as usize),
                        None => e,
                    })
            }
            _ => Self::factor(q, what),
        }
    }

    /// Factorises `q` with the elimination order `order` (`order[k]`: the unknown eliminated
    /// `k`-th), for orderings computed elsewhere (METIS, a previous run).
    ///
    /// Errors with [`Error::usage`] when `order` is not a permutation of the unknowns.
    pub fn factor_permuted(q: &Csc, what: &str, order: &[u32]) -> Result<Self> {
        let mut seen = vec![false; q.ncols];
        let valid = order.len() == q.ncols
            && order.iter().all(|&v| (v as usize) < q.ncols && !std::mem::replace(&mut seen[v as usize], true));
        if !valid {
            return Err(Error::usage(format!(
                "{what}: the elimination order is not a permutation of the {} unknowns",
                q.ncols
            )));
        }
        Self::factor_with(q, what, Some(order))
    }

    /// The factorisation with `order` (a valid permutation) or AMD.
    fn factor_with(q: &Csc, what: &str, order: Option<&[u32]>) -> Result<Self> {
        Self::factor_named(q, what, order, &|j| format!("unknown {j}"))
    }

    /// [`Cholesky::factor_with`]; `describe(j)` names unknown `j` when its pivot fails.
    fn factor_named(q: &Csc, what: &str, order: Option<&[u32]>, describe: &dyn Fn(usize) -> String) -> Result<Self> {
        let inv: Vec<u32>;
        let ord = match order {
            Some(fwd) => {
                let mut i = vec![0u32; fwd.len()];
                for (k, &v) in fwd.iter().enumerate() {
                    i[v as usize] = k as u32;
                }
                inv = i;
                SymmetricOrdering::Custom(faer::perm::PermRef::new_checked(fwd, &inv, q.ncols))
            }
            None => SymmetricOrdering::Amd,
        };
        // Always supernodal: faer picks its simplicial factorisation below 40 flops per factor
        // entry, which here are the small systems (the conformal flattenings, the default's
        // coarse levels at 10k vertices). Measured (issue 18, `perf stat -r 15`, sphere 10k):
        // default 0.132 s → 0.112 s; 100k and `--fast` unchanged within their spread.
        let params = CholeskySymbolicParams {
            supernodal_flop_ratio_threshold: SupernodalThreshold::FORCE_SUPERNODAL,
            ..Default::default()
        };
        let symbolic = with_faer(q, what, |a| factorize_symbolic_cholesky(a.symbolic(), Side::Lower, ord, params))?
            .map_err(|e| Error::numerical(format!("{what}: symbolic factorisation failed ({e:?})")))?;
        let split = match symbolic.raw() {
            SymbolicCholeskyRaw::Supernodal(sym) if q.ncols >= TREE_SOLVE_FROM => tree_solve::split(sym),
            _ => None,
        };
        let symbolic = Arc::new(Symbolic { chol: symbolic, split });
        let values = with_faer(q, what, |a| numeric(&symbolic.chol, a, what, describe))??;
        Ok(Cholesky { symbolic, pattern: fingerprint(q), values })
    }

    /// Factorises `q`, reusing this factorisation's symbolic analysis when `q` has the same
    /// sparsity pattern (only the numeric factorisation is computed), else from scratch.
    pub fn refactor(&self, q: &Csc, what: &str) -> Result<Self> {
        if fingerprint(q) != self.pattern {
            return Cholesky::factor(q, what);
        }
        let values = with_faer(q, what, |a| numeric(&self.symbolic.chol, a, what, &|j| format!("unknown {j}")))??;
        Ok(Cholesky { symbolic: Arc::clone(&self.symbolic), pattern: self.pattern, values })
    }

    /// Whether `q` has the sparsity pattern of the matrix this factorisation was computed
    /// from ([`Cholesky::refactor`] then reuses the symbolic analysis).
    pub fn same_pattern(&self, q: &Csc) -> bool {
        fingerprint(q) == self.pattern
    }

    /// Number of non-zeros of the factor `L`.
    pub fn factor_nnz(&self) -> usize {
        self.symbolic.chol.len_val()
    }

    /// Number of unknowns.
    pub fn dim(&self) -> usize {
        self.symbolic.chol.nrows()
    }

    /// Solves `Q X = B` in place for all columns of `rhs` at once.
    pub fn solve_in_place(&self, mut rhs: MatMut<'_, f64>) {
        if let (SymbolicCholeskyRaw::Supernodal(sym), Some(split)) = (self.symbolic.chol.raw(), &self.symbolic.split) {
            // Two threads on two subtrees (see `tree_solve`), on the permuted right-hand sides.
            let (n, k) = (rhs.nrows(), rhs.ncols());
            // Row-major: the rows a supernode scatters to are one cache line each.
            let mut x = vec![0.0; n * k];
            let fwd = self.symbolic.chol.perm().map(|p| p.arrays().0);
            let source = |i: usize| fwd.map_or(i, |f| f[i] as usize);
            for (i, row) in x.chunks_exact_mut(k).enumerate() {
                for (c, v) in row.iter_mut().enumerate() {
                    *v = rhs[(source(i), c)];
                }
            }
            tree_solve::solve(sym, &self.values, split, &mut x, k);
            for (i, row) in x.chunks_exact(k).enumerate() {
                for (c, &v) in row.iter().enumerate() {
                    rhs[(source(i), c)] = v;
                }
            }
            return;
        }
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

    /// [`Cholesky::solve_in_place`] by faer's own supernodal solve on one thread: the
    /// reference the two-thread tree solve is tested and benchmarked against.
    pub fn solve_in_place_reference(&self, rhs: MatMut<'_, f64>) {
        self.solve_seq(rhs)
    }

    fn solve_seq(&self, rhs: MatMut<'_, f64>) {
        let llt = LltRef::new(&self.symbolic.chol, &self.values);
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
            Error::numerical(format!("{what}: the system has too many non-zeros to index with 32 bits"))
        })?;
    let sym = faer::sparse::SymbolicSparseColMatRef::new_checked(q.nrows, q.ncols, &col_ptr, None, &q.row_idx);
    Ok(f(faer::sparse::SparseColMatRef::new(sym, &q.values)))
}

/// The numeric `LLᵀ` factorisation of `a` on the symbolic structure `symbolic`.
/// A failed pivot is reported with `describe(j)` of its unknown `j` (in the caller's numbering).
fn numeric(
    symbolic: &SymbolicCholesky<u32>,
    a: faer::sparse::SparseColMatRef<'_, u32, f64>,
    what: &str,
    describe: &dyn Fn(usize) -> String,
) -> Result<Vec<f64>> {
    let mut values = vec![0.0; symbolic.len_val()];
    // Two threads pay off for large factors only (measured: slower at 100k unknowns, 18% faster
    // at 400k, 13% at 1M).
    #[cfg(feature = "parallel")]
    let par = if a.ncols() >= PARALLEL_FROM { Par::rayon(0) } else { Par::Seq };
    #[cfg(not(feature = "parallel"))]
    let par = Par::Seq;
    let mut mem = MemBuffer::try_new(symbolic.factorize_numeric_llt_scratch::<f64>(par, Default::default()))
        .map_err(|_| Error::numerical(format!("{what}: out of memory for the factorisation")))?;
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
            let unknown = match e {
                faer::linalg::solvers::LltError::NonPositivePivot { index } => {
                    // faer's `index` is 1-based, in the elimination order; map it back to the
                    // caller's unknown (guarded: a pivot we cannot place is reported unplaced).
                    let k = index.saturating_sub(1);
                    match symbolic.perm() {
                        Some(p) => p.arrays().0.get(k).map(|&j| j as usize),
                        None => (k < a.ncols()).then_some(k),
                    }
                }
            };
            let at = unknown.map_or_else(String::new, |j| format!(" at {}", describe(j)));
            let e = Error::numerical(format!(
                "{what}: the system is singular or indefinite{at}; the patch may have no constrained vertex, \
                 or degenerate triangles"
            ));
            // The id is the unknown's index here; [`crate::solve::Eliminated`] makes it the vertex.
            match unknown {
                Some(j) => e.vertex(j),
                None => e,
            }
        })?;
    if values.iter().any(|v| !v.is_finite()) {
        return Err(Error::numerical(format!("{what}: the factorisation produced non-finite values")));
    }
    Ok(values)
}

#[cfg(test)]
#[path = "tests/cholesky.rs"]
mod tests;
