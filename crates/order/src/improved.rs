//! `improved:n,k`: the thesis's improved greedy (Petrić 2019, §3.5).
//!
//! At a node whose lowest available level is ≤ n, only the cheapest child is expanded;
//! otherwise the k cheapest (ties to the smallest label). The restricted tree is searched
//! exhaustively: at most k^(bricks above level n) leaves. Not optimal in general (`Feasible`);
//! with a budget it reports the best order so far as `Timeout`.

use crate::frontier::Frontier;
use crate::outcome::{Budget, Outcome, Status};
use crate::problem::BuildProblem;
use crate::tree_search::search;
use mason_wall::BrickId;

/// Runs improved greedy with parameters `n` (greedy up to this level) and `k` (branching).
pub fn plan(problem: &BuildProblem<'_>, n: u32, k: u32, budget: &Budget) -> Outcome {
    let wall = problem.wall();
    let rule = move |f: &Frontier<'_, '_>| {
        let lowest = f
            .available()
            .iter()
            .map(|&b| wall.brick(b).level)
            .min()
            .unwrap_or(0);
        let take = if lowest <= n { 1 } else { k.max(1) as usize };
        f.ranked()
            .into_iter()
            .take(take)
            .map(|(_, b)| b)
            .collect::<Vec<BrickId>>()
    };
    search(
        format!("improved:{n},{k}"),
        problem,
        budget,
        &rule,
        Status::Feasible,
    )
}
