//! The software rasteriser: a perspective camera, a visibility buffer (depth, triangle and
//! perspective-correct barycentric coordinates per sample), depth-tested thick lines, and a
//! box-filter downsample of the supersampled frame (anti-aliasing).

use crate::geom::DVec3;

/// Vertical (or, for tall images, horizontal) field of view.
const FOV_DEG: f64 = 28.0;

/// Where the camera looks from: degrees of azimuth about +z (0 looks from +x), degrees of
/// elevation above the xy plane, and a zoom factor (1 frames the whole bounding sphere).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct View {
    /// Degrees about +z (0 looks from +x).
    pub azimuth: f64,
    /// Degrees above the xy plane.
    pub elevation: f64,
    /// Zoom factor (1 frames the whole bounding sphere).
    pub zoom: f64,
}

impl Default for View {
    fn default() -> Self {
        View { azimuth: 30.0, elevation: 25.0, zoom: 1.0 }
    }
}

impl View {
    /// Parses `AZ,EL` or `AZ,EL,ZOOM` (degrees, degrees, factor).
    pub fn parse(s: &str) -> Result<View, String> {
        let parts: Vec<&str> = s.split(',').map(str::trim).collect();
        if !(2..=3).contains(&parts.len()) {
            return Err(format!("view \"{s}\": expected AZIMUTH,ELEVATION[,ZOOM] in degrees"));
        }
        let num = |t: &str, what: &str| -> Result<f64, String> {
            t.parse::<f64>()
                .ok()
                .filter(|v| v.is_finite())
                .ok_or_else(|| format!("view \"{s}\": {what} \"{t}\" is not a number"))
        };
        let zoom = if parts.len() == 3 { num(parts[2], "zoom")? } else { 1.0 };
        if zoom <= 0.0 {
            return Err(format!("view \"{s}\": zoom must be positive"));
        }
        Ok(View { azimuth: num(parts[0], "azimuth")?, elevation: num(parts[1], "elevation")?, zoom })
    }
}

/// A pinhole camera framing a bounding sphere, in pixels of the (supersampled) frame.
#[derive(Clone, Copy, Debug)]
pub struct Camera {
    /// Position of the eye.
    pub eye: DVec3,
    /// Unit vector to the right of the image.
    pub right: DVec3,
    /// Unit vector to the top of the image.
    pub up: DVec3,
    /// Unit viewing direction.
    pub forward: DVec3,
    focal: f64,
    cx: f64,
    cy: f64,
}

impl Camera {
    /// The camera that shows the sphere `(center, radius)` whole in a `width × height` frame.
    pub fn framing(center: DVec3, radius: f64, view: View, width: usize, height: usize) -> Camera {
        let (az, el) = (view.azimuth.to_radians(), view.elevation.to_radians());
        let to_eye = DVec3::new(el.cos() * az.cos(), el.cos() * az.sin(), el.sin());
        let forward = -to_eye;
        let world_up = if to_eye.z.abs() > 0.999 { DVec3::Y } else { DVec3::Z };
        let right = forward.cross(world_up).normalize();
        let up = right.cross(forward);
        let half = (FOV_DEG.to_radians() * 0.5).tan();
        let focal = 0.5 * width.min(height) as f64 / half;
        let radius = if radius > 0.0 && radius.is_finite() { radius } else { 1.0 };
        let distance = 1.08 * radius / (FOV_DEG.to_radians() * 0.5).sin() / view.zoom;
        Camera {
            eye: center + to_eye * distance,
            right,
            up,
            forward,
            focal,
            cx: 0.5 * width as f64,
            cy: 0.5 * height as f64,
        }
    }

    /// Tightens the framing to `points`: their projected bounding box centred and filling
    /// `fill` of the frame, then magnified by `zoom` about the centre.
    pub fn fit(mut self, points: &[DVec3], width: usize, height: usize, fill: f64, zoom: f64) -> Camera {
        let (mut x0, mut y0, mut x1, mut y1) = (f64::INFINITY, f64::INFINITY, f64::NEG_INFINITY, f64::NEG_INFINITY);
        for &p in points {
            let (x, y, z) = self.project(p);
            if z > 0.0 && x.is_finite() && y.is_finite() {
                (x0, y0, x1, y1) = (x0.min(x), y0.min(y), x1.max(x), y1.max(y));
            }
        }
        if !(x1 > x0 || y1 > y0) {
            return self;
        }
        let s = (fill * width as f64 / (x1 - x0).max(1e-9)).min(fill * height as f64 / (y1 - y0).max(1e-9)) * zoom;
        // x' = cx' + s f u maps the box's middle to the frame's centre.
        self.cx = 0.5 * width as f64 - s * (0.5 * (x0 + x1) - self.cx);
        self.cy = 0.5 * height as f64 - s * (0.5 * (y0 + y1) - self.cy);
        self.focal *= s;
        self
    }

