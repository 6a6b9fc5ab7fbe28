//! `cargo bench -p curvenet --bench pcg`: conjugate gradients on the fine level's system
//! against its factorisation (issue 31, "measure before you choose"): iteration counts against
//! mesh size for each preconditioner.
//!
//! The system is the 3D iterations' `Q = Ls M⁻¹ Ls + μ M` on the free vertices of a surface
//! (a `fast` run at N vertices; operators on its 3D positions), the right-hand side `Q x*` for
//! its own free positions `x*`, the start the closest points of a coarse surface (a `fast` run
//! at N/4, about the default's coarse level at twice the spacing). The two-level cycles take
//! that coarse surface's `Q_c`, factorised, and the prolongation `P` of barycentric weights of
//! each fine vertex's closest point on it (curve corners dropped: fixed on both levels).
//!
//! Options (after `--`): `--sizes A,B,..` (default 10000,40000,160000), `--default-surfaces`
//! (the fine and coarse surfaces from default runs, 3D-iterated, instead of `fast` ones),
//! network names (default `sphere torus`).

use curvenet::geom::distance::MeshDistance;
use curvenet::geom::DVec3;
use curvenet::network::examples;
use curvenet::operators::{cotan_operators, Metric};
use curvenet::solve::pcg::{pcg, Energy, Identity, Jacobi, LinearOperator, Preconditioner, TwoLevel};
use curvenet::solve::sparse::{product_lower, Csc};
use curvenet::solve::Eliminated;
use curvenet::{Mesh, Options};
use faer::Mat;
use std::time::Instant;

/// `Q`'s parts on `mesh` at its positions: `Ls`, `W = M⁻¹`, the diagonal `μ M`.
fn parts(mesh: &Mesh, mu: f64) -> (Csc, Vec<f64>, Vec<f64>) {
    let ops = cotan_operators(mesh, Metric::Surface, &mesh.positions);
    let w: Vec<f64> = ops.mass.iter().map(|a| 1.0 / a).collect();
    let d: Vec<f64> = ops.mass.iter().map(|a| mu * a).collect();
    (ops.ls, w, d)
}

/// The prolongation from the coarse free vertices to the fine ones, and the start (closest
/// points on the coarse surface).
fn prolongation(fine: &Mesh, coarse: &Mesh) -> (Csc, Csc, Mat<f64>) {
    let (nf, ncf) = (fine.num_vertices(), fine.num_curve);
    let ncc = coarse.num_curve;
    let index = MeshDistance::new(&coarse.positions, &coarse.faces);
    let mut t = Vec::new();
    let mut start = Mat::<f64>::zeros(nf - ncf, 3);
    for i in ncf..nf {
        let (_, q, f) = index.closest_face(fine.positions[i]);
        let c = coarse.faces[f].map(|v| v as usize);
        let [a, b, d] = c.map(|v| coarse.positions[v]);
        // Barycentric coordinates of q in (a, b, d).
        let (e1, e2, e) = (b - a, d - a, q - a);
        let (d11, d12, d22, d1, d2) = (e1.dot(e1), e1.dot(e2), e2.dot(e2), e.dot(e1), e.dot(e2));
        let det = d11 * d22 - d12 * d12;
        let (v, w) = if det > 0.0 { ((d22 * d1 - d12 * d2) / det, (d11 * d2 - d12 * d1) / det) } else { (0.0, 0.0) };
        let bary = [1.0 - v - w, v, w];
        for k in 0..3 {
            if c[k] >= ncc && bary[k] != 0.0 {
                t.push(((i - ncf) as u32, (c[k] - ncc) as u32, bary[k]));
            }
        }
        for k in 0..3 {
            start[(i - ncf, k)] = q[k];
        }
    }
    let nc_free = coarse.num_vertices() - ncc;
    let pt = Csc::from_triplets(nc_free, nf - ncf, t.iter().map(|&(i, j, v)| (j, i, v)).collect());
    let p = Csc::from_triplets(nf - ncf, nc_free, t);
    (p, pt, start)
}

