//! The artist parameters of a Cauchy constraint (\[A11\] §4.4, eq. 3): orientation, sharpness and
//! stretch, turned into ghost vertex positions
//! `g₁ = u + O Rᵢ (1 + s/‖u − vᵢ‖)(u − vᵢ)` (with a dimensionless stretch, see below).
//!
//! - `O` rotates the initial domain's normal onto the orientation `n` (the average surface
//!   normal at `u`). When no initial normal is known (curve networks in 3D), `O` is the smallest
//!   rotation that brings the edge `u − vᵢ` into the plane `⊥ n`.
//! - `Rᵢ` rotates by the sharpness `θ` about the per-side axis `rᵢ = n × (vᵢ − u)` for a point
//!   constraint, or the curve tangent `±d` with the sign of `rᵢ · d` for a curve constraint (so
//!   that the two sides rotate in opposite directions). `θ > 0` lifts the ghosts towards `+n`:
//!   both sides fall away from the constraint, a ridge (convex towards `n`); `θ = 45°` makes a
//!   right-angled crease or cone; `θ < 0` a valley.
//! - `s` stretches the ghost edge. \[A11\] eq. 3 adds the length `s` (the factor `1 + s/‖u − vᵢ‖`),
//!   which with its unit micro-Laplacian weight moves the ghost by `s` at any resolution. With
//!   the consistent weight of [`super::system::MicroWeight`] the tangent's magnitude is
//!   `‖g₁ − u‖/‖u − vᵢ‖`, so we take `s` dimensionless, `g₁ = u + O Rᵢ (1 + s)(u − vᵢ)`: the
//!   tangent is `1 + s` times longer at any resolution (the Hermite tangent magnitude).
//!
//! Higher ghosts (`k = 3`) continue the line: `g_m = u + m (g₁ − u)` (zero second difference
//! along the ghost line; \[A11\] leaves their parameters to separate per-order values).

use super::system::System;
use crate::geom::DVec3;
use glam::DQuat;

/// The parameters of one Cauchy constraint vertex.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CauchyParams {
    /// Orientation: the average unit surface normal at the vertex.
    pub orientation: DVec3,
    /// Normal of the initial (planar) domain at the vertex, when there is one.
    pub initial_normal: Option<DVec3>,
    /// Sharpness `θ`, radians.
    pub sharpness: f64,
    /// Stretch `s`, dimensionless: the tangent magnitude is multiplied by `1 + s`.
    pub stretch: f64,
    /// Unit tangent of the constraint curve (`None`: an isolated point constraint).
    pub tangent: Option<DVec3>,
}

impl CauchyParams {
    /// Orientation only: flat (`θ = 0`), no stretch, point-type axis.
    pub fn oriented(orientation: DVec3) -> Self {
        CauchyParams { orientation, initial_normal: None, sharpness: 0.0, stretch: 0.0, tangent: None }
    }

    /// The first ghost's offset `g₁ − u` for the edge `e = u − v` (\[A11\] eq. 3).
    pub fn ghost_offset(&self, e: DVec3) -> DVec3 {
        let len = e.length();
        if len == 0.0 {
            return DVec3::ZERO;
        }
        let n = self.orientation.normalize_or_zero();
        // O: the domain normal onto n, or the edge into the tangent plane ⊥ n.
        let mut d = match self.initial_normal {
            Some(n0) if n != DVec3::ZERO => DQuat::from_rotation_arc(n0.normalize(), n) * e,
            _ => e,
        };
        if n != DVec3::ZERO {
            let t = d - d.dot(n) * n;
            if t.length() > 1e-9 * len {
                d = t.normalize() * len;
            }
        }
        // Rᵢ: sharpness about the per-side axis.
        if self.sharpness != 0.0 && n != DVec3::ZERO {
            let mut r = n.cross(-d).normalize_or_zero();
            if let Some(t) = self.tangent {
                let t = t.normalize_or_zero();
                if t != DVec3::ZERO {
                    r = if r.dot(t) < 0.0 { -t } else { t };
                }
            }
            if r != DVec3::ZERO {
                d = DQuat::from_axis_angle(r, self.sharpness) * d;
            }
        }
        d * (1.0 + self.stretch)
    }
}

/// Positions of all ghosts of `system`: `edge_positions` give the edges `u − v` (the initial
/// domain, or the current surface), `params[u]` the parameters of each Cauchy vertex `u`
/// (`None`: the reflection `g₁ = 2u − v` of \[A11\] Fig. 3).
pub fn ghost_positions(system: &System, edge_positions: &[DVec3], params: &[Option<CauchyParams>]) -> Vec<DVec3> {
    system
        .ghosts
        .iter()
        .map(|g| {
            let (u, v) = (edge_positions[g.vertex as usize], edge_positions[g.source as usize]);
            let e = u - v;
            let off = match params[g.vertex as usize] {
                Some(p) => p.ghost_offset(e),
                None => e,
            };
            u + g.number as f64 * off
        })
        .collect()
}
