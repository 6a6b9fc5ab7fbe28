//! Stage 1b and 4b, the creases (docs/design.md §13): the mesh's sharp edges found
//! ([`sharp_edges`]: the dihedral-angle features), chained ([`chains`]), the chains that cannot
//! become curves of a network left smooth ([`kept_creases`]: too short, or running within the
//! snapping distance of another one), the mesh cut open along the rest ([`cut_creases`]) so
//! that each side has its own vertex normals and the sections end on the cut; after the
//! sections, the chains as crease curves with both sides' normals ([`trace_creases`]).

use super::mesh::{edge_key, Mesh};
use super::{EndsOnBoundary, Raw, Traced};
use crate::geom::DVec3;
use std::collections::{HashMap, HashSet};

/// Sharp edges that turn by more than this many degrees at a vertex end their crease curves
/// there (the curves meet at a node): a spline through a corner would round it.
pub const CREASE_CORNER_DEG: f64 = 40.0;

/// Crease chains shorter than this many sample spacings are left smooth: too short to carry a
/// curve of the network (a few sharp edges of scanning noise, a notch between two creases).
pub const MIN_CREASE_SPACINGS: f64 = 3.0;

/// What [`super::mesh::Mesh::repaired`] needs to find the creases and cut the mesh along them.
#[derive(Clone, Copy, Debug)]
pub(super) struct CreaseCut<'a> {
    /// The dihedral angle (radians) above which an edge is sharp ([`sharp_edges`]).
    pub(super) angle: f64,
    /// Chains shorter than this stay smooth ([`kept_creases`]).
    pub(super) min_len: f64,
    /// Near misses between chains closer than this to a common vertex are allowed
    /// ([`kept_creases`]).
    pub(super) gap: f64,
    /// The samples of crease curves `surface`'s checks refused in an earlier round
    /// ([`super::sample_mesh`]): a chain that runs along them stays smooth this time.
    pub(super) refused: &'a [DVec3],
    /// How close a chain's vertex must come to those samples to count as on them: one sample
    /// spacing (the crease curves were resampled along the chains).
    pub(super) refused_within: f64,
}

/// Sharp edges ([`edge_key`]) by their vertices.
type Sharp = HashSet<(u32, u32)>;

/// A chain of sharp edges: its vertices in order, and whether it is a closed loop (the last
/// vertex then joins the first).
type Chain = (Vec<u32>, bool);

/// The mesh's sharp edges ([`crate::operators::sharp_edges`]: interior edges between two
/// faces whose normals are more than `angle` (radians) apart). Edges that touch the mesh's own boundary are left smooth (the
/// boundary loops stay apart from the creases, which end one edge short of the boundary).
pub(super) fn sharp_edges(positions: &[DVec3], faces: &[[u32; 3]], angle: f64) -> Sharp {
    let (sharp, boundary) = crate::operators::sharp_edges(positions, faces, angle);
    let mut on_boundary = vec![false; positions.len()];
    for (a, b) in boundary {
        on_boundary[a as usize] = true;
        on_boundary[b as usize] = true;
    }
    sharp.into_iter().filter(|&(a, b)| !on_boundary[a as usize] && !on_boundary[b as usize]).collect()
}

/// The sharp edges chained between their junctions (vertices where other than two sharp
/// edges meet, or where the chain turns by more than [`CREASE_CORNER_DEG`]), and the closed
/// loops left; in a deterministic order. `pos` gives a vertex's position.
pub(super) fn chains(sharp: &Sharp, pos: impl Fn(u32) -> DVec3) -> Vec<Chain> {
    let mut next: HashMap<u32, Vec<u32>> = HashMap::new();
    for &(a, b) in sharp {
        next.entry(a).or_default().push(b);
        next.entry(b).or_default().push(a);
    }
    for list in next.values_mut() {
        list.sort_unstable();
    }
    let turn = |a: u32, v: u32, b: u32| (pos(v) - pos(a)).angle_between(pos(b) - pos(v)).to_degrees();
    let junction = |v: u32| {
        let list = &next[&v];
        list.len() != 2 || turn(list[0], v, list[1]) > CREASE_CORNER_DEG
    };
    let mut used: HashSet<(u32, u32)> = HashSet::new();
    let mut out = Vec::new();
    let mut starts: Vec<u32> = next.keys().copied().collect();
    starts.sort_unstable();
    // Open chains from the junctions, then closed loops from any vertex left.
    for pass in 0..2 {
        for &s in &starts {
            if pass == 0 && !junction(s) {
                continue;
            }
            for &first in &next[&s] {
                if used.contains(&edge_key(s, first)) {
                    continue;
                }
                let mut chain = vec![s];
                let (mut prev, mut v) = (s, first);
                used.insert(edge_key(s, v));
                let closed = loop {
                    chain.push(v);
                    if v == s {
                        chain.pop();
                        break true;
                    }
                    if junction(v) {
                        break false;
                    }
                    let Some(&w) = next[&v].iter().find(|&&w| w != prev && !used.contains(&edge_key(v, w))) else {
                        break false;
                    };
                    used.insert(edge_key(v, w));
                    prev = v;
                    v = w;
                };
                out.push((chain, closed));
            }
        }
    }
    out
}

