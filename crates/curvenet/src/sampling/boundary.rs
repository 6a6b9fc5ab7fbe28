//! Stage 4, the boundary: the mesh's boundary loops as boundary curves, with the ends of the
//! sections on them inserted as nodes ([`trace_boundary`]); and, while the sections are
//! chained, their ends that run along the boundary cut back to where they leave it
//! ([`Trimmer`]).

use super::mesh::{edge_key, EdgeFaces, Mesh};
use super::{EndsOnBoundary, Raw, Traced};
use crate::geom::DVec3;
use crate::topology::UnionFind;
use std::collections::HashMap;

/// The boundary loops of the mesh as boundary curves (closed, named `boundary #k`): the mesh
/// vertices along each loop, the surface on its left, with the section ends recorded on its
/// edges (`ends_on_boundary`) inserted as nodes in order along each edge; each adds one to
/// `crossings`.
pub(super) fn trace_boundary(mesh: &Mesh, ends_on_boundary: &EndsOnBoundary, crossings: &mut usize) -> Vec<Traced> {
    let mut next_of = boundary_successors(mesh);
    let mut starts: Vec<u32> = next_of.keys().copied().collect();
    starts.sort_unstable();
    let mut loops = Vec::new();
    for s in starts {
        while next_of.get(&s).is_some_and(|v| !v.is_empty()) {
            let verts = walk_loop(&mut next_of, s);
            if verts.len() < 3 {
                continue;
            }
            let samples = loop_samples(mesh, &verts, ends_on_boundary, crossings);
            let name = format!("boundary #{}", loops.len());
            loops.push(Traced {
                plane: None,
                samples,
                closed: true,
                boundary: true,
                name,
                cut: false,
                right: Vec::new(),
            });
        }
    }
    loops
}

/// The directed boundary edges as their faces have them (the surface on their left): per
/// vertex, the vertices its boundary edges lead to.
fn boundary_successors(mesh: &Mesh) -> HashMap<u32, Vec<u32>> {
    let mut next_of: HashMap<u32, Vec<u32>> = HashMap::new();
    for f in &mesh.faces {
        for k in 0..3 {
            let (a, b) = (f[k], f[(k + 1) % 3]);
            if a != b && mesh.is_boundary(edge_key(a, b)) && !mesh.on_crease(a, b) {
                next_of.entry(a).or_default().push(b);
            }
        }
    }
    next_of
}

/// The vertices of one boundary loop from `s`, following (and using up) the last successor of
/// each vertex in `next_of` until back at `s` or stuck.
fn walk_loop(next_of: &mut HashMap<u32, Vec<u32>>, s: u32) -> Vec<u32> {
    let mut verts = vec![s];
    let mut v = s;
    while let Some(w) = next_of.get_mut(&v).and_then(|list| list.pop()) {
        if w == s {
            break;
        }
        verts.push(w);
        v = w;
    }
    verts
}

/// The samples of the closed loop through `verts`: each vertex (with its normal), then the
/// section ends on the edge to the next vertex, ordered along it, as nodes (counted in
/// `crossings`).
fn loop_samples(mesh: &Mesh, verts: &[u32], ends_on_boundary: &EndsOnBoundary, crossings: &mut usize) -> Vec<Raw> {
    let (positions, normals) = (&mesh.positions, &mesh.normals);
    let m = verts.len();
    let mut samples = Vec::new();
    for k in 0..m {
        let (a, b) = (verts[k], verts[(k + 1) % m]);
        samples.push(Raw { p: positions[a as usize], n: normals[a as usize], node: false });
        if let Some(list) = ends_on_boundary.get(&edge_key(a, b)) {
            let (pa, pb) = (positions[a as usize], positions[b as usize]);
            let d = pb - pa;
            let mut xs: Vec<(f64, Raw)> =
                list.iter().map(|r| ((r.p - pa).dot(d) / d.length_squared().max(f64::MIN_POSITIVE), *r)).collect();
            xs.sort_by(|x, y| x.0.total_cmp(&y.0));
            for (_, mut r) in xs {
                r.node = true;
                *crossings += 1;
                samples.push(r);
            }
        }
    }
    samples
}

/// With `on`, makes the ends of the open polylines `traced` nodes (plane sections end on the
/// boundary when the boundary loops are kept; principal curves mark their own ends there).
pub(super) fn mark_ends(traced: &mut [Traced], on: bool) {
    for t in traced {
        if !t.closed && on {
            let last = t.samples.len() - 1;
            t.samples[0].node = true;
            t.samples[last].node = true;
        }
    }
}

/// The mesh's boundary edges in a uniform grid of cell size `h`.
struct BoundaryGrid {
    /// The cell size.
    h: f64,
    /// The boundary edges ([`super::mesh::edge_key`]) passing through each cell.
    cells: HashMap<(i64, i64, i64), Vec<(u32, u32)>>,
}

impl BoundaryGrid {
    /// The boundary edges of `edge_faces` (with vertex `positions`) in cells of size `h`
    /// (each in the cells along it, [`crate::geom::segment_cells`]: also a long edge).
    fn new(positions: &[DVec3], edge_faces: &EdgeFaces, h: f64) -> Self {
        let h = h.max(f64::MIN_POSITIVE);
        let mut cells: HashMap<(i64, i64, i64), Vec<(u32, u32)>> = HashMap::new();
        let mut along = Vec::new();
        // In a fixed order: the cells' lists decide between coincident edges (the two sides of
        // a crease the mesh was cut along) only where the normals do not.
        let mut edges: Vec<(u32, u32)> = edge_faces.iter().filter(|(_, fs)| fs.len() == 1).map(|(e, _)| *e).collect();
        edges.sort_unstable();
        for e in &edges {
            let (a, b) = (positions[e.0 as usize], positions[e.1 as usize]);
            crate::geom::segment_cells(a, b, 0.0, h, &mut along);
            for &cell in &along {
                cells.entry(cell).or_default().push(*e);
            }
        }
        BoundaryGrid { h, cells }
    }

