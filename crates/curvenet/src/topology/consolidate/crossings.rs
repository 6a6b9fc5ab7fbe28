//! Crossings: two strokes whose interiors pass each other at an angle within the gap — a
//! crossing drawn in the air, which misses by a few millimetres — are moved to meet, so that
//! node finding makes the X-junction the sketch means.
//!
//! Every fourth dense point of a piece, outside the last gap of an open piece's ends (an end
//! near another stroke is the gap stage's: a T, an overshoot or a corner), looks for the
//! nearest point of another piece (or of its own, more than four gaps along it) whose tangent
//! is at least [`MIN_DEGREES`] away from its own (strokes at a shallower angle run along each
//! other: overdraw, or a graze left as drawn), and walks the pair down, a point along either
//! stroke at a time, to a local minimum of their distance. Those within the gap and away from
//! the ends, nearest first, are the closest approaches: a pair is kept when no pair kept before joins the same two pieces within two gaps
//! along both (each crossing once, at its closest approach). A pair already within the snapping
//! tolerance meets as drawn and is left alone (and does not move).
//!
//! A kept pair is moved to its midpoint — onto the other point when one of them may not move
//! (a crease, a boundary curve, a point of an earlier crossing or contact or of a junction the
//! gap stage made; a stroke that meets another within the miss along it meets this one at
//! that point too, so that several strokes through one place make one node) — each stroke shifted by a bump that falls smoothly to zero within two gaps along it
//! (a raised cosine), and sooner where it would reach a point that may not move.

use super::dense::Dense;
use super::Piece;
use crate::geom::DVec3;
use std::collections::HashMap;

/// Strokes meeting at less than this angle are not a crossing.
pub(super) const MIN_DEGREES: f64 = 30.0;

/// The shift of a crossing falls to zero this many gaps along each stroke.
const REACH: f64 = 2.0;

/// At most this many steps down to a closest approach (16 gaps of dense points).
const MAX_DESCENT: usize = 64;

/// One crossing made: the two curves, where they now meet, and how far apart they passed.
pub(super) struct Crossing {
    pub(super) curves: [usize; 2],
    pub(super) at: DVec3,
    pub(super) miss: f64,
}

/// A candidate: the distance, the two dense points and their pieces.
#[derive(Clone, Copy)]
struct Pair {
    dist: f64,
    i: usize,
    j: usize,
    pi: usize,
    pj: usize,
}

