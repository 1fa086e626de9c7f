//! The log being written ([`McapLog`]): the schemas and channels, the metadata record, and one
//! JSON message per pose, trace event or coordination message, into any `Write + Seek` sink.
//! The log keeps what the scene needs (the bricks placed so far, who is in the wall zone) and
//! writes the whole `/wall` scene again at each placement.

use super::scene::{wall_scene, Placement};
use super::schemas;
use super::values::{nanos, pose_json, stamp};
use mason_mission::{Arena, Event, EventKind, UavState};
use mason_wall::{BrickId, Wall};
use serde_json::{json, Value};
use std::collections::BTreeMap;
use std::io::{Seek, Write};

/// Why an MCAP log could not be written.
#[derive(Debug, thiserror::Error)]
pub enum McapLogError {
    /// The MCAP writer failed (an I/O error of the sink, or a record it refused).
    #[error("MCAP writer: {0}")]
    Mcap(#[from] ::mcap::McapError),
    /// A pose, event or message names a UAV outside the team.
    #[error("UAV {uav} is not in the team of {uavs}")]
    UnknownUav {
        /// The UAV named.
        uav: u32,
        /// The team size.
        uavs: usize,
    },
    /// An event names a brick the wall does not have.
    #[error("brick index {brick} is not in the wall of {bricks} bricks")]
    UnknownBrick {
        /// The brick index.
        brick: u32,
        /// The wall's brick count.
        bricks: usize,
    },
}

/// What a log is of: written once, at the start, as the MCAP metadata record `mission`, and
/// used to draw the scene.
#[derive(Clone, Copy, Debug)]
pub struct LogMeta<'a> {
    /// Names the mission in the metadata and in every `/messages` entry.
    pub mission_id: &'a str,
    /// Team size: one pose and one state channel per UAV.
    pub uavs: usize,
    /// The layout: piles, wall position, zone.
    pub arena: &'a Arena,
    /// The design being built.
    pub wall: &'a Wall,
}

/// A UAV's pose in the `world` frame: position (m) and heading (radians from east, counter-
/// clockwise).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct UavPose {
    /// East (m).
    pub x: f64,
    /// North (m).
    pub y: f64,
    /// Up (m).
    pub z: f64,
    /// Heading (rad).
    pub yaw: f64,
}

/// The channel ids: one pose and one state channel per UAV, and one of each shared topic.
struct Channels {
    pose: Vec<u16>,
    state: Vec<u16>,
    zone: u16,
    bricks: u16,
    wall: u16,
    events: u16,
    messages: u16,
}

/// An MCAP log being written. Call [`McapLog::pose`], [`McapLog::event`] and
/// [`McapLog::message`] in mission-time order (equal times in any order), then
/// [`McapLog::finish`].
pub struct McapLog<'a, W: Write + Seek> {
    out: ::mcap::Writer<W>,
    meta: LogMeta<'a>,
    channels: Channels,
    sequence: BTreeMap<u16, u32>,
    /// Each brick placed so far, by brick index.
    placed: Vec<Option<Placement>>,
    placed_count: usize,
    /// The UAVs in the wall zone, in order.
    inside: Vec<u32>,
}

