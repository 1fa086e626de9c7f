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

#[cfg(test)]
mod tests {
    //! One broken order per rule: a valid order with exactly one rule broken, and that rule
    //! alone reported, by [`validate`] and [`order_violations`] alike.
    use super::*;
    use crate::{Budget, BuildProblem, PlannerSpec};

    fn wall() -> Wall {
        mason_wall::builtin("thesis-2x5").unwrap().wall()
    }

    /// Level by level, by id: a valid order.
    fn base(wall: &Wall) -> Vec<BrickId> {
        let mut ids: Vec<BrickId> = wall.ids().collect();
        ids.sort_by_key(|&b| (wall.brick(b).level, b));
        ids
    }

    fn rules(wall: &Wall, order: &[BrickId]) -> Vec<String> {
        let model = CostModel::default();
        let every = order_violations(wall, &model, order);
        let first = validate(wall, &model, order);
        assert_eq!(first.err().as_ref(), every.first(), "first and all agree");
        every.iter().map(mason_wall::violations::rule).collect()
    }

    #[test]
    fn one_broken_order_per_rule_reports_exactly_that_rule() {
        let w = wall();
        let ok = base(&w);
        assert!(rules(&w, &ok).is_empty());
        let n = ok.len();
        let last = ok[n - 1];
        assert!(w.ids().all(|b| !w.supports(b).contains(&last)));
        // A level-2 brick moved to just before its last support, its other supports before.
        let (pos, brick) = ok
            .iter()
            .enumerate()
            .find(|(_, &b)| w.brick(b).level == 2)
            .map(|(i, &b)| (i, b))
            .unwrap();
        let support = *w
            .supports(brick)
            .iter()
            .max_by_key(|s| ok.iter().position(|o| o == *s))
            .unwrap();
        let mut early = ok.clone();
        early.remove(pos);
        let at = early.iter().position(|&b| b == support).unwrap();
        early.insert(at, brick);
        let cases: Vec<(&str, Vec<BrickId>, &str)> = vec![
            (
                "the last brick left out",
                ok[..n - 1].to_vec(),
                "WrongLength",
            ),
            (
                "the last brick replaced by one outside the wall",
                [&ok[..n - 1], &[BrickId(99)]].concat(),
                "UnknownBrick",
            ),
            (
                "the last brick replaced by the first again",
                [&ok[..n - 1], &[ok[0]]].concat(),
                "Repeated",
            ),
            ("a brick before its last support", early, "Unsupported"),
        ];
        for (what, order, want) in cases {
            assert_eq!(rules(&w, &order), [want], "{what}");
        }
        let e = validate(
            &w,
            &CostModel::default(),
            &[&ok[..n - 1], &[ok[0]]].concat(),
        );
        assert_eq!(
            e,
            Err(OrderError::Repeated {
                step: n - 1,
                label: w.brick(ok[0]).label
            })
        );
    }

    #[test]
    fn a_wrong_claim_is_the_only_rule_a_valid_order_can_break() {
        let w = wall();
        let model = CostModel::default();
        let ok = base(&w);
        let eval = validate(&w, &model, &ok).unwrap();
        let sum: f64 = eval.steps.iter().map(|s| s.cost).sum();
        assert_eq!(eval.total_cost, sum);
        assert!(validate_claim(&w, &model, &ok, eval.total_cost).is_ok());
        // The slack is relative: 10⁻⁹ of the total (here about 10⁻⁶), not 10⁻⁹ of one.
        let near = eval.total_cost * (1.0 + 5e-10);
        assert!(eval.total_cost - near < -1e-9);
        assert!(validate_claim(&w, &model, &ok, near).is_ok());
        // A model where nothing takes time: the total is 0 and the slack exactly 10⁻⁹.
        let free = crate::model::TypeTimes {
            grasp: 0.0,
            fly: 0.0,
            drop: 0.0,
        };
        let instant = CostModel {
            red: free,
            green: free,
            blue: free,
            orange: free,
            ..model.clone()
        };
        assert_eq!(validate(&w, &instant, &ok).unwrap().total_cost, 0.0);
        assert!(validate_claim(&w, &instant, &ok, 1e-9).is_ok());
        assert!(validate_claim(&w, &instant, &ok, 2e-9).is_err());
        assert_eq!(
            validate_claim(&w, &model, &ok, eval.total_cost + 1.0),
            Err(OrderError::CostMismatch {
                claimed: eval.total_cost + 1.0,
                actual: eval.total_cost
            })
        );
    }

    #[test]
    fn orders_from_every_planner_pass() {
        for name in ["thesis-2x5", "levels5-width5"] {
            let w = mason_wall::builtin(name).unwrap().wall();
            let problem = BuildProblem::new(&w, CostModel::default()).unwrap();
            for spec in ["brute", "greedy", "improved:1,4", "exact"] {
                if spec == "brute" && w.len() > 12 {
                    continue;
                }
                let spec: PlannerSpec = spec.parse().unwrap();
                let o = spec.plan(&problem, &Budget::unlimited());
                let order = o.order.expect("an order");
                assert!(
                    order_violations(&w, problem.model(), &order).is_empty(),
                    "{spec}"
                );
                let claimed = o.total_cost.expect("a cost");
                let eval = validate_claim(&w, problem.model(), &order, claimed).unwrap();
                assert_eq!(eval.steps.len(), w.len());
            }
        }
    }
}
