use super::*;
use crate::network::Curve;
use std::f64::consts::PI;

/// A UV sphere of radius 1 (`rings` latitude bands, `2 rings` longitudes), counter-clockwise
/// seen from outside; with `top_only`, the band `z > z_cut` (a cap with one boundary loop).
pub(crate) fn uv_sphere(rings: usize, z_cut: Option<f64>) -> (Vec<DVec3>, Vec<[u32; 3]>) {
    let cols = 2 * rings;
    let mut p = vec![DVec3::Z];
    for i in 1..rings {
        let th = PI * i as f64 / rings as f64;
        for j in 0..cols {
            let ph = 2.0 * PI * j as f64 / cols as f64;
            p.push(DVec3::new(th.sin() * ph.cos(), th.sin() * ph.sin(), th.cos()));
        }
    }
    p.push(-DVec3::Z);
    let south = (p.len() - 1) as u32;
    let at = |i: usize, j: usize| (1 + (i - 1) * cols + j % cols) as u32;
    let mut f = Vec::new();
    for j in 0..cols {
        f.push([0, at(1, j), at(1, j + 1)]);
        f.push([south, at(rings - 1, j + 1), at(rings - 1, j)]);
    }
    for i in 1..rings - 1 {
        for j in 0..cols {
            f.push([at(i, j), at(i + 1, j), at(i + 1, j + 1)]);
            f.push([at(i, j), at(i + 1, j + 1), at(i, j + 1)]);
        }
    }
    if let Some(z) = z_cut {
        f.retain(|t| t.iter().all(|&v| p[v as usize].z > z - 1e-12));
    }
    (p, f)
}

/// The unit cube `[0, 1]³` as 12 triangles, counter-clockwise seen from outside.
pub(crate) fn unit_cube() -> (Vec<DVec3>, Vec<[u32; 3]>) {
    let p: Vec<DVec3> = (0..8).map(|i| DVec3::new((i & 1) as f64, ((i >> 1) & 1) as f64, (i >> 2) as f64)).collect();
    let quads = [[0, 2, 3, 1], [4, 5, 7, 6], [0, 1, 5, 4], [2, 6, 7, 3], [0, 4, 6, 2], [1, 3, 7, 5]];
    let f = quads.iter().flat_map(|q| [[q[0], q[1], q[2]], [q[0], q[2], q[3]]]).collect();
    (p, f)
}

/// The square `[0, 1]² × {0}` as two triangles, counter-clockwise seen from `+z`: vertices
/// (0,0), (1,0), (1,1), (0,1).
pub(crate) fn unit_square() -> (Vec<DVec3>, Vec<[u32; 3]>) {
    let p = vec![DVec3::ZERO, DVec3::X, DVec3::new(1.0, 1.0, 0.0), DVec3::Y];
    (p, vec![[0, 1, 2], [0, 2, 3]])
}

/// A polyline sample (normal `+z`).
pub(crate) fn raw(x: f64, y: f64, node: bool) -> Raw {
    Raw { p: DVec3::new(x, y, 0.0), n: DVec3::Z, node }
}

/// A traced section through `samples`.
pub(crate) fn traced(samples: Vec<Raw>, closed: bool) -> Traced {
    Traced { plane: Some(0), samples, closed, boundary: false, name: "s".into(), cut: false, right: Vec::new() }
}

#[test]
fn sphere_sections_lie_on_the_mesh_with_radial_normals_and_shared_crossings() {
    let (p, f) = uv_sphere(40, None);
    let opts = SampleOptions { planes: [3, 3, 3], ..Default::default() };
    let (net, rep) = sample_mesh(&p, &f, &opts).unwrap();
    assert_eq!(rep.boundary_loops, 0);
    assert!(rep.sections >= 9, "{rep:?}");
    assert!(rep.crossings >= 30, "{rep:?}");
    // The mesh (edges ≤ π/40) is within about 2e-3 of the unit sphere; so are the samples.
    for c in &net.curves {
        assert!(c.closed);
        for (q, n) in c.points.iter().zip(&c.normals) {
            assert!((q.length() - 1.0).abs() < 2.5e-3, "{q}");
            assert!(n.dot(q.normalize()) > 0.999, "normal {n} at {q}");
        }
    }
    // Every crossing sample is a sample of two curves, at the same position exactly.
    let mut seen: HashMap<[u64; 3], usize> = HashMap::new();
    for c in &net.curves {
        for q in &c.points {
            *seen.entry(q.to_array().map(f64::to_bits)).or_default() += 1;
        }
    }
    let shared = seen.values().filter(|&&k| k >= 2).count();
    assert_eq!(shared, rep.crossings, "{rep:?}");
}

#[test]
fn no_shared_nodes_puts_crossings_between_samples_and_noise_moves_samples() {
    let (p, f) = uv_sphere(40, None);
    let opts = SampleOptions { planes: [3, 3, 3], shared_nodes: false, noise: 0.01, ..Default::default() };
    let (net, rep) = sample_mesh(&p, &f, &opts).unwrap();
    let mut seen = std::collections::HashSet::new();
    let mut dup = 0;
    for c in &net.curves {
        for q in &c.points {
            if !seen.insert(q.to_array().map(f64::to_bits)) {
                dup += 1;
            }
        }
    }
    assert_eq!(dup, 0);
    // Noise σ = 1% of the spacing: samples leave the sphere by about that much, no more.
    let dev: Vec<f64> = net.curves.iter().flat_map(|c| c.points.iter().map(|q| (q.length() - 1.0).abs())).collect();
    let max = dev.iter().cloned().fold(0.0, f64::max);
    assert!(max > 1e-5 && max < 0.06 * rep.spacing + 1e-3, "max deviation {max}, spacing {}", rep.spacing);
}

