//! Edits of a network for interactive use: turning the normals of one curve about its
//! tangents (\[CG\] Fig. 1: the same two circles give a cylinder, a barrel or a bottleneck
//! depending on how their normals tilt).

use crate::error::{Error, Result};
use crate::network::{curve_label, Network};

/// `network` with the normals of curve `curve` rotated by `degrees` about the curve's unit
/// tangent at each sample (central differences; one-sided at the ends of an open curve), by
/// Rodrigues' formula `n' = n cos θ + (t × n) sin θ + t (t · n)(1 − cos θ)`.
pub fn rotate_normals(network: &Network, curve: usize, degrees: f64) -> Result<Network> {
    let Some(c) = network.curves.get(curve) else {
        return Err(Error::usage(format!(
            "curve {curve} does not exist: the network has {} curves",
            network.curves.len()
        )));
    };
    if !degrees.is_finite() {
        return Err(Error::usage(format!("rotation angle {degrees} is not a number")));
    }
    let n = c.points.len();
    if !c.has_normals() {
        return Err(Error::input(format!(
            "{} has no normals to turn (they are inferred when it is surfaced; infer them first: curvenet normals)",
            curve_label(&network.curves, curve)
        )));
    }
    if n < 2 || c.normals.len() != n {
        return Err(Error::input(format!(
            "{} has too few samples to have a tangent",
            curve_label(&network.curves, curve)
        )));
    }
    let (s, co) = degrees.to_radians().sin_cos();
    let mut out = network.clone();
    for i in 0..n {
        let (prev, next) =
            if c.closed { ((i + n - 1) % n, (i + 1) % n) } else { (i.saturating_sub(1), (i + 1).min(n - 1)) };
        let t = (c.points[next] - c.points[prev]).normalize_or_zero();
        let v = c.normals[i];
        out.curves[curve].normals[i] = v * co + t.cross(v) * s + t * t.dot(v) * (1.0 - co);
    }
    Ok(out)
}

#[cfg(test)]
#[path = "tests/edit.rs"]
mod tests;
