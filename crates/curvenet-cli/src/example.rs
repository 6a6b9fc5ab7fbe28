//! `curvenet example`: write a bundled analytic network, optionally with sensor noise.

use clap::Args;
use curvenet::io::write_network;
use curvenet::network::examples;
use curvenet::Error;
use std::io::Write;
use std::path::PathBuf;

#[derive(Args)]
pub struct ExampleArgs {
    /// Name of the example; without one, the names are listed.
    name: Option<String>,
    /// Output network file (.json, .obj, .net).
    #[arg(short, long)]
    output: Option<PathBuf>,
    /// List the bundled examples.
    #[arg(long)]
    list: bool,
    /// Add sensor-like noise: Gaussian, σ = F × the sample spacing on positions, σ = F on the
    /// unit normals ([CG] §4.5).
    #[arg(long, value_name = "F")]
    noise: Option<f64>,
    /// Seed of the noise.
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// Leave the normals out (test data for the inference; .json and .obj only).
    #[arg(long)]
    no_normals: bool,
    /// The global `-q` (`Cli::quiet`): print nothing but results, errors and warnings.
    #[arg(skip)]
    pub(crate) quiet: bool,
}

pub fn run(a: &ExampleArgs) -> Result<(), Error> {
    let names = || examples::EXAMPLES.iter().map(|e| e.0).collect::<Vec<&str>>().join(", ");
    let options_given = a.noise.is_some() || a.no_normals;
    if a.list || (a.name.is_none() && a.output.is_none() && !options_given) {
        for (name, what) in examples::EXAMPLES {
            out!("{name:<12}{what}");
        }
        if !a.list && !a.quiet {
            eprintln!(
                "Write one with `curvenet example NAME -o FILE.json`, e.g. `curvenet example torus -o torus.json`."
            );
        }
        return Ok(());
    }
    let Some(name) = &a.name else {
        return Err(Error::usage(format!("give an example name before -o: one of {}", names())));
    };
    let Some(out) = &a.output else {
        return Err(Error::usage(format!("give the output file: `curvenet example {name} -o {name}.json`")));
    };
    let net = examples::example(name)
        .ok_or_else(|| Error::usage(format!("unknown example \"{name}\"; the examples are: {}", names())))?;
    let net = match a.noise {
        Some(f) if f.is_finite() && f >= 0.0 => net.perturbed(f, a.seed),
        Some(f) => return Err(Error::usage(format!("--noise {f} is not a non-negative number"))),
        None => net,
    };
    let net = if a.no_normals { net.without_normals() } else { net };
    write_network(out, &net)?;
    let mut noise = a.noise.map(|f| format!(", noise {f} (seed {})", a.seed)).unwrap_or_default();
    if a.no_normals {
        noise.push_str(", no normals");
    }
    if a.quiet {
        return Ok(());
    }
    out!("{}: example \"{name}\", {} curves, {} samples{noise}", out.display(), net.curves.len(), net.num_samples());
    Ok(())
}
