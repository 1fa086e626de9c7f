//! A fast first plan for many robots: PIBT rolled out step by step ([`crate::pibt`]), then the
//! robots it leaves short of their goals repaired by space-time A* around everyone else.
//!
//! PIBT alone brings most robots home quickly but can circle for ever where two robots must
//! pass each other in a one-cell corridor while each one's goal lies behind the other (their
//! priorities take turns, each pushes the other back). Two remedies, both incomplete:
//! - during the rollout, a robot that has not come nearer its goal for a dozen steps follows a
//!   *detour*: distances that go round the robots resting on their goals and the robot in front
//!   of it, until it reaches its goal;
//! - the rollout stops when no further robot comes home; then each robot left short is given a
//!   continuation from where it stands, by space-time A* in the now still world around everyone
//!   else. When that fails, the robots in its way (resting on its goal, on its cheapest way
//!   there, or near either end) are replanned with it, in a few orders, the group growing on
//!   each retry.
//!
//! This is no search over configurations (LaCAM, [`crate::lacam`], is complete but slow in that
//! trap at hundreds of robots): when repair gives up, the caller falls back on LaCAM.
//! Every path is planned around all others under the rules of `crew::validate`, so the result
//! is a valid plan. This is incomplete: when repair gives up, the caller falls back on LaCAM.
//! O(T · n · d) for the rollout of T steps, plus one space-time search per repair.

use crate::moves::{MoveGraph, NIL};
use crate::outcome::Budget;
use crate::pibt::Pibt;
use crate::refine::{Occupancy, Search};
use rand::seq::SliceRandom;
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use std::collections::VecDeque;

/// How the rollout and its repair ended.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum RepairEnd {
    /// A plan: `paths[i][t]`, each cut at the robot's last arrival.
    Found(Vec<Vec<u32>>),
    /// Some robot could not be repaired (or PIBT could not step); try LaCAM. The valid partial
    /// plan so far (robots short of their goals rest where their paths end), if any.
    GaveUp(Option<Vec<Vec<u32>>>),
    /// The deadline came first.
    Budget,
}

/// What the rollout and the repair did.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct RepairStats {
    /// PIBT steps rolled out.
    pub steps: u64,
    /// Robots short of their goals after the rollout.
    pub stuck: u64,
    /// Space-time states expanded by the repair.
    pub expanded: u64,
}

