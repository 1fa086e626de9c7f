//! The move graph of a grid as flat adjacency lists, for the solvers that step many robots at
//! once ([`crate::pibt`], [`crate::lacam`], [`crate::refine`], [`crate::tswap`]). Cells keep their
//! grid indices; each free cell lists the cells one legal move away, exactly the moves of
//! [`Grid::for_each_move`] (diagonals only past two free sides). Also the rule that two
//! simultaneous diagonal moves may not cross inside one 2×2 square, as `crew::validate` checks.

use crate::grid::{Cell, Connectivity, Grid, MOVES};
use rayon::prelude::*;

/// Marks "no robot" or "no cell" in the solvers' dense arrays.
pub const NIL: u32 = u32::MAX;

/// Adjacency lists of the grid's legal moves (waiting excluded).
#[derive(Clone, Debug)]
pub struct MoveGraph {
    width: u32,
    offsets: Vec<u32>,
    targets: Vec<u32>,
    /// Each cell's moves again, one bit a direction of the grid's moves (`grid::MOVES`, as
    /// (dx, dy)): the breadth-first searches read a byte a cell instead of the lists and
    /// their offsets (the speed case's 500 tables in 0.92 of the time).
    steps: Vec<u8>,
}

impl MoveGraph {
    /// The moves of `grid` under `conn`. O(cells).
    pub fn new(grid: &Grid, conn: Connectivity) -> Self {
        Self::new_until(grid, conn, &|| false).expect("never stopped")
    }

    /// [`MoveGraph::new`], or `None` when `stop` says so (looked at every 65 536 cells).
    pub fn new_until(grid: &Grid, conn: Connectivity, stop: &dyn Fn() -> bool) -> Option<Self> {
        let mut offsets = Vec::with_capacity(grid.len() + 1);
        let mut targets = Vec::new();
        let mut steps = vec![0u8; grid.len()];
        let w = grid.width();
        offsets.push(0);
        for c in 0..grid.len() as u32 {
            if c % 65_536 == 0 && stop() {
                return None;
            }
            if grid.is_free(Cell(c)) {
                grid.for_each_move(Cell(c), conn, |n, _| {
                    targets.push(n.0);
                    let d = (
                        (n.0 % w) as i32 - (c % w) as i32,
                        (n.0 / w) as i32 - (c / w) as i32,
                    );
                    if let Some(k) = MOVES.iter().position(|&s| s == d) {
                        steps[c as usize] |= 1 << k;
                    }
                });
            }
            offsets.push(targets.len() as u32);
        }
        Some(MoveGraph {
            width: w,
            offsets,
            targets,
            steps,
        })
    }

    /// Number of cells (free or not).
    pub fn cells(&self) -> usize {
        self.offsets.len() - 1
    }

    /// The cells one move away from `c`.
    #[inline]
    pub fn neighbours(&self, c: u32) -> &[u32] {
        &self.targets[self.offsets[c as usize] as usize..self.offsets[c as usize + 1] as usize]
    }

    /// Fewest steps from `source` to every cell (moves are symmetric, so also to `source`);
    /// [`crate::distance::UNREACHABLE`] where no path goes. `source` must be free.
    /// Breadth-first search, O(cells).
    pub fn distances_from(&self, source: u32) -> Vec<u32> {
        self.distances_from_until(source, &|| false)
            .unwrap_or_default()
    }

    /// [`MoveGraph::distances_from`], or `None` when `stop` says so (looked at before the search
    /// and every 65 536 cells).
    pub fn distances_from_until(
        &self,
        source: u32,
        stop: &(dyn Fn() -> bool + Sync),
    ) -> Option<Vec<u32>> {
        self.distances_from_reusing(source, &mut Vec::new(), stop)
    }

    /// [`MoveGraph::distances_from_until`] with a caller's queue, kept between searches (one
    /// per thread when many tables are built), so that only the table itself is allocated.
    fn distances_from_reusing(
        &self,
        source: u32,
        queue: &mut Vec<u32>,
        stop: &(dyn Fn() -> bool + Sync),
    ) -> Option<Vec<u32>> {
        // Also before each search: on a map of fewer than 65 536 free cells the count below
        // never reaches a check, and a thousand tables would all be built past the deadline.
        if stop() {
            return None;
        }
        let mut dist = vec![NIL; self.cells()];
        dist[source as usize] = 0;
        queue.clear();
        queue.push(source);
        self.expand(&mut dist, queue, &mut 0, NIL, stop)?;
        Some(dist)
    }

