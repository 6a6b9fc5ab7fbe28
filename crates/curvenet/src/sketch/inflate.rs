//! Sketch inflation (\[A11\] §5): the outlines of an SVG sketch are sampled, the region inside
//! the outermost closed outline triangulated (constrained Delaunay with quality refinement,
//! spade — \[A11\] used Triangle), and inflated by the order-k system with Cauchy constraints on
//! the outline.
//!
//! - **Outline** (the closed path of largest area; every other path must lie inside it): Cauchy
//!   constraints whose orientation is the sketch normal `+z` tilted outwards by `angle`
//!   (default 90°: a balloon whose rim leaves the plane vertically), with the sketch plane as
//!   the initial domain (`O` of \[A11\] eq. 3 rotates `+z` onto the orientation).
//! - **Inner paths**: inactive constraints by default (they ride on the inflated surface,
//!   \[A11\] §5.1). A path with `class="crease"` (or `data-kind="crease"`) is then *activated*:
//!   fixed where the inflated surface carried it, oriented by that surface's normal, with the
//!   sharpness `data-sharpness` (degrees; default [`InflateOptions::crease_sharpness`]; > 0 a
//!   ridge, < 0 a valley), and the surface solved again — the workflow of \[A11\] Fig. 5.

use super::svg::SketchPath;
use crate::error::{Error, Result};
use crate::geom::mesh::Mesh;
use crate::geom::{polygon_signed_area, DVec2, DVec3};
use crate::methods::andrews2011::params::CauchyParams;
use crate::methods::andrews2011::system::{MicroWeight, Role, Stencil, System};
use crate::operators::{cotan_operators, vertex_normals, Metric};
use spade::{AngleLimit, ConstrainedDelaunayTriangulation, Point2, RefinementParameters, Triangulation};

/// Options of [`inflate`] (one per `curvenet inflate` flag).
#[derive(Clone, Debug, PartialEq)]
pub struct InflateOptions {
    /// Laplacian order `k` (1–3). Default 2 (\[A11\] §5 used `k = 2`).
    pub order: usize,
    /// Tilt of the outline's orientation out of the sketch plane, degrees (90: vertical rim).
    pub angle: f64,
    /// Stretch of the outline's constraints (dimensionless: the rim's tangent magnitude is
    /// multiplied by `1 + stretch`).
    pub stretch: f64,
    /// Sharpness of crease paths without `data-sharpness`, degrees.
    pub crease_sharpness: f64,
    /// Approximate number of vertices.
    pub vertices: usize,
    /// Re-solves with centred ghosts (see [`System::solve_with_updates`]).
    pub ghost_updates: usize,
}

impl Default for InflateOptions {
    fn default() -> Self {
        InflateOptions {
            order: 2,
            angle: 90.0,
            stretch: 0.0,
            crease_sharpness: 30.0,
            vertices: 5000,
            ghost_updates: 10,
        }
    }
}

/// An inflated sketch.
#[derive(Clone, Debug)]
pub struct Inflated {
    /// Vertex positions: x, y in the sketch's user units (y up, as [`SketchPath::points`]), z the
    /// height above the sketch plane.
    pub positions: Vec<DVec3>,
    /// Triangles, counter-clockwise seen from above.
    pub faces: Vec<[u32; 3]>,
    /// Per vertex: on a sketch path.
    pub on_path: Vec<bool>,
    /// Height of the surface above the sketch plane (max z).
    pub height: f64,
    /// Radius of the circle with the outline's area, `√(A/π)`.
    pub radius: f64,
    /// Number of crease paths activated.
    pub creases: usize,
}

#[derive(Clone, Copy, PartialEq, Eq, Debug)]
enum PathKind {
    Outline,
    Inactive,
    Crease,
}

fn point_in_polygon(p: DVec2, poly: &[DVec2]) -> bool {
    let mut inside = false;
    let n = poly.len();
    for i in 0..n {
        let (a, b) = (poly[i], poly[(i + 1) % n]);
        if (a.y > p.y) != (b.y > p.y) && p.x < a.x + (p.y - a.y) / (b.y - a.y) * (b.x - a.x) {
            inside = !inside;
        }
    }
    inside
}

