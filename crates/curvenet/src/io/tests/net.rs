use super::*;
use crate::error::Error;

const SQUARE: &str = "4\n0 0 0 0 0 1\n1 0 0 0 0 1\n1 1 0 0 0 1\n0 1 0 0 0 1\n2\n1\n0 1 2 3 0\n0\n0 2\n";

#[test]
fn reads_shared_indices_and_closed_curves() {
    let net = parse(SQUARE, "t.net").unwrap();
    assert_eq!(net.curves.len(), 2);
    assert!(net.curves[0].closed && net.curves[0].boundary);
    assert_eq!(net.curves[0].points.len(), 4);
    assert_eq!(net.curves[1].points, vec![DVec3::ZERO, DVec3::new(1.0, 1.0, 0.0)]);
}

#[test]
fn round_trip_keeps_sharing() {
    let net = parse(SQUARE, "t.net").unwrap();
    let mut buf = Vec::new();
    write(&mut buf, &net).unwrap();
    let text = String::from_utf8(buf).unwrap();
    assert!(text.starts_with("4\n"), "{text}");
    assert_eq!(parse(&text, "t").unwrap(), net);
}

#[test]
fn errors_have_positions() {
    let e = parse("2\n0 0 0 0 0 1\n1 0 0 0 0 1\n1\n0\n0 5\n", "t.net").unwrap_err();
    assert!(matches!(e, Error::Parse { line: 6, column: 3, .. }), "{e}");
    let e = parse("2\n0 0 0 0 0 1\n", "t.net").unwrap_err();
    assert!(e.to_string().contains("ends early"), "{e}");
    let e = parse("1\n0 0 x 0 0 1\n", "t.net").unwrap_err();
    assert!(matches!(e, Error::Parse { line: 2, column: 5, .. }), "{e}");
}
