//! The stages before the final solve (\[CG\] §3.1–3.3; docs/design.md §1, steps 1–7): validate
//! the options and the network, find the nodes and segments, fit the splines, trace the
//! cycles, choose the spacing, resample and tessellate — with planar projections, or with a
//! coarse first solve whose conformal flattening the patches are triangulated in.

use super::options::{MeshOptions, Options, Patching};
use super::stats::{CoarseLevel, Timings};
use crate::curves::CurveSpline;
use crate::error::{Error, Result, Warning};
use crate::geom::mesh::Mesh;
use crate::geom::DVec3;
use crate::methods::Method;
use crate::network::Network;
use crate::solve::timing::{seconds_since, timed, Instant};
use crate::solve::SolveTimings;
use crate::tessellate::{tessellate, VERTICES_PER_AREA};
use crate::topology::creases::{check_sides, patch_normals, segment_sides, Seams};
use crate::topology::cycles::{find_patches_open, half_edge_samples, patches_from_keys};
use crate::topology::resample::{resample_network, Resampled};
use crate::topology::search::CycleKey;
use crate::topology::{find_nodes, trim_dangling, Graph, Patch};
use rayon::prelude::*;

/// A stage's progress report: `(stage, seconds, detail)`.
pub type Progress<'a> = &'a mut dyn FnMut(&str, f64, &str);

/// What the stages before the final solve produced: the mesh and the figures the solve and
/// its statistics need. [`crate::Surfacer`] keeps it between solves.
#[derive(Clone, Debug)]
pub(crate) struct Prepared {
    /// The mesh the final solve runs on (curve vertices first, with their input normals).
    pub mesh: Mesh,
    /// The mesh cut open along the creases (docs/design.md §13): normal-control solves on it,
    /// the baselines on `mesh`. `None` without creases.
    pub seams: Option<Seams>,
    /// The target edge length `d`.
    pub spacing: f64,
    /// The snapping tolerance the nodes were found with.
    pub snap: f64,
    /// The validated input curves' samples and closedness (`method = cauchy` finds its
    /// constraint curves on the mesh by them).
    pub curves: Vec<(Vec<DVec3>, bool)>,
    /// Mean input sample spacing (soft constraints are scaled by it).
    pub input_spacing: f64,
    /// Number of patches.
    pub patches: usize,
    /// Number of nodes.
    pub nodes: usize,
    /// Number of segments.
    pub segments: usize,
    /// Number of connected components of the network.
    pub components: usize,
    /// Per segment: its curve, start and end nodes and number of mesh vertices (a re-solve
    /// with moved curves needs the same).
    pub layout: Vec<[usize; 4]>,
    /// What the stages repaired or assumed.
    pub warnings: Vec<Warning>,
    /// Seconds of the stages so far (`total`: their sum).
    pub timings: Timings,
    /// Seconds of the solves before the fine level's (the conformal first solve, the coarse levels).
    pub solve_timings: SolveTimings,
    /// The coarse level whose iterated surface the mesh's free vertices start on
    /// ([`crate::tessellate::transfer_positions`]; the fine level's first solve is not needed),
    /// if any: `None` without one, and after the curves changed (the start is the old curves').
    pub coarse: Option<CoarseLevel>,
}

/// The network's topology: the validated network, its nodes, segments, splines and patches.
pub(super) struct Topology {
    pub(super) net: Network,
    pub(super) g: Graph,
    pub(super) splines: Vec<CurveSpline>,
    pub(super) patches: Vec<Patch>,
    pub(super) snap: f64,
    pub(super) warnings: Vec<Warning>,
}

