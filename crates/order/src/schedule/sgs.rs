//! The schedule generation scheme: a priority list of bricks becomes a schedule.
//!
//! Serial schedule generation (Kolisch 1996) with UAVs as unary resources: bricks are taken
//! in list order, except that a brick whose supports come later in the list waits until the
//! last of them has been taken, so every permutation of the bricks decodes to a valid
//! schedule. Each brick starts at the earliest time at which its supports are placed, enough
//! UAVs are free, and no conflicting brick is placing; the UAVs are those free then whose
//! free time is latest (best fit), so that the UAVs idle longest stay for bricks that can
//! start early. Under a budget, a brick that would be placed after T is left out, and so is
//! everything above it. Decoding is O(n·(m + d)) for n bricks, m UAVs and d conflicts per
//! brick (the zone rule keeps its busy intervals sorted instead).
//!
//! The parallel scheme (`Mode::Parallel`) decodes the same list in time order instead: at
//! each moment some UAV is free, the first listed brick that can start right then (supports
//! placed, no conflict, enough UAVs free) starts; otherwise time moves to the next event. It
//! never leaves a UAV idle while a brick could start (non-delay schedules), which suits walls
//! whose layers should overlap. The planner searches with both.
//!
//! The decoder can also resume: placements made before a time are fixed, some UAVs are gone,
//! and the rest of the list is decoded from that time on (replanning after a failure).

use super::problem::{Placement, Schedule, TeamProblem};
use crate::outcome::Budget;
use mason_wall::BrickId;

const EPS: f64 = 1e-9;

/// Reward, makespan and the sum of placement ends of a decoded schedule.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Decoded {
    /// Reward placed.
    pub reward: f64,
    /// Last placement's end.
    pub makespan_s: f64,
    /// Sum of all placement ends (a tie-breaker that rewards early placement).
    pub sum_end_s: f64,
    /// Bricks placed.
    pub placed: usize,
}

/// How many steps of a parallel decode pass between two looks at the clock.
const STEPS_PER_CHECK: u64 = 16;

/// Which schedule generation scheme decodes a list.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Mode {
    /// In list order, each brick at its earliest feasible start.
    Serial,
    /// In time order, the first listed brick that can start now.
    Parallel,
}

/// Reusable decoding state for one problem.
pub struct Decoder<'a, 'w> {
    p: &'a TeamProblem<'w>,
    mode: Mode,
    pos: Vec<usize>,
    eligible: std::collections::BTreeSet<(usize, u32)>,
    ready: Vec<f64>,
    active: Vec<f64>,
    start: Vec<f64>,
    crew: Vec<[u32; 2]>,
    /// 0: not yet taken; 1: placed; 2: left out; 3: on the wall before planning began.
    state: Vec<u8>,
    /// Supports not yet taken, per brick.
    waiting_on: Vec<u32>,
    /// Taken from the list while supports were still missing.
    deferred: Vec<bool>,
    free: Vec<f64>,
    alive: Vec<bool>,
    floor: f64,
    zone: Vec<(f64, f64)>,
    stack: Vec<BrickId>,
    result: Decoded,
}

impl<'a, 'w> Decoder<'a, 'w> {
    /// A decoder for `p`.
    pub fn new(p: &'a TeamProblem<'w>, mode: Mode) -> Self {
        let n = p.len();
        Decoder {
            p,
            mode,
            pos: vec![usize::MAX; n],
            eligible: std::collections::BTreeSet::new(),
            ready: vec![0.0; n],
            active: Vec::new(),
            start: vec![f64::NAN; n],
            crew: vec![[u32::MAX; 2]; n],
            state: vec![0; n],
            waiting_on: vec![0; n],
            deferred: vec![false; n],
            free: vec![0.0; p.uavs()],
            alive: vec![true; p.uavs()],
            floor: 0.0,
            zone: Vec::new(),
            stack: Vec::new(),
            result: Decoded {
                reward: 0.0,
                makespan_s: 0.0,
                sum_end_s: 0.0,
                placed: 0,
            },
        }
    }

    fn reset(&mut self) {
        let wall = self.p.wall();
        self.start.fill(f64::NAN);
        self.state.fill(0);
        self.deferred.fill(false);
        for b in wall.ids() {
            self.waiting_on[b.index()] = wall.supports(b).len() as u32;
        }
        self.free.fill(0.0);
        self.alive.fill(true);
        self.floor = 0.0;
        self.zone.clear();
        self.result = Decoded {
            reward: 0.0,
            makespan_s: 0.0,
            sum_end_s: 0.0,
            placed: 0,
        };
        if let Some(st) = self.p.start() {
            for &b in &st.placed {
                self.state[b.index()] = 3;
                self.start[b.index()] = f64::NEG_INFINITY;
                self.release(b);
            }
            for (u, &t) in st.uav_ready_s.iter().enumerate() {
                self.alive[u] = t.is_finite();
                self.free[u] = t.max(0.0);
            }
            self.place_committed(&st.committed);
        }
    }

