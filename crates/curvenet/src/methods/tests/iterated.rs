use super::*;
use crate::methods::normal_control::{NormalControl, NormalControlParams};
use crate::methods::SurfacingMethod;
use crate::network::examples::example;
use crate::pipeline::prepare::prepare;
use crate::Options;

/// The iterations seeded with the first solve's propagation factorisation (its symbolic
/// analysis reused, `Iterated::reusing`) give the surface of iterations that analyse their
/// system afresh: same pattern, same ordering, same factor.
#[test]
fn reusing_the_first_solves_analysis_changes_nothing() {
    let network = example("torus").unwrap();
    let prepared = prepare(&network, &Options::fast().with_vertices(4000), None, &mut |_, _, _| {}).unwrap();
    let mesh = &prepared.mesh;
    let ops = cotan_operators(mesh, Metric::Planar, &mesh.positions);
    let mut t = SolveTimings::default();
    let mut method = NormalControl::new(NormalControlParams::default());
    let first = method.solve(mesh, &ops, &mut t).unwrap();
    let propagation = method.take_propagation();
    assert!(propagation.is_some(), "the first solve keeps its propagation factorisation");
    let params = IterationParams {
        options: IterationOptions::default(),
        patch_size: 1.0,
        spacing: prepared.spacing,
        energy: Energy::Area,
        guide_area: GuideArea::Barycentric,
        soft_weight: None,
    };
    let fresh = Iterated::new(params).run(mesh, first.clone(), &mut t).unwrap();
    let reused = Iterated::reusing(params, propagation).run(mesh, first.clone(), &mut t).unwrap();
    assert_eq!(fresh.1.updates.len(), reused.1.updates.len());
    let d = fresh.0.positions.iter().zip(&reused.0.positions).map(|(a, b)| a.distance(*b)).fold(0.0, f64::max);
    assert!(d <= 1e-12, "reusing the analysis moved the surface by {d:e}");
    let moved = fresh.0.positions.iter().zip(&first.positions).map(|(a, b)| a.distance(*b)).fold(0.0, f64::max);
    assert!(moved > 1e-4 * prepared.spacing, "the iterations moved the surface by only {moved:e}");
}

/// On an open surface the fit system leaves out the border rows (zero weights); kept as
/// explicit zeros (where a coupling runs through a left-out row only), its pattern is the
/// propagation system's, whose symbolic analysis its factorisation then shares
/// (`factor_like`): the same solution as a factorisation of its own, and as the product
/// without the explicit zeros.
#[test]
fn the_fit_shares_the_propagation_systems_analysis() {
    use crate::methods::normal_control::fit_weights;
    use crate::methods::{factor_like, factor_on};
    use crate::solve::sparse::{product_lower, product_lower_keeping_pattern};
    let network = example("saddle").unwrap();
    let prepared = prepare(&network, &Options::fast().with_vertices(4000), None, &mut |_, _, _| {}).unwrap();
    let mesh = &prepared.mesh;
    let (n, nc) = (mesh.num_vertices(), mesh.num_curve);
    let ops = cotan_operators(mesh, Metric::Planar, &mesh.positions);
    let inv_m: Vec<f64> = ops.mass.iter().map(|a| 1.0 / a).collect();
    let left_out = mesh.fit_row_left_out();
    assert!(left_out.iter().any(|&b| b), "the saddle's border rows are left out of the fit");
    let w = fit_weights(&left_out, &inv_m, Energy::Area);
    let prop = factor_on(mesh, &product_lower(&ops.ls, &inv_m, &ops.ls, nc), nc, "propagation").unwrap();
    let q = product_lower_keeping_pattern(&ops.ls, &w, &ops.ls, nc);
    assert!(prop.same_pattern(&q, nc));
    let plain = product_lower(&ops.ls, &w, &ops.ls, nc);
    assert!(q.row_idx.len() >= plain.row_idx.len());
    let shared = factor_like(mesh, &q, nc, "fit", Some(&prop)).unwrap();
    let own = factor_on(mesh, &q, nc, "fit").unwrap();
    let without = factor_on(mesh, &plain, nc, "fit").unwrap();
    let rhs = faer::Mat::<f64>::from_fn(n - nc, 3, |i, c| ((i * 7 + c * 3) % 11) as f64 - 5.0);
    let (a, b, c) = (shared.solve(rhs.clone()), own.solve(rhs.clone()), without.solve(rhs));
    let scale = b.norm_max();
    assert!(scale > 0.0);
    assert!((&a - &b).norm_max() <= 1e-12 * scale, "the shared analysis changed the solution");
    assert!((&a - &c).norm_max() <= 1e-8 * scale, "the explicit zeros changed the solution");
}
