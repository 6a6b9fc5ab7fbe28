use super::*;
use crate::geom::DVec3;
use crate::topology::cycles::tests::{circle, graph, line};

/// Two straight curves crossing at the origin (along x and along y, normals +z): the centre
/// node has four segment ends.
fn plus() -> (Graph, Vec<CurveSpline>, usize) {
    let (g, splines) = graph(vec![line(-DVec3::X, DVec3::X, 5), line(-DVec3::Y, DVec3::Y, 5)]);
    let centre = g.nodes.iter().position(|n| n.position.length() < 1e-12).unwrap();
    (g, splines, centre)
}

/// Direction from `v` to the other node of segment `s`.
fn away(g: &Graph, v: usize, s: usize) -> DVec3 {
    let seg = &g.segments[s];
    let other = if seg.start == v { seg.end } else { seg.start };
    (g.nodes[other].position - g.nodes[v].position).normalize()
}

#[test]
fn segment_ends_around_a_crossing_turn_counter_clockwise() {
    let (g, splines, centre) = plus();
    let ends = node_ends(&g);
    assert_eq!(ends[centre].len(), 4);
    let rot = Rotation::new(&g, &splines, &ends).unwrap();
    let dirs: Vec<DVec3> = rot.sorted[centre].iter().map(|&(s, _)| away(&g, centre, s)).collect();
    // Each next end is the previous one turned by +90° about the node normal (+z).
    for k in 0..4 {
        let turned = DVec3::Z.cross(dirs[k]);
        assert!(turned.distance(dirs[(k + 1) % 4]) < 1e-9, "{dirs:?}");
    }
    // Arriving at the centre from the east (+x), the face on the left (south-east) continues
    // to the south.
    let east = (0..g.segments.len()).find(|&s| away(&g, centre, s).distance(DVec3::X) < 1e-9).unwrap();
    let south = (0..g.segments.len()).find(|&s| away(&g, centre, s).distance(-DVec3::Y) < 1e-9).unwrap();
    let arrive = HalfEdge { segment: east, forward: g.segments[east].end == centre };
    let next = rot.next(&g, arrive);
    assert_eq!(next.segment, south);
    assert_eq!(next.forward, g.segments[south].start == centre);
}

#[test]
fn a_dangling_segment_is_a_topology_error() {
    let (g, _, _) = plus();
    let ends = node_ends(&g);
    let Err(e) = check_valence(&g, &ends) else { panic!("accepted") };
    assert!(e.to_string().contains("without meeting another curve: a dangling segment"), "{e}");
}

/// The three great circles of the sphere: 6 nodes, 12 segments, 8 triangular faces, every
/// half-edge in one of them; all are patches.
#[test]
fn three_great_circles_trace_eight_triangles() {
    let great = |axis: usize| {
        let mut c = circle(1.0, 0.0, 64, |p| p);
        for p in c.points.iter_mut().chain(c.normals.iter_mut()) {
            *p = match axis {
                0 => *p,
                1 => DVec3::new(0.0, p.x, p.y),
                _ => DVec3::new(p.y, 0.0, p.x),
            };
        }
        c
    };
    let (g, splines) = graph((0..3).map(great).collect());
    let ends = node_ends(&g);
    check_valence(&g, &ends).unwrap();
    let rot = Rotation::new(&g, &splines, &ends).unwrap();
    let faces = trace_faces(&g, &rot).unwrap();
    assert_eq!(faces.faces.len(), 8);
    for (f, face) in faces.faces.iter().enumerate() {
        assert_eq!(face.len(), 3);
        for &h in face {
            assert_eq!(faces.face_of[he_index(h)], f);
        }
    }
    let parts = Parts::new(&g);
    assert!(parts.seg_root.iter().all(|&r| r == 0) && parts.has_interior[0]);
    let c = classify_faces(&g, &faces, &parts);
    assert_eq!(c.patches.len(), 8);
    assert!(c.slits.is_empty());
    assert!(c.lone_faces.iter().all(|f| f.is_empty()));
    check_boundary_sides(&g, &faces, &parts).unwrap();
}

/// The dangling end is data: the error names the node (an end of the first line), its
/// segment and curve.
#[test]
fn a_dangling_segment_error_names_its_node() {
    let (g, _, _) = plus();
    let Err(e) = check_valence(&g, &node_ends(&g)) else { panic!("accepted") };
    let at = e.at();
    let (v, s) = (at.node.unwrap(), at.segment.unwrap());
    assert_eq!(g.nodes[v].position, -DVec3::X);
    assert!(g.segments[s].start == v || g.segments[s].end == v);
    assert_eq!(at.curve, Some(g.segments[s].curve));
    assert!(e.to_string().contains(&format!("ends at node {v} at")), "{e}");
}
