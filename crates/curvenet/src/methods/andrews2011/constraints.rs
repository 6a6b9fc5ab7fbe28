//! Constraint types on the curves of a network (\[A11\] §4–5) and the `--method cauchy` solve of a
//! network tessellated by the pipeline.
//!
//! The network JSON (docs/design.md §3) gains optional per-curve fields, ignored by the other methods:
//!
//! ```json
//! {"curves": [{"points": [...], "normals": [...],
//!              "kind": "cauchy",          // or "position", "inactive"; default "cauchy"
//!              "sharpness": 45,           // degrees; a number, or one per sample
//!              "stretch": 0.5}]}          // tangent magnitude × (1 + s); a number, or one per sample
//! ```
//!
//! The curve normals are the orientation of the Cauchy constraints (\[A11\] §4.4). Per-sample
//! values are interpolated along the curve onto the resampled curve vertices, so they survive
//! any mesh resolution. Where curves of different kinds meet, the node takes the strongest
//! (cauchy > position > inactive).

use super::params::CauchyParams;
use super::system::{MicroWeight, Role, Stencil, System};
use crate::error::{Error, Result};
use crate::geom::mesh::Mesh;
use crate::geom::DVec3;
use crate::methods::{MethodResult, SurfacingMethod};
use crate::operators::Operators;
use crate::solve::timing::{seconds_since, timed, Instant};
use crate::solve::SolveTimings;
use serde_json::Value;

/// How a curve acts on the surface (\[A11\] §5).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, PartialOrd, Ord)]
pub enum Kind {
    /// Rides on the surface without shaping it (its vertices are free).
    Inactive,
    /// Smooth position constraint: fixed position, Laplacian from the local geometry.
    Position,
    /// Cauchy constraint: position and tangent plane (orientation, sharpness, stretch).
    #[default]
    Cauchy,
}

impl Kind {
    /// The name in the network JSON (`kind`).
    pub fn name(self) -> &'static str {
        match self {
            Kind::Inactive => "inactive",
            Kind::Position => "position",
            Kind::Cauchy => "cauchy",
        }
    }

    /// The kind called `s`.
    pub fn from_name(s: &str) -> Option<Kind> {
        [Kind::Inactive, Kind::Position, Kind::Cauchy].into_iter().find(|k| k.name() == s)
    }

    /// The role of the curve's vertices in the system.
    pub fn role(self) -> Role {
        match self {
            Kind::Inactive => Role::Free,
            Kind::Position => Role::Position,
            Kind::Cauchy => Role::Cauchy,
        }
    }
}

/// The Cauchy attributes of one curve, per sample.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct CurveAttributes {
    /// How the curve acts.
    pub kind: Kind,
    /// Sample positions (to locate the resampled vertices along the curve).
    pub points: Vec<DVec3>,
    /// Whether the curve is closed.
    pub closed: bool,
    /// Sharpness per sample, radians.
    pub sharpness: Vec<f64>,
    /// Stretch per sample, dimensionless (the tangent magnitude is multiplied by `1 + s`).
    pub stretch: Vec<f64>,
}

/// The Cauchy attributes of every curve of a network, in the network's curve order.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct NetworkAttributes {
    /// One per curve.
    pub curves: Vec<CurveAttributes>,
}

fn number_or_list(v: Option<&Value>, n: usize, field: &str, curve: usize, source: &str) -> Result<Vec<f64>> {
    let bad = |what: String| Error::input(format!("{source}: curve {curve}: \"{field}\" {what}"));
    match v {
        None | Some(Value::Null) => Ok(vec![0.0; n]),
        Some(Value::Number(x)) => {
            let x = x.as_f64().filter(|x| x.is_finite()).ok_or_else(|| bad("is not a finite number".into()))?;
            Ok(vec![x; n])
        }
        Some(Value::Array(a)) => {
            if a.len() != n {
                return Err(bad(format!("has {} values for {n} samples", a.len())));
            }
            a.iter()
                .enumerate()
                .map(|(i, x)| {
                    x.as_f64()
                        .filter(|x| x.is_finite())
                        .ok_or_else(|| bad(format!("sample {i} is not a finite number")))
                })
                .collect()
        }
        Some(_) => Err(bad("must be a number or a list of numbers, one per sample".into())),
    }
}

