//! The whole pipeline, network in, surface out (\[CG\] §3.1; docs/design.md §1).
//!
//! 1. [`options`]: the run's options, their names and presets.
//! 1. [`infer`]: normals for the curves that come without them (then the paper's pipeline
//!    runs as for given normals).
//! 2. [`prepare`]: validate, find nodes, fit splines, trace the cycles, pick the spacing,
//!    resample, tessellate (planar or conformal patching: `levels.rs`, the coarse levels the
//!    default solves and iterates on before the fine one).
//! 3. [`solve`]: the method on the patches' domain operators, then normal-control's 3D
//!    iterations.
//! 4. [`details`]: parts of the surface that are only loops drawn on the rest of it left out;
//!    [`coverage`]: how near the surface passes to the strokes, and how far each patch strays.
//! 5. [`stats`]: the surface, its statistics and timings.
//!
//! [`surface`] runs them once; [`surfacer::Surfacer`] keeps the mesh and the method's
//! factorisations for re-solves with new curve normals or positions.

pub mod budget;
pub mod coverage;
pub mod cycles;
pub mod details;
pub mod files;
pub mod infer;
mod levels;
pub mod options;
pub mod prepare;
pub mod solve;
pub mod stats;
pub mod surfacer;

pub use cycles::{network_with_cycles, with_cycle_filled, with_patch_left_open};
pub use infer::{infer_normals, Inferred};
pub use options::{InferNormals, MeshOptions, OptionSpec, Options, Patching, Preset, OPTIONS};
pub use stats::{InferredNormals, Stats, Surface, Timings};

use crate::error::Result;
use crate::network::Network;
use crate::topology::consolidate::Consolidated;
use std::borrow::Cow;

/// Surfaces `network` with `options`. See [`surface_with_progress`].
pub fn surface(network: &Network, options: &Options) -> Result<Surface> {
    surface_with_progress(network, options, &mut |_, _, _| {})
}

/// Surfaces `network`, reporting each finished stage to `progress(stage, seconds, detail)`:
/// "consolidate" (when raw strokes were changed), "normals" (when inferred), "nodes", "cycles", the default's coarse level ("coarse start",
/// each "coarse iteration", "coarse level"), "resample", "tessellate", "first solve" (without
/// a coarse level), each "iteration" (detail "k of at most n, largest move …"), "solve".
pub fn surface_with_progress(
    network: &Network,
    options: &Options,
    progress: &mut dyn FnMut(&str, f64, &str),
) -> Result<Surface> {
    // A sketch's patch that runs away (a cycle the choice got wrong) is left open and the
    // sketch surfaced again, a few times at most; a network with normals or cycles of its own
    // keeps the error (docs/design.md §15).
    let retry = network.cycles.is_none() && infer::needs_inference(network, options);
    // Consolidated once: a retry surfaces the consolidated network with its cycles (which
    // consolidation leaves as they are), and its result carries this report.
    let mut consolidated = consolidate(network, options, progress)?;
    let mut current = Cow::Borrowed(network);
    let mut opened: Vec<(usize, String)> = Vec::new();
    // What the first normal inference reported (a retry's network carries the normals).
    let mut inference = None;
    loop {
        let attempt = match (&consolidated, opened.is_empty()) {
            (Some(c), true) if c.changed() => &c.network,
            _ => &*current,
        };
        match surface_as(attempt, network, options, progress, &mut inference) {
            Err(e) if retry && opened.len() < MAX_OPENED && is_runaway(&e).is_some() => {
                let patch = is_runaway(&e).unwrap_or(0);
                // A patch past the cycles (a lone loop's disk) cannot be left open: the error stands.
                let Ok(next) = cycles::with_patch_left_open(&current, options, patch) else { return Err(e) };
                // "patch N: its surface runs away … outside them", without what the error adds.
                let text = e.to_string();
                let why = text.split(" (a spike").next().unwrap_or(&text).trim_start_matches("numerical failure: ");
                opened.push((patch, why.to_string()));
                current = Cow::Owned(next);
            }
            Err(e) => return Err(e),
            Ok(mut s) => {
                for (patch, why) in opened.iter().rev() {
                    s.warnings.insert(
                        0,
                        crate::error::Warning::new(format!(
                            "{why} (a cycle that bounds no sensible surface): it was left open and the sketch \
                             surfaced again without it"
                        ))
                        .patch(*patch),
                    );
                }
                if let Some((report, warnings)) = inference.take() {
                    infer::add_to_surface(&mut s, &report, &warnings);
                }
                if let Some(c) = consolidated.take() {
                    add_consolidation(&mut s, c);
                }
                return Ok(s);
            }
        }
    }
}

