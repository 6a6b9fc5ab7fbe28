//! Stage 6, the holes: boundary loops around holes too small or too thin to be sampled are
//! left out, and so are loops that fewer than two sections reach (the hole covered: a loop
//! that one section reaches would bound a hole inside a patch joined to the rest by that
//! section only, a bridge the pipeline cannot surface, since patches are disks). Section ends
//! that then meet no other curve are cut back to their last crossing, repeatedly, since a cut
//! may leave another loop with one section ([`cover_holes`]).

use super::network::resample;
use super::{Raw, SampleOptions, SampleReport, Scales, Traced};
use crate::geom::{Aabb, DVec3};
use std::collections::HashMap;

/// A resampled curve: positions, unit normals and (a crease) the unit normals on its right.
pub(super) type Resampled = (Vec<DVec3>, Vec<DVec3>, Vec<DVec3>);

/// The key of a sample position (its bits): crossing samples are shared by the curves through
/// them, so the ends of sections are found on the other curves by position.
fn key(p: DVec3) -> [u64; 3] {
    p.to_array().map(f64::to_bits)
}

/// Leaves out the boundary loops `loops` around holes smaller than 3 sample spacings or
/// slit-shaped ([`thin_loop`]), and those that fewer than two of the sections `pieces` reach;
/// cuts the ends of open sections that end neither on a kept loop nor on a crossing that
/// another section passes through back to their last crossing (dropping pieces left with
/// fewer than two nodes), until every end is supported. Returns the sections and the kept
/// loops with their resampling; counts the holes in `report`.
pub(super) fn cover_holes(
    pieces: Vec<Traced>,
    loops: Vec<Traced>,
    opts: &SampleOptions,
    scales: &Scales,
    report: &mut SampleReport,
) -> (Vec<Traced>, Vec<(Traced, Resampled)>) {
    let mut pieces = pieces;
    let mut loop_at: HashMap<[u64; 3], usize> = HashMap::new();
    let mut loops_kept = vec![true; loops.len()];
    let mut loop_curves: Vec<Resampled> = Vec::with_capacity(loops.len());
    for (li, l) in loops.iter().enumerate() {
        for r in l.samples.iter().filter(|r| r.node) {
            loop_at.insert(key(r.p), li);
        }
        let (small, resampled) = small_hole(l, opts, scales);
        if small && l.right.is_empty() {
            report.small_holes += 1;
            loops_kept[li] = false;
        }
        loop_curves.push(resampled);
    }
    let rounds = loops.len() + pieces.len();
    for _ in 0..=rounds {
        let contacts = loop_contacts(&pieces, &loop_at, loops.len());
        for (li, c) in contacts.iter().enumerate() {
            // (Crease curves stay: they meet the other curves at their junctions too.)
            if loops_kept[li] && c.len() < 2 && loops[li].right.is_empty() {
                loops_kept[li] = false;
                if c.is_empty() {
                    report.dropped_boundary_loops += 1;
                } else {
                    report.single_contact_holes += 1;
                }
            }
        }
        let principal = opts.curves == super::CurveFamily::Principal;
        let cut_ends = unsupported_ends(&pieces, &loop_at, &loops_kept, principal);
        if cut_ends.iter().all(|c| c.is_empty()) {
            break;
        }
        pieces = cut_back(pieces, cut_ends);
    }
    let kept = loops.into_iter().zip(loop_curves).zip(loops_kept).filter(|(_, k)| *k).map(|(tp, _)| tp).collect();
    (pieces, kept)
}

