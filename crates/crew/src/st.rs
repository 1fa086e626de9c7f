//! Prioritized planning with space-time A* (Silver 2005, "cooperative A*"): robots are planned
//! one at a time, longest shortest-path first, each by A* over (cell, step) states that avoids
//! the reservation table of the robots before it. Waiting is a move. A robot may stop on its
//! goal only after every reserved visit of that cell, so nobody runs into it later. The
//! heuristic is the true step distance to the goal, from reverse resumable A*
//! ([`crate::rra`]); f is raised to the first step the goal is free for good, and ties go to
//! the deeper state, so a robot that must wait for its goal does not flood the map.
//!
//! Each robot's path is optimal given those above it; the whole is incomplete (a priority
//! order may admit no plan). O(T·V log(T·V)) per robot in the worst case for horizon T.

use crate::distance::UNREACHABLE;
use crate::grid::{Cell, Connectivity, Grid};
use crate::outcome::{Budget, Paths};
use crate::reservation::ReservationTable;
use crate::rra::GoalDistance;
use rustc_hash::FxHashMap;
use std::cmp::Ordering;
use std::collections::BinaryHeap;

/// Why space-time planning stopped without a plan.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum StFailure {
    /// The robot's goal cannot be reached on the grid at all.
    Unreachable {
        /// The robot.
        robot: usize,
    },
    /// Another robot rests for good on this robot's goal.
    GoalTaken {
        /// The robot.
        robot: usize,
    },
    /// No space-time path exists below the horizon, given the robots above.
    NoPath {
        /// The robot.
        robot: usize,
        /// The last step searched.
        horizon: u32,
    },
    /// The node cap or the deadline ran out.
    Budget {
        /// The robot being planned.
        robot: usize,
    },
}

#[derive(PartialEq, Eq)]
struct Node {
    f: u32,
    t: u32,
    cell: u32,
}
impl Ord for Node {
    fn cmp(&self, o: &Self) -> Ordering {
        o.f.cmp(&self.f)
            .then(self.t.cmp(&o.t))
            .then(o.cell.cmp(&self.cell))
    }
}
impl PartialOrd for Node {
    fn partial_cmp(&self, o: &Self) -> Option<Ordering> {
        Some(self.cmp(o))
    }
}

/// Plans every robot in `order` (highest priority first) from `starts[i]` to `goals[i]`.
/// `to_goal[i]` gives step distances towards robot i's goal. Also returns the number of
/// states expanded.
pub fn space_time_plan(
    grid: &Grid,
    conn: Connectivity,
    starts: &[Cell],
    goals: &[Cell],
    to_goal: &mut [GoalDistance],
    order: &[usize],
    budget: &Budget,
) -> (Result<Paths, StFailure>, u64) {
    let mut table = ReservationTable::new();
    let mut paths: Paths = vec![Vec::new(); starts.len()];
    let mut expanded = 0;
    for &r in order {
        let result = plan_one(
            grid,
            conn,
            &table,
            (r, starts[r], goals[r]),
            &mut to_goal[r],
            budget,
            &mut expanded,
        );
        match result {
            Ok(path) => {
                table.reserve(r as u32, &path);
                paths[r] = path;
            }
            Err(e) => return (Err(e), expanded),
        }
    }
    (Ok(paths), expanded)
}

#[allow(clippy::too_many_arguments)]
fn plan_one(
    grid: &Grid,
    conn: Connectivity,
    table: &ReservationTable,
    (robot, start, goal): (usize, Cell, Cell),
    h: &mut GoalDistance,
    budget: &Budget,
    expanded: &mut u64,
) -> Result<Vec<Cell>, StFailure> {
    let h0 = h.get(grid, start);
    if h0 == UNREACHABLE {
        return Err(StFailure::Unreachable { robot });
    }
    let Some(rest_from) = table.free_for_good_from(goal) else {
        return Err(StFailure::GoalTaken { robot });
    };
    let horizon = table.horizon().max(rest_from) + h0 + grid.width() + grid.height() + 1;
    let mut parent: FxHashMap<(u32, u32), u32> = FxHashMap::default();
    let mut open = BinaryHeap::new();
    open.push(Node {
        f: h0.max(rest_from),
        t: 0,
        cell: start.0,
    });
    parent.insert((start.0, 0), u32::MAX);
    let mut local = 0u64;
    while let Some(Node { t, cell, .. }) = open.pop() {
        local += 1;
        *expanded += 1;
        if budget.node_limit.is_some_and(|cap| local > cap)
            || (local % 4096 == 0 && budget.out_of_time())
        {
            return Err(StFailure::Budget { robot });
        }
        if cell == goal.0 && t >= rest_from {
            let mut path = vec![Cell(cell)];
            let (mut c, mut k) = (cell, t);
            while k > 0 {
                c = parent[&(c, k)];
                k -= 1;
                path.push(Cell(c));
            }
            path.reverse();
            return Ok(path);
        }
        if t >= horizon {
            continue;
        }
        let here = Cell(cell);
        let mut push = |next: Cell| {
            if parent.contains_key(&(next.0, t + 1)) {
                return;
            }
            let hn = h.get(grid, next);
            if hn == UNREACHABLE {
                return;
            }
            if table.move_clash(grid, here, next, t).is_some() {
                return;
            }
            parent.insert((next.0, t + 1), cell);
            open.push(Node {
                f: (t + 1 + hn).max(rest_from),
                t: t + 1,
                cell: next.0,
            });
        };
        push(here);
        grid.for_each_move(here, conn, |n, _| push(n));
    }
    Err(StFailure::NoPath { robot, horizon })
}
