//! `mason.crew`: MovingAI instances as numpy arrays, the crew and MAPF solvers
//! (`crew::solve_checked`) and the plan validator (`crew::validate`).
//!
//! Arrays: `grid` is bool (H, W), True where blocked; `starts` and `goals` are int (N, 2) as
//! (x, y) = (column, row), (0, 0) at the top left as in MovingAI; `paths` is int (N, T, 2).

use crate::{bad, input_error, internal, invalid, run_detached};
use mason_crew::limits::{MAX_AGENTS, MAX_CELLS};
use mason_crew::{Budget, Cell, Connectivity, Grid, Instance, PrmConfig, Status, Stop};
use mason_io::crew::{check_size, choices, RawChoices};
use numpy::ndarray::Array3;
use numpy::{IntoPyArray, PyArray2, PyArray3, PyReadonlyArray2};
use pyo3::prelude::*;
use std::path::PathBuf;

/// The largest number of (robot, step) pairs a path array may hold.
const MAX_PATH_ENTRIES: usize = 1 << 28;

/// A numpy grid (bool, H × W, True where blocked) as a [`Grid`].
fn grid_of(py: Python<'_>, grid: &Bound<'_, PyAny>) -> PyResult<Grid> {
    let np = py.import("numpy")?;
    let a = np
        .call_method1("asarray", (grid,))
        .map_err(|e| input_error(py, format!("grid: not an array ({e})")))?;
    let shape: Vec<usize> = a.getattr("shape")?.extract()?;
    if shape.len() != 2 || shape[0] == 0 || shape[1] == 0 {
        return Err(input_error(
            py,
            format!("grid: expected a 2-D (H, W) array, got shape {shape:?}"),
        ));
    }
    if (shape[0] as u64) * (shape[1] as u64) > MAX_CELLS || shape[0] > u32::MAX as usize {
        return Err(input_error(
            py,
            format!(
                "grid: {} × {} cells is more than {MAX_CELLS}",
                shape[1], shape[0]
            ),
        ));
    }
    let a = np.call_method1("ascontiguousarray", (a, "bool"))?;
    let a: PyReadonlyArray2<'_, bool> = a.extract()?;
    let blocked = a.as_slice()?.to_vec();
    Ok(Grid::new(shape[1] as u32, shape[0] as u32, blocked))
}

/// An (N, 2) array of (x, y) as cells of `grid`.
fn cells_of(py: Python<'_>, grid: &Grid, what: &str, xy: &Bound<'_, PyAny>) -> PyResult<Vec<Cell>> {
    let np = py.import("numpy")?;
    let a = np
        .call_method1("asarray", (xy,))
        .map_err(|e| input_error(py, format!("{what}: not an array ({e})")))?;
    let shape: Vec<usize> = a.getattr("shape")?.extract()?;
    if shape.len() != 2 || shape[1] != 2 {
        return Err(input_error(
            py,
            format!("{what}: expected an (N, 2) array of (x, y), got shape {shape:?}"),
        ));
    }
    if shape[0] > MAX_AGENTS {
        return Err(input_error(
            py,
            format!("{what}: {} robots is more than {MAX_AGENTS}", shape[0]),
        ));
    }
    let kind: String = a.getattr("dtype")?.getattr("kind")?.extract()?;
    if !matches!(kind.as_str(), "i" | "u") {
        return Err(input_error(
            py,
            format!("{what}: expected integers, got dtype kind {kind:?}"),
        ));
    }
    let a = np.call_method1("ascontiguousarray", (a, "int64"))?;
    let a: PyReadonlyArray2<'_, i64> = a.extract()?;
    let v = a.as_slice()?;
    (0..shape[0])
        .map(|i| {
            let (x, y) = (v[2 * i], v[2 * i + 1]);
            grid.cell(x, y).ok_or_else(|| {
                input_error(
                    py,
                    format!(
                        "{what}[{i}] = ({x}, {y}) is outside the {} × {} grid",
                        grid.width(),
                        grid.height()
                    ),
                )
            })
        })
        .collect()
}

