//! The Cauchy system of \[A11\] on problems with known answers.

// The grid tests index positions and roles by the same vertex number.
#![allow(clippy::needless_range_loop)]

use curvenet::geom::DVec3;
use curvenet::methods::andrews2011::{MicroWeight, Role, Stencil, System};

/// Cubic Hermite curve with end points `p0`, `p1` and end tangents `m0`, `m1`.
fn hermite(t: f64, p0: DVec3, p1: DVec3, m0: DVec3, m1: DVec3) -> DVec3 {
    let (t2, t3) = (t * t, t * t * t);
    (2.0 * t3 - 3.0 * t2 + 1.0) * p0 + (t3 - 2.0 * t2 + t) * m0 + (-2.0 * t3 + 3.0 * t2) * p1 + (t3 - t2) * m1
}

/// Max distance of the k = 2 polyline with Cauchy ends to the Hermite curve, `n` segments.
fn polyline_error(n: usize, micro: MicroWeight) -> f64 {
    let t: Vec<f64> = (0..=n).map(|i| i as f64 / n as f64).collect();
    let stencil = Stencil::polyline(&t);
    let mut roles = vec![Role::Free; n + 1];
    roles[0] = Role::Cauchy;
    roles[n] = Role::Cauchy;
    let (p0, p1) = (DVec3::ZERO, DVec3::new(1.0, 0.0, 0.0));
    let (m0, m1) = (DVec3::new(1.0, 2.0, 0.0), DVec3::new(1.0, -1.0, 0.5));
    let mut positions = vec![DVec3::ZERO; n + 1];
    positions[n] = p1;
    let system = System::build(&stencil, &roles, 2, micro).unwrap();
    // The ghost continues the tangent one step beyond the end: g = u ∓ h m.
    let h = 1.0 / n as f64;
    let ghosts: Vec<DVec3> =
        system.ghosts.iter().map(|g| if g.vertex == 0 { p0 - h * m0 } else { p1 + h * m1 }).collect();
    let x = system.solve(&positions, &ghosts).unwrap();
    (0..=n).map(|i| x[i].distance(hermite(t[i], p0, p1, m0, m1))).fold(0.0, f64::max)
}

#[test]
fn polyline_converges_to_the_cubic_hermite_curve() {
    let errors: Vec<f64> = [8, 16, 32, 64, 128].iter().map(|&n| polyline_error(n, MicroWeight::Consistent)).collect();
    eprintln!("k=2 Hermite errors (consistent w): {errors:?}");
    for w in errors.windows(2) {
        assert!(w[1] < 0.6 * w[0], "error does not decrease with refinement: {errors:?}");
    }
    assert!(errors[4] < 1e-2, "{errors:?}");
    let unit: Vec<f64> = [8, 16, 32, 64, 128].iter().map(|&n| polyline_error(n, MicroWeight::Unit)).collect();
    eprintln!("k=2 Hermite errors (w = 1): {unit:?}");
}

fn sphere_mean_error(order: usize, ghost_updates: usize) -> f64 {
    use curvenet::metrics::{distance_to_truth, Truth};
    let net = curvenet::network::examples::example("sphere").unwrap();
    let mut opts = curvenet::Options::default().with_method(curvenet::Method::Cauchy);
    opts.cauchy.order = order;
    opts.cauchy.ghost_updates = ghost_updates;
    let s = curvenet::surface(&net, &opts).unwrap();
    let truth = Truth::parse("sphere").unwrap().unwrap();
    distance_to_truth(&s.mesh.positions, s.mesh.num_curve, &truth).mean
}

#[test]
fn sphere_network_order_3_is_within_one_percent() {
    let e3 = sphere_mean_error(3, 10);
    eprintln!("sphere, k = 3: mean distance {e3:.3e}");
    assert!(e3 <= 0.01, "{e3}");
    // The paper's plain ghosts (no centring) are first order: worse, still bounded.
    let plain = sphere_mean_error(3, 0);
    eprintln!("sphere, k = 3, plain ghosts: mean distance {plain:.3e}");
    assert!(e3 < plain);
}

mod sketch {
    use curvenet::geom::{DVec2, DVec3};
    use curvenet::sketch::inflate::{inflate, InflateOptions, Inflated};
    use curvenet::sketch::svg::{read_svg, SketchPath};

