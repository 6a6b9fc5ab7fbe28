//! The memory budget of a run (issue 17): its peak memory estimated from the mesh size before
//! anything large is allocated, and the run refused with [`Error::Memory`] when the estimate
//! exceeds the memory available — instead of an abort ("memory allocation failed") or the
//! machine swapping.
//!
//! The estimate is linear in the vertex count, per method, from peak resident sizes measured
//! on the sphere at 10⁵ and 3·10⁵ vertices (`surface --stats`, `peak_memory_bytes`; the slope,
//! rounded up by about 10 %): the default (conformal patching, 3D iterations) 4,500 bytes per
//! vertex, the single pass (`--fast`, `--paper`, biharmonic, method (4)) 2,600, triharmonic
//! 5,600 (5,060 at 10⁵), `cauchy` 10,500 (9,240 at 10⁵), the short paper's energy 9,800. The memory available is the smaller of the process's
//! address-space limit (`ulimit -v`, less a margin for the address space the process reserves
//! without using it) and the machine's available memory (`MemAvailable`), or `max_memory`
//! ([`crate::solve::memory`]).

use super::options::Options;
use crate::error::{Error, Result};
use crate::methods::Method;

/// Peak bytes per mesh vertex of a run with `options` (see the module documentation).
pub fn bytes_per_vertex(options: &Options) -> f64 {
    match options.method {
        Method::NormalControl if options.iterate.iterations > 0 => 4500.0,
        Method::ShortPaper => 9800.0,
        Method::Cauchy => 10_500.0,
        Method::Triharmonic => 5600.0,
        _ => 2600.0,
    }
}

/// Memory every run takes besides the mesh (the executable, thread stacks, the allocator).
const BASE_BYTES: f64 = 100e6;

/// The estimated peak memory (bytes) of a run with `options` on a mesh of `vertices` vertices.
pub fn estimate(vertices: f64, options: &Options) -> f64 {
    BASE_BYTES + vertices * bytes_per_vertex(options)
}

/// The memory a run may take: `max_memory` when given, else the memory available
/// ([`crate::solve::memory::available_memory`]).
pub fn available(options: &Options) -> Option<f64> {
    crate::solve::memory::available_memory(options.mesh.max_memory)
}

/// Refuses a run of `vertices` vertices with `options` whose estimated peak exceeds the memory
/// available, naming both and a vertex count that fits.
pub(crate) fn check(vertices: f64, options: &Options) -> Result<()> {
    let Some(have) = available(options) else { return Ok(()) };
    let need = estimate(vertices, options);
    if need <= have {
        return Ok(());
    }
    let fits = ((have - BASE_BYTES) / bytes_per_vertex(options)).max(0.0);
    let source = if options.mesh.max_memory.is_some() { "`max_memory`" } else { "the memory available" };
    Err(Error::memory(format!(
        "about {vertices:.3e} vertices would take about {:.2} GB at their peak, more than {source} ({:.2} GB); give \
         at most about {:.0} `vertices` (or a larger `spacing`), or a larger `max_memory` if the memory is there",
        need / 1e9,
        have / 1e9,
        (0.9 * fits / 1000.0).floor() * 1000.0
    )))
}

/// Seconds of a default run at 10⁶ vertices on the reference machine (docs/performance.md:
/// 24 s on the sphere), and the exponent of its growth (1M → 2M: ×2.4, about n^1.25).
const SECONDS_AT_MILLION: f64 = 24.0;
const GROWTH: f64 = 1.25;

/// The estimated seconds of a run of `vertices` vertices with `options`: the default's
/// measured time scaled by the method's memory per vertex (its work follows its factor's size).
pub fn seconds(vertices: f64, options: &Options) -> f64 {
    let default = bytes_per_vertex(&Options::default());
    SECONDS_AT_MILLION * (vertices / 1e6).powf(GROWTH) * bytes_per_vertex(options) / default
}

/// A warning for a `spacing` that makes more than 10× the default vertex count, or a run
/// estimated over a minute (issue 33: `--spacing 0.01` on the torus example made 3.5M
/// vertices in 71 s without a word): the count, the time, and `vertices` suggested.
pub(crate) fn size_warning(spacing: f64, vertices: f64, options: &Options) -> Option<crate::Warning> {
    let default = crate::pipeline::MeshOptions::DEFAULT_VERTICES as f64;
    let t = seconds(vertices, options);
    (vertices > 10.0 * default || t > 60.0).then(|| {
        crate::Warning::new(format!(
            "`spacing` {spacing:.3e} makes about {vertices:.2e} vertices ({:.0}× the default {default:.0}), about {} \
             on a 2-core machine; give `vertices` to choose the size instead",
            vertices / default,
            if t < 90.0 { format!("{t:.0} s") } else { format!("{:.0} min", t / 60.0) }
        ))
    })
}

#[cfg(test)]
#[path = "tests/budget.rs"]
mod tests;
