//! Mission metrics, computed by an observer of the event stream.

use crate::state::{Event, EventKind, Observer, UavState};
use serde::Serialize;

/// What a mission achieved.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Metrics {
    /// Time the last brick was placed, when the wall was completed.
    pub makespan_s: Option<f64>,
    /// Time the mission ended (every UAV on the ground, or the time limit).
    pub end_s: f64,
    /// Bricks placed.
    pub bricks_placed: usize,
    /// Bricks in the wall.
    pub bricks_total: usize,
    /// Reward placed.
    pub reward: f64,
    /// (time, cumulative reward) at every placement.
    pub reward_over_time: Vec<(f64, f64)>,
    /// Seconds each UAV spent in each state, indexed by [`UavState::index`].
    pub time_in_state: Vec<[f64; UavState::ALL.len()]>,
    /// Seconds the wall zone was occupied.
    pub zone_busy_s: f64,
    /// Zone busy time over the mission's end time.
    pub zone_utilisation: f64,
    /// Grasped bricks lost.
    pub bricks_lost: usize,
    /// UAVs that failed.
    pub uavs_failed: usize,
    /// Times the survivors re-planned.
    pub replans: usize,
}

/// Builds [`Metrics`] from events.
#[derive(Clone, Debug)]
pub struct MetricsObserver {
    rewards: Vec<f64>,
    m: Metrics,
    state: Vec<(UavState, f64)>,
    zone_count: usize,
    zone_since: f64,
}

impl MetricsObserver {
    /// For a team of `uavs` and bricks with these rewards.
    pub fn new(uavs: usize, rewards: Vec<f64>) -> Self {
        MetricsObserver {
            m: Metrics {
                makespan_s: None,
                end_s: 0.0,
                bricks_placed: 0,
                bricks_total: rewards.len(),
                reward: 0.0,
                reward_over_time: Vec::new(),
                time_in_state: vec![[0.0; UavState::ALL.len()]; uavs],
                zone_busy_s: 0.0,
                zone_utilisation: 0.0,
                bricks_lost: 0,
                uavs_failed: 0,
                replans: 0,
            },
            rewards,
            state: vec![(UavState::Check, 0.0); uavs],
            zone_count: 0,
            zone_since: 0.0,
        }
    }

    /// Closes the books at `end` and returns the metrics.
    pub fn finish(mut self, end: f64) -> Metrics {
        for (u, &(s, since)) in self.state.iter().enumerate() {
            self.m.time_in_state[u][s.index()] += (end - since).max(0.0);
        }
        if self.zone_count > 0 {
            self.m.zone_busy_s += end - self.zone_since;
        }
        self.m.end_s = end;
        if self.m.bricks_placed == self.m.bricks_total {
            self.m.makespan_s = self
                .m
                .reward_over_time
                .last()
                .map(|&(t, _)| t)
                .or(Some(0.0));
        }
        let span = self.m.makespan_s.unwrap_or(end);
        self.m.zone_utilisation = if span > 0.0 {
            self.m.zone_busy_s / span
        } else {
            0.0
        };
        self.m
    }
}

impl Observer for MetricsObserver {
    fn event(&mut self, e: &Event) {
        let u = e.uav as usize;
        match e.kind {
            EventKind::State { state, .. } => {
                let (old, since) = self.state[u];
                self.m.time_in_state[u][old.index()] += e.t - since;
                self.state[u] = (state, e.t);
            }
            EventKind::Place { brick } => {
                self.m.bricks_placed += 1;
                self.m.reward += self.rewards[brick.index()];
                self.m.reward_over_time.push((e.t, self.m.reward));
            }
            EventKind::Lost { .. } => self.m.bricks_lost += 1,
            EventKind::Fail => self.m.uavs_failed += 1,
            EventKind::ZoneEnter => {
                if self.zone_count == 0 {
                    self.zone_since = e.t;
                }
                self.zone_count += 1;
            }
            EventKind::ZoneLeave => {
                self.zone_count -= 1;
                if self.zone_count == 0 {
                    self.m.zone_busy_s += e.t - self.zone_since;
                }
            }
            EventKind::Replan { .. } => self.m.replans += 1,
            EventKind::Grasp { .. } | EventKind::Comm { .. } => {}
        }
    }
}
