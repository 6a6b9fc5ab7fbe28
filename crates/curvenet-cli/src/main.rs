//! The `curvenet` command: argument parsing, progress and file handling around the library.
//! No numerics live here; each subcommand has its module.

/// `println!` that ignores a closed stdout (`curvenet … | head`) instead of panicking.
macro_rules! out {
    ($($arg:tt)*) => {{
        let _ = writeln!(std::io::stdout(), $($arg)*);
    }};
}

mod batch;
mod bench;
mod consolidate;
mod cycles;
mod demo;
mod eval;
mod example;
mod figures;
mod fit;
mod inflate;
mod normals;
mod options;
mod render;
mod sample;
mod study;
mod surface;

use clap::{Parser, Subcommand};
use std::io::IsTerminal;

use std::process::ExitCode;

// Large buffers (factors, right-hand sides) are allocated and freed many times a run; mimalloc
// keeps them out of repeated mmap/munmap and first-touch page faults (measured in
// the README, "Speed": it pays at 10k and 100k --fast, is neutral at 100k default;
// `--no-default-features` builds with the system's).
#[cfg(feature = "mimalloc")]
#[global_allocator]
static GLOBAL: mimalloc::MiMalloc = mimalloc::MiMalloc;

const BATCH_HELP: &str = "\
Each input's mesh is DIR/STEM.FORMAT (a stem met twice gets -2, -3, …), written atomically.
DIR/report.jsonl gets one JSON line per input as it ends: input, output, status (ok or error),
error_kind, error and exit_code of a failure, warnings, seconds, and the --stats figures (stats).
Exit 0 when every network succeeded, 1 when any failed (listed at the end).
Example: curvenet batch captures/ \"more/*.net\" --out meshes --jobs 2 --fast";

const AFTER_HELP: &str = "\
Exit codes: 0 success, 1 bad input (malformed file, invalid network, non-manifold curves, I/O),
2 usage error, 3 numerical failure, 4 internal error (a bug: please report it with the input).

Network formats (by extension): .json (reference), .obj (v/vn/l, group \"boundary\"), .net.
Normals may be left out (JSON: no \"normals\" key; OBJ: no vn, also an edge soup of l lines):
they are then inferred from the curves' shape (see `curvenet normals`).
Mesh formats (by extension): .ply (binary, with normals, mean curvature, curve flag), .obj, .off;
.glb (binary glTF 2.0, for three.js and Blender) is written, not read.
See README.md for the formats and the method.";

#[derive(Parser)]
#[command(
    name = "curvenet",
    version,
    about = "Surface a network of 3D curves (with or without normals) into a smooth triangle mesh",
    long_about = "Turns a network of 3D curves sampled with surface normals (or without: they are then inferred) \
                  into a smooth triangle mesh \
                  (Stanko et al., \"Surfacing curve networks with normal control\", Computers & Graphics 2016).",
    after_help = AFTER_HELP
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
    /// Quiet: no progress, stage lines, notes or summaries; results (e.g. `eval`'s table, a
    /// batch's totals), warnings and errors still print.
    #[arg(short, long, global = true)]
    quiet: bool,
}

#[derive(Subcommand)]
enum Command {
    /// Surface a curve network: read IN, write the mesh to OUT.
    #[command(after_help = AFTER_HELP)]
    Surface(surface::SurfaceArgs),
    /// Surface many networks: files, folders and patterns, several at a time, with a JSON-lines
    /// report; one failure never stops the batch.
    #[command(after_help = BATCH_HELP)]
    Batch(batch::BatchArgs),
    /// Write a bundled analytic network (sphere, torus, cylinder, …) to a file.
    #[command(
        after_help = "Use --list to see the names. The format follows the extension of -o: .json, .obj or .net."
    )]
    Example(example::ExampleArgs),
    /// Infer the normals of curves that come without (3D sketches, CAD edges, polylines) and
    /// write the network with them.
    Normals(normals::NormalsArgs),
    /// Consolidate the raw strokes of a sketch (gaps closed, overdraw merged, hooks and stubs
    /// trimmed: the first stage of `surface`) and write the network, to look at or edit.
    Consolidate(consolidate::ConsolidateArgs),
    /// Write the network a surface run uses (consolidated, normals inferred) with the cycles of
    /// its patches, one line per patch: delete a line to leave that patch open, then surface it.
    Cycles(cycles::CyclesArgs),
    /// Surface the bundled sphere network and report where the result went and how accurate it is.
    Demo(demo::DemoArgs),
    /// Measure a mesh against a ground truth: distances, normal angles, N* deviation ([CG] §4.3).
    #[command(after_help = eval::EVAL_HELP)]
    Eval(eval::EvalArgs),
    /// Build a curve network on a triangle mesh: plane sections with normals from the mesh.
    Sample(sample::SampleArgs),
    /// Run the paper's experiments: convergence under refinement, the accuracy report.
    Study(study::StudyArgs),
    /// Time file-to-file runs of the bundled networks at several sizes (docs/performance.md).
    Bench(bench::BenchArgs),
    /// Render a mesh or a surfaced network to PNG: shading, curvature, isophotes, N* deviation.
    #[command(after_help = render::RENDER_HELP)]
    Render(render::RenderArgs),
    /// Inflate an SVG sketch into a surface (Andrews et al. 2011, §5; docs/cauchy.md).
    Inflate(inflate::InflateArgs),
    /// Reverse engineer a mesh into Cauchy constraints (Andrews et al. 2011, §6; docs/cauchy.md).
    Fit(fit::FitArgs),
    /// Solve a model written by `fit` again.
    Resurface(fit::ResurfaceArgs),
}

