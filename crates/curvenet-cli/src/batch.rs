//! `curvenet batch`: surface many networks in one process, several at a time, one failure
//! never stopping the others; a JSON-lines report, a progress bar on a terminal, `--resume`.
//!
//! Each job surfaces one network on a rayon pool of its own (cores / jobs threads: the
//! factorisation's parallelism, sized so that the jobs together fill the cores), with a memory
//! budget of its share of the memory available. The report (`DIR/report.jsonl`) gets a line as
//! each network ends, so an interrupted batch leaves a report `--resume` can continue from.
//!
//! Nothing is lost (docs/design.md §4, "Batches"): no output may be an input (checked before
//! any work, symlinks resolved); one batch writes into a folder at a time
//! (`io::folder::FolderLock`); inputs are read only if they are regular files (a FIFO does not
//! hang the batch); the temporary files of killed runs are removed by the next; `--resume` keeps
//! a mesh only when it is whole and was made from the same input with the same options
//! (`pipeline::files::resume`).

use crate::options::{options, SolveArgs};
use clap::Args;
use curvenet::io::folder;
use curvenet::pipeline::files::{
    expand_inputs, plan_outputs, resume, surface_file, FileJob as Job, FileReport, Resumed,
};
use curvenet::Error;
use serde_json::Value;
use std::io::{IsTerminal, Write};
use std::path::PathBuf;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Mutex;
use std::time::Instant;

#[derive(Args)]
pub struct BatchArgs {
    /// Input networks: files, folders (their .json, .obj and .net files, not recursing) and
    /// glob patterns, quoted so the shell leaves them ("captures/*.json", "data/**/*.net").
    #[arg(required = true, value_name = "INPUTS")]
    inputs: Vec<String>,
    /// Folder of the meshes (one per input, named after it) and of report.jsonl; created if
    /// missing.
    #[arg(long, value_name = "DIR")]
    out: PathBuf,
    /// Networks surfaced at once [default: the number of cores]; each gets cores / jobs
    /// threads and its share of the memory.
    #[arg(short, long, value_name = "N")]
    jobs: Option<usize>,
    /// Format of the meshes.
    #[arg(long, default_value = "ply", value_parser = ["ply", "obj", "off", "glb"])]
    format: String,
    /// Skip the inputs that DIR/report.jsonl lists as ok whose mesh is there, whole and
    /// unchanged, made from the same input (content hash) with the same options; the others are
    /// redone, and their report lines say why.
    #[arg(long)]
    resume: bool,
    #[command(flatten)]
    solve: SolveArgs,
    /// The global `-q` (`Cli::quiet`): print nothing but results, errors and warnings.
    #[arg(skip)]
    pub(crate) quiet: bool,
}

