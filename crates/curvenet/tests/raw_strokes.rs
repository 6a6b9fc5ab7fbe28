//! Raw strokes (issue 28): clean networks with a known truth redrawn as a hand draws them
//! ([`curvenet::sampling::strokes`]: gaps and overshoots, strokes drawn twice or retraced,
//! hooks, uneven spacing), consolidated and surfaced; the distance to the truth, the share of
//! the strokes the surface passes near, and the raw VR strokes of the CASSIE data set.

use curvenet::geom::DVec3;
use curvenet::metrics::{distance_to_truth, example_truth};
use curvenet::network::examples::example;
use curvenet::sampling::strokes::{as_drawn, Drawn};
use curvenet::{surface, Network, Options};

fn options() -> Options {
    Options::default().with_vertices(6000)
}

/// Surfaces the strokes of example `name` drawn with `drawn`: the RMS distance to the truth
/// relative to the diagonal and the coverage, or the error.
fn drawn_example(name: &str, drawn: &Drawn, seed: u64) -> Result<(f64, f64, curvenet::Surface), curvenet::Error> {
    let net = example(name).unwrap();
    let strokes = as_drawn(&net, drawn, seed);
    if let Ok(dir) = std::env::var("CURVENET_DUMP") {
        let path = std::path::Path::new(&dir).join(format!("{name}-{seed}.json"));
        curvenet::io::write_network(&path, &strokes).unwrap();
    }
    let diag = net.bounding_box().diagonal();
    let s = surface(&strokes, &options())?;
    let truth = example_truth(name).unwrap();
    let d = distance_to_truth(&s.mesh.positions, 0, &truth);
    Ok((d.rms / diag, s.stats.coverage.unwrap_or(1.0), s))
}

/// Of `seeds` drawings of example `name`, those that surface within 1 % of the diagonal (RMS)
/// of the truth and near ≥ 95 % of the strokes (the criterion).
fn passing(name: &str, drawn: &Drawn, seeds: u64) -> u64 {
    let mut pass = 0;
    for seed in 0..seeds {
        match drawn_example(name, drawn, seed) {
            Ok((rms, coverage, s)) => {
                let ok = rms < 0.01 && coverage >= 0.95;
                eprintln!(
                    "{name} seed {seed}: rms/diag {rms:.2e}, coverage {coverage:.3}, {:?}",
                    s.stats.consolidation
                );
                pass += ok as u64;
            }
            Err(e) => eprintln!("{name} seed {seed}: {e}"),
        }
    }
    eprintln!("{name}: {pass} of {seeds} pass");
    pass
}

#[test]
fn strokes_with_gaps_overdraw_and_hooks_on_the_sphere_surface_near_the_truth() {
    let (_, _, s) = drawn_example("globe", &Drawn::default(), 0).unwrap();
    let c = s.stats.consolidation.clone().unwrap();
    assert!(c.joined > 0 && c.merged > 0 && c.trimmed > 0, "every defect is met: {c:?}");
    // Measured: 10 of 10 (9 before consolidation dropped the points a hair's breadth from a
    // sample, whose chord made a given normal tangent to the curve).
    assert!(passing("globe", &Drawn::default(), 10) >= 10);
}

#[test]
fn strokes_on_the_torus_surface_near_the_truth() {
    // Measured: 7 of 10. The others surface with coverage 65–95 % or an RMS of 1.7 % of the
    // diagonal: strokes of an equator joined into a bridge whose cycles the rotation walk
    // misreads (a segment with one patch on both sides) — issue 30's global cycle choice.
    assert!(passing("torus", &Drawn::default(), 10) >= 7);
}

#[test]
fn the_same_strokes_are_refused_without_consolidation() {
    let strokes = as_drawn(&example("globe").unwrap(), &Drawn::default(), 0);
    let mut o = options();
    o.consolidate.enabled = false;
    assert!(surface(&strokes, &o).is_err());
}

#[test]
fn a_surface_that_misses_most_of_the_strokes_is_an_error() {
    // The sphere's three great circles, and far away many strokes that meet nothing.
    let mut net = example("sphere").unwrap();
    for k in 0..40 {
        let y = 3.0 + 0.2 * k as f64;
        let points: Vec<DVec3> = (0..10).map(|i| DVec3::new(-3.0 + 0.7 * i as f64, y, 0.5 * k as f64)).collect();
        net.curves.push(curvenet::Curve { points, ..Default::default() });
    }
    for c in &mut net.curves {
        c.normals.clear();
    }
    let Err(e) = surface(&net, &options()) else { panic!("an error, not a surface near a few strokes") };
    assert!(e.to_string().contains("passes near"), "{e}");
}

