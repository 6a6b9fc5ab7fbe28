use super::*;
use crate::network::Curve;
use std::f64::consts::PI;

fn circle(axis: usize, n: usize, phase: f64) -> Curve {
    let points: Vec<DVec3> = (0..n)
        .map(|i| {
            let a = phase + 2.0 * PI * i as f64 / n as f64;
            let (c, s) = (a.cos(), a.sin());
            match axis {
                0 => DVec3::new(c, s, 0.0),
                1 => DVec3::new(0.0, c, s),
                _ => DVec3::new(s, 0.0, c),
            }
        })
        .collect();
    Curve { name: None, normals: points.clone(), points, closed: true, boundary: false, ..Default::default() }
}

#[test]
fn three_great_circles_with_shared_samples() {
    let net = Network { curves: (0..3).map(|a| circle(a, 64, 0.0)).collect(), snap: None, cycles: None };
    let (g, _) = find_nodes(&net, net.snap_tolerance()).unwrap();
    assert_eq!(g.nodes.len(), 6);
    assert_eq!(g.segments.len(), 12);
    for n in &g.nodes {
        assert!((n.position.length() - 1.0).abs() < 1e-12);
        assert!((n.normal - n.position).length() < 1e-12);
    }
}

#[test]
fn crossings_between_samples_are_found() {
    // Odd sample counts with a phase: no crossing is a sample.
    let net = Network {
        curves: vec![circle(0, 61, 0.1), circle(1, 67, 0.05), circle(2, 71, 0.2)],
        snap: Some(5e-3),
        cycles: None,
    };
    let (g, _) = find_nodes(&net, 5e-3).unwrap();
    assert_eq!(g.nodes.len(), 6, "{:?}", g.nodes);
    assert_eq!(g.segments.len(), 12);
    // The nodes are close to the true crossings (±axis points).
    for n in &g.nodes {
        let p = n.position;
        let m = p.abs().max_element();
        assert!((m - 1.0).abs() < 3e-3, "{p:?}");
    }
}

#[test]
fn flipped_normals_are_an_orientation_error() {
    let mut b = circle(1, 64, 0.0);
    b.normals.iter_mut().for_each(|n| *n = -*n);
    let net = Network { curves: vec![circle(0, 64, 0.0), b], snap: None, cycles: None };
    let Err(e) = find_nodes(&net, net.snap_tolerance()) else { panic!("accepted") };
    assert!(e.to_string().contains("curve 0 and curve 1 meet"), "{e}");
    assert!(e.to_string().contains("180°"), "{e}");
}

#[test]
fn overlapping_curves_are_rejected() {
    let net = Network { curves: vec![circle(0, 64, 0.0), circle(0, 64, 0.01)], snap: None, cycles: None };
    match find_nodes(&net, net.snap_tolerance()) {
        Err(e) => assert!(e.to_string().contains("overlapping"), "{e}"),
        Ok((g, _)) => panic!("accepted with {} nodes", g.nodes.len()),
    }
}

#[test]
fn open_curve_ends_are_nodes() {
    let c = Curve {
        name: Some("stick".into()),
        points: vec![DVec3::ZERO, DVec3::X, DVec3::new(2.0, 0.0, 0.0)],
        normals: vec![DVec3::Z; 3],
        closed: false,
        boundary: false,
        ..Default::default()
    };
    let net = Network { curves: vec![c], snap: None, cycles: None };
    let (g, _) = find_nodes(&net, net.snap_tolerance()).unwrap();
    assert_eq!(g.nodes.len(), 2);
    assert_eq!(g.segments, vec![Segment { curve: 0, first: 0, last: 2, start: 0, end: 1, boundary: false }]);
}

/// Issue 5 (beetle, 10 planes): an open curve crosses another one just before its end, close
/// enough to its last sample that the crossing snaps to it, and ends more than the clustering
/// distance beyond. The crossing used to take the last sample and the end node was inserted
/// before it, so that the curve folded back on itself at its end (a hairpin the cycle tracing
/// reads as a slit).
#[test]
fn a_crossing_near_an_open_curve_end_keeps_the_order_of_the_nodes() {
    let stick = Curve {
        name: Some("stick".into()),
        points: vec![DVec3::new(0.0, 1.0, 0.0), DVec3::new(0.0, 0.5, 0.0), DVec3::new(0.0, -0.03, 0.0)],
        normals: vec![DVec3::Z; 3],
        closed: false,
        boundary: false,
        ..Default::default()
    };
    let bar = Curve {
        name: Some("bar".into()),
        points: (0..=20).map(|i| DVec3::new(-1.0 + 0.1 * i as f64 + 0.013, 0.0, 0.0)).collect(),
        normals: vec![DVec3::Z; 21],
        closed: false,
        boundary: false,
        ..Default::default()
    };
    let net = Network { curves: vec![stick, bar], snap: Some(0.01), cycles: None };
    let (g, _) = find_nodes(&net, 0.01).unwrap();
    // Along the stick, y decreases: the crossing (y = 0) comes before the end (y = -0.03).
    let y: Vec<f64> = g.curves[0].points.iter().map(|p| p.y).collect();
    assert!(y.windows(2).all(|w| w[1] < w[0]), "the stick folds back: {y:?}");
    let ends: Vec<DVec3> = g.curves[0].nodes.iter().map(|&(_, v)| g.nodes[v].position).collect();
    assert_eq!(ends.len(), 3, "{ends:?}");
    assert!(ends[1].distance(DVec3::ZERO) < 1e-9 && ends[2].distance(DVec3::new(0.0, -0.03, 0.0)) < 1e-9, "{ends:?}");
}

/// Issue 5 (beetle, 6 planes): a curve that ends on another one at a shallow angle touches it
/// at two points a little more than the clustering distance (2 tolerances) apart: where it
/// passes over a sample of the other curve and at its end. The two contacts are one meeting:
/// one node, not two nodes joined by tiny segments of both curves (a sliver that the cycle
/// tracing put on the wrong side of the boundary).
#[test]
fn two_contacts_of_a_shallow_meeting_are_one_node() {
    let snap = 0.01;
    // The bar: samples every 8 tolerances, one at x = 0.
    let bar = Curve {
        name: Some("bar".into()),
        points: (0..=20).map(|i| DVec3::new(0.08 * (i as f64 - 10.0), 0.0, 0.0)).collect(),
        normals: vec![DVec3::Z; 21],
        closed: false,
        boundary: false,
        ..Default::default()
    };
    // The stick comes down at 15°, passes 0.8 tolerances above the bar's sample at x = 0 and
    // ends at x = 0.025, 0.13 tolerances above the bar.
    let u = DVec3::new(15f64.to_radians().cos(), -15f64.to_radians().sin(), 0.0);
    let end = DVec3::new(0.025, 0.008 - 0.025 * 15f64.to_radians().tan(), 0.0);
    let points: Vec<DVec3> = (0..8).rev().map(|k| end - u * (0.08 * k as f64)).collect();
    let n = points.len();
    let stick = Curve {
        name: Some("stick".into()),
        points,
        normals: vec![DVec3::Z; n],
        closed: false,
        boundary: false,
        ..Default::default()
    };
    let net = Network { curves: vec![stick, bar], snap: Some(snap), cycles: None };
    let (g, _) = find_nodes(&net, snap).unwrap();
    // Nodes on the bar other than its two ends: one.
    let inner: Vec<DVec3> =
        g.curves[1].nodes.iter().map(|&(_, v)| g.nodes[v].position).filter(|p| p.x.abs() < 0.5).collect();
    assert_eq!(inner.len(), 1, "nodes on the bar: {inner:?}");
}
