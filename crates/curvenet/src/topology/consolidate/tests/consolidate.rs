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

/// The smallest distance between the polylines of two curves (at their vertices).
fn curves_apart(a: &Curve, b: &Curve) -> f64 {
    a.points
        .iter()
        .map(|&p| distance_to(b, p))
        .chain(b.points.iter().map(|&p| distance_to(a, p)))
        .fold(f64::INFINITY, f64::min)
}

/// A raw sketch: a stroke across another's interior, missing it by `miss` in z, and two ends
/// that stop short of a stroke (so that the sketch is one whose ends float).
fn crossing_sketch(miss: f64) -> Vec<Curve> {
    vec![
        line(DVec3::new(0.0, 0.5, 0.0), DVec3::new(1.0, 0.5, 0.0), 21),
        line(DVec3::new(0.5, 0.0, miss), DVec3::new(0.5, 1.0, miss), 21),
        line(DVec3::new(0.0, 0.0, 0.0), DVec3::new(0.0, 0.48, 0.0), 11),
        line(DVec3::new(1.0, 0.0, 0.0), DVec3::new(1.0, 0.48, 0.0), 11),
    ]
}

#[test]
fn strokes_that_cross_in_the_air_are_moved_to_meet() {
    let miss = 0.02;
    let c = run(crossing_sketch(miss), 0.05);
    assert_eq!(c.report.crossed, 1, "{:?}", c.report);
    let (a, b) = (&c.network.curves[0], &c.network.curves[1]);
    assert!(curves_apart(a, b) < 1e-12, "the strokes still miss by {}", curves_apart(a, b));
    // Each moved by half the miss at the crossing, and not at all two gaps away from it.
    for (curve, z) in [(a, 0.0), (b, miss)] {
        let shift = curve.points.iter().map(|p| (p.z - z).abs()).fold(0.0, f64::max);
        assert!((shift - 0.5 * miss).abs() < 1e-9, "shift {shift}");
        for p in &curve.points {
            if p.distance(DVec3::new(0.5, 0.5, 0.0)) > 0.1 + 1e-9 {
                assert!((p.z - z).abs() < 1e-15, "{p}: moved beyond two gaps of the crossing");
            }
        }
    }
    assert!(c.warnings.iter().any(|w| w.message.contains("crossing")), "{:?}", c.warnings);
}

#[test]
fn strokes_that_pass_beyond_the_gap_or_along_each_other_are_left() {
    // Beyond the gap: no crossing.
    let c = run(crossing_sketch(0.06), 0.05);
    assert_eq!(c.report.crossed, 0, "{:?}", c.report);
    // At a shallow angle (15°): not a crossing either.
    let mut curves = crossing_sketch(0.02);
    let t = 15f64.to_radians();
    curves[1] = line(
        DVec3::new(0.5 - 0.5 * t.cos(), 0.5 - 0.5 * t.sin(), 0.02),
        DVec3::new(0.5 + 0.5 * t.cos(), 0.5 + 0.5 * t.sin(), 0.02),
        21,
    );
    let c = run(curves, 0.05);
    assert_eq!(c.report.crossed, 0, "{:?}", c.report);
}

#[test]
fn a_graph_whose_ends_meet_keeps_its_near_misses() {
    // The ends lie on the strokes (as in a neatened graph): the near miss is the drawing's.
    let mut curves = crossing_sketch(0.02);
    curves[2] = line(DVec3::new(0.0, 0.0, 0.0), DVec3::new(0.0, 0.5, 0.0), 11);
    curves[3] = line(DVec3::new(1.0, 0.0, 0.0), DVec3::new(1.0, 0.5, 0.0), 11);
    let net = Network { curves: curves.clone(), snap: None, cycles: None };
    let c = run(curves, 0.05);
    assert_eq!(c.report.crossed, 0, "{:?}", c.report);
    assert!(!c.changed(), "{:?}", c.report);
    assert_eq!(
        c.network.curves.iter().map(|c| c.points.clone()).collect::<Vec<_>>(),
        net.curves.iter().map(|c| c.points.clone()).collect::<Vec<_>>()
    );
}

#[test]
fn points_a_hair_apart_are_emitted_once_with_their_normals() {
    let x = |a: f64, b: f64| DVec3::new(a, b, 0.0);
    let mut pts = vec![x(0.0, 0.0), x(1.0, 0.0), x(1.0, 1e-6), x(2.0, 0.0), x(2.0 + 1e-6, 0.0)];
    let mut nrm = vec![DVec3::Z, DVec3::Z, DVec3::X, DVec3::Z, DVec3::Y];
    drop_close(&mut pts, &mut nrm, 1e-3);
    // The interior point next to a kept one goes; at the end, the end stays and the point
    // before it goes.
    assert_eq!(pts, vec![x(0.0, 0.0), x(1.0, 0.0), x(2.0 + 1e-6, 0.0)]);
    assert_eq!(nrm, vec![DVec3::Z, DVec3::Z, DVec3::Y]);
}

