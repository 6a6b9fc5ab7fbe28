//! Networks sampled from meshes (`curvenet::sampling`, issue 5): plane sections with crossings
//! between samples and 1% noise, surfaced and measured against the mesh they came from.

use curvenet::geom::{Aabb, DVec3};
use curvenet::metrics::{evaluate, Reference};
use curvenet::sampling::{sample_mesh, SampleOptions};
use curvenet::{surface, Options};
use std::f64::consts::PI;

/// A UV sphere (`rings` bands) whose radius is `1 + bump(θ, φ)`, optionally cut to `z > z_cut`.
fn sphere_mesh(rings: usize, bump: impl Fn(f64, f64) -> f64, z_cut: Option<f64>) -> (Vec<DVec3>, Vec<[u32; 3]>) {
    let cols = 2 * rings;
    let dir = |th: f64, ph: f64| DVec3::new(th.sin() * ph.cos(), th.sin() * ph.sin(), th.cos());
    let mut p = vec![DVec3::Z * (1.0 + bump(0.0, 0.0))];
    for i in 1..rings {
        let th = PI * i as f64 / rings as f64;
        for j in 0..cols {
            let ph = 2.0 * PI * j as f64 / cols as f64;
            p.push(dir(th, ph) * (1.0 + bump(th, ph)));
        }
    }
    p.push(-DVec3::Z * (1.0 + bump(PI, 0.0)));
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
        f.retain(|t| t.iter().all(|&v| p[v as usize].z > z));
    }
    (p, f)
}

/// Samples `mesh` (crossings between samples, 1% noise), surfaces it and returns the RMS
/// distance of the free vertices to the mesh relative to its bounding-box diagonal, and the
/// surface.
fn sample_and_measure(p: &[DVec3], f: &[[u32; 3]], planes: usize, vertices: usize) -> (f64, curvenet::Surface) {
    let opts = SampleOptions { planes: [planes; 3], shared_nodes: false, noise: 0.01, ..Default::default() };
    let (net, _) = sample_mesh(p, f, &opts).expect("sampling");
    let s = surface(&net, &Options::default().with_vertices(vertices)).expect("surfacing");
    let e = evaluate(
        &s.mesh.positions,
        &s.mesh.faces,
        Some(&s.normals),
        &s.curve_flags,
        Reference::Mesh { positions: p, faces: f },
        None,
    );
    let diag = Aabb::of(f.iter().flatten().map(|&v| p[v as usize])).diagonal();
    (e.distance.rms / diag, s)
}

#[test]
fn bumpy_sphere_sampled_with_noise_is_recovered_within_half_a_percent() {
    let (p, f) = sphere_mesh(60, |th, ph| 0.08 * (3.0 * th).sin() * (4.0 * ph).cos(), None);
    let (rel, s) = sample_and_measure(&p, &f, 5, 8000);
    assert!(rel <= 0.005, "RMS {:.3}% of the diagonal", 100.0 * rel);
    assert_eq!(s.stats.components, 1);
}

#[test]
fn a_cap_with_its_boundary_loop_is_surfaced_with_a_free_border() {
    let (p, f) = sphere_mesh(60, |_, _| 0.0, Some(0.0));
    let (rel, s) = sample_and_measure(&p, &f, 4, 6000);
    assert!(rel <= 0.005, "RMS {:.3}% of the diagonal", 100.0 * rel);
    assert!(s.mesh.on_boundary.iter().any(|&b| b));
}

#[test]
fn two_separate_spheres_are_two_components_of_one_surface() {
    let (mut p, mut f) = sphere_mesh(40, |_, _| 0.0, None);
    let (p2, f2) = sphere_mesh(40, |_, _| 0.0, None);
    let base = p.len() as u32;
    p.extend(p2.iter().map(|q| *q * 0.7 + DVec3::new(3.0, 0.0, 0.0)));
    f.extend(f2.iter().map(|t| t.map(|v| v + base)));
    let (rel, s) = sample_and_measure(&p, &f, 8, 8000);
    assert_eq!(s.stats.components, 2);
    assert!(rel <= 0.005, "RMS {:.3}% of the diagonal", 100.0 * rel);
}

