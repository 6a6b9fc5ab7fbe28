//! Self-intersections of a triangle mesh: the check that a surface written as a success does
//! not pass through itself (two cones through each other, a fold, a patch through its
//! neighbour; issue 29). Triangles are binned on a uniform grid of twice the median edge
//! length; each pair of triangles in a cell that share no vertex and whose boxes overlap is
//! tested by its six edges against the other triangle (Möller–Trumbore), the pairs found in
//! several cells counted once. Coplanar overlaps are not counted.

use super::DVec3;
use rayon::prelude::*;

/// What [`self_intersections`] found.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct SelfIntersections {
    /// Pairs of triangles (sharing no vertex) that cross.
    pub pairs: usize,
    /// The first crossing pair (by face index) and a point where they cross.
    pub first: Option<(u32, u32, DVec3)>,
}

/// The edge `a`→`b` crosses triangle `t` strictly inside both (with a relative margin, so that
/// touching is no crossing): the crossing point.
fn edge_crosses(a: DVec3, b: DVec3, t: [DVec3; 3]) -> Option<DVec3> {
    const EPS: f64 = 1e-9;
    let d = b - a;
    let (e1, e2) = (t[1] - t[0], t[2] - t[0]);
    let p = d.cross(e2);
    let det = e1.dot(p);
    let scale = e1.length() * e2.length() * d.length();
    if det.abs() <= 1e-12 * scale {
        return None; // parallel or coplanar
    }
    let inv = 1.0 / det;
    let s = a - t[0];
    let u = s.dot(p) * inv;
    if u <= EPS || u >= 1.0 - EPS {
        return None;
    }
    let q = s.cross(e1);
    let v = d.dot(q) * inv;
    if v <= EPS || u + v >= 1.0 - EPS {
        return None;
    }
    let w = e2.dot(q) * inv;
    if w <= EPS || w >= 1.0 - EPS {
        return None;
    }
    Some(a + w * d)
}

/// Whether triangles `x` and `y` cross: a point where they do.
fn triangles_cross(x: [DVec3; 3], y: [DVec3; 3]) -> Option<DVec3> {
    (0..3)
        .find_map(|k| edge_crosses(x[k], x[(k + 1) % 3], y))
        .or_else(|| (0..3).find_map(|k| edge_crosses(y[k], y[(k + 1) % 3], x)))
}

/// The pairs of triangles of `faces` at `positions` that share no vertex and cross.
pub fn self_intersections(positions: &[DVec3], faces: &[[u32; 3]]) -> SelfIntersections {
    if faces.len() < 2 {
        return SelfIntersections::default();
    }
    let corner = |f: usize, k: usize| positions[faces[f][k] as usize];
    let mut lengths: Vec<f64> = (0..faces.len()).map(|f| corner(f, 0).distance(corner(f, 1))).collect();
    let mid = lengths.len() / 2;
    let cell = 2.0 * *lengths.select_nth_unstable_by(mid, f64::total_cmp).1;
    drop(lengths);
    if !(cell > 0.0 && cell.is_finite()) {
        return SelfIntersections::default();
    }
    let boxes: Vec<(DVec3, DVec3)> = (0..faces.len())
        .map(|f| {
            let (a, b, c) = (corner(f, 0), corner(f, 1), corner(f, 2));
            (a.min(b).min(c), a.max(b).max(c))
        })
        .collect();
    let origin = boxes.iter().fold(DVec3::splat(f64::INFINITY), |m, b| m.min(b.0));
    let extent = boxes.iter().fold(DVec3::splat(f64::NEG_INFINITY), |m, b| m.max(b.1)) - origin;
    // Cells packed in one 64-bit key, 21 bits per axis (sorting 16-byte entries instead of
    // 32-byte ones: 97k entries in 3 ms instead of 7–10 ms, a 20k-vertex sphere). A mesh wider
    // than 2²¹ cells (tiny triangles along a curve of 5·10⁵ samples) takes larger cells so
    // that it fits, rather than piling its far triangles into one cell.
    const LAST: i64 = (1 << 21) - 1;
    let cell = cell.max(extent.max_element() / (LAST - 1) as f64);
    let index = |p: DVec3| {
        let q = ((p - origin) / cell).floor();
        [q.x as i64, q.y as i64, q.z as i64].map(|c| c.clamp(0, LAST))
    };
    let key = |i: i64, j: i64, k: i64| ((i as u64) << 42) | ((j as u64) << 21) | k as u64;
    // (cell, face) for every cell a face's box touches; a face larger than 64 cells (a sliver
    // across the mesh) is binned by its box's corner cells only, which may miss its crossings.
    let mut binned: Vec<(u64, u32)> = Vec::with_capacity(faces.len() * 4);
    for (f, b) in boxes.iter().enumerate() {
        let (lo, hi) = (index(b.0), index(b.1));
        let count = (hi[0] - lo[0] + 1) * (hi[1] - lo[1] + 1) * (hi[2] - lo[2] + 1);
        if count > 64 {
            binned.push((key(lo[0], lo[1], lo[2]), f as u32));
            binned.push((key(hi[0], hi[1], hi[2]), f as u32));
            continue;
        }
        for i in lo[0]..=hi[0] {
            for j in lo[1]..=hi[1] {
                for k in lo[2]..=hi[2] {
                    binned.push((key(i, j, k), f as u32));
                }
            }
        }
    }
    binned.par_sort_unstable();
    let mut starts: Vec<usize> = vec![0];
    for i in 1..binned.len() {
        if binned[i].0 != binned[i - 1].0 {
            starts.push(i);
        }
    }
    starts.push(binned.len());
    let found: Vec<(u32, u32, DVec3)> = starts
        .par_windows(2)
        .flat_map_iter(|w| {
            let cell_faces = &binned[w[0]..w[1]];
            let mut out = Vec::new();
            for (i, &(_, f)) in cell_faces.iter().enumerate() {
                let (f, bf) = (f as usize, boxes[f as usize]);
                for &(_, g) in &cell_faces[i + 1..] {
                    let (g, bg) = (g as usize, boxes[g as usize]);
                    if bf.0.max(bg.0).cmpgt(bf.1.min(bg.1)).any() {
                        continue;
                    }
                    if faces[f].iter().any(|v| faces[g].contains(v)) {
                        continue;
                    }
                    let x = [corner(f, 0), corner(f, 1), corner(f, 2)];
                    let y = [corner(g, 0), corner(g, 1), corner(g, 2)];
                    if let Some(p) = triangles_cross(x, y) {
                        out.push((f.min(g) as u32, f.max(g) as u32, p));
                    }
                }
            }
            out.into_iter()
        })
        .collect();
    let mut found = found;
    found.sort_by_key(|a| (a.0, a.1));
    found.dedup_by(|a, b| (a.0, a.1) == (b.0, b.1));
    SelfIntersections { pairs: found.len(), first: found.first().copied() }
}

#[cfg(test)]
#[path = "tests/intersect.rs"]
mod tests;
