//! The `curvenet` command: argument parsing, progress and file handling around the library.
//! No numerics live here.

use clap::{Args, Parser, Subcommand, ValueEnum};
use curvenet::io::{read_network, stage_mesh, write_network, Staged};
use curvenet::metrics::{distance_to_truth, Truth};
use curvenet::{examples, Error, GuideArea, Method, Options, Patching, Weighting};
use std::io::{IsTerminal, Write};

/// `println!` that ignores a closed stdout (`curvenet … | head`) instead of panicking.
macro_rules! out {
    ($($arg:tt)*) => {{
        let _ = writeln!(std::io::stdout(), $($arg)*);
    }};
}
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Instant;

const AFTER_HELP: &str = "\
Exit codes: 0 success, 1 bad input (malformed file, invalid network, non-manifold curves, I/O),
2 usage error, 3 numerical failure.

Network formats (by extension): .json (reference), .obj (v/vn/l, group \"boundary\"), .net.
Mesh formats (by extension): .ply (binary, with normals, mean curvature, curve flag), .obj, .off.
See README.md for the formats and the method.";

#[derive(Parser)]
#[command(
    name = "curvenet",
    version,
    about = "Surface a network of 3D curves with normals into a smooth triangle mesh",
    long_about = "Turns a network of 3D curves sampled with surface normals into a smooth triangle mesh \
                  (Stanko et al., \"Surfacing curve networks with normal control\", Computers & Graphics 2016).",
    after_help = AFTER_HELP
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Surface a curve network: read IN, write the mesh to OUT.
    #[command(after_help = AFTER_HELP)]
    Surface(SurfaceArgs),
    /// Write a bundled analytic network (sphere, torus, cylinder, …) to a file.
    #[command(
        after_help = "Use --list to see the names. The format follows the extension of -o: .json, .obj or .net."
    )]
    Example(ExampleArgs),
    /// Surface the bundled sphere network and report where the result went and how accurate it is.
    Demo(DemoArgs),
    /// Measure a mesh against a ground truth: distances, normal angles, N* deviation ([CG] §4.3).
    #[command(after_help = EVAL_HELP)]
    Eval(EvalArgs),
}

const EVAL_HELP: &str = "\
Truth: sphere | sphere:r | sphere:cx,cy,cz,r | torus:R,r (axis z) | cylinder:r (axis z) |
ellipsoid:a,b,c | plane (z = 0) | plane:nx,ny,nz,d | saddle (z = (x²−y²)/2) | a reference mesh
file (.obj, .ply, .off: exact point-to-triangle distances both ways, Hausdorff and RMS).
Curve vertices are excluded, as in the paper's Table 1: from the PLY 'curve' flag, or the
vertices within 5% of the mean edge length of the curves of --network.";

#[derive(Args)]
struct EvalArgs {
    /// The mesh to measure (.ply, .obj, .off).
    mesh: PathBuf,
    /// The ground truth (see below).
    #[arg(long, value_name = "SPEC")]
    truth: String,
    /// The network the mesh was made from: its curve vertices are excluded (when the mesh
    /// carries no curve flag).
    #[arg(long, value_name = "NETWORK")]
    network: Option<PathBuf>,
    /// Print JSON instead of a table.
    #[arg(long)]
    json: bool,
}

#[derive(Clone, Copy, ValueEnum)]
enum MethodArg {
    /// [CG] eq. 1–3: normals propagated, signed mean curvature, L V = −2 H N*.
    NormalControl,
    /// Δ²V = 0 with the curves fixed (positions only).
    Biharmonic,
    /// Δ³V = 0 with the curves fixed (positions only).
    Triharmonic,
    /// [CG] eq. 4: Δ²V = 0 with ΔV = −2Hn prescribed on the curves.
    Method4,
    /// The short paper's energy: ‖Δ²V‖² + w1 ‖ΔV + 2H n*‖² (+ soft).
    ShortPaper,
}

#[derive(Clone, Copy, ValueEnum)]
enum PatchingArg {
    /// Each patch triangulated in the plane of its mean point and mean normal (the paper).
    Planar,
    /// Each patch re-triangulated in a conformal flattening of a first solution, then solved again.
    Conformal,
}

#[derive(Clone, Copy, ValueEnum)]
enum EnergyArg {
    /// Σ A_v ‖ΔV + 2H n*‖²: one factorisation serves propagation and fit.
    Area,
    /// Σ ‖ΔV + 2H n*‖² as written in the paper.
    Uniform,
}

