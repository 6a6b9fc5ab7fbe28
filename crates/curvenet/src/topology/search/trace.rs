//! Candidate cycles: faces traced with a normal of their own (docs/design.md §15.1).
//!
//! The rotation walk of \[CG\] §3.2 leaves each node along the clockwise neighbour of the
//! segment it arrived by, around the node's normal. Here the normal is not the network's: each
//! trace starts at a half-edge with one of the two signs of its start node's tangent plane
//! normal and carries it along (parallel transport, Wang et al. 2008), taking at each node the
//! sign of the node's tangent plane normal that the carried one agrees with. A node whose sign
//! the network as a whole gets wrong, or where two sheets touch, then spoils only the traces
//! through it, not every face of its component. Each trace records what its cost needs: the
//! total turning of its boundary and how far the carried normal comes back from where it
//! started.

use super::super::cycles::HalfEdge;
use super::super::nodes::Graph;
use super::super::orient::transport;
use crate::curves::CurveSpline;
use crate::geom::DVec3;

/// The longest cycle traced, in segments: longer ones are not patches of a sketch.
pub(super) const MAX_CYCLE: usize = 48;

/// Choices tried at each node of a trace: the rotation's clockwise neighbour, then the next
/// (a discrepancy).
const BRANCHES: usize = 2;

/// Steps (half-edges appended) of one trace at each number of discrepancies, its dead ends
/// included.
const STEPS: usize = 400;

/// Turns other than the clockwise neighbour on one face at most: the search tries the faces
/// with none, then one, then two (a limited discrepancy search, Harvey and Ginsberg 1995).
const DISCREPANCIES: usize = 2;

/// The state of one trace's search: the steps left, the faces found and how many are wanted,
/// and the segments it may run along (all when `None`).
struct Search<'b> {
    budget: usize,
    /// Turns other than the clockwise neighbour still allowed on this path, and taken.
    discrepancies: usize,
    used: usize,
    found: Vec<Trace>,
    want: usize,
    allowed: Option<&'b [bool]>,
}

impl Search<'_> {
    /// Whether the search is over: out of steps, or as many faces found as wanted.
    fn done(&self) -> bool {
        self.budget == 0 || self.found.len() >= self.want
    }
}

/// A face being traced: its half-edges so far and what the cost and the fold test need.
#[derive(Default)]
struct Partial {
    cycle: Vec<HalfEdge>,
    normals: Vec<DVec3>,
    /// Every sample of the face with the index of its half-edge (for the inward directions).
    samples: Vec<(DVec3, usize)>,
    /// Per half-edge: the node it arrives at.
    visited: Vec<usize>,
}

impl Partial {
    /// Appends half-edge `h` with its start normal `n` and samples `p`, arriving at node `v`.
    fn push(&mut self, h: HalfEdge, n: DVec3, p: &[DVec3], v: usize) {
        self.cycle.push(h);
        self.normals.push(n);
        let k = self.cycle.len() - 1;
        self.samples.extend(p.iter().skip(1).map(|&x| (x, k)));
        self.visited.push(v);
    }

    /// Removes the last half-edge and all it brought.
    fn pop(&mut self) {
        let k = self.cycle.len() - 1;
        self.cycle.pop();
        self.normals.pop();
        self.visited.pop();
        while self.samples.last().is_some_and(|s| s.1 == k) {
            self.samples.pop();
        }
    }
}

/// Per-segment geometry and per-node segment ends, for tracing.
pub(super) struct Walker<'a> {
    g: &'a Graph,
    /// Per segment: its samples and unit tangents (spline) in sample order.
    paths: Vec<(Vec<DVec3>, Vec<DVec3>)>,
    /// Per node: its segment ends `(segment, at_start, unit tangent away from the node)`.
    pub(super) ends: Vec<Vec<(usize, bool, DVec3)>>,
    /// Per node: its unsigned tangent plane normal, where the tangents span a plane.
    estimates: Vec<Option<DVec3>>,
    /// Per node: the tangent plane normal where every segment end lies within 30° of that
    /// plane; `None` where sheets meet at an angle (petals touching at a flower's centre), so
    /// that a trace through the node keeps the normal of its own sheet.
    planar: Vec<Option<DVec3>>,
}

