//! A schedule planned and checked by [`validate_schedule_claim`], the independent oracle.

use super::{
    plan_schedule, validate_schedule_claim, Objective, ScheduleError, ScheduleEvaluation,
    TeamOutcome, TeamProblem,
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
    check_bound(p, &outcome)?;
    Ok(CheckedSchedule {
        outcome,
        evaluation,
    })
}

/// The objective must lie on its side of the proven bound: a makespan at or above its lower
/// bound, a reward or expected reward at or below its upper bound (up to rounding).
pub(super) fn check_bound(p: &TeamProblem<'_>, o: &TeamOutcome) -> Result<(), ScheduleError> {
    if o.schedule.is_none() || !o.bound.is_finite() {
        return Ok(());
    }
    let slack = 1e-9 * o.bound.abs().max(1.0);
    let (objective, value, outside) = match p.objective() {
        Objective::Makespan => ("makespan", o.makespan_s, o.makespan_s < o.bound - slack),
        Objective::Reward => ("reward", o.reward, o.reward > o.bound + slack),
        Objective::Expected { .. } => {
            let v = o.expected_reward.unwrap_or(o.reward);
            ("expected reward", v, v > o.bound + slack)
        }
    };
    if outside {
        return Err(ScheduleError::OutsideBound {
            objective,
            value,
            bound: o.bound,
        });
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::schedule::{Objective, TeamModel};
    use crate::Status;

    #[test]
    fn a_checked_schedule_places_the_whole_wall() {
        let wall = mason_wall::parse_layer_text("R G\nB R R", "t").unwrap();
        let p = TeamProblem::new(&wall, TeamModel::cmcp(), 3, None, Objective::Makespan).unwrap();
        let c = schedule_checked(&p, &Budget::nodes(200), 1).unwrap();
        assert_eq!(c.evaluation.bricks, 5);
    }

    /// #32: with a hazard of 1e-18 per hour the expected-reward bound lost all precision and
    /// fell far below the reward any schedule gets; it is now sound, and checked.
    #[test]
    fn the_expected_reward_stays_under_its_bound_at_tiny_hazards() {
        let wall = mason_wall::builtin("thesis-2x5").unwrap().wall();
        for h in [1e-300, 1e-18, 1e-6, 1.0, 1e3] {
            let objective = Objective::Expected { hazard_per_hour: h };
            let p =
                TeamProblem::new(&wall, TeamModel::thesis(), 3, Some(300.0), objective).unwrap();
            let c = schedule_checked(&p, &Budget::nodes(300), 0).unwrap();
            let v = c.outcome.expected_reward.unwrap();
            assert!(
                v <= c.outcome.bound + 1e-9,
                "h {h}: {v} > {}",
                c.outcome.bound
            );
        }
    }

    /// #32: an `expected` score costs a re-decode per failure and scenario; past the deadline
    /// it stops with a conservative estimate (never above the full one) and says `Timeout`.
    #[test]
    fn an_expected_score_cut_short_by_the_deadline_is_conservative() {
        let wall = mason_wall::builtin("mbzirc").unwrap().wall();
        let objective = Objective::Expected {
            hazard_per_hour: 2.0,
        };
        let p = TeamProblem::new(&wall, TeamModel::thesis(), 5, Some(900.0), objective).unwrap();
        let full = plan_schedule(&p, &Budget::nodes(1), 0);
        let cut = plan_schedule(&p, &Budget::time(std::time::Duration::ZERO), 0);
        assert_eq!(cut.status, Status::Timeout);
        let (f, c) = (full.expected_reward.unwrap(), cut.expected_reward.unwrap());
        assert!(c < f, "cut short {c} should be below the full estimate {f}");
        assert!(c >= 0.0);
    }

    #[test]
    fn an_objective_beyond_its_bound_is_caught() {
        let wall = mason_wall::parse_layer_text("R G\nB R R", "t").unwrap();
        let p = TeamProblem::new(&wall, TeamModel::cmcp(), 3, None, Objective::Makespan).unwrap();
        let mut o = plan_schedule(&p, &Budget::nodes(200), 1);
        o.bound = o.makespan_s * 2.0;
        assert!(matches!(
            check_bound(&p, &o),
            Err(ScheduleError::OutsideBound { .. })
        ));
    }
}