#[test]
fn a_cap_gives_a_boundary_loop_with_the_section_ends_on_it() {
    let (p, f) = uv_sphere(40, Some(0.0));
    let opts = SampleOptions { planes: [3, 3, 2], ..Default::default() };
    let (net, rep) = sample_mesh(&p, &f, &opts).unwrap();
    assert_eq!(rep.boundary_loops, 1, "{rep:?}");
    let b: Vec<&Curve> = net.curves.iter().filter(|c| c.boundary).collect();
    assert_eq!(b.len(), 1);
    assert!(b[0].closed && b[0].points.iter().all(|q| q.z.abs() < 1e-9));
    // Every open section ends on the boundary loop, at one of its samples.
    let on_loop: std::collections::HashSet<[u64; 3]> =
        b[0].points.iter().map(|q| q.to_array().map(f64::to_bits)).collect();
    let open: Vec<&Curve> = net.curves.iter().filter(|c| !c.closed).collect();
    assert!(!open.is_empty());
    for c in open {
        for q in [c.points[0], c.points[c.points.len() - 1]] {
            assert!(on_loop.contains(&q.to_array().map(f64::to_bits)), "end {q} not on the boundary loop");
        }
    }
}

#[test]
fn bad_meshes_and_options_are_errors() {
    let (p, f) = uv_sphere(10, None);
    assert!(matches!(sample_mesh(&p, &[], &SampleOptions::default()), Err(Error::Input { .. })));
    assert!(matches!(sample_mesh(&p, &[[0, 1, 999]], &SampleOptions::default()), Err(Error::Input { .. })));
    let mut q = p.clone();
    q[3].x = f64::NAN;
    assert!(matches!(sample_mesh(&q, &f, &SampleOptions::default()), Err(Error::Input { .. })));
    for o in [
        SampleOptions { planes: [0, 0, 0], ..Default::default() },
        SampleOptions { spacing: Some(-1.0), ..Default::default() },
        SampleOptions { noise: f64::NAN, ..Default::default() },
    ] {
        assert!(matches!(sample_mesh(&p, &f, &o), Err(Error::Usage { .. })), "{o:?}");
    }
    // One family only: no crossings.
    let o = SampleOptions { planes: [3, 0, 0], ..Default::default() };
    assert!(matches!(sample_mesh(&p, &f, &o), Err(Error::Topology { .. })));
}

#[test]
fn usage_errors_name_the_options_in_backticks_and_mesh_errors_their_vertex() {
    let (p, f) = unit_cube();
    let message = |o: SampleOptions| match sample_mesh(&p, &f, &o) {
        Err(e @ Error::Usage { .. }) => e.to_string(),
        other => panic!("expected a usage error, got {other:?}"),
    };
    assert!(message(SampleOptions { spacing: Some(0.0), ..Default::default() }).contains("`spacing`"));
    assert!(message(SampleOptions { spacing: Some(1e-9), ..Default::default() }).contains("`spacing`"));
    assert!(message(SampleOptions { planes: [0; 3], ..Default::default() }).contains("`planes`"));
    assert!(message(SampleOptions { tilt: f64::INFINITY, ..Default::default() }).contains("`tilt`"));
    assert!(message(SampleOptions { noise: -1.0, ..Default::default() }).contains("`noise`"));
    let mut q = p.clone();
    q[5].y = f64::NAN;
    let e = sample_mesh(&q, &f, &SampleOptions::default()).unwrap_err();
    assert_eq!(e.at().vertex, Some(5), "{e}");
    // Three faces on the edge 0–1 (a fin added to the cube).
    let mut q = p.clone();
    q.push(DVec3::new(0.5, -1.0, 0.5));
    let mut g = f.clone();
    g.push([0, 8, 1]);
    let e = sample_mesh(&q, &g, &SampleOptions::default()).unwrap_err();
    assert!(matches!(e, Error::Input { .. }) && e.to_string().contains("2-manifold"), "{e}");
    assert!(matches!(e.at().vertex, Some(0 | 1)), "{e}");
}

#[test]
fn principal_curves_on_a_sphere_cross_and_lie_on_the_mesh() {
    let (p, f) = uv_sphere(40, None);
    let opts = SampleOptions { planes: [3, 3, 3], curves: CurveFamily::Principal, ..Default::default() };
    let (net, rep) = sample_mesh(&p, &f, &opts).unwrap();
    assert!(rep.crossings > 10 && rep.sections >= 4, "{rep:?}");
    assert_eq!(rep.trimmed, 0);
    for c in &net.curves {
        assert!(c.name.as_deref().is_some_and(|n| n.starts_with("principal #")), "{:?}", c.name);
        for q in &c.points {
            assert!((q.length() - 1.0).abs() < 2.5e-3, "{q}");
        }
    }
}
