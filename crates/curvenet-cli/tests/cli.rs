//! The `curvenet` command from the outside: exit codes, messages, files written or not.
//! Every input error of the pipeline issue has a case here: its message, a non-zero exit and
//! no output file (an existing output is left as it was).

use curvenet::geom::DVec3;
use curvenet::{Curve, Network};
use std::f64::consts::{PI, TAU};
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn bin() -> Command {
    Command::new(env!("CARGO_BIN_EXE_curvenet"))
}

/// A fresh scratch directory per test.
fn scratch(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("curvenet-cli-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn run(args: &[&str]) -> Output {
    bin().args(args).output().unwrap()
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// Runs `surface` on `input` (written to a file named `file`) and expects failure with
/// `code` and a message containing every string in `expect`; the output must not appear and
/// nothing else may be left in the directory.
fn expect_failure(name: &str, file: &str, input: &[u8], code: i32, expect: &[&str]) {
    let dir = scratch(name);
    let inp = dir.join(file);
    std::fs::write(&inp, input).unwrap();
    let out = dir.join("out.ply");
    let o = run(&["surface", inp.to_str().unwrap(), "-o", out.to_str().unwrap()]);
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(code), "{name}: {err}");
    for e in expect {
        assert!(err.contains(e), "{name}: expected {e:?} in: {err}");
    }
    assert!(!err.contains("panicked"), "{name}: {err}");
    assert!(!out.exists(), "{name}: output written");
    assert_eq!(std::fs::read_dir(&dir).unwrap().count(), 1, "{name}: stray files");
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Runs `surface` on a JSON `input` and expects success, an output file, and warnings
/// containing every string in `expect`.
fn expect_success_with_warnings(name: &str, input: &[u8], expect: &[&str]) {
    let dir = scratch(name);
    let inp = dir.join("n.json");
    std::fs::write(&inp, input).unwrap();
    let out = dir.join("out.ply");
    let o = run(&["surface", inp.to_str().unwrap(), "-o", out.to_str().unwrap(), "--vertices", "3000"]);
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(0), "{name}: {err}");
    for e in expect {
        assert!(err.contains(e), "{name}: expected {e:?} in: {err}");
    }
    assert!(out.exists(), "{name}: no output");
    std::fs::remove_dir_all(&dir).unwrap();
}

fn json_of(net: &Network) -> Vec<u8> {
    let dir = scratch("json-of");
    let p = dir.join("n.json");
    curvenet::io::write_network(&p, net).unwrap();
    let bytes = std::fs::read(&p).unwrap();
    std::fs::remove_dir_all(&dir).unwrap();
    bytes
}

fn curve(points: Vec<DVec3>, normals: Vec<DVec3>, closed: bool, boundary: bool) -> Curve {
    Curve { name: None, points, normals, closed, boundary, ..Default::default() }
}

const TWO_SAMPLES: &str = r#"{"curves": [{"points": [[0,0,0],[1,0,0]], "normals": [[0,0,1],[0,0,1]]}]}"#;

#[test]
fn malformed_files_report_line_and_column() {
    expect_failure("json-truncated", "n.json", b"{\"curves\": [\n  {\"points\": [[0,0,0],", 1, &["n.json:2:"]);
    expect_failure(
        "json-type",
        "n.json",
        b"{\"curves\": [{\"points\": [[0,0,\"a\"]], \"normals\": []}]}",
        1,
        &["n.json:1:", "invalid type"],
    );
    expect_failure("obj-number", "n.obj", b"v 0 0 0\nv 1 zero 0\n", 1, &["n.obj:2:5", "zero"]);
    expect_failure("obj-l", "n.obj", b"v 0 0 0\nvn 0 0 1\nl 1 x\n", 1, &["n.obj:3:5"]);
    expect_failure("net-truncated", "n.net", b"3\n0 0 0 0 0 1\n1 0 0 0 0 1\n", 1, &["n.net:", "ends early"]);
    expect_failure(
        "net-flag",
        "n.net",
        b"2\n0 0 0 0 0 1\n1 0 0 0 0 1\n1\nyes\n0 1\n",
        1,
        &["n.net:5:1", "boundary flag"],
    );
    expect_failure("net-count", "n.net", b"two\n", 1, &["n.net:1:1", "number of samples"]);
    expect_failure("not-utf8", "n.json", &[0xff, 0xfe, 0x00], 1, &["not valid UTF-8"]);
}

#[test]
fn non_finite_values() {
    expect_failure(
        "json-overflow",
        "n.json",
        br#"{"curves": [{"points": [[0,0,1e999],[1,0,0]], "normals": [[0,0,1],[0,0,1]]}]}"#,
        1,
        &["n.json:1:"],
    );
    expect_failure("obj-nan", "n.obj", b"v 0 0 nan\n", 1, &["n.obj:1:7", "not a finite number"]);
    expect_failure("net-inf", "n.net", b"1\n0 0 0 inf 0 1\n", 1, &["n.net:2:7", "not a finite number"]);
}

#[test]
fn invalid_values_name_curve_and_sample() {
    expect_failure(
        "zero-normal",
        "n.json",
        br#"{"curves": [{"points": [[0,0,0],[1,0,0],[2,0,0]], "normals": [[0,0,1],[0,0,0],[0,0,1]]}]}"#,
        1,
        &["curve 0, sample 1", "cannot be normalised"],
    );
    expect_failure(
        "length-mismatch",
        "n.json",
        br#"{"curves": [{"name": "rim", "points": [[0,0,0],[1,0,0]], "normals": [[0,0,1]]}]}"#,
        1,
        &["curve \"rim\"", "2 points but 1 normals"],
    );
    expect_failure(
        "one-sample",
        "n.json",
        br#"{"curves": [{"points": [[0,0,0]], "normals": [[0,0,1]]}]}"#,
        1,
        &["curve 0", "1 sample", "at least 2"],
    );
    expect_failure("no-curves", "n.json", br#"{"curves": []}"#, 1, &["no curves"]);
    expect_failure(
        "obj-range",
        "n.obj",
        b"v 0 0 0\nv 1 0 0\nvn 0 0 1\nvn 0 0 1\nl 1 9\n",
        1,
        &["n.obj:5:5", "out of range"],
    );
    expect_failure(
        "net-range",
        "n.net",
        b"2\n0 0 0 0 0 1\n1 0 0 0 0 1\n1\n0\n0 2\n",
        1,
        &["n.net:6:3", "out of range"],
    );
    expect_failure("obj-normals", "n.obj", b"v 0 0 0\nv 1 0 0\nvn 0 0 1\nl 1 2\n", 1, &["2 \"v\" lines but 1 \"vn\""]);
}

fn sphere_with(extra: Curve) -> Network {
    let mut net = curvenet::network::examples::example("sphere").unwrap();
    net.curves.push(extra);
    net
}

#[test]
fn non_manifold_networks_name_the_node_or_segment() {
    // A curve that leaves a node and ends inside a patch.
    let pts: Vec<DVec3> = (0..=20)
        .map(|k| {
            let t = 0.25 * PI * k as f64 / 20.0;
            DVec3::new(t.sin() * 0.5f64.sqrt(), t.sin() * 0.5f64.sqrt(), t.cos())
        })
        .collect();
    // Issue 5: an open network is surfaced as far as it is well defined, with a warning naming
    // the curve left out.
    expect_success_with_warnings(
        "dangling",
        &json_of(&sphere_with(curve(pts.clone(), pts, false, false))),
        &["curve 3", "left out of the surface"],
    );

    // Three half-disk pages sharing a diameter: a segment used by three patches.
    let n = 32;
    let diam: Vec<DVec3> = (0..=n).map(|k| DVec3::new(-1.0 + 2.0 * k as f64 / n as f64, 0.0, 0.0)).collect();
    let mut curves = vec![curve(diam.clone(), vec![DVec3::Z; diam.len()], false, false)];
    for a in [-20f64, 0.0, 20.0] {
        let a = a.to_radians();
        let (u, nn) = (DVec3::new(0.0, a.cos(), a.sin()), DVec3::new(0.0, -a.sin(), a.cos()));
        let pts: Vec<DVec3> = (0..=n)
            .map(|k| DVec3::X * (PI * k as f64 / n as f64).cos() + u * (PI * k as f64 / n as f64).sin())
            .collect();
        curves.push(curve(pts, vec![nn; n + 1], false, true));
    }
    expect_failure(
        "book",
        "n.json",
        &json_of(&Network { curves, snap: None, cycles: None }),
        1,
        &["not a 2-manifold", "node"],
    );

    // A boundary loop whose projection crosses itself (a limaçon lifted out of its plane).
    let pts: Vec<DVec3> = (0..200)
        .map(|k| {
            let t = TAU * k as f64 / 200.0;
            let r = 0.5 + t.cos();
            DVec3::new(r * t.cos(), r * t.sin(), 0.3 * t.sin())
        })
        .collect();
    // Issue 5: an unclosed boundary curve is rejected, naming the curve.
    let mut net = curvenet::network::examples::example("saddle").unwrap();
    let b = net.curves.iter().position(|c| c.boundary).unwrap();
    let c = &mut net.curves[b];
    let keep = c.points.len() * 3 / 4;
    c.points.truncate(keep);
    c.normals.truncate(keep);
    c.closed = false;
    expect_failure(
        "open-boundary",
        "n.json",
        &json_of(&net),
        1,
        &[
            &curvenet::network::curve_label(&net.curves, b),
            "open boundary curve must be closed or end on another curve",
        ],
    );

    // Issue 5: the fold is detected and the patch triangulated on a fallback domain.
    let net = Network { curves: vec![curve(pts, vec![DVec3::Z; 200], true, true)], snap: None, cycles: None };
    expect_success_with_warnings("self-crossing", &json_of(&net), &["patch 0", "folds over", "fallback domain"]);

    // Normals of one curve pointing inward.
    let mut net = curvenet::network::examples::example("sphere").unwrap();
    net.curves[1].normals.iter_mut().for_each(|n| *n = -*n);
    expect_failure(
        "flipped",
        "n.json",
        &json_of(&net),
        1,
        &["curve \"equator z=0\" and curve \"meridian x=0\" meet at", "points inward"],
    );

    // A boundary tag on a curve with patches on both sides.
    let mut net = curvenet::network::examples::example("sphere").unwrap();
    net.curves[0].boundary = true;
    expect_failure(
        "interior-boundary",
        "n.json",
        &json_of(&net),
        1,
        &["tagged as boundary but has patches on both sides"],
    );
}

#[test]
fn usage_errors_exit_2_before_any_work() {
    let dir = scratch("usage");
    let inp = dir.join("n.json");
    std::fs::write(&inp, TWO_SAMPLES).unwrap();
    let i = inp.to_str().unwrap();
    for args in [
        vec!["surface", i, "-o", "x.stl"],
        vec!["surface", i, "-o", "x.ply", "--spacing", "-1"],
        vec!["surface", i, "-o", "x.ply", "--method", "quadharmonic"],
        vec!["surface", i],
        vec!["example", "klein-bottle", "-o", "x.json"],
        vec!["frobnicate"],
    ] {
        let o = run(&args);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {}", stderr(&o));
        assert!(!stderr(&o).is_empty());
    }
    assert!(!Path::new("x.ply").exists() && !Path::new("x.stl").exists());
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn failure_leaves_an_existing_output_untouched() {
    let dir = scratch("keep");
    let inp = dir.join("n.json");
    std::fs::write(&inp, r#"{"curves": []}"#).unwrap();
    let out = dir.join("out.obj");
    std::fs::write(&out, "previous result").unwrap();
    let o = run(&["surface", inp.to_str().unwrap(), "-o", out.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(1));
    assert_eq!(std::fs::read_to_string(&out).unwrap(), "previous result");
    assert_eq!(std::fs::read_dir(&dir).unwrap().count(), 2);
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn duplicate_samples_are_merged_with_a_warning() {
    let dir = scratch("dup");
    let mut net = curvenet::network::examples::example("sphere").unwrap();
    let (p, n) = (net.curves[0].points[5], net.curves[0].normals[5]);
    net.curves[0].points.insert(5, p);
    net.curves[0].normals.insert(5, n);
    let inp = dir.join("n.json");
    std::fs::write(&inp, json_of(&net)).unwrap();
    let out = dir.join("out.off");
    let o = run(&["surface", inp.to_str().unwrap(), "-o", out.to_str().unwrap(), "--vertices", "3000"]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    assert!(
        stderr(&o).contains(
            "warning: curve \"equator z=0\": 1 sample(s) repeated the previous one and were merged (sample 6)"
        ),
        "{}",
        stderr(&o)
    );
    assert!(out.exists());
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn every_format_in_and_out() {
    let dir = scratch("formats");
    let mut counts = Vec::new();
    for fmt in ["json", "obj", "net"] {
        let net = dir.join(format!("sphere.{fmt}"));
        let o = run(&["example", "sphere", "-o", net.to_str().unwrap()]);
        assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
        for mesh in ["ply", "obj", "off"] {
            let out = dir.join(format!("s-{fmt}.{mesh}"));
            let stats = dir.join(format!("s-{fmt}-{mesh}.json"));
            let o = run(&[
                "surface",
                net.to_str().unwrap(),
                "-o",
                out.to_str().unwrap(),
                "--vertices",
                "4000",
                "--stats",
                stats.to_str().unwrap(),
            ]);
            assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
            let m = curvenet::io::read_mesh(&out).unwrap();
            let s: serde_json::Value = serde_json::from_slice(&std::fs::read(&stats).unwrap()).unwrap();
            assert_eq!(s["vertices"].as_u64().unwrap() as usize, m.positions.len());
            for key in
                ["read", "nodes", "resample", "cycles", "tessellate", "operators", "factor", "solve", "write", "total"]
            {
                assert!(s["timings"][key].as_f64().is_some(), "timings.{key}");
            }
            for key in ["faces", "curve_vertices", "cycles", "components"] {
                assert!(s[key].as_u64().is_some(), "{key}");
            }
            assert_eq!(s["cycles"], 8);
            assert_eq!(s["components"], 1);
            if mesh == "ply" {
                let flags = m.curve_vertex.unwrap();
                assert_eq!(flags.iter().filter(|&&f| f).count(), s["curve_vertices"].as_u64().unwrap() as usize);
                let h = m.mean_curvature.unwrap();
                let mean = h.iter().sum::<f64>() / h.len() as f64;
                assert!((mean - 1.0).abs() < 0.1, "{mean}");
            }
            counts.push(m.positions.len());
        }
    }
    // The three network formats carry the same network.
    assert!(counts.iter().all(|&c| c == counts[0]), "{counts:?}");
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Issue 33: `curvenet normals` makes no surface, and its warnings do not speak of one: a
/// duplicate stroke is left out of the network written, a curve that bounds no patch is in it
/// (with its normals) and would be left out of a surface made from it.
#[test]
fn normals_warnings_speak_of_the_network() {
    let dir = scratch("normals-words");
    let flower = concat!(env!("CARGO_MANIFEST_DIR"), "/../../data/sketches/flower.obj");
    let out = dir.join("flower.json");
    let o = run(&["normals", flower, "-o", out.to_str().unwrap(), "-q"]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let err = stderr(&o);
    assert!(!err.contains("left out of the surface"), "{err}");
    assert!(err.contains("it was left out of the network"), "{err}");
    assert!(err.contains("would be left out of a surface made from the network (its normals were inferred"), "{err}");
    let net = curvenet::io::read_network(&out).unwrap();
    assert!(net.curves.iter().all(|c| c.has_normals()));
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Issue 32: an OBJ with its normals split at the creases has more `vn` than `v` lines (its
/// corners name them); `--obj-normals shared` writes one per vertex (`f a//a`), the same
/// positions and faces; the flag is refused for another format.
#[test]
fn obj_normals_split_at_creases_or_shared() {
    let dir = scratch("obj-normals");
    let net = dir.join("can.json");
    assert_eq!(run(&["example", "can", "-o", net.to_str().unwrap(), "-q"]).status.code(), Some(0));
    let lines = |p: &Path, head: &str| {
        std::fs::read_to_string(p)
            .unwrap()
            .lines()
            .filter(|l| l.starts_with(head))
            .map(String::from)
            .collect::<Vec<_>>()
    };
    let mut meshes = Vec::new();
    for how in ["split", "shared"] {
        let out = dir.join(format!("{how}.obj"));
        let o = run(&[
            "surface",
            net.to_str().unwrap(),
            "-o",
            out.to_str().unwrap(),
            "--vertices",
            "3000",
            "-q",
            "--obj-normals",
            how,
        ]);
        assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
        let (v, vn, f) = (lines(&out, "v "), lines(&out, "vn "), lines(&out, "f "));
        if how == "split" {
            assert!(vn.len() > v.len(), "the can's two crease rims split the normals: {} vn, {} v", vn.len(), v.len());
        } else {
            assert_eq!(vn.len(), v.len());
            assert!(f.iter().all(|l| l[2..].split(' ').all(|c| {
                let (a, b) = c.split_once("//").unwrap();
                a == b
            })));
        }
        let m = curvenet::io::read_mesh(&out).unwrap();
        meshes.push((m.positions, m.faces));
    }
    assert_eq!(meshes[0], meshes[1]);
    let o =
        run(&["surface", net.to_str().unwrap(), "-o", dir.join("x.ply").to_str().unwrap(), "--obj-normals", "shared"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("is for an .obj output"), "{}", stderr(&o));
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn demo_reports_where_the_result_went() {
    let dir = scratch("demo");
    let o = bin().args(["demo", "--out", "d"]).current_dir(&dir).output().unwrap();
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let text = String::from_utf8_lossy(&o.stdout);
    assert!(text.contains("d/sphere.ply"), "{text}");
    assert!(dir.join("d/sphere.ply").exists() && dir.join("d/sphere.json").exists());
    let m = curvenet::io::read_mesh(&dir.join("d/sphere.ply")).unwrap();
    assert!(m.positions.len() > 15_000);
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn help_documents_every_option() {
    let o = run(&["surface", "--help"]);
    let text = String::from_utf8_lossy(&o.stdout);
    for flag in [
        "--method",
        "--spacing",
        "--vertices",
        "--soft",
        "--iterations",
        "--tolerance",
        "--normal-prior",
        "--energy",
        "--guide-area",
        "--guide-updates",
        "--snap",
        "--stats",
        "Exit codes",
    ] {
        assert!(text.contains(flag), "{flag} missing from --help");
    }
    let o = run(&["example", "--list"]);
    let text = String::from_utf8_lossy(&o.stdout);
    for name in ["sphere", "torus", "cylinder", "barrel", "bottleneck"] {
        assert!(text.contains(name));
    }
}

/// One set of conventions (issue 33): every subcommand takes `-q` (before or after its name),
/// no markup escape leaks into any `--help`, `example` without a name lists the names, and
/// `eval` prints the truth as written, with no debug formatting.
#[test]
fn every_subcommand_takes_q_and_help_text_is_plain() {
    let top = String::from_utf8_lossy(&run(&["--help"]).stdout).into_owned();
    let commands: Vec<String> = top
        .lines()
        .skip_while(|l| !l.starts_with("Commands:"))
        .skip(1)
        .take_while(|l| l.starts_with("  "))
        .filter(|l| !l[2..].starts_with(' '))
        .filter_map(|l| l.split_whitespace().next().map(str::to_string))
        .filter(|c| c != "help")
        .collect();
    assert!(commands.len() >= 10, "{commands:?}");
    for c in &commands {
        let help = String::from_utf8_lossy(&run(&[c, "--help"]).stdout).into_owned();
        assert!(help.contains("-q, --quiet"), "`{c} --help` has no -q");
        assert!(!help.contains("\\["), "`{c} --help` shows an escaped bracket");
    }
    let dir = scratch("conventions");
    let net = dir.join("torus.json");
    let mesh = dir.join("torus.ply");
    // Without a name: the names, exit 0.
    let o = run(&["example"]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(String::from_utf8_lossy(&o.stdout).contains("torus"));
    // -q before or after the subcommand: nothing on stdout.
    let o = run(&["-q", "example", "torus", "-o", net.to_str().unwrap()]);
    assert!(o.status.success() && o.stdout.is_empty(), "{}", stderr(&o));
    let o = run(&["surface", net.to_str().unwrap(), "-o", mesh.to_str().unwrap(), "--vertices", "3000", "-q"]);
    assert!(o.status.success() && o.stdout.is_empty(), "{}", stderr(&o));
    let o = run(&["eval", mesh.to_str().unwrap(), "--truth", "torus:4,2", "-q"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let text = String::from_utf8_lossy(&o.stdout);
    assert!(text.contains("truth  torus:4,2"), "{text}");
    assert!(!text.contains('{') && !text.contains("DVec3"), "debug formatting in eval: {text}");
    // The truth kinds of the examples are in `eval --help`.
    let help = String::from_utf8_lossy(&run(&["eval", "--help"]).stdout).into_owned();
    for kind in ["lens", "can", "saddle", "ellipsoid"] {
        assert!(help.contains(kind), "`eval --help` does not document {kind}");
    }
}

/// Two outputs naming one file, or an output naming the input: a usage error before any
/// work, and the existing file is left byte-identical.
#[test]
fn outputs_naming_the_same_file_are_a_usage_error() {
    let dir = scratch("same-file");
    let net = dir.join("s.json");
    let o = bin().args(["example", "sphere", "-o"]).arg(&net).output().unwrap();
    assert!(o.status.success());
    let mesh = dir.join("m.ply");
    std::fs::write(&mesh, b"keep me").unwrap();
    for extra in [vec!["--stats", "m.ply"], vec!["--render", "x.png", "--stats", "x.png"]] {
        let o = bin()
            .current_dir(&dir)
            .args(["surface", "s.json", "-o", "m.ply", "--vertices", "500"])
            .args(&extra)
            .output()
            .unwrap();
        assert_eq!(o.status.code(), Some(2), "{extra:?}: {}", String::from_utf8_lossy(&o.stderr));
        assert!(String::from_utf8_lossy(&o.stderr).contains("two outputs"));
        assert_eq!(std::fs::read(&mesh).unwrap(), b"keep me");
    }
    let o = bin().current_dir(&dir).args(["surface", "s.json", "-o", "m.ply", "--stats", "s.json"]).output().unwrap();
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("is the input file"));
    assert!(!dir.join("x.png").exists());
}

#[test]
fn networks_without_normals_from_the_command_line() {
    let dir = scratch("no-normals");
    let p = |f: &str| dir.join(f).to_str().unwrap().to_string();
    // example --no-normals, then `normals` writes them and `surface` infers them itself.
    let o = run(&["example", "sphere", "--no-normals", "-o", &p("s.obj")]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    assert!(!std::fs::read_to_string(p("s.obj")).unwrap().contains("vn "));
    let o = run(&["normals", &p("s.obj"), "-o", &p("s.json")]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let inferred = curvenet::io::read_network(Path::new(&p("s.json"))).unwrap();
    for c in &inferred.curves {
        for (q, n) in c.points.iter().zip(&c.normals) {
            assert!(n.dot(q.normalize()) > 0.999, "normal {n} at {q}");
        }
    }
    // --infer-normals alone before the positional input (it takes its value only with `=`).
    let o = run(&[
        "surface",
        "--infer-normals",
        &p("s.json"),
        "-o",
        &p("s.ply"),
        "--vertices",
        "2000",
        "--stats",
        &p("st.json"),
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let stats = std::fs::read_to_string(p("st.json")).unwrap();
    assert!(stats.contains("\"inferred_normals\": {"), "{stats}");
    // .net cannot hold a network without normals: a usage error, nothing written.
    let o = run(&["example", "sphere", "--no-normals", "-o", &p("s.net")]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains(".net format needs a normal"), "{}", stderr(&o));
    assert!(!Path::new(&p("s.net")).exists());
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn sample_finds_creases_by_default_and_only_json_holds_them() {
    let mesh = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../data/meshes/fandisk.off");
    let mesh = mesh.to_str().unwrap();
    let dir = scratch("fandisk-creases");
    let (json, obj) = (dir.join("f.json"), dir.join("f.obj"));
    let o = run(&["sample", mesh, "-o", json.to_str().unwrap(), "--planes", "4"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let net = curvenet::io::read_network(&json).unwrap();
    assert!(net.has_creases());
    let o = run(&["sample", mesh, "-o", obj.to_str().unwrap(), "--planes", "4"]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("--no-creases") && stderr(&o).contains(".json"), "{}", stderr(&o));
    assert!(!obj.exists(), "nothing written");
    let o = run(&["sample", mesh, "-o", obj.to_str().unwrap(), "--planes", "4", "--no-creases"]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(!curvenet::io::read_network(&obj).unwrap().has_creases());
    let o = run(&["sample", mesh, "-o", json.to_str().unwrap(), "--crease-angle", "NaN"]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
}

#[test]
fn raw_strokes_are_consolidated_and_written_and_off_turns_it_off() {
    let raw = concat!(env!("CARGO_MANIFEST_DIR"), "/../../data/sketches/raw/computer-mouse.obj");
    let dir = scratch("raw-strokes");
    let out = dir.join("mouse-consolidated.json");
    let o = run(&["consolidate", raw, "-o", out.to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr(&o));
    let said = String::from_utf8_lossy(&o.stdout).to_string();
    assert!(said.contains("ends joined"), "{said}");
    assert!(stderr(&o).contains("consolidation:"), "{}", stderr(&o));
    let net = curvenet::io::read_network(&out).unwrap();
    assert!(net.curves.len() >= 30, "{}", net.curves.len());
    // The sketch surfaces with the stage (a partial surface: a warning naming what was left
    // out), and stops at "no patch" or an overlap without it.
    let (ply, stats) = (dir.join("mouse.ply"), dir.join("mouse-stats.json"));
    let o = run(&["surface", raw, "-o", ply.to_str().unwrap(), "-q", "--stats", stats.to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr(&o));
    let s = std::fs::read_to_string(&stats).unwrap();
    assert!(s.contains("\"consolidation\": {") && s.contains("\"coverage\":"), "{s}");
    // Without -q the summary line counts the warnings printed above it (issue 33).
    let o = run(&["surface", raw, "-o", ply.to_str().unwrap()]);
    let warned = stderr(&o).lines().filter(|l| l.starts_with("warning: ")).count();
    let summary = String::from_utf8_lossy(&o.stdout).lines().last().unwrap_or_default().to_string();
    assert!(warned > 1 && summary.ends_with(&format!(", {warned} warnings (above)")), "{warned}: {summary}");
    let o = run(&["surface", raw, "-o", ply.to_str().unwrap(), "-q", "--consolidate", "off"]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    // A curve given twice, sample for sample, is merged into one (a warning names it); without
    // the stage it is refused as overlapping.
    let twice = concat!(env!("CARGO_MANIFEST_DIR"), "/../../tests/data/bad/coincident-curves.json");
    let o = run(&["surface", twice, "-o", ply.to_str().unwrap(), "-q", "--stats", stats.to_str().unwrap()]);
    assert!(o.status.success() && stderr(&o).contains("\"equator again\""), "{}", stderr(&o));
    let s: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&stats).unwrap()).unwrap();
    assert_eq!(s["consolidation"]["merged"], 1, "{s}");
    let o = run(&["surface", twice, "-o", ply.to_str().unwrap(), "-q", "--consolidate", "off"]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert!(stderr(&o).contains("overlap"), "{}", stderr(&o));
}

/// `curvenet cycles` writes the network with one line per patch's cycle; a line deleted leaves
/// that patch open when the file is surfaced; an output other than JSON is refused before
/// anything runs.
#[test]
fn cycles_writes_one_line_per_patch_to_edit() {
    let dir = scratch("cycles");
    let (net, json) = (dir.join("sphere.json"), dir.join("cycles.json"));
    assert!(run(&["example", "sphere", "-o", net.to_str().unwrap()]).status.success());
    let o = run(&["cycles", net.to_str().unwrap(), "-o", json.to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(String::from_utf8_lossy(&o.stdout).contains("8 cycles"), "{}", String::from_utf8_lossy(&o.stdout));
    let text = std::fs::read_to_string(&json).unwrap();
    let lines: Vec<&str> = text.lines().collect();
    let at = lines.iter().position(|l| l.trim() == "\"cycles\": [").unwrap();
    assert_eq!(lines[at + 9].trim(), "]", "one line per cycle");
    // Delete the last cycle's line (and the comma before it).
    let mut edited: Vec<String> = lines.iter().map(|l| l.to_string()).collect();
    edited.remove(at + 8);
    edited[at + 7] = edited[at + 7].trim_end_matches(',').to_string();
    std::fs::write(&json, edited.join("\n")).unwrap();
    let (ply, stats) = (dir.join("open.ply"), dir.join("stats.json"));
    let o = run(&[
        "surface",
        json.to_str().unwrap(),
        "-o",
        ply.to_str().unwrap(),
        "--vertices",
        "3000",
        "--stats",
        stats.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let s: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&stats).unwrap()).unwrap();
    assert_eq!(s["cycles"], 7);
    let obj = dir.join("cycles.obj");
    let o = run(&["cycles", net.to_str().unwrap(), "-o", obj.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("JSON only") && !obj.exists(), "{}", stderr(&o));
    std::fs::remove_dir_all(&dir).unwrap();
}
