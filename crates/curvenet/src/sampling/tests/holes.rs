use super::*;
use crate::sampling::tests::{raw, traced};

/// The boundary loop of the square `[x0, x0 + side]²` (counter-clockwise, samples every
/// `side / 4`), with node samples at `nodes` (indices).
fn square_loop(x0: f64, side: f64, nodes: &[usize]) -> Traced {
    let c = [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)];
    let mut samples = Vec::new();
    for k in 0..4 {
        let (a, b) = (c[k], c[(k + 1) % 4]);
        for j in 0..4 {
            let t = j as f64 / 4.0;
            samples.push(raw(x0 + side * (a.0 + t * (b.0 - a.0)), side * (a.1 + t * (b.1 - a.1)), false));
        }
    }
    for &k in nodes {
        samples[k].node = true;
    }
    Traced {
        plane: None,
        samples,
        closed: true,
        boundary: true,
        name: "boundary".into(),
        cut: false,
        right: Vec::new(),
    }
}

/// An open section through `pts` with nodes at `nodes`.
fn section(pts: &[(f64, f64)], nodes: &[usize]) -> Traced {
    let mut t = traced(pts.iter().map(|&(x, y)| raw(x, y, false)).collect(), false);
    for &k in nodes {
        t.samples[k].node = true;
    }
    t
}

fn scales() -> Scales {
    let opts = SampleOptions { spacing: Some(0.1), ..Default::default() };
    Scales::new(crate::geom::Aabb::of([DVec3::ZERO, DVec3::new(10.0, 10.0, 0.0)]), &opts).unwrap()
}

#[test]
fn a_slit_is_a_thin_loop_and_a_square_is_not() {
    let slit = [DVec3::ZERO, DVec3::X, DVec3::new(1.0, 0.01, 0.0), DVec3::new(0.0, 0.01, 0.0)];
    assert!(thin_loop(&slit, 0.05));
    assert!(!thin_loop(&slit, 0.005));
    let square = [DVec3::ZERO, DVec3::X, DVec3::new(1.0, 1.0, 0.0), DVec3::Y];
    assert!(!thin_loop(&square, 0.5));
}

#[test]
fn a_loop_reached_by_two_sections_is_kept_and_one_reached_by_one_is_covered() {
    // Loop A (side 1) reached by sections 0 and 1 (at its samples 2 and 6); loop B (at x = 5)
    // reached by section 2 only. All three end on crossings that the closed section 3 passes
    // through, at (0.5, 3) and (5.5, 3).
    let a = square_loop(0.0, 1.0, &[2, 6]);
    let b = square_loop(5.0, 1.0, &[2]);
    let s0 = section(&[(0.5, 0.0), (0.5, 1.5), (0.5, 3.0)], &[0, 2]);
    let s1 = section(&[(1.0, 0.5), (0.8, 1.5), (0.5, 3.0)], &[0, 2]);
    let s2 = section(&[(5.5, 0.0), (5.5, 1.5), (5.5, 2.5), (5.5, 3.0)], &[0, 1, 3]);
    let mut s3 = section(&[(0.0, 3.0), (0.5, 3.0), (5.5, 3.0), (6.0, 3.0), (6.0, 4.0), (0.0, 4.0)], &[1, 2]);
    s3.closed = true;
    let opts = SampleOptions::default();
    let mut report = SampleReport::default();
    let (pieces, kept) = cover_holes(vec![s0, s1, s2, s3], vec![a, b], &opts, &scales(), &mut report);
    assert_eq!((report.single_contact_holes, report.dropped_boundary_loops, report.small_holes), (1, 0, 0));
    assert_eq!(kept.len(), 1);
    assert_eq!(kept[0].0.samples[0].p, DVec3::ZERO, "loop A is kept");
    assert!(kept[0].1 .0.len() >= 40, "with its resampling");
    // Section 2 lost its support on loop B: cut back to its crossing at (5.5, 1.5), whose end
    // is not supported either, then to (5.5, 3), where nothing is left of it.
    assert_eq!(pieces.len(), 3);
    assert!(pieces.iter().all(|t| !t.samples.iter().any(|r| r.p.x == 5.5 && r.p.y < 3.0)));
    assert!(pieces.iter().all(|t| !t.cut));
}

#[test]
fn a_loop_that_no_section_reaches_is_dropped_and_a_tiny_hole_covered() {
    let far = square_loop(0.0, 1.0, &[]);
    let tiny = square_loop(5.0, 0.2, &[2, 6]);
    let mut report = SampleReport::default();
    let (pieces, kept) = cover_holes(Vec::new(), vec![far, tiny], &SampleOptions::default(), &scales(), &mut report);
    assert!(pieces.is_empty() && kept.is_empty());
    assert_eq!((report.dropped_boundary_loops, report.small_holes, report.single_contact_holes), (1, 1, 0));
}