/// Validates, finds the nodes and patches, picks the spacing, resamples and tessellates
/// (with the conformal first solve when `options.mesh.patching` asks for it).
///
/// `cycles`: the patches' cycles chosen beforehand (normal inference's global search), used
/// instead of the rotation walk when they are cycles of this network's graph.
pub(crate) fn prepare(
    network: &Network,
    options: &Options,
    cycles: Option<&[CycleKey]>,
    progress: Progress<'_>,
) -> Result<Prepared> {
    let start = Instant::now();
    let mut timings = Timings::default();
    check_options(options)?;
    // A relative spacing (`1%`) is a distance on this network.
    let resolved;
    let options = match options.mesh.spacing_relative.filter(|_| options.mesh.spacing.is_none()) {
        Some(f) => {
            let mut o = options.clone();
            o.mesh.spacing = Some(f * network.bounding_box().diagonal());
            resolved = o;
            &resolved
        }
        None => options,
    };
    let mut topo = topology(network, &options.mesh, cycles, &mut timings, progress)?;

    // Spacing.
    let clock = Instant::now();
    let size = SizeModel::new(&topo.g, &topo.splines, &topo.patches);
    let target = options.mesh.vertices.unwrap_or(MeshOptions::DEFAULT_VERTICES);
    let d = options.mesh.spacing.unwrap_or_else(|| size.spacing(target));
    let estimate = size.vertices(d);
    if estimate > MeshOptions::MAX_VERTICES {
        return Err(Error::usage(format!(
            "spacing {d:.3e} would create about {estimate:.2e} vertices (limit {:.0e}); give a larger `spacing` or a smaller `vertices`",
            MeshOptions::MAX_VERTICES
        )));
    }
    super::budget::check(estimate, options)?;
    if let Some(w) = options.mesh.spacing.and_then(|d| super::budget::size_warning(d, estimate, options)) {
        // Said before the run (a progress line front ends print at once), and kept.
        progress("warning", 0.0, &w.message);
        topo.warnings.push(w);
    }
    timings.resample += seconds_since(clock);

    let mut st = SolveTimings::default();
    let (mesh, seams, d, layout, coarse) = match options.mesh.patching {
        Patching::Planar => {
            let (res, mesh) = planar_stage(&topo, d, &mut timings)?;
            let seams = timed(&mut timings.tessellate, || topo.seams(&res, &mesh));
            let layout = segment_layout(&topo.g, &res);
            topo.warnings.extend(fold_warnings(&mesh));
            progress("resample", timings.resample, &format!("spacing {d:.4e}, {} curve vertices", res.positions.len()));
            let detail = format!("{} vertices, {} faces", mesh.num_vertices(), mesh.faces.len());
            progress("tessellate", timings.tessellate, &detail);
            (mesh, seams, d, layout, None)
        }
        Patching::Conformal => {
            let spacing = options.mesh.spacing.is_none().then_some((&size, target));
            super::levels::conformal_stage(&mut topo, options, d, spacing, &mut timings, &mut st, progress)?
        }
    };
    timings.total = seconds_since(start);
    let c = topo.g.node_components();
    Ok(Prepared {
        mesh,
        seams,
        spacing: d,
        snap: topo.snap,
        curves: topo.net.curves.iter().map(|c| (c.points.clone(), c.closed)).collect(),
        input_spacing: topo.net.mean_sample_spacing(),
        patches: topo.patches.len(),
        nodes: topo.g.nodes.len(),
        segments: topo.g.segments.len(),
        components: (0..c.len()).filter(|&i| c[i] == i).count(),
        layout,
        warnings: topo.warnings,
        timings,
        solve_timings: st,
        coarse,
    })
}

/// Per segment of `g`: its curve, start and end nodes and number of vertices in `res`.
pub(crate) fn segment_layout(g: &Graph, res: &Resampled) -> Vec<[usize; 4]> {
    g.segments.iter().zip(&res.segment_vertices).map(|(s, v)| [s.curve, s.start, s.end, v.len()]).collect()
}

