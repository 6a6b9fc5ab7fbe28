//! One network file to one mesh file, with a report of the run instead of an early return:
//! the unit of `curvenet batch` and of Python's `curvenet.surface_files` (local processes or a
//! Dask cluster), so that both report the same fields. The report records what the mesh was
//! made from (the input's content hash, the options) and what was written (the mesh's size and
//! hash), so that `--resume` keeps a mesh only when it is whole and still the one asked for
//! ([`resume`]).

use super::{surface, Options, Stats};
use crate::error::{Error, Result};
use serde::{Deserialize, Serialize};
use std::collections::{BTreeMap, HashMap, HashSet};
use std::path::{Path, PathBuf};
use std::time::Instant;

/// Network extensions a folder is searched for ([`expand_inputs`]).
pub const NETWORK_EXTENSIONS: [&str; 3] = ["json", "obj", "net"];

/// One network file of a batch and the mesh file it becomes.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct FileJob {
    /// The network file.
    pub input: PathBuf,
    /// The mesh file.
    pub output: PathBuf,
}

/// What became of one network file: a line of `curvenet batch`'s `report.jsonl`.
#[derive(Clone, Debug, Serialize)]
pub struct FileReport {
    /// The network file, as given.
    pub input: String,
    /// The mesh written (`None` when the run failed: nothing was written).
    pub output: Option<String>,
    /// `"ok"` or `"error"` (Python's `surface_files` adds `"crashed"`: the process surfacing
    /// this input died).
    pub status: &'static str,
    /// The input's content hash ([`content_hash`]), when it was read.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub input_hash: Option<String>,
    /// The options of the run, by name ([`options_record`]).
    pub options: BTreeMap<String, String>,
    /// The size of the mesh written, bytes.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub output_bytes: Option<u64>,
    /// The content hash of the mesh written.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub output_hash: Option<String>,
    /// Why an earlier run's mesh of this input was not kept by `--resume` (it was redone).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub redone: Option<String>,
    /// The error's kind ([`Error::kind`]: `parse`, `input`, `topology`, `io`, `numerical`,
    /// `memory`, …), on failure.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub error_kind: Option<&'static str>,
    /// The error's message, on failure.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub error: Option<String>,
    /// The exit code `curvenet surface` would give ([`Error::exit_code`]), on failure.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub exit_code: Option<i32>,
    /// What the run repaired, assumed or left out.
    pub warnings: Vec<String>,
    /// Wall time of the run (read, surface, write), seconds.
    pub seconds: f64,
    /// The run's statistics (as `--stats` writes them), on success.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub stats: Option<Stats>,
}

impl FileReport {
    /// The run succeeded.
    pub fn is_ok(&self) -> bool {
        self.status == "ok"
    }

    /// A failed run's report.
    pub fn failure(input: &Path, e: &Error, seconds: f64) -> Self {
        FileReport {
            input: input.display().to_string(),
            output: None,
            status: "error",
            input_hash: None,
            options: BTreeMap::new(),
            output_bytes: None,
            output_hash: None,
            redone: None,
            error_kind: Some(e.kind()),
            error: Some(e.to_string()),
            exit_code: Some(e.exit_code()),
            warnings: Vec::new(),
            seconds,
            stats: None,
        }
    }
}

