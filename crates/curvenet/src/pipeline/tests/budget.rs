use super::*;

#[test]
fn a_spacing_far_above_the_default_size_is_said_with_count_and_time() {
    let o = Options::default();
    // The README's surprise: 3.5M vertices.
    let w = size_warning(0.01, 3.55e6, &o).expect("a warning");
    assert!(w.message.contains("3.55e6") && w.message.contains("178×"), "{}", w.message);
    assert!(w.message.contains("min") && w.message.contains("`vertices`"), "{}", w.message);
    // Below 10× the default and under a minute: nothing.
    assert!(size_warning(0.05, 150_000.0, &o).is_none());
    assert!(size_warning(0.05, 210_000.0, &o).is_some());
    // The time grows faster than the count, and a heavier method takes longer.
    assert!(seconds(2e6, &o) > 2.0 * seconds(1e6, &o));
    let cauchy = Options { method: Method::Cauchy, ..Options::default() };
    assert!(seconds(1e6, &cauchy) > seconds(1e6, &o));
}
