//! Details drawn on a surface (issue 30, docs/design.md §15): a closed curve that meets no
//! other bounds a disk of its own (§12, lone loops), but one drawn on another part of the
//! surface — an ornament on a shield, a button on a sketched mouse — is a detail of that part,
//! not a patch: its disk stands on the surface, a cap or a cone through it. After the solve, a
//! connected part of the mesh that is bounded by open borders only (every one of its curve
//! vertices on its border: the disk or tube of lone loops) and whose border lies on the rest
//! of the surface is left out, with a warning naming the place. The rest of the surface is
//! solved as before: parts that share no vertex share no equation.

use super::stats::Surface;
use crate::error::Warning;
use crate::geom::distance::MeshDistance;
use crate::geom::{Aabb, DVec3};
use crate::topology::UnionFind;

/// A border vertex lies on the rest of the surface within this fraction of the mesh's
/// bounding-box diagonal (the coverage's [`super::coverage::NEAR`]: a stroke that near the
/// surface counts as on it).
pub const ON_SURFACE: f64 = super::coverage::NEAR;

/// A part is drawn on the rest when at least this share of its border vertices lie on it (a
/// hand-drawn loop strays here and there).
pub const ON_SHARE: f64 = 0.9;

/// Leaves out of `surface` the parts drawn on the rest of it (module documentation); one
/// warning for all of them, `None` when there is none.
pub fn leave_out_drawn_on(surface: &mut Surface) -> Option<Warning> {
    let mesh = &surface.mesh;
    let n = mesh.num_vertices();
    if mesh.faces.len() < 2 {
        return None;
    }
    let mut parts = UnionFind::new(n);
    for f in &mesh.faces {
        parts.union(f[0] as usize, f[1] as usize);
        parts.union(f[0] as usize, f[2] as usize);
    }
    let part_of_face: Vec<usize> = mesh.faces.iter().map(|f| parts.find(f[0] as usize)).collect();
    // One part (every surface of a connected network): nothing to lie on.
    if part_of_face.iter().all(|&p| p == part_of_face[0]) {
        return None;
    }
    // Per part: vertices, edges and faces (its Euler characteristic), and its curve vertices.
    let mut count: std::collections::BTreeMap<usize, [i64; 3]> = std::collections::BTreeMap::new();
    let mut edges: std::collections::HashSet<(u32, u32)> = std::collections::HashSet::new();
    for (f, &r) in mesh.faces.iter().zip(&part_of_face) {
        let c = count.entry(r).or_default();
        c[2] += 1;
        for k in 0..3 {
            let (a, b) = (f[k], f[(k + 1) % 3]);
            if edges.insert((a.min(b), a.max(b))) {
                c[1] += 1;
            }
        }
    }
    let mut seen = vec![false; n];
    let mut curve: std::collections::BTreeMap<usize, Vec<usize>> = std::collections::BTreeMap::new();
    for f in &mesh.faces {
        for &v in f {
            let v = v as usize;
            if !seen[v] {
                seen[v] = true;
                let r = parts.find(v);
                if let Some(c) = count.get_mut(&r) {
                    c[0] += 1;
                }
                if v < mesh.num_curve {
                    curve.entry(r).or_default().push(v);
                }
            }
        }
    }
    // Candidates: disks (χ = 1) with curve vertices, when the surface has another part.
    let candidates: Vec<(usize, Vec<usize>)> =
        curve.into_iter().filter(|(r, _)| count.get(r).is_some_and(|c| c[0] - c[1] + c[2] == 1)).collect();
    if candidates.is_empty() || count.len() < 2 {
        return None;
    }
    let tol = ON_SURFACE * Aabb::of(mesh.positions.iter().copied()).diagonal();
    let bvh = MeshDistance::new(&mesh.positions, &mesh.faces);
    let mut dropped: Vec<(usize, DVec3)> = Vec::new();
    for (r, verts) in &candidates {
        let on = verts
            .iter()
            .filter(|&&v| bvh.closest_face_where(mesh.positions[v], |f| part_of_face[f] != *r).0 <= tol)
            .count();
        if on as f64 >= ON_SHARE * verts.len() as f64 {
            dropped.push((*r, mesh.positions[verts[0]]));
        }
    }
    if dropped.is_empty() {
        return None;
    }
    let gone: std::collections::BTreeSet<usize> = dropped.iter().map(|d| d.0).collect();
    let keep_face: Vec<bool> = part_of_face.iter().map(|p| !gone.contains(p)).collect();
    let patches_left: std::collections::BTreeSet<u32> =
        mesh.face_patch.iter().zip(&keep_face).filter(|x| *x.1).map(|x| *x.0).collect();
    let patches_gone =
        mesh.face_patch.iter().copied().collect::<std::collections::BTreeSet<u32>>().len() - patches_left.len();
    keep_faces(surface, &keep_face);
    surface.stats.cycles = surface.stats.cycles.saturating_sub(patches_gone);
    let places: Vec<String> = dropped.iter().take(4).map(|d| crate::geom::fmt_point(d.1)).collect();
    Some(Warning::new(format!(
        "{} part(s) of the surface bounded by closed curves that meet no other (near {}{}) lie on the rest of the \
         surface (within {:.0} % of the diagonal): taken as details drawn on it, their disks were left out",
        dropped.len(),
        places.join(", "),
        if dropped.len() > places.len() { ", …" } else { "" },
        100.0 * ON_SURFACE
    )))
}

