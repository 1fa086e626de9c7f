//! Conflict-based search (CBS; Sharon, Stern, Felner, Sturtevant, AIJ 2015): optimal sum of
//! costs for a few labelled robots. It is the yardstick the tests hold the scalable solvers to.
//!
//! The high level is a best-first search over sets of constraints, cheapest plan first. Each
//! node plans every robot alone (space-time A* under that robot's constraints) and looks for
//! the first conflict `crew::validate` would report: two robots on one cell, a swap along an
//! edge, or crossing diagonals in one 2×2 square. It branches on forbidding that cell or move
//! to one robot or the other. Every plan without conflicts is optimal when the low level is,
//! because each branch keeps all optimal plans on one side or the other.
//!
//! The low level is exact: states (cell, step), waits allowed, the true step distance as
//! heuristic; a robot may stop on its goal only after its last constraint there. Exponential in
//! the number of conflicts; use it for about ten robots on small maps, with a node cap.

use crate::moves::{MoveGraph, NIL};
use rustc_hash::FxHashSet;
use std::cmp::Reverse;
use std::collections::BinaryHeap;

/// Something one robot may not do.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
enum Constraint {
    /// Stand on `cell` at step `t`.
    Vertex { cell: u32, t: u32 },
    /// Move `from → to` between steps `t` and `t + 1`.
    Move { from: u32, to: u32, t: u32 },
}

/// How a CBS search ended.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum CbsEnd {
    /// An optimal plan (paths cut at each robot's last arrival) and its sum of costs.
    Optimal(Vec<Vec<u32>>, u64),
    /// The constraint tree ran empty: no plan exists (or a robot cannot reach its goal).
    Infeasible,
    /// The node cap came first.
    NodeLimit,
}

struct Node {
    constraints: Vec<(u32, Constraint)>,
    paths: Vec<Vec<u32>>,
}

/// An optimal plan from `starts` to `goals`, with `dist[i]` robot i's step distances to its
/// goal, expanding at most `node_limit` constraint-tree nodes.
pub fn cbs(
    graph: &MoveGraph,
    dist: &[Vec<u32>],
    starts: &[u32],
    goals: &[u32],
    node_limit: u64,
) -> CbsEnd {
    let n = starts.len();
    let mut paths = Vec::with_capacity(n);
    for i in 0..n {
        match low_level(graph, &dist[i], starts[i], goals[i], &[]) {
            Some(p) => paths.push(p),
            None => return CbsEnd::Infeasible,
        }
    }
    let mut nodes = vec![Node {
        constraints: Vec::new(),
        paths,
    }];
    let mut open = BinaryHeap::from([(Reverse(cost(&nodes[0].paths)), Reverse(0u32))]);
    let mut expanded = 0;
    while let Some((Reverse(c), Reverse(id))) = open.pop() {
        expanded += 1;
        if expanded > node_limit {
            return CbsEnd::NodeLimit;
        }
        let Some((a, ca, b, cb)) = first_conflict(graph, &nodes[id as usize].paths) else {
            let paths = std::mem::take(&mut nodes[id as usize].paths);
            return CbsEnd::Optimal(paths, c);
        };
        for (robot, constraint) in [(a, ca), (b, cb)] {
            let parent = &nodes[id as usize];
            let mut constraints = parent.constraints.clone();
            constraints.push((robot, constraint));
            let mine: Vec<Constraint> = constraints
                .iter()
                .filter(|&&(r, _)| r == robot)
                .map(|&(_, k)| k)
                .collect();
            let r = robot as usize;
            let Some(p) = low_level(graph, &dist[r], starts[r], goals[r], &mine) else {
                continue;
            };
            let mut paths = parent.paths.clone();
            paths[r] = p;
            let child = nodes.len() as u32;
            open.push((Reverse(cost(&paths)), Reverse(child)));
            nodes.push(Node { constraints, paths });
        }
    }
    CbsEnd::Infeasible
}

/// Σ of each path's last arrival on its final cell (the sum of costs `crew::validate` counts).
fn cost(paths: &[Vec<u32>]) -> u64 {
    paths
        .iter()
        .map(|p| {
            let g = p[p.len() - 1];
            p.iter().rposition(|&c| c != g).map_or(0, |t| t as u64 + 1)
        })
        .sum()
}

