//! Pictures of surfaces, headless and without a GPU: shaded surfaces, signed mean curvature
//! on a diverging colour map centred at zero, isophotes (zebra stripes), the deviation between
//! propagated and computed normals, and the input curves on top — the views by which \[CG\]
//! judges its surfaces (Fig. 3–8).
//!
//! - [`raster`]: camera, visibility buffer, depth-tested lines, anti-aliasing downsample.
//! - [`colormap`]: the diverging and sequential maps.
//! - [`font`]: bitmap text for titles and colour-bar labels.
//! - [`png`]: the PNG encoder.
//!
//! ```no_run
//! # use curvenet::render::*;
//! let net = curvenet::network::examples::example("torus").ok_or(curvenet::Error::usage("no torus example"))?;
//! let surface = curvenet::surface(&net, &curvenet::Options::default())?;
//! let scene = Scene::from_surface(&surface).with_network_curves(&net);
//! let image = render(&scene, &RenderOptions { colorings: vec![Coloring::Curvature], ..Default::default() })?;
//! image.write_png("torus.png".as_ref())?;
//! # Ok::<(), curvenet::Error>(())
//! ```

pub mod colormap;
pub mod font;
pub mod png;
pub mod raster;

pub use raster::View;

use crate::error::{Error, Result};
use crate::geom::{Aabb, DVec3};
use crate::io::MeshData;
use crate::network::Network;
use raster::{Camera, Frame, Visibility, EMPTY};
use rayon::prelude::*;
use std::path::Path;

/// An 8-bit RGB image, rows top to bottom.
#[derive(Clone, Debug, PartialEq)]
pub struct Image {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// `width × height × 3` bytes, rows top to bottom.
    pub rgb: Vec<u8>,
}

impl Image {
    /// A `width × height` image filled with `colour`.
    pub fn filled(width: u32, height: u32, colour: [u8; 3]) -> Image {
        let rgb = colour.iter().copied().cycle().take(width as usize * height as usize * 3).collect();
        Image { width, height, rgb }
    }

    /// The pixel at `(x, y)`.
    pub fn get(&self, x: u32, y: u32) -> [u8; 3] {
        let k = (y as usize * self.width as usize + x as usize) * 3;
        [self.rgb[k], self.rgb[k + 1], self.rgb[k + 2]]
    }

    /// Sets the pixel at `(x, y)`; outside the image, does nothing.
    pub fn set(&mut self, x: i32, y: i32, colour: [u8; 3]) {
        if x < 0 || y < 0 || x as u32 >= self.width || y as u32 >= self.height {
            return;
        }
        let k = (y as usize * self.width as usize + x as usize) * 3;
        self.rgb[k..k + 3].copy_from_slice(&colour);
    }

    /// Copies `other` with its top-left corner at `(x, y)`.
    pub fn blit(&mut self, other: &Image, x: u32, y: u32) {
        for row in 0..other.height.min(self.height.saturating_sub(y)) {
            let w = other.width.min(self.width.saturating_sub(x)) as usize * 3;
            let src = row as usize * other.width as usize * 3;
            let dst = ((y + row) as usize * self.width as usize + x as usize) * 3;
            self.rgb[dst..dst + w].copy_from_slice(&other.rgb[src..src + w]);
        }
    }

    /// The image as a PNG file's bytes.
    pub fn encode_png(&self) -> Vec<u8> {
        png::encode_rgb(self.width, self.height, &self.rgb)
    }

    /// Writes the image as PNG, atomically (an existing file is left as it was on failure).
    pub fn write_png(&self, path: &Path) -> Result<()> {
        self.stage_png(path)?.commit()
    }

    /// Writes the PNG beside `path` without making it visible yet (see [`crate::io::Staged`]),
    /// to commit it together with other outputs.
    pub fn stage_png(&self, path: &Path) -> Result<crate::io::Staged> {
        let bytes = self.encode_png();
        crate::io::Staged::write(path, |w| w.write_all(&bytes))
    }
}

/// What colours the surface.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Coloring {
    /// Plain shading (Blinn–Phong, two lights).
    Shaded,
    /// Signed mean curvature, diverging map centred at zero (`+` red, `−` blue), with a colour
    /// bar (\[CG\] Fig. 3, 4, 8).
    Curvature,
    /// Isophotes: zebra stripes of the reflected view direction; kinks in the stripes show
    /// tangent discontinuities, wobbles show curvature noise (\[CG\] Fig. 4).
    Isophotes,
    /// Angle in degrees between the propagated normals `N*` and the surface's own normals
    /// (\[CG\] Fig. 5), sequential map with a colour bar.
    NormalDeviation,
}

