use super::*;

#[test]
fn a_ray_leaves_a_triangle_through_the_first_edge_it_meets() {
    let q = [DVec2::ZERO, DVec2::X, DVec2::Y];
    // From (0.25, 0.25) along +x: through edge 1 ((1, 0) → (0, 1)) at (0.75, 0.25).
    let (t, k, s) = exit_edge(DVec2::new(0.25, 0.25), DVec2::X, q, None).unwrap();
    assert_eq!(k, 1);
    assert!((t - 0.5).abs() < 1e-15 && (s - 0.25).abs() < 1e-15, "{t} {s}");
    // Along −x: through edge 2 ((0, 1) → (0, 0)) at (0, 0.25), three quarters along it.
    let (t, k, s) = exit_edge(DVec2::new(0.25, 0.25), -DVec2::X, q, None).unwrap();
    assert!(k == 2 && (t - 0.25).abs() < 1e-15 && (s - 0.75).abs() < 1e-15);
    // Entered through edge 1 and heading back out of it: no other exit.
    assert!(exit_edge(DVec2::new(0.25, 0.25), DVec2::X, q, Some(1)).is_none());
    // Through a corner: kept off the edge's end.
    let (_, _, s) = exit_edge(DVec2::new(0.25, 0.0), DVec2::new(-0.25, 1.0), q, Some(0)).unwrap();
    assert!(s == 1e-7 || s == 1.0 - 1e-7, "{s}");
}

#[test]
fn a_segment_alongside_is_found_within_the_radius_and_angle() {
    let mut grid = SegGrid { h: 0.1, cells: HashMap::new() };
    grid.add(0, DVec3::ZERO, DVec3::new(0.05, 0.0, 0.0), 0.025);
    let p = DVec3::new(0.02, 0.03, 0.0);
    assert!(grid.alongside(p, DVec3::X, 0.05, 0.9, None));
    assert!(!grid.alongside(p, DVec3::X, 0.02, 0.9, None), "too far");
    assert!(!grid.alongside(p, DVec3::Y, 0.05, 0.9, None), "across");
    assert!(!grid.alongside(p, DVec3::X, 0.05, 0.9, Some((0, 0.0, 0.1))), "skipped");
    assert!(grid.alongside(p, DVec3::X, 0.05, 0.9, Some((1, 0.0, 0.1))));
    grid.remove(0);
    assert!(!grid.alongside(p, DVec3::X, 0.05, 0.9, None));
}

#[test]
fn a_streamline_on_a_flat_square_is_a_straight_chord_between_boundary_edges() {
    let p = vec![DVec3::ZERO, DVec3::X, DVec3::new(1.0, 1.0, 0.0), DVec3::Y];
    let (mesh, _) = Mesh::repaired(&p, &[[0, 1, 2], [0, 2, 3]], 1e-4, None).unwrap();
    // The axis projected on the square: (−1, 1), across the diagonal between the faces.
    let field = CrossField::new(&mesh, DVec3::new(-1.0, 1.0, 1.0).normalize(), 2f64.sqrt());
    let opts = crate::sampling::SampleOptions { spacing: Some(0.01), ..Default::default() };
    let scales = Scales::new(crate::geom::Aabb::of(p.iter().copied()), &opts).unwrap();
    let mut tracer = Tracer::new(&mesh, &field, 0.2, &scales);
    let c = DVec3::new(0.8, 0.1, 0.0);
    let u = field.dir(0, DVec3::new(-1.0, 1.0, 0.0));
    assert!(u.distance(DVec3::new(-1.0, 1.0, 0.0).normalize()) < 1e-9, "{u}");
    let line = tracer.line_from(0, 0, c, u).unwrap();
    assert!(!line.closed);
    // Back to (0.9, 0) on the bottom edge 0–1, on to (0, 0.9) on the left edge 3–0, through
    // the diagonal at (0.45, 0.45).
    let (a, b) = (line.pts[0].p, line.pts[line.pts.len() - 1].p);
    assert!(a.distance(DVec3::new(0.9, 0.0, 0.0)) < 1e-9 && b.distance(DVec3::new(0.0, 0.9, 0.0)) < 1e-9, "{a} {b}");
    assert_eq!(line.ends, [Some((0, 1)), Some((0, 3))]);
    assert!(line.pts.iter().any(|q| q.p.distance(DVec3::new(0.45, 0.45, 0.0)) < 1e-6));
    assert!(line.pts.iter().all(|q| (q.p - a).cross(b - a).length() < 1e-9 && q.n.distance(DVec3::Z) < 1e-9));
    assert_eq!(line.faces.len() + 1, line.pts.len());
    // A seed next to it is covered (no curve starts there).
    assert!(tracer.grid.alongside(c + DVec3::new(0.05, 0.05, 0.0), u, 0.18, 0.76, None));
}