/// Resamples a polyline at about `d` (uniform in arc length; closed lines wrap).
fn resample(points: &[DVec2], closed: bool, d: f64) -> Vec<DVec2> {
    let mut pts = points.to_vec();
    if closed {
        pts.push(points[0]);
    }
    let acc = crate::geom::polyline::arc_lengths(&pts, |a, b| a.distance(*b));
    let total = acc[acc.len() - 1];
    let n = ((total / d).round() as usize).max(if closed { 3 } else { 1 });
    let count = if closed { n } else { n + 1 };
    (0..count)
        .map(|k| {
            let s = total * k as f64 / n as f64;
            let (i, t) = crate::geom::polyline::locate(&acc, s);
            pts[i].lerp(pts[i + 1], t)
        })
        .collect()
}

/// Inflates a sketch's outlines (see the module docs).
pub fn inflate(paths: &[SketchPath], o: &InflateOptions) -> Result<Inflated> {
    check_options(o)?;
    let outline = find_outline(paths)?;
    let kinds = classify(paths, outline.index);
    check_inside(paths, &outline)?;
    // Spacing for about `vertices` vertices.
    let d = (crate::tessellate::VERTICES_PER_AREA * outline.area / o.vertices as f64).sqrt();
    check_not_sliver(paths, &outline, d, o.vertices)?;
    let (mut cdt, sampled) = insert_paths(paths, &outline, &kinds, d, o.crease_sharpness)?;
    refine(&mut cdt, outline.area, d)?;
    let planar = inner_triangles(&cdt, &outline.points);
    let mesh = planar.mesh();
    let positions = mesh.positions.clone();
    let ops = cotan_operators(&mesh, Metric::Planar, &mesh.positions);
    let stencil = Stencil::from_operators(&ops, positions.clone());
    let mut constraints = outline_constraints(&sampled, &planar.index, &positions, o);
    let mut result = solve(&stencil, &positions, &constraints, &positions, o)?;
    // Activate the creases on the inflated surface (\[A11\] §5.1).
    let creases = activate_creases(&sampled, &planar.index, &mesh.faces, &result, &mut constraints);
    if creases > 0 {
        result = solve(&stencil, &positions, &constraints, &result, o)?;
    }
    let height = result.iter().map(|p| p.z).fold(f64::NEG_INFINITY, f64::max);
    Ok(Inflated {
        positions: result,
        faces: mesh.faces,
        on_path: constraints.on_path,
        height,
        radius: (outline.area / std::f64::consts::PI).sqrt(),
        creases,
    })
}

/// Usage errors: an order other than 1–3, an angle outside ±180°, fewer than 50 vertices.
/// The most vertices [`inflate`] takes: 2·10⁵ (about 3 GB and 20 s; its dense ghost systems
/// take about 14 kB per vertex, measured at 2·10⁴–10⁵ vertices).
pub const MAX_INFLATE_VERTICES: usize = 200_000;

/// Peak bytes per vertex of an inflation (see [`MAX_INFLATE_VERTICES`]).
const INFLATE_BYTES_PER_VERTEX: f64 = 15_000.0;

/// The most ghost updates [`inflate`] takes ([`InflateOptions::ghost_updates`]).
pub const MAX_GHOST_UPDATES: usize = 1000;

