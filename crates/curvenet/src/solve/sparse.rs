//! A compressed sparse column matrix with `u32` row indices and the few products the methods
//! need, assembled directly in compressed form (Gustavson's column-by-column algorithm) rather
//! than through triplets.

use faer::{Mat, MatMut, MatRef};
use rayon::prelude::*;

/// A sparse matrix in compressed-column form; row indices sorted within each column.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Csc {
    /// Number of rows.
    pub nrows: usize,
    /// Number of columns.
    pub ncols: usize,
    /// Start of each column in `row_idx` and `values`, `ncols + 1`.
    pub col_ptr: Vec<usize>,
    /// Row of each stored entry, sorted within each column.
    pub row_idx: Vec<u32>,
    /// Value of each stored entry.
    pub values: Vec<f64>,
}

impl Csc {
    /// Row indices and values of column `j`.
    pub fn col(&self, j: usize) -> (&[u32], &[f64]) {
        let r = self.col_ptr[j]..self.col_ptr[j + 1];
        (&self.row_idx[r.clone()], &self.values[r])
    }

    /// Number of stored entries.
    pub fn nnz(&self) -> usize {
        self.row_idx.len()
    }

    /// Entry `(i, j)` (0 when not stored).
    pub fn get(&self, i: usize, j: usize) -> f64 {
        let (rows, vals) = self.col(j);
        match rows.binary_search(&(i as u32)) {
            Ok(k) => vals[k],
            Err(_) => 0.0,
        }
    }

    /// `y = Aᵀ x` for dense `x` (`nrows × k`) and `y` (`ncols × k`): one gather per column of
    /// `A`, columns in parallel (the two-level cycle's restriction and, through the stored
    /// transpose, its prolongation).
    pub fn tr_mul_dense(&self, x: &Mat<f64>, y: &mut Mat<f64>) {
        for c in 0..x.ncols() {
            let xc = x.col_as_slice(c);
            y.col_as_slice_mut(c).par_iter_mut().with_min_len(8192).enumerate().for_each(|(j, yj)| {
                let (rows, vals) = self.col(j);
                *yj = rows.iter().zip(vals).map(|(&i, &v)| v * xc[i as usize]).sum();
            });
        }
    }

    /// `y = A x` for dense `x` (`ncols × k`) and `y` (`nrows × k`).
    pub fn mul_dense(&self, x: MatRef<'_, f64>, mut y: MatMut<'_, f64>) {
        y.fill(0.0);
        for c in 0..x.ncols() {
            for j in 0..self.ncols {
                let xj = x[(j, c)];
                if xj == 0.0 {
                    continue;
                }
                let (rows, vals) = self.col(j);
                for (&i, &v) in rows.iter().zip(vals) {
                    y[(i as usize, c)] += v * xj;
                }
            }
        }
    }

    /// `y = A x` for a **symmetric** `A` (rows gathered from columns), in parallel over the rows.
    pub fn sym_mul_dense(&self, x: MatRef<'_, f64>, mut y: MatMut<'_, f64>) {
        for c in 0..x.ncols() {
            let xc = x.col(c);
            let yc: Vec<f64> = (0..self.ncols)
                .into_par_iter()
                .with_min_len(8192)
                .map(|i| {
                    let (rows, vals) = self.col(i);
                    rows.iter().zip(vals).map(|(&j, &v)| v * xc[j as usize]).sum()
                })
                .collect();
            for (i, v) in yc.into_iter().enumerate() {
                y[(i, c)] = v;
            }
        }
    }

    /// Adds `d[i]` to the diagonal entries (which must be stored).
    pub fn add_diagonal(&mut self, d: &[f64]) {
        for j in 0..self.ncols.min(d.len()) {
            if d[j] == 0.0 {
                continue;
            }
            let r = self.col_ptr[j]..self.col_ptr[j + 1];
            if let Ok(k) = self.row_idx[r.clone()].binary_search(&(j as u32)) {
                self.values[r.start + k] += d[j];
            }
        }
    }

