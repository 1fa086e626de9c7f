//! A sharper reward bound: the precedence-constrained knapsack in whole bricks, and the
//! full-slot argument.
//!
//! [`super::bounds::reward_upper_bound`] is the knapsack's LP (Lagrangian) bound. This module
//! proves a smaller one where it can, given a reward `achieved` by some valid schedule:
//!
//! * **Integer knapsack.** A branch and bound lists every closed set S of eligible bricks (every
//!   support of each brick inside, every brick's chain ending by T) with weight w(S) ≤ C and a
//!   reward above the best one accepted so far (at first `achieved`). Each node fixes bricks
//!   in (with their supports) or out (with the bricks on them); its bound is the Lagrangian of
//!   the free bricks, minimised over λ by Newton's method on the breakpoints of the dual (a
//!   maximum-weight closure at each step). Every λ ≥ 0 gives a sound bound, so the cut-off is
//!   sound whatever λ the method stops at.
//! * **Full slots.** With one cycle length c for every brick (place + rest), a budget T and m
//!   UAVs, a UAV starts at most K = ⌊(T − p_min)/c⌋ + 1 bricks, so C = m·K UAV-cycles. A
//!   schedule that uses all of them has every UAV start K bricks, its k-th (from 1) within
//!   [(k−1)·c, (k−1)·c + σ], σ = T − p_min − (K−1)·c < c. When σ < p_min, the bricks of one
//!   such slot all place at overlapping times (so no two of them conflict) and none can wait
//!   for another (so a brick's supports lie in earlier slots); each slot holds exactly m
//!   UAV-cycles (a 2-UAV brick counts 2); and a brick in slot k ends at (k−1)·c + its placing
//!   at the earliest, which must be ≤ T. A closed set of weight C that admits no such split
//!   into K slots is placed by no schedule. The split is searched exactly from the top (the
//!   last slot holds bricks that carry nothing in S, and so on down), with a node cap: a search
//!   cut short accepts the set, which keeps the bound sound.
//!
//! The bound is the best accepted reward once the branch and bound has run to its end; when the
//! work cap or the deadline stops it first, the LP bound stands. A split found all the way down
//! is a valid schedule (slot k starts at (k−1)·c), returned beside the bound.
//!
//! `least_makespan_at` runs the same branch and bound with one UAV-cycle less: when no closed
//! set earning a reward fits there, every schedule earning it uses all m·K cycles, so it ends
//! no earlier than (K−1)·c + p_min, and a slot schedule ending then is optimal on both counts.

use super::bounds::{knapsack, uniform_cycle};
use super::closure::{max_weight_closure_counted, EPS as CLOSURE_EPS};
use super::problem::{Placement, Schedule, TeamProblem};
use crate::outcome::Budget;
use mason_wall::BrickId;

/// Work (the max-flows' edge scans and the graphs built, the bricks the slot search looks at)
/// the refinement may do in all: past it the LP bound stands. A constant, so that the result
/// does not depend on the clock (about 0.3 s on a 2-core machine of 2026).
pub const EXACT_WORK: u64 = 40_000_000;

/// Fixed bricks past which the branch and bound gives up (its recursion depth is at most this).
const MAX_DEPTH: usize = 4000;

/// The branch and bound's stack: far more than MAX_DEPTH levels of its recursion take.
const STACK_BYTES: usize = 64 << 20;

/// Nodes the slot search may visit for one closed set before it accepts the set unproved.
const SLOT_NODES: u64 = 20_000;

/// Bricks the slot search may look at for one closed set (each node looks at the whole set)
/// before it accepts the set unproved.
const SLOT_WORK: u64 = 4_000_000;

/// How far past T a slot's earliest end may lie and still count (s): far above the
/// validator's slack, so that no schedule it accepts is refuted.
const SLOT_SLACK: f64 = 1e-3;

/// A tightened reward bound, with the best full-slot schedule met on the way.
#[derive(Clone, Debug)]
pub struct ExactBound {
    /// The proven upper bound (never above the LP bound, never below `achieved`).
    pub bound: f64,
    /// True when the branch and bound ran to its end (else `bound` is the LP bound).
    pub complete: bool,
    /// A valid schedule found by the slot search, with its reward, if any beat `achieved`.
    pub schedule: Option<(Schedule, f64)>,
}

