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
use faer::{Conj, Mat, MatMut, Par, Side};
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
const PARALLEL_FROM: usize = 250_000;

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
            let mut x = Mat::<f64>::zeros(n, k);
            let fwd = self.symbolic.chol.perm().map(|p| p.arrays().0);
            for c in 0..k {
                for i in 0..n {
                    x[(i, c)] = rhs[(fwd.map_or(i, |f| f[i] as usize), c)];
                }
            }
            tree_solve::solve(sym, &self.values, split, x.as_mut());
            for c in 0..k {
                for i in 0..n {
                    rhs[(fwd.map_or(i, |f| f[i] as usize), c)] = x[(i, c)];
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

/// Triangular solves with a supernodal factor for a few right-hand sides at once, split over
/// two threads along the elimination tree.
///
/// The solves read the whole factor once per pass and are bound by memory bandwidth. faer's
/// own solve runs on one thread (its parallel mode splits the dense blocks, which are small);
/// here two independent subtrees of the elimination tree are solved concurrently, each thread
/// reading its share of `L` once, and the few supernodes above them (the first separators of a
/// nested dissection) sequentially. The right-hand sides are interleaved (row-major) so that
/// each scattered row update touches one cache line.
mod tree_solve {
    use faer::linalg::{matmul, triangular_solve};
    use faer::reborrow::{Reborrow, ReborrowMut};
    use faer::sparse::linalg::cholesky::supernodal::SymbolicSupernodalCholesky;
    use faer::{Accum, Mat, MatMut, MatRef, Par};

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

    /// A raw view of the right-hand sides (unit row stride, column stride `cs`) shared by the
    /// two threads.
    #[derive(Clone, Copy)]
    struct Shared {
        ptr: *mut f64,
        cs: usize,
        k: usize,
    }
    // SAFETY: the threads write disjoint rows (their own subtrees'); rows of the top
    // supernodes are written by the first thread only in the forward pass (the second one
    // accumulates into its own buffer) and by neither in the backward pass.
    unsafe impl Send for Shared {}
    unsafe impl Sync for Shared {}

    impl Shared {
        /// Rows `start..start + w`, all columns.
        ///
        /// # Safety
        /// No other live view overlaps these rows.
        unsafe fn rows<'a>(self, start: usize, w: usize) -> MatMut<'a, f64> {
            MatMut::from_raw_parts_mut(self.ptr.add(start), w, self.k, 1, self.cs as isize)
        }

        /// # Safety
        /// Row `r` is not being written by another thread.
        unsafe fn at(self, r: usize, c: usize) -> *mut f64 {
            self.ptr.add(c * self.cs + r)
        }
    }

    /// Where a forward update of a row outside the thread's subtrees goes.
    enum Sink<'a> {
        /// Straight into `x`.
        Direct,
        /// Into a buffer (column-major, `top_rows` rows) indexed by the top slot.
        Buffer(&'a [u32], &'a mut [f64], usize),
    }

    /// The supernode's block of `L`: rows (its columns, then its pattern) × its columns.
    fn block<'a>(
        sym: &'a SymbolicSupernodalCholesky<u32>,
        values: &'a [f64],
        s: usize,
    ) -> (usize, &'a [u32], MatRef<'a, f64>) {
        let node = sym.supernode(s);
        let (start, pattern) = (node.start(), node.pattern());
        let w = sym.supernode_end()[s] as usize - start;
        let vals = &values[sym.col_ptr_for_val()[s] as usize..sym.col_ptr_for_val()[s + 1] as usize];
        (start, pattern, MatRef::from_column_major_slice(vals, w + pattern.len(), w))
    }

    /// `L y = b` for supernode `s`: the diagonal block solved in place, then the off-diagonal
    /// block's product (faer's dense kernels) subtracted from the pattern rows or the sink.
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
        tmp: &mut Mat<f64>,
    ) {
        let (start, pattern, ls) = block(sym, values, s);
        let w = ls.ncols();
        let (top, bottom) = ls.split_at_row(w);
        let mut xt = x.rows(start, w);
        triangular_solve::solve_lower_triangular_in_place(top, xt.rb_mut(), Par::Seq);
        let m = pattern.len();
        if m == 0 {
            return;
        }
        tmp.resize_with(m, x.k, |_, _| 0.0);
        matmul::matmul(tmp.as_mut(), Accum::Replace, bottom, xt.rb(), 1.0, Par::Seq);
        for c in 0..x.k {
            for (idx, &r) in pattern.iter().enumerate() {
                let r = r as usize;
                let v = tmp[(idx, c)];
                match sink {
                    Sink::Buffer(slot, buf, rows) if slot[r] != u32::MAX => buf[c * *rows + slot[r] as usize] -= v,
                    _ => *x.at(r, c) -= v,
                }
            }
        }
    }

    /// `Lᵀ x = y` for supernode `s`: the pattern rows gathered, the off-diagonal block's
    /// transpose applied, then the diagonal block's transpose solved.
    ///
    /// # Safety
    /// As [`forward`]; the rows of the pattern are only read.
    unsafe fn backward(sym: &SymbolicSupernodalCholesky<u32>, values: &[f64], s: usize, x: Shared, tmp: &mut Mat<f64>) {
        let (start, pattern, ls) = block(sym, values, s);
        let w = ls.ncols();
        let (top, bottom) = ls.split_at_row(w);
        let m = pattern.len();
        let mut xt = x.rows(start, w);
        if m > 0 {
            tmp.resize_with(m, x.k, |_, _| 0.0);
            for c in 0..x.k {
                for (idx, &r) in pattern.iter().enumerate() {
                    tmp[(idx, c)] = *x.at(r as usize, c);
                }
            }
            matmul::matmul(xt.rb_mut(), Accum::Add, bottom.transpose(), tmp.as_ref(), -1.0, Par::Seq);
        }
        triangular_solve::solve_upper_triangular_in_place(top.transpose(), xt, Par::Seq);
    }

    /// Solves `L Lᵀ x = b` in place (`x`: the permuted right-hand sides, `n × k`).
    pub(super) fn solve(sym: &SymbolicSupernodalCholesky<u32>, values: &[f64], split: &TreeSplit, x: MatMut<'_, f64>) {
        let k = x.ncols();
        let mut x = x;
        // A column-major copy when `x` is not column-major.
        let column_major = x.row_stride() == 1 && x.col_stride() >= x.nrows() as isize;
        let mut owned = if column_major { None } else { Some(x.to_owned()) };
        let (ptr, cs) = match owned.as_mut() {
            Some(o) => (o.as_ptr_mut(), o.col_stride() as usize),
            None => (x.as_ptr_mut(), x.col_stride() as usize),
        };
        let shared = Shared { ptr, cs, k };
        let rows = split.top_rows;
        let mut buf = vec![0.0; rows * k];
        // SAFETY (all blocks below): see `Shared`; the groups hold disjoint subtrees, whose
        // patterns reach only their own rows and the top supernodes' rows.
        rayon::join(
            || {
                let (shared, mut tmp) = (shared, Mat::<f64>::zeros(0, 0));
                for r in &split.groups[0] {
                    for s in r.clone() {
                        unsafe { forward(sym, values, s, shared, &mut Sink::Direct, &mut tmp) };
                    }
                }
            },
            || {
                let (shared, mut tmp) = (shared, Mat::<f64>::zeros(0, 0));
                let mut sink = Sink::Buffer(&split.top_slot, &mut buf, rows);
                for r in &split.groups[1] {
                    for s in r.clone() {
                        unsafe { forward(sym, values, s, shared, &mut sink, &mut tmp) };
                    }
                }
            },
        );
        let begin = sym.supernode_begin();
        let mut tmp = Mat::<f64>::zeros(0, 0);
        for &s in &split.top {
            for row in begin[s] as usize..sym.supernode_end()[s] as usize {
                let t = split.top_slot[row] as usize;
                for c in 0..k {
                    unsafe { *shared.at(row, c) += buf[c * rows + t] };
                }
            }
        }
        for &s in &split.top {
            unsafe { forward(sym, values, s, shared, &mut Sink::Direct, &mut tmp) };
        }
        for &s in split.top.iter().rev() {
            unsafe { backward(sym, values, s, shared, &mut tmp) };
        }
        rayon::join(
            || {
                let (shared, mut tmp) = (shared, Mat::<f64>::zeros(0, 0));
                for r in split.groups[0].iter().rev() {
                    for s in r.clone().rev() {
                        unsafe { backward(sym, values, s, shared, &mut tmp) };
                    }
                }
            },
            || {
                let (shared, mut tmp) = (shared, Mat::<f64>::zeros(0, 0));
                for r in split.groups[1].iter().rev() {
                    for s in r.clone().rev() {
                        unsafe { backward(sym, values, s, shared, &mut tmp) };
                    }
                }
            },
        );
        if let Some(o) = owned {
            x.copy_from(&o);
        }
    }
}
