//! The sampled network as `curvenet surface` takes it (issue 29: the default round trip
//! `sample` → `surface` failed on a human figure). The pipeline's own checks — consolidation,
//! validation, nodes, cycles, tessellation at the default options, no solve — run on the
//! assembled network; a curve they refuse is left out and they run again, at most
//! [`MAX_ROUNDS`] times. Of the curves an error names, a crease goes first (the surface is then
//! smooth there), else the curve the error is about.

use super::SampleReport;
use crate::error::{Error, Result};
use crate::network::Network;
use crate::pipeline::Options;

/// The most curves left out for the checks.
pub const MAX_ROUNDS: usize = 48;

/// The pipeline's checks of `net` at `options` (no solve).
fn check(net: &Network, options: &Options) -> Result<()> {
    let mut quiet = |_: &str, _: f64, _: &str| {};
    let consolidated = crate::pipeline::consolidate(net, options, &mut quiet)?;
    let network = consolidated.as_ref().filter(|c| c.changed()).map_or(net, |c| &c.network);
    crate::pipeline::infer::infer_and_prepare(network, options, &mut quiet).map(|_| ())
}

/// The curve of `net` to leave out for error `e`: of those whose names the message quotes, a
/// crease first, else the last named; `None` when it names none.
fn culprit(net: &Network, e: &Error) -> Option<usize> {
    let text = e.to_string();
    let named: Vec<usize> = (0..net.curves.len())
        .filter(|&i| net.curves[i].name.as_ref().is_some_and(|n| text.contains(&format!("(\"{n}\")"))))
        .collect();
    named.iter().copied().find(|&i| !net.curves[i].normals_right.is_empty()).or(named.last().copied())
}

/// `net` with the curves the pipeline's checks refuse left out, each named with its reason in
/// `report.left_out`; the error that remains, if any, in `report.unsurfaced`.
pub(super) fn surfaceable(mut net: Network, report: &mut SampleReport) -> Network {
    let options = Options::default();
    for _ in 0..MAX_ROUNDS {
        let e = match check(&net, &options) {
            Ok(()) => return net,
            Err(e) => e,
        };
        let Some(c) = culprit(&net, &e) else {
            report.unsurfaced = Some(e.to_string());
            return net;
        };
        let curve = &net.curves[c];
        let count = if !curve.normals_right.is_empty() {
            &mut report.creases
        } else if curve.boundary {
            &mut report.boundary_loops
        } else {
            &mut report.sections
        };
        *count = count.saturating_sub(1);
        let name = curve.name.clone().unwrap_or_default();
        report.left_out.push(format!("{name}: {e}"));
        net.curves.remove(c);
    }
    if let Err(e) = check(&net, &options) {
        report.unsurfaced = Some(e.to_string());
    }
    net
}
