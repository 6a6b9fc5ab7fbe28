//! Bad crossings between sections: near misses and crossings close together.

use super::FaceCut;
use crate::geom::DVec3;
use std::collections::HashMap;

/// Planes whose sections come within `near` of a section of another plane away from their
/// crossings (near-misses: the pipeline would snap them into a node that is no crossing). Of
/// each such pair, the plane with the larger index below `first_virtual` is returned (planes
/// from `first_virtual` on stand for the mesh boundary and are not moved).
pub(super) fn near_misses(
    cuts: &[FaceCut],
    crossing_points: &HashMap<(usize, usize), Vec<DVec3>>,
    near: f64,
    first_virtual: usize,
) -> Vec<(usize, DVec3)> {
    use crate::geom::closest_params_segment_segment;
    let h = near.max(f64::MIN_POSITIVE);
    let cell = |p: DVec3| ((p.x / h).floor() as i64, (p.y / h).floor() as i64, (p.z / h).floor() as i64);
    let mut grid: HashMap<(i64, i64, i64), Vec<usize>> = HashMap::new();
    for (i, c) in cuts.iter().enumerate() {
        let lo = cell(c.ends[0].min(c.ends[1]) - DVec3::splat(near));
        let hi = cell(c.ends[0].max(c.ends[1]) + DVec3::splat(near));
        if (hi.0 - lo.0 + 1) * (hi.1 - lo.1 + 1) * (hi.2 - lo.2 + 1) > 4096 {
            continue; // a cut far longer than the tolerance (coarse mesh): checked from its neighbours
        }
        for x in lo.0..=hi.0 {
            for y in lo.1..=hi.1 {
                for z in lo.2..=hi.2 {
                    grid.entry((x, y, z)).or_default().push(i);
                }
            }
        }
    }
    let mut seen = std::collections::HashSet::new();
    let mut out = Vec::new();
    for list in grid.values() {
        for (k, &i) in list.iter().enumerate() {
            for &j in &list[k + 1..] {
                let (a, b) = (&cuts[i], &cuts[j]);
                if a.plane == b.plane || !seen.insert((i.min(j), i.max(j))) {
                    continue;
                }
                let (s, t) = closest_params_segment_segment(a.ends[0], a.ends[1], b.ends[0], b.ends[1]);
                let (pa, pb) = (a.ends[0].lerp(a.ends[1], s), b.ends[0].lerp(b.ends[1], t));
                if pa.distance(pb) > near {
                    continue;
                }
                let key = (a.plane.min(b.plane), a.plane.max(b.plane));
                let m = 0.5 * (pa + pb);
                let at_crossing =
                    crossing_points.get(&key).is_some_and(|ps| ps.iter().any(|p| p.distance(m) <= 4.0 * near));
                if !at_crossing {
                    out.push((if key.1 >= first_virtual { key.0 } else { key.1 }, m));
                }
            }
        }
    }
    out
}

/// Planes to move so that no two crossings are closer than `gap` (`gap_same` for two
/// crossings of the same two planes): of two close crossings, a plane they share is kept and
/// the other one with the larger index is returned.
pub(super) fn close_crossings(
    crossing_points: &HashMap<(usize, usize), Vec<DVec3>>,
    gap: f64,
    gap_same: f64,
    first_virtual: usize,
) -> Vec<(usize, DVec3)> {
    let mut out = Vec::new();
    for (key, ps) in crossing_points {
        if let Some(p) = ps.iter().enumerate().find(|(i, p)| ps[i + 1..].iter().any(|q| q.distance(**p) <= gap_same)) {
            out.push((if key.1 >= first_virtual { key.0 } else { key.1 }, *p.1));
        }
    }
    let h = gap.max(f64::MIN_POSITIVE);
    let cell = |p: DVec3| ((p.x / h).floor() as i64, (p.y / h).floor() as i64, (p.z / h).floor() as i64);
    let mut all: Vec<((usize, usize), DVec3)> =
        crossing_points.iter().flat_map(|(k, ps)| ps.iter().map(move |p| (*k, *p))).collect();
    all.sort_by(|a, b| a.0.cmp(&b.0).then(a.1.x.total_cmp(&b.1.x)));
    let mut grid: HashMap<(i64, i64, i64), Vec<usize>> = HashMap::new();
    for (i, (_, p)) in all.iter().enumerate() {
        grid.entry(cell(*p)).or_default().push(i);
    }
    for (i, (ka, p)) in all.iter().enumerate() {
        let c = cell(*p);
        for dx in -1..=1 {
            for dy in -1..=1 {
                for dz in -1..=1 {
                    for &j in grid.get(&(c.0 + dx, c.1 + dy, c.2 + dz)).map_or(&[][..], |v| &v[..]) {
                        let (kb, q) = &all[j];
                        if j <= i || q.distance(*p) > gap {
                            continue;
                        }
                        let planes = [ka.0, ka.1, kb.0, kb.1];
                        let shared = planes.iter().find(|&&x| planes.iter().filter(|&&y| y == x).count() > 1);
                        let pick = planes
                            .iter()
                            .copied()
                            .filter(|x| Some(x) != shared && *x < first_virtual)
                            .max()
                            .unwrap_or(ka.0);
                        out.push((pick, *p));
                    }
                }
            }
        }
    }
    out
}
