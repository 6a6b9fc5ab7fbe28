//! The iterated normal-control method: removes the planar-metric bias of \[CG\] §3.4 (its §5
//! admits the weights "are not optimal") by rebuilding the operators on the 3D surface.
//!
//! Starting from a first solve `V₀` (with the planar operators), iteration `k`:
//!
//! 1. builds `Ls`, `M` on the current surface `V_k` (3D cotangent weights, mixed areas);
//! 2. re-propagates the normals, `min ‖L N‖²_M + μ ‖N − n(V_k)‖²_M` with the curve normals
//!    fixed: the biharmonic propagation of \[CG\] plus a weak pull towards the normals `n(V_k)`
//!    of the current surface. The biharmonic interpolant alone leaves a resolution-independent
//!    error in `N*` (2.3° mean on the torus R 4, r 2) that bounds the final accuracy; the pull
//!    lets large-scale normal information come from the fitted surface while the curves'
//!    normals stay exact. `μ = (prior_scale · s)⁻⁴` with `s` the mean patch size, so the pull
//!    acts at scales above `prior_scale · s` (scale and resolution independent);
//! 3. evaluates the guide `H` (eq. 1) on `(V_k, N)` with the areas `M`;
//! 4. fits `min Σ_v A_v ‖(L V)_v + 2 H n_v‖² + μ ‖V − V_k‖²_M`: the area-weighted energy
//!    (docs/design.md §1; the unweighted one drifts) plus the same proximal term, so that steps 2 and
//!    4 share one matrix `Ls M⁻¹ Ls + μ M` and one factorisation per iteration (whose symbolic
//!    analysis is computed once for the whole run: the pattern never changes);
//! 5. keeps only the normal component of the update, `V_{k+1} = V_k + n nᵀ (V' − V_k)`: the
//!    fit leaves the tangential distribution of vertices free, and letting it move makes the
//!    vertices drift along the surface from one iteration to the next until triangles degenerate.
//!
//! It stops when the largest update falls below `tolerance × spacing`, after
//! `max_iterations`, or — keeping the last good surface — when a triangle degenerates or the
//! updates grow (divergence).

use super::normal_control::{fit_weights, seam_normal_targets, seam_targets};
use super::{check_finite, factor_like, factor_on, known_rows, scatter, Energy, GuideArea, MethodResult};
use crate::error::{Error, Result};
use crate::geom::mesh::Mesh;
use crate::geom::DVec3;
use crate::operators::{blended_mean_curvature, cotan_operators, vertex_normals, Metric, Operators};
use crate::solve::pcg::Energy as Quadratic;
use crate::solve::sparse::{product_lower, product_lower_keeping_pattern, Csc};
use crate::solve::timing::timed;
use crate::solve::two_level::{Coarse, FineSystem};
use crate::solve::{Eliminated, LeastSquares, SolveTimings};
use faer::Mat;
use std::cell::{OnceCell, RefCell};
use std::sync::{Arc, Mutex};

/// The user's settings of the 3D iterations (options `iterations`, `inner_steps`,
/// `tolerance`, `normal_prior`; docs/design.md §6).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct IterationOptions {
    /// `iterations`: at most this many iterations (each one factorisation, or two with open
    /// borders); 0 keeps the weights of the patches' domains. Default
    /// [`IterationOptions::DEFAULT_ITERATIONS`].
    pub iterations: usize,
    /// `inner_steps`: repeats of steps 2–5 on the same operators and factorisation (≥ 1).
    /// Default [`IterationOptions::DEFAULT_INNER_STEPS`].
    pub inner_steps: usize,
    /// `tolerance`: stop when the largest vertex update is below `tolerance × spacing`.
    /// Default [`IterationOptions::DEFAULT_TOLERANCE`].
    pub tolerance: f64,
    /// `normal_prior`: scale of the normal prior as a fraction of the mean patch size (0
    /// disables it). Default [`IterationOptions::DEFAULT_NORMAL_PRIOR`].
    pub normal_prior: f64,
    /// `fine_solve`: how a default run's fine level solves its systems (issue 31,
    /// `solve::two_level`). Default [`FineSolve::Auto`].
    pub fine_solve: FineSolve,
}

