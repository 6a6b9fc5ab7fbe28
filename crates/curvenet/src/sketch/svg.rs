//! A small SVG reader for sketches ([A11] §5): the outlines of `path` (`d` with M/L/H/V/C/S/Q/T/Z,
//! absolute and relative), `circle`, `ellipse`, `rect`, `polygon` and `polyline` elements, each
//! flattened to a polyline, with its `class` and `data-*` attributes. Transforms, arcs (`A`)
//! and units other than user units are not supported and reported as errors with the line.

use crate::error::{Error, Result};
use crate::geom::DVec2;

/// One flattened outline of a sketch.
#[derive(Clone, Debug, PartialEq)]
pub struct SketchPath {
    /// Points in SVG user units, y axis flipped (up) so that counter-clockwise is positive.
    pub points: Vec<DVec2>,
    pub closed: bool,
    /// The element's `class` attribute (space-separated names).
    pub class: String,
    /// `data-sharpness` (degrees), when given.
    pub sharpness: Option<f64>,
    /// `data-kind` (`crease`, `inactive`, `boundary`), when given.
    pub kind: Option<String>,
    /// 1-based line of the element in the file (for messages).
    pub line: usize,
}

fn err(source: &str, line: usize, msg: impl Into<String>) -> Error {
    Error::Parse { path: source.to_string(), line, column: 1, message: msg.into() }
}

/// The attributes of a start tag, `name="value"` or `name='value'`.
fn attributes(tag: &str) -> Vec<(String, String)> {
    let mut out = Vec::new();
    let b = tag.as_bytes();
    let mut i = 0;
    while i < b.len() {
        while i < b.len() && !(b[i].is_ascii_alphabetic() || b[i] == b'_') {
            i += 1;
        }
        let start = i;
        while i < b.len() && (b[i].is_ascii_alphanumeric() || matches!(b[i], b'-' | b'_' | b':' | b'.')) {
            i += 1;
        }
        let name = &tag[start..i];
        while i < b.len() && b[i].is_ascii_whitespace() {
            i += 1;
        }
        if i < b.len() && b[i] == b'=' {
            i += 1;
            while i < b.len() && b[i].is_ascii_whitespace() {
                i += 1;
            }
            if i < b.len() && (b[i] == b'"' || b[i] == b'\'') {
                let q = b[i];
                let vs = i + 1;
                i = vs;
                while i < b.len() && b[i] != q {
                    i += 1;
                }
                out.push((name.to_string(), tag[vs..i.min(tag.len())].to_string()));
                i += 1;
            }
        }
    }
    out
}

/// Numbers of a path or points list (commas or spaces, signs and exponents, "1.5.5" = 1.5 .5).
fn tokenize(d: &str) -> Vec<Tok> {
    let mut out = Vec::new();
    let b = d.as_bytes();
    let mut i = 0;
    while i < b.len() {
        let c = b[i];
        if c.is_ascii_alphabetic() && c != b'e' && c != b'E' {
            out.push(Tok::Cmd(c as char));
            i += 1;
        } else if c.is_ascii_digit() || c == b'-' || c == b'+' || c == b'.' {
            let s = i;
            i += 1;
            let mut dot = c == b'.';
            while i < b.len() {
                let x = b[i];
                if x.is_ascii_digit() {
                    i += 1;
                } else if x == b'.' && !dot {
                    dot = true;
                    i += 1;
                } else if (x == b'e' || x == b'E') && i + 1 < b.len() {
                    i += 1;
                    if b[i] == b'-' || b[i] == b'+' {
                        i += 1;
                    }
                    dot = true;
                } else {
                    break;
                }
            }
            out.push(d[s..i].parse::<f64>().map(Tok::Num).unwrap_or(Tok::Bad));
        } else {
            i += 1;
        }
    }
    out
}

#[derive(Clone, Copy, Debug, PartialEq)]
enum Tok {
    Cmd(char),
    Num(f64),
    Bad,
}

/// Segments per Bézier piece: enough for chords ≲ `step`.
fn pieces(len: f64, step: f64) -> usize {
    ((len / step).ceil() as usize).clamp(4, 10_000)
}

