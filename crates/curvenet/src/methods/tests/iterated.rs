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
