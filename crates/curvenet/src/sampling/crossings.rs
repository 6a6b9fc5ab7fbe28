//! Stage 3, the crossings: where two sections of different families cross on a triangle,
//! the crossing point is the triangle's point on both planes, a node sample shared by both
//! polylines ([`cross_sections`]). The bad spots that move the planes are found here too
//! ([`Crossings::add_bad_spots`]): crossings at a shallow angle, section ends on the mesh
//! boundary at a shallow angle, sections that pass close by each other without crossing
//! ([`near_misses`]) and crossings close together ([`close_crossings`]); the last two serve the
//! principal curves as well.

use super::mesh::Mesh;
use super::planes::{Planes, MIN_CROSSING_ANGLE_DEG};
use super::sections::FaceCut;
use super::{Raw, Scales};
use crate::geom::DVec3;
use std::collections::HashMap;

/// Crossing points per pair of planes `(smaller index, larger index)`; the mesh boundary is a
/// pseudo-plane with the index after the last plane.
pub(super) type CrossingPoints = HashMap<(usize, usize), Vec<DVec3>>;

/// The crossings of the sections of a set of planes.
pub(super) struct Crossings {
    /// Per face cut: its crossings as (parameter along `ends[0]` → `ends[1]`, node sample).
    pub(super) at: Vec<Vec<(f64, Raw)>>,
    /// The number of crossings.
    pub(super) count: usize,
    /// The crossing points per pair of planes (and the section ends on the boundary).
    pub(super) points: CrossingPoints,
    /// Bad spots: (plane to move, place).
    pub(super) shallow: Vec<(usize, DVec3)>,
}

/// The normal at point `p` of face `fi`: the vertex normals interpolated barycentrically (not
/// normalised); the first corner's normal on a face of zero area.
fn face_normal_at(mesh: &Mesh, fi: usize, p: DVec3) -> DVec3 {
    let (faces, positions, normals) = (&mesh.faces, &mesh.positions, &mesh.normals);
    let v = faces[fi].map(|i| positions[i as usize]);
    let area = (v[1] - v[0]).cross(v[2] - v[0]);
    let a2 = area.length_squared();
    if a2 == 0.0 {
        return normals[faces[fi][0] as usize];
    }
    let w0 = (v[1] - p).cross(v[2] - p).dot(area) / a2;
    let w1 = (v[2] - p).cross(v[0] - p).dot(area) / a2;
    let w2 = 1.0 - w0 - w1;
    let [n0, n1, n2] = faces[fi].map(|i| normals[i as usize]);
    w0 * n0 + w1 * n1 + w2 * n2
}

/// The crossings of the face cuts `cuts` of `planes` (`cuts_of_face`: the cuts in each face):
/// per face, for two cuts of different families, the point of the first cut on the second's
/// plane, if both cuts reach the other's plane inside the face. Crossings at an angle below
/// [`MIN_CROSSING_ANGLE_DEG`] are bad spots of the second cut's plane.
pub(super) fn cross_sections(mesh: &Mesh, planes: &Planes, cuts: &[FaceCut], cuts_of_face: &[Vec<usize>]) -> Crossings {
    let dirs = planes.dirs;
    let cos_min = MIN_CROSSING_ANGLE_DEG.to_radians().cos();
    let mut x = Crossings { at: vec![Vec::new(); cuts.len()], count: 0, points: HashMap::new(), shallow: Vec::new() };
    for (fi, list) in cuts_of_face.iter().enumerate() {
        for (i, &ca) in list.iter().enumerate() {
            for &cb in &list[i + 1..] {
                let (a, b) = (&cuts[ca], &cuts[cb]);
                let (axis_a, lev_a) = planes.planes[a.plane];
                let (axis_b, lev_b) = planes.planes[b.plane];
                if axis_a == axis_b {
                    continue;
                }
                // Parameter on a where a's line meets b's plane, and on b where it meets a's.
                let (sa0, sa1) = (a.ends[0].dot(dirs[axis_b]) - lev_b, a.ends[1].dot(dirs[axis_b]) - lev_b);
                let (sb0, sb1) = (b.ends[0].dot(dirs[axis_a]) - lev_a, b.ends[1].dot(dirs[axis_a]) - lev_a);
                if (sa0 > 0.0) == (sa1 > 0.0) || (sb0 > 0.0) == (sb1 > 0.0) {
                    continue;
                }
                let ta = sa0 / (sa0 - sa1);
                let tb = sb0 / (sb0 - sb1);
                let p = a.ends[0].lerp(a.ends[1], ta);
                let raw = Raw { p, n: face_normal_at(mesh, fi, p), node: true };
                x.at[ca].push((ta, raw));
                x.at[cb].push((tb, raw));
                x.count += 1;
                x.points.entry((a.plane.min(b.plane), a.plane.max(b.plane))).or_default().push(p);
                let (da, db) = (a.ends[1] - a.ends[0], b.ends[1] - b.ends[0]);
                let cos = da.dot(db).abs() / (da.length() * db.length());
                if cos > cos_min {
                    x.shallow.push((b.plane, p));
                }
            }
        }
    }
    x
}

