//! Stage 7, the network: each polyline kept is resampled at the sample spacing
//! ([`resample`]: corners, ends and, with shared nodes, crossings kept as samples), hairpins
//! are cut off ([`remove_hairpins`]), and the curves make the network
//! ([`assemble`]), with the snapping tolerance written in it and sensor noise added
//! ([`Network::perturbed`]).

use super::holes::Resampled;
use super::{Raw, SampleOptions, SampleReport, Scales, Traced};
use crate::error::{Error, Result};
use crate::geom::DVec3;
use crate::network::{Curve, Network};

/// Turning angle (degrees) above which a polyline sample is a corner (a sharp edge of the
/// mesh crossed by the section) and is kept through resampling: a chord across it would cut
/// the corner and come close to the curves on the other side of the edge.
pub const CORNER_DEG: f64 = 30.0;

/// The network of the sections `pieces` and the boundary loops `loops` (already resampled),
/// in that order: each resampled at `scales.spacing` (crossings kept as samples with
/// `opts.shared_nodes`), hairpins closer than `scales.near` cut off, curves with too few
/// samples left out; snapping tolerance `scales.snap`; with `opts.noise`, perturbed
/// ([`Network::perturbed`] with `opts.seed`). Counts the curves and hairpins in `report`.
///
/// Errors: [`Error::Topology`] when no curve is left or `report` counts no crossing.
pub(super) fn assemble(
    pieces: Vec<Traced>,
    loops: Vec<(Traced, Resampled)>,
    opts: &SampleOptions,
    scales: &Scales,
    report: &mut SampleReport,
) -> Result<Network> {
    let mut curves = Vec::new();
    let loops = loops.into_iter().map(|(t, pn)| (t, Some(pn)));
    for (t, pn) in pieces.into_iter().map(|t| (t, None)).chain(loops) {
        let (mut points, mut normals, mut normals_right) = pn.unwrap_or_else(|| {
            let (p, n) = resample(&t.samples, t.closed, scales.spacing, opts.shared_nodes);
            (p, n, Vec::new())
        });
        if normals_right.is_empty() {
            report.hairpins += remove_hairpins(&mut points, &mut normals, t.closed, scales.near);
        }
        report.folded_normals += repair_folded_normals(&points, &mut normals, t.closed);
        report.folded_normals += repair_folded_normals(&points, &mut normals_right, t.closed);
        let need = if t.closed { 3 } else { 2 };
        if points.len() < need {
            continue;
        }
        if !normals_right.is_empty() {
            report.creases += 1;
        } else if t.boundary {
            report.boundary_loops += 1;
        } else {
            report.sections += 1;
        }
        curves.push(Curve {
            name: Some(t.name),
            points,
            normals,
            normals_right,
            closed: t.closed,
            boundary: t.boundary,
        });
    }
    if report.crossings == 0 || curves.is_empty() {
        return Err(Error::topology(
            "the plane sections do not cross each other on the mesh: give more planes (`planes`) in at least two directions",
        ));
    }
    let mut net = Network { curves, snap: Some(scales.snap), cycles: None };
    if opts.noise > 0.0 {
        net = net.perturbed(opts.noise, opts.seed);
    }
    Ok(net)
}

/// A sample normal within this many degrees of the curve's direction, or more than this many
/// degrees from the normals of both its neighbours while they are less than half as far from
/// each other, comes from a folded mesh face (a flap or sliver, often on a scanned mesh's
/// boundary): a surface's normal is across every curve on it and turns smoothly away from
/// creases. `curvenet sample` replaces it by the nearest good normal on the curve.
pub const FOLDED_NORMAL_DEG: f64 = 45.0;

