use super::*;
use crate::geom::Aabb;
use crate::sampling::mesh::Mesh;
use crate::sampling::tests::unit_cube;
use crate::sampling::{SampleOptions, Scales};

#[test]
fn a_plane_goes_to_the_middle_of_the_widest_gap_between_vertex_levels() {
    let levels = [0.0, 0.1, 0.5, 1.0];
    // Window [0, 1]: gaps 0.1, 0.4 and 0.5; the widest is 0.5..1.
    assert_eq!(plane_level(&levels, 0.5, 0.5), 0.75);
    // Window [0.2, 0.4]: no vertex level inside, one gap, its middle is the nominal level.
    assert!((plane_level(&levels, 0.3, 0.1) - 0.3).abs() < 1e-15);
    // Two equal gaps (0..1 and 1..2 in the window [0, 2.4]): the one nearer the nominal level.
    assert_eq!(plane_level(&[0.0, 1.0, 2.0], 1.2, 1.2), 1.5);
}

#[test]
fn the_section_directions_are_the_axes_turned_about_1_2_3() {
    assert_eq!(section_directions(0.0), [DVec3::X, DVec3::Y, DVec3::Z]);
    let d = section_directions(20.0);
    let axis = DVec3::new(1.0, 2.0, 3.0).normalize();
    for (k, e) in [DVec3::X, DVec3::Y, DVec3::Z].into_iter().enumerate() {
        assert!((d[k].length() - 1.0).abs() < 1e-12);
        // Turned about the axis: the same angle to it, 20° about it.
        assert!((d[k].dot(axis) - e.dot(axis)).abs() < 1e-12);
        let (u, v) = (e - axis * e.dot(axis), d[k] - axis * d[k].dot(axis));
        assert!((u.angle_between(v).to_degrees() - 20.0).abs() < 1e-9);
    }
    assert!(d[0].dot(d[1]).abs() < 1e-12 && d[0].cross(d[1]).dot(d[2]) > 0.999);
}

#[test]
fn planes_split_the_extent_into_equal_slabs() {
    let (p, _) = unit_cube();
    let planes = Planes::new(&p, [2, 0, 1], 0.0, 3f64.sqrt());
    // The cube's vertex levels are 0 and 1: nothing to avoid near the slab middles.
    let expected = [(0, 0.25), (0, 0.75), (2, 0.5)];
    assert_eq!(planes.len(), 3);
    for (got, want) in planes.planes.iter().zip(expected) {
        assert!(got.0 == want.0 && (got.1 - want.1).abs() < 1e-15, "{:?}", planes.planes);
    }
    assert_eq!(planes.nominal, vec![0.25, 0.75, 0.5]);
    let mut moved = Planes::new(&p, [2, 0, 1], 0.0, 3f64.sqrt());
    moved.move_planes(vec![1], &mut Rng::new(1));
    assert_eq!(moved.planes[0], planes.planes[0]);
    assert!(moved.planes[1].0 == 0 && moved.planes[1].1 != planes.planes[1].1, "{:?}", moved.planes);
    assert!((moved.planes[1].1 - 0.75).abs() <= 0.45 * 0.5 + 0.03 * 0.5, "{:?}", moved.planes);
}

#[test]
fn planes_without_bad_crossings_stay_where_they_are() {
    let (p, f) = unit_cube();
    let (mesh, _) = Mesh::repaired(&p, &f, 1e-3, None).unwrap();
    let opts = SampleOptions { spacing: Some(0.05), ..Default::default() };
    let scales = Scales::new(Aabb::of(p.iter().copied()), &opts).unwrap();
    // Sections x = 0.3 and y = 0.6: loops around the cube that cross at right angles on the
    // bottom and the top, at (0.3, 0.6, 0) and (0.3, 0.6, 1), and are 0.3 apart elsewhere.
    let mut planes = Planes {
        dirs: section_directions(0.0),
        planes: vec![(0, 0.3), (1, 0.6)],
        nominal: vec![0.3, 0.6],
        axis_levels: vec![vec![0.0, 1.0]; 3],
        slab_of: [1.0; 3],
    };
    let placed = place_planes(&mesh, &mut planes, true, &scales);
    assert_eq!(placed.unresolved, 0);
    assert_eq!(planes.planes, vec![(0, 0.3), (1, 0.6)]);
    assert_eq!(placed.crossings.count, 2);
    assert!(placed.crossings.shallow.is_empty());
    let mut at: Vec<DVec3> = placed.crossings.points[&(0, 1)].clone();
    at.sort_by(|a, b| a.z.total_cmp(&b.z));
    for (q, z) in at.iter().zip([0.0, 1.0]) {
        assert!(q.distance(DVec3::new(0.3, 0.6, z)) < 1e-12, "{q}");
    }
}
