//! Guide paths that spread robots out in space and time (after the space utilisation
//! optimisation of Okumura, "Engineering LaCAM*", AAMAS 2024, in our own terms).
//!
//! Each robot gets a path to its goal no longer than its shortest path plus `margin`, chosen to
//! meet the other robots' guide paths as little as possible: space-time A*
//! ([`crate::spacetime`]) where a step costs one plus `weight` for every robot already on the
//! cell at that step, or crossing it along the edge. Robots are routed one by one, twice, each
//! time around everyone else's latest path.
//! The paths are only advice for PIBT ([`crate::pibt::Pibt::set_guide`]): nothing here needs
//! to be collision-free, and LaCAM stays complete whatever the advice.
//! O(passes · n · S log S) for n robots and S states searched per robot (bounded by `cap`).

use crate::moves::MoveGraph;
use crate::outcome::Budget;
use crate::spacetime::{key, Limits, Open, Query, Rules, Search};
use rustc_hash::FxHashMap;
use std::cmp::Reverse;

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
    let mut search = Search::new();
    for _pass in 0..2 {
        for i in 0..n {
            if budget.out_of_time() {
                return paths;
            }
            table.add(&paths[i], -1);
            let crowd = Crowd {
                usage: &table,
                dist: &dist[i],
                weight,
            };
            if let Some(p) = route(
                &mut search,
                graph,
                crowd,
                (starts[i], goals[i]),
                margin,
                cap,
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

/// The order of open states: least f first, then nearest the goal, then the last generated.
type Rank = (Reverse<u32>, Reverse<u32>, u32);

/// The rules of the guide search for one robot: its step distances `dist` to the goal, and a
/// step costs one plus `weight` for every other robot met (`usage`).
struct Crowd<'a> {
    usage: &'a Usage,
    dist: &'a [u32],
    weight: u32,
}

impl Rules for Crowd<'_> {
    type Rank = Rank;

    #[inline]
    fn rank(s: Open) -> Rank {
        (Reverse(s.f), Reverse(s.h), s.id)
    }

    #[inline]
    fn id(r: &Rank) -> u32 {
        r.2
    }

    #[inline]
    fn distance(&mut self, cell: u32) -> u32 {
        self.dist[cell as usize]
    }

    #[inline]
    fn step(&self, from: u32, to: u32, t: u32) -> Option<u32> {
        Some(1 + self.weight * self.usage.meets(from, to, t))
    }
}

/// The least crowded path from `start` to `goal` at most `margin` steps longer than the
/// shortest; `None` when the search expands more than `cap` states before its goal.
fn route(
    search: &mut Search<Rank>,
    graph: &MoveGraph,
    mut crowd: Crowd,
    (start, goal): (u32, u32),
    margin: u32,
    cap: usize,
) -> Option<Vec<u32>> {
    let query = Query {
        start,
        goal,
        rest_from: 0,
        limits: Limits {
            arrive_by: crowd.dist[start as usize] + margin,
            // The goal is tested before the cap: the goal may be the cap's next state.
            node_limit: (cap as u64).saturating_add(1),
            ..Limits::default()
        },
    };
    search.run(graph, &mut crowd, &query, &mut 0).ok()
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
