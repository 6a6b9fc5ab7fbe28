//! The input model: a network of 3D curves sampled with positions and surface normals
//! (\[CG\] §3: "a discrete sample of positions pᵢ together with the unit surface normals nᵢ").
//!
//! A [`Network`] is what the readers in [`crate::io`] produce and what the examples in
//! [`crate::network::examples`] build. [`Network::validated`] checks it at the door and returns a
//! cleaned copy (unit normals, no repeated samples) that the pipeline works on.

pub mod edit;
pub mod examples;

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
    /// They point to the outside of the surface (the side the user sees). **Empty: unknown** —
    /// the pipeline infers them (`topology::orient`, docs/design.md §12).
    pub normals: Vec<DVec3>,
    /// **Crease** normals (docs/design.md §13): the surface's normal on the *right* of the
    /// curve, same length as `points`. Walking along the curve in sample order with `normals`
    /// as "up", the surface that `normals` belongs to lies on the left and the one of
    /// `normals_right` on the right; the surface folds along the curve (a G0 seam) wherever
    /// the two differ by more than [`Network::SMOOTH_CREASE_DEGREES`]. **Empty: a smooth
    /// curve** (one normal for both sides).
    pub normals_right: Vec<DVec3>,
    /// The last sample connects back to the first.
    pub closed: bool,
    /// The curve bounds the surface: it has a patch on one side only.
    pub boundary: bool,
}

/// A curve network: curves that meet at nodes and bound the patches of the surface.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Network {
    /// The curves.
    pub curves: Vec<Curve>,
    /// Snapping tolerance (a distance): two curves closer than this meet at a node. `None`
    /// uses [`Network::DEFAULT_SNAP_RELATIVE`] times the bounding-box diagonal.
    pub snap: Option<f64>,
    /// The cycles that bound the patches, chosen beforehand (written by `curvenet normals` from
    /// the global cycle search, or edited by a person: docs/design.md §15). `None`: the
    /// pipeline finds them. A network with cycles is taken as it is (no consolidation): the
    /// cycles name its segments.
    pub cycles: Option<Vec<CycleKey>>,
}

/// A patch's cycle by its segments' places on the curves: per segment `(curve, first sample,
/// last sample, forward)` — the stretch of curve `curve` between the nodes at samples `first`
/// and `last`, run along in sample order (`forward`) or against it. The samples are those of
/// the curve as node finding splits it (validated, with a sample inserted where another curve
/// crosses between two samples; `last` equals the number of samples where a segment ends at
/// sample 0 of a closed curve), so cycles are written by `curvenet cycles` and edited by
/// deleting or copying them, not by counting samples in the file. Places survive a new node
/// finding on the same curves, which numbers the segments anew.
pub type CycleKey = Vec<(usize, usize, usize, bool)>;

impl Curve {
    /// The curve carries its normals (an empty `normals` means unknown: they are inferred).
    pub fn has_normals(&self) -> bool {
        !self.normals.is_empty()
    }

    /// The curve is a crease: it carries [`Curve::normals_right`].
    pub fn is_crease(&self) -> bool {
        !self.normals_right.is_empty()
    }

    /// The normal of a crease's both sides together at sample `i` (their normalised mean; the
    /// left one where they cancel): the one normal the smooth stages and baselines use.
    pub fn mean_normal(&self, i: usize) -> DVec3 {
        let n = self.normals[i];
        match self.normals_right.get(i) {
            Some(r) => {
                let m = (n.normalize_or_zero() + r.normalize_or_zero()).normalize_or_zero();
                if m == DVec3::ZERO {
                    n
                } else {
                    m
                }
            }
            None => n,
        }
    }

    /// The normal of the surface on the right of sample `i` (the left one, `normals[i]`, on a
    /// smooth curve).
    pub fn normal_right(&self, i: usize) -> DVec3 {
        self.normals_right.get(i).copied().unwrap_or(self.normals[i])
    }
}

