//! Triangle meshes out and back in (docs/design.md §4): OBJ and OFF (text, full `f64` round-trip
//! precision) and PLY (binary little-endian, with per-vertex normal, signed mean curvature
//! `mean_curvature` and the curve-vertex flag `curve`). The reader also accepts ASCII and
//! big-endian PLY and polygon faces (fan-triangulated), so that meshes from other tools load.

use super::{extension, parse_error, parse_f64, Staged, Tokens};
use crate::error::{Error, Result};
use crate::geom::DVec3;
use std::io::Write;
use std::path::Path;

/// A borrowed view of a mesh and its optional per-vertex attributes, for writing.
#[derive(Clone, Copy, Debug)]
pub struct MeshData<'a> {
    /// Vertex positions, `#V`.
    pub positions: &'a [DVec3],
    /// Triangles as vertex indices, counter-clockwise seen from outside, `#F`.
    pub faces: &'a [[u32; 3]],
    /// Unit vertex normals, `#V`.
    pub normals: Option<&'a [DVec3]>,
    /// Signed mean curvature per vertex (`+1` on a unit sphere with outward normals), `#V`.
    pub mean_curvature: Option<&'a [f64]>,
    /// `true` for vertices on the input curves, `#V`.
    pub curve_vertex: Option<&'a [bool]>,
    /// The propagated normals `N*` of normal-control (\[CG\] Fig. 5 compares them with the
    /// mesh's), `#V`. PLY only (`pnx pny pnz`).
    pub propagated_normals: Option<&'a [DVec3]>,
    /// OBJ only: the normals split where faces meet at a crease (`f v//vn`, one `vn` per
    /// corner group: creases look sharp in Blender and MeshLab), else one `vn` per vertex
    /// (`f v//v`: every vertex shared, so trimesh and Open3D read a watertight mesh).
    pub obj_split_normals: bool,
}

/// A mesh read from a file, with whichever attributes the file carried.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct MeshFile {
    /// Vertex positions, `#V`.
    pub positions: Vec<DVec3>,
    /// Triangles, `#F`.
    pub faces: Vec<[u32; 3]>,
    /// Vertex normals, when the file has them.
    pub normals: Option<Vec<DVec3>>,
    /// Signed mean curvature per vertex (PLY `mean_curvature`).
    pub mean_curvature: Option<Vec<f64>>,
    /// Per vertex: on a curve (PLY `curve`).
    pub curve_vertex: Option<Vec<bool>>,
    /// The propagated normals `N*` (PLY `pnx pny pnz`).
    pub propagated_normals: Option<Vec<DVec3>>,
}

impl MeshFile {
    /// The mesh and its attributes, for [`crate::io::write_mesh`].
    pub fn as_data(&self) -> MeshData<'_> {
        MeshData {
            positions: &self.positions,
            faces: &self.faces,
            normals: self.normals.as_deref(),
            mean_curvature: self.mean_curvature.as_deref(),
            curve_vertex: self.curve_vertex.as_deref(),
            propagated_normals: self.propagated_normals.as_deref(),
            obj_split_normals: true,
        }
    }
}

#[derive(Clone, Copy, PartialEq, Eq)]
enum MeshFormat {
    Obj,
    Ply,
    Off,
    /// Binary glTF: written, not read.
    Glb,
}

fn mesh_format(path: &Path) -> Result<MeshFormat> {
    match extension(path).as_str() {
        "obj" => Ok(MeshFormat::Obj),
        "ply" => Ok(MeshFormat::Ply),
        "off" => Ok(MeshFormat::Off),
        "glb" => Ok(MeshFormat::Glb),
        ext => Err(Error::usage(format!(
            "{}: unknown mesh format \".{ext}\"; use .obj, .ply, .off or .glb (written only)",
            path.display()
        ))),
    }
}

/// Checks that `path` names a mesh format this module writes (a usage error otherwise).
pub fn check_mesh_path(path: &Path) -> Result<()> {
    mesh_format(path).map(|_| ())
}

/// Writes a mesh; the format comes from the extension (`.obj`, `.ply`, `.off`, `.glb`). Atomic: on
/// failure `path` is left as it was.
pub fn write_mesh(path: &Path, mesh: MeshData<'_>) -> Result<()> {
    stage_mesh(path, mesh)?.commit()
}

