use super::*;
use std::collections::BTreeMap;

/// The edge uses counted the obvious way: an ordered map from `(a, b)`, `a < b`.
fn counted(faces: &[[u32; 3]]) -> Vec<(u32, u32, u32, u32)> {
    let mut m: BTreeMap<(u32, u32), (u32, u32)> = BTreeMap::new();
    for f in faces {
        for k in 0..3 {
            let (a, b) = (f[k], f[(k + 1) % 3]);
            let e = m.entry((a.min(b), a.max(b))).or_default();
            if a < b {
                e.0 += 1
            } else {
                e.1 += 1
            }
        }
    }
    m.into_iter().map(|((a, b), (f, r))| (a, b, f, r)).collect()
}

fn visited(faces: &[[u32; 3]]) -> Vec<(u32, u32, u32, u32)> {
    let mut out = Vec::new();
    for_each_edge(faces, |a, b, f, r| out.push((a, b, f, r)));
    out
}

#[test]
fn edges_are_counted_once_in_order() {
    // A fan around vertex 0, a fin on edge 0–1 (three faces), a flipped face on edge 3–4.
    let faces = [[0, 1, 2], [0, 2, 3], [0, 3, 4], [1, 0, 5], [0, 1, 6], [3, 4, 7], [9, 8, 7]];
    assert_eq!(visited(&faces), counted(&faces));
    let (edge, on) = bad_edge(&faces).expect("the fin is found");
    assert_eq!(edge, [0, 1]);
    assert_eq!(on, vec![0, 3, 4]);
    // Without the fin, the flipped face is the first bad edge: 3→4 twice.
    let faces = [[0, 1, 2], [0, 2, 3], [0, 3, 4], [1, 0, 5], [3, 4, 7]];
    assert_eq!(visited(&faces), counted(&faces));
    assert_eq!(bad_edge(&faces).map(|e| e.0), Some([3, 4]));
    // A closed, consistently oriented tetrahedron: every edge once each way.
    let tet = [[0, 2, 1], [0, 1, 3], [1, 2, 3], [2, 0, 3]];
    assert!(visited(&tet).iter().all(|&(_, _, f, r)| f == 1 && r == 1));
    assert_eq!(visited(&tet).len(), 6);
    assert!(bad_edge(&tet).is_none());
    assert!(visited(&[]).is_empty());
}
