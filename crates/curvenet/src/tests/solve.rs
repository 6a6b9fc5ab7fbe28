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
