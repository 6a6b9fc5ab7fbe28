//! The cross field of the principal curves ([`super::principal`]): a smooth field of four
//! directions at right angles on the faces (a 4-RoSy field), aligned with the principal
//! curvature directions where the surface is clearly anisotropic and with a fixed axis
//! projected on the surface where it is not (planes, spheres). Per face, the second
//! fundamental form is fitted to the vertex normals' differences along its edges
//! (Rusinkiewicz 2004), its principal direction enters the field with the weight
//! `(κ₁ − κ₂) / (|κ₁| + |κ₂| + κ₀)`, and the field is smoothed across the edges (the angle
//! measured from the shared edge is carried over, times 4). Each face holds the field as a
//! unit complex number `z = exp(4iθ)`, `θ` the angle of one of the four directions in the
//! face's [`Frame`].

use super::mesh::Mesh;
use crate::geom::{DVec2, DVec3};

/// Smoothing sweeps of the cross field.
const SMOOTHING_SWEEPS: usize = 150;
/// Weight of the projected axis in the field (relative to a fully anisotropic face).
const AXIS_WEIGHT: f64 = 0.1;

/// An orthonormal frame of a face: origin `o` at its first corner, `e1` along its first edge,
/// `e2 = n × e1`, `n` its unit normal (zero vectors for a degenerate face).
#[derive(Clone, Copy)]
pub(super) struct Frame {
    /// Origin (the face's first corner).
    pub(super) o: DVec3,
    /// First axis, along the face's first edge.
    pub(super) e1: DVec3,
    /// Second axis, `n × e1`.
    pub(super) e2: DVec3,
    /// The face's unit normal.
    pub(super) n: DVec3,
}

impl Frame {
    /// The frame of the triangle `a`, `b`, `c`.
    fn of(a: DVec3, b: DVec3, c: DVec3) -> Frame {
        let n = (b - a).cross(c - a).normalize_or_zero();
        let e1 = (b - a).normalize_or_zero();
        Frame { o: a, e1, e2: n.cross(e1), n }
    }
    /// Point `p` in frame coordinates (projected on the face's plane).
    pub(super) fn to2(&self, p: DVec3) -> DVec2 {
        DVec2::new((p - self.o).dot(self.e1), (p - self.o).dot(self.e2))
    }
    /// The point of the face's plane with frame coordinates `q`.
    pub(super) fn to3(&self, q: DVec2) -> DVec3 {
        self.o + q.x * self.e1 + q.y * self.e2
    }
    /// Direction `d` in frame coordinates (projected on the face's plane).
    pub(super) fn dir2(&self, d: DVec3) -> DVec2 {
        DVec2::new(d.dot(self.e1), d.dot(self.e2))
    }
}

/// The cross field on the faces of a mesh (see the module documentation).
pub(super) struct CrossField {
    /// The frame of each face.
    pub(super) frames: Vec<Frame>,
    /// Whether each face has a frame (non-zero normal and first edge); the others have no
    /// field.
    pub(super) good: Vec<bool>,
    /// Per face: `exp(4iθ)` as a 2D vector.
    z: Vec<DVec2>,
}

impl CrossField {
    /// The smoothed cross field of `mesh`, oriented by `axis` where the surface is isotropic;
    /// curvatures are measured against `κ₀ = 1 / diag`.
    pub(super) fn new(mesh: &Mesh, axis: DVec3, diag: f64) -> CrossField {
        let frames: Vec<Frame> = mesh
            .faces
            .iter()
            .map(|f| {
                let [a, b, c] = f.map(|v| mesh.positions[v as usize]);
                Frame::of(a, b, c)
            })
            .collect();
        let good: Vec<bool> = frames.iter().map(|f| f.n != DVec3::ZERO && f.e1 != DVec3::ZERO).collect();
        let prior = prior(mesh, &frames, &good, axis, diag);
        let adj = adjacency(mesh, &frames, &good);
        let mut z: Vec<DVec2> = prior.iter().map(|p| p.normalize_or_zero()).collect();
        for _ in 0..SMOOTHING_SWEEPS {
            for fi in 0..frames.len() {
                let mut s = prior[fi];
                for &(g, r) in &adj[fi] {
                    s += r.rotate(z[g]);
                }
                if s.length() > 1e-12 {
                    z[fi] = s.normalize();
                }
            }
        }
        CrossField { frames, good, z }
    }