/// How the default's fine level solves its 3D iteration's systems (`fine_solve`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FineSolve {
    /// Two-level from [`FineSolve::AUTO_FROM`] fine vertices when the coarse level converged
    /// (its last update below [`FineSolve::CONVERGED`] × its spacing), else direct.
    Auto,
    /// Conjugate gradients preconditioned by the coarse level's factorisation.
    TwoLevel,
    /// A factorisation of its own.
    Direct,
}

impl FineSolve {
    /// Every choice.
    pub const ALL: [FineSolve; 3] = [FineSolve::Auto, FineSolve::TwoLevel, FineSolve::Direct];

    /// Fine vertices from which `auto` solves two-level. Measured (docs/performance.md): at
    /// 1M vertices two-level took 0.75× (sphere) and 0.62× (globe) of the direct run's time
    /// and 0.67–0.75× its peak; at 20k the torus took 1.7× as long, the others the same.
    pub const AUTO_FROM: usize = 400_000;

    /// The coarse level's last update, ÷ its spacing, below which `auto` counts it converged.
    /// Where it did not (the torus: 0.3 of the spacing, against 0.02 on the sphere), the fine
    /// iteration moves far from its start, the first solves take 9–15 iterations and the run
    /// took 1.1× the direct one's time (1M vertices).
    pub const CONVERGED: f64 = 0.1;

    /// Its name in options.
    pub fn name(self) -> &'static str {
        match self {
            FineSolve::Auto => "auto",
            FineSolve::TwoLevel => "two-level",
            FineSolve::Direct => "direct",
        }
    }
}

impl IterationOptions {
    /// Default `iterations`.
    pub const DEFAULT_ITERATIONS: usize = 2;
    /// Default `inner_steps`.
    pub const DEFAULT_INNER_STEPS: usize = 4;
    /// Default `tolerance` (relative to the spacing).
    pub const DEFAULT_TOLERANCE: f64 = 3e-3;
    /// Default `normal_prior`.
    pub const DEFAULT_NORMAL_PRIOR: f64 = 0.16;
}

impl Default for IterationOptions {
    fn default() -> Self {
        IterationOptions {
            iterations: Self::DEFAULT_ITERATIONS,
            inner_steps: Self::DEFAULT_INNER_STEPS,
            tolerance: Self::DEFAULT_TOLERANCE,
            normal_prior: Self::DEFAULT_NORMAL_PRIOR,
            fine_solve: FineSolve::Auto,
        }
    }
}

/// Parameters of the iteration: the user's settings and the run's scales.
#[derive(Clone, Copy, Debug)]
pub struct IterationParams {
    /// The user's settings.
    pub options: IterationOptions,
    /// Mean patch size `s` (square root of the mean patch area).
    pub patch_size: f64,
    /// Target edge length (for the tolerance).
    pub spacing: f64,
    /// Energy weighting of the fit.
    pub energy: Energy,
    /// The area dividing the guide (eq. 1); on the current surface `Surface` is `Mass`.
    pub guide_area: GuideArea,
    /// Soft-constraint weight per curve vertex (scaled as in normal-control), `None` for hard.
    pub soft_weight: Option<f64>,
}

/// Why the iteration stopped.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Stop {
    /// The update fell below the tolerance.
    Converged,
    /// `max_iterations` were done.
    MaxIterations,
    /// A triangle of the current surface degenerated; the previous surface was kept.
    Degenerate,
    /// The updates grew twice in a row; the surface before the growth was kept.
    Diverging,
}

impl Stop {
    /// The name in the statistics (`iteration_stop`).
    pub fn name(self) -> &'static str {
        match self {
            Stop::Converged => "converged",
            Stop::MaxIterations => "max-iterations",
            Stop::Degenerate => "degenerate",
            Stop::Diverging => "diverging",
        }
    }
}

/// What the iteration did.
#[derive(Clone, Debug)]
pub struct IterationReport {
    /// Largest vertex update of each iteration.
    pub updates: Vec<f64>,
    /// Why it stopped.
    pub stop: Stop,
    /// The systems solved by two-level conjugate gradients (none with factorisations).
    pub cg: CgCounts,
}

