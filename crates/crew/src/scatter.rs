//! Guide paths that spread robots out in space and time (after the space utilisation
//! optimisation of Okumura, "Engineering LaCAM*", AAMAS 2024, in our own terms).
//!
//! Each robot gets a simple path (no waits, no cell twice) to its goal no longer than its
//! shortest path plus `margin`, chosen to meet the other robots' guide paths as little as
//! possible: a search over cells, each cell settled once, that ranks a partial path first by
//! the robots it meets (on the same cell at the same step, crossing it along an edge, or resting
//! on their goals for good), then
//! by its length plus the step distance left, then nearest the goal, then by cell. Meeting
//! fewer robots comes first, whatever the detour within the margin. Robots are routed one by
//! one in a seeded random order, each around everyone else's latest path, in passes: at least
//! two, and more while the meetings of a pass keep falling (at most [`MAX_PASSES`]).
//! The paths are only advice for PIBT ([`crate::pibt::Pibt::set_guide`]): nothing here needs
//! to be collision-free, and LaCAM stays complete whatever the advice.
//!
//! The first version searched space-time states with a step costing one plus two per robot
//! met, and did not count robots resting on their goals; ranking meetings first and counting
//! the resting robots spreads the robots much more. LaCAM's first plan, sum of costs, before
//! and after (`--refine-rounds 0 --time-limit 10`, seed 0, 4-connected, random-1, this 2-core
//! machine, 2026-11-26): warehouse-10-20-10-2-1 500 agents 68 097 → 51 340, 1000 agents
//! 195 818 → 151 563; den520d 1000 211 437 → 175 186; Boston_0_256 1000 230 593 → 198 218;
//! room-64-64-8 300 30 640 → 29 691; empty-32-32 512 21 363 → 20 291. Worse on the small
//! dense maps: random-32-32-20 409 47 984 → 54 204, room-32-32-4 341 35 166 → 36 710.
//! O(passes · n · V log V) for n robots, V cells within the margin of each robot's shortest
//! paths.

use crate::moves::{MoveGraph, NIL};
use crate::outcome::Budget;
use rand::seq::SliceRandom;
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use std::cmp::Reverse;
use std::collections::BinaryHeap;

/// Passes over all robots at most.
pub const MAX_PASSES: usize = 8;

/// Guide paths for robots from `starts` to `goals` (`dist[i]`: step distances to goal i),
/// each at most `margin` steps longer than the shortest; the order of each pass comes from
/// `seed`. Stops early (keeping the paths it has) when the budget runs out.
pub fn guide_paths(
    graph: &MoveGraph,
    dist: &[Vec<u32>],
    starts: &[u32],
    goals: &[u32],
    margin: u32,
    budget: &Budget,
    seed: u64,
) -> Vec<Vec<u32>> {
    let n = starts.len();
    let mut paths: Vec<Vec<u32>> = (0..n)
        .map(|i| shortest(graph, &dist[i], starts[i], goals[i]))
        .collect();
    let mut table = Usage::new(graph.cells());
    for p in &paths {
        table.add(p, 1);
    }
    let mut rng = ChaCha8Rng::seed_from_u64(seed ^ 0x5ca7_7e12);
    let mut order: Vec<usize> = (0..n).collect();
    let mut search = Spread::new(graph.cells());
    let mut before = u64::MAX;
    for pass in 0..MAX_PASSES {
        order.shuffle(&mut rng);
        let mut met = 0u64;
        for &i in &order {
            if budget.out_of_time() {
                return paths;
            }
            table.add(&paths[i], -1);
            let ub = dist[i][starts[i] as usize].saturating_add(margin);
            if let Some((p, m)) = search.run(graph, &table, &dist[i], (starts[i], goals[i]), ub) {
                paths[i] = p;
                met += u64::from(m);
            }
            table.add(&paths[i], 1);
        }
        if met == 0 || (pass >= 1 && met >= before) {
            break;
        }
        before = met;
    }
    paths
}

