use super::*;

#[test]
fn locate_finds_the_edge_and_parameter() {
    let arc = arc_lengths(&[0.0f64, 1.0, 1.0, 3.0], |a, b| (b - a).abs());
    assert_eq!(arc, vec![0.0, 1.0, 1.0, 3.0]);
    assert_eq!(locate(&arc, 0.5), (0, 0.5));
    // The zero-length edge 1–2 is skipped: length 2 lies halfway along edge 2.
    assert_eq!(locate(&arc, 2.0), (2, 0.5));
    assert_eq!(locate(&arc, 1.0), (2, 0.0));
    assert_eq!(locate(&arc, 3.0), (2, 1.0));
    // Outside the polyline: clamped to its ends.
    assert_eq!(locate(&arc, -1.0), (0, 0.0));
    assert_eq!(locate(&arc, 7.0), (2, 1.0));
}
