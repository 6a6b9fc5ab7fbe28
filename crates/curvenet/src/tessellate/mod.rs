//! Tessellation of the patches ([CG] §3.3): each cycle is projected on the plane through its
//! mean point with its mean normal and triangulated there by a quality constrained Delaunay
//! triangulation (spade: minimum angle ≥ 25°, target edge ≈ `d`, no new points on the
//! boundary). A tube patch (two facing boundary loops) is unrolled along a seam onto a
//! trapezoidal strip instead (an annulus domain cut open). All patches are merged into one
//! [`Mesh`] that shares the curve vertices; the per-face planar coordinates are kept for the
//! paper's planar cotangent weights.

pub mod conformal;

use crate::topology::resample::Resampled;
use crate::error::{Error, Result};
use crate::geom::{fmt_point, plane_frame, polygon_signed_area, polygon_vector_area, DVec2, DVec3};
use crate::geom::mesh::Mesh;
use crate::topology::{Graph, HalfEdge, Patch};
use rayon::prelude::*;
use spade::{AngleLimit, ConstrainedDelaunayTriangulation, Point2, RefinementParameters, Triangulation};

/// Minimum angle the refinement aims for, in degrees.
pub const MIN_ANGLE_DEG: f64 = 25.0;
/// Maximum triangle area as a multiple of `d²` (an equilateral triangle of side `d` has
/// 0.433 d²; refinement stops once every triangle is below the limit, so the mean edge comes
/// out close to `d`).
pub const MAX_AREA_FACTOR: f64 = 0.69;
/// Free vertices per unit planar area, times `d²`, that the refinement produces (measured;
/// used to turn a target vertex count into a spacing).
pub const VERTICES_PER_AREA: f64 = 1.155;

/// A vertex of a patch triangulation: a curve vertex (global id) or a new free vertex of the
/// patch (local id).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum VRef {
    Curve(u32),
    New(u32),
}

struct PatchMesh {
    new_positions: Vec<DVec3>,
    triangles: Vec<[VRef; 3]>,
    planar: Vec<[DVec2; 3]>,
    /// Triangulated in a fallback domain: its planar projection folds over.
    fold_fallback: bool,
}

/// Curve vertex ids around one loop of half-edges (each node once).
fn loop_vertices(res: &Resampled, hs: &[HalfEdge]) -> Vec<u32> {
    let mut ids = Vec::new();
    for h in hs {
        let sv = &res.segment_vertices[h.segment];
        if h.forward {
            ids.extend_from_slice(&sv[..sv.len() - 1]);
        } else {
            ids.extend(sv[1..].iter().rev());
        }
    }
    ids
}

fn describe_patch(g: &Graph, hs: &[HalfEdge]) -> String {
    let mut curves: Vec<&str> = hs.iter().map(|h| g.labels[g.segments[h.segment].curve].as_str()).collect();
    curves.dedup();
    let mut s = curves.join(", ");
    if s.len() > 200 {
        s.truncate(200);
        s.push('…');
    }
    s
}

