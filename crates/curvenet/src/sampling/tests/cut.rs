use super::*;
use crate::sampling::tests::{raw, traced};

/// Issue 5: a section in a bad spot loses only the stretch around it, up to the nearest node
/// (crossing or boundary end) on either side, which end the pieces left.
#[test]
fn a_section_is_cut_at_a_bad_spot_between_the_nodes_around_it() {
    // Samples at x = 0..10; nodes at 0 (boundary end), 3, 6 and 10 (boundary end).
    let samples: Vec<Raw> = (0..=10)
        .map(|i| Raw { p: DVec3::new(i as f64, 0.0, 0.0), n: DVec3::Z, node: matches!(i, 0 | 3 | 6 | 10) })
        .collect();
    let t = |closed| traced(samples.clone(), closed);
    let xs = |t: &Traced| t.samples.iter().map(|r| r.p.x).collect::<Vec<_>>();
    // A spot near x = 4.4 (within 0.5 of sample 4 only): samples 4 and 5 go, the pieces end at
    // the crossings at 3 and 6.
    let pieces = cut_at_spots(t(false), &[DVec3::new(4.4, 0.1, 0.0)], 0.5);
    assert_eq!(
        pieces.iter().map(xs).collect::<Vec<_>>(),
        vec![vec![0.0, 1.0, 2.0, 3.0], vec![6.0, 7.0, 8.0, 9.0, 10.0]]
    );
    assert!(pieces.iter().all(|p| p.cut && !p.closed && p.samples[0].node && p.samples[p.samples.len() - 1].node));
    // A spot on the crossing at 6 itself: it goes too, and with it the stretch up to the end
    // at 10 (a single sample is no piece); the piece left ends at 3.
    let pieces = cut_at_spots(t(false), &[DVec3::new(6.0, 0.0, 0.0)], 0.5);
    assert_eq!(pieces.iter().map(xs).collect::<Vec<_>>(), vec![vec![0.0, 1.0, 2.0, 3.0]]);
    // An end cut back (gap 0): up to the first crossing.
    let pieces = cut_at_spots(t(false), &[DVec3::new(10.0, 0.0, 0.0)], 0.0);
    assert_eq!(pieces.iter().map(xs).collect::<Vec<_>>(), vec![vec![0.0, 1.0, 2.0, 3.0, 4.0, 5.0, 6.0]]);
    // A closed section opens at the spot: one piece from 6 round to 3.
    let pieces = cut_at_spots(t(true), &[DVec3::new(4.4, 0.1, 0.0)], 0.5);
    assert_eq!(pieces.iter().map(xs).collect::<Vec<_>>(), vec![vec![6.0, 7.0, 8.0, 9.0, 10.0, 0.0, 1.0, 2.0, 3.0]]);
}

/// Samples every 0.1 along the polyline through `corners` (in the plane z = 0).
fn polyline(corners: &[(f64, f64)]) -> Vec<Raw> {
    let mut out = vec![raw(corners[0].0, corners[0].1, false)];
    for w in corners.windows(2) {
        let (a, b) = (DVec3::new(w[0].0, w[0].1, 0.0), DVec3::new(w[1].0, w[1].1, 0.0));
        let k = (a.distance(b) / 0.1).round() as usize;
        for j in 1..=k {
            let q = a.lerp(b, j as f64 / k as f64);
            out.push(raw(q.x, q.y, false));
        }
    }
    out
}

#[test]
fn a_section_that_turns_back_by_more_than_90_degrees_is_cut_there() {
    // Along x to (2, 0), then back at 122° to (1.5, 0.8): one sharp turn, at the corner.
    let back = polyline(&[(0.0, 0.0), (2.0, 0.0), (1.5, 0.8)]);
    let at = sharp_turns(&back, false, 0.25, SHARP_TURN_DEG);
    assert_eq!(at.len(), 1);
    assert!(at[0].distance(DVec3::new(2.0, 0.0, 0.0)) < 1e-12, "{}", at[0]);
    // A 45° bend is no sharp turn.
    let bend = polyline(&[(0.0, 0.0), (2.0, 0.0), (3.0, 1.0)]);
    assert!(sharp_turns(&bend, false, 0.25, SHARP_TURN_DEG).is_empty());
    // A closed square turns by 90° at each corner: not more.
    let square = polyline(&[(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0), (0.0, 0.0)]);
    let square = &square[..square.len() - 1];
    assert!(sharp_turns(square, true, 0.25, SHARP_TURN_DEG).is_empty());
    assert_eq!(sharp_turns(square, true, 0.25, 80.0).len(), 4);
}