    /// Goes on with a breadth-first search whose cells `queue` holds in the order found, the
    /// first `head` of them expanded, until every cell nearer than `depth` steps is expanded:
    /// then every cell within `depth` steps of the source has its distance in `dist`, and
    /// every cell beyond still has [`NIL`]. `None` when `stop` says so (every 65 536 cells).
    fn expand(
        &self,
        dist: &mut [u32],
        queue: &mut Vec<u32>,
        head: &mut usize,
        depth: u32,
        stop: &(dyn Fn() -> bool + Sync),
    ) -> Option<()> {
        let w = self.width as i32;
        let offset = MOVES.map(|(dx, dy)| dy * w + dx);
        while *head < queue.len() {
            let c = queue[*head];
            // In the order found, distances never fall: the rest are as far.
            if dist[c as usize] >= depth {
                break;
            }
            *head += 1;
            if *head % 65_536 == 0 && stop() {
                return None;
            }
            let d = dist[c as usize] + 1;
            let mut bits = self.steps[c as usize];
            while bits != 0 {
                let m = c.wrapping_add_signed(offset[bits.trailing_zeros() as usize]);
                bits &= bits - 1;
                if dist[m as usize] == NIL {
                    dist[m as usize] = d;
                    queue.push(m);
                }
            }
        }
        Some(())
    }

    /// For a diagonal move `a → b`, the two other corners of its 2×2 square; `None` for a
    /// straight move or a wait.
    #[inline]
    pub fn corners(&self, a: u32, b: u32) -> Option<(u32, u32)> {
        let (ax, ay) = (a % self.width, a / self.width);
        let (bx, by) = (b % self.width, b / self.width);
        (ax != bx && ay != by).then(|| (ay * self.width + bx, by * self.width + ax))
    }
}

/// Step distances to each of `goals`, one breadth-first search per goal, run on all cores.
/// The result does not depend on the number of threads. Memory: cells × goals × 4 bytes.
pub fn goal_distances(grid: &Grid, conn: Connectivity, goals: &[Cell]) -> Vec<Vec<u32>> {
    distances_to_goals(&MoveGraph::new(grid, conn), goals)
}

/// [`goal_distances`] on a move graph the caller has already built (on a large map the graph
/// is a good part of the setup's time and memory: build it once).
pub fn distances_to_goals(graph: &MoveGraph, goals: &[Cell]) -> Vec<Vec<u32>> {
    distances_to_goals_until(graph, goals, &|| false).unwrap_or_default()
}

/// [`distances_to_goals`], or `None` when `stop` says so before every table is done.
pub fn distances_to_goals_until(
    graph: &MoveGraph,
    goals: &[Cell],
    stop: &(dyn Fn() -> bool + Sync),
) -> Option<Vec<Vec<u32>>> {
    goals
        .par_iter()
        .map_init(Vec::new, |queue, &g| {
            graph.distances_from_reusing(g.0, queue, stop)
        })
        .collect()
}

/// Breadth-first searches from each of a set of goals that stop at a depth and go on later
/// (TSWAP's assignment needs the distances only up to its longest pair, see
/// [`crate::tswap::bottleneck_assignment`]): `dist[g]` holds the exact step distance to goal g
/// of every cell within the depth reached, [`NIL`] beyond and where no path goes.
pub struct GoalSearches {
    /// The distances found so far, one table a goal.
    pub dist: Vec<Vec<u32>>,
    /// Each search's cells in the order found, and how many of them are expanded.
    fronts: Vec<(Vec<u32>, usize)>,
}

impl GoalSearches {
    /// The searches from `goals`, each at its goal alone (depth 0).
    pub fn new(graph: &MoveGraph, goals: &[Cell]) -> Self {
        let dist = goals
            .iter()
            .map(|g| {
                let mut d = vec![NIL; graph.cells()];
                d[g.0 as usize] = 0;
                d
            })
            .collect();
        let fronts = goals.iter().map(|g| (vec![g.0], 0)).collect();
        GoalSearches { dist, fronts }
    }

    /// Every search taken on until each cell within `depth` steps of its goal has its distance,
    /// on all cores (each search alone: the tables do not depend on the cores). `None` when
    /// `stop` says so (before, and every 65 536 cells of a search).
    pub fn deepen(
        &mut self,
        graph: &MoveGraph,
        depth: u32,
        stop: &(dyn Fn() -> bool + Sync),
    ) -> Option<()> {
        self.dist
            .par_iter_mut()
            .zip(self.fronts.par_iter_mut())
            .try_for_each(|(dist, (queue, head))| {
                if stop() {
                    return None;
                }
                graph.expand(dist, queue, head, depth, stop)
            })
    }

    /// Whether every search has reached every cell it can: the tables are whole.
    pub fn whole(&self) -> bool {
        self.fronts.iter().all(|(queue, head)| *head == queue.len())
    }

