//! The whole pipeline on small generated networks (`curvenet::metrics::check::fuzz_case`): a run either
//! fails with an error message or returns a surface that passes `curvenet::metrics::check::check_surface`
//! (finite, manifold, consistently oriented, no hole, samples on the surface in hard mode).
#![no_main]
use curvenet::metrics::check::{check_surface, fuzz_case, Constraints};
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let Some((net, options)) = fuzz_case(data) else { return };
    match curvenet::surface(&net, &options) {
        Ok(s) => {
            let snap = net.snap_tolerance();
            let hard = if options.soft.is_some() { Constraints::Soft } else { Constraints::Hard };
            let problems = check_surface(&s, &net, snap, hard);
            assert!(problems.is_empty(), "invariants violated: {problems:#?}");
        }
        Err(e) => assert!(!e.to_string().is_empty()),
    }
});
