//! Networks without normals (issue 15): analytic networks and networks sampled from the
//! vendored meshes, their normals removed, surfaced and measured against the truth and against
//! the same build with the normals given.

use curvenet::geom::{Aabb, DVec3};
use curvenet::metrics::{distance_to_truth, evaluate, example_truth, Reference};
use curvenet::network::examples::example;
use curvenet::sampling::{sample_mesh, SampleOptions};
use curvenet::{surface, Network, Options};

/// RMS distance of the surface of `net` to the truth of example `name`.
fn rms_to_truth(name: &str, net: &Network, options: &Options) -> f64 {
    let s = surface(net, options).unwrap_or_else(|e| panic!("{name}: {e}"));
    // Every cycle filled: no open border but the boundary curves' (a hole would be a warning).
    assert!(!s.warnings.iter().any(|w| w.message.contains("the surface is open along")), "{name}: {:?}", s.warnings);
    // Measured where normals were inferred (with the coverage); none open either way.
    assert_eq!(s.stats.open_borders.is_some(), !net.has_all_normals(), "{name}");
    assert_eq!(s.stats.open_borders.unwrap_or(0), 0, "{name}");
    distance_to_truth(&s.mesh.positions, 0, &example_truth(name).unwrap()).rms
}

#[test]
fn analytic_examples_without_normals_are_within_three_times_the_error_with() {
    let options = Options::default().with_vertices(10_000);
    for name in ["sphere", "globe", "cube", "torus", "cylinder", "saddle"] {
        let net = example(name).unwrap();
        let with = rms_to_truth(name, &net, &options);
        let without = rms_to_truth(name, &net.without_normals(), &options);
        let diag = net.bounding_box().diagonal();
        eprintln!("{name}: with {with:.3e}, without {without:.3e} ({:.4}% of the diagonal)", 100.0 * without / diag);
        assert!(without <= (3.0 * with).max(2e-3 * diag), "{name}: without normals {without:.3e}, with {with:.3e}");
    }
}

/// Reads a vendored mesh (`data/meshes/NAME`).
fn vendored(name: &str) -> (Vec<DVec3>, Vec<[u32; 3]>) {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../data/meshes").join(name);
    let m = curvenet::io::read_mesh(&path).unwrap();
    (m.positions, m.faces)
}

#[test]
fn sampled_meshes_without_normals_are_within_three_times_the_error_with() {
    for name in ["bumpy-cube.obj", "beetle.off"] {
        let (p, f) = vendored(name);
        // Smooth curves only: the inference gives one normal per sample (a crease's two sides
        // are not inferred), so both sides of the comparison are sampled without creases.
        let opts = SampleOptions { crease_angle: None, ..SampleOptions::default() };
        let (net, _) = sample_mesh(&p, &f, &opts).unwrap();
        let diag = Aabb::of(p.iter().copied()).diagonal();
        let measure = |net: &Network| {
            let s = surface(net, &Options::default().with_vertices(20_000)).unwrap_or_else(|e| panic!("{name}: {e}"));
            let e = evaluate(
                &s.mesh.positions,
                &s.mesh.faces,
                Some(&s.normals),
                &s.curve_flags,
                Reference::Mesh { positions: &p, faces: &f },
                None,
            );
            e.distance.rms
        };
        let with = measure(&net);
        let without = measure(&net.without_normals());
        eprintln!("{name}: with {:.4}%, without {:.4}% of the diagonal", 100.0 * with / diag, 100.0 * without / diag);
        assert!(without <= (3.0 * with).max(2e-3 * diag), "{name}: without normals {without:.3e}, with {with:.3e}");
    }
}

