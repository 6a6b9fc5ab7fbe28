//! `cargo bench -p curvenet`: file-to-file runs of the bundled networks (read JSON, surface,
//! write PLY), repeated; prints the median per stage, the median total and its ratio to the
//! factorisation alone. No external harness: the figures are printed as a table.
//!
//! Options (after `--`): `--runs K` (default 11), `--vertices N` (default 20000), network
//! names (default `sphere torus`).

use curvenet::network::examples;
use curvenet::{io, Options, Timings};
use std::time::Instant;

use curvenet::metrics::median;

fn main() {
    let args: Vec<String> = std::env::args().skip(1).filter(|a| a != "--bench").collect();
    let mut runs = 11;
    let mut vertices = 20_000;
    let mut names = Vec::new();
    let mut i = 0;
    while i < args.len() {
        match args[i].as_str() {
            "--runs" => {
                runs = args[i + 1].parse().expect("--runs K");
                i += 1;
            }
            "--vertices" => {
                vertices = args[i + 1].parse().expect("--vertices N");
                i += 1;
            }
            other => names.push(other.to_string()),
        }
        i += 1;
    }
    if names.is_empty() {
        names = vec!["sphere".into(), "torus".into()];
    }
    let dir = std::env::temp_dir().join(format!("curvenet-bench-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    println!("file-to-file runs (read JSON → surface → write PLY), median of {runs}, release build");
    println!(
        "{:<10} {:>8} {:>8} {:>8} {:>8} {:>8} {:>8} {:>8} {:>8} {:>8} {:>9} {:>7}",
        "network",
        "vertices",
        "read",
        "nodes",
        "resample",
        "tessel.",
        "operat.",
        "factor",
        "solve",
        "write",
        "total [s]",
        "÷factor"
    );
    for name in &names {
        let net = examples::example(name).expect("unknown example");
        let input = dir.join(format!("{name}.json"));
        let output = dir.join(format!("{name}.ply"));
        io::write_network(&input, &net).expect("write network");
        let opts = Options::default().with_vertices(vertices);
        let mut all: Vec<Timings> = Vec::new();
        let mut nv = 0;
        for _ in 0..runs {
            let start = Instant::now();
            let t0 = Instant::now();
            let net = io::read_network(&input).expect("read");
            let read = t0.elapsed().as_secs_f64();
            let s = curvenet::surface(&net, &opts).expect("surface");
            let t0 = Instant::now();
            io::write_mesh(&output, s.mesh_data()).expect("write");
            let mut t = s.stats.timings;
            t.read = read;
            t.write = t0.elapsed().as_secs_f64();
            t.total = start.elapsed().as_secs_f64();
            nv = s.stats.vertices;
            all.push(t);
        }
        let m = |f: fn(&Timings) -> f64| median(all.iter().map(f).collect());
        let (total, factor) = (m(|t| t.total), m(|t| t.factor));
        println!(
            "{:<10} {:>8} {:>8.4} {:>8.4} {:>8.4} {:>8.4} {:>8.4} {:>8.4} {:>8.4} {:>8.4} {:>9.4} {:>7.2}",
            name,
            nv,
            m(|t| t.read),
            m(|t| t.nodes),
            m(|t| t.resample),
            m(|t| t.tessellate),
            m(|t| t.operators),
            factor,
            m(|t| t.solve),
            m(|t| t.write),
            total,
            total / factor
        );
    }
    let _ = std::fs::remove_dir_all(&dir);
}
