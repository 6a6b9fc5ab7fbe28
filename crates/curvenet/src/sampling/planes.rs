//! Section planes: their directions and their levels away from the vertices.

use crate::geom::DVec3;

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

/// Crossings at a smaller angle than this (between the two cut directions on a triangle)
/// move one of the planes: such curves run alongside each other over a long stretch.
pub const MIN_CROSSING_ANGLE_DEG: f64 = 18.0;

/// How many times [`sample_mesh`] moves planes off shallow crossings before it keeps them.
pub const MAX_PLANE_MOVES: usize = 24;