/// The slot structure a schedule using every UAV-cycle must have, when it applies.
struct Slots {
    cycle: f64,
    /// Slots (starts per UAV).
    k: usize,
    m: usize,
    budget: f64,
}

fn full_slots(p: &TeamProblem<'_>, budget: f64) -> Option<Slots> {
    let c = uniform_cycle(p)?;
    let p_min = p
        .wall()
        .ids()
        .map(|b| p.place_s(b))
        .fold(f64::INFINITY, f64::min);
    if budget + 1e-9 < p_min || c <= 0.0 {
        return None;
    }
    let k = ((budget - p_min) / c + 1e-9).floor() + 1.0;
    let sigma = budget - p_min - (k - 1.0) * c;
    // A margin far above the validator's time slack (1e-6 s per check, so at most 1e-6·K per
    // window over K cycles) keeps the windows apart.
    (sigma + SLOT_SLACK + 4e-6 * k < p_min && p.wall().ids().all(|b| p.place_s(b) <= c + 1e-9))
        .then_some(Slots {
            cycle: c,
            k: k as usize,
            m: p.uavs(),
            budget,
        })
}

/// A node's Lagrangian solution: its bound, the λ it was found at, and a heaviest closure of
/// the free bricks at that λ that fits the capacity (`fits`, with its reward).
struct Sol {
    bound: f64,
    lambda: f64,
    fits: Vec<bool>,
    fits_reward: f64,
    /// Free bricks of a closure just over the capacity and not in `fits` (branching candidates).
    over: Vec<usize>,
    /// `fits` (with the fixed-in bricks) was already offered as a candidate.
    offered: bool,
}

enum Peel {
    Infeasible,
    /// Slot k (from 0): its bricks.
    Feasible(Vec<Vec<usize>>),
    Unknown,
}

struct Bb<'a, 'w> {
    p: &'a TeamProblem<'w>,
    n: usize,
    weight: Vec<f64>,
    reward: Vec<f64>,
    requires: Vec<Vec<usize>>,
    carries: Vec<Vec<usize>>,
    capacity: f64,
    /// −1 out, 0 free, 1 in.
    state: Vec<i8>,
    in_reward: f64,
    in_weight: f64,
    /// Branching order: bricks by (level, index), and each brick's place in it.
    rank: Vec<usize>,
    rank_of: Vec<usize>,
    /// The sets offered so far (each is looked at once).
    offered: std::collections::HashSet<Vec<u32>>,
    /// The best reward accepted: only sets above it are still sought.
    best: f64,
    slots: Option<Slots>,
    witness: Option<(Vec<Vec<usize>>, f64)>,
    work: u64,
    work_cap: u64,
    stopped: bool,
    slack: f64,
    search: &'a Budget,
    undo: Vec<usize>,
}

impl Bb<'_, '_> {
    fn out_of_work(&mut self) -> bool {
        if self.work > self.work_cap || self.search.out_of_time() {
            self.stopped = true;
        }
        self.stopped
    }

    /// A heaviest closure of the free bricks under reward − λ·weight: its members, reward and
    /// weight (`None`: stopped).
    fn closure(&mut self, lambda: f64) -> Option<(Vec<bool>, f64, f64)> {
        let mut pos = vec![usize::MAX; self.n];
        let free: Vec<usize> = (0..self.n).filter(|&i| self.state[i] == 0).collect();
        for (k, &i) in free.iter().enumerate() {
            pos[i] = k;
        }
        let weights: Vec<f64> = free
            .iter()
            .map(|&i| self.reward[i] - lambda * self.weight[i])
            .collect();
        let requires: Vec<Vec<usize>> = free
            .iter()
            .map(|&i| {
                self.requires[i]
                    .iter()
                    .filter(|&&s| self.state[s] == 0)
                    .map(|&s| pos[s])
                    .collect()
            })
            .collect();
        self.work += free.len() as u64 + requires.iter().map(|r| r.len() as u64).sum::<u64>();
        let search = self.search;
        let (set, scans) =
            max_weight_closure_counted(&weights, &requires, &|| search.out_of_time());
        self.work += scans;
        let Some(set) = set else {
            self.stopped = true;
            return None;
        };
        let mut member = vec![false; self.n];
        let (mut r, mut w) = (0.0, 0.0);
        for (k, &i) in free.iter().enumerate() {
            if set[k] {
                member[i] = true;
                r += self.reward[i];
                w += self.weight[i];
            }
        }
        Some((member, r, w))
    }

