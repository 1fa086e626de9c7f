//! Lazy constraints addition search (LaCAM; Okumura, AAAI 2023): a complete search over
//! configurations (where every robot stands) that uses PIBT ([`crate::pibt`]) to propose the
//! next configuration.
//!
//! The high level is a depth-first search on configurations. Each configuration keeps its own
//! low-level search tree of *constraints* ("robot i goes to cell v"), grown lazily: every time
//! the configuration is visited, one constraint node is taken from its queue, its children (the
//! next robot in priority order, pinned to each of its cells) are queued behind it, and PIBT
//! completes the step around the constraints. Since every constraint set is eventually tried, every successor
//! configuration of every reached configuration is eventually generated: the search is
//! complete. A step that leads back to a configuration already seen is dropped, and the next
//! constraint set of the same configuration is tried at once, which is how the search breaks
//! the loops PIBT alone can fall into. It reports [`LacamEnd::Exhausted`] only after the whole reachable configuration
//! space is explored, which proves that no plan exists.
//!
//! Priorities follow the paper: a robot away from its goal gains one each step, a robot on its
//! goal drops back to its initial fraction (the distance to its goal, scaled below one).
//!
//! The first plan found is not optimal; [`crate::refine`] improves it. Memory: O(n) per
//! configuration reached. Time per configuration: one PIBT step, O(n · d), plus O(n log n) to
//! order the robots.

use crate::moves::{MoveGraph, NIL};
use crate::outcome::Budget;
use crate::pibt::Pibt;
use rand::seq::SliceRandom;
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use rustc_hash::FxHashMap;
use std::collections::VecDeque;

/// How a LaCAM search ended.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum LacamEnd {
    /// A plan: `paths[i][t]`, each cut at the robot's last arrival on its goal.
    Found(Vec<Vec<u32>>),
    /// Every reachable configuration was explored and none has all robots on their goals.
    Exhausted,
    /// The deadline or the node cap came first.
    Budget,
}

struct Node {
    config: Box<[u32]>,
    parent: u32,
    order: Box<[u32]>,
    priority: Box<[f32]>,
    /// The queue of constraint sets still to try from this configuration.
    tree: VecDeque<Vec<(u32, u32)>>,
}

/// Searches from `starts` to `goals` (cell indices) with PIBT seeded by `seed`. `dist[i]` are
/// robot i's step distances to its goal. Returns the end and the number of configurations
/// created.
pub fn lacam(
    graph: &MoveGraph,
    dist: &[Vec<u32>],
    starts: &[u32],
    goals: &[u32],
    budget: &Budget,
    seed: u64,
) -> (LacamEnd, u64) {
    lacam_guided(graph, dist, starts, goals, &[], budget, seed)
}

/// [`lacam`] with PIBT following `guide` paths where robots stand on them
/// ([`crate::pibt::Pibt::set_guide`]; empty: none).
pub fn lacam_guided(
    graph: &MoveGraph,
    dist: &[Vec<u32>],
    starts: &[u32],
    goals: &[u32],
    guide: &[Vec<u32>],
    budget: &Budget,
    seed: u64,
) -> (LacamEnd, u64) {
    lacam_search(
        graph,
        dist,
        starts,
        goals,
        guide,
        budget,
        seed,
        SearchRules::default(),
    )
}

/// The rules a [`lacam_search`] follows besides its advice.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SearchRules {
    /// What happens when a step leads to a configuration already reached. Off: the step is
    /// dropped and the same configuration tries its next constraint set (LaCAM). On: the
    /// search goes on from the configuration reached, which is put on top of the stack again
    /// (as LaCAM* does, without its costs): the search follows the robots' motion instead of
    /// working through the constraints of a configuration it keeps coming back to. Both are
    /// complete (every push of a known configuration uses up one constraint set, of which
    /// there are finitely many). Measured on small dense maps (see [`crate::restart`]),
    /// revisiting finds much shorter first plans, but on some seeds it needs many more
    /// configurations.
    pub revisit: bool,
    /// Whether PIBT's last tie-break before chance goes to a free cell
    /// ([`crate::pibt::Pibt::set_prefer_free`]).
    pub prefer_free: bool,
}

