//! `curvenet batch` (issue 19): every input reported, one failure never stopping the others,
//! `--resume`, folders and patterns, meshes identical to `curvenet surface`.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn curvenet(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_curvenet")).args(args).output().unwrap()
}

fn scratch(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("curvenet-batch-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// A folder of four good networks (JSON and `.net`) and two malformed ones.
fn folder(dir: &Path) -> PathBuf {
    let inputs = dir.join("in");
    std::fs::create_dir_all(&inputs).unwrap();
    for (name, file) in [("sphere", "a.json"), ("torus", "b.net"), ("cylinder", "c.json"), ("globe", "d.net")] {
        let o = curvenet(&["example", name, "-o", inputs.join(file).to_str().unwrap()]);
        assert!(o.status.success());
    }
    std::fs::write(inputs.join("e.json"), "{\"curves\": [").unwrap();
    std::fs::write(inputs.join("f.net"), "3\n0 0 0 0 0 1\n1 0 0 0 0 1\n0 1 0 0 0 1\n1\n1\n0 1 7 0\n").unwrap();
    std::fs::write(inputs.join("notes.txt"), "not a network").unwrap();
    inputs
}

fn report(dir: &Path) -> Vec<serde_json::Value> {
    let text = std::fs::read_to_string(dir.join("report.jsonl")).unwrap();
    text.lines().map(|l| serde_json::from_str(l).unwrap()).collect()
}

#[test]
fn a_folder_with_bad_networks_is_reported_line_by_line() {
    let dir = scratch("folder");
    let inputs = folder(&dir);
    let out = dir.join("out");
    let o = curvenet(&["batch", inputs.to_str().unwrap(), "--out", out.to_str().unwrap(), "--jobs", "2", "--fast"]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(1), "{err}");
    assert!(err.contains("6 networks: 4 ok, 2 failed"), "{err}");
    let lines = report(&out);
    assert_eq!(lines.len(), 6, "one line per network (notes.txt is not one)");
    for l in &lines {
        let input = l["input"].as_str().unwrap();
        let bad = input.ends_with("e.json") || input.ends_with("f.net");
        if bad {
            assert_eq!(l["status"], "error", "{l}");
            assert!(matches!(l["error_kind"].as_str(), Some("parse" | "input")), "{l}");
            assert!(l["error"].as_str().unwrap().contains(input), "the message names the file: {l}");
            assert_eq!(l["exit_code"], 1);
        } else {
            assert_eq!(l["status"], "ok", "{l}");
            let mesh = Path::new(l["output"].as_str().unwrap());
            assert!(mesh.is_file(), "{l}");
            assert!(l["stats"]["vertices"].as_u64().unwrap() > 1000, "{l}");
        }
    }
    // No leftovers: meshes for the good ones, the report, the folder's lock file, nothing else.
    let mut names: Vec<String> =
        std::fs::read_dir(&out).unwrap().map(|e| e.unwrap().file_name().to_string_lossy().into_owned()).collect();
    names.sort();
    assert_eq!(names, [".curvenet.lock", "a.ply", "b.ply", "c.ply", "d.ply", "report.jsonl"]);

    // --resume: the four done are kept, the two bad ones tried again, the report still whole.
    let o = curvenet(&["batch", inputs.to_str().unwrap(), "--out", out.to_str().unwrap(), "--fast", "--resume"]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(1), "{err}");
    assert!(err.contains("4 networks done in an earlier run, 2 to go"), "{err}");
    assert_eq!(report(&out).len(), 6);
    // Once the bad ones are mended, the batch succeeds.
    std::fs::remove_file(inputs.join("e.json")).unwrap();
    std::fs::remove_file(inputs.join("f.net")).unwrap();
    let o = curvenet(&["batch", inputs.to_str().unwrap(), "--out", out.to_str().unwrap(), "--fast", "--resume", "-q"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert_eq!(report(&out).len(), 4);
    let _ = std::fs::remove_dir_all(&dir);
}

/// Patterns and files, a missing file reported (not fatal), one job: the meshes are the bytes
/// `curvenet surface` writes (with one job the solve has every thread, as a single run).
#[test]
fn patterns_missing_files_and_identical_meshes() {
    let dir = scratch("pattern");
    let inputs = folder(&dir);
    let out = dir.join("out");
    let pattern = format!("{}/*.json", inputs.display());
    let missing = inputs.join("missing.json");
    let o = curvenet(&[
        "batch",
        &pattern,
        missing.to_str().unwrap(),
        inputs.join("b.net").to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--jobs",
        "1",
        "--format",
        "obj",
    ]);
    assert_eq!(o.status.code(), Some(1));
    let lines = report(&out);
    assert_eq!(lines.len(), 5, "a.json c.json e.json missing.json b.net");
    let missing_line = lines.iter().find(|l| l["input"].as_str().unwrap().ends_with("missing.json")).unwrap();
    assert_eq!(missing_line["error_kind"], "io");
    let single = dir.join("single.obj");
    let o = curvenet(&["surface", inputs.join("b.net").to_str().unwrap(), "-o", single.to_str().unwrap(), "-q"]);
    assert!(o.status.success());
    assert_eq!(std::fs::read(&single).unwrap(), std::fs::read(out.join("b.obj")).unwrap());
    // Bad arguments are usage errors before any work.
    let o = curvenet(&["batch", &pattern, "--out", out.to_str().unwrap(), "--jobs", "0"]);
    assert_eq!(o.status.code(), Some(2));
    let o = curvenet(&["batch", "/nonexistent/*.json", "--out", out.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(2), "{}", String::from_utf8_lossy(&o.stderr));
    let _ = std::fs::remove_dir_all(&dir);
}
