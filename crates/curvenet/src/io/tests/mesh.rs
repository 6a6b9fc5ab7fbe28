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