impl NetworkAttributes {
    /// Reads the optional `kind`, `sharpness` (degrees) and `stretch` fields of a network JSON
    /// text. `source` names the file in messages.
    pub fn from_json(text: &str, source: &str) -> Result<Self> {
        let text = text.strip_prefix('\u{feff}').unwrap_or(text);
        let v: Value = serde_json::from_str(text).map_err(|e| Error::Parse {
            path: source.to_string(),
            line: e.line(),
            column: e.column(),
            message: e.to_string(),
        })?;
        let curves = v
            .get("curves")
            .and_then(Value::as_array)
            .ok_or_else(|| Error::input(format!("{source}: no \"curves\" list")))?;
        let mut out = Vec::with_capacity(curves.len());
        for (ci, c) in curves.iter().enumerate() {
            let points: Vec<DVec3> = c
                .get("points")
                .and_then(Value::as_array)
                .map(|a| {
                    a.iter()
                        .filter_map(|p| {
                            let p = p.as_array()?;
                            Some(DVec3::new(p.first()?.as_f64()?, p.get(1)?.as_f64()?, p.get(2)?.as_f64()?))
                        })
                        .collect()
                })
                .unwrap_or_default();
            let n = points.len();
            let kind = match c.get("kind") {
                None | Some(Value::Null) => Kind::Cauchy,
                Some(Value::String(s)) => Kind::from_name(s).ok_or_else(|| {
                    Error::input(format!(
                        "{source}: curve {ci}: unknown \"kind\" \"{s}\" (expected cauchy, position or inactive)"
                    ))
                })?,
                Some(_) => return Err(Error::input(format!("{source}: curve {ci}: \"kind\" must be a string"))),
            };
            let sharpness = number_or_list(c.get("sharpness"), n, "sharpness", ci, source)?;
            if let Some(i) = sharpness.iter().position(|&s| s.abs() > 180.0) {
                return Err(Error::input(format!(
                    "{source}: curve {ci}: \"sharpness\" {}° at sample {i} is not in [-180, 180] degrees",
                    sharpness[i]
                )));
            }
            let sharpness = sharpness.into_iter().map(f64::to_radians).collect();
            let stretch = number_or_list(c.get("stretch"), n, "stretch", ci, source)?;
            if let Some(i) = stretch.iter().position(|&s| s <= -1.0) {
                return Err(Error::input(format!(
                    "{source}: curve {ci}: \"stretch\" {} at sample {i} is ≤ −1 (the tangent would vanish or flip)",
                    stretch[i]
                )));
            }
            let closed = c.get("closed").and_then(Value::as_bool).unwrap_or(false);
            out.push(CurveAttributes { kind, points, closed, sharpness, stretch });
        }
        Ok(NetworkAttributes { curves: out })
    }

    /// Reads the attributes of a network file (JSON only; other formats carry none).
    pub fn read(path: &std::path::Path) -> Result<Option<Self>> {
        if path.extension().and_then(|e| e.to_str()).map(|e| e.eq_ignore_ascii_case("json")) != Some(true) {
            return Ok(None);
        }
        let text = crate::io::read_text(path, crate::io::MAX_INPUT_BYTES)?;
        Ok(Some(Self::from_json(&text, &path.display().to_string())?))
    }
}

/// Where a point lies along the closest curve: `(curve, segment, t, distance²)`.
fn locate(curves: &[(Vec<DVec3>, bool)], p: DVec3) -> Vec<(usize, usize, f64, f64)> {
    curves
        .iter()
        .enumerate()
        .filter_map(|(ci, (pts, closed))| {
            let m = pts.len();
            if m == 0 {
                return None;
            }
            if m == 1 {
                return Some((ci, 0, 0.0, pts[0].distance_squared(p)));
            }
            let segs = if *closed { m } else { m - 1 };
            (0..segs)
                .map(|s| {
                    let (a, b) = (pts[s], pts[(s + 1) % m]);
                    let ab = b - a;
                    let t = ((p - a).dot(ab) / ab.length_squared().max(f64::MIN_POSITIVE)).clamp(0.0, 1.0);
                    (ci, s, t, (a + t * ab).distance_squared(p))
                })
                .min_by(|x, y| x.3.total_cmp(&y.3))
        })
        .collect()
}

