//! End-to-end tests of the surfacing pipeline on networks with known answers.

use curvenet::curves::CurveSpline;
use curvenet::geom::DVec3;
use curvenet::metrics::example_truth;
use curvenet::metrics::{distance_to_truth, DistanceStats, MeshDistance, Truth};
use curvenet::network::examples::example;
use curvenet::topology::{find_nodes, find_patches, Patch};
use curvenet::{surface, Curve, Method, Network, Options};
use std::f64::consts::TAU;

/// (nodes, segments, patches) of a network.
fn topology(net: &Network) -> (usize, usize, Vec<Patch>) {
    let (net, _) = net.validated().unwrap();
    let (g, _) = find_nodes(&net, net.snap_tolerance()).unwrap();
    let splines: Vec<CurveSpline> =
        g.curves.iter().map(|c| CurveSpline::fit(&c.points, &c.normals, c.closed)).collect();
    let patches = find_patches(&g, &splines).unwrap();
    (g.nodes.len(), g.segments.len(), patches)
}

fn run(net: &Network, method: Method) -> curvenet::Surface {
    surface(net, &Options { method, ..Default::default() }).unwrap()
}

/// Mean distance to the z axis of the vertices within ±0.05 of mid-height.
fn mid_radius(s: &curvenet::Surface) -> f64 {
    let r: Vec<f64> = s.mesh.positions.iter().filter(|p| p.z.abs() < 0.05).map(|p| p.truncate().length()).collect();
    assert!(r.len() > 50);
    r.iter().sum::<f64>() / r.len() as f64
}

#[test]
fn cycle_counts() {
    let (n, s, p) = topology(&example("sphere").unwrap());
    assert_eq!((n, s, p.len()), (6, 12, 8));
    let (n, s, p) = topology(&example("cube").unwrap());
    assert_eq!((n, s, p.len()), (8, 12, 6));
    // One boundary loop and two crossing interior curves: 4 patches, the outside dropped.
    let (n, s, p) = topology(&example("saddle").unwrap());
    assert_eq!((n, s, p.len()), (5, 8, 4));
    let (n, s, p) = topology(&example("torus").unwrap());
    assert_eq!((n, s, p.len()), (8, 16, 8));
    // Two facing boundary loops: one tube, not two disks.
    let (_, _, p) = topology(&example("cylinder").unwrap());
    assert!(matches!(p.as_slice(), [Patch::Tube(_)]), "{p:?}");
}

fn error_with(net: &Network, truth: &Truth, options: &Options) -> DistanceStats {
    let s = surface(net, options).unwrap();
    distance_to_truth(&s.mesh.positions, s.mesh.num_curve, truth)
}

fn planar(method: Method) -> Options {
    Options::fast().with_method(method)
}

#[test]
fn sphere_accuracy_and_method_ordering() {
    let net = example("sphere").unwrap();
    let truth = example_truth("sphere").unwrap();
    // The default: conformal patching and 3D-operator iterations.
    let best = error_with(&net, &truth, &Options::default());
    // One pass on the paper's planar projections and weights, for each method.
    let nc = error_with(&net, &truth, &planar(Method::NormalControl));
    let bi = error_with(&net, &truth, &planar(Method::Biharmonic));
    let tri = error_with(&net, &truth, &planar(Method::Triharmonic));
    let paper = error_with(&net, &truth, &Options::paper());
    eprintln!(
        "sphere mean distance: default {:.5} (max {:.5}); planar weights: normal-control {:.5}, biharmonic {:.5}, \
         triharmonic {:.5}; the paper's variant {:.5}",
        best.mean, best.max, nc.mean, bi.mean, tri.mean, paper.mean
    );
    // [CG] Table 1: 0.0319 mean, 0.0502 max.
    assert!(best.mean <= 5e-4 && best.max <= 2.5e-3, "{best:?}");
    assert!(nc.mean <= 0.0100, "{nc:?}");
    assert!(nc.mean < bi.mean && bi.mean < tri.mean);
    // A faithful implementation of the paper measured 0.0085.
    assert!((paper.mean / 0.0085 - 1.0).abs() < 0.2 && paper.mean <= 0.0100, "{paper:?}");
    assert!(best.count > 15_000 && best.count < 22_000, "{}", best.count);
}

#[test]
fn torus_accuracy() {
    let net = example("torus").unwrap();
    let truth = example_truth("torus").unwrap();
    let best = error_with(&net, &truth, &Options::default());
    let nc = error_with(&net, &truth, &planar(Method::NormalControl));
    let bi = error_with(&net, &truth, &planar(Method::Biharmonic));
    eprintln!(
        "torus R 4, r 2 mean distance: default {:.5} (max {:.5}); planar weights: normal-control {:.4}, biharmonic {:.4}",
        best.mean, best.max, nc.mean, bi.mean
    );
    // [CG] Table 1: 0.126 mean, 0.321 max.
    assert!(best.mean <= 5e-3 && best.max <= 5e-2, "{best:?}");
    assert!(nc.mean < bi.mean, "{nc:?} {bi:?}");
}

