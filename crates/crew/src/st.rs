//! Prioritized planning with space-time A* (Silver 2005, "cooperative A*"): robots are planned
//! one at a time, longest shortest-path first, each by space-time A* ([`crate::spacetime`])
//! over (cell, step) states that avoids the reservation table of the robots before it. Waiting
//! is a move. A robot may stop on its goal only after every reserved visit of that cell, so
//! nobody runs into it later. The heuristic is the true step distance to the goal, from
//! reverse resumable A* ([`crate::rra`]); f is raised to the first step the goal is free for
//! good, and ties go to the deeper state, so a robot that must wait for its goal does not
//! flood the map.
//!
//! Each robot's path is optimal given those above it; the whole is incomplete (a priority
//! order may admit no plan). O(T·V log(T·V)) per robot in the worst case for horizon T.

use crate::distance::UNREACHABLE;
use crate::grid::{Cell, Connectivity, Grid};
use crate::moves::MoveGraph;
use crate::outcome::{Budget, Paths};
use crate::reservation::ReservationTable;
use crate::rra::GoalDistance;
use crate::spacetime::{Limits, Open, Query, Rules, Search, Stop};
use std::cmp::Reverse;

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

/// The order of open states: least f first, then the deepest, then the lowest cell (then the
/// first generated, which only tells copies of one state apart).
type Rank = (Reverse<u32>, u32, Reverse<u32>, Reverse<u32>);

/// The world as robots planned so far leave it to the next: their reservations, and the
/// step distances to the next robot's goal.
struct Reserved<'a> {
    grid: &'a Grid,
    table: &'a ReservationTable,
    to_goal: &'a mut GoalDistance,
}

impl Rules for Reserved<'_> {
    type Rank = Rank;
    const UNIT_STEPS: bool = true;

    #[inline]
    fn rank(s: Open) -> Rank {
        (Reverse(s.f), s.t, Reverse(s.cell), Reverse(s.id))
    }

    #[inline]
    fn id(r: &Rank) -> u32 {
        r.3 .0
    }

    #[inline]
    fn distance(&mut self, cell: u32) -> u32 {
        self.to_goal.get(self.grid, Cell(cell))
    }

    #[inline]
    fn step(&self, from: u32, to: u32, t: u32) -> Option<u32> {
        let clash = self.table.move_clash(self.grid, Cell(from), Cell(to), t);
        clash.is_none().then_some(1)
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
    let graph = MoveGraph::new(grid, conn);
    let mut search = Search::new();
    let mut table = ReservationTable::new();
    let mut paths: Paths = vec![Vec::new(); starts.len()];
    let mut expanded = 0;
    for &r in order {
        let mut world = Reserved {
            grid,
            table: &table,
            to_goal: &mut to_goal[r],
        };
        let result = plan_one(
            (&graph, &mut search),
            &mut world,
            (r, starts[r], goals[r]),
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

/// Plans `robot` from `start` to `goal` around the robots in `world`.
fn plan_one(
    (graph, search): (&MoveGraph, &mut Search<Rank>),
    world: &mut Reserved,
    (robot, start, goal): (usize, Cell, Cell),
    budget: &Budget,
    expanded: &mut u64,
) -> Result<Vec<Cell>, StFailure> {
    let h0 = world.distance(start.0);
    if h0 == UNREACHABLE {
        return Err(StFailure::Unreachable { robot });
    }
    let Some(rest_from) = world.table.free_for_good_from(goal) else {
        return Err(StFailure::GoalTaken { robot });
    };
    let grid = world.grid;
    let horizon = world.table.horizon().max(rest_from) + h0 + grid.width() + grid.height() + 1;
    let query = Query {
        start: start.0,
        goal: goal.0,
        rest_from,
        limits: Limits {
            last_step: horizon,
            node_limit: budget.node_limit.unwrap_or(u64::MAX),
            deadline: budget.deadline,
            ..Limits::default()
        },
    };
    match search.run(graph, world, &query, expanded) {
        Ok(path) => Ok(path.into_iter().map(Cell).collect()),
        Err(Stop::Exhausted) => Err(StFailure::NoPath { robot, horizon }),
        Err(Stop::Budget) => Err(StFailure::Budget { robot }),
    }
}
