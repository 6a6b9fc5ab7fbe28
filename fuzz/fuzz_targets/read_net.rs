//! The .net network reader on arbitrary bytes, then validation: never a panic, and a parsed
//! network that validates has finite samples and unit normals
//! ([`curvenet::metrics::check::check_network_reader`]).
#![no_main]
use curvenet::io::NetworkFormat;
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    if let Err(e) = curvenet::metrics::check::check_network_reader(data, NetworkFormat::Net) {
        panic!("{e}");
    }
});
