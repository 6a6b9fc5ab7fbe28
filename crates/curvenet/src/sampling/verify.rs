//! The sampled network as `curvenet surface` takes it (issue 29: the default round trip
//! `sample` → `surface` failed on a human figure). The pipeline's own checks — consolidation,
//! validation, nodes, cycles, tessellation at the default options, no solve — run on the
//! assembled network; a curve they refuse is left out and they run again, at most
//! [`MAX_ROUNDS`] times. Of the curves an error names, a crease goes first (the surface is then
//! smooth there), else the curve the error is about.

use super::SampleReport;
use crate::error::{Error, Result};
use crate::geom::DVec3;
use crate::network::Network;
use crate::pipeline::Options;

/// The most curves left out for the checks.
pub const MAX_ROUNDS: usize = 48;

/// The crease curves [`surfaceable`] left out.
#[derive(Default)]
pub(super) struct LeftOutCreases {
    /// Their samples.
    pub(super) points: Vec<DVec3>,
    /// Per curve: its name and the error.
    pub(super) why: Vec<String>,
}

/// The pipeline's checks of `net` at `options` (no solve).
fn check(net: &Network, options: &Options) -> Result<()> {
    let mut quiet = |_: &str, _: f64, _: &str| {};
    let consolidated = crate::pipeline::consolidate(net, options, &mut quiet)?;
    let network = consolidated.as_ref().filter(|c| c.changed()).map_or(net, |c| &c.network);
    crate::pipeline::infer::infer_and_prepare(network, options, &mut quiet).map(|_| ())
}

/// The curve of `net` to leave out for error `e`: of those whose names the message quotes, a
/// crease first, else the last named; `None` when it names none.
fn culprit(net: &Network, e: &Error) -> Option<usize> {
    let text = e.to_string();
    let named: Vec<usize> = (0..net.curves.len())
        .filter(|&i| {
            net.curves[i]
                .name
                .as_ref()
                .is_some_and(|n| text.contains(&format!("curve \"{n}\"")) || text.contains(&format!("(\"{n}\")")))
        })
        .collect();
    named.iter().copied().find(|&i| !net.curves[i].normals_right.is_empty()).or(named.last().copied())
}

/// `net` with the curves the pipeline's checks refuse left out, each named with its reason in
/// `report.left_out`; the error that remains, if any, in `report.unsurfaced`. Also the samples
/// of the crease curves left out ([`super::sample_mesh`] samples again with their chains
/// smooth: a section that ended on a crease left out would end on nothing).
pub(super) fn surfaceable(mut net: Network, report: &mut SampleReport) -> (Network, LeftOutCreases) {
    let options = Options::default();
    let mut creases = LeftOutCreases::default();
    for _ in 0..MAX_ROUNDS {
        let e = match check(&net, &options) {
            Ok(()) => return (net, creases),
            Err(e) => e,
        };
        let Some(c) = culprit(&net, &e) else {
            report.unsurfaced = Some(e.to_string());
            return (net, creases);
        };
        let curve = &net.curves[c];
        let count = if !curve.normals_right.is_empty() {
            creases.points.extend_from_slice(&curve.points);
            creases.why.push(format!("{}: {e}", curve.name.as_deref().unwrap_or_default()));
            &mut report.creases
        } else if curve.boundary {
            &mut report.boundary_loops
        } else {
            &mut report.sections
        };
        *count = count.saturating_sub(1);
        let name = curve.name.clone().unwrap_or_default();
        report.left_out.push(format!("{name}: {e}"));
        net.curves.remove(c);
    }
    if let Err(e) = check(&net, &options) {
        report.unsurfaced = Some(e.to_string());
    }
    (net, creases)
}

/// Vertices of the quick surface [`mesh_coverage`] measures.
pub const COVERAGE_VERTICES: usize = 6000;

/// A point of the sampled mesh counts as covered when the quick surface passes this close to
/// it, relative to the mesh's bounding-box diagonal.
pub const COVERAGE_DISTANCE: f64 = 0.02;

/// At most this many of the mesh's vertices are measured (evenly strided).
const COVERAGE_PROBES: usize = 20_000;

/// The share of the mesh's area (`positions`, `faces`: the mesh that was sampled, `diag` its
/// box diagonal) that the surface of `net` passes within [`COVERAGE_DISTANCE`] of: the
/// surface of the default options at [`COVERAGE_VERTICES`] vertices, each mesh vertex weighted by
/// a third of its faces' area. The round trip's own check (issue 29: a sampled human figure
/// whose network `surface` took came back without its arms). `None` when that surface fails.
pub fn mesh_coverage(net: &Network, positions: &[DVec3], faces: &[[u32; 3]], diag: f64) -> Option<f64> {
    let mut options = Options::default();
    options.mesh.vertices = Some(COVERAGE_VERTICES);
    let surface = crate::pipeline::surface(net, &options).ok()?;
    let tree = crate::geom::distance::MeshDistance::new(&surface.mesh.positions, &surface.mesh.faces);
    let mut area = vec![0.0; positions.len()];
    for f in faces {
        let [a, b, c] = f.map(|i| positions[i as usize]);
        let third = (b - a).cross(c - a).length() / 6.0;
        f.iter().for_each(|&i| area[i as usize] += third);
    }
    let stride = positions.len().div_ceil(COVERAGE_PROBES).max(1);
    let (mut near, mut total) = (0.0, 0.0);
    for v in (0..positions.len()).step_by(stride) {
        total += area[v];
        if tree.closest(positions[v]).0 <= COVERAGE_DISTANCE * diag {
            near += area[v];
        }
    }
    Some(if total > 0.0 { near / total } else { 1.0 })
}