fn xy_array<'py>(py: Python<'py>, grid: &Grid, cells: &[Cell]) -> Bound<'py, PyArray2<i64>> {
    let mut flat = Vec::with_capacity(2 * cells.len());
    for &c in cells {
        let (x, y) = grid.xy(c);
        flat.extend([i64::from(x), i64::from(y)]);
    }
    numpy::ndarray::Array2::from_shape_vec((cells.len(), 2), flat)
        .expect("2 entries per cell")
        .into_pyarray(py)
}

fn connectivity(py: Python<'_>, c: u32) -> PyResult<Connectivity> {
    c.to_string()
        .parse()
        .map_err(|e| input_error(py, format!("connectivity: {e}")))
}

/// `(grid, starts, goals)` as numpy arrays.
type Instance3<'py> = (
    Bound<'py, PyArray2<bool>>,
    Bound<'py, PyArray2<i64>>,
    Bound<'py, PyArray2<i64>>,
);

/// Reads a MovingAI `.map` and the first `agents` of a `.scen` (None: all): returns
/// `(grid, starts, goals)` — bool (H, W) True where blocked, and int (N, 2) arrays of (x, y).
#[pyfunction]
#[pyo3(signature = (map_path, scen_path, agents = None))]
fn load_movingai<'py>(
    py: Python<'py>,
    map_path: PathBuf,
    scen_path: PathBuf,
    agents: Option<i64>,
) -> PyResult<Instance3<'py>> {
    let agents = agents.map(|a| crate::count(py, "agents", a)).transpose()?;
    let map = map_path.to_string_lossy().into_owned();
    let input = mason_io::CrewInput {
        map: Some(&map),
        scen: Some(&scen_path),
        agents,
        image: None,
    };
    let (inst, _) = py
        .detach(|| mason_io::load_crew(&input, Connectivity::Four))
        .map_err(bad(py))?;
    let g = &inst.grid;
    let blocked: Vec<bool> = (0..g.len() as u32).map(|c| !g.is_free(Cell(c))).collect();
    let grid =
        numpy::ndarray::Array2::from_shape_vec((g.height() as usize, g.width() as usize), blocked)
            .map_err(|e| internal(py, e))?
            .into_pyarray(py);
    Ok((
        grid,
        xy_array(py, g, &inst.robots),
        xy_array(py, g, &inst.goals),
    ))
}

/// A crew plan, checked by `crew::validate`.
#[pyclass(module = "mason.crew", name = "Solution", frozen)]
pub struct PySolution {
    status: Status,
    reason: Option<String>,
    paths: Option<Array3<i64>>,
    goals: Vec<[i64; 2]>,
    sum_of_costs: Option<u64>,
    makespan: Option<u64>,
    lower_bound: Option<u64>,
    elapsed_s: f64,
}

