//! Discrete differential operators on the mesh (\[CG\] §3.4): the cotangent Laplacian `Ls`, the
//! mixed Voronoi mass matrix `M`, vertex normals, and the two mean-curvature estimates — the
//! cotangent formula and the paper's normal-blended formula (eq. 1).
//!
//! Sign conventions (docs/design.md §1): `(Ls)_ij = ½(cot αᵢⱼ + cot βᵢⱼ)`, `(Ls)_ii = −Σⱼ (Ls)_ij`
//! (negative semi-definite); `L = M⁻¹ Ls`; on a smooth surface `L V ≈ −2 H N` with `H > 0` on a
//! sphere with outward normals.

use crate::geom::mesh::{LaplacianPattern, Mesh};
use crate::geom::{DVec2, DVec3};
use crate::solve::sparse::Csc;

/// Where the cotangent weights and areas are measured.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Metric {
    /// In the plane each patch was triangulated in (\[CG\] §3.4: "based on the planar
    /// triangulation"). Not isometric to the surface: a known bias of the paper (\[CG\] §5).
    #[default]
    Planar,
    /// On the 3D surface given by vertex positions.
    Surface,
}

/// `Ls` and the diagonal of `M` for one metric.
#[derive(Clone, Debug)]
pub struct Operators {
    /// Cotangent Laplacian `Ls`, `#V × #V`, symmetric, negative semi-definite.
    pub ls: Csc,
    /// Mixed Voronoi areas (the diagonal of `M`), `#V`.
    pub mass: Vec<f64>,
    /// Barycentric areas (a third of each incident triangle), `#V`: the area the mean-curvature
    /// guide's sum covers (\[CG\] eq. 1; [`crate::methods::GuideArea::Barycentric`]).
    pub barycentric: Vec<f64>,
}

/// Corner cotangents and mixed Voronoi areas of one triangle given its corners (2D or 3D).
/// Returns `(cot at corner k, area share of corner k)`.
///
/// Near-degenerate triangles: the sine is clamped to `1e-12 · |u||v|`, so a cotangent stays
/// finite (≤ 1e12) rather than becoming infinite.
fn corner_terms(p: [DVec3; 3]) -> ([f64; 3], [f64; 3]) {
    let mut cot = [0.0; 3];
    let mut cross_len = 0.0;
    for k in 0..3 {
        let a = p[k];
        let u = p[(k + 1) % 3] - a;
        let v = p[(k + 2) % 3] - a;
        let c = u.cross(v).length();
        cross_len = c;
        cot[k] = u.dot(v) / c.max(1e-12 * u.length() * v.length()).max(f64::MIN_POSITIVE);
    }
    let area = 0.5 * cross_len;
    // Mixed areas (Meyer, Desbrun, Schröder, Barr 2003): Voronoi areas for non-obtuse
    // triangles, else half the area to the obtuse corner and a quarter to the others.
    let mut share = [0.0; 3];
    if let Some(obtuse) = (0..3).find(|&k| cot[k] < 0.0) {
        for (k, s) in share.iter_mut().enumerate() {
            *s = if k == obtuse { 0.5 * area } else { 0.25 * area };
        }
    } else {
        for (k, s) in share.iter_mut().enumerate() {
            let (i, j) = ((k + 1) % 3, (k + 2) % 3);
            // |p_k p_i|² cot(angle at j) + |p_k p_j|² cot(angle at i), over 8.
            *s = (p[k].distance_squared(p[i]) * cot[j] + p[k].distance_squared(p[j]) * cot[i]) / 8.0;
        }
    }
    (cot, share)
}

/// Sums per-face contributions into per-vertex values on all threads: `add(face, acc)` adds
/// face `face`'s share to `acc` (length `n`); each thread fills its own buffer over a range of
/// faces and the buffers are summed (a scatter without locks or atomics).
fn accumulate<T>(n: usize, num_faces: usize, add: impl Fn(usize, &mut [T]) + Sync) -> Vec<T>
where
    T: Copy + Default + Send + Sync + std::ops::AddAssign,
{
    use rayon::prelude::*;
    let threads = if num_faces < 20_000 { 1 } else { rayon::current_num_threads().max(1) };
    let chunk = num_faces.div_ceil(threads).max(1);
    let mut parts: Vec<Vec<T>> = (0..threads)
        .into_par_iter()
        .map(|t| {
            let mut acc = vec![T::default(); n];
            for f in t * chunk..((t + 1) * chunk).min(num_faces) {
                add(f, &mut acc);
            }
            acc
        })
        .collect();
    let mut total = parts.swap_remove(0);
    for p in parts {
        total.par_iter_mut().zip(p.par_iter()).with_min_len(8192).for_each(|(a, b)| *a += *b);
    }
    total
}

