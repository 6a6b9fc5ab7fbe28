use super::*;

/// The unit square in two triangles, lifted by an affine map.
fn square(lift: impl Fn(DVec2) -> DVec3) -> Vec<([DVec2; 3], Corners, [u32; 3])> {
    let q = [DVec2::new(0.0, 0.0), DVec2::new(1.0, 0.0), DVec2::new(1.0, 1.0), DVec2::new(0.0, 1.0)];
    let n = (lift(q[1]) - lift(q[0])).cross(lift(q[3]) - lift(q[0])).normalize();
    [[0, 1, 2], [0, 2, 3]]
        .iter()
        .map(|t| (t.map(|i| q[i]), (t.map(|i| lift(q[i])), [n; 3]), t.map(|i| i as u32)))
        .collect()
}

fn affine(q: DVec2) -> DVec3 {
    DVec3::new(1.0 + 2.0 * q.x - q.y, 0.5 * q.y, 3.0 * q.x + q.y)
}

#[test]
fn points_inside_get_the_affine_lift_exactly() {
    let tris = square(affine);
    let grid = Grid::new(&tris);
    for &(x, y) in &[(0.1, 0.2), (0.5, 0.5), (0.9, 0.05), (0.0, 1.0), (0.33, 0.99)] {
        let q = DVec2::new(x, y);
        let p = grid.blend(&tris, q).unwrap();
        assert!(p.distance(affine(q)) < 1e-12, "{q:?}: {p:?}");
    }
}

#[test]
fn points_outside_go_to_the_nearest_border_point() {
    let tris = square(affine);
    let grid = Grid::new(&tris);
    // Just left of the square's left edge: clamped onto it.
    let p = grid.blend(&tris, DVec2::new(-0.01, 0.5)).unwrap();
    assert!(p.distance(affine(DVec2::new(0.0, 0.5))) < 0.03, "{p:?}");
}

#[test]
fn an_empty_patch_places_nothing() {
    let grid = Grid::new(&[]);
    assert!(grid.blend(&[], DVec2::new(0.5, 0.5)).is_none());
}
