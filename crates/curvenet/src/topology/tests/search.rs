use super::*;
use crate::network::examples::example;
use crate::network::{Curve, Network};
use crate::topology::{find_nodes, find_patches, trim_dangling};
use std::collections::BTreeSet;

/// The graph of `net` with its normals removed (zero: unknown), trimmed of dangling parts,
/// and its splines.
fn unknown(net: &Network) -> (Graph, Vec<CurveSpline>) {
    let (mut net, _) = net.without_normals().validated().unwrap();
    for c in &mut net.curves {
        c.normals = vec![DVec3::ZERO; c.points.len()];
    }
    let (mut g, _) = find_nodes(&net, net.snap_tolerance()).unwrap();
    trim_dangling(&mut g).unwrap();
    let splines = g.curves.iter().map(|c| CurveSpline::fit(&c.points, &c.normals, c.closed)).collect();
    (g, splines)
}

/// A cycle as the set of its segments' places on the curves, whatever the graph's numbering.
fn places(g: &Graph, cycle: &[HalfEdge]) -> BTreeSet<(usize, usize, usize)> {
    cycle
        .iter()
        .map(|h| {
            let s = &g.segments[h.segment];
            (s.curve, s.first, s.last)
        })
        .collect()
}

/// An open polyline from `a` to `b` in `n` pieces.
fn line(a: DVec3, b: DVec3, n: usize) -> Curve {
    Curve { points: (0..=n).map(|i| a.lerp(b, i as f64 / n as f64)).collect(), ..Default::default() }
}

/// A closed curve through `f(2πk/n)`, `k < n`.
fn closed(n: usize, f: impl Fn(f64) -> DVec3) -> Curve {
    let points = (0..n).map(|k| f(std::f64::consts::TAU * k as f64 / n as f64)).collect();
    Curve { points, closed: true, ..Default::default() }
}

/// Every segment of the choice bounds at most two patches, and every patch that shares a
/// segment with another runs along it the other way (one orientation).
fn check_manifold_and_oriented(g: &Graph, c: &Choice) {
    let mut runs: Vec<Vec<bool>> = vec![Vec::new(); g.segments.len()];
    for p in &c.patches {
        for h in &p.cycle {
            runs[h.segment].push(h.forward);
        }
    }
    for (s, r) in runs.iter().enumerate() {
        assert!(r.len() <= 2, "segment {s} bounds {} patches", r.len());
        if r.len() == 2 {
            assert_ne!(r[0], r[1], "segment {s}: both patches run along it the same way");
        }
        assert_eq!(c.uses[s] as usize, r.len());
    }
}

#[test]
fn analytic_networks_without_normals_get_the_walks_cycles() {
    // The rotation walk on the true normals gives the right patches of these networks: the
    // search, which sees no normal, must find the same cycles.
    for name in ["sphere", "globe", "cube", "torus", "lens"] {
        let net = example(name).unwrap();
        let (g, splines) = {
            let (net, _) = net.validated().unwrap();
            let (g, _) = find_nodes(&net, net.snap_tolerance()).unwrap();
            let splines: Vec<CurveSpline> =
                g.curves.iter().map(|c| CurveSpline::fit(&c.points, &c.normals, c.closed)).collect();
            (g, splines)
        };
        let truth: BTreeSet<BTreeSet<_>> =
            find_patches(&g, &splines).unwrap().iter().map(|p| places(&g, &p.half_edges())).collect();
        let (u, usplines) = unknown(&net);
        let choice = choose_cycles(&u, &usplines);
        let chosen: BTreeSet<BTreeSet<_>> = choice.patches.iter().map(|p| places(&u, &p.cycle)).collect();
        assert_eq!(chosen, truth, "{name}: the search's cycles differ from the walk's on the true normals");
        check_manifold_and_oriented(&u, &choice);
        assert!(choice.uses.iter().all(|&k| k == 2), "{name}: a closed network has no border");
    }
}

#[test]
fn closed_parts_face_outward() {
    // The sphere's patches, oriented by the search: counter-clockwise seen from outside, so
    // the normals it carries point away from the centre.
    let (g, splines) = unknown(&example("sphere").unwrap());
    let choice = choose_cycles(&g, &splines);
    for p in &choice.patches {
        for (h, n) in p.cycle.iter().zip(&p.normals) {
            let seg = &g.segments[h.segment];
            let at = g.nodes[if h.forward { seg.start } else { seg.end }].position;
            assert!(n.dot(at) > 0.5, "normal {n} at {at} points inward");
        }
    }
}