impl<'a, W: Write + Seek> McapLog<'a, W> {
    /// Starts a log in `sink`: the header, the schemas and channels, the metadata record
    /// `mission` (mission id, wall name, bricks, team size) and the first `/wall` scene at t = 0.
    pub fn new(sink: W, meta: &LogMeta<'a>) -> Result<Self, McapLogError> {
        let options = ::mcap::WriteOptions::new()
            .compression(None)
            .profile("")
            .library(concat!("mason-report/", env!("CARGO_PKG_VERSION")));
        let mut out = options.create(sink)?;
        let schema = |out: &mut ::mcap::Writer<W>, name: &str, body: Value| {
            out.add_schema(name, "jsonschema", body.to_string().as_bytes())
        };
        let pose_schema = schema(&mut out, "foxglove.PoseInFrame", schemas::pose_in_frame())?;
        let state_schema = schema(&mut out, "mason.UavState", schemas::uav_state())?;
        let zone_schema = schema(&mut out, "mason.Zone", schemas::zone())?;
        let brick_schema = schema(&mut out, "mason.Brick", schemas::brick())?;
        let scene_schema = schema(&mut out, "foxglove.SceneUpdate", schemas::scene_update())?;
        let log_schema = schema(&mut out, "foxglove.Log", schemas::log())?;
        let message_schema = schema(&mut out, "mason.Message", schemas::message())?;
        let none = BTreeMap::new();
        let channel = |out: &mut ::mcap::Writer<W>, schema: u16, topic: &str| {
            out.add_channel(schema, topic, "json", &none)
        };
        let mut pose = Vec::with_capacity(meta.uavs);
        let mut state = Vec::with_capacity(meta.uavs);
        for i in 0..meta.uavs {
            pose.push(channel(&mut out, pose_schema, &format!("/uav/{i}/pose"))?);
            state.push(channel(&mut out, state_schema, &format!("/uav/{i}/state"))?);
        }
        let channels = Channels {
            pose,
            state,
            zone: channel(&mut out, zone_schema, "/zone")?,
            bricks: channel(&mut out, brick_schema, "/bricks")?,
            wall: channel(&mut out, scene_schema, "/wall")?,
            events: channel(&mut out, log_schema, "/events")?,
            messages: channel(&mut out, message_schema, "/messages")?,
        };
        out.write_metadata(&::mcap::records::Metadata {
            name: "mission".into(),
            metadata: BTreeMap::from([
                ("mission_id".into(), meta.mission_id.into()),
                ("wall".into(), meta.wall.name().into()),
                ("bricks".into(), meta.wall.len().to_string()),
                ("uavs".into(), meta.uavs.to_string()),
                ("frame".into(), "world: x east, y north, z up (m)".into()),
            ]),
        })?;
        let mut log = McapLog {
            out,
            meta: *meta,
            channels,
            sequence: BTreeMap::new(),
            placed: vec![None; meta.wall.len()],
            placed_count: 0,
            inside: Vec::new(),
        };
        log.scene(0.0)?;
        Ok(log)
    }

    /// One message on `channel` at mission time `t`, numbered in its channel from 1.
    fn write(&mut self, channel: u16, t: f64, body: &Value) -> Result<(), McapLogError> {
        let seq = self.sequence.entry(channel).or_insert(0);
        *seq += 1;
        let header = ::mcap::records::MessageHeader {
            channel_id: channel,
            sequence: *seq,
            log_time: nanos(t),
            publish_time: nanos(t),
        };
        self.out
            .write_to_known_channel(&header, body.to_string().as_bytes())?;
        Ok(())
    }

    /// The team size.
    pub(super) fn uavs(&self) -> usize {
        self.meta.uavs
    }

    /// UAV `uav`'s index, if it is in the team.
    pub(super) fn check_uav(&self, uav: u32) -> Result<usize, McapLogError> {
        let i = uav as usize;
        if i < self.meta.uavs {
            Ok(i)
        } else {
            Err(McapLogError::UnknownUav {
                uav,
                uavs: self.meta.uavs,
            })
        }
    }

    /// UAV `uav`'s pose at mission time `t` (s), on `/uav/<uav>/pose`. Which poses to log, and
    /// their heading: [`PoseSampler`](super::PoseSampler).
    pub fn pose(&mut self, t: f64, uav: u32, p: UavPose) -> Result<(), McapLogError> {
        let i = self.check_uav(uav)?;
        let body = json!({
            "timestamp": stamp(t),
            "frame_id": "world",
            "pose": pose_json(p.x, p.y, p.z, p.yaw),
        });
        self.write(self.channels.pose[i], t, &body)
    }

