use super::*;

/// An open polyline through `points` with normals +z.
fn line(points: &[[f64; 3]]) -> Curve {
    let points: Vec<DVec3> = points.iter().map(|&p| DVec3::from(p)).collect();
    Curve {
        name: None,
        normals: vec![DVec3::Z; points.len()],
        points,
        closed: false,
        boundary: false,
        ..Default::default()
    }
}

fn labels(n: usize) -> Vec<String> {
    (0..n).map(|i| format!("curve {i}")).collect()
}

#[test]
fn arc_lengths_and_distances_along_curves() {
    let open = line(&[[0.0, 0.0, 0.0], [3.0, 4.0, 0.0], [3.0, 4.0, 12.0]]);
    let mut closed = line(&[[0.0, 0.0, 0.0], [4.0, 0.0, 0.0], [4.0, 3.0, 0.0]]);
    closed.closed = true;
    let curves = [open, closed];
    let names = labels(2);
    let lines = Polylines::new(&curves, &names);
    assert_eq!(lines.arcs, vec![vec![0.0, 5.0, 17.0], vec![0.0, 4.0, 7.0, 12.0]]);
    assert_eq!((lines.num_edges(0), lines.num_edges(1)), (2, 3));
    assert_eq!((lines.total(0), lines.total(1)), (17.0, 12.0));
    // Along the open curve the plain difference, around the loop the shorter way.
    assert_eq!(lines.along(0, 1.0, 16.0), 15.0);
    assert_eq!(lines.along(1, 1.0, 11.0), 2.0);
    let l = Loc { curve: 0, edge: 1, s: 0.25 };
    assert_eq!(lines.arc_at(l), 8.0);
    assert_eq!(lines.point_at(l), DVec3::new(3.0, 4.0, 3.0));
    assert_eq!(lines.normal_at(l), DVec3::Z);
}

/// Two single-edge curves crossing between their samples, at (0.3, 0, 0): one contact, at
/// 0.65 along the first edge and 0.5 along the second; one cluster.
#[test]
fn two_crossing_edges_have_one_contact() {
    let curves = [line(&[[-1.0, 0.0, 0.0], [1.0, 0.0, 0.0]]), line(&[[0.3, -1.0, 0.0], [0.3, 1.0, 0.0]])];
    let names = labels(2);
    let lines = Polylines::new(&curves, &names);
    let hits = find_contacts(&lines, 0.01).unwrap();
    assert_eq!(hits.len(), 1);
    let h = &hits[0];
    assert_eq!((h.a.curve, h.a.edge, h.b.curve, h.b.edge), (0, 0, 1, 0));
    assert!((h.a.s - 0.65).abs() < 1e-12 && (h.b.s - 0.5).abs() < 1e-12, "{:?} {:?}", h.a, h.b);
    assert!(h.mid.distance(DVec3::new(0.3, 0.0, 0.0)) < 1e-12);
    assert_eq!(cluster_contacts(&lines, &hits, 0.01), vec![vec![0]]);
}

/// Two curves that cross at a shared sample, the origin: both edges of each curve touch it,
/// four contacts in all (one per pair of edges), all in one cluster.
#[test]
fn a_crossing_at_a_shared_sample_is_one_cluster_of_four_contacts() {
    let curves = [
        line(&[[-1.0, 0.0, 0.0], [0.0, 0.0, 0.0], [1.0, 0.0, 0.0]]),
        line(&[[0.0, -1.0, 0.0], [0.0, 0.0, 0.0], [0.0, 1.0, 0.0]]),
    ];
    let names = labels(2);
    let lines = Polylines::new(&curves, &names);
    let hits = find_contacts(&lines, 0.01).unwrap();
    let pairs: Vec<(usize, usize)> = hits.iter().map(|h| (h.a.edge, h.b.edge)).collect();
    assert_eq!(pairs, vec![(0, 0), (0, 1), (1, 0), (1, 1)]);
    assert!(hits.iter().all(|h| h.mid.length() < 1e-12));
    assert_eq!(cluster_contacts(&lines, &hits, 0.01), vec![vec![0, 1, 2, 3]]);
}

/// A U-shaped curve crosses a straight one twice, a unit apart: two clusters. Neighbouring
/// edges of one curve are no contacts.
#[test]
fn two_crossings_far_apart_are_two_clusters() {
    let curves = [
        line(&[[-1.0, 0.0, 0.0], [1.0, 0.0, 0.0]]),
        line(&[[-0.5, -1.0, 0.0], [-0.5, 1.0, 0.0], [0.5, 1.0, 0.0], [0.5, -1.0, 0.0]]),
    ];
    let names = labels(2);
    let lines = Polylines::new(&curves, &names);
    let hits = find_contacts(&lines, 0.01).unwrap();
    assert_eq!(hits.len(), 2);
    assert_eq!(cluster_contacts(&lines, &hits, 0.01), vec![vec![0], vec![1]]);
}

#[test]
fn a_tangle_of_long_random_segments_is_refused_not_enumerated() {
    // 3000 segments across the unit cube, all within a tolerance of 0.3 of each other's cells.
    let mut rng = crate::network::Rng::new(7);
    let curves: Vec<crate::Curve> = (0..3000)
        .map(|_| crate::Curve {
            points: vec![
                DVec3::new(rng.uniform(), rng.uniform(), rng.uniform()),
                DVec3::new(rng.uniform(), rng.uniform(), rng.uniform()),
            ],
            ..Default::default()
        })
        .collect();
    let labels: Vec<String> = (0..curves.len()).map(|i| format!("curve {i}")).collect();
    let lines = Polylines::new(&curves, &labels);
    let e = find_contacts(&lines, 0.3).map(|h| h.len()).unwrap_err();
    assert!(e.to_string().contains("too dense"), "{e}");
}

#[test]
fn a_densely_sampled_circle_has_no_contacts_with_itself() {
    let n = 20_000;
    let curves = vec![crate::Curve {
        points: (0..n)
            .map(|k| {
                let a = std::f64::consts::TAU * k as f64 / n as f64;
                DVec3::new(a.cos(), a.sin(), 0.0)
            })
            .collect(),
        closed: true,
        ..Default::default()
    }];
    let labels = vec!["circle".to_string()];
    let lines = Polylines::new(&curves, &labels);
    assert!(find_contacts(&lines, 3e-3).unwrap().is_empty());
}
