//! `curvenet render`: a PNG picture of a mesh, or of a network surfaced on the fly.

use crate::options::{options, SolveArgs};
use crate::Progress;
use clap::Args;
use curvenet::io::read_mesh;
use curvenet::render::{render, Coloring, RenderOptions, Scene, View};
use curvenet::Error;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::time::Instant;

pub const RENDER_HELP: &str = "\
INPUT is a mesh (.ply, .off, .obj with faces) or a curve network (.json, .net, .obj with lines),
which is surfaced first with the surfacing options below.

Colourings (--color, comma-separated, one panel each; `all` for every one):
  shaded            plain shading
  curvature         signed mean curvature, diverging map centred at 0 (+ red, - blue), colour bar
  isophotes         zebra stripes of reflected light: kinks show tangent breaks
  normal-deviation  angle between the propagated normals N* and the surface's normals, in degrees
                    (networks surfaced by normal-control, or PLY files written by curvenet)

Examples:
  curvenet render sphere.ply -o sphere.png --color curvature
  curvenet render torus.json -o torus.png --color curvature,isophotes --grid
  curvenet render mesh.obj -o m.png --curves net.json --view 60,20,1.5 --size 800x600";

#[derive(Args)]
pub struct RenderArgs {
    /// Mesh (.ply, .off, .obj) or curve network (.json, .net, .obj with polylines).
    input: PathBuf,
    /// Output image (.png). Written only if rendering succeeds.
    #[arg(short, long)]
    output: PathBuf,
    #[command(flatten)]
    picture: PictureArgs,
    /// Curves to draw on a mesh input (a network file); a network input draws its own.
    #[arg(long, value_name = "NETWORK")]
    curves: Option<PathBuf>,
    /// Surfacing options (network input only).
    #[command(flatten)]
    solve: SolveArgs,
    /// The global `-q` (`Cli::quiet`): print nothing but results, errors and warnings.
    #[arg(skip)]
    pub(crate) quiet: bool,
}

/// How the picture looks: shared by `render` and `surface --render`.
#[derive(Args, Clone)]
pub struct PictureArgs {
    /// Colourings, comma-separated: shaded, curvature, isophotes, normal-deviation, or all.
    #[arg(long = "color", alias = "colour", value_name = "LIST", default_value = "shaded")]
    pub color: String,
    /// Camera: azimuth and elevation in degrees, optional zoom (repeat for several views).
    #[arg(long, value_name = "AZ,EL[,ZOOM]", allow_hyphen_values = true)]
    pub view: Vec<String>,
    /// Several views in one image: four standard views (front, side, top, three-quarter) when
    /// no --view is given.
    #[arg(long)]
    pub grid: bool,
    /// Panels per row [default: one per colouring; 2 for --grid with one colouring].
    #[arg(long, value_name = "N")]
    pub columns: Option<usize>,
    /// Image size in pixels.
    #[arg(long, value_name = "WxH", default_value = "1200x900")]
    pub size: String,
    /// Colour range: ±R for curvature, [0, R] degrees for normal deviation [default: from the
    /// data, the 95th percentile of |H| / 99th of the angles].
    #[arg(long, value_name = "R", allow_negative_numbers = true)]
    pub range: Option<f64>,
    /// Number of isophote stripes.
    #[arg(long, value_name = "N", default_value_t = 12)]
    pub stripes: u32,
    /// Do not draw the curves.
    #[arg(long)]
    pub no_curves: bool,
    /// Title prefix of every panel.
    #[arg(long)]
    pub title: Option<String>,
}