    /// Bricks on their way keep their crews; each starts at the earliest time from its given
    /// start on at which its supports are placed, its crew is free and nothing conflicts, taken
    /// in order of those starts (a brick waits for a support that comes later).
    fn place_committed(&mut self, committed: &[Placement]) {
        let mut pending: Vec<&Placement> = committed.iter().collect();
        pending.sort_by(|a, b| a.start_s.total_cmp(&b.start_s).then(a.brick.cmp(&b.brick)));
        while !pending.is_empty() {
            let ready = |d: &Self, pl: &Placement| {
                d.p.wall().supports(pl.brick).iter().all(|s| d.on_wall(*s))
            };
            // A support neither placed nor on its way is the caller's error: place anyway.
            let k = pending.iter().position(|pl| ready(self, pl)).unwrap_or(0);
            let pl = pending.remove(k);
            let mut t = pl.start_s;
            for s in self.p.wall().supports(pl.brick) {
                if self.on_wall(*s) {
                    t = t.max(self.start[s.index()] + self.p.place_s(*s));
                }
            }
            for &u in &pl.uavs {
                t = t.max(self.free[u]);
            }
            let t = self.conflict_free(pl.brick, t);
            self.keep(&Placement {
                start_s: t,
                ..pl.clone()
            });
        }
    }

    /// Placed in this decode, or before planning began.
    fn on_wall(&self, b: BrickId) -> bool {
        matches!(self.state[b.index()], 1 | 3)
    }

    /// Fixes one placement: its crew is busy until the end of its cycle.
    fn keep(&mut self, pl: &Placement) {
        let mut crew = [u32::MAX; 2];
        for (k, &u) in pl.uavs.iter().take(2).enumerate() {
            crew[k] = u as u32;
            let ready = pl.start_s + self.p.place_s(pl.brick) + self.p.rest_s(pl.brick);
            self.free[u] = self.free[u].max(ready);
        }
        self.commit(pl.brick, pl.start_s, crew);
    }

    /// Decodes a whole priority list (a permutation of the bricks, or a part of it; bricks not
    /// listed are left out).
    pub fn decode(&mut self, list: &[BrickId]) -> Decoded {
        self.reset();
        self.run(list)
    }

    /// [`Self::decode`], given up (`None`) once `budget` runs out. Only the parallel scheme
    /// checks it (every [`STEPS_PER_CHECK`] steps): it scans the eligible bricks at every event,
    /// so on a huge wall one decode can outlast a time limit, where the serial scheme's single
    /// pass cannot be given up without leaving the search with no schedule at all.
    pub fn decode_within(&mut self, list: &[BrickId], budget: &Budget) -> Option<Decoded> {
        self.reset();
        match self.mode {
            Mode::Parallel => self.run_parallel(list, Some(budget)),
            Mode::Serial => Some(self.run(list)),
        }
    }

    /// Fixes `kept` placements (they must be valid together), removes the UAVs not `alive`,
    /// and decodes `list` (the bricks not kept) with no start before `floor`.
    pub fn resume(
        &mut self,
        kept: &[Placement],
        alive: &[bool],
        floor: f64,
        list: &[BrickId],
    ) -> Decoded {
        self.reset();
        for (a, &b) in self.alive.iter_mut().zip(alive) {
            *a &= b;
        }
        self.floor = floor;
        for pl in kept {
            if self.state[pl.brick.index()] == 0 {
                self.keep(pl);
            }
        }
        self.run(list)
    }

    fn run(&mut self, list: &[BrickId]) -> Decoded {
        if self.mode == Mode::Parallel {
            return self
                .run_parallel(list, None)
                .expect("a decode without a budget always ends");
        }
        for &b in list {
            if self.state[b.index()] != 0 {
                continue;
            }
            if self.waiting_on[b.index()] > 0 {
                self.deferred[b.index()] = true;
                continue;
            }
            self.stack.push(b);
            while let Some(x) = self.stack.pop() {
                self.take(x);
            }
        }
        self.result
    }

