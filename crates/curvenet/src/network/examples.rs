//! Bundled analytic networks with known ground truth (their ground truth: `crate::metrics::example_truth`).
//!
//! | name | network | truth |
//! |---|---|---|
//! | `sphere` | unit sphere, 3 great circles (6 nodes, 12 segments, 8 patches) | sphere r = 1 |
//! | `globe` | unit sphere, 8 meridians and 3 parallels (26 nodes, 32 patches; a denser network: ≈ 1k curve vertices at 10k vertices) | sphere r = 1 |
//! | `cube` | unit sphere traced by the 12 edges of a cube (8 nodes, 12 segments, 6 patches) | sphere r = 1 |
//! | `torus` | R = 4, r = 2: 4 meridians, outer and inner equators (8 patches) | torus |
//! | `cylinder` | two boundary circles r = 1 at z = ±1, radial normals | cylinder r = 1 |
//! | `barrel` | the same circles, normals tilted 30° away from the middle | — (mid radius > 1) |
//! | `bottleneck` | normals tilted 30° towards the middle | — (mid radius < 1) |
//! | `saddle` | z = (x² − y²)/2 over the unit disk: boundary circle + the two axes (4 patches) | saddle |
//! | `lens` | two unit-sphere caps meeting at a 60° crease circle (r = √3/2), two arcs over each cap (8 patches) | lens |
//! | `can` | closed cylinder r = 1, z ∈ [−1, 1]: two 90° crease rims, four side lines, two diameters per lid (12 patches) | can |

use crate::geom::DVec3;
use crate::network::{Curve, Network};
use std::f64::consts::{PI, TAU};

/// Names and one-line descriptions of the bundled examples.
pub const EXAMPLES: [(&str, &str); 10] = [
    ("sphere", "unit sphere: 3 great circles (6 nodes, 12 segments, 8 patches)"),
    ("globe", "unit sphere: 8 meridians and 3 parallels (26 nodes, 32 patches), 1 curve vertex in 10"),
    ("cube", "unit sphere traced by the 12 edges of a cube (8 nodes, 12 segments, 6 patches)"),
    ("torus", "torus R = 4, r = 2: 4 meridians and the outer and inner equators"),
    ("cylinder", "two boundary circles (r = 1, z = ±1) with radial normals: a tube"),
    ("barrel", "the cylinder's circles with normals tilted 30° outward: a barrel"),
    ("bottleneck", "the cylinder's circles with normals tilted 30° inward: a bottleneck"),
    ("saddle", "z = (x² − y²)/2 over the unit disk: boundary circle and the two axes"),
    ("lens", "two unit-sphere caps meeting at a 60° crease circle, two arcs over each cap"),
    ("can", "closed cylinder (r = 1, z = ±1): two 90° crease rims, 4 side lines, 2 diameters per lid"),
];

fn curve(name: &str, closed: bool, boundary: bool, samples: impl Iterator<Item = (DVec3, DVec3)>) -> Curve {
    let (points, normals) = samples.unzip();
    Curve { name: Some(name.to_string()), points, normals, closed, boundary, ..Default::default() }
}

/// `n` parameters `a + (b − a) k / n`, `k = 0..n` (closed: the end excluded) or `0..=n`.
fn params(a: f64, b: f64, n: usize, closed: bool) -> impl Iterator<Item = f64> {
    let m = if closed { n } else { n + 1 };
    (0..m).map(move |k| a + (b - a) * k as f64 / n as f64)
}

