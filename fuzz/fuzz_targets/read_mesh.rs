//! The mesh readers (PLY, OBJ, OFF) on arbitrary bytes: never a panic, and a mesh that reads
//! has faces within range. The first byte picks the format.
#![no_main]
use libfuzzer_sys::fuzz_target;
use std::path::Path;

fuzz_target!(|data: &[u8]| {
    let Some((&pick, bytes)) = data.split_first() else { return };
    let name = ["m.ply", "m.obj", "m.off"][pick as usize % 3];
    match curvenet::io::parse_mesh(bytes, Path::new(name), name) {
        Ok(m) => assert!(m.faces.iter().flatten().all(|&i| (i as usize) < m.positions.len())),
        Err(e) => assert!(!e.to_string().is_empty()),
    }
});
