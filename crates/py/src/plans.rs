//! Build orders (`mason.plan_order`, `mason.Plan`) and team schedules
//! (`mason.plan_schedule`, `mason.Schedule`), each checked by its validator as in the CLI.

use crate::walls::PyWall;
use crate::{bad, error, input_error, internal, run_detached, to_py};
use mason_order::schedule::{schedule_checked, Objective, Schedule, TeamProblem};
use mason_order::{
    plan_checked, Better, Budget, BuildProblem, CostModel, OnBetter, PlannerSpec, Status, Stop,
};
use mason_wall::{BrickId, Wall};
use numpy::PyArray1;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use std::sync::{Arc, Mutex};
use std::time::Duration;

/// A checked time limit ([`mason_io::time_limit`]).
pub(crate) fn time_limit(py: Python<'_>, limit: Option<f64>) -> PyResult<Option<Duration>> {
    Ok(mason_io::time_limit("time_limit", limit)
        .map_err(bad(py))?
        .map(Duration::from_secs_f64))
}

/// Brick ids (thesis ids or CMCP ids, as the CLI prints them) as the wall's bricks.
pub(crate) fn brick_ids(py: Python<'_>, wall: &Wall, ids: &[i64]) -> PyResult<Vec<BrickId>> {
    ids.iter()
        .enumerate()
        .map(|(k, &id)| {
            u32::try_from(id)
                .ok()
                .and_then(|l| wall.by_label(l))
                .ok_or_else(|| {
                    input_error(
                        py,
                        format!("entry {k}: brick {id} is not in wall {}", wall.name()),
                    )
                })
        })
        .collect()
}

fn status_name(s: Status) -> String {
    s.to_string()
}

/// The cost model of a TOML file, or the thesis's.
fn cost_model(py: Python<'_>, model: Option<std::path::PathBuf>) -> PyResult<CostModel> {
    mason_io::load_model(model.as_deref()).map_err(bad(py))
}

/// A build order, checked by `order::validate` (its costs recomputed from the model).
#[pyclass(module = "mason", name = "Plan", frozen)]
pub struct PyPlan {
    pub(crate) wall: Arc<Wall>,
    pub(crate) order: Vec<BrickId>,
    pub(crate) planner: String,
    status: Status,
    total_cost: f64,
    json: serde_json::Value,
}

impl PyPlan {
    /// The JSON the CLI prints, compact.
    pub(crate) fn json_text(&self) -> String {
        self.json.to_string()
    }
}

#[pymethods]
impl PyPlan {
    /// The build order: a numpy int64 array of brick ids, first placed first.
    #[getter]
    fn order<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<i64>> {
        let ids: Vec<i64> = self
            .order
            .iter()
            .map(|&b| i64::from(self.wall.brick(b).label))
            .collect();
        PyArray1::from_vec(py, ids)
    }

    /// Total cost (s) as recomputed by the validator.
    #[getter]
    fn total_cost(&self) -> f64 {
        self.total_cost
    }

    /// `optimal`, `feasible` or `timeout` (the best order found within the time limit).
    #[getter]
    fn status(&self) -> String {
        status_name(self.status)
    }

    /// The planner, as `planner=` names it.
    #[getter]
    fn planner(&self) -> String {
        self.planner.clone()
    }

    /// The steps: dicts with `id`, `placed_neighbours` and `cost`.
    #[getter]
    fn steps<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        to_py(py, &self.json["steps"])
    }

    /// The plan as the JSON `mason plan --json` prints.
    fn to_json(&self) -> String {
        serde_json::to_string_pretty(&self.json).unwrap_or_default()
    }

    fn __len__(&self) -> usize {
        self.order.len()
    }

    fn __repr__(&self) -> String {
        format!(
            "<mason.Plan {} of {:?}: {} bricks, total cost {:.2} s, {}>",
            self.planner,
            self.wall.name(),
            self.order.len(),
            self.total_cost,
            self.status
        )
    }
}

