//! Consolidation: raw strokes as people draw them, made into a network whose curves meet —
//! the stage before node finding (docs/design.md §14). A 3D sketch's strokes nearly meet but
//! share no point, overshoot one another, are drawn twice or retraced, and jitter at their
//! ends; node finding ([`super::nodes`]) joins curves only within the snapping tolerance and
//! refuses curves that run along each other. Within a larger tolerance, the *gap*:
//!
//! 1. **Overdraw** (`overdraw.rs`): stretches of strokes that run along each other become one
//!    curve, their positions (and normals where given) averaged.
//! 2. **Jitter** (`ends.rs`): hooks and tiny loops at stroke ends are cut.
//! 3. **Gaps** (`ends.rs`): an end that stops short of a stroke or overshoots it becomes a
//!    junction on it (T, X); two ends that nearly meet, a corner (L) or a closed loop. In a
//!    sketch of loose strokes (fewer than half of the ends meet a stroke as drawn), an end
//!    still free is then carried on along its direction, up to three gaps (`ends.rs`),
//!    to the first stroke it points at.
//! 4. **Crossings** (`crossings.rs`): two strokes that pass each other at an angle within the
//!    gap, away from their ends, are moved to meet (an X drawn in the air).
//!
//! The strokes are worked on as dense polylines (`dense.rs`: points at most a quarter of the gap
//! apart, on the input polylines, in one spatial hash): O(n) hash queries of a bounded
//! neighbourhood each. A network in which nothing is within reach of these rules — every
//! curve end on another curve or free beyond the gap, no overdraw — comes back exactly as it
//! was given (clean networks and every network with shared crossings are not touched).
//!
//! The default gap follows the sketch, not its units: [`GAP_OVER_P90`] times the 90th
//! percentile of the distances from a stroke end to the nearest other stroke, between
//! [`MIN_GAP`] and [`MAX_GAP`] of the bounding-box diagonal (and at least twice the snapping
//! tolerance).

mod crossings;
mod dense;
mod ends;
mod overdraw;

use crate::error::{Result, Warning};
use crate::geom::{fmt_point, DVec3};
use crate::network::{Curve, Network};
use crate::solve::timing::{seconds_since, Instant};
use dense::Dense;
use serde::Serialize;

/// Smallest default gap, relative to the bounding-box diagonal.
pub const MIN_GAP: f64 = 0.005;
/// Largest default gap, relative to the bounding-box diagonal.
pub const MAX_GAP: f64 = 0.02;
/// Overdraw band: strokes within this fraction of the gap of each other, running the same way,
/// are one stroke drawn twice.
pub const OVERDRAW_BAND: f64 = 0.5;
/// The default gap over the 90th percentile of the stroke ends' distances to other strokes.
pub const GAP_OVER_P90: f64 = 1.25;
/// At most this many dense points (the spacing grows on very large networks).
const MAX_DENSE_POINTS: f64 = 4e6;

/// The consolidation options (`consolidate`, `gap`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ConsolidateOptions {
    /// `consolidate`: run the stage (default on).
    pub enabled: bool,
    /// `gap`: the tolerance (a distance). `None`: from the sketch (module documentation).
    pub gap: Option<f64>,
}

impl Default for ConsolidateOptions {
    fn default() -> Self {
        ConsolidateOptions { enabled: true, gap: None }
    }
}

/// What consolidation did (the `consolidation` of `--stats`).
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct Consolidation {
    /// The gap tolerance used.
    pub gap: f64,
    /// Stroke ends joined to another stroke (T, X, L junctions, loops closed).
    pub joined: usize,
    /// Crossings of two strokes' interiors that missed within the gap, moved to meet.
    pub crossed: usize,
    /// Overdrawn stretches merged into the stroke they run along.
    pub merged: usize,
    /// Hooks, loops and stubs cut from stroke ends, and remnants left out.
    pub trimmed: usize,
    /// Curves given.
    pub curves_in: usize,
    /// Curves after consolidation.
    pub curves_out: usize,
    /// Seconds.
    pub seconds: f64,
}

/// A consolidated network.
#[derive(Clone, Debug)]
pub struct Consolidated {
    /// The network (the input itself when nothing was changed).
    pub network: Network,
    /// What was done.
    pub report: Consolidation,
    /// One warning per kind of change, with places.
    pub warnings: Vec<Warning>,
}

impl Consolidated {
    /// Something was changed.
    pub fn changed(&self) -> bool {
        let r = &self.report;
        r.joined + r.crossed + r.merged + r.trimmed > 0
    }
}

