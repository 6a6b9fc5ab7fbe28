//! Patches from cycles chosen beforehand ([`crate::topology::search`], on the graph that normal
//! inference built): mapped onto this graph's segments by their places on the curves, the
//! segments no chosen cycle runs along left out, and the lone boundary loops (parts of the
//! network made of boundary curves only) paired into tubes and disks as the rotation walk
//! pairs them.

use super::faces::Parts;
use super::{find_patches_open, HalfEdge, Patch};
use crate::curves::CurveSpline;
use crate::error::{Result, Warning};
use crate::topology::nodes::Graph;
use crate::topology::open::remove_segments;
use crate::topology::search::CycleKey;
use std::collections::HashMap;

/// Per segment place `(curve, first sample, last sample)`: the segment's index in `g` (the
/// same segment in another graph of the same curves, which numbers its segments anew).
pub fn segment_places(g: &Graph) -> HashMap<(usize, usize, usize), usize> {
    g.segments.iter().enumerate().map(|(i, s)| ((s.curve, s.first, s.last), i)).collect()
}

/// Checks cycles given with the network (`"cycles"` in its JSON, docs/design.md §15): each a
/// closed chain of segments of `g` — a segment is the stretch of a curve between two nodes,
/// written `[curve, first sample, last sample, forward]` — each segment in at most two cycles.
/// The error names the cycle, the segment and what is wrong with it.
pub fn check_keys(g: &Graph, keys: &[CycleKey]) -> Result<()> {
    let at = segment_places(g);
    let parts = Parts::new(g);
    let lone = |s: usize| !parts.has_interior[parts.seg_root[s]] && g.segments[s].boundary;
    // Per segment: the cycles along it so far, with their direction.
    let mut uses: Vec<Vec<(usize, bool)>> = vec![Vec::new(); g.segments.len()];
    let fail = |k: usize, what: String| {
        Err(crate::Error::topology(format!(
            "cycle {k} of the network's \"cycles\": {what} (a cycle lists the segments around a patch, \
             [curve, first sample, last sample, forward] each, as `curvenet normals` writes them; remove \
             \"cycles\" to let the pipeline find them)"
        )))
    };
    for (k, key) in keys.iter().enumerate() {
        if key.is_empty() {
            return fail(k, "it has no segments".into());
        }
        let mut ends = Vec::with_capacity(key.len());
        for &(c, f, l, forward) in key {
            let Some(&s) = at.get(&(c, f, l)) else {
                let what = match g.labels.get(c) {
                    None => format!("curve {c} is not in the network ({} curves)", g.labels.len()),
                    Some(name) => format!(
                        "{name} has no segment from sample {f} to sample {l} (segments run between the nodes where \
                         curves meet)"
                    ),
                };
                return fail(k, what);
            };
            let what = match uses[s].as_slice() {
                [.., (j, _)] if *j == k => Some("twice".to_string()),
                [_, _] => Some("in a third cycle".to_string()),
                [(j, fw)] if *fw == forward => Some(format!(
                    "in the direction cycle {j} runs along it too (two patches that share a segment run along it in \
                     opposite directions: reverse this cycle's segments, or cycle {j}'s)"
                )),
                _ => None,
            };
            if let Some(what) = what {
                return fail(k, format!("the segment of {} from sample {f} to {l} is {what}", g.labels[c]));
            }
            uses[s].push((k, forward));
            let seg = &g.segments[s];
            ends.push(if forward { (seg.start, seg.end) } else { (seg.end, seg.start) });
        }
        if key.iter().all(|&(c, f, l, _)| lone(at[&(c, f, l)])) {
            return fail(
                k,
                "it runs along closed boundary curves that meet no other curve only, which every run fills by itself"
                    .into(),
            );
        }
        for i in 0..ends.len() {
            let next = ends[(i + 1) % ends.len()];
            if ends[i].1 != next.0 {
                let (c, f, l, _) = key[i];
                return fail(
                    k,
                    format!(
                        "it does not close: the segment of {} from sample {f} to {l} ends at node {}, the next \
                         segment starts at node {}",
                        g.labels[c], ends[i].1, next.0
                    ),
                );
            }
        }
    }
    Ok(())
}

/// The cycles of `patches` as [`CycleKey`]s on `g`, in patch order: the disks, except those
/// made of lone boundary loops (parts of the network with boundary curves only), which
/// [`patches_from_keys`] finds again by itself, as it finds the tubes between them.
pub fn keys_of(g: &Graph, patches: &[Patch]) -> Vec<CycleKey> {
    let parts = Parts::new(g);
    let lone = |s: usize| !parts.has_interior[parts.seg_root[s]] && g.segments[s].boundary;
    patches
        .iter()
        .filter_map(|p| match p {
            Patch::Disk(cycle) if !cycle.iter().all(|h| lone(h.segment)) => Some(key_of(g, cycle)),
            _ => None,
        })
        .collect()
}

/// The cycle of half-edges `cycle` of `g` as a [`CycleKey`]: its segments' places.
pub fn key_of(g: &Graph, cycle: &[HalfEdge]) -> CycleKey {
    cycle
        .iter()
        .map(|h| {
            let s = &g.segments[h.segment];
            (s.curve, s.first, s.last, h.forward)
        })
        .collect()
}

