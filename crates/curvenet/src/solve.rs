//! Factor once, solve many: a sparse Cholesky factorisation (faer's supernodal `LLᵀ` with AMD
//! ordering) of the SPD system on the unknown vertices, reused for every right-hand side
//! (DESIGN §1, last convention). Hard constraints are eliminated before the factorisation.

use crate::error::{Error, Result};
use crate::sparse::Csc;
use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::cholesky::llt::factor::LltRegularization;
use faer::sparse::linalg::cholesky::{
    factorize_symbolic_cholesky, CholeskySymbolicParams, LltRef, SymbolicCholesky, SymbolicCholeskyRaw,
    SymmetricOrdering,
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
        let order = use_nd.then(|| crate::ordering::nested_dissection(q));
        Self::factor_with(q, what, order.as_deref())
    }

    /// [`Cholesky::factor`] for a system whose unknowns fall in parts coupled only along thin
    /// borders (`parts[i]`: the part of unknown `i`; for the surfacing systems, the patch of
    /// each free vertex, see [`crate::mesh::Mesh::free_vertex_patches`]): nested dissection
    /// along the parts ([`crate::ordering::nested_dissection_in_parts`]) from
    /// [`Ordering::PARTS_FROM`] unknowns. `None` or parts of the wrong length: as
    /// [`Cholesky::factor`].
    pub fn factor_in_parts(q: &Csc, what: &str, parts: Option<&[u32]>) -> Result<Self> {
        match parts {
            Some(p) if p.len() == q.ncols => {
                let order =
                    (q.ncols >= Ordering::PARTS_FROM).then(|| crate::ordering::nested_dissection_in_parts(q, p));
                let order = order.or_else(|| {
                    (q.ncols >= Ordering::NESTED_DISSECTION_FROM).then(|| crate::ordering::nested_dissection(q))
                });
                // A failed pivot names the patch of its unknown.
                Self::factor_named(q, what, order.as_deref(), &|j| format!("free vertex {j} of patch {}", p[j]))
            }
            _ => Self::factor(q, what),
        }
    }

    /// Factorises `q` with the elimination order `order` (`order[k]`: the unknown eliminated
    /// `k`-th), for orderings computed elsewhere (METIS, a previous run).
    ///
    /// Errors with [`Error::Usage`] when `order` is not a permutation of the unknowns.
    pub fn factor_permuted(q: &Csc, what: &str, order: &[u32]) -> Result<Self> {
        let mut seen = vec![false; q.ncols];
        let valid = order.len() == q.ncols
            && order.iter().all(|&v| (v as usize) < q.ncols && !std::mem::replace(&mut seen[v as usize], true));
        if !valid {
            return Err(Error::Usage(format!(
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
        let symbolic = with_faer(q, what, |a| {
            factorize_symbolic_cholesky(a.symbolic(), Side::Lower, ord, CholeskySymbolicParams::default())
        })?
        .map_err(|e| Error::Numerical(format!("{what}: symbolic factorisation failed ({e:?})")))?;
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
            Error::Numerical(format!("{what}: the system has too many non-zeros to index with 32 bits"))
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
            let at = match e {
                faer::linalg::solvers::LltError::NonPositivePivot { index } => {
                    // faer's `index` is 1-based, in the elimination order; map it back to the
                    // caller's unknown (guarded: a pivot we cannot place is reported unplaced).
                    let k = index.saturating_sub(1);
                    match symbolic.perm() {
                        Some(p) => p.arrays().0.get(k).map(|&j| j as usize),
                        None => (k < a.ncols()).then_some(k),
                    }
                    .map_or_else(String::new, |j| format!(" at {}", describe(j)))
                }
            };
            Error::Numerical(format!(
                "{what}: the system is singular or indefinite{at}; the patch may have no constrained vertex, \
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

/// Dense kernels of the supernodal triangular solves with a few right-hand sides (`k ≤ ~9`
/// columns). A supernode's block of `L` is column-major, `h = w + m` rows (its `w` columns,
/// then its `m` pattern rows) by `w` columns; the right-hand sides `z` are column-major `h × k`
/// too: the supernode's own rows, then its pattern's.
///
/// Both passes sweep the block four columns at a time, each column from the diagonal down in
/// memory order (four sequential streams; the next four columns, and the next supernode's
/// first four, prefetched whole: without it the solves wait on memory, not on arithmetic): the
/// forward pass solves the 4 × 4 triangle and subtracts the four columns times the solved
/// values from every row below (own rows and pattern rows in one sweep); the backward pass
/// takes the four dot products with the rows below, then solves the triangle. The triangles
/// of all right-hand sides are solved side by side (their divisions overlap). Each value of
/// `L` is read from memory once per pass. The loops use AVX2 when the processor has it (checked at run time);
/// no fused multiply–add, and the same order of operations on both paths: the same bits.
mod kernels {
    /// Forward substitution: `z[..w] ← T⁻¹ z[..w]`, `z[w..] −= B z[..w]` for the block
    /// `[T; B]`.
    pub(super) fn forward(block: &[f64], w: usize, h: usize, k: usize, z: &mut [f64]) {
        #[cfg(target_arch = "x86_64")]
        if std::is_x86_feature_detected!("avx2") {
            // SAFETY: the processor has AVX2.
            return unsafe { forward_avx2(block, w, h, k, z) };
        }
        forward_generic::<false>(block, w, h, k, z)
    }

    /// Backward substitution: `z[..w] ← T⁻ᵀ (z[..w] − Bᵀ z[w..])`.
    pub(super) fn backward(block: &[f64], w: usize, h: usize, k: usize, z: &mut [f64]) {
        #[cfg(target_arch = "x86_64")]
        if std::is_x86_feature_detected!("avx2") {
            // SAFETY: the processor has AVX2.
            return unsafe { backward_avx2(block, w, h, k, z) };
        }
        backward_generic::<false>(block, w, h, k, z)
    }

    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    unsafe fn forward_avx2(block: &[f64], w: usize, h: usize, k: usize, z: &mut [f64]) {
        forward_generic::<true>(block, w, h, k, z)
    }

    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    unsafe fn backward_avx2(block: &[f64], w: usize, h: usize, k: usize, z: &mut [f64]) {
        backward_generic::<true>(block, w, h, k, z)
    }

    /// Asks for the cache lines of the columns `j..j + 4` from row `j` on: the next group of
    /// columns arrives while the current one is used (one prefetch per line; the columns of a
    /// supernode are short, so the hardware's stream detection alone lags behind).
    #[inline(always)]
    pub(super) fn prefetch(block: &[f64], h: usize, j: usize, w: usize) {
        #[cfg(target_arch = "x86_64")]
        for q in j..(j + 4).min(w) {
            let (from, to) = (q * h + j, ((q + 1) * h).min(block.len()));
            let mut at = from;
            while at < to {
                // SAFETY: a prefetch of an address inside `block` (no access is made).
                unsafe {
                    use std::arch::x86_64::{_mm_prefetch, _MM_HINT_T0};
                    _mm_prefetch::<_MM_HINT_T0>(block.as_ptr().add(at) as *const i8);
                }
                at += 8;
            }
        }
        #[cfg(not(target_arch = "x86_64"))]
        let _ = (block, h, j, w);
    }

    #[inline(always)]
    pub(super) fn forward_generic<const AVX2: bool>(block: &[f64], w: usize, h: usize, k: usize, z: &mut [f64]) {
        let column = |j: usize, from: usize| &block[j * h + from..(j + 1) * h];
        for j0 in (0..w).step_by(4) {
            let jb = (w - j0).min(4);
            prefetch(block, h, j0 + 4, w);
            // The triangle: z_j /= T_jj, then z_i -= T_ij z_j inside it; the right-hand sides
            // side by side, so that their divisions overlap.
            for j in j0..j0 + jb {
                let col = column(j, 0);
                for zc in z.chunks_exact_mut(h).take(k) {
                    let v = zc[j] / col[j];
                    zc[j] = v;
                    for i in j + 1..j0 + jb {
                        zc[i] -= col[i] * v;
                    }
                }
            }
            for zc in z.chunks_exact_mut(h).take(k) {
                // Every row below: z_i -= Σ_q L_iq z_q.
                if jb == 4 {
                    let a = [-zc[j0], -zc[j0 + 1], -zc[j0 + 2], -zc[j0 + 3]];
                    let b =
                        [column(j0, j0 + 4), column(j0 + 1, j0 + 4), column(j0 + 2, j0 + 4), column(j0 + 3, j0 + 4)];
                    axpy4::<AVX2>(&mut zc[j0 + 4..], b, a);
                } else {
                    for j in j0..j0 + jb {
                        let v = zc[j];
                        let (_, below) = zc.split_at_mut(j0 + jb);
                        for (zi, &l) in below.iter_mut().zip(column(j, j0 + jb)) {
                            *zi -= l * v;
                        }
                    }
                }
            }
        }
    }

    #[inline(always)]
    pub(super) fn backward_generic<const AVX2: bool>(block: &[f64], w: usize, h: usize, k: usize, z: &mut [f64]) {
        let column = |j: usize, from: usize| &block[j * h + from..(j + 1) * h];
        for j0 in (0..w).step_by(4).rev() {
            let jb = (w - j0).min(4);
            if j0 >= 4 {
                prefetch(block, h, j0 - 4, w);
            }
            for zc in z.chunks_exact_mut(h).take(k) {
                // Every row below: z_q -= Σ_i L_iq z_i.
                let (head, below) = zc.split_at_mut(j0 + jb);
                if jb == 4 {
                    let b =
                        [column(j0, j0 + 4), column(j0 + 1, j0 + 4), column(j0 + 2, j0 + 4), column(j0 + 3, j0 + 4)];
                    let d = dot4::<AVX2>(b, below);
                    for q in 0..4 {
                        head[j0 + q] -= d[q];
                    }
                } else {
                    for j in j0..j0 + jb {
                        head[j] -= dot(column(j, j0 + jb), below);
                    }
                }
            }
            // The triangle, from its last row up: z_j = (z_j − Σ_{i>j} T_ij z_i) / T_jj; the
            // right-hand sides side by side (their divisions overlap).
            for j in (j0..j0 + jb).rev() {
                let col = column(j, 0);
                for head in z.chunks_exact_mut(h).take(k) {
                    let mut s = head[j];
                    for i in j + 1..j0 + jb {
                        s -= col[i] * head[i];
                    }
                    head[j] = s / col[j];
                }
            }
        }
    }

    /// `y += Σ_q b_q a_q` over the rows of `y` (each `b_q` at least as long), four rows at a
    /// time in one vector each.
    #[inline(always)]
    fn axpy4<const AVX2: bool>(y: &mut [f64], b: [&[f64]; 4], a: [f64; 4]) {
        let m = y.len();
        let b = b.map(|c| &c[..m]);
        let mut i = 0;
        #[cfg(target_arch = "x86_64")]
        if AVX2 {
            use std::arch::x86_64::*;
            // SAFETY: AVX2 is enabled in the callers with AVX2 = true; every access is below m.
            unsafe {
                let a = a.map(|v| _mm256_set1_pd(v));
                let (yp, bp) = (y.as_mut_ptr(), b.map(|c| c.as_ptr()));
                while i + 4 <= m {
                    let t = |q: usize| _mm256_mul_pd(_mm256_loadu_pd(bp[q].add(i)), a[q]);
                    let s = _mm256_add_pd(_mm256_add_pd(t(0), t(1)), _mm256_add_pd(t(2), t(3)));
                    _mm256_storeu_pd(yp.add(i), _mm256_add_pd(_mm256_loadu_pd(yp.add(i)), s));
                    i += 4;
                }
            }
        }
        for i in i..m {
            y[i] += ((b[0][i] * a[0]) + (b[1][i] * a[1])) + ((b[2][i] * a[2]) + (b[3][i] * a[3]));
        }
    }

    /// `[Σ_i b_q[i] y[i]]_q` for four columns `b_q` (at least as long as `y`), in four-lane
    /// partial sums.
    #[inline(always)]
    fn dot4<const AVX2: bool>(b: [&[f64]; 4], y: &[f64]) -> [f64; 4] {
        let m = y.len();
        let b = b.map(|c| &c[..m]);
        // Eight partial sums per column (lane l: the rows i ≡ l mod 8), added in a fixed order.
        let mut acc = [[0.0f64; 8]; 4];
        let mut i = 0;
        #[cfg(target_arch = "x86_64")]
        if AVX2 {
            use std::arch::x86_64::*;
            // SAFETY: AVX2 is enabled in the callers with AVX2 = true; every access is below m.
            unsafe {
                let (yp, bp) = (y.as_ptr(), b.map(|c| c.as_ptr()));
                let mut v = [[_mm256_setzero_pd(); 2]; 4];
                while i + 8 <= m {
                    let y0 = _mm256_loadu_pd(yp.add(i));
                    let y1 = _mm256_loadu_pd(yp.add(i + 4));
                    for q in 0..4 {
                        v[q][0] = _mm256_add_pd(v[q][0], _mm256_mul_pd(_mm256_loadu_pd(bp[q].add(i)), y0));
                        v[q][1] = _mm256_add_pd(v[q][1], _mm256_mul_pd(_mm256_loadu_pd(bp[q].add(i + 4)), y1));
                    }
                    i += 8;
                }
                for q in 0..4 {
                    _mm256_storeu_pd(acc[q].as_mut_ptr(), v[q][0]);
                    _mm256_storeu_pd(acc[q].as_mut_ptr().add(4), v[q][1]);
                }
            }
        }
        if !AVX2 {
            while i + 8 <= m {
                for q in 0..4 {
                    for l in 0..8 {
                        acc[q][l] += b[q][i + l] * y[i + l];
                    }
                }
                i += 8;
            }
        }
        let mut out = acc.map(|a| ((a[0] + a[4]) + (a[2] + a[6])) + ((a[1] + a[5]) + (a[3] + a[7])));
        for i in i..m {
            for q in 0..4 {
                out[q] += b[q][i] * y[i];
            }
        }
        out
    }

    /// `Σ aᵢ bᵢ` over the shorter length, in eight interleaved partial sums (vector lanes).
    #[inline(always)]
    fn dot(a: &[f64], b: &[f64]) -> f64 {
        let n = a.len().min(b.len());
        let (a, b) = (&a[..n], &b[..n]);
        let mut acc = [0.0f64; 8];
        let (ca, cb) = (a.chunks_exact(8), b.chunks_exact(8));
        let (ra, rb) = (ca.remainder(), cb.remainder());
        for (x, y) in ca.zip(cb) {
            for l in 0..8 {
                acc[l] += x[l] * y[l];
            }
        }
        let mut s = ((acc[0] + acc[4]) + (acc[1] + acc[5])) + ((acc[2] + acc[6]) + (acc[3] + acc[7]));
        for (x, y) in ra.iter().zip(rb) {
            s += x * y;
        }
        s
    }
}

/// Triangular solves with a supernodal factor for a few right-hand sides at once, split over
/// two threads along the elimination tree.
///
/// The solves read the whole factor once per pass and are bound by memory bandwidth. faer's
/// own solve runs on one thread (its parallel mode splits the dense blocks, which are small);
/// here two independent subtrees of the elimination tree are solved concurrently, each thread
/// reading its share of `L` once, and the few supernodes above them (the first separators of a
/// nested dissection) sequentially. The dense work per supernode is done by [`kernels`]:
/// faer's general matrix products pack their operands and cost ~4× the bandwidth floor on
/// these thin (few-column) products.
mod tree_solve {
    use faer::sparse::linalg::cholesky::supernodal::SymbolicSupernodalCholesky;

    /// Supernodes per thread and the ones above them.
    #[derive(Debug, Default)]
    pub(super) struct TreeSplit {
        /// Per thread: its subtrees as ranges of supernodes (postorder: contiguous).
        groups: [Vec<std::ops::Range<usize>>; 2],
        /// The remaining supernodes (ancestors of the groups), in increasing order.
        top: Vec<usize>,
        /// Per row of the factor: its slot among the top supernodes' rows, or `u32::MAX`.
        top_slot: Vec<u32>,
        top_rows: usize,
    }

    /// The split of `sym`'s elimination tree: descend from the roots through single children
    /// and through any subtree holding over 60% of the remaining work, then share the subtrees
    /// found between two threads (largest first to the lighter). `None` when the tree does not
    /// split in two shares of at least 20% each (a chain, a tiny system).
    pub(super) fn split(sym: &SymbolicSupernodalCholesky<u32>) -> Option<TreeSplit> {
        let ns = sym.n_supernodes();
        let begin = sym.supernode_begin();
        let vp = sym.col_ptr_for_val();
        let n = sym.nrows();
        if ns < 4 {
            return None;
        }
        // Parent: the supernode holding the first off-diagonal row.
        let mut parent = vec![usize::MAX; ns];
        for (s, p) in parent.iter_mut().enumerate() {
            if let Some(&r) = sym.supernode(s).pattern().iter().min() {
                let r = r as usize;
                let t = begin.partition_point(|&b| b as usize <= r) - 1;
                if t <= s {
                    return None; // not a postorder: keep the sequential solve
                }
                *p = t;
            }
        }
        let mut work: Vec<usize> = (0..ns).map(|s| (vp[s + 1] - vp[s]) as usize).collect();
        let mut first = (0..ns).collect::<Vec<_>>();
        let mut children: Vec<Vec<usize>> = vec![Vec::new(); ns];
        for s in 0..ns {
            if parent[s] != usize::MAX {
                let p = parent[s];
                work[p] += work[s];
                first[p] = first[p].min(first[s]);
                children[p].push(s);
            }
        }
        let total: usize = (0..ns).filter(|&s| parent[s] == usize::MAX).map(|s| work[s]).sum();
        let mut candidates: Vec<usize> = (0..ns).filter(|&s| parent[s] == usize::MAX).collect();
        let mut top = Vec::new();
        loop {
            let sum: usize = candidates.iter().map(|&c| work[c]).sum();
            let Some((i, &heavy)) = candidates.iter().enumerate().max_by_key(|(_, &c)| work[c]) else {
                return None;
            };
            if candidates.len() == 1 || (work[heavy] * 10 > sum * 6 && !children[heavy].is_empty()) {
                candidates.swap_remove(i);
                top.push(heavy);
                candidates.extend_from_slice(&children[heavy]);
            } else {
                break;
            }
        }
        candidates.sort_by_key(|&c| std::cmp::Reverse(work[c]));
        let mut groups: [Vec<std::ops::Range<usize>>; 2] = [Vec::new(), Vec::new()];
        let mut load = [0usize; 2];
        for c in candidates {
            let g = if load[0] <= load[1] { 0 } else { 1 };
            load[g] += work[c];
            groups[g].push(first[c]..c + 1);
        }
        if load[0].min(load[1]) * 5 < total {
            return None;
        }
        for g in &mut groups {
            g.sort_by_key(|r| r.start);
        }
        top.sort_unstable();
        let mut top_slot = vec![u32::MAX; n];
        let mut top_rows = 0;
        for &s in &top {
            for r in begin[s] as usize..sym.supernode_end()[s] as usize {
                top_slot[r] = top_rows as u32;
                top_rows += 1;
            }
        }
        Some(TreeSplit { groups, top, top_slot, top_rows })
    }

    /// A raw view of the right-hand sides (row-major: row `r`'s `k` values contiguous, so that
    /// a scattered row update touches one cache line) shared by the
    /// two threads.
    #[derive(Clone, Copy)]
    struct Shared {
        ptr: *mut f64,
        k: usize,
    }
    // SAFETY: the threads write disjoint rows (their own subtrees'); rows of the top
    // supernodes are written by the first thread only in the forward pass (the second one
    // accumulates into its own buffer) and by neither in the backward pass.
    unsafe impl Send for Shared {}
    unsafe impl Sync for Shared {}

    impl Shared {
        /// # Safety
        /// Row `r` is not being written by another thread.
        unsafe fn at(self, r: usize, c: usize) -> *mut f64 {
            self.ptr.add(r * self.k + c)
        }
    }

    /// Where a forward update of a row outside the thread's subtrees goes.
    enum Sink<'a> {
        /// Straight into `x`.
        Direct,
        /// Into a buffer (row-major, `top_rows` rows) indexed by the top slot.
        Buffer(&'a [u32], &'a mut [f64]),
    }

    /// The supernode's block of `L`: its first row, its pattern (the rows below its columns)
    /// and its values, column-major with leading dimension `w + pattern.len()`.
    fn block<'a>(
        sym: &'a SymbolicSupernodalCholesky<u32>,
        values: &'a [f64],
        s: usize,
    ) -> (usize, &'a [u32], &'a [f64]) {
        let node = sym.supernode(s);
        let vals = &values[sym.col_ptr_for_val()[s] as usize..sym.col_ptr_for_val()[s + 1] as usize];
        (node.start(), node.pattern(), vals)
    }

    /// `L y = b` for supernode `s` ([`super::kernels::forward`]): its own rows solved, the
    /// products with its pattern rows subtracted from those rows or the sink.
    ///
    /// # Safety
    /// No other thread touches this supernode's rows or, with [`Sink::Direct`], the rows of
    /// its pattern.
    unsafe fn forward(
        sym: &SymbolicSupernodalCholesky<u32>,
        values: &[f64],
        s: usize,
        x: Shared,
        sink: &mut Sink<'_>,
        z: &mut Vec<f64>,
    ) {
        let (start, pattern, block) = block(sym, values, s);
        let (w, m, k) = (sym.supernode_end()[s] as usize - start, pattern.len(), x.k);
        let h = w + m;
        gather_own(z, x, start, w, h);
        prefetch_first(sym, values, s + 1, false);
        super::kernels::forward(block, w, h, k, z);
        put_back(z, x, start, w, h);
        // z's pattern rows hold −B x: added to the rows they belong to.
        for (idx, &r) in pattern.iter().enumerate() {
            let r = r as usize;
            let row: &mut [f64] = match sink {
                Sink::Buffer(slot, buf) if slot[r] != u32::MAX => {
                    let t = slot[r] as usize;
                    &mut buf[t * k..(t + 1) * k]
                }
                _ => std::slice::from_raw_parts_mut(x.at(r, 0), k),
            };
            for (c, v) in row.iter_mut().enumerate() {
                *v += z[c * h + w + idx];
            }
        }
    }

    /// `Lᵀ x = y` for supernode `s` ([`super::kernels::backward`]): its own rows and its
    /// pattern's gathered, its own rows solved.
    ///
    /// # Safety
    /// As [`forward`]; the rows of the pattern are only read.
    unsafe fn backward(sym: &SymbolicSupernodalCholesky<u32>, values: &[f64], s: usize, x: Shared, z: &mut Vec<f64>) {
        let (start, pattern, block) = block(sym, values, s);
        let (w, m, k) = (sym.supernode_end()[s] as usize - start, pattern.len(), x.k);
        let h = w + m;
        gather_own(z, x, start, w, h);
        for (idx, &r) in pattern.iter().enumerate() {
            let row = std::slice::from_raw_parts(x.at(r as usize, 0), k);
            for (c, &v) in row.iter().enumerate() {
                z[c * h + w + idx] = v;
            }
        }
        if s > 0 {
            prefetch_first(sym, values, s - 1, true);
        }
        super::kernels::backward(block, w, h, k, z);
        put_back(z, x, start, w, h);
    }

    /// Prefetches the columns supernode `s` uses first: its first four (forward) or its last
    /// group of four (`last`, backward).
    fn prefetch_first(sym: &SymbolicSupernodalCholesky<u32>, values: &[f64], s: usize, last: bool) {
        if s >= sym.n_supernodes() {
            return;
        }
        let (start, pattern, block) = block(sym, values, s);
        let w = sym.supernode_end()[s] as usize - start;
        let j = if last { w.saturating_sub(1) / 4 * 4 } else { 0 };
        super::kernels::prefetch(block, w + pattern.len(), j, w);
    }

    /// `z` (column-major `h × k`) ← the rows `start..start + w` of `x` on top, zeros below.
    ///
    /// # Safety
    /// Rows `start..start + w` of `x` are not being written by another thread.
    unsafe fn gather_own(z: &mut Vec<f64>, x: Shared, start: usize, w: usize, h: usize) {
        let k = x.k;
        z.clear();
        z.resize(h * k, 0.0);
        let rows = std::slice::from_raw_parts(x.at(start, 0), w * k);
        for (j, row) in rows.chunks_exact(k).enumerate() {
            for (c, &v) in row.iter().enumerate() {
                z[c * h + j] = v;
            }
        }
    }

    /// The top `w` rows of `z` back into rows `start..start + w` of `x`.
    ///
    /// # Safety
    /// No other thread touches rows `start..start + w` of `x`.
    unsafe fn put_back(z: &[f64], x: Shared, start: usize, w: usize, h: usize) {
        let k = x.k;
        let rows = std::slice::from_raw_parts_mut(x.at(start, 0), w * k);
        for (j, row) in rows.chunks_exact_mut(k).enumerate() {
            for (c, v) in row.iter_mut().enumerate() {
                *v = z[c * h + j];
            }
        }
    }

    /// Solves `L Lᵀ x = b` in place (`x`: the permuted right-hand sides, row-major `n × k`).
    pub(super) fn solve(
        sym: &SymbolicSupernodalCholesky<u32>,
        values: &[f64],
        split: &TreeSplit,
        x: &mut [f64],
        k: usize,
    ) {
        let shared = Shared { ptr: x.as_mut_ptr(), k };
        let rows = split.top_rows;
        let mut buf = vec![0.0; rows * k];
        // SAFETY (all blocks below): see `Shared`; the groups hold disjoint subtrees, whose
        // patterns reach only their own rows and the top supernodes' rows.
        rayon::join(
            || {
                let (shared, mut z) = (shared, Vec::new());
                for r in &split.groups[0] {
                    for s in r.clone() {
                        unsafe { forward(sym, values, s, shared, &mut Sink::Direct, &mut z) };
                    }
                }
            },
            || {
                let (shared, mut z) = (shared, Vec::new());
                let mut sink = Sink::Buffer(&split.top_slot, &mut buf);
                for r in &split.groups[1] {
                    for s in r.clone() {
                        unsafe { forward(sym, values, s, shared, &mut sink, &mut z) };
                    }
                }
            },
        );
        let begin = sym.supernode_begin();
        let mut z = Vec::new();
        for &s in &split.top {
            for row in begin[s] as usize..sym.supernode_end()[s] as usize {
                let t = split.top_slot[row] as usize;
                for c in 0..k {
                    unsafe { *shared.at(row, c) += buf[t * k + c] };
                }
            }
        }
        for &s in &split.top {
            unsafe { forward(sym, values, s, shared, &mut Sink::Direct, &mut z) };
        }
        for &s in split.top.iter().rev() {
            unsafe { backward(sym, values, s, shared, &mut z) };
        }
        rayon::join(
            || {
                let (shared, mut z) = (shared, Vec::new());
                for r in split.groups[0].iter().rev() {
                    for s in r.clone().rev() {
                        unsafe { backward(sym, values, s, shared, &mut z) };
                    }
                }
            },
            || {
                let (shared, mut z) = (shared, Vec::new());
                for r in split.groups[1].iter().rev() {
                    for s in r.clone().rev() {
                        unsafe { backward(sym, values, s, shared, &mut z) };
                    }
                }
            },
        );
    }
}