#[test]
fn torus_with_negative_curvature_inside() {
    // R 3, r 2: the mean curvature is negative on the inner side; the signed guide must not push
    // any region to the wrong side.
    let (big_r, r) = (3.0, 2.0);
    let net = curvenet::network::examples::torus(big_r, r);
    let truth = Truth::Torus { major: big_r, minor: r };
    let s = surface(&net, &Options::default()).unwrap();
    let e = distance_to_truth(&s.mesh.positions, s.mesh.num_curve, &truth);
    // Signed offset per band of the tube angle θ (0 outside, π inside).
    let mut bands = vec![(0.0, 0usize); 12];
    for p in &s.mesh.positions[s.mesh.num_curve..] {
        let (dx, dz) = (p.truncate().length() - big_r, p.z);
        let b = (((dz.atan2(dx) + std::f64::consts::PI) / std::f64::consts::TAU * 12.0) as usize).min(11);
        bands[b].0 += (dx * dx + dz * dz).sqrt() - r;
        bands[b].1 += 1;
    }
    let worst = bands.iter().map(|b| (b.0 / b.1 as f64).abs()).fold(0.0, f64::max);
    eprintln!("torus R 3, r 2 mean distance {:.5} (max {:.5}); worst band offset {worst:.5}", e.mean, e.max);
    assert!(e.mean <= 1e-2, "{e:?}");
    assert!(worst < 1e-2, "{bands:?}");
}

#[test]
fn normal_control_shapes_tubes() {
    let barrel = mid_radius(&run(&example("barrel").unwrap(), Method::NormalControl));
    let bottleneck = mid_radius(&run(&example("bottleneck").unwrap(), Method::NormalControl));
    let cylinder = mid_radius(&run(&example("cylinder").unwrap(), Method::NormalControl));
    eprintln!("mid-height radius: barrel {barrel:.4}, cylinder {cylinder:.4}, bottleneck {bottleneck:.4}");
    assert!(barrel >= 1.10, "{barrel}");
    assert!(bottleneck <= 0.90, "{bottleneck}");
    assert!((cylinder - 1.0).abs() < 0.002, "{cylinder}");
    let s = run(&example("cylinder").unwrap(), Method::NormalControl);
    let e = distance_to_truth(&s.mesh.positions, s.mesh.num_curve, &example_truth("cylinder").unwrap());
    assert!(e.max < 1e-3, "{e:?}");
    // Positions-only baselines cannot tell the three apart (on the same mesh: planar patching,
    // whose spacing does not depend on a first normal-controlled solution).
    let bi = |name: &str| mid_radius(&surface(&example(name).unwrap(), &planar(Method::Biharmonic)).unwrap());
    assert!((bi("barrel") - bi("bottleneck")).abs() < 1e-9);
}

#[test]
fn hard_constraints_interpolate_the_input_samples() {
    for name in ["sphere", "torus", "saddle", "barrel"] {
        let net = example(name).unwrap();
        let s = run(&net, Method::NormalControl);
        let md = MeshDistance::new(&s.mesh.positions, &s.mesh.faces);
        let worst = net.curves.iter().flat_map(|c| c.points.iter()).map(|p| md.closest(*p).0).fold(0.0, f64::max);
        eprintln!("{name}: farthest input sample {worst:.2e} from the mesh (spacing {:.2e})", s.stats.spacing);
        assert!(worst <= 0.01 * s.stats.spacing, "{name}: {worst}");
    }
}

#[test]
fn sampling_direction_does_not_matter() {
    let net = example("sphere").unwrap();
    let mut rev = net.clone();
    for c in rev.curves.iter_mut().step_by(2) {
        c.points.reverse();
        c.normals.reverse();
    }
    let a = run(&net, Method::NormalControl);
    let b = run(&rev, Method::NormalControl);
    assert_eq!(a.stats.cycles, b.stats.cycles);
    let truth = Truth::Sphere { center: DVec3::ZERO, radius: 1.0 };
    let (ea, eb) = (
        distance_to_truth(&a.mesh.positions, a.mesh.num_curve, &truth),
        distance_to_truth(&b.mesh.positions, b.mesh.num_curve, &truth),
    );
    assert!((ea.mean - eb.mean).abs() < 0.05 * ea.mean, "{ea:?} {eb:?}");
    assert!((a.stats.vertices as f64 - b.stats.vertices as f64).abs() < 0.01 * a.stats.vertices as f64);
}

