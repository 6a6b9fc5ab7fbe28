//! Dense kernels of the supernodal triangular solves with a few right-hand sides (`k ≤ ~9`
//! columns). A supernode's block of `L` is column-major, `h = w + m` rows (its `w` columns,
//! then its `m` pattern rows) by `w` columns; the right-hand sides `z` are column-major `h × k`
//! too: the supernode's own rows, then its pattern's.
//!
//! Both passes sweep the block four columns at a time, each column from the diagonal down in
//! memory order (four sequential streams; the next four columns, and the next supernode's
//! first four, prefetched whole: without it the solves wait on memory, not on arithmetic): the
//! forward pass solves the 4 × 4 triangle and subtracts the four columns times the solved
//! values from every row below (own rows and pattern rows in one sweep); the backward pass
//! takes the four dot products with the rows below, then solves the triangle. The triangles
//! of all right-hand sides are solved side by side (their divisions overlap). Each value of
//! `L` is read from memory once per pass. The loops use AVX2 when the processor has it (checked at run time);
//! no fused multiply–add, and the same order of operations on both paths: the same bits.

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
                let b = [column(j0, j0 + 4), column(j0 + 1, j0 + 4), column(j0 + 2, j0 + 4), column(j0 + 3, j0 + 4)];
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
                let b = [column(j0, j0 + 4), column(j0 + 1, j0 + 4), column(j0 + 2, j0 + 4), column(j0 + 3, j0 + 4)];
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
    // Advanced by the vector loop on x86-64 only.
    #[cfg_attr(not(target_arch = "x86_64"), allow(unused_mut))]
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
