//! The reference JSON network format (docs/design.md §3):
//! `{"curves": [{"name", "closed", "boundary", "points": [[x,y,z],…], "normals": [[…],…]}], "snap"}`.
//! A curve without `normals` (or with `"normals": null`) has unknown normals: they are inferred.
//! Unknown fields are read past so that later extensions stay readable by older versions, and
//! named in a warning with their line (and the closest known key: `normal` — did you mean
//! `normals`?), so that a misspelled field is never dropped without a word (issue 29).

use super::parse_error;
use crate::error::{Result, Warning};
use crate::geom::DVec3;
use crate::network::{Curve, Network};
use serde::de::{Deserializer, IgnoredAny, MapAccess, Visitor};
use serde::Deserialize;
use std::io::Write;

/// The keys of a network object, and of a curve (the last three: `--method cauchy`'s
/// attributes, read by `methods::andrews2011`).
const NETWORK_KEYS: [&str; 3] = ["curves", "snap", "cycles"];
const CURVE_KEYS: [&str; 9] =
    ["name", "closed", "boundary", "points", "normals", "normals_right", "kind", "sharpness", "stretch"];

struct JsonNetwork {
    curves: Vec<JsonCurve>,
    snap: Option<f64>,
    /// The patches' cycles, `[[curve, first, last, forward], …]` each (docs/design.md §15).
    cycles: Option<Vec<crate::network::CycleKey>>,
    /// Unknown keys, with the curve they were met in (`None`: the network object).
    unknown: Vec<(Option<usize>, String)>,
}

struct JsonCurve {
    name: Option<String>,
    closed: bool,
    boundary: bool,
    points: Vec<[f64; 3]>,
    /// Absent (or `null`): unknown, inferred (docs/design.md §12).
    normals: Option<Vec<[f64; 3]>>,
    /// A crease's second normal per sample (docs/design.md §13); absent: a smooth curve.
    normals_right: Option<Vec<[f64; 3]>>,
    unknown: Vec<String>,
}

/// `", found \"pionts\" — did you mean \"points\"?"` when one of `unknown` is close to `key`.
fn found_instead(key: &str, unknown: &[String]) -> String {
    match unknown.iter().find(|u| closest(u, &[key]).is_some()) {
        Some(u) => format!(" (found \"{u}\": did you mean \"{key}\"?)"),
        None => String::new(),
    }
}

impl<'de> Deserialize<'de> for JsonCurve {
    fn deserialize<D: Deserializer<'de>>(d: D) -> std::result::Result<Self, D::Error> {
        struct V;
        impl<'de> Visitor<'de> for V {
            type Value = JsonCurve;
            fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
                f.write_str("a curve object")
            }
            fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> std::result::Result<JsonCurve, A::Error> {
                let mut c = JsonCurve {
                    name: None,
                    closed: false,
                    boundary: false,
                    points: Vec::new(),
                    normals: None,
                    normals_right: None,
                    unknown: Vec::new(),
                };
                let mut has_points = false;
                while let Some(key) = map.next_key::<String>()? {
                    match key.as_str() {
                        "name" => c.name = map.next_value()?,
                        "closed" => c.closed = map.next_value()?,
                        "boundary" => c.boundary = map.next_value()?,
                        "points" => {
                            c.points = map.next_value()?;
                            has_points = true;
                        }
                        "normals" => c.normals = map.next_value()?,
                        "normals_right" => c.normals_right = map.next_value()?,
                        _ => {
                            map.next_value::<IgnoredAny>()?;
                            c.unknown.push(key);
                        }
                    }
                }
                if !has_points {
                    return Err(serde::de::Error::custom(format!(
                        "missing field `points`{}",
                        found_instead("points", &c.unknown)
                    )));
                }
                Ok(c)
            }
        }
        d.deserialize_map(V)
    }
}

impl<'de> Deserialize<'de> for JsonNetwork {
    fn deserialize<D: Deserializer<'de>>(d: D) -> std::result::Result<Self, D::Error> {
        struct V;
        impl<'de> Visitor<'de> for V {
            type Value = JsonNetwork;
            fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
                f.write_str("a network object with a \"curves\" list")
            }
            fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> std::result::Result<JsonNetwork, A::Error> {
                let (mut curves, mut snap, mut cycles, mut unknown) = (None::<Vec<JsonCurve>>, None, None, Vec::new());
                while let Some(key) = map.next_key::<String>()? {
                    match key.as_str() {
                        "curves" => curves = Some(map.next_value()?),
                        "snap" => snap = map.next_value()?,
                        "cycles" => cycles = map.next_value()?,
                        _ => {
                            map.next_value::<IgnoredAny>()?;
                            unknown.push(key);
                        }
                    }
                }
                let Some(mut curves) = curves else {
                    return Err(serde::de::Error::custom(format!(
                        "missing field `curves`{}",
                        found_instead("curves", &unknown)
                    )));
                };
                let mut all: Vec<(Option<usize>, String)> = unknown.into_iter().map(|k| (None, k)).collect();
                for (i, c) in curves.iter_mut().enumerate() {
                    all.extend(std::mem::take(&mut c.unknown).into_iter().map(|k| (Some(i), k)));
                }
                Ok(JsonNetwork { curves, snap, cycles, unknown: all })
            }
        }
        d.deserialize_map(V)
    }
}

