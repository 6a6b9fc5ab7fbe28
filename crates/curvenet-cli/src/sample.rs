//! `curvenet sample`: build a curve network on a triangle mesh (plane sections with normals
//! from the mesh; see [`curvenet::sampling`]).

use clap::Args;
use curvenet::io::{read_mesh, write_network};
use curvenet::sampling::{sample_mesh, CurveFamily, SampleOptions};
use curvenet::Error;
use std::io::Write;
use std::path::PathBuf;

#[derive(Args)]
pub struct SampleArgs {
    /// The mesh to sample (.obj, .ply, .off), triangles counter-clockwise seen from outside.
    mesh: PathBuf,
    /// Output network file (.json, .obj, .net).
    #[arg(short, long)]
    output: PathBuf,
    /// Section planes per axis, X,Y,Z (a single number for all three); with --curves principal
    /// their mean sets the distance between the curves.
    /// [default: 8,8,8, more when the network's surface would leave parts of the mesh out]
    #[arg(long, value_name = "X,Y,Z")]
    planes: Option<String>,
    /// Distance between samples along the curves (default: 1/200 of the bounding-box diagonal).
    #[arg(long, value_name = "D")]
    spacing: Option<f64>,
    /// Sensor-like noise: Gaussian, σ = F × the sample spacing on positions, σ = F on the unit
    /// normals.
    #[arg(long, value_name = "F", default_value_t = 0.0)]
    noise: f64,
    /// Seed of the noise.
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// Leave out the exact crossing samples: each curve is sampled uniformly along its length and
    /// crossings fall between samples, as with sensors.
    #[arg(long)]
    no_shared_nodes: bool,
    /// Leave out the mesh's boundary loops.
    #[arg(long)]
    no_boundary: bool,
    /// Leave the normals out (test data for the inference; .json and .obj only).
    #[arg(long)]
    no_normals: bool,
    /// The plane directions are the coordinate axes turned by DEG degrees about (1,2,3)
    /// (0: axis-aligned; then walls parallel to an axis are cut along coincident curves).
    #[arg(long, value_name = "DEG", default_value_t = SampleOptions::DEFAULT_TILT_DEG)]
    tilt: f64,
    /// The curves: `planes` (plane sections in three directions) or `principal` (curves along
    /// the principal curvature directions — a fixed axis projected on the surface where it is
    /// isotropic — crossing at about 90°, half the mean box extent over the mean --planes
    /// count apart; crossings exact on the mesh, free ends cut back to their last crossing).
    #[arg(long, value_name = "KIND", default_value = "planes", value_parser = ["planes", "principal"])]
    curves: String,
    /// The mesh's creases: edges whose two faces' normals are more than DEG degrees apart are
    /// sharp; their chains become crease curves (two normals per sample, `normals_right`;
    /// .json only) and the other curves end on them [default: 30, the creases left smooth when
    /// the network without them covers the mesh better]
    #[arg(long, value_name = "DEG")]
    crease_angle: Option<f64>,
    /// Find no creases: every curve smooth across (one normal per sample; a mesh with sharp
    /// edges then comes back rounded).
    #[arg(long, conflicts_with = "crease_angle")]
    no_creases: bool,
    /// Redraw the curves as a hand draws them, test data for consolidation with the mesh as its
    /// truth: strokes that stop short of or overshoot each other by up to GAP (a fraction of
    /// the bounding-box diagonal, e.g. 0.01), some drawn twice or retraced, hooks at some ends,
    /// uneven spacing about the sections' own (random by --seed; crease normals are not kept).
    #[arg(long, value_name = "GAP")]
    as_drawn: Option<f64>,
    /// The global `-q` (`Cli::quiet`): print nothing but results, errors and warnings.
    #[arg(skip)]
    pub(crate) quiet: bool,
}

