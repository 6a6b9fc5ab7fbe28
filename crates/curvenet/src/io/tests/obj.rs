use super::*;
use crate::error::Error;

#[test]
fn reads_closed_boundary_polylines() {
    let text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nvn 0 0 1\nvn 0 0 1\ng boundary\nl 1 2 3 1\ng inner\nl -3 -2\n";
    let net = parse(text, "t.obj").unwrap();
    assert_eq!(net.curves.len(), 2);
    assert!(net.curves[0].closed && net.curves[0].boundary);
    assert_eq!(net.curves[0].points.len(), 3);
    assert!(!net.curves[1].closed && !net.curves[1].boundary);
    assert_eq!(net.curves[1].points, vec![DVec3::ZERO, DVec3::X]);
    assert_eq!(net.curves[1].name.as_deref(), Some("inner"));
}

#[test]
fn errors_have_positions() {
    let e = parse("v 0 0 0\nv 1 0 0\nvn 0 0 1\nvn 0 0 1\nl 1 7\n", "t.obj").unwrap_err();
    assert!(matches!(e, Error::Parse { line: 5, column: 5, .. }), "{e}");
    let e = parse("v 0 zero 0\n", "t.obj").unwrap_err();
    assert!(matches!(e, Error::Parse { line: 1, column: 5, .. }), "{e}");
    let e = parse("v 0 0 0\nv 1 0 0\nvn 0 0 1\nl 1 2\n", "t.obj").unwrap_err();
    assert!(e.to_string().contains("2 \"v\" lines but 1 \"vn\""), "{e}");
}

#[test]
fn round_trip() {
    let net = Network {
        curves: vec![Curve {
            name: Some("c".into()),
            points: vec![DVec3::ZERO, DVec3::X, DVec3::Y],
            normals: vec![DVec3::Z; 3],
            closed: true,
            boundary: true,
        }],
        snap: None,
    };
    let mut buf = Vec::new();
    write(&mut buf, &net).unwrap();
    let back = parse(std::str::from_utf8(&buf).unwrap(), "t").unwrap();
    assert_eq!(back.curves[0].points, net.curves[0].points);
    assert!(back.curves[0].closed && back.curves[0].boundary);
}
