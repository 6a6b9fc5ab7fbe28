//! Stage timing: one clock for every stage of the pipeline and every solver step.
//!
//! `std::time::Instant` panics on `wasm32-unknown-unknown` (no clock without a JavaScript
//! host), so there every duration reads as zero and the front end times the whole call itself.
//! Code times a step with [`timed`] (`let q = timed(&mut t.operators, || assemble())`), not with
//! clock calls of its own.

#[cfg(not(target_arch = "wasm32"))]
pub use std::time::Instant;

/// A clock that never advances (WebAssembly without a host clock).
#[cfg(target_arch = "wasm32")]
#[derive(Clone, Copy, Debug)]
pub struct Instant;

#[cfg(target_arch = "wasm32")]
impl Instant {
    /// Now (always the same instant).
    pub fn now() -> Instant {
        Instant
    }
    /// Zero.
    pub fn elapsed(&self) -> std::time::Duration {
        std::time::Duration::ZERO
    }
}

/// Runs `f` and adds its wall-clock seconds to `slot`.
pub fn timed<R>(slot: &mut f64, f: impl FnOnce() -> R) -> R {
    let clock = Instant::now();
    let r = f();
    *slot += clock.elapsed().as_secs_f64();
    r
}

/// Seconds since `clock` started.
pub fn seconds_since(clock: Instant) -> f64 {
    clock.elapsed().as_secs_f64()
}

/// Wall-clock seconds spent in the numerical stages of a solve (added to by the methods): the
/// `operators`, `factor` and `solve` stages of the run's statistics (docs/design.md §5).
#[derive(Clone, Copy, Debug, Default)]
pub struct SolveTimings {
    /// Assembling operators, system matrices and right-hand sides.
    pub operators: f64,
    /// Numeric (and symbolic) factorisations.
    pub factor: f64,
    /// Triangular solves.
    pub solve: f64,
}