#[test]
fn a_small_loop_crossed_by_a_stroke_is_moved_once() {
    // A loop shorter than the bump's two sides (4 gaps round) missing a stroke by a fifth of
    // the gap: each of its points moves by at most half the miss (no point shifted from both
    // sides at once).
    let (r, miss) = (0.03, 0.01);
    let loop_pts: Vec<DVec3> = (0..24)
        .map(|k| {
            let t = std::f64::consts::TAU * k as f64 / 24.0 - std::f64::consts::FRAC_PI_2;
            DVec3::new(0.5, 0.5 + r * t.cos(), r - miss + r * t.sin())
        })
        .collect();
    let mut curves = crossing_sketch(0.0);
    curves[1] = Curve { points: loop_pts.clone(), closed: true, ..Default::default() };
    let c = run(curves, 0.05);
    assert_eq!(c.report.crossed, 1, "{:?}", c.report);
    let moved = &c.network.curves[1];
    assert!(curves_apart(&c.network.curves[0], moved) < 1e-12);
    for p in &moved.points {
        let before = loop_pts.iter().map(|q| q.distance(*p)).fold(f64::INFINITY, f64::min);
        assert!(before <= 0.5 * miss + 1e-9, "{p} moved {before} from the loop");
    }
}

#[test]
fn an_exact_duplicate_is_overdraw_and_a_shared_node_is_not() {
    // A short stroke drawn three times sample for sample (the input shares every sample), near a
    // crossing stroke: one curve is left of the three.
    let a = line(DVec3::new(0.2, 0.0, 0.0), DVec3::new(0.4, 0.0, 0.0), 6);
    let cross = line(DVec3::new(0.3, -0.5, 0.0), DVec3::new(0.3, 0.5, 0.0), 11);
    let c = run(vec![a.clone(), cross.clone(), a.clone(), a], 0.05);
    assert_eq!(c.report.merged, 2, "{:?}", c.report);
    assert_eq!(c.network.curves.len(), 2);
    // Two strokes leaving one shared sample at a shallow angle (a neatened graph's node) stay two.
    let o = DVec3::ZERO;
    let b = line(o, DVec3::new(1.0, 0.05, 0.0), 21);
    let d = line(o, DVec3::new(1.0, -0.05, 0.0), 21);
    let c = run(vec![b, d], 0.05);
    assert_eq!(c.report.merged, 0, "{:?}", c.report);
    assert_eq!(c.network.curves.len(), 2);
}

#[test]
fn a_retrace_that_cuts_the_corner_it_turned_is_cut_at_its_turn() {
    // Out along an L (down, then right), back in one straight sample that cuts the corner: the
    // way back runs up to 0.03 off the way out and at 17° to it near the corner, so overdraw
    // (band 0.025, 20°) does not take all of it. The turn becomes the end.
    let gap = 0.05;
    let pts = vec![
        DVec3::new(0.0, 0.3, 0.0),
        DVec3::new(0.0, 0.0, 0.0),
        DVec3::new(0.6, 0.0, 0.0),
        DVec3::new(0.3, 0.02, 0.0),
        DVec3::new(0.02, 0.03, 0.0),
    ];
    let c = run(vec![Curve { points: pts, ..Default::default() }], gap);
    assert!(c.report.trimmed >= 1, "{:?}", c.report);
    let total: f64 = c.network.curves.iter().map(curve_length).sum();
    assert!((total - 0.9).abs() < 0.05, "one pass (0.9 long) left, got {total}");
    // A hairpin whose way back leaves the way out (a V opening to 0.2 apart) is drawn so: kept.
    let v = vec![DVec3::new(0.0, 0.0, 0.0), DVec3::new(0.6, 0.0, 0.0), DVec3::new(0.0, 0.2, 0.0)];
    let c = run(vec![Curve { points: v.clone(), ..Default::default() }], gap);
    let total: f64 = c.network.curves.iter().map(curve_length).sum();
    let drawn = 0.6 + (0.36f64 + 0.04).sqrt();
    assert!((total - drawn).abs() < 1e-9, "{total} != {drawn}: {:?}", c.report);
}

/// A bar and a stem drawn towards it from `(0.5, 1)`, ending `short` below the bar, its last
/// stretch turned by `turn` degrees away from the bar's normal; a second, separate stroke far
/// away so that the sketch has loose ends.
fn stem_sketch(short: f64, turn: f64) -> Vec<Curve> {
    let bar = line(DVec3::new(0.0, 0.0, 0.0), DVec3::new(1.0, 0.0, 0.0), 21);
    let (s, c) = turn.to_radians().sin_cos();
    let foot = DVec3::new(0.5, short, 0.0);
    let knee = foot + 0.3 * DVec3::new(-s, c, 0.0);
    let mut stem = line(DVec3::new(0.5, 1.0, 0.0), knee, 15);
    stem.points.pop();
    stem.points.extend(line(knee, foot, 13).points);
    let far = line(DVec3::new(3.0, 0.0, 0.0), DVec3::new(3.0, 1.0, 0.0), 11);
    vec![bar, stem, far]
}

