//! The whole crew pipeline: assign goals, plan each robot's path, resolve collisions.

use crate::assign::{assign, AssignError, AssignMethod};
use crate::astar::astar;
use crate::distance::UNREACHABLE;
use crate::grid::Cell;
use crate::instance::Instance;
use crate::outcome::{Budget, CrewOutcome, CrewStats, Status};
use crate::paper::resolve_by_waiting;
use crate::prm::{PrmConfig, Roadmap};
use crate::rra::GoalDistance;
use crate::st::{space_time_plan, StFailure};
use std::time::Instant;
use thiserror::Error;

/// How single-robot paths are found.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PathMethod {
    /// A* on the grid.
    Astar,
    /// A probabilistic roadmap.
    Prm,
}

impl std::str::FromStr for PathMethod {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        match s {
            "astar" => Ok(PathMethod::Astar),
            "prm" => Ok(PathMethod::Prm),
            _ => Err(format!("unknown path method `{s}` (astar, prm)")),
        }
    }
}

/// How collisions are resolved.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Resolution {
    /// The paper's priority waits.
    Paper,
    /// Prioritized space-time A* with a reservation table.
    St,
}

impl std::str::FromStr for Resolution {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        match s {
            "paper" => Ok(Resolution::Paper),
            "st" => Ok(Resolution::St),
            _ => Err(format!("unknown resolution `{s}` (paper, st)")),
        }
    }
}

/// Everything a crew solve needs besides the instance.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct CrewConfig {
    /// Goal assignment.
    pub assign: AssignMethod,
    /// Single-robot paths.
    pub paths: PathMethod,
    /// Collision resolution.
    pub resolve: Resolution,
    /// Roadmap settings (`prm` only); its seed is the solve's seed.
    pub prm: PrmConfig,
}

impl Default for CrewConfig {
    fn default() -> Self {
        CrewConfig {
            assign: AssignMethod::Hungarian,
            paths: PathMethod::Astar,
            resolve: Resolution::St,
            prm: PrmConfig::default(),
        }
    }
}

