//! Curve networks sampled on triangle meshes (`curvenet sample`): the way to turn any mesh
//! into a test network whose ground truth is the mesh itself.
//!
//! [`sample_mesh`] intersects the mesh with families of planes perpendicular to the X, Y and Z
//! axes ("plane sections") and chains the cut segments into polylines: closed loops, or open
//! polylines that end on the mesh boundary. Where two sections of different families cross on a
//! triangle, the crossing point is computed on that triangle (the point of the triangle on both
//! planes) and inserted in both polylines, so that the network has nodes. A mesh with boundary
//! also gives its boundary loops as boundary-tagged curves, with the section end points inserted
//! in them. Normals are interpolated from the mesh's angle-weighted vertex normals (linearly
//! along an edge, barycentrically inside a triangle). The polylines are then resampled at a
//! uniform spacing; optionally the exact crossing samples are left out (as with sensors, whose
//! samples do not fall on crossings) and sensor noise is added ([`Network::perturbed`]).
//!
//! Sections that meet no other curve (a small closed loop around a bump that no other plane
//! crosses) and boundary loops that no section reaches cannot bound patches of the network;
//! they are left out and counted in [`SampleReport`].
//!
//! The stages, one file each, in the order of the data:
//!
//! 1. `mesh`: the input checked and repaired (welded, cracks zipped, pinches split), vertex
//!    normals and edge adjacency; with creases, `creases`: the sharp edges found and chained,
//!    the mesh cut open along them (each side its own vertex normals; after stage 4 the
//!    chains become crease curves).
//! 2. `planes`, `sections`: the section planes placed away from vertices and moved off bad
//!    crossings; each face cut by each plane, the cuts chained into polylines, ends that run
//!    along the boundary cut back.
//! 3. `crossings`: the exact crossings between sections on the triangles, and the bad spots
//!    (shallow crossings, near misses, crossings close together) that move the planes.
//!    Instead of 2–3, `cross_field`, `streamlines` and [`principal`]: streamlines of a cross
//!    field of principal directions, with their crossings.
//! 4. `boundary`: the boundary loops with the section ends on them as nodes.
//! 5. `cut`: sections cut at the bad spots left, at sharp turns and at crowded ends; sections
//!    that meet no other curve dropped.
//! 6. `holes`: small holes and holes that fewer than two sections reach covered, unsupported
//!    section ends cut back to their last crossing.
//! 7. `network`: the curves resampled, hairpins cut off, the network assembled, noise added.

use crate::error::{Error, Result};
use crate::geom::{Aabb, DVec3};
use crate::network::Network;
use std::collections::HashMap;

mod boundary;
mod creases;
mod cross_field;
mod crossings;
mod cut;
mod holes;
mod mesh;
mod network;
mod planes;
pub mod principal;
mod sections;
mod streamlines;
pub mod strokes;
pub mod verify;

pub use creases::{CREASE_CORNER_DEG, MIN_CREASE_SPACINGS};

/// A network with creases whose quick surface covers this share of the mesh's area is kept
/// without trying the network without creases ([`sample_mesh`]).
pub const GOOD_COVERAGE: f64 = 0.97;

/// The network without creases replaces the one with them when its surface covers more of
/// the mesh by more than this share.
pub const COVERAGE_MARGIN: f64 = 0.03;

/// The most times [`SampleOptions::adapt`] samples again with 1.5× the planes.
pub const MAX_REFINES: usize = 2;

/// The most times the mesh is sampled again with the crease curves `surface`'s checks refused
/// left smooth ([`sample_mesh`]); after the last, refused creases are left out.
pub const MAX_RESAMPLES: usize = 3;
pub use cut::SHARP_TURN_DEG;
use mesh::Mesh;
pub use mesh::{split_pinches, zip_cracks};
pub use network::{remove_hairpins, CORNER_DEG, FOLDED_NORMAL_DEG};
pub use planes::{section_directions, MAX_PLANE_MOVES, MIN_CROSSING_ANGLE_DEG};

/// Distance between the principal curves ([`CurveFamily::Principal`]) as a fraction of the
/// distance between the section planes for the same `planes` counts: two families instead of
/// three, and curves that stop short of the ones alongside them (measured on the test meshes:
/// 2/3, the same curve length per area, leaves too large patches where curves stop).
pub const PRINCIPAL_SEPARATION: f64 = 0.5;

