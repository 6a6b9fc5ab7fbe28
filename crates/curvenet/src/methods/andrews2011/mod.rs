//! # The linear variational system of Andrews, Joshi and Carr ([A11])
//!
//! *A Linear Variational System for Modelling From Curves*, Computer Graphics Forum 2011:
//! order-k Laplacian systems `Δᵏ p = 0` with Cauchy constraints through ghost vertices and
//! micro-Laplacians, a second surfacing system next to the normal-control pipeline. See
//! `docs/cauchy.md` for the user's view.
//!
//! The modules, in the order data flows:
//!
//! 1. [`system`]: the stencil (cotangent weights and areas of a fixed initial domain), vertex
//!    roles, and the row-by-row assembly of [A11] Algorithm 2 (`buildEqn`, eq. 1–2); LU solve.
//! 2. [`params`]: orientation, sharpness, stretch → ghost vertex positions ([A11] eq. 3).
//! 3. [`constraints`]: curve attributes (`kind`, `sharpness`, `stretch`) read from the network
//!    JSON, and the solve of a curve network tessellated by the pipeline (`--method cauchy`).
//! 4. [`reduce`]: the ghost vertex basis ([A11] §6.2, eq. 4–5) for re-solves without
//!    re-factorising.
//!
//! The tools built on it, SVG sketch inflation ([A11] §5) and reverse engineering a mesh into
//! Cauchy constraints ([A11] §6), are in [`crate::sketch`].

pub mod constraints;
pub mod params;
pub mod reduce;
pub mod system;

pub use constraints::{CurveAttributes, Kind, NetworkAttributes};
pub use params::{ghost_positions, CauchyParams};
pub use reduce::GhostBasis;
pub use system::{MicroWeight, Role, Stencil, System};