#[test]
fn faces_agree_with_the_normals() {
    for name in ["sphere", "torus", "barrel", "saddle", "cube"] {
        let net = example(name).unwrap();
        let s = run(&net, Method::NormalControl);
        // Mesh normals at curve vertices point the same way as the input normals.
        let agree = (0..s.mesh.num_curve).filter(|&i| s.normals[i].dot(s.mesh.curve_normals[i]) > 0.5).count();
        assert!(agree as f64 > 0.99 * s.mesh.num_curve as f64, "{name}: {agree}/{}", s.mesh.num_curve);
    }
}

#[test]
fn a_lone_boundary_loop_bounds_a_flat_disk() {
    let n = 64;
    let points: Vec<DVec3> =
        (0..n).map(|k| DVec3::new((TAU * k as f64 / n as f64).cos(), (TAU * k as f64 / n as f64).sin(), 0.5)).collect();
    let net = Network {
        curves: vec![Curve {
            name: None,
            normals: vec![DVec3::Z; n],
            points,
            closed: true,
            boundary: true,
            ..Default::default()
        }],
        snap: None,
        cycles: None,
    };
    let (_, _, p) = topology(&net);
    assert!(matches!(p.as_slice(), [Patch::Disk(_)]));
    for method in Method::ALL {
        let s = run(&net, method);
        let worst = s.mesh.positions.iter().map(|p| (p.z - 0.5).abs()).fold(0.0, f64::max);
        // The triharmonic and short-paper matrices have condition numbers ~ h⁻⁶ and h⁻⁸ (≈ 1e10
        // and 1e15 here): their round-off errors are larger than the others'.
        let tol = match method {
            Method::Triharmonic => 1e-6,
            Method::ShortPaper => 1e-4,
            _ => 1e-9,
        };
        assert!(worst < tol, "{method:?}: {worst}");
        assert!(s.normals.iter().all(|n| n.z > 0.999));
    }
}

#[test]
fn soft_constraints_stay_close_to_the_curves() {
    let net = example("sphere").unwrap();
    let hard = run(&net, Method::NormalControl);
    let moved = |s: f64| {
        let soft = surface(&net, &Options { soft: Some(s), ..Default::default() }).unwrap();
        (0..hard.mesh.num_curve).map(|i| hard.mesh.positions[i].distance(soft.mesh.positions[i])).fold(0.0, f64::max)
    };
    let (tight, loose) = (moved(0.3), moved(10.0));
    assert!(tight > 0.0 && tight < 0.001, "{tight}");
    assert!(loose > tight, "{loose} {tight}");
}

#[test]
fn soft_constraints_filter_sensor_noise() {
    // [CG] §4.5: σ = 5% of the sample spacing on positions, 5% on the normals.
    for (name, truth) in [("sphere", example_truth("sphere").unwrap()), ("torus", example_truth("torus").unwrap())] {
        let noisy = example(name).unwrap().perturbed(0.05, 1);
        let hard = error_with(&noisy, &truth, &Options::default());
        let soft = error_with(&noisy, &truth, &Options { soft: Some(1.5), ..Default::default() });
        eprintln!("noisy {name}: mean distance to the clean truth, hard {:.5}, soft {:.5}", hard.mean, soft.mean);
        assert!(soft.mean < 0.6 * hard.mean, "{name}: {soft:?} {hard:?}");
    }
}

#[test]
fn vertex_count_and_spacing_options() {
    let net = example("sphere").unwrap();
    for target in [5_000, 40_000] {
        let s = surface(&net, &Options::default().with_vertices(target)).unwrap();
        let r = s.stats.vertices as f64 / target as f64;
        assert!((0.85..1.15).contains(&r), "{target}: {}", s.stats.vertices);
    }
    let s = surface(&net, &Options::default().with_spacing(0.05)).unwrap();
    // Mean edge length close to the spacing.
    let mut total = 0.0;
    for f in &s.mesh.faces {
        for k in 0..3 {
            total += s.mesh.positions[f[k] as usize].distance(s.mesh.positions[f[(k + 1) % 3] as usize]);
        }
    }
    let mean = total / (3 * s.mesh.faces.len()) as f64;
    assert!((mean / 0.05 - 1.0).abs() < 0.25, "{mean}");
}

#[test]
fn triangulations_have_good_angles() {
    let s = run(&example("sphere").unwrap(), Method::NormalControl);
    let mut small = 0;
    for q in &s.mesh.planar {
        for k in 0..3 {
            let (u, v) = (q[(k + 1) % 3] - q[k], q[(k + 2) % 3] - q[k]);
            let angle = u.angle_to(v).abs().to_degrees();
            if angle < 25.0 - 1e-6 {
                small += 1;
            }
        }
    }
    // Only corners at the nodes (where curves meet at 90°, split among a few triangles) may
    // fall below the refinement's 25°.
    assert!(small < 50, "{small} angles below 25°");
}

