//! The .net network reader on arbitrary bytes, then validation: never a panic, and a parsed
//! network that validates has finite samples and unit normals.
#![no_main]
use curvenet::io::{parse_network, NetworkFormat};
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    // read_network rejects non-UTF-8 before parsing (tested in the catalogue).
    let Ok(text) = std::str::from_utf8(data) else { return };
    match parse_network(text, NetworkFormat::Net, "fuzz.net") {
        Ok(net) => {
            if let Ok((clean, _)) = net.validated() {
                for c in &clean.curves {
                    assert!(c.points.iter().all(|p| p.is_finite()));
                    assert!(c.normals.iter().all(|n| (n.length() - 1.0).abs() < 1e-9));
                }
            }
        }
        Err(e) => assert!(!e.to_string().is_empty()),
    }
});
