//! Polylines parameterised by arc length: the cumulative lengths of their samples and the
//! point at a given length. Shared by node finding, the samplers and sketch inflation.

/// The edge `e` (between samples `e` and `e + 1`) and the parameter `t ∈ [0, 1]` along it of
/// arc length `s` on a polyline whose samples have the cumulative lengths `arc` (`arc[0] = 0`,
/// at least two samples). `s` outside `[0, arc.last()]` gives the first or last edge's end;
/// a zero-length edge gives `t = 0`.
pub fn locate(arc: &[f64], s: f64) -> (usize, f64) {
    let e = (arc.partition_point(|&x| x <= s).max(1) - 1).min(arc.len() - 2);
    let len = arc[e + 1] - arc[e];
    let t = if len > 0.0 { ((s - arc[e]) / len).clamp(0.0, 1.0) } else { 0.0 };
    (e, t)
}

/// The cumulative arc lengths of `points` (`0` at the first), given the distance between two
/// consecutive ones.
pub fn arc_lengths<P>(points: &[P], distance: impl Fn(&P, &P) -> f64) -> Vec<f64> {
    let mut arc = Vec::with_capacity(points.len());
    let mut total = 0.0;
    for (i, p) in points.iter().enumerate() {
        if i > 0 {
            total += distance(&points[i - 1], p);
        }
        arc.push(total);
    }
    arc
}

#[cfg(test)]
#[path = "tests/polyline.rs"]
mod tests;
