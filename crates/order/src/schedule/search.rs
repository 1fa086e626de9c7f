//! The anytime team schedule planner: list scheduling with a local search over priority lists.
//!
//! * Starting lists: level by level (left to right), longest remaining chain first, and, under a
//!   budget, the bricks of the precedence-constrained knapsack's best fitting closure first
//!   (from the reward bound), filled greedily by reward per UAV-cycle.
//! * Moves: take a brick and move it, with the ancestors that come after the new place, to a
//!   random earlier or later place; decode with [`super::sgs`]; keep the list if the score is
//!   no worse (plateau moves let the search drift). After many moves without improvement it
//!   restarts from the best list, perturbed.
//! * Scores: `makespan` — (makespan, Σ ends); `reward` — (−reward, makespan, Σ ends);
//!   `expected` — the reward averaged over sampled failure scenarios, in which at each failure
//!   the survivors re-decode the rest of the same list from that moment (common random
//!   numbers: every list is scored on the same scenarios).
//! * Two threads search from different seeds; the better result wins, ties to the first, so
//!   the result depends only on the seed unless the deadline stops the search.
//! * Stops when the result meets its bound (status `Optimal`), at the budget's node cap
//!   (decodes per thread) or at its deadline (`Timeout`, best so far).
//! * Under the zone rule, a whole-wall makespan result then goes through
//!   [`super::polish`] (two threads, seeds 2s and 2s + 1; under a deadline the list search
//!   gets three quarters of the time left); a polished schedule is kept only if
//!   [`validate_schedule`] accepts it and it ends earlier.

use super::bounds::{
    earliest_end, expected_reward_upper_bound_within, makespan_lower_bound_within,
    reward_upper_bound_within, RewardBound,
};
use super::polish;
use super::problem::{Objective, Placement, Schedule, TeamOutcome, TeamProblem, TeamStats};
use super::sgs::{Decoded, Decoder, Mode};
use super::slots::{exact_with_work, least_makespan_at, EXACT_WORK};
use super::validate::validate_schedule;
use crate::outcome::{Better, Budget, Status};
use mason_wall::BrickId;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::time::Instant;

/// Decodes per thread when the budget sets no node cap, for walls up to [`FULL_DECODES_UP_TO`]
/// bricks.
pub const DEFAULT_DECODES: u64 = 4000;

/// Walls up to this size get the full [`DEFAULT_DECODES`] (more for small walls); larger ones
/// get fewer in proportion, so that the deterministic search's work stays that of a
/// 2048-brick wall (at least [`LEAST_DECODES`]).
pub const FULL_DECODES_UP_TO: u64 = 2048;

/// The fewest decodes per thread of the deterministic search.
pub const LEAST_DECODES: u64 = 16;

/// Decodes per thread of the deterministic search (no node cap, no deadline) on `n` bricks.
pub fn default_decodes(n: usize) -> u64 {
    let n = n.max(1) as u64;
    if n <= FULL_DECODES_UP_TO {
        DEFAULT_DECODES.max(2_000_000 / n)
    } else {
        (DEFAULT_DECODES * FULL_DECODES_UP_TO / n).max(LEAST_DECODES)
    }
}

/// Failure scenarios sampled for the `expected` objective.
pub const SCENARIOS: usize = 32;

/// A score: smaller is better, compared lexicographically.
type Score = [f64; 3];

fn better(a: &Score, b: &Score) -> bool {
    for k in 0..3 {
        if a[k] < b[k] - 1e-9 {
            return true;
        }
        if a[k] > b[k] + 1e-9 {
            return false;
        }
    }
    false
}

/// One failure scenario: each UAV's failure time (∞: it survives).
type Scenario = Vec<f64>;

fn scenarios(p: &TeamProblem<'_>, hazard_per_hour: f64, seed: u64) -> Vec<Scenario> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed ^ 0x5eed_fa11);
    let rate = hazard_per_hour / 3600.0;
    (0..SCENARIOS)
        .map(|_| {
            (0..p.uavs())
                .map(|_| {
                    if rate > 0.0 {
                        let u: f64 = rng.gen::<f64>();
                        -(1.0 - u).ln() / rate
                    } else {
                        f64::INFINITY
                    }
                })
                .collect()
        })
        .collect()
}

