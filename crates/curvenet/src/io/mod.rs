//! Reading and writing files: curve networks in (JSON, OBJ, `.net`), meshes out (OBJ, PLY,
//! OFF) and back in. Formats are documented in the README ("Formats") and docs/design.md §3–4; the
//! format is chosen by the file extension.
//!
//! Every writer is atomic: it writes a temporary file beside the target and renames it, so a
//! failed run never leaves a half-written file.

pub mod folder;
mod glb;
mod json;
pub use json::closest as closest_key;
mod mesh;
mod net;
mod obj;
pub use obj::network_from_edges;

pub use mesh::{check_mesh_path, mesh_bytes, parse_mesh, read_mesh, stage_mesh, write_mesh, MeshData, MeshFile};

use crate::error::{Error, Result, Warning};
use crate::network::Network;
use std::io::Write;
use std::path::Path;

/// File formats for curve networks.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum NetworkFormat {
    /// The reference JSON format (docs/design.md §3).
    Json,
    /// Wavefront OBJ polylines: `v`, `vn` paired by index, `l`, group `boundary`.
    Obj,
    /// The `.net` format of the method's authors.
    Net,
}

impl NetworkFormat {
    /// The format for a file name's extension (case-insensitive), or a usage error.
    pub fn from_path(path: &Path) -> Result<Self> {
        let ext = extension(path);
        match ext.as_str() {
            "json" => Ok(Self::Json),
            "obj" => Ok(Self::Obj),
            "net" => Ok(Self::Net),
            _ => Err(Error::usage(format!(
                "{}: unknown network format \".{ext}\"; use .json, .obj or .net",
                path.display()
            ))),
        }
    }
}

pub(crate) fn extension(path: &Path) -> String {
    path.extension().and_then(|e| e.to_str()).unwrap_or("").to_ascii_lowercase()
}

/// The largest input file read (networks, meshes, models): 1 GiB. A larger file, or an input
/// that never ends (`/dev/zero`, a pipe), is an input error after this many bytes, not an
/// out-of-memory abort.
pub const MAX_INPUT_BYTES: u64 = 1 << 30;

/// How the first bytes of an input must look ([`read_input`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum InputKind {
    /// Text: no NUL byte (JSON, OBJ, `.net`, OFF, SVG, models).
    Text,
    /// A PLY file: starts with `ply`.
    Ply,
}

/// Reads the file at `path`, at most `max` bytes (more is an input error naming the limit),
/// rejecting it at its first 64 KiB when they cannot start a file of `kind` (a NUL byte in
/// text: binary data such as `/dev/zero`; a PLY without its `ply` line) — before reading the
/// rest.
pub fn read_input(path: &Path, kind: InputKind, max: u64) -> Result<Vec<u8>> {
    let file = std::fs::File::open(path).map_err(|e| Error::io(path, e))?;
    read_opened(file, path, kind, max)
}

/// Opens `path` for reading if it is a regular file, else an input error naming what it is (a
/// FIFO, socket, device or folder): without blocking, since an ordinary open of a FIFO with no
/// writer waits forever, and checked on the opened file, so that a file replaced after a
/// folder was listed is caught too. `curvenet batch` and `surface_files` read their inputs so.
pub fn open_regular(path: &Path) -> Result<std::fs::File> {
    let mut open = std::fs::OpenOptions::new();
    open.read(true);
    #[cfg(unix)]
    {
        use std::os::unix::fs::OpenOptionsExt;
        open.custom_flags(libc::O_NONBLOCK);
    }
    let file = open.open(path).map_err(|e| Error::io(path, e))?;
    let kind = file.metadata().map_err(|e| Error::io(path, e))?.file_type();
    if kind.is_file() {
        return Ok(file);
    }
    let what = if kind.is_dir() {
        "a folder"
    } else {
        #[cfg(unix)]
        {
            use std::os::unix::fs::FileTypeExt;
            if kind.is_fifo() {
                "a FIFO (named pipe)"
            } else if kind.is_socket() {
                "a socket"
            } else if kind.is_block_device() || kind.is_char_device() {
                "a device"
            } else {
                "not a regular file"
            }
        }
        #[cfg(not(unix))]
        {
            "not a regular file"
        }
    };
    Err(Error::input(format!("{}: {what}, not a regular file: only regular files are read here", path.display())))
}