/// Human-readable name of curve `index` for messages: `curve "equator"` for a curve the input
/// names, `curve 3` for one it does not. A curve whose name no other curve has is shown by its
/// name alone, without its index: the index shifts when curves before it are left out, merged
/// or split, the name does not, so a run's messages name it one way and the name is the one in
/// the input file. A name several curves share (an OBJ group of many polylines) keeps the index
/// beside it: `curve 3 ("rim")`.
/// Control characters and escape sequences in a name are shown escaped (`\u{1b}`), so that a
/// file's text never drives the terminal a message is printed on. A curve named by its place in
/// the input ([`position_name`]: `curve 42`, `curve 42 part 2`, given when curves are left out
/// or split, so that later messages keep the input's numbers) is shown by that name alone:
/// one number names one curve in every message of a run (issue 33).
pub fn curve_label(curves: &[Curve], index: usize) -> String {
    let name = curves.get(index).and_then(|c| c.name.as_deref());
    let shared = name.is_some_and(|n| curves.iter().filter(|c| c.name.as_deref() == Some(n)).nth(1).is_some());
    label_of(index, name, shared)
}

/// [`curve_label`] of every curve, the names counted once (linear in the curves, where a
/// label each would be quadratic).
pub fn curve_labels(curves: &[Curve]) -> Vec<String> {
    let mut count: std::collections::HashMap<&str, usize> = std::collections::HashMap::new();
    for n in curves.iter().filter_map(|c| c.name.as_deref()) {
        *count.entry(n).or_default() += 1;
    }
    curves
        .iter()
        .enumerate()
        .map(|(i, c)| {
            let name = c.name.as_deref();
            label_of(i, name, name.is_some_and(|n| count.get(n).copied().unwrap_or(0) > 1))
        })
        .collect()
}

/// The label of curve `index` named `name`, a name `shared` with other curves or not.
fn label_of(index: usize, name: Option<&str>, shared: bool) -> String {
    match name {
        Some(name) if is_position_name(name) => name.to_string(),
        Some(name) => {
            let shown: String = name
                .chars()
                .map(|ch| if ch.is_control() { ch.escape_unicode().to_string() } else { ch.to_string() })
                .collect();
            if shared {
                format!("curve {index} (\"{shown}\")")
            } else {
                format!("curve \"{shown}\"")
            }
        }
        None => format!("curve {index}"),
    }
}

/// The name of input curve `index` by its place: `curve 42` ([`curve_label`]).
pub fn position_name(index: usize) -> String {
    format!("curve {index}")
}

/// The name of an unnamed curve of an OBJ file by the line of its first `l` statement:
/// `curve at line 1234` ([`curve_label`] shows it alone, as a [`position_name`]).
pub fn line_name(line: usize) -> String {
    format!("curve at line {line}")
}

/// Whether `name` is a [`position_name`] or a [`line_name`], or one of their parts (`curve 42
/// part 2`).
fn is_position_name(name: &str) -> bool {
    let Some(rest) = name.strip_prefix("curve ") else { return false };
    let rest = rest.strip_prefix("at line ").unwrap_or(rest);
    let mut words = rest.split(" part ");
    words.all(|w| !w.is_empty() && w.bytes().all(|b| b.is_ascii_digit()))
}

impl Network {
    /// Default snapping tolerance relative to the bounding-box diagonal.
    pub const DEFAULT_SNAP_RELATIVE: f64 = 1e-3;
    /// Default snapping tolerance relative to the mean sample spacing.
    pub const DEFAULT_SNAP_SPACING: f64 = 0.1;
    /// Samples closer than this (relative to the bounding-box diagonal) are duplicates.
    pub const DUPLICATE_RELATIVE: f64 = 1e-9;
    /// Largest supported coordinate magnitude and bounding-box diagonal, and (its inverse) the
    /// smallest supported diagonal. The pipeline is scale invariant, but it forms squared
    /// lengths, areas and the fourth power of a patch size (the short paper's `ω₁ = W / s⁴`):
    /// within `1e±60` none of them over- or underflows an `f64`.
    pub const MAX_EXTENT: f64 = 1e60;
    /// Largest supported ratio of the distance from the origin to the bounding-box diagonal:
    /// beyond it an `f64` keeps fewer than about 7 significant digits of the shape.
    pub const MAX_OFFSET_RATIO: f64 = 1e9;
    /// A normal within this cosine of the curve's direction on both sides of its sample
    /// (about 11°) is tangent to the curve: it defines no side of the surface.
    pub const TANGENT_NORMAL_COSINE: f64 = 0.98;
    /// Consecutive samples whose normals are more than 120° apart (cosine below this; the
    /// ends of open curves excepted) are an input error: normals that flip sign along a curve (a surface turns its normal smoothly;
    /// a network sampled so coarsely that its normal turns by 120° between two samples does
    /// not define the surface between them either).
    pub const FLIPPED_NORMAL_COSINE: f64 = -0.5;
    /// Where the two normals of a crease curve are closer than this angle (degrees), the
    /// surface is smooth across the curve (a crease may fade out along a curve).
    pub const SMOOTH_CREASE_DEGREES: f64 = 3.0;

