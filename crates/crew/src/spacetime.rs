//! Space-time A* (Silver 2005): one robot's quickest (or cheapest) path around the others,
//! the search shared by prioritized planning ([`crate::st`]) and anytime refinement
//! ([`crate::refine`]); the guide paths ([`crate::scatter`]) search cells, not states.
//!
//! States are (cell, step). From each, the robot waits or makes one move of the
//! [`MoveGraph`]. The caller's [`Rules`] say what the rest of the world does: the cost of a
//! step (at least one) or that it is blocked, the step distance to the goal as heuristic, and
//! which of two equally good open states goes first. The robot may stop on its goal only from
//! [`Query::rest_from`] on, so f is raised to that step. Each state is expanded once, the
//! first time it leaves the open list; when every step costs one ([`Rules::UNIT_STEPS`]) the
//! first copy generated is as good as any, and later copies are not generated at all, which
//! saves work but changes no path. [`Limits`] bound the steps searched, merge states by cell
//! once the world stands still, and cap the states expanded.
//!
//! With step costs of at least one and a consistent heuristic (the true step distance is), the
//! path found is optimal for the robot given the rules, among paths the limits allow.
//! O(S log S) time and O(S) memory for the S states searched; S ≤ V · T for V cells and T
//! steps searched.
//!
//! CBS's low level ([`crate::cbs`]) keeps its own space-time A* on purpose: CBS is the oracle
//! the tests hold these solvers to, so it must not share their search.

use crate::moves::{MoveGraph, NIL};
use rustc_hash::FxHashSet;
use std::collections::BinaryHeap;
use std::time::Instant;

/// What the world around the robot allows, as one search sees it.
pub trait Rules {
    /// The order of open states: the greatest is expanded first. Ranks of two different
    /// states must differ (the state's id does it).
    type Rank: Ord;

    /// Whether every step costs one. A state's cost is then its step, so the first copy of a
    /// state generated is as good as any: later copies are not generated at all.
    const UNIT_STEPS: bool = false;

    /// The rank of an open state.
    fn rank(state: Open) -> Self::Rank;

    /// The id of the state `rank` ranks.
    fn id(rank: &Self::Rank) -> u32;

    /// The fewest steps from `cell` to the goal, or [`NIL`] (the same value as
    /// [`crate::distance::UNREACHABLE`]) when it cannot be reached.
    fn distance(&mut self, cell: u32) -> u32;

    /// The cost (at least one) of waiting, when `from == to`, or moving from `from` at step `t`
    /// to `to` at step `t + 1`; `None` when something blocks it.
    fn step(&self, from: u32, to: u32, t: u32) -> Option<u32>;
}

/// An open state, as [`Rules::rank`] sees it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Open {
    /// Cost so far plus the distance left, raised to [`Query::rest_from`].
    pub f: u32,
    /// The distance left.
    pub h: u32,
    /// The step.
    pub t: u32,
    /// The cell.
    pub cell: u32,
    /// The state's id, in the order the states were generated.
    pub id: u32,
}

/// Bounds on one search. The default bounds nothing.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Limits {
    /// States at this step or later are tested for the goal but not expanded.
    pub last_step: u32,
    /// From this step on the world no longer changes: states there are told apart by their
    /// cell alone, which keeps a search that waits for ever finite.
    pub still_from: u32,
    /// Only states from which the goal can still be reached by this step are generated.
    pub arrive_by: u32,
    /// At most this many states are expanded.
    pub node_limit: u64,
    /// The search gives up after this instant (looked at every 4096 states).
    pub deadline: Option<Instant>,
}

impl Default for Limits {
    fn default() -> Self {
        Limits {
            last_step: u32::MAX,
            still_from: u32::MAX,
            arrive_by: u32::MAX,
            node_limit: u64::MAX,
            deadline: None,
        }
    }
}

/// One robot's search: from `start` at step 0 to `goal`, where it may stay from `rest_from` on.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Query {
    /// The cell at step 0.
    pub start: u32,
    /// The goal cell.
    pub goal: u32,
    /// The first step from which the robot may stay on its goal for good.
    pub rest_from: u32,
    /// Bounds on the search.
    pub limits: Limits,
}

