//! Cycles of segments that bound the patches ([CG] §3.2, "Exploiting local tangent space to
//! detect cycles").
//!
//! At every node the incident segments are sorted counter-clockwise around the node normal;
//! faces are then traced as in a half-edge structure: arriving at a node along a segment, leave
//! along the segment that comes just before it in the counter-clockwise order (the clockwise
//! neighbour). With outward normals, this traces every patch counter-clockwise as seen from
//! outside, with the patch on the left of each half-edge; the direction in which a curve was
//! sampled does not matter.
//!
//! Boundary segments bound one patch only. In a connected part of the network that has
//! interior (non-boundary) segments, the faces made of boundary half-edges only are the
//! outside and are dropped. A part made of boundary curves only must be a single loop; such
//! *lone loops* are paired: two loops that face each other (each loop's plane roughly
//! perpendicular to the line joining their centroids, and normals that run along that line)
//! bound one tube ([CG] Fig. 1, two circles on a cylinder); any other lone loop bounds a disk.

use super::nodes::Graph;
use crate::curves::CurveSpline;
use crate::error::{Error, Result};
use crate::geom::{fmt_point, plane_frame, polygon_vector_area, DVec3};

/// A segment traversed in one direction: `forward` runs from its start node to its end node.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct HalfEdge {
    pub segment: usize,
    pub forward: bool,
}

/// A patch of the surface.
#[derive(Clone, Debug, PartialEq)]
pub enum Patch {
    /// A disk bounded by one cycle of half-edges, counter-clockwise seen from outside.
    Disk(Vec<HalfEdge>),
    /// A tube (annulus) between two lone boundary loops; each loop is traversed with the
    /// surface on its left seen from outside.
    Tube([Vec<HalfEdge>; 2]),
}

impl Patch {
    /// All half-edges of the patch boundary.
    pub fn half_edges(&self) -> Vec<HalfEdge> {
        match self {
            Patch::Disk(c) => c.clone(),
            Patch::Tube([a, b]) => a.iter().chain(b).copied().collect(),
        }
    }
}