    pub fn circle(r: f64) -> Vec<SketchPath> {
        let n = 400;
        let points = (0..n)
            .map(|k| {
                let a = std::f64::consts::TAU * k as f64 / n as f64;
                DVec2::new(r * a.cos(), r * a.sin())
            })
            .collect();
        vec![SketchPath { points, closed: true, class: String::new(), sharpness: None, kind: None, line: 1 }]
    }

    pub fn run(paths: &[SketchPath], o: InflateOptions) -> Inflated {
        inflate(paths, &o).unwrap()
    }

    /// Mean angle (degrees) between the sketch plane and the faces that touch the rim.
    pub fn rim_angle(s: &Inflated) -> f64 {
        let mut sum = 0.0;
        let mut count = 0;
        for f in &s.faces {
            let p = |k: usize| s.positions[f[k] as usize];
            if !f.iter().any(|&v| s.on_path[v as usize]) {
                continue;
            }
            let n = (p(1) - p(0)).cross(p(2) - p(0)).normalize();
            sum += n.dot(DVec3::Z).clamp(-1.0, 1.0).acos().to_degrees();
            count += 1;
        }
        sum / count as f64
    }

    #[test]
    fn circle_inflates_to_a_dome_with_the_prescribed_rim_angle() {
        let c = circle(1.0);
        for angle in [30.0, 45.0, 60.0] {
            let s = run(&c, InflateOptions { angle, ..Default::default() });
            let measured = rim_angle(&s);
            eprintln!("rim angle {angle}: measured {measured:.2}, height {:.3}", s.height);
            assert!((measured - angle).abs() < 5.0, "prescribed {angle}°, measured {measured:.2}°");
            assert!(s.positions.iter().all(|p| p.z > -1e-9));
        }
        // Default: a balloon between 0.3 and 1.5 radii high.
        let d = run(&c, InflateOptions::default());
        eprintln!("default dome height {:.3} (radius 1)", d.height);
        assert!(d.height > 0.3 && d.height < 1.5, "{}", d.height);
        // Height grows with stretch.
        let heights: Vec<f64> = [0.0, 0.5, 1.0]
            .iter()
            .map(|&stretch| run(&c, InflateOptions { stretch, ..Default::default() }).height)
            .collect();
        eprintln!("heights for stretch 0, 0.5, 1: {heights:?}");
        assert!(heights[0] < heights[1] && heights[1] < heights[2], "{heights:?}");
    }

    #[test]
    fn order_3_dome_is_rounder_than_order_2() {
        // Roundness: RMS distance to the sphere cap with the same rim (radius 1) and rim angle α
        // (sphere radius 1/sin α, centre below the plane by cot α) — the round dome those
        // boundary conditions describe ([A11] §3: k = 3 controls curvature, k = 2 flattens).
        let c = circle(1.0);
        for angle in [45.0f64, 60.0] {
            let a = angle.to_radians();
            let (rad, z0) = (1.0 / a.sin(), -1.0 / a.tan());
            let dev = |order: usize| {
                let s = run(&c, InflateOptions { order, angle, ..Default::default() });
                let d: Vec<f64> = s.positions.iter().map(|p| (*p - DVec3::new(0.0, 0.0, z0)).length() - rad).collect();
                (d.iter().map(|x| x * x).sum::<f64>() / d.len() as f64).sqrt()
            };
            let (d2, d3) = (dev(2), dev(3));
            eprintln!("rim angle {angle}: sphere-cap deviation k=2 {d2:.4}, k=3 {d3:.4}");
            assert!(d3 < d2, "k=3 {d3} vs k=2 {d2}");
        }
    }

    #[test]
    fn svg_paths_are_read_and_checked() {
        let svg = r#"<svg><path d="M 0 0 L 10 0 l 0 10 H 0 Z" class="outline"/>
            <path class="crease" data-sharpness="20" d="M2 5 C 4 7, 6 3, 8 5"/></svg>"#;
        let p = read_svg(svg, "t.svg", 0.1).unwrap();
        assert_eq!(p.len(), 2);
        assert!(p[0].closed && p[0].points.len() == 4);
        assert_eq!(p[1].sharpness, Some(20.0));
        assert_eq!(p[1].points.last().copied(), Some(DVec2::new(8.0, -5.0)));
        // Arcs are read now; a malformed number is an error at its line and column.
        let bad = read_svg("<svg>\n<path d=\"M 0 0 L 1 x\"/></svg>", "t.svg", 0.1).unwrap_err();
        assert!(bad.to_string().contains("t.svg:2:20"), "{bad}");
        let outside = r#"<svg><rect x="0" y="0" width="1" height="1"/><path d="M 0.5 0.5 L 3 3"/></svg>"#;
        let e = inflate(&read_svg(outside, "t.svg", 0.01).unwrap(), &InflateOptions::default()).unwrap_err();
        assert!(e.to_string().contains("leaves the outline"), "{e}");
    }
}

