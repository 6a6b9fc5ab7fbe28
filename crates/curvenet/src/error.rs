//! Errors and warnings (docs/design.md §7).
//!
//! Every user-facing error says *what* is wrong, *where* and, where there is one, *how to fix
//! it*. The "where" is data, not only text: [`Error::at`] gives the curve, sample, node,
//! segment, patch or vertex ([`At`]) so that front ends and scripts can point at it (the
//! Python bindings expose them as attributes). Errors are grouped by who has to act, which is
//! also what the command-line exit code reports:
//!
//! | kind | meaning | exit code |
//! |---|---|---|
//! | [`Error::Parse`] | a file is malformed (line, column) | 1 |
//! | [`Error::Input`] | the network's data are invalid (curve, sample) | 1 |
//! | [`Error::Topology`] | the curves do not bound an oriented 2-manifold (node, segment, patch) | 1 |
//! | [`Error::Io`] | a file could not be read or written | 1 |
//! | [`Error::usage`] | an option value or a file name cannot be used | 2 |
//! | [`Error::Numerical`] | a linear system or a patch is degenerate (patch, vertex) | 3 |
//! | [`Error::Internal`] | a bug in curvenet: please report it with the input | 4 |
//!
//! **Option names in messages.** Messages name options by their library name in backticks,
//! `` `spacing` ``, the same name in every front end ([`crate::pipeline::options`]); each front
//! end may respell them for its users ([`Error::spelled`]: `--spacing` on the command line;
//! Python keeps `` `spacing` ``, its keyword's name).

use std::fmt;

/// Where an error or warning is: the ids that are known, `None` for the others. Indices are
/// 0-based: curves and samples in the order of the input network, nodes, segments and patches
/// in the order the pipeline numbers them (as `--stats` counts them), vertices of the mesh.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct At {
    /// Curve index in the input network.
    pub curve: Option<usize>,
    /// Sample index along that curve.
    pub sample: Option<usize>,
    /// Node index (where curves meet).
    pub node: Option<usize>,
    /// Segment index (a piece of curve between two nodes).
    pub segment: Option<usize>,
    /// Patch index (a cycle of segments, one piece of surface).
    pub patch: Option<usize>,
    /// Mesh vertex index.
    pub vertex: Option<usize>,
    /// A position in space near the problem.
    pub point: Option<[f64; 3]>,
}

/// The error type of every fallible curvenet operation.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum Error {
    /// A file is malformed. Occurs when a network or mesh file does not follow its format
    /// (docs/design.md §3–4); `line` and `column` are 1-based. Fix the file at that position.
    #[error("{path}:{line}:{column}: {message}")]
    Parse {
        /// The file (or `<string>` for text).
        path: String,
        /// 1-based line.
        line: usize,
        /// 1-based column.
        column: usize,
        /// What is wrong there.
        message: String,
    },

    /// The network's values are invalid: non-finite numbers, zero normals, too few samples,
    /// normals that disagree in orientation. [`Error::at`] names the curve and sample.
    #[error("{message}")]
    Input {
        /// What is wrong, where, and how to fix it.
        message: String,
        /// The ids of the place (boxed: keeps `Result<T, Error>` small).
        at: Box<At>,
    },

    /// The curves do not bound an oriented 2-manifold: a dangling segment, a segment with
    /// patches on both sides of a boundary, a cycle that crosses itself when projected.
    /// [`Error::at`] names the node, segment, patch or curve.
    #[error("{message}")]
    Topology {
        /// What is wrong, where, and how to fix it.
        message: String,
        /// The ids of the place.
        at: Box<At>,
    },

    /// A file could not be read or written.
    #[error("{path}: {source}{}", io_hint(source))]
    Io {
        /// The file.
        path: String,
        /// The operating system's error.
        source: std::io::Error,
    },

    /// An option value or a file name cannot be used (unknown extension, conflicting options,
    /// a size over the limits).
    #[error("{message}")]
    Usage {
        /// What cannot be used and what can.
        message: String,
    },

    /// A numerical failure: a system that is not positive definite, a degenerate patch, an
    /// ill-conditioned solve. [`Error::at`] names the patch or vertex where known.
    #[error("numerical failure: {message}")]
    Numerical {
        /// What failed and what to try.
        message: String,
        /// The ids of the place.
        at: Box<At>,
    },

    /// A run whose estimated peak memory exceeds what is available (the process's address-space
    /// limit, the machine's available memory, or `max_memory`), refused before it allocates;
    /// or an allocation that failed. The message names the estimate and a smaller setting.
    #[error("not enough memory: {message}")]
    Memory {
        /// The estimate, the memory available, and what to change.
        message: String,
    },

    /// A broken invariant inside curvenet: a bug, not a problem of the input. Please report
    /// it with the input that caused it.
    #[error("internal error (please report it with the input): {message}")]
    Internal {
        /// What went wrong.
        message: String,
    },
}