    /// Pixel coordinates (x right, y down) and view depth of `p`.
    pub fn project(&self, p: DVec3) -> (f64, f64, f64) {
        let d = p - self.eye;
        let z = d.dot(self.forward);
        let x = self.cx + self.focal * d.dot(self.right) / z;
        let y = self.cy - self.focal * d.dot(self.up) / z;
        (x, y, z)
    }

    /// A direction in view space: x right, y up, z towards the viewer.
    pub fn to_view(&self, v: DVec3) -> DVec3 {
        DVec3::new(v.dot(self.right), v.dot(self.up), -v.dot(self.forward))
    }
}

/// No triangle covers the sample.
pub const EMPTY: u32 = u32::MAX;

/// The visibility buffer of one frame: per sample the inverse depth of the nearest surface,
/// its triangle, and perspective-correct barycentric coordinates of vertices 1 and 2.
pub struct Visibility {
    /// Width in samples.
    pub width: usize,
    /// Height in samples.
    pub height: usize,
    /// Per sample: inverse depth of the nearest surface (0: none).
    pub inv_depth: Vec<f32>,
    /// Per sample: the nearest triangle, or [`EMPTY`].
    pub triangle: Vec<u32>,
    /// Per sample: perspective-correct barycentric coordinates of vertices 1 and 2.
    pub bary: Vec<[f32; 2]>,
}

impl Visibility {
    /// Rasterises `faces` seen by `camera` (z-buffer on inverse depth; triangles with a
    /// vertex behind the camera are skipped).
    pub fn rasterize(
        camera: &Camera,
        positions: &[DVec3],
        faces: &[[u32; 3]],
        width: usize,
        height: usize,
    ) -> Visibility {
        let n = width * height;
        let mut vis =
            Visibility { width, height, inv_depth: vec![0.0; n], triangle: vec![EMPTY; n], bary: vec![[0.0; 2]; n] };
        let projected: Vec<(f64, f64, f64)> = positions.iter().map(|&p| camera.project(p)).collect();
        for (t, f) in faces.iter().enumerate() {
            let [a, b, c] = [projected[f[0] as usize], projected[f[1] as usize], projected[f[2] as usize]];
            if a.2 <= 1e-9 || b.2 <= 1e-9 || c.2 <= 1e-9 {
                continue;
            }
            let area = (b.0 - a.0) * (c.1 - a.1) - (b.1 - a.1) * (c.0 - a.0);
            if area.abs() < 1e-12 || !area.is_finite() {
                continue;
            }
            let x0 = a.0.min(b.0).min(c.0).floor().max(0.0) as usize;
            let y0 = a.1.min(b.1).min(c.1).floor().max(0.0) as usize;
            let x1 = (a.0.max(b.0).max(c.0).ceil() as i64).min(width as i64 - 1);
            let y1 = (a.1.max(b.1).max(c.1).ceil() as i64).min(height as i64 - 1);
            if x1 < x0 as i64 || y1 < y0 as i64 {
                continue;
            }
            let (iza, izb, izc) = (1.0 / a.2, 1.0 / b.2, 1.0 / c.2);
            for y in y0..=y1 as usize {
                let py = y as f64 + 0.5;
                for x in x0..=x1 as usize {
                    let px = x as f64 + 0.5;
                    // Screen-space barycentric coordinates from edge functions.
                    let l1 = ((px - a.0) * (c.1 - a.1) - (py - a.1) * (c.0 - a.0)) / area;
                    let l2 = ((b.0 - a.0) * (py - a.1) - (b.1 - a.1) * (px - a.0)) / area;
                    let l0 = 1.0 - l1 - l2;
                    if l0 < 0.0 || l1 < 0.0 || l2 < 0.0 {
                        continue;
                    }
                    // Inverse depth is affine in screen space; attributes are affine after
                    // division by depth (perspective-correct interpolation).
                    let (w0, w1, w2) = (l0 * iza, l1 * izb, l2 * izc);
                    let iz = w0 + w1 + w2;
                    let k = y * width + x;
                    if iz as f32 > vis.inv_depth[k] {
                        vis.inv_depth[k] = iz as f32;
                        vis.triangle[k] = t as u32;
                        vis.bary[k] = [(w1 / iz) as f32, (w2 / iz) as f32];
                    }
                }
            }
        }
        vis
    }
}

/// An RGB frame of `f32` colours, for drawing before the downsample.
pub struct Frame {
    /// Width in samples.
    pub width: usize,
    /// Height in samples.
    pub height: usize,
    /// Per sample: linear RGB in `[0, 1]`, rows top to bottom.
    pub rgb: Vec<[f32; 3]>,
}

