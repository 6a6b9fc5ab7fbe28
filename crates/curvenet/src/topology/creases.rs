//! Creases: curves along which the surface folds (docs/design.md §13).
//!
//! A crease curve carries two normals per sample ([`crate::Curve::normals_right`]): `normals`
//! for the surface on its left (walking along the curve with `normals` up), `normals_right`
//! for the one on its right. Patches run counter-clockwise seen from outside, on the left of
//! their half-edges ([`super::cycles`]), so a half-edge along its segment's direction sees the
//! left normals and one against it the right normals: every patch knows its own normal at
//! every curve vertex of its border ([`patch_normals`]).
//!
//! The normal-control solve then runs on the mesh **cut open along the creases**
//! ([`Seams::cut`]): at a curve vertex the triangles around it fall into sectors separated by
//! the curve edges where the two patches' normals differ by more than
//! [`crate::Network::SMOOTH_CREASE_DEGREES`]; each sector gets its own copy of the vertex
//! with its own normal. The copies share the (fixed) position, so the surface stays
//! watertight; but on the cut mesh the normal propagation, the curvature guide, the fit and
//! the 3D iterations do not couple across the crease, which becomes a G0 seam — the copies
//! are open-boundary vertices of their sides (their one-sided Laplacian is no curvature: the
//! fit leaves their rows out, as on any open border, design.md §1 "Open boundaries").
//! [`Seams::merge`] maps a solution back onto the uncut mesh.

use super::cycles::Patch;
use super::resample::Resampled;
use super::{Graph, UnionFind};
use crate::curves::CurveSpline;
use crate::error::{Error, Result};
use crate::geom::mesh::Mesh;
use crate::geom::{fmt_point, DVec3};
use crate::network::Network;
use rayon::prelude::*;
use std::collections::HashMap;

/// Per segment of `g`, per vertex of `res.segment_vertices`: the unit normals `[left, right]`
/// of the segment's curve, from one spline per side through the curve's own normals (at nodes
/// too: not averaged with the other curves there). Needs the sides of a crease network
/// ([`crate::topology::SplitCurve::sides`]).
pub fn segment_sides(g: &Graph, res: &Resampled) -> Vec<Vec<[DVec3; 2]>> {
    let splines: Vec<[CurveSpline; 2]> = g
        .curves
        .par_iter()
        .map(|c| {
            let side = |k: usize| c.sides.iter().map(|s| s[k]).collect::<Vec<DVec3>>();
            [CurveSpline::fit(&c.points, &side(0), c.closed), CurveSpline::fit(&c.points, &side(1), c.closed)]
        })
        .collect();
    g.segments
        .par_iter()
        .zip(&res.segment_vertices)
        .map(|(seg, ids)| {
            let pieces = ids.len() - 1;
            let [l, r] = &splines[seg.curve];
            let (l, r) = (l.resample(seg.first, seg.last, pieces), r.resample(seg.first, seg.last, pieces));
            l.iter().zip(&r).map(|(a, b)| [a.1, b.1]).collect()
        })
        .collect()
}

/// What a patch knows at a curve vertex of its border.
#[derive(Clone, Copy, Debug)]
pub struct Side {
    /// The patch's unit normal: the side of each half-edge's curve the patch lies on (left
    /// along the segment's direction, right against it), averaged where two half-edges of the
    /// patch meet (at its corners).
    pub normal: DVec3,
    /// The normal curvature of the patch across its border there, `∂n/∂ν · ν`: measured at
    /// the corners along the neighbouring half-edges of the cycle (the curves that leave the
    /// border into the patch), interpolated linearly along each half-edge in between.
    pub across: f64,
}

