//! Maximum-weight closure by minimum cut (Picard 1976), with Dinic's max-flow.
//!
//! A closure of a DAG is a set of nodes that contains every successor of each of its nodes
//! (here: every support of each brick). The heaviest closure is the source side of a minimum
//! s–t cut in the network s→v (weight > 0), v→t (−weight), v→w (∞ for each required w).
//! Dinic's algorithm takes O(V²E) in the worst case and far less on walls.

const INF: f64 = f64::INFINITY;
/// Capacities and weights at or below this are taken as zero.
pub(crate) const EPS: f64 = 1e-9;

struct Edge {
    to: usize,
    cap: f64,
}

/// A flow network with residual capacities; edge `e` and `e ^ 1` are each other's reverse.
struct Network {
    edges: Vec<Edge>,
    out: Vec<Vec<usize>>,
    level: Vec<i32>,
    next: Vec<usize>,
    /// Edges looked at so far (the work done).
    scans: u64,
}

impl Network {
    fn new(nodes: usize) -> Self {
        Network {
            edges: Vec::new(),
            out: vec![Vec::new(); nodes],
            level: vec![0; nodes],
            next: vec![0; nodes],
            scans: 0,
        }
    }

    fn add(&mut self, from: usize, to: usize, cap: f64) {
        self.out[from].push(self.edges.len());
        self.edges.push(Edge { to, cap });
        self.out[to].push(self.edges.len());
        self.edges.push(Edge { to: from, cap: 0.0 });
    }

    fn levels(&mut self, s: usize, t: usize) -> bool {
        self.level.fill(-1);
        self.level[s] = 0;
        let mut queue = std::collections::VecDeque::from([s]);
        while let Some(v) = queue.pop_front() {
            self.scans += self.out[v].len() as u64;
            for &e in &self.out[v] {
                let w = self.edges[e].to;
                if self.edges[e].cap > EPS && self.level[w] < 0 {
                    self.level[w] = self.level[v] + 1;
                    queue.push_back(w);
                }
            }
        }
        self.level[t] >= 0
    }

    /// One augmenting path in the level graph, found iteratively; returns the flow pushed.
    fn augment(&mut self, s: usize, t: usize) -> f64 {
        let mut path: Vec<usize> = Vec::new();
        let mut v = s;
        loop {
            if v == t {
                let f = path.iter().map(|&e| self.edges[e].cap).fold(INF, f64::min);
                for &e in &path {
                    self.edges[e].cap -= f;
                    self.edges[e ^ 1].cap += f;
                }
                return f;
            }
            let mut advanced = false;
            while self.next[v] < self.out[v].len() {
                self.scans += 1;
                let e = self.out[v][self.next[v]];
                let w = self.edges[e].to;
                if self.edges[e].cap > EPS && self.level[w] == self.level[v] + 1 {
                    path.push(e);
                    v = w;
                    advanced = true;
                    break;
                }
                self.next[v] += 1;
            }
            if !advanced {
                if v == s {
                    return 0.0;
                }
                // Dead end: retreat and skip the edge that led here.
                self.level[v] = -1;
                let e = path.pop().expect("not at the source");
                v = self.edges[e ^ 1].to;
                self.next[v] += 1;
            }
        }
    }

    /// Dinic's phases until no augmenting path is left (true), or until `stop` says so,
    /// looked at every 1024 augmentations (false: the flow is not maximal).
    fn max_flow(&mut self, s: usize, t: usize, stop: &dyn Fn() -> bool) -> bool {
        let mut paths = 0u64;
        while self.levels(s, t) {
            if stop() {
                return false;
            }
            self.next.fill(0);
            while self.augment(s, t) > EPS {
                paths += 1;
                if paths % 1024 == 0 && stop() {
                    return false;
                }
            }
        }
        true
    }
}

/// The heaviest closure: `weight[v]` per node, `requires[v]` the nodes `v` needs. Returns a
/// membership flag per node (nodes of weight ≤ 0 with nothing above them stay out), or `None`
/// when `stop` says so before the flow is maximal.
pub fn max_weight_closure_until(
    weight: &[f64],
    requires: &[Vec<usize>],
    stop: &dyn Fn() -> bool,
) -> Option<Vec<bool>> {
    max_weight_closure_counted(weight, requires, stop).0
}

/// [`max_weight_closure_until`], with the work it did: the edges it looked at, a measure of
/// time that does not depend on the clock.
pub fn max_weight_closure_counted(
    weight: &[f64],
    requires: &[Vec<usize>],
    stop: &dyn Fn() -> bool,
) -> (Option<Vec<bool>>, u64) {
    let n = weight.len();
    let (s, t) = (n, n + 1);
    let mut net = Network::new(n + 2);
    for v in 0..n {
        if weight[v] > EPS {
            net.add(s, v, weight[v]);
        } else if weight[v] < -EPS {
            net.add(v, t, -weight[v]);
        }
        for &w in &requires[v] {
            net.add(v, w, INF);
        }
    }
    if !net.max_flow(s, t, stop) {
        return (None, net.scans);
    }
    // The closure: nodes still reachable from s in the residual network.
    let mut inside = vec![false; n + 2];
    inside[s] = true;
    let mut stack = vec![s];
    while let Some(v) = stack.pop() {
        for &e in &net.out[v] {
            let w = net.edges[e].to;
            if net.edges[e].cap > EPS && !inside[w] {
                inside[w] = true;
                stack.push(w);
            }
        }
    }
    inside.truncate(n);
    (Some(inside), net.scans + net.edges.len() as u64)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn max_weight_closure(weight: &[f64], requires: &[Vec<usize>]) -> Vec<bool> {
        max_weight_closure_until(weight, requires, &|| false).expect("no stop")
    }

    /// Every subset of a small DAG, closed ones only, heaviest by enumeration.
    fn brute(weight: &[f64], requires: &[Vec<usize>]) -> f64 {
        let n = weight.len();
        (0u32..1 << n)
            .filter(|m| {
                (0..n).all(|v| m & (1 << v) == 0 || requires[v].iter().all(|&w| m & (1 << w) != 0))
            })
            .map(|m| {
                (0..n)
                    .filter(|v| m & (1 << v) != 0)
                    .map(|v| weight[v])
                    .sum::<f64>()
            })
            .fold(0.0, f64::max)
    }

    #[test]
    fn matches_enumeration_on_small_dags() {
        use rand::{Rng, SeedableRng};
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(3);
        for _ in 0..300 {
            let n = rng.gen_range(1..10);
            let weight: Vec<f64> = (0..n).map(|_| f64::from(rng.gen_range(-6i32..7))).collect();
            let requires: Vec<Vec<usize>> = (0..n)
                .map(|v| (0..v).filter(|_| rng.gen_bool(0.3)).collect())
                .collect();
            let set = max_weight_closure(&weight, &requires);
            for v in 0..n {
                if set[v] {
                    assert!(requires[v].iter().all(|&w| set[w]), "not closed");
                }
            }
            let got: f64 = (0..n).filter(|&v| set[v]).map(|v| weight[v]).sum();
            assert!((got - brute(&weight, &requires)).abs() < 1e-9);
        }
    }
}