impl Coloring {
    /// Every colouring.
    pub const ALL: [Coloring; 4] =
        [Coloring::Shaded, Coloring::Curvature, Coloring::Isophotes, Coloring::NormalDeviation];

    /// The command-line name.
    pub fn name(self) -> &'static str {
        match self {
            Coloring::Shaded => "shaded",
            Coloring::Curvature => "curvature",
            Coloring::Isophotes => "isophotes",
            Coloring::NormalDeviation => "normal-deviation",
        }
    }

    /// The caption of a panel in this colouring.
    pub fn caption(self) -> &'static str {
        match self {
            Coloring::Shaded => "shaded",
            Coloring::Curvature => "mean curvature H",
            Coloring::Isophotes => "isophotes",
            Coloring::NormalDeviation => "angle(N*, n) [deg]",
        }
    }

    /// The colouring called `s` ([`Coloring::name`]; `zebra` is `isophotes`).
    pub fn parse(s: &str) -> Option<Coloring> {
        Coloring::ALL.into_iter().find(|c| c.name() == s || (s == "zebra" && *c == Coloring::Isophotes))
    }
}

/// What is drawn: a triangle mesh with per-vertex attributes, and polylines on top.
#[derive(Clone, Debug, Default)]
pub struct Scene {
    /// Vertex positions, `#V`.
    pub positions: Vec<DVec3>,
    /// Triangles, counter-clockwise seen from outside, `#F`.
    pub faces: Vec<[u32; 3]>,
    /// Unit vertex normals (shading, isophotes).
    pub normals: Vec<DVec3>,
    /// Signed mean curvature per vertex (`+1` on the unit sphere).
    pub mean_curvature: Vec<f64>,
    /// The propagated normals `N*`, when the mesh carries them.
    pub propagated_normals: Option<Vec<DVec3>>,
    /// Polylines drawn over the surface (the input curves).
    pub curves: Vec<Vec<DVec3>>,
}

impl Scene {
    /// A scene from a mesh and whichever attributes it carries; normals and mean curvature are
    /// computed (cotangent formula, 0 on open-boundary vertices) where missing.
    pub fn from_mesh(mesh: MeshData<'_>) -> Result<Scene> {
        let n = mesh.positions.len();
        if n == 0 || mesh.faces.is_empty() {
            return Err(Error::input("the mesh has no triangles to render"));
        }
        if let Some(i) = mesh.positions.iter().position(|p| !p.is_finite()) {
            return Err(Error::input(format!("vertex {i} of the mesh is not finite")));
        }
        check_faces(mesh.faces, n)?;
        let boundary = crate::operators::border_vertices(mesh.faces, n);
        let (normals, mean_curvature) = match (mesh.normals, mesh.mean_curvature) {
            (Some(nr), Some(h)) if nr.len() == n && h.len() == n => (nr.to_vec(), h.to_vec()),
            (nr, _) => {
                let (computed_n, h) =
                    crate::operators::normals_and_mean_curvature(mesh.faces, mesh.positions, &boundary);
                (nr.filter(|v| v.len() == n).map(<[DVec3]>::to_vec).unwrap_or(computed_n), h)
            }
        };
        Ok(Scene {
            positions: mesh.positions.to_vec(),
            faces: mesh.faces.to_vec(),
            normals,
            mean_curvature,
            propagated_normals: mesh.propagated_normals.filter(|v| v.len() == n).map(<[DVec3]>::to_vec),
            curves: Vec::new(),
        }
        .split_at_sharp_edges())
    }

    /// The scene with its vertices split where two faces' normals are more than
    /// [`crate::operators::SHARP_SHADING_DEG`] apart, each side with its own normal
    /// ([`crate::operators::split_normals`]), so that creases are shaded sharp; the copies
    /// keep the vertex's curvature and `N*`.
    pub fn split_at_sharp_edges(self) -> Scene {
        let angle = crate::operators::SHARP_SHADING_DEG.to_radians();
        let split = crate::operators::split_normals(&self.faces, &self.positions, &self.normals, angle);
        if split.normals.len() == self.positions.len() {
            return Scene { normals: split.normals, ..self };
        }
        let of = split.vertex;
        let copy = |v: &[f64]| of.iter().map(|&i| v[i as usize]).collect::<Vec<f64>>();
        let copy3 = |v: &[DVec3]| of.iter().map(|&i| v[i as usize]).collect::<Vec<DVec3>>();
        Scene {
            positions: copy3(&self.positions),
            faces: split.corners,
            normals: split.normals,
            mean_curvature: copy(&self.mean_curvature),
            propagated_normals: self.propagated_normals.as_deref().map(copy3),
            curves: self.curves,
        }
    }

