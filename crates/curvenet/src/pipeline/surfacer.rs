//! A surfacing run that keeps its mesh and factorisations for fast re-solves with new curve
//! normals or positions: the editing loop of \[CG\] §5 (change the normals along a curve, see the
//! surface follow).
//!
//! [`Surfacer::new`] runs the stages up to the tessellation once ([`crate::pipeline`]); each
//! [`Surfacer::solve`] runs the final solve on that mesh. Every method's matrices depend on
//! the mesh and its domain operators only, not on the curve values (\[CG\] eq. 1–3: the normals
//! and positions enter the right-hand sides; for `cauchy` the ghost vertices), so after
//! [`Surfacer::update_normals`] or [`Surfacer::update_points`] a solve costs right-hand sides
//! and triangular solves — for every method ([`crate::methods::SurfacingMethod`]); the
//! operators of the patches' domains are kept too.
//!
//! With `iterations` > 0 (the default) a re-solve starts on the last surface, its free
//! vertices moved by the biharmonic extension of the curve vertices' moves, and runs one 3D
//! iteration's steps with the operators and factorisations of the last iteration (issue 31):
//! no assembly, no factorisation. Those operators were built on an earlier surface; rebuilding
//! them on the start (a numeric refactorisation) gave the same distances to a fresh solve
//! (saddle rim lifted by 3.5 spacings: 0.083 against 0.082 spacing) at a factorisation's cost.
//! One such iteration leaves the surface within about 0.1 spacing of a fresh solve on the same
//! mesh; each further [`Surfacer::solve`] without an update runs another and comes closer
//! (0.03–0.05 after the second; `pipeline::surfacer` tests). Measured at 20k vertices
//! (`cargo bench -p curvenet --bench resolve`, `bench/resolve.py`; docs/performance.md): a
//! re-solve costs about a quarter of a fresh default run and a third of a fresh `fast` one.
//!
//! The mesh is kept as built with the first curves: with planar patching the projection planes
//! follow the cycles' mean normals, so a run from scratch with the new values may triangulate
//! slightly differently. A re-solve equals a fresh solve on the kept mesh.

use super::prepare::{prepare, segment_layout, Prepared};
use super::solve::{solve_prepared, Kept};
use super::{Options, Surface, Timings};
use crate::curves::CurveSpline;
use crate::error::{Error, Result};
use crate::geom::mesh::Mesh;
use crate::geom::DVec3;
use crate::network::{curve_label, Network};
use crate::topology::find_nodes;
use crate::topology::resample::{resample_network, resample_network_as, Resampled};
use rayon::prelude::*;
use std::borrow::Cow;

/// A network prepared for repeated solves (see the module documentation).
pub struct Surfacer {
    network: Network,
    /// What the inference found when curves came without normals (added to the first solve's
    /// surface).
    inferred: Option<(super::InferredNormals, Vec<crate::Warning>)>,
    /// What consolidation did (added to the first solve's surface).
    consolidated: Option<crate::topology::consolidate::Consolidated>,
    options: Options,
    prepared: Prepared,
    kept: Option<Kept>,
    solves: usize,
    /// The cycles chosen by normal inference's global search, kept for a fresh preparation.
    cycles: Option<Vec<crate::topology::search::CycleKey>>,
}

