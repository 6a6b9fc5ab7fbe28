//! Nodes and segments ([CG] §3.2: "a node is the intersection between two or more curves; a
//! segment is a portion of curve bounded by two adjacent nodes").
//!
//! Curves meet where they share a sample *or* pass within the snapping tolerance of each other
//! between samples (sensor data rarely sample a crossing exactly). Candidate pairs of polyline
//! edges come from a uniform spatial hash grid (not all pairs); their closest points
//! ([`closest_params_segment_segment`]) within the tolerance are hits. Hits closer than twice
//! the tolerance form one node. The node is inserted into every curve passing through it
//! (snapping the nearest sample when it is within a quarter of an edge, inserting a new sample
//! otherwise); its normal is the average of the normals the curves give there. Curves whose
//! normals disagree by more than 90° at a node are an orientation error.

use super::UnionFind;
use crate::error::{Error, Result, Warning};
use crate::geom::{closest_params_segment_segment, fmt_point, Aabb, DVec3};
use crate::network::{curve_label, Network};
use std::collections::HashMap;

/// A point where curves meet (or where an open curve ends).
#[derive(Clone, Debug, PartialEq)]
pub struct Node {
    pub position: DVec3,
    /// Unit normal: the average of the curves' normals at the node.
    pub normal: DVec3,
}

/// A curve of the network after node insertion. For closed curves the samples are rotated so
/// that a node sits at sample 0.
#[derive(Clone, Debug)]
pub struct SplitCurve {
    pub name: Option<String>,
    pub points: Vec<DVec3>,
    pub normals: Vec<DVec3>,
    pub closed: bool,
    pub boundary: bool,
    /// `(sample index, node id)` for every node on the curve, by increasing sample index.
    pub nodes: Vec<(usize, usize)>,
}

/// A portion of a curve between two adjacent nodes.
#[derive(Clone, Debug, PartialEq)]
pub struct Segment {
    /// Index of the curve (in the input network and in [`Graph::curves`]).
    pub curve: usize,
    /// First and last sample of the segment on its [`SplitCurve`]; `last` may equal the
    /// number of samples of a closed curve (sample 0 again).
    pub first: usize,
    pub last: usize,
    /// Nodes at the first and last sample.
    pub start: usize,
    pub end: usize,
    /// The segment lies on a boundary curve.
    pub boundary: bool,
}

/// Nodes, split curves and segments of a network.
#[derive(Clone, Debug)]
pub struct Graph {
    pub nodes: Vec<Node>,
    pub curves: Vec<SplitCurve>,
    pub segments: Vec<Segment>,
    /// Names of the input curves, for messages.
    pub(crate) labels: Vec<String>,
}

impl Graph {
    /// `segment 4 (curve 2 "rim", from node 1 at (…) to node 3 at (…))`, for messages.
    pub fn describe_segment(&self, s: usize) -> String {
        let seg = &self.segments[s];
        format!(
            "segment {s} ({}, from node {} at {} to node {} at {})",
            self.labels[seg.curve],
            seg.start,
            fmt_point(self.nodes[seg.start].position),
            seg.end,
            fmt_point(self.nodes[seg.end].position)
        )
    }

    /// The connected component of every node (its smallest node index), through segments.
    pub fn node_components(&self) -> Vec<usize> {
        let mut uf = UnionFind::new(self.nodes.len());
        for s in &self.segments {
            uf.union(s.start, s.end);
        }
        (0..self.nodes.len()).map(|i| uf.find(i)).collect()
    }

    /// `node 3 at (x, y, z)`, for messages.
    pub fn describe_node(&self, n: usize) -> String {
        format!("node {n} at {}", fmt_point(self.nodes[n].position))
    }
}

/// Where a curve passes: edge `edge` (from sample `edge` to the next) at fraction `s`.
#[derive(Clone, Copy, Debug)]
struct Loc {
    curve: usize,
    edge: usize,
    s: f64,
}

struct Hit {
    mid: DVec3,
    a: Loc,
    b: Loc,
}

type Cell = (i64, i64, i64);

fn cell_of(p: DVec3, h: f64) -> Cell {
    ((p.x / h).floor() as i64, (p.y / h).floor() as i64, (p.z / h).floor() as i64)
}

