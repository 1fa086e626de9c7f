//! Probabilistic roadmap (Kavraki, Švestka, Latombe, Overmars 1996), as the crew paper uses it.
//!
//! `samples` distinct free cells are drawn with a seeded ChaCha8 generator. Each is joined by
//! free straight segments (see [`crate::line`]) to its `neighbours` nearest reachable samples,
//! looking at up to 3·`neighbours` nearest candidates found with an R*-tree. A robot's start and goal join the roadmap the same way, A* on the
//! roadmap (Euclidean edge weights) finds a route, and the route is rasterised to grid moves.
//! Not complete and not optimal: with too few samples a reachable goal may be missed.
//! Building costs O(s·k·L) for s samples, k neighbours and segments of length L.

use crate::grid::{Cell, Connectivity, Grid};
use crate::line::{segment, segment_is_free};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rstar::primitives::GeomWithData;
use rstar::RTree;
use rustc_hash::FxHashSet;
use std::cmp::Ordering;
use std::collections::BinaryHeap;

/// Roadmap settings.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct PrmConfig {
    /// Number of random free cells sampled.
    pub samples: usize,
    /// Nearest samples each node tries to connect to.
    pub neighbours: usize,
    /// Seed of the sampler.
    pub seed: u64,
}

impl Default for PrmConfig {
    fn default() -> Self {
        PrmConfig {
            samples: 4000,
            neighbours: 10,
            seed: 0,
        }
    }
}

type Point = GeomWithData<[f64; 2], u32>;

/// Each node looks at up to this many times `neighbours` nearest samples to find `neighbours`
/// free connections; in a warehouse most of the very nearest samples lie behind a shelf.
const CANDIDATES: usize = 3;

/// A roadmap over the free cells of a grid.
#[derive(Clone, Debug)]
pub struct Roadmap {
    nodes: Vec<Cell>,
    edges: Vec<Vec<(u32, f64)>>,
    index: RTree<Point>,
    neighbours: usize,
}

fn point(grid: &Grid, c: Cell) -> [f64; 2] {
    let (x, y) = grid.xy(c);
    [x as f64, y as f64]
}

impl Roadmap {
    /// Samples and connects a roadmap.
    pub fn build(grid: &Grid, conn: Connectivity, config: PrmConfig) -> Roadmap {
        let mut rng = ChaCha8Rng::seed_from_u64(config.seed);
        let free: Vec<Cell> = (0..grid.len() as u32)
            .map(Cell)
            .filter(|c| grid.is_free(*c))
            .collect();
        let mut nodes = Vec::new();
        if config.samples >= free.len() {
            nodes = free;
        } else {
            let mut taken = FxHashSet::default();
            while nodes.len() < config.samples {
                let c = free[rng.gen_range(0..free.len())];
                if taken.insert(c) {
                    nodes.push(c);
                }
            }
        }
        let index = RTree::bulk_load(
            nodes
                .iter()
                .enumerate()
                .map(|(i, &c)| Point::new(point(grid, c), i as u32))
                .collect(),
        );
        let mut edges: Vec<Vec<(u32, f64)>> = vec![Vec::new(); nodes.len()];
        for (i, &c) in nodes.iter().enumerate() {
            let mut joined = 0;
            for near in index
                .nearest_neighbor_iter(&point(grid, c))
                .filter(|p| p.data as usize != i)
                .take(CANDIDATES * config.neighbours)
            {
                if joined == config.neighbours {
                    break;
                }
                let j = near.data as usize;
                if edges[i].iter().any(|&(k, _)| k as usize == j) {
                    joined += 1;
                    continue;
                }
                let (lo, hi) = (i.min(j), i.max(j));
                if segment_is_free(grid, conn, nodes[lo], nodes[hi]) {
                    let w = grid.euclidean(c, nodes[j]);
                    edges[i].push((j as u32, w));
                    edges[j].push((i as u32, w));
                    joined += 1;
                }
            }
        }
        for e in &mut edges {
            e.sort_by_key(|&(k, _)| k);
            e.dedup_by_key(|&mut (k, _)| k);
        }
        Roadmap {
            nodes,
            edges,
            index,
            neighbours: config.neighbours,
        }
    }

    /// Number of roadmap nodes.
    pub fn node_count(&self) -> usize {
        self.nodes.len()
    }

    /// Number of undirected roadmap edges.
    pub fn edge_count(&self) -> usize {
        self.edges.iter().map(Vec::len).sum::<usize>() / 2
    }

