//! The options of a surfacing run: one set of names for the library, the command line and
//! Python (docs/design.md §6).
//!
//! [`Options`] nests the settings by where they act: the mesh ([`MeshOptions`]), and each
//! method's own struct ([`NormalControlOptions`], [`IterationOptions`],
//! [`ShortPaperOptions`], [`CauchyOptions`]). Every leaf has one name, listed in [`OPTIONS`]
//! with its documentation; front ends set options by that name ([`Options::set`]): the
//! command line as `--name` (dashes for underscores), Python as the keyword `name=`. Presets
//! ([`Preset`]) are defined here only; explicit values override the preset.

use crate::error::{Error, Result};
use crate::methods::andrews2011::CauchyOptions;
use crate::methods::eg2016::ShortPaperOptions;
use crate::methods::iterated::{FineSolve, IterationOptions};
use crate::methods::normal_control::NormalControlOptions;
use crate::methods::{Energy, GuideArea, Method};
use crate::topology::consolidate::ConsolidateOptions;

/// The domain each patch is triangulated in (option `patching`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Patching {
    /// The plane of the cycle's mean point and mean normal (\[CG\] §3.3).
    #[default]
    Planar,
    /// A conformal flattening (LSCM) of the patch on a first solution: triangles keep their
    /// shape on the surface and the "planar" cotangent weights are nearly the surface's.
    Conformal,
}

impl Patching {
    /// Every choice.
    pub const ALL: [Patching; 2] = [Patching::Planar, Patching::Conformal];

    /// The name used in options and files.
    pub fn name(self) -> &'static str {
        match self {
            Patching::Planar => "planar",
            Patching::Conformal => "conformal",
        }
    }
}

/// Which curves' normals are inferred (option `infer_normals`, docs/design.md §12).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum InferNormals {
    /// Only those of curves that come without normals (given normals win).
    #[default]
    Missing,
    /// Every curve's, given normals ignored (to compare with them).
    All,
}

impl InferNormals {
    /// Every choice.
    pub const ALL: [InferNormals; 2] = [InferNormals::Missing, InferNormals::All];

    /// The name used in options: `missing`, `all`.
    pub fn name(self) -> &'static str {
        match self {
            InferNormals::Missing => "missing",
            InferNormals::All => "all",
        }
    }
}

/// How the mesh is built: its resolution, where curves meet, the patches' domains.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MeshOptions {
    /// `spacing`: target edge length `d` of the mesh (and curve sampling distance). Overrides
    /// `vertices`.
    pub spacing: Option<f64>,
    /// `spacing` given as a share of the network's bounding-box diagonal (`"1%"`: 0.01), used
    /// when `spacing` is `None`; overrides `vertices`.
    pub spacing_relative: Option<f64>,
    /// `vertices`: approximate total vertex count, used when `spacing` is not given. `None`:
    /// [`MeshOptions::DEFAULT_VERTICES`].
    pub vertices: Option<usize>,
    /// `snap`: curves closer than this meet at a node, also between samples. `None`: the
    /// network's `snap`, else [`crate::Network::snap_tolerance`].
    pub snap: Option<f64>,
    /// `patching`: the domain each patch is triangulated in. Default
    /// [`MeshOptions::DEFAULT_PATCHING`].
    pub patching: Patching,
    /// `max_memory`: the most memory (bytes) a run may take; a run whose estimated peak is
    /// larger is refused before it allocates ([`crate::pipeline::budget`]). `None`: the memory
    /// available (the process's address-space limit, the machine's available memory).
    pub max_memory: Option<f64>,
}

impl MeshOptions {
    /// Default approximate vertex count.
    pub const DEFAULT_VERTICES: usize = 20_000;
    /// Largest mesh a run may create (a guard against a mistyped spacing).
    pub const MAX_VERTICES: f64 = 5e7;
    /// Default `patching`: the conformal flattening (4× more accurate than the projection on
    /// the sphere, docs/accuracy.md).
    pub const DEFAULT_PATCHING: Patching = Patching::Conformal;
}

