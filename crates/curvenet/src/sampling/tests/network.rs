use super::*;
use crate::geom::Aabb;
use crate::sampling::tests::{raw, traced};

#[test]
fn a_straight_polyline_is_resampled_uniformly_with_its_ends() {
    let line = [raw(0.0, 0.0, false), raw(0.37, 0.0, false), raw(1.0, 0.0, false)];
    let (p, n) = resample(&line, false, 0.1, true);
    assert_eq!(p.len(), 11);
    for (k, q) in p.iter().enumerate() {
        assert!((q.x - k as f64 / 10.0).abs() < 1e-12 && q.y == 0.0, "{q}");
    }
    assert!(n.iter().all(|n| *n == DVec3::Z));
}

#[test]
fn crossings_are_samples_with_shared_nodes_and_fall_between_samples_without() {
    let line = [raw(0.0, 0.0, false), raw(0.37, 0.0, true), raw(1.0, 0.0, false)];
    let (p, _) = resample(&line, false, 0.1, true);
    // 0..0.37 in 4 steps, 0.37..1 in 6.
    assert_eq!(p.len(), 11);
    assert_eq!(p[4], DVec3::new(0.37, 0.0, 0.0));
    assert!((p[1].x - 0.0925).abs() < 1e-12 && (p[5].x - 0.475).abs() < 1e-12);
    let (p, _) = resample(&line, false, 0.1, false);
    assert_eq!(p.len(), 11);
    assert!(p.iter().all(|q| (q.x - 0.37).abs() > 0.02));
}

#[test]
fn corners_are_kept_through_resampling() {
    let l: Vec<Raw> = (0..=4)
        .map(|k| raw(k as f64 * 0.25, 0.0, false))
        .chain((1..=4).map(|k| raw(1.0, k as f64 * 0.25, false)))
        .collect();
    let (p, _) = resample(&l, false, 0.3, false);
    // Each leg (length 1) in round(1 / 0.3) = 3 steps, the corner a sample.
    assert_eq!(p.len(), 7);
    assert_eq!(p[3], DVec3::X);
    // The same polyline closed (a triangle): its three corners are samples.
    let (p, _) = resample(&l, true, 0.3, false);
    for c in [DVec3::ZERO, DVec3::X, DVec3::new(1.0, 1.0, 0.0)] {
        assert!(p.contains(&c), "corner {c} missing from {p:?}");
    }
}

#[test]
fn a_closed_curve_without_corners_starts_half_a_step_from_its_node() {
    // A circle of 64 samples (no corners), radius 1, one node at angle 0.
    let circle: Vec<Raw> = (0..64)
        .map(|k| {
            let a = std::f64::consts::TAU * k as f64 / 64.0;
            raw(a.cos(), a.sin(), k == 0)
        })
        .collect();
    let (p, n) = resample(&circle, true, 0.1, false);
    assert_eq!(p.len(), n.len());
    // 2π / 0.1 ≈ 63 samples, none at the node.
    assert!((60..=64).contains(&p.len()), "{}", p.len());
    assert!(p.iter().all(|q| q.distance(DVec3::X) > 0.04));
    let (p, _) = resample(&circle, true, 0.1, true);
    assert_eq!(p[0], DVec3::X);
}

#[test]
fn a_hairpin_is_cut_off() {
    // Along y = 0 to (1, 0), up a narrow notch to y = 0.5 and back down 0.01 beside it, on to
    // (2, 0).
    let mut pts: Vec<DVec3> = (0..=10).map(|k| DVec3::new(k as f64 / 10.0, 0.0, 0.0)).collect();
    pts.extend((1..=5).map(|k| DVec3::new(1.0, k as f64 / 10.0, 0.0)));
    pts.extend((0..=5).rev().map(|k| DVec3::new(1.01, k as f64 / 10.0, 0.0)));
    pts.extend((1..=9).map(|k| DVec3::new(1.01 + k as f64 * 0.11, 0.0, 0.0)));
    let mut normals = vec![DVec3::Z; pts.len()];
    assert_eq!(remove_hairpins(&mut pts, &mut normals, false, 0.02), 1);
    assert_eq!(pts.len(), normals.len());
    assert!(pts.iter().all(|q| q.y == 0.0), "{pts:?}");
    assert_eq!(pts[0], DVec3::ZERO);
    assert!((pts[pts.len() - 1].x - 2.0).abs() < 1e-12);
    // Without a hairpin nothing changes.
    let mut line: Vec<DVec3> = (0..30).map(|k| DVec3::new(k as f64 / 10.0, 0.0, 0.0)).collect();
    let mut normals = vec![DVec3::Z; 30];
    assert_eq!(remove_hairpins(&mut line, &mut normals, false, 0.02), 0);
    assert_eq!(line.len(), 30);
}

#[test]
fn the_network_needs_a_crossing() {
    let opts = SampleOptions { spacing: Some(0.1), noise: 0.0, ..Default::default() };
    let scales = Scales::new(Aabb::of([DVec3::ZERO, DVec3::new(3.0, 4.0, 0.0)]), &opts).unwrap();
    let section = || {
        let mut t = traced((0..=10).map(|k| raw(k as f64 / 10.0, 0.0, k == 5)).collect(), false);
        t.name = "X=0 #0".into();
        t
    };
    let mut report = SampleReport::default();
    let e = assemble(vec![section()], Vec::new(), &opts, &scales, &mut report).unwrap_err();
    assert!(matches!(e, Error::Topology { .. }) && e.to_string().contains("`planes`"), "{e}");
    let mut report = SampleReport { crossings: 1, ..Default::default() };
    let net = assemble(vec![section()], Vec::new(), &opts, &scales, &mut report).unwrap();
    assert_eq!((report.sections, report.boundary_loops, report.hairpins), (1, 0, 0));
    assert!((net.snap.unwrap() - 0.012).abs() < 1e-15);
    assert_eq!(net.curves.len(), 1);
    let c = &net.curves[0];
    assert!(c.name.as_deref() == Some("X=0 #0") && !c.closed && !c.boundary && c.points.len() == 11);
    // With noise the samples move.
    let noisy = SampleOptions { noise: 0.01, ..opts };
    let net = assemble(vec![section()], Vec::new(), &noisy, &scales, &mut report).unwrap();
    assert!(net.curves[0].points.iter().any(|q| q.y != 0.0));
}

#[test]
fn normals_of_folded_faces_are_replaced_and_crease_steps_kept() {
    let points: Vec<DVec3> = (0..6).map(|i| DVec3::new(i as f64, 0.0, 0.0)).collect();
    let up = DVec3::Z;
    // A spike at 2 (90° off both neighbours, which agree) and a normal along the curve at 5.
    let mut normals = vec![up, up, DVec3::Y, up, up, DVec3::new(1.0, 0.0, 0.1).normalize()];
    assert_eq!(repair_folded_normals(&points, &mut normals, false), 2);
    assert!(normals.iter().all(|&n| n == up), "{normals:?}");
    // A step across a crease (the normal turns by 60° once) is no fold.
    let turned = DVec3::new(0.0, 60f64.to_radians().sin(), 60f64.to_radians().cos());
    let mut step = vec![up, up, up, turned, turned, turned];
    assert_eq!(repair_folded_normals(&points, &mut step, false), 0);
    // Nothing good to copy: left for the validation to name.
    let mut all_bad = vec![DVec3::X; 6];
    assert_eq!(repair_folded_normals(&points, &mut all_bad, false), 0);
}