    fn enlist(&mut self, c: BrickId) {
        let i = c.index();
        if self.state[i] != 0 || self.waiting_on[i] > 0 || self.pos[i] == usize::MAX {
            return;
        }
        let mut ready: f64 = 0.0;
        for s in self.p.wall().supports(c) {
            if self.on_wall(*s) {
                ready = ready.max(self.start[s.index()] + self.p.place_s(*s));
            } else {
                ready = f64::INFINITY;
            }
        }
        self.ready[i] = ready;
        self.eligible.insert((self.pos[i], c.0));
    }

    fn run_parallel(&mut self, list: &[BrickId], stop: Option<&Budget>) -> Option<Decoded> {
        let wall = self.p.wall();
        self.pos.fill(usize::MAX);
        for (k, b) in list.iter().enumerate() {
            if self.state[b.index()] == 0 {
                self.pos[b.index()] = k;
            }
        }
        self.eligible.clear();
        self.active.clear();
        for b in wall.ids() {
            if self.state[b.index()] == 1 {
                self.active.push(self.start[b.index()] + self.p.place_s(b));
            }
        }
        for &b in list {
            self.enlist(b);
        }
        let budget = self.p.budget_s().unwrap_or(f64::INFINITY);
        let mut t = self.floor;
        let mut picked: Vec<(usize, u32)> = Vec::new();
        let mut steps = 0u64;
        while !self.eligible.is_empty() {
            steps += 1;
            if steps % STEPS_PER_CHECK == 0 && stop.is_some_and(Budget::out_of_time) {
                return None;
            }
            let free: usize = (0..self.free.len())
                .filter(|&u| self.alive[u] && self.free[u] <= t + EPS)
                .count();
            let mut chosen = None;
            picked.clear();
            if free > 0 {
                for &(k, raw) in &self.eligible {
                    let b = BrickId(raw);
                    let ready = self.ready[b.index()];
                    if ready.is_infinite() || t + self.p.place_s(b) > budget + EPS {
                        picked.push((k, raw)); // can never be placed: left out
                        continue;
                    }
                    if ready > t + EPS || self.p.need(b) as usize > free {
                        continue;
                    }
                    if self.conflict_free(b, t) > t + EPS {
                        continue;
                    }
                    chosen = Some((k, raw));
                    break;
                }
            }
            for &(k, raw) in &picked {
                self.eligible.remove(&(k, raw));
                self.state[raw as usize] = 2;
                self.release(BrickId(raw));
                for &c in self.p.wall().carried(BrickId(raw)) {
                    self.enlist(c);
                }
            }
            if let Some((k, raw)) = chosen {
                let b = BrickId(raw);
                self.eligible.remove(&(k, raw));
                let crew = self
                    .crew_free_by(t, self.p.need(b) as usize)
                    .expect("enough UAVs free: checked above");
                self.assign(b, t, crew);
                self.active.push(t + self.p.place_s(b));
                for &c in self.p.wall().carried(b) {
                    self.enlist(c);
                }
                continue;
            }
            if !picked.is_empty() {
                continue;
            }
            // Nothing can start at t: move to the next event.
            let mut next = f64::INFINITY;
            for u in 0..self.free.len() {
                if self.alive[u] && self.free[u] > t + EPS {
                    next = next.min(self.free[u]);
                }
            }
            self.active.retain(|&e| e > t + EPS);
            for &e in &self.active {
                next = next.min(e);
            }
            for &(_, raw) in &self.eligible {
                let r = self.ready[raw as usize];
                if r > t + EPS {
                    next = next.min(r);
                }
            }
            if !next.is_finite() {
                break;
            }
            t = next;
        }
        for (_, raw) in std::mem::take(&mut self.eligible) {
            self.state[raw as usize] = 2;
        }
        Some(self.result)
    }

    /// The earliest start ≥ `t0` at which `b` conflicts with no placing brick.
    fn conflict_free(&self, b: BrickId, t0: f64) -> f64 {
        let p = self.p.place_s(b);
        let mut t = t0;
        if self.p.zone_rule() {
            let mut k = self.zone.partition_point(|&(_, e)| e <= t + EPS);
            while let Some(&(s, e)) = self.zone.get(k) {
                if s >= t + p - EPS {
                    break;
                }
                t = t.max(e);
                k += 1;
            }
            return t;
        }
        loop {
            let mut moved = false;
            for &c in self.p.conflicts(b) {
                if self.state[c.index()] != 1 {
                    continue;
                }
                let s = self.start[c.index()];
                let e = s + self.p.place_s(c);
                if s < t + p - EPS && e > t + EPS {
                    t = e;
                    moved = true;
                }
            }
            if !moved {
                return t;
            }
        }
    }

