//! `greedy`: the thesis's greedy planner (Petrić 2019, §3.4).
//!
//! At every step it places the cheapest available brick, ties to the smallest label.
//! O(n log n + e log n) with a lazy priority queue. Not optimal in general (`Feasible`).

use crate::outcome::{Budget, Outcome, Stats, Status};
use crate::problem::BuildProblem;
use mason_wall::BrickId;
use std::cmp::{Ordering, Reverse};
use std::collections::BinaryHeap;
use std::time::Instant;

#[derive(PartialEq)]
struct Entry {
    cost: f64,
    label: u32,
    brick: BrickId,
    neighbours_seen: u32,
}

impl Eq for Entry {}
impl PartialOrd for Entry {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}
impl Ord for Entry {
    fn cmp(&self, other: &Self) -> Ordering {
        self.cost
            .total_cmp(&other.cost)
            .then(self.label.cmp(&other.label))
    }
}

/// Runs greedy. The budget is accepted for a uniform interface; greedy always finishes.
pub fn plan(problem: &BuildProblem<'_>, _budget: &Budget) -> Outcome {
    let start = Instant::now();
    let wall = problem.wall();
    let n = problem.len();
    let mut missing: Vec<u32> = wall.ids().map(|b| wall.supports(b).len() as u32).collect();
    let mut placed_nb = vec![0u32; n];
    let mut placed = vec![false; n];
    let mut heap = BinaryHeap::new();
    let entry = |b: BrickId, k: u32| {
        Reverse(Entry {
            cost: problem.cost(b, k as usize),
            label: wall.brick(b).label,
            brick: b,
            neighbours_seen: k,
        })
    };
    for b in wall.ids().filter(|b| missing[b.index()] == 0) {
        heap.push(entry(b, 0));
    }
    let mut order = Vec::with_capacity(n);
    let mut total = 0.0;
    let mut stats = Stats::default();
    while let Some(Reverse(e)) = heap.pop() {
        let b = e.brick;
        // Stale entries: placed already, or a neighbour was placed since they were pushed.
        if placed[b.index()] || e.neighbours_seen != placed_nb[b.index()] {
            continue;
        }
        stats.nodes += 1;
        placed[b.index()] = true;
        total += e.cost;
        order.push(b);
        for &nb in wall.neighbours(b) {
            placed_nb[nb.index()] += 1;
            if !placed[nb.index()] && missing[nb.index()] == 0 {
                heap.push(entry(nb, placed_nb[nb.index()]));
            }
        }
        for &c in wall.carried(b) {
            missing[c.index()] -= 1;
            if missing[c.index()] == 0 {
                heap.push(entry(c, placed_nb[c.index()]));
            }
        }
    }
    stats.leaves = 1;
    stats.elapsed = start.elapsed();
    let complete = order.len() == n;
    Outcome {
        planner: "greedy".into(),
        status: if complete {
            Status::Feasible
        } else {
            Status::Infeasible
        },
        total_cost: complete.then_some(total),
        order: complete.then_some(order),
        stats,
    }
}
