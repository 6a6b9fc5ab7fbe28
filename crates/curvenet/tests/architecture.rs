//! The layout rules of the project (docs/design.md §11), checked on the source tree: the
//! library's module tree reads as the pipeline — at most 15 top-level modules, no import cycle
//! between them — and no source file or function grows past what a reader takes in (900 lines
//! per file, 150 per function; tests aside).

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

const MAX_TOP_LEVEL_MODULES: usize = 15;
const MAX_FILE_LINES: usize = 900;
const MAX_FUNCTION_LINES: usize = 150;

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// The `.rs` files below `dir`, without test folders (`tests/`) and build outputs.
fn sources(dir: &Path, out: &mut Vec<PathBuf>) {
    let Ok(entries) = std::fs::read_dir(dir) else { return };
    let mut entries: Vec<_> = entries.flatten().map(|e| e.path()).collect();
    entries.sort();
    for p in entries {
        let name = p.file_name().and_then(|n| n.to_str()).unwrap_or("");
        if p.is_dir() {
            if name != "tests" && name != "target" {
                sources(&p, out);
            }
        } else if name.ends_with(".rs") {
            out.push(p);
        }
    }
}

/// The code of each line of `text` without comments (doc comments included) and with the
/// contents of string and char literals removed (strings may span lines).
fn code_lines(text: &str) -> Vec<String> {
    let mut out = Vec::new();
    let mut in_str = false;
    for line in text.lines() {
        let mut code = String::new();
        let mut chars = line.chars().peekable();
        while let Some(c) = chars.next() {
            match c {
                '\\' if in_str => {
                    chars.next();
                }
                '"' => {
                    in_str = !in_str;
                    code.push('"');
                }
                _ if in_str => {}
                '/' if chars.peek() == Some(&'/') => break,
                '\'' => {
                    // A char literal ('{', '\n') or a lifetime ('a): skip a literal's content.
                    let rest: String = chars.clone().take(3).collect();
                    if rest.starts_with('\\') {
                        chars.next();
                        chars.next();
                        if chars.peek() == Some(&'\'') {
                            chars.next();
                        }
                    } else if rest.chars().nth(1) == Some('\'') {
                        chars.next();
                        chars.next();
                    }
                    code.push('\'');
                }
                _ => code.push(c),
            }
        }
        out.push(code);
    }
    out
}

/// The code lines of `text` up to an inline `#[cfg(test)] mod tests { … }` (tests aside).
fn without_inline_tests(text: &str) -> Vec<String> {
    let mut lines = code_lines(text);
    let raw: Vec<&str> = text.lines().collect();
    let is_mod = |l: &str| {
        let l = l.trim();
        let decl = l.starts_with("mod ") || l.starts_with("pub mod ") || l.starts_with("pub(crate) mod ");
        decl && l.ends_with('{')
    };
    let inline_tests =
        (0..raw.len()).find(|&i| raw[i].trim() == "#[cfg(test)]" && raw.get(i + 1).is_some_and(|l| is_mod(l)));
    if let Some(end) = inline_tests {
        lines.truncate(end);
    }
    lines
}

fn lib_rs() -> String {
    std::fs::read_to_string(root().join("crates/curvenet/src/lib.rs")).unwrap()
}

/// The modules `lib.rs` declares (`mod x;` with any visibility and attributes).
fn top_level_modules() -> Vec<String> {
    code_lines(&lib_rs())
        .iter()
        .filter_map(|l| {
            let words: Vec<&str> = l.split_whitespace().collect();
            let i = words.iter().position(|w| *w == "mod")?;
            words[..i].iter().all(|w| w.starts_with("pub") || w.starts_with("#[")).then_some(())?;
            Some(words.get(i + 1)?.trim_end_matches(';').to_string())
        })
        .collect()
}

/// The names `lib.rs` re-exports at the crate root, with the module they come from
/// (`pub use pipeline::{surface, Options};` → `surface`, `Options` → `pipeline`).
fn root_reexports() -> BTreeMap<String, String> {
    let mut out = BTreeMap::new();
    for l in code_lines(&lib_rs()) {
        let Some(rest) = l.trim().strip_prefix("pub use ") else { continue };
        let module: String = rest.chars().take_while(|c| c.is_ascii_alphanumeric() || *c == '_').collect();
        let tail = rest.trim_end_matches(';');
        let names: Vec<&str> = match (tail.find('{'), tail.rfind('}')) {
            (Some(a), Some(b)) => tail[a + 1..b].split(',').collect(),
            _ => vec![tail],
        };
        for n in names {
            let n = n.trim().rsplit("::").next().unwrap_or("").trim();
            if !n.is_empty() {
                out.insert(n.to_string(), module.clone());
            }
        }
    }
    out
}

