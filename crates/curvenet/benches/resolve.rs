//! `cargo bench -p curvenet --bench resolve`: the interactive loop of issue 31 — move the
//! interior samples of one curve, re-solve with the kept [`curvenet::Surfacer`] — against a
//! fresh run (`curvenet::surface`, in the library: no file reading or writing) with `--fast`
//! and in the default mode, measured in the same process. Prints medians and the ratios.
//!
//! Options (after `--`): `--runs K` (default 7), `--vertices N` (default 20000), network
//! names (default `sphere torus`).

use curvenet::geom::DVec3;
use curvenet::metrics::median;
use curvenet::network::examples;
use curvenet::{Network, Options, Surfacer};
use std::time::Instant;

/// The samples of curve `c` pushed along their normals by a bump of height `h` that vanishes
/// near the other curves (at the nodes), so that the nodes and segments stay.
pub fn bumped(net: &Network, c: usize, h: f64) -> Vec<DVec3> {
    let diag = net.bounding_box().diagonal();
    let others: Vec<DVec3> =
        net.curves.iter().enumerate().filter(|&(i, _)| i != c).flat_map(|(_, k)| k.points.iter().copied()).collect();
    let curve = &net.curves[c];
    curve
        .points
        .iter()
        .zip(&curve.normals)
        .map(|(&p, &n)| {
            let d = others.iter().map(|q| q.distance(p)).fold(f64::INFINITY, f64::min);
            let t = (d / (0.15 * diag)).clamp(0.0, 1.0);
            let w = t * t * (3.0 - 2.0 * t);
            p + n.normalize_or_zero() * (h * diag * w)
        })
        .collect()
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).filter(|a| a != "--bench").collect();
    let mut runs = 7;
    let mut vertices = 20_000;
    let mut names = Vec::new();
    let mut i = 0;
    while i < args.len() {
        match args[i].as_str() {
            "--runs" => {
                runs = args[i + 1].parse().expect("--runs K");
                i += 1;
            }
            "--vertices" => {
                vertices = args[i + 1].parse().expect("--vertices N");
                i += 1;
            }
            other => names.push(other.to_string()),
        }
        i += 1;
    }
    if names.is_empty() {
        names = vec!["sphere".into(), "torus".into()];
    }
    println!("re-solve after moving the interior samples of curve 0 (a bump of 1 % of the diagonal),");
    println!("median of {runs}, release build; fresh = curvenet::surface in the library; to fresh / max: the");
    println!("last re-solve's mean and largest vertex distance to a fresh run on the moved network, ÷ diagonal");
    println!(
        "{:<8} {:<8} {:>8} {:>10} {:>10} {:>10} {:>10} {:>9} {:>9} {:>9} {:>9} {:>9}",
        "network",
        "mode",
        "vertices",
        "fresh [s]",
        "update [s]",
        "solve [s]",
        "re-solve",
        "÷fresh",
        "÷fast",
        "moved",
        "to fresh",
        "max"
    );
    for name in &names {
        let net = examples::example(name).expect("unknown example");
        let fast = Options::fast().with_vertices(vertices);
        // The median time of `runs` fresh runs with `opts`.
        let fresh_run = |opts: &Options| {
            median(
                (0..runs)
                    .map(|_| {
                        let t = Instant::now();
                        curvenet::surface(&net, opts).expect("surface");
                        t.elapsed().as_secs_f64()
                    })
                    .collect(),
            )
        };
        let fresh_fast = fresh_run(&fast);
        for (mode, opts) in [("fast", fast.clone()), ("default", Options::default().with_vertices(vertices))] {
            let fresh = fresh_run(&opts);
            let mut s = Surfacer::new(&net, &opts).expect("surfacer");
            let first = s.solve().expect("first solve");
            let (mut update, mut solve, mut moved) = (Vec::new(), Vec::new(), 0.0f64);
            let mut last = None;
            for k in 0..runs {
                // Alternate between two shapes so that every re-solve has something to do.
                let h = if k % 2 == 0 { 0.01 } else { -0.01 };
                let points = bumped(&net, 0, h);
                let t = Instant::now();
                s.update_points(0, &points).expect("update_points");
                update.push(t.elapsed().as_secs_f64());
                let t = Instant::now();
                let again = s.solve().expect("re-solve");
                solve.push(t.elapsed().as_secs_f64());
                if std::env::var("RESOLVE_STAGES").is_ok() {
                    eprintln!("{name} {mode}: {:?}", again.stats.timings);
                    let m = &again.mesh;
                    let t = Instant::now();
                    let _ = curvenet::geom::intersect::self_intersections(&m.positions, &m.faces);
                    let a = t.elapsed().as_secs_f64();
                    let t = Instant::now();
                    let _ = curvenet::operators::normals_and_mean_curvature(&m.faces, &m.positions, &m.on_boundary);
                    let b = t.elapsed().as_secs_f64();
                    let t = Instant::now();
                    let _ = curvenet::pipeline::coverage::check_reach(m);
                    let c = t.elapsed().as_secs_f64();
                    let t = Instant::now();
                    let _ = curvenet::operators::cotan_operators(m, curvenet::Metric::Planar, &m.positions);
                    let d = t.elapsed().as_secs_f64();
                    eprintln!("  self-intersections {a:.4} normals+H {b:.4} reach {c:.4} planar ops {d:.4}");
                }
                last = Some((again.mesh.positions.clone(), points));
                moved = again
                    .mesh
                    .positions
                    .iter()
                    .zip(&first.mesh.positions)
                    .map(|(a, b)| a.distance(*b))
                    .fold(moved, f64::max);
            }
            // The last re-solve against a fresh run on the moved network: the distance of its
            // vertices to the fresh surface, relative to the diagonal.
            let (positions, points) = last.expect("a re-solve");
            let mut moved_net = net.clone();
            moved_net.curves[0].points = points;
            let reference = curvenet::surface(&moved_net, &opts).expect("fresh run on the moved network");
            let diag = net.bounding_box().diagonal();
            let index = curvenet::geom::distance::MeshDistance::new(&reference.mesh.positions, &reference.mesh.faces);
            let d: Vec<f64> = positions.iter().map(|&p| index.closest(p).0 / diag).collect();
            let (mean, max) = (d.iter().sum::<f64>() / d.len() as f64, d.iter().copied().fold(0.0, f64::max));
            let (update, solve) = (median(update), median(solve));
            let total = update + solve;
            println!(
                "{:<8} {:<8} {:>8} {:>10.4} {:>10.4} {:>10.4} {:>10.4} {:>9.3} {:>9.3} {:>9.2e} {:>9.2e} {:>9.2e}",
                name,
                mode,
                first.stats.vertices,
                fresh,
                update,
                solve,
                total,
                total / fresh,
                total / fresh_fast,
                moved,
                mean,
                max
            );
        }
    }
}
