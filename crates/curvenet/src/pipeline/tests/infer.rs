use super::*;
use crate::metrics::{distance_to_truth, example_truth};
use crate::network::examples::example;
use crate::Error;

/// RMS distance to the truth of example `name` surfaced from `net` with `options`.
fn rms(name: &str, net: &Network, options: &Options) -> f64 {
    let s = crate::surface(net, options).unwrap();
    distance_to_truth(&s.mesh.positions, 0, &example_truth(name).unwrap()).rms
}

#[test]
fn inferred_normals_of_the_analytic_examples_are_the_true_ones() {
    // Exact (up to the sampling) where the curves are planar and cross in their planes. normals (least twist is no
    // twist); the saddle's boundary circle twists: within a few degrees.
    for (name, tolerance) in
        [("sphere", 0.5), ("globe", 0.5), ("cube", 0.5), ("torus", 0.5), ("cylinder", 0.5), ("saddle", 4.0)]
    {
        let given = example(name).unwrap();
        let inferred = infer_normals(&given.without_normals(), &Options::default()).unwrap();
        let (given, _) = given.validated().unwrap();
        let mut worst = 0.0f64;
        for (a, b) in given.curves.iter().zip(&inferred.network.curves) {
            for (n, m) in a.normals.iter().zip(&b.normals) {
                worst = worst.max(n.dot(*m).clamp(-1.0, 1.0).acos().to_degrees());
            }
        }
        assert!(worst < tolerance, "{name}: inferred normals up to {worst:.3}° from the true ones");
        assert_eq!(inferred.report.curves, given.curves.len());
    }
}

#[test]
fn sphere_without_normals_is_as_accurate_as_with() {
    let net = example("sphere").unwrap();
    let options = Options::default().with_vertices(8000);
    let with = rms("sphere", &net, &options);
    let without = rms("sphere", &net.without_normals(), &options);
    assert!(without <= 1e-3 && without <= 3.0 * with, "without normals {without:.2e}, with {with:.2e}");
}

#[test]
fn saddle_without_normals_has_the_right_shape() {
    let net = example("saddle").unwrap();
    let options = Options::default().with_vertices(8000);
    let with = rms("saddle", &net, &options);
    let without = rms("saddle", &net.without_normals(), &options);
    let diag = net.bounding_box().diagonal();
    assert!(without <= (3.0 * with).max(2e-3 * diag), "without normals {without:.2e}, with {with:.2e}");
}

#[test]
fn given_normals_win_and_all_reinfers_them() {
    let net = example("barrel").unwrap();
    // The barrel's tilted normals are given: kept as they are.
    let kept = infer_normals(&net, &Options::default()).unwrap();
    let (valid, _) = net.validated().unwrap();
    assert_eq!(kept.network, valid);
    assert_eq!(kept.report.curves, 0);
    // Re-inferred: the two circles face each other, a cylinder's radial normals.
    let options = Options { infer_normals: InferNormals::All, ..Default::default() };
    let all = infer_normals(&net, &options).unwrap();
    assert_eq!(all.report.curves, 2);
    for c in &all.network.curves {
        for (p, n) in c.points.iter().zip(&c.normals) {
            assert!(n.dot(DVec3::new(p.x, p.y, 0.0).normalize()) > 0.999, "{n} at {p}");
        }
    }
}

#[test]
fn a_single_open_stroke_is_refused() {
    let net = Network {
        curves: vec![crate::Curve {
            name: Some("stroke".into()),
            points: (0..10).map(|i| DVec3::new(i as f64, (i as f64).sin(), 0.0)).collect(),
            ..Default::default()
        }],
        snap: None,
        cycles: None,
    };
    let e = crate::surface(&net, &Options::default()).unwrap_err();
    assert!(matches!(e, Error::Topology { .. }), "{e}");
    assert!(e.to_string().contains("stroke"), "{e}");
}

#[test]
fn node_finding_takes_a_validated_network_without_normals() {
    let (net, _) = example("sphere").unwrap().without_normals().validated().unwrap();
    let (g, _) = crate::topology::find_nodes(&net, net.snap_tolerance()).unwrap();
    assert_eq!(g.nodes.len(), 6);
    assert!(g.nodes.iter().all(|n| n.normal == DVec3::ZERO));
}

/// A unit circle in the plane z = 0 as `k` open arcs that meet end to end, without normals.
fn circle_of_arcs(k: usize) -> Network {
    let arc = |j: usize| crate::Curve {
        name: None,
        points: (0..=32)
            .map(|i| {
                let a = std::f64::consts::TAU * (j as f64 + i as f64 / 32.0) / k as f64;
                DVec3::new(a.cos(), a.sin(), 0.0)
            })
            .collect(),
        ..Default::default()
    };
    Network { curves: (0..k).map(arc).collect(), snap: None, cycles: None }
}

#[test]
fn a_loop_of_open_arcs_is_a_disk() {
    // The arcs meet tangentially (no tangent plane at the joints): the plane of their points.
    let inferred = infer_normals(&circle_of_arcs(2), &Options::default()).unwrap();
    for c in &inferred.network.curves {
        assert!(c.normals.iter().all(|n| n.z.abs() > 0.999), "{:?}", &c.normals[..3]);
    }
    // Three arcs: a loop of curves without anything inside is an open disk, not two faces
    // back to back.
    let s = crate::surface(&circle_of_arcs(3), &Options::default().with_vertices(2000)).unwrap();
    assert_eq!(s.stats.cycles, 1, "{:?}", s.warnings);
    assert!(s.mesh.positions.iter().all(|p| p.z.abs() < 1e-6));
    // The cycle search keeps one face: the other side folds onto it (docs/design.md §15).
    let r = s.stats.inferred_normals.as_ref().unwrap();
    assert!(!r.walk_fallback && r.chosen_cycles == 1, "{r:?}");
}

