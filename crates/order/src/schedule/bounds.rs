//! Proven bounds for team schedules.
//!
//! * Makespan (whole wall), a lower bound: the largest of
//!   - the longest precedence chain of placing phases;
//!   - the resource bound: with S UAV-cycles in all (a 2-UAV brick counts 2) and m UAVs,
//!     some UAV starts ⌈S/m⌉ bricks, so with one cycle length c it ends no earlier than
//!     (⌈S/m⌉ − 1)·c + the shortest placing phase; with mixed cycles, the total UAV time
//!     less the most rest the m last bricks can leave out, plus (zone rule) the UAVs' first
//!     starts and last ends, spread over m UAVs: their least sum is found exactly for a
//!     relaxation (`ZoneEnds`, and for teams up to 16 with the bricks under and on each
//!     first and last brick, `near_loss`, where a UAV's last brick also leaves the bricks it
//!     carries to the other UAVs and a 2-UAV brick that is the last of one UAV only lets its
//!     partner go on after its rest); with 2-UAV bricks, unless one of them is some
//!     UAV's last brick, the last of them leaves its two UAVs free at once and one waits at
//!     least the shortest placing phase for the other's next brick (`pair_wait`, and per chain
//!     of 2-UAV bricks `chain_waits`), and two UAVs coming from two 1-UAV bricks to one 2-UAV
//!     brick arrive apart (`merge_waits`);
//!   - under the zone rule, the sum of all placing phases (they never overlap); under the
//!     distance rule, the same sum over a clique of mutually conflicting bricks (greedily grown
//!     from every brick), which never overlap either.
//! * Reward by a budget T, an upper bound: the Lagrangian (= LP) relaxation of the
//!   precedence-constrained knapsack. A brick weighs its UAV time (`uavs · cycle`), the team
//!   has `m · (T + longest rest)` of it (with one cycle length: `m` times the starts that fit
//!   in T), and bricks whose precedence chain cannot end by T are out. For every λ ≥ 0,
//!   `λ·C + max over closed sets of Σ (reward − λ·weight)` bounds every valid schedule; the
//!   inner maximum is a maximum-weight closure ([`super::closure`]), and λ is found by
//!   bisection on the subgradient. With integer rewards the bound is rounded down. The planner
//!   then tightens it where it can ([`super::slots`]: the knapsack in whole bricks, and the
//!   full-slot argument).
//! * Expected reward with each UAV failing at rate λ_f: the same relaxation with the
//!   expected working time `E[min(F, T)] = (1 − e^(−λ_f T))/λ_f` per UAV. The relaxation is
//!   concave in the capacity, so by Jensen it bounds the expectation of every policy, even
//!   one that knows the failure times.

use super::closure::{max_weight_closure_until, EPS as CLOSURE_EPS};
use super::problem::TeamProblem;
use crate::outcome::Budget;
use mason_wall::BrickId;

/// The earliest each brick can be placed: its longest chain of placing phases.
pub fn earliest_end(p: &TeamProblem<'_>) -> Vec<f64> {
    let wall = p.wall();
    let mut order: Vec<BrickId> = wall.ids().collect();
    order.sort_by_key(|&b| wall.brick(b).level);
    let mut head = vec![0.0; p.len()];
    for b in order {
        let ready = wall
            .supports(b)
            .iter()
            .map(|s| head[s.index()])
            .fold(0.0, f64::max);
        head[b.index()] = ready + p.place_s(b);
    }
    head
}

/// One cycle length shared by every brick of the wall, if there is one.
pub(super) fn uniform_cycle(p: &TeamProblem<'_>) -> Option<f64> {
    let c = p.place_s(BrickId(0)) + p.rest_s(BrickId(0));
    p.wall()
        .ids()
        .all(|b| (p.place_s(b) + p.rest_s(b) - c).abs() < 1e-9)
        .then_some(c)
}

/// A lower bound on the makespan of any schedule that places every brick.
pub fn makespan_lower_bound(p: &TeamProblem<'_>) -> f64 {
    makespan_lower_bound_within(p, &Budget::unlimited())
}

