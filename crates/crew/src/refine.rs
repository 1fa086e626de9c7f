//! Anytime refinement of a valid plan by large neighbourhood search (after Li, Chen, Harabor,
//! Stuckey, Koenig, "Anytime multi-agent path finding via large neighborhood search",
//! IJCAI 2021).
//!
//! One round takes a few robots (a *neighbourhood*), removes their paths, and plans them again
//! one by one, in random order, with space-time A* around everyone else's path (the robots
//! replanned first included). The new paths are kept when their sum of costs is no higher
//! (`RefineConfig::ties`, the default; strictly lower otherwise); otherwise the old ones go
//! back. The plan is therefore valid after every round and its sum of costs never rises; the
//! caller stops on a deadline or a round count.
//!
//! Keeping paths of equal cost (a sideways move, as lacam3's refiner does) moves robots out of
//! each other's way without a gain, so that later rounds find gains that were blocked. Measured
//! 2026-11-26 against the strict rule, side by side with lacam3 on this 2-core machine (sum of
//! costs, seed 0, 4-connected, random-1, 10 s): warehouse-10-20-10-2-1 500 agents 55 145
//! against 58 641, 1000 agents 187 552 against 189 534; den520d 1000 172 475 against 176 357;
//! Boston_0_256 1000 197 330 against 199 045; room-64-64-8 300 26 409 against 26 702;
//! empty-32-32 512 17 661 against 18 251 (single runs, the machine shared).
//!
//! Neighbourhood sizes climb a ladder (variable neighbourhood search; `size_ladder`): half
//! `RefineConfig::neighbourhood`, then the size itself after `SIZE_PATIENCE` rounds in a row
//! without a gain, then twice it, then round again; every gain drops back to the smallest.
//! Small neighbourhoods are cheap and often succeed on dense maps; the larger ones get out of
//! the local optima where the small ones stall. Measured 2026-11-26 against fixed sizes, all
//! four side by side on the loaded 2-core machine (sum of costs, 10 s, seed 1, 4-connected,
//! random-1; fixed 2 / fixed 4 / ladder 2-4-8 with a patience of 100 / of 400 rounds):
//! random-32-32-20 409 agents 22 111 / 23 275 / 21 519 / 21 769; room-64-64-8 300 26 655 /
//! 27 632 / 26 521 / 26 521; room-32-32-4 341 33 062 / 33 003 / 32 997 / 32 811;
//! maze-32-32-2 333 66 568 / 66 988 / 66 380 / 66 294; random-32-32-20 200 5 429 / 5 249 /
//! 5 267 / 5 277 (single runs; the patience of 200 lies between the two measured).
//!
//! Neighbourhoods, chosen by adaptive weights (a kind that improved gets chosen more):
//! - *delayed*: a robot that arrives later than its shortest path would allow, with the robots
//!   that stand on the cells of its path around the same times;
//! - *area*: the robots that pass through the cells nearest a random cell;
//! - *random*: robots drawn at random.
//!
//! The cap on states expanded per robot replanned is chosen per neighbourhood too, among
//! `RefineConfig::node_limit` and its half, quarter and eighth (`Caps`): each is drawn with a
//! probability proportional to the sum of costs it has gained per state expanded (sums that
//! fade by 0.5 % per neighbourhood, each arm's shrunk towards the rate of all arms by one
//! cap's worth of states, so that an arm little tried counts as average and an arm that gains
//! nothing fades whatever its cap). Where rounds mostly fail, a failing search runs to its
//! cap, and a smaller cap buys many more rounds; where the gains come from long searches, the
//! large caps keep them. With the cap fixed at 30 000, searches that failed at the cap took
//! 87 % of the states expanded on lak303d with 1000 agents and 78 % on
//! warehouse-10-20-10-2-1 with 1000; fixed at 7 500, den520d 1000 gained half as much.
//! Measured 2026-11-28 on the loaded 2-core machine (10 s, seed 0 unless said, 4-connected,
//! single runs alternating; sum of costs, the cap fixed against chosen): warehouse-10-20-10-2-1
//! 1000 agents 147 619 against 142 341 (LaCAM's plan 156 452 in both), lak303d 1000 (a
//! generated scenario) a gain over LaCAM's plan of 1 240 against 2 942, random-32-32-20 409
//! 21 455 / 21 674 against 21 150 / 21 302 (two runs), seed 3 24 490 against 24 868,
//! room-64-64-8 300 25 819 against 25 809. A first version whose prior favoured the small caps
//! (and drew a sixteenth too) lost 1-3.5 % on random-32-32-20 409 at seeds 0 and 3, where the
//! gains come from searches of 8 000 states and more.
//!
//! Space-time A* ([`crate::spacetime`]) is optimal for one robot given the others: states
//! (cell, step), waits allowed, the true step distance as heuristic (ties to the state nearer
//! the goal, then the deeper), and the robot may stop on its goal only after the last time
//! anybody else passes there. Beyond the last step of the longest other path the world no
//! longer changes, so states there are merged by cell and the search is finite.
//! Each round is O(k · T · V log(T · V)) in the worst case for k robots and horizon T.
//!
//! Several cores: rounds run in batches of `RefineConfig::batch` neighbourhoods, drawn one after
//! the other from the seeded generator (each apart from those before it), then planned side by
//! side (rayon) against the same plan, which none of them changes: each sees the plan without
//! its own robots, plus the paths it has planned again so far. They are committed in the order
//! drawn. The first keeps its paths when they are cheaper, exactly as a lone round would; each
//! later one too, provided its paths, planned before the earlier ones were kept, still avoid
//! everyone (checked with the search's own move test; such clashes turned out rare). The batch
//! size is part of the configuration, never the number of cores, so a seed gives the same plan
//! on one thread or many; only a deadline makes the result depend on speed.
//!
//! The default batch is 4. A batch finds about a tenth fewer improvements per round, and the
//! searches of one batch differ widely in length (one runs to its node cap while another ends
//! at once), but with a second core free it runs about half as many rounds again in the same
//! time. Measured on 2 free cores (warehouse-10-20-10-2-1, 4-connected, sum of costs over the
//! lower bound, seeds 0–2): 500 agents in 10 s, batch 4 +11.7 / +11.5 / +10.1 % against batch
//! 1's +12.3 / +12.8 / +16.1 %; 1000 agents in 30 s (seeds 0–1), +104.4 / +95.2 % against
//! +112.8 / +111.5 %. On one core, or with the second core busy, batch 1 does better (500
//! agents: about +12.5 % against +17 %): `RefineConfig::batch` / `--refine-batch 1`.