/// On SIGINT, SIGTERM or SIGHUP: remove the outputs staged and not yet committed (their
/// temporary files beside the targets, [`curvenet::io::remove_staged_files`]) and exit with
/// 128 + the signal's number, as the shell reports a killed process. The signals are taken
/// by a thread of their own (signal-hook), so the cleanup runs outside the signal context.
/// SIGXFSZ (a file-size limit, `ulimit -f`, reached while writing) is caught and ignored: the
/// write then fails with an I/O error ("File too large") that the run reports, and the staged
/// file is removed, instead of the process being killed with nothing said.
#[cfg(unix)]
fn clean_up_on_signals() {
    use signal_hook::consts::{SIGHUP, SIGINT, SIGTERM, SIGXFSZ};
    let _ = signal_hook::flag::register(SIGXFSZ, std::sync::Arc::new(std::sync::atomic::AtomicBool::new(false)));
    let Ok(mut signals) = signal_hook::iterator::Signals::new([SIGINT, SIGTERM, SIGHUP]) else {
        return;
    };
    std::thread::spawn(move || {
        if let Some(sig) = signals.forever().next() {
            curvenet::io::remove_staged_files();
            std::process::exit(128 + sig);
        }
    });
}

#[cfg(not(unix))]
fn clean_up_on_signals() {}

/// Reads the network at `path`, printing the warnings of the read (unknown JSON keys).
fn read_network(path: &std::path::Path) -> Result<curvenet::Network, curvenet::Error> {
    let (network, warnings) = curvenet::io::read_network_with_warnings(path)?;
    for w in &warnings {
        eprintln!("warning: {w}");
    }
    Ok(network)
}

fn main() -> ExitCode {
    clean_up_on_signals();
    // Under `ulimit -v`, as many threads as the matrix products' workspaces leave room for.
    curvenet::solve::memory::fit_thread_pool_to_address_space();
    let cli = Cli::parse();
    // The global `-q` handed to the subcommands that print progress or a summary.
    macro_rules! quietly {
        ($a:ident, $run:path) => {{
            let mut a = $a;
            a.quiet = cli.quiet;
            $run(&a)
        }};
    }
    let result = match cli.command {
        Command::Surface(a) => quietly!(a, surface::run),
        Command::Batch(a) => quietly!(a, batch::run),
        Command::Example(a) => quietly!(a, example::run),
        Command::Demo(a) => quietly!(a, demo::run),
        Command::Normals(a) => quietly!(a, normals::run),
        Command::Consolidate(a) => quietly!(a, consolidate::run),
        Command::Cycles(a) => quietly!(a, cycles::run),
        Command::Eval(a) => eval::run(&a),
        Command::Sample(a) => quietly!(a, sample::run),
        Command::Study(a) => study::run(&a),
        Command::Bench(a) => bench::run(&a),
        Command::Render(a) => quietly!(a, render::run),
        Command::Inflate(a) => quietly!(a, inflate::run),
        Command::Fit(a) => quietly!(a, fit::run),
        Command::Resurface(a) => quietly!(a, fit::run_resurface),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {}", e.spelled(&flag_spelling()));
            ExitCode::from(e.exit_code() as u8)
        }
    }
}

/// The library names options neutrally in its messages (`` `spacing` ``): on the command line
/// they are the long flags of the same name (`--spacing`). Only names that are flags of some
/// subcommand are respelled.
fn flag_spelling() -> impl Fn(&str) -> Option<String> {
    use clap::CommandFactory;
    let cmd = Cli::command();
    let mut flags: Vec<String> = cmd
        .get_subcommands()
        .flat_map(|s| s.get_arguments().filter_map(|a| a.get_long().map(str::to_string)).collect::<Vec<_>>())
        .collect();
    flags.sort();
    flags.dedup();
    move |name: &str| {
        let long = name.replace('_', "-");
        flags.binary_search(&long).is_ok().then(|| format!("--{long}"))
    }
}

/// Progress of one surfacing run on a terminal: a line per finished stage, and below them a bar
/// with the percentage done, the elapsed time and the stage that runs (the factorisation gives
/// no intermediate figure: the bar's clock keeps going while it runs). The percentage weighs
/// the stages by their measured share of a default run (docs/performance.md: the solve and the
/// iterations take 85–95 %). Nothing off a terminal or with `--quiet`.
pub(crate) struct Progress {
    bar: Option<indicatif::ProgressBar>,
    /// The 3D iterations the run will do at most (their share of the bar).
    iterations: std::cell::Cell<usize>,
    /// Whether the run solves a coarse level first (the default; it reports "coarse start").
    coarse: std::cell::Cell<bool>,
    /// Warnings the library said before the run's end (stage "warning": printed at once, on
    /// a terminal or not, even with `--quiet`), so that the run's list does not repeat them.
    said: std::cell::RefCell<Vec<String>>,
}