/// The reward `list` earns in one scenario, given its fault-free decode (`fault_free`, with
/// reward `fault_free_reward`): at each failure the failed UAV's placement in progress is lost
/// and the survivors decode the rest of the list from that moment.
///
/// Each failure re-decodes the rest of the list, so a scenario can cost a decode per UAV. When
/// `budget` runs out first, the scenario stops with a value that is never above its true one
/// (see [`safe_reward`]) and `false`; otherwise the value is exact and `true`.
pub fn reward_under_failures(
    p: &TeamProblem<'_>,
    decoder: &mut Decoder<'_, '_>,
    list: &[BrickId],
    fault_free: &Schedule,
    fault_free_reward: f64,
    failures: &[f64],
    budget: &Budget,
) -> (f64, bool) {
    let mut reward = fault_free_reward;
    let mut events: Vec<(f64, usize)> = failures
        .iter()
        .enumerate()
        .filter(|(_, t)| t.is_finite())
        .map(|(u, &t)| (t, u))
        .collect();
    events.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
    let mut alive = vec![true; failures.len()];
    let mut schedule = fault_free.clone();
    let mut done = vec![false; p.len()];
    for (t, u) in events {
        alive[u] = false;
        let busy_after = |pl: &Placement| pl.start_s + p.place_s(pl.brick) > t;
        let lost = |pl: &Placement| pl.uavs.contains(&u) && busy_after(pl);
        if schedule
            .placements
            .iter()
            .all(|pl| pl.start_s < t && !lost(pl))
        {
            // Everything had started by t and u had finished its part: nothing changes.
            continue;
        }
        if budget.out_of_time() {
            return (safe_reward(p, &schedule, t), false);
        }
        let kept: Vec<Placement> = schedule
            .placements
            .iter()
            .filter(|pl| pl.start_s < t && !lost(pl))
            .cloned()
            .collect();
        done.fill(false);
        for pl in &kept {
            done[pl.brick.index()] = true;
        }
        let rest: Vec<BrickId> = list.iter().copied().filter(|b| !done[b.index()]).collect();
        reward = decoder.resume(&kept, &alive, t, &rest).reward;
        schedule = decoder.schedule();
    }
    (reward, true)
}

/// The reward of `schedule`'s placements that end by `t` (and by the budget): a failure at or
/// after `t` cannot take them back, and a re-decode after it only adds, so this is never above
/// the scenario's reward.
fn safe_reward(p: &TeamProblem<'_>, schedule: &Schedule, t: f64) -> f64 {
    let by = p.budget_s().map_or(t, |b| b.min(t));
    schedule
        .placements
        .iter()
        .filter(|pl| pl.start_s + p.place_s(pl.brick) <= by)
        .map(|pl| p.reward(pl.brick))
        .sum()
}

struct Searcher<'a, 'w> {
    p: &'a TeamProblem<'w>,
    decoder: Decoder<'a, 'w>,
    scenarios: Vec<Scenario>,
    budget: &'a Budget,
    /// A score was cut short by the deadline: its expected reward is a conservative estimate.
    cut_short: bool,
    /// The last list's fault-free decode.
    last: Option<Decoded>,
    decodes: u64,
    improvements: u64,
}

impl Searcher<'_, '_> {
    /// The decode and schedule of the list just scored, if `keep` and it was decoded whole.
    fn kept(&self, keep: bool) -> Option<(Decoded, Schedule)> {
        self.last
            .filter(|_| keep)
            .map(|d| (d, self.decoder.schedule()))
    }

    fn score(&mut self, list: &[BrickId]) -> Score {
        self.decodes += 1;
        // A parallel decode given up at the deadline scores worst: the other thread's serial
        // decode always ends, so the search still has a schedule.
        let Some(d) = self.decoder.decode_within(list, self.budget) else {
            self.last = None;
            return [f64::INFINITY; 3];
        };
        self.last = Some(d);
        match self.p.objective() {
            Objective::Makespan => [d.makespan_s, d.sum_end_s, 0.0],
            Objective::Reward => [-d.reward, d.makespan_s, d.sum_end_s],
            Objective::Expected { .. } => {
                let fault_free = self.decoder.schedule();
                let mut total = 0.0;
                for f in &self.scenarios {
                    // Past the deadline, a scenario not yet flown counts what its first
                    // failure cannot take back.
                    let (r, whole) = if self.cut_short {
                        let first = f.iter().copied().fold(f64::INFINITY, f64::min);
                        (safe_reward(self.p, &fault_free, first), false)
                    } else {
                        reward_under_failures(
                            self.p,
                            &mut self.decoder,
                            list,
                            &fault_free,
                            d.reward,
                            f,
                            self.budget,
                        )
                    };
                    self.cut_short |= !whole;
                    total += r;
                }
                [
                    -total / self.scenarios.len() as f64,
                    -d.reward,
                    d.makespan_s,
                ]
            }
        }
    }
}