    /// Bounding box of all samples.
    pub fn bounding_box(&self) -> Aabb {
        Aabb::of(self.curves.iter().flat_map(|c| c.points.iter().copied()))
    }

    /// The snapping tolerance in effect: `snap`, or the larger of
    /// [`Network::DEFAULT_SNAP_RELATIVE`] × the bounding-box diagonal and
    /// [`Network::DEFAULT_SNAP_SPACING`] × the mean sample spacing (sparsely sampled or noisy
    /// curves cross between samples at a distance that grows with the spacing).
    pub fn snap_tolerance(&self) -> f64 {
        self.snap.unwrap_or_else(|| {
            (Self::DEFAULT_SNAP_RELATIVE * self.bounding_box().diagonal())
                .max(Self::DEFAULT_SNAP_SPACING * self.mean_sample_spacing())
        })
    }

    /// Every curve carries its normals (nothing to infer).
    pub fn has_all_normals(&self) -> bool {
        self.curves.iter().all(Curve::has_normals)
    }

    /// Some curve is a crease ([`Curve::is_crease`]).
    pub fn has_creases(&self) -> bool {
        self.curves.iter().any(Curve::is_crease)
    }

    /// A copy with every curve's normals removed (unknown): test data for normal inference.
    pub fn without_normals(&self) -> Network {
        let mut out = self.clone();
        for c in &mut out.curves {
            c.normals.clear();
            c.normals_right.clear();
        }
        out
    }

    /// Total number of samples.
    pub fn num_samples(&self) -> usize {
        self.curves.iter().map(|c| c.points.len()).sum()
    }

    /// Mean distance between consecutive samples over all curves.
    pub fn mean_sample_spacing(&self) -> f64 {
        let (mut sum, mut count) = (0.0, 0usize);
        for c in &self.curves {
            let n = c.points.len();
            let m = if c.closed { n } else { n.saturating_sub(1) };
            for i in 0..m {
                sum += c.points[i].distance(c.points[(i + 1) % n]);
                count += 1;
            }
        }
        if count > 0 {
            sum / count as f64
        } else {
            0.0
        }
    }

    /// A copy with sensor-like noise (\[CG\] §4.5, Fig. 7): Gaussian noise of standard deviation
    /// `fraction × spacing` on the positions (`spacing` the mean sample spacing) and a
    /// Gaussian perturbation of standard deviation `fraction` on the unit normals, which are then
    /// re-normalised. Samples that coincide (crossings sampled by both curves) receive the same
    /// perturbation, so curves that met still meet. Deterministic for a given `seed`.
    pub fn perturbed(&self, fraction: f64, seed: u64) -> Network {
        let sigma = fraction * self.mean_sample_spacing();
        let mut rng = Rng::new(seed);
        let mut shared: std::collections::HashMap<[u64; 3], (DVec3, DVec3)> = std::collections::HashMap::new();
        let mut out = self.clone();
        for c in &mut out.curves {
            let known = c.has_normals();
            for (i, p) in c.points.iter_mut().enumerate() {
                // Key by position rounded to 1e-9 of the spacing, so coincident samples share it.
                // (+ 0.0 turns −0 into +0, so that both round to the same key.)
                let q = (*p / (1e-9 * sigma.max(f64::MIN_POSITIVE))).round() + DVec3::ZERO;
                let key = [q.x.to_bits(), q.y.to_bits(), q.z.to_bits()];
                let (dp, dn) =
                    *shared.entry(key).or_insert_with(|| (rng.gaussian3() * sigma, rng.gaussian3() * fraction));
                *p += dp;
                if known {
                    let right = c.normals_right.get_mut(i);
                    for n in std::iter::once(&mut c.normals[i]).chain(right) {
                        let m = n.normalize_or_zero() + dn;
                        *n = if m.length() > 1e-6 { m.normalize() } else { *n };
                    }
                }
            }
        }
        out
    }