fn max_error(x: &Mat<f64>, truth: &Mat<f64>) -> f64 {
    let mut m = 0.0f64;
    for i in 0..x.nrows() {
        let d = DVec3::new(x[(i, 0)] - truth[(i, 0)], x[(i, 1)] - truth[(i, 1)], x[(i, 2)] - truth[(i, 2)]);
        m = m.max(d.length());
    }
    m
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).filter(|a| a != "--bench").collect();
    let mut sizes = vec![10_000, 40_000, 160_000];
    let mut names = Vec::new();
    let mut surfaces = Options::fast();
    let mut i = 0;
    while i < args.len() {
        if args[i] == "--sizes" {
            sizes = args[i + 1].split(',').map(|s| s.parse().expect("--sizes A,B")).collect();
            i += 1;
        } else if args[i] == "--default-surfaces" {
            surfaces = Options::default();
        } else {
            names.push(args[i].clone());
        }
        i += 1;
    }
    if names.is_empty() {
        names = vec!["sphere".into(), "torus".into()];
    }
    println!("conjugate gradients on Q = Ls M⁻¹ Ls + μ M (3 columns), from the coarse surface's closest points;");
    println!(
        "iterations to a relative residual of 1e-6 (its largest vertex error ÷ spacing) and of 1e-9, time to 1e-6;"
    );
    println!("direct: assembly + factorisation + one solve");
    println!(
        "{:<8} {:>8} {:<16} {:>6} {:>10} {:>6} {:>9}",
        "network", "free", "preconditioner", "1e-6", "err/sp", "1e-9", "time [s]"
    );
    for name in &names {
        let net = examples::example(name).expect("unknown example");
        for &n in &sizes {
            let fine = curvenet::surface(&net, &surfaces.clone().with_vertices(n)).expect("fine surface").mesh;
            let coarse = curvenet::surface(&net, &surfaces.clone().with_vertices(n / 4)).expect("coarse surface").mesh;
            let area = curvenet::geom::mesh::surface_area(&fine.faces, &fine.positions);
            let patches = fine.face_patch.iter().max().map_or(1, |m| *m as usize + 1);
            let mu = (0.16 * (area / patches as f64).sqrt()).powi(-4);
            let spacing = (area / fine.num_vertices() as f64 * 2.0 / 3f64.sqrt()).sqrt();
            let (ls, w, d) = parts(&fine, mu);
            let first = fine.num_curve;
            let q = Energy::new(&ls, &w, &d, first);
            let free = q.dim();
            let truth = Mat::from_fn(free, 3, |i, c| fine.positions[first + i][c]);
            let mut b = Mat::<f64>::zeros(free, 3);
            q.apply(truth.as_ref(), b.as_mut());
            // Coarse system, factorised.
            let (lsc, wc, dc) = parts(&coarse, mu);
            let mut qc = product_lower(&lsc, &wc, &lsc, coarse.num_curve);
            qc.add_diagonal(&dc[coarse.num_curve..]);
            let coarse_factor = Eliminated::factor(&qc, coarse.num_curve, None, "coarse").expect("coarse factor");
            let (p, pt, start) = prolongation(&fine, &coarse);
            let diag = q.diag();
            let inv_diag: Vec<f64> = diag.iter().map(|x| 1.0 / x).collect();
            let rho = curvenet::solve::pcg::jacobi_spectral_radius(&q, &inv_diag, 30);
            let omega = 1.0 / rho;
            let two = |omega: f64, smoothing: usize| TwoLevel {
                a: &q,
                inv_diag: &inv_diag,
                omega,
                smoothing,
                p: &p,
                pt: &pt,
                coarse: &coarse_factor,
            };
            let preconditioners: Vec<(&str, Box<dyn Preconditioner + '_>)> = vec![
                ("none", Box::new(Identity)),
                ("jacobi", Box::new(Jacobi::new(&diag))),
                ("2-level additive", Box::new(two(omega, 0))),
                ("2-level V(1,1)", Box::new(two(omega, 1))),
                ("2-level V(2,2)", Box::new(two(omega, 2))),
            ];
            println!(
                "{:<8} {:>8} start error {:.3} spacing (coarse {} vertices), λmax(D⁻¹Q) ≈ {rho:.2}",
                name,
                free,
                max_error(&start, &truth) / spacing,
                coarse.num_vertices()
            );
            for (label, m) in &preconditioners {
                if (free > 50_000 || surfaces.iterate.iterations > 0) && matches!(*label, "none" | "jacobi") {
                    // Thousands of iterations: measured up to 40k only.
                    continue;
                }
                let mut x = start.clone();
                let t = Instant::now();
                let r6 = pcg(&q, m.as_ref(), b.as_ref(), x.as_mut(), 1e-6, 3000);
                let time = t.elapsed().as_secs_f64();
                let err = max_error(&x, &truth) / spacing;
                let mut x9 = start.clone();
                let r9 = pcg(&q, m.as_ref(), b.as_ref(), x9.as_mut(), 1e-9, 3000);
                let it = |r: &curvenet::solve::pcg::CgReport| {
                    if r.converged {
                        r.iterations.to_string()
                    } else {
                        format!(">{}", r.iterations)
                    }
                };
                println!(
                    "{:<8} {:>8} {:<16} {:>6} {:>10.2e} {:>6} {:>9.3}",
                    "",
                    "",
                    label,
                    it(&r6),
                    err,
                    it(&r9),
                    time
                );
            }
            let t = Instant::now();
            let lower = product_lower(&ls, &w, &ls, first);
            let mut lower = lower;
            lower.add_diagonal(&d[first..]);
            let f = Eliminated::factor(&lower, first, None, "fine").expect("fine factor");
            let _ = f.solve(b.clone());
            println!(
                "{:<8} {:>8} {:<16} {:>6} {:>10} {:>6} {:>9.3}",
                "",
                "",
                "direct",
                "",
                "",
                "",
                t.elapsed().as_secs_f64()
            );
        }
    }
}
