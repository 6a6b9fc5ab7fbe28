use super::super::contacts::Polylines;
use super::*;
use crate::network::Curve;

/// Samples at x = 0, 1, 2, 3 (open), normals +z.
fn ruler(closed: bool) -> Curve {
    let points: Vec<DVec3> = (0..4).map(|i| DVec3::new(i as f64, 0.0, 0.0)).collect();
    Curve { name: None, normals: vec![DVec3::Z; 4], points, closed, boundary: false, ..Default::default() }
}

fn labels(n: usize) -> Vec<String> {
    (0..n).map(|i| format!("curve {i}")).collect()
}

/// Nodes at arc 0.1 (a tenth of edge 0 from sample 0: snapped to it), 1.5 (mid-edge:
/// inserted), 2.9 (snapped to sample 3).
#[test]
fn nodes_near_samples_snap_and_the_others_are_inserted() {
    let curves = [ruler(false)];
    let names = labels(1);
    let lines = Polylines::new(&curves, &names);
    let (snapped, inserts) = place_nodes(&lines, 0, &[(0.1, 7), (1.5, 8), (2.9, 9)]);
    assert_eq!(snapped, vec![Some(7), None, None, Some(9)]);
    assert_eq!(inserts, vec![(1, 1.5, 8)]);
}

/// Two nodes on the last quarter of edge 2: the first does not take sample 3 (the second one,
/// further along, does), so it is inserted before it and the order is kept.
#[test]
fn a_node_does_not_snap_past_another_one() {
    let curves = [ruler(false)];
    let names = labels(1);
    let lines = Polylines::new(&curves, &names);
    let (snapped, inserts) = place_nodes(&lines, 0, &[(2.8, 1), (2.9, 2)]);
    assert_eq!(snapped, vec![None, None, None, Some(2)]);
    assert_eq!(inserts, vec![(2, 2.8, 1)]);
}

/// A closed ruler (back from x = 3 to 0, length 6) with nodes at arc 1.5 (inserted on edge 1)
/// and 3 (sample 3): split, it starts at the first node.
#[test]
fn a_closed_curve_is_rotated_to_start_at_a_node() {
    let curves = [ruler(true)];
    let names = labels(1);
    let lines = Polylines::new(&curves, &names);
    let nodes = [
        Node { position: DVec3::new(1.5, 0.0, 0.0), normal: DVec3::Z },
        Node { position: DVec3::new(3.0, 0.0, 0.0), normal: DVec3::Z },
    ];
    let mut list = vec![(3.0, 1), (1.5, 0)];
    let sc = split_curve(&lines, 0, &mut list, &nodes);
    let x: Vec<f64> = sc.points.iter().map(|p| p.x).collect();
    assert_eq!(x, vec![1.5, 2.0, 3.0, 0.0, 1.0]);
    assert_eq!(sc.nodes, vec![(0, 0), (2, 1)]);
    let segments = segments_of(&[sc], &names).unwrap();
    // The second segment runs from sample 2 around to sample 5 = sample 0 again.
    assert_eq!(
        segments,
        vec![
            Segment { curve: 0, first: 0, last: 2, start: 0, end: 1, boundary: false },
            Segment { curve: 0, first: 2, last: 5, start: 1, end: 0, boundary: false },
        ]
    );
}

#[test]
fn open_curves_get_end_nodes_unless_a_node_is_there() {
    let curves = [ruler(false), ruler(true)];
    let names = labels(2);
    let lines = Polylines::new(&curves, &names);
    // A meeting node at the start of the open curve, none on the closed one.
    let mut nodes = vec![Node { position: DVec3::ZERO, normal: DVec3::Z }];
    let mut on_curve = vec![vec![(0.0, 0)], vec![]];
    add_end_nodes(&lines, &mut nodes, &mut on_curve, 0.01);
    assert_eq!(nodes.len(), 3);
    assert_eq!(nodes[1].position, DVec3::new(3.0, 0.0, 0.0));
    assert_eq!(nodes[2].position, DVec3::ZERO);
    assert_eq!(on_curve, vec![vec![(0.0, 0), (3.0, 1)], vec![(0.0, 2)]]);
}

#[test]
fn two_nodes_on_one_point_are_an_input_error() {
    let mut sc = split_curve(
        &Polylines::new(&[ruler(false)], &labels(1)),
        0,
        &mut [(0.0, 0), (3.0, 1)],
        &[Node { position: DVec3::ZERO, normal: DVec3::Z }, Node { position: DVec3::X * 3.0, normal: DVec3::Z }],
    );
    sc.points[2] = sc.points[1];
    let Err(e) = segments_of(&[sc], &labels(1)) else { panic!("accepted") };
    assert!(e.to_string().starts_with("curve 0: two nodes fall on the same point"), "{e}");
}