    /// The closest boundary edge point within the grid's cell size of `p`: (distance, edge, t).
    /// Of coincident edges (the two sides of a crease cut), the one whose vertex normals
    /// (`normals`) agree best with `n`.
    fn closest(&self, positions: &[DVec3], normals: &[DVec3], p: DVec3, n: DVec3) -> Option<(f64, (u32, u32), f64)> {
        let h = self.h;
        let c = ((p.x / h).floor() as i64, (p.y / h).floor() as i64, (p.z / h).floor() as i64);
        let mut best: Option<(f64, (u32, u32), f64)> = None;
        for dx in -1..=1 {
            for dy in -1..=1 {
                for dz in -1..=1 {
                    for e in self.cells.get(&(c.0 + dx, c.1 + dy, c.2 + dz)).map_or(&[][..], |v| &v[..]) {
                        let (a, b) = (positions[e.0 as usize], positions[e.1 as usize]);
                        let d = b - a;
                        let t = ((p - a).dot(d) / d.length_squared().max(f64::MIN_POSITIVE)).clamp(0.0, 1.0);
                        let dist = p.distance(a + t * d);
                        let agree = n.dot(normals[e.0 as usize] + normals[e.1 as usize]);
                        let better = |x: &(f64, (u32, u32), f64)| {
                            let theirs = n.dot(normals[x.1 .0 as usize] + normals[x.1 .1 as usize]);
                            dist < x.0 || (dist == x.0 && agree > theirs)
                        };
                        if dist <= h && best.as_ref().is_none_or(better) {
                            best = Some((dist, *e, t));
                        }
                    }
                }
            }
        }
        best
    }
}

/// Cuts back section ends that run along the mesh boundary ([`Trimmer::trim_start`]).
pub(super) struct Trimmer {
    /// The boundary edges, in cells of the band width.
    grid: BoundaryGrid,
    /// The band along the boundary: three times the snapping tolerance.
    band: f64,
    /// The boundary loop (a representative vertex) of each vertex.
    loop_of: Vec<usize>,
}

impl Trimmer {
    /// A trimmer for the boundary of `mesh` with band width `band`.
    pub(super) fn new(mesh: &Mesh, band: f64) -> Trimmer {
        let grid = BoundaryGrid::new(&mesh.positions, &mesh.edge_faces, band);
        // Boundary loop of each boundary vertex (components of the boundary edges).
        let mut loop_uf = UnionFind::new(mesh.positions.len());
        for (e, fs) in &mesh.edge_faces {
            if fs.len() == 1 {
                loop_uf.union(e.0 as usize, e.1 as usize);
            }
        }
        let loop_of: Vec<usize> = (0..mesh.positions.len()).map(|v| loop_uf.find(v)).collect();
        Trimmer { grid, band, loop_of }
    }

    /// A section that ends on the mesh boundary (its first sample, on boundary edge `edge`)
    /// but runs along it first (closer than the band to it) would be snapped onto the boundary
    /// curve over that stretch by the pipeline: its first samples within the band are removed
    /// and the section starts instead at the boundary point closest to its first sample
    /// outside the band (a short link across to the boundary), if that point is on the same
    /// boundary loop. A section within the band all along is emptied.
    /// Returns the boundary edge of the new end, or `None` when nothing was cut.
    pub(super) fn trim_start(&self, mesh: &Mesh, samples: &mut Vec<Raw>, edge: (u32, u32)) -> Option<(u32, u32)> {
        let (grid, band, positions, normals) = (&self.grid, self.band, &mesh.positions, &mesh.normals);
        // The end point itself is on the boundary; look at the following samples.
        let mut k = 1;
        while k < samples.len()
            && grid.closest(positions, normals, samples[k].p, samples[k].n).is_some_and(|c| c.0 < band)
        {
            k += 1;
        }
        // Leaves the band within 2.5 band widths of arc: a fair crossing (≥ 24°), keep it.
        let arc: f64 = (1..k.min(samples.len())).map(|i| samples[i].p.distance(samples[i - 1].p)).sum();
        if arc <= 2.5 * band || k >= samples.len() {
            if k >= samples.len() {
                samples.clear();
            }
            return None;
        }
        let (_, e, t) = grid.closest(positions, normals, samples[k - 1].p, samples[k - 1].n)?;
        // Across to another boundary loop would span a hole: keep the section as it is.
        if self.loop_of[e.0 as usize] != self.loop_of[edge.0 as usize] {
            return None;
        }
        let (a, b) = (positions[e.0 as usize], positions[e.1 as usize]);
        let n = mesh.normals[e.0 as usize].lerp(mesh.normals[e.1 as usize], t);
        let end = Raw { p: a.lerp(b, t), n, node: false };
        samples.drain(0..k - 1);
        samples[0] = end;
        Some(e)
    }
}

#[cfg(test)]
#[path = "tests/boundary.rs"]
mod tests;