/// The vendored 3D sketches (`data/sketches`, CASSIE, no normals) that surface today (5 of 6), with the
/// share of their input vertices within 0.5% of the diagonal of the surface.
#[test]
fn sketches_without_normals_surface_through_their_strokes() {
    use curvenet::metrics::MeshDistance;
    // The shield stopped on overlapping patches before the cycles were chosen together; all
    // five are the search's now, none falls back to the rotation walk.
    for name in ["computer-mouse.obj", "hat.obj", "teapot.obj", "vacuum.obj", "shield.obj"] {
        let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../data/sketches").join(name);
        let net = curvenet::io::read_network(&path).unwrap();
        assert!(net.curves.iter().all(|c| !c.has_normals()));
        let s = surface(&net, &Options::default()).unwrap_or_else(|e| panic!("{name}: {e}"));
        assert!(curvenet::geom::mesh::bad_edge(&s.mesh.faces).is_none(), "{name}: not manifold");
        let inferred = s.stats.inferred_normals.as_ref().expect("inferred");
        assert_eq!(inferred.curves, net.curves.len() - inferred.left_out);
        assert!(!inferred.walk_fallback && inferred.chosen_cycles > 0, "{name}: the cycles were not the search's");
        let diag = net.bounding_box().diagonal();
        let d = MeshDistance::new(&s.mesh.positions, &s.mesh.faces);
        let samples: Vec<DVec3> = net.curves.iter().flat_map(|c| c.points.iter().copied()).collect();
        // The shield's ornaments are loops drawn on it: their own disks are left out (details
        // drawn on the surface, `pipeline::details`) and the shield is pulled onto them.
        let within = 5e-3;
        let near = samples.iter().filter(|p| d.closest(**p).0 <= within * diag).count();
        let share = near as f64 / samples.len() as f64;
        eprintln!("{name}: {:.1}% of the input vertices within {:.1}% of the diagonal", 100.0 * share, 100.0 * within);
        assert!(share >= 0.95, "{name}: only {:.1}% of the input vertices near the surface", 100.0 * share);
        if name == "shield.obj" {
            assert!(s.warnings.iter().any(|w| w.message.contains("taken as details drawn on it")), "{name}");
        }
        // The teapot's greedy choice left a side panel open (issue 30; the run said so): the
        // open sides of its border segments, traced again with their neighbours' normals, close it.
        if name == "teapot.obj" {
            assert!(!s.warnings.iter().any(|w| w.message.contains("the surface is open along")), "{:?}", s.warnings);
            assert_eq!(s.stats.open_borders, Some(0));
        }
    }
}

/// The neatened `flower` (issue 30): six petals, each a closed stroke that touches the rest at
/// one of the flower's two centres only, in a plane of its own. One node normal cannot serve
/// them (the run stopped on a normal that turned by 135° along a petal); each petal is now a
/// sheet of its own — tagged boundary by the inference, kept apart by node finding — with a
/// vertex of its own at the centre, and lies on the surface.
#[test]
fn a_flowers_petals_are_sheets_of_their_own() {
    use curvenet::metrics::MeshDistance;
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../data/sketches/flower.obj");
    let net = curvenet::io::read_network(&path).unwrap();
    let s = surface(&net, &Options::default()).unwrap_or_else(|e| panic!("flower: {e}"));
    assert!(curvenet::geom::mesh::bad_edge(&s.mesh.faces).is_none(), "flower: not manifold");
    let petals: Vec<&str> = s
        .warnings
        .iter()
        .map(|w| w.message.as_str())
        .filter(|m| m.contains("closed curves tagged boundary that touch the network at one place only"))
        .collect();
    assert_eq!(petals.len(), 2, "{petals:?}");
    assert!(petals.iter().all(|m| m.matches("curve at line").count() >= 3), "{petals:?}");
    let diag = net.bounding_box().diagonal();
    let d = MeshDistance::new(&s.mesh.positions, &s.mesh.faces);
    let loops: Vec<&curvenet::Curve> = net.curves.iter().filter(|c| c.closed).collect();
    assert_eq!(loops.len(), 6);
    for c in loops {
        let far = c.points.iter().map(|p| d.closest(*p).0).fold(0.0, f64::max);
        assert!(far <= 2e-3 * diag, "a petal {:?} is {:.2e} of the diagonal from the surface", c.name, far / diag);
    }
    // Both leaves (the second's tip strokes coincide over its tip: cut back to where they part
    // by consolidation) and the petals: 91.8 % of the samples within 1 % of the diagonal (62 %
    // without the second leaf); the stem and the roots are single strokes.
    let samples: Vec<DVec3> = net.curves.iter().flat_map(|c| c.points.iter().copied()).collect();
    let near = samples.iter().filter(|p| d.closest(**p).0 <= 1e-2 * diag).count() as f64 / samples.len() as f64;
    assert!(near >= 0.9, "flower: {:.1} % of the samples near the surface", 100.0 * near);
    // A vertex per petal at each centre: the mesh's vertices there are several.
    for m in &petals {
        let at = m.split("near (").nth(1).and_then(|r| r.split(')').next()).unwrap();
        let p: Vec<f64> = at.split(", ").map(|x| x.parse().unwrap()).collect();
        let p = DVec3::new(p[0], p[1], p[2]);
        let close = s.mesh.positions.iter().filter(|q| q.distance(p) <= 1e-3 * diag).count();
        assert!(close >= 3, "{close} vertices near {p}");
    }
}

