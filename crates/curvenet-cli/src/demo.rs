//! `curvenet demo`: surface the bundled sphere and report where the result went.

use crate::Progress;
use clap::Args;
use curvenet::io::write_network;
use curvenet::metrics::{distance_to_truth, Truth};
use curvenet::network::examples;
use curvenet::render::{render, Coloring, RenderOptions, Scene};
use curvenet::{Error, Options};
use std::io::Write;
use std::path::{Path, PathBuf};

#[derive(Args)]
pub struct DemoArgs {
    /// Directory for the demo's files.
    #[arg(long, default_value = "curvenet-demo")]
    out: PathBuf,
    /// The global `-q` (`Cli::quiet`): no progress (the demo's report is its result).
    #[arg(skip)]
    pub(crate) quiet: bool,
}

pub fn run(a: &DemoArgs) -> Result<(), Error> {
    std::fs::create_dir_all(&a.out).map_err(|e| Error::Io { path: a.out.display().to_string(), source: e })?;
    let net = examples::example("sphere").ok_or_else(|| Error::usage("sphere example missing"))?;
    let network_path = a.out.join("sphere.json");
    let mesh_path = a.out.join("sphere.ply");
    write_network(&network_path, &net)?;
    let progress = Progress::new(a.quiet);
    let surface = curvenet::surface_with_progress(&net, &Options::default(), &mut |s, t, d| progress.stage(s, t, d))?;
    curvenet::io::write_mesh(&mesh_path, surface.mesh_data())?;
    let picture_path = a.out.join("sphere.png");
    let scene = Scene::from_surface(&surface).with_network_curves(&net);
    let picture = RenderOptions {
        colorings: vec![Coloring::Shaded, Coloring::Curvature],
        width: 1400,
        height: 700,
        ..Default::default()
    };
    render(&scene, &picture)?.write_png(&picture_path)?;
    let truth = Truth::Sphere { center: Default::default(), radius: 1.0 };
    let err = distance_to_truth(&surface.mesh.positions, surface.mesh.num_curve, &truth);
    let s = &surface.stats;
    out!("Surfaced the bundled sphere network (3 great circles with normals) by normal control:");
    out!(
        "  {} vertices ({} free, {} on the curves), {} faces, {} patches, in {:.3} s",
        s.vertices,
        s.vertices - s.curve_vertices,
        s.curve_vertices,
        s.faces,
        s.cycles,
        s.timings.total
    );
    out!(
        "  distance of the free vertices to the unit sphere: mean {:.4}, max {:.4}, RMS {:.4} (the paper's Table 1: mean 0.0319)",
        err.mean, err.max, err.rms
    );
    out!("Wrote:");
    out!("  {}  the input network", show(&network_path));
    out!("  {}  the surface (PLY with normals, mean curvature and the curve-vertex flag)", show(&mesh_path));
    out!("  {}  a picture: shaded, and coloured by mean curvature (1 on the unit sphere)", show(&picture_path));
    out!("Next: curvenet surface {} -o sphere.obj --vertices 50000", show(&network_path));
    Ok(())
}

fn show(p: &Path) -> String {
    p.display().to_string()
}
