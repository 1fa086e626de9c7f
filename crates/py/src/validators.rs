//! Validators for plans made elsewhere: `mason.validate_order`, `mason.validate_schedule` and
//! `mason.check_trace` take what the CLI writes (a dict, its JSON text, or Mason's own
//! `Plan`, `Schedule` and `Trace`), or a plain form (a list of brick ids; a CSV of
//! `uav,brick,start[,end]` rows), read by `mason_io::artefacts` and checked by the domain
//! validators, as `mason check` does.

use crate::missions::PyTrace;
use crate::plans::{PyPlan, PySchedule};
use crate::walls::PyWall;
use crate::{bad, error};
use mason_io::artefacts;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};
use std::fmt::{Debug, Display};
use std::path::Path;

/// The artefact's text: Mason's own objects give their JSON, a str is taken as it is (JSON
/// or the plain forms), a list of ids becomes one id per line, anything else goes through
/// `json.dumps`.
fn text_of(py: Python<'_>, obj: &Bound<'_, PyAny>, what: &str) -> PyResult<String> {
    if let Ok(p) = obj.cast::<PyPlan>() {
        return Ok(p.get().json_text());
    }
    if let Ok(s) = obj.cast::<PySchedule>() {
        return Ok(s.get().json_text());
    }
    if let Ok(t) = obj.cast::<PyTrace>() {
        return Ok(t.get().json_text());
    }
    if let Ok(text) = obj.extract::<String>() {
        return Ok(text);
    }
    if what == "plan" {
        if let Ok(ids) = obj.extract::<Vec<i64>>() {
            return Ok(ids
                .iter()
                .map(i64::to_string)
                .collect::<Vec<_>>()
                .join("\n"));
        }
    }
    let value = crate::from_py(py, obj, what)?;
    Ok(value.to_string())
}

/// `mason.ValidationError` naming the first broken rule, with every one found in its
/// `violations` attribute (a list of `"Rule: message"`).
fn broken<E: Debug + Display>(py: Python<'_>, what: &str, found: &[E]) -> PyErr {
    let lines: Vec<String> = found
        .iter()
        .map(|e| format!("{}: {e}", artefacts::rule(e)))
        .collect();
    let first = lines.first().cloned().unwrap_or_default();
    let err = error(py, "ValidationError", format!("{what}: breaks {first}"));
    let _ = err
        .value(py)
        .setattr("violations", PyList::new(py, &lines).ok());
    err
}

/// Checks a build order of `wall`: every brick once, each after its supports, with the total
/// cost recomputed (`order::validate`) and, when the plan states one, compared.
///
/// `plan` is a `mason.Plan`, the dict or JSON text of `mason plan --json`, or a list of brick
/// ids (first placed first). `model` is a cost-model TOML (default: the thesis's). With
/// `all=True` the error's `violations` lists every broken rule. Returns `{"total_cost",
/// "steps"}`; raises `mason.ValidationError` (first broken rule) or `mason.InputError`.
#[pyfunction]
#[pyo3(signature = (wall, plan, model = None, all = false))]
fn validate_order<'py>(
    py: Python<'py>,
    wall: &PyWall,
    plan: &Bound<'py, PyAny>,
    model: Option<std::path::PathBuf>,
    all: bool,
) -> PyResult<Bound<'py, PyDict>> {
    let text = text_of(py, plan, "plan")?;
    let model = mason_io::load_model(model.as_deref()).map_err(bad(py))?;
    let w = &wall.wall;
    let file = artefacts::parse_order(&text, Path::new("plan"), w).map_err(bad(py))?;
    let eval = file
        .check(w, &model, all)
        .map_err(|found| broken(py, "plan", &found))?;
    let d = PyDict::new(py);
    d.set_item("total_cost", eval.total_cost)?;
    d.set_item("steps", eval.steps.len())?;
    Ok(d)
}

/// Checks a team schedule of `wall` (`order::schedule::validate_schedule`: crews, the zone
/// and distance rules, precedence, each UAV's cycle, the budget), the ends its rows state, and
/// the reward and makespan it claims.
///
/// `schedule` is a `mason.Schedule`, the dict or JSON text of `mason plan --objective …
/// --json`, or CSV text of `uav,brick,start[,end]` rows. `model` (`thesis`, `cmcp` or a TOML),
/// `uavs` and `budget` default to what the schedule states. Returns `{"reward", "makespan_s",
/// "bricks_placed"}` as recomputed.
#[pyfunction]
#[pyo3(signature = (wall, schedule, model = None, uavs = None, budget = None, all = false, metric = None))]
#[allow(clippy::too_many_arguments)]
fn validate_schedule<'py>(
    py: Python<'py>,
    wall: &PyWall,
    schedule: &Bound<'py, PyAny>,
    model: Option<&str>,
    uavs: Option<i64>,
    budget: Option<f64>,
    all: bool,
    metric: Option<&str>,
) -> PyResult<Bound<'py, PyDict>> {
    let text = text_of(py, schedule, "schedule")?;
    let uavs = uavs.map(|u| crate::count(py, "uavs", u)).transpose()?;
    let w = &wall.wall;
    let path = Path::new("schedule");
    let file = artefacts::parse_schedule(&text, path, w).map_err(bad(py))?;
    let setting = file
        .setting(path, model, metric, uavs, budget)
        .map_err(bad(py))?;
    let eval = file
        .check(w, &setting, all)
        .map_err(|found| broken(py, "schedule", &found))?;
    let d = PyDict::new(py);
    d.set_item("reward", eval.reward)?;
    d.set_item("makespan_s", eval.makespan_s)?;
    d.set_item("bricks_placed", eval.bricks)?;
    Ok(d)
}

/// Checks a mission trace of `wall` with `mission::check_trace`: one UAV in the zone (or one
/// orange pair), every brick placed once, by a UAV in the zone holding it, after its
/// supports, and every grasped brick placed or lost.
///
/// `trace` is a `mason.Trace`, the dict or JSON text of `mason simulate --json` or of
/// `launch`'s `trace.json`, or a list of event dicts. `uavs` defaults to what it states.
/// Returns `{"placed", "lost", "in_flight"}`.
#[pyfunction]
#[pyo3(signature = (wall, trace, uavs = None, all = false))]
fn check_trace<'py>(
    py: Python<'py>,
    wall: &PyWall,
    trace: &Bound<'py, PyAny>,
    uavs: Option<i64>,
    all: bool,
) -> PyResult<Bound<'py, PyDict>> {
    let text = text_of(py, trace, "trace")?;
    let w = &wall.wall;
    let file = artefacts::parse_trace_json(&text, Path::new("trace"), w).map_err(bad(py))?;
    let uavs = match uavs {
        Some(u) => crate::count(py, "uavs", u)?,
        None => file.uavs,
    };
    if uavs == 0 || uavs > mason_order::schedule::MAX_UAVS {
        return Err(crate::input_error(
            py,
            format!(
                "uavs {uavs}: expected 1 to {}",
                mason_order::schedule::MAX_UAVS
            ),
        ));
    }
    let summary = file
        .check(w, uavs, all)
        .map_err(|found| broken(py, "trace", &found))?;
    let d = PyDict::new(py);
    d.set_item("placed", summary.placed)?;
    d.set_item("lost", summary.lost)?;
    d.set_item("in_flight", summary.in_flight)?;
    Ok(d)
}

pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(validate_order, m)?)?;
    m.add_function(wrap_pyfunction!(validate_schedule, m)?)?;
    m.add_function(wrap_pyfunction!(check_trace, m)?)?;
    Ok(())
}
