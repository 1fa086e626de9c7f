//! Restarts of the LaCAM configuration search ([`crate::lacam`]), two at a time.
//!
//! LaCAM's depth-first search is complete but its first descent can wander: on a dense room
//! (MovingAI room-32-32-4, 341 robots, 4-connected) one seed in three walked 21 000
//! configurations before it reached the goals, a plan with a makespan of 21 382 and a sum of
//! costs 82 times the lower bound, which no amount of refinement repairs. Other seeds found
//! plans after about 300 configurations. The cure is the one SAT solvers use for heavy-tailed
//! runs: restart with another seed under a cap on the search, and raise the cap each time.
//!
//! Attempts run in pairs side by side (rayon), both under the same cap on LaCAM iterations;
//! the cap starts at `4 · (longest shortest path) + 64` and doubles with each pair (never past
//! the caller's own cap, `Budget::node_limit`, which ends the search when reached), so the
//! search stays complete (a cap eventually exceeds the whole configuration space, and an
//! attempt that reports [`LacamEnd::Exhausted`] has explored everything, whatever its cap).
//! When an attempt of a pair finds a plan, the plan of lower sum of costs wins (ties: the first
//! of the pair). Then up to `extra` more pairs run under the cap that succeeded, each keeping
//! the best plan so far, while time remains in the share `extra_until` of the budget: several
//! first plans to choose from help most on dense maps, where refinement moves slowly.
//!
//! The two attempts of a pair differ in their advice too: the even one follows the guide paths
//! ([`crate::scatter`]), the odd one does without. The guide paths help most on large maps and
//! can mislead on small dense ones; the pair keeps whichever plan is cheaper. Measured
//! 2026-11-26 (sum of costs of the plan kept after the extra pairs, `--refine-rounds 0
//! --time-limit 10`, seeds 0–2, 4-connected, random-1), every attempt guided against pairs
//! split: maze-32-32-2 333 agents 86 696 / 82 839 / 83 732 against 75 230 / 75 100 / 75 788;
//! room-32-32-4 341 36 597 / 37 389 / 36 239 against 36 354 / 35 773 / 35 354;
//! random-32-32-20 409 35 179 / 26 517 / 25 869 against 32 300 / 26 517 / 31 203;
//! warehouse-10-20-10-2-1 500 50 305 / 49 167 / 50 285 against 50 933 / 49 611 / 50 285 and
//! 1000 151 563 / 146 090 / 153 661 against 151 951 / 150 530 / 151 217.
//!
//! They differ in PIBT's last tie-break too ([`crate::pibt::Pibt::set_prefer_free`]): the
//! guided attempt sends a robot to a free cell among equally good ones, the unguided one
//! chooses at random. Measured 2026-11-28 on the first descents alone (LaCAM without
//! restarts, cap 20 000, seeds 3, 1003, 2003, 3003, 4-connected, random-1), unguided attempts
//! preferring free cells against choosing at random: random-32-32-20 409 agents configurations
//! 140–1 123, mean sum of costs 42 411, against 98–131 and 28 220; maze-32-32-2 333 76 466
//! against 72 780; room-32-32-4 341 42 171 against 42 207; warehouse-10-20-10-2-1 1000
//! 239 724 against 251 684 (there the guided attempt's 155 031 wins the pair anyway). Guided
//! attempts choosing at random were worse on the large maps (seeds 0, 1000, 2000: room-64-64-8
//! 700 agents 149 105 against 154 191; random-64-64-20 1000 84 130 against 88 562;
//! warehouse-10-20-10-2-1 1000 155 031 against 157 729), so they keep the rule.
//!
//! In the extra pairs the even attempt also revisits ([`crate::lacam::lacam_search`]): a step
//! that reaches a known configuration continues from it, as LaCAM* does, instead of trying the
//! next constraint set of the configuration it came from. On small dense maps this gives far
//! shorter plans, but on some seeds it needs many more configurations before any plan, and
//! its first plan can be much costlier (random-32-32-20 409 agents, seed 3: 83 105 against
//! 45 844); so the pairs before the first plan never revisit, and the first plan and its time
//! stay what they were. Measured 2026-11-26 (sum of costs of the plan kept after the extra
//! pairs, `--refine-rounds 0 --time-limit 10`, seeds 0–3, 4-connected, random-1), without
//! revisits against with them in the extra pairs: random-32-32-20 409 agents 30 401 / 29 090 /
//! 25 794 / 32 360 against 27 780 / 30 378 / 25 264 / 32 360; room-32-32-4 341 34 972 /
//! 33 033 / 33 666 / 32 601 against 34 273 / 33 033 / 33 666 / 32 623; maze-32-32-2 333
//! unchanged. Revisiting in every guided attempt, the first pairs included, gave lower sums
//! after the extra pairs (geometric mean 2.0 % below none over 16 runs) but, on a loaded
//! machine where the extra pairs had little time, refinement from seed 3's first plan ended
//! at 50 497 in 10 s, against 25 478 with revisits in the extra pairs only (lacam3: 22 765).
//!
//! Caps count iterations, never time, and attempt `k`'s seed is a fixed function of the seed
//! and `k`, so a seed gives the same plan on one core or two; only a deadline that cuts the
//! search makes the result depend on speed. Cost: at most about twice the iterations of the
//! attempt that succeeds, per core, plus the extra pairs.

