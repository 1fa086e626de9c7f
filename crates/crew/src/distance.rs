//! Single-source distances on the grid: breadth-first search in time steps (every move, straight
//! or diagonal, takes one step) and Dijkstra in path length (diagonal √2). These are the oracle
//! for A* in tests, the heuristic of space-time A*, and the costs of `path` assignment.
//! Both are O(V log V) or better in the number of free cells.

use crate::grid::{Cell, Connectivity, Grid};
use std::cmp::Ordering;
use std::collections::{BinaryHeap, VecDeque};

/// Marks a cell no path reaches.
pub const UNREACHABLE: u32 = u32::MAX;

/// Fewest time steps from `source` to every cell (moves are symmetric, so this is also the
/// distance *to* `source`). Blocked or unreachable cells hold [`UNREACHABLE`].
pub fn step_distances(grid: &Grid, conn: Connectivity, source: Cell) -> Vec<u32> {
    let mut dist = vec![UNREACHABLE; grid.len()];
    if !grid.is_free(source) {
        return dist;
    }
    dist[source.0 as usize] = 0;
    let mut queue = VecDeque::from([source]);
    while let Some(c) = queue.pop_front() {
        let d = dist[c.0 as usize] + 1;
        grid.for_each_move(c, conn, |n, _| {
            let slot = &mut dist[n.0 as usize];
            if *slot == UNREACHABLE {
                *slot = d;
                queue.push_back(n);
            }
        });
    }
    dist
}

#[derive(PartialEq)]
struct Entry(f64, u32);
impl Eq for Entry {}
impl Ord for Entry {
    fn cmp(&self, other: &Self) -> Ordering {
        other.0.total_cmp(&self.0).then(other.1.cmp(&self.1))
    }
}
impl PartialOrd for Entry {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}

/// Shortest path length (straight 1, diagonal √2) from `source` to every cell;
/// `f64::INFINITY` where unreachable.
pub fn path_lengths(grid: &Grid, conn: Connectivity, source: Cell) -> Vec<f64> {
    let mut dist = vec![f64::INFINITY; grid.len()];
    if !grid.is_free(source) {
        return dist;
    }
    dist[source.0 as usize] = 0.0;
    let mut heap = BinaryHeap::from([Entry(0.0, source.0)]);
    while let Some(Entry(d, c)) = heap.pop() {
        if d > dist[c as usize] {
            continue;
        }
        grid.for_each_move(Cell(c), conn, |n, diagonal| {
            let nd = d + if diagonal {
                std::f64::consts::SQRT_2
            } else {
                1.0
            };
            if nd < dist[n.0 as usize] {
                dist[n.0 as usize] = nd;
                heap.push(Entry(nd, n.0));
            }
        });
    }
    dist
}
