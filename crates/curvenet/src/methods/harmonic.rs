//! k-harmonic interpolation on a given mesh: `Δᵏ X = 0` on the free vertices with `X = bc` on
//! the fixed ones, for any number of columns (positions, weights, colours).
//!
//! The operators are the library's own ([`crate::operators`]) on the 3D positions: the
//! cotangent Laplacian `Ls` and the mixed Voronoi mass matrix `M` of Meyer, Desbrun, Schröder
//! and Barr 2003 (Voronoi areas, half / quarter of the triangle for obtuse ones). The systems
//! are those of the [`crate::methods::polyharmonic`] baselines (\[CG\] §4.3) in symmetric form:
//!
//! - `k = 1`: `(−Ls)_ff X_f = (Ls)_fc X_c`;
//! - `k = 2`: `(Ls M⁻¹ Ls)_ff X_f = −(Ls M⁻¹ Ls)_fc X_c`;
//! - `k = 3`: `(−Ls M⁻¹ Ls M⁻¹ Ls)_ff X_f = …`,
//!
//! which are the systems of libigl's `igl::harmonic(V, F, b, bc, k)`: its quadratic form is
//! `(−L)(M⁻¹(−L))ᵏ⁻¹` with `cotmatrix` (= `Ls`) and `massmatrix(MASSMATRIX_TYPE_DEFAULT)`,
//! which for triangles is `VORONOI`, the same mixed area. Used by the Python bindings' interop
//! check against libigl.

use crate::error::{Error, Result};
use crate::geom::mesh::Mesh;
use crate::geom::DVec3;
use crate::operators::{cotan_operators, Metric};
use crate::solve::Eliminated;
use faer::Mat;

/// Solves `Δᵏ X = 0` (`order` k = 1, 2 or 3) on the mesh `(positions, faces)` with the rows
/// `fixed[i]` of `X` set to `values[i·columns .. (i+1)·columns]` (row-major `|fixed| × columns`).
/// Returns `X`, row-major `#V × columns`, with the fixed rows equal to `values`.
///
/// Errors with [`Error::usage`] when an index is out of range, a fixed vertex repeats, the
/// sizes disagree or the order is unsupported, and [`Error::Numerical`] when a vertex has no
/// area (isolated, or degenerate triangles) or a free component touches no fixed vertex.
pub fn harmonic(
    positions: &[DVec3],
    faces: &[[u32; 3]],
    fixed: &[usize],
    values: &[f64],
    columns: usize,
    order: usize,
) -> Result<Vec<f64>> {
    let n = positions.len();
    if !(1..=3).contains(&order) {
        return Err(Error::usage(format!("harmonic order k = {order} is not supported (1, 2 or 3)")));
    }
    if let Some(i) = positions.iter().position(|p| !p.is_finite()) {
        return Err(Error::usage(format!("vertex {i} is not finite")));
    }
    for (fi, f) in faces.iter().enumerate() {
        if let Some(k) = (0..3).find(|&k| f[k] as usize >= n) {
            return Err(Error::usage(format!("face {fi}, corner {k}: vertex {} out of range ({n} vertices)", f[k])));
        }
    }
    if fixed.is_empty() {
        return Err(Error::usage("no fixed vertex: Δᵏ X = 0 has no unique solution without one"));
    }
    if values.len() != fixed.len() * columns {
        return Err(Error::usage(format!(
            "{} fixed vertices with {columns} columns need {} values, got {}",
            fixed.len(),
            fixed.len() * columns,
            values.len()
        )));
    }
    // New order: the fixed vertices first (as listed), then the free ones.
    let mut new_of_old = vec![u32::MAX; n];
    for (k, &v) in fixed.iter().enumerate() {
        if v >= n {
            return Err(Error::usage(format!("fixed vertex {v} (entry {k}) out of range ({n} vertices)")));
        }
        if new_of_old[v] != u32::MAX {
            return Err(Error::usage(format!("fixed vertex {v} is listed twice (entry {k})")));
        }
        new_of_old[v] = k as u32;
    }
    let nb = fixed.len();
    let mut old_of_new: Vec<usize> = fixed.to_vec();
    for (v, slot) in new_of_old.iter_mut().enumerate() {
        if *slot == u32::MAX {
            *slot = old_of_new.len() as u32;
            old_of_new.push(v);
        }
    }
    let mut out = vec![0.0; n * columns];
    for (k, &v) in fixed.iter().enumerate() {
        out[v * columns..(v + 1) * columns].copy_from_slice(&values[k * columns..(k + 1) * columns]);
    }
    if nb == n || columns == 0 {
        return Ok(out);
    }
    let mesh = Mesh {
        positions: old_of_new.iter().map(|&v| positions[v]).collect(),
        faces: faces.iter().map(|f| f.map(|v| new_of_old[v as usize])).collect(),
        num_curve: nb,
        on_boundary: vec![false; n],
        face_patch: vec![0; faces.len()],
        ..Default::default()
    };
    let ops = cotan_operators(&mesh, Metric::Surface, &mesh.positions);
    if order > 1 {
        if let Some(i) = ops.mass.iter().position(|a| !(*a > 0.0)) {
            return Err(Error::numerical(format!(
                "vertex {} has zero area (isolated, or degenerate triangles around it)",
                old_of_new[i]
            )));
        }
    }
    let mut known = Mat::<f64>::zeros(n, columns);
    for k in 0..nb {
        for c in 0..columns {
            known[(k, c)] = values[k * columns + c];
        }
    }
    let (q, rhs) = if order == 1 {
        // −(Q X̃)_f with Q = −Ls: (Ls X̃)_f.
        let mut y = Mat::<f64>::zeros(n, columns);
        ops.ls.mul_dense(known.as_ref(), y.as_mut());
        let rhs = Mat::<f64>::from_fn(n - nb, columns, |i, c| y[(nb + i, c)]);
        (ops.ls.restrict(nb, -1.0), rhs)
    } else {
        use crate::methods::polyharmonic as poly;
        let products = poly::Products::new(&ops, order);
        (poly::matrix(&ops, &products, nb), poly::rhs(&ops, &products, &known, nb))
    };
    let system = Eliminated::factor(&q, nb, None, &format!("harmonic system (k = {order})"))?;
    let rhs = system.solve(rhs);
    for i in 0..n - nb {
        let v = old_of_new[nb + i];
        for c in 0..columns {
            let x = rhs[(i, c)];
            if !x.is_finite() {
                return Err(Error::numerical(format!("harmonic solve: vertex {v} is not finite")));
            }
            out[v * columns + c] = x;
        }
    }
    Ok(out)
}

#[cfg(test)]
#[path = "tests/harmonic.rs"]
mod tests;