use crate::moves::{MoveGraph, NIL};
use crate::outcome::Budget;
use crate::spacetime::{key, Limits, Open, Query, Rules, Search};
use rand::seq::SliceRandom;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rayon::prelude::*;
use rustc_hash::FxHashMap;
use std::cmp::Reverse;
use std::sync::Mutex;

/// When refinement stops besides the deadline.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct RefineConfig {
    /// Robots replanned per round: the middle rung of the size ladder (half of it, it, twice it;
    /// see the module notes).
    pub neighbourhood: usize,
    /// Whether new paths of equal sum of costs replace the old ones too (a sideways move that
    /// changes where the robots are without making the plan worse; see the module notes).
    pub ties: bool,
    /// Stop after this many rounds (`None`: only the deadline, or `stall`, stops it).
    pub rounds: Option<u64>,
    /// Stop after this many rounds in a row without improvement (`None`: never).
    pub stall: Option<u64>,
    /// Cap on space-time states expanded per robot replanned: the largest of the caps a
    /// neighbourhood may get (it, half, a quarter, an eighth; chosen by how much each has
    /// gained per state expanded, see the module notes).
    pub node_limit: u64,
    /// Neighbourhoods drawn per batch and planned side by side (at least 1; see the module
    /// notes). The plan depends on it and on the seed, never on the number of cores.
    pub batch: usize,
}

impl Default for RefineConfig {
    fn default() -> Self {
        RefineConfig {
            neighbourhood: 4,
            ties: true,
            rounds: None,
            stall: Some(1000),
            node_limit: 30_000,
            batch: BATCH,
        }
    }
}

/// What refinement did.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct RefineStats {
    /// Rounds run.
    pub rounds: u64,
    /// Rounds whose new paths were kept and cheaper.
    pub improvements: u64,
    /// Rounds whose new paths were kept at equal cost (`RefineConfig::ties`).
    pub sideways: u64,
    /// Space-time states expanded.
    pub expanded: u64,
    /// Whether it stopped because `RefineConfig::stall` rounds in a row brought no gain.
    pub stalled: bool,
}

/// Everyone's paths indexed by (cell, step), kept in step with `paths`.
pub(crate) struct Occupancy {
    /// (step << 32 | cell) → robot, for every step before the robot's last.
    pub(crate) at: FxHashMap<u64, u32>,
    /// cell → (first step, robot) of the robot resting there for good.
    pub(crate) rest: Vec<(u32, u32)>,
    /// cell → (step, robot) of every visit before a robot's last step.
    pub(crate) visits: Vec<Vec<(u32, u32)>>,
}

impl Occupancy {
    pub(crate) fn new(cells: usize, paths: &[Vec<u32>]) -> Self {
        let mut o = Occupancy {
            at: FxHashMap::default(),
            rest: vec![(0, NIL); cells],
            visits: vec![Vec::new(); cells],
        };
        for (r, p) in paths.iter().enumerate() {
            o.add(r as u32, p);
        }
        o
    }

    pub(crate) fn add(&mut self, r: u32, p: &[u32]) {
        let last = p.len() - 1;
        for (t, &c) in p[..last].iter().enumerate() {
            self.at.insert(key(c, t as u32), r);
            self.visits[c as usize].push((t as u32, r));
        }
        self.rest[p[last] as usize] = (last as u32, r);
    }

    pub(crate) fn remove(&mut self, r: u32, p: &[u32]) {
        let last = p.len() - 1;
        for (t, &c) in p[..last].iter().enumerate() {
            self.at.remove(&key(c, t as u32));
            self.visits[c as usize].retain(|&(_, x)| x != r);
        }
        self.rest[p[last] as usize] = (0, NIL);
    }

    #[inline]
    fn who(&self, cell: u32, t: u32) -> u32 {
        if let Some(&r) = self.at.get(&key(cell, t)) {
            return r;
        }
        let (from, r) = self.rest[cell as usize];
        if r != NIL && t >= from {
            r
        } else {
            NIL
        }
    }
}

#[inline]
fn pos(p: &[u32], t: u32) -> u32 {
    p[(t as usize).min(p.len() - 1)]
}

/// Steps until a path last arrives on its final cell.
pub(crate) fn arrival(p: &[u32]) -> u64 {
    let last = p[p.len() - 1];
    p.iter()
        .rposition(|&c| c != last)
        .map_or(0, |t| t as u64 + 1)
}

/// Neighbourhoods drawn per batch by default (see the module notes).
const BATCH: usize = 4;

