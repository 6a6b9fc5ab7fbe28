//! Invariants every surface the pipeline returns must satisfy, checked from the outside: the
//! fuzzers run [`check_surface`] on every output, and the tests use it too.
//!
//! The invariants (any failure is a bug in curvenet, not in the input):
//! 1. every position, normal and mean curvature is finite;
//! 2. every face has three distinct vertices in range and a non-zero area;
//! 3. the mesh is an edge-manifold: an edge has one or two faces;
//! 4. the orientation is consistent: two faces sharing an edge traverse it in opposite
//!    directions (so no directed edge appears twice);
//! 5. no silent hole: an edge with one face joins two vertices on boundary curves;
//! 6. with hard constraints, every input sample lies on the surface, within half the spacing
//!    plus twice the snapping tolerance plus a quarter of its longest input edge (the surface
//!    interpolates the curves' resampled splines, which pass through the samples; a node moves
//!    the nearest sample onto itself when it is within a quarter of an edge, and the hits
//!    within twice the tolerance merge into one node: [`crate::topology::nodes`]).

use crate::geom::mesh::for_each_edge;
use crate::geom::DVec3;
use crate::metrics::MeshDistance;
use crate::network::Network;
use crate::pipeline::Surface;

/// What [`check_surface`] verifies about the samples.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Constraints {
    /// Hard curve constraints: every input sample lies on the surface (invariant 6).
    Hard,
    /// Soft constraints: the surface may leave the samples; invariant 6 is not checked.
    Soft,
}

/// Checks the invariants listed in the module documentation on `surface`, the result of
/// surfacing `network` (as given, before validation) with snapping tolerance `snap`. Returns
/// one message per violated invariant (at most a few examples each); empty when all hold.
pub fn check_surface(surface: &Surface, network: &Network, snap: f64, constraints: Constraints) -> Vec<String> {
    let mut problems = Vec::new();
    let mesh = &surface.mesh;
    let p = &mesh.positions;
    let n = p.len();

    // 1. Finite values.
    if let Some(i) = p.iter().position(|x| !x.is_finite()) {
        problems.push(format!("vertex {i}: position {:?} is not finite", p[i]));
    }
    if let Some(i) = surface.normals.iter().position(|x| !x.is_finite()) {
        problems.push(format!("vertex {i}: normal is not finite"));
    }
    if let Some(i) = surface.mean_curvature.iter().position(|x| !x.is_finite()) {
        problems.push(format!("vertex {i}: mean curvature is not finite"));
    }
    if surface.normals.len() != n || surface.mean_curvature.len() != n || mesh.on_boundary.len() != n {
        problems.push("per-vertex attributes do not match the vertex count".into());
    }
    if mesh.faces.is_empty() {
        problems.push("the surface has no faces".into());
    }

    // 2. Faces.
    let mut bad_faces = 0;
    for (fi, f) in mesh.faces.iter().enumerate() {
        let [a, b, c] = f.map(|i| i as usize);
        if a >= n || b >= n || c >= n || a == b || b == c || a == c {
            if bad_faces == 0 {
                problems.push(format!("face {fi} {f:?}: repeated or out-of-range vertex"));
            }
            bad_faces += 1;
            continue;
        }
        let area2 = (p[b] - p[a]).cross(p[c] - p[a]).length();
        if !(area2 > 0.0) && problems.iter().all(|m| !m.contains("zero area")) {
            problems.push(format!("face {fi} {f:?} has zero area"));
        }
    }
    if bad_faces > 0 {
        return problems;
    }

    // 3–5. Edges: the faces on each undirected edge, and each directed edge's uses.
    let (mut non_manifold, mut flipped, mut holes) = (Vec::new(), Vec::new(), Vec::new());
    for_each_edge(&mesh.faces, |a, b, fwd, back| {
        if fwd + back > 2 {
            non_manifold.push((a, b));
        } else if fwd > 1 || back > 1 {
            flipped.push((a, b));
        } else if fwd + back == 1 && !(mesh.on_boundary[a as usize] && mesh.on_boundary[b as usize]) {
            holes.push((a, b));
        }
    });
    for (list, what) in [
        (non_manifold, "shared by more than two faces (non-manifold)"),
        (flipped, "traversed twice in the same direction (inconsistent orientation)"),
        (holes, "with one face but not on a boundary curve (a hole)"),
    ] {
        if !list.is_empty() {
            let mut list = list;
            list.sort_unstable();
            problems.push(format!("{} edge(s) {what}, e.g. {:?}", list.len(), &list[..list.len().min(3)]));
        }
    }

    // 6. Samples on the surface.
    if constraints == Constraints::Hard && !mesh.faces.is_empty() && problems.is_empty() {
        let bvh = MeshDistance::new(p, &mesh.faces);
        let base = 0.5 * surface.stats.spacing + 2.0 * snap;
        let mut worst: Option<(f64, usize, usize, DVec3, f64)> = None;
        for (ci, c) in network.curves.iter().enumerate() {
            let m = c.points.len();
            let edge = |a: usize, b: usize| c.points[a].distance(c.points[b]);
            for (si, q) in c.points.iter().enumerate() {
                let before = if si > 0 {
                    edge(si - 1, si)
                } else if c.closed {
                    edge(m - 1, 0)
                } else {
                    0.0
                };
                let after = if si + 1 < m {
                    edge(si, si + 1)
                } else if c.closed {
                    edge(m - 1, 0)
                } else {
                    0.0
                };
                let tolerance = base + 0.25 * before.max(after);
                let d = bvh.closest(*q).0;
                if d > tolerance && worst.is_none_or(|w| d - tolerance > w.0 - w.4) {
                    worst = Some((d, ci, si, *q, tolerance));
                }
            }
        }
        if let Some((d, ci, si, q, tolerance)) = worst {
            problems.push(format!(
                "curve {ci}, sample {si} at {q:?} is {d:.3e} from the surface (tolerance {tolerance:.3e})"
            ));
        }
    }
    problems
}

