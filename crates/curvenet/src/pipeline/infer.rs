//! Normals for networks that come without them (docs/design.md §12): 3D sketches, CAD edges,
//! polylines. Runs before the paper's pipeline, which then sees a network with a normal at
//! every sample and runs exactly as for given normals.
//!
//! The normals come from the network's shape ([`crate::topology::orient`]): exact at the
//! crossings (the tangent plane holds the crossing curves' tangents), one orientation for the
//! whole network (outward where it is closed), carried along the segments between crossings
//! with the least twist. Given normals always win: only curves without normals are inferred
//! (every curve with `infer_normals = all`).
//!
//! Measured and left out: reading the normals between the crossings off a first surface fitted
//! to the positions alone (the triharmonic fit, planar or 3D metric) made the final surfaces
//! worse on 3 of 4 networks at 10k–20k vertices (torus 37×, beetle 1.15×, sphere 1.07× the
//! error; bumpy cube 0.96×): a positions-only fit of a coarse network is further from the truth
//! than the least-twist normals (docs/design.md §12).

use super::options::{InferNormals, Options};
use super::prepare::{check_options, prepare, Prepared, Progress};
use super::stats::InferredNormals;
use crate::curves::CurveSpline;
use crate::error::{Result, Warning};
use crate::geom::DVec3;
use crate::network::Network;
use crate::solve::timing::{seconds_since, Instant};
use crate::topology::cycles::{find_patches_open, half_edge_samples, segment_places};
use crate::topology::nodes::Graph;
use crate::topology::orient::infer_normals as orient_graph;
use crate::topology::search::CycleKey;
use crate::topology::Patch;
use crate::topology::{find_nodes, trim_dangling};
use rayon::prelude::*;

/// Strokes left out as duplicates before the overlap is reported as an error (each costs a
/// node finding: a tangle of strokes is refused rather than taken apart one by one).
pub const MAX_LEFT_OUT: usize = 16;

/// A network with its normals inferred.
#[derive(Clone, Debug)]
pub struct Inferred {
    /// The validated network with a unit normal at every sample.
    pub network: Network,
    /// What the inference found (the `inferred_normals` of `--stats`).
    pub report: InferredNormals,
    /// What was assumed or repaired (the validation's warnings among them).
    pub warnings: Vec<Warning>,
    /// The cycles chosen for the patches ([`crate::topology::search`]), on the curves of
    /// `network`; `None` where the rotation walk on the inferred normals finds them.
    pub cycles: Option<Vec<CycleKey>>,
}

/// Whether a run with `options` infers normals for `network`: some curve has none, or
/// `infer_normals = all`.
pub fn needs_inference(network: &Network, options: &Options) -> bool {
    options.infer_normals == InferNormals::All || !network.has_all_normals()
}

/// Infers the normals of the curves of `network` that have none (every curve's with
/// `infer_normals = all`); see the module documentation. `options` give the snapping
/// tolerance.
///
/// Errors: those of [`crate::surface`] for the network's validity and topology (dangling
/// strokes, curves that bound no 2-manifold). A network whose orientation contradicts itself
/// (a Möbius-like network) is a warning naming the segments, not an error.
pub fn infer_normals(network: &Network, options: &Options) -> Result<Inferred> {
    // The choice a surface run with `options` makes (`infer_and_prepare`: the search's cycles
    // or the walk's, whichever is tried first and can be tessellated). The network returned
    // carries the cycles chosen (its `cycles`; none for the walk's), so that a surface made
    // from it has the same patches.
    let mut quiet = |_: &str, _: f64, _: &str| {};
    let prepared = match needs_inference(network, options) && network.cycles.is_none() {
        true => infer_and_prepare(network, options, &mut quiet).ok().and_then(|(i, _)| i),
        false => None,
    };
    let mut inferred = match prepared {
        Some(i) => i,
        // Where no surface can be made: the inference the run would try first.
        None => {
            let searched = infer(network, options, true);
            let walked = infer(network, options, false);
            match (searched, walked) {
                (Ok(s), Ok(w)) if s.report.patched_share + 0.02 < w.report.patched_share => w,
                (Ok(s), _) => s,
                (Err(_), Ok(w)) => w,
                (Err(e), Err(_)) => return Err(e),
            }
        }
    };
    // Cycles the network came with stay (they are the user's; they name its curves, so none
    // may have been left out); else the patches a run makes of the cycles chosen (the search's
    // where they fit the network's graph, the walk's otherwise), so that the file surfaces
    // as the run does.
    match inferred.network.cycles.take() {
        Some(given) => {
            if inferred.network.curves.len() != network.curves.len() {
                return Err(curves_left_out(network.curves.len() - inferred.network.curves.len()));
            }
            inferred.network.cycles = Some(given);
        }
        // Nothing inferred: the network as it came (the walk finds its cycles as before).
        None if !needs_inference(network, options) => {}
        None => {
            let mut quiet = |_: &str, _: f64, _: &str| {};
            let mut timings = crate::pipeline::Timings::default();
            let topo = super::prepare::topology(
                &inferred.network,
                &options.mesh,
                inferred.cycles.as_deref(),
                &mut timings,
                &mut quiet,
            );
            inferred.network.cycles = topo.ok().map(|t| crate::topology::cycles::keys_of(&t.g, &t.patches));
        }
    }
    for w in &mut inferred.warnings {
        w.message = without_a_surface(&w.message);
    }
    Ok(inferred)
}

