use super::*;
use crate::error::Error;

#[test]
fn round_trip() {
    let net = Network {
        curves: vec![Curve {
            name: Some("a \"b\"".into()),
            points: vec![DVec3::new(0.1, 1.0 / 3.0, -2e-17), DVec3::X],
            normals: vec![DVec3::Z, DVec3::Z],
            closed: false,
            boundary: true,
            ..Default::default()
        }],
        snap: Some(1e-5),
        cycles: None,
    };
    let mut buf = Vec::new();
    write(&mut buf, &net).unwrap();
    let back = parse(std::str::from_utf8(&buf).unwrap(), "t").unwrap().0;
    assert_eq!(back, net);
}

#[test]
fn malformed_reports_line_and_column() {
    let text = "{\"curves\": [\n  {\"points\": [[0,0,0],[1,0]],\n \"normals\": []}]}";
    match parse(text, "x.json") {
        Err(Error::Parse { line, column, message, .. }) => {
            assert_eq!(line, 2);
            assert!(column > 20, "{column}");
            assert!(message.contains("length"), "{message}");
        }
        other => panic!("{other:?}"),
    }
    assert!(matches!(parse("{\"curves\": [", "x"), Err(Error::Parse { line: 1, .. })));
}

#[test]
fn normals_may_be_left_out_or_null_per_curve() {
    let text = r#"{"curves": [
        {"points": [[0,0,0],[1,0,0]]},
        {"points": [[0,0,0],[0,1,0]], "normals": null},
        {"points": [[0,0,0],[0,0,1]], "normals": [[1,0,0],[1,0,0]]}]}"#;
    let net = parse(text, "t.json").unwrap().0;
    let known: Vec<bool> = net.curves.iter().map(|c| c.has_normals()).collect();
    assert_eq!(known, vec![false, false, true]);
    // Written back without a "normals" key where they are unknown.
    let mut buf = Vec::new();
    write(&mut buf, &net).unwrap();
    let out = std::str::from_utf8(&buf).unwrap();
    assert_eq!(out.matches("\"normals\"").count(), 1, "{out}");
    assert_eq!(parse(out, "t").unwrap().0, net);
}

#[test]
fn misspelled_keys_find_the_known_one() {
    assert_eq!(closest("normal", &CURVE_KEYS), Some("normals"));
    assert_eq!(closest("boundry", &CURVE_KEYS), Some("boundary"));
    assert_eq!(closest("pionts", &CURVE_KEYS), Some("points"));
    assert_eq!(closest("Closed", &CURVE_KEYS), Some("closed"));
    assert_eq!(closest("colour", &CURVE_KEYS), None);
    assert_eq!(closest("snapping", &NETWORK_KEYS), Some("snap"));
}

#[test]
fn unknown_keys_are_warnings_with_their_line_and_a_missing_field_names_what_was_found() {
    let text = "{\"curves\": [\n {\"points\": [[0,0,0],[1,0,0]],\n  \"normal\": [[0,0,1],[0,0,1]]},\n {\"points\": [[0,0,0],[1,0,0]], \"boundry\": true}\n]}";
    let (net, warnings) = parse(text, "n.json").unwrap();
    assert_eq!(net.curves.len(), 2);
    assert!(net.curves[0].normals.is_empty(), "the misspelled normals are not read");
    let said: Vec<String> = warnings.iter().map(|w| w.to_string()).collect();
    assert_eq!(said.len(), 2, "{said:?}");
    assert!(said[0].starts_with("n.json:3: unknown key \"normal\" in curve 0") && said[0].contains("\"normals\"?"));
    assert!(said[1].starts_with("n.json:4: unknown key \"boundry\" in curve 1") && said[1].contains("\"boundary\"?"));
    let e = parse("{\"curves\": [{\"pionts\": [[0,0,0]]}]}", "p.json").unwrap_err().to_string();
    assert!(e.contains("missing field `points` (found \"pionts\": did you mean \"points\"?)"), "{e}");
}