/// The property the network-reader fuzzers (`fuzz/fuzz_targets/read_{json,obj,net}.rs`)
/// check on arbitrary bytes read as `format`: the reader returns (never panics); an error has
/// a message; a network that validates has finite samples and unit normals. `Err` names the
/// violation (the fuzz target turns it into a crash).
pub fn check_network_reader(data: &[u8], format: crate::io::NetworkFormat) -> Result<(), String> {
    // read_network rejects non-UTF-8 before parsing (tested in the catalogue).
    let Ok(text) = std::str::from_utf8(data) else { return Ok(()) };
    match crate::io::parse_network(text, format, "fuzz") {
        Ok(net) => {
            let Ok((clean, _)) = net.validated() else { return Ok(()) };
            for (ci, c) in clean.curves.iter().enumerate() {
                if let Some(si) = c.points.iter().position(|p| !p.is_finite()) {
                    return Err(format!("validated curve {ci}, sample {si}: position not finite"));
                }
                if let Some(si) = c.normals.iter().position(|n| !((n.length() - 1.0).abs() < 1e-9)) {
                    return Err(format!("validated curve {ci}, sample {si}: normal not of unit length"));
                }
            }
            Ok(())
        }
        Err(e) if e.to_string().is_empty() => Err("an error without a message".into()),
        Err(_) => Ok(()),
    }
}

