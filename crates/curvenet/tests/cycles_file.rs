//! Cycles given with a network (issue 30, item 5; docs/design.md §15): `curvenet normals`
//! (Python `infer_normals`) writes the cycles the surface run chose, a surface made from that
//! file has the same patches (before, it traced its own and stopped on overlapping patches for
//! `shield` and `hat`), a person can leave a cycle open by deleting it, and cycles that do not
//! fit the network are an error naming the cycle.

use curvenet::io::{network_to_string, parse_network, read_network, NetworkFormat};
use curvenet::network::examples::example;
use curvenet::network::CycleKey;
use curvenet::{
    infer_normals, network_with_cycles, surface, with_cycle_filled, with_patch_left_open, Network, Options,
};
use std::collections::HashMap;

fn sketch(name: &str) -> Network {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../data/sketches").join(format!("{name}.obj"));
    read_network(&path).unwrap()
}

/// `net` written as JSON and read back.
fn through_json(net: &Network) -> Network {
    parse_network(&network_to_string(net, NetworkFormat::Json), NetworkFormat::Json, "cycles.json").unwrap()
}

/// Edges of `faces` in one face only.
fn border_edges(faces: &[[u32; 3]]) -> usize {
    let mut count: HashMap<(u32, u32), u32> = HashMap::new();
    for f in faces {
        for k in 0..3 {
            let (a, b) = (f[k], f[(k + 1) % 3]);
            *count.entry((a.min(b), a.max(b))).or_default() += 1;
        }
    }
    count.values().filter(|&&n| n == 1).count()
}

#[test]
fn inferred_normals_carry_the_cycles_the_sketchs_surface_uses() {
    // `infer_normals` takes the network as it is (`curvenet consolidate --normals` consolidates
    // first): the direct run without consolidation is the one to compare with.
    let mut options = Options::default().with_vertices(8000);
    options.consolidate.enabled = false;
    let mut with_cycles = 0;
    for name in ["computer-mouse", "flower", "hat", "shield", "teapot", "vacuum"] {
        let net = sketch(name);
        let direct = surface(&net, &options).unwrap_or_else(|e| panic!("{name}: {e}"));
        let inferred = infer_normals(&net, &options).unwrap();
        assert_eq!(inferred.network.cycles, inferred.cycles, "{name}");
        with_cycles += usize::from(inferred.cycles.is_some());
        let back = through_json(&inferred.network);
        assert_eq!(back.cycles, inferred.network.cycles, "{name}: the cycles through JSON");
        let again = surface(&back, &options).unwrap_or_else(|e| panic!("{name}, its normals and cycles: {e}"));
        eprintln!(
            "{name}: {} patches, {} vertices; from the file: {} patches, {} vertices",
            direct.stats.cycles, direct.stats.vertices, again.stats.cycles, again.stats.vertices
        );
        assert_eq!(again.stats.cycles, direct.stats.cycles, "{name}: patches");
        assert_eq!(border_edges(&again.mesh.faces), border_edges(&direct.mesh.faces), "{name}: border edges");
    }
    assert!(with_cycles >= 3, "{with_cycles} of 6 sketches carry cycles");
}

/// The sphere without normals, its normals and cycles inferred.
fn sphere_with_cycles() -> Network {
    let inferred = infer_normals(&example("sphere").unwrap().without_normals(), &Options::default()).unwrap();
    let net = inferred.network;
    assert_eq!(net.cycles.as_ref().map(Vec::len), Some(8), "the sphere's 8 octants");
    net
}

#[test]
fn a_cycle_deleted_from_the_file_is_left_open() {
    let options = Options::default().with_vertices(4000);
    let mut net = sphere_with_cycles();
    let closed = surface(&net, &options).unwrap();
    assert_eq!(border_edges(&closed.mesh.faces), 0);
    net.cycles.as_mut().unwrap().pop();
    let open = surface(&through_json(&net), &options).unwrap();
    assert_eq!(open.stats.cycles, 7);
    // One octant open: its border, three quarter circles, is the mesh's border.
    let border = border_edges(&open.mesh.faces);
    let expected = 1.5 * std::f64::consts::PI / open.stats.spacing;
    assert!((border as f64 - expected).abs() < 0.2 * expected, "{border} border edges, about {expected:.0} expected");
    // The edited cycles survive a new inference of the normals (they are the user's).
    let again = infer_normals(&net.without_normals(), &Options::default()).unwrap();
    assert_eq!(again.network.cycles, net.cycles);
}

#[test]
fn cycles_that_do_not_fit_the_network_are_errors_naming_the_cycle() {
    let options = Options::default().with_vertices(2000);
    let net = sphere_with_cycles();
    let cycles = net.cycles.clone().unwrap();
    let with = |edit: &dyn Fn(&mut Vec<CycleKey>)| {
        let mut n = net.clone();
        edit(n.cycles.as_mut().unwrap());
        surface(&n, &options).map(|_| ()).unwrap_err().to_string()
    };
    let e = with(&|c| c[2][0].0 = 7);
    assert!(e.contains("cycle 2 of the network's \"cycles\"") && e.contains("curve 7 is not in the network"), "{e}");
    let e = with(&|c| c[1][0].2 += 1);
    assert!(e.contains("cycle 1 ") && e.contains("has no segment from sample"), "{e}");
    let e = with(&|c| {
        c[3].pop();
    });
    assert!(e.contains("cycle 3 ") && e.contains("does not close"), "{e}");
    let e = with(&|c| c.push(cycles[0].clone()));
    assert!(e.contains("cycle 8 ") && e.contains("in a third cycle"), "{e}");
    let e = with(&|c| c.push(Vec::new()));
    assert!(e.contains("cycle 8 ") && e.contains("has no segments"), "{e}");
    let e = with(&|c| {
        let first = c[4][0];
        c[4].push(first);
    });
    assert!(e.contains("cycle 4 ") && e.contains("is twice"), "{e}");
    // A cycle turned the other way runs along its neighbours' segments in their direction.
    let e = with(&|c| {
        c[5].reverse();
        c[5].iter_mut().for_each(|s| s.3 = !s.3);
    });
    assert!(e.contains("cycle 5 ") && e.contains("in the direction cycle"), "{e}");
}

