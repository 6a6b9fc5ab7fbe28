//! Fault injection on `curvenet batch` and `surface` (issue 29, "nothing lost"): outputs that
//! would overwrite inputs, two runs into one folder, FIFOs, `kill -9` at chosen moments, a
//! file-size limit, `--resume` on a truncated mesh or other options. Each fault ends as
//! promised: inputs byte-identical, no temporary file left after the next run, the report
//! valid JSON lines only, no hang past a timeout.

#![cfg(unix)]

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

fn bin() -> &'static str {
    env!("CARGO_BIN_EXE_curvenet")
}

/// Runs the CLI with `args`, killed and failed after `limit` seconds (a hang is a failure).
fn curvenet_within(limit: f64, args: &[&str]) -> Output {
    let mut child =
        Command::new(bin()).args(args).stdout(Stdio::piped()).stderr(Stdio::piped()).spawn().expect("the CLI runs");
    let start = Instant::now();
    loop {
        if child.try_wait().unwrap().is_some() {
            return child.wait_with_output().unwrap();
        }
        if start.elapsed().as_secs_f64() > limit {
            let _ = child.kill();
            panic!("curvenet {args:?} still ran after {limit} s (a hang)");
        }
        std::thread::sleep(Duration::from_millis(20));
    }
}

fn curvenet(args: &[&str]) -> Output {
    curvenet_within(300.0, args)
}