/// Triangulates a planar polygon (`boundary[i]` at `pts[i]`, counter-clockwise) plus an
/// optional set of vertex identifications, refining to spacing `d`.
fn triangulate(
    pts: Vec<DVec2>,
    map: Vec<VRef>,
    d: f64,
    what: &dyn Fn() -> String,
) -> Result<(Vec<[usize; 3]>, Vec<DVec2>, Vec<VRef>)> {
    let n = pts.len();
    if n < 3 {
        return Err(Error::topology(format!("{}: a patch needs at least 3 boundary vertices", what())));
    }
    let area = polygon_signed_area(&pts);
    if !(area > 0.0) {
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
    // Output vertices: the border, all lattice points, then the refinement's new points.
    let mut positions: Vec<DVec2> = pts.clone();
    positions.extend_from_slice(&lattice.points);
    let refined = cdt.num_vertices() - total;
    positions.extend(cdt.vertices().skip(total).map(|v| DVec2::new(v.position().x, v.position().y)));
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
    tris.extend(lat.triangles.iter().map(|t| t.map(|v| n + v as usize)));
    // New vertices: the lattice points, then the refinement points some triangle uses.
    let mut map = map;
    let mut next_new =
        map.iter().filter_map(|m| if let VRef::New(k) = m { Some(*k + 1) } else { None }).max().unwrap_or(0);
    for _ in 0..m {
        map.push(VRef::New(next_new));
        next_new += 1;
    }
    let mut new_of: Vec<Option<VRef>> = vec![None; refined];
    for t in &tris {
        for &i in t {
            if i >= n + m && new_of[i - n - m].is_none() {
                new_of[i - n - m] = Some(VRef::New(next_new));
                next_new += 1;
            }
        }
    }
    map.extend(new_of.into_iter().map(|r| r.unwrap_or(VRef::New(u32::MAX))));
    Ok((tris, positions, map))
}

/// Points of a hexagonal lattice with their lattice coordinates.
struct Lattice {
    points: Vec<DVec2>,
    /// Point index at `row * cols + col`, `u32::MAX` where there is none. Row `k` holds the
    /// points `x = x0 + (k odd ? d/2 : 0) + col·d`.
    grid: Vec<u32>,
    rows: usize,
    cols: usize,
}

/// The lattice's own triangles (each with its three corners in the lattice,
/// counter-clockwise), the outline of their union, and which points are inside it.
struct LatticeTriangles {
    triangles: Vec<[u32; 3]>,
    /// Edges of exactly one triangle.
    outline: Vec<[u32; 2]>,
    /// Per point: in some triangle and on no outline edge.
    interior: Vec<bool>,
}

/// Triangles of the hexagonal lattice whose three corners are lattice points. Each triangle
/// lies inside the polygon the lattice was made for: its corners are at least `0.6 d` from the
/// border, more than the circumradius `d/√3`, so no border vertex lies in it and no border
/// edge crosses it.
fn lattice_triangles(lat: &Lattice) -> LatticeTriangles {
    let m = lat.points.len();
    let at = |row: usize, col: isize| -> u32 {
        if row >= lat.rows || col < 0 || col as usize >= lat.cols {
            u32::MAX
        } else {
            lat.grid[row * lat.cols + col as usize]
        }
    };
    // Neighbours of (row, col) in row + 1: left and right (odd rows are shifted by d/2).
    let up = |row: usize, col: isize| if row % 2 == 0 { (col - 1, col) } else { (col, col + 1) };
    // Edge use counts per point and direction: 0 east, 1 up-left, 2 up-right.
    let mut uses = vec![0u8; 3 * m];
    let mut triangles = Vec::new();
    let mut in_triangle = vec![false; m];
    for row in 0..lat.rows.saturating_sub(1) {
        for col in 0..lat.cols as isize {
            let a = at(row, col);
            if a == u32::MAX {
                continue;
            }
            let (ul, ur) = up(row, col);
            let (above_l, above_r) = (at(row + 1, ul), at(row + 1, ur));
            // "Up" triangle: a, its east neighbour b, and the point above between them.
            let b = at(row, col + 1);
            if b != u32::MAX && above_r != u32::MAX {
                triangles.push([a, b, above_r]);
                uses[3 * a as usize] += 1; // a–b
                uses[3 * a as usize + 2] += 1; // a–apex
                uses[3 * b as usize + 1] += 1; // b–apex
            }
            // "Down" triangle: a and the two points above it.
            if above_l != u32::MAX && above_r != u32::MAX {
                triangles.push([a, above_r, above_l]);
                uses[3 * above_l as usize] += 1; // left–right above
                uses[3 * a as usize + 2] += 1; // a–right
                uses[3 * a as usize + 1] += 1; // a–left
            }
        }
    }
    for t in &triangles {
        for &v in t {
            in_triangle[v as usize] = true;
        }
    }
    let mut interior = in_triangle;
    let mut outline = Vec::new();
    for row in 0..lat.rows {
        for col in 0..lat.cols as isize {
            let a = at(row, col);
            if a == u32::MAX {
                continue;
            }
            let (ul, ur) = up(row, col);
            let ends = [at(row, col + 1), at(row + 1, ul), at(row + 1, ur)];
            for (dir, &b) in ends.iter().enumerate() {
                if b != u32::MAX && uses[3 * a as usize + dir] == 1 {
                    outline.push([a, b]);
                    interior[a as usize] = false;
                    interior[b as usize] = false;
                }
            }
        }
    }
    LatticeTriangles { triangles, outline, interior }
}

/// Points of the hexagonal lattice of side `d` inside the counter-clockwise polygon `poly`, at
/// least `0.6 d` from its border.
fn hex_lattice(poly: &[DVec2], d: f64) -> Lattice {
    let n = poly.len();
    let margin = 0.6 * d;
    let (mut lo, mut hi) = (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY));
    for p in poly {
        lo = lo.min(*p);
        hi = hi.max(*p);
    }
    let ext = hi - lo;
    let empty = Lattice { points: Vec::new(), grid: Vec::new(), rows: 0, cols: 0 };
    if !(ext.x > 2.0 * margin && ext.y > 2.0 * margin) || !(d > 0.0) || ext.x / d * ext.y / d > 4e8 {
        return empty;
    }
    // Border edges in a grid of cells of size d, to find the nearby ones.
    let (nx, ny) = ((ext.x / d) as usize + 1, (ext.y / d) as usize + 1);
    let cell = |p: DVec2| (((p.x - lo.x) / d) as usize).min(nx - 1) + nx * (((p.y - lo.y) / d) as usize).min(ny - 1);
    let mut grid: Vec<Vec<u32>> = vec![Vec::new(); nx * ny];
    for i in 0..n {
        let (a, b) = (poly[i], poly[(i + 1) % n]);
        let (cmin, cmax) = (a.min(b), a.max(b));
        let (x0, x1) = (((cmin.x - lo.x) / d) as usize, (((cmax.x - lo.x) / d) as usize).min(nx - 1));
        let (y0, y1) = (((cmin.y - lo.y) / d) as usize, (((cmax.y - lo.y) / d) as usize).min(ny - 1));
        for y in y0..=y1 {
            for x in x0..=x1 {
                grid[x + nx * y].push(i as u32);
            }
        }
    }
    let near_border = |p: DVec2| {
        let c = cell(p);
        let (cx, cy) = (c % nx, c / nx);
        for y in cy.saturating_sub(1)..=(cy + 1).min(ny - 1) {
            for x in cx.saturating_sub(1)..=(cx + 1).min(nx - 1) {
                for &e in &grid[x + nx * y] {
                    let (a, b) = (poly[e as usize], poly[(e as usize + 1) % n]);
                    let ab = b - a;
                    let t = ((p - a).dot(ab) / ab.length_squared().max(f64::MIN_POSITIVE)).clamp(0.0, 1.0);
                    if p.distance(a + ab * t) < margin {
                        return true;
                    }
                }
            }
        }
        false
    };
    let row = 0.5 * 3f64.sqrt() * d;
    let mut out = Vec::new();
    let mut xs = Vec::new();
    let rows = (ext.y / row) as usize + 1;
    let cols = (ext.x / d) as usize + 2;
    let mut grid = vec![u32::MAX; (rows + 1) * cols];
    for k in 0..=rows {
        let y = lo.y + k as f64 * row + 0.5 * (ext.y - rows as f64 * row).max(0.0);
        // Even-odd crossings of the horizontal line with the border.
        xs.clear();
        for i in 0..n {
            let (a, b) = (poly[i], poly[(i + 1) % n]);
            if (a.y > y) != (b.y > y) {
                xs.push(a.x + (y - a.y) / (b.y - a.y) * (b.x - a.x));
            }
        }
        xs.sort_by(f64::total_cmp);
        let shift = if k % 2 == 1 { 0.5 * d } else { 0.0 };
        for pair in xs.chunks(2) {
            let [x0, x1] = [pair[0], *pair.get(1).unwrap_or(&pair[0])];
            let start = ((x0 - lo.x - shift) / d).ceil().max(0.0) as usize;
            let mut col = start;
            let mut x = lo.x + shift + col as f64 * d;
            while x < x1 && col < cols {
                let p = DVec2::new(x, y);
                if x > x0 && !near_border(p) {
                    grid[k * cols + col] = out.len() as u32;
                    out.push(p);
                }
                col += 1;
                x = lo.x + shift + col as f64 * d;
            }
        }
    }
    Lattice { points: out, grid, rows: rows + 1, cols }
}

