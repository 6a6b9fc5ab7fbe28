//! curvenet for the browser viewer: the library behind a plain C ABI (no bindgen tool to
//! install). JavaScript copies text into memory from [`cn_alloc`], calls an entry point, and
//! reads the results as typed arrays over the module's memory through [`cn_buffer_ptr`] /
//! [`cn_buffer_len`], [`cn_text_ptr`] / [`cn_text_len`] and [`cn_stat`]. No numerics here: the
//! surfacing, curvature, colour maps and normal rotation are the library's.
//!
//! Entry points return 0 on success; otherwise the library's error message is in the text
//! buffer and the return value is its exit code (1 bad input, 2 usage, 3 numerical).

use curvenet::io::{parse_network, NetworkFormat};
use curvenet::render::{colormap, Scene};
use curvenet::{Error, Method, Network, Options};
use std::cell::RefCell;

/// Buffers readable from JavaScript, by index of [`cn_buffer_ptr`].
#[derive(Default)]
struct Output {
    /// 0: positions, `3 × #V` f32.
    positions: Vec<f32>,
    /// 1: triangles, `3 × #F` u32.
    faces: Vec<u32>,
    /// 2: unit vertex normals, `3 × #V` f32.
    normals: Vec<f32>,
    /// 3: colour by signed mean curvature (diverging map, ±range), `3 × #V` f32.
    curvature_colors: Vec<f32>,
    /// 4: colour by the angle between N* and the normals (empty without N*), `3 × #V` f32.
    deviation_colors: Vec<f32>,
    /// 5: the input curves' samples, polylines one after the other, `3 × #points` f32.
    curve_points: Vec<f32>,
    /// 6: start of each polyline in points, plus the end, u32.
    curve_offsets: Vec<u32>,
    /// 7: signed mean curvature, `#V` f32.
    mean_curvature: Vec<f32>,
    /// 8: the patch of each triangle, `#F` u32.
    face_patch: Vec<u32>,
    /// Statistics, by index of [`cn_stat`].
    stats: [f64; 8],
}

thread_local! {
    static OUTPUT: RefCell<Output> = RefCell::new(Output::default());
    static TEXT: RefCell<String> = const { RefCell::new(String::new()) };
    /// The last surface, for [`cn_export_mesh`].
    static LAST: RefCell<Option<curvenet::Surface>> = const { RefCell::new(None) };
    /// The bytes of the last export.
    static BYTES: RefCell<Vec<u8>> = const { RefCell::new(Vec::new()) };
    /// The curve of the last error (`u32::MAX`: none or unknown).
    static ERROR_CURVE: RefCell<u32> = const { RefCell::new(u32::MAX) };
}

fn set_text(text: String) {
    TEXT.with(|t| *t.borrow_mut() = text);
}

fn finish(result: Result<(), Error>) -> u32 {
    match result {
        Ok(()) => {
            ERROR_CURVE.with(|c| *c.borrow_mut() = u32::MAX);
            0
        }
        Err(e) => {
            let curve = e.at().curve.map_or(u32::MAX, |c| c.min(u32::MAX as usize - 1) as u32);
            ERROR_CURVE.with(|c| *c.borrow_mut() = curve);
            set_text(e.to_string());
            e.exit_code() as u32
        }
    }
}

/// The curve the last error names (the viewer highlights it), or `u32::MAX`.
#[no_mangle]
pub extern "C" fn cn_error_curve() -> u32 {
    ERROR_CURVE.with(|c| *c.borrow())
}

/// Memory for `len` bytes that JavaScript fills (free with [`cn_free`]).
#[no_mangle]
pub extern "C" fn cn_alloc(len: usize) -> *mut u8 {
    let mut v = Vec::<u8>::with_capacity(len.max(1));
    let p = v.as_mut_ptr();
    std::mem::forget(v);
    p
}

/// Frees memory from [`cn_alloc`].
///
/// # Safety
/// `ptr` and `len` must come from one call of [`cn_alloc`].
#[no_mangle]
pub unsafe extern "C" fn cn_free(ptr: *mut u8, len: usize) {
    drop(Vec::from_raw_parts(ptr, 0, len.max(1)));
}