/// Per patch, per curve vertex of its border: its [`Side`].
pub fn patch_normals(patches: &[Patch], res: &Resampled, sides: &[Vec<[DVec3; 2]>]) -> HashMap<(u32, u32), Side> {
    let mut sum: HashMap<(u32, u32), (DVec3, f64, usize)> = HashMap::new();
    // The patch side's vertices and normals of half-edge `h`, in traversal order.
    let walk = |h: super::HalfEdge| -> Vec<(u32, DVec3)> {
        let side = usize::from(!h.forward);
        let mut out: Vec<(u32, DVec3)> =
            res.segment_vertices[h.segment].iter().zip(&sides[h.segment]).map(|(&v, s)| (v, s[side])).collect();
        if !h.forward {
            out.reverse();
        }
        out
    };
    // Normal curvature between two consecutive vertices: (n₁ − n₀)·(p₁ − p₀)/|p₁ − p₀|².
    let curvature = |a: (u32, DVec3), b: (u32, DVec3)| {
        let e = res.positions[b.0 as usize] - res.positions[a.0 as usize];
        if e.length_squared() > 0.0 {
            (b.1 - a.1).dot(e) / e.length_squared()
        } else {
            0.0
        }
    };
    for (p, patch) in patches.iter().enumerate() {
        let cycles: Vec<&Vec<super::HalfEdge>> = match patch {
            Patch::Disk(c) => vec![c],
            Patch::Tube([a, b]) => vec![a, b],
        };
        for cycle in cycles {
            let walks: Vec<Vec<(u32, DVec3)>> = cycle.iter().map(|&h| walk(h)).collect();
            let m = walks.len();
            for (i, w) in walks.iter().enumerate() {
                let (prev, next) = (&walks[(i + m - 1) % m], &walks[(i + 1) % m]);
                let start = curvature(prev[prev.len() - 2], prev[prev.len() - 1]);
                let end = curvature(next[0], next[1]);
                let last = (w.len() - 1).max(1) as f64;
                for (k, &(v, n)) in w.iter().enumerate() {
                    let t = k as f64 / last;
                    let e = sum.entry((p as u32, v)).or_insert((DVec3::ZERO, 0.0, 0));
                    e.0 += n;
                    e.1 += (1.0 - t) * start + t * end;
                    e.2 += 1;
                }
            }
        }
    }
    sum.into_iter().map(|(k, (n, a, c))| (k, Side { normal: n.normalize_or_zero(), across: a / c as f64 })).collect()
}

/// Checks that every crease has its sides the right way round: at the corners of a patch
/// where a crease meets another curve, the normal the patch takes from the crease must agree
/// with the one it takes from the other curve (both are the patch's normal at one point). A
/// crease whose *other* side agrees at most of its corners has its `normals` and
/// `normals_right` swapped — an input error naming the curve and the corner, rather than a
/// surface folded along it.
pub fn check_sides(g: &Graph, patches: &[Patch], labels: &[String]) -> Result<()> {
    // Per crease curve: corners voting for its sides as given, corners voting for swapped.
    let mut votes: HashMap<usize, (usize, usize, Option<DVec3>)> = HashMap::new();
    let crease = |c: usize| g.curves[c].sides.iter().any(|s| s[0] != s[1]);
    let end = |h: super::HalfEdge, at_start: bool| -> [DVec3; 2] {
        let seg = &g.segments[h.segment];
        let c = &g.curves[seg.curve];
        let n = c.points.len();
        let sample = if at_start == h.forward { seg.first } else { seg.last } % n;
        let [l, r] = c.sides[sample];
        if h.forward {
            [l, r]
        } else {
            [r, l]
        }
    };
    let cycles: Vec<Vec<super::HalfEdge>> = patches
        .iter()
        .flat_map(|p| match p {
            Patch::Disk(c) => vec![c.clone()],
            Patch::Tube([a, b]) => vec![a.clone(), b.clone()],
        })
        .collect();
    for cycle in &cycles {
        for i in 0..cycle.len() {
            let (a, b) = (cycle[i], cycle[(i + 1) % cycle.len()]);
            // The corner at the node where `a` arrives and `b` leaves.
            let (ca, cb) = (g.segments[a.segment].curve, g.segments[b.segment].curve);
            for (h, at_start, other, oc) in [(a, false, b, cb), (b, true, a, ca)] {
                let hc = g.segments[h.segment].curve;
                if !crease(hc) || crease(oc) || hc == oc {
                    continue;
                }
                let [own, swapped] = end(h, at_start);
                let reference = end(other, !at_start)[0];
                let (keep, flip) = (own.angle_between(reference), swapped.angle_between(reference));
                let v = votes.entry(hc).or_insert((0, 0, None));
                if flip < 0.5 * keep && keep > 20f64.to_radians() {
                    v.1 += 1;
                    let node =
                        if at_start == h.forward { g.segments[h.segment].start } else { g.segments[h.segment].end };
                    v.2.get_or_insert(g.nodes[node].position);
                } else if keep < 0.5 * flip && flip > 20f64.to_radians() {
                    v.0 += 1;
                }
            }
        }
    }
    let mut bad: Vec<Votes> = votes.into_iter().filter(|(_, v)| v.1 > v.0).collect();
    bad.sort_by_key(|b| b.0);
    if let Some(&(c, (_, n, Some(at)))) = bad.first() {
        return Err(Error::input(format!(
            "{}: its `normals` and `normals_right` look swapped (at {n} corner(s) of its patches, e.g. {}, the other \
             side agrees with the curves it meets). Walking along the curve in sample order with `normals` up, \
             `normals` belongs to the surface on the left and `normals_right` to the one on the right",
            labels[c],
            fmt_point(at)
        ))
        .curve(c)
        .point(at));
    }
    Ok(())
}

