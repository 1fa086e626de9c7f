//! Incremental search state shared by the tree searches: what is placed, what is available,
//! and how many neighbours of each brick are down. `place` and `undo` are O(degree).

use crate::problem::BuildProblem;
use mason_wall::BrickId;

pub(crate) struct Frontier<'p, 'w> {
    problem: &'p BuildProblem<'w>,
    missing: Vec<u32>,
    placed_neighbours: Vec<u32>,
    /// Bricks whose supports are all placed and which are not placed yet.
    available: Vec<BrickId>,
}

impl<'p, 'w> Frontier<'p, 'w> {
    pub(crate) fn new(problem: &'p BuildProblem<'w>) -> Self {
        let wall = problem.wall();
        let missing: Vec<u32> = wall.ids().map(|b| wall.supports(b).len() as u32).collect();
        let available = wall.ids().filter(|b| missing[b.index()] == 0).collect();
        Frontier {
            problem,
            placed_neighbours: vec![0; missing.len()],
            missing,
            available,
        }
    }

    pub(crate) fn available(&self) -> &[BrickId] {
        &self.available
    }

    /// The cost of placing `b` now.
    pub(crate) fn cost_now(&self, b: BrickId) -> f64 {
        self.problem
            .cost(b, self.placed_neighbours[b.index()] as usize)
    }

    /// Places an available brick; returns its cost.
    pub(crate) fn place(&mut self, b: BrickId) -> f64 {
        let cost = self.cost_now(b);
        let wall = self.problem.wall();
        let at = self
            .available
            .iter()
            .position(|&x| x == b)
            .expect("placed brick must be available");
        self.available.remove(at);
        for &n in wall.neighbours(b) {
            self.placed_neighbours[n.index()] += 1;
        }
        for &c in wall.carried(b) {
            self.missing[c.index()] -= 1;
            if self.missing[c.index()] == 0 {
                self.available.push(c);
            }
        }
        cost
    }

    /// Undoes `place(b)`; `b` must be the most recently placed brick.
    pub(crate) fn undo(&mut self, b: BrickId) {
        let wall = self.problem.wall();
        for &c in wall.carried(b).iter().rev() {
            if self.missing[c.index()] == 0 {
                let at = self
                    .available
                    .iter()
                    .rposition(|&x| x == c)
                    .expect("carried brick was made available");
                self.available.remove(at);
            }
            self.missing[c.index()] += 1;
        }
        for &n in wall.neighbours(b) {
            self.placed_neighbours[n.index()] -= 1;
        }
        self.available.push(b);
    }

    /// The available bricks sorted by (current cost, label): the thesis tie rule.
    pub(crate) fn ranked(&self) -> Vec<(f64, BrickId)> {
        let wall = self.problem.wall();
        let mut v: Vec<(f64, BrickId)> = self
            .available
            .iter()
            .map(|&b| (self.cost_now(b), b))
            .collect();
        v.sort_by(|a, b| {
            a.0.total_cmp(&b.0)
                .then(wall.brick(a.1).label.cmp(&wall.brick(b.1).label))
        });
        v
    }
}
