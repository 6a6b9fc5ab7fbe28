//! Fallback domains for disk patches whose planar projection folds over (the cycle crosses
//! itself or runs clockwise in its plane, or a sharp corner turns the other way): a deep or
//! twisted patch (\[CG\] §3.3 and §5 list it as a limitation). First the plane of the cycle's
//! vector area, then a convex domain, an ellipse, on which the triangulation is always
//! injective. The parts made here are marked `fold_fallback` ([`crate::geom::mesh::Mesh::fold_fallback`]).

use super::planar::{corner_turned, Cycle};
use super::triangulate::{lift_patch, triangulate};
use super::PatchMesh;
use crate::error::{Error, Result};
use crate::geom::{plane_frame, DVec2, DVec3};

/// Triangulates the disk patch around `cycle`, whose projection on the plane normal to `n`
/// folds over, at spacing `d`: in the plane normal to `area_n` (the cycle's vector area) when
/// that plane differs from the first and its projection neither turns a corner the other way
/// nor fails to triangulate; else on [`ellipse_domain`], the new vertices placed at the
/// cycle's centroid (the solve needs only their metric).
///
/// Errors: `first` (the error of the planar projection) when the ellipse cannot be
/// triangulated either; a too narrow patch ([`lift_patch`]).
pub(super) fn tessellate_folded(
    cycle: &Cycle,
    n: DVec3,
    area_n: DVec3,
    d: f64,
    what: &dyn Fn() -> String,
    first: Error,
) -> Result<PatchMesh> {
    let (p3, center) = (&cycle.p3, cycle.center);
    // The projection folds over (the cycle crosses itself or runs clockwise in its plane): a
    // deep or twisted patch ([CG] §3.3 and §5 list it as a limitation). Try the plane of the
    // cycle's vector area, then a convex domain that is always injective.
    if area_n != DVec3::ZERO && area_n.dot(n) < 1.0 - 1e-9 {
        let (pts, e1, e2) = cycle.project(area_n);
        if let Some(Ok((tris, pos2, map))) = corner_turned(p3, &cycle.n3, &cycle.inner, &pts)
            .is_none()
            .then(|| triangulate(pts, cycle.map.clone(), d, what))
        {
            let mut part = lift_patch(tris, &pos2, &map, |q| center + q.x * e1 + q.y * e2, what)?;
            part.fold_fallback = true;
            return Ok(part);
        }
    }
    let pts = ellipse_domain(p3, n);
    let (tris, pos2, map) = triangulate(pts, cycle.map.clone(), d, what).map_err(|_| first)?;
    // New vertices start at the centroid of the border: the solve needs only their metric.
    let mut part = lift_patch(tris, &pos2, &map, |_| center, what)?;
    part.fold_fallback = true;
    Ok(part)
}

/// A convex domain for a cycle whose planar projection folds over: its vertices `p3` placed
/// counter-clockwise on an ellipse by arc length (chord lengths), the ellipse's axes along the
/// principal directions of the cycle projected on the plane normal to `n`, with their ratio,
/// and its perimeter equal to the cycle's length. A convex border makes the triangulation of
/// the domain (and a Tutte/harmonic map onto it, Floater 1997) injective whatever the shape of
/// the cycle in 3D.
pub(super) fn ellipse_domain(p3: &[DVec3], n: DVec3) -> Vec<DVec2> {
    let m = p3.len();
    let center = p3.iter().sum::<DVec3>() / m as f64;
    let (e1, e2) = plane_frame(n);
    // 2×2 covariance of the projected cycle and its principal axes.
    let (mut sxx, mut sxy, mut syy) = (0.0, 0.0, 0.0);
    for p in p3 {
        let q = DVec2::new((*p - center).dot(e1), (*p - center).dot(e2));
        sxx += q.x * q.x;
        sxy += q.x * q.y;
        syy += q.y * q.y;
    }
    let tr = sxx + syy;
    let disc = ((sxx - syy).powi(2) + 4.0 * sxy * sxy).sqrt();
    let (l1, l2) = (0.5 * (tr + disc), (0.5 * (tr - disc)).max(0.0));
    // Axis ratio, bounded so that the domain never degenerates into a slit.
    let ratio = if l1 > 0.0 { (l2 / l1).sqrt().clamp(0.2, 1.0) } else { 1.0 };
    let angle = 0.5 * (2.0 * sxy).atan2(sxx - syy);
    let (c, s) = (angle.cos(), angle.sin());
    // Arc-length table of the unit-major ellipse (a = 1, b = ratio).
    const K: usize = 1024;
    let pt = |t: f64| DVec2::new(t.cos(), ratio * t.sin());
    let mut table = vec![0.0; K + 1];
    for k in 0..K {
        let (t0, t1) = (std::f64::consts::TAU * k as f64 / K as f64, std::f64::consts::TAU * (k + 1) as f64 / K as f64);
        table[k + 1] = table[k] + pt(t0).distance(pt(t1));
    }
    let mut cum = vec![0.0; m + 1];
    for i in 0..m {
        cum[i + 1] = cum[i] + p3[i].distance(p3[(i + 1) % m]);
    }
    let scale = cum[m] / table[K];
    (0..m)
        .map(|i| {
            let target = cum[i] / cum[m] * table[K];
            let k = (table.partition_point(|&v| v <= target).clamp(1, K) - 1).min(K - 1);
            let f = ((target - table[k]) / (table[k + 1] - table[k]).max(f64::MIN_POSITIVE)).clamp(0.0, 1.0);
            let t = std::f64::consts::TAU * (k as f64 + f) / K as f64;
            let q = pt(t) * scale;
            DVec2::new(c * q.x - s * q.y, s * q.x + c * q.y)
        })
        .collect()
}

#[cfg(test)]
#[path = "tests/fallback.rs"]
mod tests;