    /// The per-sample checks of [`Network::validated`]: matching lengths, enough samples,
    /// finite coordinates, normalisable normals (both sides of a crease).
    fn check_samples(&self) -> Result<()> {
        for (ci, c) in self.curves.iter().enumerate() {
            let label = || curve_label(&self.curves, ci);
            if c.has_normals() && c.points.len() != c.normals.len() {
                return Err(Error::input(format!(
                    "{}: {} points but {} normals; give one per point in the same order, or none (inferred)",
                    label(),
                    c.points.len(),
                    c.normals.len()
                ))
                .curve(ci));
            }
            if c.is_crease() && (!c.has_normals() || c.normals_right.len() != c.points.len()) {
                return Err(Error::input(format!(
                    "{}: {} points, {} normals and {} normals_right; a crease needs both normals at every point, \
                     in the same order",
                    label(),
                    c.points.len(),
                    c.normals.len(),
                    c.normals_right.len()
                ))
                .curve(ci));
            }
            let need = if c.closed { 3 } else { 2 };
            if c.points.len() < need {
                return Err(Error::input(format!(
                    "{} has {} sample(s); a{} curve needs at least {need}",
                    label(),
                    c.points.len(),
                    if c.closed { " closed" } else { "n open" }
                ))
                .curve(ci));
            }
            for (si, p) in c.points.iter().enumerate() {
                if !p.is_finite() {
                    return Err(Error::input(format!(
                        "{}, sample {si}: point {} has a non-finite coordinate",
                        label(),
                        fmt_point(*p)
                    ))
                    .curve(ci)
                    .sample(si));
                }
            }
            let right = c.normals_right.iter().enumerate().map(|(si, n)| (si, n, "normals_right"));
            for (si, n, what) in c.normals.iter().enumerate().map(|(si, n)| (si, n, "normal")).chain(right) {
                let u = n.normalize_or_zero();
                if !n.is_finite() || u == DVec3::ZERO || !u.is_finite() {
                    return Err(Error::input(format!(
                        "{}, sample {si}: {what} {} cannot be normalised; every sample needs a \
                         finite, non-zero normal pointing to the outside of the surface",
                        label(),
                        fmt_point(*n)
                    ))
                    .curve(ci)
                    .sample(si));
                }
            }
        }
        Ok(())
    }

