//! Open networks (\[CG\] §5 lists them as a limitation): curves, or parts of curves, that bound
//! no patch. A *dangling* segment has an end where no other curve meets it (a node of valence
//! 1): it cannot bound a patch on either side. [`trim_dangling`] removes such segments one by
//! one (a dangling chain is eaten back to the first node where curves really meet), and lone
//! closed curves that are not boundary curves and meet no other curve, and reports each curve
//! it shortened or left out as a [`Warning`] naming the curve and where its kept part ends.
//! The rest of the network is surfaced as usual.

use super::nodes::Graph;
use crate::error::{Error, Result, Warning};
use crate::geom::fmt_point;

/// Removes dangling segments (repeatedly) and lone interior loops from `g`, renumbering its
/// nodes and segments. Returns one warning per curve affected.
///
/// Errors ([`Error::Topology`]): nothing is left (no two curves of the network meet).
pub fn trim_dangling(g: &mut Graph) -> Result<Vec<Warning>> {
    let attached = attached_boundary(g);
    let mut warnings = trim_dangling_only(g)?;
    warnings.extend(cover_detached_holes(g, &attached));
    Ok(warnings)
}

/// Per curve of `g`: a boundary curve that shares a connected part of the network with
/// interior (non-boundary) segments.
pub fn attached_boundary(g: &Graph) -> Vec<bool> {
    let comp = g.node_components();
    let mut has_interior = vec![false; g.nodes.len()];
    for seg in &g.segments {
        if !seg.boundary {
            has_interior[comp[seg.start]] = true;
        }
    }
    let mut attached = vec![false; g.curves.len()];
    for seg in &g.segments {
        if seg.boundary && has_interior[comp[seg.start]] {
            attached[seg.curve] = true;
        }
    }
    attached
}

/// Boundary loops that were `attached` to interior curves ([`attached_boundary`]) but are no
/// longer, because the curves that reached them were left out (dangling, or slits: a hole that
/// a single curve reaches): such a loop bounds a hole inside a patch of the rest of the
/// network, which the patches (disks) cannot leave open. Alone it would be surfaced as a disk
/// of its own over that patch (two sheets). It is left out, so that the hole is covered, with a
/// warning naming it — unless no interior curve is left at all (then it is the network's only
/// border and bounds a disk). Returns one warning per loop left out.
pub fn cover_detached_holes(g: &mut Graph, attached: &[bool]) -> Vec<Warning> {
    let comp = g.node_components();
    let mut has_interior = vec![false; g.nodes.len()];
    for seg in &g.segments {
        if !seg.boundary {
            has_interior[comp[seg.start]] = true;
        }
    }
    if !has_interior.iter().any(|&x| x) {
        return Vec::new();
    }
    let gone: Vec<usize> = (0..g.segments.len())
        .filter(|&s| {
            let seg = &g.segments[s];
            seg.boundary && !has_interior[comp[seg.start]] && attached.get(seg.curve).copied().unwrap_or(false)
        })
        .collect();
    if gone.is_empty() {
        return Vec::new();
    }
    let mut curves: Vec<usize> = gone.iter().map(|&s| g.segments[s].curve).collect();
    curves.sort_unstable();
    curves.dedup();
    let warnings = curves
        .iter()
        .map(|&c| {
            let at = g
                .segments
                .iter()
                .find(|seg| seg.curve == c)
                .map_or(crate::geom::DVec3::ZERO, |seg| g.nodes[seg.start].position);
            Warning::new(format!(
                "{} (a boundary curve) is no longer reached by other curves (the curves that reached it were left out); \
                 the hole it bounds near {} cannot be cut out of the patch around it and was covered (the boundary \
                 curve was left out of the surface)",
                g.labels[c],
                fmt_point(at)
            ))
            .curve(c)
        })
        .collect();
    remove_segments(g, &gone);
    warnings
}

