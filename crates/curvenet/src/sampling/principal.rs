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
//! The stages: the field (module `cross_field`), the streamlines (a `Tracer`), their
//! crossings, the curves as polylines with their crossings and bad spots.
//!
//! Reference: S. Rusinkiewicz, *Estimating curvatures and their derivatives on triangle
//! meshes*, 3DPVT 2004 (per-face fit of the second fundamental form).

use super::cross_field::{CrossField, Frame};
use super::crossings::{close_crossings, near_misses, CrossingPoints};
use super::mesh::{edge_key, Mesh};
use super::planes::{section_directions, MIN_CROSSING_ANGLE_DEG};
use super::sections::FaceCut;
use super::{EndsOnBoundary, Raw, SampleOptions, Scales, Traced, Traces, PRINCIPAL_SEPARATION};
use crate::geom::{DVec2, DVec3};
use std::collections::HashMap;

/// A curve stops when it comes within this fraction of the separation of another curve
/// running alongside (within [`PARALLEL_DEG`]).
const STOP_FRACTION: f64 = 0.3;
/// Directions closer than this (degrees) count as alongside.
const PARALLEL_DEG: f64 = 35.0;

/// A point of a traced curve with its normal: on an edge (the edge's vertex normals
/// interpolated) or inside a face (the seed: the face's vertex normals interpolated).
#[derive(Clone, Copy)]
struct Pt {
    /// Position.
    p: DVec3,
    /// Normal (not normalised).
    n: DVec3,
}

/// A traced curve: points, the face of each segment (`faces[k]` holds `pts[k]..pts[k+1]`).
struct Line {
    /// The points (a closed curve does not repeat its first one).
    pts: Vec<Pt>,
    /// The face of each segment.
    faces: Vec<usize>,
    /// A closed loop (its last segment back to the first point).
    closed: bool,
    /// Boundary edges the curve ends on (first end, last end).
    ends: [Option<(u32, u32)>; 2],
}

/// One way of a curve from its seed ([`Tracer::trace_one`]).
struct Half {
    /// The points from the seed on.
    pts: Vec<Pt>,
    /// The face of each segment.
    faces: Vec<usize>,
    /// The boundary edge it ended on.
    boundary: Option<(u32, u32)>,
    /// Back at the seed: the whole curve, closed.
    closed: bool,
}

/// A segment in a [`SegGrid`]: (curve, start, end, arc position).
type GridSeg = (usize, DVec3, DVec3, f64);

/// Segments of the traced curves in a uniform grid (for the stop and seed tests).
struct SegGrid {
    /// The cell size.
    h: f64,
    /// The segments passing through each cell.
    cells: HashMap<(i64, i64, i64), Vec<GridSeg>>,
}

impl SegGrid {
    /// The cell of point `p`.
    fn cell(&self, p: DVec3) -> (i64, i64, i64) {
        ((p.x / self.h).floor() as i64, (p.y / self.h).floor() as i64, (p.z / self.h).floor() as i64)
    }
    /// Adds segment `a`–`b` of curve `line` at arc position `arc`.
    fn add(&mut self, line: usize, a: DVec3, b: DVec3, arc: f64) {
        let (lo, hi) = (self.cell(a.min(b)), self.cell(a.max(b)));
        if (hi.0 - lo.0 + 1) * (hi.1 - lo.1 + 1) * (hi.2 - lo.2 + 1) > 64 {
            return;
        }
        for x in lo.0..=hi.0 {
            for y in lo.1..=hi.1 {
                for z in lo.2..=hi.2 {
                    self.cells.entry((x, y, z)).or_default().push((line, a, b, arc));
                }
            }
        }
    }
    /// A segment within `r` of `p` running along `d` (within [`PARALLEL_DEG`] or `cos_limit`),
    /// other than those of `skip` (curve, arc window).
    fn alongside(&self, p: DVec3, d: DVec3, r: f64, cos_limit: f64, skip: Option<(usize, f64, f64)>) -> bool {
        let c = self.cell(p);
        let reach = (r / self.h).ceil() as i64;
        for x in c.0 - reach..=c.0 + reach {
            for y in c.1 - reach..=c.1 + reach {
                for z in c.2 - reach..=c.2 + reach {
                    for &(line, a, b, arc) in self.cells.get(&(x, y, z)).map_or(&[][..], |v| &v[..]) {
                        if let Some((l, lo, hi)) = skip {
                            if l == line && arc > lo && arc < hi {
                                continue;
                            }
                        }
                        let e = b - a;
                        let t = ((p - a).dot(e) / e.length_squared().max(f64::MIN_POSITIVE)).clamp(0.0, 1.0);
                        if p.distance(a + t * e) <= r && e.normalize_or_zero().dot(d).abs() >= cos_limit {
                            return true;
                        }
                    }
                }
            }
        }
        false
    }
    /// Removes the segments of curve `line`.
    fn remove(&mut self, line: usize) {
        self.cells.values_mut().for_each(|l| l.retain(|x| x.0 != line));
    }
}

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

