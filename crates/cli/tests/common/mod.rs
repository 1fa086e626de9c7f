//! Helpers shared by the CLI test binaries: run `mason`, read its output, check a bad-input
//! error, find the project's Python venv. Each test binary uses only some of them.
#![allow(dead_code)]

use std::path::PathBuf;
use std::process::{Command, Output};

/// The workspace root.
pub fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// The venv's python (`${MASON_PYENV:-target/pyenv}`) if it can import `module`, else `None`
/// with a skip notice; with MASON_REQUIRE_PYTHON set, a missing module fails the test instead.
/// `installer` is the project script that installs it.
pub fn python_with(module: &str, installer: &str) -> Option<PathBuf> {
    let env = std::env::var_os("MASON_PYENV")
        .map(PathBuf::from)
        .unwrap_or_else(|| PathBuf::from("target/pyenv"));
    let env = if env.is_absolute() {
        env
    } else {
        root().join(env)
    };
    let python = env.join("bin/python");
    let works = Command::new(&python)
        .args(["-c", &format!("import {module}")])
        .output()
        .is_ok_and(|o| o.status.success());
    if works {
        return Some(python);
    }
    assert!(
        std::env::var_os("MASON_REQUIRE_PYTHON").is_none(),
        "MASON_REQUIRE_PYTHON is set but {} cannot import {module} (run {installer})",
        python.display()
    );
    eprintln!(
        "skipped: no Python {module} in {} ({installer} installs it)",
        env.display()
    );
    None
}

/// A fixture in the workspace's `tests/data`.
pub fn data(name: &str) -> String {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../tests/data")
        .join(name)
        .to_string_lossy()
        .into_owned()
}

/// Runs the `mason` binary.
pub fn mason(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_mason"))
        .args(args)
        .output()
        .expect("mason runs")
}

pub fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

pub fn stdout(o: &Output) -> String {
    String::from_utf8_lossy(&o.stdout).into_owned()
}

/// Exit 2, one line on stderr containing every `needle`, and no panic.
pub fn assert_input_error(o: &Output, needles: &[&str]) {
    let err = stderr(o);
    assert_eq!(o.status.code(), Some(2), "stderr: {err}");
    assert_eq!(err.trim_end().lines().count(), 1, "one line: {err}");
    assert!(!err.contains("panicked"), "{err}");
    for n in needles {
        assert!(err.contains(n), "`{n}` missing in: {err}");
    }
}

/// A usage error from the argument parser: exit 2, its first line names what is wrong, and no
/// panic (clap adds a usage line and a hint below it).
pub fn assert_usage_error(o: &Output, needles: &[&str]) {
    let err = stderr(o);
    assert_eq!(o.status.code(), Some(2), "stderr: {err}");
    assert!(!err.contains("panicked"), "{err}");
    let first = err.lines().next().unwrap_or_default();
    assert!(first.starts_with("error: "), "{err}");
    for n in needles {
        assert!(first.contains(n), "`{n}` missing in: {first}");
    }
}