/// Reads the network `input` (a regular file only: [`crate::io::open_regular`]), surfaces it
/// with `options` (a JSON network keeps its `cauchy` attributes for that method, as `curvenet
/// surface` reads them) and writes the mesh to `output` (atomically; the format from its
/// extension). Never fails: an error — a panic too, reported as an internal error — is the
/// report's.
pub fn surface_file(input: &Path, output: &Path, options: &Options) -> FileReport {
    let clock = Instant::now();
    let mut input_hash = None;
    let run = |input_hash: &mut Option<String>| -> Result<FileReport> {
        crate::io::check_mesh_path(output)?;
        let format = crate::io::NetworkFormat::from_path(input)?;
        let file = crate::io::open_regular(input)?;
        let bytes = crate::io::read_opened(file, input, crate::io::InputKind::Text, crate::io::MAX_INPUT_BYTES)?;
        *input_hash = Some(content_hash(&bytes));
        let text = crate::io::text_of(bytes, input)?;
        let (network, read_warnings) =
            crate::io::parse_network_with_warnings(&text, format, &input.display().to_string())?;
        drop(text);
        let mut opts = options.clone();
        if opts.method == crate::Method::Cauchy && opts.cauchy.attributes.is_none() {
            opts.cauchy.attributes =
                crate::methods::andrews2011::NetworkAttributes::read(input)?.map(std::sync::Arc::new);
        }
        let s = surface(&network, &opts)?;
        crate::io::write_mesh(output, s.mesh_data())?;
        let (output_bytes, output_hash) = file_hash(output).map_err(|e| Error::io(output, e))?;
        Ok(FileReport {
            input: input.display().to_string(),
            output: Some(output.display().to_string()),
            status: "ok",
            input_hash: input_hash.clone(),
            options: options_record(options),
            output_bytes: Some(output_bytes),
            output_hash: Some(output_hash),
            redone: None,
            error_kind: None,
            error: None,
            exit_code: None,
            warnings: read_warnings.iter().chain(&s.warnings).map(|w| w.to_string()).collect(),
            seconds: clock.elapsed().as_secs_f64(),
            stats: Some(s.stats),
        })
    };
    let outcome = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| run(&mut input_hash)));
    let failed = |e: &Error| {
        let mut r = FileReport::failure(input, e, clock.elapsed().as_secs_f64());
        r.input_hash = input_hash.clone();
        r.options = options_record(options);
        r
    };
    match outcome {
        Ok(Ok(report)) => report,
        Ok(Err(e)) => failed(&e),
        Err(_) => failed(&Error::internal("the run panicked (a bug: please report it with the input)")),
    }
}

/// The options that decide the surface, by name, as [`Options::get`] gives them back (what
/// the report records, and `--resume` compares). `max_memory` is left out: it changes when a
/// run is refused, not the surface.
pub fn options_record(options: &Options) -> BTreeMap<String, String> {
    super::OPTIONS
        .iter()
        .filter(|s| s.name != "max_memory")
        .filter_map(|s| options.get(s.name).map(|v| (s.name.to_string(), v)))
        .collect()
}

/// A 64-bit content hash of `bytes` as 16 hex digits: FNV-1a over little-endian 64-bit words
/// and the length. Not cryptographic — it tells a truncated, edited or other file from the one
/// recorded, not a forged one.
pub fn content_hash(bytes: &[u8]) -> String {
    let mut h = Hasher::default();
    h.update(bytes);
    h.finish()
}

#[derive(Clone, Copy)]
struct Hasher {
    state: u64,
    len: u64,
    tail: [u8; 8],
    tail_len: usize,
}

impl Default for Hasher {
    fn default() -> Self {
        Hasher { state: 0xcbf2_9ce4_8422_2325, len: 0, tail: [0; 8], tail_len: 0 }
    }
}

impl Hasher {
    const PRIME: u64 = 0x0000_0100_0000_01b3;

    fn word(&mut self, w: u64) {
        self.state = (self.state ^ w).wrapping_mul(Self::PRIME);
    }

    fn update(&mut self, mut bytes: &[u8]) {
        self.len += bytes.len() as u64;
        while self.tail_len > 0 && !bytes.is_empty() {
            self.tail[self.tail_len] = bytes[0];
            self.tail_len = (self.tail_len + 1) % 8;
            bytes = &bytes[1..];
            if self.tail_len == 0 {
                self.word(u64::from_le_bytes(self.tail));
            }
        }
        let mut words = bytes.chunks_exact(8);
        for w in &mut words {
            self.word(u64::from_le_bytes(w.try_into().unwrap_or_default()));
        }
        for &b in words.remainder() {
            self.tail[self.tail_len] = b;
            self.tail_len += 1;
        }
    }