    /// A grid path from `start` to `goal` through the roadmap, or `None` when the roadmap does
    /// not connect them. Also returns the roadmap nodes expanded.
    pub fn path(
        &self,
        grid: &Grid,
        conn: Connectivity,
        start: Cell,
        goal: Cell,
    ) -> (Option<Vec<Cell>>, u64) {
        if start == goal {
            return (Some(vec![start]), 0);
        }
        if segment_is_free(grid, conn, start, goal) {
            let mut cells = vec![start];
            cells.extend(segment(grid, conn, start, goal).expect("free segment"));
            return (Some(cells), 0);
        }
        // Virtual nodes: n = start, n + 1 = goal.
        let n = self.nodes.len() as u32;
        let links = |c: Cell| -> Vec<(u32, f64)> {
            self.index
                .nearest_neighbor_iter(&point(grid, c))
                .take(CANDIDATES * self.neighbours)
                .filter(|p| segment_is_free(grid, conn, c, self.nodes[p.data as usize]))
                .take(self.neighbours)
                .map(|p| (p.data, grid.euclidean(c, self.nodes[p.data as usize])))
                .collect()
        };
        let from_start = links(start);
        let to_goal = links(goal);
        let cell_of = |i: u32| match i.cmp(&n) {
            Ordering::Less => self.nodes[i as usize],
            Ordering::Equal => start,
            Ordering::Greater => goal,
        };
        let h = |i: u32| grid.euclidean(cell_of(i), goal);
        let mut g: rustc_hash::FxHashMap<u32, (f64, u32)> = Default::default();
        let mut open = BinaryHeap::new();
        let mut closed = FxHashSet::default();
        g.insert(n, (0.0, u32::MAX));
        open.push(Entry(h(n), 0.0, n));
        let mut expanded = 0;
        while let Some(Entry(_, gc, i)) = open.pop() {
            if !closed.insert(i) {
                continue;
            }
            expanded += 1;
            if i == n + 1 {
                // Rasterise the chain of roadmap nodes.
                let mut chain = vec![i];
                let mut k = i;
                while k != n {
                    k = g[&k].1;
                    chain.push(k);
                }
                chain.reverse();
                let mut cells = vec![start];
                for w in chain.windows(2) {
                    let (a, b) = (cell_of(w[0]), cell_of(w[1]));
                    cells.extend(oriented_segment(grid, conn, (a, w[0]), (b, w[1]), n));
                }
                return (Some(cells), expanded);
            }
            let mut relax = |j: u32, w: f64| {
                let ng = gc + w;
                if g.get(&j).is_none_or(|&(old, _)| ng < old - 1e-12) {
                    g.insert(j, (ng, i));
                    open.push(Entry(ng + h(j), ng, j));
                }
            };
            if i == n {
                for &(j, w) in &from_start {
                    relax(j, w);
                }
            } else if i < n {
                for &(j, w) in &self.edges[i as usize] {
                    relax(j, w);
                }
                if let Some(&(_, w)) = to_goal.iter().find(|&&(j, _)| j == i) {
                    relax(n + 1, w);
                }
            }
        }
        (None, expanded)
    }
}

/// Rasterises `a → b` the way the link was checked: roadmap edges from the lower node index to
/// the higher; the start link start-first and the goal link goal-first (`start_id` is the
/// start's virtual id, the goal's is `start_id + 1`).
fn oriented_segment(
    grid: &Grid,
    conn: Connectivity,
    (a, ia): (Cell, u32),
    (b, ib): (Cell, u32),
    start_id: u32,
) -> Vec<Cell> {
    if a == b {
        return Vec::new();
    }
    let forward = if ia == start_id {
        true
    } else if ib == start_id + 1 {
        false
    } else {
        ia < ib
    };
    if forward {
        segment(grid, conn, a, b).expect("checked segment")
    } else {
        let mut back = segment(grid, conn, b, a).expect("checked segment");
        back.pop();
        back.reverse();
        back.push(b);
        back
    }
}

#[derive(PartialEq)]
struct Entry(f64, f64, u32);
impl Eq for Entry {}
impl Ord for Entry {
    fn cmp(&self, o: &Self) -> Ordering {
        o.0.total_cmp(&self.0)
            .then(self.1.total_cmp(&o.1))
            .then(o.2.cmp(&self.2))
    }
}
impl PartialOrd for Entry {
    fn partial_cmp(&self, o: &Self) -> Option<Ordering> {
        Some(self.cmp(o))
    }
}