/// A closed curve through `f(2πk/n)`, `k < n`, with normals `g` (the truth's).
fn closed(n: usize, f: impl Fn(f64) -> DVec3, g: impl Fn(DVec3) -> DVec3, boundary: bool) -> curvenet::Curve {
    let points: Vec<DVec3> = (0..n).map(|k| f(std::f64::consts::TAU * k as f64 / n as f64)).collect();
    let normals = points.iter().map(|&p| g(p)).collect();
    curvenet::Curve { name: None, points, normals, closed: true, boundary, ..Default::default() }
}

/// The network as an OBJ edge soup: vertices shared by position, one `l a b` per edge, the
/// boundary curves under `g boundary` — as an exporter writes it.
fn edge_soup(net: &Network) -> Network {
    let mut ids: std::collections::HashMap<[i64; 3], usize> = std::collections::HashMap::new();
    let (mut v, mut lines) = (String::new(), [String::new(), String::new()]);
    for c in &net.curves {
        let mut k: Vec<usize> = c
            .points
            .iter()
            .map(|p| {
                let key = [(p.x * 1e9).round() as i64, (p.y * 1e9).round() as i64, (p.z * 1e9).round() as i64];
                let n = ids.len() + 1;
                *ids.entry(key).or_insert_with(|| {
                    v.push_str(&format!("v {} {} {}\n", p.x, p.y, p.z));
                    n
                })
            })
            .collect();
        if c.closed {
            k.push(k[0]);
        }
        for w in k.windows(2) {
            lines[c.boundary as usize].push_str(&format!("l {} {}\n", w[0], w[1]));
        }
    }
    let text = format!("{v}g curves\n{}g boundary\n{}", lines[0], lines[1]);
    curvenet::io::parse_network(&text, curvenet::io::NetworkFormat::Obj, "soup.obj").unwrap()
}

