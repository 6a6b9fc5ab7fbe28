//! Curves along principal directions (`curvenet sample --curves principal`).
//!
//! A smooth cross field on the faces (four directions at right angles, a 4-RoSy field) is
//! aligned with the principal curvature directions where the surface is clearly anisotropic
//! and with a fixed axis projected on the surface where it is not (planes, spheres): per face,
//! the second fundamental form is fitted to the vertex normals' differences along its edges
//! (Rusinkiewicz 2004), its principal direction enters the field with the weight
//! `(κ₁ − κ₂) / (|κ₁| + |κ₂| + κ₀)`, and the field is smoothed across the edges (the angle
//! measured from the shared edge is carried over, times 4). Streamlines of the field are then
//! traced on the mesh, face by face, from seeds spread over the surface (a seed starts a curve
//! in each of its two directions that no curve already covers within the separation), both
//! ways, until they reach the mesh boundary, close up, or come alongside another curve. Curves
//! of the two directions cross at about 90°. Crossings are computed exactly on the triangles
//! (two segments in the same face, in the face's plane) and shared by both curves, normals
//! are interpolated from the mesh, as for the plane sections; free ends are cut back to their
//! last crossing by [`super::sample_mesh`].
//!
//! The stages: the field (module `cross_field`), the streamlines (module `streamlines`),
//! then here their crossings (`cross_lines`) and the curves as polylines with their
//! crossings and bad spots (`polylines`).
//!
//! Reference: S. Rusinkiewicz, *Estimating curvatures and their derivatives on triangle
//! meshes*, 3DPVT 2004 (per-face fit of the second fundamental form).

use super::cross_field::{CrossField, Frame};
use super::crossings::{close_crossings, near_misses, CrossingPoints};
use super::mesh::{edge_key, Mesh};
use super::planes::{section_directions, MIN_CROSSING_ANGLE_DEG};
use super::sections::FaceCut;
use super::streamlines::{face_normal, Line, Tracer};
use super::{EndsOnBoundary, Raw, SampleOptions, Scales, Traced, Traces, PRINCIPAL_SEPARATION};
use crate::geom::DVec3;
use std::collections::HashMap;

/// The principal curves of the mesh (see the module documentation),
/// [`PRINCIPAL_SEPARATION`] × the box's mean extent over the mean of the non-zero
/// `opts.planes` counts apart, the field oriented by the third section direction
/// ([`section_directions`] of `opts.tilt`) where the surface is isotropic. The bad spots are
/// shallow crossings, ends on the boundary at a shallow angle, near misses closer than
/// `scales.near` and crossings closer than `scales.gap`.
pub(super) fn trace_principal(mesh: &Mesh, opts: &SampleOptions, scales: &Scales) -> Traces {
    // Curves along the principal directions, `separation` apart.
    let ext = scales.bbox.max - scales.bbox.min;
    let counts: Vec<f64> = opts.planes.iter().filter(|&&k| k > 0).map(|&k| k as f64).collect();
    let mean_count = counts.iter().sum::<f64>() / counts.len().max(1) as f64;
    let separation = PRINCIPAL_SEPARATION * (ext.x + ext.y + ext.z) / 3.0 / mean_count.max(1.0);
    let axis = section_directions(opts.tilt)[2];
    let field = CrossField::new(mesh, axis, scales.diag);
    let lines = Tracer::new(mesh, &field, separation, scales).seed_lines();
    let mut x = cross_lines(mesh, &field.frames, &lines);
    // The curves as traced polylines with their crossings; the mesh boundary as a pseudo
    // curve (index `lines.len()`) for the near-miss and close-crossing tests.
    let boundary_id = lines.len();
    let (traced, mut cuts, ends_on_boundary) = polylines(mesh, &lines, &mut x);
    for (e, fs) in &mesh.edge_faces {
        if fs.len() == 1 {
            let ends = [mesh.positions[e.0 as usize], mesh.positions[e.1 as usize]];
            cuts.push(FaceCut { plane: boundary_id, edges: [*e, *e], ends });
        }
    }
    let mut spots = x.spots;
    spots.extend(near_misses(&cuts, &x.points, scales.near, boundary_id));
    spots.extend(close_crossings(&x.points, scales.gap, scales.gap, boundary_id));
    spots.retain(|s| s.0 < boundary_id);
    let mut bad: Vec<usize> = spots.iter().map(|x| x.0).collect();
    bad.sort_unstable();
    bad.dedup();
    Traces { traced, ends_on_boundary, unresolved: bad.len(), spots, crossings: x.count, trimmed: 0 }
}

/// The crossings of the curves ([`cross_lines`]).
struct LineCrossings {
    /// Per curve: (segment, parameter along it, node sample) of its crossings.
    inserts: Vec<Vec<(usize, f64, Raw)>>,
    /// Crossing points per pair of curves (and the curve ends on the boundary).
    points: CrossingPoints,
    /// Bad spots: (curve, place).
    spots: Vec<(usize, DVec3)>,
    /// The number of crossings.
    count: usize,
}

/// The ends of segment `k` of curve `l` (the last segment of a closed curve ends at its first
/// point).
fn seg_ends(l: &Line, k: usize) -> (DVec3, DVec3) {
    (l.pts[k].p, l.pts[(k + 1) % l.pts.len()].p)
}