fn scratch(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("curvenet-faults-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// Three networks of examples in `dir/in`, in `ext`.
fn inputs(dir: &Path, ext: &str) -> PathBuf {
    let inputs = dir.join("in");
    std::fs::create_dir_all(&inputs).unwrap();
    for name in ["sphere", "torus", "cube"] {
        let o = curvenet(&["example", name, "-o", inputs.join(format!("{name}.{ext}")).to_str().unwrap()]);
        assert!(o.status.success());
    }
    inputs
}

/// Every file of `dir` with its bytes.
fn contents(dir: &Path) -> BTreeMap<String, Vec<u8>> {
    std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap())
        .filter(|e| e.file_type().unwrap().is_file())
        .map(|e| (e.file_name().to_string_lossy().into_owned(), std::fs::read(e.path()).unwrap()))
        .collect()
}

/// The report's lines, each of which must be a JSON object.
fn report(dir: &Path) -> Vec<serde_json::Value> {
    let text = std::fs::read_to_string(dir.join("report.jsonl")).unwrap_or_default();
    text.lines()
        .map(|l| serde_json::from_str::<serde_json::Value>(l).unwrap_or_else(|e| panic!("a torn line {l:?}: {e}")))
        .collect()
}

fn temporaries(dir: &Path) -> Vec<String> {
    std::fs::read_dir(dir)
        .map(|r| {
            r.map(|e| e.unwrap().file_name().to_string_lossy().into_owned()).filter(|n| n.ends_with(".tmp")).collect()
        })
        .unwrap_or_default()
}

fn text(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

#[test]
fn a_batch_never_writes_over_its_inputs() {
    let dir = scratch("inputs");
    let nets = inputs(&dir, "obj");
    let before = contents(&nets);
    std::os::unix::fs::symlink(&nets, dir.join("link")).unwrap();
    std::fs::hard_link(nets.join("cube.obj"), dir.join("cube.obj")).unwrap();
    let n = nets.to_str().unwrap();
    for out in [n, dir.join("link").to_str().unwrap(), dir.join("in/../in").to_str().unwrap()] {
        let o = curvenet(&["batch", n, "--out", out, "--format", "obj", "-q"]);
        assert_eq!(o.status.code(), Some(2), "--out {out}: {}", text(&o));
        assert!(text(&o).contains("would overwrite the input"), "{}", text(&o));
    }
    // A hard link in --out to an input is the input too.
    let o = curvenet(&[
        "batch",
        nets.join("cube.obj").to_str().unwrap(),
        "--out",
        dir.to_str().unwrap(),
        "--format",
        "obj",
    ]);
    assert_eq!(o.status.code(), Some(2), "{}", text(&o));
    assert_eq!(contents(&nets), before, "the inputs are byte-identical");
    // Into a folder of its own, or in another format beside them, the batch runs.
    let o = curvenet(&["batch", n, "--out", n, "--format", "ply", "-q", "--vertices", "2000"]);
    assert!(o.status.success(), "{}", text(&o));
    let after = contents(&nets);
    assert!(before.iter().all(|(k, v)| after.get(k) == Some(v)));
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn two_batches_into_one_folder_one_stops_the_report_stays_whole() {
    let dir = scratch("two");
    let nets = inputs(&dir, "json");
    let out = dir.join("out");
    let (n, o) = (nets.to_str().unwrap(), out.to_str().unwrap());
    // The first holds the folder while it surfaces; the second, started meanwhile, stops.
    let mut first = Command::new(bin())
        .args(["batch", n, "--out", o, "-q", "--vertices", "40000", "--jobs", "1"])
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let lock = out.join(".curvenet.lock");
    let start = Instant::now();
    while std::fs::read_to_string(&lock).map_or(true, |s| s.trim().is_empty()) && start.elapsed().as_secs() < 60 {
        std::thread::sleep(Duration::from_millis(10));
    }
    let second = curvenet(&["batch", n, "--out", o, "-q", "--vertices", "3000"]);
    let first_status = first.wait().unwrap();
    assert!(first_status.success());
    assert_eq!(second.status.code(), Some(2), "{}", text(&second));
    assert!(text(&second).contains("another curvenet run"), "{}", text(&second));
    let lines = report(&out);
    assert_eq!(lines.len(), 3);
    assert!(lines.iter().all(|l| l["options"]["vertices"] == "40000"), "every line is the first run's");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_fifo_is_an_input_error_not_a_hang() {
    let dir = scratch("fifo");
    let nets = inputs(&dir, "json");
    let fifo = nets.join("pipe.json");
    assert!(Command::new("mkfifo").arg(&fifo).status().unwrap().success());
    let out = dir.join("out");
    let o = curvenet_within(
        120.0,
        &[
            "batch",
            nets.to_str().unwrap(),
            fifo.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
            "--vertices",
            "2000",
        ],
    );
    assert_eq!(o.status.code(), Some(1), "{}", text(&o));
    let lines = report(&out);
    assert_eq!(lines.len(), 4, "three networks and the FIFO");
    let bad = lines.iter().find(|l| l["input"].as_str().unwrap().ends_with("pipe.json")).unwrap();
    assert_eq!(bad["status"], "error");
    assert!(bad["error"].as_str().unwrap().contains("FIFO"), "{bad}");
    assert_eq!(lines.iter().filter(|l| l["status"] == "ok").count(), 3);
    let _ = std::fs::remove_dir_all(&dir);
}

/// `kill -9` at several moments of a batch (reading, solving, writing): the next `--resume`
/// removes the temporary files the dead run left, keeps only whole meshes, and ends with every
/// mesh the same as an uninterrupted run's.
#[test]
fn kill_9_at_any_moment_then_resume_loses_nothing() {
    let dir = scratch("kill");
    let nets = inputs(&dir, "json");
    let n = nets.to_str().unwrap();
    let clean = dir.join("clean");
    let args = |out: &Path| -> Vec<String> {
        ["batch", n, "--out", out.to_str().unwrap(), "-q", "--vertices", "30000", "--jobs", "1"]
            .map(String::from)
            .to_vec()
    };
    let o = Command::new(bin()).args(args(&clean)).output().unwrap();
    assert!(o.status.success());
    let truth: BTreeMap<String, Vec<u8>> = contents(&clean).into_iter().filter(|(k, _)| k.ends_with(".ply")).collect();
    for (k, ms) in [50u64, 400, 900, 1500, 2500].into_iter().enumerate() {
        let out = dir.join(format!("out{k}"));
        let mut child = Command::new(bin()).args(args(&out)).stderr(Stdio::null()).spawn().unwrap();
        std::thread::sleep(Duration::from_millis(ms));
        let _ = child.kill(); // SIGKILL: no cleanup runs
        let _ = child.wait();
        // A temporary file of the killed run may be there; it must be gone after the resume.
        let _ = std::fs::create_dir_all(&out);
        std::fs::write(out.join(".sphere.ply.999999999.tmp"), b"partial").unwrap();
        let mut resume = args(&out);
        resume.push("--resume".into());
        let o = Command::new(bin()).args(&resume).output().unwrap();
        assert!(o.status.success(), "after a kill at {ms} ms: {}", text(&o));
        assert_eq!(temporaries(&out), Vec::<String>::new(), "after a kill at {ms} ms");
        assert_eq!(report(&out).len(), 3, "after a kill at {ms} ms");
        let meshes: BTreeMap<String, Vec<u8>> =
            contents(&out).into_iter().filter(|(k, _)| k.ends_with(".ply")).collect();
        assert!(meshes == truth, "after a kill at {ms} ms the meshes differ from an uninterrupted run's");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn resume_redoes_a_truncated_mesh_and_meshes_of_other_options() {
    let dir = scratch("resume");
    let nets = inputs(&dir, "json");
    let out = dir.join("out");
    let (n, o) = (nets.to_str().unwrap(), out.to_str().unwrap());
    assert!(curvenet(&["batch", n, "--out", o, "-q", "--vertices", "5000"]).status.success());
    let whole = std::fs::read(out.join("torus.ply")).unwrap();
    std::fs::write(out.join("torus.ply"), &whole[..whole.len() / 2]).unwrap();
    let r = curvenet(&["batch", n, "--out", o, "--vertices", "5000", "--resume"]);
    assert!(r.status.success());
    assert!(text(&r).contains("redoing") && text(&r).contains("torus.json"), "{}", text(&r));
    assert!(text(&r).contains("2 networks done in an earlier run, 1 to go"), "{}", text(&r));
    assert_eq!(std::fs::read(out.join("torus.ply")).unwrap(), whole);
    let torus = report(&out).into_iter().find(|l| l["input"].as_str().unwrap().ends_with("torus.json")).unwrap();
    assert!(torus["redone"].as_str().unwrap().contains("truncated"), "{torus}");
    // Other options: every mesh redone, the report says which option.
    let r = curvenet(&["batch", n, "--out", o, "--vertices", "8000", "--resume", "-q"]);
    assert!(r.status.success());
    let lines = report(&out);
    assert!(lines.iter().all(|l| l["redone"].as_str().is_some_and(|w| w.contains("vertices 5000 (now 8000)"))));
    // A changed input is redone too.
    std::fs::copy(nets.join("cube.json"), nets.join("sphere.json")).unwrap();
    let r = curvenet(&["batch", n, "--out", o, "--vertices", "8000", "--resume"]);
    assert!(text(&r).contains("sphere.json: the input changed since"), "{}", text(&r));
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_file_size_limit_is_an_io_error_with_nothing_left() {
    let dir = scratch("ulimit");
    let nets = inputs(&dir, "json");
    let mesh = dir.join("sphere.ply");
    let script = format!(
        "ulimit -f 64; exec '{}' surface '{}' -o '{}' --vertices 30000 -q",
        bin(),
        nets.join("sphere.json").display(),
        mesh.display()
    );
    let o = Command::new("sh").arg("-c").arg(&script).output().unwrap();
    assert_eq!(o.status.code(), Some(1), "{}", text(&o));
    assert!(text(&o).contains("ulimit -f"), "{}", text(&o));
    assert!(!mesh.exists());
    assert_eq!(temporaries(&dir), Vec::<String>::new());
    let _ = std::fs::remove_dir_all(&dir);
}