/// Writes a mesh under a temporary name beside `path`; [`Staged::commit`] moves it into place.
pub fn stage_mesh(path: &Path, mesh: MeshData<'_>) -> Result<Staged> {
    let format = mesh_format(path)?;
    check_mesh_data(mesh)?;
    Staged::write(path, |w| write_format(w, format, mesh))
}

/// The bytes of a mesh file in the format of extension `ext` (`ply`, `obj`, `off`, `glb`),
/// as [`write_mesh`] writes it: for a download (the browser viewer) or a stream.
pub fn mesh_bytes(ext: &str, mesh: MeshData<'_>) -> Result<Vec<u8>> {
    let format = mesh_format(Path::new(&format!("mesh.{ext}")))?;
    check_mesh_data(mesh)?;
    let mut out = Vec::new();
    write_format(&mut out, format, mesh).map_err(|e| Error::internal(format!("writing the mesh: {e}")))?;
    Ok(out)
}

fn write_format(w: &mut dyn Write, format: MeshFormat, mesh: MeshData<'_>) -> std::io::Result<()> {
    match format {
        MeshFormat::Obj => write_obj(w, mesh),
        MeshFormat::Ply => write_ply(w, mesh),
        MeshFormat::Off => write_off(w, mesh),
        MeshFormat::Glb => super::glb::write_glb(w, mesh),
    }
}

/// One attribute entry per vertex, faces in range, every value finite: a usage error (sizes)
/// or a numerical failure (values) otherwise, before anything is written.
fn check_mesh_data(mesh: MeshData<'_>) -> Result<()> {
    let n = mesh.positions.len();
    for (name, len) in [
        ("normals", mesh.normals.map(|a| a.len())),
        ("mean_curvature", mesh.mean_curvature.map(|a| a.len())),
        ("curve_vertex", mesh.curve_vertex.map(|a| a.len())),
        ("propagated_normals", mesh.propagated_normals.map(|a| a.len())),
    ] {
        if let Some(len) = len {
            if len != n {
                return Err(Error::usage(format!("mesh attribute {name} has {len} entries for {n} vertices")));
            }
        }
    }
    if let Some(bad) = mesh.faces.iter().flatten().find(|&&i| i as usize >= n) {
        return Err(Error::usage(format!("mesh face refers to vertex {bad} but there are {n} vertices")));
    }
    // No NaN or infinity is ever written: a non-finite value is a numerical failure upstream.
    let vectors =
        [("position", Some(mesh.positions)), ("normal", mesh.normals), ("propagated normal", mesh.propagated_normals)];
    for (name, values) in vectors {
        if let Some(i) = values.and_then(|v| v.iter().position(|p| !p.is_finite())) {
            return Err(Error::numerical(format!("vertex {i}: its {name} is not finite; nothing was written")));
        }
    }
    if let Some(i) = mesh.mean_curvature.and_then(|h| h.iter().position(|h| !h.is_finite())) {
        return Err(Error::numerical(format!("vertex {i}: its mean curvature is not finite; nothing was written")));
    }
    Ok(())
}

