//! Details drawn on a surface (issue 30, docs/design.md §15): a closed curve that meets no
//! other bounds a disk of its own (§12, lone loops), but one drawn on another part of the
//! surface — an ornament on a shield, a button on a sketched mouse — is a detail of that part,
//! not a patch: its disk stands on the surface, a cap or a cone through it. After the solve, a
//! connected part of the mesh that is a disk (Euler characteristic 1: a lone loop's, or a
//! loop with strokes across it) and whose curve vertices lie over the inside of the rest of
//! the surface (not at its border: a lid that closes another part's opening is no detail) is
//! left out, with a warning naming the place. The rest of the surface is solved as before:
//! parts that share no vertex share no equation.
//!
//! Strokes that bound no patch but run over one — those loops, a stroke drawn inside a panel,
//! the dangling part of a stroke, one the cycle choice left out — are then constraints of the
//! surface they lie on ([`pull_onto_strokes`]): the surface is deformed onto them, the
//! displacement a biharmonic field (`Δ² D = 0`, [`crate::methods::harmonic`]) that is zero on
//! the curves of the network and equal to the stroke's offset at the vertices under it.

use super::stats::Surface;
use crate::error::Warning;
use crate::geom::distance::MeshDistance;
use crate::geom::{Aabb, DVec3};
use crate::topology::UnionFind;

/// A border vertex lies on the rest of the surface within this fraction of the mesh's
/// bounding-box diagonal (the coverage's [`super::coverage::NEAR`]: a stroke that near the
/// surface counts as on it).
pub const ON_SURFACE: f64 = super::coverage::NEAR;

/// A part is drawn on the rest when at least this share of its curve vertices lie on it (a
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
        // On the rest within the tolerance, over a face with no curve vertex (inside a patch).
        let inside = |f: usize| f != usize::MAX && mesh.faces[f].iter().all(|&v| v as usize >= mesh.num_curve);
        let on = verts
            .iter()
            .filter(|&&v| {
                let (d, _, f) = bvh.closest_face_where(mesh.positions[v], |f| part_of_face[f] != *r);
                d <= tol && inside(f)
            })
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
        "{} disk-shaped part(s) of the surface whose curves meet no other part (near {}{}) lie on the rest of the \
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
    let num_curve = used[..mesh.num_curve].iter().filter(|u| **u).count();
    mesh.positions = masked(&mesh.positions, &used);
    mesh.curve_normals = masked(&mesh.curve_normals, &used);
    mesh.on_boundary = masked(&mesh.on_boundary, &used);
    mesh.num_curve = num_curve;
    mesh.faces = masked(&mesh.faces, keep).into_iter().map(|f| f.map(|v| index[v as usize])).collect();
    mesh.planar = masked(&mesh.planar, keep);
    mesh.face_patch = masked(&mesh.face_patch, keep);
    mesh.seam_rows.retain(|r| used[r.0 as usize]);
    mesh.seam_rows.iter_mut().for_each(|r| r.0 = index[r.0 as usize]);
    mesh.pattern = Default::default();
    surface.normals = masked(&surface.normals, &used);
    surface.mean_curvature = masked(&surface.mean_curvature, &used);
    surface.propagated_normals = surface.propagated_normals.as_deref().map(|p| masked(p, &used));
    surface.curve_flags = masked(&surface.curve_flags, &used);
    surface.stats.vertices = mesh.num_vertices();
    surface.stats.faces = mesh.faces.len();
    surface.stats.curve_vertices = mesh.num_curve;
}

/// The items of `v` whose entry in `mask` is set (`v` may be shorter: the curve vertices'
/// attributes against a per-vertex mask).
fn masked<T: Copy>(v: &[T], mask: &[bool]) -> Vec<T> {
    v.iter().zip(mask).filter(|x| *x.1).map(|x| *x.0).collect()
}

/// Strokes within this fraction of the bounding-box diagonal of the surface pull it onto them
/// (the raw CASSIE strokes that bound no patch lie within 1–4 % of the surface, docs/design.md
/// §15).
pub const PULL_REACH: f64 = 0.04;

/// A stroke point pulls the surface only over its inside: at a vertex at least this many edges
/// from the curves of the network (a stroke that runs on past a border, or along a curve it
/// duplicates, does not).
const INSIDE_HOPS: u32 = 3;