impl Frame {
    /// Draws the polyline `points` as a line `width` samples wide in `colour`, hidden where the
    /// surface in `vis` is nearer than the line by more than `depth_slack` (relative).
    pub fn polyline(
        &mut self,
        camera: &Camera,
        vis: &Visibility,
        points: &[DVec3],
        width: f64,
        colour: [f32; 3],
        depth_slack: f64,
    ) {
        let half = 0.5 * width;
        for w in points.windows(2) {
            let (a, b) = (camera.project(w[0]), camera.project(w[1]));
            if a.2 <= 1e-9 || b.2 <= 1e-9 {
                continue;
            }
            let (dx, dy) = (b.0 - a.0, b.1 - a.1);
            let len2 = dx * dx + dy * dy;
            let x0 = (a.0.min(b.0) - half).floor().max(0.0) as i64;
            let y0 = (a.1.min(b.1) - half).floor().max(0.0) as i64;
            let x1 = ((a.0.max(b.0) + half).ceil() as i64).min(self.width as i64 - 1);
            let y1 = ((a.1.max(b.1) + half).ceil() as i64).min(self.height as i64 - 1);
            for y in y0..=y1 {
                let py = y as f64 + 0.5;
                for x in x0..=x1 {
                    let px = x as f64 + 0.5;
                    let t = if len2 > 0.0 { (((px - a.0) * dx + (py - a.1) * dy) / len2).clamp(0.0, 1.0) } else { 0.0 };
                    let (qx, qy) = (a.0 + t * dx, a.1 + t * dy);
                    if (px - qx).powi(2) + (py - qy).powi(2) > half * half {
                        continue;
                    }
                    let k = y as usize * self.width + x as usize;
                    // Inverse depth along the projected segment is affine in t.
                    let iz = (1.0 - t) / a.2 + t / b.2;
                    if (vis.inv_depth[k] as f64) > iz * (1.0 + depth_slack) {
                        continue;
                    }
                    self.rgb[k] = colour;
                }
            }
        }
    }

    /// Averages `factor × factor` blocks into 8-bit sRGB (the anti-aliasing filter).
    pub fn downsample(&self, factor: usize) -> (usize, usize, Vec<u8>) {
        let (w, h) = (self.width / factor, self.height / factor);
        let mut out = vec![0u8; w * h * 3];
        let norm = 1.0 / (factor * factor) as f32;
        for y in 0..h {
            for x in 0..w {
                let mut acc = [0.0f32; 3];
                for sy in 0..factor {
                    let row = (y * factor + sy) * self.width;
                    for sx in 0..factor {
                        let c = self.rgb[row + x * factor + sx];
                        acc[0] += c[0];
                        acc[1] += c[1];
                        acc[2] += c[2];
                    }
                }
                for ch in 0..3 {
                    out[(y * w + x) * 3 + ch] = (acc[ch] * norm * 255.0 + 0.5).clamp(0.0, 255.0) as u8;
                }
            }
        }
        (w, h, out)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_target_projects_to_the_centre_and_up_is_up() {
        let cam = Camera::framing(DVec3::ZERO, 1.0, View::default(), 200, 100);
        let (x, y, z) = cam.project(DVec3::ZERO);
        assert!((x - 100.0).abs() < 1e-9 && (y - 50.0).abs() < 1e-9 && z > 0.0);
        let (_, y_up, _) = cam.project(DVec3::new(0.0, 0.0, 0.5));
        assert!(y_up < 50.0, "+z is drawn above the centre");
    }

    #[test]
    fn nearer_triangle_wins() {
        let cam = Camera::framing(DVec3::ZERO, 1.0, View { azimuth: 0.0, elevation: 0.0, zoom: 1.0 }, 64, 64);
        // Two squares facing +x: the one at x = 0.5 is nearer to an eye on +x.
        let p = |x: f64, y: f64, z: f64| DVec3::new(x, y, z);
        let positions = vec![
            p(0.0, -1.0, -1.0),
            p(0.0, 1.0, -1.0),
            p(0.0, 1.0, 1.0),
            p(0.5, -0.2, -0.2),
            p(0.5, 0.2, -0.2),
            p(0.5, 0.2, 0.2),
        ];
        let faces = vec![[0, 1, 2], [3, 4, 5]];
        let vis = Visibility::rasterize(&cam, &positions, &faces, 64, 64);
        let counts = [0u32, 1].map(|t| vis.triangle.iter().filter(|&&v| v == t).count());
        assert!(counts[0] > 0 && counts[1] > 0);
        // The near triangle lies in front of the far one: drawn alone, the far one covers
        // more samples than it keeps when the near one hides part of it.
        let alone = Visibility::rasterize(&cam, &positions, &faces[..1], 64, 64);
        let far_alone = alone.triangle.iter().filter(|&&v| v == 0).count();
        assert!(counts[0] < far_alone);
        // Drawing order does not matter.
        let swapped = Visibility::rasterize(&cam, &positions, &[faces[1], faces[0]], 64, 64);
        assert_eq!(swapped.triangle.iter().filter(|&&v| v == 0).count(), counts[1]);
    }
}