impl Default for MeshOptions {
    fn default() -> Self {
        MeshOptions {
            spacing: None,
            spacing_relative: None,
            vertices: None,
            snap: None,
            patching: Self::DEFAULT_PATCHING,
            max_memory: None,
        }
    }
}

/// Options of a surfacing run (docs/design.md §6). The leaves' names are the option names of
/// every front end ([`OPTIONS`]).
#[derive(Clone, Debug, PartialEq, Default)]
pub struct Options {
    /// `method`: the surfacing method. Default [`Method::NormalControl`].
    pub method: Method,
    /// The mesh: `spacing`, `vertices`, `snap`, `patching`.
    pub mesh: MeshOptions,
    /// `soft`: soft curve constraints (\[CG\] §4.5) instead of hard ones: the surface may leave
    /// the curves to smooth out deviations shorter than about `S` input sample spacings
    /// (`S ≈ 1–3` for sensor noise). With the iterations, the curve normals are soft too. The
    /// penalty is `ω Σ_s ‖v_s − v*_s‖²` with `ω = d / λ³`, `λ = S h`, `d` the spacing and `h`
    /// the mean input sample spacing: a deviation of wavelength `λ` costs as much in the
    /// penalty as in the fit energy, independently of scale and resolution. normal-control
    /// and short-paper only. `None`: hard constraints.
    pub soft: Option<f64>,
    /// normal-control: `energy`, `guide_area`, `guide_updates`.
    pub normal_control: NormalControlOptions,
    /// The 3D iterations of normal-control: `iterations`, `inner_steps`, `tolerance`,
    /// `normal_prior`, `fine_solve`.
    pub iterate: IterationOptions,
    /// short-paper: `w1`.
    pub short_paper: ShortPaperOptions,
    /// cauchy: `order`, `ghost_updates`, and the per-curve attributes.
    pub cauchy: CauchyOptions,
    /// `infer_normals`: which curves' normals are inferred ([`crate::pipeline::infer`]).
    pub infer_normals: InferNormals,
    /// `consolidate`, `gap`: raw strokes joined, merged and trimmed before node finding
    /// ([`crate::topology::consolidate`]).
    pub consolidate: ConsolidateOptions,
}

/// A named starting point for the options, defined here only; explicit values override it.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Preset {
    /// Conformal patching and the 3D iterations: curvenet's accurate default.
    #[default]
    Default,
    /// The fast single pass: the paper's planar patching and weights with the consistent guide
    /// and one guide update (one factorisation; sphere 1e-3, torus 0.2 mean error at 20k
    /// vertices — the default is 4× (sphere) to 80× (torus) more accurate for 2–3× the time).
    Fast,
    /// The method as the paper describes it (\[CG\] §3): planar projections and planar weights,
    /// the unweighted energy of eq. 2, eq. 1 divided by the area on `V*`, no guide update, no
    /// iteration; for `cauchy`, \[A11\]'s own ghost vertices (no update). A faithful
    /// implementation measured 0.0085 mean distance on the sphere.
    Paper,
}

impl Preset {
    /// Every preset.
    pub const ALL: [Preset; 3] = [Preset::Default, Preset::Fast, Preset::Paper];

    /// The preset's name: `default`, `fast`, `paper`.
    pub fn name(self) -> &'static str {
        match self {
            Preset::Default => "default",
            Preset::Fast => "fast",
            Preset::Paper => "paper",
        }
    }

    /// The preset called `name`; a usage error listing the presets otherwise.
    pub fn from_name(name: &str) -> Result<Self> {
        Self::ALL
            .into_iter()
            .find(|p| p.name() == name)
            .ok_or_else(|| Error::usage(format!("unknown preset \"{name}\" (default, fast, paper)")))
    }
}

