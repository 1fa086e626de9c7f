//! Re-planning a team schedule in flight: when a UAV fails, the survivors plan the rest of
//! the wall from where they stand.
//!
//! The simulator describes the moment as an [`order::schedule::TeamStart`](mason_order::schedule::TeamStart):
//! the bricks on the wall, the bricks on their way (their carriers and the expected start of
//! their placing phase, from each carrier's state and the arena's flight times), and when each
//! idle UAV could start fetching (∞ for a UAV that is down or landing). A [`Replanner`] turns
//! it into new per-UAV brick lists and a new shared order. [`ScheduleReplanner`] uses the team
//! schedule planner with a small decode cap and a 100 ms deadline, so a replan is
//! deterministic for a seed unless the deadline stops it; every replan is checked by
//! `order::schedule::validate_continuation` before it is flown (a rejected one is counted and the
//! UAVs keep their lists).

use mason_order::schedule::{
    plan_schedule, validate_continuation, Objective, TeamModel, TeamProblem, TeamStart,
};
use mason_order::Budget;
use mason_wall::{BrickId, Wall};
use std::sync::atomic::{AtomicU64, Ordering};
use std::time::Duration;

/// New lists after a replan.
#[derive(Clone, Debug, PartialEq)]
pub struct Replan {
    /// Per UAV, its bricks in the order it places them.
    pub lists: Vec<Vec<BrickId>>,
    /// Every planned brick by planned start (the zone's order of need).
    pub order: Vec<BrickId>,
}

/// Plans the rest of a mission from a [`TeamStart`] at mission time `now`.
pub trait Replanner: Sync {
    /// New lists, or `None` to keep flying the current ones.
    fn replan(&self, wall: &Wall, start: TeamStart, now: f64) -> Option<Replan>;
}

/// The team schedule planner as a [`Replanner`].
#[derive(Debug)]
pub struct ScheduleReplanner {
    /// The team model the schedule was planned with.
    pub model: TeamModel,
    /// The objective (its budget, if any, is in mission time).
    pub objective: Objective,
    /// The mission budget T (s), for `reward` and `expected`.
    pub budget_s: Option<f64>,
    /// Decodes per planner thread.
    pub decodes: u64,
    /// Deadline of one replan.
    pub time_limit: Duration,
    /// Seed of the planner.
    pub seed: u64,
    /// Replans the validator refused (a planner bug if ever above 0).
    pub rejected: AtomicU64,
}

impl ScheduleReplanner {
    /// A replanner with a 100 ms deadline and 300 decodes per thread.
    pub fn new(model: TeamModel, objective: Objective, budget_s: Option<f64>, seed: u64) -> Self {
        ScheduleReplanner {
            model,
            objective,
            budget_s,
            decodes: 300,
            time_limit: Duration::from_millis(100),
            seed,
            rejected: AtomicU64::new(0),
        }
    }
}

impl Replanner for ScheduleReplanner {
    fn replan(&self, wall: &Wall, mut start: TeamStart, now: f64) -> Option<Replan> {
        let budget = match self.budget_s {
            Some(t) if t - now <= 0.0 => return None,
            Some(t) => Some(t - now),
            None => None,
        };
        // An idle UAV still has to fetch a brick before it can place one.
        let fetch = self
            .model
            .types
            .iter()
            .map(|t| t.cycle_rest_s)
            .fold(f64::INFINITY, f64::min);
        for t in &mut start.uav_ready_s {
            *t += fetch;
        }
        let uavs = start.uav_ready_s.len();
        let p = TeamProblem::new(wall, self.model.clone(), uavs, budget, self.objective)
            .ok()?
            .with_start(start)
            .ok()?;
        let limit = Budget {
            deadline: std::time::Instant::now().checked_add(self.time_limit),
            node_limit: Some(self.decodes),
            ..Budget::default()
        };
        let out = plan_schedule(&p, &limit, self.seed);
        let s = out.schedule?;
        let start = p.start().expect("set above");
        if validate_continuation(wall, p.model(), uavs, budget, start, &s).is_err() {
            self.rejected.fetch_add(1, Ordering::Relaxed);
            return None;
        }
        Some(Replan {
            lists: s.by_uav(uavs),
            order: s.placements.iter().map(|pl| pl.brick).collect(),
        })
    }
}