/// A configuration that cannot run on an instance.
#[derive(Clone, Debug, PartialEq, Eq, Error)]
pub enum SetupError {
    /// The assignment method does not apply.
    #[error(transparent)]
    Assign(#[from] AssignError),
    /// `st` plans its own paths on the grid.
    #[error("--resolve st searches space-time paths on the grid itself; use --paths astar (prm goes with --resolve paper)")]
    StNeedsGrid,
}

/// Assigns, plans and resolves. The outcome carries a plan exactly when its status is
/// `Optimal` or `Feasible`; otherwise its reason says why not.
pub fn solve(
    inst: &Instance,
    config: &CrewConfig,
    budget: &Budget,
) -> Result<CrewOutcome, SetupError> {
    let started = Instant::now();
    if config.resolve == Resolution::St && config.paths == PathMethod::Prm {
        return Err(SetupError::StNeedsGrid);
    }
    let goal_index = assign(inst, config.assign)?;
    let goals: Vec<Cell> = goal_index.iter().map(|&g| inst.goals[g]).collect();
    let grid = &inst.grid;
    let conn = inst.connectivity;
    let xy = |c: Cell| grid.xy(c);
    let mut stats = CrewStats::default();
    let fail = |status: Status, reason: String, mut stats: CrewStats| {
        stats.elapsed = started.elapsed();
        Ok(CrewOutcome {
            status,
            goals: goals.clone(),
            paths: None,
            reason: Some(reason),
            stats,
        })
    };
    let n = inst.robot_count();
    let result = match config.resolve {
        Resolution::Paper => {
            let roadmap =
                (config.paths == PathMethod::Prm).then(|| Roadmap::build(grid, conn, config.prm));
            let mut single = Vec::with_capacity(n);
            for (r, (&start, &goal)) in inst.robots.iter().zip(&goals).enumerate() {
                if budget.out_of_time() {
                    return fail(
                        Status::Timeout,
                        format!("time ran out planning robot {r}'s path"),
                        stats,
                    );
                }
                let (path, expanded) = match &roadmap {
                    None => {
                        let (p, e) = astar(grid, conn, start, goal);
                        (p.map(|p| p.cells), e)
                    }
                    Some(map) => map.path(grid, conn, start, goal),
                };
                stats.expanded += expanded;
                match path {
                    Some(p) => single.push(p),
                    None => {
                        let why = match &roadmap {
                            None => "no path exists on the grid".to_string(),
                            Some(map) => format!(
                                "the roadmap ({} nodes, {} edges) does not connect them; try more --samples or --neighbours",
                                map.node_count(),
                                map.edge_count()
                            ),
                        };
                        return fail(
                            Status::Infeasible,
                            format!(
                                "robot {r} cannot reach its goal {:?} from {:?}: {why}",
                                xy(goal),
                                xy(start)
                            ),
                            stats,
                        );
                    }
                }
            }
            let order = priority_order(&single.iter().map(|p| p.len() as u64).collect::<Vec<_>>());
            let (resolved, waits) = resolve_by_waiting(grid, &single, &order);
            stats.waits = waits;
            resolved.map_err(|d| {
                let what = if d.blocked_goal {
                    format!(
                        "blocked goal: robot {} rests on its goal {:?}, which robot {} must cross at step {}",
                        d.other,
                        xy(d.cell),
                        d.robot,
                        d.step
                    )
                } else {
                    format!(
                        "deadlock: robot {} cannot wait its way past robot {} at {:?} (step {})",
                        d.robot,
                        d.other,
                        xy(d.cell),
                        d.step
                    )
                };
                (Status::Infeasible, format!("{what}; the paper's priority waits cannot resolve it (try --resolve st)"))
            })
        }
        Resolution::St => {
            let mut to_goal: Vec<GoalDistance> = (0..n)
                .map(|r| GoalDistance::new(grid, conn, goals[r], inst.robots[r]))
                .collect();
            let lengths: Vec<u64> = (0..n)
                .map(|r| to_goal[r].get(grid, inst.robots[r]))
                .map(|d| {
                    if d == UNREACHABLE {
                        u64::MAX
                    } else {
                        u64::from(d)
                    }
                })
                .collect();
            let order = priority_order(&lengths);
            let (planned, expanded) = space_time_plan(
                grid,
                conn,
                &inst.robots,
                &goals,
                &mut to_goal,
                &order,
                budget,
            );
            stats.expanded += expanded;
            planned.map_err(|f| match f {
                StFailure::Unreachable { robot } => (
                    Status::Infeasible,
                    format!(
                        "robot {robot} cannot reach its goal {:?} from {:?}: no path exists on the grid",
                        xy(goals[robot]),
                        xy(inst.robots[robot])
                    ),
                ),
                StFailure::GoalTaken { robot } => (
                    Status::Infeasible,
                    format!("robot {robot}'s goal {:?} is taken by another robot", xy(goals[robot])),
                ),
                StFailure::NoPath { robot, horizon } => (
                    Status::Infeasible,
                    format!(
                        "robot {robot} has no collision-free path to {:?} within {horizon} steps around the robots planned before it (prioritized planning is incomplete)",
                        xy(goals[robot])
                    ),
                ),
                StFailure::Budget { robot } => (
                    Status::Timeout,
                    format!("the search budget ran out while planning robot {robot}"),
                ),
            })
        }
    };
    stats.elapsed = started.elapsed();
    match result {
        Ok(paths) => {
            let status = if n == 1 && config.resolve == Resolution::St {
                Status::Optimal
            } else {
                Status::Feasible
            };
            Ok(CrewOutcome {
                status,
                goals,
                paths: Some(paths),
                reason: None,
                stats,
            })
        }
        Err((status, reason)) => fail(status, reason, stats),
    }
}

/// Robots by path length, longest first; ties to the lower index.
fn priority_order(lengths: &[u64]) -> Vec<usize> {
    let mut order: Vec<usize> = (0..lengths.len()).collect();
    order.sort_by(|&a, &b| lengths[b].cmp(&lengths[a]).then(a.cmp(&b)));
    order
}