fn check_options(o: &InflateOptions) -> Result<()> {
    if !(1..=3).contains(&o.order) {
        return Err(Error::usage(format!("order {} is not 1, 2 or 3", o.order)));
    }
    if !(o.angle.is_finite() && o.angle.abs() <= 180.0) {
        return Err(Error::usage(format!("angle {} is not in [-180, 180] degrees", o.angle)));
    }
    if o.vertices < 50 {
        return Err(Error::usage(format!("{} vertices is too few (at least 50)", o.vertices)));
    }
    if o.vertices > MAX_INFLATE_VERTICES {
        return Err(Error::usage(format!(
            "{} vertices is more than the {MAX_INFLATE_VERTICES} an inflation takes (its dense ghost systems take \
             about 15 kB per vertex)",
            o.vertices
        )));
    }
    let need = 100e6 + INFLATE_BYTES_PER_VERTEX * o.vertices as f64;
    if let Some(have) = crate::solve::memory::available_memory(None).filter(|&have| need > have) {
        return Err(Error::memory(format!(
            "{} vertices would take about {:.2} GB, more than the memory available ({:.2} GB); give at most about {:.0} \
             `vertices`",
            o.vertices,
            need / 1e9,
            have / 1e9,
            (0.9 * (have - 100e6).max(0.0) / INFLATE_BYTES_PER_VERTEX / 1000.0).floor() * 1000.0
        )));
    }
    if !(o.stretch.is_finite() && o.stretch > -1.0) {
        return Err(Error::usage(format!("`stretch` {} is not a number above -1", o.stretch)));
    }
    if !(o.crease_sharpness.is_finite() && o.crease_sharpness.abs() <= 180.0) {
        return Err(Error::usage(format!("`crease_sharpness` {} is not in [-180, 180] degrees", o.crease_sharpness)));
    }
    if o.ghost_updates > MAX_GHOST_UPDATES {
        return Err(Error::usage(format!(
            "`ghost_updates` {} is more than {MAX_GHOST_UPDATES} (the updates converge within a few dozen)",
            o.ghost_updates
        )));
    }
    Ok(())
}

/// The outline of a sketch: which path, its points counter-clockwise, its area.
struct Outline {
    index: usize,
    points: Vec<DVec2>,
    area: f64,
}

/// The outline: the closed path of largest area, made counter-clockwise.
fn find_outline(paths: &[SketchPath]) -> Result<Outline> {
    let index = paths
        .iter()
        .enumerate()
        .filter(|(_, p)| p.closed && p.points.len() >= 3)
        .max_by(|a, b| polygon_signed_area(&a.1.points).abs().total_cmp(&polygon_signed_area(&b.1.points).abs()))
        .map(|(i, _)| i)
        .ok_or_else(|| Error::input("the sketch has no closed path to bound the surface"))?;
    let mut points = paths[index].points.clone();
    if polygon_signed_area(&points) < 0.0 {
        points.reverse();
    }
    let area = polygon_signed_area(&points);
    if area.is_nan() || area <= 0.0 {
        return Err(Error::input(format!("line {}: the outline encloses no area", paths[index].line)));
    }
    Ok(Outline { index, points, area })
}

/// What each path becomes: the outline, a crease (`class="crease"` or `data-kind="crease"`),
/// or an inactive curve.
fn classify(paths: &[SketchPath], outline: usize) -> Vec<PathKind> {
    paths
        .iter()
        .enumerate()
        .map(|(i, p)| {
            if i == outline {
                PathKind::Outline
            } else if p.kind.as_deref() == Some("crease") || p.class.split_whitespace().any(|c| c == "crease") {
                PathKind::Crease
            } else {
                PathKind::Inactive
            }
        })
        .collect()
}

/// An input error for the first path with a point outside the outline.
fn check_inside(paths: &[SketchPath], outline: &Outline) -> Result<()> {
    for (i, p) in paths.iter().enumerate() {
        if i != outline.index && p.points.iter().any(|&q| !point_in_polygon(q, &outline.points)) {
            return Err(Error::input(format!(
                "line {}: a path leaves the outline (line {}); every path must lie inside the closed outline",
                p.line, paths[outline.index].line
            )));
        }
    }
    Ok(())
}

type Cdt = ConstrainedDelaunayTriangulation<Point2<f64>>;

/// A path resampled into the triangulation: its vertices, in order along it.
struct Sampled {
    kind: PathKind,
    handles: Vec<spade::handles::FixedVertexHandle>,
    closed: bool,
    /// Sharpness of a crease, degrees.
    sharpness: f64,
}

