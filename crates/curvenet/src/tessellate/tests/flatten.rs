use super::*;
use crate::tessellate::tessellate;
use crate::tessellate::tests::{prepared, unit_square};

/// A flat patch flattens onto itself: its flattened area is the area of the coarse mesh, and
/// triangulating it in its flattening covers the same area.
#[test]
fn a_flat_patch_keeps_its_area_in_its_flattening() {
    let (g, coarse_res, patches) = prepared(vec![unit_square()], 0.1);
    let coarse = tessellate(&g, &coarse_res, &patches, 0.1).unwrap();
    let area = |m: &Mesh| -> f64 {
        m.faces
            .iter()
            .map(|f| {
                let [a, b, c] = f.map(|v| m.positions[v as usize]);
                0.5 * (b - a).cross(c - a).z
            })
            .sum()
    };
    let flat = flatten_patches(&patches, &coarse_res, &coarse);
    let Some(f) = &flat[0] else { panic!("no flattening") };
    assert!((f.area - area(&coarse)).abs() < 1e-9, "{} vs {}", f.area, area(&coarse));
    // Every coarse vertex of the patch has a place in the flattening.
    assert_eq!(f.uv.len(), coarse.positions.len());
    // Finer, in the flattening: the same curve vertices as the planar tessellation at 0.05.
    let (g, res, patches) = prepared(vec![unit_square()], 0.05);
    let (mesh, kept) = crate::tessellate::tessellate_conformal(&g, &res, &patches, 0.05, &coarse_res, &flat).unwrap();
    assert!(kept.is_empty(), "patches kept in projection: {kept:?}");
    assert_eq!(mesh.num_curve, res.positions.len());
    assert_eq!(mesh.face_patch.len(), mesh.faces.len());
}
