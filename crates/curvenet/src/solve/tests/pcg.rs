use super::*;
use crate::solve::sparse::{grid_laplacian, lower_triangle as lower, product};

/// Three deterministic right-hand sides.
fn rhs(n: usize) -> Mat<f64> {
    Mat::from_fn(n, 3, |i, c| ((i * (c + 3)) as f64 * 0.37).sin() + 0.1 * c as f64)
}

fn max_diff(a: &Mat<f64>, b: &Mat<f64>) -> f64 {
    let mut m = 0.0f64;
    for c in 0..a.ncols() {
        for i in 0..a.nrows() {
            m = m.max((a[(i, c)] - b[(i, c)]).abs());
        }
    }
    m
}

#[test]
fn conjugate_gradients_reach_the_direct_solution() {
    // Nearly singular (diagonal 4.05): plain CG needs many iterations, Jacobi as many here
    // (a constant diagonal), both reach the factorisation's solution.
    let a = grid_laplacian(24, 4.05);
    let n = a.nrows;
    let b = rhs(n);
    let direct = Eliminated::factor(&lower(&a), 0, None, "test").unwrap().solve(b.clone());
    let scale = (0..n).map(|i| direct[(i, 0)].abs()).fold(0.0, f64::max);
    for (name, m) in [("identity", &Identity as &dyn Preconditioner), ("jacobi", &Jacobi::new(&vec![4.05; n]))] {
        let mut x = Mat::<f64>::zeros(n, 3);
        let report = pcg(&a, m, b.as_ref(), x.as_mut(), 1e-12, 2000);
        assert!(report.converged, "{name}: {:?}", report.residuals.last());
        assert!(report.iterations > 20, "{name}: {} iterations", report.iterations);
        let d = max_diff(&x, &direct);
        assert!(d <= 1e-9 * scale, "{name}: {d:e}");
        // The residuals are those of the solution it returns.
        let mut ax = Mat::<f64>::zeros(n, 3);
        a.apply(x.as_ref(), ax.as_mut());
        assert!(max_diff(&ax, &b) <= 1e-10 * 3.0 * (n as f64).sqrt());
    }
}

#[test]
fn a_two_level_cycle_with_an_exact_coarse_level_is_exact() {
    // P = identity and the coarse system A itself: the cycle is A⁻¹ (one iteration), additive
    // (no smoothing, ω = 0) or with smoothing.
    let a = grid_laplacian(16, 4.2);
    let n = a.nrows;
    let id = Csc::from_triplets(n, n, (0..n as u32).map(|i| (i, i, 1.0)).collect());
    let coarse = Eliminated::factor(&lower(&a), 0, None, "test").unwrap();
    let b = rhs(n);
    for (smoothing, omega) in [(0, 0.0), (1, 0.5), (2, 0.7)] {
        let inv_diag = vec![1.0 / 4.2; n];
        let m = TwoLevel { a: &a, inv_diag: &inv_diag, omega, smoothing, p: &id, pt: &id, coarse: &coarse };
        let mut x = Mat::<f64>::zeros(n, 3);
        let report = pcg(&a, &m, b.as_ref(), x.as_mut(), 1e-10, 50);
        assert!(report.converged && report.iterations == 1, "smoothing {smoothing}: {report:?}");
    }
}

#[test]
fn the_energy_operator_is_the_assembled_product() {
    // Ls W Ls on the unknowns 5.. plus a diagonal, against the assembled matrix.
    let ls = grid_laplacian(9, 4.0);
    let n = ls.nrows;
    let first = 5;
    let w: Vec<f64> = (0..n).map(|i| 1.0 + (i % 7) as f64 * 0.1).collect();
    let diagonal: Vec<f64> = (0..n).map(|i| 0.01 * (i % 3) as f64).collect();
    let e = Energy::new(&ls, &w, &diagonal, first);
    let mut q = product(&ls, &w, &ls, first);
    q.add_diagonal(&diagonal[first..]);
    let x = rhs(n - first);
    let (mut y, mut z) = (Mat::<f64>::zeros(n - first, 3), Mat::<f64>::zeros(n - first, 3));
    e.apply(x.as_ref(), y.as_mut());
    q.mul_dense(x.as_ref(), z.as_mut());
    assert!(max_diff(&y, &z) <= 1e-12 * 100.0);
    let d = e.diag();
    for (j, dj) in d.iter().enumerate() {
        assert!((dj - q.get(j, j)).abs() <= 1e-12 * 100.0, "{j}");
    }
}
