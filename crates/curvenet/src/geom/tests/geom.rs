use super::*;

#[test]
fn frame_is_right_handed() {
    for n in [DVec3::X, DVec3::new(0.3, -0.4, 0.8).normalize(), -DVec3::Z] {
        let (e1, e2) = plane_frame(n);
        assert!((e1.cross(e2) - n).length() < 1e-12);
        assert!(e1.dot(n).abs() < 1e-12);
    }
}

#[test]
fn crossing_segments_meet() {
    let (s, t) = closest_params_segment_segment(
        DVec3::new(-1.0, 0.0, 0.0),
        DVec3::new(1.0, 0.0, 0.0),
        DVec3::new(0.5, -1.0, 0.1),
        DVec3::new(0.5, 1.0, 0.1),
    );
    assert!((s - 0.75).abs() < 1e-12 && (t - 0.5).abs() < 1e-12);
}

#[test]
fn parallel_segments_are_handled() {
    let (s, t) =
        closest_params_segment_segment(DVec3::ZERO, DVec3::X, DVec3::new(2.0, 1.0, 0.0), DVec3::new(3.0, 1.0, 0.0));
    assert_eq!((s, t), (1.0, 0.0));
}

#[test]
fn square_area() {
    let sq = [DVec2::new(0.0, 0.0), DVec2::new(1.0, 0.0), DVec2::new(1.0, 1.0), DVec2::new(0.0, 1.0)];
    assert!((polygon_signed_area(&sq) - 1.0).abs() < 1e-15);
    let sq3: Vec<DVec3> = sq.iter().map(|p| p.extend(0.0)).collect();
    assert!((polygon_vector_area(&sq3) - DVec3::Z).length() < 1e-15);
}