    /// The submatrix of rows and columns `first..`, times `scale`.
    pub fn restrict(&self, first: usize, scale: f64) -> Csc {
        let m = self.ncols - first;
        let mut out = Csc { nrows: self.nrows - first, ncols: m, col_ptr: vec![0], ..Default::default() };
        for j in first..self.ncols {
            let (rows, vals) = self.col(j);
            for (&i, &v) in rows.iter().zip(vals) {
                if i as usize >= first {
                    out.row_idx.push(i - first as u32);
                    out.values.push(scale * v);
                }
            }
            out.col_ptr.push(out.row_idx.len());
        }
        out
    }

    /// `self + scale · other` (same shape; the pattern is the union).
    pub fn add_scaled(&self, other: &Csc, scale: f64) -> Csc {
        let mut out = Csc { nrows: self.nrows, ncols: self.ncols, col_ptr: vec![0], ..Default::default() };
        for j in 0..self.ncols {
            let ((ra, va), (rb, vb)) = (self.col(j), other.col(j));
            let (mut a, mut b) = (0, 0);
            while a < ra.len() || b < rb.len() {
                let (ia, ib) = (ra.get(a).copied().unwrap_or(u32::MAX), rb.get(b).copied().unwrap_or(u32::MAX));
                if ia == ib {
                    out.row_idx.push(ia);
                    out.values.push(va[a] + scale * vb[b]);
                    a += 1;
                    b += 1;
                } else if ia < ib {
                    out.row_idx.push(ia);
                    out.values.push(va[a]);
                    a += 1;
                } else {
                    out.row_idx.push(ib);
                    out.values.push(scale * vb[b]);
                    b += 1;
                }
            }
            out.col_ptr.push(out.row_idx.len());
        }
        out
    }

    /// Builds an `n × m` matrix from `(row, col, value)` triplets; duplicates are summed.
    pub fn from_triplets(nrows: usize, ncols: usize, mut triplets: Vec<(u32, u32, f64)>) -> Csc {
        triplets.sort_unstable_by_key(|t| (t.1, t.0));
        let mut c = Csc { nrows, ncols, col_ptr: vec![0; ncols + 1], row_idx: Vec::new(), values: Vec::new() };
        let mut last: Option<(u32, u32)> = None;
        for (i, j, v) in triplets {
            if last == Some((i, j)) {
                if let Some(x) = c.values.last_mut() {
                    *x += v;
                }
                continue;
            }
            c.row_idx.push(i);
            c.values.push(v);
            c.col_ptr[j as usize + 1] += 1;
            last = Some((i, j));
        }
        for j in 0..ncols {
            c.col_ptr[j + 1] += c.col_ptr[j];
        }
        c
    }
}

/// `(A · diag(d) · B)` restricted to rows and columns `first..`, for square `A` and `B` of the
/// same size, assembled column by column (Gustavson). Entries with `d[k] = 0` are skipped, so a
/// zero weight removes row `k` of `B` from the product. Columns are built in parallel.
///
/// With `A = B = Ls` symmetric this is the Gram matrix `Σ_k d_k (Ls)_{k·}ᵀ (Ls)_{k·}` of the
/// weighted least-squares energies, e.g. `Ls M⁻¹ Ls` (docs/design.md §1).
pub fn product(a: &Csc, d: &[f64], b: &Csc, first: usize) -> Csc {
    product_impl(a, d, b, first, false, false)
}

/// The lower triangle (with the diagonal) of [`product`], for symmetric products that are only
/// factored (the Cholesky factorisation reads the lower triangle): half the work and memory.
pub fn product_lower(a: &Csc, d: &[f64], b: &Csc, first: usize) -> Csc {
    product_impl(a, d, b, first, true, false)
}

/// [`product_lower`] with the pattern of the product for non-zero weights: a zero `d[k]` keeps
/// its entries, as explicit zeros. The fit systems (zero weights on the rows they leave out)
/// then have the pattern of the propagation system on the same mesh, whose symbolic
/// analysis their factorisation shares ([`crate::solve::system::Eliminated::refactor`]).
pub fn product_lower_keeping_pattern(a: &Csc, d: &[f64], b: &Csc, first: usize) -> Csc {
    product_impl(a, d, b, first, true, true)
}

