//! Tools built on the Andrews et al. system (\[A11\], [`crate::methods::andrews2011`]):
//!
//! 1. [`svg`]: SVG sketches read as planar strokes.
//! 2. [`inflate`]: an SVG sketch → planar triangulation → inflated surface (\[A11\] §5).
//! 3. [`fit`]: reverse engineering a mesh into Cauchy constraints and solving them again
//!    (\[A11\] §6).

pub mod fit;
pub mod inflate;
pub mod svg;
