//! Curve names in the messages of a run (issue 33: `vacuum.obj` said `curve 41 ("input curve
//! 42")`, then `curve 41 ("input curve 43")` — one number, two curves, after a curve was left
//! out). On the vendored sketches, every number a run's warnings and errors give names one
//! curve.

use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;
use std::process::Command;

/// Per curve number in `text`: the labels it appears with (`curve 41`, or `curve 41 ("rim")` as
/// messages once named curves; a named curve is now `curve "rim"`, without a number).
fn labels(text: &str) -> BTreeMap<String, BTreeSet<String>> {
    let mut out: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
    let mut from = 0;
    while let Some(found) = text[from..].find("curve ") {
        let at = from + found;
        let start = at + "curve ".len();
        from = start;
        // A whole word ("curve", not "crease curve"'s end of another word) followed by a number.
        if text[..at].chars().next_back().is_some_and(|c| c.is_alphanumeric()) {
            continue;
        }
        let digits: String = text[start..].chars().take_while(char::is_ascii_digit).collect();
        if digits.is_empty() {
            continue;
        }
        let rest = &text[start + digits.len()..];
        let label = match rest.strip_prefix(" (\"").and_then(|r| r.find("\")").map(|e| &r[..e])) {
            Some(name) => format!("curve {digits} (\"{name}\")"),
            None => format!("curve {digits}"),
        };
        out.entry(digits).or_default().insert(label);
    }
    out
}

#[test]
fn one_number_names_one_curve_in_every_message_of_a_run() {
    let sketches = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../data/sketches");
    let dir = std::env::temp_dir().join(format!("curvenet-names-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let mut files: Vec<_> = std::fs::read_dir(&sketches).unwrap().flatten().map(|e| e.path()).collect();
    files.retain(|p| p.extension().is_some_and(|e| e == "obj"));
    files.sort();
    assert!(files.len() >= 6, "{files:?}");
    for f in &files {
        let out = dir.join("out.ply");
        let o = Command::new(env!("CARGO_BIN_EXE_curvenet"))
            .args(["surface", f.to_str().unwrap(), "-o", out.to_str().unwrap(), "--vertices", "4000", "--fast"])
            .output()
            .unwrap();
        let text = String::from_utf8_lossy(&o.stderr);
        for (n, names) in labels(&text) {
            assert!(names.len() == 1, "{}: curve {n} is named {names:?} in one run:\n{text}", f.display());
        }
        // Each name can be found in the input: `curve at line N` at an `l` statement,
        // `curve "name"` in the file's text.
        let input = std::fs::read_to_string(f).unwrap();
        let lines: Vec<&str> = input.lines().collect();
        for part in text.split("curve at line ").skip(1) {
            let n: usize = part.chars().take_while(char::is_ascii_digit).collect::<String>().parse().unwrap();
            assert!(lines.get(n - 1).is_some_and(|l| l.starts_with("l ")), "{}: line {n} is no polyline", f.display());
        }
        for part in text.split("curve \"").skip(1) {
            let name = part.split('"').next().unwrap();
            assert!(input.contains(name), "{}: curve \"{name}\" is not in the file", f.display());
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
}