/// Rounds in a row without a gain before the neighbourhood grows (see [`size_ladder`]).
const SIZE_PATIENCE: u64 = 200;

/// Arms of [`Caps`]: the configured cap on states per robot, then halved this many times.
const CAP_ARMS: usize = 4;

/// How fast [`Caps`] forgets: each record scales the sums before it by this.
const CAP_MEMORY: f64 = 0.995;

/// The cap on states expanded per robot replanned, chosen per neighbourhood among the
/// configured cap and its halves (see the module notes): each arm is drawn with a probability
/// proportional to what it has gained per state expanded, in sums that fade with
/// [`CAP_MEMORY`], each arm's shrunk towards the rate of all arms by one cap's worth of
/// states.
struct Caps {
    caps: Vec<u64>,
    gain: Vec<f64>,
    spent: Vec<f64>,
}

impl Caps {
    fn new(node_limit: u64) -> Self {
        let mut caps: Vec<u64> = (0..CAP_ARMS).map(|j| (node_limit >> j).max(1)).collect();
        caps.dedup();
        let n = caps.len();
        Caps {
            caps,
            gain: vec![0.0; n],
            spent: vec![0.0; n],
        }
    }

    fn cap(&self, arm: usize) -> u64 {
        self.caps[arm]
    }

    /// Gain per state expanded of `arm`, with the prior of one cap's worth of states at the
    /// rate of all arms together (a tiny rate before any gain): an arm little tried is drawn
    /// about as often as the average arm, and one that gains nothing fades whatever its cap.
    fn rate(&self, arm: usize) -> f64 {
        let spent: f64 = self.spent.iter().sum();
        let all = (self.gain.iter().sum::<f64>() + 1e-9) / (spent + 1.0);
        let cap = self.caps[arm] as f64;
        (self.gain[arm] + all * cap) / (self.spent[arm] + cap)
    }

    fn pick(&self, rng: &mut ChaCha8Rng) -> usize {
        let total: f64 = (0..self.caps.len()).map(|a| self.rate(a)).sum();
        let mut pick = rng.gen::<f64>() * total;
        for a in 0..self.caps.len() - 1 {
            let r = self.rate(a);
            if pick < r {
                return a;
            }
            pick -= r;
        }
        self.caps.len() - 1
    }

    /// A neighbourhood planned under `arm`'s cap gained `gain` and expanded `expanded` states.
    fn record(&mut self, arm: usize, gain: u64, expanded: u64) {
        for a in 0..self.caps.len() {
            self.gain[a] *= CAP_MEMORY;
            self.spent[a] *= CAP_MEMORY;
        }
        self.gain[arm] += gain as f64;
        self.spent[arm] += expanded as f64;
    }
}

/// The neighbourhood sizes refinement climbs through, smallest first, for a configured size
/// `k` (at least 1): half of it, it, and twice it, without repeats.
fn size_ladder(k: usize) -> Vec<usize> {
    let k = k.max(1);
    let mut ladder = vec![(k / 2).max(1), k, 2 * k];
    ladder.dedup();
    ladder
}

/// One neighbourhood of a batch: its kind, its robots in planning order, and what planning
/// them again gave.
struct Candidate {
    kind: usize,
    /// The arm of [`Caps`] that gave this neighbourhood its cap on states per robot.
    arm: usize,
    group: Vec<usize>,
    /// The new paths of `group`'s first robots, in order; all of them unless a search failed.
    fresh: Vec<Vec<u32>>,
    expanded: u64,
}

impl Candidate {
    /// Plans the group again, one robot after another, around everyone else as `occ` and
    /// `paths` hold them (read only); `cost` are the robots' current costs. With `ties` the new
    /// paths may cost as much as the old ones in all, not only less.
    fn plan(
        &mut self,
        search: &mut Search<OpenEntry>,
        graph: &MoveGraph,
        dist: &[Vec<u32>],
        goals: &[u32],
        (occ, paths, cost): (&Occupancy, &[Vec<u32>], &[u64]),
        (node_limit, ties): (u64, bool),
    ) {
        self.fresh.clear();
        self.expanded = 0;
        // The new paths must arrive, in all, at least one step sooner than the old ones: each
        // search gets what is left of the old cost after the paths planned before it and the
        // shortest paths of the robots after it, and prunes every state that would overrun it.
        let old: u64 = self.group.iter().map(|&r| cost[r]).sum();
        let mut shortest_after: u64 = self
            .group
            .iter()
            .map(|&r| u64::from(dist[r][pos(&paths[r], 0) as usize]))
            .sum();
        let mut spent = 0u64;
        for i in 0..self.group.len() {
            let r = self.group[i];
            shortest_after -= u64::from(dist[r][pos(&paths[r], 0) as usize]);
            let Some(left) = old.checked_sub(u64::from(!ties) + spent + shortest_after) else {
                return;
            };
            let view = View {
                occ,
                paths,
                absent: &self.group,
                planned: &self.fresh,
            };
            let found = replan(
                search,
                (graph, &view),
                &dist[r],
                (pos(&paths[r], 0), goals[r]),
                (node_limit, u32::try_from(left).unwrap_or(u32::MAX)),
                &mut self.expanded,
            );
            match found {
                Some(p) => {
                    spent += arrival(&p);
                    self.fresh.push(p);
                }
                None => return,
            }
        }
    }

    /// Old and new sum of costs of the group, when every robot got a new path.
    fn costs(&self, cost: &[u64]) -> Option<(u64, u64)> {
        (self.fresh.len() == self.group.len()).then(|| {
            (
                self.group.iter().map(|&r| cost[r]).sum(),
                self.fresh.iter().map(|p| arrival(p)).sum(),
            )
        })
    }