/// # Safety
/// `ptr` must point to `len` readable bytes.
unsafe fn text_arg(ptr: *const u8, len: usize) -> Result<String, Error> {
    let bytes = std::slice::from_raw_parts(ptr, len);
    String::from_utf8(bytes.to_vec()).map_err(|e| Error::input(format!("the file is not UTF-8 text: {e}")))
}

fn format_of(code: u32) -> Result<NetworkFormat, Error> {
    match code {
        0 => Ok(NetworkFormat::Json),
        1 => Ok(NetworkFormat::Obj),
        2 => Ok(NetworkFormat::Net),
        _ => Err(Error::usage(format!("unknown network format code {code}"))),
    }
}

fn method_of(code: u32) -> Result<Method, Error> {
    Ok(match code {
        0 => Method::NormalControl,
        1 => Method::Biharmonic,
        2 => Method::Triharmonic,
        3 => Method::Method4,
        4 => Method::ShortPaper,
        5 => Method::Cauchy,
        _ => return Err(Error::usage(format!("unknown method code {code}"))),
    })
}

/// The viewer's options: `quality` 0 is `--fast`, 1 the default; `soft` ≤ 0 means hard.
pub fn options(method: u32, vertices: u32, soft: f64, quality: u32) -> Result<Options, Error> {
    let base = if quality == 0 { Options::fast() } else { Options::default() };
    Ok(Options { soft: if soft > 0.0 { Some(soft) } else { None }, ..base }
        .with_method(method_of(method)?)
        .with_vertices(vertices.max(100) as usize))
}

fn flat(v: &[curvenet::geom::DVec3]) -> Vec<f32> {
    v.iter().flat_map(|p| [p.x as f32, p.y as f32, p.z as f32]).collect()
}

/// Surfaces `network` and fills the output buffers.
pub fn surface_into_output(network: &Network, options: &Options) -> Result<(), Error> {
    let surface = curvenet::surface(network, options)?;
    let scene = Scene::from_surface(&surface).with_network_curves(network);
    let range = scene.curvature_range();
    let deviation = scene.normal_deviation_degrees();
    let dev_max = deviation.as_ref().map(|d| d.iter().copied().fold(0.0f64, f64::max).max(0.1)).unwrap_or(0.0);
    let mut out = Output {
        positions: flat(&scene.positions),
        faces: scene.faces.iter().flatten().copied().collect(),
        normals: flat(&scene.normals),
        curvature_colors: scene.mean_curvature.iter().flat_map(|h| colormap::diverging(h / range)).collect(),
        deviation_colors: deviation.iter().flatten().flat_map(|a| colormap::sequential(a / dev_max)).collect(),
        mean_curvature: scene.mean_curvature.iter().map(|&h| h as f32).collect(),
        face_patch: surface.mesh.face_patch.clone(),
        ..Default::default()
    };
    for c in &scene.curves {
        out.curve_offsets.push((out.curve_points.len() / 3) as u32);
        out.curve_points.extend(flat(c));
    }
    out.curve_offsets.push((out.curve_points.len() / 3) as u32);
    let s = &surface.stats;
    out.stats = [
        s.vertices as f64,
        s.faces as f64,
        s.curve_vertices as f64,
        s.cycles as f64,
        range,
        dev_max,
        s.spacing,
        surface.warnings.len() as f64,
    ];
    let warnings: Vec<String> = surface.warnings.iter().map(|w| w.to_string()).collect();
    set_text(warnings.join("\n"));
    OUTPUT.with(|o| *o.borrow_mut() = out);
    LAST.with(|l| *l.borrow_mut() = Some(surface));
    Ok(())
}

/// The curves of a network as polylines (buffers 5 and 6; the others emptied): what the viewer
/// shows before the surface is there, and where an error's curve is highlighted.
fn curves_into_output(network: &Network) {
    let mut out = Output::default();
    for c in &network.curves {
        out.curve_offsets.push((out.curve_points.len() / 3) as u32);
        out.curve_points.extend(flat(&c.points));
        if c.closed && !c.points.is_empty() {
            out.curve_points.extend(flat(&c.points[..1]));
        }
    }
    out.curve_offsets.push((out.curve_points.len() / 3) as u32);
    OUTPUT.with(|o| *o.borrow_mut() = out);
}

