//! Binary glTF 2.0 (`.glb`) out, for the web (three.js) and Blender: one mesh of one triangle
//! primitive with `POSITION`, `NORMAL`, the custom attributes `_MEAN_CURVATURE` (signed, `+1`
//! on a unit sphere) and `_CURVE` (1 on the input curves), and `UNSIGNED_INT` indices.
//!
//! glTF stores 32-bit floats, and one normal per vertex: vertices on sharp edges are repeated
//! once per sector of faces, with their sector's normal ([`crate::operators::split_normals`],
//! as the OBJ writer's `f v//vn`), so that creases look sharp. The coordinates are written as
//! they are (glTF's +Y up is the network's +Y).
//!
//! Layout (glTF 2.0 §4.4): a 12-byte header (`glTF`, version 2, total length), a JSON chunk
//! padded with spaces and a binary chunk padded with zeros, each to 4 bytes.

use super::mesh::MeshData;
use crate::geom::DVec3;
use std::io::Write;

/// glTF component type `FLOAT`.
const FLOAT: u32 = 5126;
/// glTF component type `UNSIGNED_INT`.
const UNSIGNED_INT: u32 = 5125;
/// Buffer view targets: vertex attributes, indices.
const ARRAY_BUFFER: u32 = 34962;
const ELEMENT_ARRAY_BUFFER: u32 = 34963;

/// One accessor over its own buffer view: a vertex attribute (named) or the indices.
struct Block {
    attribute: Option<&'static str>,
    component: u32,
    kind: &'static str,
    count: usize,
    bytes: Vec<u8>,
    bounds: Option<([f32; 3], [f32; 3])>,
}

fn floats(values: impl Iterator<Item = f32>, len: usize) -> Vec<u8> {
    let mut b = Vec::with_capacity(4 * len);
    for v in values {
        b.extend_from_slice(&v.to_le_bytes());
    }
    b
}

fn vec3s(values: &[DVec3]) -> Vec<u8> {
    floats(values.iter().flat_map(|p| [p.x as f32, p.y as f32, p.z as f32]), 3 * values.len())
}

