//! An output folder that several runs may point at: one batch writes into it at a time (an
//! advisory lock the operating system releases when the process ends, however it ends), the
//! temporary files of runs that died are removed by the next, and no output may be an input
//! (docs/design.md §4, "Batches").

use crate::error::{Error, Result};
use std::collections::HashMap;
use std::fs::{File, OpenOptions};
use std::io::{Read, Seek, Write};
use std::path::{Path, PathBuf};

/// The lock file of an output folder. It stays in the folder (removing it would let a second
/// run lock a fresh file while a first still holds the old one); it holds the process id of the
/// run that holds it.
pub const LOCK_FILE: &str = ".curvenet.lock";

/// The exclusive lock of an output folder, held while the value lives.
#[derive(Debug)]
pub struct FolderLock {
    _file: File,
    /// The lock file.
    pub path: PathBuf,
}

impl FolderLock {
    /// Locks `dir` (which must exist) for this process, or fails with a usage error naming the
    /// process that holds it. On a file system without locks the folder is used unlocked.
    pub fn acquire(dir: &Path) -> Result<FolderLock> {
        let path = dir.join(LOCK_FILE);
        let mut file = OpenOptions::new()
            .read(true)
            .write(true)
            .create(true)
            .truncate(false)
            .open(&path)
            .map_err(|e| Error::io(&path, e))?;
        match try_lock(&file) {
            Ok(()) => {}
            Err(e) if e.kind() == std::io::ErrorKind::WouldBlock => {
                let mut holder = String::new();
                let _ = file.read_to_string(&mut holder);
                let holder = holder.trim();
                let who = if holder.is_empty() { String::new() } else { format!(" (process {holder})") };
                return Err(Error::usage(format!(
                    "{}: another curvenet run{who} is writing into this folder; wait for it to end, or give another \
                     output folder",
                    dir.display()
                )));
            }
            Err(e) if e.kind() == std::io::ErrorKind::Unsupported => {}
            Err(e) => return Err(Error::io(&path, e)),
        }
        let pid = std::process::id();
        let _ = file.set_len(0).and_then(|_| file.rewind()).and_then(|_| writeln!(file, "{pid}"));
        Ok(FolderLock { _file: file, path })
    }
}

/// An exclusive advisory lock on `file` without waiting (`flock`; `File::try_lock` needs a
/// newer Rust than the crate's minimum): `WouldBlock` when another open file holds it,
/// `Unsupported` where there are no such locks.
fn try_lock(file: &File) -> std::io::Result<()> {
    #[cfg(unix)]
    {
        use std::os::unix::io::AsRawFd;
        // SAFETY: flock on a descriptor this `File` owns; the lock goes with the descriptor.
        if unsafe { libc::flock(file.as_raw_fd(), libc::LOCK_EX | libc::LOCK_NB) } == 0 {
            return Ok(());
        }
        let e = std::io::Error::last_os_error();
        match e.raw_os_error() {
            Some(libc::EWOULDBLOCK) => Err(std::io::ErrorKind::WouldBlock.into()),
            Some(libc::ENOLCK) | Some(libc::EOPNOTSUPP) => Err(std::io::ErrorKind::Unsupported.into()),
            _ => Err(e),
        }
    }
    #[cfg(not(unix))]
    {
        let _ = file;
        Err(std::io::ErrorKind::Unsupported.into())
    }
}

/// Whether process `pid` is alive (`true` when that cannot be known).
fn alive(pid: u32) -> bool {
    #[cfg(unix)]
    {
        let Ok(pid) = libc::pid_t::try_from(pid) else { return true };
        // SAFETY: kill with signal 0 sends nothing; it only checks that the process exists.
        let r = unsafe { libc::kill(pid, 0) };
        r == 0 || std::io::Error::last_os_error().raw_os_error() != Some(libc::ESRCH)
    }
    #[cfg(not(unix))]
    {
        let _ = pid;
        true
    }
}