impl PictureArgs {
    /// The library's render options these flags select (a usage error names the bad flag).
    pub fn options(&self) -> Result<RenderOptions, Error> {
        let colorings = parse_colorings(&self.color)?;
        let mut views =
            self.view.iter().map(|v| View::parse(v).map_err(Error::usage)).collect::<Result<Vec<_>, _>>()?;
        if self.grid && views.is_empty() {
            views = vec![
                View { azimuth: 0.0, elevation: 0.0, zoom: 1.0 },
                View { azimuth: 90.0, elevation: 0.0, zoom: 1.0 },
                View { azimuth: 0.0, elevation: 90.0, zoom: 1.0 },
                View::default(),
            ];
        }
        let (width, height) = parse_size(&self.size)?;
        if let Some(r) = self.range {
            if !(r.is_finite() && r > 0.0) {
                return Err(Error::usage(format!("--range {r}: must be a positive number")));
            }
        }
        let columns = self.columns.or(if colorings.len() == 1 && views.len() > 1 { Some(2) } else { None });
        Ok(RenderOptions {
            width,
            height,
            colorings,
            views,
            columns,
            range: self.range,
            stripes: self.stripes,
            curves: !self.no_curves,
            title: self.title.clone(),
        })
    }
}

fn parse_colorings(list: &str) -> Result<Vec<Coloring>, Error> {
    if list.trim() == "all" {
        return Ok(Coloring::ALL.to_vec());
    }
    list.split(',')
        .map(|s| {
            Coloring::parse(s.trim()).ok_or_else(|| {
                Error::usage(format!(
                    "--color: unknown colouring \"{}\"; use shaded, curvature, isophotes, normal-deviation or all",
                    s.trim()
                ))
            })
        })
        .collect()
}

fn parse_size(s: &str) -> Result<(u32, u32), Error> {
    let bad = || Error::usage(format!("--size \"{s}\": expected WIDTHxHEIGHT in pixels, e.g. 1200x900"));
    let (w, h) = s.split_once(['x', 'X']).ok_or_else(bad)?;
    Ok((w.trim().parse().map_err(|_| bad())?, h.trim().parse().map_err(|_| bad())?))
}

/// Checks that `path` ends in `.png` (before any work).
pub fn check_png_path(path: &Path) -> Result<(), Error> {
    match path.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase).as_deref() {
        Some("png") => Ok(()),
        _ => Err(Error::usage(format!("{}: the image must be a .png file", path.display()))),
    }
}

/// Whether `path` holds a mesh rather than a network: by extension, and for OBJ by whether it
/// has faces (`f`) rather than polylines (`l`).
fn is_mesh(path: &Path) -> Result<bool, Error> {
    let ext = path.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase).unwrap_or_default();
    match ext.as_str() {
        "ply" | "off" => Ok(true),
        "json" | "net" => Ok(false),
        "obj" => {
            let text = curvenet::io::read_input(path, curvenet::io::InputKind::Text, curvenet::io::MAX_INPUT_BYTES)?;
            Ok(text.split(|&b| b == b'\n').any(|l| l.starts_with(b"f ")))
        }
        _ => Err(Error::usage(format!(
            "{}: unknown input format \".{ext}\"; a mesh (.ply, .off, .obj) or a network (.json, .net, .obj)",
            path.display()
        ))),
    }
}

pub fn run(a: &RenderArgs) -> Result<(), Error> {
    let start = Instant::now();
    check_png_path(&a.output)?;
    let opts = a.picture.options()?;
    let scene = if is_mesh(&a.input)? {
        let mesh = read_mesh(&a.input)?;
        let scene = Scene::from_mesh(mesh.as_data())?;
        match &a.curves {
            Some(p) => scene.with_network_curves(&crate::read_network(p)?),
            None => scene,
        }
    } else {
        if a.curves.is_some() {
            return Err(Error::usage("--curves is for mesh inputs; a network input draws its own curves"));
        }
        let network = crate::read_network(&a.input)?;
        let progress = Progress::new(a.quiet);
        let surface =
            curvenet::surface_with_progress(&network, &options(&a.solve)?, &mut |s, t, d| progress.stage(s, t, d))?;
        for w in surface.warnings.iter().filter(|w| !progress.already_said(&w.message)) {
            eprintln!("warning: {w}");
        }
        Scene::from_surface(&surface).with_network_curves(&network)
    };
    let image = render(&scene, &opts)?;
    image.write_png(&a.output)?;
    if !a.quiet {
        out!(
            "{}: {}x{} pixels, {} triangles, in {:.2} s",
            a.output.display(),
            image.width,
            image.height,
            scene.faces.len(),
            start.elapsed().as_secs_f64()
        );
    }
    Ok(())
}
