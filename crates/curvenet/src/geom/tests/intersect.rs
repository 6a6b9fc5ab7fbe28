use super::*;

/// A square of two triangles in the plane z = `z`, turned by `turn` about the x axis.
fn square(z: f64, turn: bool, base: u32) -> (Vec<DVec3>, Vec<[u32; 3]>) {
    let p = [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)];
    let pts = p
        .iter()
        .map(|&(x, y)| if turn { DVec3::new(0.7 * x + 0.2, z + 0.1, 0.6 * y + 0.1) } else { DVec3::new(x, y, z) })
        .collect();
    (pts, vec![[base, base + 1, base + 2], [base, base + 2, base + 3]])
}

#[test]
fn crossing_squares_are_found_apart_ones_are_not() {
    let (mut p, mut f) = square(0.0, false, 0);
    let (q, g) = square(0.0, true, 4);
    p.extend(q);
    f.extend(g);
    let found = self_intersections(&p, &f);
    assert!(found.pairs >= 2, "{found:?}");
    let x = found.first.unwrap().2;
    assert!(x.z.abs() < 1e-12 && (x.y - 0.1).abs() < 1e-12, "on the line where the planes cross: {x}");
    // Parallel planes, and a shared edge (the two triangles of one square), cross nowhere.
    let (mut p, mut f) = square(0.0, false, 0);
    let (q, g) = square(0.5, false, 4);
    p.extend(q);
    f.extend(g);
    assert_eq!(self_intersections(&p, &f).pairs, 0);
}