/// Traces the streamlines of a cross field on a mesh, keeping them apart.
struct Tracer<'a> {
    /// The mesh traced on.
    mesh: &'a Mesh,
    /// The field followed.
    field: &'a CrossField,
    /// The segments traced so far.
    grid: SegGrid,
    /// The distance between the curves.
    separation: f64,
    /// The sample spacing (a curve closes within 0.3 of it from its seed).
    spacing: f64,
    /// A curve stops within this distance of another one alongside ([`STOP_FRACTION`]).
    stop_r: f64,
    /// Cosine of [`PARALLEL_DEG`].
    cos_par: f64,
    /// Longest curve half: 3 box diagonals.
    max_len: f64,
}

impl<'a> Tracer<'a> {
    /// A tracer of `field`'s streamlines on `mesh`, `separation` apart.
    fn new(mesh: &'a Mesh, field: &'a CrossField, separation: f64, scales: &Scales) -> Tracer<'a> {
        Tracer {
            mesh,
            field,
            grid: SegGrid { h: separation.max(f64::MIN_POSITIVE), cells: HashMap::new() },
            separation,
            spacing: scales.spacing,
            stop_r: STOP_FRACTION * separation,
            cos_par: PARALLEL_DEG.to_radians().cos(),
            max_len: 3.0 * scales.diag,
        }
    }

    /// The curves from seeds at the face centroids, in a fixed pseudo-random order: a seed
    /// starts a curve along each of the field directions closest to its face's two frame axes
    /// that no curve runs along within 0.9 separation (40°).
    fn seed_lines(mut self) -> Vec<Line> {
        let (mesh, field) = (self.mesh, self.field);
        let nf = mesh.faces.len();
        // Seeds: face centroids in a fixed pseudo-random order.
        let mut order: Vec<usize> = (0..nf).filter(|&f| field.good[f]).collect();
        let mut rng = crate::network::Rng::new(0x9121_1C1A);
        for i in (1..order.len()).rev() {
            let j = (rng.next_u64() % (i as u64 + 1)) as usize;
            order.swap(i, j);
        }
        let cos_seed = 40f64.to_radians().cos();
        let mut lines: Vec<Line> = Vec::new();
        for &fi in &order {
            let fr = field.frames[fi];
            let c = mesh.faces[fi].map(|v| mesh.positions[v as usize]).iter().sum::<DVec3>() / 3.0;
            for base in [fr.e1, fr.e2] {
                let u = field.dir(fi, base);
                if u == DVec3::ZERO || self.grid.alongside(c, u, 0.9 * self.separation, cos_seed, None) {
                    continue;
                }
                if let Some(line) = self.line_from(lines.len(), fi, c, u) {
                    lines.push(line);
                }
            }
        }
        lines
    }

    /// The curve `id` through seed `c` in face `fi`, traced along `u` and, unless that closes
    /// it, along `−u`; `None` (its segments removed from the grid) when it is shorter than two
    /// separations.
    fn line_from(&mut self, id: usize, fi: usize, c: DVec3, u: DVec3) -> Option<Line> {
        let fwd = self.trace_one(id, fi, c, u, 1.0);
        let (pts, segs, closed, ends) = if fwd.closed {
            (fwd.pts, fwd.faces, true, [None, None])
        } else {
            let back = self.trace_one(id, fi, c, -u, -1.0);
            let mut pts: Vec<Pt> = back.pts.iter().rev().copied().collect();
            let mut segs: Vec<usize> = back.faces.iter().rev().copied().collect();
            if pts.is_empty() {
                pts = fwd.pts.clone();
            } else {
                pts.extend(fwd.pts.iter().skip(1).copied());
            }
            segs.extend(fwd.faces.iter().copied());
            (pts, segs, false, [back.boundary, fwd.boundary])
        };
        let (mut pts, segs) = (pts, segs);
        if closed {
            // The last point is the seed again: the closing segment ends the loop.
            pts.pop();
        }
        let length: f64 = pts.windows(2).map(|w| w[0].p.distance(w[1].p)).sum();
        if pts.len() < 2 || segs.len() + usize::from(!closed) != pts.len() || length < 2.0 * self.separation {
            // Too short: left out (its segments no longer count), its id reused.
            self.grid.remove(id);
            return None;
        }
        Some(Line { pts, faces: segs, closed, ends })
    }

    /// Traces curve `line` one way from point `p0` in face `fi0` along (about) `d0`, face by
    /// face, adding its segments to the grid at arc positions times `sign` (+1 forward, −1
    /// backward, for the self test). Stops at the boundary, alongside another curve (or an
    /// earlier stretch of this one), back at the seed `p0` (closed), or after the maximum
    /// length.
    fn trace_one(&mut self, line: usize, fi0: usize, p0: DVec3, d0: DVec3, sign: f64) -> Half {
        let (mesh, field, separation) = (self.mesh, self.field, self.separation);
        let seed = p0;
        let mut out = Half { pts: Vec::new(), faces: Vec::new(), boundary: None, closed: false };
        let (mut fi, mut p, mut d, mut entry): (usize, DVec3, DVec3, Option<usize>) = (fi0, p0, d0, None);
        let mut len = 0.0;
        for _ in 0..200_000 {
            if !field.good[fi] {
                break;
            }
            let fr = field.frames[fi];
            let dir = field.dir(fi, d - fr.n * d.dot(fr.n));
            if dir == DVec3::ZERO {
                break;
            }
            // Exit through the first edge the ray meets (not the entry edge).
            let q: [DVec2; 3] = mesh.faces[fi].map(|v| fr.to2(mesh.positions[v as usize]));
            let Some((_, k, s)) = exit_edge(fr.to2(p), fr.dir2(dir), q, entry) else { break };
            let f = mesh.faces[fi];
            let (va, vb) = (f[k], f[(k + 1) % 3]);
            let qp = mesh.positions[va as usize].lerp(mesh.positions[vb as usize], s);
            if out.pts.is_empty() {
                out.pts.push(Pt { p, n: face_normal(mesh, fi, p) });
            }
            // Back at the seed: the curve closes.
            let seg_len = p.distance(qp);
            if len > 2.0 * separation {
                let e = qp - p;
                let t = ((seed - p).dot(e) / e.length_squared().max(f64::MIN_POSITIVE)).clamp(0.0, 1.0);
                if (p + t * e).distance(seed) <= 0.3 * self.spacing && e.normalize_or_zero().dot(d0) > 0.5 {
                    out.faces.push(fi);
                    out.pts.push(Pt { p: seed, n: face_normal(mesh, fi0, seed) });
                    out.closed = true;
                    break;
                }
            }
            // Alongside another curve (or an earlier stretch of this one): stop here.
            let cur = sign * len;
            let skip = Some((line, cur - 2.0 * separation, cur + 2.0 * separation));
            if self.grid.alongside(qp, dir, self.stop_r, self.cos_par, skip) && len > 0.25 * separation {
                out.faces.push(fi);
                out.pts.push(Pt { p: qp, n: edge_normal(mesh, va, vb, qp) });
                break;
            }
            out.faces.push(fi);
            out.pts.push(Pt { p: qp, n: edge_normal(mesh, va, vb, qp) });
            self.grid.add(line, p, qp, sign * (len + 0.5 * seg_len));
            len += seg_len;
            if len > self.max_len {
                break;
            }
            let key = edge_key(va, vb);
            let Some(g) = mesh.across(fi, k) else {
                if mesh.is_boundary(key) {
                    out.boundary = Some(key);
                }
                break;
            };
            entry = (0..3).find(|&j| edge_key(mesh.faces[g][j], mesh.faces[g][(j + 1) % 3]) == key);
            fi = g;
            p = qp;
            d = dir;
        }
        out
    }
}

