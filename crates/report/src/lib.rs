//! Mason reports: figures drawn from plain data, returned as strings, and MCAP logs written into
//! a sink the caller gives. No file access.
//!
//! SVG figures: the wall with its build order ([`wall_svg`]), the mission Gantt chart
//! ([`gantt_svg`]), the team schedule Gantt chart ([`schedule_svg`]), reward over time ([`reward_svg`]), crew paths ([`crew_svg`]) and an aerial view with what was read from it ([`aerial_svg`]).
//! Self-contained HTML replays: [`mission_replay_html`] and [`crew_replay_html`].
//! The JSON of a mission's events and metrics ([`event_json`], [`metrics_json`]) and plain-text
//! clocks for tables ([`text`]).
//! MCAP logs for Foxglove ([`McapLog`], [`mission_mcap`]): written into any `Write + Seek` sink,
//! with UAV poses logged when [`PoseSampler`] says, for simulated traces and live agents alike.
//! ROS 2 bags of a mission ([`mission_rosbag`]: rosbag2, CDR written by [`Cdr`]) and the wall
//! as ROS 2 markers, shared with the ROS 2 bridge ([`wall_scene_json`]).
//!
//! ```
//! let wall = mason_wall::parse_layer_text("R G\nB R R", "example").unwrap();
//! let svg = mason_report::wall_svg(&wall, None);
//! assert!(svg.starts_with("<svg"));
//! ```
#![deny(missing_docs)]

mod aerial_svg;
mod crew_svg;
mod gantt;
mod json;
mod mcap;
mod page;
mod replay;
mod reward;
mod rosbag;
mod schedule_svg;
mod svg;
pub mod text;
mod wall_layout;
mod wall_svg;

pub use self::mcap::{
    brick_box, cruise_altitude, mission_mcap, write_trace, LogMeta, McapLog, McapLogError,
    PoseSampler, UavPose, POSE_RATE_HZ,
};
pub use aerial_svg::{aerial_audit_svg, aerial_svg};
pub use crew_svg::crew_svg;
pub use gantt::{gantt_svg, state_colour};
pub use json::{
    event_json, metrics_json, plan_json, runs_json, schedule_json, simulate_json, wall_json,
    PlanDoc, RunSetting, ScheduleDoc, WallDoc,
};
pub use page::{pre, report_page, Section};
pub use replay::{crew_replay_html, mission_replay_html};
pub use reward::{reward_svg, Series};
pub use rosbag::{
    cube_array, mission_rosbag, pose_stamped, string_message, uav_topics, wall_cubes,
    wall_scene_json, BagMeta, BrickStatus, Cdr, Cube, Qos, RosBag, RosBagFiles, RosType, Stamp,
    TopicId, BRICK_NS, FRAME, MISSION_TOPIC, ROS_DISTRO, SCENE_VERSION, WALL_TOPIC,
};
pub use schedule_svg::schedule_svg;
pub use svg::{escape, robot_colour};
pub use wall_layout::{front_layout, Band, FrontLayout, Spot, CAPTION_M};
pub use wall_svg::wall_svg;
