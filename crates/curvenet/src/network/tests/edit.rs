use super::*;

#[test]
fn rotating_a_circle_s_radial_normals_tilts_them_out_of_plane() {
    let net = crate::network::examples::example("cylinder").unwrap();
    let turned = rotate_normals(&net, 0, 30.0).unwrap();
    for (a, b) in net.curves[0].normals.iter().zip(&turned.curves[0].normals) {
        let angle = a.normalize().dot(b.normalize()).clamp(-1.0, 1.0).acos().to_degrees();
        assert!((angle - 30.0).abs() < 1e-6, "{angle}");
        assert!((b.z).abs() > 0.4, "radial normals turned about a horizontal tangent leave the plane");
    }
    assert_eq!(turned.curves[1], net.curves[1], "other curves untouched");
    assert!(rotate_normals(&net, 9, 1.0).unwrap_err().to_string().contains("curve 9"));
}
