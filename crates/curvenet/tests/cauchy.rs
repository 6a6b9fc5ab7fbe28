//! The Cauchy system of [A11] on problems with known answers.

use curvenet::cauchy::{MicroWeight, Role, Stencil, System};
use curvenet::geom::DVec3;

/// Cubic Hermite curve with end points `p0`, `p1` and end tangents `m0`, `m1`.
fn hermite(t: f64, p0: DVec3, p1: DVec3, m0: DVec3, m1: DVec3) -> DVec3 {
    let (t2, t3) = (t * t, t * t * t);
    (2.0 * t3 - 3.0 * t2 + 1.0) * p0 + (t3 - 2.0 * t2 + t) * m0 + (-2.0 * t3 + 3.0 * t2) * p1 + (t3 - t2) * m1
}

/// Max distance of the k = 2 polyline with Cauchy ends to the Hermite curve, `n` segments.
fn polyline_error(n: usize, micro: MicroWeight) -> f64 {
    let t: Vec<f64> = (0..=n).map(|i| i as f64 / n as f64).collect();
    let stencil = Stencil::polyline(&t);
    let mut roles = vec![Role::Free; n + 1];
    roles[0] = Role::Cauchy;
    roles[n] = Role::Cauchy;
    let (p0, p1) = (DVec3::ZERO, DVec3::new(1.0, 0.0, 0.0));
    let (m0, m1) = (DVec3::new(1.0, 2.0, 0.0), DVec3::new(1.0, -1.0, 0.5));
    let mut positions = vec![DVec3::ZERO; n + 1];
    positions[n] = p1;
    let system = System::build(&stencil, &roles, 2, micro).unwrap();
    // The ghost continues the tangent one step beyond the end: g = u ∓ h m.
    let h = 1.0 / n as f64;
    let ghosts: Vec<DVec3> =
        system.ghosts.iter().map(|g| if g.vertex == 0 { p0 - h * m0 } else { p1 + h * m1 }).collect();
    let x = system.solve(&positions, &ghosts).unwrap();
    (0..=n).map(|i| x[i].distance(hermite(t[i], p0, p1, m0, m1))).fold(0.0, f64::max)
}

#[test]
fn polyline_converges_to_the_cubic_hermite_curve() {
    let errors: Vec<f64> = [8, 16, 32, 64, 128].iter().map(|&n| polyline_error(n, MicroWeight::Consistent)).collect();
    eprintln!("k=2 Hermite errors (consistent w): {errors:?}");
    for w in errors.windows(2) {
        assert!(w[1] < 0.6 * w[0], "error does not decrease with refinement: {errors:?}");
    }
    assert!(errors[4] < 1e-2, "{errors:?}");
    let unit: Vec<f64> = [8, 16, 32, 64, 128].iter().map(|&n| polyline_error(n, MicroWeight::Unit)).collect();
    eprintln!("k=2 Hermite errors (w = 1): {unit:?}");
}

fn sphere_mean_error(order: usize, ghost_updates: usize) -> f64 {
    use curvenet::metrics::{distance_to_truth, Truth};
    let net = curvenet::examples::example("sphere").unwrap();
    let opts = curvenet::Options { method: curvenet::Method::Cauchy, order, ghost_updates, ..Default::default() };
    let s = curvenet::surface(&net, &opts).unwrap();
    let truth = Truth::parse("sphere").unwrap().unwrap();
    distance_to_truth(&s.mesh.positions, s.mesh.num_curve, &truth).mean
}

#[test]
fn sphere_network_order_3_is_within_one_percent() {
    let e3 = sphere_mean_error(3, 10);
    eprintln!("sphere, k = 3: mean distance {e3:.3e}");
    assert!(e3 <= 0.01, "{e3}");
    // The paper's plain ghosts (no centring) are first order: worse, still bounded.
    let plain = sphere_mean_error(3, 0);
    eprintln!("sphere, k = 3, plain ghosts: mean distance {plain:.3e}");
    assert!(e3 < plain);
}