/// Why a search ended without a path.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Stop {
    /// Every state within the limits was searched.
    Exhausted,
    /// The node limit or the deadline came first.
    Budget,
}

/// A searched state: cell, step, parent id, cost so far.
#[derive(Clone, Copy)]
struct Node {
    cell: u32,
    t: u32,
    parent: u32,
    g: u32,
}

/// Space-time A* with buffers kept from one search to the next; `K` is the [`Rules::Rank`] of
/// the rules it searches under.
pub struct Search<K> {
    nodes: Vec<Node>,
    seen: FxHashSet<u64>,
    open: BinaryHeap<K>,
}

impl<K: Ord> Default for Search<K> {
    fn default() -> Self {
        Search::new()
    }
}

/// The key of state (`cell`, `t`) in a hash set or map.
#[inline]
pub fn key(cell: u32, t: u32) -> u64 {
    (u64::from(t) << 32) | u64::from(cell)
}

impl<K: Ord> Search<K> {
    /// Empty buffers.
    pub fn new() -> Self {
        Search {
            nodes: Vec::new(),
            seen: FxHashSet::default(),
            open: BinaryHeap::new(),
        }
    }

    /// The best path for `query` under `rules`, as the cells from step 0, ending on the goal.
    /// Adds the states expanded to `expanded`.
    pub fn run<R: Rules<Rank = K>>(
        &mut self,
        graph: &MoveGraph,
        rules: &mut R,
        query: &Query,
        expanded: &mut u64,
    ) -> Result<Vec<u32>, Stop> {
        let Query {
            start,
            goal,
            rest_from,
            limits,
        } = *query;
        self.nodes.clear();
        self.seen.clear();
        self.open.clear();
        let h0 = rules.distance(start);
        if h0 == NIL {
            return Err(Stop::Exhausted);
        }
        let still = limits.still_from;
        // With unit steps a state below `still` is marked when generated, so it is generated
        // (and expanded) once; any other state is marked when expanded.
        let marked_early = |t: u32| R::UNIT_STEPS && t < still;
        if marked_early(0) {
            self.seen.insert(key(start, 0));
        }
        self.push::<R>(
            Node {
                cell: start,
                t: 0,
                parent: NIL,
                g: 0,
            },
            h0,
            rest_from,
        );
        let mut local = 0u64;
        while let Some(rank) = self.open.pop() {
            let id = R::id(&rank);
            let Node { cell, t, g, .. } = self.nodes[id as usize];
            if !marked_early(t) && !self.seen.insert(key(cell, t.min(still))) {
                continue;
            }
            local += 1;
            *expanded += 1;
            if local > limits.node_limit
                || (local % 4096 == 0 && limits.deadline.is_some_and(|d| Instant::now() >= d))
            {
                return Err(Stop::Budget);
            }
            if cell == goal && t >= rest_from {
                return Ok(self.path(id));
            }
            if t >= limits.last_step {
                continue;
            }
            for &next in std::iter::once(&cell).chain(graph.neighbours(cell)) {
                let h = rules.distance(next);
                if h == NIL || t + 1 + h > limits.arrive_by {
                    continue;
                }
                let k = key(next, (t + 1).min(still));
                if self.seen.contains(&k) {
                    continue;
                }
                let Some(cost) = rules.step(cell, next, t) else {
                    continue;
                };
                if marked_early(t + 1) {
                    self.seen.insert(k);
                }
                let node = Node {
                    cell: next,
                    t: t + 1,
                    parent: id,
                    g: g + cost,
                };
                self.push::<R>(node, h, rest_from);
            }
        }
        Err(Stop::Exhausted)
    }

    /// Adds `node`, `h` steps from the goal, to the open list.
    #[inline]
    fn push<R: Rules<Rank = K>>(&mut self, node: Node, h: u32, rest_from: u32) {
        let id = self.nodes.len() as u32;
        self.nodes.push(node);
        self.open.push(R::rank(Open {
            f: (node.g + h).max(rest_from),
            h,
            t: node.t,
            cell: node.cell,
            id,
        }));
    }

