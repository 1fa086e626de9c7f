//! A mission's trace as a ROS 2 bag ([`mission_rosbag`]): the topics the ROS 2 bridge
//! publishes, rebuilt from the events (poses as the Foxglove log samples them,
//! [`trace_poses`]).
//!
//! | topic | type | when |
//! |---|---|---|
//! | `/mason/uav_<i>/pose` | `geometry_msgs/msg/PoseStamped` | each pose sample (2 Hz along a leg, and at each state event) |
//! | `/mason/uav_<i>/state` | `std_msgs/msg/String` | each event of UAV i (state, brick, mode, failure) |
//! | `/mason/wall` | `visualization_msgs/msg/MarkerArray` | at 0, and each grasp, placement or loss |
//! | `/mason/mission` | `std_msgs/msg/String` | at 0, when its content changes, and at the end |
//!
//! Every message is stamped with its mission time (header and bag time alike; 0 = mission
//! start). The trace has no claims: a brick is *claimed* from its grasp to its placement or
//! loss. It has no incarnations either: a UAV's incarnation is 1 and grows when it is heard
//! again after a failure (a restart of `mason launch`).

use super::bag::{Qos, RosBag, RosBagFiles, TopicId};
use super::messages::{cube_array, pose_stamped, string, RosType, Stamp};
use super::wall::{wall_cubes, BrickStatus, BRICK_NS, FRAME};
use crate::mcap::{nanos, trace_poses};
use crate::McapLogError;
use mason_mission::{Arena, CommMode, Event, EventKind, UavState};
use mason_wall::{BrickId, Wall};
use serde_json::{json, Value};
use std::collections::BTreeMap;

/// What a bag is of.
#[derive(Clone, Copy, Debug)]
pub struct BagMeta<'a> {
    /// Team size: one pose and one state topic per UAV.
    pub uavs: usize,
    /// The layout: where the wall stands.
    pub arena: &'a Arena,
    /// The design being built.
    pub wall: &'a Wall,
    /// Every UAV's coordination mode at the start.
    pub mode: CommMode,
    /// Messages the team dropped on arrival, by cause (in the last `/mason/mission` message).
    pub rejected: &'a BTreeMap<String, u64>,
}

/// Poses: a stream, the last ten kept.
const POSE_QOS: Qos = Qos {
    depth: 10,
    latched: false,
};
/// States: a late subscriber gets each UAV's last ten.
const STATE_QOS: Qos = Qos {
    depth: 10,
    latched: true,
};
/// The wall and the mission summary: a late subscriber gets the latest.
const LATEST_QOS: Qos = Qos {
    depth: 1,
    latched: true,
};

/// The topic names of UAV `i`: its pose and its state.
pub fn uav_topics(i: usize) -> (String, String) {
    (
        format!("/mason/uav_{i}/pose"),
        format!("/mason/uav_{i}/state"),
    )
}

/// The wall's topic.
pub const WALL_TOPIC: &str = "/mason/wall";
/// The mission summary's topic.
pub const MISSION_TOPIC: &str = "/mason/mission";

/// One UAV as the trace tells it so far.
#[derive(Clone, Debug)]
struct UavView {
    state: Option<UavState>,
    outcome: &'static str,
    brick: Option<BrickId>,
    mode: CommMode,
    incarnation: u64,
    failed: bool,
}

impl UavView {
    fn in_game(&self) -> bool {
        !self.failed && self.state != Some(UavState::Down)
    }
}

/// The bag being filled from a trace.
struct Filler<'a> {
    bag: RosBag,
    meta: BagMeta<'a>,
    pose: Vec<TopicId>,
    state: Vec<TopicId>,
    wall: TopicId,
    mission: TopicId,
    uavs: Vec<UavView>,
    bricks: Vec<BrickStatus>,
    last_mission: Option<Value>,
}

