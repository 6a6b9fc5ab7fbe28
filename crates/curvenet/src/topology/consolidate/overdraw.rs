//! Overdraw: strokes, or stretches of strokes, drawn along each other (a stroke drawn twice, a
//! stroke retraced back over itself, two strokes that share a stretch) become one curve.
//!
//! The strokes are visited longest first. A dense point of a stroke is *covered* when a point
//! kept earlier — of a longer stroke, or of the same stroke further back along it (a retrace)
//! — lies within the band and runs the same way (tangents within [`PARALLEL_DEGREES`], either
//! sense). A covered run as long as [`MIN_RUN`] bands is overdraw: it is removed from its
//! stroke (splitting it), and each of its points is averaged into the point that covered it
//! (positions, and normals where given). Shorter runs are crossings at a shallow angle, left to
//! node finding. What remains of a stroke between removed runs becomes its pieces; pieces
//! shorter than two gaps (or folded within one and a half) are dropped with it.

use super::dense::Dense;
use super::Piece;
use crate::geom::DVec3;

/// Tangents of two stretches within this angle (either sense) run along each other.
pub(super) const PARALLEL_DEGREES: f64 = 20.0;

/// Normals (where both stretches carry them) within this angle: one surface drawn twice.
pub(super) const NORMALS_DEGREES: f64 = 30.0;

/// A covered run whose offset across its cover drifts at more than this angle is a crossing.
pub(super) const CROSSING_DEGREES: f64 = 8.0;

/// A covered run at least this many bands long is overdraw (shorter ones: a shallow crossing).
pub(super) const MIN_RUN: f64 = 4.0;

/// A covered run sharing this many input samples with the curves covering it is a duplicate
/// stroke (a junction of a graph shares one: its node).
pub(super) const DUPLICATE_SAMPLES: usize = 3;

/// One overdrawn stretch: the curve it was on, the curve it was merged into, where, and its
/// length.
pub(super) struct Merge {
    pub(super) curve: usize,
    pub(super) onto: usize,
    pub(super) at: DVec3,
    pub(super) length: f64,
}

/// What [`merge_overdraw`] made.
pub(super) struct Overdraw {
    /// Every curve's pieces, in curve order and along each curve.
    pub(super) pieces: Vec<Piece>,
    /// The stretches merged.
    pub(super) merges: Vec<Merge>,
    /// Remnants dropped (pieces shorter than the gap between or beside merged runs).
    pub(super) dropped: usize,
    /// Per dense point: its position was averaged.
    pub(super) moved: Vec<bool>,
}