/// A stroke end that runs within this many snapping tolerances of another stroke from where it
/// meets it is cut back to where they part (`ends::trim_end_runs`): node finding's
/// tolerance, at which it refuses curves that stay together.
pub const END_RUN_TOLERANCE: f64 = 1.0;
/// ... when that run, measured on the dense points (a quarter gap apart), is at least this many
/// snapping tolerances long: node finding refuses two curves still within the tolerance 5, 10
/// and 20 tolerances from their meeting; shorter runs are one meeting there, left as drawn.
/// With the default gap (mostly 10–40 tolerances) a run of 20 is seen as 15 or more; with a
/// gap over 60 tolerances the dense points may be too far apart to see it, and node finding's
/// refusal stands.
pub const END_RUN_MIN: f64 = 15.0;

/// A stretch of a stroke being consolidated: dense points in order, an added point at either
/// end (a junction on another stroke), and what happened to it.
pub(super) struct Piece {
    pub(super) curve: usize,
    pub(super) idx: Vec<usize>,
    pub(super) closed: bool,
    pub(super) ends: [Option<DVec3>; 2],
    pub(super) joined: [bool; 2],
    pub(super) changed: bool,
}

impl Piece {
    fn new(curve: usize, idx: Vec<usize>, closed: bool) -> Self {
        Piece { curve, idx, closed, ends: [None; 2], joined: [false; 2], changed: false }
    }

    fn length(&self, d: &Dense) -> f64 {
        self.idx.windows(2).map(|w| d.pos[w[0]].distance(d.pos[w[1]])).sum()
    }

    /// Ends the piece's `side` at the junction `q` (on another stroke), dropping the end
    /// points within `near` of it (node finding would see them as a second meeting there) and
    /// those where the way to `q` turns back by more than 90° (what is left of a hook).
    fn end_at(&mut self, d: &Dense, side: usize, q: DVec3, near: f64) {
        while self.idx.len() > 2 {
            let n = self.idx.len();
            let (j, k) = if side == 0 { (self.idx[0], self.idx[1]) } else { (self.idx[n - 1], self.idx[n - 2]) };
            let folds = (q - d.pos[j]).dot(d.pos[j] - d.pos[k]) < 0.0;
            if d.pos[j].distance(q) > near && !folds {
                break;
            }
            if side == 0 {
                self.idx.remove(0);
            } else {
                self.idx.pop();
            }
        }
        self.ends[side] = Some(q);
        self.joined[side] = true;
        self.changed = true;
    }

    /// Cuts the piece so that its `side` end (0 first, 1 last) is at position `k`.
    fn cut_to(&mut self, side: usize, k: usize) {
        if side == 0 {
            self.idx.drain(..k);
        } else {
            self.idx.truncate(k + 1);
        }
    }
}

