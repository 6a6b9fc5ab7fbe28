use crate::pipeline::{surface, Options};

/// A unit square outline in the plane `z = 0` as an OBJ edge soup (no normals: a flat disk),
/// with a circle of radius 0.15 about `(0.5, 0.5, z)`: in the square's plane, or standing on
/// end (in the plane `y = 0.5`) when `upright`.
fn square_with_circle(z: f64, upright: bool) -> crate::Network {
    let mut text = String::from("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nl 1 2\nl 2 3\nl 3 4\nl 4 1\n");
    let n = 24;
    for k in 0..n {
        let t = std::f64::consts::TAU * k as f64 / n as f64;
        let (c, s) = (0.15 * t.cos(), 0.15 * t.sin());
        let p = if upright { [0.5 + c, 0.5, z + s] } else { [0.5 + c, 0.5 + s, z] };
        text.push_str(&format!("v {} {} {}\n", p[0], p[1], p[2]));
    }
    for k in 0..n {
        text.push_str(&format!("l {} {}\n", 5 + k, 5 + (k + 1) % n));
    }
    crate::io::parse_network(&text, crate::io::NetworkFormat::Obj, "square.obj").unwrap()
}

/// A closed curve drawn on the square is a detail of it: its disk (a second sheet on the
/// square) is left out with a warning, and what is left is the square, flat, every attribute
/// of the mesh cut to match. Drawn above it, standing on end so that it faces no other loop
/// (its lowest point 0.05 above the square: over three times the tolerance), it is a disk of
/// its own.
#[test]
fn a_loop_drawn_on_the_surface_is_a_detail_and_one_above_it_a_disk() {
    let options = Options::default().with_vertices(3000);
    let on = surface(&square_with_circle(0.0, false), &options).unwrap();
    let said = on.warnings.iter().any(|w| w.message.contains("taken as details drawn on it"));
    assert!(said, "{:?}", on.warnings);
    assert_eq!(on.stats.cycles, 1);
    assert!(crate::geom::mesh::bad_edge(&on.mesh.faces).is_none());
    assert!(on.mesh.positions.iter().all(|p| p.z.abs() < 1e-9));
    assert_eq!(on.stats.vertices, on.mesh.positions.len());
    assert_eq!((on.normals.len(), on.curve_flags.len()), (on.mesh.positions.len(), on.mesh.positions.len()));
    assert_eq!(on.mesh.faces.len(), on.mesh.face_patch.len());
    assert_eq!(on.mesh.curve_normals.len(), on.mesh.num_curve);
    assert!(on.mesh.faces.iter().flatten().all(|&v| (v as usize) < on.mesh.positions.len()));
    // The outline's disk is all there, as without the circle: one sheet, no hole.
    let mut alone = square_with_circle(0.0, false);
    alone.curves.truncate(1);
    let alone = surface(&alone, &options).unwrap();
    let area = |s: &crate::pipeline::Surface| crate::geom::mesh::surface_area(&s.mesh.faces, &s.mesh.positions);
    assert!((area(&on) / area(&alone) - 1.0).abs() < 1e-3, "{} against {}", area(&on), area(&alone));

    let above = surface(&square_with_circle(0.2, true), &options).unwrap();
    assert!(!above.warnings.iter().any(|w| w.message.contains("taken as details drawn on it")));
    assert_eq!(above.stats.cycles, 2);
    assert!(above.mesh.positions.iter().any(|p| p.z > 0.1));
}

/// A unit square outline (a flat disk) with a straight stroke inside it at height `z`, from
/// `(0.3, 0.5, z)` to `(0.7, 0.5, z)`, meeting nothing.
fn square_with_stroke(z: f64) -> crate::Network {
    let text = format!(
        "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nl 1 2\nl 2 3\nl 3 4\nl 4 1\nv 0.3 0.5 {z}\nv 0.5 0.5 {z}\nv 0.7 0.5 {z}\nl 5 6 7\n"
    );
    crate::io::parse_network(&text, crate::io::NetworkFormat::Obj, "square.obj").unwrap()
}

/// A stroke that bounds no patch but runs over one, 0.02 above it (1.4 % of the diagonal), is
/// a constraint: the surface passes through it (within a thousandth of the diagonal) and stays
/// on its border curve; 0.2 above (14 %, beyond the reach) it pulls nothing and the disk stays
/// flat.
#[test]
fn a_stroke_over_a_patch_pulls_the_surface_onto_it() {
    let mut options = Options::default().with_vertices(3000);
    // As drawn: consolidation would carry the stroke's ends on to the border (a sketch of loose
    // strokes), and the stroke would split the disk.
    options.consolidate.enabled = false;
    let s = surface(&square_with_stroke(0.02), &options).unwrap();
    assert!(s.warnings.iter().any(|w| w.message.contains("were taken as constraints")), "{:?}", s.warnings);
    let d = crate::geom::distance::MeshDistance::new(&s.mesh.positions, &s.mesh.faces);
    let diag = crate::geom::Aabb::of(s.mesh.positions.iter().copied()).diagonal();
    for k in 0..=20 {
        let p = crate::geom::DVec3::new(0.3 + 0.4 * k as f64 / 20.0, 0.5, 0.02);
        assert!(d.closest(p).0 < 1e-3 * diag, "{p}: {:.2e} off", d.closest(p).0);
    }
    assert!(s.mesh.positions[..s.mesh.num_curve].iter().all(|p| p.z.abs() < 1e-12), "the border stays");
    assert!(s.mesh.positions.iter().all(|p| p.z > -1e-3 && p.z < 0.021), "a bump to the stroke, no more");

    let far = surface(&square_with_stroke(0.2), &options).unwrap();
    assert!(!far.warnings.iter().any(|w| w.message.contains("were taken as constraints")));
    assert!(far.mesh.positions.iter().all(|p| p.z.abs() < 1e-9));
}
