//! `curvenet study figures`: regenerates `docs/figures/*.png`, the paper-style pictures
//! (\[CG\] Fig. 1, 3–5): every method on the sphere and the torus in curvature and isophotes, the
//! cylinder with three normal sets, and the deviation of the propagated normals.

use clap::Args;
use curvenet::network::examples::example;
use curvenet::render::{render_panels, Coloring, Panel, Scene, View};
use curvenet::{Error, Method, Network, Options};
use std::io::Write;
use std::path::{Path, PathBuf};
use std::time::Instant;

#[derive(Args)]
pub struct FiguresArgs {
    /// Directory for the PNG files.
    #[arg(long, default_value = "docs/figures")]
    out: PathBuf,
    /// Approximate vertex count of each surface.
    #[arg(long, value_name = "N", default_value_t = curvenet::MeshOptions::DEFAULT_VERTICES)]
    vertices: usize,
    /// The real meshes (bumpy-cube.obj, fandisk.off); their figure is skipped when missing.
    #[arg(long, value_name = "DIR", default_value = "data/meshes")]
    data: PathBuf,
    /// The 3D sketches without normals (computer-mouse, hat, teapot, vacuum .obj); their figure
    /// is skipped when missing.
    #[arg(long, value_name = "DIR", default_value = "data/sketches")]
    sketches: PathBuf,
}

/// The methods compared, as in docs/accuracy.md: the baselines with the paper's planar
/// patching and weights, the paper's method as written, and curvenet's default.
fn methods(vertices: usize) -> Vec<(&'static str, Options)> {
    let planar = |method| Options::fast().with_method(method).with_vertices(vertices);
    vec![
        ("biharmonic", planar(Method::Biharmonic)),
        ("triharmonic", planar(Method::Triharmonic)),
        ("method (4)", planar(Method::Method4)),
        ("[CG] normal control", Options::paper().with_vertices(vertices)),
        ("curvenet default", Options::default().with_vertices(vertices)),
    ]
}

fn network(name: &str) -> Result<Network, Error> {
    example(name).ok_or_else(|| Error::usage(format!("example {name} missing")))
}

fn scene(net: &Network, options: &Options) -> Result<Scene, Error> {
    Ok(Scene::from_surface(&curvenet::surface(net, options)?).with_network_curves(net))
}

fn panel<'a>(scene: &'a Scene, coloring: Coloring, view: View, title: String, range: Option<f64>) -> Panel<'a> {
    Panel { scene, coloring, view, title, range, stripes: 14, curves: true }
}

fn write(dir: &Path, name: &str, image: curvenet::render::Image) -> Result<(), Error> {
    let path = dir.join(name);
    image.write_png(&path)?;
    out!("  {}", path.display());
    Ok(())
}

/// One row of curvature maps (a common colour range: the default surface's) and one of
/// isophotes, a column per method.
fn methods_figure(dir: &Path, name: &str, net: &Network, view: View, vertices: usize) -> Result<(), Error> {
    let methods = methods(vertices);
    let scenes = methods.iter().map(|(_, o)| scene(net, o)).collect::<Result<Vec<_>, _>>()?;
    let range = scenes.last().map(Scene::curvature_range);
    let mut panels = Vec::new();
    for ((label, _), s) in methods.iter().zip(&scenes) {
        panels.push(panel(s, Coloring::Curvature, view, format!("{label}: H"), range));
    }
    for ((label, _), s) in methods.iter().zip(&scenes) {
        panels.push(panel(s, Coloring::Isophotes, view, format!("{label}: isophotes"), None));
    }
    write(dir, name, render_panels(&panels, methods.len(), 2500, 1100)?)
}

pub fn run(a: &FiguresArgs) -> Result<(), Error> {
    let start = Instant::now();
    std::fs::create_dir_all(&a.out).map_err(|e| Error::Io { path: a.out.display().to_string(), source: e })?;
    out!("writing figures to {}:", a.out.display());
    let oblique = View { azimuth: 30.0, elevation: 25.0, zoom: 1.0 };
    methods_figure(&a.out, "methods-sphere.png", &network("sphere")?, oblique, a.vertices)?;
    methods_figure(
        &a.out,
        "methods-torus.png",
        &network("torus")?,
        View { azimuth: 30.0, elevation: 40.0, zoom: 1.0 },
        a.vertices,
    )?;

    // [CG] Fig. 1: the same two circles with three sets of normals.
    let side = View { azimuth: 20.0, elevation: 15.0, zoom: 1.0 };
    let default = Options::default().with_vertices(a.vertices);
    let tubes = ["cylinder", "barrel", "bottleneck"]
        .iter()
        .map(|n| Ok((*n, scene(&network(n)?, &default)?)))
        .collect::<Result<Vec<_>, Error>>()?;
    let range = tubes.iter().map(|(_, s)| s.curvature_range()).fold(0.0, f64::max);
    let mut panels: Vec<Panel> =
        tubes.iter().map(|(n, s)| panel(s, Coloring::Shaded, side, n.to_string(), None)).collect();
    panels.extend(tubes.iter().map(|(n, s)| panel(s, Coloring::Curvature, side, format!("{n}: H"), Some(range))));
    write(&a.out, "tubes.png", render_panels(&panels, 3, 1500, 1000)?)?;

    // [CG] Fig. 5: where the propagated normals N* leave the surface's own normals.
    let sphere = network("sphere")?;
    let torus = network("torus")?;
    let paper = Options::paper().with_vertices(a.vertices);
    let scenes = [
        ("sphere, [CG]", scene(&sphere, &paper)?),
        ("sphere, default", scene(&sphere, &default)?),
        ("torus, [CG]", scene(&torus, &paper)?),
        ("torus, default", scene(&torus, &default)?),
    ];
    let panels: Vec<Panel> = scenes
        .iter()
        .map(|(n, s)| panel(s, Coloring::NormalDeviation, oblique, format!("{n}: angle(N*, n)"), None))
        .collect();
    write(&a.out, "normal-deviation.png", render_panels(&panels, 4, 2400, 650)?)?;

    // The globe: many curves, shaded and isophotes.
    let globe = network("globe")?;
    let g = scene(&globe, &default)?;
    let panels = [
        panel(&g, Coloring::Shaded, oblique, "globe: 8 meridians, 3 parallels".into(), None),
        panel(&g, Coloring::Isophotes, oblique, "globe: isophotes".into(), None),
    ];
    write(&a.out, "globe.png", render_panels(&panels, 2, 1400, 700)?)?;
    crease_figure(&a.out, a.vertices)?;
    real_mesh_figure(&a.out, &a.data, a.vertices)?;
    sketch_figure(&a.out, &a.sketches, a.vertices)?;
    out!("done in {:.1} s", start.elapsed().as_secs_f64());
    Ok(())
}