impl Error {
    /// An [`Error::Input`] with `message` (add the ids with [`Error::curve`], …).
    pub fn input(message: impl Into<String>) -> Self {
        Error::Input { message: message.into(), at: Box::default() }
    }

    /// An [`Error::Topology`] with `message`.
    pub fn topology(message: impl Into<String>) -> Self {
        Error::Topology { message: message.into(), at: Box::default() }
    }

    /// An [`Error::Numerical`] with `message`.
    pub fn numerical(message: impl Into<String>) -> Self {
        Error::Numerical { message: message.into(), at: Box::default() }
    }

    /// An [`Error::usage`] with `message`.
    pub fn usage(message: impl Into<String>) -> Self {
        Error::Usage { message: message.into() }
    }

    /// An [`Error::Memory`] with `message`.
    pub fn memory(message: impl Into<String>) -> Self {
        Error::Memory { message: message.into() }
    }

    /// An [`Error::Internal`] with `message`.
    pub fn internal(message: impl Into<String>) -> Self {
        Error::Internal { message: message.into() }
    }

    /// An [`Error::Parse`] of `path` at 1-based `line` and `column`.
    pub fn parse(path: impl Into<String>, line: usize, column: usize, message: impl Into<String>) -> Self {
        Error::Parse { path: path.into(), line, column, message: message.into() }
    }

    /// An [`Error::Io`] on `path`.
    pub fn io(path: &std::path::Path, source: std::io::Error) -> Self {
        Error::Io { path: path.display().to_string(), source }
    }

    /// The process exit code the command-line tool uses for this error:
    /// 1 bad input, 2 usage (and a run too large for the memory available), 3 numerical failure,
    /// 4 internal error.
    pub fn exit_code(&self) -> i32 {
        match self {
            Error::Parse { .. } | Error::Input { .. } | Error::Topology { .. } | Error::Io { .. } => 1,
            Error::Usage { .. } | Error::Memory { .. } => 2,
            Error::Numerical { .. } => 3,
            Error::Internal { .. } => 4,
        }
    }

