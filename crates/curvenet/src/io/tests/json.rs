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
    };
    let mut buf = Vec::new();
    write(&mut buf, &net).unwrap();
    let back = parse(std::str::from_utf8(&buf).unwrap(), "t").unwrap();
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
    let net = parse(text, "t.json").unwrap();
    let known: Vec<bool> = net.curves.iter().map(|c| c.has_normals()).collect();
    assert_eq!(known, vec![false, false, true]);
    // Written back without a "normals" key where they are unknown.
    let mut buf = Vec::new();
    write(&mut buf, &net).unwrap();
    let out = std::str::from_utf8(&buf).unwrap();
    assert_eq!(out.matches("\"normals\"").count(), 1, "{out}");
    assert_eq!(parse(out, "t").unwrap(), net);
}
