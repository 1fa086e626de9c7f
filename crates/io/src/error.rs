//! The one error of input reading: a file, a line or a flag, and what is wrong with it.

use std::path::PathBuf;

/// Bad input. The message is one line that names where (file and line, flag, or key) and why.
#[derive(Debug, thiserror::Error)]
pub enum InputError {
    /// The file cannot be opened or read.
    #[error("{}: {source}", path.display())]
    Io {
        /// The file.
        path: PathBuf,
        /// Why.
        source: std::io::Error,
    },
    /// A folder, FIFO, socket or device where a file was expected.
    #[error("{}: {kind}; give a file", path.display())]
    NotAFile {
        /// The path.
        path: PathBuf,
        /// What it is instead.
        kind: &'static str,
    },
    /// Larger than the limit for this input.
    #[error("{}: larger than {limit} bytes, the limit for this input (mason_io::MAX_*_BYTES)", path.display())]
    TooLarge {
        /// The file.
        path: PathBuf,
        /// The limit (bytes).
        limit: u64,
    },
    /// Not UTF-8 where text was expected.
    #[error("{}: not UTF-8 text (byte {byte})", path.display())]
    NotText {
        /// The file.
        path: PathBuf,
        /// The first bad byte.
        byte: usize,
    },
    /// Any other bad input: the message names the file and line, or the flag, and the reason.
    #[error("{0}")]
    Bad(String),
}

impl InputError {
    /// Bad input, in one line.
    pub fn bad(message: impl Into<String>) -> Self {
        InputError::Bad(message.into())
    }
}

/// Result of reading input.
pub type InputResult<T> = Result<T, InputError>;
