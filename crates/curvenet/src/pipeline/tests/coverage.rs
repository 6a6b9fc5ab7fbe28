use super::*;

/// A square of curve vertices 0..4 around a free vertex 4 at height `h`, as one patch.
fn pyramid(h: f64) -> Vec<f64> {
    let positions = vec![
        DVec3::new(0.0, 0.0, 0.0),
        DVec3::new(1.0, 0.0, 0.0),
        DVec3::new(1.0, 1.0, 0.0),
        DVec3::new(0.0, 1.0, 0.0),
        DVec3::new(0.5, 0.5, h),
    ];
    let faces = vec![[0, 1, 4], [1, 2, 4], [2, 3, 4], [3, 0, 4]];
    reach_of(&positions, &faces, &[0; 4], 4)
}

#[test]
fn reach_is_the_distance_outside_the_curves_box_over_its_diagonal() {
    assert_eq!(pyramid(0.0), vec![0.0]);
    // The box of the square is flat; a dome of height 0.5 reaches 0.5 / √2.
    assert!((pyramid(0.5)[0] - 0.5 / 2f64.sqrt()).abs() < 1e-12);
    assert!((pyramid(-3.0)[0] - 3.0 / 2f64.sqrt()).abs() < 1e-12);
}

#[test]
fn a_dome_stays_a_spike_runs_away() {
    assert!(pyramid(0.5)[0] <= MAX_REACH);
    assert!(pyramid(2.0)[0] > MAX_REACH);
}

/// An octahedron of curve vertices: closed, no open border; one face taken out, a hole — one
/// loop, its three edges long, centred on the face; the same border on a boundary curve, none.
#[test]
fn open_borders_off_the_boundary_curves_are_named_once_per_loop() {
    let positions = vec![DVec3::X, DVec3::Y, -DVec3::X, -DVec3::Y, DVec3::Z, -DVec3::Z];
    let mut faces = vec![[0, 1, 4], [1, 2, 4], [2, 3, 4], [3, 0, 4], [1, 0, 5], [2, 1, 5], [3, 2, 5], [0, 3, 5]];
    let mut mesh =
        Mesh { positions, faces: faces.clone(), num_curve: 6, on_boundary: vec![false; 6], ..Default::default() };
    assert_eq!(check_open_borders(&mesh).0, 0);
    assert!(check_open_borders(&mesh).1.is_none());
    faces.remove(0);
    mesh.faces = faces;
    assert_eq!(check_open_borders(&mesh).0, 1);
    let w = check_open_borders(&mesh).1.expect("a hole").message;
    let side = 2f64.sqrt();
    assert!(w.contains("open along 1 border loop(s)"), "{w}");
    assert!(w.contains(&format!("({:.3e} long in all", 3.0 * side)), "{w}");
    // The centre of the face's edges' midpoints: (1/3, 1/3, 1/3).
    assert!(w.contains(&format!("near {}", crate::geom::fmt_point(DVec3::splat(1.0 / 3.0)))), "{w}");
    mesh.on_boundary = vec![true, true, false, false, true, false];
    assert_eq!(check_open_borders(&mesh), (0, None));
    // Only free vertices off the curves: their edges are inside patches, never a border.
    mesh.on_boundary = vec![false; 6];
    mesh.num_curve = 0;
    assert_eq!(check_open_borders(&mesh), (0, None));
}