#[pymethods]
impl PySolution {
    /// The paths: int (N, T, 2) of (x, y), robot i at step t; each robot rests on its goal to
    /// the end. None when no plan was found (see `status` and `reason`).
    #[getter]
    fn paths<'py>(&self, py: Python<'py>) -> Option<Bound<'py, PyArray3<i64>>> {
        self.paths.as_ref().map(|p| PyArray3::from_array(py, p))
    }

    /// The goal each robot was given: int (N, 2), as assigned (`assign` other than
    /// `"given"` chooses them).
    #[getter]
    fn goals<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<i64>>> {
        let flat: Vec<i64> = self.goals.iter().flatten().copied().collect();
        Ok(
            numpy::ndarray::Array2::from_shape_vec((self.goals.len(), 2), flat)
                .map_err(|e| internal(py, e))?
                .into_pyarray(py),
        )
    }

    /// Σ over robots of the steps until each last arrives at its goal.
    #[getter]
    fn sum_of_costs(&self) -> Option<u64> {
        self.sum_of_costs
    }

    /// The largest of those.
    #[getter]
    fn makespan(&self) -> Option<u64> {
        self.makespan
    }

    /// Σ of each robot's fewest steps to its goal: a lower bound on the sum of costs (None
    /// when a goal is unreachable).
    #[getter]
    fn lower_bound(&self) -> Option<u64> {
        self.lower_bound
    }

    /// `optimal`, `feasible`, `timeout` or `infeasible`.
    #[getter]
    fn status(&self) -> String {
        self.status.to_string()
    }

    /// Why there is no plan, if there is none.
    #[getter]
    fn reason(&self) -> Option<String> {
        self.reason.clone()
    }

    /// Seconds the solver took.
    #[getter]
    fn elapsed_s(&self) -> f64 {
        self.elapsed_s
    }

    fn __repr__(&self) -> String {
        format!(
            "<mason.crew.Solution {}: {} robots, sum of costs {:?}, makespan {:?}, lower bound {:?}>",
            self.status,
            self.goals.len(),
            self.sum_of_costs,
            self.makespan,
            self.lower_bound
        )
    }
}

/// Assigns robots to goals and plans collision-free paths; the plan is checked by
/// `crew::validate`.
///
/// `assign`: `"given"` (robot i to goal i), `"hungarian"`, `"path"`, `"perm"` or `"joint"`
/// (interchangeable robots: TSWAP plans assignment and paths together; `resolve` is then
/// ignored). `resolve`: `"lacam"` (complete, then refined until `time_limit`), `"st"` or
/// `"paper"`. `paths`: `"astar"` or `"prm"`. `connectivity`: 4 or 8. The solve runs with the
/// GIL released and stops on Ctrl-C.
#[pyfunction]
#[pyo3(signature = (grid, starts, goals, assign = "given", resolve = "lacam", connectivity = 4, time_limit = 1.0, seed = 0, paths = "astar"))]
#[allow(clippy::too_many_arguments)]
fn solve(
    py: Python<'_>,
    grid: &Bound<'_, PyAny>,
    starts: &Bound<'_, PyAny>,
    goals: &Bound<'_, PyAny>,
    assign: &str,
    resolve: &str,
    connectivity: u32,
    time_limit: Option<f64>,
    seed: u64,
    paths: &str,
) -> PyResult<PySolution> {
    let limit = crate::plans::time_limit(py, time_limit)?;
    let joint = assign == "joint";
    let picked = choices(
        RawChoices {
            assign: Some(assign),
            paths,
            resolve: (!joint).then_some(resolve),
            connectivity: &connectivity.to_string(),
            seed,
            refine_rounds: None,
            refine_batch: None,
        },
        PrmConfig {
            seed,
            ..PrmConfig::default()
        },
        true,
    )
    .map_err(bad(py))?;
    let g = grid_of(py, grid)?;
    let robots = cells_of(py, &g, "starts", starts)?;
    let targets = cells_of(py, &g, "goals", goals)?;
    let pairing = (robots.len() == targets.len()).then(|| (0..robots.len()).collect());
    let inst =
        Instance::new(g, picked.connectivity, robots, targets, pairing, "grid").map_err(bad(py))?;
    check_size(&inst, "grid").map_err(bad(py))?;
    let stop = Stop::new();
    let budget = match limit {
        Some(l) => Budget::time(l),
        None => Budget::unlimited(),
    }
    .with_stop(Some(stop.clone()));
    let checked = run_detached(
        py,
        &stop,
        || mason_crew::solve_checked(&inst, &picked.config, &budget),
        |_| Ok(()),
    )?
    .map_err(|e| match e {
        mason_crew::CheckedSolveError::Setup(e) => input_error(py, e.to_string()),
        e => internal(py, e),
    })?;
    // The solver's own sum, else computed (a search per robot) unless the time is up.
    let lower_bound = if checked.outcome.stats.lower_bound.is_some() || !budget.out_of_time() {
        checked.lower_bound(&inst)
    } else {
        None
    };
    let o = checked.outcome;
    let g = &inst.grid;
    let paths = match &o.paths {
        Some(p) => {
            let t = p.iter().map(Vec::len).max().unwrap_or(0);
            if p.len() * t > MAX_PATH_ENTRIES {
                return Err(input_error(
                    py,
                    format!(
                        "{} robots × {t} steps is too long a plan to return",
                        p.len()
                    ),
                ));
            }
            let mut a = Array3::<i64>::zeros((p.len(), t, 2));
            for (i, path) in p.iter().enumerate() {
                for k in 0..t {
                    let (x, y) = g.xy(path[k.min(path.len() - 1)]);
                    a[[i, k, 0]] = i64::from(x);
                    a[[i, k, 1]] = i64::from(y);
                }
            }
            Some(a)
        }
        None => None,
    };
    let goals = o
        .goals
        .iter()
        .map(|&c| {
            let (x, y) = g.xy(c);
            [i64::from(x), i64::from(y)]
        })
        .collect();
    Ok(PySolution {
        status: o.status,
        reason: o.reason.clone(),
        paths,
        goals,
        sum_of_costs: checked.metrics.map(|m| m.sum_of_costs),
        makespan: checked.metrics.map(|m| m.makespan),
        lower_bound,
        elapsed_s: o.stats.elapsed.as_secs_f64(),
    })
}

