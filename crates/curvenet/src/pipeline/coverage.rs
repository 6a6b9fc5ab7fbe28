//! How much of the input the surface passes near: the check that a run which left strokes out
//! (dangling, duplicates, curves that bound no patch) says so, and refuses a surface that
//! misses most of the sketch (docs/design.md §14).

use crate::error::{Error, Result, Warning};
use crate::geom::distance::MeshDistance;
use crate::geom::mesh::Mesh;
use crate::network::{curve_label, Network};

/// A stroke point counts as on the surface within this fraction of the bounding-box diagonal.
pub const NEAR: f64 = 0.01;
/// A surface near less than this fraction of the stroke length is an error.
pub const MIN_COVERAGE: f64 = 0.5;
/// A curve near the surface over less than this fraction of its length is named as left out.
const CURVE_LEFT_OUT: f64 = 0.5;

/// The fraction of the total length of `network`'s curves within [`NEAR`] × its diagonal of
/// `mesh`, and per curve.
pub fn stroke_coverage(mesh: &Mesh, network: &Network) -> (f64, Vec<f64>) {
    let tol = NEAR * network.bounding_box().diagonal();
    let bvh = MeshDistance::new(&mesh.positions, &mesh.faces);
    let (mut near_total, mut total) = (0.0, 0.0);
    let mut per_curve = Vec::with_capacity(network.curves.len());
    for c in &network.curves {
        let n = c.points.len();
        let m = if c.closed { n } else { n.saturating_sub(1) };
        let (mut near, mut len) = (0.0, 0.0);
        for i in 0..m {
            let (a, b) = (c.points[i], c.points[(i + 1) % n]);
            let l = a.distance(b);
            let pieces = ((l / tol).ceil() as usize).clamp(1, 1000);
            for k in 0..pieces {
                let p = a.lerp(b, (k as f64 + 0.5) / pieces as f64);
                if bvh.closest(p).0 <= tol {
                    near += l / pieces as f64;
                }
            }
            len += l;
        }
        per_curve.push(if len > 0.0 { near / len } else { 1.0 });
        near_total += near;
        total += len;
    }
    (if total > 0.0 { near_total / total } else { 1.0 }, per_curve)
}

/// Checks the coverage of `network` (the input as given) by `mesh`: an error below
/// [`MIN_COVERAGE`], a warning naming the curves left out otherwise. Returns the coverage.
pub fn check_coverage(mesh: &Mesh, network: &Network, warnings: &mut Vec<Warning>) -> Result<f64> {
    let (all, per_curve) = stroke_coverage(mesh, network);
    let out: Vec<usize> = (0..per_curve.len()).filter(|&c| per_curve[c] < CURVE_LEFT_OUT).collect();
    if out.is_empty() {
        return Ok(all);
    }
    let names: Vec<String> = out.iter().take(8).map(|&c| curve_label(&network.curves, c)).collect();
    let more = if out.len() > names.len() { format!(" and {} more", out.len() - names.len()) } else { String::new() };
    let text = format!(
        "the surface passes near {:.0} % of the strokes' length (within {:.0} % of the bounding-box diagonal); {} of \
         {} curves are left out (mostly or wholly): {}{more}",
        100.0 * all,
        100.0 * NEAR,
        out.len(),
        per_curve.len(),
        names.join(", ")
    );
    if all < MIN_COVERAGE {
        return Err(Error::topology(format!(
            "{text}. A surface that misses most of the sketch is not written: the curves there could not be closed \
             into patches (strokes that do not meet: a larger `gap`; or curves that bound no 2-manifold)"
        ))
        .curve(out[0]));
    }
    warnings.push(Warning::new(text).curve(out[0]));
    Ok(all)
}