    /// The dual value at λ of the node: λ·C + Σ over the fixed-in bricks and the closure.
    fn dual(&self, lambda: f64, r: f64, w: f64) -> f64 {
        lambda * self.capacity
            + (self.in_reward - lambda * self.in_weight)
            + (r - lambda * w)
            + self.slack
    }

    /// The node's bound at one λ only (one closure): enough to cut most siblings.
    fn quick(&mut self, lambda: f64) -> Option<f64> {
        if self.in_weight > self.capacity + 1e-9 {
            return Some(f64::NEG_INFINITY);
        }
        let (_, r, w) = self.closure(lambda)?;
        Some(self.dual(lambda, r, w))
    }

    /// The node's Lagrangian bound, minimised over λ ≥ 0 by Newton's method on the dual's
    /// breakpoints.
    fn solve(&mut self) -> Option<Sol> {
        let room = self.capacity - self.in_weight;
        if room < -1e-9 {
            return Some(Sol {
                bound: f64::NEG_INFINITY,
                lambda: 0.0,
                fits: Vec::new(),
                fits_reward: 0.0,
                over: Vec::new(),
                offered: false,
            });
        }
        let (all, r0, w0) = self.closure(0.0)?;
        if w0 <= room + 1e-9 {
            return Some(Sol {
                bound: self.dual(0.0, r0, w0),
                lambda: 0.0,
                fits: all,
                fits_reward: r0,
                over: Vec::new(),
                offered: false,
            });
        }
        // Lines of the dual: the empty closure (fits) and the λ = 0 one (over the capacity).
        let mut lo = (vec![false; self.n], 0.0, 0.0);
        let mut hi = (all, r0, w0);
        let mut bound = f64::INFINITY;
        let mut at = 0.0;
        for _ in 0..64 {
            let lambda = ((hi.1 - lo.1) / (hi.2 - lo.2)).max(0.0);
            let (set, r, w) = self.closure(lambda)?;
            let g = self.dual(lambda, r, w);
            if g < bound {
                bound = g;
                at = lambda;
            }
            let line = self.dual(lambda, lo.1, lo.2);
            let done = g <= line + 1e-9;
            if w <= room + 1e-9 {
                lo = (set, r, w);
            } else {
                hi = (set, r, w);
            }
            if done {
                break;
            }
        }
        // The relaxation's optimum is the fitting closure itself (whole) when it reaches the
        // bound; otherwise the bricks of the closure over the capacity are the ones to split on.
        let whole = bound - self.slack <= self.in_reward + lo.1 + 1e-9;
        let over = match whole {
            true => Vec::new(),
            false => (0..self.n).filter(|&i| hi.0[i] && !lo.0[i]).collect(),
        };
        Some(Sol {
            bound,
            lambda: at,
            fits: lo.0,
            fits_reward: lo.1,
            over,
            offered: false,
        })
    }

    /// Fixes `b` in (with its supports) or out (with the bricks on it); false when that
    /// contradicts an earlier fixing. The changes go on the undo log.
    fn fix(&mut self, b: usize, inside: bool) -> bool {
        let mut stack = vec![b];
        while let Some(v) = stack.pop() {
            match (self.state[v], inside) {
                (0, _) => {
                    self.state[v] = if inside { 1 } else { -1 };
                    if inside {
                        self.in_reward += self.reward[v];
                        self.in_weight += self.weight[v];
                    }
                    self.undo.push(v);
                    let next = if inside {
                        &self.requires[v]
                    } else {
                        &self.carries[v]
                    };
                    stack.extend(next.iter().copied());
                }
                (1, true) | (-1, false) => {}
                _ => return false,
            }
        }
        true
    }