/// Formats `count` records in chunks (each record appended to a byte buffer by `record`) and
/// writes them in order. Formatting runs on as many threads as rayon's pool has, taking the
/// chunks in order, while the calling thread writes each chunk as soon as it and those before
/// it are ready (the file system's copy overlaps the formatting): text output at several
/// million lines per second.
fn write_records(w: &mut dyn Write, count: usize, record: impl Fn(usize, &mut Vec<u8>) + Sync) -> std::io::Result<()> {
    use std::sync::atomic::{AtomicUsize, Ordering};
    use std::sync::{Condvar, Mutex};
    const CHUNK: usize = 16384;
    let chunks = count.div_ceil(CHUNK);
    let format = |c: usize| {
        let mut buf = Vec::with_capacity(CHUNK * 64);
        for i in c * CHUNK..((c + 1) * CHUNK).min(count) {
            record(i, &mut buf);
        }
        buf
    };
    let threads = rayon::current_num_threads();
    // One thread (WebAssembly, RAYON_NUM_THREADS=1) or a single chunk: format and write in turn.
    if chunks < 2 || threads < 2 || cfg!(target_arch = "wasm32") {
        for c in 0..chunks {
            w.write_all(&format(c))?;
        }
        return Ok(());
    }
    let next = AtomicUsize::new(0);
    let slots: Mutex<Vec<Option<Vec<u8>>>> = Mutex::new(vec![None; chunks]);
    let ready = Condvar::new();
    std::thread::scope(|scope| {
        for _ in 0..threads {
            scope.spawn(|| loop {
                let c = next.fetch_add(1, Ordering::Relaxed);
                if c >= chunks {
                    break;
                }
                let buf = format(c);
                slots.lock().unwrap_or_else(|e| e.into_inner())[c] = Some(buf);
                ready.notify_all();
            });
        }
        for c in 0..chunks {
            let mut guard = slots.lock().unwrap_or_else(|e| e.into_inner());
            let buf = loop {
                match guard[c].take() {
                    Some(b) => break b,
                    None => guard = ready.wait(guard).unwrap_or_else(|e| e.into_inner()),
                }
            };
            drop(guard);
            if let Err(e) = w.write_all(&buf) {
                // Stop the formatters at their next chunk.
                next.store(chunks, Ordering::Relaxed);
                return Err(e);
            }
        }
        Ok(())
    })
}

/// Appends a float with the shortest representation that reads back exactly (zmij: the
/// Schubfach/yy algorithm, 1.8× faster than ryu here; serde_json already depends on it).
fn put_f64(buf: &mut Vec<u8>, x: f64) {
    buf.extend_from_slice(zmij::Buffer::new().format(x).as_bytes());
}

fn put_u32(buf: &mut Vec<u8>, x: u32) {
    buf.extend_from_slice(itoa::Buffer::new().format(x).as_bytes());
}

fn put_vec3(buf: &mut Vec<u8>, head: &[u8], p: DVec3) {
    buf.extend_from_slice(head);
    for (k, c) in [p.x, p.y, p.z].into_iter().enumerate() {
        if k > 0 {
            buf.push(b' ');
        }
        put_f64(buf, c);
    }
    buf.push(b'\n');
}

/// OBJ with per-corner normals (`f v//vn`): the vertex normals, split where two faces' normals
/// are more than [`crate::operators::SHARP_SHADING_DEG`] apart so that creases look sharp in
/// Blender or MeshLab ([`crate::operators::split_normals`]; the positions stay shared); with
/// [`MeshData::obj_split_normals`] off, one normal per vertex (`f v//v`).
fn write_obj(w: &mut dyn Write, m: MeshData<'_>) -> std::io::Result<()> {
    writeln!(w, "# written by curvenet: {} vertices, {} faces", m.positions.len(), m.faces.len())?;
    let angle = crate::operators::SHARP_SHADING_DEG.to_radians();
    let split = m
        .normals
        .filter(|_| m.obj_split_normals)
        .map(|ns| crate::operators::split_normals(m.faces, m.positions, ns, angle));
    let (normals, corners): (&[DVec3], &[[u32; 3]]) = match (&split, m.normals) {
        (Some(s), _) => (&s.normals, &s.corners),
        (None, Some(ns)) => (ns, m.faces),
        (None, None) => (&[], m.faces),
    };
    // One stream of records: the positions, the normals, then the faces.
    let n = m.positions.len();
    let nn = normals.len();
    write_records(w, n + nn + m.faces.len(), |i, b| {
        if i < n {
            put_vec3(b, b"v ", m.positions[i]);
        } else if i < n + nn {
            put_vec3(b, b"vn ", normals[i - n]);
        } else {
            b.push(b'f');
            let fi = i - n - nn;
            for (k, &v) in m.faces[fi].iter().enumerate() {
                b.push(b' ');
                put_u32(b, v + 1);
                if nn > 0 {
                    b.extend_from_slice(b"//");
                    put_u32(b, corners[fi][k] + 1);
                }
            }
            b.push(b'\n');
        }
    })
}

