//! One network file to one mesh file, with a report of the run instead of an early return:
//! the unit of `curvenet batch` and of Python's `curvenet.surface_files` (local processes or a
//! Dask cluster), so that both report the same fields.

use super::{surface, Options, Stats};
use crate::error::{Error, Result};
use serde::Serialize;
use std::collections::HashSet;
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
    /// `"ok"` or `"error"`.
    pub status: &'static str,
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
            error_kind: Some(e.kind()),
            error: Some(e.to_string()),
            exit_code: Some(e.exit_code()),
            warnings: Vec::new(),
            seconds,
            stats: None,
        }
    }
}

/// Reads the network `input`, surfaces it with `options` (a JSON network keeps its `cauchy`
/// attributes for that method, as `curvenet surface` reads them) and writes the mesh to
/// `output` (atomically; the format from its extension). Never fails: an error — a panic too,
/// reported as an internal error — is the report's.
pub fn surface_file(input: &Path, output: &Path, options: &Options) -> FileReport {
    let clock = Instant::now();
    let run = || -> Result<FileReport> {
        crate::io::check_mesh_path(output)?;
        let network = crate::io::read_network(input)?;
        let mut opts = options.clone();
        if opts.method == crate::Method::Cauchy && opts.cauchy.attributes.is_none() {
            opts.cauchy.attributes =
                crate::methods::andrews2011::NetworkAttributes::read(input)?.map(std::sync::Arc::new);
        }
        let s = surface(&network, &opts)?;
        crate::io::write_mesh(output, s.mesh_data())?;
        Ok(FileReport {
            input: input.display().to_string(),
            output: Some(output.display().to_string()),
            status: "ok",
            error_kind: None,
            error: None,
            exit_code: None,
            warnings: s.warnings.iter().map(|w| w.to_string()).collect(),
            seconds: clock.elapsed().as_secs_f64(),
            stats: Some(s.stats),
        })
    };
    match std::panic::catch_unwind(std::panic::AssertUnwindSafe(run)) {
        Ok(Ok(report)) => report,
        Ok(Err(e)) => FileReport::failure(input, &e, clock.elapsed().as_secs_f64()),
        Err(_) => FileReport::failure(
            input,
            &Error::internal("the run panicked (a bug: please report it with the input)"),
            clock.elapsed().as_secs_f64(),
        ),
    }
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
