//! What a planner returns: a status, maybe an order, and statistics; and the search budget.

use mason_wall::stop::Stop;
use mason_wall::BrickId;
use serde::Serialize;
use std::sync::Arc;
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

/// Limits on a search: a deadline, a node cap and a stop flag, and who hears of progress.
/// Passed in, never global.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Budget {
    /// Stop after this instant.
    pub deadline: Option<Instant>,
    /// Stop after expanding this many nodes.
    pub node_limit: Option<u64>,
    /// Stop when this flag is raised (Ctrl-C, a caller's cancel), as at the deadline.
    pub stop: Option<Stop>,
    /// Told of each better result of the anytime searches (team schedules).
    pub on_better: Option<OnBetter>,
}

/// A better result found by an anytime search: its objective value (makespan in seconds,
/// reward, or expected reward), the proven bound, and the schedules decoded so far.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Better {
    /// The objective of the best result so far.
    pub value: f64,
    /// The proven bound on the objective.
    pub bound: f64,
    /// Schedules decoded so far.
    pub decodes: u64,
    /// Seconds since the search started.
    pub elapsed_s: f64,
}

/// A listener for [`Better`] results, called from the searching thread.
#[derive(Clone)]
pub struct OnBetter(pub Arc<dyn Fn(Better) + Send + Sync>);

impl PartialEq for OnBetter {
    fn eq(&self, other: &Self) -> bool {
        Arc::ptr_eq(&self.0, &other.0)
    }
}

impl std::fmt::Debug for OnBetter {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("OnBetter")
    }
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
            ..Budget::default()
        }
    }

    /// The budget of an anytime search (team schedules): with a time limit, search until the
    /// deadline with no node cap; without one, the search's own deterministic default.
    pub fn anytime(limit: Option<Duration>) -> Self {
        match limit {
            Some(l) => Budget {
                node_limit: Some(u64::MAX),
                ..Budget::time(l)
            },
            None => Budget::unlimited(),
        }
    }

    /// The same budget, also stopped by `stop`.
    pub fn with_stop(mut self, stop: Option<Stop>) -> Self {
        self.stop = stop;
        self
    }

    /// Whether the deadline has passed or a stop was asked (the clock is read on each call).
    pub fn out_of_time(&self) -> bool {
        mason_wall::stop::raised(&self.stop) || self.deadline.is_some_and(|d| Instant::now() >= d)
    }

    /// Tells the listener, if any, of a better result.
    pub fn better(&self, b: Better) {
        if let Some(f) = &self.on_better {
            (f.0)(b);
        }
    }

    /// A node cap (deterministic, unlike a deadline).
    pub fn nodes(limit: u64) -> Self {
        Budget {
            deadline: None,
            node_limit: Some(limit),
            ..Budget::default()
        }
    }

    /// True when `nodes` expansions exhaust the budget. The clock is read every 1024 nodes.
    pub fn exhausted(&self, nodes: u64) -> bool {
        if self.node_limit.is_some_and(|cap| nodes >= cap) {
            return true;
        }
        nodes % 1024 == 0 && self.out_of_time()
    }
}
