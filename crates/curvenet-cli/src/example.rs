//! `curvenet example`: write a bundled analytic network, optionally with sensor noise.

use clap::Args;
use curvenet::io::write_network;
use curvenet::network::examples;
use curvenet::Error;
use std::io::Write;
use std::path::PathBuf;

#[derive(Args)]
pub struct ExampleArgs {
    /// Name of the example (see --list).
    #[arg(required_unless_present = "list")]
    name: Option<String>,
    /// Output network file (.json, .obj, .net).
    #[arg(short, long, required_unless_present = "list")]
    output: Option<PathBuf>,
    /// List the bundled examples.
    #[arg(long)]
    list: bool,
    /// Add sensor-like noise: Gaussian, σ = F × the sample spacing on positions, σ = F on the
    /// unit normals (\[CG\] §4.5).
    #[arg(long, value_name = "F")]
    noise: Option<f64>,
    /// Seed of the noise.
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// Leave the normals out (test data for the inference; .json and .obj only).
    #[arg(long)]
    no_normals: bool,
}

pub fn run(a: &ExampleArgs) -> Result<(), Error> {
    if a.list {
        for (name, what) in examples::EXAMPLES {
            out!("{name:<12}{what}");
        }
        return Ok(());
    }
    let (Some(name), Some(out)) = (&a.name, &a.output) else {
        return Err(Error::usage("give an example name and -o FILE (see --list)"));
    };
    let net = examples::example(name).ok_or_else(|| {
        let names: Vec<&str> = examples::EXAMPLES.iter().map(|e| e.0).collect();
        Error::usage(format!("unknown example \"{name}\"; the examples are: {}", names.join(", ")))
    })?;
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
    out!("{}: example \"{name}\", {} curves, {} samples{noise}", out.display(), net.curves.len(), net.num_samples());
    Ok(())
}
