//! Surfacing methods: one module per paper or baseline.
//!
//! - [`normal_control`]: the journal paper's method ([CG] §3.4, eq. 1–3), with signed mean
//!   curvature, hard or soft constraints ([CG] §4.5).
//! - [`iterated`]: normal-control iterated with operators rebuilt on the 3D surface.
//! - [`polyharmonic`]: the biharmonic `Δ²V = 0` and triharmonic `Δ³V = 0` baselines ([CG] §4.3).
//! - [`method4`]: [CG] §4.2 eq. 4, `Δ²V = 0` with `ΔV = b₁` on the curves.
//! - [`eg2016`]: the energy of the authors' Eurographics 2016 short paper ([EG]).
//!
//! Every method solves for the free vertices with the curve vertices fixed (hard constraints
//! eliminated), factoring each distinct system matrix once.

pub mod andrews2011;
pub mod eg2016;
pub mod harmonic;
pub mod iterated;
pub mod method4;
pub mod normal_control;
pub mod polyharmonic;

use crate::geom::DVec3;
use crate::geom::mesh::Mesh;
use crate::solve::Cholesky;
use crate::solve::sparse::Csc;
use faer::Mat;

/// Which surfacing method to run.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Method {
    /// [CG] eq. 1–3: propagate positions and normals, estimate the signed mean curvature,
    /// fit `L V = −2 H N*`.
    #[default]
    NormalControl,
    /// `Δ²V = 0` with the curve vertices fixed (positions only).
    Biharmonic,
    /// `Δ³V = 0` with the curve vertices fixed (positions only).
    Triharmonic,
    /// [CG] §4.2 eq. 4: `Δ²V = 0` with `ΔV = b₁` at the curve vertices, from the normals.
    Method4,
    /// [EG]: `‖Δ²V‖² + ω₁ ‖ΔV + 2H n*‖² + ω₀ soft`.
    ShortPaper,
    /// [A11]: `Δᵏ V = 0` (`Options::order`) with ghost-vertex Cauchy constraints on the curves
    /// ([`crate::methods::andrews2011`]).
    Cauchy,
}

impl Method {
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

    pub fn from_name(s: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|m| m.name() == s)
    }
}

/// How the terms of the normal-control energy are weighted (docs/design.md §1).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Weighting {
    /// `Σ_v A_v ‖(LV)_v + 2H n*‖²`: the system matrix is `Ls M⁻¹ Ls`, the same as the
    /// propagation's, so one factorisation serves both (closed surfaces).
    #[default]
    Area,
    /// `Σ_v ‖(LV)_v + 2H n*‖²` as written in [CG] eq. 2 (matrix `Ls M⁻² Ls`).
    Uniform,
}

impl Weighting {
    pub fn name(self) -> &'static str {
        match self {
            Weighting::Area => "area",
            Weighting::Uniform => "uniform",
        }
    }
}

/// Which Voronoi area `A` divides the sum in the mean-curvature guide ([CG] eq. 1).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum GuideArea {
    /// The area `M` of the Laplacian the fit uses. With the planar metric, `L = M⁻¹Ls` of the
    /// true surface exceeds `−2HN` by the local area ratio of the projection; dividing `h` by
    /// the same planar area scales the target by the same ratio, so the bias cancels to first
    /// order (sphere at 20k vertices: mean error 0.0011 instead of 0.0084).
    #[default]
    Mass,
    /// The Voronoi area of `v*` on the propagated surface `V*`, as [CG] §3.4 states it.
    Surface,
}

impl GuideArea {
    pub fn name(self) -> &'static str {
        match self {
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
    /// The signed mean-curvature guide `H` of [CG] eq. 1 (normal-control only), `#V`.
    pub guide_curvature: Option<Vec<f64>>,
}

/// Wall-clock seconds spent in the numerical stages (added to by the methods).
#[derive(Clone, Copy, Debug, Default)]
pub struct SolveTimings {
    pub operators: f64,
    pub factor: f64,
    pub solve: f64,
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

/// Right-hand side of the weighted least-squares system `min Σ_k w_k ‖(Ls X)_k − b_k‖²` on the
/// unknown rows `first..`: `(Ls diag(w) (b − Ls X̃))_u`, where `X̃` holds the known rows.
pub(crate) fn weighted_rhs(ls: &Csc, w: &[f64], target: Option<&Mat<f64>>, known: &Mat<f64>, first: usize) -> Mat<f64> {
    let n = ls.nrows;
    let k = known.ncols();
    let mut y = Mat::<f64>::zeros(n, k);
    // X̃ is zero but on the known rows: the column-wise product skips the zeros.
    ls.mul_dense(known.as_ref(), y.as_mut());
    for c in 0..k {
        for i in 0..n {
            let b = target.map_or(0.0, |t| t[(i, c)]);
            y[(i, c)] = w[i] * (b - y[(i, c)]);
        }
    }
    let mut z = Mat::<f64>::zeros(n, k);
    ls.sym_mul_dense(y.as_ref(), z.as_mut());
    let mut out = Mat::<f64>::zeros(n - first, k);
    for c in 0..k {
        for i in first..n {
            out[(i - first, c)] = z[(i, c)];
        }
    }
    out
}

/// Copies 3 columns starting at `col` of the solution (rows = unknowns `first..`) into
/// `positions[first..]`.
pub(crate) fn scatter(sol: &Mat<f64>, col: usize, first: usize, out: &mut [DVec3]) {
    for i in 0..sol.nrows() {
        out[first + i] = DVec3::new(sol[(i, col)], sol[(i, col + 1)], sol[(i, col + 2)]);
    }
}

/// Factorises a system on the vertices `first..` of `mesh`: along the patches when the
/// unknowns are the free vertices (see [`Cholesky::factor_in_parts`]).
pub(crate) fn factor_on(mesh: &Mesh, q: &Csc, first: usize, what: &str) -> crate::error::Result<Cholesky> {
    let parts = (first == mesh.num_curve).then(|| mesh.free_vertex_patches());
    Cholesky::factor_in_parts(q, what, parts.as_deref())
}

pub(crate) fn check_finite(p: &[DVec3], what: &str) -> crate::error::Result<()> {
    if let Some(i) = p.iter().position(|v| !v.is_finite()) {
        return Err(crate::error::Error::numerical(format!(
            "{what}: vertex {i} is not finite; the system is ill-conditioned"
        )));
    }
    Ok(())
}
