//! Open networks whose curves were left out in places (issue 5, networks sampled from real
//! meshes): what the pipeline does with what is left.

use curvenet::geom::DVec3;
use curvenet::{surface, Curve, Network, Options};

fn polyline(name: &str, points: Vec<DVec3>, closed: bool, boundary: bool) -> Curve {
    let n = points.len();
    Curve { name: Some(name.into()), points, normals: vec![DVec3::Z; n], closed, boundary, ..Default::default() }
}

fn line(name: &str, a: DVec3, b: DVec3, pieces: usize) -> Curve {
    polyline(name, (0..=pieces).map(|i| a.lerp(b, i as f64 / pieces as f64)).collect(), false, false)
}

/// Issue 5 (beetle, 8 to 12 planes): a hole whose boundary loop only one curve reaches (the
/// other curves that reached it were left out). That curve has the same patch on both sides
/// (a bridge) and is left out; the loop then used to be surfaced as a disk of its own over the
/// patch around it — a second sheet, a second component. It is now left out with a warning
/// naming it, the hole covered by the patch around it: one sheet.
#[test]
fn a_hole_reached_by_a_single_curve_is_covered_with_a_warning() {
    hole_reached_by_a_bridge(1.3);
    // The bridge drawn past the hole's border (at the border's first sample): still a stroke
    // into a hole, not a petal touching the grid (node finding keeps a closed boundary curve
    // apart only where two other passages meet it).
    hole_reached_by_a_bridge(1.32);
}

fn hole_reached_by_a_bridge(end: f64) {
    let mut curves = Vec::new();
    // The border: the square [0, 3]², counter-clockwise about +z, sampled every 0.05.
    let corners = [DVec3::ZERO, DVec3::new(3.0, 0.0, 0.0), DVec3::new(3.0, 3.0, 0.0), DVec3::new(0.0, 3.0, 0.0)];
    let mut border = Vec::new();
    for k in 0..4 {
        border.extend((0..60).map(|i| corners[k].lerp(corners[(k + 1) % 4], i as f64 / 60.0)));
    }
    curves.push(polyline("border", border, true, true));
    // A 3 × 3 grid of curves ending on the border.
    for c in [1.0, 2.0] {
        curves.push(line("x", DVec3::new(c, 0.0, 0.0), DVec3::new(c, 3.0, 0.0), 60));
        curves.push(line("y", DVec3::new(0.0, c, 0.0), DVec3::new(3.0, c, 0.0), 60));
    }
    // A hole of radius 0.2 in the middle cell, and one curve from the grid to it.
    let hole: Vec<DVec3> = (0..40)
        .map(|i| {
            let a = -std::f64::consts::FRAC_PI_2 + std::f64::consts::TAU * i as f64 / 40.0;
            DVec3::new(1.5 + 0.2 * a.cos(), 1.5 + 0.2 * a.sin(), 0.0)
        })
        .collect();
    curves.push(polyline("hole", hole, true, true));
    curves.push(line("bridge", DVec3::new(1.5, 1.0, 0.0), DVec3::new(1.5, end, 0.0), 6));
    let net = Network { curves, snap: Some(1e-3), cycles: None };
    let s = surface(&net, &Options::default().with_vertices(3000)).unwrap();
    assert_eq!(s.stats.components, 1);
    let text: Vec<&str> = s.warnings.iter().map(|w| w.message.as_str()).collect();
    assert!(text.iter().any(|w| w.contains("\"bridge\"") && w.contains("same patch on both sides")), "{text:?}");
    assert!(text.iter().any(|w| w.contains("\"hole\"") && w.contains("covered")), "{text:?}");
    // One sheet: the area of the surface is that of the square.
    let area: f64 = s
        .mesh
        .faces
        .iter()
        .map(|f| {
            let p = f.map(|v| s.mesh.positions[v as usize]);
            0.5 * (p[1] - p[0]).cross(p[2] - p[0]).length()
        })
        .sum();
    assert!((area - 9.0).abs() < 0.05, "area {area}");
}

/// Issue 29: the cylinder's two rims without their boundary flag (`"boundry": true`, a typo)
/// bound a patch on each side; the error says to mark them as borders, not to change the
/// spacing.
#[test]
fn loops_that_meet_nothing_without_the_boundary_flag_get_the_right_hint() {
    let mut net = curvenet::network::examples::example("cylinder").unwrap();
    for c in &mut net.curves {
        c.boundary = false;
    }
    let Err(e) = surface(&net, &Options::default().with_vertices(3000)) else { panic!("surfaced") };
    let text = e.to_string();
    assert!(text.contains("mark it as one (`\"boundary\": true`)"), "{text}");
    assert!(!text.contains("smaller `spacing`"), "{text}");
}