/// The error for cycles given with a network some of whose curves inference left out.
fn curves_left_out(n: usize) -> crate::Error {
    crate::Error::topology(format!(
        "the network's \"cycles\" name its curves by index, but {n} of its curves were left out as duplicates \
         while inferring normals: remove them from the file, or remove \"cycles\""
    ))
}

/// A warning of the inference said where no surface is made (`curvenet normals`, Python's
/// `infer_normals`; issue 33): a stroke removed as a duplicate is left out of the network
/// written; a curve that bounds no patch is in it, with its normals, and would be left out of a
/// surface.
fn without_a_surface(message: &str) -> String {
    message.replace(": it was left out of the surface", ": it was left out of the network").replace(
        "was left out of the surface",
        "would be left out of a surface made from the network (its normals were inferred all the same)",
    )
}

/// Normal inference and preparation for a network that needs it. Two choices of the patches
/// are made: the cycles chosen over the whole network ([`crate::topology::search`]) and the
/// rotation walk on the inferred normals (\[CG\] §3.2, as before the search). The search's is
/// tried first unless the walk's runs along clearly more of the sketch (2 % of its length:
/// the greedy search leaves open what it cannot justify, a thin closed part such as a
/// sketched ear among it); where the first cannot be surfaced (its own error or the
/// preparation's), the other, with a warning that says why. When neither can, the walk's
/// error is the run's. `None` for a network that has all its normals.
pub(crate) fn infer_and_prepare(
    network: &Network,
    options: &Options,
    progress: Progress<'_>,
) -> Result<(Option<Inferred>, Prepared)> {
    if !needs_inference(network, options) {
        return Ok((None, prepare(network, options, network.cycles.as_deref(), progress)?));
    }
    if let Some(given) = network.cycles.as_deref() {
        // Cycles given with the network: its curves' normals are inferred around them (the
        // search's, as without them), the patches are the given cycles.
        let mut i = infer(network, options, true)?;
        if i.network.curves.len() != network.curves.len() {
            return Err(curves_left_out(network.curves.len() - i.network.curves.len()));
        }
        // The given cycles are the patches (also of a `Surfacer`'s re-preparation).
        i.cycles = Some(given.to_vec());
        let p = prepare(&i.network, options, Some(given), progress).map_err(explain)?;
        return Ok((Some(i), p));
    }
    let searched = infer(network, options, true);
    let walked = infer(network, options, false);
    // Both inferences are the run's work: the one used reports the time of the two.
    let seconds: f64 = [&searched, &walked].iter().filter_map(|r| r.as_ref().ok()).map(|i| i.report.seconds).sum();
    let search_first = match (&searched, &walked) {
        (Ok(s), Ok(w)) => s.report.patched_share + 0.02 >= w.report.patched_share,
        (Ok(_), Err(_)) => true,
        (Err(_), _) => false,
    };
    // `repairs`: meetings of curves whose inferred normals disagree that may be made one
    // (a crease the inference smoothed, a dense junction; issue 30) — only when neither
    // choice can be surfaced as inferred, so that a choice that surfaces keeps its normals.
    let attempt = |mut i: Inferred, repairs: usize, progress: Progress<'_>| {
        i.report.seconds = seconds;
        let mut repaired = 0;
        loop {
            match prepare(&i.network, options, i.cycles.as_deref(), progress) {
                Ok(p) => return Ok::<_, crate::Error>((i, p)),
                Err(e) if repaired < repairs && points_inward(&e).is_some() => {
                    let p = points_inward(&e).unwrap_or(DVec3::ZERO);
                    let snap = i.network.snap.unwrap_or_else(|| i.network.snap_tolerance());
                    if !agree_at(&mut i.network, p, 2.0 * snap) {
                        return Err(explain(e));
                    }
                    repaired += 1;
                    i.report.contradictions += 1;
                    i.warnings.push(
                        Warning::new(format!(
                            "{e}: the inferred normals there were made one (their mean) and the network surfaced so"
                        ))
                        .curve(e.at().curve.unwrap_or(0)),
                    );
                }
                Err(e) => return Err(explain(e)),
            }
        }
    };
    let (first, second) = if search_first { (searched, walked) } else { (walked, searched) };
    let copies = (first.as_ref().ok().cloned(), second.as_ref().ok().cloned());
    let first = first.and_then(|i| attempt(i, 0, &mut *progress));
    let (this, other) = if search_first {
        ("the rotation walk on the inferred normals", "chosen over the whole network")
    } else {
        ("the cycle choice over the whole network", "of the rotation walk on the inferred normals")
    };
    let fell_back = |e: &crate::Error| {
        Warning::new(format!(
            "the patches {other} could not be surfaced ({e}); they were found by {this} instead: check the result"
        ))
    };
    match first {
        Ok((i, p)) => Ok((Some(i), p)),
        Err(e) => {
            // The second choice; when it fails too, each again with their normals made one
            // where curves meet at odds; when that fails too, the walk's error stands (as
            // before the search).
            match second.and_then(|i| attempt(i, 0, &mut *progress)) {
                Ok((mut i, p)) => {
                    i.warnings.push(fell_back(&e));
                    Ok((Some(i), p))
                }
                Err(e2) => {
                    if let Some(Ok((i, p))) = copies.0.map(|i| attempt(i, MAX_MEETINGS_REPAIRED, &mut *progress)) {
                        return Ok((Some(i), p));
                    }
                    if let Some(Ok((mut i, p))) = copies.1.map(|i| attempt(i, MAX_MEETINGS_REPAIRED, &mut *progress)) {
                        i.warnings.push(fell_back(&e));
                        return Ok((Some(i), p));
                    }
                    Err(if search_first { e2 } else { e })
                }
            }
        }
    }
}