    /// Whether some new path differs from the robot's path in `paths`.
    fn moves(&self, paths: &[Vec<u32>]) -> bool {
        self.group
            .iter()
            .zip(&self.fresh)
            .any(|(&r, p)| paths[r] != *p)
    }

    /// Whether the new paths still avoid everyone, as `occ` and `paths` hold them now.
    fn fits(&self, graph: &MoveGraph, goals: &[u32], occ: &Occupancy, paths: &[Vec<u32>]) -> bool {
        (0..self.fresh.len()).all(|i| {
            let view = View {
                occ,
                paths,
                absent: &self.group,
                planned: &self.fresh[..i],
            };
            let p = &self.fresh[i];
            let goal = goals[self.group[i]];
            let Some(free_from) = view.free_from(goal) else {
                return false;
            };
            p.len() as u32 > free_from
                && p.windows(2)
                    .enumerate()
                    .all(|(t, w)| view.can_move(graph, w[0], w[1], t as u32))
        })
    }
}

/// Improves `paths` (valid for `goals`) in place until the budget or `config` stops it, and
/// never makes the sum of costs worse.
///
/// Rounds run in batches of `config.batch` neighbourhoods drawn one after another, planned in
/// parallel on rayon's current pool against the same plan, and committed in the order drawn:
/// an improving neighbourhood is kept when its new paths still avoid those kept before it in
/// the batch. The plan depends on the seed alone, not on the threads or their timing (unless the
/// deadline stops it).
pub fn refine(
    graph: &MoveGraph,
    dist: &[Vec<u32>],
    goals: &[u32],
    paths: &mut [Vec<u32>],
    config: &RefineConfig,
    budget: &Budget,
    seed: u64,
) -> RefineStats {
    let n = paths.len();
    let mut stats = RefineStats::default();
    if n == 0 || config.neighbourhood == 0 {
        return stats;
    }
    let mut rng = ChaCha8Rng::seed_from_u64(seed ^ 0x5eed_1a75);
    let mut occ = Occupancy::new(graph.cells(), paths);
    // Search scratch, taken by whichever thread plans a neighbourhood and given back after:
    // as many as threads ran at once, and one thread keeps reusing the same (warm) one.
    let scratch: Mutex<Vec<Search<OpenEntry>>> = Mutex::new(Vec::new());
    let mut weights = [1.0f64; 3];
    let mut caps = Caps::new(config.node_limit);
    let mut stall = 0u64;
    let lower: u64 = (0..n)
        .map(|i| u64::from(dist[i][pos(&paths[i], 0) as usize]))
        .sum();
    let mut cost: Vec<u64> = paths.iter().map(|p| arrival(p)).collect();
    let mut soc: u64 = cost.iter().sum();
    // Variable neighbourhood search: the size climbs a ladder (half the configured size, the
    // size, twice it) after `SIZE_PATIENCE` rounds in a row without a gain at one rung, wraps
    // round after the top, and drops back to the bottom after every gain.
    let ladder: Vec<usize> = size_ladder(config.neighbourhood)
        .into_iter()
        .map(|k| k.min(n))
        .collect();
    let mut rung = 0usize;
    let mut rung_stall = 0u64;
    let mut batch: Vec<Candidate> = Vec::with_capacity(config.batch);
    loop {
        if rung_stall >= SIZE_PATIENCE {
            rung = (rung + 1) % ladder.len();
            rung_stall = 0;
        }
        let k = ladder[rung];
        if soc <= lower || budget.out_of_time() || config.rounds.is_some_and(|r| stats.rounds >= r)
        {
            return stats;
        }
        if config.stall.is_some_and(|s| stall >= s) {
            stats.stalled = true;
            return stats;
        }
        let per_batch = config.batch.max(1) as u64;
        let size = config
            .rounds
            .map_or(per_batch, |r| (r - stats.rounds).min(per_batch));
        stats.rounds += size;
        // Draw the neighbourhoods one after another, each apart from those before it.
        batch.clear();
        let mut taken: Vec<usize> = Vec::new();
        for c in 0..size as usize {
            let arm = caps.pick(&mut rng);
            let total: f64 = weights.iter().sum();
            let mut pick = rng.gen::<f64>() * total;
            let mut kind = 0;
            while kind < 2 && pick >= weights[kind] {
                pick -= weights[kind];
                kind += 1;
            }
            let group = match kind {
                0 => delayed_group(dist, paths, &cost, &occ, k, &taken, &mut rng),
                1 => area_group(graph, paths, &occ, k, &taken, &mut rng),
                _ => random_group(n, k, &taken, &mut rng),
            };
            match group {
                Some(mut group) => {
                    group.shuffle(&mut rng);
                    taken.extend_from_slice(&group);
                    batch.push(Candidate {
                        kind,
                        arm,
                        group,
                        fresh: Vec::new(),
                        expanded: 0,
                    });
                }
                None => {
                    // Nobody left for this kind: the first of a batch sees the whole plan.
                    if c == 0 {
                        weights[kind] = (weights[kind] * 0.9).max(0.05);
                    }
                    stall += 1;
                }
            }
        }
        // Plan them side by side against the same plan, read only.
        let shared = (&occ, &*paths);
        batch.par_iter_mut().for_each(|cand| {
            let taken = scratch.lock().map(|mut s| s.pop()).unwrap_or(None);
            let mut search = taken.unwrap_or_default();
            cand.plan(
                &mut search,
                graph,
                dist,
                goals,
                (shared.0, shared.1, &cost),
                (caps.cap(cand.arm), config.ties),
            );
            if let Ok(mut s) = scratch.lock() {
                s.push(search);
            }
        });
        // Commit in the order drawn.
        let mut changed = false;
        for cand in &batch {
            stats.expanded += cand.expanded;
            let kept = match cand.costs(&cost) {
                Some((old, new))
                    if (new < old || (config.ties && new == old && cand.moves(paths)))
                        && (!changed || cand.fits(graph, goals, &occ, paths)) =>
                {
                    Some(old - new)
                }
                _ => None,
            };
            caps.record(cand.arm, kept.unwrap_or(0), cand.expanded);
            match kept {
                Some(gain) => {
                    for (&r, p) in cand.group.iter().zip(&cand.fresh) {
                        occ.remove(r as u32, &paths[r]);
                        paths[r].clone_from(p);
                        cost[r] = arrival(p);
                    }
                    for &r in &cand.group {
                        occ.add(r as u32, &paths[r]);
                    }
                    soc -= gain;
                    if gain > 0 {
                        rung = 0;
                        rung_stall = 0;
                        stats.improvements += 1;
                        stall = 0;
                        weights[cand.kind] += gain as f64;
                    } else {
                        rung_stall += 1;
                        stats.sideways += 1;
                        stall += 1;
                    }
                    changed = true;
                }
                None => {
                    rung_stall += 1;
                    weights[cand.kind] = (weights[cand.kind] * 0.99).max(0.05);
                    stall += 1;
                }
            }
        }
    }
}