impl Options {
    /// The options of `preset`.
    pub fn preset(preset: Preset) -> Self {
        let default = Options::default();
        match preset {
            Preset::Default => default,
            Preset::Fast => Options {
                mesh: MeshOptions { patching: Patching::Planar, ..default.mesh },
                iterate: IterationOptions { iterations: 0, ..default.iterate },
                normal_control: NormalControlOptions { guide_area: GuideArea::Mass, ..default.normal_control },
                ..default
            },
            Preset::Paper => Options {
                mesh: MeshOptions { patching: Patching::Planar, ..default.mesh },
                iterate: IterationOptions { iterations: 0, ..default.iterate },
                normal_control: NormalControlOptions {
                    energy: Energy::Uniform,
                    guide_area: GuideArea::Surface,
                    guide_updates: 0,
                },
                cauchy: CauchyOptions { ghost_updates: 0, ..default.cauchy },
                ..default
            },
        }
    }

    /// [`Preset::Fast`].
    pub fn fast() -> Self {
        Self::preset(Preset::Fast)
    }

    /// [`Preset::Paper`].
    pub fn paper() -> Self {
        Self::preset(Preset::Paper)
    }

    /// These options with `vertices = n` (and no `spacing`).
    pub fn with_vertices(mut self, n: usize) -> Self {
        self.mesh.vertices = Some(n);
        self.mesh.spacing = None;
        self.mesh.spacing_relative = None;
        self
    }

    /// These options with `spacing = d`.
    pub fn with_spacing(mut self, d: f64) -> Self {
        self.mesh.spacing = Some(d);
        self.mesh.spacing_relative = None;
        self
    }

    /// These options with `method = m`.
    pub fn with_method(mut self, m: Method) -> Self {
        self.method = m;
        self
    }

    /// The options of `preset` with the named values `given` set over it ([`Options::set`]),
    /// as every front end builds them. `spacing` and `vertices` together are a usage error.
    pub fn from_named(preset: Preset, given: &[(&str, &str)]) -> Result<Self> {
        if given.iter().any(|g| g.0 == "spacing") && given.iter().any(|g| g.0 == "vertices") {
            return Err(Error::usage("give `spacing` or `vertices`, not both"));
        }
        let mut o = Options::preset(preset);
        for (name, value) in given {
            o.set(name, value)?;
        }
        Ok(o)
    }

    /// Sets the option `name` ([`OPTIONS`]) from its text `value`, parsed as its type (a number,
    /// a whole number, a choice by name). Errors with [`Error::Usage`] naming the option and
    /// what it takes; the options are unchanged then.
    pub fn set(&mut self, name: &str, value: &str) -> Result<()> {
        let spec = OPTIONS.iter().find(|s| s.name == name).ok_or_else(|| {
            let names: Vec<&str> = OPTIONS.iter().map(|s| s.name).collect();
            Error::usage(format!("unknown option \"{name}\"; the options are {}", names.join(", ")))
        })?;
        (spec.set)(self, value.trim())
            .map_err(|takes| Error::usage(format!("option `{name}` takes {takes}, not \"{value}\"")))
    }

    /// The value of option `name` as text (`None` for an unset optional value or an unknown
    /// name): what [`Options::set`] takes back.
    pub fn get(&self, name: &str) -> Option<String> {
        OPTIONS.iter().find(|s| s.name == name).and_then(|s| (s.get)(self))
    }
}

/// One option as front ends see it: its name, what it takes, what it does.
pub struct OptionSpec {
    /// The name: the field's name in its struct; `--name` (dashes) on the command line, the
    /// keyword `name` in Python.
    pub name: &'static str,
    /// A placeholder for the value in help texts (`D`, `N`, …), or the choices.
    pub value_name: &'static str,
    /// The choices of a named value (empty for numbers).
    pub choices: &'static [&'static str],
    /// What it does (one paragraph).
    pub help: &'static str,
    /// The default when the value is unset (`None` in [`Options::default`]), in words.
    pub unset: Option<&'static str>,
    /// Other names the command line accepts.
    pub aliases: &'static [&'static str],
    set: fn(&mut Options, &str) -> std::result::Result<(), &'static str>,
    get: fn(&Options) -> Option<String>,
}

impl OptionSpec {
    /// The default value as text: that of [`Options::default`], or the `unset` words.
    pub fn default_text(&self) -> String {
        (self.get)(&Options::default()).or(self.unset.map(str::to_string)).unwrap_or_default()
    }
}