/// A traced face: its half-edges, and per half-edge the carried normal at its start node.
#[derive(Clone, Debug)]
pub(super) struct Trace {
    pub(super) cycle: Vec<HalfEdge>,
    pub(super) normals: Vec<DVec3>,
    /// Per half-edge: the unit directions into the face at the segment's start node and at
    /// its end node (in the segment's own order, whichever way the face runs along it), for
    /// the fold test between faces that share the segment ([`Walker::corner_inward`]).
    pub(super) inward: Vec<[DVec3; 2]>,
    /// Total turning of the boundary about the carried normal (radians): 2π for a flat face
    /// traversed counter-clockwise, 2π − ∫K on a curved one (Gauss–Bonnet).
    pub(super) turning: f64,
    /// Angle (radians) between the start normal and the normal carried once around.
    pub(super) holonomy: f64,
    /// Nodes where the face leaves along another segment than the clockwise neighbour.
    pub(super) discrepancies: usize,
}

/// Signed angle from `a` to `b` about the unit axis `n` (both projected across `n`).
fn angle_about(a: DVec3, b: DVec3, n: DVec3) -> f64 {
    let (a, b) = (a - n * a.dot(n), b - n * b.dot(n));
    a.cross(b).dot(n).atan2(a.dot(b))
}

/// The unit direction from `p` (a sample of half-edge `k` of a face, tangent `t`) into the
/// face: towards the nearest sample of the face's other half-edges that lies within about 15°
/// of the plane across `t` at `p` (the face's width there, also where the face is not convex:
/// a half ring's centroid lies outside it), across `t`; towards the centroid of the face's
/// samples where no sample lies in that plane.
fn inward(p: DVec3, t: DVec3, k: usize, samples: &[(DVec3, usize)]) -> DVec3 {
    let across = |d: DVec3| (d - t * d.dot(t)).normalize_or_zero();
    let mut best: Option<(f64, DVec3)> = None;
    for &(q, j) in samples {
        let d = q - p;
        let len = d.length();
        if j == k || len == 0.0 || d.dot(t).abs() > 0.25 * len {
            continue;
        }
        if best.is_none_or(|b| len < b.0) {
            best = Some((len, d));
        }
    }
    match best {
        Some((_, d)) => across(d),
        None => {
            let centroid = samples.iter().map(|s| s.0).sum::<DVec3>() / samples.len().max(1) as f64;
            across(centroid - p)
        }
    }
}

impl<'a> Walker<'a> {
    /// Geometry of `g` for tracing; `splines[c]` is the spline of `g.curves[c]`.
    pub(super) fn new(g: &'a Graph, splines: &[CurveSpline]) -> Self {
        let paths = g
            .segments
            .iter()
            .map(|seg| {
                let c = &g.curves[seg.curve];
                let sp = &splines[seg.curve];
                let m = c.points.len();
                let idx: Vec<usize> = (seg.first..=seg.last).map(|i| i % m).collect();
                let p: Vec<DVec3> = idx.iter().map(|&i| c.points[i]).collect();
                let t: Vec<DVec3> = idx.iter().map(|&i| sp.tangent(sp.knot(i), true).normalize_or_zero()).collect();
                (p, t)
            })
            .collect();
        let mut ends: Vec<Vec<(usize, bool, DVec3)>> = vec![Vec::new(); g.nodes.len()];
        for (s, seg) in g.segments.iter().enumerate() {
            let sp = &splines[seg.curve];
            let t0 = sp.tangent(sp.knot(seg.first), true).normalize_or_zero();
            let t1 = -sp.tangent(sp.knot(seg.last), false).normalize_or_zero();
            ends[seg.start].push((s, true, t0));
            ends[seg.end].push((s, false, t1));
        }
        let estimates: Vec<Option<DVec3>> = ends
            .iter()
            .map(|list| {
                let t: Vec<DVec3> = list.iter().map(|e| e.2).collect();
                super::super::orient::tangent_plane_normal(&t).map(|(n, _)| n)
            })
            .collect();
        let planar = estimates
            .iter()
            .zip(&ends)
            .map(|(e, list)| e.filter(|n| list.iter().all(|x| x.2.dot(*n).abs() < 0.5)))
            .collect();
        Walker { g, paths, ends, estimates, planar }
    }

    /// A start normal for half-edge `h` at its first node: the node's tangent plane normal,
    /// else one across `h` and another segment leaving there; `None` when every segment there
    /// leaves along one line.
    pub(super) fn start_normal(&self, h: HalfEdge) -> Option<DVec3> {
        let seg = &self.g.segments[h.segment];
        let v = if h.forward { seg.start } else { seg.end };
        let t = self.leaving(h);
        let n = match self.estimates[v] {
            Some(n) if (n - t * n.dot(t)).length() > 0.3 => n,
            _ => {
                let mut best = DVec3::ZERO;
                for e in &self.ends[v] {
                    let c = t.cross(e.2);
                    if c.length() > best.length() {
                        best = c;
                    }
                }
                best
            }
        };
        let n = (n - t * n.dot(t)).normalize_or_zero();
        (n.length() > 0.5).then_some(n)
    }