    fn undo_to(&mut self, mark: usize) {
        while self.undo.len() > mark {
            let v = self.undo.pop().expect("undo entry");
            if self.state[v] == 1 {
                self.in_reward -= self.reward[v];
                self.in_weight -= self.weight[v];
            }
            self.state[v] = 0;
        }
    }

    /// Only sets above the best accepted reward are sought (rewards are whole numbers).
    fn cut(&self, bound: f64) -> bool {
        bound < self.best + 1.0 - 1e-6
    }

    fn node(&mut self, sol: Option<Sol>) {
        if self.out_of_work() {
            return;
        }
        // Each level of the recursion fixes at least one brick; a deeper tree gives up (the
        // LP bound stands) rather than risk a small thread's stack.
        if self.undo.len() > MAX_DEPTH {
            self.stopped = true;
            return;
        }
        let Some(mut sol) = sol.or_else(|| self.solve()) else {
            return;
        };
        if self.cut(sol.bound) {
            return;
        }
        let free = |s: &Self, i: usize| s.state[i] == 0;
        if !sol.offered {
            sol.offered = true;
            let r = self.in_reward + sol.fits_reward;
            if !self.cut(r) {
                self.offer(&sol.fits, r);
                if self.cut(sol.bound) || self.stopped {
                    return;
                }
            }
        }
        let lambda = sol.lambda;
        if let Some(&v) = sol.over.iter().min_by_key(|&&i| self.rank_of[i]) {
            self.branch(v, true, lambda);
            self.branch(v, false, lambda);
            return;
        }
        // The relaxation's optimum is whole (the fixed-in bricks and `fits`): split off the
        // other sets. The first free brick goes the set's way (same solution) or the other way.
        let Some(&v) = self.rank.iter().find(|&&i| free(self, i)) else {
            return;
        };
        let along = sol.fits[v];
        let mark = self.undo.len();
        if self.fix(v, along) {
            let mut kept = sol;
            for i in 0..self.n {
                if !free(self, i) {
                    kept.fits[i] = false;
                }
            }
            kept.fits_reward = (0..self.n)
                .filter(|&i| kept.fits[i])
                .map(|i| self.reward[i])
                .sum();
            self.node(Some(kept));
        }
        self.undo_to(mark);
        self.branch(v, !along, lambda);
    }

    /// A child: `v` fixed `inside` or out; cut at the parent's λ when it can be.
    fn branch(&mut self, v: usize, inside: bool, lambda: f64) {
        if self.stopped {
            return;
        }
        let mark = self.undo.len();
        if self.fix(v, inside) {
            match self.quick(lambda) {
                Some(b) if self.cut(b) => {}
                Some(_) => self.node(None),
                None => {}
            }
        }
        self.undo_to(mark);
    }

    /// A closed set (the fixed-in bricks and `extra`) that fits, with a reward above the best
    /// accepted: accepted unless the full-slot argument refutes it.
    fn offer(&mut self, extra: &[bool], reward: f64) {
        let set: Vec<bool> = (0..self.n)
            .map(|i| self.state[i] == 1 || (self.state[i] == 0 && extra[i]))
            .collect();
        let key: Vec<u32> = (0..self.n).filter(|&i| set[i]).map(|i| i as u32).collect();
        if !self.offered.insert(key) {
            return;
        }
        let weight: f64 = (0..self.n)
            .filter(|&i| set[i])
            .map(|i| self.weight[i])
            .sum();
        if self
            .slots
            .as_ref()
            .is_some_and(|s| weight > (s.m * s.k) as f64 - 0.5)
        {
            match self.peel(&set) {
                Peel::Infeasible => return,
                Peel::Feasible(split) => {
                    if self.witness.as_ref().is_none_or(|w| reward > w.1) {
                        self.witness = Some((split, reward));
                    }
                }
                Peel::Unknown => {}
            }
        }
        self.best = self.best.max(reward);
    }