/// Resamples every path at the spacing `d` into a constrained Delaunay triangulation, the
/// outline first, then the others in order; each path's chords become constraint edges. An
/// open path's end within half a spacing of an earlier path's sample is snapped onto it, so
/// that touching paths share the vertex (a vertex inside a constraint edge would split it
/// behind our back). Paths that cross are an input error.
fn insert_paths(
    paths: &[SketchPath],
    outline: &Outline,
    kinds: &[PathKind],
    d: f64,
    crease_sharpness: f64,
) -> Result<(Cdt, Vec<Sampled>)> {
    let mut cdt = Cdt::new();
    let mut sampled: Vec<Sampled> = Vec::new();
    let mut order: Vec<usize> = (0..paths.len()).collect();
    order.sort_by_key(|&i| (i != outline.index, i));
    let mut placed: Vec<DVec2> = Vec::new();
    for i in order {
        let p = &paths[i];
        let pts = if i == outline.index { outline.points.clone() } else { p.points.clone() };
        let mut r = resample(&pts, p.closed, d);
        if !p.closed {
            let last = r.len() - 1;
            for k in [0, last] {
                if let Some(q) = placed.iter().copied().min_by(|a, b| a.distance(r[k]).total_cmp(&b.distance(r[k]))) {
                    if q.distance(r[k]) < 0.5 * d {
                        r[k] = q;
                    }
                }
            }
        }
        placed.extend_from_slice(&r);
        let handles: Vec<_> = r
            .iter()
            .map(|q| cdt.insert(Point2::new(q.x, q.y)))
            .collect::<std::result::Result<_, _>>()
            .map_err(|e| Error::input(format!("line {}: a point cannot be triangulated ({e:?})", p.line)))?;
        let m = handles.len();
        let edges = if p.closed { m } else { m - 1 };
        for k in 0..edges {
            let (a, b) = (handles[k], handles[(k + 1) % m]);
            if a == b {
                continue;
            }
            if !cdt.can_add_constraint(a, b) {
                return Err(Error::input(format!(
                    "line {}: the path crosses another path; paths may only touch at their samples",
                    p.line
                )));
            }
            cdt.add_constraint(a, b);
        }
        let sharpness = p.sharpness.unwrap_or(crease_sharpness);
        sampled.push(Sampled { kind: kinds[i], handles, closed: p.closed, sharpness });
    }
    Ok((cdt, sampled))
}

/// A sliver outline (an ellipse with `ry = 1e-4`) has almost no area for its length: at the
/// spacing `d` its area gives, its paths would take more samples than the `vertices` asked
/// for the whole sketch (a circle's outline takes √(2π · vertices)), and the triangulation's
/// refinement between them would run for minutes. An input error naming the outline's mean
/// width (2 × area / perimeter).
fn check_not_sliver(paths: &[SketchPath], outline: &Outline, d: f64, vertices: usize) -> Result<()> {
    let length = |pts: &[DVec2], closed: bool| {
        let open: f64 = pts.windows(2).map(|w| w[0].distance(w[1])).sum();
        let close = match (closed, pts.first(), pts.last()) {
            (true, Some(a), Some(b)) => a.distance(*b),
            _ => 0.0,
        };
        open + close
    };
    let total: f64 = paths
        .iter()
        .enumerate()
        .map(|(i, p)| if i == outline.index { length(&outline.points, true) } else { length(&p.points, p.closed) })
        .sum();
    let samples = total / d;
    if !(samples <= 0.5 * vertices as f64) {
        let perimeter = length(&outline.points, true);
        return Err(Error::input(format!(
            "line {}: the outline is a sliver (area {:.3e}, perimeter {:.3e}: mean width {:.3e}); its paths would take {:.0} \
             samples for {vertices} vertices; draw it wider",
            paths[outline.index].line,
            outline.area,
            perimeter,
            2.0 * outline.area / perimeter,
            samples.min(1e18)
        )));
    }
    Ok(())
}

/// Refines the triangulation (angles ≥ 25°, areas ≤ 0.69 d², the constraint edges kept);
/// a numerical error when that takes too many new vertices for the outline's `area`.
fn refine(cdt: &mut Cdt, area: f64, d: f64) -> Result<()> {
    let expected = (4.0 * area / (0.69 * d * d)) as usize + 10_000;
    let result = cdt.refine(
        RefinementParameters::<f64>::new()
            .with_angle_limit(AngleLimit::from_deg(25.0))
            .with_max_allowed_area(0.69 * d * d)
            .keep_constraint_edges()
            .with_max_additional_vertices(expected),
    );
    if !result.refinement_complete {
        return Err(Error::numerical(format!(
            "the sketch's triangulation did not finish within {expected} new vertices"
        )));
    }
    Ok(())
}

