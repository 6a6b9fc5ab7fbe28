//! The final solve on a prepared mesh (\[CG\] §3.4; docs/design.md §1, steps 8–13): the
//! operators of the patches' domains, the method ([`crate::methods::SurfacingMethod`]), then
//! normal-control's 3D iterations, then the result's normals, curvature and statistics.

use super::options::Options;
use super::prepare::{Prepared, Progress};
use super::stats::{CoarseLevel, Stats, Surface, Timings};
use crate::error::{Error, Result, Warning};
use crate::geom::mesh::Mesh;
use crate::methods::andrews2011::Andrews2011;
use crate::methods::eg2016::{ShortPaper, ShortPaperParams};
use crate::methods::iterated::{CgCounts, Iterated, IterationOptions, IterationParams, Stop};
use crate::methods::method4::Method4;
use crate::methods::normal_control::{NormalControl, NormalControlParams};
use crate::methods::polyharmonic::Polyharmonic;
use crate::methods::{Energy, Method, MethodResult, SurfacingMethod};
use crate::operators::{cotan_operators, normals_and_mean_curvature, Metric, Operators};
use crate::solve::timing::{seconds_since, timed, Instant};
use std::borrow::Cow;

/// What a [`crate::Surfacer`] keeps between solves on one prepared mesh: the method with its
/// factorisations and the iterations with their symbolic analysis.
pub(crate) struct Kept {
    method: Box<dyn SurfacingMethod>,
    iterated: Option<Iterated>,
    /// The operators of the patches' domains (they depend on the mesh only).
    ops: Option<Operators>,
    /// The last solve's positions on the solved mesh: the start of a re-solve's iteration.
    last: Option<Vec<crate::geom::DVec3>>,
    /// Whether this is a [`crate::Surfacer`]'s (kept between solves) or a one-shot run's.
    keep: bool,
}

impl Kept {
    /// Whether a factorisation is kept (the method's, or the 3D iterations' when the first
    /// solve started on the coarse level's surface).
    pub(crate) fn is_factored(&self) -> bool {
        self.method.is_factored() || self.iterated.as_ref().is_some_and(Iterated::is_factored)
    }

    /// The network's curves moved (see [`SurfacingMethod::set_curves`]).
    pub(crate) fn set_curves(&mut self, curves: &[(Vec<crate::geom::DVec3>, bool)]) {
        self.method.set_curves(curves);
    }
}

/// The soft-constraint weight per curve vertex for `soft = s` (see [`Options::soft`]):
/// `d / (s h)³` with the spacing `d` and the mean input sample spacing `h`; the uniform energy
/// carries an extra `1/area` factor, compensated by the mean vertex area.
fn soft_weight(options: &Options, s: f64, input_spacing: f64, mean_area: f64, spacing: f64) -> f64 {
    let base = spacing / (s * input_spacing).powi(3);
    match options.normal_control.energy {
        Energy::Area => base,
        Energy::Uniform => base / mean_area,
    }
}

/// The method object of `options.method` with its scales from the patches' domains of
/// `solved` (the mesh it solves on: cut along the creases for normal-control).
fn make_method(options: &Options, prepared: &Prepared, solved: &Mesh) -> Box<dyn SurfacingMethod> {
    // The domains' total area (that of the mass matrix of `domain_operators`).
    let area: f64 = solved.planar.iter().map(|q| 0.5 * (q[1] - q[0]).perp_dot(q[2] - q[0]).abs()).sum();
    let mean_area = area / solved.num_vertices() as f64;
    let soft = |s: f64| soft_weight(options, s, prepared.input_spacing, mean_area, prepared.spacing);
    let mesh = &prepared.mesh;
    match options.method {
        Method::NormalControl => Box::new(NormalControl::new(NormalControlParams {
            options: options.normal_control,
            soft_weight: options.soft.map(soft),
        })),
        Method::Biharmonic => Box::new(Polyharmonic::new(2)),
        Method::Triharmonic => Box::new(Polyharmonic::new(3)),
        Method::Method4 => Box::new(Method4::new()),
        Method::ShortPaper => {
            // ω₁ = w1 / s⁴ with s the mean patch size.
            let patch_count = mesh.face_patch.iter().max().map_or(1, |m| *m as usize + 1);
            let s = (area / patch_count as f64).sqrt();
            Box::new(ShortPaper::new(ShortPaperParams {
                omega1: options.short_paper.w1 / s.powi(4),
                omega0: options.soft.map(soft),
            }))
        }
        Method::Cauchy => Box::new(Andrews2011::new(prepared.curves.clone(), options.cauchy.clone(), prepared.snap)),
    }
}

/// The operators of the patches' domains, checked: a vertex without area is a numerical error
/// naming its patch.
fn domain_operators(mesh: &Mesh) -> Result<Operators> {
    let ops = cotan_operators(mesh, Metric::Planar, &mesh.positions);
    if let Some(i) = ops.mass.iter().position(|a| !(*a > 0.0)) {
        let patch = mesh.faces.iter().position(|f| f.contains(&(i as u32))).map(|f| mesh.face_patch[f]);
        let at = patch.map_or_else(String::new, |p| format!(" of patch {p}"));
        let e = Error::numerical(format!("vertex {i}{at} has zero area: degenerate triangles around it")).vertex(i);
        return Err(match patch {
            Some(p) => e.patch(p as usize),
            None => e,
        });
    }
    Ok(ops)
}