fn write_off(w: &mut dyn Write, m: MeshData<'_>) -> std::io::Result<()> {
    writeln!(w, "OFF")?;
    writeln!(w, "{} {} 0", m.positions.len(), m.faces.len())?;
    write_records(w, m.positions.len(), |i, b| put_vec3(b, b"", m.positions[i]))?;
    write_records(w, m.faces.len(), |i, b| {
        b.push(b'3');
        for &v in &m.faces[i] {
            b.push(b' ');
            put_u32(b, v);
        }
        b.push(b'\n');
    })
}

/// Binary PLY. Every vertex property is a `double`, the curve flag too (0 or 1): libigl's
/// `read_triangle_mesh` refuses a file whose positions and normals differ in type, and one
/// whose other properties (read together as extra data) do; trimesh, Open3D, MeshLab and
/// Blender read doubles.
fn write_ply(w: &mut dyn Write, m: MeshData<'_>) -> std::io::Result<()> {
    writeln!(w, "ply\nformat binary_little_endian 1.0\ncomment written by curvenet")?;
    writeln!(w, "element vertex {}", m.positions.len())?;
    writeln!(w, "property double x\nproperty double y\nproperty double z")?;
    if m.normals.is_some() {
        writeln!(w, "property double nx\nproperty double ny\nproperty double nz")?;
    }
    if m.mean_curvature.is_some() {
        writeln!(w, "property double mean_curvature")?;
    }
    if m.curve_vertex.is_some() {
        writeln!(w, "property double curve")?;
    }
    if m.propagated_normals.is_some() {
        writeln!(w, "property double pnx\nproperty double pny\nproperty double pnz")?;
    }
    writeln!(w, "element face {}", m.faces.len())?;
    writeln!(w, "property list uchar int vertex_indices\nend_header")?;
    let mut buf = Vec::with_capacity(64);
    for i in 0..m.positions.len() {
        buf.clear();
        let p = m.positions[i];
        for c in [p.x, p.y, p.z] {
            buf.extend_from_slice(&c.to_le_bytes());
        }
        if let Some(ns) = m.normals {
            for c in [ns[i].x, ns[i].y, ns[i].z] {
                buf.extend_from_slice(&c.to_le_bytes());
            }
        }
        if let Some(h) = m.mean_curvature {
            buf.extend_from_slice(&h[i].to_le_bytes());
        }
        if let Some(c) = m.curve_vertex {
            buf.extend_from_slice(&(if c[i] { 1.0f64 } else { 0.0 }).to_le_bytes());
        }
        if let Some(pn) = m.propagated_normals {
            for c in [pn[i].x, pn[i].y, pn[i].z] {
                buf.extend_from_slice(&c.to_le_bytes());
            }
        }
        w.write_all(&buf)?;
    }
    for f in m.faces {
        buf.clear();
        buf.push(3);
        for &i in f {
            buf.extend_from_slice(&(i as i32).to_le_bytes());
        }
        w.write_all(&buf)?;
    }
    Ok(())
}

/// The format of a mesh to read: GLB is written only (a usage error).
fn readable_format(path: &Path) -> Result<MeshFormat> {
    match mesh_format(path)? {
        MeshFormat::Glb => Err(Error::usage(format!(
            "{}: GLB is an output format; read meshes from .obj, .ply or .off",
            path.display()
        ))),
        f => Ok(f),
    }
}

/// Reads a triangle mesh (`.obj`, `.off`, `.ply`); polygons are fan-triangulated.
pub fn read_mesh(path: &Path) -> Result<MeshFile> {
    let format = readable_format(path)?;
    let kind = if format == MeshFormat::Ply { super::InputKind::Ply } else { super::InputKind::Text };
    let bytes = super::read_input(path, kind, super::MAX_INPUT_BYTES)?;
    parse_mesh(&bytes, path, &path.display().to_string())
}