    /// The field direction of face `fi` closest to `d` (3D, tangent): a unit vector in the
    /// face's plane.
    pub(super) fn dir(&self, fi: usize, d: DVec3) -> DVec3 {
        let fr = self.frames[fi];
        let theta = self.z[fi].y.atan2(self.z[fi].x) / 4.0;
        let d2 = fr.dir2(d);
        let mut best = (f64::NEG_INFINITY, DVec3::ZERO);
        for k in 0..4 {
            let u = DVec2::from_angle(theta + k as f64 * std::f64::consts::FRAC_PI_2);
            let s = u.dot(d2);
            if s > best.0 {
                best = (s, fr.e1 * u.x + fr.e2 * u.y);
            }
        }
        best.1
    }
}

/// The field each face wants before smoothing (zero for faces that are not `good`): its
/// principal direction weighted by the anisotropy `(κ₁ − κ₂) / (|κ₁| + |κ₂| + 1/diag)`, plus
/// `axis` projected on the face with weight [`AXIS_WEIGHT`] × the projection's length.
fn prior(mesh: &Mesh, frames: &[Frame], good: &[bool], axis: DVec3, diag: f64) -> Vec<DVec2> {
    let (positions, normals) = (&mesh.positions, &mesh.normals);
    let kappa0 = 1.0 / diag;
    let mut prior = vec![DVec2::ZERO; frames.len()];
    for (fi, f) in mesh.faces.iter().enumerate() {
        if !good[fi] {
            continue;
        }
        let fr = frames[fi];
        // Second fundamental form [[a, b], [b, c]] from the three edges.
        let (mut ata, mut atb) = (glam::DMat3::ZERO, glam::DVec3::ZERO);
        for k in 0..3 {
            let (i, j) = (f[k] as usize, f[(k + 1) % 3] as usize);
            let e = fr.dir2(positions[j] - positions[i]);
            let dn = fr.dir2(normals[j] - normals[i]);
            for (row, rhs) in [(DVec3::new(e.x, e.y, 0.0), dn.x), (DVec3::new(0.0, e.x, e.y), dn.y)] {
                ata += glam::DMat3::from_cols(row * row.x, row * row.y, row * row.z);
                atb += row * rhs;
            }
        }
        let abc = if ata.determinant().abs() > 1e-30 { ata.inverse() * atb } else { DVec3::ZERO };
        let (a, b, c) = (abc.x, abc.y, abc.z);
        let aniso = ((a - c).powi(2) + 4.0 * b * b).sqrt();
        let trace_abs = {
            let m = 0.5 * (a + c);
            (m + 0.5 * aniso).abs() + (m - 0.5 * aniso).abs()
        };
        let w = aniso / (trace_abs + kappa0);
        let theta = 0.5 * (2.0 * b).atan2(a - c);
        let mut z = w * DVec2::from_angle(4.0 * theta);
        let g = fr.dir2(axis);
        if g.length() > 1e-6 {
            z += AXIS_WEIGHT * g.length() * DVec2::from_angle(4.0 * g.y.atan2(g.x));
        }
        prior[fi] = z;
    }
    prior
}

/// Per face: the `good` faces across its edges, each with the rotation (a unit complex number,
/// times 4) from that face's frame to this one's across the shared edge: the angle measured
/// from the edge is the same in both.
fn adjacency(mesh: &Mesh, frames: &[Frame], good: &[bool]) -> Vec<Vec<(usize, DVec2)>> {
    let edge_angle = |fi: usize, a: u32, b: u32| -> f64 {
        let d = frames[fi].dir2(mesh.positions[b as usize] - mesh.positions[a as usize]);
        d.y.atan2(d.x)
    };
    let mut adj: Vec<Vec<(usize, DVec2)>> = vec![Vec::new(); frames.len()];
    for (fi, f) in mesh.faces.iter().enumerate() {
        for k in 0..3 {
            if let Some(g) = mesh.across(fi, k) {
                if good[fi] && good[g] {
                    let (a, b) = (f[k], f[(k + 1) % 3]);
                    let rot = 4.0 * (edge_angle(fi, a, b) - edge_angle(g, a, b));
                    adj[fi].push((g, DVec2::from_angle(rot)));
                }
            }
        }
    }
    adj
}

#[cfg(test)]
#[path = "tests/cross_field.rs"]
mod tests;