/// The first path segment of each name the code `c` reaches through `crate::` (a group
/// `crate::{a, b::c}` is expanded to `a`, `b`).
fn crate_paths(c: &str) -> Vec<String> {
    let ident = |s: &str| -> String { s.chars().take_while(|ch| ch.is_ascii_alphanumeric() || *ch == '_').collect() };
    let mut out = Vec::new();
    for (i, _) in c.match_indices("crate::") {
        let rest = &c[i + 7..];
        let Some(group) = rest.strip_prefix('{') else {
            out.push(ident(rest));
            continue;
        };
        // The group's top-level items (nested groups skipped by depth).
        let mut depth = 0;
        let mut item = String::new();
        for ch in group.chars() {
            match ch {
                '{' => depth += 1,
                '}' if depth == 0 => break,
                '}' => depth -= 1,
                ',' if depth == 0 => {
                    out.push(ident(item.trim()));
                    item.clear();
                    continue;
                }
                _ => {}
            }
            if depth == 0 {
                item.push(ch);
            }
        }
        out.push(ident(item.trim()));
    }
    out.retain(|s| !s.is_empty());
    out
}

#[test]
fn at_most_15_top_level_modules() {
    let modules = top_level_modules();
    assert!(modules.len() >= 10, "the scan finds the modules: {modules:?}");
    assert!(modules.len() <= MAX_TOP_LEVEL_MODULES, "{} top-level modules: {modules:?}", modules.len());
}

/// The edges `a → b` of the top-level modules: `a`'s code names `crate::b`, or a name the crate
/// root re-exports from `b`.
fn module_graph(modules: &[String]) -> BTreeMap<String, BTreeSet<String>> {
    let src = root().join("crates/curvenet/src");
    let reexports = root_reexports();
    let mut graph = BTreeMap::new();
    for m in modules {
        let mut files = Vec::new();
        let file = src.join(format!("{m}.rs"));
        if file.exists() {
            files.push(file);
        }
        sources(&src.join(m), &mut files);
        let mut uses = BTreeSet::new();
        for f in files {
            let text = std::fs::read_to_string(&f).unwrap();
            for c in without_inline_tests(&text) {
                assert!(!c.contains("super::super::super"), "{}: name distant modules by crate:: paths", f.display());
                for name in crate_paths(&c) {
                    let module = if modules.contains(&name) { Some(name) } else { reexports.get(&name).cloned() };
                    if let Some(module) = module.filter(|x| x != m) {
                        uses.insert(module);
                    }
                }
            }
        }
        graph.insert(m.clone(), uses);
    }
    graph
}

#[test]
fn no_import_cycle_between_top_level_modules() {
    let modules = top_level_modules();
    let graph = module_graph(&modules);
    assert!(graph["pipeline"].contains("methods"), "the scan finds imports: {graph:?}");
    // Through a crate-root re-export (`crate::Surface` is `pipeline::Surface`) too.
    assert!(graph["render"].contains("pipeline"), "the scan follows re-exports: {graph:?}");
    // Kahn's algorithm: whatever is left has a cycle.
    let mut left: BTreeMap<&String, BTreeSet<&String>> = graph.iter().map(|(k, v)| (k, v.iter().collect())).collect();
    loop {
        let free: Vec<&String> = left.iter().filter(|(_, v)| v.is_empty()).map(|(k, _)| *k).collect();
        if free.is_empty() {
            break;
        }
        for k in free {
            left.remove(k);
            for v in left.values_mut() {
                v.remove(k);
            }
        }
    }
    assert!(left.is_empty(), "import cycle among {left:?}");
}

/// Every non-test source file of the workspace's crates.
fn workspace_sources() -> Vec<PathBuf> {
    let mut files = Vec::new();
    for dir in ["crates/curvenet/src", "crates/curvenet-cli/src", "python/src", "viewer/wasm/src"] {
        sources(&root().join(dir), &mut files);
    }
    files
}

#[test]
fn no_file_over_900_lines() {
    let files = workspace_sources();
    assert!(files.len() > 50, "found {} files", files.len());
    let long: Vec<String> = files
        .iter()
        .map(|f| (f, std::fs::read_to_string(f).unwrap().lines().count()))
        .filter(|(_, n)| *n > MAX_FILE_LINES)
        .map(|(f, n)| format!("{} ({n} lines)", f.display()))
        .collect();
    assert!(long.is_empty(), "files over {MAX_FILE_LINES} lines: {long:?}");
}

/// `(name, first line, length)` of every `fn` in `text`, nested closures counted in their
/// function, by matching braces (comments and literals left out).
fn functions(text: &str) -> Vec<(String, usize, usize)> {
    let lines = without_inline_tests(text);
    let mut out = Vec::new();
    for (i, c) in lines.iter().enumerate() {
        let t = c.trim_start();
        let Some(pos) = t.find("fn ") else { continue };
        // Qualifiers before `fn` (literals are emptied: `extern "C"` reads `extern ""`).
        let words_ok = t[..pos].split_whitespace().all(|w| {
            w.starts_with("pub") || w.starts_with("#[") || ["const", "async", "unsafe", "extern", "\"\""].contains(&w)
        });
        if !words_ok || !(pos == 0 || t[..pos].ends_with(' ')) {
            continue;
        }
        let name: String = t[pos + 3..].chars().take_while(|ch| ch.is_ascii_alphanumeric() || *ch == '_').collect();
        if name.is_empty() {
            continue;
        }
        let mut depth = 0i64;
        let mut started = false;
        for (j, c) in lines.iter().enumerate().skip(i) {
            depth += c.matches('{').count() as i64 - c.matches('}').count() as i64;
            started |= c.contains('{');
            if (started && depth <= 0) || (!started && c.trim_end().ends_with(';')) {
                out.push((name.clone(), i + 1, j - i + 1));
                break;
            }
        }
    }
    out
}

