//! Topology of the network: raw strokes consolidated into curves that meet ([`consolidate`]),
//! where curves meet ([`nodes`]) and which cycles of segments bound
//! the patches of the surface ([`cycles`], \[CG\] §3.2); dangling parts of open networks are
//! trimmed first ([`open`]); the normals of curves that come without them are inferred
//! ([`orient`]); the mesh is cut open along crease curves for the solve ([`creases`]).

pub mod consolidate;
pub mod creases;
pub mod cycles;
pub mod nodes;
pub mod open;
pub mod orient;
pub mod resample;
pub mod search;

pub use cycles::{find_patches, HalfEdge, Patch};
pub use nodes::{find_nodes, Graph, Node, Segment, SplitCurve};
pub use open::trim_dangling;

/// Disjoint sets over `0..n` with path halving; roots are the smallest members.
pub(crate) struct UnionFind(Vec<usize>);

impl UnionFind {
    pub fn new(n: usize) -> Self {
        UnionFind((0..n).collect())
    }

    pub fn find(&mut self, mut i: usize) -> usize {
        while self.0[i] != i {
            self.0[i] = self.0[self.0[i]];
            i = self.0[i];
        }
        i
    }

    pub fn union(&mut self, a: usize, b: usize) {
        let (a, b) = (self.find(a), self.find(b));
        if a != b {
            self.0[a.max(b)] = a.min(b);
        }
    }
}