#[test]
fn ellipsoid_tori_and_cone_without_normals_as_json_and_edge_soup() {
    use std::f64::consts::TAU;
    let (a, b, c) = (2.0, 1.5, 1.0);
    let ellipsoid = Network {
        curves: vec![
            closed(160, |u| DVec3::new(a * u.cos(), b * u.sin(), 0.0), |p| p / DVec3::new(a * a, b * b, c * c), false),
            closed(160, |u| DVec3::new(0.0, b * u.cos(), c * u.sin()), |p| p / DVec3::new(a * a, b * b, c * c), false),
            closed(160, |u| DVec3::new(a * u.sin(), 0.0, c * u.cos()), |p| p / DVec3::new(a * a, b * b, c * c), false),
        ],
        snap: None,
        cycles: None,
    };
    let torus = |big: f64, r: f64| {
        let normal = move |p: DVec3| p - DVec3::new(p.x, p.y, 0.0).normalize() * big;
        let mut curves: Vec<curvenet::Curve> = (0..4)
            .map(|k| {
                let ph = TAU * k as f64 / 4.0;
                closed(
                    160,
                    move |t| DVec3::new((big + r * t.cos()) * ph.cos(), (big + r * t.cos()) * ph.sin(), r * t.sin()),
                    normal,
                    false,
                )
            })
            .collect();
        for rr in [big + r, big - r] {
            curves.push(closed(160, move |t| DVec3::new(rr * t.cos(), rr * t.sin(), 0.0), normal, false));
        }
        Network { curves, snap: None, cycles: None }
    };
    // The cone z = 2 − ρ (45°) between ρ = 0.5 and 1.5: boundary circles, a middle circle and six
    // rulings.
    let cone_normal = |p: DVec3| DVec3::new(p.x, p.y, 0.0).normalize() + DVec3::Z;
    let mut cone = Network { curves: Vec::new(), snap: None, cycles: None };
    for rr in [0.5, 1.0, 1.5] {
        cone.curves.push(closed(
            160,
            move |t| DVec3::new(rr * t.cos(), rr * t.sin(), 2.0 - rr),
            cone_normal,
            rr != 1.0,
        ));
    }
    for k in 0..6 {
        let ph = TAU * k as f64 / 6.0;
        let points: Vec<DVec3> = (0..=40)
            .map(|j| 0.5 + j as f64 / 40.0)
            .map(|rr| DVec3::new(rr * ph.cos(), rr * ph.sin(), 2.0 - rr))
            .collect();
        let normals = points.iter().map(|&p| cone_normal(p)).collect();
        cone.curves.push(curvenet::Curve {
            name: None,
            points,
            normals,
            closed: false,
            boundary: false,
            ..Default::default()
        });
    }
    type Distance = Box<dyn Fn(DVec3) -> f64>;
    let cases: Vec<(&str, Network, Distance)> = vec![
        ("ellipsoid", ellipsoid, {
            let t = curvenet::metrics::Truth::Ellipsoid { axes: DVec3::new(a, b, c) };
            Box::new(move |p| t.distance(p))
        }),
        ("torus 4, 2", torus(4.0, 2.0), {
            let t = curvenet::metrics::Truth::Torus { major: 4.0, minor: 2.0 };
            Box::new(move |p| t.distance(p))
        }),
        ("torus 3, 1", torus(3.0, 1.0), {
            let t = curvenet::metrics::Truth::Torus { major: 3.0, minor: 1.0 };
            Box::new(move |p| t.distance(p))
        }),
        ("cone", cone, Box::new(|p: DVec3| (p.z - (2.0 - p.x.hypot(p.y))).abs() / 2f64.sqrt())),
    ];
    let options = Options::default().with_vertices(10_000);
    for (name, net, distance) in cases {
        let rms = |net: &Network| {
            let s = surface(net, &options).unwrap_or_else(|e| panic!("{name}: {e}"));
            let d: Vec<f64> = s.mesh.positions.iter().map(|&p| distance(p)).collect();
            (d.iter().map(|x| x * x).sum::<f64>() / d.len() as f64).sqrt()
        };
        let diag = net.bounding_box().diagonal();
        let with = rms(&net);
        let limit = (3.0 * with).max(2e-3 * diag);
        for (form, bare) in [("JSON", net.without_normals()), ("edge soup", edge_soup(&net))] {
            assert!(!bare.curves.iter().any(|c| c.has_normals()));
            let without = rms(&bare);
            eprintln!("{name} ({form}): with {with:.3e}, without {without:.3e}");
            assert!(without <= limit, "{name} ({form}): without normals {without:.3e}, with {with:.3e}");
        }
    }
}