/// Meetings of curves whose inferred normals disagree made one at most, one after another.
const MAX_MEETINGS_REPAIRED: usize = 8;

/// The place of node finding's error on curves that meet with normals more than 90° apart.
fn points_inward(e: &crate::Error) -> Option<DVec3> {
    match e {
        crate::Error::Input { message, .. } if message.contains("one of them points inward") => {
            e.at().point.map(DVec3::from_array)
        }
        _ => None,
    }
}

/// Makes the normals of `net`'s curves agree where they pass within `radius` of `p`: on each
/// such curve the two samples around its closest point to `p` take the mean of those samples'
/// normals (their bisector where two sheets meet at a crease), across the curve's tangent.
/// `false` when nothing changed (no curve there, or the normals cancel out).
fn agree_at(net: &mut Network, p: DVec3, radius: f64) -> bool {
    // Per curve passing near `p`: the samples around its closest point.
    let mut around: Vec<(usize, [usize; 2])> = Vec::new();
    for (ci, c) in net.curves.iter().enumerate() {
        let m = c.points.len();
        if m < 2 || c.normals.len() != m {
            continue;
        }
        let pieces = if c.closed { m } else { m - 1 };
        let best = (0..pieces)
            .map(|k| {
                let (a, b) = (c.points[k], c.points[(k + 1) % m]);
                (crate::geom::distance::closest_point_on_segment(p, a, b).distance(p), k)
            })
            .min_by(|x, y| x.0.total_cmp(&y.0));
        if let Some((_, k)) = best.filter(|b| b.0 <= radius) {
            around.push((ci, [k, (k + 1) % m]));
        }
    }
    let sum: DVec3 =
        around.iter().flat_map(|(c, ks)| ks.iter().map(move |&k| (*c, k))).map(|(c, k)| net.curves[c].normals[k]).sum();
    let Some(mean) = sum.try_normalize() else { return false };
    let mut changed = false;
    for (c, ks) in around {
        let curve = &mut net.curves[c];
        let t = (curve.points[ks[1]] - curve.points[ks[0]]).normalize_or_zero();
        let n = (mean - t * mean.dot(t)).normalize_or_zero();
        for k in ks {
            if n != DVec3::ZERO && n != curve.normals[k] {
                curve.normals[k] = n;
                changed = true;
            }
        }
    }
    changed
}

