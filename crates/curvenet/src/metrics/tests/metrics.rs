use super::*;

#[test]
fn closest_points_are_on_the_surfaces() {
    let p = DVec3::new(0.3, -1.7, 0.9);
    let s = Truth::Sphere { center: DVec3::new(0.1, 0.0, 0.0), radius: 2.0 };
    assert!((s.distance(p) - ((p - DVec3::new(0.1, 0.0, 0.0)).length() - 2.0).abs()).abs() < 1e-15);
    let t = Truth::Torus { major: 4.0, minor: 2.0 };
    assert!((t.distance(DVec3::new(6.5, 0.0, 0.0)) - 0.5).abs() < 1e-15);
    assert!((t.distance(DVec3::new(0.0, 4.0, 1.0)) - 1.0).abs() < 1e-15);
    let sad = Truth::Saddle;
    let q = sad.closest_point(p);
    assert!((q.z - 0.5 * (q.x * q.x - q.y * q.y)).abs() < 1e-12);
    // The offset is along the normal.
    let d = p - q;
    assert!(d.normalize().cross(sad.normal(p)).length() < 1e-9);
}

#[test]
fn bvh_matches_brute_force() {
    // A bumpy open grid surface.
    let k = 20;
    let mut p = Vec::new();
    for j in 0..=k {
        for i in 0..=k {
            let (u, v) = (i as f64 / k as f64, j as f64 / k as f64);
            p.push(DVec3::new(u, v, 0.2 * (6.0 * u).sin() * (4.0 * v).cos()));
        }
    }
    let id = |i: usize, j: usize| (j * (k + 1) + i) as u32;
    let mut t = Vec::new();
    for j in 0..k {
        for i in 0..k {
            t.push([id(i, j), id(i + 1, j), id(i + 1, j + 1)]);
            t.push([id(i, j), id(i + 1, j + 1), id(i, j + 1)]);
        }
    }
    let md = MeshDistance::new(&p, &t);
    let mut s = 12345u64;
    let mut rnd = || {
        s = s.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
        (s >> 11) as f64 / (1u64 << 53) as f64
    };
    for _ in 0..300 {
        let q = DVec3::new(rnd() * 1.6 - 0.3, rnd() * 1.6 - 0.3, rnd() - 0.5);
        let brute = t
            .iter()
            .map(|f| q.distance(closest_point_on_triangle(q, p[f[0] as usize], p[f[1] as usize], p[f[2] as usize])))
            .fold(f64::INFINITY, f64::min);
        assert!((md.closest(q).0 - brute).abs() < 1e-12, "{q:?}");
    }
}

#[test]
fn ellipsoid_closest_points() {
    let e = Truth::Ellipsoid { axes: DVec3::new(3.0, 2.0, 1.0) };
    for p in
        [DVec3::new(4.0, 0.5, 0.2), DVec3::new(0.3, -0.2, 0.1), DVec3::new(0.0, 0.0, 2.0), DVec3::new(-1.0, 1.5, -0.7)]
    {
        let q = e.closest_point(p);
        // On the surface.
        assert!(((q / DVec3::new(3.0, 2.0, 1.0)).length_squared() - 1.0).abs() < 1e-9, "{p:?} {q:?}");
        // The offset is along the normal.
        if p.distance(q) > 1e-9 {
            assert!((p - q).normalize().cross(e.normal(p)).length() < 1e-6, "{p:?}");
        }
    }
    // A sphere as an ellipsoid.
    let s = Truth::Ellipsoid { axes: DVec3::splat(2.0) };
    assert!((s.distance(DVec3::new(1.0, 2.0, 2.0)) - 1.0).abs() < 1e-12);
}

#[test]
fn truth_specs() {
    assert_eq!(Truth::parse("torus:4,2"), Some(Ok(Truth::Torus { major: 4.0, minor: 2.0 })));
    assert_eq!(
        Truth::parse("sphere:1,2,3,4"),
        Some(Ok(Truth::Sphere { center: DVec3::new(1.0, 2.0, 3.0), radius: 4.0 }))
    );
    assert_eq!(Truth::parse("plane"), Some(Ok(Truth::Plane { normal: DVec3::Z, offset: 0.0 })));
    assert!(matches!(Truth::parse("cylinder:-1"), Some(Err(_))));
    assert!(matches!(Truth::parse("torus:4,x"), Some(Err(_))));
    assert_eq!(Truth::parse("reference.obj"), None);
}

