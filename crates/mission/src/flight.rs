//! What a mission flies from a team schedule: plan the schedule and check it with the validator
//! that knows nothing of the planner ([`schedule_checked`]: `plan_schedule`, then
//! `validate_schedule_claim`), and
//! turn it into the shared order and the per-UAV lists the simulator and the agents fly.
//!
//! The shared order is the schedule's bricks by start time, then the bricks the schedule
//! leaves out (after a `reward` budget) in a base order, so that the team can still finish
//! the wall. The team model is the thesis model of the cost model's times
//! ([`TeamModel::from_cost_model`]), so that the schedule's timings are the simulator's.
//!
//! ```
//! use mason_mission::{flight_plan, FlightRequest};
//! use mason_order::schedule::Objective;
//! let wall = mason_wall::builtin("thesis-2x5").unwrap().wall();
//! let cost = mason_order::CostModel::default();
//! let base: Vec<_> = wall.ids().collect();
//! let request = FlightRequest { objective: Objective::Makespan, uavs: 2, budget_s: None, seed: 0 };
//! let plan = flight_plan(&wall, &cost, &request, &base, &mason_order::Budget::nodes(200)).unwrap();
//! assert_eq!(plan.order.len(), wall.len());
//! assert_eq!(plan.lists.iter().map(Vec::len).sum::<usize>(), wall.len());
//! ```

use mason_order::schedule::{
    schedule_checked, Objective, Schedule, ScheduleError, TeamModel, TeamProblem, TeamProblemError,
};
use mason_order::{Budget, CostModel};
use mason_wall::{BrickId, Wall};
use thiserror::Error;

/// What a planner may take to plan the shared order a mission flies (s).
pub const ORDER_TIME_LIMIT_S: f64 = 60.0;

/// The schedule a mission asks for.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FlightRequest {
    /// What the schedule optimises (with its hazard for `expected`).
    pub objective: Objective,
    /// Team size.
    pub uavs: usize,
    /// The budget T (s): needed by `reward` and `expected`, refused by `makespan`.
    pub budget_s: Option<f64>,
    /// The planner's seed.
    pub seed: u64,
}

/// What a mission flies from a team schedule.
#[derive(Clone, Debug, PartialEq)]
pub struct FlightPlan {
    /// The thesis team model of the cost model's times (the simulator's timings).
    pub team: TeamModel,
    /// The shared order: scheduled bricks by start, then the rest as `base` has them.
    pub order: Vec<BrickId>,
    /// Each UAV's bricks in the order it places them.
    pub lists: Vec<Vec<BrickId>>,
}