/// Assembles `Ls` and `M` on `mesh` with the given metric; `positions` are the 3D positions used
/// by [`Metric::Surface`] (ignored for [`Metric::Planar`], which reads `mesh.planar`). The
/// per-face cotangents and areas are computed in parallel; the pattern comes from the mesh's
/// cache when [`Mesh::laplacian_pattern`] filled it.
pub fn cotan_operators(mesh: &Mesh, metric: Metric, positions: &[DVec3]) -> Operators {
    use rayon::prelude::*;
    let n = mesh.num_vertices();
    // The pattern cached on the mesh (iterations assemble many times), else a temporary one.
    let pattern = match mesh.pattern.get() {
        Some(p) => p.clone(),
        None => std::sync::Arc::new(LaplacianPattern::new(n, &mesh.faces)),
    };
    let lift = |q: DVec2| DVec3::new(q.x, q.y, 0.0);
    let nnz = pattern.csc.values.len();
    // One pass over the faces: the off-diagonal entries (values[..nnz]), the mixed areas
    // (values[nnz..nnz + n]) and the barycentric areas (values[nnz + n..]); the diagonal follows
    // from the columns' sums.
    let mut values = accumulate(nnz + 2 * n, mesh.faces.len(), |fi, acc: &mut [f64]| {
        let f = mesh.faces[fi];
        let p = match metric {
            Metric::Planar => {
                let q = mesh.planar[fi];
                [lift(q[0]), lift(q[1]), lift(q[2])]
            }
            Metric::Surface => [positions[f[0] as usize], positions[f[1] as usize], positions[f[2] as usize]],
        };
        let (cot, share) = corner_terms(p);
        let third = (p[1] - p[0]).cross(p[2] - p[0]).length() / 6.0;
        let slots = &pattern.slots[fi];
        for k in 0..3 {
            // The edge opposite corner k gets ½ cot(angle k).
            let w = 0.5 * cot[k];
            acc[slots[k][0] as usize] += w;
            acc[slots[k][1] as usize] += w;
            acc[nnz + f[k] as usize] += share[k];
            acc[nnz + n + f[k] as usize] += third;
        }
    });
    let barycentric = values.split_off(nnz + n);
    let mass = values.split_off(nnz);
    // (Ls)_jj = −Σ_{i≠j} (Ls)_ij: the diagonal entries are still zero, so minus the column sum.
    let diag: Vec<f64> = (0..n)
        .into_par_iter()
        .with_min_len(8192)
        .map(|j| -values[pattern.csc.col_ptr[j]..pattern.csc.col_ptr[j + 1]].iter().sum::<f64>())
        .collect();
    for (j, d) in diag.into_iter().enumerate() {
        values[pattern.diag[j] as usize] = d;
    }
    let ls =
        Csc { nrows: n, ncols: n, col_ptr: pattern.csc.col_ptr.clone(), row_idx: pattern.csc.row_idx.clone(), values };
    Operators { ls, mass, barycentric }
}

/// Mixed Voronoi areas of the mesh at `positions` (3D).
pub fn mixed_areas(faces: &[[u32; 3]], positions: &[DVec3]) -> Vec<f64> {
    accumulate(positions.len(), faces.len(), |fi, a: &mut [f64]| {
        let f = faces[fi];
        let (_, share) = corner_terms([positions[f[0] as usize], positions[f[1] as usize], positions[f[2] as usize]]);
        for k in 0..3 {
            a[f[k] as usize] += share[k];
        }
    })
}

/// Area-weighted vertex normals (unit; zero for isolated vertices).
pub fn vertex_normals(faces: &[[u32; 3]], positions: &[DVec3]) -> Vec<DVec3> {
    use rayon::prelude::*;
    let n = accumulate(positions.len(), faces.len(), |fi, n: &mut [DVec3]| {
        let f = faces[fi];
        let [a, b, c] = [positions[f[0] as usize], positions[f[1] as usize], positions[f[2] as usize]];
        let fnrm = (b - a).cross(c - a);
        for &i in &f {
            n[i as usize] += fnrm;
        }
    });
    n.par_iter().with_min_len(8192).map(|v| v.normalize_or_zero()).collect()
}