/// The network in `ptr[..len]` as polylines in buffers 5 (points) and 6 (offsets).
///
/// # Safety
/// `ptr` must point to `len` readable bytes.
#[no_mangle]
pub unsafe extern "C" fn cn_network_curves(ptr: *const u8, len: usize, format: u32) -> u32 {
    finish((|| {
        let text = text_arg(ptr, len)?;
        curves_into_output(&parse_network(&text, format_of(format)?, "network")?);
        Ok(())
    })())
}

/// The last surface as a mesh file (`format`: 0 PLY, 1 OBJ, 2 GLB, 3 OFF, as the command line
/// writes them) in the bytes buffer ([`cn_bytes_ptr`], [`cn_bytes_len`]).
#[no_mangle]
pub extern "C" fn cn_export_mesh(format: u32) -> u32 {
    finish((|| {
        let ext = match format {
            0 => "ply",
            1 => "obj",
            2 => "glb",
            3 => "off",
            _ => return Err(Error::usage(format!("unknown mesh format code {format}"))),
        };
        let bytes = LAST.with(|l| match l.borrow().as_ref() {
            Some(s) => curvenet::io::mesh_bytes(ext, s.mesh_data()),
            None => Err(Error::usage("no surface to export yet")),
        })?;
        BYTES.with(|b| *b.borrow_mut() = bytes);
        Ok(())
    })())
}

/// Address of the bytes buffer (the last export).
#[no_mangle]
pub extern "C" fn cn_bytes_ptr() -> *const u8 {
    BYTES.with(|b| b.borrow().as_ptr())
}

/// Length of the bytes buffer.
#[no_mangle]
pub extern "C" fn cn_bytes_len() -> usize {
    BYTES.with(|b| b.borrow().len())
}

/// Surfaces the network in `ptr[..len]` (`format`: 0 JSON, 1 OBJ, 2 .net) with `method`
/// (0 normal-control, 1 biharmonic, 2 triharmonic, 3 method (4), 4 short paper, 5 cauchy
/// (\[A11\], order 2)), about
/// `vertices` vertices, soft constraints `soft` (≤ 0: hard) and `quality` (0 fast, 1 default).
/// Warnings go to the text buffer.
///
/// # Safety
/// `ptr` must point to `len` readable bytes.
#[no_mangle]
pub unsafe extern "C" fn cn_surface(
    ptr: *const u8,
    len: usize,
    format: u32,
    method: u32,
    vertices: u32,
    soft: f64,
    quality: u32,
) -> u32 {
    finish((|| {
        let text = text_arg(ptr, len)?;
        let network = parse_network(&text, format_of(format)?, "network")?;
        surface_into_output(&network, &options(method, vertices, soft, quality)?)
    })())
}

/// Puts the bundled example `name` (UTF-8 in `ptr[..len]`) as JSON in the text buffer.
///
/// # Safety
/// `ptr` must point to `len` readable bytes.
#[no_mangle]
pub unsafe extern "C" fn cn_example(ptr: *const u8, len: usize) -> u32 {
    finish((|| {
        let name = text_arg(ptr, len)?;
        let net = curvenet::network::examples::example(&name)
            .ok_or_else(|| Error::usage(format!("no example named \"{name}\"")))?;
        set_text(curvenet::io::network_to_string(&net, NetworkFormat::Json));
        Ok(())
    })())
}

/// The network in `ptr[..len]` (format `format`) changed by `edit`, as JSON in the text
/// buffer: the entry points that edit a network.
///
/// # Safety
/// `ptr` must point to `len` readable bytes.
unsafe fn edit_network(
    ptr: *const u8,
    len: usize,
    format: u32,
    edit: impl FnOnce(&Network) -> Result<Network, Error>,
) -> u32 {
    finish((|| {
        let text = text_arg(ptr, len)?;
        let network = parse_network(&text, format_of(format)?, "network")?;
        set_text(curvenet::io::network_to_string(&edit(&network)?, NetworkFormat::Json));
        Ok(())
    })())
}