    /// The directions into a face from its half-edge `k` at the segment's start and end
    /// nodes, read off the face's corners there: the neighbouring half-edge's direction away
    /// from the node, across the half-edge's tangent. Where the corner is (nearly) straight
    /// (sine below 0.5: a smooth loop of short segments, a kink) or the face goes on along
    /// the same curve, towards the nearest sample of the face across the tangent at the node
    /// ([`inward`]). Both faces of a segment are so compared at the same two places.
    fn corner_inward(&self, cycle: &[HalfEdge], k: usize, samples: &[(DVec3, usize)]) -> [DVec3; 2] {
        let n = cycle.len();
        let (h, prev, next) = (cycle[k], cycle[(k + n - 1) % n], cycle[(k + 1) % n]);
        let end = |s: usize, at_start: bool| {
            let seg = &self.g.segments[s];
            let v = if at_start { seg.start } else { seg.end };
            self.ends[v].iter().find(|e| e.0 == s && e.1 == at_start).map_or(DVec3::ZERO, |e| e.2)
        };
        let seg = &self.g.segments[h.segment];
        let (p, _) = &self.paths[h.segment];
        // h's end at its first node and at its last (pointing away from the node along h),
        // and the neighbouring half-edge's end there.
        let at_first = (h.forward, end(h.segment, h.forward), prev, end(prev.segment, !prev.forward));
        let at_last = (!h.forward, end(h.segment, !h.forward), next, end(next.segment, next.forward));
        let mut out = [DVec3::ZERO; 2];
        for (at_start, t, other, d) in [at_first, at_last] {
            let node = if at_start { p[0] } else { p[p.len() - 1] };
            let across = d - t * d.dot(t);
            let same_curve = self.g.segments[other.segment].curve == seg.curve && other.segment != h.segment;
            out[usize::from(!at_start)] =
                if across.length() > 0.5 && !same_curve { across.normalize() } else { inward(node, t, k, samples) };
        }
        out
    }

    /// The unit tangent of `h` where it leaves its first node.
    pub(super) fn leaving(&self, h: HalfEdge) -> DVec3 {
        let seg = &self.g.segments[h.segment];
        let v = if h.forward { seg.start } else { seg.end };
        self.ends[v].iter().find(|e| e.0 == h.segment && e.1 == h.forward).map_or(DVec3::ZERO, |e| e.2)
    }

    /// The samples and tangents of `h` in its direction.
    fn path(&self, h: HalfEdge) -> (Vec<DVec3>, Vec<DVec3>) {
        let (p, t) = &self.paths[h.segment];
        if h.forward {
            (p.clone(), t.clone())
        } else {
            (p.iter().rev().copied().collect(), t.iter().rev().map(|x| -*x).collect())
        }
    }

    /// The face on the left of `h0` about the normal `n0` (unit, across `h0`'s tangent),
    /// traced as the module documentation says: of the simple cycles of at most [`MAX_CYCLE`]
    /// segments, the first found with the fewest discrepancies (at most [`DISCREPANCIES`]);
    /// `None` when there is none within the steps.
    ///
    /// A trace that comes back to its first node closes there, whatever the order of the
    /// segment ends around it: at a node where sheets touch (petals at the centre of a flower)
    /// that order means nothing, and the cost judges the corner the closing makes.
    pub(super) fn trace(&self, h0: HalfEdge, n0: DVec3) -> Option<Trace> {
        self.trace_within(h0, n0, None, 1).pop()
    }

    /// The first `want` faces [`Walker::trace`]'s search finds (in its order: clockwise
    /// first, the next neighbour where that leads to no simple cycle), along the segments
    /// `allowed` only (all when `None`; `h0`'s own segment is taken as allowed).
    pub(super) fn trace_within(&self, h0: HalfEdge, n0: DVec3, allowed: Option<&[bool]>, want: usize) -> Vec<Trace> {
        let s0 = &self.g.segments[h0.segment];
        let first = if h0.forward { s0.start } else { s0.end };
        let mut search = Search { budget: 0, discrepancies: 0, used: 0, found: Vec::new(), want, allowed };
        for d in 0..=DISCREPANCIES {
            let mut partial = Partial::default();
            search.budget = STEPS;
            search.discrepancies = d;
            let before = search.found.len();
            // A deeper level finds the shallower one's faces again first: they are not counted.
            search.want = want + before;
            self.extend(h0, n0, first, h0, n0, 0.0, &mut partial, &mut search);
            let seen: Vec<Vec<usize>> = search.found[..before].iter().map(|t| super::key(&t.cycle)).collect();
            let mut k = before;
            while k < search.found.len() {
                if seen.contains(&super::key(&search.found[k].cycle)) {
                    search.found.remove(k);
                } else {
                    k += 1;
                }
            }
            if search.found.len() >= want {
                break;
            }
        }
        search.found
    }