/// Plans a build order for `wall` and checks it with the order validator.
///
/// `planner` is `"exact"`, `"greedy"`, `"brute"` or `"improved:N,K"` (e.g. `"improved:1,4"`);
/// `model` a cost model TOML file (default: the thesis's); `time_limit` seconds (None: no
/// limit), after which the best order so far is returned with status `"timeout"`. Ctrl-C
/// stops the search. Raises `mason.NoSolutionError` when no complete order was found.
#[pyfunction]
#[pyo3(signature = (wall, planner = "exact", model = None, time_limit = None))]
fn plan_order(
    py: Python<'_>,
    wall: &PyWall,
    planner: &str,
    model: Option<std::path::PathBuf>,
    time_limit: Option<f64>,
) -> PyResult<PyPlan> {
    let spec: PlannerSpec = planner
        .parse()
        .map_err(|e| input_error(py, format!("planner: {e}")))?;
    let limit = self::time_limit(py, time_limit)?;
    let model = cost_model(py, model)?;
    let w = wall.wall.clone();
    let problem = BuildProblem::new(&w, model).map_err(bad(py))?;
    let stop = Stop::new();
    let budget = match limit {
        Some(l) => Budget::time(l),
        None => Budget::unlimited(),
    }
    .with_stop(Some(stop.clone()));
    let checked = run_detached(
        py,
        &stop,
        || plan_checked(&problem, spec, &budget),
        |_| Ok(()),
    )?
    .map_err(|e| internal(py, e))?;
    let (Some(order), Some(eval)) = (&checked.outcome.order, &checked.evaluation) else {
        let why = if checked.outcome.status == Status::Infeasible {
            "no valid build order exists".to_string()
        } else {
            format!("{spec}: no complete build order within the budget")
        };
        return Err(error(py, "NoSolutionError", why));
    };
    Ok(PyPlan {
        wall: w.clone(),
        order: order.clone(),
        planner: spec.to_string(),
        status: checked.outcome.status,
        total_cost: eval.total_cost,
        json: mason_report::plan_json(&problem, &checked),
    })
}

/// A team schedule, checked by `order::validate_schedule` (reward and makespan recomputed)
/// and against its proven bound.
#[pyclass(module = "mason", name = "Schedule", frozen)]
pub struct PySchedule {
    pub(crate) wall: Arc<Wall>,
    pub(crate) schedule: Schedule,
    pub(crate) uavs: usize,
    objective: Objective,
    status: Status,
    makespan: f64,
    reward: f64,
    expected_reward: Option<f64>,
    bound: f64,
    gap: f64,
    ends: Vec<f64>,
    json: serde_json::Value,
}

impl PySchedule {
    /// The JSON the CLI prints, compact.
    pub(crate) fn json_text(&self) -> String {
        self.json.to_string()
    }
}

#[pymethods]
impl PySchedule {
    /// The last placement's end (s).
    #[getter]
    fn makespan(&self) -> f64 {
        self.makespan
    }

    /// The reward placed (by the budget, when there is one).
    #[getter]
    fn reward(&self) -> f64 {
        self.reward
    }

    /// For `objective="expected"`: the expected reward when UAVs fail at `uav_hazard`.
    #[getter]
    fn expected_reward(&self) -> Option<f64> {
        self.expected_reward
    }

    /// The proven bound: a lower bound on the makespan, or an upper bound on the reward.
    #[getter]
    fn bound(&self) -> f64 {
        self.bound
    }

    /// The distance to the bound (never negative; 0 means proven optimal).
    #[getter]
    fn gap(&self) -> f64 {
        self.gap
    }

    /// `optimal`, `feasible` or `timeout`.
    #[getter]
    fn status(&self) -> String {
        status_name(self.status)
    }

    /// The objective's name.
    #[getter]
    fn objective(&self) -> &'static str {
        self.objective.name()
    }

    /// Team size.
    #[getter]
    fn uavs(&self) -> usize {
        self.uavs
    }

    /// The placements as a numpy structured array with fields `uav` (int32), `brick` (int64,
    /// the brick id), `start` and `end` (float64, s), by start time; an orange brick placed
    /// by two UAVs has a row for each.
    fn to_numpy<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let mut uav = Vec::new();
        let mut brick = Vec::new();
        let mut start = Vec::new();
        let mut end = Vec::new();
        for (pl, &e) in self.schedule.placements.iter().zip(&self.ends) {
            for &u in &pl.uavs {
                uav.push(u as i32);
                brick.push(i64::from(self.wall.brick(pl.brick).label));
                start.push(pl.start_s);
                end.push(e);
            }
        }
        let np = py.import("numpy")?;
        let dtype = vec![
            ("uav", "<i4"),
            ("brick", "<i8"),
            ("start", "<f8"),
            ("end", "<f8"),
        ];
        let out = np.call_method1("empty", (uav.len(), dtype))?;
        out.set_item("uav", PyArray1::from_vec(py, uav))?;
        out.set_item("brick", PyArray1::from_vec(py, brick))?;
        out.set_item("start", PyArray1::from_vec(py, start))?;
        out.set_item("end", PyArray1::from_vec(py, end))?;
        Ok(out)
    }

    /// The schedule as the JSON `mason plan --objective … --json` prints.
    fn to_json(&self) -> String {
        serde_json::to_string_pretty(&self.json).unwrap_or_default()
    }

    fn __len__(&self) -> usize {
        self.schedule.placements.len()
    }

    fn __repr__(&self) -> String {
        format!(
            "<mason.Schedule {} of {:?}, {} UAVs: makespan {:.1} s, reward {}, bound {}, {}>",
            self.objective.name(),
            self.wall.name(),
            self.uavs,
            self.makespan,
            self.reward,
            self.bound,
            self.status
        )
    }
}

