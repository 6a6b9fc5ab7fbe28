//! Stroke ends: jitter trimmed (hooks and tiny loops), then gaps closed — an end that stops
//! short of another stroke, or overshoots it, within the gap becomes a junction on it (a T or an
//! X), and two ends that nearly meet become one corner (an L), or close their stroke (a loop).
//!
//! An end is looked at over its *window*, the last gap of arc length of its piece. For each
//! window point the nearest point of the other pieces (or of the same piece, more than four
//! gaps along it) is found in the dense hash. An end already within the snapping tolerance of
//! another stroke meets it (node finding joins them): left as drawn. Where the window comes
//! closest inside (an overshoot: the stroke passed the other one), the stub beyond is cut and
//! the end set on the other stroke; otherwise an end within the gap is extended to the nearest
//! point. A junction that lands within the window of the other stroke's own free end is that
//! end's too (an L-corner, or the loop of a stroke whose ends nearly meet).

use super::dense::Dense;
use super::Piece;
use crate::geom::DVec3;

/// A point of a piece's dense polyline nearest to a query: its distance, position, piece, and
/// the dense point at the segment's nearer end.
#[derive(Clone, Copy)]
struct Near {
    dist: f64,
    q: DVec3,
    piece: usize,
    k: usize,
}

/// Where each dense point sits: `(piece, position in it)`.
struct Slots(Vec<Option<(u32, u32)>>);

impl Slots {
    fn new(n: usize, pieces: &[Piece]) -> Self {
        let mut s = Slots(vec![None; n]);
        for p in 0..pieces.len() {
            s.set(pieces, p);
        }
        s
    }

    fn set(&mut self, pieces: &[Piece], p: usize) {
        for (k, &j) in pieces[p].idx.iter().enumerate() {
            self.0[j] = Some((p as u32, k as u32));
        }
    }

    fn clear(&mut self, idx: &[usize]) {
        idx.iter().for_each(|&j| self.0[j] = None);
    }
}

/// Cuts the hooks and tiny loops at the ends of the open pieces: within the last gap of arc
/// length (a third of a piece shorter than three gaps), the innermost point where the stroke
/// turns by more than 120°, or (pieces at least three gaps long) after which it runs more than
/// 90° away from its body's direction (that of the stretch one to two gaps from the end),
/// becomes the end. Returns `(curve, where)` per end trimmed.
pub(super) fn trim_hooks(d: &Dense, pieces: &mut [Piece], gap: f64) -> Vec<(usize, DVec3)> {
    let mut out = Vec::new();
    for piece in pieces.iter_mut() {
        let length = piece.length(d);
        if piece.closed || piece.idx.len() < 3 {
            continue;
        }
        // Short pieces: a window of a third of their length, sharp turns only.
        let (window, body_rule) = if length >= 3.0 * gap { (gap, true) } else { (length / 3.0, false) };
        for side in 0..2 {
            let seq: Vec<usize> = if side == 0 { piece.idx.clone() } else { piece.idx.iter().rev().copied().collect() };
            let at = |s: f64| seq.iter().copied().find(|&j| d.along(seq[0], j) >= s).unwrap_or(seq[seq.len() - 1]);
            let body = (d.pos[at(gap)] - d.pos[at(2.0 * gap)]).normalize_or_zero();
            let mut cut = None;
            for k in 1..seq.len() - 1 {
                if d.along(seq[0], seq[k]) > window {
                    break;
                }
                let out_dir = (d.pos[seq[k - 1]] - d.pos[seq[k]]).normalize_or_zero();
                let in_dir = (d.pos[seq[k]] - d.pos[seq[k + 1]]).normalize_or_zero();
                // A turn of more than 120° (a hairpin), or, on long pieces, a way back against
                // the body's direction.
                if out_dir.dot(in_dir) < -0.5 || (body_rule && out_dir.dot(body) < 0.0) {
                    cut = Some(k);
                }
            }
            if let Some(k) = cut {
                out.push((piece.curve, d.pos[seq[0]]));
                if side == 0 {
                    piece.idx.drain(..k);
                } else {
                    let len = piece.idx.len();
                    piece.idx.truncate(len - k);
                }
                piece.changed = true;
            }
        }
    }
    out
}

