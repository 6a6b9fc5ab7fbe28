//! Conformal patching (\[CG\] §6 calls for "a more advanced 3D patching"): each disk patch of a
//! coarse first solution is flattened by least squares conformal maps ([`super::conformal`]),
//! and the patch is triangulated again in that flattening, its fine curve vertices placed on
//! the flattened border by arc length.

use super::triangulate::{lift_patch, triangulate};
use super::{describe_patch, loop_vertices, PatchMesh, VRef};
use crate::error::Result;
use crate::geom::mesh::Mesh;
use crate::geom::{polygon_signed_area, DVec2, DVec3};
use crate::topology::resample::Resampled;
use crate::topology::{Graph, HalfEdge, Patch};
use rayon::prelude::*;

/// The conformal flattening of one disk patch of a coarse first solution.
#[derive(Clone, Debug)]
pub struct PatchFlattening {
    /// Coarse vertex id → flattened position, scaled so that the border keeps its 3D length.
    uv: std::collections::HashMap<u32, DVec2>,
    /// Area enclosed by the flattened border.
    pub area: f64,
}

impl PatchFlattening {
    /// The flattened position of the coarse vertex `v` (`None` when it is not in the patch).
    pub fn uv_of(&self, v: u32) -> Option<DVec2> {
        self.uv.get(&v).copied()
    }
}

/// Flattens every disk patch of `coarse` (a solved mesh over the curve vertices `coarse_res`)
/// by LSCM ([`crate::tessellate::conformal::lscm`]). `None` for tubes and for patches whose flattening
/// fails or folds over (they keep their planar projection).
pub fn flatten_patches(patches: &[Patch], coarse_res: &Resampled, coarse: &Mesh) -> Vec<Option<PatchFlattening>> {
    let mut faces_of: Vec<Vec<[u32; 3]>> = vec![Vec::new(); patches.len()];
    for (f, &p) in coarse.faces.iter().zip(&coarse.face_patch) {
        faces_of[p as usize].push(*f);
    }
    patches
        .par_iter()
        .enumerate()
        .map(|(i, p)| match p {
            Patch::Disk(hs) => flatten_disk(hs, coarse_res, coarse, &faces_of[i]),
            Patch::Tube(_) => None,
        })
        .collect()
}

/// The LSCM flattening of one disk patch of `coarse` (bounded by the half-edges `hs` over the
/// curve vertices `coarse_res`, with the triangles `faces`), pinned at its first border vertex
/// and the border vertex farthest from it, scaled so that the border keeps its 3D length.
/// `None` when the flattening fails or folds over.
fn flatten_disk(hs: &[HalfEdge], coarse_res: &Resampled, coarse: &Mesh, faces: &[[u32; 3]]) -> Option<PatchFlattening> {
    // Local numbering of the coarse patch's vertices.
    let mut local = std::collections::HashMap::new();
    let mut global = Vec::new();
    let local_faces: Vec<[u32; 3]> = faces
        .iter()
        .map(|f| {
            f.map(|v| {
                *local.entry(v).or_insert_with(|| {
                    global.push(v);
                    (global.len() - 1) as u32
                })
            })
        })
        .collect();
    let p3: Vec<DVec3> = global.iter().map(|&v| coarse.positions[v as usize]).collect();
    let border = loop_vertices(coarse_res, hs);
    let first = border[0];
    let pos = |v: u32| coarse.positions[v as usize];
    let far = *border.iter().max_by(|a, b| pos(**a).distance(pos(first)).total_cmp(&pos(**b).distance(pos(first))))?;
    let uv =
        super::conformal::lscm(&p3, &local_faces, [*local.get(&first)? as usize, *local.get(&far)? as usize]).ok()?;
    if local_faces.iter().any(|f| {
        let [a, b, c] = f.map(|v| uv[v as usize]);
        let counter_clockwise = (b - a).perp_dot(c - a) > 0.0; // false for NaN too
        !counter_clockwise
    }) {
        return None;
    }
    let ring: Vec<DVec2> = border.iter().map(|v| local.get(v).map(|&l| uv[l as usize])).collect::<Option<_>>()?;
    let m = border.len();
    let len3: f64 = (0..m).map(|k| pos(border[k]).distance(pos(border[(k + 1) % m]))).sum();
    let len2: f64 = (0..m).map(|k| ring[k].distance(ring[(k + 1) % m])).sum();
    let scale = len3 / len2;
    let area = polygon_signed_area(&ring) * scale * scale;
    let uv = global.iter().zip(&uv).map(|(&g, q)| (g, *q * scale)).collect();
    Some(PatchFlattening { uv, area })
}

/// A disk patch triangulated in its flattening; `None` when the border cannot be placed or
/// the triangulation fails (the caller falls back to the planar projection).
pub(super) fn conformal_disk(
    g: &Graph,
    res: &Resampled,
    hs: &[HalfEdge],
    d: f64,
    index: usize,
    coarse_res: &Resampled,
    flat: &PatchFlattening,
) -> Option<Result<PatchMesh>> {
    let what = || format!("patch {index} (bounded by {})", describe_patch(g, hs));
    let uv_of = |v: u32| flat.uv.get(&v).copied();
    let mut pts = Vec::new();
    for h in hs {
        let (cs, fs) = (&coarse_res.segment_vertices[h.segment], &res.segment_vertices[h.segment]);
        let (mc, mf) = (cs.len() - 1, fs.len() - 1);
        for k in 0..mf {
            let kf = if h.forward { k } else { mf - k };
            let x = kf as f64 * mc as f64 / mf as f64;
            let i0 = (x.floor() as usize).min(mc - 1);
            pts.push(uv_of(cs[i0])?.lerp(uv_of(cs[i0 + 1])?, x - i0 as f64));
        }
    }
    let ids = loop_vertices(res, hs);
    if pts.len() != ids.len() {
        return None;
    }
    let map: Vec<VRef> = ids.iter().map(|&i| VRef::Curve(i)).collect();
    let (tris, pos2, map) = triangulate(pts, map, d, &what).ok()?;
    // New vertices start at the centroid of the border: the solve needs only their metric.
    let centroid = ids.iter().map(|&i| res.positions[i as usize]).sum::<DVec3>() / ids.len() as f64;
    Some(lift_patch(tris, &pos2, &map, |_| centroid, &what))
}

#[cfg(test)]
#[path = "tests/flatten.rs"]
mod tests;
