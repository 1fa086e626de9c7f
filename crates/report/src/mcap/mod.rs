//! MCAP logs of a mission, for Foxglove: UAV poses, states, the wall zone, bricks, the wall as a
//! 3-D scene, every event as a log line, and the coordination messages.
//!
//! Every channel is JSON (`message_encoding = "json"`) with a JSON Schema
//! (`schema encoding = "jsonschema"`). The channels Foxglove draws use the schema names it knows,
//! so the file opens without set-up; the JSON Schemas are written here from Foxglove's public
//! schema definitions (the `foxglove` crate is not used).
//!
//! | topic | schema | one message per |
//! |---|---|---|
//! | `/uav/<i>/pose` | `foxglove.PoseInFrame` | pose sample of UAV i |
//! | `/uav/<i>/state` | `mason.UavState` | state transition of UAV i |
//! | `/zone` | `mason.Zone` | zone enter or leave |
//! | `/bricks` | `mason.Brick` | brick grasped, placed or lost |
//! | `/wall` | `foxglove.SceneUpdate` | start of the log, and each placement |
//! | `/events` | `foxglove.Log` | trace event |
//! | `/messages` | `mason.Message` | coordination message |
//!
//! Times: a message's `log_time` and `publish_time` are its mission time in nanoseconds (0 =
//! mission start), and every `timestamp` field is the same time as `{sec, nsec}`. Nothing reads
//! the wall clock, so one trace always gives the same bytes. Chunks are uncompressed and indexed.
//!
//! Geometry, in the frame `world`: x east and y north as in [`Arena`](mason_mission::Arena), z
//! up, metres. The wall's bricks are placed as [`brick_box`] says. Each `/wall` message holds
//! the whole scene (zone box, piles, every brick of the design as a faint cube and every brick
//! placed so far as a solid one, entity `brick/<label>`), so a viewer that seeks and shows only
//! the latest message still shows the right wall.
//!
//! One file per part:
//! - `writer`: [`McapLog`], the log being written: channels, and one message per pose, event
//!   or coordination message, into any `Write + Seek` sink;
//! - `schemas`: the JSON Schemas of the channels (Foxglove's and Mason's own);
//! - `values`: the JSON form of times, vectors, poses and colours;
//! - `scene`: the wall as a 3-D scene (zone, piles, design, bricks placed) and [`brick_box`];
//! - `pose_sampler`: [`PoseSampler`], when a UAV's pose is logged and its heading;
//! - `trace`: [`write_trace`] and [`mission_mcap`], a simulated trace turned into a log, with
//!   poses along each leg.
//!
//! ```
//! use mason_mission::{Arena, Event, EventKind, UavState};
//! let wall = mason_wall::parse_layer_text("R G", "example").unwrap();
//! let arena = Arena::default();
//! let meta = mason_report::LogMeta { mission_id: "demo", uavs: 1, arena: &arena, wall: &wall };
//! let trace = [Event {
//!     t: 0.0,
//!     uav: 0,
//!     kind: EventKind::State { state: UavState::Check, outcome: "start", x: 50.0, y: 45.0 },
//! }];
//! let bytes = mason_report::mission_mcap(&meta, &trace, 10.0).unwrap();
//! assert!(bytes.starts_with(b"\x89MCAP0\r\n"));
//! ```

mod pose_sampler;
mod scene;
mod schemas;
mod trace;
mod values;
mod writer;

pub(crate) use trace::trace_poses;
pub(crate) use values::nanos;

#[cfg(test)]
mod tests;

pub use pose_sampler::{PoseSampler, POSE_RATE_HZ};
pub use scene::brick_box;
pub use trace::{cruise_altitude, mission_mcap, write_trace};
pub use writer::{LogMeta, McapLog, McapLogError, UavPose};