/// Finds and closes the crossings of `pieces` that miss by more than `snap` and at most `gap`
/// (module documentation). `fixed[c]`: curve `c` does not move; `junctions`: the points the
/// gap stage joined ends at (the strokes there do not move). Returns the crossings made and
/// marks the dense points it moved in `moved`.
pub(super) fn join_crossings(
    d: &mut Dense,
    pieces: &[Piece],
    gap: f64,
    snap: f64,
    fixed: &[bool],
    junctions: &[DVec3],
    moved: &mut [bool],
) -> Vec<Crossing> {
    let n = d.pos.len();
    // Where each dense point sits: (piece, position in it).
    let mut slot: Vec<Option<(usize, usize)>> = vec![None; n];
    for (p, piece) in pieces.iter().enumerate() {
        for (k, &j) in piece.idx.iter().enumerate() {
            slot[j] = Some((p, k));
        }
    }
    let in_end_window = |p: usize, k: usize| {
        let piece = &pieces[p];
        if piece.closed {
            return false;
        }
        let j = piece.idx[k];
        d.along(j, piece.idx[0]) <= gap || d.along(j, piece.idx[piece.idx.len() - 1]) <= gap
    };
    let cos_min = MIN_DEGREES.to_radians().cos();
    let crossing = |i: usize, j: usize| {
        let far_along = d.curve[i] != d.curve[j] || d.along(i, j) > 4.0 * gap;
        let (ti, tj) = (d.tan[i], d.tan[j]);
        far_along && ti != DVec3::ZERO && tj != DVec3::ZERO && ti.dot(tj).abs() <= cos_min
    };
    // Every fourth point asks (at most a gap apart along the stroke: a crossing that misses
    // by the gap is seen from the nearest of them at most 1.12 gaps away); the pair it finds
    // is walked down to the closest approach of the two strokes.
    let mut pairs: Vec<Pair> = Vec::new();
    for (pi, piece) in pieces.iter().enumerate() {
        for (ki, &i) in piece.idx.iter().enumerate().step_by(4) {
            if in_end_window(pi, ki) {
                continue;
            }
            let mut best: Option<Pair> = None;
            d.near(d.pos[i], 1.15 * gap, |j| {
                let Some((pj, kj)) = slot[j] else { return };
                if j == i || !crossing(i, j) || in_end_window(pj, kj) {
                    return;
                }
                let dist = d.pos[i].distance(d.pos[j]);
                if best.is_none_or(|b| dist < b.dist) {
                    best = Some(Pair { dist, i, j, pi, pj });
                }
            });
            let Some(b) = best else { continue };
            // A closest approach away from the ends (strokes that diverge from a junction at
            // their ends come nearest in the end's window, which is the gap stage's).
            let m = descend(d, pieces, &slot, b);
            let inside = |x: usize| slot[x].is_some_and(|(p, k)| !in_end_window(p, k));
            if m.dist <= gap && inside(m.i) && inside(m.j) && crossing(m.i, m.j) {
                pairs.push(if m.i < m.j { m } else { Pair { i: m.j, j: m.i, pi: m.pj, pj: m.pi, ..m } });
            }
        }
    }
    pairs.sort_by(|a, b| a.i.cmp(&b.i).then(a.j.cmp(&b.j)));
    pairs.dedup_by(|a, b| a.i == b.i && a.j == b.j);
    pairs.sort_by(|a, b| a.dist.total_cmp(&b.dist).then(a.i.cmp(&b.i)).then(a.j.cmp(&b.j)));
    // The closest approaches: per pair of pieces, the crossings kept so far.
    let mut kept: HashMap<(usize, usize), Vec<(usize, usize)>> = HashMap::new();
    let mut approaches = Vec::new();
    let mut contacts = Vec::new();
    for pair in pairs {
        let key = (pair.pi.min(pair.pj), pair.pi.max(pair.pj));
        let (a, b) = if pair.pi <= pair.pj { (pair.i, pair.j) } else { (pair.j, pair.i) };
        let list = kept.entry(key).or_default();
        let near = |x: usize, y: usize| d.curve[x] == d.curve[y] && d.along(x, y) <= REACH * gap;
        if list.iter().any(|&(ka, kb)| (near(a, ka) && near(b, kb)) || (near(a, kb) && near(b, ka))) {
            continue;
        }
        list.push((a, b));
        if pair.dist > snap {
            approaches.push(pair);
        } else {
            contacts.push(pair);
        }
    }
    // Points that may not move: fixed curves, and the strokes at the gap stage's junctions.
    let mut pinned: Vec<bool> = (0..n).map(|j| fixed[d.curve[j] as usize]).collect();
    for &q in junctions {
        d.near(q, d.h, |j| pinned[j] = true);
    }
    // And the strokes where they meet as drawn (within the snapping tolerance): node finding
    // joins them there, and a crossing nearby meets them at that point.
    for pair in &contacts {
        pinned[pair.i] = true;
        pinned[pair.j] = true;
    }
    let mut out = Vec::new();
    for pair in approaches {
        // Several strokes through one place (a pole, a dense junction) meet at one point: a
        // stroke that already meets another within the miss (or twice the snapping tolerance)
        // along it meets this one there — no further than the miss, so that no stroke is
        // pulled onto a third one beside it.
        let reach = pair.dist.max(2.0 * snap);
        let i = settled_near(d, &pieces[pair.pi], slot[pair.i].map_or(0, |s| s.1), reach, &pinned);
        let j = settled_near(d, &pieces[pair.pj], slot[pair.j].map_or(0, |s| s.1), reach, &pinned);
        if d.pos[i] == d.pos[j] {
            continue;
        }
        let target = match (pinned[i], pinned[j]) {
            (true, true) => continue,
            (true, false) => d.pos[i],
            (false, true) => d.pos[j],
            (false, false) => d.pos[i].lerp(d.pos[j], 0.5),
        };
        // Each stroke's bump, unless it would be steeper than one in two (a point that may
        // not move right beside the crossing): then the crossing is left as drawn.
        let mut bumps = Vec::new();
        for (x, p) in [(i, pair.pi), (j, pair.pj)] {
            if !pinned[x] {
                let sides = bump(d, &pieces[p], slot[x].map_or(0, |s| s.1), REACH * gap, &pinned);
                bumps.push((x, target - d.pos[x], sides));
            }
        }
        if bumps.iter().any(|(_, delta, sides)| sides.iter().any(|side| delta.length() > 0.5 * side.1)) {
            continue;
        }
        for (x, delta, sides) in bumps {
            apply(d, x, delta, sides, moved);
        }
        pinned[i] = true;
        pinned[j] = true;
        out.push(Crossing { curves: [d.curve[i] as usize, d.curve[j] as usize], at: target, miss: pair.dist });
    }
    // (The tangents and the hash are not used after this stage: emission reads positions.)
    out
}