/// A coarse torus with conformal patching: at 1000 vertices its first, coarse solution (twice
/// the spacing) has overlapping patches; it is made at the spacing itself instead, and the
/// surface comes out (it was an error: `study accuracy` could not start its convergence table).
#[test]
fn coarse_torus_with_conformal_patching() {
    let net = example("torus").unwrap();
    let truth = example_truth("torus").unwrap();
    for vertices in [600, 1000, 1200] {
        let s = surface(&net, &Options::default().with_vertices(vertices)).unwrap();
        let e = distance_to_truth(&s.mesh.positions, s.mesh.num_curve, &truth);
        assert!(e.mean < 0.05, "{vertices} vertices: mean {}", e.mean);
    }
}

/// Issue 18: the default converges with the mesh on the paper's coarse torus network (4
/// meridians, outer and inner equators): its RMS error never grows by more than 10 % from one
/// size to the next (it grew by 26 % from 80k to 320k when the iterations ran on the fine mesh
/// and stopped at their cap), and the sphere and torus keep the accuracy.
#[test]
fn the_default_converges_with_the_mesh_on_the_coarse_torus() {
    let net = example("torus").unwrap();
    let truth = example_truth("torus").unwrap();
    let rms: Vec<f64> = [20_000, 80_000, 320_000]
        .iter()
        .map(|&n| error_with(&net, &truth, &Options::default().with_vertices(n)).rms)
        .collect();
    eprintln!("torus RMS at 20k, 80k, 320k: {rms:?}");
    for w in rms.windows(2) {
        assert!(w[1] <= 1.1 * w[0], "{rms:?}");
    }
    let torus = error_with(&net, &truth, &Options::default().with_vertices(25_000));
    assert!(torus.mean <= 2.5e-3, "{torus:?}");
    let sphere = error_with(&example("sphere").unwrap(), &example_truth("sphere").unwrap(), &Options::default());
    assert!(sphere.mean <= 2.5e-4, "{sphere:?}");
}

#[test]
fn the_fine_level_solved_two_level_is_the_factorised_surface() {
    // Closed (one system), open with its borders (the fit's own system) and a tube: the same
    // mesh, the vertices within 1e-5 of the diagonal of the direct solution's, without a
    // fallback; the direct mode reports no conjugate gradients.
    for name in ["sphere", "saddle", "cylinder"] {
        let net = example(name).unwrap();
        let direct = surface(&net, &Options::default().with_vertices(6000)).unwrap();
        let mut options = Options::default().with_vertices(6000);
        options.set("fine_solve", "two-level").unwrap();
        let two = surface(&net, &options).unwrap();
        assert_eq!(two.mesh.faces, direct.mesh.faces, "{name}");
        let cg = two.stats.fine_cg.as_ref().unwrap_or_else(|| panic!("{name}: no conjugate gradients"));
        assert!(cg.fallbacks == 0 && cg.iterations.len() >= 2, "{name}: {cg:?}");
        assert!(direct.stats.fine_cg.is_none(), "{name}");
        let (lo, hi) = direct
            .mesh
            .positions
            .iter()
            .fold((DVec3::INFINITY, DVec3::NEG_INFINITY), |(l, h), p| (l.min(*p), h.max(*p)));
        let diag = lo.distance(hi);
        let far =
            two.mesh.positions.iter().zip(&direct.mesh.positions).map(|(a, b)| a.distance(*b)).fold(0.0, f64::max);
        assert!(far < 1e-5 * diag, "{name}: {far:e} of {diag}");
    }
}

#[test]
fn the_statistics_report_the_coarse_level() {
    // The default iterates a coarse level at twice the spacing (about a quarter of the
    // vertices) and the fine mesh starts there; the single pass has none.
    let net = example("sphere").unwrap();
    let s = surface(&net, &Options::default().with_vertices(8000)).unwrap();
    let (fine, coarse) = (s.stats.vertices as f64, s.stats.coarse_vertices as f64);
    assert!(coarse > 0.15 * fine && coarse < 0.4 * fine, "{coarse} coarse vertices for {fine}");
    let updates = &s.stats.coarse_iteration_updates;
    assert!((1..=2).contains(&updates.len()), "{updates:?}");
    assert!(updates.iter().all(|u| u.is_finite() && *u > 0.0), "{updates:?}");
    let fast = surface(&net, &Options::fast().with_vertices(8000)).unwrap();
    assert_eq!((fast.stats.coarse_vertices, fast.stats.coarse_iteration_updates.len()), (0, 0));
}
