//! Lone boundary loops: parts of the network made of boundary curves only. Each must be a
//! single loop; its two faces (one per direction) are the two candidate patch borders. Two
//! loops that face each other (each loop's plane roughly perpendicular to the line joining
//! their centroids, and normals that run along that line) bound one tube (\[CG\] Fig. 1, two
//! circles on a cylinder), nearest pairs first; any other lone loop bounds a disk, on the side
//! its normals lean to.

use super::faces::{Faces, NodeEnds, Parts};
use super::{half_edge_samples, HalfEdge, Patch};
use crate::error::{Error, Result};
use crate::geom::{fmt_point, polygon_vector_area, DVec3};
use crate::topology::nodes::Graph;

/// A lone boundary loop.
pub(super) struct Lone {
    /// Its two faces: the loop traversed in both directions.
    pub(super) faces: [Vec<HalfEdge>; 2],
    /// The samples along `faces[0]` (each node once).
    points: Vec<DVec3>,
    /// The normals at `points`.
    normals: Vec<DVec3>,
    /// Mean of `points`.
    pub(super) centroid: DVec3,
    /// Unit vector area of `points` (zero when it vanishes).
    pub(super) axis: DVec3,
    /// The loop's first curve, and its name for messages.
    curve: (usize, String),
}

/// The lone loops of `g`: for every part without interior segments (its faces `lone_faces`,
/// [`super::faces::Classified::lone_faces`]), in part order, the loop with its samples.
///
/// Errors ([`Error::Topology`]): a part that is not a single loop (not two faces, or a node
/// with other than two segment ends).
pub(super) fn lone_loops(
    g: &Graph,
    faces: &Faces,
    parts: &Parts,
    lone_faces: &[Vec<usize>],
    ends: &NodeEnds,
) -> Result<Vec<Lone>> {
    let ns = g.segments.len();
    let mut lones: Vec<Lone> = Vec::new();
    for (root, fs) in lone_faces.iter().enumerate() {
        if fs.is_empty() {
            continue;
        }
        let in_part = |s: &usize| parts.seg_root[*s] == root;
        let simple =
            (0..ns).filter(in_part).all(|s| ends[g.segments[s].start].len() == 2 && ends[g.segments[s].end].len() == 2);
        if fs.len() != 2 || !simple {
            let seg = (0..ns).find(in_part).unwrap_or(0);
            return Err(Error::topology(format!(
                "the boundary curves around {} form a network without interior curves that is not a single loop; \
                 tag only the outer border as boundary",
                g.describe_segment(seg)
            ))
            .curve(g.segments[seg].curve)
            .segment(seg));
        }
        let a = faces.faces[fs[0]].clone();
        let b = faces.faces[fs[1]].clone();
        let (points, normals) = loop_samples(g, &a);
        let centroid = points.iter().sum::<DVec3>() / points.len() as f64;
        let axis = polygon_vector_area(&points).normalize_or_zero();
        let c = g.segments[a[0].segment].curve;
        lones.push(Lone { faces: [a, b], points, normals, centroid, axis, curve: (c, g.labels[c].clone()) });
    }
    Ok(lones)
}

/// The patches of the lone loops `lones`: first the tubes of the pairs that face each other
/// ([`pair_tubes`]), then a disk for every other loop ([`lone_disk`]).
///
/// Errors: a disk whose side cannot be told ([`lone_disk`]) — with the reason when the loop
/// faces another whose normals point to the other side of their tube.
pub(super) fn lone_patches(lones: &[Lone]) -> Result<Vec<Patch>> {
    let (mut patches, used, mismatched) = pair_tubes(lones);
    for (i, l) in lones.iter().enumerate() {
        if used[i] {
            continue;
        }
        match (lone_disk(l), mismatched.iter().find(|m| m.0 == i || m.1 == i)) {
            (Ok(disk), _) => patches.push(disk),
            (Err(_), Some(&(a, b))) => return Err(opposite_rims(&lones[a], &lones[b])),
            (Err(e), None) => return Err(e),
        }
    }
    Ok(patches)
}