/// The pair of points of the two pieces of `pair` nearest each other reached from it by steps
/// of one point along either piece or both (a local minimum of their distance).
fn descend(d: &Dense, pieces: &[Piece], slot: &[Option<(usize, usize)>], mut pair: Pair) -> Pair {
    let step = |x: usize, by: isize| -> Option<usize> {
        let (p, k) = slot[x]?;
        let piece = &pieces[p];
        let m = piece.idx.len() as isize;
        let t = k as isize + by;
        if piece.closed {
            Some(piece.idx[t.rem_euclid(m) as usize])
        } else {
            (0..m).contains(&t).then(|| piece.idx[t as usize])
        }
    };
    // At most a few gaps' worth of steps (a stroke winding about another would otherwise walk
    // along it).
    for _ in 0..MAX_DESCENT {
        let mut next = pair;
        for (a, b) in [(-1, 0), (1, 0), (0, -1), (0, 1), (-1, -1), (-1, 1), (1, -1), (1, 1)] {
            let (Some(i), Some(j)) = (step(pair.i, a), step(pair.j, b)) else { continue };
            let dist = d.pos[i].distance(d.pos[j]);
            if dist < next.dist {
                next = Pair { dist, i, j, ..pair };
            }
        }
        if next.dist >= pair.dist {
            return pair;
        }
        pair = next;
    }
    pair
}

/// The point of `piece` that may not move nearest along it to its `k`-th point, within `reach`
/// along (the `k`-th point itself when none is).
fn settled_near(d: &Dense, piece: &Piece, k: usize, reach: f64, pinned: &[bool]) -> usize {
    let m = piece.idx.len();
    let centre = piece.idx[k];
    let mut best: Option<(f64, usize)> = None;
    for step in [-1isize, 1] {
        let mut t = k as isize;
        for _ in 0..m {
            let j = if piece.closed {
                piece.idx[t.rem_euclid(m as isize) as usize]
            } else if t >= 0 && (t as usize) < m {
                piece.idx[t as usize]
            } else {
                break;
            };
            let s = d.along(centre, j);
            if s > reach {
                break;
            }
            if pinned[j] {
                if best.is_none_or(|b| s < b.0) {
                    best = Some((s, j));
                }
                break;
            }
            t += step;
        }
    }
    best.map_or(centre, |b| b.1)
}

/// One side of a bump: the points with their distance along the stroke, and where it ends.
type Side = (Vec<(usize, f64)>, f64);

/// The bump centred on point `k` of `piece`: on either side the points within `reach` along it,
/// stopping short of the first point that may not move (or the piece's end where it is a
/// junction) if that comes sooner.
fn bump(d: &Dense, piece: &Piece, k: usize, reach: f64, pinned: &[bool]) -> Vec<Side> {
    let m = piece.idx.len();
    let at = |t: isize| -> Option<usize> {
        if piece.closed {
            Some(piece.idx[t.rem_euclid(m as isize) as usize])
        } else if t >= 0 && (t as usize) < m {
            Some(piece.idx[t as usize])
        } else {
            None
        }
    };
    let centre = piece.idx[k];
    // Distances are summed along the piece (a loop the gap stage closed has no wrap-around arc
    // length of its own); on a loop each side goes at most halfway round.
    let steps = if piece.closed { (m - 1) / 2 } else { m };
    let round =
        if piece.closed { piece.length(d) + d.pos[piece.idx[m - 1]].distance(d.pos[piece.idx[0]]) } else { 0.0 };
    // Per side: the points within reach with their distance along, and the reach on that side.
    let mut sides: Vec<Side> = Vec::new();
    for step in [-1isize, 1] {
        let mut pts = Vec::new();
        let mut limit = if piece.closed { reach.min(0.5 * round) } else { reach };
        let mut t = k as isize + step;
        let (mut s, mut prev) = (0.0, centre);
        let mut ran_off = true;
        for _ in 0..steps {
            let Some(j) = at(t) else { break };
            s += d.pos[prev].distance(d.pos[j]);
            if s >= limit {
                ran_off = false;
                break;
            }
            if pinned[j] {
                limit = s;
                ran_off = false;
                break;
            }
            pts.push((j, s));
            prev = j;
            t += step;
        }
        // An open piece's end that is a junction stays where it is.
        let end = if step < 0 { 0 } else { 1 };
        if !piece.closed && ran_off && at(t).is_none() && piece.ends[end].is_some() {
            limit = limit.min(s + d.h);
        }
        sides.push((pts, limit));
    }
    sides
}

/// Moves dense point `centre` by `delta` and the points of its bump's `sides` by a raised
/// cosine of their distance along the stroke, zero where each side ends.
fn apply(d: &mut Dense, centre: usize, delta: DVec3, sides: Vec<Side>, moved: &mut [bool]) {
    d.pos[centre] += delta;
    moved[centre] = true;
    for (pts, limit) in sides {
        for (j, s) in pts {
            if s >= limit {
                break;
            }
            let w = 0.5 * (1.0 + (std::f64::consts::PI * s / limit).cos());
            d.pos[j] += w * delta;
            moved[j] = true;
        }
    }
}
