//! `exact`: provably optimal build orders for the thesis cost model, in linear time on every
//! wall whose neighbour graph is a forest.
//!
//! **Why it is exact.** A brick's cost depends only on its level, its type, and how many of its
//! neighbours are already placed. Neighbours always share a level, and building level by level
//! always respects precedence (a support is always one level down). So any relative order of the
//! bricks *within* each level can be realised, and the total cost is the sum, over the
//! connected components of the neighbour graph, of a cost that depends only on which end of
//! each neighbour edge is placed first — an acyclic orientation of the component.
//!
//! * A component that is a tree (every layer-text wall: each layer is a chain) is solved by
//!   dynamic programming over the tree: O(size), for any κ, even non-monotone.
//! * A component with cycles (possible in 3-D CMCP walls) of at most
//!   [`SUBSET_DP_LIMIT`] bricks is solved by dynamic programming over subsets: O(2^c·c).
//! * A larger cyclic component is ordered by greedy within it, and the plan is reported as
//!   `Feasible`, not `Optimal`.
//!
//! The plan lists level 1 first; within a level, components follow their smallest label, and a
//! component's bricks follow its chosen orientation, smallest label first among ties.

use crate::outcome::{Budget, Outcome, Stats, Status};
use crate::problem::BuildProblem;
use mason_wall::{BrickId, Wall};
use std::collections::BTreeMap;
use std::time::Instant;

/// Largest cyclic component solved exactly by subset dynamic programming.
pub const SUBSET_DP_LIMIT: usize = 20;

/// Runs the exact planner. The budget is accepted for a uniform interface; the planner is
/// polynomial except on cyclic components, which are capped at [`SUBSET_DP_LIMIT`] bricks.
pub fn plan(problem: &BuildProblem<'_>, _budget: &Budget) -> Outcome {
    let start = Instant::now();
    let wall = problem.wall();
    let mut proven = true;
    let mut stats = Stats::default();
    // Components, grouped by level, in order of their smallest label.
    let mut by_level: BTreeMap<(u32, u32), Vec<BrickId>> = BTreeMap::new();
    for comp in components(wall) {
        let b0 = comp[0];
        let key = (
            wall.brick(b0).level,
            comp.iter().map(|&b| wall.brick(b).label).min().unwrap_or(0),
        );
        by_level.insert(key, comp);
    }
    let mut order = Vec::with_capacity(problem.len());
    for comp in by_level.values() {
        let edges: usize = comp
            .iter()
            .map(|&b| wall.neighbours(b).len())
            .sum::<usize>()
            / 2;
        stats.nodes += comp.len() as u64;
        let part = if edges + 1 == comp.len() {
            tree_order(problem, comp)
        } else if comp.len() <= SUBSET_DP_LIMIT {
            subset_order(problem, comp)
        } else {
            proven = false;
            greedy_order(problem, comp)
        };
        order.extend(part);
    }
    stats.leaves = 1;
    stats.elapsed = start.elapsed();
    let total = problem.order_cost(&order);
    Outcome {
        planner: "exact".into(),
        status: if proven {
            Status::Optimal
        } else {
            Status::Feasible
        },
        order: Some(order),
        total_cost: Some(total),
        stats,
    }
}

/// Connected components of the neighbour graph, each sorted by index.
fn components(wall: &Wall) -> Vec<Vec<BrickId>> {
    let mut seen = vec![false; wall.len()];
    let mut out = Vec::new();
    for root in wall.ids() {
        if seen[root.index()] {
            continue;
        }
        seen[root.index()] = true;
        let mut comp = vec![root];
        let mut i = 0;
        while i < comp.len() {
            for &n in wall.neighbours(comp[i]) {
                if !seen[n.index()] {
                    seen[n.index()] = true;
                    comp.push(n);
                }
            }
            i += 1;
        }
        comp.sort_unstable();
        out.push(comp);
    }
    out
}

/// Topological order of a component given "a before b" decisions, smallest label first.
fn orient_to_order(wall: &Wall, comp: &[BrickId], before: &[(BrickId, BrickId)]) -> Vec<BrickId> {
    let local: BTreeMap<BrickId, usize> = comp.iter().enumerate().map(|(i, &b)| (b, i)).collect();
    let mut indeg = vec![0usize; comp.len()];
    let mut out_edges = vec![Vec::new(); comp.len()];
    for &(a, b) in before {
        out_edges[local[&a]].push(local[&b]);
        indeg[local[&b]] += 1;
    }
    let mut ready: std::collections::BinaryHeap<std::cmp::Reverse<(u32, usize)>> = comp
        .iter()
        .enumerate()
        .filter(|(i, _)| indeg[*i] == 0)
        .map(|(i, &b)| std::cmp::Reverse((wall.brick(b).label, i)))
        .collect();
    let mut order = Vec::with_capacity(comp.len());
    while let Some(std::cmp::Reverse((_, i))) = ready.pop() {
        order.push(comp[i]);
        for &j in &out_edges[i] {
            indeg[j] -= 1;
            if indeg[j] == 0 {
                ready.push(std::cmp::Reverse((wall.brick(comp[j]).label, j)));
            }
        }
    }
    order
}

