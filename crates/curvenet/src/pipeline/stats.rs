//! What a run returns: the surface, its statistics and per-stage timings (docs/design.md §5,
//! the `--stats` file; the names are stable, benchmarks read them).

use crate::error::Warning;
use crate::geom::mesh::Mesh;
use crate::geom::DVec3;
use crate::io::MeshData;
use serde::Serialize;

/// The coarse level of a run (`pipeline::levels`), for the statistics.
#[derive(Clone, Debug, Default)]
pub(crate) struct CoarseLevel {
    /// Its vertices.
    pub(crate) vertices: usize,
    /// Largest vertex update of each of its 3D iterations.
    pub(crate) updates: Vec<f64>,
    /// Its factorisations and the prolongation to the fine level, when they precondition the
    /// fine level's systems (`solve::two_level`).
    pub(crate) system: Option<std::sync::Arc<crate::solve::two_level::Coarse>>,
}

/// Seconds per stage.
#[derive(Clone, Copy, Debug, Default, Serialize)]
pub struct Timings {
    /// Reading the input file (front ends).
    pub read: f64,
    /// Consolidating raw strokes (gaps, overdraw, jitter; `topology::consolidate`).
    pub consolidate: f64,
    /// Inferring the normals of curves that come without (0 when all are given).
    pub normals: f64,
    /// Validation, nodes and segments.
    pub nodes: f64,
    /// Splines and resampling.
    pub resample: f64,
    /// Cycles (patches).
    pub cycles: f64,
    /// Tessellation (with the conformal flattening).
    pub tessellate: f64,
    /// Operators, system matrices and right-hand sides.
    pub operators: f64,
    /// Factorisations.
    pub factor: f64,
    /// Triangular solves.
    pub solve: f64,
    /// Writing the output (front ends).
    pub write: f64,
    /// The whole run.
    pub total: f64,
}

/// Statistics of a run.
#[derive(Clone, Debug, Default, Serialize)]
pub struct Stats {
    /// Vertices of the mesh.
    pub vertices: usize,
    /// Triangles of the mesh.
    pub faces: usize,
    /// Vertices on the curves (they come first).
    pub curve_vertices: usize,
    /// Patches (cycles and tubes).
    pub cycles: usize,
    /// Connected components of the network.
    pub components: usize,
    /// Nodes where curves meet.
    pub nodes: usize,
    /// Segments between nodes.
    pub segments: usize,
    /// Target edge length of the mesh.
    pub spacing: f64,
    /// The method's name.
    pub method: String,
    /// Iterations of the 3D-operator loop that ran (0: planar weights only).
    pub iterations: usize,
    /// Why the loop stopped: `converged`, `max-iterations`, `degenerate`, `diverging`.
    pub iteration_stop: Option<String>,
    /// Largest vertex update of each iteration.
    pub iteration_updates: Vec<f64>,
    /// Vertices of the coarse level the fine mesh started on (the default: twice the
    /// spacing, `pipeline::levels`); 0 without one.
    pub coarse_vertices: usize,
    /// Largest vertex update of each 3D iteration of the coarse level (`iterations` counts
    /// the fine level's).
    pub coarse_iteration_updates: Vec<f64>,
    /// The fine level's systems solved by two-level conjugate gradients (`fine_solve =
    /// two-level`, or `auto` from 400k vertices when the coarse level converged): iterations
    /// per solve, fallbacks to a factorisation, the largest final residual. `None` when they
    /// were factorised.
    pub fine_cg: Option<crate::methods::iterated::CgCounts>,
    /// Peak resident memory of the process in bytes, when the front end measured it.
    pub peak_memory_bytes: Option<u64>,
    /// What the normal inference found, when curves came without normals (or with
    /// `infer_normals = all`).
    pub inferred_normals: Option<InferredNormals>,
    /// The fraction of the input strokes' length the surface passes near (within 1 % of the
    /// diagonal, `pipeline::coverage`), where strokes may have been left out: measured when
    /// normals were inferred, strokes consolidated or the run warned.
    pub coverage: Option<f64>,
    /// How far the farthest patch strays outside its boundary curves' bounding box, over that
    /// box's diagonal (`pipeline::coverage::patch_reach`); a surface beyond
    /// `coverage::MAX_REACH` is refused.
    pub reach: f64,
    /// Pairs of triangles that share no vertex and cross (`geom::intersect`): a surface that
    /// passes through itself, named in a warning.
    pub self_intersections: usize,
    /// Loops of the surface's open border that no boundary curve runs along (cycles left
    /// unfilled, or a sketch's border not found to be one; `coverage::check_open_borders`),
    /// counted with the coverage; `None` where that is not measured.
    pub open_borders: Option<usize>,
    /// What consolidation did (`None` with `consolidate = off`).
    pub consolidation: Option<crate::topology::consolidate::Consolidation>,
    /// Seconds per stage.
    pub timings: Timings,
}

