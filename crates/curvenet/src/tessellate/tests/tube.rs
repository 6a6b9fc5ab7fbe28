use super::*;
use crate::network::Curve;
use crate::tessellate::tessellate;
use crate::tessellate::tests::{euler_characteristic, prepared};
use crate::topology::Patch;

/// A boundary circle of radius 1 at height `z` about the z axis, normals pointing away from
/// the axis, sample 0 at (1, 0, z).
fn rim(z: f64) -> Curve {
    let n = 48;
    let points: Vec<DVec3> = (0..n)
        .map(|i| {
            let a = std::f64::consts::TAU * i as f64 / n as f64;
            DVec3::new(a.cos(), a.sin(), z)
        })
        .collect();
    let normals = points.iter().map(|p| DVec3::new(p.x, p.y, 0.0)).collect();
    Curve { name: None, points, normals, closed: true, boundary: true, ..Default::default() }
}

/// Two facing circles bound a tube: an annulus (Euler characteristic 0) whose faces all face
/// away from the axis; the seam from (1, 0, 0) to (1, 0, 1) gets round(h/d) − 1 = 9 new
/// vertices, evenly spaced before the smoothing (`relax`), which moves them less than d/4.
#[test]
fn two_circles_bound_an_outward_annulus_with_a_straight_seam() {
    let d = 0.1;
    let (g, res, patches) = prepared(vec![rim(0.0), rim(1.0)], d);
    assert!(matches!(patches[..], [Patch::Tube(_)]), "{patches:?}");
    let mesh = tessellate(&g, &res, &patches, d).unwrap();
    assert_eq!(euler_characteristic(&mesh.faces), 0);
    for f in &mesh.faces {
        let [a, b, c] = f.map(|v| mesh.positions[v as usize]);
        let out = (a + b + c) / 3.0 * DVec3::new(1.0, 1.0, 0.0);
        assert!((b - a).cross(c - a).dot(out) > 0.0, "face {f:?} faces the axis");
    }
    for k in 1..10 {
        let p = mesh.positions[mesh.num_curve + k - 1];
        assert!(p.distance(DVec3::new(1.0, 0.0, k as f64 / 10.0)) < 0.25 * d, "seam vertex {k} at {p:?}");
    }
}