/// What the two-level conjugate gradients did in a run's iterations (`solve::two_level`).
#[derive(Clone, Debug, Default, PartialEq, serde::Serialize)]
pub struct CgCounts {
    /// Iterations of each solve, in order.
    pub iterations: Vec<usize>,
    /// Solves that did not converge and were factorised instead.
    pub fallbacks: usize,
    /// The largest relative residual a converged solve stopped at.
    pub residual: f64,
}

/// Smallest triangle angle below which a surface counts as degenerate for the 3D operators.
const MIN_ANGLE_DEG: f64 = 0.5;

fn degenerate(faces: &[[u32; 3]], p: &[DVec3]) -> bool {
    let limit = MIN_ANGLE_DEG.to_radians().sin();
    faces.iter().any(|f| {
        let [a, b, c] = [p[f[0] as usize], p[f[1] as usize], p[f[2] as usize]];
        let cross = (b - a).cross(c - a).length();
        let (ab, bc, ca) = (a.distance(b), b.distance(c), c.distance(a));
        // sin of the smallest angle = 2·area / (product of the two longest sides).
        let longest = ab.max(bc).max(ca);
        let middle = ab + bc + ca - longest - ab.min(bc).min(ca);
        !(cross > limit * longest * middle)
    })
}

/// The 3D iterations as an object that keeps the symbolic analysis of its systems: the
/// pattern never changes (same faces), so every iteration — and every later run on the same
/// mesh ([`crate::Surfacer`]) — is a numeric refactorisation only.
pub struct Iterated {
    /// The parameters of every run.
    pub params: IterationParams,
    /// The last factorisations of the normals' system and (with open borders, uniform
    /// weighting or soft constraints) of the fit's.
    systems: Option<(Eliminated, Option<Eliminated>)>,
    /// Whether the last iteration's operators are kept with its factorisations, for
    /// [`Iterated::resolve`] ([`crate::Surfacer`]; a one-shot run frees them).
    pub(crate) keep_operators: bool,
    /// The last iteration's operators (when `keep_operators`).
    operators: Option<Operators>,
    /// A coarse level of the same surface whose factorisations precondition conjugate
    /// gradients instead of factorising this level's systems (issue 31; a one-shot default
    /// run's fine level, `solve::two_level`).
    pub(crate) coarse: Option<Arc<Coarse>>,
    /// What those conjugate gradients did in the last run.
    cg: Mutex<CgCounts>,
}

/// One iteration's operators and systems on the current surface `V_k`.
struct Step<'a> {
    mesh: &'a Mesh,
    params: &'a IterationParams,
    ops: Operators,
    inv_m: Vec<f64>,
    /// The fit's row weights.
    w: Vec<f64>,
    /// The first unknown row (0 with soft constraints).
    first: usize,
    /// The prior's weight `μ` (free vertices).
    mu: f64,
}

impl<'a> Step<'a> {
    /// The step on the operators `ops` of a surface: `W` from its areas, the first unknown row
    /// (hard constraints eliminate the curve vertices; soft ones keep every vertex unknown,
    /// normals included: the curve normals are then pulled towards the input ones only, with
    /// the same weight as the positions — sensor normals are noisy too) and the prior's `μ`.
    fn new(mesh: &'a Mesh, params: &'a IterationParams, ops: Operators, left_out: &[bool]) -> Self {
        let o = &params.options;
        let mu = if o.normal_prior > 0.0 { (o.normal_prior * params.patch_size).powi(-4) } else { 0.0 };
        let first = if params.soft_weight.is_some() { 0 } else { mesh.num_curve };
        let inv_m: Vec<f64> = ops.mass.iter().map(|a| 1.0 / a).collect();
        let w = fit_weights(left_out, &inv_m, params.energy);
        Step { mesh, params, ops, inv_m, w, first, mu }
    }

    /// The pull towards a target per row: the soft weight on curve vertices, `μ A_v` elsewhere.
    fn pull(&self, k: usize) -> f64 {
        if k < self.mesh.num_curve {
            self.params.soft_weight.unwrap_or(0.0)
        } else {
            self.mu * self.ops.mass[k]
        }
    }