/// Checks the values of the options a library caller may have set directly (front ends check
/// them when they are set by name, [`Options::set`]).
pub(super) fn check_options(options: &Options) -> Result<()> {
    if let Some(d) = options.mesh.spacing {
        if !(d.is_finite() && d > 0.0) {
            return Err(Error::usage(format!("spacing {d} is not a positive distance")));
        }
    }
    if let Some(f) = options.mesh.spacing_relative {
        if !(f.is_finite() && f > 0.0 && f <= 1.0) {
            return Err(Error::usage(format!(
                "relative spacing {f} is not a share of the diagonal in (0, 1] (`spacing` 0–100%)"
            )));
        }
    }
    if options.mesh.vertices == Some(0) {
        return Err(Error::usage("the vertex count must be positive"));
    }
    if let Some(w) = options.soft {
        if !(w.is_finite() && w > 0.0) {
            return Err(Error::usage(format!("soft-constraint weight {w} is not a positive number")));
        }
        if !matches!(options.method, Method::NormalControl | Method::ShortPaper) {
            return Err(Error::usage(format!(
                "`soft` applies to normal-control and short-paper only, not to {}",
                options.method.name()
            )));
        }
    }
    if let Some(s) = options.mesh.snap {
        if !(s.is_finite() && s > 0.0) {
            return Err(Error::usage(format!("snapping tolerance {s} is not a positive distance")));
        }
    }
    if let Some(m) = options.mesh.max_memory.filter(|m| !(m.is_finite() && *m > 0.0)) {
        return Err(Error::usage(format!("`max_memory` {m} is not a positive size in bytes")));
    }
    let counts = [
        ("iterations", options.iterate.iterations),
        ("inner_steps", options.iterate.inner_steps),
        ("guide_updates", options.normal_control.guide_updates),
        ("ghost_updates", options.cauchy.ghost_updates),
    ];
    let max = super::options::MAX_ITERATION_COUNT;
    if let Some((name, n)) = counts.iter().find(|(_, n)| *n > max) {
        return Err(Error::usage(format!(
            "`{name}` {n} is more than {max} (the iterations stop at convergence long before)"
        )));
    }
    Ok(())
}

/// Validation, nodes and segments (\[CG\] §3.1), splines (the tangents at nodes) and cycles
/// (\[CG\] §3.2).
pub(super) fn topology(
    network: &Network,
    mesh: &MeshOptions,
    cycles: Option<&[CycleKey]>,
    timings: &mut Timings,
    progress: Progress<'_>,
) -> Result<Topology> {
    let clock = Instant::now();
    let (net, mut warnings) = network.validated()?;
    let snap = mesh.snap.or(net.snap).unwrap_or_else(|| net.snap_tolerance());
    let (mut g, w) = find_nodes(&net, snap)?;
    warnings.extend(w);
    warnings.extend(trim_dangling(&mut g)?);
    timings.nodes = seconds_since(clock);
    progress("nodes", timings.nodes, &format!("{} nodes, {} segments", g.nodes.len(), g.segments.len()));

    let splines: Vec<CurveSpline> = timed(&mut timings.resample, || {
        g.curves.par_iter().map(|c| CurveSpline::fit(&c.points, &c.normals, c.closed)).collect()
    });
    // Cycles the network came with are the user's: they must fit (the inference's own fall
    // back to the walk where node finding on its network differs).
    if let Some(given) = network.cycles.as_deref() {
        crate::topology::cycles::check_keys(&g, given)?;
    }
    // The network's own cycles where the caller has none (a re-preparation, `Surfacer`).
    let cycles = cycles.or(network.cycles.as_deref());
    let (patches, w) = timed(&mut timings.cycles, || match cycles {
        Some(keys) => match patches_from_keys(&mut g, &splines, keys)? {
            Some(found) => Ok(found),
            None => find_patches_open(&mut g, &splines),
        },
        None => find_patches_open(&mut g, &splines),
    })?;
    warnings.extend(w);
    if net.has_creases() {
        check_sides(&g, &patches, &g.labels)?;
    }
    progress("cycles", timings.cycles, &format!("{} patches", patches.len()));
    Ok(Topology { net, g, splines, patches, snap, warnings })
}