    /// Splits `set` into the full slots, from the last one down.
    fn peel(&mut self, set: &[bool]) -> Peel {
        let slots = self.slots.as_ref().expect("slots apply");
        let (k, m, cycle, budget) = (slots.k, slots.m, slots.cycle, slots.budget);
        let mut members: Vec<usize> = (0..self.n).filter(|&i| set[i]).collect();
        members.sort_by_key(|&i| (self.p.wall().brick(BrickId(i as u32)).level, i));
        let mut rem = set.to_vec();
        // Bricks of the set on each brick, still in it.
        let mut above = vec![0usize; self.n];
        for &i in &members {
            for &s in &self.requires[i] {
                above[s] += 1;
            }
        }
        let mut split = vec![Vec::new(); k];
        let (mut nodes, mut work) = (0u64, 0u64);
        let out = self.peel_from(
            &mut PeelState {
                members: &members,
                rem: &mut rem,
                above: &mut above,
                split: &mut split,
                nodes: &mut nodes,
                work: &mut work,
                depth: &mut vec![0; self.n],
            },
            k,
            m,
            cycle,
            budget,
        );
        self.work += work + self.n as u64;
        match out {
            Some(true) => Peel::Feasible(split),
            Some(false) => Peel::Infeasible,
            None => Peel::Unknown,
        }
    }

    /// Some(true): split found (in `split`); Some(false): none exists; None: cut short.
    fn peel_from(
        &self,
        st: &mut PeelState<'_>,
        k: usize,
        m: usize,
        cycle: f64,
        budget: f64,
    ) -> Option<bool> {
        *st.nodes += 1;
        if *st.nodes > SLOT_NODES {
            return None;
        }
        if k == 0 {
            return Some(st.members.iter().all(|&i| !st.rem[i]));
        }
        // Each node looks at every brick of the set once.
        *st.work += st.members.len() as u64;
        if *st.work > SLOT_WORK {
            return None;
        }
        // The longest chain left must fit in the k slots left (the bricks left, in level
        // order: each one's supports come first).
        let depth = &mut *st.depth;
        for &i in st.members {
            if st.rem[i] {
                depth[i] = 1 + self.requires[i]
                    .iter()
                    .filter(|&&s| st.rem[s])
                    .map(|&s| depth[s])
                    .max()
                    .unwrap_or(0);
                if depth[i] > k {
                    return Some(false);
                }
            }
        }
        // Slot k (from 1) starts at (k−1)·c at the earliest: its bricks must end by T.
        let start = (k - 1) as f64 * cycle;
        let mut tops: Vec<usize> = st
            .members
            .iter()
            .copied()
            .filter(|&i| st.rem[i] && st.above[i] == 0)
            .filter(|&i| start + self.p.place_s(BrickId(i as u32)) <= budget + SLOT_SLACK)
            .collect();
        tops.sort_by_key(|&i| (std::cmp::Reverse(depth[i]), i));
        let mut chosen = Vec::new();
        self.choose(st, &tops, 0, m, &mut chosen, k, m, cycle, budget)
    }

    /// Picks slot k's bricks from `tops[from..]` (exactly `need` more UAV-cycles, none in
    /// conflict with another), then peels the slots below.
    #[allow(clippy::too_many_arguments)]
    fn choose(
        &self,
        st: &mut PeelState<'_>,
        tops: &[usize],
        from: usize,
        need: usize,
        chosen: &mut Vec<usize>,
        k: usize,
        m: usize,
        cycle: f64,
        budget: f64,
    ) -> Option<bool> {
        // Every call counts, so that the cap also bounds the recursion's depth.
        *st.nodes += 1;
        if *st.nodes > SLOT_NODES {
            return None;
        }
        if need == 0 {
            for &i in chosen.iter() {
                st.rem[i] = false;
                for &s in &self.requires[i] {
                    st.above[s] -= 1;
                }
            }
            let below = self.peel_from(st, k - 1, m, cycle, budget);
            for &i in chosen.iter() {
                st.rem[i] = true;
                for &s in &self.requires[i] {
                    st.above[s] += 1;
                }
            }
            if below == Some(true) {
                st.split[k - 1] = chosen.clone();
            }
            return below;
        }
        let mut unknown = false;
        for t in from..tops.len() {
            let b = tops[t];
            let w = self.p.need(BrickId(b as u32)) as usize;
            if w > need || chosen.iter().any(|&c| self.conflict(b, c)) {
                continue;
            }
            chosen.push(b);
            let r = self.choose(st, tops, t + 1, need - w, chosen, k, m, cycle, budget);
            chosen.pop();
            match r {
                Some(true) => return Some(true),
                None => {
                    unknown = true;
                    if *st.nodes > SLOT_NODES {
                        return None;
                    }
                }
                Some(false) => {}
            }
        }
        if unknown {
            None
        } else {
            Some(false)
        }
    }