/// [`read_input`] of an opened `file` (its name `path`, for messages).
pub fn read_opened(mut file: std::fs::File, path: &Path, kind: InputKind, max: u64) -> Result<Vec<u8>> {
    use std::io::Read;
    let source = path.display().to_string();
    let mut bytes = Vec::new();
    const HEAD: u64 = 64 << 10;
    (&mut file).take(HEAD.min(max + 1)).read_to_end(&mut bytes).map_err(|e| Error::io(path, e))?;
    let head = &bytes[..];
    match kind {
        InputKind::Text => {
            if head.starts_with(&[0xff, 0xfe]) || head.starts_with(&[0xfe, 0xff]) {
                return Err(Error::parse(
                    &source,
                    1,
                    1,
                    "file is not valid UTF-8 text: UTF-16 (it starts with a UTF-16 byte-order mark); save it as UTF-8",
                ));
            }
            if let Some(i) = head.iter().position(|&b| b == 0) {
                let (line, column) = line_col(&head[..i]);
                return Err(Error::parse(&source, line, column, "a NUL byte: binary data, not a text file"));
            }
        }
        InputKind::Ply => {
            let start = head.strip_prefix(b"\xef\xbb\xbf").unwrap_or(head);
            if !(start.starts_with(b"ply\n") || start.starts_with(b"ply\r\n") || start == b"ply") {
                return Err(Error::parse(&source, 1, 1, "not a PLY file: the first line must be \"ply\""));
            }
        }
    }
    if bytes.len() as u64 == HEAD.min(max + 1) {
        // A regular file's size is known: refuse one whose parse would not fit in memory, and
        // reserve its bytes fallibly. Other inputs (pipes) grow in fallible steps.
        let size = file.metadata().ok().filter(|m| m.is_file()).map(|m| m.len().min(max + 1));
        if let Some(size) = size {
            check_parse_memory(&source, size)?;
        }
        let mut rest = (&mut file).take(max + 1 - bytes.len() as u64);
        loop {
            let want = size.map_or(1 << 20, |s| s.saturating_sub(bytes.len() as u64).max(1 << 16)) as usize;
            bytes.try_reserve(want).map_err(|_| {
                Error::memory(format!("{source}: out of memory reading the input after {} MB", bytes.len() >> 20))
            })?;
            let start = bytes.len();
            let spare = bytes.capacity() - start;
            bytes.resize(start + spare, 0);
            let n = read_full(&mut rest, &mut bytes[start..]).map_err(|e| Error::io(path, e))?;
            bytes.truncate(start + n);
            if n < spare {
                break;
            }
        }
    }
    if bytes.len() as u64 > max {
        return Err(Error::input(format!(
            "{source}: larger than {} MiB, the largest input read (or an input that never ends)",
            max >> 20
        )));
    }
    Ok(bytes)
}

/// Reads into `buf` until it is full or the input ends; returns the bytes read.
fn read_full(r: &mut impl std::io::Read, buf: &mut [u8]) -> std::io::Result<usize> {
    let mut n = 0;
    while n < buf.len() {
        match r.read(&mut buf[n..]) {
            Ok(0) => break,
            Ok(k) => n += k,
            Err(e) if e.kind() == std::io::ErrorKind::Interrupted => {}
            Err(e) => return Err(e),
        }
    }
    Ok(n)
}