impl Crossings {
    /// Adds the bad spots other than shallow crossings: with `boundary`, section ends on the
    /// mesh boundary at an angle below [`MIN_CROSSING_ANGLE_DEG`] (the boundary is the
    /// pseudo-plane `boundary_plane`, its edges pseudo-cuts that sections must not run
    /// alongside); then near misses closer than `scales.near` ([`near_misses`]) and crossings
    /// closer than `scales.gap` ([`close_crossings`]).
    pub(super) fn add_bad_spots(
        &mut self,
        mesh: &Mesh,
        cuts: &[FaceCut],
        boundary_plane: usize,
        boundary: bool,
        scales: &Scales,
    ) {
        let cos_min = MIN_CROSSING_ANGLE_DEG.to_radians().cos();
        let positions = &mesh.positions;
        let mut with_boundary: Vec<FaceCut> = cuts.to_vec();
        if boundary {
            for (e, fs) in &mesh.edge_faces {
                if fs.len() == 1 {
                    let ends = [positions[e.0 as usize], positions[e.1 as usize]];
                    with_boundary.push(FaceCut { plane: boundary_plane, edges: [*e, *e], ends });
                }
            }
            for c in cuts {
                for k in 0..2 {
                    if mesh.is_boundary(c.edges[k]) {
                        self.points.entry((c.plane, boundary_plane)).or_default().push(c.ends[k]);
                        let e = positions[c.edges[k].1 as usize] - positions[c.edges[k].0 as usize];
                        let d = c.ends[1] - c.ends[0];
                        if d.dot(e).abs() / (d.length() * e.length()) > cos_min {
                            self.shallow.push((c.plane, c.ends[k]));
                        }
                    }
                }
            }
        }
        // On a mesh cut along its creases a section crossing a crease ends on both sides at
        // one point: one end on the boundary, not two crossings close together.
        let tiny = 1e-9 * scales.diag;
        for ((_, b), ps) in self.points.iter_mut() {
            if *b == boundary_plane && !mesh.sharp.is_empty() {
                let mut kept: Vec<DVec3> = Vec::with_capacity(ps.len());
                for &p in ps.iter() {
                    if !kept.iter().any(|q| q.distance(p) <= tiny) {
                        kept.push(p);
                    }
                }
                *ps = kept;
            }
        }
        self.shallow.extend(near_misses(&with_boundary, &self.points, scales.near, boundary_plane));
        // Crossings closer than `gap` to each other: two crossings of the same two sections
        // (the pipeline would merge them into one node where the curves touch without
        // crossing), or three sections nearly through one point (a tiny cell whose nodes the
        // pipeline cannot tell apart once the crossings fall between noisy samples).
        self.shallow.extend(close_crossings(&self.points, scales.gap, scales.gap, boundary_plane));
    }
}

