//! From clusters of contacts to nodes: each distinct passage of a curve through a cluster,
//! checks that the curves there cross rather than overlap, and the node's position and normal
//! (the averages over the passages), with the check that the curves' normals agree in
//! orientation.

use super::contacts::{Hit, Loc, Polylines};
use super::{Node, OVERLAP_PROBE, SAME_MEETING};
use crate::error::{Error, Result, Warning};
use crate::geom::{fmt_point, DVec3};

/// One passage of a curve through a meeting: `(curve, arc position, location)`.
pub(super) type Passage = (usize, f64, Loc);

/// Per curve: `(arc position, node id)` of the nodes on it, in no particular order.
pub(super) type OnCurve = Vec<Vec<(f64, usize)>>;

/// The nodes of the meetings `clusters` (lists of indices into `hits`), in cluster order, and
/// where they lie on each curve, with a warning per closed boundary curve taken as a sheet of
/// its own ([`own_sheets`]).
///
/// Errors ([`Error::Input`]): curves that overlap ([`passages`], [`check_overlap`]), curves
/// whose normals disagree in orientation ([`meeting_node`]).
pub(super) fn meeting_nodes(
    lines: &Polylines,
    hits: &[Hit],
    clusters: &[Vec<usize>],
    snap: f64,
) -> Result<(Vec<Node>, OnCurve, Vec<Warning>)> {
    let mut all = Vec::with_capacity(clusters.len());
    for cluster in clusters {
        let passages = passages(lines, hits, cluster, snap)?;
        check_overlap(lines, &passages, snap)?;
        all.push(passages);
    }
    let own = own_sheets(lines, &all, snap);
    let mut warnings = Vec::new();
    // Each cluster becomes a node; each distinct passage of a curve through it a node sample.
    let mut nodes: Vec<Node> = Vec::new();
    // Per curve: (arc position, node id).
    let mut on_curve: OnCurve = vec![Vec::new(); lines.curves.len()];
    for mut passages in all {
        let before = passages.len();
        let apart: Vec<Passage> = passages.iter().filter(|p| own[p.0]).copied().collect();
        passages.retain(|p| !own[p.0]);
        if let Some(&(_, _, loc)) = apart.first() {
            let mut others: Vec<&str> = passages.iter().map(|p| lines.labels[p.0].as_str()).collect();
            others.dedup();
            let names: Vec<&str> = apart.iter().map(|p| lines.labels[p.0].as_str()).collect();
            warnings.push(
                Warning::new(format!(
                    "{} {} closed {} tagged boundary that {} the network at one place only, at {} first sample \
                     (near {}{}): taken as the border{} of {} of {} own (petals; the mesh has a vertex of its own \
                     for each at the contact{})",
                    names.join(", "),
                    if names.len() > 1 { "are" } else { "is a" },
                    if names.len() > 1 { "curves" } else { "curve" },
                    if names.len() > 1 { "touch" } else { "touches" },
                    if names.len() > 1 { "their" } else { "its" },
                    fmt_point(lines.point_at(loc)),
                    if others.is_empty() { String::new() } else { format!(", on {}", others.join(", ")) },
                    if names.len() > 1 { "s" } else { "" },
                    if names.len() > 1 { "sheets" } else { "a sheet" },
                    if names.len() > 1 { "their" } else { "its" },
                    match passages.len() {
                        0 => "; no node is left there",
                        1 => "; the one stroke left there has no node there: it ends or passes on",
                        _ => "",
                    },
                ))
                .curve(apart[0].0),
            );
        }
        // A meeting whose other side was such a sheet only is no node (a curve's end node is
        // added with the ends).
        if passages.is_empty() || (passages.len() < 2 && passages.len() < before) {
            continue;
        }
        let node = meeting_node(lines, &passages)?;
        let id = nodes.len();
        nodes.push(node);
        for p in &passages {
            on_curve[p.0].push((p.1, id));
        }
    }
    Ok((nodes, on_curve, warnings))
}

