use super::*;
use crate::curves::CurveSpline;
use crate::error::Error;
use crate::network::{Curve, Network};
use crate::topology::resample::resample_network;
use crate::topology::{find_nodes, find_patches};

/// The topology stages of the pipeline on `curves`: the graph, its curve vertices at spacing
/// `d` and its patches (for the tests of the tessellation stages).
pub(super) fn prepared(curves: Vec<Curve>, d: f64) -> (Graph, Resampled, Vec<Patch>) {
    let net = Network { curves, snap: None, cycles: None };
    let (g, _) = find_nodes(&net, net.snap_tolerance()).unwrap();
    let splines: Vec<CurveSpline> =
        g.curves.iter().map(|c| CurveSpline::fit(&c.points, &c.normals, c.closed)).collect();
    let patches = find_patches(&g, &splines).unwrap();
    let res = resample_network(&g, &splines, d);
    (g, res, patches)
}

/// A closed boundary curve: the unit square in z = 0, counter-clockwise about +z, normals +z.
pub(super) fn unit_square() -> Curve {
    let c = [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)];
    let corner = |k: usize| DVec3::new(c[k % 4].0, c[k % 4].1, 0.0);
    let points: Vec<DVec3> = (0..40).map(|k| corner(k / 10).lerp(corner(k / 10 + 1), (k % 10) as f64 / 10.0)).collect();
    Curve {
        name: Some("square".into()),
        normals: vec![DVec3::Z; points.len()],
        points,
        closed: true,
        boundary: true,
        ..Default::default()
    }
}

/// `V − E + F` of a triangle mesh (over the vertices its faces use).
pub(super) fn euler_characteristic(faces: &[[u32; 3]]) -> i64 {
    let mut edges = std::collections::HashSet::new();
    let mut vertices = std::collections::HashSet::new();
    for f in faces {
        for k in 0..3 {
            let (a, b) = (f[k], f[(k + 1) % 3]);
            edges.insert((a.min(b), a.max(b)));
            vertices.insert(a);
        }
    }
    vertices.len() as i64 - edges.len() as i64 + faces.len() as i64
}

#[test]
fn loop_vertices_list_each_node_once_in_traversal_order() {
    // Segment 0 from node 0 to node 1 through vertices 4, 5; segment 1 back through 6.
    let res = Resampled { segment_vertices: vec![vec![0, 4, 5, 1], vec![1, 6, 0]], ..Default::default() };
    let fwd = [HalfEdge { segment: 0, forward: true }, HalfEdge { segment: 1, forward: true }];
    assert_eq!(loop_vertices(&res, &fwd), vec![0, 4, 5, 1, 6]);
    let bwd = [HalfEdge { segment: 1, forward: false }, HalfEdge { segment: 0, forward: false }];
    assert_eq!(loop_vertices(&res, &bwd), vec![0, 6, 1, 5, 4]);
}

#[test]
fn a_square_patch_is_tessellated_into_a_disk_of_its_area() {
    let d = 0.05;
    let (g, res, patches) = prepared(vec![unit_square()], d);
    assert_eq!(patches.len(), 1);
    let mesh = tessellate(&g, &res, &patches, d).unwrap();
    // The curve vertices come first, unchanged.
    assert_eq!(mesh.num_curve, res.positions.len());
    assert_eq!(&mesh.positions[..mesh.num_curve], &res.positions[..]);
    let mut area = 0.0;
    for f in &mesh.faces {
        let [a, b, c] = f.map(|v| mesh.positions[v as usize]);
        let n = (b - a).cross(c - a);
        assert!(n.z > 0.0, "a face is not counter-clockwise about +z: {f:?}");
        area += 0.5 * n.z;
    }
    // The area enclosed by the curve vertices (the spline rounds the corners a little).
    let Patch::Disk(hs) = &patches[0] else { panic!("{patches:?}") };
    let border: Vec<DVec2> = loop_vertices(&res, hs).iter().map(|&v| res.positions[v as usize].truncate()).collect();
    let enclosed = crate::geom::polygon_signed_area(&border);
    assert!((enclosed - 1.0).abs() < 0.01, "the border encloses {enclosed}");
    assert!((area - enclosed).abs() < 1e-9, "area {area}, enclosed {enclosed}");
    assert_eq!(euler_characteristic(&mesh.faces), 1);
    assert!(mesh.fold_fallback.is_empty());
    // About VERTICES_PER_AREA / d² free vertices in the unit square.
    let free = (mesh.positions.len() - mesh.num_curve) as f64;
    let expected = VERTICES_PER_AREA / (d * d);
    assert!((free / expected - 1.0).abs() < 0.15, "{free} free vertices, expected about {expected}");
}

/// Two patches by hand: a right triangle (nodes 0–2) and three collinear nodes (3–5), whose
/// cycle encloses no area. The error names patch 1.
#[test]
fn the_error_of_a_patch_names_it() {
    use crate::topology::Segment;
    let p = [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [0.0, 0.0], [1.0, 0.0], [2.0, 0.0]];
    let positions: Vec<DVec3> = p.iter().map(|&[x, y]| DVec3::new(x, y, 0.0)).collect();
    let nodes = positions.iter().map(|&position| crate::topology::Node { position, normal: DVec3::Z }).collect();
    let next = |s: usize| 3 * (s / 3) + (s + 1) % 3;
    let segments =
        (0..6).map(|s| Segment { curve: s, first: 0, last: 1, start: s, end: next(s), boundary: true }).collect();
    let g = Graph { nodes, curves: Vec::new(), segments, labels: (0..6).map(|c| format!("curve {c}")).collect() };
    let res = Resampled {
        normals: vec![DVec3::Z; 6],
        on_boundary: vec![true; 6],
        segment_vertices: (0..6).map(|s| vec![s as u32, next(s) as u32]).collect(),
        positions,
    };
    let cycle = |k: usize| Patch::Disk((3 * k..3 * k + 3).map(|segment| HalfEdge { segment, forward: true }).collect());
    let Err(e) = tessellate(&g, &res, &[cycle(0), cycle(1)], 0.5) else { panic!("accepted") };
    assert!(
        e.to_string().starts_with("patch 1 (bounded by curve 3, curve 4, curve 5): the cycle encloses no area"),
        "{e}"
    );
    assert_eq!(e.at().patch, Some(1));
    // The first patch alone is fine.
    let mesh = tessellate(&g, &res, &[cycle(0)], 0.5);
    assert!(matches!(mesh, Err(Error::Topology { .. })), "vertices 3–5 bound no patch: {mesh:?}");
}
