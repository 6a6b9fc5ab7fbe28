//! The whole pipeline, network in, surface out (\[CG\] §3.1; docs/design.md §1).
//!
//! 1. [`options`]: the run's options, their names and presets.
//! 2. [`prepare`]: validate, find nodes, fit splines, trace the cycles, pick the spacing,
//!    resample, tessellate (planar or conformal patching).
//! 3. [`solve`]: the method on the patches' domain operators, then normal-control's 3D
//!    iterations.
//! 4. [`stats`]: the surface, its statistics and timings.
//!
//! [`surface`] runs them once; [`surfacer::Surfacer`] keeps the mesh and the method's
//! factorisations for re-solves with new curve normals or positions.

pub mod options;
pub mod prepare;
pub mod solve;
pub mod stats;
pub mod surfacer;

pub use options::{MeshOptions, OptionSpec, Options, Patching, Preset, OPTIONS};
pub use stats::{Stats, Surface, Timings};

use crate::error::Result;
use crate::network::Network;
use std::borrow::Cow;

/// Surfaces `network` with `options`. See [`surface_with_progress`].
pub fn surface(network: &Network, options: &Options) -> Result<Surface> {
    surface_with_progress(network, options, &mut |_, _, _| {})
}

/// Surfaces `network`, reporting each finished stage to `progress(stage, seconds, detail)`.
pub fn surface_with_progress(
    network: &Network,
    options: &Options,
    progress: &mut dyn FnMut(&str, f64, &str),
) -> Result<Surface> {
    let prepared = prepare::prepare(network, options, progress)?;
    let base = prepared.timings;
    solve::solve_prepared(Cow::Owned(prepared), options, progress, None, base)
}