/// [`makespan_lower_bound`], looser but still sound when `search` runs out first (the
/// conflict cliques found so far each bound the makespan).
pub fn makespan_lower_bound_within(p: &TeamProblem<'_>, search: &Budget) -> f64 {
    let ids = || p.wall().ids();
    let chain = earliest_end(p).into_iter().fold(0.0, f64::max);
    let resource = match uniform_cycle(p) {
        Some(c) => {
            let slots: u64 = ids().map(|b| u64::from(p.need(b))).sum();
            let per_uav = slots.div_ceil(p.uavs() as u64);
            let shortest = ids().map(|b| p.place_s(b)).fold(f64::INFINITY, f64::min);
            (per_uav as f64 - 1.0) * c + shortest
        }
        None => {
            // Σ_u (end_u − start_u) ≥ W − R, with R the most rest the UAVs' last bricks can
            // leave out; under the zone rule the UAVs' first starts and last ends are also
            // staggered by at least the shortest placing phase (orange pairs share one).
            let work: f64 = ids()
                .map(|b| f64::from(p.need(b)) * (p.place_s(b) + p.rest_s(b)))
                .sum();
            // A schedule may leave UAVs unused: take the weakest case over k used UAVs.
            let shortest = ids().map(|b| p.place_s(b)).fold(f64::INFINITY, f64::min);
            let pairs = ids().any(|b| p.need(b) == 2);
            // A 2-UAV brick can open the schedule only if it stands on nothing.
            let first_pair = ids().any(|b| p.need(b) == 2 && p.wall().supports(b).is_empty());
            let ends = p.zone_rule().then(|| ZoneEnds::new(p));
            let mut bound = f64::INFINITY;
            for k in 1..=p.uavs() {
                let mut loss = -last_rests(p, k);
                if let Some(e) = &ends {
                    let steps = zone_stagger(k, pairs, first_pair) + zone_stagger(k, pairs, true);
                    // With 2-UAV bricks, either one of them is some UAV's last brick, or the
                    // last of them leaves its UAVs to wait (`pair_wait`, and `chain_waits`).
                    let zone_loss = if pairs && k >= 2 {
                        e.loss(k, Last::SomePair, Some(shortest)).min(e.loss(
                            k,
                            Last::Singles,
                            Some(shortest),
                        ))
                    } else {
                        e.loss(k, Last::Any, None)
                    };
                    loss = (loss + steps as f64 * shortest).max(zone_loss);
                }
                let mut at_k = (work + loss) / k as f64;
                if ends.is_some() && pairs && k <= NEAR_UAVS {
                    // `chain_waits` leaves these schedules out of the loss.
                    at_k = at_k.min(only_pairs_bound(p, work, k));
                }
                bound = bound.min(at_k);
            }
            bound
        }
    };
    let zone = if p.zone_rule() {
        ids().map(|b| p.place_s(b)).sum()
    } else {
        conflict_clique(p, search)
    };
    chain.max(resource).max(zone)
}

/// Under the zone rule, the least time the UAVs of a 2-UAV brick wait between bricks in all
/// when no 2-UAV brick is the last brick of either of its UAVs (`shortest`: the shortest
/// placing phase of any brick).
///
/// Take the last 2-UAV brick placed (by start). Both its UAVs have a next brick and are free
/// at the same moment F (start + placing + rest of that brick). Their next bricks are not one
/// brick: that would be a 2-UAV brick placed later. So they are two bricks, each starting at F
/// or later, and under the zone rule their placing phases do not overlap: the later starts at
/// least F + the earlier's placing phase ≥ F + `shortest`, and its UAV, free since F, waits at
/// least that long. The bound counts `k·makespan ≥ W + first starts + (makespan − last ends)
/// − last rests + waits`, so this wait adds to the loss of every such schedule; schedules in
/// which some 2-UAV brick is a UAV's last are covered by the relaxation without the wait.
fn pair_wait(shortest: f64) -> f64 {
    shortest
}

/// Under the zone rule, the placing phases (of the shortest brick) that k UAVs' first starts
/// add up to at least: the UAVs' first bricks place one after another, so the j-th of them
/// (from 0) starts no earlier than j phases. A 2-UAV brick takes two UAVs at once: with
/// `pair_opens` (one can be the very first brick) the fewest phases are 0, 0, 1, 1, 2, …;
/// with `pairs` only (every 2-UAV brick stands on another brick, so one comes first)
/// 0, 1, 1, 2, 2, …; with no 2-UAV brick 0, 1, 2, …. Read backwards from the makespan, the
/// same count bounds the UAVs' last ends.
fn zone_stagger(k: usize, pairs: bool, pair_opens: bool) -> usize {
    (0..k)
        .map(|i| match (pairs, pair_opens) {
            (true, true) => i / 2,
            (true, false) => i.div_ceil(2),
            (false, _) => i,
        })
        .sum()
}

/// The zone rule's first starts and last ends, found exactly for a relaxation.
///
/// Every UAV has a first brick and a last one. Under the zone rule the UAVs' first bricks
/// place one after another, so a UAV's first start is at least the placing phases of the
/// first bricks placed before its own; reading back from the makespan, a UAV's last end is
/// at least the placing phases of the last bricks placed after its own before the makespan,
/// and the rest after its last brick is time it need not spend. So with k UAVs at work,
/// `k·makespan ≥ W + Σ first starts + Σ (makespan − last end) − Σ last rests`, W their whole
/// work. A sequence of bricks, each the first (or last) of w of its UAVs (1 ≤ w ≤ its need),
/// covering k UAVs, costs Σ_t p_t · (UAVs covered after t), less Σ w_t·r_t at the end: the
/// least such cost bounds the schedule's. Relaxed: each group of bricks with the same times
/// may be used as often as it has bricks for each w, precedence is ignored except that the
/// very first brick stands on nothing (it opens the schedule) and the very last carries
/// nothing (it closes it). By the exchange argument the cheapest sequence orders its bricks by
/// p/w (Smith's rule), so a knapsack over the groups in that order, built from the back so
/// that the cost does not depend on k, gives every k at once in O(groups · m²).
struct ZoneEnds {
    /// Least cost of a sequence covering c UAVs (index c): without the rests (first starts),
    /// and with them (last ends) by [`Last`] flag (index 0: only 1-UAV bricks, 1: some 2-UAV
    /// brick).
    start: Vec<f64>,
    end: [Vec<f64>; 2],
    /// Groups: (place, rest, w, usable first, usable last, a 2-UAV group).
    items: Vec<(f64, f64, usize, bool, bool, bool)>,
    /// For k ≤ [`NEAR_UAVS`]: the same least first-start and last-end costs where each brick
    /// also waits for the bricks under it and is waited for by the bricks on it
    /// ([`near_loss`]), by the number of 2-UAV bricks among the first (last) bricks; −∞ above.
    near_start: Vec<PairCounts>,
    near_end: Vec<PairCounts>,
    /// The wall's 2-UAV bricks.
    pair_bricks: usize,
    /// The least wait of a merge ([`merge_wait`]).
    merge: f64,
}

