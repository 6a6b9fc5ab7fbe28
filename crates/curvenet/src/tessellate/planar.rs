//! Disk patches in their planar projection (\[CG\] §3.3): the cycle of curve vertices around
//! the patch is projected on the plane through its mean point with its mean normal and
//! triangulated there ([`super::triangulate`]). When the normals cancel out (a hemisphere
//! bounded by a great circle) or disagree with the cycle's orientation, the plane of the
//! cycle's vector area is used instead. A projection that folds over goes to the fallback
//! domains ([`super::fallback`]).

use super::triangulate::{lift_patch, triangulate};
use super::{describe_patch, fallback, loop_vertices, PatchMesh, VRef};
use crate::error::{Error, Result};
use crate::geom::{fmt_point, plane_frame, polygon_vector_area, DVec2, DVec3};
use crate::topology::resample::Resampled;
use crate::topology::{Graph, HalfEdge};

/// The cycle of curve vertices around a disk patch, in 3D.
pub(super) struct Cycle {
    /// Positions of the curve vertices, counter-clockwise seen from outside.
    pub(super) p3: Vec<DVec3>,
    /// Their unit normals.
    pub(super) n3: Vec<DVec3>,
    /// Per vertex: a corner inside a segment (a curve's own corner), not a node where the cycle
    /// turns from one curve to another.
    pub(super) inner: Vec<bool>,
    /// Mean point of the vertices.
    pub(super) center: DVec3,
    /// Per vertex: the curve vertex it is.
    pub(super) map: Vec<VRef>,
}

impl Cycle {
    /// The curve vertices of `res` around the loop of half-edges `hs`.
    pub(super) fn new(res: &Resampled, hs: &[HalfEdge]) -> Self {
        let ids = loop_vertices(res, hs);
        let p3: Vec<DVec3> = ids.iter().map(|&i| res.positions[i as usize]).collect();
        let center = p3.iter().sum::<DVec3>() / p3.len() as f64;
        let map: Vec<VRef> = ids.iter().map(|&i| VRef::Curve(i)).collect();
        let n3: Vec<DVec3> = ids.iter().map(|&i| res.normals[i as usize]).collect();
        // Corners inside segments (not at nodes, where the cycle turns from one curve to another).
        let mut inner = vec![true; ids.len()];
        let mut k = 0;
        for h in hs {
            if k < inner.len() {
                inner[k] = false;
            }
            k += res.segment_vertices[h.segment].len() - 1;
        }
        Cycle { p3, n3, inner, center, map }
    }

    /// The projection of the vertices on the plane through the mean point normal to `n`: the
    /// planar points and the plane's frame `(e1, e2)` ([`plane_frame`]).
    pub(super) fn project(&self, n: DVec3) -> (Vec<DVec2>, DVec3, DVec3) {
        let (p3, center) = (&self.p3, self.center);
        let (e1, e2) = plane_frame(n);
        let pts: Vec<DVec2> = p3.iter().map(|p| DVec2::new((*p - center).dot(e1), (*p - center).dot(e2))).collect();
        (pts, e1, e2)
    }
}

/// Triangulates the disk patch `index` bounded by the half-edges `hs` at spacing `d`, in its
/// planar projection, or in a fallback domain where the projection folds over (the part is
/// then marked `fold_fallback`).
///
/// Errors ([`Error::Topology`]): the cycle encloses no area, or neither the projection nor any
/// fallback domain can be triangulated (the projection's error is reported).
pub(super) fn tessellate_disk(g: &Graph, res: &Resampled, hs: &[HalfEdge], d: f64, index: usize) -> Result<PatchMesh> {
    let what = || format!("patch {index} (bounded by {})", describe_patch(g, hs));
    let cycle = Cycle::new(res, hs);
    let (p3, center) = (&cycle.p3, cycle.center);
    // [CG] §3.3: the plane through the mean point with the mean normal. When the normals
    // cancel out (a hemisphere bounded by a great circle) or disagree with the cycle's
    // orientation, the plane of the cycle's vector area is used instead.
    let mean_n = cycle.n3.iter().sum::<DVec3>() / cycle.n3.len() as f64;
    let area_n = polygon_vector_area(p3).normalize_or_zero();
    let n = if mean_n.length() > 0.1 && mean_n.dot(area_n) > 0.0 { mean_n.normalize() } else { area_n };
    if n == DVec3::ZERO {
        return Err(Error::topology(format!("{}: the cycle encloses no area", what())));
    }
    let (pts, e1, e2) = cycle.project(n);
    let first = match corner_turned(p3, &cycle.n3, &cycle.inner, &pts) {
        None => match triangulate(pts, cycle.map.clone(), d, &what) {
            Ok((tris, pos2, map)) => return lift_patch(tris, &pos2, &map, |q| center + q.x * e1 + q.y * e2, &what),
            Err(e @ Error::Topology { .. }) => e,
            Err(e) => return Err(e),
        },
        Some(i) => Error::topology(format!(
            "{}: the cycle's corner at {} turns the other way in projection than on the surface (a sharp \
             corner across a crease); the patch cannot be triangulated in a plane",
            what(),
            fmt_point(p3[i])
        ))
        .point(p3[i]),
    };
    fallback::tessellate_folded(&cycle, n, area_n, d, &what, first)
}

/// Turning angle (degrees) of a cycle corner above which [`corner_turned`] compares its sign on
/// the surface and in projection.
const CORNER_TURN_DEG: f64 = 20.0;

/// The first corner of the cycle `p3` (normals `n3`) inside a segment (`inner`: a curve's
/// own corner, not a node where the cycle passes from one curve to the next) that turns by more than
/// [`CORNER_TURN_DEG`] one way on the surface (about the curve normal there) and the other
/// way in the planar projection `pts`. Where a curve turns sharply across a crease, the
/// patches on its two sides have planes far apart, and both may see the corner as convex: both
/// triangulations then hold the triangle across the corner (an edge in four triangles). The
/// projection folds over there, as when the cycle crosses itself.
pub(super) fn corner_turned(p3: &[DVec3], n3: &[DVec3], inner: &[bool], pts: &[DVec2]) -> Option<usize> {
    let m = p3.len();
    let limit = CORNER_TURN_DEG.to_radians();
    (0..m).filter(|&i| inner[i]).find(|&i| {
        let (a, c) = ((i + m - 1) % m, (i + 1) % m);
        let n = n3[i];
        let flat = |v: DVec3| v - n * v.dot(n);
        let (u, v) = (flat(p3[i] - p3[a]), flat(p3[c] - p3[i]));
        let t3 = u.cross(v).dot(n).atan2(u.dot(v));
        let (q, r) = (pts[i] - pts[a], pts[c] - pts[i]);
        let t2 = q.perp_dot(r).atan2(q.dot(r));
        (t3 < -limit && t2 > limit) || (t3 > limit && t2 < -limit)
    })
}

#[cfg(test)]
#[path = "tests/planar.rs"]
mod tests;
