//! Cycles of segments that bound the patches (\[CG\] §3.2, "Exploiting local tangent space to
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
//! bound one tube (\[CG\] Fig. 1, two circles on a cylinder); any other lone loop bounds a disk.
//!
//! The stages: `faces.rs` checks the nodes, sorts the segment ends around them and traces and
//! classifies the faces; `lone.rs` turns the lone boundary loops into tubes and disks.

mod chosen;
mod faces;
mod lone;

use super::nodes::Graph;
use crate::curves::CurveSpline;
use crate::error::{Error, Result};
use crate::geom::DVec3;
pub use chosen::{check_keys, key_of, keys_of, open_cycle_along, patches_from_keys, segment_places};
use faces::{check_boundary_sides, check_valence, classify_faces, node_ends, trace_faces, Parts, Rotation};
use lone::{lone_loops, lone_patches};

/// A segment traversed in one direction: `forward` runs from its start node to its end node.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct HalfEdge {
    /// Index of the segment in [`Graph::segments`].
    pub segment: usize,
    /// Traversed from the segment's start node to its end node.
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
        ))
        .curve(g.segments[slits[0]].curve)
        .segment(slits[0])),
    }
}

/// [`find_patches`], except that segments with the same patch on both sides (slits: a curve
/// that cuts into a patch, or a bridge left by snapping) are returned as `Ok(Err(segments))`
/// instead of an error, for [`find_patches_open`] to leave them out.
pub fn find_patches_or_slits(
    g: &Graph,
    splines: &[CurveSpline],
) -> Result<std::result::Result<Vec<Patch>, Vec<usize>>> {
    let ends = node_ends(g);
    check_valence(g, &ends)?;
    let rotation = Rotation::new(g, splines, &ends)?;
    let faces = trace_faces(g, &rotation)?;
    let parts = Parts::new(g);
    let classified = classify_faces(g, &faces, &parts);
    let mut patches = classified.patches;
    let mut slits = classified.slits;
    if !slits.is_empty() {
        slits.sort_unstable();
        slits.dedup();
        return Ok(Err(slits));
    }
    check_boundary_sides(g, &faces, &parts)?;
    // Lone boundary loops: parts of the network made of boundary curves only.
    let lones = lone_loops(g, &faces, &parts, &classified.lone_faces, &ends)?;
    patches.extend(lone_patches(&lones)?);
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
                    ))
                    .curve(g.segments[s].curve)
                    .segment(s));
                }
                for &s in slits.iter().take(10) {
                    warnings.push(
                        crate::error::Warning::new(format!(
                            "{} has the same patch on both sides (a curve that cuts into a patch, or curves snapped \
                         into a bridge): it was left out of the surface",
                            g.describe_segment(s)
                        ))
                        .curve(g.segments[s].curve),
                    );
                }
                super::open::remove_segments(g, &slits);
                warnings.extend(super::open::trim_dangling(g)?);
                warnings.extend(super::open::cover_detached_holes(g, &attached));
            }
        }
    }
    Err(Error::internal("leaving out slits did not converge"))
}

#[cfg(test)]
#[path = "tests/cycles.rs"]
mod tests;