#[test]
fn clean_examples_give_the_same_surface_with_consolidation_on_and_off() {
    for name in ["sphere", "torus", "cube", "can"] {
        let net: Network = example(name).unwrap();
        let mut off = options();
        off.consolidate.enabled = false;
        let (a, b) = (surface(&net, &options()).unwrap(), surface(&net, &off).unwrap());
        assert_eq!(a.mesh.positions, b.mesh.positions, "{name}");
        assert_eq!(a.mesh.faces, b.mesh.faces, "{name}");
    }
}

/// The raw CASSIE strokes (`data/sketches/raw`): whatever surfaces stays near the strokes — no
/// vertex farther outside their bounding box than half its diagonal. The raw `flower` made a
/// spike twice the sketch's size out of a folded patch and exited 0 before the reach check
/// (`pipeline::coverage::check_reach`); then it was refused; now that patch is left open
/// (below). Each has about the vertices asked for.
#[test]
fn raw_sketches_never_give_a_surface_far_outside_the_strokes() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../data/sketches/raw");
    for name in ["computer-mouse", "flower", "hat", "shield", "teapot", "vacuum"] {
        let net = curvenet::io::read_network(&dir.join(format!("{name}.obj"))).unwrap();
        let b = net.bounding_box();
        let margin = 0.5 * b.diagonal();
        match surface(&net, &Options::default()) {
            Ok(s) => {
                let far = s.mesh.positions.iter().map(|&x| (b.min - x).max(x - b.max).max(DVec3::ZERO).length());
                let far = far.fold(0.0, f64::max);
                eprintln!(
                    "{name}: surfaced, reach {:.2}, farthest vertex {:.2} diagonals outside",
                    s.stats.reach,
                    far / b.diagonal()
                );
                assert!(far <= margin, "{name}: a vertex {:.2} diagonals outside the strokes", far / b.diagonal());
                // The vertex count follows the request also where patches keep a fallback
                // planar domain (the raw `vacuum`'s five: 36.8k vertices for 20k before the
                // spacing measured those domains on the coarse level).
                let asked = curvenet::MeshOptions::DEFAULT_VERTICES as f64;
                let ratio = s.mesh.num_vertices() as f64 / asked;
                assert!((0.75..=1.25).contains(&ratio), "{name}: {} vertices for {asked}", s.mesh.num_vertices());
            }
            Err(e) => eprintln!("{name}: {e}"),
        }
    }
}

/// A sketch's patch that runs away is left open and the sketch surfaced again, with a warning
/// naming the patch: the raw `vacuum`'s patch 4 (a cycle the choice got wrong; before the
/// spacing of fallback domains was measured, the raw `flower`'s patch 10) stopped the run; now
/// it surfaces, no patch farther out than the reach allows, and the coverage (above half of the
/// strokes, or the run would be an error) is measured against the strokes as drawn. What
/// consolidation and the normal inference did before the first try is reported as in a run
/// without a retry: their counts and seconds in the statistics, their warnings first.
#[test]
fn a_sketch_patch_that_runs_away_is_left_open() {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../data/sketches/raw/vacuum.obj");
    let net = curvenet::io::read_network(&path).unwrap();
    let s = surface(&net, &Options::default().with_vertices(20000)).unwrap();
    let opened = s.warnings.iter().find(|w| w.message.contains("it was left open and the sketch surfaced again"));
    assert!(opened.is_some_and(|w| w.at.patch == Some(4) && w.message.contains("runs away")), "{:?}", s.warnings);
    assert!(s.stats.reach <= curvenet::pipeline::coverage::MAX_REACH);
    let coverage = s.stats.coverage.expect("measured");
    eprintln!("vacuum: coverage {coverage:.2}, reach {:.2}", s.stats.reach);
    assert!(coverage >= curvenet::pipeline::coverage::MIN_COVERAGE);
    let c = s.stats.consolidation.as_ref().expect("the consolidation's report survives the retry");
    assert!(c.joined > 0 && c.trimmed > 0, "{c:?}");
    assert!(s.stats.timings.consolidate > 0.0);
    assert!(s.warnings[0].message.starts_with("consolidation: "), "{}", s.warnings[0]);
    let inferred = s.stats.inferred_normals.as_ref().expect("the inference's report survives the retry");
    assert!(inferred.curves > 0 && s.stats.timings.normals > 0.0, "{inferred:?}");
}
