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

/// One open node of the depth-first search: its children in expansion order (dropped when the
/// search holds more than [`KEPT_CHILDREN`], and then recomputed on the way back: the rule is
/// deterministic and the frontier is the same again), the next one to try, and the cost of the
/// path that led to it.
struct Level {
    children: Option<Vec<BrickId>>,
    next: usize,
    cost: f64,
}

/// How many children the open nodes keep in all before the deeper ones' parents drop theirs,
/// so that memory stays O(depth) on walls of a million bricks (whose every level has a
/// thousand children) while small walls never recompute.
const KEPT_CHILDREN: usize = 1 << 22;

impl Search<'_, '_, '_> {
    /// Depth-first search with an explicit stack (a wall of a million bricks is a million levels
    /// deep, far beyond the thread's stack), expanding children exactly as a recursive search
    /// would.
    fn run(&mut self, total: usize) {
        if total == 0 {
            self.leaf(0.0);
            return;
        }
        let first = (self.children)(&self.frontier);
        let mut kept = first.len();
        let mut stack = vec![Level {
            children: Some(first),
            next: 0,
            cost: 0.0,
        }];
        while let Some(top) = stack.last_mut() {
            if top.children.is_none() {
                let again = (self.children)(&self.frontier);
                kept += again.len();
                top.children = Some(again);
            }
            let children = top.children.as_deref().unwrap_or_default();
            let Some(&b) = children.get(top.next) else {
                kept -= children.len();
                stack.pop();
                if let Some(b) = self.path.pop() {
                    self.frontier.undo(b);
                }
                continue;
            };
            top.next += 1;
            let cost = top.cost;
            self.stats.nodes += 1;
            if self.stopped || self.budget.exhausted(self.stats.nodes) {
                self.stopped = true;
                return;
            }
            let c = self.frontier.place(b);
            self.path.push(b);
            if self.path.len() == total {
                self.leaf(cost + c);
                self.path.pop();
                self.frontier.undo(b);
                continue;
            }
            if kept > KEPT_CHILDREN {
                if let Some(dropped) = top.children.take() {
                    kept -= dropped.len();
                }
            }
            let below = (self.children)(&self.frontier);
            kept += below.len();
            stack.push(Level {
                children: Some(below),
                next: 0,
                cost: cost + c,
            });
        }
    }

    fn leaf(&mut self, cost: f64) {
        self.stats.leaves += 1;
        if self.best.as_ref().is_none_or(|(c, _)| cost < *c) {
            self.best = Some((cost, self.path.clone()));
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
    s.run(problem.len());
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

#[cfg(test)]
mod tests {
    use crate::{Budget, BuildProblem, CostModel, PlannerSpec, Status};

    /// Issue #15: a wall far deeper than the thread's stack (the recursive search overflowed
    /// it and aborted), with a node budget so that the test is deterministic.
    #[test]
    fn brute_on_a_100k_brick_wall_does_not_overflow_the_stack() {
        use mason_wall::{Brick, BrickType, Footprint, Origin, Wall};
        // A column of 100 000 bricks: 100 000 levels deep, one choice per level.
        let bricks = (1..=100_000u32)
            .map(|level| Brick {
                label: 1000 * level + 1,
                kind: BrickType::Red,
                level,
                segment: 1,
                footprint: Footprint {
                    x0: 0.0,
                    x1: 0.3,
                    y0: 0.0,
                    y1: 0.2,
                },
                origin: Origin::None,
            })
            .collect();
        let wall = Wall::from_bricks("column", bricks).unwrap();
        let problem = BuildProblem::new(&wall, CostModel::default()).unwrap();
        let out = PlannerSpec::Brute.plan(&problem, &Budget::nodes(150_000));
        assert_eq!(out.status, Status::Optimal);
        let order = out.order.expect("the only order");
        crate::validate(&wall, problem.model(), &order).unwrap();
    }
}
