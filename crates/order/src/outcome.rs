//! What a planner returns: a status, maybe an order, and statistics; and the search budget.

use mason_wall::BrickId;
use serde::Serialize;
use std::time::{Duration, Instant};

/// How a search ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Status {
    /// The order is proven optimal.
    Optimal,
    /// A valid order, not proven optimal.
    Feasible,
    /// The budget ran out; the order, if any, is the best found so far.
    Timeout,
    /// No valid order exists.
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

/// Search statistics.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct Stats {
    /// Wall-clock time spent.
    pub elapsed: Duration,
    /// Search nodes expanded (bricks placed during search).
    pub nodes: u64,
    /// Complete orders reached.
    pub leaves: u64,
}

/// A planner's result.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Outcome {
    /// The planner, as written on the command line (`improved:1,4`).
    pub planner: String,
    /// How the search ended.
    pub status: Status,
    /// The build order, first placed first; `None` only when no complete order was reached.
    pub order: Option<Vec<BrickId>>,
    /// Total cost of `order`.
    pub total_cost: Option<f64>,
    /// Statistics.
    pub stats: Stats,
}

/// Limits on a search: a deadline and/or a node cap. Passed in, never global.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Budget {
    /// Stop after this instant.
    pub deadline: Option<Instant>,
    /// Stop after expanding this many nodes.
    pub node_limit: Option<u64>,
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
        }
    }

    /// A node cap (deterministic, unlike a deadline).
    pub fn nodes(limit: u64) -> Self {
        Budget {
            deadline: None,
            node_limit: Some(limit),
        }
    }

    /// True when `nodes` expansions exhaust the budget. The clock is read every 1024 nodes.
    pub fn exhausted(&self, nodes: u64) -> bool {
        if self.node_limit.is_some_and(|cap| nodes >= cap) {
            return true;
        }
        nodes % 1024 == 0 && self.deadline.is_some_and(|d| Instant::now() >= d)
    }
}