/// Bar units (per mille) of the stages before the solve.
const PREPARE_PER_MILLE: u64 = 100;
/// Bar units of the stages before the fine solve when a coarse level is solved and iterated
/// first: about a third of a default run (1M sphere: 9 s of 27 s, docs/performance.md).
const PREPARE_COARSE_PER_MILLE: u64 = 350;

impl Progress {
    pub(crate) fn new(quiet: bool) -> Self {
        let bar = (!quiet && std::io::stderr().is_terminal()).then(|| {
            let bar = indicatif::ProgressBar::new(1000);
            if let Ok(style) = indicatif::ProgressStyle::with_template("  {bar:30} {percent:>3}%  {elapsed:>4}  {msg}")
            {
                bar.set_style(style);
            }
            bar.set_message("reading");
            bar.enable_steady_tick(std::time::Duration::from_millis(200));
            bar
        });
        Progress {
            bar,
            iterations: std::cell::Cell::new(0),
            coarse: std::cell::Cell::new(false),
            said: Default::default(),
        }
    }

    /// Whether the warning `message` was printed during the run ([`Progress::stage`]).
    pub(crate) fn already_said(&self, message: &str) -> bool {
        self.said.borrow().iter().any(|m| m == message)
    }

    /// Sets how many 3D iterations follow the first solve (0 for a single pass).
    pub(crate) fn expect_iterations(&self, n: usize) {
        self.iterations.set(n);
    }

    pub(crate) fn stage(&self, name: &str, seconds: f64, detail: &str) {
        if name == "warning" {
            if self.already_said(detail) {
                return;
            }
            let line = format!("warning: {detail}");
            match &self.bar {
                Some(bar) => bar.println(line),
                None => eprintln!("{line}"),
            }
            self.said.borrow_mut().push(detail.to_string());
            return;
        }
        let Some(bar) = &self.bar else { return };
        bar.println(format!("  {name:<16}{seconds:>8.3} s   {detail}"));
        let its = self.iterations.get() as u64;
        if name == "coarse start" {
            self.coarse.set(true);
        }
        let prepare = if self.coarse.get() { PREPARE_COARSE_PER_MILLE } else { PREPARE_PER_MILLE };
        // "k of at most n, …" (iterations of the coarse or the fine level).
        let words: Vec<&str> = detail.split([' ', ',']).collect();
        let k = words.first().and_then(|k| k.parse::<u64>().ok()).unwrap_or(1);
        let of = words.get(4).and_then(|n| n.parse::<u64>().ok()).unwrap_or(its).max(1);
        // The solve's share: one part for the first solve, one per iteration.
        let solve_share = (1000 - prepare) / (1 + its);
        let (position, next) = match name {
            "read" => (20, "finding the nodes"),
            "normals" => (30, "finding the nodes"),
            "nodes" => (40, "finding the patches"),
            "cycles" => (50, "resampling the curves"),
            "resample" => (60, "tessellating the patches"),
            // The coarse level: its planar start, then its 3D iterations.
            "coarse start" => (100, "coarse level: 3D iteration 1"),
            "coarse iteration" => {
                let next = if k < of { format!("coarse level: 3D iteration {}", k + 1) } else { "flattening".into() };
                bar.set_position((100 + (PREPARE_COARSE_PER_MILLE - 150) * k / of).max(bar.position()));
                bar.set_message(next);
                return;
            }
            "coarse level" => (PREPARE_COARSE_PER_MILLE - 50, "tessellating the patches"),
            "tessellate" => (prepare, "solving (factorising)"),
            "first solve" => (prepare + solve_share, "3D iteration 1"),
            "iteration" => {
                // After the coarse level the fine one runs fewer iterations than `its`.
                let solve_share = (1000 - prepare) / (1 + of);
                bar.set_position((prepare + solve_share * (1 + k)).min(999).max(bar.position()));
                bar.set_message(if k < of { format!("3D iteration {}", k + 1) } else { "finishing".into() });
                return;
            }
            "solve" => (1000, "writing"),
            _ => (bar.position(), ""),
        };
        bar.set_position(position.max(bar.position()));
        if !next.is_empty() {
            bar.set_message(next);
        }
        if name == "write" {
            bar.finish_and_clear();
        }
    }
}

impl Drop for Progress {
    fn drop(&mut self) {
        if let Some(bar) = &self.bar {
            bar.finish_and_clear();
        }
    }
}

/// Peak resident memory of this process (Linux: `VmHWM` of /proc/self/status).
pub(crate) fn peak_memory_bytes() -> Option<u64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with("VmHWM:"))?;
    let kb: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kb * 1024)
}