#[test]
fn the_scanners_see_what_they_must() {
    let text = "fn a() {\n    let s = \"}\n{\";\n    let c = '{';\n}\npub(crate) fn b(x: u32) -> u32\n{\n    x\n}\n\
                #[no_mangle]\npub extern \"C\" fn c() {\n}\n#[cfg(test)]\nfn d() {\n}\n#[cfg(test)]\nmod tests {\nfn e() {}\n}\n";
    let found = functions(text);
    let expected: Vec<(String, usize, usize)> =
        vec![("a".into(), 1, 5), ("b".into(), 6, 4), ("c".into(), 11, 2), ("d".into(), 14, 2)];
    assert_eq!(found, expected);
    assert_eq!(crate_paths("use crate::{geom::DVec3, error::Error}; crate::io::x"), vec!["geom", "error", "io"]);
    assert_eq!(root_reexports().get("Surfacer").map(String::as_str), Some("pipeline"));
}

#[test]
fn no_function_over_150_lines() {
    let mut long = Vec::new();
    let mut count = 0;
    for f in workspace_sources() {
        let text = std::fs::read_to_string(&f).unwrap();
        for (name, line, n) in functions(&text) {
            count += 1;
            if n > MAX_FUNCTION_LINES {
                long.push(format!("{}:{line} {name} ({n} lines)", f.display()));
            }
        }
    }
    assert!(count > 500, "the scan finds the functions: {count}");
    assert!(long.is_empty(), "functions over {MAX_FUNCTION_LINES} lines: {long:?}");
}

/// `cargo tree`'s resolved features of every crate in the graph of `args`: `name version` →
/// features.
fn resolved_features(args: &[&str]) -> BTreeMap<String, String> {
    let o = std::process::Command::new(env!("CARGO"))
        .args(["tree", "--locked", "--prefix", "none", "-f", "{p}|{f}"])
        .args(args)
        .current_dir(root())
        .output()
        .expect("cargo tree runs");
    assert!(o.status.success(), "cargo tree {args:?}: {}", String::from_utf8_lossy(&o.stderr));
    let mut out = BTreeMap::new();
    for line in String::from_utf8_lossy(&o.stdout).lines() {
        let Some((p, f)) = line.trim_end_matches(" (*)").split_once('|') else { continue };
        // `name vX.Y.Z` (a path crate adds its folder; a proc macro "(proc-macro)").
        let key: String = p.split_whitespace().take(2).collect::<Vec<_>>().join(" ");
        let f = f.trim_end_matches(" (*)").trim().to_string();
        let merged = out.entry(key).or_insert_with(String::new);
        let mut all: BTreeSet<String> =
            merged.split(',').chain(f.split(',')).filter(|s| !s.is_empty()).map(String::from).collect();
        all.remove("");
        *merged = all.into_iter().collect::<Vec<_>>().join(",");
    }
    out
}

/// One build serves the demo, the tests and Python (issue 33): every crate that the CLI's
/// build shares with the workspace's test build, or with the Python bindings' build, is
/// resolved with the same features, so that the README's test command and `pip install
/// ./python` compile none of them again (measured on a fresh target: the test build after the
/// CLI's compiled only the tests' own crates and the workspace's targets, 86 s; pip after it
/// only PyO3, NumPy and the bindings, 23 s). A crate that breaks this is named here; give the
/// library the features the other graph turns on (crates/curvenet/Cargo.toml).
#[test]
fn one_build_serves_the_cli_the_tests_and_python() {
    let cli = resolved_features(&["-p", "curvenet-cli", "-e", "normal,build"]);
    let tests = resolved_features(&["--workspace", "-e", "normal,build,dev"]);
    let python = resolved_features(&["-p", "curvenet-py", "-e", "normal,build"]);
    assert!(cli.contains_key("faer v0.24.4") || cli.keys().any(|k| k.starts_with("faer ")), "{cli:?}");
    for (other, name) in [(&tests, "the workspace's tests"), (&python, "the Python bindings")] {
        let differ: Vec<String> = cli
            .iter()
            .filter_map(|(k, f)| other.get(k).filter(|g| *g != f).map(|g| format!("{k}: CLI [{f}], {name} [{g}]")))
            .collect();
        assert!(differ.is_empty(), "crates built twice, with other features for {name}: {differ:#?}");
    }
}
