use super::*;

/// A planar grid on [0, 1]² (z = 0), jittered so that the weights are not uniform.
fn grid(m: usize) -> (Vec<DVec3>, Vec<[u32; 3]>) {
    let mut p = Vec::new();
    for j in 0..=m {
        for i in 0..=m {
            let inner = i > 0 && i < m && j > 0 && j < m;
            let jitter = if inner { 0.2 * ((i * 7 + j * 13) % 5) as f64 / 5.0 - 0.1 } else { 0.0 };
            p.push(DVec3::new((i as f64 + jitter) / m as f64, (j as f64 - jitter) / m as f64, 0.0));
        }
    }
    let id = |i: usize, j: usize| (j * (m + 1) + i) as u32;
    let mut f = Vec::new();
    for j in 0..m {
        for i in 0..m {
            f.push([id(i, j), id(i + 1, j), id(i + 1, j + 1)]);
            f.push([id(i, j), id(i + 1, j + 1), id(i, j + 1)]);
        }
    }
    (p, f)
}

/// Linear functions are k-harmonic for the cotangent Laplacian on a planar mesh when k rings
/// at the border are fixed: the solution reproduces them (fixed vertices listed out of order).
#[test]
fn reproduces_linear_functions() {
    let m = 24;
    let (p, f) = grid(m);
    let value = |q: DVec3| [2.0 * q.x - q.y + 0.5, q.x + 3.0 * q.y];
    for k in 1..=3 {
        let band = k as f64 / m as f64 + 1e-9;
        let mut fixed: Vec<usize> =
            (0..p.len()).filter(|&v| p[v].x.min(p[v].y).min(1.0 - p[v].x).min(1.0 - p[v].y) < band).collect();
        fixed.reverse();
        let values: Vec<f64> = fixed.iter().flat_map(|&v| value(p[v])).collect();
        let x = harmonic(&p, &f, &fixed, &values, 2, k).unwrap();
        let err = (0..p.len())
            .map(|v| (x[2 * v] - value(p[v])[0]).abs().max((x[2 * v + 1] - value(p[v])[1]).abs()))
            .fold(0.0, f64::max);
        assert!(err < 1e-10, "k = {k}: error {err:e}");
        // Not trivially all fixed.
        assert!(fixed.len() < p.len() / 2, "k = {k}: {} of {} fixed", fixed.len(), p.len());
    }
}

#[test]
fn errors_name_the_problem() {
    let (p, f) = grid(4);
    let e = harmonic(&p, &f, &[0, 0], &[0.0, 1.0], 1, 2).unwrap_err().to_string();
    assert!(e.contains("fixed vertex 0 is listed twice"), "{e}");
    let e = harmonic(&p, &f, &[0, 99], &[0.0, 1.0], 1, 2).unwrap_err().to_string();
    assert!(e.contains("fixed vertex 99"), "{e}");
    let e = harmonic(&p, &f, &[0], &[0.0, 1.0], 1, 2).unwrap_err().to_string();
    assert!(e.contains("need 1 values, got 2"), "{e}");
    let e = harmonic(&p, &f, &[0], &[0.0], 1, 4).unwrap_err().to_string();
    assert!(e.contains("k = 4"), "{e}");
    let e = harmonic(&p, &[[0, 1, 77]], &[0], &[0.0], 1, 2).unwrap_err().to_string();
    assert!(e.contains("face 0, corner 2"), "{e}");
    let e = harmonic(&p, &f, &[], &[], 1, 2).unwrap_err().to_string();
    assert!(e.contains("no fixed vertex"), "{e}");
}
