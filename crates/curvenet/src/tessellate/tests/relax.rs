use super::*;

/// A hexagonal patch of the lattice: the centre and its six neighbours (fixed border).
fn hexagon(center: DVec2) -> (Vec<[usize; 3]>, Vec<DVec2>) {
    let mut pos: Vec<DVec2> = (0..6).map(|k| DVec2::from_angle(k as f64 * std::f64::consts::FRAC_PI_3)).collect();
    pos.push(center);
    let tris = (0..6).map(|k| [6, k, (k + 1) % 6]).collect();
    (tris, pos)
}

#[test]
fn a_regular_hexagon_is_a_fixed_point() {
    let (tris, mut pos) = hexagon(DVec2::ZERO);
    relax(&tris, &mut pos, 6, &[]);
    assert!(pos[6].length() < 1e-14, "{:?}", pos[6]);
}

#[test]
fn an_off_centre_vertex_moves_to_the_centre_and_the_border_stays() {
    let (tris, mut pos) = hexagon(DVec2::new(0.4, -0.3));
    let border: Vec<DVec2> = pos[..6].to_vec();
    relax(&tris, &mut pos, 6, &[]);
    assert!(pos[6].length() < 0.02, "{:?}", pos[6]);
    assert_eq!(&pos[..6], &border[..]);
}

#[test]
fn no_triangle_flips_or_collapses() {
    // A thin fan: the centroid of the one-ring lies outside the kernel of the star (an arrow-shaped
    // border), moving there would flip a triangle.
    let mut pos = vec![
        DVec2::new(-1.0, 0.0),
        DVec2::new(0.0, -0.1),
        DVec2::new(1.0, 0.0),
        DVec2::new(0.0, 1.0),
        DVec2::new(0.0, 0.05),
    ];
    // Arrow: the border 0-1-2-3 with the fourth corner pulled in.
    pos[3] = DVec2::new(0.0, 0.12);
    let tris = vec![[4, 0, 1], [4, 1, 2], [4, 2, 3], [4, 3, 0]];
    let before: Vec<f64> = tris.iter().map(|t| signed_area(&pos, t)).collect();
    assert!(before.iter().all(|&a| a > 0.0));
    relax(&tris, &mut pos, 4, &[]);
    for (t, b) in tris.iter().zip(before) {
        let a = signed_area(&pos, t);
        assert!(a > 0.0 && a >= MIN_AREA_RATIO.powi(RELAX_PASSES as i32) * b, "{a} from {b}");
    }
}

#[test]
fn a_seam_vertex_moves_with_both_sides() {
    // A strip cut along x = 0 (= x = 2): the seam vertex at height 0.5 is point 4 on the left
    // edge and point 5 on the right, off its balanced position in y.
    let pos0 = vec![
        DVec2::new(0.0, 0.0),
        DVec2::new(2.0, 0.0),
        DVec2::new(2.0, 1.0),
        DVec2::new(0.0, 1.0),
        DVec2::new(0.0, 0.8),
        DVec2::new(2.0, 0.8),
        DVec2::new(1.0, 0.5),
    ];
    let tris = vec![[0, 6, 4], [4, 6, 3], [0, 1, 6], [6, 1, 5], [6, 5, 2], [6, 2, 3]];
    let mut pos = pos0.clone();
    let twins = [Twin { a: 4, b: 5, offset: DVec2::new(2.0, 0.0) }];
    relax(&tris, &mut pos, 6, &twins);
    assert!((pos[5] - pos[4] - DVec2::new(2.0, 0.0)).length() < 1e-12);
    assert!(pos[4].y < 0.75, "the seam vertex moved towards its balanced height: {:?}", pos[4]);
    assert_eq!(&pos[..4], &pos0[..4]);
}
