//! Priority inheritance with backtracking (PIBT; Okumura, Machida, Défago, Yokoo, AIJ 2022) as
//! a one-step configuration generator.
//!
//! Given where every robot stands now, PIBT chooses where each stands one step later. Robots
//! decide in priority order. A robot tries its cells (its own and its neighbours) nearest to its
//! goal first, ties broken by preferring a cell that hinders fewer others (fewer undecided
//! robots next to it would step onto it to get nearer their own goals; after the tie-breaking
//! study of Okumura and Nagai, SoCS 2025, in our own terms), then a cell nobody stands on now,
//! then at random. Taking a
//! cell another undecided robot stands on passes the taker's priority to that robot, which must
//! then move away (recursively); when it cannot, the taker backtracks to its next cell. A robot
//! that finds nothing stays.
//!
//! Corridors one cell wide defeat plain PIBT: two robots whose ways cross in a corridor push
//! each other to and fro for ever (the one ahead is pushed to its goal, which lies on the
//! other's way, or they face each other and take turns winning). Two rules, in our own terms
//! after the swap operation of LaCAM* (Okumura, IJCAI 2023), handle this:
//! - *swap*: when the robot on a robot's best cell cannot get out of its way by being pushed
//!   ahead (the corridor ahead ends, or ends with the two still wanting past each other), the
//!   robot backs off towards the nearest junction behind it and pulls the other after it;
//! - *no face-off*: a robot that is pushed does not, if it has any other choice, step ahead of
//!   its pusher into a cell where the two would face each other in that way again. Without
//!   this, the pair reaches the junction and the pulled robot walks straight back in.
//!
//! Both rules look along the corridor for a junction; a dead end where a robot rests on its own
//! goal does not count as a way on there (the robot has no reason to leave it). Without this,
//! a side pocket holding a settled robot looked like a place to pass, the swap was not tried,
//! and on MovingAI random-32-32-20 with 409 robots (random-1, seed 3) a few robots in short
//! corridors kept trading places: LaCAM's first descents took 749–4 607 configurations
//! (sum of costs 42 966–322 654) over six attempts, against 127–343 (26 187–32 044) with it.
//!
//! The rules only reorder a robot's choices; the step stays a PIBT step (and LaCAM stays
//! complete, whatever the generator proposes). They cost O(corridor length) per robot
//! pushed. On MovingAI's warehouse-10-20-10-2-1 (random-1, 4-connected) plain PIBT steps leave
//! about 150 of 1000 robots circling; with the two rules, 987 are home and LaCAM finishes the
//! rest in a few hundred configurations.
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
    occupied_now: Vec<u32>,
    occupied_next: Vec<u32>,
    rng: ChaCha8Rng,
    /// Whether the corridor rules are on (see [`Pibt::set_swap`]).
    swap: bool,
    /// Whether ties in distance go to the cell that hinders fewer others (see
    /// [`Pibt::set_hindrance`]).
    hindrance: bool,
    /// Whether the ties left go to a cell nobody stands on now (see [`Pibt::set_prefer_free`]).
    prefer_free: bool,
    /// Per robot, the next cell of its guide path from each cell on it (empty: none).
    guide: Vec<rustc_hash::FxHashMap<u32, u32>>,
}

impl<'a> Pibt<'a> {
    /// A generator for robots whose step distances to their goals are `dist[i]`.
    pub fn new(graph: &'a MoveGraph, dist: &'a [Vec<u32>], seed: u64) -> Self {
        Pibt {
            graph,
            dist,
            occupied_now: vec![NIL; graph.cells()],
            occupied_next: vec![NIL; graph.cells()],
            rng: ChaCha8Rng::seed_from_u64(seed),
            swap: true,
            hindrance: true,
            prefer_free: true,
            guide: Vec::new(),
        }
    }

    /// Turns the corridor rules (swap, no face-off; see the module) on (the default) or off,
    /// which leaves plain PIBT.
    pub fn set_swap(&mut self, on: bool) {
        self.swap = on;
    }

    /// Breaks ties between cells equally near the goal in favour of the cell fewer undecided
    /// neighbouring robots would step onto to get nearer their own goals (on), or only by
    /// occupancy and at random (off).
    pub fn set_hindrance(&mut self, on: bool) {
        self.hindrance = on;
    }

