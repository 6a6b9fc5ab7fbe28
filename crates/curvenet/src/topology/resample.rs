//! The segments resampled at the mesh spacing (\[CG\] §3.1, design.md §1 step 3): the curve
//! vertices of the mesh, shared by the patches on both sides of every segment.

use super::Graph;
use crate::curves::CurveSpline;
use crate::geom::DVec3;
/// The resampled curve network: the curve vertices of the mesh.
#[derive(Clone, Debug, Default)]
pub struct Resampled {
    /// Positions of the curve vertices. Vertex `k < nodes` is node `k`.
    pub positions: Vec<DVec3>,
    /// Unit normals of the curve vertices.
    pub normals: Vec<DVec3>,
    /// Per curve vertex: lies on a boundary curve.
    pub on_boundary: Vec<bool>,
    /// Per segment: its vertices from the start node to the end node (both included).
    pub segment_vertices: Vec<Vec<u32>>,
}

/// Resamples every segment of `g` at spacing ≈ `d`: a segment of arc length `ℓ` gets
/// `max(1, round(ℓ/d))` pieces of equal arc length, so nodes stay exact.
pub fn resample_network(g: &Graph, splines: &[CurveSpline], d: f64) -> Resampled {
    resample_with(g, splines, &|_, len, min| ((len / d).round() as usize).max(min))
}

/// Resamples segment `s` of `g` into `pieces[s]` pieces of equal arc length (the counts of an
/// earlier resampling: the same mesh vertices on moved curves).
pub fn resample_network_as(g: &Graph, splines: &[CurveSpline], pieces: &[usize]) -> Resampled {
    resample_with(g, splines, &|s, _, min| pieces.get(s).copied().unwrap_or(min).max(min))
}

/// Resamples segment `s` of arc length `ℓ` into `pieces(s, ℓ, min)` pieces, `min` the fewest a
/// cycle allows (a loop on one node ≥ 3, two segments between the same nodes ≥ 2 each).
fn resample_with(
    g: &Graph,
    splines: &[CurveSpline],
    pieces: &(dyn Fn(usize, f64, usize) -> usize + Sync),
) -> Resampled {
    use rayon::prelude::*;
    let mut r = Resampled {
        positions: g.nodes.iter().map(|n| n.position).collect(),
        normals: g.nodes.iter().map(|n| n.normal).collect(),
        on_boundary: vec![false; g.nodes.len()],
        segment_vertices: Vec::with_capacity(g.segments.len()),
    };
    // A cycle needs three vertices: a loop on one node gets ≥ 3 pieces, two segments that
    // join the same two nodes get ≥ 2 each.
    let mut parallel = std::collections::HashMap::new();
    for seg in &g.segments {
        *parallel.entry((seg.start.min(seg.end), seg.start.max(seg.end))).or_insert(0usize) += 1;
    }
    let samples: Vec<Vec<(DVec3, DVec3)>> = g
        .segments
        .par_iter()
        .enumerate()
        .map(|(si, seg)| {
            let sp = &splines[seg.curve];
            let len = sp.arc_between(seg.first, seg.last);
            let min = if seg.start == seg.end {
                3
            } else if parallel[&(seg.start.min(seg.end), seg.start.max(seg.end))] > 1 {
                2
            } else {
                1
            };
            sp.resample(seg.first, seg.last, pieces(si, len, min))
        })
        .collect();
    for (seg, s) in g.segments.iter().zip(samples) {
        let mut ids = Vec::with_capacity(s.len());
        ids.push(seg.start as u32);
        for &(p, n) in &s[1..s.len() - 1] {
            ids.push(r.positions.len() as u32);
            r.positions.push(p);
            r.normals.push(n);
            r.on_boundary.push(seg.boundary);
        }
        ids.push(seg.end as u32);
        if seg.boundary {
            r.on_boundary[seg.start] = true;
            r.on_boundary[seg.end] = true;
        }
        r.segment_vertices.push(ids);
    }
    r
}