    /// The kind's name: `parse`, `input`, `topology`, `io`, `usage`, `numerical`, `memory`,
    /// `internal`.
    pub fn kind(&self) -> &'static str {
        match self {
            Error::Parse { .. } => "parse",
            Error::Input { .. } => "input",
            Error::Topology { .. } => "topology",
            Error::Io { .. } => "io",
            Error::Usage { .. } => "usage",
            Error::Numerical { .. } => "numerical",
            Error::Memory { .. } => "memory",
            Error::Internal { .. } => "internal",
        }
    }

    /// Where the error is (all `None` for kinds without a place, and where unknown).
    pub fn at(&self) -> At {
        match self {
            Error::Input { at, .. } | Error::Topology { at, .. } | Error::Numerical { at, .. } => **at,
            _ => At::default(),
        }
    }

    fn with(mut self, f: impl FnOnce(&mut At)) -> Self {
        if let Error::Input { at, .. } | Error::Topology { at, .. } | Error::Numerical { at, .. } = &mut self {
            f(at);
        }
        self
    }

    /// Records the curve (for the kinds with a place; others are returned unchanged).
    pub fn curve(self, curve: usize) -> Self {
        self.with(|a| a.curve = Some(curve))
    }

    /// Records the sample along the curve.
    pub fn sample(self, sample: usize) -> Self {
        self.with(|a| a.sample = Some(sample))
    }

    /// Records the node.
    pub fn node(self, node: usize) -> Self {
        self.with(|a| a.node = Some(node))
    }

    /// Records the segment.
    pub fn segment(self, segment: usize) -> Self {
        self.with(|a| a.segment = Some(segment))
    }

    /// Records the patch.
    pub fn patch(self, patch: usize) -> Self {
        self.with(|a| a.patch = Some(patch))
    }

    /// Records the mesh vertex.
    pub fn vertex(self, vertex: usize) -> Self {
        self.with(|a| a.vertex = Some(vertex))
    }

    /// Records a position near the problem (a `DVec3` or `[x, y, z]`).
    pub fn point(self, p: impl Into<[f64; 3]>) -> Self {
        let p = p.into();
        self.with(|a| a.point = Some(p))
    }

    /// The message with every option name in backticks that `spell` knows respelled for a
    /// front end: `spell("spacing")` returns `Some("--spacing")` on the command line. Names it
    /// returns `None` for are left as they are.
    pub fn spelled(&self, spell: &dyn Fn(&str) -> Option<String>) -> String {
        respell(&self.to_string(), spell)
    }
}

/// `text` with each `` `name` `` for which `spell(name)` is `Some(s)` replaced by `s`.
pub fn respell(text: &str, spell: &dyn Fn(&str) -> Option<String>) -> String {
    let mut out = String::with_capacity(text.len());
    let mut rest = text;
    while let Some(open) = rest.find('`') {
        let (before, after) = rest.split_at(open);
        out.push_str(before);
        match after[1..].find('`') {
            Some(close) => {
                let name = &after[1..1 + close];
                match spell(name) {
                    Some(s) => out.push_str(&s),
                    None => out.push_str(&after[..close + 2]),
                }
                rest = &after[close + 2..];
            }
            None => {
                out.push_str(after);
                rest = "";
            }
        }
    }
    out.push_str(rest);
    out
}

/// Shorthand for `Result<T, curvenet::Error>`.
pub type Result<T> = std::result::Result<T, Error>;

/// Something the pipeline repaired, assumed or left out on the user's behalf (a merged
/// duplicate sample, a snapped crossing, a trimmed dangling curve, a patch triangulated on a
/// fallback domain). The run succeeds; front ends show these to the user.
#[derive(Clone, Debug, PartialEq)]
pub struct Warning {
    /// What happened, where, and what the user may want to do.
    pub message: String,
    /// The ids of the place.
    pub at: At,
}

impl Warning {
    /// A warning with `message` (add the ids with [`Warning::curve`], …).
    pub fn new(message: impl Into<String>) -> Self {
        Warning { message: message.into(), at: At::default() }
    }

    /// Records the curve.
    pub fn curve(mut self, curve: usize) -> Self {
        self.at.curve = Some(curve);
        self
    }

    /// Records the sample along the curve.
    pub fn sample(mut self, sample: usize) -> Self {
        self.at.sample = Some(sample);
        self
    }

    /// Records the node.
    pub fn node(mut self, node: usize) -> Self {
        self.at.node = Some(node);
        self
    }

    /// Records the patch.
    pub fn patch(mut self, patch: usize) -> Self {
        self.at.patch = Some(patch);
        self
    }
}

impl fmt::Display for Warning {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.message)
    }
}

#[cfg(test)]
#[path = "tests/error.rs"]
mod tests;

/// What a user can do about the I/O errors whose operating-system text says little.
fn io_hint(e: &std::io::Error) -> &'static str {
    match e.kind() {
        std::io::ErrorKind::FileTooLarge => {
            " (the file-size limit of the process, `ulimit -f`, was reached; nothing was written)"
        }
        std::io::ErrorKind::StorageFull => " (the disk is full; nothing was written)",
        _ => "",
    }
}