/// The final solve on a prepared mesh: the method, then the 3D iterations. `kept`, when given,
/// holds the method and iterations of earlier solves on the same mesh and options (empty:
/// created here and stored); without it the method's factorisations are freed before the
/// iterations (lower peak memory). `base` are the timings of the stages before (added to).
/// An owned `prepared` gives its mesh to the result; a borrowed one is copied.
pub(crate) fn solve_prepared(
    prepared: Cow<'_, Prepared>,
    options: &Options,
    progress: Progress<'_>,
    kept: Option<&mut Option<Kept>>,
    base: Timings,
) -> Result<Surface> {
    let start = Instant::now();
    let mut timings = base;
    let mut st = prepared.solve_timings;
    let mut warnings = prepared.warnings.clone();
    // Normal-control solves on the mesh cut open along the creases; the baselines ignore
    // the creases' second normals (design.md §13).
    let seams = prepared.seams.as_ref().filter(|_| options.method == Method::NormalControl);
    let mesh = seams.map_or(&prepared.mesh, |s| &s.mesh);
    let keep = kept.is_some();
    let mut one_shot: Option<Kept> = None;
    let slot: &mut Option<Kept> = match kept {
        Some(k) => k,
        None => &mut one_shot,
    };
    let fresh = slot.is_none();
    let state = slot.get_or_insert_with(|| Kept {
        method: make_method(options, &prepared, mesh),
        iterated: None,
        ops: None,
        last: None,
        keep,
    });
    let iterating = options.iterate.iterations > 0 && options.method == Method::NormalControl;
    // A re-solve of a Surfacer after the curves changed: from the last surface with the kept
    // operators and factorisations of its last iteration (issue 31; [`Iterated::resolve`]).
    let resolved = match (iterating && !fresh, state.last.as_deref(), state.iterated.as_mut()) {
        (true, Some(last), Some(iterated)) => iterated.resolve(mesh, last, &mut st).transpose()?,
        _ => None,
    };
    // The coarse level iterated and the free vertices start on its surface: the fine level's
    // first solve is left out (not after the curves moved: the start is the old surface's),
    // and with it the domain operators. A start whose fine iteration degenerates or diverges
    // (a tube's seam at very few vertices) falls back to the fine level's own first solve.
    let from_coarse_start = iterating && fresh && prepared.coarse.is_some();
    let ops = if from_coarse_start || resolved.is_some() {
        None
    } else {
        match state.ops.take() {
            Some(ops) => Some(ops),
            None => Some(timed(&mut st.operators, || domain_operators(mesh))?),
        }
    };
    let mut from_coarse = resolved;
    if from_coarse_start {
        let start = MethodResult { positions: mesh.positions.clone(), propagated_normals: None, guide_curvature: None };
        let (r, report) = iterate(options, &prepared, start, state, &mut st, progress, true)?;
        if matches!(report.stop, Stop::Converged | Stop::MaxIterations) {
            from_coarse = Some((r, report));
        } else {
            state.iterated = None;
        }
    }
    let mut iteration_report: (Vec<f64>, Option<Stop>, CgCounts) = (Vec::new(), None, CgCounts::default());
    let mut result;
    // The coarse level's figures, when the fine level started on it.
    let coarse = from_coarse.as_ref().and(prepared.coarse.clone());
    if let Some((r, report)) = from_coarse {
        result = r;
        iteration_report = (report.updates, Some(report.stop), report.cg);
    } else {
        let ops = match ops {
            Some(ops) => ops,
            None => timed(&mut st.operators, || domain_operators(mesh))?,
        };
        result = state.method.solve(mesh, &ops, &mut st)?;
        // A Surfacer's next solve reuses them (they depend on the mesh only).
        state.ops = keep.then_some(ops);
        if iterating {
            progress("first solve", st.operators + st.factor + st.solve, options.method.name());
        }
        if !keep {
            // Lower peak memory: the iterations factorise their own systems.
            state.method.release();
        }
    }
    // The baselines keep the weights of their patching's domains, as in [CG] Table 1.
    if iterating && iteration_report.1.is_none() {
        let (r, report) = iterate(options, &prepared, result, state, &mut st, progress, false)?;
        result = r;
        let stopped = |why: &str| {
            Warning::new(format!(
                "the 3D iteration stopped after {} step(s): {why}; the last good surface is kept",
                report.updates.len()
            ))
        };
        match report.stop {
            Stop::Degenerate => warnings.push(stopped("a triangle degenerated")),
            Stop::Diverging => warnings.push(stopped("its updates grew")),
            Stop::Converged | Stop::MaxIterations => {}
        }
        iteration_report = (report.updates, Some(report.stop), report.cg);
    }
    if keep {
        state.last = Some(result.positions.clone());
    }
    if let Some(s) = seams {
        result.positions = s.merge(&result.positions);
        result.propagated_normals = result.propagated_normals.map(|n| s.merge(&n));
        result.guide_curvature = result.guide_curvature.map(|h| s.merge(&h));
    }
    timings.operators = st.operators;
    timings.factor = st.factor;
    timings.solve = st.solve;
    progress("solve", st.operators + st.factor + st.solve, options.method.name());
    let (curves, spacing) = (prepared.curves.clone(), prepared.spacing);
    let mut surface = finish(prepared, options, result, (iteration_report, coarse), warnings, timings, base, start);
    surface.stats.reach = super::coverage::check_reach(&surface.mesh)?;
    let clock = Instant::now();
    if let Some(w) = super::details::leave_out_drawn_on(&mut surface) {
        surface.warnings.push(w);
    }
    if let Some(w) = super::details::pull_onto_strokes(&mut surface, &curves, spacing) {
        surface.warnings.push(w);
    }
    if let Some(w) = super::coverage::check_self_intersections(&surface.mesh, &mut surface.stats) {
        surface.warnings.push(w);
    }
    surface.stats.timings.operators += seconds_since(clock);
    surface.stats.timings.total += seconds_since(clock);
    Ok(surface)
}