/// Options of [`sample_mesh`]; each maps onto a flag of `curvenet sample`.
#[derive(Clone, Debug, PartialEq)]
pub struct SampleOptions {
    /// `--planes X,Y,Z`: number of section planes perpendicular to each axis (0 skips an axis).
    /// The planes of a family split the box's extent along the axis into equal slabs and pass
    /// through their middles. Default [`SampleOptions::DEFAULT_PLANES`].
    pub planes: [usize; 3],
    /// `--spacing D`: distance between consecutive samples along the curves. Default
    /// [`SampleOptions::DEFAULT_SPACING_RELATIVE`] × the bounding-box diagonal.
    pub spacing: Option<f64>,
    /// `--noise F`: Gaussian noise, σ = F × the sample spacing on positions and σ = F on the
    /// unit normals ([`Network::perturbed`]). 0: none.
    pub noise: f64,
    /// `--seed S`: seed of the noise.
    pub seed: u64,
    /// `false` with `--no-shared-nodes`: the curves are sampled uniformly along their whole
    /// length and the exact crossing points are not samples (crossings fall between samples).
    pub shared_nodes: bool,
    /// `false` with `--no-boundary`: leave the mesh's boundary loops out.
    pub boundary: bool,
    /// `--tilt DEG`: the three plane directions are the coordinate axes turned by this angle
    /// about the axis (1, 2, 3)/√14. With axis-aligned planes (`0`), a wall parallel to an axis
    /// (extruded CAD features) is cut by two families along the same lines, and the curves would
    /// overlap. Default [`SampleOptions::DEFAULT_TILT_DEG`].
    pub tilt: f64,
    /// `--curves planes|principal`: plane sections (default), or curves along the principal
    /// curvature directions ([`CurveFamily::Principal`]), [`PRINCIPAL_SEPARATION`] × the box's
    /// mean extent over the mean of the `planes` counts apart.
    pub curves: CurveFamily,
    /// `--crease-angle DEG`: mesh edges whose faces' normals are more than this many degrees
    /// apart are sharp; their chains become crease curves of the network (with the normals of
    /// both sides, docs/design.md §13) and the other curves end on them. Default
    /// [`SampleOptions::DEFAULT_CREASE_DEG`]; `None` (`--no-creases`): every curve smooth.
    pub crease_angle: Option<f64>,
    /// The mesh is the truth: when the surface of the network sampled covers less than
    /// [`GOOD_COVERAGE`] of the mesh ([`verify::mesh_coverage`]), the network without creases
    /// and then with 1.5× the planes (at most [`MAX_REFINES`] times) are tried, and the one that
    /// covers the most kept. Default `true`; `curvenet sample` turns it off when `--planes` or
    /// `--crease-angle` is given.
    pub adapt: bool,
}

/// The largest sample spacing [`sample_mesh`] takes, relative to the mesh's bounding-box
/// diagonal (the default is 1/200).
pub const MAX_SPACING_RELATIVE: f64 = 0.05;

/// The most section planes per axis [`sample_mesh`] takes.
pub const MAX_PLANES: usize = 1000;

/// The curves [`sample_mesh`] draws on the mesh.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum CurveFamily {
    /// Plane sections in three directions.
    #[default]
    Planes,
    /// Streamlines of a cross field aligned with the principal curvature directions (a fixed
    /// axis projected on the surface where it is isotropic), crossing at about 90°
    /// ([`principal`]).
    Principal,
}

impl SampleOptions {
    /// Default plane counts per axis.
    pub const DEFAULT_PLANES: [usize; 3] = [8, 8, 8];
    /// Default sample spacing relative to the bounding-box diagonal.
    pub const DEFAULT_SPACING_RELATIVE: f64 = 1.0 / 200.0;
    /// The snapping tolerance written in the network, relative to the spacing: above the chord
    /// sag (spacing² κ / 8 ≈ 3% of the spacing on the test meshes) plus 1% noise on two curves
    /// (about 4%), below the default (0.2 spacing at the default spacing) so that curves that
    /// pass close by without crossing (mesh boundaries, creases) are not snapped together.
    pub const SNAP_SPACING: f64 = 0.12;
    /// Default `tilt` in degrees.
    pub const DEFAULT_TILT_DEG: f64 = 20.0;
    /// Default `crease_angle` in degrees.
    pub const DEFAULT_CREASE_DEG: f64 = 30.0;
}