/// The real meshes of `data/meshes` (see its README): a smaller plane count
/// than `bench/real_meshes.sh` to keep the test short.
#[test]
fn real_meshes() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../data/meshes");
    // The beetle at 6 and 10 planes: issue 5's failures (a crossing snapped past an open
    // curve's end, a shallow meeting read as two nodes, holes reached by one section).
    for (name, planes) in
        [("bumpy-cube.obj", 6), ("fandisk.off", 6), ("beetle.off", 6), ("beetle.off", 8), ("beetle.off", 10)]
    {
        let m = curvenet::io::read_mesh(&dir.join(name)).unwrap();
        let (rel, s) = sample_and_measure(&m.positions, &m.faces, planes, 10000);
        eprintln!("{name} at {planes} planes: RMS {:.3}% of the diagonal", 100.0 * rel);
        assert!(rel <= 0.005, "{name} at {planes} planes: RMS {:.3}% of the diagonal", 100.0 * rel);
        assert_eq!(s.stats.components, 1, "{name} at {planes} planes");
    }
}

/// A torus (R, r) with `n × m` quads split in two, counter-clockwise seen from outside.
fn torus_mesh(big: f64, small: f64, n: usize, m: usize) -> (Vec<DVec3>, Vec<[u32; 3]>) {
    let mut p = Vec::with_capacity(n * m);
    for i in 0..n {
        let u = 2.0 * PI * i as f64 / n as f64;
        for j in 0..m {
            let v = 2.0 * PI * j as f64 / m as f64;
            p.push(DVec3::new((big + small * v.cos()) * u.cos(), (big + small * v.cos()) * u.sin(), small * v.sin()));
        }
    }
    let at = |i: usize, j: usize| ((i % n) * m + j % m) as u32;
    let mut f = Vec::with_capacity(2 * n * m);
    for i in 0..n {
        for j in 0..m {
            f.push([at(i, j), at(i + 1, j), at(i + 1, j + 1)]);
            f.push([at(i, j), at(i + 1, j + 1), at(i, j + 1)]);
        }
    }
    (p, f)
}

/// `curvenet sample --curves principal`: curves along the principal directions (meridians and
/// parallels on a torus; a fixed axis where the sphere is isotropic), crossings between
/// samples, 1% noise, surfaced within half a percent of the diagonal.
#[test]
fn principal_curves_on_a_torus_and_a_sphere_are_surfaced_within_half_a_percent() {
    use curvenet::sampling::CurveFamily;
    for (name, (p, f)) in [("torus", torus_mesh(4.0, 2.0, 120, 60)), ("sphere", sphere_mesh(50, |_, _| 0.0, None))] {
        let opts = SampleOptions {
            planes: [6; 3],
            shared_nodes: false,
            noise: 0.01,
            curves: CurveFamily::Principal,
            ..Default::default()
        };
        let (net, report) = sample_mesh(&p, &f, &opts).expect("sampling");
        assert!(report.sections >= 8 && report.crossings >= 16, "{name}: {report:?}");
        let s = surface(&net, &Options::default().with_vertices(6000)).expect("surfacing");
        let e = evaluate(
            &s.mesh.positions,
            &s.mesh.faces,
            Some(&s.normals),
            &s.curve_flags,
            Reference::Mesh { positions: &p, faces: &f },
            None,
        );
        let diag = Aabb::of(f.iter().flatten().map(|&v| p[v as usize])).diagonal();
        let rel = e.distance.rms / diag;
        eprintln!(
            "{name}: {} curves, {} crossings, RMS {:.4}% of the diagonal",
            report.sections,
            report.crossings,
            100.0 * rel
        );
        assert!(rel <= 0.005, "{name}: RMS {:.3}% of the diagonal", 100.0 * rel);
        assert_eq!(s.stats.components, 1);
    }
}