fn collect(
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
                "{}: the patch is too narrow for the spacing (a triangle would join a vertex to itself); lower the spacing",
                what()
            )));
        }
        triangles.push(r);
        planar.push([pos2[t[0]], pos2[t[1]], pos2[t[2]]]);
    }
    Ok(PatchMesh { new_positions, triangles, planar, fold_fallback: false })
}

fn tessellate_disk(g: &Graph, res: &Resampled, hs: &[HalfEdge], d: f64, index: usize) -> Result<PatchMesh> {
    let what = || format!("patch {index} (bounded by {})", describe_patch(g, hs));
    let ids = loop_vertices(res, hs);
    let p3: Vec<DVec3> = ids.iter().map(|&i| res.positions[i as usize]).collect();
    let center = p3.iter().sum::<DVec3>() / p3.len() as f64;
    // [CG] §3.3: the plane through the mean point with the mean normal. When the normals
    // cancel out (a hemisphere bounded by a great circle) or disagree with the cycle's
    // orientation, the plane of the cycle's vector area is used instead.
    let mean_n = ids.iter().map(|&i| res.normals[i as usize]).sum::<DVec3>() / ids.len() as f64;
    let area_n = polygon_vector_area(&p3).normalize_or_zero();
    let n = if mean_n.length() > 0.1 && mean_n.dot(area_n) > 0.0 { mean_n.normalize() } else { area_n };
    if n == DVec3::ZERO {
        return Err(Error::topology(format!("{}: the cycle encloses no area", what())));
    }
    let map: Vec<VRef> = ids.iter().map(|&i| VRef::Curve(i)).collect();
    let project = |n: DVec3| {
        let (e1, e2) = plane_frame(n);
        let pts: Vec<DVec2> = p3.iter().map(|p| DVec2::new((*p - center).dot(e1), (*p - center).dot(e2))).collect();
        (pts, e1, e2)
    };
    let n3: Vec<DVec3> = ids.iter().map(|&i| res.normals[i as usize]).collect();
    // Corners inside segments (not at nodes, where the cycle turns from one curve to another).
    let mut inner = vec![true; ids.len()];
    let mut k = 0;
    for h in hs {
        if k < inner.len() {
            inner[k] = false;
        }
        k += res.segment_vertices[h.segment].len() - 1;
    }
    let (pts, e1, e2) = project(n);
    let first = match corner_turned(&p3, &n3, &inner, &pts) {
        None => match triangulate(pts, map.clone(), d, &what) {
            Ok((tris, pos2, map)) => return collect(tris, &pos2, &map, |q| center + q.x * e1 + q.y * e2, &what),
            Err(e @ Error::Topology { .. }) => e,
            Err(e) => return Err(e),
        },
        Some(i) => Error::topology(format!(
            "{}: the cycle's corner at {} turns the other way in projection than on the surface (a sharp \
             corner across a crease); the patch cannot be triangulated in a plane",
            what(),
            fmt_point(p3[i])
        )),
    };
    // The projection folds over (the cycle crosses itself or runs clockwise in its plane): a
    // deep or twisted patch ([CG] §3.3 and §5 list it as a limitation). Try the plane of the
    // cycle's vector area, then a convex domain that is always injective.
    if area_n != DVec3::ZERO && area_n.dot(n) < 1.0 - 1e-9 {
        let (pts, e1, e2) = project(area_n);
        if let Some(Ok((tris, pos2, map))) =
            corner_turned(&p3, &n3, &inner, &pts).is_none().then(|| triangulate(pts, map.clone(), d, &what))
        {
            let mut part = collect(tris, &pos2, &map, |q| center + q.x * e1 + q.y * e2, &what)?;
            part.fold_fallback = true;
            return Ok(part);
        }
    }
    let pts = ellipse_domain(&p3, n);
    let (tris, pos2, map) = triangulate(pts, map, d, &what).map_err(|_| first)?;
    // New vertices start at the centroid of the border: the solve needs only their metric.
    let mut part = collect(tris, &pos2, &map, |_| center, &what)?;
    part.fold_fallback = true;
    Ok(part)
}

