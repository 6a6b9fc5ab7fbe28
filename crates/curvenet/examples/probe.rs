use curvenet::examples::{example, example_truth};
use curvenet::metrics::distance_to_truth;
use curvenet::*;
fn main() {
    let args: Vec<String> = std::env::args().collect();
    let name = &args[1];
    let n: usize = args.get(2).map(|s| s.parse().unwrap()).unwrap_or(20000);
    let net = example(name).unwrap();
    for method in Method::ALL {
        for weights in [Metric::Planar, Metric::Surface] {
            for energy in [Weighting::Area, Weighting::Uniform] {
                if method != Method::NormalControl && energy == Weighting::Uniform {
                    continue;
                }
                let o = Options {
                    method,
                    weights,
                    energy,
                    vertices: Some(n),
                    ..Default::default()
                };
                let t = std::time::Instant::now();
                let s = surface(&net, &o).unwrap();
                let dt = t.elapsed().as_secs_f64();
                let p = &s.mesh.positions;
                let mut line = format!(
                    "{:15} {:8?} {:8?} V {:6} free {:6} t {:.3}",
                    method.name(),
                    weights,
                    energy,
                    s.stats.vertices,
                    s.stats.vertices - s.stats.curve_vertices,
                    dt
                );
                if let Some(tr) = example_truth(name) {
                    let e = distance_to_truth(p, s.mesh.num_curve, &tr);
                    line += &format!(
                        " min {:.4} max {:.4} mean {:.5} rms {:.5}",
                        e.min, e.max, e.mean, e.rms
                    );
                }
                // mid radius for tubes
                let mid: Vec<f64> = p
                    .iter()
                    .filter(|q| q.z.abs() < 0.05)
                    .map(|q| q.truncate().length())
                    .collect();
                if !mid.is_empty()
                    && (name == "barrel" || name == "bottleneck" || name == "cylinder")
                {
                    line += &format!(" mid r {:.4}", mid.iter().sum::<f64>() / mid.len() as f64);
                }
                println!("{line}");
            }
        }
    }
}