/// A closed (u periodic, v periodic when `closed_v`) parametric grid, triangulated.
fn grid(nu: usize, nv: usize, closed_v: bool, f: impl Fn(f64, f64) -> DVec3) -> (Vec<DVec3>, Vec<[u32; 3]>) {
    let rows = if closed_v { nv } else { nv + 1 };
    let mut p = Vec::new();
    for j in 0..rows {
        for i in 0..nu {
            p.push(f(i as f64 / nu as f64, j as f64 / nv as f64));
        }
    }
    let id = |i: usize, j: usize| ((j % rows) * nu + i % nu) as u32;
    let mut faces = Vec::new();
    for j in 0..nv {
        for i in 0..nu {
            faces.push([id(i, j), id(i + 1, j), id(i + 1, j + 1)]);
            faces.push([id(i, j), id(i + 1, j + 1), id(i, j + 1)]);
        }
    }
    (p, faces)
}

/// The truths' mean curvature against the cotangent curvature of fine parametric meshes: the
/// formulas and their signs (outward normals, `+1/r` on a sphere) agree with the library's.
#[test]
fn analytic_mean_curvature_matches_fine_meshes() {
    use std::f64::consts::TAU;
    let torus = Truth::Torus { major: 4.0, minor: 2.0 };
    let (tp, tf) = grid(400, 200, true, |u, v| {
        let (su, cu) = (TAU * u).sin_cos();
        let (sv, cv) = (TAU * v).sin_cos();
        DVec3::new((4.0 + 2.0 * cv) * cu, (4.0 + 2.0 * cv) * su, 2.0 * sv)
    });
    let cyl = Truth::Cylinder { radius: 1.0 };
    let (cp, cf) = grid(200, 100, false, |u, v| {
        let (s, c) = (TAU * u).sin_cos();
        DVec3::new(c, s, 2.0 * v - 1.0)
    });
    let saddle = Truth::Saddle;
    // The saddle's graph over [−½, ½]², orientation upward.
    let n = 120;
    let mut sp = Vec::new();
    for j in 0..=n {
        for i in 0..=n {
            let (x, y) = (i as f64 / n as f64 - 0.5, j as f64 / n as f64 - 0.5);
            sp.push(DVec3::new(x, y, 0.5 * (x * x - y * y)));
        }
    }
    let mut sf = Vec::new();
    let sid = |i: usize, j: usize| (j * (n + 1) + i) as u32;
    for j in 0..n {
        for i in 0..n {
            sf.push([sid(i, j), sid(i + 1, j), sid(i + 1, j + 1)]);
            sf.push([sid(i, j), sid(i + 1, j + 1), sid(i, j + 1)]);
        }
    }
    for (name, truth, p, f, tol) in
        [("torus", torus, tp, tf, 0.01), ("cylinder", cyl, cp, cf, 0.01), ("saddle", saddle, sp, sf, 0.02)]
    {
        let free: Vec<usize> = (0..p.len()).collect();
        let e = curvature_error(&p, &f, &free, &truth).unwrap();
        assert!(e.relative_p99 < tol, "{name}: {e:?}");
        // The sign: a flipped formula would be off by twice the curvature.
        assert!(e.relative_max < 0.5, "{name}: {e:?}");
    }
    // Flat: no scale, no figure.
    let (pp, pf) = grid(10, 10, false, |u, v| DVec3::new(u, v, 0.0));
    let plane = Truth::Plane { normal: DVec3::Z, offset: 0.0 };
    assert!(curvature_error(&pp, &pf, &(0..pp.len()).collect::<Vec<_>>(), &plane).is_none());
    // The ellipsoid's formula against the sphere it becomes, and its extreme points.
    let e = Truth::Ellipsoid { axes: DVec3::new(2.0, 1.0, 1.0) };
    let h = e.mean_curvature(DVec3::new(0.0, 0.0, 2.0)).unwrap();
    // At (0, 0, 1): principal curvatures c/a² = 1/4 (along x) and c/b² = 1.
    assert!((h - 0.625).abs() < 1e-12, "{h}");
    let s = Truth::Ellipsoid { axes: DVec3::splat(3.0) };
    assert!((s.mean_curvature(DVec3::new(1.0, 2.0, 0.5)).unwrap() - 1.0 / 3.0).abs() < 1e-12);
}