/// Finds and merges the overdrawn stretches of the curves of `d` (within `band` of each other;
/// remnants shorter than two `gap`s dropped). `fixed[c]`: curve `c` is never covered (a crease or a boundary).
pub(super) fn merge_overdraw(d: &mut Dense, band: f64, gap: f64, snap: f64, fixed: &[bool]) -> Overdraw {
    let n = d.pos.len();
    let curves = d.ranges.len();
    let mut order: Vec<usize> = (0..curves).collect();
    order.sort_by(|&a, &b| fixed[b].cmp(&fixed[a]).then(d.length[b].total_cmp(&d.length[a])).then(a.cmp(&b)));
    let cos_parallel = PARALLEL_DEGREES.to_radians().cos();
    let cos_normals = NORMALS_DEGREES.to_radians().cos();
    let mut kept = vec![false; n];
    let mut cover: Vec<Option<usize>> = vec![None; n];
    let mut merges = Vec::new();
    let mut pieces_of: Vec<Vec<Piece>> = (0..curves).map(|_| Vec::new()).collect();
    let mut dropped = 0;
    for &c in &order {
        let (s, e) = d.ranges[c];
        // Covered points of c: by kept points of earlier curves, or by earlier uncovered points
        // of c itself far enough back along it.
        if !fixed[c] {
            for i in s..e {
                let mut best: Option<(f64, usize)> = None;
                d.near(d.pos[i], band, |j| {
                    let other = d.curve[j] as usize != c;
                    let ok = if other { kept[j] } else { j < i && cover[j].is_none() && d.along(i, j) > 3.0 * band };
                    // Where both carry normals they agree (a stroke drawn twice on one surface),
                    // unlike a curve that ends on a crease along the other side of it.
                    let (ni, nj) = (d.nrm[i], d.nrm[j]);
                    let same_side = ni == DVec3::ZERO || nj == DVec3::ZERO || ni.dot(nj) >= cos_normals;
                    if ok && same_side && d.tan[i].dot(d.tan[j]).abs() >= cos_parallel {
                        let dist = d.pos[i].distance(d.pos[j]);
                        if best.is_none_or(|b| dist < b.0) {
                            best = Some((dist, j));
                        }
                    }
                });
                cover[i] = best.map(|b| b.1);
            }
        }
        let runs = covered_runs(d, c, &cover);
        for (a, b) in runs {
            let length = run_length(d, a, b);
            let idx = run_indices(d, a, b);
            // A run within two gaps of an open stroke's end (a hook may follow) is that end lying
            // along another stroke, drawn on past a junction or back to it: overdraw whatever
            // its length.
            let (s0, e0) = d.ranges[c];
            let near_end = |end: usize| idx.iter().any(|&i| d.along(i, end) <= 2.0 * gap);
            let at_end = !d.closed[c] && (near_end(s0) || near_end(e0 - 1));
            // Within twice the snapping tolerance over more than six of it: node finding would
            // refuse the pair as overlapping, whatever the run's length.
            let close =
                idx.iter().filter(|&&i| cover[i].is_some_and(|j| d.pos[i].distance(d.pos[j]) <= 2.0 * snap)).count();
            let tight = close as f64 * d.h >= 6.0 * snap;
            let long = length >= MIN_RUN * band || (at_end && length >= band) || tight;
            let crossing = !at_end && crosses(d, &idx, &cover, length, band);
            if !long || crossing || shares_a_point(d, &idx, &cover, band) {
                idx.iter().for_each(|&i| cover[i] = None);
                continue;
            }
            let mut onto: Vec<usize> = idx.iter().filter_map(|&i| cover[i]).map(|j| d.curve[j] as usize).collect();
            onto.sort_unstable();
            let onto = mode(&onto).unwrap_or(c);
            merges.push(Merge { curve: c, onto, at: d.pos[idx[idx.len() / 2]], length });
        }
        for i in s..e {
            kept[i] = cover[i].is_none();
        }
        // The kept runs are the pieces; those shorter than the gap are dropped.
        let whole = (s..e).all(|i| kept[i]);
        if whole {
            pieces_of[c].push(Piece::new(c, (s..e).collect(), d.closed[c]));
            continue;
        }
        for (a, b) in kept_runs(d, c, &kept) {
            let idx = run_indices(d, a, b);
            // A remnant beside removed overdraw: short, folded within a small extent (the
            // turn of a retrace), or lying within the gap of kept strokes all along (the rest
            // of a retrace that strayed further from the way out than the band).
            let extent = idx.iter().map(|&i| d.pos[i].distance(d.pos[idx[0]])).fold(0.0, f64::max);
            let short = run_length(d, a, b) < 2.0 * gap || extent < 1.5 * gap || idx.len() < 2;
            if short || lies_along(d, &idx, gap, &kept) {
                idx.iter().for_each(|&i| kept[i] = false);
                dropped += 1;
                continue;
            }
            pieces_of[c].push(Piece::new(c, idx, false));
        }
    }
    let moved = average_into(d, &cover, &kept);
    Overdraw { pieces: pieces_of.into_iter().flatten().collect(), merges, dropped, moved }
}