/// Planes whose sections come within `near` of a section of another plane away from their
/// crossings (near-misses: the pipeline would snap them into a node that is no crossing). Of
/// each such pair, the plane with the larger index below `first_virtual` is returned (planes
/// from `first_virtual` on stand for the mesh boundary and are not moved).
pub(super) fn near_misses(
    cuts: &[FaceCut],
    crossing_points: &CrossingPoints,
    near: f64,
    first_virtual: usize,
) -> Vec<(usize, DVec3)> {
    use crate::geom::closest_params_segment_segment;
    // Cells as long as a typical cut (padded by `near`): each cut in a few cells, and few cuts per
    // cell (cells of side `near` put a mesh edge in dozens, and the pairs were found again in
    // each: half of `curvenet sample`'s time on a 4.7k-vertex figure).
    // The median cut: on a mesh of uneven edges (long slivers, dense fillets) the mean would
    // put a dense region's cuts in one cell.
    let mut lengths: Vec<f64> = cuts.iter().map(|c| c.ends[0].distance(c.ends[1])).collect();
    let median = if lengths.is_empty() {
        0.0
    } else {
        let mid = lengths.len() / 2;
        *lengths.select_nth_unstable_by(mid, f64::total_cmp).1
    };
    let h = near.max(median).max(f64::MIN_POSITIVE);
    let mut grid: HashMap<(i64, i64, i64), Vec<u32>> = HashMap::new();
    let mut along = Vec::new();
    for (i, c) in cuts.iter().enumerate() {
        // Each cut in the cells along it (a cut far longer than the tolerance on a coarse mesh
        // fills a line of cells, not its box).
        crate::geom::segment_cells(c.ends[0], c.ends[1], near, h, &mut along);
        for &cell in &along {
            grid.entry(cell).or_default().push(i as u32);
        }
    }
    // The candidate pairs once each, in a fixed order.
    let mut pairs: Vec<(u32, u32)> = Vec::new();
    for list in grid.values() {
        for (k, &i) in list.iter().enumerate() {
            for &j in &list[k + 1..] {
                if cuts[i as usize].plane != cuts[j as usize].plane {
                    pairs.push((i.min(j), i.max(j)));
                }
            }
        }
    }
    pairs.sort_unstable();
    pairs.dedup();
    let mut out = Vec::new();
    for (i, j) in pairs {
        let (a, b) = (&cuts[i as usize], &cuts[j as usize]);
        let (s, t) = closest_params_segment_segment(a.ends[0], a.ends[1], b.ends[0], b.ends[1]);
        let (pa, pb) = (a.ends[0].lerp(a.ends[1], s), b.ends[0].lerp(b.ends[1], t));
        if pa.distance(pb) > near {
            continue;
        }
        let key = (a.plane.min(b.plane), a.plane.max(b.plane));
        let m = 0.5 * (pa + pb);
        let at_crossing = crossing_points.get(&key).is_some_and(|ps| ps.iter().any(|p| p.distance(m) <= 4.0 * near));
        if !at_crossing {
            out.push((if key.1 >= first_virtual { key.0 } else { key.1 }, m));
        }
    }
    out
}

/// Planes to move so that no two crossings are closer than `gap` (`gap_same` for two
/// crossings of the same two planes): of two close crossings, a plane they share is kept and
/// the other one with the larger index is returned.
pub(super) fn close_crossings(
    crossing_points: &CrossingPoints,
    gap: f64,
    gap_same: f64,
    first_virtual: usize,
) -> Vec<(usize, DVec3)> {
    let mut out = Vec::new();
    for (key, ps) in crossing_points {
        if let Some(p) = ps.iter().enumerate().find(|(i, p)| ps[i + 1..].iter().any(|q| q.distance(**p) <= gap_same)) {
            out.push((if key.1 >= first_virtual { key.0 } else { key.1 }, *p.1));
        }
    }
    let h = gap.max(f64::MIN_POSITIVE);
    let cell = |p: DVec3| ((p.x / h).floor() as i64, (p.y / h).floor() as i64, (p.z / h).floor() as i64);
    let mut all: Vec<((usize, usize), DVec3)> =
        crossing_points.iter().flat_map(|(k, ps)| ps.iter().map(move |p| (*k, *p))).collect();
    all.sort_by(|a, b| a.0.cmp(&b.0).then(a.1.x.total_cmp(&b.1.x)));
    let mut grid: HashMap<(i64, i64, i64), Vec<usize>> = HashMap::new();
    for (i, (_, p)) in all.iter().enumerate() {
        grid.entry(cell(*p)).or_default().push(i);
    }
    for (i, (ka, p)) in all.iter().enumerate() {
        let c = cell(*p);
        for dx in -1..=1 {
            for dy in -1..=1 {
                for dz in -1..=1 {
                    for &j in grid.get(&(c.0 + dx, c.1 + dy, c.2 + dz)).map_or(&[][..], |v| &v[..]) {
                        let (kb, q) = &all[j];
                        if j <= i || q.distance(*p) > gap {
                            continue;
                        }
                        let planes = [ka.0, ka.1, kb.0, kb.1];
                        let shared = planes.iter().find(|&&x| planes.iter().filter(|&&y| y == x).count() > 1);
                        let pick = planes
                            .iter()
                            .copied()
                            .filter(|x| Some(x) != shared && *x < first_virtual)
                            .max()
                            .unwrap_or(ka.0);
                        out.push((pick, *p));
                    }
                }
            }
        }
    }
    out
}

#[cfg(test)]
#[path = "tests/crossings.rs"]
mod tests;