/// Bricks sorted by (level, left edge): the layer-by-layer list.
fn level_list(p: &TeamProblem<'_>) -> Vec<BrickId> {
    let wall = p.wall();
    let mut l: Vec<BrickId> = wall.ids().collect();
    l.sort_by(|&a, &b| {
        let (x, y) = (wall.brick(a), wall.brick(b));
        x.level
            .cmp(&y.level)
            .then(x.footprint.x0.total_cmp(&y.footprint.x0))
            .then(a.cmp(&b))
    });
    l
}

/// The longest chain of placing phases from each brick to the top.
fn tails(p: &TeamProblem<'_>) -> Vec<f64> {
    let wall = p.wall();
    let mut order = level_list(p);
    order.reverse();
    let mut tail = vec![0.0; p.len()];
    for b in order {
        let above = wall
            .carried(b)
            .iter()
            .map(|c| tail[c.index()])
            .fold(0.0, f64::max);
        tail[b.index()] = above + p.place_s(b);
    }
    tail
}

/// Longest remaining chain first, then level, then left edge.
fn chain_list(p: &TeamProblem<'_>) -> Vec<BrickId> {
    let tail = tails(p);
    let mut l = level_list(p);
    l.sort_by(|&a, &b| tail[b.index()].total_cmp(&tail[a.index()]));
    l
}

/// Node visits that [`knapsack_list`]'s greedy additions may make in all (a start list is a
/// heuristic: past this, or past the deadline, it stops adding and lists the rest by ratio).
const KNAPSACK_WORK: u64 = 50_000_000;

/// Under a budget: the knapsack closure first (level order), then greedy additions by reward
/// per weight of the brick and its missing supports, then everything else.
fn knapsack_list(
    p: &TeamProblem<'_>,
    budget_s: f64,
    rb: &RewardBound,
    search: &Budget,
) -> Vec<BrickId> {
    let wall = p.wall();
    let head = earliest_end(p);
    let mut chosen = rb.fitting.clone();
    let mut used: f64 = (0..p.len())
        .filter(|&i| chosen[i])
        .map(|i| rb.weight[i])
        .sum();
    // Group membership by stamp: each group gets a fresh one.
    let mut stamp = vec![0u64; p.len()];
    let mut next_stamp = 0u64;
    let mut work = 0u64;
    'rounds: loop {
        if search.out_of_time() {
            break;
        }
        // Best addable group: a brick with its unchosen ancestors.
        let mut best: Option<(f64, Vec<usize>)> = None;
        for b in wall.ids() {
            if chosen[b.index()]
                || head[b.index()] > budget_s + 1e-9
                // Weights are never negative: a group weighs at least its brick.
                || used + rb.weight[b.index()] > rb.capacity + 1e-9
            {
                continue;
            }
            next_stamp += 1;
            stamp[b.index()] = next_stamp;
            let mut group = vec![b.index()];
            let mut k = 0;
            while k < group.len() {
                for s in wall.supports(BrickId(group[k] as u32)) {
                    if !chosen[s.index()] && stamp[s.index()] != next_stamp {
                        stamp[s.index()] = next_stamp;
                        group.push(s.index());
                    }
                }
                k += 1;
            }
            work += group.len() as u64;
            if work > KNAPSACK_WORK {
                break 'rounds;
            }
            let w: f64 = group.iter().map(|&i| rb.weight[i]).sum();
            if used + w > rb.capacity + 1e-9 {
                continue;
            }
            let r: f64 = group.iter().map(|&i| p.reward(BrickId(i as u32))).sum();
            let ratio = r / w.max(1e-9);
            if best.as_ref().is_none_or(|(q, _)| ratio > *q + 1e-12) {
                best = Some((ratio, group));
            }
        }
        let Some((_, group)) = best else { break };
        for i in group {
            used += rb.weight[i];
            chosen[i] = true;
        }
    }
    let levels = level_list(p);
    let mut l: Vec<BrickId> = levels
        .iter()
        .copied()
        .filter(|b| chosen[b.index()])
        .collect();
    let mut rest: Vec<BrickId> = levels.into_iter().filter(|b| !chosen[b.index()]).collect();
    // The rest by reward per weight, best first (stable: level order within ties).
    rest.sort_by(|&a, &b| {
        let ra = p.reward(a) / rb.weight[a.index()].max(1e-9);
        let rb_ = p.reward(b) / rb.weight[b.index()].max(1e-9);
        rb_.total_cmp(&ra)
    });
    l.extend(rest);
    l
}

