use super::*;
use crate::sampling::tests::unit_cube;

/// The sharp edges along a polyline through `pts` (indices into the positions).
fn along(idx: &[u32]) -> Sharp {
    idx.windows(2).map(|w| edge_key(w[0], w[1])).collect()
}

/// The crease options of these tests: chains shorter than `min_len` smooth, near misses
/// within `gap` of a common vertex allowed, the chains along `refused` smooth.
fn cut(min_len: f64, gap: f64, refused: &[DVec3]) -> CreaseCut<'_> {
    CreaseCut { angle: 0.5, min_len, gap, refused, refused_within: 0.1 }
}

#[test]
fn the_cube_has_twelve_sharp_edges_chained_between_its_corners() {
    let (p, f) = unit_cube();
    let sharp = sharp_edges(&p, &f, 30f64.to_radians());
    assert_eq!(sharp.len(), 12, "the cube's edges, not the sides' diagonals");
    let all = chains(&sharp, |v| p[v as usize]);
    assert_eq!(all.len(), 12);
    assert!(all.iter().all(|(c, closed)| c.len() == 2 && !closed));
    // Above 90° nothing is sharp.
    assert!(sharp_edges(&p, &f, 100f64.to_radians()).is_empty());
    // Cut open, each corner has three copies, and the creases are kept whole.
    let (kept, smoothed) = kept_creases(&p, sharp.clone(), &cut(0.5, 0.1, &[]), 1e-3);
    assert_eq!((kept.len(), smoothed), (12, 0));
    let (mut q, mut g) = (p.clone(), f.clone());
    let (original, _) = cut_creases(&mut q, &mut g, kept);
    assert_eq!((q.len(), original.len()), (24, 24));
    assert!(original.iter().enumerate().all(|(v, &o)| q[v] == p[o as usize]));
    // Edges longer than the minimum length only.
    let (kept, smoothed) = kept_creases(&p, sharp, &cut(1.5, 0.1, &[]), 1e-3);
    assert_eq!((kept.len(), smoothed), (0, 12));
}

#[test]
fn of_two_chains_running_side_by_side_the_shorter_is_left_smooth() {
    // Chain A along y = 0 (x 0..4), chain B along y = 0.01 (x 1..3), chain C along y = 0.5.
    let mut p: Vec<DVec3> = (0..5).map(|i| DVec3::new(i as f64, 0.0, 0.0)).collect();
    p.extend((1..4).map(|i| DVec3::new(i as f64, 0.01, 0.0)));
    p.extend((0..5).map(|i| DVec3::new(i as f64, 0.5, 0.0)));
    let a = along(&[0, 1, 2, 3, 4]);
    let b = along(&[5, 6, 7]);
    let c = along(&[8, 9, 10, 11, 12]);
    let sharp: Sharp = a.iter().chain(&b).chain(&c).copied().collect();
    let (kept, smoothed) = kept_creases(&p, sharp.clone(), &cut(0.5, 0.1, &[]), 0.02);
    assert_eq!(smoothed, 1);
    assert_eq!(kept, a.iter().chain(&c).copied().collect::<Sharp>());
    // Farther apart than the near distance: all kept.
    let (kept, smoothed) = kept_creases(&p, sharp, &cut(0.5, 0.1, &[]), 0.005);
    assert_eq!((kept.len(), smoothed), (10, 0));
}

#[test]
fn chains_meeting_at_a_corner_are_no_near_miss() {
    // Two chains from a common end at 30° to each other: close only near the corner.
    let dir = DVec3::new(30f64.to_radians().cos(), 30f64.to_radians().sin(), 0.0);
    let mut p: Vec<DVec3> = (0..5).map(|i| DVec3::new(i as f64 * 0.1, 0.0, 0.0)).collect();
    p.extend((1..5).map(|i| dir * (i as f64 * 0.1)));
    let sharp: Sharp = along(&[0, 1, 2, 3, 4]).into_iter().chain(along(&[0, 5, 6, 7, 8])).collect();
    let (kept, smoothed) = kept_creases(&p, sharp, &cut(0.1, 0.05, &[]), 0.02);
    assert_eq!((kept.len(), smoothed), (8, 0));
}

#[test]
fn a_chain_along_a_refused_crease_is_left_smooth() {
    // Two parallel chains 1 apart; the samples of a crease curve `surface` refused lie along
    // the first (between its vertices, as a resampled curve's do).
    let mut p: Vec<DVec3> = (0..5).map(|i| DVec3::new(i as f64 * 0.2, 0.0, 0.0)).collect();
    p.extend((0..5).map(|i| DVec3::new(i as f64 * 0.2, 1.0, 0.0)));
    let a = along(&[0, 1, 2, 3, 4]);
    let b = along(&[5, 6, 7, 8, 9]);
    let sharp: Sharp = a.iter().chain(&b).copied().collect();
    let refused: Vec<DVec3> = (0..9).map(|i| DVec3::new(0.05 + i as f64 * 0.1, 0.01, 0.0)).collect();
    let (kept, smoothed) = kept_creases(&p, sharp.clone(), &cut(0.1, 0.05, &refused), 0.02);
    assert_eq!(smoothed, 1);
    assert_eq!(kept, b);
    // Nothing refused: both kept.
    let (kept, smoothed) = kept_creases(&p, sharp, &cut(0.1, 0.05, &[]), 0.02);
    assert_eq!((kept.len(), smoothed), (8, 0));
}