/// Consolidates the strokes of `network` (see the module documentation); `snap` the
/// snapping tolerance of the run (`None`: the network's). Errors: those of
/// [`Network::validated`].
pub fn consolidate(network: &Network, options: &ConsolidateOptions, snap: Option<f64>) -> Result<Consolidated> {
    let start = Instant::now();
    let unchanged = |gap: f64| Consolidated {
        network: network.clone(),
        report: Consolidation {
            gap,
            curves_in: network.curves.len(),
            curves_out: network.curves.len(),
            seconds: seconds_since(start),
            ..Default::default()
        },
        warnings: Vec::new(),
    };
    if !options.enabled {
        return Ok(unchanged(0.0));
    }
    let (net, _) = network.validated()?;
    let snap = snap.or(net.snap).unwrap_or_else(|| net.snap_tolerance());
    let diag = net.bounding_box().diagonal();
    let total: f64 = net.curves.iter().map(curve_length).sum();
    let spacing = |gap: f64| (0.25 * gap).max(total / MAX_DENSE_POINTS);
    let gap = match options.gap {
        Some(g) => g,
        None => {
            let probe = Dense::new(&net.curves, spacing(MAX_GAP * diag), MAX_GAP * diag);
            default_gap(&probe, &net.curves, diag, snap)
        }
    };
    // An open boundary curve is an error of its own (node finding names it): not repaired here.
    if !(gap > snap) || net.curves.iter().any(|c| c.boundary && !c.closed) {
        return Ok(unchanged(gap));
    }
    let mut d = Dense::new(&net.curves, spacing(gap), gap);
    // Creases and boundary curves are the network's own: never merged into another or moved.
    let fixed: Vec<bool> = net.curves.iter().map(|c| c.is_crease() || c.boundary).collect();
    let od = overdraw::merge_overdraw(&mut d, OVERDRAW_BAND * gap, gap, snap, &fixed);
    let mut pieces = od.pieces;
    let mut hooks = ends::trim_hooks(&d, &mut pieces, gap);
    hooks.extend(ends::trim_retraces(&d, &mut pieces, gap));
    let runs = ends::trim_end_runs(&d, &mut pieces, END_RUN_TOLERANCE * snap, END_RUN_MIN * snap, gap, &fixed);
    let gaps = ends::close_gaps(&d, &mut pieces, gap, snap, &fixed);
    let junctions: Vec<DVec3> = gaps.joins.iter().map(|j| j.2).collect();
    let mut moved = od.moved;
    // Strokes whose ends were drawn onto other strokes (a graph, neatened or drawn with shared
    // points) meet where they were meant to: their interiors' near misses are left as drawn.
    let crossings = if gaps.joins.len() > gaps.met {
        crossings::join_crossings(&mut d, &pieces, gap, snap, &fixed, &junctions, &mut moved)
    } else {
        Vec::new()
    };
    if od.merges.is_empty()
        && od.dropped == 0
        && hooks.is_empty()
        && runs.is_empty()
        && gaps.joins.is_empty()
        && gaps.stubs.is_empty()
        && crossings.is_empty()
    {
        return Ok(unchanged(gap));
    }
    let curves = emit(&d, &net.curves, &pieces, &moved);
    let labels: Vec<String> = crate::network::curve_labels(&net.curves);
    let mut warnings = warnings(&labels, &od.merges, &hooks, &gaps, od.dropped, gap);
    warnings.extend(crossing_warning(&labels, &crossings, gap));
    warnings.extend(end_run_warning(&labels, &runs, snap));
    let report = Consolidation {
        gap,
        joined: gaps.joins.len(),
        crossed: crossings.len(),
        merged: od.merges.len(),
        trimmed: hooks.len() + runs.len() + gaps.stubs.len() + od.dropped,
        curves_in: net.curves.len(),
        curves_out: curves.len(),
        seconds: seconds_since(start),
    };
    // The tolerance the strokes were consolidated with, also for node finding (the default
    // follows the mean sample spacing, which the changed strokes no longer have).
    Ok(Consolidated { network: Network { curves, snap: Some(snap), cycles: None }, report, warnings })
}

/// The warning for the ends cut back where they ran along another stroke (one for all).
fn end_run_warning(labels: &[String], runs: &[ends::EndRun], snap: f64) -> Option<Warning> {
    let first = runs.first()?;
    let places: Vec<String> = runs
        .iter()
        .take(3)
        .map(|r| format!("{} along {} to {} ({:.3e} cut)", labels[r.curve], labels[r.along], fmt_point(r.at), r.length))
        .collect();
    let more = if runs.len() > 3 { format!(" and {} more", runs.len() - 3) } else { String::new() };
    Some(
        Warning::new(format!(
            "consolidation: {} stroke end(s) that ran along another stroke from where they meet it (within {:.3e}, \
             a sharp tip or a stroke drawn along another) were cut back to where they part: {}{more}",
            runs.len(),
            END_RUN_TOLERANCE * snap,
            places.join("; ")
        ))
        .curve(first.curve),
    )
}

fn curve_length(c: &Curve) -> f64 {
    let n = c.points.len();
    let m = if c.closed { n } else { n.saturating_sub(1) };
    (0..m).map(|i| c.points[i].distance(c.points[(i + 1) % n])).sum()
}

/// [`GAP_OVER_P90`] times the 90th percentile of the distances from an open curve's end to the
/// nearest other curve (or the same curve four gaps along it; capped at [`MAX_GAP`] of the
/// diagonal), between [`MIN_GAP`] and [`MAX_GAP`] of it and at least twice `snap`: nearly
/// every end of a sketch is meant to meet a stroke, detail strokes aside.
fn default_gap(d: &Dense, curves: &[Curve], diag: f64, snap: f64) -> f64 {
    let reach = MAX_GAP * diag;
    let mut dists: Vec<f64> = Vec::new();
    for (c, curve) in curves.iter().enumerate() {
        if curve.closed {
            continue;
        }
        let (s, e) = d.ranges[c];
        for end in [s, e - 1] {
            let mut best = reach;
            d.near(d.pos[end], reach, |j| {
                if d.curve[j] as usize != c || d.along(end, j) > 4.0 * reach {
                    best = best.min(d.pos[j].distance(d.pos[end]));
                }
            });
            dists.push(best);
        }
    }
    if dists.is_empty() {
        return (MIN_GAP * diag).max(2.0 * snap);
    }
    dists.sort_by(f64::total_cmp);
    let p90 = dists[(dists.len() * 9 / 10).min(dists.len() - 1)];
    (GAP_OVER_P90 * p90).clamp(MIN_GAP * diag, MAX_GAP * diag).max(2.0 * snap)
}