fn parse_planes(s: &str) -> Result<[usize; 3], Error> {
    let bad = || Error::usage(format!("--planes {s}: give three counts X,Y,Z (e.g. 8,8,8) or one count"));
    let v: Vec<usize> = s.split(',').map(|t| t.trim().parse::<usize>().map_err(|_| bad())).collect::<Result<_, _>>()?;
    match v.as_slice() {
        [n] => Ok([*n; 3]),
        [x, y, z] => Ok([*x, *y, *z]),
        _ => Err(bad()),
    }
}

pub fn run(a: &SampleArgs) -> Result<(), Error> {
    let format = curvenet::io::NetworkFormat::from_path(&a.output)?;
    let opts = SampleOptions {
        planes: a.planes.as_deref().map(parse_planes).transpose()?.unwrap_or(SampleOptions::DEFAULT_PLANES),
        spacing: a.spacing,
        noise: a.noise,
        seed: a.seed,
        shared_nodes: !a.no_shared_nodes,
        boundary: !a.no_boundary,
        tilt: a.tilt,
        curves: if a.curves == "principal" { CurveFamily::Principal } else { CurveFamily::Planes },
        crease_angle: (!a.no_creases).then_some(a.crease_angle.unwrap_or(SampleOptions::DEFAULT_CREASE_DEG)),
        // The counts and the creases asked for are kept as asked.
        adapt: a.planes.is_none() && a.crease_angle.is_none(),
    };
    if let Some(deg) = a.crease_angle.filter(|d| !(d.is_finite() && *d > 0.0 && *d < 180.0)) {
        return Err(Error::usage(format!("--crease-angle {deg}: give an angle in degrees between 0 and 180")));
    }
    let mesh = read_mesh(&a.mesh)?;
    let (net, r) = sample_mesh(&mesh.positions, &mesh.faces, &opts)?;
    let net = match a.as_drawn {
        Some(gap) if !(gap.is_finite() && (0.0..0.2).contains(&gap)) => {
            return Err(Error::usage(format!("--as-drawn {gap}: give a gap between 0 and 0.2 of the diagonal")));
        }
        Some(gap) => {
            // The strokes' samples as far apart as the sections' (--spacing).
            let spacing = net.mean_sample_spacing() / net.bounding_box().diagonal();
            let drawn = curvenet::sampling::strokes::Drawn { gap, spacing, ..Default::default() };
            curvenet::sampling::strokes::as_drawn(&net, &drawn, a.seed)
        }
        None => net,
    };
    let net = if a.no_normals { net.without_normals() } else { net };
    if net.has_creases() && format != curvenet::io::NetworkFormat::Json {
        return Err(Error::usage(format!(
            "{}: the mesh has {} crease(s) (sharp edges above --crease-angle {}°), and only .json holds a crease's two \
             normals; write .json, or give --no-creases for a network of smooth curves",
            a.output.display(),
            r.creases,
            a.crease_angle.unwrap_or(SampleOptions::DEFAULT_CREASE_DEG)
        )));
    }
    write_network(&a.output, &net)?;
    let mut dropped = String::new();
    if r.dropped_sections + r.dropped_boundary_loops > 0 {
        dropped = format!(
            "; left out {} section(s) and {} boundary loop(s) that meet no other curve",
            r.dropped_sections, r.dropped_boundary_loops
        );
    }
    if r.zipped > 0 {
        dropped += &format!("; welded {} boundary vertex pair(s) across cracks", r.zipped);
    }
    if r.cut_bad > 0 {
        dropped += &format!(
            "; cut {} section(s) at bad spots (a shallow crossing, two crossings close together or a near miss left after {} plane moves, an end crowding another one on the boundary, a sharp turn): the stretch between the crossings around each spot left out",
            r.cut_bad,
            curvenet::sampling::MAX_PLANE_MOVES
        );
    }
    if r.sharp_turns > 0 {
        dropped += &format!(
            "; cut sections at {} place(s) where they turned back by more than {}° within the surface (a plane grazing a sharp crease)",
            r.sharp_turns,
            curvenet::sampling::SHARP_TURN_DEG
        );
    }
    if r.small_holes > 0 {
        dropped += &format!("; covered {} hole(s) smaller than 3 sample spacings or slit-shaped", r.small_holes);
    }
    if r.single_contact_holes > 0 {
        dropped += &format!(
            "; covered {} hole(s) that a single section reached (that section's end cut back to its last crossing)",
            r.single_contact_holes
        );
    }
    if r.trimmed > 0 {
        dropped += &format!("; cut back {} section end(s) that ran along the boundary", r.trimmed);
    }
    if r.hairpins > 0 {
        dropped += &format!("; cut {} hairpin(s) where a curve came back along itself", r.hairpins);
    }
    if r.folded_normals > 0 {
        dropped += &format!(
            "; replaced {} normal(s) from folded mesh faces (within {}° of the curve's direction, or off both neighbours) by the nearest good one on the curve",
            r.folded_normals,
            curvenet::sampling::FOLDED_NORMAL_DEG
        );
    }
    if r.smoothed_creases > 0 {
        dropped += &format!(
            "; left {} chain(s) of sharp edges smooth (shorter than {} sample spacings, within the snapping distance of a longer crease, or refused by `surface`)",
            r.smoothed_creases,
            curvenet::sampling::MIN_CREASE_SPACINGS
        );
    }
    if !r.left_out.is_empty() {
        dropped += &format!(
            "; left out {} curve(s) that `surface` refused (each named in a warning), so that it takes the rest",
            r.left_out.len()
        );
    }
    if !r.smoothed_refused.is_empty() {
        dropped += &format!(
            "; sampled again with {} crease(s) that `surface` refused left smooth (each named in a warning)",
            r.smoothed_refused.len()
        );
    }
    print_warnings(&r, a.quiet);
    if r.pinches > 0 {
        dropped += &format!("; split {} pinch vertex(es) where the mesh boundary touches itself", r.pinches);
    }
    if a.quiet {
        return Ok(());
    }
    out!(
        "{}: {} {}, {} boundary loops, {} creases, {} crossings, {} samples, spacing {:.4e}{dropped}",
        a.output.display(),
        r.sections,
        if a.curves == "principal" { "principal curves" } else { "sections" },
        r.boundary_loops,
        r.creases,
        r.crossings,
        net.num_samples(),
        r.spacing
    );
    Ok(())
}

