//! The whole pipeline, network in, surface out ([CG] §3.1; docs/design.md §1): validate, find nodes,
//! fit splines, trace the cycles, pick the spacing, resample, tessellate, solve.

pub mod surfacer;

use crate::solve::timing::Instant;
use crate::curves::CurveSpline;
use crate::topology::resample::{resample_network, Resampled};
use crate::error::{Error, Result, Warning};
use crate::geom::DVec3;
use crate::io::MeshData;
use crate::geom::mesh::Mesh;
use crate::methods::iterated::{iterate, IterationParams, Stop};
use crate::methods::method4::method4;
use crate::methods::normal_control::{normal_control, normal_control_cached, Factors, NormalControlParams};
use crate::methods::polyharmonic::polyharmonic;
use crate::methods::eg2016::{short_paper, ShortPaperParams};
use crate::methods::{GuideArea, Method, SolveTimings, Weighting};
use crate::network::Network;
use crate::operators::{cotan_operators, normals_and_mean_curvature, Metric};
use crate::tessellate::{flatten_patches, tessellate, tessellate_conformal, VERTICES_PER_AREA};
use crate::topology::cycles::find_patches_open;
use crate::topology::cycles::half_edge_samples;
use crate::topology::{find_nodes, trim_dangling, Graph, Patch};
use rayon::prelude::*;
use serde::Serialize;
use std::borrow::Cow;

/// Options of a surfacing run. Each field maps one-to-one onto a command-line flag.
#[derive(Clone, Debug, PartialEq)]
pub struct Options {
    /// `--method`: the surfacing method. Default: [`Method::NormalControl`].
    pub method: Method,
    /// `--spacing D`: target edge length `d` of the mesh (and curve sampling distance).
    /// Overrides `vertices`.
    pub spacing: Option<f64>,
    /// `--vertices N`: approximate total vertex count, used when `spacing` is not given.
    /// Default: [`Options::DEFAULT_VERTICES`].
    pub vertices: Option<usize>,
    /// `--w1 W`: weight of the curvature guide in the short paper's energy (`--method
    /// short-paper`), dimensionless: `ω₁ = W / s⁴` with `s` the mean patch size.
    pub w1: f64,
    /// `--soft S`: soft curve constraints ([CG] §4.5) instead of hard ones: the surface may
    /// leave the curves to smooth out deviations shorter than about `S` input sample spacings
    /// (`S ≈ 1–3` for sensor noise; 0 would be hard). With the iterations, the curve normals are
    /// soft too. The penalty is `ω Σ_s ‖v_s − v*_s‖²` with `ω = d / λ³`, `λ = S h`, `d` the
    /// spacing and `h` the mean input sample spacing: a deviation of wavelength `λ` costs as
    /// much in the penalty as in the fit energy, independently of scale and resolution.
    /// normal-control and short-paper only.
    pub soft: Option<f64>,
    /// `--patching`: the domain each patch is triangulated in: its planar projection
    /// ([CG] §3.3) or a conformal flattening of a first solution (then solved again).
    pub patching: Patching,
    /// `--iterations K`: iterations of the normal-control fit with operators rebuilt on the 3D
    /// surface ([`crate::methods::iterated`]); 0 keeps the weights of the patches' domains. The
    /// baselines always keep those. Default: [`Options::DEFAULT_ITERATIONS`].
    pub iterations: usize,
    /// `--inner-steps N`: per iteration, repeats of the normal pull and the fit on the same
    /// operators (triangular solves only). Default [`Options::DEFAULT_INNER_STEPS`].
    pub inner_steps: usize,
    /// `--tolerance T`: the iteration stops when no vertex moves more than `T × spacing`.
    pub tolerance: f64,
    /// `--normal-prior S`: scale of the iterated method's pull of the propagated normals towards
    /// the current surface's, as a fraction of the mean patch size (0 disables it).
    pub normal_prior: f64,
    /// `--energy`: weighting of the normal-control energy (docs/design.md §1). Default: area.
    pub energy: Weighting,
    /// `--guide-area`: the area dividing the mean-curvature guide ([CG] eq. 1): the
    /// Laplacian's own (default, consistent with the fit) or that of the propagated surface
    /// (the paper's wording).
    pub guide_area: GuideArea,
    /// `--guide-updates K`: how many times the mean-curvature guide is re-estimated on the
    /// fitted surface and the fit repeated (same factorisation; 0 is the paper). Default 1.
    pub guide_updates: usize,
    /// `--snap S`: snapping tolerance for curves meeting between samples; overrides the
    /// network's `snap`. Default: 1e-3 × the bounding-box diagonal.
    pub snap: Option<f64>,
    /// `--order K`: the Laplacian order of `--method cauchy` ([A11] eq. 1), 1–3. Default 2.
    pub order: usize,
    /// Per-curve `kind`, `sharpness`, `stretch` of `--method cauchy` (read from the network
    /// JSON by [`crate::methods::andrews2011::NetworkAttributes::read`]); `None`: every curve a flat Cauchy
    /// constraint oriented by its normals.
    pub cauchy: Option<std::sync::Arc<crate::methods::andrews2011::NetworkAttributes>>,
    /// `--ghost-updates N`: re-solves of `--method cauchy` with centred ghosts (see
    /// [`crate::methods::andrews2011::constraints::solve_network`]; 0: the paper's ghosts). Default 10.
    pub ghost_updates: usize,
}