/// [`trim_dangling`] without the holes it cuts off ([`cover_detached_holes`]).
fn trim_dangling_only(g: &mut Graph) -> Result<Vec<Warning>> {
    let ns = g.segments.len();
    let mut valence = vec![0usize; g.nodes.len()];
    let mut incident: Vec<Vec<usize>> = vec![Vec::new(); g.nodes.len()];
    for (s, seg) in g.segments.iter().enumerate() {
        valence[seg.start] += 1;
        valence[seg.end] += 1;
        incident[seg.start].push(s);
        incident[seg.end].push(s);
    }
    let mut removed = vec![false; ns];
    // Per curve: the node where its kept part now ends (the last node a trim stopped at).
    let mut stop_at: Vec<Option<usize>> = vec![None; g.curves.len()];
    let mut queue: Vec<usize> = (0..g.nodes.len()).filter(|&v| valence[v] == 1).collect();
    while let Some(v) = queue.pop() {
        if valence[v] != 1 {
            continue;
        }
        let Some(&s) = incident[v].iter().find(|&&s| !removed[s]) else { continue };
        let seg = &g.segments[s];
        if seg.boundary {
            // An unclosed boundary: cutting it back would leave an open border that bounds
            // nothing; find_patches reports it, naming the curve.
            continue;
        }
        removed[s] = true;
        let other = if seg.start == v { seg.end } else { seg.start };
        valence[v] -= 1;
        valence[other] -= 1;
        stop_at[seg.curve] = Some(other);
        if valence[other] == 1 {
            queue.push(other);
        }
    }
    // Lone loops: a closed non-boundary curve whose only node is its own (one loop segment).
    for (s, seg) in g.segments.iter().enumerate() {
        if !removed[s] && !seg.boundary && seg.start == seg.end && valence[seg.start] == 2 {
            removed[s] = true;
            valence[seg.start] = 0;
            stop_at[seg.curve] = Some(seg.start);
        }
    }
    if !removed.iter().any(|&r| r) {
        return Ok(Vec::new());
    }
    let mut warnings = Vec::new();
    for (c, stop) in stop_at.iter().enumerate() {
        let Some(v) = stop else { continue };
        let kept = g.segments.iter().enumerate().any(|(s, seg)| seg.curve == c && !removed[s]);
        // A plain curve's label alone ("curve 60 (curve)" read like a name, issue 33).
        let what = if g.curves[c].boundary { " (a boundary curve)" } else { "" };
        warnings.push(
            Warning::new(if kept {
                format!(
                    "{}{what} has a dangling end that meets no other curve: the part beyond node {v} at {} bounds \
                 no patch and was left out of the surface",
                    g.labels[c],
                    fmt_point(g.nodes[*v].position)
                )
            } else {
                format!(
                "{}{what} does not meet other curves so as to bound a patch (near {}); it was left out of the surface",
                g.labels[c],
                fmt_point(g.nodes[*v].position)
            )
            })
            .curve(c),
        );
    }
    if removed.iter().all(|&r| r) {
        let named: Vec<&str> = stop_at
            .iter()
            .enumerate()
            .filter(|(_, s)| s.is_some())
            .map(|(c, _)| g.labels[c].as_str())
            .take(10)
            .collect();
        let first = stop_at.iter().position(Option::is_some);
        // Closed curves that meet nothing: borders not marked as such ("boundry", issue 29).
        let loops: Vec<&str> = (0..g.curves.len())
            .filter(|&c| {
                let segs: Vec<_> = g.segments.iter().filter(|s| s.curve == c).collect();
                g.curves[c].closed && !g.curves[c].boundary && segs.len() == 1 && segs[0].start == segs[0].end
            })
            .map(|c| g.labels[c].as_str())
            .take(10)
            .collect();
        let hint = if loops.is_empty() {
            String::new()
        } else {
            format!(
                ". {} {} a closed loop that meets no other curve: if it is an open border of the surface (the rims of \
                 a tube), mark it as one (`\"boundary\": true`)",
                loops.join(", "),
                if loops.len() == 1 { "is" } else { "are each" }
            )
        };
        let e = Error::topology(format!(
            "no curves of the network bound a patch: every curve dangles or meets no other ({}{}). Curves must \
             cross each other (or end on each other) to enclose patches{hint}",
            named.join(", "),
            if stop_at.iter().filter(|s| s.is_some()).count() > named.len() { ", …" } else { "" }
        ));
        return Err(match first {
            Some(c) => e.curve(c),
            None => e,
        });
    }
    let gone: Vec<usize> = (0..ns).filter(|&s| removed[s]).collect();
    remove_segments(g, &gone);
    Ok(warnings)
}

/// Removes segments `remove` from `g` and the nodes no kept segment uses, renumbering both.
pub fn remove_segments(g: &mut Graph, remove: &[usize]) {
    let mut removed = vec![false; g.segments.len()];
    for &s in remove {
        removed[s] = true;
    }
    // Renumber: keep nodes used by a kept segment.
    let mut new_id = vec![usize::MAX; g.nodes.len()];
    let mut nodes = Vec::new();
    for seg in g.segments.iter().zip(&removed).filter(|(_, r)| !**r).map(|(s, _)| s) {
        for v in [seg.start, seg.end] {
            if new_id[v] == usize::MAX {
                new_id[v] = nodes.len();
                nodes.push(g.nodes[v].clone());
            }
        }
    }
    let segments = g
        .segments
        .iter()
        .zip(&removed)
        .filter(|(_, r)| !**r)
        .map(|(s, _)| {
            let mut s = s.clone();
            s.start = new_id[s.start];
            s.end = new_id[s.end];
            s
        })
        .collect();
    for c in &mut g.curves {
        c.nodes = c.nodes.iter().filter(|(_, v)| new_id[*v] != usize::MAX).map(|&(i, v)| (i, new_id[v])).collect();
    }
    g.nodes = nodes;
    g.segments = segments;
}

#[cfg(test)]
#[path = "tests/open.rs"]
mod tests;
