//! Missions: `mason.simulate` (one run, its trace checked by `check_trace`), `mason.monte_carlo`
//! (many seeds on Rust threads, every trace checked) and `mason.summarise` (the same summary
//! from runs flown elsewhere, e.g. on a Dask cluster).

use crate::plans::{PyPlan, PySchedule};
use crate::walls::PyWall;
use crate::{bad, from_py, input_error, internal, run_detached, to_py};
use mason_io::FaultSpec;
use mason_mission::{
    for_each_run, Coord, FlightPlan, MissionConfig, MissionInput, RunFigures, Summariser,
    ORDER_TIME_LIMIT_S,
};
use mason_order::schedule::TeamModel;
use mason_order::{plan_checked, Budget, BuildProblem, CostModel, PlannerSpec, Stop};
use mason_wall::{BrickId, Wall};
use numpy::{PyArray1, PyReadonlyArray1};
use pyo3::prelude::*;
use std::path::PathBuf;
use std::sync::Arc;

/// Everything a mission flies, resolved and checked once.
struct Setting {
    wall: Arc<Wall>,
    model: CostModel,
    config: MissionConfig,
    coord: Coord,
    slot: f64,
    planner: String,
    order: Vec<BrickId>,
    lists: Option<Vec<Vec<BrickId>>>,
}

impl Setting {
    fn input(&self) -> MissionInput<'_> {
        MissionInput {
            wall: &self.wall,
            order: &self.order,
            model: &self.model,
            assignment: self.lists.as_deref(),
            replanner: None,
            config: &self.config,
        }
    }

    fn header(&self, seed: u64) -> mason_report::RunSetting<'_> {
        mason_report::RunSetting {
            wall: &self.wall,
            uavs: self.config.uavs,
            coord: self.coord,
            planner: &self.planner,
            order: &self.order,
            seed,
            slot_s: self.slot,
            faults: &self.config.faults,
        }
    }
}

/// Whether `a` is the wall a plan was made for (the same object, or the same bricks).
fn same_wall(a: &Wall, b: &Wall) -> bool {
    std::ptr::eq(a, b)
        || (a.len() == b.len() && a.ids().all(|i| a.brick(i).label == b.brick(i).label))
}

#[allow(clippy::too_many_arguments)]
fn setting(
    py: Python<'_>,
    wall: &PyWall,
    plan_or_schedule: Option<&Bound<'_, PyAny>>,
    uavs: usize,
    coord: &str,
    faults: Option<&Bound<'_, PyAny>>,
    model: Option<PathBuf>,
    mission: Option<PathBuf>,
    slot: Option<f64>,
) -> PyResult<Setting> {
    let coord: Coord = coord
        .parse()
        .map_err(|e| input_error(py, format!("coord: {e}")))?;
    let mut config = match &mission {
        Some(p) => mason_io::read_mission(p, uavs).map_err(bad(py))?,
        None => MissionConfig::default(),
    };
    config.uavs = uavs;
    if let Some(f) = faults {
        let value = from_py(py, f, "faults")?;
        let spec: FaultSpec =
            serde_json::from_value(value).map_err(|e| input_error(py, format!("faults: {e}")))?;
        config.faults = spec.resolve().map_err(bad(py))?;
    }
    if slot.is_some() {
        config.coord.slot_s = slot;
    }
    config
        .validate()
        .map_err(|e| input_error(py, format!("mission: {e}")))?;
    let w = wall.wall.clone();
    let model = mason_io::load_model(model.as_deref()).map_err(bad(py))?;
    let slot = mason_mission::slot_length(&w, &model, &config).map_err(bad(py))?;
    let plan = plan_or_schedule.map(|p| (p.cast::<PyPlan>(), p.cast::<PySchedule>()));
    let (planner, order, lists) = match plan {
        Some((Ok(p), _)) => {
            let p = p.get();
            if !same_wall(&p.wall, &w) {
                return Err(input_error(
                    py,
                    format!(
                        "the plan is for wall {:?}, not {:?}",
                        p.wall.name(),
                        w.name()
                    ),
                ));
            }
            (p.planner.clone(), p.order.clone(), None)
        }
        Some((_, Ok(s))) => {
            let s = s.get();
            if !same_wall(&s.wall, &w) {
                return Err(input_error(
                    py,
                    format!(
                        "the schedule is for wall {:?}, not {:?}",
                        s.wall.name(),
                        w.name()
                    ),
                ));
            }
            if s.uavs != uavs {
                return Err(input_error(
                    py,
                    format!("the schedule is for {} UAVs, not {uavs}", s.uavs),
                ));
            }
            // Bricks a reward schedule leaves out follow in the exact planner's order.
            let base = exact_order(py, &w, &model)?;
            let flight = FlightPlan::of_schedule(
                &w,
                TeamModel::from_cost_model(&model),
                &s.schedule,
                uavs,
                &base,
            );
            ("schedule".to_string(), flight.order, Some(flight.lists))
        }
        Some(_) => {
            return Err(input_error(
                py,
                "plan_or_schedule: expected a mason.Plan, a mason.Schedule or None",
            ))
        }
        None => ("exact".to_string(), exact_order(py, &w, &model)?, None),
    };
    Ok(Setting {
        wall: w,
        model,
        config,
        coord,
        slot,
        planner,
        order,
        lists,
    })
}