/// Roles and Cauchy parameters of the curve vertices `0..mesh.num_curve` of a tessellated
/// network: kinds and values from `attrs` (default: every curve Cauchy, flat, no stretch),
/// orientation from the curve normals, tangents from the input curves. `curves` are the
/// network's curves (points, closed); `snap` decides which curves meet at a vertex.
pub fn curve_constraints(
    mesh: &Mesh,
    curves: &[(Vec<DVec3>, bool)],
    attrs: Option<&NetworkAttributes>,
    snap: f64,
) -> Result<(Vec<Role>, Vec<Option<CauchyParams>>)> {
    let n = mesh.num_vertices();
    let mut roles = vec![Role::Free; n];
    let mut params = vec![None; n];
    if let Some(a) = attrs {
        if a.curves.len() != curves.len() {
            return Err(Error::input(format!(
                "the Cauchy attributes list {} curves, the network {}",
                a.curves.len(),
                curves.len()
            )));
        }
    }
    let located: Vec<Vec<(usize, usize, f64, f64)>> = {
        use rayon::prelude::*;
        let src: Vec<(Vec<DVec3>, bool)> = match attrs {
            Some(a) => a.curves.iter().map(|c| (c.points.clone(), c.closed)).collect(),
            None => curves.to_vec(),
        };
        (0..mesh.num_curve).into_par_iter().map(|u| locate(&src, mesh.positions[u])).collect()
    };
    for u in 0..mesh.num_curve {
        let hits = &located[u];
        let best = hits.iter().map(|h| h.3).fold(f64::INFINITY, f64::min);
        let tol = (best.sqrt() + snap).powi(2);
        let near: Vec<&(usize, usize, f64, f64)> = hits.iter().filter(|h| h.3 <= tol).collect();
        let Some(&&(ci, s, t, _)) = near.iter().min_by(|x, y| x.3.total_cmp(&y.3)) else { continue };
        let kind = match attrs {
            Some(a) => near.iter().map(|h| a.curves[h.0].kind).max().unwrap_or_default(),
            None => Kind::Cauchy,
        };
        roles[u] = kind.role();
        if kind != Kind::Cauchy {
            continue;
        }
        let (sharpness, stretch, pts, _closed) = match attrs {
            Some(a) => {
                let c = &a.curves[ci];
                (&c.sharpness[..], &c.stretch[..], &c.points[..], c.closed)
            }
            None => (&[][..], &[][..], &curves[ci].0[..], curves[ci].1),
        };
        let m = pts.len();
        let s1 = if m > 1 { (s + 1) % m } else { 0 };
        let lerp = |v: &[f64]| if v.is_empty() { 0.0 } else { (1.0 - t) * v[s] + t * v[s1] };
        // Several curves through the vertex: a node, no single tangent (point-type axis).
        let distinct = near.iter().map(|h| h.0).collect::<std::collections::BTreeSet<_>>().len();
        let tangent = (distinct == 1 && m > 1).then(|| (pts[s1] - pts[s]).normalize_or_zero());
        params[u] = Some(CauchyParams {
            orientation: mesh.curve_normals[u],
            initial_normal: None,
            sharpness: lerp(sharpness),
            stretch: lerp(stretch),
            tangent,
        });
    }
    Ok((roles, params))
}