    fn conflict(&self, a: usize, b: usize) -> bool {
        self.p.zone_rule()
            || self
                .p
                .conflicts(BrickId(a as u32))
                .binary_search(&BrickId(b as u32))
                .is_ok()
    }
}

struct PeelState<'s> {
    members: &'s [usize],
    rem: &'s mut Vec<bool>,
    above: &'s mut Vec<usize>,
    split: &'s mut Vec<Vec<usize>>,
    nodes: &'s mut u64,
    /// Bricks looked at (capped by [`SLOT_WORK`]).
    work: &'s mut u64,
    /// Per brick: the longest chain of bricks left ending at it (scratch).
    depth: &'s mut Vec<usize>,
}

/// The reward bound of [`super::bounds::reward_upper_bound_within`], tightened by the integer
/// knapsack and the full-slot argument (see the module notes), given `achieved`, a reward some
/// valid schedule reaches (0 if none is known) and `lp`, the LP bound. Rewards must be whole
/// numbers; otherwise `lp` is returned as it is.
pub fn reward_upper_bound_exact(
    p: &TeamProblem<'_>,
    budget: f64,
    achieved: f64,
    lp: f64,
    search: &Budget,
) -> ExactBound {
    exact_with_work(p, budget, achieved, lp, search, EXACT_WORK)
}

/// [`reward_upper_bound_exact`] with a work cap of its own (`work`, in [`EXACT_WORK`]'s units).
pub(crate) fn exact_with_work(
    p: &TeamProblem<'_>,
    budget: f64,
    achieved: f64,
    lp: f64,
    search: &Budget,
    work: u64,
) -> ExactBound {
    let whole = |x: f64| x.fract() == 0.0 && x >= 0.0;
    let unchanged = ExactBound {
        bound: lp,
        complete: false,
        schedule: None,
    };
    if !p.wall().ids().all(|b| whole(p.reward(b))) || achieved >= lp - 1e-9 {
        return ExactBound {
            complete: achieved >= lp - 1e-9,
            ..unchanged
        };
    }
    let Some(mut bb) = run(
        p,
        budget,
        achieved.floor(),
        0.0,
        full_slots(p, budget),
        search,
        work,
    ) else {
        return unchanged;
    };
    let schedule = bb.witness.take().and_then(|(split, reward)| {
        let s = bb.slots.as_ref()?;
        (reward > achieved + 1e-9).then(|| (slot_schedule(&split, s, p), reward))
    });
    if bb.stopped {
        return ExactBound {
            schedule,
            ..unchanged
        };
    }
    ExactBound {
        bound: bb.best.min(lp),
        complete: true,
        schedule,
    }
}

