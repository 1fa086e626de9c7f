//! Mission rehearsal: a UAV team flies a wall's build order (thesis ch. 4–5).
//!
//! A fast, deterministic discrete-event simulator ([`sim`]) runs one state machine per UAV
//! ([`state`]) in an [`arena`], with the UAV model and faults of [`config`]. The UAVs share one
//! wall zone and coordinate by a policy behind one trait ([`policy`]): [`comm`] (messages over
//! a lossy [`channel`]), [`windows`] (fixed time slots) or [`auto`] (messages, falling back to
//! windows when heartbeats are lost). Events go to an [`Observer`]: a `Vec<Event>` trace,
//! [`metrics`], or [`check::TraceChecker`], the independent safety check. [`montecarlo`] runs
//! many seeds over the cores.
//!
//! The per-UAV decisions live in one decision core ([`core`]), shared by the simulator and
//! by the [`agent`]: one UAV as a separate process that knows only what it has heard, speaking
//! the team protocol of [`agent::wire`]. The [`bus`] flies a team of agents on a virtual
//! clock, with the radio faults of [`link`] (the same [`LinkFaults`] as the real transport's)
//! and agents killed and restarted.
//!
//! Shared by every backend and log: the altitude rule ([`mod@altitude`]: [`cruise_altitude`],
//! [`altitude()`]), the seed of each agent ([`agent::agent_seed`]), and the flight plan of a
//! team schedule ([`flight`]: [`flight_plan`], planned and checked by
//! `mason_order::schedule::validate_schedule_claim`). [`replan`] re-plans the schedule when a UAV
//! fails.
//!
//! ```
//! use mason_mission::{check_trace, make_policy, simulate, Coord, MissionConfig, MissionInput, MissionStatus};
//! let wall = mason_wall::builtin("thesis-2x5").unwrap().wall();
//! let model = mason_order::CostModel::default();
//! let order: Vec<_> = wall.ids().collect(); // level by level: a valid order
//! let config = MissionConfig::with_uavs(3);
//! let input = MissionInput {
//!     wall: &wall, order: &order, model: &model, assignment: None, replanner: None, config: &config,
//! };
//! let mut trace = Vec::new();
//! let result = simulate(input, make_policy(Coord::Comm, 20.0).as_mut(), 7, &mut trace);
//! assert_eq!(result.status, MissionStatus::Complete);
//! assert_eq!(check_trace(&wall, 3, &trace).unwrap().placed, 10);
//! ```

#![deny(missing_docs)]

pub mod agent;
pub mod altitude;
pub mod arena;
pub mod auto;
pub mod bus;
pub mod channel;
pub mod check;
mod checked;
pub mod comm;
pub mod config;
pub mod coord;
pub mod core;
pub mod flight;
pub mod link;
pub mod metrics;
pub mod montecarlo;
pub mod policy;
pub mod replan;
pub mod sim;
pub mod state;
pub mod windows;

pub use altitude::{altitude, altitude_during, climb_fraction, cruise_altitude};
pub use arena::{Arena, Point};
pub use bus::killed_events;
pub use check::{check_trace, trace_violations, TraceChecker, TraceError, TraceSummary};
pub use checked::fly_checked;
pub use config::{
    ConfigError, Faults, MissionConfig, UavFailure, UavModel, Window, MAX_MISSION_TIME_S,
    MIN_HEARTBEAT_S,
};
pub use coord::{make_policy, slot_length, Coord};
pub use flight::{flight_plan, FlightPlan, FlightPlanError, FlightRequest, ORDER_TIME_LIMIT_S};
pub use link::{Fate, LinkFaults, LinkFaultsError};
pub use metrics::Metrics;
pub use montecarlo::{
    for_each_run, reward_by, run_many, summarise, RunFigures, Spread, Stream, Summariser, Summary,
};
pub use policy::{Coordination, EntryQuery};
pub use replan::{Replan, Replanner, ScheduleReplanner};
pub use sim::{simulate, MissionInput, MissionResult, MissionStatus};
pub use state::{event_cap, CommMode, Event, EventKind, Flood, Observer, UavState};