/// The guide paths by cell: each visit of a cell with the step and the cell moved to next, and
/// the step from which each robot rests on its goal. One short list per cell, scanned whole:
/// far fewer cache misses than hash maps keyed by (cell, step), which took half the time of
/// the guide paths on 1000 robots.
pub(crate) struct Usage {
    /// cell → (step, next cell, or `NIL` at the path's last step) of every visit.
    visits: Vec<Vec<(u32, u32)>>,
    /// goal cell → the last steps of the paths ending there.
    resting: Vec<Vec<u32>>,
}

impl Usage {
    /// No paths, on `cells` cells.
    pub(crate) fn new(cells: usize) -> Self {
        Usage {
            visits: vec![Vec::new(); cells],
            resting: vec![Vec::new(); cells],
        }
    }

    /// Adds path `p` (`by` > 0) or takes it away (`by` ≤ 0; it must have been added).
    pub(crate) fn add(&mut self, p: &[u32], by: i32) {
        let (goal, last) = (p[p.len() - 1], p.len() as u32 - 1);
        let here = &mut self.resting[goal as usize];
        if by > 0 {
            here.push(last);
        } else if let Some(k) = here.iter().position(|&l| l == last) {
            here.swap_remove(k);
        }
        for (t, &c) in p.iter().enumerate() {
            let visit = (t as u32, p.get(t + 1).copied().unwrap_or(NIL));
            let v = &mut self.visits[c as usize];
            if by > 0 {
                v.push(visit);
            } else if let Some(k) = v.iter().position(|&x| x == visit) {
                v.swap_remove(k);
            }
        }
    }

    /// The robots met moving from `a` at step `t` to `b` at step `t + 1`: on `b` then, coming
    /// the other way along the edge, or resting on `b` by then.
    pub(crate) fn meets(&self, a: u32, b: u32, t: u32) -> u32 {
        let mut met = 0;
        for &(s, next) in &self.visits[b as usize] {
            if s == t + 1 || (s == t && next == a && a != b) {
                met += 1;
            }
        }
        let rest = self.resting[b as usize]
            .iter()
            .filter(|&&last| t + 1 > last)
            .count() as u32;
        met + rest
    }
}

fn shortest(graph: &MoveGraph, dist: &[u32], start: u32, goal: u32) -> Vec<u32> {
    let mut p = vec![start];
    let mut c = start;
    while c != goal {
        c = *graph
            .neighbours(c)
            .iter()
            .min_by_key(|&&m| (dist[m as usize], m))
            .expect("a free cell with a path to the goal has a neighbour");
        p.push(c);
    }
    p
}

/// An open entry: (robots met, length plus distance left, distance left, cell, length,
/// previous cell); the least first.
type Entry = Reverse<(u32, u32, u32, u32, u32, u32)>;

/// The search over cells of one robot's guide path, with buffers kept from one robot to the
/// next.
struct Spread {
    /// The previous cell of each cell settled in the current search.
    parent: Vec<u32>,
    /// `stamp[c] == round`: cell c is settled in the current search.
    stamp: Vec<u32>,
    round: u32,
    open: BinaryHeap<Entry>,
}

impl Spread {
    fn new(cells: usize) -> Self {
        Spread {
            parent: vec![NIL; cells],
            stamp: vec![0; cells],
            round: 0,
            open: BinaryHeap::new(),
        }
    }