/// Samples `(position, normal)` along a half-edge, from its first node up to (excluding) its
/// last node, on the split curves of `g`.
pub(crate) fn half_edge_samples(g: &Graph, h: HalfEdge) -> Vec<(DVec3, DVec3)> {
    let seg = &g.segments[h.segment];
    let c = &g.curves[seg.curve];
    let n = c.points.len();
    let idx: Vec<usize> = (seg.first..=seg.last).map(|i| i % n).collect();
    let mut out: Vec<(DVec3, DVec3)> = idx.iter().map(|&i| (c.points[i], c.normals[i])).collect();
    if !h.forward {
        out.reverse();
    }
    out.pop();
    out
}

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
fn conormal_score(p: &[DVec3], n: &[DVec3], dir: impl Fn(DVec3) -> DVec3) -> f64 {
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

/// Finds the patches of the network: sorts segments around nodes by the node normal, traces
/// the faces and classifies them (see the module documentation).
///
/// `splines[c]` is the spline of `g.curves[c]` (segment tangents at nodes come from it).
///
/// Errors ([`Error::Topology`]) name the node or segment: a dangling segment (a node of
/// valence 1), a curve that leaves a node along the node normal, a boundary segment with patches
/// on both sides or on neither, a patch that meets itself along a segment, boundary curves that
/// form something other than a loop, a lone loop whose inside cannot be told from the normals.
pub fn find_patches(g: &Graph, splines: &[CurveSpline]) -> Result<Vec<Patch>> {
    match find_patches_or_slits(g, splines)? {
        Ok(patches) => Ok(patches),
        Err(slits) => Err(Error::topology(format!(
            "{} has the same patch on both sides: a curve that dangles into a patch or cuts it open \
             cannot be surfaced; remove it or connect both of its ends to other curves (if it crosses \
             another curve without meeting it at a node, raise the snapping tolerance)",
            g.describe_segment(slits[0])
        ))),
    }
}

/// [`find_patches`], except that segments with the same patch on both sides (slits: a curve
/// that cuts into a patch, or a bridge left by snapping) are returned as `Ok(Err(segments))`
/// instead of an error, for [`find_patches_open`] to leave them out.
pub fn find_patches_or_slits(
    g: &Graph,
    splines: &[CurveSpline],
) -> Result<std::result::Result<Vec<Patch>, Vec<usize>>> {
    let ns = g.segments.len();
    // Segment ends at each node: (segment, at_start).
    let mut ends: Vec<Vec<(usize, bool)>> = vec![Vec::new(); g.nodes.len()];
    for (s, seg) in g.segments.iter().enumerate() {
        ends[seg.start].push((s, true));
        ends[seg.end].push((s, false));
    }
    for (v, list) in ends.iter().enumerate() {
        if list.len() == 1 {
            let seg = &g.segments[list[0].0];
            let what = if seg.boundary {
                "an open boundary curve must be closed or end on another curve"
            } else {
                "extend it to a crossing with another curve, tag the surface border as boundary, or remove it"
            };
            return Err(Error::topology(format!(
                "{} ends at {} without meeting another curve: a dangling segment cannot bound a patch; {what}",
                g.labels[seg.curve],
                g.describe_node(v)
            )));
        }
    }
    // A 2-manifold's border passes through a node once or not at all: 0 or 2 boundary ends.
    for (v, list) in ends.iter().enumerate() {
        let boundary: Vec<usize> = list.iter().filter(|(s, _)| g.segments[*s].boundary).map(|(s, _)| *s).collect();
        if boundary.len() != 0 && boundary.len() != 2 {
            let mut names: Vec<&str> = boundary.iter().map(|&s| g.labels[g.segments[s].curve].as_str()).collect();
            names.dedup();
            return Err(Error::topology(format!(
                "{} boundary segment ends meet at {} ({}): the surface is not a 2-manifold there — a segment \
                 shared by more than two patches, or borders that touch. A border passes through a node once",
                boundary.len(),
                g.describe_node(v),
                names.join(", ")
            )));
        }
    }
    // Sort the ends counter-clockwise around the node normal.
    let mut slot = vec![[0usize; 2]; ns]; // position of (segment, at_start) in its node's list
    let mut sorted: Vec<Vec<(usize, bool)>> = Vec::with_capacity(g.nodes.len());
    for (v, list) in ends.iter().enumerate() {
        let normal = g.nodes[v].normal;
        let (e1, e2) = plane_frame(normal);
        let mut keyed = Vec::with_capacity(list.len());
        for &(s, at_start) in list {
            let seg = &g.segments[s];
            let sp = &splines[seg.curve];
            let d = if at_start { sp.tangent(sp.knot(seg.first), true) } else { -sp.tangent(sp.knot(seg.last), false) };
            let proj = d - normal * d.dot(normal);
            if proj.length() <= 1e-3 * d.length() || !proj.is_finite() {
                return Err(Error::topology(format!(
                    "{} leaves {} along the node's normal: normals must be perpendicular to the curves",
                    g.labels[seg.curve],
                    g.describe_node(v)
                )));
            }
            keyed.push((proj.dot(e2).atan2(proj.dot(e1)), s, at_start));
        }
        keyed.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
        for (k, &(_, s, at_start)) in keyed.iter().enumerate() {
            slot[s][if at_start { 0 } else { 1 }] = k;
        }
        sorted.push(keyed.into_iter().map(|(_, s, a)| (s, a)).collect());
    }
    let he_index = |h: HalfEdge| 2 * h.segment + if h.forward { 0 } else { 1 };
    let next = |h: HalfEdge| -> HalfEdge {
        let seg = &g.segments[h.segment];
        // Arrive at the far node through the far end of the segment.
        let (v, arrive_at_start) = if h.forward { (seg.end, false) } else { (seg.start, true) };
        let list = &sorted[v];
        let p = slot[h.segment][if arrive_at_start { 0 } else { 1 }];
        let (s, at_start) = list[(p + list.len() - 1) % list.len()];
        HalfEdge { segment: s, forward: at_start }
    };

    // Trace faces.
    let mut face_of = vec![usize::MAX; 2 * ns];
    let mut faces: Vec<Vec<HalfEdge>> = Vec::new();
    for s in 0..ns {
        for forward in [true, false] {
            let h0 = HalfEdge { segment: s, forward };
            if face_of[he_index(h0)] != usize::MAX {
                continue;
            }
            let f = faces.len();
            let mut face = Vec::new();
            let mut h = h0;
            loop {
                face_of[he_index(h)] = f;
                face.push(h);
                h = next(h);
                if h == h0 {
                    break;
                }
                if face.len() > 2 * ns {
                    return Err(Error::topology("internal error: face tracing did not close"));
                }
            }
            faces.push(face);
        }
    }

    // Connected components of the segment graph.
    let comp = g.node_components();
    let seg_root: Vec<usize> = g.segments.iter().map(|seg| comp[seg.start]).collect();
    let mut has_interior = vec![false; g.nodes.len()];
    for (s, seg) in g.segments.iter().enumerate() {
        if !seg.boundary {
            has_interior[seg_root[s]] = true;
        }
    }

    let mut patches = Vec::new();
    let mut slits = Vec::new();
    let mut lone_faces: Vec<Vec<usize>> = vec![Vec::new(); g.nodes.len()]; // by component root
    for (f, face) in faces.iter().enumerate() {
        let root = seg_root[face[0].segment];
        let all_boundary = face.iter().all(|h| g.segments[h.segment].boundary);
        if all_boundary {
            if !has_interior[root] {
                lone_faces[root].push(f);
            }
            continue; // outside of the surface
        }
        // A patch must not meet itself along a segment.
        for (i, h) in face.iter().enumerate() {
            if face[i + 1..].iter().any(|k| k.segment == h.segment) {
                slits.push(h.segment);
            }
        }
        patches.push(Patch::Disk(face.clone()));
    }
    if !slits.is_empty() {
        slits.sort_unstable();
        slits.dedup();
        return Ok(Err(slits));
    }
    // Every boundary segment in a part with interior curves bounds exactly one patch.
    for (s, seg) in g.segments.iter().enumerate() {
        if !seg.boundary || !has_interior[seg_root[s]] {
            continue;
        }
        let real = |forward: bool| {
            let f = face_of[he_index(HalfEdge { segment: s, forward })];
            faces[f].iter().any(|h| !g.segments[h.segment].boundary)
        };
        match (real(true), real(false)) {
            (true, true) => {
                return Err(Error::topology(format!(
                    "{} is tagged as boundary but has patches on both sides; remove the boundary tag from {}",
                    g.describe_segment(s),
                    g.labels[seg.curve]
                )))
            }
            (false, false) => {
                return Err(Error::topology(format!(
                    "{} is tagged as boundary but bounds no patch: near it the network is not a 2-manifold \
                     (a segment shared by more than two patches, or normals that disagree in orientation)",
                    g.describe_segment(s)
                )))
            }
            _ => {}
        }
    }

    // Lone boundary loops: parts of the network made of boundary curves only.
    struct Lone {
        faces: [Vec<HalfEdge>; 2],
        points: Vec<DVec3>,
        normals: Vec<DVec3>,
        centroid: DVec3,
        axis: DVec3,
    }
    let mut lones: Vec<Lone> = Vec::new();
    for (root, fs) in lone_faces.iter().enumerate() {
        if fs.is_empty() {
            continue;
        }
        let in_part = |s: &usize| seg_root[*s] == root;
        let simple =
            (0..ns).filter(in_part).all(|s| ends[g.segments[s].start].len() == 2 && ends[g.segments[s].end].len() == 2);
        if fs.len() != 2 || !simple {
            let seg = (0..ns).find(in_part).unwrap_or(0);
            return Err(Error::topology(format!(
                "the boundary curves around {} form a network without interior curves that is not a single loop; \
                 tag only the outer border as boundary",
                g.describe_segment(seg)
            )));
        }
        let a = faces[fs[0]].clone();
        let b = faces[fs[1]].clone();
        let (points, normals) = loop_samples(g, &a);
        let centroid = points.iter().sum::<DVec3>() / points.len() as f64;
        let axis = polygon_vector_area(&points).normalize_or_zero();
        lones.push(Lone { faces: [a, b], points, normals, centroid, axis });
    }
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
                pairs.push((dist, i, j, si, sj));
            }
        }
    }
    pairs.sort_by(|a, b| a.0.total_cmp(&b.0));
    let mut used = vec![false; lones.len()];
    for &(_, i, j, si, sj) in &pairs {
        if used[i] || used[j] {
            continue;
        }
        used[i] = true;
        used[j] = true;
        // The traversal whose conormal points to the other loop keeps the tube on its left.
        let li = if si > 0.0 { lones[i].faces[0].clone() } else { lones[i].faces[1].clone() };
        let lj = if sj > 0.0 { lones[j].faces[0].clone() } else { lones[j].faces[1].clone() };
        patches.push(Patch::Tube([li, lj]));
    }
    for (i, l) in lones.iter().enumerate() {
        if used[i] {
            continue;
        }
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
                )));
            }
            s > 0.0
        };
        patches.push(Patch::Disk(if first { l.faces[0].clone() } else { l.faces[1].clone() }));
    }
    Ok(Ok(patches))
}

