//! Exit codes: 0 success, 1 infeasible or nothing found in the budget, 2 bad input or usage.

use std::fmt;

/// An error that ends the program with a chosen exit code and one line.
#[derive(Debug)]
pub struct Failure {
    /// Exit code.
    pub code: u8,
    /// The one-line message.
    pub message: String,
}

impl fmt::Display for Failure {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.message)
    }
}

impl std::error::Error for Failure {}

/// Result of a command.
pub type CliResult<T> = Result<T, Failure>;

/// Bad input or usage (exit 2).
pub fn input_error(message: impl Into<String>) -> Failure {
    Failure {
        code: 2,
        message: message.into(),
    }
}

/// Nothing found or infeasible (exit 1).
pub fn no_solution(message: impl Into<String>) -> Failure {
    Failure {
        code: 1,
        message: message.into(),
    }
}

/// Writing an output file failed (exit 2: the path given is unusable).
pub fn write_file(path: &std::path::Path, contents: &[u8]) -> CliResult<()> {
    if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir).map_err(|e| input_error(format!("{}: {e}", dir.display())))?;
    }
    std::fs::write(path, contents).map_err(|e| input_error(format!("{}: {e}", path.display())))
}
