//! Normals for curves that come without them (docs/design.md §12): 3D sketches, CAD feature
//! curves, polylines.
//!
//! The normal-control pipeline needs a normal at every sample (\[CG\] §3). Where a curve has
//! none, the graph carries zero normals after [`super::find_nodes`], and this module fills
//! them in three steps:
//!
//! 1. **Nodes** ([`node_estimates`]): where two or more curves cross, the surface's tangent
//!    plane holds their tangents, so the node normal is their cross product (for more than two
//!    tangents: the sum of the pairwise cross products, signs aligned). This is exact on any
//!    smooth surface; only its sign is unknown. Where the tangents are (nearly) parallel the
//!    node has no estimate of its own.
//! 2. **Orientation** (`orient`): one sign for the whole network. A node's normal is carried
//!    along each segment to the next node by parallel transport (rotation-minimising frames,
//!    double reflection, Wang et al. 2008) and compared with that node's estimate; the signs
//!    are fixed along a maximum spanning tree of these agreements, starting from the curves
//!    whose normals were given. Nodes without an estimate take the transported normal.
//! 3. **Along the segments** (`fill_segments`): the start node's normal transported along the
//!    segment, turned about the tangent by a share of the angle it misses the end node's
//!    normal by that grows with the arc length. Loops without a crossing take the normal of
//!    their plane (a disk) or, when two loops face each other, the direction away from their
//!    centre (a tube: two parallel circles bound a cylinder). A component without any given
//!    normal is then turned outward (`turn_outward`: at the network's extreme samples the
//!    normals point away).

use super::nodes::Graph;
use crate::curves::CurveSpline;
use crate::error::{Result, Warning};
use crate::geom::DVec3;

/// Sines below this between the tangents at a node: the node has no tangent plane of its own
/// (the curves pass it in one direction).
pub const MIN_NODE_SINE: f64 = 0.05;

/// What the inference found and assumed, for the run's statistics and warnings.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct OrientReport {
    /// Curves (of the graph) whose normals were inferred.
    pub inferred_curves: usize,
    /// Nodes whose normal came from the tangents of the curves that cross there.
    pub nodes_from_tangents: usize,
    /// Nodes whose normal was carried along a segment from a neighbour (no crossing).
    pub nodes_transported: usize,
    /// Links along which the carried normal is far from the next node's own estimate (|cos|
    /// below half the estimate's confidence, about 60°–120° apart): the sign there is a guess.
    pub doubtful_links: usize,
    /// Segments along which the orientation contradicts itself (Möbius-like, or noise).
    pub contradictions: Vec<usize>,
    /// Components turned around so that their normals point outward.
    pub flipped_components: usize,
    /// What was assumed, for the user.
    pub warnings: Vec<Warning>,
}

/// The unit tangent of segment `s` of `g` at its start (`at_start`) or end, pointing away from
/// the node (as the rotation system sees it).
fn end_tangent(g: &Graph, splines: &[CurveSpline], s: usize, at_start: bool) -> DVec3 {
    let seg = &g.segments[s];
    let sp = &splines[seg.curve];
    let d = if at_start { sp.tangent(sp.knot(seg.first), true) } else { -sp.tangent(sp.knot(seg.last), false) };
    d.normalize_or_zero()
}

/// Per node of `g`: an unsigned normal estimate from the tangents of the segments that leave
/// it, and its confidence (the largest sine between two of them), or `None` when the tangents
/// are (nearly) parallel.
pub fn node_estimates(g: &Graph, splines: &[CurveSpline]) -> Vec<Option<(DVec3, f64)>> {
    let mut tangents: Vec<Vec<DVec3>> = vec![Vec::new(); g.nodes.len()];
    for (s, seg) in g.segments.iter().enumerate() {
        tangents[seg.start].push(end_tangent(g, splines, s, true));
        tangents[seg.end].push(end_tangent(g, splines, s, false));
    }
    tangents.iter().map(|t| tangent_plane_normal(t)).collect()
}