#[inline]
fn at(p: &[u32], t: usize) -> u32 {
    p[t.min(p.len() - 1)]
}

/// The first conflict in step order, as the constraint each of its two robots would get.
fn first_conflict(
    graph: &MoveGraph,
    paths: &[Vec<u32>],
) -> Option<(u32, Constraint, u32, Constraint)> {
    let end = paths.iter().map(Vec::len).max().unwrap_or(1);
    for t in 0..end {
        for i in 0..paths.len() {
            for j in i + 1..paths.len() {
                let (pi, pj) = (&paths[i], &paths[j]);
                if at(pi, t) == at(pj, t) {
                    let k = Constraint::Vertex {
                        cell: at(pi, t),
                        t: t as u32,
                    };
                    return Some((i as u32, k, j as u32, k));
                }
                if t + 1 >= end {
                    continue;
                }
                let (a, b) = (at(pi, t), at(pi, t + 1));
                let (c, d) = (at(pj, t), at(pj, t + 1));
                if a == b || c == d {
                    continue;
                }
                let crossing = graph
                    .corners(a, b)
                    .is_some_and(|(x, y)| (c, d) == (x, y) || (c, d) == (y, x));
                if (a == d && b == c) || crossing {
                    let t = t as u32;
                    return Some((
                        i as u32,
                        Constraint::Move { from: a, to: b, t },
                        j as u32,
                        Constraint::Move { from: c, to: d, t },
                    ));
                }
            }
        }
    }
    None
}

/// Space-time A* for one robot under its constraints; the path ends at its arrival.
///
/// Kept apart from the shared search in [`crate::spacetime`] on purpose: CBS is the oracle the
/// tests hold `st`, `refine` and LaCAM to, so a fault in that search must not reach it too.
fn low_level(
    graph: &MoveGraph,
    dist: &[u32],
    start: u32,
    goal: u32,
    constraints: &[Constraint],
) -> Option<Vec<u32>> {
    if dist[start as usize] == NIL {
        return None;
    }
    let vertex: FxHashSet<(u32, u32)> = constraints
        .iter()
        .filter_map(|k| match *k {
            Constraint::Vertex { cell, t } => Some((cell, t)),
            Constraint::Move { .. } => None,
        })
        .collect();
    let moves: FxHashSet<(u32, u32, u32)> = constraints
        .iter()
        .filter_map(|k| match *k {
            Constraint::Move { from, to, t } => Some((from, to, t)),
            Constraint::Vertex { .. } => None,
        })
        .collect();
    let last = constraints
        .iter()
        .map(|k| match *k {
            Constraint::Vertex { t, .. } | Constraint::Move { t, .. } => t + 1,
        })
        .max()
        .unwrap_or(0);
    let settle = vertex
        .iter()
        .filter(|&&(c, _)| c == goal)
        .map(|&(_, t)| t + 1)
        .max()
        .unwrap_or(0);
    let mut nodes: Vec<(u32, u32, u32)> = vec![(start, 0, NIL)];
    let mut closed: FxHashSet<(u32, u32)> = FxHashSet::default();
    let mut open = BinaryHeap::from([(
        Reverse(dist[start as usize].max(settle)),
        0u32,
        Reverse(0u32),
    )]);
    while let Some((_, t, Reverse(id))) = open.pop() {
        let cell = nodes[id as usize].0;
        if !closed.insert((cell, t.min(last))) {
            continue;
        }
        if cell == goal && t >= settle {
            let mut path = Vec::new();
            let mut x = id;
            while x != NIL {
                path.push(nodes[x as usize].0);
                x = nodes[x as usize].2;
            }
            path.reverse();
            return Some(path);
        }
        for &next in std::iter::once(&cell).chain(graph.neighbours(cell)) {
            let h = dist[next as usize];
            if h == NIL
                || vertex.contains(&(next, t + 1))
                || (next != cell && moves.contains(&(cell, next, t)))
                || closed.contains(&(next, (t + 1).min(last)))
            {
                continue;
            }
            let nid = nodes.len() as u32;
            nodes.push((next, t + 1, id));
            open.push((Reverse((t + 1 + h).max(settle)), t + 1, Reverse(nid)));
        }
    }
    None
}
