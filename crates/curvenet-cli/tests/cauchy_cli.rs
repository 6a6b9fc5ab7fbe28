//! The `inflate`, `fit`, `resurface` commands and `--method cauchy` end to end.

use std::path::{Path, PathBuf};
use std::process::Command;

fn bin() -> Command {
    Command::new(env!("CARGO_BIN_EXE_curvenet"))
}

fn tmp(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("curvenet-cauchy-cli-{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d.join(name)
}

fn sketches() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/sketches")
}

#[test]
fn inflate_bundled_sketches_with_defaults() {
    for name in ["leaf.svg", "circle.svg"] {
        let out = tmp(&format!("{name}.ply"));
        let o = bin().arg("inflate").arg(sketches().join(name)).arg("-o").arg(&out).output().unwrap();
        assert!(o.status.success(), "{name}: {}", String::from_utf8_lossy(&o.stderr));
        let text = String::from_utf8_lossy(&o.stdout);
        // "height H = R × the outline's radius"
        let ratio: f64 = text.split(" = ").nth(1).and_then(|s| s.split_whitespace().next()).unwrap().parse().unwrap();
        assert!(ratio > 0.3 && ratio < 1.5, "{name}: {text}");
        assert!(out.exists());
    }
}

#[test]
fn bad_sketches_are_errors_without_output() {
    let svg = tmp("bad.svg");
    std::fs::write(&svg, "<svg>\n<path d=\"M 0 0 A 1 1 0 0 0 2 2 Z\"/>\n</svg>").unwrap();
    let out = tmp("bad.ply");
    let o = bin().arg("inflate").arg(&svg).arg("-o").arg(&out).output().unwrap();
    assert_eq!(o.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&o.stderr).contains("bad.svg:2"));
    assert!(!out.exists());
}

#[test]
fn surface_method_cauchy_reads_curve_kinds() {
    let net = tmp("sphere.json");
    assert!(bin().args(["example", "sphere", "-o"]).arg(&net).output().unwrap().status.success());
    // A bad kind is an input error naming the curve.
    let text = std::fs::read_to_string(&net).unwrap().replacen("\"points\"", "\"kind\": \"wobbly\", \"points\"", 1);
    let bad = tmp("bad.json");
    std::fs::write(&bad, text).unwrap();
    let o = bin().arg("surface").arg(&bad).arg("-o").arg(tmp("bad.ply")).args(["--method", "cauchy"]).output().unwrap();
    assert_eq!(o.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&o.stderr).contains("curve 0"), "{}", String::from_utf8_lossy(&o.stderr));
    let o = bin()
        .arg("surface")
        .arg(&net)
        .arg("-o")
        .arg(tmp("s.ply"))
        .args(["--method", "cauchy", "--order", "3", "--vertices", "3000"])
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
}