/// The normal of the plane that holds the unit directions `t` (\[CG\] §3.2: the curves at a
/// node lie in its tangent plane): for two directions their cross product, for more the
/// direction of least scatter (the smallest eigenvector of `Σ t tᵀ`, independent of their
/// order) — or, at a corner where they leave to one side and no plane holds them (a cube's
/// corner), the opposite of their sum — with the largest sine between two of them as its
/// confidence. `None` below [`MIN_NODE_SINE`].
pub fn tangent_plane_normal(t: &[DVec3]) -> Option<(DVec3, f64)> {
    let mut best = (0.0, DVec3::ZERO);
    for i in 0..t.len() {
        for j in i + 1..t.len() {
            let c = t[i].cross(t[j]);
            if c.length() > best.0 {
                best = (c.length(), c);
            }
        }
    }
    if best.0 < MIN_NODE_SINE {
        return None;
    }
    let sum: DVec3 = t.iter().sum();
    let n = if t.len() == 2 {
        best.1.normalize_or_zero()
    } else if t.len() == 3 && (0..3).all(|i| t[i].dot(t[(i + 1) % 3]) < 0.5) && sum.length() > 1.0 && !planar(t) {
        // A corner (three curves leaving along the edges of a cube, 60° or more apart, to one
        // side): no plane holds them; the normal is the direction they leave away from.
        -sum.normalize()
    } else {
        let n = crate::geom::smallest_eigenvector(crate::geom::scatter(t.iter().copied(), DVec3::ZERO));
        if n.dot(best.1) < 0.0 {
            -n
        } else {
            n
        }
    };
    (n != DVec3::ZERO).then_some((n, best.0))
}

/// The unit directions `t` lie near one plane: every one within about 25° of the plane of least
/// scatter.
fn planar(t: &[DVec3]) -> bool {
    let n = crate::geom::smallest_eigenvector(crate::geom::scatter(t.iter().copied(), DVec3::ZERO));
    t.iter().all(|d| d.dot(n).abs() < 0.42)
}

/// Unit tangents of split curve `c` of `g` at its samples (from its spline).
fn sample_tangents(g: &Graph, splines: &[CurveSpline], c: usize) -> Vec<DVec3> {
    let sp = &splines[c];
    (0..g.curves[c].points.len()).map(|i| sp.tangent(sp.knot(i), true).normalize_or_zero()).collect()
}

/// The sample indices of segment `s` from its first to its last sample (wrapping on closed
/// curves: the last index of a closed curve's final segment is sample 0 again).
fn segment_indices(g: &Graph, s: usize) -> Vec<usize> {
    let seg = &g.segments[s];
    let m = g.curves[seg.curve].points.len();
    (seg.first..=seg.last).map(|i| i % m).collect()
}

/// Parallel transport of the vector `r` (⊥ `t[0]`) along the points `p` with unit tangents `t`
/// by double reflection (Wang, Jüttler, Zheng, Liu 2008, "Computation of rotation minimizing
/// frames", Algorithm 1); returns the carried vector at every point.
pub fn transport(p: &[DVec3], t: &[DVec3], r: DVec3) -> Vec<DVec3> {
    let mut out = Vec::with_capacity(p.len());
    let mut r = (r - t[0] * r.dot(t[0])).normalize_or_zero();
    out.push(r);
    for i in 0..p.len().saturating_sub(1) {
        let v1 = p[i + 1] - p[i];
        let c1 = v1.dot(v1);
        let (rl, tl) =
            if c1 > 0.0 { (r - v1 * (2.0 / c1 * v1.dot(r)), t[i] - v1 * (2.0 / c1 * v1.dot(t[i]))) } else { (r, t[i]) };
        let v2 = t[i + 1] - tl;
        let c2 = v2.dot(v2);
        let next = if c2 > 1e-30 { rl - v2 * (2.0 / c2 * v2.dot(rl)) } else { rl };
        // Keep it across the tangent and of unit length (rounding drifts over long curves).
        let next = (next - t[i + 1] * next.dot(t[i + 1])).normalize_or_zero();
        r = if next == DVec3::ZERO { r } else { next };
        out.push(r);
    }
    out
}