/// Patches of an open network: [`find_patches_or_slits`], leaving out the slits (segments with
/// the same patch on both sides), then whatever dangles ([`super::open::trim_dangling`]) and the
/// boundary loops that no curve reaches any more ([`super::open::cover_detached_holes`]: a hole
/// that a single curve reached is covered), until the rest bounds patches. Each curve left out
/// or shortened is named in a warning.
pub fn find_patches_open(g: &mut Graph, splines: &[CurveSpline]) -> Result<(Vec<Patch>, Vec<crate::error::Warning>)> {
    let mut warnings = Vec::new();
    let attached = super::open::attached_boundary(g);
    for _ in 0..64 {
        match find_patches_or_slits(g, splines)? {
            Ok(patches) => return Ok((patches, warnings)),
            Err(slits) => {
                // A boundary segment bounds the surface: leaving it out would open a hole.
                if let Some(&s) = slits.iter().find(|&&s| g.segments[s].boundary) {
                    return Err(Error::topology(format!(
                        "{} is a boundary segment with the same patch on both sides: the boundary cuts into the \
                         surface; remove its boundary tag or connect it",
                        g.describe_segment(s)
                    )));
                }
                for &s in slits.iter().take(10) {
                    warnings.push(crate::error::Warning::new(format!(
                        "{} has the same patch on both sides (a curve that cuts into a patch, or curves snapped \
                         into a bridge): it was left out of the surface",
                        g.describe_segment(s)
                    )));
                }
                super::open::remove_segments(g, &slits);
                warnings.extend(super::open::trim_dangling(g)?);
                warnings.extend(super::open::cover_detached_holes(g, &attached));
            }
        }
    }
    Err(Error::topology("internal error: leaving out slits did not converge"))
}