#[test]
fn wireframes_and_lone_loops_without_normals() {
    let parse = |text: &str| curvenet::io::parse_network(text, curvenet::io::NetworkFormat::Obj, "t.obj").unwrap();
    // A cube's 12 edges, one `l a b` each: corners where three curves leave to one side.
    let mut text = String::new();
    let corners: Vec<[i32; 3]> = (0..8).map(|i| [i & 1, (i >> 1) & 1, (i >> 2) & 1]).collect();
    for c in &corners {
        text.push_str(&format!("v {} {} {}\n", c[0], c[1], c[2]));
    }
    for a in 0..8 {
        for b in a + 1..8 {
            if (0..3).map(|k| (corners[a][k] - corners[b][k]).abs()).sum::<i32>() == 1 {
                text.push_str(&format!("l {} {}\n", a + 1, b + 1));
            }
        }
    }
    let s = surface(&parse(&text), &Options::default().with_vertices(3000)).unwrap();
    assert_eq!(s.stats.cycles, 6);
    assert!(curvenet::geom::mesh::bad_edge(&s.mesh.faces).is_none());
    // Outward: the surface's vertex normals point away from the cube's centre on the whole.
    let c = DVec3::splat(0.5);
    let out: f64 = s.mesh.positions.iter().zip(&s.normals).map(|(p, n)| n.dot(*p - c)).sum();
    assert!(out > 0.0);
    // A lone square outline is a flat disk.
    let s = surface(
        &parse("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nl 1 2\nl 2 3\nl 3 4\nl 4 1\n"),
        &Options::default().with_vertices(2000),
    )
    .unwrap();
    assert_eq!(s.stats.cycles, 1);
    assert!(s.mesh.positions.iter().all(|p| p.z.abs() < 1e-9));
    // Two parallel circles, no normals, no boundary tags: the cylinder between them.
    let cyl = example("cylinder").unwrap();
    let mut bare = cyl.without_normals();
    bare.curves.iter_mut().for_each(|c| c.boundary = false);
    let s = surface(&bare, &Options::default().with_vertices(4000)).unwrap();
    let truth = example_truth("cylinder").unwrap();
    assert!(distance_to_truth(&s.mesh.positions, 0, &truth).max < 1e-3);
}

/// The vendored sketches as separate strokes that cross without sharing a vertex: every curve
/// keeps its own samples, each moved by a deterministic jitter of about 2·10⁻⁴ of the diagonal
/// (crossings become near misses within the snapping tolerance). Not yet: the hat (its small
/// flower ornament's patches fold over each other) and the teapot (89.9 % of the input
/// vertices near the surface: strokes left out).
#[test]
fn sketches_as_separate_strokes_surface_too() {
    use curvenet::metrics::MeshDistance;
    for name in ["computer-mouse.obj", "vacuum.obj"] {
        let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../data/sketches").join(name);
        let soup = curvenet::io::read_network(&path).unwrap();
        let diag = soup.bounding_box().diagonal();
        let mut state = 0x2545_f491_4f6c_dd1du64;
        let mut jitter = || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            ((state >> 11) as f64 / (1u64 << 53) as f64 - 0.5) * 4e-4 * diag
        };
        let mut strokes = soup.clone();
        for c in &mut strokes.curves {
            c.boundary = false;
            for p in &mut c.points {
                *p += DVec3::new(jitter(), jitter(), jitter());
            }
        }
        let s = surface(&strokes, &Options::default()).unwrap_or_else(|e| panic!("{name}: {e}"));
        assert!(curvenet::geom::mesh::bad_edge(&s.mesh.faces).is_none(), "{name}: not manifold");
        let d = MeshDistance::new(&s.mesh.positions, &s.mesh.faces);
        let samples: Vec<DVec3> = strokes.curves.iter().flat_map(|c| c.points.iter().copied()).collect();
        let share = samples.iter().filter(|p| d.closest(**p).0 <= 5e-3 * diag).count() as f64 / samples.len() as f64;
        eprintln!("{name} as strokes: {:.1}% of the input vertices within 0.5% of the diagonal", 100.0 * share);
        assert!(share >= 0.95, "{name}: only {:.1}% of the input vertices near the surface", 100.0 * share);
    }
}