    /// `q` plus the pull on the diagonal of the unknown rows.
    fn with_prox(&self, mut q: Csc) -> Csc {
        let prox: Vec<f64> = (self.first..self.mesh.num_vertices()).map(|k| self.pull(k)).collect();
        q.add_diagonal(&prox);
        q
    }
}

impl Iterated {
    /// Whether the last iteration's factorisations are kept.
    pub fn is_factored(&self) -> bool {
        self.systems.is_some()
    }

    /// The iterations with `params`, nothing factorised yet.
    pub fn new(params: IterationParams) -> Self {
        Iterated { params, systems: None, keep_operators: false, operators: None, coarse: None, cg: Default::default() }
    }

    /// The last iteration's factorisations (the normals' system and the fit's when it has its
    /// own), taken: a coarse level's, to precondition its fine level.
    pub(crate) fn take_systems(&mut self) -> Option<(Eliminated, Option<Eliminated>)> {
        self.systems.take()
    }

    /// The iterations with `params`, whose first normals' system reuses the symbolic analysis
    /// (ordering, elimination tree, supernodes) of `propagation`, the first solve's
    /// `(Ls M⁻¹ Ls)_ff` on the same mesh: `Ls M⁻¹ Ls + μ M` has its pattern, so the first
    /// iteration is a numeric factorisation only (a different pattern is analysed afresh).
    pub(crate) fn reusing(params: IterationParams, propagation: Option<Eliminated>) -> Self {
        Iterated {
            params,
            systems: propagation.map(|p| (p, None)),
            keep_operators: false,
            operators: None,
            coarse: None,
            cg: Default::default(),
        }
    }

    /// Iterates from `start` (a normal-control result on `mesh`). Returns the final surface
    /// and a report. With soft constraints the curve vertices are unknowns pulled towards
    /// their input positions in every fit (and move freely, without the normal projection).
    pub fn run(
        &mut self,
        mesh: &Mesh,
        start: MethodResult,
        t: &mut SolveTimings,
    ) -> Result<(MethodResult, IterationReport)> {
        self.run_reporting(mesh, start, t, &mut |_, _, _| {})
    }

    /// [`Iterated::run`], calling `step(k, of, update)` after iteration `k` of at most `of`
    /// (`update`: its largest vertex move): progress for long runs.
    pub fn run_reporting(
        &mut self,
        mesh: &Mesh,
        start: MethodResult,
        t: &mut SolveTimings,
        step: &mut dyn FnMut(usize, usize, f64),
    ) -> Result<(MethodResult, IterationReport)> {
        let params = self.params;
        let (n, nc) = (mesh.num_vertices(), mesh.num_curve);
        let mut report = IterationReport { updates: Vec::new(), stop: Stop::MaxIterations, cg: CgCounts::default() };
        std::mem::take(&mut *self.cg.lock().unwrap_or_else(|e| e.into_inner()));
        let mut current = start;
        if n == nc || params.options.iterations == 0 {
            report.stop = Stop::Converged;
            return Ok((current, report));
        }
        // Every iteration assembles the operators on the same faces: cache their pattern.
        let _ = mesh.laplacian_pattern();
        for _ in 0..params.options.iterations {
            let vk = &current.positions;
            if degenerate(&mesh.faces, vk) {
                report.stop = Stop::Degenerate;
                break;
            }
            let (next, normals, h) = self.iteration(mesh, vk, t)?;
            let update = next.iter().zip(vk).map(|(a, b)| a.distance(*b)).fold(0.0, f64::max);
            let growing = report.updates.len() >= 2 && {
                let u = &report.updates;
                update > u[u.len() - 1] && u[u.len() - 1] > u[u.len() - 2]
            };
            report.updates.push(update);
            step(report.updates.len(), params.options.iterations, update);
            if growing {
                report.stop = Stop::Diverging;
                break;
            }
            current = MethodResult { positions: next, propagated_normals: Some(normals), guide_curvature: Some(h) };
            if update < params.options.tolerance * params.spacing {
                report.stop = Stop::Converged;
                break;
            }
        }
        report.cg = std::mem::take(&mut *self.cg.lock().unwrap_or_else(|e| e.into_inner()));
        Ok((current, report))
    }

