//! A global choice of the cycles that bound the patches, and one orientation for them, for
//! networks whose normals are inferred (docs/design.md §15; after Zhuang, Zou, Carr and Ju,
//! "A general and efficient method for finding cycles in 3D curve networks", 2013).
//!
//! The rotation walk of \[CG\] §3.2 needs a normal at every node with the right sign: one
//! wrong sign (a junction whose tangent plane the inference turned over, a dense or nearly
//! planar junction of a sketch) changes every face through that node, and the run then stops
//! on folded or overlapping patches. Here every cycle is chosen against all the others:
//!
//! 1. **Candidates** (`trace`): from each segment, one face on each side, traced with a
//!    normal carried along the face itself rather than the network's (at a junction whose
//!    curves lie in one plane, the plane's normal with the carried one's sign); a trace that
//!    comes back to its first node closes there (petals touching at a flower's centre). The
//!    face leaves each node along the clockwise neighbour; where that path meets a node twice
//!    or runs too long, the faces that leave along the next neighbour at one node, then at two,
//!    are tried (a limited discrepancy search: the first simple cycle with the fewest such
//!    turns).
//! 2. **Cost**: how far the face is from a patch of a smooth surface — its total turning
//!    (2π for a flat disk, 2π − ∫K on a curved one, Gauss–Bonnet; a face traced on the wrong
//!    side of a junction turns by much less or much more), how far its normal comes back
//!    from where it started after one turn (the twist along it), a twentieth per segment, and
//!    0.15 per turn along the next neighbour instead of the clockwise one.
//! 3. **Search**: the cycles in order of cost, each kept when every segment it runs along
//!    still bounds fewer than two kept patches (one for a boundary curve), when it does not
//!    fold onto a kept patch across a shared segment (the directions from the segment into
//!    the two faces, at its end nodes, less than 60° apart: the outside face of an open sheet,
//!    the flat disk under a shallow dome — the dihedral test of Zhuang et al.), and when it can be oriented
//!    as the kept patches it shares segments with (a union–find with parities: patches that
//!    share a segment run along it in opposite directions) — greedy best-first over the
//!    candidates (Zhuang et al. rank the pairings the same way and search the best set; the
//!    greedy pass is their first step).
//!    **Holes** (3b): the open side of each segment that one kept patch bounds is traced again,
//!    with that patch's normal there (the new face oriented as its neighbour) and among the
//!    segments that can still take a patch only — the first trace of that side may have run
//!    along a segment two patches took since — and the new faces are offered in the same way,
//!    for up to three rounds.
//! 4. **One orientation**: the kept patches turned as the parities say; closed parts turned
//!    outward (positive enclosed volume), open ones to agree with most of the normals the
//!    network had.
//!
//! The result serves the normals: per segment end, the normal of the chosen patches there
//! ([`Choice::end_votes`]), which [`super::orient::follow_patches`] uses to repair the sign
//! (or, where the patches disagree with the junction's tangents, the direction) of the
//! inferred node normals. A choice that cannot be surfaced falls back to the rotation walk
//! (`pipeline::infer`).

mod trace;

use super::cycles::HalfEdge;
use super::nodes::Graph;
use crate::curves::CurveSpline;
use crate::geom::DVec3;
use trace::{Trace, Walker};

/// A chosen patch: its cycle and, per half-edge, the patch's normal at its start node (both
/// oriented as the patch is: counter-clockwise seen from the side the normals point to).
#[derive(Clone, Debug)]
pub struct Chosen {
    /// The half-edges, each segment at most once.
    pub cycle: Vec<HalfEdge>,
    /// The normal at the start node of each half-edge.
    pub normals: Vec<DVec3>,
    /// Per half-edge: the directions into the patch at its segment's start and end nodes.
    pub inward: Vec<[DVec3; 2]>,
    /// The candidate's cost (module documentation, step 2).
    pub cost: f64,
}

/// The cycles chosen for a network, oriented.
#[derive(Clone, Debug, Default)]
pub struct Choice {
    /// The chosen patches.
    pub patches: Vec<Chosen>,
    /// Per segment: how many chosen patches it bounds (0: left out, 1: a border, 2: inside).
    pub uses: Vec<u8>,
    /// Distinct candidate cycles traced.
    pub candidates: usize,
}

