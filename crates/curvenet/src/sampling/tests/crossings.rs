use super::*;
use crate::geom::Aabb;
use crate::sampling::planes::section_directions;
use crate::sampling::sections::cut_faces;
use crate::sampling::{SampleOptions, Scales};

/// The one-triangle mesh through `a`, `b`, `c`.
fn triangle(a: DVec3, b: DVec3, c: DVec3) -> Mesh {
    Mesh::repaired(&[a, b, c], &[[0, 1, 2]], 1e-6, None).unwrap().0
}

/// Planes `x = lx` and `y = ly`.
fn planes_xy(lx: f64, ly: f64) -> Planes {
    let mut planes = Planes::new(&[DVec3::ZERO, DVec3::ONE], [1, 1, 0], 0.0, 1.0);
    assert_eq!(planes.dirs, section_directions(0.0));
    planes.planes = vec![(0, lx), (1, ly)];
    planes
}

#[test]
fn two_sections_cross_on_a_triangle_at_its_point_on_both_planes() {
    let mesh = triangle(DVec3::ZERO, DVec3::X, DVec3::Y);
    let planes = planes_xy(0.25, 0.25);
    let (cuts, cuts_of_face) = cut_faces(&mesh, &planes);
    assert_eq!(cuts.len(), 2);
    assert_eq!(cuts_of_face, vec![vec![0, 1]]);
    let x = cross_sections(&mesh, &planes, &cuts, &cuts_of_face);
    assert_eq!(x.count, 1);
    let (ta, a) = x.at[0][0];
    let (tb, b) = x.at[1][0];
    let p = DVec3::new(0.25, 0.25, 0.0);
    assert!(a.p.distance(p) < 1e-15 && a.node, "{a:?}");
    assert_eq!(a.p, b.p);
    // The normal of a flat triangle is its normal.
    assert!(a.n.distance(DVec3::Z) < 1e-12, "{:?}", a.n);
    // The parameters place the crossing on both cuts.
    assert!(cuts[0].ends[0].lerp(cuts[0].ends[1], ta).distance(p) < 1e-15);
    assert!(cuts[1].ends[0].lerp(cuts[1].ends[1], tb).distance(p) < 1e-15);
    assert_eq!(x.points[&(0, 1)], vec![a.p]);
    assert!(x.shallow.is_empty(), "a right angle is not shallow");
}

#[test]
fn sections_that_do_not_meet_inside_the_triangle_do_not_cross() {
    let mesh = triangle(DVec3::ZERO, DVec3::X, DVec3::Y);
    // x = 0.6 and y = 0.6 both cut the triangle, but meet at (0.6, 0.6), outside.
    let planes = planes_xy(0.6, 0.6);
    let (cuts, cuts_of_face) = cut_faces(&mesh, &planes);
    assert_eq!(cuts.len(), 2);
    let x = cross_sections(&mesh, &planes, &cuts, &cuts_of_face);
    assert_eq!(x.count, 0);
    assert!(x.at.iter().all(|a| a.is_empty()) && x.points.is_empty());
}

#[test]
fn a_shallow_crossing_is_a_bad_spot_of_the_second_plane() {
    // The plane x + y + z / 10 = 1: the cuts by x = 0.25 and y = 0.25 run nearly (anti)parallel
    // in it, and cross at (0.25, 0.25, 5).
    let mesh = triangle(DVec3::X, DVec3::Y, DVec3::new(0.0, 0.0, 10.0));
    let planes = planes_xy(0.25, 0.25);
    let (cuts, cuts_of_face) = cut_faces(&mesh, &planes);
    let x = cross_sections(&mesh, &planes, &cuts, &cuts_of_face);
    assert_eq!(x.count, 1);
    assert_eq!(x.shallow.len(), 1);
    assert_eq!(x.shallow[0].0, 1);
    assert!(x.shallow[0].1.distance(DVec3::new(0.25, 0.25, 5.0)) < 1e-12, "{}", x.shallow[0].1);
}

