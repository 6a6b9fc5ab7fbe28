use super::*;

/// Moved curves move the attributes' samples too (the constraint vertices are located on
/// them), keep the per-sample values, and drop the kept system.
#[test]
fn set_curves_moves_the_attribute_samples() {
    let points = vec![DVec3::ZERO, DVec3::X, DVec3::Y];
    let attrs = NetworkAttributes {
        curves: vec![CurveAttributes {
            kind: Kind::Cauchy,
            points: points.clone(),
            closed: true,
            sharpness: vec![0.1, 0.2, 0.3],
            stretch: vec![0.0; 3],
        }],
    };
    let options = super::super::CauchyOptions { attributes: Some(std::sync::Arc::new(attrs)), ..Default::default() };
    let mut m = Andrews2011::new(vec![(points.clone(), true)], options, 1e-3);
    let moved: Vec<DVec3> = points.iter().map(|p| *p + DVec3::Z).collect();
    m.set_curves(&[(moved.clone(), true)]);
    let a = m.options.attributes.as_ref().unwrap();
    assert_eq!(a.curves[0].points, moved);
    assert_eq!(a.curves[0].sharpness, vec![0.1, 0.2, 0.3]);
    assert_eq!(m.curves[0].0, moved);
    assert!(!m.is_factored());
    // A curve whose sample count changed keeps its attribute samples.
    m.set_curves(&[(moved[..2].to_vec(), false)]);
    assert_eq!(m.options.attributes.as_ref().unwrap().curves[0].points, moved);
}

/// The attribute fields are checked at the door: finite, sharpness within ±180°, stretch > −1;
/// a byte-order mark is skipped.
#[test]
fn attributes_are_checked() {
    let doc = |extra: &str| {
        format!("\u{feff}{{\"curves\": [{{\"points\": [[0,0,0],[1,0,0],[0,1,0]], \"closed\": true{extra}}}]}}")
    };
    let a = NetworkAttributes::from_json(&doc(", \"sharpness\": 90"), "a.json").unwrap();
    assert!((a.curves[0].sharpness[1] - std::f64::consts::FRAC_PI_2).abs() < 1e-12);
    for (extra, want) in [
        (", \"sharpness\": 500", "[-180, 180]"),
        (", \"sharpness\": [0, -181, 0]", "sample 1"),
        (", \"stretch\": -1", "≤ −1"),
        (", \"stretch\": \"big\"", "must be a number"),
        (", \"sharpness\": [0, 1]", "2 values for 3 samples"),
    ] {
        let e = NetworkAttributes::from_json(&doc(extra), "a.json").unwrap_err();
        let m = e.to_string();
        assert!(m.contains("a.json: curve 0") && m.contains(want), "{extra}: {m}");
        assert_eq!(e.exit_code(), 1, "{m}");
    }
}