/// The sharp edges of `sharp` that make creases of the network, and the number of chains left
/// smooth: repeatedly (the junctions change as chains go) the chains shorter than `min_len`
/// go, then of two chains that come within `near` of each other more than `gap` away from
/// their common vertices (a near miss the network would read as overlapping curves), the
/// shorter one.
pub(super) fn kept_creases(positions: &[DVec3], mut sharp: Sharp, cut: &CreaseCut, near: f64) -> (Sharp, usize) {
    let (min_len, gap) = (cut.min_len, cut.gap);
    let pos = |v: u32| positions[v as usize];
    let refused = Refused::new(cut.refused, cut.refused_within);
    let length = |(c, closed): &Chain| {
        let m = c.len();
        let edges = if *closed { m } else { m - 1 };
        (0..edges).map(|k| pos(c[k]).distance(pos(c[(k + 1) % m]))).sum::<f64>()
    };
    let mut dropped = 0;
    // Each round drops at least one chain (or returns), so the loop ends.
    loop {
        let all = chains(&sharp, pos);
        let lengths: Vec<f64> = all.iter().map(length).collect();
        // A single sharp edge whose ends meet no other sharp edge has no vertex the cut opens
        // (a fan splits only where two sharp edges part it): it would be a crease curve on a
        // mesh that is smooth across it, which sections cross without meeting (issue 29: a
        // sampled human figure's "crease #77 runs within the snapping tolerance of curve 6").
        let mut degree: HashMap<u32, usize> = HashMap::new();
        for &(a, b) in &sharp {
            *degree.entry(a).or_default() += 1;
            *degree.entry(b).or_default() += 1;
        }
        let unopened = |(c, closed): &Chain| !*closed && c.len() < 3 && c.iter().all(|v| degree.get(v) == Some(&1));
        let mut drop: Vec<usize> = (0..all.len())
            .filter(|&i| lengths[i] < min_len || unopened(&all[i]) || refused.covers(&all[i].0, positions))
            .collect();
        if drop.is_empty() {
            drop = near_misses(&all, &lengths, positions, near, gap);
        }
        if drop.is_empty() {
            return (sharp, dropped);
        }
        for i in drop {
            let (c, closed) = &all[i];
            let m = c.len();
            for k in 0..if *closed { m } else { m - 1 } {
                sharp.remove(&edge_key(c[k], c[(k + 1) % m]));
            }
            dropped += 1;
        }
    }
}

/// The samples of refused crease curves ([`CreaseCut::refused`]) in a grid of cell `within`.
struct Refused {
    /// Per cell: the samples in it.
    grid: HashMap<crate::geom::GridCell, Vec<DVec3>>,
    /// The distance within which a vertex is on them.
    within: f64,
}

impl Refused {
    fn new(points: &[DVec3], within: f64) -> Refused {
        let within = within.max(f64::MIN_POSITIVE);
        let mut grid: HashMap<crate::geom::GridCell, Vec<DVec3>> = HashMap::new();
        for &p in points {
            grid.entry(crate::geom::grid_cell(p, within)).or_default().push(p);
        }
        Refused { grid, within }
    }

