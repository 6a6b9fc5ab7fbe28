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
            .map(|f| [p[f[0] as usize].truncate(), p[f[1] as usize].truncate(), p[f[2] as usize].truncate()])
            .collect(),
        face_patch: vec![0; t.len()],
        on_boundary: vec![false; n],
        positions: p,
        faces: t,
        num_curve: 0,
        curve_normals: vec![],
        pattern: Default::default(),
        fold_fallback: vec![],
        seam_rows: Vec::new(),
    }
}

#[test]
fn hand_checked_triangle() {
    // Right isosceles triangle: cot 90° = 0, cot 45° = 1.
    let (cot, share) = corner_terms([DVec3::ZERO, DVec3::X, DVec3::Y]);
    assert!(cot[0].abs() < 1e-15 && (cot[1] - 1.0).abs() < 1e-15 && (cot[2] - 1.0).abs() < 1e-15);
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
                let lx: DVec3 = rows.iter().zip(vals).map(|(&r, &v)| v * p[r as usize]).sum();
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
            .map(|f| 0.5 * (p[f[1] as usize] - p[f[0] as usize]).cross(p[f[2] as usize] - p[f[0] as usize]).length())
            .sum();
        assert!((total - want).abs() < 1e-12);
    }
}

/// A unit sphere from a subdivided octahedron: curvature estimates must be ≈ 1.
pub(crate) fn sphere(levels: usize) -> (Vec<DVec3>, Vec<[u32; 3]>) {
    let mut p = vec![DVec3::X, -DVec3::X, DVec3::Y, -DVec3::Y, DVec3::Z, -DVec3::Z];
    let mut t: Vec<[u32; 3]> =
        vec![[0, 2, 4], [2, 1, 4], [1, 3, 4], [3, 0, 4], [2, 0, 5], [1, 2, 5], [3, 1, 5], [0, 3, 5]];
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
            let (a, b, c) = (m(f[0], f[1], &mut p), m(f[1], f[2], &mut p), m(f[2], f[0], &mut p));
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
    let hb = blended_mean_curvature(&t, &p, &p, &mixed_areas(&t, &p), &[]);
    let mut valence = vec![0; p.len()];
    t.iter().flatten().for_each(|&i| valence[i as usize] += 1);
    let worst = (0..p.len()).filter(|&i| valence[i] == 6).map(|i| (hb[i] - 1.0).abs()).fold(0.0, f64::max);
    assert!(worst < 0.02, "{worst}");
    let irregular: Vec<f64> = (0..p.len()).filter(|&i| valence[i] != 6).map(|i| hb[i]).collect();
    assert_eq!(irregular.len(), 6);
    assert!(irregular.iter().all(|x| (x - 2.0 / 3.0).abs() < 0.01), "{irregular:?}");
    // Flipped normals flip the sign: the estimate is signed.
    let inward: Vec<DVec3> = p.iter().map(|v| -*v).collect();
    let tf: Vec<[u32; 3]> = t.iter().map(|f| [f[0], f[2], f[1]]).collect();
    let hn = blended_mean_curvature(&tf, &p, &inward, &mixed_areas(&tf, &p), &[]);
    assert!(hn.iter().zip(&hb).all(|(a, b)| (a + b).abs() < 1e-12));
}

/// Degenerate triangles (cotangent blow-up): collinear, coincident corners, a needle, at tiny
/// and huge scales — the cotangents are clamped (|cot| ≤ 1e12) and every term stays finite.
#[test]
fn degenerate_triangles_give_finite_clamped_terms() {
    for s in [1e-12, 1.0, 1e12] {
        for tri in [
            [DVec3::ZERO, DVec3::X, DVec3::X * 2.0],               // collinear
            [DVec3::ZERO, DVec3::ZERO, DVec3::Y],                  // two corners coincide
            [DVec3::ZERO, DVec3::ZERO, DVec3::ZERO],               // a point
            [DVec3::ZERO, DVec3::X, DVec3::new(0.5, 1e-300, 0.0)], // flat to underflow
            [DVec3::ZERO, DVec3::X, DVec3::new(1e6, 1.0, 0.0)],    // a long needle
        ] {
            let (cot, share) = corner_terms(tri.map(|p| p * s));
            assert!(cot.iter().chain(&share).all(|x| x.is_finite()), "×{s:e} {tri:?}: {cot:?} {share:?}");
            assert!(cot.iter().all(|c| c.abs() <= 1.000001e12), "×{s:e} {tri:?}: {cot:?}");
        }
    }
    // In an operator: a grid with one collapsed vertex still has a finite, symmetric Laplacian.
    let (mut p, t) = grid(4, |u, v| DVec3::new(u, v, 0.0));
    p[6] = p[7];
    let m = mesh_of(p, t);
    let ops = cotan_operators(&m, Metric::Planar, &m.positions);
    assert!(ops.ls.values.iter().all(|x| x.is_finite()) && ops.mass.iter().all(|x| x.is_finite()));
}

/// The unit cube, two triangles per side, counter-clockwise seen from outside.
fn cube() -> (Vec<DVec3>, Vec<[u32; 3]>) {
    let p: Vec<DVec3> = (0..8).map(|i| DVec3::new((i & 1) as f64, ((i >> 1) & 1) as f64, (i >> 2) as f64)).collect();
    let quads = [[0, 2, 3, 1], [4, 5, 7, 6], [0, 1, 5, 4], [2, 6, 7, 3], [0, 4, 6, 2], [1, 3, 7, 5]];
    (p, quads.iter().flat_map(|q| [[q[0], q[1], q[2]], [q[0], q[2], q[3]]]).collect())
}

#[test]
fn a_cube_split_at_its_edges_has_three_sectors_per_corner_with_the_face_normals() {
    let (p, f) = cube();
    let is_edge = |a: u32, b: u32| {
        (p[a as usize] - p[b as usize]).abs().max_element() > 0.5 && {
            // A cube edge changes one coordinate; a face diagonal two.
            let d = (p[a as usize] - p[b as usize]).abs();
            (d.x + d.y + d.z - 1.0).abs() < 1e-12
        }
    };
    let (corners, of) = sectors(p.len(), &f, is_edge);
    assert_eq!(of.len(), 24, "3 sectors at each of the 8 corners");
    // The two triangles of one side share their corners' sectors; different sides do not.
    for (fi, c) in corners.iter().enumerate() {
        for (k, &s) in c.iter().enumerate() {
            assert_eq!(of[s as usize], f[fi][k]);
        }
    }
    assert_eq!(corners[0][0], corners[1][0]);
    assert_ne!(corners[0][0], corners[4][0]);
    // Nothing sharp: one sector per vertex, the faces unchanged.
    let (same, of) = sectors(p.len(), &f, |_, _| false);
    assert_eq!((same, of.len()), (f.clone(), 8));

    let smooth = angle_weighted_normals(&f, &p);
    let SplitNormals { normals, corners, vertex } = split_normals(&f, &p, &smooth, 30f64.to_radians());
    assert_eq!(vertex.len(), normals.len());
    for (fi, c) in corners.iter().enumerate() {
        let q = f[fi].map(|i| p[i as usize]);
        let face = (q[1] - q[0]).cross(q[2] - q[0]).normalize();
        for &s in c {
            assert!(normals[s as usize].distance(face) < 1e-12, "face {fi}: {} vs {face}", normals[s as usize]);
        }
    }
    // Above 90°, nothing is split: the corners keep the smooth normals.
    let SplitNormals { normals: kept, corners, .. } = split_normals(&f, &p, &smooth, 100f64.to_radians());
    assert_eq!((kept, corners), (smooth, f));
}
