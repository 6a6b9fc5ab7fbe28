//! The SVG reader: transforms, groups, `defs`, `use`, arcs, shapes, errors with their
//! positions, limits.

use super::*;

fn read(svg: &str, step: f64) -> Vec<SketchPath> {
    read_svg(svg, "t.svg", step).unwrap_or_else(|e| panic!("{e}"))
}

/// The error of reading `svg`, as `(line, column, message)`.
fn error(svg: &str) -> (usize, usize, String) {
    match read_svg(svg, "t.svg", 0.1) {
        Err(Error::Parse { path, line, column, message }) => {
            assert_eq!(path, "t.svg");
            (line, column, message)
        }
        other => panic!("expected a parse error, got {other:?}"),
    }
}

fn close(a: &[DVec2], b: &[DVec2], tol: f64) -> bool {
    a.len() == b.len() && a.iter().zip(b).all(|(p, q)| p.distance(*q) <= tol)
}

/// Distance from `p` to the closed polygon `poly`.
fn to_polygon(p: DVec2, poly: &[DVec2]) -> f64 {
    (0..poly.len())
        .map(|i| {
            let (a, b) = (poly[i], poly[(i + 1) % poly.len()]);
            let t = ((p - a).dot(b - a) / (b - a).length_squared()).clamp(0.0, 1.0);
            p.distance(a + t * (b - a))
        })
        .fold(f64::INFINITY, f64::min)
}

