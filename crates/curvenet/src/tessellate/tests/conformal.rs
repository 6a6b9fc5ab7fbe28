use super::*;

/// A patch of the unit sphere (spherical cap of half-angle 60°) as a polar grid.
fn cap() -> (Vec<DVec3>, Vec<[u32; 3]>) {
    let (rings, sectors) = (12, 48);
    let mut p = vec![DVec3::Z];
    for r in 1..=rings {
        let th = 60f64.to_radians() * r as f64 / rings as f64;
        for s in 0..sectors {
            let ph = std::f64::consts::TAU * s as f64 / sectors as f64;
            p.push(DVec3::new(th.sin() * ph.cos(), th.sin() * ph.sin(), th.cos()));
        }
    }
    let id = |r: usize, s: usize| (if r == 0 { 0 } else { 1 + (r - 1) * sectors + s % sectors }) as u32;
    let mut f = Vec::new();
    for s in 0..sectors {
        f.push([0, id(1, s), id(1, s + 1)]);
    }
    for r in 1..rings {
        for s in 0..sectors {
            f.push([id(r, s), id(r + 1, s), id(r + 1, s + 1)]);
            f.push([id(r, s), id(r + 1, s + 1), id(r, s + 1)]);
        }
    }
    (p, f)
}

#[test]
fn a_flat_patch_maps_isometrically() {
    let (p, f) = cap();
    let flat: Vec<DVec3> = p.iter().map(|q| DVec3::new(2.0 * q.x + 0.3 * q.y, q.y - 0.5, 0.0)).collect();
    // Orientation: the cap's faces are counter-clockwise seen from +z.
    let uv = lscm(&flat, &f, [1, 1 + 24]).unwrap();
    // A planar patch is mapped by a similarity: distances ratios preserved.
    let d3 = flat[5].distance(flat[100]);
    let d2 = uv[5].distance(uv[100]);
    let s = uv[1].distance(uv[25]) / flat[1].distance(flat[25]);
    assert!((d2 / d3 - s).abs() < 1e-9, "{} {}", d2 / d3, s);
}

#[test]
fn a_spherical_cap_maps_conformally_and_orientation_preserving() {
    let (p, f) = cap();
    let uv = lscm(&p, &f, [1, 1 + 11 * 48 + 24]).unwrap();
    let mut worst = 0.0f64;
    for t in &f {
        let (a, b, c) = (uv[t[0] as usize], uv[t[1] as usize], uv[t[2] as usize]);
        assert!((b - a).perp_dot(c - a) > 0.0, "flipped triangle");
        // Angles of the image vs the 3D triangle.
        let (pa, pb, pc) = (p[t[0] as usize], p[t[1] as usize], p[t[2] as usize]);
        let a3 = (pb - pa).angle_between(pc - pa);
        let a2 = (b - a).angle_to(c - a).abs();
        worst = worst.max((a3 - a2).abs());
    }
    assert!(worst.to_degrees() < 3.0, "{}", worst.to_degrees());
}
