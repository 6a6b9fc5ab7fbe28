//! Tessellation of the patches (\[CG\] §3.3; docs/design.md §1 step 5): every patch is
//! triangulated in a planar domain whose border is the patch's cycle of curve vertices, and
//! all patches are merged into one [`Mesh`] that shares the curve vertices. The triangles'
//! planar coordinates are kept for the paper's planar cotangent weights.
//!
//! The stages, one file each:
//!
//! - `planar.rs`, disk patches: the cycle is projected on the plane through its mean point
//!   with its mean normal (\[CG\] §3.3); where the normals cancel out or disagree with the
//!   cycle, on the plane of the cycle's vector area.
//! - `triangulate.rs` and `lattice.rs`, the triangulation of the planar polygon: the interior
//!   is covered by a hexagonal lattice of side `d` (equilateral triangles, taken as they are)
//!   kept at least `0.6 d` from the border; only the band between the border and the
//!   lattice's outline goes through spade's constrained Delaunay triangulation and its
//!   refinement (minimum angle [`MIN_ANGLE_DEG`], maximum area [`MAX_AREA_FACTOR`]` d²`,
//!   border and outline edges kept, so that the border vertices are exactly the curve
//!   vertices).
//! - `fallback.rs`, patches whose projection folds over (the cycle crosses itself or runs
//!   clockwise in its plane, or a sharp corner turns the other way): the plane of the cycle's
//!   vector area, else a convex domain (an ellipse) that is always injective. These patches
//!   are listed in [`Mesh::fold_fallback`].
//! - `tube.rs`, tube patches (two facing boundary loops): the annulus cut open along a seam
//!   and unrolled onto a trapezoidal strip.
//! - `flatten.rs` and [`conformal`], conformal patching: each disk patch of a coarse first
//!   solution flattened by least squares conformal maps, and triangulated in its flattening.
//! - `relax.rs`: the triangulation smoothed in its domain (balanced one-rings where the band
//!   meets the lattice, and across a tube's seam).
//! - `transfer.rs`: positions for a fine mesh blended from a coarse solved one (the default
//!   iterates on the coarse mesh and starts the fine level there).
//! - `merge.rs`: the patches merged into one mesh, the curve vertices first.

pub mod conformal;
mod fallback;
mod flatten;
mod lattice;
mod merge;
mod planar;
mod relax;
mod transfer;
mod triangulate;
mod tube;

pub use flatten::{flatten_patches, PatchFlattening};
pub use transfer::{transfer, transfer_positions};

use crate::error::Result;
use crate::geom::mesh::Mesh;
use crate::geom::DVec2;
use crate::geom::DVec3;
use crate::topology::resample::Resampled;
use crate::topology::{Graph, HalfEdge, Patch};
use rayon::prelude::*;

/// Minimum angle the refinement of the border band aims for, in degrees.
pub const MIN_ANGLE_DEG: f64 = 25.0;
/// Maximum triangle area in the border band as a multiple of `d²` (an equilateral triangle of
/// side `d` has 0.433 d²; refinement stops once every triangle is below the limit, so the mean
/// edge comes out close to `d`).
pub const MAX_AREA_FACTOR: f64 = 0.69;
/// Free vertices per unit planar area, times `d²` (the density of the hexagonal lattice of
/// side `d` is 2/√3 ≈ 1.155; used to turn a target vertex count into a spacing).
pub const VERTICES_PER_AREA: f64 = 1.155;

/// A vertex of a patch triangulation: a curve vertex (global id) or a new free vertex of the
/// patch (local id).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
enum VRef {
    Curve(u32),
    New(u32),
}

/// One patch triangulated: its new vertices in 3D, its triangles and their planar corners.
struct PatchMesh {
    new_positions: Vec<DVec3>,
    triangles: Vec<[VRef; 3]>,
    planar: Vec<[DVec2; 3]>,
    /// Triangulated in a fallback domain: its planar projection folds over.
    fold_fallback: bool,
}

/// Curve vertex ids around one loop of half-edges (each node once).
fn loop_vertices(res: &Resampled, hs: &[HalfEdge]) -> Vec<u32> {
    let mut ids = Vec::new();
    for h in hs {
        let sv = &res.segment_vertices[h.segment];
        if h.forward {
            ids.extend_from_slice(&sv[..sv.len() - 1]);
        } else {
            ids.extend(sv[1..].iter().rev());
        }
    }
    ids
}

/// The names of the curves around a patch, for messages (at most about 200 characters).
fn describe_patch(g: &Graph, hs: &[HalfEdge]) -> String {
    let mut curves: Vec<&str> = hs.iter().map(|h| g.labels[g.segments[h.segment].curve].as_str()).collect();
    curves.dedup();
    let mut s = curves.join(", ");
    if s.len() > 200 {
        // Cut at a character boundary (names may hold any UTF-8).
        let end = (0..=200).rev().find(|&i| s.is_char_boundary(i)).unwrap_or(0);
        s.truncate(end);
        s.push('…');
    }
    s
}

/// Tessellates every patch at spacing `d` and merges them into one mesh whose first vertices
/// are the curve vertices of `res`. The errors of a patch name it ([`crate::error::At::patch`]).
pub fn tessellate(g: &Graph, res: &Resampled, patches: &[Patch], d: f64) -> Result<Mesh> {
    let parts: Vec<Result<PatchMesh>> = patches
        .par_iter()
        .enumerate()
        .map(|(i, p)| {
            let part = match p {
                Patch::Disk(hs) => planar::tessellate_disk(g, res, hs, d, i),
                Patch::Tube(loops) => tube::tessellate_tube(g, res, loops, d, i),
            };
            part.map_err(|e| e.patch(i))
        })
        .collect();
    merge::merge(res, parts)
}

/// Tessellates every patch at spacing `d` over the curve vertices `res`: disk patches with a
/// flattening ([`flatten_patches`]) in it, the others as [`tessellate`] does. The fine curve
/// vertices are placed on the flattened border by arc length along each segment (both
/// resamplings are uniform in arc length). Returns the mesh and the indices of the disk patches
/// kept in their planar projection.
pub fn tessellate_conformal(
    g: &Graph,
    res: &Resampled,
    patches: &[Patch],
    d: f64,
    coarse_res: &Resampled,
    flat: &[Option<PatchFlattening>],
) -> Result<(Mesh, Vec<usize>)> {
    let parts: Vec<(Result<PatchMesh>, bool)> = patches
        .par_iter()
        .enumerate()
        .map(|(i, p)| {
            let (part, kept) = match (p, &flat[i]) {
                (Patch::Disk(hs), Some(f)) => match flatten::conformal_disk(g, res, hs, d, i, coarse_res, f) {
                    Some(part) => (part, false),
                    None => (planar::tessellate_disk(g, res, hs, d, i), true),
                },
                (Patch::Disk(hs), None) => (planar::tessellate_disk(g, res, hs, d, i), true),
                (Patch::Tube(loops), _) => (tube::tessellate_tube(g, res, loops, d, i), false),
            };
            (part.map_err(|e| e.patch(i)), kept)
        })
        .collect();
    let kept: Vec<usize> = parts.iter().enumerate().filter(|(_, p)| p.1).map(|(i, _)| i).collect();
    Ok((merge::merge(res, parts.into_iter().map(|p| p.0).collect())?, kept))
}

#[cfg(test)]
#[path = "tests/tessellate.rs"]
mod tests;
