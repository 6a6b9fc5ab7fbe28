//! `curvenet fit` and `curvenet resurface`: reverse engineering a mesh into Cauchy constraints
//! and solving the fitted model again (\[A11\] §6; docs/cauchy.md).

use clap::Args;
use curvenet::io::{check_mesh_path, read_mesh, MeshData};
use curvenet::sketch::fit::{fit, resurface, CauchyModel, FitOptions};
use curvenet::Error;
use std::io::Write;
use std::path::PathBuf;

#[derive(Args)]
pub struct FitArgs {
    /// Input mesh (.obj, .off, .ply).
    input: PathBuf,
    /// Output model (.json): the domain mesh, its Cauchy vertices and ghost vertices.
    #[arg(short, long)]
    output: PathBuf,
    /// Laplacian order (1, 2 or 3).
    #[arg(long, value_name = "K", default_value_t = 2)]
    order: usize,
    /// Dihedral angle above which an edge is a feature, degrees.
    #[arg(long, value_name = "DEG", default_value_t = 30.0)]
    angle: f64,
    /// Fit the ghost vertices by least squares (point to point, complete setup).
    #[arg(long)]
    optimize: bool,
    /// Smooth meshes: the feature vertices are the fraction F of vertices with the most extreme
    /// mean curvature (crests and troughs) instead of the dihedral-angle edges.
    #[arg(long, value_name = "F")]
    curvature: Option<f64>,
    /// Greedy reduction of the feature curves until the largest error is below T × the mesh's
    /// largest extent / 5 ([A11] §6.1 uses 0.1).
    #[arg(long, value_name = "T")]
    reduce: Option<f64>,
    /// Also write the re-surfaced mesh.
    #[arg(long, value_name = "MESH")]
    surface: Option<PathBuf>,
    /// Time a fresh factor-and-solve against re-solves through the ghost basis ([A11] §6.2).
    #[arg(long)]
    bench: bool,
    /// The global `-q` (`Cli::quiet`): print nothing but results, errors and warnings.
    #[arg(skip)]
    pub(crate) quiet: bool,
}

#[derive(Args)]
pub struct ResurfaceArgs {
    /// A model written by `curvenet fit`.
    input: PathBuf,
    /// Output mesh (.ply, .obj, .off, .glb).
    #[arg(short, long)]
    output: PathBuf,
    /// The global `-q` (`Cli::quiet`): no summary line.
    #[arg(skip)]
    pub(crate) quiet: bool,
}

fn stage(
    path: &std::path::Path,
    positions: &[curvenet::geom::DVec3],
    faces: &[[u32; 3]],
) -> Result<curvenet::io::Staged, Error> {
    let normals = curvenet::operators::vertex_normals(faces, positions);
    curvenet::io::stage_mesh(
        path,
        MeshData {
            positions,
            faces,
            normals: Some(&normals),
            mean_curvature: None,
            curve_vertex: None,
            propagated_normals: None,
            obj_split_normals: true,
        },
    )
}

pub fn run(a: &FitArgs) -> Result<(), Error> {
    if a.output.extension().and_then(|e| e.to_str()) != Some("json") {
        return Err(Error::usage(format!("{}: the model is written as .json", a.output.display())));
    }
    if let Some(s) = &a.surface {
        check_mesh_path(s)?;
    }
    let mesh = read_mesh(&a.input)?;
    let opts = FitOptions {
        order: a.order,
        angle: a.angle,
        optimize: a.optimize,
        curvature_fraction: a.curvature,
        reduce: a.reduce,
    };
    let (model, out, report) = fit(&mesh.positions, &mesh.faces, &opts)?;
    let json = serde_json::to_string(&model).map_err(|e| Error::usage(e.to_string()))?;
    if a.bench {
        let positions = mesh.positions.clone();
        let n = positions.len();
        let mut roles = vec![curvenet::methods::andrews2011::Role::Free; n];
        for &c in &model.constraints {
            roles[c as usize] = curvenet::methods::andrews2011::Role::Cauchy;
        }
        let mut m = curvenet::geom::mesh::Mesh::default();
        m.positions = positions.clone();
        m.faces = mesh.faces.clone();
        let ops = curvenet::operators::cotan_operators(&m, curvenet::Metric::Surface, &positions);
        let stencil = curvenet::methods::andrews2011::Stencil::from_operators(&ops, positions.clone());
        let system = curvenet::methods::andrews2011::System::build(
            &stencil,
            &roles,
            a.order,
            curvenet::methods::andrews2011::MicroWeight::Consistent,
        )?;
        let ghosts: Vec<curvenet::geom::DVec3> =
            model.ghosts.iter().map(|(_, p)| curvenet::geom::DVec3::from_array(*p)).collect();
        let b =
            curvenet::methods::andrews2011::reduce::bench(&system, &positions, &ghosts, 1e-3 * report.diagonal, 10, 5)?;
        out!(
            "re-solve bench: {} unknowns, {} ghosts; fresh LU factor+solve {:.4} s; basis {:.3} s; \
             all ghosts moved (K + W G) {:.4} s = {:.1}x faster; {} ghosts of 10 vertices moved {:.6} s = {:.0}x faster; \
             basis vs direct solve max difference {:.2e}",
            b.unknowns,
            b.ghosts,
            b.factor_and_solve,
            b.basis,
            b.full_update,
            b.factor_and_solve / b.full_update,
            b.partial_ghosts,
            b.partial_update,
            b.factor_and_solve / b.partial_update,
            b.max_difference
        );
    }
    // Both outputs staged, then committed together.
    let staged_model = curvenet::io::Staged::write(&a.output, |w| w.write_all(json.as_bytes()))?;
    let staged_surface = match &a.surface {
        Some(s) => Some(stage(s, &out, &mesh.faces)?),
        None => None,
    };
    staged_model.commit()?;
    if let Some(s) = staged_surface {
        s.commit()?;
    }
    if !a.quiet && a.reduce.is_some() {
        out!("greedy reduction: {} of {} feature curves kept", report.curves_kept, report.curves);
    }
    if !a.quiet {
        out!(
            "{}: {} vertices, {} feature vertices, {} ghosts; re-surfaced: max {:.3e}, RMS {:.3e} ({:.3}% of the diagonal {:.3}); {:.3} s",
            a.output.display(),
            report.vertices,
            report.feature_vertices,
            report.ghosts,
            report.max_distance,
            report.rms_distance,
            100.0 * report.rms_distance / report.diagonal,
            report.diagonal,
            report.seconds
        );
    }
    Ok(())
}

pub fn run_resurface(a: &ResurfaceArgs) -> Result<(), Error> {
    check_mesh_path(&a.output)?;
    let bytes = curvenet::io::read_input(&a.input, curvenet::io::InputKind::Text, curvenet::io::MAX_INPUT_BYTES)?;
    let model: CauchyModel = serde_json::from_slice(&bytes).map_err(|e| Error::Parse {
        path: a.input.display().to_string(),
        line: e.line(),
        column: e.column(),
        message: e.to_string(),
    })?;
    let out = resurface(&model).map_err(|e| match e {
        Error::Input { message, .. } => Error::input(format!("{}: {message}", a.input.display())),
        e => e,
    })?;
    stage(&a.output, &out, &model.faces)?.commit()?;
    if a.quiet {
        return Ok(());
    }
    out!("{}: {} vertices re-surfaced from {} Cauchy vertices", a.output.display(), out.len(), model.constraints.len());
    Ok(())
}
