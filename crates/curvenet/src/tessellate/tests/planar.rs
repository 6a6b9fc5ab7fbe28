use super::*;

/// An L-shaped cycle in z = 0, counter-clockwise about +z: its corner at (1, 1) turns
/// right (−90°) on the surface. In its own plane the projection agrees; a projection that
/// shows that corner turning left (pushed out to (2, 2)) folds there.
#[test]
fn a_corner_turning_the_other_way_in_projection_is_a_fold() {
    let l = [(0.0, 0.0), (2.0, 0.0), (2.0, 1.0), (1.0, 1.0), (1.0, 2.0), (0.0, 2.0)];
    let p3: Vec<DVec3> = l.iter().map(|&(x, y)| DVec3::new(x, y, 0.0)).collect();
    let n3 = vec![DVec3::Z; 6];
    let inner = vec![true; 6];
    let same: Vec<DVec2> = l.iter().map(|&(x, y)| DVec2::new(x, y)).collect();
    assert_eq!(corner_turned(&p3, &n3, &inner, &same), None);
    let mut folded = same.clone();
    folded[3] = DVec2::new(2.0, 2.0);
    assert_eq!(corner_turned(&p3, &n3, &inner, &folded), Some(3));
    // At a node (not inner) the corner is not compared.
    let at_nodes = vec![true, true, true, false, true, true];
    assert_eq!(corner_turned(&p3, &n3, &at_nodes, &folded), None);
}