    /// Checks the network and returns a cleaned copy: unit normals (a curve without normals
    /// stays without: they are unknown), consecutive duplicate
    /// samples merged (each merge is reported as a warning), a closed curve's repeated first
    /// sample dropped.
    ///
    /// Errors ([`Error::Input`]), each naming the curve and sample: no curves; `points` and
    /// `normals` of different lengths; a non-finite coordinate; a zero or non-normalisable
    /// normal; fewer than 2 distinct samples (3 for a closed curve); all samples coincident;
    /// a snapping tolerance that is not a positive number; coordinates or an extent outside
    /// [`Network::MAX_EXTENT`]; a network far from the origin compared with its size
    /// ([`Network::MAX_OFFSET_RATIO`]); a normal tangent to its curve
    /// ([`Network::TANGENT_NORMAL_COSINE`]); normals that flip between consecutive samples
    /// ([`Network::FLIPPED_NORMAL_COSINE`]).
    pub fn validated(&self) -> Result<(Network, Vec<Warning>)> {
        let mut warnings = Vec::new();
        if self.curves.is_empty() {
            return Err(Error::input("the network has no curves: give at least one curve with points (and normals)"));
        }
        self.check_samples()?;
        if let Some(s) = self.snap {
            if !(s.is_finite() && s > 0.0) {
                return Err(Error::input(format!(
                    "snapping tolerance {s} is not a positive number; give a distance such as 1e-6 or leave it out"
                )));
            }
        }
        let bbox = self.bounding_box();
        // (The diagonal underflows to 0 for extents below 1e-154: test the spread itself.)
        let diag = bbox.diagonal().max((bbox.max - bbox.min).max_element());
        if !(diag > 0.0) {
            return Err(Error::input("all samples of the network coincide: there is nothing to surface"));
        }
        let far = bbox.min.abs().max(bbox.max.abs()).max_element();
        if !(far <= Self::MAX_EXTENT && (1.0 / Self::MAX_EXTENT..=Self::MAX_EXTENT).contains(&diag)) {
            return Err(Error::input(format!(
                "the network's coordinates (largest magnitude {far:.3e}, bounding-box diagonal {diag:.3e}) are \
                 outside the supported range [{:.0e}, {:.0e}]; rescale the network (the result scales with it)",
                1.0 / Self::MAX_EXTENT,
                Self::MAX_EXTENT
            )));
        }
        if far > Self::MAX_OFFSET_RATIO * diag {
            return Err(Error::input(format!(
                "the network lies {far:.3e} from the origin but is only {diag:.3e} across: too few significant \
                 digits are left of its shape; translate it towards the origin"
            )));
        }
        let dup_tol = Self::DUPLICATE_RELATIVE * diag;

        let mut curves = Vec::with_capacity(self.curves.len());
        let labels = curve_labels(&self.curves);
        for (ci, c) in self.curves.iter().enumerate() {
            let label = labels[ci].clone();
            let mut points: Vec<DVec3> = Vec::with_capacity(c.points.len());
            let mut normals: Vec<DVec3> = Vec::with_capacity(c.points.len());
            let mut normals_right: Vec<DVec3> = Vec::with_capacity(c.normals_right.len());
            let mut merged = Vec::new();
            // The input sample of each kept point (for the ids of errors).
            let mut input_sample: Vec<usize> = Vec::with_capacity(c.points.len());
            for (si, p) in c.points.iter().enumerate() {
                if let Some(last) = points.last() {
                    if last.distance(*p) <= dup_tol {
                        merged.push(si);
                        continue;
                    }
                }
                input_sample.push(si);
                points.push(*p);
                if let Some(n) = c.normals.get(si) {
                    normals.push(n.normalize());
                }
                if let Some(n) = c.normals_right.get(si) {
                    normals_right.push(n.normalize());
                }
            }
            if !merged.is_empty() {
                let list: Vec<String> = merged.iter().take(5).map(|s| s.to_string()).collect();
                warnings.push(
                    Warning::new(format!(
                        "{label}: {} sample(s) repeated the previous one and were merged (sample {}{})",
                        merged.len(),
                        list.join(", "),
                        if merged.len() > 5 { ", …" } else { "" }
                    ))
                    .curve(ci)
                    .sample(merged[0]),
                );
            }
            if c.closed && points.len() > 1 && points[0].distance(points[points.len() - 1]) <= dup_tol {
                points.pop();
                normals.truncate(points.len());
                normals_right.truncate(points.len());
                warnings.push(
                    Warning::new(format!(
                        "{label}: closed curve repeats its first sample at the end; the repeat was dropped"
                    ))
                    .curve(ci),
                );
            }
            let need = if c.closed { 3 } else { 2 };
            if points.len() < need {
                return Err(Error::input(format!(
                    "{label} has {} distinct sample(s); a{} curve needs at least {need}",
                    points.len(),
                    if c.closed { " closed" } else { "n open" }
                ))
                .curve(ci));
            }
            let tangent = |n: &[DVec3]| (!n.is_empty()).then(|| tangent_normal(&points, n, c.closed)).flatten();
            let bad = tangent(&normals).map(|si| (si, normals[si], "normal"));
            if let Some((si, n, what)) =
                bad.or_else(|| tangent(&normals_right).map(|si| (si, normals_right[si], "normals_right")))
            {
                let sample = input_sample[si];
                return Err(Error::input(format!(
                    "{label}, sample {sample}: {what} {} is tangent to the curve (within {:.0}° of its direction); \
                     normals must be across the curve, pointing to the outside of the surface",
                    fmt_point(n),
                    Self::TANGENT_NORMAL_COSINE.acos().to_degrees()
                ))
                .curve(ci)
                .sample(sample)
                .point(points[si]));
            }
            let flip = |n: &[DVec3]| flipped_normal(n, c.closed);
            let bad = flip(&normals)
                .map(|si| (si, "normal"))
                .or_else(|| flip(&normals_right).map(|si| (si, "normals_right")));
            if let Some((si, what)) = bad {
                let sample = input_sample[si];
                let list = if what == "normal" { &normals } else { &normals_right };
                let prev = list[if si > 0 { si - 1 } else { list.len() - 1 }];
                return Err(Error::input(format!(
                    "{label}, sample {sample}: {what} {} turns by {:.0}° from the previous sample's {}; normals must \
                     point to the same side of the surface all along a curve (a sign flip, as from a sensor axis read \
                     the wrong way?)",
                    fmt_point(list[si]),
                    list[si].angle_between(prev).to_degrees(),
                    fmt_point(prev)
                ))
                .curve(ci)
                .sample(sample)
                .point(points[si]));
            }
            curves.push(Curve {
                name: c.name.clone(),
                points,
                normals,
                normals_right,
                closed: c.closed,
                boundary: c.boundary,
            });
        }
        Ok((Network { curves, snap: self.snap, cycles: self.cycles.clone() }, warnings))
    }
}

