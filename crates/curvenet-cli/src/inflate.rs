//! `curvenet inflate`: an SVG sketch inflated into a surface (\[A11\] §5; docs/cauchy.md).

use clap::Args;
use curvenet::io::{check_mesh_path, write_mesh, MeshData};
use curvenet::sketch::inflate::{inflate, read_sketch, InflateOptions};
use curvenet::Error;
use std::io::Write;
use std::path::PathBuf;
use std::time::Instant;

#[derive(Args)]
pub struct InflateArgs {
    /// Input sketch (.svg): the largest closed path bounds the surface; paths with
    /// class="crease" become creases, the others inactive curves.
    input: PathBuf,
    /// Output mesh (.ply, .obj, .off, .glb). Written only if the whole run succeeds.
    #[arg(short, long)]
    output: PathBuf,
    /// Laplacian order (1, 2 or 3).
    #[arg(long, value_name = "K", default_value_t = 2)]
    order: usize,
    /// Tilt of the outline's orientation out of the sketch plane, degrees (90: a balloon).
    #[arg(long, value_name = "DEG", default_value_t = 90.0)]
    angle: f64,
    /// Stretch of the outline's Cauchy constraints: the rim's tangent magnitude × (1 + S).
    #[arg(long, value_name = "S", default_value_t = 0.0)]
    stretch: f64,
    /// Sharpness of creases without data-sharpness, degrees (> 0 ridge, < 0 valley).
    #[arg(long, value_name = "DEG", default_value_t = 30.0)]
    crease_sharpness: f64,
    /// Approximate number of vertices.
    #[arg(long, value_name = "N", default_value_t = 5000)]
    vertices: usize,
    /// Re-solves with centred ghost vertices (0: the paper's ghosts).
    #[arg(long, value_name = "N", default_value_t = 10)]
    ghost_updates: usize,
    /// The global `-q` (`Cli::quiet`): print nothing but results, errors and warnings.
    #[arg(skip)]
    pub(crate) quiet: bool,
}

pub fn run(a: &InflateArgs) -> Result<(), Error> {
    let start = Instant::now();
    check_mesh_path(&a.output)?;
    let paths = read_sketch(&a.input)?;
    let opts = InflateOptions {
        order: a.order,
        angle: a.angle,
        stretch: a.stretch,
        crease_sharpness: a.crease_sharpness,
        vertices: a.vertices,
        ghost_updates: a.ghost_updates,
    };
    let s = inflate(&paths, &opts)?;
    let normals = curvenet::operators::vertex_normals(&s.faces, &s.positions);
    write_mesh(
        &a.output,
        MeshData {
            positions: &s.positions,
            faces: &s.faces,
            normals: Some(&normals),
            mean_curvature: None,
            curve_vertex: Some(&s.on_path),
            propagated_normals: None,
            obj_split_normals: true,
        },
    )?;
    if !a.quiet {
        out!(
            "{}: {} paths ({} creases), {} vertices, {} faces, height {:.4} = {:.3} × the outline's radius, {:.3} s",
            a.output.display(),
            paths.len(),
            s.creases,
            s.positions.len(),
            s.faces.len(),
            s.height,
            s.height / s.radius,
            start.elapsed().as_secs_f64()
        );
    }
    Ok(())
}