#[test]
fn a_section_end_on_the_boundary_at_a_shallow_angle_is_a_bad_spot() {
    // A long thin triangle: y = 0.05 runs at about 3° to its long edges.
    let mesh = triangle(DVec3::ZERO, DVec3::new(10.0, 0.0, 0.0), DVec3::new(10.0, 1.0, 0.0));
    let mut planes = planes_xy(5.0, 0.05);
    planes.planes.truncate(1);
    let opts = SampleOptions { spacing: Some(0.01), ..Default::default() };
    let scales = Scales::new(Aabb::of([DVec3::ZERO, DVec3::new(10.0, 1.0, 0.0)]), &opts).unwrap();
    // x = 5: across the triangle, its ends on the boundary at a fair angle.
    let (cuts, cuts_of_face) = cut_faces(&mesh, &planes);
    let mut x = cross_sections(&mesh, &planes, &cuts, &cuts_of_face);
    x.add_bad_spots(&mesh, &cuts, 1, true, &scales);
    assert!(x.shallow.is_empty(), "{:?}", x.shallow);
    assert_eq!(x.points[&(0, 1)].len(), 2);
    // y = 0.05: from the hypotenuse to the far edge at a shallow angle to the hypotenuse.
    planes.planes = vec![(1, 0.05)];
    let (cuts, cuts_of_face) = cut_faces(&mesh, &planes);
    let mut x = cross_sections(&mesh, &planes, &cuts, &cuts_of_face);
    x.add_bad_spots(&mesh, &cuts, 1, true, &scales);
    assert_eq!(x.shallow.len(), 1, "{:?}", x.shallow);
    assert!(x.shallow[0].0 == 0 && x.shallow[0].1.distance(DVec3::new(0.5, 0.05, 0.0)) < 1e-12);
    // Without the boundary, no end is checked.
    let mut x = cross_sections(&mesh, &planes, &cuts, &cuts_of_face);
    x.add_bad_spots(&mesh, &cuts, 1, false, &scales);
    assert!(x.shallow.is_empty());
}

#[test]
fn near_misses_away_from_crossings_move_the_plane_with_the_larger_index() {
    let cut = |plane, a: DVec3, b: DVec3| FaceCut { plane, edges: [(0, 1), (1, 2)], ends: [a, b] };
    // Plane 0 along y = 0, plane 2 along y = 0.01 (no crossing), plane 1 crosses plane 0.
    let cuts = [
        cut(0, DVec3::ZERO, DVec3::X),
        cut(2, DVec3::new(0.0, 0.01, 0.0), DVec3::new(1.0, 0.01, 0.0)),
        cut(1, DVec3::new(0.5, -1.0, 0.0), DVec3::new(0.5, 1.0, 0.0)),
    ];
    let mut points: CrossingPoints = HashMap::new();
    points.insert((0, 1), vec![DVec3::new(0.5, 0.0, 0.0)]);
    let out = near_misses(&cuts, &points, 0.02, 3);
    // 0–2 nearly touch (plane 2 moves); 0–1 and 1–2 meet at the crossing (0.5, 0): no miss
    // for 0–1; 1–2 meet at (0.5, 0.01), within 4 × 0.02 of no 1–2 crossing: a miss too.
    let mut planes: Vec<usize> = out.iter().map(|x| x.0).collect();
    planes.sort_unstable();
    assert_eq!(planes, vec![2, 2]);
    // Plane 2 as the boundary pseudo-plane (first_virtual 2): the other plane moves.
    let mut planes: Vec<usize> = near_misses(&cuts, &points, 0.02, 2).iter().map(|x| x.0).collect();
    planes.sort_unstable();
    assert_eq!(planes, vec![0, 1]);
}

#[test]
fn close_crossings_move_a_plane_they_do_not_share() {
    let mut points: CrossingPoints = HashMap::new();
    // Two crossings of planes 0 and 1 close together: plane 1 moves.
    points.insert((0, 1), vec![DVec3::ZERO, DVec3::new(0.05, 0.0, 0.0)]);
    let out = close_crossings(&points, 0.01, 0.1, 9);
    assert_eq!(out, vec![(1, DVec3::ZERO)]);
    // Three planes nearly through a point: of crossings 0–1 and 0–2, plane 2 (not shared)
    // moves.
    let mut points: CrossingPoints = HashMap::new();
    points.insert((0, 1), vec![DVec3::ZERO]);
    points.insert((0, 2), vec![DVec3::new(0.001, 0.0, 0.0)]);
    let out = close_crossings(&points, 0.01, 0.01, 9);
    assert_eq!(out.iter().map(|x| x.0).collect::<Vec<_>>(), vec![2]);
    // Far apart: nothing.
    points.insert((0, 2), vec![DVec3::new(1.0, 0.0, 0.0)]);
    assert!(close_crossings(&points, 0.01, 0.01, 9).is_empty());
}