/// Every point of `idx` has a kept point other than those of `idx` within `gap`.
fn lies_along(d: &Dense, idx: &[usize], gap: f64, kept: &[bool]) -> bool {
    // (A closed curve's run may wrap through its first point: not a range.)
    let mut sorted = idx.to_vec();
    sorted.sort_unstable();
    let mine = |j: usize| sorted.binary_search(&j).is_ok();
    idx.iter().all(|&i| {
        let mut hit = false;
        d.near(d.pos[i], gap, |j| hit |= kept[j] && !mine(j));
        hit
    })
}

/// A covered run that passes from one side of the covering stroke to the other at an angle —
/// its mean offset across the stroke over its first quarter and over its last point to opposite
/// sides (each a fifth of the band off it) and differ by more than [`CROSSING_DEGREES`] over
/// the distance between them — is a shallow crossing of another stroke, left to node finding;
/// overdraw keeps its side, jitter aside. (Runs at a stroke's end are not tested: an end
/// drawn along a stroke is merged, whatever its angle.)
fn crosses(d: &Dense, idx: &[usize], cover: &[Option<usize>], length: f64, band: f64) -> bool {
    let offset = |i: usize| {
        cover[i].map_or(DVec3::ZERO, |j| {
            let o = d.pos[i] - d.pos[j];
            o - d.tan[j] * o.dot(d.tan[j])
        })
    };
    let q = (idx.len() / 4).max(1);
    let mean = |part: &[usize]| part.iter().map(|&i| offset(i)).sum::<DVec3>() / part.len() as f64;
    let (a, b) = (mean(&idx[..q]), mean(&idx[idx.len() - q..]));
    let clear = |o: DVec3| o.length() > 0.2 * band;
    let other = idx.iter().filter_map(|&i| cover[i]).all(|j| d.curve[j] != d.curve[idx[0]]);
    other
        && clear(a)
        && clear(b)
        && a.dot(b) < 0.0
        && a.distance(b) > CROSSING_DEGREES.to_radians().sin() * 0.75 * length
}

/// A covered run that shares a point with a curve covering it — a vertex of both, as where
/// the curves of a neatened graph leave their node at a shallow angle — is a junction, not
/// overdraw: graphs with shared crossings are left as they are. A run that shares
/// [`DUPLICATE_SAMPLES`] samples or more is a stroke drawn again sample for sample (an exact
/// duplicate): overdraw.
fn shares_a_point(d: &Dense, idx: &[usize], cover: &[Option<usize>], band: f64) -> bool {
    let exact = 1e-9 * band;
    let ends = [idx[0], idx[idx.len() - 1]];
    let mut around: Vec<usize> = ends.iter().flat_map(|&i| [d.prev(i), Some(i), d.next(i)]).flatten().collect();
    around.retain(|i| !idx.contains(i));
    around.sort_unstable();
    around.dedup();
    let mut covering: Vec<u32> = idx.iter().filter_map(|&i| cover[i]).map(|j| d.curve[j]).collect();
    covering.sort_unstable();
    covering.dedup();
    // A shared vertex is an input sample of both curves.
    let shared = idx
        .iter()
        .copied()
        .chain(around)
        .filter(|&i| d.sample[i])
        .filter(|&i| {
            let mut shared = false;
            d.near(d.pos[i], exact, |j| {
                shared |= d.curve[j] != d.curve[i] && covering.binary_search(&d.curve[j]).is_ok()
            });
            shared
        })
        .take(DUPLICATE_SAMPLES)
        .count();
    shared > 0 && shared < DUPLICATE_SAMPLES
}

/// The most frequent value of a sorted list.
fn mode(sorted: &[usize]) -> Option<usize> {
    let mut best: Option<(usize, usize)> = None;
    let mut i = 0;
    while i < sorted.len() {
        let j = sorted[i..].iter().position(|&x| x != sorted[i]).map_or(sorted.len(), |k| i + k);
        if best.is_none_or(|b| j - i > b.1) {
            best = Some((sorted[i], j - i));
        }
        i = j;
    }
    best.map(|b| b.0)
}

