//! The triangle mesh the pipeline builds and solves on.

use crate::geom::{DVec2, DVec3};
use crate::solve::sparse::Csc;

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
    /// Per face: corner coordinates in the plane its patch was triangulated in (\[CG\] §3.3);
    /// the paper's cotangent weights come from these. `#F`.
    pub planar: Vec<[DVec2; 3]>,
    /// Per face: index of its patch. `#F`.
    pub face_patch: Vec<u32>,
    /// Patches whose planar projection folds over (\[CG\] §3.3): triangulated in the plane of
    /// their vector area or on a convex (elliptic) domain instead.
    pub fold_fallback: Vec<usize>,
    /// The seam rows of a mesh cut open along creases (`topology::creases`, docs/design.md
    /// §13), sorted by vertex: per copy of a crease vertex, `½ Σ |e| ν_e` over its open edges
    /// `e` (`ν_e` the outward conormal of the side, across `e` and the copy's normal), and
    /// `½ Σ |e| S ν_e` (`S ν` the normal's derivative across the seam, estimated from the
    /// curves that leave it). Their one-sided Laplacian is no curvature, but its boundary term
    /// is known: `(Ls V)_v ≈ −2 A_v H_v n_v − ½ Σ |e| ν_e`, `(Ls N)_v ≈ −½ Σ |e| S ν_e`, so the
    /// propagation and the fit keep their rows with these targets. Empty otherwise.
    pub seam_rows: Vec<(u32, [DVec3; 2])>,
    /// The Laplacian's sparsity pattern, computed on first use (the faces must not change
    /// afterwards).
    pub(crate) pattern: std::sync::OnceLock<std::sync::Arc<LaplacianPattern>>,
}

impl Mesh {
    /// Number of vertices, `#V`.
    pub fn num_vertices(&self) -> usize {
        self.positions.len()
    }

    /// Number of free (not curve) vertices.
    pub fn num_free(&self) -> usize {
        self.positions.len() - self.num_curve
    }