/// Peak memory of parsing an input, per byte of the file: its bytes, the text, and the parsed
/// vectors while they grow. Measured 5–8.6 with `curvenet.read_mesh` / `read_network` on the
/// densest files (one-digit coordinates: `v 0 0 0` OBJ, OFF, JSON networks; docs/robustness.md).
pub const PARSE_BYTES_PER_INPUT_BYTE: f64 = 9.0;

/// Refuses a file of `size` bytes whose parse ([`PARSE_BYTES_PER_INPUT_BYTE`]) would exceed
/// the memory available ([`crate::solve::memory::available_for_reading`]).
fn check_parse_memory(source: &str, size: u64) -> Result<()> {
    let need = size as f64 * PARSE_BYTES_PER_INPUT_BYTE;
    match crate::solve::memory::available_for_reading() {
        Some(available) if need > available => Err(Error::memory(format!(
            "{source}: reading this {:.0} MB file needs about {:.0} MB of memory, more than the {:.0} MB available",
            size as f64 / 1e6,
            need / 1e6,
            available.max(0.0) / 1e6
        ))),
        _ => Ok(()),
    }
}

/// Reads a curve network; the format comes from the extension. The network is returned as
/// written in the file: call [`Network::validated`] (the pipeline does) to check its values.
/// What the file holds that was not read (unknown JSON keys) is dropped here: front ends call
/// [`read_network_with_warnings`] and show them.
pub fn read_network(path: &Path) -> Result<Network> {
    read_network_with_warnings(path).map(|(n, _)| n)
}

/// [`read_network`] with the warnings of the read: each unknown key of a JSON network, with its
/// line and the closest known key ("`normal` — did you mean `normals`?").
pub fn read_network_with_warnings(path: &Path) -> Result<(Network, Vec<Warning>)> {
    let format = NetworkFormat::from_path(path)?;
    let text = read_text(path, MAX_INPUT_BYTES)?;
    parse_network_with_warnings(&text, format, &path.display().to_string())
}

/// Reads a text file as [`read_input`] does, at most `max` bytes; invalid UTF-8 is a parse error
/// naming its line and column. A UTF-8 byte-order mark stays in the text: parsers skip it.
pub fn read_text(path: &Path, max: u64) -> Result<String> {
    text_of(read_input(path, InputKind::Text, max)?, path)
}

/// The bytes read from `path` as UTF-8 text; invalid UTF-8 is a parse error naming its line and
/// column.
pub fn text_of(bytes: Vec<u8>, path: &Path) -> Result<String> {
    String::from_utf8(bytes).map_err(|e| {
        let (line, column) = line_col(&e.as_bytes()[..e.utf8_error().valid_up_to()]);
        Error::Parse { path: path.display().to_string(), line, column, message: "file is not valid UTF-8 text".into() }
    })
}

/// Parses a curve network from text; `source` names it in error messages.
/// A UTF-8 byte-order mark at the start (as some Windows editors write) is skipped.
pub fn parse_network(text: &str, format: NetworkFormat, source: &str) -> Result<Network> {
    parse_network_with_warnings(text, format, source).map(|(n, _)| n)
}

/// [`parse_network`] with the warnings of the parse ([`read_network_with_warnings`]).
pub fn parse_network_with_warnings(text: &str, format: NetworkFormat, source: &str) -> Result<(Network, Vec<Warning>)> {
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    match format {
        NetworkFormat::Json => json::parse(text, source),
        NetworkFormat::Obj => obj::parse(text, source).map(|n| (n, Vec::new())),
        NetworkFormat::Net => net::parse(text, source).map(|n| (n, Vec::new())),
    }
}

/// Writes a curve network; the format comes from the extension. Atomic. The patches' cycles
/// ([`Network::cycles`]) are written in JSON only.
pub fn write_network(path: &Path, network: &Network) -> Result<()> {
    let format = NetworkFormat::from_path(path)?;
    if let Some(why) = unwritable(format, network) {
        return Err(Error::usage(format!("{}: {why}", path.display())));
    }
    write_atomic(path, |w| match format {
        NetworkFormat::Json => json::write(w, network),
        NetworkFormat::Obj => obj::write(w, network),
        NetworkFormat::Net => net::write(w, network),
    })
}