#[test]
fn bad_spots_cut_sections_and_sections_without_crossings_are_dropped() {
    let opts = crate::sampling::SampleOptions { spacing: Some(0.1), ..Default::default() };
    let scales = Scales::new(crate::geom::Aabb::of([DVec3::ZERO, DVec3::new(10.0, 10.0, 0.0)]), &opts).unwrap();
    assert_eq!(scales.gap, 0.1);
    // A sharp turn at (2, 0) (sample 20) between crossings at (1, 0) (sample 10) and on the way
    // back (sample 24), another crossing further on (sample 27).
    let mut back = polyline(&[(0.0, 0.0), (2.0, 0.0), (1.5, 0.8)]);
    for k in [10, 24, 27] {
        back[k].node = true;
    }
    let after = back[24].p;
    // A straight section with a crossing, and one with none.
    let mut straight = polyline(&[(0.0, 5.0), (3.0, 5.0)]);
    straight[15].node = true;
    let lonely = polyline(&[(0.0, 8.0), (3.0, 8.0)]);
    let mut report = SampleReport::default();
    let sections = vec![traced(back, false), traced(straight, false), traced(lonely, false)];
    let pieces = cut_bad_spots(sections, &[], &scales, &mut report);
    // The turn loses the stretch between its crossings: pieces (0, 0)–(1, 0), which then
    // meets nothing (its only node an end), and sample 24 to the end, which keeps crossing 27.
    assert_eq!((report.sharp_turns, report.cut_bad, report.dropped_sections), (1, 1, 2));
    let names: Vec<&str> = pieces.iter().map(|t| t.name.as_str()).collect();
    assert_eq!(names, vec!["s.2", "s"]);
    assert!(pieces[0].cut && pieces[0].samples[0].node && pieces[0].samples[0].p == after);
    assert_eq!(pieces[0].samples.len(), 6);
    // A bad spot of plane 0 left after the moves, on the straight section (plane 0 too).
    let straight = traced(polyline(&[(0.0, 5.0), (3.0, 5.0)]), false);
    let mut report = SampleReport::default();
    let pieces = cut_bad_spots(vec![straight], &[(0, DVec3::new(1.5, 5.05, 0.0))], &scales, &mut report);
    assert_eq!((report.cut_bad, report.dropped_sections), (1, 0));
    assert_eq!(pieces.len(), 0, "no crossing on either side: both pieces fall off the ends");
}

#[test]
fn crowded_ends_cut_the_shorter_section() {
    let long = traced(polyline(&[(0.0, 0.0), (3.0, 0.0)]), false);
    let short = traced(polyline(&[(3.05, 0.0), (3.05, 1.0)]), false);
    let far = traced(polyline(&[(0.0, 5.0), (1.0, 5.0)]), false);
    let mut spots = vec![Vec::new(); 3];
    crowded_ends(&[long, short, far], 0.1, &mut spots);
    assert_eq!(spots, vec![vec![], vec![DVec3::new(3.05, 0.0, 0.0)], vec![]]);
}

#[test]
fn a_section_meets_another_curve_at_an_inner_node() {
    let mut t = traced(polyline(&[(0.0, 0.0), (1.0, 0.0)]), false);
    assert!(!meets_another(&t));
    t.samples[0].node = true;
    let last = t.samples.len() - 1;
    t.samples[last].node = true;
    assert!(!meets_another(&t), "ends on the boundary only");
    t.cut = true;
    assert!(meets_another(&t), "a cut piece between two crossings");
    t.cut = false;
    t.samples[3].node = true;
    assert!(meets_another(&t));
    let mut c = traced(polyline(&[(0.0, 0.0), (1.0, 0.0), (1.0, 1.0)]), true);
    assert!(!meets_another(&c));
    c.samples[0].node = true;
    assert!(meets_another(&c));
}