    /// Whether `p` lies within the distance of a refused sample.
    fn near(&self, p: DVec3) -> bool {
        let (x, y, z) = crate::geom::grid_cell(p, self.within);
        (-1..=1).any(|dx| {
            (-1..=1).any(|dy| {
                (-1..=1).any(|dz| {
                    self.grid
                        .get(&(x + dx, y + dy, z + dz))
                        .is_some_and(|l| l.iter().any(|q| q.distance(p) <= self.within))
                })
            })
        })
    }

    /// Whether at least half the vertices of `chain` lie on refused samples.
    fn covers(&self, chain: &[u32], positions: &[DVec3]) -> bool {
        !self.grid.is_empty() && 2 * chain.iter().filter(|&&v| self.near(positions[v as usize])).count() >= chain.len()
    }
}

/// How many of `points` (samples of crease curves refused in this round) lie farther than
/// `within` from every one of `old` (those refused before): 0 when the round refused nothing
/// new.
pub(super) fn new_points(old: &[DVec3], points: &[DVec3], within: f64) -> usize {
    let old = Refused::new(old, within);
    points.iter().filter(|&&p| !old.near(p)).count()
}

/// Of each pair of chains of `all` that come within `near` of each other more than `gap` away
/// from their common vertices, the shorter one (unless the other one is already in). A grid
/// of cell `near` (widened to half the longest edge) over the vertices finds the close pairs;
/// a vertex's distance to the other chain is measured to its edges at the vertices found.
fn near_misses(all: &[Chain], lengths: &[f64], positions: &[DVec3], near: f64, gap: f64) -> Vec<usize> {
    let pos = |v: u32| positions[v as usize];
    let mut longest: f64 = 0.0;
    for (c, closed) in all {
        let m = c.len();
        for k in 0..if *closed { m } else { m - 1 } {
            longest = longest.max(pos(c[k]).distance(pos(c[(k + 1) % m])));
        }
    }
    let cell = near.max(0.5 * longest).max(f64::MIN_POSITIVE);
    let key = |p: DVec3| [(p.x / cell).floor() as i64, (p.y / cell).floor() as i64, (p.z / cell).floor() as i64];
    // Per grid cell: (chain, index of the vertex in it).
    let mut grid: HashMap<[i64; 3], Vec<(usize, usize)>> = HashMap::new();
    for (ci, (c, _)) in all.iter().enumerate() {
        for (k, &v) in c.iter().enumerate() {
            grid.entry(key(pos(v))).or_default().push((ci, k));
        }
    }
    // Chains meet only at their ends (junctions; loops have none).
    let ends = |(c, closed): &Chain| if *closed { Vec::new() } else { vec![c[0], c[c.len() - 1]] };
    let r = ((near + longest) / cell).ceil() as i64;
    let mut gone = vec![false; all.len()];
    for (ci, chain) in all.iter().enumerate() {
        if gone[ci] {
            continue;
        }
        let mine = ends(chain);
        'vertices: for &v in &chain.0 {
            let p = pos(v);
            let [x, y, z] = key(p);
            for dx in -r..=r {
                for dy in -r..=r {
                    for dz in -r..=r {
                        let Some(list) = grid.get(&[x + dx, y + dy, z + dz]) else { continue };
                        for &(dj, k) in list {
                            let other = &all[dj];
                            if dj == ci || gone[dj] || distance_to_edges(p, other, k, positions) > near {
                                continue;
                            }
                            let theirs = ends(other);
                            if mine.iter().any(|w| theirs.contains(w) && pos(*w).distance(p) <= gap) {
                                continue;
                            }
                            gone[if lengths[ci] <= lengths[dj] { ci } else { dj }] = true;
                            break 'vertices;
                        }
                    }
                }
            }
        }
    }
    (0..all.len()).filter(|&i| gone[i]).collect()
}

/// The distance from `p` to the edges of a chain at its vertex `k`.
fn distance_to_edges(p: DVec3, (c, closed): &Chain, k: usize, positions: &[DVec3]) -> f64 {
    let closed = *closed;
    let m = c.len();
    let pos = |i: usize| positions[c[i] as usize];
    let mut best = p.distance(pos(k));
    let mut neighbours = Vec::with_capacity(2);
    if k > 0 || closed {
        neighbours.push((k + m - 1) % m);
    }
    if k + 1 < m || closed {
        neighbours.push((k + 1) % m);
    }
    for j in neighbours {
        let (a, b) = (pos(k), pos(j));
        let d = b - a;
        let t = ((p - a).dot(d) / d.length_squared().max(f64::MIN_POSITIVE)).clamp(0.0, 1.0);
        best = best.min(p.distance(a + t * d));
    }
    best
}

