//! Anytime refinement of a valid plan by large neighbourhood search (after Li, Chen, Harabor,
//! Stuckey, Koenig, "Anytime multi-agent path finding via large neighborhood search",
//! IJCAI 2021).
//!
//! One round takes a few robots (a *neighbourhood*), removes their paths, and plans them again
//! one by one, in random order, with space-time A* around everyone else's path (the robots
//! replanned first included). The new paths are kept only when their sum of costs is strictly
//! lower; otherwise the old ones go back. The plan is therefore valid after every round and its
//! sum of costs never rises; the caller stops on a deadline or a round count.
//!
//! Neighbourhoods, chosen by adaptive weights (a kind that improved gets chosen more):
//! - *delayed*: a robot that arrives later than its shortest path would allow, with the robots
//!   that stand on the cells of its path around the same times;
//! - *area*: the robots that pass through the cells nearest a random cell;
//! - *random*: robots drawn at random.
//!
//! Space-time A* is optimal for one robot given the others: states (cell, step), waits allowed,
//! the true step distance as heuristic (ties to the state nearer the goal, then the deeper), and the robot may stop on its goal only after the last
//! time anybody else passes there. Beyond the last step of the longest other path the world no
//! longer changes, so states there are merged by cell and the search is finite.
//! Each round is O(k · T · V log(T · V)) in the worst case for k robots and horizon T.

use crate::moves::{MoveGraph, NIL};
use crate::outcome::Budget;
use rand::seq::SliceRandom;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rustc_hash::{FxHashMap, FxHashSet};
use std::cmp::Reverse;
use std::collections::BinaryHeap;

/// When refinement stops besides the deadline.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct RefineConfig {
    /// Robots replanned per round.
    pub neighbourhood: usize,
    /// Stop after this many rounds (`None`: only the deadline, or `stall`, stops it).
    pub rounds: Option<u64>,
    /// Stop after this many rounds in a row without improvement (`None`: never).
    pub stall: Option<u64>,
    /// Cap on space-time states expanded per robot replanned.
    pub node_limit: u64,
}

impl Default for RefineConfig {
    fn default() -> Self {
        RefineConfig {
            neighbourhood: 4,
            rounds: None,
            stall: Some(1000),
            node_limit: 30_000,
        }
    }
}

/// What refinement did.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct RefineStats {
    /// Rounds run.
    pub rounds: u64,
    /// Rounds whose new paths were kept.
    pub improvements: u64,
    /// Space-time states expanded.
    pub expanded: u64,
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

#[inline]
fn key(cell: u32, t: u32) -> u64 {
    (u64::from(t) << 32) | u64::from(cell)
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

/// Improves `paths` (valid for `goals`) in place until the budget or `config` stops it, and
/// never makes the sum of costs worse.
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
    let mut search = Search::new();
    let mut weights = [1.0f64; 3];
    let mut stall = 0u64;
    let lower: u64 = (0..n)
        .map(|i| u64::from(dist[i][pos(&paths[i], 0) as usize]))
        .sum();
    let mut soc: u64 = paths.iter().map(|p| arrival(p)).sum();
    loop {
        if soc <= lower
            || budget.out_of_time()
            || config.rounds.is_some_and(|r| stats.rounds >= r)
            || config.stall.is_some_and(|s| stall >= s)
        {
            return stats;
        }
        stats.rounds += 1;
        let total: f64 = weights.iter().sum();
        let mut pick = rng.gen::<f64>() * total;
        let mut kind = 0;
        while kind < 2 && pick >= weights[kind] {
            pick -= weights[kind];
            kind += 1;
        }
        let k = config.neighbourhood.min(n);
        let group = match kind {
            0 => delayed_group(dist, paths, &occ, k, &mut rng),
            1 => area_group(graph, paths, &occ, k, &mut rng),
            _ => random_group(n, k, &mut rng),
        };
        let Some(mut group) = group else {
            weights[kind] = (weights[kind] * 0.9).max(0.05);
            stall += 1;
            continue;
        };
        group.shuffle(&mut rng);
        let old: Vec<Vec<u32>> = group.iter().map(|&r| paths[r].clone()).collect();
        let old_cost: u64 = old.iter().map(|p| arrival(p)).sum();
        for (&r, p) in group.iter().zip(&old) {
            occ.remove(r as u32, p);
        }
        let mut fresh: Vec<Vec<u32>> = Vec::with_capacity(group.len());
        let mut ok = true;
        for &r in &group {
            let found = search.plan(
                graph,
                &occ,
                paths,
                &dist[r],
                (pos(&paths[r], 0), 0, goals[r]),
                config.node_limit,
                &mut stats.expanded,
            );
            match found {
                Some(p) => {
                    occ.add(r as u32, &p);
                    paths[r] = p.clone();
                    fresh.push(p);
                }
                None => {
                    ok = false;
                    break;
                }
            }
        }
        let new_cost: u64 = fresh.iter().map(|p| arrival(p)).sum();
        if ok && new_cost < old_cost {
            soc -= old_cost - new_cost;
            stats.improvements += 1;
            stall = 0;
            weights[kind] += (old_cost - new_cost) as f64;
        } else {
            for (&r, p) in group.iter().zip(&fresh) {
                occ.remove(r as u32, p);
            }
            for (&r, p) in group.iter().zip(old) {
                occ.add(r as u32, &p);
                paths[r] = p;
            }
            weights[kind] = (weights[kind] * 0.99).max(0.05);
            stall += 1;
        }
    }
}