    /// The sparsity pattern of `Ls` for these faces (computed once).
    pub fn laplacian_pattern(&self) -> std::sync::Arc<LaplacianPattern> {
        self.pattern
            .get_or_init(|| std::sync::Arc::new(LaplacianPattern::new(self.num_vertices(), &self.faces)))
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

    /// Per vertex: the fit leaves its row out — an open-boundary vertex that is not a seam
    /// copy ([`Mesh::seam_rows`]).
    pub fn fit_row_left_out(&self) -> Vec<bool> {
        let mut out = self.on_boundary.clone();
        for &(v, _) in &self.seam_rows {
            out[v as usize] = false;
        }
        out
    }

    /// `true` for curve vertices, `#V` (the PLY `curve` flag).
    pub fn curve_flags(&self) -> Vec<bool> {
        (0..self.positions.len()).map(|i| i < self.num_curve).collect()
    }
}
/// The sparsity pattern of `Ls`: each vertex's neighbours and itself, sorted.
fn laplacian_pattern(n: usize, faces: &[[u32; 3]]) -> Csc {
    let mut deg = vec![1usize; n];
    for f in faces {
        for k in 0..3 {
            deg[f[k] as usize] += 2; // upper bound: each face adds two neighbours
        }
    }
    let mut col_ptr = Vec::with_capacity(n + 1);
    col_ptr.push(0);
    for j in 0..n {
        col_ptr.push(col_ptr[j] + deg[j]);
    }
    let mut rows = vec![u32::MAX; col_ptr[n]];
    let mut fill: Vec<usize> = col_ptr[..n].to_vec();
    for (j, f) in fill.iter_mut().enumerate() {
        rows[*f] = j as u32;
        *f += 1;
    }
    for f in faces {
        for k in 0..3 {
            let j = f[k] as usize;
            for i in [f[(k + 1) % 3], f[(k + 2) % 3]] {
                rows[fill[j]] = i;
                fill[j] += 1;
            }
        }
    }
    // Sort each column (in parallel), then deduplicate and compact.
    {
        use rayon::prelude::*;
        let mut columns: Vec<&mut [u32]> = Vec::with_capacity(n);
        let mut rest = rows.as_mut_slice();
        for j in 0..n {
            let (col, tail) = std::mem::take(&mut rest).split_at_mut(col_ptr[j + 1] - col_ptr[j]);
            columns.push(&mut col[..fill[j] - col_ptr[j]]);
            rest = tail;
        }
        columns.par_iter_mut().with_min_len(4096).for_each(|c| c.sort_unstable());
    }
    let mut out =
        Csc { nrows: n, ncols: n, col_ptr: Vec::with_capacity(n + 1), row_idx: Vec::new(), values: Vec::new() };
    out.col_ptr.push(0);
    for j in 0..n {
        let mut last = u32::MAX;
        for &r in &rows[col_ptr[j]..fill[j]] {
            if r != last {
                out.row_idx.push(r);
                last = r;
            }
        }
        out.col_ptr.push(out.row_idx.len());
    }
    out.values = vec![0.0; out.row_idx.len()];
    out
}

/// The sparsity pattern of `Ls` for a set of faces, with the position of every face's
/// entries in the value array, so that assembling `Ls` for any metric is a pass over the faces
/// without searches.
#[derive(Clone, Debug, Default)]
pub struct LaplacianPattern {
    /// `Ls`'s pattern (values zero).
    pub csc: Csc,
    /// Position of each vertex's diagonal entry in `csc.values`.
    pub(crate) diag: Vec<u32>,
    /// Per face and corner `k` (the edge opposite `k`, between `i = k+1` and `j = k+2`):
    /// positions of the entries `(i, j)` and `(j, i)`.
    pub(crate) slots: Vec<[[u32; 2]; 3]>,
}

impl LaplacianPattern {
    /// The pattern of `Ls` for `n` vertices and `faces`, with each face's entry positions.
    pub fn new(n: usize, faces: &[[u32; 3]]) -> Self {
        let csc = laplacian_pattern(n, faces);
        let find = |i: usize, j: usize| {
            let r = csc.col_ptr[j]..csc.col_ptr[j + 1];
            let k = csc.row_idx[r.clone()].binary_search(&(i as u32)).unwrap_or(0);
            (r.start + k) as u32
        };
        use rayon::prelude::*;
        let diag = (0..n).into_par_iter().with_min_len(8192).map(|v| find(v, v)).collect();
        let slots = faces
            .par_iter()
            .with_min_len(8192)
            .map(|f| {
                let mut s = [[0u32; 2]; 3];
                for (k, sk) in s.iter_mut().enumerate() {
                    let (i, j) = (f[(k + 1) % 3] as usize, f[(k + 2) % 3] as usize);
                    *sk = [find(i, j), find(j, i)];
                }
                s
            })
            .collect();
        LaplacianPattern { csc, diag, slots }
    }
}

/// Total area of the triangles `faces` at `positions`.
pub fn surface_area(faces: &[[u32; 3]], positions: &[DVec3]) -> f64 {
    faces
        .iter()
        .map(|f| {
            let p = |k: usize| positions[f[k] as usize];
            0.5 * (p(1) - p(0)).cross(p(2) - p(0)).length()
        })
        .sum()
}

/// Visits every undirected edge `a < b` of `faces` once, in increasing `(a, b)` order, with
/// how many faces traverse it from `a` to `b` (`fwd`) and from `b` to `a` (`back`). The uses
/// are bucketed by their smaller vertex (a counting sort), so this is linear in the faces
/// without hashing: the pipeline runs it on every tessellation.
pub fn for_each_edge(faces: &[[u32; 3]], mut visit: impl FnMut(u32, u32, u32, u32)) {
    let n = faces.iter().flatten().max().map_or(0, |m| *m as usize + 1);
    let mut start = vec![0usize; n + 1];
    for f in faces {
        for k in 0..3 {
            start[f[k].min(f[(k + 1) % 3]) as usize + 1] += 1;
        }
    }
    for v in 0..n {
        start[v + 1] += start[v];
    }
    // Each use: the larger vertex, shifted, with the direction in the lowest bit (1: b → a).
    let mut uses = vec![0u64; start[n]];
    let mut next = start.clone();
    for f in faces {
        for k in 0..3 {
            let (a, b) = (f[k], f[(k + 1) % 3]);
            let lo = a.min(b) as usize;
            uses[next[lo]] = (u64::from(a.max(b)) << 1) | u64::from(a > b);
            next[lo] += 1;
        }
    }
    for lo in 0..n {
        let bucket = &mut uses[start[lo]..start[lo + 1]];
        bucket.sort_unstable();
        let mut i = 0;
        while i < bucket.len() {
            let hi = bucket[i] >> 1;
            let (mut fwd, mut back) = (0, 0);
            while i < bucket.len() && bucket[i] >> 1 == hi {
                if bucket[i] & 1 == 0 {
                    fwd += 1
                } else {
                    back += 1
                }
                i += 1;
            }
            visit(lo as u32, hi as u32, fwd, back);
        }
    }
}

/// The first edge (in vertex order) of `faces` that breaks edge-manifoldness or orientation
/// (used by more than two faces, or twice in the same direction), with the faces on it;
/// `None` when there is none. The pipeline runs this on every tessellation (invariants 3–4)
/// so that overlapping patches are an error, never a written non-manifold mesh.
pub fn bad_edge(faces: &[[u32; 3]]) -> Option<([u32; 2], Vec<usize>)> {
    let mut bad = None;
    for_each_edge(faces, |a, b, fwd, back| {
        if bad.is_none() && (fwd + back > 2 || fwd > 1 || back > 1) {
            bad = Some([a, b]);
        }
    });
    let [a, b] = bad?;
    let on = faces.iter().enumerate().filter(|(_, f)| f.contains(&a) && f.contains(&b)).map(|(i, _)| i).collect();
    Some(([a, b], on))
}

#[cfg(test)]
#[path = "tests/mesh.rs"]
mod tests;
