//! A* on the grid (Hart, Nilsson, Raphael 1968) with the octile heuristic (Manhattan under
//! 4-connectivity). Straight moves cost 1 and diagonal moves √2, so the path is a shortest one
//! in length; ties in f go to the larger g, then to the smaller cell index.
//! Optimal, since the heuristic is consistent; O(V log V) in the free cells.

use crate::grid::{Cell, Connectivity, Grid};
use std::cmp::Ordering;
use std::collections::BinaryHeap;

/// A path on the grid.
#[derive(Clone, Debug, PartialEq)]
pub struct GridPath {
    /// The cells from start to goal, both included; consecutive cells are one move apart.
    pub cells: Vec<Cell>,
    /// Length: straight moves 1, diagonal √2.
    pub length: f64,
}

#[derive(PartialEq)]
struct Node {
    f: f64,
    g: f64,
    cell: u32,
}
impl Eq for Node {}
impl Ord for Node {
    fn cmp(&self, o: &Self) -> Ordering {
        o.f.total_cmp(&self.f)
            .then(self.g.total_cmp(&o.g))
            .then(o.cell.cmp(&self.cell))
    }
}
impl PartialOrd for Node {
    fn partial_cmp(&self, o: &Self) -> Option<Ordering> {
        Some(self.cmp(o))
    }
}

/// A shortest path from `start` to `goal`, or `None` when the goal cannot be reached.
/// Also returns the number of cells expanded.
pub fn astar(grid: &Grid, conn: Connectivity, start: Cell, goal: Cell) -> (Option<GridPath>, u64) {
    if !grid.is_free(start) || !grid.is_free(goal) {
        return (None, 0);
    }
    let mut g = vec![f64::INFINITY; grid.len()];
    let mut parent = vec![u32::MAX; grid.len()];
    let mut closed = vec![false; grid.len()];
    let mut open = BinaryHeap::new();
    g[start.0 as usize] = 0.0;
    open.push(Node {
        f: grid.octile(start, goal, conn),
        g: 0.0,
        cell: start.0,
    });
    let mut expanded = 0;
    while let Some(Node { g: gc, cell, .. }) = open.pop() {
        if closed[cell as usize] {
            continue;
        }
        closed[cell as usize] = true;
        expanded += 1;
        if cell == goal.0 {
            let mut cells = vec![goal];
            let mut c = cell;
            while c != start.0 {
                c = parent[c as usize];
                cells.push(Cell(c));
            }
            cells.reverse();
            return (Some(GridPath { cells, length: gc }), expanded);
        }
        grid.for_each_move(Cell(cell), conn, |n, diagonal| {
            let ng = gc
                + if diagonal {
                    std::f64::consts::SQRT_2
                } else {
                    1.0
                };
            let i = n.0 as usize;
            if !closed[i] && ng < g[i] - 1e-12 {
                g[i] = ng;
                parent[i] = cell;
                open.push(Node {
                    f: ng + grid.octile(n, goal, conn),
                    g: ng,
                    cell: n.0,
                });
            }
        });
    }
    (None, expanded)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::distance::path_lengths;

    #[test]
    fn goes_around_a_wall() {
        let mut grid = Grid::open(5, 5);
        for y in 0..4 {
            grid.set_blocked(grid.cell(2, y).unwrap(), true);
        }
        let s = grid.cell(0, 0).unwrap();
        let t = grid.cell(4, 0).unwrap();
        for conn in [Connectivity::Four, Connectivity::Eight] {
            let (p, _) = astar(&grid, conn, s, t);
            let p = p.unwrap();
            assert!((p.length - path_lengths(&grid, conn, s)[t.0 as usize]).abs() < 1e-9);
            assert!(p.cells.windows(2).all(|w| grid.is_move(w[0], w[1], conn)));
        }
    }

    #[test]
    fn unreachable_is_none() {
        let mut grid = Grid::open(3, 1);
        grid.set_blocked(Cell(1), true);
        assert_eq!(astar(&grid, Connectivity::Eight, Cell(0), Cell(2)).0, None);
    }
}
