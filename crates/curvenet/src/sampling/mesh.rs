//! Stage 1, the mesh: the input checked ([`check_mesh`]) and repaired ([`Mesh::repaired`]):
//! vertices at the same position welded, cracks zipped ([`zip_cracks`]), pinch vertices split
//! ([`split_pinches`]); then its angle-weighted vertex normals ([`crate::operators::angle_weighted_normals`]) and the
//! faces around each edge, which must be at most two (a 2-manifold with boundary).

use super::creases;
use crate::error::{Error, Result};
use crate::geom::{Aabb, DVec3};
use std::collections::HashMap;

/// The faces around each undirected edge ([`edge_key`]): one for a boundary edge, two inside.
pub(super) type EdgeFaces = HashMap<(u32, u32), Vec<usize>>;

/// The repaired mesh the curves are traced on.
pub(super) struct Mesh {
    /// Vertex positions (welded groups moved to their mean, split pinches appended).
    pub(super) positions: Vec<DVec3>,
    /// Triangles, counter-clockwise seen from outside, none degenerate in its indices.
    pub(super) faces: Vec<[u32; 3]>,
    /// Unit angle-weighted vertex normals ([`crate::operators::angle_weighted_normals`]).
    pub(super) normals: Vec<DVec3>,
    /// The faces around each edge ([`EdgeFaces`]).
    pub(super) edge_faces: EdgeFaces,
    /// Per vertex: the vertex of the repaired mesh before the cut along its creases
    /// ([`super::creases::cut_creases`]) it is a copy of.
    pub(super) original: Vec<u32>,
    /// The sharp edges ([`edge_key`] of `original` vertices) the mesh was cut along.
    pub(super) sharp: std::collections::HashSet<(u32, u32)>,
}

/// What [`Mesh::repaired`] changed, for the [`super::SampleReport`].
pub(super) struct Repairs {
    /// Boundary vertices welded across cracks ([`zip_cracks`]).
    pub(super) zipped: usize,
    /// Pinch vertices split ([`split_pinches`]).
    pub(super) pinches: usize,
    /// Chains of sharp edges left smooth ([`super::creases::kept_creases`]).
    pub(super) smoothed_creases: usize,
}

/// Checks the input mesh: faces, vertex indices in range, finite coordinates, non-zero extent.
/// Returns the bounding box of the vertices used by the faces.
///
/// Errors: [`Error::Input`] naming the face or vertex at fault.
pub(super) fn check_mesh(positions: &[DVec3], faces: &[[u32; 3]]) -> Result<Aabb> {
    if faces.is_empty() {
        return Err(Error::input("the mesh has no faces: there is nothing to sample"));
    }
    for (fi, f) in faces.iter().enumerate() {
        for &v in f {
            if v as usize >= positions.len() {
                return Err(Error::input(format!(
                    "face {fi} uses vertex {v} but the mesh has {} vertices",
                    positions.len()
                )));
            }
        }
    }
    if let Some(i) = positions.iter().position(|p| !p.is_finite()) {
        return Err(Error::input(format!("mesh vertex {i} has a non-finite coordinate")).vertex(i));
    }
    let bbox = Aabb::of(faces.iter().flatten().map(|&v| positions[v as usize]));
    let diag = bbox.diagonal();
    if !(diag > 0.0 && diag.is_finite()) {
        return Err(Error::input("the mesh has zero extent"));
    }
    Ok(bbox)
}

