use super::*;
use crate::geom::DVec3;
use crate::topology::cycles::find_patches;
use crate::topology::cycles::tests::{circle, graph};

fn radial(p: DVec3) -> DVec3 {
    DVec3::new(p.x, p.y, 0.0)
}

fn boundary(mut c: crate::network::Curve) -> crate::network::Curve {
    c.boundary = true;
    c
}

/// The unit square, counter-clockwise about +z, normals +z: the conormal points into the
/// square. Along a constant direction it cancels out (bottom and top edges); towards the
/// centroid, seen from the corners, it is cos 45° along every edge.
#[test]
fn conormal_scores_of_the_unit_square() {
    let p = [DVec3::ZERO, DVec3::X, DVec3::new(1.0, 1.0, 0.0), DVec3::Y];
    let n = [DVec3::Z; 4];
    assert!(conormal_score(&p, &n, |_| DVec3::Y).abs() < 1e-15);
    let c = DVec3::new(0.5, 0.5, 0.0);
    let s = conormal_score(&p, &n, |q| c - q);
    assert!((s - std::f64::consts::FRAC_1_SQRT_2).abs() < 1e-15, "{s}");
}

#[test]
fn two_facing_circles_bound_a_tube() {
    let (g, splines) = graph(vec![boundary(circle(1.0, 0.0, 48, radial)), boundary(circle(1.0, 1.0, 48, radial))]);
    let patches = find_patches(&g, &splines).unwrap();
    let [Patch::Tube([a, b])] = &patches[..] else { panic!("{patches:?}") };
    // Each loop is traversed with its conormal towards the other loop.
    for (hs, towards) in [(a, DVec3::Z), (b, -DVec3::Z)] {
        let (p, n) = loop_samples(&g, hs);
        assert!(conormal_score(&p, &n, |_| towards) > 0.9, "{hs:?}");
    }
}

/// Issue 29: a tube whose top rim's normals point inward (the bottom's outward) winds both
/// rims the same way; before, it surfaced silently into two cones through each other. Now it
/// is an error naming the rim to flip. Both rims inward is a tube that faces inward.
#[test]
fn rims_with_normals_to_opposite_sides_are_an_error_naming_the_curve() {
    let inward = |p: DVec3| -radial(p);
    let (g, splines) = graph(vec![boundary(circle(1.0, 0.0, 48, radial)), boundary(circle(1.0, 1.0, 48, inward))]);
    let e = find_patches(&g, &splines).unwrap_err();
    assert!(e.to_string().contains("Flip the normals of curve 1"), "{e}");
    assert_eq!(e.at().curve, Some(1));
    // With normals tilted 60° out of the plane, one rim flipped: never a tube. Where both
    // loops' normals lean to one side they are two caps (a disk each); else the error.
    let tilt = |s: f64| move |p: DVec3| (radial(p).normalize() * 0.5 + DVec3::Z * s * 0.866).normalize();
    for (a, b) in [(1.0, -1.0), (1.0, 1.0), (-1.0, -1.0), (-1.0, 1.0)] {
        let flipped = move |p: DVec3| -tilt(b)(p);
        let (g, splines) =
            graph(vec![boundary(circle(1.0, 0.0, 48, tilt(a))), boundary(circle(1.0, 1.0, 48, flipped))]);
        match find_patches(&g, &splines) {
            Ok(patches) => assert!(patches.iter().all(|p| matches!(p, Patch::Disk(_))), "tilts {a} {b}: {patches:?}"),
            Err(e) => assert!(e.to_string().contains("Flip the normals of curve 1"), "tilts {a} {b}: {e}"),
        }
    }
    let (g, splines) = graph(vec![boundary(circle(1.0, 0.0, 48, inward)), boundary(circle(1.0, 1.0, 48, inward))]);
    let patches = find_patches(&g, &splines).unwrap();
    assert!(matches!(&patches[..], [Patch::Tube(_)]), "{patches:?}");
}

/// Side by side in one plane, two circles do not face each other: two disks. With normals
/// leaning out and up (the rim of a dome), each disk lies inside its circle, counter-clockwise
/// about +z.
#[test]
fn circles_that_do_not_face_each_other_bound_disks() {
    let dome = |c: DVec3| move |p: DVec3| (p - c) * DVec3::new(1.0, 1.0, 0.0) + DVec3::Z;
    let shifted = |x: f64| {
        let mut c = boundary(circle(1.0, 0.0, 48, |_| DVec3::Z));
        let centre = DVec3::new(x, 0.0, 0.0);
        for (p, n) in c.points.iter_mut().zip(c.normals.iter_mut()) {
            *p += centre;
            *n = dome(centre)(*p);
        }
        c
    };
    let (g, splines) = graph(vec![shifted(0.0), shifted(3.0)]);
    let patches = find_patches(&g, &splines).unwrap();
    assert_eq!(patches.len(), 2);
    for p in &patches {
        let Patch::Disk(hs) = p else { panic!("{patches:?}") };
        let (points, _) = loop_samples(&g, hs);
        assert!(polygon_vector_area(&points).z > 3.0, "{hs:?} runs clockwise");
    }
}

/// A lone loop whose normals are tangent to it: neither its conormal nor its normals tell the
/// inside.
#[test]
fn a_loop_with_tangent_normals_has_no_side() {
    let c = circle(1.0, 0.0, 32, |p| DVec3::new(-p.y, p.x, 0.0));
    let l = Lone {
        faces: [Vec::new(), Vec::new()],
        centroid: DVec3::ZERO,
        axis: DVec3::Z,
        points: c.points,
        normals: c.normals,
        curve: (0, "curve 0".into()),
    };
    let Err(e) = lone_disk(&l) else { panic!("accepted") };
    assert!(e.to_string().starts_with("cannot tell on which side of the boundary loop through (1"), "{e}");
}