fn product_impl(a: &Csc, d: &[f64], b: &Csc, first: usize, lower: bool, keep: bool) -> Csc {
    let n = b.ncols;
    let m = n - first;
    const CHUNK: usize = 2048;
    let chunks: Vec<(Vec<usize>, Vec<u32>, Vec<f64>)> = (first..n)
        .collect::<Vec<_>>()
        .par_chunks(CHUNK)
        // Dense accumulators per thread, reused across its chunks (marks are column ids,
        // unique across chunks, so they need no reset).
        .map_init(
            || (vec![0.0f64; m], vec![u32::MAX; m]),
            |(acc, mark), cols| {
                let mut touched: Vec<u32> = Vec::new();
                let mut counts = Vec::with_capacity(cols.len());
                let mut rows = Vec::new();
                let mut vals = Vec::new();
                for &j in cols {
                    touched.clear();
                    let (bk, bv) = b.col(j);
                    for (&k, &bkj) in bk.iter().zip(bv) {
                        let w = d[k as usize] * bkj;
                        if w == 0.0 && !(keep && bkj != 0.0) {
                            continue;
                        }
                        let (ai, av) = a.col(k as usize);
                        for (&i, &aik) in ai.iter().zip(av) {
                            let i = i as usize;
                            if i < first || (lower && i < j) {
                                continue;
                            }
                            let r = i - first;
                            if mark[r] != j as u32 {
                                mark[r] = j as u32;
                                acc[r] = 0.0;
                                touched.push(r as u32);
                            }
                            acc[r] += aik * w;
                        }
                    }
                    touched.sort_unstable();
                    counts.push(touched.len());
                    for &r in &touched {
                        rows.push(r);
                        vals.push(acc[r as usize]);
                    }
                }
                (counts, rows, vals)
            },
        )
        .collect();
    let mut out =
        Csc { nrows: m, ncols: m, col_ptr: Vec::with_capacity(m + 1), row_idx: Vec::new(), values: Vec::new() };
    let total: usize = chunks.iter().map(|c| c.1.len()).sum();
    out.row_idx.reserve_exact(total);
    out.values.reserve_exact(total);
    out.col_ptr.push(0);
    for (counts, rows, vals) in chunks {
        for c in counts {
            let last = *out.col_ptr.last().unwrap_or(&0);
            out.col_ptr.push(last + c);
        }
        out.row_idx.extend_from_slice(&rows);
        out.values.extend_from_slice(&vals);
    }
    out
}

#[cfg(test)]
#[path = "tests/sparse.rs"]
mod tests;

/// The 5-point Laplacian of a `k × k` grid with `diagonal` on the diagonal (`> 4`: SPD), for
/// the solver and ordering tests.
#[cfg(test)]
pub(crate) fn grid_laplacian(k: usize, diagonal: f64) -> Csc {
    let mut t = Vec::new();
    for j in 0..k {
        for i in 0..k {
            let v = (j * k + i) as u32;
            t.push((v, v, diagonal));
            if i + 1 < k {
                t.push((v, v + 1, -1.0));
                t.push((v + 1, v, -1.0));
            }
            if j + 1 < k {
                t.push((v, v + k as u32, -1.0));
                t.push((v + k as u32, v, -1.0));
            }
        }
    }
    Csc::from_triplets(k * k, k * k, t)
}

/// The lower triangle of `a` (what the Cholesky factorisation takes), for the solver tests.
#[cfg(test)]
pub(crate) fn lower_triangle(a: &Csc) -> Csc {
    let mut t = Vec::new();
    for j in 0..a.ncols {
        let (rows, vals) = a.col(j);
        for (&i, &v) in rows.iter().zip(vals) {
            if i as usize >= j {
                t.push((i, j as u32, v));
            }
        }
    }
    Csc::from_triplets(a.nrows, a.ncols, t)
}
