//! `brute`: the thesis's brute force (Petrić 2019, §3.3).
//!
//! Enumerates every build order (every linear extension of the precedence DAG) depth first,
//! children in label order, and keeps the cheapest. Exact, and exponential: up to n! orders.
//! With a budget it stops early and reports the best order so far as `Timeout`.

use crate::frontier::Frontier;
use crate::outcome::{Budget, Outcome, Status};
use crate::problem::BuildProblem;
use crate::tree_search::search;
use mason_wall::BrickId;

/// Runs the brute force.
pub fn plan(problem: &BuildProblem<'_>, budget: &Budget) -> Outcome {
    let wall = problem.wall();
    let all = move |f: &Frontier<'_, '_>| {
        let mut v: Vec<BrickId> = f.available().to_vec();
        v.sort_by_key(|&b| wall.brick(b).label);
        v
    };
    search("brute".into(), problem, budget, &all, Status::Optimal)
}
