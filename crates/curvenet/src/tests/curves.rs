use super::*;
use std::f64::consts::PI;

fn circle(n: usize) -> (Vec<DVec3>, Vec<DVec3>) {
    let p: Vec<DVec3> = (0..n)
        .map(|i| {
            let a = 2.0 * PI * i as f64 / n as f64;
            DVec3::new(a.cos(), a.sin(), 0.0)
        })
        .collect();
    (p.clone(), p)
}

#[test]
fn periodic_spline_reproduces_a_circle() {
    let (p, n) = circle(16);
    let s = CurveSpline::fit(&p, &n, true);
    // Fourth-order accurate: doubling the samples divides the length error by ≈ 16.
    let e16 = (s.length() - 2.0 * PI).abs();
    let (p2, n2) = circle(32);
    let e32 = (CurveSpline::fit(&p2, &n2, true).length() - 2.0 * PI).abs();
    assert!(e16 < 3e-4 && e16 / e32 > 12.0, "{e16} {e32}");
    for k in 0..100 {
        let t = s.period() * k as f64 / 100.0;
        assert!((s.position(t).length() - 1.0).abs() < 2e-4);
        assert!((s.normal(t) - s.position(t).normalize()).length() < 1e-3);
    }
}

#[test]
fn resampling_is_uniform_and_exact_at_ends() {
    let (p, n) = circle(32);
    let s = CurveSpline::fit(&p, &n, true);
    let r = s.resample(8, 24, 40);
    assert_eq!(r.len(), 41);
    assert_eq!(r[0].0, p[8]);
    assert_eq!(r[40].0, p[24]);
    let d: Vec<f64> = r.windows(2).map(|w| w[0].0.distance(w[1].0)).collect();
    let (lo, hi) = d.iter().fold((f64::MAX, 0.0f64), |(a, b), &x| (a.min(x), b.max(x)));
    // Equal arcs; the chords differ only by the spline's tiny curvature variation.
    assert!(hi / lo < 1.0 + 1e-5, "{lo} {hi}");
    // Wrapping interval: the whole loop from sample 5.
    let r = s.resample(5, 5, 10);
    assert_eq!(r.len(), 11);
    assert_eq!(r[10].0, p[5]);
}

#[test]
fn natural_spline_through_a_line_is_the_line() {
    let p = vec![DVec3::ZERO, DVec3::new(1.0, 0.0, 0.0), DVec3::new(3.0, 0.0, 0.0)];
    let n = vec![DVec3::Z; 3];
    let s = CurveSpline::fit(&p, &n, false);
    assert!((s.length() - 3.0).abs() < 1e-12);
    let r = s.resample(0, 2, 3);
    for (k, (q, _)) in r.iter().enumerate() {
        assert!((q.x - k as f64).abs() < 1e-9 && q.y.abs() < 1e-12);
    }
    assert!((s.tangent(0.0, true) - DVec3::X).length() < 1e-12);
    let t_end = s.tangent(s.period(), false);
    assert!((t_end - DVec3::X).length() < 1e-12);
}
