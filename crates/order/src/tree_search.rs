//! Depth-first search over build orders, shared by `brute` and `improved`. The planners differ
//! only in which children of a node they expand.

use crate::frontier::Frontier;
use crate::outcome::{Budget, Outcome, Stats, Status};
use crate::problem::BuildProblem;
use mason_wall::BrickId;
use std::time::Instant;

/// Chooses the children to expand at a node, in expansion order.
pub(crate) type ChildRule<'r> = dyn Fn(&Frontier<'_, '_>) -> Vec<BrickId> + 'r;

struct Search<'a, 'p, 'w> {
    frontier: Frontier<'p, 'w>,
    children: &'a ChildRule<'a>,
    budget: &'a Budget,
    path: Vec<BrickId>,
    best: Option<(f64, Vec<BrickId>)>,
    stats: Stats,
    stopped: bool,
}

impl Search<'_, '_, '_> {
    fn run(&mut self, cost: f64, remaining: usize) {
        if remaining == 0 {
            self.stats.leaves += 1;
            if self.best.as_ref().is_none_or(|(c, _)| cost < *c) {
                self.best = Some((cost, self.path.clone()));
            }
            return;
        }
        for b in (self.children)(&self.frontier) {
            self.stats.nodes += 1;
            if self.stopped || self.budget.exhausted(self.stats.nodes) {
                self.stopped = true;
                return;
            }
            let c = self.frontier.place(b);
            self.path.push(b);
            self.run(cost + c, remaining - 1);
            self.path.pop();
            self.frontier.undo(b);
        }
    }
}

/// Searches the tree the rule defines, exhaustively unless the budget runs out. `complete`
/// is the status when the whole tree was searched.
pub(crate) fn search(
    name: String,
    problem: &BuildProblem<'_>,
    budget: &Budget,
    children: &ChildRule<'_>,
    complete: Status,
) -> Outcome {
    let start = Instant::now();
    let mut s = Search {
        frontier: Frontier::new(problem),
        children,
        budget,
        path: Vec::with_capacity(problem.len()),
        best: None,
        stats: Stats::default(),
        stopped: false,
    };
    s.run(0.0, problem.len());
    let mut stats = s.stats;
    stats.elapsed = start.elapsed();
    let (status, order, total_cost) = match (s.best, s.stopped) {
        (Some((c, o)), false) => (complete, Some(o), Some(c)),
        (Some((c, o)), true) => (Status::Timeout, Some(o), Some(c)),
        (None, true) => (Status::Timeout, None, None),
        (None, false) => (Status::Infeasible, None, None),
    };
    Outcome {
        planner: name,
        status,
        order,
        total_cost,
        stats,
    }
}