impl std::fmt::Debug for OptionSpec {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("OptionSpec").field("name", &self.name).finish_non_exhaustive()
    }
}

fn number(v: &str) -> std::result::Result<f64, &'static str> {
    v.parse::<f64>().ok().filter(|x| x.is_finite()).ok_or("a finite number")
}

/// A size in bytes: a number with an optional K, M, G or T suffix (powers of 1024), above 0.
fn bytes(v: &str) -> Option<f64> {
    let v = v.trim();
    let (digits, scale) = match v.char_indices().last() {
        Some((i, c)) if c.is_ascii_alphabetic() => {
            let scale = match c.to_ascii_uppercase() {
                'K' => 1024f64,
                'M' => 1024f64.powi(2),
                'G' => 1024f64.powi(3),
                'T' => 1024f64.powi(4),
                _ => return None,
            };
            (&v[..i], scale)
        }
        _ => (v, 1.0),
    };
    let x = number(digits).ok()? * scale;
    (x.is_finite() && x > 0.0).then_some(x)
}

/// The most iterations, inner steps or updates an option takes: each one is a solve, and the
/// iterations stop at convergence (`tolerance`) well before.
pub const MAX_ITERATION_COUNT: usize = 1000;

/// A count of iterations or updates: a whole number up to [`MAX_ITERATION_COUNT`].
fn bounded_count(v: &str) -> std::result::Result<usize, &'static str> {
    count(v).ok().filter(|&n| n <= MAX_ITERATION_COUNT).ok_or("a whole number from 0 to 1000")
}

fn count(v: &str) -> std::result::Result<usize, &'static str> {
    v.parse::<usize>().map_err(|_| "a whole number ≥ 0")
}

/// The choice named `v`; names are spelled with dashes, and underscores are taken for them
/// (Python keywords and values are written with underscores: `method="normal_control"`).
fn choice<T: Copy>(
    all: &[T],
    name: fn(T) -> &'static str,
    v: &str,
    takes: &'static str,
) -> std::result::Result<T, &'static str> {
    let v = v.replace('_', "-");
    all.iter().copied().find(|c| name(*c) == v).ok_or(takes)
}

/// Text of a number that parses back to the same `f64` (Rust's shortest round-trip form).
fn text(x: f64) -> String {
    format!("{x:?}")
}