/// Angle-weighted vertex normals (each face's unit normal weighted by its corner angle; Thürmer
/// and Wüthrich 1998), unit length; zero for a vertex of degenerate faces only. Less sensitive
/// to the triangulation than [`vertex_normals`]: the normals of sampled meshes.
pub fn angle_weighted_normals(faces: &[[u32; 3]], positions: &[DVec3]) -> Vec<DVec3> {
    let mut n = vec![DVec3::ZERO; positions.len()];
    for f in faces {
        let p = f.map(|i| positions[i as usize]);
        let fnrm = (p[1] - p[0]).cross(p[2] - p[0]).normalize_or_zero();
        if fnrm == DVec3::ZERO {
            continue;
        }
        for k in 0..3 {
            let (a, b) = (p[(k + 1) % 3] - p[k], p[(k + 2) % 3] - p[k]);
            let angle = a.angle_between(b);
            if angle.is_finite() {
                n[f[k] as usize] += angle * fnrm;
            }
        }
    }
    n.iter().map(|v| v.normalize_or_zero()).collect()
}

/// The vertices on open borders (an edge of one face only): where [`cotan_mean_curvature`]
/// is skipped. Face indices beyond `n` are ignored.
pub fn border_vertices(faces: &[[u32; 3]], n: usize) -> Vec<bool> {
    let mut edges: Vec<(u32, u32)> =
        faces.iter().flat_map(|f| (0..3).map(move |k| (f[k].min(f[(k + 1) % 3]), f[k].max(f[(k + 1) % 3])))).collect();
    edges.sort_unstable();
    let mut border = vec![false; n];
    let mut i = 0;
    while i < edges.len() {
        let mut j = i + 1;
        while j < edges.len() && edges[j] == edges[i] {
            j += 1;
        }
        if j - i == 1 {
            let (a, b) = edges[i];
            for v in [a, b] {
                if let Some(flag) = border.get_mut(v as usize) {
                    *flag = true;
                }
            }
        }
        i = j;
    }
    border
}

/// Signed mean curvature by the cotangent formula: `H = −½ (M⁻¹ Ls V) · n` with `n` the vertex
/// normal (`+1` on a unit sphere). Vertices in `skip` (open-boundary vertices, where the
/// one-sided Laplacian is not a curvature) get 0.
pub fn cotan_mean_curvature(faces: &[[u32; 3]], positions: &[DVec3], skip: &[bool]) -> Vec<f64> {
    normals_and_mean_curvature(faces, positions, skip).1
}

/// [`vertex_normals`] and [`cotan_mean_curvature`] together (the curvature needs the normals).
pub fn normals_and_mean_curvature(faces: &[[u32; 3]], positions: &[DVec3], skip: &[bool]) -> (Vec<DVec3>, Vec<f64>) {
    use rayon::prelude::*;
    /// Per vertex: `Ls V`, the mixed area and the area-weighted normal.
    #[derive(Clone, Copy, Default)]
    struct LapArea(DVec3, f64, DVec3);
    impl std::ops::AddAssign for LapArea {
        fn add_assign(&mut self, o: Self) {
            self.0 += o.0;
            self.1 += o.1;
            self.2 += o.2;
        }
    }
    let acc = accumulate(positions.len(), faces.len(), |fi, acc: &mut [LapArea]| {
        let f = faces[fi];
        let p = [positions[f[0] as usize], positions[f[1] as usize], positions[f[2] as usize]];
        let (cot, share) = corner_terms(p);
        let fnrm = (p[1] - p[0]).cross(p[2] - p[0]);
        for k in 0..3 {
            let (i, j) = (f[(k + 1) % 3] as usize, f[(k + 2) % 3] as usize);
            let w = 0.5 * cot[k];
            acc[i].0 += w * (positions[j] - positions[i]);
            acc[j].0 += w * (positions[i] - positions[j]);
            let v = &mut acc[f[k] as usize];
            v.1 += share[k];
            v.2 += fnrm;
        }
    });
    let normals: Vec<DVec3> = acc.par_iter().with_min_len(8192).map(|a| a.2.normalize_or_zero()).collect();
    let h = (0..positions.len())
        .into_par_iter()
        .with_min_len(8192)
        .map(|i| {
            let LapArea(lv, mass, _) = acc[i];
            if skip.get(i).copied().unwrap_or(false) || mass <= 0.0 {
                0.0
            } else {
                -0.5 * lv.dot(normals[i]) / mass
            }
        })
        .collect();
    (normals, h)
}