    /// One iteration from `V_k` = `vk`: operators on `V_k`, the systems (re)factorised, then
    /// steps 2–5 `inner_steps` times. Returns the new positions, normals and guide.
    fn iteration(
        &mut self,
        mesh: &Mesh,
        vk: &[DVec3],
        t: &mut SolveTimings,
    ) -> Result<(Vec<DVec3>, Vec<DVec3>, Vec<f64>)> {
        let params = &self.params;
        let left_out = mesh.fit_row_left_out();
        let closed = !left_out.iter().any(|&b| b);
        let step =
            timed(&mut t.operators, || Step::new(mesh, params, cotan_operators(mesh, Metric::Surface, vk), &left_out));
        let first = step.first;
        if let Some(coarse) = self.coarse.clone() {
            if let Some(result) = self.two_level(&step, &coarse, &left_out, vk, t) {
                return result;
            }
        }
        let q = timed(&mut t.operators, || {
            step.with_prox(product_lower(&step.ops.ls, &step.inv_m, &step.ops.ls, step.first))
        });
        let kept = self.systems.take();
        let normals_system = timed(&mut t.factor, || match &kept {
            Some((c, _)) => c.refactor(&q, "iterated propagation system"),
            None => factor_on(mesh, &q, first, "iterated propagation system"),
        })?;
        // Fit matrix: the normals' one on closed surfaces with the area weighting.
        let fit_own = if closed && params.energy == Energy::Area {
            None
        } else {
            let qf = timed(&mut t.operators, || {
                step.with_prox(product_lower_keeping_pattern(&step.ops.ls, &step.w, &step.ops.ls, first))
            });
            // The normals' system's symbolic analysis, shared (the same pattern).
            Some(timed(&mut t.factor, || match kept.as_ref().and_then(|k| k.1.as_ref()) {
                Some(c) => c.refactor(&qf, "iterated fit system"),
                None => factor_like(mesh, &qf, first, "iterated fit system", Some(&normals_system)),
            })?)
        };
        let fit = fit_own.as_ref().unwrap_or(&normals_system);
        let result = inner_steps(&step, vk, &normals_system, fit, t);
        self.systems = Some((normals_system, fit_own));
        self.operators = self.keep_operators.then_some(step.ops);
        result
    }

    /// The iteration's inner steps with this level's systems solved by conjugate gradients
    /// preconditioned by `coarse` (no factorisation); `None` when its systems are not those
    /// of `coarse` (soft constraints, another fit).
    fn two_level(
        &self,
        step: &Step<'_>,
        coarse: &Coarse,
        left_out: &[bool],
        vk: &[DVec3],
        t: &mut SolveTimings,
    ) -> Option<Result<Stepped>> {
        let (mesh, params) = (step.mesh, step.params);
        let own_fit = left_out.iter().any(|&b| b) || params.energy != Energy::Area;
        if step.first != mesh.num_curve || own_fit != coarse.fit.is_some() || self.keep_operators {
            return None;
        }
        let clock = crate::solve::timing::Instant::now();
        let pull: Vec<f64> =
            (0..mesh.num_vertices()).map(|k| if k < step.first { 0.0 } else { step.pull(k) }).collect();
        let counts = &self.cg;
        let normals =
            Iterative::new(step, (&step.inv_m, &pull), &coarse.normals, coarse, "iterated propagation system", counts);
        let fit = match &coarse.fit {
            Some(f) => Some(Iterative::new(step, (&step.w, &pull), f, coarse, "iterated fit system", counts)?),
            None => None,
        };
        t.operators += crate::solve::timing::seconds_since(clock);
        let normals = normals?;
        *normals.initial.borrow_mut() = coarse.normals_start.as_ref();
        Some(inner_steps(step, vk, &normals, fit.as_ref().map_or(&normals as &dyn System, |f| f as &dyn System), t))
    }