/// [`infer_normals`]; `search`: the cycles chosen over the whole network and the node normals
/// repaired from them (else the rotation walk's, as before the search).
fn infer(network: &Network, options: &Options, search: bool) -> Result<Inferred> {
    let start = Instant::now();
    check_options(options)?;
    let (mut net, mut warnings) = network.validated()?;
    let mut known: Vec<bool> =
        net.curves.iter().map(|c| c.has_normals() && options.infer_normals == InferNormals::Missing).collect();
    if known.iter().all(|k| *k) {
        return Ok(Inferred { network: net, report: InferredNormals::default(), warnings, cycles: None });
    }
    let snap = options.mesh.snap.or(net.snap).unwrap_or_else(|| net.snap_tolerance());
    let mut left_out = 0;
    let mut g = loop {
        let mut work = net.clone();
        for (c, k) in work.curves.iter_mut().zip(&known) {
            if !k {
                c.normals = vec![DVec3::ZERO; c.points.len()];
            }
        }
        match find_nodes(&work, snap) {
            Ok((g, w)) => {
                warnings.extend(w);
                break g;
            }
            // A sketched stroke drawn twice (or along another): leave it out and say so.
            Err(e) if is_overlap(&e).is_some_and(|c| !known[c]) && net.curves.len() > 1 && left_out < MAX_LEFT_OUT => {
                let c = is_overlap(&e).unwrap_or(0);
                name_curves(&mut net);
                warnings.push(Warning::new(format!("{e}: it was left out of the surface")));
                net.curves.remove(c);
                known.remove(c);
                left_out += 1;
            }
            Err(e) => return Err(e),
        }
    };
    // The validation's warnings and the strokes left out, which a second pass on the cleaned
    // network would not give again.
    let first_warnings = warnings.clone();
    let splines = fit_splines(&g);
    let orient = orient_graph(&mut g, &splines, &known)?;
    fill_gaps(&mut g, &known);
    warnings.extend(orient.warnings.iter().cloned());
    let lone = close_lone_loops(&mut g, &known);
    let (repaired, mut cycles, cycles_seconds) =
        if search { follow_chosen_cycles(&mut g, &splines, &known)? } else { (0, None, 0.0) };
    if repaired > 0 {
        clear_outside_segments(&mut g, &known);
        fill_gaps(&mut g, &known);
    }
    for &c in &lone {
        warnings.push(
            Warning::new(format!(
                "{} is a closed curve that meets no other: it was taken as the border of a disk (of a tube with \
                 a loop that faces it)",
                g.labels[c]
            ))
            .curve(c),
        );
    }
    let mut report = InferredNormals {
        curves: orient.inferred_curves,
        nodes_from_tangents: orient.nodes_from_tangents,
        nodes_transported: orient.nodes_transported,
        doubtful_links: orient.doubtful_links,
        contradictions: orient.contradictions.len(),
        left_out,
        turned_outward: orient.flipped_components,
        ..Default::default()
    };
    // The surface's topology with these normals: its errors are the network's (dangling
    // strokes, curves that bound no 2-manifold), reported here rather than after the solve.
    let mut trimmed = g.clone();
    warnings.extend(trim_dangling(&mut trimmed)?);
    let splines = fit_splines(&trimmed);
    let patches = match cycles.as_ref().map(|k| disks(&trimmed, k)) {
        Some(Some(p)) => p,
        _ => {
            cycles = None;
            find_patches_open(&mut trimmed, &splines)?.0
        }
    };
    // Petals: the network again with them tagged as the borders of sheets of their own, which
    // node finding keeps apart (a normal of their own where they touch the others).
    let petals = petals(&g, &trimmed, &patches, &known);
    if let Some(mut again) = with_petals_apart(&net, &petals, snap, options, search) {
        let mut w = first_warnings;
        let new: Vec<Warning> = again.warnings.into_iter().filter(|x| !w.contains(x)).collect();
        w.extend(new);
        again.warnings = w;
        again.report.left_out += left_out;
        again.report.seconds = seconds_since(start);
        return Ok(again);
    }
    let mut network = with_graph_normals(&net, &g, &known);
    for &c in &lone {
        network.curves[c].boundary = true;
    }
    // The tolerance the nodes were found with, also after curves were left out (the default
    // follows the mean sample spacing).
    network.snap = Some(snap);
    // A curve that was trimmed (a dangling end) is not tagged: a boundary curve is never cut back.
    let count = |g: &Graph| {
        let mut n = vec![0usize; g.curves.len()];
        g.segments.iter().for_each(|s| n[s.curve] += 1);
        n
    };
    let (before, after) = (count(&g), count(&trimmed));
    let whole: Vec<bool> = (0..g.curves.len()).map(|c| known[c] || before[c] != after[c]).collect();
    let mut dropped = Vec::new();
    for (curves, outer, covered) in flat_components(&trimmed, &patches, &whole, cycles.is_some()) {
        dropped.push(outer);
        if curves.is_empty() || !covered {
            continue;
        }
        let names: Vec<&str> = curves.iter().take(6).map(|&c| trimmed.labels[c].as_str()).collect();
        warnings.push(
            Warning::new(format!(
                "the curves {}{} enclose no volume (every cycle of them lies on one sheet): they were taken \
                 as an open surface whose border is patch {outer}'s cycle (tagged as boundary)",
                names.join(", "),
                if curves.len() > names.len() { ", …" } else { "" }
            ))
            .curve(curves[0]),
        );
        report.opened_components += 1;
        for c in curves {
            network.curves[c].boundary = true;
        }
    }
    if let Some(k) = cycles.as_mut() {
        dropped.sort_unstable();
        for &i in dropped.iter().rev() {
            k.remove(i);
        }
        report.cycles_repaired_nodes = repaired;
        report.chosen_cycles = k.len();
        report.cycles_seconds = cycles_seconds;
    }
    report.patched_share = patched_share(&g, &trimmed, &patches);
    report.walk_fallback = !search;
    report.seconds = seconds_since(start);
    Ok(Inferred { network, report, warnings, cycles })
}

