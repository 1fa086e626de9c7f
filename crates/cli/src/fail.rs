//! Exit codes: 0 success, 1 infeasible or nothing found in the budget, 2 bad input or usage,
//! 3 a launched team's merged trace fails `check_trace`, 130 interrupted. Every library error
//! becomes one line and its code here.

use std::fmt;
use std::path::{Path, PathBuf};

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

/// Exit code when a launched team's merged trace fails `check_trace` (or cannot be read).
pub const UNSAFE: u8 = 3;

/// Exit code of a command interrupted by a signal (as shells report SIGINT).
pub const INTERRUPTED: u8 = 130;

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

impl From<mason_io::InputError> for Failure {
    fn from(e: mason_io::InputError) -> Self {
        input_error(e.to_string())
    }
}

impl From<mason_fleet::FleetError> for Failure {
    fn from(e: mason_fleet::FleetError) -> Self {
        let code = match e {
            mason_fleet::FleetError::Trace { .. } => UNSAFE,
            _ => 2,
        };
        Failure {
            code,
            message: e.to_string(),
        }
    }
}

impl From<mason_bench::BenchError> for Failure {
    fn from(e: mason_bench::BenchError) -> Self {
        input_error(e.to_string())
    }
}

/// Checks, before any work, that an output can go to `path` (exit 2 otherwise).
pub fn check_output(path: &Path) -> CliResult<()> {
    Ok(mason_io::check_output(path)?)
}

/// [`check_output`] for every output path given.
pub fn check_outputs(paths: &[&Option<PathBuf>]) -> CliResult<()> {
    for p in paths.iter().copied().flatten() {
        check_output(p)?;
    }
    Ok(())
}

/// Writes one output file atomically ([`mason_io::write_files`]).
pub fn write_file(path: &Path, contents: &[u8]) -> CliResult<()> {
    Ok(mason_io::write_file(path, contents)?)
}

/// Writes all of a command's output files, or none ([`mason_io::write_files`]).
pub fn write_all(files: &[(PathBuf, Vec<u8>)]) -> CliResult<()> {
    let borrowed: Vec<(&Path, &[u8])> = files
        .iter()
        .map(|(p, c)| (p.as_path(), c.as_slice()))
        .collect();
    Ok(mason_io::write_files(&borrowed)?)
}