/// Turning angle (degrees) of a cycle corner above which [`corner_turned`] compares its sign on
/// the surface and in projection.
const CORNER_TURN_DEG: f64 = 20.0;

/// The first corner of the cycle `p3` (normals `n3`) inside a segment (`inner`: a curve's
/// own corner, not a node where the cycle passes from one curve to the next) that turns by more than
/// [`CORNER_TURN_DEG`] one way on the surface (about the curve normal there) and the other
/// way in the planar projection `pts`. Where a curve turns sharply across a crease, the
/// patches on its two sides have planes far apart, and both may see the corner as convex: both
/// triangulations then hold the triangle across the corner (an edge in four triangles). The
/// projection folds over there, as when the cycle crosses itself.
fn corner_turned(p3: &[DVec3], n3: &[DVec3], inner: &[bool], pts: &[DVec2]) -> Option<usize> {
    let m = p3.len();
    let limit = CORNER_TURN_DEG.to_radians();
    (0..m).filter(|&i| inner[i]).find(|&i| {
        let (a, c) = ((i + m - 1) % m, (i + 1) % m);
        let n = n3[i];
        let flat = |v: DVec3| v - n * v.dot(n);
        let (u, v) = (flat(p3[i] - p3[a]), flat(p3[c] - p3[i]));
        let t3 = u.cross(v).dot(n).atan2(u.dot(v));
        let (q, r) = (pts[i] - pts[a], pts[c] - pts[i]);
        let t2 = q.perp_dot(r).atan2(q.dot(r));
        (t3 < -limit && t2 > limit) || (t3 > limit && t2 < -limit)
    })
}