impl Topology {
    /// The mesh `mesh` (on the curve vertices `res`) cut open along the network's creases;
    /// `None` without creases (or where every crease is smooth).
    pub(super) fn seams(&self, res: &Resampled, mesh: &Mesh) -> Option<Seams> {
        if !self.net.has_creases() {
            return None;
        }
        let sides = segment_sides(&self.g, res);
        Seams::cut(mesh, &patch_normals(&self.patches, res, &sides))
    }
}

/// Resamples and tessellates at spacing `d` with planar projections (\[CG\] §3.3).
pub(super) fn planar_stage(topo: &Topology, d: f64, timings: &mut Timings) -> Result<(Resampled, Mesh)> {
    let res = timed(&mut timings.resample, || resample_network(&topo.g, &topo.splines, d));
    let mesh = timed(&mut timings.tessellate, || -> Result<Mesh> {
        let mesh = tessellate(&topo.g, &res, &topo.patches, d)?;
        manifold(&mesh, &topo.g, &res)?;
        Ok(mesh)
    })?;
    Ok((res, mesh))
}

/// A tessellation stage's result: the mesh, its cut along the creases, the spacing, the
/// segments' layout, the coarse level whose iterated surface the free vertices start on.
pub(super) type Stage = (Mesh, Option<Seams>, f64, Vec<[usize; 4]>, Option<CoarseLevel>);

/// Checks that the tessellated patches join into an edge-manifold, consistently oriented mesh
/// ([`crate::geom::mesh::bad_edge`]); an edge in more than two faces means that two patches overlap
/// (two curves come closer than the spacing between nodes, or a patch folds onto its
/// neighbour). The error names the patches, the curves and the place.
pub(super) fn manifold(mesh: &Mesh, g: &Graph, res: &Resampled) -> Result<()> {
    let Some(([a, b], faces)) = crate::geom::mesh::bad_edge(&mesh.faces) else { return Ok(()) };
    let mut patches: Vec<u32> = faces.iter().map(|&f| mesh.face_patch[f]).collect();
    patches.sort_unstable();
    patches.dedup();
    let curve_of = |v: u32| {
        res.segment_vertices.iter().position(|sv| sv.contains(&v)).map(|s| g.labels[g.segments[s].curve].clone())
    };
    let mut curves: Vec<String> = [a, b].iter().filter_map(|&v| curve_of(v)).collect();
    curves.dedup();
    // A closed curve that meets no other (one segment, from its node back to it) bounds a
    // patch on each side: a border not marked as one ("boundry", issue 29).
    let lone_loops: Vec<&str> = (0..g.curves.len())
        .filter(|&c| {
            let segs: Vec<_> = g.segments.iter().filter(|s| s.curve == c).collect();
            let c = &g.curves[c];
            c.closed && !c.boundary && segs.len() == 1 && segs[0].start == segs[0].end
        })
        .map(|c| g.labels[c].as_str())
        .filter(|l| curves.iter().any(|n| n == l))
        .collect();
    let hint = if lone_loops.is_empty() {
        "give a smaller `spacing`, a larger `snap`, or fix the curves there".to_string()
    } else {
        format!(
            "{} {} a closed loop that meets no other curve, with a patch on either side: if it is an open border of \
             the surface, mark it as one (`\"boundary\": true`)",
            lone_loops.join(" and "),
            if lone_loops.len() == 1 { "is" } else { "are each" }
        )
    };
    let list = |v: &[String]| if v.is_empty() { "interior vertices".to_string() } else { v.join(" and ") };
    let patches: Vec<String> = patches.iter().map(|p| p.to_string()).collect();
    // The segment the bad edge lies on (both ends on it), else one through either end.
    let segment = res
        .segment_vertices
        .iter()
        .position(|sv| sv.contains(&a) && sv.contains(&b))
        .or_else(|| [a, b].iter().find_map(|&v| res.segment_vertices.iter().position(|sv| sv.contains(&v))));
    let e = Error::topology(format!(
        "patches {} overlap near {} (an edge of {} in {} triangles): the curves come closer than the \
         mesh spacing between crossings, or a patch folds onto its neighbour; {hint}",
        patches.join(", "),
        crate::geom::fmt_point(mesh.positions[a as usize]),
        list(&curves),
        faces.len()
    ))
    .point(mesh.positions[a as usize]);
    let e = match segment {
        Some(s) => e.segment(s).curve(g.segments[s].curve),
        None => e,
    };
    Err(match patches.first().and_then(|p| p.parse().ok()) {
        Some(p) => e.patch(p),
        None => e,
    })
}

