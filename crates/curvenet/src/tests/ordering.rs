use super::*;

/// The 5-point Laplacian pattern of a k × k grid.
fn grid(k: usize) -> Csc {
    let n = k * k;
    let mut t = Vec::new();
    for j in 0..k {
        for i in 0..k {
            let v = (j * k + i) as u32;
            t.push((v, v, 4.0));
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
    Csc::from_triplets(n, n, t)
}

#[test]
fn is_a_permutation_with_little_fill() {
    let q = grid(150);
    let order = nested_dissection_with_leaves(&q, 64);
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
    assert_eq!(nested_dissection_with_leaves(&q, 32), nested_dissection_with_leaves(&lower, 32));
}