/// Pairs the loops that face each other into tubes, nearest pairs (by centroid distance)
/// first, each loop in one tube at most. Two loops face each other when both axes are within
/// 45° of the line joining their centroids and the conormals of both ([`conormal_score`])
/// point along that line, towards or away from the other loop, by at least 0.3. Each loop is
/// traversed in the direction whose conormal points to the other loop (the tube on its left).
/// Seen along the line, the two traversals of a tube wind opposite ways; a pair whose normals
/// make them wind the same way (one rim's normals point to the other side of the tube: a
/// twisted band, two cones through each other) is no tube. Returns the tubes, per loop whether
/// it is in one, and the pairs left out for winding the same way.
pub(super) fn pair_tubes(lones: &[Lone]) -> (Vec<Patch>, Vec<bool>, Vec<(usize, usize)>) {
    // Pair loops that face each other into tubes; nearest pairs first.
    let cos45 = std::f64::consts::FRAC_1_SQRT_2;
    let mut pairs = Vec::new();
    for i in 0..lones.len() {
        for j in i + 1..lones.len() {
            let d = lones[j].centroid - lones[i].centroid;
            let dist = d.length();
            let dh = d.normalize_or_zero();
            if dh == DVec3::ZERO || lones[i].axis.dot(dh).abs() < cos45 || lones[j].axis.dot(dh).abs() < cos45 {
                continue;
            }
            let si = conormal_score(&lones[i].points, &lones[i].normals, |_| dh);
            let sj = conormal_score(&lones[j].points, &lones[j].normals, |_| -dh);
            if si.abs() >= 0.3 && sj.abs() >= 0.3 {
                // The winding of each chosen traversal about the line (at least cos 45° in size).
                let wi = si.signum() * lones[i].axis.dot(dh);
                let wj = sj.signum() * lones[j].axis.dot(dh);
                pairs.push((dist, i, j, si, sj, wi * wj < 0.0));
            }
        }
    }
    pairs.sort_by(|a, b| a.0.total_cmp(&b.0));
    let mut patches = Vec::new();
    let mut used = vec![false; lones.len()];
    let mut mismatched = Vec::new();
    for &(_, i, j, si, sj, opposite) in &pairs {
        if used[i] || used[j] {
            continue;
        }
        if !opposite {
            mismatched.push((i, j));
            continue;
        }
        used[i] = true;
        used[j] = true;
        // The traversal whose conormal points to the other loop keeps the tube on its left.
        let li = if si > 0.0 { lones[i].faces[0].clone() } else { lones[i].faces[1].clone() };
        let lj = if sj > 0.0 { lones[j].faces[0].clone() } else { lones[j].faces[1].clone() };
        patches.push(Patch::Tube([li, lj]));
    }
    (patches, used, mismatched)
}

/// The error of two loops that face each other as a tube's rims with normals to opposite sides
/// of it; it names the rim whose normals point towards the tube's axis (most tubes face out).
fn opposite_rims(a: &Lone, b: &Lone) -> Error {
    let line = (b.centroid - a.centroid).normalize_or_zero();
    // Mean of n · r̂, r̂ the direction from the line through both centroids.
    let outward = |l: &Lone| {
        let sum: f64 = l
            .points
            .iter()
            .zip(&l.normals)
            .map(|(&p, &n)| {
                let r = p - a.centroid;
                n.dot((r - r.dot(line) * line).normalize_or_zero())
            })
            .sum();
        sum / l.points.len().max(1) as f64
    };
    let (wrong, right) = if outward(a) <= outward(b) { (a, b) } else { (b, a) };
    Error::input(format!(
        "{w} and {r} face each other as the two rims of a tube, but their normals point to opposite sides of it \
         (those of {w} towards the tube's axis, those of {r} away from it): no surface follows both, and neither \
         loop bounds a disk on its own. Flip the normals of {w} (or those of {r}, for a tube that faces inward)",
        w = wrong.curve.1,
        r = right.curve.1
    ))
    .curve(wrong.curve.0)
    .point(wrong.points[0])
}

/// The disk bounded by a lone loop: the traversal whose conormal points to the centroid
/// (score at least 0.05 either way), else the one whose vector area agrees with the mean
/// normal.
///
/// Errors ([`Error::Topology`]): neither tells the side (normals tangent to the loop's plane).
pub(super) fn lone_disk(l: &Lone) -> Result<Patch> {
    let c = l.centroid;
    let inward = conormal_score(&l.points, &l.normals, |p| c - p);
    let first = if inward.abs() >= 0.05 {
        inward > 0.0
    } else {
        let mean_n = l.normals.iter().sum::<DVec3>();
        let a = polygon_vector_area(&l.points);
        let s = a.dot(mean_n) / (a.length() * mean_n.length()).max(f64::MIN_POSITIVE);
        if s.abs() < 0.05 {
            return Err(Error::topology(format!(
                "cannot tell on which side of the boundary loop through {} the surface lies: its normals are \
                 tangent to the plane of the loop and point nowhere near its inside; give another loop for a tube \
                 or tilt the normals",
                fmt_point(l.points[0])
            ))
            .point(l.points[0]));
        }
        s > 0.0
    };
    Ok(Patch::Disk(if first { l.faces[0].clone() } else { l.faces[1].clone() }))
}

/// The samples (positions and normals) around a loop of half-edges, each node once.
fn loop_samples(g: &Graph, hs: &[HalfEdge]) -> (Vec<DVec3>, Vec<DVec3>) {
    let mut p = Vec::new();
    let mut n = Vec::new();
    for &h in hs {
        for (a, b) in half_edge_samples(g, h) {
            p.push(a);
            n.push(b);
        }
    }
    (p, n)
}

/// Σᵢ (nᵢ × (pᵢ₊₁ − pᵢ)) · dirᵢ / length: how much the conormal (which points into the patch on
/// the left of the traversal) points along `dir(pᵢ)`, in [−1, 1].
pub(super) fn conormal_score(p: &[DVec3], n: &[DVec3], dir: impl Fn(DVec3) -> DVec3) -> f64 {
    let m = p.len();
    let (mut s, mut len) = (0.0, 0.0);
    for i in 0..m {
        let e = p[(i + 1) % m] - p[i];
        let l = e.length();
        if l == 0.0 {
            continue;
        }
        let d = dir(p[i]).normalize_or_zero();
        s += n[i].cross(e).dot(d);
        len += l;
    }
    if len > 0.0 {
        s / len
    } else {
        0.0
    }
}

#[cfg(test)]
#[path = "tests/lone.rs"]
mod tests;
