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

use crate::error::{Error, Result};
use crate::geom::{Aabb, DVec3};
use crate::network::{Curve, Network};
use std::collections::HashMap;

mod boundary;
mod crossings;
mod cut;
mod mesh;
mod network;
mod planes;
pub mod principal;
mod sections;

use boundary::{trace_boundary, trim_along, BoundaryGrid};
use crossings::{close_crossings, near_misses};
use cut::{cut_at_spots, sharp_turns, thin_loop};
pub use cut::SHARP_TURN_DEG;
use mesh::edge_key;
pub use mesh::{split_pinches, vertex_normals, zip_cracks};
use network::resample;
pub use network::{remove_hairpins, CORNER_DEG};
use planes::plane_level;
pub use planes::{section_directions, MAX_PLANE_MOVES, MIN_CROSSING_ANGLE_DEG};
use sections::FaceCut;

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
}

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
}

/// A sample of a polyline before resampling: position, normal, and whether it is a crossing
/// (a node of the network, kept through resampling).
#[derive(Clone, Copy, Debug)]
struct Raw {
    p: DVec3,
    n: DVec3,
    node: bool,
}

/// A polyline traced on the mesh.
struct Traced {
    /// The section plane (none for boundary loops).
    plane: Option<usize>,
    samples: Vec<Raw>,
    closed: bool,
    boundary: bool,
    name: String,
    /// A piece of a section cut at a bad spot ([`cut_at_spots`]): it may end at crossings.
    cut: bool,
}

