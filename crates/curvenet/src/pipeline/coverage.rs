//! How the surface fits its input, both ways:
//! - **coverage**, how much of the input the surface passes near: a run which left strokes out
//!   (dangling, duplicates, curves that bound no patch) says so, and a surface that misses most
//!   of the sketch is refused (docs/design.md §14);
//! - **reach**, how far each patch strays from its own boundary curves: a patch whose solve ran
//!   away (a spike or balloon far outside the curves, from a degenerate cycle or a folded
//!   domain) is refused instead of written (docs/design.md §14);
//! - **self-intersections**: a surface that passes through itself (two cones through each
//!   other, a patch through its neighbour) is named in a warning, never a quiet success.

use crate::error::{Error, Result, Warning};
use crate::geom::distance::MeshDistance;
use crate::geom::mesh::Mesh;
use crate::geom::{Aabb, DVec3};
use crate::network::{curve_label, Network};

/// A stroke point counts as on the surface within this fraction of the bounding-box diagonal.
pub const NEAR: f64 = 0.01;
/// A surface near less than this fraction of the stroke length is an error.
pub const MIN_COVERAGE: f64 = 0.5;
/// A curve near the surface over less than this fraction of its length is named as left out.
const CURVE_LEFT_OUT: f64 = 0.5;

/// The fraction of the total length of `network`'s curves within [`NEAR`] × its diagonal of
/// `mesh`, and per curve.
pub fn stroke_coverage(mesh: &Mesh, network: &Network) -> (f64, Vec<f64>) {
    let tol = NEAR * network.bounding_box().diagonal();
    let bvh = MeshDistance::new(&mesh.positions, &mesh.faces);
    let (mut near_total, mut total) = (0.0, 0.0);
    let mut per_curve = Vec::with_capacity(network.curves.len());
    for c in &network.curves {
        let n = c.points.len();
        let m = if c.closed { n } else { n.saturating_sub(1) };
        let (mut near, mut len) = (0.0, 0.0);
        for i in 0..m {
            let (a, b) = (c.points[i], c.points[(i + 1) % n]);
            let l = a.distance(b);
            let pieces = ((l / tol).ceil() as usize).clamp(1, 1000);
            for k in 0..pieces {
                let p = a.lerp(b, (k as f64 + 0.5) / pieces as f64);
                if bvh.closest(p).0 <= tol {
                    near += l / pieces as f64;
                }
            }
            len += l;
        }
        per_curve.push(if len > 0.0 { near / len } else { 1.0 });
        near_total += near;
        total += len;
    }
    (if total > 0.0 { near_total / total } else { 1.0 }, per_curve)
}

/// Checks the coverage of `network` (the input as given) by `mesh`: an error below
/// [`MIN_COVERAGE`], a warning naming the curves left out otherwise. Returns the coverage.
pub fn check_coverage(mesh: &Mesh, network: &Network, warnings: &mut Vec<Warning>) -> Result<f64> {
    let (all, per_curve) = stroke_coverage(mesh, network);
    let out: Vec<usize> = (0..per_curve.len()).filter(|&c| per_curve[c] < CURVE_LEFT_OUT).collect();
    if out.is_empty() {
        return Ok(all);
    }
    let names: Vec<String> = out.iter().take(8).map(|&c| curve_label(&network.curves, c)).collect();
    let more = if out.len() > names.len() { format!(" and {} more", out.len() - names.len()) } else { String::new() };
    let text = format!(
        "the surface passes near {:.0} % of the strokes' length (within {:.0} % of the bounding-box diagonal); {} of \
         {} curves are left out (mostly or wholly): {}{more}",
        100.0 * all,
        100.0 * NEAR,
        out.len(),
        per_curve.len(),
        names.join(", ")
    );
    if all < MIN_COVERAGE {
        return Err(Error::topology(format!(
            "{text}. A surface that misses most of the sketch is not written: the curves there could not be closed \
             into patches (strokes that do not meet: a larger `gap`; or curves that bound no 2-manifold)"
        ))
        .curve(out[0]));
    }
    warnings.push(Warning::new(text).curve(out[0]));
    Ok(all)
}

/// A patch whose surface lies farther than this many times its boundary's bounding-box
/// diagonal from that box has run away. A hemisphere over a circle reaches 0.35 of the circle's
/// box diagonal; the most measured on a surface people expect is in docs/design.md §14.
pub const MAX_REACH: f64 = 1.0;

/// Per patch of `mesh`: the largest distance of its vertices from the bounding box of its curve
/// vertices, over that box's diagonal (0 for a patch without curve vertices).
pub fn patch_reach(mesh: &Mesh) -> Vec<f64> {
    reach_of(&mesh.positions, &mesh.faces, &mesh.face_patch, mesh.num_curve)
}

/// [`patch_reach`] of the faces `faces` with patches `face_patch` at `positions`, the first
/// `num_curve` of which lie on curves.
fn reach_of(positions: &[DVec3], faces: &[[u32; 3]], face_patch: &[u32], num_curve: usize) -> Vec<f64> {
    let patches = face_patch.iter().map(|&p| p as usize + 1).max().unwrap_or(0);
    let mut boxes = vec![Aabb::empty(); patches];
    for (f, &p) in faces.iter().zip(face_patch) {
        for &v in f.iter().filter(|&&v| (v as usize) < num_curve) {
            boxes[p as usize].extend(positions[v as usize]);
        }
    }
    let mut reach = vec![0.0f64; patches];
    for (f, &p) in faces.iter().zip(face_patch) {
        let b = &boxes[p as usize];
        let d = b.diagonal();
        if !(d > 0.0) {
            continue;
        }
        for &v in f {
            let x = positions[v as usize];
            let out = (b.min - x).max(x - b.max).max(DVec3::ZERO).length();
            reach[p as usize] = reach[p as usize].max(out / d);
        }
    }
    reach
}