/// A convex domain for a cycle whose planar projection folds over: its vertices `p3` placed
/// counter-clockwise on an ellipse by arc length (chord lengths), the ellipse's axes along the
/// principal directions of the cycle projected on the plane normal to `n`, with their ratio,
/// and its perimeter equal to the cycle's length. A convex border makes the triangulation of
/// the domain (and a Tutte/harmonic map onto it, Floater 1997) injective whatever the shape of
/// the cycle in 3D.
fn ellipse_domain(p3: &[DVec3], n: DVec3) -> Vec<DVec2> {
    let m = p3.len();
    let center = p3.iter().sum::<DVec3>() / m as f64;
    let (e1, e2) = plane_frame(n);
    // 2×2 covariance of the projected cycle and its principal axes.
    let (mut sxx, mut sxy, mut syy) = (0.0, 0.0, 0.0);
    for p in p3 {
        let q = DVec2::new((*p - center).dot(e1), (*p - center).dot(e2));
        sxx += q.x * q.x;
        sxy += q.x * q.y;
        syy += q.y * q.y;
    }
    let tr = sxx + syy;
    let disc = ((sxx - syy).powi(2) + 4.0 * sxy * sxy).sqrt();
    let (l1, l2) = (0.5 * (tr + disc), (0.5 * (tr - disc)).max(0.0));
    // Axis ratio, bounded so that the domain never degenerates into a slit.
    let ratio = if l1 > 0.0 { (l2 / l1).sqrt().clamp(0.2, 1.0) } else { 1.0 };
    let angle = 0.5 * (2.0 * sxy).atan2(sxx - syy);
    let (c, s) = (angle.cos(), angle.sin());
    // Arc-length table of the unit-major ellipse (a = 1, b = ratio).
    const K: usize = 1024;
    let pt = |t: f64| DVec2::new(t.cos(), ratio * t.sin());
    let mut table = vec![0.0; K + 1];
    for k in 0..K {
        let (t0, t1) = (std::f64::consts::TAU * k as f64 / K as f64, std::f64::consts::TAU * (k + 1) as f64 / K as f64);
        table[k + 1] = table[k] + pt(t0).distance(pt(t1));
    }
    let mut cum = vec![0.0; m + 1];
    for i in 0..m {
        cum[i + 1] = cum[i] + p3[i].distance(p3[(i + 1) % m]);
    }
    let scale = cum[m] / table[K];
    (0..m)
        .map(|i| {
            let target = cum[i] / cum[m] * table[K];
            let k = (table.partition_point(|&v| v <= target).clamp(1, K) - 1).min(K - 1);
            let f = ((target - table[k]) / (table[k + 1] - table[k]).max(f64::MIN_POSITIVE)).clamp(0.0, 1.0);
            let t = std::f64::consts::TAU * (k as f64 + f) / K as f64;
            let q = pt(t) * scale;
            DVec2::new(c * q.x - s * q.y, s * q.x + c * q.y)
        })
        .collect()
}