/// Least costs by the number of 2-UAV bricks among the UAVs' first (or last) bricks that are
/// the first (last) brick of one of their UAVs only, then of both (index c for exactly c, the
/// last index for [`PAIR_CAP`] or more).
type PairCounts = [[f64; PAIR_CAP + 1]; PAIR_CAP + 1];

/// [`near_loss`] counts the 2-UAV bricks among the first (last) bricks up to this many.
const PAIR_CAP: usize = 3;

/// The pair splits [`ZoneEnds::loss`] counts when, among the UAVs' first bricks, `first` =
/// (f1, f2) 2-UAV bricks are the first brick of one of their UAVs only (f1) or of both (f2),
/// and likewise `last` = (l1, l2) among their last bricks (a count at [`PAIR_CAP`] meaning that
/// many or more), in a schedule with 2-UAV bricks in which no UAV places only 2-UAV bricks
/// ([`only_pairs_bound`] covers those).
///
/// Chain the 2-UAV bricks: one follows another when it is the next brick of both UAVs of the
/// other (the same crew, back to back). A 2-UAV brick that is some UAV's first brick has no
/// such predecessor, so it starts a chain of its own (f = f1 + f2 chains start so), and one
/// that is some UAV's last brick ends its chain (l = l1 + l2 chains end so). Every other chain
/// ends with its two UAVs going on to two different bricks (else the next brick would continue
/// it), and after each of those, as in [`pair_wait`], the two UAVs are free at the same moment
/// and the later of their two next bricks starts a placing phase later: one UAV waits at least
/// the shortest placing phase, between two of its bricks (waits after different 2-UAV bricks
/// are different stretches of time). With c chains, x of which both start on a first brick
/// and end on a last one, c ≥ max(1, f + l − x) and c − l chains split. In such a chain, if
/// one UAV's first and last bricks are both in it, that UAV places only 2-UAV bricks;
/// otherwise its first brick is the first of one UAV only and its last the last of the other
/// only, so x ≤ min(f1, l1), and at least max(1 − l, f2 + max(0, f1 − l1)) chains split.
fn chain_waits(q: usize, (f1, f2): (usize, usize), (l1, l2): (usize, usize)) -> usize {
    if q == 0 {
        return 0;
    }
    let l = l1 + l2;
    // l1 at the cap may be larger: then it may cover every f1.
    let unmatched = match l1 >= PAIR_CAP {
        true => 0,
        false => f1.saturating_sub(l1),
    };
    1usize.saturating_sub(l).max(f2 + unmatched)
}

/// Under the zone rule, the least time the earlier of two UAVs waits when both come from
/// 1-UAV bricks to one 2-UAV brick (a *merge*), 0 without 1-UAV bricks: if x (UAV a) and y
/// (UAV b) are those two bricks and x starts first, y starts at least a placing phase of x
/// later (their phases do not overlap), so b is free no earlier than
/// s_x + p_x + p_y + r_y while a is free at s_x + p_x + r_x; the 2-UAV brick starts when both
/// are, so a waits at least p_y + r_y − r_x ≥ (the shortest cycle of a 1-UAV brick) − (the
/// longest rest of one), at least 0. (Thesis times: 74 − 66 = 8 s.)
fn merge_wait(p: &TeamProblem<'_>) -> f64 {
    let singles = || p.wall().ids().filter(|&b| p.need(b) == 1);
    let cycle = singles()
        .map(|b| p.place_s(b) + p.rest_s(b))
        .fold(f64::INFINITY, f64::min);
    let rest = singles().map(|b| p.rest_s(b)).fold(0.0, f64::max);
    match cycle.is_finite() {
        true => (cycle - rest).max(0.0),
        false => 0.0,
    }
}