/// Rolls PIBT out from `starts` for at most `max_steps` steps, then repairs.
pub fn rollout_and_repair(
    graph: &MoveGraph,
    dist: &[Vec<u32>],
    starts: &[u32],
    goals: &[u32],
    max_steps: u32,
    budget: &Budget,
    seed: u64,
) -> (RepairEnd, RepairStats) {
    let n = starts.len();
    let mut stats = RepairStats::default();
    let mut pibt = Pibt::new(graph, dist, seed);
    let max_d = (0..n)
        .map(|i| dist[i][starts[i] as usize])
        .max()
        .unwrap_or(0);
    let mut priority: Vec<f32> = (0..n)
        .map(|i| dist[i][starts[i] as usize] as f32 / (max_d as f32 + 1.0))
        .collect();
    let mut configs: Vec<Vec<u32>> = vec![starts.to_vec()];
    let home = |q: &[u32]| (0..n).filter(|&i| q[i] == goals[i]).count();
    let (mut best_step, mut best_home) = (0, home(starts));
    let mut order: Vec<u32> = (0..n as u32).collect();
    // Steps since each robot last came nearer its goal than ever before, and that nearest.
    let mut nearest: Vec<u32> = (0..n).map(|i| dist[i][starts[i] as usize]).collect();
    let mut idle = vec![0u32; n];
    let mut detoured = vec![false; n];
    let patience = 2 * max_d as usize + 64;
    while best_home < n && configs.len() <= max_steps as usize {
        if configs.len() % 32 == 0 && budget.out_of_time() {
            return (RepairEnd::Budget, stats);
        }
        let q = configs.last().expect("non-empty");
        order.sort_by(|&a, &b| priority[b as usize].total_cmp(&priority[a as usize]));
        let mut next = vec![0; n];
        if !pibt.step(q, &mut next, &order, &[]) {
            return (RepairEnd::GaveUp(None), stats);
        }
        for i in 0..n {
            let p = priority[i];
            priority[i] = if next[i] == goals[i] {
                p - p.floor()
            } else {
                p + 1.0
            };
        }
        for i in 0..n {
            let d = dist[i][next[i] as usize];
            if next[i] == goals[i] {
                nearest[i] = 0;
                idle[i] = 0;
                if detoured[i] {
                    pibt.set_detour(i, None);
                    detoured[i] = false;
                }
            } else if d < nearest[i] {
                nearest[i] = d;
                idle[i] = 0;
            } else {
                idle[i] += 1;
                if idle[i] >= DETOUR_AFTER {
                    idle[i] = 0;
                    let table = detour(graph, &dist[i], &next, goals, i);
                    detoured[i] = table.is_some();
                    pibt.set_detour(i, table);
                }
            }
        }
        let h = home(&next);
        configs.push(next);
        if h > best_home {
            (best_step, best_home) = (configs.len() - 1, h);
        }
        // Stop early once PIBT has circled for long without bringing anyone new home.
        if configs.len() - 1 > best_step + patience {
            break;
        }
    }
    configs.truncate(best_step + 1);
    stats.steps = best_step as u64;
    let mut paths: Vec<Vec<u32>> = (0..n)
        .map(|i| {
            let mut p: Vec<u32> = configs.iter().map(|q| q[i]).collect();
            let last = p[p.len() - 1];
            let arrive = p.iter().rposition(|&c| c != last).map_or(0, |t| t + 1);
            p.truncate(arrive + 1);
            p
        })
        .collect();
    drop(configs);
    let mut queue: VecDeque<usize> = (0..n)
        .filter(|&i| paths[i][paths[i].len() - 1] != goals[i])
        .collect();
    stats.stuck = queue.len() as u64;
    if queue.is_empty() {
        return (RepairEnd::Found(paths), stats);
    }
    let mut occ = Occupancy::new(graph.cells(), &paths);
    let mut search = Search::new();
    let mut rng = ChaCha8Rng::seed_from_u64(seed ^ 0x4e9a_1200);
    let mut tries = vec![0u32; n];
    let mut attempts = 0u64;
    while let Some(a) = queue.pop_front() {
        if paths[a][paths[a].len() - 1] == goals[a] {
            continue;
        }
        if budget.out_of_time() {
            return (RepairEnd::Budget, stats);
        }
        tries[a] += 1;
        attempts += 1;
        if tries[a] > MAX_TRIES || attempts > 4 * stats.stuck + 8 {
            return (RepairEnd::GaveUp(Some(paths)), stats);
        }
        let size = 1 + 4 * tries[a] as usize;
        let group = blockers(graph, &occ, starts, goals, a, size);
        let mut done = false;
        for attempt in 0..4 {
            let mut order = group.clone();
            order[1..].shuffle(&mut rng);
            if attempt % 2 == 1 {
                order.rotate_left(1);
            }
            if replan(
                graph,
                dist,
                &mut occ,
                &mut search,
                &mut paths,
                (best_step as u32, goals),
                &order,
                &mut stats.expanded,
            ) {
                done = true;
                break;
            }
            if group.len() == 1 {
                break;
            }
        }
        if !done {
            queue.push_back(a);
        }
    }
    (RepairEnd::Found(paths), stats)
}

/// Repairs tried per robot (each with a larger group) before giving up; in all, at most four times
/// as many repairs as robots left short (plus a few).
const MAX_TRIES: u32 = 6;

/// Steps without progress after which a robot in the rollout takes a detour.
const DETOUR_AFTER: u32 = 12;

/// Step distances to robot `i`'s goal that go around the robots resting on their own goals in
/// configuration `q`; `None` when those robots wall it off from its goal.
fn detour(
    graph: &MoveGraph,
    true_dist: &[u32],
    q: &[u32],
    goals: &[u32],
    i: usize,
) -> Option<Vec<u32>> {
    let mut dist = vec![NIL; graph.cells()];
    let mut walls: Vec<u32> = q
        .iter()
        .zip(goals)
        .enumerate()
        .filter(|&(r, (&c, &g))| c == g && r != i)
        .map(|(_, (&c, _))| c)
        .collect();
    // The robot standing on its next cell along a shortest path, if any, is in the way too.
    let here = q[i];
    if let Some(&ahead) = graph
        .neighbours(here)
        .iter()
        .min_by_key(|&&m| (true_dist[m as usize], m))
    {
        if q.contains(&ahead) {
            walls.push(ahead);
        }
    }
    for &c in &walls {
        dist[c as usize] = NIL - 1;
    }
    let goal = goals[i];
    if dist[goal as usize] != NIL {
        return None;
    }
    dist[goal as usize] = 0;
    let mut queue = VecDeque::from([goal]);
    while let Some(c) = queue.pop_front() {
        let d = dist[c as usize] + 1;
        for &m in graph.neighbours(c) {
            if dist[m as usize] == NIL {
                dist[m as usize] = d;
                queue.push_back(m);
            }
        }
    }
    if dist[q[i] as usize] == NIL {
        return None;
    }
    // Cells of resting robots: reachable only by pushing them, so ranked after every free cell.
    for &c in &walls {
        dist[c as usize] = NIL - 1;
    }
    for x in dist.iter_mut() {
        if *x == NIL {
            *x = NIL - 1;
        }
    }
    Some(dist)
}

