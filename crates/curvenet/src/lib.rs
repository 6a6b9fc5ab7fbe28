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
//! 10. [`render`]: PNG pictures (shading, curvature, isophotes, normal deviation, curves).
//! 10. [`check`]: the invariants every output satisfies (finite, manifold, oriented, samples
//!     on the surface), used by the tests and the fuzzers (`fuzz/`).
//!
//! [`cauchy`]: a second surfacing system, the order-k Laplacians with ghost-vertex Cauchy
//! constraints of Andrews et al. 2011 ([A11]; `--method cauchy`, `inflate`, `fit`).
//!
//! [`pipeline`] runs them all: [`surface`] is the one-shot entry point; [`surfacer`] keeps the
//! mesh and factorisations for fast re-solves with new normals; [`harmonic`] interpolates on a
//! given mesh (libigl's `harmonic`). [`sampling`] builds test networks on triangle meshes
//! (plane sections, `curvenet sample`).

pub mod cauchy;
pub mod check;
pub mod clock;
pub mod conformal;
pub mod curves;
pub mod edit;
pub mod error;
pub mod examples;
pub mod geom;
pub mod harmonic;
pub mod io;
pub mod mesh;
pub mod methods;
pub mod metrics;
pub mod network;
pub mod operators;
pub mod ordering;
pub mod pipeline;
pub mod render;
pub mod sampling;
pub mod solve;
pub mod sparse;
pub mod surfacer;
pub mod tessellate;
pub mod topology;

pub use error::{Error, Result, Warning};
pub use methods::{GuideArea, Method, Weighting};
pub use network::{Curve, Network};
pub use operators::Metric;
pub use pipeline::{surface, surface_with_progress, Options, Patching, Stats, Surface, Timings};
pub use surfacer::Surfacer;
