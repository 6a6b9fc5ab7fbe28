//! Tube patches (\[CG\] Fig. 1: two facing boundary loops, an annulus): the annulus is cut open
//! along a seam from the first loop to the second and unrolled onto a trapezoidal strip, the
//! first loop along the bottom edge (its arc length as abscissa), the second along the top
//! edge at the height of the distance between the loops' centroids, the seam vertices shared
//! by the left and right edges. The strip is triangulated ([`super::triangulate`]) and lifted
//! back to 3D by blending the two loops at the same relative abscissa.

use super::triangulate::{lift_patch, triangulate};
use super::{describe_patch, loop_vertices, PatchMesh, VRef};
use crate::error::Result;
use crate::geom::{DVec2, DVec3};
use crate::topology::resample::Resampled;
use crate::topology::{Graph, HalfEdge};

/// Triangulates the tube patch `index` between the two loops of half-edges `loops` (each with
/// the tube on its left) at spacing `d`, on the unrolled strip; the seam gets
/// `max(2, round(h/d)) − 1` new vertices for a distance `h` between the loops' centroids.
pub(super) fn tessellate_tube(
    g: &Graph,
    res: &Resampled,
    loops: &[Vec<HalfEdge>; 2],
    d: f64,
    index: usize,
) -> Result<PatchMesh> {
    let all: Vec<HalfEdge> = loops[0].iter().chain(&loops[1]).copied().collect();
    let what = || format!("tube patch {index} (between {})", describe_patch(g, &all));
    let a = loop_vertices(res, &loops[0]);
    let b = loop_vertices(res, &loops[1]);
    let pos = |i: u32| res.positions[i as usize];
    let cum = |ids: &[u32]| {
        let mut c = vec![0.0];
        for k in 0..ids.len() {
            let l = pos(ids[k]).distance(pos(ids[(k + 1) % ids.len()]));
            c.push(c[k] + l);
        }
        c
    };
    let ca = a.iter().map(|&i| pos(i)).sum::<DVec3>() / a.len() as f64;
    let cb = b.iter().map(|&i| pos(i)).sum::<DVec3>() / b.len() as f64;
    let h = ca.distance(cb);
    // Start B at the sample closest to A's first sample, so the seam runs straight across.
    let j0 = (0..b.len())
        .min_by(|&x, &y| pos(b[x]).distance(pos(a[0])).total_cmp(&pos(b[y]).distance(pos(a[0]))))
        .unwrap_or(0);
    let b: Vec<u32> = (0..b.len()).map(|k| b[(j0 + k) % b.len()]).collect();
    let (xa, xb) = (cum(&a), cum(&b));
    let (la, lb) = (xa[a.len()], xb[b.len()]);
    let x_off = 0.5 * (la - lb);
    let m = ((h / d).round() as usize).max(2);
    let mut pts = Vec::new();
    let mut map = Vec::new();
    // Bottom edge: loop A left to right (the tube is on its left, above).
    for (k, &i) in a.iter().enumerate() {
        pts.push(DVec2::new(xa[k], 0.0));
        map.push(VRef::Curve(i));
    }
    pts.push(DVec2::new(la, 0.0));
    map.push(VRef::Curve(a[0]));
    // Right seam, bottom to top; seam vertex k is shared with the left seam.
    for k in 1..m {
        let t = k as f64 / m as f64;
        pts.push(DVec2::new(la, 0.0).lerp(DVec2::new(x_off + lb, h), t));
        map.push(VRef::New((k - 1) as u32));
    }
    // Top edge: loop B right to left (its traversal direction).
    for (k, &i) in b.iter().enumerate() {
        pts.push(DVec2::new(x_off + lb - xb[k], h));
        map.push(VRef::Curve(i));
    }
    pts.push(DVec2::new(x_off, h));
    map.push(VRef::Curve(b[0]));
    // Left seam, top to bottom.
    for k in (1..m).rev() {
        let t = k as f64 / m as f64;
        pts.push(DVec2::new(0.0, 0.0).lerp(DVec2::new(x_off, h), t));
        map.push(VRef::New((k - 1) as u32));
    }
    let (tris, pos2, map) = triangulate(pts, map, d, &what)?;
    // Lift: blend the two loops at the same strip abscissa.
    let at = |ids: &[u32], c: &[f64], x: f64| {
        let l = c[ids.len()];
        let x = x.rem_euclid(l);
        let k = (c.partition_point(|&v| v <= x).max(1) - 1).min(ids.len() - 1);
        let t = ((x - c[k]) / (c[k + 1] - c[k]).max(f64::MIN_POSITIVE)).clamp(0.0, 1.0);
        pos(ids[k]).lerp(pos(ids[(k + 1) % ids.len()]), t)
    };
    let lift = |q: DVec2| {
        let v = (q.y / h).clamp(0.0, 1.0);
        // Not clamped: the smoothing (`relax`) may move a seam vertex past the strip's edge, and
        // `at` wraps around the loop.
        let u = q.x / la.max(f64::MIN_POSITIVE);
        at(&a, &xa, u * la).lerp(at(&b, &xb, lb - u * lb), v)
    };
    lift_patch(tris, &pos2, &map, lift, &what)
}

#[cfg(test)]
#[path = "tests/tube.rs"]
mod tests;
