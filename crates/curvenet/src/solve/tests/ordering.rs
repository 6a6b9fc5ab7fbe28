use super::*;

/// The 5-point Laplacian pattern of a k × k grid.
fn grid(k: usize) -> Csc {
    crate::solve::sparse::grid_laplacian(k, 4.0)
}

#[test]
fn is_a_permutation_with_little_fill() {
    let q = grid(150);
    let order = nested_dissection_with_leaves(&q, None, 64);
    let mut seen = vec![false; q.ncols];
    for &v in &order {
        assert!(!seen[v as usize]);
        seen[v as usize] = true;
    }
    assert!(seen.iter().all(|&s| s));
    // Fill: far below the natural (banded) order's, and of the order of minimum degree's.
    let nd = crate::solve::Cholesky::factor_ordered(&q, "grid", crate::solve::Ordering::NestedDissection).unwrap();
    let amd = crate::solve::Cholesky::factor_ordered(&q, "grid", crate::solve::Ordering::Amd).unwrap();
    let banded = 150 * q.ncols; // the band of the natural order fills completely
    eprintln!("grid 150²: L nnz nested dissection {}, AMD {}, natural ≈ {banded}", nd.factor_nnz(), amd.factor_nnz());
    assert!(nd.factor_nnz() < banded / 3);
    assert!((nd.factor_nnz() as f64) < 1.5 * amd.factor_nnz() as f64);
}

#[test]
fn disconnected_parts_are_ordered() {
    let mut t = Vec::new();
    for v in 0..500u32 {
        t.push((v, v, 1.0));
    }
    let q = Csc::from_triplets(500, 500, t);
    assert_eq!(nested_dissection(&q).len(), 500);
}

#[test]
fn a_lower_triangle_gives_the_same_order() {
    let q = grid(80);
    let mut lower = Csc { nrows: q.nrows, ncols: q.ncols, col_ptr: vec![0], ..Default::default() };
    for j in 0..q.ncols {
        let (rows, vals) = q.col(j);
        for (&i, &v) in rows.iter().zip(vals) {
            if i as usize >= j {
                lower.row_idx.push(i);
                lower.values.push(v);
            }
        }
        lower.col_ptr.push(lower.row_idx.len());
    }
    assert_eq!(nested_dissection_with_leaves(&q, None, 32), nested_dissection_with_leaves(&lower, None, 32));
}

/// The propagation system of the sphere network at ~20k vertices: its free vertices and the
/// patch of each.
fn sphere_system() -> (Csc, Vec<u32>) {
    use crate::operators::{cotan_operators, Metric};
    let net = crate::network::examples::example("sphere").unwrap();
    let s = crate::surface(&net, &crate::Options::fast().with_vertices(20_000)).unwrap();
    let mesh = &s.mesh;
    let ops = cotan_operators(mesh, Metric::Planar, &mesh.positions);
    let inv_m: Vec<f64> = ops.mass.iter().map(|a| 1.0 / a).collect();
    let q = crate::solve::sparse::product(&ops.ls, &inv_m, &ops.ls, mesh.num_curve);
    (q, mesh.free_vertex_patches())
}

#[test]
fn dissection_along_patches_has_less_fill() {
    use crate::solve::{Cholesky, Ordering};
    let (q, parts) = sphere_system();
    let order = nested_dissection_in_parts(&q, &parts);
    let in_parts = Cholesky::factor_permuted(&q, "sphere", &order).unwrap();
    let levels = Cholesky::factor_ordered(&q, "sphere", Ordering::NestedDissection).unwrap();
    let amd = Cholesky::factor_ordered(&q, "sphere", Ordering::Amd).unwrap();
    let (p, l, a) = (in_parts.factor_nnz(), levels.factor_nnz(), amd.factor_nnz());
    eprintln!("sphere {} unknowns: L nnz in parts {p}, by levels {l}, AMD {a}", q.ncols);
    // Measured: 2.07M, 2.90M, 2.67M.
    assert!((p as f64) < 0.85 * a as f64 && p < l);
    // The factorisation is right: a solve has a small residual.
    let mut x = faer::Mat::<f64>::ones(q.ncols, 2);
    in_parts.solve_in_place(x.as_mut());
    let mut r = faer::Mat::<f64>::zeros(q.ncols, 2);
    q.sym_mul_dense(x.as_ref(), r.as_mut());
    let worst = (0..q.ncols).map(|i| (r[(i, 0)] - 1.0).abs().max((r[(i, 1)] - 1.0).abs())).fold(0.0, f64::max);
    assert!(worst < 1e-6, "residual {worst}");
}

#[test]
fn a_wrong_permutation_is_an_error() {
    let q = grid(10);
    let mut order: Vec<u32> = (0..q.ncols as u32).collect();
    order[3] = 5;
    assert!(crate::solve::Cholesky::factor_permuted(&q, "grid", &order).is_err());
    assert!(crate::solve::Cholesky::factor_permuted(&q, "grid", &order[1..]).is_err());
}
