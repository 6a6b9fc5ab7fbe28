//! `curvenet eval`: measure a mesh against a ground truth (\[CG\] §4.3, Table 1 and Fig. 5).

use clap::Args;
use curvenet::io::read_network;
use curvenet::metrics::Truth;
use curvenet::Error;
use std::io::Write;
use std::path::{Path, PathBuf};

pub const EVAL_HELP: &str = "\
Truth: sphere | sphere:r | sphere:cx,cy,cz,r | torus:R,r (axis z) | cylinder:r (axis z) |
ellipsoid:a,b,c | plane (z = 0) | plane:nx,ny,nz,d | saddle (z = (x²−y²)/2) | lens | lens:r,h
(two balls of radius r at z = ±h: the `lens` example is 1,0.5) | can | can:r,h (closed cylinder
of radius r, lids at z = ±h: the `can` example is 1,1) | a reference mesh file (.obj, .ply,
.off: exact point-to-triangle distances both ways, Hausdorff and RMS).
Curve vertices are excluded, as in the paper's Table 1: from the PLY 'curve' flag, or the
vertices within 5% of the mean edge length of the curves of --network.";

#[derive(Args)]
pub struct EvalArgs {
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

/// A mesh statistics can be measured on: some triangles, every vertex finite (an input error
/// naming the file and vertex otherwise: statistics of NaN or of nothing would mislead).
fn measurable(mesh: &curvenet::io::MeshFile, path: &Path) -> Result<(), Error> {
    if mesh.faces.is_empty() || mesh.positions.is_empty() {
        return Err(Error::input(format!("{}: the mesh has no triangles to measure", path.display())));
    }
    if let Some(i) = mesh.positions.iter().position(|p| !p.is_finite()) {
        return Err(Error::input(format!(
            "{}: vertex {i} has a non-finite coordinate ({}, {}, {})",
            path.display(),
            mesh.positions[i].x,
            mesh.positions[i].y,
            mesh.positions[i].z
        )));
    }
    Ok(())
}

pub fn run(a: &EvalArgs) -> Result<(), Error> {
    use curvenet::metrics::{evaluate, near_curves, DistanceStats, Reference};
    let mesh = curvenet::io::read_mesh(&a.mesh)?;
    measurable(&mesh, &a.mesh)?;
    let reference_mesh;
    let (reference, truth_text) = match Truth::parse(&a.truth) {
        Some(Ok(t)) => (Reference::Analytic(t), a.truth.clone()),
        Some(Err(e)) => return Err(Error::usage(e)),
        None => {
            reference_mesh = curvenet::io::read_mesh(Path::new(&a.truth))?;
            measurable(&reference_mesh, Path::new(&a.truth))?;
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
        out!("{}", serde_json::to_string_pretty(&v).map_err(|e| Error::usage(e.to_string()))?);
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
    if let Some(c) = &e.mean_curvature {
        row("mean curvature error", &c.absolute);
        out!(
            "mean curvature, error relative to |H| = {:.4}: median {:.2} %, 99th percentile {:.2} %, max {:.2} %",
            c.scale,
            100.0 * c.relative_median,
            100.0 * c.relative_p99,
            100.0 * c.relative_max
        );
    }
    Ok(())
}
