//! The curves split at their nodes: the end nodes of open curves (and a node on every closed
//! curve that meets nothing), the nodes inserted into the sample lists (snapping the nearest
//! sample when it is within a quarter of an edge, inserting a new sample otherwise), and the
//! segments between consecutive nodes.

use super::contacts::{Loc, Polylines};
use super::meetings::OnCurve;
use super::{Node, Segment, SplitCurve};
use crate::error::{Error, Result};
use crate::geom::{fmt_point, Aabb, DVec3};

/// Adds the nodes that no meeting made: the ends of open curves (unless a node lies within
/// `snap` of the end along the curve), and sample 0 of closed curves without a node.
pub(super) fn add_end_nodes(lines: &Polylines, nodes: &mut Vec<Node>, on_curve: &mut OnCurve, snap: f64) {
    // Open curves end at nodes; closed curves without a crossing get one node at sample 0.
    for (c, curve) in lines.curves.iter().enumerate() {
        let total = lines.total(c);
        if curve.closed {
            if on_curve[c].is_empty() {
                nodes.push(Node {
                    position: curve.points[0],
                    normal: if curve.has_normals() { curve.mean_normal(0) } else { DVec3::ZERO },
                });
                on_curve[c].push((0.0, nodes.len() - 1));
            }
            continue;
        }
        let near = |x: f64, list: &[(f64, usize)]| list.iter().any(|&(a, _)| (a - x).abs() <= snap.max(1e-12 * total));
        let last = curve.points.len() - 1;
        if !near(0.0, &on_curve[c]) {
            nodes.push(Node {
                position: curve.points[0],
                normal: if curve.has_normals() { curve.mean_normal(0) } else { DVec3::ZERO },
            });
            on_curve[c].push((0.0, nodes.len() - 1));
        }
        if !near(total, &on_curve[c]) {
            nodes.push(Node {
                position: curve.points[last],
                normal: if curve.has_normals() { curve.mean_normal(last) } else { DVec3::ZERO },
            });
            on_curve[c].push((total, nodes.len() - 1));
        }
    }
}

/// Where the nodes land on a curve's samples: per sample, the node that takes it (snapped),
/// and the nodes inserted as new samples, as `(edge, arc position, node)` sorted by arc.
pub(super) type Placement = (Vec<Option<usize>>, Vec<(usize, f64, usize)>);

/// Places the nodes `list` (`(arc position, node)`, sorted by arc) on curve `c`: a node takes
/// the nearer sample of its edge when that sample is within a quarter of the edge length and
/// free (the later sample only when no other node lies further along the same edge, which
/// keeps the nodes in order); otherwise it is inserted on the edge.
pub(super) fn place_nodes(lines: &Polylines, c: usize, list: &[(f64, usize)]) -> Placement {
    let curve = &lines.curves[c];
    let n = curve.points.len();
    let arc = &lines.arcs[c];
    let total = arc[arc.len() - 1];
    // Per sample: the node snapped to it; the other nodes are inserted on their edges.
    let mut snapped: Vec<Option<usize>> = vec![None; n];
    let mut inserts: Vec<(usize, f64, usize)> = Vec::new(); // (edge, arc, node)
    let wrap = |a: f64| if curve.closed { a.rem_euclid(total) } else { a.clamp(0.0, total) };
    let wrapped: Vec<f64> = list.iter().map(|&(a, _)| wrap(a)).collect();
    for &(a, node) in list.iter() {
        let a = wrap(a);
        let (e, _) = crate::geom::polyline::locate(arc, a);
        let len = arc[e + 1] - arc[e];
        let (d0, d1) = (a - arc[e], arc[e + 1] - a);
        let lim = 0.25 * len;
        let s0 = e;
        let s1 = (e + 1) % n;
        let s1_valid = curve.closed || e + 1 < n;
        if d0 <= lim && snapped[s0].is_none() && d0 <= d1 {
            snapped[s0] = Some(node);
        } else if d1 <= lim
            && s1_valid
            && snapped[s1].is_none()
            // A node further along the same edge keeps the order: it takes sample e + 1 (or
            // is inserted before it), this one is inserted before it. Snapping this one
            // forward would put the other one behind it and fold the curve back.
            && !wrapped.iter().any(|&b| b > a && b <= arc[e + 1])
        {
            snapped[s1] = Some(node);
        } else if d0 <= lim && snapped[s0].is_none() {
            snapped[s0] = Some(node);
        } else {
            inserts.push((e, a, node));
        }
    }
    inserts.sort_by(|x, y| x.1.total_cmp(&y.1));
    (snapped, inserts)
}

