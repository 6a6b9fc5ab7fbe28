use super::*;

fn tetra() -> MeshFile {
    MeshFile {
        positions: vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::new(0.1, 0.2, 1.0 / 3.0)],
        faces: vec![[0, 2, 1], [0, 1, 3], [1, 2, 3], [2, 0, 3]],
        normals: Some(vec![DVec3::Z, DVec3::X, DVec3::Y, DVec3::Z]),
        mean_curvature: Some(vec![1.0, -0.5, 0.25, 2.0]),
        curve_vertex: Some(vec![true, false, false, true]),
        propagated_normals: Some(vec![DVec3::X, DVec3::Y, DVec3::Z, DVec3::X]),
    }
}

#[test]
fn round_trips() {
    let dir = std::env::temp_dir().join(format!("curvenet-mesh-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let m = tetra();
    for ext in ["ply", "obj", "off"] {
        let p = dir.join(format!("t.{ext}"));
        write_mesh(&p, m.as_data()).unwrap();
        let back = read_mesh(&p).unwrap();
        assert_eq!(back.positions, m.positions, "{ext}");
        assert_eq!(back.faces, m.faces, "{ext}");
        if ext == "ply" {
            assert_eq!(back.mean_curvature, m.mean_curvature);
            assert_eq!(back.curve_vertex, m.curve_vertex);
            assert_eq!(back.normals, m.normals);
            assert_eq!(back.propagated_normals, m.propagated_normals);
        }
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// The text formats print the shortest decimal that reads back to the same bits, with an
/// exponent where one is shorter (`1e+21`, `5e-324`): every value survives a round trip.
#[test]
fn text_formats_keep_every_bit() {
    let dir = std::env::temp_dir().join(format!("curvenet-mesh-bits-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let mut m = tetra();
    m.positions = vec![
        DVec3::new(0.1 + 0.2, -1.0 / 3.0, 1e21),
        DVec3::new(-0.0, 5e-324, -2.2250738585072014e-308),
        DVec3::new(f64::MAX / 3.0, 123456789.0, -1.2345678901234567e-5),
        DVec3::new(1e-7, 0.5, 9007199254740993.0),
    ];
    for ext in ["obj", "off"] {
        let p = dir.join(format!("bits.{ext}"));
        write_mesh(&p, m.as_data()).unwrap();
        let back = read_mesh(&p).unwrap();
        for (a, b) in back.positions.iter().zip(&m.positions) {
            assert_eq!(a.to_array().map(f64::to_bits), b.to_array().map(f64::to_bits), "{ext}");
        }
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn unknown_extension_is_a_usage_error() {
    let e = write_mesh(Path::new("x.stl"), tetra().as_data()).unwrap_err();
    assert_eq!(e.exit_code(), 2);
}

#[test]
fn ascii_ply_with_quads() {
    let text = b"ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n";
    let m = read_ply(text, "t").unwrap();
    assert_eq!(m.faces, vec![[0, 1, 2], [0, 2, 3]]);
}

/// No NaN or infinity is ever written: a non-finite position, normal or curvature is a
/// numerical error naming the vertex, and neither the target nor a temporary file appears.
#[test]
fn non_finite_values_are_never_written() {
    let dir = std::env::temp_dir().join(format!("curvenet-mesh-nan-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    type Breaker = (&'static str, fn(&mut MeshFile));
    let breakers: [Breaker; 4] = [
        ("position", |m| m.positions[2].y = f64::NAN),
        ("normal", |m| m.normals.as_mut().unwrap()[1].x = f64::INFINITY),
        ("mean curvature", |m| m.mean_curvature.as_mut().unwrap()[3] = f64::NAN),
        ("propagated normal", |m| m.propagated_normals.as_mut().unwrap()[0].z = f64::NEG_INFINITY),
    ];
    for (what, breaker) in breakers {
        let mut m = tetra();
        breaker(&mut m);
        for ext in ["ply", "obj", "off"] {
            let p = dir.join(format!("t.{ext}"));
            let e = write_mesh(&p, m.as_data()).unwrap_err();
            assert!(matches!(e, Error::Numerical { .. }) && e.to_string().contains(what), "{ext}: {e}");
            assert_eq!(std::fs::read_dir(&dir).unwrap().count(), 0, "{ext}: a file was written");
        }
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// GLB (glTF 2.0 §4.4): the header, 4-byte aligned JSON and BIN chunks, one accessor per
/// attribute with the vertex count, positions with their bounds, indices of every face; a
/// vertex on a sharp edge repeated per sector; reading a GLB is a usage error.
#[test]
fn glb_has_the_layout_of_the_standard() {
    let dir = std::env::temp_dir().join(format!("curvenet-glb-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let m = tetra();
    let p = dir.join("t.glb");
    write_mesh(&p, m.as_data()).unwrap();
    let b = std::fs::read(&p).unwrap();
    let u32_at = |i: usize| u32::from_le_bytes([b[i], b[i + 1], b[i + 2], b[i + 3]]) as usize;
    assert_eq!(&b[0..4], b"glTF");
    assert_eq!(u32_at(4), 2);
    assert_eq!(u32_at(8), b.len());
    let json_len = u32_at(12);
    assert_eq!(&b[16..20], b"JSON");
    assert_eq!(json_len % 4, 0);
    let doc: serde_json::Value = serde_json::from_slice(&b[20..20 + json_len]).unwrap();
    let bin = 20 + json_len;
    assert_eq!(&b[bin + 4..bin + 8], b"BIN\0");
    assert_eq!(u32_at(bin), b.len() - bin - 8);
    assert_eq!(doc["buffers"][0]["byteLength"].as_u64().unwrap() as usize, u32_at(bin));
    let prim = &doc["meshes"][0]["primitives"][0];
    let acc = |name: &str| &doc["accessors"][prim["attributes"][name].as_u64().unwrap() as usize];
    // The tetrahedron's every edge is sharp: each vertex has one normal per face around it.
    let n = acc("POSITION")["count"].as_u64().unwrap();
    assert_eq!(n, 12);
    for name in ["NORMAL", "_MEAN_CURVATURE", "_CURVE"] {
        assert_eq!(acc(name)["count"].as_u64().unwrap(), n, "{name}");
    }
    assert_eq!(acc("POSITION")["max"], serde_json::json!([1.0, 1.0, 1.0 / 3.0f32]));
    assert_eq!(acc("POSITION")["min"], serde_json::json!([0.0, 0.0, 0.0]));
    let indices = &doc["accessors"][prim["indices"].as_u64().unwrap() as usize];
    assert_eq!(indices["count"].as_u64().unwrap(), 12);
    for v in doc["bufferViews"].as_array().unwrap() {
        assert_eq!(v["byteOffset"].as_u64().unwrap() % 4, 0);
    }
    let e = read_mesh(&p).unwrap_err();
    assert_eq!(e.exit_code(), 2, "{e}");
    std::fs::remove_dir_all(&dir).unwrap();
}

/// The PLY's vertex properties share one type (libigl's reader refuses a file where they do
/// not, then crashes).
#[test]
fn ply_vertex_properties_share_one_type() {
    let dir = std::env::temp_dir().join(format!("curvenet-plytype-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let p = dir.join("t.ply");
    write_mesh(&p, tetra().as_data()).unwrap();
    let b = std::fs::read(&p).unwrap();
    let end = b.windows(10).position(|w| w == b"end_header").unwrap();
    let header = std::str::from_utf8(&b[..end]).unwrap();
    let vertex = header.split("element face").next().unwrap();
    let types: std::collections::BTreeSet<&str> =
        vertex.lines().filter_map(|l| l.strip_prefix("property ")).filter_map(|l| l.split(' ').next()).collect();
    assert_eq!(types.into_iter().collect::<Vec<_>>(), ["double"], "{header}");
    std::fs::remove_dir_all(&dir).unwrap();
}
