use super::*;
use crate::sampling::tests::{raw, traced, unit_square};

fn square() -> Mesh {
    let (p, f) = unit_square();
    Mesh::repaired(&p, &f, 1e-3, None).unwrap().0
}

#[test]
fn the_boundary_of_a_square_is_one_loop_with_the_section_ends_inserted_in_order() {
    let mesh = square();
    let mut ends: HashMap<(u32, u32), Vec<Raw>> = HashMap::new();
    // Two ends on the bottom edge (given out of order), one on the left edge.
    ends.insert((0, 1), vec![raw(0.7, 0.0, false), raw(0.2, 0.0, false)]);
    ends.insert((0, 3), vec![raw(0.0, 0.5, false)]);
    let mut crossings = 10;
    let loops = trace_boundary(&mesh, &ends, &mut crossings);
    assert_eq!(crossings, 13);
    assert_eq!(loops.len(), 1);
    let l = &loops[0];
    assert!(l.closed && l.boundary && l.plane.is_none() && l.name == "boundary #0");
    // Counter-clockwise (the surface on the left), from the smallest vertex.
    let xy: Vec<(f64, f64, bool)> = l.samples.iter().map(|r| (r.p.x, r.p.y, r.node)).collect();
    assert_eq!(
        xy,
        vec![
            (0.0, 0.0, false),
            (0.2, 0.0, true),
            (0.7, 0.0, true),
            (1.0, 0.0, false),
            (1.0, 1.0, false),
            (0.0, 1.0, false),
            (0.0, 0.5, true),
        ]
    );
}

#[test]
fn a_closed_mesh_has_no_boundary_loop_and_two_holes_give_two() {
    let (p, f) = crate::sampling::tests::unit_cube();
    let (mesh, _) = Mesh::repaired(&p, &f, 1e-3, None).unwrap();
    assert!(trace_boundary(&mesh, &HashMap::new(), &mut 0).is_empty());
    // The cube without its top and bottom: a tube with two boundary squares.
    let tube: Vec<[u32; 3]> =
        f.iter().copied().filter(|t| t.iter().any(|&v| v < 4) && t.iter().any(|&v| v >= 4)).collect();
    assert_eq!(tube.len(), 8);
    let (mesh, _) = Mesh::repaired(&p, &tube, 1e-3, None).unwrap();
    let loops = trace_boundary(&mesh, &HashMap::new(), &mut 0);
    assert_eq!(loops.len(), 2);
    for l in &loops {
        let z = l.samples[0].p.z;
        assert!(l.samples.len() == 4 && l.samples.iter().all(|r| r.p.z == z));
    }
}

#[test]
fn section_ends_are_marked_as_nodes_only_when_asked() {
    let mut t = vec![traced(vec![raw(0.0, 0.0, false), raw(1.0, 0.0, false), raw(2.0, 0.0, false)], false)];
    t.push(traced(vec![raw(0.0, 1.0, false), raw(1.0, 1.0, false), raw(1.0, 2.0, false)], true));
    mark_ends(&mut t, false);
    assert!(t.iter().all(|t| t.samples.iter().all(|r| !r.node)));
    mark_ends(&mut t, true);
    assert_eq!(t[0].samples.iter().map(|r| r.node).collect::<Vec<_>>(), vec![true, false, true]);
    assert!(t[1].samples.iter().all(|r| !r.node), "a closed loop has no ends");
}

#[test]
fn an_end_that_runs_along_the_boundary_is_cut_back_to_where_it_leaves_it() {
    let mesh = square();
    let trimmer = Trimmer::new(&mesh, 0.05);
    // From (0.1, 0) on the bottom edge along y = 0.01, then up into the square.
    let along = vec![
        raw(0.1, 0.0, false),
        raw(0.2, 0.01, false),
        raw(0.3, 0.01, false),
        raw(0.4, 0.01, false),
        raw(0.5, 0.3, false),
        raw(0.5, 0.6, false),
    ];
    let mut s = along.clone();
    assert_eq!(trimmer.trim_start(&mesh, &mut s, (0, 1)), Some((0, 1)));
    // It now starts at the boundary point below its last sample in the band.
    let xy: Vec<(f64, f64)> = s.iter().map(|r| (r.p.x, r.p.y)).collect();
    assert_eq!(xy, vec![(0.4, 0.0), (0.5, 0.3), (0.5, 0.6)]);
    assert!(!s[0].node);
    // An end that leaves the boundary at once is kept as it is.
    let mut s = vec![raw(0.1, 0.0, false), raw(0.1, 0.3, false), raw(0.1, 0.6, false)];
    let before: Vec<DVec3> = s.iter().map(|r| r.p).collect();
    assert_eq!(trimmer.trim_start(&mesh, &mut s, (0, 1)), None);
    assert_eq!(s.iter().map(|r| r.p).collect::<Vec<_>>(), before);
    // A section within the band all along is emptied.
    let mut s = along[..4].to_vec();
    assert_eq!(trimmer.trim_start(&mesh, &mut s, (0, 1)), None);
    assert!(s.is_empty());
}
