//! `order::validate`: checks a build order and recomputes its cost, knowing nothing of the
//! planners. It is the oracle in tests and runs after every plan in the CLI.

use crate::model::CostModel;
use mason_wall::violations::Violations;
use mason_wall::{BrickId, Wall};
use serde::Serialize;
use std::ops::ControlFlow;
use thiserror::Error;

/// One placement of a checked order.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Step {
    /// The brick.
    pub brick: BrickId,
    /// How many of its neighbours were already placed (not capped).
    pub placed_neighbours: u32,
    /// Its cost under the model (κ capped at two neighbours).
    pub cost: f64,
}

/// A checked order with its recomputed costs.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Evaluation {
    /// Every placement in order.
    pub steps: Vec<Step>,
    /// Σ of the step costs.
    pub total_cost: f64,
}

/// Why an order is not a valid build order.
#[derive(Clone, Debug, PartialEq, Error)]
pub enum OrderError {
    /// Wrong number of entries.
    #[error("the order has {found} entries but the wall has {expected} bricks")]
    WrongLength {
        /// Entries.
        found: usize,
        /// Bricks.
        expected: usize,
    },
    /// An index outside the wall.
    #[error("step {step}: brick index {index} is not in the wall")]
    UnknownBrick {
        /// Step (0-based).
        step: usize,
        /// The index.
        index: u32,
    },
    /// A brick placed twice.
    #[error("step {step}: brick {label} is placed a second time")]
    Repeated {
        /// Step.
        step: usize,
        /// Its label.
        label: u32,
    },
    /// A brick placed before one of its supports.
    #[error("step {step}: brick {label} is placed before its support {support}")]
    Unsupported {
        /// Step.
        step: usize,
        /// Its label.
        label: u32,
        /// The missing support's label.
        support: u32,
    },
    /// The claimed total differs from the recomputed one.
    #[error("claimed total cost {claimed} differs from the recomputed {actual}")]
    CostMismatch {
        /// Claimed.
        claimed: f64,
        /// Recomputed.
        actual: f64,
    },
}

/// Checks that `order` places every brick of `wall` exactly once, each after its supports, and
/// recomputes every step's cost from the model's formula. Stops at the first broken rule
/// ([`order_violations`] lists every one).
pub fn validate(
    wall: &Wall,
    model: &CostModel,
    order: &[BrickId],
) -> Result<Evaluation, OrderError> {
    let mut found = Violations::first();
    match walk(wall, model, order, &mut found) {
        ControlFlow::Continue(eval) => found.into_result(eval),
        ControlFlow::Break(()) => Err(found.into_vec().remove(0)),
    }
}

/// Every rule `order` breaks, in order of the steps (a wrong length first): the rules of
/// [`validate`], which stops at the first. A brick placed before its supports still counts as
/// placed afterwards; an unknown or repeated entry is skipped.
pub fn order_violations(wall: &Wall, model: &CostModel, order: &[BrickId]) -> Vec<OrderError> {
    let mut found = Violations::every();
    let _ = walk(wall, model, order, &mut found);
    found.into_vec()
}

fn walk(
    wall: &Wall,
    model: &CostModel,
    order: &[BrickId],
    found: &mut Violations<OrderError>,
) -> ControlFlow<(), Evaluation> {
    if order.len() != wall.len() {
        found.report(OrderError::WrongLength {
            found: order.len(),
            expected: wall.len(),
        })?;
    }
    let mut placed = vec![false; wall.len()];
    let mut steps = Vec::with_capacity(order.len());
    let mut total = 0.0;
    for (step, &b) in order.iter().enumerate() {
        if b.index() >= wall.len() {
            found.report(OrderError::UnknownBrick { step, index: b.0 })?;
            continue;
        }
        let brick = wall.brick(b);
        if placed[b.index()] {
            found.report(OrderError::Repeated {
                step,
                label: brick.label,
            })?;
            continue;
        }
        for &s in wall.supports(b).iter().filter(|s| !placed[s.index()]) {
            found.report(OrderError::Unsupported {
                step,
                label: brick.label,
                support: wall.brick(s).label,
            })?;
        }
        let k = wall
            .neighbours(b)
            .iter()
            .filter(|n| placed[n.index()])
            .count();
        let t = model.times(brick.kind);
        let factor = 1.0 + (-model.alpha * f64::from(brick.level)).exp();
        let cost =
            factor * (model.grasp_attempts * t.grasp + t.fly + model.kappa[k.min(2)] * t.drop);
        total += cost;
        steps.push(Step {
            brick: b,
            placed_neighbours: k as u32,
            cost,
        });
        placed[b.index()] = true;
    }
    ControlFlow::Continue(Evaluation {
        steps,
        total_cost: total,
    })
}

/// Validates `order` and checks that `claimed` matches the recomputed total (relative 1e-9).
pub fn validate_claim(
    wall: &Wall,
    model: &CostModel,
    order: &[BrickId],
    claimed: f64,
) -> Result<Evaluation, OrderError> {
    let eval = validate(wall, model, order)?;
    if (eval.total_cost - claimed).abs() > 1e-9 * eval.total_cost.abs().max(1.0) {
        return Err(OrderError::CostMismatch {
            claimed,
            actual: eval.total_cost,
        });
    }
    Ok(eval)
}