/// The waits at merges ([`merge_wait`], `merge`) that [`ZoneEnds::loss`] adds to
/// [`chain_waits`]' splits (`shortest` each), with the same counts and in the same schedules
/// (2-UAV bricks, no UAV placing only 2-UAV bricks). A merge's wait lies between a 1-UAV brick
/// and the 2-UAV brick after it, a split's between a 2-UAV brick and the brick after it, and
/// the first starts and last ends lie outside every UAV's first and last bricks: no stretch of
/// time counts twice.
///
/// * No 2-UAV brick among the first bricks (f1 = f2 = 0): the 2-UAV brick that starts first
///   is no UAV's first brick, so both its UAVs come from a brick placed before it, which is
///   not a 2-UAV brick (none starts earlier), and not one brick (a 1-UAV brick has one UAV):
///   a merge, `merge` more.
/// * None that is the first or the last brick of one UAV only (f1 = l1 = 0), some that are the
///   first of both (f2 ≥ 1) and some the last of both (l2 ≥ 1): a chain that starts on a
///   first brick and ends on a last one would leave its UAVs placing only 2-UAV bricks, so
///   there are c ≥ f2 + l2 chains and c − l2 ≥ f2 splits. With one split more, that is
///   `shortest` more than [`chain_waits`] counts (f2). Otherwise c = f2 + l2: the chains that
///   start on first bricks are exactly those that split, and the others (at least one) start
///   with their two UAVs coming from two different bricks and end on the last brick of both.
///   Take the one of those that starts first: a UAV of it coming from a 2-UAV brick comes from
///   the end of a chain that started earlier, so on its own first brick, and would place only
///   2-UAV bricks (that chain, then this one up to its last brick). So both come from 1-UAV
///   bricks: a merge, `merge` more. Either way at least min(`merge`, `shortest`) more.
fn merge_waits(
    q: usize,
    (f1, f2): (usize, usize),
    (l1, l2): (usize, usize),
    shortest: f64,
    merge: f64,
) -> f64 {
    if q == 0 {
        return 0.0;
    }
    if f1 == 0 && f2 == 0 {
        merge
    } else if f1 == 0 && l1 == 0 && f2 >= 1 && l2 >= 1 {
        merge.min(shortest)
    } else {
        0.0
    }
}

/// The makespan bound over the schedules in which some UAV places 2-UAV bricks and nothing
/// else (see [`chain_waits`]), with k UAVs at work: that UAV's time aside (at most every 2-UAV
/// brick's cycle), the other k − 1 UAVs work the rest of W, less the rests their last bricks
/// can leave out.
fn only_pairs_bound(p: &TeamProblem<'_>, work: f64, k: usize) -> f64 {
    if k < 2 {
        return f64::INFINITY;
    }
    let pairs: f64 = p
        .wall()
        .ids()
        .filter(|&b| p.need(b) == 2)
        .map(|b| p.place_s(b) + p.rest_s(b))
        .sum();
    (work - pairs - last_rests(p, k - 1)) / (k - 1) as f64
}

/// Which UAVs' last bricks [`ZoneEnds::loss`] allows.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Last {
    /// Any bricks.
    Any,
    /// Only 1-UAV bricks: no 2-UAV brick is the last of either of its UAVs.
    Singles,
    /// At least one 2-UAV brick is the last of one of its UAVs or both.
    SomePair,
}

impl Last {
    /// Whether a set of last bricks with (`true`) or without 2-UAV bricks is allowed.
    fn allows(self, some_pair: bool) -> bool {
        match self {
            Last::Any => true,
            Last::Singles => !some_pair,
            Last::SomePair => some_pair,
        }
    }
}

/// Teams up to this size also get [`near_loss`].
const NEAR_UAVS: usize = 16;

impl ZoneEnds {
    fn new(p: &TeamProblem<'_>) -> ZoneEnds {
        let wall = p.wall();
        let mut carries = vec![false; p.len()];
        for b in wall.ids() {
            for s in wall.supports(b) {
                carries[s.index()] = true;
            }
        }
        // Groups of bricks with the same place, rest and need: (place, rest, need, count,
        // some stands on nothing, some carries nothing).
        let mut groups: Vec<(f64, f64, u32, usize, bool, bool)> = Vec::new();
        for b in wall.ids() {
            let key = (p.place_s(b), p.rest_s(b), p.need(b));
            let opens = wall.supports(b).is_empty();
            let closes = !carries[b.index()];
            match groups.iter_mut().find(|g| (g.0, g.1, g.2) == key) {
                Some(g) => {
                    g.3 += 1;
                    g.4 |= opens;
                    g.5 |= closes;
                }
                None => groups.push((key.0, key.1, key.2, 1, opens, closes)),
            }
        }
        // Items: (place, rest, w, count, usable first, usable last, a 2-UAV group).
        let mut items: Vec<(f64, f64, usize, usize, bool, bool, bool)> = Vec::new();
        for &(place, rest, need, count, opens, closes) in &groups {
            for w in 1..=need as usize {
                items.push((place, rest, w, count, opens, closes, need > 1));
            }
        }
        // Built from the back of the sequence: the largest p/w first.
        items.sort_by(|a, b| (b.0 / b.2 as f64).total_cmp(&(a.0 / a.2 as f64)));
        let m = p.uavs();
        // Per flag (some 2-UAV item used), the least cost covering c UAVs.
        let knapsack = |with_rest: bool| {
            let mut best = [vec![f64::INFINITY; m + 1], vec![f64::INFINITY; m + 1]];
            best[0][0] = 0.0;
            for &(place, rest, w, count, _, _, pair) in &items {
                let mut next = best.clone();
                for (flag, costs) in best.iter().enumerate() {
                    let to = usize::from(flag == 1 || pair);
                    for (c, &from) in costs.iter().enumerate() {
                        if !from.is_finite() {
                            continue;
                        }
                        let mut cost = from;
                        let mut cov = c;
                        for _ in 0..count {
                            if cov + w > m {
                                break;
                            }
                            // Placed before the UAVs covered so far: it delays each of them.
                            cost +=
                                place * cov as f64 - if with_rest { w as f64 * rest } else { 0.0 };
                            cov += w;
                            next[to][cov] = next[to][cov].min(cost);
                        }
                    }
                }
                best = next;
            }
            best
        };
        let (near_start, near_end) = near_loss(p, m.min(NEAR_UAVS));
        let [s0, s1] = knapsack(false);
        let start: Vec<f64> = s0.iter().zip(&s1).map(|(a, b)| a.min(*b)).collect();
        ZoneEnds {
            near_start,
            near_end,
            pair_bricks: wall.ids().filter(|&b| p.need(b) == 2).count(),
            merge: merge_wait(p),
            start,
            end: knapsack(true),
            items: items
                .iter()
                .map(|&(pl, r, w, _, o, c, pair)| (pl, r, w, o, c, pair))
                .collect(),
        }
    }