    /// A re-solve on the same mesh after the curve values changed ([`crate::Surfacer`], issue
    /// 31): the start is `previous` (the last result, on this mesh) with the curve vertices at
    /// their new positions and the free vertices moved by the biharmonic extension of their
    /// moves (`Q_ff δ_f = −(Ls M⁻¹ Ls)_fc δ_c`, one solve with the kept factorisation), then
    /// one iteration's inner steps (module docs, steps 2–5) with the kept operators and
    /// factorisations — built on the surface of the last factorisation, not on the start: no
    /// assembly and no factorisation, right-hand sides and triangular solves only. `None` when
    /// nothing is kept (no earlier iteration, or a one-shot run) or the start degenerates.
    pub(crate) fn resolve(
        &mut self,
        mesh: &Mesh,
        previous: &[DVec3],
        t: &mut SolveTimings,
    ) -> Option<Result<(MethodResult, IterationReport)>> {
        let (n, nc) = (mesh.num_vertices(), mesh.num_curve);
        let (normals_system, fit_own) = self.systems.as_ref()?;
        if previous.len() != n || n == nc || self.operators.as_ref()?.mass.len() != n {
            return None;
        }
        let ops = self.operators.take()?;
        let params = &self.params;
        let o = &params.options;
        let clock = crate::solve::timing::Instant::now();
        let step = Step::new(mesh, params, ops, &mesh.fit_row_left_out());
        let first = step.first;
        let mut start = previous.to_vec();
        // Hard constraints: the curve vertices at their new places, the free ones moved with
        // them. (Soft ones keep the last solve's curve vertices, pulled towards the input.)
        if first == nc {
            start[..nc].copy_from_slice(&mesh.positions[..nc]);
            let moves: Vec<DVec3> = (0..nc).map(|k| mesh.positions[k] - previous[k]).collect();
            let energy = LeastSquares { a: &step.ops.ls, w: &step.inv_m, first };
            let rhs = energy.rhs(None, &known_rows(n, nc, &[&moves]));
            let delta = normals_system.solve(rhs);
            for k in nc..n {
                start[k] += DVec3::new(delta[(k - nc, 0)], delta[(k - nc, 1)], delta[(k - nc, 2)]);
            }
        }
        t.solve += crate::solve::timing::seconds_since(clock);
        if degenerate(&mesh.faces, &start) {
            self.operators = Some(step.ops);
            return None;
        }
        let fit = fit_own.as_ref().unwrap_or(normals_system);
        let result = inner_steps(&step, &start, normals_system, fit, t).map(|(next, normals, h)| {
            let update = next.iter().zip(&start).map(|(a, b)| a.distance(*b)).fold(0.0, f64::max);
            let stop = if update < o.tolerance * params.spacing { Stop::Converged } else { Stop::MaxIterations };
            let result = MethodResult { positions: next, propagated_normals: Some(normals), guide_curvature: Some(h) };
            (result, IterationReport { updates: vec![update], stop, cg: CgCounts::default() })
        });
        self.operators = Some(step.ops);
        Some(result)
    }
}

/// What an iteration's inner steps give: the positions, the propagated normals, the guide.
type Stepped = (Vec<DVec3>, Vec<DVec3>, Vec<f64>);

/// Conjugate gradients on the fit stop when an iteration moves no coordinate by more than this
/// × the spacing (the 3D iterations' own tolerance is 3e-3: the solve's error stays well
/// below what they resolve).
const CG_POSITION_STEP: f64 = 3e-4;

/// Conjugate gradients on the normals stop when an iteration moves no component by more than
/// this (unit vectors).
const CG_NORMAL_STEP: f64 = 3e-5;

/// A system of one iteration: factorised, or solved by conjugate gradients.
trait System {
    /// `Q X = rhs` on the unknown rows; `start` gives their current values, `step` the largest
    /// move of an iteration that counts as converged, measured along `along`'s rows when
    /// given (for iterative solves only).
    fn solve_from(
        &self,
        rhs: Mat<f64>,
        start: &dyn Fn() -> Mat<f64>,
        step: f64,
        along: Option<&Mat<f64>>,
    ) -> Result<Mat<f64>>;
}

impl System for Eliminated {
    fn solve_from(&self, rhs: Mat<f64>, _: &dyn Fn() -> Mat<f64>, _: f64, _: Option<&Mat<f64>>) -> Result<Mat<f64>> {
        Ok(self.solve(rhs))
    }
}