fn tessellate_tube(g: &Graph, res: &Resampled, loops: &[Vec<HalfEdge>; 2], d: f64, index: usize) -> Result<PatchMesh> {
    let all: Vec<HalfEdge> = loops[0].iter().chain(&loops[1]).copied().collect();
    let what = || format!("tube patch {index} (between {})", describe_patch(g, &all));
    let a = loop_vertices(res, &loops[0]);
    let b = loop_vertices(res, &loops[1]);
    let pos = |i: u32| res.positions[i as usize];
    let cum = |ids: &[u32]| {
        let mut c = vec![0.0];
        for k in 0..ids.len() {
            let l = pos(ids[k]).distance(pos(ids[(k + 1) % ids.len()]));
            c.push(c[k] + l);
        }
        c
    };
    let ca = a.iter().map(|&i| pos(i)).sum::<DVec3>() / a.len() as f64;
    let cb = b.iter().map(|&i| pos(i)).sum::<DVec3>() / b.len() as f64;
    let h = ca.distance(cb);
    // Start B at the sample closest to A's first sample, so the seam runs straight across.
    let j0 = (0..b.len())
        .min_by(|&x, &y| pos(b[x]).distance(pos(a[0])).total_cmp(&pos(b[y]).distance(pos(a[0]))))
        .unwrap_or(0);
    let b: Vec<u32> = (0..b.len()).map(|k| b[(j0 + k) % b.len()]).collect();
    let (xa, xb) = (cum(&a), cum(&b));
    let (la, lb) = (xa[a.len()], xb[b.len()]);
    let x_off = 0.5 * (la - lb);
    let m = ((h / d).round() as usize).max(2);
    let mut pts = Vec::new();
    let mut map = Vec::new();
    // Bottom edge: loop A left to right (the tube is on its left, above).
    for (k, &i) in a.iter().enumerate() {
        pts.push(DVec2::new(xa[k], 0.0));
        map.push(VRef::Curve(i));
    }
    pts.push(DVec2::new(la, 0.0));
    map.push(VRef::Curve(a[0]));
    // Right seam, bottom to top; seam vertex k is shared with the left seam.
    for k in 1..m {
        let t = k as f64 / m as f64;
        pts.push(DVec2::new(la, 0.0).lerp(DVec2::new(x_off + lb, h), t));
        map.push(VRef::New((k - 1) as u32));
    }
    // Top edge: loop B right to left (its traversal direction).
    for (k, &i) in b.iter().enumerate() {
        pts.push(DVec2::new(x_off + lb - xb[k], h));
        map.push(VRef::Curve(i));
    }
    pts.push(DVec2::new(x_off, h));
    map.push(VRef::Curve(b[0]));
    // Left seam, top to bottom.
    for k in (1..m).rev() {
        let t = k as f64 / m as f64;
        pts.push(DVec2::new(0.0, 0.0).lerp(DVec2::new(x_off, h), t));
        map.push(VRef::New((k - 1) as u32));
    }
    let (tris, pos2, map) = triangulate(pts, map, d, &what)?;
    // Lift: blend the two loops at the same strip abscissa.
    let at = |ids: &[u32], c: &[f64], x: f64| {
        let l = c[ids.len()];
        let x = x.rem_euclid(l);
        let k = (c.partition_point(|&v| v <= x).max(1) - 1).min(ids.len() - 1);
        let t = ((x - c[k]) / (c[k + 1] - c[k]).max(f64::MIN_POSITIVE)).clamp(0.0, 1.0);
        pos(ids[k]).lerp(pos(ids[(k + 1) % ids.len()]), t)
    };
    let lift = |q: DVec2| {
        let v = (q.y / h).clamp(0.0, 1.0);
        let u = (q.x / la.max(f64::MIN_POSITIVE)).clamp(0.0, 1.0);
        at(&a, &xa, u * la).lerp(at(&b, &xb, lb - u * lb), v)
    };
    collect(tris, &pos2, &map, lift, &what)
}

/// Tessellates every patch at spacing `d` and merges them into one mesh whose first vertices
/// are the curve vertices of `res`.
pub fn tessellate(g: &Graph, res: &Resampled, patches: &[Patch], d: f64) -> Result<Mesh> {
    let parts: Vec<Result<PatchMesh>> = patches
        .par_iter()
        .enumerate()
        .map(|(i, p)| match p {
            Patch::Disk(hs) => tessellate_disk(g, res, hs, d, i),
            Patch::Tube(loops) => tessellate_tube(g, res, loops, d, i),
        })
        .collect();
    merge(res, parts)
}

/// The conformal flattening of one disk patch of a coarse first solution.
#[derive(Clone, Debug)]
pub struct PatchFlattening {
    /// Coarse vertex id → flattened position, scaled so that the border keeps its 3D length.
    uv: std::collections::HashMap<u32, DVec2>,
    /// Area enclosed by the flattened border.
    pub area: f64,
}

/// Flattens every disk patch of `coarse` (a solved mesh over the curve vertices `coarse_res`)
/// by LSCM ([`crate::tessellate::conformal::lscm`]). `None` for tubes and for patches whose flattening
/// fails or folds over (they keep their planar projection).
pub fn flatten_patches(patches: &[Patch], coarse_res: &Resampled, coarse: &Mesh) -> Vec<Option<PatchFlattening>> {
    let mut faces_of: Vec<Vec<[u32; 3]>> = vec![Vec::new(); patches.len()];
    for (f, &p) in coarse.faces.iter().zip(&coarse.face_patch) {
        faces_of[p as usize].push(*f);
    }
    patches
        .par_iter()
        .enumerate()
        .map(|(i, p)| match p {
            Patch::Disk(hs) => flatten_disk(hs, coarse_res, coarse, &faces_of[i]),
            Patch::Tube(_) => None,
        })
        .collect()
}