/// Parses a triangle mesh from the bytes of a file named `name` (its extension gives the
/// format); `source` names it in messages. What [`read_mesh`] does after reading the file.
pub fn parse_mesh(bytes: &[u8], name: &Path, source: &str) -> Result<MeshFile> {
    let format = readable_format(name)?;
    let source = source.to_string();
    let mesh = match format {
        MeshFormat::Ply => read_ply(bytes, &source)?,
        _ => {
            let text =
                std::str::from_utf8(bytes).map_err(|_| parse_error(&source, 1, 1, "file is not valid UTF-8 text"))?;
            if format == MeshFormat::Obj {
                read_obj(text, &source)?
            } else {
                read_off(text, &source)?
            }
        }
    };
    check_faces(&mesh, &source)?;
    Ok(mesh)
}

fn check_faces(m: &MeshFile, source: &str) -> Result<()> {
    let n = m.positions.len();
    for (fi, f) in m.faces.iter().enumerate() {
        for &i in f {
            if i as usize >= n {
                return Err(Error::input(format!(
                    "{source}: face {fi} refers to vertex {i}, but the mesh has {n} vertices"
                )));
            }
        }
    }
    Ok(())
}

fn fan(poly: &[u32], faces: &mut Vec<[u32; 3]>) {
    for k in 1..poly.len().saturating_sub(1) {
        faces.push([poly[0], poly[k], poly[k + 1]]);
    }
}

fn read_obj(text: &str, source: &str) -> Result<MeshFile> {
    let mut m = MeshFile::default();
    let mut normals = Vec::new();
    let mut poly = Vec::new();
    // Per face corner with a normal index (`v//vn`, `v/vt/vn`): (vertex, normal index).
    let mut corner_normals: Vec<(u32, usize)> = Vec::new();
    let mut corners_without = false;
    for (li, line) in text.lines().enumerate() {
        let mut t = Tokens::of_line(li + 1, line);
        let Some((_, kw)) = t.next() else { continue };
        match kw {
            "v" | "vn" => {
                let mut c = [0.0; 3];
                for (k, ck) in c.iter_mut().enumerate() {
                    let (col, tok) = t.next().ok_or_else(|| {
                        parse_error(source, li + 1, line.len() + 1, format!("\"{kw}\" needs 3 numbers, found {k}"))
                    })?;
                    *ck = parse_f64(source, li + 1, col, tok, "a coordinate")?;
                }
                if kw == "v" {
                    m.positions.push(DVec3::from_array(c))
                } else {
                    normals.push(DVec3::from_array(c))
                }
            }
            "f" => {
                poly.clear();
                while let Some((col, tok)) = t.next() {
                    let head = tok.split('/').next().unwrap_or(tok);
                    // The normal index, when the corner gives one and it is in range.
                    let vn = tok.split('/').nth(2).and_then(|x| x.parse::<i64>().ok()).and_then(|j| {
                        let j = if j < 0 { normals.len() as i64 + j } else { j - 1 };
                        (0..normals.len() as i64).contains(&j).then_some(j as usize)
                    });
                    let i: i64 = head.parse().map_err(|_| {
                        parse_error(source, li + 1, col, format!("expected a vertex index, found \"{tok}\""))
                    })?;
                    let i = if i < 0 { m.positions.len() as i64 + i } else { i - 1 };
                    if i < 0 || i >= m.positions.len() as i64 {
                        return Err(parse_error(source, li + 1, col, format!("vertex index {head} is out of range")));
                    }
                    poly.push(i as u32);
                    match vn {
                        Some(j) => corner_normals.push((i as u32, j)),
                        None => corners_without = true,
                    }
                }
                if poly.len() < 3 {
                    return Err(parse_error(source, li + 1, 1, "a face needs at least 3 vertices"));
                }
                fan(&poly, &mut m.faces);
            }
            _ => {}
        }
    }
    if !corner_normals.is_empty() && !corners_without {
        // Per-corner normals (split at creases, as curvenet writes them): each vertex gets the
        // mean of its corners' normals.
        let mut sum = vec![DVec3::ZERO; m.positions.len()];
        for &(v, j) in &corner_normals {
            sum[v as usize] += normals[j];
        }
        if sum.iter().all(|s| *s != DVec3::ZERO) {
            m.normals = Some(sum.iter().map(|s| s.normalize_or_zero()).collect());
        }
    } else if normals.len() == m.positions.len() && !normals.is_empty() {
        m.normals = Some(normals);
    }
    Ok(m)
}

