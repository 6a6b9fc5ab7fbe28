use super::*;
use crate::geom::DVec3;

fn line(a: DVec3, b: DVec3, n: usize) -> Curve {
    let points = (0..n).map(|i| a.lerp(b, i as f64 / (n - 1) as f64)).collect();
    Curve { points, ..Default::default() }
}

fn run(curves: Vec<Curve>, gap: f64) -> Consolidated {
    let net = Network { curves, snap: None, cycles: None };
    consolidate(&net, &ConsolidateOptions { enabled: true, gap: Some(gap) }, Some(1e-4)).unwrap()
}

/// The distance from `p` to the polyline of `c`.
fn distance_to(c: &Curve, p: DVec3) -> f64 {
    let n = c.points.len();
    let m = if c.closed { n } else { n - 1 };
    (0..m)
        .map(|i| {
            let (a, b) = (c.points[i], c.points[(i + 1) % n]);
            let ab = b - a;
            let t = ((p - a).dot(ab) / ab.length_squared()).clamp(0.0, 1.0);
            p.distance(a + t * ab)
        })
        .fold(f64::INFINITY, f64::min)
}

#[test]
fn a_stroke_that_stops_short_ends_on_the_other_one() {
    let a = line(DVec3::new(0.0, 0.0, 0.0), DVec3::new(1.0, 0.0, 0.0), 11);
    let b = line(DVec3::new(0.5, 0.02, 0.0), DVec3::new(0.5, 1.0, 0.0), 11);
    let c = run(vec![a.clone(), b], 0.05);
    assert_eq!(c.report.joined, 1, "{:?}", c.report);
    let end = c.network.curves[1].points[0];
    assert!(distance_to(&c.network.curves[0], end) < 1e-12, "{end}");
    // The stroke joined onto is not changed, only named by its input place (as the changed
    // ones are), so that messages keep the input's numbers.
    let kept = &c.network.curves[0];
    assert_eq!(kept.name.as_deref(), Some("curve 0"));
    assert_eq!(crate::Curve { name: None, ..kept.clone() }, a, "the stroke joined onto is not changed");
}

#[test]
fn an_overshoot_is_cut_back_to_the_crossing() {
    let a = line(DVec3::new(0.0, 0.0, 0.0), DVec3::new(1.0, 0.0, 0.0), 11);
    let b = line(DVec3::new(0.5, -0.03, 0.001), DVec3::new(0.5, 1.0, 0.001), 11);
    let c = run(vec![a, b], 0.05);
    assert_eq!(c.report.joined, 1, "{:?}", c.report);
    assert!(c.report.trimmed >= 1, "{:?}", c.report);
    let b = &c.network.curves[1];
    assert!(b.points.iter().all(|p| p.y >= -1e-9), "stub left: {:?}", b.points);
    assert!(distance_to(&c.network.curves[0], b.points[0]) < 1e-12);
}

#[test]
fn two_ends_that_nearly_meet_make_one_corner() {
    let a = line(DVec3::new(0.0, 0.0, 0.0), DVec3::new(1.0, 0.0, 0.0), 11);
    let b = line(DVec3::new(1.01, 0.01, 0.0), DVec3::new(1.0, 1.0, 0.0), 11);
    let c = run(vec![a, b], 0.05);
    assert!(c.report.joined >= 1, "{:?}", c.report);
    let (a, b) = (&c.network.curves[0], &c.network.curves[1]);
    let (ea, eb) = (a.points[a.points.len() - 1], b.points[0]);
    assert!(ea.distance(eb) < 1e-12, "{ea} {eb}");
}

#[test]
fn a_stroke_drawn_twice_becomes_one_curve_at_the_average() {
    let a = line(DVec3::new(0.0, 0.0, 0.0), DVec3::new(1.0, 0.0, 0.0), 21);
    let b = line(DVec3::new(0.0, 0.01, 0.0), DVec3::new(1.0, 0.01, 0.0), 17);
    let cross = line(DVec3::new(0.5, -0.5, 0.0), DVec3::new(0.5, 0.5, 0.0), 11);
    let c = run(vec![a, b, cross], 0.05);
    assert_eq!(c.report.merged, 1, "{:?}", c.report);
    assert_eq!(c.network.curves.len(), 2, "{:?}", c.network.curves.iter().map(|c| &c.name).collect::<Vec<_>>());
    let mid = &c.network.curves[0];
    let y = mid.points[mid.points.len() / 2].y;
    assert!((y - 0.005).abs() < 1e-3, "averaged to {y}");
}

#[test]
fn a_stroke_retraced_over_itself_keeps_one_pass() {
    let mut a = line(DVec3::new(0.0, 0.0, 0.0), DVec3::new(1.0, 0.0, 0.0), 21);
    let back = line(DVec3::new(1.0, 0.005, 0.0), DVec3::new(0.3, 0.005, 0.0), 15);
    a.points.extend(back.points);
    let c = run(vec![a], 0.05);
    assert_eq!(c.report.merged, 1, "{:?}", c.report);
    let total: f64 = c.network.curves.iter().map(curve_length).sum();
    assert!((total - 1.0).abs() < 0.06, "one pass of length 1 left, got {total}");
}

#[test]
fn a_hook_at_a_stroke_end_is_trimmed() {
    let mut a = line(DVec3::new(0.0, 0.0, 0.0), DVec3::new(1.0, 0.0, 0.0), 21);
    a.points.push(DVec3::new(0.99, 0.02, 0.0));
    a.points.push(DVec3::new(0.985, 0.015, 0.0));
    let c = run(vec![a], 0.05);
    assert!(c.report.trimmed >= 1, "{:?}", c.report);
    let p = &c.network.curves[0].points;
    assert!(p.iter().all(|q| q.y.abs() < 1e-9), "{p:?}");
}

#[test]
fn a_loop_whose_ends_nearly_meet_is_closed() {
    let n = 40;
    let points: Vec<DVec3> = (0..n)
        .map(|i| {
            let t = 0.97 * std::f64::consts::TAU * i as f64 / (n - 1) as f64;
            DVec3::new(t.cos(), t.sin(), 0.0)
        })
        .collect();
    let c = run(vec![Curve { points, ..Default::default() }], 0.3);
    assert_eq!(c.report.joined, 1, "{:?}", c.report);
    assert!(c.network.curves[0].closed);
}

#[test]
fn a_clean_network_comes_back_as_it_was() {
    for (name, _) in crate::network::examples::EXAMPLES {
        let Some(net) = crate::network::examples::example(name) else { continue };
        let c = consolidate(&net, &ConsolidateOptions::default(), None).unwrap();
        assert!(!c.changed(), "{name}: {:?} {:?}", c.report, c.warnings);
        assert_eq!(c.network, net, "{name}");
    }
}

#[test]
fn off_changes_nothing() {
    let a = line(DVec3::new(0.0, 0.0, 0.0), DVec3::new(1.0, 0.0, 0.0), 11);
    let b = line(DVec3::new(0.5, 0.02, 0.0), DVec3::new(0.5, 1.0, 0.0), 11);
    let net = Network { curves: vec![a, b], snap: None, cycles: None };
    let c = consolidate(&net, &ConsolidateOptions { enabled: false, gap: None }, None).unwrap();
    assert_eq!(c.network, net);
    assert!(!c.changed());
}