/// Signed angle from `a` to `b` about the unit axis `t` (both taken across `t`).
fn angle_about(a: DVec3, b: DVec3, t: DVec3) -> f64 {
    let (a, b) = (a - t * a.dot(t), b - t * b.dot(t));
    a.cross(b).dot(t).atan2(a.dot(b))
}

/// `v` turned by `angle` about the unit axis `t` (Rodrigues).
fn rotate_about(v: DVec3, t: DVec3, angle: f64) -> DVec3 {
    let (s, c) = angle.sin_cos();
    v * c + t.cross(v) * s + t * t.dot(v) * (1.0 - c)
}

/// Arc fractions (0 at the first point, 1 at the last) of the polyline `p`.
fn arc_fractions(p: &[DVec3]) -> Vec<f64> {
    let mut acc = vec![0.0; p.len()];
    for i in 1..p.len() {
        acc[i] = acc[i - 1] + p[i].distance(p[i - 1]);
    }
    let total = acc.last().copied().unwrap_or(0.0);
    if total > 0.0 {
        acc.iter_mut().for_each(|a| *a /= total);
    }
    acc
}

/// Points and tangents of segment `s` in sample order.
fn segment_path(g: &Graph, tangents: &[Vec<DVec3>], s: usize) -> (Vec<DVec3>, Vec<DVec3>) {
    let c = g.segments[s].curve;
    let idx = segment_indices(g, s);
    (idx.iter().map(|&i| g.curves[c].points[i]).collect(), idx.iter().map(|&i| tangents[c][i]).collect())
}

/// Infers the missing normals of `g` (zero vectors: the curves `known[c] == false`, and the
/// nodes only such curves pass) in place: node estimates, one orientation, the normals along
/// the segments (module documentation, steps 1–3). `splines` are fitted to the graph's curves
/// (their positions; the normals are not used).
///
/// A network whose orientation contradicts itself around a cycle (a Möbius-like network) is
/// reported in [`OrientReport::contradictions`] and a warning naming the segments.
pub fn infer_normals(g: &mut Graph, splines: &[CurveSpline], known: &[bool]) -> Result<OrientReport> {
    let mut report = OrientReport { inferred_curves: known.iter().filter(|k| !**k).count(), ..Default::default() };
    let tangents: Vec<Vec<DVec3>> = (0..g.curves.len()).map(|c| sample_tangents(g, splines, c)).collect();
    let estimates = node_estimates(g, splines);
    // Nodes with a given normal (some known curve passes them) are fixed.
    let fixed: Vec<bool> = g.nodes.iter().map(|n| n.normal != DVec3::ZERO).collect();
    orient(g, &tangents, &estimates, &fixed, &mut report)?;
    fill_segments(g, &tangents, known);
    turn_outward(g, known, &fixed, &mut report);
    for &s in report.contradictions.iter().take(5) {
        report.warnings.push(
            Warning::new(format!(
                "the curves cannot be given one orientation everywhere: the normal carried along {} comes back \
                 reversed at its end (a Möbius-like network, or a crossing whose tangent plane is unclear); \
                 the surface may fold there — give the normals of some curves",
                g.describe_segment(s)
            ))
            .curve(g.segments[s].curve),
        );
    }
    if report.doubtful_links > 0 {
        report.warnings.push(Warning::new(format!(
            "the orientation of {} link(s) between crossings is a guess (the normal carried along the curve \
             is far from the next crossing's tangent plane normal): check the result there, or give the \
             normals of some curves",
            report.doubtful_links
        )));
    }
    Ok(report)
}