fn flatten_disk(hs: &[HalfEdge], coarse_res: &Resampled, coarse: &Mesh, faces: &[[u32; 3]]) -> Option<PatchFlattening> {
    // Local numbering of the coarse patch's vertices.
    let mut local = std::collections::HashMap::new();
    let mut global = Vec::new();
    let local_faces: Vec<[u32; 3]> = faces
        .iter()
        .map(|f| {
            f.map(|v| {
                *local.entry(v).or_insert_with(|| {
                    global.push(v);
                    (global.len() - 1) as u32
                })
            })
        })
        .collect();
    let p3: Vec<DVec3> = global.iter().map(|&v| coarse.positions[v as usize]).collect();
    let border = loop_vertices(coarse_res, hs);
    let first = border[0];
    let pos = |v: u32| coarse.positions[v as usize];
    let far = *border.iter().max_by(|a, b| pos(**a).distance(pos(first)).total_cmp(&pos(**b).distance(pos(first))))?;
    let uv =
        crate::tessellate::conformal::lscm(&p3, &local_faces, [*local.get(&first)? as usize, *local.get(&far)? as usize]).ok()?;
    if local_faces.iter().any(|f| {
        let [a, b, c] = f.map(|v| uv[v as usize]);
        !((b - a).perp_dot(c - a) > 0.0)
    }) {
        return None;
    }
    let ring: Vec<DVec2> = border.iter().map(|v| local.get(v).map(|&l| uv[l as usize])).collect::<Option<_>>()?;
    let m = border.len();
    let len3: f64 = (0..m).map(|k| pos(border[k]).distance(pos(border[(k + 1) % m]))).sum();
    let len2: f64 = (0..m).map(|k| ring[k].distance(ring[(k + 1) % m])).sum();
    let scale = len3 / len2;
    let area = polygon_signed_area(&ring) * scale * scale;
    let uv = global.iter().zip(&uv).map(|(&g, q)| (g, *q * scale)).collect();
    Some(PatchFlattening { uv, area })
}

/// Tessellates every patch at spacing `d` over the curve vertices `res`: disk patches with a
/// flattening ([`flatten_patches`]) in it, the others as [`tessellate`] does. The fine curve
/// vertices are placed on the flattened border by arc length along each segment (both
/// resamplings are uniform in arc length). Returns the mesh and the indices of the disk patches
/// kept in their planar projection.
pub fn tessellate_conformal(
    g: &Graph,
    res: &Resampled,
    patches: &[Patch],
    d: f64,
    coarse_res: &Resampled,
    flat: &[Option<PatchFlattening>],
) -> Result<(Mesh, Vec<usize>)> {
    let parts: Vec<(Result<PatchMesh>, bool)> = patches
        .par_iter()
        .enumerate()
        .map(|(i, p)| match (p, &flat[i]) {
            (Patch::Disk(hs), Some(f)) => match conformal_disk(g, res, hs, d, i, coarse_res, f) {
                Some(part) => (part, false),
                None => (tessellate_disk(g, res, hs, d, i), true),
            },
            (Patch::Disk(hs), None) => (tessellate_disk(g, res, hs, d, i), true),
            (Patch::Tube(loops), _) => (tessellate_tube(g, res, loops, d, i), false),
        })
        .collect();
    let kept: Vec<usize> = parts.iter().enumerate().filter(|(_, p)| p.1).map(|(i, _)| i).collect();
    Ok((merge(res, parts.into_iter().map(|p| p.0).collect())?, kept))
}

/// A disk patch triangulated in its flattening; `None` when the border cannot be placed or
/// the triangulation fails (the caller falls back to the planar projection).
fn conformal_disk(
    g: &Graph,
    res: &Resampled,
    hs: &[HalfEdge],
    d: f64,
    index: usize,
    coarse_res: &Resampled,
    flat: &PatchFlattening,
) -> Option<Result<PatchMesh>> {
    let what = || format!("patch {index} (bounded by {})", describe_patch(g, hs));
    let uv_of = |v: u32| flat.uv.get(&v).copied();
    let mut pts = Vec::new();
    for h in hs {
        let (cs, fs) = (&coarse_res.segment_vertices[h.segment], &res.segment_vertices[h.segment]);
        let (mc, mf) = (cs.len() - 1, fs.len() - 1);
        for k in 0..mf {
            let kf = if h.forward { k } else { mf - k };
            let x = kf as f64 * mc as f64 / mf as f64;
            let i0 = (x.floor() as usize).min(mc - 1);
            pts.push(uv_of(cs[i0])?.lerp(uv_of(cs[i0 + 1])?, x - i0 as f64));
        }
    }
    let ids = loop_vertices(res, hs);
    if pts.len() != ids.len() {
        return None;
    }
    let map: Vec<VRef> = ids.iter().map(|&i| VRef::Curve(i)).collect();
    let (tris, pos2, map) = triangulate(pts, map, d, &what).ok()?;
    // New vertices start at the centroid of the border: the solve needs only their metric.
    let centroid = ids.iter().map(|&i| res.positions[i as usize]).sum::<DVec3>() / ids.len() as f64;
    Some(collect(tris, &pos2, &map, |_| centroid, &what))
}

