//! The bad-input catalogue (`tests/data/bad/` at the repository root, made by its
//! `generate.py`): every file there must make `curvenet surface FILE -o OUT` exit with the
//! expected code and a message containing the expected substrings, never panic, and leave no
//! output and no temporary file behind; an output that existed before is left byte-identical.
//! The few hard inputs the pipeline now handles (a dangling curve, a folding projection) are
//! kept with exit 0: they must be surfaced, with the expected warning.

use std::path::{Path, PathBuf};
use std::process::Command;

fn catalogue() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../tests/data/bad")
}

/// A fresh scratch directory.
fn scratch(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("curvenet-bad-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

struct Case {
    file: String,
    exit: i32,
    messages: Vec<String>,
}

fn manifest() -> Vec<Case> {
    let text = std::fs::read_to_string(catalogue().join("expected.json")).unwrap();
    let doc: serde_json::Value = serde_json::from_str(&text).unwrap();
    doc.as_object()
        .unwrap()
        .iter()
        .map(|(file, v)| Case {
            file: file.clone(),
            exit: v["exit"].as_i64().unwrap() as i32,
            messages: v["message"].as_array().unwrap().iter().map(|m| m.as_str().unwrap().to_string()).collect(),
        })
        .collect()
}

#[test]
fn every_catalogue_file_has_an_expectation() {
    let cases = manifest();
    let listed: std::collections::BTreeSet<&str> = cases.iter().map(|c| c.file.as_str()).collect();
    let mut files = 0;
    for entry in std::fs::read_dir(catalogue()).unwrap() {
        let name = entry.unwrap().file_name().into_string().unwrap();
        if name == "expected.json" || name == "generate.py" {
            continue;
        }
        files += 1;
        assert!(listed.contains(name.as_str()), "{name} has no entry in expected.json");
    }
    assert_eq!(files, cases.len(), "expected.json lists files that do not exist");
    // Every network format is covered.
    for ext in [".json", ".obj", ".net"] {
        assert!(cases.iter().filter(|c| c.file.ends_with(ext)).count() >= 15, "few {ext} cases");
    }
}

#[test]
fn every_bad_input_fails_cleanly() {
    let dir = scratch("catalogue");
    let mut failures = Vec::new();
    for (k, case) in manifest().iter().enumerate() {
        // Even cases: no output before the run; odd cases: an existing output to keep intact.
        let out = dir.join(if k % 2 == 0 { "out.ply" } else { "out.obj" });
        let before = format!("previous result of case {k}\n").into_bytes();
        if k % 2 == 1 {
            std::fs::write(&out, &before).unwrap();
        }
        let o = Command::new(env!("CARGO_BIN_EXE_curvenet"))
            .args(["surface", catalogue().join(&case.file).to_str().unwrap(), "-o", out.to_str().unwrap(), "-q"])
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&o.stderr);
        let mut problems = Vec::new();
        if o.status.code() != Some(case.exit) {
            problems.push(format!("exit {:?}, expected {}", o.status.code(), case.exit));
        }
        for m in &case.messages {
            if !err.contains(m.as_str()) {
                problems.push(format!("message lacks {m:?}"));
            }
        }
        if case.exit == 0 {
            // A hard input the pipeline now handles (open networks, folding projections):
            // it is surfaced, with a warning saying what was done.
            if err.contains("panicked") || !err.starts_with("warning: ") {
                problems.push("no warning".into());
            }
            if std::fs::read(&out).map(|b| b == before || b.is_empty()).unwrap_or(true) {
                problems.push("no output written".into());
            }
        } else {
            if err.contains("panicked") || !err.starts_with("error: ") {
                problems.push("no clean error message".into());
            }
            if k % 2 == 0 && out.exists() {
                problems.push("an output file was written".into());
            }
            if k % 2 == 1 && std::fs::read(&out).ok().as_deref() != Some(&before[..]) {
                problems.push("the existing output was changed".into());
            }
        }
        let _ = std::fs::remove_file(&out);
        let stray: Vec<_> = std::fs::read_dir(&dir).unwrap().map(|e| e.unwrap().file_name()).collect();
        if !stray.is_empty() {
            problems.push(format!("files left behind: {stray:?}"));
            for s in stray {
                let _ = std::fs::remove_file(dir.join(s));
            }
        }
        if !problems.is_empty() {
            failures.push(format!("{}: {} — stderr: {}", case.file, problems.join("; "), err.trim()));
        }
    }
    std::fs::remove_dir_all(&dir).unwrap();
    assert!(failures.is_empty(), "{} case(s) failed:\n{}", failures.len(), failures.join("\n"));
}
