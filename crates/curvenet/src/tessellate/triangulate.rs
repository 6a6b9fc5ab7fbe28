//! The triangulation of one planar patch domain: a hexagonal lattice inside
//! ([`super::lattice`]), a refined constrained Delaunay triangulation (spade) of the band
//! between the border and the lattice, and the lift of the result to a [`PatchMesh`].

use super::lattice::{hex_lattice, lattice_triangles, Lattice, LatticeTriangles};
use super::relax::{relax, Twin};
use super::{PatchMesh, VRef, MAX_AREA_FACTOR, MIN_ANGLE_DEG};
use crate::error::{Error, Result};
use crate::geom::{polygon_signed_area, DVec2, DVec3};
use spade::{AngleLimit, ConstrainedDelaunayTriangulation, Point2, RefinementParameters, Triangulation};

/// A triangulated domain: triangles (indices into `positions`), the planar positions (the
/// border first, in its order), and per position the vertex it is (`map`).
pub(super) type Triangulated = (Vec<[usize; 3]>, Vec<DVec2>, Vec<VRef>);

/// Triangulates a planar polygon (`pts`, counter-clockwise; `map[i]` is the vertex at
/// `pts[i]`, where two border positions may be one vertex, as along a tube's seam), refining
/// to spacing `d`.
///
/// Outputs the positions in the order: the border (`pts`), the lattice points, the points
/// the refinement added; the map extended with new vertices ([`VRef::New`], numbered after
/// those already in `map`) for the lattice points and for the refinement points that some
/// triangle uses (`VRef::New(u32::MAX)` for the others). `what` names the patch in messages.
///
/// Errors ([`Error::Topology`]): fewer than 3 border vertices, a border that runs clockwise or
/// encloses no area, crosses itself or has two vertices on one point; [`Error::Numerical`]:
/// the refinement does not finish.
pub(super) fn triangulate(pts: Vec<DVec2>, map: Vec<VRef>, d: f64, what: &dyn Fn() -> String) -> Result<Triangulated> {
    let n = pts.len();
    if n < 3 {
        return Err(Error::topology(format!("{}: a patch needs at least 3 boundary vertices", what())));
    }
    let area = polygon_signed_area(&pts);
    let counter_clockwise = area > 0.0; // false for NaN too
    if !counter_clockwise {
        return Err(Error::topology(format!(
            "{}: the cycle runs clockwise (or encloses no area) when projected on its plane; \
             the projection folds over or the normals disagree with the cycle",
            what()
        )));
    }
    // Interior points on a hexagonal lattice of side `d` (equilateral triangles of edge d),
    // away from the border. The lattice's own triangles are taken as they are; only the zone
    // between the border and the lattice region goes through the constrained Delaunay
    // triangulation and its refinement, with the lattice region's outline as constraint edges
    // (its inside is then an excluded hole, like the outside of the border).
    let lattice = hex_lattice(&pts, d);
    let lat = lattice_triangles(&lattice);
    let m = lattice.points.len();
    let (mut tris, refined_points) = border_band(&pts, &lattice, &lat, area, d, what)?;
    tris.extend(lat.triangles.iter().map(|t| t.map(|v| n + v as usize)));
    // Output vertices: the border, all lattice points, then the refinement's new points.
    let refined = refined_points.len();
    let mut positions: Vec<DVec2> = pts.clone();
    positions.extend_from_slice(&lattice.points);
    positions.extend(refined_points);
    // Balance the one-rings where the band meets the lattice; a seam vertex of a tube (on both
    // edges of its strip) moves as one vertex with the triangles of both sides.
    let mut first_at = std::collections::HashMap::new();
    let mut twins = Vec::new();
    for (i, r) in map.iter().enumerate() {
        if let VRef::New(_) = r {
            if let Some(&a) = first_at.get(r) {
                twins.push(Twin { a, b: i, offset: positions[i] - positions[a] });
            } else {
                first_at.insert(*r, i);
            }
        }
    }
    relax(&tris, &mut positions, n, &twins);
    let map = number_new_vertices(map, n, m, refined, &tris);
    Ok((tris, positions, map))
}

