use super::*;
use crate::network::examples::example;
use crate::pipeline::{solve_prepared, surface};

fn max_distance(a: &[DVec3], b: &[DVec3]) -> f64 {
    assert_eq!(a.len(), b.len());
    a.iter().zip(b).map(|(p, q)| p.distance(*q)).fold(0.0, f64::max)
}

/// Curve `curve`'s normals tilted by `angle` (radians) about the x axis: a smooth, consistent
/// change of the normal field along the curve.
fn tilted(network: &Network, curve: usize, angle: f64) -> Vec<DVec3> {
    let (s, c) = angle.sin_cos();
    network.curves[curve].normals.iter().map(|n| DVec3::new(n.x, c * n.y - s * n.z, s * n.y + c * n.z)).collect()
}

/// The first solve equals the one-shot pipeline; a re-solve after new normals equals a fresh
/// solve (new factorisations) on the same mesh, and differs from the first surface.
fn check(name: &str, options: &Options, curve: usize) {
    let network = example(name).unwrap();
    let one_shot = surface(&network, options).unwrap();
    let mut s = Surfacer::new(&network, options).unwrap();
    assert!(!s.is_factored());
    let first = s.solve().unwrap();
    assert!(s.is_factored());
    assert_eq!(first.mesh.faces, one_shot.mesh.faces, "{name}: same mesh");
    let d0 = max_distance(&first.mesh.positions, &one_shot.mesh.positions);
    assert!(d0 <= 1e-12, "{name}: first solve differs from the pipeline by {d0:e}");

    let normals = tilted(&network, curve, 0.15);
    s.update_normals(curve, &normals).unwrap();
    let again = s.solve().unwrap();
    let fresh =
        solve_prepared(std::borrow::Cow::Borrowed(&s.prepared), options, &mut |_, _, _| {}, None, Timings::default())
            .unwrap();
    let d = max_distance(&again.mesh.positions, &fresh.mesh.positions);
    assert!(d <= 1e-10, "{name}: re-solve differs from a fresh solve by {d:e}");
    let moved = max_distance(&again.mesh.positions, &first.mesh.positions);
    assert!(moved > 1e-3, "{name}: the new normals moved the surface by only {moved:e}");
    assert_eq!(s.network().curves[curve].normals, normals);
}

#[test]
fn resolve_equals_fresh_solve_closed() {
    check("sphere", &Options { vertices: Some(3000), ..Options::fast() }, 0);
}

#[test]
fn resolve_equals_fresh_solve_open_border() {
    // Open border: the fit has its own factorisation, kept too.
    check("saddle", &Options { vertices: Some(3000), ..Options::fast() }, 1);
}

#[test]
fn resolve_equals_fresh_solve_with_iterations() {
    check("sphere", &Options { vertices: Some(3000), ..Options::default() }, 0);
}

#[test]
fn update_normals_errors() {
    let network = example("sphere").unwrap();
    let mut s = Surfacer::new(&network, &Options { vertices: Some(2000), ..Options::fast() }).unwrap();
    let count = network.curves.len();
    let e = s.update_normals(count, &[]).unwrap_err().to_string();
    assert!(e.contains(&format!("curve {count} does not exist")), "{e}");
    let n = network.curves[0].normals.len();
    let e = s.update_normals(0, &network.curves[0].normals[1..]).unwrap_err().to_string();
    assert!(e.contains(&format!("{} normals given for {n} samples", n - 1)), "{e}");
    let mut bad = network.curves[0].normals.clone();
    bad[3] = DVec3::ZERO;
    let e = s.update_normals(0, &bad).unwrap_err().to_string();
    assert!(e.contains("sample 3"), "{e}");
    // Unchanged after the errors.
    assert_eq!(s.network().curves[0].normals, network.curves[0].normals);
}
