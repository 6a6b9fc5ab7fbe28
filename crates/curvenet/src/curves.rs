//! Cubic splines through the samples of a curve and uniform resampling in arc length
//! (\[CG\] §3.3: "the positions pᵢ and normals nᵢ along the curve network are interpolated with
//! cubic splines and resampled with arc length parameterization").
//!
//! One spline per curve interpolates the positions and the normals together (a 6-vector per
//! sample) over the cumulative chord length; open curves use natural end conditions, closed
//! curves periodic ones. Segments between nodes are resampled as parameter intervals of their
//! curve's spline, so the curve stays C² across nodes and node positions stay exact.

use crate::geom::DVec3;

/// 5-point Gauss–Legendre nodes and weights on [−1, 1].
const GAUSS5: [(f64, f64); 5] = [
    (0.0, 0.568_888_888_888_888_9),
    (-0.538_469_310_105_683_1, 0.478_628_670_499_366_5),
    (0.538_469_310_105_683_1, 0.478_628_670_499_366_5),
    (-0.906_179_845_938_664, 0.236_926_885_056_189_08),
    (0.906_179_845_938_664, 0.236_926_885_056_189_08),
];

type V6 = [f64; 6];

/// A C² cubic spline through `(pᵢ, nᵢ)` samples, parameterised by cumulative chord length.
///
/// Parameter `t` runs over `[0, T]` (open) or is periodic with period `T` (closed); sample `i`
/// sits at [`CurveSpline::knot`]`(i)`, and for a closed curve `knot(n) = T` is sample 0 again.
#[derive(Clone, Debug)]
pub struct CurveSpline {
    t: Vec<f64>,
    y: Vec<V6>,
    m: Vec<V6>,
    /// Arc length from t = 0 to each knot.
    arc: Vec<f64>,
    closed: bool,
}

impl CurveSpline {
    /// Fits the spline through `points` and `normals` (same length, ≥ 2, ≥ 3 when closed, no
    /// two consecutive samples equal).
    pub fn fit(points: &[DVec3], normals: &[DVec3], closed: bool) -> Self {
        let n = points.len();
        let mut y: Vec<V6> = points.iter().zip(normals).map(|(p, q)| [p.x, p.y, p.z, q.x, q.y, q.z]).collect();
        let mut t = Vec::with_capacity(n + 1);
        t.push(0.0);
        for i in 1..n {
            t.push(t[i - 1] + points[i].distance(points[i - 1]).max(f64::MIN_POSITIVE));
        }
        if closed {
            t.push(t[n - 1] + points[0].distance(points[n - 1]).max(f64::MIN_POSITIVE));
            y.push(y[0]);
        }
        let m = if closed { periodic_moments(&t, &y) } else { natural_moments(&t, &y) };
        let mut s = CurveSpline { t, y, m, arc: Vec::new(), closed };
        let mut arc = Vec::with_capacity(s.t.len());
        arc.push(0.0);
        for i in 0..s.t.len() - 1 {
            let l = s.piece_arc(i, s.t[i], s.t[i + 1]);
            arc.push(arc[i] + l);
        }
        s.arc = arc;
        s
    }

    /// Number of knots (samples, plus the repeated first one for closed curves).
    pub fn num_knots(&self) -> usize {
        self.t.len()
    }

    /// Parameter of sample `i` (`i = n` allowed for closed curves: the period).
    pub fn knot(&self, i: usize) -> f64 {
        self.t[i]
    }

    /// Period (closed) or parameter length (open).
    pub fn period(&self) -> f64 {
        self.t[self.t.len() - 1]
    }

    /// Whether the curve is periodic (closed).
    pub fn is_closed(&self) -> bool {
        self.closed
    }

    /// Total arc length.
    pub fn length(&self) -> f64 {
        self.arc[self.arc.len() - 1]
    }

    fn piece(&self, t: f64) -> usize {
        let k = self.t.len() - 1;
        match self.t.partition_point(|&x| x <= t) {
            0 => 0,
            p => (p - 1).min(k - 1),
        }
    }

    fn wrap(&self, t: f64) -> f64 {
        if self.closed {
            t.rem_euclid(self.period())
        } else {
            t.clamp(0.0, self.period())
        }
    }

    fn eval6(&self, t: f64) -> V6 {
        let t = self.wrap(t);
        let i = self.piece(t);
        let h = self.t[i + 1] - self.t[i];
        let a = (self.t[i + 1] - t) / h;
        let b = 1.0 - a;
        let c = (a * a * a - a) * h * h / 6.0;
        let d = (b * b * b - b) * h * h / 6.0;
        let mut out = [0.0; 6];
        for k in 0..6 {
            out[k] = a * self.y[i][k] + b * self.y[i + 1][k] + c * self.m[i][k] + d * self.m[i + 1][k];
        }
        out
    }

