//! Goal assignment and paths solved together for interchangeable robots: target swapping
//! (TSWAP; Okumura and Défago, "Solving simultaneous target assignment and path planning
//! efficiently with time-independent execution", ICAPS 2022 / AIJ 2023), in its synchronous
//! form.
//!
//! Every robot first gets a goal by a bottleneck assignment on true step distances (the least
//! possible longest distance). Then, step by step, each robot not on its goal takes one step along
//! a shortest path to its goal:
//! - onto a free cell, it moves (a robot may follow another into the cell it leaves);
//! - when a robot resting on its own goal is in the way, the two exchange goals (the blocker
//!   now heads for the mover's goal, and the mover's goal is the cell in front of it);
//! - when robots wait on each other in a cycle, the goals rotate along the cycle, each robot
//!   taking the goal of the one that wanted its cell, so each is one step nearer its new goal;
//! - otherwise it waits.
//!
//! Moves are checked against the rules of `crew::validate` (no shared cell, no swap, no crossing
//! diagonals), so the plan is valid for the final assignment. The sum of distances to the goals
//! never grows and every exchange makes progress, so with connected free space every robot
//! reaches a goal (the paper's argument); the step cap in [`TswapConfig`] only guards against
//! inputs outside that argument. O(n · d) per step plus the deadlock walks; the assignment is
//! O(log D · n · E) for E robot–goal pairs within the bottleneck distance, after m
//! breadth-first searches.

use crate::moves::{MoveGraph, NIL};
use crate::outcome::Budget;
use std::cmp::Reverse;
use std::collections::BinaryHeap;

/// How a TSWAP run ended.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum TswapEnd {
    /// Every robot rests on a goal: its goal index, and its path cut at its last arrival.
    Found {
        /// Goal index of each robot.
        goals: Vec<usize>,
        /// Path of each robot (cells).
        paths: Vec<Vec<u32>>,
    },
    /// Some robot cannot reach any goal left to it.
    Unreachable {
        /// The robot.
        robot: usize,
    },
    /// The deadline or the step cap came first.
    Budget,
}

/// Bottleneck assignment on step distances: the least possible longest robot-to-goal distance
/// (binary search over the distances, each probed by augmenting paths), and among those
/// pairings one that tries each robot's nearer goals first. `dist[g]` holds the step distances
/// to goal g. `None` for a robot when no complete pairing reaches a goal from every robot; the
/// robots that can be paired then still are.
pub fn bottleneck_assignment(dist: &[Vec<u32>], starts: &[u32]) -> Vec<Option<usize>> {
    let n = starts.len();
    // Each robot's reachable goals, nearest first.
    let options: Vec<Vec<(u32, u32)>> = starts
        .iter()
        .map(|&s| {
            let mut o: Vec<(u32, u32)> = dist
                .iter()
                .enumerate()
                .filter_map(|(g, d)| (d[s as usize] != NIL).then_some((d[s as usize], g as u32)))
                .collect();
            o.sort_unstable();
            o
        })
        .collect();
    let mut levels: Vec<u32> = options.iter().flatten().map(|&(d, _)| d).collect();
    levels.sort_unstable();
    levels.dedup();
    if levels.is_empty() {
        return vec![None; n];
    }
    // No pairing is shorter than the farthest of each robot's nearest goals.
    let floor = options
        .iter()
        .filter_map(|o| o.first())
        .map(|o| o.0)
        .max()
        .unwrap_or(0);
    let (mut lo, mut hi) = (levels.partition_point(|&d| d < floor), levels.len() - 1);
    let mut best = matching(&options, dist.len(), levels[hi]);
    if best.iter().any(Option::is_none) {
        return best;
    }
    while lo < hi {
        let mid = (lo + hi) / 2;
        let m = matching(&options, dist.len(), levels[mid]);
        if m.iter().all(Option::is_some) {
            hi = mid;
            best = m;
        } else {
            lo = mid + 1;
        }
    }
    least_sum_matching(&options, dist.len(), levels[hi])
        .map(|m| m.into_iter().map(Some).collect())
        .unwrap_or(best)
}