/// Tree DP. `best[v][o]`: least cost of v's subtree when o = 1 if v's parent is placed before
/// v (and so counts as a placed neighbour of v), 0 otherwise.
fn tree_order(problem: &BuildProblem<'_>, comp: &[BrickId]) -> Vec<BrickId> {
    let wall = problem.wall();
    let root = comp[0];
    // Iterative DFS for a parent array and a pre-order.
    let mut parent: BTreeMap<BrickId, Option<BrickId>> = BTreeMap::new();
    let mut pre = Vec::with_capacity(comp.len());
    let mut stack = vec![(root, None)];
    while let Some((v, p)) = stack.pop() {
        parent.insert(v, p);
        pre.push(v);
        for &n in wall.neighbours(v).iter().rev() {
            if Some(n) != p {
                stack.push((n, Some(v)));
            }
        }
    }
    let children = |v: BrickId| {
        let p = parent[&v];
        wall.neighbours(v)
            .iter()
            .copied()
            .filter(move |&n| Some(n) != p)
    };
    // For each node: best[o], the chosen count state per o, and per child the choice table
    // choice[state_after] = (state_before, child_first).
    struct Node {
        best: [f64; 2],
        state: [usize; 2],
        steps: Vec<[(usize, bool); 3]>,
    }
    let mut table: BTreeMap<BrickId, Node> = BTreeMap::new();
    for &v in pre.iter().rev() {
        let mut g = [0.0, f64::INFINITY, f64::INFINITY];
        let mut steps = Vec::new();
        for c in children(v) {
            let fc = table[&c].best;
            let mut next = [f64::INFINITY; 3];
            let mut choice = [(0usize, false); 3];
            for j in 0..3 {
                if !g[j].is_finite() {
                    continue;
                }
                // The child first: v gains a placed neighbour; the child does not see v.
                let up = (j + 1).min(2);
                if g[j] + fc[0] < next[up] {
                    next[up] = g[j] + fc[0];
                    choice[up] = (j, true);
                }
                // v first: the child sees v as placed.
                if g[j] + fc[1] < next[j] {
                    next[j] = g[j] + fc[1];
                    choice[j] = (j, false);
                }
            }
            g = next;
            steps.push(choice);
        }
        let mut best = [f64::INFINITY; 2];
        let mut state = [0; 2];
        for o in 0..2 {
            for (j, &gj) in g.iter().enumerate() {
                let total = gj + problem.cost(v, o + j);
                if total < best[o] {
                    best[o] = total;
                    state[o] = j;
                }
            }
        }
        table.insert(v, Node { best, state, steps });
    }
    // Reconstruct: walk down from the root with its parent-orientation o.
    let mut before = Vec::with_capacity(comp.len());
    let mut todo = vec![(root, 0usize)];
    while let Some((v, o)) = todo.pop() {
        let node = &table[&v];
        let mut j = node.state[o];
        let kids: Vec<BrickId> = children(v).collect();
        for (c, choice) in kids.iter().zip(&node.steps).rev() {
            let (prev, child_first) = choice[j];
            if child_first {
                before.push((*c, v));
                todo.push((*c, 0));
            } else {
                before.push((v, *c));
                todo.push((*c, 1));
            }
            j = prev;
        }
    }
    orient_to_order(wall, comp, &before)
}

/// Subset DP over placement order for a small component with cycles.
fn subset_order(problem: &BuildProblem<'_>, comp: &[BrickId]) -> Vec<BrickId> {
    let wall = problem.wall();
    let c = comp.len();
    let local: BTreeMap<BrickId, usize> = comp.iter().enumerate().map(|(i, &b)| (b, i)).collect();
    let nb_mask: Vec<u32> = comp
        .iter()
        .map(|&b| {
            wall.neighbours(b)
                .iter()
                .fold(0u32, |m, n| m | 1 << local[n])
        })
        .collect();
    let full = (1usize << c) - 1;
    let mut best = vec![f64::INFINITY; full + 1];
    let mut last = vec![u8::MAX; full + 1];
    best[0] = 0.0;
    for mask in 0..full {
        if !best[mask].is_finite() {
            continue;
        }
        for (i, &nb) in nb_mask.iter().enumerate() {
            if mask & (1 << i) != 0 {
                continue;
            }
            let k = (nb & mask as u32).count_ones() as usize;
            let next = mask | (1 << i);
            let total = best[mask] + problem.cost(comp[i], k);
            if total < best[next] {
                best[next] = total;
                last[next] = i as u8;
            }
        }
    }
    let mut order = Vec::with_capacity(c);
    let mut mask = full;
    while mask != 0 {
        let i = last[mask] as usize;
        order.push(comp[i]);
        mask &= !(1 << i);
    }
    order.reverse();
    order
}

/// Greedy inside one large cyclic component (not proven optimal).
fn greedy_order(problem: &BuildProblem<'_>, comp: &[BrickId]) -> Vec<BrickId> {
    let wall = problem.wall();
    let mut placed: BTreeMap<BrickId, bool> = comp.iter().map(|&b| (b, false)).collect();
    let mut order = Vec::with_capacity(comp.len());
    for _ in 0..comp.len() {
        let next = comp
            .iter()
            .filter(|b| !placed[b])
            .map(|&b| {
                let k = wall.neighbours(b).iter().filter(|n| placed[n]).count();
                (problem.cost(b, k), wall.brick(b).label, b)
            })
            .min_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)))
            .map(|x| x.2)
            .expect("component has unplaced bricks");
        placed.insert(next, true);
        order.push(next);
    }
    order
}