/// Decodes arbitrary bytes into a small network and options for the pipeline fuzzer
/// (`fuzz/fuzz_targets/pipeline.rs`) and its regression tests: one of the bundled networks
/// (sphere, cube, saddle, cylinder) subsampled to a few samples per curve, scaled, moved and
/// perturbed by the bytes (positions, normals, flags), or a few curves made of the bytes
/// alone; a vertex budget of 300–1000 keeps a run to milliseconds. `None` when `data` is
/// too short.
pub fn fuzz_case(data: &[u8]) -> Option<(Network, crate::Options)> {
    use crate::methods::iterated::IterationOptions;
    use crate::pipeline::{MeshOptions, Patching};
    use crate::{Curve, Method, Options};
    let (head, rest) = data.split_at_checked(8)?;
    let mut bytes = rest.iter().copied().cycle().take(rest.len().max(1) * 64);
    let mut next = || bytes.next().unwrap_or(0);
    let signed = |b: u8| (b as i8) as f64 / 128.0;
    let mut net = match head[0] % 5 {
        4 => {
            // Free-form: 1–4 curves of 2–9 samples on a coarse grid.
            let curves = (0..1 + head[1] % 4)
                .map(|_| {
                    let n = 2 + (next() % 8) as usize;
                    let flags = next();
                    let mut point = || DVec3::new(signed(next()), signed(next()), signed(next())) * 4.0;
                    let points: Vec<DVec3> = (0..n).map(|_| point()).collect();
                    let normals = (0..n).map(|_| DVec3::new(signed(next()), signed(next()), signed(next()))).collect();
                    Curve { points, normals, closed: flags & 1 != 0, boundary: flags & 2 != 0, ..Default::default() }
                })
                .collect();
            Network { curves, snap: None, cycles: None }
        }
        k => {
            let name = ["sphere", "cube", "saddle", "cylinder"][k as usize];
            let mut net = crate::network::examples::example(name)?;
            let keep = 4 + (head[1] % 16) as usize;
            for c in &mut net.curves {
                // Every `step`-th sample (a power of two, so that the bundled networks' crossings,
                // at multiples of a power of two, stay samples), and an open curve's last one.
                let len = c.points.len();
                let step = 1usize << (len / keep).max(1).ilog2();
                let kept = |k: usize| k % step == 0 || (!c.closed && k + 1 == len);
                c.points = (0..len).filter(|&k| kept(k)).map(|k| c.points[k]).collect();
                c.normals = (0..len).filter(|&k| kept(k)).map(|k| c.normals[k]).collect();
            }
            // Perturb: positions by up to `amp` of the spacing, normals by up to `amp`.
            let amp = [0.0, 0.01, 0.1, 0.5][(head[5] % 4) as usize];
            let spacing = net.mean_sample_spacing();
            for c in &mut net.curves {
                for (p, n) in c.points.iter_mut().zip(&mut c.normals) {
                    *p += DVec3::new(signed(next()), signed(next()), signed(next())) * amp * spacing;
                    *n += DVec3::new(signed(next()), signed(next()), signed(next())) * amp;
                }
            }
            // Occasionally flip one curve's normals, toggle a flag, or drop a curve.
            let which = (head[6] >> 4) as usize % net.curves.len();
            match head[6] % 8 {
                0 => net.curves[which].normals.iter_mut().for_each(|n| *n = -*n),
                1 => net.curves[which].boundary ^= true,
                2 => net.curves[which].closed ^= true,
                3 if net.curves.len() > 1 => {
                    net.curves.remove(which);
                }
                _ => {}
            }
            net
        }
    };
    // Scale by 10^(−12…12) and move by up to 10 sizes.
    let scale = 10f64.powi((head[4] % 25) as i32 - 12);
    let shift = DVec3::new(signed(head[7]), signed(head[7].rotate_left(3)), 0.0) * 10.0;
    for c in &mut net.curves {
        c.points.iter_mut().for_each(|p| *p = (*p + shift) * scale);
    }
    let options = Options {
        method: match head[2] % 16 {
            0 => Method::Biharmonic,
            1 => Method::Triharmonic,
            2 => Method::Method4,
            3 => Method::ShortPaper,
            _ => Method::NormalControl,
        },
        mesh: MeshOptions {
            patching: if head[2] & 16 != 0 { Patching::Planar } else { Patching::Conformal },
            vertices: Some(300 + 100 * (head[3] % 8) as usize),
            ..MeshOptions::default()
        },
        iterate: IterationOptions { iterations: ((head[2] >> 5) % 3) as usize, ..IterationOptions::default() },
        soft: (head[2] >> 7 == 1 && head[2] % 16 >= 3).then_some(2.0),
        ..Options::default()
    };
    Some((net, options))
}

#[cfg(test)]
#[path = "tests/check.rs"]
mod tests;