impl Default for SearchRules {
    /// LaCAM as published, with free cells preferred.
    fn default() -> Self {
        SearchRules {
            revisit: false,
            prefer_free: true,
        }
    }
}

/// [`lacam_guided`] under the given [`SearchRules`].
#[allow(clippy::too_many_arguments)]
pub fn lacam_search(
    graph: &MoveGraph,
    dist: &[Vec<u32>],
    starts: &[u32],
    goals: &[u32],
    guide: &[Vec<u32>],
    budget: &Budget,
    seed: u64,
    rules: SearchRules,
) -> (LacamEnd, u64) {
    let n = starts.len();
    let mut rng = ChaCha8Rng::seed_from_u64(seed ^ 0x1aca_0001);
    let mut pibt = Pibt::new(graph, dist, seed);
    if !guide.is_empty() {
        pibt.set_guide(guide);
    }
    pibt.set_prefer_free(rules.prefer_free);
    let revisit = rules.revisit;
    let max_d = (0..n)
        .map(|i| dist[i][starts[i] as usize])
        .max()
        .unwrap_or(0);
    let initial: Box<[f32]> = (0..n)
        .map(|i| dist[i][starts[i] as usize] as f32 / (max_d as f32 + 1.0))
        .collect();
    let mut nodes: Vec<Node> = Vec::new();
    let mut explored: FxHashMap<Box<[u32]>, u32> = FxHashMap::default();
    let root = Node {
        config: starts.into(),
        parent: NIL,
        order: order_of(&initial),
        priority: initial.clone(),
        tree: VecDeque::from([Vec::new()]),
    };
    explored.insert(root.config.clone(), 0);
    nodes.push(root);
    let mut open: Vec<u32> = vec![0];
    let mut next = vec![0u32; n];
    let mut iterations = 0u64;
    loop {
        iterations += 1;
        if budget.out_of_time() || budget.node_limit.is_some_and(|cap| iterations > cap) {
            return (LacamEnd::Budget, nodes.len() as u64);
        }
        let Some(&top) = open.last() else {
            return (LacamEnd::Exhausted, nodes.len() as u64);
        };
        let node = &mut nodes[top as usize];
        if *node.config == *goals {
            return (
                LacamEnd::Found(extract(&nodes, top, goals)),
                nodes.len() as u64,
            );
        }
        let Some(constraints) = node.tree.pop_front() else {
            open.pop();
            continue;
        };
        if constraints.len() < n {
            let i = node.order[constraints.len()];
            let v = node.config[i as usize];
            let mut cells: Vec<u32> = std::iter::once(v)
                .chain(graph.neighbours(v).iter().copied())
                .collect();
            cells.shuffle(&mut rng);
            for u in cells {
                let mut child = Vec::with_capacity(constraints.len() + 1);
                child.extend_from_slice(&constraints);
                child.push((i, u));
                node.tree.push_back(child);
            }
        }
        if !pibt.step(&node.config, &mut next, &node.order, &constraints) {
            continue;
        }
        if let Some(&known) = explored.get(next.as_slice()) {
            if revisit {
                open.push(known);
            }
            continue;
        }
        let priority: Box<[f32]> = (0..n)
            .map(|i| {
                let p = node.priority[i];
                if next[i] == goals[i] {
                    p - p.floor()
                } else {
                    p + 1.0
                }
            })
            .collect();
        let child = Node {
            config: next.as_slice().into(),
            parent: top,
            order: order_of(&priority),
            priority,
            tree: VecDeque::from([Vec::new()]),
        };
        let id = nodes.len() as u32;
        explored.insert(child.config.clone(), id);
        nodes.push(child);
        open.push(id);
    }
}

