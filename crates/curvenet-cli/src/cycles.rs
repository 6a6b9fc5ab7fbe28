//! `curvenet cycles`: the network a surface run uses (consolidated, normals inferred) with the
//! cycles of its patches, one line per patch, to edit — delete a line to leave that patch open
//! — and surface (docs/design.md §15).

use crate::options::{options, SolveArgs};
use clap::Args;
use curvenet::io::{write_network, NetworkFormat};
use curvenet::Error;
use std::io::Write;
use std::path::PathBuf;

#[derive(Args)]
pub struct CyclesArgs {
    /// Input curve network or sketch (.json, .obj, .net).
    input: PathBuf,
    /// Output network with its normals and a "cycles" list (.json only: the other formats have
    /// no place for cycles). Written only if the stages succeed.
    #[arg(short, long)]
    output: PathBuf,
    /// Consolidation of raw strokes, as `surface --consolidate` (`off`: the strokes as drawn).
    #[arg(long, value_name = "on|off")]
    consolidate: Option<String>,
    /// Consolidation tolerance, as `surface --gap`.
    #[arg(long, value_name = "D")]
    gap: Option<String>,
    /// Snapping tolerance, as `surface --snap`.
    #[arg(long, value_name = "S")]
    snap: Option<String>,
    /// The global `-q` (`Cli::quiet`): print nothing but results, errors and warnings.
    #[arg(skip)]
    pub(crate) quiet: bool,
}

pub fn run(a: &CyclesArgs) -> Result<(), Error> {
    if NetworkFormat::from_path(&a.output)? != NetworkFormat::Json {
        return Err(Error::usage(format!(
            "{}: cycles are written in JSON only (the other formats have no place for them); name the output .json",
            a.output.display()
        )));
    }
    crate::surface::distinct_paths(&a.input, &[Some(&a.output)])?;
    let network = crate::read_network(&a.input)?;
    let mut given: Vec<(&'static str, String)> = Vec::new();
    for (key, value) in [("consolidate", &a.consolidate), ("gap", &a.gap), ("snap", &a.snap)] {
        if let Some(v) = value {
            given.push((key, v.clone()));
        }
    }
    let opts = options(&SolveArgs { given, ..Default::default() })?;
    let (out, warnings) = curvenet::network_with_cycles(&network, &opts)?;
    for w in &warnings {
        eprintln!("warning: {w}");
    }
    write_network(&a.output, &out)?;
    if !a.quiet {
        let cycles = out.cycles.as_ref().map_or(0, Vec::len);
        out!(
            "{}: {} curves, {cycles} cycles (one line each, in patch order: delete a line to leave that patch open), \
             then `curvenet surface {} -o OUT`",
            a.output.display(),
            out.curves.len(),
            a.output.display()
        );
    }
    Ok(())
}
