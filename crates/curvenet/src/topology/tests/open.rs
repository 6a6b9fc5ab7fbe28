use super::*;
use crate::geom::DVec3;
use crate::network::{Curve, Network};
use crate::topology::find_nodes;

/// The three great circles of the unit sphere (64 samples each) and a stick from (1, 0, 0)
/// outwards: the stick dangles and is left out, with a warning that names its curve.
#[test]
fn a_dangling_curve_is_left_out_with_a_warning_naming_it() {
    let great = |axis: usize| {
        let points: Vec<DVec3> = (0..64)
            .map(|i| {
                let a = std::f64::consts::TAU * i as f64 / 64.0;
                let (c, s) = (a.cos(), a.sin());
                [DVec3::new(c, s, 0.0), DVec3::new(0.0, c, s), DVec3::new(s, 0.0, c)][axis]
            })
            .collect();
        Curve { name: None, normals: points.clone(), points, closed: true, boundary: false, ..Default::default() }
    };
    let stick = Curve {
        name: Some("stick".into()),
        points: vec![DVec3::X, DVec3::new(1.5, 0.0, 0.0), DVec3::new(2.0, 0.0, 0.0)],
        normals: vec![DVec3::Z; 3],
        closed: false,
        boundary: false,
        ..Default::default()
    };
    let mut curves: Vec<Curve> = (0..3).map(great).collect();
    curves.push(stick);
    let net = Network { curves, snap: None, cycles: None };
    let (mut g, _) = find_nodes(&net, net.snap_tolerance()).unwrap();
    assert_eq!((g.nodes.len(), g.segments.len()), (7, 13));
    let warnings = trim_dangling(&mut g).unwrap();
    assert_eq!((g.nodes.len(), g.segments.len()), (6, 12));
    assert_eq!(warnings.len(), 1);
    assert!(warnings[0].message.starts_with("curve \"stick\" does not meet other curves"), "{}", warnings[0]);
    assert_eq!(warnings[0].at.curve, Some(3));
}