/// The best result so far, kept for the progress callback.
#[derive(Default)]
struct Best {
    latest: Option<Better>,
    told: Option<Better>,
}

/// Plans a team schedule for `wall` and checks it (`order::validate_schedule`, and the
/// objective against its proven bound).
///
/// `objective` is `"makespan"` (whole wall, shortest), `"reward"` (most reward by `budget`
/// seconds) or `"expected"` (most expected reward by `budget` when each UAV fails at
/// `uav_hazard` per hour). `model` is `"thesis"`, `"cmcp"` or a team-model TOML file;
/// `metric` (`"xy"` or `"xyz"`) measures its distance rule in the plan or in 3-D.
/// The search runs until `time_limit` seconds (None: a fixed number of decodes, the same
/// schedule for the same seed), on two threads with the GIL released; Ctrl-C stops it.
/// `progress`, if given, is called now and then with a dict of the best so far: `value`
/// (makespan, or the (expected) reward), `bound`, `decodes` and `elapsed_s`.
#[pyfunction]
#[pyo3(signature = (wall, objective = "makespan", uavs = 3, model = "thesis", budget = None, uav_hazard = None, time_limit = 1.0, seed = 0, progress = None, metric = None))]
#[allow(clippy::too_many_arguments)]
fn plan_schedule(
    py: Python<'_>,
    wall: &PyWall,
    objective: &str,
    uavs: i64,
    model: &str,
    budget: Option<f64>,
    uav_hazard: Option<f64>,
    time_limit: Option<f64>,
    seed: u64,
    progress: Option<Bound<'_, PyAny>>,
    metric: Option<&str>,
) -> PyResult<PySchedule> {
    let uavs = crate::count(py, "uavs", uavs)?;
    let objective = mason_io::objective(objective, uav_hazard).map_err(bad(py))?;
    let limit = self::time_limit(py, time_limit)?;
    let team = mason_io::load_team_model(Some(model), metric).map_err(bad(py))?;
    let w = wall.wall.clone();
    let problem = TeamProblem::new(&w, team, uavs, budget, objective).map_err(bad(py))?;
    let stop = Stop::new();
    let best = Arc::new(Mutex::new(Best::default()));
    let mut search = Budget::anytime(limit).with_stop(Some(stop.clone()));
    if progress.is_some() {
        let best = best.clone();
        let minimise = matches!(objective, Objective::Makespan);
        search.on_better = Some(OnBetter(Arc::new(move |b: Better| {
            if let Ok(mut best) = best.lock() {
                let improves = best.latest.is_none_or(|l| {
                    if minimise {
                        b.value < l.value
                    } else {
                        b.value > l.value
                    }
                });
                if improves {
                    best.latest = Some(b);
                }
            }
        })));
    }
    let tick = |py: Python<'_>| -> PyResult<()> {
        let Some(callback) = &progress else {
            return Ok(());
        };
        let news = {
            let mut b = best.lock().map_err(|_| internal(py, "progress lock"))?;
            let news = b.latest.filter(|l| b.told != Some(*l));
            if news.is_some() {
                b.told = news;
            }
            news
        };
        if let Some(b) = news {
            let d = PyDict::new(py);
            d.set_item("value", b.value)?;
            d.set_item("bound", b.bound)?;
            d.set_item("decodes", b.decodes)?;
            d.set_item("elapsed_s", b.elapsed_s)?;
            callback.call1((d,))?;
        }
        Ok(())
    };
    let checked = run_detached(
        py,
        &stop,
        || schedule_checked(&problem, &search, seed),
        tick,
    )?
    .map_err(|e| internal(py, format!("the planner produced an invalid schedule: {e}")))?;
    let o = &checked.outcome;
    let schedule = o.schedule.clone().unwrap_or_default();
    let ends = schedule
        .placements
        .iter()
        .map(|pl| pl.start_s + problem.place_s(pl.brick))
        .collect();
    Ok(PySchedule {
        wall: w.clone(),
        uavs,
        objective,
        status: o.status,
        makespan: o.makespan_s,
        reward: o.reward,
        expected_reward: o.expected_reward,
        bound: o.bound,
        gap: o.gap(objective),
        ends,
        json: mason_report::schedule_json(&problem, &checked, seed),
        schedule,
    })
}

pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<PyPlan>()?;
    m.add_class::<PySchedule>()?;
    m.add_function(wrap_pyfunction!(plan_order, m)?)?;
    m.add_function(wrap_pyfunction!(plan_schedule, m)?)?;
    Ok(())
}
