//! The agent runtime: everything a UAV agent process needs except argument parsing, for the
//! `mason` command, the Python package and the ROS 2 bridge alike.
//!
//! - [`clock`]: mission time ([`Clock`], the real [`MissionClock`]);
//! - [`transport`]: how messages reach the team ([`Transport`]; [`Hub`], an in-memory bus;
//!   `ZenohLink` over Zenoh with the `zenoh` feature);
//! - [`faults`]: the [`FaultLayer`], faults on purpose drawn from the same model as the
//!   simulator's virtual bus ([`mason_mission::LinkFaults`]);
//! - [`drive`]: the loop that runs one [`mason_mission::agent::Agent`] ([`drive()`]);
//! - [`log`]: where an agent writes what it does ([`AgentLog`], [`JsonLines`],
//!   [`McapAgentLog`]); [`trace`]: the one strict reader of those trace files;
//! - [`world`]: the simulated camera's view of the wall across processes ([`TraceWorld`]);
//! - [`network`]: mission id, key prefix, endpoints and security, checked ([`Network`]);
//! - `authority` (feature `zenoh`): the mission authority, its certificates and keys, and the
//!   check of a member's files (`make_keys`, `check_member`);
//! - [`setting`]: what a team shares ([`FleetSetting`]); [`agent`]: one agent process
//!   ([`fly_agent`]); [`launch`]: a team of processes, merged and checked ([`launch()`]).
//!
//! ```
//! use mason_fleet::{fly_agent, AgentOptions, FleetSetting, Hub, Network, NetworkFlags};
//! use mason_mission::{Coord, LinkFaults, MissionConfig};
//! # let wall = mason_wall::builtin("thesis-2x5").unwrap().wall();
//! # let model = mason_order::CostModel::default();
//! let order: Vec<_> = wall.ids().collect(); // level by level: a valid order
//! let config = MissionConfig::with_uavs(1);
//! let slot = mason_mission::slot_length(&wall, &model, &config).unwrap();
//! let setting = FleetSetting {
//!     wall, model, order, config, coord: Coord::Comm, slot, speed: 1000.0, seed: 7,
//!     dead_after: 30.0, link: LinkFaults::default(),
//! };
//! // In-process: no network, so nothing to secure.
//! let flags = NetworkFlags { mission: Some("demo".into()), insecure: true, ..NetworkFlags::default() };
//! let net = Network::resolve(None, &flags).unwrap();
//! let opts = AgentOptions { uav: 0, incarnation: 1, ..AgentOptions::default() };
//! let mut link = Hub::new(1).links().pop().unwrap();
//! let stop = std::sync::atomic::AtomicBool::new(false);
//! let report = fly_agent(&setting, &net, &opts, &mut link, &stop).unwrap();
//! assert_eq!(report.placed_known, 10);
//! ```

#![deny(missing_docs)]

pub mod agent;
#[cfg(feature = "zenoh")]
pub mod authority;
pub mod clock;
pub mod drive;
pub mod error;
pub mod faults;
pub mod launch;
pub mod log;
pub mod network;
pub mod setting;
pub mod trace;
pub mod transport;
pub mod world;
#[cfg(feature = "zenoh")]
pub mod zenoh_link;

pub use agent::{fly_agent, AgentOptions, AgentReport, MAX_START_AHEAD_S};
pub use clock::{unix_now, Clock, MissionClock, MAX_SPEED, MIN_SPEED};
pub use drive::{drive, Ending, LAST_WORD_REPEATS};
pub use error::{FleetError, FleetResult};
pub use faults::{FaultLayer, FaultStats};
pub use launch::{
    crash, drops_in_log, launch, schedule, Action, AgentRun, Launch, LaunchOptions, DROPPED_LINE,
};
pub use log::{AgentLog, Capped, JsonLines, McapAgentLog, MAX_LOG_BYTES};
pub use mason_mission::agent::agent_seed;
pub use network::{
    check_chunks, check_endpoint, Network, NetworkFile, NetworkFlags, SecureLink, Security,
    DEFAULT_PREFIX, MAX_KEY_CHUNK, MAX_PREFIX_CHUNKS, SECURE_SCHEMES,
};
pub use setting::{default_dead_after, least_dead_after, FleetSetting, DEAD_AFTER_HEARTBEATS};
pub use trace::{append_death, merge, parse_trace, placed_by, read_trace, MAX_TRACE_BYTES};
pub use transport::{Hub, HubLink, Transport};
pub use world::TraceWorld;
#[cfg(feature = "zenoh")]
pub use zenoh_link::ZenohLink;