/// The triangles of the triangulation inside the outline, their vertices renumbered.
struct Planar {
    /// Per triangulation vertex: its number, `u32::MAX` outside the outline.
    index: Vec<u32>,
    /// Per vertex: its position in the sketch plane.
    pos2: Vec<DVec2>,
    faces: Vec<[u32; 3]>,
}

/// The faces of `cdt` whose centroid lies inside `outer`, vertices numbered in the order the
/// faces meet them.
fn inner_triangles(cdt: &Cdt, outer: &[DVec2]) -> Planar {
    let mut index = vec![u32::MAX; cdt.num_vertices()];
    let mut pos2: Vec<DVec2> = Vec::new();
    let mut faces: Vec<[u32; 3]> = Vec::new();
    for f in cdt.inner_faces() {
        let vs = f.vertices();
        let p: Vec<DVec2> = vs.iter().map(|v| DVec2::new(v.position().x, v.position().y)).collect();
        if !point_in_polygon((p[0] + p[1] + p[2]) / 3.0, outer) {
            continue;
        }
        let mut tri = [0u32; 3];
        for k in 0..3 {
            let h = vs[k].fix().index();
            if index[h] == u32::MAX {
                index[h] = pos2.len() as u32;
                pos2.push(p[k]);
            }
            tri[k] = index[h];
        }
        faces.push(tri);
    }
    Planar { index, pos2, faces }
}

impl Planar {
    /// The flat mesh (z = 0), one patch, its own planar domain.
    fn mesh(&self) -> Mesh {
        let (pos2, faces) = (&self.pos2, &self.faces);
        let n = pos2.len();
        Mesh {
            positions: pos2.iter().map(|q| DVec3::new(q.x, q.y, 0.0)).collect(),
            planar: faces.iter().map(|f| [pos2[f[0] as usize], pos2[f[1] as usize], pos2[f[2] as usize]]).collect(),
            face_patch: vec![0; faces.len()],
            on_boundary: vec![false; n],
            faces: faces.clone(),
            num_curve: 0,
            curve_normals: Vec::new(),
            ..Default::default()
        }
    }
}

/// Per vertex: its role in the system, its Cauchy constraint, whether it lies on a path.
struct Constraints {
    roles: Vec<Role>,
    params: Vec<Option<CauchyParams>>,
    on_path: Vec<bool>,
}

/// The outline's Cauchy constraints (orientation `+z` tilted outwards by `angle`, the sketch
/// plane as the initial normal, `stretch`) and the vertices on paths; every other vertex free.
fn outline_constraints(sampled: &[Sampled], index: &[u32], positions: &[DVec3], o: &InflateOptions) -> Constraints {
    let n = positions.len();
    let mut c = Constraints { roles: vec![Role::Free; n], params: vec![None; n], on_path: vec![false; n] };
    let angle = o.angle.to_radians();
    for s in sampled {
        let ids: Vec<u32> = s.handles.iter().map(|h| index[h.index()]).collect();
        let m = ids.len();
        for (k, &id) in ids.iter().enumerate() {
            if id == u32::MAX {
                continue;
            }
            c.on_path[id as usize] = true;
            if s.kind != PathKind::Outline {
                continue;
            }
            let prev = ids[(k + m - 1) % m];
            let next = ids[(k + 1) % m];
            if prev == u32::MAX || next == u32::MAX || !s.closed {
                continue;
            }
            let t = (positions[next as usize] - positions[prev as usize]).normalize_or_zero();
            // Counter-clockwise outline: outwards is the tangent turned clockwise.
            let out = DVec3::new(t.y, -t.x, 0.0);
            c.roles[id as usize] = Role::Cauchy;
            c.params[id as usize] = Some(CauchyParams {
                orientation: angle.cos() * DVec3::Z + angle.sin() * out,
                initial_normal: Some(DVec3::Z),
                sharpness: 0.0,
                stretch: o.stretch,
                tangent: Some(t),
            });
        }
    }
    c
}

