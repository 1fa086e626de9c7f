//! Monte Carlo: many seeded missions spread over the cores with rayon; every trace is checked.
//!
//! Statistics stream: [`for_each_run`] flies the seeds in chunks of [`CHUNK`] and hands each
//! result, in seed order, to a sink, so memory does not grow with the number of runs. A
//! [`Stream`] keeps the mean exactly (a compensated sum in seed order) and its p5 and p95 from a
//! bounded sample: every value while there are at most [`SAMPLE_CAP`] (then the percentiles are
//! exact, and equal to [`Spread::of`]), after that a uniform reservoir sample of
//! [`SAMPLE_CAP`] values (Vitter's Algorithm R, with a fixed-seed ChaCha8 generator, so the
//! figures are the same bit for bit for the same seeds).

use crate::check::{TraceChecker, TraceError};
use crate::coord::{make_policy, Coord};
use crate::sim::{simulate, MissionInput, MissionResult, MissionStatus};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rayon::prelude::*;
use serde::Serialize;

/// How many values a [`Stream`] keeps for its percentiles (512 KiB).
pub const SAMPLE_CAP: usize = 65_536;
/// How many seeds [`for_each_run`] flies at once before handing their results on.
pub const CHUNK: usize = 4_096;

/// Streaming mean and p5/p95 of one quantity (see the module documentation).
#[derive(Clone, Debug)]
pub struct Stream {
    n: u64,
    sum: f64,
    compensation: f64,
    sample: Vec<f64>,
    rng: ChaCha8Rng,
}

impl Default for Stream {
    fn default() -> Self {
        Stream {
            n: 0,
            sum: 0.0,
            compensation: 0.0,
            sample: Vec::new(),
            rng: ChaCha8Rng::seed_from_u64(0x5eed_5a3b),
        }
    }
}

impl Stream {
    /// Adds one value.
    pub fn push(&mut self, v: f64) {
        self.n += 1;
        // Neumaier's compensated sum.
        let t = self.sum + v;
        if self.sum.abs() >= v.abs() {
            self.compensation += (self.sum - t) + v;
        } else {
            self.compensation += (v - t) + self.sum;
        }
        self.sum = t;
        if self.sample.len() < SAMPLE_CAP {
            self.sample.push(v);
        } else {
            let j = self.rng.gen_range(0..self.n);
            if (j as usize) < SAMPLE_CAP {
                self.sample[j as usize] = v;
            }
        }
    }

    /// Values pushed.
    pub fn count(&self) -> u64 {
        self.n
    }

    /// The spread: exactly [`Spread::of`] up to [`SAMPLE_CAP`] values; beyond, the exact mean
    /// and the sample's percentiles.
    pub fn spread(&self) -> Spread {
        let mut s = Spread::of(&self.sample);
        if self.n > SAMPLE_CAP as u64 {
            s.mean = (self.sum + self.compensation) / self.n as f64;
        }
        s
    }
}

/// Streaming [`Summary`] (and, optionally, the reward by a time and the mean re-plans).
#[derive(Clone, Debug)]
pub struct Summariser {
    runs: usize,
    completed: usize,
    makespan: Stream,
    bricks: Stream,
    reward: Stream,
    zone: Stream,
    reward_by: Option<(f64, Stream)>,
    replans: u64,
}

impl Summariser {
    /// An empty summary; with `reward_by_t`, also the reward placed by that time.
    pub fn new(reward_by_t: Option<f64>) -> Self {
        Summariser {
            runs: 0,
            completed: 0,
            makespan: Stream::default(),
            bricks: Stream::default(),
            reward: Stream::default(),
            zone: Stream::default(),
            reward_by: reward_by_t.map(|t| (t, Stream::default())),
            replans: 0,
        }
    }

    /// Adds one run.
    pub fn push(&mut self, r: &MissionResult) {
        self.push_figures(&RunFigures::of(r));
        if let Some((t, s)) = &mut self.reward_by {
            s.push(reward_placed_by(r, *t));
        }
        self.replans += r.metrics.replans as u64;
    }

    /// Adds one run's [`RunFigures`] (as [`Summariser::push`] does for a whole result, without
    /// the reward-by-time and replan figures): runs summarised elsewhere, e.g. on other machines,
    /// give the same summary when pushed in seed order.
    pub fn push_figures(&mut self, f: &RunFigures) {
        self.runs += 1;
        if f.complete {
            if let Some(m) = f.makespan_s {
                self.completed += 1;
                self.makespan.push(m);
            }
        }
        self.bricks.push(f.bricks_placed as f64);
        self.reward.push(f.reward);
        self.zone.push(f.zone_utilisation);
    }

