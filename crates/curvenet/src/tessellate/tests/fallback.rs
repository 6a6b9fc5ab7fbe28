use super::*;
use crate::geom::polygon_signed_area;

/// The unit square's covariance is isotropic: its four corners go on a circle of perimeter 4
/// (the 1024-gon the arc-length table uses), a quarter of the perimeter apart, starting on the
/// first axis.
#[test]
fn the_ellipse_of_a_square_is_a_circle_of_its_perimeter() {
    let p3 = [DVec3::ZERO, DVec3::X, DVec3::new(1.0, 1.0, 0.0), DVec3::Y];
    let q = ellipse_domain(&p3, DVec3::Z);
    let k = 1024.0;
    let r = 4.0 / (k * 2.0 * (std::f64::consts::PI / k).sin());
    let expected = [DVec2::new(r, 0.0), DVec2::new(0.0, r), DVec2::new(-r, 0.0), DVec2::new(0.0, -r)];
    for (a, b) in q.iter().zip(expected) {
        assert!(a.distance(b) < 1e-9, "{q:?}, expected {expected:?}");
    }
}

/// A 4 × 1 rectangle (as its four corners): the ellipse's axes have the ratio of the
/// principal directions' spreads, 1/4, the major axis along x; the domain is convex and
/// counter-clockwise.
#[test]
fn the_ellipse_of_a_rectangle_follows_its_principal_axes() {
    let (w, h) = (4.0, 1.0);
    let p3 = [DVec3::ZERO, DVec3::new(w, 0.0, 0.0), DVec3::new(w, h, 0.0), DVec3::new(0.0, h, 0.0)];
    let q = ellipse_domain(&p3, DVec3::Z);
    assert!(polygon_signed_area(&q) > 0.0);
    // The ellipse through the points: x²/a² + y²/b² = 1 with b = a/4.
    let a = q.iter().map(|p| p.x.abs()).fold(0.0, f64::max);
    for p in &q {
        let e = (p.x / a).powi(2) + (4.0 * p.y / a).powi(2);
        assert!((e - 1.0).abs() < 1e-6, "{p:?} is off the ellipse ({e})");
    }
}