/// Why no flight plan was made.
#[derive(Clone, Debug, PartialEq, Error)]
pub enum FlightPlanError {
    /// The schedule problem cannot be posed (bad team size, budget, model or objective).
    #[error(transparent)]
    Problem(#[from] TeamProblemError),
    /// The planner's schedule failed the validator: a bug in the planner.
    #[error("the planner produced an invalid schedule: {0}")]
    InvalidSchedule(ScheduleError),
    /// The base order names a brick that is not in the wall.
    #[error("the base order names brick index {brick}, but the wall has {bricks} bricks")]
    UnknownBrick {
        /// The brick's index.
        brick: u32,
        /// The wall's size.
        bricks: usize,
    },
}

/// Plans (and validates) the schedule a mission flies, within `budget`. Bricks the schedule
/// leaves out (after the budget T) follow in `base`'s order, so that the mission can still
/// finish the wall. A search that found no schedule flies `base` with empty lists.
pub fn flight_plan(
    wall: &Wall,
    cost: &CostModel,
    request: &FlightRequest,
    base: &[BrickId],
    budget: &Budget,
) -> Result<FlightPlan, FlightPlanError> {
    if let Some(b) = base.iter().find(|b| b.index() >= wall.len()) {
        return Err(FlightPlanError::UnknownBrick {
            brick: b.0,
            bricks: wall.len(),
        });
    }
    let team = TeamModel::from_cost_model(cost);
    let p = TeamProblem::new(
        wall,
        team.clone(),
        request.uavs,
        request.budget_s,
        request.objective,
    )?;
    let schedule = schedule_checked(&p, budget, request.seed)
        .map_err(FlightPlanError::InvalidSchedule)?
        .outcome
        .schedule
        .unwrap_or_default();
    Ok(FlightPlan::of_schedule(
        wall,
        team,
        &schedule,
        request.uavs,
        base,
    ))
}

impl FlightPlan {
    /// The flight plan of a checked `schedule` for `uavs` UAVs: its bricks by start, then the
    /// rest of `base` (indices within `wall`, as [`flight_plan`] checks).
    pub fn of_schedule(
        wall: &Wall,
        team: TeamModel,
        schedule: &Schedule,
        uavs: usize,
        base: &[BrickId],
    ) -> FlightPlan {
        let mut listed = vec![false; wall.len()];
        let mut order: Vec<BrickId> = Vec::with_capacity(wall.len());
        for pl in &schedule.placements {
            listed[pl.brick.index()] = true;
            order.push(pl.brick);
        }
        order.extend(base.iter().copied().filter(|b| !listed[b.index()]));
        FlightPlan {
            team,
            order,
            lists: schedule.by_uav(uavs),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn mbzirc() -> Wall {
        mason_wall::builtin("mbzirc").unwrap().wall()
    }

    fn request(objective: Objective, budget_s: Option<f64>) -> FlightRequest {
        FlightRequest {
            objective,
            uavs: 3,
            budget_s,
            seed: 0,
        }
    }

    #[test]
    fn a_makespan_plan_is_the_planners_schedule() {
        let wall = mbzirc();
        let cost = CostModel::default();
        let mut base: Vec<BrickId> = wall.ids().collect();
        base.reverse();
        let budget = Budget::nodes(300);
        let plan = flight_plan(
            &wall,
            &cost,
            &request(Objective::Makespan, None),
            &base,
            &budget,
        )
        .unwrap();
        let team = TeamModel::from_cost_model(&cost);
        let p = TeamProblem::new(&wall, team.clone(), 3, None, Objective::Makespan).unwrap();
        let s = mason_order::schedule::plan_schedule(&p, &budget, 0)
            .schedule
            .unwrap();
        let order: Vec<BrickId> = s.placements.iter().map(|pl| pl.brick).collect();
        assert_eq!(plan.team, team);
        assert_eq!(
            plan.order, order,
            "the whole wall is scheduled: base adds nothing"
        );
        assert_eq!(plan.lists, s.by_uav(3));
    }

    #[test]
    fn bricks_left_out_by_a_budget_follow_in_the_base_order() {
        let wall = mbzirc();
        let base: Vec<BrickId> = wall.ids().collect();
        let plan = flight_plan(
            &wall,
            &CostModel::default(),
            &request(Objective::Reward, Some(300.0)),
            &base,
            &Budget::nodes(300),
        )
        .unwrap();
        let scheduled: std::collections::BTreeSet<BrickId> =
            plan.lists.iter().flatten().copied().collect();
        assert!(
            !scheduled.is_empty() && scheduled.len() < wall.len(),
            "{scheduled:?}"
        );
        let mut sorted = plan.order.clone();
        sorted.sort();
        assert_eq!(sorted, base, "every brick once");
        let (head, rest) = plan.order.split_at(scheduled.len());
        assert!(head.iter().all(|b| scheduled.contains(b)));
        assert!(
            rest.windows(2).all(|w| w[0] < w[1]),
            "the rest in base order"
        );
    }

    #[test]
    fn a_problem_that_cannot_be_posed_is_a_typed_error() {
        let wall = mbzirc();
        let base: Vec<BrickId> = wall.ids().collect();
        let plan = |r: FlightRequest| {
            flight_plan(&wall, &CostModel::default(), &r, &base, &Budget::nodes(10))
        };
        assert_eq!(
            plan(request(Objective::Reward, None)),
            Err(FlightPlanError::Problem(TeamProblemError::NeedsBudget(
                "reward"
            )))
        );
        assert_eq!(
            plan(request(Objective::Makespan, Some(100.0))),
            Err(FlightPlanError::Problem(
                TeamProblemError::BudgetWithMakespan
            ))
        );
        assert!(matches!(
            plan(FlightRequest {
                uavs: 1,
                ..request(Objective::Makespan, None)
            }),
            Err(FlightPlanError::Problem(
                TeamProblemError::TeamTooSmall { .. }
            ))
        ));
        assert_eq!(
            flight_plan(
                &wall,
                &CostModel::default(),
                &request(Objective::Makespan, None),
                &[BrickId(9999)],
                &Budget::nodes(10)
            ),
            Err(FlightPlanError::UnknownBrick {
                brick: 9999,
                bricks: wall.len()
            })
        );
    }
}