impl Options {
    /// Default approximate vertex count.
    pub const DEFAULT_VERTICES: usize = 20_000;
    /// Default `w1`.
    pub const DEFAULT_W1: f64 = 1e6;
    /// Default `iterations`.
    pub const DEFAULT_ITERATIONS: usize = 2;
    /// Default `inner_steps`.
    pub const DEFAULT_INNER_STEPS: usize = 4;
    /// Default `tolerance` (relative to the spacing).
    pub const DEFAULT_TOLERANCE: f64 = 3e-3;
    /// Default `normal_prior`.
    pub const DEFAULT_NORMAL_PRIOR: f64 = 0.16;
    /// Largest mesh a run may create (a guard against a mistyped spacing).
    pub const MAX_VERTICES: f64 = 5e7;
}

impl Options {
    /// The method as the paper describes it ([CG] §3): planar projections and planar weights,
    /// the unweighted energy of eq. 2, eq. 1 divided by the area on `V*`, no guide update, no
    /// iteration. A faithful implementation measured 0.0085 mean distance on the sphere.
    pub fn paper() -> Self {
        Options {
            patching: Patching::Planar,
            iterations: 0,
            energy: Weighting::Uniform,
            guide_area: GuideArea::Surface,
            guide_updates: 0,
            ..Options::default()
        }
    }
}

impl Options {
    /// The fast single pass: the paper's planar patching and weights with the consistent guide
    /// and one guide update (one factorisation; sphere 1e-3, torus 0.2 mean error at 20k
    /// vertices — the default is 4× (sphere) to 80× (torus) more accurate for 2–3× the time).
    pub fn fast() -> Self {
        Options { patching: Patching::Planar, iterations: 0, ..Options::default() }
    }
}

impl Default for Options {
    fn default() -> Self {
        Options {
            method: Method::NormalControl,
            spacing: None,
            vertices: None,
            soft: None,
            w1: Options::DEFAULT_W1,
            patching: Patching::Conformal,
            iterations: Options::DEFAULT_ITERATIONS,
            inner_steps: Options::DEFAULT_INNER_STEPS,
            tolerance: Options::DEFAULT_TOLERANCE,
            normal_prior: Options::DEFAULT_NORMAL_PRIOR,
            energy: Weighting::Area,
            guide_area: GuideArea::Mass,
            guide_updates: 1,
            snap: None,
            order: 2,
            cauchy: None,
            ghost_updates: 10,
        }
    }
}

