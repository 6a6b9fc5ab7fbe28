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