    /// The scene of a surfacing result (its mesh, normals, curvature and `N*`).
    pub fn from_surface(surface: &crate::Surface) -> Scene {
        Scene {
            positions: surface.mesh.positions.clone(),
            faces: surface.mesh.faces.clone(),
            normals: surface.normals.clone(),
            mean_curvature: surface.mean_curvature.clone(),
            propagated_normals: surface.propagated_normals.clone(),
            curves: Vec::new(),
        }
        .split_at_sharp_edges()
    }

    /// Adds the network's curves (closed curves drawn closed) as polylines.
    pub fn with_network_curves(mut self, network: &Network) -> Scene {
        for c in &network.curves {
            let mut pts = c.points.clone();
            if c.closed && !pts.is_empty() {
                pts.push(pts[0]);
            }
            self.curves.push(pts);
        }
        self
    }

    /// Checks that the attributes have one entry per vertex and the faces valid indices
    /// (the fields are public: a scene built by hand is checked before it is drawn).
    pub fn check(&self) -> Result<()> {
        let n = self.positions.len();
        if self.faces.is_empty() {
            return Err(Error::input("the mesh has no triangles to render"));
        }
        check_faces(&self.faces, n)?;
        let lengths = [
            ("normals", self.normals.len()),
            ("mean curvatures", self.mean_curvature.len()),
            ("propagated normals", self.propagated_normals.as_ref().map_or(n, Vec::len)),
        ];
        if let Some((what, len)) = lengths.iter().find(|(_, len)| *len != n) {
            return Err(Error::input(format!("the scene has {len} {what} for {n} vertices")));
        }
        Ok(())
    }

    fn bounds(&self) -> (DVec3, f64) {
        let b = Aabb::of(self.positions.iter().copied());
        let c = b.center();
        let r = self.positions.iter().map(|p| p.distance(c)).fold(0.0, f64::max);
        (c, r)
    }

    /// Angle in degrees between `N*` and the normals, per vertex (`None` without `N*`).
    pub fn normal_deviation_degrees(&self) -> Option<Vec<f64>> {
        let pn = self.propagated_normals.as_ref()?;
        Some(
            pn.iter()
                .zip(&self.normals)
                .map(|(a, b)| {
                    let (a, b) = (a.normalize_or_zero(), b.normalize_or_zero());
                    a.cross(b).length().atan2(a.dot(b)).to_degrees()
                })
                .collect(),
        )
    }

    /// The symmetric colour range `±R` of the curvature map: the 95th percentile of `|H|`
    /// (a few noisy vertices do not wash out the map; a sphere's map is one colour).
    pub fn curvature_range(&self) -> f64 {
        percentile(self.mean_curvature.iter().map(|h| h.abs()).collect(), 0.95).max(1e-12)
    }
}

/// An error naming the first face that refers to a vertex beyond the `n` of the mesh.
fn check_faces(faces: &[[u32; 3]], n: usize) -> Result<()> {
    match faces.iter().enumerate().find(|(_, f)| f.iter().any(|&v| v as usize >= n)) {
        Some((k, f)) => Err(Error::input(format!("face {k} {f:?} refers to a vertex beyond the {n} of the mesh"))),
        None => Ok(()),
    }
}

fn percentile(mut values: Vec<f64>, q: f64) -> f64 {
    values.retain(|v| v.is_finite());
    if values.is_empty() {
        return 0.0;
    }
    let k = ((values.len() - 1) as f64 * q).round() as usize;
    *values.select_nth_unstable_by(k, |a, b| a.total_cmp(b)).1
}

/// One panel of a picture: a scene, how it is coloured, from where, and its title.
#[derive(Clone, Debug)]
pub struct Panel<'a> {
    /// What is drawn.
    pub scene: &'a Scene,
    /// How it is coloured.
    pub coloring: Coloring,
    /// From where.
    pub view: View,
    /// The caption above the panel.
    pub title: String,
    /// Colour range: `±range` for curvature, `[0, range]` degrees for normal deviation;
    /// `None` picks it from the data. Give panels one range to compare them.
    pub range: Option<f64>,
    /// Number of isophote stripes over the half-circle of reflected directions.
    pub stripes: u32,
    /// Draw the scene's curves.
    pub curves: bool,
}