#[derive(Clone, Copy, ValueEnum)]
enum GuideAreaArg {
    /// The Laplacian's own Voronoi area (consistent with the fit; removes most planar bias).
    Mass,
    /// The Voronoi area on the propagated surface V*, as the paper states it.
    Surface,
}

#[derive(Args)]
struct SurfaceArgs {
    /// Input curve network (.json, .obj, .net).
    input: PathBuf,
    /// Output mesh (.ply, .obj, .off). Written only if the whole run succeeds.
    #[arg(short, long)]
    output: PathBuf,
    /// Surfacing method.
    #[arg(long, value_enum, default_value = "normal-control")]
    method: MethodArg,
    /// Target edge length of the mesh and sampling distance along the curves.
    #[arg(long, value_name = "D", conflicts_with = "vertices")]
    spacing: Option<f64>,
    /// Approximate total number of vertices (used when --spacing is not given).
    #[arg(long, value_name = "N", default_value_t = Options::DEFAULT_VERTICES)]
    vertices: usize,
    /// Soft curve constraints: the surface may leave the curves to smooth out deviations shorter
    /// than about S input sample spacings (S ≈ 1–3 for sensor noise). normal-control and
    /// short-paper (where it is the short paper's w0).
    #[arg(long, value_name = "S", alias = "w0")]
    soft: Option<f64>,
    /// Weight of the curvature guide in --method short-paper, dimensionless (ω₁ = W / s⁴, s the
    /// mean patch size).
    #[arg(long, value_name = "W", default_value_t = Options::DEFAULT_W1)]
    w1: f64,
    /// Domain each patch is triangulated in.
    #[arg(long, value_enum, default_value = "conformal")]
    patching: PatchingArg,
    /// Iterations with cotangent weights rebuilt on the 3D surface (0: the paper's planar weights).
    /// The loop stops earlier when it converges.
    #[arg(long, value_name = "K", default_value_t = Options::DEFAULT_ITERATIONS)]
    iterations: usize,
    /// Per iteration, repeats of the normal pull and the fit on the same factorisation.
    #[arg(long, value_name = "N", default_value_t = Options::DEFAULT_INNER_STEPS)]
    inner_steps: usize,
    /// Convergence threshold of the iterations: largest vertex move, as a fraction of the spacing.
    #[arg(long, value_name = "T", default_value_t = Options::DEFAULT_TOLERANCE)]
    tolerance: f64,
    /// Scale of the iterations' pull of the propagated normals towards the surface's, as a
    /// fraction of the mean patch size (0: none).
    #[arg(long, value_name = "S", default_value_t = Options::DEFAULT_NORMAL_PRIOR)]
    normal_prior: f64,
    /// Weighting of the normal-control energy.
    #[arg(long, value_enum, default_value = "area")]
    energy: EnergyArg,
    /// Area dividing the mean-curvature guide ([CG] eq. 1).
    #[arg(long, value_enum, default_value = "mass")]
    guide_area: GuideAreaArg,
    /// Times the mean-curvature guide is re-estimated on the fitted surface and the fit repeated
    /// (cheap: same factorisation). 0 reproduces the paper.
    #[arg(long, value_name = "K", default_value_t = 1)]
    guide_updates: usize,
    /// Snapping tolerance: curves closer than this meet at a node [default: the network's "snap",
    /// else 1e-3 × its bounding-box diagonal].
    #[arg(long, value_name = "S")]
    snap: Option<f64>,
    /// Reproduce the paper exactly: planar patching and weights, unweighted energy, eq. 1 divided
    /// by the area on V*, no guide update, no iteration (overrides those options).
    #[arg(long)]
    paper: bool,
    /// Write run statistics (sizes and per-stage timings) as JSON.
    #[arg(long, value_name = "FILE")]
    stats: Option<PathBuf>,
    /// Print nothing but errors and warnings.
    #[arg(short, long)]
    quiet: bool,
}

#[derive(Args)]
struct ExampleArgs {
    /// Name of the example (see --list).
    #[arg(required_unless_present = "list")]
    name: Option<String>,
    /// Output network file (.json, .obj, .net).
    #[arg(short, long, required_unless_present = "list")]
    output: Option<PathBuf>,
    /// List the bundled examples.
    #[arg(long)]
    list: bool,
    /// Add sensor-like noise: Gaussian, σ = F × the sample spacing on positions, σ = F on the
    /// unit normals ([CG] §4.5).
    #[arg(long, value_name = "F")]
    noise: Option<f64>,
    /// Seed of the noise.
    #[arg(long, default_value_t = 1)]
    seed: u64,
}

