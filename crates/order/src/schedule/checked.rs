//! A schedule planned and checked by [`validate_schedule_claim`], the independent oracle.

use super::{
    plan_schedule, validate_schedule_claim, ScheduleError, ScheduleEvaluation, TeamOutcome,
    TeamProblem,
};
use crate::Budget;

/// A planned, validated schedule.
#[derive(Clone, Debug)]
pub struct CheckedSchedule {
    /// The planner's outcome.
    pub outcome: TeamOutcome,
    /// The validator's recomputation.
    pub evaluation: ScheduleEvaluation,
}

/// Plans `p` within `budget` from `seed` and validates the schedule and its claimed reward and
/// makespan (an error is a planner bug, never a result).
pub fn schedule_checked(
    p: &TeamProblem<'_>,
    budget: &Budget,
    seed: u64,
) -> Result<CheckedSchedule, ScheduleError> {
    let outcome = plan_schedule(p, budget, seed);
    let schedule = outcome.schedule.clone().unwrap_or_default();
    let evaluation = validate_schedule_claim(
        p.wall(),
        p.model(),
        p.uavs(),
        p.budget_s(),
        &schedule,
        outcome.reward,
        outcome.makespan_s,
    )?;
    Ok(CheckedSchedule {
        outcome,
        evaluation,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::schedule::{Objective, TeamModel};

    #[test]
    fn a_checked_schedule_places_the_whole_wall() {
        let wall = mason_wall::parse_layer_text("R G\nB R R", "t").unwrap();
        let p = TeamProblem::new(&wall, TeamModel::cmcp(), 3, None, Objective::Makespan).unwrap();
        let c = schedule_checked(&p, &Budget::nodes(200), 1).unwrap();
        assert_eq!(c.evaluation.bricks, 5);
    }
}
