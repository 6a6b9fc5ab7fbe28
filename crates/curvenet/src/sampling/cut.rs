//! Sections cut at bad spots and sharp turns.

use super::{Raw, Traced};
use crate::geom::DVec3;

/// Cuts a traced section at `spots`: around each spot, the samples within `gap` of it (at
/// least the nearest one) are removed, and on either side the samples up to the nearest node
/// (a crossing, or an end on the boundary), which is kept as the end of the piece there.
/// Returns the pieces left (open, flagged `cut`), named after the section with a suffix;
/// pieces shorter than `gap / 2` are left out.
pub(super) fn cut_at_spots(t: Traced, spots: &[DVec3], gap: f64) -> Vec<Traced> {
    let m = t.samples.len();
    let mut remove = vec![false; m];
    let step = |k: usize, forward: bool| -> Option<usize> {
        match (forward, t.closed) {
            (true, true) => Some((k + 1) % m),
            (false, true) => Some((k + m - 1) % m),
            (true, false) => (k + 1 < m).then_some(k + 1),
            (false, false) => k.checked_sub(1),
        }
    };
    for &spot in spots {
        let Some(i) = (0..m)
            .min_by(|&a, &b| t.samples[a].p.distance_squared(spot).total_cmp(&t.samples[b].p.distance_squared(spot)))
        else {
            continue;
        };
        remove[i] = true;
        for forward in [true, false] {
            // The run within `gap` of the spot, then on to the next node.
            let mut k = i;
            let mut in_run = true;
            for _ in 0..m {
                let Some(next) = step(k, forward) else { break };
                if remove[next] && next == i {
                    break;
                }
                in_run = in_run && t.samples[next].p.distance(spot) <= gap;
                if !in_run && t.samples[next].node {
                    break;
                }
                remove[next] = true;
                k = next;
            }
        }
    }
    // Runs of kept samples; a closed section starts after a removed sample.
    let start = if t.closed { (0..m).find(|&k| remove[k]).map_or(0, |k| (k + 1) % m) } else { 0 };
    let mut runs: Vec<Vec<Raw>> = Vec::new();
    let mut current: Vec<Raw> = Vec::new();
    for j in 0..m {
        let k = (start + j) % m;
        if remove[k] {
            if !current.is_empty() {
                runs.push(std::mem::take(&mut current));
            }
        } else {
            current.push(t.samples[k]);
        }
    }
    if !current.is_empty() {
        runs.push(current);
    }
    if remove.iter().all(|&r| !r) {
        return vec![t];
    }
    runs.into_iter()
        .filter(|r| r.len() >= 2 && r.windows(2).map(|w| w[0].p.distance(w[1].p)).sum::<f64>() >= 0.5 * gap)
        .enumerate()
        .map(|(k, samples)| Traced {
            plane: t.plane,
            samples,
            closed: false,
            boundary: t.boundary,
            name: format!("{}.{}", t.name, k + 1),
            cut: true,
        })
        .collect()
}

/// Points of a polyline (`pts`, closed or open) where it turns within the surface (about its
/// normal) by more than `limit_deg` between the directions to the samples `reach` behind and
/// ahead; of turns closer than `reach`, the sharpest.
pub(super) fn sharp_turns(pts: &[Raw], closed: bool, reach: f64, limit_deg: f64) -> Vec<DVec3> {
    let m = pts.len();
    let find = |i: usize, step: isize| -> Option<DVec3> {
        let mut j = i as isize;
        for _ in 0..m {
            j += step;
            let jj = if closed {
                j.rem_euclid(m as isize) as usize
            } else if j < 0 || j >= m as isize {
                return None;
            } else {
                j as usize
            };
            if pts[jj].p.distance(pts[i].p) >= reach {
                return Some(pts[jj].p);
            }
        }
        None
    };
    let mut turn = vec![0.0; m];
    for i in 0..m {
        let (Some(b), Some(a)) = (find(i, -1), find(i, 1)) else { continue };
        let n = pts[i].n.normalize_or_zero();
        let flat = |v: DVec3| v - n * v.dot(n);
        let (u, v) = (flat(pts[i].p - b), flat(a - pts[i].p));
        turn[i] = u.cross(v).dot(n).atan2(u.dot(v)).abs().to_degrees();
    }
    (0..m)
        .filter(|&i| {
            turn[i] > limit_deg && (0..m).all(|j| j == i || !(turn[j] > turn[i] && pts[j].p.distance(pts[i].p) < reach))
        })
        .map(|i| pts[i].p)
        .collect()
}

/// Turning angle within the surface (degrees, about the normal, over half a sample spacing on
/// either side) above which a section is cut ([`SampleReport::sharp_turns`]).
pub const SHARP_TURN_DEG: f64 = 90.0;

/// A closed polyline two of whose non-adjacent edges come within `tol` of each other.
pub(super) fn thin_loop(points: &[DVec3], tol: f64) -> bool {
    let m = points.len();
    (0..m).any(|i| {
        (i + 2..m).any(|j| {
            if (j + 1) % m == i {
                return false;
            }
            let (s, t) = crate::geom::closest_params_segment_segment(
                points[i],
                points[(i + 1) % m],
                points[j],
                points[(j + 1) % m],
            );
            points[i].lerp(points[(i + 1) % m], s).distance(points[j].lerp(points[(j + 1) % m], t)) <= tol
        })
    })
}