    /// Schedules `b` (its supports are all taken) or leaves it out.
    /// The `need`-th earliest time a live UAV is free (`need` is 1 or 2), if enough live.
    fn nth_free(&self, need: usize) -> Option<f64> {
        let (mut first, mut second) = (f64::INFINITY, f64::INFINITY);
        let mut live = 0;
        for u in (0..self.free.len()).filter(|&u| self.alive[u]) {
            live += 1;
            let f = self.free[u];
            if f < first {
                second = first;
                first = f;
            } else if f < second {
                second = f;
            }
        }
        (live >= need).then_some(if need == 1 { first } else { second })
    }

    /// Best fit: the `need` live UAVs free by `t` whose free times are latest, so that those
    /// idle longest stay for bricks that can start earlier.
    fn crew_free_by(&self, t: f64, need: usize) -> Option<[u32; 2]> {
        let mut crew = [u32::MAX; 2];
        for k in 0..need {
            let mut best: Option<usize> = None;
            for u in 0..self.free.len() {
                if !self.alive[u] || self.free[u] > t + EPS || crew[..k].contains(&(u as u32)) {
                    continue;
                }
                if best.is_none_or(|v| self.free[u] > self.free[v]) {
                    best = Some(u);
                }
            }
            crew[k] = best? as u32;
        }
        Some(crew)
    }

    /// Places `b` at `t` with `crew`, which is busy until the end of its cycle.
    fn assign(&mut self, b: BrickId, t: f64, crew: [u32; 2]) {
        let busy_until = t + self.p.place_s(b) + self.p.rest_s(b);
        for &u in crew.iter().filter(|&&u| u != u32::MAX) {
            self.free[u as usize] = busy_until;
        }
        self.commit(b, t, crew);
    }

    /// Schedules `b` (its supports are all taken) or leaves it out.
    fn take(&mut self, b: BrickId) {
        let wall = self.p.wall();
        let mut lb = self.floor;
        let mut possible = true;
        for s in wall.supports(b) {
            if !self.on_wall(*s) {
                possible = false;
                break;
            }
            lb = lb.max(self.start[s.index()] + self.p.place_s(*s));
        }
        let need = self.p.need(b) as usize;
        let placed = possible
            .then(|| self.nth_free(need))
            .flatten()
            .and_then(|free| {
                let t = self.conflict_free(b, lb.max(free));
                let in_budget = self
                    .p
                    .budget_s()
                    .is_none_or(|budget| t + self.p.place_s(b) <= budget + EPS);
                in_budget
                    .then(|| self.crew_free_by(t, need).map(|c| (t, c)))
                    .flatten()
            });
        match placed {
            Some((t, crew)) => self.assign(b, t, crew),
            None => {
                self.state[b.index()] = 2;
                self.release(b);
            }
        }
    }

    fn commit(&mut self, b: BrickId, t: f64, crew: [u32; 2]) {
        let i = b.index();
        let end = t + self.p.place_s(b);
        self.start[i] = t;
        self.crew[i] = crew;
        self.state[i] = 1;
        if self.p.zone_rule() {
            let k = self.zone.partition_point(|&(s, _)| s < t);
            self.zone.insert(k, (t, end));
        }
        // A brick on its way may end after the budget: flown, but it earns nothing.
        if self.p.budget_s().is_none_or(|t| end <= t + EPS) {
            self.result.reward += self.p.reward(b);
        }
        self.result.makespan_s = self.result.makespan_s.max(end);
        self.result.sum_end_s += end;
        self.result.placed += 1;
        self.release(b);
    }

    /// `b` is taken: the bricks it carries wait on one support fewer.
    fn release(&mut self, b: BrickId) {
        for &c in self.p.wall().carried(b) {
            let w = &mut self.waiting_on[c.index()];
            *w = w.saturating_sub(1);
            if *w == 0 && self.deferred[c.index()] && self.state[c.index()] == 0 {
                self.deferred[c.index()] = false;
                self.stack.push(c);
            }
        }
    }

    /// The schedule decoded last, sorted by start.
    pub fn schedule(&self) -> Schedule {
        let mut s = Schedule {
            placements: (0..self.start.len())
                .filter(|&i| self.state[i] == 1)
                .map(|i| Placement {
                    brick: BrickId(i as u32),
                    uavs: self.crew[i]
                        .iter()
                        .filter(|&&u| u != u32::MAX)
                        .map(|&u| u as usize)
                        .collect(),
                    start_s: self.start[i],
                })
                .collect(),
        };
        s.sort();
        s
    }
}