/// Move `list[i]` to position `j`, taking along (before it) its ancestors that sit after `j`.
fn pull(p: &TeamProblem<'_>, list: &mut Vec<BrickId>, pos: &mut [usize], i: usize, j: usize) {
    let b = list[i];
    let mut group = vec![b];
    if j < i {
        let mut k = 0;
        while k < group.len() {
            for &s in p.wall().supports(group[k]) {
                if pos[s.index()] > j && !group.contains(&s) {
                    group.push(s);
                }
            }
            k += 1;
            if group.len() > 64 {
                break;
            }
        }
    }
    group.sort_by_key(|g| pos[g.index()]);
    let mut in_group = vec![false; p.len()];
    for g in &group {
        in_group[g.index()] = true;
    }
    let rest: Vec<BrickId> = list
        .iter()
        .copied()
        .filter(|x| !in_group[x.index()])
        .collect();
    let at = rest.iter().take_while(|x| pos[x.index()] < j).count();
    let mut out = Vec::with_capacity(list.len());
    out.extend_from_slice(&rest[..at]);
    out.extend_from_slice(&group);
    out.extend_from_slice(&rest[at..]);
    *list = out;
    for (k, x) in list.iter().enumerate() {
        pos[x.index()] = k;
    }
}

fn positions(list: &[BrickId], n: usize) -> Vec<usize> {
    let mut pos = vec![0; n];
    for (k, b) in list.iter().enumerate() {
        pos[b.index()] = k;
    }
    pos
}

/// What a search thread aims at: the objective's bound (`target`: stop there) and when the
/// search started (for progress reports).
#[derive(Clone, Copy)]
struct Aim {
    target: Option<f64>,
    bound: f64,
    started: Instant,
}

struct ThreadResult {
    mode: Mode,
    score: Score,
    list: Vec<BrickId>,
    /// The best list's decode and schedule, when the thread still had them.
    decoded: Option<(Decoded, Schedule)>,
    decodes: u64,
    improvements: u64,
    timed_out: bool,
}

