use super::*;
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
    crate::sparse::grid_laplacian(k, 4.01)
}

#[test]
fn tree_solves_match_the_sequential_solve() {
    // The squared grid Laplacian: a two-ring stencil like the surfacing systems'.
    let l = grid(80);
    let q = crate::sparse::product(&l, &vec![1.0; l.ncols], &l, 0);
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
