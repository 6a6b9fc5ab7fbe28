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
    let (nodes, on_curve, warnings) = meeting_nodes(&lines, &hits, &clusters, 0.01).unwrap();
    assert!(warnings.is_empty());
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

/// A petal: a closed loop in the xz plane (normals −y) whose seam touches a crossing of two
/// lines in the xy plane (normals +z, 90° from the petal's and more than 90° from its flipped
/// side). Untagged, the loop is one more passage of the node (its normal in the node's mean);
/// tagged boundary, it is a sheet of its own: the node keeps the two lines only, with their
/// normal, and a warning names the loop. A loop through two meetings stays in both.
#[test]
fn a_closed_boundary_curve_touching_at_one_place_is_a_sheet_of_its_own() {
    let petal: Vec<[f64; 3]> = (0..24)
        .map(|k| {
            let t = std::f64::consts::TAU * k as f64 / 24.0;
            [0.5 * t.sin(), 0.0, 0.5 - 0.5 * t.cos()]
        })
        .collect();
    let mut loop_ = line(&petal, -DVec3::Y);
    loop_.closed = true;
    let cross = [
        line(&[[-1.0, 0.0, 0.0], [0.0, 0.0, 0.0], [1.0, 0.0, 0.0]], DVec3::Z),
        line(&[[0.0, -1.0, 0.0], [0.0, 0.0, 0.0], [0.0, 1.0, 0.0]], DVec3::Z),
    ];
    let names = labels(3);
    let run = |boundary: bool| {
        let mut curves = cross.to_vec();
        let mut l = loop_.clone();
        l.boundary = boundary;
        curves.push(l);
        let lines = Polylines::new(&curves, &names);
        let hits = find_contacts(&lines, 0.01).unwrap();
        let clusters = cluster_contacts(&lines, &hits, 0.01);
        meeting_nodes(&lines, &hits, &clusters, 0.01).unwrap()
    };
    let (nodes, on_curve, warnings) = run(false);
    assert_eq!(nodes.len(), 1);
    assert_eq!(on_curve[2].len(), 1);
    assert!(nodes[0].normal.dot(DVec3::Z) < 0.99, "{}", nodes[0].normal);
    assert!(warnings.is_empty());
    let (nodes, on_curve, warnings) = run(true);
    assert_eq!(nodes.len(), 1);
    assert_eq!(nodes[0].normal, DVec3::Z);
    assert!(on_curve[2].is_empty(), "{on_curve:?}");
    assert_eq!(on_curve[0], vec![(1.0, 0)]);
    assert_eq!(warnings.len(), 1);
    assert!(
        warnings[0].message.starts_with("curve 2 is a closed curve tagged boundary that touches"),
        "{}",
        warnings[0].message
    );
    assert_eq!(warnings[0].at.curve, Some(2));
    // The loop's top also on a third line: two meetings, a node at each.
    let mut curves = cross.to_vec();
    curves.push(line(&[[-1.0, 0.0, 1.0], [0.0, 0.0, 1.0], [1.0, 0.0, 1.0]], -DVec3::Y));
    let mut l = loop_.clone();
    l.boundary = true;
    curves.push(l);
    let names = labels(4);
    let lines = Polylines::new(&curves, &names);
    let hits = find_contacts(&lines, 0.01).unwrap();
    let clusters = cluster_contacts(&lines, &hits, 0.01);
    let (nodes, on_curve, warnings) = meeting_nodes(&lines, &hits, &clusters, 0.01).unwrap();
    assert_eq!((nodes.len(), on_curve[3].len()), (2, 2));
    assert!(warnings.is_empty());
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