/// Creases (docs/design.md §13): the lens and the can kept sharp, and the can with one
/// averaged normal per rim sample instead (the blob of the issue), shaded and in isophotes.
fn crease_figure(dir: &Path, vertices: usize) -> Result<(), Error> {
    let default = Options::default().with_vertices(vertices);
    let can = network("can")?;
    let mut averaged = can.clone();
    for c in averaged.curves.iter_mut().filter(|c| c.is_crease()) {
        c.normals = (0..c.points.len()).map(|i| c.mean_normal(i)).collect();
        c.normals_right.clear();
    }
    let scenes = [
        ("lens: 60 deg crease", scene(&network("lens")?, &default)?),
        ("can: 90 deg rims", scene(&can, &default)?),
        ("can, rims with one averaged normal", scene(&averaged, &default)?),
    ];
    let view = View { azimuth: 30.0, elevation: 25.0, zoom: 1.0 };
    let mut panels: Vec<Panel> =
        scenes.iter().map(|(n, s)| panel(s, Coloring::Shaded, view, n.to_string(), None)).collect();
    panels.extend(scenes.iter().map(|(_, s)| panel(s, Coloring::Isophotes, view, "isophotes".into(), None)));
    write(dir, "creases.png", render_panels(&panels, 3, 1800, 1100)?)
}

/// Networks sampled on real meshes (`curvenet sample`: 8 plane sections per axis, crossings
/// between samples, 1% noise), surfaced, beside the mesh they came from.
fn real_mesh_figure(dir: &Path, data: &Path, vertices: usize) -> Result<(), Error> {
    use curvenet::sampling::{sample_mesh, SampleOptions};
    let names = ["bumpy-cube.obj", "fandisk.off"];
    if !names.iter().all(|n| data.join(n).exists()) {
        out!("  (real-mesh figure skipped: {} has no {})", data.display(), names.join(", "));
        return Ok(());
    }
    let opts = SampleOptions { noise: 0.01, shared_nodes: false, adapt: false, ..SampleOptions::default() };
    let mut scenes = Vec::new();
    for name in names {
        let mesh = curvenet::io::read_mesh(&data.join(name))?;
        let (net, _) = sample_mesh(&mesh.positions, &mesh.faces, &opts)?;
        let source = Scene::from_mesh(mesh.as_data())?;
        let surfaced = scene(&net, &Options::default().with_vertices(vertices))?;
        scenes.push((name, source, surfaced));
    }
    let view = View { azimuth: 35.0, elevation: 25.0, zoom: 1.0 };
    let mut panels = Vec::new();
    for (name, source, surfaced) in &scenes {
        panels
            .push(Panel { curves: false, ..panel(source, Coloring::Shaded, view, format!("{name}: the mesh"), None) });
        panels.push(panel(surfaced, Coloring::Shaded, view, format!("{name}: sampled network, surfaced"), None));
        panels.push(panel(surfaced, Coloring::Isophotes, view, "isophotes".into(), None));
    }
    write(dir, "real-meshes.png", render_panels(&panels, 3, 2100, 1300)?)
}

/// 3D sketches without normals (CASSIE, OBJ edge soup): the strokes on the surface made from
/// them with inferred normals, shaded and in isophotes.
fn sketch_figure(dir: &Path, data: &Path, vertices: usize) -> Result<(), Error> {
    let names = [("computer-mouse.obj", 30.0), ("hat.obj", 30.0), ("teapot.obj", 30.0), ("vacuum.obj", 20.0)];
    if !names.iter().all(|(n, _)| data.join(n).exists()) {
        out!("  (sketch figure skipped: {} lacks one of the sketches)", data.display());
        return Ok(());
    }
    let mut scenes = Vec::new();
    for (name, azimuth) in names {
        let net = curvenet::io::read_network(&data.join(name))?;
        scenes.push((name, azimuth, scene(&net, &Options::default().with_vertices(vertices))?));
    }
    let mut panels = Vec::new();
    for (name, azimuth, s) in &scenes {
        let view = View { azimuth: *azimuth, elevation: 20.0, zoom: 1.0 };
        panels.push(panel(s, Coloring::Shaded, view, format!("{name}: strokes, no normals -> surface"), None));
        panels.push(panel(s, Coloring::Isophotes, view, "isophotes".into(), None));
    }
    write(dir, "sketches.png", render_panels(&panels, 4, 2400, 1300)?)
}
