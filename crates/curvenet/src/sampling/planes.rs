//! Stage 2, the section planes: their normals ([`section_directions`]), their levels in the
//! middle of equal slabs of the mesh's extent, moved into the widest gap between vertex levels
//! nearby ([`plane_level`]), and moved again at random while their sections cross badly
//! ([`place_planes`]: a shallow crossing, two crossings close together, a near miss; at most
//! [`MAX_PLANE_MOVES`] times).

use super::crossings::{self, Crossings};
use super::mesh::Mesh;
use super::sections::{cut_faces, FaceCut};
use super::Scales;
use crate::geom::DVec3;
use crate::network::Rng;

/// Crossings at a smaller angle than this (between the two cut directions on a triangle)
/// move one of the planes: such curves run alongside each other over a long stretch.
pub const MIN_CROSSING_ANGLE_DEG: f64 = 18.0;

/// How many times [`super::sample_mesh`] moves planes off shallow crossings before it keeps
/// them.
pub const MAX_PLANE_MOVES: usize = 24;

/// The normals of the three section families: the coordinate axes turned by `tilt_deg` about
/// (1, 2, 3)/√14 (an axis along no symmetry of the cube, so that no turned axis is parallel to a
/// coordinate plane for small angles).
pub fn section_directions(tilt_deg: f64) -> [DVec3; 3] {
    let q = glam::DQuat::from_axis_angle(DVec3::new(1.0, 2.0, 3.0).normalize(), tilt_deg.to_radians());
    [q * DVec3::X, q * DVec3::Y, q * DVec3::Z]
}

/// The level near `nominal` (within `± window`) farthest from every vertex level: the middle of
/// the widest gap between the sorted vertex coordinates `levels` in the window. A plane there
/// passes through no vertex, and stays away from flat faces perpendicular to its axis (CAD
/// models): a section just beside such a face would run alongside the sections that cross it.
pub(super) fn plane_level(levels: &[f64], nominal: f64, window: f64) -> f64 {
    let (a, b) = (nominal - window, nominal + window);
    let first = levels.partition_point(|&x| x < a);
    let last = levels.partition_point(|&x| x <= b);
    let mut cuts = vec![a];
    cuts.extend_from_slice(&levels[first..last]);
    cuts.push(b);
    let mut best = (f64::NEG_INFINITY, nominal);
    for w in cuts.windows(2) {
        // Prefer wide gaps, then gaps near the nominal level.
        let mid = 0.5 * (w[0] + w[1]);
        let score = (w[1] - w[0]) - 1e-3 * (mid - nominal).abs();
        if score > best.0 {
            best = (score, mid);
        }
    }
    best.1
}

/// The section planes, and what moving them needs.
pub(super) struct Planes {
    /// The normals of the three families ([`section_directions`]).
    pub(super) dirs: [DVec3; 3],
    /// Per plane: its family (axis 0, 1, 2) and its level along the family's normal.
    pub(super) planes: Vec<(usize, f64)>,
    /// Per plane: its nominal level (the middle of its slab).
    nominal: Vec<f64>,
    /// Per axis: the vertex levels along its normal, sorted (empty for an axis without planes).
    axis_levels: Vec<Vec<f64>>,
    /// Per axis: the width of the slabs.
    slab_of: [f64; 3],
}

impl Planes {
    /// `counts[axis]` planes per family, in the middles of equal slabs of the vertices' extent
    /// along the normals ([`section_directions`] of `tilt_deg`), each moved to the widest gap
    /// between vertex levels within 30% of a slab ([`plane_level`]). A family is skipped when
    /// its count is 0 or the extent below `1e-9 × diag`.
    pub(super) fn new(positions: &[DVec3], counts: [usize; 3], tilt_deg: f64, diag: f64) -> Planes {
        let dirs = section_directions(tilt_deg);
        let mut planes: Vec<(usize, f64)> = Vec::new();
        let mut nominal: Vec<f64> = Vec::new();
        let mut axis_levels: Vec<Vec<f64>> = vec![Vec::new(); 3];
        let mut slab_of = [0.0; 3];
        for axis in 0..3 {
            let k = counts[axis];
            let dir = dirs[axis];
            let mut levels: Vec<f64> = positions.iter().map(|p| p.dot(dir)).collect();
            levels.sort_by(f64::total_cmp);
            let (lo, hi) = (levels[0], levels[levels.len() - 1]);
            let ext = hi - lo;
            // Also skipped: a NaN extent.
            if k == 0 || ext.partial_cmp(&(1e-9 * diag)) != Some(std::cmp::Ordering::Greater) {
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
        Planes { dirs, planes, nominal, axis_levels, slab_of }
    }

    /// The number of planes.
    pub(super) fn len(&self) -> usize {
        self.planes.len()
    }

    /// Moves each plane of `bad` to a random level within ±45% of the slab width around its
    /// nominal level (then into the widest vertex gap within 3%). Deterministic: `rng` has a
    /// fixed seed.
    fn move_planes(&mut self, bad: Vec<usize>, rng: &mut Rng) {
        for pi in bad {
            let axis = self.planes[pi].0;
            let slab = self.slab_of[axis];
            let offset = (2.0 * rng.uniform() - 1.0) * 0.45 * slab;
            self.planes[pi].1 = plane_level(&self.axis_levels[axis], self.nominal[pi] + offset, 0.03 * slab);
        }
    }
}

/// The face cuts and crossings of the planes where [`place_planes`] left them.
pub(super) struct Placed {
    /// The section segments in the faces.
    pub(super) cuts: Vec<FaceCut>,
    /// Their crossings.
    pub(super) crossings: Crossings,
    /// Planes still in a bad spot.
    pub(super) unresolved: usize,
}

/// Cuts the mesh by `planes` and moves the planes in bad spots (shallow crossings, near
/// misses, crossings closer than `scales.gap`; with `boundary`, also ends on the mesh boundary
/// at a shallow angle) until there are none, or [`MAX_PLANE_MOVES`] moves have been made: then
/// the configuration with the fewest bad planes is cut once more and kept. `planes` ends as the
/// configuration of the result.
pub(super) fn place_planes(mesh: &Mesh, planes: &mut Planes, boundary: bool, scales: &Scales) -> Placed {
    let mut round = 0;
    let mut final_pass = false;
    let mut best: Option<(usize, Vec<(usize, f64)>)> = None;
    let mut rng = Rng::new(0x5EC7);
    loop {
        let (cuts, cuts_of_face) = cut_faces(mesh, planes);
        let mut crossings = crossings::cross_sections(mesh, planes, &cuts, &cuts_of_face);
        crossings.add_bad_spots(mesh, &cuts, planes.len(), boundary, scales);
        let mut bad: Vec<usize> = crossings.shallow.iter().map(|x| x.0).collect();
        bad.sort_unstable();
        bad.dedup();
        round += 1;
        if bad.is_empty() || final_pass {
            return Placed { cuts, crossings, unresolved: bad.len() };
        }
        if best.as_ref().is_none_or(|b| bad.len() < b.0) {
            best = Some((bad.len(), planes.planes.clone()));
        }
        if round > MAX_PLANE_MOVES {
            // Out of moves: cut once more with the best configuration seen.
            if let Some((_, p)) = best.take() {
                planes.planes = p;
            }
            final_pass = true;
            continue;
        }
        planes.move_planes(bad, &mut rng);
    }
}

#[cfg(test)]
#[path = "tests/planes.rs"]
mod tests;