/// Every surfacing option, in the order of `curvenet surface --help`.
pub const OPTIONS: &[OptionSpec] = &[
    OptionSpec {
        name: "method",
        value_name: "M",
        choices: &["normal-control", "biharmonic", "triharmonic", "method4", "short-paper", "cauchy"],
        help: "Surfacing method: normal-control ([CG] eq. 1–3: normals propagated, signed mean curvature, \
               L V = −2 H N*), biharmonic (Δ²V = 0 with the curves fixed), triharmonic (Δ³V = 0), method4 \
               ([CG] eq. 4: Δ²V = 0 with ΔV = −2Hn on the curves), short-paper ([EG]: ‖Δ²V‖² + ω₁ ‖ΔV + 2H n*‖²), \
               cauchy (Andrews et al. 2011: Δᵏ V = 0 with ghost-vertex Cauchy constraints; per-curve kind, \
               sharpness, stretch from the network JSON, docs/cauchy.md).",
        unset: None,
        aliases: &[],
        set: |o, v| {
            o.method = choice(&Method::ALL, Method::name, v, "one of normal-control, biharmonic, triharmonic, method4, short-paper, cauchy")?;
            Ok(())
        },
        get: |o| Some(o.method.name().to_string()),
    },
    OptionSpec {
        name: "spacing",
        value_name: "D",
        choices: &[],
        help: "Target edge length of the mesh and sampling distance along the curves, a distance or a share of \
               the network's bounding-box diagonal (`1%`); overrides `vertices`. Each segment between nodes gets \
               round(ℓ/D) pieces, so nodes stay exact. A spacing that makes more than 10× the default vertex count, \
               or a run estimated over a minute, is a warning before the run.",
        unset: Some("from `vertices`"),
        aliases: &[],
        set: |o, v| {
            let takes = "a positive distance, or a percentage of the bounding-box diagonal (`1%`)";
            if let Some(p) = v.strip_suffix('%') {
                let p = number(p.trim()).ok().filter(|p| *p > 0.0 && *p <= 100.0).ok_or(takes)?;
                (o.mesh.spacing, o.mesh.spacing_relative) = (None, Some(p / 100.0));
            } else {
                (o.mesh.spacing, o.mesh.spacing_relative) = (Some(number(v).ok().filter(|d| *d > 0.0).ok_or(takes)?), None);
            }
            Ok(())
        },
        // The percentage rounded to 12 digits (7 % is 0.07, and 100 × 0.07 is 7.000000000000001).
        get: |o| {
            o.mesh.spacing.map(text).or_else(|| o.mesh.spacing_relative.map(|f| format!("{}%", text((1e12 * f).round() / 1e10))))
        },
    },
    OptionSpec {
        name: "vertices",
        value_name: "N",
        choices: &[],
        help: "Approximate total number of vertices (sets the spacing when `spacing` is not given).",
        unset: Some("20000"),
        aliases: &[],
        set: |o, v| {
            o.mesh.vertices = Some(count(v).ok().filter(|n| *n > 0).ok_or("a positive whole number")?);
            Ok(())
        },
        get: |o| o.mesh.vertices.map(|n| n.to_string()),
    },
    OptionSpec {
        name: "soft",
        value_name: "S",
        choices: &[],
        help: "Soft curve constraints ([CG] §4.5): the surface may leave the curves to smooth out deviations \
               shorter than about S input sample spacings (S ≈ 1–2 filters sensor noise); with the iterations \
               the curve normals are soft too. normal-control and short-paper (where it is the short paper's w0).",
        unset: Some("hard constraints"),
        aliases: &["w0"],
        set: |o, v| {
            o.soft = Some(number(v).ok().filter(|s| *s > 0.0).ok_or("a positive number")?);
            Ok(())
        },
        get: |o| o.soft.map(text),
    },
    OptionSpec {
        name: "patching",
        value_name: "planar|conformal",
        choices: &["planar", "conformal"],
        help: "The domain each patch is triangulated in: the plane of its mean point and mean normal \
               ([CG] §3.3), or a conformal flattening (LSCM) of a first, coarse solution, in which \
               triangles keep their shape on the surface.",
        unset: None,
        aliases: &[],
        set: |o, v| {
            o.mesh.patching = choice(&Patching::ALL, Patching::name, v, "planar or conformal")?;
            Ok(())
        },
        get: |o| Some(o.mesh.patching.name().to_string()),
    },
    OptionSpec {
        name: "iterations",
        value_name: "K",
        choices: &[],
        help: "normal-control iterations with cotangent weights and areas rebuilt on the 3D surface (removes \
               the planar-metric bias, [CG] §5); stops earlier when converged. 0: the weights of the patches' \
               domains. The baselines always use those.",
        unset: None,
        aliases: &[],
        set: |o, v| {
            o.iterate.iterations = bounded_count(v)?;
            Ok(())
        },
        get: |o| Some(o.iterate.iterations.to_string()),
    },
    OptionSpec {
        name: "inner_steps",
        value_name: "N",
        choices: &[],
        help: "Per iteration, repeats of the normals' pull and the fit on the same factorisation \
               (triangular solves only).",
        unset: None,
        aliases: &[],
        set: |o, v| {
            o.iterate.inner_steps = bounded_count(v)?;
            Ok(())
        },
        get: |o| Some(o.iterate.inner_steps.to_string()),
    },
    OptionSpec {
        name: "tolerance",
        value_name: "T",
        choices: &[],
        help: "The iterations stop when no vertex moves more than T × spacing.",
        unset: None,
        aliases: &[],
        set: |o, v| {
            o.iterate.tolerance = number(v).ok().filter(|t| *t >= 0.0).ok_or("a number ≥ 0")?;
            Ok(())
        },
        get: |o| Some(text(o.iterate.tolerance)),
    },
    OptionSpec {
        name: "normal_prior",
        value_name: "S",
        choices: &[],
        help: "In the iterations, the propagated normals are pulled towards the current surface's normals at \
               scales above S × the mean patch size (0: none).",
        unset: None,
        aliases: &[],
        set: |o, v| {
            o.iterate.normal_prior = number(v).ok().filter(|t| *t >= 0.0).ok_or("a number ≥ 0")?;
            Ok(())
        },
        get: |o| Some(text(o.iterate.normal_prior)),
    },
    OptionSpec {
        name: "fine_solve",
        value_name: "auto|two-level|direct",
        choices: &["auto", "two-level", "direct"],
        help: "How the default's fine level solves its 3D iteration's systems: by conjugate gradients \
               preconditioned by the coarse level's factorisation (two-level: no fine factorisation, a \
               quarter less peak memory; a solve that does not converge is factorised instead), by a \
               factorisation of its own (direct), or two-level from 400k vertices when the coarse level \
               converged (auto).",
        unset: None,
        aliases: &[],
        set: |o, v| {
            o.iterate.fine_solve = choice(&FineSolve::ALL, FineSolve::name, v, "auto, two-level or direct")?;
            Ok(())
        },
        get: |o| Some(o.iterate.fine_solve.name().to_string()),
    },
    OptionSpec {
        name: "energy",
        value_name: "area|uniform",
        choices: &["area", "uniform"],
        help: "Weighting of the normal-control energy: Σ A_v ‖ΔV + 2H n*‖² (one factorisation serves \
               propagation and fit) or the paper's unweighted Σ ‖ΔV + 2H n*‖².",
        unset: None,
        aliases: &[],
        set: |o, v| {
            o.normal_control.energy = choice(&Energy::ALL, Energy::name, v, "area or uniform")?;
            Ok(())
        },
        get: |o| Some(o.normal_control.energy.name().to_string()),
    },
    OptionSpec {
        name: "guide_area",
        value_name: "barycentric|mass|surface",
        choices: &["barycentric", "mass", "surface"],
        help: "The area dividing the mean-curvature guide ([CG] eq. 1): the barycentric area of the fit's \
               metric (the area the sum covers: fair curvature at irregular vertices), the Laplacian's own \
               Voronoi area (the fast preset's) or the area on the propagated surface V* (the paper's wording).",
        unset: None,
        aliases: &[],
        set: |o, v| {
            o.normal_control.guide_area = choice(&GuideArea::ALL, GuideArea::name, v, "barycentric, mass or surface")?;
            Ok(())
        },
        get: |o| Some(o.normal_control.guide_area.name().to_string()),
    },
    OptionSpec {
        name: "guide_updates",
        value_name: "K",
        choices: &[],
        help: "Times the mean-curvature guide is re-estimated on the fitted surface and the fit repeated \
               (same factorisation). 0 reproduces the paper.",
        unset: None,
        aliases: &[],
        set: |o, v| {
            o.normal_control.guide_updates = bounded_count(v)?;
            Ok(())
        },
        get: |o| Some(o.normal_control.guide_updates.to_string()),
    },
    OptionSpec {
        name: "w1",
        value_name: "W",
        choices: &[],
        help: "short-paper: weight of the curvature guide, dimensionless (ω₁ = W / s⁴, s the mean patch size). \
               Small values make the Δ⁴ system ill-conditioned (checked: an error, not a wrong surface).",
        unset: None,
        aliases: &[],
        set: |o, v| {
            o.short_paper.w1 = number(v).ok().filter(|w| *w > 0.0).ok_or("a positive number")?;
            Ok(())
        },
        get: |o| Some(text(o.short_paper.w1)),
    },
    OptionSpec {
        name: "infer_normals",
        value_name: "missing|all",
        choices: &["missing", "all"],
        help: "Which curves' normals are inferred from the network's shape (tangent planes where curves \
               cross, one orientation, least twist along the curves): those of curves that come without \
               normals (given normals win), or all of them (to compare with the given ones).",
        unset: None,
        aliases: &[],
        set: |o, v| {
            let v = match v {
                "true" | "True" | "yes" => "all",
                "false" | "False" | "no" => "missing",
                v => v,
            };
            o.infer_normals = choice(&InferNormals::ALL, InferNormals::name, v, "missing or all")?;
            Ok(())
        },
        get: |o| Some(o.infer_normals.name().to_string()),
    },
    OptionSpec {
        name: "snap",
        value_name: "S",
        choices: &[],
        help: "Snapping tolerance: curves closer than S meet at a node, also between samples.",
        unset: Some("the network's own snap value, else the larger of 1e-3 × its bounding-box diagonal and 0.1 × the mean sample spacing"),
        aliases: &[],
        set: |o, v| {
            o.mesh.snap = Some(number(v).ok().filter(|s| *s > 0.0).ok_or("a positive distance")?);
            Ok(())
        },
        get: |o| o.mesh.snap.map(text),
    },
    OptionSpec {
        name: "consolidate",
        value_name: "on|off",
        choices: &["on", "off"],
        help: "Consolidate raw strokes before node finding: ends that stop short of or overshoot another stroke \
               within the gap become junctions on it, strokes drawn along each other (twice, retraced) become one \
               curve, hooks and stubs at stroke ends are trimmed. A clean network is left exactly as given.",
        unset: None,
        aliases: &[],
        set: |o, v| {
            o.consolidate.enabled = match v {
                "on" | "true" | "True" | "yes" => true,
                "off" | "false" | "False" | "no" => false,
                _ => return Err("on or off"),
            };
            Ok(())
        },
        get: |o| Some(if o.consolidate.enabled { "on" } else { "off" }.to_string()),
    },
    OptionSpec {
        name: "gap",
        value_name: "D",
        choices: &[],
        help: "Consolidation tolerance: stroke ends within D of another stroke are joined to it, strokes within \
               D/2 of each other over a stretch of 2 D are merged, hooks and stubs shorter than D trimmed.",
        unset: Some("from the sketch: 1.25 × the 90th percentile of the distances from a stroke end to the \
                     nearest other stroke, between 0.5 % and 2 % of the bounding-box diagonal"),
        aliases: &[],
        set: |o, v| {
            o.consolidate.gap = Some(number(v).ok().filter(|s| *s > 0.0).ok_or("a positive distance")?);
            Ok(())
        },
        get: |o| o.consolidate.gap.map(text),
    },
    OptionSpec {
        name: "max_memory",
        value_name: "BYTES",
        choices: &[],
        help: "The most memory a run may take (e.g. 4G, 500M, 2e9 bytes): a run whose estimated peak is \
               larger is refused before it starts, naming the estimate and a vertex count that fits.",
        unset: Some("the memory available: the process's address-space limit (ulimit -v) or the machine's available memory"),
        aliases: &[],
        set: |o, v| {
            o.mesh.max_memory = Some(bytes(v).ok_or("a size in bytes, such as 4G, 500M or 2e9")?);
            Ok(())
        },
        get: |o| o.mesh.max_memory.map(text),
    },
    OptionSpec {
        name: "order",
        value_name: "K",
        choices: &[],
        help: "cauchy: the Laplacian order k of Δᵏ V = 0 (1, 2 or 3).",
        unset: None,
        aliases: &[],
        set: |o, v| {
            o.cauchy.order = count(v).ok().filter(|k| (1..=3).contains(k)).ok_or("1, 2 or 3")?;
            Ok(())
        },
        get: |o| Some(o.cauchy.order.to_string()),
    },
    OptionSpec {
        name: "ghost_updates",
        value_name: "N",
        choices: &[],
        help: "cauchy: re-solves with centred ghost vertices (second-order tangent conditions; 0: the \
               paper's ghosts).",
        unset: None,
        aliases: &[],
        set: |o, v| {
            o.cauchy.ghost_updates = bounded_count(v)?;
            Ok(())
        },
        get: |o| Some(o.cauchy.ghost_updates.to_string()),
    },
];

#[cfg(test)]
#[path = "tests/options.rs"]
mod tests;