/// The exact planner's order, as the CLI flies by default.
fn exact_order(py: Python<'_>, wall: &Wall, model: &CostModel) -> PyResult<Vec<BrickId>> {
    let problem = BuildProblem::new(wall, model.clone()).map_err(bad(py))?;
    let stop = Stop::new();
    let budget = Budget::time(std::time::Duration::from_secs_f64(ORDER_TIME_LIMIT_S))
        .with_stop(Some(stop.clone()));
    let checked = run_detached(
        py,
        &stop,
        || plan_checked(&problem, PlannerSpec::Exact, &budget),
        |_| Ok(()),
    )?
    .map_err(|e| internal(py, e))?;
    checked.outcome.order.ok_or_else(|| {
        crate::error(
            py,
            "NoSolutionError",
            "exact: no complete build order within the budget",
        )
    })
}

/// One flown mission: its metrics and events, as `mason simulate --json` prints them.
#[pyclass(module = "mason", name = "Trace", frozen)]
pub struct PyTrace {
    json: serde_json::Value,
}

impl PyTrace {
    /// The JSON the CLI prints, compact.
    pub(crate) fn json_text(&self) -> String {
        self.json.to_string()
    }
}

#[pymethods]
impl PyTrace {
    /// The run's metrics (`makespan_s`, `bricks_placed`, `reward`, …), a dict.
    #[getter]
    fn metrics<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        to_py(py, &self.json["metrics"])
    }

    /// The events, dicts with `t`, `uav`, `kind` and the kind's fields (bricks by id).
    #[getter]
    fn events<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        to_py(py, &self.json["events"])
    }

    /// The whole run as the JSON `mason simulate --json` prints.
    fn to_json(&self) -> String {
        serde_json::to_string_pretty(&self.json).unwrap_or_default()
    }

    fn __repr__(&self) -> String {
        let m = &self.json["metrics"];
        format!(
            "<mason.Trace {}: {}/{} bricks, makespan {} s, {} events>",
            m["status"].as_str().unwrap_or("?"),
            m["bricks_placed"],
            m["bricks_total"],
            m["makespan_s"],
            self.json["events"].as_array().map_or(0, Vec::len)
        )
    }
}

/// Flies one mission with a team of `uavs` UAVs and checks its trace (`check_trace`).
///
/// `plan_or_schedule` is a `mason.Plan` (a shared build order), a `mason.Schedule` (each UAV
/// flies its own bricks) or None (the exact planner's order). `coord` is `"comm"`,
/// `"windows"` or `"auto"`. `faults` is a dict as the faults TOML file has it (`grasp_fail`,
/// `detect_fail`, `uav_fail` ["U@T", …], `uav_hazard`, `blackout` ["A-B", …], `msg_loss`,
/// `latency`). `model` is a cost-model TOML, `mission` a mission TOML (arena, UAV model,
/// timings), `slot` the windows slot (s).
#[pyfunction]
#[pyo3(signature = (wall, plan_or_schedule = None, uavs = 3, coord = "comm", faults = None, seed = 0, model = None, mission = None, slot = None))]
#[allow(clippy::too_many_arguments)]
fn simulate(
    py: Python<'_>,
    wall: &PyWall,
    plan_or_schedule: Option<Bound<'_, PyAny>>,
    uavs: i64,
    coord: &str,
    faults: Option<Bound<'_, PyAny>>,
    seed: u64,
    model: Option<PathBuf>,
    mission: Option<PathBuf>,
    slot: Option<f64>,
) -> PyResult<PyTrace> {
    let s = setting(
        py,
        wall,
        plan_or_schedule.as_ref(),
        crate::count(py, "uavs", uavs)?,
        coord,
        faults.as_ref(),
        model,
        mission,
        slot,
    )?;
    let (r, trace) = py
        .detach(|| mason_mission::fly_checked(s.input(), s.coord, s.slot, seed))
        .map_err(|e| trace_failure(py, None, e))?;
    Ok(PyTrace {
        json: mason_report::simulate_json(&s.header(seed), &r, &trace),
    })
}

