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
    for name in ["leaf.svg", "circle.svg", "petals.svg"] {
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
    // A malformed number in the path data: the error names its line and column.
    std::fs::write(&svg, "<svg>\n<path d=\"M 0 0 L 10 0 L 10 1x0 Z\"/>\n</svg>").unwrap();
    let out = tmp("bad.ply");
    let o = bin().arg("inflate").arg(&svg).arg("-o").arg(&out).output().unwrap();
    assert_eq!(o.status.code(), Some(1));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.contains("bad.svg:2:29"), "{err}");
    assert!(!out.exists());
    // Paths in <defs> are not strokes: nothing is left to inflate.
    std::fs::write(&svg, "<svg>\n<defs><circle r=\"5\"/></defs>\n</svg>").unwrap();
    let o = bin().arg("inflate").arg(&svg).arg("-o").arg(&out).output().unwrap();
    assert_eq!(o.status.code(), Some(1));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.contains("bad.svg:1:1") && err.contains("no path"), "{err}");
    assert!(!out.exists());
}

/// Inflates `svg` (written to `name`) into an .off mesh; returns the vertices and faces.
fn inflate_svg(name: &str, svg: &str) -> (Vec<[f64; 3]>, Vec<[usize; 3]>) {
    let input = tmp(name);
    std::fs::write(&input, svg).unwrap();
    let out = tmp(&format!("{name}.off"));
    let o = bin().arg("inflate").arg(&input).arg("-o").arg(&out).args(["--vertices", "2000", "-q"]).output().unwrap();
    assert!(o.status.success(), "{name}: {}", String::from_utf8_lossy(&o.stderr));
    let text = std::fs::read_to_string(&out).unwrap();
    let mut lines = text.lines().skip(1);
    let counts: Vec<usize> = lines.next().unwrap().split_whitespace().map(|x| x.parse().unwrap()).collect();
    let nums = |l: &str| l.split_whitespace().map(|x| x.parse::<f64>().unwrap()).collect::<Vec<f64>>();
    let vertices = lines.by_ref().take(counts[0]).map(nums).map(|v| [v[0], v[1], v[2]]).collect();
    let faces = lines.take(counts[1]).map(nums).map(|f| [f[1] as usize, f[2] as usize, f[3] as usize]).collect();
    (vertices, faces)
}

/// Per axis: (min, max) of the vertices.
fn bounds(v: &[[f64; 3]]) -> [(f64, f64); 3] {
    std::array::from_fn(|k| v.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), p| (a.min(p[k]), b.max(p[k]))))
}

#[test]
fn inflate_applies_group_transforms() {
    // The output is in the sketch's user units (not normalised), y up: the circle of centre
    // (100, 100) and radius 80 moved by translate(500, 0) scale(3) has centre (800, 300) and
    // radius 240, and inflates to the plain circle's dome scaled by 3 (height too).
    let circle = r#"<circle cx="100" cy="100" r="80"/>"#;
    let (plain, _) = inflate_svg("plain.svg", &format!("<svg>{circle}</svg>"));
    let (moved, _) =
        inflate_svg("moved.svg", &format!(r#"<svg><g transform="translate(500,0) scale(3)">{circle}</g></svg>"#));
    let (p, m) = (bounds(&plain), bounds(&moved));
    let width = |b: (f64, f64)| b.1 - b.0;
    let centre = |b: (f64, f64)| (b.0 + b.1) / 2.0;
    eprintln!("plain {p:?}\nmoved {m:?}");
    for k in 0..2 {
        let ratio = width(m[k]) / width(p[k]);
        assert!((ratio - 3.0).abs() < 0.03, "axis {k}: width ratio {ratio}");
    }
    assert!((width(p[0]) - 160.0).abs() < 0.2, "{p:?}");
    assert!((centre(p[0]) - 100.0).abs() < 0.1 && (centre(p[1]) + 100.0).abs() < 0.1, "{p:?}");
    assert!((centre(m[0]) - 800.0).abs() < 0.3 && (centre(m[1]) + 300.0).abs() < 0.3, "{m:?}");
    let heights = (p[2].1, m[2].1);
    assert!((heights.1 / heights.0 - 3.0).abs() < 0.03, "heights {heights:?}");
}

#[test]
fn inflate_a_path_of_arcs() {
    // A circle of radius 50 drawn by two arcs: a dome whose rim is the circle, one boundary loop.
    let svg = r#"<svg><path d="M 150 100 A 50 50 0 0 1 50 100 a 50 50 0 0 1 100 0 Z"/></svg>"#;
    let (v, f) = inflate_svg("arcs.svg", svg);
    assert!(v.len() > 500 && !f.is_empty(), "{} vertices, {} faces", v.len(), f.len());
    let mut edges = std::collections::HashMap::new();
    for t in &f {
        for k in 0..3 {
            let (a, b) = (t[k], t[(k + 1) % 3]);
            *edges.entry((a.min(b), a.max(b))).or_insert(0) += 1;
        }
    }
    assert!(edges.values().all(|&c| c <= 2), "an edge in more than two faces");
    // The boundary (edges of one face) is one closed loop on the circle, in the sketch plane.
    let boundary: Vec<(usize, usize)> = edges.iter().filter(|e| *e.1 == 1).map(|e| *e.0).collect();
    let mut degree = std::collections::HashMap::new();
    for &(a, b) in &boundary {
        *degree.entry(a).or_insert(0) += 1;
        *degree.entry(b).or_insert(0) += 1;
    }
    assert!(degree.values().all(|&d| d == 2), "the boundary is not a union of loops");
    let mut seen = std::collections::HashSet::from([boundary[0].0]);
    let (mut prev, mut cur) = (boundary[0].0, boundary[0].1);
    while seen.insert(cur) {
        let next = boundary.iter().find_map(|&(a, b)| {
            if a == cur && b != prev {
                Some(b)
            } else if b == cur && a != prev {
                Some(a)
            } else {
                None
            }
        });
        (prev, cur) = (cur, next.unwrap());
    }
    assert_eq!(seen.len(), degree.len(), "the boundary is more than one loop");
    for &i in degree.keys() {
        let [x, y, z] = v[i];
        let r = ((x - 100.0).powi(2) + (y + 100.0).powi(2)).sqrt();
        assert!((r - 50.0).abs() < 0.05 && z.abs() < 1e-6, "boundary vertex {:?}", v[i]);
    }
    let top = v.iter().map(|p| p[2]).fold(f64::NEG_INFINITY, f64::max);
    assert!(top > 15.0 && top < 75.0, "dome height {top}");
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
