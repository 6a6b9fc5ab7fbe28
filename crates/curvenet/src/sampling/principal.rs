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
//! Reference: S. Rusinkiewicz, *Estimating curvatures and their derivatives on triangle
//! meshes*, 3DPVT 2004 (per-face fit of the second fundamental form).

use super::crossings::{close_crossings, near_misses};
use super::mesh::{edge_key, Mesh};
use super::planes::{section_directions, MIN_CROSSING_ANGLE_DEG};
use super::sections::FaceCut;
use super::{Raw, SampleOptions, Scales, Traced, Traces, PRINCIPAL_SEPARATION};
use crate::geom::{DVec2, DVec3};
use std::collections::HashMap;

/// Smoothing sweeps of the cross field.
const SMOOTHING_SWEEPS: usize = 150;
/// Weight of the projected axis in the field (relative to a fully anisotropic face).
const AXIS_WEIGHT: f64 = 0.1;
/// A curve stops when it comes within this fraction of the separation of another curve
/// running alongside (within [`PARALLEL_DEG`]).
const STOP_FRACTION: f64 = 0.3;
/// Directions closer than this (degrees) count as alongside.
const PARALLEL_DEG: f64 = 35.0;

/// What [`trace`] produced: the curves (crossings as node samples), the curve ends on boundary
/// edges, the bad spots (curve index, place), and the number of crossings.
struct Principal {
    pub traced: Vec<Traced>,
    pub ends_on_boundary: HashMap<(u32, u32), Vec<Raw>>,
    pub spots: Vec<(usize, DVec3)>,
    pub crossings: usize,
}

/// An orthonormal frame of a face: `e1` along its first edge, `n` its unit normal.
#[derive(Clone, Copy)]
struct Frame {
    o: DVec3,
    e1: DVec3,
    e2: DVec3,
    n: DVec3,
}

impl Frame {
    fn to2(&self, p: DVec3) -> DVec2 {
        DVec2::new((p - self.o).dot(self.e1), (p - self.o).dot(self.e2))
    }
    fn to3(&self, q: DVec2) -> DVec3 {
        self.o + q.x * self.e1 + q.y * self.e2
    }
    fn dir2(&self, d: DVec3) -> DVec2 {
        DVec2::new(d.dot(self.e1), d.dot(self.e2))
    }
}

/// A point of a traced curve: on an edge (`edge`, with the vertex normals interpolated) or
/// inside face (`edge` none: the seed, normal from the face).
#[derive(Clone, Copy)]
struct Pt {
    p: DVec3,
    n: DVec3,
}

/// A traced curve: points, the face of each segment (`faces[k]` holds `pts[k]..pts[k+1]`).
struct Line {
    pts: Vec<Pt>,
    faces: Vec<usize>,
    closed: bool,
    /// Boundary edges the curve ends on (first end, last end).
    ends: [Option<(u32, u32)>; 2],
}

/// Segments of the traced curves in a uniform grid (for the stop and seed tests).
struct SegGrid {
    h: f64,
    cells: HashMap<(i64, i64, i64), Vec<(usize, DVec3, DVec3, f64)>>,
}

impl SegGrid {
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
}

/// The principal curves of the mesh, [`PRINCIPAL_SEPARATION`] × the box's mean extent over
/// the mean of the non-zero `opts.planes` counts apart, the field oriented by the third
/// section direction ([`section_directions`] of `opts.tilt`) where the surface is isotropic.
pub(super) fn trace_principal(mesh: &Mesh, opts: &SampleOptions, scales: &Scales) -> Traces {
    // Curves along the principal directions, `separation` apart.
    let ext = scales.bbox.max - scales.bbox.min;
    let counts: Vec<f64> = opts.planes.iter().filter(|&&k| k > 0).map(|&k| k as f64).collect();
    let mean_count = counts.iter().sum::<f64>() / counts.len().max(1) as f64;
    let separation = PRINCIPAL_SEPARATION * (ext.x + ext.y + ext.z) / 3.0 / mean_count.max(1.0);
    let axis = section_directions(opts.tilt)[2];
    let r = trace(
        &mesh.positions,
        &mesh.faces,
        &mesh.normals,
        &mesh.edge_faces,
        axis,
        separation,
        scales.spacing,
        scales.near,
        scales.gap,
        scales.diag,
    );
    let mut bad: Vec<usize> = r.spots.iter().map(|x| x.0).collect();
    bad.sort_unstable();
    bad.dedup();
    Traces {
        traced: r.traced,
        ends_on_boundary: r.ends_on_boundary,
        unresolved: bad.len(),
        spots: r.spots,
        crossings: r.crossings,
        trimmed: 0,
    }
}