/// Options of [`render`]: which colourings and views, laid out in a grid.
#[derive(Clone, Debug)]
pub struct RenderOptions {
    /// Width of the whole picture in pixels.
    pub width: u32,
    /// Height of the whole picture in pixels.
    pub height: u32,
    /// The colourings, one panel each (per view).
    pub colorings: Vec<Coloring>,
    /// One panel per colouring and view; empty: the default view.
    pub views: Vec<View>,
    /// Columns of the grid; `None`: one row per view, one column per colouring.
    pub columns: Option<usize>,
    /// Colour range of every panel (see [`Panel::range`]).
    pub range: Option<f64>,
    /// Isophote stripes (see [`Panel::stripes`]).
    pub stripes: u32,
    /// Draw the scene's curves.
    pub curves: bool,
    /// Prefix of every panel's title.
    pub title: Option<String>,
}

impl Default for RenderOptions {
    fn default() -> Self {
        RenderOptions {
            width: 1200,
            height: 900,
            colorings: vec![Coloring::Shaded],
            views: Vec::new(),
            columns: None,
            range: None,
            stripes: 12,
            curves: true,
            title: None,
        }
    }
}

/// Renders `scene` in every colouring and view of `options`, one panel each, in a grid.
pub fn render(scene: &Scene, options: &RenderOptions) -> Result<Image> {
    let views = if options.views.is_empty() { vec![View::default()] } else { options.views.clone() };
    let colorings = if options.colorings.is_empty() { vec![Coloring::Shaded] } else { options.colorings.clone() };
    let mut panels = Vec::new();
    for &view in &views {
        for &coloring in &colorings {
            let mut title = coloring.caption().to_string();
            if let Some(t) = &options.title {
                title = format!("{t}: {title}");
            }
            if views.len() > 1 {
                title = format!("{title}  (az {}, el {})", view.azimuth, view.elevation);
            }
            panels.push(Panel {
                scene,
                coloring,
                view,
                title,
                range: options.range,
                stripes: options.stripes,
                curves: options.curves,
            });
        }
    }
    let columns = options.columns.unwrap_or(colorings.len());
    render_panels(&panels, columns, options.width, options.height)
}

/// The most memory a render may take (its supersampled frames, [`render_bytes`]): 2.5 GB, so
/// that a render fits a 4 GB address space with the mesh beside it.
pub const MAX_RENDER_BYTES: u64 = 2_500_000_000;

/// The memory `panels` panels of `pw × ph` pixels take while they are drawn, all at once (the
/// panels are drawn in parallel): per supersample a triangle index, barycentric coordinates,
/// a depth and a colour (32 bytes; 3×3 supersamples per pixel up to 0.7 Mpixel, 2×2 above),
/// and the final image (3 bytes per pixel).
pub fn render_bytes(pw: u32, ph: u32, panels: usize) -> u64 {
    let px = pw as u64 * ph as u64;
    let ss = if px <= 700_000 { 9 } else { 4 };
    panels as u64 * px * (ss * 32 + 3)
}