fn read_off(text: &str, source: &str) -> Result<MeshFile> {
    let mut toks = text.lines().enumerate().map(|(i, l)| Tokens::of_line(i + 1, l)).filter(|t| !t.is_empty());
    let mut t = toks.next().ok_or_else(|| parse_error(source, 1, 1, "empty file"))?;
    let (col, head) = t.next().unwrap_or((1, ""));
    if !head.ends_with("OFF") {
        return Err(parse_error(source, t.line, col, format!("expected \"OFF\", found \"{head}\"")));
    }
    if t.is_empty() {
        t = toks.next().ok_or_else(|| parse_error(source, 1, 1, "missing vertex and face counts"))?;
    }
    let line = t.line;
    let mut counts = [0usize; 2];
    for c in counts.iter_mut() {
        let (col, tok) = t.next().ok_or_else(|| parse_error(source, line, 1, "expected vertex and face counts"))?;
        *c = tok.parse().map_err(|_| parse_error(source, line, col, format!("expected a count, found \"{tok}\"")))?;
    }
    let [nv, nf] = counts;
    let mut m = MeshFile::default();
    m.positions.reserve(nv.min(1 << 26));
    for k in 0..nv {
        let mut t =
            toks.next().ok_or_else(|| parse_error(source, line, 1, format!("file ends before vertex {k} of {nv}")))?;
        let mut c = [0.0; 3];
        for ck in c.iter_mut() {
            let l = t.line;
            let (col, tok) = t.next().ok_or_else(|| parse_error(source, l, 1, "a vertex needs 3 coordinates"))?;
            *ck = parse_f64(source, l, col, tok, "a coordinate")?;
        }
        m.positions.push(DVec3::from_array(c));
    }
    let mut poly = Vec::new();
    for k in 0..nf {
        let mut t =
            toks.next().ok_or_else(|| parse_error(source, line, 1, format!("file ends before face {k} of {nf}")))?;
        let l = t.line;
        let (col, tok) = t.next().ok_or_else(|| parse_error(source, l, 1, "empty face"))?;
        let deg: usize = tok
            .parse()
            .map_err(|_| parse_error(source, l, col, format!("expected a vertex count, found \"{tok}\"")))?;
        poly.clear();
        for _ in 0..deg {
            let (col, tok) = t
                .next()
                .ok_or_else(|| parse_error(source, l, 1, format!("face {k} lists fewer than {deg} vertices")))?;
            let i: usize = tok
                .parse()
                .map_err(|_| parse_error(source, l, col, format!("expected a vertex index, found \"{tok}\"")))?;
            if i >= nv {
                return Err(parse_error(source, l, col, format!("vertex index {i} is out of range ({nv} vertices)")));
            }
            poly.push(i as u32);
        }
        if deg < 3 {
            return Err(parse_error(source, l, col, "a face needs at least 3 vertices"));
        }
        fan(&poly, &mut m.faces);
    }
    Ok(m)
}

#[derive(Clone, Copy, PartialEq, Eq, Debug)]
enum Scalar {
    I8,
    U8,
    I16,
    U16,
    I32,
    U32,
    F32,
    F64,
}

impl Scalar {
    fn parse(s: &str) -> Option<Self> {
        Some(match s {
            "char" | "int8" => Self::I8,
            "uchar" | "uint8" => Self::U8,
            "short" | "int16" => Self::I16,
            "ushort" | "uint16" => Self::U16,
            "int" | "int32" => Self::I32,
            "uint" | "uint32" => Self::U32,
            "float" | "float32" => Self::F32,
            "double" | "float64" => Self::F64,
            _ => return None,
        })
    }
    fn size(self) -> usize {
        match self {
            Self::I8 | Self::U8 => 1,
            Self::I16 | Self::U16 => 2,
            Self::I32 | Self::U32 | Self::F32 => 4,
            Self::F64 => 8,
        }
    }
}

struct Prop {
    name: String,
    /// `Some(count type)` for list properties.
    list: Option<Scalar>,
    ty: Scalar,
}

struct Element {
    name: String,
    count: usize,
    props: Vec<Prop>,
}