/// The domain each patch is triangulated in.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Patching {
    /// The plane of the cycle's mean point and mean normal ([CG] §3.3).
    #[default]
    Planar,
    /// A conformal flattening (LSCM) of the patch on a first solution: triangles keep their
    /// shape on the surface and the "planar" cotangent weights are nearly the surface's.
    Conformal,
}

impl Patching {
    pub fn name(self) -> &'static str {
        match self {
            Patching::Planar => "planar",
            Patching::Conformal => "conformal",
        }
    }
}

/// Seconds per stage (docs/design.md §5; the names are stable: benchmarks read them).
#[derive(Clone, Copy, Debug, Default, Serialize)]
pub struct Timings {
    pub read: f64,
    pub nodes: f64,
    pub resample: f64,
    pub cycles: f64,
    pub tessellate: f64,
    pub operators: f64,
    pub factor: f64,
    pub solve: f64,
    pub write: f64,
    pub total: f64,
}

/// Statistics of a run (docs/design.md §5, written by `--stats`).
#[derive(Clone, Debug, Default, Serialize)]
pub struct Stats {
    pub vertices: usize,
    pub faces: usize,
    pub curve_vertices: usize,
    pub cycles: usize,
    pub components: usize,
    pub nodes: usize,
    pub segments: usize,
    pub spacing: f64,
    pub method: String,
    /// Iterations of the 3D-operator loop that ran (0: planar weights only).
    pub iterations: usize,
    /// Why the loop stopped: `converged`, `max-iterations`, `degenerate`, `diverging`.
    pub iteration_stop: Option<String>,
    /// Largest vertex update of each iteration.
    pub iteration_updates: Vec<f64>,
    /// Peak resident memory of the process in bytes, when the front end measured it.
    pub peak_memory_bytes: Option<u64>,
    pub timings: Timings,
}

/// The result of a surfacing run.
#[derive(Clone, Debug)]
pub struct Surface {
    /// The mesh with its final positions; vertices `0..mesh.num_curve` lie on the curves.
    pub mesh: Mesh,
    /// Unit vertex normals of the final mesh.
    pub normals: Vec<DVec3>,
    /// Signed mean curvature of the final mesh (cotangent formula; 0 on open boundaries).
    pub mean_curvature: Vec<f64>,
    /// The propagated normals `N*` (normal-control only).
    pub propagated_normals: Option<Vec<DVec3>>,
    pub curve_flags: Vec<bool>,
    pub stats: Stats,
    pub warnings: Vec<Warning>,
}

impl Surface {
    /// The mesh and its attributes, for [`crate::io::write_mesh`].
    pub fn mesh_data(&self) -> MeshData<'_> {
        MeshData {
            positions: &self.mesh.positions,
            faces: &self.mesh.faces,
            normals: Some(&self.normals),
            mean_curvature: Some(&self.mean_curvature),
            curve_vertex: Some(&self.curve_flags),
            propagated_normals: self.propagated_normals.as_deref(),
        }
    }
}

