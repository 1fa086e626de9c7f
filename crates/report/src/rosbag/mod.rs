//! ROS 2 bags of a mission (rosbag2: a `metadata.yaml` and one MCAP file of profile `ros2`),
//! and what the ROS 2 bridge shares with them: the topics, the message types and their
//! definitions, the wall's markers.
//!
//! The topics are those the bridge (`ros2/` at the repository root) publishes live:
//! `/mason/uav_<i>/pose` (`geometry_msgs/msg/PoseStamped`, frame [`FRAME`]),
//! `/mason/uav_<i>/state` and `/mason/mission` (`std_msgs/msg/String`, JSON), `/mason/wall`
//! (`visualization_msgs/msg/MarkerArray`, one `CUBE` per brick). Messages are CDR
//! ([`Cdr`], written here), schemas the ROS 2 message definitions (`ros2msg`).
//!
//! One file per part:
//! - `cdr`: [`Cdr`], the encoder;
//! - `messages`: [`RosType`] (names, definitions, hashes) and the three message encoders;
//! - `wall`: the bricks as markers coloured by status, and [`wall_scene_json`] for the bridge;
//! - `bag`: [`RosBag`], the MCAP file and `metadata.yaml`;
//! - `trace`: [`mission_rosbag`], a mission's trace as a bag.
//!
//! ```
//! use mason_mission::{Arena, CommMode, Event, EventKind, UavState};
//! let wall = mason_wall::parse_layer_text("R G", "example").unwrap();
//! let arena = Arena::default();
//! let none = Default::default();
//! let meta = mason_report::BagMeta {
//!     uavs: 1, arena: &arena, wall: &wall, mode: CommMode::Comm, rejected: &none,
//! };
//! let trace = [Event {
//!     t: 0.0,
//!     uav: 0,
//!     kind: EventKind::State { state: UavState::Check, outcome: "start", x: 50.0, y: 45.0 },
//! }];
//! let bag = mason_report::mission_rosbag("example", &meta, &trace, 10.0).unwrap();
//! assert_eq!(bag.mcap_name, "example_0.mcap");
//! assert!(bag.metadata.starts_with("rosbag2_bagfile_information:\n  version: 9\n"));
//! ```

mod bag;
mod cdr;
mod messages;
mod trace;
mod wall;

pub use bag::{Qos, RosBag, RosBagFiles, TopicId, ROS_DISTRO};
pub use cdr::Cdr;
pub use messages::{cube_array, pose_stamped, string as string_message, Cube, RosType, Stamp};
pub use trace::{mission_rosbag, uav_topics, BagMeta, MISSION_TOPIC, WALL_TOPIC};
pub use wall::{wall_cubes, wall_scene_json, BrickStatus, BRICK_NS, FRAME, SCENE_VERSION};