/// Per curve: whether it is a sheet of its own ([CG] assumes one tangent plane per node; the
/// petals of a sketched flower touch at its centre in planes of their own): a closed curve
/// tagged boundary that passes through exactly one meeting, once, at its seam (its first
/// sample, within [`SAME_MEETING`] tolerances), where two other passages at least meet (other
/// strokes, other petals; a single stroke that ends on a loop or crosses it is a stroke into a
/// hole or across a border, which stays on it). Such a curve
/// bounds a patch of its own; at the meeting it makes no node with the others, so that its
/// disk keeps its own normal there. Normal inference tags petals so
/// (`pipeline::infer::petals`, the same count of passages).
fn own_sheets(lines: &Polylines, all: &[Vec<Passage>], snap: f64) -> Vec<bool> {
    let mut count = vec![0usize; lines.curves.len()];
    for passages in all {
        for p in passages {
            count[p.0] += 1;
        }
    }
    let candidate: Vec<bool> =
        lines.curves.iter().zip(&count).map(|(c, &n)| c.closed && c.boundary && n == 1).collect();
    let mut own = vec![false; lines.curves.len()];
    for passages in all {
        // The loop touches the others at its seam (its first sample): where a petal is drawn
        // from and back to (and where inference puts a petal's first sample).
        let at_seam = |p: &Passage| lines.along(p.0, p.1, 0.0) <= SAME_MEETING * snap;
        // Two other passages at least: a node of the others (a stroke that ends on a loop, or
        // passes through it, is a stroke into a hole or across a border, which stays on it).
        if passages.len() < 3 {
            continue;
        }
        for p in passages.iter().filter(|p| candidate[p.0] && at_seam(p)) {
            own[p.0] = true;
        }
    }
    own
}

/// The passages of the curves through one meeting (the contacts `cluster` of `hits`): per
/// curve, the runs of contact locations within [`SAME_MEETING`] tolerances of each other
/// along the curve, each run represented by the location of its closest contact (where the
/// curve comes nearest to another one: the crossing itself, whatever the number of samples
/// within the tolerance around it — the middle of the run drifts with the sampling); runs of a
/// closed curve on both sides of its seam are one. Sorted by curve and arc position.
///
/// Errors ([`Error::Input`]): a run longer than 8 tolerances (a curve that runs along another
/// one, or along itself).
pub(super) fn passages(lines: &Polylines, hits: &[Hit], cluster: &[usize], snap: f64) -> Result<Vec<Passage>> {
    let labels = lines.labels;
    // (curve, arc position, location, distance between the contact's two points)
    let mut locs: Vec<(usize, f64, Loc, f64)> = Vec::new();
    for &k in cluster {
        let gap = lines.point_at(hits[k].a).distance(lines.point_at(hits[k].b));
        for l in [hits[k].a, hits[k].b] {
            locs.push((l.curve, lines.arc_at(l), l, gap));
        }
    }
    locs.sort_by(|x, y| x.0.cmp(&y.0).then(x.1.total_cmp(&y.1)));
    // Split into passages: runs of one curve whose arc positions are close.
    let mut passages: Vec<Passage> = Vec::new();
    let mut i = 0;
    while i < locs.len() {
        let mut j = i + 1;
        while j < locs.len()
            && locs[j].0 == locs[i].0
            && lines.along(locs[i].0, locs[j].1, locs[j - 1].1) <= SAME_MEETING * snap
        {
            j += 1;
        }
        let c = locs[i].0;
        let extent = lines.along(c, locs[j - 1].1, locs[i].1);
        if extent > 8.0 * snap {
            let others: Vec<&str> = locs.iter().filter(|l| l.0 != c).map(|l| labels[l.0].as_str()).collect();
            let other = others.first().copied().unwrap_or("itself");
            return Err(Error::input(format!(
                "{} runs within the snapping tolerance ({snap:.3e}) of {other} for a length of {extent:.3e} near {}: \
                 overlapping or coincident curves cannot be surfaced; remove the duplicate or lower `snap`",
                labels[c],
                fmt_point(lines.point_at(locs[i].2)),
            ))
            .curve(c)
            .point(lines.point_at(locs[i].2)));
        }
        // The passage at the run's closest contact (the first of equals).
        let best = (i..j).fold(i, |b, k| if locs[k].3 < locs[b].3 { k } else { b });
        let (c, arc, loc, _) = locs[best];
        passages.push((c, arc, loc));
        i = j;
    }
    // A closed curve's run may straddle its seam (arc 0 / length): merge first and last.
    let mut merged: Vec<(usize, f64, Loc)> = Vec::new();
    for p in passages {
        if !merged.iter().any(|q| q.0 == p.0 && lines.along(p.0, p.1, q.1) <= SAME_MEETING * snap) {
            merged.push(p);
        }
    }
    Ok(merged)
}

