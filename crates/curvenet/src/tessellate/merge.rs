//! The patches merged into one mesh: the curve vertices first (shared by the patches on both
//! sides of every segment), then each patch's new vertices in patch order; per face its
//! planar corners and its patch.

use super::{PatchMesh, VRef};
use crate::error::{Error, Result};
use crate::geom::fmt_point;
use crate::geom::mesh::Mesh;
use crate::topology::resample::Resampled;

/// Merges per-patch triangulations into one mesh whose first vertices are the curve vertices
/// of `res`; the first error of a part is returned.
///
/// Errors: a curve vertex that no triangle uses ([`Error::Topology`]); more than 2³² vertices
/// ([`Error::Usage`]).
pub(super) fn merge(res: &Resampled, parts: Vec<Result<PatchMesh>>) -> Result<Mesh> {
    let nc = res.positions.len();
    let mut mesh = Mesh {
        positions: res.positions.clone(),
        faces: Vec::new(),
        num_curve: nc,
        curve_normals: res.normals.clone(),
        on_boundary: res.on_boundary.clone(),
        planar: Vec::new(),
        face_patch: Vec::new(),
        pattern: Default::default(),
        fold_fallback: Vec::new(),
        seam_rows: Vec::new(),
    };
    let parts = parts.into_iter().collect::<Result<Vec<PatchMesh>>>()?;
    let (new, tris) = parts.iter().fold((0, 0), |(v, t), p| (v + p.new_positions.len(), t + p.triangles.len()));
    mesh.positions.reserve_exact(new);
    mesh.faces.reserve_exact(tris);
    mesh.planar.reserve_exact(tris);
    mesh.face_patch.reserve_exact(tris);
    for (pi, part) in parts.into_iter().enumerate() {
        if part.fold_fallback {
            mesh.fold_fallback.push(pi);
        }
        let base = mesh.positions.len() as u32;
        mesh.positions.extend_from_slice(&part.new_positions);
        for (t, q) in part.triangles.iter().zip(part.planar) {
            let id = |r: VRef| match r {
                VRef::Curve(i) => i,
                VRef::New(k) => base + k,
            };
            mesh.faces.push([id(t[0]), id(t[1]), id(t[2])]);
            mesh.planar.push(q);
            mesh.face_patch.push(pi as u32);
        }
    }
    mesh.on_boundary.resize(mesh.positions.len(), false);
    if mesh.positions.len() > u32::MAX as usize {
        return Err(Error::usage("the mesh would exceed 4 billion vertices; increase `spacing`"));
    }
    // Every curve vertex must be used by some face (a vertex left out means a broken patch).
    let mut used = vec![false; mesh.positions.len()];
    for f in &mesh.faces {
        for &i in f {
            used[i as usize] = true;
        }
    }
    if let Some(i) = used.iter().position(|u| !u) {
        return Err(Error::topology(format!(
            "vertex {i} at {} is not part of any patch (a curve that bounds no patch?)",
            fmt_point(mesh.positions[i])
        ))
        .vertex(i)
        .point(mesh.positions[i]));
    }
    Ok(mesh)
}

#[cfg(test)]
#[path = "tests/merge.rs"]
mod tests;