/// Repairs the inferred normals of `g` from the patches chosen for it ([`super::search`]):
/// `ends[s]` holds the chosen patches' normal at the start and at the end of segment `s`
/// ([`super::search::Choice::end_votes`]); a node's vote is their sum over its ends. A node
/// normal within 60° of its vote (either sign) keeps its direction and takes the vote's sign;
/// one further from it (the junction's tangents span another plane than its patches: a dense
/// or nearly planar junction) takes the vote's direction, unless the junction's tangents give
/// a plane of their own. Nodes that a `known` curve passes keep their given normal; nodes no
/// patch passes take the sign carried to them from their neighbours. The normals along the
/// segments of inferred curves are then carried again between the nodes (step 3). Returns the
/// nodes changed.
pub fn follow_patches(g: &mut Graph, splines: &[CurveSpline], known: &[bool], ends: &[[Option<DVec3>; 2]]) -> usize {
    let mut fixed = vec![false; g.nodes.len()];
    for (c, curve) in g.curves.iter().enumerate() {
        if known[c] {
            curve.nodes.iter().for_each(|&(_, v)| fixed[v] = true);
        }
    }
    let mut votes: Vec<Option<DVec3>> = vec![None; g.nodes.len()];
    for (seg, e) in g.segments.iter().zip(ends) {
        for (v, vote) in [(seg.start, e[0]), (seg.end, e[1])] {
            if let Some(x) = vote {
                votes[v] = Some(votes[v].unwrap_or(DVec3::ZERO) + x.normalize_or_zero());
            }
        }
    }
    let estimates = node_estimates(g, splines);
    let mut changed = 0;
    for v in 0..g.nodes.len() {
        let Some(vote) = votes[v].map(|x| x.normalize_or_zero()) else { continue };
        if fixed[v] || vote == DVec3::ZERO {
            continue;
        }
        let cur = g.nodes[v].normal;
        let new = if cur.dot(vote).abs() >= 0.5 || estimates[v].is_some() {
            if cur.dot(vote) < 0.0 {
                -cur
            } else {
                cur
            }
        } else {
            vote
        };
        if new != cur {
            g.nodes[v].normal = new;
            changed += 1;
        }
    }
    if changed > 0 {
        let tangents: Vec<Vec<DVec3>> = (0..g.curves.len()).map(|c| sample_tangents(g, splines, c)).collect();
        // Nodes no chosen patch passes (ends of dangling strokes, strokes left out) take the
        // sign of the normal carried to them from a node that has a vote, breadth first, so
        // that no segment turns its normal over between its two ends.
        let mut settled: Vec<bool> = (0..g.nodes.len()).map(|v| fixed[v] || votes[v].is_some()).collect();
        let mut queue: std::collections::VecDeque<usize> = (0..g.nodes.len()).filter(|&v| settled[v]).collect();
        let mut at: Vec<Vec<usize>> = vec![Vec::new(); g.nodes.len()];
        for (s, seg) in g.segments.iter().enumerate() {
            at[seg.start].push(s);
            at[seg.end].push(s);
        }
        while let Some(v) = queue.pop_front() {
            for &s in &at[v] {
                let seg = &g.segments[s];
                let w = if seg.start == v { seg.end } else { seg.start };
                if settled[w] {
                    continue;
                }
                settled[w] = true;
                if carry(g, &tangents, s, v).dot(g.nodes[w].normal) < 0.0 {
                    g.nodes[w].normal = -g.nodes[w].normal;
                    changed += 1;
                }
                queue.push_back(w);
            }
        }
        fill_segments(g, &tangents, known);
    }
    changed
}