/// The maximal runs `(first, last)` (inclusive, along the curve; a closed curve's run may wrap
/// through its first point) of points of curve `c` where `flag` holds.
fn runs_where(d: &Dense, c: usize, flag: impl Fn(usize) -> bool) -> Vec<(usize, usize)> {
    let (s, e) = d.ranges[c];
    let mut runs: Vec<(usize, usize)> = Vec::new();
    let mut i = s;
    while i < e {
        if !flag(i) {
            i += 1;
            continue;
        }
        let mut j = i;
        while j + 1 < e && flag(j + 1) {
            j += 1;
        }
        runs.push((i, j));
        i = j + 1;
    }
    // A closed curve's run through its seam: the last run continues into the first.
    if d.closed[c] && runs.len() > 1 {
        let (first, last) = (runs[0], runs[runs.len() - 1]);
        if first.0 == s && last.1 == e - 1 {
            runs.pop();
            runs[0] = (last.0, first.1);
        }
    }
    runs
}

fn covered_runs(d: &Dense, c: usize, cover: &[Option<usize>]) -> Vec<(usize, usize)> {
    runs_where(d, c, |i| cover[i].is_some())
}

fn kept_runs(d: &Dense, c: usize, kept: &[bool]) -> Vec<(usize, usize)> {
    runs_where(d, c, |i| kept[i])
}

/// The points of a run `(a, b)` in order (through the seam of a closed curve when `b < a`).
pub(super) fn run_indices(d: &Dense, a: usize, b: usize) -> Vec<usize> {
    let mut out = vec![a];
    let mut i = a;
    while i != b {
        match d.next(i) {
            Some(j) => i = j,
            None => break,
        }
        out.push(i);
    }
    out
}

/// Arc length of a run.
fn run_length(d: &Dense, a: usize, b: usize) -> f64 {
    let idx = run_indices(d, a, b);
    idx.windows(2).map(|w| d.pos[w[0]].distance(d.pos[w[1]])).sum()
}

/// Averages every covered point into the point that covers it: the kept point moves halfway
/// to the mean of the points it covers (each stroke drawn counts once, whatever its sampling),
/// normals summed where they point to the same side. The kept points between moved ones take
/// the mean of their neighbours' shifts (a few passes, so that the merged stretch joins the
/// rest of its curve smoothly). Returns the points moved.
fn average_into(d: &mut Dense, cover: &[Option<usize>], kept: &[bool]) -> Vec<bool> {
    let n = d.pos.len();
    let mut sum = vec![DVec3::ZERO; n];
    let mut nsum = vec![DVec3::ZERO; n];
    let mut count = vec![0usize; n];
    for i in 0..n {
        if let Some(j) = cover[i] {
            if !kept[j] {
                continue;
            }
            sum[j] += d.pos[i];
            count[j] += 1;
            if d.nrm[i].dot(d.nrm[j]) > 0.0 {
                nsum[j] += d.nrm[i];
            }
        }
    }
    let mut shift = vec![DVec3::ZERO; n];
    let mut moved = vec![false; n];
    for j in 0..n {
        if count[j] > 0 {
            shift[j] = 0.5 * (sum[j] / count[j] as f64 - d.pos[j]);
            d.nrm[j] = (d.nrm[j] + nsum[j] / count[j] as f64).normalize_or_zero();
            moved[j] = true;
        }
    }
    for _ in 0..4 {
        let old = shift.clone();
        for j in 0..n {
            if !kept[j] || count[j] > 0 {
                continue;
            }
            let side = |k: Option<usize>| k.filter(|&k| kept[k]).map_or(DVec3::ZERO, |k| old[k]);
            let s = 0.5 * (side(d.prev(j)) + side(d.next(j)));
            if s != DVec3::ZERO {
                shift[j] = s;
                moved[j] = true;
            }
        }
    }
    for j in 0..n {
        d.pos[j] += shift[j];
    }
    d.retangent();
    moved
}
