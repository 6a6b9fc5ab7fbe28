//! Networks without normals (issue 15): analytic networks and networks sampled from the
//! vendored meshes, their normals removed, surfaced and measured against the truth and against
//! the same build with the normals given.

use curvenet::geom::{Aabb, DVec3};
use curvenet::metrics::{distance_to_truth, evaluate, example_truth, Reference};
use curvenet::network::examples::example;
use curvenet::sampling::{sample_mesh, SampleOptions};
use curvenet::{surface, Network, Options};

/// RMS distance of the surface of `net` to the truth of example `name`.
fn rms_to_truth(name: &str, net: &Network, options: &Options) -> f64 {
    let s = surface(net, options).unwrap_or_else(|e| panic!("{name}: {e}"));
    distance_to_truth(&s.mesh.positions, 0, &example_truth(name).unwrap()).rms
}

#[test]
fn analytic_examples_without_normals_are_within_three_times_the_error_with() {
    let options = Options::default().with_vertices(10_000);
    for name in ["sphere", "globe", "cube", "torus", "cylinder", "saddle"] {
        let net = example(name).unwrap();
        let with = rms_to_truth(name, &net, &options);
        let without = rms_to_truth(name, &net.without_normals(), &options);
        let diag = net.bounding_box().diagonal();
        eprintln!("{name}: with {with:.3e}, without {without:.3e} ({:.4}% of the diagonal)", 100.0 * without / diag);
        assert!(without <= (3.0 * with).max(2e-3 * diag), "{name}: without normals {without:.3e}, with {with:.3e}");
    }
}

/// Reads a vendored mesh (`data/meshes/NAME`).
fn vendored(name: &str) -> (Vec<DVec3>, Vec<[u32; 3]>) {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../data/meshes").join(name);
    let m = curvenet::io::read_mesh(&path).unwrap();
    (m.positions, m.faces)
}

#[test]
fn sampled_meshes_without_normals_are_within_three_times_the_error_with() {
    for name in ["bumpy-cube.obj", "beetle.off"] {
        let (p, f) = vendored(name);
        let (net, _) = sample_mesh(&p, &f, &SampleOptions::default()).unwrap();
        let diag = Aabb::of(p.iter().copied()).diagonal();
        let measure = |net: &Network| {
            let s = surface(net, &Options::default().with_vertices(20_000)).unwrap_or_else(|e| panic!("{name}: {e}"));
            let e = evaluate(
                &s.mesh.positions,
                &s.mesh.faces,
                Some(&s.normals),
                &s.curve_flags,
                Reference::Mesh { positions: &p, faces: &f },
                None,
            );
            e.distance.rms
        };
        let with = measure(&net);
        let without = measure(&net.without_normals());
        eprintln!("{name}: with {:.4}%, without {:.4}% of the diagonal", 100.0 * with / diag, 100.0 * without / diag);
        assert!(without <= (3.0 * with).max(2e-3 * diag), "{name}: without normals {without:.3e}, with {with:.3e}");
    }
}

/// The vendored 3D sketches (`data/sketches`, CASSIE, no normals) that surface today (4 of 6), with the
/// share of their input vertices within 0.5% of the diagonal of the surface.
#[test]
fn sketches_without_normals_surface_through_their_strokes() {
    use curvenet::metrics::MeshDistance;
    for name in ["computer-mouse.obj", "hat.obj", "teapot.obj", "vacuum.obj"] {
        let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../data/sketches").join(name);
        let net = curvenet::io::read_network(&path).unwrap();
        assert!(net.curves.iter().all(|c| !c.has_normals()));
        let s = surface(&net, &Options::default()).unwrap_or_else(|e| panic!("{name}: {e}"));
        assert!(curvenet::geom::mesh::bad_edge(&s.mesh.faces).is_none(), "{name}: not manifold");
        let inferred = s.stats.inferred_normals.as_ref().expect("inferred");
        assert_eq!(inferred.curves, net.curves.len() - inferred.left_out);
        let diag = net.bounding_box().diagonal();
        let d = MeshDistance::new(&s.mesh.positions, &s.mesh.faces);
        let samples: Vec<DVec3> = net.curves.iter().flat_map(|c| c.points.iter().copied()).collect();
        let near = samples.iter().filter(|p| d.closest(**p).0 <= 5e-3 * diag).count();
        let share = near as f64 / samples.len() as f64;
        eprintln!("{name}: {:.1}% of the input vertices within 0.5% of the diagonal", 100.0 * share);
        assert!(share >= 0.95, "{name}: only {:.1}% of the input vertices near the surface", 100.0 * share);
    }
}