/// `a` and up to `size - 1` robots in its way: resting on its goal, on its cheapest way there,
/// then near either end of it.
fn blockers(
    graph: &MoveGraph,
    occ: &Occupancy,
    starts: &[u32],
    goals: &[u32],
    a: usize,
    size: usize,
) -> Vec<usize> {
    let mut group = vec![a];
    let add = |r: u32, group: &mut Vec<usize>| {
        if r != NIL && group.len() < size && !group.contains(&(r as usize)) {
            group.push(r as usize);
        }
    };
    add(occ.rest[goals[a] as usize].1, &mut group);
    // The robots resting on the cheapest way to the goal, where passing a resting robot costs
    // as much as `penalty` steps: with a high penalty the way goes round them when it can.
    let penalty = 4 + 8 * (size as u32);
    let from = occ_last(occ, a, starts[a]);
    let mut cost = vec![u32::MAX; graph.cells()];
    let mut back = vec![NIL; graph.cells()];
    let mut heap = std::collections::BinaryHeap::from([(std::cmp::Reverse(0u32), from)]);
    cost[from as usize] = 0;
    while let Some((std::cmp::Reverse(k), c)) = heap.pop() {
        if k > cost[c as usize] {
            continue;
        }
        if c == goals[a] {
            break;
        }
        for &m in graph.neighbours(c) {
            let step = if occ.rest[m as usize].1 != NIL {
                1 + penalty
            } else {
                1
            };
            if k + step < cost[m as usize] {
                cost[m as usize] = k + step;
                back[m as usize] = c;
                heap.push((std::cmp::Reverse(k + step), m));
            }
        }
    }
    let mut c = goals[a];
    while c != NIL && c != from {
        add(occ.rest[c as usize].1, &mut group);
        c = back[c as usize];
    }
    // Then whoever rests near either end, nearest first, farther out as the group grows.
    let radius = 2 + size / 2;
    let mut seen = rustc_hash::FxHashSet::default();
    let mut ring = vec![goals[a], from];
    for _ in 0..radius {
        let mut next_ring = Vec::new();
        for &c in &ring {
            for &m in graph.neighbours(c) {
                if seen.insert(m) {
                    add(occ.rest[m as usize].1, &mut group);
                    next_ring.push(m);
                }
            }
        }
        ring = next_ring;
    }
    group
}

/// Where robot `a` rests now (its start when it is not in `occ`).
fn occ_last(occ: &Occupancy, a: usize, start: u32) -> u32 {
    occ.rest
        .iter()
        .position(|&(_, r)| r == a as u32)
        .map_or(start, |c| c as u32)
}

/// Replans the continuations of `order`, one by one, from where each stands at step `t0` (the
/// end of the rollout, when the world is still); on failure restores the old paths.
#[allow(clippy::too_many_arguments)]
fn replan(
    graph: &MoveGraph,
    dist: &[Vec<u32>],
    occ: &mut Occupancy,
    search: &mut Search,
    paths: &mut [Vec<u32>],
    (t0, goals): (u32, &[u32]),
    order: &[usize],
    expanded: &mut u64,
) -> bool {
    let old: Vec<Vec<u32>> = order.iter().map(|&r| paths[r].clone()).collect();
    for &r in order {
        occ.remove(r as u32, &paths[r]);
    }
    let mut placed = 0;
    for &r in order {
        // Every member keeps its path up to `t0` and gets a new one from there (a robot
        // repaired before may have moved on past `t0`; that part is replaced too).
        let p = &paths[r];
        let here = p[(t0 as usize).min(p.len() - 1)];
        match search.plan(
            graph,
            occ,
            paths,
            &dist[r],
            (here, t0, goals[r]),
            100_000,
            expanded,
        ) {
            Some(rest) => {
                let mut p = paths[r].clone();
                p.resize(t0 as usize + 1, here);
                p.truncate(t0 as usize);
                p.extend_from_slice(&rest);
                let g = p[p.len() - 1];
                let arrive = p.iter().rposition(|&c| c != g).map_or(0, |t| t + 1);
                p.truncate(arrive + 1);
                occ.add(r as u32, &p);
                paths[r] = p;
                placed += 1;
            }
            None => break,
        }
    }
    if placed == order.len() {
        return true;
    }
    for &r in &order[..placed] {
        occ.remove(r as u32, &paths[r]);
    }
    for (&r, p) in order.iter().zip(old) {
        occ.add(r as u32, &p);
        paths[r] = p;
    }
    false
}