    /// One trace event: a line on `/events`, and by kind a `/uav/<i>/state`, `/zone` or
    /// `/bricks` message; a placement also writes the new `/wall` scene.
    pub fn event(&mut self, e: &Event) -> Result<(), McapLogError> {
        let i = self.check_uav(e.uav)?;
        let t = e.t;
        let (level, line) = match e.kind {
            EventKind::State {
                state,
                outcome,
                x,
                y,
            } => {
                let body = json!({
                    "timestamp": stamp(t), "uav": e.uav, "state": state.name(),
                    "outcome": outcome, "x": x, "y": y,
                });
                self.write(self.channels.state[i], t, &body)?;
                let level = match state {
                    UavState::SafeLand | UavState::Down => 3,
                    _ if outcome == "failed" || outcome == "gave_up" => 3,
                    _ => 2,
                };
                (
                    level,
                    format!("{} ({outcome}) at ({x:.2}, {y:.2})", state.name()),
                )
            }
            EventKind::Grasp { brick } | EventKind::Place { brick } | EventKind::Lost { brick } => {
                let label = self.label(brick)?;
                let action = match e.kind {
                    EventKind::Grasp { .. } => "grasp",
                    EventKind::Place { .. } => "place",
                    _ => "lost",
                };
                if action == "place" && self.placed[brick.index()].is_none() {
                    self.placed[brick.index()] = Some(Placement { at: t, uav: e.uav });
                    self.placed_count += 1;
                }
                let body = json!({
                    "timestamp": stamp(t), "uav": e.uav, "action": action, "brick": label,
                    "placed": self.placed_count,
                });
                self.write(self.channels.bricks, t, &body)?;
                if action == "place" {
                    self.scene(t)?;
                }
                let level = if action == "lost" { 3 } else { 2 };
                (level, format!("{action} brick {label}"))
            }
            EventKind::ZoneEnter | EventKind::ZoneLeave => {
                let enter = matches!(e.kind, EventKind::ZoneEnter);
                if enter {
                    if !self.inside.contains(&e.uav) {
                        self.inside.push(e.uav);
                        self.inside.sort_unstable();
                    }
                } else {
                    self.inside.retain(|&u| u != e.uav);
                }
                let what = if enter { "enter" } else { "leave" };
                let body = json!({
                    "timestamp": stamp(t), "uav": e.uav, "event": what,
                    "inside": self.inside, "count": self.inside.len(),
                });
                self.write(self.channels.zone, t, &body)?;
                (2, format!("zone {what} (inside: {:?})", self.inside))
            }
            EventKind::Fail => (4, "failed: out of the mission".to_string()),
            EventKind::Replan { bricks } => (2, format!("re-planned the rest: {bricks} bricks")),
            EventKind::Comm { mode } => {
                let name = match mode {
                    mason_mission::CommMode::Comm => "comm",
                    mason_mission::CommMode::Windows => "windows",
                };
                let level = if name == "windows" { 3 } else { 2 };
                (level, format!("coordination mode: {name}"))
            }
        };
        let body = json!({
            "timestamp": stamp(t), "level": level, "message": line,
            "name": format!("uav{}", e.uav), "file": "", "line": 0,
        });
        self.write(self.channels.events, t, &body)
    }

    /// A coordination message sent by `from_uav` at `t`, on `/messages`: its `kind` (heartbeat,
    /// claim, zone request, …) and its JSON body, tagged with the mission id.
    pub fn message(
        &mut self,
        t: f64,
        from_uav: u32,
        kind: &str,
        body: &Value,
    ) -> Result<(), McapLogError> {
        self.check_uav(from_uav)?;
        let msg = json!({
            "timestamp": stamp(t), "mission_id": self.meta.mission_id, "from": from_uav,
            "kind": kind, "body": body,
        });
        self.write(self.channels.messages, t, &msg)
    }

    /// Writes the summary and the footer, and returns the sink.
    pub fn finish(mut self) -> Result<W, McapLogError> {
        self.out.finish()?;
        Ok(self.out.into_inner())
    }

    /// A brick's label, if the wall has it.
    fn label(&self, brick: BrickId) -> Result<u32, McapLogError> {
        if brick.index() < self.meta.wall.len() {
            Ok(self.meta.wall.brick(brick).label)
        } else {
            Err(McapLogError::UnknownBrick {
                brick: brick.0,
                bricks: self.meta.wall.len(),
            })
        }
    }

    /// The whole scene at `t` on `/wall`.
    fn scene(&mut self, t: f64) -> Result<(), McapLogError> {
        let body = wall_scene(t, self.meta.arena, self.meta.wall, &self.placed);
        self.write(self.channels.wall, t, &body)
    }
}