/// Cuts the retraced ends of the open pieces that overdraw left (the way back deviates from the
/// way out by more than its band, or at more than its angle, as where a coarsely sampled stroke
/// is retraced across a corner it turned): where the stroke turns back by more than 120° (over
/// half a gap either side) and everything after the turn, up to half the piece, stays within a
/// gap of the piece before it, the turn becomes the end — the stroke's one pass is kept. An end
/// that is a point of another curve is left. Returns `(curve, where)` per end cut.
pub(super) fn trim_retraces(d: &Dense, pieces: &mut [Piece], gap: f64) -> Vec<(usize, DVec3)> {
    let mut out = Vec::new();
    for piece in pieces.iter_mut() {
        // Open pieces along their curve in order (every dense point of a stretch): the rest of
        // the piece is an index range.
        let ordered = piece.idx.windows(2).all(|w| w[1] == w[0] + 1);
        if piece.closed || piece.idx.len() < 8 || !ordered {
            continue;
        }
        let length = piece.length(d);
        for side in 0..2 {
            let seq: Vec<usize> = if side == 0 { piece.idx.clone() } else { piece.idx.iter().rev().copied().collect() };
            // An end that is a point of another curve (a node of a network with shared
            // crossings) is where it was meant to be: never cut.
            let mut meets = false;
            d.near(d.pos[seq[0]], 1e-9 * gap, |j| meets |= d.curve[j] as usize != piece.curve);
            if meets {
                continue;
            }
            let Some(k) = retrace_turn(d, &seq, gap, 0.5 * length) else { continue };
            out.push((piece.curve, d.pos[seq[0]]));
            if side == 0 {
                piece.idx.drain(..k);
            } else {
                let len = piece.idx.len();
                piece.idx.truncate(len - k);
            }
            piece.changed = true;
        }
    }
    out
}

/// One end cut back where it ran along another stroke: the curve, the curve it ran along, where
/// it ends now, and the length cut.
pub(super) struct EndRun {
    pub(super) curve: usize,
    pub(super) along: usize,
    pub(super) at: DVec3,
    pub(super) length: f64,
}

/// Cuts back the ends of the open pieces that run along another stroke from where they meet it
/// — within `tol` (the snapping tolerance) for at least `min_run` (more than node finding
/// takes for one meeting) and at most two gaps (longer runs are overdraw's) — to where they
/// part: a leaf's two outline strokes and its midrib that end at its tip and coincide over its
/// last few samples, a stroke that ends on another and was drawn along it for a stretch. Node
/// finding refuses such ends (curves that run within the tolerance of each other); cut back,
/// each is an end near the other stroke, which the gap rule makes a junction on it. Shorter
/// pieces are cut first (the longest keeps a shared tip); creases and boundary curves
/// (`fixed`) are never cut, and what remains of a piece is at least as long as its cut and a
/// gap. Returns the ends cut.
pub(super) fn trim_end_runs(
    d: &Dense,
    pieces: &mut [Piece],
    tol: f64,
    min_run: f64,
    gap: f64,
    fixed: &[bool],
) -> Vec<EndRun> {
    let mut slots = Slots::new(d.pos.len(), pieces);
    let lengths: Vec<f64> = pieces.iter().map(|p| p.length(d)).collect();
    let mut order: Vec<usize> = (0..pieces.len()).collect();
    order.sort_by(|&a, &b| lengths[a].total_cmp(&lengths[b]).then(a.cmp(&b)));
    let mut out = Vec::new();
    for p in order {
        if pieces[p].closed || fixed[pieces[p].curve] {
            continue;
        }
        for side in 0..2 {
            let n = pieces[p].idx.len();
            if n < 3 {
                break;
            }
            let seq: Vec<usize> =
                if side == 0 { pieces[p].idx.clone() } else { pieces[p].idx.iter().rev().copied().collect() };
            let Some(first) = nearest_other(d, pieces, &slots, p, seq[0], tol) else { continue };
            // The end's run along other strokes: the dense points within `tol` of one.
            let runs_on = |k: usize| nearest_other(d, pieces, &slots, p, seq[k], tol).is_some();
            let mut k = 1;
            while k < n && d.along(seq[0], seq[k]) <= 2.0 * gap && runs_on(k) {
                k += 1;
            }
            // Still along past two gaps: overdraw's (or no end's), left to node finding.
            if k >= n - 1 || runs_on(k) {
                continue;
            }
            let (run, cut_length) = (d.along(seq[0], seq[k - 1]), d.along(seq[0], seq[k]));
            let rest = pieces[p].length(d) - cut_length;
            if run < min_run || rest < cut_length.max(gap) {
                continue;
            }
            // `seq[k]` becomes the end.
            let cut: Vec<usize> = seq[..k].to_vec();
            let piece = &mut pieces[p];
            if side == 0 {
                piece.idx.drain(..k);
            } else {
                piece.idx.truncate(n - k);
            }
            piece.changed = true;
            slots.clear(&cut);
            slots.set(pieces, p);
            out.push(EndRun {
                curve: pieces[p].curve,
                along: pieces[first.piece].curve,
                at: d.pos[seq[k]],
                length: cut_length,
            });
        }
    }
    out
}

