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
    let _ = std::fs::remove_dir_all(&dir);
}
