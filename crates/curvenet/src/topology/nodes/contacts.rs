//! Where curves come within the snapping tolerance of each other (*contacts*), and which
//! contacts are one meeting of curves (*clusters*, one node each).
//!
//! Candidate pairs of polyline edges come from a uniform spatial hash of their bounding boxes
//! (inflated by the tolerance), not from all pairs; the closest points of a candidate pair
//! ([`closest_params_segment_segment`]) within the tolerance are a contact. Contacts closer
//! than twice the tolerance are one cluster, and so are contacts of the same two curves within
//! [`SAME_MEETING`] tolerances along both curves.

use super::SAME_MEETING;
use crate::geom::{closest_params_segment_segment, Aabb, DVec3};
use crate::network::Curve;
use crate::topology::UnionFind;
use std::collections::HashMap;

/// The curves of a network as polylines with their cumulative arc lengths: the state the
/// stages of [`super::find_nodes`] share.
pub(super) struct Polylines<'a> {
    /// The input curves.
    pub(super) curves: &'a [Curve],
    /// Per curve: the arc length at each sample, then (closed curves) the total length once
    /// more at the end; `arcs[c].len() - 1` edges.
    pub(super) arcs: Vec<Vec<f64>>,
    /// Per curve: its name for messages ([`crate::network::curve_label`]).
    pub(super) labels: &'a [String],
    /// Some curve is a crease: the split curves keep their sides' normals.
    pub(super) creases: bool,
}

impl<'a> Polylines<'a> {
    /// The polylines of `curves`, named `labels` in messages.
    pub(super) fn new(curves: &'a [Curve], labels: &'a [String]) -> Self {
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
        Polylines { curves, arcs, labels, creases: curves.iter().any(Curve::is_crease) }
    }

    /// Number of edges of curve `c`.
    pub(super) fn num_edges(&self, c: usize) -> usize {
        self.arcs[c].len() - 1
    }

    /// Length of curve `c`.
    pub(super) fn total(&self, c: usize) -> f64 {
        self.arcs[c][self.arcs[c].len() - 1]
    }

    /// The end points of edge `e` of curve `c`.
    pub(super) fn ends(&self, c: usize, e: usize) -> (DVec3, DVec3) {
        let p = &self.curves[c].points;
        (p[e], p[(e + 1) % p.len()])
    }

    /// Arc length of a location along its curve.
    pub(super) fn arc_at(&self, l: Loc) -> f64 {
        let arcs = &self.arcs;
        arcs[l.curve][l.edge] + l.s * (arcs[l.curve][l.edge + 1] - arcs[l.curve][l.edge])
    }

    /// Distance along curve `c` between two arc positions (the shorter way round on loops).
    pub(super) fn along(&self, c: usize, a: f64, b: f64) -> f64 {
        let d = (a - b).abs();
        if self.curves[c].closed {
            d.min(self.arcs[c][self.arcs[c].len() - 1] - d)
        } else {
            d
        }
    }

    /// Position of a location.
    pub(super) fn point_at(&self, l: Loc) -> DVec3 {
        let (p, q) = self.ends(l.curve, l.edge);
        p.lerp(q, l.s)
    }

    /// Unit normal at a location: the normals of the edge's ends interpolated (the first one
    /// where they cancel out); zero on a curve without normals (unknown).
    pub(super) fn normal_at(&self, l: Loc) -> DVec3 {
        let c = &self.curves[l.curve];
        if !c.has_normals() {
            return DVec3::ZERO;
        }
        let n0 = c.mean_normal(l.edge);
        let n1 = c.mean_normal((l.edge + 1) % c.points.len());
        lerp_unit(n0, n1, l.s)
    }

    /// The unit normals of both sides of a crease curve at a location (`[left, right]`;
    /// both the curve's normal on a smooth curve). The curve must carry normals.
    pub(super) fn sides_at(&self, l: Loc) -> [DVec3; 2] {
        let c = &self.curves[l.curve];
        let j = (l.edge + 1) % c.points.len();
        [lerp_unit(c.normals[l.edge], c.normals[j], l.s), lerp_unit(c.normal_right(l.edge), c.normal_right(j), l.s)]
    }
}

/// `a + s (b − a)` normalised (`a` where it vanishes).
fn lerp_unit(a: DVec3, b: DVec3, s: f64) -> DVec3 {
    let n = a.lerp(b, s);
    if n.length_squared() > 1e-24 {
        n.normalize()
    } else {
        a
    }
}

/// Where a curve passes: edge `edge` (from sample `edge` to the next) at fraction `s`.
#[derive(Clone, Copy, Debug)]
pub(super) struct Loc {
    pub(super) curve: usize,
    pub(super) edge: usize,
    pub(super) s: f64,
}

/// A contact: the closest points `a` and `b` of two edges within the tolerance, and their
/// midpoint.
pub(super) struct Hit {
    pub(super) mid: DVec3,
    pub(super) a: Loc,
    pub(super) b: Loc,
}

