//! `crew::validate`: checks a multi-robot plan knowing nothing of the solvers (DESIGN §6).
//!
//! Every path starts on its robot's start and ends on its goal; every step is a wait or a legal
//! move on free cells; and no two robots ever share a cell, swap along an edge, or cross
//! diagonals in one 2×2 square, counting the time robots rest on their goals afterwards.

use crate::grid::{Cell, Connectivity, Grid};
use mason_wall::violations::Violations;
use rustc_hash::FxHashMap;
use std::ops::ControlFlow;
use thiserror::Error;

/// What is wrong with a plan. Robots are 0-based; steps count from 0.
#[derive(Clone, Debug, PartialEq, Eq, Error)]
pub enum PlanError {
    /// Not one path per robot.
    #[error("{paths} paths for {robots} robots")]
    PathCount {
        /// Paths given.
        paths: usize,
        /// Robots.
        robots: usize,
    },
    /// An empty path.
    #[error("robot {robot} has an empty path")]
    EmptyPath {
        /// The robot.
        robot: usize,
    },
    /// A path that does not begin on the robot's start.
    #[error("robot {robot} starts at {found:?}, not at its start {expected:?}")]
    WrongStart {
        /// The robot.
        robot: usize,
        /// (x, y) found.
        found: (u32, u32),
        /// (x, y) expected.
        expected: (u32, u32),
    },
    /// A path that does not end on the robot's goal.
    #[error("robot {robot} ends at {found:?}, not at its goal {expected:?}")]
    WrongGoal {
        /// The robot.
        robot: usize,
        /// (x, y) found.
        found: (u32, u32),
        /// (x, y) expected.
        expected: (u32, u32),
    },
    /// A path through an obstacle or off the grid.
    #[error("robot {robot} is on a blocked cell at step {step}")]
    Blocked {
        /// The robot.
        robot: usize,
        /// The step.
        step: usize,
    },
    /// A step that is neither a wait nor a legal move.
    #[error("robot {robot} makes an illegal move {from:?} → {to:?} at step {step}")]
    IllegalMove {
        /// The robot.
        robot: usize,
        /// The step the move starts at.
        step: usize,
        /// (x, y) before.
        from: (u32, u32),
        /// (x, y) after.
        to: (u32, u32),
    },
    /// Two robots on one cell.
    #[error("robots {a} and {b} are both on {cell:?} at step {step}")]
    Vertex {
        /// One robot.
        a: usize,
        /// The other.
        b: usize,
        /// (x, y).
        cell: (u32, u32),
        /// The step.
        step: usize,
    },
    /// Two robots exchanging cells.
    #[error("robots {a} and {b} swap cells between steps {step} and {}", step + 1)]
    Swap {
        /// One robot.
        a: usize,
        /// The other.
        b: usize,
        /// The step the moves start at.
        step: usize,
    },
    /// A stated sum of costs or makespan that the plan does not give.
    #[error("the plan states {what} {claimed} but gives {actual}")]
    Claim {
        /// `sum of costs` or `makespan`.
        what: &'static str,
        /// Stated.
        claimed: u64,
        /// Recomputed.
        actual: u64,
    },
    /// Two robots crossing diagonals of one 2×2 square.
    #[error("robots {a} and {b} cross diagonals between steps {step} and {}", step + 1)]
    Crossing {
        /// One robot.
        a: usize,
        /// The other.
        b: usize,
        /// The step the moves start at.
        step: usize,
    },
}

/// Sum of costs and makespan of a valid plan.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct PlanMetrics {
    /// Σ over robots of the steps until the robot last arrives on its goal.
    pub sum_of_costs: u64,
    /// The largest of those.
    pub makespan: u64,
}

/// Steps until a path last arrives at its final cell.
pub fn arrival(path: &[Cell]) -> usize {
    let goal = path[path.len() - 1];
    path.iter().rposition(|&c| c != goal).map_or(0, |i| i + 1)
}

/// Checks `paths` (robot i from `starts[i]` to `goals[i]`) and returns its metrics; stops at
/// the first broken rule ([`plan_violations`] lists every one).
pub fn validate(
    grid: &Grid,
    conn: Connectivity,
    starts: &[Cell],
    goals: &[Cell],
    paths: &[Vec<Cell>],
) -> Result<PlanMetrics, PlanError> {
    let mut found = Violations::first();
    match walk(grid, conn, starts, goals, paths, &mut found) {
        ControlFlow::Continue(()) => found.into_result(metrics(paths)),
        ControlFlow::Break(()) => Err(found.into_vec().remove(0)),
    }
}

