//! The surfacing options shared by `surface` and `study`, mapped one to one onto
//! [`curvenet::Options`].

use clap::{Args, ValueEnum};
use curvenet::{GuideArea, Method, Options, Patching, Weighting};

#[derive(Clone, Copy, ValueEnum)]
pub enum MethodArg {
    /// [CG] eq. 1–3: normals propagated, signed mean curvature, L V = −2 H N*.
    NormalControl,
    /// Δ²V = 0 with the curves fixed (positions only).
    Biharmonic,
    /// Δ³V = 0 with the curves fixed (positions only).
    Triharmonic,
    /// [CG] eq. 4: Δ²V = 0 with ΔV = −2Hn prescribed on the curves.
    Method4,
    /// The short paper's energy: ‖Δ²V‖² + w1 ‖ΔV + 2H n*‖² (+ soft).
    ShortPaper,
    /// Andrews et al. 2011: Δᵏ V = 0 (--order) with ghost-vertex Cauchy constraints on the curves
    /// (per-curve kind/sharpness/stretch in the JSON; docs/cauchy.md).
    Cauchy,
}

#[derive(Clone, Copy, ValueEnum)]
pub enum PatchingArg {
    /// Each patch triangulated in the plane of its mean point and mean normal (the paper).
    Planar,
    /// Each patch re-triangulated in a conformal flattening of a first solution, then solved again.
    Conformal,
}

#[derive(Clone, Copy, ValueEnum)]
pub enum EnergyArg {
    /// Σ A_v ‖ΔV + 2H n*‖²: one factorisation serves propagation and fit.
    Area,
    /// Σ ‖ΔV + 2H n*‖² as written in the paper.
    Uniform,
}

#[derive(Clone, Copy, ValueEnum)]
pub enum GuideAreaArg {
    /// The Laplacian's own Voronoi area (consistent with the fit; removes most planar bias).
    Mass,
    /// The Voronoi area on the propagated surface V*, as the paper states it.
    Surface,
}

/// The options of a surfacing run, shared by the commands that surface.
#[derive(Args, Clone)]
pub struct SolveArgs {
    /// Surfacing method.
    #[arg(long, value_enum, default_value = "normal-control")]
    pub method: MethodArg,
    /// Target edge length of the mesh and sampling distance along the curves.
    #[arg(long, value_name = "D", conflicts_with = "vertices")]
    pub spacing: Option<f64>,
    /// Approximate total number of vertices (used when --spacing is not given).
    #[arg(long, value_name = "N", default_value_t = Options::DEFAULT_VERTICES)]
    pub vertices: usize,
    /// Soft curve constraints: the surface may leave the curves to smooth out deviations shorter
    /// than about S input sample spacings (S ≈ 1–3 for sensor noise). normal-control and
    /// short-paper (where it is the short paper's w0).
    #[arg(long, value_name = "S", alias = "w0")]
    pub soft: Option<f64>,
    /// Weight of the curvature guide in --method short-paper, dimensionless (ω₁ = W / s⁴, s the
    /// mean patch size).
    #[arg(long, value_name = "W", default_value_t = Options::DEFAULT_W1)]
    pub w1: f64,
    /// Domain each patch is triangulated in.
    #[arg(long, value_enum, default_value = "conformal")]
    pub patching: PatchingArg,
    /// Iterations with cotangent weights rebuilt on the 3D surface (0: the paper's planar weights).
    /// The loop stops earlier when it converges.
    #[arg(long, value_name = "K", default_value_t = Options::DEFAULT_ITERATIONS)]
    pub iterations: usize,
    /// Per iteration, repeats of the normal pull and the fit on the same factorisation.
    #[arg(long, value_name = "N", default_value_t = Options::DEFAULT_INNER_STEPS)]
    pub inner_steps: usize,
    /// Convergence threshold of the iterations: largest vertex move, as a fraction of the spacing.
    #[arg(long, value_name = "T", default_value_t = Options::DEFAULT_TOLERANCE)]
    pub tolerance: f64,
    /// Scale of the iterations' pull of the propagated normals towards the surface's, as a
    /// fraction of the mean patch size (0: none).
    #[arg(long, value_name = "S", default_value_t = Options::DEFAULT_NORMAL_PRIOR)]
    pub normal_prior: f64,
    /// Weighting of the normal-control energy.
    #[arg(long, value_enum, default_value = "area")]
    pub energy: EnergyArg,
    /// Area dividing the mean-curvature guide ([CG] eq. 1).
    #[arg(long, value_enum, default_value = "mass")]
    pub guide_area: GuideAreaArg,
    /// Times the mean-curvature guide is re-estimated on the fitted surface and the fit repeated
    /// (cheap: same factorisation). 0 reproduces the paper.
    #[arg(long, value_name = "K", default_value_t = 1)]
    pub guide_updates: usize,
    /// Snapping tolerance: curves closer than this meet at a node [default: the network's "snap",
    /// else 1e-3 × its bounding-box diagonal].
    #[arg(long, value_name = "S")]
    pub snap: Option<f64>,
    /// Laplacian order of --method cauchy (1, 2 or 3).
    #[arg(long, value_name = "K", default_value_t = 2)]
    pub order: usize,
    /// Re-solves of --method cauchy with centred ghost vertices (0: the paper's ghosts).
    #[arg(long, value_name = "N", default_value_t = 10)]
    pub ghost_updates: usize,
    /// The fast single pass: planar patching and weights, no iterations (one factorisation).
    #[arg(long, conflicts_with = "paper")]
    pub fast: bool,
    /// Reproduce the paper exactly: planar patching and weights, unweighted energy, eq. 1 divided
    /// by the area on V*, no guide update, no iteration (overrides those options).
    #[arg(long)]
    pub paper: bool,
}

/// The library options the flags select (`--paper` resets the method's details).
pub fn options(a: &SolveArgs) -> Options {
    let o = explicit_options(a);
    if a.fast {
        return Options { patching: curvenet::Patching::Planar, iterations: 0, ..o };
    }
    if a.paper {
        return Options {
            method: o.method,
            spacing: o.spacing,
            vertices: o.vertices,
            soft: o.soft,
            snap: o.snap,
            order: o.order,
            // [A11]'s own ghosts for --method cauchy.
            ghost_updates: 0,
            ..Options::paper()
        };
    }
    o
}

fn explicit_options(a: &SolveArgs) -> Options {
    Options {
        method: match a.method {
            MethodArg::NormalControl => Method::NormalControl,
            MethodArg::Biharmonic => Method::Biharmonic,
            MethodArg::Triharmonic => Method::Triharmonic,
            MethodArg::Method4 => Method::Method4,
            MethodArg::ShortPaper => Method::ShortPaper,
            MethodArg::Cauchy => Method::Cauchy,
        },
        spacing: a.spacing,
        vertices: Some(a.vertices),
        soft: a.soft,
        w1: a.w1,
        patching: match a.patching {
            PatchingArg::Planar => Patching::Planar,
            PatchingArg::Conformal => Patching::Conformal,
        },
        iterations: a.iterations,
        inner_steps: a.inner_steps,
        tolerance: a.tolerance,
        normal_prior: a.normal_prior,
        energy: match a.energy {
            EnergyArg::Area => Weighting::Area,
            EnergyArg::Uniform => Weighting::Uniform,
        },
        guide_area: match a.guide_area {
            GuideAreaArg::Mass => GuideArea::Mass,
            GuideAreaArg::Surface => GuideArea::Surface,
        },
        guide_updates: a.guide_updates,
        snap: a.snap,
        order: a.order,
        cauchy: None,
        ghost_updates: a.ghost_updates,
    }
}