/// The initial-domain edges `u − v` at the Cauchy vertices of a network mesh, mapped into the
/// tangent plane of the orientation: per ghost pair `(u, v)`, the 3D vector and the domain
/// length.
///
/// The patches' domains are planar (`mesh.planar`), the curve vertices exact in 3D. At `u`, for
/// each patch around it, the angle `φ` that turns the domain's directions into the tangent plane
/// `⊥ n` (frame `a`, `n × a`) is the mean over the curve edges `u c` of the patch of the difference
/// between their 3D and domain angles (faces are counter-clockwise in both, so the map keeps
/// orientation). The edge `u − v` is then the domain vector turned by `φ` and set in the
/// tangent plane: the rotation `O` of \[A11\] eq. 3 from the domain normal to the orientation.
pub fn domain_edges(
    mesh: &Mesh,
    roles: &[Role],
    params: &[Option<CauchyParams>],
) -> std::collections::HashMap<(u32, u32), (DVec3, f64)> {
    use crate::geom::DVec2;
    use std::collections::HashMap;
    let nc = mesh.num_curve;
    // Faces around each Cauchy vertex, with the corner index of the vertex.
    let mut around: HashMap<u32, Vec<(usize, usize)>> = HashMap::new();
    for (fi, f) in mesh.faces.iter().enumerate() {
        for (k, &v) in f.iter().enumerate() {
            if roles[v as usize] == Role::Cauchy {
                around.entry(v).or_default().push((fi, k));
            }
        }
    }
    let mut out = HashMap::new();
    for (&u, faces) in &around {
        let Some(p) = params[u as usize] else { continue };
        let n = p.orientation.normalize_or_zero();
        if n == DVec3::ZERO {
            continue;
        }
        let (a, _) = crate::geom::plane_frame(n);
        let b = n.cross(a);
        let pu = mesh.positions[u as usize];
        // Per patch: Σ e^{i(β3 − β2)} over the curve edges.
        let mut rot: HashMap<u32, DVec2> = HashMap::new();
        for &(fi, k) in faces {
            let f = mesh.faces[fi];
            let q = mesh.planar[fi];
            for j in 1..3 {
                let c = f[(k + j) % 3] as usize;
                if c >= nc {
                    continue;
                }
                let d2 = q[(k + j) % 3] - q[k];
                let d3 = mesh.positions[c] - pu;
                let (x3, y3) = (d3.dot(a), d3.dot(b));
                if d2.length() == 0.0 || (x3 == 0.0 && y3 == 0.0) {
                    continue;
                }
                let phi = y3.atan2(x3) - d2.y.atan2(d2.x);
                *rot.entry(mesh.face_patch[fi]).or_insert(DVec2::ZERO) += DVec2::new(phi.cos(), phi.sin());
            }
        }
        for &(fi, k) in faces {
            let f = mesh.faces[fi];
            let q = mesh.planar[fi];
            let Some(r) = rot.get(&mesh.face_patch[fi]).and_then(|r| r.try_normalize()) else { continue };
            for j in 1..3 {
                let v = f[(k + j) % 3];
                if roles[v as usize] == Role::Cauchy || out.contains_key(&(u, v)) {
                    continue;
                }
                let e2 = q[k] - q[(k + j) % 3];
                // Turn by φ: (r.x + i r.y)(e2.x + i e2.y).
                let (x, y) = (r.x * e2.x - r.y * e2.y, r.y * e2.x + r.x * e2.y);
                out.insert((u, v), (x * a + y * b, e2.length()));
            }
        }
    }
    out
}

/// `--method cauchy --order K` on a tessellated network: the order-k system with the curve
/// constraints of [`curve_constraints`], cotangent weights of the patches' planar domains, as a
/// [`SurfacingMethod`]. The system and its LU factorisation depend on the vertex roles and the
/// domain, not on the curve normals (they enter the ghost positions, the right-hand side): a
/// solve with new normals reuses them; new curve positions build a new system (the
/// micro-Laplacians' lengths fall back to the mesh positions where the domain gives none).
pub struct Andrews2011 {
    /// The network's curves (points, closed): where the curve vertices lie on them.
    curves: Vec<(Vec<DVec3>, bool)>,
    /// The user's settings, with the per-curve attributes.
    options: super::CauchyOptions,
    /// Which curves meet at a vertex (the run's snapping tolerance).
    snap: f64,
    /// Roles, domain edge lengths, system and factorisation of the last solve.
    kept: Option<Kept>,
}

