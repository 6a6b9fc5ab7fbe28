//! A surfacing run that keeps its mesh and factorisations for fast re-solves with new curve
//! normals: the editing loop of [CG] §5 (change the normals along a curve, see the surface
//! follow).
//!
//! [`Surfacer::new`] runs the stages up to the tessellation once ([`crate::pipeline`]); each
//! [`Surfacer::solve`] runs the final solve on that mesh. The normal-control matrices
//! (propagation `(Ls M⁻¹ Ls)_ff`, fit) depend on the mesh and its planar operators only, not on
//! the curve normals ([CG] eq. 1–3: the normals enter the right-hand sides), so after
//! [`Surfacer::update_normals`] a solve costs right-hand sides and triangular solves. With
//! [`crate::Options::iterations`] > 0 the 3D iterations still factorise their own systems
//! (their operators follow the surface); [`crate::Options::fast`] (no iteration) is the
//! interactive setting.
//!
//! The mesh is kept as built with the first normals: with planar patching the projection
//! planes follow the cycles' mean normals, so a run from scratch with the new normals may
//! triangulate slightly differently. A re-solve equals a fresh solve on the kept mesh.

use crate::curves::CurveSpline;
use crate::topology::resample::resample_network;
use crate::error::{Error, Result};
use crate::geom::DVec3;
use crate::geom::mesh::Mesh;
use crate::methods::normal_control::Factors;
use crate::network::{curve_label, Network};
use crate::pipeline::{prepare, solve_prepared, Options, Prepared, Surface, Timings};
use crate::topology::find_nodes;
use rayon::prelude::*;
use std::borrow::Cow;

/// A network prepared for repeated solves (see the module documentation).
pub struct Surfacer {
    network: Network,
    options: Options,
    prepared: Prepared,
    factors: Factors,
    solves: usize,
}

impl Surfacer {
    /// Validates `network` and builds the mesh with `options` (every stage of
    /// [`crate::surface`] but the final solve). Errors as [`crate::surface`].
    pub fn new(network: &Network, options: &Options) -> Result<Self> {
        let prepared = prepare(network, options, &mut |_, _, _| {})?;
        Ok(Surfacer {
            network: network.clone(),
            options: options.clone(),
            prepared,
            factors: Factors::default(),
            solves: 0,
        })
    }

    /// The network with the current normals.
    pub fn network(&self) -> &Network {
        &self.network
    }

    /// The options of every solve.
    pub fn options(&self) -> &Options {
        &self.options
    }

    /// The mesh the solves run on (free vertices at their planar lift until solved; curve
    /// normals the current ones).
    pub fn mesh(&self) -> &Mesh {
        &self.prepared.mesh
    }

    /// Whether a factorisation from an earlier solve is kept.
    pub fn is_factored(&self) -> bool {
        !self.factors.is_empty()
    }

    /// Surfaces the network with the current normals. The first call factorises; later ones
    /// reuse the normal-control factorisations. The statistics' timings of the first solve
    /// include the preparation; later ones only the solve.
    pub fn solve(&mut self) -> Result<Surface> {
        let base = if self.solves == 0 { self.prepared.timings } else { Timings::default() };
        let surface = solve_prepared(
            Cow::Borrowed(&self.prepared),
            &self.options,
            &mut |_, _, _| {},
            Some(&mut self.factors),
            base,
        )?;
        if self.solves == 0 {
            // The conformal first solve belongs to the preparation: counted once.
            self.prepared.solve_timings = Default::default();
        }
        self.solves += 1;
        Ok(surface)
    }

    /// Replaces the normals of curve `curve` (index in the network) by `normals`, one per
    /// sample of the curve; they need not be unit length. The next [`Surfacer::solve`] uses
    /// them with the kept mesh and factorisations.
    ///
    /// Errors: [`Error::usage`] for a curve index out of range; [`Error::Input`] for a wrong
    /// number of normals or an invalid normal (curve and sample named), as [`crate::surface`];
    /// [`Error::Topology`] when the new normals change the network's nodes (they are averaged
    /// there: normals that cancel). The surfacer is unchanged on error.
    pub fn update_normals(&mut self, curve: usize, normals: &[DVec3]) -> Result<()> {
        let count = self.network.curves.len();
        let Some(c) = self.network.curves.get(curve) else {
            return Err(Error::usage(format!("curve {curve} does not exist: the network has {count} curves")));
        };
        if normals.len() != c.points.len() {
            return Err(Error::input(format!(
                "{}: {} normals given for {} samples; give one normal per sample",
                curve_label(&self.network.curves, curve),
                normals.len(),
                c.points.len()
            )));
        }
        let mut network = self.network.clone();
        network.curves[curve].normals = normals.to_vec();
        // The curve normals of the mesh: the stages that produce them, with the kept snapping
        // tolerance and spacing (the positions come out as before: they do not depend on the
        // normals).
        let (net, _) = network.validated()?;
        let (g, _) = find_nodes(&net, self.prepared.snap)?;
        let splines: Vec<CurveSpline> =
            g.curves.par_iter().map(|c| CurveSpline::fit(&c.points, &c.normals, c.closed)).collect();
        let res = resample_network(&g, &splines, self.prepared.spacing);
        let mesh = &self.prepared.mesh;
        let scale = net.bounding_box().diagonal();
        let same = res.positions.len() == mesh.num_curve
            && res.positions.iter().zip(&mesh.positions).all(|(a, b)| a.distance(*b) <= 1e-12 * scale);
        if !same {
            return Err(Error::topology(format!(
                "the new normals of {} change the network's nodes or curve vertices; build a new surfacer",
                curve_label(&self.network.curves, curve)
            )));
        }
        self.prepared.mesh.curve_normals = res.normals;
        self.network = network;
        Ok(())
    }
}

#[cfg(test)]
#[path = "tests/surfacer.rs"]
mod tests;
