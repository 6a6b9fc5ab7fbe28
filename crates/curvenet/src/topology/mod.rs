//! Topology of the network: where curves meet ([`nodes`]) and which cycles of segments bound
//! the patches of the surface ([`cycles`], [CG] §3.2).

pub mod cycles;
pub mod nodes;

pub use cycles::{find_patches, HalfEdge, Patch};
pub use nodes::{find_nodes, Graph, Node, Segment, SplitCurve};
