use super::*;

fn unit_square() -> Vec<DVec2> {
    vec![DVec2::new(0.0, 0.0), DVec2::new(1.0, 0.0), DVec2::new(1.0, 1.0), DVec2::new(0.0, 1.0)]
}

/// The unit square at d = 0.1: rows 0.0866 apart from y = 0, points kept 0.06 from the
/// border. Rows 1–10 (y ≤ 0.866) are in; the even rows hold x = 0.1 … 0.9 (9 points), the
/// odd rows (shifted by 0.05) x = 0.15 … 0.85 (8 points): 5 · 9 + 5 · 8 = 85 points.
#[test]
fn the_lattice_of_the_unit_square_has_85_points_at_spacing_d() {
    let d = 0.1;
    let lat = hex_lattice(&unit_square(), d);
    assert_eq!(lat.points.len(), 85);
    let row = 0.5 * 3f64.sqrt() * d;
    for p in &lat.points {
        let k = (p.y / row).round();
        assert!((p.y - k * row).abs() < 1e-12, "{p:?} is not on a row");
        assert!((1..=10).contains(&(k as i64)), "{p:?}");
        let shift = if k as i64 % 2 == 1 { 0.5 * d } else { 0.0 };
        assert!(((p.x - shift) / d - ((p.x - shift) / d).round()).abs() < 1e-9, "{p:?} is off the columns");
        let border = p.x.min(p.y).min(1.0 - p.x).min(1.0 - p.y);
        assert!(border >= 0.6 * d, "{p:?} is {border} from the border");
    }
}

/// Between consecutive rows of 9 and 8 points (17 points in a zigzag) lie 15 triangles; 9
/// such strips: 135 triangles, all equilateral of side d and counter-clockwise. The interior
/// points (in a triangle, on no outline edge) are those of rows 2–9 without the ends of their
/// row, 4 · 7 + 4 · 6 = 52; the other 33 are on the outline.
#[test]
fn the_lattice_triangles_of_the_unit_square() {
    let d = 0.1;
    let lat = hex_lattice(&unit_square(), d);
    let t = lattice_triangles(&lat);
    assert_eq!(t.triangles.len(), 135);
    for tri in &t.triangles {
        let [a, b, c] = tri.map(|v| lat.points[v as usize]);
        for (p, q) in [(a, b), (b, c), (c, a)] {
            assert!((p.distance(q) - d).abs() < 1e-12, "{tri:?}");
        }
        assert!((b - a).perp_dot(c - a) > 0.0, "{tri:?} is clockwise");
    }
    assert_eq!(t.interior.iter().filter(|&&i| i).count(), 52);
    // The outline is closed: every outline point has two outline edges.
    let mut degree = vec![0; lat.points.len()];
    for e in &t.outline {
        degree[e[0] as usize] += 1;
        degree[e[1] as usize] += 1;
    }
    assert!(degree.iter().all(|&k| k == 0 || k == 2), "{degree:?}");
    assert_eq!(degree.iter().filter(|&&k| k == 2).count(), 85 - 52);
}

#[test]
fn a_polygon_narrower_than_the_margins_has_no_lattice() {
    let thin: Vec<DVec2> = unit_square().iter().map(|p| DVec2::new(p.x, 0.1 * p.y)).collect();
    assert!(hex_lattice(&thin, 0.1).points.is_empty());
    assert!(lattice_triangles(&hex_lattice(&thin, 0.1)).triangles.is_empty());
}