/// Where the ray from `x` along `u` leaves the triangle `q` (2D): the first edge it meets
/// other than local edge `entry` (edge `k` runs from `q[k]` to `q[k + 1]`), as (ray
/// parameter, `k`, parameter along the edge kept 1e-7 away from its ends); `None` if it meets
/// none.
fn exit_edge(x: DVec2, u: DVec2, q: [DVec2; 3], entry: Option<usize>) -> Option<(f64, usize, f64)> {
    let mut exit: Option<(f64, usize, f64)> = None;
    for k in 0..3 {
        if Some(k) == entry {
            continue;
        }
        let (a, b) = (q[k], q[(k + 1) % 3]);
        let e = b - a;
        let den = u.perp_dot(e);
        if den.abs() < 1e-300 {
            continue;
        }
        let t = (a - x).perp_dot(e) / den;
        let s = (a - x).perp_dot(u) / den;
        if t > 1e-12 && (-1e-9..=1.0 + 1e-9).contains(&s) && exit.is_none_or(|ex| t < ex.0) {
            exit = Some((t, k, s.clamp(1e-7, 1.0 - 1e-7)));
        }
    }
    exit
}

/// The vertex normals of edge `a`–`b` interpolated linearly at `p` (projected on the edge).
fn edge_normal(mesh: &Mesh, a: u32, b: u32, p: DVec3) -> DVec3 {
    let (pa, pb) = (mesh.positions[a as usize], mesh.positions[b as usize]);
    let t = ((p - pa).dot(pb - pa) / (pb - pa).length_squared().max(f64::MIN_POSITIVE)).clamp(0.0, 1.0);
    mesh.normals[a as usize].lerp(mesh.normals[b as usize], t)
}

/// The vertex normals of face `fi` interpolated barycentrically at `p`.
fn face_normal(mesh: &Mesh, fi: usize, p: DVec3) -> DVec3 {
    let [a, b, c] = mesh.faces[fi].map(|v| mesh.positions[v as usize]);
    let area = (b - a).cross(c - a);
    let a2 = area.length_squared().max(f64::MIN_POSITIVE);
    let w0 = (b - p).cross(c - p).dot(area) / a2;
    let w1 = (c - p).cross(a - p).dot(area) / a2;
    let [n0, n1, n2] = mesh.faces[fi].map(|v| mesh.normals[v as usize]);
    w0 * n0 + w1 * n1 + (1.0 - w0 - w1) * n2
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