/// Checks that the curves through a meeting separate away from it: curves that cross
/// separate, curves that overlap stay within the tolerance. Each passage is probed a quarter,
/// half and all of [`OVERLAP_PROBE`] tolerances along its curve on both sides; another
/// passage's curve within `snap` of the probe points at all of them (near that passage) is an
/// overlap.
///
/// Errors ([`Error::Input`]): an overlap, naming both curves.
pub(super) fn check_overlap(lines: &Polylines, passages: &[Passage], snap: f64) -> Result<()> {
    let (curves, arcs, labels) = (lines.curves, &lines.arcs, lines.labels);
    // Curves that cross separate away from the node; curves that overlap stay within the
    // tolerance. Probe each passage OVERLAP_PROBE tolerances along the curve on both sides.
    let delta = OVERLAP_PROBE * snap;
    for (a, pa) in passages.iter().enumerate() {
        for (b, pb) in passages.iter().enumerate() {
            if a == b {
                continue;
            }
            for side in [-1.0, 1.0] {
                // Overlapping curves stay together: within the tolerance at every probe
                // (a quarter, half and all of OVERLAP_PROBE tolerances along). A curve
                // that crosses again further on is close at one probe only.
                // A curve that ends before the half probe (a crease of one mesh edge crossing
                // a section at a shallow angle) has not been seen to stay: no overlap.
                let mut together = true;
                let mut probed = 0;
                for frac in [0.25, 0.5, 1.0] {
                    let Some(probe) = polyline_at_arc(
                        &curves[pa.0].points,
                        &arcs[pa.0],
                        curves[pa.0].closed,
                        pa.1 + side * frac * delta,
                    ) else {
                        break;
                    };
                    probed += 1;
                    let d = polyline_distance(
                        &curves[pb.0].points,
                        &arcs[pb.0],
                        curves[pb.0].closed,
                        pb.1,
                        2.0 * frac * delta,
                        probe,
                    );
                    if d > snap {
                        together = false;
                        break;
                    }
                }
                if probed >= 2 && together {
                    return Err(Error::input(format!(
                        "{} runs within the snapping tolerance ({snap:.3e}) of {} near {}: overlapping or coincident \
                         curves (or curves touching at a very shallow angle) cannot be surfaced; remove the duplicate \
                         or lower `snap`",
                        labels[pa.0],
                        if pa.0 == pb.0 { "itself".to_string() } else { labels[pb.0].clone() },
                        fmt_point(lines.point_at(pa.2)),
                    ))
                    .curve(pa.0)
                    .point(lines.point_at(pa.2)));
                }
            }
        }
    }
    Ok(())
}

