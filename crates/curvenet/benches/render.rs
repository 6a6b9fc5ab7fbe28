//! `cargo bench -p curvenet --bench render`: the time to render a surface to PNG, at 1200×900,
//! for the sphere and the torus at 20k vertices (one panel per colouring; medians of 7 runs;
//! encoding the PNG included). The surfacing time is printed beside it for comparison.

use curvenet::network::examples;
use curvenet::render::{render, Coloring, RenderOptions, Scene};
use curvenet::Options;
use std::time::Instant;

use curvenet::metrics::median;

fn main() {
    println!("render 1200x900 (rasterise, shade, anti-alias, encode PNG), median of 7, release build");
    println!(
        "{:<8} {:>9} {:>10} {:>10} {:>10} {:>10} {:>10}",
        "network", "vertices", "surface", "shaded", "curvature", "isophotes", "N* dev."
    );
    for name in ["sphere", "torus"] {
        let net = examples::example(name).expect("bundled example");
        let clock = Instant::now();
        let surface = curvenet::surface(&net, &Options::default()).expect("surfaces");
        let surfacing = clock.elapsed().as_secs_f64();
        let scene = Scene::from_surface(&surface).with_network_curves(&net);
        let times: Vec<f64> = Coloring::ALL
            .iter()
            .map(|&c| {
                let opts = RenderOptions { colorings: vec![c], ..Default::default() };
                median(
                    (0..7)
                        .map(|_| {
                            let t = Instant::now();
                            let png = render(&scene, &opts).expect("renders").encode_png();
                            std::hint::black_box(png);
                            t.elapsed().as_secs_f64()
                        })
                        .collect(),
                )
            })
            .collect();
        println!(
            "{:<8} {:>9} {:>9.3}s {:>9.3}s {:>9.3}s {:>9.3}s {:>9.3}s",
            name, surface.stats.vertices, surfacing, times[0], times[1], times[2], times[3]
        );
    }
}