/// Cuts the mesh open along the sharp edges `sharp` ([`sharp_edges`], [`kept_creases`]): at
/// every vertex the faces around it fall into sectors separated by sharp edges
/// ([`crate::operators::sectors`]); each sector after the first gets a copy of the vertex
/// (appended). Returns per vertex the vertex it is a copy of (itself for the originals) and
/// the sharp edges.
pub(crate) fn cut_creases(positions: &mut Vec<DVec3>, faces: &mut [[u32; 3]], sharp: Sharp) -> (Vec<u32>, Sharp) {
    if sharp.is_empty() {
        return ((0..positions.len() as u32).collect(), sharp);
    }
    let (corners, original) = crate::operators::sectors(positions.len(), faces, |a, b| sharp.contains(&edge_key(a, b)));
    faces.copy_from_slice(&corners);
    for &v in &original[positions.len()..] {
        positions.push(positions[v as usize]);
    }
    (original, sharp)
}

/// The creases of the mesh ([`cut_creases`]) as crease curves: its sharp edges' [`chains`]. Per sample the
/// normals of both sides (`samples` the left ones, on the left walking along the chain,
/// `right` the others); the section ends on its edges (from either side) inserted as nodes in
/// order along each edge, each counted once in `crossings`.
pub(super) fn trace_creases(mesh: &Mesh, ends: &EndsOnBoundary, crossings: &mut usize) -> Vec<Traced> {
    if mesh.sharp.is_empty() {
        return Vec::new();
    }
    // Per sharp edge (directed a → b, original vertices, which keep their index and position
    // through the cut), the copies of a and b in the face on its left.
    let mut left: HashMap<(u32, u32), (u32, u32)> = HashMap::new();
    for f in &mesh.faces {
        for k in 0..3 {
            let (x, y) = (f[k], f[(k + 1) % 3]);
            let (a, b) = (mesh.original[x as usize], mesh.original[y as usize]);
            if mesh.sharp.contains(&edge_key(a, b)) {
                left.insert((a, b), (x, y));
            }
        }
    }
    let pos = |v: u32| mesh.positions[v as usize];
    let chains = chains(&mesh.sharp, pos);
    let mut out = Vec::new();
    for (chain, closed) in chains {
        let m = chain.len();
        let edges = if closed { m } else { m - 1 };
        let (mut samples, mut right) = (Vec::new(), Vec::new());
        for k in 0..edges {
            let (a, b) = (chain[k], chain[(k + 1) % m]);
            let (Some(&(la, lb)), Some(&(rb, ra))) = (left.get(&(a, b)), left.get(&(b, a))) else { continue };
            let n = |x: u32| mesh.normals[x as usize];
            samples.push(Raw { p: pos(a), n: n(la), node: k == 0 && !closed });
            right.push(n(ra));
            let (pa, pb) = (pos(a), pos(b));
            let d = pb - pa;
            let mut xs: Vec<(f64, DVec3)> = [edge_key(la, lb), edge_key(ra, rb)]
                .iter()
                .filter_map(|e| ends.get(e))
                .flatten()
                .map(|r| ((r.p - pa).dot(d) / d.length_squared().max(f64::MIN_POSITIVE), r.p))
                .collect();
            xs.sort_by(|x, y| x.0.total_cmp(&y.0));
            xs.dedup_by(|x, y| x.1.distance(y.1) <= 1e-9 * d.length());
            for (t, p) in xs {
                let t = t.clamp(0.0, 1.0);
                samples.push(Raw { p, n: n(la).lerp(n(lb), t), node: true });
                right.push(n(ra).lerp(n(rb), t));
                *crossings += 1;
            }
            if k + 1 == edges && !closed {
                samples.push(Raw { p: pb, n: n(lb), node: true });
                right.push(n(rb));
            }
        }
        if samples.len() < if closed { 3 } else { 2 } {
            continue;
        }
        let name = format!("crease #{}", out.len());
        out.push(Traced { plane: None, samples, closed, boundary: false, name, cut: false, right });
    }
    out
}

#[cfg(test)]
#[path = "tests/creases.rs"]
mod tests;