/// A cursor over the body of a PLY file, ASCII or binary.
struct PlyReader<'a> {
    bytes: &'a [u8],
    pos: usize,
    ascii: bool,
    big_endian: bool,
    source: &'a str,
}

impl PlyReader<'_> {
    fn err(&self, msg: impl Into<String>) -> Error {
        Error::input(format!("{}: byte {}: {}", self.source, self.pos, msg.into()))
    }

    fn read(&mut self, ty: Scalar) -> Result<f64> {
        if self.ascii {
            while self.pos < self.bytes.len() && self.bytes[self.pos].is_ascii_whitespace() {
                self.pos += 1;
            }
            let start = self.pos;
            while self.pos < self.bytes.len() && !self.bytes[self.pos].is_ascii_whitespace() {
                self.pos += 1;
            }
            if start == self.pos {
                return Err(self.err("file ends early"));
            }
            let tok = std::str::from_utf8(&self.bytes[start..self.pos]).unwrap_or("?");
            return tok.parse::<f64>().map_err(|_| self.err(format!("expected a number, found \"{tok}\"")));
        }
        let n = ty.size();
        if self.pos + n > self.bytes.len() {
            return Err(self.err("file ends early"));
        }
        let mut b = [0u8; 8];
        b[..n].copy_from_slice(&self.bytes[self.pos..self.pos + n]);
        if self.big_endian {
            b[..n].reverse();
        }
        self.pos += n;
        Ok(match ty {
            Scalar::I8 => b[0] as i8 as f64,
            Scalar::U8 => b[0] as f64,
            Scalar::I16 => i16::from_le_bytes([b[0], b[1]]) as f64,
            Scalar::U16 => u16::from_le_bytes([b[0], b[1]]) as f64,
            Scalar::I32 => i32::from_le_bytes([b[0], b[1], b[2], b[3]]) as f64,
            Scalar::U32 => u32::from_le_bytes([b[0], b[1], b[2], b[3]]) as f64,
            Scalar::F32 => f32::from_le_bytes([b[0], b[1], b[2], b[3]]) as f64,
            Scalar::F64 => f64::from_le_bytes(b),
        })
    }
}