/// The plan as one neighbourhood sees it while it is planned again: everyone in `occ` and
/// `paths` but the robots `absent`, plus the new paths `planned` of the first of those.
struct View<'a> {
    occ: &'a Occupancy,
    paths: &'a [Vec<u32>],
    absent: &'a [usize],
    planned: &'a [Vec<u32>],
}

impl View<'_> {
    /// Who is on `cell` at step `t`, or `NIL`.
    #[inline(always)]
    fn who(&self, cell: u32, t: u32) -> u32 {
        let r = self.occ.who(cell, t);
        // Somebody present there rules out the planned paths, which avoid everyone present.
        if r != NIL && !self.absent.contains(&(r as usize)) {
            return r;
        }
        for (i, p) in self.planned.iter().enumerate() {
            if pos(p, t) == cell {
                return self.absent[i] as u32;
            }
        }
        NIL
    }

    /// The path of robot `r`, which must not be absent unless planned.
    #[inline]
    fn path(&self, r: u32) -> &[u32] {
        match self.absent.iter().position(|&a| a == r as usize) {
            Some(i) => &self.planned[i],
            None => &self.paths[r as usize],
        }
    }

    /// The first step from which a robot may rest on `goal` for good, or `None` when somebody
    /// else rests there.
    fn free_from(&self, goal: u32) -> Option<u32> {
        let (_, resting) = self.occ.rest[goal as usize];
        if resting != NIL && !self.absent.contains(&(resting as usize)) {
            return None;
        }
        if self.planned.iter().any(|p| p[p.len() - 1] == goal) {
            return None;
        }
        let before = self.occ.visits[goal as usize]
            .iter()
            .filter(|&&(_, r)| !self.absent.contains(&(r as usize)))
            .map(|&(t, _)| t + 1);
        let mine = self.planned.iter().flat_map(|p| {
            p[..p.len() - 1]
                .iter()
                .enumerate()
                .filter(|&(_, &c)| c == goal)
                .map(|(t, _)| t as u32 + 1)
        });
        Some(before.chain(mine).max().unwrap_or(0))
    }

    /// One step past the last step at which anybody still moves (at least one).
    fn horizon(&self) -> u32 {
        let others = self
            .paths
            .iter()
            .enumerate()
            .filter(|(r, _)| !self.absent.contains(r))
            .map(|(_, p)| p.len() as u32);
        let mine = self.planned.iter().map(|p| p.len() as u32);
        others.chain(mine).max().unwrap_or(0)
    }

    /// Whether a robot may move (or wait, when `a == b`) from `a` at step `t` to `b` at step
    /// `t + 1`: nobody is on `b` then, nobody swaps with it, nobody crosses its diagonal.
    #[inline(always)]
    fn can_move(&self, graph: &MoveGraph, a: u32, b: u32, t: u32) -> bool {
        if self.who(b, t + 1) != NIL {
            return false;
        }
        if a == b {
            return true;
        }
        let j = self.who(b, t);
        if j != NIL && pos(self.path(j), t + 1) == a {
            return false;
        }
        if let Some((c, d)) = graph.corners(a, b) {
            for (x, y) in [(c, d), (d, c)] {
                let j = self.who(x, t);
                if j != NIL && pos(self.path(j), t + 1) == y {
                    return false;
                }
            }
        }
        true
    }
}

