//! Team schedules (DESIGN §4.1): which UAV places which brick when.
//!
//! A [`TeamProblem`] is a wall, a team of m UAVs, a [`TeamModel`] (per-type placing and cycle
//! times, UAVs per brick, rewards, the concurrency rule), an optional budget and an
//! [`Objective`]. [`plan_schedule`] is the anytime planner; [`exhaustive_schedule`] the exact
//! one for tiny walls; [`bounds`] gives the proven bounds every result is measured against;
//! [`validate_schedule`] checks a schedule without knowing any planner.
//!
//! ```
//! use mason_order::schedule::{plan_schedule, validate_schedule, Objective, TeamModel, TeamProblem};
//! use mason_order::{Budget, Status};
//!
//! let wall = mason_wall::parse_layer_text("R G\nB R R", "example").unwrap();
//! let p = TeamProblem::new(&wall, TeamModel::cmcp(), 3, None, Objective::Makespan).unwrap();
//! let out = plan_schedule(&p, &Budget::nodes(500), 7);
//! let checked = validate_schedule(&wall, p.model(), 3, None, out.schedule.as_ref().unwrap()).unwrap();
//! assert_eq!(checked.bricks, 5);
//! assert!(out.makespan_s >= out.bound);
//! ```

pub mod bounds;
mod checked;
mod closure;
pub mod exhaustive;
mod model;
pub mod polish;
mod problem;
pub mod search;
pub mod sgs;
pub mod slots;
mod validate;

pub use checked::{schedule_checked, CheckedSchedule};
pub use exhaustive::exhaustive_schedule;
pub use model::{
    Concurrency, Metric, TeamModel, TeamModelError, TeamModelPatch, TypePatch, TypeSchedule,
    MAX_SECONDS, MIN_PLACE_S,
};
pub use problem::{
    brick_centre, Objective, ObjectiveParseError, Placement, Schedule, TeamOutcome, TeamProblem,
    TeamProblemError, TeamStart, TeamStats, MAX_CONFLICT_PAIRS, MAX_UAVS,
};
pub use search::{plan_schedule, plan_schedule_with};
pub use validate::{
    claim_violations, continuation_violations, end_violations, schedule_violations,
    validate_continuation, validate_schedule, validate_schedule_claim, ClaimedEnd, ScheduleError,
    ScheduleEvaluation, TIME_EPS,
};
