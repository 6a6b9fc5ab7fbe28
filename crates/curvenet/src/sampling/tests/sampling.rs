use super::cut::cut_at_spots;
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
fn a_pinch_vertex_is_split_into_one_vertex_per_fan() {
    // Two triangles that share only vertex 0.
    let mut p = vec![
        DVec3::ZERO,
        DVec3::new(1.0, 0.0, 0.0),
        DVec3::new(1.0, 1.0, 0.0),
        DVec3::new(-1.0, 0.0, 0.0),
        DVec3::new(-1.0, -1.0, 0.0),
    ];
    let mut f = vec![[0, 1, 2], [0, 3, 4]];
    assert_eq!(split_pinches(&mut p, &mut f, 0.1), 1);
    assert_eq!(p.len(), 6);
    assert_ne!(f[0][0], f[1][0]);
    assert!(p[f[0][0] as usize].distance(p[f[1][0] as usize]) > 0.15);
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

/// Issue 5: a section in a bad spot loses only the stretch around it, up to the nearest node
/// (crossing or boundary end) on either side, which end the pieces left.
#[test]
fn a_section_is_cut_at_a_bad_spot_between_the_nodes_around_it() {
    // Samples at x = 0..10; nodes at 0 (boundary end), 3, 6 and 10 (boundary end).
    let samples: Vec<Raw> = (0..=10)
        .map(|i| Raw { p: DVec3::new(i as f64, 0.0, 0.0), n: DVec3::Z, node: matches!(i, 0 | 3 | 6 | 10) })
        .collect();
    let t = |closed| Traced {
        plane: Some(0),
        samples: samples.clone(),
        closed,
        boundary: false,
        name: "s".into(),
        cut: false,
    };
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
