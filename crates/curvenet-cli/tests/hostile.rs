//! The hostile sweep (issue 17), kept: inputs that never end, time bombs and dense data, each
//! run bounded in time, ending with an error code (1 or 2), never a signal or a panic.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use std::time::{Duration, Instant};

fn bin() -> Command {
    Command::new(env!("CARGO_BIN_EXE_curvenet"))
}

fn scratch(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("curvenet-hostile-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// Runs `curvenet args`, killed after `limit`; returns its output and wall time.
fn run_bounded(args: &[&str], limit: Duration) -> (Output, Duration) {
    let start = Instant::now();
    let mut child =
        bin().args(args).stdout(std::process::Stdio::piped()).stderr(std::process::Stdio::piped()).spawn().unwrap();
    loop {
        if child.try_wait().unwrap().is_some() {
            break;
        }
        if start.elapsed() > limit {
            let _ = child.kill();
            break;
        }
        std::thread::sleep(Duration::from_millis(10));
    }
    let out = child.wait_with_output().unwrap();
    (out, start.elapsed())
}

/// An input that never ends (`/dev/zero` under every extension) is refused at its first bytes,
/// by every command that reads it: exit 1, within 2 s, no output written.
#[cfg(unix)]
#[test]
fn endless_inputs_are_refused_at_their_first_bytes() {
    let dir = scratch("zero");
    let link = |ext: &str| {
        let p = dir.join(format!("zero.{ext}"));
        std::os::unix::fs::symlink("/dev/zero", &p).unwrap();
        p.to_str().unwrap().to_string()
    };
    let (json, obj, net, ply, off, svg) =
        (link("json"), link("obj"), link("net"), link("ply"), link("off"), link("svg"));
    let out = |name: &str| dir.join(name).to_str().unwrap().to_string();
    let (mesh_out, png, net_out, model) = (out("o.ply"), out("o.png"), out("o.json"), out("m.json"));
    let runs: Vec<Vec<&str>> = vec![
        vec!["surface", &json, "-o", &mesh_out],
        vec!["surface", &obj, "-o", &mesh_out],
        vec!["surface", &net, "-o", &mesh_out],
        vec!["normals", &json, "-o", &net_out],
        vec!["render", &json, "-o", &png],
        vec!["render", &obj, "-o", &png],
        vec!["render", &ply, "-o", &png],
        vec!["render", &off, "-o", &png],
        vec!["sample", &ply, "-o", &net_out],
        vec!["sample", &off, "-o", &net_out],
        vec!["sample", &obj, "-o", &net_out],
        vec!["fit", &off, "-o", &model],
        vec!["resurface", &json, "-o", &mesh_out],
        vec!["eval", &ply, "--truth", "sphere"],
        vec!["eval", &mesh_out, "--truth", &off],
        vec!["inflate", &svg, "-o", &mesh_out],
    ];
    for args in runs {
        let (o, took) = run_bounded(&args, Duration::from_secs(10));
        let msg = String::from_utf8_lossy(&o.stderr);
        assert!(took <= Duration::from_secs(2), "{args:?}: {took:?}");
        assert!(matches!(o.status.code(), Some(1)), "{args:?}: {:?} {msg}", o.status);
        assert!(msg.starts_with("error: "), "{args:?}: {msg}");
        for f in [&mesh_out, &png, &net_out, &model] {
            assert!(!Path::new(f).exists(), "{args:?} wrote {f}");
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// SVG time bombs: an ellipse a ten-thousandth as tall as it is wide (its outline would take
/// ~10⁵ samples and minutes of refinement) is refused in well under 5 s; 10⁵ nested groups
/// read in linear time.
#[test]
fn svg_time_bombs_end_within_five_seconds() {
    let dir = scratch("svg");
    let write = |name: &str, text: String| {
        let p = dir.join(name);
        std::fs::write(&p, text).unwrap();
        p.to_str().unwrap().to_string()
    };
    let head = r#"<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 100 100">"#;
    let sliver = write("sliver.svg", format!(r#"{head}<ellipse cx="50" cy="50" rx="40" ry="1e-4"/></svg>"#));
    let deep = 100_000;
    let nested = write(
        "nested.svg",
        format!(r#"{head}{}<circle cx="50" cy="50" r="40"/>{}</svg>"#, "<g>".repeat(deep), "</g>".repeat(deep)),
    );
    let out = dir.join("o.ply");
    let out = out.to_str().unwrap();
    let (o, took) = run_bounded(&["inflate", &sliver, "-o", out], Duration::from_secs(30));
    let msg = String::from_utf8_lossy(&o.stderr);
    assert!(took <= Duration::from_secs(5), "sliver: {took:?}");
    assert_eq!(o.status.code(), Some(1), "{msg}");
    assert!(msg.contains("sliver") && msg.contains("line 1"), "{msg}");
    let (o, took) = run_bounded(&["inflate", &nested, "-o", out, "-q"], Duration::from_secs(30));
    assert!(took <= Duration::from_secs(5), "nested groups: {took:?}");
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    // Coordinates far out (1e300) or not numbers: an error naming the line (and column).
    let far = write("far.svg", format!("{head}\n<circle cx=\"1e300\" cy=\"50\" r=\"40\"/>\n</svg>"));
    let nan =
        write("nan.svg", format!("{head}\n<circle cx=\"50\" cy=\"50\" r=\"40\"/>\n<path d=\"M 1 1 L 2 NaN\"/></svg>"));
    for (file, expect) in [(&far, "far.svg:2:"), (&nan, "nan.svg:3:")] {
        let (o, _) = run_bounded(&["inflate", file, "-o", out], Duration::from_secs(30));
        let msg = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(1), "{msg}");
        assert!(msg.contains(expect), "{msg}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// SIGTERM while the outputs are being written (their temporary files beside the targets):
/// the process exits 143 and the output folder holds only what it held before.
#[cfg(unix)]
#[test]
fn sigterm_while_writing_leaves_the_folder_as_it_was() {
    let dir = scratch("sigterm");
    let o = bin().current_dir(&dir).args(["example", "sphere", "-o", "s.json"]).output().unwrap();
    assert!(o.status.success());
    std::fs::write(dir.join("keep.obj"), b"keep me").unwrap();
    let before = |d: &Path| {
        let mut v: Vec<String> =
            std::fs::read_dir(d).unwrap().map(|e| e.unwrap().file_name().to_string_lossy().into_owned()).collect();
        v.sort();
        v
    };
    let listing = before(&dir);
    // A text mesh of a few hundred thousand vertices takes a while to write: time enough to see
    // its temporary file and send the signal then (tried a few times: the write may win).
    for vertices in ["200000", "400000", "800000"] {
        let mut child = bin()
            .current_dir(&dir)
            .args(["surface", "s.json", "-o", "keep.obj", "--fast", "--vertices", vertices, "-q"])
            .stderr(std::process::Stdio::piped())
            .spawn()
            .unwrap();
        let start = Instant::now();
        let mut signalled = false;
        while child.try_wait().unwrap().is_none() && start.elapsed() < Duration::from_secs(120) {
            let staged = before(&dir).iter().any(|n| n.ends_with(".tmp"));
            if staged {
                let pid = child.id().to_string();
                assert!(Command::new("kill").args(["-TERM", &pid]).status().unwrap().success());
                signalled = true;
                break;
            }
            std::thread::sleep(Duration::from_millis(1));
        }
        let status = child.wait().unwrap();
        if !signalled {
            // The run finished first: put the folder back and try a larger mesh.
            std::fs::write(dir.join("keep.obj"), b"keep me").unwrap();
            continue;
        }
        assert_eq!(status.code(), Some(143), "{status:?}");
        assert_eq!(before(&dir), listing, "files left after SIGTERM");
        assert_eq!(std::fs::read(dir.join("keep.obj")).unwrap(), b"keep me");
        let _ = std::fs::remove_dir_all(&dir);
        return;
    }
    panic!("never caught the run while it was writing its output");
}

/// Bad values at the door: NaN options exit 2, sizes beyond the memory budget exit 2 with the
/// estimate, bad file contents exit 1 naming the place, control characters escaped.
#[test]
fn bad_values_and_sizes_are_refused_at_the_door() {
    let dir = scratch("door");
    let path = |name: &str| dir.join(name).to_str().unwrap().to_string();
    let (sph, mesh) = (path("s.json"), path("m.ply"));
    assert!(bin().args(["example", "sphere", "-o", &sph]).output().unwrap().status.success());
    assert!(bin().args(["surface", &sph, "-o", &mesh, "--vertices", "2000", "-q"]).output().unwrap().status.success());
    let svg = path("c.svg");
    std::fs::write(
        &svg,
        r#"<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 100 100"><circle cx="50" cy="50" r="40"/></svg>"#,
    )
    .unwrap();
    let fandisk = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../data/meshes/fandisk.off");
    let fandisk = fandisk.to_str().unwrap();
    let (x_ply, x_json, x_png) = (path("x.ply"), path("x.json"), path("x.png"));
    let usage: Vec<(Vec<&str>, &str)> = vec![
        (vec!["surface", &sph, "-o", &x_ply, "--tolerance", "NaN"], "tolerance"),
        (vec!["surface", &sph, "-o", &x_ply, "--normal-prior", "NaN"], "normal-prior"),
        (vec!["surface", &sph, "-o", &x_ply, "--max-memory", "-1"], "max-memory"),
        (vec!["surface", &sph, "-o", &x_ply, "--vertices", "1000000", "--max-memory", "1G"], "not enough memory"),
        (vec!["inflate", &svg, "-o", &x_ply, "--stretch", "NaN"], "stretch"),
        (vec!["inflate", &svg, "-o", &x_ply, "--crease-sharpness", "NaN"], "crease-sharpness"),
        (vec!["inflate", &svg, "-o", &x_ply, "--vertices", "1000000000"], "vertices"),
        (vec!["fit", &mesh, "-o", &x_json, "--angle", "NaN"], "angle"),
        (vec!["render", &mesh, "-o", &x_png, "--size", "6000x6000"], "GB"),
        (vec!["sample", fandisk, "-o", &x_json, "--planes", "10000"], "planes"),
        (vec!["sample", fandisk, "-o", &x_json, "--spacing", "100"], "spacing"),
    ];
    for (args, expect) in usage {
        let (o, took) = run_bounded(&args, Duration::from_secs(20));
        let msg = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {msg}");
        assert!(msg.contains(expect), "{args:?}: {msg}");
        assert!(took < Duration::from_secs(5), "{args:?}: {took:?}");
    }
    assert!(["x.ply", "x.json", "x.png"].iter().all(|f| !dir.join(f).exists()));

    // Normals flipping sign from sample to sample, on a curve named with escape sequences.
    let mut net: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&sph).unwrap()).unwrap();
    let curve = &mut net["curves"][1];
    curve["name"] = "evil\u{1b}[31m\u{7}".into();
    let normals = curve["normals"].as_array_mut().unwrap();
    for (i, n) in normals.iter_mut().enumerate() {
        if i % 2 == 1 {
            *n = n.as_array().unwrap().iter().map(|x| serde_json::Value::from(-x.as_f64().unwrap())).collect();
        }
    }
    let alt = path("alt.json");
    std::fs::write(&alt, net.to_string()).unwrap();
    let o = bin().args(["surface", &alt, "-o", &x_ply]).output().unwrap();
    let msg = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(1), "{msg}");
    assert!(
        msg.contains("curve \"evil\\u{1b}[31m\\u{7}\"") && msg.contains("sample") && msg.contains("turns by"),
        "{msg}"
    );
    assert!(!o.stderr.iter().any(|&b| b == 0x1b || b == 0x07), "raw control characters: {msg}");

    // eval of a mesh with a NaN vertex, and of an empty mesh; a model without constraints.
    let nan = path("nan.off");
    std::fs::write(&nan, "OFF\n3 1 0\n0 0 0\n1 0 0\nnan 1 0\n3 0 1 2\n").unwrap();
    let empty = path("empty.off");
    std::fs::write(&empty, "OFF\n0 0 0\n").unwrap();
    let model = path("model.json");
    std::fs::write(
        &model,
        r#"{"order":2,"positions":[[0,0,0],[1,0,0],[0,1,0]],"faces":[[0,1,2]],"constraints":[],"ghosts":[]}"#,
    )
    .unwrap();
    for (args, expect) in [
        (vec!["eval", &nan, "--truth", "sphere"], "finite"),
        (vec!["eval", &empty, "--truth", "sphere"], "no triangles"),
        (vec!["eval", &mesh, "--truth", &nan], "finite"),
        (vec!["resurface", &model, "-o", &x_ply], "no Cauchy constraints"),
    ] {
        let o = bin().args(&args).output().unwrap();
        let msg = String::from_utf8_lossy(&o.stderr);
        assert!(matches!(o.status.code(), Some(1)), "{args:?}: {msg}");
        assert!(msg.contains(expect), "{args:?}: {msg}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// 10⁵ samples on one circle (a boundary with upward normals): the flat disk, in under 5 s.
#[test]
fn a_densely_sampled_circle_surfaces_in_seconds() {
    let dir = scratch("circle");
    let n = 100_000;
    let pts: Vec<String> = (0..n)
        .map(|i| {
            let t = std::f64::consts::TAU * i as f64 / n as f64;
            format!("[{},{},0]", t.cos(), t.sin())
        })
        .collect();
    let normals = vec!["[0,0,1]"; n].join(",");
    let text = format!(
        r#"{{"curves":[{{"points":[{}],"normals":[{normals}],"closed":true,"boundary":true}}]}}"#,
        pts.join(",")
    );
    let input = dir.join("circle.json");
    std::fs::write(&input, text).unwrap();
    let out = dir.join("disk.off");
    let (o, took) =
        run_bounded(&["surface", input.to_str().unwrap(), "-o", out.to_str().unwrap(), "-q"], Duration::from_secs(30));
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(took < Duration::from_secs(5), "{took:?}");
    let text = std::fs::read_to_string(&out).unwrap();
    let zmax = text
        .lines()
        .skip(2)
        .filter_map(|l| {
            let v: Vec<f64> = l.split_whitespace().filter_map(|t| t.parse().ok()).collect();
            (v.len() == 3 && !l.starts_with("3 ")).then(|| v[2].abs())
        })
        .fold(0.0, f64::max);
    assert!(zmax < 1e-9, "the disk is not flat: |z| up to {zmax:e}");
    let _ = std::fs::remove_dir_all(&dir);
}

/// One OBJ `l` line of 5·10⁵ indices (a densely sampled closed curve without normals): read in
/// well under a second (token columns were counted from the line's start: quadratic, 30 s) and
/// surfaced within the bound. The whole run took 9 s alone and 15.4 s beside this binary's other
/// tests (CI, 2026-12-05), half of it consolidation's overdraw scan, which visited every sample
/// within the band of each one along the dense curve itself; consolidation now leaves out the
/// samples far closer together than its gap (2.8 s → under 0.05 s; the run 6.3 → 3.3 s). The
/// read and consolidation stages are what is timed here, from `--stats`, against 20× bounds:
/// a quadratic scan would exceed them many times over.
#[test]
fn a_long_polyline_line_is_read_in_linear_time() {
    let dir = scratch("polyline");
    let n = 500_000;
    let mut text = String::with_capacity(n * 40);
    for i in 0..n {
        let t = std::f64::consts::TAU * i as f64 / n as f64;
        text.push_str(&format!("v {:.9} {:.9} {:.9}\n", t.cos(), t.sin(), 0.3 * (2.0 * t).sin()));
    }
    text.push('l');
    for i in 0..=n {
        text.push_str(&format!(" {}", i % n + 1));
    }
    text.push('\n');
    let input = dir.join("loop.obj");
    std::fs::write(&input, text).unwrap();
    let out = dir.join("patch.ply");
    let stats = dir.join("stats.json");
    let args =
        ["surface", input.to_str().unwrap(), "-o", out.to_str().unwrap(), "-q", "--stats", stats.to_str().unwrap()];
    let (o, took) = run_bounded(&args, Duration::from_secs(60));
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let stats: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&stats).unwrap()).unwrap();
    let read = stats["timings"]["read"].as_f64().unwrap();
    assert!(read < 3.0, "reading took {read} s (whole run {took:?})");
    let consolidate = stats["timings"]["consolidate"].as_f64().unwrap();
    assert!(consolidate < 1.0, "consolidation took {consolidate} s (whole run {took:?})");
    let _ = std::fs::remove_dir_all(&dir);
}

/// A file whose parse would not fit in the process's memory (30 MB of `v 0 0 0` under a 1.5 GB
/// address-space limit: 270 MB to parse, 200 MB available) is refused before it is read: exit 2,
/// a message naming the estimate — not an allocation abort.
#[cfg(unix)]
#[test]
fn an_input_too_large_for_memory_is_refused_before_reading() {
    let dir = scratch("parse-memory");
    let input = dir.join("points.obj");
    let mut text = "v 0 0 0\n".repeat(30 << 17);
    text.push_str("f 1 2 3\n");
    std::fs::write(&input, text).unwrap();
    let o = Command::new("sh")
        .arg("-c")
        .arg(format!(
            "ulimit -v 1500000 && exec '{}' eval '{}' --truth '{}'",
            env!("CARGO_BIN_EXE_curvenet"),
            input.display(),
            input.display()
        ))
        .output()
        .unwrap();
    let msg = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{msg}");
    assert!(msg.contains("MB of memory") && msg.contains("points.obj"), "{msg}");
    let _ = std::fs::remove_dir_all(&dir);
}
