//! `curvenet bench`: file-to-file runs of the bundled sphere and torus networks at several
//! sizes, each in its own process (`curvenet surface … --stats`), so that the peak memory is that
//! of one run. Prints per-stage medians, the peak memory and the ratio of the whole run to the
//! factorisation; `--out` writes them as Markdown (docs/performance.md).

use clap::Args;
use curvenet::io::write_network;
use curvenet::network::examples;
use curvenet::Error;
use std::fmt::Write as _;
use std::io::Write;
use std::path::PathBuf;
use std::process::Command;
use std::time::Instant;

#[derive(Args)]
pub struct BenchArgs {
    /// Approximate vertex counts.
    #[arg(long, value_delimiter = ',', default_value = "10000,100000,1000000")]
    sizes: Vec<usize>,
    /// Bundled networks.
    #[arg(long, value_delimiter = ',', default_value = "sphere,torus,globe")]
    networks: Vec<String>,
    /// Modes: `fast` (single pass) and `default`.
    #[arg(long, value_delimiter = ',', default_value = "fast,default")]
    modes: Vec<String>,
    /// Runs per configuration (the median is reported; at most 3 from 500k vertices).
    #[arg(long, default_value_t = 5)]
    runs: usize,
    /// Write the results as Markdown to this file.
    #[arg(long)]
    out: Option<PathBuf>,
    /// With --out: replace only the section between `<!-- NAME -->` and `<!-- /NAME -->` of the
    /// file (appended when missing), keeping the rest.
    #[arg(long, value_name = "NAME", requires = "out")]
    section: Option<String>,
}

const STAGES: [&str; 10] =
    ["read", "normals", "nodes", "resample", "cycles", "tessellate", "operators", "factor", "solve", "write"];

struct Row {
    network: String,
    mode: String,
    vertices: u64,
    curve_vertices: u64,
    stages: Vec<f64>,
    total: f64,
    wall: f64,
    peak: Option<u64>,
    /// Median over the runs of each run's whole time ÷ its factorisation time.
    ratio: f64,
}

use curvenet::metrics::median;