use crate::lacam::{lacam_search, LacamEnd, SearchRules};
use crate::moves::MoveGraph;
use crate::outcome::Budget;
use std::time::Instant;

/// How the restarted search ended.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Restarted {
    /// The best plan found, exhaustion, or the budget.
    pub end: LacamEnd,
    /// Configurations created over all attempts.
    pub configurations: u64,
    /// Attempts run.
    pub attempts: u64,
    /// The sum of costs of the first plan found (before the extra attempts).
    pub first_sum_of_costs: Option<u64>,
    /// When the first plan was found.
    pub first_found: Option<Instant>,
}

/// Attempt `k`'s seed: attempt 0 keeps `seed`, so an instance solved at once gives the plan
/// plain LaCAM gives.
fn attempt_seed(seed: u64, k: u64) -> u64 {
    if k == 0 {
        return seed;
    }
    let mut z = seed ^ k.wrapping_mul(0x9e37_79b9_7f4a_7c15);
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}

/// Attempt `k`'s rules: even attempts (guided) prefer free cells and, in the extra pairs,
/// revisit; odd ones (unguided) break ties at random and never revisit (see the module).
fn rules_of(k: u64, extra_pair: bool) -> SearchRules {
    SearchRules {
        revisit: extra_pair && k % 2 == 0,
        prefer_free: k % 2 == 0,
    }
}

fn sum_of_costs(paths: &[Vec<u32>]) -> u64 {
    paths.iter().map(|p| p.len() as u64 - 1).sum()
}