    /// The least `Σ first starts + Σ (makespan − last end) − Σ last rests` with k UAVs at
    /// work, over the schedules whose last bricks `last` allows (+∞: none, or k UAVs cannot
    /// all have a brick), plus, in a schedule with 2-UAV bricks (`shortest`: the shortest
    /// placing phase), the waits after 2-UAV bricks whose UAVs part: one ([`pair_wait`]) when
    /// no 2-UAV brick is a last brick, and where the bricks under and on each first and last
    /// brick count, one per [`chain_waits`], and the merges of [`merge_waits`].
    fn loss(&self, k: usize, last: Last, shortest: Option<f64>) -> f64 {
        let mut first = f64::INFINITY;
        let mut end = f64::INFINITY;
        for &(place, rest, w, opens, closes, pair) in &self.items {
            if w > k {
                continue;
            }
            let delay = place * (k - w) as f64;
            if opens {
                first = first.min(delay + self.start[k - w]);
            }
            if closes {
                for flag in 0..2 {
                    if last.allows(pair || flag == 1) {
                        end = end.min(delay - w as f64 * rest + self.end[flag][k - w]);
                    }
                }
            }
        }
        if let (Last::Singles, Some(s)) = (last, shortest) {
            end += pair_wait(s);
        }
        let near = match (self.near_start.get(k), self.near_end.get(k)) {
            (Some(starts), Some(ends)) => {
                let mut least = f64::INFINITY;
                let counts = || (0..=PAIR_CAP).flat_map(|a| (0..=PAIR_CAP).map(move |b| (a, b)));
                for (l1, l2) in counts() {
                    if !last.allows(l1 + l2 > 0) {
                        continue;
                    }
                    for (f1, f2) in counts() {
                        let waits = shortest.map_or(0.0, |p| {
                            chain_waits(self.pair_bricks, (f1, f2), (l1, l2)) as f64 * p
                                + merge_waits(self.pair_bricks, (f1, f2), (l1, l2), p, self.merge)
                        });
                        least = least.min(starts[f1][f2] + ends[l1][l2] + waits);
                    }
                }
                least
            }
            _ => f64::NEG_INFINITY,
        };
        (first + end).max(near)
    }
}

