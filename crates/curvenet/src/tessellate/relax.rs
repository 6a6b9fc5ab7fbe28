//! Smoothing of a patch triangulation in its domain (issue 18, "fair meshes"): the free
//! vertices move to the area-weighted centroid of their incident triangles' centroids, the
//! border stays. The lattice's inside is a fixed point of that map (every vertex there is
//! already the centroid of its regular hexagon); what moves is the refined band and the rows
//! where it meets the lattice, whose vertices of valence 5 and 7 otherwise sit in lop-sided
//! one-rings. The cotangent Laplacian of such a ring is a poor curvature estimate (the mean
//! curvature of points exactly on the unit sphere was off by 16 % there, 20k vertices), and
//! the fit (\[CG\] eq. 2) turns it into bumps; after smoothing the one-rings are balanced
//! (measured in docs/accuracy.md, "Fairness").
//!
//! Moves that would flip a triangle or shrink it below [`MIN_AREA_RATIO`] of its area are
//! taken back, so the triangulation stays valid in the domain.

use crate::geom::DVec2;

/// Smoothing passes over a patch.
pub(super) const RELAX_PASSES: usize = 4;

/// A smoothing pass keeps no triangle smaller than this fraction of its area before the pass.
const MIN_AREA_RATIO: f64 = 0.25;

/// A position shared by two domain points: the tube's seam vertices sit on both edges of the
/// unrolled strip. `b`'s position is `a`'s plus `offset`.
#[derive(Clone, Copy, Debug)]
pub(super) struct Twin {
    pub(super) a: usize,
    pub(super) b: usize,
    pub(super) offset: DVec2,
}

fn signed_area(p: &[DVec2], t: &[usize; 3]) -> f64 {
    0.5 * (p[t[1]] - p[t[0]]).perp_dot(p[t[2]] - p[t[0]])
}

/// Smooths the domain positions `pos` of the triangulation `tris` in [`RELAX_PASSES`] passes:
/// positions from index `fixed` on move, those before stay, except the seam `twins`, which move
/// together (each pair as one vertex, with the triangles of both sides).
pub(super) fn relax(tris: &[[usize; 3]], pos: &mut [DVec2], fixed: usize, twins: &[Twin]) {
    let n = pos.len();
    let mut movable: Vec<bool> = (0..n).map(|i| i >= fixed).collect();
    let mut partner = vec![usize::MAX; n];
    for t in twins {
        movable[t.a] = true;
        partner[t.a] = t.b;
        partner[t.b] = t.a;
    }
    let mut acc = vec![DVec2::ZERO; n];
    let mut weight = vec![0.0; n];
    for _ in 0..RELAX_PASSES {
        acc.iter_mut().for_each(|a| *a = DVec2::ZERO);
        weight.iter_mut().for_each(|w| *w = 0.0);
        for t in tris {
            let area = signed_area(pos, t);
            if area <= 0.0 {
                continue;
            }
            let c = (pos[t[0]] + pos[t[1]] + pos[t[2]]) / 3.0;
            for &v in t {
                acc[v] += area * c;
                weight[v] += area;
            }
        }
        for t in twins {
            // The seam's other side, moved into `a`'s frame.
            let (other, w) = (acc[t.b] - weight[t.b] * t.offset, weight[t.b]);
            acc[t.a] += other;
            weight[t.a] += w;
        }
        let old: Vec<DVec2> = pos.to_vec();
        for v in 0..n {
            if movable[v] && weight[v] > 0.0 {
                pos[v] = acc[v] / weight[v];
            }
        }
        for t in twins {
            pos[t.b] = pos[t.a] + t.offset;
        }
        // Take back the moves around triangles that flip or shrink too much, until none does.
        loop {
            let mut changed = false;
            for t in tris {
                let before = signed_area(&old, t);
                if before > 0.0 && signed_area(pos, t) < MIN_AREA_RATIO * before {
                    for &v in t {
                        if pos[v] != old[v] {
                            pos[v] = old[v];
                            changed = true;
                            if partner[v] != usize::MAX {
                                pos[partner[v]] = old[partner[v]];
                            }
                        }
                    }
                }
            }
            if !changed {
                break;
            }
        }
    }
}

#[cfg(test)]
#[path = "tests/relax.rs"]
mod tests;