/// The consolidated curves: an untouched curve as it was given (named by its input place,
/// [`crate::network::position_name`], when it had no name); each piece of a changed one
/// with its input samples, the points it gained (junctions, cut ends) and its averaged points.
fn emit(d: &Dense, input: &[Curve], pieces: &[Piece], moved: &[bool]) -> Vec<Curve> {
    let mut out = Vec::new();
    let mut k = 0;
    for (c, curve) in input.iter().enumerate() {
        let mine: Vec<&Piece> = pieces[k..].iter().take_while(|p| p.curve == c).collect();
        k += mine.len();
        let (s, e) = d.ranges[c];
        let whole = mine.len() == 1
            && !mine[0].changed
            && mine[0].closed == curve.closed
            && mine[0].idx.len() == e - s
            && !mine[0].idx.iter().any(|&j| moved[j]);
        if whole {
            // Named by its input place when unnamed, as the changed ones are: the numbers in
            // messages stay the input's (issue 33).
            let mut kept = curve.clone();
            kept.name.get_or_insert_with(|| crate::network::position_name(c));
            out.push(kept);
            continue;
        }
        let base = curve.name.clone().unwrap_or_else(|| crate::network::position_name(c));
        let many = mine.len() > 1;
        for (n, p) in mine.iter().enumerate() {
            let keep = |t: usize, j: usize| t == 0 || t + 1 == p.idx.len() || d.sample[j] || moved[j];
            let mut pts: Vec<DVec3> = Vec::new();
            let mut nrm: Vec<DVec3> = Vec::new();
            let first = p.idx[0];
            let last = p.idx[p.idx.len() - 1];
            if let Some(q) = p.ends[0] {
                pts.push(q);
                nrm.push(d.nrm[first]);
            }
            for (t, &j) in p.idx.iter().enumerate() {
                if keep(t, j) {
                    pts.push(d.pos[j]);
                    nrm.push(d.nrm[j]);
                }
            }
            if let Some(q) = p.ends[1] {
                pts.push(q);
                nrm.push(d.nrm[last]);
            }
            unfold_ends(&mut pts, &mut nrm);
            drop_close(&mut pts, &mut nrm, dense::FINEST * d.h);
            if pts.len() < 2 || (p.closed && pts.len() < 3) {
                continue;
            }
            let normals = if curve.has_normals() && nrm.len() == pts.len() { nrm } else { Vec::new() };
            let name = if many { format!("{base} part {}", n + 1) } else { base.clone() };
            out.push(Curve {
                name: Some(name),
                points: pts,
                normals,
                normals_right: Vec::new(),
                closed: p.closed,
                boundary: curve.boundary,
            });
        }
    }
    out
}

/// Removes the points closer than `min` to the point kept before them (the ends stay): an
/// averaged or moved point next to an input sample can land a hair's breadth from it, and the
/// chord between them — a random direction — would be the curve's tangent there (a given
/// normal along it is refused).
fn drop_close(pts: &mut Vec<DVec3>, nrm: &mut Vec<DVec3>, min: f64) {
    let n = pts.len();
    if n < 3 {
        pts.dedup_by(|a, b| a.distance(*b) == 0.0);
        nrm.truncate(pts.len());
        return;
    }
    let mut keep = vec![false; n];
    keep[0] = true;
    let mut last = 0;
    for i in 1..n - 1 {
        if pts[i].distance(pts[last]) >= min {
            keep[i] = true;
            last = i;
        }
    }
    keep[n - 1] = true;
    if last > 0 && pts[n - 1].distance(pts[last]) < min {
        keep[last] = false;
    }
    let mut flags = keep.iter();
    pts.retain(|_| flags.next().is_some_and(|&f| f));
    let mut flags = keep.iter();
    nrm.retain(|_| flags.next().is_some_and(|&f| f));
}