/// Checks that the tessellated patches join into an edge-manifold, consistently oriented mesh
/// ([`crate::geom::mesh::bad_edge`]); an edge in more than two faces means that two patches overlap
/// (two curves come closer than the spacing between nodes, or a patch folds onto its
/// neighbour). The error names the patches, the curves and the place.
fn manifold(mesh: &Mesh, g: &Graph, res: &Resampled) -> Result<()> {
    let Some(([a, b], faces)) = crate::geom::mesh::bad_edge(&mesh.faces) else { return Ok(()) };
    let mut patches: Vec<u32> = faces.iter().map(|&f| mesh.face_patch[f]).collect();
    patches.sort_unstable();
    patches.dedup();
    let curve_of = |v: u32| {
        res.segment_vertices.iter().position(|sv| sv.contains(&v)).map(|s| g.labels[g.segments[s].curve].clone())
    };
    let mut curves: Vec<String> = [a, b].iter().filter_map(|&v| curve_of(v)).collect();
    curves.dedup();
    let list = |v: &[String]| if v.is_empty() { "interior vertices".to_string() } else { v.join(" and ") };
    let patches: Vec<String> = patches.iter().map(|p| p.to_string()).collect();
    Err(Error::topology(format!(
        "patches {} overlap near {} (an edge of {} in {} triangles): the curves come closer than the \
         mesh spacing between crossings, or a patch folds onto its neighbour; give a smaller `spacing`, \
         a larger `snap`, or fix the curves there",
        patches.join(", "),
        crate::geom::fmt_point(mesh.positions[a as usize]),
        list(&curves),
        faces.len()
    )))
}

/// Surfaces `network` with `options`. See [`surface_with_progress`].
pub fn surface(network: &Network, options: &Options) -> Result<Surface> {
    surface_with_progress(network, options, &mut |_, _, _| {})
}

/// Sizes that predict the vertex count: free vertices ≈ `c A / d²` over the patches' projected
/// area `A`, curve vertices ≈ `ℓ / d` over the segments' length `ℓ`.
#[derive(Clone)]
struct SizeModel {
    /// `c A`: the vertices-per-area constant times the domains' total area.
    area: f64,
    length: f64,
    /// Area of each patch's domain (projection or strip).
    patch_areas: Vec<f64>,
}

impl SizeModel {
    fn new(g: &Graph, splines: &[CurveSpline], patches: &[Patch]) -> Self {
        let length: f64 = g.segments.iter().map(|s| splines[s.curve].arc_between(s.first, s.last)).sum();
        let samples = |hs: &[crate::topology::HalfEdge]| -> Vec<DVec3> {
            hs.iter().flat_map(|&h| half_edge_samples(g, h)).map(|x| x.0).collect()
        };
        let patch_areas: Vec<f64> = patches
            .iter()
            .map(|p| match p {
                Patch::Disk(hs) => crate::geom::polygon_vector_area(&samples(hs)).length(),
                Patch::Tube([a, b]) => {
                    let (la, lb) = (samples(a), samples(b));
                    let len = |v: &[DVec3]| (0..v.len()).map(|i| v[i].distance(v[(i + 1) % v.len()])).sum::<f64>();
                    let c = |v: &[DVec3]| v.iter().sum::<DVec3>() / v.len() as f64;
                    0.5 * (len(&la) + len(&lb)) * c(&la).distance(c(&lb))
                }
            })
            .collect();
        SizeModel { area: VERTICES_PER_AREA * patch_areas.iter().sum::<f64>(), length, patch_areas }
    }

    fn vertices(&self, d: f64) -> f64 {
        self.area / (d * d) + self.length / d
    }

    /// The spacing that gives about `target` vertices (`n = c A x² + ℓ x`, `x = 1/d`).
    fn spacing(&self, target: usize) -> f64 {
        let (ca, l, n) = (self.area, self.length, target.max(10) as f64);
        let x = if ca > 0.0 { (-l + (l * l + 4.0 * ca * n).sqrt()) / (2.0 * ca) } else { n / l };
        1.0 / x
    }
}

/// One warning per patch of `mesh` whose planar projection folds over (triangulated in a
/// fallback domain, see [`crate::tessellate`]).
fn fold_warnings(mesh: &Mesh) -> Vec<Warning> {
    mesh.fold_fallback
        .iter()
        .map(|p| {
            Warning::new(format!(
                "patch {p}: its planar projection folds over (a deep or twisted cycle); it was triangulated on a \
                 fallback domain (the plane of its vector area, or an ellipse its border is mapped onto by arc length)"
            ))
        })
        .collect()
}

