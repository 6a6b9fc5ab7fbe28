//! Stage timing that also builds for WebAssembly: `std::time::Instant` panics on
//! `wasm32-unknown-unknown` (no clock without a JavaScript host), so there every duration reads
//! as zero and the front end times the whole call itself.

#[cfg(not(target_arch = "wasm32"))]
pub use std::time::Instant;

/// A clock that never advances (WebAssembly without a host clock).
#[cfg(target_arch = "wasm32")]
#[derive(Clone, Copy, Debug)]
pub struct Instant;

#[cfg(target_arch = "wasm32")]
impl Instant {
    pub fn now() -> Instant {
        Instant
    }
    pub fn elapsed(&self) -> std::time::Duration {
        std::time::Duration::ZERO
    }
}
