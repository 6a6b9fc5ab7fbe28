//! The faces of the network (\[CG\] §3.2, "Exploiting local tangent space to detect cycles"):
//! the segment ends at every node, checked for dangling segments and borders that are not
//! manifold, sorted counter-clockwise around the node normal (a rotation system), the faces
//! it traces, and their classification into patches, slits and the faces of lone boundary
//! loops.

use super::{HalfEdge, Patch};
use crate::curves::CurveSpline;
use crate::error::{Error, Result};
use crate::geom::plane_frame;
use crate::topology::nodes::Graph;

/// Per node: the segment ends there, `(segment, at_start)`, in segment order (a loop segment
/// of one node has both ends there).
pub(super) type NodeEnds = Vec<Vec<(usize, bool)>>;

/// The segment ends at each node of `g`.
pub(super) fn node_ends(g: &Graph) -> NodeEnds {
    // Segment ends at each node: (segment, at_start).
    let mut ends: Vec<Vec<(usize, bool)>> = vec![Vec::new(); g.nodes.len()];
    for (s, seg) in g.segments.iter().enumerate() {
        ends[seg.start].push((s, true));
        ends[seg.end].push((s, false));
    }
    ends
}

/// Checks the valence of every node (its segment ends `ends`): no dangling segment (a node
/// with one end), and 0 or 2 boundary segment ends (a 2-manifold's border passes through a
/// node once or not at all).
///
/// Errors ([`Error::Topology`]): the first node that fails, in node order.
pub(super) fn check_valence(g: &Graph, ends: &NodeEnds) -> Result<()> {
    for (v, list) in ends.iter().enumerate() {
        if list.len() == 1 {
            let seg = &g.segments[list[0].0];
            let what = if seg.boundary {
                "an open boundary curve must be closed or end on another curve"
            } else {
                "extend it to a crossing with another curve, tag the surface border as boundary, or remove it"
            };
            return Err(Error::topology(format!(
                "{} ends at {} without meeting another curve: a dangling segment cannot bound a patch; {what}",
                g.labels[seg.curve],
                g.describe_node(v)
            ))
            .curve(seg.curve)
            .segment(list[0].0)
            .node(v));
        }
    }
    // A 2-manifold's border passes through a node once or not at all: 0 or 2 boundary ends.
    for (v, list) in ends.iter().enumerate() {
        let boundary: Vec<usize> = list.iter().filter(|(s, _)| g.segments[*s].boundary).map(|(s, _)| *s).collect();
        if !boundary.is_empty() && boundary.len() != 2 {
            let mut names: Vec<&str> = boundary.iter().map(|&s| g.labels[g.segments[s].curve].as_str()).collect();
            names.dedup();
            return Err(Error::topology(format!(
                "{} boundary segment ends meet at {} ({}): the surface is not a 2-manifold there — a segment \
                 shared by more than two patches, or borders that touch. A border passes through a node once",
                boundary.len(),
                g.describe_node(v),
                names.join(", ")
            ))
            .node(v));
        }
    }
    Ok(())
}

/// The rotation system of the network: the segment ends at every node sorted
/// counter-clockwise around the node normal, by the angle of the segment's tangent (from its
/// spline) projected on the node's tangent plane.
pub(super) struct Rotation {
    /// Per node: the segment ends `(segment, at_start)` counter-clockwise, starting from the
    /// first axis of the node's [`plane_frame`] (ties by segment index).
    pub(super) sorted: Vec<Vec<(usize, bool)>>,
    /// Per segment: the position of its start end (`[0]`) and its end end (`[1]`) in its
    /// node's list.
    slot: Vec<[usize; 2]>,
}