    fn deriv_pos(&self, i: usize, t: f64) -> DVec3 {
        let h = self.t[i + 1] - self.t[i];
        let a = (self.t[i + 1] - t) / h;
        let b = 1.0 - a;
        let mut d = [0.0; 3];
        for (k, dk) in d.iter_mut().enumerate() {
            *dk = (self.y[i + 1][k] - self.y[i][k]) / h - (3.0 * a * a - 1.0) / 6.0 * h * self.m[i][k]
                + (3.0 * b * b - 1.0) / 6.0 * h * self.m[i + 1][k];
        }
        DVec3::from_array(d)
    }

    /// Position at parameter `t`.
    pub fn position(&self, t: f64) -> DVec3 {
        let v = self.eval6(t);
        DVec3::new(v[0], v[1], v[2])
    }

    /// Unit normal at parameter `t` (the interpolated normal, re-normalised).
    pub fn normal(&self, t: f64) -> DVec3 {
        let v = self.eval6(t);
        DVec3::new(v[3], v[4], v[5]).normalize_or_zero()
    }

    /// Derivative of the position with respect to `t` (≈ unit tangent for chord-length
    /// parameterisation). At a knot, `from_right` selects the piece after (or before) it.
    pub fn tangent(&self, t: f64, from_right: bool) -> DVec3 {
        let tw = self.wrap(t);
        let mut i = self.piece(tw);
        if !from_right && i > 0 && tw <= self.t[i] {
            i -= 1;
        }
        if !from_right && self.closed && tw <= self.t[0] && i == 0 {
            return self.deriv_pos(self.t.len() - 2, self.period());
        }
        self.deriv_pos(i, tw)
    }

    fn piece_arc(&self, i: usize, t0: f64, t1: f64) -> f64 {
        let (c, r) = (0.5 * (t0 + t1), 0.5 * (t1 - t0));
        GAUSS5.iter().map(|&(x, w)| w * self.deriv_pos(i, c + r * x).length()).sum::<f64>() * r
    }

    /// Arc length from 0 to `t`, for `t` in `[0, 2T]` on closed curves (one extra period).
    pub fn arc_length_at(&self, t: f64) -> f64 {
        if self.closed && t > self.period() {
            return self.length() + self.arc_length_at(t - self.period());
        }
        let t = self.wrap(t);
        let i = self.piece(t);
        self.arc[i] + self.piece_arc(i, self.t[i], t)
    }

    /// Parameter at which the arc length from 0 equals `s` (Newton's method safeguarded by
    /// bisection inside the spline piece).
    pub fn param_at_arc_length(&self, s: f64) -> f64 {
        let (s, offset) = if self.closed && s > self.length() { (s - self.length(), self.period()) } else { (s, 0.0) };
        let k = self.arc.len() - 1;
        let i = match self.arc.partition_point(|&x| x <= s) {
            0 => 0,
            p => (p - 1).min(k - 1),
        };
        let (mut lo, mut hi) = (self.t[i], self.t[i + 1]);
        let target = s - self.arc[i];
        let len = self.arc[i + 1] - self.arc[i];
        let mut t = lo + (hi - lo) * if len > 0.0 { (target / len).clamp(0.0, 1.0) } else { 0.0 };
        for _ in 0..50 {
            let f = self.piece_arc(i, self.t[i], t) - target;
            if f.abs() <= 1e-13 * self.length().max(f64::MIN_POSITIVE) {
                break;
            }
            if f > 0.0 {
                hi = t;
            } else {
                lo = t;
            }
            let d = self.deriv_pos(i, t).length();
            let newton = if d > 0.0 { t - f / d } else { f64::NAN };
            t = if newton > lo && newton < hi { newton } else { 0.5 * (lo + hi) };
            if hi - lo <= 1e-15 * self.period() {
                break;
            }
        }
        t + offset
    }

    /// Resamples the stretch between knots `i0` and `i1` (for closed curves `i1 ≤ i0` wraps
    /// through sample 0; `i1 = i0` is the whole loop) into `pieces` parts of equal arc length.
    /// Returns `pieces + 1` (position, unit normal) pairs; the first and last are exactly the
    /// knot samples.
    pub fn resample(&self, i0: usize, i1: usize, pieces: usize) -> Vec<(DVec3, DVec3)> {
        let pieces = pieces.max(1);
        let s0 = self.arc[i0];
        let mut s1 = self.arc[i1];
        if self.closed && i1 <= i0 {
            s1 += self.length();
        }
        let at = |k: usize| {
            let v = self.y[k];
            (DVec3::new(v[0], v[1], v[2]), DVec3::new(v[3], v[4], v[5]).normalize())
        };
        let mut out = Vec::with_capacity(pieces + 1);
        out.push(at(i0));
        for k in 1..pieces {
            let s = s0 + (s1 - s0) * k as f64 / pieces as f64;
            let t = self.param_at_arc_length(s);
            let v = self.eval6(t);
            let mut n = DVec3::new(v[3], v[4], v[5]).normalize_or_zero();
            if n == DVec3::ZERO {
                // The interpolated normals cancelled (they flip between samples): fall back to
                // the nearer sample's normal rather than producing a zero vector.
                let tw = self.wrap(t);
                let j = self.piece(tw);
                n = at(if tw - self.t[j] < self.t[j + 1] - tw { j } else { j + 1 }).1;
            }
            out.push((DVec3::new(v[0], v[1], v[2]), n));
        }
        out.push(at(i1));
        out
    }