/// Builds the branch and bound (capacity less `short` UAV-cycles, seeking sets above `best`)
/// and runs it to its end or its cap. The recursion is as deep as the bricks it fixes: it runs
/// on a thread of its own with room for MAX_DEPTH levels whatever the caller's stack.
fn run<'a, 'w>(
    p: &'a TeamProblem<'w>,
    budget: f64,
    best: f64,
    short: f64,
    slots: Option<Slots>,
    search: &'a Budget,
    work: u64,
) -> Option<Bb<'a, 'w>> {
    let n = p.len();
    let k = knapsack(p, budget, budget);
    let mut carries = vec![Vec::new(); n];
    for (i, req) in k.requires.iter().enumerate() {
        for &s in req {
            carries[s].push(i);
        }
    }
    let mut rank: Vec<usize> = (0..n).filter(|&i| k.eligible[i]).collect();
    rank.sort_by_key(|&i| (p.wall().brick(BrickId(i as u32)).level, i));
    let mut rank_of = vec![usize::MAX; n];
    for (k, &i) in rank.iter().enumerate() {
        rank_of[i] = k;
    }
    let mut bb = Bb {
        p,
        n,
        weight: k.weight,
        reward: (0..n).map(|i| p.reward(BrickId(i as u32))).collect(),
        requires: k.requires,
        carries,
        capacity: k.capacity - short,
        state: k.eligible.iter().map(|&e| if e { 0 } else { -1 }).collect(),
        in_reward: 0.0,
        in_weight: 0.0,
        rank,
        rank_of,
        offered: Default::default(),
        best,
        slots,
        witness: None,
        work: 0,
        work_cap: work,
        stopped: false,
        slack: 4.0 * CLOSURE_EPS * (n + 2) as f64,
        search,
        undo: Vec::new(),
    };
    std::thread::scope(|sc| {
        std::thread::Builder::new()
            .name("reward-bound".into())
            .stack_size(STACK_BYTES)
            .spawn_scoped(sc, move || {
                bb.node(None);
                bb
            })
            .ok()
            .and_then(|h| h.join().ok())
    })
}

/// The least makespan of any schedule earning `reward` or more, when the full-slot argument
/// applies and the branch and bound proves that every closed set earning that much uses all
/// m·K UAV-cycles (none fits in one cycle less): every UAV then starts K bricks, the last at
/// (K−1)·c or later, so the makespan is at least (K−1)·c + the shortest placing phase.
/// `None` when that cannot be shown within `work` (or rewards are not whole numbers).
pub(crate) fn least_makespan_at(
    p: &TeamProblem<'_>,
    budget: f64,
    reward: f64,
    search: &Budget,
    work: u64,
) -> Option<f64> {
    let s = full_slots(p, budget)?;
    if !p.wall().ids().all(|b| p.reward(b).fract() == 0.0) {
        return None;
    }
    let bb = run(p, budget, reward - 1.0, 1.0, None, search, work)?;
    let p_min = p
        .wall()
        .ids()
        .map(|b| p.place_s(b))
        .fold(f64::INFINITY, f64::min);
    (!bb.stopped && bb.best < reward - 0.5).then(|| (s.k - 1) as f64 * s.cycle + p_min)
}