/// Why `network` cannot be written in `format`: `.net` needs a normal at every sample; OBJ
/// holds normals for every curve or for none; only JSON holds a crease's second normal.
fn unwritable(format: NetworkFormat, network: &Network) -> Option<&'static str> {
    let some = network.curves.iter().any(|c| c.has_normals());
    match format {
        NetworkFormat::Net if !network.has_all_normals() => Some(
            "the .net format needs a normal at every sample; write .json or .obj (or infer the normals first: \
             curvenet normals)",
        ),
        NetworkFormat::Obj if some && !network.has_all_normals() => Some(
            "OBJ holds normals for every curve or for none, and some curves of this network have none; write \
             .json (or infer the missing normals first: curvenet normals)",
        ),
        NetworkFormat::Net | NetworkFormat::Obj if network.has_creases() => Some(
            "this network has crease curves (two normals per sample, `normals_right`), which only the JSON \
             format holds; write .json",
        ),
        _ => None,
    }
}

/// `network` as the text of a file in `format` (what [`write_network`] writes; empty for a
/// network the format cannot hold, see [`write_network`]).
pub fn network_to_string(network: &Network, format: NetworkFormat) -> String {
    if unwritable(format, network).is_some() {
        return String::new();
    }
    let mut buf = Vec::new();
    let _ = match format {
        NetworkFormat::Json => json::write(&mut buf, network),
        NetworkFormat::Obj => obj::write(&mut buf, network),
        NetworkFormat::Net => net::write(&mut buf, network),
    };
    String::from_utf8(buf).unwrap_or_default()
}

/// 1-based line and column of the end of `prefix`.
fn line_col(prefix: &[u8]) -> (usize, usize) {
    let line = 1 + prefix.iter().filter(|&&b| b == b'\n').count();
    let col = 1 + prefix.iter().rev().take_while(|&&b| b != b'\n').count();
    (line, col)
}

/// A file written in full to a temporary name beside its target, not yet visible under the
/// target name. [`Staged::commit`] renames it into place; dropping it uncommitted removes it.
/// Staging several outputs and committing them together keeps a failed run from leaving some
/// of them written.
#[derive(Debug)]
pub struct Staged {
    tmp: std::path::PathBuf,
    path: std::path::PathBuf,
    done: bool,
}

/// The temporary files of the [`Staged`] outputs not yet committed or dropped, for
/// [`remove_staged_files`].
static STAGED: std::sync::Mutex<Vec<std::path::PathBuf>> = std::sync::Mutex::new(Vec::new());

fn unregister(tmp: &Path) {
    let mut list = STAGED.lock().unwrap_or_else(|e| e.into_inner());
    list.retain(|p| p != tmp);
}

/// Removes the temporary files of every output staged and not yet committed (or dropped):
/// what a signal handler calls before the process exits on SIGINT or SIGTERM (the command
/// line does), so that an interrupted run leaves the output folder as it was.
pub fn remove_staged_files() {
    let list = STAGED.lock().unwrap_or_else(|e| e.into_inner());
    for tmp in list.iter() {
        let _ = std::fs::remove_file(tmp);
    }
}

