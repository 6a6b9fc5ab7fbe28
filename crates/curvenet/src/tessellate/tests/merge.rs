use super::*;
use crate::geom::{DVec2, DVec3};

/// Four curve vertices: the corners of the unit square.
fn corners() -> Resampled {
    let positions = vec![DVec3::ZERO, DVec3::X, DVec3::new(1.0, 1.0, 0.0), DVec3::Y];
    Resampled { normals: vec![DVec3::Z; 4], on_boundary: vec![true; 4], positions, segment_vertices: Vec::new() }
}

fn part(triangles: Vec<[VRef; 3]>, new_positions: Vec<DVec3>) -> PatchMesh {
    let planar = vec![[DVec2::ZERO; 3]; triangles.len()];
    PatchMesh { new_positions, triangles, planar, fold_fallback: false }
}

/// Two patches on either side of the diagonal 0–2: the first one triangle, the second a fan
/// around one new vertex. The merged mesh shares the curve vertices 0 and 2 and numbers the
/// new vertex after the curve vertices.
#[test]
fn two_patches_share_their_curve_vertices() {
    use VRef::{Curve as C, New as N};
    let a = part(vec![[C(0), C(1), C(2)]], Vec::new());
    let b = part(vec![[C(0), C(2), N(0)], [C(2), C(3), N(0)], [C(3), C(0), N(0)]], vec![DVec3::new(0.3, 0.7, 0.0)]);
    let mesh = merge(&corners(), vec![Ok(a), Ok(b)]).unwrap();
    assert_eq!(mesh.num_curve, 4);
    assert_eq!(mesh.positions.len(), 5);
    assert_eq!(mesh.positions[4], DVec3::new(0.3, 0.7, 0.0));
    assert_eq!(mesh.faces, vec![[0, 1, 2], [0, 2, 4], [2, 3, 4], [3, 0, 4]]);
    assert_eq!(mesh.face_patch, vec![0, 1, 1, 1]);
    assert_eq!(mesh.planar.len(), 4);
    assert_eq!(mesh.on_boundary, vec![true, true, true, true, false]);
    assert!(mesh.fold_fallback.is_empty());
}

#[test]
fn a_curve_vertex_that_no_patch_uses_is_a_topology_error() {
    use VRef::Curve as C;
    let Err(e) = merge(&corners(), vec![Ok(part(vec![[C(0), C(1), C(2)]], Vec::new()))]) else { panic!("accepted") };
    assert!(matches!(e, Error::Topology { .. }), "{e}");
    assert!(e.to_string().starts_with("vertex 3 at"), "{e}");
    assert_eq!((e.at().vertex, e.at().point), (Some(3), Some([0.0, 1.0, 0.0])));
}

#[test]
fn the_error_of_a_part_is_the_error_of_the_merge() {
    let Err(e) = merge(&corners(), vec![Err(Error::numerical("patch 0 failed"))]) else { panic!("accepted") };
    assert!(e.to_string().contains("patch 0 failed"), "{e}");
}
