//! Priority inheritance with backtracking (PIBT; Okumura, Machida, Défago, Yokoo, AIJ 2022) as
//! a one-step configuration generator.
//!
//! Given where every robot stands now, PIBT chooses where each stands one step later. Robots
//! decide in priority order. A robot tries its cells (its own and its neighbours) nearest to its
//! goal first, ties broken by preferring a cell nobody stands on now, then at random. Taking a
//! cell another undecided robot stands on passes the taker's priority to that robot, which must
//! then move away (recursively); when it cannot, the taker backtracks to its next cell. A robot
//! that finds nothing stays.
//!
//! Here the step may also carry constraints (robot i must go to cell v), the low-level search of
//! LaCAM ([`crate::lacam`]); constrained robots decide first. Every step returned is legal under
//! `crew::validate`: no two robots on one cell, no swap along an edge, and (8-connected) no two
//! diagonal moves crossing inside one 2×2 square. When the constraints make that impossible the
//! step is refused, never repaired. O(n · d) per step for n robots and degree d, plus the
//! recursion, which visits each robot at most once.

use crate::moves::{MoveGraph, NIL};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// Reusable state of the generator: who stands where now and next.
pub struct Pibt<'a> {
    graph: &'a MoveGraph,
    dist: &'a [Vec<u32>],
    /// Per-robot distance tables that replace `dist` (detours), when set.
    detour: Vec<Option<Vec<u32>>>,
    occupied_now: Vec<u32>,
    occupied_next: Vec<u32>,
    rng: ChaCha8Rng,
}

impl<'a> Pibt<'a> {
    /// A generator for robots whose step distances to their goals are `dist[i]`.
    pub fn new(graph: &'a MoveGraph, dist: &'a [Vec<u32>], seed: u64) -> Self {
        Pibt {
            graph,
            dist,
            detour: vec![None; dist.len()],
            occupied_now: vec![NIL; graph.cells()],
            occupied_next: vec![NIL; graph.cells()],
            rng: ChaCha8Rng::seed_from_u64(seed),
        }
    }

    /// Makes robot `i` follow `table` (step distances to its goal on some detour) instead of
    /// its true distances, or its true distances again with `None`.
    pub fn set_detour(&mut self, i: usize, table: Option<Vec<u32>>) {
        self.detour[i] = table;
    }

    /// Fills `to` with one legal step from `from`: constrained robots go where `constraints`
    /// say, the others decide in `order`. Returns false (and leaves `to` unspecified) when no
    /// legal step meets the constraints this way.
    pub fn step(
        &mut self,
        from: &[u32],
        to: &mut [u32],
        order: &[u32],
        constraints: &[(u32, u32)],
    ) -> bool {
        for (i, &v) in from.iter().enumerate() {
            self.occupied_now[v as usize] = i as u32;
        }
        to.fill(NIL);
        let ok = self.constrain(from, to, constraints) && {
            for &i in order {
                if to[i as usize] == NIL {
                    self.push(i, from, to);
                }
            }
            self.legal(from, to)
        };
        for (&v, &u) in from.iter().zip(to.iter()) {
            self.occupied_now[v as usize] = NIL;
            if u != NIL {
                self.occupied_next[u as usize] = NIL;
            }
        }
        ok
    }

    fn constrain(&mut self, from: &[u32], to: &mut [u32], constraints: &[(u32, u32)]) -> bool {
        for &(i, u) in constraints {
            let v = from[i as usize];
            if self.occupied_next[u as usize] != NIL || self.clashes(v, u, to) {
                return false;
            }
            to[i as usize] = u;
            self.occupied_next[u as usize] = i;
        }
        true
    }

    /// Whether moving `v → u` swaps with, or crosses, a robot that has already decided.
    #[inline]
    fn clashes(&self, v: u32, u: u32, to: &[u32]) -> bool {
        if u == v {
            return false;
        }
        let j = self.occupied_now[u as usize];
        if j != NIL && to[j as usize] == v {
            return true;
        }
        if let Some((c, d)) = self.graph.corners(v, u) {
            for (x, y) in [(c, d), (d, c)] {
                let k = self.occupied_now[x as usize];
                if k != NIL && to[k as usize] == y {
                    return true;
                }
            }
        }
        false
    }

    /// PIBT for robot `i`: true when it moved (or stayed) without pushing anyone into a dead end.
    fn push(&mut self, i: u32, from: &[u32], to: &mut [u32]) -> bool {
        let v = from[i as usize];
        let dist = self.detour[i as usize]
            .as_deref()
            .unwrap_or(&self.dist[i as usize]);
        let mut cand = [(0u32, 0u32, 0u32, 0u32); 9];
        let mut len = 0;
        for &u in std::iter::once(&v).chain(self.graph.neighbours(v)) {
            let busy = u32::from(self.occupied_now[u as usize] != NIL && u != v);
            cand[len] = (dist[u as usize], busy, self.rng.gen::<u32>(), u);
            len += 1;
        }
        let cand = &mut cand[..len];
        cand.sort_unstable();
        for &(_, _, _, u) in cand.iter() {
            if self.occupied_next[u as usize] != NIL || self.clashes(v, u, to) {
                continue;
            }
            to[i as usize] = u;
            self.occupied_next[u as usize] = i;
            let j = self.occupied_now[u as usize];
            if j != NIL && j != i && to[j as usize] == NIL && !self.push(j, from, to) {
                continue;
            }
            return true;
        }
        to[i as usize] = v;
        self.occupied_next[v as usize] = i;
        false
    }

    /// The final check: one robot per cell, no swaps, no crossings.
    fn legal(&self, from: &[u32], to: &[u32]) -> bool {
        to.iter()
            .enumerate()
            .all(|(i, &u)| self.occupied_next[u as usize] == i as u32)
            && from.iter().zip(to).all(|(&v, &u)| !self.clashes(v, u, to))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::grid::{Connectivity, Grid};
    use crate::moves::goal_distances;
    use crate::Cell;

    #[test]
    fn a_robot_on_the_way_is_pushed_aside() {
        // A corridor with one side pocket: robot 0 must pass robot 1, resting on its goal, which
        // gives way (into the pocket or ahead) because robot 0 has the higher priority.
        let mut g = Grid::new(5, 2, vec![true; 10]);
        for x in 0..5 {
            g.set_blocked(g.cell(x, 0).unwrap(), false);
        }
        g.set_blocked(g.cell(2, 1).unwrap(), false);
        let m = MoveGraph::new(&g, Connectivity::Four);
        let c = |x, y| g.cell(x, y).unwrap().0;
        let goals = [Cell(c(3, 0)), Cell(c(2, 0))];
        let dist = goal_distances(&g, Connectivity::Four, &goals);
        let mut p = Pibt::new(&m, &dist, 1);
        let mut q = vec![c(1, 0), c(2, 0)];
        let mut next = vec![0; 2];
        for _ in 0..8 {
            assert!(p.step(&q, &mut next, &[0, 1], &[]));
            std::mem::swap(&mut q, &mut next);
        }
        assert_eq!(q[0], c(3, 0));
    }
}
