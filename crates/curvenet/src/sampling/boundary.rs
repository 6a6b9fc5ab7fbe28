//! The mesh's boundary loops, and section ends trimmed along the boundary.

use super::{edge_key, Raw, Traced};
use crate::geom::DVec3;
use std::collections::HashMap;

/// The boundary loops of the mesh as boundary curves: mesh vertices along the loop with the
/// section end points on its edges inserted as nodes.
pub(super) fn trace_boundary(
    positions: &[DVec3],
    faces: &[[u32; 3]],
    normals: &[DVec3],
    edge_faces: &HashMap<(u32, u32), Vec<usize>>,
    ends_on_boundary: &HashMap<(u32, u32), Vec<Raw>>,
    crossings: &mut usize,
) -> Vec<Traced> {
    // Directed boundary edges as their face has them (the surface on their left).
    let mut next_of: HashMap<u32, Vec<u32>> = HashMap::new();
    for f in faces {
        for k in 0..3 {
            let (a, b) = (f[k], f[(k + 1) % 3]);
            if a != b && edge_faces.get(&edge_key(a, b)).is_some_and(|fs| fs.len() == 1) {
                next_of.entry(a).or_default().push(b);
            }
        }
    }
    let mut starts: Vec<u32> = next_of.keys().copied().collect();
    starts.sort_unstable();
    let mut loops = Vec::new();
    for s in starts {
        while next_of.get(&s).is_some_and(|v| !v.is_empty()) {
            let mut verts = vec![s];
            let mut v = s;
            loop {
                let Some(list) = next_of.get_mut(&v) else { break };
                let Some(w) = list.pop() else { break };
                if w == s {
                    break;
                }
                verts.push(w);
                v = w;
            }
            if verts.len() < 3 {
                continue;
            }
            let m = verts.len();
            let mut samples = Vec::new();
            for k in 0..m {
                let (a, b) = (verts[k], verts[(k + 1) % m]);
                samples.push(Raw { p: positions[a as usize], n: normals[a as usize], node: false });
                if let Some(list) = ends_on_boundary.get(&edge_key(a, b)) {
                    let (pa, pb) = (positions[a as usize], positions[b as usize]);
                    let d = pb - pa;
                    let mut xs: Vec<(f64, Raw)> = list
                        .iter()
                        .map(|r| ((r.p - pa).dot(d) / d.length_squared().max(f64::MIN_POSITIVE), *r))
                        .collect();
                    xs.sort_by(|x, y| x.0.total_cmp(&y.0));
                    for (_, mut r) in xs {
                        r.node = true;
                        *crossings += 1;
                        samples.push(r);
                    }
                }
            }
            let name = format!("boundary #{}", loops.len());
            loops.push(Traced { plane: None, samples, closed: true, boundary: true, name, cut: false });
        }
    }
    loops
}

/// The mesh's boundary edges in a uniform grid of cell size `h`.
pub(super) struct BoundaryGrid {
    h: f64,
    cells: HashMap<(i64, i64, i64), Vec<(u32, u32)>>,
}

impl BoundaryGrid {
    pub(super) fn new(positions: &[DVec3], edge_faces: &HashMap<(u32, u32), Vec<usize>>, h: f64) -> Self {
        let h = h.max(f64::MIN_POSITIVE);
        let mut cells: HashMap<(i64, i64, i64), Vec<(u32, u32)>> = HashMap::new();
        let cell = |p: DVec3| ((p.x / h).floor() as i64, (p.y / h).floor() as i64, (p.z / h).floor() as i64);
        for (e, fs) in edge_faces {
            if fs.len() != 1 {
                continue;
            }
            let (a, b) = (positions[e.0 as usize], positions[e.1 as usize]);
            let (lo, hi) = (cell(a.min(b)), cell(a.max(b)));
            if (hi.0 - lo.0 + 1) * (hi.1 - lo.1 + 1) * (hi.2 - lo.2 + 1) > 4096 {
                continue;
            }
            for x in lo.0..=hi.0 {
                for y in lo.1..=hi.1 {
                    for z in lo.2..=hi.2 {
                        cells.entry((x, y, z)).or_default().push(*e);
                    }
                }
            }
        }
        BoundaryGrid { h, cells }
    }

    /// The closest boundary edge point within the grid's cell size of `p`: (distance, edge, t).
    pub(super) fn closest(&self, positions: &[DVec3], p: DVec3) -> Option<(f64, (u32, u32), f64)> {
        let h = self.h;
        let c = ((p.x / h).floor() as i64, (p.y / h).floor() as i64, (p.z / h).floor() as i64);
        let mut best: Option<(f64, (u32, u32), f64)> = None;
        for dx in -1..=1 {
            for dy in -1..=1 {
                for dz in -1..=1 {
                    for e in self.cells.get(&(c.0 + dx, c.1 + dy, c.2 + dz)).map_or(&[][..], |v| &v[..]) {
                        let (a, b) = (positions[e.0 as usize], positions[e.1 as usize]);
                        let d = b - a;
                        let t = ((p - a).dot(d) / d.length_squared().max(f64::MIN_POSITIVE)).clamp(0.0, 1.0);
                        let dist = p.distance(a + t * d);
                        if dist <= h && best.is_none_or(|x| dist < x.0) {
                            best = Some((dist, *e, t));
                        }
                    }
                }
            }
        }
        best
    }
}

/// A section that ends on the mesh boundary but runs along it first (closer than `band` to
/// it) would be snapped onto the boundary curve over that stretch by the pipeline: its first
/// samples within the band are removed and the section ends instead at the boundary point
/// closest to its first sample outside the band (a short link across to the boundary), if
/// that point is on the same boundary loop (`on_same_loop`).
/// Returns the boundary edge of the new end, or `None` when nothing was cut.
pub(super) fn trim_along(
    samples: &mut Vec<Raw>,
    grid: &BoundaryGrid,
    band: f64,
    positions: &[DVec3],
    normals: &[DVec3],
    on_same_loop: &dyn Fn((u32, u32)) -> bool,
) -> Option<(u32, u32)> {
    // The end point itself is on the boundary; look at the following samples.
    let mut k = 1;
    while k < samples.len() && grid.closest(positions, samples[k].p).is_some_and(|c| c.0 < band) {
        k += 1;
    }
    // Leaves the band within 2.5 band widths of arc: a fair crossing (≥ 24°), keep it.
    let arc: f64 = (1..k.min(samples.len())).map(|i| samples[i].p.distance(samples[i - 1].p)).sum();
    if arc <= 2.5 * band || k >= samples.len() {
        if k >= samples.len() {
            samples.clear();
        }
        return None;
    }
    let (_, e, t) = grid.closest(positions, samples[k - 1].p)?;
    // Across to another boundary loop would span a hole: keep the section as it is.
    if !on_same_loop(e) {
        return None;
    }
    let (a, b) = (positions[e.0 as usize], positions[e.1 as usize]);
    let n = normals[e.0 as usize].lerp(normals[e.1 as usize], t);
    let end = Raw { p: a.lerp(b, t), n, node: false };
    samples.drain(0..k - 1);
    samples[0] = end;
    Some(e)
}