/// Writes `m` as a GLB file to `w`.
pub(super) fn write_glb(w: &mut dyn Write, m: MeshData<'_>) -> std::io::Result<()> {
    // The glTF vertices: each mesh vertex once per normal sector.
    let split = m.normals.map(|ns| {
        crate::operators::split_normals(m.faces, m.positions, ns, crate::operators::SHARP_SHADING_DEG.to_radians())
    });
    let (vertex, faces): (Vec<u32>, &[[u32; 3]]) = match &split {
        Some(s) => (s.vertex.clone(), &s.corners),
        None => ((0..m.positions.len() as u32).collect(), m.faces),
    };
    let positions: Vec<DVec3> = vertex.iter().map(|&v| m.positions[v as usize]).collect();
    let (lo, hi) = positions.iter().fold(([f32::INFINITY; 3], [f32::NEG_INFINITY; 3]), |(lo, hi), p| {
        let q = [p.x as f32, p.y as f32, p.z as f32];
        (std::array::from_fn(|k| lo[k].min(q[k])), std::array::from_fn(|k| hi[k].max(q[k])))
    });
    let n = positions.len();
    let mut blocks = vec![Block {
        attribute: Some("POSITION"),
        component: FLOAT,
        kind: "VEC3",
        count: n,
        bytes: vec3s(&positions),
        bounds: (n > 0).then_some((lo, hi)),
    }];
    if let Some(s) = &split {
        let unit: Vec<DVec3> = s.normals.iter().map(|v| v.try_normalize().unwrap_or(DVec3::Z)).collect();
        blocks.push(Block {
            attribute: Some("NORMAL"),
            component: FLOAT,
            kind: "VEC3",
            count: n,
            bytes: vec3s(&unit),
            bounds: None,
        });
    }
    if let Some(h) = m.mean_curvature {
        let bytes = floats(vertex.iter().map(|&v| h[v as usize] as f32), n);
        blocks.push(Block {
            attribute: Some("_MEAN_CURVATURE"),
            component: FLOAT,
            kind: "SCALAR",
            count: n,
            bytes,
            bounds: None,
        });
    }
    if let Some(c) = m.curve_vertex {
        let bytes = floats(vertex.iter().map(|&v| if c[v as usize] { 1.0 } else { 0.0 }), n);
        blocks.push(Block {
            attribute: Some("_CURVE"),
            component: FLOAT,
            kind: "SCALAR",
            count: n,
            bytes,
            bounds: None,
        });
    }
    let mut indices = Vec::with_capacity(12 * faces.len());
    for f in faces {
        for &i in f {
            indices.extend_from_slice(&i.to_le_bytes());
        }
    }
    blocks.push(Block {
        attribute: None,
        component: UNSIGNED_INT,
        kind: "SCALAR",
        count: 3 * faces.len(),
        bytes: indices,
        bounds: None,
    });

    // The JSON document: one buffer, a view and an accessor per block (each 4-byte aligned).
    let (mut views, mut accessors, mut attributes) = (Vec::new(), Vec::new(), serde_json::Map::new());
    let mut offset = 0usize;
    let mut index_accessor = 0;
    for (k, b) in blocks.iter().enumerate() {
        let target = if b.attribute.is_some() { ARRAY_BUFFER } else { ELEMENT_ARRAY_BUFFER };
        views.push(serde_json::json!({
            "buffer": 0, "byteOffset": offset, "byteLength": b.bytes.len(), "target": target
        }));
        let mut accessor = serde_json::json!({
            "bufferView": k, "componentType": b.component, "count": b.count, "type": b.kind
        });
        if let Some((lo, hi)) = b.bounds {
            accessor["min"] = serde_json::json!(lo);
            accessor["max"] = serde_json::json!(hi);
        }
        accessors.push(accessor);
        match b.attribute {
            Some(name) => {
                attributes.insert(name.to_string(), serde_json::json!(k));
            }
            None => index_accessor = k,
        }
        offset += b.bytes.len().next_multiple_of(4);
    }
    let doc = serde_json::json!({
        "asset": { "version": "2.0", "generator": concat!("curvenet ", env!("CARGO_PKG_VERSION")) },
        "scene": 0,
        "scenes": [{ "nodes": [0] }],
        "nodes": [{ "mesh": 0, "name": "curvenet surface" }],
        "materials": [{
            "name": "surface",
            "pbrMetallicRoughness": { "baseColorFactor": [0.8, 0.8, 0.8, 1.0], "metallicFactor": 0.0, "roughnessFactor": 0.5 }
        }],
        "meshes": [{ "primitives": [{
            "attributes": attributes, "indices": index_accessor, "mode": 4, "material": 0
        }] }],
        "buffers": [{ "byteLength": offset }],
        "bufferViews": views,
        "accessors": accessors,
    });
    let mut json = serde_json::to_vec(&doc).map_err(std::io::Error::other)?;
    while json.len() % 4 != 0 {
        json.push(b' ');
    }
    let total = 12 + 8 + json.len() + 8 + offset;
    let total =
        u32::try_from(total).map_err(|_| std::io::Error::other("the mesh is too large for a GLB file (over 4 GiB)"))?;
    w.write_all(b"glTF")?;
    w.write_all(&2u32.to_le_bytes())?;
    w.write_all(&total.to_le_bytes())?;
    w.write_all(&(json.len() as u32).to_le_bytes())?;
    w.write_all(b"JSON")?;
    w.write_all(&json)?;
    w.write_all(&(offset as u32).to_le_bytes())?;
    w.write_all(b"BIN\0")?;
    for b in &blocks {
        w.write_all(&b.bytes)?;
        w.write_all(&[0u8; 3][..b.bytes.len().next_multiple_of(4) - b.bytes.len()])?;
    }
    Ok(())
}