    /// Breaks the ties that the hindrance rule leaves in favour of a cell nobody stands on now
    /// (on, the default) or at random (off). Preferring free cells makes a pushed robot's
    /// choice the same every time the same robots meet, which can keep a knot of robots
    /// trading places for ever (on MovingAI random-32-32-20 with 409 robots it kept a few
    /// robots from their goals in most first descents); [`crate::restart`] runs half of its
    /// attempts without it.
    pub fn set_prefer_free(&mut self, on: bool) {
        self.prefer_free = on;
    }

    /// Gives each robot a guide path ([`crate::scatter`]): a robot standing on its guide path
    /// tries the path's next cell first, before the cells nearest its goal.
    pub fn set_guide(&mut self, paths: &[Vec<u32>]) {
        self.guide = paths
            .iter()
            .map(|p| p.windows(2).map(|w| (w[0], w[1])).collect())
            .collect();
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
                    self.push(i, NIL, from, to);
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
    fn push(&mut self, i: u32, pusher: u32, from: &[u32], to: &mut [u32]) -> bool {
        let v = from[i as usize];
        let dist = &self.dist[i as usize];
        let guided = self.guide.get(i as usize).and_then(|g| g.get(&v).copied());
        let mut cand = [(0u32, 0u32, 0u32, 0u32); 9];
        let mut len = 0;
        for &u in std::iter::once(&v).chain(self.graph.neighbours(v)) {
            let busy =
                u32::from(self.prefer_free && self.occupied_now[u as usize] != NIL && u != v);
            let hinder = if self.hindrance && u != v {
                self.hindrance_at(i, u, to)
            } else {
                0
            };
            cand[len] = (
                dist[u as usize],
                2 * hinder + busy,
                self.rng.gen::<u32>(),
                u,
            );
            if guided == Some(u) {
                cand[len].0 = 0;
            }
            len += 1;
        }
        let cand = &mut cand[..len];
        cand.sort_unstable();
        let partner = if self.swap {
            self.swap_partner(i, v, cand[0].3, to)
        } else {
            None
        };
        if partner.is_some() {
            cand.reverse();
        } else if self.swap && pusher != NIL && cand.len() > 1 {
            // No face-off: stepping ahead of the pusher into a cell where the two would be
            // caught as before comes last.
            let mut trapped = [false; 9];
            for (k, c) in cand.iter().enumerate() {
                trapped[k] = c.3 != v && self.swap_required(pusher, i, v, c.3);
            }
            if trapped.iter().any(|&t| t) {
                let mut keyed: [(bool, (u32, u32, u32, u32)); 9] = [(false, (0, 0, 0, 0)); 9];
                for (k, c) in cand.iter().enumerate() {
                    keyed[k] = (trapped[k], *c);
                }
                let keyed = &mut keyed[..cand.len()];
                keyed.sort_by_key(|&(t, _)| t);
                for (c, (_, k)) in cand.iter_mut().zip(keyed.iter()) {
                    *c = *k;
                }
            }
        }
        for &(_, _, _, u) in cand.iter() {
            if self.occupied_next[u as usize] != NIL || self.clashes(v, u, to) {
                continue;
            }
            to[i as usize] = u;
            self.occupied_next[u as usize] = i;
            let j = self.occupied_now[u as usize];
            if j != NIL && j != i && to[j as usize] == NIL && !self.push(j, i, from, to) {
                continue;
            }
            if let Some(k) = partner {
                // Pull the partner into the cell `i` leaves: the two now move together
                // towards the partner's goal, until `i` can step aside.
                let w = from[k as usize];
                if u != v
                    && to[k as usize] == NIL
                    && self.occupied_next[v as usize] == NIL
                    && !self.clashes(w, v, to)
                {
                    to[k as usize] = v;
                    self.occupied_next[v as usize] = k;
                }
            }
            return true;
        }
        to[i as usize] = v;
        self.occupied_next[v as usize] = i;
        false
    }

    /// How many undecided robots other than `i`, standing next to `u`, would get nearer their
    /// goals by stepping onto `u`: the robots `i` hinders by taking `u`.
    fn hindrance_at(&self, i: u32, u: u32, to: &[u32]) -> u32 {
        let mut count = 0;
        for &w in self.graph.neighbours(u) {
            let j = self.occupied_now[w as usize];
            if j != NIL && j != i && to[j as usize] == NIL {
                let dj = self.table(j);
                count += u32::from(dj[u as usize] < dj[w as usize]);
            }
        }
        count
    }

    /// Robot `i`'s step distances to its goal.
    #[inline]
    fn table(&self, i: u32) -> &[u32] {
        &self.dist[i as usize]
    }

    /// The robot `i` should swap with, if any (LaCAM*'s swap, Okumura IJCAI 2023, in our own
    /// terms). `i` stands on `v` and would most like `best`. When pushing the undecided robot
    /// on `best` ahead along the corridor cannot get it out of `i`'s way for good, `i` retreats
    /// instead and pulls it along, provided the corridor behind `i` opens onto a junction
    /// where the two can pass.
    fn swap_partner(&self, i: u32, v: u32, best: u32, to: &[u32]) -> Option<u32> {
        if best == v {
            return None;
        }
        let j = self.occupied_now[best as usize];
        (j != NIL
            && to[j as usize] == NIL
            && self.swap_required(i, j, v, best)
            && self.swap_possible(v, best))
        .then_some(j)
    }

    /// Whether `pusher` (on `a`) pushing `puller` (on `b`) ahead along a corridor leaves the
    /// two still facing each other: the push ends in a dead end or where the pusher stops
    /// gaining, and the puller still wants to go back past the pusher.
    fn swap_required(&self, pusher: u32, puller: u32, mut a: u32, mut b: u32) -> bool {
        let dp = self.table(pusher);
        let dq = self.table(puller);
        for _ in 0..self.graph.cells() {
            if dp[b as usize] >= dp[a as usize] {
                break;
            }
            let mut onward = NIL;
            let mut count = 0;
            for &c in self.graph.neighbours(b) {
                if c != a && !self.settled(c) {
                    count += 1;
                    onward = c;
                }
            }
            if count >= 2 {
                return false;
            }
            if count == 0 {
                break;
            }
            (a, b) = (b, onward);
        }
        dq[a as usize] < dq[b as usize] && (dp[a as usize] == 0 || dp[b as usize] < dp[a as usize])
    }

    /// Whether a robot on `a` backing away from `b` (pulling the robot on `b` after it) comes
    /// to a junction, where the two can pass, before a dead end.
    fn swap_possible(&self, mut a: u32, mut b: u32) -> bool {
        for _ in 0..self.graph.cells() {
            let mut onward = NIL;
            let mut count = 0;
            for &c in self.graph.neighbours(a) {
                if c != b && !self.settled(c) {
                    count += 1;
                    onward = c;
                }
            }
            if count >= 2 {
                return true;
            }
            if count == 0 {
                return false;
            }
            (b, a) = (a, onward);
        }
        false
    }

    /// Whether `c` is a dead end (one neighbour) where a robot rests on its own goal. The
    /// corridor rules do not count such a cell as a way on: stepping into it would push a
    /// robot out of a pocket it has no reason to leave, so a corridor whose only side
    /// pockets are such cells is still a corridor (after LaCAM*'s swap, in our own terms).
    #[inline]
    fn settled(&self, c: u32) -> bool {
        let k = self.occupied_now[c as usize];
        k != NIL && self.graph.neighbours(c).len() == 1 && self.table(k)[c as usize] == 0
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

    #[test]
    fn ties_go_to_the_cell_that_hinders_no_one() {
        // Robot 0 on (0,0) has two cells one step nearer its goal (1,1): (1,0) and (0,1). Robot
        // 1 on (2,0), still undecided, heads for (0,0) through (1,0). With the hindrance
        // tie-break robot 0 always takes (0,1), whatever the seed; without it, the coin decides.
        let g = Grid::new(4, 3, vec![false; 12]);
        let m = MoveGraph::new(&g, Connectivity::Four);
        let c = |x, y| g.cell(x, y).unwrap();
        let goals = [c(1, 1), c(0, 0)];
        let dist = goal_distances(&g, Connectivity::Four, &goals);
        let from = [c(0, 0).0, c(2, 0).0];
        let mut took = [0usize; 2];
        for hinder in [true, false] {
            for seed in 0..32 {
                let mut p = Pibt::new(&m, &dist, seed);
                p.set_hindrance(hinder);
                let mut to = vec![0; 2];
                assert!(p.step(&from, &mut to, &[0, 1], &[]));
                assert!(to[0] == c(0, 1).0 || to[0] == c(1, 0).0);
                if hinder {
                    assert_eq!(to[0], c(0, 1).0, "seed {seed}");
                } else {
                    took[usize::from(to[0] == c(1, 0).0)] += 1;
                }
            }
        }
        assert!(took[1] > 0, "without the tie-break some seed takes (1,0)");
    }

    /// Steps PIBT with LaCAM's dynamic priorities (a robot away from its goal gains one per
    /// step, one on its goal drops back) until every robot is home; the steps it took.
    fn rollout(
        g: &Grid,
        starts: &[Cell],
        goals: &[Cell],
        swap: bool,
        steps: usize,
    ) -> Option<usize> {
        let m = MoveGraph::new(g, Connectivity::Four);
        let dist = goal_distances(g, Connectivity::Four, goals);
        let mut p = Pibt::new(&m, &dist, 7);
        p.set_swap(swap);
        let n = starts.len();
        let mut q: Vec<u32> = starts.iter().map(|c| c.0).collect();
        let mut priority: Vec<f32> = (0..n).map(|i| 0.1 * i as f32).collect();
        let mut next = vec![0; n];
        for t in 0..steps {
            if (0..n).all(|i| q[i] == goals[i].0) {
                return Some(t);
            }
            let mut order: Vec<u32> = (0..n as u32).collect();
            order.sort_by(|&a, &b| priority[b as usize].total_cmp(&priority[a as usize]));
            assert!(p.step(&q, &mut next, &order, &[]));
            std::mem::swap(&mut q, &mut next);
            for i in 0..n {
                let x = priority[i];
                priority[i] = if q[i] == goals[i].0 {
                    x - x.floor()
                } else {
                    x + 1.0
                };
            }
        }
        None
    }

    /// Two shelves with a one-cell aisle between them, open at both ends (the junctions).
    fn aisle() -> Grid {
        crate::movingai::parse_map(
            "type octile\nheight 5\nwidth 7\nmap\n.......\n.@@@@@.\n.......\n.@@@@@.\n.......\n",
            "aisle",
        )
        .unwrap()
    }

    #[test]
    fn corridor_rules_let_a_robot_overtake_one_whose_goal_is_on_its_way() {
        // Robot 0 at the aisle's mouth must reach (4,2); robot 1, just inside, stops at (2,2) on
        // its way. Plain PIBT pushes robot 1 past its goal, then robot 1 pushes robot 0 back,
        // for ever; with the corridor rules robot 1 lets robot 0 in first.
        let g = aisle();
        let c = |x, y| g.cell(x, y).unwrap();
        let (starts, goals) = ([c(0, 2), c(1, 2)], [c(4, 2), c(2, 2)]);
        assert!(rollout(&g, &starts, &goals, true, 60).is_some());
        assert_eq!(rollout(&g, &starts, &goals, false, 60), None);
    }

    #[test]
    fn corridor_rules_let_robots_facing_each_other_pass() {
        // Two robots in the aisle, each with its goal behind the other.
        let g = aisle();
        let c = |x, y| g.cell(x, y).unwrap();
        let (starts, goals) = ([c(2, 2), c(3, 2)], [c(5, 2), c(1, 2)]);
        assert!(rollout(&g, &starts, &goals, true, 60).is_some());
    }

    #[test]
    fn a_pocket_holding_a_settled_robot_is_no_place_to_pass() {
        // The aisle of `aisle` with a one-cell pocket below its middle, where robot 2 rests on
        // its goal. Robots 0 and 1 face each other at the pocket's mouth. Counted as a way on,
        // the pocket hides that the two must swap (back out to the aisle's end and pass
        // there); without the swap they keep trading places in front of it.
        let g = crate::movingai::parse_map(
            "type octile\nheight 6\nwidth 7\nmap\n.......\n.@@@@@.\n.......\n.@@.@@.\n.@@@@@.\n.......\n",
            "pocket",
        )
        .unwrap();
        let c = |x, y| g.cell(x, y).unwrap();
        let starts = [c(2, 2), c(3, 2), c(3, 3)];
        let goals = [c(5, 2), c(1, 2), c(3, 3)];
        assert!(rollout(&g, &starts, &goals, true, 60).is_some());
    }
}