mod grid {
    use curvenet::geom::mesh::Mesh;
    use curvenet::geom::{DVec2, DVec3};
    use curvenet::methods::andrews2011::{CauchyParams, MicroWeight, Role, Stencil, System};
    use curvenet::operators::{cotan_operators, Metric};

    /// A (2n+1)² grid on [−1, 1]², cut along alternating diagonals. Vertex (i, j) is
    /// `i (2n+1) + j` at x = i/n − 1, y = j/n − 1.
    fn grid(n: usize) -> (Mesh, Stencil) {
        let m = 2 * n + 1;
        let pos2: Vec<DVec2> =
            (0..m * m).map(|k| DVec2::new((k / m) as f64 / n as f64 - 1.0, (k % m) as f64 / n as f64 - 1.0)).collect();
        let mut faces = Vec::new();
        for i in 0..m - 1 {
            for j in 0..m - 1 {
                let (a, b, c, d) = (i * m + j, (i + 1) * m + j, (i + 1) * m + j + 1, i * m + j + 1);
                let t = if (i + j) % 2 == 0 { [[a, b, c], [a, c, d]] } else { [[a, b, d], [b, c, d]] };
                faces.extend(t.map(|f| f.map(|v| v as u32)));
            }
        }
        let mut mesh = Mesh::default();
        mesh.positions = pos2.iter().map(|p| DVec3::new(p.x, p.y, 0.0)).collect();
        mesh.planar = faces.iter().map(|f: &[u32; 3]| f.map(|v| pos2[v as usize])).collect();
        mesh.face_patch = vec![0; faces.len()];
        mesh.on_boundary = vec![false; m * m];
        mesh.faces = faces;
        let ops = cotan_operators(&mesh, Metric::Planar, &mesh.positions);
        let stencil = Stencil::from_operators(&ops, mesh.positions.clone());
        (mesh, stencil)
    }

    fn solve(stencil: &Stencil, roles: &[Role], params: &[Option<CauchyParams>], fixed: &[DVec3]) -> Vec<DVec3> {
        let system = System::build(stencil, roles, 2, MicroWeight::Consistent).unwrap();
        let offsets: Vec<DVec3> = system
            .ghosts
            .iter()
            .map(|g| {
                let e = stencil.positions[g.vertex as usize] - stencil.positions[g.source as usize];
                params[g.vertex as usize].map_or(e, |p| p.ghost_offset(e))
            })
            .collect();
        let f = system.factor().unwrap();
        system.solve_with_updates(&f, fixed, &offsets, 10).unwrap()
    }

    /// Mean tilt (degrees from +z) of the faces touching vertex set `near`, per side of x = 0.
    fn tilt(mesh: &Mesh, p: &[DVec3], near: impl Fn(usize) -> bool, side: f64) -> f64 {
        let mut s = Vec::new();
        for f in &mesh.faces {
            let c = f.iter().map(|&v| p[v as usize]).sum::<DVec3>() / 3.0;
            if !f.iter().any(|&v| near(v as usize)) || c.x * side <= 0.0 {
                continue;
            }
            let n = (p[f[1] as usize] - p[f[0] as usize]).cross(p[f[2] as usize] - p[f[0] as usize]).normalize();
            s.push(n.z.abs().clamp(0.0, 1.0).acos().to_degrees());
        }
        s.iter().sum::<f64>() / s.len() as f64
    }