/// `curvenet cycles` (`network_with_cycles`): the network a default run uses, with every
/// patch's cycle; surfaced, it gives the run's mesh — on sketches (consolidated, normals and
/// cycles inferred), on a network with normals (the walk's cycles) and on a tube (two lone
/// boundary loops, no cycle to write: found again).
#[test]
fn the_network_with_its_cycles_surfaces_as_the_run_did() {
    let options = Options::default().with_vertices(6000);
    for (name, net) in [
        ("shield", sketch("shield")),
        ("hat", sketch("hat")),
        ("sphere", example("sphere").unwrap()),
        ("cylinder", example("cylinder").unwrap()),
    ] {
        let direct = surface(&net, &options).unwrap_or_else(|e| panic!("{name}: {e}"));
        let (with, _) = network_with_cycles(&net, &options).unwrap();
        let cycles = with.cycles.as_ref().unwrap().len();
        let again = surface(&through_json(&with), &options).unwrap_or_else(|e| panic!("{name} with its cycles: {e}"));
        eprintln!("{name}: {cycles} cycles, {} patches, {} faces", again.stats.cycles, again.mesh.faces.len());
        assert_eq!(again.stats.cycles, direct.stats.cycles, "{name}");
        assert_eq!(again.mesh.faces.len(), direct.mesh.faces.len(), "{name}");
        let expected = match name {
            "sphere" => Some(8),
            "cylinder" => Some(0),
            _ => None,
        };
        assert!(expected.is_none_or(|e| e == cycles), "{name}: {cycles} cycles");
    }
}

/// The viewer's click (`with_patch_left_open`): patch `k` of a run left open, also twice in a
/// row (the second on the network with cycles the first returned); a patch past the cycles is
/// an error naming it. `Surfacer` re-solves keep the given cycles.
#[test]
fn a_patch_of_a_run_is_left_open_by_its_number() {
    let options = Options::default().with_vertices(3000);
    let sphere = example("sphere").unwrap();
    let once = with_patch_left_open(&sphere, &options, 3).unwrap();
    let twice = with_patch_left_open(&once, &options, 0).unwrap();
    assert_eq!(surface(&once, &options).unwrap().stats.cycles, 7);
    assert_eq!(surface(&twice, &options).unwrap().stats.cycles, 6);
    let e = with_patch_left_open(&sphere, &options, 8).unwrap_err();
    assert!(e.to_string().contains("patch 8 cannot be left open") && e.exit_code() == 2, "{e}");
    let mut s = curvenet::Surfacer::new(&twice, &options).unwrap();
    assert_eq!(s.solve().unwrap().stats.cycles, 6);
}

/// The viewer's click on a curve (`with_cycle_filled`): the octant left open is filled again
/// from any of its curves; a curve with patches on both sides is an error saying so; on the
/// neatened teapot with one of its patches left open, the hole found along some curve is
/// filled (fewer border edges).
#[test]
fn an_open_cycle_is_filled_from_a_curve_along_it() {
    let options = Options::default().with_vertices(3000);
    let sphere = example("sphere").unwrap();
    let (with, _) = network_with_cycles(&sphere, &options).unwrap();
    let curve = with.cycles.as_ref().unwrap()[3][0].0;
    let open = with_patch_left_open(&with, &options, 3).unwrap();
    let e = with_cycle_filled(&with, &options, curve).unwrap_err().to_string();
    assert!(e.contains("borders no open cycle"), "{e}");
    let filled = with_cycle_filled(&open, &options, curve).unwrap();
    let s = surface(&filled, &options).unwrap();
    assert_eq!((s.stats.cycles, border_edges(&s.mesh.faces)), (8, 0));

    let options = Options::default().with_vertices(8000);
    let (teapot, _) = network_with_cycles(&sketch("teapot"), &options).unwrap();
    let whole = border_edges(&surface(&teapot, &options).unwrap().mesh.faces);
    let open = with_patch_left_open(&teapot, &options, 5).unwrap();
    let before = border_edges(&surface(&open, &options).unwrap().mesh.faces);
    assert!(before > whole, "{before} border edges with a patch left open, {whole} before");
    let filled = (0..open.curves.len()).find_map(|c| with_cycle_filled(&open, &options, c).ok()).expect("a hole");
    let s = surface(&filled, &options).unwrap();
    eprintln!(
        "teapot: {whole} border edges, {before} with a patch left open, {} after one hole filled",
        border_edges(&s.mesh.faces)
    );
    assert!(border_edges(&s.mesh.faces) < before);
}
