use super::*;
use crate::error::Error;

#[test]
fn reads_closed_boundary_polylines() {
    let text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nvn 0 0 1\nvn 0 0 1\ng boundary\nl 1 2 3 1\ng inner\nl -3 -2\n";
    let net = parse(text, "t.obj").unwrap();
    assert_eq!(net.curves.len(), 2);
    assert!(net.curves[0].closed && net.curves[0].boundary);
    assert_eq!(net.curves[0].points.len(), 3);
    assert!(!net.curves[1].closed && !net.curves[1].boundary);
    assert_eq!(net.curves[1].points, vec![DVec3::ZERO, DVec3::X]);
    assert_eq!(net.curves[1].name.as_deref(), Some("inner"));
}

#[test]
fn errors_have_positions() {
    let e = parse("v 0 0 0\nv 1 0 0\nvn 0 0 1\nvn 0 0 1\nl 1 7\n", "t.obj").unwrap_err();
    assert!(matches!(e, Error::Parse { line: 5, column: 5, .. }), "{e}");
    let e = parse("v 0 zero 0\n", "t.obj").unwrap_err();
    assert!(matches!(e, Error::Parse { line: 1, column: 5, .. }), "{e}");
    let e = parse("v 0 0 0\nv 1 0 0\nvn 0 0 1\nl 1 2\n", "t.obj").unwrap_err();
    assert!(e.to_string().contains("2 \"v\" lines but 1 \"vn\""), "{e}");
}

#[test]
fn round_trip() {
    let net = Network {
        curves: vec![Curve {
            name: Some("c".into()),
            points: vec![DVec3::ZERO, DVec3::X, DVec3::Y],
            normals: vec![DVec3::Z; 3],
            closed: true,
            boundary: true,
            ..Default::default()
        }],
        snap: None,
        cycles: None,
    };
    let mut buf = Vec::new();
    write(&mut buf, &net).unwrap();
    let back = parse(std::str::from_utf8(&buf).unwrap(), "t").unwrap();
    assert_eq!(back.curves[0].points, net.curves[0].points);
    assert!(back.curves[0].closed && back.curves[0].boundary);
}

#[test]
fn without_normals_an_edge_soup_is_chained_into_curves_split_at_nodes() {
    // A square loop 1-2-3-4 with a tail 3-5-6, written one edge per line in shuffled order,
    // one edge twice, and a separate closed triangle 7-8-9.
    let text = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 2 1 0\nv 3 1 0\nv 5 5 5\nv 6 5 5\nv 5 6 5\n\
                l 2 3\nl 1 2\nl 4 1\nl 3 4\nl 5 6\nl 3 5\nl 1 2\nl 7 8 9 7\n";
    let net = parse(text, "soup.obj").unwrap();
    assert!(net.curves.iter().all(|c| !c.has_normals()));
    let mut chains: Vec<(usize, bool)> = net.curves.iter().map(|c| (c.points.len(), c.closed)).collect();
    chains.sort_unstable();
    // The loop through node 3 (closed at it), the tail from node 3 to the end 6, the triangle.
    assert_eq!(chains, vec![(3, false), (3, true), (4, true)]);
}

#[test]
fn chains_split_at_every_vertex_of_valence_other_than_two() {
    // A plus sign: four arms from the centre 0.
    let chains = chain_edges(&[[0, 1], [1, 2], [0, 3], [3, 4], [0, 5], [0, 6], [6, 7]]);
    assert_eq!(chains.len(), 4);
    assert!(chains.iter().all(|(c, closed)| c[0] == 0 && !closed));
    let mut lengths: Vec<usize> = chains.iter().map(|c| c.0.len()).collect();
    lengths.sort_unstable();
    assert_eq!(lengths, vec![2, 3, 3, 3]);
}

