//! Surfacing methods: one module per paper or baseline, one interface ([`SurfacingMethod`]).
//!
//! - [`normal_control`]: the journal paper's method (\[CG\] §3.4, eq. 1–3), with signed mean
//!   curvature, hard or soft constraints (\[CG\] §4.5).
//! - [`iterated`]: normal-control iterated with operators rebuilt on the 3D surface.
//! - [`polyharmonic`]: the biharmonic `Δ²V = 0` and triharmonic `Δ³V = 0` baselines (\[CG\] §4.3);
//!   [`harmonic`]: the same systems on any mesh (libigl's `harmonic`).
//! - [`method4`]: \[CG\] §4.2 eq. 4, `Δ²V = 0` with `ΔV = b₁` on the curves.
//! - [`eg2016`]: the energy of the authors' Eurographics 2016 short paper (\[EG\]).
//! - [`andrews2011`]: the order-k Laplacians with ghost-vertex Cauchy constraints of Andrews et
//!   al. 2011 (\[A11\]).
//!
//! Every method solves for the free vertices with the curve vertices fixed (hard constraints
//! eliminated) or pulled (soft), factoring each distinct system matrix once
//! ([`crate::solve::Eliminated`]). The matrices depend on the mesh and its operators only, not
//! on the curve positions and normals, so a method object keeps its factorisations and solves
//! again for new curve values with right-hand sides and triangular solves
//! ([`crate::Surfacer`]).

pub mod andrews2011;
pub mod eg2016;
pub mod harmonic;
pub mod iterated;
pub mod method4;
pub mod normal_control;
pub mod polyharmonic;

use crate::error::Result;
use crate::geom::mesh::Mesh;
use crate::geom::DVec3;
use crate::operators::Operators;
use crate::solve::sparse::Csc;
use crate::solve::{Eliminated, SolveTimings};
use faer::Mat;

/// One surfacing method on a tessellated mesh: factor once, solve for given constraint values.
///
/// The curve vertices `..mesh.num_curve` carry the constraint values: their positions
/// `mesh.positions` and normals `mesh.curve_normals`. `ops` are the mesh's operators (the
/// patches' domain metric). The first [`SurfacingMethod::solve`] factorises the method's
/// systems; later calls on the same mesh and operators reuse them, whatever the curve values.
pub trait SurfacingMethod: Send + Sync {
    /// The method's name, as [`Method::name`].
    fn name(&self) -> &'static str;

    /// Solves for the free vertices with the current curve values (factorising on the first
    /// call). Errors with [`crate::Error::Numerical`] when a system is singular or the solve
    /// is not finite.
    fn solve(&mut self, mesh: &Mesh, ops: &Operators, t: &mut SolveTimings) -> Result<MethodResult>;

    /// Whether factorisations from an earlier solve are kept.
    fn is_factored(&self) -> bool;

    /// Frees the kept factorisations (the next solve factorises again).
    fn release(&mut self);

    /// The network's curves moved (same nodes and segments): for the methods that read the
    /// input curves themselves (`cauchy` locates its constraint curves on the mesh by them).
    /// `curves`: each curve's samples and closedness. The others ignore it.
    fn set_curves(&mut self, curves: &[(Vec<DVec3>, bool)]) {
        let _ = curves;
    }
}

/// Which surfacing method to run.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Method {
    /// \[CG\] eq. 1–3: propagate positions and normals, estimate the signed mean curvature,
    /// fit `L V = −2 H N*`.
    #[default]
    NormalControl,
    /// `Δ²V = 0` with the curve vertices fixed (positions only).
    Biharmonic,
    /// `Δ³V = 0` with the curve vertices fixed (positions only).
    Triharmonic,
    /// \[CG\] §4.2 eq. 4: `Δ²V = 0` with `ΔV = b₁` at the curve vertices, from the normals.
    Method4,
    /// The short paper's energy (\[EG\]): `‖Δ²V‖² + ω₁ ‖ΔV + 2H n*‖² + ω₀ soft`.
    ShortPaper,
    /// Andrews et al. 2011 (\[A11\]): `Δᵏ V = 0` (option `order`) with ghost-vertex Cauchy constraints on the curves
    /// ([`crate::methods::andrews2011`]).
    Cauchy,
}

impl Method {
    /// Every method, in the order of the documentation.
    pub const ALL: [Method; 6] = [
        Method::NormalControl,
        Method::Biharmonic,
        Method::Triharmonic,
        Method::Method4,
        Method::ShortPaper,
        Method::Cauchy,
    ];

    /// The name used on the command line and in files.
    pub fn name(self) -> &'static str {
        match self {
            Method::NormalControl => "normal-control",
            Method::Biharmonic => "biharmonic",
            Method::Triharmonic => "triharmonic",
            Method::Method4 => "method4",
            Method::ShortPaper => "short-paper",
            Method::Cauchy => "cauchy",
        }
    }

    /// The method called `s` ([`Method::name`]).
    pub fn from_name(s: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|m| m.name() == s)
    }
}

/// How the terms of the normal-control energy are weighted (option `energy`, docs/design.md §1).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Energy {
    /// `Σ_v A_v ‖(LV)_v + 2H n*‖²`: the system matrix is `Ls M⁻¹ Ls`, the same as the
    /// propagation's, so one factorisation serves both (closed surfaces).
    #[default]
    Area,
    /// `Σ_v ‖(LV)_v + 2H n*‖²` as written in \[CG\] eq. 2 (matrix `Ls M⁻² Ls`).
    Uniform,
}

impl Energy {
    /// Every weighting.
    pub const ALL: [Energy; 2] = [Energy::Area, Energy::Uniform];

