//! The whole crew pipeline: assign goals, plan each robot's path, resolve collisions.

use crate::assign::{assign, AssignError, AssignMethod};
use crate::astar::astar;
use crate::distance::UNREACHABLE;
use crate::grid::Cell;
use crate::instance::Instance;
use crate::lacam::LacamEnd;
use crate::moves::{distances_to_goals_until, GoalSearches, MoveGraph};
use crate::outcome::{Budget, CrewOutcome, CrewStats, Paths, Status};
use crate::paper::resolve_by_waiting;
use crate::prm::{PrmConfig, Roadmap};
use crate::refine::{refine, RefineConfig};
use crate::restart::lacam_restarts;
use crate::rra::GoalDistance;
use crate::scatter::guide_paths;
use crate::st::{space_time_plan, StFailure};
use crate::tswap::{bottleneck_assignment, tswap, TswapEnd};
use std::time::Instant;
use thiserror::Error;

/// How single-robot paths are found.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PathMethod {
    /// A* on the grid.
    Astar,
    /// A probabilistic roadmap.
    Prm,
}

impl std::str::FromStr for PathMethod {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        match s {
            "astar" => Ok(PathMethod::Astar),
            "prm" => Ok(PathMethod::Prm),
            _ => Err(format!("unknown path method `{s}` (astar, prm)")),
        }
    }
}

/// How collisions are resolved.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Resolution {
    /// The paper's priority waits.
    Paper,
    /// Prioritized space-time A* with a reservation table.
    St,
    /// LaCAM over PIBT steps (complete), then anytime refinement by large neighbourhood search.
    Lacam,
}

impl std::str::FromStr for Resolution {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        match s {
            "paper" => Ok(Resolution::Paper),
            "st" => Ok(Resolution::St),
            "lacam" => Ok(Resolution::Lacam),
            _ => Err(format!("unknown resolution `{s}` (paper, st, lacam)")),
        }
    }
}

/// Everything a crew solve needs besides the instance.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct CrewConfig {
    /// Goal assignment.
    pub assign: AssignMethod,
    /// Single-robot paths.
    pub paths: PathMethod,
    /// Collision resolution.
    pub resolve: Resolution,
    /// Roadmap settings (`prm` only); its seed is the roadmap's seed.
    pub prm: PrmConfig,
    /// Seed of LaCAM's tie-breaking and of refinement (`lacam`).
    pub seed: u64,
    /// When refinement stops besides the deadline (`lacam`).
    pub refine: RefineConfig,
}

impl Default for CrewConfig {
    fn default() -> Self {
        CrewConfig {
            assign: AssignMethod::Hungarian,
            paths: PathMethod::Astar,
            resolve: Resolution::St,
            prm: PrmConfig::default(),
            seed: 0,
            refine: RefineConfig::default(),
        }
    }
}

