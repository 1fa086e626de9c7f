//! `mason` from Python: the native part (`mason._mason`) of the package in `python/mason`.
//!
//! It binds the libraries and adds no logic of its own (DESIGN §2, §9): walls
//! (`mason_io::load_wall`), build orders (`mason_order::plan_checked`), team schedules
//! (`schedule_checked`), missions (`fly_checked`, `for_each_run`), crews (`solve_checked`) and
//! the validators. JSON goes through `mason_report`, so that `to_json()` is what the CLI prints.
//!
//! Long calls run on a Rust thread with the GIL released ([`run_detached`]); the calling thread
//! wakes every [`TICK`] to look for Ctrl-C (then it raises the search's [`Stop`] flag and the
//! search returns at its next budget check) and to hand progress to Python. Errors are the
//! Python classes of `mason._errors`, carrying the CLI's one-line messages.

use mason_wall::stop::Stop;
use pyo3::exceptions::PyRuntimeError;
use pyo3::prelude::*;
use pyo3::types::PyType;
use std::sync::mpsc;
use std::time::Duration;

mod crew;
mod missions;
mod plans;
mod validators;
mod walls;

/// How often a thread waiting on a solve looks for Ctrl-C and progress.
pub const TICK: Duration = Duration::from_millis(40);

/// A Python exception of `mason._errors` (`InputError`, `NoSolutionError`,
/// `ValidationError`, `MasonError`) carrying `message`.
pub(crate) fn error(py: Python<'_>, class: &str, message: impl Into<String>) -> PyErr {
    let message = message.into();
    let class = py
        .import("mason._errors")
        .and_then(|m| m.getattr(class))
        .and_then(|c| c.cast_into::<PyType>().map_err(PyErr::from));
    match class {
        Ok(t) => PyErr::from_type(t, message),
        Err(_) => PyRuntimeError::new_err(message),
    }
}

/// Bad input: `mason.InputError` (a `ValueError`), the CLI's exit code 2.
pub(crate) fn input_error(py: Python<'_>, message: impl Into<String>) -> PyErr {
    error(py, "InputError", message)
}

/// A Rust error turned into `mason.InputError` with its message.
pub(crate) fn bad<E: std::fmt::Display>(py: Python<'_>) -> impl Fn(E) -> PyErr + '_ {
    move |e| input_error(py, e.to_string())
}

/// A validator's finding: `mason.ValidationError` (a `ValueError`).
pub(crate) fn invalid(py: Python<'_>, message: impl Into<String>) -> PyErr {
    error(py, "ValidationError", message)
}

/// A solver's result that failed its validator: a bug in Mason, never a result.
pub(crate) fn internal(py: Python<'_>, message: impl std::fmt::Display) -> PyErr {
    error(py, "MasonError", format!("internal error: {message}"))
}

/// A count argument (`uavs`, `runs`, `agents`) as a `usize`: a negative one is an
/// `InputError` naming the argument, not an `OverflowError`.
pub(crate) fn count(py: Python<'_>, name: &str, v: i64) -> PyResult<usize> {
    usize::try_from(v)
        .map_err(|_| input_error(py, format!("{name} {v}: expected a count, 0 or more")))
}

/// A JSON value as Python objects (dicts, lists, numbers, strings, None).
pub(crate) fn to_py<'py>(py: Python<'py>, v: &serde_json::Value) -> PyResult<Bound<'py, PyAny>> {
    let text = serde_json::to_string(v).map_err(|e| internal(py, e))?;
    py.import("json")?.call_method1("loads", (text,))
}

/// A Python object (a dict or list as the CLI writes them, or their JSON text) as JSON.
pub(crate) fn from_py(
    py: Python<'_>,
    obj: &Bound<'_, PyAny>,
    what: &str,
) -> PyResult<serde_json::Value> {
    let text: String = match obj.extract::<String>() {
        Ok(text) => text,
        Err(_) => py
            .import("json")?
            .call_method1("dumps", (obj,))
            .map_err(|e| input_error(py, format!("{what}: not JSON data ({e})")))?
            .extract()?,
    };
    serde_json::from_str(&text).map_err(|e| input_error(py, format!("{what}: not JSON: {e}")))
}

/// Runs `work` on a new thread with the GIL released and waits for it. Every [`TICK`] the
/// waiting thread takes the GIL back to look for signals (Ctrl-C raises `stop`, waits for the
/// search to return, and raises KeyboardInterrupt) and calls `tick` (progress; an exception
/// there stops the search too and is raised). `tick` is called once more at the end.
pub(crate) fn run_detached<T: Send>(
    py: Python<'_>,
    stop: &Stop,
    work: impl FnOnce() -> T + Send,
    mut tick: impl FnMut(Python<'_>) -> PyResult<()>,
) -> PyResult<T> {
    std::thread::scope(|scope| {
        let (done_tx, done_rx) = mpsc::channel::<()>();
        let handle = scope.spawn(move || {
            let out = work();
            let _ = done_tx.send(());
            out
        });
        let mut rx = done_rx;
        let mut failure: Option<PyErr> = None;
        loop {
            let (got, back) = py.detach(move || {
                let got = rx.recv_timeout(TICK);
                (got, rx)
            });
            rx = back;
            if !matches!(got, Err(mpsc::RecvTimeoutError::Timeout)) {
                break;
            }
            if let Err(e) = py.check_signals().and_then(|()| tick(py)) {
                stop.raise();
                failure = Some(e);
                break;
            }
        }
        let joined = py.detach(move || handle.join());
        if let Some(e) = failure {
            return Err(e);
        }
        tick(py)?;
        joined.map_err(|_| internal(py, "a solver thread panicked"))
    })
}

/// The native module `mason._mason`; `mason/__init__.py` re-exports it.
#[pymodule]
fn _mason(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    walls::register(m)?;
    plans::register(m)?;
    missions::register(m)?;
    validators::register(m)?;
    crew::register(m)?;
    Ok(())
}
