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
    };
    let e = crate::surface(&net, &Options::default()).unwrap_err();
    assert!(matches!(e, Error::Topology { .. }), "{e}");
    assert!(e.to_string().contains("stroke"), "{e}");
}
