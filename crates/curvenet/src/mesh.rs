//! The triangle mesh the pipeline builds and solves on.

use crate::geom::{DVec2, DVec3};

/// A triangle mesh whose first [`Mesh::num_curve`] vertices lie on the curve network.
///
/// Vertices `0..num_curve` are the resampled curve vertices (constrained); the others are the
/// free vertices of the patches, patch by patch. Faces are counter-clockwise seen from outside
/// (they agree with the input normals).
#[derive(Clone, Debug, Default)]
pub struct Mesh {
    /// Vertex positions, `#V`. Curve vertices are exact; free vertices hold the lift of their
    /// planar position until a method solves for them.
    pub positions: Vec<DVec3>,
    /// Triangles, `#F`.
    pub faces: Vec<[u32; 3]>,
    /// Number of curve vertices (they come first).
    pub num_curve: usize,
    /// Unit input normals at the curve vertices, `num_curve`.
    pub curve_normals: Vec<DVec3>,
    /// Per vertex: lies on a boundary curve (an open border of the surface), `#V`.
    pub on_boundary: Vec<bool>,
    /// Per face: corner coordinates in the plane its patch was triangulated in ([CG] §3.3);
    /// the paper's cotangent weights come from these. `#F`.
    pub planar: Vec<[DVec2; 3]>,
    /// Per face: index of its patch. `#F`.
    pub face_patch: Vec<u32>,
    /// Patches whose planar projection folds over ([CG] §3.3): triangulated in the plane of
    /// their vector area or on a convex (elliptic) domain instead.
    pub fold_fallback: Vec<usize>,
    /// The Laplacian's sparsity pattern, computed on first use (the faces must not change
    /// afterwards).
    pub(crate) pattern: std::sync::OnceLock<std::sync::Arc<crate::operators::LaplacianPattern>>,
}

impl Mesh {
    pub fn num_vertices(&self) -> usize {
        self.positions.len()
    }

    pub fn num_free(&self) -> usize {
        self.positions.len() - self.num_curve
    }

    /// The sparsity pattern of `Ls` for these faces (computed once).
    pub fn laplacian_pattern(&self) -> std::sync::Arc<crate::operators::LaplacianPattern> {
        self.pattern
            .get_or_init(|| {
                std::sync::Arc::new(crate::operators::LaplacianPattern::new(self.num_vertices(), &self.faces))
            })
            .clone()
    }

    /// The patch of each free vertex, `#V − num_curve` (free vertices lie inside one patch):
    /// the parts of [`crate::solve::Cholesky::factor_in_parts`] for systems on the free
    /// vertices.
    pub fn free_vertex_patches(&self) -> Vec<u32> {
        let nc = self.num_curve;
        let mut parts = vec![0u32; self.num_free()];
        for (f, &p) in self.faces.iter().zip(&self.face_patch) {
            for &v in f {
                if let Some(slot) = (v as usize).checked_sub(nc).and_then(|i| parts.get_mut(i)) {
                    *slot = p;
                }
            }
        }
        parts
    }

    /// `true` for curve vertices, `#V` (the PLY `curve` flag).
    pub fn curve_flags(&self) -> Vec<bool> {
        (0..self.positions.len()).map(|i| i < self.num_curve).collect()
    }
}
