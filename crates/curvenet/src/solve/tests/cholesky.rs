use super::*;
use crate::solve::kernels;
use faer::Mat;

#[test]
fn solves_a_tridiagonal_system() {
    let n = 50;
    let mut q = Csc { nrows: n, ncols: n, col_ptr: vec![0], ..Default::default() };
    for j in 0..n {
        for i in j.saturating_sub(1)..(j + 2).min(n) {
            q.row_idx.push(i as u32);
            q.values.push(if i == j { 2.0 } else { -1.0 });
        }
        q.col_ptr.push(q.row_idx.len());
    }
    let chol = Cholesky::factor(&q, "test").unwrap();
    let mut b = Mat::<f64>::zeros(n, 2);
    for i in 0..n {
        b[(i, 0)] = 1.0;
        b[(i, 1)] = i as f64;
    }
    let b0 = b.clone();
    chol.solve_in_place(b.as_mut());
    let mut r = Mat::<f64>::zeros(n, 2);
    q.mul_dense(b.as_ref(), r.as_mut());
    for c in 0..2 {
        for i in 0..n {
            assert!((r[(i, c)] - b0[(i, c)]).abs() < 1e-9);
        }
    }
}

#[test]
fn indefinite_is_an_error() {
    let q =
        Csc { nrows: 2, ncols: 2, col_ptr: vec![0, 2, 4], row_idx: vec![0, 1, 0, 1], values: vec![1.0, 2.0, 2.0, 1.0] };
    let e = Cholesky::factor(&q, "toy").err().unwrap();
    assert_eq!(e.exit_code(), 3);
}

#[test]
fn refactor_reuses_the_pattern() {
    let n = 30;
    let build = |d: f64| {
        let mut q = Csc { nrows: n, ncols: n, col_ptr: vec![0], ..Default::default() };
        for j in 0..n {
            for i in j.saturating_sub(1)..(j + 2).min(n) {
                q.row_idx.push(i as u32);
                q.values.push(if i == j { d } else { -1.0 });
            }
            q.col_ptr.push(q.row_idx.len());
        }
        q
    };
    let a = Cholesky::factor(&build(2.5), "a").unwrap();
    let q = build(4.0);
    let b = a.refactor(&q, "b").unwrap();
    let mut x = Mat::<f64>::ones(n, 1);
    b.solve_in_place(x.as_mut());
    let mut r = Mat::<f64>::zeros(n, 1);
    q.mul_dense(x.as_ref(), r.as_mut());
    assert!((0..n).all(|i| (r[(i, 0)] - 1.0).abs() < 1e-12));
    assert!(std::sync::Arc::ptr_eq(&a.symbolic, &b.symbolic));
}

/// The 5-point Laplacian of a k × k grid plus a small shift (SPD).
fn grid(k: usize) -> Csc {
    crate::solve::sparse::grid_laplacian(k, 4.01)
}

#[test]
fn tree_solves_match_the_sequential_solve() {
    // The squared grid Laplacian: a two-ring stencil like the surfacing systems'.
    let l = grid(80);
    let q = crate::solve::sparse::product(&l, &vec![1.0; l.ncols], &l, 0);
    let n = q.ncols;
    for ordering in [Ordering::Amd, Ordering::NestedDissection] {
        let chol = Cholesky::factor_ordered(&q, "grid", ordering).unwrap();
        assert!(chol.symbolic.split.is_some(), "{ordering:?}: the elimination tree should split");
        for k in [1usize, 3, 6, 9] {
            let mut b = Mat::<f64>::zeros(n, k);
            for c in 0..k {
                for i in 0..n {
                    b[(i, c)] = ((i * 7 + c * 13) % 17) as f64 - 8.0;
                }
            }
            let mut x = b.clone();
            chol.solve_in_place(x.as_mut());
            let mut reference = b.clone();
            chol.solve_seq(reference.as_mut());
            let mut r = Mat::<f64>::zeros(n, k);
            q.mul_dense(x.as_ref(), r.as_mut());
            for c in 0..k {
                for i in 0..n {
                    assert!((r[(i, c)] - b[(i, c)]).abs() < 1e-9, "{ordering:?} k={k}: residual at ({i}, {c})");
                    assert!((x[(i, c)] - reference[(i, c)]).abs() < 1e-9 * (1.0 + reference[(i, c)].abs()));
                }
            }
        }
    }
}

