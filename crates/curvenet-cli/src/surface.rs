//! `curvenet surface`: read a network, surface it, write the mesh (and statistics).

use crate::options::{options, SolveArgs};
use crate::Progress;
use clap::Args;
use curvenet::io::{stage_mesh, Staged};
use curvenet::Error;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::time::Instant;

#[derive(Args)]
pub struct SurfaceArgs {
    /// Input curve network (.json, .obj, .net).
    input: PathBuf,
    /// Output mesh (.ply, .obj, .off, .glb). Written only if the whole run succeeds.
    #[arg(short, long)]
    output: PathBuf,
    #[command(flatten)]
    solve: SolveArgs,
    /// Normals of an .obj output: `split` where faces meet at a crease (`f v//vn`: creases
    /// look sharp in Blender and MeshLab), or `shared`, one per vertex (`f v//v`: every vertex
    /// shared, so trimesh and Open3D load a watertight mesh).
    #[arg(long, value_name = "HOW", default_value = "split", value_parser = ["split", "shared"])]
    obj_normals: String,
    /// Write run statistics (sizes and per-stage timings) as JSON.
    #[arg(long, value_name = "FILE")]
    stats: Option<PathBuf>,
    /// Also render the surface to this PNG (see `curvenet render --help` for the picture options).
    #[arg(long, value_name = "PNG")]
    render: Option<PathBuf>,
    #[command(flatten, next_help_heading = "Picture (with --render)")]
    picture: crate::render::PictureArgs,
    /// The global `-q` (`Cli::quiet`): print nothing but results, errors and warnings.
    #[arg(skip)]
    pub(crate) quiet: bool,
}

pub fn run(a: &SurfaceArgs) -> Result<(), Error> {
    let start = Instant::now();
    let progress = Progress::new(a.quiet);
    // Check the output names before any work, so that a typo does not cost a whole run.
    curvenet::io::check_mesh_path(&a.output)?;
    let obj = a.output.extension().is_some_and(|e| e.eq_ignore_ascii_case("obj"));
    if a.obj_normals != "split" && !obj {
        return Err(Error::usage(format!(
            "`--obj-normals {}` is for an .obj output; {} is not one",
            a.obj_normals,
            a.output.display()
        )));
    }
    distinct_paths(&a.input, &[Some(&a.output), a.stats.as_ref(), a.render.as_ref()])?;
    let picture = match &a.render {
        Some(path) => {
            crate::render::check_png_path(path)?;
            Some((path, a.picture.options()?))
        }
        None => None,
    };
    let clock = Instant::now();
    let network = crate::read_network(&a.input)?;
    let read = clock.elapsed().as_secs_f64();
    progress.stage("read", read, &format!("{} curves, {} samples", network.curves.len(), network.num_samples()));
    let mut opts = options(&a.solve)?;
    if opts.method == curvenet::Method::Cauchy {
        opts.cauchy.attributes =
            curvenet::methods::andrews2011::NetworkAttributes::read(&a.input)?.map(std::sync::Arc::new);
    }
    if opts.method == curvenet::Method::NormalControl {
        progress.expect_iterations(opts.iterate.iterations);
    }
    let mut surface = curvenet::surface_with_progress(&network, &opts, &mut |s, t, d| progress.stage(s, t, d))?;
    for w in surface.warnings.iter().filter(|w| !progress.already_said(&w.message)) {
        eprintln!("warning: {w}");
    }
    let clock = Instant::now();
    let data = curvenet::io::MeshData { obj_split_normals: a.obj_normals == "split", ..surface.mesh_data() };
    let staged_mesh = stage_mesh(&a.output, data)?;
    let write = clock.elapsed().as_secs_f64();
    surface.stats.peak_memory_bytes = crate::peak_memory_bytes();
    let t = &mut surface.stats.timings;
    t.read = read;
    t.write = write;
    t.total = start.elapsed().as_secs_f64();
    let staged_stats = match &a.stats {
        Some(path) => {
            let json = serde_json::to_string_pretty(&surface.stats).map_err(|e| Error::usage(e.to_string()))?;
            Some(Staged::write(path, |w| w.write_all(json.as_bytes()))?)
        }
        None => None,
    };
    let staged_png = match &picture {
        Some((path, opts)) => {
            let scene = curvenet::render::Scene::from_surface(&surface).with_network_curves(&network);
            Some(curvenet::render::render(&scene, opts)?.stage_png(path)?)
        }
        None => None,
    };
    staged_mesh.commit()?;
    if let Some(s) = staged_stats {
        s.commit()?;
    }
    if let Some(s) = staged_png {
        s.commit()?;
    }
    progress.stage("write", write, &a.output.display().to_string());
    if !a.quiet {
        let s = &surface.stats;
        // A long run of warnings scrolls the first ones away: the summary counts them.
        let warned = match surface.warnings.len() {
            0 => String::new(),
            1 => ", 1 warning (above)".to_string(),
            n => format!(", {n} warnings (above)"),
        };
        out!(
            "{}: {} vertices ({} on curves), {} faces, {} patches, spacing {:.4e}, {} in {:.3} s{warned}",
            a.output.display(),
            s.vertices,
            s.curve_vertices,
            s.faces,
            s.cycles,
            s.spacing,
            s.method,
            s.timings.total
        );
    }
    Ok(())
}

/// The outputs name different files, none of them the input (compared as given and, where they
/// exist, as canonical paths): a usage error otherwise, before any work, so that no output
/// overwrites another or the input.
pub(crate) fn distinct_paths(input: &Path, outputs: &[Option<&PathBuf>]) -> Result<(), Error> {
    let key = |p: &Path| std::fs::canonicalize(p).unwrap_or_else(|_| p.to_path_buf());
    let outputs: Vec<&PathBuf> = outputs.iter().flatten().copied().collect();
    for (i, a) in outputs.iter().enumerate() {
        if key(a) == key(input) {
            return Err(Error::usage(format!("{} is the input file; write the outputs elsewhere", a.display())));
        }
        if let Some(b) = outputs[..i].iter().find(|b| key(b) == key(a)) {
            return Err(Error::usage(format!(
                "{} is named for two outputs; give each output (mesh, `stats`, `render`) its own file",
                b.display()
            )));
        }
    }
    Ok(())
}
