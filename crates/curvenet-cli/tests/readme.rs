//! The README's "Use" block and the demo's "Next:" line run as written (issue 33: they named
//! files a new user does not have). Each line runs in a fresh folder with the repository's
//! `data/` beside it, in order (later lines use the files of earlier ones); `curvenet` is this
//! build's binary.

use std::path::{Path, PathBuf};
use std::process::Command;

fn repo() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..").canonicalize().unwrap()
}

fn scratch(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("curvenet-readme-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// Runs a `curvenet …` line (comments cut, no quoting in these lines) in `dir`; panics with its
/// stderr unless it exits 0.
fn run_line(line: &str, dir: &Path) -> String {
    let code = line.split(" #").next().unwrap().trim();
    let mut words = code.split_whitespace();
    assert_eq!(words.next(), Some("curvenet"), "{line}");
    let o = Command::new(env!("CARGO_BIN_EXE_curvenet")).args(words).current_dir(dir).output().unwrap();
    assert!(o.status.success(), "`{code}` failed: {}", String::from_utf8_lossy(&o.stderr));
    String::from_utf8_lossy(&o.stdout).into_owned()
}

#[cfg(unix)]
#[test]
fn the_readme_use_block_runs_as_written() {
    let readme = std::fs::read_to_string(repo().join("README.md")).unwrap();
    let block: Vec<&str> = readme
        .lines()
        .skip_while(|l| *l != "## Use")
        .skip_while(|l| !l.starts_with("```"))
        .skip(1)
        .take_while(|l| !l.starts_with("```"))
        .filter(|l| l.starts_with("curvenet "))
        .collect();
    assert!(block.len() >= 8, "the Use block: {block:?}");
    let dir = scratch("use");
    std::os::unix::fs::symlink(repo().join("data"), dir.join("data")).unwrap();
    for line in &block {
        run_line(line, &dir);
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn the_demo_next_line_runs_as_written() {
    let dir = scratch("demo-next");
    let out = run_line("curvenet demo", &dir);
    let next = out.lines().find_map(|l| l.strip_prefix("Next: ")).unwrap_or_else(|| panic!("no Next: line in {out}"));
    run_line(next, &dir);
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Every option of `curvenet surface --help` is in the README: the surfacing and output options
/// in the `curvenet surface` table (as `` `--flag``), the picture options (`--render`'s, under
/// "Picture") in the `curvenet render` section (issue 33: the table lacked `--infer-normals`
/// and `--render`).
#[test]
fn every_surface_option_is_in_the_readme() {
    let readme = std::fs::read_to_string(repo().join("README.md")).unwrap();
    let section = |start: &str| -> String {
        readme
            .lines()
            .skip_while(|l| !l.starts_with(start))
            .skip(1)
            .take_while(|l| !l.starts_with("### "))
            .collect::<Vec<_>>()
            .join("\n")
    };
    let (table, render) = (section("### `curvenet surface"), section("### `curvenet render"));
    let o = Command::new(env!("CARGO_BIN_EXE_curvenet")).args(["surface", "--help"]).output().unwrap();
    let help = String::from_utf8_lossy(&o.stdout).into_owned();
    let mut picture = false;
    let mut missing = Vec::new();
    let mut seen = 0;
    for line in help.lines() {
        if !line.starts_with(' ') && line.ends_with(':') {
            picture = line.starts_with("Picture");
            continue;
        }
        let Some(flag) = line.split_whitespace().find(|w| w.starts_with("--")) else { continue };
        let flag: String = flag.chars().take_while(|c| *c == '-' || c.is_ascii_alphanumeric()).collect();
        if !line.trim_start().starts_with('-') || flag == "--help" {
            continue;
        }
        seen += 1;
        let doc = if picture { &render } else { &table };
        if !doc.contains(&format!("`{flag}"))
            && !doc.contains(&format!("`-q, {flag}"))
            && !doc.contains(&format!("`-o, {flag}"))
        {
            missing.push(flag);
        }
    }
    assert!(seen >= 25, "{seen} options read from the help");
    assert!(missing.is_empty(), "not in the README: {missing:?}");
    // And the other way: every option the table's first column names is one the help gives
    // (a renamed or removed option does not linger in the README).
    let mut stale = Vec::new();
    for row in table.lines().filter(|l| l.starts_with("| `")) {
        let first = row.split('|').nth(1).unwrap_or("");
        for word in first.split(|c: char| c == '`' || c == ',' || c.is_whitespace()) {
            let flag: String = word.chars().take_while(|c| *c == '-' || c.is_ascii_alphanumeric()).collect();
            if flag.starts_with("--")
                && !help.contains(&format!("{flag} "))
                && !help.contains(&format!("{flag}\n"))
                && !help.contains(&format!("{flag}["))
            {
                stale.push(flag);
            }
        }
    }
    assert!(stale.is_empty(), "in the README's table, not in `surface --help`: {stale:?}");
}

/// The numbers `d.de-x` of `text` (scientific notation, as the reports write them).
fn scientific(text: &str) -> Vec<String> {
    let mut out = Vec::new();
    for word in text.split(|c: char| !(c.is_ascii_digit() || c == '.' || c == 'e' || c == '-')) {
        let word = word.trim_matches(|c: char| c == '.' || c == '-');
        if let Some((m, e)) = word.split_once('e') {
            if m.contains('.') && m.parse::<f64>().is_ok() && e.parse::<i32>().is_ok() {
                out.push(word.to_string());
            }
        }
    }
    out
}

/// Every figure of the README's "Measured" section in scientific notation is one of
/// docs/accuracy.md's (the generated report) to the digits the README quotes (issue 33: the
/// README's sections gave the soft constraints' figures two ways, neither the report's).
#[test]
fn the_readme_measured_figures_are_the_reports() {
    let readme = std::fs::read_to_string(repo().join("README.md")).unwrap();
    let start = readme.find("## Measured").unwrap();
    let section = &readme[start..start + readme[start..].find("\n## Pictures").unwrap()];
    let report = std::fs::read_to_string(repo().join("docs/accuracy.md")).unwrap();
    let values: Vec<f64> = report
        .split(|c: char| !(c.is_ascii_digit() || c == '.' || c == 'e' || c == '-'))
        .filter_map(|w| w.trim_matches(|c: char| c == '.' || c == '-').parse::<f64>().ok())
        .collect();
    let quoted = scientific(section);
    assert!(quoted.len() >= 15, "{quoted:?}");
    let mut absent = Vec::new();
    for q in &quoted {
        let (m, e) = q.split_once('e').unwrap();
        let decimals = m.split_once('.').map_or(0, |(_, d)| d.len()) as i32;
        let half_unit = 0.5 * 10f64.powi(e.parse::<i32>().unwrap() - decimals);
        let v: f64 = q.parse().unwrap();
        if !values.iter().any(|a| (a - v).abs() <= half_unit * 1.0001) {
            absent.push(q.clone());
        }
    }
    assert!(absent.is_empty(), "README figures not in docs/accuracy.md: {absent:?}");
}