/// Robots by priority, highest first; ties to the lower index.
fn order_of(priority: &[f32]) -> Box<[u32]> {
    let mut order: Vec<u32> = (0..priority.len() as u32).collect();
    order.sort_by(|&a, &b| priority[b as usize].total_cmp(&priority[a as usize]));
    order.into()
}

/// The configurations from the root to `last`, as one path per robot cut at its last arrival.
fn extract(nodes: &[Node], last: u32, goals: &[u32]) -> Vec<Vec<u32>> {
    let mut chain = Vec::new();
    let mut k = last;
    while k != NIL {
        chain.push(k);
        k = nodes[k as usize].parent;
    }
    chain.reverse();
    (0..goals.len())
        .map(|i| {
            let mut p: Vec<u32> = chain.iter().map(|&k| nodes[k as usize].config[i]).collect();
            let arrive = p.iter().rposition(|&c| c != goals[i]).map_or(0, |t| t + 1);
            p.truncate(arrive + 1);
            p
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::generate::keep_largest_region;
    use crate::grid::{Cell, Connectivity, Grid};
    use crate::moves::goal_distances;
    use crate::validate::validate;
    use rand::Rng;

    #[test]
    fn revisiting_finds_valid_plans_and_agrees_on_which_instances_have_none() {
        // Both rules are complete: on every small instance where neither runs out of its
        // cap, they must agree on whether a plan exists, and every plan must be valid.
        let mut rng = ChaCha8Rng::seed_from_u64(11);
        let (mut found, mut none) = (0, 0);
        for k in 0..400 {
            let conn = if k % 2 == 0 {
                Connectivity::Four
            } else {
                Connectivity::Eight
            };
            let (w, h) = (rng.gen_range(2..6), rng.gen_range(2..6));
            let blocked = (0..w * h).map(|_| rng.gen_bool(0.2)).collect();
            let mut grid = Grid::new(w, h, blocked);
            keep_largest_region(&mut grid);
            let mut free: Vec<Cell> = (0..grid.len() as u32)
                .map(Cell)
                .filter(|&c| grid.is_free(c))
                .collect();
            let n = 2 + k % 4;
            if free.len() < n + 1 {
                continue;
            }
            free.shuffle(&mut rng);
            let starts: Vec<Cell> = free[..n].to_vec();
            free.shuffle(&mut rng);
            let goals: Vec<Cell> = free[..n].to_vec();
            let graph = MoveGraph::new(&grid, conn);
            let dist = goal_distances(&grid, conn, &goals);
            if (0..n).any(|i| dist[i][starts[i].0 as usize] == crate::distance::UNREACHABLE) {
                continue;
            }
            let s: Vec<u32> = starts.iter().map(|c| c.0).collect();
            let g: Vec<u32> = goals.iter().map(|c| c.0).collect();
            let capped = Budget {
                node_limit: Some(200_000),
                ..Budget::unlimited()
            };
            let ends: Vec<LacamEnd> = [false, true]
                .iter()
                .map(|&revisit| {
                    let rules = SearchRules {
                        revisit,
                        ..SearchRules::default()
                    };
                    lacam_search(&graph, &dist, &s, &g, &[], &capped, k as u64, rules).0
                })
                .collect();
            for end in &ends {
                if let LacamEnd::Found(paths) = end {
                    let cells: Vec<Vec<Cell>> = paths
                        .iter()
                        .map(|p| p.iter().map(|&c| Cell(c)).collect())
                        .collect();
                    validate(&grid, conn, &starts, &goals, &cells)
                        .unwrap_or_else(|e| panic!("instance {k}: {e}"));
                }
            }
            match (&ends[0], &ends[1]) {
                (LacamEnd::Found(_), LacamEnd::Found(_)) => found += 1,
                (LacamEnd::Exhausted, LacamEnd::Exhausted) => none += 1,
                (LacamEnd::Budget, _) | (_, LacamEnd::Budget) => {}
                (a, b) => panic!("instance {k}: without revisits {a:?}, with {b:?}"),
            }
        }
        assert!(
            found >= 100 && none >= 5,
            "{found} solved, {none} without a plan"
        );
    }
}