/// Keeps the faces `keep` of `surface` and the vertices they use (in their order: the curve
/// vertices stay first), with every per-vertex and per-face attribute and the statistics.
fn keep_faces(surface: &mut Surface, keep: &[bool]) {
    let mesh = &mut surface.mesh;
    let n = mesh.num_vertices();
    let mut used = vec![false; n];
    for (f, _) in mesh.faces.iter().zip(keep).filter(|x| *x.1) {
        f.iter().for_each(|&v| used[v as usize] = true);
    }
    let mut index = vec![u32::MAX; n];
    let mut next = 0u32;
    for v in 0..n {
        if used[v] {
            index[v] = next;
            next += 1;
        }
    }
    let pick = |v: &[bool]| v.iter().zip(&used).filter(|x| *x.1).map(|x| *x.0).collect::<Vec<bool>>();
    let pick3 = |v: &[DVec3]| v.iter().zip(&used).filter(|x| *x.1).map(|x| *x.0).collect::<Vec<DVec3>>();
    let num_curve = used[..mesh.num_curve].iter().filter(|u| **u).count();
    mesh.positions = pick3(&mesh.positions);
    mesh.curve_normals = mesh.curve_normals.iter().zip(&used).filter(|x| *x.1).map(|x| *x.0).collect();
    mesh.on_boundary = pick(&mesh.on_boundary);
    mesh.num_curve = num_curve;
    let faces = std::mem::take(&mut mesh.faces);
    mesh.faces = faces.iter().zip(keep).filter(|x| *x.1).map(|x| x.0.map(|v| index[v as usize])).collect();
    mesh.planar = mesh.planar.iter().zip(keep).filter(|x| *x.1).map(|x| *x.0).collect();
    mesh.face_patch = mesh.face_patch.iter().zip(keep).filter(|x| *x.1).map(|x| *x.0).collect();
    mesh.seam_rows.retain(|r| used[r.0 as usize]);
    mesh.seam_rows.iter_mut().for_each(|r| r.0 = index[r.0 as usize]);
    mesh.pattern = Default::default();
    surface.normals = pick3(&surface.normals);
    surface.mean_curvature = surface.mean_curvature.iter().zip(&used).filter(|x| *x.1).map(|x| *x.0).collect();
    surface.propagated_normals = surface.propagated_normals.as_deref().map(pick3);
    surface.curve_flags = pick(&surface.curve_flags);
    surface.stats.vertices = mesh.num_vertices();
    surface.stats.faces = mesh.faces.len();
    surface.stats.curve_vertices = mesh.num_curve;
}

#[cfg(test)]
#[path = "tests/details.rs"]
mod tests;