#[test]
fn surfacer_reports_the_inference_on_its_first_solve() {
    let net = example("sphere").unwrap().without_normals();
    let mut s = crate::Surfacer::new(&net, &Options::fast().with_vertices(2000)).unwrap();
    assert!(s.network().has_all_normals());
    let first = s.solve().unwrap();
    assert_eq!(first.stats.inferred_normals.as_ref().map(|r| r.curves), Some(3));
    assert!(s.solve().unwrap().stats.inferred_normals.is_none());
}

/// A normal within 25° of a chord is taken across it: from its neighbours' normals where they
/// are across (a node normal tangent to one of its curves), not from what is left of itself,
/// which points anywhere.
#[test]
fn a_normal_along_a_chord_is_taken_across_it_from_its_neighbours() {
    let points: Vec<DVec3> = (0..8)
        .map(|k| {
            let t = std::f64::consts::TAU * k as f64 / 8.0;
            DVec3::new(t.cos(), t.sin(), 0.0)
        })
        .collect();
    let mut curve = crate::Curve { points, closed: true, ..Default::default() };
    curve.normals = vec![DVec3::Z; 8];
    // Sample 0's normal nearly along the chord to sample 1, tipped a little below the plane: its
    // own rest across the chord points down, its neighbours' up.
    let chord = (curve.points[1] - curve.points[0]).normalize();
    curve.normals[0] = (chord - 0.2 * DVec3::Z).normalize();
    across_chords(&mut curve);
    let n = curve.normals[0];
    assert!(n.dot(chord).abs() < 1e-9, "{n}");
    assert!(n.dot(DVec3::Z) > 0.9, "{n} not the neighbours' side");
    // The others were across already and are kept.
    assert!(curve.normals[1..].iter().all(|&n| n == DVec3::Z));
}

#[test]
fn the_patched_share_is_of_the_whole_sketch_dangling_parts_included() {
    // A disk's rim and a stroke dangling out of it: the patches run along the rim only, and
    // the share that compares the search's choice with the walk's counts the stroke too (a
    // choice whose left-out parts were not counted read 1.0 — docs/design.md §15 step 6).
    let mut net = circle_of_arcs(3);
    let stroke = (0..=10).map(|i| DVec3::new(1.0 + 0.05 * i as f64, 0.0, 0.0)).collect();
    net.curves.push(crate::Curve { points: stroke, ..Default::default() });
    let rim = std::f64::consts::TAU;
    for search in [true, false] {
        let r = infer(&net, &Options::default(), search).unwrap().report;
        let expected = rim / (rim + 0.5);
        assert!((r.patched_share - expected).abs() < 0.01, "search {search}: {} vs {expected}", r.patched_share);
    }
}

/// Two straight curves crossing at the origin (along x and along y) whose inferred normals are
/// 104° apart there (a crease the inference smoothed): made one at the crossing — the two
/// samples around it on each curve take the mean, across their curve, no longer more than 90°
/// apart — and left alone elsewhere; far from any curve, nothing changes.
#[test]
fn normals_at_odds_where_curves_meet_are_made_one() {
    let line = |d: DVec3, n: DVec3| crate::Curve {
        points: (-3..=3).map(|k| d * (k as f64 + 0.5) * 0.1).collect(),
        normals: vec![n; 7],
        ..Default::default()
    };
    let t = 52f64.to_radians();
    let a = line(DVec3::X, DVec3::new(0.0, t.sin(), t.cos()));
    let b = line(DVec3::Y, DVec3::new(t.sin(), 0.0, -t.cos()));
    let mut net = Network { curves: vec![a, b], snap: Some(1e-3), cycles: None };
    let before = net.curves[0].normals[3].dot(net.curves[1].normals[3]);
    assert!((before.acos().to_degrees() - 112.4).abs() < 1.0, "{}", before.acos().to_degrees());
    assert!(!agree_at(&mut net.clone(), DVec3::new(5.0, 5.0, 5.0), 0.01));
    assert!(agree_at(&mut net, DVec3::ZERO, 0.01));
    for (c, along) in net.curves.iter().zip([DVec3::X, DVec3::Y]) {
        let around: Vec<usize> = (0..7).filter(|&k| c.points[k].length() < 0.06).collect();
        assert_eq!(around, vec![2, 3]);
        for k in 0..7 {
            let moved = around.contains(&k);
            assert_eq!(moved, c.normals[k] != c.normals[0], "sample {k}");
            assert!(c.normals[k].dot(along).abs() < 1e-12 && (c.normals[k].length() - 1.0).abs() < 1e-12);
        }
    }
    assert!(net.curves[0].normals[3].dot(net.curves[1].normals[3]) > -1e-12, "no longer more than 90° apart");
    let e = Error::input("curve 0 and curve 1 meet at (0, 0, 0) with normals 112° apart: one of them points inward")
        .point(DVec3::ZERO);
    assert_eq!(points_inward(&e), Some(DVec3::ZERO));
}
