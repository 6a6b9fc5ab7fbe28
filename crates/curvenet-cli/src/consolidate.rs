//! `curvenet consolidate`: the raw strokes of a sketch joined, merged and trimmed into a
//! network whose curves meet (the stage `surface` runs first), written to look at or edit.

use crate::options::{options, SolveArgs};
use clap::Args;
use curvenet::io::write_network;
use curvenet::Error;
use std::io::Write;
use std::path::PathBuf;

#[derive(Args)]
pub struct ConsolidateArgs {
    /// Input curve network or sketch (.json, .obj edge soup or polylines, .net).
    input: PathBuf,
    /// Output network (.json, .obj, .net). Written only if the stage succeeds.
    #[arg(short, long)]
    output: PathBuf,
    /// Consolidation tolerance: stroke ends within D of another stroke are joined to it,
    /// strokes within D/2 of each other merged [default: from the sketch, 0.5–2 % of its
    /// bounding-box diagonal].
    #[arg(long, value_name = "D")]
    gap: Option<String>,
    /// Snapping tolerance: ends closer than S to another stroke already meet it [default: the
    /// network's own, else the larger of 1e-3 × its bounding-box diagonal and 0.1 × the mean
    /// sample spacing].
    #[arg(long, value_name = "S")]
    snap: Option<String>,
    /// Also infer the normals of the consolidated curves that have none (as `curvenet normals`).
    #[arg(long)]
    normals: bool,
    /// The global `-q` (`Cli::quiet`): print nothing but results, errors and warnings.
    #[arg(skip)]
    pub(crate) quiet: bool,
}

pub fn run(a: &ConsolidateArgs) -> Result<(), Error> {
    curvenet::io::NetworkFormat::from_path(&a.output)?;
    crate::surface::distinct_paths(&a.input, &[Some(&a.output)])?;
    let network = crate::read_network(&a.input)?;
    let mut given: Vec<(&'static str, String)> = Vec::new();
    if let Some(g) = &a.gap {
        given.push(("gap", g.clone()));
    }
    if let Some(s) = &a.snap {
        given.push(("snap", s.clone()));
    }
    let opts = options(&SolveArgs { given, ..Default::default() })?;
    let c = curvenet::topology::consolidate::consolidate(&network, &opts.consolidate, opts.mesh.snap)?;
    for w in &c.warnings {
        eprintln!("warning: {w}");
    }
    let mut out = c.network.clone();
    let mut inferred = 0;
    if a.normals {
        let mut o = opts.clone();
        o.consolidate.enabled = false;
        let i = curvenet::infer_normals(&out, &o)?;
        for w in &i.warnings {
            eprintln!("warning: {w}");
        }
        inferred = i.report.curves;
        out = i.network;
    }
    write_network(&a.output, &out)?;
    if !a.quiet {
        let r = &c.report;
        let normals = if a.normals { format!(", normals inferred for {inferred}") } else { String::new() };
        out!(
            "{}: {} strokes in, {} curves out (gap {:.3e}): {} ends joined, {} crossings met, {} overdrawn \
             stretches merged, {} hooks and stubs trimmed{normals} in {:.3} s",
            a.output.display(),
            r.curves_in,
            out.curves.len(),
            r.gap,
            r.joined,
            r.crossed,
            r.merged,
            r.trimmed,
            r.seconds
        );
    }
    Ok(())
}