/// A fine system solved by two-level conjugate gradients ([`FineSystem`]), factorised after
/// the first solve that does not converge (and then used as such; that factorisation's time
/// counts as the solve's).
struct Iterative<'a> {
    system: FineSystem<'a>,
    step: &'a Step<'a>,
    /// The system's row weights `W`.
    w: &'a [f64],
    what: &'static str,
    fallback: OnceCell<Eliminated>,
    counts: &'a Mutex<CgCounts>,
    /// The first solve's start, when better than the caller's (its zero rows are the
    /// caller's).
    initial: RefCell<Option<&'a Mat<f64>>>,
}

impl<'a> Iterative<'a> {
    /// `Ls W Ls + pull` of `step`, preconditioned by `coarse` (its coarse counterpart) through
    /// the prolongation of `level`.
    fn new(
        step: &'a Step<'a>,
        (w, pull): (&'a [f64], &'a [f64]),
        coarse: &'a Eliminated,
        level: &'a Coarse,
        what: &'static str,
        counts: &'a Mutex<CgCounts>,
    ) -> Option<Self> {
        let q = Quadratic::new(&step.ops.ls, w, pull, step.first);
        let system = FineSystem::new(q, coarse, &level.p, &level.pt)?;
        Some(Iterative { system, step, w, what, fallback: OnceCell::new(), counts, initial: RefCell::new(None) })
    }
}

impl System for Iterative<'_> {
    fn solve_from(
        &self,
        rhs: Mat<f64>,
        start: &dyn Fn() -> Mat<f64>,
        step: f64,
        along: Option<&Mat<f64>>,
    ) -> Result<Mat<f64>> {
        if let Some(f) = self.fallback.get() {
            return Ok(f.solve(rhs));
        }
        let mut st = start();
        if let Some(initial) = self.initial.take().filter(|m| m.nrows() == st.nrows() && m.ncols() == st.ncols()) {
            for i in 0..st.nrows() {
                if (0..st.ncols()).any(|c| initial[(i, c)] != 0.0) {
                    for c in 0..st.ncols() {
                        st[(i, c)] = initial[(i, c)];
                    }
                }
            }
        }
        let (x, report) = self.system.solve(&rhs, st, step, along);
        {
            let mut counts = self.counts.lock().unwrap_or_else(|e| e.into_inner());
            counts.iterations.push(report.iterations);
            if report.converged && x.is_all_finite() {
                counts.residual = counts.residual.max(report.residuals.last().copied().unwrap_or(0.0));
                return Ok(x);
            }
            counts.fallbacks += 1;
        }
        let s = self.step;
        let q = s.with_prox(product_lower(&s.ops.ls, self.w, &s.ops.ls, s.first));
        let f = factor_on(s.mesh, &q, s.first, self.what)?;
        let x = f.solve(rhs);
        let _ = self.fallback.set(f);
        Ok(x)
    }
}

/// The rows `first..` of `x` as a matrix (the unknowns' current values).
fn unknown_rows(x: &[DVec3], first: usize) -> Mat<f64> {
    Mat::from_fn(x.len() - first, 3, |i, c| x[first + i][c])
}