/// The share of the length of the segments of `g` (the whole graph, dangling parts and all)
/// that `patches` (or the boundary loops that the preparation closes on their own) run along
/// in `trimmed` (what is left of `g` once dangling parts and slits are left out): how much of
/// the sketch a choice of cycles surfaces, before anything is solved. Measured against the
/// whole graph, so that a choice whose slits (segments with its patch on both sides) were
/// left out does not count as covering them — both choices are made on the same graph.
fn patched_share(g: &Graph, trimmed: &Graph, patches: &[Patch]) -> f64 {
    let mut used: Vec<bool> = trimmed.segments.iter().map(|s| s.boundary).collect();
    patches.iter().flat_map(|p| p.half_edges()).for_each(|h| used[h.segment] = true);
    let length = |g: &Graph, s: &crate::topology::Segment| {
        let c = &g.curves[s.curve];
        let m = c.points.len();
        (s.first..s.last).map(|i| (c.points[(i + 1) % m] - c.points[i % m]).length()).sum::<f64>()
    };
    let total: f64 = g.segments.iter().map(|s| length(g, s)).sum();
    let on: f64 = trimmed.segments.iter().zip(&used).filter(|(_, u)| **u).map(|(s, _)| length(trimmed, s)).sum();
    if total > 0.0 {
        (on / total).min(1.0)
    } else {
        1.0
    }
}

/// The cycles of `g` chosen globally ([`crate::topology::search`], on `g` with its dangling
/// parts trimmed) and the node normals of `g` repaired from them
/// ([`crate::topology::orient::follow_patches`]). Returns the nodes repaired and the cycles.
fn follow_chosen_cycles(
    g: &mut Graph,
    splines: &[CurveSpline],
    known: &[bool],
) -> Result<(usize, Option<Vec<CycleKey>>, f64)> {
    let clock = Instant::now();
    let mut trimmed = g.clone();
    trim_dangling(&mut trimmed)?;
    let choice = crate::topology::search::choose_cycles(&trimmed, &fit_splines(&trimmed));
    let by_key = segment_places(g);
    let mut ends = vec![[None, None]; g.segments.len()];
    for (seg, vote) in trimmed.segments.iter().zip(choice.end_votes(&trimmed)) {
        if let Some(&i) = by_key.get(&(seg.curve, seg.first, seg.last)) {
            ends[i] = vote;
        }
    }
    let repaired = crate::topology::orient::follow_patches(g, splines, known, &ends);
    Ok((repaired, Some(choice.keys(&trimmed)), seconds_since(clock)))
}

/// [`infer`] again on `net` with the curves `petals` tagged as boundary curves, each with its
/// first sample where it touches the others (`(curve, contact)`), so that node finding keeps
/// them apart as sheets of their own (`snap` kept); `None` without petals, for a network with
/// cycles given (they name its segments as they are), or when that fails (the first pass
/// stands).
fn with_petals_apart(
    net: &Network,
    petals: &[(usize, DVec3)],
    snap: f64,
    options: &Options,
    search: bool,
) -> Option<Inferred> {
    if petals.is_empty() || net.cycles.is_some() {
        return None;
    }
    let mut tagged = net.clone();
    for &(c, at) in petals {
        let curve = &mut tagged.curves[c];
        curve.boundary = true;
        // The sample nearest the contact first (node finding looks for the touch at the seam).
        let first = (0..curve.points.len())
            .min_by(|&a, &b| curve.points[a].distance(at).total_cmp(&curve.points[b].distance(at)))
            .unwrap_or(0);
        curve.points.rotate_left(first);
        for v in [&mut curve.normals, &mut curve.normals_right] {
            if v.len() == curve.points.len() {
                v.rotate_left(first);
            }
        }
    }
    tagged.snap = Some(snap);
    infer(&tagged, options, search).ok()
}