/// The first-start and last-end loss of [`ZoneEnds`], stronger for small teams: a brick starts
/// no earlier than the placing phases of all the bricks under it (they place one after another
/// before it), and ends no later than the makespan less those of all the bricks on it. Per
/// brick these are bounded below by `head` = max(Σ supports' p, max over supports (p + head))
/// and `tail` likewise upwards. A last brick's tail depends on how many of its UAVs (w) it is
/// the last of: the bricks it carries start after it and none of those w UAVs places anything
/// after its last brick, so the other m − w place them ([`others_tail`]); and a 2-UAV brick
/// that is the last of one UAV only has a partner that places another brick after its rest,
/// so the makespan is at least its rest and the shortest placing phase after its end. A group
/// of bricks with the same times takes its members' least head and, per w, least tail. The
/// j-th first brick then starts at max(its head, the phases of the first bricks before it),
/// and likewise for the last ends; Smith's order no longer holds, so a
/// dynamic programme over (UAVs covered, phases so far) finds the least cost exactly, with
/// every group usable any number of times (a relaxation). Entry k: the least first-start cost
/// with k UAVs at work, and the least last-end cost by flag (index 1: some 2-UAV brick among
/// the last bricks), for k ≤ `kmax`.
fn near_loss(p: &TeamProblem<'_>, kmax: usize) -> (Vec<PairCounts>, Vec<PairCounts>) {
    use std::collections::BTreeMap;
    let wall = p.wall();
    let mut order: Vec<BrickId> = wall.ids().collect();
    order.sort_by_key(|&b| wall.brick(b).level);
    let mut carried: Vec<Vec<BrickId>> = vec![Vec::new(); p.len()];
    for &b in &order {
        for &s in wall.supports(b) {
            carried[s.index()].push(b);
        }
    }
    let shortest = wall
        .ids()
        .map(|b| p.place_s(b))
        .fold(f64::INFINITY, f64::min);
    let head = waits(p, order.iter().copied(), |b| wall.supports(b));
    let tail = waits(p, order.iter().rev().copied(), |b| {
        carried[b.index()].as_slice()
    });
    // Groups (place, rest, need) with their least head, and their least tail as the last
    // brick of 1 or of 2 UAVs.
    let mut groups: Vec<(f64, f64, u32, f64, [f64; 2])> = Vec::new();
    for b in wall.ids() {
        let key = (p.place_s(b), p.rest_s(b), p.need(b));
        let h = head[b.index()];
        let t = [1, 2].map(|w| {
            // A UAV of `b` for which it is not the last brick places another after its rest.
            let partner = match (w as u32) < p.need(b) {
                true => p.rest_s(b) + shortest,
                false => 0.0,
            };
            tail[b.index()]
                .max(others_tail(p, &carried[b.index()], w))
                .max(partner)
        });
        match groups.iter_mut().find(|g| (g.0, g.1, g.2) == key) {
            Some(g) => {
                g.3 = g.3.min(h);
                g.4 = [g.4[0].min(t[0]), g.4[1].min(t[1])];
            }
            None => groups.push((key.0, key.1, key.2, h, t)),
        }
    }
    // One side: `wait` is a group's least head (start) or tail (end); `rest` counts at the end.
    // Per 2-UAV bricks used (up to PAIR_CAP), the least cost covering c UAVs.
    let side = |end: bool| -> Vec<PairCounts> {
        let mut best = vec![[[f64::INFINITY; PAIR_CAP + 1]; PAIR_CAP + 1]; kmax + 1];
        best[0][0][0] = 0.0;
        // The 2-UAV bricks so far, for one UAV and for both, after one more brick.
        let count = |(one, both): (usize, usize), need: u32, w: usize| match (need > 1, w) {
            (false, _) => (one, both),
            (true, 1) => ((one + 1).min(PAIR_CAP), both),
            (true, _) => (one, (both + 1).min(PAIR_CAP)),
        };
        // (covered, phases so far as bits, 2-UAV bricks for one UAV, for both) → least cost;
        // the first brick must wait for nothing.
        let mut layer: BTreeMap<(usize, u64, (usize, usize)), f64> = BTreeMap::new();
        for &(place, rest, need, h, t) in &groups {
            for w in 1..=(need as usize).min(kmax) {
                let wait = if end { t[w - 1] } else { h };
                if wait > 0.0 {
                    continue;
                }
                let cost = -if end { w as f64 * rest } else { 0.0 };
                let e = layer
                    .entry((w, place.to_bits(), count((0, 0), need, w)))
                    .or_insert(f64::INFINITY);
                *e = e.min(cost);
            }
        }
        while !layer.is_empty() {
            let mut next: BTreeMap<(usize, u64, (usize, usize)), f64> = BTreeMap::new();
            for (&(c, o, pairs), &cost) in &layer {
                best[c][pairs.0][pairs.1] = best[c][pairs.0][pairs.1].min(cost);
                let o = f64::from_bits(o);
                for &(place, rest, need, h, t) in &groups {
                    for w in 1..=(need as usize) {
                        if c + w > kmax {
                            break;
                        }
                        let wait = if end { t[w - 1] } else { h };
                        let add = w as f64 * (o.max(wait) - if end { rest } else { 0.0 });
                        let e = next
                            .entry((c + w, (o + place).to_bits(), count(pairs, need, w)))
                            .or_insert(f64::INFINITY);
                        *e = e.min(cost + add);
                    }
                }
            }
            layer = next;
        }
        best
    };
    (side(false), side(true))
}

/// How long after a brick ends the bricks it carries take at least when that brick is the
/// last of `w` of its UAVs: they start after it, and none of those w UAVs places anything
/// after its last brick, so the other m − w UAVs place them all (+∞ if they cannot: too few
/// for a 2-UAV brick, or none). Some UAV starts ⌈S/(m − w)⌉ of them (S: their UAV-cycles), a
/// cycle apart at least, and the last ends a placing phase after its start.
fn others_tail(p: &TeamProblem<'_>, carried: &[BrickId], w: usize) -> f64 {
    if carried.is_empty() {
        return 0.0;
    }
    let others = p.uavs().saturating_sub(w);
    let slots: usize = carried.iter().map(|&c| p.need(c) as usize).sum();
    if carried.iter().any(|&c| p.need(c) as usize > others) {
        return f64::INFINITY;
    }
    let cycle = carried
        .iter()
        .map(|&c| p.place_s(c) + p.rest_s(c))
        .fold(f64::INFINITY, f64::min);
    let place = carried
        .iter()
        .map(|&c| p.place_s(c))
        .fold(f64::INFINITY, f64::min);
    (slots.div_ceil(others) - 1) as f64 * cycle + place
}