/// Solves the order-k system for the constraints, `fixed` giving the constrained positions;
/// the ghost offsets come from the planar `positions`.
fn solve(
    stencil: &Stencil,
    positions: &[DVec3],
    c: &Constraints,
    fixed: &[DVec3],
    o: &InflateOptions,
) -> Result<Vec<DVec3>> {
    let system = System::build(stencil, &c.roles, o.order, MicroWeight::Consistent)?;
    let offsets: Vec<DVec3> = system
        .ghosts
        .iter()
        .map(|g| {
            let e = positions[g.vertex as usize] - positions[g.source as usize];
            c.params[g.vertex as usize].map_or(e, |p| p.ghost_offset(e))
        })
        .collect();
    let f = system.factor()?;
    system.solve_with_updates(&f, fixed, &offsets, o.ghost_updates)
}

/// Activates the crease paths on the inflated surface `result` (\[A11\] §5.1): each crease
/// vertex not already constrained is fixed where it is, oriented by the surface's normal there,
/// with the path's sharpness. Returns the number of crease paths.
fn activate_creases(
    sampled: &[Sampled],
    index: &[u32],
    faces: &[[u32; 3]],
    result: &[DVec3],
    c: &mut Constraints,
) -> usize {
    if !sampled.iter().any(|s| s.kind == PathKind::Crease) {
        return 0;
    }
    let normals = vertex_normals(faces, result);
    let mut creases = 0;
    for s in sampled.iter().filter(|s| s.kind == PathKind::Crease) {
        creases += 1;
        let ids: Vec<u32> = s.handles.iter().map(|h| index[h.index()]).collect();
        let m = ids.len();
        for (k, &id) in ids.iter().enumerate() {
            if id == u32::MAX || c.roles[id as usize] == Role::Cauchy {
                continue;
            }
            let a = if k > 0 || s.closed { ids[(k + m - 1) % m] } else { id };
            let b = if k + 1 < m || s.closed { ids[(k + 1) % m] } else { id };
            let t = (result[b as usize] - result[a as usize]).normalize_or_zero();
            c.roles[id as usize] = Role::Cauchy;
            c.params[id as usize] = Some(CauchyParams {
                orientation: normals[id as usize],
                initial_normal: Some(DVec3::Z),
                sharpness: s.sharpness.to_radians(),
                stretch: 0.0,
                tangent: Some(t),
            });
        }
    }
    creases
}

/// Largest sketch file [`read_sketch`] reads, bytes.
pub const MAX_SKETCH_BYTES: u64 = 64 << 20;

/// Reads the outlines of an SVG file, flattened to chords of 1/1000 of the sketch's size
/// ([`super::svg::read_svg`]). Files larger than [`MAX_SKETCH_BYTES`] are an input error, text
/// that is not UTF-8 a parse error at the first bad byte.
pub fn read_sketch(path: &std::path::Path) -> Result<Vec<SketchPath>> {
    let source = path.display().to_string();
    let bytes = crate::io::read_input(path, crate::io::InputKind::Text, MAX_SKETCH_BYTES)?;
    let text = String::from_utf8(bytes).map_err(|e| {
        let valid = &e.as_bytes()[..e.utf8_error().valid_up_to()];
        let line_start = valid.iter().rposition(|&b| b == b'\n').map_or(0, |i| i + 1);
        let line = 1 + valid.iter().filter(|&&b| b == b'\n').count();
        let column = 1 + String::from_utf8_lossy(&valid[line_start..]).chars().count();
        Error::parse(&source, line, column, "the file is not valid UTF-8 text")
    })?;
    // A coarse pass for the size, then the flattening at a chord relative to it.
    let coarse = super::svg::read_svg(&text, &source, f64::INFINITY)?;
    let bb = crate::geom::Aabb::of(coarse.iter().flat_map(|p| p.points.iter().map(|q| DVec3::new(q.x, q.y, 0.0))));
    let size = bb.diagonal();
    if !(size > 0.0 && size.is_finite()) {
        return Err(Error::input(format!("{source}: the sketch has no extent")));
    }
    super::svg::read_svg(&text, &source, size / 1000.0)
}