    fn finish(mut self) -> String {
        if self.tail_len > 0 {
            let mut last = [0u8; 8];
            last[..self.tail_len].copy_from_slice(&self.tail[..self.tail_len]);
            self.word(u64::from_le_bytes(last));
        }
        self.word(self.len);
        format!("{:016x}", self.state)
    }
}

/// The size and [`content_hash`] of the file at `path`, read in pieces.
pub fn file_hash(path: &Path) -> std::io::Result<(u64, String)> {
    use std::io::Read;
    let mut file = std::fs::File::open(path)?;
    let mut h = Hasher::default();
    let mut buf = vec![0u8; 1 << 20];
    loop {
        let n = match file.read(&mut buf) {
            Ok(0) => break,
            Ok(n) => n,
            Err(e) if e.kind() == std::io::ErrorKind::Interrupted => continue,
            Err(e) => return Err(e),
        };
        h.update(&buf[..n]);
    }
    Ok((h.len, h.finish()))
}

/// A line of an earlier report, as `--resume` reads it.
#[derive(Debug, Deserialize)]
struct EarlierLine {
    input: String,
    output: Option<String>,
    status: String,
    input_hash: Option<String>,
    #[serde(default)]
    options: BTreeMap<String, String>,
    output_bytes: Option<u64>,
    output_hash: Option<String>,
}

/// What `--resume` makes of an earlier report: the lines of the meshes kept (as they were
/// written), and why the others asked for again are redone, by input.
#[derive(Debug, Default)]
pub struct Resumed {
    /// The earlier report's lines of the meshes kept, in its order.
    pub kept: Vec<String>,
    /// The inputs whose meshes are kept.
    pub done: HashSet<PathBuf>,
    /// Why an earlier mesh of an input was not kept.
    pub redone: HashMap<PathBuf, String>,
}

/// Reads the earlier `report` (the text of `report.jsonl`) for the `jobs` asked for now with
/// `options`: an earlier mesh is kept only when its line says ok, it is the output planned for
/// the same input, the mesh file is whole and unchanged (its size and hash as recorded), the
/// input is unchanged (its hash) and the options are the same. Otherwise the input is redone
/// and [`Resumed::redone`] says why. Lines that are not JSON (a torn line) are skipped.
pub fn resume(report: &str, jobs: &[FileJob], options: &Options) -> Resumed {
    let wanted: HashMap<&Path, &Path> = jobs.iter().map(|j| (j.input.as_path(), j.output.as_path())).collect();
    let now = options_record(options);
    let mut r = Resumed::default();
    for line in report.lines() {
        let Ok(e) = serde_json::from_str::<EarlierLine>(line) else { continue };
        let input = PathBuf::from(&e.input);
        let Some(&output) = wanted.get(input.as_path()) else { continue };
        if e.status != "ok" || r.done.contains(&input) {
            continue;
        }
        let why = match why_redo(&e, &input, output, &now) {
            None => {
                r.redone.remove(&input);
                r.done.insert(input);
                r.kept.push(line.to_string());
                continue;
            }
            Some(why) => why,
        };
        r.redone.insert(input, why);
    }
    r
}