#[derive(Args)]
struct DemoArgs {
    /// Directory for the demo's files.
    #[arg(long, default_value = "curvenet-demo")]
    out: PathBuf,
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let result = match cli.command {
        Command::Surface(a) => run_surface(&a),
        Command::Example(a) => run_example(&a),
        Command::Demo(a) => run_demo(&a),
        Command::Eval(a) => run_eval(&a),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::from(e.exit_code() as u8)
        }
    }
}

fn options(a: &SurfaceArgs) -> Options {
    let o = explicit_options(a);
    if a.paper {
        return Options {
            method: o.method,
            spacing: o.spacing,
            vertices: o.vertices,
            soft: o.soft,
            snap: o.snap,
            ..Options::paper()
        };
    }
    o
}

fn explicit_options(a: &SurfaceArgs) -> Options {
    Options {
        method: match a.method {
            MethodArg::NormalControl => Method::NormalControl,
            MethodArg::Biharmonic => Method::Biharmonic,
            MethodArg::Triharmonic => Method::Triharmonic,
            MethodArg::Method4 => Method::Method4,
            MethodArg::ShortPaper => Method::ShortPaper,
        },
        spacing: a.spacing,
        vertices: Some(a.vertices),
        soft: a.soft,
        w1: a.w1,
        patching: match a.patching {
            PatchingArg::Planar => Patching::Planar,
            PatchingArg::Conformal => Patching::Conformal,
        },
        iterations: a.iterations,
        inner_steps: a.inner_steps,
        tolerance: a.tolerance,
        normal_prior: a.normal_prior,
        energy: match a.energy {
            EnergyArg::Area => Weighting::Area,
            EnergyArg::Uniform => Weighting::Uniform,
        },
        guide_area: match a.guide_area {
            GuideAreaArg::Mass => GuideArea::Mass,
            GuideAreaArg::Surface => GuideArea::Surface,
        },
        guide_updates: a.guide_updates,
        snap: a.snap,
    }
}

/// Prints one progress line per finished stage on a terminal.
struct Progress {
    on: bool,
}

impl Progress {
    fn new(quiet: bool) -> Self {
        Progress { on: !quiet && std::io::stderr().is_terminal() }
    }
    fn stage(&self, name: &str, seconds: f64, detail: &str) {
        if self.on {
            eprintln!("  {name:<11}{seconds:>8.3} s   {detail}");
        }
    }
}