/// Every rule of [`validate`] that `paths` break: each robot's own rules (start, goal, cells,
/// moves) robot by robot, then the conflicts step by step. A wrong path count stops the check;
/// so does a path that is empty or leaves the grid, before the conflicts.
pub fn plan_violations(
    grid: &Grid,
    conn: Connectivity,
    starts: &[Cell],
    goals: &[Cell],
    paths: &[Vec<Cell>],
) -> Vec<PlanError> {
    let mut found = Violations::every();
    let _ = walk(grid, conn, starts, goals, paths, &mut found);
    found.into_vec()
}

/// The stated figures that `metrics` (recomputed by [`validate`]) does not bear out.
pub fn claim_violations(
    metrics: &PlanMetrics,
    sum_of_costs: Option<u64>,
    makespan: Option<u64>,
) -> Vec<PlanError> {
    let stated = [
        ("sum of costs", sum_of_costs, metrics.sum_of_costs),
        ("makespan", makespan, metrics.makespan),
    ];
    stated
        .into_iter()
        .filter_map(|(what, claimed, actual)| {
            let claimed = claimed?;
            (claimed != actual).then_some(PlanError::Claim {
                what,
                claimed,
                actual,
            })
        })
        .collect()
}

fn metrics(paths: &[Vec<Cell>]) -> PlanMetrics {
    let arrivals: Vec<u64> = paths.iter().map(|p| arrival(p) as u64).collect();
    PlanMetrics {
        sum_of_costs: arrivals.iter().sum(),
        makespan: arrivals.iter().copied().max().unwrap_or(0),
    }
}

fn walk(
    grid: &Grid,
    conn: Connectivity,
    starts: &[Cell],
    goals: &[Cell],
    paths: &[Vec<Cell>],
    found: &mut Violations<PlanError>,
) -> ControlFlow<()> {
    if paths.len() != starts.len() || goals.len() != starts.len() {
        return found.report(PlanError::PathCount {
            paths: paths.len(),
            robots: starts.len(),
        });
    }
    let on_grid = |c: Cell| (c.0 as usize) < grid.len();
    // Cells off the grid are shown as they are; they have no (x, y).
    let xy = |c: Cell| {
        if on_grid(c) {
            grid.xy(c)
        } else {
            (c.0, u32::MAX)
        }
    };
    let mut well_formed = true;
    for (r, path) in paths.iter().enumerate() {
        let (Some(&first), Some(&last)) = (path.first(), path.last()) else {
            found.report(PlanError::EmptyPath { robot: r })?;
            well_formed = false;
            continue;
        };
        if first != starts[r] {
            found.report(PlanError::WrongStart {
                robot: r,
                found: xy(first),
                expected: xy(starts[r]),
            })?;
        }
        if last != goals[r] {
            found.report(PlanError::WrongGoal {
                robot: r,
                found: xy(last),
                expected: xy(goals[r]),
            })?;
        }
        for (t, &c) in path.iter().enumerate() {
            if !on_grid(c) || !grid.is_free(c) {
                found.report(PlanError::Blocked { robot: r, step: t })?;
                well_formed &= on_grid(c);
            }
        }
        for (t, w) in path.windows(2).enumerate() {
            if w[0] != w[1] && on_grid(w[0]) && on_grid(w[1]) && !grid.is_move(w[0], w[1], conn) {
                found.report(PlanError::IllegalMove {
                    robot: r,
                    step: t,
                    from: xy(w[0]),
                    to: xy(w[1]),
                })?;
            }
        }
    }
    if !well_formed {
        return ControlFlow::Continue(());
    }
    conflicts(grid, paths, found)
}