    /// The path from `start` to `goal` of at most `ub` steps that meets the fewest robots of
    /// `usage` (see the module), with the robots it meets; `None` when there is none.
    fn run(
        &mut self,
        graph: &MoveGraph,
        usage: &Usage,
        dist: &[u32],
        (start, goal): (u32, u32),
        ub: u32,
    ) -> Option<(Vec<u32>, u32)> {
        self.round = self.round.wrapping_add(1);
        if self.round == 0 {
            self.stamp.fill(0);
            self.round = 1;
        }
        self.open.clear();
        let d0 = dist[start as usize];
        if d0 == NIL || d0 > ub {
            return None;
        }
        self.open.push(Reverse((0, d0, d0, start, 0, NIL)));
        while let Some(Reverse((met, _, _, cell, g, from))) = self.open.pop() {
            if self.stamp[cell as usize] == self.round {
                continue;
            }
            self.stamp[cell as usize] = self.round;
            self.parent[cell as usize] = from;
            if cell == goal {
                let mut path = vec![cell];
                let mut c = from;
                while c != NIL {
                    path.push(c);
                    c = self.parent[c as usize];
                }
                path.reverse();
                return Some((path, met));
            }
            for &next in graph.neighbours(cell) {
                let h = dist[next as usize];
                if next == start
                    || h == NIL
                    || self.stamp[next as usize] == self.round
                    || g + 1 + h > ub
                {
                    continue;
                }
                let m = met + usage.meets(cell, next, g);
                self.open
                    .push(Reverse((m, g + 1 + h, h, next, g + 1, cell)));
            }
        }
        None
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::grid::{Cell, Connectivity, Grid};
    use crate::moves::goal_distances;

    #[test]
    fn a_guide_path_goes_around_a_robot_resting_on_its_goal() {
        // Robot 0 reaches its goal in the middle of an open 5×3 room at step 1 and rests there;
        // robot 1's shortest path along the middle row would cross it at step 2, so its guide
        // goes around (two steps longer, within the margin).
        let g = Grid::open(5, 3);
        let c = |x, y| g.cell(x, y).unwrap().0;
        let (starts, goals) = ([c(2, 0), c(0, 1)], [c(2, 1), c(4, 1)]);
        let m = MoveGraph::new(&g, Connectivity::Four);
        let goal_cells = [Cell(goals[0]), Cell(goals[1])];
        let dist = goal_distances(&g, Connectivity::Four, &goal_cells);
        let paths = guide_paths(&m, &dist, &starts, &goals, 4, &Budget::unlimited(), 0);
        assert_eq!(paths[0], vec![c(2, 0), c(2, 1)]);
        assert!(!paths[1].contains(&c(2, 1)), "{:?}", paths[1]);
        assert_eq!(paths[1].len(), 7);
        // Without the margin for the detour it has to cross.
        let tight = guide_paths(&m, &dist, &starts, &goals, 1, &Budget::unlimited(), 0);
        assert!(tight[1].contains(&c(2, 1)));
    }

    #[test]
    fn meetings_are_counted_as_defined_after_paths_come_and_go() {
        // Random walks on an open 6×5 grid; some are taken away again. For every move, the
        // count must be: walks on the target cell one step later, walks coming the other way
        // along the edge, and walks ending on the target cell by then.
        use rand::Rng;
        let g = Grid::open(6, 5);
        let m = MoveGraph::new(&g, Connectivity::Four);
        let mut rng = ChaCha8Rng::seed_from_u64(7);
        let walk = |rng: &mut ChaCha8Rng| {
            let mut p = vec![rng.gen_range(0..m.cells() as u32)];
            for _ in 0..rng.gen_range(0..12) {
                let c = p[p.len() - 1];
                let moves = m.neighbours(c);
                p.push(if rng.gen_bool(0.2) {
                    c
                } else {
                    moves[rng.gen_range(0..moves.len())]
                });
            }
            p
        };
        let mut usage = Usage::new(m.cells());
        let mut kept = Vec::new();
        for k in 0..60 {
            let p = walk(&mut rng);
            usage.add(&p, 1);
            if k % 3 == 0 {
                usage.add(&p, -1);
            } else {
                kept.push(p);
            }
        }
        let at = |p: &Vec<u32>, t: usize| p[t.min(p.len() - 1)];
        for a in 0..m.cells() as u32 {
            for &b in m.neighbours(a).iter().chain([a].iter()) {
                for t in 0..14u32 {
                    let want = kept
                        .iter()
                        .map(|p| {
                            let on = (t as usize + 1 < p.len() && p[t as usize + 1] == b) as u32;
                            let crossing = (a != b
                                && (t as usize + 1) < p.len()
                                && p[t as usize] == b
                                && p[t as usize + 1] == a)
                                as u32;
                            let resting =
                                (at(p, usize::MAX) == b && t + 1 > p.len() as u32 - 1) as u32;
                            on + crossing + resting
                        })
                        .sum::<u32>();
                    assert_eq!(usage.meets(a, b, t), want, "{a} → {b} at {t}");
                }
            }
        }
    }

    #[test]
    fn guide_paths_meet_fewer_robots_than_shortest_paths() {
        let grid = crate::generate::warehouse(40, 30, 0.05, 2);
        let (robots, goals) = crate::generate::random_tasks(&grid, 60, 3);
        let m = MoveGraph::new(&grid, Connectivity::Four);
        let dist = goal_distances(&grid, Connectivity::Four, &goals);
        let s: Vec<u32> = robots.iter().map(|c| c.0).collect();
        let t: Vec<u32> = goals.iter().map(|c| c.0).collect();
        let plain: Vec<Vec<u32>> = (0..s.len())
            .map(|i| shortest(&m, &dist[i], s[i], t[i]))
            .collect();
        let guided = guide_paths(&m, &dist, &s, &t, 10, &Budget::unlimited(), 1);
        let met = |paths: &[Vec<u32>]| -> u32 {
            (0..paths.len())
                .map(|i| {
                    let mut others = Usage::new(m.cells());
                    for (j, p) in paths.iter().enumerate() {
                        if j != i {
                            others.add(p, 1);
                        }
                    }
                    let p = &paths[i];
                    (0..p.len() - 1)
                        .map(|k| others.meets(p[k], p[k + 1], k as u32))
                        .sum::<u32>()
                })
                .sum()
        };
        for (i, p) in guided.iter().enumerate() {
            assert_eq!((p[0], p[p.len() - 1]), (s[i], t[i]));
            assert!(p.len() as u32 - 1 <= dist[i][s[i] as usize] + 10);
            let mut seen = p.clone();
            seen.sort_unstable();
            seen.dedup();
            assert_eq!(seen.len(), p.len(), "robot {i}: a cell twice");
        }
        let (a, b) = (met(&plain), met(&guided));
        assert!(b < a, "guided {b} meetings, shortest {a}");
    }

    #[test]
    fn guide_paths_are_walks_within_the_margin_and_spread_out() {
        // Two robots head-on along the top row of an open strip two rows deep: one of them is
        // routed along the bottom row, so the guides never meet.
        let g = Grid::open(8, 2);
        let c = |x, y| g.cell(x, y).unwrap();
        let (starts, goals) = ([c(0, 0), c(7, 0)], [c(6, 0), c(1, 0)]);
        let m = MoveGraph::new(&g, Connectivity::Four);
        let dist = goal_distances(&g, Connectivity::Four, &goals);
        let s: Vec<u32> = starts.iter().map(|c: &Cell| c.0).collect();
        let t: Vec<u32> = goals.iter().map(|c: &Cell| c.0).collect();
        let paths = guide_paths(&m, &dist, &s, &t, 4, &Budget::unlimited(), 0);
        for (i, p) in paths.iter().enumerate() {
            assert_eq!((p[0], p[p.len() - 1]), (s[i], t[i]));
            assert!(p.len() as u32 - 1 <= dist[i][s[i] as usize] + 4);
            for w in p.windows(2) {
                assert!(w[0] == w[1] || m.neighbours(w[0]).contains(&w[1]));
            }
        }
        let at = |p: &Vec<u32>, k: usize| p[k.min(p.len() - 1)];
        for k in 0..8 {
            assert_ne!(at(&paths[0], k), at(&paths[1], k), "step {k}");
            assert!(
                !(at(&paths[0], k) == at(&paths[1], k + 1)
                    && at(&paths[0], k + 1) == at(&paths[1], k)),
                "swap at step {k}"
            );
        }
    }
}