/// A complete matching of robots to goals using pairs no longer than `limit`, with the least
/// sum of distances among those (`None` when there is no complete one): successive shortest
/// augmenting paths, Dijkstra on reduced costs with one potential per robot and per goal
/// (Johnson's reweighting keeps every reduced cost ≥ 0 and every matched pair's at 0).
/// Each search stops at the first free goal it settles, so a robot with a free goal nearby
/// costs little.
fn least_sum_matching(options: &[Vec<(u32, u32)>], goals: usize, limit: u32) -> Option<Vec<usize>> {
    let n = options.len();
    let mut goal_of = vec![NIL; n];
    let mut robot_of = vec![NIL; goals];
    let mut search = Augment {
        options,
        limit,
        robot_pot: vec![0; n],
        goal_pot: vec![0; goals],
        reach: vec![i64::MAX; goals],
        from: vec![NIL; goals],
        settled: vec![false; goals],
        touched: Vec::new(),
        heap: BinaryHeap::new(),
    };
    for s in 0..n {
        search.reset();
        search.relax(s, 0);
        let mut settled_list: Vec<u32> = Vec::new();
        let mut end = None;
        while let Some(Reverse((d, g))) = search.heap.pop() {
            let gi = g as usize;
            if search.settled[gi] || d > search.reach[gi] {
                continue;
            }
            search.settled[gi] = true;
            settled_list.push(g);
            match robot_of[gi] {
                NIL => {
                    end = Some((g, d));
                    break;
                }
                owner => search.relax(owner as usize, d),
            }
        }
        let (end, total) = end?;
        // New potentials (Johnson's, capped at the end's distance and shifted by it): every
        // settled node drops by how far short of the end it was, which keeps reduced costs ≥ 0
        // and makes the path's zero.
        search.robot_pot[s] -= total;
        for &g in &settled_list {
            let gi = g as usize;
            let shift = total - search.reach[gi];
            search.goal_pot[gi] -= shift;
            if robot_of[gi] != NIL && g != end {
                search.robot_pot[robot_of[gi] as usize] -= shift;
            }
        }
        // Flip the path from the end back to s.
        let mut g = end;
        loop {
            let a = search.from[g as usize];
            let previous = goal_of[a as usize];
            goal_of[a as usize] = g;
            robot_of[g as usize] = a;
            if a as usize == s {
                break;
            }
            g = previous;
        }
    }
    Some(goal_of.into_iter().map(|g| g as usize).collect())
}

/// The state of [`least_sum_matching`]'s searches: potentials, and per search each goal's
/// distance, the robot it was reached from and whether it is settled.
struct Augment<'a> {
    options: &'a [Vec<(u32, u32)>],
    limit: u32,
    robot_pot: Vec<i64>,
    goal_pot: Vec<i64>,
    reach: Vec<i64>,
    from: Vec<u32>,
    settled: Vec<bool>,
    touched: Vec<u32>,
    heap: BinaryHeap<Reverse<(i64, u32)>>,
}

impl Augment<'_> {
    /// Forgets the last search's distances.
    fn reset(&mut self) {
        for &g in &self.touched {
            self.reach[g as usize] = i64::MAX;
            self.settled[g as usize] = false;
        }
        self.touched.clear();
        self.heap.clear();
    }

    /// Offers robot `a`'s goals within the limit, robot `a` being `base` away from the start.
    fn relax(&mut self, a: usize, base: i64) {
        for &(d, g) in self.options[a]
            .iter()
            .take_while(|&&(d, _)| d <= self.limit)
        {
            let gi = g as usize;
            if self.settled[gi] {
                continue;
            }
            let cost = base + i64::from(d) + self.robot_pot[a] - self.goal_pot[gi];
            if cost < self.reach[gi] {
                if self.reach[gi] == i64::MAX {
                    self.touched.push(g);
                }
                self.reach[gi] = cost;
                self.from[gi] = a as u32;
                self.heap.push(Reverse((cost, g)));
            }
        }
    }
}

/// A maximum matching of robots to goals using pairs no longer than `limit` (Kuhn's augmenting
/// paths, iterative; each robot tries its nearest goals first).
fn matching(options: &[Vec<(u32, u32)>], goals: usize, limit: u32) -> Vec<Option<usize>> {
    let n = options.len();
    let mut goal_of = vec![NIL; n];
    let mut robot_of = vec![NIL; goals];
    let mut seen = vec![0u32; goals];
    let mut stamp = 0u32;
    // Greedy start: each robot takes its nearest free goal within the limit.
    for (r, opts) in options.iter().enumerate() {
        if let Some(&(_, g)) = opts
            .iter()
            .take_while(|&&(d, _)| d <= limit)
            .find(|&&(_, g)| robot_of[g as usize] == NIL)
        {
            goal_of[r] = g;
            robot_of[g as usize] = r as u32;
        }
    }
    for r in 0..n {
        if goal_of[r] != NIL {
            continue;
        }
        stamp += 1;
        // Depth-first search for an augmenting path, with an explicit stack of (robot, next option).
        let mut stack: Vec<(u32, usize)> = vec![(r as u32, 0)];
        let mut via: Vec<u32> = Vec::new();
        let mut found = false;
        while let Some(&(a, start)) = stack.last() {
            let opts = &options[a as usize];
            let mut k = start;
            let mut next = None;
            while k < opts.len() && opts[k].0 <= limit {
                let g = opts[k].1;
                k += 1;
                if seen[g as usize] != stamp {
                    seen[g as usize] = stamp;
                    next = Some(g);
                    break;
                }
            }
            stack.last_mut().expect("non-empty").1 = k;
            match next {
                Some(g) => {
                    via.push(g);
                    let owner = robot_of[g as usize];
                    if owner == NIL {
                        found = true;
                        break;
                    }
                    stack.push((owner, 0));
                }
                None => {
                    stack.pop();
                    via.pop();
                }
            }
        }
        if found {
            for (&(a, _), &g) in stack.iter().zip(&via) {
                goal_of[a as usize] = g;
                robot_of[g as usize] = a;
            }
        }
    }
    goal_of
        .into_iter()
        .map(|g| (g != NIL).then_some(g as usize))
        .collect()
}