/// Finds the nodes of a validated network and splits its curves into segments.
///
/// `snap` is the snapping tolerance (a distance). Errors: curves that overlap (run within the
/// tolerance of each other over a stretch longer than a few tolerances), and curves whose
/// normals disagree in orientation at a node.
pub fn find_nodes(net: &Network, snap: f64) -> Result<(Graph, Vec<Warning>)> {
    let curves = &net.curves;
    let labels: Vec<String> = (0..curves.len()).map(|i| curve_label(curves, i)).collect();
    let warnings = Vec::new();

    // Cumulative arc length of each polyline, and edge list.
    let arcs: Vec<Vec<f64>> = curves
        .iter()
        .map(|c| {
            let n = c.points.len();
            let mut a = Vec::with_capacity(n + 1);
            a.push(0.0);
            let m = if c.closed { n } else { n - 1 };
            for i in 0..m {
                a.push(a[i] + c.points[i].distance(c.points[(i + 1) % n]));
            }
            a
        })
        .collect();
    let num_edges = |c: usize| arcs[c].len() - 1;
    let mut edges: Vec<(u32, u32)> = Vec::new();
    for c in 0..curves.len() {
        for e in 0..num_edges(c) {
            edges.push((c as u32, e as u32));
        }
    }
    let ends = |c: usize, e: usize| {
        let p = &curves[c].points;
        (p[e], p[(e + 1) % p.len()])
    };
    let arc_at = |l: Loc| arcs[l.curve][l.edge] + l.s * (arcs[l.curve][l.edge + 1] - arcs[l.curve][l.edge]);
    // Distance along a curve between two arc positions (the shorter way round on loops).
    let along = |c: usize, a: f64, b: f64| {
        let d = (a - b).abs();
        if curves[c].closed {
            d.min(arcs[c][arcs[c].len() - 1] - d)
        } else {
            d
        }
    };

    // Spatial hash of edge boxes inflated by the tolerance.
    let mut lengths: Vec<f64> =
        edges.iter().map(|&(c, e)| arcs[c as usize][e as usize + 1] - arcs[c as usize][e as usize]).collect();
    lengths.sort_by(f64::total_cmp);
    let median = lengths[lengths.len() / 2];
    let h = (2.0 * snap).max(median).max(f64::MIN_POSITIVE);
    let boxes: Vec<Aabb> = edges
        .iter()
        .map(|&(c, e)| {
            let (p, q) = ends(c as usize, e as usize);
            let mut b = Aabb::of([p, q]);
            b.min -= DVec3::splat(snap);
            b.max += DVec3::splat(snap);
            b
        })
        .collect();
    let mut grid: HashMap<Cell, Vec<u32>> = HashMap::new();
    for (k, b) in boxes.iter().enumerate() {
        let (lo, hi) = (cell_of(b.min, h), cell_of(b.max, h));
        for x in lo.0..=hi.0 {
            for y in lo.1..=hi.1 {
                for z in lo.2..=hi.2 {
                    grid.entry((x, y, z)).or_default().push(k as u32);
                }
            }
        }
    }

    // Hits: closest points of edge pairs within the tolerance.
    let mut hits: Vec<Hit> = Vec::new();
    for (cell, list) in &grid {
        for (i, &ka) in list.iter().enumerate() {
            for &kb in &list[i + 1..] {
                let (ba, bb) = (&boxes[ka as usize], &boxes[kb as usize]);
                let lo = ba.min.max(bb.min);
                let hi = ba.max.min(bb.max);
                if lo.x > hi.x || lo.y > hi.y || lo.z > hi.z || cell_of(lo, h) != *cell {
                    continue; // disjoint, or the pair is handled in another cell
                }
                let (ca, ea) = (edges[ka as usize].0 as usize, edges[ka as usize].1 as usize);
                let (cb, eb) = (edges[kb as usize].0 as usize, edges[kb as usize].1 as usize);
                if ca == cb {
                    let m = num_edges(ca);
                    let adjacent = ea.abs_diff(eb) <= 1 || (curves[ca].closed && ea.abs_diff(eb) == m - 1);
                    if adjacent {
                        continue;
                    }
                }
                let (p0, p1) = ends(ca, ea);
                let (q0, q1) = ends(cb, eb);
                let (s, t) = closest_params_segment_segment(p0, p1, q0, q1);
                let (pa, pb) = (p0.lerp(p1, s), q0.lerp(q1, t));
                if pa.distance(pb) > snap {
                    continue;
                }
                let a = Loc { curve: ca, edge: ea, s };
                let b = Loc { curve: cb, edge: eb, s: t };
                if ca == cb && along(ca, arc_at(a), arc_at(b)) <= 4.0 * snap {
                    continue; // the same stretch of curve (dense samples within the tolerance)
                }
                hits.push(Hit { mid: 0.5 * (pa + pb), a, b });
            }
        }
    }
    // Deterministic order regardless of hash iteration.
    hits.sort_by(|x, y| {
        (x.a.curve, x.a.edge, x.b.curve, x.b.edge)
            .cmp(&(y.a.curve, y.a.edge, y.b.curve, y.b.edge))
            .then(x.a.s.total_cmp(&y.a.s))
    });

    // Cluster hits closer than twice the tolerance.
    let mut uf = UnionFind::new(hits.len());
    let hc = (2.0 * snap).max(f64::MIN_POSITIVE);
    let mut hgrid: HashMap<Cell, Vec<usize>> = HashMap::new();
    for (k, hit) in hits.iter().enumerate() {
        hgrid.entry(cell_of(hit.mid, hc)).or_default().push(k);
    }
    for (k, hit) in hits.iter().enumerate() {
        let c = cell_of(hit.mid, hc);
        for dx in -1..=1 {
            for dy in -1..=1 {
                for dz in -1..=1 {
                    if let Some(list) = hgrid.get(&(c.0 + dx, c.1 + dy, c.2 + dz)) {
                        for &j in list {
                            if j > k && hits[j].mid.distance(hit.mid) <= hc {
                                uf.union(k, j);
                            }
                        }
                    }
                }
            }
        }
    }
    // Two hits of the same two curves within a few tolerances along both curves are one meeting
    // (curves that meet at a shallow angle stay within the tolerance over a stretch longer than
    // the clustering distance; a curve that ends on another one at a shallow angle touches it
    // twice): one node, not two nodes joined by two tiny segments of the two curves.
    let mut by_pair: HashMap<(usize, usize), Vec<usize>> = HashMap::new();
    for (k, hit) in hits.iter().enumerate() {
        if hit.a.curve != hit.b.curve {
            by_pair.entry((hit.a.curve, hit.b.curve)).or_default().push(k);
        }
    }
    let mut pair_keys: Vec<&(usize, usize)> = by_pair.keys().collect();
    pair_keys.sort_unstable();
    for key in pair_keys {
        let list = &by_pair[key];
        for (i, &k) in list.iter().enumerate() {
            for &j in &list[i + 1..] {
                let (x, y) = (&hits[k], &hits[j]);
                if along(key.0, arc_at(x.a), arc_at(y.a)) <= SAME_MEETING * snap
                    && along(key.1, arc_at(x.b), arc_at(y.b)) <= SAME_MEETING * snap
                {
                    uf.union(k, j);
                }
            }
        }
    }
    let mut clusters: Vec<Vec<usize>> = Vec::new();
    let mut root_index: HashMap<usize, usize> = HashMap::new();
    for k in 0..hits.len() {
        let r = uf.find(k);
        let ci = *root_index.entry(r).or_insert_with(|| {
            clusters.push(Vec::new());
            clusters.len() - 1
        });
        clusters[ci].push(k);
    }

    // Each cluster becomes a node; each distinct passage of a curve through it a node sample.
    let mut nodes: Vec<Node> = Vec::new();
    // Per curve: (arc position, node id).
    let mut on_curve: Vec<Vec<(f64, usize)>> = vec![Vec::new(); curves.len()];
    let point_at = |l: Loc| {
        let (p, q) = ends(l.curve, l.edge);
        p.lerp(q, l.s)
    };
    let normal_at = |l: Loc| {
        let c = &curves[l.curve];
        let n0 = c.normals[l.edge];
        let n1 = c.normals[(l.edge + 1) % c.points.len()];
        let n = n0.lerp(n1, l.s);
        if n.length_squared() > 1e-24 {
            n.normalize()
        } else {
            n0
        }
    };
    for cluster in &clusters {
        let mut locs: Vec<(usize, f64, Loc)> = Vec::new();
        for &k in cluster {
            for l in [hits[k].a, hits[k].b] {
                locs.push((l.curve, arc_at(l), l));
            }
        }
        locs.sort_by(|x, y| x.0.cmp(&y.0).then(x.1.total_cmp(&y.1)));
        // Split into passages: runs of one curve whose arc positions are close.
        let mut passages: Vec<(usize, f64, Loc)> = Vec::new();
        let mut i = 0;
        while i < locs.len() {
            let mut j = i + 1;
            while j < locs.len()
                && locs[j].0 == locs[i].0
                && along(locs[i].0, locs[j].1, locs[j - 1].1) <= SAME_MEETING * snap
            {
                j += 1;
            }
            let c = locs[i].0;
            let extent = along(c, locs[j - 1].1, locs[i].1);
            if extent > 8.0 * snap {
                let others: Vec<&str> = locs.iter().filter(|l| l.0 != c).map(|l| labels[l.0].as_str()).collect();
                let other = others.first().copied().unwrap_or("itself");
                return Err(Error::input(format!(
                    "{} runs within the snapping tolerance ({snap:.3e}) of {other} for a length of {extent:.3e} near {}: \
                     overlapping or coincident curves cannot be surfaced; remove the duplicate or lower \"snap\"",
                    labels[c],
                    fmt_point(point_at(locs[i].2)),
                )));
            }
            // The passage at the middle location of the run.
            passages.push(locs[(i + j - 1) / 2]);
            i = j;
        }
        // A closed curve's run may straddle its seam (arc 0 / length): merge first and last.
        let mut merged: Vec<(usize, f64, Loc)> = Vec::new();
        for p in passages {
            if !merged.iter().any(|q| q.0 == p.0 && along(p.0, p.1, q.1) <= SAME_MEETING * snap) {
                merged.push(p);
            }
        }
        let passages = merged;
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
                    let mut together = true;
                    let mut probed = false;
                    for frac in [0.25, 0.5, 1.0] {
                        let Some(probe) = polyline_at_arc(
                            &curves[pa.0].points,
                            &arcs[pa.0],
                            curves[pa.0].closed,
                            pa.1 + side * frac * delta,
                        ) else {
                            break;
                        };
                        probed = true;
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
                    if probed && together {
                        return Err(Error::input(format!(
                            "{} runs within the snapping tolerance ({snap:.3e}) of {} near {}: overlapping or coincident \
                             curves (or curves touching at a very shallow angle) cannot be surfaced; remove the duplicate \
                             or lower \"snap\"",
                            labels[pa.0],
                            if pa.0 == pb.0 { "itself".to_string() } else { labels[pb.0].clone() },
                            fmt_point(point_at(pa.2)),
                        )));
                    }
                }
            }
        }
        let position = passages.iter().map(|p| point_at(p.2)).sum::<DVec3>() / passages.len() as f64;
        let normals: Vec<DVec3> = passages.iter().map(|p| normal_at(p.2)).collect();
        for a in 0..normals.len() {
            for b in a + 1..normals.len() {
                let cos = normals[a].dot(normals[b]);
                if cos < 0.0 {
                    return Err(Error::input(format!(
                        "{} and {} meet at {} with normals {:.0}° apart: one of them points inward. \
                         Normals must point to the outside of the surface on every curve; flip the normals of one curve",
                        labels[passages[a].0],
                        labels[passages[b].0],
                        fmt_point(position),
                        cos.clamp(-1.0, 1.0).acos().to_degrees()
                    )));
                }
            }
        }
        let normal = normals.iter().sum::<DVec3>().normalize_or_zero();
        let normal = if normal == DVec3::ZERO { normals[0] } else { normal };
        let id = nodes.len();
        nodes.push(Node { position, normal });
        for p in &passages {
            on_curve[p.0].push((p.1, id));
        }
    }

    // Open curves end at nodes; closed curves without a crossing get one node at sample 0.
    for (c, curve) in curves.iter().enumerate() {
        let total = arcs[c][arcs[c].len() - 1];
        if curve.closed {
            if on_curve[c].is_empty() {
                nodes.push(Node { position: curve.points[0], normal: curve.normals[0] });
                on_curve[c].push((0.0, nodes.len() - 1));
            }
            continue;
        }
        let near = |x: f64, list: &[(f64, usize)]| list.iter().any(|&(a, _)| (a - x).abs() <= snap.max(1e-12 * total));
        let last = curve.points.len() - 1;
        if !near(0.0, &on_curve[c]) {
            nodes.push(Node { position: curve.points[0], normal: curve.normals[0] });
            on_curve[c].push((0.0, nodes.len() - 1));
        }
        if !near(total, &on_curve[c]) {
            nodes.push(Node { position: curve.points[last], normal: curve.normals[last] });
            on_curve[c].push((total, nodes.len() - 1));
        }
    }

    // Insert the nodes into the curves.
    let mut split: Vec<SplitCurve> = Vec::with_capacity(curves.len());
    for (c, curve) in curves.iter().enumerate() {
        let n = curve.points.len();
        let list = &mut on_curve[c];
        list.sort_by(|a, b| a.0.total_cmp(&b.0));
        let arc = &arcs[c];
        let total = arc[arc.len() - 1];
        // Sample at which each node lands: Err(insert position along edge) or Ok(existing sample).
        let mut snapped: Vec<Option<usize>> = vec![None; n];
        let mut inserts: Vec<(usize, f64, usize)> = Vec::new(); // (edge, arc, node)
        let wrap = |a: f64| if curve.closed { a.rem_euclid(total) } else { a.clamp(0.0, total) };
        let wrapped: Vec<f64> = list.iter().map(|&(a, _)| wrap(a)).collect();
        for &(a, node) in list.iter() {
            let a = wrap(a);
            let e = (arc.partition_point(|&x| x <= a).max(1) - 1).min(arc.len() - 2);
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
        let mut points = Vec::with_capacity(n + inserts.len());
        let mut normals = Vec::with_capacity(n + inserts.len());
        let mut markers = Vec::new();
        let mut k = 0;
        for i in 0..n {
            match snapped[i] {
                Some(node) => {
                    markers.push((points.len(), node));
                    points.push(nodes[node].position);
                    normals.push(nodes[node].normal);
                }
                None => {
                    points.push(curve.points[i]);
                    normals.push(curve.normals[i]);
                }
            }
            while k < inserts.len() && inserts[k].0 == i {
                let node = inserts[k].2;
                markers.push((points.len(), node));
                points.push(nodes[node].position);
                normals.push(nodes[node].normal);
                k += 1;
            }
        }
        // Rotate closed curves so that a node is at sample 0.
        if curve.closed {
            let r = markers[0].0;
            points.rotate_left(r);
            normals.rotate_left(r);
            let m = points.len();
            for mk in markers.iter_mut() {
                mk.0 = (mk.0 + m - r) % m;
            }
            markers.sort();
        }
        split.push(SplitCurve {
            name: curve.name.clone(),
            points,
            normals,
            closed: curve.closed,
            boundary: curve.boundary,
            nodes: markers,
        });
    }

    // Two nodes on one curve may have landed on coincident positions: reject degenerate
    // (zero-length) pieces with a clear message.
    let mut segments = Vec::new();
    for (c, sc) in split.iter().enumerate() {
        let m = sc.points.len();
        for i in 1..m {
            if sc.points[i].distance(sc.points[i - 1]) <= 1e-12 * total_scale(&sc.points) {
                return Err(Error::input(format!(
                    "{}: two nodes fall on the same point {} (crossings closer than the sampling); resample the curve more finely or lower \"snap\"",
                    labels[c],
                    fmt_point(sc.points[i])
                )));
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
    Ok((Graph { nodes, curves: split, segments, labels }, warnings))
}

/// Hits of the same two curves closer than this (in snapping tolerances, along both curves)
/// form one node; also the largest gap (along a curve) between the hits of one passage of a
/// curve through a node.
const SAME_MEETING: f64 = 4.0;

/// How far from a node (in snapping tolerances) two curves must have separated for the node to
/// count as a crossing rather than an overlap: crossings at angles below asin(1/20) ≈ 3° are
/// reported as overlaps.
const OVERLAP_PROBE: f64 = 20.0;

/// Point of a polyline at arc length `s` (wrapping for closed curves); `None` past the ends of
/// an open curve.
fn polyline_at_arc(points: &[DVec3], arc: &[f64], closed: bool, s: f64) -> Option<DVec3> {
    let total = arc[arc.len() - 1];
    let s = if closed {
        s.rem_euclid(total)
    } else if (0.0..=total).contains(&s) {
        s
    } else {
        return None;
    };
    let e = (arc.partition_point(|&x| x <= s).max(1) - 1).min(arc.len() - 2);
    let len = arc[e + 1] - arc[e];
    let t = if len > 0.0 { (s - arc[e]) / len } else { 0.0 };
    Some(points[e].lerp(points[(e + 1) % points.len()], t))
}

/// Distance from `p` to the part of a polyline within arc length `half` of `center`.
fn polyline_distance(points: &[DVec3], arc: &[f64], closed: bool, center: f64, half: f64, p: DVec3) -> f64 {
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

fn total_scale(points: &[DVec3]) -> f64 {
    Aabb::of(points.iter().copied()).diagonal().max(f64::MIN_POSITIVE)
}

#[cfg(test)]
#[path = "tests/nodes.rs"]
mod tests;