/// The warnings of a sampling (and, unless `quiet`, the note on the planes taken) on stderr.
fn print_warnings(r: &curvenet::sampling::SampleReport, quiet: bool) {
    if let Some(p) = r.planes.filter(|_| !quiet) {
        eprintln!(
            "note: sampled with {},{},{} planes: fewer left parts of the mesh out of the network's surface (give --planes to choose)",
            p[0], p[1], p[2]
        );
    }
    if let Some((creases, with, without)) = r.creases_dropped {
        eprintln!(
            "warning: the mesh's {creases} crease(s) are left smooth: with them the network's quick surface passed near {:.0} % of the mesh, without them {:.0} % (give --crease-angle to keep them, --no-creases to say so)",
            100.0 * with,
            100.0 * without
        );
    }
    if let Some(c) = r.mesh_coverage.filter(|&c| c < curvenet::sampling::GOOD_COVERAGE) {
        eprintln!(
            "warning: the network's quick surface passes near only {:.0} % of the mesh's area (within {} of its bounding-box diagonal): `surface` will leave parts of the mesh out",
            100.0 * c,
            curvenet::sampling::verify::COVERAGE_DISTANCE
        );
    }
    for why in &r.smoothed_refused {
        eprintln!("warning: left smooth (the mesh sampled again without it) {why}");
    }
    for why in &r.left_out {
        eprintln!("warning: left out {why}");
    }
    if let Some(e) = &r.unsurfaced {
        eprintln!("warning: `curvenet surface` will refuse this network with default options: {e}");
    }
}