/// A singular system factored along patches names the patch of the failing unknown.
#[test]
fn a_singular_system_names_the_patch() {
    // Two decoupled blocks: unknowns 0..3 (patch 0, positive definite) and 3..6 (patch 1, the
    // singular path Laplacian with no constrained vertex).
    let n = 6;
    let mut q = Csc { nrows: n, ncols: n, col_ptr: vec![0], ..Default::default() };
    for j in 0..n {
        let (lo, hi) = if j < 3 { (0, 3) } else { (3, 6) };
        for i in j.saturating_sub(1).max(lo)..(j + 2).min(hi) {
            q.row_idx.push(i as u32);
            let diag = if j < 3 {
                2.0
            } else if j == 3 || j == 5 {
                1.0
            } else {
                2.0
            };
            q.values.push(if i == j { diag } else { -1.0 });
        }
        q.col_ptr.push(q.row_idx.len());
    }
    let Err(e) = Cholesky::factor_in_parts(&q, "test system", Some(&[0, 0, 0, 1, 1, 1])) else { panic!("factored") };
    let e = e.to_string();
    assert!(e.contains("test system") && e.contains("of patch 1"), "{e}");
}

/// A supernode's block `[T; B]` (`T` lower triangular with a positive diagonal), column-major
/// `(w + m) × w`, with deterministic pseudo-random values.
fn block(w: usize, m: usize, seed: u64) -> Vec<f64> {
    let h = w + m;
    let mut state = seed.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
    let mut next = || {
        state = state.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
        ((state >> 11) as f64 / (1u64 << 53) as f64) - 0.5
    };
    let mut b = vec![0.0; h * w];
    for j in 0..w {
        for i in j..h {
            b[j * h + i] = if i == j { 1.5 + next().abs() } else { next() };
        }
    }
    b
}

#[test]
fn supernode_kernels_match_dense_substitution() {
    for (w, m) in [(1, 0), (1, 5), (3, 2), (4, 0), (4, 9), (5, 1), (8, 8), (13, 33), (16, 7)] {
        let h = w + m;
        let l = block(w, m, (w * 100 + m) as u64);
        for k in [1, 3, 6] {
            let z0: Vec<f64> = (0..h * k).map(|i| ((i * 37 % 101) as f64) / 50.0 - 1.0).collect();
            // Forward, densely: x = T⁻¹ z_top, z_bottom − B x.
            let mut want = z0.clone();
            for c in 0..k {
                let zc = &mut want[c * h..(c + 1) * h];
                for j in 0..w {
                    zc[j] /= l[j * h + j];
                    for i in j + 1..h {
                        zc[i] -= l[j * h + i] * zc[j];
                    }
                }
            }
            let mut got = z0.clone();
            kernels::forward(&l, w, h, k, &mut got);
            for (a, b) in got.iter().zip(&want) {
                assert!((a - b).abs() <= 1e-12 * (1.0 + b.abs()), "forward w={w} m={m} k={k}: {a} vs {b}");
            }
            // Backward, densely: x = T⁻ᵀ (z_top − Bᵀ z_bottom).
            let mut want = z0.clone();
            for c in 0..k {
                let zc = &mut want[c * h..(c + 1) * h];
                for j in (0..w).rev() {
                    let s: f64 = (j + 1..h).map(|i| l[j * h + i] * zc[i]).sum();
                    zc[j] = (zc[j] - s) / l[j * h + j];
                }
            }
            let mut got = z0.clone();
            kernels::backward(&l, w, h, k, &mut got);
            for (a, b) in got.iter().zip(&want) {
                assert!((a - b).abs() <= 1e-12 * (1.0 + b.abs()), "backward w={w} m={m} k={k}: {a} vs {b}");
            }
            // The vector path gives the same bits as the portable one.
            #[cfg(target_arch = "x86_64")]
            if std::is_x86_feature_detected!("avx2") {
                let (mut a, mut b) = (z0.clone(), z0.clone());
                kernels::forward_generic::<false>(&l, w, h, k, &mut a);
                kernels::forward(&l, w, h, k, &mut b);
                assert_eq!(a, b, "forward bits w={w} m={m} k={k}");
                kernels::backward_generic::<false>(&l, w, h, k, &mut a);
                kernels::backward(&l, w, h, k, &mut b);
                assert_eq!(a, b, "backward bits w={w} m={m} k={k}");
            }
        }
    }
}