    /// Search `g` taken on to every cell it can reach.
    pub fn finish(&mut self, graph: &MoveGraph, g: usize) {
        let (queue, head) = &mut self.fronts[g];
        graph.expand(&mut self.dist[g], queue, head, NIL, &|| false);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_search_cut_short_and_finished_is_the_whole_table() {
        let mut g = Grid::open(9, 7);
        for x in 0..8 {
            g.set_blocked(g.cell(x, 3).unwrap(), true);
        }
        g.set_blocked(g.cell(4, 5).unwrap(), true);
        for conn in [Connectivity::Four, Connectivity::Eight] {
            let m = MoveGraph::new(&g, conn);
            let goals = [g.cell(0, 0).unwrap(), g.cell(2, 6).unwrap()];
            let whole = distances_to_goals(&m, &goals);
            let mut s = GoalSearches::new(&m, &goals);
            for depth in [0, 1, 3, 6] {
                s.deepen(&m, depth, &|| false).expect("never stopped");
                for (cut, full) in s.dist.iter().zip(&whole) {
                    for (&a, &b) in cut.iter().zip(full) {
                        // Exact within the depth, nothing beyond.
                        assert_eq!(
                            a,
                            if b <= depth { b } else { NIL },
                            "{conn:?} depth {depth}"
                        );
                    }
                }
            }
            assert!(!s.whole());
            s.finish(&m, 1);
            assert_eq!(s.dist[1], whole[1]);
            assert_ne!(s.dist[0], whole[0]);
            s.deepen(&m, NIL, &|| false).expect("never stopped");
            assert!(s.whole());
            assert_eq!(s.dist, whole);
        }
    }

    #[test]
    fn lists_the_grids_moves() {
        let mut g = Grid::open(3, 3);
        g.set_blocked(g.cell(1, 0).unwrap(), true);
        let m = MoveGraph::new(&g, Connectivity::Eight);
        for c in 0..g.len() as u32 {
            let mut want: Vec<u32> = if g.is_free(Cell(c)) {
                g.moves(Cell(c), Connectivity::Eight)
                    .iter()
                    .map(|x| x.0 .0)
                    .collect()
            } else {
                vec![]
            };
            let mut got = m.neighbours(c).to_vec();
            want.sort_unstable();
            got.sort_unstable();
            assert_eq!(got, want, "cell {c}");
        }
        assert_eq!(m.corners(0, 4), Some((1, 3)));
        for c in [0, 2, 5, 8] {
            assert_eq!(
                m.distances_from(c),
                crate::distance::step_distances(&g, Connectivity::Eight, Cell(c))
            );
        }
        assert_eq!(m.corners(0, 1), None);
    }

    /// A random grid (about a third blocked, so some free cells are cut off) and its free cells.
    fn random_grid(w: u32, h: u32, seed: u64) -> (Grid, Vec<Cell>) {
        use rand::{Rng, SeedableRng};
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
        let blocked: Vec<bool> = (0..w * h).map(|_| rng.gen_bool(0.35)).collect();
        let g = Grid::new(w, h, blocked);
        let free = (0..g.len() as u32)
            .map(Cell)
            .filter(|&c| g.is_free(c))
            .collect();
        (g, free)
    }

    #[test]
    fn the_step_bits_are_the_lists_moves() {
        for seed in 0..4 {
            for conn in [Connectivity::Four, Connectivity::Eight] {
                let (g, _) = random_grid(19, 13, seed);
                let m = MoveGraph::new(&g, conn);
                for c in 0..g.len() as u32 {
                    let (x, y) = ((c % 19) as i32, (c / 19) as i32);
                    let mut stepped: Vec<u32> = (0..8)
                        .filter(|k| m.steps[c as usize] & (1 << k) != 0)
                        .map(|k| ((y + MOVES[k].1) * 19 + x + MOVES[k].0) as u32)
                        .collect();
                    let mut listed = m.neighbours(c).to_vec();
                    stepped.sort_unstable();
                    listed.sort_unstable();
                    assert_eq!(stepped, listed, "seed {seed}, {conn:?}, cell {c}");
                }
            }
        }
    }

    #[test]
    fn parallel_tables_equal_serial_breadth_first_search() {
        for seed in 0..6 {
            for conn in [Connectivity::Four, Connectivity::Eight] {
                let (g, free) = random_grid(23, 17, seed);
                let goals: Vec<Cell> = free.iter().copied().step_by(3).collect();
                let m = MoveGraph::new(&g, conn);
                let tables = distances_to_goals(&m, &goals);
                assert_eq!(tables.len(), goals.len());
                let mut unreachable = 0;
                for (t, &goal) in tables.iter().zip(&goals) {
                    let want = crate::distance::step_distances(&g, conn, goal);
                    assert_eq!(*t, want, "seed {seed}, {conn:?}, goal {goal:?}");
                    unreachable += t.iter().filter(|&&d| d == NIL).count();
                }
                // Blocked cells at least, and on these grids some cut-off free cells too.
                assert!(unreachable > 0);
                assert_eq!(goal_distances(&g, conn, &goals), tables);
            }
        }
    }

    #[test]
    fn tables_stop_when_told() {
        // The stop is looked at every 65 536 cells searched: an open 300×300 grid has 90 000.
        let g = Grid::open(300, 300);
        let m = MoveGraph::new(&g, Connectivity::Four);
        let goals: Vec<Cell> = (0..4).map(Cell).collect();
        assert!(distances_to_goals_until(&m, &goals, &|| true).is_none());
        assert!(distances_to_goals_until(&m, &goals, &|| false).is_some());
        // A small map is stopped too (before each table).
        let (g, free) = random_grid(20, 20, 2);
        let m = MoveGraph::new(&g, Connectivity::Four);
        assert!(distances_to_goals_until(&m, &free[..5], &|| true).is_none());
    }
}