#[test]
fn an_end_released_short_of_a_stroke_it_points_at_is_carried_on_to_it() {
    // 2.4 gaps short, drawn straight at the bar: beyond the gap, within the reach along it.
    let c = run(stem_sketch(0.12, 0.0), 0.05);
    assert_eq!(c.report.joined, 1, "{:?}", c.report);
    let stem = &c.network.curves[1];
    let end = stem.points[stem.points.len() - 1];
    assert!(distance_to(&c.network.curves[0], end) < 1e-12, "{end}");
    assert!((end.x - 0.5).abs() < 0.02, "joined along its direction, at {end}");
    // Pointing 20° off the bar's normal still meets it (within the miss), nearer its end.
    let c = run(stem_sketch(0.12, 20.0), 0.05);
    assert_eq!(c.report.joined, 1, "{:?}", c.report);
}

#[test]
fn an_end_beyond_the_gap_that_points_elsewhere_or_too_far_stays_free() {
    // Pointing 60° away from the bar: the ray misses it.
    let c = run(stem_sketch(0.12, 60.0), 0.05);
    assert_eq!(c.report.joined, 0, "{:?}", c.report);
    // Straight at it but 3.6 gaps short: beyond the reach.
    let c = run(stem_sketch(0.18, 0.0), 0.05);
    assert_eq!(c.report.joined, 0, "{:?}", c.report);
    assert!(!c.changed(), "{:?}", c.report);
}

#[test]
fn a_graph_whose_ends_meet_keeps_its_free_ends_free() {
    // Most ends meet a stroke as drawn (a neatened graph): the one released short is meant so.
    let mut curves = stem_sketch(0.12, 0.0);
    curves[2] = line(DVec3::new(0.0, 0.0, 0.0), DVec3::new(0.0, 1.0, 0.0), 11);
    curves.push(line(DVec3::new(1.0, 0.0, 0.0), DVec3::new(1.0, 1.0, 0.0), 11));
    curves.push(line(DVec3::new(0.0, 1.0, 0.0), DVec3::new(1.0, 1.0, 0.0), 21));
    let c = run(curves, 0.05);
    assert_eq!(c.report.joined, 0, "{:?}", c.report);
    assert!(!c.changed(), "{:?}", c.report);
}

/// A sharp tip (a leaf's two outline strokes drawn to one point): stroke 1 leaves stroke 0's
/// end along it, within a third of the snapping tolerance for 40 tolerances, then parts at 20°.
/// Node finding refuses the strokes as drawn (they run within the tolerance of each other);
/// consolidated, stroke 1's end is cut back to where they part and joined there, stroke 0's
/// free end beside it with it (an L corner: the tip, shorter than the gap, is left out), and
/// node finding takes the network. A stroke that ends on another and leaves it at an angle is
/// left as drawn.
#[test]
fn an_end_that_runs_along_another_stroke_is_cut_back_to_where_they_part() {
    let snap = 1e-4;
    let a = line(DVec3::ZERO, DVec3::new(1.0, 0.0, 0.0), 1001);
    let mut tip: Vec<DVec3> =
        (0..=40).map(|i| DVec3::new(1e-4 * i as f64, if i == 0 { 0.0 } else { 3e-5 }, 0.0)).collect();
    let part = DVec3::new(20f64.to_radians().cos(), 20f64.to_radians().sin(), 0.0);
    let from = tip[40];
    tip.extend((1..=500).map(|i| from + part * (1e-3 * i as f64)));
    let b = Curve { points: tip, ..Default::default() };
    let raw = Network { curves: vec![a.clone(), b], snap: Some(snap), cycles: None };
    let Err(e) = crate::topology::find_nodes(&raw, snap) else { panic!("node finding took the tip as drawn") };
    assert!(e.to_string().contains("runs within the snapping tolerance"), "{e}");
    let c = consolidate(&raw, &ConsolidateOptions { enabled: true, gap: Some(0.02) }, Some(snap)).unwrap();
    assert!(c.warnings.iter().any(|w| w.message.contains("ran along another stroke")), "{:?}", c.warnings);
    assert!(c.report.trimmed >= 1 && c.report.joined >= 1, "{:?}", c.report);
    let (s0, s1) = (c.network.curves[0].points[0], c.network.curves[1].points[0]);
    assert!(s0.distance(s1) <= snap, "{s0} {s1}");
    assert!(s1.x >= 3e-3 && s1.x <= 0.02, "stroke 1 starts at {s1}");
    // Stroke 0 past the corner as drawn.
    let kept = &c.network.curves[0].points;
    assert!(kept.len() > 900 && kept.last() == a.points.last(), "{} points", kept.len());
    crate::topology::find_nodes(&c.network, snap).unwrap();
    // A T drawn onto the line (shared point, leaving at 60°): nothing to do.
    let t = line(DVec3::new(0.5, 0.0, 0.0), DVec3::new(0.5 + 0.5, 0.5 * 3f64.sqrt(), 0.0), 101);
    let net = Network { curves: vec![a, t], snap: Some(snap), cycles: None };
    let c = consolidate(&net, &ConsolidateOptions { enabled: true, gap: Some(0.02) }, Some(snap)).unwrap();
    assert!(!c.changed(), "{:?}", c.report);
}