/// Whether the boundary loop `l` is around a hole too small to be sampled as a curve: smaller
/// than 3 sample spacings across, or slit-shaped (its sides within `scales.near` of each
/// other: it would run alongside itself); with the loop resampled.
fn small_hole(l: &Traced, opts: &SampleOptions, scales: &Scales) -> (bool, Resampled) {
    if !l.right.is_empty() {
        // A crease: both sides resampled alike (the same positions and nodes).
        let (points, normals) = resample(&l.samples, l.closed, scales.spacing, opts.shared_nodes);
        let other: Vec<Raw> = l.samples.iter().zip(&l.right).map(|(r, &n)| Raw { n, ..*r }).collect();
        let (_, right) = resample(&other, l.closed, scales.spacing, opts.shared_nodes);
        return (false, (points, normals, right));
    }
    let (points, normals) = resample(&l.samples, true, scales.spacing, opts.shared_nodes);
    let small = Aabb::of(l.samples.iter().map(|r| r.p)).diagonal() < 3.0 * scales.spacing
        || (points.len() <= 40 && thin_loop(&points, scales.near));
    (small, (points, normals, Vec::new()))
}

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

/// The section ends on each of the `n_loops` boundary loops: (piece, whether at its first
/// sample), for the node ends of open `pieces` at a node sample of a loop (`loop_at`).
fn loop_contacts(pieces: &[Traced], loop_at: &HashMap<[u64; 3], usize>, n_loops: usize) -> Vec<Vec<(usize, bool)>> {
    let mut contacts: Vec<Vec<(usize, bool)>> = vec![Vec::new(); n_loops];
    for (i, t) in pieces.iter().enumerate().filter(|(_, t)| !t.closed) {
        for (first, r) in [(true, t.samples[0]), (false, t.samples[t.samples.len() - 1])] {
            if let Some(&li) = loop_at.get(&key(r.p)).filter(|_| r.node) {
                contacts[li].push((i, first));
            }
        }
    }
    contacts
}

/// Per piece: its ends that no other curve supports. Every open piece must end where another
/// curve passes: on a kept boundary loop, or (a piece cut at a bad spot) on a crossing that a
/// kept section passes through (not where it ends: two pieces ending on their own crossing
/// would make a corner, not a junction). Principal curves (`principal`) may end in such
/// corners (at about 90°): their free ends are cut back to their last crossing, and two curves
/// often end on the same one (cutting both further would peel the whole network from its free
/// ends).
fn unsupported_ends(
    pieces: &[Traced],
    loop_at: &HashMap<[u64; 3], usize>,
    loops_kept: &[bool],
    principal: bool,
) -> Vec<Vec<DVec3>> {
    let mut on_sections: HashMap<[u64; 3], Vec<usize>> = HashMap::new();
    for (i, t) in pieces.iter().enumerate() {
        let m = t.samples.len();
        for (k, r) in t.samples.iter().enumerate() {
            if r.node && (t.closed || (k > 0 && k + 1 < m) || principal) {
                on_sections.entry(key(r.p)).or_default().push(i);
            }
        }
    }
    let supported = |i: usize, r: Raw| {
        r.node
            && (loop_at.get(&key(r.p)).is_some_and(|&li| loops_kept[li])
                || on_sections.get(&key(r.p)).is_some_and(|l| l.iter().any(|&j| j != i)))
    };
    let mut cut_ends: Vec<Vec<DVec3>> = vec![Vec::new(); pieces.len()];
    for (i, t) in pieces.iter().enumerate().filter(|(_, t)| !t.closed) {
        for r in [t.samples[0], t.samples[t.samples.len() - 1]] {
            if !supported(i, r) {
                cut_ends[i].push(r.p);
            }
        }
    }
    cut_ends
}

/// `pieces` with the ends `cut_ends` (per piece) cut back to the last crossing
/// ([`super::cut::cut_at_spots`] with no gap); pieces left with fewer than two nodes are left
/// out.
fn cut_back(pieces: Vec<Traced>, cut_ends: Vec<Vec<DVec3>>) -> Vec<Traced> {
    let mut out = Vec::new();
    for (t, ends) in pieces.into_iter().zip(cut_ends) {
        if ends.is_empty() {
            out.push(t);
        } else {
            out.extend(
                super::cut::cut_at_spots(t, &ends, 0.0)
                    .into_iter()
                    .filter(|t| t.samples.iter().filter(|s| s.node).count() >= 2),
            );
        }
    }
    out
}

#[cfg(test)]
#[path = "tests/holes.rs"]
mod tests;