/// Runs TSWAP from `starts` towards the goal cells `goal_cells`, with `dist[g]` the step
/// distances to goal g and `initial[r]` robot r's first goal index. Stops after `max_steps`.
pub fn tswap(
    graph: &MoveGraph,
    dist: &[Vec<u32>],
    goal_cells: &[u32],
    starts: &[u32],
    initial: &[usize],
    max_steps: u32,
    budget: &Budget,
) -> TswapEnd {
    let n = starts.len();
    let mut goal: Vec<usize> = initial.to_vec();
    let mut at: Vec<u32> = starts.to_vec();
    let mut occupant = vec![NIL; graph.cells()];
    for (r, &c) in at.iter().enumerate() {
        occupant[c as usize] = r as u32;
    }
    let mut paths: Vec<Vec<u32>> = starts.iter().map(|&s| vec![s]).collect();
    let mut came_from = vec![NIL; n];
    let mut moved = vec![false; n];
    let mut mark = vec![0u32; n];
    let mut stamp = 0u32;
    for r in 0..n {
        if dist[goal[r]][at[r] as usize] == NIL {
            return TswapEnd::Unreachable { robot: r };
        }
    }
    for step in 0..max_steps {
        if (0..n).all(|r| at[r] == goal_cells[goal[r]]) {
            break;
        }
        if step % 16 == 0 && budget.out_of_time() {
            return TswapEnd::Budget;
        }
        moved.fill(false);
        came_from.fill(NIL);
        // First pass: exchanges, rotations and moves; later passes: moves into cells freed meanwhile.
        let mut first = true;
        loop {
            let mut any = false;
            for r in 0..n {
                if moved[r] || at[r] == goal_cells[goal[r]] {
                    continue;
                }
                let u = toward(graph, &dist[goal[r]], at[r], &occupant);
                let j = occupant[u as usize];
                if j == NIL {
                    if crosses(graph, &occupant, &came_from, at[r], u) {
                        continue;
                    }
                    occupant[at[r] as usize] = NIL;
                    occupant[u as usize] = r as u32;
                    came_from[r] = at[r];
                    at[r] = u;
                    moved[r] = true;
                    any = true;
                    continue;
                }
                if !first {
                    continue;
                }
                let j = j as usize;
                if !moved[j] && at[j] == goal_cells[goal[j]] {
                    goal.swap(r, j);
                    continue;
                }
                stamp += 1;
                if let Some(cycle) = deadlock(
                    graph,
                    dist,
                    goal_cells,
                    &goal,
                    &at,
                    &occupant,
                    &moved,
                    r,
                    (&mut mark, stamp),
                ) {
                    // cycle[k] wants the cell of cycle[k + 1]: cycle[k + 1] takes cycle[k]'s goal.
                    let taken: Vec<usize> = cycle.iter().map(|&a| goal[a]).collect();
                    for k in 0..cycle.len() {
                        goal[cycle[(k + 1) % cycle.len()]] = taken[k];
                    }
                }
            }
            first = false;
            if !any {
                break;
            }
        }
        for r in 0..n {
            paths[r].push(at[r]);
        }
    }
    if !(0..n).all(|r| at[r] == goal_cells[goal[r]]) {
        return TswapEnd::Budget;
    }
    for (r, p) in paths.iter_mut().enumerate() {
        let g = goal_cells[goal[r]];
        let arrive = p.iter().rposition(|&c| c != g).map_or(0, |t| t + 1);
        p.truncate(arrive + 1);
    }
    TswapEnd::Found { goals: goal, paths }
}

/// The next cell on a shortest path to the goal; among equals, a free one, then the first.
#[inline]
fn toward(graph: &MoveGraph, dist: &[u32], v: u32, occupant: &[u32]) -> u32 {
    let mut best = (u32::MAX, true, v);
    for &u in graph.neighbours(v) {
        let key = (dist[u as usize], occupant[u as usize] != NIL, u);
        if (key.0, key.1) < (best.0, best.1) {
            best = key;
        }
    }
    best.2
}