/// On a torus the principal directions are the meridians and the parallels: the principal
/// curves follow them (away from their cut ends).
#[test]
fn principal_curves_on_a_torus_are_meridians_and_parallels() {
    use curvenet::sampling::CurveFamily;
    let (p, f) = torus_mesh(4.0, 2.0, 120, 60);
    let opts = SampleOptions { planes: [5; 3], curves: CurveFamily::Principal, ..Default::default() };
    let (net, _) = sample_mesh(&p, &f, &opts).expect("sampling");
    let (mut off, mut total) = (0usize, 0usize);
    for c in &net.curves {
        for w in c.points.windows(2) {
            let (a, b) = (w[0], w[1]);
            let m = 0.5 * (a + b);
            let t = (b - a).normalize();
            // Parallel direction: around the z axis; meridian: in the plane through the axis.
            let along_parallel = DVec3::new(-m.y, m.x, 0.0).normalize();
            let cos = t.dot(along_parallel).abs();
            let cos_meridian = (1.0 - cos * cos).max(0.0).sqrt();
            total += 1;
            if cos.max(cos_meridian) < 10f64.to_radians().cos() {
                off += 1;
            }
        }
    }
    assert!(
        (off as f64) < 0.02 * total as f64,
        "{off} of {total} curve edges more than 10° off the principal directions"
    );
}

/// The default round trip `sample` → `surface` on a human-like figure (`figure.off`: a union of
/// ellipsoids, capsules and boxes, meshed by marching tetrahedra — creases everywhere, many of
/// them tangles of one or two mesh edges). Before, sampling wrote a network that `surface`
/// refused, then one whose surface had no arms (the creases `surface` refused left out, the
/// sections that ended on them dangling). Now the mesh is the truth (`SampleOptions::adapt`):
/// the network without the tangled creases, with more planes through the thin limbs, is kept
/// because its surface covers the mesh. Measured both ways: the surface against the mesh and
/// the mesh against the surface (missing arms show only in the second).
#[test]
fn the_default_round_trip_on_a_figure_with_many_creases() {
    use curvenet::sampling::{sample_mesh, SampleOptions};
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../tests/data/meshes/figure.off");
    let m = curvenet::io::read_mesh(&path).unwrap();
    let (net, report) = sample_mesh(&m.positions, &m.faces, &SampleOptions::default()).unwrap();
    assert!(report.unsurfaced.is_none(), "{:?}", report.unsurfaced);
    eprintln!(
        "figure: {} curves left out for surface's checks, creases dropped {:?}, planes {:?}, quick coverage {:?}",
        report.left_out.len(),
        report.creases_dropped,
        report.planes,
        report.mesh_coverage
    );
    let s = curvenet::surface(&net, &curvenet::Options::default()).unwrap_or_else(|e| panic!("{e}"));
    let diag = curvenet::geom::Aabb::of(m.positions.iter().copied()).diagonal();
    // The surface against the mesh. Measured: 20 of 16,173 vertices (0.1 %) farther than 2 %
    // of the diagonal (2.2 % before, with the arms missing). At most 2 %.
    let to_mesh = curvenet::metrics::MeshDistance::new(&m.positions, &m.faces);
    let far = s.mesh.positions.iter().filter(|&&p| to_mesh.closest(p).0 > 0.02 * diag).count();
    eprintln!(
        "figure: {far} of {} surface vertices farther than 2 % of the diagonal from the mesh",
        s.mesh.positions.len()
    );
    assert!(
        far * 50 <= s.mesh.positions.len(),
        "{far} of {} vertices farther than 2 % of the diagonal",
        s.mesh.positions.len()
    );
    // The mesh against the surface: the share of the mesh's vertices the surface passes within
    // 2 % of the diagonal. Measured: 98.4 % (no arms before). At least 97 %.
    let to_surface = curvenet::metrics::MeshDistance::new(&s.mesh.positions, &s.mesh.faces);
    let near = m.positions.iter().filter(|&&p| to_surface.closest(p).0 <= 0.02 * diag).count();
    let share = near as f64 / m.positions.len() as f64;
    eprintln!("figure: the surface passes near {:.1} % of the mesh's vertices", 100.0 * share);
    assert!(share >= 0.97, "the surface passes near only {:.1} % of the mesh's vertices", 100.0 * share);
}