/// Sizes that predict the vertex count: free vertices ≈ `c A / d²` over the patches' projected
/// area `A`, curve vertices ≈ `ℓ / d` over the segments' length `ℓ`.
#[derive(Clone)]
pub(super) struct SizeModel {
    /// `c A`: the vertices-per-area constant times the domains' total area.
    pub(super) area: f64,
    /// `ℓ`: the segments' total arc length.
    pub(super) length: f64,
    /// Area of each patch's domain (projection or strip).
    pub(super) patch_areas: Vec<f64>,
}

impl SizeModel {
    /// The model of the network `g` with its `splines` and `patches`.
    pub(super) fn new(g: &Graph, splines: &[CurveSpline], patches: &[Patch]) -> Self {
        let length: f64 = g.segments.iter().map(|s| splines[s.curve].arc_between(s.first, s.last)).sum();
        let samples = |hs: &[crate::topology::HalfEdge]| -> Vec<DVec3> {
            hs.iter().flat_map(|&h| half_edge_samples(g, h)).map(|x| x.0).collect()
        };
        let patch_areas: Vec<f64> = patches
            .iter()
            .map(|p| match p {
                Patch::Disk(hs) => crate::geom::polygon_vector_area(&samples(hs)).length(),
                Patch::Tube([a, b]) => {
                    let (la, lb) = (samples(a), samples(b));
                    let len = |v: &[DVec3]| (0..v.len()).map(|i| v[i].distance(v[(i + 1) % v.len()])).sum::<f64>();
                    let c = |v: &[DVec3]| v.iter().sum::<DVec3>() / v.len() as f64;
                    0.5 * (len(&la) + len(&lb)) * c(&la).distance(c(&lb))
                }
            })
            .collect();
        SizeModel { area: VERTICES_PER_AREA * patch_areas.iter().sum::<f64>(), length, patch_areas }
    }

    /// The predicted vertex count at spacing `d`.
    fn vertices(&self, d: f64) -> f64 {
        self.area / (d * d) + self.length / d
    }

    /// The spacing that gives about `target` vertices (`n = c A x² + ℓ x`, `x = 1/d`).
    pub(super) fn spacing(&self, target: usize) -> f64 {
        let (ca, l, n) = (self.area, self.length, target.max(10) as f64);
        let x = if ca > 0.0 { (-l + (l * l + 4.0 * ca * n).sqrt()) / (2.0 * ca) } else { n / l };
        1.0 / x
    }
}

/// One warning per patch of `mesh` whose planar projection folds over (triangulated in a
/// fallback domain, see [`crate::tessellate`]).
pub(super) fn fold_warnings(mesh: &Mesh) -> Vec<Warning> {
    mesh.fold_fallback
        .iter()
        .map(|p| {
            Warning::new(format!(
                "patch {p}: its planar projection folds over (a deep or twisted cycle); it was triangulated on a \
                 fallback domain (the plane of its vector area, or an ellipse its border is mapped onto by arc length)"
            ))
            .patch(*p)
        })
        .collect()
}