/// The band between the border `pts` (`n` points) and the outline of the lattice's triangles
/// `lat`: the constrained Delaunay triangulation of both, with the outside of the border and
/// the inside of the outline excluded, refined to minimum angle [`MIN_ANGLE_DEG`] and maximum
/// area [`MAX_AREA_FACTOR`]` d²` without splitting the constraint edges. `area` is the
/// polygon's area (it bounds the refinement's budget).
///
/// Returns the band's triangles, numbered as [`triangulate`] outputs them (border `0..n`,
/// lattice points `n..n + m`, refinement points from `n + m`), and the refinement's points.
fn border_band(
    pts: &[DVec2],
    lattice: &Lattice,
    lat: &LatticeTriangles,
    area: f64,
    d: f64,
    what: &dyn Fn() -> String,
) -> Result<(Vec<[usize; 3]>, Vec<DVec2>)> {
    let n = pts.len();
    let m = lattice.points.len();
    // CDT vertices: the border, then the lattice points on the outline (or in no triangle).
    let outline: Vec<u32> = (0..m as u32).filter(|&v| !lat.interior[v as usize]).collect();
    let mut cdt_of = vec![u32::MAX; m];
    for (k, &v) in outline.iter().enumerate() {
        cdt_of[v as usize] = (n + k) as u32;
    }
    let vertices: Vec<Point2<f64>> =
        pts.iter().chain(outline.iter().map(|&v| &lattice.points[v as usize])).map(|p| Point2::new(p.x, p.y)).collect();
    let mut edges: Vec<[usize; 2]> = (0..n).map(|i| [i, (i + 1) % n]).collect();
    edges.extend(lat.outline.iter().map(|e| [cdt_of[e[0] as usize] as usize, cdt_of[e[1] as usize] as usize]));
    let total = vertices.len();
    let mut conflict = None;
    let cdt = ConstrainedDelaunayTriangulation::<Point2<f64>>::try_bulk_load_cdt(vertices, edges, |e| {
        conflict.get_or_insert(e);
    });
    let mut cdt =
        cdt.map_err(|e| Error::topology(format!("{}: the projected cycle cannot be triangulated ({e:?})", what())))?;
    if cdt.num_vertices() != total {
        return Err(Error::topology(format!(
            "{}: two boundary vertices fall on the same point when projected on the patch's plane \
             (the cycle folds over in projection)",
            what()
        )));
    }
    if let Some([a, _]) = conflict {
        let p = if a < n { pts[a] } else { lattice.points[outline[a - n] as usize] };
        return Err(Error::topology(format!(
            "{}: the cycle crosses itself when projected on its plane (near ({:.4}, {:.4})); \
             the patch is too deep or twisted for a planar projection: add a curve that splits it",
            what(),
            p.x,
            p.y
        )));
    }
    let max_area = MAX_AREA_FACTOR * d * d;
    let expected = (area / max_area * 4.0) as usize + 4 * n + 1000;
    let result = cdt.refine(
        RefinementParameters::<f64>::new()
            .with_angle_limit(AngleLimit::from_deg(MIN_ANGLE_DEG))
            .with_max_allowed_area(max_area)
            .keep_constraint_edges()
            .exclude_outer_faces(true)
            .with_max_additional_vertices(expected),
    );
    if !result.refinement_complete {
        return Err(Error::numerical(format!(
            "{}: the quality triangulation did not finish within {expected} new vertices \
             (very small angles between curves at a node?)",
            what()
        )));
    }
    let mut excluded = vec![false; cdt.num_all_faces()];
    for f in &result.excluded_faces {
        excluded[f.index()] = true;
    }
    let refined: Vec<DVec2> = cdt.vertices().skip(total).map(|v| DVec2::new(v.position().x, v.position().y)).collect();
    let out_of = |i: usize| -> usize {
        if i < n {
            i
        } else if i < total {
            n + outline[i - n] as usize
        } else {
            n + m + (i - total)
        }
    };
    let mut tris = Vec::with_capacity(cdt.num_inner_faces() + lat.triangles.len());
    for f in cdt.inner_faces() {
        if excluded[f.fix().index()] {
            continue;
        }
        let v = f.vertices();
        tris.push([out_of(v[0].fix().index()), out_of(v[1].fix().index()), out_of(v[2].fix().index())]);
    }
    Ok((tris, refined))
}