/// A flown mission's failure, as the CLI says it: a flood (durations too short to make
/// progress) is an `InputError`; anything else a simulator bug that `check_trace` caught.
fn trace_failure(py: Python<'_>, seed: Option<u64>, e: mason_mission::TraceError) -> PyErr {
    let run = seed.map_or("mission".to_string(), |s| format!("mission seed {s}"));
    match e {
        mason_mission::TraceError::Flooded(f) => crate::input_error(
            py,
            format!("{run}: {f} (the times of the mission and the model)"),
        ),
        e => internal(py, format!("{run} failed check_trace: {e}")),
    }
}

/// Runs flown per call of `for_each_run` between looks at the stop flag.
const PER_CALL: u64 = 256;

/// Flies seeds `seed .. seed + runs` on Rust threads (the GIL released), checks every trace,
/// and returns the summary dict that `mason simulate --runs N --json` prints. Ctrl-C stops it.
///
/// The arguments are those of `simulate`. With `per_run=True` the dict also has `runs`, a
/// numpy structured array with one row per seed (`seed`, `complete`, `makespan_s` (NaN when
/// incomplete), `bricks_placed`, `reward`, `zone_utilisation`), which `mason.summarise`
/// turns into the same summary: chunks of seeds flown on other machines add up exactly.
#[pyfunction]
#[pyo3(signature = (wall, plan_or_schedule = None, uavs = 3, coord = "comm", faults = None, seed = 0, runs = 100, model = None, mission = None, slot = None, per_run = false))]
#[allow(clippy::too_many_arguments)]
fn monte_carlo<'py>(
    py: Python<'py>,
    wall: &PyWall,
    plan_or_schedule: Option<Bound<'_, PyAny>>,
    uavs: i64,
    coord: &str,
    faults: Option<Bound<'_, PyAny>>,
    seed: u64,
    runs: i64,
    model: Option<PathBuf>,
    mission: Option<PathBuf>,
    slot: Option<f64>,
    per_run: bool,
) -> PyResult<Bound<'py, PyAny>> {
    let runs = crate::count(py, "runs", runs)?;
    if runs == 0 {
        return Err(input_error(py, "runs must be at least 1"));
    }
    if seed.checked_add(runs as u64 - 1).is_none() {
        return Err(input_error(
            py,
            format!(
                "seed {seed}, runs {runs}: the seeds would run past {}",
                u64::MAX
            ),
        ));
    }
    let s = setting(
        py,
        wall,
        plan_or_schedule.as_ref(),
        crate::count(py, "uavs", uavs)?,
        coord,
        faults.as_ref(),
        model,
        mission,
        slot,
    )?;
    let stop = Stop::new();
    let work = || {
        let mut summary = Summariser::new(None);
        let mut figures: Vec<RunFigures> = Vec::new();
        let mut done = 0u64;
        while done < runs as u64 && !stop.raised() {
            let n = PER_CALL.min(runs as u64 - done);
            for_each_run(
                s.input(),
                s.coord,
                s.slot,
                seed + done,
                n as usize,
                &|| {},
                &mut |r| {
                    summary.push(r);
                    if per_run {
                        figures.push(RunFigures::of(r));
                    }
                },
            )?;
            done += n;
        }
        Ok((summary, figures))
    };
    let (summary, figures) = run_detached(py, &stop, work, |_| Ok(()))?
        .map_err(|(s, e): (u64, mason_mission::TraceError)| trace_failure(py, Some(s), e))?;
    let out = to_py(
        py,
        &mason_report::runs_json(&s.header(seed), &summary.summary()),
    )?;
    if per_run {
        out.set_item("runs", figures_array(py, seed, &figures)?)?;
    }
    Ok(out)
}