impl Default for SampleOptions {
    fn default() -> Self {
        SampleOptions {
            planes: Self::DEFAULT_PLANES,
            spacing: None,
            noise: 0.0,
            seed: 1,
            shared_nodes: true,
            boundary: true,
            tilt: Self::DEFAULT_TILT_DEG,
            curves: CurveFamily::Planes,
            crease_angle: Some(Self::DEFAULT_CREASE_DEG),
            adapt: true,
        }
    }
}

/// What [`sample_mesh`] produced and left out.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct SampleReport {
    /// Section polylines kept (curves of the network, boundary loops excluded).
    pub sections: usize,
    /// Boundary loops kept.
    pub boundary_loops: usize,
    /// Crease curves (chains of the mesh's sharp edges, [`SampleOptions::crease_angle`]).
    pub creases: usize,
    /// Crossings between sections (and section ends on boundary loops).
    pub crossings: usize,
    /// Sections left out because they meet no other curve.
    pub dropped_sections: usize,
    /// Boundary loops left out because no section reaches them.
    pub dropped_boundary_loops: usize,
    /// The sample spacing used.
    pub spacing: f64,
    /// Boundary vertices where the boundary touches itself (several fans of faces), split into
    /// one copy per fan, the copies moved apart into their fans ([`split_pinches`]).
    pub pinches: usize,
    /// Boundary vertices welded to a boundary vertex across a crack ([`zip_cracks`]).
    pub zipped: usize,
    /// Hairpins cut off the curves ([`remove_hairpins`]).
    pub hairpins: usize,
    /// Planes still in a close or shallow crossing after [`MAX_PLANE_MOVES`] moves (the
    /// pipeline may then find overlapping curves there).
    pub unresolved: usize,
    /// Section ends cut back where they ran along the mesh boundary ([`SampleOptions`]).
    pub trimmed: usize,
    /// Sections cut at bad spots: a shallow crossing, two crossings close together or a near
    /// miss still there after the plane moves ([`MAX_PLANE_MOVES`]), a section end on the
    /// boundary too close to another one, a sharp turn ([`SampleReport::sharp_turns`]). Each
    /// loses the stretch between the crossings on either side of the spot.
    pub cut_bad: usize,
    /// Places where a section turns back within the surface by more than
    /// [`SHARP_TURN_DEG`] (a plane grazing one side of a sharp crease): cut there like the bad
    /// spots ([`SampleReport::cut_bad`]).
    pub sharp_turns: usize,
    /// Boundary loops left out because a single section reached them (the hole is covered;
    /// that section's end is cut back to its last crossing).
    pub single_contact_holes: usize,
    /// Boundary loops left out because they are smaller than 3 sample spacings across.
    pub small_holes: usize,
    /// Sample normals along their curve (within [`FOLDED_NORMAL_DEG`]: a folded mesh
    /// face) replaced by the nearest good one on the curve.
    pub folded_normals: usize,
    /// Chains of sharp edges left smooth: shorter than [`MIN_CREASE_SPACINGS`] sample
    /// spacings, or running within the snapping distance of a longer one.
    pub smoothed_creases: usize,
    /// Curves left out because `surface`'s checks refused them (`verify`): each curve's name
    /// and the error.
    pub left_out: Vec<String>,
    /// The error `surface`'s checks still give after those rounds, if any.
    pub unsurfaced: Option<String>,
    /// Crease curves `surface`'s checks refused in an earlier round, their chains of sharp
    /// edges left smooth when the mesh was sampled again ([`MAX_RESAMPLES`] times at most):
    /// each curve's name in that round and the error.
    pub smoothed_refused: Vec<String>,
    /// With [`SampleOptions::adapt`]: the share of the mesh's area the network's quick surface
    /// passes near ([`verify::COVERAGE_DISTANCE`], the default options at
    /// [`verify::COVERAGE_VERTICES`] vertices); `None` when not measured or when that surface
    /// failed.
    pub mesh_coverage: Option<f64>,
    /// The creases were all left smooth because the network without them covers the mesh
    /// better by more than [`COVERAGE_MARGIN`]: the number of crease curves, the coverage
    /// with them and without them (at the same planes).
    pub creases_dropped: Option<(usize, f64, f64)>,
    /// The plane counts used when [`SampleOptions::adapt`] took more than those asked for.
    pub planes: Option<[usize; 3]>,
}