/// Checks a crew plan: robot i's path `paths[i]` (int (N, T, 2), or a list of (T_i, 2) arrays)
/// from `starts[i]` to `goals[i]`, moving by `connectivity` on free cells with no vertex,
/// swap or corner conflict. Returns `{"sum_of_costs", "makespan"}`; raises
/// `mason.ValidationError` naming the first broken rule.
#[pyfunction]
#[pyo3(signature = (grid, starts, goals, paths, connectivity = 4))]
fn validate<'py>(
    py: Python<'py>,
    grid: &Bound<'py, PyAny>,
    starts: &Bound<'py, PyAny>,
    goals: &Bound<'py, PyAny>,
    paths: &Bound<'py, PyAny>,
    connectivity: u32,
) -> PyResult<Bound<'py, pyo3::types::PyDict>> {
    let conn = self::connectivity(py, connectivity)?;
    let g = grid_of(py, grid)?;
    let s = cells_of(py, &g, "starts", starts)?;
    let t = cells_of(py, &g, "goals", goals)?;
    let mut p: Vec<Vec<Cell>> = Vec::new();
    let mut total = 0usize;
    for (i, path) in paths.try_iter()?.enumerate() {
        let cells = cells_of(py, &g, &format!("paths[{i}]"), &path?)?;
        total += cells.len();
        if total > MAX_PATH_ENTRIES {
            return Err(input_error(py, "paths: too many steps"));
        }
        p.push(cells);
    }
    let m = mason_crew::validate(&g, conn, &s, &t, &p).map_err(|e| invalid(py, e.to_string()))?;
    let d = pyo3::types::PyDict::new(py);
    d.set_item("sum_of_costs", m.sum_of_costs)?;
    d.set_item("makespan", m.makespan)?;
    Ok(d)
}

/// Adds the submodule `crew` (re-exported as `mason.crew`).
pub(crate) fn register(parent: &Bound<'_, PyModule>) -> PyResult<()> {
    let m = PyModule::new(parent.py(), "crew")?;
    m.add_class::<PySolution>()?;
    m.add_function(wrap_pyfunction!(load_movingai, &m)?)?;
    m.add_function(wrap_pyfunction!(solve, &m)?)?;
    m.add_function(wrap_pyfunction!(validate, &m)?)?;
    parent.add_submodule(&m)
}