/// Surfaces `network`, reporting each finished stage to `progress(stage, seconds, detail)`.
pub fn surface_with_progress(
    network: &Network,
    options: &Options,
    progress: &mut dyn FnMut(&str, f64, &str),
) -> Result<Surface> {
    let prepared = prepare(network, options, progress)?;
    let base = prepared.timings;
    solve_prepared(Cow::Owned(prepared), options, progress, None, base)
}

/// What the stages before the final solve produced: the mesh and the figures the solve and
/// its statistics need. [`crate::pipeline::surfacer::Surfacer`] keeps it between solves.
#[derive(Clone, Debug)]
pub(crate) struct Prepared {
    /// The mesh the final solve runs on (curve vertices first, with their input normals).
    pub mesh: Mesh,
    /// The target edge length `d`.
    pub spacing: f64,
    /// The snapping tolerance the nodes were found with.
    pub snap: f64,
    /// The validated input curves' samples and closedness (`--method cauchy` finds its
    /// constraint curves on the mesh by them).
    pub curves: Vec<(Vec<DVec3>, bool)>,
    /// Mean input sample spacing (soft constraints are scaled by it).
    pub input_spacing: f64,
    pub patches: usize,
    pub nodes: usize,
    pub segments: usize,
    pub components: usize,
    pub warnings: Vec<Warning>,
    /// Seconds of the stages so far (`total`: their sum).
    pub timings: Timings,
    /// Seconds of the conformal first solve.
    pub solve_timings: SolveTimings,
}