    /// The summary so far.
    pub fn summary(&self) -> Summary {
        Summary {
            runs: self.runs,
            completed: self.completed,
            makespan_s: self.makespan.spread(),
            bricks_placed: self.bricks.spread(),
            reward: self.reward.spread(),
            zone_utilisation: self.zone.spread(),
        }
    }

    /// The reward placed by the time given to [`Summariser::new`].
    pub fn reward_by(&self) -> Option<Spread> {
        self.reward_by.as_ref().map(|(_, s)| s.spread())
    }

    /// Mean re-plans per run.
    pub fn replans_mean(&self) -> f64 {
        self.replans as f64 / self.runs.max(1) as f64
    }
}

fn reward_placed_by(r: &MissionResult, t: f64) -> f64 {
    r.metrics
        .reward_over_time
        .iter()
        .take_while(|(at, _)| *at <= t)
        .last()
        .map_or(0.0, |&(_, reward)| reward)
}

/// The figures of one run that a [`Summary`] is made of.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct RunFigures {
    /// The wall was completed.
    pub complete: bool,
    /// Makespan (s), when completed.
    pub makespan_s: Option<f64>,
    /// Bricks placed.
    pub bricks_placed: usize,
    /// Reward placed.
    pub reward: f64,
    /// Zone utilisation.
    pub zone_utilisation: f64,
}

impl RunFigures {
    /// The figures of a result.
    pub fn of(r: &MissionResult) -> Self {
        RunFigures {
            complete: r.status == MissionStatus::Complete,
            makespan_s: r.metrics.makespan_s,
            bricks_placed: r.metrics.bricks_placed,
            reward: r.metrics.reward,
            zone_utilisation: r.metrics.zone_utilisation,
        }
    }
}

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
    let mut s = Summariser::new(None);
    for r in results {
        s.push(r);
    }
    s.summary()
}

/// The reward each run had placed by `t` seconds.
pub fn reward_by(results: &[MissionResult], t: f64) -> Spread {
    let mut s = Stream::default();
    for r in results {
        s.push(reward_placed_by(r, t));
    }
    s.spread()
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
    let mut out = Vec::with_capacity(runs.min(CHUNK));
    for_each_run(input, coord, slot, first_seed, runs, progress, &mut |r| {
        out.push(r.clone())
    })?;
    Ok(out)
}

/// Runs seeds `first_seed .. first_seed + runs`, [`CHUNK`] at a time in parallel, checking
/// every trace, and hands each result to `sink` in seed order; memory stays that of one chunk.
/// `progress` is called once per finished run (from any thread).
pub fn for_each_run(
    input: MissionInput<'_>,
    coord: Coord,
    slot: f64,
    first_seed: u64,
    runs: usize,
    progress: &(dyn Fn() + Sync),
    sink: &mut dyn FnMut(&MissionResult),
) -> Result<(), (u64, TraceError)> {
    let mut start = 0u64;
    while start < runs as u64 {
        let end = (start + CHUNK as u64).min(runs as u64);
        let chunk: Vec<MissionResult> = (start..end)
            .into_par_iter()
            .map(|i| {
                let seed = first_seed.wrapping_add(i);
                let mut policy = make_policy(coord, slot);
                let mut checker = TraceChecker::new(input.wall, input.config.uavs);
                let r = simulate(input, policy.as_mut(), seed, &mut checker);
                progress();
                if let Some(f) = r.flood {
                    return Err((seed, TraceError::Flooded(f)));
                }
                checker.finish().map(|_| r).map_err(|e| (seed, e))
            })
            .collect::<Result<_, _>>()?;
        for r in &chunk {
            sink(r);
        }
        start = end;
    }
    Ok(())
}

#[cfg(test)]
mod stream_tests {
    use super::*;

    #[test]
    fn a_stream_equals_spread_of_up_to_the_cap() {
        let values: Vec<f64> = (0..1000)
            .map(|i| ((i * 7919) % 1000) as f64 * 0.5)
            .collect();
        let mut s = Stream::default();
        for &v in &values {
            s.push(v);
        }
        assert_eq!(s.spread(), Spread::of(&values));
    }

    #[test]
    fn beyond_the_cap_memory_is_bounded_the_mean_exact_and_the_result_repeatable() {
        let n = 3 * SAMPLE_CAP as u64 + 17;
        let run = || {
            let mut s = Stream::default();
            for i in 0..n {
                s.push((i % 1000) as f64);
            }
            assert_eq!(s.sample.len(), SAMPLE_CAP);
            s.spread()
        };
        let a = run();
        assert_eq!(a, run());
        let exact_mean = (0..n).map(|i| (i % 1000) as f64).sum::<f64>() / n as f64;
        assert!((a.mean - exact_mean).abs() < 1e-9);
        assert!((a.p5 - 50.0).abs() <= 10.0, "{a:?}");
        assert!((a.p95 - 950.0).abs() <= 10.0, "{a:?}");
    }
}