fn run_surface(a: &SurfaceArgs) -> Result<(), Error> {
    let start = Instant::now();
    let progress = Progress::new(a.quiet);
    // Check the output names before any work, so that a typo does not cost a whole run.
    curvenet::io::check_mesh_path(&a.output)?;
    let clock = Instant::now();
    let network = read_network(&a.input)?;
    let read = clock.elapsed().as_secs_f64();
    progress.stage("read", read, &format!("{} curves, {} samples", network.curves.len(), network.num_samples()));
    let opts = options(a);
    let mut surface = curvenet::surface_with_progress(&network, &opts, &mut |s, t, d| progress.stage(s, t, d))?;
    for w in &surface.warnings {
        eprintln!("warning: {w}");
    }
    let clock = Instant::now();
    let staged_mesh = stage_mesh(&a.output, surface.mesh_data())?;
    let write = clock.elapsed().as_secs_f64();
    let t = &mut surface.stats.timings;
    t.read = read;
    t.write = write;
    t.total = start.elapsed().as_secs_f64();
    let staged_stats = match &a.stats {
        Some(path) => {
            let json = serde_json::to_string_pretty(&surface.stats).map_err(|e| Error::Usage(e.to_string()))?;
            Some(Staged::write(path, |w| w.write_all(json.as_bytes()))?)
        }
        None => None,
    };
    staged_mesh.commit()?;
    if let Some(s) = staged_stats {
        s.commit()?;
    }
    progress.stage("write", write, &a.output.display().to_string());
    if !a.quiet {
        let s = &surface.stats;
        out!(
            "{}: {} vertices ({} on curves), {} faces, {} patches, spacing {:.4e}, {} in {:.3} s",
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

fn run_example(a: &ExampleArgs) -> Result<(), Error> {
    if a.list {
        for (name, what) in examples::EXAMPLES {
            out!("{name:<12}{what}");
        }
        return Ok(());
    }
    let (Some(name), Some(out)) = (&a.name, &a.output) else {
        return Err(Error::Usage("give an example name and -o FILE (see --list)".into()));
    };
    let net = examples::example(name).ok_or_else(|| {
        let names: Vec<&str> = examples::EXAMPLES.iter().map(|e| e.0).collect();
        Error::Usage(format!("unknown example \"{name}\"; the examples are: {}", names.join(", ")))
    })?;
    let net = match a.noise {
        Some(f) if f.is_finite() && f >= 0.0 => net.perturbed(f, a.seed),
        Some(f) => return Err(Error::Usage(format!("--noise {f} is not a non-negative number"))),
        None => net,
    };
    write_network(out, &net)?;
    let noise = a.noise.map(|f| format!(", noise {f} (seed {})", a.seed)).unwrap_or_default();
    out!("{}: example \"{name}\", {} curves, {} samples{noise}", out.display(), net.curves.len(), net.num_samples());
    Ok(())
}

fn run_demo(a: &DemoArgs) -> Result<(), Error> {
    std::fs::create_dir_all(&a.out).map_err(|e| Error::Io { path: a.out.display().to_string(), source: e })?;
    let net = examples::example("sphere").ok_or_else(|| Error::Usage("sphere example missing".into()))?;
    let network_path = a.out.join("sphere.json");
    let mesh_path = a.out.join("sphere.ply");
    write_network(&network_path, &net)?;
    let progress = Progress::new(false);
    let surface = curvenet::surface_with_progress(&net, &Options::default(), &mut |s, t, d| progress.stage(s, t, d))?;
    curvenet::io::write_mesh(&mesh_path, surface.mesh_data())?;
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
    out!("Next: curvenet surface {} -o sphere.obj --vertices 50000", show(&network_path));
    Ok(())
}

fn show(p: &Path) -> String {
    p.display().to_string()
}

fn run_eval(a: &EvalArgs) -> Result<(), Error> {
    use curvenet::metrics::{evaluate, near_curves, DistanceStats, Reference};
    let mesh = curvenet::io::read_mesh(&a.mesh)?;
    let reference_mesh;
    let (reference, truth_text) = match Truth::parse(&a.truth) {
        Some(Ok(t)) => (Reference::Analytic(t), format!("{t:?}")),
        Some(Err(e)) => return Err(Error::Usage(e)),
        None => {
            reference_mesh = curvenet::io::read_mesh(Path::new(&a.truth))?;
            (
                Reference::Mesh { positions: &reference_mesh.positions, faces: &reference_mesh.faces },
                format!("mesh {} ({} vertices)", a.truth, reference_mesh.positions.len()),
            )
        }
    };
    let exclude = match (&mesh.curve_vertex, &a.network) {
        (_, Some(net)) => {
            let net = read_network(net)?;
            let edges: Vec<f64> = mesh
                .faces
                .iter()
                .flat_map(|f| (0..3).map(move |k| (f[k], f[(k + 1) % 3])))
                .map(|(i, j)| mesh.positions[i as usize].distance(mesh.positions[j as usize]))
                .collect();
            let mean = edges.iter().sum::<f64>() / edges.len().max(1) as f64;
            near_curves(&mesh.positions, &net, 0.05 * mean)
        }
        (Some(flags), None) => flags.clone(),
        (None, None) => {
            eprintln!("warning: no curve flag in the mesh and no --network: every vertex is evaluated");
            vec![false; mesh.positions.len()]
        }
    };
    let e = evaluate(
        &mesh.positions,
        &mesh.faces,
        mesh.normals.as_deref(),
        &exclude,
        reference,
        mesh.propagated_normals.as_deref(),
    );
    if a.json {
        let v = serde_json::json!({ "mesh": a.mesh.display().to_string(), "truth": a.truth, "evaluation": e });
        out!("{}", serde_json::to_string_pretty(&v).map_err(|e| Error::Usage(e.to_string()))?);
        return Ok(());
    }
    out!("mesh   {} ({} vertices, {} on the curves excluded)", a.mesh.display(), mesh.positions.len(), e.excluded);
    out!("truth  {truth_text}");
    out!("{:<28}{:>12}{:>12}{:>12}{:>12}", "", "min", "max", "mean", "RMS");
    let row = |name: &str, d: &DistanceStats| {
        out!("{name:<28}{:>12.4e}{:>12.4e}{:>12.4e}{:>12.4e}", d.min, d.max, d.mean, d.rms);
    };
    row("distance to the truth", &e.distance);
    if let Some(r) = &e.reverse {
        row("distance truth → mesh", r);
    }
    row("normal angle [deg]", &e.normal_angle);
    if let Some(p) = &e.propagated_deviation {
        row("N* vs mesh normals [deg]", p);
    }
    if let Some(h) = e.hausdorff {
        out!("Hausdorff distance {h:.4e}");
    }
    Ok(())
}
