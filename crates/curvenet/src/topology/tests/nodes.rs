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
    Curve { name: None, normals: points.clone(), points, closed: true, boundary: false }
}

#[test]
fn three_great_circles_with_shared_samples() {
    let net = Network { curves: (0..3).map(|a| circle(a, 64, 0.0)).collect(), snap: None };
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
    let net = Network { curves: vec![circle(0, 61, 0.1), circle(1, 67, 0.05), circle(2, 71, 0.2)], snap: Some(5e-3) };
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
    let net = Network { curves: vec![circle(0, 64, 0.0), b], snap: None };
    let Err(e) = find_nodes(&net, net.snap_tolerance()) else { panic!("accepted") };
    assert!(e.to_string().contains("curve 0 and curve 1 meet"), "{e}");
    assert!(e.to_string().contains("180°"), "{e}");
}

#[test]
fn overlapping_curves_are_rejected() {
    let net = Network { curves: vec![circle(0, 64, 0.0), circle(0, 64, 0.01)], snap: None };
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
    };
    let net = Network { curves: vec![c], snap: None };
    let (g, _) = find_nodes(&net, net.snap_tolerance()).unwrap();
    assert_eq!(g.nodes.len(), 2);
    assert_eq!(g.segments, vec![Segment { curve: 0, first: 0, last: 2, start: 0, end: 1, boundary: false }]);
}