/// Per curve vertex: the sector of each face around it, and per sector its normal and its
/// curvature across ([`Side::across`]).
type Sectors = (Vec<u32>, Vec<(DVec3, f64)>);

/// Per crease curve with swapped-side votes: (curve, (votes as given, votes swapped, a corner)).
type Votes = (usize, (usize, usize, Option<DVec3>));

/// The mesh cut open along its creases, and the way back (module documentation).
#[derive(Clone, Debug)]
pub struct Seams {
    /// The cut mesh: each curve vertex where the surface folds has one copy per side (the
    /// copies come right after the uncut mesh's curve vertices, so that curve vertices still
    /// come first), with that side's normal; the copies are open-boundary vertices.
    pub mesh: Mesh,
    /// Per vertex of `mesh`: the vertex of the uncut mesh it stands for.
    pub original: Vec<u32>,
    /// Number of curve vertices cut (with two or more sides).
    pub cut: usize,
}

impl Seams {
    /// Cuts `mesh` (faces tagged with the index of their patch in `normals`' keys) where the
    /// patches' normals at a curve vertex differ by more than
    /// [`Network::SMOOTH_CREASE_DEGREES`]. Curve vertices not cut take the mean of their
    /// patches' normals. `None` when nothing is cut.
    pub fn cut(mesh: &Mesh, normals: &HashMap<(u32, u32), Side>) -> Option<Seams> {
        let nc = mesh.num_curve;
        let mut around: Vec<Vec<u32>> = vec![Vec::new(); nc];
        for (f, face) in mesh.faces.iter().enumerate() {
            for &v in face {
                if (v as usize) < nc {
                    around[v as usize].push(f as u32);
                }
            }
        }
        let smooth = Network::SMOOTH_CREASE_DEGREES.to_radians().cos();
        let normal_of = |p: u32, v: u32| normals.get(&(p, v)).map_or(mesh.curve_normals[v as usize], |s| s.normal);
        let across_of = |p: u32, v: u32| normals.get(&(p, v)).map_or(f64::NAN, |s| s.across);
        // Per curve vertex: per incident face, its sector; per sector, its normal.
        let sectors: Vec<Sectors> = around
            .par_iter()
            .enumerate()
            .map(|(v, faces)| {
                let v = v as u32;
                let mut uf = UnionFind::new(faces.len());
                let mut by_edge: HashMap<u32, usize> = HashMap::new();
                for (k, &f) in faces.iter().enumerate() {
                    for &w in mesh.faces[f as usize].iter().filter(|&&w| w != v) {
                        if let Some(&j) = by_edge.get(&w) {
                            let (pa, pb) = (mesh.face_patch[faces[j] as usize], mesh.face_patch[f as usize]);
                            if pa == pb || normal_of(pa, v).dot(normal_of(pb, v)) >= smooth {
                                uf.union(j, k);
                            }
                        } else {
                            by_edge.insert(w, k);
                        }
                    }
                }
                let mut group = vec![0u32; faces.len()];
                let mut roots: Vec<usize> = Vec::new();
                let mut sums: Vec<HashMap<u32, DVec3>> = Vec::new();
                for k in 0..faces.len() {
                    let r = uf.find(k);
                    let g = roots.iter().position(|&x| x == r).unwrap_or_else(|| {
                        roots.push(r);
                        sums.push(HashMap::new());
                        roots.len() - 1
                    });
                    group[k] = g as u32;
                    let p = mesh.face_patch[faces[k] as usize];
                    sums[g].entry(p).or_insert_with(|| normal_of(p, v));
                }
                let normals = sums
                    .iter()
                    .map(|s| {
                        let n = s.values().sum::<DVec3>().normalize_or_zero();
                        let n = if n == DVec3::ZERO { mesh.curve_normals[v as usize] } else { n };
                        let across = s.keys().map(|&p| across_of(p, v)).sum::<f64>() / s.len() as f64;
                        (n, across)
                    })
                    .collect();
                (group, normals)
            })
            .collect();
        let extra: usize = sectors.iter().map(|s| s.1.len().saturating_sub(1)).sum();
        let cut = sectors.iter().filter(|s| s.1.len() > 1).count();
        let mut out = mesh.clone();
        out.pattern = Default::default();
        out.curve_normals = sectors.iter().map(|s| s.1.first().map_or(DVec3::ZERO, |x| x.0)).collect();
        let mut across: Vec<f64> = sectors.iter().map(|s| s.1.first().map_or(f64::NAN, |x| x.1)).collect();
        if extra == 0 {
            return None;
        }
        let shift = |v: u32| if (v as usize) < nc { v } else { v + extra as u32 };
        let mut original: Vec<u32> = (0..mesh.num_vertices() as u32).collect();
        let mut copies: Vec<u32> = Vec::with_capacity(extra);
        for f in out.faces.iter_mut() {
            for v in f.iter_mut() {
                *v = shift(*v);
            }
        }
        for (v, (group, normals)) in sectors.iter().enumerate() {
            if normals.len() < 2 {
                continue;
            }
            out.on_boundary[v] = true;
            let first = (nc + copies.len()) as u32;
            for (k, &f) in around[v].iter().enumerate() {
                if group[k] > 0 {
                    // (`around[v]` lists the faces that hold `v`.)
                    for x in out.faces[f as usize].iter_mut().filter(|x| **x == v as u32) {
                        *x = first + group[k] - 1;
                    }
                }
            }
            for &(n, a) in &normals[1..] {
                copies.push(v as u32);
                out.curve_normals.push(n);
                across.push(a);
            }
        }
        let tail = out.positions.split_off(nc);
        let copied: Vec<DVec3> = copies.iter().map(|&v| out.positions[v as usize]).collect();
        out.positions.extend(copied);
        out.positions.extend(tail);
        let tail = out.on_boundary.split_off(nc);
        out.on_boundary.extend(copies.iter().map(|_| true));
        out.on_boundary.extend(tail);
        let tail = original.split_off(nc);
        original.extend(&copies);
        original.extend(tail);
        out.num_curve = nc + extra;
        out.seam_rows = seam_rows(&out, &copies, &sectors, &across, nc);
        Some(Seams { mesh: out, original, cut })
    }

