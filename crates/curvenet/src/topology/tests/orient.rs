use super::*;
use crate::network::examples::example;
use crate::topology::find_nodes;

/// The graph of example `name` with its normals removed, its splines and the known flags.
fn unknown_graph(name: &str) -> (Graph, Vec<CurveSpline>, Vec<bool>) {
    let net = example(name).unwrap().without_normals();
    let (mut net, _) = net.validated().unwrap();
    for c in &mut net.curves {
        c.normals = vec![DVec3::ZERO; c.points.len()];
    }
    let snap = net.snap_tolerance();
    let (g, _) = find_nodes(&net, snap).unwrap();
    let splines: Vec<CurveSpline> =
        g.curves.iter().map(|c| CurveSpline::fit(&c.points, &c.normals, c.closed)).collect();
    let known = vec![false; g.curves.len()];
    (g, splines, known)
}

#[test]
fn tangent_plane_of_crossing_curves() {
    let (n, conf) = tangent_plane_normal(&[DVec3::X, DVec3::Y, -DVec3::X, -DVec3::Y]).unwrap();
    assert!((n.dot(DVec3::Z).abs() - 1.0).abs() < 1e-12);
    assert!((conf - 1.0).abs() < 1e-12);
    // Curves that pass in one direction span no plane.
    assert!(tangent_plane_normal(&[DVec3::X, -DVec3::X]).is_none());
    assert!(tangent_plane_normal(&[DVec3::X]).is_none());
}

#[test]
fn transport_along_a_planar_circle_stays_in_its_plane() {
    let k = 200;
    let p: Vec<DVec3> = (0..=k)
        .map(|i| {
            let a = std::f64::consts::TAU * i as f64 / k as f64;
            DVec3::new(a.cos(), a.sin(), 0.0)
        })
        .collect();
    let t: Vec<DVec3> = (0..=k)
        .map(|i| {
            let a = std::f64::consts::TAU * i as f64 / k as f64;
            DVec3::new(-a.sin(), a.cos(), 0.0)
        })
        .collect();
    // The radial direction stays radial, the plane normal stays the plane normal.
    let radial = transport(&p, &t, DVec3::X);
    for (q, r) in p.iter().zip(&radial) {
        assert!(r.dot(*q) > 1.0 - 1e-9, "{r} at {q}");
    }
    let up = transport(&p, &t, DVec3::Z);
    assert!(up.iter().all(|r| r.dot(DVec3::Z) > 1.0 - 1e-9));
}

#[test]
fn rotation_and_angle_agree() {
    let t = DVec3::Z;
    let a = DVec3::X;
    let b = rotate_about(a, t, 0.7);
    assert!((angle_about(a, b, t) - 0.7).abs() < 1e-12);
}

#[test]
fn three_great_circles_get_outward_radial_normals() {
    let (mut g, splines, known) = unknown_graph("sphere");
    let report = infer_normals(&mut g, &splines, &known).unwrap();
    assert_eq!(report.inferred_curves, 3);
    assert_eq!(report.nodes_from_tangents + 1, g.nodes.len(), "{report:?}");
    for c in &g.curves {
        for (p, n) in c.points.iter().zip(&c.normals) {
            assert!(n.dot(p.normalize()) > 1.0 - 1e-6, "normal {n} at {p}");
        }
    }
}

#[test]
fn torus_normals_point_away_from_the_tube_axis() {
    let (mut g, splines, known) = unknown_graph("torus");
    infer_normals(&mut g, &splines, &known).unwrap();
    for c in &g.curves {
        for (p, n) in c.points.iter().zip(&c.normals) {
            // The tube's centre circle (R = 4) point nearest p.
            let ring = DVec3::new(p.x, p.y, 0.0).normalize() * 4.0;
            let truth = (*p - ring).normalize();
            assert!(n.dot(truth) > 1.0 - 1e-6, "normal {n} at {p}, truth {truth}");
        }
    }
}

#[test]
fn two_facing_loops_are_a_tube_and_one_loop_a_disk() {
    let (mut g, splines, known) = unknown_graph("cylinder");
    infer_normals(&mut g, &splines, &known).unwrap();
    for c in &g.curves {
        for (p, n) in c.points.iter().zip(&c.normals) {
            let radial = DVec3::new(p.x, p.y, 0.0).normalize();
            assert!(n.dot(radial) > 1.0 - 1e-6, "normal {n} at {p}");
        }
    }
    let (mut g, splines, known) = unknown_graph("cylinder");
    g.segments.truncate(1);
    g.curves.truncate(1);
    let mut g1 = g.clone();
    g1.nodes.truncate(1);
    infer_normals(&mut g1, &splines[..1], &known[..1]).unwrap();
    assert!(g1.curves[0].normals.iter().all(|n| n.dot(DVec3::Z).abs() > 1.0 - 1e-9));
}

#[test]
fn given_normals_fix_the_orientation() {
    // The sphere with its equator's normals given pointing inward: the inferred meridians follow.
    let mut net = example("sphere").unwrap();
    for c in &mut net.curves[1..] {
        c.normals.clear();
    }
    for n in &mut net.curves[0].normals {
        *n = -*n;
    }
    let (mut net, _) = net.validated().unwrap();
    let known: Vec<bool> = net.curves.iter().map(|c| c.has_normals()).collect();
    for c in &mut net.curves {
        if !c.has_normals() {
            c.normals = vec![DVec3::ZERO; c.points.len()];
        }
    }
    let (mut g, _) = find_nodes(&net, net.snap_tolerance()).unwrap();
    let splines: Vec<CurveSpline> =
        g.curves.iter().map(|c| CurveSpline::fit(&c.points, &c.normals, c.closed)).collect();
    infer_normals(&mut g, &splines, &known).unwrap();
    for c in &g.curves[1..] {
        for (p, n) in c.points.iter().zip(&c.normals) {
            assert!(n.dot(p.normalize()) < -1.0 + 1e-6, "normal {n} at {p}");
        }
    }
}
