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

/// The `.rs` files below `dir`, without test folders (`tests/`) and fuzz/build outputs.
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

/// The code of a line without its `//` comment (doc comments included) and string contents.
fn code(line: &str) -> String {
    let mut out = String::new();
    let mut in_str = false;
    let mut chars = line.chars().peekable();
    while let Some(c) = chars.next() {
        match c {
            '\\' if in_str => {
                chars.next();
            }
            '"' => {
                in_str = !in_str;
                out.push('"');
            }
            '/' if !in_str && chars.peek() == Some(&'/') => break,
            _ if in_str => {}
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
                out.push('\'');
            }
            _ => out.push(c),
        }
    }
    out
}

/// The lines of `text` up to an inline `#[cfg(test)] mod tests {` block (tests aside).
fn without_inline_tests(text: &str) -> Vec<&str> {
    let lines: Vec<&str> = text.lines().collect();
    let end = (0..lines.len())
        .find(|&i| lines[i].trim() == "#[cfg(test)]" && lines.get(i + 1).is_some_and(|l| l.trim().ends_with('{')))
        .unwrap_or(lines.len());
    lines[..end].to_vec()
}

fn top_level_modules() -> Vec<String> {
    let lib = std::fs::read_to_string(root().join("crates/curvenet/src/lib.rs")).unwrap();
    lib.lines()
        .filter_map(|l| l.trim().strip_prefix("pub mod ").or_else(|| l.trim().strip_prefix("mod ")))
        .map(|m| m.trim_end_matches(';').to_string())
        .collect()
}

#[test]
fn at_most_15_top_level_modules() {
    let modules = top_level_modules();
    assert!(modules.len() <= MAX_TOP_LEVEL_MODULES, "{} top-level modules: {modules:?}", modules.len());
}

/// The edges `a → b` of the top-level modules: `a`'s code names `crate::b`.
fn module_graph(modules: &[String]) -> BTreeMap<String, BTreeSet<String>> {
    let src = root().join("crates/curvenet/src");
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
            for line in without_inline_tests(&text) {
                let c = code(line);
                for (i, _) in c.match_indices("crate::") {
                    let name: String =
                        c[i + 7..].chars().take_while(|ch| ch.is_ascii_alphanumeric() || *ch == '_').collect();
                    if modules.contains(&name) && &name != m {
                        uses.insert(name);
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
    assert!(left.is_empty(), "import cycle among {:?}", left);
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
/// function, by matching braces.
fn functions(text: &str) -> Vec<(String, usize, usize)> {
    let lines = without_inline_tests(text);
    let mut out = Vec::new();
    for (i, line) in lines.iter().enumerate() {
        let c = code(line);
        let t = c.trim_start();
        let Some(pos) = t.find("fn ") else { continue };
        let head = &t[..pos];
        let words_ok = head
            .split_whitespace()
            .all(|w| w.starts_with("pub") || ["const", "async", "unsafe", "extern", "\"C\"", "default"].contains(&w));
        if !words_ok || !(pos == 0 || t[..pos].ends_with(' ')) {
            continue;
        }
        let name: String = t[pos + 3..].chars().take_while(|ch| ch.is_ascii_alphanumeric() || *ch == '_').collect();
        if name.is_empty() {
            continue;
        }
        let mut depth = 0i64;
        let mut started = false;
        for (j, l) in lines.iter().enumerate().skip(i) {
            let c = code(l);
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
fn the_function_scanner_counts_lines() {
    let text = "fn a() {\n    let s = \"}\";\n    let c = '{';\n}\npub(crate) fn b(x: u32) -> u32\n{\n    x\n}\n";
    assert_eq!(functions(text), vec![("a".into(), 1, 4), ("b".into(), 5, 4)]);
}

#[test]
fn no_function_over_150_lines() {
    let mut long = Vec::new();
    for f in workspace_sources() {
        let text = std::fs::read_to_string(&f).unwrap();
        for (name, line, n) in functions(&text) {
            if n > MAX_FUNCTION_LINES {
                long.push(format!("{}:{line} {name} ({n} lines)", f.display()));
            }
        }
    }
    assert!(long.is_empty(), "functions over {MAX_FUNCTION_LINES} lines: {long:?}");
}
