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