/// LaCAM with restarts (see the module). `extra`: pairs run after the first plan;
/// `extra_until`: no extra pair starts after this instant, and none runs past it.
#[allow(clippy::too_many_arguments)]
pub fn lacam_restarts(
    graph: &MoveGraph,
    dist: &[Vec<u32>],
    starts: &[u32],
    goals: &[u32],
    guide: &[Vec<u32>],
    budget: &Budget,
    seed: u64,
    extra: usize,
    extra_until: Option<Instant>,
) -> Restarted {
    let longest = starts
        .iter()
        .enumerate()
        .map(|(i, &s)| u64::from(dist[i][s as usize]))
        .max()
        .unwrap_or(0);
    // The caller's own cap on iterations, if any, bounds every attempt's.
    let outer = budget.node_limit.unwrap_or(u64::MAX);
    let mut cap = (4 * longest + 64).min(outer);
    let mut out = Restarted {
        end: LacamEnd::Budget,
        configurations: 0,
        attempts: 0,
        first_sum_of_costs: None,
        first_found: None,
    };
    let mut best: Option<(u64, Vec<Vec<u32>>)> = None;
    let mut extra_left = extra;
    let mut k = 0u64;
    loop {
        let mut b = budget.clone();
        b.node_limit = Some(cap);
        if best.is_some() {
            if let Some(until) = extra_until {
                b.deadline = Some(b.deadline.map_or(until, |d| d.min(until)));
            }
        }
        // Even attempts follow the guide paths, odd ones do without; in the extra pairs the
        // even ones revisit known configurations too (see the module).
        let extra_pair = best.is_some();
        let run = |k: u64| {
            let advice = if k % 2 == 0 { guide } else { &[] };
            lacam_search(
                graph,
                dist,
                starts,
                goals,
                advice,
                &b,
                attempt_seed(seed, k),
                rules_of(k, extra_pair),
            )
        };
        let ((e0, c0), (e1, c1)) = rayon::join(|| run(k), || run(k + 1));
        k += 2;
        out.attempts += 2;
        out.configurations += c0 + c1;
        let mut exhausted = false;
        for e in [e0, e1] {
            match e {
                LacamEnd::Found(p) => {
                    let soc = sum_of_costs(&p);
                    if best.as_ref().is_none_or(|(s, _)| soc < *s) {
                        best = Some((soc, p));
                    }
                }
                LacamEnd::Exhausted => exhausted = true,
                LacamEnd::Budget => {}
            }
        }
        if exhausted && best.is_none() {
            out.end = LacamEnd::Exhausted;
            return out;
        }
        if let Some((soc, _)) = &best {
            if out.first_found.is_none() {
                out.first_found = Some(Instant::now());
                out.first_sum_of_costs = Some(*soc);
            } else {
                extra_left = extra_left.saturating_sub(1);
            }
            let late = extra_until.is_some_and(|u| Instant::now() >= u);
            if extra_left == 0 || late || budget.out_of_time() {
                break;
            }
            continue;
        }
        if budget.out_of_time() || cap >= outer {
            return out;
        }
        cap = cap.saturating_mul(2).min(outer);
    }
    out.end = LacamEnd::Found(best.expect("a plan").1);
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::grid::{Connectivity, Grid};
    use crate::moves::goal_distances;
    use crate::Cell;

    #[test]
    fn seeds_of_attempts_differ_and_attempt_zero_keeps_the_seed() {
        assert_eq!(attempt_seed(7, 0), 7);
        let s: std::collections::BTreeSet<u64> = (0..100).map(|k| attempt_seed(7, k)).collect();
        assert_eq!(s.len(), 100);
    }

    #[test]
    fn a_pair_keeps_the_cheaper_of_its_guided_and_unguided_plans() {
        let grid = crate::generate::warehouse(40, 30, 0.05, 2);
        let mut checked = 0;
        for seed in 0..12u64 {
            let (robots, goals) = crate::generate::random_tasks(&grid, 80, seed);
            let m = MoveGraph::new(&grid, Connectivity::Four);
            let dist = goal_distances(&grid, Connectivity::Four, &goals);
            let s: Vec<u32> = robots.iter().map(|c| c.0).collect();
            let t: Vec<u32> = goals.iter().map(|c| c.0).collect();
            let guide =
                crate::scatter::guide_paths(&m, &dist, &s, &t, 10, &Budget::unlimited(), seed);
            let longest = (0..s.len())
                .map(|i| u64::from(dist[i][s[i] as usize]))
                .max()
                .unwrap();
            let capped = Budget {
                node_limit: Some(4 * longest + 64),
                ..Budget::unlimited()
            };
            let guided =
                lacam_search(&m, &dist, &s, &t, &guide, &capped, seed, rules_of(0, false)).0;
            let plain = lacam_search(
                &m,
                &dist,
                &s,
                &t,
                &[],
                &capped,
                attempt_seed(seed, 1),
                rules_of(1, false),
            )
            .0;
            let (LacamEnd::Found(a), LacamEnd::Found(b)) = (guided, plain) else {
                continue;
            };
            let want = if sum_of_costs(&b) < sum_of_costs(&a) {
                b
            } else {
                a
            };
            let r = lacam_restarts(
                &m,
                &dist,
                &s,
                &t,
                &guide,
                &Budget::unlimited(),
                seed,
                0,
                None,
            );
            assert_eq!(r.attempts, 2, "seed {seed}");
            assert_eq!(r.end, LacamEnd::Found(want), "seed {seed}");
            checked += 1;
        }
        assert!(
            checked >= 3,
            "only {checked} instances solved at the first cap"
        );
    }

    #[test]
    fn a_blocked_instance_is_exhausted_not_looped() {
        // Two robots in a two-cell corridor that must swap: no plan exists, whatever the cap.
        let g = Grid::new(2, 1, vec![false; 2]);
        let m = MoveGraph::new(&g, Connectivity::Four);
        let goals = [Cell(1), Cell(0)];
        let dist = goal_distances(&g, Connectivity::Four, &goals);
        let r = lacam_restarts(
            &m,
            &dist,
            &[0, 1],
            &[1, 0],
            &[],
            &Budget::unlimited(),
            3,
            2,
            None,
        );
        assert_eq!(r.end, LacamEnd::Exhausted);
    }
}