/// A sample of a polyline before resampling: position, normal, and whether it is a crossing
/// (a node of the network, kept through resampling).
#[derive(Clone, Copy, Debug)]
struct Raw {
    /// Position on the mesh.
    p: DVec3,
    /// Normal interpolated from the vertex normals (not normalised).
    n: DVec3,
    /// A crossing or a section end on the boundary: a node of the network.
    node: bool,
}

/// A polyline traced on the mesh.
struct Traced {
    /// The section plane or principal curve (none for boundary loops).
    plane: Option<usize>,
    /// The samples in order (a closed polyline does not repeat its first one).
    samples: Vec<Raw>,
    /// A closed loop.
    closed: bool,
    /// A boundary loop of the mesh.
    boundary: bool,
    /// The curve's name in the network.
    name: String,
    /// A piece of a section cut at a bad spot ([`cut::cut_at_spots`]): it may end at crossings.
    cut: bool,
    /// A crease curve ([`creases::trace_creases`]): the normals of the surface on its right,
    /// per sample (`samples` hold the left ones). Empty for the other curves.
    right: Vec<DVec3>,
}

/// Polyline ends on boundary edges: edge ([`mesh::edge_key`]) → the end samples on it.
type EndsOnBoundary = HashMap<(u32, u32), Vec<Raw>>;

/// The curves traced on the mesh by [`sections::trace_sections`] or
/// [`principal::trace_principal`], before the boundary loops.
struct Traces {
    /// The polylines, crossings as node samples.
    traced: Vec<Traced>,
    /// The polyline ends on boundary edges.
    ends_on_boundary: EndsOnBoundary,
    /// The number of planes (curves) still in a bad spot.
    unresolved: usize,
    /// The bad spots left: (plane or curve, place).
    spots: Vec<(usize, DVec3)>,
    /// The number of crossings.
    crossings: usize,
    /// The number of ends cut back along the boundary.
    trimmed: usize,
}

/// The sizes the stages share.
struct Scales {
    /// The bounding box of the input mesh.
    bbox: Aabb,
    /// Its diagonal.
    diag: f64,
    /// The sample spacing.
    spacing: f64,
    /// The network's snapping tolerance: the crossings fall between samples by the chord sag
    /// and the noise, a few percent of the spacing each ([`SampleOptions::SNAP_SPACING`]).
    snap: f64,
    /// Sections of two planes closer than this away from their crossings would be snapped
    /// together by the pipeline: twice the snapping tolerance.
    near: f64,
    /// Crossings closer than this are moved apart: one sample spacing, and well beyond the
    /// pipeline's node clustering (twice `near`). Two crossings of the same two sections: the
    /// same.
    gap: f64,
}

impl Scales {
    /// The sizes for a mesh with box `bbox` and the options `opts`.
    ///
    /// Errors: [`Error::Usage`] for a spacing that is not a positive distance, below 1e-6 of
    /// the box diagonal or above [`MAX_SPACING_RELATIVE`] of it.
    fn new(bbox: Aabb, opts: &SampleOptions) -> Result<Scales> {
        let diag = bbox.diagonal();
        let spacing = opts.spacing.unwrap_or(SampleOptions::DEFAULT_SPACING_RELATIVE * diag);
        if !(spacing.is_finite() && spacing > 0.0) {
            return Err(Error::usage(format!("sample spacing (`spacing`) {spacing} is not a positive distance")));
        }
        if spacing * 1e6 < diag {
            return Err(Error::usage(format!(
                "sample spacing (`spacing`) {spacing} is below 1e-6 of the mesh's size {diag:.4e}; the network would be too large"
            )));
        }
        if spacing > MAX_SPACING_RELATIVE * diag {
            return Err(Error::usage(format!(
                "sample spacing (`spacing`) {spacing} is above {MAX_SPACING_RELATIVE} of the mesh's size {diag:.4e}: \
                 the sections would have too few samples to cross and to follow the mesh; give at most {:.4e}",
                MAX_SPACING_RELATIVE * diag
            )));
        }
        let snap = SampleOptions::SNAP_SPACING * spacing;
        let near = 2.0 * snap;
        let gap = spacing.max(2.0 * near);
        Ok(Scales { bbox, diag, spacing, snap, near, gap })
    }
}

