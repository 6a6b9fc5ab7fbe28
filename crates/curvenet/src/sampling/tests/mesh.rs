use super::*;
use crate::sampling::tests::{unit_cube, unit_square};

#[test]
fn a_cube_is_closed_and_every_edge_has_two_faces() {
    let (p, f) = unit_cube();
    let (mesh, repairs) = Mesh::repaired(&p, &f, 0.01, None).unwrap();
    assert_eq!((repairs.zipped, repairs.pinches), (0, 0));
    assert_eq!(mesh.faces, f);
    assert_eq!(mesh.edge_faces.len(), 18);
    assert!(mesh.edge_faces.values().all(|fs| fs.len() == 2));
    assert!(!mesh.is_boundary(edge_key(0, 1)));
    // Faces 0 ([0, 2, 3]) and 1 ([0, 3, 1]) share the edge 0–3 (local edge 2 of face 0).
    assert_eq!(mesh.across(0, 2), Some(1));
    // The corner normals point along the diagonals, away from the centre.
    for (q, n) in p.iter().zip(&mesh.normals) {
        let out = (*q - DVec3::splat(0.5)).normalize();
        assert!((n.length() - 1.0).abs() < 1e-12 && n.dot(out) > 0.99, "{n} at {q}");
    }
}

#[test]
fn vertices_at_the_same_position_are_welded() {
    // The square's two triangles with their own copies of the diagonal's vertices.
    let p = vec![
        DVec3::ZERO,
        DVec3::X,
        DVec3::new(1.0, 1.0, 0.0),
        DVec3::new(-0.0, 0.0, 0.0),
        DVec3::new(1.0, 1.0, 0.0),
        DVec3::Y,
    ];
    let f = vec![[0, 1, 2], [3, 4, 5]];
    let (mesh, _) = Mesh::repaired(&p, &f, 1e-3, None).unwrap();
    assert_eq!(mesh.faces, vec![[0, 1, 2], [0, 2, 5]]);
    // Four boundary edges, one inner edge.
    assert_eq!(mesh.edge_faces.values().filter(|fs| fs.len() == 1).count(), 4);
    assert_eq!(mesh.edge_faces[&(0, 2)], vec![0, 1]);
}

#[test]
fn the_input_checks_name_the_place() {
    let (p, f) = unit_square();
    assert!(check_mesh(&p, &[]).is_err());
    let e = check_mesh(&p, &[[0, 1, 7]]).unwrap_err();
    assert!(e.to_string().contains("face 0 uses vertex 7"), "{e}");
    let mut q = p.clone();
    q[2].z = f64::INFINITY;
    assert_eq!(check_mesh(&q, &f).unwrap_err().at().vertex, Some(2));
    let flat = vec![DVec3::ONE; 3];
    assert!(check_mesh(&flat, &[[0, 1, 2]]).unwrap_err().to_string().contains("zero extent"));
    let b = check_mesh(&p, &f).unwrap();
    assert_eq!((b.min, b.max), (DVec3::ZERO, DVec3::new(1.0, 1.0, 0.0)));
}

#[test]
fn a_narrow_crack_is_zipped() {
    // Two unit squares side by side, 0.001 apart: the facing boundary vertices are welded.
    let mut p = Vec::new();
    for x0 in [0.0, 1.001] {
        p.extend([
            DVec3::new(x0, 0.0, 0.0),
            DVec3::new(x0 + 1.0, 0.0, 0.0),
            DVec3::new(x0 + 1.0, 1.0, 0.0),
            DVec3::new(x0, 1.0, 0.0),
        ]);
    }
    let mut f = vec![[0, 1, 2], [0, 2, 3], [4, 5, 6], [4, 6, 7]];
    assert_eq!(zip_cracks(&mut p, &mut f, 0.01), 2);
    // 1 and 4, 2 and 7 welded at their midpoints: one rectangle, 6 boundary edges, 3 inside.
    assert_eq!(f.len(), 4);
    assert_eq!(f[2][0], f[0][1]);
    assert_eq!(f[3][2], f[0][2]);
    for v in [f[0][1], f[0][2]] {
        assert!((p[v as usize].x - 1.0005).abs() < 1e-12, "{}", p[v as usize]);
    }
    let (mesh, _) = Mesh::repaired(&p, &f, 0.0, None).unwrap();
    assert_eq!(mesh.edge_faces.values().filter(|fs| fs.len() == 1).count(), 6);
    assert_eq!(mesh.edge_faces.values().filter(|fs| fs.len() == 2).count(), 3);
    // Not within the tolerance: nothing changes.
    let (mut q, mut g) = (p.clone(), f.clone());
    assert_eq!(zip_cracks(&mut q, &mut g, 1e-6), 0);
    assert_eq!((q, g), (p, f));
}

#[test]
fn a_pinch_vertex_is_split_into_one_vertex_per_fan() {
    // Two triangles that share only vertex 0.
    let mut p = vec![
        DVec3::ZERO,
        DVec3::new(1.0, 0.0, 0.0),
        DVec3::new(1.0, 1.0, 0.0),
        DVec3::new(-1.0, 0.0, 0.0),
        DVec3::new(-1.0, -1.0, 0.0),
    ];
    let mut f = vec![[0, 1, 2], [0, 3, 4]];
    assert_eq!(split_pinches(&mut p, &mut f, 0.1), 1);
    assert_eq!(p.len(), 6);
    assert_ne!(f[0][0], f[1][0]);
    assert!(p[f[0][0] as usize].distance(p[f[1][0] as usize]) > 0.15);
}