    /// Per-vertex values of the cut mesh on the uncut one (a vertex takes its first copy's).
    pub fn merge<T: Clone>(&self, values: &[T]) -> Vec<T> {
        // Copies point back to curve vertices that come before them, so the vertices seen for
        // the first time are the uncut mesh's, in its order.
        let mut seen = vec![false; self.original.len()];
        let mut out = Vec::with_capacity(self.original.len());
        for (i, &v) in self.original.iter().enumerate() {
            if !std::mem::replace(&mut seen[v as usize], true) {
                out.push(values[i].clone());
            }
        }
        out
    }
}

/// The seam rows of the cut mesh `mesh` ([`Mesh::seam_rows`]): for every copy of a cut vertex
/// (the vertices `v < nc` with two or more `sectors`, and the `copies` after them), `½ Σ |e| ν_e`
/// over its open edges. Faces run counter-clockwise seen from outside, so an open edge `p → q`
/// of a face has the face on its left and the outward conormal `(q − p) × n` on its right.
fn seam_rows(mesh: &Mesh, copies: &[u32], sectors: &[Sectors], across: &[f64], nc: usize) -> Vec<(u32, [DVec3; 2])> {
    let mut seam = vec![false; mesh.num_curve];
    for (v, s) in sectors.iter().enumerate() {
        seam[v] = s.1.len() > 1;
    }
    for k in 0..copies.len() {
        seam[nc + k] = true;
    }
    let mut edges: HashMap<(u32, u32), (usize, [u32; 2])> = HashMap::new();
    for f in &mesh.faces {
        for k in 0..3 {
            let (p, q) = (f[k], f[(k + 1) % 3]);
            let touches = |v: u32| seam.get(v as usize).copied().unwrap_or(false);
            if touches(p) || touches(q) {
                let e = edges.entry((p.min(q), p.max(q))).or_insert((0, [p, q]));
                e.0 += 1;
            }
        }
    }
    let mut rows: HashMap<u32, [DVec3; 2]> = HashMap::new();
    for (count, [p, q]) in edges.into_values() {
        if count != 1 {
            continue;
        }
        let e = mesh.positions[q as usize] - mesh.positions[p as usize];
        let (np, nq) = (mesh.curve_normals[p as usize], mesh.curve_normals[q as usize]);
        let nu = e.cross(np + nq).normalize_or_zero();
        // The normal's derivative across the seam, S ν = κ_ν ν + (ν · S t) t (S the shape
        // operator, symmetric): κ_ν measured where curves leave the seam (`across`; the
        // curvature along the edge where nothing was measured), ν · S t along the edge.
        let along = (nq - np).dot(e) / e.length_squared();
        let twist = (nq - np).dot(nu);
        for a in [p, q] {
            if seam.get(a as usize).copied().unwrap_or(false) {
                let kappa = across.get(a as usize).copied().filter(|x| x.is_finite()).unwrap_or(along);
                let r = rows.entry(a).or_insert([DVec3::ZERO; 2]);
                r[0] += 0.5 * e.length() * nu;
                r[1] += 0.5 * (e.length() * kappa * nu + twist * e / e.length());
            }
        }
    }
    let mut rows: Vec<(u32, [DVec3; 2])> = rows.into_iter().collect();
    rows.sort_by_key(|r| r.0);
    rows
}
