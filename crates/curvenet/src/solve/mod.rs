//! Factor once, solve many: the sparse linear algebra every method shares (docs/design.md §8).
//!
//! - [`system`]: the factor-once object of every method, [`Eliminated`]: a system on the
//!   unknown rows with the known rows eliminated (libigl's `min_quad_with_fixed`), its symbolic
//!   analysis kept for numeric refactors, solved for many right-hand sides; and the weighted
//!   least-squares energies [`LeastSquares`] that give its matrix and right-hand sides.
//! - [`cholesky`]: faer's supernodal `LLᵀ` of the symmetric positive definite systems, with
//!   triangular solves tuned for a few right-hand sides (modules `kernels`, `tree_solve`).
//! - [`lu`]: sparse LU for the non-symmetric ones (the Andrews et al. system).
//! - [`ordering`]: fill-reducing orderings (nested dissection by levels and along patches).
//! - [`sparse`]: the compressed-column matrix and the products `A diag(d) B` the energies need.
//! - [`pcg`], [`two_level`]: conjugate gradients, and the fine level's systems solved by them
//!   with the coarse level's factorisation as a two-level preconditioner (issue 31).
//! - [`timing`]: the stage clock (also on WebAssembly).
//!
//! [`Cholesky`] and [`Lu`] are used through one trait, [`Factorization`].

pub mod cholesky;
mod kernels;
pub mod lu;
pub mod memory;
pub mod ordering;
pub mod pcg;
pub mod sparse;
pub mod system;
pub mod timing;
mod tree_solve;
pub mod two_level;

pub use cholesky::{Cholesky, Ordering};
pub use lu::Lu;
pub use system::{Eliminated, LeastSquares};
pub use timing::{timed, SolveTimings};

pub(crate) use cholesky::PARALLEL_FROM;

/// A factorised square system `A X = B`, solved for any number of right-hand sides.
pub trait Factorization: Send + Sync {
    /// Number of unknowns (rows of `A`).
    fn dim(&self) -> usize;

    /// Solves `A X = B` in place: `rhs` holds `B` (`dim × k`) and receives `X`.
    fn solve_in_place(&self, rhs: faer::MatMut<'_, f64>);
}

impl Factorization for Cholesky {
    fn dim(&self) -> usize {
        Cholesky::dim(self)
    }

    fn solve_in_place(&self, rhs: faer::MatMut<'_, f64>) {
        Cholesky::solve_in_place(self, rhs)
    }
}