/// Runs as a numpy structured array (see `monte_carlo`).
fn figures_array<'py>(
    py: Python<'py>,
    first_seed: u64,
    figures: &[RunFigures],
) -> PyResult<Bound<'py, PyAny>> {
    let np = py.import("numpy")?;
    let dtype = vec![
        ("seed", "<u8"),
        ("complete", "?"),
        ("makespan_s", "<f8"),
        ("bricks_placed", "<i8"),
        ("reward", "<f8"),
        ("zone_utilisation", "<f8"),
    ];
    let out = np.call_method1("empty", (figures.len(), dtype))?;
    let seeds: Vec<u64> = (0..figures.len() as u64).map(|k| first_seed + k).collect();
    out.set_item("seed", PyArray1::from_vec(py, seeds))?;
    let col = |f: fn(&RunFigures) -> f64| figures.iter().map(f).collect::<Vec<f64>>();
    let complete: Vec<bool> = figures.iter().map(|f| f.complete).collect();
    out.set_item("complete", PyArray1::from_vec(py, complete))?;
    out.set_item(
        "makespan_s",
        PyArray1::from_vec(py, col(|f| f.makespan_s.unwrap_or(f64::NAN))),
    )?;
    let bricks: Vec<i64> = figures.iter().map(|f| f.bricks_placed as i64).collect();
    out.set_item("bricks_placed", PyArray1::from_vec(py, bricks))?;
    out.set_item("reward", PyArray1::from_vec(py, col(|f| f.reward)))?;
    out.set_item(
        "zone_utilisation",
        PyArray1::from_vec(py, col(|f| f.zone_utilisation)),
    )?;
    Ok(out)
}

/// The summary (`runs`, `completed`, and mean/p5/p95 of makespan, bricks placed, reward and
/// zone utilisation) of per-run rows as `monte_carlo(..., per_run=True)` returns them, taken
/// in the order given (seed order gives `monte_carlo`'s summary exactly).
#[pyfunction]
fn summarise<'py>(py: Python<'py>, runs: &Bound<'py, PyAny>) -> PyResult<Bound<'py, PyAny>> {
    let np = py.import("numpy")?;
    let column = |name: &str, dtype: &str| -> PyResult<Bound<'py, PyAny>> {
        let c = runs
            .get_item(name)
            .map_err(|e| input_error(py, format!("runs: no field {name:?} ({e})")))?;
        np.call_method1("ascontiguousarray", (c, dtype))
    };
    let complete = column("complete", "bool")?;
    let complete: PyReadonlyArray1<'_, bool> = complete.extract()?;
    let makespan = column("makespan_s", "float64")?;
    let makespan: PyReadonlyArray1<'_, f64> = makespan.extract()?;
    let bricks = column("bricks_placed", "int64")?;
    let bricks: PyReadonlyArray1<'_, i64> = bricks.extract()?;
    let reward = column("reward", "float64")?;
    let reward: PyReadonlyArray1<'_, f64> = reward.extract()?;
    let zone = column("zone_utilisation", "float64")?;
    let zone: PyReadonlyArray1<'_, f64> = zone.extract()?;
    let n = complete.len()?;
    if [makespan.len()?, bricks.len()?, reward.len()?, zone.len()?]
        .iter()
        .any(|&l| l != n)
    {
        return Err(input_error(py, "runs: the fields differ in length"));
    }
    let (c, m, b, r, z) = (
        complete.as_slice()?,
        makespan.as_slice()?,
        bricks.as_slice()?,
        reward.as_slice()?,
        zone.as_slice()?,
    );
    let mut s = Summariser::new(None);
    for k in 0..n {
        if b[k] < 0 {
            return Err(input_error(
                py,
                format!("runs: row {k}: bricks_placed {} < 0", b[k]),
            ));
        }
        s.push_figures(&RunFigures {
            complete: c[k],
            makespan_s: (!m[k].is_nan()).then_some(m[k]),
            bricks_placed: b[k] as usize,
            reward: r[k],
            zone_utilisation: z[k],
        });
    }
    let summary = serde_json::to_value(s.summary()).map_err(|e| internal(py, e))?;
    to_py(py, &summary)
}

pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<PyTrace>()?;
    m.add_function(wrap_pyfunction!(simulate, m)?)?;
    m.add_function(wrap_pyfunction!(monte_carlo, m)?)?;
    m.add_function(wrap_pyfunction!(summarise, m)?)?;
    Ok(())
}