/// The placing phases that must come before (or after) each brick, visited in `bricks` with
/// its neighbours below (or above) in `near`: each of them, and the longest chain through them.
fn waits<'a>(
    p: &TeamProblem<'_>,
    bricks: impl Iterator<Item = BrickId>,
    near: impl Fn(BrickId) -> &'a [BrickId],
) -> Vec<f64> {
    let mut wait = vec![0.0f64; p.len()];
    for b in bricks {
        let next = near(b);
        let sum: f64 = next.iter().map(|&s| p.place_s(s)).sum();
        let chain = next
            .iter()
            .map(|&s| p.place_s(s) + wait[s.index()])
            .fold(0.0, f64::max);
        wait[b.index()] = sum.max(chain);
    }
    wait
}

/// The most rest time `m` UAVs' last bricks can add up to: each UAV's last brick is its own
/// UAV-slot of a brick (a 2-UAV brick has two, and may be the last of one of its UAVs only), so
/// at most the `m` longest rests over all UAV-slots. (Counting a 2-UAV brick only as the last
/// of both its UAVs, as this did before, passed the optimum: a pair's UAV may stop on it while
/// its partner goes on.)
fn last_rests(p: &TeamProblem<'_>, m: usize) -> f64 {
    let mut slots: Vec<f64> = p
        .wall()
        .ids()
        .flat_map(|b| std::iter::repeat_n(p.rest_s(b), p.need(b) as usize))
        .collect();
    slots.sort_by(|a, b| b.total_cmp(a));
    slots.iter().take(m).sum()
}

/// Membership tests [`conflict_clique`] may make in all: every clique it grew bounds the
/// makespan, so stopping there (or at the deadline) keeps a sound, deterministic bound.
const CLIQUE_WORK: u64 = 200_000_000;

/// The heaviest clique of mutually conflicting bricks found by growing one greedily from each
/// brick (longest placing phase first): its placing phases never overlap, so their sum bounds
/// the makespan. O(n·d²) for d conflicts per brick, at most [`CLIQUE_WORK`] tests.
fn conflict_clique(p: &TeamProblem<'_>, search: &Budget) -> f64 {
    let mut best = 0.0f64;
    let mut clique: Vec<BrickId> = Vec::new();
    let mut work = 0u64;
    for b in p.wall().ids() {
        if work > CLIQUE_WORK || search.out_of_time() {
            break;
        }
        let mut cands: Vec<BrickId> = p.conflicts(b).to_vec();
        cands.sort_by(|x, y| p.place_s(*y).total_cmp(&p.place_s(*x)).then(x.cmp(y)));
        clique.clear();
        clique.push(b);
        for c in cands {
            work += clique.len() as u64;
            if clique
                .iter()
                .all(|k| p.conflicts(c).binary_search(k).is_ok())
            {
                clique.push(c);
            }
        }
        best = best.max(clique.iter().map(|&k| p.place_s(k)).sum());
    }
    best
}

/// The reward relaxation's data: per brick weight and eligibility, the team's capacity.
pub(super) struct Knapsack {
    pub(super) weight: Vec<f64>,
    pub(super) eligible: Vec<bool>,
    /// The supports of each eligible brick (the closure's requirements).
    pub(super) requires: Vec<Vec<usize>>,
    pub(super) capacity: f64,
}

pub(super) fn knapsack(p: &TeamProblem<'_>, budget: f64, uav_time: f64) -> Knapsack {
    let head = earliest_end(p);
    let eligible: Vec<bool> = head.iter().map(|&h| h <= budget + 1e-9).collect();
    let requires: Vec<Vec<usize>> = p
        .wall()
        .ids()
        .map(|b| match eligible[b.index()] {
            true => p.wall().supports(b).iter().map(|s| s.index()).collect(),
            false => Vec::new(),
        })
        .collect();
    let ids = || p.wall().ids();
    let m = p.uavs() as f64;
    match uniform_cycle(p) {
        // Weights in cycles: a UAV starts at most ⌊(T − shortest placing)/c⌋ + 1 bricks.
        Some(c) if uav_time >= budget => {
            let shortest = ids().map(|b| p.place_s(b)).fold(f64::INFINITY, f64::min);
            let starts = if budget + 1e-9 >= shortest {
                ((budget - shortest) / c + 1e-9).floor() + 1.0
            } else {
                0.0
            };
            Knapsack {
                weight: ids().map(|b| f64::from(p.need(b))).collect(),
                eligible,
                requires,
                capacity: m * starts,
            }
        }
        _ => {
            let longest_rest = ids().map(|b| p.rest_s(b)).fold(0.0, f64::max);
            Knapsack {
                weight: ids()
                    .map(|b| f64::from(p.need(b)) * (p.place_s(b) + p.rest_s(b)))
                    .collect(),
                eligible,
                requires,
                capacity: m * (uav_time + longest_rest),
            }
        }
    }
}