/// The petals among `patches` (on `trimmed`, `g` with its dangling parts left out), each with
/// the point where it touches the others: inferred closed curves that `g` splits at one node
/// only, a node where two other passages of curves of `g` meet at least, and that bound one
/// patch alone on one side only — a sheet that touches the rest of the network at one place
/// (the petals at a flower's centre). One node normal cannot serve petals in different
/// planes: they are surfaced as sheets of their own
/// ([`crate::topology::find_nodes`] keeps a closed boundary curve that touches the others at
/// one place apart).
fn petals(g: &Graph, trimmed: &Graph, patches: &[Patch], known: &[bool]) -> Vec<(usize, DVec3)> {
    let mut segments_of = vec![0usize; g.curves.len()];
    g.segments.iter().for_each(|s| segments_of[s.curve] += 1);
    // Passages of curves through each node of `g` (`trimmed` numbers its nodes anew): node
    // finding's count at the meeting.
    let in_g = segment_places(g);
    let mut passages = vec![0usize; g.nodes.len()];
    g.curves.iter().flat_map(|c| c.nodes.iter()).for_each(|&(_, v)| passages[v] += 1);
    let mut uses = vec![0usize; trimmed.segments.len()];
    patches.iter().flat_map(|p| p.half_edges()).for_each(|h| uses[h.segment] += 1);
    let mut out: Vec<(usize, DVec3)> = patches
        .iter()
        .filter_map(|p| match p {
            Patch::Disk(hs) if hs.len() == 1 => {
                let s = &trimmed.segments[hs[0].segment];
                let c = s.curve;
                let node = in_g.get(&(c, s.first, s.last)).map(|&k| g.segments[k].start);
                let petal = s.start == s.end
                    && !s.boundary
                    && !known[c]
                    && trimmed.curves[c].closed
                    && segments_of[c] == 1
                    && uses[hs[0].segment] == 1
                    && node.is_some_and(|v| passages[v] >= 3);
                petal.then(|| (c, trimmed.nodes[s.start].position))
            }
            _ => None,
        })
        .collect();
    out.sort_by_key(|x| x.0);
    out.dedup_by_key(|x| x.0);
    out
}

/// The cycles `keys` as disk patches of `g`; `None` when one of them is not on `g`.
fn disks(g: &Graph, keys: &[CycleKey]) -> Option<Vec<Patch>> {
    let at = segment_places(g);
    keys.iter()
        .map(|k| {
            k.iter()
                .map(|&(c, f, l, forward)| {
                    at.get(&(c, f, l)).map(|&segment| crate::topology::HalfEdge { segment, forward })
                })
                .collect::<Option<Vec<_>>>()
                .map(Patch::Disk)
        })
        .collect()
}

/// A component of `g` whose `patches` enclose (nearly) no volume — a loop of curves, or a
/// planar-like network drawn without its border tagged, whose faces double-cover one sheet
/// (each cycle seen from both sides) — is an open surface: its largest face is the outside.
/// Returns, per such component, the curves to tag as boundary (those not `keep` all of whose
/// segments lie on that face, when they make up the whole face) and the face. The test: the
/// volume enclosed by the faces (fans from their centres) below 5% of that of a sphere of the
/// same area.
///
/// With `closed_only` (cycles chosen globally, where an open sheet is open already), a part with
/// a segment that one of its patches bounds alone is left as it is. The last field of each
/// result says whether the curves to tag make up the whole face.
fn flat_components(g: &Graph, patches: &[Patch], keep: &[bool], closed_only: bool) -> Vec<(Vec<usize>, usize, bool)> {
    let comps = g.node_components();
    let mut by_comp: std::collections::BTreeMap<usize, Vec<usize>> = std::collections::BTreeMap::new();
    for (i, p) in patches.iter().enumerate() {
        if let (Patch::Disk(hs), false) = (p, p.half_edges().iter().any(|h| g.segments[h.segment].boundary)) {
            by_comp.entry(comps[g.segments[hs[0].segment].start]).or_default().push(i);
        }
    }
    let mut out = Vec::new();
    for list in by_comp.values() {
        let cycles: Vec<Vec<DVec3>> = list
            .iter()
            .map(|&i| patches[i].half_edges().iter().flat_map(|&h| half_edge_samples(g, h)).map(|x| x.0).collect())
            .collect();
        let all: Vec<DVec3> = cycles.iter().flatten().copied().collect();
        let o = all.iter().sum::<DVec3>() / all.len().max(1) as f64;
        let (mut volume, mut areas) = (0.0, Vec::with_capacity(cycles.len()));
        for cyc in &cycles {
            let c = cyc.iter().sum::<DVec3>() / cyc.len().max(1) as f64;
            let mut area = 0.0;
            for k in 0..cyc.len() {
                let (p, q) = (cyc[k], cyc[(k + 1) % cyc.len()]);
                area += 0.5 * (p - c).cross(q - c).length();
                volume += (c - o).dot((p - o).cross(q - o)) / 6.0;
            }
            areas.push(area);
        }
        let total: f64 = areas.iter().sum();
        // A sphere of area A holds A^{3/2} / (6 √π).
        let sphere = total.powf(1.5) / (6.0 * std::f64::consts::PI.sqrt());
        if !(volume.abs() < 0.05 * sphere) || list.len() < 2 {
            continue;
        }
        if closed_only {
            let mut uses: std::collections::HashMap<usize, usize> = std::collections::HashMap::new();
            list.iter().flat_map(|&i| patches[i].half_edges()).for_each(|h| *uses.entry(h.segment).or_default() += 1);
            if uses.values().any(|&u| u < 2) {
                continue;
            }
        }
        let k = (0..list.len()).max_by(|&a, &b| areas[a].total_cmp(&areas[b])).unwrap_or(0);
        let outer = list[k];
        let on_outer: std::collections::BTreeSet<usize> =
            patches[outer].half_edges().iter().map(|h| h.segment).collect();
        let curves: Vec<usize> = on_outer
            .iter()
            .map(|&s| g.segments[s].curve)
            .collect::<std::collections::BTreeSet<_>>()
            .into_iter()
            .filter(|&c| {
                !keep[c] && g.segments.iter().enumerate().all(|(s, seg)| seg.curve != c || on_outer.contains(&s))
            })
            .collect();
        // The whole border or nothing: a border tagged in part does not close.
        let covered = on_outer.iter().all(|&s| curves.contains(&g.segments[s].curve));
        if closed_only || (!curves.is_empty() && covered) {
            out.push((curves, outer, covered));
        }
    }
    out
}