    #[test]
    fn sharpness_45_at_a_curve_gives_a_right_angled_crease() {
        let n = 16;
        let m = 2 * n + 1;
        let (mesh, stencil) = grid(n);
        let mut roles = vec![Role::Free; m * m];
        let mut params = vec![None; m * m];
        let mut fixed = mesh.positions.clone();
        for k in 0..m * m {
            let p = mesh.positions[k];
            if p.x.abs() < 1e-12 {
                roles[k] = Role::Cauchy;
                params[k] = Some(CauchyParams {
                    orientation: DVec3::Z,
                    initial_normal: Some(DVec3::Z),
                    sharpness: 45f64.to_radians(),
                    stretch: 0.0,
                    tangent: Some(DVec3::Y),
                });
            } else if (p.x.abs() - 1.0).abs() < 1e-12 {
                roles[k] = Role::Position;
                fixed[k].z = -1.0;
            }
        }
        let p = solve(&stencil, &roles, &params, &fixed);
        let crease = |v: usize| roles[v] == Role::Cauchy;
        let (l, r) = (tilt(&mesh, &p, crease, -1.0), tilt(&mesh, &p, crease, 1.0));
        eprintln!("crease: side tilts {l:.2}°, {r:.2}° (dihedral {:.2}°)", 180.0 - l - r);
        assert!((l - 45.0).abs() < 5.0 && (r - 45.0).abs() < 5.0, "{l} {r}");
        assert!(p.iter().all(|q| q.z <= 1e-9), "a ridge: both sides fall away");
    }

    #[test]
    fn ghost_basis_matches_direct_solves() {
        // [A11] eq. 4–5: K + W G equals a solve with the ghosts G, for any G.
        let n = 8;
        let m = 2 * n + 1;
        let (mesh, stencil) = grid(n);
        let mut roles = vec![Role::Free; m * m];
        for k in 0..m * m {
            let p = mesh.positions[k];
            if (p.x.abs() - 1.0).abs() < 1e-12 || (p.y.abs() - 1.0).abs() < 1e-12 || p.x.abs() < 1e-12 {
                roles[k] = Role::Cauchy;
            }
        }
        for order in [2, 3] {
            let system = System::build(&stencil, &roles, order, MicroWeight::Consistent).unwrap();
            let f = system.factor().unwrap();
            let basis = curvenet::methods::andrews2011::GhostBasis::new(&system, &f, &mesh.positions).unwrap();
            let ghosts: Vec<DVec3> = (0..system.ghosts.len())
                .map(|i| DVec3::new((i as f64 * 0.37).sin(), (i as f64 * 0.11).cos(), 0.01 * i as f64))
                .collect();
            let x = basis.evaluate(&ghosts);
            let direct = system.solve(&mesh.positions, &ghosts).unwrap();
            for (r, &v) in system.free.iter().enumerate() {
                let b = DVec3::new(x[(r, 0)], x[(r, 1)], x[(r, 2)]);
                assert!(b.distance(direct[v as usize]) < 1e-9, "order {order}: {b} vs {}", direct[v as usize]);
            }
        }
    }

    #[test]
    fn isolated_point_constraint_gives_a_cone() {
        let n = 16;
        let m = 2 * n + 1;
        let (mesh, stencil) = grid(n);
        let apex = n * m + n;
        let run = |sharp: f64| {
            let mut roles = vec![Role::Free; m * m];
            let mut params = vec![None; m * m];
            let mut fixed = mesh.positions.clone();
            for k in 0..m * m {
                let p = mesh.positions[k];
                if (p.x.abs() - 1.0).abs() < 1e-12 || (p.y.abs() - 1.0).abs() < 1e-12 {
                    roles[k] = Role::Position;
                }
            }
            roles[apex] = Role::Cauchy;
            fixed[apex].z = 0.5;
            params[apex] = Some(CauchyParams {
                orientation: DVec3::Z,
                initial_normal: Some(DVec3::Z),
                sharpness: sharp.to_radians(),
                stretch: 0.0,
                tangent: None,
            });
            let p = solve(&stencil, &roles, &params, &fixed);
            let near = |v: usize| v == apex;
            0.5 * (tilt(&mesh, &p, near, -1.0) + tilt(&mesh, &p, near, 1.0))
        };
        let (cone, flat) = (run(45.0), run(0.0));
        eprintln!("apex tilt: sharpness 45° → {cone:.2}°, 0° → {flat:.2}°");
        assert!((cone - 45.0).abs() < 5.0, "{cone}");
        // Without sharpness the apex is rounded (a point holds the tangent plane only locally).
        assert!(flat < cone - 15.0, "{flat} vs {cone}");
    }
}

