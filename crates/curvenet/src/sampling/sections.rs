//! Stage 2b, the plane sections: each face crossed by a plane is cut along a segment from
//! edge to edge ([`cut_faces`]); the segments of each plane are chained through the edges they
//! share into polylines ([`trace_sections`]), closed loops or open polylines that end on the
//! mesh boundary, with the crossings ([`super::crossings`]) inserted as node samples. Points on
//! edges take the edge's vertex normals interpolated linearly ([`edge_point`]).

use super::boundary::Trimmer;
use super::crossings::Crossings;
use super::mesh::{edge_key, Mesh};
use super::planes::{place_planes, Planes};
use super::{EndsOnBoundary, Raw, SampleOptions, Scales, Traced, Traces};
use crate::geom::DVec3;
use std::collections::HashMap;

/// One plane section segment inside a face: it enters/leaves through edges `edges[0]`,
/// `edges[1]` at points `ends[0]`, `ends[1]`.
#[derive(Clone, Copy)]
pub(super) struct FaceCut {
    /// The plane (or principal curve, or boundary pseudo-plane) it belongs to.
    pub(super) plane: usize,
    /// The edges ([`edge_key`]) it enters and leaves the face through.
    pub(super) edges: [(u32, u32); 2],
    /// Its end points on those edges.
    pub(super) ends: [DVec3; 2],
}

/// Where plane `(axis, level)` (normal `dirs[axis]`) cuts edge `e` of the mesh: the point and
/// the edge's vertex normals interpolated linearly there (not normalised).
pub(super) fn edge_point(mesh: &Mesh, dirs: &[DVec3; 3], e: (u32, u32), plane: (usize, f64)) -> (DVec3, DVec3) {
    let (positions, normals) = (&mesh.positions, &mesh.normals);
    let (a, b) = (positions[e.0 as usize], positions[e.1 as usize]);
    let (sa, sb) = (a.dot(dirs[plane.0]) - plane.1, b.dot(dirs[plane.0]) - plane.1);
    let t = (sa / (sa - sb)).clamp(0.0, 1.0);
    let n = normals[e.0 as usize].lerp(normals[e.1 as usize], t);
    (a.lerp(b, t), n)
}

/// Cuts every face by every plane: the segments where a plane separates a face's corners
/// (plane by plane, faces in order), and per face the indices of its segments.
pub(super) fn cut_faces(mesh: &Mesh, planes: &Planes) -> (Vec<FaceCut>, Vec<Vec<usize>>) {
    let (positions, faces, dirs) = (&mesh.positions, &mesh.faces, &planes.dirs);
    let mut cuts_of_face: Vec<Vec<usize>> = vec![Vec::new(); faces.len()];
    let mut cuts: Vec<FaceCut> = Vec::new();
    for (pi, &(axis, c)) in planes.planes.iter().enumerate() {
        for (fi, f) in faces.iter().enumerate() {
            let side = f.map(|v| positions[v as usize].dot(dirs[axis]) > c);
            if side[0] == side[1] && side[1] == side[2] {
                continue;
            }
            let mut edges = Vec::with_capacity(2);
            for k in 0..3 {
                if side[k] != side[(k + 1) % 3] {
                    edges.push(edge_key(f[k], f[(k + 1) % 3]));
                }
            }
            if edges.len() != 2 {
                continue;
            }
            let e = [edges[0], edges[1]];
            let ends = e.map(|e| edge_point(mesh, dirs, e, (axis, c)).0);
            cuts_of_face[fi].push(cuts.len());
            cuts.push(FaceCut { plane: pi, edges: e, ends });
        }
    }
    (cuts, cuts_of_face)
}

