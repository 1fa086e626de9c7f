//! Mason build orders: the thesis cost model, the planners and the validator.
//!
//! A [`BuildProblem`] pairs a [`mason_wall::Wall`] with a [`CostModel`] (DESIGN §4). Planners
//! are free functions, one per module, that take the problem and a [`Budget`] and return an
//! [`Outcome`] whose [`Status`] is `Optimal`, `Feasible`, `Timeout` or `Infeasible`:
//!
//! * [`brute`] — the thesis's brute force (exact, exponential);
//! * [`greedy`] — cheapest available brick first;
//! * [`improved`] — the thesis's improved greedy `improved:n,k`;
//! * [`exact`] — provably optimal, linear time on layer walls.
//!
//! [`validate()`] knows nothing of the planners: it checks an order and recomputes its cost;
//! [`plan_checked`] runs a planner and the validator together.
//!
//! ```
//! use mason_order::{validate, Budget, BuildProblem, CostModel, PlannerSpec, Status};
//!
//! let wall = mason_wall::parse_layer_text("R G\nB R R", "example").unwrap();
//! let problem = BuildProblem::new(&wall, CostModel::default()).unwrap();
//! let exact = PlannerSpec::Exact.plan(&problem, &Budget::unlimited());
//! let brute = PlannerSpec::Brute.plan(&problem, &Budget::unlimited());
//! assert_eq!(exact.status, Status::Optimal);
//! let order = exact.order.unwrap();
//! let checked = validate(&wall, problem.model(), &order).unwrap();
//! assert!((checked.total_cost - brute.total_cost.unwrap()).abs() < 1e-9);
//! ```
#![deny(missing_docs)]

pub mod brute;
mod checked;
pub mod exact;
mod frontier;
pub mod greedy;
pub mod improved;
mod model;
mod outcome;
mod planner;
mod problem;
pub mod schedule;
mod tree_search;
mod validate;

pub use checked::{plan_checked, CheckedPlan, InvalidPlan};
pub use mason_wall::stop::Stop;
pub use model::{CostModel, ModelError, TypeTimes};
pub use outcome::{Better, Budget, OnBetter, Outcome, Stats, Status};
pub use planner::{PlannerParseError, PlannerSpec};
pub use problem::BuildProblem;
pub use validate::{order_violations, validate, validate_claim, Evaluation, OrderError, Step};
