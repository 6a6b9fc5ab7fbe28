//! # curvenet — surfacing curve networks with normal control
//!
//! Turns a network of 3D curves sampled with surface normals into a smooth triangle mesh, by
//! the method of Stanko, Hahmann, Bonneau and Saguin-Sprynski, *Surfacing curve networks with
//! normal control*, Computers & Graphics 2016 ([CG]), with its baselines.
//!
//! ```no_run
//! let Some(network) = curvenet::examples::example("sphere") else { return Ok(()) };
//! let surface = curvenet::surface(&network, &curvenet::Options::default())?;
//! curvenet::io::write_mesh("sphere.ply".as_ref(), surface.mesh_data())?;
//! # Ok::<(), curvenet::Error>(())
//! ```
//!
//! The modules follow the pipeline, in the order data flows (DESIGN §1):
//!
//! 1. [`network`]: the input model and its validation; [`io`] reads and writes files.
//! 2. [`topology::nodes`]: where curves meet; segments between nodes.
//! 3. [`curves`]: cubic splines in arc length, uniform resampling.
//! 4. [`topology::cycles`]: cycles sorted by the node normals, patches.
//! 5. [`tessellate`]: planar projection and quality constrained Delaunay per patch.
//! 6. [`operators`]: cotangent Laplacian, mass matrix, normals, mean curvature ([CG] eq. 1).
//! 7. [`solve`]: sparse Cholesky, factor once and solve many; [`sparse`]: matrix assembly.
//! 8. [`methods`]: normal-control ([CG] eq. 1–3), biharmonic, triharmonic.
//! 9. [`metrics`]: distances to analytic ground truth; [`examples`]: analytic networks.
//! 10. [`check`]: the invariants every output satisfies (finite, manifold, oriented, samples
//!     on the surface), used by the tests and the fuzzers (`fuzz/`).
//!
//! [`pipeline`] runs them all: [`surface`] is the one-shot entry point.

pub mod check;
pub mod conformal;
pub mod curves;
pub mod error;
pub mod examples;
pub mod geom;
pub mod io;
pub mod mesh;
pub mod methods;
pub mod metrics;
pub mod network;
pub mod operators;
pub mod ordering;
pub mod pipeline;
pub mod solve;
pub mod sparse;
pub mod tessellate;
pub mod topology;

pub use error::{Error, Result, Warning};
pub use methods::{GuideArea, Method, Weighting};
pub use network::{Curve, Network};
pub use operators::Metric;
pub use pipeline::{surface, surface_with_progress, Options, Patching, Stats, Surface, Timings};