/// The plane sections of the mesh (see the module documentation): planes placed off bad
/// crossings ([`place_planes`]), their cuts chained into polylines. With `opts.boundary`, an
/// end that runs along the mesh boundary is cut back to where it leaves it ([`Trimmer`]) and
/// the ends on boundary edges are recorded for the boundary loops.
pub(super) fn trace_sections(mesh: &Mesh, opts: &SampleOptions, scales: &Scales) -> Traces {
    let mut planes = Planes::new(&mesh.positions, opts.planes, opts.tilt, scales.diag);
    let placed = place_planes(mesh, &mut planes, opts.boundary || !mesh.sharp.is_empty(), scales);
    let mut chainer = Chainer {
        mesh,
        planes: &planes,
        cuts: &placed.cuts,
        crossings: &placed.crossings,
        boundary: opts.boundary || !mesh.sharp.is_empty(),
        trimmer: Trimmer::new(mesh, 3.0 * scales.snap),
        traced: Vec::new(),
        ends_on_boundary: HashMap::new(),
        trimmed: 0,
    };
    let mut cuts_of_plane: Vec<Vec<usize>> = vec![Vec::new(); planes.len()];
    for (ci, c) in placed.cuts.iter().enumerate() {
        cuts_of_plane[c.plane].push(ci);
    }
    for (pi, list) in cuts_of_plane.iter().enumerate() {
        chainer.chain_plane(pi, list);
    }
    let Chainer { traced, ends_on_boundary, trimmed, .. } = chainer;
    Traces {
        traced,
        ends_on_boundary,
        unresolved: placed.unresolved,
        spots: placed.crossings.shallow,
        crossings: placed.crossings.count,
        trimmed,
    }
}

/// Chains the face cuts of the planes into polylines; collects the polylines, their ends on
/// boundary edges and the number of ends trimmed.
struct Chainer<'a> {
    /// The mesh cut.
    mesh: &'a Mesh,
    /// The planes where they were left.
    planes: &'a Planes,
    /// Their face cuts.
    cuts: &'a [FaceCut],
    /// The crossings on the cuts.
    crossings: &'a Crossings,
    /// Whether the boundary loops are kept (ends are trimmed and recorded).
    boundary: bool,
    /// Cuts back ends that run along the boundary.
    trimmer: Trimmer,
    /// The polylines chained so far.
    traced: Vec<Traced>,
    /// Section end points on boundary edges, for the boundary loops.
    ends_on_boundary: EndsOnBoundary,
    /// The number of ends cut back.
    trimmed: usize,
}

/// A polyline of one plane walked through its cuts ([`Chainer::walk`]).
struct Walk {
    /// The samples: entry points and crossings.
    samples: Vec<Raw>,
    /// Back at the first cut.
    closed: bool,
    /// The edge the walk left the last cut through (an open polyline's last end).
    last_edge: (u32, u32),
}

