//! The build-order problem: a wall and a cost model, with per-brick cost terms precomputed.

use crate::model::{CostModel, ModelError};
use mason_wall::{BrickId, Wall};

/// A wall to order under a cost model.
#[derive(Clone, Debug)]
pub struct BuildProblem<'w> {
    wall: &'w Wall,
    model: CostModel,
    /// `(1 + e^(−αl))·(n_g·t_g + t_f)` per brick.
    fixed: Vec<f64>,
    /// `(1 + e^(−αl))·t_d` per brick.
    drop: Vec<f64>,
}

impl<'w> BuildProblem<'w> {
    /// A problem; fails when the model is invalid.
    pub fn new(wall: &'w Wall, model: CostModel) -> Result<Self, ModelError> {
        model.validate()?;
        let (fixed, drop) = wall
            .bricks()
            .iter()
            .map(|b| {
                let f = model.level_factor(b.level);
                let t = model.times(b.kind);
                (f * (model.grasp_attempts * t.grasp + t.fly), f * t.drop)
            })
            .unzip();
        Ok(BuildProblem {
            wall,
            model,
            fixed,
            drop,
        })
    }

    /// The wall.
    pub fn wall(&self) -> &'w Wall {
        self.wall
    }

    /// The cost model.
    pub fn model(&self) -> &CostModel {
        &self.model
    }

    /// Number of bricks.
    pub fn len(&self) -> usize {
        self.fixed.len()
    }

    /// Always false: walls are never empty.
    pub fn is_empty(&self) -> bool {
        self.fixed.is_empty()
    }

    /// Cost of placing `b` when `placed_neighbours` of its neighbours are already placed.
    pub fn cost(&self, b: BrickId, placed_neighbours: usize) -> f64 {
        let i = b.index();
        self.fixed[i] + self.model.kappa[placed_neighbours.min(2)] * self.drop[i]
    }

    /// Total cost of a complete order (assumed valid; see [`crate::validate`] to check one).
    pub fn order_cost(&self, order: &[BrickId]) -> f64 {
        let mut placed = vec![false; self.len()];
        let mut total = 0.0;
        for &b in order {
            let k = self
                .wall
                .neighbours(b)
                .iter()
                .filter(|n| placed[n.index()])
                .count();
            total += self.cost(b, k);
            placed[b.index()] = true;
        }
        total
    }
}