/// The first sample whose unit normal lies within [`Network::TANGENT_NORMAL_COSINE`] of the
/// curve's direction on both sides of it (on the one side at the ends of an open curve).
fn tangent_normal(points: &[DVec3], normals: &[DVec3], closed: bool) -> Option<usize> {
    let n = points.len();
    let chord = |i: usize, j: usize| (points[j] - points[i]).normalize_or_zero();
    (0..n).find(|&i| {
        let before = if i > 0 {
            Some(chord(i - 1, i))
        } else if closed {
            Some(chord(n - 1, 0))
        } else {
            None
        };
        let after = if i + 1 < n {
            Some(chord(i, i + 1))
        } else if closed {
            Some(chord(n - 1, 0))
        } else {
            None
        };
        let along = |c: Option<DVec3>| c.is_none_or(|c| normals[i].dot(c).abs() > Network::TANGENT_NORMAL_COSINE);
        (before.is_some() || after.is_some()) && along(before) && along(after)
    })
}

/// The first sample whose unit normal turns by more than [`Network::FLIPPED_NORMAL_COSINE`]'s
/// angle from the previous sample's (around a closed curve, sample 0 from the last one): the
/// sign flips of inconsistent sensor data. The end samples of an open curve are left out (an
/// end may sit on a node whose normal a sketch's inference averages over the curves there).
fn flipped_normal(normals: &[DVec3], closed: bool) -> Option<usize> {
    let n = normals.len();
    let (start, end) = if closed { (0, n) } else { (2, n.saturating_sub(1)) };
    (start..end).find(|&i| normals[i].dot(normals[(i + n - 1) % n]) < Network::FLIPPED_NORMAL_COSINE)
}

/// A small deterministic generator (SplitMix64) with Gaussian samples (Box–Muller), so that
/// noisy test networks are reproducible without a dependency.
pub(crate) struct Rng(u64);

impl Rng {
    pub fn new(seed: u64) -> Self {
        Rng(seed ^ 0x9E37_79B9_7F4A_7C15)
    }

    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// Uniform in (0, 1).
    pub fn uniform(&mut self) -> f64 {
        ((self.next_u64() >> 11) as f64 + 0.5) / (1u64 << 53) as f64
    }

    pub fn gaussian(&mut self) -> f64 {
        let (u, v) = (self.uniform(), self.uniform());
        (-2.0 * u.ln()).sqrt() * (std::f64::consts::TAU * v).cos()
    }

    pub fn gaussian3(&mut self) -> DVec3 {
        DVec3::new(self.gaussian(), self.gaussian(), self.gaussian())
    }
}

#[cfg(test)]
#[path = "tests/network.rs"]
mod tests;