impl Chainer<'_> {
    /// Chains the cuts `list` of plane `pi`: open polylines first, from the cuts with an
    /// edge no other cut of the plane shares (on the boundary), then closed loops through the
    /// cuts left. Pieces are named `X=level #k`.
    fn chain_plane(&mut self, pi: usize, list: &[usize]) {
        let mut by_edge: HashMap<(u32, u32), Vec<usize>> = HashMap::new();
        for &ci in list {
            for e in self.cuts[ci].edges {
                by_edge.entry(e).or_default().push(ci);
            }
        }
        let mut used: HashMap<usize, bool> = list.iter().map(|&c| (c, false)).collect();
        // Open chains start at a boundary edge (one cut), then closed loops.
        let mut starts: Vec<(usize, usize)> = Vec::new();
        for &ci in list {
            for k in 0..2 {
                if by_edge[&self.cuts[ci].edges[k]].len() == 1 {
                    starts.push((ci, k));
                }
            }
        }
        let closed_starts: Vec<(usize, usize)> = list.iter().map(|&c| (c, 0)).collect();
        let mut piece = 0;
        for (ci0, k0) in starts.into_iter().chain(closed_starts) {
            if used[&ci0] {
                continue;
            }
            let Walk { mut samples, closed, last_edge } = self.walk(pi, &by_edge, &mut used, (ci0, k0));
            if !closed && !self.end_open(&mut samples, [self.cuts[ci0].edges[k0], last_edge]) {
                continue;
            }
            let axis_name = ["X", "Y", "Z"];
            let (axis, lev) = self.planes.planes[pi];
            self.traced.push(Traced {
                plane: Some(pi),
                samples,
                closed,
                boundary: false,
                name: format!("{}={:.6} #{piece}", axis_name[axis], lev),
                cut: false,
                right: Vec::new(),
            });
            piece += 1;
        }
    }

    /// Walks plane `pi`'s cuts from cut `start.0`, entered through its edge `start.1`, to the
    /// next cut through each shared edge (`by_edge`), marking them `used`: the entry points and
    /// the crossings in order, until it is back at the first cut (closed) or reaches an edge
    /// without an unused next cut (open: that edge's point ends it).
    fn walk(
        &self,
        pi: usize,
        by_edge: &HashMap<(u32, u32), Vec<usize>>,
        used: &mut HashMap<usize, bool>,
        start: (usize, usize),
    ) -> Walk {
        let (cuts, plane) = (self.cuts, self.planes.planes[pi]);
        let mut samples = Vec::new();
        let (ci0, k0) = start;
        let (mut ci, mut enter) = (ci0, k0);
        loop {
            *used.get_mut(&ci).unwrap_or(&mut false) = true;
            let c = &cuts[ci];
            let e_in = c.edges[enter];
            let (p, n) = edge_point(self.mesh, &self.planes.dirs, e_in, plane);
            samples.push(Raw { p, n, node: false });
            let mut xs = self.crossings.at[ci].clone();
            if enter == 0 {
                xs.sort_by(|a, b| a.0.total_cmp(&b.0));
            } else {
                xs.sort_by(|a, b| b.0.total_cmp(&a.0));
            }
            samples.extend(xs.into_iter().map(|x| x.1));
            let e_out = c.edges[1 - enter];
            let next = by_edge[&e_out].iter().copied().find(|&o| o != ci);
            match next {
                Some(o) if o == ci0 => {
                    return Walk { samples, closed: true, last_edge: e_out };
                }
                Some(o) if !used[&o] => {
                    enter = if cuts[o].edges[0] == e_out { 0 } else { 1 };
                    ci = o;
                }
                _ => {
                    let (p, n) = edge_point(self.mesh, &self.planes.dirs, e_out, plane);
                    samples.push(Raw { p, n, node: false });
                    return Walk { samples, closed: false, last_edge: e_out };
                }
            }
        }
    }

    /// The ends of an open polyline (on edges `end_edges`, first and last): with boundary
    /// loops kept, an end on a boundary edge that runs along the boundary first is cut back to
    /// where it leaves it ([`Trimmer::trim_start`]), and the ends on boundary edges are
    /// recorded. Returns `false` (nothing recorded) when fewer than 2 samples are left.
    fn end_open(&mut self, samples: &mut Vec<Raw>, mut end_edges: [(u32, u32); 2]) -> bool {
        // Ends on boundary edges meet the boundary loops there. An end that runs along
        // the boundary first is cut back to where it leaves it.
        if self.boundary {
            for (side, end) in end_edges.iter_mut().enumerate() {
                if !self.mesh.is_boundary(*end) {
                    continue;
                }
                if side == 1 {
                    samples.reverse();
                }
                if let Some(e) = self.trimmer.trim_start(self.mesh, samples, *end) {
                    *end = e;
                    self.trimmed += 1;
                }
                if side == 1 {
                    samples.reverse();
                }
            }
        }
        if samples.len() < 2 {
            return false;
        }
        for (e, raw) in [(end_edges[0], samples[0]), (end_edges[1], samples[samples.len() - 1])] {
            if self.mesh.is_boundary(e) {
                self.ends_on_boundary.entry(e).or_default().push(raw);
            }
        }
        true
    }
}

#[cfg(test)]
#[path = "tests/sections.rs"]
mod tests;
