//! Stage 5, the bad spots: each section is cut where it is in a bad spot
//! ([`cut_bad_spots`]): a bad crossing left after the plane moves, a sharp turn within the
//! surface ([`sharp_turns`]), an end on the boundary crowding another one. It loses the
//! stretch around the spot up to the crossings on either side ([`cut_at_spots`]). Sections
//! that then meet no other curve are left out.

use super::{Raw, SampleReport, Scales, Traced};
use crate::geom::DVec3;

/// Turning angle within the surface (degrees, about the normal, over half a sample spacing on
/// either side) above which a section is cut ([`SampleReport::sharp_turns`]).
pub const SHARP_TURN_DEG: f64 = 90.0;

/// The sections `traced` cut at their bad spots: the planes' bad spots `unresolved_at`
/// (plane, place) still left after the plane moves, on the section or within `scales.gap` of
/// it; the places where it turns back within the surface by more than [`SHARP_TURN_DEG`]
/// (a plane that grazes one side of a sharp crease, so that the section runs along the crease
/// before it crosses it: the patches on the two sides of such a corner fold over in any plane,
/// fandisk); and section ends on the boundary closer than `scales.gap` to another one (the
/// boundary nearly touching itself, or a cut-back end moved next to another one: the pipeline
/// would merge them into a node with too many boundary ends; the shorter piece's end is cut).
/// Sections left without a crossing are dropped. Counts the cuts, turns and dropped sections
/// in `report`.
pub(super) fn cut_bad_spots(
    traced: Vec<Traced>,
    unresolved_at: &[(usize, DVec3)],
    scales: &Scales,
    report: &mut SampleReport,
) -> Vec<Traced> {
    let mut spots = unresolved_spots(&traced, unresolved_at, scales.gap);
    for (t, s) in traced.iter().zip(spots.iter_mut()) {
        let at = sharp_turns(&t.samples, t.closed, 0.5 * scales.spacing, SHARP_TURN_DEG);
        report.sharp_turns += at.len();
        s.extend(at);
    }
    crowded_ends(&traced, scales.gap, &mut spots);
    // A section in a bad spot loses the stretch around it, between the crossings on either
    // side (the rest of the section still bounds patches, ending on those crossings).
    let mut pieces: Vec<Traced> = Vec::new();
    for (t, s) in traced.into_iter().zip(&spots) {
        if s.is_empty() {
            pieces.push(t);
            continue;
        }
        report.cut_bad += 1;
        pieces.extend(cut_at_spots(t, s, scales.gap));
    }
    pieces.retain(|t| {
        let meets = meets_another(t);
        if !meets {
            report.dropped_sections += 1;
        }
        meets
    });
    pieces
}

/// Per polyline of `traced`: the bad spots `unresolved_at` of its plane within `gap` of one
/// of its samples (none for boundary loops).
fn unresolved_spots(traced: &[Traced], unresolved_at: &[(usize, DVec3)], gap: f64) -> Vec<Vec<DVec3>> {
    traced
        .iter()
        .map(|t| match t.plane {
            Some(p) => unresolved_at
                .iter()
                .filter(|(q, at)| *q == p && t.samples.iter().any(|r| r.p.distance(*at) <= gap))
                .map(|x| x.1)
                .collect(),
            None => Vec::new(),
        })
        .collect()
}

/// Adds to `spots` the ends of open polylines of `traced` within `gap` of an end of another
/// one: of each such pair (neither already crowded), the end of the shorter polyline.
fn crowded_ends(traced: &[Traced], gap: f64, spots: &mut [Vec<DVec3>]) {
    let ends: Vec<(usize, DVec3, f64)> = traced
        .iter()
        .enumerate()
        .filter(|(_, t)| !t.closed && t.samples.len() >= 2)
        .flat_map(|(i, t)| {
            let len: f64 = t.samples.windows(2).map(|w| w[0].p.distance(w[1].p)).sum();
            [(i, t.samples[0].p, len), (i, t.samples[t.samples.len() - 1].p, len)]
        })
        .collect();
    let mut crowded = vec![false; ends.len()];
    for (a, ea) in ends.iter().enumerate() {
        for (b, eb) in ends.iter().enumerate().skip(a + 1) {
            // (Two ends on one point: a section crossing a crease, cut there, ends on both sides.)
            let d = ea.1.distance(eb.1);
            if ea.0 != eb.0 && d <= gap && d > 1e-9 * gap && !crowded[a] && !crowded[b] {
                let (k, e) = if ea.2 <= eb.2 { (a, ea) } else { (b, eb) };
                crowded[k] = true;
                spots[e.0].push(e.1);
            }
        }
    }
}

/// Whether a section meets another curve: a closed one has a node, an open one a node inside
/// (its ends on the boundary do not count), or it is a cut piece that ends on two nodes.
fn meets_another(t: &Traced) -> bool {
    let nodes = t.samples.iter().filter(|s| s.node).count();
    let m = t.samples.len();
    let inner = t.samples.iter().enumerate().filter(|&(k, s)| s.node && k > 0 && k + 1 < m).count();
    if t.closed {
        nodes > 0
    } else {
        inner > 0 || (t.cut && nodes == 2)
    }
}

/// Cuts a traced section at `spots`: around each spot, the samples within `gap` of it (at
/// least the nearest one) are removed, and on either side the samples up to the nearest node
/// (a crossing, or an end on the boundary), which is kept as the end of the piece there.
/// Returns the pieces left (open, flagged `cut`), named after the section with a suffix;
/// pieces shorter than `gap / 2` are left out. A section without a sample removed is returned
/// as it is.
pub(super) fn cut_at_spots(t: Traced, spots: &[DVec3], gap: f64) -> Vec<Traced> {
    let remove = removed_around(&t, spots, gap);
    let runs = kept_runs(&t, &remove);
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
            right: Vec::new(),
        })
        .collect()
}

/// Which samples of `t` [`cut_at_spots`] removes: per spot, the nearest sample, the run on
/// either side within `gap` of the spot, then on to the next node (excluded).
fn removed_around(t: &Traced, spots: &[DVec3], gap: f64) -> Vec<bool> {
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
    remove
}

/// The runs of samples of `t` not marked in `remove`, in order; a closed section starts after
/// its first removed sample.
fn kept_runs(t: &Traced, remove: &[bool]) -> Vec<Vec<Raw>> {
    let m = t.samples.len();
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
    runs
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

#[cfg(test)]
#[path = "tests/cut.rs"]
mod tests;
