//! # The linear variational system of Andrews, Joshi and Carr (\[A11\])
//!
//! *A Linear Variational System for Modelling From Curves*, Computer Graphics Forum 2011:
//! order-k Laplacian systems `Δᵏ p = 0` with Cauchy constraints through ghost vertices and
//! micro-Laplacians, a second surfacing system next to the normal-control pipeline. See
//! `docs/cauchy.md` for the user's view.
//!
//! The modules, in the order data flows:
//!
//! 1. [`system`]: the stencil (cotangent weights and areas of a fixed initial domain), vertex
//!    roles, and the row-by-row assembly of \[A11\] Algorithm 2 (`buildEqn`, eq. 1–2); LU solve.
//! 2. [`params`]: orientation, sharpness, stretch → ghost vertex positions (\[A11\] eq. 3).
//! 3. [`constraints`]: curve attributes (`kind`, `sharpness`, `stretch`) read from the network
//!    JSON, and the solve of a curve network tessellated by the pipeline (`--method cauchy`).
//! 4. [`reduce`]: the ghost vertex basis (\[A11\] §6.2, eq. 4–5) for re-solves without
//!    re-factorising.
//!
//! The tools built on it, SVG sketch inflation (\[A11\] §5) and reverse engineering a mesh into
//! Cauchy constraints (\[A11\] §6), are in [`crate::sketch`].

pub mod constraints;
pub mod params;
pub mod reduce;
pub mod system;

pub use constraints::Andrews2011;
pub use constraints::{CurveAttributes, Kind, NetworkAttributes};
pub use params::{ghost_positions, CauchyParams};
pub use reduce::GhostBasis;
pub use system::{MicroWeight, Role, Stencil, System};

/// The user's settings of `method = cauchy` (options `order`, `ghost_updates`; docs/design.md
/// §6) and the per-curve attributes read from the network JSON.
#[derive(Clone, Debug, PartialEq)]
pub struct CauchyOptions {
    /// `order`: the Laplacian order `k` of \[A11\] eq. 1, 1–3. Default
    /// [`CauchyOptions::DEFAULT_ORDER`].
    pub order: usize,
    /// `ghost_updates`: re-solves with centred ghost vertices (see
    /// [`System::solve_with_updates`]; 0: the paper's ghosts). Default
    /// [`CauchyOptions::DEFAULT_GHOST_UPDATES`].
    pub ghost_updates: usize,
    /// Per-curve `kind`, `sharpness`, `stretch` (read from the network JSON by
    /// [`NetworkAttributes::read`]); `None`: every curve a flat Cauchy constraint oriented by
    /// its normals.
    pub attributes: Option<std::sync::Arc<NetworkAttributes>>,
}

impl CauchyOptions {
    /// Default `order`: the biharmonic, as in most of \[A11\]'s figures.
    pub const DEFAULT_ORDER: usize = 2;
    /// Default `ghost_updates`.
    pub const DEFAULT_GHOST_UPDATES: usize = 10;
}

impl Default for CauchyOptions {
    fn default() -> Self {
        CauchyOptions { order: Self::DEFAULT_ORDER, ghost_updates: Self::DEFAULT_GHOST_UPDATES, attributes: None }
    }
}