/// One orientation for the nodes of `g` (step 2): sets every node normal that is not `fixed`
/// from `estimates` with a consistent sign, or by transport where it has no estimate.
fn orient(
    g: &mut Graph,
    tangents: &[Vec<DVec3>],
    estimates: &[Option<(DVec3, f64)>],
    fixed: &[bool],
    report: &mut OrientReport,
) -> Result<()> {
    let n = g.nodes.len();
    let mut adjacent: Vec<Vec<usize>> = vec![Vec::new(); n];
    for (s, seg) in g.segments.iter().enumerate() {
        adjacent[seg.start].push(s);
        adjacent[seg.end].push(s);
    }
    let mut done = fixed.to_vec();
    let comps = g.node_components();
    let mut seeded = vec![false; n];
    for v in 0..n {
        if fixed[v] {
            seeded[comps[v]] = true;
        }
    }
    // Components without a given normal start at their most confident node; one without any
    // estimate (loops that cross nothing, single strokes) at a guess from its shape.
    let curves_of = curves_by_component(g, &comps);
    let tubes = tube_loops(g, &curves_of, estimates);
    for (root, members) in members_by_component(&comps) {
        if seeded[root] {
            continue;
        }
        let best =
            members.iter().filter_map(|&v| estimates[v].map(|(e, c)| (v, e, c))).max_by(|a, b| a.2.total_cmp(&b.2));
        let (v, normal) = match best {
            Some((v, e, _)) => (v, e),
            None => {
                let curves = curves_of.get(&root).map_or(&[][..], |c| &c[..]);
                (root, shape_guess(g, tangents, &members, curves, &tubes, &adjacent))
            }
        };
        g.nodes[v].normal = normal;
        done[v] = true;
    }
    // Prim's algorithm on the agreement |cos| between a carried normal and the next node's
    // estimate: the most certain links decide first.
    let mut heap = std::collections::BinaryHeap::new();
    let push_links = |v: usize, g: &Graph, heap: &mut std::collections::BinaryHeap<(Key, usize, usize)>| {
        for &s in &adjacent[v] {
            let seg = &g.segments[s];
            let w = if seg.start == v { seg.end } else { seg.start };
            let carried = carry(g, tangents, s, v);
            let score = estimates[w].map_or(0.0, |(e, c)| carried.dot(e).abs() * c);
            heap.push((Key(score), s, v));
        }
    };
    for v in 0..n {
        if done[v] {
            push_links(v, g, &mut heap);
        }
    }
    while let Some((Key(score), s, from)) = heap.pop() {
        let seg = &g.segments[s];
        let to = if seg.start == from { seg.end } else { seg.start };
        if done[to] {
            continue;
        }
        let carried = carry(g, tangents, s, from);
        g.nodes[to].normal = match estimates[to] {
            Some((e, _)) => {
                report.nodes_from_tangents += 1;
                if score < 0.5 * estimates[to].map_or(0.0, |x| x.1) {
                    report.doubtful_links += 1;
                }
                if e.dot(carried) < 0.0 {
                    -e
                } else {
                    e
                }
            }
            None => {
                report.nodes_transported += 1;
                carried
            }
        };
        done[to] = true;
        push_links(to, g, &mut heap);
    }
    report.contradictions = contradictions(g, tangents, fixed);
    Ok(())
}

/// The nodes of each component (by its root, the component's smallest node), in one pass.
fn members_by_component(comps: &[usize]) -> std::collections::BTreeMap<usize, Vec<usize>> {
    let mut out: std::collections::BTreeMap<usize, Vec<usize>> = std::collections::BTreeMap::new();
    for (v, &root) in comps.iter().enumerate() {
        out.entry(root).or_default().push(v);
    }
    out
}

/// The curves of each component (by its root): those with a node in it, in one pass.
fn curves_by_component(g: &Graph, comps: &[usize]) -> std::collections::BTreeMap<usize, Vec<usize>> {
    let mut out: std::collections::BTreeMap<usize, Vec<usize>> = std::collections::BTreeMap::new();
    for (c, sc) in g.curves.iter().enumerate() {
        let mut roots: Vec<usize> = sc.nodes.iter().map(|&(_, v)| comps[v]).collect();
        roots.sort_unstable();
        roots.dedup();
        for r in roots {
            out.entry(r).or_default().push(c);
        }
    }
    out
}

/// A total order on confidences for the priority queue.
#[derive(Clone, Copy, PartialEq)]
struct Key(f64);
impl Eq for Key {}
impl PartialOrd for Key {
    fn partial_cmp(&self, o: &Self) -> Option<std::cmp::Ordering> {
        Some(self.cmp(o))
    }
}
impl Ord for Key {
    fn cmp(&self, o: &Self) -> std::cmp::Ordering {
        self.0.total_cmp(&o.0)
    }
}

/// The normal of node `from` carried along segment `s` to its other end.
fn carry(g: &Graph, tangents: &[Vec<DVec3>], s: usize, from: usize) -> DVec3 {
    let (mut p, mut t) = segment_path(g, tangents, s);
    if g.segments[s].start != from {
        p.reverse();
        t.reverse();
    }
    transport(&p, &t, g.nodes[from].normal).last().copied().unwrap_or(DVec3::ZERO)
}