impl Surfacer {
    /// Validates `network` and builds the mesh with `options` (every stage of
    /// [`crate::surface`] but the final solve). Errors as [`crate::surface`].
    ///
    /// Raw strokes are consolidated first ([`crate::topology::consolidate`]; a clean network
    /// is kept as given), then a network with curves without normals has them inferred
    /// ([`crate::infer_normals`]); [`Surfacer::network`] is then the network consolidated and
    /// with its inferred normals, which the updates change and whose curve indices they take (a stroke left out
    /// as a duplicate is not in it; the first solve's warnings name it). Moved points keep the
    /// normals inferred for the first shape.
    pub fn new(network: &Network, options: &Options) -> Result<Self> {
        let consolidated = super::consolidate(network, options, &mut |_, _, _| {})?;
        let network = consolidated.as_ref().filter(|c| c.changed()).map_or(network, |c| &c.network);
        let (inferred, mut prepared) = super::infer::infer_and_prepare(network, options, &mut |_, _, _| {})?;
        // Its solves keep factorisations for the re-solves: the coarse level's, kept for a
        // two-level fine solve, would only add to the peak.
        if let Some(c) = prepared.coarse.as_mut() {
            c.system = None;
        }
        let (network, inferred, cycles) = match inferred {
            Some(i) => (i.network, Some((i.report, i.warnings)), i.cycles),
            None => (network.clone(), None, None),
        };
        Ok(Surfacer {
            network,
            inferred,
            consolidated,
            options: options.clone(),
            prepared,
            kept: None,
            solves: 0,
            cycles,
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
        self.kept.as_ref().is_some_and(Kept::is_factored)
    }

    /// Surfaces the network with the current curve values. The first call factorises; later
    /// ones reuse the method's factorisations (with the 3D iterations: one iteration from the
    /// last surface, see the module documentation). The statistics' timings of the first solve
    /// include the preparation; later ones only the solve.
    pub fn solve(&mut self) -> Result<Surface> {
        let base = if self.solves == 0 { self.prepared.timings } else { Timings::default() };
        let surface = solve_prepared(
            Cow::Borrowed(&self.prepared),
            &self.options,
            &mut |_, _, _| {},
            Some(&mut self.kept),
            base,
        )?;
        let mut surface = surface;
        if self.solves == 0 {
            // The conformal first solve belongs to the preparation: counted once.
            self.prepared.solve_timings = Default::default();
            if let Some((report, warnings)) = &self.inferred {
                super::infer::add_to_surface(&mut surface, report, warnings);
            }
            if let Some(c) = &self.consolidated {
                super::add_consolidation(&mut surface, c.clone());
            }
        }
        self.solves += 1;
        Ok(surface)
    }

    /// Replaces the normals of curve `curve` (index in the network) by `normals`, one per
    /// sample of the curve; they need not be unit length. The next [`Surfacer::solve`] uses
    /// them with the kept mesh and factorisations.
    ///
    /// Errors: [`Error::Usage`] for a curve index out of range; [`Error::Input`] for a wrong
    /// number of normals or an invalid normal (curve and sample named), as [`crate::surface`];
    /// [`Error::Topology`] when the new normals change the network's nodes (they are averaged
    /// there: normals that cancel). The surfacer is unchanged on error.
    ///
    /// On a network with crease curves the kept preparation holds each patch's side normals
    /// and the seam targets made from them: an update prepares the network again (the cost of
    /// a first solve, the preparation of [`Surfacer::new`]).
    pub fn update_normals(&mut self, curve: usize, normals: &[DVec3]) -> Result<()> {
        let network = self.changed(curve, normals, "normals", |c, n| c.normals = n)?;
        if network.has_creases() {
            return self.reprepared(network);
        }
        // The curve normals of the mesh: the stages that produce them, with the kept snapping
        // tolerance and spacing (the positions come out as before: they do not depend on the
        // normals).
        let res = self.resampled(&network, curve, "normals")?;
        let mesh = &self.prepared.mesh;
        let scale = network.bounding_box().diagonal();
        if !res.positions.iter().zip(&mesh.positions).all(|(a, b)| a.distance(*b) <= 1e-12 * scale) {
            return Err(self.topology_changed(curve, "normals"));
        }
        self.prepared.mesh.curve_normals = res.normals;
        // The free vertices' start on the coarse level's surface is the old curves'.
        self.prepared.coarse = None;
        self.network = network;
        Ok(())
    }

    /// Moves the samples of curve `curve` to `points`, one per sample (the normals stay). The
    /// curves must keep their nodes and segments (the same curves meet, in the same order) and
    /// the mesh its curve vertices: the next [`Surfacer::solve`] uses the new curve vertices
    /// with the kept mesh connectivity and factorisations (every method's matrices depend on
    /// the patches' domains, not on the curve positions). The free vertices' domain stays the
    /// one of the first curves: for large moves build a new surfacer.
    ///
    /// Errors as [`Surfacer::update_normals`]; [`Error::Topology`] when the move changes the
    /// nodes, the segments or their vertex counts.
    pub fn update_points(&mut self, curve: usize, points: &[DVec3]) -> Result<()> {
        let network = self.changed(curve, points, "points", |c, p| c.points = p)?;
        if network.has_creases() {
            return self.reprepared(network);
        }
        let res = self.resampled(&network, curve, "points")?;
        let (net, _) = network.validated()?;
        self.prepared.mesh.positions[..res.positions.len()].copy_from_slice(&res.positions);
        self.prepared.mesh.curve_normals = res.normals;
        self.prepared.curves = net.curves.iter().map(|c| (c.points.clone(), c.closed)).collect();
        self.prepared.input_spacing = net.mean_sample_spacing();
        self.prepared.coarse = None;
        if self.options.soft.is_some() {
            // The soft weight is scaled by the input sample spacing: a new system.
            self.kept = None;
        }
        if let Some(k) = self.kept.as_mut() {
            k.set_curves(&self.prepared.curves);
        }
        self.network = network;
        Ok(())
    }

    /// The network with `values` (one per sample of curve `curve`) set by `put`; `what` names
    /// them in errors.
    fn changed(
        &self,
        curve: usize,
        values: &[DVec3],
        what: &str,
        put: impl FnOnce(&mut crate::Curve, Vec<DVec3>),
    ) -> Result<Network> {
        let count = self.network.curves.len();
        let Some(c) = self.network.curves.get(curve) else {
            return Err(Error::usage(format!("curve {curve} does not exist: the network has {count} curves")));
        };
        if values.len() != c.points.len() {
            return Err(Error::input(format!(
                "{}: {} {what} given for {} samples; give one per sample",
                curve_label(&self.network.curves, curve),
                values.len(),
                c.points.len()
            ))
            .curve(curve));
        }
        let mut network = self.network.clone();
        put(&mut network.curves[curve], values.to_vec());
        Ok(network)
    }

    /// The curve vertices of `network` (the stages that produce them, with the kept snapping
    /// tolerance and spacing), checked to have the kept mesh's segments and vertex counts.
    fn resampled(&self, network: &Network, curve: usize, what: &str) -> Result<Resampled> {
        let (net, _) = network.validated()?;
        let (g, _) = find_nodes(&net, self.prepared.snap)?;
        let splines: Vec<CurveSpline> =
            g.curves.par_iter().map(|c| CurveSpline::fit(&c.points, &c.normals, c.closed)).collect();
        // The kept mesh's vertex count per segment (pieces = vertices − 1), on the moved curves.
        let pieces: Vec<usize> = self.prepared.layout.iter().map(|l| l[3].saturating_sub(1)).collect();
        let res = if g.segments.len() == pieces.len() {
            resample_network_as(&g, &splines, &pieces)
        } else {
            resample_network(&g, &splines, self.prepared.spacing)
        };
        if res.positions.len() != self.prepared.mesh.num_curve || segment_layout(&g, &res) != self.prepared.layout {
            return Err(self.topology_changed(curve, what));
        }
        Ok(res)
    }

    /// Takes `network` (a network with creases, [`Surfacer::update_normals`]) with a fresh
    /// preparation: the kept factorisations go, the next solve is a first solve. The surfacer
    /// is unchanged on error.
    fn reprepared(&mut self, network: Network) -> Result<()> {
        self.prepared = prepare(&network, &self.options, self.cycles.as_deref(), &mut |_, _, _| {})?;
        self.kept = None;
        self.solves = 0;
        self.network = network;
        Ok(())
    }

    fn topology_changed(&self, curve: usize, what: &str) -> Error {
        Error::topology(format!(
            "the new {what} of {} change the network's nodes or curve vertices; build a new surfacer",
            curve_label(&self.network.curves, curve)
        ))
        .curve(curve)
    }
}

#[cfg(test)]
#[path = "tests/surfacer.rs"]
mod tests;