    /// Arc length between knots `i0` and `i1` (wrapping as in [`CurveSpline::resample`]).
    pub fn arc_between(&self, i0: usize, i1: usize) -> f64 {
        let mut l = self.arc[i1] - self.arc[i0];
        if self.closed && i1 <= i0 {
            l += self.length();
        }
        l
    }
}

/// Second derivatives of the natural cubic spline (M₀ = Mₙ = 0): tridiagonal solve.
fn natural_moments(t: &[f64], y: &[V6]) -> Vec<V6> {
    let n = t.len();
    let mut m = vec![[0.0; 6]; n];
    if n < 3 {
        return m;
    }
    // Interior unknowns 1..n-2: h_{i-1} M_{i-1} + 2(h_{i-1}+h_i) M_i + h_i M_{i+1} = r_i.
    let k = n - 2;
    let mut diag = vec![0.0; k];
    let mut upper = vec![0.0; k];
    let mut rhs = vec![[0.0; 6]; k];
    for j in 0..k {
        let i = j + 1;
        let (h0, h1) = (t[i] - t[i - 1], t[i + 1] - t[i]);
        diag[j] = 2.0 * (h0 + h1);
        upper[j] = h1;
        for c in 0..6 {
            rhs[j][c] = 6.0 * ((y[i + 1][c] - y[i][c]) / h1 - (y[i][c] - y[i - 1][c]) / h0);
        }
    }
    // Thomas algorithm; lower[j] = h_{j} (= upper[j-1]). Diagonally dominant: stable.
    for j in 1..k {
        let w = upper[j - 1] / diag[j - 1];
        diag[j] -= w * upper[j - 1];
        for c in 0..6 {
            rhs[j][c] -= w * rhs[j - 1][c];
        }
    }
    for j in (0..k).rev() {
        for c in 0..6 {
            let next = if j + 1 < k { m[j + 2][c] } else { 0.0 };
            m[j + 1][c] = (rhs[j][c] - upper[j] * next) / diag[j];
        }
    }
    m
}

/// Second derivatives of the periodic cubic spline: cyclic tridiagonal solve by the
/// Sherman–Morrison correction of the Thomas algorithm. `t` and `y` include the repeated
/// first sample at the end.
fn periodic_moments(t: &[f64], y: &[V6]) -> Vec<V6> {
    let n = t.len() - 1; // distinct samples
    let h = |i: usize| t[(i % n) + 1] - t[i % n];
    let hm = |i: usize| h((i + n - 1) % n);
    // Row i: hm(i) M_{i-1} + 2(hm(i)+h(i)) M_i + h(i) M_{i+1} = r_i, indices mod n.
    let mut a = vec![0.0; n]; // sub-diagonal (a[0] is the corner)
    let mut b = vec![0.0; n];
    let mut c = vec![0.0; n]; // super-diagonal (c[n-1] is the corner)
    let mut r = vec![[0.0; 6]; n];
    for i in 0..n {
        a[i] = hm(i);
        c[i] = h(i);
        b[i] = 2.0 * (a[i] + c[i]);
        let (ip, im) = ((i + 1) % n, (i + n - 1) % n);
        for k in 0..6 {
            r[i][k] = 6.0 * ((y[ip][k] - y[i][k]) / h(i) - (y[i][k] - y[im][k]) / hm(i));
        }
    }
    // Sherman–Morrison: A = T + u vᵀ with u = (γ, 0…, 0, c_{n-1}), v = (1, 0…, 0, a_0/γ).
    let gamma = -b[0];
    let mut bb = b.clone();
    bb[0] -= gamma;
    bb[n - 1] -= c[n - 1] * a[0] / gamma;
    let solve = |rhs: &mut [V6]| {
        let mut d = bb.clone();
        for i in 1..n {
            let w = a[i] / d[i - 1];
            d[i] -= w * c[i - 1];
            for k in 0..6 {
                rhs[i][k] -= w * rhs[i - 1][k];
            }
        }
        for k in 0..6 {
            rhs[n - 1][k] /= d[n - 1];
        }
        for i in (0..n - 1).rev() {
            for k in 0..6 {
                rhs[i][k] = (rhs[i][k] - c[i] * rhs[i + 1][k]) / d[i];
            }
        }
    };
    let mut x = r;
    solve(&mut x);
    let mut z = vec![[0.0; 6]; n];
    for k in 0..6 {
        z[0][k] = gamma;
        z[n - 1][k] = c[n - 1];
    }
    solve(&mut z);
    let mut m = vec![[0.0; 6]; n + 1];
    for k in 0..6 {
        let vx = x[0][k] + a[0] / gamma * x[n - 1][k];
        let vz = z[0][k] + a[0] / gamma * z[n - 1][k];
        let f = vx / (1.0 + vz);
        for i in 0..n {
            m[i][k] = x[i][k] - f * z[i][k];
        }
        m[n][k] = m[0][k];
    }
    m
}

#[cfg(test)]
#[path = "tests/curves.rs"]
mod tests;
