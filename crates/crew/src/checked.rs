//! A crew plan solved and checked by [`crate::validate()`], the independent oracle.

use crate::{
    solve, validate, Budget, CrewConfig, CrewOutcome, Instance, PlanError, PlanMetrics, SetupError,
};

/// A solve with its validation.
#[derive(Clone, Debug)]
pub struct CheckedCrewPlan {
    /// The solver's outcome.
    pub outcome: CrewOutcome,
    /// The validator's metrics, when there is a plan.
    pub metrics: Option<PlanMetrics>,
}

/// Why a checked solve gave no result.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum CheckedSolveError {
    /// The configuration cannot run on the instance (bad input).
    #[error(transparent)]
    Setup(#[from] SetupError),
    /// The solver's plan failed validation: a bug, never a result.
    #[error("the crew plan failed validation: {0}")]
    Invalid(#[from] PlanError),
}

/// Solves `inst` with `config` within `budget` and validates the plan.
pub fn solve_checked(
    inst: &Instance,
    config: &CrewConfig,
    budget: &Budget,
) -> Result<CheckedCrewPlan, CheckedSolveError> {
    let outcome = solve(inst, config, budget)?;
    let metrics = match &outcome.paths {
        Some(paths) => Some(validate(
            &inst.grid,
            inst.connectivity,
            &inst.robots,
            &outcome.goals,
            paths,
        )?),
        None => None,
    };
    Ok(CheckedCrewPlan { outcome, metrics })
}

impl CheckedCrewPlan {
    /// Σ of the robots' fewest steps to their goals, a lower bound on the sum of costs: the
    /// solver's own sum when it made one, else computed; `None` when a goal is unreachable.
    pub fn lower_bound(&self, inst: &Instance) -> Option<u64> {
        self.outcome
            .stats
            .lower_bound
            .or_else(|| shortest_steps(inst, &self.outcome.goals).into_iter().sum())
    }
}

/// Each robot's fewest steps to its goal in `goals` (`None` when unreachable), on all cores.
pub fn shortest_steps(inst: &Instance, goals: &[crate::Cell]) -> Vec<Option<u64>> {
    use rayon::prelude::*;
    inst.robots
        .par_iter()
        .zip(goals)
        .map(|(&s, &g)| {
            let d = crate::distance::step_distances(&inst.grid, inst.connectivity, s)[g.0 as usize];
            (d != crate::distance::UNREACHABLE).then_some(u64::from(d))
        })
        .collect()
}