impl Choice {
    /// Per segment of `g`: the normal of the chosen patches at its start and at its end — the
    /// sum of the patches' normals over the *fan* the end belongs to (the ends that chosen
    /// patches join around the node, corner by corner), `None` for an end no chosen patch
    /// uses. Where one sheet passes a node all its ends have the same; where sheets touch at
    /// a node (petals at a flower's centre) each sheet has its own.
    pub fn end_votes(&self, g: &Graph) -> Vec<[Option<DVec3>; 2]> {
        // End 2s is segment s's end at its start node, 2s + 1 the one at its end node.
        let end_of = |h: HalfEdge, leaving: bool| 2 * h.segment + usize::from(h.forward != leaving);
        let mut fans = super::UnionFind::new(2 * g.segments.len());
        for p in &self.patches {
            let n = p.cycle.len();
            for k in 0..n {
                fans.union(end_of(p.cycle[(k + n - 1) % n], false), end_of(p.cycle[k], true));
            }
        }
        let mut sums: Vec<Option<DVec3>> = vec![None; 2 * g.segments.len()];
        for p in &self.patches {
            for (h, n) in p.cycle.iter().zip(&p.normals) {
                let r = fans.find(end_of(*h, true));
                sums[r] = Some(sums[r].unwrap_or(DVec3::ZERO) + *n);
            }
        }
        (0..g.segments.len()).map(|s| [sums[fans.find(2 * s)], sums[fans.find(2 * s + 1)]]).collect()
    }
}

/// A chosen cycle by its half-edges' places on the curves (the same cycle in another graph of
/// the same curves: [`crate::topology::cycles::patches_from_keys`]).
pub use crate::network::CycleKey;

impl Choice {
    /// The chosen cycles as [`CycleKey`]s on `g`.
    pub fn keys(&self, g: &Graph) -> Vec<CycleKey> {
        self.patches.iter().map(|p| crate::topology::cycles::key_of(g, &p.cycle)).collect()
    }
}

/// The canonical key of a cycle: its segments, sorted.
fn key(cycle: &[HalfEdge]) -> Vec<usize> {
    let mut k: Vec<usize> = cycle.iter().map(|h| h.segment).collect();
    k.sort_unstable();
    k
}

/// The cost of a traced face (module documentation, step 2): `|turning − 2π| / π` plus the
/// holonomy over π, plus a twentieth per segment (of two equal faces the smaller; a long
/// cycle around a whole part of a sketch comes after its cells).
fn cost(t: &Trace) -> f64 {
    (t.turning - std::f64::consts::TAU).abs() / std::f64::consts::PI
        + t.holonomy / std::f64::consts::PI
        + 0.05 * t.cycle.len() as f64
        + DISCREPANCY_COST * t.discrepancies as f64
}

/// The cost of each node where a face leaves along another segment than the clockwise
/// neighbour (`trace`).
const DISCREPANCY_COST: f64 = 0.15;