type Cell = (i64, i64, i64);

/// Candidate pairs of edges (within the tolerance of one grid cell) allowed per edge before the
/// network counts as too dense to find its nodes ([`find_contacts`]).
pub(super) const MAX_PAIRS_PER_EDGE: usize = 2000;

fn cell_of(p: DVec3, h: f64) -> Cell {
    ((p.x / h).floor() as i64, (p.y / h).floor() as i64, (p.z / h).floor() as i64)
}

/// The edges of all polylines in a uniform spatial hash (cells of side `h`: the median edge
/// length, at least twice the tolerance): each edge in the cells its pieces of length ≤ `h`,
/// inflated by the tolerance, meet — linear in the edge's length, also for one long edge.
struct EdgeHash {
    /// `(curve, edge)` of every edge.
    edges: Vec<(u32, u32)>,
    /// Per edge: its bounding box inflated by the tolerance.
    boxes: Vec<Aabb>,
    /// The edges whose box meets each cell.
    grid: HashMap<Cell, Vec<u32>>,
}

impl EdgeHash {
    fn new(lines: &Polylines, snap: f64) -> Self {
        let (curves, arcs) = (lines.curves, &lines.arcs);
        let mut edges: Vec<(u32, u32)> = Vec::new();
        for c in 0..curves.len() {
            for e in 0..lines.num_edges(c) {
                edges.push((c as u32, e as u32));
            }
        }
        // Spatial hash of edge boxes inflated by the tolerance.
        let mut lengths: Vec<f64> =
            edges.iter().map(|&(c, e)| arcs[c as usize][e as usize + 1] - arcs[c as usize][e as usize]).collect();
        lengths.sort_by(f64::total_cmp);
        let median = lengths[lengths.len() / 2];
        let h = (2.0 * snap).max(median).max(f64::MIN_POSITIVE);
        let boxes: Vec<Aabb> = edges
            .iter()
            .map(|&(c, e)| {
                let (p, q) = lines.ends(c as usize, e as usize);
                let mut b = Aabb::of([p, q]);
                b.min -= DVec3::splat(snap);
                b.max += DVec3::splat(snap);
                b
            })
            .collect();
        // Each edge goes into the cells its pieces of length ≤ h meet (inflated by the
        // tolerance), not every cell of its box: a long straight edge (a 2-sample CAD line
        // across the network) fills a line of cells, not a slab of them.
        let mut grid: HashMap<Cell, Vec<u32>> = HashMap::new();
        let mut cells: Vec<Cell> = Vec::new();
        for (k, &(c, e)) in edges.iter().enumerate() {
            let (p, q) = lines.ends(c as usize, e as usize);
            crate::geom::segment_cells(p, q, snap, h, &mut cells);
            for &cell in &cells {
                grid.entry(cell).or_default().push(k as u32);
            }
        }
        EdgeHash { edges, boxes, grid }
    }
}