    /// One step of [`Walker::trace`]: appends `h` (carrying the normal `n`, the boundary having
    /// turned by `turning` so far) to `partial` and goes on from its last node — along the
    /// clockwise neighbour of the arrival end first, and where no simple cycle comes of that
    /// and `search` allows another discrepancy, along the next one ([`BRANCHES`] choices per
    /// node, [`STEPS`] steps per level of discrepancies: a junction of a sketch whose ends lie
    /// a little out of order must not cost its faces). The faces found go to `search`;
    /// `partial` is as it was on return.
    #[allow(clippy::too_many_arguments)]
    fn extend(
        &self,
        h0: HalfEdge,
        n0: DVec3,
        first: usize,
        h: HalfEdge,
        n: DVec3,
        mut turning: f64,
        partial: &mut Partial,
        search: &mut Search,
    ) {
        if search.done() {
            return;
        }
        search.budget -= 1;
        let g = self.g;
        let (p, t) = self.path(h);
        let carried = transport(&p, &t, n);
        for i in 0..t.len().saturating_sub(1) {
            turning += angle_about(t[i], t[i + 1], carried[i]);
        }
        let seg = &g.segments[h.segment];
        let (v, arrive_at_start) = if h.forward { (seg.end, false) } else { (seg.start, true) };
        if v != first && partial.visited.contains(&v) {
            return;
        }
        let Some(&(mut nv)) = carried.last() else { return };
        if let Some(est) = self.planar[v] {
            if est.dot(nv).abs() > 0.5 {
                nv = if est.dot(nv) < 0.0 { -est } else { est };
            }
        }
        // The arrival end's tangent points away from v, back along the segment.
        let Some(a) = self.ends[v].iter().find(|e| e.0 == h.segment && e.1 == arrive_at_start).map(|e| e.2) else {
            return;
        };
        // The counter-clockwise angle from the arrival end about `nv`, in (0, 2π].
        let ccw = |d: DVec3| {
            let ang = angle_about(a, d, nv);
            if ang <= 0.0 {
                ang + std::f64::consts::TAU
            } else {
                ang
            }
        };
        // Leave along the clockwise neighbour of the arrival end (the largest counter-clockwise
        // angle from it), then the next; or back along `h0` at the first node.
        let options: Vec<(f64, usize, bool, DVec3)> = if v == first {
            let d = self.leaving(h0);
            vec![(ccw(d), h0.segment, h0.forward, d)]
        } else {
            let mut o: Vec<(f64, usize, bool, DVec3)> = self.ends[v]
                .iter()
                .filter(|&&(s, at_start, d)| {
                    !(s == h.segment && at_start == arrive_at_start)
                        && search.allowed.is_none_or(|a| a[s])
                        && (d - nv * d.dot(nv)).length() >= 1e-3
                })
                .map(|&(s, at_start, d)| (ccw(d), s, at_start, d))
                .collect();
            o.sort_by(|x, y| y.0.total_cmp(&x.0));
            o.truncate(BRANCHES);
            o
        };
        partial.push(h, n, &p, v);
        for (rank, (ang, s, at_start, d)) in options.into_iter().enumerate() {
            // Interior angle on the left: counter-clockwise from the leaving to the arriving end.
            let corner = std::f64::consts::PI - (std::f64::consts::TAU - ang);
            let nn = (nv - d * nv.dot(d)).normalize_or_zero();
            if nn == DVec3::ZERO {
                continue;
            }
            if v == first {
                let holonomy = nn.angle_between(n0);
                let cycle = partial.cycle.clone();
                let inward = (0..cycle.len()).map(|k| self.corner_inward(&cycle, k, &partial.samples)).collect();
                search.found.push(Trace {
                    cycle,
                    normals: partial.normals.clone(),
                    inward,
                    turning: turning + corner,
                    holonomy,
                    discrepancies: search.used,
                });
                break;
            }
            if partial.cycle.len() >= MAX_CYCLE || partial.cycle.iter().any(|c| c.segment == s) {
                continue;
            }
            let next = HalfEdge { segment: s, forward: at_start };
            if rank > 0 {
                if search.discrepancies == 0 {
                    break;
                }
                search.discrepancies -= 1;
                search.used += 1;
            }
            self.extend(h0, n0, first, next, nn, turning + corner, partial, search);
            if rank > 0 {
                search.discrepancies += 1;
                search.used -= 1;
            }
            if search.done() {
                break;
            }
        }
        partial.pop();
    }
}