/// Replaces each normal of `normals` (empty: nothing to do) that comes from a folded face
/// ([`FOLDED_NORMAL_DEG`]) by the normal of the nearest sample along the polyline that does
/// not (none: left as it is, the network's validation names it). Returns the number replaced.
pub(super) fn repair_folded_normals(points: &[DVec3], normals: &mut [DVec3], closed: bool) -> usize {
    let m = points.len();
    if normals.len() != m || m < 2 {
        return 0;
    }
    let limit = FOLDED_NORMAL_DEG.to_radians();
    // The neighbours of sample i (none past the ends of an open polyline).
    let prev = |i: usize| if i > 0 { Some(i - 1) } else { closed.then_some(m - 1) };
    let next = |i: usize| if i + 1 < m { Some(i + 1) } else { closed.then_some(0) };
    let unit: Vec<DVec3> = normals.iter().map(|n| n.normalize_or_zero()).collect();
    let bad: Vec<bool> = (0..m)
        .map(|i| {
            let (a, b) = (prev(i).unwrap_or(i), next(i).unwrap_or(i));
            let tangent = (points[b] - points[a]).normalize_or_zero();
            let spike = match (prev(i), next(i)) {
                (Some(a), Some(b)) => {
                    let off = unit[i].angle_between(unit[a]).min(unit[i].angle_between(unit[b]));
                    off > limit && unit[a].angle_between(unit[b]) < 0.5 * off
                }
                _ => false,
            };
            unit[i] == DVec3::ZERO || unit[i].dot(tangent).abs() > limit.cos() || spike
        })
        .collect();
    let mut replaced = 0;
    for i in (0..m).filter(|&i| bad[i]) {
        // The nearest good sample, looking both ways (around a closed polyline).
        let near = (1..m).find_map(|d| {
            let back = if i >= d { Some(i - d) } else { closed.then(|| i + m - d) };
            let ahead = if i + d < m { Some(i + d) } else { closed.then(|| (i + d) % m) };
            [back, ahead].into_iter().flatten().find(|&j| !bad[j])
        });
        if let Some(j) = near {
            normals[i] = normals[j];
            replaced += 1;
        }
    }
    replaced
}

/// Resamples a polyline at about `spacing` by arc length (positions on the polyline, so on
/// the mesh; normals interpolated linearly and normalised). Corner samples ([`corners`]), the
/// ends of an open curve and, with `keep_nodes`, the node samples are kept, and each stretch
/// between two kept samples is split evenly. Without `keep_nodes` the crossings are not
/// samples (a closed curve without corners starts half a step from its first node).
pub(super) fn resample(raw: &[Raw], closed: bool, spacing: f64, keep_nodes: bool) -> (Vec<DVec3>, Vec<DVec3>) {
    let mut pts: Vec<Raw> = raw.to_vec();
    if closed {
        pts.push(pts[0]);
    }
    let arc_of = |pts: &[Raw]| crate::geom::polyline::arc_lengths(pts, |a, b| b.p.distance(a.p));
    let reach = 0.3 * spacing;
    let mut corner = corners(&pts, &arc_of(&pts), closed, reach);
    // A corner next to a kept node would make a tiny edge: the node is enough.
    if keep_nodes {
        for i in 0..pts.len() {
            if corner[i] && pts.iter().any(|r| r.node && r.p.distance(pts[i].p) < reach) {
                corner[i] = false;
            }
        }
    }
    let fixed_flag: Vec<bool> = (0..pts.len()).map(|i| corner[i] || (keep_nodes && pts[i].node)).collect();
    // A closed curve starts at a kept sample, or at a node (then shifted by half a step).
    let mut shift = false;
    if closed {
        pts.pop();
        let mut flags = fixed_flag[..pts.len()].to_vec();
        let start = flags.iter().position(|&f| f).or_else(|| {
            shift = true;
            pts.iter().position(|r| r.node)
        });
        if let Some(k) = start {
            pts.rotate_left(k);
            flags.rotate_left(k);
        }
        pts.push(pts[0]);
        flags[0] = true;
        flags.push(true);
        return finish(&pts, &arc_of(&pts), &flags, closed, spacing, shift);
    }
    let mut flags = fixed_flag;
    let m = flags.len();
    flags[0] = true;
    flags[m - 1] = true;
    finish(&pts, &arc_of(&pts), &flags, closed, spacing, false)
}

/// Splits each stretch between two `fixed` samples evenly at about `spacing`; with `shift`
/// (a closed curve with one stretch) the samples are moved by half a step.
fn finish(
    pts: &[Raw],
    arc: &[f64],
    fixed: &[bool],
    closed: bool,
    spacing: f64,
    shift: bool,
) -> (Vec<DVec3>, Vec<DVec3>) {
    let m = pts.len();
    let at = |s: f64| -> (DVec3, DVec3) {
        let (k, t) = crate::geom::polyline::locate(arc, s);
        (pts[k].p.lerp(pts[k + 1].p, t), pts[k].n.lerp(pts[k + 1].n, t))
    };
    let mut out_p = Vec::new();
    let mut out_n = Vec::new();
    let mut push = |(p, n): (DVec3, DVec3)| {
        out_p.push(p);
        out_n.push(n.normalize_or_zero());
    };
    let idx: Vec<usize> = (0..m).filter(|&i| fixed[i]).collect();
    if shift && idx.len() == 2 {
        let total = arc[m - 1];
        let k = (total / spacing).round().max(3.0) as usize;
        for j in 0..k {
            push(at((total * (j as f64 + 0.5) / k as f64).min(total)));
        }
        return (out_p, out_n);
    }
    for w in idx.windows(2) {
        let (s0, s1) = (arc[w[0]], arc[w[1]]);
        if s1 - s0 <= 0.0 {
            continue;
        }
        let k = ((s1 - s0) / spacing).round().max(1.0) as usize;
        push((pts[w[0]].p, pts[w[0]].n));
        for j in 1..k {
            push(at(s0 + (s1 - s0) * j as f64 / k as f64));
        }
    }
    if !closed {
        push((pts[m - 1].p, pts[m - 1].n));
    }
    (out_p, out_n)
}

