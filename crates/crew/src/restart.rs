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
//! Caps count iterations, never time, and attempt `k`'s seed is a fixed function of the seed
//! and `k`, so a seed gives the same plan on one core or two; only a deadline that cuts the
//! search makes the result depend on speed. Cost: at most about twice the iterations of the
//! attempt that succeeds, per core, plus the extra pairs.

use crate::lacam::{lacam_guided, LacamEnd};
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
        let run =
            |k: u64| lacam_guided(graph, dist, starts, goals, guide, &b, attempt_seed(seed, k));
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