/// Patches of a sketch left open at most, one after another, when they run away.
const MAX_OPENED: usize = 3;

/// The patch of a run-away error ([`coverage::check_reach`]).
fn is_runaway(e: &crate::Error) -> Option<usize> {
    match e {
        crate::Error::Numerical { message, .. } if message.contains("runs away from its curves") => e.at().patch,
        _ => None,
    }
}

/// What a normal inference reported: its statistics and warnings.
type Inference = (InferredNormals, Vec<crate::error::Warning>);

/// [`surface_with_progress`] once: `network` (consolidated, or with its cycles) surfaced, its
/// coverage measured against `original` (the strokes as given). The report of a normal
/// inference goes to `inference` when that holds none yet (the caller adds it to the surface:
/// a retry's network carries the inferred normals, and its run infers none).
fn surface_as(
    network: &Network,
    original: &Network,
    options: &Options,
    progress: &mut dyn FnMut(&str, f64, &str),
    inference: &mut Option<Inference>,
) -> Result<Surface> {
    let (inferred, prepared) = infer::infer_and_prepare(network, options, progress)?;
    if let (Some(i), None) = (&inferred, &inference) {
        *inference = Some((i.report.clone(), i.warnings.clone()));
    }
    if let Some(r) = inferred.as_ref().map(|i| &i.report) {
        progress("normals", r.seconds, &format!("{} curves inferred", r.curves));
    }
    let explain = |e| if inferred.is_some() { infer::explain(e) } else { e };
    let base = prepared.timings;
    let mut surface = solve::solve_prepared(Cow::Owned(prepared), options, progress, None, base).map_err(explain)?;
    if inferred.is_some() || !surface.warnings.is_empty() || !std::ptr::eq(network, original) {
        let mut warnings = Vec::new();
        let clock = crate::solve::timing::Instant::now();
        surface.stats.coverage = Some(coverage::check_coverage(&surface.mesh, original, &mut warnings)?);
        let (loops, open) = coverage::check_open_borders(&surface.mesh);
        surface.stats.open_borders = Some(loops);
        warnings.extend(open);
        surface.stats.timings.total += crate::solve::timing::seconds_since(clock);
        surface.warnings.extend(warnings);
    }
    Ok(surface)
}

/// The consolidation stage ([`crate::topology::consolidate`]) with the run's options: `None`
/// when it is off.
pub(crate) fn consolidate(
    network: &Network,
    options: &Options,
    progress: &mut dyn FnMut(&str, f64, &str),
) -> Result<Option<Consolidated>> {
    // A network with its cycles is taken as it is: the cycles name its segments.
    if !options.consolidate.enabled || network.cycles.is_some() {
        return Ok(None);
    }
    prepare::check_options(options)?;
    let c = crate::topology::consolidate::consolidate(network, &options.consolidate, options.mesh.snap)?;
    let r = &c.report;
    if c.changed() {
        let detail = format!("{} joined, {} crossed, {} merged, {} trimmed", r.joined, r.crossed, r.merged, r.trimmed);
        progress("consolidate", r.seconds, &detail);
    }
    Ok(Some(c))
}

/// Adds what consolidation did to the `surface` of the network it made: its statistics and
/// seconds, its warnings first.
pub(crate) fn add_consolidation(surface: &mut Surface, c: Consolidated) {
    surface.stats.timings.consolidate = c.report.seconds;
    surface.stats.timings.total += c.report.seconds;
    surface.stats.consolidation = Some(c.report);
    let mut warnings = c.warnings;
    warnings.append(&mut surface.warnings);
    surface.warnings = warnings;
}