/// Flattens a path's `d` into subpaths `(points, closed)`; `step` is the flattening chord.
fn path_outlines(d: &str, step: f64) -> std::result::Result<Vec<(Vec<DVec2>, bool)>, String> {
    let toks = tokenize(d);
    let mut subs: Vec<(Vec<DVec2>, bool)> = Vec::new();
    let mut cur: Vec<DVec2> = Vec::new();
    let (mut p, mut start) = (DVec2::ZERO, DVec2::ZERO);
    let mut last_ctrl: Option<(char, DVec2)> = None;
    let mut i = 0;
    let mut cmd = ' ';
    let num = |i: &mut usize| -> std::result::Result<f64, String> {
        match toks.get(*i) {
            Some(Tok::Num(x)) => {
                *i += 1;
                Ok(*x)
            }
            Some(Tok::Bad) => Err("malformed number".into()),
            _ => Err(format!("path data: a number is missing (token {})", *i + 1)),
        }
    };
    let finish = |cur: &mut Vec<DVec2>, subs: &mut Vec<(Vec<DVec2>, bool)>, closed: bool| {
        if cur.len() >= 2 {
            subs.push((std::mem::take(cur), closed));
        } else {
            cur.clear();
        }
    };
    while i < toks.len() {
        match toks[i] {
            Tok::Cmd(c) => {
                cmd = c;
                i += 1;
                if c == 'Z' || c == 'z' {
                    if cur.first().is_some_and(|f| cur.last().is_some_and(|l| f.distance(*l) < 1e-12)) {
                        cur.pop();
                    }
                    finish(&mut cur, &mut subs, true);
                    p = start;
                    last_ctrl = None;
                    continue;
                }
            }
            Tok::Bad => return Err("malformed number in path data".into()),
            Tok::Num(_) => {
                if cmd == ' ' {
                    return Err("path data must start with a command (M)".into());
                }
            }
        }
        if matches!(cmd, 'Z' | 'z') {
            return Err("numbers after Z".into());
        }
        let rel = cmd.is_ascii_lowercase();
        let base = if rel { p } else { DVec2::ZERO };
        let pt = |i: &mut usize| -> std::result::Result<DVec2, String> { Ok(base + DVec2::new(num(i)?, num(i)?)) };
        match cmd.to_ascii_uppercase() {
            'M' => {
                finish(&mut cur, &mut subs, false);
                p = pt(&mut i)?;
                start = p;
                cur.push(p);
                // Further pairs are line-tos.
                cmd = if rel { 'l' } else { 'L' };
                last_ctrl = None;
            }
            'L' => {
                p = pt(&mut i)?;
                cur.push(p);
                last_ctrl = None;
            }
            'H' => {
                let x = num(&mut i)?;
                p = DVec2::new(if rel { p.x + x } else { x }, p.y);
                cur.push(p);
                last_ctrl = None;
            }
            'V' => {
                let y = num(&mut i)?;
                p = DVec2::new(p.x, if rel { p.y + y } else { y });
                cur.push(p);
                last_ctrl = None;
            }
            'C' | 'S' => {
                let c1 = if cmd.to_ascii_uppercase() == 'C' {
                    pt(&mut i)?
                } else {
                    match last_ctrl {
                        Some(('C', c)) => 2.0 * p - c,
                        _ => p,
                    }
                };
                let c2 = pt(&mut i)?;
                let e = pt(&mut i)?;
                let len = p.distance(c1) + c1.distance(c2) + c2.distance(e);
                let n = pieces(len, step);
                for k in 1..=n {
                    let t = k as f64 / n as f64;
                    let s = 1.0 - t;
                    cur.push(s * s * s * p + 3.0 * s * s * t * c1 + 3.0 * s * t * t * c2 + t * t * t * e);
                }
                last_ctrl = Some(('C', c2));
                p = e;
            }
            'Q' | 'T' => {
                let c = if cmd.to_ascii_uppercase() == 'Q' {
                    pt(&mut i)?
                } else {
                    match last_ctrl {
                        Some(('Q', c)) => 2.0 * p - c,
                        _ => p,
                    }
                };
                let e = pt(&mut i)?;
                let n = pieces(p.distance(c) + c.distance(e), step);
                for k in 1..=n {
                    let t = k as f64 / n as f64;
                    let s = 1.0 - t;
                    cur.push(s * s * p + 2.0 * s * t * c + t * t * e);
                }
                last_ctrl = Some(('Q', c));
                p = e;
            }
            other => return Err(format!("path command {other} is not supported (use M, L, H, V, C, S, Q, T, Z)")),
        }
    }
    finish(&mut cur, &mut subs, false);
    Ok(subs)
}