/// The segments whose carried normal comes back reversed (beyond 155°) at their other end:
/// the orientation contradicts itself around a cycle through them (a Möbius-like network, or
/// tangent planes that noise turned over).
fn contradictions(g: &Graph, tangents: &[Vec<DVec3>], fixed: &[bool]) -> Vec<usize> {
    (0..g.segments.len())
        .filter(|&s| {
            let seg = &g.segments[s];
            seg.start != seg.end
                && !(fixed[seg.start] && fixed[seg.end])
                && carry(g, tangents, s, seg.start).dot(g.nodes[seg.end].normal) < -0.9
        })
        .collect()
}

/// Turns each component that has no given normal so that its normals point outward: in each
/// of 26 directions `u` (the cube's faces, edges and corners) the sample farthest along `u` lies
/// on the component's hull, where an outward normal points along `u`; the votes `n · u` decide.
/// (On a closed surface the normal at its farthest point from any interior point points away
/// from it; the network's extreme samples stand for the surface's.) When the votes nearly
/// cancel (|Σ| < 1: an open sheet), the normals face the positive side of the coordinate axis
/// their sum leans along most (a saddle over the xy-plane faces +z).
fn turn_outward(g: &mut Graph, known: &[bool], fixed: &[bool], report: &mut OrientReport) {
    let comps = g.node_components();
    let mut directions = Vec::new();
    for x in -1..=1 {
        for y in -1..=1 {
            for z in -1..=1 {
                if (x, y, z) != (0, 0, 0) {
                    directions.push(DVec3::new(x as f64, y as f64, z as f64).normalize());
                }
            }
        }
    }
    let mut curves_of = curves_by_component(g, &comps);
    for (root, members) in members_by_component(&comps) {
        if members.iter().any(|&v| fixed[v]) {
            continue;
        }
        let curves = curves_of.remove(&root).unwrap_or_default();
        let mut vote = 0.0;
        for u in &directions {
            let best = curves
                .iter()
                .flat_map(|&c| g.curves[c].points.iter().zip(&g.curves[c].normals))
                .max_by(|a, b| a.0.dot(*u).total_cmp(&b.0.dot(*u)));
            if let Some((_, normal)) = best {
                vote += normal.dot(*u);
            }
        }
        // An open sheet (a saddle, a shield) has no outside: the votes nearly cancel. It then
        // faces the positive side of the axis its normals lean along most.
        if vote.abs() < 1.0 {
            let sum: DVec3 = curves.iter().flat_map(|&c| g.curves[c].normals.iter().copied()).sum();
            let axis = sum.abs().max_position();
            vote = sum[axis];
        }
        if vote < 0.0 {
            for &v in &members {
                g.nodes[v].normal = -g.nodes[v].normal;
            }
            for &c in &curves {
                if !known[c] {
                    g.curves[c].normals.iter_mut().for_each(|m| *m = -*m);
                }
            }
            report.flipped_components += 1;
        }
    }
}

/// A normal for a component (its nodes `members`, its curves `curves`) whose nodes have no tangent plane (loops that cross nothing,
/// curves that only touch end to end): for the loop of a tube (another loop of the network
/// faces it) the direction away from its centre, else the normal of the plane its points
/// span (least squares), else any direction across the curve.
fn shape_guess(
    g: &Graph,
    tangents: &[Vec<DVec3>],
    members: &[usize],
    curves: &[usize],
    tubes: &std::collections::HashSet<usize>,
    adjacent: &[Vec<usize>],
) -> DVec3 {
    let v = members[0];
    let Some(&s) = adjacent[v].first() else { return DVec3::Z };
    let c = g.segments[s].curve;
    let pts = &g.curves[c].points;
    let t = tangents[c][g.segments[s].first % pts.len()];
    // The points of the whole component (`curves`): a loop may be made of several open curves.
    let all: Vec<DVec3> = curves.iter().flat_map(|&k| g.curves[k].points.iter().copied()).collect();
    let centre = all.iter().sum::<DVec3>() / all.len().max(1) as f64;
    let across = |d: DVec3| (d - t * d.dot(t)).normalize_or_zero();
    let looped = g.curves[c].closed || curves.iter().all(|&k| !g.curves[k].closed);
    if looped && all.len() >= 3 {
        let plane = crate::geom::smallest_eigenvector(crate::geom::scatter(all.iter().copied(), centre));
        if tubes.contains(&c) {
            let out = across(g.nodes[v].position - centre);
            if out != DVec3::ZERO {
                return out;
            }
        }
        let n = across(plane);
        if n != DVec3::ZERO {
            return n;
        }
    }
    let n = across(crate::geom::plane_frame(t).0);
    if n == DVec3::ZERO {
        DVec3::Z
    } else {
        n
    }
}

