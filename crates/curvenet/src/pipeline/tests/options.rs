use super::*;

#[test]
fn every_option_round_trips_through_its_name() {
    for preset in Preset::ALL {
        let o = Options::preset(preset);
        for spec in OPTIONS {
            let mut again = Options::preset(preset);
            if let Some(v) = o.get(spec.name) {
                again.set(spec.name, &v).unwrap_or_else(|e| panic!("{}: {e}", spec.name));
            }
            assert_eq!(again, o, "{} in preset {}", spec.name, preset.name());
        }
    }
}

#[test]
fn names_are_unique_and_lowercase() {
    let mut names: Vec<&str> = OPTIONS.iter().map(|s| s.name).collect();
    assert!(names.iter().all(|n| n.chars().all(|c| c.is_ascii_lowercase() || c.is_ascii_digit() || c == '_')));
    names.sort_unstable();
    let n = names.len();
    names.dedup();
    assert_eq!(names.len(), n);
}

#[test]
fn presets_are_defined_once() {
    let paper = Options::preset(Preset::Paper);
    assert_eq!(paper.mesh.patching, Patching::Planar);
    assert_eq!(paper.iterate.iterations, 0);
    assert_eq!(paper.normal_control.energy, Energy::Uniform);
    assert_eq!(paper.normal_control.guide_area, GuideArea::Surface);
    assert_eq!(paper.normal_control.guide_updates, 0);
    assert_eq!(paper.cauchy.ghost_updates, 0);
    let fast = Options::fast();
    assert_eq!((fast.mesh.patching, fast.iterate.iterations), (Patching::Planar, 0));
    // fast keeps the guide of the single pass it always was (issue 18 changed the default's).
    assert_eq!(fast.normal_control.guide_area, GuideArea::Mass);
    assert_eq!(Options::default().normal_control.guide_area, GuideArea::Barycentric);
    assert_eq!(
        fast.normal_control,
        NormalControlOptions { guide_area: GuideArea::Mass, ..Options::default().normal_control }
    );
    assert_eq!(Preset::from_name("paper").unwrap(), Preset::Paper);
    assert!(matches!(Preset::from_name("quick"), Err(Error::Usage { .. })));
}

#[test]
fn named_values_override_the_preset_and_bad_ones_are_usage_errors() {
    let o = Options::from_named(Preset::Paper, &[("iterations", "3"), ("method", "cauchy"), ("w1", "2e5")]).unwrap();
    assert_eq!(o.iterate.iterations, 3);
    assert_eq!(o.method, Method::Cauchy);
    assert_eq!(o.short_paper.w1, 2e5);
    assert_eq!(o.normal_control.energy, Energy::Uniform);
    for (name, value, says) in [
        ("vertices", "0", "`vertices` takes a positive whole number"),
        ("spacing", "-1", "`spacing` takes a positive distance"),
        ("method", "magic", "`method` takes one of normal-control"),
        ("order", "4", "`order` takes 1, 2 or 3"),
        ("tolerance", "nan", "`tolerance` takes a number ≥ 0"),
        ("colour", "red", "unknown option \"colour\""),
    ] {
        let e = Options::default().clone().set(name, value).unwrap_err();
        assert!(matches!(e, Error::Usage { .. }) && e.to_string().contains(says), "{name}: {e}");
    }
    let both = Options::from_named(Preset::Default, &[("spacing", "0.1"), ("vertices", "100")]);
    assert!(both.unwrap_err().to_string().contains("not both"));
}

#[test]
fn the_unset_vertices_text_is_the_default() {
    let spec = OPTIONS.iter().find(|s| s.name == "vertices").unwrap();
    assert_eq!(spec.default_text(), MeshOptions::DEFAULT_VERTICES.to_string());
}

#[test]
fn every_option_has_help_and_a_default() {
    for spec in OPTIONS {
        assert!(spec.help.len() > 20, "{}", spec.name);
        assert!(!spec.default_text().is_empty(), "{}", spec.name);
        for c in spec.choices {
            Options::default().set(spec.name, c).unwrap();
        }
    }
}

#[test]
fn named_choices_take_underscores_for_dashes() {
    // Python writes values as it writes keywords (issue 33): `method="normal_control"`.
    let mut o = Options::default();
    o.set("method", "short_paper").unwrap();
    assert_eq!(o.method, Method::ShortPaper);
    o.set("method", "normal-control").unwrap();
    assert_eq!(o.method, Method::NormalControl);
    assert!(o.set("method", "normal control").is_err());
}

#[test]
fn spacing_takes_a_share_of_the_diagonal() {
    let mut o = Options::default();
    o.set("spacing", "1%").unwrap();
    assert_eq!((o.mesh.spacing, o.mesh.spacing_relative), (None, Some(0.01)));
    assert_eq!(o.get("spacing").as_deref(), Some("1.0%"));
    o.set("spacing", "0.02").unwrap();
    assert_eq!((o.mesh.spacing, o.mesh.spacing_relative), (Some(0.02), None));
    for bad in ["0%", "150%", "-1%", "x%"] {
        assert!(o.set("spacing", bad).is_err(), "{bad}");
    }
    // On a network: the share of its bounding-box diagonal.
    let net = crate::network::examples::example("sphere").unwrap();
    let diag = net.bounding_box().diagonal();
    let mut rel = Options::fast();
    rel.set("spacing", "5%").unwrap();
    let s = crate::pipeline::surface(&net, &rel).unwrap();
    assert!((s.stats.spacing - 0.05 * diag).abs() < 1e-12 * diag, "{} vs {}", s.stats.spacing, 0.05 * diag);
}