/// Chooses the cycles of `g` (module documentation); `splines[c]` is the spline of
/// `g.curves[c]`; the node normals of `g` (zero where unknown) decide the orientation of
/// open parts.
pub fn choose_cycles(g: &Graph, splines: &[CurveSpline]) -> Choice {
    let walker = Walker::new(g, splines);
    // 1. Candidates: one face on each side of every segment.
    let mut traces: Vec<Trace> = Vec::new();
    let mut keys: std::collections::HashMap<Vec<usize>, usize> = std::collections::HashMap::new();
    // Parts of boundary curves only (lone loops) are the rotation walk's: tubes and disks.
    let comp = g.node_components();
    let mut interior = vec![false; g.nodes.len()];
    g.segments.iter().filter(|s| !s.boundary).for_each(|s| interior[comp[s.start]] = true);
    for s in 0..g.segments.len() {
        if !interior[comp[g.segments[s].start]] {
            continue;
        }
        let h = HalfEdge { segment: s, forward: true };
        let Some(n) = walker.start_normal(h) else { continue };
        for sign in [1.0, -1.0] {
            if let Some(t) = walker.trace(h, n * sign) {
                let k = key(&t.cycle);
                match keys.get(&k) {
                    Some(&i) if cost(&traces[i]) <= cost(&t) => {}
                    Some(&i) => traces[i] = t,
                    None => {
                        keys.insert(k, traces.len());
                        traces.push(t);
                    }
                }
            }
        }
    }
    // 2.–3. Cheapest first, each segment in at most two patches (a boundary curve in one),
    // no fold onto a patch kept before, one orientation for all of them.
    let mut order: Vec<usize> = (0..traces.len()).collect();
    let costs: Vec<f64> = traces.iter().map(cost).collect();
    order.sort_by(|&a, &b| costs[a].total_cmp(&costs[b]).then(a.cmp(&b)));
    let mut kept = Kept::new(g);
    for i in order {
        kept.offer(g, &traces[i], costs[i]);
    }
    let mut candidates = traces.len();
    let mut seen: std::collections::HashSet<Vec<usize>> = keys.into_keys().collect();
    // 3b. The holes: faces traced again from the open side of each border segment, with the
    // normal of the patch on its other side, among the segments that can still take a patch.
    for _ in 0..HOLE_ROUNDS {
        let found = holes(g, &walker, &kept, &mut seen);
        if found.is_empty() {
            break;
        }
        candidates += found.len();
        let before = kept.patches.len();
        for (t, c) in found {
            kept.offer(g, &t, c);
        }
        if kept.patches.len() == before {
            break;
        }
    }
    let Kept { uses, mut patches, mut parity, .. } = kept;
    // 4. One orientation: each patch turned as its parity says; the parts are the parities'
    // sets.
    let mut parts: std::collections::BTreeMap<usize, Vec<usize>> = std::collections::BTreeMap::new();
    for (f, p) in patches.iter_mut().enumerate() {
        let (root, odd) = parity.find(f);
        if odd {
            *p = flipped(p);
        }
        parts.entry(root).or_default().push(f);
    }
    let mut choice = Choice { patches, uses, candidates };
    face_outward(g, &mut choice, parts.values());
    canonical_order(&mut choice.patches);
    choice
}

/// Rounds of [`holes`] at most: each traces the open sides of the border segments again with
/// the patches kept so far.
const HOLE_ROUNDS: usize = 3;

/// The patches kept so far (module documentation, step 3).
struct Kept {
    /// Per segment: how many kept patches it bounds.
    uses: Vec<u8>,
    /// Per segment: the kept patches on it and the index of the half-edge they run along it.
    on: Vec<Vec<(usize, usize)>>,
    parity: Parity,
    patches: Vec<Chosen>,
}

impl Kept {
    fn new(g: &Graph) -> Self {
        Kept {
            uses: vec![0; g.segments.len()],
            on: vec![Vec::new(); g.segments.len()],
            parity: Parity::default(),
            patches: Vec::new(),
        }
    }

    /// How many patches segment `s` of `g` can bound: two, one for a boundary curve.
    fn room(g: &Graph, s: usize) -> u8 {
        if g.segments[s].boundary {
            1
        } else {
            2
        }
    }

    /// Keeps `t` when each of its segments still has room for it, it does not fold onto a
    /// kept patch across a shared segment and it can be oriented as the kept patches it
    /// shares segments with.
    fn offer(&mut self, g: &Graph, t: &Trace, cost: f64) {
        if !t.cycle.iter().all(|h| self.uses[h.segment] < Self::room(g, h.segment)) {
            return;
        }
        // Against each kept patch on its segments: the relative orientation (`true`: one of
        // the two must be turned over, they run along the segment the same way) and the fold.
        let mut links: Vec<(usize, bool)> = Vec::new();
        let mut folds = false;
        for (k, h) in t.cycle.iter().enumerate() {
            for &(j, kj) in &self.on[h.segment] {
                let hj = self.patches[j].cycle[kj];
                let turn = hj.forward == h.forward;
                let (a, b) = (self.patches[j].inward[kj], t.inward[k]);
                folds |= 0.5 * (a[0].dot(b[0]) + a[1].dot(b[1])) > FOLD_COS;
                links.push((j, turn));
            }
        }
        if folds || !self.parity.consistent(&links) {
            return;
        }
        let f = self.parity.push();
        links.iter().for_each(|&(j, turn)| self.parity.union(f, j, turn));
        for (k, h) in t.cycle.iter().enumerate() {
            self.uses[h.segment] += 1;
            self.on[h.segment].push((f, k));
        }
        self.patches.push(Chosen {
            cycle: t.cycle.clone(),
            normals: t.normals.clone(),
            inward: t.inward.clone(),
            cost,
        });
    }
}