/// Checks the options other than the spacing: some planes, a finite tilt, a non-negative
/// noise.
///
/// Errors: [`Error::Usage`] naming the option.
fn check_options(opts: &SampleOptions) -> Result<()> {
    if let Some(&p) = opts.planes.iter().find(|&&p| p > MAX_PLANES) {
        return Err(Error::usage(format!(
            "{p} section planes per axis (`planes`) is more than {MAX_PLANES}: the sections would crowd within the \
             sample spacing; give fewer planes"
        )));
    }
    if opts.planes.iter().sum::<usize>() == 0 {
        return Err(Error::usage("no section planes: give at least one plane count (`planes`) above 0"));
    }
    if !opts.tilt.is_finite() {
        return Err(Error::usage(format!("`tilt` {} is not a finite angle", opts.tilt)));
    }
    if !(opts.noise.is_finite() && opts.noise >= 0.0) {
        return Err(Error::usage(format!("`noise` {} is not a non-negative number", opts.noise)));
    }
    if let Some(deg) = opts.crease_angle.filter(|d| !(d.is_finite() && *d > 0.0 && *d < 180.0)) {
        return Err(Error::usage(format!("`crease_angle` {deg}: give an angle in degrees between 0 and 180")));
    }
    Ok(())
}

/// Samples a curve network on a triangle mesh (see the module documentation).
///
/// `positions` (`#V`) and `faces` (`#F`, counter-clockwise seen from outside: the normals of
/// the network point to that side). Returns the network and a report of what was kept.
///
/// Errors: [`Error::Input`] for a mesh without faces, a face index out of range, a non-finite
/// coordinate, an edge shared by more than two faces (naming the edge), a mesh with zero
/// extent; [`Error::Usage`] for a spacing that is not a positive distance, no planes, a tilt
/// that is not finite, a negative noise; [`Error::Topology`] when the sections give no
/// crossing at all.
pub fn sample_mesh(positions: &[DVec3], faces: &[[u32; 3]], opts: &SampleOptions) -> Result<(Network, SampleReport)> {
    let bbox = mesh::check_mesh(positions, faces)?;
    let scales = Scales::new(bbox, opts)?;
    check_options(opts)?;
    let (net, mut report) = sample_checked(positions, faces, opts, &scales)?;
    if !opts.adapt {
        return Ok((net, report));
    }
    let diag = scales.diag;
    let coverage = |net: &Network| verify::mesh_coverage(net, positions, faces, diag);
    let better = |a: &SampleReport, b: &SampleReport| {
        a.mesh_coverage.unwrap_or(0.0) > b.mesh_coverage.unwrap_or(0.0) + COVERAGE_MARGIN
    };
    report.mesh_coverage = coverage(&net);
    let mut best = (net, report);
    let mut opts = opts.clone();
    // With creases, the sections end on them; where the creases are a tangle (a mesh of
    // sliver triangles, marching cubes over boxes) a region may end up bounded by no patch.
    if opts.crease_angle.is_some() && best.1.creases + best.1.smoothed_refused.len() > 0 && !covers(&best.1) {
        let smooth_opts = SampleOptions { crease_angle: None, ..opts.clone() };
        let (smooth, mut smooth_report) = sample_checked(positions, faces, &smooth_opts, &scales)?;
        smooth_report.mesh_coverage = coverage(&smooth);
        if better(&smooth_report, &best.1) {
            let cover = |r: &SampleReport| r.mesh_coverage.unwrap_or(0.0);
            let creases = best.1.creases + best.1.smoothed_refused.len();
            smooth_report.creases_dropped = Some((creases, cover(&best.1), cover(&smooth_report)));
            best = (smooth, smooth_report);
            opts = smooth_opts;
        }
    }
    // Thin parts (limbs, handles) that too few planes cut: more planes.
    for _ in 0..MAX_REFINES {
        if covers(&best.1) {
            break;
        }
        let planes = opts.planes.map(|n| (n + n.div_ceil(2)).min(MAX_PLANES));
        if planes == opts.planes {
            break;
        }
        opts.planes = planes;
        let (finer, mut finer_report) = sample_checked(positions, faces, &opts, &scales)?;
        finer_report.mesh_coverage = coverage(&finer);
        if !better(&finer_report, &best.1) {
            break;
        }
        finer_report.creases_dropped = best.1.creases_dropped;
        finer_report.planes = Some(planes);
        best = (finer, finer_report);
    }
    Ok(best)
}

