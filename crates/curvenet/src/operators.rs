//! Discrete differential operators on the mesh ([CG] §3.4): the cotangent Laplacian `Ls`, the
//! mixed Voronoi mass matrix `M`, vertex normals, and the two mean-curvature estimates — the
//! cotangent formula and the paper's normal-blended formula (eq. 1).
//!
//! Sign conventions (DESIGN §1): `(Ls)_ij = ½(cot αᵢⱼ + cot βᵢⱼ)`, `(Ls)_ii = −Σⱼ (Ls)_ij`
//! (negative semi-definite); `L = M⁻¹ Ls`; on a smooth surface `L V ≈ −2 H N` with `H > 0` on a
//! sphere with outward normals.

use crate::geom::{DVec2, DVec3};
use crate::mesh::Mesh;
use crate::sparse::Csc;

/// Where the cotangent weights and areas are measured.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Metric {
    /// In the plane each patch was triangulated in ([CG] §3.4: "based on the planar
    /// triangulation"). Not isometric to the surface: a known bias of the paper ([CG] §5).
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
        cot[k] = u.dot(v)
            / c.max(1e-12 * u.length() * v.length())
                .max(f64::MIN_POSITIVE);
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
            *s =
                (p[k].distance_squared(p[i]) * cot[j] + p[k].distance_squared(p[j]) * cot[i]) / 8.0;
        }
    }
    (cot, share)
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
    // Sort and deduplicate each column, then compact.
    let mut out = Csc {
        nrows: n,
        ncols: n,
        col_ptr: Vec::with_capacity(n + 1),
        row_idx: Vec::new(),
        values: Vec::new(),
    };
    out.col_ptr.push(0);
    for j in 0..n {
        let col = &mut rows[col_ptr[j]..fill[j]];
        col.sort_unstable();
        let mut last = u32::MAX;
        for &r in col.iter() {
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

/// Assembles `Ls` and `M` on `mesh` with the given metric; `positions` are the 3D positions used
/// by [`Metric::Surface`] (ignored for [`Metric::Planar`], which reads `mesh.planar`).
pub fn cotan_operators(mesh: &Mesh, metric: Metric, positions: &[DVec3]) -> Operators {
    let n = mesh.num_vertices();
    let mut ls = laplacian_pattern(n, &mesh.faces);
    let mut mass = vec![0.0; n];
    let lift = |q: DVec2| DVec3::new(q.x, q.y, 0.0);
    for (fi, f) in mesh.faces.iter().enumerate() {
        let p = match metric {
            Metric::Planar => {
                let q = mesh.planar[fi];
                [lift(q[0]), lift(q[1]), lift(q[2])]
            }
            Metric::Surface => [
                positions[f[0] as usize],
                positions[f[1] as usize],
                positions[f[2] as usize],
            ],
        };
        let (cot, share) = corner_terms(p);
        for k in 0..3 {
            mass[f[k] as usize] += share[k];
            // The edge opposite corner k gets ½ cot(angle k).
            let (i, j) = (f[(k + 1) % 3] as usize, f[(k + 2) % 3] as usize);
            let w = 0.5 * cot[k];
            add(&mut ls, i, j, w);
            add(&mut ls, j, i, w);
            add(&mut ls, i, i, -w);
            add(&mut ls, j, j, -w);
        }
    }
    Operators { ls, mass }
}

fn add(m: &mut Csc, i: usize, j: usize, v: f64) {
    let r = m.col_ptr[j]..m.col_ptr[j + 1];
    if let Ok(k) = m.row_idx[r.clone()].binary_search(&(i as u32)) {
        m.values[r.start + k] += v;
    }
}

/// Mixed Voronoi areas of the mesh at `positions` (3D).
pub fn mixed_areas(faces: &[[u32; 3]], positions: &[DVec3]) -> Vec<f64> {
    let mut a = vec![0.0; positions.len()];
    for f in faces {
        let (_, share) = corner_terms([
            positions[f[0] as usize],
            positions[f[1] as usize],
            positions[f[2] as usize],
        ]);
        for k in 0..3 {
            a[f[k] as usize] += share[k];
        }
    }
    a
}

/// Area-weighted vertex normals (unit; zero for isolated vertices).
pub fn vertex_normals(faces: &[[u32; 3]], positions: &[DVec3]) -> Vec<DVec3> {
    let mut n = vec![DVec3::ZERO; positions.len()];
    for f in faces {
        let [a, b, c] = [
            positions[f[0] as usize],
            positions[f[1] as usize],
            positions[f[2] as usize],
        ];
        let fnrm = (b - a).cross(c - a);
        for &i in f {
            n[i as usize] += fnrm;
        }
    }
    n.iter().map(|v| v.normalize_or_zero()).collect()
}

/// Signed mean curvature by the cotangent formula: `H = −½ (M⁻¹ Ls V) · n` with `n` the vertex
/// normal (`+1` on a unit sphere). Vertices in `skip` (open-boundary vertices, where the
/// one-sided Laplacian is not a curvature) get 0.
pub fn cotan_mean_curvature(faces: &[[u32; 3]], positions: &[DVec3], skip: &[bool]) -> Vec<f64> {
    let n = positions.len();
    let mut lv = vec![DVec3::ZERO; n];
    let mut mass = vec![0.0; n];
    for f in faces {
        let p = [
            positions[f[0] as usize],
            positions[f[1] as usize],
            positions[f[2] as usize],
        ];
        let (cot, share) = corner_terms(p);
        for k in 0..3 {
            let (i, j) = (f[(k + 1) % 3] as usize, f[(k + 2) % 3] as usize);
            let w = 0.5 * cot[k];
            lv[i] += w * (positions[j] - positions[i]);
            lv[j] += w * (positions[i] - positions[j]);
            mass[f[k] as usize] += share[k];
        }
    }
    let normals = vertex_normals(faces, positions);
    (0..n)
        .map(|i| {
            if skip.get(i).copied().unwrap_or(false) || mass[i] <= 0.0 {
                0.0
            } else {
                -0.5 * lv[i].dot(normals[i]) / mass[i]
            }
        })
        .collect()
}

/// The paper's mean-curvature vector ([CG] eq. 1), blending positions `V*` with normals `N*`:
///
/// `h(v) = 1/(4A) Σᵢ (n + nᵢ + nᵢ₊₁)/‖n + nᵢ + nᵢ₊₁‖ × (vᵢ₊₁ − vᵢ)`,
///
/// summed over the edges `vᵢ → vᵢ₊₁` opposite to `v` in its one-ring (counter-clockwise), `A`
/// the mixed Voronoi area of `v` on the surface `V*`. `h ≈ H n`; the returned scalar is the
/// **signed** `H = h · n*(v)` (DESIGN §1: the papers' `‖h‖` loses the sign). Vertices in `skip`
/// (open boundary: incomplete ring) get 0.
pub fn blended_mean_curvature(
    faces: &[[u32; 3]],
    positions: &[DVec3],
    normals: &[DVec3],
    skip: &[bool],
) -> Vec<f64> {
    let n = positions.len();
    let area = mixed_areas(faces, positions);
    let mut h = vec![DVec3::ZERO; n];
    for f in faces {
        for k in 0..3 {
            let v = f[k] as usize;
            let (a, b) = (f[(k + 1) % 3] as usize, f[(k + 2) % 3] as usize);
            let m = (normals[v] + normals[a] + normals[b]).normalize_or_zero();
            h[v] += m.cross(positions[b] - positions[a]);
        }
    }
    (0..n)
        .map(|i| {
            if skip.get(i).copied().unwrap_or(false) || area[i] <= 0.0 {
                0.0
            } else {
                h[i].dot(normals[i]) / (4.0 * area[i])
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A (u, v)-grid mesh of `k × k` quads split into triangles over [0,1]², lifted by `f`.
    pub(crate) fn grid(k: usize, f: impl Fn(f64, f64) -> DVec3) -> (Vec<DVec3>, Vec<[u32; 3]>) {
        let mut p = Vec::new();
        for j in 0..=k {
            for i in 0..=k {
                p.push(f(i as f64 / k as f64, j as f64 / k as f64));
            }
        }
        let id = |i: usize, j: usize| (j * (k + 1) + i) as u32;
        let mut t = Vec::new();
        for j in 0..k {
            for i in 0..k {
                t.push([id(i, j), id(i + 1, j), id(i + 1, j + 1)]);
                t.push([id(i, j), id(i + 1, j + 1), id(i, j + 1)]);
            }
        }
        (p, t)
    }

    fn mesh_of(p: Vec<DVec3>, t: Vec<[u32; 3]>) -> Mesh {
        let n = p.len();
        Mesh {
            planar: t
                .iter()
                .map(|f| {
                    [
                        p[f[0] as usize].truncate(),
                        p[f[1] as usize].truncate(),
                        p[f[2] as usize].truncate(),
                    ]
                })
                .collect(),
            face_patch: vec![0; t.len()],
            on_boundary: vec![false; n],
            positions: p,
            faces: t,
            num_curve: 0,
            curve_normals: vec![],
        }
    }

    #[test]
    fn hand_checked_triangle() {
        // Right isosceles triangle: cot 90° = 0, cot 45° = 1.
        let (cot, share) = corner_terms([DVec3::ZERO, DVec3::X, DVec3::Y]);
        assert!(
            cot[0].abs() < 1e-15 && (cot[1] - 1.0).abs() < 1e-15 && (cot[2] - 1.0).abs() < 1e-15
        );
        assert!((share.iter().sum::<f64>() - 0.5).abs() < 1e-15);
        // The right angle is not obtuse: Voronoi shares (1/4 at the right angle, 1/8 at the others).
        assert!((share[0] - 0.25).abs() < 1e-15 && (share[1] - 0.125).abs() < 1e-15);
    }

    #[test]
    fn rows_sum_to_zero_and_planar_coordinates_are_harmonic() {
        let (p, t) = grid(12, |u, v| DVec3::new(u + 0.3 * v, v + 0.1 * u * u, 0.0));
        let mesh = mesh_of(p.clone(), t);
        for metric in [Metric::Planar, Metric::Surface] {
            let ops = cotan_operators(&mesh, metric, &p);
            let k = 13;
            for j in 0..ops.ls.ncols {
                let (rows, vals) = ops.ls.col(j);
                // L·1 = 0
                assert!(vals.iter().sum::<f64>().abs() < 1e-12);
                // Interior vertices: Ls applied to the x and y coordinates vanishes.
                let (i, jj) = (j % k, j / k);
                if i > 0 && i < k - 1 && jj > 0 && jj < k - 1 {
                    let lx: DVec3 = rows
                        .iter()
                        .zip(vals)
                        .map(|(&r, &v)| v * p[r as usize])
                        .sum();
                    assert!(lx.length() < 1e-12, "{lx:?}");
                }
            }
            // Symmetric.
            for j in 0..ops.ls.ncols {
                let (rows, vals) = ops.ls.col(j);
                for (&r, &v) in rows.iter().zip(vals) {
                    assert!((ops.ls.get(j, r as usize) - v).abs() < 1e-14);
                }
            }
            // Areas add up to the total area.
            let total: f64 = ops.mass.iter().sum();
            let want: f64 = mesh
                .faces
                .iter()
                .map(|f| {
                    0.5 * (p[f[1] as usize] - p[f[0] as usize])
                        .cross(p[f[2] as usize] - p[f[0] as usize])
                        .length()
                })
                .sum();
            assert!((total - want).abs() < 1e-12);
        }
    }

    /// A unit sphere from a subdivided octahedron: curvature estimates must be ≈ 1.
    pub(crate) fn sphere(levels: usize) -> (Vec<DVec3>, Vec<[u32; 3]>) {
        let mut p = vec![
            DVec3::X,
            -DVec3::X,
            DVec3::Y,
            -DVec3::Y,
            DVec3::Z,
            -DVec3::Z,
        ];
        let mut t: Vec<[u32; 3]> = vec![
            [0, 2, 4],
            [2, 1, 4],
            [1, 3, 4],
            [3, 0, 4],
            [2, 0, 5],
            [1, 2, 5],
            [3, 1, 5],
            [0, 3, 5],
        ];
        for _ in 0..levels {
            let mut mid = std::collections::HashMap::new();
            let mut nt = Vec::new();
            let mut m = |a: u32, b: u32, p: &mut Vec<DVec3>| {
                *mid.entry((a.min(b), a.max(b))).or_insert_with(|| {
                    p.push((p[a as usize] + p[b as usize]).normalize());
                    (p.len() - 1) as u32
                })
            };
            for f in &t {
                let (a, b, c) = (
                    m(f[0], f[1], &mut p),
                    m(f[1], f[2], &mut p),
                    m(f[2], f[0], &mut p),
                );
                nt.extend([[f[0], a, c], [a, f[1], b], [c, b, f[2]], [a, b, c]]);
            }
            t = nt;
        }
        (p, t)
    }

    #[test]
    fn mean_curvature_of_a_fine_sphere_is_one() {
        let (p, t) = sphere(5);
        let h = cotan_mean_curvature(&t, &p, &[]);
        let mean = h.iter().sum::<f64>() / h.len() as f64;
        assert!((mean - 1.0).abs() < 0.02, "{mean}");
        let worst = h.iter().map(|x| (x - 1.0).abs()).fold(0.0, f64::max);
        assert!(worst < 0.02, "{worst}");
        // The paper's eq. (1) with the exact normals: within 2% at every regular vertex. At the
        // 6 valence-4 vertices of the octahedron (90° corners) eq. (1) reads 2/3: it averages
        // the normals over each triangle, which there differ from the face normal.
        let hb = blended_mean_curvature(&t, &p, &p, &[]);
        let mut valence = vec![0; p.len()];
        t.iter().flatten().for_each(|&i| valence[i as usize] += 1);
        let worst = (0..p.len())
            .filter(|&i| valence[i] == 6)
            .map(|i| (hb[i] - 1.0).abs())
            .fold(0.0, f64::max);
        assert!(worst < 0.02, "{worst}");
        let irregular: Vec<f64> = (0..p.len())
            .filter(|&i| valence[i] != 6)
            .map(|i| hb[i])
            .collect();
        assert_eq!(irregular.len(), 6);
        assert!(
            irregular.iter().all(|x| (x - 2.0 / 3.0).abs() < 0.01),
            "{irregular:?}"
        );
        // Flipped normals flip the sign: the estimate is signed.
        let inward: Vec<DVec3> = p.iter().map(|v| -*v).collect();
        let tf: Vec<[u32; 3]> = t.iter().map(|f| [f[0], f[2], f[1]]).collect();
        let hn = blended_mean_curvature(&tf, &p, &inward, &[]);
        assert!(hn.iter().zip(&hb).all(|(a, b)| (a + b).abs() < 1e-12));
    }
}
