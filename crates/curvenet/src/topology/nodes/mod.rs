//! Nodes and segments (\[CG\] §3.2: "a node is the intersection between two or more curves; a
//! segment is a portion of curve bounded by two adjacent nodes").
//!
//! Curves meet where they share a sample *or* pass within the snapping tolerance of each other
//! between samples (sensor data rarely sample a crossing exactly). Candidate pairs of polyline
//! edges come from a uniform spatial hash grid (not all pairs); their closest points
//! ([`crate::geom::closest_params_segment_segment`]) within the tolerance are hits. Hits closer
//! than twice the tolerance form one node, and so do hits of the same two curves within a few
//! tolerances along both curves (a shallow meeting). Curves that stay within the tolerance of
//! each other over a stretch are an overlap error. The node is inserted into every curve passing through it
//! (snapping the nearest sample when it is within a quarter of an edge, inserting a new sample
//! otherwise); its normal is the average of the normals the curves give there. Curves whose
//! normals disagree by more than 90° at a node are an orientation error.
//!
//! The stages, one file each: `contacts.rs` finds the contacts between curves and clusters
//! them into meetings, `meetings.rs` turns each meeting into a node (with the overlap and
//! orientation checks), `split.rs` adds the end nodes, inserts the nodes into the curves and
//! cuts the curves into segments.

mod contacts;
mod meetings;
mod split;

use super::UnionFind;
use crate::error::{Result, Warning};
use crate::geom::{fmt_point, DVec3};
use crate::network::Network;
use contacts::{cluster_contacts, find_contacts, Polylines};
use meetings::meeting_nodes;
use split::{add_end_nodes, segments_of, split_curve};

/// A point where curves meet (or where an open curve ends).
#[derive(Clone, Debug, PartialEq)]
pub struct Node {
    /// Position (where curves meet: the mean of the points where they pass).
    pub position: DVec3,
    /// Unit normal: the average of the curves' normals at the node.
    pub normal: DVec3,
}

/// A curve of the network after node insertion. For closed curves the samples are rotated so
/// that a node sits at sample 0.
#[derive(Clone, Debug)]
pub struct SplitCurve {
    /// The input curve's name.
    pub name: Option<String>,
    /// Samples, with the nodes inserted (a node's sample is at the node's position).
    pub points: Vec<DVec3>,
    /// Normals at `points` (a node's sample has the node's normal).
    pub normals: Vec<DVec3>,
    /// The last sample connects back to the first.
    pub closed: bool,
    /// The curve bounds the surface.
    pub boundary: bool,
    /// `(sample index, node id)` for every node on the curve, by increasing sample index.
    pub nodes: Vec<(usize, usize)>,
    /// Per sample: the index of the input curve's sample it stands for ([`usize::MAX`] for a
    /// node inserted between samples).
    pub origin: Vec<usize>,
    /// Per sample, in a network with creases only (empty otherwise): the curve's own unit
    /// normals `[left, right]` of its two sides (equal on a smooth curve), not averaged with
    /// the other curves at nodes (docs/design.md §13).
    pub sides: Vec<[DVec3; 2]>,
}

/// A portion of a curve between two adjacent nodes.
#[derive(Clone, Debug, PartialEq)]
pub struct Segment {
    /// Index of the curve (in the input network and in [`Graph::curves`]).
    pub curve: usize,
    /// First sample of the segment on its [`SplitCurve`].
    pub first: usize,
    /// Last sample of the segment; it may equal the number of samples of a closed curve
    /// (sample 0 again).
    pub last: usize,
    /// Node at the first sample.
    pub start: usize,
    /// Node at the last sample.
    pub end: usize,
    /// The segment lies on a boundary curve.
    pub boundary: bool,
}

/// Nodes, split curves and segments of a network.
#[derive(Clone, Debug)]
pub struct Graph {
    /// The nodes: first those where curves meet, then, curve by curve, the ends of open curves
    /// where they meet nothing and a node on each closed curve that meets no other curve
    /// (renumbered when segments are left out, [`crate::topology::open::remove_segments`]).
    pub nodes: Vec<Node>,
    /// The curves of the network, in input order, with the nodes inserted.
    pub curves: Vec<SplitCurve>,
    /// The segments, curve by curve, in order along each curve.
    pub segments: Vec<Segment>,
    /// Names of the input curves, for messages.
    pub(crate) labels: Vec<String>,
}

impl Graph {
    /// `segment 4 (curve 2 "rim", from node 1 at (…) to node 3 at (…))`, for messages.
    pub fn describe_segment(&self, s: usize) -> String {
        let seg = &self.segments[s];
        format!(
            "segment {s} ({}, from node {} at {} to node {} at {})",
            self.labels[seg.curve],
            seg.start,
            fmt_point(self.nodes[seg.start].position),
            seg.end,
            fmt_point(self.nodes[seg.end].position)
        )
    }

    /// The connected component of every node (its smallest node index), through segments.
    pub fn node_components(&self) -> Vec<usize> {
        let mut uf = UnionFind::new(self.nodes.len());
        for s in &self.segments {
            uf.union(s.start, s.end);
        }
        (0..self.nodes.len()).map(|i| uf.find(i)).collect()
    }

    /// `node 3 at (x, y, z)`, for messages.
    pub fn describe_node(&self, n: usize) -> String {
        format!("node {n} at {}", fmt_point(self.nodes[n].position))
    }
}

/// Finds the nodes of a validated network and splits its curves into segments (\[CG\] §3.2).
/// A curve without normals gets zero normals in the graph (unknown; a node only such curves
/// pass has a zero normal): [`super::orient`] fills them in.
///
/// `snap` is the snapping tolerance (a distance). Errors ([`crate::Error::Input`], naming the
/// curve and a point): curves that overlap (run within the tolerance of each other over a
/// stretch longer than a few tolerances), curves whose normals disagree in orientation at a
/// node, and two nodes that land on one point of a curve. The warnings name the closed boundary
/// curves that touch the network at one place only, taken as sheets of their own.
pub fn find_nodes(net: &Network, snap: f64) -> Result<(Graph, Vec<Warning>)> {
    let curves = &net.curves;
    let labels: Vec<String> = crate::network::curve_labels(curves);
    let lines = Polylines::new(curves, &labels);
    let hits = find_contacts(&lines, snap)?;
    let clusters = cluster_contacts(&lines, &hits, snap);
    let (mut nodes, mut on_curve, warnings) = meeting_nodes(&lines, &hits, &clusters, snap)?;
    add_end_nodes(&lines, &mut nodes, &mut on_curve, snap);
    // Insert the nodes into the curves.
    let split: Vec<SplitCurve> =
        on_curve.iter_mut().enumerate().map(|(c, list)| split_curve(&lines, c, list, &nodes)).collect();
    let segments = segments_of(&split, &labels)?;
    Ok((Graph { nodes, curves: split, segments, labels }, warnings))
}

/// Hits of the same two curves closer than this (in snapping tolerances, along both curves)
/// form one node; also the largest gap (along a curve) between the hits of one passage of a
/// curve through a node.
const SAME_MEETING: f64 = 4.0;

/// How far from a node (in snapping tolerances) two curves must have separated for the node to
/// count as a crossing rather than an overlap: crossings at angles below asin(1/20) ≈ 3° are
/// reported as overlaps.
const OVERLAP_PROBE: f64 = 20.0;

#[cfg(test)]
#[path = "tests/nodes.rs"]
mod tests;
