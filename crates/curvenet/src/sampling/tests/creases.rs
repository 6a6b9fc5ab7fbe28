use super::*;
use crate::sampling::tests::unit_cube;

/// The sharp edges along a polyline through `pts` (indices into the positions).
fn along(idx: &[u32]) -> Sharp {
    idx.windows(2).map(|w| edge_key(w[0], w[1])).collect()
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
    let (kept, smoothed) = kept_creases(&p, sharp.clone(), 0.5, 1e-3, 0.1);
    assert_eq!((kept.len(), smoothed), (12, 0));
    let (mut q, mut g) = (p.clone(), f.clone());
    let (original, _) = cut_creases(&mut q, &mut g, kept);
    assert_eq!((q.len(), original.len()), (24, 24));
    assert!(original.iter().enumerate().all(|(v, &o)| q[v] == p[o as usize]));
    // Edges longer than the minimum length only.
    let (kept, smoothed) = kept_creases(&p, sharp, 1.5, 1e-3, 0.1);
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
    let (kept, smoothed) = kept_creases(&p, sharp.clone(), 0.5, 0.02, 0.1);
    assert_eq!(smoothed, 1);
    assert_eq!(kept, a.iter().chain(&c).copied().collect::<Sharp>());
    // Farther apart than the near distance: all kept.
    let (kept, smoothed) = kept_creases(&p, sharp, 0.5, 0.005, 0.1);
    assert_eq!((kept.len(), smoothed), (10, 0));
}

#[test]
fn chains_meeting_at_a_corner_are_no_near_miss() {
    // Two chains from a common end at 30° to each other: close only near the corner.
    let dir = DVec3::new(30f64.to_radians().cos(), 30f64.to_radians().sin(), 0.0);
    let mut p: Vec<DVec3> = (0..5).map(|i| DVec3::new(i as f64 * 0.1, 0.0, 0.0)).collect();
    p.extend((1..5).map(|i| dir * (i as f64 * 0.1)));
    let sharp: Sharp = along(&[0, 1, 2, 3, 4]).into_iter().chain(along(&[0, 5, 6, 7, 8])).collect();
    let (kept, smoothed) = kept_creases(&p, sharp, 0.1, 0.02, 0.05);
    assert_eq!((kept.len(), smoothed), (8, 0));
}