/// The bag `name` (its folder's name) of a mission's trace (time order, as the simulator and
/// `mason launch` give it), ending at `end_s`.
pub fn mission_rosbag(
    name: &str,
    meta: &BagMeta<'_>,
    trace: &[Event],
    end_s: f64,
) -> Result<RosBagFiles, McapLogError> {
    let poses = trace_poses(meta.uavs, trace, end_s)?;
    let mut f = Filler::new(name, meta)?;
    f.wall(0.0)?;
    f.mission(0.0, false)?;
    let mut events = trace.iter().peekable();
    for (t, uav, p) in poses {
        while let Some(e) = events.next_if(|e| e.t < t) {
            f.event(e)?;
        }
        let cdr = pose_stamped(Stamp::of_seconds(t), FRAME, [p.x, p.y, p.z], p.yaw);
        f.bag.write(f.pose[uav as usize], nanos(t), &cdr)?;
    }
    for e in events {
        f.event(e)?;
    }
    let end = trace.iter().map(|e| e.t).fold(end_s.max(0.0), f64::max);
    f.mission(end, true)?;
    f.bag.finish()
}

impl<'a> Filler<'a> {
    fn new(name: &str, meta: &BagMeta<'a>) -> Result<Self, McapLogError> {
        let mut bag = RosBag::new(name)?;
        let mut pose = Vec::with_capacity(meta.uavs);
        let mut state = Vec::with_capacity(meta.uavs);
        for i in 0..meta.uavs {
            let (p, s) = uav_topics(i);
            pose.push(bag.topic(&p, RosType::PoseStamped, POSE_QOS)?);
            state.push(bag.topic(&s, RosType::String, STATE_QOS)?);
        }
        let wall = bag.topic(WALL_TOPIC, RosType::MarkerArray, LATEST_QOS)?;
        let mission = bag.topic(MISSION_TOPIC, RosType::String, LATEST_QOS)?;
        let view = UavView {
            state: None,
            outcome: "",
            brick: None,
            mode: meta.mode,
            incarnation: 1,
            failed: false,
        };
        Ok(Filler {
            bag,
            meta: *meta,
            pose,
            state,
            wall,
            mission,
            uavs: vec![view; meta.uavs],
            bricks: vec![BrickStatus::Pending; meta.wall.len()],
            last_mission: None,
        })
    }

    /// A brick's index, if the wall has it.
    fn brick(&self, b: BrickId) -> Result<usize, McapLogError> {
        let bricks = self.meta.wall.len();
        if b.index() < bricks {
            Ok(b.index())
        } else {
            Err(McapLogError::UnknownBrick { brick: b.0, bricks })
        }
    }

    /// One event: UAV `e.uav`'s state message, and the wall and mission when they change.
    fn event(&mut self, e: &Event) -> Result<(), McapLogError> {
        let i = e.uav as usize;
        if i >= self.meta.uavs {
            return Err(McapLogError::UnknownUav {
                uav: e.uav,
                uavs: self.meta.uavs,
            });
        }
        let mut wall_changed = false;
        match e.kind {
            EventKind::State { state, outcome, .. } => {
                let u = &mut self.uavs[i];
                if u.failed {
                    u.failed = false;
                    u.incarnation += 1;
                }
                u.state = Some(state);
                u.outcome = outcome;
            }
            EventKind::Grasp { brick } => {
                let b = self.brick(brick)?;
                self.uavs[i].brick = Some(brick);
                if self.bricks[b] != BrickStatus::Placed {
                    self.bricks[b] = BrickStatus::Claimed;
                }
                wall_changed = true;
            }
            EventKind::Place { brick } | EventKind::Lost { brick } => {
                let b = self.brick(brick)?;
                self.uavs[i].brick = None;
                let placed = matches!(e.kind, EventKind::Place { .. });
                if placed {
                    self.bricks[b] = BrickStatus::Placed;
                } else if self.bricks[b] != BrickStatus::Placed {
                    self.bricks[b] = BrickStatus::Pending;
                }
                wall_changed = true;
            }
            EventKind::Fail => {
                let u = &mut self.uavs[i];
                u.failed = true;
                if let Some(b) = u.brick.take() {
                    if self.bricks[b.index()] == BrickStatus::Claimed {
                        self.bricks[b.index()] = BrickStatus::Pending;
                        wall_changed = true;
                    }
                }
            }
            EventKind::Comm { mode } => self.uavs[i].mode = mode,
            EventKind::ZoneEnter | EventKind::ZoneLeave | EventKind::Replan { .. } => {}
        }
        let body = self.state_json(i, e.t);
        self.bag
            .write(self.state[i], nanos(e.t), &string(&body.to_string()))?;
        if wall_changed {
            self.wall(e.t)?;
        }
        self.mission(e.t, false)
    }