/// The node of a meeting: the mean position of the passages, and the normalised sum of the
/// curves' normals there (the first curve's normal when they cancel out).
///
/// Errors ([`Error::Input`]): two passages whose normals are more than 90° apart (one of the
/// curves has its normals pointing inward).
pub(super) fn meeting_node(lines: &Polylines, passages: &[Passage]) -> Result<Node> {
    let labels = lines.labels;
    let position = passages.iter().map(|p| lines.point_at(p.2)).sum::<DVec3>() / passages.len() as f64;
    let normals: Vec<DVec3> = passages.iter().map(|p| lines.normal_at(p.2)).collect();
    // Where a crease passes, the smooth curves may lie on its different sides (a cylinder's
    // side line and lid diameter meet its rim 90° apart): each curve is compared with the
    // sides of the creases only, and the best-agreeing pair of sides counts.
    let crease = |p: &Passage| lines.curves[p.0].is_crease();
    let any_crease = passages.iter().any(crease);
    let sides: Vec<[DVec3; 2]> =
        passages.iter().map(|p| if crease(p) { lines.sides_at(p.2) } else { [lines.normal_at(p.2); 2] }).collect();
    for a in 0..normals.len() {
        for b in a + 1..normals.len() {
            if any_crease && !crease(&passages[a]) && !crease(&passages[b]) {
                continue;
            }
            let best = |x: &[DVec3; 2], y: &[DVec3; 2]| {
                x.iter().flat_map(|u| y.iter().map(move |v| u.dot(*v))).fold(f64::NEG_INFINITY, f64::max)
            };
            let cos = if any_crease { best(&sides[a], &sides[b]) } else { normals[a].dot(normals[b]) };
            if cos < 0.0 {
                return Err(Error::input(format!(
                    "{} and {} meet at {} with normals {:.0}° apart: one of them points inward. \
                     Normals must point to the outside of the surface on every curve; flip the normals of one curve",
                    labels[passages[a].0],
                    labels[passages[b].0],
                    fmt_point(position),
                    cos.clamp(-1.0, 1.0).acos().to_degrees()
                ))
                .curve(passages[a].0)
                .point(position));
            }
        }
    }
    let normal = normals.iter().sum::<DVec3>().normalize_or_zero();
    let normal = if normal == DVec3::ZERO { normals[0] } else { normal };
    Ok(Node { position, normal })
}

/// Point of a polyline at arc length `s` (wrapping for closed curves); `None` past the ends of
/// an open curve.
pub(super) fn polyline_at_arc(points: &[DVec3], arc: &[f64], closed: bool, s: f64) -> Option<DVec3> {
    let total = arc[arc.len() - 1];
    let s = if closed {
        s.rem_euclid(total)
    } else if (0.0..=total).contains(&s) {
        s
    } else {
        return None;
    };
    let (e, t) = crate::geom::polyline::locate(arc, s);
    Some(points[e].lerp(points[(e + 1) % points.len()], t))
}

/// Distance from `p` to the part of a polyline within arc length `half` of `center`.
pub(super) fn polyline_distance(points: &[DVec3], arc: &[f64], closed: bool, center: f64, half: f64, p: DVec3) -> f64 {
    let total = arc[arc.len() - 1];
    let m = arc.len() - 1;
    let mut best = f64::INFINITY;
    for e in 0..m {
        // Arc distance from the window centre to this edge.
        let (a0, a1) = (arc[e], arc[e + 1]);
        let mut gap = if center < a0 {
            a0 - center
        } else if center > a1 {
            center - a1
        } else {
            0.0
        };
        if closed {
            gap = gap.min((a0 + total - center).abs().min((center + total - a1).abs()));
        }
        if gap > half {
            continue;
        }
        let (q0, q1) = (points[e], points[(e + 1) % points.len()]);
        let d = q1 - q0;
        let t = if d.length_squared() > 0.0 { ((p - q0).dot(d) / d.length_squared()).clamp(0.0, 1.0) } else { 0.0 };
        best = best.min(p.distance(q0 + t * d));
    }
    best
}

#[cfg(test)]
#[path = "tests/meetings.rs"]
mod tests;
