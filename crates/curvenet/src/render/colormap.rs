//! Colour maps: a diverging map centred at zero for signed quantities (mean curvature) and a
//! sequential map for magnitudes (normal deviation in degrees).
//!
//! Both are piecewise linear through control points taken from well-known perceptual maps:
//! the diverging one follows Moreland's "cool to warm" (blue, light grey at zero, red), the
//! sequential one follows viridis (dark purple, blue, green, yellow).

/// An sRGB colour with components in `[0, 1]`.
pub type Rgb = [f32; 3];

/// Moreland's cool-to-warm diverging map at `t ∈ [−1, 1]` (`0` is the neutral grey).
pub fn diverging(t: f64) -> Rgb {
    const STOPS: [(f64, Rgb); 5] = [
        (-1.0, [0.230, 0.299, 0.754]),
        (-0.5, [0.552, 0.690, 0.996]),
        (0.0, [0.865, 0.865, 0.865]),
        (0.5, [0.958, 0.604, 0.482]),
        (1.0, [0.706, 0.016, 0.150]),
    ];
    piecewise(&STOPS, t)
}

/// The viridis sequential map at `t ∈ [0, 1]`.
pub fn sequential(t: f64) -> Rgb {
    // Colour components of viridis, not π-related constants (0.318 is a green's blue).
    #[allow(clippy::approx_constant)]
    const STOPS: [(f64, Rgb); 6] = [
        (0.0, [0.267, 0.005, 0.329]),
        (0.2, [0.254, 0.265, 0.530]),
        (0.4, [0.164, 0.471, 0.558]),
        (0.6, [0.134, 0.659, 0.518]),
        (0.8, [0.478, 0.821, 0.318]),
        (1.0, [0.993, 0.906, 0.144]),
    ];
    piecewise(&STOPS, t)
}

/// Linear interpolation through `(position, colour)` stops sorted by position; clamped at the
/// ends, NaN maps to the first stop.
fn piecewise(stops: &[(f64, Rgb)], t: f64) -> Rgb {
    let first = stops[0];
    let last = stops[stops.len() - 1];
    if t.is_nan() || t <= first.0 {
        return first.1;
    }
    if t >= last.0 {
        return last.1;
    }
    let i = stops.windows(2).position(|w| t <= w[1].0).unwrap_or(stops.len() - 2);
    let (a, b) = (stops[i], stops[i + 1]);
    let s = ((t - a.0) / (b.0 - a.0)) as f32;
    [a.1[0] + s * (b.1[0] - a.1[0]), a.1[1] + s * (b.1[1] - a.1[1]), a.1[2] + s * (b.1[2] - a.1[2])]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn diverging_is_neutral_at_zero_and_clamps() {
        let g = diverging(0.0);
        assert!((g[0] - g[1]).abs() < 1e-6 && (g[1] - g[2]).abs() < 1e-6);
        assert_eq!(diverging(5.0), diverging(1.0));
        assert_eq!(diverging(-5.0), diverging(-1.0));
        assert!(diverging(1.0)[0] > diverging(1.0)[2], "positive is red");
        assert!(diverging(-1.0)[2] > diverging(-1.0)[0], "negative is blue");
        assert_eq!(sequential(f64::NAN), sequential(0.0));
    }
}
