//! The reference JSON network format (docs/design.md §3):
//! `{"curves": [{"name", "closed", "boundary", "points": [[x,y,z],…], "normals": [[…],…]}], "snap"}`.
//! A curve without `normals` (or with `"normals": null`) has unknown normals: they are inferred.
//! Unknown fields are ignored so that later extensions stay readable by older versions.

use super::parse_error;
use crate::error::Result;
use crate::geom::DVec3;
use crate::network::{Curve, Network};
use serde::Deserialize;
use std::io::Write;

#[derive(Deserialize)]
struct JsonNetwork {
    curves: Vec<JsonCurve>,
    #[serde(default)]
    snap: Option<f64>,
}

#[derive(Deserialize)]
struct JsonCurve {
    #[serde(default)]
    name: Option<String>,
    #[serde(default)]
    closed: bool,
    #[serde(default)]
    boundary: bool,
    points: Vec<[f64; 3]>,
    /// Absent (or `null`): unknown, inferred (docs/design.md §12).
    #[serde(default)]
    normals: Option<Vec<[f64; 3]>>,
    /// A crease's second normal per sample (docs/design.md §13); absent: a smooth curve.
    #[serde(default)]
    normals_right: Option<Vec<[f64; 3]>>,
}

pub(super) fn parse(text: &str, source: &str) -> Result<Network> {
    let raw: JsonNetwork = serde_json::from_str(text).map_err(|e| {
        let full = e.to_string();
        let message = match full.rfind(" at line ") {
            Some(i) => full[..i].to_string(),
            None => full,
        };
        parse_error(source, e.line(), e.column(), message)
    })?;
    let v = |a: &[f64; 3]| DVec3::from_array(*a);
    Ok(Network {
        curves: raw
            .curves
            .into_iter()
            .map(|c| Curve {
                name: c.name,
                points: c.points.iter().map(v).collect(),
                normals: c.normals.iter().flatten().map(v).collect(),
                normals_right: c.normals_right.iter().flatten().map(v).collect(),
                closed: c.closed,
                boundary: c.boundary,
            })
            .collect(),
        snap: raw.snap,
    })
}

fn write_points(w: &mut dyn Write, pts: &[DVec3]) -> std::io::Result<()> {
    for (i, p) in pts.iter().enumerate() {
        let sep = if i + 1 < pts.len() { "," } else { "" };
        writeln!(w, "        [{:?}, {:?}, {:?}]{sep}", p.x, p.y, p.z)?;
    }
    Ok(())
}

pub(super) fn write(w: &mut dyn Write, net: &Network) -> std::io::Result<()> {
    writeln!(w, "{{")?;
    if let Some(s) = net.snap {
        writeln!(w, "  \"snap\": {s:?},")?;
    }
    writeln!(w, "  \"curves\": [")?;
    for (ci, c) in net.curves.iter().enumerate() {
        writeln!(w, "    {{")?;
        if let Some(name) = &c.name {
            writeln!(w, "      \"name\": {},", serde_json::to_string(name).unwrap_or_default())?;
        }
        writeln!(w, "      \"closed\": {},", c.closed)?;
        writeln!(w, "      \"boundary\": {},", c.boundary)?;
        writeln!(w, "      \"points\": [")?;
        write_points(w, &c.points)?;
        if c.has_normals() {
            writeln!(w, "      ],")?;
            writeln!(w, "      \"normals\": [")?;
            write_points(w, &c.normals)?;
        }
        if c.is_crease() {
            writeln!(w, "      ],")?;
            writeln!(w, "      \"normals_right\": [")?;
            write_points(w, &c.normals_right)?;
        }
        writeln!(w, "      ]")?;
        writeln!(w, "    }}{}", if ci + 1 < net.curves.len() { "," } else { "" })?;
    }
    writeln!(w, "  ]")?;
    writeln!(w, "}}")
}

#[cfg(test)]
#[path = "tests/json.rs"]
mod tests;
