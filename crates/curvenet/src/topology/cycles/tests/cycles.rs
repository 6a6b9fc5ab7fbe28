use super::*;
use crate::network::{Curve, Network};
use crate::topology::find_nodes;

/// The graph of `curves` (snapping tolerance from the network) and its splines.
pub(super) fn graph(curves: Vec<Curve>) -> (Graph, Vec<CurveSpline>) {
    let net = Network { curves, snap: None, cycles: None };
    let (g, _) = find_nodes(&net, net.snap_tolerance()).unwrap();
    let splines = g.curves.iter().map(|c| CurveSpline::fit(&c.points, &c.normals, c.closed)).collect();
    (g, splines)
}

/// A circle of `n` samples about the z axis at height `z`, radius `r`, sample 0 at (r, 0, z),
/// counter-clockwise about +z, with normals `normal(point)`.
pub(super) fn circle(r: f64, z: f64, n: usize, normal: impl Fn(DVec3) -> DVec3) -> Curve {
    let points: Vec<DVec3> = (0..n)
        .map(|i| {
            let a = std::f64::consts::TAU * i as f64 / n as f64;
            DVec3::new(r * a.cos(), r * a.sin(), z)
        })
        .collect();
    let normals = points.iter().map(|&p| normal(p)).collect();
    Curve { name: None, points, normals, closed: true, boundary: false, ..Default::default() }
}

/// An open polyline from `a` to `b` with `n` samples and normals +z.
pub(super) fn line(a: DVec3, b: DVec3, n: usize) -> Curve {
    let points: Vec<DVec3> = (0..n).map(|i| a.lerp(b, i as f64 / (n - 1) as f64)).collect();
    Curve { name: None, normals: vec![DVec3::Z; n], points, closed: false, boundary: false, ..Default::default() }
}

/// Two concentric circles in z = 0 joined by a radial bridge (segment 2): the face between the
/// circles runs along the bridge both ways, a slit.
#[test]
fn a_bridge_between_two_loops_is_a_slit() {
    let (g, splines) = graph(vec![
        circle(1.0, 0.0, 64, |_| DVec3::Z),
        circle(2.0, 0.0, 64, |_| DVec3::Z),
        line(DVec3::X, 2.0 * DVec3::X, 5),
    ]);
    assert_eq!(g.segments.len(), 3);
    assert_eq!(g.segments[2].curve, 2);
    assert_eq!(find_patches_or_slits(&g, &splines).unwrap(), Err(vec![2]));
    let Err(e) = find_patches(&g, &splines) else { panic!("accepted") };
    assert!(e.to_string().starts_with("segment 2 (curve 2, from node"), "{e}");
    assert!(e.to_string().contains("has the same patch on both sides"), "{e}");
    assert_eq!((e.at().segment, e.at().curve), (Some(2), Some(2)));
}

/// Three great circles, one of them tagged as boundary: its segments have patches on both
/// sides.
#[test]
fn a_boundary_inside_the_surface_is_a_topology_error() {
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
    let mut curves: Vec<Curve> = (0..3).map(great).collect();
    curves[1].boundary = true;
    let (g, splines) = graph(curves);
    let Err(e) = find_patches(&g, &splines) else { panic!("accepted") };
    assert!(e.to_string().contains("is tagged as boundary but has patches on both sides"), "{e}");
    assert!(matches!(e, Error::Topology { .. }), "{e}");
    let s = e.at().segment.unwrap();
    assert!(g.segments[s].boundary);
    assert_eq!(e.at().curve, Some(1));
}
