//! The input model: a network of 3D curves sampled with positions and surface normals
//! ([CG] §3: "a discrete sample of positions pᵢ together with the unit surface normals nᵢ").
//!
//! A [`Network`] is what the readers in [`crate::io`] produce and what the examples in
//! [`crate::examples`] build. [`Network::validated`] checks it at the door and returns a
//! cleaned copy (unit normals, no repeated samples) that the pipeline works on.

use crate::error::{Error, Result, Warning};
use crate::geom::{fmt_point, Aabb, DVec3};

/// One sampled curve.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Curve {
    /// Optional name, used in messages.
    pub name: Option<String>,
    /// Sample positions, in order along the curve (≥ 2; ≥ 3 when `closed`).
    pub points: Vec<DVec3>,
    /// Surface normals at the samples, same length as `points`; non-zero, need not be unit.
    /// They point to the outside of the surface (the side the user sees).
    pub normals: Vec<DVec3>,
    /// The last sample connects back to the first.
    pub closed: bool,
    /// The curve bounds the surface: it has a patch on one side only.
    pub boundary: bool,
}

/// A curve network: curves that meet at nodes and bound the patches of the surface.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Network {
    pub curves: Vec<Curve>,
    /// Snapping tolerance (a distance): two curves closer than this meet at a node. `None`
    /// uses [`Network::DEFAULT_SNAP_RELATIVE`] times the bounding-box diagonal.
    pub snap: Option<f64>,
}

/// Human-readable name of curve `index` for messages: `curve 3 ("equator")`.
pub fn curve_label(curves: &[Curve], index: usize) -> String {
    match curves.get(index).and_then(|c| c.name.as_deref()) {
        Some(name) => format!("curve {index} (\"{name}\")"),
        None => format!("curve {index}"),
    }
}

impl Network {
    /// Default snapping tolerance relative to the bounding-box diagonal.
    pub const DEFAULT_SNAP_RELATIVE: f64 = 1e-3;
    /// Samples closer than this (relative to the bounding-box diagonal) are duplicates.
    pub const DUPLICATE_RELATIVE: f64 = 1e-9;

    /// Bounding box of all samples.
    pub fn bounding_box(&self) -> Aabb {
        Aabb::of(self.curves.iter().flat_map(|c| c.points.iter().copied()))
    }

    /// The snapping tolerance in effect: `snap` or the relative default.
    pub fn snap_tolerance(&self) -> f64 {
        self.snap.unwrap_or_else(|| Self::DEFAULT_SNAP_RELATIVE * self.bounding_box().diagonal())
    }

    /// Total number of samples.
    pub fn num_samples(&self) -> usize {
        self.curves.iter().map(|c| c.points.len()).sum()
    }

    /// Checks the network and returns a cleaned copy: unit normals, consecutive duplicate
    /// samples merged (each merge is reported as a warning), a closed curve's repeated first
    /// sample dropped.
    ///
    /// Errors ([`Error::Input`]), each naming the curve and sample: no curves; `points` and
    /// `normals` of different lengths; a non-finite coordinate; a zero or non-normalisable
    /// normal; fewer than 2 distinct samples (3 for a closed curve); all samples coincident;
    /// a snapping tolerance that is not a positive number.
    pub fn validated(&self) -> Result<(Network, Vec<Warning>)> {
        let mut warnings = Vec::new();
        if self.curves.is_empty() {
            return Err(Error::Input(
                "the network has no curves: give at least one curve with points and normals".into(),
            ));
        }
        for (ci, c) in self.curves.iter().enumerate() {
            let label = || curve_label(&self.curves, ci);
            if c.points.len() != c.normals.len() {
                return Err(Error::Input(format!(
                    "{}: {} points but {} normals; every point needs one normal, in the same order",
                    label(),
                    c.points.len(),
                    c.normals.len()
                )));
            }
            let need = if c.closed { 3 } else { 2 };
            if c.points.len() < need {
                return Err(Error::Input(format!(
                    "{} has {} sample(s); a{} curve needs at least {need}",
                    label(),
                    c.points.len(),
                    if c.closed { " closed" } else { "n open" }
                )));
            }
            for (si, p) in c.points.iter().enumerate() {
                if !p.is_finite() {
                    return Err(Error::Input(format!(
                        "{}, sample {si}: point {} has a non-finite coordinate",
                        label(),
                        fmt_point(*p)
                    )));
                }
            }
            for (si, n) in c.normals.iter().enumerate() {
                let u = n.normalize_or_zero();
                if !n.is_finite() || u == DVec3::ZERO || !u.is_finite() {
                    return Err(Error::Input(format!(
                        "{}, sample {si}: normal {} cannot be normalised; every sample needs a \
                         finite, non-zero normal pointing to the outside of the surface",
                        label(),
                        fmt_point(*n)
                    )));
                }
            }
        }
        if let Some(s) = self.snap {
            if !(s.is_finite() && s > 0.0) {
                return Err(Error::Input(format!(
                    "snapping tolerance {s} is not a positive number; give a distance such as 1e-6 or leave it out"
                )));
            }
        }
        let diag = self.bounding_box().diagonal();
        if !(diag > 0.0) || !diag.is_finite() {
            return Err(Error::Input(
                "all samples of the network coincide (or its extent overflows): there is nothing to surface".into(),
            ));
        }
        let dup_tol = Self::DUPLICATE_RELATIVE * diag;

        let mut curves = Vec::with_capacity(self.curves.len());
        for (ci, c) in self.curves.iter().enumerate() {
            let label = curve_label(&self.curves, ci);
            let mut points: Vec<DVec3> = Vec::with_capacity(c.points.len());
            let mut normals: Vec<DVec3> = Vec::with_capacity(c.points.len());
            let mut merged = Vec::new();
            for (si, (p, n)) in c.points.iter().zip(&c.normals).enumerate() {
                if let Some(last) = points.last() {
                    if last.distance(*p) <= dup_tol {
                        merged.push(si);
                        continue;
                    }
                }
                points.push(*p);
                normals.push(n.normalize());
            }
            if !merged.is_empty() {
                let list: Vec<String> = merged.iter().take(5).map(|s| s.to_string()).collect();
                warnings.push(Warning(format!(
                    "{label}: {} sample(s) repeated the previous one and were merged (sample {}{})",
                    merged.len(),
                    list.join(", "),
                    if merged.len() > 5 { ", …" } else { "" }
                )));
            }
            if c.closed && points.len() > 1 && points[0].distance(points[points.len() - 1]) <= dup_tol {
                points.pop();
                normals.pop();
                warnings.push(Warning(format!(
                    "{label}: closed curve repeats its first sample at the end; the repeat was dropped"
                )));
            }
            let need = if c.closed { 3 } else { 2 };
            if points.len() < need {
                return Err(Error::Input(format!(
                    "{label} has {} distinct sample(s); a{} curve needs at least {need}",
                    points.len(),
                    if c.closed { " closed" } else { "n open" }
                )));
            }
            curves.push(Curve { name: c.name.clone(), points, normals, closed: c.closed, boundary: c.boundary });
        }
        Ok((Network { curves, snap: self.snap }, warnings))
    }
}

#[cfg(test)]
#[path = "tests/network.rs"]
mod tests;