/// Samples a curve network on a triangle mesh (see the module documentation).
///
/// `positions` (`#V`) and `faces` (`#F`, counter-clockwise seen from outside: the normals of
/// the network point to that side). Returns the network and a report of what was kept.
///
/// Errors: [`Error::Input`] for a mesh without faces, a face index out of range, a non-finite
/// coordinate, an edge shared by more than two faces (naming the edge), a mesh with zero
/// extent; [`Error::usage`] for a spacing that is not a positive distance, or no planes;
/// [`Error::Topology`] when the sections give no crossing at all.
pub fn sample_mesh(positions: &[DVec3], faces: &[[u32; 3]], opts: &SampleOptions) -> Result<(Network, SampleReport)> {
    if faces.is_empty() {
        return Err(Error::input("the mesh has no faces: there is nothing to sample"));
    }
    for (fi, f) in faces.iter().enumerate() {
        for &v in f {
            if v as usize >= positions.len() {
                return Err(Error::input(format!(
                    "face {fi} uses vertex {v} but the mesh has {} vertices",
                    positions.len()
                )));
            }
        }
    }
    if let Some(i) = positions.iter().position(|p| !p.is_finite()) {
        return Err(Error::input(format!("mesh vertex {i} has a non-finite coordinate")));
    }
    let bbox = Aabb::of(faces.iter().flatten().map(|&v| positions[v as usize]));
    let diag = bbox.diagonal();
    if !(diag > 0.0 && diag.is_finite()) {
        return Err(Error::input("the mesh has zero extent"));
    }
    let spacing = opts.spacing.unwrap_or(SampleOptions::DEFAULT_SPACING_RELATIVE * diag);
    if !(spacing.is_finite() && spacing > 0.0) {
        return Err(Error::usage(format!("sample spacing {spacing} is not a positive distance")));
    }
    if spacing * 1e6 < diag {
        return Err(Error::usage(format!(
            "sample spacing {spacing} is below 1e-6 of the mesh's size {diag:.4e}; the network would be too large"
        )));
    }
    if opts.planes.iter().sum::<usize>() == 0 {
        return Err(Error::usage("no section planes: give at least one plane count above 0"));
    }
    if !opts.tilt.is_finite() {
        return Err(Error::usage(format!("tilt {} is not a finite angle", opts.tilt)));
    }
    if !(opts.noise.is_finite() && opts.noise >= 0.0) {
        return Err(Error::usage(format!("noise {} is not a non-negative number", opts.noise)));
    }
    // Weld vertices at the same position (unwelded seams would read as boundary).
    let mut first_at: HashMap<[u64; 3], u32> = HashMap::new();
    let weld: Vec<u32> = positions
        .iter()
        .enumerate()
        .map(|(i, p)| {
            let key = (*p + DVec3::ZERO).to_array().map(f64::to_bits);
            *first_at.entry(key).or_insert(i as u32)
        })
        .collect();
    let mut welded: Vec<[u32; 3]> = faces
        .iter()
        .map(|f| f.map(|v| weld[v as usize]))
        .filter(|f| f[0] != f[1] && f[1] != f[2] && f[0] != f[2])
        .collect();
    let mut moved = positions.to_vec();
    // The network's snapping tolerance: the crossings fall between samples by the chord sag
    // and the noise, a few percent of the spacing each ([`SampleOptions::SNAP_SPACING`]).
    let snap = SampleOptions::SNAP_SPACING * spacing;
    let near = 2.0 * snap;
    let zipped = zip_cracks(&mut moved, &mut welded, near);
    let pinches = split_pinches(&mut moved, &mut welded, near);
    // Crossings closer than this are moved apart: one sample spacing, and well beyond the
    // pipeline's node clustering (twice its snapping tolerance).
    let gap = spacing.max(2.0 * near);
    // Two crossings of the same two sections: the same.
    let gap_same = gap;
    let (positions, faces) = (&moved[..], &welded[..]);
    let normals = vertex_normals(positions, faces);

    // Faces around each undirected edge.
    let mut edge_faces: HashMap<(u32, u32), Vec<usize>> = HashMap::new();
    for (fi, f) in faces.iter().enumerate() {
        for k in 0..3 {
            let (a, b) = (f[k], f[(k + 1) % 3]);
            if a == b {
                continue;
            }
            edge_faces.entry(edge_key(a, b)).or_default().push(fi);
        }
    }
    if let Some((e, fs)) = edge_faces.iter().find(|(_, fs)| fs.len() > 2) {
        return Err(Error::input(format!(
            "the mesh is not a 2-manifold: edge between vertices {} and {} is shared by {} faces",
            e.0,
            e.1,
            fs.len()
        )));
    }

    let principal = opts.curves == CurveFamily::Principal;
    let (mut traced, ends_on_boundary, unresolved, unresolved_at, mut crossings, report_trimmed) = if principal {
        // Curves along the principal directions, `separation` apart.
        let ext = bbox.max - bbox.min;
        let counts: Vec<f64> = opts.planes.iter().filter(|&&k| k > 0).map(|&k| k as f64).collect();
        let mean_count = counts.iter().sum::<f64>() / counts.len().max(1) as f64;
        let separation = PRINCIPAL_SEPARATION * (ext.x + ext.y + ext.z) / 3.0 / mean_count.max(1.0);
        let axis = section_directions(opts.tilt)[2];
        let r = principal::trace(positions, faces, &normals, &edge_faces, axis, separation, spacing, near, gap, diag);
        let mut bad: Vec<usize> = r.spots.iter().map(|x| x.0).collect();
        bad.sort_unstable();
        bad.dedup();
        (r.traced, r.ends_on_boundary, bad.len(), r.spots, r.crossings, 0)
    } else {
        // Section planes: axis, level, away from vertex levels ([`plane_level`]).
        let dirs = section_directions(opts.tilt);
        let mut planes: Vec<(usize, f64)> = Vec::new();
        // Per plane: its nominal level, the sorted vertex levels along its axis, the slab width.
        let mut nominal: Vec<f64> = Vec::new();
        let mut axis_levels: Vec<Vec<f64>> = vec![Vec::new(); 3];
        let mut slab_of = [0.0; 3];
        for axis in 0..3 {
            let k = opts.planes[axis];
            let dir = dirs[axis];
            let mut levels: Vec<f64> = positions.iter().map(|p| p.dot(dir)).collect();
            levels.sort_by(f64::total_cmp);
            let (lo, hi) = (levels[0], levels[levels.len() - 1]);
            let ext = hi - lo;
            if k == 0 || !(ext > 1e-9 * diag) {
                continue;
            }
            let slab = ext / k as f64;
            for i in 0..k {
                let c = lo + (i as f64 + 0.5) * slab;
                nominal.push(c);
                planes.push((axis, plane_level(&levels, c, 0.3 * slab)));
            }
            axis_levels[axis] = levels;
            slab_of[axis] = slab;
        }

        let edge_point = |e: (u32, u32), plane: (usize, f64)| -> (DVec3, DVec3) {
            let (a, b) = (positions[e.0 as usize], positions[e.1 as usize]);
            let (sa, sb) = (a.dot(dirs[plane.0]) - plane.1, b.dot(dirs[plane.0]) - plane.1);
            let t = (sa / (sa - sb)).clamp(0.0, 1.0);
            let n = normals[e.0 as usize].lerp(normals[e.1 as usize], t);
            (a.lerp(b, t), n)
        };
        let face_normal_at = |fi: usize, p: DVec3| -> DVec3 {
            let v = faces[fi].map(|i| positions[i as usize]);
            let area = (v[1] - v[0]).cross(v[2] - v[0]);
            let a2 = area.length_squared();
            if a2 == 0.0 {
                return normals[faces[fi][0] as usize];
            }
            let w0 = (v[1] - p).cross(v[2] - p).dot(area) / a2;
            let w1 = (v[2] - p).cross(v[0] - p).dot(area) / a2;
            let w2 = 1.0 - w0 - w1;
            let [n0, n1, n2] = faces[fi].map(|i| normals[i as usize]);
            w0 * n0 + w1 * n1 + w2 * n2
        };
        let cos_min = MIN_CROSSING_ANGLE_DEG.to_radians().cos();
        // Sections of two planes closer than `near` away from their crossings would be snapped
        // together by the pipeline: twice its default snapping tolerance (Network::snap_tolerance).
        let mut round = 0;
        let unresolved;
        let unresolved_at: Vec<(usize, DVec3)>;
        let mut final_pass = false;
        let mut best: Option<(usize, Vec<(usize, f64)>)> = None;
        let mut rng = crate::network::Rng::new(0x5EC7);
        let (cuts, crossing_at, crossings) = loop {
            // Cut every face by every plane.
            let mut cuts_of_face: Vec<Vec<usize>> = vec![Vec::new(); faces.len()];
            let mut cuts: Vec<FaceCut> = Vec::new();
            for (pi, &(axis, c)) in planes.iter().enumerate() {
                for (fi, f) in faces.iter().enumerate() {
                    let side = f.map(|v| positions[v as usize].dot(dirs[axis]) > c);
                    if side[0] == side[1] && side[1] == side[2] {
                        continue;
                    }
                    let mut edges = Vec::with_capacity(2);
                    for k in 0..3 {
                        if side[k] != side[(k + 1) % 3] {
                            edges.push(edge_key(f[k], f[(k + 1) % 3]));
                        }
                    }
                    if edges.len() != 2 {
                        continue;
                    }
                    let e = [edges[0], edges[1]];
                    let ends = e.map(|e| edge_point(e, (axis, c)).0);
                    cuts_of_face[fi].push(cuts.len());
                    cuts.push(FaceCut { plane: pi, edges: e, ends });
                }
            }
            // Crossings: per face, for two cuts of different axes, the point of the first cut on
            // the second's plane (the triangle's point on both planes), shared by both polylines.
            // crossing_at[cut] = list of (parameter along ends[0] → ends[1], sample).
            let mut crossing_at: Vec<Vec<(f64, Raw)>> = vec![Vec::new(); cuts.len()];
            let mut crossings = 0usize;
            let mut shallow: Vec<(usize, DVec3)> = Vec::new();
            let mut crossing_points: HashMap<(usize, usize), Vec<DVec3>> = HashMap::new();
            for (fi, list) in cuts_of_face.iter().enumerate() {
                for (x, &ca) in list.iter().enumerate() {
                    for &cb in &list[x + 1..] {
                        let (a, b) = (&cuts[ca], &cuts[cb]);
                        let (axis_a, lev_a) = planes[a.plane];
                        let (axis_b, lev_b) = planes[b.plane];
                        if axis_a == axis_b {
                            continue;
                        }
                        // Parameter on a where a's line meets b's plane, and on b where it meets a's.
                        let (sa0, sa1) = (a.ends[0].dot(dirs[axis_b]) - lev_b, a.ends[1].dot(dirs[axis_b]) - lev_b);
                        let (sb0, sb1) = (b.ends[0].dot(dirs[axis_a]) - lev_a, b.ends[1].dot(dirs[axis_a]) - lev_a);
                        if (sa0 > 0.0) == (sa1 > 0.0) || (sb0 > 0.0) == (sb1 > 0.0) {
                            continue;
                        }
                        let ta = sa0 / (sa0 - sa1);
                        let tb = sb0 / (sb0 - sb1);
                        let p = a.ends[0].lerp(a.ends[1], ta);
                        let raw = Raw { p, n: face_normal_at(fi, p), node: true };
                        crossing_at[ca].push((ta, raw));
                        crossing_at[cb].push((tb, raw));
                        crossings += 1;
                        crossing_points.entry((a.plane.min(b.plane), a.plane.max(b.plane))).or_default().push(p);
                        let (da, db) = (a.ends[1] - a.ends[0], b.ends[1] - b.ends[0]);
                        let cos = da.dot(db).abs() / (da.length() * db.length());
                        if cos > cos_min {
                            shallow.push((b.plane, p));
                        }
                    }
                }
            }
            // The mesh boundary as a pseudo-plane (index planes.len()): sections must end on it at
            // a fair angle and not run alongside it.
            let boundary_plane = planes.len();
            let mut with_boundary: Vec<FaceCut> = cuts.clone();
            if opts.boundary {
                for (e, fs) in &edge_faces {
                    if fs.len() == 1 {
                        let ends = [positions[e.0 as usize], positions[e.1 as usize]];
                        with_boundary.push(FaceCut { plane: boundary_plane, edges: [*e, *e], ends });
                    }
                }
                for c in &cuts {
                    for k in 0..2 {
                        if edge_faces.get(&c.edges[k]).is_some_and(|f| f.len() == 1) {
                            crossing_points.entry((c.plane, boundary_plane)).or_default().push(c.ends[k]);
                            let e = positions[c.edges[k].1 as usize] - positions[c.edges[k].0 as usize];
                            let d = c.ends[1] - c.ends[0];
                            if d.dot(e).abs() / (d.length() * e.length()) > cos_min {
                                shallow.push((c.plane, c.ends[k]));
                            }
                        }
                    }
                }
            }
            shallow.extend(near_misses(&with_boundary, &crossing_points, near, boundary_plane));
            // Crossings closer than `gap` to each other: two crossings of the same two sections
            // (the pipeline would merge them into one node where the curves touch without
            // crossing), or three sections nearly through one point (a tiny cell whose nodes the
            // pipeline cannot tell apart once the crossings fall between noisy samples).
            shallow.extend(close_crossings(&crossing_points, gap, gap_same, boundary_plane));
            let mut bad: Vec<usize> = shallow.iter().map(|x| x.0).collect();
            bad.sort_unstable();
            bad.dedup();
            round += 1;
            if bad.is_empty() || final_pass {
                unresolved = bad.len();
                unresolved_at = shallow;
                break (cuts, crossing_at, crossings);
            }
            if best.as_ref().is_none_or(|b| bad.len() < b.0) {
                best = Some((bad.len(), planes.clone()));
            }
            if round > MAX_PLANE_MOVES {
                // Out of moves: cut once more with the best configuration seen.
                if let Some((_, p)) = best.take() {
                    planes = p;
                }
                final_pass = true;
                continue;
            }
            // Move each plane in a bad crossing to a random level within ±45% of the slab width
            // around its nominal level (deterministic: the generator has a fixed seed).
            for pi in bad {
                let axis = planes[pi].0;
                let slab = slab_of[axis];
                let offset = (2.0 * rng.uniform() - 1.0) * 0.45 * slab;
                planes[pi].1 = plane_level(&axis_levels[axis], nominal[pi] + offset, 0.03 * slab);
            }
        };

        // Chain the cuts of each plane into polylines through shared edges.
        let mut traced: Vec<Traced> = Vec::new();
        // Section end points on boundary edges, for the boundary loops: edge → (point, normal).
        let mut ends_on_boundary: HashMap<(u32, u32), Vec<Raw>> = HashMap::new();
        let mut report_trimmed = 0;
        let boundary_grid = BoundaryGrid::new(positions, &edge_faces, 3.0 * snap);
        // Boundary loop of each boundary vertex (components of the boundary edges).
        let mut loop_uf = crate::topology::UnionFind::new(positions.len());
        for (e, fs) in &edge_faces {
            if fs.len() == 1 {
                loop_uf.union(e.0 as usize, e.1 as usize);
            }
        }
        let loop_of: Vec<usize> = (0..positions.len()).map(|v| loop_uf.find(v)).collect();
        let mut cuts_of_plane: Vec<Vec<usize>> = vec![Vec::new(); planes.len()];
        for (ci, c) in cuts.iter().enumerate() {
            cuts_of_plane[c.plane].push(ci);
        }
        let axis_name = ["X", "Y", "Z"];
        for (pi, list) in cuts_of_plane.iter().enumerate() {
            let mut by_edge: HashMap<(u32, u32), Vec<usize>> = HashMap::new();
            for &ci in list {
                for e in cuts[ci].edges {
                    by_edge.entry(e).or_default().push(ci);
                }
            }
            let mut used: HashMap<usize, bool> = list.iter().map(|&c| (c, false)).collect();
            // Open chains start at a boundary edge (one cut), then closed loops.
            let mut starts: Vec<(usize, usize)> = Vec::new();
            for &ci in list {
                for k in 0..2 {
                    if by_edge[&cuts[ci].edges[k]].len() == 1 {
                        starts.push((ci, k));
                    }
                }
            }
            let closed_starts: Vec<(usize, usize)> = list.iter().map(|&c| (c, 0)).collect();
            let mut piece = 0;
            for (ci0, k0) in starts.into_iter().chain(closed_starts) {
                if used[&ci0] {
                    continue;
                }
                let mut samples = Vec::new();
                let (mut ci, mut enter) = (ci0, k0);
                let closed;
                loop {
                    *used.get_mut(&ci).unwrap_or(&mut false) = true;
                    let c = &cuts[ci];
                    let e_in = c.edges[enter];
                    let (p, n) = edge_point(e_in, planes[pi]);
                    samples.push(Raw { p, n, node: false });
                    let mut xs = crossing_at[ci].clone();
                    if enter == 0 {
                        xs.sort_by(|a, b| a.0.total_cmp(&b.0));
                    } else {
                        xs.sort_by(|a, b| b.0.total_cmp(&a.0));
                    }
                    samples.extend(xs.into_iter().map(|x| x.1));
                    let e_out = c.edges[1 - enter];
                    let next = by_edge[&e_out].iter().copied().find(|&o| o != ci);
                    match next {
                        Some(o) if o == ci0 => {
                            closed = true;
                            break;
                        }
                        Some(o) if !used[&o] => {
                            enter = if cuts[o].edges[0] == e_out { 0 } else { 1 };
                            ci = o;
                        }
                        _ => {
                            let (p, n) = edge_point(e_out, planes[pi]);
                            samples.push(Raw { p, n, node: false });
                            closed = false;
                            break;
                        }
                    }
                }
                if !closed {
                    // Ends on boundary edges meet the boundary loops there. An end that runs along
                    // the boundary first is cut back to where it leaves it (`trim_along`).
                    let mut end_edges = [cuts[ci0].edges[k0], cuts[ci].edges[1 - enter]];
                    if opts.boundary {
                        for side in 0..2 {
                            if edge_faces.get(&end_edges[side]).is_none_or(|f| f.len() != 1) {
                                continue;
                            }
                            if side == 1 {
                                samples.reverse();
                            }
                            let same_loop = loop_of[end_edges[side].0 as usize];
                            if let Some(e) = trim_along(
                                &mut samples,
                                &boundary_grid,
                                3.0 * snap,
                                positions,
                                &normals,
                                &|e: (u32, u32)| loop_of[e.0 as usize] == same_loop,
                            ) {
                                end_edges[side] = e;
                                report_trimmed += 1;
                            }
                            if side == 1 {
                                samples.reverse();
                            }
                        }
                    }
                    if samples.len() < 2 {
                        continue;
                    }
                    for (e, raw) in [(end_edges[0], samples[0]), (end_edges[1], samples[samples.len() - 1])] {
                        if edge_faces.get(&e).is_some_and(|f| f.len() == 1) {
                            ends_on_boundary.entry(e).or_default().push(raw);
                        }
                    }
                }
                let (axis, lev) = planes[pi];
                traced.push(Traced {
                    plane: Some(pi),
                    samples,
                    closed,
                    boundary: false,
                    name: format!("{}={:.6} #{piece}", axis_name[axis], lev),
                    cut: false,
                });
                piece += 1;
            }
        }
        (traced, ends_on_boundary, unresolved, unresolved_at, crossings, report_trimmed)
    };
    // Section ends on the boundary are nodes (when the boundary loop is kept).
    let mut boundary_loops = Vec::new();
    if opts.boundary {
        boundary_loops = trace_boundary(positions, faces, &normals, &edge_faces, &ends_on_boundary, &mut crossings);
    }
    let has_boundary = !boundary_loops.is_empty();
    for t in &mut traced {
        // Plane sections end on the boundary (principal curves mark their own ends there).
        if !t.closed && has_boundary && !principal {
            let last = t.samples.len() - 1;
            t.samples[0].node = true;
            t.samples[last].node = true;
        }
    }
    let mut report =
        SampleReport { spacing, crossings, pinches, zipped, unresolved, trimmed: report_trimmed, ..Default::default() };
    // Where each section must be cut: the planes' bad spots still left after the plane moves,
    // and section ends on the boundary closer than `gap` to another one (the boundary nearly
    // touching itself, or a cut-back end moved next to another one: the pipeline would merge
    // them into a node with too many boundary ends; the shorter piece's end is cut).
    let mut spots: Vec<Vec<DVec3>> = traced
        .iter()
        .map(|t| match t.plane {
            Some(p) => unresolved_at
                .iter()
                .filter(|(q, at)| *q == p && t.samples.iter().any(|r| r.p.distance(*at) <= gap))
                .map(|x| x.1)
                .collect(),
            None => Vec::new(),
        })
        .collect();
    // Sections that turn back within the surface (by more than [`SHARP_TURN_DEG`] about the
    // normal: a plane that grazes one side of a sharp crease, so that the section runs along the
    // crease before it crosses it) are cut there: the patches on the two sides of such a
    // corner fold over in any plane (fandisk).
    for (t, s) in traced.iter().zip(spots.iter_mut()) {
        let at = sharp_turns(&t.samples, t.closed, 0.5 * spacing, SHARP_TURN_DEG);
        report.sharp_turns += at.len();
        s.extend(at);
    }
    let ends: Vec<(usize, DVec3, f64)> = traced
        .iter()
        .enumerate()
        .filter(|(_, t)| !t.closed && t.samples.len() >= 2)
        .flat_map(|(i, t)| {
            let len: f64 = t.samples.windows(2).map(|w| w[0].p.distance(w[1].p)).sum();
            [(i, t.samples[0].p, len), (i, t.samples[t.samples.len() - 1].p, len)]
        })
        .collect();
    let mut crowded = vec![false; ends.len()];
    for (a, ea) in ends.iter().enumerate() {
        for (b, eb) in ends.iter().enumerate().skip(a + 1) {
            if ea.0 != eb.0 && ea.1.distance(eb.1) <= gap && !crowded[a] && !crowded[b] {
                let (k, e) = if ea.2 <= eb.2 { (a, ea) } else { (b, eb) };
                crowded[k] = true;
                spots[e.0].push(e.1);
            }
        }
    }
    // A section in a bad spot loses the stretch around it, between the crossings on either
    // side (the rest of the section still bounds patches, ending on those crossings).
    let mut pieces: Vec<Traced> = Vec::new();
    for (t, s) in traced.into_iter().zip(&spots) {
        if s.is_empty() {
            pieces.push(t);
            continue;
        }
        report.cut_bad += 1;
        pieces.extend(cut_at_spots(t, s, gap));
    }
    // Sections that meet no other curve (a crossing inside; the ends on the boundary do not
    // count, nor do a cut piece's ends alone if they are not crossings) are left out.
    pieces.retain(|t| {
        let nodes = t.samples.iter().filter(|s| s.node).count();
        let m = t.samples.len();
        let inner = t.samples.iter().enumerate().filter(|&(k, s)| s.node && k > 0 && k + 1 < m).count();
        let meets = if t.closed { nodes > 0 } else { inner > 0 || (t.cut && nodes == 2) };
        if !meets {
            report.dropped_sections += 1;
        }
        meets
    });
    // Boundary loops: each section end on the loop is a node sample of it. Loops around holes
    // too small or too thin to be sampled as curves are left out (the hole covered). A loop
    // that no section reaches bounds no patch of the network; a loop that one section reaches
    // would bound a hole inside a patch joined to the rest by that section only (a bridge the
    // pipeline cannot surface: patches are disks): it is left out too, the hole covered. The
    // ends of sections on a loop left out are cut back to their last crossing (they would
    // dangle); repeated, since a cut may leave another loop with one section.
    let key = |p: DVec3| p.to_array().map(f64::to_bits);
    let mut loop_at: HashMap<[u64; 3], usize> = HashMap::new();
    let mut loops_kept = vec![true; boundary_loops.len()];
    let mut loop_curves: Vec<Option<(Vec<DVec3>, Vec<DVec3>)>> = Vec::with_capacity(boundary_loops.len());
    for (li, l) in boundary_loops.iter().enumerate() {
        for r in l.samples.iter().filter(|r| r.node) {
            loop_at.insert(key(r.p), li);
        }
        // A hole smaller than a few sample spacings, or slit-shaped (its sides within `near`
        // of each other), would run alongside itself.
        let (points, normals) = resample(&l.samples, true, spacing, opts.shared_nodes);
        let small = Aabb::of(l.samples.iter().map(|r| r.p)).diagonal() < 3.0 * spacing
            || (points.len() <= 40 && thin_loop(&points, near));
        if small {
            report.small_holes += 1;
            loops_kept[li] = false;
        }
        loop_curves.push(Some((points, normals)));
    }
    for _ in 0..=boundary_loops.len() + pieces.len() {
        // Section ends per loop: (piece, at its first sample).
        let mut contacts: Vec<Vec<(usize, bool)>> = vec![Vec::new(); boundary_loops.len()];
        for (i, t) in pieces.iter().enumerate().filter(|(_, t)| !t.closed) {
            for (first, r) in [(true, t.samples[0]), (false, t.samples[t.samples.len() - 1])] {
                if let Some(&li) = loop_at.get(&key(r.p)).filter(|_| r.node) {
                    contacts[li].push((i, first));
                }
            }
        }
        for (li, c) in contacts.iter().enumerate() {
            if loops_kept[li] && c.len() < 2 {
                loops_kept[li] = false;
                if c.is_empty() {
                    report.dropped_boundary_loops += 1;
                } else {
                    report.single_contact_holes += 1;
                }
            }
        }
        // Every open piece must end where another curve passes: on a kept boundary loop, or
        // (a piece cut at a bad spot) on a crossing that a kept section passes through. The crossing samples are
        // shared by both curves, so the ends are found by position. Other ends are cut back
        // to the piece's last crossing.
        // Crossings that a kept section passes through (not where it ends: two pieces ending
        // on their own crossing would make a corner, not a junction). Principal curves may
        // end in such corners (at about 90°): their free ends are cut back to their last
        // crossing, and two curves often end on the same one (cutting both further would
        // peel the whole network from its free ends).
        let mut on_sections: HashMap<[u64; 3], Vec<usize>> = HashMap::new();
        for (i, t) in pieces.iter().enumerate() {
            let m = t.samples.len();
            for (k, r) in t.samples.iter().enumerate() {
                if r.node && (t.closed || (k > 0 && k + 1 < m) || principal) {
                    on_sections.entry(key(r.p)).or_default().push(i);
                }
            }
        }
        let supported = |i: usize, r: Raw| {
            r.node
                && (loop_at.get(&key(r.p)).is_some_and(|&li| loops_kept[li])
                    || on_sections.get(&key(r.p)).is_some_and(|l| l.iter().any(|&j| j != i)))
        };
        let mut cut_ends: Vec<Vec<DVec3>> = vec![Vec::new(); pieces.len()];
        for (i, t) in pieces.iter().enumerate().filter(|(_, t)| !t.closed) {
            for r in [t.samples[0], t.samples[t.samples.len() - 1]] {
                if !supported(i, r) {
                    cut_ends[i].push(r.p);
                }
            }
        }
        if cut_ends.iter().all(|c| c.is_empty()) {
            break;
        }
        let old = std::mem::take(&mut pieces);
        for (t, ends) in old.into_iter().zip(cut_ends) {
            if ends.is_empty() {
                pieces.push(t);
            } else {
                pieces.extend(
                    cut_at_spots(t, &ends, 0.0)
                        .into_iter()
                        .filter(|t| t.samples.iter().filter(|s| s.node).count() >= 2),
                );
            }
        }
    }
    let mut curves = Vec::new();
    let kept_loops =
        boundary_loops.into_iter().zip(loop_curves).zip(loops_kept).filter(|(_, k)| *k).map(|((t, pn), _)| (t, pn));
    for (t, pn) in pieces.into_iter().map(|t| (t, None)).chain(kept_loops) {
        let (mut points, mut normals) =
            pn.unwrap_or_else(|| resample(&t.samples, t.closed, spacing, opts.shared_nodes));
        report.hairpins += remove_hairpins(&mut points, &mut normals, t.closed, near);
        let need = if t.closed { 3 } else { 2 };
        if points.len() < need {
            continue;
        }
        if t.boundary {
            report.boundary_loops += 1;
        } else {
            report.sections += 1;
        }
        curves.push(Curve { name: Some(t.name), points, normals, closed: t.closed, boundary: t.boundary });
    }
    if report.crossings == 0 || curves.is_empty() {
        return Err(Error::topology(
            "the plane sections do not cross each other on the mesh: give more planes (`planes`) in at least two directions",
        ));
    }
    let mut net = Network { curves, snap: Some(snap) };
    if opts.noise > 0.0 {
        net = net.perturbed(opts.noise, opts.seed);
    }
    Ok((net, report))
}

#[cfg(test)]
#[path = "tests/sampling.rs"]
mod tests;