/// Rotates the normals of curve `curve` of the network in `ptr[..len]` by `degrees` about the
/// curve's tangent; the new network, as JSON, goes to the text buffer.
///
/// # Safety
/// `ptr` must point to `len` readable bytes.
#[no_mangle]
pub unsafe extern "C" fn cn_rotate_normals(ptr: *const u8, len: usize, format: u32, curve: u32, degrees: f64) -> u32 {
    edit_network(ptr, len, format, |network| curvenet::network::edit::rotate_normals(network, curve as usize, degrees))
}

/// The network in `ptr[..len]` as a surface run with the viewer's options uses it, with its
/// patches' cycles (`curvenet::network_with_cycles`); as JSON, to the text buffer.
///
/// # Safety
/// `ptr` must point to `len` readable bytes.
#[no_mangle]
pub unsafe extern "C" fn cn_cycles(
    ptr: *const u8,
    len: usize,
    format: u32,
    method: u32,
    vertices: u32,
    quality: u32,
) -> u32 {
    edit_network(ptr, len, format, |network| {
        Ok(curvenet::network_with_cycles(network, &options(method, vertices, 0.0, quality)?)?.0)
    })
}

/// The network in `ptr[..len]` with patch `patch` of its surface (with the viewer's options)
/// left open (`curvenet::with_patch_left_open`: its cycle removed, the cycles written first
/// if the network has none); the new network, as JSON, goes to the text buffer.
///
/// # Safety
/// `ptr` must point to `len` readable bytes.
#[no_mangle]
pub unsafe extern "C" fn cn_open_patch(
    ptr: *const u8,
    len: usize,
    format: u32,
    patch: u32,
    method: u32,
    vertices: u32,
    quality: u32,
) -> u32 {
    edit_network(ptr, len, format, |network| {
        curvenet::with_patch_left_open(network, &options(method, vertices, 0.0, quality)?, patch as usize)
    })
}

/// The network in `ptr[..len]` with the open cycle along curve `curve` filled
/// (`curvenet::with_cycle_filled`, with the viewer's options); the new network, as JSON, goes
/// to the text buffer.
///
/// # Safety
/// `ptr` must point to `len` readable bytes.
#[no_mangle]
pub unsafe extern "C" fn cn_fill_cycle(
    ptr: *const u8,
    len: usize,
    format: u32,
    curve: u32,
    method: u32,
    vertices: u32,
    quality: u32,
) -> u32 {
    edit_network(ptr, len, format, |network| {
        curvenet::with_cycle_filled(network, &options(method, vertices, 0.0, quality)?, curve as usize)
    })
}

/// Number of curves of the network in `ptr[..len]` (or `u32::MAX` if it does not parse).
///
/// # Safety
/// `ptr` must point to `len` readable bytes.
#[no_mangle]
pub unsafe extern "C" fn cn_curve_count(ptr: *const u8, len: usize, format: u32) -> u32 {
    let parsed = text_arg(ptr, len).and_then(|t| parse_network(&t, format_of(format)?, "network"));
    parsed.map(|n| n.curves.len() as u32).unwrap_or(u32::MAX)
}

fn with_buffer<T>(kind: u32, f: impl FnOnce(*const u8, usize) -> T) -> T {
    OUTPUT.with(|o| {
        let o = o.borrow();
        let (p, n) = match kind {
            0 => (o.positions.as_ptr() as *const u8, o.positions.len()),
            1 => (o.faces.as_ptr() as *const u8, o.faces.len()),
            2 => (o.normals.as_ptr() as *const u8, o.normals.len()),
            3 => (o.curvature_colors.as_ptr() as *const u8, o.curvature_colors.len()),
            4 => (o.deviation_colors.as_ptr() as *const u8, o.deviation_colors.len()),
            5 => (o.curve_points.as_ptr() as *const u8, o.curve_points.len()),
            6 => (o.curve_offsets.as_ptr() as *const u8, o.curve_offsets.len()),
            7 => (o.mean_curvature.as_ptr() as *const u8, o.mean_curvature.len()),
            8 => (o.face_patch.as_ptr() as *const u8, o.face_patch.len()),
            _ => (std::ptr::null(), 0),
        };
        f(p, n)
    })
}

/// Address of output buffer `kind` (see `Output`; 4-byte elements).
#[no_mangle]
pub extern "C" fn cn_buffer_ptr(kind: u32) -> *const u8 {
    with_buffer(kind, |p, _| p)
}

