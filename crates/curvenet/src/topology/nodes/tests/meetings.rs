use super::super::contacts::{cluster_contacts, find_contacts};
use super::*;
use crate::network::Curve;

fn line(points: &[[f64; 3]], normal: DVec3) -> Curve {
    let points: Vec<DVec3> = points.iter().map(|&p| DVec3::from(p)).collect();
    Curve {
        name: None,
        normals: vec![normal; points.len()],
        points,
        closed: false,
        boundary: false,
        ..Default::default()
    }
}

fn labels(n: usize) -> Vec<String> {
    (0..n).map(|i| format!("curve {i}")).collect()
}

/// The crossing at a shared sample (four contacts): one passage per curve, at arc length 1
/// (the middle sample), and a node at the origin with the common normal.
#[test]
fn a_crossing_is_one_passage_per_curve_and_one_node() {
    let curves = [
        line(&[[-1.0, 0.0, 0.0], [0.0, 0.0, 0.0], [1.0, 0.0, 0.0]], DVec3::Z),
        line(&[[0.0, -1.0, 0.0], [0.0, 0.0, 0.0], [0.0, 1.0, 0.0]], DVec3::Z),
    ];
    let names = labels(2);
    let lines = Polylines::new(&curves, &names);
    let hits = find_contacts(&lines, 0.01).unwrap();
    let clusters = cluster_contacts(&lines, &hits, 0.01);
    let p = passages(&lines, &hits, &clusters[0], 0.01).unwrap();
    assert_eq!(p.iter().map(|p| (p.0, p.1)).collect::<Vec<_>>(), vec![(0, 1.0), (1, 1.0)]);
    check_overlap(&lines, &p, 0.01).unwrap();
    let node = meeting_node(&lines, &p).unwrap();
    assert!(node.position.length() < 1e-12);
    assert_eq!(node.normal, DVec3::Z);
    let (nodes, on_curve) = meeting_nodes(&lines, &hits, &clusters, 0.01).unwrap();
    assert_eq!(nodes, vec![node]);
    assert_eq!(on_curve, vec![vec![(1.0, 0)], vec![(1.0, 0)]]);
}

/// Two parallel lines half a tolerance apart touch all along: an overlap error (the contacts
/// form a run longer than 8 tolerances, or the probes along one line stay within the
/// tolerance of the other).
#[test]
fn parallel_curves_within_the_tolerance_overlap() {
    let a: Vec<[f64; 3]> = (0..=20).map(|i| [0.05 * i as f64, 0.0, 0.0]).collect();
    let b: Vec<[f64; 3]> = (0..=20).map(|i| [0.05 * i as f64, 0.005, 0.0]).collect();
    let curves = [line(&a, DVec3::Z), line(&b, DVec3::Z)];
    let names = labels(2);
    let lines = Polylines::new(&curves, &names);
    let hits = find_contacts(&lines, 0.01).unwrap();
    let clusters = cluster_contacts(&lines, &hits, 0.01);
    let Err(e) = meeting_nodes(&lines, &hits, &clusters, 0.01) else { panic!("accepted") };
    assert!(e.to_string().contains("runs within the snapping tolerance"), "{e}");
}

#[test]
fn normals_more_than_90_degrees_apart_are_an_orientation_error() {
    let curves = [
        line(&[[-1.0, 0.0, 0.0], [0.0, 0.0, 0.0], [1.0, 0.0, 0.0]], DVec3::Z),
        line(&[[0.0, -1.0, 0.0], [0.0, 0.0, 0.0], [0.0, 1.0, 0.0]], -DVec3::Z),
    ];
    let names = labels(2);
    let lines = Polylines::new(&curves, &names);
    let hits = find_contacts(&lines, 0.01).unwrap();
    let p = passages(&lines, &hits, &cluster_contacts(&lines, &hits, 0.01)[0], 0.01).unwrap();
    let Err(e) = meeting_node(&lines, &p) else { panic!("accepted") };
    assert!(e.to_string().starts_with("curve 0 and curve 1 meet at"), "{e}");
    assert!(e.to_string().contains("180°"), "{e}");
    assert_eq!(e.at().curve, Some(0));
    assert_eq!(e.at().point, Some([0.0; 3]));
}

/// The polyline (0,0,0) – (1,0,0) – (1,1,0), arc lengths 0, 1, 2.
#[test]
fn points_and_distances_along_a_polyline() {
    let p = [DVec3::ZERO, DVec3::X, DVec3::new(1.0, 1.0, 0.0)];
    let arc = [0.0, 1.0, 2.0];
    assert_eq!(polyline_at_arc(&p, &arc, false, 1.5), Some(DVec3::new(1.0, 0.5, 0.0)));
    assert_eq!(polyline_at_arc(&p, &arc, false, 2.5), None);
    assert_eq!(polyline_at_arc(&p, &arc, false, -0.1), None);
    // Closed (the triangle, arc 2 + √2 around): wraps.
    let arc_c = [0.0, 1.0, 2.0, 2.0 + 2f64.sqrt()];
    let q = polyline_at_arc(&p, &arc_c, true, arc_c[3] + 0.5).unwrap();
    assert!(q.distance(DVec3::new(0.5, 0.0, 0.0)) < 1e-12, "{q:?}");
    // (2, 0.5, 0) is 1 from the second edge; within 0.4 of arc 0.5 only the first edge counts.
    let x = DVec3::new(2.0, 0.5, 0.0);
    assert_eq!(polyline_distance(&p, &arc, false, 1.5, 0.1, x), 1.0);
    let d = polyline_distance(&p, &arc, false, 0.5, 0.4, x);
    assert!((d - 0.5f64.hypot(1.0)).abs() < 1e-12, "{d}");
}
