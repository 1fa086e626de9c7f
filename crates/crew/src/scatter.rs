//! Guide paths that spread robots out in space and time (after the space utilisation
//! optimisation of Okumura, "Engineering LaCAM*", AAMAS 2024, in our own terms).
//!
//! Each robot gets a path to its goal no longer than its shortest path plus `margin`, chosen to
//! meet the other robots' guide paths as little as possible: space-time A* where a step costs
//! one plus `weight` for every robot already on the cell at that step, or crossing it along the
//! edge. Robots are routed one by one, twice, each time around everyone else's latest path.
//! The paths are only advice for PIBT ([`crate::pibt::Pibt::set_guide`]): nothing here needs
//! to be collision-free, and LaCAM stays complete whatever the advice.
//! O(passes · n · S log S) for n robots and S states searched per robot (bounded by `cap`).

use crate::moves::{MoveGraph, NIL};
use crate::outcome::Budget;
use rustc_hash::{FxHashMap, FxHashSet};
use std::cmp::Reverse;
use std::collections::BinaryHeap;

/// Guide paths for robots from `starts` to `goals` (`dist[i]`: step distances to goal i); a
/// robot whose search finds nothing within `cap` states keeps its plain shortest path.
pub fn guide_paths(
    graph: &MoveGraph,
    dist: &[Vec<u32>],
    starts: &[u32],
    goals: &[u32],
    (margin, weight, cap): (u32, u32, usize),
    budget: &Budget,
) -> Vec<Vec<u32>> {
    let n = starts.len();
    let mut paths: Vec<Vec<u32>> = (0..n)
        .map(|i| shortest(graph, &dist[i], starts[i], goals[i]))
        .collect();
    let mut table = Usage::default();
    for p in &paths {
        table.add(p, 1);
    }
    for _pass in 0..2 {
        for i in 0..n {
            if budget.out_of_time() {
                return paths;
            }
            table.add(&paths[i], -1);
            if let Some(p) = route(
                graph, &dist[i], starts[i], goals[i], &table, margin, weight, cap,
            ) {
                paths[i] = p;
            }
            table.add(&paths[i], 1);
        }
    }
    paths
}

/// Robots on each (cell, step) and along each (edge, step) of the guide paths.
#[derive(Default)]
struct Usage {
    at: FxHashMap<u64, u32>,
    along: FxHashMap<(u32, u32, u32), u32>,
}

impl Usage {
    fn add(&mut self, p: &[u32], by: i32) {
        for (t, &c) in p.iter().enumerate() {
            let e = self.at.entry(key(c, t as u32)).or_default();
            *e = e.wrapping_add_signed(by);
            if t + 1 < p.len() && p[t + 1] != c {
                let e = self.along.entry((c, p[t + 1], t as u32)).or_default();
                *e = e.wrapping_add_signed(by);
            }
        }
    }

    fn meets(&self, a: u32, b: u32, t: u32) -> u32 {
        let here = self.at.get(&key(b, t + 1)).copied().unwrap_or(0);
        let crossing = if a == b {
            0
        } else {
            self.along.get(&(b, a, t)).copied().unwrap_or(0)
        };
        here + crossing
    }
}

#[inline]
fn key(cell: u32, t: u32) -> u64 {
    (u64::from(t) << 32) | u64::from(cell)
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

#[allow(clippy::too_many_arguments)]
fn route(
    graph: &MoveGraph,
    dist: &[u32],
    start: u32,
    goal: u32,
    table: &Usage,
    margin: u32,
    weight: u32,
    cap: usize,
) -> Option<Vec<u32>> {
    let limit = dist[start as usize] + margin;
    let mut nodes: Vec<(u32, u32, u32)> = vec![(start, 0, NIL)];
    let mut open = BinaryHeap::from([(Reverse(dist[start as usize]), Reverse(0u32), 0u32)]);
    let mut closed: FxHashSet<u64> = FxHashSet::default();
    let mut cost: Vec<u32> = vec![0];
    while let Some((_, _, id)) = open.pop() {
        let (cell, t, _) = nodes[id as usize];
        if !closed.insert(key(cell, t)) {
            continue;
        }
        if cell == goal {
            let mut path = Vec::with_capacity(t as usize + 1);
            let mut x = id;
            while x != NIL {
                path.push(nodes[x as usize].0);
                x = nodes[x as usize].2;
            }
            path.reverse();
            return Some(path);
        }
        if closed.len() > cap {
            return None;
        }
        let g = cost[id as usize];
        for &next in std::iter::once(&cell).chain(graph.neighbours(cell)) {
            let h = dist[next as usize];
            if t + 1 + h > limit || closed.contains(&key(next, t + 1)) {
                continue;
            }
            let g2 = g + 1 + weight * table.meets(cell, next, t);
            let nid = nodes.len() as u32;
            nodes.push((next, t + 1, id));
            cost.push(g2);
            open.push((Reverse(g2 + h), Reverse(h), nid));
        }
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::grid::{Cell, Connectivity, Grid};
    use crate::moves::goal_distances;

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
        let paths = guide_paths(&m, &dist, &s, &t, (4, 3, 1000), &Budget::unlimited());
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
