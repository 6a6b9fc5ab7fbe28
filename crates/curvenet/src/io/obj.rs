//! Curve networks as Wavefront OBJ polylines: `v x y z` samples, `vn x y z` normals paired
//! with the `v` lines by index (the i-th `vn` is the normal of the i-th `v`), `l i j k …`
//! polylines (1-based or negative relative indices; `i/…` forms accepted), closed when the
//! first and last index agree. Polylines under `g boundary` are boundary curves; `g`/`o` names
//! name the curves. Other statements (`vt`, `f`, `usemtl`, …) are ignored.
//!
//! Without any `vn` the normals are unknown (inferred, docs/design.md §12), and the `l` lines
//! may be an **edge soup** as exporters write it (Blender, Houdini: one `l a b` per edge): the
//! lines of each group are chained into maximal polylines through the vertices they share,
//! split at vertices where other than two edges meet (nodes) and closed where they come back
//! to their start. A curve of such a file that no group names is named after the line of its
//! first `l` statement (`curve at line 1234`, [`crate::network::line_name`]): messages point
//! into the file.

use super::{parse_error, parse_f64, Tokens};
use crate::error::{Error, Result};
use crate::geom::{fmt_point, DVec3};
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
    if vn.is_empty() {
        return chain_soup(polys.into_iter().map(|p| (p.name, p.boundary, p.idx)).collect(), &v, source);
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
            normals_right: Vec::new(),
            closed,
            boundary: p.boundary,
        });
    }
    Ok(Network { curves, snap: None, cycles: None })
}

/// An `l` line's samples: `(line, column, index)` as read (1-based, resolved).
type LineIndices = Vec<(usize, usize, i64)>;