fn search_thread(
    p: &TeamProblem<'_>,
    starts: &[Vec<BrickId>],
    budget: &Budget,
    seed: u64,
    mode: Mode,
    aim: Aim,
    scen: Vec<Scenario>,
) -> ThreadResult {
    let Aim {
        target,
        bound,
        started: t0,
    } = aim;
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut s = Searcher {
        p,
        decoder: Decoder::new(p, mode),
        scenarios: scen,
        budget,
        cut_short: false,
        last: None,
        decodes: 0,
        improvements: 0,
    };
    // Small walls decode fast: give them more decodes (the same for every seed); an
    // `expected` score costs a decode per failure scenario, so it gets fewer.
    let per_score = 1 + s.scenarios.len() as u64;
    let cap = budget
        .node_limit
        .unwrap_or(default_decodes(p.len()) / per_score);
    // The primary objective at its bound: nothing can beat it.
    let reached = |sc: &Score| target.is_some_and(|t| sc[0] <= t + 1e-9);
    let mut timed_out = false;
    let mut best_list = starts[0].clone();
    let mut best = s.score(&best_list);
    // The best list's decode and schedule, taken when it is scored (improvements are few): a
    // decode of a huge wall can take longer than what is left of a time limit, so the winner
    // is never decoded again after the search (an `expected` score ends on a scenario's
    // decode, so there the winner is decoded again).
    let keep = !matches!(p.objective(), Objective::Expected { .. });
    let mut best_decoded = s.kept(keep);
    for l in &starts[1..] {
        if budget.out_of_time() {
            timed_out = true;
            break;
        }
        let sc = s.score(l);
        if better(&sc, &best) {
            best = sc;
            best_list = l.clone();
            best_decoded = s.kept(keep);
        }
    }
    // The listener hears the objective itself: a makespan, or a (expected) reward.
    let tell = |sc: &Score, decodes: u64| {
        budget.better(Better {
            value: match p.objective() {
                Objective::Makespan => sc[0],
                _ => -sc[0],
            },
            bound,
            decodes,
            elapsed_s: t0.elapsed().as_secs_f64(),
        })
    };
    tell(&best, s.decodes);
    let n = p.len();
    let mut cur = best_list.clone();
    let mut cur_score = best;
    let mut pos = positions(&cur, n);
    let mut stale = 0u64;
    let patience = (40 * n as u64).clamp(200, 4000);
    while !reached(&best) && s.decodes < cap && n > 1 {
        if budget.out_of_time() {
            timed_out = true;
            break;
        }
        let mut cand = cur.clone();
        let mut cpos = pos.clone();
        let moves = if rng.gen_bool(0.8) {
            1
        } else {
            rng.gen_range(2..4)
        };
        for _ in 0..moves {
            let i = rng.gen_range(0..n);
            let span = (n / 4).max(4);
            let lo = i.saturating_sub(span);
            let hi = (i + span).min(n - 1);
            let j = rng.gen_range(lo..=hi);
            pull(p, &mut cand, &mut cpos, i, j);
        }
        let sc = s.score(&cand);
        if !better(&cur_score, &sc) {
            if better(&sc, &cur_score) {
                stale = 0;
            } else {
                stale += 1;
            }
            cur = cand;
            pos = cpos;
            cur_score = sc;
            if better(&cur_score, &best) {
                best = cur_score;
                best_list = cur.clone();
                best_decoded = s.kept(keep);
                s.improvements += 1;
                tell(&best, s.decodes);
            }
        } else {
            stale += 1;
        }
        if stale > patience {
            // Restart from the best list with a random kick.
            cur = best_list.clone();
            pos = positions(&cur, n);
            for _ in 0..rng.gen_range(2..6) {
                let i = rng.gen_range(0..n);
                let j = rng.gen_range(0..n);
                pull(p, &mut cur, &mut pos, i, j);
            }
            cur_score = s.score(&cur);
            stale = 0;
        }
    }
    let decoded = best_decoded;
    ThreadResult {
        mode,
        score: best,
        list: best_list,
        decoded,
        decodes: s.decodes,
        improvements: s.improvements,
        timed_out: timed_out || s.cut_short,
    }
}

/// Work (in [`EXACT_WORK`]'s units) of the exact reward bound's first try, before the search.
const FIRST_EXACT_WORK: u64 = EXACT_WORK / 4;

/// The bricks of `s` in start order, then the rest level by level: a list that decodes to
/// (nearly) `s`.
fn schedule_list(p: &TeamProblem<'_>, s: &Schedule) -> Vec<BrickId> {
    let mut sorted = s.clone();
    sorted.sort();
    let mut seen = vec![false; p.len()];
    let mut list: Vec<BrickId> = Vec::with_capacity(p.len());
    for pl in &sorted.placements {
        if !std::mem::replace(&mut seen[pl.brick.index()], true) {
            list.push(pl.brick);
        }
    }
    list.extend(level_list(p).into_iter().filter(|b| !seen[b.index()]));
    list
}

/// The figures of a full-slot schedule earning `reward`.
fn slot_decoded(p: &TeamProblem<'_>, s: &Schedule, reward: f64) -> Decoded {
    let ends = || {
        s.placements
            .iter()
            .map(|pl| pl.start_s + p.place_s(pl.brick))
    };
    Decoded {
        reward,
        makespan_s: ends().fold(0.0, f64::max),
        sum_end_s: ends().sum(),
        placed: s.placements.len(),
    }
}

/// Plans a team schedule for `p`'s objective within `budget`, deterministically for `seed`
/// (unless the deadline stops it), on up to two threads.
pub fn plan_schedule(p: &TeamProblem<'_>, budget: &Budget, seed: u64) -> TeamOutcome {
    plan_schedule_with(p, budget, seed, &[])
}