/// The contacts between the polylines: for every pair of edges whose inflated boxes overlap
/// (and that are not neighbours on one curve), their closest points when they are within
/// `snap` of each other. Contacts of a curve with itself within `4 snap` along it (a stretch of
/// dense samples) are not contacts. Sorted by curves, edges and position (deterministic).
///
/// Errors ([`Error::Input`]): more candidate pairs than [`MAX_PAIRS_PER_EDGE`] per edge (plus
/// a million): curves so dense within the tolerance (a hairball, an edge soup of random
/// segments) that their meetings cannot be told apart — refused before the pairs fill memory.
pub(super) fn find_contacts(lines: &Polylines, snap: f64) -> crate::error::Result<Vec<Hit>> {
    let curves = lines.curves;
    let EdgeHash { edges, boxes, grid } = EdgeHash::new(lines, snap);
    // Candidate pairs: edges that share a cell and whose inflated boxes overlap (once each).
    let mut pairs: Vec<(u32, u32)> = Vec::new();
    let limit = MAX_PAIRS_PER_EDGE * edges.len() + 1_000_000;
    for list in grid.values() {
        // `list` is in edge order, i.e. by curve, then along it. The pairs of one curve that are
        // the same stretch of it by arc length alone are a run at the start of what follows each
        // edge: skipped by a binary search, not visited — on densely sampled curves a cell holds
        // many edges of one pass of a curve, and visiting all their pairs would be quadratic.
        for (i, &ka) in list.iter().enumerate() {
            let rest = &list[i + 1..];
            let skip = rest.partition_point(|&kb| along_forward(lines, &edges, ka, kb) <= 4.0 * snap);
            for &kb in &rest[skip..] {
                let (ba, bb) = (&boxes[ka as usize], &boxes[kb as usize]);
                let lo = ba.min.max(bb.min);
                let hi = ba.max.min(bb.max);
                if lo.x <= hi.x && lo.y <= hi.y && lo.z <= hi.z && !same_stretch(lines, &edges, ka, kb, snap) {
                    pairs.push((ka.min(kb), ka.max(kb)));
                }
            }
            // Refuse before the pairs fill memory.
            if pairs.len() > limit {
                let (c, _) = edges[ka as usize];
                return Err(crate::error::Error::input(format!(
                    "{} and {} other curve pieces crowd within the snapping tolerance ({snap:.3e}) of one place: the \
                     curves are too dense there to tell their meetings apart (a tangle of strokes or random segments); \
                     give a smaller `snap` or clean the curves",
                    lines.labels[c as usize],
                    list.len() - 1
                ))
                .curve(c as usize));
            }
        }
    }
    pairs.sort_unstable();
    pairs.dedup();
    // Hits: closest points of edge pairs within the tolerance.
    let mut hits: Vec<Hit> = Vec::new();
    for (ka, kb) in pairs {
        let (ca, ea) = (edges[ka as usize].0 as usize, edges[ka as usize].1 as usize);
        let (cb, eb) = (edges[kb as usize].0 as usize, edges[kb as usize].1 as usize);
        if ca == cb {
            let m = lines.num_edges(ca);
            let adjacent = ea.abs_diff(eb) <= 1 || (curves[ca].closed && ea.abs_diff(eb) == m - 1);
            if adjacent {
                continue;
            }
        }
        let (p0, p1) = lines.ends(ca, ea);
        let (q0, q1) = lines.ends(cb, eb);
        let (s, t) = closest_params_segment_segment(p0, p1, q0, q1);
        let (pa, pb) = (p0.lerp(p1, s), q0.lerp(q1, t));
        if pa.distance(pb) > snap {
            continue;
        }
        let a = Loc { curve: ca, edge: ea, s };
        let b = Loc { curve: cb, edge: eb, s: t };
        if ca == cb && lines.along(ca, lines.arc_at(a), lines.arc_at(b)) <= 4.0 * snap {
            continue; // the same stretch of curve (dense samples within the tolerance)
        }
        hits.push(Hit { mid: 0.5 * (pa + pb), a, b });
    }
    // Deterministic order regardless of hash iteration.
    hits.sort_by(|x, y| {
        (x.a.curve, x.a.edge, x.b.curve, x.b.edge)
            .cmp(&(y.a.curve, y.a.edge, y.b.curve, y.b.edge))
            .then(x.a.s.total_cmp(&y.a.s))
    });
    Ok(hits)
}

/// How far along one curve edge `kb` reaches beyond the start of edge `ka` (`kb` after `ka` in
/// edge order, not going round a loop): a bound of [`same_stretch`]'s distance, monotone in `kb`
/// over the edges of `ka`'s curve; infinite for another curve.
fn along_forward(lines: &Polylines, edges: &[(u32, u32)], ka: u32, kb: u32) -> f64 {
    let ((ca, ea), (cb, eb)) = (edges[ka as usize], edges[kb as usize]);
    if ca != cb {
        return f64::INFINITY;
    }
    let arcs = &lines.arcs[ca as usize];
    arcs[eb as usize + 1] - arcs[ea as usize]
}

/// Edges `ka` and `kb` of one curve whose points are all within `4 snap` of each other along
/// it: any contact between them is the same stretch of curve (dense samples within the
/// tolerance, see [`find_contacts`]), so the pair is not even a candidate — on densely sampled
/// curves almost every pair in a cell is such a pair.
fn same_stretch(lines: &Polylines, edges: &[(u32, u32)], ka: u32, kb: u32, snap: f64) -> bool {
    let ((ca, ea), (cb, eb)) = (edges[ka as usize], edges[kb as usize]);
    if ca != cb {
        return false;
    }
    let (c, arcs) = (ca as usize, &lines.arcs[ca as usize]);
    let (ea, eb) = (ea as usize, eb as usize);
    let far = lines.along(c, arcs[ea], arcs[eb + 1]).max(lines.along(c, arcs[ea + 1], arcs[eb]));
    let far = far.max(lines.along(c, arcs[ea], arcs[eb])).max(lines.along(c, arcs[ea + 1], arcs[eb + 1]));
    far <= 4.0 * snap
}

/// Groups the contacts `hits` into meetings (one node each): contacts whose midpoints are
/// within `2 snap` of each other (transitively), and contacts of the same two curves within
/// [`SAME_MEETING`] tolerances along both curves. Returns the clusters as lists of indices
/// into `hits`, in the order of their first contact.
pub(super) fn cluster_contacts(lines: &Polylines, hits: &[Hit], snap: f64) -> Vec<Vec<usize>> {
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
                if lines.along(key.0, lines.arc_at(x.a), lines.arc_at(y.a)) <= SAME_MEETING * snap
                    && lines.along(key.1, lines.arc_at(x.b), lines.arc_at(y.b)) <= SAME_MEETING * snap
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
    clusters
}

#[cfg(test)]
#[path = "tests/contacts.rs"]
mod tests;