/// Removes the samples next to either end where the curve turns back by more than 120° (a
/// junction reached by folding back over the last stretch): the end sample itself is kept.
fn unfold_ends(pts: &mut Vec<DVec3>, nrm: &mut Vec<DVec3>) {
    for _ in 0..2 {
        while pts.len() > 2 {
            let d0 = (pts[0] - pts[1]).normalize_or_zero();
            let d1 = (pts[1] - pts[2]).normalize_or_zero();
            if d0.dot(d1) >= -0.5 {
                break;
            }
            pts.remove(1);
            nrm.remove(1);
        }
        pts.reverse();
        nrm.reverse();
    }
}

/// The warning for the crossings made, naming the first few.
fn crossing_warning(labels: &[String], crossings: &[crossings::Crossing], gap: f64) -> Option<Warning> {
    let first = crossings.first()?;
    let shown: Vec<String> = crossings
        .iter()
        .take(3)
        .map(|x| format!("{} and {} at {}", labels[x.curves[0]], labels[x.curves[1]], fmt_point(x.at)))
        .collect();
    let more = if crossings.len() > 3 { format!(" and {} more", crossings.len() - 3) } else { String::new() };
    let widest = crossings.iter().map(|x| x.miss).fold(0.0, f64::max);
    Some(
        Warning::new(format!(
            "consolidation: {} crossing(s) of strokes that passed each other within the gap ({gap:.3e}; the widest \
             {widest:.3e} apart) were moved to meet: {}{more}",
            crossings.len(),
            shown.join("; ")
        ))
        .curve(first.curves[0]),
    )
}

/// One warning per kind of change, naming the first few places.
fn warnings(
    labels: &[String],
    merges: &[overdraw::Merge],
    hooks: &[(usize, DVec3)],
    gaps: &ends::Gaps,
    dropped: usize,
    gap: f64,
) -> Vec<Warning> {
    let list = |items: Vec<(usize, String)>| -> (String, Option<usize>) {
        let shown: Vec<String> = items.iter().take(3).map(|x| x.1.clone()).collect();
        let more = if items.len() > 3 { format!(" and {} more", items.len() - 3) } else { String::new() };
        (format!("{}{more}", shown.join("; ")), items.first().map(|x| x.0))
    };
    let mut out = Vec::new();
    let mut push = |text: String, first: Option<usize>| {
        let w = Warning::new(text);
        out.push(match first {
            Some(c) => w.curve(c),
            None => w,
        });
    };
    if !gaps.joins.is_empty() {
        let (places, first) = list(
            gaps.joins
                .iter()
                .map(|&(c, t, q)| (c, format!("{} onto {} at {}", labels[c], labels[t], fmt_point(q))))
                .collect(),
        );
        push(
            format!(
                "consolidation: {} stroke end(s) that stopped short of or overshot another stroke within the gap \
                 ({gap:.3e}){} were joined to it: {places} (`consolidate = off` keeps the strokes as drawn)",
                gaps.joins.len(),
                match gaps.extended {
                    0 => String::new(),
                    n => format!(
                        " or pointed at it within {:.3e} ({n} of them, carried on along their direction)",
                        ends::EXTEND_REACH * gap
                    ),
                }
            ),
            first,
        );
    }
    if !merges.is_empty() {
        let (places, first) = list(
            merges
                .iter()
                .map(|m| {
                    let onto = if m.onto == m.curve { "itself".to_string() } else { labels[m.onto].clone() };
                    (
                        m.curve,
                        format!("{} along {onto} near {} ({:.3e} long)", labels[m.curve], fmt_point(m.at), m.length),
                    )
                })
                .collect(),
        );
        push(
            format!(
                "consolidation: {} overdrawn stretch(es) (strokes drawn twice, retraced or along another within \
                 {:.3e}) were merged into one curve, their positions averaged: {places}",
                merges.len(),
                OVERDRAW_BAND * gap
            ),
            first,
        );
    }
    let trims = hooks.len() + gaps.stubs.len() + dropped;
    if trims > 0 {
        let items: Vec<(usize, String)> =
            hooks.iter().chain(&gaps.stubs).map(|&(c, q)| (c, format!("{} at {}", labels[c], fmt_point(q)))).collect();
        let (places, first) = list(items);
        push(
            format!(
                "consolidation: {trims} hook(s), loop(s) and stub(s) shorter than the gap ({gap:.3e}) were trimmed from \
                 stroke ends{}{places}",
                if places.is_empty() { String::new() } else { ": ".to_string() }
            ),
            first,
        );
    }
    out
}

#[cfg(test)]
#[path = "tests/consolidate.rs"]
mod tests;