    /// UAV `i`'s state message.
    fn state_json(&self, i: usize, t: f64) -> Value {
        let u = &self.uavs[i];
        json!({
            "t": t, "uav": i, "state": u.state.map(UavState::name), "outcome": u.outcome,
            "brick": u.brick.map(|b| self.meta.wall.brick(b).label),
            "mode": u.mode, "incarnation": u.incarnation, "in_game": u.in_game(),
        })
    }

    /// The whole wall at `t`.
    fn wall(&mut self, t: f64) -> Result<(), McapLogError> {
        let cubes = wall_cubes(self.meta.arena, self.meta.wall, &self.bricks);
        let cdr = cube_array(Stamp::of_seconds(t), FRAME, BRICK_NS, &cubes);
        self.bag.write(self.wall, nanos(t), &cdr)
    }

    /// The mission summary at `t`, if it changed (always at the end, with the counters).
    fn mission(&mut self, t: f64, end: bool) -> Result<(), McapLogError> {
        let placed = self
            .bricks
            .iter()
            .filter(|&&s| s == BrickStatus::Placed)
            .count();
        let modes: Vec<CommMode> = self.uavs.iter().map(|u| u.mode).collect();
        let mode = match modes.first() {
            Some(m) if modes.iter().all(|x| x == m) => json!(m),
            Some(_) => json!("mixed"),
            None => Value::Null,
        };
        let rejected = if end {
            json!(self.meta.rejected)
        } else {
            json!({})
        };
        let body = json!({
            "placed": placed, "total": self.meta.wall.len(), "mode": mode,
            "uavs": self.meta.uavs,
            "in_game": self.uavs.iter().filter(|u| u.in_game()).count(),
            "rejected": rejected,
        });
        if !end && self.last_mission.as_ref() == Some(&body) {
            return Ok(());
        }
        let mut stamped = body.clone();
        stamped["t"] = json!(t);
        self.last_mission = Some(body);
        self.bag
            .write(self.mission, nanos(t), &string(&stamped.to_string()))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ev(t: f64, uav: u32, kind: EventKind) -> Event {
        Event { t, uav, kind }
    }

    fn state(t: f64, uav: u32, s: UavState) -> Event {
        let kind = EventKind::State {
            state: s,
            outcome: "ok",
            x: 10.0 + t,
            y: 10.0,
        };
        ev(t, uav, kind)
    }

    /// Counts of messages per topic, read back from the MCAP file.
    fn counts(files: &RosBagFiles) -> BTreeMap<String, usize> {
        let mut out = BTreeMap::new();
        for m in ::mcap::MessageStream::new(&files.mcap).unwrap() {
            let m = m.unwrap();
            assert_eq!(m.channel.message_encoding, "cdr");
            let schema = m.channel.schema.as_ref().unwrap();
            assert_eq!(schema.encoding, "ros2msg");
            *out.entry(m.channel.topic.clone()).or_default() += 1;
        }
        out
    }

    #[test]
    fn a_trace_becomes_the_four_topics() {
        let wall = mason_wall::parse_layer_text("R G", "two").unwrap();
        let arena = Arena::default();
        let rejected = BTreeMap::from([("replay".to_string(), 3)]);
        let meta = BagMeta {
            uavs: 2,
            arena: &arena,
            wall: &wall,
            mode: CommMode::Comm,
            rejected: &rejected,
        };
        let b0 = BrickId(0);
        let trace = [
            state(0.0, 0, UavState::Check),
            state(0.0, 1, UavState::Check),
            state(1.0, 0, UavState::TakeOff),
            ev(2.0, 0, EventKind::Grasp { brick: b0 }),
            ev(3.0, 0, EventKind::Place { brick: b0 }),
            ev(3.5, 1, EventKind::Fail),
            ev(
                4.0,
                0,
                EventKind::Comm {
                    mode: CommMode::Windows,
                },
            ),
        ];
        let files = mission_rosbag("two", &meta, &trace, 5.0).unwrap();
        let c = counts(&files);
        assert_eq!(c["/mason/uav_0/state"], 5);
        assert_eq!(c["/mason/uav_1/state"], 2);
        // 0, the grasp and the placement.
        assert_eq!(c[WALL_TOPIC], 3);
        // 0, placed 1, UAV 1 out, modes mixed, the end.
        assert_eq!(c[MISSION_TOPIC], 5);
        assert!(c["/mason/uav_0/pose"] >= 4);
        assert!(files.metadata.contains("message_count: 3\n"));
        // The last mission message carries the counters.
        let last = ::mcap::MessageStream::new(&files.mcap)
            .unwrap()
            .map(|m| m.unwrap())
            .filter(|m| m.channel.topic == MISSION_TOPIC)
            .last()
            .unwrap();
        let text = String::from_utf8_lossy(&last.data[8..last.data.len() - 1]).into_owned();
        let v: Value = serde_json::from_str(&text).unwrap();
        assert_eq!(v["placed"], 1);
        assert_eq!(v["in_game"], 1);
        assert_eq!(v["mode"], "mixed");
        assert_eq!(v["rejected"]["replay"], 3);
        assert_eq!(last.log_time, 5_000_000_000);
    }

    /// A one-brick wall, the default arena, no rejections.
    fn one_brick() -> (Wall, Arena, BTreeMap<String, u64>) {
        let wall = mason_wall::parse_layer_text("R", "one").unwrap();
        (wall, Arena::default(), BTreeMap::new())
    }

    /// A bag of one UAV building `wall`.
    fn lone_uav<'a>(
        wall: &'a Wall,
        arena: &'a Arena,
        none: &'a BTreeMap<String, u64>,
    ) -> BagMeta<'a> {
        BagMeta {
            uavs: 1,
            arena,
            wall,
            mode: CommMode::Comm,
            rejected: none,
        }
    }

    #[test]
    fn a_uav_heard_again_after_a_failure_is_a_new_incarnation() {
        let (wall, arena, none) = one_brick();
        let meta = lone_uav(&wall, &arena, &none);
        let mut f = Filler::new("one", &meta).unwrap();
        f.event(&state(0.0, 0, UavState::Check)).unwrap();
        f.event(&ev(1.0, 0, EventKind::Fail)).unwrap();
        assert!(!f.uavs[0].in_game());
        f.event(&state(2.0, 0, UavState::Check)).unwrap();
        assert_eq!(f.uavs[0].incarnation, 2);
        assert!(f.uavs[0].in_game());
    }

    #[test]
    fn a_stranger_or_an_unknown_brick_is_refused() {
        let (wall, arena, none) = one_brick();
        let meta = lone_uav(&wall, &arena, &none);
        let stranger = [state(0.0, 1, UavState::Check)];
        assert!(matches!(
            mission_rosbag("x", &meta, &stranger, 1.0),
            Err(McapLogError::UnknownUav { uav: 1, uavs: 1 })
        ));
        let unknown = [ev(0.0, 0, EventKind::Place { brick: BrickId(4) })];
        assert!(matches!(
            mission_rosbag("x", &meta, &unknown, 1.0),
            Err(McapLogError::UnknownBrick {
                brick: 4,
                bricks: 1
            })
        ));
    }
}