    /// The cells from the start to state `id`.
    fn path(&self, id: u32) -> Vec<u32> {
        let mut path = Vec::with_capacity(self.nodes[id as usize].t as usize + 1);
        let mut x = id;
        while x != NIL {
            path.push(self.nodes[x as usize].cell);
            x = self.nodes[x as usize].parent;
        }
        path.reverse();
        path
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::grid::{Cell, Connectivity, Grid};
    use rustc_hash::FxHashMap;
    use std::cmp::Reverse;

    /// Rules for tests: step distances `dist`; a step costs one plus `toll[to]`; (cell, step)
    /// pairs `held` and the cell `barred` (at every step) may not be entered; ties to the
    /// lesser f, then to the lower cell, then to the first generated.
    struct Plain<'a> {
        dist: &'a [u32],
        toll: Vec<u32>,
        held: FxHashMap<(u32, u32), ()>,
        barred: u32,
    }

    type LowCell = (Reverse<u32>, Reverse<u32>, Reverse<u32>);

    impl Rules for Plain<'_> {
        type Rank = LowCell;
        fn rank(s: Open) -> LowCell {
            (Reverse(s.f), Reverse(s.cell), Reverse(s.id))
        }
        fn id(r: &LowCell) -> u32 {
            r.2 .0
        }
        fn distance(&mut self, cell: u32) -> u32 {
            self.dist[cell as usize]
        }
        fn step(&self, _: u32, to: u32, t: u32) -> Option<u32> {
            let free = to != self.barred && !self.held.contains_key(&(to, t + 1));
            free.then(|| 1 + self.toll[to as usize])
        }
    }

    /// The same rules with ties to the higher cell.
    struct HighCell<'a>(Plain<'a>);

    impl Rules for HighCell<'_> {
        type Rank = (Reverse<u32>, u32, Reverse<u32>);
        fn rank(s: Open) -> Self::Rank {
            (Reverse(s.f), s.cell, Reverse(s.id))
        }
        fn id(r: &Self::Rank) -> u32 {
            r.2 .0
        }
        fn distance(&mut self, cell: u32) -> u32 {
            self.0.distance(cell)
        }
        fn step(&self, from: u32, to: u32, t: u32) -> Option<u32> {
            self.0.step(from, to, t)
        }
    }

    /// The same rules, saying that every step costs one.
    struct Unit<'a>(Plain<'a>);

    impl Rules for Unit<'_> {
        type Rank = LowCell;
        const UNIT_STEPS: bool = true;
        fn rank(s: Open) -> LowCell {
            Plain::rank(s)
        }
        fn id(r: &LowCell) -> u32 {
            Plain::id(r)
        }
        fn distance(&mut self, cell: u32) -> u32 {
            self.0.distance(cell)
        }
        fn step(&self, from: u32, to: u32, t: u32) -> Option<u32> {
            self.0.step(from, to, t)
        }
    }

    fn plain(dist: &[u32]) -> Plain<'_> {
        Plain {
            dist,
            toll: vec![0; dist.len()],
            held: FxHashMap::default(),
            barred: NIL,
        }
    }

    fn query(start: u32, goal: u32) -> Query {
        Query {
            start,
            goal,
            rest_from: 0,
            limits: Limits::default(),
        }
    }

    fn walled() -> Grid {
        let mut grid = Grid::open(9, 7);
        for (x, y) in [
            (2, 0),
            (2, 1),
            (2, 2),
            (2, 3),
            (5, 6),
            (5, 5),
            (5, 4),
            (5, 3),
            (7, 1),
        ] {
            grid.set_blocked(grid.cell(x, y).unwrap(), true);
        }
        grid
    }

    fn is_walk(graph: &MoveGraph, p: &[u32]) -> bool {
        p.windows(2)
            .all(|w| w[0] == w[1] || graph.neighbours(w[0]).contains(&w[1]))
    }

    /// Least total toll to `goal` by Dijkstra over cells, where entering a cell costs one plus
    /// its toll (waiting never helps when nothing moves).
    fn dijkstra(graph: &MoveGraph, toll: &[u32], goal: u32) -> Vec<u32> {
        let mut best = vec![NIL; graph.cells()];
        let mut open = BinaryHeap::from([(Reverse(0u32), goal)]);
        best[goal as usize] = 0;
        while let Some((Reverse(d), c)) = open.pop() {
            if d > best[c as usize] {
                continue;
            }
            // Reversed: the cost of the move m → c is paid on entering c.
            for &m in graph.neighbours(c) {
                let nd = d + 1 + toll[c as usize];
                if nd < best[m as usize] {
                    best[m as usize] = nd;
                    open.push((Reverse(nd), m));
                }
            }
        }
        best
    }

    #[test]
    fn agrees_with_breadth_first_search_when_nothing_moves() {
        let grid = walled();
        for conn in [Connectivity::Four, Connectivity::Eight] {
            let graph = MoveGraph::new(&grid, conn);
            let goal = grid.cell(8, 6).unwrap().0;
            let dist = graph.distances_from(goal);
            let mut search = Search::new();
            for start in (0..grid.len() as u32).filter(|&c| grid.is_free(Cell(c))) {
                let mut expanded = 0;
                let p = search
                    .run(
                        &graph,
                        &mut plain(&dist),
                        &query(start, goal),
                        &mut expanded,
                    )
                    .unwrap();
                assert_eq!(p.len() as u32 - 1, dist[start as usize], "{start} {conn:?}");
                assert_eq!((p[0], p[p.len() - 1]), (start, goal));
                assert!(is_walk(&graph, &p));
                assert!(expanded > u64::from(dist[start as usize]));
            }
        }
    }

    #[test]
    fn agrees_with_dijkstra_when_steps_cost_more() {
        let grid = walled();
        let graph = MoveGraph::new(&grid, Connectivity::Eight);
        let goal = grid.cell(0, 6).unwrap().0;
        let dist = graph.distances_from(goal);
        let toll: Vec<u32> = (0..grid.len() as u32).map(|c| (c * 7 + 3) % 5).collect();
        let best = dijkstra(&graph, &toll, goal);
        let mut search = Search::new();
        for start in (0..grid.len() as u32).filter(|&c| grid.is_free(Cell(c))) {
            let mut rules = Plain {
                toll: toll.clone(),
                ..plain(&dist)
            };
            let p = search
                .run(&graph, &mut rules, &query(start, goal), &mut 0)
                .unwrap();
            let paid: u32 = p.windows(2).map(|w| 1 + toll[w[1] as usize]).sum();
            assert_eq!(paid, best[start as usize], "from {start}");
            assert!(is_walk(&graph, &p));
        }
    }

    #[test]
    fn waits_for_a_held_cell_and_rests_only_when_allowed() {
        // A corridor 0 1 2 3 4: cell 2 is held at step 2, so the robot waits a step.
        let grid = Grid::open(5, 1);
        let graph = MoveGraph::new(&grid, Connectivity::Four);
        let dist = graph.distances_from(4);
        let mut rules = plain(&dist);
        rules.held.insert((2, 2), ());
        let mut search = Search::new();
        let p = search
            .run(&graph, &mut rules, &query(0, 4), &mut 0)
            .unwrap();
        assert_eq!(p.len(), 6);
        assert!(p.iter().enumerate().all(|(t, &c)| (c, t) != (2, 2)));
        // The goal may be kept only from step 7 on: the path ends there, on the goal.
        let late = Query {
            rest_from: 7,
            ..query(0, 4)
        };
        let p = search
            .run(&graph, &mut plain(&dist), &late, &mut 0)
            .unwrap();
        assert_eq!((p.len(), p[7]), (8, 4));
    }

    #[test]
    fn limits_end_searches_that_cannot_succeed() {
        // The goal is barred at every step: only the limits end the search.
        let grid = Grid::open(4, 3);
        let graph = MoveGraph::new(&grid, Connectivity::Four);
        let dist = graph.distances_from(11);
        let blocked = |limits| {
            let mut rules = Plain {
                barred: 11,
                ..plain(&dist)
            };
            let q = Query {
                limits,
                ..query(0, 11)
            };
            let mut expanded = 0;
            let end = Search::new().run(&graph, &mut rules, &q, &mut expanded);
            (end, expanded)
        };
        let still = Limits {
            still_from: 6,
            ..Limits::default()
        };
        assert_eq!(blocked(still).0, Err(Stop::Exhausted));
        let last = Limits {
            last_step: 20,
            ..Limits::default()
        };
        assert_eq!(blocked(last).0, Err(Stop::Exhausted));
        let capped = Limits {
            node_limit: 50,
            ..Limits::default()
        };
        assert_eq!(blocked(capped), (Err(Stop::Budget), 51));
    }

    #[test]
    fn arrive_by_keeps_paths_short_whatever_they_cost() {
        // Tolls make the straight row dear; without a bound the robot detours by the next row.
        let grid = Grid::open(6, 2);
        let graph = MoveGraph::new(&grid, Connectivity::Four);
        let dist = graph.distances_from(5);
        let mut toll = vec![0; 12];
        toll[2] = 10;
        toll[3] = 10;
        let mut search = Search::new();
        let mut rules = Plain {
            toll: toll.clone(),
            ..plain(&dist)
        };
        let free = search
            .run(&graph, &mut rules, &query(0, 5), &mut 0)
            .unwrap();
        assert_eq!(free.len(), 8);
        let tight = Query {
            limits: Limits {
                arrive_by: 5,
                ..Limits::default()
            },
            ..query(0, 5)
        };
        let mut rules = Plain {
            toll,
            ..plain(&dist)
        };
        let short = search.run(&graph, &mut rules, &tight, &mut 0).unwrap();
        assert_eq!(short, vec![0, 1, 2, 3, 4, 5]);
    }

    #[test]
    fn unit_steps_change_the_work_but_no_path() {
        // Among moving obstacles, with and without merging, marking states when generated
        // finds the same paths after the same expansions as marking them when expanded.
        use rand::{Rng, SeedableRng};
        let grid = walled();
        let graph = MoveGraph::new(&grid, Connectivity::Eight);
        let free: Vec<u32> = (0..grid.len() as u32)
            .filter(|&c| grid.is_free(Cell(c)))
            .collect();
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(7);
        let (mut found, mut failed) = (0, 0);
        for k in 0..200 {
            let (start, goal) = (
                free[rng.gen_range(0..free.len())],
                free[rng.gen_range(0..free.len())],
            );
            let dist = graph.distances_from(goal);
            let mut held = FxHashMap::default();
            for t in 1..30 {
                for &c in &free {
                    if c != start && rng.gen_bool(0.2) {
                        held.insert((c, t), ());
                    }
                }
            }
            let q = Query {
                rest_from: rng.gen_range(0..20),
                limits: Limits {
                    still_from: if k % 2 == 0 { 12 } else { 30 },
                    node_limit: 5000,
                    ..Limits::default()
                },
                ..query(start, goal)
            };
            let rules = || Plain {
                held: held.clone(),
                ..plain(&dist)
            };
            let (mut a, mut b) = (0, 0);
            let by_expansion = Search::new().run(&graph, &mut rules(), &q, &mut a);
            let by_generation = Search::new().run(&graph, &mut Unit(rules()), &q, &mut b);
            assert_eq!((&by_expansion, a), (&by_generation, b), "case {k}");
            if by_expansion.is_ok() {
                found += 1;
            } else {
                failed += 1;
            }
        }
        assert!(found >= 20 && failed >= 5, "{found} found, {failed} failed");
    }

    #[test]
    fn the_rank_breaks_ties() {
        // From one corner of a 2×2 square to the other: two equal paths, by cell 1 or cell 2.
        let grid = Grid::open(2, 2);
        let graph = MoveGraph::new(&grid, Connectivity::Four);
        let dist = graph.distances_from(3);
        let low = Search::new()
            .run(&graph, &mut plain(&dist), &query(0, 3), &mut 0)
            .unwrap();
        let high = Search::new()
            .run(&graph, &mut HighCell(plain(&dist)), &query(0, 3), &mut 0)
            .unwrap();
        assert_eq!((low, high), (vec![0, 1, 3], vec![0, 2, 3]));
    }

    #[test]
    fn an_unreachable_goal_is_exhausted_at_once() {
        let mut grid = Grid::open(3, 1);
        grid.set_blocked(Cell(1), true);
        let graph = MoveGraph::new(&grid, Connectivity::Four);
        let dist = graph.distances_from(2);
        let mut expanded = 0;
        let end = Search::new().run(&graph, &mut plain(&dist), &query(0, 2), &mut expanded);
        assert_eq!((end, expanded), (Err(Stop::Exhausted), 0));
    }
}
