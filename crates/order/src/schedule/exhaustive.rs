//! An exact team schedule planner for tiny walls, the oracle of the tests.
//!
//! Every schedule can be left-shifted without loss: list its bricks by start time and place
//! each, with the same UAVs, at the earliest time its supports, its UAVs' cycles and the
//! bricks already placed allow; no brick starts later than before, so no budget is missed and
//! the makespan does not grow. This search enumerates exactly those lists: every sequence of
//! bricks (under a budget, every subset in every order) and every choice of UAVs per brick,
//! with one symmetry cut (of the UAVs not used yet, only the first is tried). It is
//! exponential — O(n!·mⁿ) — and meant for walls of a handful of bricks.

use super::problem::{Objective, Placement, Schedule, TeamOutcome, TeamProblem, TeamStats};
use crate::outcome::{Budget, Status};
use mason_wall::BrickId;
use std::time::Instant;

const EPS: f64 = 1e-9;

struct State<'a, 'w> {
    p: &'a TeamProblem<'w>,
    start: Vec<Option<f64>>,
    crew: Vec<Vec<usize>>,
    free: Vec<f64>,
    used: Vec<bool>,
    nodes: u64,
    budget: Budget,
    stopped: bool,
    best: Option<(f64, f64, Schedule)>,
}

impl State<'_, '_> {
    fn conflicts(&self, b: BrickId, a: BrickId) -> bool {
        self.p.zone_rule() || self.p.conflicts(b).contains(&a)
    }

    fn earliest(&self, b: BrickId, crew: &[usize]) -> f64 {
        let wall = self.p.wall();
        let mut t = crew.iter().map(|&u| self.free[u]).fold(0.0, f64::max);
        for s in wall.supports(b) {
            let s = *s;
            t = t.max(self.start[s.index()].expect("supports placed") + self.p.place_s(s));
        }
        let len = self.p.place_s(b);
        loop {
            let mut moved = false;
            for a in wall.ids() {
                let Some(sa) = self.start[a.index()] else {
                    continue;
                };
                let ea = sa + self.p.place_s(a);
                if self.conflicts(b, a) && sa < t + len - EPS && ea > t + EPS {
                    t = ea;
                    moved = true;
                }
            }
            if !moved {
                return t;
            }
        }
    }

    fn record(&mut self) {
        let (mut reward, mut makespan, mut count) = (0.0, 0.0f64, 0);
        for b in self.p.wall().ids() {
            if let Some(s) = self.start[b.index()] {
                reward += self.p.reward(b);
                makespan = makespan.max(s + self.p.place_s(b));
                count += 1;
            }
        }
        if matches!(self.p.objective(), Objective::Makespan) && count < self.p.len() {
            return;
        }
        let better = match &self.best {
            None => true,
            Some((r, m, _)) => reward > r + 1e-9 || (reward > r - 1e-9 && makespan < m - 1e-9),
        };
        if better {
            let mut s = Schedule {
                placements: self
                    .p
                    .wall()
                    .ids()
                    .filter_map(|b| {
                        Some(Placement {
                            brick: b,
                            uavs: self.crew[b.index()].clone(),
                            start_s: self.start[b.index()]?,
                        })
                    })
                    .collect(),
            };
            s.sort();
            self.best = Some((reward, makespan, s));
        }
    }

    fn crews(&self, need: usize) -> Vec<Vec<usize>> {
        // Used UAVs, plus as many unused ones as the brick needs (unused UAVs are alike).
        let m = self.p.uavs();
        let unused = (0..m).filter(|&u| !self.used[u]).take(need);
        let mut pool: Vec<usize> = (0..m).filter(|&u| self.used[u]).chain(unused).collect();
        pool.sort_unstable();
        match need {
            1 => pool.iter().map(|&u| vec![u]).collect(),
            _ => {
                let mut out = Vec::new();
                for (k, &a) in pool.iter().enumerate() {
                    for &b in &pool[k + 1..] {
                        out.push(vec![a, b]);
                    }
                }
                out
            }
        }
    }

    fn dfs(&mut self) {
        self.nodes += 1;
        if self.budget.exhausted(self.nodes) {
            self.stopped = true;
            return;
        }
        self.record();
        let wall = self.p.wall();
        for b in wall.ids() {
            if self.stopped {
                return;
            }
            if self.start[b.index()].is_some()
                || wall
                    .supports(b)
                    .iter()
                    .any(|s| self.start[s.index()].is_none())
            {
                continue;
            }
            for crew in self.crews(self.p.need(b) as usize) {
                let t = self.earliest(b, &crew);
                let end = t + self.p.place_s(b);
                if self.p.budget_s().is_some_and(|bt| end > bt + EPS) {
                    continue;
                }
                let saved: Vec<(f64, bool)> =
                    crew.iter().map(|&u| (self.free[u], self.used[u])).collect();
                for &u in &crew {
                    self.free[u] = end + self.p.rest_s(b);
                    self.used[u] = true;
                }
                self.start[b.index()] = Some(t);
                self.crew[b.index()] = crew.clone();
                self.dfs();
                self.start[b.index()] = None;
                self.crew[b.index()].clear();
                for (&u, &(f, us)) in crew.iter().zip(&saved) {
                    self.free[u] = f;
                    self.used[u] = us;
                }
            }
        }
    }
}

/// The best schedule by exhaustive search (`Optimal`), or the best found when the budget
/// stops it (`Timeout`). Not for the `expected` objective (it returns the reward optimum).
pub fn exhaustive_schedule(p: &TeamProblem<'_>, budget: &Budget) -> TeamOutcome {
    let t0 = Instant::now();
    let n = p.len();
    let mut st = State {
        p,
        start: vec![None; n],
        crew: vec![Vec::new(); n],
        free: vec![0.0; p.uavs()],
        used: vec![false; p.uavs()],
        nodes: 0,
        budget: budget.clone(),
        stopped: false,
        best: None,
    };
    st.dfs();
    let stats = TeamStats {
        elapsed: t0.elapsed(),
        decodes: st.nodes,
        improvements: 0,
    };
    let status = if st.stopped {
        Status::Timeout
    } else {
        Status::Optimal
    };
    match st.best {
        Some((reward, makespan_s, schedule)) => {
            let bound = match p.objective() {
                Objective::Makespan => makespan_s,
                _ => reward,
            };
            TeamOutcome {
                status,
                schedule: Some(schedule),
                reward,
                makespan_s,
                expected_reward: None,
                bound,
                stats,
            }
        }
        None => TeamOutcome {
            status: if st.stopped {
                Status::Timeout
            } else {
                Status::Infeasible
            },
            schedule: None,
            reward: 0.0,
            makespan_s: 0.0,
            expected_reward: None,
            bound: 0.0,
            stats,
        },
    }
}
