//! Errors and warnings.
//!
//! Every user-facing error says *what* is wrong, *where* (file line and column, curve and
//! sample index, node position, segment) and, where there is one, *how to fix it*. Errors are
//! grouped by who has to act, which is also what the command-line exit code reports:
//!
//! | variant | meaning | exit code |
//! |---|---|---|
//! | [`Error::Parse`] | a file is malformed (line, column) | 1 |
//! | [`Error::Input`] | the network's data are invalid (curve, sample) | 1 |
//! | [`Error::Topology`] | the curves do not bound an oriented 2-manifold (node, segment) | 1 |
//! | [`Error::Io`] | a file could not be read or written | 1 |
//! | [`Error::Usage`] | an option or file name cannot be used | 2 |
//! | [`Error::Numerical`] | a linear system or a patch is degenerate | 3 |

use std::fmt;

/// The error type of every fallible curvenet operation.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// A file is malformed. Occurs when a network file does not follow its format
    /// (see the README, "Formats"); `line` and `column` are 1-based.
    #[error("{path}:{line}:{column}: {message}")]
    Parse { path: String, line: usize, column: usize, message: String },

    /// The network's values are invalid: non-finite numbers, zero normals, too few samples,
    /// normals that disagree in orientation. The message names the curve and sample.
    #[error("{0}")]
    Input(String),

    /// The curves do not bound an oriented 2-manifold: a dangling segment, a segment with
    /// patches on both sides of a boundary, a cycle that crosses itself when projected. The
    /// message names the node, segment or curve.
    #[error("{0}")]
    Topology(String),

    /// A file could not be read or written.
    #[error("{path}: {source}")]
    Io { path: String, source: std::io::Error },

    /// An option value or a file name cannot be used (unknown extension, conflicting options).
    #[error("{0}")]
    Usage(String),

    /// A numerical failure: a system that is not positive definite, a degenerate patch.
    #[error("numerical failure: {0}")]
    Numerical(String),
}

impl Error {
    /// The process exit code the command-line tool uses for this error:
    /// 1 bad input, 2 usage, 3 numerical failure.
    pub fn exit_code(&self) -> i32 {
        match self {
            Error::Parse { .. } | Error::Input(_) | Error::Topology(_) | Error::Io { .. } => 1,
            Error::Usage(_) => 2,
            Error::Numerical(_) => 3,
        }
    }

    pub(crate) fn io(path: &std::path::Path, source: std::io::Error) -> Self {
        Error::Io { path: path.display().to_string(), source }
    }
}

/// Shorthand for `Result<T, curvenet::Error>`.
pub type Result<T> = std::result::Result<T, Error>;

/// Something the pipeline repaired or assumed on the user's behalf (a merged duplicate sample,
/// a snapped crossing). The run succeeds; front ends show these to the user.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Warning(pub String);

impl fmt::Display for Warning {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.0)
    }
}