/// The schedule of a full-slot split: slot k (from 0) starts at k·c, its bricks taking the
/// UAVs in turn.
fn slot_schedule(split: &[Vec<usize>], s: &Slots, p: &TeamProblem<'_>) -> Schedule {
    let mut placements = Vec::new();
    for (k, bricks) in split.iter().enumerate() {
        let mut u = 0;
        for &b in bricks {
            let brick = BrickId(b as u32);
            let need = p.need(brick) as usize;
            placements.push(Placement {
                brick,
                uavs: (u..u + need).collect(),
                start_s: k as f64 * s.cycle,
            });
            u += need;
        }
    }
    let mut out = Schedule { placements };
    out.sort();
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::schedule::bounds::reward_upper_bound;
    use crate::schedule::{exhaustive_schedule, plan_schedule, TeamModel};
    use crate::schedule::{Objective, ScheduleError};
    use crate::Status;

    /// Four reds within 0.8 m of each other, two UAVs, T = 90 s (cmcp: 40 s placing, 50 s
    /// cycle): two starts per UAV, four UAV-cycles. The LP (and integer) knapsack takes all
    /// four; using every cycle would put two conflicting bricks in one slot, so the bound is 3.
    fn crowded() -> mason_wall::Wall {
        let text = "1 1 0 0 0.1 0\n2 1 0.25 0 0.1 0\n3 1 0.5 0 0.1 0\n4 1 0.75 0 0.1 0\n";
        mason_wall::parse_cmcp(text, "t", mason_wall::CmcpSizes::Yaml).unwrap()
    }

    fn reward_problem(wall: &mason_wall::Wall, uavs: usize, budget: f64) -> TeamProblem<'_> {
        TeamProblem::new(
            wall,
            TeamModel::cmcp(),
            uavs,
            Some(budget),
            Objective::Reward,
        )
        .unwrap()
    }

    #[test]
    fn a_set_that_cannot_fill_its_slots_is_refuted() {
        let wall = crowded();
        let p = reward_problem(&wall, 2, 90.0);
        let lp = reward_upper_bound(&p, 90.0).bound;
        assert_eq!(lp, 4.0);
        let exact = reward_upper_bound_exact(&p, 90.0, 0.0, lp, &Budget::unlimited());
        assert!(exact.complete);
        assert_eq!(exact.bound, 3.0);
        let opt = exhaustive_schedule(&p, &Budget::unlimited());
        assert_eq!((opt.status, opt.reward), (Status::Optimal, 2.0));
    }

    #[test]
    fn the_full_slot_argument_needs_slots_that_overlap_in_time() {
        // At T = 130 s a UAV still starts two bricks (σ = 40 s = the placing phase): two
        // bricks of one "slot" may then place one after the other, so it does not apply.
        let wall = crowded();
        let p = reward_problem(&wall, 2, 130.0);
        assert!(full_slots(&p, 130.0).is_none());
        assert!(full_slots(&p, 129.0).is_some());
        let lp = reward_upper_bound(&p, 130.0).bound;
        let exact = reward_upper_bound_exact(&p, 130.0, 0.0, lp, &Budget::unlimited());
        assert_eq!(exact.bound, 4.0);
        assert_eq!(exhaustive_schedule(&p, &Budget::unlimited()).reward, 3.0);
    }

    #[test]
    fn a_found_split_is_a_valid_schedule() {
        // Two reds 1 m apart, a blue on them both and a red far away: the slot search places
        // the two reds first, then the blue and the far red.
        let text = "1 1 0.5 0 0.1 0\n2 1 1.5 0 0.1 0\n3 3 1.0 0 0.3 0\n4 1 4.0 0 0.1 0\n";
        let wall = mason_wall::parse_cmcp(text, "t", mason_wall::CmcpSizes::Yaml).unwrap();
        let p = reward_problem(&wall, 2, 90.0);
        let lp = reward_upper_bound(&p, 90.0).bound;
        let exact = reward_upper_bound_exact(&p, 90.0, 0.0, lp, &Budget::unlimited());
        let (s, r) = exact.schedule.expect("a split");
        let ev = crate::schedule::validate_schedule(&wall, p.model(), 2, Some(90.0), &s).unwrap();
        assert_eq!((ev.reward, r, exact.bound), (7.0, 7.0, 7.0));
        // Every set earning 7 uses all four UAV-cycles: the makespan is at least 50 + 40 s, and
        // the planner returns the slot schedule without searching.
        let least = least_makespan_at(&p, 90.0, 7.0, &Budget::unlimited(), EXACT_WORK);
        assert_eq!(least, Some(90.0));
        assert_eq!(
            least_makespan_at(&p, 90.0, 6.0, &Budget::unlimited(), EXACT_WORK),
            None
        );
        let out = plan_schedule(&p, &Budget::unlimited(), 0);
        assert_eq!(
            (out.status, out.reward, out.makespan_s),
            (Status::Optimal, 7.0, 90.0)
        );
        assert_eq!(out.stats.decodes, 0);
    }

    #[test]
    fn stopped_early_it_keeps_the_lp_bound() {
        let wall = crowded();
        let p = reward_problem(&wall, 2, 90.0);
        let stop = Budget::time(std::time::Duration::ZERO);
        let exact = reward_upper_bound_exact(&p, 90.0, 0.0, 4.0, &stop);
        assert!(!exact.complete);
        assert_eq!(exact.bound, 4.0);
    }

    /// The planner reports the tightened bound, and `schedule_checked` refuses a reward above
    /// it.
    #[test]
    fn the_planner_reports_the_tightened_bound_and_the_check_holds_it() {
        let wall = crowded();
        let p = reward_problem(&wall, 2, 90.0);
        let out = plan_schedule(&p, &Budget::nodes(200), 0);
        assert_eq!((out.reward, out.bound), (2.0, 3.0));
        let mut o = out.clone();
        o.reward = 4.0;
        assert!(matches!(
            crate::schedule::checked::check_bound(&p, &o),
            Err(ScheduleError::OutsideBound { .. })
        ));
    }
}