#[test]
fn a_network_without_normals_round_trips_without_vn() {
    let net = Network {
        curves: vec![Curve {
            name: Some("c".into()),
            points: vec![DVec3::ZERO, DVec3::X, DVec3::Y],
            normals: Vec::new(),
            closed: true,
            boundary: false,
            ..Default::default()
        }],
        snap: None,
        cycles: None,
    };
    let mut buf = Vec::new();
    write(&mut buf, &net).unwrap();
    let text = std::str::from_utf8(&buf).unwrap();
    assert!(!text.contains("vn "), "{text}");
    let back = parse(text, "t").unwrap();
    assert_eq!(back.curves[0].points, net.curves[0].points);
    assert!(back.curves[0].closed && !back.curves[0].has_normals());
}

/// A graph of points and edges (polyscope's arrays) gives the curves of the OBJ edge soup
/// with the same `v` and `l` lines; normals follow their points; bad indices name the edge.
#[test]
fn network_from_edges_is_the_edge_soup_of_an_obj() {
    // A figure eight of two loops through point 0, a tail from point 0 (a node of valence 5),
    // and a self-edge that is skipped.
    let p: Vec<DVec3> = (0..8).map(|i| DVec3::new(i as f64, (i * i) as f64, 1.0)).collect();
    let edges: [[i64; 2]; 9] = [[0, 1], [1, 2], [2, 0], [0, 3], [3, 4], [4, 0], [0, 5], [5, 6], [6, 6]];
    let mut obj = String::new();
    for q in &p {
        obj.push_str(&format!("v {} {} {}\n", q.x, q.y, q.z));
    }
    for [a, b] in edges {
        obj.push_str(&format!("l {} {}\n", a + 1, b + 1));
    }
    let soup = parse(&obj, "soup.obj").unwrap();
    let normals: Vec<DVec3> = (0..8).map(|i| DVec3::new(0.0, 0.0, 1.0 + i as f64)).collect();
    let net = network_from_edges(&p, &edges, Some(&normals)).unwrap();
    assert_eq!(net.curves.len(), 3);
    assert_eq!(net.curves.len(), soup.curves.len());
    let text: Vec<&str> = obj.lines().collect();
    for (a, b) in net.curves.iter().zip(&soup.curves) {
        assert_eq!((&a.points, a.closed, a.boundary), (&b.points, b.closed, b.boundary));
        // The soup's curve is named after the first `l` line of its edges (the arrays' is not).
        assert!(a.name.is_none());
        let line: usize = b.name.as_deref().and_then(|n| n.strip_prefix("curve at line ")).unwrap().parse().unwrap();
        let ids: Vec<usize> = text[line - 1].split(' ').skip(1).map(|i| i.parse::<usize>().unwrap() - 1).collect();
        assert!(ids.iter().all(|&i| b.points.contains(&p[i])), "line {line}: {:?}", text[line - 1]);
        assert!(b.normals.is_empty());
        // Each normal is its point's.
        for (q, n) in a.points.iter().zip(&a.normals) {
            assert_eq!(n.z, 1.0 + q.x);
        }
    }
    assert!(network_from_edges(&p, &edges, None).unwrap().curves.iter().all(|c| c.normals.is_empty()));
    let e = network_from_edges(&p, &[[0, 1], [1, 8]], None).unwrap_err().to_string();
    assert!(e.contains("edge 1: point index 8 is out of range (there are 8 points"), "{e}");
    let e = network_from_edges(&p, &[[-1, 1]], None).unwrap_err().to_string();
    assert!(e.contains("edge 0: point index -1"), "{e}");
    let e = network_from_edges(&p, &edges, Some(&normals[..3])).unwrap_err().to_string();
    assert!(e.contains("3 normals for 8 points"), "{e}");
    let mut bad = p.clone();
    bad[2].y = f64::NAN;
    let e = network_from_edges(&bad, &edges, None).unwrap_err().to_string();
    assert!(e.contains("edge 1: point 2 is not finite"), "{e}");
}