/// Curve `c` with the nodes `list` (`(arc position, node)`) inserted ([`place_nodes`]), a
/// node's sample taking the node's position and normal; a closed curve is rotated so that a
/// node is at sample 0.
pub(super) fn split_curve(lines: &Polylines, c: usize, list: &mut [(f64, usize)], nodes: &[Node]) -> SplitCurve {
    let curve = &lines.curves[c];
    let n = curve.points.len();
    list.sort_by(|a, b| a.0.total_cmp(&b.0));
    let (snapped, inserts) = place_nodes(lines, c, list);
    let mut points = Vec::with_capacity(n + inserts.len());
    let mut normals = Vec::with_capacity(n + inserts.len());
    let mut origin = Vec::with_capacity(n + inserts.len());
    // A crease network's curves keep their own normals on both sides, nodes included.
    let keep_sides = lines.creases;
    let mut sides = Vec::with_capacity(if keep_sides { n + inserts.len() } else { 0 });
    let arc = &lines.arcs[c];
    let mut markers = Vec::new();
    let mut k = 0;
    for (i, &snap) in snapped.iter().enumerate() {
        origin.push(i);
        if keep_sides {
            sides.push([curve.normals[i], curve.normal_right(i)]);
        }
        match snap {
            Some(node) => {
                markers.push((points.len(), node));
                points.push(nodes[node].position);
                normals.push(nodes[node].normal);
            }
            None => {
                points.push(curve.points[i]);
                normals.push(curve.normals.get(i).copied().unwrap_or(DVec3::ZERO));
            }
        }
        while k < inserts.len() && inserts[k].0 == i {
            let node = inserts[k].2;
            markers.push((points.len(), node));
            points.push(nodes[node].position);
            normals.push(nodes[node].normal);
            origin.push(usize::MAX);
            if keep_sides {
                let e = inserts[k].0;
                let len = arc[e + 1] - arc[e];
                let s = if len > 0.0 { ((inserts[k].1 - arc[e]) / len).clamp(0.0, 1.0) } else { 0.0 };
                sides.push(lines.sides_at(Loc { curve: c, edge: e, s }));
            }
            k += 1;
        }
    }
    // Rotate closed curves so that a node is at sample 0.
    if curve.closed {
        let r = markers[0].0;
        points.rotate_left(r);
        normals.rotate_left(r);
        origin.rotate_left(r);
        if keep_sides {
            sides.rotate_left(r);
        }
        let m = points.len();
        for mk in markers.iter_mut() {
            mk.0 = (mk.0 + m - r) % m;
        }
        markers.sort();
    }
    SplitCurve {
        name: curve.name.clone(),
        points,
        normals,
        closed: curve.closed,
        boundary: curve.boundary,
        nodes: markers,
        origin,
        sides,
    }
}

/// The segments of the split curves `split`, curve by curve, between consecutive nodes
/// (around closed curves, from the last node back to the first). `labels` name the curves in
/// messages.
///
/// Errors ([`Error::Input`]): two consecutive samples on one point (two nodes that landed
/// together: crossings closer than the sampling).
pub(super) fn segments_of(split: &[SplitCurve], labels: &[String]) -> Result<Vec<Segment>> {
    // Two nodes on one curve may have landed on coincident positions: reject degenerate
    // (zero-length) pieces with a clear message.
    let mut segments = Vec::new();
    for (c, sc) in split.iter().enumerate() {
        let m = sc.points.len();
        let tiny = 1e-12 * total_scale(&sc.points);
        for i in 1..m {
            if sc.points[i].distance(sc.points[i - 1]) <= tiny {
                return Err(Error::input(format!(
                    "{}: two nodes fall on the same point {} (crossings closer than the sampling); resample the curve more finely or lower `snap`",
                    labels[c],
                    fmt_point(sc.points[i])
                ))
                .curve(c)
                .point(sc.points[i]));
            }
        }
        let k = sc.nodes.len();
        let pairs = if sc.closed { k } else { k - 1 };
        for j in 0..pairs {
            let (first, start) = sc.nodes[j];
            let (last, end) = if j + 1 < k { sc.nodes[j + 1] } else { (m, sc.nodes[0].1) };
            segments.push(Segment { curve: c, first, last, start, end, boundary: sc.boundary });
        }
    }
    Ok(segments)
}

/// The diagonal of the bounding box of `points` (at least the smallest positive number).
fn total_scale(points: &[DVec3]) -> f64 {
    Aabb::of(points.iter().copied()).diagonal().max(f64::MIN_POSITIVE)
}

#[cfg(test)]
#[path = "tests/split.rs"]
mod tests;
