//! Mesh checks and repairs: welding, cracks zipped, pinches split, vertex normals, edge keys.

use crate::geom::DVec3;
use std::collections::HashMap;

/// Angle-weighted vertex normals (each face's unit normal weighted by its corner angle), unit
/// length; zero for a vertex of degenerate faces only.
pub fn vertex_normals(positions: &[DVec3], faces: &[[u32; 3]]) -> Vec<DVec3> {
    let mut n = vec![DVec3::ZERO; positions.len()];
    for f in faces {
        let p = f.map(|i| positions[i as usize]);
        let fnrm = (p[1] - p[0]).cross(p[2] - p[0]).normalize_or_zero();
        if fnrm == DVec3::ZERO {
            continue;
        }
        for k in 0..3 {
            let (a, b) = (p[(k + 1) % 3] - p[k], p[(k + 2) % 3] - p[k]);
            let angle = a.angle_between(b);
            if angle.is_finite() {
                n[f[k] as usize] += angle * fnrm;
            }
        }
    }
    n.iter().map(|v| v.normalize_or_zero()).collect()
}

pub(super) fn edge_key(a: u32, b: u32) -> (u32, u32) {
    (a.min(b), a.max(b))
}

/// Closes cracks in the mesh: a boundary vertex closer than `tol` to a boundary vertex it
/// shares no face with (the two sides of a narrow slit, an unwelded seam with a small gap) is
/// welded to it (both move to their midpoint). Faces that degenerate are dropped. Nothing is
/// changed if welding would make an edge non-manifold. Returns the number of vertices welded.
pub fn zip_cracks(positions: &mut [DVec3], faces: &mut Vec<[u32; 3]>, tol: f64) -> usize {
    let mut count: HashMap<(u32, u32), usize> = HashMap::new();
    for f in faces.iter() {
        for k in 0..3 {
            *count.entry(edge_key(f[k], f[(k + 1) % 3])).or_default() += 1;
        }
    }
    let mut boundary: Vec<u32> =
        count.iter().filter(|(_, &c)| c == 1).flat_map(|(e, _)| [e.0, e.1]).collect::<Vec<_>>();
    boundary.sort_unstable();
    boundary.dedup();
    if boundary.is_empty() {
        return 0;
    }
    let mut neighbours: HashMap<u32, Vec<u32>> = HashMap::new();
    for f in faces.iter() {
        for &a in f {
            for &b in f {
                if a != b {
                    neighbours.entry(a).or_default().push(b);
                }
            }
        }
    }
    let h = tol.max(f64::MIN_POSITIVE);
    let cell = |p: DVec3| ((p.x / h).floor() as i64, (p.y / h).floor() as i64, (p.z / h).floor() as i64);
    let mut grid: HashMap<(i64, i64, i64), Vec<u32>> = HashMap::new();
    for &v in &boundary {
        grid.entry(cell(positions[v as usize])).or_default().push(v);
    }
    let mut uf = crate::topology::UnionFind::new(positions.len());
    let mut welded = 0;
    for &v in &boundary {
        let p = positions[v as usize];
        let c = cell(p);
        for dx in -1..=1 {
            for dy in -1..=1 {
                for dz in -1..=1 {
                    for &w in grid.get(&(c.0 + dx, c.1 + dy, c.2 + dz)).map_or(&[][..], |l| &l[..]) {
                        if w > v
                            && positions[w as usize].distance(p) <= tol
                            && !neighbours.get(&v).is_some_and(|n| n.contains(&w))
                        {
                            uf.union(v as usize, w as usize);
                            welded += 1;
                        }
                    }
                }
            }
        }
    }
    if welded == 0 {
        return 0;
    }
    let new_faces: Vec<[u32; 3]> = faces
        .iter()
        .map(|f| f.map(|v| uf.find(v as usize) as u32))
        .filter(|f| f[0] != f[1] && f[1] != f[2] && f[0] != f[2])
        .collect();
    let mut count: HashMap<(u32, u32), usize> = HashMap::new();
    for f in &new_faces {
        for k in 0..3 {
            *count.entry(edge_key(f[k], f[(k + 1) % 3])).or_default() += 1;
        }
    }
    if count.values().any(|&c| c > 2) {
        return 0;
    }
    // Move each welded group to its mean.
    let mut sum: HashMap<usize, (DVec3, usize)> = HashMap::new();
    for &v in &boundary {
        let r = uf.find(v as usize);
        let e = sum.entry(r).or_insert((DVec3::ZERO, 0));
        e.0 += positions[v as usize];
        e.1 += 1;
    }
    for (r, (s, n)) in sum {
        if n > 1 {
            positions[r] = s / n as f64;
        }
    }
    *faces = new_faces;
    welded
}

/// Splits every vertex whose faces form several fans (a pinch: the boundary touches itself
/// there, or two sheets meet at a point) into one vertex per fan, and moves each copy towards
/// the mean of its fan's other vertices by `offset` (at most 40% of the way), so that the
/// boundary curves through it do not touch. Returns the number of vertices split.
pub fn split_pinches(positions: &mut Vec<DVec3>, faces: &mut [[u32; 3]], offset: f64) -> usize {
    let mut faces_of: Vec<Vec<usize>> = vec![Vec::new(); positions.len()];
    for (fi, f) in faces.iter().enumerate() {
        for &v in f {
            faces_of[v as usize].push(fi);
        }
    }
    let mut split = 0;
    for v in 0..faces_of.len() {
        let fs = std::mem::take(&mut faces_of[v]);
        if fs.len() < 2 {
            continue;
        }
        // Fans: faces around v joined through the edges (v, w) they share.
        let mut fan = vec![usize::MAX; fs.len()];
        let mut count = 0;
        for start in 0..fs.len() {
            if fan[start] != usize::MAX {
                continue;
            }
            fan[start] = count;
            let mut stack = vec![start];
            while let Some(i) = stack.pop() {
                let fi = &faces[fs[i]];
                for (j, gj) in fs.iter().enumerate() {
                    let shares = fi.iter().filter(|&&w| w != v as u32 && faces[*gj].contains(&w)).count() > 0;
                    if fan[j] == usize::MAX && shares {
                        fan[j] = count;
                        stack.push(j);
                    }
                }
            }
            count += 1;
        }
        if count < 2 {
            continue;
        }
        split += 1;
        let p = positions[v];
        for k in 0..count {
            let members: Vec<usize> = (0..fs.len()).filter(|&i| fan[i] == k).map(|i| fs[i]).collect();
            let others: Vec<DVec3> = members
                .iter()
                .flat_map(|&fi| faces[fi].iter().copied().filter(|&w| w != v as u32).collect::<Vec<_>>())
                .map(|w| positions[w as usize])
                .collect();
            let mean = others.iter().sum::<DVec3>() / others.len().max(1) as f64;
            let step = (mean - p).clamp_length_max((0.4 * (mean - p).length()).min(offset));
            let id = if k == 0 {
                v as u32
            } else {
                positions.push(p);
                (positions.len() - 1) as u32
            };
            positions[id as usize] = p + step;
            for fi in members {
                for w in faces[fi].iter_mut() {
                    if *w == v as u32 {
                        *w = id;
                    }
                }
            }
        }
    }
    split
}