/// Merges per-patch triangulations into one mesh whose first vertices are the curve vertices.
fn merge(res: &Resampled, parts: Vec<Result<PatchMesh>>) -> Result<Mesh> {
    let nc = res.positions.len();
    let mut mesh = Mesh {
        positions: res.positions.clone(),
        faces: Vec::new(),
        num_curve: nc,
        curve_normals: res.normals.clone(),
        on_boundary: res.on_boundary.clone(),
        planar: Vec::new(),
        face_patch: Vec::new(),
        pattern: Default::default(),
        fold_fallback: Vec::new(),
    };
    let parts = parts.into_iter().collect::<Result<Vec<PatchMesh>>>()?;
    let (new, tris) = parts.iter().fold((0, 0), |(v, t), p| (v + p.new_positions.len(), t + p.triangles.len()));
    mesh.positions.reserve_exact(new);
    mesh.faces.reserve_exact(tris);
    mesh.planar.reserve_exact(tris);
    mesh.face_patch.reserve_exact(tris);
    for (pi, part) in parts.into_iter().enumerate() {
        if part.fold_fallback {
            mesh.fold_fallback.push(pi);
        }
        let base = mesh.positions.len() as u32;
        mesh.positions.extend_from_slice(&part.new_positions);
        for (t, q) in part.triangles.iter().zip(part.planar) {
            let id = |r: VRef| match r {
                VRef::Curve(i) => i,
                VRef::New(k) => base + k,
            };
            mesh.faces.push([id(t[0]), id(t[1]), id(t[2])]);
            mesh.planar.push(q);
            mesh.face_patch.push(pi as u32);
        }
    }
    mesh.on_boundary.resize(mesh.positions.len(), false);
    if mesh.positions.len() > u32::MAX as usize {
        return Err(Error::usage("the mesh would exceed 4 billion vertices; increase the spacing"));
    }
    // Every curve vertex must be used by some face (a vertex left out means a broken patch).
    let mut used = vec![false; mesh.positions.len()];
    for f in &mesh.faces {
        for &i in f {
            used[i as usize] = true;
        }
    }
    if let Some(i) = used.iter().position(|u| !u) {
        return Err(Error::topology(format!(
            "vertex {i} at {} is not part of any patch (a curve that bounds no patch?)",
            fmt_point(mesh.positions[i])
        )));
    }
    Ok(mesh)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// An L-shaped cycle in z = 0, counter-clockwise about +z: its corner at (1, 1) turns
    /// right (−90°) on the surface. In its own plane the projection agrees; a projection that
    /// shows that corner turning left (pushed out to (2, 2)) folds there.
    #[test]
    fn a_corner_turning_the_other_way_in_projection_is_a_fold() {
        let l = [(0.0, 0.0), (2.0, 0.0), (2.0, 1.0), (1.0, 1.0), (1.0, 2.0), (0.0, 2.0)];
        let p3: Vec<DVec3> = l.iter().map(|&(x, y)| DVec3::new(x, y, 0.0)).collect();
        let n3 = vec![DVec3::Z; 6];
        let inner = vec![true; 6];
        let same: Vec<DVec2> = l.iter().map(|&(x, y)| DVec2::new(x, y)).collect();
        assert_eq!(corner_turned(&p3, &n3, &inner, &same), None);
        let mut folded = same.clone();
        folded[3] = DVec2::new(2.0, 2.0);
        assert_eq!(corner_turned(&p3, &n3, &inner, &folded), Some(3));
        // At a node (not inner) the corner is not compared.
        let at_nodes = vec![true, true, true, false, true, true];
        assert_eq!(corner_turned(&p3, &n3, &at_nodes, &folded), None);
    }
}