/// Why the earlier mesh of line `e` cannot be kept for `input` → `output` with the options
/// `now`, or `None` when it can.
fn why_redo(e: &EarlierLine, input: &Path, output: &Path, now: &BTreeMap<String, String>) -> Option<String> {
    if e.output.as_deref().map(Path::new) != Some(output) {
        return Some(format!("the earlier mesh was written to {} instead", e.output.as_deref().unwrap_or("nowhere")));
    }
    let (Some(bytes), Some(hash), Some(input_hash)) = (e.output_bytes, &e.output_hash, &e.input_hash) else {
        return Some("the earlier report records no sizes and hashes (an older curvenet)".into());
    };
    match file_hash(output) {
        Err(_) => return Some("the mesh is missing".into()),
        Ok((b, _)) if b != bytes => {
            return Some(format!(
                "the mesh is not the one written: {b} bytes instead of {bytes} (truncated or changed)"
            ))
        }
        Ok((_, h)) if &h != hash => return Some("the mesh is not the one written: its content changed".into()),
        Ok(_) => {}
    }
    let read = crate::io::open_regular(input)
        .and_then(|f| crate::io::read_opened(f, input, crate::io::InputKind::Text, crate::io::MAX_INPUT_BYTES));
    match read {
        Err(_) => return Some("the input cannot be read now".into()),
        Ok(b) if &content_hash(&b) != input_hash => return Some("the input changed since".into()),
        Ok(_) => {}
    }
    if &e.options != now {
        let keys: std::collections::BTreeSet<&String> = e.options.keys().chain(now.keys()).collect();
        let differ: Vec<String> = keys
            .into_iter()
            .filter(|k| e.options.get(*k) != now.get(*k))
            .map(|k| {
                let show = |v: Option<&String>| v.map_or("unset".to_string(), |v| v.clone());
                format!("{k} {} (now {})", show(e.options.get(k)), show(now.get(k)))
            })
            .collect();
        return Some(format!("made with other options: {}", differ.join(", ")));
    }
    None
}

/// The input files: each argument a file, a folder (its network files, sorted) or a glob
/// pattern; a path that is none of these is kept, to be reported as missing. Duplicates (the
/// same file twice) once. A folder without networks, or a pattern matching no file, is a usage
/// error (a typo, not an empty batch).
pub fn expand_inputs(args: &[String]) -> Result<Vec<PathBuf>> {
    let mut out: Vec<PathBuf> = Vec::new();
    let is_network = |p: &Path| {
        p.is_file()
            && p.extension()
                .and_then(|e| e.to_str())
                .is_some_and(|e| NETWORK_EXTENSIONS.contains(&e.to_ascii_lowercase().as_str()))
    };
    for arg in args {
        let path = Path::new(arg);
        if path.is_dir() {
            let mut files: Vec<PathBuf> = std::fs::read_dir(path)
                .map_err(|e| Error::io(path, e))?
                .filter_map(|e| e.ok().map(|e| e.path()))
                .filter(|p| is_network(p))
                .collect();
            if files.is_empty() {
                return Err(Error::usage(format!("{arg}: the folder holds no .json, .obj or .net file")));
            }
            files.sort();
            out.extend(files);
        } else if path.exists() || !arg.contains(['*', '?', '[']) {
            out.push(path.to_path_buf());
        } else {
            let paths = glob::glob(arg).map_err(|e| Error::usage(format!("pattern {arg:?}: {e}")))?;
            let mut files: Vec<PathBuf> = paths.filter_map(|p| p.ok()).filter(|p| p.is_file()).collect();
            if files.is_empty() {
                return Err(Error::usage(format!("{arg}: the pattern matches no file")));
            }
            files.sort();
            out.extend(files);
        }
    }
    let mut seen = HashSet::new();
    out.retain(|p| seen.insert(std::fs::canonicalize(p).unwrap_or_else(|_| p.clone())));
    Ok(out)
}

/// One job per input: the input and its mesh `DIR/STEM.FORMAT`; a stem met again gets `-2`,
/// `-3`, … (in input order).
pub fn plan_outputs(inputs: &[PathBuf], dir: &Path, format: &str) -> Vec<FileJob> {
    let mut used: HashSet<String> = HashSet::new();
    inputs
        .iter()
        .map(|input| {
            let stem = input.file_stem().map_or("network".into(), |s| s.to_string_lossy().into_owned());
            let mut name = stem.clone();
            let mut k = 1;
            while !used.insert(name.clone()) {
                k += 1;
                name = format!("{stem}-{k}");
            }
            FileJob { input: input.clone(), output: dir.join(format!("{name}.{format}")) }
        })
        .collect()
}
