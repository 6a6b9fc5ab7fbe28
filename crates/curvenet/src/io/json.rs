//! The reference JSON network format (DESIGN §3):
//! `{"curves": [{"name", "closed", "boundary", "points": [[x,y,z],…], "normals": [[…],…]}], "snap"}`.
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
    normals: Vec<[f64; 3]>,
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
                normals: c.normals.iter().map(v).collect(),
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
            writeln!(
                w,
                "      \"name\": {},",
                serde_json::to_string(name).unwrap_or_default()
            )?;
        }
        writeln!(w, "      \"closed\": {},", c.closed)?;
        writeln!(w, "      \"boundary\": {},", c.boundary)?;
        writeln!(w, "      \"points\": [")?;
        write_points(w, &c.points)?;
        writeln!(w, "      ],")?;
        writeln!(w, "      \"normals\": [")?;
        write_points(w, &c.normals)?;
        writeln!(w, "      ]")?;
        writeln!(
            w,
            "    }}{}",
            if ci + 1 < net.curves.len() { "," } else { "" }
        )?;
    }
    writeln!(w, "  ]")?;
    writeln!(w, "}}")
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::error::Error;

    #[test]
    fn round_trip() {
        let net = Network {
            curves: vec![Curve {
                name: Some("a \"b\"".into()),
                points: vec![DVec3::new(0.1, 1.0 / 3.0, -2e-17), DVec3::X],
                normals: vec![DVec3::Z, DVec3::Z],
                closed: false,
                boundary: true,
            }],
            snap: Some(1e-5),
        };
        let mut buf = Vec::new();
        write(&mut buf, &net).unwrap();
        let back = parse(std::str::from_utf8(&buf).unwrap(), "t").unwrap();
        assert_eq!(back, net);
    }

    #[test]
    fn malformed_reports_line_and_column() {
        let text = "{\"curves\": [\n  {\"points\": [[0,0,0],[1,0]],\n \"normals\": []}]}";
        match parse(text, "x.json") {
            Err(Error::Parse {
                line,
                column,
                message,
                ..
            }) => {
                assert_eq!(line, 2);
                assert!(column > 20, "{column}");
                assert!(message.contains("length"), "{message}");
            }
            other => panic!("{other:?}"),
        }
        assert!(matches!(
            parse("{\"curves\": [", "x"),
            Err(Error::Parse { line: 1, .. })
        ));
    }
}