/// Deforms `surface` onto the points of `curves` (the network's curves, each its samples and
/// closedness) that lie over its inside within [`PULL_REACH`] of the diagonal and more than
/// two mesh edges (`spacing` long) from its curve vertices (module documentation). `Ok(None)`
/// when no stroke pulls; a warning saying how many points pulled and how far the surface
/// moved otherwise. Errors only as the biharmonic solve does.
pub fn pull_onto_strokes(surface: &mut Surface, curves: &[(Vec<DVec3>, bool)], spacing: f64) -> Option<Warning> {
    let mesh = &surface.mesh;
    let nc = mesh.num_curve;
    if nc == 0 || mesh.faces.is_empty() || !(spacing > 0.0) {
        return None;
    }
    // The stroke points off the network's curves: densified to the spacing, farther than two
    // edges from every curve vertex (a point index over them, as degenerate triangles).
    let dots: Vec<[u32; 3]> = (0..nc as u32).map(|v| [v, v, v]).collect();
    let on_curves = MeshDistance::new(&mesh.positions, &dots);
    let mut off: Vec<DVec3> = Vec::new();
    for (points, closed) in curves {
        let n = points.len();
        let m = if *closed { n } else { n.saturating_sub(1) };
        for i in 0..m {
            let (a, b) = (points[i], points[(i + 1) % n]);
            let pieces = ((a.distance(b) / spacing).ceil() as usize).clamp(1, 1000);
            for k in 0..pieces {
                let p = a.lerp(b, k as f64 / pieces as f64);
                if on_curves.closest(p).0 > 2.0 * spacing {
                    off.push(p);
                }
            }
        }
    }
    if off.is_empty() {
        return None;
    }
    let diag = Aabb::of(mesh.positions.iter().copied()).diagonal();
    let reach = PULL_REACH * diag;
    // Edges from the curve vertices (breadth first over the faces' edges).
    let hops = hops_from_curves(mesh);
    let bvh = MeshDistance::new(&mesh.positions, &mesh.faces);
    let mut sum: std::collections::BTreeMap<usize, (DVec3, f64)> = std::collections::BTreeMap::new();
    for p in off {
        let (d, q, f) = bvh.closest_face(p);
        if !(d <= reach) || f == usize::MAX {
            continue;
        }
        let corner = mesh.faces[f].map(|v| v as usize);
        let Some(&v) =
            corner.iter().min_by(|&&a, &&b| mesh.positions[a].distance(q).total_cmp(&mesh.positions[b].distance(q)))
        else {
            continue;
        };
        if hops[v] < INSIDE_HOPS {
            continue;
        }
        let e = sum.entry(v).or_insert((DVec3::ZERO, 0.0));
        e.0 += p - q;
        e.1 += 1.0;
    }
    let largest = sum.values().map(|(d, k)| (*d / *k).length()).fold(0.0, f64::max);
    // Points already on the surface (within a thousandth of the diagonal) need no pull.
    if sum.is_empty() || largest <= 1e-3 * diag {
        return None;
    }
    // Only the patches under the strokes move (free vertices belong to one patch each; the
    // curve vertices between patches stay): the biharmonic solve runs on them alone.
    let mut moving = std::collections::BTreeSet::new();
    for (f, &p) in mesh.faces.iter().zip(&mesh.face_patch) {
        if f.iter().any(|v| sum.contains_key(&(*v as usize))) {
            moving.insert(p);
        }
    }
    let faces: Vec<[u32; 3]> =
        mesh.faces.iter().zip(&mesh.face_patch).filter(|x| moving.contains(x.1)).map(|x| *x.0).collect();
    let mut local = vec![u32::MAX; mesh.num_vertices()];
    let mut global: Vec<usize> = Vec::new();
    for f in &faces {
        for &v in f {
            if local[v as usize] == u32::MAX {
                local[v as usize] = global.len() as u32;
                global.push(v as usize);
            }
        }
    }
    let faces: Vec<[u32; 3]> = faces.iter().map(|f| f.map(|v| local[v as usize])).collect();
    let positions: Vec<DVec3> = global.iter().map(|&v| mesh.positions[v]).collect();
    let mut fixed: Vec<usize> = Vec::new();
    let mut values: Vec<f64> = Vec::new();
    for (i, &v) in global.iter().enumerate() {
        let d = if v < nc {
            DVec3::ZERO
        } else if let Some((d, k)) = sum.get(&v) {
            *d / *k
        } else {
            continue;
        };
        fixed.push(i);
        values.extend([d.x, d.y, d.z]);
    }
    let field = match crate::methods::harmonic::harmonic(&positions, &faces, &fixed, &values, 3, 2) {
        Ok(f) => f,
        Err(e) => {
            return Some(Warning::new(format!(
                "strokes that bound no patch run over one, but the surface could not be pulled onto them ({e}): it \
                 was left as solved"
            )))
        }
    };
    let pulled = sum.len();
    let mesh = &mut surface.mesh;
    for (i, &v) in global.iter().enumerate() {
        if v >= nc {
            mesh.positions[v] += DVec3::new(field[3 * i], field[3 * i + 1], field[3 * i + 2]);
        }
    }
    let (normals, mean_curvature) =
        crate::operators::normals_and_mean_curvature(&mesh.faces, &mesh.positions, &mesh.on_boundary);
    surface.normals = normals;
    surface.mean_curvature = mean_curvature;
    Some(Warning::new(format!(
        "strokes that bound no patch but run over one (within {:.0} % of the diagonal) were taken as constraints: \
         the surface was pulled onto them at {pulled} vertices, by up to {largest:.3e}",
        100.0 * PULL_REACH
    )))
}

/// Per vertex of `mesh`: the number of edges to the nearest curve vertex (`u32::MAX` when none
/// is connected).
fn hops_from_curves(mesh: &crate::geom::mesh::Mesh) -> Vec<u32> {
    let n = mesh.num_vertices();
    let mut next: Vec<Vec<u32>> = vec![Vec::new(); n];
    for f in &mesh.faces {
        for k in 0..3 {
            next[f[k] as usize].push(f[(k + 1) % 3]);
            next[f[(k + 1) % 3] as usize].push(f[k]);
        }
    }
    let mut hops = vec![u32::MAX; n];
    let mut queue: std::collections::VecDeque<usize> = (0..mesh.num_curve).collect();
    queue.iter().for_each(|&v| hops[v] = 0);
    while let Some(v) = queue.pop_front() {
        for &w in &next[v] {
            if hops[w as usize] == u32::MAX {
                hops[w as usize] = hops[v] + 1;
                queue.push_back(w as usize);
            }
        }
    }
    hops
}

#[cfg(test)]
#[path = "tests/details.rs"]
mod tests;