/// [`plan_schedule`] with extra starting lists (e.g. the plan being repaired).
pub fn plan_schedule_with(
    p: &TeamProblem<'_>,
    budget: &Budget,
    seed: u64,
    extra_starts: &[Vec<BrickId>],
) -> TeamOutcome {
    let t0 = Instant::now();
    // Bounds are for whole problems; a replan from a start state reports none.
    let whole = p.start().is_none();
    let reward_bound = p
        .budget_s()
        .filter(|_| whole)
        .map(|b| (b, reward_upper_bound_within(p, b, budget)));
    let mut starts: Vec<Vec<BrickId>> = extra_starts.to_vec();
    if let Some((b, rb)) = &reward_bound {
        starts.push(knapsack_list(p, *b, rb, budget));
    }
    // Under `reward`, a first, short try at the exact bound (cheap where the LP bound is tight or
    // nearly so): its full-slot schedule, if any, starts the search too.
    let exact = match (p.objective(), &reward_bound) {
        (Objective::Reward, Some((b, rb))) => {
            let e = exact_with_work(p, *b, 0.0, rb.bound, budget, FIRST_EXACT_WORK);
            if let Some((s, _)) = &e.schedule {
                starts.push(schedule_list(p, s));
            }
            Some(e)
        }
        _ => None,
    };
    starts.push(level_list(p));
    starts.push(chain_list(p));
    // Only the makespan objective stops at its bound: under a budget, reaching the reward
    // bound still leaves the makespan to shorten.
    let (bound, target) = match (p.objective(), &reward_bound) {
        _ if !whole => (f64::NAN, None),
        (Objective::Makespan, _) => {
            let lb = makespan_lower_bound_within(p, budget);
            (lb, Some(lb))
        }
        (Objective::Reward, Some((_, rb))) => (
            exact.as_ref().map_or(rb.bound, |e| e.bound.min(rb.bound)),
            None,
        ),
        (Objective::Expected { hazard_per_hour }, Some((b, _))) => (
            expected_reward_upper_bound_within(p, *b, hazard_per_hour, budget),
            None,
        ),
        (_, None) => unreachable!("TeamProblem::new requires a budget for reward and expected"),
    };
    // The first try's schedule may be optimal on both counts already: its reward at the bound,
    // and its makespan the least any schedule earning that much can have. Then there is
    // nothing left to search.
    if let (Some(e), Some((b, _))) = (&exact, &reward_bound) {
        if let (true, Some((s, reward))) = (e.complete, &e.schedule) {
            let d = slot_decoded(p, s, *reward);
            let least = (*reward >= bound - 1e-9)
                .then(|| least_makespan_at(p, *b, *reward, budget, FIRST_EXACT_WORK))
                .flatten();
            if least.is_some_and(|l| d.makespan_s <= l + 1e-9) {
                budget.better(Better {
                    value: *reward,
                    bound,
                    decodes: 0,
                    elapsed_s: t0.elapsed().as_secs_f64(),
                });
                return TeamOutcome {
                    status: Status::Optimal,
                    schedule: Some(s.clone()),
                    reward: *reward,
                    makespan_s: d.makespan_s,
                    expected_reward: None,
                    bound,
                    stats: TeamStats {
                        elapsed: t0.elapsed(),
                        decodes: 0,
                        improvements: 0,
                    },
                };
            }
        }
    }
    let scen = match p.objective() {
        Objective::Expected { hazard_per_hour } => scenarios(p, hazard_per_hour, seed),
        _ => Vec::new(),
    };
    // Under the zone rule, a whole-wall makespan search ends with the polish of its best
    // schedule ([`super::polish`]); under a deadline the list search leaves it a quarter of the
    // time left.
    let polish = p.objective() == Objective::Makespan
        && whole
        && p.zone_rule()
        && (2..=polish::MAX_BRICKS).contains(&p.len());
    let search_budget = match (polish, budget.deadline) {
        (true, Some(d)) => {
            let now = Instant::now();
            Budget {
                deadline: Some(now + d.saturating_duration_since(now).mul_f64(0.75)),
                ..budget.clone()
            }
        }
        _ => budget.clone(),
    };
    let budget_all = budget;
    let budget = &search_budget;
    let mut results: Vec<ThreadResult> = std::thread::scope(|sc| {
        let handles: Vec<_> = (0..2u64)
            .map(|k| {
                let starts = &starts;
                let scen = scen.clone();
                let mode = if k == 0 { Mode::Parallel } else { Mode::Serial };
                sc.spawn(move || {
                    search_thread(
                        p,
                        starts,
                        budget,
                        seed.wrapping_mul(2).wrapping_add(k),
                        mode,
                        Aim {
                            target,
                            bound,
                            started: t0,
                        },
                        scen,
                    )
                })
            })
            .collect();
        handles
            .into_iter()
            .map(|h| h.join().expect("search thread"))
            .collect()
    });
    let mut win = 0;
    for k in 1..results.len() {
        if better(&results[k].score, &results[win].score) {
            win = k;
        }
    }
    let timed_out = results.iter().any(|r| r.timed_out);
    let decodes = results.iter().map(|r| r.decodes).sum();
    let improvements = results.iter().map(|r| r.improvements).sum();
    let r = results.swap_remove(win);
    let (mut d, mut schedule) = r.decoded.unwrap_or_else(|| {
        let mut decoder = Decoder::new(p, r.mode);
        let d = decoder.decode(&r.list);
        (d, decoder.schedule())
    });
    let budget = budget_all;
    if polish && d.makespan_s > bound + 1e-9 && !budget.out_of_time() {
        // Moves per thread: the default's, no more than a node cap, unbounded under a deadline
        // (which stops it).
        let moves = match budget.node_limit {
            Some(u64::MAX) if budget.deadline.is_some() => u64::MAX,
            Some(cap) => cap.min(polish::polish_moves(p.len())),
            None => polish::polish_moves(p.len()),
        };
        let found: Vec<Option<Schedule>> = std::thread::scope(|sc| {
            let handles: Vec<_> = (0..2u64)
                .map(|k| {
                    let schedule = &schedule;
                    let seed = seed.wrapping_mul(2).wrapping_add(k);
                    sc.spawn(move || polish::polish_zone_makespan(p, schedule, moves, seed, budget))
                })
                .collect();
            handles
                .into_iter()
                .map(|h| h.join().expect("polish thread"))
                .collect()
        });
        for s in found.into_iter().flatten() {
            // Kept only if the independent validator agrees that it places every brick
            // earlier; ties go to the first thread.
            if let Ok(e) = validate_schedule(p.wall(), p.model(), p.uavs(), None, &s) {
                if e.bricks == p.len() && e.makespan_s < d.makespan_s - 1e-9 {
                    d.makespan_s = e.makespan_s;
                    d.sum_end_s = s
                        .placements
                        .iter()
                        .map(|pl| pl.start_s + p.place_s(pl.brick))
                        .sum();
                    schedule = s;
                    budget.better(Better {
                        value: d.makespan_s,
                        bound,
                        decodes,
                        elapsed_s: t0.elapsed().as_secs_f64(),
                    });
                }
            }
        }
    }
    let mut bound = bound;
    if let (Some(first), Some((b, _))) = (exact, &reward_bound) {
        // Still below the bound after the search, and the first try stopped short: the whole
        // work cap, now given the reward reached.
        let more = (d.reward < bound - 1e-9 && !first.complete)
            .then(|| exact_with_work(p, *b, d.reward, bound, budget, EXACT_WORK));
        for e in [Some(first), more].into_iter().flatten() {
            bound = bound.min(e.bound);
            if let Some((s, reward)) = e.schedule {
                if reward > d.reward + 1e-9 {
                    d = slot_decoded(p, &s, reward);
                    schedule = s;
                }
            }
        }
    }
    let expected_reward = match p.objective() {
        Objective::Expected { .. } => Some(-r.score[0]),
        _ => None,
    };
    let value_meets_bound = match p.objective() {
        Objective::Makespan => d.makespan_s <= bound + 1e-9,
        Objective::Reward => d.reward >= bound - 1e-9,
        Objective::Expected { .. } => false,
    };
    let status = if value_meets_bound {
        Status::Optimal
    } else if timed_out {
        Status::Timeout
    } else {
        Status::Feasible
    };
    TeamOutcome {
        status,
        schedule: Some(schedule),
        reward: d.reward,
        makespan_s: d.makespan_s,
        expected_reward,
        bound,
        stats: TeamStats {
            elapsed: t0.elapsed(),
            decodes,
            improvements,
        },
    }
}
