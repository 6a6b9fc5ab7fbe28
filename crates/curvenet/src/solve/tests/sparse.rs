use super::*;

/// Dense → Csc.
pub(crate) fn from_dense(a: &[Vec<f64>]) -> Csc {
    let (n, m) = (a.len(), a[0].len());
    let mut c = Csc { nrows: n, ncols: m, col_ptr: vec![0], ..Default::default() };
    for j in 0..m {
        for (i, row) in a.iter().enumerate() {
            if row[j] != 0.0 {
                c.row_idx.push(i as u32);
                c.values.push(row[j]);
            }
        }
        c.col_ptr.push(c.row_idx.len());
    }
    c
}

#[test]
fn product_matches_dense() {
    let a = vec![vec![2.0, -1.0, 0.0], vec![-1.0, 2.0, -1.0], vec![0.0, -1.0, 1.0]];
    let d = [0.5, 0.0, 3.0];
    let ca = from_dense(&a);
    let p = product(&ca, &d, &ca, 1);
    for i in 1..3 {
        for j in 1..3 {
            let want: f64 = (0..3).map(|k| a[i][k] * d[k] * a[k][j]).sum();
            assert!((p.get(i - 1, j - 1) - want).abs() < 1e-15, "{i} {j}");
        }
    }
}

#[test]
fn triplets_sum_duplicates() {
    let c = Csc::from_triplets(3, 2, vec![(2, 1, 1.0), (0, 0, 2.0), (2, 1, 0.5), (1, 1, -1.0)]);
    assert_eq!(c.col_ptr, vec![0, 1, 3]);
    assert_eq!(c.row_idx, vec![0, 1, 2]);
    assert_eq!(c.values, vec![2.0, -1.0, 1.5]);
}

#[test]
fn restrict_and_add() {
    let a = from_dense(&[vec![1.0, 2.0, 0.0], vec![0.0, 3.0, 4.0], vec![5.0, 0.0, 6.0]]);
    let b = from_dense(&[vec![0.0, 1.0, 1.0], vec![1.0, 0.0, 0.0], vec![0.0, 0.0, 1.0]]);
    let c = a.add_scaled(&b, 2.0);
    for (i, row) in [[1.0, 4.0, 2.0], [2.0, 3.0, 4.0], [5.0, 0.0, 8.0]].iter().enumerate() {
        for j in 0..3 {
            assert_eq!(c.get(i, j), row[j]);
        }
    }
    let r = a.restrict(1, -1.0);
    assert_eq!((r.nrows, r.ncols), (2, 2));
    assert_eq!((r.get(0, 0), r.get(0, 1), r.get(1, 0), r.get(1, 1)), (-3.0, -4.0, 0.0, -6.0));
}

#[test]
fn a_zero_weight_keeps_its_entries_when_asked() {
    // A path graph's Laplacian-like matrix: with d[2] = 0 the plain product loses the
    // coupling of unknowns 1 and 3 through row 2; the pattern-keeping one stores it as an
    // explicit zero, so that both products with and without the zero weight share a pattern.
    let a = vec![
        vec![2.0, -1.0, 0.0, 0.0, 0.0],
        vec![-1.0, 2.0, -1.0, 0.0, 0.0],
        vec![0.0, -1.0, 2.0, -1.0, 0.0],
        vec![0.0, 0.0, -1.0, 2.0, -1.0],
        vec![0.0, 0.0, 0.0, -1.0, 2.0],
    ];
    let ca = from_dense(&a);
    let zero = [1.0, 0.5, 0.0, 2.0, 1.0];
    let full = [1.0, 0.5, 3.0, 2.0, 1.0];
    let plain = product_lower(&ca, &zero, &ca, 1);
    let kept = product_lower_keeping_pattern(&ca, &zero, &ca, 1);
    let other = product_lower(&ca, &full, &ca, 1);
    assert_ne!((&plain.col_ptr, &plain.row_idx), (&other.col_ptr, &other.row_idx));
    assert_eq!((&kept.col_ptr, &kept.row_idx), (&other.col_ptr, &other.row_idx));
    // The same values: the kept entries are zeros.
    for i in 0..4 {
        for j in 0..=i {
            assert_eq!(kept.get(i, j), plain.get(i, j), "{i} {j}");
        }
    }
    assert!(kept.row_idx.len() > plain.row_idx.len());
}
