//! The `.net` format that the method's authors used for their own networks:
//!
//! ```text
//! N                      number of samples
//! x y z nx ny nz         N lines: position and normal of each sample
//! K                      number of curves
//! b                      K times two lines: boundary flag (1 or 0),
//! i0 i1 … ik             and the 0-based sample indices of the curve
//! ```
//! A closed curve repeats its first index at the end; crossing curves share the index of the
//! crossing sample. Blank lines and `#` comments are skipped.

use super::{parse_error, parse_f64, Tokens};
use crate::error::Result;
use crate::geom::DVec3;
use crate::network::{Curve, Network};
use std::collections::HashMap;
use std::io::Write;

pub(super) fn parse(text: &str, source: &str) -> Result<Network> {
    let mut lines = text.lines().enumerate().map(|(i, l)| Tokens::of_line(i + 1, l)).filter(|t| !t.is_empty());
    let last_line = text.lines().count().max(1);
    let eof = |what: &str| parse_error(source, last_line, 1, format!("file ends early: expected {what}"));

    let count = |t: &mut Tokens, what: &str| -> Result<usize> {
        let line = t.line;
        let (col, tok) = t.next().ok_or_else(|| parse_error(source, line, 1, format!("expected {what}")))?;
        let n = tok.parse::<usize>().map_err(|_| {
            parse_error(source, line, col, format!("expected {what} (a non-negative integer), found \"{tok}\""))
        })?;
        if let Some((col, tok)) = t.next() {
            return Err(parse_error(source, line, col, format!("unexpected \"{tok}\" after {what}")));
        }
        Ok(n)
    };

    let mut t = lines.next().ok_or_else(|| eof("the number of samples"))?;
    let n = count(&mut t, "the number of samples")?;
    let mut points = Vec::with_capacity(n.min(1 << 24));
    let mut normals = Vec::with_capacity(n.min(1 << 24));
    for k in 0..n {
        let mut t = lines.next().ok_or_else(|| eof(&format!("sample {k} of {n} (x y z nx ny nz)")))?;
        let mut c = [0.0; 6];
        for (j, cj) in c.iter_mut().enumerate() {
            let line = t.line;
            let (col, tok) = t.next().ok_or_else(|| {
                parse_error(source, line, 1, format!("sample {k}: expected 6 numbers (x y z nx ny nz), found {j}"))
            })?;
            *cj = parse_f64(source, line, col, tok, &format!("sample {k}"))?;
        }
        if let Some((col, tok)) = t.next() {
            return Err(parse_error(source, t.line, col, format!("sample {k}: unexpected 7th value \"{tok}\"")));
        }
        points.push(DVec3::new(c[0], c[1], c[2]));
        normals.push(DVec3::new(c[3], c[4], c[5]));
    }
    let mut t = lines.next().ok_or_else(|| eof("the number of curves"))?;
    let k = count(&mut t, "the number of curves")?;
    let mut curves = Vec::with_capacity(k.min(1 << 20));
    for ci in 0..k {
        let mut t = lines.next().ok_or_else(|| eof(&format!("the boundary flag of curve {ci}")))?;
        let line = t.line;
        let (col, tok) = t.next().ok_or_else(|| eof("a boundary flag"))?;
        let boundary = match tok {
            "1" => true,
            "0" => false,
            _ => {
                return Err(parse_error(
                    source,
                    line,
                    col,
                    format!("curve {ci}: boundary flag must be 1 or 0, found \"{tok}\""),
                ))
            }
        };
        if let Some((col, tok)) = t.next() {
            return Err(parse_error(
                source,
                line,
                col,
                format!("curve {ci}: unexpected \"{tok}\" after the boundary flag"),
            ));
        }
        let mut t = lines.next().ok_or_else(|| eof(&format!("the sample indices of curve {ci}")))?;
        let line = t.line;
        let mut ids = Vec::with_capacity(t.remaining());
        while let Some((col, tok)) = t.next() {
            let i: usize = tok.parse().map_err(|_| {
                parse_error(source, line, col, format!("curve {ci}: expected a sample index, found \"{tok}\""))
            })?;
            if i >= n {
                return Err(parse_error(
                    source,
                    line,
                    col,
                    format!(
                        "curve {ci}: sample index {i} is out of range (the file has {n} samples, indices 0..{})",
                        n.saturating_sub(1)
                    ),
                ));
            }
            ids.push(i);
        }
        let closed = ids.len() > 2 && ids[0] == ids[ids.len() - 1];
        if closed {
            ids.pop();
        }
        curves.push(Curve {
            name: None,
            points: ids.iter().map(|&i| points[i]).collect(),
            normals: ids.iter().map(|&i| normals[i]).collect(),
            normals_right: Vec::new(),
            closed,
            boundary,
        });
    }
    if let Some(t) = lines.next() {
        return Err(parse_error(source, t.line, 1, format!("unexpected content after the {k} curves")));
    }
    Ok(Network { curves, snap: None, cycles: None })
}

pub(super) fn write(w: &mut dyn Write, net: &Network) -> std::io::Result<()> {
    // Bit-identical positions share one sample, so that crossings stay shared.
    let mut index: HashMap<[u64; 3], usize> = HashMap::new();
    let mut samples: Vec<(DVec3, DVec3)> = Vec::new();
    let mut curves_ids = Vec::with_capacity(net.curves.len());
    for c in &net.curves {
        let mut ids = Vec::with_capacity(c.points.len() + 1);
        for (p, n) in c.points.iter().zip(&c.normals) {
            let key = [p.x.to_bits(), p.y.to_bits(), p.z.to_bits()];
            let id = *index.entry(key).or_insert_with(|| {
                samples.push((*p, *n));
                samples.len() - 1
            });
            ids.push(id);
        }
        if c.closed {
            ids.push(ids[0]);
        }
        curves_ids.push(ids);
    }
    writeln!(w, "{}", samples.len())?;
    for (p, n) in &samples {
        writeln!(w, "{:?} {:?} {:?} {:?} {:?} {:?}", p.x, p.y, p.z, n.x, n.y, n.z)?;
    }
    writeln!(w, "{}", net.curves.len())?;
    for (c, ids) in net.curves.iter().zip(&curves_ids) {
        writeln!(w, "{}", if c.boundary { 1 } else { 0 })?;
        let s: Vec<String> = ids.iter().map(|i| i.to_string()).collect();
        writeln!(w, "{}", s.join(" "))?;
    }
    Ok(())
}

#[cfg(test)]
#[path = "tests/net.rs"]
mod tests;