/// The curves of an OBJ without normals (module documentation): the `l` lines of each group
/// (name and boundary flag) chained through their shared vertices into maximal polylines, split
/// at vertices of valence other than 2.
fn chain_soup(lines: Vec<(Option<String>, bool, LineIndices)>, v: &[DVec3], source: &str) -> Result<Network> {
    // Groups in order of first appearance; edges per group.
    let mut groups: Vec<(Option<String>, bool, Vec<[usize; 2]>)> = Vec::new();
    let mut group_of: std::collections::HashMap<(Option<String>, bool), usize> = std::collections::HashMap::new();
    // The first `l` line of each edge: an unnamed curve is named after its first line in the
    // file, where a user can find it (issue 33: "curve 42" of an edge soup was nowhere).
    let mut line_of: std::collections::HashMap<[usize; 2], usize> = std::collections::HashMap::new();
    for (name, boundary, idx) in lines {
        let mut ids = Vec::with_capacity(idx.len());
        for (line, col, i) in &idx {
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
        let g = *group_of.entry((name.clone(), boundary)).or_insert_with(|| {
            groups.push((name, boundary, Vec::new()));
            groups.len() - 1
        });
        groups[g].2.extend(ids.windows(2).filter(|w| w[0] != w[1]).map(|w| [w[0], w[1]]));
        if let Some(&(line, _, _)) = idx.first() {
            for w in ids.windows(2) {
                line_of.entry([w[0].min(w[1]), w[0].max(w[1])]).or_insert(line);
            }
        }
    }
    let mut curves = Vec::new();
    for (name, boundary, edges) in groups {
        let chains = chain_edges(&edges);
        // An unnamed chain: the first line of its edges (closing edge included).
        let first_line = |ids: &[usize], closed: bool| {
            let closing = closed.then(|| [ids[ids.len() - 1], ids[0]]);
            ids.windows(2)
                .map(|w| [w[0], w[1]])
                .chain(closing)
                .filter_map(|[a, b]| line_of.get(&[a.min(b), a.max(b)]).copied())
                .min()
        };
        let names: Vec<Option<String>> = match &name {
            Some(_) => vec![None; chains.len()],
            None => {
                chains.iter().map(|(ids, closed)| first_line(ids, *closed).map(crate::network::line_name)).collect()
            }
        };
        let mut chained = chained_curves(v, None, chains, name.as_deref(), boundary);
        for (c, n) in chained.iter_mut().zip(names) {
            if n.is_some() {
                c.name = n;
            }
        }
        curves.extend(chained);
    }
    Ok(Network { curves, snap: None, cycles: None })
}

/// The curves of `chains` (of [`chain_edges`]) between `points`, with the points' `normals`
/// where given; the `k`-th chain of a group named `name` is named `name.k` (the first `name`).
fn chained_curves(
    points: &[DVec3],
    normals: Option<&[DVec3]>,
    chains: Vec<(Vec<usize>, bool)>,
    name: Option<&str>,
    boundary: bool,
) -> Vec<Curve> {
    chains
        .into_iter()
        .enumerate()
        .map(|(k, (ids, closed))| Curve {
            name: name.map(|n| if k == 0 { n.to_string() } else { format!("{n}.{k}") }),
            points: ids.iter().map(|&i| points[i]).collect(),
            normals: normals.map_or_else(Vec::new, |n| ids.iter().map(|&i| n[i]).collect()),
            normals_right: Vec::new(),
            closed,
            boundary,
        })
        .collect()
}

/// A network from a graph of points and edges (polyscope's `nodes (N, 3)` and `edges (E, 2)`,
/// meshio's points and line cells, an OBJ edge soup's `v` and `l`): the edges chained through
/// the points they share into maximal curves, split where a point has other than two edges
/// (an OBJ file without groups gives the same curves). `normals`, one per
/// point, are the curves' normals where given (else they are inferred). Points no edge uses are
/// ignored; an edge from a point to itself is skipped.
///
/// Errors ([`Error::Input`]): an edge index out of range, naming the edge; `normals` not one
/// per point; a point that is not finite.
pub fn network_from_edges(points: &[DVec3], edges: &[[i64; 2]], normals: Option<&[DVec3]>) -> Result<Network> {
    if let Some(n) = normals {
        if n.len() != points.len() {
            return Err(Error::input(format!(
                "{} normals for {} points: give one normal per point (or none, to infer them)",
                n.len(),
                points.len()
            )));
        }
    }
    let mut ids = Vec::with_capacity(edges.len());
    for (k, &[a, b]) in edges.iter().enumerate() {
        let at = |i: i64| {
            usize::try_from(i).ok().filter(|&i| i < points.len()).ok_or_else(|| {
                Error::input(format!(
                    "edge {k}: point index {i} is out of range (there are {} points, indexed from 0)",
                    points.len()
                ))
            })
        };
        let (a, b) = (at(a)?, at(b)?);
        if let Some(i) = [a, b].into_iter().find(|&i| !points[i].is_finite()) {
            return Err(Error::input(format!("edge {k}: point {i} is not finite ({})", fmt_point(points[i]))));
        }
        if a != b {
            ids.push([a, b]);
        }
    }
    Ok(Network { curves: chained_curves(points, normals, chain_edges(&ids), None, false), snap: None, cycles: None })
}

/// Maximal chains of the undirected `edges` (repeated edges counted once): vertex lists from
/// one vertex of valence ≠ 2 to the next, and the closed loops of valence-2 vertices
/// (`(vertices, closed)`, the loop's first vertex not repeated). Deterministic: chains start at
/// the lowest vertex.
pub(super) fn chain_edges(edges: &[[usize; 2]]) -> Vec<(Vec<usize>, bool)> {
    let mut unique: Vec<[usize; 2]> = edges.iter().map(|&[a, b]| [a.min(b), a.max(b)]).collect();
    unique.sort_unstable();
    unique.dedup();
    let mut adjacent: std::collections::BTreeMap<usize, Vec<usize>> = std::collections::BTreeMap::new();
    for (e, &[a, b]) in unique.iter().enumerate() {
        adjacent.entry(a).or_default().push(e);
        adjacent.entry(b).or_default().push(e);
    }
    let mut used = vec![false; unique.len()];
    let other = |e: usize, x: usize| if unique[e][0] == x { unique[e][1] } else { unique[e][0] };
    let mut out = Vec::new();
    // Walks from vertex `start` along edge `e` until a vertex of valence ≠ 2 or the start.
    let walk = |start: usize, mut e: usize, used: &mut Vec<bool>| -> (Vec<usize>, bool) {
        let mut chain = vec![start];
        let mut at = start;
        loop {
            used[e] = true;
            at = other(e, at);
            if at == start {
                return (chain, true);
            }
            chain.push(at);
            let around = &adjacent[&at];
            if around.len() != 2 {
                return (chain, false);
            }
            match around.iter().find(|&&f| !used[f]) {
                Some(&f) => e = f,
                None => return (chain, false),
            }
        }
    };
    for (&x, around) in &adjacent {
        if around.len() != 2 {
            for &e in around {
                if !used[e] {
                    out.push(walk(x, e, &mut used));
                }
            }
        }
    }
    for (&x, around) in &adjacent {
        for &e in around {
            if !used[e] {
                out.push(walk(x, e, &mut used));
            }
        }
    }
    out
}

pub(super) fn write(w: &mut dyn Write, net: &Network) -> std::io::Result<()> {
    // Without normals (every curve's unknown): `v` and `l` only; read back, they are inferred.
    let normals = net.has_all_normals();
    if normals {
        writeln!(w, "# curve network written by curvenet: v/vn pairs by index, one l per curve")?;
    } else {
        writeln!(w, "# curve network written by curvenet: v and one l per curve, no normals (inferred when read)")?;
    }
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
        if normals {
            for n in &c.normals {
                writeln!(w, "vn {:?} {:?} {:?}", n.x, n.y, n.z)?;
            }
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
