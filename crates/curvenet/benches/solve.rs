//! `cargo bench -p curvenet --bench solve`: the triangular solves of the surfacing system
//! (`(Ls M⁻¹ Ls)_ff`, factored along the patches) with 3 and 6 right-hand sides, curvenet's
//! solve against faer's own sequential supernodal solve on the same factor, in the same run.
//! Prints medians and their ratio, and the time to stream the factor's values once (a floor:
//! a solve reads them twice).
//!
//! Options (after `--`): `--vertices N` (default 100000), `--runs K` (default 15).

use curvenet::network::examples;
use curvenet::operators::{cotan_operators, Metric};
use curvenet::solve::sparse::product_lower;
use curvenet::solve::Cholesky;
use curvenet::Options;
use faer::Mat;
use std::time::Instant;

use curvenet::metrics::median;

fn main() {
    let args: Vec<String> = std::env::args().skip(1).filter(|a| a != "--bench").collect();
    let (mut vertices, mut runs) = (100_000usize, 15usize);
    let mut i = 0;
    while i + 1 < args.len() {
        match args[i].as_str() {
            "--vertices" => vertices = args[i + 1].parse().expect("--vertices N"),
            "--runs" => runs = args[i + 1].parse().expect("--runs K"),
            other => panic!("unknown option {other}"),
        }
        i += 2;
    }
    let net = examples::example("sphere").expect("bundled sphere");
    let options = Options::fast().with_vertices(vertices);
    let mesh = curvenet::surface(&net, &options).expect("surfacing the sphere").mesh;
    let nc = mesh.num_curve;
    let ops = cotan_operators(&mesh, Metric::Planar, &mesh.positions);
    let inv_m: Vec<f64> = ops.mass.iter().map(|a| 1.0 / a).collect();
    let q = product_lower(&ops.ls, &inv_m, &ops.ls, nc);
    let chol = Cholesky::factor_in_parts(&q, "bench", Some(&mesh.free_vertex_patches())).expect("factor");
    let n = chol.dim();
    println!(
        "sphere, {} vertices, {n} unknowns, factor nnz {:.2}M; median of {runs}, release build",
        mesh.num_vertices(),
        chol.factor_nnz() as f64 / 1e6
    );
    // Streaming the factor's values once (as many bytes as one triangular pass reads).
    let values = vec![1.0f64; chol.factor_nnz()];
    let stream = median(
        (0..runs)
            .map(|_| {
                let t = Instant::now();
                // Eight independent sums: bound by memory, not by the adder's latency.
                let mut acc = [0.0f64; 8];
                for c in values.chunks_exact(8) {
                    for (a, v) in acc.iter_mut().zip(c) {
                        *a += v;
                    }
                }
                std::hint::black_box(acc);
                t.elapsed().as_secs_f64()
            })
            .collect(),
    );
    println!(
        "{:<8} {:>12} {:>12} {:>8} {:>14} {:>12}",
        "columns", "curvenet [ms]", "faer seq [ms]", "ratio", "2 × stream [ms]", "max |diff|"
    );
    for k in [3usize, 6] {
        let b = Mat::<f64>::from_fn(n, k, |i, j| ((i * 7 + j * 13) % 101) as f64 / 101.0 - 0.5);
        let time = |f: &dyn Fn(&mut Mat<f64>)| {
            let mut out = b.clone();
            let t = median(
                (0..runs)
                    .map(|_| {
                        let mut x = b.clone();
                        let t = Instant::now();
                        f(&mut x);
                        let e = t.elapsed().as_secs_f64();
                        out = x;
                        e
                    })
                    .collect(),
            );
            (t, out)
        };
        let (ours, x) = time(&|x: &mut Mat<f64>| chol.solve_in_place(x.as_mut()));
        let (reference, y) = time(&|x: &mut Mat<f64>| chol.solve_in_place_reference(x.as_mut()));
        let diff = (0..k)
            .flat_map(|c| (0..n).map(move |i| (c, i)))
            .map(|(c, i)| (x[(i, c)] - y[(i, c)]).abs())
            .fold(0.0, f64::max);
        println!(
            "{k:<8} {:>12.2} {:>12.2} {:>8.2} {:>14.2} {:>12.1e}",
            1e3 * ours,
            1e3 * reference,
            ours / reference,
            2e3 * stream,
            diff
        );
    }
}
