//! Clean networks redrawn as a hand draws them (test data with a known truth for
//! [`crate::topology::consolidate`]): each curve cut into strokes that stop short of or overshoot
//! one another by up to a given gap, some drawn twice or retraced back over themselves, hooks at
//! some ends, uneven sample spacing. The curves' shape — hence the surface the strokes should
//! give — is unchanged: the truth of the clean network (an analytic surface, the mesh it was
//! sampled on) is the truth of the strokes.

use crate::geom::DVec3;
use crate::network::{Curve, Network, Rng};

/// The defects of [`as_drawn`], lengths relative to the network's bounding-box diagonal.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Drawn {
    /// Strokes per curve (each closed curve at least 2).
    pub strokes_per_curve: usize,
    /// Largest gap or overshoot at a stroke end (uniform in `[-gap, gap]`; negative: short).
    pub gap: f64,
    /// Mean distance between a stroke's samples (each spacing uniform in 0.4–1.6 of it).
    pub spacing: f64,
    /// Fraction of the strokes drawn twice (the second time `offset` away).
    pub duplicates: f64,
    /// Fraction of the strokes retraced back over their last 40 % (`offset` away).
    pub retraced: f64,
    /// Fraction of the stroke ends with a hook (a curl back of a third of the gap).
    pub hooks: f64,
    /// Distance between a stroke and its second drawing or retrace.
    pub offset: f64,
    /// Keep the curves' normals (when they have them).
    pub normals: bool,
}

impl Default for Drawn {
    fn default() -> Self {
        Drawn {
            strokes_per_curve: 3,
            gap: 0.01,
            spacing: 0.01,
            duplicates: 0.2,
            retraced: 0.1,
            hooks: 0.2,
            offset: 0.002,
            normals: true,
        }
    }
}

/// The curves of `network` redrawn as strokes with the defects `drawn` (deterministic in
/// `seed`); see the module documentation. The strokes carry no names and no boundary tags.
pub fn as_drawn(network: &Network, drawn: &Drawn, seed: u64) -> Network {
    let diag = network.bounding_box().diagonal();
    let mut rng = Rng::new(seed);
    let mut curves = Vec::new();
    for c in &network.curves {
        let path = Path::new(c);
        let k = if c.closed { drawn.strokes_per_curve.max(2) } else { drawn.strokes_per_curve.max(1) };
        let piece = path.length / k as f64;
        let start = if c.closed { rng.uniform() * path.length } else { 0.0 };
        let mut splits: Vec<f64> = (0..=k).map(|j| start + j as f64 * piece).collect();
        for split in splits.iter_mut().take(k).skip(1) {
            *split += (rng.uniform() - 0.5) * 0.3 * piece;
        }
        for j in 0..k {
            let (mut a, mut b) = (splits[j], splits[j + 1]);
            // Gaps and overshoots (open curves keep their own ends within their length).
            a -= (2.0 * rng.uniform() - 1.0) * drawn.gap * diag;
            b += (2.0 * rng.uniform() - 1.0) * drawn.gap * diag;
            if !c.closed {
                a = a.clamp(0.0, path.length);
                b = b.clamp(0.0, path.length);
            }
            if b - a < 2.0 * drawn.spacing * diag {
                continue;
            }
            let mut stroke = path.stroke(a, b, drawn.spacing * diag, &mut rng);
            for end in 0..2 {
                if rng.uniform() < drawn.hooks {
                    hook(&mut stroke, end, drawn.gap * diag / 3.0);
                }
            }
            if rng.uniform() < drawn.retraced {
                let back = path.stroke(a + 0.6 * (b - a), b, drawn.spacing * diag, &mut rng);
                let shift = path.side(b) * drawn.offset * diag;
                stroke.0.extend(back.0.iter().rev().skip(1).map(|p| *p + shift));
                stroke.1.extend(back.1.iter().rev().skip(1));
            }
            let twice = rng.uniform() < drawn.duplicates;
            let keep = drawn.normals && c.has_normals();
            let curve = |(p, n): (Vec<DVec3>, Vec<DVec3>)| Curve {
                points: p,
                normals: if keep { n } else { Vec::new() },
                ..Default::default()
            };
            curves.push(curve(stroke));
            if twice {
                let again = path.stroke(a, b, drawn.spacing * diag, &mut rng);
                let shift = path.side(0.5 * (a + b)) * drawn.offset * diag;
                curves.push(curve((again.0.iter().map(|p| *p + shift).collect(), again.1)));
            }
        }
    }
    Network { curves, snap: None, cycles: None }
}

/// A curl back at one end of a stroke (`end` 0: its first sample, 1: its last).
fn hook(stroke: &mut (Vec<DVec3>, Vec<DVec3>), end: usize, size: f64) {
    let (p, n) = stroke;
    let m = p.len();
    let (e, before) = if end == 0 { (p[0], p[1]) } else { (p[m - 1], p[m - 2]) };
    let ne = if end == 0 { n[0] } else { n[m - 1] };
    let t = (e - before).normalize_or_zero();
    let side = t.cross(if ne == DVec3::ZERO { t.any_orthonormal_vector() } else { ne }).normalize_or_zero();
    let curl = [e + size * (0.5 * t + 0.8 * side), e + size * (-0.4 * t + 1.0 * side)];
    for q in curl {
        if end == 0 {
            p.insert(0, q);
            n.insert(0, ne);
        } else {
            p.push(q);
            n.push(ne);
        }
    }
}

/// A curve as a path by arc length (wrapping on a closed curve).
struct Path<'a> {
    curve: &'a Curve,
    arc: Vec<f64>,
    length: f64,
}

impl<'a> Path<'a> {
    fn new(curve: &'a Curve) -> Self {
        let n = curve.points.len();
        let mut arc = vec![0.0];
        let m = if curve.closed { n } else { n - 1 };
        for i in 0..m {
            arc.push(arc[i] + curve.points[i].distance(curve.points[(i + 1) % n]));
        }
        let length = arc[arc.len() - 1];
        Path { curve, arc, length }
    }

    /// Position and normal at arc length `s`.
    fn at(&self, s: f64) -> (DVec3, DVec3) {
        let s = if self.curve.closed { s.rem_euclid(self.length) } else { s.clamp(0.0, self.length) };
        let (e, t) = crate::geom::polyline::locate(&self.arc, s);
        let n = self.curve.points.len();
        let p = self.curve.points[e].lerp(self.curve.points[(e + 1) % n], t);
        let nrm = if self.curve.has_normals() {
            self.curve.normals[e].lerp(self.curve.normals[(e + 1) % n], t).normalize_or_zero()
        } else {
            DVec3::ZERO
        };
        (p, nrm)
    }

    /// A unit vector across the curve at `s` (in the surface where it has normals).
    fn side(&self, s: f64) -> DVec3 {
        let (p, n) = self.at(s);
        let t = (self.at(s + 1e-3 * self.length).0 - p).normalize_or_zero();
        let up = if n == DVec3::ZERO { t.any_orthonormal_vector() } else { n };
        t.cross(up).normalize_or_zero()
    }

    /// Samples from `a` to `b` (arc lengths) about `h` apart, unevenly.
    fn stroke(&self, a: f64, b: f64, h: f64, rng: &mut Rng) -> (Vec<DVec3>, Vec<DVec3>) {
        let (mut p, mut n) = (Vec::new(), Vec::new());
        let mut s = a;
        loop {
            let (x, y) = self.at(s.min(b));
            p.push(x);
            n.push(y);
            if s >= b {
                break;
            }
            s += h * (0.4 + 1.2 * rng.uniform());
        }
        (p, n)
    }
}
