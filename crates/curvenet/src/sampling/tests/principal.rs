use super::*;
use crate::sampling::cross_field::CrossField;
use crate::sampling::streamlines::Pt;

/// The square `[0, 1]²` as two triangles.
fn square() -> Mesh {
    let p = vec![DVec3::ZERO, DVec3::X, DVec3::new(1.0, 1.0, 0.0), DVec3::Y];
    Mesh::repaired(&p, &[[0, 1, 2], [0, 2, 3]], 1e-4, None).unwrap().0
}

/// A curve through `pts`, all in face 0 of [`square`] (a polyline of one face per segment).
fn line(pts: &[(f64, f64)], closed: bool) -> Line {
    let pts: Vec<Pt> = pts.iter().map(|&(x, y)| Pt { p: DVec3::new(x, y, 0.0), n: DVec3::Z }).collect();
    let segs = pts.len() - usize::from(!closed);
    Line { pts, faces: vec![0; segs], closed, ends: [None, None] }
}

#[test]
fn two_curves_cross_in_a_face_at_the_point_on_both() {
    let mesh = square();
    let field = CrossField::new(&mesh, DVec3::X, 1.0);
    // Face 0 is (0,0), (1,0), (1,1): below the diagonal.
    let a = line(&[(0.1, 0.05), (0.9, 0.05), (0.95, 0.5)], false);
    let b = line(&[(0.3, 0.01), (0.3, 0.2)], false);
    let x = cross_lines(&mesh, &field.frames, &[a, b]);
    assert_eq!(x.count, 1);
    assert_eq!(x.inserts[0].len(), 1);
    let (seg, t, r) = x.inserts[0][0];
    assert!(seg == 0 && (t - 0.25).abs() < 1e-12 && r.node);
    assert!(r.p.distance(DVec3::new(0.3, 0.05, 0.0)) < 1e-12 && r.n.distance(DVec3::Z) < 1e-12);
    let (seg, w, rb) = x.inserts[1][0];
    assert!(seg == 0 && (w - 0.04 / 0.19).abs() < 1e-12 && rb.p == r.p);
    assert_eq!(x.points[&(0, 1)], vec![r.p]);
    assert!(x.spots.is_empty());
}

#[test]
fn a_curve_becomes_a_polyline_with_its_crossings_and_boundary_ends_as_nodes() {
    let mesh = square();
    let mut a = line(&[(0.2, 0.0), (0.6, 0.2), (0.9, 0.3)], false);
    a.ends = [Some((0, 1)), None];
    let inserts = vec![vec![
        (1, 0.5, Raw { p: DVec3::new(0.75, 0.25, 0.0), n: DVec3::Z, node: true }),
        (0, 0.5, Raw { p: DVec3::new(0.4, 0.1, 0.0), n: DVec3::Z, node: true }),
    ]];
    let mut x = LineCrossings { inserts, points: HashMap::new(), spots: Vec::new(), count: 2 };
    let (traced, cuts, ends) = polylines(&mesh, &[a], &mut x);
    assert_eq!(traced.len(), 1);
    let t = &traced[0];
    assert_eq!(t.name, "principal #0");
    let got: Vec<(f64, bool)> = t.samples.iter().map(|r| (r.p.x, r.node)).collect();
    assert_eq!(got, vec![(0.2, true), (0.4, true), (0.6, false), (0.75, true), (0.9, false)]);
    assert_eq!(cuts.len(), 2);
    assert_eq!(ends[&(0, 1)].len(), 1);
    assert_eq!(x.points[&(0, 1)], vec![DVec3::new(0.2, 0.0, 0.0)]);
    // The first segment meets the boundary edge y = 0 at about 27°: a fair angle.
    assert!(x.spots.is_empty());
}

#[test]
fn streamlines_on_a_flat_square_follow_the_projected_axis_and_cross_at_right_angles() {
    let mesh = square();
    // The field follows the third section direction (z turned by 20°) projected on the square:
    // the same direction in both faces, so the curves are straight chords, in two directions
    // at right angles.
    let opts = SampleOptions { planes: [4, 4, 4], tilt: 20.0, ..Default::default() };
    let scales = Scales::new(crate::geom::Aabb::of(mesh.positions.iter().copied()), &opts).unwrap();
    let t = trace_principal(&mesh, &opts, &scales);
    assert!(t.traced.len() >= 4, "{}", t.traced.len());
    assert!(t.crossings >= 4, "{}", t.crossings);
    let axis = section_directions(20.0)[2];
    let axis = DVec3::new(axis.x, axis.y, 0.0).normalize();
    for c in &t.traced {
        assert!(!c.closed);
        let (a, b) = (c.samples[0].p, c.samples[c.samples.len() - 1].p);
        assert!(c.samples.iter().all(|r| (r.p - a).cross(b - a).length() < 1e-9), "{}", c.name);
        let cos = (b - a).normalize().dot(axis).abs();
        assert!(!(1e-9..=1.0 - 1e-9).contains(&cos), "{}: cos {cos}", c.name);
        assert!(c.samples.iter().all(|r| r.p.z == 0.0));
    }
}