/// Validates, finds the nodes and patches, picks the spacing, resamples and tessellates
/// (with the conformal first solve when `options.patching` asks for it).
pub(crate) fn prepare(
    network: &Network,
    options: &Options,
    progress: &mut dyn FnMut(&str, f64, &str),
) -> Result<Prepared> {
    let start = Instant::now();
    let mut timings = Timings::default();
    if let Some(d) = options.spacing {
        if !(d.is_finite() && d > 0.0) {
            return Err(Error::usage(format!("spacing {d} is not a positive distance")));
        }
    }
    if options.vertices == Some(0) {
        return Err(Error::usage("the vertex count must be positive"));
    }
    if let Some(w) = options.soft {
        if !(w.is_finite() && w > 0.0) {
            return Err(Error::usage(format!("soft-constraint weight {w} is not a positive number")));
        }
        if !matches!(options.method, Method::NormalControl | Method::ShortPaper) {
            return Err(Error::usage(format!(
                "`soft` applies to normal-control and short-paper only, not to {}",
                options.method.name()
            )));
        }
    }
    if let Some(s) = options.snap {
        if !(s.is_finite() && s > 0.0) {
            return Err(Error::usage(format!("snapping tolerance {s} is not a positive distance")));
        }
    }

    // Nodes and segments.
    let clock = Instant::now();
    let (net, mut warnings) = network.validated()?;
    let snap = options.snap.or(net.snap).unwrap_or_else(|| net.snap_tolerance());
    let (mut g, w) = find_nodes(&net, snap)?;
    warnings.extend(w);
    warnings.extend(trim_dangling(&mut g)?);
    timings.nodes = clock.elapsed().as_secs_f64();
    progress("nodes", timings.nodes, &format!("{} nodes, {} segments", g.nodes.len(), g.segments.len()));

    // Splines (needed for the tangents at nodes) and cycles.
    let clock = Instant::now();
    let splines: Vec<CurveSpline> =
        g.curves.par_iter().map(|c| CurveSpline::fit(&c.points, &c.normals, c.closed)).collect();
    let spline_time = clock.elapsed().as_secs_f64();
    let clock = Instant::now();
    let (patches, w) = find_patches_open(&mut g, &splines)?;
    warnings.extend(w);
    timings.cycles = clock.elapsed().as_secs_f64();
    progress("cycles", timings.cycles, &format!("{} patches", patches.len()));

    // Spacing, resampling, tessellation and the first solve.
    let clock = Instant::now();
    let size = SizeModel::new(&g, &splines, &patches);
    let target = options.vertices.unwrap_or(Options::DEFAULT_VERTICES);
    let mut d = options.spacing.unwrap_or_else(|| size.spacing(target));
    let estimate = size.vertices(d);
    if estimate > Options::MAX_VERTICES {
        return Err(Error::usage(format!(
            "spacing {d:.3e} would create about {estimate:.2e} vertices (limit {:.0e}); give a larger `spacing` or a smaller `vertices`",
            Options::MAX_VERTICES
        )));
    }
    timings.resample = spline_time + clock.elapsed().as_secs_f64();

    let mut st = SolveTimings::default();
    let input_spacing = net.mean_sample_spacing();
    // Resample and tessellate at spacing `d` with planar projections.
    let planar_stage = |d: f64, timings: &mut Timings| -> Result<(Resampled, Mesh)> {
        let clock = Instant::now();
        let res = resample_network(&g, &splines, d);
        timings.resample += clock.elapsed().as_secs_f64();
        let clock = Instant::now();
        let mesh = tessellate(&g, &res, &patches, d)?;
        manifold(&mesh, &g, &res)?;
        timings.tessellate += clock.elapsed().as_secs_f64();
        Ok((res, mesh))
    };

    let mesh = match options.patching {
        Patching::Planar => {
            let (res, mesh) = planar_stage(d, &mut timings)?;
            warnings.extend(fold_warnings(&mesh));
            progress("resample", timings.resample, &format!("spacing {d:.4e}, {} curve vertices", res.positions.len()));
            progress(
                "tessellate",
                timings.tessellate,
                &format!("{} vertices, {} faces", mesh.num_vertices(), mesh.faces.len()),
            );
            mesh
        }
        Patching::Conformal => {
            // Better patching ([CG] §6): a coarse first solution (twice the spacing) on planar
            // projections, then each patch re-tessellated in a conformal flattening of it.
            let d0 = 2.0 * d;
            let (coarse_res, coarse) = planar_stage(d0, &mut timings)?;
            warnings.extend(fold_warnings(&coarse));
            // The first solution only shapes the flattening: normal-control whatever the method.
            let ops = cotan_operators(&coarse, Metric::Planar, &coarse.positions);
            let first = normal_control(
                &coarse,
                &ops,
                &NormalControlParams { guide_updates: 1, ..Default::default() },
                &mut st,
            )?;
            let coarse = Mesh { positions: first.positions, ..coarse };
            let clock = Instant::now();
            let flat = flatten_patches(&patches, &coarse_res, &coarse);
            timings.tessellate += clock.elapsed().as_secs_f64();
            if options.spacing.is_none() {
                // The vertex count follows the flattened domains' area, not the projections'.
                let total: f64 =
                    flat.iter().zip(&size.patch_areas).map(|(f, a)| f.as_ref().map_or(*a, |f| f.area)).sum();
                d = SizeModel { area: VERTICES_PER_AREA * total, ..size.clone() }.spacing(target);
            }
            let clock = Instant::now();
            let res = resample_network(&g, &splines, d);
            timings.resample += clock.elapsed().as_secs_f64();
            progress("resample", timings.resample, &format!("spacing {d:.4e}, {} curve vertices", res.positions.len()));
            let clock = Instant::now();
            let (mesh, kept) = tessellate_conformal(&g, &res, &patches, d, &coarse_res, &flat)?;
            manifold(&mesh, &g, &res)?;
            timings.tessellate += clock.elapsed().as_secs_f64();
            warnings.extend(fold_warnings(&mesh).into_iter().filter(|w| !warnings.contains(w)).collect::<Vec<_>>());
            for p in kept {
                warnings.push(Warning::new(format!(
                    "patch {p}: its conformal flattening folds over; it keeps the planar projection"
                )));
            }
            progress(
                "tessellate",
                timings.tessellate,
                &format!("conformal: {} vertices, {} faces", mesh.num_vertices(), mesh.faces.len()),
            );
            mesh
        }
    };
    timings.total = start.elapsed().as_secs_f64();
    Ok(Prepared {
        mesh,
        spacing: d,
        snap,
        curves: net.curves.iter().map(|c| (c.points.clone(), c.closed)).collect(),
        input_spacing,
        patches: patches.len(),
        nodes: g.nodes.len(),
        segments: g.segments.len(),
        components: {
            let c = g.node_components();
            (0..c.len()).filter(|&i| c[i] == i).count()
        },
        warnings,
        timings,
        solve_timings: st,
    })
}

