use super::*;
use crate::solve::sparse::{grid_laplacian, lower_triangle as lower};

/// `Ls W Ls + diag` assembled (both triangles) on the rows `first..`.
fn assembled(ls: &Csc, w: &[f64], diagonal: &[f64], first: usize) -> Csc {
    let n = ls.ncols;
    let mut dense = vec![vec![0.0; n]; n];
    for k in 0..n {
        let (rows, vals) = ls.col(k);
        for (&i, &a) in rows.iter().zip(vals) {
            for (&j, &b) in rows.iter().zip(vals) {
                dense[i as usize][j as usize] += a * w[k] * b;
            }
        }
    }
    let mut t = Vec::new();
    for i in first..n {
        for j in first..n {
            let v = dense[i][j] + if i == j { diagonal[i] } else { 0.0 };
            if v != 0.0 {
                t.push(((i - first) as u32, (j - first) as u32, v));
            }
        }
    }
    Csc::from_triplets(n - first, n - first, t)
}

#[test]
fn the_prolongation_leaves_out_curve_corners_and_checks_the_systems() {
    // Fine: 2 curve vertices, 3 free ones; coarse: 1 curve vertex, 2 free ones.
    let locations: Vec<Location> =
        vec![(2, [0, 1, 2], [0.5, 0.25, 0.25]), (3, [1, 2, 0], [1.0, 0.0, 0.0]), (4, [0, 2, 1], [0.2, 0.3, 0.5])];
    let q = grid_laplacian(1, 3.0);
    let two = Csc::from_triplets(2, 2, vec![(0, 0, 2.0), (1, 1, 2.0)]);
    let system = |a: &Csc| Eliminated::factor(&lower(a), 1, None, "test").unwrap();
    let normals = [DVec3::Z, DVec3::X, DVec3::Y];
    let coarse = Coarse::new(&locations, (2, 5), (1, 3), (system(&two), None), Some(&normals)).unwrap();
    assert_eq!((coarse.p.nrows, coarse.p.ncols), (3, 2));
    let dense = |i: usize, j: usize| {
        let (rows, vals) = coarse.p.col(j);
        rows.iter().zip(vals).find(|(r, _)| **r as usize == i).map_or(0.0, |(_, v)| *v)
    };
    // Coarse vertex 0 is on a curve: its weights are dropped (the correction is zero there).
    assert_eq!(
        [dense(0, 0), dense(0, 1), dense(1, 0), dense(1, 1), dense(2, 0), dense(2, 1)],
        [0.25, 0.25, 1.0, 0.0, 0.5, 0.3]
    );
    // The transpose is stored too, and the coarse normals are interpolated and normalised.
    assert_eq!((coarse.pt.nrows, coarse.pt.ncols), (2, 3));
    let start = coarse.normals_start.as_ref().unwrap();
    let n0 = (0.5 * DVec3::Z + 0.25 * DVec3::X + 0.25 * DVec3::Y).normalize();
    assert!((start[(0, 0)] - n0.x).abs() < 1e-15 && (start[(0, 2)] - n0.z).abs() < 1e-15);
    // A coarse system on other unknowns, or a location outside the fine mesh: no coarse level.
    assert!(Coarse::new(&locations, (2, 5), (1, 3), (system(&q), None), None).is_none());
    assert!(Coarse::new(&locations, (2, 4), (1, 3), (system(&two), None), None).is_none());
}

#[test]
fn with_an_exact_coarse_level_the_fine_system_is_solved_in_one_iteration() {
    // P = identity and the coarse system the fine one itself: one iteration, the direct
    // solution, from any start.
    let k = 12;
    let ls = grid_laplacian(k, 4.0);
    let n = ls.ncols;
    let first = 5;
    let w: Vec<f64> = (0..n).map(|i| 1.0 + (i % 7) as f64 * 0.1).collect();
    let diagonal = vec![1e-3; n];
    let q = assembled(&ls, &w, &diagonal, first);
    let coarse = Eliminated::factor(&lower(&q), 0, None, "test").unwrap();
    let m = n - first;
    let id = Csc::from_triplets(m, m, (0..m as u32).map(|i| (i, i, 1.0)).collect());
    let system = FineSystem::new(Energy::new(&ls, &w, &diagonal, first), &coarse, &id, &id).unwrap();
    let b = Mat::from_fn(m, 3, |i, c| ((i * (c + 2)) as f64 * 0.29).cos());
    let direct = coarse.solve(b.clone());
    let (x, report) = system.solve(&b, Mat::from_fn(m, 3, |i, _| i as f64), 0.0, None);
    assert!(report.converged && report.iterations <= 2, "{report:?}");
    let err = (0..m).flat_map(|i| (0..3).map(move |c| (i, c))).map(|(i, c)| (x[(i, c)] - direct[(i, c)]).abs());
    assert!(err.fold(0.0, f64::max) < 1e-8);
    // Sizes that do not fit: no system.
    let small = Csc::from_triplets(m - 1, m - 1, vec![]);
    assert!(FineSystem::new(Energy::new(&ls, &w, &diagonal, first), &coarse, &small, &small).is_none());
}