/// `e` from surfacing a network whose normals were (partly) inferred: an input error about
/// normals says that these normals were inferred, not given.
pub(crate) fn explain(e: crate::Error) -> crate::Error {
    match e {
        crate::Error::Input { message, at } if message.contains("normal") => crate::Error::Input {
            message: format!(
                "{message} [these normals were inferred from the curves' shape: give the normals of the curves \
                 there, or check that they cross cleanly]"
            ),
            at,
        },
        e => e,
    }
}

/// The inferred closed curves of `g` that meet no other curve (one loop segment on a node of
/// their own), tagged as boundary in `g`: a lone loop bounds a disk (or a tube with a loop
/// that faces it), where a network with normals would leave it out. Returns them.
fn close_lone_loops(g: &mut Graph, known: &[bool]) -> Vec<usize> {
    let mut valence = vec![0usize; g.nodes.len()];
    for s in &g.segments {
        valence[s.start] += 1;
        valence[s.end] += 1;
    }
    let mut lone = Vec::new();
    for s in 0..g.segments.len() {
        let seg = &g.segments[s];
        let c = seg.curve;
        if !known[c] && !seg.boundary && seg.start == seg.end && valence[seg.start] == 2 && g.curves[c].closed {
            g.segments[s].boundary = true;
            g.curves[c].boundary = true;
            lone.push(c);
        }
    }
    lone
}

/// The curve of an overlap error of node finding (a curve that runs along another).
fn is_overlap(e: &crate::Error) -> Option<usize> {
    match e {
        crate::Error::Input { message, .. } if message.contains("runs within the snapping tolerance") => e.at().curve,
        _ => None,
    }
}

/// Names every unnamed curve of `net` by its index (`curve 7`, [`crate::network::position_name`]),
/// so that messages keep the input's numbers after some were left out.
fn name_curves(net: &mut Network) {
    for (i, c) in net.curves.iter_mut().enumerate() {
        if c.name.is_none() {
            c.name = Some(crate::network::position_name(i));
        }
    }
}

/// Adds what the inference found (`report`, `warnings`) to the `surface` of the network it made: its
/// statistics, its seconds and its warnings (first; the run's own after them, repeats left out).
pub(crate) fn add_to_surface(surface: &mut super::Surface, report: &InferredNormals, warnings: &[Warning]) {
    let t = &mut surface.stats.timings;
    t.normals = report.seconds;
    t.total += report.seconds;
    surface.stats.inferred_normals = Some(report.clone());
    let mut warnings = warnings.to_vec();
    for w in surface.warnings.drain(..) {
        if !warnings.contains(&w) {
            warnings.push(w);
        }
    }
    surface.warnings = warnings;
}

/// Splines through the curves of `g` (positions and the current normals).
fn fit_splines(g: &Graph) -> Vec<CurveSpline> {
    g.curves.par_iter().map(|c| CurveSpline::fit(&c.points, &c.normals, c.closed)).collect()
}

