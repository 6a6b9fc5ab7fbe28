use curvenet::examples::example;
use curvenet::operators::{cotan_operators, Metric};
use curvenet::*;
fn main() {
    let net = example("cylinder").unwrap();
    let o = Options {
        method: Method::Triharmonic,
        ..Default::default()
    };
    let s = surface(&net, &o).unwrap();
    let mesh = &s.mesh;
    let a = cotan_operators(mesh, Metric::Planar, &mesh.positions);
    let b = cotan_operators(mesh, Metric::Surface, &mesh.positions);
    let mut worst = (0.0, 0);
    for j in 0..a.ls.ncols {
        let (ra, va) = a.ls.col(j);
        let (rb, vb) = b.ls.col(j);
        assert_eq!(ra, rb);
        for k in 0..va.len() {
            let d = (va[k] - vb[k]).abs();
            if d > worst.0 {
                worst = (d, j);
            }
        }
    }
    println!(
        "max |Ls diff| {:?} at vertex {} (curve? {})",
        worst.0,
        worst.1,
        worst.1 < mesh.num_curve
    );
    let mut mw = (0.0, 0);
    for i in 0..a.mass.len() {
        let d = (a.mass[i] - b.mass[i]).abs() / a.mass[i];
        if d > mw.0 {
            mw = (d, i);
        }
    }
    println!(
        "max rel mass diff {:?} at {} pos {:?}",
        mw.0, mw.1, mesh.positions[mw.1]
    );
    let mut ratios: Vec<(f64, usize)> = mesh
        .faces
        .iter()
        .enumerate()
        .map(|(fi, f)| {
            let p = |k: usize| mesh.positions[f[k] as usize];
            let a3 = 0.5 * (p(1) - p(0)).cross(p(2) - p(0)).length();
            let q = mesh.planar[fi];
            let a2 = 0.5 * (q[1] - q[0]).perp_dot(q[2] - q[0]);
            (a3 / a2, fi)
        })
        .collect();
    ratios.sort_by(|a, b| b.0.total_cmp(&a.0));
    for &(r, fi) in ratios.iter().take(5) {
        println!(
            "ratio {r:.3} face {:?} planar {:?}",
            mesh.faces[fi], mesh.planar[fi]
        );
    }
    println!("median {:.3}", ratios[ratios.len() / 2].0);
    for fi in (0..mesh.faces.len()).step_by(4000) {
        for k in 0..3 {
            let v = mesh.faces[fi][k] as usize;
            let q = mesh.planar[fi][k];
            let p = mesh.positions[v];
            println!(
                "v {v} planar ({:.3},{:.3}) 3d z {:.3} angle {:.3}",
                q.x,
                q.y,
                p.z,
                p.y.atan2(p.x)
            );
        }
    }
    let o2 = Options {
        method: Method::Triharmonic,
        weights: Metric::Surface,
        ..Default::default()
    };
    let s2 = surface(&net, &o2).unwrap();
    let (i, r) = s2
        .mesh
        .positions
        .iter()
        .enumerate()
        .map(|(i, p)| (i, p.truncate().length()))
        .fold((0, 0.0), |acc, x| if x.1 > acc.1 { x } else { acc });
    println!(
        "worst radius {r} at vertex {i} pos {:?} (free from {})",
        s2.mesh.positions[i], s2.mesh.num_curve
    );
}
#[allow(dead_code)]
fn _unused() {}