/// New candidates for the holes the kept patches leave (module documentation, step 3b): from
/// each segment one kept patch bounds and another could, the face on its open side — the
/// half-edge against the kept patch's, with the kept patch's normal there, so that the face
/// is oriented as its neighbour — traced along the segments that still have room, so that it
/// cannot run along a segment two patches bound already. Faces seen before (`seen`) are not
/// offered again; the new ones are returned cheapest first with their costs.
fn holes(
    g: &Graph,
    walker: &Walker,
    kept: &Kept,
    seen: &mut std::collections::HashSet<Vec<usize>>,
) -> Vec<(Trace, f64)> {
    let allowed: Vec<bool> = (0..g.segments.len()).map(|s| kept.uses[s] < Kept::room(g, s)).collect();
    let mut found: Vec<(Trace, f64)> = Vec::new();
    for (s, on) in kept.on.iter().enumerate() {
        if on.len() != 1 || !allowed[s] {
            continue;
        }
        let (j, k) = on[0];
        let p = &kept.patches[j];
        let n = p.cycle.len();
        // The kept half-edge's end node is the open side's start; its normal there is the
        // kept patch's at its next half-edge's start.
        let h = HalfEdge { segment: s, forward: !p.cycle[k].forward };
        let normal = p.normals[(k + 1) % n];
        let t = walker.leaving(h);
        let n0 = (normal - t * normal.dot(t)).normalize_or_zero();
        if n0 == DVec3::ZERO {
            continue;
        }
        for t in walker.trace_within(h, n0, Some(&allowed), HOLE_ALTERNATIVES) {
            if !seen.insert(key(&t.cycle)) {
                continue;
            }
            let c = cost(&t);
            found.push((t, c));
        }
    }
    found.sort_by(|a, b| a.1.total_cmp(&b.1));
    found
}

/// Faces traced per open side in [`holes`]: the first few the search finds.
const HOLE_ALTERNATIVES: usize = 2;

/// Two patches that share a segment fold onto each other when the directions from the segment
/// into each of them (at its two end nodes, `trace`'s `corner_inward`; averaged) are less
/// than 60° apart:
/// the outside face of an open sheet seen against the sheet, the flat disk under a shallow
/// dome. Smooth continuations (180°) and creases down to 60° (a box's 90° edges) are kept.
const FOLD_COS: f64 = 0.5;

/// Union–find over the kept patches with the parity of each patch's orientation relative to
/// its root (`true`: turned over), so that one orientation is kept for every set of patches
/// joined by shared segments.
#[derive(Default)]
struct Parity {
    parent: Vec<usize>,
    odd: Vec<bool>,
}

impl Parity {
    /// A new patch, its own root.
    fn push(&mut self) -> usize {
        self.parent.push(self.parent.len());
        self.odd.push(false);
        self.parent.len() - 1
    }

    /// The root of `i` and the parity of `i` relative to it (path halving keeps parities).
    fn find(&mut self, i: usize) -> (usize, bool) {
        let (mut r, mut odd) = (i, false);
        while self.parent[r] != r {
            odd ^= self.odd[r];
            r = self.parent[r];
        }
        // Compress: point `i`'s path at the root with the accumulated parities.
        let (mut x, mut acc) = (i, odd);
        while self.parent[x] != x {
            let (next, step) = (self.parent[x], self.odd[x]);
            self.parent[x] = r;
            self.odd[x] = acc;
            acc ^= step;
            x = next;
        }
        (r, odd)
    }

    /// Whether a new patch can be joined to the patches `links` (`(patch, turned)`: the new
    /// one's orientation relative to that patch) without a contradiction.
    fn consistent(&mut self, links: &[(usize, bool)]) -> bool {
        let mut implied: Vec<(usize, bool)> = Vec::new();
        for &(j, turn) in links {
            let (r, odd) = self.find(j);
            let want = odd ^ turn;
            match implied.iter().find(|x| x.0 == r) {
                Some(x) if x.1 != want => return false,
                Some(_) => {}
                None => implied.push((r, want)),
            }
        }
        true
    }