/// Clears the normals of the samples of inferred curves outside every segment (past the end
/// node of a stroke), for [`fill_gaps`] to carry them again from the nodes' current normals.
fn clear_outside_segments(g: &mut Graph, known: &[bool]) {
    let mut covered: Vec<Vec<bool>> = g.curves.iter().map(|c| vec![false; c.points.len()]).collect();
    for seg in &g.segments {
        let m = covered[seg.curve].len();
        (seg.first..=seg.last).for_each(|i| covered[seg.curve][i % m] = true);
    }
    for (c, sc) in g.curves.iter_mut().enumerate() {
        if known[c] {
            continue;
        }
        for (n, &cov) in sc.normals.iter_mut().zip(&covered[c]) {
            if !cov {
                *n = DVec3::ZERO;
            }
        }
    }
}

/// Samples of inferred curves outside every segment (past an end node that snapped short of
/// the curve's end) take the normal of the nearest sample that has one.
fn fill_gaps(g: &mut Graph, known: &[bool]) {
    for (c, sc) in g.curves.iter_mut().enumerate() {
        if known[c] || sc.normals.iter().all(|n| *n != DVec3::ZERO) {
            continue;
        }
        let m = sc.normals.len();
        for _ in 0..m {
            let mut changed = false;
            for i in 0..m {
                if sc.normals[i] == DVec3::ZERO {
                    let prev = if i > 0 { sc.normals[i - 1] } else { DVec3::ZERO };
                    let next = if i + 1 < m { sc.normals[i + 1] } else { DVec3::ZERO };
                    let n = if prev != DVec3::ZERO { prev } else { next };
                    if n != DVec3::ZERO {
                        sc.normals[i] = n;
                        changed = true;
                    }
                }
            }
            if !changed {
                break;
            }
        }
        if sc.normals.contains(&DVec3::ZERO) {
            sc.normals.iter_mut().for_each(|n| *n = DVec3::Z);
        }
    }
}

/// Takes every normal of `curve` across the polyline's own chords where it runs within 25° of
/// one (the spline's tangent differs from the chords at the sharp bends and hooks of sketched
/// strokes; validation refuses a normal along the curve): projected off the chord it is
/// closest to, then off the other one if still needed.
fn across_chords(curve: &mut crate::Curve) {
    let m = curve.points.len();
    for i in 0..m {
        let chord = |a: usize, b: usize| (curve.points[b] - curve.points[a]).normalize_or_zero();
        let before = if i > 0 {
            chord(i - 1, i)
        } else if curve.closed {
            chord(m - 1, 0)
        } else {
            DVec3::ZERO
        };
        let after = if i + 1 < m {
            chord(i, i + 1)
        } else if curve.closed {
            chord(m - 1, 0)
        } else {
            DVec3::ZERO
        };
        let mut n = curve.normals[i];
        let mut chords = [before, after];
        chords.sort_by(|a, b| b.dot(n).abs().total_cmp(&a.dot(n).abs()));
        for t in chords {
            if n.dot(t).abs() > 0.9 {
                // What is left of a normal within 25° of the chord points anywhere across it:
                // taken from the neighbours' normals instead where they are across it (a node
                // of many curves may get a normal tangent to one of them, as the neatened
                // flower's valence-11 centres do to a petal's outline).
                let prev = if i > 0 { i - 1 } else { m - 1 };
                let next = if i + 1 < m { i + 1 } else { 0 };
                let near = |j: usize| (curve.closed || j.abs_diff(i) == 1).then(|| curve.normals[j]);
                let sum: DVec3 = [near(prev), near(next)].into_iter().flatten().sum();
                // (Once taken across one chord, the normal is only projected off the other.)
                let fresh = n == curve.normals[i];
                let from = if fresh && (sum - t * sum.dot(t)).length() > 0.5 * sum.length() { sum } else { n };
                let across = (from - t * from.dot(t)).normalize_or_zero();
                if across != DVec3::ZERO {
                    n = across;
                }
            }
        }
        curve.normals[i] = n;
    }
}

/// `net` with the normals of its inferred curves taken from the split curves of `g` (by each
/// sample's origin).
fn with_graph_normals(net: &Network, g: &Graph, known: &[bool]) -> Network {
    let mut out = net.clone();
    for (c, (curve, sc)) in out.curves.iter_mut().zip(&g.curves).enumerate() {
        if known[c] {
            continue;
        }
        // Every input sample is in its split curve (a sample a node replaced keeps the node's
        // normal), and `fill_gaps` left no zero normal there.
        curve.normals = vec![DVec3::ZERO; curve.points.len()];
        for (j, &o) in sc.origin.iter().enumerate() {
            if let Some(n) = curve.normals.get_mut(o) {
                *n = sc.normals[j];
            }
        }
        across_chords(curve);
    }
    out
}

#[cfg(test)]
#[path = "tests/infer.rs"]
mod tests;