impl Mesh {
    /// The checked input mesh repaired for tracing: vertices at the same position welded
    /// (unwelded seams would read as boundary), faces that degenerate dropped, cracks narrower
    /// than `near` zipped and pinch vertices split apart by `near` (see [`zip_cracks`],
    /// [`split_pinches`]); with its vertex normals and edge adjacency.
    ///
    /// Errors: [`Error::Input`] for an edge shared by more than two faces (naming the edge).
    /// With `creases`, the repaired mesh is then cut open along its sharp edges
    /// (those [`super::creases::kept_creases`] keeps, [`super::creases::cut_creases`]): its
    /// vertex normals are those of each side.
    pub(super) fn repaired(
        positions: &[DVec3],
        faces: &[[u32; 3]],
        near: f64,
        creases: Option<creases::CreaseCut<'_>>,
    ) -> Result<(Mesh, Repairs)> {
        let mut welded = weld(positions, faces);
        let mut moved = positions.to_vec();
        let zipped = zip_cracks(&mut moved, &mut welded, near);
        let pinches = split_pinches(&mut moved, &mut welded, near);
        check_manifold(&edge_faces(&welded), positions.len())?;
        let mut smoothed_creases = 0;
        let (original, sharp) = match creases {
            Some(c) => {
                let sharp = creases::sharp_edges(&moved, &welded, c.angle);
                let (kept, smoothed) = creases::kept_creases(&moved, sharp, &c, near);
                smoothed_creases = smoothed;
                creases::cut_creases(&mut moved, &mut welded, kept)
            }
            None => ((0..moved.len() as u32).collect(), Default::default()),
        };
        let normals = crate::operators::angle_weighted_normals(&welded, &moved);
        let edge_faces = edge_faces(&welded);
        let mesh = Mesh { positions: moved, faces: welded, normals, edge_faces, original, sharp };
        Ok((mesh, Repairs { zipped, pinches, smoothed_creases }))
    }

    /// Whether the edge from `a` to `b` lies on a crease the mesh was cut along.
    pub(super) fn on_crease(&self, a: u32, b: u32) -> bool {
        !self.sharp.is_empty() && self.sharp.contains(&edge_key(self.original[a as usize], self.original[b as usize]))
    }

    /// Whether `e` ([`edge_key`]) is an edge of one face only.
    pub(super) fn is_boundary(&self, e: (u32, u32)) -> bool {
        self.edge_faces.get(&e).is_some_and(|f| f.len() == 1)
    }

    /// The face across local edge `k` (`f[k]` → `f[k + 1]`) of face `fi`, if the edge has two.
    pub(super) fn across(&self, fi: usize, k: usize) -> Option<usize> {
        let f = self.faces[fi];
        let e = edge_key(f[k], f[(k + 1) % 3]);
        self.edge_faces.get(&e).and_then(|l| (l.len() == 2).then(|| if l[0] == fi { l[1] } else { l[0] }))
    }
}

/// `faces` with each vertex replaced by the first vertex at the same position (`-0.0` and
/// `0.0` alike), and the faces that degenerate (two corners the same) left out.
fn weld(positions: &[DVec3], faces: &[[u32; 3]]) -> Vec<[u32; 3]> {
    let mut first_at: HashMap<[u64; 3], u32> = HashMap::new();
    let weld: Vec<u32> = positions
        .iter()
        .enumerate()
        .map(|(i, p)| {
            let key = (*p + DVec3::ZERO).to_array().map(f64::to_bits);
            *first_at.entry(key).or_insert(i as u32)
        })
        .collect();
    faces.iter().map(|f| f.map(|v| weld[v as usize])).filter(|f| f[0] != f[1] && f[1] != f[2] && f[0] != f[2]).collect()
}

/// The faces around each undirected edge of `faces`.
pub(super) fn edge_faces(faces: &[[u32; 3]]) -> EdgeFaces {
    let mut edge_faces: EdgeFaces = HashMap::new();
    for (fi, f) in faces.iter().enumerate() {
        for k in 0..3 {
            let (a, b) = (f[k], f[(k + 1) % 3]);
            if a == b {
                continue;
            }
            edge_faces.entry(edge_key(a, b)).or_default().push(fi);
        }
    }
    edge_faces
}

/// An [`Error::Input`] if an edge has more than two faces, naming the edge (and its first
/// vertex as the error's place when it is one of the `input_vertices` of the input mesh, not a
/// copy made by [`split_pinches`]).
fn check_manifold(edge_faces: &EdgeFaces, input_vertices: usize) -> Result<()> {
    if let Some((e, fs)) = edge_faces.iter().find(|(_, fs)| fs.len() > 2) {
        let err = Error::input(format!(
            "the mesh is not a 2-manifold: edge between vertices {} and {} is shared by {} faces",
            e.0,
            e.1,
            fs.len()
        ));
        return Err(if (e.0 as usize) < input_vertices { err.vertex(e.0 as usize) } else { err });
    }
    Ok(())
}

/// The key of the undirected edge between vertices `a` and `b`: the smaller index first.
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
