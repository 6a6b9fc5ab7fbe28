//! Pictures with known answers: the curvature map of a sphere is one colour band; a torus with
//! R = 3, r = 2 is red (H > 0) outside and blue (H < 0) on the inner rim; a rendered PNG
//! decodes back to the image.

use curvenet::network::examples;
use curvenet::render::{render, Coloring, RenderOptions, Scene, View};
use curvenet::Options;
#[path = "support/png.rs"]
mod support;
use support::decode_rgb;

fn scene(net: &curvenet::Network) -> Scene {
    let options = Options::default().with_vertices(8000);
    Scene::from_surface(&curvenet::surface(net, &options).expect("surfaces"))
}

/// Pixels inside the surface's silhouette (no white background among their 8 neighbours, so
/// no anti-aliased edge) that are not dark (curves, text).
fn surface_pixels(img: &curvenet::render::Image, rows: std::ops::Range<u32>) -> Vec<[u8; 3]> {
    let white = [255, 255, 255];
    let mut out = Vec::new();
    for y in rows.start.max(1)..rows.end.min(img.height - 1) {
        for x in 1..img.width - 1 {
            let p = img.get(x, y);
            let edge = (0..9).any(|k| img.get(x + k % 3 - 1, y + k / 3 - 1) == white);
            if !edge && *p.iter().max().unwrap() > 60 {
                out.push(p);
            }
        }
    }
    out
}

#[test]
fn the_sphere_is_one_colour_band() {
    let s = scene(&examples::example("sphere").unwrap());
    let range = s.curvature_range();
    assert!((range - 1.0).abs() < 0.05, "colour range ±{range} for a unit sphere");
    // Every vertex falls in the top eighth of the colour bar (bands of R/4 from −R to +R).
    let below: Vec<f64> = s.mean_curvature.iter().copied().filter(|h| h / range < 0.75).collect();
    assert!(below.is_empty(), "{} vertices below the top band, e.g. H = {:?}", below.len(), below.first());
    let opts = RenderOptions {
        width: 400,
        height: 300,
        colorings: vec![Coloring::Curvature],
        curves: false,
        ..Default::default()
    };
    let img = render(&s, &opts).unwrap();
    // The view area (below the title, above the colour bar): every surface pixel is red.
    let px = surface_pixels(&img, 20..img.height - 40);
    assert!(px.len() > 10_000, "the sphere covers the view ({} pixels)", px.len());
    let not_red = px.iter().filter(|p| p[0] as i32 - (p[1].max(p[2]) as i32) <= 50).count();
    assert_eq!(not_red, 0, "{not_red} of {} surface pixels are not red", px.len());
}

#[test]
fn the_torus_is_red_outside_and_blue_on_the_inner_rim() {
    let s = scene(&examples::torus(3.0, 2.0));
    let top = View { azimuth: 0.0, elevation: 90.0, zoom: 1.0 };
    let opts = RenderOptions {
        width: 400,
        height: 400,
        colorings: vec![Coloring::Curvature],
        views: vec![top],
        curves: false,
        ..Default::default()
    };
    let img = render(&s, &opts).unwrap();
    // Scan the middle row of the view from the centre (the hole) outwards.
    let title = 26;
    let bar = 12 + 8 + 8;
    let y = title + (img.height - title - bar) / 2;
    let row: Vec<[u8; 3]> = (img.width / 2..img.width).map(|x| img.get(x, y)).collect();
    let first = row.iter().position(|&p| p != [255, 255, 255]).expect("the hole is surrounded by the torus");
    let last = row.iter().rposition(|&p| p != [255, 255, 255]).unwrap();
    assert!(first > 3, "the centre is the hole");
    let inner = row[first + 2];
    // Three quarters of the way out, radius ≈ 4: H = (R + 2r cos θ) / (2r (R + r cos θ)) ≈ 0.31.
    let outer = row[first + (last - first) * 3 / 4];
    assert!(inner[2] as i32 - inner[0] as i32 > 40, "inner rim {inner:?} is blue (H < 0)");
    assert!(outer[0] as i32 - outer[2] as i32 > 40, "outside {outer:?} is red (H > 0)");
}

#[test]
fn isophotes_alternate_and_png_round_trips() {
    let s = scene(&examples::example("sphere").unwrap());
    let opts = RenderOptions { width: 300, height: 300, colorings: vec![Coloring::Isophotes], ..Default::default() };
    let img = render(&s, &opts).unwrap();
    let px = surface_pixels(&img, 20..img.height);
    let (light, dark) = px.iter().fold((0, 0), |(l, d), p| if p[0] > 180 { (l + 1, d) } else { (l, d + 1) });
    assert!(light > 1000 && dark > 200, "stripes: {light} light, {dark} darker pixels");
    let decoded = decode_rgb(&img.encode_png()).unwrap();
    assert_eq!((decoded.0, decoded.1), (img.width, img.height));
    assert_eq!(decoded.2, img.rgb);
}

#[test]
fn bad_requests_are_errors() {
    let s = scene(&examples::example("sphere").unwrap());
    let mut no_nstar = s.clone();
    no_nstar.propagated_normals = None;
    let opts = RenderOptions { colorings: vec![Coloring::NormalDeviation], ..Default::default() };
    let e = render(&no_nstar, &opts).unwrap_err().to_string();
    assert!(e.contains("N*"), "{e}");
    // Wide but short panels still render (the view area shrinks, nothing underflows).
    let short = RenderOptions { width: 900, height: 64, colorings: vec![Coloring::Curvature], ..Default::default() };
    assert_eq!(render(&s, &short).unwrap().height, 64);
    let mut short_normals = s.clone();
    short_normals.normals.pop();
    let e = render(&short_normals, &RenderOptions::default()).unwrap_err().to_string();
    assert!(e.contains("normals for"), "{e}");
    let tiny = RenderOptions { width: 10, height: 10, ..Default::default() };
    assert!(render(&s, &tiny).unwrap_err().to_string().contains("10x10"));
}
