use super::*;

/// A cylinder of radius 1 along z, `n` sectors, `rows` rows of height `h`, open at both ends.
fn cylinder(n: usize, rows: usize, h: f64) -> (Vec<DVec3>, Vec<[u32; 3]>) {
    let mut p = Vec::new();
    for r in 0..=rows {
        for k in 0..n {
            let a = std::f64::consts::TAU * k as f64 / n as f64;
            p.push(DVec3::new(a.cos(), a.sin(), r as f64 * h));
        }
    }
    let at = |r: usize, k: usize| (r * n + k % n) as u32;
    let mut f = Vec::new();
    for r in 0..rows {
        for k in 0..n {
            f.push([at(r, k), at(r, k + 1), at(r + 1, k + 1)]);
            f.push([at(r, k), at(r + 1, k + 1), at(r + 1, k)]);
        }
    }
    (p, f)
}

#[test]
fn a_face_frame_maps_its_plane_to_2d_and_back() {
    let (a, b, c) = (DVec3::new(1.0, 2.0, 3.0), DVec3::new(2.0, 2.0, 3.0), DVec3::new(1.0, 2.0, 5.0));
    let fr = Frame::of(a, b, c);
    assert_eq!((fr.o, fr.e1), (a, DVec3::X));
    assert!(fr.n.distance(-DVec3::Y) < 1e-15 && fr.e2.distance(DVec3::Z) < 1e-15);
    assert!(fr.to2(c).distance(DVec2::new(0.0, 2.0)) < 1e-15);
    let q = DVec3::new(1.5, 2.0, 4.0);
    assert!(fr.to3(fr.to2(q)).distance(q) < 1e-15);
    // Off the plane: projected.
    assert!(fr.to2(q + DVec3::Y).distance(fr.to2(q)) < 1e-15);
    assert!(fr.dir2(DVec3::new(1.0, 5.0, 1.0)).distance(DVec2::new(1.0, 1.0)) < 1e-15);
}

#[test]
fn on_a_cylinder_the_field_follows_the_axis_and_the_circles() {
    let (p, f) = cylinder(48, 12, 0.25);
    let (mesh, _) = Mesh::repaired(&p, &f, 1e-4, None).unwrap();
    // The fixed axis at 45° to the principal directions: the curvature wins.
    let axis = DVec3::new(1.0, 0.0, 1.0).normalize();
    let field = CrossField::new(&mesh, axis, 4.0);
    assert!(field.good.iter().all(|&g| g));
    for fi in (0..mesh.faces.len()).step_by(7) {
        let along = field.dir(fi, DVec3::Z);
        assert!((along.length() - 1.0).abs() < 1e-12);
        assert!(along.dot(DVec3::Z) > 0.99, "face {fi}: {along}");
        // The direction closest to the circle's tangent is that tangent.
        let c = mesh.faces[fi].map(|v| mesh.positions[v as usize]).iter().sum::<DVec3>() / 3.0;
        let tangent = DVec3::Z.cross(c).normalize();
        assert!(field.dir(fi, tangent).dot(tangent) > 0.99, "face {fi}");
        // In the face's plane.
        assert!(along.dot(field.frames[fi].n).abs() < 1e-12);
    }
}

#[test]
fn on_a_flat_square_the_field_follows_the_projected_axis() {
    let p = vec![DVec3::ZERO, DVec3::X, DVec3::new(1.0, 1.0, 0.0), DVec3::Y];
    let (mesh, _) = Mesh::repaired(&p, &[[0, 1, 2], [0, 2, 3]], 1e-4, None).unwrap();
    // No curvature: the axis (1, 2, 5) projected on the plane is (1, 2, 0).
    let field = CrossField::new(&mesh, DVec3::new(1.0, 2.0, 5.0).normalize(), 1.0);
    let want = DVec3::new(1.0, 2.0, 0.0).normalize();
    for fi in 0..2 {
        assert!(field.dir(fi, want).distance(want) < 1e-9, "{}", field.dir(fi, want));
        let across = DVec3::Z.cross(want);
        assert!(field.dir(fi, across).distance(across) < 1e-9);
    }
}