/// A configuration that cannot run on an instance.
#[derive(Clone, Debug, PartialEq, Eq, Error)]
pub enum SetupError {
    /// The assignment method does not apply.
    #[error(transparent)]
    Assign(#[from] AssignError),
    /// `st` plans its own paths on the grid.
    #[error("--resolve st and lacam search on the grid itself; use --paths astar (prm goes with --resolve paper)")]
    StNeedsGrid,
}

/// Assigns, plans and resolves. The outcome carries a plan exactly when its status is
/// `Optimal` or `Feasible`; otherwise its reason says why not.
pub fn solve(
    inst: &Instance,
    config: &CrewConfig,
    budget: &Budget,
) -> Result<CrewOutcome, SetupError> {
    let started = Instant::now();
    if config.resolve != Resolution::Paper && config.paths == PathMethod::Prm {
        return Err(SetupError::StNeedsGrid);
    }
    if config.assign == AssignMethod::Joint {
        return Ok(solve_joint(inst, budget, started));
    }
    let goal_index = assign(inst, config.assign)?;
    let goals: Vec<Cell> = goal_index.iter().map(|&g| inst.goals[g]).collect();
    let grid = &inst.grid;
    let conn = inst.connectivity;
    let xy = |c: Cell| grid.xy(c);
    let mut stats = CrewStats::default();
    let fail = |status: Status, reason: String, mut stats: CrewStats| {
        stats.elapsed = started.elapsed();
        Ok(CrewOutcome {
            status,
            goals: goals.clone(),
            paths: None,
            reason: Some(reason),
            stats,
        })
    };
    let n = inst.robot_count();
    let result = match config.resolve {
        Resolution::Paper => {
            let roadmap =
                (config.paths == PathMethod::Prm).then(|| Roadmap::build(grid, conn, config.prm));
            let mut single = Vec::with_capacity(n);
            for (r, (&start, &goal)) in inst.robots.iter().zip(&goals).enumerate() {
                if budget.out_of_time() {
                    return fail(
                        Status::Timeout,
                        format!("time ran out planning robot {r}'s path"),
                        stats,
                    );
                }
                let (path, expanded) = match &roadmap {
                    None => {
                        let (p, e) = astar(grid, conn, start, goal);
                        (p.map(|p| p.cells), e)
                    }
                    Some(map) => map.path(grid, conn, start, goal),
                };
                stats.expanded += expanded;
                match path {
                    Some(p) => single.push(p),
                    None => {
                        let why = match &roadmap {
                            None => "no path exists on the grid".to_string(),
                            Some(map) => format!(
                                "the roadmap ({} nodes, {} edges) does not connect them; try more --samples or --neighbours",
                                map.node_count(),
                                map.edge_count()
                            ),
                        };
                        return fail(
                            Status::Infeasible,
                            format!(
                                "robot {r} cannot reach its goal {:?} from {:?}: {why}",
                                xy(goal),
                                xy(start)
                            ),
                            stats,
                        );
                    }
                }
            }
            let order = priority_order(&single.iter().map(|p| p.len() as u64).collect::<Vec<_>>());
            let (resolved, waits) = resolve_by_waiting(grid, &single, &order);
            stats.waits = waits;
            resolved.map_err(|d| {
                let what = if d.blocked_goal {
                    format!(
                        "blocked goal: robot {} rests on its goal {:?}, which robot {} must cross at step {}",
                        d.other,
                        xy(d.cell),
                        d.robot,
                        d.step
                    )
                } else {
                    format!(
                        "deadlock: robot {} cannot wait its way past robot {} at {:?} (step {})",
                        d.robot,
                        d.other,
                        xy(d.cell),
                        d.step
                    )
                };
                (Status::Infeasible, format!("{what}; the paper's priority waits cannot resolve it (try --resolve st)"))
            })
        }
        Resolution::St => {
            let mut to_goal: Vec<GoalDistance> = (0..n)
                .map(|r| GoalDistance::new(grid, conn, goals[r], inst.robots[r]))
                .collect();
            let lengths: Vec<u64> = (0..n)
                .map(|r| to_goal[r].get(grid, inst.robots[r]))
                .map(|d| {
                    if d == UNREACHABLE {
                        u64::MAX
                    } else {
                        u64::from(d)
                    }
                })
                .collect();
            let order = priority_order(&lengths);
            let (planned, expanded) = space_time_plan(
                grid,
                conn,
                &inst.robots,
                &goals,
                &mut to_goal,
                &order,
                budget,
            );
            stats.expanded += expanded;
            planned.map_err(|f| match f {
                StFailure::Unreachable { robot } => (
                    Status::Infeasible,
                    format!(
                        "robot {robot} cannot reach its goal {:?} from {:?}: no path exists on the grid",
                        xy(goals[robot]),
                        xy(inst.robots[robot])
                    ),
                ),
                StFailure::GoalTaken { robot } => (
                    Status::Infeasible,
                    format!("robot {robot}'s goal {:?} is taken by another robot", xy(goals[robot])),
                ),
                StFailure::NoPath { robot, horizon } => (
                    Status::Infeasible,
                    format!(
                        "robot {robot} has no collision-free path to {:?} within {horizon} steps around the robots planned before it (prioritized planning is incomplete)",
                        xy(goals[robot])
                    ),
                ),
                StFailure::Budget { robot } => (
                    Status::Timeout,
                    format!("the search budget ran out while planning robot {robot}"),
                ),
            })
        }
        Resolution::Lacam => solve_lacam(inst, &goals, config, budget, &mut stats, started),
    };
    stats.elapsed = started.elapsed();
    match result {
        Ok(paths) => {
            let lower_bound_met = config.resolve == Resolution::Lacam
                && stats.lower_bound == Some(sum_of_costs(&paths));
            let status = if (n == 1 && config.resolve == Resolution::St) || lower_bound_met {
                Status::Optimal
            } else {
                Status::Feasible
            };
            Ok(CrewOutcome {
                status,
                goals,
                paths: Some(paths),
                reason: None,
                stats,
            })
        }
        Err((status, reason)) => fail(status, reason, stats),
    }
}

/// Robots by path length, longest first; ties to the lower index.
fn priority_order(lengths: &[u64]) -> Vec<usize> {
    let mut order: Vec<usize> = (0..lengths.len()).collect();
    order.sort_by(|&a, &b| lengths[b].cmp(&lengths[a]).then(a.cmp(&b)));
    order
}

fn to_cells(paths: Vec<Vec<u32>>) -> Paths {
    paths
        .into_iter()
        .map(|p| p.into_iter().map(Cell).collect())
        .collect()
}

/// Sum of costs of a plan on cell indices (each robot counted to its last arrival).
fn plan_cost(paths: &[Vec<u32>]) -> u64 {
    paths.iter().map(|p| crate::refine::arrival(p)).sum()
}

fn sum_of_costs(paths: &Paths) -> u64 {
    paths
        .iter()
        .map(|p| crate::validate::arrival(p) as u64)
        .sum()
}

/// Guide paths ([`crate::scatter`]): at most 10 steps longer than the shortest.
const GUIDE_MARGIN: u32 = 10;

/// Under a time limit the guide paths stop at this share of it (robots not yet rerouted keep
/// the path they have): with 1000 robots they took 0.3–0.8 s of a 1 s limit on an unloaded
/// machine, far more than the distance tables, and left LaCAM no time for a first plan.
/// Without a time limit they always run to the end, so plans stay the same for a seed.
const GUIDE_SHARE: f64 = 0.3;

/// LaCAM restarts ([`crate::restart`]) after the first plan: at most 8 more pairs of attempts,
/// none after the first fifth of the time limit. On room-32-32-4 with 341 robots (seeds 0–3,
/// 10 s) the final sum of costs fell from 32 333 / 41 146 / 34 369 / 33 718 to 31 971 / 30 919 /
/// 31 742 / 32 515.
const EXTRA: (usize, f64) = (8, 0.2);

/// When refinement stalls (`RefineConfig::stall` rounds without a gain) with time left and a
/// gap to the lower bound, the search starts again: a new pair of LaCAM attempts under another
/// seed, refined until it stalls in turn, at most this many times; the cheapest plan wins.
/// A stalled refinement sits in a local optimum its neighbourhoods cannot leave, and another
/// first plan leads to another one. On room-32-32-4 with 341 robots (seed 4, 10 s) refinement
/// stalled at 37 173 after 4.2 s and left the rest of the time unused; the count keeps a run
/// without a deadline deterministic and short.
const RESTARTS: u64 = 8;

/// Restart `k`'s seed (a fixed function of the run's seed).
fn restart_seed(seed: u64, k: u64) -> u64 {
    let mut z = seed ^ k.wrapping_mul(0xd1b5_4a32_d192_ed03);
    z = (z ^ (z >> 29)).wrapping_mul(0x9e37_79b9_7f4a_7c15);
    z ^ (z >> 32)
}

/// The reason when the budget ran out while the distance tables were being computed.
fn tables_out_of_time(grid: &crate::Grid, goals: usize) -> (Status, String) {
    (
        Status::Timeout,
        format!(
            "the budget ran out while building the move graph and the distance tables ({goals} goals × {} cells), before any search",
            grid.len()
        ),
    )
}

/// LaCAM for a first plan, then refinement until the budget or `config.refine` stops it.
fn solve_lacam(
    inst: &Instance,
    goals: &[Cell],
    config: &CrewConfig,
    budget: &Budget,
    stats: &mut CrewStats,
    started: Instant,
) -> Result<Paths, (Status, String)> {
    let (grid, conn) = (&inst.grid, inst.connectivity);
    let tables = MoveGraph::new_until(grid, conn, &|| budget.out_of_time()).and_then(|graph| {
        distances_to_goals_until(&graph, goals, &|| budget.out_of_time()).map(|d| (graph, d))
    });
    let Some((graph, dist)) = tables else {
        return Err(tables_out_of_time(grid, goals.len()));
    };
    stats.tables = Some(started.elapsed());
    for (r, (&s, &g)) in inst.robots.iter().zip(goals).enumerate() {
        if dist[r][s.0 as usize] == UNREACHABLE {
            return Err((
                Status::Infeasible,
                format!(
                    "robot {r} cannot reach its goal {:?} from {:?}: no path exists on the grid",
                    grid.xy(g),
                    grid.xy(s)
                ),
            ));
        }
    }
    let starts: Vec<u32> = inst.robots.iter().map(|c| c.0).collect();
    let targets: Vec<u32> = goals.iter().map(|c| c.0).collect();
    stats.lower_bound = Some(
        starts
            .iter()
            .enumerate()
            .map(|(r, &s)| u64::from(dist[r][s as usize]))
            .sum(),
    );
    // Guide paths that spread the robots out, then LaCAM from the start: complete, and with
    // PIBT's corridor rules its first descent is usually already a plan.
    let guide_started = Instant::now();
    let mut guide_budget = budget.clone();
    guide_budget.deadline = budget
        .deadline
        .map(|d| started + d.saturating_duration_since(started).mul_f64(GUIDE_SHARE));
    let guide = guide_paths(
        &graph,
        &dist,
        &starts,
        &targets,
        GUIDE_MARGIN,
        &guide_budget,
        config.seed,
    );
    if !guide_budget.out_of_time() {
        stats.guide = Some(guide_started.elapsed());
    }
    let extra_until = budget
        .deadline
        .map(|d| started + d.saturating_duration_since(started).mul_f64(EXTRA.1));
    let searched = lacam_restarts(
        &graph,
        &dist,
        &starts,
        &targets,
        &guide,
        budget,
        config.seed,
        EXTRA.0,
        extra_until,
    );
    let configurations = searched.configurations;
    stats.configurations = configurations;
    match searched.end {
        LacamEnd::Found(mut paths) => {
            stats.first_solution = searched.first_found.map(|t| t.duration_since(started));
            stats.first_sum_of_costs = searched.first_sum_of_costs;
            let r = refine(
                &graph,
                &dist,
                &targets,
                &mut paths,
                &config.refine,
                budget,
                config.seed,
            );
            stats.refine_rounds = r.rounds;
            stats.improvements = r.improvements;
            stats.expanded += r.expanded;
            let lower = stats.lower_bound.unwrap_or(0);
            let mut best = plan_cost(&paths);
            // Only an open-ended refinement starts again: a fixed `rounds` is the caller's.
            let mut stalled = r.stalled && config.refine.rounds.is_none();
            let mut k = 0;
            while stalled && k < RESTARTS && best > lower && !budget.out_of_time() {
                k += 1;
                let seed = restart_seed(config.seed, k);
                let again = lacam_restarts(
                    &graph, &dist, &starts, &targets, &guide, budget, seed, 0, None,
                );
                stats.configurations += again.configurations;
                let LacamEnd::Found(mut other) = again.end else {
                    break;
                };
                let r = refine(
                    &graph,
                    &dist,
                    &targets,
                    &mut other,
                    &config.refine,
                    budget,
                    seed,
                );
                stats.restarts += 1;
                stats.refine_rounds += r.rounds;
                stats.improvements += r.improvements;
                stats.expanded += r.expanded;
                stalled = r.stalled;
                let cost = plan_cost(&other);
                if cost < best {
                    best = cost;
                    paths = other;
                }
            }
            Ok(to_cells(paths))
        }
        LacamEnd::Exhausted => Err((
            Status::Infeasible,
            format!(
                "LaCAM explored all {configurations} reachable configurations and none has every robot on its goal: no plan exists"
            ),
        )),
        LacamEnd::Budget => Err((
            Status::Timeout,
            format!(
                "the budget ran out before a first plan ({configurations} LaCAM configurations)"
            ),
        )),
    }
}

/// The depth of TSWAP's first goal searches; each round doubles it (see [`joint_tables`]).
const FIRST_DEPTH: u32 = 32;

/// The goal searches TSWAP needs from `starts`, and the bottleneck assignment on them: the
/// searches go `first_depth` steps deep, then twice as deep, and so on, until the assignment
/// pairs every robot or the searches reach every cell. A complete assignment within the depth
/// reached is the one the whole tables give (its longest pair is within the depth, and every
/// pair up to it is there), and TSWAP never needs a distance beyond its longest pair (each
/// robot's distance to its goal never grows past it, and its next cell is one step nearer):
/// on a large floor the searches stop near the goals, instead of crossing the whole map 500
/// times. `None` when `stop` says so.
fn joint_tables(
    graph: &MoveGraph,
    goals: &[Cell],
    starts: &[u32],
    first_depth: u32,
    stop: &(dyn Fn() -> bool + Sync),
) -> Option<(GoalSearches, Vec<Option<usize>>)> {
    let mut searches = GoalSearches::new(graph, goals);
    let mut depth = first_depth.max(1);
    loop {
        searches.deepen(graph, depth, stop)?;
        let greedy = bottleneck_assignment(&searches.dist, starts);
        if greedy.iter().all(Option::is_some) || searches.whole() {
            return Some((searches, greedy));
        }
        depth = depth.saturating_mul(2);
    }
}

/// Unlabelled: TSWAP from the bottleneck step-distance assignment.
fn solve_joint(inst: &Instance, budget: &Budget, started: Instant) -> CrewOutcome {
    let (grid, conn) = (&inst.grid, inst.connectivity);
    let starts: Vec<u32> = inst.robots.iter().map(|c| c.0).collect();
    let goal_cells: Vec<u32> = inst.goals.iter().map(|c| c.0).collect();
    let mut stats = CrewStats::default();
    let done = |status, goals: Vec<usize>, paths, reason, mut stats: CrewStats| {
        stats.elapsed = started.elapsed();
        CrewOutcome {
            status,
            goals: goals.iter().map(|&g| inst.goals[g]).collect(),
            paths,
            reason,
            stats,
        }
    };
    let fallback: Vec<usize> = (0..inst.robot_count()).collect();
    let stop = || budget.out_of_time();
    let tables = MoveGraph::new_until(grid, conn, &stop).and_then(|graph| {
        joint_tables(&graph, &inst.goals, &starts, FIRST_DEPTH, &stop).map(|t| (graph, t))
    });
    let Some((graph, (mut searches, greedy))) = tables else {
        let (status, reason) = tables_out_of_time(grid, inst.goals.len());
        return done(status, fallback, None, Some(reason), stats);
    };
    let dist = &searches.dist;
    if let Some(r) = greedy.iter().position(Option::is_none) {
        return done(
            Status::Infeasible,
            fallback,
            None,
            Some(format!(
                "robot {r} at {:?} can reach none of the goals left to it",
                grid.xy(inst.robots[r])
            )),
            stats,
        );
    }
    let initial: Vec<usize> = greedy.into_iter().map(|g| g.expect("checked")).collect();
    let longest = (0..inst.robot_count())
        .map(|r| dist[initial[r]][starts[r] as usize])
        .max()
        .unwrap_or(0);
    let max_steps = (longest + inst.robot_count() as u32 + grid.len() as u32).saturating_mul(4);
    match tswap(&graph, dist, &goal_cells, &starts, &initial, max_steps, budget) {
        TswapEnd::Found { goals, paths } => {
            stats.first_solution = Some(started.elapsed());
            // A robot's last goal may lie beyond the depth its search reached.
            let mut bound = 0u64;
            for (&s, &g) in starts.iter().zip(&goals) {
                if searches.dist[g][s as usize] == crate::moves::NIL {
                    searches.finish(&graph, g);
                }
                bound += u64::from(searches.dist[g][s as usize]);
            }
            stats.lower_bound = Some(bound);
            done(Status::Feasible, goals, Some(to_cells(paths)), None, stats)
        }
        TswapEnd::Unreachable { robot } => done(
            Status::Infeasible,
            initial,
            None,
            Some(format!("robot {robot} cannot reach its goal")),
            stats,
        ),
        TswapEnd::Budget => done(
            Status::Timeout,
            initial,
            None,
            Some(format!(
                "TSWAP did not bring every robot to a goal within the budget ({max_steps} steps at most)"
            )),
            stats,
        ),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::grid::Connectivity;
    use crate::moves::distances_to_goals;
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    /// Searches cut at any depth give TSWAP the same assignment and the same plan as the whole
    /// tables, on random floors with walls (robots walled off from every goal too), for both
    /// connectivities; within the depth reached their distances are the whole tables'.
    #[test]
    fn goal_searches_cut_short_plan_as_the_whole_tables() {
        let mut rng = ChaCha8Rng::seed_from_u64(29);
        // Cases where the searches stopped short of whole tables, and where a robot is left
        // unpaired (walled off): both must occur for the test to mean something.
        let (mut cut_short, mut unpaired) = (0, 0);
        for case in 0..120 {
            let (w, h) = (rng.gen_range(3..14u32), rng.gen_range(3..14u32));
            let conn = if case % 2 == 0 {
                Connectivity::Four
            } else {
                Connectivity::Eight
            };
            let mut grid = crate::Grid::open(w, h);
            for c in 0..grid.len() as u32 {
                if rng.gen_bool(0.25) {
                    grid.set_blocked(Cell(c), true);
                }
            }
            let mut free: Vec<Cell> = (0..grid.len() as u32)
                .map(Cell)
                .filter(|&c| grid.is_free(c))
                .collect();
            if free.len() < 2 {
                continue;
            }
            for i in (1..free.len()).rev() {
                free.swap(i, rng.gen_range(0..=i));
            }
            let n = rng.gen_range(1..=(free.len() / 2).min(12));
            let goals: Vec<Cell> = free[..n].to_vec();
            let starts: Vec<u32> = free[n..2 * n].iter().map(|c| c.0).collect();
            let goal_cells: Vec<u32> = goals.iter().map(|c| c.0).collect();
            let graph = MoveGraph::new(&grid, conn);
            let whole = distances_to_goals(&graph, &goals);
            let want = bottleneck_assignment(&whole, &starts);
            unpaired += usize::from(want.iter().any(Option::is_none));
            let plan = |dist: &[Vec<u32>], initial: &[Option<usize>]| {
                let initial: Option<Vec<usize>> = initial.iter().copied().collect();
                initial.map(|i| {
                    let end = tswap(
                        &graph,
                        dist,
                        &goal_cells,
                        &starts,
                        &i,
                        10_000,
                        &Budget::default(),
                    );
                    match end {
                        TswapEnd::Found { goals, paths } => Some((goals, paths)),
                        _ => None,
                    }
                })
            };
            let want_plan = plan(&whole, &want);
            for first in [1, 2, 3, 5, 32] {
                let (searches, got) =
                    joint_tables(&graph, &goals, &starts, first, &|| false).expect("never stopped");
                cut_short += usize::from(!searches.whole());
                assert_eq!(got, want, "case {case}, first depth {first}");
                assert_eq!(
                    plan(&searches.dist, &got),
                    want_plan,
                    "case {case}, first depth {first}"
                );
                for (cut, full) in searches.dist.iter().zip(&whole) {
                    for (&a, &b) in cut.iter().zip(full) {
                        assert!(a == b || a == crate::moves::NIL, "case {case}: {a} for {b}");
                    }
                }
            }
        }
        assert!(
            cut_short > 0 && unpaired > 0,
            "{cut_short} cut short, {unpaired} unpaired"
        );
    }
}