/// Normal-control's 3D iterations from `result`, with the iterations object `state` keeps
/// (created on the first run; its parameters follow the current surface).
fn iterate(
    options: &Options,
    prepared: &Prepared,
    result: MethodResult,
    state: &mut Kept,
    st: &mut crate::solve::SolveTimings,
    progress: Progress<'_>,
    from_coarse: bool,
) -> Result<(MethodResult, crate::methods::iterated::IterationReport)> {
    let mesh = prepared.seams.as_ref().map_or(&prepared.mesh, |s| &s.mesh);
    let d = prepared.spacing;
    let area = crate::geom::mesh::surface_area(&mesh.faces, &result.positions);
    let mean_area = area / mesh.num_vertices() as f64;
    let fine_iterations = if from_coarse { super::levels::FINE_ITERATIONS } else { options.iterate.iterations };
    let params = IterationParams {
        options: IterationOptions { iterations: fine_iterations, ..options.iterate },
        patch_size: (area / prepared.patches.max(1) as f64).sqrt(),
        spacing: d,
        energy: options.normal_control.energy,
        guide_area: options.normal_control.guide_area,
        soft_weight: options.soft.map(|s| soft_weight(options, s, prepared.input_spacing, mean_area, d)),
    };
    let iterated = state.iterated.get_or_insert_with(|| Iterated::new(params));
    iterated.params = params;
    iterated.keep_operators = state.keep;
    // A one-shot run's fine level: conjugate gradients preconditioned by the coarse level
    // instead of a factorisation, when the levels kept it for that (`fine_solve`; a Surfacer
    // keeps factorisations for its re-solves).
    iterated.coarse = prepared.coarse.as_ref().and_then(|c| c.system.clone()).filter(|_| from_coarse && !state.keep);
    let clock = Instant::now();
    iterated.run_reporting(mesh, result, st, &mut |k, of, update| {
        progress("iteration", seconds_since(clock), &format!("{k} of at most {of}, largest move {update:.2e}"));
    })
}

/// The surface of a finished solve: the result's positions on the prepared mesh, its normals
/// and mean curvature, the statistics.
#[allow(clippy::too_many_arguments)]
fn finish(
    prepared: Cow<'_, Prepared>,
    options: &Options,
    result: MethodResult,
    (iteration_report, coarse): ((Vec<f64>, Option<Stop>, CgCounts), Option<CoarseLevel>),
    warnings: Vec<Warning>,
    mut timings: Timings,
    base: Timings,
    start: Instant,
) -> Surface {
    let (cycles, components, nodes, segments, d) =
        (prepared.patches, prepared.components, prepared.nodes, prepared.segments, prepared.spacing);
    let clock = Instant::now();
    let mut mesh = prepared.into_owned().mesh;
    mesh.positions = result.positions;
    let (normals, mean_curvature) = normals_and_mean_curvature(&mesh.faces, &mesh.positions, &mesh.on_boundary);
    timings.operators += seconds_since(clock);
    timings.total = base.total + seconds_since(start);
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
        coarse_vertices: coarse.as_ref().map_or(0, |c| c.vertices),
        coarse_iteration_updates: coarse.map_or_else(Vec::new, |c| c.updates),
        fine_cg: (!iteration_report.2.iterations.is_empty()).then_some(iteration_report.2),
        inferred_normals: None,
        consolidation: None,
        coverage: None,
        reach: 0.0,
        self_intersections: 0,
        open_borders: None,
        peak_memory_bytes: None,
        timings,
    };
    let curve_flags = mesh.curve_flags();
    Surface {
        mesh,
        normals,
        mean_curvature,
        propagated_normals: result.propagated_normals,
        curve_flags,
        stats,
        warnings,
    }
}
