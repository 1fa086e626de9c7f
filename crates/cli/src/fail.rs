//! Exit codes: 0 success, 1 infeasible or nothing found in the budget, 2 bad input or usage.

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

/// The folder `path` goes into (`.` for a bare file name).
fn folder_of(path: &Path) -> &Path {
    path.parent()
        .filter(|d| !d.as_os_str().is_empty())
        .unwrap_or(Path::new("."))
}

/// Checks, before any work, that an output can go to `path`: its folder exists (no folder is
/// created) and `path` is not itself a folder. Exit 2 otherwise.
pub fn check_output(path: &Path) -> CliResult<()> {
    let dir = folder_of(path);
    if !dir.is_dir() {
        return Err(input_error(format!(
            "{}: the folder {} does not exist (create it first)",
            path.display(),
            dir.display()
        )));
    }
    if path.is_dir() {
        return Err(input_error(format!(
            "{}: is a folder; give a file name",
            path.display()
        )));
    }
    Ok(())
}

/// The temporary name `path` is written under before it is renamed into place.
fn temporary(path: &Path) -> PathBuf {
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    folder_of(path).join(format!(".{name}.mason-{}.tmp", std::process::id()))
}

/// Writes all of a command's output files, or none: every path is checked first, each file is
/// written to a temporary name in its own folder, and only when all are written are they
/// renamed into place. On failure the temporary files are removed (exit 2).
pub fn write_files(files: &[(&Path, &[u8])]) -> CliResult<()> {
    for (path, _) in files {
        check_output(path)?;
    }
    let mut written: Vec<PathBuf> = Vec::new();
    let clean = |written: &[PathBuf]| {
        for t in written {
            let _ = std::fs::remove_file(t);
        }
    };
    for (path, contents) in files {
        let tmp = temporary(path);
        if let Err(e) = std::fs::write(&tmp, contents) {
            let _ = std::fs::remove_file(&tmp);
            clean(&written);
            return Err(input_error(format!("{}: {e}", path.display())));
        }
        written.push(tmp);
    }
    for (i, (path, _)) in files.iter().enumerate() {
        if let Err(e) = std::fs::rename(&written[i], path) {
            clean(&written[i..]);
            return Err(input_error(format!("{}: {e}", path.display())));
        }
    }
    Ok(())
}

/// Writes one output file atomically (see [`write_files`]).
pub fn write_file(path: &Path, contents: &[u8]) -> CliResult<()> {
    write_files(&[(path, contents)])
}

/// [`write_files`] for owned paths and contents.
pub fn write_all(files: &[(PathBuf, Vec<u8>)]) -> CliResult<()> {
    let borrowed: Vec<(&Path, &[u8])> = files
        .iter()
        .map(|(p, c)| (p.as_path(), c.as_slice()))
        .collect();
    write_files(&borrowed)
}

/// [`check_output`] for every output path given.
pub fn check_outputs(paths: &[&Option<PathBuf>]) -> CliResult<()> {
    for p in paths.iter().copied().flatten() {
        check_output(p)?;
    }
    Ok(())
}