/// Corner samples of `pts` (open polyline; a closed one repeats its first sample at the end):
/// the turning angle between the directions to the samples at least `reach` behind and ahead
/// exceeds [`CORNER_DEG`]; of corners closer than `reach`, the sharpest is kept.
fn corners(pts: &[Raw], arc: &[f64], closed: bool, reach: f64) -> Vec<bool> {
    let m = pts.len();
    let total = arc[m - 1];
    let mut angle = vec![0.0; m];
    let cos_max = CORNER_DEG.to_radians().cos();
    for i in 0..m {
        if !closed && (i == 0 || i == m - 1) {
            continue;
        }
        if closed && total < 4.0 * reach {
            break;
        }
        let find = |step: isize| -> Option<DVec3> {
            let mut j = i as isize;
            for _ in 0..m {
                j += step;
                let jj =
                    if closed { j.rem_euclid(m as isize - 1) as usize } else { j.clamp(0, m as isize - 1) as usize };
                if pts[jj].p.distance(pts[i].p) >= reach {
                    return Some(pts[jj].p);
                }
                if !closed && (jj == 0 || jj == m - 1) {
                    return None;
                }
            }
            None
        };
        if let (Some(b), Some(a)) = (find(-1), find(1)) {
            let (u, v) = ((pts[i].p - b).normalize_or_zero(), (a - pts[i].p).normalize_or_zero());
            let c = u.dot(v);
            if c < cos_max {
                angle[i] = c.clamp(-1.0, 1.0).acos();
            }
        }
    }
    // Keep local maxima within `reach`.
    let mut out = vec![false; m];
    for i in 0..m {
        if angle[i] == 0.0 {
            continue;
        }
        let mut best = true;
        for j in 0..m {
            if j != i && angle[j] > angle[i] && pts[j].p.distance(pts[i].p) < reach {
                best = false;
                break;
            }
        }
        out[i] = best;
    }
    out
}

/// Cuts hairpins off a resampled curve: where the curve comes back within `tol` of itself
/// after a few samples (a narrow notch of the mesh boundary, a thin fin cut by a plane), the
/// samples in between are removed, so that the curve does not run alongside itself (the
/// pipeline would take it for an overlap). Returns the number of hairpins cut.
pub fn remove_hairpins(points: &mut Vec<DVec3>, normals: &mut Vec<DVec3>, closed: bool, tol: f64) -> usize {
    const REACH: usize = 12;
    let mut cut = 0;
    let mut i = 0;
    while i < points.len() {
        let m = points.len();
        if m <= REACH + 3 {
            break;
        }
        let last = if closed { i + REACH } else { (i + REACH).min(m - 1) };
        // Segment (i, i+1) against segment (j, j+1), j ≥ i + 2: close → drop i+1 ..= j.
        let seg_dist = |j: usize| {
            let (a0, a1) = (points[i], points[(i + 1) % m]);
            let (b0, b1) = (points[j % m], points[(j + 1) % m]);
            let (s, t) = crate::geom::closest_params_segment_segment(a0, a1, b0, b1);
            a0.lerp(a1, s).distance(b0.lerp(b1, t))
        };
        let top = if closed { last } else { last.min(m - 2) };
        let far = (i + 2..=top).filter(|&j| seg_dist(j) <= tol).max();
        if let Some(j) = far {
            // Remove samples i+1 ..= j (cyclically).
            let remove: Vec<usize> = (i + 1..=j).map(|k| k % m).collect();
            if remove.len() + 3 > m {
                break;
            }
            let mut keep = vec![true; m];
            for k in remove {
                keep[k] = false;
            }
            let before = keep[..i].iter().filter(|&&k| !k).count();
            let mut it = keep.iter();
            points.retain(|_| *it.next().unwrap_or(&true));
            let mut it = keep.iter();
            normals.retain(|_| *it.next().unwrap_or(&true));
            i -= before;
            cut += 1;
            continue;
        }
        i += 1;
    }
    cut
}

#[cfg(test)]
#[path = "tests/network.rs"]
mod tests;