/// The final solve on a prepared mesh: the method, then the 3D iterations. `factors`, when
/// given, holds the normal-control factorisations of earlier solves on the same mesh and
/// options (empty: computed here and stored); without it they are freed before the
/// iterations (lower peak memory). `base` are the timings of the stages before (added to).
/// An owned `prepared` gives its mesh to the result; a borrowed one is copied.
pub(crate) fn solve_prepared(
    prepared: Cow<'_, Prepared>,
    options: &Options,
    progress: &mut dyn FnMut(&str, f64, &str),
    factors: Option<&mut Factors>,
    base: Timings,
) -> Result<Surface> {
    let start = Instant::now();
    let mut timings = base;
    let mut st = prepared.solve_timings;
    let mut warnings = prepared.warnings.clone();
    let input_spacing = prepared.input_spacing;
    let d = prepared.spacing;
    let mesh = &prepared.mesh;
    // The soft weight per curve vertex (see `Options::soft`); the uniform energy carries an
    // extra 1/area factor, compensated by the mean vertex area.
    let soft_scale = |s: f64, mean_area: f64, spacing: f64| {
        let base = spacing / (s * input_spacing).powi(3);
        match options.energy {
            Weighting::Area => base,
            Weighting::Uniform => base / mean_area,
        }
    };
    let run = |mesh: &Mesh,
               spacing: f64,
               metric_positions: &[DVec3],
               metric: Metric,
               st: &mut SolveTimings,
               factors: &mut Factors| {
        let clock = Instant::now();
        let ops = cotan_operators(mesh, metric, metric_positions);
        st.operators += clock.elapsed().as_secs_f64();
        if let Some(i) = ops.mass.iter().position(|a| !(*a > 0.0)) {
            let patch = mesh.faces.iter().position(|f| f.contains(&(i as u32))).map(|f| mesh.face_patch[f]);
            let at = patch.map_or_else(String::new, |p| format!(" of patch {p}"));
            return Err(Error::numerical(format!("vertex {i}{at} has zero area: degenerate triangles around it")));
        }
        match options.method {
            Method::NormalControl => {
                let mean_area = ops.mass.iter().sum::<f64>() / ops.mass.len() as f64;
                let soft_weight = options.soft.map(|w| soft_scale(w, mean_area, spacing));
                normal_control_cached(
                    mesh,
                    &ops,
                    &NormalControlParams {
                        weighting: options.energy,
                        guide_area: options.guide_area,
                        guide_updates: options.guide_updates,
                        soft_weight,
                    },
                    st,
                    factors,
                )
            }
            Method::Biharmonic => polyharmonic(mesh, &ops, 2, st),
            Method::Triharmonic => polyharmonic(mesh, &ops, 3, st),
            Method::Method4 => method4(mesh, &ops, st),
            Method::ShortPaper => {
                let area: f64 = ops.mass.iter().sum();
                let patch_count = mesh.face_patch.iter().max().map_or(1, |m| *m as usize + 1);
                let s = (area / patch_count as f64).sqrt();
                let mean_area = area / ops.mass.len() as f64;
                let params = ShortPaperParams {
                    omega1: options.w1 / s.powi(4),
                    omega0: options.soft.map(|w| soft_scale(w, mean_area, spacing)),
                };
                short_paper(mesh, &ops, &params, st)
            }
            Method::Cauchy => crate::methods::andrews2011::constraints::solve_network(
                mesh,
                &ops,
                &prepared.curves,
                options.cauchy.as_deref(),
                prepared.snap,
                options.order,
                options.ghost_updates,
                st,
            ),
        }
    };
    let mut one_shot = Factors::default();
    let kept = match factors {
        Some(f) => f,
        None => &mut one_shot,
    };
    let mut result = run(mesh, d, &mesh.positions, Metric::Planar, &mut st, kept)?;
    drop(one_shot);
    let mut iteration_report: (Vec<f64>, Option<Stop>) = (Vec::new(), None);
    if options.iterations > 0 {
        match options.method {
            Method::NormalControl => {
                let area: f64 = mesh
                    .faces
                    .iter()
                    .map(|f| {
                        let p = |k: usize| result.positions[f[k] as usize];
                        0.5 * (p(1) - p(0)).cross(p(2) - p(0)).length()
                    })
                    .sum();
                let params = IterationParams {
                    max_iterations: options.iterations,
                    tolerance: options.tolerance,
                    prior_scale: options.normal_prior,
                    patch_size: (area / prepared.patches.max(1) as f64).sqrt(),
                    spacing: d,
                    weighting: options.energy,
                    soft_weight: options.soft.map(|w| soft_scale(w, area / mesh.num_vertices() as f64, d)),
                    inner: options.inner_steps,
                };
                let (r, report) = iterate(mesh, result, &params, &mut st)?;
                result = r;
                match report.stop {
                    Stop::Degenerate => warnings.push(Warning::new(format!(
                        "the 3D iteration stopped after {} step(s): a triangle degenerated; the last good surface is kept",
                        report.updates.len()
                    ))),
                    Stop::Diverging => warnings.push(Warning::new(format!(
                        "the 3D iteration stopped after {} step(s): its updates grew; the last good surface is kept",
                        report.updates.len()
                    ))),
                    Stop::Converged | Stop::MaxIterations => {}
                }
                iteration_report = (report.updates, Some(report.stop));
            }
            // The baselines keep the weights of their patching's domains, as in [CG] Table 1.
            Method::Biharmonic | Method::Triharmonic | Method::Method4 | Method::ShortPaper | Method::Cauchy => {}
        }
    }
    timings.operators = st.operators;
    timings.factor = st.factor;
    timings.solve = st.solve;
    progress("solve", st.operators + st.factor + st.solve, options.method.name());

    let (cycles, components, nodes, segments) =
        (prepared.patches, prepared.components, prepared.nodes, prepared.segments);
    let clock = Instant::now();
    let mut mesh = prepared.into_owned().mesh;
    mesh.positions = result.positions;
    let (normals, mean_curvature) = normals_and_mean_curvature(&mesh.faces, &mesh.positions, &mesh.on_boundary);
    timings.operators += clock.elapsed().as_secs_f64();
    timings.total = base.total + start.elapsed().as_secs_f64();
    let stats = Stats {
        vertices: mesh.num_vertices(),
        faces: mesh.faces.len(),
        curve_vertices: mesh.num_curve,
        cycles,
        components,
        nodes,
        segments,
        spacing: d,
        method: options.method.name().to_string(),
        iterations: iteration_report.0.len(),
        iteration_stop: iteration_report.1.map(|s| s.name().to_string()),
        iteration_updates: iteration_report.0,
        peak_memory_bytes: None,
        timings,
    };
    let curve_flags = mesh.curve_flags();
    Ok(Surface {
        mesh,
        normals,
        mean_curvature,
        propagated_normals: result.propagated_normals,
        curve_flags,
        stats,
        warnings,
    })
}