fn conflicts(
    grid: &Grid,
    paths: &[Vec<Cell>],
    found: &mut Violations<PlanError>,
) -> ControlFlow<()> {
    let xy = |c: Cell| grid.xy(c);
    let end = paths.iter().map(Vec::len).max().unwrap_or(1);
    let at = |r: usize, t: usize| paths[r][t.min(paths[r].len() - 1)];
    let mut cells: FxHashMap<Cell, usize> = FxHashMap::default();
    let mut moves: FxHashMap<(Cell, Cell), usize> = FxHashMap::default();
    for t in 0..end {
        cells.clear();
        for r in 0..paths.len() {
            if let Some(&b) = cells.get(&at(r, t)) {
                found.report(PlanError::Vertex {
                    a: b,
                    b: r,
                    cell: xy(at(r, t)),
                    step: t,
                })?;
            } else {
                cells.insert(at(r, t), r);
            }
        }
        // At the last step every robot rests (at() holds it on its last cell): no moves.
        moves.clear();
        for r in 0..paths.len() {
            let (a, b) = (at(r, t), at(r, t + 1));
            if a != b {
                moves.insert((a, b), r);
            }
        }
        for r in 0..paths.len() {
            let (a, b) = (at(r, t), at(r, t + 1));
            if a == b {
                continue;
            }
            if let Some(&o) = moves.get(&(b, a)) {
                // Each pair once, from its lower robot (the first to see it).
                if r < o {
                    found.report(PlanError::Swap {
                        a: o.min(r),
                        b: o.max(r),
                        step: t,
                    })?;
                }
            }
            let ((ax, ay), (bx, by)) = (xy(a), xy(b));
            if ax != bx && ay != by {
                let c = grid.cell(bx as i64, ay as i64).expect("inside");
                let d = grid.cell(ax as i64, by as i64).expect("inside");
                if let Some(&o) = moves.get(&(c, d)).or_else(|| moves.get(&(d, c))) {
                    if r < o {
                        found.report(PlanError::Crossing {
                            a: o.min(r),
                            b: o.max(r),
                            step: t,
                        })?;
                    }
                }
            }
        }
    }
    ControlFlow::Continue(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cells(g: &Grid, xy: &[(i64, i64)]) -> Vec<Cell> {
        xy.iter().map(|&(x, y)| g.cell(x, y).unwrap()).collect()
    }

    /// A 6×4 room with one obstacle at (2,1): robot 0 goes along the top row from (0,0) to
    /// (4,0); robot 1 goes down from (5,0) to (5,3) and waits there; robot 2 rests on (0,3).
    struct Plan {
        grid: Grid,
        starts: Vec<Cell>,
        goals: Vec<Cell>,
        paths: Vec<Vec<Cell>>,
    }

    fn base() -> Plan {
        let mut grid = Grid::open(6, 4);
        grid.set_blocked(grid.cell(2, 1).unwrap(), true);
        let paths = vec![
            cells(&grid, &[(0, 0), (1, 0), (2, 0), (3, 0), (4, 0)]),
            cells(&grid, &[(5, 0), (5, 1), (5, 2), (5, 3)]),
            cells(&grid, &[(0, 3)]),
        ];
        Plan {
            starts: paths.iter().map(|p| p[0]).collect(),
            goals: paths.iter().map(|p| p[p.len() - 1]).collect(),
            grid,
            paths,
        }
    }

    /// The rules `plan` breaks (8-connected), checked both ways.
    fn broken(plan: &Plan) -> Vec<String> {
        let e8 = Connectivity::Eight;
        let (g, s, goals, p) = (&plan.grid, &plan.starts, &plan.goals, &plan.paths);
        let every = plan_violations(g, e8, s, goals, p);
        let first = validate(g, e8, s, goals, p);
        assert_eq!(first.err().as_ref(), every.first(), "first and all agree");
        every.iter().map(mason_wall::violations::rule).collect()
    }

    #[test]
    fn one_broken_plan_per_rule_reports_exactly_that_rule() {
        let ok = base();
        assert!(broken(&ok).is_empty());
        let m = validate(
            &ok.grid,
            Connectivity::Eight,
            &ok.starts,
            &ok.goals,
            &ok.paths,
        );
        assert_eq!(
            m,
            Ok(PlanMetrics {
                sum_of_costs: 4 + 3,
                makespan: 4
            })
        );
        let g = &ok.grid;
        let at = |x, y| g.cell(x, y).unwrap();
        type Edit<'a> = Box<dyn Fn(&mut Plan) + 'a>;
        let cases: Vec<(&str, Edit<'_>, &str)> = vec![
            (
                "one path too few",
                Box::new(|p: &mut Plan| {
                    p.paths.pop();
                }),
                "PathCount",
            ),
            (
                "one goal too few",
                Box::new(|p: &mut Plan| {
                    p.goals.pop();
                }),
                "PathCount",
            ),
            (
                "robot 2 has no path",
                Box::new(|p: &mut Plan| p.paths[2].clear()),
                "EmptyPath",
            ),
            (
                "robot 2 should start on (1,3)",
                Box::new(move |p: &mut Plan| p.starts[2] = at(1, 3)),
                "WrongStart",
            ),
            (
                "robot 1 should end on (4,3)",
                Box::new(move |p: &mut Plan| p.goals[1] = at(4, 3)),
                "WrongGoal",
            ),
            (
                "robot 2 stands on the obstacle",
                Box::new(move |p: &mut Plan| {
                    p.paths[2] = vec![at(2, 1)];
                    p.starts[2] = at(2, 1);
                    p.goals[2] = at(2, 1);
                }),
                "Blocked",
            ),
            (
                "robot 2 stands off the grid",
                Box::new(|p: &mut Plan| {
                    p.paths[2] = vec![Cell(1000)];
                    p.starts[2] = Cell(1000);
                    p.goals[2] = Cell(1000);
                }),
                "Blocked",
            ),
            (
                "robot 2 stands just past the last cell",
                Box::new(|p: &mut Plan| {
                    let past = Cell(p.grid.len() as u32);
                    p.paths[2] = vec![past];
                    p.starts[2] = past;
                    p.goals[2] = past;
                }),
                "Blocked",
            ),
            (
                "robot 0 jumps from (1,0) to (3,0)",
                Box::new(move |p: &mut Plan| {
                    p.paths[0].remove(2);
                }),
                "IllegalMove",
            ),
            (
                "robot 0 cuts the obstacle's corner, (1,2) to (2,1)'s diagonal neighbour",
                Box::new(move |p: &mut Plan| {
                    p.paths[2] = vec![at(1, 2), at(2, 1 + 1), at(3, 1)];
                    p.starts[2] = at(1, 2);
                    p.goals[2] = at(3, 1);
                }),
                "IllegalMove",
            ),
            (
                "robot 2 rests on (3,0), on robot 0's way",
                Box::new(move |p: &mut Plan| {
                    p.paths[2] = vec![at(3, 0)];
                    p.starts[2] = at(3, 0);
                    p.goals[2] = at(3, 0);
                }),
                "Vertex",
            ),
            (
                "robot 2 and robot 0 exchange (0,1) and (0,0)",
                Box::new(move |p: &mut Plan| {
                    p.paths[2] = vec![at(0, 1), at(0, 0)];
                    p.starts[2] = at(0, 1);
                    p.goals[2] = at(0, 0);
                    p.paths[0] = vec![at(0, 0), at(0, 1), at(1, 2), at(2, 3)];
                    p.goals[0] = at(2, 3);
                }),
                "Swap",
            ),
            (
                "robot 2 crosses robot 0's diagonal",
                Box::new(move |p: &mut Plan| {
                    p.paths[2] = vec![at(1, 0), at(0, 1)];
                    p.starts[2] = at(1, 0);
                    p.goals[2] = at(0, 1);
                    p.paths[0] = vec![at(0, 0), at(1, 1), at(1, 2)];
                    p.goals[0] = at(1, 2);
                }),
                "Crossing",
            ),
        ];
        for (what, edit, want) in cases {
            let mut plan = base();
            edit(&mut plan);
            assert_eq!(broken(&plan), [want], "{what}");
        }
    }

    #[test]
    fn robots_off_the_grid_are_not_checked_for_conflicts() {
        // Two robots on one cell off the grid: two blocked cells, no conflict to check.
        let mut plan = base();
        let off = Cell(1000);
        for r in [1, 2] {
            plan.paths[r] = vec![off];
            plan.starts[r] = off;
            plan.goals[r] = off;
        }
        assert_eq!(broken(&plan), ["Blocked", "Blocked"]);
    }

    #[test]
    fn the_first_conflict_is_the_lowest_robots_and_each_pair_is_reported_once() {
        // In one step robots 0 and 3 swap, and so do robots 1 and 2.
        let g = Grid::open(6, 3);
        let paths = vec![
            cells(&g, &[(0, 0), (1, 0)]),
            cells(&g, &[(3, 0), (4, 0)]),
            cells(&g, &[(4, 0), (3, 0)]),
            cells(&g, &[(1, 0), (0, 0)]),
        ];
        let starts: Vec<Cell> = paths.iter().map(|p| p[0]).collect();
        let goals: Vec<Cell> = paths.iter().map(|p| p[1]).collect();
        let e8 = Connectivity::Eight;
        let first = validate(&g, e8, &starts, &goals, &paths);
        assert_eq!(
            first,
            Err(PlanError::Swap {
                a: 0,
                b: 3,
                step: 0
            })
        );
        let all = plan_violations(&g, e8, &starts, &goals, &paths);
        assert_eq!(
            all,
            [
                PlanError::Swap {
                    a: 0,
                    b: 3,
                    step: 0
                },
                PlanError::Swap {
                    a: 1,
                    b: 2,
                    step: 0
                }
            ]
        );
        // Two pairs crossing diagonals: 0 with 3 in the left square, 1 with 2 in the right.
        let paths = vec![
            cells(&g, &[(0, 0), (1, 1)]),
            cells(&g, &[(3, 0), (4, 1)]),
            cells(&g, &[(4, 0), (3, 1)]),
            cells(&g, &[(1, 0), (0, 1)]),
        ];
        let starts: Vec<Cell> = paths.iter().map(|p| p[0]).collect();
        let goals: Vec<Cell> = paths.iter().map(|p| p[1]).collect();
        let first = validate(&g, e8, &starts, &goals, &paths);
        assert_eq!(
            first,
            Err(PlanError::Crossing {
                a: 0,
                b: 3,
                step: 0
            })
        );
        let all = plan_violations(&g, e8, &starts, &goals, &paths);
        assert_eq!(
            all,
            [
                PlanError::Crossing {
                    a: 0,
                    b: 3,
                    step: 0
                },
                PlanError::Crossing {
                    a: 1,
                    b: 2,
                    step: 0
                }
            ]
        );
        // Three robots on one cell: the first there is named with each of the others.
        let paths = vec![
            cells(&g, &[(0, 0), (1, 0)]),
            cells(&g, &[(2, 0), (1, 0)]),
            cells(&g, &[(1, 1), (1, 0)]),
        ];
        let starts: Vec<Cell> = paths.iter().map(|p| p[0]).collect();
        let goals: Vec<Cell> = paths.iter().map(|p| p[1]).collect();
        let all = plan_violations(&g, e8, &starts, &goals, &paths);
        let cell = (1, 0);
        assert_eq!(
            all,
            [
                PlanError::Vertex {
                    a: 0,
                    b: 1,
                    cell,
                    step: 1
                },
                PlanError::Vertex {
                    a: 0,
                    b: 2,
                    cell,
                    step: 1
                }
            ]
        );
    }

    #[test]
    fn arrival_counts_the_steps_until_the_last_arrival() {
        let g = Grid::open(4, 1);
        let at = |x| g.cell(x, 0).unwrap();
        assert_eq!(arrival(&[at(0)]), 0);
        assert_eq!(arrival(&[at(0), at(1), at(1)]), 1);
        // Leaving the goal and coming back counts until the return.
        assert_eq!(arrival(&[at(1), at(0), at(1), at(1)]), 2);
    }

    #[test]
    fn stated_figures_are_checked_against_the_recomputed_ones() {
        let ok = base();
        let m = validate(
            &ok.grid,
            Connectivity::Eight,
            &ok.starts,
            &ok.goals,
            &ok.paths,
        )
        .unwrap();
        assert!(claim_violations(&m, Some(7), Some(4)).is_empty());
        assert!(claim_violations(&m, None, None).is_empty());
        assert_eq!(
            claim_violations(&m, Some(6), Some(5)),
            [
                PlanError::Claim {
                    what: "sum of costs",
                    claimed: 6,
                    actual: 7
                },
                PlanError::Claim {
                    what: "makespan",
                    claimed: 5,
                    actual: 4
                }
            ]
        );
    }

    #[test]
    fn plans_from_every_solver_pass() {
        use crate::{solve, AssignMethod, Budget, CrewConfig, Instance, PathMethod, Resolution};
        let mut grid = Grid::open(9, 7);
        for y in 1..6 {
            grid.set_blocked(grid.cell(4, y).unwrap(), true);
        }
        let robots = cells(&grid, &[(0, 0), (8, 0), (0, 6), (8, 6), (2, 3)]);
        let goals = cells(&grid, &[(8, 6), (0, 6), (8, 0), (0, 0), (6, 3)]);
        let combos = [
            (AssignMethod::Given, PathMethod::Astar, Resolution::Paper),
            (AssignMethod::Perm, PathMethod::Astar, Resolution::St),
            (AssignMethod::Hungarian, PathMethod::Prm, Resolution::Paper),
            (AssignMethod::Path, PathMethod::Astar, Resolution::St),
            (AssignMethod::Given, PathMethod::Astar, Resolution::Lacam),
            (AssignMethod::Joint, PathMethod::Astar, Resolution::St),
        ];
        let mut planned = 0;
        for conn in [Connectivity::Four, Connectivity::Eight] {
            let pairing = Some((0..robots.len()).collect());
            let inst = Instance::new(
                grid.clone(),
                conn,
                robots.clone(),
                goals.clone(),
                pairing,
                "room",
            )
            .unwrap();
            for (assign, paths, resolve) in combos {
                let mut config = CrewConfig {
                    assign,
                    paths,
                    resolve,
                    ..CrewConfig::default()
                };
                config.refine.rounds = Some(20);
                let out = solve(&inst, &config, &Budget::unlimited()).unwrap();
                let what = format!("{assign:?} {paths:?} {resolve:?} {conn:?}");
                // The paper's priority waits may meet a deadlock, and say so.
                let Some(plan) = out.paths else {
                    assert_eq!(resolve, Resolution::Paper, "{what}: {:?}", out.reason);
                    continue;
                };
                planned += 1;
                let found = plan_violations(&inst.grid, conn, &inst.robots, &out.goals, &plan);
                assert!(found.is_empty(), "{what}: {found:?}");
            }
        }
        assert!(planned >= 2 * combos.len() - 2, "{planned} plans");
    }

    #[test]
    fn finds_each_conflict() {
        let g = Grid::open(4, 4);
        let e8 = Connectivity::Eight;
        let swap = [cells(&g, &[(0, 0), (1, 0)]), cells(&g, &[(1, 0), (0, 0)])];
        let s = [swap[0][0], swap[1][0]];
        let goals = [swap[0][1], swap[1][1]];
        assert!(matches!(
            validate(&g, e8, &s, &goals, &swap),
            Err(PlanError::Swap { .. })
        ));
        let cross = [cells(&g, &[(0, 0), (1, 1)]), cells(&g, &[(1, 0), (0, 1)])];
        let s = [cross[0][0], cross[1][0]];
        let goals = [cross[0][1], cross[1][1]];
        assert!(matches!(
            validate(&g, e8, &s, &goals, &cross),
            Err(PlanError::Crossing { .. })
        ));
        // Robot 1 rests on its goal at (1,0) from step 0; robot 0 passes through it at step 1.
        let rest = [cells(&g, &[(0, 0), (1, 0), (2, 0)]), cells(&g, &[(1, 0)])];
        let s = [rest[0][0], rest[1][0]];
        let goals = [rest[0][2], rest[1][0]];
        assert!(matches!(
            validate(&g, e8, &s, &goals, &rest),
            Err(PlanError::Vertex { step: 1, .. })
        ));
        let jump = [cells(&g, &[(0, 0), (2, 0)])];
        assert!(matches!(
            validate(&g, e8, &[jump[0][0]], &[jump[0][1]], &jump),
            Err(PlanError::IllegalMove { .. })
        ));
        let ok = [
            cells(&g, &[(0, 0), (0, 0), (1, 1), (2, 2)]),
            cells(&g, &[(3, 3), (3, 2)]),
        ];
        let m = validate(&g, e8, &[ok[0][0], ok[1][0]], &[ok[0][3], ok[1][1]], &ok).unwrap();
        assert_eq!(
            m,
            PlanMetrics {
                sum_of_costs: 4,
                makespan: 3
            }
        );
    }
}