impl Staged {
    /// Writes through `body` into a temporary file beside `path`.
    pub fn write(path: &Path, body: impl FnOnce(&mut dyn Write) -> std::io::Result<()>) -> Result<Staged> {
        let dir = match path.parent() {
            Some(d) if !d.as_os_str().is_empty() => d.to_path_buf(),
            _ => std::path::PathBuf::from("."),
        };
        let name = path.file_name().and_then(|n| n.to_str()).unwrap_or("out");
        let tmp = dir.join(format!(".{name}.{}.tmp", std::process::id()));
        STAGED.lock().unwrap_or_else(|e| e.into_inner()).push(tmp.clone());
        let staged = Staged { tmp, path: path.to_path_buf(), done: false };
        let result = (|| -> std::io::Result<()> {
            let file = std::fs::File::create(&staged.tmp)?;
            let mut w = std::io::BufWriter::with_capacity(1 << 20, file);
            body(&mut w)?;
            w.flush()?;
            w.into_inner().map_err(|e| e.into_error())?;
            Ok(())
        })();
        result.map_err(|e| Error::io(path, e))?;
        Ok(staged)
    }

    /// Moves the file to its target name.
    pub fn commit(mut self) -> Result<()> {
        std::fs::rename(&self.tmp, &self.path).map_err(|e| Error::io(&self.path, e))?;
        self.done = true;
        unregister(&self.tmp);
        Ok(())
    }
}

impl Drop for Staged {
    fn drop(&mut self) {
        if !self.done {
            let _ = std::fs::remove_file(&self.tmp);
            unregister(&self.tmp);
        }
    }
}

/// Writes through `body` into a temporary file beside `path`, then renames it onto `path`.
/// On any error the temporary file is removed and `path` is left as it was.
pub(crate) fn write_atomic(path: &Path, body: impl FnOnce(&mut dyn Write) -> std::io::Result<()>) -> Result<()> {
    Staged::write(path, body)?.commit()
}

/// Writes `text` to `path` atomically.
pub fn write_text(path: &Path, text: &str) -> Result<()> {
    write_atomic(path, |w| w.write_all(text.as_bytes()))
}

/// A line-oriented tokenizer for the text formats: yields `(line, column, token)` with
/// 1-based positions, skipping `#` comments.
pub(crate) struct Tokens<'a> {
    pub line: usize,
    rest: Vec<(usize, &'a str)>,
}

impl<'a> Tokens<'a> {
    /// Splits one line (1-based `line`) into tokens with their columns.
    pub fn of_line(line_no: usize, line: &'a str) -> Self {
        let line = match line.find('#') {
            Some(i) => &line[..i],
            None => line,
        };
        let mut rest = Vec::new();
        let bytes = line.as_bytes();
        let mut i = 0;
        // Columns count characters; counted incrementally (a line of a million indices is
        // linear, not quadratic).
        let (mut counted, mut column) = (0, 1);
        while i < bytes.len() {
            if bytes[i].is_ascii_whitespace() {
                i += 1;
                continue;
            }
            let start = i;
            while i < bytes.len() && !bytes[i].is_ascii_whitespace() {
                i += 1;
            }
            column += line[counted..start].chars().count();
            counted = start;
            rest.push((column, &line[start..i]));
        }
        rest.reverse();
        Tokens { line: line_no, rest }
    }

    pub fn is_empty(&self) -> bool {
        self.rest.is_empty()
    }

    pub fn next(&mut self) -> Option<(usize, &'a str)> {
        self.rest.pop()
    }

    pub fn remaining(&self) -> usize {
        self.rest.len()
    }
}

pub(crate) fn parse_error(source: &str, line: usize, column: usize, message: impl Into<String>) -> Error {
    Error::Parse { path: source.to_string(), line, column, message: message.into() }
}

/// Parses a finite `f64` token; `what` names the value in the message.
pub(crate) fn parse_f64(source: &str, line: usize, col: usize, tok: &str, what: &str) -> Result<f64> {
    match tok.parse::<f64>() {
        Ok(v) if v.is_finite() => Ok(v),
        Ok(_) => Err(parse_error(source, line, col, format!("{what} \"{tok}\" is not a finite number"))),
        Err(_) => Err(parse_error(source, line, col, format!("expected a number for {what}, found \"{tok}\""))),
    }
}

#[cfg(test)]
#[path = "tests/io.rs"]
mod tests;
