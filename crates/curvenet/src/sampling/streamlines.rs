//! The streamlines of the principal curves ([`super::principal`]): traced on the mesh face
//! by face along the cross field ([`super::cross_field`]), from seeds at the face centroids in
//! a fixed pseudo-random order, both ways, until they reach the mesh boundary, close up, or
//! come alongside another curve ([`Tracer`]). A seed starts a curve in each of its two
//! directions that no curve already covers within the separation; curves shorter than two
//! separations are left out.

use super::cross_field::CrossField;
use super::mesh::{edge_key, Mesh};
use super::Scales;
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
pub(super) struct Pt {
    /// Position.
    pub(super) p: DVec3,
    /// Normal (not normalised).
    pub(super) n: DVec3,
}

/// A traced curve: points, the face of each segment (`faces[k]` holds `pts[k]..pts[k+1]`).
pub(super) struct Line {
    /// The points (a closed curve does not repeat its first one).
    pub(super) pts: Vec<Pt>,
    /// The face of each segment.
    pub(super) faces: Vec<usize>,
    /// A closed loop (its last segment back to the first point).
    pub(super) closed: bool,
    /// Boundary edges the curve ends on (first end, last end).
    pub(super) ends: [Option<(u32, u32)>; 2],
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

/// Traces the streamlines of a cross field on a mesh, keeping them apart.
pub(super) struct Tracer<'a> {
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
    pub(super) fn new(mesh: &'a Mesh, field: &'a CrossField, separation: f64, scales: &Scales) -> Tracer<'a> {
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
    pub(super) fn seed_lines(mut self) -> Vec<Line> {
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
pub(super) fn face_normal(mesh: &Mesh, fi: usize, p: DVec3) -> DVec3 {
    let [a, b, c] = mesh.faces[fi].map(|v| mesh.positions[v as usize]);
    let area = (b - a).cross(c - a);
    let a2 = area.length_squared().max(f64::MIN_POSITIVE);
    let w0 = (b - p).cross(c - p).dot(area) / a2;
    let w1 = (c - p).cross(a - p).dot(area) / a2;
    let [n0, n1, n2] = mesh.faces[fi].map(|v| mesh.normals[v as usize]);
    w0 * n0 + w1 * n1 + (1.0 - w0 - w1) * n2
}

#[cfg(test)]
#[path = "tests/streamlines.rs"]
mod tests;