#[test]
fn group_transforms_compose() {
    // translate(10, 20) scale(2): a point maps to 2 p + (10, 20).
    let g = read(r#"<svg><g transform="translate(10,20) scale(2)"><circle cx="1" cy="1" r="1"/></g></svg>"#, 0.1);
    let plain = read(r#"<svg><circle cx="12" cy="22" r="2"/></svg>"#, 0.1);
    assert_eq!(g.len(), 1);
    // The chords are `step` in the root's units: the same sampling as the plain circle.
    assert!(close(&g[0].points, &plain[0].points, 1e-9), "{} vs {} points", g[0].points.len(), plain[0].points.len());
    // A transform on the shape itself composes after the group's.
    let s = read(
        r#"<svg><g transform="scale(2)"><line x1="0" y1="0" x2="1" y2="0" transform="translate(3 0)"/></g></svg>"#,
        0.1,
    );
    assert_eq!(s[0].points, vec![DVec2::new(6.0, 0.0), DVec2::new(8.0, 0.0)]);
    assert!(!s[0].closed);
}

#[test]
fn nested_groups_compose_in_order() {
    let svg = r#"<svg>
      <g transform="translate(5, 0)">
        <g transform="rotate(90)">
          <g transform="matrix(1 0 0 1 0 0) skewX(0) skewY(0)">
            <line x1="0" y1="0" x2="1" y2="0"/>
          </g>
        </g>
      </g>
    </svg>"#;
    let p = read(svg, 0.1);
    // Rotated first (x → y), then moved; y flipped up.
    assert!(close(&p[0].points, &[DVec2::new(5.0, 0.0), DVec2::new(5.0, -1.0)], 1e-12), "{:?}", p[0].points);
    assert_eq!(p[0].line, 5);
    let skew = read(r#"<svg><g transform="skewX(45)"><line x1="0" y1="1" x2="0" y2="2"/></g></svg>"#, 0.1);
    assert!(close(&skew[0].points, &[DVec2::new(1.0, -1.0), DVec2::new(2.0, -2.0)], 1e-12), "{:?}", skew[0].points);
}

#[test]
fn defs_and_other_non_strokes_are_skipped() {
    let svg = r##"<svg xmlns="http://www.w3.org/2000/svg" xmlns:ink="http://www.inkscape.org/namespaces/inkscape">
      <defs><path d="M 0 0 L 9 9"/><circle r="3"/></defs>
      <symbol id="s"><circle r="4"/></symbol>
      <clipPath><rect width="1" height="1"/></clipPath>
      <mask><rect width="1" height="1"/></mask>
      <pattern><rect width="1" height="1"/></pattern>
      <marker><path d="M 0 0 L 1 1"/></marker>
      <metadata><path d="M 0 0 L 1 1"/></metadata>
      <text>label<tspan>x</tspan></text>
      <ink:path d="M 0 0 L 1 1"/>
      <rect x="1" y="2" width="3" height="4" class="outline"/>
    </svg>"##;
    let p = read(svg, 0.1);
    assert_eq!(p.len(), 1);
    assert_eq!(p[0].class, "outline");
    assert_eq!(p[0].line, 11);
    // Only skipped elements: nothing to read.
    let (line, column, m) = error("<svg>\n  <defs><circle r=\"1\"/></defs>\n</svg>");
    assert_eq!((line, column), (1, 1));
    assert!(m.contains("no path"), "{m}");
}

#[test]
fn use_instantiates_its_reference() {
    let svg = r##"<svg xmlns="http://www.w3.org/2000/svg" xmlns:xlink="http://www.w3.org/1999/xlink">
      <defs>
        <line id="l" x1="0" y1="0" x2="1" y2="0" class="crease"/>
        <g id="two"><use href="#l"/><use href="#l" y="1"/></g>
      </defs>
      <symbol id="s"><line x1="0" y1="0" x2="0" y2="1"/></symbol>
      <use href="#l" x="10" y="20"/>
      <use xlink:href="#l" transform="scale(2)" x="1"/>
      <use href="#two" transform="translate(100 0)"/>
      <use href="#s" x="-1"/>
    </svg>"##;
    let p = read(svg, 0.1);
    let lines: Vec<Vec<DVec2>> = p.iter().map(|s| s.points.clone()).collect();
    let seg = |x0: f64, y0: f64, x1: f64, y1: f64| vec![DVec2::new(x0, -y0), DVec2::new(x1, -y1)];
    assert_eq!(
        lines,
        vec![
            seg(10.0, 20.0, 11.0, 20.0),
            // The use's transform applies after its x, y: scale(2) translate(1, 0).
            seg(2.0, 0.0, 4.0, 0.0),
            seg(100.0, 0.0, 101.0, 0.0),
            seg(100.0, 1.0, 101.0, 1.0),
            seg(-1.0, 0.0, -1.0, 1.0),
        ]
    );
    // The instance keeps the referenced element's attributes and line.
    assert_eq!(p[0].class, "crease");
    assert_eq!(p[0].line, 3);
}

#[test]
fn bad_references_are_errors() {
    let (line, _, m) = error("<svg>\n<g id=\"a\"><circle r=\"1\"/><use href=\"#a\"/></g></svg>");
    assert_eq!(line, 2);
    assert!(m.contains("cycle"), "{m}");
    let (_, _, m) = error(r##"<svg><use id="x" href="#y"/><use id="y" href="#x"/></svg>"##);
    assert!(m.contains("cycle"), "{m}");
    let (line, column, m) = error("<svg>\n <use href=\"#nothing\"/></svg>");
    assert_eq!((line, column), (2, 13));
    assert!(m.contains("no element has id=\"nothing\""), "{m}");
    let (_, _, m) = error(r#"<svg><use href="other.svg#c"/></svg>"#);
    assert!(m.contains("#id"), "{m}");
    let (_, _, m) = error(r#"<svg><use/></svg>"#);
    assert!(m.contains("without href"), "{m}");
    let (_, _, m) = error(r##"<svg><symbol id="s" viewBox="0 0 1 1"><circle r="1"/></symbol><use href="#s"/></svg>"##);
    assert!(m.contains("viewBox"), "{m}");
}

#[test]
fn exponential_use_expansion_is_bounded() {
    // Each level uses the previous one twice: 2^40 circles.
    let mut svg = String::from(r#"<svg><defs><circle id="l0" r="0.01"/>"#);
    for k in 1..=40 {
        svg += &format!(r##"<g id="l{k}"><use href="#l{}"/><use href="#l{}"/></g>"##, k - 1, k - 1);
    }
    svg += r##"</defs><use href="#l40"/></svg>"##;
    let start = std::time::Instant::now();
    let (_, _, m) = error(&svg);
    assert!(m.contains(&format!("more than {MAX_ELEMENTS} elements")), "{m}");
    assert!(start.elapsed().as_secs_f64() < 20.0);
    // A chain of uses deeper than the limit.
    let mut svg = String::from(r#"<svg><defs><circle id="u0" r="1"/>"#);
    for k in 1..=MAX_USE_DEPTH + 1 {
        svg += &format!(r##"<use id="u{k}" href="#u{}"/>"##, k - 1);
    }
    svg += &format!(r##"</defs><use href="#u{}"/></svg>"##, MAX_USE_DEPTH + 1);
    let (_, _, m) = error(&svg);
    assert!(m.contains("nested <use>"), "{m}");
}

#[test]
fn a_circle_of_two_arcs_matches_the_circle_element() {
    let step = 0.05;
    let circle = read(r#"<svg><circle cx="10" cy="10" r="10"/></svg>"#, step);
    for d in [
        "M 20 10 A 10 10 0 0 1 0 10 A 10 10 0 0 1 20 10 Z",
        "M 20 10 a 10 10 0 1 0 -20 0 a 10 10 0 1 0 20 0 z",
        // Radii too small are enlarged until the ends fit (here to 10).
        "M 20 10 A 1 1 0 0 1 0 10 A 2 2 0 0 1 20 10 Z",
        // The rotation of a circle's axes changes nothing.
        "M 20 10 A 10 10 30 0 1 0 10 A 10 10 -60 0 1 20 10 Z",
    ] {
        let arcs = read(&format!(r#"<svg><path d="{d}"/></svg>"#), step);
        assert_eq!(arcs.len(), 1, "{d}");
        let (a, c) = (&arcs[0].points, &circle[0].points);
        assert!(arcs[0].closed, "{d}");
        // Every arc sample lies on the circle (up to the centre's conditioning when the ends are
        // a diameter apart); samples as dense as the circle element's.
        let centre = DVec2::new(10.0, -10.0);
        assert!(a.iter().all(|p| (p.distance(centre) - 10.0).abs() < 1e-6), "{d}");
        assert!(
            (a.len() as f64 - c.len() as f64).abs() <= 0.01 * c.len() as f64 + 2.0,
            "{d}: {} vs {}",
            a.len(),
            c.len()
        );
        // Each outline within the other's chordal error (≈ step² / 8r).
        let tol = step * step / (8.0 * 10.0) * 1.01;
        assert!(a.iter().all(|&p| to_polygon(p, c) <= tol), "{d}");
        assert!(c.iter().all(|&p| to_polygon(p, a) <= tol), "{d}");
        let area = |p: &[DVec2]| crate::geom::polygon_signed_area(p).abs();
        assert!((area(a) - area(c)).abs() < 1e-3 * area(c), "{d}");
    }
}

#[test]
fn arc_edge_cases() {
    // Zero radius: a line; identical ends: no arc; rotated ellipse: on the ellipse.
    let p = read(r#"<svg><path d="M 0 0 A 0 5 0 0 1 3 4 A 1 1 0 0 1 3 4"/></svg>"#, 0.1);
    assert_eq!(p[0].points, vec![DVec2::new(0.0, 0.0), DVec2::new(3.0, -4.0)]);
    let p = read(r#"<svg><path d="M 2 0 A 2 1 90 1 1 -2 0"/></svg>"#, 0.01);
    // Radii 2, 1 with the axes turned by 90°: enlarged to 4, 2 to join (±2, 0), a half ellipse.
    let last = *p[0].points.last().unwrap();
    assert_eq!(last, DVec2::new(-2.0, 0.0));
    assert!(p[0].points.len() > 100);
    // The old test's arc: radius 1 cannot join (0, 0) and (2, 2): a half circle of radius √2.
    let p = read(r#"<svg><path d="M 0 0 A 1 1 0 0 0 2 2"/></svg>"#, 0.01);
    let c = DVec2::new(1.0, -1.0);
    assert!(p[0].points.iter().all(|q| (q.distance(c) - 2f64.sqrt()).abs() < 1e-9));
}

#[test]
fn shapes_and_units() {
    let svg = r#"<svg>
      <rect x="0" y="0" width="1in" height="2.54cm"/>
      <rect x="0" y="0" width="10" height="4" rx="1"/>
      <ellipse cx="0" cy="0" rx="3" ry="1"/>
      <ellipse cx="0" cy="0" ry="2"/>
      <polygon points="0,0 1,0 1,1"/>
      <polyline points="0 0 1 0 1 1" data-kind="inactive" data-sharpness="-20"/>
    </svg>"#;
    let p = read(svg, 0.1);
    assert_eq!(p.len(), 6);
    assert!(close(
        &p[0].points,
        &[DVec2::new(0.0, 0.0), DVec2::new(96.0, 0.0), DVec2::new(96.0, -96.0), DVec2::new(0.0, -96.0)],
        1e-9
    ));
    // Rounded corners: inside the rectangle, away from its corners, closed without a repeat.
    let r = &p[1].points;
    assert!(r.iter().all(|q| q.x >= -1e-12 && q.x <= 10.0 + 1e-12 && q.y <= 1e-12 && q.y >= -4.0 - 1e-12));
    assert!(r.iter().all(|q| q.distance(DVec2::new(0.0, 0.0)) > 0.4));
    assert!(r.first().unwrap().distance(*r.last().unwrap()) > 1e-6);
    let area = crate::geom::polygon_signed_area(r).abs();
    let exact = 40.0 - (4.0 - std::f64::consts::PI);
    assert!((area - exact).abs() < 1e-2, "{area} vs {exact}");
    assert!(p[2].points.iter().all(|q| (q.x * q.x / 9.0 + q.y * q.y - 1.0).abs() < 1e-9));
    // SVG 2: one radius given stands for both.
    assert!(p[3].points.iter().all(|q| (q.length() - 2.0).abs() < 1e-9));
    assert!(p[4].closed && !p[5].closed);
    assert_eq!(p[5].kind.as_deref(), Some("inactive"));
    assert_eq!(p[5].sharpness, Some(-20.0));
    // The old reader's forms: px, relative commands, smooth curves, implicit line-tos.
    let q = read(r#"<svg><path d="m 1 1 2 0 s 1 1 2 0 t 1 0 h 1 v 1 Z"/><circle r="2px"/></svg>"#, 0.1);
    assert_eq!(q.len(), 2);
    assert_eq!(q[0].points[..2], [DVec2::new(1.0, -1.0), DVec2::new(3.0, -1.0)]);
    assert_eq!(q[0].points.last().copied(), Some(DVec2::new(7.0, -2.0)));
    // A drawing command after Z starts at the closed subpath's start.
    let z = read(r#"<svg><path d="M 0 0 L 1 0 L 1 1 Z L 5 5"/></svg>"#, 0.1);
    assert_eq!(z[1].points, vec![DVec2::new(0.0, 0.0), DVec2::new(5.0, -5.0)]);
}

#[test]
fn errors_name_line_and_column() {
    // Path data: at the bad character.
    let (line, column, m) = error("<svg>\n  <path d=\"M 0 0 L 1 x\"/>\n</svg>");
    assert_eq!((line, column), (2, 22), "{m}");
    assert!(m.contains("<path> d"), "{m}");
    let (line, column, m) = error("<svg>\n<path d=\"M 0 0 L 1 2 X 3\"/></svg>");
    assert_eq!((line, column), (2, 22), "{m}");
    assert!(m.contains("'X'"), "{m}");
    let (line, column, _) = error("<svg>\n<path d=\"M 0 0 L 1\"/></svg>");
    assert_eq!((line, column), (2, 19));
    // Multi-byte characters count as one column.
    let (line, column, _) = error("<svg><!-- é -->\n<path d=\"M 0 0 L é\"/></svg>");
    assert_eq!((line, column), (2, 18));
    // Lengths, transforms, numbers.
    let (_, _, m) = error(r#"<svg><circle r="1em"/></svg>"#);
    assert!(m.contains("relative units"), "{m}");
    let (_, _, m) = error(r#"<svg><rect width="50%" height="1"/></svg>"#);
    assert!(m.contains("relative units"), "{m}");
    let (line, column, m) = error("<svg>\n<g transform=\"rotate(1,\"><circle r=\"1\"/></g></svg>");
    assert_eq!(line, 2, "{m}");
    assert!(column >= 15, "{column}");
    let (_, _, m) = error(r#"<svg><circle r="abc"/></svg>"#);
    assert!(m.contains("<circle> r"), "{m}");
    let (_, _, m) = error(r#"<svg><circle r="0"/></svg>"#);
    assert!(m.contains("positive"), "{m}");
    let (_, _, m) = error(r#"<svg><path d="M0 0L1 1" data-sharpness="sharp"/></svg>"#);
    assert!(m.contains("data-sharpness"), "{m}");
    let (_, _, m) = error(r#"<svg><path d="M0 0L1 1" data-sharpness="500"/></svg>"#);
    assert!(m.contains("[-180, 180]"), "{m}");
    let (_, _, m) = error(r#"<svg><polygon points="0 0 1"/></svg>"#);
    assert!(m.contains("even number"), "{m}");
    let (_, _, m) = error(r#"<svg><g transform="scale(1e300)"><circle r="1e300"/></g></svg>"#);
    assert!(m.contains("overflow"), "{m}");
    // XML: roxmltree's position.
    let (line, column, m) = error("<svg>\n<path d='M 0 0'>\n</svg>");
    assert_eq!((line, column), (3, 1), "{m}");
    assert!(m.starts_with("XML: "), "{m}");
    let (_, _, m) = error("<html><path d='M 0 0 L 1 1'/></html>");
    assert!(m.contains("not <svg>"), "{m}");
    let (_, _, m) = error("<svg><svg x=\"1\" viewBox=\"0 0 1 1\"><circle r=\"1\"/></svg></svg>");
    assert!(m.contains("viewBox"), "{m}");
}

#[test]
fn odd_inputs_are_errors_not_panics() {
    for svg in [
        "",
        "<",
        "<svg",
        "<svg/>",
        "<svg><path/></svg>",
        "<svg><path d=''/></svg>",
        "<svg><path d='M 0 0 A'/></svg>",
        "<svg><path d='M 0 0 A 1 1 0 2 0 1 1'/></svg>",
        "<svg><path d='M 0 0 A 1 1 0 é 0 1 1'/></svg>",
        "<svg><path d='é'/></svg>",
        "<svg><path d='M 0 0 Z 1'/></svg>",
        "<svg><path d='M 1e400 0 L 1 1'/></svg>",
        "<svg><g transform='é(1)'><circle r='1'/></g></svg>",
        "<svg><circle r='1' cx='1e308' transform='scale(10)'/></svg>",
        "<svg><use href='#'/></svg>",
        "<!DOCTYPE svg [<!ENTITY e SYSTEM 'file:///etc/passwd'>]><svg><path d='&e;'/></svg>",
        "\u{feff}<svg><circle r='1' transform='matrix(1)'/></svg>",
    ] {
        assert!(read_svg(svg, "t.svg", 0.1).is_err(), "{svg}");
    }
    // A DTD with internal entities is read.
    let p = read("<!DOCTYPE svg [<!ENTITY d 'M 0 0 L 1 1'>]><svg><path d='&d;'/></svg>", 0.1);
    assert_eq!(p[0].points.len(), 2);
    // The coarsest flattening (the first pass of `read_sketch`).
    let p = read("<svg><path d='M 0 0 C 1 1 2 1 3 0 A 5 5 0 0 1 0 0'/><circle r='1'/></svg>", f64::INFINITY);
    assert_eq!(p[0].points.len(), 1 + 4 + 4);
    assert_eq!(p[1].points.len(), 12);
}

#[test]
fn deep_nesting_is_read_without_recursion() {
    let read_nested = |n: usize| {
        let mut svg = String::with_capacity(n * 30);
        svg += "<svg>\n";
        for _ in 0..n {
            svg += "<g transform=\"translate(1 0)\">";
        }
        svg += "<circle r=\"1\"/>";
        for _ in 0..n {
            svg += "</g>";
        }
        svg += "</svg>";
        let start = std::time::Instant::now();
        let p = read(&svg, 0.1);
        (p, start.elapsed().as_secs_f64())
    };
    let (p, t) = read_nested(100_000);
    assert_eq!(p.len(), 1);
    let centre = p[0].points.iter().sum::<DVec2>() / p[0].points.len() as f64;
    assert!(centre.distance(DVec2::new(100_000.0, 0.0)) < 1e-6, "{centre}");
    assert_eq!(p[0].line, 2);
    // Linear: far below what recounting lines or a quadratic walk would take.
    assert!(t < 5.0, "{t} s");
}

#[test]
fn lines_and_columns_from_the_table() {
    let text = "ab\ncdé\n\nx";
    let l = Lines::new(text);
    assert_eq!(l.at(0), (1, 1));
    assert_eq!(l.at(2), (1, 3));
    assert_eq!(l.at(3), (2, 1));
    assert_eq!(l.at(7), (2, 4));
    assert_eq!(l.at(8), (3, 1));
    assert_eq!(l.at(9), (4, 1));
    assert_eq!(l.at(100), (4, 2));
}

#[test]
fn mutated_inputs_never_panic() {
    // A deterministic stand-in for the fuzz target: bytes of valid sketches replaced, inserted
    // or deleted (a small LCG), every result Ok with finite points or an Err.
    let seeds = [
        include_str!("../../../../../examples/sketches/leaf.svg"),
        r##"<svg xmlns:xlink="http://www.w3.org/1999/xlink"><defs><path id="p" d="M 0 0 A 5 3 30 1 0 10 10 Q 1 2 3 4 T 5 6 z"/></defs>
<g transform="rotate(30 5 5) skewY(10)"><use xlink:href="#p" x="1in" y="2"/><rect x="1" y="1" width="8" height="5" rx="2"/>
<ellipse cx="3" cy="3" rx="1" ry="2"/><polyline points="0,0 1,1 2,0"/><line x1="0" x2="3" y1="1" y2="1"/></g></svg>"##,
    ];
    let alphabet = b" <>/=\"'#-.,0123456789eEmMlLhHvVcCsSqQtTaAzZ()gusvdrx\xc3\xa9";
    let mut state = 0x2545_f491_4f6c_dd1du64;
    let mut next = move || {
        state = state.wrapping_mul(6_364_136_223_846_793_005).wrapping_add(1_442_695_040_888_963_407);
        (state >> 33) as usize
    };
    for round in 0..20_000 {
        let mut bytes = seeds[round % seeds.len()].as_bytes().to_vec();
        for _ in 0..1 + next() % 4 {
            let at = next() % bytes.len().max(1);
            let b = alphabet[next() % alphabet.len()];
            match next() % 3 {
                0 if at < bytes.len() => bytes[at] = b,
                1 => bytes.insert(at.min(bytes.len()), b),
                _ if at < bytes.len() => {
                    bytes.remove(at);
                }
                _ => {}
            }
        }
        let Ok(text) = std::str::from_utf8(&bytes) else { continue };
        for step in [f64::INFINITY, 0.5] {
            if let Ok(paths) = read_svg(text, "t.svg", step) {
                assert!(paths.iter().all(|p| p.points.len() >= 2 && p.points.iter().all(|q| q.is_finite())), "{text}");
            }
        }
    }
}
