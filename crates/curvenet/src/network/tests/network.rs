use super::*;

fn line(n: usize) -> Curve {
    Curve {
        name: None,
        points: (0..n).map(|i| DVec3::new(i as f64, 0.0, 0.0)).collect(),
        normals: vec![DVec3::Z * 2.0; n],
        closed: false,
        boundary: false,
        ..Default::default()
    }
}

#[test]
fn normals_are_normalised_and_duplicates_merged() {
    let mut c = line(3);
    c.points.insert(1, c.points[0]);
    c.normals.insert(1, DVec3::Z);
    let (v, w) = Network { curves: vec![c], snap: None, cycles: None }.validated().unwrap();
    assert_eq!(v.curves[0].points.len(), 3);
    assert_eq!(v.curves[0].normals[0], DVec3::Z);
    assert_eq!(w.len(), 1);
    assert!(w[0].message.contains("merged"), "{}", w[0]);
}

#[test]
fn errors_name_curve_and_sample() {
    let mut c = line(3);
    c.normals[2] = DVec3::ZERO;
    let e = Network { curves: vec![line(2), c], snap: None, cycles: None }.validated().unwrap_err();
    assert!(e.to_string().contains("curve 1, sample 2"), "{e}");
    assert_eq!((e.at().curve, e.at().sample), (Some(1), Some(2)));

    let mut c = line(3);
    c.points[1].y = f64::NAN;
    let e = Network { curves: vec![c], snap: None, cycles: None }.validated().unwrap_err();
    assert!(e.to_string().contains("sample 1") && e.to_string().contains("non-finite"), "{e}");
    assert_eq!((e.at().curve, e.at().sample), (Some(0), Some(1)));

    let mut c = line(3);
    c.normals.pop();
    let e = Network { curves: vec![c], snap: None, cycles: None }.validated().unwrap_err();
    assert!(e.to_string().contains("3 points but 2 normals"), "{e}");
    assert_eq!((e.at().curve, e.at().sample), (Some(0), None));

    let e = Network { curves: vec![line(1)], snap: None, cycles: None }.validated().unwrap_err();
    assert!(e.to_string().contains("at least 2"), "{e}");

    let e = Network { curves: vec![], snap: None, cycles: None }.validated().unwrap_err();
    assert!(e.to_string().contains("no curves"), "{e}");
}

#[test]
fn noise_is_seeded_and_keeps_crossings() {
    let net = crate::network::examples::example("sphere").unwrap();
    let a = net.perturbed(0.05, 7);
    let b = net.perturbed(0.05, 7);
    assert_eq!(a, b);
    assert_ne!(a, net.perturbed(0.05, 8));
    // Standard deviation of the position noise ≈ 5% of the spacing.
    let d: Vec<f64> = net
        .curves
        .iter()
        .zip(&a.curves)
        .flat_map(|(c, n)| c.points.iter().zip(&n.points).map(|(p, q)| p.distance(*q)))
        .collect();
    let rms = (d.iter().map(|x| x * x).sum::<f64>() / d.len() as f64 / 3.0).sqrt();
    let want = 0.05 * net.mean_sample_spacing();
    assert!((rms / want - 1.0).abs() < 0.15, "{rms} {want}");
    // The crossing samples of the equator and a meridian moved together.
    assert!(a.curves[0].points[32].distance(a.curves[1].points[0]) < 1e-12);
}

#[test]
fn normals_tangent_to_the_curve_are_rejected() {
    let mut c = line(4);
    c.normals[2] = DVec3::new(1.0, 0.02, 0.0);
    let e = Network { curves: vec![c.clone()], snap: None, cycles: None }.validated().unwrap_err();
    assert!(e.to_string().contains("curve 0, sample 2: normal") && e.to_string().contains("tangent"), "{e}");
    // 45° off the curve is a valid (if unusual) normal.
    c.normals[2] = DVec3::new(1.0, 0.0, 1.0);
    assert!(Network { curves: vec![c], snap: None, cycles: None }.validated().is_ok());
}

#[test]
fn extents_outside_the_supported_range_are_rejected() {
    for (scale, shift) in [(1e70, 0.0), (1e-70, 0.0), (1.0, 1e10)] {
        let mut c = line(3);
        c.points.iter_mut().for_each(|p| *p = (*p + DVec3::splat(shift)) * scale);
        let e = Network { curves: vec![c], snap: None, cycles: None }.validated().unwrap_err().to_string();
        assert!(e.contains("supported range") || e.contains("translate it"), "{scale:e} {shift:e}: {e}");
    }
    let mut c = line(3);
    c.points.iter_mut().for_each(|p| *p = (*p + DVec3::splat(1e6)) * 1e-12);
    assert!(Network { curves: vec![c], snap: None, cycles: None }.validated().is_ok());
}