/// Counts the crossing triangle pairs of `mesh` into `stats.self_intersections`; a warning
/// naming the first place and its patches when there are any.
pub fn check_self_intersections(mesh: &Mesh, stats: &mut super::Stats) -> Option<Warning> {
    let found = crate::geom::intersect::self_intersections(&mesh.positions, &mesh.faces);
    stats.self_intersections = found.pairs;
    let (f, g, p) = found.first?;
    let (pf, pg) = (mesh.face_patch[f as usize] as usize, mesh.face_patch[g as usize] as usize);
    let which = if pf == pg { format!("patch {pf} through itself") } else { format!("patches {pf} and {pg}") };
    Some(
        Warning::new(format!(
            "the surface passes through itself: {} pair(s) of triangles cross, the first near {} ({which}); a fold \
             or two sheets through each other, from normals that point to opposite sides or curves closer than the \
             mesh spacing",
            found.pairs,
            crate::geom::fmt_point(p)
        ))
        .patch(pf),
    )
}

/// Refuses a surface with a patch that ran away ([`MAX_REACH`]); returns the largest reach.
pub fn check_reach(mesh: &Mesh) -> Result<f64> {
    let reach = patch_reach(mesh);
    let worst = (0..reach.len()).max_by(|&a, &b| reach[a].total_cmp(&reach[b]));
    match worst {
        Some(p) if !(reach[p] <= MAX_REACH) => Err(Error::numerical(format!(
            "patch {p}: its surface runs away from its curves, to {:.1} times their extent outside them (a spike \
             or balloon, from a cycle that bounds no sensible surface or a domain that folded over); it is not \
             written. The run's warnings say where its patching fell back; normals given for its curves fix their sides",
            reach[p]
        ))
        .patch(p)),
        Some(p) => Ok(reach[p]),
        None => Ok(0.0),
    }
}

#[cfg(test)]
#[path = "tests/coverage.rs"]
mod tests;

/// The open borders of `mesh` that no boundary curve runs along: loops of edges in one face
/// only, between curve vertices (free vertices lie inside patches), not both on a boundary
/// curve. A closed shape's cycle left unfilled — a hole a person sees at once, while every
/// stroke around it lies on the surface and the coverage is full — is named in a warning with
/// the loops' count, length and place (the longest first), or an open border of a sketch whose
/// curves were not found to be one. Returns the number of loops and the warning (`None` when
/// every border is a boundary curve's).
pub fn check_open_borders(mesh: &Mesh) -> (usize, Option<Warning>) {
    let curve = |v: u32| (v as usize) < mesh.num_curve;
    let mut faces_of: std::collections::HashMap<[u32; 2], u32> = std::collections::HashMap::new();
    for f in &mesh.faces {
        for k in 0..3 {
            let (a, b) = (f[k], f[(k + 1) % 3]);
            if curve(a) && curve(b) {
                *faces_of.entry([a.min(b), a.max(b)]).or_insert(0) += 1;
            }
        }
    }
    let boundary = |v: u32| mesh.on_boundary.get(v as usize).copied().unwrap_or(false);
    let mut open: Vec<[u32; 2]> =
        faces_of.into_iter().filter(|&(e, n)| n == 1 && !(boundary(e[0]) && boundary(e[1]))).map(|(e, _)| e).collect();
    if open.is_empty() {
        return (0, None);
    }
    open.sort_unstable();
    // Loops: the edges' connected components (union-find on their vertices).
    let mut parent: std::collections::HashMap<u32, u32> = std::collections::HashMap::new();
    fn root(parent: &mut std::collections::HashMap<u32, u32>, v: u32) -> u32 {
        let mut r = v;
        while let Some(&p) = parent.get(&r).filter(|&&p| p != r) {
            r = p;
        }
        parent.insert(v, r);
        r
    }
    for &[a, b] in &open {
        let (ra, rb) = (root(&mut parent, a), root(&mut parent, b));
        parent.insert(ra.max(rb), ra.min(rb));
    }
    // Per loop: its length and the length-weighted sum of its edges' midpoints (its centre: the
    // middle of a hole).
    let mut loops: std::collections::BTreeMap<u32, (f64, DVec3)> = std::collections::BTreeMap::new();
    for &[a, b] in &open {
        let (pa, pb) = (mesh.positions[a as usize], mesh.positions[b as usize]);
        let l = loops.entry(root(&mut parent, a)).or_insert((0.0, DVec3::ZERO));
        l.0 += pa.distance(pb);
        l.1 += pa.distance(pb) * 0.5 * (pa + pb);
    }
    let total: f64 = loops.values().map(|l| l.0).sum();
    let (longest, sum) = loops.values().copied().max_by(|x, y| x.0.total_cmp(&y.0)).unwrap_or((0.0, DVec3::ZERO));
    let at = if longest > 0.0 { sum / longest } else { sum };
    let warning = Warning::new(format!(
        "the surface is open along {} border loop(s) of curves that are not boundary curves ({total:.3e} long in all; \
         the longest, {longest:.3e}, near {}): a cycle of curves left unfilled — a hole, where the shape is closed — or \
         an open border of the sketch; the curves around it could not be made into a patch (look there, or tag a true \
         border `\"boundary\": true`)",
        loops.len(),
        crate::geom::fmt_point(at)
    ));
    (loops.len(), Some(warning))
}
