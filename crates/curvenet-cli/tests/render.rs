//! `curvenet render` and `surface --render` from the outside: PNG files written, usage errors
//! before any work, nothing written on failure.

use std::path::PathBuf;
use std::process::{Command, Output};
#[path = "../../curvenet/tests/support/png.rs"]
mod support;
use support::decode_rgb;

fn run(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_curvenet")).args(args).output().unwrap()
}

fn scratch(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("curvenet-render-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn s(p: &std::path::Path) -> &str {
    p.to_str().unwrap()
}

#[test]
fn renders_meshes_and_networks() {
    let dir = scratch("ok");
    let (net, mesh, png) = (dir.join("torus.json"), dir.join("torus.ply"), dir.join("a.png"));
    assert!(run(&["example", "torus", "-o", s(&net)]).status.success());
    let o = run(&[
        "surface",
        s(&net),
        "-o",
        s(&mesh),
        "--fast",
        "--vertices",
        "4000",
        "--render",
        s(&png),
        "--color",
        "curvature",
        "--size",
        "300x200",
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let (w, h, _) = decode_rgb(&std::fs::read(&png).unwrap()).expect("a PNG");
    assert_eq!((w, h), (300, 200));
    let grid = dir.join("grid.png");
    let o = run(&[
        "render",
        s(&mesh),
        "-o",
        s(&grid),
        "--curves",
        s(&net),
        "--color",
        "all",
        "--grid",
        "--size",
        "800x800",
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert_eq!(decode_rgb(&std::fs::read(&grid).unwrap()).map(|x| (x.0, x.1)), Some((800, 800)));
    let direct = dir.join("direct.png");
    let o = run(&[
        "render",
        s(&net),
        "-o",
        s(&direct),
        "--fast",
        "--vertices",
        "3000",
        "--view",
        "-30,10,1.2",
        "--size",
        "200x150",
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(direct.exists());
}

#[test]
fn usage_errors_write_nothing() {
    let dir = scratch("bad");
    let net = dir.join("sphere.json");
    assert!(run(&["example", "sphere", "-o", s(&net)]).status.success());
    let png = dir.join("x.png");
    let cases: [(&[&str], &str); 6] = [
        (&["--size", "12"], "WIDTHxHEIGHT"),
        (&["--size", "10x10"], "between 64"),
        (&["--color", "rainbow"], "unknown colouring \"rainbow\""),
        (&["--view", "1,2,3,4"], "AZIMUTH"),
        (&["--range", "-1"], "positive"),
        (&["--curves", "other.json"], "--curves is for mesh inputs"),
    ];
    for (extra, expect) in cases {
        let mut args = vec!["render", s(&net), "-o", s(&png), "--vertices", "2000", "--fast"];
        args.extend_from_slice(extra);
        let o = run(&args);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{extra:?}: {err}");
        assert!(err.contains(expect), "{extra:?}: {err}");
        assert!(!err.contains("panicked"));
        assert!(!png.exists(), "{extra:?} wrote the image");
    }
    let o = run(&["render", s(&net), "-o", s(&dir.join("x.jpg"))]);
    assert_eq!(o.status.code(), Some(2));
    // surface --render checks the picture options before surfacing: no mesh written either.
    let mesh = dir.join("m.ply");
    let o = run(&["surface", s(&net), "-o", s(&mesh), "--render", s(&png), "--size", "1x"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(!mesh.exists() && !png.exists());
    let leftovers: Vec<_> = std::fs::read_dir(&dir).unwrap().map(|e| e.unwrap().file_name()).collect();
    assert_eq!(leftovers.len(), 1, "only the network remains: {leftovers:?}");
}
