//! The SVG sketch reader on arbitrary bytes ([`curvenet::sketch::svg::read_svg`]): never a
//! panic; an error has a message; outlines read have at least two finite points. Read twice as
//! `read_sketch` does: coarsely for the size, then at chords of 1/1000 of it.
#![no_main]
use curvenet::geom::DVec2;
use curvenet::sketch::svg::{read_svg, SketchPath};
use libfuzzer_sys::fuzz_target;

fn check(result: curvenet::Result<Vec<SketchPath>>) -> Option<Vec<SketchPath>> {
    match result {
        Ok(paths) => {
            assert!(!paths.is_empty());
            for p in &paths {
                assert!(p.points.len() >= 2 && p.points.iter().all(|q| q.is_finite()), "{p:?}");
            }
            Some(paths)
        }
        Err(e) => {
            assert!(!e.to_string().is_empty());
            None
        }
    }
}

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else { return };
    let Some(coarse) = check(read_svg(text, "fuzz.svg", f64::INFINITY)) else { return };
    let (lo, hi) = coarse
        .iter()
        .flat_map(|p| p.points.iter().copied())
        .fold((DVec2::INFINITY, DVec2::NEG_INFINITY), |(lo, hi), q| (lo.min(q), hi.max(q)));
    let size = (hi - lo).length();
    if size > 0.0 && size.is_finite() {
        check(read_svg(text, "fuzz.svg", size / 1000.0));
    }
});