#[test]
fn bundled_sketches_inflate_to_domes() {
    use curvenet::sketch::inflate::{inflate, read_sketch, InflateOptions};
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/sketches");
    for name in ["leaf.svg", "circle.svg"] {
        let paths = read_sketch(&dir.join(name)).unwrap();
        let s = inflate(&paths, &InflateOptions::default()).unwrap();
        let ratio = s.height / s.radius;
        eprintln!("{name}: height / radius {ratio:.3}, {} creases", s.creases);
        assert!(ratio > 0.3 && ratio < 1.5, "{name}: {ratio}");
    }
}

mod fitting {
    use curvenet::geom::DVec3;
    use curvenet::sketch::fit::{fit, resurface, FitOptions};
    use std::collections::HashMap;

    /// A box [0,2]×[0,1]×[0,1] with each face an n-grid (outward, counter-clockwise).
    fn boxed(n: i64) -> (Vec<DVec3>, Vec<[u32; 3]>) {
        let mut index: HashMap<[i64; 3], u32> = HashMap::new();
        let mut pos = Vec::new();
        let mut faces = Vec::new();
        let mut id = |c: [i64; 3], pos: &mut Vec<DVec3>| {
            *index.entry(c).or_insert_with(|| {
                pos.push(DVec3::new(2.0 * c[0] as f64 / n as f64, c[1] as f64 / n as f64, c[2] as f64 / n as f64));
                (pos.len() - 1) as u32
            })
        };
        for axis in 0..3 {
            for side in [0, n] {
                let (a, b) = ((axis + 1) % 3, (axis + 2) % 3);
                for i in 0..n {
                    for j in 0..n {
                        let c = |di: i64, dj: i64| {
                            let mut v = [0i64; 3];
                            v[axis] = side;
                            v[a] = i + di;
                            v[b] = j + dj;
                            v
                        };
                        let q = [c(0, 0), c(1, 0), c(1, 1), c(0, 1)].map(|v| id(v, &mut pos));
                        let t = if side == n {
                            [[q[0], q[1], q[2]], [q[0], q[2], q[3]]]
                        } else {
                            [[q[0], q[2], q[1]], [q[0], q[3], q[2]]]
                        };
                        faces.extend(t);
                    }
                }
            }
        }
        (pos, faces)
    }

    #[test]
    fn a_box_is_reproduced_from_its_edges() {
        let (p, f) = boxed(8);
        let (model, out, report) = fit(&p, &f, &FitOptions::default()).unwrap();
        eprintln!("box: {} features, max {:.2e}", report.feature_vertices, report.max_distance);
        assert!(report.max_distance < 1e-8 * report.diagonal, "{report:?}");
        let again = resurface(&model).unwrap();
        assert!(again.iter().zip(&out).all(|(a, b)| a.distance(*b) < 1e-9));
    }

    #[test]
    fn fandisk_refit_is_within_one_percent_of_the_diagonal() {
        let data = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../data/meshes");
        let path = data.join("fandisk.off");
        let m = curvenet::io::read_mesh(&path).unwrap();
        for order in [2, 3] {
            let (_, _, r) = fit(&m.positions, &m.faces, &FitOptions { order, ..Default::default() }).unwrap();
            let rel = r.rms_distance / r.diagonal;
            eprintln!(
                "fandisk k={order}: RMS {:.3}% of the diagonal, max {:.3}%",
                100.0 * rel,
                100.0 * r.max_distance / r.diagonal
            );
            assert!(rel <= 0.01, "{r:?}");
        }
        // The least-squares fit of the ghosts (complete setup, point to point) improves on the
        // naive guess.
        let (_, _, naive) = fit(&m.positions, &m.faces, &FitOptions::default()).unwrap();
        let (_, _, fitted) = fit(&m.positions, &m.faces, &FitOptions { optimize: true, ..Default::default() }).unwrap();
        eprintln!("fandisk k=2: RMS naive {:.3e}, fitted {:.3e}", naive.rms_distance, fitted.rms_distance);
        assert!(fitted.rms_distance < naive.rms_distance);
        {
            let m = curvenet::io::read_mesh(&data.join("bumpy-cube.obj")).unwrap();
            let o = FitOptions { order: 3, curvature_fraction: Some(0.1), ..Default::default() };
            let (_, _, r) = fit(&m.positions, &m.faces, &o).unwrap();
            let rel = r.rms_distance / r.diagonal;
            eprintln!("bumpy-cube k=3, 10% curvature features: RMS {:.3}% of the diagonal", 100.0 * rel);
            assert!(rel <= 0.01, "{r:?}");
        }
    }
}