fn read_ply(bytes: &[u8], source: &str) -> Result<MeshFile> {
    let header_end = bytes
        .windows(10)
        .position(|w| w == b"end_header")
        .ok_or_else(|| parse_error(source, 1, 1, "not a PLY file: no \"end_header\""))?;
    let header =
        std::str::from_utf8(&bytes[..header_end]).map_err(|_| parse_error(source, 1, 1, "PLY header is not text"))?;
    let mut body = header_end + 10;
    while body < bytes.len() && bytes[body] != b'\n' {
        body += 1;
    }
    body += 1;
    let mut elements: Vec<Element> = Vec::new();
    let (mut ascii, mut big_endian) = (false, false);
    for (li, line) in header.lines().enumerate() {
        let mut t = Tokens::of_line(li + 1, line);
        let bad = |col: usize, msg: &str| parse_error(source, li + 1, col, msg.to_string());
        match t.next() {
            Some((_, "ply")) | Some((_, "comment")) | Some((_, "obj_info")) | None => {}
            Some((_, "format")) => match t.next() {
                Some((_, "ascii")) => ascii = true,
                Some((_, "binary_little_endian")) => {}
                Some((_, "binary_big_endian")) => big_endian = true,
                Some((col, _)) => return Err(bad(col, "unknown PLY format")),
                None => return Err(bad(1, "missing PLY format")),
            },
            Some((_, "element")) => {
                let name = t.next().map(|x| x.1.to_string()).unwrap_or_default();
                let (col, tok) = t.next().ok_or_else(|| bad(1, "element needs a count"))?;
                let count = tok.parse().map_err(|_| bad(col, "element count is not a number"))?;
                elements.push(Element { name, count, props: Vec::new() });
            }
            Some((col, "property")) => {
                let el = elements.last_mut().ok_or_else(|| bad(col, "property before any element"))?;
                let (c1, t1) = t.next().ok_or_else(|| bad(col, "property needs a type"))?;
                let prop = if t1 == "list" {
                    let (c2, t2) = t.next().ok_or_else(|| bad(c1, "list needs a count type"))?;
                    let (c3, t3) = t.next().ok_or_else(|| bad(c2, "list needs an item type"))?;
                    let name = t.next().map(|x| x.1.to_string()).unwrap_or_default();
                    Prop {
                        name,
                        list: Some(Scalar::parse(t2).ok_or_else(|| bad(c2, "unknown PLY type"))?),
                        ty: Scalar::parse(t3).ok_or_else(|| bad(c3, "unknown PLY type"))?,
                    }
                } else {
                    let name = t.next().map(|x| x.1.to_string()).unwrap_or_default();
                    Prop { name, list: None, ty: Scalar::parse(t1).ok_or_else(|| bad(c1, "unknown PLY type"))? }
                };
                el.props.push(prop);
            }
            Some((col, other)) => return Err(bad(col, &format!("unknown PLY header keyword \"{other}\""))),
        }
    }
    let mut r = PlyReader { bytes, pos: body, ascii, big_endian, source };
    let mut m = MeshFile::default();
    let mut poly = Vec::new();
    for el in &elements {
        let is_vertex = el.name == "vertex";
        let is_face = el.name == "face";
        let find = |n: &str| el.props.iter().position(|p| p.name == n);
        let (ix, iy, iz) = (find("x"), find("y"), find("z"));
        let (inx, iny, inz) = (find("nx"), find("ny"), find("nz"));
        let ih = find("mean_curvature");
        let ic = find("curve");
        let (ipx, ipy, ipz) = (find("pnx"), find("pny"), find("pnz"));
        let has_pn = is_vertex && ipx.is_some() && ipy.is_some() && ipz.is_some();
        let mut pnormals = Vec::new();
        if is_vertex && (ix.is_none() || iy.is_none() || iz.is_none()) {
            return Err(parse_error(source, 1, 1, "PLY vertex element lacks x, y or z"));
        }
        let has_n = is_vertex && inx.is_some() && iny.is_some() && inz.is_some();
        let mut normals = Vec::new();
        let mut curv = Vec::new();
        let mut flags = Vec::new();
        let mut vals = vec![0.0; el.props.len()];
        // An element without properties takes no bytes: skip it at once, whatever its count
        // (a fuzzed header declared 1.4e11 of them and the loop took minutes).
        let records = if el.props.is_empty() { 0 } else { el.count };
        for _ in 0..records {
            for (k, p) in el.props.iter().enumerate() {
                if let Some(cty) = p.list {
                    let len = r.read(cty)?;
                    if !(0.0..=1e6).contains(&len) {
                        return Err(r.err(format!("implausible list length {len}")));
                    }
                    poly.clear();
                    for _ in 0..len as usize {
                        let v = r.read(p.ty)?;
                        if is_face && (p.name == "vertex_indices" || p.name == "vertex_index") {
                            if v < 0.0 || v >= m.positions.len() as f64 {
                                return Err(r.err(format!("face refers to vertex {v}, out of range")));
                            }
                            poly.push(v as u32);
                        }
                    }
                    if is_face && !poly.is_empty() {
                        fan(&poly, &mut m.faces);
                    }
                } else {
                    vals[k] = r.read(p.ty)?;
                }
            }
            if is_vertex {
                let g = |i: Option<usize>| i.map(|i| vals[i]).unwrap_or(0.0);
                m.positions.push(DVec3::new(g(ix), g(iy), g(iz)));
                if has_n {
                    normals.push(DVec3::new(g(inx), g(iny), g(inz)));
                }
                if ih.is_some() {
                    curv.push(g(ih));
                }
                if ic.is_some() {
                    flags.push(g(ic) != 0.0);
                }
                if has_pn {
                    pnormals.push(DVec3::new(g(ipx), g(ipy), g(ipz)));
                }
            }
        }
        if is_vertex {
            m.normals = has_n.then_some(normals);
            m.mean_curvature = ih.map(|_| curv);
            m.curve_vertex = ic.map(|_| flags);
            m.propagated_normals = has_pn.then_some(pnormals);
        }
    }
    Ok(m)
}

#[cfg(test)]
#[path = "tests/mesh.rs"]
mod tests;