/// The paper's mean-curvature vector (\[CG\] eq. 1), blending positions `V*` with normals `N*`:
///
/// `h(v) = 1/(4A) Σᵢ (n + nᵢ + nᵢ₊₁)/‖n + nᵢ + nᵢ₊₁‖ × (vᵢ₊₁ − vᵢ)`,
///
/// summed over the edges `vᵢ → vᵢ₊₁` opposite to `v` in its one-ring (counter-clockwise), with
/// `A = area[v]` the Voronoi area of `v`. `h ≈ H n` when `area` is measured on the surface
/// `V*` ([`mixed_areas`]); the returned scalar is the **signed** `H = h · n*(v)` (docs/design.md §1: the
/// papers' `‖h‖` loses the sign). Vertices in `skip` (open boundary: incomplete ring) get 0.
///
/// Which area to use is a modelling choice: with the planar metric of \[CG\] §3.4, dividing by
/// the *planar* Voronoi area (the `M` of the Laplacian) scales `h` by the local area ratio of
/// the projection, exactly as the planar Laplacian scales `ΔV`, so the fit `L V = −2 H N*`
/// stays consistent to first order (see [`crate::methods::normal_control`]).
pub fn blended_mean_curvature(
    faces: &[[u32; 3]],
    positions: &[DVec3],
    normals: &[DVec3],
    area: &[f64],
    skip: &[bool],
) -> Vec<f64> {
    use rayon::prelude::*;
    let n = positions.len();
    let h = accumulate(n, faces.len(), |fi, h: &mut [DVec3]| {
        let f = faces[fi];
        for k in 0..3 {
            let v = f[k] as usize;
            let (a, b) = (f[(k + 1) % 3] as usize, f[(k + 2) % 3] as usize);
            let m = (normals[v] + normals[a] + normals[b]).normalize_or_zero();
            h[v] += m.cross(positions[b] - positions[a]);
        }
    });
    (0..n)
        .into_par_iter()
        .with_min_len(8192)
        .map(|i| {
            if skip.get(i).copied().unwrap_or(false) || area[i] <= 0.0 {
                0.0
            } else {
                h[i].dot(normals[i]) / (4.0 * area[i])
            }
        })
        .collect()
}

/// Faces around each vertex grouped into sectors: faces that share an edge at the vertex
/// which `sharp` does not call sharp (the two vertices of the edge) are in one sector. Returns
/// per face corner its sector, and per sector the vertex it belongs to: the first sector of
/// vertex `v` (in face order) is `v` itself, the others are numbered from `#V` on (as a mesh
/// cut open along the sharp edges numbers the vertex copies it appends).
pub fn sectors(num_vertices: usize, faces: &[[u32; 3]], sharp: impl Fn(u32, u32) -> bool) -> (Vec<[u32; 3]>, Vec<u32>) {
    let mut corners = faces.to_vec();
    let mut of: Vec<u32> = (0..num_vertices as u32).collect();
    // The faces around each vertex that touches a sharp edge.
    let mut on_sharp = vec![false; num_vertices];
    for f in faces {
        for k in 0..3 {
            let (a, b) = (f[k], f[(k + 1) % 3]);
            if sharp(a, b) {
                on_sharp[a as usize] = true;
                on_sharp[b as usize] = true;
            }
        }
    }
    let mut around: std::collections::HashMap<u32, Vec<(usize, usize)>> = Default::default();
    for (fi, f) in faces.iter().enumerate() {
        for (k, &v) in f.iter().enumerate() {
            if on_sharp[v as usize] {
                around.entry(v).or_default().push((fi, k));
            }
        }
    }
    let mut verts: Vec<u32> = around.keys().copied().collect();
    verts.sort_unstable();
    for v in verts {
        let fs = &around[&v];
        let mut uf = crate::topology::UnionFind::new(fs.len());
        // Per other vertex w: the first face (of `fs`) seen with the edge v–w.
        let mut by_other: std::collections::HashMap<u32, usize> = Default::default();
        for (j, &(fi, _)) in fs.iter().enumerate() {
            for &w in faces[fi].iter().filter(|&&w| w != v) {
                if sharp(v, w) {
                    continue;
                }
                match by_other.get(&w) {
                    Some(&i) => uf.union(i, j),
                    None => {
                        by_other.insert(w, j);
                    }
                }
            }
        }
        let mut id_of_root: std::collections::HashMap<usize, u32> = Default::default();
        id_of_root.insert(uf.find(0), v);
        for (j, &(fi, k)) in fs.iter().enumerate() {
            let root = uf.find(j);
            let id = *id_of_root.entry(root).or_insert_with(|| {
                of.push(v);
                (of.len() - 1) as u32
            });
            corners[fi][k] = id;
        }
    }
    (corners, of)
}

/// An undirected mesh edge: its two vertices, smaller first.
pub type Edge = (u32, u32);