/// What the normal inference found ([`crate::pipeline::infer`]), for `--stats`.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct InferredNormals {
    /// Curves whose normals were inferred.
    pub curves: usize,
    /// Nodes whose normal came from the tangents of the curves that cross there.
    pub nodes_from_tangents: usize,
    /// Nodes without a tangent plane of their own: their normal was carried along a curve.
    pub nodes_transported: usize,
    /// Links between nodes where the orientation was a guess (the carried normal far from the
    /// next node's tangent plane normal).
    pub doubtful_links: usize,
    /// Segments along which the orientation contradicts itself (a warning names them).
    pub contradictions: usize,
    /// Curves left out because they run along another curve (a stroke drawn twice).
    pub left_out: usize,
    /// Components that enclose no volume, taken as open surfaces (their border tagged as
    /// boundary).
    pub opened_components: usize,
    /// Times a component (or the whole closed surface) was turned to face outward.
    pub turned_outward: usize,
    /// Patches whose cycles the global search chose ([`crate::topology::search`]).
    pub chosen_cycles: usize,
    /// Nodes whose inferred normal the chosen patches turned over or replaced.
    pub cycles_repaired_nodes: usize,
    /// Seconds of the global cycle search.
    pub cycles_seconds: f64,
    /// The patches are the rotation walk's on the inferred normals, not the cycles chosen over
    /// the whole network: those could not be surfaced (a warning says why), or the walk's run
    /// along clearly more of the sketch.
    pub walk_fallback: bool,
    /// The share of the network's segment length that the patches of this inference run along.
    pub patched_share: f64,
    /// Seconds of the whole inference.
    pub seconds: f64,
}

/// The result of a surfacing run.
#[derive(Clone, Debug)]
pub struct Surface {
    /// The mesh with its final positions; vertices `0..mesh.num_curve` lie on the curves.
    pub mesh: Mesh,
    /// Unit vertex normals of the final mesh.
    pub normals: Vec<DVec3>,
    /// Signed mean curvature of the final mesh (cotangent formula; 0 on open boundaries).
    pub mean_curvature: Vec<f64>,
    /// The propagated normals `N*` (normal-control, method4, short-paper).
    pub propagated_normals: Option<Vec<DVec3>>,
    /// Per vertex: lies on a curve (the PLY `curve` flag).
    pub curve_flags: Vec<bool>,
    /// The run's statistics.
    pub stats: Stats,
    /// What was repaired, assumed or left out.
    pub warnings: Vec<Warning>,
}

impl Surface {
    /// The mesh and its attributes, for [`crate::io::write_mesh`].
    pub fn mesh_data(&self) -> MeshData<'_> {
        MeshData {
            positions: &self.mesh.positions,
            faces: &self.mesh.faces,
            normals: Some(&self.normals),
            mean_curvature: Some(&self.mean_curvature),
            curve_vertex: Some(&self.curve_flags),
            propagated_normals: self.propagated_normals.as_deref(),
            obj_split_normals: true,
        }
    }
}