pub fn run(a: &BatchArgs) -> Result<(), Error> {
    let start = Instant::now();
    if a.jobs == Some(0) || a.jobs.is_some_and(|j| j > 1024) {
        return Err(Error::usage("`jobs` must be between 1 and 1024"));
    }
    let base = options(&a.solve)?;
    let inputs = expand_inputs(&a.inputs)?;
    if inputs.is_empty() {
        return Err(Error::usage("no network found in the inputs (files, folders of .json/.obj/.net, patterns)"));
    }
    let report_path = a.out.join("report.jsonl");
    let jobs = plan_outputs(&inputs, &a.out, &a.format);
    // Nothing is written over an input: meshes, the report, the lock (symlinks resolved).
    let mut outputs: Vec<PathBuf> = jobs.iter().map(|j| j.output.clone()).collect();
    outputs.extend([report_path.clone(), a.out.join(folder::LOCK_FILE)]);
    folder::check_outputs_apart(&inputs, &outputs)?;
    std::fs::create_dir_all(&a.out).map_err(|e| Error::io(&a.out, e))?;
    let _lock = folder::FolderLock::acquire(&a.out)?;
    let stale = folder::remove_stale_temporaries(&a.out);
    if !stale.is_empty() && !a.quiet {
        eprintln!("removed {} temporary file(s) that an interrupted run left in {}", stale.len(), a.out.display());
    }
    // Lines kept from an earlier run (--resume): ok, the mesh whole, input and options the same.
    let resumed = if a.resume {
        match std::fs::read_to_string(&report_path) {
            Ok(text) => resume(&text, &jobs, &base),
            Err(_) => Resumed::default(),
        }
    } else {
        Resumed::default()
    };
    let Resumed { kept, done, redone } = resumed;
    if !a.quiet {
        for job in &jobs {
            if let Some(why) = redone.get(&job.input) {
                eprintln!("redoing {}: {why}", job.input.display());
            }
        }
    }
    let todo: Vec<&Job> = jobs.iter().filter(|j| !done.contains(&j.input)).collect();
    let mut report = std::fs::File::create(&report_path).map_err(|e| Error::io(&report_path, e))?;
    let mut head = String::new();
    for line in &kept {
        head.push_str(line);
        head.push('\n');
    }
    report.write_all(head.as_bytes()).map_err(|e| Error::io(&report_path, e))?;
    // Under an address-space limit, no more threads than the matrix products' workspaces fit.
    let cores = match curvenet::solve::memory::address_space_limit() {
        Some(limit) => curvenet::solve::memory::threads_within(limit),
        None => std::thread::available_parallelism().map_or(1, |n| n.get()),
    };
    let workers = a.jobs.unwrap_or(cores).clamp(1, todo.len().max(1));
    let threads = (cores / workers).max(1);
    let mut base = base;
    if base.mesh.max_memory.is_none() {
        base.mesh.max_memory = curvenet::solve::memory::available_memory(None).map(|m| m / workers as f64);
    }
    let progress = Progress::new(todo.len(), kept.len(), a.quiet);
    let next = AtomicUsize::new(0);
    let shared = Mutex::new((report, Vec::<(String, String)>::new()));
    std::thread::scope(|scope| {
        for _ in 0..workers {
            scope.spawn(|| {
                let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build();
                loop {
                    let k = next.fetch_add(1, Ordering::Relaxed);
                    let Some(job) = todo.get(k) else { break };
                    let mut report = match &pool {
                        Ok(pool) => pool.install(|| surface_file(&job.input, &job.output, &base)),
                        Err(e) => {
                            FileReport::failure(&job.input, &Error::internal(format!("no thread pool: {e}")), 0.0)
                        }
                    };
                    report.redone = redone.get(&job.input).cloned();
                    let line = serde_json::to_value(&report).unwrap_or(Value::Null);
                    // One write of the whole line, under the lock of the folder and the mutex.
                    let text = format!("{line}\n");
                    let mut guard = shared.lock().unwrap_or_else(|e| e.into_inner());
                    let (report, failed) = &mut *guard;
                    if let Err(e) = report.write_all(text.as_bytes()) {
                        eprintln!(
                            "warning: {}: the report line of {} was not written: {e}",
                            report_path.display(),
                            job.input.display()
                        );
                    }
                    if line["status"] != "ok" {
                        failed
                            .push((job.input.display().to_string(), line["error"].as_str().unwrap_or("").to_string()));
                    }
                    progress.finished(job, &line);
                }
            });
        }
    });
    progress.clear();
    let (_, failed) = shared.into_inner().unwrap_or_else(|e| e.into_inner());
    let total = jobs.len();
    eprintln!(
        "{total} networks: {} ok{}, {} failed, in {:.1} s ({} job{} × {threads} thread{}); report: {}",
        total - failed.len(),
        if kept.is_empty() { String::new() } else { format!(" ({} from the earlier run)", kept.len()) },
        failed.len(),
        start.elapsed().as_secs_f64(),
        workers,
        if workers == 1 { "" } else { "s" },
        if threads == 1 { "" } else { "s" },
        report_path.display()
    );
    if failed.is_empty() {
        return Ok(());
    }
    for (input, error) in &failed {
        eprintln!("  failed: {input}: {error}");
    }
    Err(Error::input(format!("{} of {total} networks failed (see {})", failed.len(), report_path.display())))
}

/// A progress bar with counts and ETA on a terminal; one line per network otherwise.
struct Progress {
    bar: Option<indicatif::ProgressBar>,
    total: usize,
    count: AtomicUsize,
    quiet: bool,
}

impl Progress {
    fn new(todo: usize, kept: usize, quiet: bool) -> Self {
        let bar = (!quiet && std::io::stderr().is_terminal()).then(|| {
            let bar = indicatif::ProgressBar::new(todo as u64);
            if let Ok(style) =
                indicatif::ProgressStyle::with_template("{bar:40} {pos}/{len} networks, {elapsed} (ETA {eta}) {msg}")
            {
                bar.set_style(style);
            }
            bar
        });
        if kept > 0 && !quiet {
            eprintln!("resuming: {kept} networks done in an earlier run, {todo} to go");
        }
        Progress { bar, total: todo, count: AtomicUsize::new(0), quiet }
    }

    fn finished(&self, job: &Job, line: &Value) {
        let k = self.count.fetch_add(1, Ordering::Relaxed) + 1;
        let ok = line["status"] == "ok";
        let what = if ok {
            format!(
                "ok     {} → {} ({:.2} s)",
                job.input.display(),
                job.output.display(),
                line["seconds"].as_f64().unwrap_or(0.0)
            )
        } else {
            format!("error  {}: {}", job.input.display(), line["error"].as_str().unwrap_or(""))
        };
        match &self.bar {
            Some(bar) => {
                if !ok {
                    bar.println(what);
                }
                bar.inc(1);
            }
            None if !self.quiet => eprintln!("[{k}/{}] {what}", self.total),
            None => {}
        }
    }

    fn clear(&self) {
        if let Some(bar) = &self.bar {
            bar.finish_and_clear();
        }
    }
}