impl Rotation {
    /// Sorts the segment ends `ends` around the nodes of `g`; `splines[c]` is the spline of
    /// `g.curves[c]`.
    ///
    /// Errors ([`Error::Topology`]): a segment that leaves its node along the node normal (its
    /// projected tangent is shorter than 10⁻³ of the tangent).
    pub(super) fn new(g: &Graph, splines: &[CurveSpline], ends: &NodeEnds) -> Result<Self> {
        // Sort the ends counter-clockwise around the node normal.
        let mut slot = vec![[0usize; 2]; g.segments.len()]; // position of (segment, at_start) in its node's list
        let mut sorted: Vec<Vec<(usize, bool)>> = Vec::with_capacity(g.nodes.len());
        for (v, list) in ends.iter().enumerate() {
            let normal = g.nodes[v].normal;
            let (e1, e2) = plane_frame(normal);
            let mut keyed = Vec::with_capacity(list.len());
            for &(s, at_start) in list {
                let seg = &g.segments[s];
                let sp = &splines[seg.curve];
                let d =
                    if at_start { sp.tangent(sp.knot(seg.first), true) } else { -sp.tangent(sp.knot(seg.last), false) };
                let proj = d - normal * d.dot(normal);
                if proj.length() <= 1e-3 * d.length() || !proj.is_finite() {
                    return Err(Error::topology(format!(
                        "{} leaves {} along the node's normal: normals must be perpendicular to the curves",
                        g.labels[seg.curve],
                        g.describe_node(v)
                    ))
                    .curve(seg.curve)
                    .segment(s)
                    .node(v));
                }
                keyed.push((proj.dot(e2).atan2(proj.dot(e1)), s, at_start));
            }
            keyed.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
            for (k, &(_, s, at_start)) in keyed.iter().enumerate() {
                slot[s][if at_start { 0 } else { 1 }] = k;
            }
            sorted.push(keyed.into_iter().map(|(_, s, a)| (s, a)).collect());
        }
        Ok(Rotation { sorted, slot })
    }

    /// The half-edge that follows `h` around its face: arriving at the far node of `h`, leave
    /// along the segment end just before it in the counter-clockwise order (the clockwise
    /// neighbour), which keeps the face on the left.
    pub(super) fn next(&self, g: &Graph, h: HalfEdge) -> HalfEdge {
        let seg = &g.segments[h.segment];
        // Arrive at the far node through the far end of the segment.
        let (v, arrive_at_start) = if h.forward { (seg.end, false) } else { (seg.start, true) };
        let list = &self.sorted[v];
        let p = self.slot[h.segment][if arrive_at_start { 0 } else { 1 }];
        let (s, at_start) = list[(p + list.len() - 1) % list.len()];
        HalfEdge { segment: s, forward: at_start }
    }
}

/// Index of a half-edge: `2 segment` forward, `2 segment + 1` backward.
pub(super) fn he_index(h: HalfEdge) -> usize {
    2 * h.segment + if h.forward { 0 } else { 1 }
}

/// The faces traced by a rotation system: every half-edge in exactly one face.
pub(super) struct Faces {
    /// The faces, each a cycle of half-edges, in the order of their first half-edge
    /// (segment 0 forward, segment 0 backward, segment 1 forward, …).
    pub(super) faces: Vec<Vec<HalfEdge>>,
    /// Per half-edge ([`he_index`]): its face.
    pub(super) face_of: Vec<usize>,
}

/// Traces the faces of `rot` ([`Rotation::next`] from every half-edge not yet in a face).
///
/// Errors ([`Error::Internal`]): a face that does not close (a broken rotation system).
pub(super) fn trace_faces(g: &Graph, rot: &Rotation) -> Result<Faces> {
    let ns = g.segments.len();
    // Trace faces.
    let mut face_of = vec![usize::MAX; 2 * ns];
    let mut faces: Vec<Vec<HalfEdge>> = Vec::new();
    for s in 0..ns {
        for forward in [true, false] {
            let h0 = HalfEdge { segment: s, forward };
            if face_of[he_index(h0)] != usize::MAX {
                continue;
            }
            let f = faces.len();
            let mut face = Vec::new();
            let mut h = h0;
            loop {
                face_of[he_index(h)] = f;
                face.push(h);
                h = rot.next(g, h);
                if h == h0 {
                    break;
                }
                if face.len() > 2 * ns {
                    return Err(Error::internal("face tracing did not close"));
                }
            }
            faces.push(face);
        }
    }
    Ok(Faces { faces, face_of })
}