fn sphere() -> Network {
    // Crossings at multiples of 90° fall on samples (128 per circle).
    let n = 128;
    type Circle = (&'static str, fn(f64, f64) -> DVec3);
    let circles: [Circle; 3] = [
        ("equator z=0", |c, s| DVec3::new(c, s, 0.0)),
        ("meridian x=0", |c, s| DVec3::new(0.0, c, s)),
        ("meridian y=0", |c, s| DVec3::new(s, 0.0, c)),
    ];
    Network {
        curves: circles
            .iter()
            .map(|(name, f)| {
                curve(name, true, false, params(0.0, TAU, n, true).map(|t| (f(t.cos(), t.sin()), f(t.cos(), t.sin()))))
            })
            .collect(),
        snap: None,
        cycles: None,
    }
}

fn globe() -> Network {
    // Meridians from pole to pole every 45°, parallels at 0° and ±45°: crossings on samples.
    let at = |lat: f64, lon: f64| {
        let p = DVec3::new(lat.cos() * lon.cos(), lat.cos() * lon.sin(), lat.sin());
        (p, p)
    };
    let mut curves = Vec::new();
    for k in 0..8 {
        let lon = k as f64 * PI / 4.0;
        curves.push(curve(
            &format!("meridian {}°", k * 45),
            false,
            false,
            params(-PI / 2.0, PI / 2.0, 64, false).map(|lat| at(lat, lon)),
        ));
    }
    for lat_deg in [-45i32, 0, 45] {
        let lat = (lat_deg as f64).to_radians();
        curves.push(curve(
            &format!("parallel {lat_deg}°"),
            true,
            false,
            params(0.0, TAU, 128, true).map(|lon| at(lat, lon)),
        ));
    }
    Network { curves, snap: None, cycles: None }
}

fn cube() -> Network {
    let corners: Vec<DVec3> =
        (0..8).map(|i| DVec3::new([-1.0, 1.0][i & 1], [-1.0, 1.0][(i >> 1) & 1], [-1.0, 1.0][(i >> 2) & 1])).collect();
    let mut curves = Vec::new();
    for a in 0..8 {
        for bit in [1, 2, 4] {
            let b = a | bit;
            if b == a {
                continue;
            }
            let (p, q) = (corners[a], corners[b]);
            // Edge of the cube projected radially onto the unit sphere: a great-circle arc.
            let samples = params(0.0, 1.0, 48, false).map(|t| {
                let x = p.lerp(q, t).normalize();
                (x, x)
            });
            curves.push(curve(&format!("edge {a}-{b}"), false, false, samples));
        }
    }
    Network { curves, snap: None, cycles: None }
}

/// Torus point and outward normal at angles `(φ, θ)` (axis z).
pub(crate) fn torus_point(big_r: f64, r: f64, phi: f64, theta: f64) -> (DVec3, DVec3) {
    let n = DVec3::new(theta.cos() * phi.cos(), theta.cos() * phi.sin(), theta.sin());
    let p = DVec3::new((big_r + r * theta.cos()) * phi.cos(), (big_r + r * theta.cos()) * phi.sin(), r * theta.sin());
    (p, n)
}

/// Torus with 4 meridians and the outer and inner equators.
pub fn torus(big_r: f64, r: f64) -> Network {
    let mut curves = Vec::new();
    for k in 0..4 {
        let phi = k as f64 * PI / 2.0;
        curves.push(curve(
            &format!("meridian {}", 90 * k),
            true,
            false,
            params(0.0, TAU, 64, true).map(|t| torus_point(big_r, r, phi, t)),
        ));
    }
    curves.push(curve(
        "outer equator",
        true,
        false,
        params(0.0, TAU, 192, true).map(|t| torus_point(big_r, r, t, 0.0)),
    ));
    curves.push(curve("inner equator", true, false, params(0.0, TAU, 64, true).map(|t| torus_point(big_r, r, t, PI))));
    Network { curves, snap: None, cycles: None }
}

/// Two boundary circles r = 1 at z = ±1 with normals tilted by `tilt` (radians) away from the
/// middle (positive: barrel) or towards it (negative: bottleneck).
pub fn tube(tilt: f64) -> Network {
    let ring = |z: f64, name: &str| {
        let up = if z > 0.0 { 1.0 } else { -1.0 };
        curve(
            name,
            true,
            true,
            params(0.0, TAU, 64, true).map(move |t| {
                let radial = DVec3::new(t.cos(), t.sin(), 0.0);
                (radial + DVec3::Z * z, tilt.cos() * radial + up * tilt.sin() * DVec3::Z)
            }),
        )
    };
    Network { curves: vec![ring(1.0, "top"), ring(-1.0, "bottom")], snap: None, cycles: None }
}

fn saddle() -> Network {
    let f = |x: f64, y: f64| 0.5 * (x * x - y * y);
    let sample = move |x: f64, y: f64| (DVec3::new(x, y, f(x, y)), DVec3::new(-x, y, 1.0).normalize());
    Network {
        curves: vec![
            curve("rim", true, true, params(0.0, TAU, 128, true).map(move |t| sample(t.cos(), t.sin()))),
            curve("x axis", false, false, params(-1.0, 1.0, 64, false).map(move |x| sample(x, 0.0))),
            curve("y axis", false, false, params(-1.0, 1.0, 64, false).map(move |y| sample(0.0, y))),
        ],
        snap: None,
        cycles: None,
    }
}

/// A crease curve through `samples` of `(position, left normal, right normal)`.
fn crease(name: &str, closed: bool, samples: impl Iterator<Item = (DVec3, DVec3, DVec3)>) -> Curve {
    let (mut points, mut normals, mut right) = (Vec::new(), Vec::new(), Vec::new());
    for (p, l, r) in samples {
        points.push(p);
        normals.push(l);
        right.push(r);
    }
    Curve { name: Some(name.to_string()), points, normals, normals_right: right, closed, ..Default::default() }
}

/// The lens: the boundary of the intersection of two unit balls centred at `z = ±½`. Its
/// caps meet at the circle `z = 0`, `r = √3/2`, with normals 60° apart (a 60° crease); the
/// crease runs counter-clockwise seen from above, so the upper cap is on its left.
fn lens() -> Network {
    let (a, h) = (0.75f64.sqrt(), 0.5);
    let rim = params(0.0, TAU, 128, true).map(move |t| {
        let (c, s) = (t.cos(), t.sin());
        (DVec3::new(a * c, a * s, 0.0), DVec3::new(a * c, a * s, h), DVec3::new(a * c, a * s, -h))
    });
    let mut curves = vec![crease("rim", true, rim)];
    let top = PI / 3.0;
    for (k, up) in [(0, 1.0), (1, 1.0), (0, -1.0), (1, -1.0)] {
        // Arcs over a cap in the planes y = 0 and x = 0: centre (0, 0, −up·h), polar angle φ.
        let dir = if k == 0 { DVec3::X } else { DVec3::Y };
        let arc = params(-top, top, 64, false).map(move |phi| {
            let n = dir * phi.sin() + DVec3::Z * (up * phi.cos());
            (n - DVec3::Z * (up * h), n)
        });
        let name = format!("{} arc {}", if up > 0.0 { "upper" } else { "lower" }, if k == 0 { "xz" } else { "yz" });
        curves.push(curve(&name, false, false, arc));
    }
    Network { curves, snap: None, cycles: None }
}

/// The closed cylinder r = 1, z ∈ [−1, 1]: two crease rims (90°), four side lines and two
/// diameters on each lid. Both rims run counter-clockwise seen from above: the top lid lies on
/// the left of the top rim, the side on the left of the bottom rim.
fn can() -> Network {
    let rim = |z: f64| {
        params(0.0, TAU, 128, true).map(move |t| {
            let radial = DVec3::new(t.cos(), t.sin(), 0.0);
            let (lid, side) = (DVec3::Z * z.signum(), radial);
            let (l, r) = if z > 0.0 { (lid, side) } else { (side, lid) };
            (radial + DVec3::Z * z, l, r)
        })
    };
    let mut curves = vec![crease("top rim", true, rim(1.0)), crease("bottom rim", true, rim(-1.0))];
    for k in 0..4 {
        let t = k as f64 * PI / 2.0;
        let radial = DVec3::new(t.cos(), t.sin(), 0.0);
        curves.push(curve(
            &format!("side {}", 90 * k),
            false,
            false,
            params(-1.0, 1.0, 32, false).map(move |z| (radial + DVec3::Z * z, radial)),
        ));
    }
    for z in [1.0f64, -1.0] {
        for (name, dir) in [("x", DVec3::X), ("y", DVec3::Y)] {
            let lid = if z > 0.0 { "top" } else { "bottom" };
            curves.push(curve(
                &format!("{lid} diameter {name}"),
                false,
                false,
                params(-1.0, 1.0, 32, false).map(move |u| (dir * u + DVec3::Z * z, DVec3::Z * z.signum())),
            ));
        }
    }
    Network { curves, snap: None, cycles: None }
}

/// The bundled example `name` (see [`EXAMPLES`]).
pub fn example(name: &str) -> Option<Network> {
    Some(match name {
        "sphere" => sphere(),
        "globe" => globe(),
        "cube" => cube(),
        "torus" => torus(4.0, 2.0),
        "cylinder" => tube(0.0),
        "barrel" => tube(30f64.to_radians()),
        "bottleneck" => tube(-(30f64.to_radians())),
        "saddle" => saddle(),
        "lens" => lens(),
        "can" => can(),
        _ => return None,
    })
}
