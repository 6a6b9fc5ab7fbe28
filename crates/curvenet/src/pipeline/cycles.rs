//! The network a surface run uses, with the cycles of its patches written into it
//! (`curvenet cycles`, Python `curvenet.cycles`; docs/design.md §15): consolidated, its missing
//! normals inferred, and `cycles` listing every patch's cycle in patch order. A
//! surface made from it has the run's patches; a person deletes a cycle to leave its patch
//! open, or adds one.

use super::options::Options;
use super::prepare::{topology, Topology};
use super::stats::Timings;
use crate::error::{Error, Result, Warning};
use crate::network::Network;
use crate::topology::cycles::{key_of, keys_of, open_cycle_along};

/// `network` as a surface run with `options` would surface it — consolidated (unless it has
/// cycles), its missing normals inferred (keeping cycles it has) — with its topology, and the
/// warnings of those stages.
fn as_surfaced(network: &Network, options: &Options) -> Result<(Network, Topology, Vec<Warning>)> {
    let mut quiet = |_: &str, _: f64, _: &str| {};
    let mut warnings = Vec::new();
    let consolidated = super::consolidate(network, options, &mut quiet)?;
    let net = match consolidated {
        Some(c) if c.changed() => {
            warnings.extend(c.warnings);
            c.network
        }
        _ => network.clone(),
    };
    let net = if super::infer::needs_inference(&net, options) {
        let i = super::infer_normals(&net, options)?;
        // Curves that bound no patch: the node finding below says so again, in a surface's words.
        warnings.extend(i.warnings.into_iter().filter(|w| !w.message.contains("would be left out of a surface")));
        i.network
    } else {
        net
    };
    let topo = topology(&net, &options.mesh, net.cycles.as_deref(), &mut Timings::default(), &mut quiet)?;
    warnings.extend(topo.warnings.iter().cloned());
    Ok((net, topo, warnings))
}

/// `network` as a surface run with `options` would surface it, with its patches' cycles in
/// [`Network::cycles`], and the warnings of the stages run (consolidation, inference, node
/// finding, cycles). A network that has cycles keeps them (checked against it).
pub fn network_with_cycles(network: &Network, options: &Options) -> Result<(Network, Vec<Warning>)> {
    let (net, topo, warnings) = as_surfaced(network, options)?;
    // The network as the run had it, not validated again: a surface made from it validates it
    // as the run did (the same graph, so the keys fit) and gives the run's mesh to the bit.
    let mut out = net;
    out.cycles = Some(keys_of(&topo.g, &topo.patches));
    Ok((out, warnings))
}

/// `network` with patch `patch` (numbered as a surface of it with `options` numbers its
/// patches) left open: its cycle removed from [`Network::cycles`], which are first written
/// as [`network_with_cycles`] does (the viewer's click, docs/design.md §15). Patches past the
/// cycles (those of lone closed boundary curves, found again by every run) cannot be left open
/// this way: an error.
pub fn with_patch_left_open(network: &Network, options: &Options, patch: usize) -> Result<Network> {
    let (mut net, _) = network_with_cycles(network, options)?;
    let cycles = net.cycles.get_or_insert_with(Vec::new);
    if patch >= cycles.len() {
        return Err(Error::usage(format!(
            "patch {patch} cannot be left open: the network's cycles are the patches 0 to {} (a patch past them is \
             bounded by closed boundary curves that meet no other, which every run fills)",
            cycles.len() as isize - 1
        )));
    }
    cycles.remove(patch);
    Ok(net)
}

/// `network` with the open cycle along curve `curve` (of the network as surfaced: consolidated
/// where it has no cycles yet) filled: the cycle of the open border (a loop of segments with a
/// patch on one side only, boundary curves aside) that runs along it added to
/// [`Network::cycles`], which are first written as [`network_with_cycles`] does (the viewer's
/// click on a curve, docs/design.md §15). Errors when `curve` borders no open cycle or its
/// border branches ([`open_cycle_along`]).
pub fn with_cycle_filled(network: &Network, options: &Options, curve: usize) -> Result<Network> {
    let (mut net, topo, _) = as_surfaced(network, options)?;
    let cycle = open_cycle_along(&topo.g, &topo.patches, curve)?;
    let mut cycles = keys_of(&topo.g, &topo.patches);
    cycles.push(key_of(&topo.g, &cycle));
    net.cycles = Some(cycles);
    Ok(net)
}
