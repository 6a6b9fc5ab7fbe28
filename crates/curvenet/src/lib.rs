//! # curvenet — surfacing curve networks with normal control
//!
//! Turns a network of 3D curves sampled with surface normals into a smooth triangle mesh, by
//! the method of Stanko, Hahmann, Bonneau and Saguin-Sprynski, *Surfacing curve networks with
//! normal control*, Computers & Graphics 2016 (\[CG\]), with its baselines.
//!
//! ```no_run
//! let Some(network) = curvenet::network::examples::example("sphere") else { return Ok(()) };
//! let surface = curvenet::surface(&network, &curvenet::Options::default())?;
//! curvenet::io::write_mesh("sphere.ply".as_ref(), surface.mesh_data())?;
//! # Ok::<(), curvenet::Error>(())
//! ```
//!
//! The modules follow the pipeline, in the order data flows (docs/design.md §1):
//!
//! 1. [`network`]: the input model and its validation, the bundled example networks.
//! 2. [`io`]: reading networks, writing and reading meshes.
//! 3. [`curves`]: cubic splines in arc length.
//! 4. [`topology`]: where curves meet (nodes, segments), which cycles bound the patches
//!    (\[CG\] §3.2), the segments resampled at the mesh spacing.
//! 5. [`tessellate`]: each patch triangulated in its planar or conformal domain (\[CG\] §3.3).
//! 6. [`operators`]: cotangent Laplacian, mass matrix, normals, mean curvature (\[CG\] eq. 1).
//! 7. [`solve`]: sparse Cholesky, factor once and solve many.
//! 8. [`methods`]: normal-control (\[CG\] eq. 1–3), its 3D iterations, the baselines, the
//!    short paper's energy (\[EG\]) and the system of Andrews et al. (\[A11\]).
//! 9. [`pipeline`]: all of the above, network in, surface out: [`surface`] once, [`Surfacer`]
//!    for re-solves with kept factorisations.
//! 10. [`metrics`]: distances to analytic ground truth, the invariants every output satisfies.
//!
//! Then the tools: [`sampling`] builds test networks on triangle meshes, [`render`] draws PNG
//! pictures, [`sketch`] inflates SVG sketches and fits meshes with the \[A11\] system. [`geom`]
//! (vectors, the triangle mesh) and [`error`] sit under everything.
//!
//! # References
//!
//! Cited as \[CG\], \[EG\] and \[A11\] throughout (docs/design.md has the mathematics):
//!
//! - \[CG\] T. Stanko, S. Hahmann, G.-P. Bonneau, N. Saguin-Sprynski. *Surfacing curve networks
//!   with normal control*. Computers & Graphics 58 (2016).
//! - \[EG\] the same authors. *Smooth Interpolation of Curve Networks with Surface Normals*.
//!   Eurographics 2016 short paper.
//! - \[A11\] J. Andrews, P. Joshi, N. Carr. *A Linear Variational System for Modelling From
//!   Curves*. Computer Graphics Forum 30(6) (2011).

#![warn(missing_docs)]
#![deny(rustdoc::broken_intra_doc_links)]
// NaN-aware tests: `!(x > 0.0)` holds for NaN, `x <= 0.0` does not; inputs are checked so.
#![allow(clippy::neg_cmp_op_on_partial_ord)]
// Numerical loops index several arrays (rows, columns, weights) in lockstep.
#![allow(clippy::needless_range_loop)]

pub mod curves;
pub mod error;
pub mod geom;
pub mod io;
pub mod methods;
pub mod metrics;
pub mod network;
pub mod operators;
pub mod pipeline;
pub mod render;
pub mod sampling;
pub mod sketch;
pub mod solve;
pub mod tessellate;
pub mod topology;

pub use error::{Error, Result, Warning};
pub use geom::mesh::Mesh;
pub use methods::{Energy, GuideArea, Method, SurfacingMethod};
pub use network::{Curve, Network};
pub use operators::Metric;
pub use pipeline::surfacer::Surfacer;
pub use pipeline::{infer_normals, network_with_cycles, with_cycle_filled, with_patch_left_open, InferNormals};
pub use pipeline::{surface, surface_with_progress, MeshOptions, Options, Patching, Preset, Stats, Surface, Timings};