/// Steps 2–5 of the module documentation, `inner_steps` times on the operators and
/// factorisations of one iteration (each repeat costs only triangular solves: the normals'
/// pull and the proximal term relax slowly).
fn inner_steps(
    step: &Step<'_>,
    vk: &[DVec3],
    normals_system: &dyn System,
    fit: &dyn System,
    t: &mut SolveTimings,
) -> Result<(Vec<DVec3>, Vec<DVec3>, Vec<f64>)> {
    let (mesh, params, first) = (step.mesh, step.params, step.first);
    let (n, nc) = (mesh.num_vertices(), mesh.num_curve);
    let known_normals = known_rows(n, first, &[&mesh.curve_normals]);
    let known = if first == 0 { Mat::<f64>::zeros(n, 3) } else { known_rows(n, nc, &[&mesh.positions]) };
    let nk = vertex_normals(&mesh.faces, vk);
    // Step 5 keeps the normal part of the fit's move only: its iterative solve stops on that.
    let normal_rows = unknown_rows(&nk, first);
    let mut v = vk.to_vec();
    let mut normals = Vec::new();
    let mut h = Vec::new();
    // The last solutions, the next iterative solves' starts (closer than the normalised
    // normals and the projected positions: the fit's tangential part is left out of `v`).
    let (mut last_normals, mut last_fit): (Option<Mat<f64>>, Option<Mat<f64>>) = (None, None);
    for inner in 0..params.options.inner_steps.max(1) {
        let clock = crate::solve::timing::Instant::now();
        // 2. Normals, pulled towards the current surface's.
        let prior = if inner == 0 { nk.clone() } else { vertex_normals(&mesh.faces, &v) };
        let seam = seam_normal_targets(mesh, &step.ops.ls, &prior);
        let mut rhs = LeastSquares { a: &step.ops.ls, w: &step.inv_m, first }.rhs(seam.as_ref(), &known_normals);
        for k in first..n {
            let target = if k < nc { mesh.curve_normals[k] } else { prior[k] };
            for c in 0..3 {
                rhs[(k - first, c)] += step.pull(k) * target[c];
            }
        }
        let start = || last_normals.clone().unwrap_or_else(|| unknown_rows(&prior, first));
        let sol = normals_system.solve_from(rhs, &start, CG_NORMAL_STEP, None)?;
        normals = mesh.curve_normals.clone();
        normals.resize(n, DVec3::ZERO);
        scatter(&sol, 0, first, &mut normals);
        last_normals = Some(sol);
        for (k, x) in normals.iter_mut().enumerate().skip(first) {
            let u = x.normalize_or_zero();
            *x = if u == DVec3::ZERO || !u.is_finite() { prior[k] } else { u };
        }
        // 3. Guide on the current surface.
        let area = match params.guide_area {
            GuideArea::Barycentric => &step.ops.barycentric,
            GuideArea::Mass | GuideArea::Surface => &step.ops.mass,
        };
        h = blended_mean_curvature(&mesh.faces, &v, &normals, area, &mesh.on_boundary);
        if let Some(i) = h.iter().position(|x| !x.is_finite()) {
            return Err(Error::numerical(format!("iterated guide is not finite at vertex {i}")).vertex(i));
        }
        let mut b = Mat::<f64>::zeros(n, 3);
        for k in 0..n {
            let s = -2.0 * step.ops.mass[k] * h[k];
            for c in 0..3 {
                b[(k, c)] = s * normals[k][c];
            }
        }
        seam_targets(mesh, &step.ops.mass, &normals, &mut h, &mut b);
        // 4. Fit, with the proximal pull (and the soft pull of the curve vertices).
        let mut rhs = LeastSquares { a: &step.ops.ls, w: &step.w, first }.rhs(Some(&b), &known);
        for k in first..n {
            let target = if k < nc { mesh.positions[k] } else { v[k] };
            for c in 0..3 {
                rhs[(k - first, c)] += step.pull(k) * target[c];
            }
        }
        let start = || last_fit.clone().unwrap_or_else(|| unknown_rows(&v, first));
        let sol = fit.solve_from(rhs, &start, CG_POSITION_STEP * params.spacing, Some(&normal_rows))?;
        let mut next = v.clone();
        scatter(&sol, 0, first, &mut next);
        last_fit = Some(sol);
        // 5. Normal component of the move from V_k only (free vertices; soft curve vertices
        // move freely).
        let mut moved = 0.0f64;
        for k in 0..n {
            if k >= nc {
                next[k] = vk[k] + nk[k] * (next[k] - vk[k]).dot(nk[k]);
            }
            moved = moved.max(next[k].distance(v[k]));
        }
        check_finite(&next, "iterated fit")?;
        v = next;
        t.solve += crate::solve::timing::seconds_since(clock);
        if moved < params.options.tolerance * params.spacing {
            break;
        }
    }
    Ok((v, normals, h))
}

/// Iterates once from `start` without keeping the factorisations (see [`Iterated::run`]).
pub fn iterate(
    mesh: &Mesh,
    start: MethodResult,
    params: &IterationParams,
    t: &mut SolveTimings,
) -> Result<(MethodResult, IterationReport)> {
    Iterated::new(*params).run(mesh, start, t)
}

#[cfg(test)]
#[path = "tests/iterated.rs"]
mod tests;