    /// The name used in options and files.
    pub fn name(self) -> &'static str {
        match self {
            Energy::Area => "area",
            Energy::Uniform => "uniform",
        }
    }
}

/// Which area `A` divides the sum in the mean-curvature guide (\[CG\] eq. 1).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum GuideArea {
    /// The barycentric area of the fit's metric (a third of the one-ring): the area eq. 1's sum
    /// covers. Eq. 1 sums `n × dx` around the one-ring, `≈ 2H` times the enclosed area, which is
    /// three barycentric areas on any ring; the mixed Voronoi area of [`GuideArea::Mass`] equals
    /// it only on regular rings. At the valence-5 and -7 vertices where a patch's lattice meets
    /// its border band the difference is 10–15 %, and the fit turns it into bumps (sphere, 20k
    /// vertices, points exactly on the sphere: guide error 0.00 % instead of 12.7 % at the 99th
    /// percentile; docs/accuracy.md, "Fairness"). The fit's target stays `−2 M_v H_v n_v`, with
    /// the Laplacian's own area; both areas come from the same metric, so the planar bias
    /// cancellation of [`GuideArea::Mass`] holds too.
    #[default]
    Barycentric,
    /// The area `M` of the Laplacian the fit uses. With the planar metric, `L = M⁻¹Ls` of the
    /// true surface exceeds `−2HN` by the local area ratio of the projection; dividing `h` by
    /// the same planar area scales the target by the same ratio, so the bias cancels to first
    /// order (sphere at 20k vertices: mean error 0.0011 instead of 0.0084). The `fast` preset's
    /// choice (as before issue 18).
    Mass,
    /// The Voronoi area of `v*` on the propagated surface `V*`, as \[CG\] §3.4 states it.
    Surface,
}

impl GuideArea {
    /// Every choice.
    pub const ALL: [GuideArea; 3] = [GuideArea::Barycentric, GuideArea::Mass, GuideArea::Surface];

    /// The name used in options and files.
    pub fn name(self) -> &'static str {
        match self {
            GuideArea::Barycentric => "barycentric",
            GuideArea::Mass => "mass",
            GuideArea::Surface => "surface",
        }
    }
}

/// What a method computed.
#[derive(Clone, Debug, Default)]
pub struct MethodResult {
    /// Final vertex positions, `#V`.
    pub positions: Vec<DVec3>,
    /// Propagated unit normals `N*` (normal-control only), `#V`.
    pub propagated_normals: Option<Vec<DVec3>>,
    /// The signed mean-curvature guide `H` of \[CG\] eq. 1 (normal-control only), `#V`.
    pub guide_curvature: Option<Vec<f64>>,
}

/// `n × k` dense matrix with the rows of the known (curve) vertices `0..first` taken from
/// `cols` and zeros elsewhere: `X̃` of the eliminated systems.
pub(crate) fn known_rows(n: usize, first: usize, cols: &[&[DVec3]]) -> Mat<f64> {
    let mut x = Mat::<f64>::zeros(n, 3 * cols.len());
    for (c, vals) in cols.iter().enumerate() {
        for i in 0..first {
            let v = vals[i];
            x[(i, 3 * c)] = v.x;
            x[(i, 3 * c + 1)] = v.y;
            x[(i, 3 * c + 2)] = v.z;
        }
    }
    x
}

/// Copies 3 columns starting at `col` of the solution (rows = unknowns `first..`) into
/// `positions[first..]`.
pub(crate) fn scatter(sol: &Mat<f64>, col: usize, first: usize, out: &mut [DVec3]) {
    for i in 0..sol.nrows() {
        out[first + i] = DVec3::new(sol[(i, col)], sol[(i, col + 1)], sol[(i, col + 2)]);
    }
}

/// Factorises a system on the vertices `first..` of `mesh`: along the patches when the
/// unknowns are the free vertices (see [`crate::solve::Cholesky::factor_in_parts`]).
pub(crate) fn factor_on(mesh: &Mesh, q: &Csc, first: usize, what: &str) -> Result<Eliminated> {
    let parts = (first == mesh.num_curve).then(|| mesh.free_vertex_patches());
    Eliminated::factor(q, first, parts.as_deref(), what)
}

/// [`factor_on`], sharing the symbolic analysis (ordering, elimination tree, supernodes) of
/// `like` when `q` has its unknowns and pattern — the result is the one [`factor_on`] gives,
/// without the analysis: the fit systems on the propagation system's pattern
/// ([`crate::solve::sparse::product_lower_keeping_pattern`]).
pub(crate) fn factor_like(
    mesh: &Mesh,
    q: &Csc,
    first: usize,
    what: &str,
    like: Option<&Eliminated>,
) -> Result<Eliminated> {
    match like {
        // A failed pivot names its patch, as with factor_on.
        Some(l) if l.same_pattern(q, first) => l.refactor(q, what).map_err(|e| {
            let patch = e.at().vertex.and_then(|v| mesh.free_vertex_patches().get(v.wrapping_sub(first)).copied());
            match patch {
                Some(p) if first == mesh.num_curve => e.patch(p as usize),
                _ => e,
            }
        }),
        _ => factor_on(mesh, q, first, what),
    }
}

pub(crate) fn check_finite(p: &[DVec3], what: &str) -> crate::error::Result<()> {
    if let Some(i) = p.iter().position(|v| !v.is_finite()) {
        return Err(crate::error::Error::numerical(format!(
            "{what}: vertex {i} is not finite; the system is ill-conditioned"
        ))
        .vertex(i));
    }
    Ok(())
}