/// Length in elements of output buffer `kind`.
#[no_mangle]
pub extern "C" fn cn_buffer_len(kind: u32) -> usize {
    with_buffer(kind, |_, n| n)
}

/// Statistic `kind` of the last surface: 0 vertices, 1 faces, 2 curve vertices, 3 patches,
/// 4 curvature colour range ±R, 5 largest N* deviation in degrees, 6 spacing, 7 warnings.
#[no_mangle]
pub extern "C" fn cn_stat(kind: u32) -> f64 {
    OUTPUT.with(|o| o.borrow().stats.get(kind as usize).copied().unwrap_or(f64::NAN))
}

/// Address of the text buffer (UTF-8): an error message, warnings, or a network.
#[no_mangle]
pub extern "C" fn cn_text_ptr() -> *const u8 {
    TEXT.with(|t| t.borrow().as_ptr())
}

/// Length in bytes of the text buffer.
#[no_mangle]
pub extern "C" fn cn_text_len() -> usize {
    TEXT.with(|t| t.borrow().len())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn call_surface(text: &str, method: u32) -> u32 {
        unsafe { cn_surface(text.as_ptr(), text.len(), 0, method, 3000, 0.0, 0) }
    }

    fn text() -> String {
        TEXT.with(|t| t.borrow().clone())
    }

    #[test]
    fn the_abi_surfaces_an_example_and_reports_errors() {
        let name = "sphere";
        assert_eq!(unsafe { cn_example(name.as_ptr(), name.len()) }, 0);
        let json = text();
        assert_eq!(call_surface(&json, 0), 0);
        let v = cn_stat(0) as usize;
        assert!(v > 2000, "{v} vertices");
        assert_eq!(cn_buffer_len(0), 3 * v);
        assert_eq!(cn_buffer_len(3), 3 * v);
        assert_eq!(cn_buffer_len(4), 3 * v, "normal-control has N*");
        assert_eq!(cn_buffer_len(1), 3 * cn_stat(1) as usize);
        assert_eq!(cn_buffer_len(6), 4, "three curves: four offsets");
        assert_eq!(unsafe { cn_curve_count(json.as_ptr(), json.len(), 0) }, 3);
        // Biharmonic has no propagated normals.
        assert_eq!(call_surface(&json, 1), 0);
        assert_eq!(cn_buffer_len(4), 0);
        // Errors carry the library's message and exit code.
        assert_eq!(call_surface("{\"curves\": [", 0), 1);
        assert!(text().contains("network:1:"), "{}", text());
        assert_eq!(call_surface(&json, 9), 2);
        assert_eq!(unsafe { cn_rotate_normals(json.as_ptr(), json.len(), 0, 7, 10.0) }, 2);
        assert!(text().contains("curve 7"));
        // Exports of the last surface; the curve an error names.
        assert_eq!(call_surface(&json, 0), 0);
        assert_eq!(cn_export_mesh(0), 0);
        let ply = BYTES.with(|b| b.borrow().clone());
        let header = String::from_utf8_lossy(&ply[..200]).into_owned();
        assert!(header.contains(&format!("element vertex {}", cn_stat(0))), "{header}");
        assert_eq!(cn_export_mesh(2), 0);
        assert_eq!(&BYTES.with(|b| b.borrow()[..4].to_vec()), b"glTF");
        assert_eq!(cn_export_mesh(7), 2);
        let bad = json.replacen("\"normals\": [\n        [", "\"normals\": [\n        [0, 0, 0], [", 1);
        assert_eq!(call_surface(&bad, 0), 1, "{}", text());
        assert_eq!(cn_error_curve(), 0, "{}", text());
        assert_eq!(unsafe { cn_network_curves(json.as_ptr(), json.len(), 0) }, 0);
        assert_eq!(cn_buffer_len(6), 4);
        assert_eq!(cn_error_curve(), u32::MAX);
        let cyl = "cylinder";
        assert_eq!(unsafe { cn_example(cyl.as_ptr(), cyl.len()) }, 0);
        let c = text();
        assert_eq!(unsafe { cn_rotate_normals(c.as_ptr(), c.len(), 0, 0, 30.0) }, 0);
        assert_ne!(text(), c);
    }
}