/// Lays `panels` out in a grid of `columns` columns filling `width × height` pixels.
///
/// Errors ([`Error::Usage`]): a side outside 64–16384 pixels, panels under 64×64, a render
/// that would take more than [`MAX_RENDER_BYTES`], normal deviation without `N*`.
pub fn render_panels(panels: &[Panel<'_>], columns: usize, width: u32, height: u32) -> Result<Image> {
    if panels.is_empty() {
        return Err(Error::usage("nothing to render: no panels"));
    }
    let columns = columns.clamp(1, panels.len());
    let rows = panels.len().div_ceil(columns);
    if width < 64 || height < 64 || width > 16384 || height > 16384 {
        return Err(Error::usage(format!(
            "image size {width}x{height}: each side must be between 64 and 16384 pixels"
        )));
    }
    let (pw, ph) = (width / columns as u32, height / rows as u32);
    let bytes = render_bytes(pw, ph, panels.len());
    if bytes > MAX_RENDER_BYTES {
        return Err(Error::usage(format!(
            "image size {width}x{height} would take about {:.1} GB to render (supersampled frames), more than the \
             {:.1} GB allowed; give a smaller size (about {}x{} fits)",
            bytes as f64 / 1e9,
            MAX_RENDER_BYTES as f64 / 1e9,
            (width as f64 * (MAX_RENDER_BYTES as f64 / bytes as f64).sqrt()) as u32,
            (height as f64 * (MAX_RENDER_BYTES as f64 / bytes as f64).sqrt()) as u32,
        )));
    }
    if pw < 64 || ph < 64 {
        return Err(Error::usage(format!(
            "image size {width}x{height} is too small for {} panels ({columns} columns): each panel needs 64x64 pixels",
            panels.len()
        )));
    }
    for p in panels {
        if p.coloring == Coloring::NormalDeviation && p.scene.propagated_normals.is_none() {
            return Err(Error::usage(
                "normal deviation needs the propagated normals N*: render a network surfaced by normal-control, or a PLY written by curvenet (pnx/pny/pnz)",
            ));
        }
        p.scene.check()?;
    }
    let images: Vec<Image> = panels.par_iter().map(|p| render_panel(p, pw, ph)).collect();
    let mut out = Image::filled(width, height, [255, 255, 255]);
    for (k, img) in images.iter().enumerate() {
        out.blit(img, (k % columns) as u32 * pw, (k / columns) as u32 * ph);
    }
    Ok(out)
}

/// The value printed on a colour bar: three significant digits, no exponent between 0.01 and
/// 10⁴.
pub fn format_value(v: f64) -> String {
    if v == 0.0 || !v.is_finite() {
        return "0".into();
    }
    let e = v.abs().log10().floor() as i32;
    if (-2..4).contains(&e) {
        format!("{:.*}", (2 - e).max(0) as usize, v)
    } else {
        format!("{v:.2e}")
    }
}

fn to_u8(c: [f32; 3]) -> [u8; 3] {
    c.map(|v| (v * 255.0 + 0.5).clamp(0.0, 255.0) as u8)
}

fn render_panel(p: &Panel<'_>, pw: u32, ph: u32) -> Image {
    let scale = if pw >= 420 { 2 } else { 1 };
    let title_h = font::text_height(scale) + 10 * scale;
    let has_bar = matches!(p.coloring, Coloring::Curvature | Coloring::NormalDeviation);
    let bar_h = if has_bar { 12 * scale + font::text_height(scale) + 8 * scale } else { 0 };
    let (vw, vh) = (pw as usize, ph.saturating_sub(title_h + bar_h).max(16) as usize);
    let ss = if vw * vh <= 700_000 { 3 } else { 2 };
    let (w, h) = (vw * ss, vh * ss);
    let scene = p.scene;
    let (center, radius) = scene.bounds();
    // Framed on the bounding sphere from the view's direction, then tightened to the mesh's
    // projection (the zoom applies after the fit).
    let camera = Camera::framing(center, radius, View { zoom: 1.0, ..p.view }, w, h).fit(
        &scene.positions,
        w,
        h,
        0.9,
        p.view.zoom,
    );
    let vis = Visibility::rasterize(&camera, &scene.positions, &scene.faces, w, h);

    // Per-vertex scalar of the colouring, and its range.
    let deviation;
    let (values, range): (&[f64], f64) = match p.coloring {
        Coloring::Curvature => (&scene.mean_curvature, p.range.unwrap_or_else(|| scene.curvature_range())),
        Coloring::NormalDeviation => {
            deviation = scene.normal_deviation_degrees().unwrap_or_default();
            let r = p.range.unwrap_or_else(|| percentile(deviation.clone(), 0.99).max(0.1));
            (&deviation, r)
        }
        _ => (&[], 1.0),
    };
    let background = [1.0f32, 1.0, 1.0];
    let mut frame = Frame { width: w, height: h, rgb: vec![background; w * h] };
    let stripes = p.stripes.max(1) as f64;
    frame.rgb.par_chunks_mut(w).enumerate().for_each(|(y, row)| {
        for (x, out) in row.iter_mut().enumerate() {
            let k = y * w + x;
            let t = vis.triangle[k];
            if t == EMPTY {
                continue;
            }
            let f = scene.faces[t as usize];
            let [b1, b2] = vis.bary[k];
            let (b1, b2) = (b1 as f64, b2 as f64);
            let b0 = 1.0 - b1 - b2;
            let (i0, i1, i2) = (f[0] as usize, f[1] as usize, f[2] as usize);
            let n = scene.normals[i0] * b0 + scene.normals[i1] * b1 + scene.normals[i2] * b2;
            let mut nv = camera.to_view(n.normalize_or_zero());
            let mut tint = 1.0f32;
            if nv.z < 0.0 {
                // The back of an open surface: shade its side with the flipped normal, darker.
                nv = -nv;
                tint = 0.75;
            }
            // Two lights in view space (a key light above left, a fill light below right) and
            // a Blinn–Phong highlight of the key light, for a viewer along +z.
            let key = DVec3::new(-0.45, 0.6, 0.66).normalize();
            let fill = DVec3::new(0.5, -0.3, 0.8).normalize();
            let diffuse = (0.75 * nv.dot(key).max(0.0) + 0.3 * nv.dot(fill).max(0.0)) as f32;
            let half = (key + DVec3::Z).normalize();
            let spec = nv.dot(half).max(0.0).powi(48) as f32;
            let c = match p.coloring {
                Coloring::Shaded => {
                    let base = [0.72f32, 0.76, 0.84];
                    base.map(|b| b * (0.22 + 0.85 * diffuse) + 0.35 * spec)
                }
                Coloring::Curvature | Coloring::NormalDeviation => {
                    let s = values[i0] * b0 + values[i1] * b1 + values[i2] * b2;
                    let base = if p.coloring == Coloring::Curvature {
                        colormap::diverging(s / range)
                    } else {
                        colormap::sequential(s / range)
                    };
                    base.map(|b| b * (0.5 + 0.55 * diffuse) + 0.12 * spec)
                }
                Coloring::Isophotes => {
                    // Reflect the view direction (+z) about the normal; stripes of equal
                    // elevation of the reflected ray (an environment of horizontal bands).
                    let r = 2.0 * nv.z * nv - DVec3::Z;
                    let phi = r.y.clamp(-1.0, 1.0).asin();
                    let band = ((phi / std::f64::consts::PI + 0.5) * stripes).floor() as i64;
                    let v = if band.rem_euclid(2) == 0 { 0.95f32 } else { 0.08 };
                    [v, v, v].map(|b| b * (0.75 + 0.25 * diffuse))
                }
            };
            *out = c.map(|v| v * tint);
        }
    });
    if p.curves {
        let line_width = 2.0 * ss as f64 * if pw >= 420 { 1.0 } else { 0.75 };
        for c in &scene.curves {
            frame.polyline(&camera, &vis, c, line_width, [0.1, 0.1, 0.1], 0.004);
        }
    }
    let (dw, dh, pixels) = frame.downsample(ss);
    let view_img = Image { width: dw as u32, height: dh as u32, rgb: pixels };

    let mut img = Image::filled(pw, ph, [255, 255, 255]);
    img.blit(&view_img, 0, title_h);
    let ink = [20, 20, 20];
    // A title too long for the panel drops to the small font, then is cut.
    let title_scale = if font::text_width(&p.title, scale) + 8 * scale <= pw { scale } else { 1 };
    let max_chars = (pw / (8 * title_scale)).saturating_sub(1) as usize;
    let title: String = p.title.chars().take(max_chars).collect();
    font::draw_text(&mut img, (4 * scale) as i32, (5 * scale) as i32, &title, title_scale, ink);
    if has_bar {
        let y0 = ph.saturating_sub(bar_h) + 2 * scale;
        let (x0, x1) = (pw / 5, pw - pw / 5);
        let bar_px = 12 * scale - 4 * scale;
        for x in x0..x1 {
            let t = (x - x0) as f64 / (x1 - x0 - 1).max(1) as f64;
            let c = if p.coloring == Coloring::Curvature {
                colormap::diverging(2.0 * t - 1.0)
            } else {
                colormap::sequential(t)
            };
            for y in y0..y0 + bar_px {
                img.set(x as i32, y as i32, to_u8(c));
            }
        }
        let labels: Vec<(u32, String)> = if p.coloring == Coloring::Curvature {
            vec![(x0, format_value(-range)), ((x0 + x1) / 2, "0".into()), (x1, format!("+{}", format_value(range)))]
        } else {
            vec![(x0, "0".into()), ((x0 + x1) / 2, format_value(0.5 * range)), (x1, format_value(range))]
        };
        let ly = (y0 + bar_px + 3 * scale) as i32;
        for (x, text) in labels {
            let tw = font::text_width(&text, scale);
            let lx = (x as i32 - tw as i32 / 2).clamp(0, pw as i32 - tw as i32);
            font::draw_text(&mut img, lx, ly, &text, scale, ink);
            for y in y0 + bar_px..y0 + bar_px + 2 * scale {
                img.set(x.min(pw - 1) as i32, y as i32, ink);
            }
        }
    }
    img
}

#[cfg(test)]
#[path = "tests/render.rs"]
mod tests;
