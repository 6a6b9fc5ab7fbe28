//! Curve networks as Wavefront OBJ polylines: `v x y z` samples, `vn x y z` normals paired
//! with the `v` lines by index (the i-th `vn` is the normal of the i-th `v`), `l i j k …`
//! polylines (1-based or negative relative indices; `i/…` forms accepted), closed when the
//! first and last index agree. Polylines under `g boundary` are boundary curves; `g`/`o` names
//! name the curves. Other statements (`vt`, `f`, `usemtl`, …) are ignored.

use super::{parse_error, parse_f64, Tokens};
use crate::error::Result;
use crate::geom::DVec3;
use crate::network::{Curve, Network};
use std::io::Write;

pub(super) fn parse(text: &str, source: &str) -> Result<Network> {
    let mut v: Vec<DVec3> = Vec::new();
    let mut vn: Vec<DVec3> = Vec::new();
    // (line, column, index) per polyline sample, resolved once all v lines are known.
    struct Poly {
        name: Option<String>,
        boundary: bool,
        idx: Vec<(usize, usize, i64)>,
    }
    let mut polys: Vec<Poly> = Vec::new();
    let mut group: Option<String> = None;
    let mut boundary = false;
    let mut faces = 0usize;
    for (li, line) in text.lines().enumerate() {
        let mut t = Tokens::of_line(li + 1, line);
        let Some((_, kw)) = t.next() else { continue };
        match kw {
            "v" | "vn" => {
                let what = if kw == "v" { "a vertex coordinate" } else { "a normal coordinate" };
                let mut c = [0.0; 3];
                for (k, ck) in c.iter_mut().enumerate() {
                    let Some((col, tok)) = t.next() else {
                        return Err(parse_error(
                            source,
                            li + 1,
                            line.len() + 1,
                            format!("\"{kw}\" needs 3 numbers, found {k}"),
                        ));
                    };
                    *ck = parse_f64(source, li + 1, col, tok, what)?;
                }
                if kw == "v" {
                    v.push(DVec3::from_array(c))
                } else {
                    vn.push(DVec3::from_array(c))
                }
            }
            "l" => {
                let mut idx = Vec::new();
                while let Some((col, tok)) = t.next() {
                    let head = tok.split('/').next().unwrap_or(tok);
                    let i: i64 = head.parse().map_err(|_| {
                        parse_error(source, li + 1, col, format!("expected a vertex index, found \"{tok}\""))
                    })?;
                    // Negative indices are relative to the vertices read so far.
                    let i = if i < 0 { v.len() as i64 + i + 1 } else { i };
                    idx.push((li + 1, col, i));
                }
                if idx.len() < 2 {
                    return Err(parse_error(source, li + 1, 1, "a polyline (\"l\") needs at least 2 indices"));
                }
                polys.push(Poly { name: group.clone(), boundary, idx });
            }
            "g" | "o" => {
                let mut names = Vec::new();
                while let Some((_, tok)) = t.next() {
                    names.push(tok.to_string());
                }
                if kw == "g" {
                    boundary = names.iter().any(|n| n.eq_ignore_ascii_case("boundary"));
                }
                group = if names.is_empty() { None } else { Some(names.join(" ")) };
            }
            "f" => faces += 1,
            _ => {}
        }
    }
    if polys.is_empty() {
        let hint = if faces > 0 { " (the file has faces: it looks like a mesh, not a curve network)" } else { "" };
        return Err(parse_error(source, 1, 1, format!("no polylines (\"l\" lines) found{hint}")));
    }
    if vn.len() != v.len() {
        return Err(parse_error(
            source,
            1,
            1,
            format!(
                "{} \"v\" lines but {} \"vn\" lines; each sample needs a normal: the i-th \"vn\" is the normal of the i-th \"v\"",
                v.len(),
                vn.len()
            ),
        ));
    }
    let mut curves = Vec::with_capacity(polys.len());
    for p in polys {
        let mut ids = Vec::with_capacity(p.idx.len());
        for (line, col, i) in &p.idx {
            if *i < 1 || *i as usize > v.len() {
                return Err(parse_error(
                    source,
                    *line,
                    *col,
                    format!("vertex index {i} is out of range (the file has {} vertices)", v.len()),
                ));
            }
            ids.push(*i as usize - 1);
        }
        let closed = ids.len() > 2 && ids[0] == ids[ids.len() - 1];
        if closed {
            ids.pop();
        }
        curves.push(Curve {
            name: p.name,
            points: ids.iter().map(|&i| v[i]).collect(),
            normals: ids.iter().map(|&i| vn[i]).collect(),
            closed,
            boundary: p.boundary,
        });
    }
    Ok(Network { curves, snap: None })
}

pub(super) fn write(w: &mut dyn Write, net: &Network) -> std::io::Result<()> {
    writeln!(w, "# curve network written by curvenet: v/vn pairs by index, one l per curve")?;
    let mut base = 1usize;
    for (ci, c) in net.curves.iter().enumerate() {
        let name = c.name.clone().unwrap_or_else(|| format!("curve{ci}"));
        if c.boundary {
            writeln!(w, "g boundary")?;
        } else {
            writeln!(w, "g {}", name.replace(char::is_whitespace, "_"))?;
        }
        for p in &c.points {
            writeln!(w, "v {:?} {:?} {:?}", p.x, p.y, p.z)?;
        }
        for n in &c.normals {
            writeln!(w, "vn {:?} {:?} {:?}", n.x, n.y, n.z)?;
        }
        write!(w, "l")?;
        for i in 0..c.points.len() {
            write!(w, " {}", base + i)?;
        }
        if c.closed {
            write!(w, " {base}")?;
        }
        writeln!(w)?;
        base += c.points.len();
    }
    Ok(())
}

#[cfg(test)]
#[path = "tests/obj.rs"]
mod tests;