/// Traces curves along the principal directions on the mesh (see the module documentation),
/// `separation` apart. `normals`: unit vertex normals; `axis`: the direction whose projection
/// orients the field where the surface is isotropic; `spacing`, `near`, `gap`: as in
/// [`super::sample_mesh`] (sample spacing, near-miss distance, smallest distance between
/// crossings).
#[allow(clippy::too_many_arguments)]
fn trace(
    positions: &[DVec3],
    faces: &[[u32; 3]],
    normals: &[DVec3],
    edge_faces: &HashMap<(u32, u32), Vec<usize>>,
    axis: DVec3,
    separation: f64,
    spacing: f64,
    near: f64,
    gap: f64,
    diag: f64,
) -> Principal {
    let nf = faces.len();
    let frames: Vec<Frame> = faces
        .iter()
        .map(|f| {
            let [a, b, c] = f.map(|v| positions[v as usize]);
            let n = (b - a).cross(c - a).normalize_or_zero();
            let e1 = (b - a).normalize_or_zero();
            Frame { o: a, e1, e2: n.cross(e1), n }
        })
        .collect();
    let good: Vec<bool> = frames.iter().map(|f| f.n != DVec3::ZERO && f.e1 != DVec3::ZERO).collect();
    // Neighbour across local edge k (f[k] → f[k+1]).
    let neighbour = |fi: usize, k: usize| -> Option<usize> {
        let f = faces[fi];
        let e = edge_key(f[k], f[(k + 1) % 3]);
        edge_faces.get(&e).and_then(|l| (l.len() == 2).then(|| if l[0] == fi { l[1] } else { l[0] }))
    };

    // Cross field: per face a unit complex number z = exp(4iθ), θ the angle of one of the four
    // directions in the face's frame.
    let kappa0 = 1.0 / diag;
    let mut prior = vec![DVec2::ZERO; nf];
    for (fi, f) in faces.iter().enumerate() {
        if !good[fi] {
            continue;
        }
        let fr = frames[fi];
        // Second fundamental form [[a, b], [b, c]] from the three edges.
        let (mut ata, mut atb) = (glam::DMat3::ZERO, glam::DVec3::ZERO);
        for k in 0..3 {
            let (i, j) = (f[k] as usize, f[(k + 1) % 3] as usize);
            let e = fr.dir2(positions[j] - positions[i]);
            let dn = fr.dir2(normals[j] - normals[i]);
            for (row, rhs) in [(DVec3::new(e.x, e.y, 0.0), dn.x), (DVec3::new(0.0, e.x, e.y), dn.y)] {
                ata += glam::DMat3::from_cols(row * row.x, row * row.y, row * row.z);
                atb += row * rhs;
            }
        }
        let abc = if ata.determinant().abs() > 1e-30 { ata.inverse() * atb } else { DVec3::ZERO };
        let (a, b, c) = (abc.x, abc.y, abc.z);
        let aniso = ((a - c).powi(2) + 4.0 * b * b).sqrt();
        let trace_abs = {
            let m = 0.5 * (a + c);
            (m + 0.5 * aniso).abs() + (m - 0.5 * aniso).abs()
        };
        let w = aniso / (trace_abs + kappa0);
        let theta = 0.5 * (2.0 * b).atan2(a - c);
        let mut z = w * DVec2::from_angle(4.0 * theta);
        let g = fr.dir2(axis);
        if g.length() > 1e-6 {
            z += AXIS_WEIGHT * g.length() * DVec2::from_angle(4.0 * g.y.atan2(g.x));
        }
        prior[fi] = z;
    }
    // Rotation (as a unit complex number, times 4) from face g's frame to face f's across
    // their shared edge: the angle measured from the edge is the same in both.
    let edge_angle = |fi: usize, a: u32, b: u32| -> f64 {
        let d = frames[fi].dir2(positions[b as usize] - positions[a as usize]);
        d.y.atan2(d.x)
    };
    let mut adj: Vec<Vec<(usize, DVec2)>> = vec![Vec::new(); nf];
    for (fi, f) in faces.iter().enumerate() {
        for k in 0..3 {
            if let Some(g) = neighbour(fi, k) {
                if good[fi] && good[g] {
                    let (a, b) = (f[k], f[(k + 1) % 3]);
                    let rot = 4.0 * (edge_angle(fi, a, b) - edge_angle(g, a, b));
                    adj[fi].push((g, DVec2::from_angle(rot)));
                }
            }
        }
    }
    let mut z: Vec<DVec2> = prior.iter().map(|p| p.normalize_or_zero()).collect();
    for _ in 0..SMOOTHING_SWEEPS {
        for fi in 0..nf {
            let mut s = prior[fi];
            for &(g, r) in &adj[fi] {
                s += r.rotate(z[g]);
            }
            if s.length() > 1e-12 {
                z[fi] = s.normalize();
            }
        }
    }
    // The field direction of face `fi` closest to `d` (3D, tangent).
    let field_dir = |fi: usize, d: DVec3| -> DVec3 {
        let fr = frames[fi];
        let theta = z[fi].y.atan2(z[fi].x) / 4.0;
        let d2 = fr.dir2(d);
        let mut best = (f64::NEG_INFINITY, DVec3::ZERO);
        for k in 0..4 {
            let u = DVec2::from_angle(theta + k as f64 * std::f64::consts::FRAC_PI_2);
            let s = u.dot(d2);
            if s > best.0 {
                best = (s, fr.e1 * u.x + fr.e2 * u.y);
            }
        }
        best.1
    };
    let edge_normal = |a: u32, b: u32, p: DVec3| -> DVec3 {
        let (pa, pb) = (positions[a as usize], positions[b as usize]);
        let t = ((p - pa).dot(pb - pa) / (pb - pa).length_squared().max(f64::MIN_POSITIVE)).clamp(0.0, 1.0);
        normals[a as usize].lerp(normals[b as usize], t)
    };
    let face_normal = |fi: usize, p: DVec3| -> DVec3 {
        let [a, b, c] = faces[fi].map(|v| positions[v as usize]);
        let area = (b - a).cross(c - a);
        let a2 = area.length_squared().max(f64::MIN_POSITIVE);
        let w0 = (b - p).cross(c - p).dot(area) / a2;
        let w1 = (c - p).cross(a - p).dot(area) / a2;
        let [n0, n1, n2] = faces[fi].map(|v| normals[v as usize]);
        w0 * n0 + w1 * n1 + (1.0 - w0 - w1) * n2
    };

    // Tracing. One way from point `p` in face `fi` along (about) `d`; `skip_edge`: the local
    // edge it entered by. Stops at the boundary, alongside another curve, back at `seed`
    // (closed), or after `max_len`.
    let stop_r = STOP_FRACTION * separation;
    let cos_par = PARALLEL_DEG.to_radians().cos();
    let max_len = 3.0 * diag;
    let mut grid = SegGrid { h: separation.max(f64::MIN_POSITIVE), cells: HashMap::new() };
    struct Half {
        pts: Vec<Pt>,
        faces: Vec<usize>,
        boundary: Option<(u32, u32)>,
        closed: bool,
    }
    // `sign`: +1 forward, −1 backward (arc positions from the seed, for the self test).
    let trace_one =
        |grid: &mut SegGrid, line: usize, fi0: usize, p0: DVec3, d0: DVec3, seed: DVec3, sign: f64| -> Half {
            let mut out = Half { pts: Vec::new(), faces: Vec::new(), boundary: None, closed: false };
            let (mut fi, mut p, mut d, mut entry): (usize, DVec3, DVec3, Option<usize>) = (fi0, p0, d0, None);
            let mut len = 0.0;
            for _ in 0..200_000 {
                if !good[fi] {
                    break;
                }
                let fr = frames[fi];
                let dir = field_dir(fi, d - fr.n * d.dot(fr.n));
                if dir == DVec3::ZERO {
                    break;
                }
                // Exit through the first edge the ray meets (not the entry edge).
                let x = fr.to2(p);
                let u = fr.dir2(dir);
                let q: [DVec2; 3] = faces[fi].map(|v| fr.to2(positions[v as usize]));
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
                let Some((_, k, s)) = exit else { break };
                let f = faces[fi];
                let (va, vb) = (f[k], f[(k + 1) % 3]);
                let qp = positions[va as usize].lerp(positions[vb as usize], s);
                if out.pts.is_empty() {
                    out.pts.push(Pt { p, n: face_normal(fi, p) });
                }
                // Back at the seed: the curve closes.
                let seg_len = p.distance(qp);
                if len > 2.0 * separation {
                    let e = qp - p;
                    let t = ((seed - p).dot(e) / e.length_squared().max(f64::MIN_POSITIVE)).clamp(0.0, 1.0);
                    if (p + t * e).distance(seed) <= 0.3 * spacing && e.normalize_or_zero().dot(d0) > 0.5 {
                        out.faces.push(fi);
                        out.pts.push(Pt { p: seed, n: face_normal(fi0, seed) });
                        out.closed = true;
                        break;
                    }
                }
                // Alongside another curve (or an earlier stretch of this one): stop here.
                let cur = sign * len;
                if grid.alongside(
                    qp,
                    dir,
                    stop_r,
                    cos_par,
                    Some((line, cur - 2.0 * separation, cur + 2.0 * separation)),
                ) && len > 0.25 * separation
                {
                    out.faces.push(fi);
                    out.pts.push(Pt { p: qp, n: edge_normal(va, vb, qp) });
                    break;
                }
                out.faces.push(fi);
                out.pts.push(Pt { p: qp, n: edge_normal(va, vb, qp) });
                grid.add(line, p, qp, sign * (len + 0.5 * seg_len));
                len += seg_len;
                if len > max_len {
                    break;
                }
                let key = edge_key(va, vb);
                let Some(g) = neighbour(fi, k) else {
                    if edge_faces.get(&key).is_some_and(|l| l.len() == 1) {
                        out.boundary = Some(key);
                    }
                    break;
                };
                entry = (0..3).find(|&j| edge_key(faces[g][j], faces[g][(j + 1) % 3]) == key);
                fi = g;
                p = qp;
                d = dir;
            }
            out
        };

    // Seeds: face centroids in a fixed pseudo-random order.
    let mut order: Vec<usize> = (0..nf).filter(|&f| good[f]).collect();
    let mut rng = crate::network::Rng::new(0x9121_1C1A);
    for i in (1..order.len()).rev() {
        let j = (rng.next_u64() % (i as u64 + 1)) as usize;
        order.swap(i, j);
    }
    let cos_seed = 40f64.to_radians().cos();
    let mut lines: Vec<Line> = Vec::new();
    for &fi in &order {
        let fr = frames[fi];
        let c = faces[fi].map(|v| positions[v as usize]).iter().sum::<DVec3>() / 3.0;
        for base in [fr.e1, fr.e2] {
            let u = field_dir(fi, base);
            if u == DVec3::ZERO || grid.alongside(c, u, 0.9 * separation, cos_seed, None) {
                continue;
            }
            let id = lines.len();
            let fwd = trace_one(&mut grid, id, fi, c, u, c, 1.0);
            let (pts, segs, closed, ends) = if fwd.closed {
                (fwd.pts, fwd.faces, true, [None, None])
            } else {
                let back = trace_one(&mut grid, id, fi, c, -u, c, -1.0);
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
            if pts.len() < 2 || segs.len() + usize::from(!closed) != pts.len() || length < 2.0 * separation {
                // Too short: left out (its segments no longer count), its id reused.
                grid.cells.values_mut().for_each(|l| l.retain(|x| x.0 != id));
                continue;
            }
            lines.push(Line { pts, faces: segs, closed, ends });
        }
    }

    // Crossings: two segments in the same face, in its plane.
    let mut in_face: HashMap<usize, Vec<(usize, usize)>> = HashMap::new();
    for (li, l) in lines.iter().enumerate() {
        for (k, &f) in l.faces.iter().enumerate() {
            in_face.entry(f).or_default().push((li, k));
        }
    }
    let seg_ends = |li: usize, k: usize| {
        let l = &lines[li];
        (l.pts[k].p, l.pts[(k + 1) % l.pts.len()].p)
    };
    let mut inserts: Vec<Vec<(usize, f64, Raw)>> = vec![Vec::new(); lines.len()];
    let mut crossing_points: HashMap<(usize, usize), Vec<DVec3>> = HashMap::new();
    let mut spots: Vec<(usize, DVec3)> = Vec::new();
    let mut crossings = 0;
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
                let (a0, a1) = seg_ends(la, ka);
                let (b0, b1) = seg_ends(lb, kb);
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
                let x = fr.to3(p + t * u);
                let raw = Raw { p: x, n: face_normal(f, x), node: true };
                inserts[la].push((ka, t, raw));
                inserts[lb].push((kb, w, raw));
                crossings += 1;
                crossing_points.entry((la.min(lb), la.max(lb))).or_default().push(x);
                if u.normalize().dot(v.normalize()).abs() > cos_min {
                    spots.push((la.max(lb), x));
                }
            }
        }
    }
    // The curves as traced polylines with their crossings; the mesh boundary as a pseudo
    // curve (index `lines.len()`) for the near-miss and close-crossing tests.
    let boundary_id = lines.len();
    let mut ends_on_boundary: HashMap<(u32, u32), Vec<Raw>> = HashMap::new();
    let mut cuts: Vec<FaceCut> = Vec::new();
    let mut traced = Vec::new();
    for (li, l) in lines.iter().enumerate() {
        let mut ins = std::mem::take(&mut inserts[li]);
        ins.sort_by(|a, b| a.0.cmp(&b.0).then(a.1.total_cmp(&b.1)));
        let mut samples = Vec::with_capacity(l.pts.len() + ins.len());
        let mut it = ins.into_iter().peekable();
        for (k, pt) in l.pts.iter().enumerate() {
            samples.push(Raw { p: pt.p, n: pt.n, node: false });
            while let Some(x) = it.next_if(|x| x.0 == k) {
                samples.push(x.2);
            }
        }
        for (k, &f) in l.faces.iter().enumerate() {
            let (a, b) = seg_ends(li, k);
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
                crossing_points.entry((li, boundary_id)).or_default().push(r.p);
                // Ends on the boundary at a shallow angle.
                let (pa, pb) = (positions[e.0 as usize], positions[e.1 as usize]);
                let k = if side == 0 { 0 } else { l.faces.len() - 1 };
                let (s0, s1) = seg_ends(li, k);
                let d = s1 - s0;
                if d.dot(pb - pa).abs() / (d.length() * pa.distance(pb)).max(f64::MIN_POSITIVE) > cos_min {
                    spots.push((li, r.p));
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
    for (e, fs) in edge_faces {
        if fs.len() == 1 {
            let ends = [positions[e.0 as usize], positions[e.1 as usize]];
            cuts.push(FaceCut { plane: boundary_id, edges: [*e, *e], ends });
        }
    }
    spots.extend(near_misses(&cuts, &crossing_points, near, boundary_id));
    spots.extend(close_crossings(&crossing_points, gap, gap, boundary_id));
    spots.retain(|s| s.0 < boundary_id);
    Principal { traced, ends_on_boundary, spots, crossings }
}
