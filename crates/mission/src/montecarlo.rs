//! Monte Carlo: many seeded missions spread over the cores with rayon; every trace is checked.

use crate::check::{TraceChecker, TraceError};
use crate::coord::{make_policy, Coord};
use crate::sim::{simulate, MissionInput, MissionResult, MissionStatus};
use rayon::prelude::*;
use serde::Serialize;

/// Mean and the 5th and 95th percentiles.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Spread {
    /// Mean.
    pub mean: f64,
    /// 5th percentile.
    pub p5: f64,
    /// 95th percentile.
    pub p95: f64,
}

impl Spread {
    /// Of a sample (NaN when empty). Percentiles by nearest rank.
    pub fn of(values: &[f64]) -> Spread {
        if values.is_empty() {
            return Spread {
                mean: f64::NAN,
                p5: f64::NAN,
                p95: f64::NAN,
            };
        }
        let mut v = values.to_vec();
        v.sort_by(f64::total_cmp);
        let rank = |p: f64| v[(((p * v.len() as f64).ceil() as usize).max(1) - 1).min(v.len() - 1)];
        Spread {
            mean: v.iter().sum::<f64>() / v.len() as f64,
            p5: rank(0.05),
            p95: rank(0.95),
        }
    }
}

/// A summary of N runs.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Summary {
    /// Runs.
    pub runs: usize,
    /// Runs that completed the wall.
    pub completed: usize,
    /// Makespan over completed runs (s).
    pub makespan_s: Spread,
    /// Bricks placed over all runs.
    pub bricks_placed: Spread,
    /// Reward over all runs.
    pub reward: Spread,
    /// Zone utilisation over all runs.
    pub zone_utilisation: Spread,
}

/// Summarises results.
pub fn summarise(results: &[MissionResult]) -> Summary {
    let done: Vec<f64> = results
        .iter()
        .filter(|r| r.status == MissionStatus::Complete)
        .filter_map(|r| r.metrics.makespan_s)
        .collect();
    let all = |f: fn(&MissionResult) -> f64| Spread::of(&results.iter().map(f).collect::<Vec<_>>());
    Summary {
        runs: results.len(),
        completed: done.len(),
        makespan_s: Spread::of(&done),
        bricks_placed: all(|r| r.metrics.bricks_placed as f64),
        reward: all(|r| r.metrics.reward),
        zone_utilisation: all(|r| r.metrics.zone_utilisation),
    }
}

/// The reward each run had placed by `t` seconds.
pub fn reward_by(results: &[MissionResult], t: f64) -> Spread {
    let by = |r: &MissionResult| {
        r.metrics
            .reward_over_time
            .iter()
            .take_while(|(at, _)| *at <= t)
            .last()
            .map_or(0.0, |&(_, reward)| reward)
    };
    Spread::of(&results.iter().map(by).collect::<Vec<_>>())
}

/// Runs seeds `first_seed .. first_seed + runs` in parallel, checking every trace. `progress`
/// is called once per finished run (from any thread).
pub fn run_many(
    input: MissionInput<'_>,
    coord: Coord,
    slot: f64,
    first_seed: u64,
    runs: usize,
    progress: &(dyn Fn() + Sync),
) -> Result<Vec<MissionResult>, (u64, TraceError)> {
    (0..runs as u64)
        .into_par_iter()
        .map(|i| {
            let seed = first_seed.wrapping_add(i);
            let mut policy = make_policy(coord, slot);
            let mut checker = TraceChecker::new(input.wall, input.config.uavs);
            let r = simulate(input, policy.as_mut(), seed, &mut checker);
            progress();
            checker.finish().map(|_| r).map_err(|e| (seed, e))
        })
        .collect()
}