/// The dihedral-angle features of a mesh: its interior edges (two faces) whose faces' normals
/// are more than `angle` (radians) apart, as (smaller, larger) vertex pairs, sorted; and its
/// boundary edges (one face), likewise. The one detection of sharp edges: `curvenet sample`'s
/// creases, `curvenet fit`'s feature curves and the display normals ([`split_normals`]).
pub fn sharp_edges(positions: &[DVec3], faces: &[[u32; 3]], angle: f64) -> (Vec<Edge>, Vec<Edge>) {
    let face_normal = |f: &[u32; 3]| {
        let p = f.map(|i| positions[i as usize]);
        (p[1] - p[0]).cross(p[2] - p[0]).normalize_or_zero()
    };
    // Per undirected edge, the normals of its faces (up to three kept: a non-manifold edge is
    // neither sharp nor boundary).
    let mut edge: std::collections::HashMap<(u32, u32), Vec<DVec3>> = Default::default();
    for f in faces {
        let n = face_normal(f);
        for k in 0..3 {
            let (a, b) = (f[k], f[(k + 1) % 3]);
            let list = edge.entry((a.min(b), a.max(b))).or_default();
            if list.len() < 3 {
                list.push(n);
            }
        }
    }
    let cos = angle.cos();
    let (mut sharp, mut boundary) = (Vec::new(), Vec::new());
    for (e, ns) in edge {
        match ns.as_slice() {
            [_] => boundary.push(e),
            [n, m] if n.dot(*m) < cos => sharp.push(e),
            _ => {}
        }
    }
    sharp.sort_unstable();
    boundary.sort_unstable();
    (sharp, boundary)
}

/// The dihedral angle (degrees) above which display normals are split ([`split_normals`]): the
/// OBJ writer's per-corner normals, renders and the viewer shade such edges sharp. Blender's
/// default auto-smooth angle; a crease found by `curvenet sample` is at least this sharp.
pub const SHARP_SHADING_DEG: f64 = 30.0;

/// What [`split_normals`] returns.
#[derive(Clone, Debug, PartialEq)]
pub struct SplitNormals {
    /// The normals: one per vertex, then one per extra sector of a vertex on sharp edges.
    pub normals: Vec<DVec3>,
    /// Per face corner, the index of its normal.
    pub corners: Vec<[u32; 3]>,
    /// Per normal, the vertex it belongs to.
    pub vertex: Vec<u32>,
}

/// Normals split at sharp edges, for display (OBJ `f v//vn`, renders): edges between two faces
/// whose normals are more than `angle` (radians) apart are sharp, and each sector of faces
/// around a vertex on them ([`sectors`]) gets its own angle-weighted normal, appended after
/// `normals` (one per vertex, kept for the vertices on no sharp edge).
pub fn split_normals(faces: &[[u32; 3]], positions: &[DVec3], normals: &[DVec3], angle: f64) -> SplitNormals {
    let face_normal = |f: &[u32; 3]| {
        let p = f.map(|i| positions[i as usize]);
        (p[1] - p[0]).cross(p[2] - p[0]).normalize_or_zero()
    };
    let sharp: std::collections::HashSet<(u32, u32)> = sharp_edges(positions, faces, angle).0.into_iter().collect();
    let sharp = |a: u32, b: u32| sharp.contains(&(a.min(b), a.max(b)));
    let (corners, of) = sectors(positions.len(), faces, sharp);
    if of.len() == positions.len() {
        return SplitNormals { normals: normals.to_vec(), corners: faces.to_vec(), vertex: of };
    }
    // The sector normals of the vertices on sharp edges (angle-weighted over their faces).
    let mut split = vec![DVec3::ZERO; of.len()];
    let mut is_split = vec![false; positions.len()];
    for &v in &of[positions.len()..] {
        is_split[v as usize] = true;
    }
    for (f, c) in faces.iter().zip(&corners) {
        let n = face_normal(f);
        let p = f.map(|i| positions[i as usize]);
        for k in 0..3 {
            if is_split[f[k] as usize] {
                let angle = (p[(k + 1) % 3] - p[k]).angle_between(p[(k + 2) % 3] - p[k]);
                if angle.is_finite() {
                    split[c[k] as usize] += angle * n;
                }
            }
        }
    }
    let mut out = normals.to_vec();
    for (s, &v) in of.iter().enumerate() {
        if is_split[v as usize] {
            let n = split[s].try_normalize().unwrap_or(normals[v as usize]);
            if s < positions.len() {
                out[s] = n;
            } else {
                out.push(n);
            }
        }
    }
    SplitNormals { normals: out, corners, vertex: of }
}

#[cfg(test)]
#[path = "tests/operators.rs"]
mod tests;
