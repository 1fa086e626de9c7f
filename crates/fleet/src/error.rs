//! The agent runtime's errors.

use std::path::PathBuf;

/// What can stop an agent, a launch or a trace read.
#[derive(Debug, thiserror::Error)]
pub enum FleetError {
    /// A file or option was bad (its message names it).
    #[error(transparent)]
    Input(#[from] mason_io::InputError),
    /// An option is out of range or contradicts another (the message names the flag).
    #[error("{0}")]
    Bad(String),
    /// A trace file cannot be read, or has a bad line.
    #[error("{}{}: {reason}", path.display(), line.map_or(String::new(), |l| format!(": line {l}")))]
    Trace {
        /// The file.
        path: PathBuf,
        /// The line (1-based), when one line is bad.
        line: Option<usize>,
        /// Why.
        reason: String,
    },
    /// Writing a log, a trace or a process failed.
    #[error("{}: {source}", path.display())]
    Io {
        /// The file or program.
        path: PathBuf,
        /// Why.
        source: std::io::Error,
    },
    /// The network refused (an endpoint in use, a session that cannot open).
    #[error("{0}")]
    Network(String),
}

impl FleetError {
    /// A bad option, in one line.
    pub fn bad(message: impl Into<String>) -> Self {
        FleetError::Bad(message.into())
    }
}

/// Result of the agent runtime.
pub type FleetResult<T> = Result<T, FleetError>;