/// The innermost turn `k` of `seq` (an end first, within `reach` of it along) after which the
/// end's arm `seq[..k]` stays within `gap` of `seq[k..]`; `None` without one.
fn retrace_turn(d: &Dense, seq: &[usize], gap: f64, reach: f64) -> Option<usize> {
    let a = ((0.5 * gap / d.h).ceil() as usize).max(1);
    let (lo, hi) = (seq[0].min(seq[seq.len() - 1]), seq[0].max(seq[seq.len() - 1]));
    let mut best = None;
    for k in a..seq.len().saturating_sub(a) {
        if d.along(seq[0], seq[k]) > reach {
            break;
        }
        let back = (d.pos[seq[k - a]] - d.pos[seq[k]]).normalize_or_zero();
        let on = (d.pos[seq[k + a]] - d.pos[seq[k]]).normalize_or_zero();
        // Back and on both leave the turn the same way (within 60°): a hairpin.
        if back.dot(on) < 0.5 || d.along(seq[0], seq[k]) < gap {
            continue;
        }
        // Every point of the arm has a point of the rest within the gap.
        let rest = |j: usize| {
            (lo..=hi).contains(&j)
                && (j as isize - seq[k] as isize).signum() == (seq[seq.len() - 1] as isize - seq[k] as isize).signum()
        };
        let covered = seq[..k].iter().all(|&i| {
            let mut hit = false;
            d.near(d.pos[i], gap, |j| hit |= j == seq[k] || rest(j));
            hit
        });
        if covered {
            best = Some(k);
        }
    }
    best
}

/// What gap closing did: `(curve, curve joined, where)` per end joined, `(curve, where)` per
/// stub cut, and how many ends met another stroke as drawn (within the snapping tolerance).
pub(super) struct Gaps {
    pub(super) joins: Vec<(usize, usize, DVec3)>,
    pub(super) stubs: Vec<(usize, DVec3)>,
    pub(super) met: usize,
    /// Of the joins, those made along the end's direction beyond the gap ([`EXTEND_REACH`]).
    pub(super) extended: usize,
}

/// How far, in gaps, an end that stops short of every stroke by more than the gap is carried
/// on along its direction to meet one (a stroke drawn towards another and released early).
pub(super) const EXTEND_REACH: f64 = 3.0;
/// The widest miss of that extension, in gaps, sideways from the end's direction (and at most
/// `tan 30°` of the distance along it).
const EXTEND_MISS: f64 = 0.5;