/// Whether the diagonal move `a → b` would cross a move made earlier in this step.
#[inline]
fn crosses(graph: &MoveGraph, occupant: &[u32], came_from: &[u32], a: u32, b: u32) -> bool {
    let Some((c, d)) = graph.corners(a, b) else {
        return false;
    };
    [(c, d), (d, c)].iter().any(|&(x, y)| {
        let k = occupant[y as usize];
        k != NIL && came_from[k as usize] == x
    })
}

/// The cycle of robots, starting at `r`, each wanting the next one's cell, if there is one.
#[allow(clippy::too_many_arguments)]
fn deadlock(
    graph: &MoveGraph,
    dist: &[Vec<u32>],
    goal_cells: &[u32],
    goal: &[usize],
    at: &[u32],
    occupant: &[u32],
    moved: &[bool],
    r: usize,
    (mark, stamp): (&mut [u32], u32),
) -> Option<Vec<usize>> {
    let mut cycle = vec![r];
    mark[r] = stamp;
    let mut a = r;
    loop {
        let u = toward(graph, &dist[goal[a]], at[a], occupant);
        let b = occupant[u as usize];
        if b == NIL {
            return None;
        }
        let b = b as usize;
        if b == r {
            return (cycle.len() > 1).then_some(cycle);
        }
        if mark[b] == stamp || moved[b] || at[b] == goal_cells[goal[b]] {
            return None;
        }
        mark[b] = stamp;
        cycle.push(b);
        a = b;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::hungarian::hungarian;
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    /// Random distance tables (some pairs unreachable): the assignment is as short in its
    /// longest pair as any complete one, and as short in sum as the Hungarian method finds
    /// among pairs within that longest distance.
    #[test]
    fn the_assignment_is_bottleneck_then_least_sum() {
        let mut rng = ChaCha8Rng::seed_from_u64(7);
        for case in 0..300 {
            let n = rng.gen_range(1..8);
            let m = n + rng.gen_range(0..3);
            // dist[g][robot cell]: robot r stands on cell r.
            let dist: Vec<Vec<u32>> = (0..m)
                .map(|_| {
                    (0..n)
                        .map(|_| {
                            if rng.gen_bool(0.1) {
                                NIL
                            } else {
                                rng.gen_range(0..12)
                            }
                        })
                        .collect()
                })
                .collect();
            let starts: Vec<u32> = (0..n as u32).collect();
            let got = bottleneck_assignment(&dist, &starts);
            // The best longest pair and the best sum under it, by brute force over all
            // injective pairings.
            let mut best: Option<(u32, u32)> = None;
            let mut pick = vec![0usize; n];
            fn walk(
                r: usize,
                used: &mut Vec<bool>,
                pick: &mut Vec<usize>,
                dist: &[Vec<u32>],
                best: &mut Option<(u32, u32)>,
            ) {
                if r == pick.len() {
                    let ds: Vec<u32> = pick.iter().enumerate().map(|(r, &g)| dist[g][r]).collect();
                    let key = (*ds.iter().max().unwrap(), ds.iter().sum());
                    if best.is_none_or(|b| key < b) {
                        *best = Some(key);
                    }
                    return;
                }
                for g in 0..used.len() {
                    if !used[g] && dist[g][r] != NIL {
                        used[g] = true;
                        pick[r] = g;
                        walk(r + 1, used, pick, dist, best);
                        used[g] = false;
                    }
                }
            }
            walk(0, &mut vec![false; m], &mut pick, &dist, &mut best);
            match best {
                None => assert!(got.iter().any(Option::is_none), "case {case}"),
                Some((longest, sum)) => {
                    let goals: Vec<usize> = got.iter().map(|g| g.expect("complete")).collect();
                    let mut seen = goals.clone();
                    seen.sort_unstable();
                    seen.dedup();
                    assert_eq!(seen.len(), n, "case {case}: a goal taken twice");
                    let ds: Vec<u32> = goals.iter().enumerate().map(|(r, &g)| dist[g][r]).collect();
                    assert_eq!(*ds.iter().max().unwrap(), longest, "case {case}");
                    assert_eq!(ds.iter().sum::<u32>(), sum, "case {case}");
                    // The Hungarian method agrees on the sum within the longest distance.
                    let cost: Vec<Vec<f64>> = (0..n)
                        .map(|r| {
                            (0..m)
                                .map(|g| match dist[g][r] {
                                    d if d != NIL && d <= longest => f64::from(d),
                                    _ => 1e6,
                                })
                                .collect()
                        })
                        .collect();
                    let h = hungarian(&cost);
                    let hs: f64 = h.iter().enumerate().map(|(r, &g)| cost[r][g]).sum();
                    assert_eq!(hs, f64::from(sum), "case {case}");
                }
            }
        }
    }
}