/// Reads the outlines of an SVG text. `step` is the flattening chord length (user units).
pub fn read_svg(text: &str, source: &str, step: f64) -> Result<Vec<SketchPath>> {
    let mut out = Vec::new();
    let mut pos = 0;
    while let Some(lt) = text[pos..].find('<') {
        let start = pos + lt;
        let line = text[..start].bytes().filter(|&c| c == b'\n').count() + 1;
        if text[start..].starts_with("<!--") {
            pos = start + text[start..].find("-->").map(|e| e + 3).unwrap_or(text.len() - start);
            continue;
        }
        let Some(gt) = text[start..].find('>') else {
            return Err(err(source, line, "unterminated tag"));
        };
        let tag = &text[start + 1..start + gt];
        pos = start + gt + 1;
        let name: String = tag.chars().take_while(|c| c.is_ascii_alphanumeric() || *c == ':').collect();
        let name = name.rsplit(':').next().unwrap_or("").to_string();
        if !matches!(name.as_str(), "path" | "circle" | "ellipse" | "rect" | "polygon" | "polyline") {
            continue;
        }
        let attrs = attributes(&tag[name.len()..]);
        let get = |k: &str| attrs.iter().find(|(n, _)| n == k).map(|(_, v)| v.as_str());
        if get("transform").is_some() {
            return Err(err(
                source,
                line,
                format!("<{name}>: the transform attribute is not supported; apply it to the coordinates"),
            ));
        }
        let f = |k: &str| -> Result<f64> {
            let v = get(k).unwrap_or("0");
            v.trim()
                .trim_end_matches("px")
                .parse::<f64>()
                .map_err(|_| err(source, line, format!("<{name}>: {k}=\"{v}\" is not a number")))
        };
        let outlines: Vec<(Vec<DVec2>, bool)> = match name.as_str() {
            "path" => {
                path_outlines(get("d").unwrap_or(""), step).map_err(|m| err(source, line, format!("<path>: {m}")))?
            }
            "circle" | "ellipse" => {
                let (cx, cy) = (f("cx")?, f("cy")?);
                let (rx, ry) = if name == "circle" { (f("r")?, f("r")?) } else { (f("rx")?, f("ry")?) };
                if !(rx > 0.0 && ry > 0.0) {
                    return Err(err(source, line, format!("<{name}>: the radius must be positive")));
                }
                let n = pieces(std::f64::consts::TAU * rx.max(ry), step).max(12);
                let pts = (0..n)
                    .map(|k| {
                        let a = std::f64::consts::TAU * k as f64 / n as f64;
                        DVec2::new(cx + rx * a.cos(), cy + ry * a.sin())
                    })
                    .collect();
                vec![(pts, true)]
            }
            "rect" => {
                let (x, y, w, h) = (f("x")?, f("y")?, f("width")?, f("height")?);
                if !(w > 0.0 && h > 0.0) {
                    return Err(err(source, line, "<rect>: width and height must be positive"));
                }
                vec![(
                    vec![DVec2::new(x, y), DVec2::new(x + w, y), DVec2::new(x + w, y + h), DVec2::new(x, y + h)],
                    true,
                )]
            }
            _ => {
                let nums: Vec<f64> = tokenize(get("points").unwrap_or(""))
                    .into_iter()
                    .filter_map(|t| if let Tok::Num(x) = t { Some(x) } else { None })
                    .collect();
                if nums.len() < 4 || nums.len() % 2 != 0 {
                    return Err(err(
                        source,
                        line,
                        format!("<{name}>: points must hold an even number (≥ 4) of coordinates"),
                    ));
                }
                vec![(nums.chunks(2).map(|c| DVec2::new(c[0], c[1])).collect(), name == "polygon")]
            }
        };
        let sharpness = match get("data-sharpness") {
            Some(v) => Some(
                v.trim()
                    .parse::<f64>()
                    .map_err(|_| err(source, line, format!("data-sharpness=\"{v}\" is not a number")))?,
            ),
            None => None,
        };
        for (points, closed) in outlines {
            out.push(SketchPath {
                // SVG's y axis points down: flip it.
                points: points.into_iter().map(|p| DVec2::new(p.x, -p.y)).collect(),
                closed,
                class: get("class").unwrap_or("").to_string(),
                sharpness,
                kind: get("data-kind").map(str::to_string),
                line,
            });
        }
    }
    if out.is_empty() {
        return Err(err(source, 1, "no path, circle, ellipse, rect, polygon or polyline element"));
    }
    Ok(out)
}