/// A delayed robot and the robots met on its path, none of them `taken`, or `None` when no
/// such robot is delayed.
fn delayed_group(
    dist: &[Vec<u32>],
    paths: &[Vec<u32>],
    cost: &[u64],
    occ: &Occupancy,
    k: usize,
    taken: &[usize],
    rng: &mut ChaCha8Rng,
) -> Option<Vec<usize>> {
    let delayed: Vec<(usize, u64)> = paths
        .iter()
        .enumerate()
        .filter(|(r, _)| !taken.contains(r))
        .filter_map(|(r, p)| {
            let late = cost[r] - u64::from(dist[r][p[0] as usize]);
            (late > 0).then_some((r, late))
        })
        .collect();
    if delayed.is_empty() {
        return None;
    }
    let total: u64 = delayed.iter().map(|d| d.1).sum();
    let mut pick = rng.gen_range(0..total);
    let mut a = delayed[0].0;
    for &(r, late) in &delayed {
        if pick < late {
            a = r;
            break;
        }
        pick -= late;
    }
    let mut group = vec![a];
    let path = &paths[a];
    let mut steps: Vec<usize> = (0..path.len()).collect();
    steps.shuffle(rng);
    'outer: for t in steps {
        for &(s, r) in &occ.visits[path[t] as usize] {
            let r = r as usize;
            if (s as usize).abs_diff(t) <= 3 && !group.contains(&r) && !taken.contains(&r) {
                group.push(r);
                if group.len() >= k {
                    break 'outer;
                }
            }
        }
    }
    fill_random(&mut group, paths.len(), k, taken, rng);
    Some(group)
}

/// The robots passing through the cells nearest a random robot's random cell, none of them
/// `taken`; `None` when every robot is.
fn area_group(
    graph: &MoveGraph,
    paths: &[Vec<u32>],
    occ: &Occupancy,
    k: usize,
    taken: &[usize],
    rng: &mut ChaCha8Rng,
) -> Option<Vec<usize>> {
    let free: Vec<usize> = (0..paths.len()).filter(|r| !taken.contains(r)).collect();
    let &r = free.choose(rng)?;
    let centre = paths[r][rng.gen_range(0..paths[r].len())];
    let mut group = vec![r];
    let mut seen = FxHashMap::default();
    let mut queue = std::collections::VecDeque::from([centre]);
    seen.insert(centre, ());
    while let Some(c) = queue.pop_front() {
        if group.len() >= k || seen.len() > 400 {
            break;
        }
        let mut here: Vec<usize> = occ.visits[c as usize]
            .iter()
            .map(|&(_, x)| x as usize)
            .collect();
        let (_, resting) = occ.rest[c as usize];
        if resting != NIL {
            here.push(resting as usize);
        }
        here.sort_unstable();
        here.dedup();
        here.shuffle(rng);
        for x in here {
            if group.len() < k && !group.contains(&x) && !taken.contains(&x) {
                group.push(x);
            }
        }
        for &m in graph.neighbours(c) {
            if seen.insert(m, ()).is_none() {
                queue.push_back(m);
            }
        }
    }
    fill_random(&mut group, paths.len(), k, taken, rng);
    Some(group)
}

/// Robots drawn at random, none of them `taken`; `None` when none could be drawn.
fn random_group(n: usize, k: usize, taken: &[usize], rng: &mut ChaCha8Rng) -> Option<Vec<usize>> {
    let mut group = Vec::new();
    fill_random(&mut group, n, k, taken, rng);
    (!group.is_empty()).then_some(group)
}

fn fill_random(group: &mut Vec<usize>, n: usize, k: usize, taken: &[usize], rng: &mut ChaCha8Rng) {
    let mut tries = 0;
    while group.len() < k.min(n) && tries < 4 * k {
        let r = rng.gen_range(0..n);
        if !group.contains(&r) && !taken.contains(&r) {
            group.push(r);
        }
        tries += 1;
    }
}

/// An open state of space-time A*: (f, h, t, id), least f first, then nearest the goal, then
/// deepest, then the first generated.
type OpenEntry = (Reverse<u32>, Reverse<u32>, u32, Reverse<u32>);

/// The rules of space-time A* around the robots of a [`View`], with step distances `dist` to
/// the goal: every step costs one.
struct Around<'a> {
    graph: &'a MoveGraph,
    view: &'a View<'a>,
    dist: &'a [u32],
}

impl Rules for Around<'_> {
    type Rank = OpenEntry;
    const UNIT_STEPS: bool = true;

    #[inline(always)]
    fn rank(s: Open) -> OpenEntry {
        (Reverse(s.f), Reverse(s.h), s.t, Reverse(s.id))
    }

    #[inline(always)]
    fn id(r: &OpenEntry) -> u32 {
        r.3 .0
    }

    #[inline(always)]
    fn distance(&mut self, cell: u32) -> u32 {
        self.dist[cell as usize]
    }

    #[inline(always)]
    fn step(&self, from: u32, to: u32, t: u32) -> Option<u32> {
        self.view.can_move(self.graph, from, to, t).then_some(1)
    }
}

