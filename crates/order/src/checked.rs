//! A planner's outcome with its order checked by [`crate::validate_claim`], the independent
//! oracle: what every caller of a planner (the CLI, the bench suites, Python) runs.

use crate::{validate_claim, Budget, BuildProblem, Evaluation, OrderError, Outcome, PlannerSpec};

/// A planner's outcome after validation.
#[derive(Clone, Debug)]
pub struct CheckedPlan {
    /// The planner's outcome.
    pub outcome: Outcome,
    /// The validator's evaluation of the order, when there is one.
    pub evaluation: Option<Evaluation>,
}

/// A planner produced an order the validator rejects: a bug, never a result.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("{planner} produced an invalid plan: {source}")]
pub struct InvalidPlan {
    /// The planner.
    pub planner: String,
    /// What the validator found.
    pub source: OrderError,
}

/// Runs `spec` on `problem` within `budget` and validates its order and claimed cost.
pub fn plan_checked(
    problem: &BuildProblem<'_>,
    spec: PlannerSpec,
    budget: &Budget,
) -> Result<CheckedPlan, InvalidPlan> {
    let outcome = spec.plan(problem, budget);
    let evaluation = match (&outcome.order, outcome.total_cost) {
        (Some(order), Some(cost)) => Some(
            validate_claim(problem.wall(), problem.model(), order, cost).map_err(|source| {
                InvalidPlan {
                    planner: spec.to_string(),
                    source,
                }
            })?,
        ),
        _ => None,
    };
    Ok(CheckedPlan {
        outcome,
        evaluation,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_planner_is_checked_on_a_small_wall() {
        let wall = mason_wall::parse_layer_text("R G\nB R R", "t").unwrap();
        let p = BuildProblem::new(&wall, crate::CostModel::default()).unwrap();
        for spec in ["brute", "greedy", "improved:1,2", "exact"] {
            let spec: PlannerSpec = spec.parse().unwrap();
            let c = plan_checked(&p, spec, &Budget::unlimited()).unwrap();
            let e = c.evaluation.expect("an order");
            assert!((e.total_cost - c.outcome.total_cost.unwrap()).abs() < 1e-9);
        }
    }
}
