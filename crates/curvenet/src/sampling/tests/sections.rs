use super::*;
use crate::geom::Aabb;
use crate::sampling::planes::section_directions;
use crate::sampling::tests::{unit_cube, unit_square};

/// The scales of the unit cube with spacing 0.05 (`near` 0.012, `gap` 0.05).
fn scales(p: &[DVec3]) -> Scales {
    let opts = SampleOptions { spacing: Some(0.05), ..Default::default() };
    Scales::new(Aabb::of(p.iter().copied()), &opts).unwrap()
}

#[test]
fn a_plane_cuts_a_tetrahedron_along_a_triangle() {
    let p = [DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z];
    let f = [[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]];
    let (mesh, _) = Mesh::repaired(&p, &f, 1e-3, None).unwrap();
    let mut planes = Planes::new(&p, [1, 0, 0], 0.0, 1.0);
    assert!((planes.planes[0].1 - 0.5).abs() < 1e-15);
    planes.planes[0].1 = 0.5;
    let (cuts, cuts_of_face) = cut_faces(&mesh, &planes);
    // x = 0.5 separates vertex 1 from the others: the three faces around it are cut.
    assert_eq!(cuts.len(), 3);
    assert_eq!(cuts_of_face.iter().map(Vec::len).collect::<Vec<_>>(), vec![1, 1, 0, 1]);
    for c in &cuts {
        // The midpoints of the edges 1–0, 1–2 and 1–3.
        let mid = [DVec3::new(0.5, 0.0, 0.0), DVec3::new(0.5, 0.5, 0.0), DVec3::new(0.5, 0.0, 0.5)];
        assert!(c.ends.iter().all(|e| mid.contains(e)) && c.ends[0] != c.ends[1], "{:?}", c.ends);
        assert!(c.edges.iter().all(|e| e.0 == 1 || e.1 == 1));
    }
    let opts = SampleOptions { planes: [1, 0, 0], tilt: 0.0, ..Default::default() };
    let t = trace_sections(&mesh, &opts, &scales(&p));
    // One closed loop through the midpoints of the edges at vertex 1.
    assert_eq!(t.traced.len(), 1);
    let s = &t.traced[0];
    assert!(s.closed && s.name.starts_with("X=0.5"), "{}", s.name);
    let mut pts: Vec<DVec3> = s.samples.iter().map(|r| r.p).collect();
    pts.sort_by(|a, b| a.y.total_cmp(&b.y).then(a.z.total_cmp(&b.z)));
    let want = [DVec3::new(0.5, 0.0, 0.0), DVec3::new(0.5, 0.0, 0.5), DVec3::new(0.5, 0.5, 0.0)];
    assert!(pts.iter().zip(want).all(|(a, b)| a.distance(b) < 1e-12), "{pts:?}");
    assert!(s.samples.iter().all(|r| !r.node));
    assert_eq!((t.crossings, t.unresolved, t.trimmed), (0, 0, 0));
}

#[test]
fn a_plane_section_of_the_unit_cube_is_a_square_loop() {
    let (p, f) = unit_cube();
    let (mesh, _) = Mesh::repaired(&p, &f, 1e-3, None).unwrap();
    let opts = SampleOptions { planes: [1, 0, 0], tilt: 0.0, ..Default::default() };
    let t = trace_sections(&mesh, &opts, &scales(&p));
    assert_eq!(t.traced.len(), 1);
    let s = &t.traced[0];
    assert!(s.closed);
    // Four cube edges along x and the four face diagonals it crosses.
    assert_eq!(s.samples.len(), 8);
    for r in &s.samples {
        assert!((r.p.x - 0.5).abs() < 1e-12, "{}", r.p);
        let (y, z) = (r.p.y, r.p.z);
        assert!(y == 0.0 || y == 1.0 || z == 0.0 || z == 1.0, "{}", r.p);
        assert!(r.n.length() > 0.5 && r.n.x.abs() < 1e-12, "normal {} at {}", r.n, r.p);
    }
    // Consecutive samples are on the same face: at most one coordinate changes between 0 and 1.
    for k in 0..8 {
        let (a, b) = (s.samples[k].p, s.samples[(k + 1) % 8].p);
        assert!(a.distance(b) <= 0.5f64.sqrt() + 1e-12, "{a} {b}");
    }
}

#[test]
fn sections_of_a_square_end_on_the_boundary_and_cross() {
    let (p, f) = unit_square();
    let (mesh, _) = Mesh::repaired(&p, &f, 1e-3, None).unwrap();
    // Two planes of the first family, one of the second (through the middle, off the
    // diagonal where the others cross it), tilted: three chords, two crossings.
    let opts = SampleOptions { planes: [2, 1, 0], tilt: 10.0, ..Default::default() };
    let t = trace_sections(&mesh, &opts, &scales(&p));
    assert_eq!(t.traced.len(), 3);
    assert_eq!((t.crossings, t.unresolved), (2, 0));
    for s in &t.traced {
        assert!(!s.closed && s.samples.len() >= 3);
        // A chord: its samples on a line.
        let (a, b) = (s.samples[0].p, s.samples[s.samples.len() - 1].p);
        assert!(s.samples.iter().all(|r| (r.p - a).cross(b - a).length() < 1e-12));
        let nodes = s.samples.iter().filter(|r| r.node).count();
        assert_eq!(nodes, if s.name.starts_with('X') { 1 } else { 2 }, "{}", s.name);
        assert!(!s.samples[0].node && !s.samples[s.samples.len() - 1].node);
    }
    // Both ends of each on boundary edges.
    assert_eq!(t.ends_on_boundary.values().map(Vec::len).sum::<usize>(), 6);
    for (e, ends) in &t.ends_on_boundary {
        assert!(mesh.is_boundary(*e));
        let (a, b) = (mesh.positions[e.0 as usize], mesh.positions[e.1 as usize]);
        for r in ends {
            assert!((r.p - a).cross(b - a).length() < 1e-12, "{} not on {a}–{b}", r.p);
        }
    }
}

#[test]
fn an_edge_point_interpolates_the_vertex_normals() {
    let (p, f) = unit_cube();
    let (mesh, _) = Mesh::repaired(&p, &f, 1e-3, None).unwrap();
    let dirs = section_directions(0.0);
    // Edge 0–1 along x, cut by x = 0.25.
    let (q, n) = edge_point(&mesh, &dirs, (0, 1), (0, 0.25));
    assert_eq!(q, DVec3::new(0.25, 0.0, 0.0));
    assert!(n.distance(mesh.normals[0].lerp(mesh.normals[1], 0.25)) < 1e-15);
    // A plane beyond the edge: clamped to its end.
    assert_eq!(edge_point(&mesh, &dirs, (0, 1), (0, 2.0)).0, DVec3::X);
}