/// The connected parts of the segment graph, and which have interior (non-boundary) segments.
pub(super) struct Parts {
    /// Per segment: its part (the smallest node index in it, [`Graph::node_components`]).
    pub(super) seg_root: Vec<usize>,
    /// Per part (by its root node): it has an interior segment.
    pub(super) has_interior: Vec<bool>,
}

impl Parts {
    /// The parts of `g`.
    pub(super) fn new(g: &Graph) -> Self {
        // Connected components of the segment graph.
        let comp = g.node_components();
        let seg_root: Vec<usize> = g.segments.iter().map(|seg| comp[seg.start]).collect();
        let mut has_interior = vec![false; g.nodes.len()];
        for (s, seg) in g.segments.iter().enumerate() {
            if !seg.boundary {
                has_interior[seg_root[s]] = true;
            }
        }
        Parts { seg_root, has_interior }
    }
}

/// The faces sorted out ([`classify_faces`]).
pub(super) struct Classified {
    /// The faces with an interior segment, as disk patches, in face order.
    pub(super) patches: Vec<Patch>,
    /// Segments that a patch meets on both sides (with repeats).
    pub(super) slits: Vec<usize>,
    /// Per part (by its root node) without interior segments: its faces (a lone boundary
    /// loop has two, one per direction).
    pub(super) lone_faces: Vec<Vec<usize>>,
}

/// Sorts the faces out: a face made of boundary half-edges only is the outside of the surface
/// (dropped) or, in a part without interior segments, a face of a lone loop; every other face
/// is a disk patch. A segment that a patch meets twice is a slit.
pub(super) fn classify_faces(g: &Graph, faces: &Faces, parts: &Parts) -> Classified {
    let (seg_root, has_interior) = (&parts.seg_root, &parts.has_interior);
    let mut patches = Vec::new();
    let mut slits = Vec::new();
    let mut lone_faces: Vec<Vec<usize>> = vec![Vec::new(); g.nodes.len()]; // by component root
    for (f, face) in faces.faces.iter().enumerate() {
        let root = seg_root[face[0].segment];
        let all_boundary = face.iter().all(|h| g.segments[h.segment].boundary);
        if all_boundary {
            if !has_interior[root] {
                lone_faces[root].push(f);
            }
            continue; // outside of the surface
        }
        // A patch must not meet itself along a segment.
        for (i, h) in face.iter().enumerate() {
            if face[i + 1..].iter().any(|k| k.segment == h.segment) {
                slits.push(h.segment);
            }
        }
        patches.push(Patch::Disk(face.clone()));
    }
    Classified { patches, slits, lone_faces }
}

/// Checks that every boundary segment in a part with interior segments bounds exactly one
/// patch (a face with an interior segment on one side, the outside on the other).
///
/// Errors ([`Error::Topology`]): the first boundary segment with patches on both sides or on
/// neither.
pub(super) fn check_boundary_sides(g: &Graph, faces: &Faces, parts: &Parts) -> Result<()> {
    // Every boundary segment in a part with interior curves bounds exactly one patch.
    for (s, seg) in g.segments.iter().enumerate() {
        if !seg.boundary || !parts.has_interior[parts.seg_root[s]] {
            continue;
        }
        let real = |forward: bool| {
            let f = faces.face_of[he_index(HalfEdge { segment: s, forward })];
            faces.faces[f].iter().any(|h| !g.segments[h.segment].boundary)
        };
        match (real(true), real(false)) {
            (true, true) => {
                return Err(Error::topology(format!(
                    "{} is tagged as boundary but has patches on both sides; remove the boundary tag from {}",
                    g.describe_segment(s),
                    g.labels[seg.curve]
                ))
                .curve(seg.curve)
                .segment(s))
            }
            (false, false) => {
                return Err(Error::topology(format!(
                    "{} is tagged as boundary but bounds no patch: near it the network is not a 2-manifold \
                     (a segment shared by more than two patches, or normals that disagree in orientation)",
                    g.describe_segment(s)
                ))
                .curve(seg.curve)
                .segment(s))
            }
            _ => {}
        }
    }
    Ok(())
}

#[cfg(test)]
#[path = "tests/faces.rs"]
mod tests;