#[test]
fn a_flat_grid_is_an_open_sheet() {
    // Four lines each way on the plane z = 0: nine cells, and no patch for the outside (it
    // folds onto the cells along the border).
    let mut curves = Vec::new();
    for i in 0..4 {
        let x = i as f64;
        curves.push(line(DVec3::new(x, 0.0, 0.0), DVec3::new(x, 3.0, 0.0), 30));
        curves.push(line(DVec3::new(0.0, x, 0.0), DVec3::new(3.0, x, 0.0), 30));
    }
    let (g, splines) = unknown(&Network { curves, snap: None, cycles: None });
    let choice = choose_cycles(&g, &splines);
    check_manifold_and_oriented(&g, &choice);
    assert_eq!(choice.patches.len(), 9);
    assert!(choice.patches.iter().all(|p| p.cycle.len() == 4));
    let border = choice.uses.iter().filter(|&&k| k == 1).count();
    assert_eq!(border, 12, "the 12 pieces of the outline bound one cell each");
}

#[test]
fn a_box_keeps_its_right_angles() {
    // The twelve edges of a cube: six square faces meeting at 90°, a closed part.
    let c = |i: usize| DVec3::new((i & 1) as f64, ((i >> 1) & 1) as f64, ((i >> 2) & 1) as f64);
    let mut curves = Vec::new();
    for a in 0..8 {
        for bit in [1, 2, 4] {
            if a & bit == 0 {
                curves.push(line(c(a), c(a | bit), 20));
            }
        }
    }
    let (g, splines) = unknown(&Network { curves, snap: None, cycles: None });
    let choice = choose_cycles(&g, &splines);
    check_manifold_and_oriented(&g, &choice);
    assert_eq!(choice.patches.len(), 6);
    assert!(choice.uses.iter().all(|&k| k == 2));
    // Outward: the normals point away from the box's centre.
    let centre = DVec3::splat(0.5);
    for p in &choice.patches {
        let seg = &g.segments[p.cycle[0].segment];
        let at = g.nodes[if p.cycle[0].forward { seg.start } else { seg.end }].position;
        assert!(p.normals[0].dot(at - centre) > 0.0);
    }
}

#[test]
fn a_shallow_dome_is_not_closed_by_its_rim() {
    // Two arcs crossing over the top of a low spherical cap, on a rim circle: four cells on
    // the dome; the flat disk of the rim would fold onto them and is left out (the rim is a
    // border), though it is the flattest cycle there is.
    let (r, h) = (1.0, 0.25);
    let big = (r * r + h * h) / (2.0 * h);
    let cap = |x: f64, y: f64| DVec3::new(x, y, (big * big - x * x - y * y).sqrt() - (big - h));
    let arc = |dir: DVec3| Curve {
        points: (0..=40).map(|i| -1.0 + 2.0 * i as f64 / 40.0).map(|t| cap(t * dir.x, t * dir.y)).collect(),
        ..Default::default()
    };
    let rim = closed(64, |a| DVec3::new(r * a.cos(), r * a.sin(), 0.0));
    let (g, splines) = unknown(&Network { curves: vec![rim, arc(DVec3::X), arc(DVec3::Y)], snap: None, cycles: None });
    let choice = choose_cycles(&g, &splines);
    check_manifold_and_oriented(&g, &choice);
    assert_eq!(choice.patches.len(), 4, "{:?}", choice.patches.iter().map(|p| p.cycle.len()).collect::<Vec<_>>());
    let rim_uses: Vec<u8> =
        (0..g.segments.len()).filter(|&s| g.segments[s].curve == 0).map(|s| choice.uses[s]).collect();
    assert!(rim_uses.iter().all(|&k| k == 1), "{rim_uses:?}");
}

#[test]
fn petals_touching_at_one_node_are_patches_of_their_own() {
    // Two closed loops in perpendicular planes through one common point, crossing there at a
    // right angle (sheets that touch): each loop bounds a patch; no cycle runs through the
    // node twice.
    let petal_xz = closed(48, |a| DVec3::new(1.0 + a.cos(), 0.0, a.sin()));
    let petal_xy = closed(48, |a| DVec3::new(a.cos(), -1.0 + a.sin(), 0.0));
    let (g, splines) = unknown(&Network { curves: vec![petal_xz, petal_xy], snap: None, cycles: None });
    assert_eq!(g.nodes.len(), 1);
    let choice = choose_cycles(&g, &splines);
    check_manifold_and_oriented(&g, &choice);
    assert_eq!(choice.patches.len(), 2);
    assert!(choice.patches.iter().all(|p| p.cycle.len() == 1));
}

#[test]
fn parity_union_find_refuses_a_contradiction() {
    let mut p = Parity::default();
    let (a, b, c) = (p.push(), p.push(), p.push());
    p.union(b, a, true);
    p.union(c, b, true);
    // c runs with a (turned twice).
    assert_eq!(p.find(c), (p.find(a).0, p.find(a).1));
    // A new patch turned against a but not against c is a contradiction.
    let d = p.push();
    assert!(!p.consistent(&[(a, true), (c, false)]));
    assert!(p.consistent(&[(a, true), (c, true)]));
    p.union(d, a, true);
    assert_ne!(p.find(d).1, p.find(a).1);
}
