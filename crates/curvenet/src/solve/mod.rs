//! Factor once, solve many: the sparse linear algebra every method shares.
//!
//! - [`cholesky`]: faer's supernodal `LLᵀ` of the SPD systems on the unknown vertices, with the
//!   symbolic analysis kept for numeric refactors and triangular solves tuned for a few
//!   right-hand sides ([`kernels`], [`tree_solve`]).
//! - [`ordering`]: fill-reducing orderings (nested dissection by levels and along patches).
//! - [`sparse`]: the compressed-column matrix and the products `A diag(d) B` the energies need.
//! - [`timing`]: the stage clock (also on WebAssembly).

pub mod cholesky;
mod kernels;
pub mod ordering;
pub mod sparse;
pub mod timing;
mod tree_solve;

pub use cholesky::{Cholesky, Ordering};
pub(crate) use cholesky::PARALLEL_FROM;