/// A delayed robot and the robots met on its path, or `None` when nobody is delayed.
fn delayed_group(
    dist: &[Vec<u32>],
    paths: &[Vec<u32>],
    occ: &Occupancy,
    k: usize,
    rng: &mut ChaCha8Rng,
) -> Option<Vec<usize>> {
    let delayed: Vec<(usize, u64)> = paths
        .iter()
        .enumerate()
        .filter_map(|(r, p)| {
            let late = arrival(p) - u64::from(dist[r][p[0] as usize]);
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
            if (s as usize).abs_diff(t) <= 3 && !group.contains(&r) {
                group.push(r);
                if group.len() >= k {
                    break 'outer;
                }
            }
        }
    }
    fill_random(&mut group, paths.len(), k, rng);
    Some(group)
}

/// The robots passing through the cells nearest a random robot's random cell.
fn area_group(
    graph: &MoveGraph,
    paths: &[Vec<u32>],
    occ: &Occupancy,
    k: usize,
    rng: &mut ChaCha8Rng,
) -> Option<Vec<usize>> {
    let r = rng.gen_range(0..paths.len());
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
            if group.len() < k && !group.contains(&x) {
                group.push(x);
            }
        }
        for &m in graph.neighbours(c) {
            if seen.insert(m, ()).is_none() {
                queue.push_back(m);
            }
        }
    }
    fill_random(&mut group, paths.len(), k, rng);
    Some(group)
}

fn random_group(n: usize, k: usize, rng: &mut ChaCha8Rng) -> Option<Vec<usize>> {
    let mut group = Vec::new();
    fill_random(&mut group, n, k, rng);
    Some(group)
}

fn fill_random(group: &mut Vec<usize>, n: usize, k: usize, rng: &mut ChaCha8Rng) {
    let mut tries = 0;
    while group.len() < k.min(n) && tries < 4 * k {
        let r = rng.gen_range(0..n);
        if !group.contains(&r) {
            group.push(r);
        }
        tries += 1;
    }
}

/// An open state of space-time A*: (f, h, t, node), least f first, then nearest the goal, then
/// deepest.
type OpenEntry = (Reverse<u32>, Reverse<u32>, u32, Reverse<u32>);

/// Space-time A* with reusable buffers.
pub(crate) struct Search {
    nodes: Vec<(u32, u32, u32)>,
    closed: FxHashSet<u64>,
    open: BinaryHeap<OpenEntry>,
}

impl Search {
    pub(crate) fn new() -> Self {
        Search {
            nodes: Vec::new(),
            closed: FxHashSet::default(),
            open: BinaryHeap::new(),
        }
    }

    /// The quickest path from `start` at step `t0` to `goal` around `occ` (which must not hold
    /// the robot itself from `t0` on), as the cells from step `t0`; `None` when there is none
    /// within the cap.
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn plan(
        &mut self,
        graph: &MoveGraph,
        occ: &Occupancy,
        paths: &[Vec<u32>],
        dist: &[u32],
        (start, t0, goal): (u32, u32, u32),
        node_limit: u64,
        expanded: &mut u64,
    ) -> Option<Vec<u32>> {
        if occ.rest[goal as usize].1 != NIL {
            return None;
        }
        let free_from = occ.visits[goal as usize]
            .iter()
            .map(|&(t, _)| t + 1)
            .max()
            .unwrap_or(0);
        let horizon = paths
            .iter()
            .map(|p| p.len() as u32)
            .max()
            .unwrap_or(0)
            .max(free_from)
            .max(t0 + 1);
        self.nodes.clear();
        self.closed.clear();
        self.open.clear();
        let h0 = dist[start as usize];
        if h0 == NIL {
            return None;
        }
        self.nodes.push((start, t0, NIL));
        self.open.push((
            Reverse((t0 + h0).max(free_from)),
            Reverse(h0),
            t0,
            Reverse(0),
        ));
        let mut local = 0u64;
        while let Some((_, _, t, Reverse(id))) = self.open.pop() {
            let (cell, _, _) = self.nodes[id as usize];
            let k = key(cell, t.min(horizon));
            if !self.closed.insert(k) {
                continue;
            }
            local += 1;
            *expanded += 1;
            if local > node_limit {
                return None;
            }
            if cell == goal && t >= free_from {
                let mut path = Vec::with_capacity(t as usize + 1);
                let mut x = id;
                while x != NIL {
                    path.push(self.nodes[x as usize].0);
                    x = self.nodes[x as usize].2;
                }
                path.reverse();
                return Some(path);
            }
            for &next in std::iter::once(&cell).chain(graph.neighbours(cell)) {
                let h = dist[next as usize];
                if h == NIL || !self.can_move(graph, occ, paths, cell, next, t) {
                    continue;
                }
                let nk = key(next, (t + 1).min(horizon));
                if self.closed.contains(&nk) {
                    continue;
                }
                let nid = self.nodes.len() as u32;
                self.nodes.push((next, t + 1, id));
                self.open.push((
                    Reverse((t + 1 + h).max(free_from)),
                    Reverse(h),
                    t + 1,
                    Reverse(nid),
                ));
            }
        }
        None
    }

    #[inline]
    fn can_move(
        &self,
        graph: &MoveGraph,
        occ: &Occupancy,
        paths: &[Vec<u32>],
        a: u32,
        b: u32,
        t: u32,
    ) -> bool {
        if occ.who(b, t + 1) != NIL {
            return false;
        }
        if a == b {
            return true;
        }
        let j = occ.who(b, t);
        if j != NIL && pos(&paths[j as usize], t + 1) == a {
            return false;
        }
        if let Some((c, d)) = graph.corners(a, b) {
            for (x, y) in [(c, d), (d, c)] {
                let j = occ.who(x, t);
                if j != NIL && pos(&paths[j as usize], t + 1) == y {
                    return false;
                }
            }
        }
        true
    }
}