/// `map` (the border's vertices) extended with new vertices: one per lattice point (`m`, in
/// order), then one per refinement point (`refined` of them, from position `n + m`) that some
/// triangle of `tris` uses, numbered in the order the triangles first use them;
/// `VRef::New(u32::MAX)` for the unused ones. New vertices are numbered after the largest
/// [`VRef::New`] already in `map`.
fn number_new_vertices(mut map: Vec<VRef>, n: usize, m: usize, refined: usize, tris: &[[usize; 3]]) -> Vec<VRef> {
    let mut next_new =
        map.iter().filter_map(|m| if let VRef::New(k) = m { Some(*k + 1) } else { None }).max().unwrap_or(0);
    for _ in 0..m {
        map.push(VRef::New(next_new));
        next_new += 1;
    }
    let mut new_of: Vec<Option<VRef>> = vec![None; refined];
    for t in tris {
        for &i in t {
            if i >= n + m && new_of[i - n - m].is_none() {
                new_of[i - n - m] = Some(VRef::New(next_new));
                next_new += 1;
            }
        }
    }
    map.extend(new_of.into_iter().map(|r| r.unwrap_or(VRef::New(u32::MAX))));
    map
}

/// Lifts a triangulated domain ([`triangulate`]'s output) to a [`PatchMesh`]: each new vertex
/// placed at `lift` of its (first) planar position, the triangles in vertex references with
/// their planar corners.
///
/// Errors ([`Error::Topology`]): a triangle whose corners are one vertex twice (the patch is
/// too narrow for the spacing, e.g. across a tube's seam).
pub(super) fn lift_patch(
    tris: Vec<[usize; 3]>,
    pos2: &[DVec2],
    map: &[VRef],
    lift: impl Fn(DVec2) -> DVec3,
    what: &dyn Fn() -> String,
) -> Result<PatchMesh> {
    let num_new = map
        .iter()
        .filter_map(|m| if let VRef::New(k) = m { (*k != u32::MAX).then_some(*k as usize + 1) } else { None })
        .max()
        .unwrap_or(0);
    let mut new_positions = vec![DVec3::ZERO; num_new];
    let mut seen = vec![false; num_new];
    for (i, m) in map.iter().enumerate() {
        if let VRef::New(k) = *m {
            if k != u32::MAX && !seen[k as usize] {
                seen[k as usize] = true;
                new_positions[k as usize] = lift(pos2[i]);
            }
        }
    }
    let mut triangles = Vec::with_capacity(tris.len());
    let mut planar = Vec::with_capacity(tris.len());
    for t in tris {
        let r = [map[t[0]], map[t[1]], map[t[2]]];
        if r[0] == r[1] || r[1] == r[2] || r[0] == r[2] {
            return Err(Error::topology(format!(
                "{}: the patch is too narrow for the spacing (a triangle would join a vertex to itself); lower `spacing`",
                what()
            )));
        }
        triangles.push(r);
        planar.push([pos2[t[0]], pos2[t[1]], pos2[t[2]]]);
    }
    Ok(PatchMesh { new_positions, triangles, planar, fold_fallback: false })
}

#[cfg(test)]
#[path = "tests/triangulate.rs"]
mod tests;
