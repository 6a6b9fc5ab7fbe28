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