/// The quickest path from `start` at step 0 to `goal` around everyone in `view` (which must not
/// hold the robot itself), as the cells from step 0; `None` when there is none within the cap.
fn replan(
    search: &mut Search<OpenEntry>,
    (graph, view): (&MoveGraph, &View),
    dist: &[u32],
    (start, goal): (u32, u32),
    (node_limit, arrive_by): (u64, u32),
    expanded: &mut u64,
) -> Option<Vec<u32>> {
    let rest_from = view.free_from(goal)?;
    let query = Query {
        start,
        goal,
        rest_from,
        limits: Limits {
            still_from: view.horizon().max(rest_from).max(1),
            node_limit,
            arrive_by,
            ..Limits::default()
        },
    };
    let mut rules = Around { graph, view, dist };
    search.run(graph, &mut rules, &query, expanded).ok()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::generate::{keep_largest_region, random_tasks, warehouse};
    use crate::moves::goal_distances;
    use crate::validate::validate;
    use crate::{solve, AssignMethod, Cell, Connectivity, CrewConfig, Grid, Instance, Resolution};

    /// LaCAM's first plan, unrefined; `None` when there is none.
    fn first_plan(inst: &Instance) -> Option<Vec<Vec<u32>>> {
        let config = CrewConfig {
            assign: AssignMethod::Given,
            resolve: Resolution::Lacam,
            refine: RefineConfig {
                rounds: Some(0),
                stall: None,
                ..RefineConfig::default()
            },
            ..CrewConfig::default()
        };
        let budget = Budget {
            node_limit: Some(2_000_000),
            ..Budget::default()
        };
        let out = solve(inst, &config, &budget).unwrap();
        let paths = out.paths?;
        Some(
            paths
                .iter()
                .map(|p| p.iter().map(|c| c.0).collect())
                .collect(),
        )
    }

    fn cells(paths: &[Vec<u32>]) -> Vec<Vec<Cell>> {
        paths
            .iter()
            .map(|p| p.iter().map(|&c| Cell(c)).collect())
            .collect()
    }

    /// A random small grid with `n` robots and goals on distinct free cells.
    fn small_instance(rng: &mut ChaCha8Rng, n: usize, conn: Connectivity) -> Option<Instance> {
        let (w, h) = (rng.gen_range(3..7), rng.gen_range(3..7));
        let blocked = (0..w * h).map(|_| rng.gen_bool(0.15)).collect();
        let mut grid = Grid::new(w, h, blocked);
        keep_largest_region(&mut grid);
        let mut free: Vec<Cell> = (0..grid.len() as u32)
            .map(Cell)
            .filter(|&c| grid.is_free(c))
            .collect();
        if free.len() < n + 2 {
            return None;
        }
        free.shuffle(rng);
        let robots = free[..n].to_vec();
        free.shuffle(rng);
        let goals = free[..n].to_vec();
        Instance::new(grid, conn, robots, goals, Some((0..n).collect()), "small").ok()
    }

    /// A legal path from `start` to `goal`: a few random moves and waits, then straight down
    /// the step distance.
    fn wander(
        graph: &MoveGraph,
        dist: &[u32],
        start: u32,
        steps: usize,
        rng: &mut ChaCha8Rng,
    ) -> Vec<u32> {
        let mut path = vec![start];
        let mut c = start;
        for _ in 0..steps {
            let moves: Vec<u32> = std::iter::once(c)
                .chain(graph.neighbours(c).iter().copied())
                .collect();
            c = *moves.choose(rng).unwrap();
            path.push(c);
        }
        while dist[c as usize] > 0 {
            c = *graph
                .neighbours(c)
                .iter()
                .find(|&&m| dist[m as usize] + 1 == dist[c as usize])
                .unwrap();
            path.push(c);
        }
        path
    }

    #[test]
    fn the_commit_check_agrees_with_the_validator() {
        // A later neighbourhood of a batch is kept only when `fits` says its paths avoid
        // everyone; on random paths against valid plans, `fits` must say exactly what
        // `crew::validate` says of the plan with those paths in.
        let mut rng = ChaCha8Rng::seed_from_u64(3);
        let (mut fit, mut clash) = (0, 0);
        for k in 0..300 {
            let conn = if k % 2 == 0 {
                Connectivity::Four
            } else {
                Connectivity::Eight
            };
            let n = 2 + k % 5;
            let Some(inst) = small_instance(&mut rng, n, conn) else {
                continue;
            };
            let graph = MoveGraph::new(&inst.grid, conn);
            let dist = goal_distances(&inst.grid, conn, &inst.goals);
            let goals: Vec<u32> = inst.goals.iter().map(|c| c.0).collect();
            let Some(paths) = first_plan(&inst) else {
                continue;
            };
            let occ = Occupancy::new(graph.cells(), &paths);
            let mut group: Vec<usize> = (0..n).collect();
            group.shuffle(&mut rng);
            group.truncate(1 + k % 2);
            let fresh: Vec<Vec<u32>> = group
                .iter()
                .map(|&r| wander(&graph, &dist[r], paths[r][0], rng.gen_range(0..6), &mut rng))
                .collect();
            let mut after = paths.clone();
            for (&r, p) in group.iter().zip(&fresh) {
                after[r].clone_from(p);
            }
            let cand = Candidate {
                kind: 0,
                arm: 0,
                group,
                fresh,
                expanded: 0,
            };
            let fits = cand.fits(&graph, &goals, &occ, &paths);
            let valid = validate(&inst.grid, conn, &inst.robots, &inst.goals, &cells(&after));
            assert_eq!(fits, valid.is_ok(), "instance {k}: {valid:?}");
            if fits {
                fit += 1;
            } else {
                clash += 1;
            }
        }
        assert!(fit >= 20 && clash >= 20, "{fit} fit, {clash} clash");
    }

    /// A warehouse instance for the refinement tests, with its move graph, distances, goal
    /// cells and LaCAM's first plan.
    #[allow(clippy::type_complexity)]
    fn warehouse_case(n: usize) -> (Instance, MoveGraph, Vec<Vec<u32>>, Vec<u32>, Vec<Vec<u32>>) {
        let grid = warehouse(60, 40, 0.05, 2);
        let (robots, goals) = random_tasks(&grid, n, 4);
        let inst = Instance::new(
            grid,
            Connectivity::Four,
            robots,
            goals,
            Some((0..n).collect()),
            "warehouse",
        )
        .unwrap();
        let graph = MoveGraph::new(&inst.grid, inst.connectivity);
        let dist = goal_distances(&inst.grid, inst.connectivity, &inst.goals);
        let targets: Vec<u32> = inst.goals.iter().map(|c| c.0).collect();
        let paths = first_plan(&inst).expect("a first plan");
        (inst, graph, dist, targets, paths)
    }

    #[test]
    fn sideways_moves_keep_the_plan_valid_and_the_cost_equal() {
        // With ties on, a round may keep new paths of equal cost: the plan must stay valid and
        // no costlier after each such round, some rounds must actually move sideways, and with
        // ties off none may.
        let (inst, graph, dist, targets, first) = warehouse_case(90);
        for ties in [true, false] {
            let mut paths = first.clone();
            let mut soc: u64 = paths.iter().map(|p| arrival(p)).sum();
            let mut sideways = 0;
            let config = RefineConfig {
                rounds: Some(1),
                stall: None,
                batch: 1,
                ties,
                ..RefineConfig::default()
            };
            for seed in 0..150 {
                let before = paths.clone();
                let stats = refine(
                    &graph,
                    &dist,
                    &targets,
                    &mut paths,
                    &config,
                    &Budget::unlimited(),
                    seed,
                );
                let m = validate(
                    &inst.grid,
                    inst.connectivity,
                    &inst.robots,
                    &inst.goals,
                    &cells(&paths),
                )
                .unwrap_or_else(|e| panic!("round {seed}: {e}"));
                assert!(m.sum_of_costs <= soc, "round {seed}: cost rose");
                if stats.sideways > 0 {
                    assert_eq!(
                        m.sum_of_costs, soc,
                        "round {seed}: sideways but cost changed"
                    );
                    assert!(paths != before, "round {seed}: sideways but nothing moved");
                }
                soc = m.sum_of_costs;
                sideways += stats.sideways;
            }
            if ties {
                assert!(sideways > 0, "no sideways move in 150 rounds");
            } else {
                assert_eq!(sideways, 0);
            }
        }
    }

    #[test]
    fn the_caps_halve_and_the_arm_that_gains_most_per_state_is_drawn_most() {
        assert_eq!(Caps::new(30_000).caps, vec![30_000, 15_000, 7_500, 3_750]);
        assert_eq!(Caps::new(2).caps, vec![2, 1]);
        let mut caps = Caps::new(16_000);
        let mut rng = ChaCha8Rng::seed_from_u64(1);
        let drawn = |caps: &Caps, rng: &mut ChaCha8Rng| {
            let mut n = vec![0; caps.caps.len()];
            for _ in 0..10_000 {
                n[caps.pick(rng)] += 1;
            }
            n
        };
        // Before any record every arm is drawn about as often.
        let before = drawn(&caps, &mut rng);
        assert!(
            before.iter().all(|&n| (2_000..3_000).contains(&n)),
            "{before:?}"
        );
        // The largest cap gains 10 per 16 000 states, the smallest nothing: the largest
        // becomes the most drawn, the untried ones stay at the average, and the smallest is
        // drawn least, but still drawn.
        for _ in 0..200 {
            caps.record(0, 10, 16_000);
            caps.record(3, 0, 2_000);
        }
        let after = drawn(&caps, &mut rng);
        assert!(after[0] > after[1] && after[0] > after[2], "{after:?}");
        assert!(
            after[3] > 0 && after[3] < after[1] && after[3] < after[2],
            "{after:?}"
        );
    }

    #[test]
    fn the_size_ladder_halves_and_doubles_the_configured_size() {
        assert_eq!(size_ladder(4), vec![2, 4, 8]);
        assert_eq!(size_ladder(5), vec![2, 5, 10]);
        assert_eq!(size_ladder(2), vec![1, 2, 4]);
        assert_eq!(size_ladder(1), vec![1, 2]);
        assert_eq!(size_ladder(0), vec![1, 2]);
    }

    #[test]
    fn a_fixed_number_of_rounds_gives_the_same_plan_twice() {
        let (_, graph, dist, targets, first) = warehouse_case(90);
        let config = RefineConfig {
            rounds: Some(200),
            stall: None,
            ..RefineConfig::default()
        };
        let run = || {
            let mut paths = first.clone();
            let stats = refine(
                &graph,
                &dist,
                &targets,
                &mut paths,
                &config,
                &Budget::unlimited(),
                5,
            );
            (paths, stats)
        };
        let (a, sa) = run();
        let (b, sb) = run();
        assert_eq!(sa, sb);
        assert!(a == b, "the plans differ");
        assert!(sa.improvements > 0);
    }

    #[test]
    fn every_batch_leaves_a_valid_plan_no_costlier_than_before() {
        let (inst, graph, dist, targets, mut paths) = warehouse_case(90);
        let first: u64 = paths.iter().map(|p| arrival(p)).sum();
        let mut soc = first;
        let mut several_kept = 0;
        let one_batch = RefineConfig {
            rounds: Some(4),
            stall: None,
            batch: 4,
            ..RefineConfig::default()
        };
        for seed in 0..80 {
            let stats = refine(
                &graph,
                &dist,
                &targets,
                &mut paths,
                &one_batch,
                &Budget::unlimited(),
                seed,
            );
            assert_eq!(stats.rounds, 4);
            let m = validate(
                &inst.grid,
                inst.connectivity,
                &inst.robots,
                &inst.goals,
                &cells(&paths),
            )
            .unwrap_or_else(|e| panic!("batch {seed}: {e}"));
            assert!(m.sum_of_costs <= soc, "batch {seed}: cost rose");
            soc = m.sum_of_costs;
            if stats.improvements >= 2 {
                several_kept += 1;
            }
        }
        assert!(soc < first, "no batch improved the plan ({first})");
        assert!(
            several_kept > 0,
            "no batch kept more than one neighbourhood"
        );
    }
}