/// Whether the network's quick surface covers [`GOOD_COVERAGE`] of the mesh.
fn covers(report: &SampleReport) -> bool {
    report.mesh_coverage.is_some_and(|c| c >= GOOD_COVERAGE)
}

/// The mesh sampled ([`sample_once`]) and checked ([`verify::surfaceable`]): a crease curve
/// `surface`'s checks refuse is not just left out, since the sections were cut to end on it;
/// the mesh is sampled again with its chain smooth, so that they run across (issue 29: a
/// sampled human figure lost its arms to the creases left out), [`MAX_RESAMPLES`] times at
/// most.
fn sample_checked(
    positions: &[DVec3],
    faces: &[[u32; 3]],
    opts: &SampleOptions,
    scales: &Scales,
) -> Result<(Network, SampleReport)> {
    let mut refused: Vec<DVec3> = Vec::new();
    let mut smoothed_refused: Vec<String> = Vec::new();
    let mut round = 0;
    loop {
        let (net, mut report) = sample_once(positions, faces, opts, scales, &refused)?;
        let (net, creases) = verify::surfaceable(net, &mut report);
        // A crease refused again (its chain runs on beyond the refused stretch, so it was kept)
        // would be refused in every round: sample again only for new ones.
        let new = creases::new_points(&refused, &creases.points, scales.spacing);
        if new == 0 || round == MAX_RESAMPLES {
            report.smoothed_refused = smoothed_refused;
            return Ok((net, report));
        }
        refused.extend(creases.points);
        smoothed_refused.extend(creases.why);
        round += 1;
    }
}

/// One sampling of the mesh at `scales`, the chains along `refused` (samples of crease curves
/// refused in earlier rounds) left smooth; not yet checked by `verify`.
fn sample_once(
    positions: &[DVec3],
    faces: &[[u32; 3]],
    opts: &SampleOptions,
    scales: &Scales,
    refused: &[DVec3],
) -> Result<(Network, SampleReport)> {
    let (mesh, repairs) = Mesh::repaired(
        positions,
        faces,
        scales.near,
        opts.crease_angle.map(|deg| creases::CreaseCut {
            angle: deg.to_radians(),
            min_len: MIN_CREASE_SPACINGS * scales.spacing,
            gap: scales.gap,
            refused,
            refused_within: scales.spacing,
        }),
    )?;
    let principal = opts.curves == CurveFamily::Principal;
    let traces = if principal {
        principal::trace_principal(&mesh, opts, scales)
    } else {
        sections::trace_sections(&mesh, opts, scales)
    };
    let mut crossings = traces.crossings;
    let mut boundary_loops = Vec::new();
    if opts.boundary {
        boundary_loops = boundary::trace_boundary(&mesh, &traces.ends_on_boundary, &mut crossings);
    }
    let creases = creases::trace_creases(&mesh, &traces.ends_on_boundary, &mut crossings);
    let has_creases = !creases.is_empty();
    boundary_loops.extend(creases);
    let mut traced = traces.traced;
    boundary::mark_ends(&mut traced, (!boundary_loops.is_empty() || has_creases) && !principal);
    let mut report = SampleReport {
        spacing: scales.spacing,
        crossings,
        pinches: repairs.pinches,
        zipped: repairs.zipped,
        smoothed_creases: repairs.smoothed_creases,
        unresolved: traces.unresolved,
        trimmed: traces.trimmed,
        ..Default::default()
    };
    let pieces = cut::cut_bad_spots(traced, &traces.spots, scales, &mut report);
    let (pieces, loops) = holes::cover_holes(pieces, boundary_loops, opts, scales, &mut report);
    let net = network::assemble(pieces, loops, opts, scales, &mut report)?;
    Ok((net, report))
}

#[cfg(test)]
#[path = "tests/sampling.rs"]
mod tests;