/// The crossings of the curves `lines`: two segments in the same face (faces in order) that
/// cross in its plane (`frames`), not neighbours on the same curve. Crossings at an angle
/// below [`MIN_CROSSING_ANGLE_DEG`] are bad spots of the curve with the larger index.
fn cross_lines(mesh: &Mesh, frames: &[Frame], lines: &[Line]) -> LineCrossings {
    let mut in_face: HashMap<usize, Vec<(usize, usize)>> = HashMap::new();
    for (li, l) in lines.iter().enumerate() {
        for (k, &f) in l.faces.iter().enumerate() {
            in_face.entry(f).or_default().push((li, k));
        }
    }
    let mut x =
        LineCrossings { inserts: vec![Vec::new(); lines.len()], points: HashMap::new(), spots: Vec::new(), count: 0 };
    let cos_min = MIN_CROSSING_ANGLE_DEG.to_radians().cos();
    let mut face_list: Vec<(&usize, &Vec<(usize, usize)>)> = in_face.iter().collect();
    face_list.sort_unstable_by_key(|x| *x.0);
    for (&f, list) in face_list {
        let fr = frames[f];
        for (i, &(la, ka)) in list.iter().enumerate() {
            for &(lb, kb) in &list[i + 1..] {
                if la == lb && ka.abs_diff(kb) <= 1 {
                    continue;
                }
                let (a0, a1) = seg_ends(&lines[la], ka);
                let (b0, b1) = seg_ends(&lines[lb], kb);
                let (p, q) = (fr.to2(a0), fr.to2(a1));
                let (r, s) = (fr.to2(b0), fr.to2(b1));
                let (u, v) = (q - p, s - r);
                let den = u.perp_dot(v);
                if den.abs() < 1e-14 * u.length() * v.length() {
                    continue;
                }
                let t = (r - p).perp_dot(v) / den;
                let w = (r - p).perp_dot(u) / den;
                if !((0.0..1.0).contains(&t) && (0.0..1.0).contains(&w)) {
                    continue;
                }
                let p3 = fr.to3(p + t * u);
                let raw = Raw { p: p3, n: face_normal(mesh, f, p3), node: true };
                x.inserts[la].push((ka, t, raw));
                x.inserts[lb].push((kb, w, raw));
                x.count += 1;
                x.points.entry((la.min(lb), la.max(lb))).or_default().push(p3);
                if u.normalize().dot(v.normalize()).abs() > cos_min {
                    x.spots.push((la.max(lb), p3));
                }
            }
        }
    }
    x
}

/// The curves as polylines (named `principal #k`) with their crossings `x.inserts` as node
/// samples in order, their segments as face cuts (for the near-miss test), and their ends on
/// boundary edges: nodes, recorded per edge and as crossings with the boundary pseudo-curve
/// `lines.len()` in `x.points`; an end at an angle below [`MIN_CROSSING_ANGLE_DEG`] to its
/// edge is a bad spot.
fn polylines(mesh: &Mesh, lines: &[Line], x: &mut LineCrossings) -> (Vec<Traced>, Vec<FaceCut>, EndsOnBoundary) {
    let (positions, faces) = (&mesh.positions, &mesh.faces);
    let boundary_id = lines.len();
    let cos_min = MIN_CROSSING_ANGLE_DEG.to_radians().cos();
    let mut ends_on_boundary: EndsOnBoundary = HashMap::new();
    let mut cuts: Vec<FaceCut> = Vec::new();
    let mut traced = Vec::new();
    for (li, l) in lines.iter().enumerate() {
        let mut samples = line_samples(l, std::mem::take(&mut x.inserts[li]));
        for (k, &f) in l.faces.iter().enumerate() {
            let (a, b) = seg_ends(l, k);
            let e = faces[f];
            cuts.push(FaceCut { plane: li, edges: [edge_key(e[0], e[1]), edge_key(e[1], e[2])], ends: [a, b] });
        }
        if !l.closed {
            for (side, edge) in l.ends.iter().enumerate() {
                let Some(e) = edge else { continue };
                let idx = if side == 0 { 0 } else { samples.len() - 1 };
                samples[idx].node = true;
                let r = samples[idx];
                ends_on_boundary.entry(*e).or_default().push(r);
                x.points.entry((li, boundary_id)).or_default().push(r.p);
                // Ends on the boundary at a shallow angle.
                let (pa, pb) = (positions[e.0 as usize], positions[e.1 as usize]);
                let k = if side == 0 { 0 } else { l.faces.len() - 1 };
                let (s0, s1) = seg_ends(l, k);
                let d = s1 - s0;
                if d.dot(pb - pa).abs() / (d.length() * pa.distance(pb)).max(f64::MIN_POSITIVE) > cos_min {
                    x.spots.push((li, r.p));
                }
            }
        }
        traced.push(Traced {
            plane: Some(li),
            samples,
            closed: l.closed,
            boundary: false,
            name: format!("principal #{li}"),
            cut: false,
            right: Vec::new(),
        });
    }
    (traced, cuts, ends_on_boundary)
}

/// The samples of curve `l`: its points, each followed by the crossings `ins` on the segment
/// it starts (segment, parameter, sample), in order along the segment.
fn line_samples(l: &Line, mut ins: Vec<(usize, f64, Raw)>) -> Vec<Raw> {
    ins.sort_by(|a, b| a.0.cmp(&b.0).then(a.1.total_cmp(&b.1)));
    let mut samples = Vec::with_capacity(l.pts.len() + ins.len());
    let mut it = ins.into_iter().peekable();
    for (k, pt) in l.pts.iter().enumerate() {
        samples.push(Raw { p: pt.p, n: pt.n, node: false });
        while let Some(x) = it.next_if(|x| x.0 == k) {
            samples.push(x.2);
        }
    }
    samples
}

#[cfg(test)]
#[path = "tests/principal.rs"]
mod tests;
