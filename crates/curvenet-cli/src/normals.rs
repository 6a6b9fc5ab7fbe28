//! `curvenet normals`: infer the normals of the curves that come without them and write the
//! network with them, to look at or edit before surfacing.

use crate::options::{options, SolveArgs};
use clap::Args;
use curvenet::io::write_network;
use curvenet::Error;
use std::io::Write;
use std::path::PathBuf;

#[derive(Args)]
pub struct NormalsArgs {
    /// Input curve network (.json, .obj, .net).
    input: PathBuf,
    /// Output network with a normal at every sample (.json, .obj, .net). Written only if the
    /// inference succeeds.
    #[arg(short, long)]
    output: PathBuf,
    /// Infer every curve's normals, also where they are given (to compare with them).
    #[arg(long)]
    all: bool,
    /// Snapping tolerance: curves closer than S meet at a node [default: the network's own, else
    /// the larger of 1e-3 × its bounding-box diagonal and 0.1 × the mean sample spacing].
    #[arg(long, value_name = "S")]
    snap: Option<String>,
    /// The global `-q` (`Cli::quiet`): print nothing but results, errors and warnings.
    #[arg(skip)]
    pub(crate) quiet: bool,
}

pub fn run(a: &NormalsArgs) -> Result<(), Error> {
    curvenet::io::NetworkFormat::from_path(&a.output)?;
    crate::surface::distinct_paths(&a.input, &[Some(&a.output)])?;
    let network = crate::read_network(&a.input)?;
    let mut given: Vec<(&'static str, String)> = Vec::new();
    if a.all {
        given.push(("infer_normals", "all".into()));
    }
    if let Some(s) = &a.snap {
        given.push(("snap", s.clone()));
    }
    let opts = options(&SolveArgs { given, ..Default::default() })?;
    let inferred = curvenet::infer_normals(&network, &opts)?;
    for w in &inferred.warnings {
        eprintln!("warning: {w}");
    }
    let json = curvenet::io::NetworkFormat::from_path(&a.output)? == curvenet::io::NetworkFormat::Json;
    if inferred.network.cycles.is_some() && !json {
        eprintln!(
            "warning: the cycles chosen for the patches are kept in JSON only: a surface made from {} may find \
             others (write .json to keep them)",
            a.output.display()
        );
    }
    write_network(&a.output, &inferred.network)?;
    if !a.quiet {
        let r = &inferred.report;
        out!(
            "{}: {} curves, normals inferred for {} ({} crossings from their tangents, {} carried along curves, \
             {} turned outward) in {:.3} s",
            a.output.display(),
            inferred.network.curves.len(),
            r.curves,
            r.nodes_from_tangents,
            r.nodes_transported,
            r.turned_outward,
            r.seconds
        );
    }
    Ok(())
}