/// A heaviest closed set of eligible bricks under reward − λ·weight (`None`: `search` ran out
/// before it was found).
fn closure_at(
    p: &TeamProblem<'_>,
    k: &Knapsack,
    lambda: f64,
    search: &Budget,
) -> Option<(Vec<bool>, f64, f64)> {
    let n = p.len();
    let weight: Vec<f64> = (0..n)
        .map(|i| {
            if k.eligible[i] {
                p.reward(BrickId(i as u32)) - lambda * k.weight[i]
            } else {
                0.0
            }
        })
        .collect();
    let set = max_weight_closure_until(&weight, &k.requires, &|| search.out_of_time())?;
    let set: Vec<bool> = set.iter().zip(&k.eligible).map(|(&s, &e)| s && e).collect();
    let (mut r, mut w) = (0.0, 0.0);
    for i in (0..n).filter(|&i| set[i]) {
        r += p.reward(BrickId(i as u32));
        w += k.weight[i];
    }
    Some((set, r, w))
}

/// The reward relaxation's result.
#[derive(Clone, Debug)]
pub struct RewardBound {
    /// The proven upper bound.
    pub bound: f64,
    /// The best closed set found that fits the capacity (a starting point for planners).
    pub fitting: Vec<bool>,
    /// Per brick: the relaxation's weight, and whether its chain can end by T.
    pub weight: Vec<f64>,
    /// The capacity in those weights.
    pub capacity: f64,
}

/// The Lagrangian dual of the knapsack over closed sets: every λ ≥ 0 gives an upper bound,
/// so stopping early (`search` out of time) keeps a sound one, at worst the sum of the
/// eligible bricks' rewards.
fn lagrangian(p: &TeamProblem<'_>, k: Knapsack, search: &Budget) -> RewardBound {
    let n = p.len();
    let ratio_max = (0..n)
        .filter(|&i| k.eligible[i] && k.weight[i] > 0.0)
        .map(|i| p.reward(BrickId(i as u32)) / k.weight[i])
        .fold(0.0, f64::max);
    let (mut lo, mut hi) = (0.0f64, ratio_max + 1.0);
    // Every brick placed by T is eligible: their rewards together bound any schedule.
    let mut best: f64 = (0..n)
        .filter(|&i| k.eligible[i])
        .map(|i| p.reward(BrickId(i as u32)).max(0.0))
        .sum();
    let mut fitting = vec![false; n];
    let mut fitting_reward = -1.0;
    // The closure leaves out weights at or below EPS (and the max-flow stops at EPS), so a
    // closure may fall short of the heaviest by up to that much per node: each dual value is
    // raised by the most it can have lost, or the bound could land just below a whole reward
    // and be rounded down past it (a 10 000-brick grid claimed 1199 for a schedule of 1200).
    let slack = 4.0 * CLOSURE_EPS * (n + 2) as f64;
    for _ in 0..60 {
        if search.out_of_time() {
            break;
        }
        let lambda = (lo + hi) / 2.0;
        let Some((set, r, w)) = closure_at(p, &k, lambda, search) else {
            break;
        };
        best = best.min(lambda * k.capacity + r - lambda * w + slack);
        if w <= k.capacity + 1e-9 {
            if r > fitting_reward {
                fitting_reward = r;
                fitting = set;
            }
            hi = lambda;
        } else {
            lo = lambda;
        }
        if hi - lo < 1e-12 {
            break;
        }
    }
    // (λ = 0 bounds too: every eligible brick's reward, where `best` started. Its closure is
    // not computed: rewards at or below the closure's tolerance would be left out of it.)
    RewardBound {
        bound: best,
        fitting,
        weight: k.weight,
        capacity: k.capacity,
    }
}

/// An upper bound on the reward any valid schedule places by `budget`.
/// Rounded down when every reward is a whole number.
pub fn reward_upper_bound(p: &TeamProblem<'_>, budget: f64) -> RewardBound {
    reward_upper_bound_within(p, budget, &Budget::unlimited())
}

/// [`reward_upper_bound`], looser but still sound when `search` runs out first.
pub fn reward_upper_bound_within(p: &TeamProblem<'_>, budget: f64, search: &Budget) -> RewardBound {
    let mut b = lagrangian(p, knapsack(p, budget, budget), search);
    if p.wall().ids().all(|id| p.reward(id).fract() == 0.0) {
        b.bound = (b.bound + 1e-6).floor();
    }
    b
}

/// An upper bound on the expected reward by `budget` when each UAV fails at
/// `hazard_per_hour` (exponential), for any policy.
pub fn expected_reward_upper_bound(p: &TeamProblem<'_>, budget: f64, hazard_per_hour: f64) -> f64 {
    expected_reward_upper_bound_within(p, budget, hazard_per_hour, &Budget::unlimited())
}

/// [`expected_reward_upper_bound`], looser but still sound when `search` runs out first.
pub fn expected_reward_upper_bound_within(
    p: &TeamProblem<'_>,
    budget: f64,
    hazard_per_hour: f64,
    search: &Budget,
) -> f64 {
    let rate = hazard_per_hour / 3600.0;
    // (1 − e^(−rT))/r, written with exp_m1 so that a tiny rate keeps its precision (with
    // `1 − exp` a rate of 1e-18/h gave 0 and a bound far below the reward), and never more
    // than T.
    let uav_time = if rate > 0.0 {
        (-(-rate * budget).exp_m1() / rate).min(budget)
    } else {
        budget
    };
    // The expectation need not be a whole number: no rounding.
    lagrangian(p, knapsack(p, budget, uav_time), search).bound
}
