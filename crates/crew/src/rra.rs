//! Reverse resumable A* (Silver 2005): true step distances *to* a goal, computed only as far as
//! they are asked for. A backward A* runs from the goal towards the robot's start; when a cell
//! not yet settled is asked for, the search resumes until it is. With a consistent heuristic
//! (Chebyshev under 8-connectivity, Manhattan under 4) every settled cell holds its exact
//! distance. This is the heuristic of space-time A*, at a fraction of a full breadth-first
//! table's cost on large maps.

use crate::distance::UNREACHABLE;
use crate::grid::{Cell, Connectivity, Grid};
use std::cmp::Ordering;
use std::collections::BinaryHeap;

#[derive(Clone, Debug, PartialEq, Eq)]
struct Node {
    f: u32,
    g: u32,
    cell: u32,
}
impl Ord for Node {
    fn cmp(&self, o: &Self) -> Ordering {
        o.f.cmp(&self.f)
            .then(self.g.cmp(&o.g))
            .then(o.cell.cmp(&self.cell))
    }
}
impl PartialOrd for Node {
    fn partial_cmp(&self, o: &Self) -> Option<Ordering> {
        Some(self.cmp(o))
    }
}

/// Step distances to one goal, settled on demand.
#[derive(Clone, Debug)]
pub struct GoalDistance {
    target: (u32, u32),
    conn: Connectivity,
    g: Vec<u32>,
    settled: Vec<bool>,
    open: BinaryHeap<Node>,
    expanded: u64,
}

impl GoalDistance {
    /// Starts a backward search from `goal`, aimed at `start`.
    pub fn new(grid: &Grid, conn: Connectivity, goal: Cell, start: Cell) -> Self {
        let mut d = GoalDistance {
            target: grid.xy(start),
            conn,
            g: vec![UNREACHABLE; grid.len()],
            settled: vec![false; grid.len()],
            open: BinaryHeap::new(),
            expanded: 0,
        };
        if grid.is_free(goal) {
            d.g[goal.0 as usize] = 0;
            let f = d.h(grid, goal);
            d.open.push(Node {
                f,
                g: 0,
                cell: goal.0,
            });
        }
        d
    }

    fn h(&self, grid: &Grid, c: Cell) -> u32 {
        let (x, y) = grid.xy(c);
        let dx = x.abs_diff(self.target.0);
        let dy = y.abs_diff(self.target.1);
        match self.conn {
            Connectivity::Four => dx + dy,
            Connectivity::Eight => dx.max(dy),
        }
    }

    /// Cells settled so far.
    pub fn expanded(&self) -> u64 {
        self.expanded
    }

    /// The fewest steps from `c` to the goal, or [`UNREACHABLE`].
    pub fn get(&mut self, grid: &Grid, c: Cell) -> u32 {
        let i = c.0 as usize;
        if self.settled[i] {
            return self.g[i];
        }
        while let Some(n) = self.open.pop() {
            let k = n.cell as usize;
            if self.settled[k] || n.g > self.g[k] {
                continue;
            }
            self.settled[k] = true;
            self.expanded += 1;
            let ng = n.g + 1;
            grid.for_each_move(Cell(n.cell), self.conn, |m, _| {
                let j = m.0 as usize;
                if !self.settled[j] && ng < self.g[j] {
                    self.g[j] = ng;
                    let f = ng + self.h(grid, m);
                    self.open.push(Node {
                        f,
                        g: ng,
                        cell: m.0,
                    });
                }
            });
            if k == i {
                return self.g[i];
            }
        }
        self.settled[i] = true;
        self.g[i] = UNREACHABLE;
        UNREACHABLE
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::distance::step_distances;

    #[test]
    fn equals_breadth_first_search_everywhere() {
        let mut grid = Grid::open(12, 9);
        for (x, y) in [
            (3, 0),
            (3, 1),
            (3, 2),
            (3, 3),
            (7, 8),
            (7, 7),
            (7, 6),
            (7, 5),
            (5, 4),
            (10, 2),
        ] {
            grid.set_blocked(grid.cell(x, y).unwrap(), true);
        }
        for conn in [Connectivity::Four, Connectivity::Eight] {
            let goal = grid.cell(11, 8).unwrap();
            let bfs = step_distances(&grid, conn, goal);
            let mut rra = GoalDistance::new(&grid, conn, goal, Cell(0));
            // Ask in an order unrelated to the search's own.
            for i in (0..grid.len() as u32)
                .rev()
                .step_by(7)
                .chain(0..grid.len() as u32)
            {
                assert_eq!(
                    rra.get(&grid, Cell(i)),
                    bfs[i as usize],
                    "cell {i} ({conn:?})"
                );
            }
        }
    }
}