/// The known key closest to `key` (edit distance at most 2, or one a prefix of the other:
/// `normal`, `boundry`, `pionts`, `point`), if any. Also the Python bindings' check of a
/// curve given as a dict.
pub fn closest<'a>(key: &str, known: &[&'a str]) -> Option<&'a str> {
    let k = key.to_ascii_lowercase();
    known
        .iter()
        .map(|&name| (edit_distance(&k, name), name))
        .filter(|&(d, name)| d <= 2 || (k.len() >= 4 && (name.starts_with(&k) || k.starts_with(name))))
        .min_by_key(|&(d, _)| d)
        .map(|(_, name)| name)
}

/// Levenshtein distance, with a transposition of neighbours counting one (`pionts`).
fn edit_distance(a: &str, b: &str) -> usize {
    let (a, b): (Vec<char>, Vec<char>) = (a.chars().collect(), b.chars().collect());
    let mut d = vec![vec![0usize; b.len() + 1]; a.len() + 1];
    for (i, row) in d.iter_mut().enumerate() {
        row[0] = i;
    }
    for j in 0..=b.len() {
        d[0][j] = j;
    }
    for i in 1..=a.len() {
        for j in 1..=b.len() {
            let cost = usize::from(a[i - 1] != b[j - 1]);
            d[i][j] = (d[i - 1][j] + 1).min(d[i][j - 1] + 1).min(d[i - 1][j - 1] + cost);
            if i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1] {
                d[i][j] = d[i][j].min(d[i - 2][j - 2] + 1);
            }
        }
    }
    d[a.len()][b.len()]
}

/// The 1-based line of the `n`-th occurrence (0-based) of `"key":` in `text`, for messages.
fn key_line(text: &str, key: &str, n: usize) -> Option<usize> {
    let quoted = format!("\"{key}\"");
    let mut found = 0;
    let mut from = 0;
    while let Some(i) = text[from..].find(&quoted) {
        let at = from + i;
        from = at + quoted.len();
        if text[from..].trim_start().starts_with(':') {
            if found == n {
                return Some(1 + text[..at].bytes().filter(|&b| b == b'\n').count());
            }
            found += 1;
        }
    }
    None
}

pub(super) fn parse(text: &str, source: &str) -> Result<(Network, Vec<Warning>)> {
    let raw: JsonNetwork = serde_json::from_str(text).map_err(|e| {
        let full = e.to_string();
        let message = match full.rfind(" at line ") {
            Some(i) => full[..i].to_string(),
            None => full,
        };
        parse_error(source, e.line(), e.column(), message)
    })?;
    let mut warnings = Vec::new();
    let mut seen: std::collections::HashMap<&str, usize> = std::collections::HashMap::new();
    for (curve, key) in &raw.unknown {
        let n = seen.entry(key.as_str()).or_insert(0);
        let line = key_line(text, key, *n).map_or(String::new(), |l| format!(":{l}"));
        *n += 1;
        let (place, known): (String, &[&str]) = match curve {
            Some(c) => (format!("curve {c}"), &CURVE_KEYS),
            None => ("the network".into(), &NETWORK_KEYS),
        };
        let hint = match closest(key, known) {
            Some(k) => format!(" — did you mean \"{k}\"?"),
            None => format!("; the known keys are {}", known.join(", ")),
        };
        let w = Warning::new(format!("{source}{line}: unknown key \"{key}\" in {place}, ignored{hint}"));
        warnings.push(match curve {
            Some(c) => w.curve(*c),
            None => w,
        });
    }
    let v = |a: &[f64; 3]| DVec3::from_array(*a);
    let network = Network {
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
        cycles: raw.cycles,
    };
    Ok((network, warnings))
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
    match &net.cycles {
        None => writeln!(w, "  ]")?,
        Some(cycles) => {
            // One cycle per line: `[curve, first sample, last sample, forward]` per segment.
            writeln!(w, "  ],")?;
            writeln!(w, "  \"cycles\": [")?;
            for (k, cycle) in cycles.iter().enumerate() {
                let segments: Vec<String> =
                    cycle.iter().map(|(c, f, l, fw)| format!("[{c}, {f}, {l}, {fw}]")).collect();
                writeln!(w, "    [{}]{}", segments.join(", "), if k + 1 < cycles.len() { "," } else { "" })?;
            }
            writeln!(w, "  ]")?;
        }
    }
    writeln!(w, "}}")
}

#[cfg(test)]
#[path = "tests/json.rs"]
mod tests;