/// Closes the gaps at the free ends of the open `pieces` (see the module documentation):
/// within `gap`, ends within `snap` of another stroke left as they are. `fixed[c]`: the ends of
/// curve `c` are not moved (a crease).
pub(super) fn close_gaps(d: &Dense, pieces: &mut [Piece], gap: f64, snap: f64, fixed: &[bool]) -> Gaps {
    let mut slots = Slots::new(d.pos.len(), pieces);
    let mut out = Gaps { joins: Vec::new(), stubs: Vec::new(), met: 0, extended: 0 };
    for p in 0..pieces.len() {
        for side in 0..2 {
            if pieces[p].closed || pieces[p].joined[side] || fixed[pieces[p].curve] || pieces[p].idx.len() < 2 {
                continue;
            }
            let seq: Vec<usize> = window(d, &pieces[p], side, gap);
            let hits: Vec<Option<Near>> =
                seq.iter().map(|&k| nearest(d, pieces, &slots, p, pieces[p].idx[k], gap)).collect();
            let first = hits[0].map_or(f64::INFINITY, |h| h.dist);
            if first <= snap {
                pieces[p].joined[side] = true;
                out.met += 1;
                continue;
            }
            let best =
                (0..hits.len()).filter_map(|k| hits[k].map(|h| (k, h))).min_by(|a, b| a.1.dist.total_cmp(&b.1.dist));
            let Some((kmin, hit)) = best else { continue };
            let overshoot = kmin > 0 && hit.dist <= (0.5 * gap).min(0.5 * first);
            let (hit, cut) = if overshoot {
                (hit, Some(seq[kmin]))
            } else if let Some(h) = hits[0] {
                (h, None)
            } else {
                continue;
            };
            slots.clear(&pieces[p].idx);
            if let Some(k) = cut {
                out.stubs.push((pieces[p].curve, d.pos[pieces[p].idx[seq[0]]]));
                pieces[p].cut_to(side, k);
            }
            pieces[p].end_at(d, side, hit.q, 2.0 * snap);
            slots.set(pieces, p);
            out.joins.push((pieces[p].curve, pieces[hit.piece].curve, hit.q));
            if !fixed[pieces[hit.piece].curve] {
                corner(d, pieces, &mut slots, p, hit, gap, snap, &mut out);
            }
        }
    }
    // Only in a sketch of loose strokes: where most ends met a stroke as drawn (a neatened
    // graph, a CAD export: 79–100 % of the ends of the vendored neatened sketches, 10–25 % of
    // the raw ones), an end left free is meant free.
    let ends = 2 * pieces.iter().filter(|p| !p.closed).count();
    if 2 * out.met < ends {
        extend_ends(d, pieces, &mut slots, gap, snap, fixed, &mut out);
    }
    out
}

/// The second pass of gap closing: a free end with no stroke within the gap, of a piece at
/// least two gaps long, is carried on along its direction (the chord of its last gap of arc
/// length) to the first stroke that this ray passes within [`EXTEND_MISS`] gaps of, at most
/// [`EXTEND_REACH`] gaps away — a stroke drawn towards another and released early (raw VR
/// sketches leave ends 2–3 % of the diagonal short, past any isotropic gap that does not
/// also merge neighbouring strokes). The hit becomes a junction as in the first pass
/// (an L-corner where it lands within a gap of the other stroke's free end).
fn extend_ends(
    d: &Dense,
    pieces: &mut [Piece],
    slots: &mut Slots,
    gap: f64,
    snap: f64,
    fixed: &[bool],
    out: &mut Gaps,
) {
    let reach = EXTEND_REACH * gap;
    let cone = 30f64.to_radians().tan();
    for p in 0..pieces.len() {
        for side in 0..2 {
            let piece = &pieces[p];
            if piece.closed || piece.joined[side] || fixed[piece.curve] || piece.idx.len() < 3 {
                continue;
            }
            if piece.length(d) < 2.0 * gap {
                continue;
            }
            let n = piece.idx.len();
            let end = if side == 0 { piece.idx[0] } else { piece.idx[n - 1] };
            let x = d.pos[end];
            let inner = window(d, piece, side, gap).last().map_or(end, |&k| piece.idx[k]);
            let t = (x - d.pos[inner]).normalize_or_zero();
            if t == DVec3::ZERO || nearest(d, pieces, slots, p, end, gap).is_some() {
                continue;
            }
            // The first dense point along the ray within the miss: (distance along, point).
            let mut best: Option<(f64, usize, usize)> = None;
            d.near(x, reach + d.h, |j| {
                let Some((q, _)) = slots.0[j] else { return };
                let q = q as usize;
                if q == p && d.along(end, j) <= 4.0 * reach {
                    return;
                }
                let v = d.pos[j] - x;
                let a = v.dot(t);
                let miss = (v - a * t).length();
                if a > 0.0 && a <= reach && miss <= (EXTEND_MISS * gap).min(cone * a) && best.is_none_or(|b| a < b.0) {
                    best = Some((a, j, q));
                }
            });
            let Some((_, j, q)) = best else { continue };
            let hit = Near { dist: d.pos[j].distance(x), q: d.pos[j], piece: q, k: j };
            slots.clear(&pieces[p].idx);
            pieces[p].end_at(d, side, hit.q, 2.0 * snap);
            slots.set(pieces, p);
            out.joins.push((pieces[p].curve, pieces[q].curve, hit.q));
            out.extended += 1;
            if !fixed[pieces[q].curve] {
                corner(d, pieces, slots, p, hit, gap, snap, out);
            }
        }
    }
}