    /// Joins `a` to `b` with relative parity `turn`.
    fn union(&mut self, a: usize, b: usize, turn: bool) {
        let (ra, pa) = self.find(a);
        let (rb, pb) = self.find(b);
        if ra != rb {
            self.parent[ra] = rb;
            self.odd[ra] = pa ^ pb ^ turn;
        }
    }
}

/// Index of a half-edge in the rotation walk's order: `2 segment` forward, `2 segment + 1`
/// backward.
fn he_index(h: HalfEdge) -> usize {
    2 * h.segment + usize::from(!h.forward)
}

/// The order of the rotation walk's faces (\[CG\] §3.2, `cycles::faces`): each cycle starts at
/// its first half-edge in [`he_index`] order, the cycles sorted by it — so that where the
/// search and the walk choose the same patches, the meshes are the same too.
fn canonical_order(patches: &mut [Chosen]) {
    for p in patches.iter_mut() {
        let k = (0..p.cycle.len()).min_by_key(|&i| he_index(p.cycle[i])).unwrap_or(0);
        p.cycle.rotate_left(k);
        p.normals.rotate_left(k);
    }
    patches.sort_by_key(|p| p.cycle.first().map_or(usize::MAX, |&h| he_index(h)));
}

/// `p` traversed the other way round, its normals turned over.
fn flipped(p: &Chosen) -> Chosen {
    let n = p.cycle.len();
    let cycle: Vec<HalfEdge> =
        p.cycle.iter().rev().map(|h| HalfEdge { segment: h.segment, forward: !h.forward }).collect();
    // The reversed half-edge k starts where the original half-edge n−1−k ended: at the start
    // of original half-edge n−k (mod n).
    let normals = (0..n).map(|k| -p.normals[(n - k) % n]).collect();
    let inward = p.inward.iter().rev().copied().collect();
    Chosen { cycle, normals, inward, cost: p.cost }
}

/// Step 4 of the module documentation, for patches already oriented alike within each of
/// their `parts`: each closed part turned outward, each open one to the side most of the
/// network's node normals point to.
fn face_outward<'a>(g: &Graph, choice: &mut Choice, parts: impl Iterator<Item = &'a Vec<usize>>) {
    // Closed parts outward: the volume the patches enclose (fans from their centroids, about
    // the part's centroid) is positive when the cycles run counter-clockwise seen from outside.
    for members in parts {
        let closed = members.iter().all(|&i| choice.patches[i].cycle.iter().all(|h| choice.uses[h.segment] == 2));
        let loops: Vec<Vec<DVec3>> = members.iter().map(|&i| cycle_points(g, &choice.patches[i].cycle)).collect();
        let all: Vec<DVec3> = loops.iter().flatten().copied().collect();
        let o = all.iter().sum::<DVec3>() / all.len().max(1) as f64;
        let mut volume = 0.0;
        for l in &loops {
            let c = l.iter().sum::<DVec3>() / l.len().max(1) as f64;
            for k in 0..l.len() {
                volume += (c - o).dot((l[k] - o).cross(l[(k + 1) % l.len()] - o)) / 6.0;
            }
        }
        // An open part: the side most of the network's current node normals point to.
        let turn = if closed {
            volume < 0.0
        } else {
            let mut agree = 0.0;
            for &i in members {
                let p = &choice.patches[i];
                for (h, n) in p.cycle.iter().zip(&p.normals) {
                    let seg = &g.segments[h.segment];
                    agree += n.dot(g.nodes[if h.forward { seg.start } else { seg.end }].normal);
                }
            }
            agree < 0.0
        };
        if turn {
            for &i in members.iter() {
                choice.patches[i] = flipped(&choice.patches[i]);
            }
        }
    }
}

/// The samples around `cycle`, in its direction.
fn cycle_points(g: &Graph, cycle: &[HalfEdge]) -> Vec<DVec3> {
    cycle.iter().flat_map(|&h| super::cycles::half_edge_samples(g, h)).map(|x| x.0).collect()
}

#[cfg(test)]
#[path = "../tests/search.rs"]
mod tests;
