use super::*;
use crate::error::Error;

fn square(side: f64) -> Vec<DVec2> {
    vec![DVec2::new(0.0, 0.0), DVec2::new(side, 0.0), DVec2::new(side, side), DVec2::new(0.0, side)]
}

fn curve_map(n: u32) -> Vec<VRef> {
    (0..n).map(VRef::Curve).collect()
}

fn no_name() -> String {
    "test patch".into()
}

#[test]
fn the_unit_square_is_covered_by_counter_clockwise_triangles() {
    let (tris, pos, map) = triangulate(square(1.0), curve_map(4), 0.1, &no_name).unwrap();
    // The border first, unchanged; then the 85 lattice points (tests/lattice.rs) as new
    // vertices 0..85.
    assert_eq!(&pos[..4], &square(1.0)[..]);
    assert_eq!(&map[..4], &curve_map(4)[..]);
    assert_eq!(pos.len(), map.len());
    assert_eq!(&map[4..89], &(0..85).map(VRef::New).collect::<Vec<_>>()[..]);
    let mut area = 0.0;
    for t in &tris {
        let [a, b, c] = t.map(|i| pos[i]);
        let twice = (b - a).perp_dot(c - a);
        assert!(twice > 0.0, "{t:?} is clockwise or flat");
        area += 0.5 * twice;
        assert!(t.iter().all(|&i| map[i] != VRef::New(u32::MAX)), "{t:?} uses an unnumbered vertex");
    }
    assert!((area - 1.0).abs() < 1e-12, "area {area}");
}

#[test]
fn a_clockwise_border_is_a_topology_error() {
    let mut cw = square(1.0);
    cw.reverse();
    let Err(e) = triangulate(cw, curve_map(4), 0.1, &no_name) else { panic!("accepted") };
    assert!(matches!(e, Error::Topology { .. }), "{e}");
    assert!(e.to_string().starts_with("test patch: the cycle runs clockwise"), "{e}");
}

#[test]
fn two_border_vertices_are_not_a_patch() {
    let Err(e) = triangulate(square(1.0)[..2].to_vec(), curve_map(2), 0.1, &no_name) else { panic!("accepted") };
    assert!(e.to_string().contains("at least 3 boundary vertices"), "{e}");
}

/// Border `[C0, N0, C1]` (n = 3), two lattice points, three refinement points (positions 5,
/// 6, 7) of which the triangles use 7 then 5: the lattice points become N1, N2, then 7 becomes
/// N3 and 5 N4; 6 is unused.
#[test]
fn new_vertices_are_numbered_lattice_first_then_by_first_use() {
    let map = vec![VRef::Curve(0), VRef::New(0), VRef::Curve(1)];
    let tris = [[0, 1, 7], [2, 3, 5]];
    let out = number_new_vertices(map, 3, 2, 3, &tris);
    use VRef::{Curve as C, New as N};
    assert_eq!(out, vec![C(0), N(0), C(1), N(1), N(2), N(4), N(u32::MAX), N(3)]);
}

#[test]
fn lifting_places_each_new_vertex_once_and_rejects_a_triangle_on_one_vertex() {
    let pos = [DVec2::new(0.0, 0.0), DVec2::new(1.0, 0.0), DVec2::new(0.0, 1.0), DVec2::new(0.0, 1.0)];
    // Positions 2 and 3 are the same new vertex (as on a tube's seam).
    let map = [VRef::Curve(7), VRef::Curve(8), VRef::New(0), VRef::New(0)];
    let lift = |q: DVec2| DVec3::new(q.x, q.y, 5.0);
    let part = lift_patch(vec![[0, 1, 2]], &pos, &map, lift, &no_name).unwrap();
    assert_eq!(part.new_positions, vec![DVec3::new(0.0, 1.0, 5.0)]);
    assert_eq!(part.triangles, vec![[VRef::Curve(7), VRef::Curve(8), VRef::New(0)]]);
    assert_eq!(part.planar, vec![[pos[0], pos[1], pos[2]]]);
    let Err(e) = lift_patch(vec![[0, 2, 3]], &pos, &map, lift, &no_name) else { panic!("accepted") };
    assert!(e.to_string().contains("too narrow for the spacing"), "{e}");
}
