//! What the suites share: their error, checked solves with the suites' budgets, and where the
//! shared benchmark data lives.

use mason_mission::{Coord, MissionConfig, MissionInput, MissionResult};
use mason_order::{plan_checked, Budget, BuildProblem, CheckedPlan, CostModel, PlannerSpec};
use mason_wall::Wall;
use std::path::PathBuf;
use std::time::Duration;

/// Why a suite could not run: bad options or data (the message names them), or a result that
/// failed its validator (a bug).
#[derive(Debug, thiserror::Error)]
pub enum BenchError {
    /// Bad options or missing or bad data.
    #[error("{0}")]
    Input(String),
    /// A planner's, solver's or simulator's result failed its independent check.
    #[error("internal error: {0}")]
    Invalid(String),
}

impl From<mason_io::InputError> for BenchError {
    fn from(e: mason_io::InputError) -> Self {
        BenchError::Input(e.to_string())
    }
}

/// Result of a suite.
pub type BenchResult<T> = Result<T, BenchError>;

/// Bad options or data.
pub fn input_error(message: impl Into<String>) -> BenchError {
    BenchError::Input(message.into())
}

/// The budget of a search limited to `limit` seconds, or unlimited.
pub fn budget(limit: Option<f64>) -> Budget {
    match limit {
        Some(s) => Budget::time(Duration::from_secs_f64(s)),
        None => Budget::unlimited(),
    }
}

/// A planner run and checked by `order::validate_claim`.
pub fn solve(
    problem: &BuildProblem<'_>,
    spec: PlannerSpec,
    limit: Option<f64>,
) -> BenchResult<CheckedPlan> {
    plan_checked(problem, spec, &budget(limit)).map_err(|e| BenchError::Invalid(e.to_string()))
}

/// Checks a mission configuration and computes the windows slot for a wall.
pub fn prepare(wall: &Wall, model: &CostModel, config: &MissionConfig) -> BenchResult<f64> {
    config
        .validate()
        .map_err(|e| input_error(format!("mission: {e}")))?;
    mason_mission::slot_length(wall, model, config).map_err(|e| input_error(format!("--{e}")))
}

/// One mission, its trace checked.
pub fn fly_once(
    input: MissionInput<'_>,
    coord: Coord,
    slot: f64,
    seed: u64,
) -> BenchResult<(MissionResult, Vec<mason_mission::Event>)> {
    mason_mission::fly_checked(input, coord, slot, seed)
        .map_err(|e| BenchError::Invalid(format!("mission trace failed check_trace: {e}")))
}

/// A Monte Carlo batch, every trace checked.
pub fn fly_many(
    input: MissionInput<'_>,
    coord: Coord,
    slot: f64,
    seed: u64,
    runs: usize,
) -> BenchResult<Vec<MissionResult>> {
    mason_mission::run_many(input, coord, slot, seed, runs, &|| {})
        .map_err(|(s, e)| BenchError::Invalid(format!("mission seed {s} failed check_trace: {e}")))
}

/// Where the shared MAPF benchmarks are, if present: `$MASON_BENCHMARKS/mapf`,
/// `../shared/benchmarks/mapf` or `./benchmarks/mapf`.
pub fn benchmarks_dir() -> Option<PathBuf> {
    let candidates = [
        std::env::var_os("MASON_BENCHMARKS").map(PathBuf::from),
        Some(PathBuf::from("../shared/benchmarks")),
        Some(PathBuf::from("benchmarks")),
    ];
    candidates
        .into_iter()
        .flatten()
        .map(|d| d.join("mapf"))
        .find(|d| d.join("maps").is_dir())
}

/// The time limit a compared planner gets: the tree searches are capped, the others not.
pub fn search_limit(spec: PlannerSpec, limit: f64) -> Option<f64> {
    matches!(spec, PlannerSpec::Brute | PlannerSpec::Improved { .. }).then_some(limit)
}