/// The open border of `patches` that runs along curve `curve`, as a cycle that fills it: the
/// segments of `g` with one patch on one side and none on the other (boundary curves aside),
/// followed from one of `curve`'s, each run against its patch's direction (so the new patch is
/// oriented as its neighbours). Errors (usage: what the user pointed at has no such border)
/// when `curve` borders no open cycle, or when the border branches at a node (several open
/// borders meet there: the cycle to fill is a person's choice, in the file).
pub fn open_cycle_along(g: &Graph, patches: &[Patch], curve: usize) -> Result<Vec<HalfEdge>> {
    let n = g.segments.len();
    let mut along: Vec<Vec<bool>> = vec![Vec::new(); n];
    for p in patches {
        for h in p.half_edges() {
            along[h.segment].push(h.forward);
        }
    }
    // Per open segment the direction of the filling half-edge, and its start node.
    let fill: Vec<Option<HalfEdge>> = (0..n)
        .map(|s| {
            (along[s].len() == 1 && !g.segments[s].boundary).then(|| HalfEdge { segment: s, forward: !along[s][0] })
        })
        .collect();
    let from = |h: HalfEdge| if h.forward { g.segments[h.segment].start } else { g.segments[h.segment].end };
    let to = |h: HalfEdge| if h.forward { g.segments[h.segment].end } else { g.segments[h.segment].start };
    let mut leaving: Vec<Vec<HalfEdge>> = vec![Vec::new(); g.nodes.len()];
    for h in fill.iter().flatten() {
        leaving[from(*h)].push(*h);
    }
    let label = g.labels.get(curve).cloned().unwrap_or_else(|| format!("curve {curve}"));
    let Some(first) = fill.iter().flatten().find(|h| g.segments[h.segment].curve == curve).copied() else {
        return Err(crate::Error::usage(format!(
            "{label} borders no open cycle (each of its segments has patches on both sides, or none): nothing to fill"
        )));
    };
    let mut cycle = vec![first];
    while to(cycle[cycle.len() - 1]) != from(first) {
        let at = to(cycle[cycle.len() - 1]);
        let next: Vec<HalfEdge> =
            leaving[at].iter().filter(|h| !cycle.iter().any(|c| c.segment == h.segment)).copied().collect();
        match next.as_slice() {
            [h] if cycle.len() < n => cycle.push(*h),
            [] => {
                return Err(crate::Error::usage(format!(
                    "the open border along {label} does not close at node {at}: it ends on curves with patches on both \
                     sides or none"
                )))
            }
            _ => {
                return Err(crate::Error::usage(format!(
                    "the open border along {label} branches at node {at} (several open borders meet there): which \
                     cycle to fill is yours to choose — add it to the \"cycles\" of `curvenet cycles`' file"
                )))
            }
        }
    }
    Ok(cycle)
}

/// The patches of `g` bounded by the cycles `keys`, and the lone loops' tubes and disks;
/// segments outside them are removed from `g`, each curve left out wholly named in a warning.
/// `None` when some key is not a segment of `g` (the graph differs from the one the cycles
/// were chosen on): the caller then finds the patches itself.
pub fn patches_from_keys(
    g: &mut Graph,
    splines: &[CurveSpline],
    keys: &[CycleKey],
) -> Result<Option<(Vec<Patch>, Vec<Warning>)>> {
    let at = segment_places(g);
    if keys.iter().flatten().any(|k| !at.contains_key(&(k.0, k.1, k.2))) {
        return Ok(None);
    }
    let mut used = vec![false; g.segments.len()];
    keys.iter().flatten().for_each(|k| used[at[&(k.0, k.1, k.2)]] = true);
    let parts = Parts::new(g);
    let lone = |g: &Graph, parts: &Parts, s: usize| !parts.has_interior[parts.seg_root[s]] && g.segments[s].boundary;
    let unused: Vec<usize> = (0..g.segments.len()).filter(|&s| !used[s] && !lone(g, &parts, s)).collect();
    let mut warnings = Vec::new();
    let mut named: Vec<usize> = Vec::new();
    for &s in &unused {
        let c = g.segments[s].curve;
        if !named.contains(&c) {
            named.push(c);
        }
    }
    for &c in named.iter().take(10) {
        let whole = g.segments.iter().enumerate().filter(|(_, seg)| seg.curve == c).all(|(s, _)| !used[s]);
        let what = if whole { "bounds none of the patches chosen" } else { "runs partly outside the patches chosen" };
        warnings.push(
            Warning::new(format!(
                "{} {what} (it cuts into a patch or dangles from the network): the part outside was left out of \
                 the surface",
                g.labels[c]
            ))
            .curve(c),
        );
    }
    if named.len() > 10 {
        warnings.push(Warning::new(format!("{} more curves were left out in part or wholly", named.len() - 10)));
    }
    remove_segments(g, &unused);
    let at = segment_places(g);
    let mut patches: Vec<Patch> = keys
        .iter()
        .map(|k| {
            Patch::Disk(k.iter().map(|&(c, f, l, forward)| HalfEdge { segment: at[&(c, f, l)], forward }).collect())
        })
        .collect();
    // Lone boundary loops: the rotation walk's tubes and disks, on a graph of them alone.
    let parts = Parts::new(g);
    let others: Vec<usize> = (0..g.segments.len()).filter(|&s| !lone(g, &parts, s)).collect();
    if others.len() < g.segments.len() {
        let mut sub = g.clone();
        remove_segments(&mut sub, &others);
        let (loops, w) = find_patches_open(&mut sub, splines)?;
        warnings.extend(w);
        let back = |h: &HalfEdge| {
            let s = &sub.segments[h.segment];
            HalfEdge { segment: at[&(s.curve, s.first, s.last)], forward: h.forward }
        };
        for p in loops {
            patches.push(match p {
                Patch::Disk(c) => Patch::Disk(c.iter().map(back).collect()),
                Patch::Tube([a, b]) => Patch::Tube([a.iter().map(back).collect(), b.iter().map(back).collect()]),
            });
        }
    }
    Ok(Some((patches, warnings)))
}