/// The loops that cross nothing (a component of one closed curve without a tangent plane at
/// its node) that pair into tubes, as the cycles will pair them (`cycles::lone`): both planes
/// within 45° of perpendicular to the line between their centres, nearest pairs first, each
/// loop in one pair at most. Two parallel circles are a cylinder's borders; a loop left alone
/// bounds a disk.
fn tube_loops(
    g: &Graph,
    curves_of: &std::collections::BTreeMap<usize, Vec<usize>>,
    estimates: &[Option<(DVec3, f64)>],
) -> std::collections::HashSet<usize> {
    let loops: Vec<(usize, DVec3, DVec3)> = curves_of
        .values()
        .filter(|cs| cs.len() == 1)
        .map(|cs| cs[0])
        .filter(|&c| {
            let sc = &g.curves[c];
            sc.closed && sc.nodes.len() == 1 && estimates[sc.nodes[0].1].is_none()
        })
        .map(|c| {
            let p = &g.curves[c].points;
            (c, p.iter().sum::<DVec3>() / p.len() as f64, crate::geom::polygon_vector_area(p).normalize_or_zero())
        })
        .collect();
    let cos45 = std::f64::consts::FRAC_1_SQRT_2;
    let mut pairs = Vec::new();
    for i in 0..loops.len() {
        for j in i + 1..loops.len() {
            let d = loops[j].1 - loops[i].1;
            let dh = d.normalize_or_zero();
            if dh != DVec3::ZERO && loops[i].2.dot(dh).abs() >= cos45 && loops[j].2.dot(dh).abs() >= cos45 {
                pairs.push((d.length(), i, j));
            }
        }
    }
    pairs.sort_by(|a, b| a.0.total_cmp(&b.0));
    let mut used = vec![false; loops.len()];
    let mut out = std::collections::HashSet::new();
    for (_, i, j) in pairs {
        if !used[i] && !used[j] {
            used[i] = true;
            used[j] = true;
            out.insert(loops[i].0);
            out.insert(loops[j].0);
        }
    }
    out
}

/// Step 3: the sample normals of the curves that are not `known`, segment by segment — the
/// start node's normal carried along, turned about the tangent by the share (growing with the
/// arc length) of the angle by which it misses the end node's normal.
fn fill_segments(g: &mut Graph, tangents: &[Vec<DVec3>], known: &[bool]) {
    for s in 0..g.segments.len() {
        let seg = g.segments[s].clone();
        if known[seg.curve] {
            continue;
        }
        let (p, t) = segment_path(g, tangents, s);
        let carried = transport(&p, &t, g.nodes[seg.start].normal);
        let end = g.nodes[seg.end].normal;
        let miss = angle_about(*carried.last().unwrap_or(&end), end, *t.last().unwrap_or(&DVec3::Z));
        let frac = arc_fractions(&p);
        let m = g.curves[seg.curve].points.len();
        for (k, i) in (seg.first..=seg.last).enumerate() {
            let n = rotate_about(carried[k], t[k], miss * frac[k]).normalize_or_zero();
            g.curves[seg.curve].normals[i % m] = n;
        }
        let (first, last) = (seg.first % m, seg.last % m);
        g.curves[seg.curve].normals[first] = g.nodes[seg.start].normal;
        g.curves[seg.curve].normals[last] = end;
    }
}

#[cfg(test)]
#[path = "tests/orient.rs"]
mod tests;
