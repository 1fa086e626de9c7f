//! What a crew solve returns: a status, maybe a plan, the reason when there is none, and
//! statistics; and the search budget.

use crate::grid::Cell;
use mason_wall::stop::Stop;
use serde::Serialize;
use std::time::{Duration, Instant};

/// How a solve ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Status {
    /// The plan is proven optimal for its objective.
    Optimal,
    /// A valid plan, not proven optimal.
    Feasible,
    /// The budget ran out before a plan was found.
    Timeout,
    /// The method cannot produce a plan for this instance; the reason says why.
    Infeasible,
}

impl std::fmt::Display for Status {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            Status::Optimal => "optimal",
            Status::Feasible => "feasible",
            Status::Timeout => "timeout",
            Status::Infeasible => "infeasible",
        })
    }
}

/// Limits on a solve: a deadline, a cap on search nodes and a stop flag. Passed in, never
/// global.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Budget {
    /// Stop after this instant.
    pub deadline: Option<Instant>,
    /// Stop after expanding this many search nodes in one robot's search.
    pub node_limit: Option<u64>,
    /// Stop when this flag is raised (Ctrl-C, a caller's cancel), as at the deadline.
    pub stop: Option<Stop>,
}

impl Budget {
    /// No limit.
    pub fn unlimited() -> Self {
        Budget::default()
    }

    /// A time limit from now.
    pub fn time(limit: Duration) -> Self {
        Budget {
            deadline: Instant::now().checked_add(limit),
            node_limit: None,
            stop: None,
        }
    }

    /// The same budget, also stopped by `stop`.
    pub fn with_stop(mut self, stop: Option<Stop>) -> Self {
        self.stop = stop;
        self
    }

    /// Whether the deadline has passed or a stop was asked.
    pub fn out_of_time(&self) -> bool {
        mason_wall::stop::raised(&self.stop) || self.deadline.is_some_and(|d| Instant::now() >= d)
    }
}

/// Timed paths: `paths[i][t]` is robot i's cell at step t; after its last entry a robot stays
/// on its goal.
pub type Paths = Vec<Vec<Cell>>;

/// Solve statistics.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct CrewStats {
    /// Wall-clock time of the whole solve.
    pub elapsed: Duration,
    /// Search nodes expanded (grid cells, roadmap nodes or space-time states).
    pub expanded: u64,
    /// Waits inserted by `paper` resolution.
    pub waits: u64,
    /// Time to the first plan (`lacam`, `joint`); the rest of `elapsed` went to refinement.
    pub first_solution: Option<Duration>,
    /// Time spent on the move graph and the goals' distance tables, from the start of the
    /// solve (`lacam`), when they were finished.
    pub tables: Option<Duration>,
    /// Time spent on the guide paths after the tables (`lacam`), when they were finished.
    pub guide: Option<Duration>,
    /// Sum of costs of the first plan, before refinement (`lacam`).
    pub first_sum_of_costs: Option<u64>,
    /// Configurations created by LaCAM.
    pub configurations: u64,
    /// Refinement rounds run, and how many of them improved the plan.
    pub refine_rounds: u64,
    /// Refinement rounds whose new paths were kept.
    pub improvements: u64,
    /// New LaCAM plans refined after the first one's refinement stalled (`lacam`).
    pub restarts: u64,
    /// Σ of each robot's fewest steps to its assigned goal, when the solver computed it on the
    /// way (`lacam`, `joint`).
    pub lower_bound: Option<u64>,
}

/// A crew solve's result.
#[derive(Clone, Debug, PartialEq)]
pub struct CrewOutcome {
    /// How the solve ended.
    pub status: Status,
    /// The goal cell of each robot, as assigned.
    pub goals: Vec<Cell>,
    /// The plan; present exactly when the status is `Optimal` or `Feasible`.
    pub paths: Option<Paths>,
    /// Why there is no plan.
    pub reason: Option<String>,
    /// Statistics.
    pub stats: CrewStats,
}