pub fn run(a: &BenchArgs) -> Result<(), Error> {
    let exe = std::env::current_exe().map_err(|e| Error::Io { path: "curvenet".into(), source: e })?;
    let dir = std::env::temp_dir().join(format!("curvenet-bench-{}", std::process::id()));
    std::fs::create_dir_all(&dir).map_err(|e| Error::Io { path: dir.display().to_string(), source: e })?;
    let mut rows = Vec::new();
    for name in &a.networks {
        let net = examples::example(name).ok_or_else(|| Error::usage(format!("unknown example \"{name}\"")))?;
        let input = dir.join(format!("{name}.json"));
        write_network(&input, &net)?;
        // Modes ending in "-nn" surface the network with its normals removed (inferred).
        let bare = dir.join(format!("{name}-nn.json"));
        write_network(&bare, &net.without_normals())?;
        for &size in &a.sizes {
            for mode in &a.modes {
                let runs = if size >= 500_000 { a.runs.clamp(1, 3) } else { a.runs.max(1) };
                let (mut stages, mut totals, mut walls, mut peaks, mut ratios) =
                    (vec![Vec::new(); STAGES.len()], vec![], vec![], vec![], vec![]);
                let mut sizes = (0, 0);
                for _ in 0..runs {
                    let stats = dir.join("stats.json");
                    let mut cmd = Command::new(&exe);
                    let (mode, input) = match mode.strip_suffix("-nn") {
                        Some(m) => (m, &bare),
                        None => (mode.as_str(), &input),
                    };
                    cmd.arg("surface").arg(input).arg("-o").arg(dir.join("out.obj"));
                    cmd.arg("--vertices").arg(size.to_string()).arg("--stats").arg(&stats).arg("-q");
                    match mode {
                        "fast" => {
                            cmd.arg("--fast");
                        }
                        "default" => {}
                        other => {
                            return Err(Error::usage(format!(
                                "unknown mode \"{other}\" (fast, default; -nn: without normals)"
                            )))
                        }
                    }
                    let clock = Instant::now();
                    let out = cmd.output().map_err(|e| Error::Io { path: exe.display().to_string(), source: e })?;
                    let wall = clock.elapsed().as_secs_f64();
                    if !out.status.success() {
                        return Err(Error::numerical(format!(
                            "benchmark run failed ({name}, {size}, {mode}): {}",
                            String::from_utf8_lossy(&out.stderr)
                        )));
                    }
                    let text = std::fs::read_to_string(&stats)
                        .map_err(|e| Error::Io { path: stats.display().to_string(), source: e })?;
                    let s: serde_json::Value = serde_json::from_str(&text).map_err(|e| Error::usage(e.to_string()))?;
                    for (k, st) in STAGES.iter().enumerate() {
                        stages[k].push(s["timings"][st].as_f64().unwrap_or(0.0));
                    }
                    let total = s["timings"]["total"].as_f64().unwrap_or(0.0);
                    totals.push(total);
                    // Each run's own ratio: its whole run and its factorisation share the
                    // machine's state (the figure the issue asks for, "in one run").
                    ratios.push(total / s["timings"]["factor"].as_f64().unwrap_or(0.0).max(1e-12));
                    walls.push(wall);
                    if let Some(p) = s["peak_memory_bytes"].as_u64() {
                        peaks.push(p);
                    }
                    sizes = (s["vertices"].as_u64().unwrap_or(0), s["curve_vertices"].as_u64().unwrap_or(0));
                }
                let row = Row {
                    network: name.clone(),
                    mode: mode.clone(),
                    vertices: sizes.0,
                    curve_vertices: sizes.1,
                    stages: stages.into_iter().map(median).collect(),
                    total: median(totals),
                    wall: median(walls),
                    peak: peaks.iter().max().copied(),
                    ratio: median(ratios),
                };
                let _ = writeln!(
                    std::io::stderr(),
                    "  {name} {mode} {}: total {:.3} s (wall {:.3} s), factor {:.3} s, peak {}",
                    row.vertices,
                    row.total,
                    row.wall,
                    row.stages[7],
                    row.peak.map(|p| format!("{:.0} MB", p as f64 / 1e6)).unwrap_or_else(|| "?".into())
                );
                rows.push(row);
            }
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
    let table = table(&rows);
    out!("{table}");
    if let (Some(path), Some(name)) = (&a.out, &a.section) {
        let old = std::fs::read_to_string(path).unwrap_or_default();
        let (open, close) = (format!("<!-- {name} -->"), format!("<!-- /{name} -->"));
        let body = format!(
            "{open}\n`curvenet bench --sizes {} --networks {} --modes {} --runs {} --section {name}` \
             (mode `-nn`: the same network with its normals removed, inferred by the run; `normals`: that \
             stage's seconds).\n\n{table}{close}",
            join(&a.sizes),
            a.networks.join(","),
            a.modes.join(","),
            a.runs
        );
        let doc = match (old.find(&open), old.find(&close)) {
            (Some(i), Some(j)) if j > i => format!("{}{body}{}", &old[..i], &old[j + close.len()..]),
            _ => format!("{}\n{body}\n", old.trim_end()),
        };
        curvenet::io::write_text(path, &doc)?;
        out!("wrote section {name} of {}", path.display());
    } else if let Some(path) = &a.out {
        let mut doc = String::new();
        let _ = writeln!(doc, "# Performance\n");
        let _ = writeln!(
            doc,
            "Regenerated by `bench/report.sh` (`curvenet bench --out docs/performance.md`, then \
             `bench/peer.py`); this file is their output. Machine: {}. Release build; every run is a \
             separate process reading the network (JSON) and writing the mesh (OBJ); medians of {} runs \
             (3 from 500k vertices); stage times as reported by `--stats`, wall = the whole process as \
             seen from outside (includes process start and exit). `fast` = `--fast` (one factorisation), \
             `default` = conformal patching and 3D iterations (see docs/accuracy.md).\n",
            crate::study::machine(),
            a.runs
        );
        let _ = writeln!(doc, "{table}");
        let _ = writeln!(
            doc,
            "`÷factor` is the whole run over the factorisation time (symbolic and numeric, all \
             factorisations of the run), the median of each run's own ratio. Peak memory is the \
             process's resident high-water mark.\n"
        );
        let _ = writeln!(doc, "<!-- peer -->");
        // Keep the peer section of an earlier report, if any.
        if let Ok(old) = std::fs::read_to_string(path) {
            if let Some(i) = old.find("<!-- peer -->") {
                let rest = &old[i + "<!-- peer -->".len()..];
                doc.push_str(rest.trim_start_matches('\n'));
            }
        }
        curvenet::io::write_text(path, &doc)?;
        out!("wrote {}", path.display());
    }
    Ok(())
}

/// `10000,100000`.
fn join(v: &[usize]) -> String {
    v.iter().map(|x| x.to_string()).collect::<Vec<_>>().join(",")
}

fn table(rows: &[Row]) -> String {
    let mut t = String::new();
    let _ = write!(t, "| network | mode | vertices (curve) |");
    for s in STAGES {
        let _ = write!(t, " {s} |");
    }
    let _ = writeln!(t, " total [s] | wall [s] | ÷factor | peak memory |");
    let _ = writeln!(t, "|{}", "---|".repeat(STAGES.len() + 7));
    for r in rows {
        let _ = write!(t, "| {} | {} | {} ({}) |", r.network, r.mode, r.vertices, r.curve_vertices);
        for v in &r.stages {
            let _ = write!(t, " {v:.4} |");
        }
        let peak = r.peak.map(|p| format!("{:.0} MB", p as f64 / 1e6)).unwrap_or_else(|| "—".into());
        let _ = writeln!(t, " {:.3} | {:.3} | {:.2} | {peak} |", r.total, r.wall, r.ratio);
    }
    t
}