struct Kept {
    /// The curve vertices' positions the system was built for.
    curve_positions: Vec<DVec3>,
    roles: Vec<Role>,
    edge_lengths: Vec<((u32, u32), f64)>,
    system: System,
    factored: super::system::Factored,
}

impl Andrews2011 {
    /// The method for the network's `curves`, nothing factorised yet.
    pub fn new(curves: Vec<(Vec<DVec3>, bool)>, options: super::CauchyOptions, snap: f64) -> Self {
        Andrews2011 { curves, options, snap, kept: None }
    }
}

impl SurfacingMethod for Andrews2011 {
    fn name(&self) -> &'static str {
        crate::methods::Method::Cauchy.name()
    }

    fn solve(&mut self, mesh: &Mesh, ops: &Operators, t: &mut SolveTimings) -> Result<MethodResult> {
        let clock = Instant::now();
        let attrs = self.options.attributes.as_deref();
        let (roles, params) = curve_constraints(mesh, &self.curves, attrs, self.snap)?;
        if !roles.iter().any(|r| *r != Role::Free) {
            return Err(Error::input("every curve is inactive: the Cauchy system has no constraint"));
        }
        let edges = domain_edges(mesh, &roles, &params);
        let mut edge_lengths: Vec<((u32, u32), f64)> = edges.iter().map(|(&k, &(_, len))| (k, len)).collect();
        edge_lengths.sort_unstable_by_key(|e| e.0);
        let curve_positions = &mesh.positions[..mesh.num_curve];
        let reuse = self
            .kept
            .take()
            .filter(|k| k.roles == roles && k.edge_lengths == edge_lengths && k.curve_positions == curve_positions);
        let kept = match reuse {
            Some(k) => {
                t.operators += seconds_since(clock);
                k
            }
            None => {
                let mut stencil = Stencil::from_operators(ops, mesh.positions.clone());
                stencil.edge_lengths = edge_lengths.iter().copied().collect();
                let system = System::build(&stencil, &roles, self.options.order, MicroWeight::Consistent)?;
                t.operators += seconds_since(clock);
                let factored = timed(&mut t.factor, || system.factor())?;
                Kept { curve_positions: curve_positions.to_vec(), roles, edge_lengths, system, factored }
            }
        };
        let clock = Instant::now();
        // Ghost offsets O Rᵢ (1 + s) e per ghost line ([A11] eq. 3).
        let offsets: Vec<DVec3> = kept
            .system
            .ghosts
            .iter()
            .map(|g| match (params[g.vertex as usize], edges.get(&(g.vertex, g.source))) {
                (Some(p), Some(&(e, _))) => p.ghost_offset(e),
                _ => mesh.positions[g.vertex as usize] - mesh.positions[g.source as usize],
            })
            .collect();
        t.operators += seconds_since(clock);
        let updates = self.options.ghost_updates;
        let positions =
            timed(&mut t.solve, || kept.system.solve_with_updates(&kept.factored, &mesh.positions, &offsets, updates));
        self.kept = Some(kept);
        Ok(MethodResult { positions: positions?, ..Default::default() })
    }

    fn is_factored(&self) -> bool {
        self.kept.is_some()
    }

    fn release(&mut self) {
        self.kept = None;
    }

    fn set_curves(&mut self, curves: &[(Vec<DVec3>, bool)]) {
        self.curves = curves.to_vec();
        // The curve vertices are located on the attributes' samples when there are attributes:
        // those move too (per-sample values stay with their samples).
        if let Some(a) = &self.options.attributes {
            let mut moved = (**a).clone();
            for (c, (points, _)) in moved.curves.iter_mut().zip(curves) {
                if c.points.len() == points.len() {
                    c.points = points.clone();
                }
            }
            self.options.attributes = Some(std::sync::Arc::new(moved));
        }
        self.kept = None;
    }
}

#[cfg(test)]
#[path = "tests/constraints.rs"]
mod tests;