/// A junction `hit` made by an end of piece `p` that lands within the window of a free end of
/// the piece it lands on: that end is cut back to the junction and ends there too (an
/// L-corner); on `p` itself, the piece is closed (a loop).
#[allow(clippy::too_many_arguments)]
fn corner(
    d: &Dense,
    pieces: &mut [Piece],
    slots: &mut Slots,
    p: usize,
    hit: Near,
    gap: f64,
    snap: f64,
    out: &mut Gaps,
) {
    let t = hit.piece;
    if pieces[t].closed {
        return;
    }
    for side in 0..2 {
        if t == p && pieces[p].ends[side].is_some() {
            continue; // the end that made the junction
        }
        if pieces[t].joined[side] {
            continue;
        }
        let end = if side == 0 { pieces[t].idx[0] } else { pieces[t].idx[pieces[t].idx.len() - 1] };
        let j = hit.k;
        let Some(k) = pieces[t].idx.iter().position(|&i| i == j) else { return };
        if d.along(end, j) > gap || pieces[t].idx.len() < 3 {
            continue;
        }
        slots.clear(&pieces[t].idx);
        if d.along(end, j) > 0.0 {
            out.stubs.push((pieces[t].curve, d.pos[end]));
        }
        pieces[t].cut_to(side, k);
        pieces[t].changed = true;
        pieces[t].joined[side] = true;
        if t == p {
            pieces[t].closed = true;
        } else {
            pieces[t].end_at(d, side, hit.q, 2.0 * snap);
        }
        slots.set(pieces, t);
        return;
    }
}

/// The positions in piece `p`'s list of its window at `side` (0: its first point, 1: its
/// last), from the end inward, at most the gap along it and leaving two points.
fn window(d: &Dense, piece: &Piece, side: usize, gap: f64) -> Vec<usize> {
    let n = piece.idx.len();
    let pos = |k: usize| if side == 0 { k } else { n - 1 - k };
    let end = piece.idx[pos(0)];
    (0..n.saturating_sub(1)).map(pos).take_while(|&k| d.along(end, piece.idx[k]) <= gap).collect()
}

/// The nearest point within `r` of dense point `i` (of piece `p`) on the other pieces' dense
/// polylines, or on `p`'s own more than four `r` along it.
fn nearest(d: &Dense, pieces: &[Piece], slots: &Slots, p: usize, i: usize, r: f64) -> Option<Near> {
    nearest_beyond(d, pieces, slots, p, i, r, 4.0 * r)
}

/// [`nearest`] on the other pieces only.
fn nearest_other(d: &Dense, pieces: &[Piece], slots: &Slots, p: usize, i: usize, r: f64) -> Option<Near> {
    nearest_beyond(d, pieces, slots, p, i, r, f64::INFINITY)
}

/// [`nearest`], with `p`'s own points more than `own` along it.
fn nearest_beyond(d: &Dense, pieces: &[Piece], slots: &Slots, p: usize, i: usize, r: f64, own: f64) -> Option<Near> {
    let x = d.pos[i];
    let mut best: Option<Near> = None;
    d.near(x, r + d.h, |j| {
        let Some((t, k)) = slots.0[j] else { return };
        let (t, k) = (t as usize, k as usize);
        if t == p && d.along(i, j) <= own {
            return;
        }
        let idx = &pieces[t].idx;
        let mut consider = |k0: usize, k1: usize| {
            let (a, b) = (d.pos[idx[k0]], d.pos[idx[k1]]);
            let ab = b - a;
            let s =
                if ab.length_squared() > 0.0 { ((x - a).dot(ab) / ab.length_squared()).clamp(0.0, 1.0) } else { 0.0 };
            let q = a + s * ab;
            let dist = q.distance(x);
            if dist <= r && best.is_none_or(|b| dist < b.dist) {
                best = Some(Near { dist, q, piece: t, k: idx[if s < 0.5 { k0 } else { k1 }] });
            }
        };
        if k + 1 < idx.len() {
            consider(k, k + 1);
        } else if pieces[t].closed && idx.len() > 2 {
            consider(k, 0);
        }
        if k > 0 {
            consider(k - 1, k);
        }
    });
    best
}