/// The process id in the name of a staged output's temporary file, `.NAME.PID.tmp`
/// ([`super::Staged`]).
fn staged_pid(name: &str) -> Option<u32> {
    let rest = name.strip_prefix('.')?.strip_suffix(".tmp")?;
    let (stem, pid) = rest.rsplit_once('.')?;
    if stem.is_empty() || !pid.bytes().all(|b| b.is_ascii_digit()) {
        return None;
    }
    pid.parse().ok()
}

/// Removes the temporary files (`.NAME.PID.tmp`) that processes no longer alive left in `dir`
/// (killed while writing: `kill -9`, a power cut); returns them. Those of live processes, and
/// every other file, stay.
pub fn remove_stale_temporaries(dir: &Path) -> Vec<PathBuf> {
    let Ok(entries) = std::fs::read_dir(dir) else { return Vec::new() };
    let own = std::process::id();
    let mut removed = Vec::new();
    for entry in entries.flatten() {
        let name = entry.file_name();
        let Some(pid) = name.to_str().and_then(staged_pid) else { continue };
        if pid == own || alive(pid) || !entry.file_type().is_ok_and(|t| t.is_file()) {
            continue;
        }
        if std::fs::remove_file(entry.path()).is_ok() {
            removed.push(entry.path());
        }
    }
    removed.sort();
    removed
}

/// Where `path` leads: its symlinks and `..` resolved as far as it exists, the rest appended
/// (an output not yet written).
fn resolved(path: &Path) -> PathBuf {
    if let Ok(p) = std::fs::canonicalize(path) {
        return p;
    }
    let absolute = if path.is_absolute() {
        path.to_path_buf()
    } else {
        std::env::current_dir().map(|d| d.join(path)).unwrap_or_else(|_| path.to_path_buf())
    };
    match (absolute.parent(), absolute.file_name()) {
        (Some(parent), Some(name)) if parent != absolute => resolved(parent).join(name),
        _ => absolute,
    }
}

/// The identity of an existing file (device and inode on Unix), which hard links share.
fn identity(path: &Path) -> Option<(u64, u64)> {
    #[cfg(unix)]
    {
        use std::os::unix::fs::MetadataExt;
        std::fs::metadata(path).ok().map(|m| (m.dev(), m.ino()))
    }
    #[cfg(not(unix))]
    {
        let _ = path;
        None
    }
}

/// Checks that no path of `outputs` is one of `inputs` — the same file after resolving
/// symlinks and `..`, or a hard link to it — before any work: a usage error naming both
/// otherwise, so that a batch never overwrites its inputs (an `--out` that is, or links to, the
/// input folder, with the inputs' format).
pub fn check_outputs_apart(inputs: &[PathBuf], outputs: &[PathBuf]) -> Result<()> {
    let mut by_path: HashMap<PathBuf, &Path> = HashMap::new();
    let mut by_id: HashMap<(u64, u64), &Path> = HashMap::new();
    for input in inputs {
        by_path.insert(resolved(input), input);
        if let Some(id) = identity(input) {
            by_id.insert(id, input);
        }
    }
    for output in outputs {
        let hit = by_path.get(&resolved(output)).or_else(|| identity(output).and_then(|id| by_id.get(&id)));
        if let Some(input) = hit {
            return Err(Error::usage(format!(
                "{} would overwrite the input {}: give an output folder apart from the inputs (or another \
                 --format); nothing was written",
                output.display(),
                input.display()
            )));
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_staged_name_gives_its_process_id() {
        assert_eq!(staged_pid(".sphere.ply.4242.tmp"), Some(4242));
        assert_eq!(staged_pid(".a.b.ply.7.tmp"), Some(7));
        assert_eq!(staged_pid("sphere.ply.4242.tmp"), None);
        assert_eq!(staged_pid(".sphere.ply.tmp"), None);
        assert_eq!(staged_pid(".4242.tmp"), None);
        assert_eq!(staged_pid(".x.42a.tmp"), None);
    }
}
