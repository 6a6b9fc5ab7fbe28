//! Plane sections cut on the triangles.

use crate::geom::DVec3;

/// One plane section segment inside a face: it enters/leaves through edges `edges[0]`,
/// `edges[1]` at points `ends[0]`, `ends[1]`.
#[derive(Clone, Copy)]
pub(super) struct FaceCut {
    pub(super) plane: usize,
    pub(super) edges: [(u32, u32); 2],
    pub(super) ends: [DVec3; 2],
}
